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
 * samples it wrote are flagged dirty: a later test recomputes a dirty
 * texel only when its stale value fails to cull. Because depths only
 * decrease, a texel is never below the true max of its pixels, so culling
 * never removes a possible winner, and the face-id and depth buffers are
 * byte-identical to the z-buffer's.
 *
 * It wins when many polygons are hidden behind earlier ones in scene
 * order (depth complexity, closed models seen with culling off); it costs
 * a small lookup per polygon and the lazy pyramid upkeep otherwise.
 *
 * Implements the z-pyramid of N. Greene, M. Kass and G. Miller,
 * "Hierarchical Z-Buffer Visibility", SIGGRAPH 1993 (its simple mode:
 * polygons tested against the pyramid in the order given).
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "hsr.h"
#include "hzb.h"
#include "raster.h"
#include "zbuffer.h"

extern const HsrAlgo hsr_zbuffer;

/* ==== the pyramid ==== */

int hzb_pyr_begin(HzbPyramid *p, FrameBufs *fb, int y0, int y1, int simd)
{
    fbuf_clear_rows(fb, y0, y1);
    int w = fb->w, h = y1 - y0;
    p->simd = simd;
    p->w = w;
    p->y0 = y0;
    p->h = h;
    p->d0 = fb->depth + (size_t)y0 * w;
    p->lw[0] = w;
    p->lh[0] = h;
    p->off[0] = 0;
    int k = 0;
    size_t total = 0;
    /* halve up to one texel, and at least up to the first kept level */
    while ((p->lw[k] > 1 || p->lh[k] > 1 || k < HZB_FIRST) && k + 1 < HZB_MAX_LEVELS) {
        k++;
        p->lw[k] = (p->lw[k - 1] + 1) / 2;
        p->lh[k] = (p->lh[k - 1] + 1) / 2;
        p->off[k] = total;
        if (k >= HZB_FIRST)
            total += (size_t)p->lw[k] * p->lh[k];
    }
    p->nlev = k + 1;
    if (total > p->cap) {
        float *t = realloc(p->tex, total * sizeof *t);
        if (t)
            p->tex = t;
        uint8_t *d = realloc(p->dirty, total);
        if (d)
            p->dirty = d;
        if (!t || !d) {
            p->nlev = 0;        /* still correct: nothing is culled */
            return -1;
        }
        p->cap = total;
    }
    for (size_t i = 0; i < total; i++)
        p->tex[i] = INFINITY;
    memset(p->dirty, 0, total);
    return 0;
}

void hzb_pyr_free(HzbPyramid *p)
{
    free(p->tex);
    free(p->dirty);
    p->tex = NULL;
    p->dirty = NULL;
    p->cap = 0;
}

static inline float maxf(float a, float b)
{
    return a > b ? a : b;
}

void hzb_pyr_mark(HzbPyramid *p, int x0, int x1, int ya, int yb)
{
    if (p->nlev == 0)
        return;
    int tx0 = x0 >> HZB_FIRST, tx1 = (x1 - 1) >> HZB_FIRST;
    int ty0 = (ya - p->y0) >> HZB_FIRST, ty1 = (yb - 1 - p->y0) >> HZB_FIRST;
    uint8_t *dl = p->dirty + p->off[HZB_FIRST];
    int stride = p->lw[HZB_FIRST];
    for (int ty = ty0; ty <= ty1; ty++) {
        for (int tx = tx0; tx <= tx1; tx++) {
            size_t i = (size_t)ty * stride + tx;
            if (dl[i])
                continue;       /* and so are its ancestors */
            dl[i] = 1;
            int ax = tx >> 1, ay = ty >> 1;
            for (int k = HZB_FIRST + 1; k < p->nlev; k++, ax >>= 1, ay >>= 1) {
                uint8_t *d = &p->dirty[p->off[k] + (size_t)ay * p->lw[k] + ax];
                if (*d)
                    break;
                *d = 1;
            }
        }
    }
}

/* Max of the pixels under texel (tx, ty) of level HZB_FIRST: the same
 * pixels at every level, so the same maximum (up to the sign of a zero,
 * and -0 == +0 in every test). */
static float block_max(const HzbPyramid *p, int tx, int ty)
{
    const int S = 1 << HZB_FIRST;
    int sx = tx * S, sy = ty * S, ey = sy + S < p->h ? sy + S : p->h;
    const float *row = p->d0 + (size_t)sy * p->w;
#ifdef ZV_SSE2
    if (p->simd >= SIMD_SSE2 && sx + S <= p->w) {
        __m128 v = _mm_loadu_ps(row + sx);
        for (int j = sy; j < ey; j++, row += p->w)
            for (int x = sx; x < sx + S; x += 4)
                v = _mm_max_ps(v, _mm_loadu_ps(row + x));
        v = _mm_max_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
        v = _mm_max_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2)));
        return _mm_cvtss_f32(v);
    }
#endif
    int ex = sx + S < p->w ? sx + S : p->w;
    float m = -INFINITY;
    for (int j = sy; j < ey; j++, row += p->w)
        for (int x = sx; x < ex; x++)
            m = maxf(m, row[x]);
    return m;
}

float hzb_pyr_refresh(HzbPyramid *p, int k, int tx, int ty)
{
    size_t i = p->off[k] + (size_t)ty * p->lw[k] + tx;
    float m;
    if (k == HZB_FIRST) {
        m = block_max(p, tx, ty);
    } else {
        /* children 2t and 2t + 1, the last one repeated at an odd edge */
        int cw = p->lw[k - 1], ch = p->lh[k - 1];
        int cx[2] = { 2 * tx, 2 * tx + 1 < cw ? 2 * tx + 1 : cw - 1 };
        int cy[2] = { 2 * ty, 2 * ty + 1 < ch ? 2 * ty + 1 : ch - 1 };
        m = -INFINITY;
        for (int b = 0; b < 2; b++)
            for (int a = 0; a < 2; a++) {
                size_t c = p->off[k - 1] + (size_t)cy[b] * cw + cx[a];
                float v = p->dirty[c] ? hzb_pyr_refresh(p, k - 1, cx[a], cy[b]) : p->tex[c];
                m = maxf(m, v);
            }
    }
    p->tex[i] = m;
    p->dirty[i] = 0;
    return m;
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
        hzb_pyr_mark(p, q->x0, q->x1, ya, yb);
    }
}

/* ==== the algorithm ==== */

int hzb_base_init(HzbBase *b)
{
    b->zb = hsr_zbuffer.create();
    return b->zb ? 0 : -1;
}

int hzb_base_begin(HzbBase *b, FrameBufs *fb, int y0, int y1, int simd)
{
    zbuffer_begin(b->zb, simd);
    return hzb_pyr_begin(&b->pyr, fb, y0, y1, simd);
}

void hzb_base_free(HzbBase *b)
{
    if (b->zb)
        hsr_zbuffer.destroy(b->zb);
    hzb_pyr_free(&b->pyr);
}

static void *hzb_create(void)
{
    HzbBase *s = calloc(1, sizeof *s);
    if (s && hzb_base_init(s)) {
        free(s);
        s = NULL;
    }
    return s;
}

static void hzb_destroy(void *st)
{
    if (!st)
        return;
    hzb_base_free(st);
    free(st);
}

static void hzb_render(void *st, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    HzbBase *s = st;
    const ScreenPolys *sp = in->sp;
    double t0 = now_ms();
    hzb_base_begin(s, fb, y0, y1, simd_use(in->simd));
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
