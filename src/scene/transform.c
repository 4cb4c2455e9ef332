/* transform.c: where the scene stands and how it is seen. The up axis
 * as quarter turns, each object's matrix, the camera's view, fitting
 * the camera to the scene (scene_fit, on load and after a reset), and
 * the light. */

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "scene.h"
#include "scene_internal.h"

static Vec3 mesh_vertex(const Mesh *m, uint32_t v)
{
    return v3(m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]);
}

/* ==== transforms and fitting ==== */

/* The up-axis turns: rows of the 3x3 rotation taking model to world
 * coordinates, each a quarter-turn (determinant +1, no mirror). */
static const signed char up_rot[UP_COUNT][3][3] = {
    [UP_Y] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
    [UP_Z] = { { 1, 0, 0 }, { 0, 0, 1 }, { 0, -1, 0 } },      /* z -> up, y -> away */
    [UP_X] = { { 0, -1, 0 }, { 1, 0, 0 }, { 0, 0, 1 } },      /* x -> up */
    [UP_NEG_Y] = { { 1, 0, 0 }, { 0, -1, 0 }, { 0, 0, -1 } },
    [UP_NEG_Z] = { { 1, 0, 0 }, { 0, 0, -1 }, { 0, 1, 0 } },
    [UP_NEG_X] = { { 0, 1, 0 }, { -1, 0, 0 }, { 0, 0, 1 } },
};
static const char *const up_names[UP_COUNT] = { "y", "z", "x", "-y", "-z", "-x" };

const char *up_axis_name(int up) { return up >= 0 && up < UP_COUNT ? up_names[up] : "?"; }

int up_axis_from_name(const char *s)
{
    for (int i = 0; i < UP_COUNT; i++)
        if (strcmp(s, up_names[i]) == 0 || (s[0] == '+' && strcmp(s + 1, up_names[i]) == 0))
            return i;
    return -1;
}

void scene_set_up(Scene *s, int up)
{
    for (int i = 0; i < s->nobjs; i++)
        s->objs[i].up = up;
    scene_fit(s);
}

int scene_up_forced(const Scene *s)
{
    for (int i = 0; i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        int own = o->mesh && o->mesh->info.up > UP_Y && o->mesh->info.up < UP_COUNT ? o->mesh->info.up : UP_Y;
        if (o->up != own)
            return s->objs[0].up;
    }
    return -1;
}

Mat4 object_matrix(const Object *o)
{
    Mat4 m = m4_translate(v3_scale(o->centre, -1));
    Vec3 c = o->centre;
    if (o->up > UP_Y && o->up < UP_COUNT) {
        /* exact: products by 0 and +-1 (y up leaves the matrix alone) */
        Mat4 u = m4_identity();
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                u.m[i][j] = up_rot[o->up][i][j];
        m = m4_mul(u, m);
        c = m4_dir(&u, c);
    }
    m = m4_mul(m4_scale(o->scale), m);
    m = m4_mul(m4_rotate_ypr(o->yaw, o->pitch, o->roll), m);
    return m4_mul(m4_translate(v3_add(c, o->offset)), m);
}

Mat4 camera_view(const Camera *c)
{
    Mat4 m = m4_translate(v3_scale(c->centre, -1));
    m = m4_mul(m4_rotate_ypr(c->yaw, c->pitch, c->roll), m);
    return m4_mul(m4_translate(v3_scale(c->pan, c->radius)), m);
}

/* Grow a view-space box by point p. */
static inline void box_add(float lo[3], float hi[3], Vec3 p)
{
    float q[3] = { p.x, p.y, p.z };
    for (int k = 0; k < 3; k++) {
        if (q[k] < lo[k]) lo[k] = q[k];
        if (q[k] > hi[k]) hi[k] = q[k];
    }
}

void scene_fit(Scene *s)
{
    /* The box of every vertex as the camera sees it (turned, not panned):
     * its centre becomes the image centre and its half extents what the
     * projection fills 90% of the image with. Grid copies, which can be
     * many, count by their boxes' corners. The radius about the centre
     * bounds the depth range. Objects count at their home placement (as
     * loaded and laid out), not where the viewer has moved them: the fit
     * then depends only on the turn, which the command line can give
     * (--fit-from), so every view can be reproduced exactly. */
    Camera *c = &s->cam;
    Mat4 turn = m4_rotate_ypr(c->yaw, c->pitch, c->roll);
    c->fit_yaw = c->yaw;
    c->fit_pitch = c->pitch;
    c->fit_roll = c->roll;
    float lo[3] = { FLT_MAX, FLT_MAX, FLT_MAX }, hi[3] = { -FLT_MAX, -FLT_MAX, -FLT_MAX };
    float wlo[3] = { FLT_MAX, FLT_MAX, FLT_MAX }, whi[3] = { -FLT_MAX, -FLT_MAX, -FLT_MAX };
    for (int i = 0; i < s->nobjs; i++) {
        Object home = s->objs[i];
        home.yaw = home.pitch = home.roll = 0;
        home.offset = home.home;
        home.scale = home.home_scale;
        const Object *o = &home;
        Mat4 m = object_matrix(o);
        if (i >= (int)s->nbase_objs) {
            for (int k = 0; k < 8; k++) {
                Vec3 p = v3(o->centre.x + (k & 1 ? o->half.x : -o->half.x),
                            o->centre.y + (k & 2 ? o->half.y : -o->half.y),
                            o->centre.z + (k & 4 ? o->half.z : -o->half.z));
                p = m4_point(&m, p);
                box_add(wlo, whi, p);
                box_add(lo, hi, m4_dir(&turn, p));
            }
            continue;
        }
        Mat4 tm = m4_mul(turn, m);
        const Mesh *me = o->mesh;
        for (uint32_t v = o->vert_min; v <= o->vert_max && v < me->nverts; v++) {
            Vec3 p = mesh_vertex(me, v);
            box_add(wlo, whi, m4_point(&m, p));
            box_add(lo, hi, m4_point(&tm, p));
        }
    }
    c->pan = v3(0, 0, 0);
    c->zoom = 1;
    if (lo[0] > hi[0]) {
        c->centre = v3(0, 0, 0);
        c->radius = 1;
        c->fit_half = v3(1, 1, 1);
        return;
    }
    /* view-space box centre back to world space (turn is a rotation);
     * halves and centres in double: lo + hi and hi - lo of finite floats
     * can pass FLT_MAX, their halves cannot */
    Vec3 vc = v3((float)(((double)lo[0] + hi[0]) * 0.5), (float)(((double)lo[1] + hi[1]) * 0.5),
                 (float)(((double)lo[2] + hi[2]) * 0.5));
    Mat4 back = turn;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            back.m[i][j] = turn.m[j][i];
    c->centre = m4_dir(&back, vc);
    Vec3 h = v3((float)(((double)hi[0] - lo[0]) * 0.5), (float)(((double)hi[1] - lo[1]) * 0.5),
                (float)(((double)hi[2] - lo[2]) * 0.5));
    float big = fmaxf(h.x, fmaxf(h.y, h.z));
    float tiny = big > 0 ? big * 1e-3f : 1;
    c->fit_half = v3(fmaxf(h.x, tiny), fmaxf(h.y, tiny), fmaxf(h.z, tiny));
    /* radius: the world box's half diagonal, measured from the centre;
     * in double, where the square of a coordinate of 1e20 still fits */
    double r2 = 0;
    for (int k = 0; k < 8; k++) {
        double d[3] = { (double)(k & 1 ? whi[0] : wlo[0]) - c->centre.x,
                        (double)(k & 2 ? whi[1] : wlo[1]) - c->centre.y,
                        (double)(k & 4 ? whi[2] : wlo[2]) - c->centre.z };
        double q = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (q > r2)
            r2 = q;
    }
    c->radius = r2 > 0 ? (float)fmin(sqrt(r2), FLT_MAX) : 1.0f;
}

void scene_reset(Scene *s)
{
    for (int i = 0; i < s->nobjs; i++) {
        Object *o = &s->objs[i];
        o->yaw = o->open_yaw;
        o->pitch = o->open_pitch;
        o->roll = o->open_roll;
        o->scale = o->home_scale * (o->open_scale != 0 ? o->open_scale : 1);
        o->offset = v3_add(o->home, o->open_move);
    }
    int persp = s->cam.persp;
    float fov = s->cam.fov_deg > 0 ? s->cam.fov_deg : 50;
    memset(&s->cam, 0, sizeof s->cam);
    s->cam.persp = persp;
    s->cam.fov_deg = fov;
    scene_fit(s);
}

void scene_view_like(Scene *s, const Camera *c)
{
    s->cam.yaw = c->fit_yaw;
    s->cam.pitch = c->fit_pitch;
    s->cam.roll = c->fit_roll;
    scene_fit(s);
    s->cam.yaw = c->yaw;
    s->cam.pitch = c->pitch;
    s->cam.roll = c->roll;
    s->cam.zoom = c->zoom;
    s->cam.pan = c->pan;
}

void light_set(Light *l, float yaw_deg, float pitch_deg, float ambient)
{
    float y = deg2rad(yaw_deg), p = deg2rad(pitch_deg);
    l->yaw = yaw_deg;
    l->pitch = pitch_deg;
    l->dir = v3(cosf(p) * sinf(y), sinf(p), cosf(p) * cosf(y));
    l->ambient = ambient < 0 ? 0 : ambient > 1 ? 1 : ambient;
}
