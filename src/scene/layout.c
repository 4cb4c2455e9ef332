/* layout.c: where several files go in one scene, and the colours of
 * objects that bring none.
 *
 * Files loaded together are rarely made to share coordinates: a bunny
 * 0.15 units tall sits invisibly inside a teapot 3 units wide. `row`
 * and `grid` scale each file (all its objects together, about the centre
 * of its box) to a common size and set the files side by side, a file's
 * own objects keeping their places relative to each other, level and
 * across the screen of a view turned by the given yaw; `none` keeps
 * the files' coordinates, which an assembly of parts needs. The result
 * is the objects' home placement, so a reset comes back to it. */

#include <float.h>
#include <math.h>
#include <string.h>

#include "scene.h"

const char *const layout_names[LAYOUT_COUNT] = { "row", "grid", "none" };

int layout_from_name(const char *name)
{
    for (int i = 0; i < LAYOUT_COUNT; i++)
        if (strcmp(name, layout_names[i]) == 0)
            return i;
    return -1;
}

/* Object o at its home placement (as loaded and laid out, unturned). */
static Object at_home(const Object *o)
{
    Object h = *o;
    h.yaw = h.pitch = h.roll = 0;
    h.offset = h.home;
    h.scale = h.home_scale;
    return h;
}

/* The world box of objects [a, b) at their home placement. */
static void files_box(const Scene *s, int a, int b, Vec3 *lo_out, Vec3 *hi_out)
{
    float lo[3] = { FLT_MAX, FLT_MAX, FLT_MAX }, hi[3] = { -FLT_MAX, -FLT_MAX, -FLT_MAX };
    for (int i = a; i < b; i++) {
        Object h = at_home(&s->objs[i]);
        if (!h.face_count)
            continue;
        Mat4 m = object_matrix(&h);
        for (int k = 0; k < 8; k++) {
            Vec3 p = m4_point(&m, v3(h.centre.x + (k & 1 ? h.half.x : -h.half.x),
                                     h.centre.y + (k & 2 ? h.half.y : -h.half.y),
                                     h.centre.z + (k & 4 ? h.half.z : -h.half.z)));
            float q[3] = { p.x, p.y, p.z };
            for (int c = 0; c < 3; c++) {
                lo[c] = fminf(lo[c], q[c]);
                hi[c] = fmaxf(hi[c], q[c]);
            }
        }
    }
    if (lo[0] > hi[0])
        lo[0] = lo[1] = lo[2] = hi[0] = hi[1] = hi[2] = 0;
    *lo_out = v3(lo[0], lo[1], lo[2]);
    *hi_out = v3(hi[0], hi[1], hi[2]);
}

void scene_layout(Scene *s, LayoutKind kind, float yaw)
{
    if (kind == LAYOUT_NONE || s->nmeshes < 2)
        return;
    int nfiles = s->nmeshes;
    int cols = kind == LAYOUT_ROW ? nfiles : (int)ceil(sqrt((double)nfiles));
    /* each file to a box of diagonal 1, in cells 1.25 apart */
    const float cell = 1.25f;
    /* rows run level, across the screen of a view turned by yaw (whatever
     * its pitch), and stack down the vertical */
    Mat4 turn = m4_rotate_ypr(yaw, 0, 0);
    Vec3 right = v3(turn.m[0][0], turn.m[0][1], turn.m[0][2]);
    Vec3 up = v3(0, 1, 0);
    int first = 0;
    for (int f = 0; f < nfiles; f++) {
        int last = first;
        while (last < (int)s->nbase_objs && s->objs[last].mesh == &s->meshes[f])
            last++;
        Vec3 lo, hi;
        files_box(s, first, last, &lo, &hi);
        Vec3 mid = v3_scale(v3_add(lo, hi), 0.5f);
        float diag = v3_len(v3_sub(hi, lo));
        float k = diag > 0 ? 1.0f / diag : 1.0f;
        int cx = f % cols, cy = f / cols;
        Vec3 target = v3_add(v3_scale(right, ((float)cx - 0.5f * (float)(cols - 1)) * cell),
                             v3_scale(up, -(float)cy * cell));
        for (int i = first; i < last; i++) {
            Object *o = &s->objs[i];
            /* the object's centre moves with the file's scaling about mid;
             * its matrix puts the centre at (its image without offset) +
             * offset, whatever the up axis */
            Object h = at_home(o);
            Mat4 m = object_matrix(&h);
            Vec3 c = m4_point(&m, o->centre);
            Vec3 to = v3_add(target, v3_scale(v3_sub(c, mid), k));
            o->home = v3_add(o->home, v3_sub(to, c));
            o->home_scale *= k;
            o->offset = o->home;
            o->scale = o->home_scale;
        }
        first = last;
    }
}

/* Soft, clearly different colours for objects without their own. */
static const uint8_t object_rgb[8][3] = {
    { 200, 200, 200 }, { 222, 150,  90 }, { 110, 170, 220 }, { 130, 195, 120 },
    { 215, 120, 150 }, { 200, 185, 100 }, { 150, 130, 210 }, { 100, 190, 180 },
};

void object_colour(int i, uint8_t rgb_out[3])
{
    memcpy(rgb_out, object_rgb[i % 8], 3);
    if (i >= 8) {
        /* beyond the list, shift the hue a little per round */
        int r = i / 8;
        uint8_t t = rgb_out[0];
        if (r % 3 == 1) {
            rgb_out[0] = rgb_out[1];
            rgb_out[1] = rgb_out[2];
            rgb_out[2] = t;
        } else if (r % 3 == 2) {
            rgb_out[0] = rgb_out[2];
            rgb_out[2] = rgb_out[1];
            rgb_out[1] = t;
        }
    }
}
