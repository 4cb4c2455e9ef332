/* zbuffer.c: the plain per-pixel z-buffer, the reference every other
 * algorithm is compared with. Each polygon is walked row by row with the
 * exact edge walkers of raster.h and its samples are depth-tested one by
 * one against the (depth, id) pair stored there. */

#include <math.h>
#include <stdlib.h>

#include "raster.h"
#include "hsr.h"
#include "zbuffer.h"

typedef struct {
    PolyWalk walk;          /* general polygons */
    int32_t *xs;            /* crossings of one row */
    int      xs_cap;
} ZState;

static void *zb_create(void)
{
    return calloc(1, sizeof(ZState));
}

static void zb_destroy(void *st)
{
    ZState *z = st;
    polywalk_free(&z->walk);
    free(z->xs);
    free(z);
}

void fbuf_clear_rows(FrameBufs *fb, int y0, int y1)
{
    size_t a = (size_t)y0 * fb->w, b = (size_t)y1 * fb->w;
    for (size_t i = a; i < b; i++) {
        fb->ids[i] = -1;
        fb->depth[i] = INFINITY;
    }
}

/* Depth-test samples [xa, xb) of row j. Returns samples written. */
static inline uint64_t span_test(const ScreenPoly *p, FrameBufs *fb, int j, int xa, int xb)
{
    int32_t *ids = fb->ids + (size_t)j * fb->w;
    float *dep = fb->depth + (size_t)j * fb->w;
    float zr = plane_row(p, j);
    int32_t id = p->face;
    uint64_t n = 0;
    for (int i = xa; i < xb; i++) {
        float z = plane_at(p, zr, i);
        if (hsr_wins(z, id, dep[i], ids[i])) {
            dep[i] = z;
            ids[i] = id;
            n++;
        }
    }
    return n;
}

/* A triangle: two edge walkers active per row. */
static uint64_t draw_triangle(const ScreenPolys *sp, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    const ScreenVert *v = &sp->verts[p->first];
    EdgeWalk e[3];
    int ne = 0;
    for (int k = 0; k < 3; k++)
        if (edge_setup(&e[ne], &v[k], &v[k == 2 ? 0 : k + 1], ya) && e[ne].row1 > ya)
            ne++;
    if (ne < 2)
        return 0;
    uint64_t n = 0;
    int w = fb->w;
    for (int j = ya; j < yb; j++) {
        int32_t x[2];
        int m = 0;
        for (int k = 0; k < ne; k++) {
            if (j < e[k].row0 || j >= e[k].row1)
                continue;
            x[m++ & 1] = e[k].xi;
            edge_step(&e[k]);
        }
        if (m < 2)
            continue;
        int32_t xa = x[0] < x[1] ? x[0] : x[1], xb = x[0] < x[1] ? x[1] : x[0];
        xa = clamp_col(xa, w);
        xb = clamp_col(xb, w);
        if (xa < xb)
            n += span_test(p, fb, j, xa, xb);
    }
    return n;
}

static uint64_t draw_polygon(ZState *z, const ScreenPolys *sp, uint32_t pi, FrameBufs *fb, int ya, int yb)
{
    const ScreenPoly *p = &sp->polys[pi];
    int ne = polywalk_begin(&z->walk, sp, pi, ya);
    if (ne <= 0)
        return 0;
    if (ne > z->xs_cap) {
        int32_t *q = realloc(z->xs, (size_t)ne * 2 * sizeof *q);
        if (!q)
            return 0;
        z->xs = q;
        z->xs_cap = ne * 2;
    }
    uint64_t n = 0;
    for (int j = ya; j < yb; j++) {
        int m = polywalk_row(&z->walk, j, z->xs);
        for (int k = 0; k + 1 < m; k += 2) {
            int32_t xa = clamp_col(z->xs[k], fb->w), xb = clamp_col(z->xs[k + 1], fb->w);
            if (xa < xb)
                n += span_test(p, fb, j, xa, xb);
        }
    }
    return n;
}

uint64_t zbuffer_draw_poly(void *st, const ScreenPolys *sp, uint32_t pi, FrameBufs *fb, int y0, int y1)
{
    const ScreenPoly *p = &sp->polys[pi];
    int ya = p->y0 > y0 ? p->y0 : y0, yb = p->y1 < y1 ? p->y1 : y1;
    if (ya >= yb)
        return 0;
    if (screen_poly_nverts(sp, pi) == 3)
        return draw_triangle(sp, p, fb, ya, yb);
    return draw_polygon(st, sp, pi, fb, ya, yb);
}

static void zb_render(void *st, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    const ScreenPolys *sp = in->sp;
    fbuf_clear_rows(fb, y0, y1);
    uint64_t written = 0, polys = 0;
    for (uint32_t i = 0; i < sp->npolys; i++) {
        const ScreenPoly *p = &sp->polys[i];
        if (p->y1 <= y0 || p->y0 >= y1)
            continue;
        polys++;
        written += zbuffer_draw_poly(st, sp, i, fb, y0, y1);
    }
    stats->polys_in += polys;
    stats->pixels_written += written;
}

const HsrAlgo hsr_zbuffer = {
    .name = "zbuffer",
    .summary = "plain per-pixel z-buffer (the reference)",
    .create = zb_create,
    .destroy = zb_destroy,
    .render = zb_render,
};
