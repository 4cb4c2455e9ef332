/* sketch.c: polygons drawn by hand (zview --sketch), the way the classic
 * hidden-surface course projects let their users test the algorithms.
 *
 * The canvas is the square [-1, 1] x [-1, 1] seen straight on. Each
 * closed polygon lies in a plane of its own, nearer than the one drawn
 * before it (depth steps of SKETCH_DZ towards the viewer), so the last
 * drawn covers the earlier ones; flipping reverses that order. A polygon
 * can be tilted about its centre, so that it leans through its
 * neighbours' planes and the algorithms have piercing faces to resolve.
 * The drawing becomes OBJ text (one `o` per polygon, per-vertex colours),
 * which the ordinary loader reads: the sketch is rendered, saved and
 * reopened exactly like any model. */

#define _DEFAULT_SOURCE     /* open_memstream */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "scene.h"
#include "sketch.h"

#define SKETCH_TILT_MAX 75.0f   /* degrees: steeper would stand edge-on */

void sketch_init(Sketch *k)
{
    memset(k, 0, sizeof *k);
    k->sel = -1;
}

void sketch_free(Sketch *k)
{
    free(k->pts);
    free(k->start);
    free(k->tilt);
    sketch_init(k);
}

/* Room for one more polygon record (start has npolys + 2 entries: the
 * open polygon's start and the sentinel). */
static int room_polys(Sketch *k)
{
    uint32_t need = k->npolys + 2;
    if (grow_array((void **)&k->start, &k->cap_start, need, sizeof *k->start))
        return -1;
    uint32_t cap = k->cap_tilt;
    if (grow_array((void **)&k->tilt, &cap, 2 * (k->npolys + 1), sizeof *k->tilt))
        return -1;
    k->cap_tilt = cap;
    return 0;
}

uint32_t sketch_open_points(const Sketch *k)
{
    return k->npts - (k->npolys ? k->start[k->npolys] : 0);
}

int sketch_add_point(Sketch *k, float x, float y)
{
    if (!(x >= -1 && x <= 1 && y >= -1 && y <= 1))
        return -1;      /* off the canvas (or NaN) */
    if (room_polys(k) || grow_array((void **)&k->pts, &k->cap_pts, k->npts + 1, sizeof *k->pts))
        return -1;
    if (k->npolys == 0)
        k->start[0] = 0;
    k->pts[k->npts++] = (SketchPt){ x, y };
    return 0;
}

int sketch_close(Sketch *k)
{
    if (sketch_open_points(k) < 3 || room_polys(k))
        return -1;
    uint32_t p = k->npolys++;
    k->start[p + 1] = k->npts;
    k->tilt[2 * p] = k->tilt[2 * p + 1] = 0;
    k->sel = (int)p;
    return 0;
}

int sketch_undo(Sketch *k)
{
    if (sketch_open_points(k) > 0) {
        k->npts--;          /* the open polygon's last vertex */
        return 0;
    }
    if (k->npolys == 0)
        return -1;
    /* no open corners: the last polygon goes, corners and all (one
     * step per polygon, not one per corner) */
    k->npolys--;
    k->npts = k->start[k->npolys];
    if (k->sel >= (int)k->npolys)
        k->sel = (int)k->npolys - 1;
    return 0;
}

void sketch_clear(Sketch *k)
{
    k->npts = k->npolys = 0;
    k->sel = -1;
    k->flipped = 0;
}

void sketch_flip(Sketch *k)
{
    k->flipped = !k->flipped;
}

int sketch_tilt(Sketch *k, float dx_deg, float dy_deg)
{
    if (k->sel < 0 || k->sel >= (int)k->npolys)
        return -1;
    float *t = &k->tilt[2 * k->sel];
    t[0] = fmaxf(-SKETCH_TILT_MAX, fminf(SKETCH_TILT_MAX, t[0] + dx_deg));
    t[1] = fmaxf(-SKETCH_TILT_MAX, fminf(SKETCH_TILT_MAX, t[1] + dy_deg));
    return 0;
}

void sketch_select_next(Sketch *k)
{
    if (k->npolys)
        k->sel = (k->sel + 1) % (int)k->npolys;
}

/* Depth of polygon p's plane at its centre: nearer (larger z, towards
 * the viewer) for later polygons, or earlier ones when flipped. */
static float plane_z(const Sketch *k, uint32_t p)
{
    uint32_t rank = k->flipped ? k->npolys - 1 - p : p;
    return SKETCH_DZ * (float)(rank + 1);
}

/* The centre of polygon p (mean of its corners). */
static SketchPt centre(const Sketch *k, uint32_t p)
{
    SketchPt c = { 0, 0 };
    uint32_t a = k->start[p], b = k->start[p + 1];
    for (uint32_t i = a; i < b; i++) {
        c.x += k->pts[i].x;
        c.y += k->pts[i].y;
    }
    c.x /= (float)(b - a);
    c.y /= (float)(b - a);
    return c;
}

float sketch_depth_at(const Sketch *k, uint32_t p, float x, float y)
{
    SketchPt c = centre(k, p);
    return plane_z(k, p) + tanf(deg2rad(k->tilt[2 * p])) * (x - c.x) + tanf(deg2rad(k->tilt[2 * p + 1])) * (y - c.y);
}

int sketch_to_obj(const Sketch *k, FILE *f)
{
    int bad = fprintf(f, "# zview sketch: %u polygon%s, the last drawn %s\n", k->npolys, k->npolys == 1 ? "" : "s",
                      k->flipped ? "farthest" : "nearest") < 0;
    uint32_t v = 0;
    for (uint32_t p = 0; p < k->npolys && !bad; p++) {
        uint8_t rgb[3];
        object_colour((int)p + 1, rgb);
        bad |= fprintf(f, "o polygon%u\n", p + 1) < 0;
        uint32_t a = k->start[p], b = k->start[p + 1];
        for (uint32_t i = a; i < b; i++) {
            const SketchPt *q = &k->pts[i];
            bad |= fprintf(f, "v %.6g %.6g %.6g %.4g %.4g %.4g\n", (double)q->x, (double)q->y,
                           (double)sketch_depth_at(k, p, q->x, q->y), rgb[0] / 255.0, rgb[1] / 255.0,
                           rgb[2] / 255.0) < 0;
        }
        bad |= fprintf(f, "f") < 0;
        for (uint32_t i = a; i < b; i++)
            bad |= fprintf(f, " %u", v + 1 + (i - a)) < 0;
        bad |= fprintf(f, "\n") < 0;
        v += b - a;
    }
    return bad ? -1 : 0;
}

char *sketch_to_text(const Sketch *k, size_t *len_out)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return NULL;
    int rc = sketch_to_obj(k, f);
    if (fclose(f) != 0 || rc) {
        free(buf);
        return NULL;
    }
    if (len_out)
        *len_out = len;
    return buf;
}
