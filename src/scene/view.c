/* view.c: named views, and a useful first view.
 *
 * A model's files say nothing of where its front is, and the plain view
 * down -z shows many of them end-on, edge-on or from the back (an open
 * box's back wall). The first view is therefore chosen among eight
 * three-quarter views from above (yaws 30, 60, 120 and 150 degrees either
 * side, pitch 25) as the one that sees the most surface facing it: the
 * sum over polygons of their area-weighted normal's component towards
 * the viewer. For a closed model that is its projected area, so a long
 * model is seen from the side and a flat one face-on; for an open one
 * (a room, a box without its front) it prefers the side its faces open
 * to. Near-ties go to the views nearer the front. Huge models are
 * sampled (at most SAMPLE_POLYS polygons), which is plenty for a sum of
 * areas. */

#include <math.h>
#include <string.h>

#include "scene.h"

#define SAMPLE_POLYS 200000
#define NCAND 8

typedef struct {
    const char *name;
    float yaw, pitch;
} NamedView;

/* yaw turns the front to the right, pitch tips it down (scene.h) */
static const NamedView named[] = {
    { "front", 0, 0 },     { "back", 180, 0 },  { "left", 90, 0 },   { "right", -90, 0 },
    { "top", 0, 90 },      { "bottom", 0, -90 }, { "iso", -45, 35.264f },
};

int view_from_name(const char *name, float *yaw_out, float *pitch_out)
{
    for (size_t i = 0; i < sizeof named / sizeof named[0]; i++)
        if (strcmp(name, named[i].name) == 0) {
            *yaw_out = named[i].yaw;
            *pitch_out = named[i].pitch;
            return 0;
        }
    return -1;
}

const char *view_name(int i)
{
    return i >= 0 && i < (int)(sizeof named / sizeof named[0]) ? named[i].name : NULL;
}

/* The direction from the model towards the viewer, in model space, for
 * a view turned by yaw and pitch (the inverse turn of (0, 0, 1)). */
static Vec3 view_dir(float yaw_deg, float pitch_deg)
{
    float y = deg2rad(yaw_deg), p = deg2rad(pitch_deg);
    return v3(-sinf(y) * cosf(p), sinf(p), cosf(y) * cosf(p));
}

void scene_pick_view(const Scene *s, float *yaw_out, float *pitch_out)
{
    static const float yaws[NCAND] = { -30, 30, -60, 60, -120, 120, -150, 150 };
    const float pitch = 25;
    Vec3 d[NCAND];
    double score[NCAND] = { 0 };
    for (int c = 0; c < NCAND; c++)
        d[c] = view_dir(yaws[c], pitch);
    uint32_t total = 0;
    for (uint32_t oi = 0; oi < s->nbase_objs && (int)oi < s->nobjs; oi++)
        total += s->objs[oi].poly_count;
    uint32_t stride = total > SAMPLE_POLYS ? total / SAMPLE_POLYS + 1 : 1;
    for (uint32_t oi = 0; oi < s->nbase_objs && (int)oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        if (!o->mesh)
            continue;
        const float *pos = o->mesh->pos;
        /* the views are of the world: the object's up axis turns its normals */
        Mat4 om = object_matrix(o);
        for (uint32_t k = o->poly_first; k < o->poly_first + o->poly_count; k += stride) {
            /* Newell's vector: the normal times twice the area */
            float n[3] = { 0, 0, 0 };
            uint32_t c0 = s->poly_start[k], c1 = s->poly_start[k + 1];
            for (uint32_t c = c0; c < c1; c++) {
                const float *p = &pos[3 * (size_t)s->poly_corner[c]];
                const float *q = &pos[3 * (size_t)s->poly_corner[c + 1 < c1 ? c + 1 : c0]];
                n[0] += (p[1] - q[1]) * (p[2] + q[2]);
                n[1] += (p[2] - q[2]) * (p[0] + q[0]);
                n[2] += (p[0] - q[0]) * (p[1] + q[1]);
            }
            Vec3 wn = m4_dir(&om, v3(n[0], n[1], n[2]));
            for (int c = 0; c < NCAND; c++) {
                float f = wn.x * d[c].x + wn.y * d[c].y + wn.z * d[c].z;
                if (f > 0)
                    score[c] += f;
            }
        }
    }
    int best = 0;
    double bests = -1;
    for (int c = 0; c < NCAND; c++) {
        /* a view nearer the front wins a near-tie (a symmetric model) */
        double sc = score[c] * (1 + 0.05 * cos(deg2rad(yaws[c])));
        if (sc > bests * (1 + 1e-9)) {
            bests = sc;
            best = c;
        }
    }
    *yaw_out = yaws[best];
    *pitch_out = pitch;
}
