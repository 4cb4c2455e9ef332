/* hzb.c: the hierarchical z-buffer (simple mode), and the z-pyramid that
 * octree.c shares.
 *
 * Per band of rows, a pyramid of depth maxima sits over the band's depth
 * buffer (hzb.h): level 0 is the depth buffer itself, each level above
 * holds the max of 2 x 2 texels of the one below, up to a single texel.
 * Polygons are taken in scene order. Before a polygon is rasterized, its
 * sample box (clipped to the band) is looked up at the finest level where
 * it spans at most 2 x 2 texels; if its zmin (the front end's safe lower
 * bound of every depth plane_at() can give inside it) is strictly greater
 * than all of them, every sample it covers already holds a strictly
 * nearer (depth, id) pair, so hsr_wins() would reject every one of them:
 * the polygon is skipped without changing the result. Otherwise it is
 * drawn exactly as the z-buffer draws it (zbuffer_draw_poly: the raster.h
 * edge walkers and plane_row()/plane_at()), and the texels above the
 * samples it wrote are lowered level by level until a level no longer
 * changes. Because depths only decrease, a texel is never below the true
 * max of its pixels, so culling never removes a possible winner, and the
 * face-id and depth buffers are byte-identical to the z-buffer's.
 *
 * It wins when many polygons are hidden behind earlier ones in scene
 * order (depth complexity, closed models seen with culling off); it costs
 * a 4-texel lookup per polygon and the pyramid updates otherwise. */

#include <math.h>
#include <stdlib.h>

#include "hsr.h"
#include "hzb.h"
#include "raster.h"
#include "zbuffer.h"

extern const HsrAlgo hsr_zbuffer;

/* ==== the pyramid ==== */

int hzb_pyr_begin(HzbPyramid *p, FrameBufs *fb, int y0, int y1)
{
    fbuf_clear_rows(fb, y0, y1);
    int w = fb->w, h = y1 - y0;
    p->w = w;
    p->y0 = y0;
    p->h = h;
    p->d0 = fb->depth + (size_t)y0 * w;
    p->lw[0] = w;
    p->lh[0] = h;
    p->off[0] = 0;
    int k = 0;
    size_t total = 0;
    while ((p->lw[k] > 1 || p->lh[k] > 1) && k + 1 < HZB_MAX_LEVELS) {
        k++;
        p->lw[k] = (p->lw[k - 1] + 1) / 2;
        p->lh[k] = (p->lh[k - 1] + 1) / 2;
        p->off[k] = total;
        total += (size_t)p->lw[k] * p->lh[k];
    }
    p->nlev = k + 1;
    if (total > p->cap) {
        float *t = realloc(p->tex, total * sizeof *t);
        if (!t) {
            p->nlev = 0;        /* still correct: nothing is culled */
            return -1;
        }
        p->tex = t;
        p->cap = total;
    }
    for (size_t i = 0; i < total; i++)
        p->tex[i] = INFINITY;
    return 0;
}

void hzb_pyr_free(HzbPyramid *p)
{
    free(p->tex);
    p->tex = NULL;
    p->cap = 0;
}

static inline float maxf(float a, float b)
{
    return a > b ? a : b;
}

void hzb_pyr_update(HzbPyramid *p, int x0, int x1, int ya, int yb)
{
    int bx0 = x0, bx1 = x1 - 1, by0 = ya - p->y0, by1 = yb - 1 - p->y0;
    const float *src = p->d0;
    int sw = p->w, sh = p->h, sstride = p->w;
    for (int k = 1; k < p->nlev; k++) {
        float *dst = p->tex + p->off[k];
        int dstride = p->lw[k];
        bx0 >>= 1; bx1 >>= 1; by0 >>= 1; by1 >>= 1;
        int changed = 0;
        for (int ty = by0; ty <= by1; ty++) {
            int sy0 = 2 * ty, sy1 = 2 * ty + 1 < sh ? 2 * ty + 1 : sh - 1;
            const float *ra = src + (size_t)sy0 * sstride, *rb = src + (size_t)sy1 * sstride;
            float *d = dst + (size_t)ty * dstride;
            for (int tx = bx0; tx <= bx1; tx++) {
                int sx0 = 2 * tx, sx1 = 2 * tx + 1 < sw ? 2 * tx + 1 : sw - 1;
                float m = maxf(maxf(ra[sx0], ra[sx1]), maxf(rb[sx0], rb[sx1]));
                if (m != d[tx]) {
                    d[tx] = m;
                    changed = 1;
                }
            }
        }
        if (!changed)
            break;
        src = dst;
        sw = p->lw[k];
        sh = p->lh[k];
        sstride = dstride;
    }
}

/* ==== one polygon: test, draw, update ==== */

void hzb_draw_poly(HzbPyramid *p, void *zstate, const ScreenPolys *sp, uint32_t pi,
                   FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    const ScreenPoly *q = &sp->polys[pi];
    int ya = q->y0 > y0 ? q->y0 : y0, yb = q->y1 < y1 ? q->y1 : y1;
    if (ya >= yb)
        return;
    stats->polys_in++;
    if (hzb_pyr_hidden(p, q->x0, q->x1, ya, yb, q->zmin)) {
        stats->polys_culled++;
        return;
    }
    uint64_t n = zbuffer_draw_poly(zstate, sp, pi, fb, ya, yb);
    if (n) {
        stats->pixels_written += n;
        hzb_pyr_update(p, q->x0, q->x1, ya, yb);
    }
}

/* ==== the algorithm ==== */

typedef struct {
    void      *zb;          /* the z-buffer's state (edge walkers) */
    HzbPyramid pyr;
} HzbState;

static void *hzb_create(void)
{
    HzbState *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->zb = hsr_zbuffer.create();
    if (!s->zb) {
        free(s);
        return NULL;
    }
    return s;
}

static void hzb_destroy(void *st)
{
    HzbState *s = st;
    if (!s)
        return;
    hsr_zbuffer.destroy(s->zb);
    hzb_pyr_free(&s->pyr);
    free(s);
}

static void hzb_render(void *st, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    HzbState *s = st;
    const ScreenPolys *sp = in->sp;
    double t0 = now_ms();
    hzb_pyr_begin(&s->pyr, fb, y0, y1);
    stats->build_ms += now_ms() - t0;
    for (uint32_t i = 0; i < sp->npolys; i++) {
        const ScreenPoly *q = &sp->polys[i];
        if (q->y1 <= y0 || q->y0 >= y1)
            continue;
        hzb_draw_poly(&s->pyr, s->zb, sp, i, fb, y0, y1, stats);
    }
}

const HsrAlgo hsr_hzb = {
    .name = "hzb",
    .summary = "hierarchical z-buffer: a z-pyramid culls hidden polygons, scene order",
    .create = hzb_create,
    .destroy = hzb_destroy,
    .render = hzb_render,
};
