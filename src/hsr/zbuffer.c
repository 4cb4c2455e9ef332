/* zbuffer.c: the plain per-pixel z-buffer, the reference every other
 * algorithm is compared with. Each polygon is walked row by row with the
 * exact edge walkers of raster.h and its samples are depth-tested one by
 * one against the (depth, id) pair stored there. */

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

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
    memset(fb->ids + a, 0xff, (b - a) * sizeof *fb->ids);   /* -1 */
    size_t i = a;
#ifdef __SSE2__
    const __m128 inf = _mm_set1_ps(INFINITY);
    for (; i < b && (i & 3); i++)
        fb->depth[i] = INFINITY;
    for (; i + 4 <= b; i += 4)
        _mm_store_ps(fb->depth + i, inf);
#endif
    for (; i < b; i++)
        fb->depth[i] = INFINITY;
}

/* Depth-test samples [xa, xb) of row j. Returns samples written. */
static inline uint64_t span_test(const ScreenPoly *p, FrameBufs *fb, int j, int xa, int xb)
{
    int32_t *ids = fb->ids + (size_t)j * fb->w;
    float *dep = fb->depth + (size_t)j * fb->w;
    float zr = plane_row(p, j);
    int32_t id = p->face;
    uint64_t n = 0;
    int i = xa;
#ifdef __SSE2__
    /* Four samples at a time: the same IEEE operations as plane_at()
     * (a convert, a multiply, an add), so bit-equal depths; the (depth,
     * id) comparison of hsr_wins() without branches. */
    if (xb - xa >= 4) {
        const __m128 va = _mm_set1_ps(p->a), vzr = _mm_set1_ps(zr);
        const __m128i vid = _mm_set1_epi32(id);
        const __m128i bias = _mm_set1_epi32(INT32_MIN);
        const __m128i vidb = _mm_xor_si128(vid, bias);   /* unsigned compare via bias */
        __m128i vk = _mm_setr_epi32(xa - p->x0, xa - p->x0 + 1, xa - p->x0 + 2, xa - p->x0 + 3);
        const __m128i four = _mm_set1_epi32(4);
        for (; i + 4 <= xb; i += 4) {
            __m128 z = _mm_add_ps(vzr, _mm_mul_ps(va, _mm_cvtepi32_ps(vk)));
            vk = _mm_add_epi32(vk, four);
            __m128 zb = _mm_loadu_ps(dep + i);
            __m128i ib = _mm_loadu_si128((const __m128i *)(ids + i));
            __m128i lt = _mm_castps_si128(_mm_cmplt_ps(z, zb));
            __m128i eq = _mm_castps_si128(_mm_cmpeq_ps(z, zb));
            __m128i idlt = _mm_cmpgt_epi32(_mm_xor_si128(ib, bias), vidb);
            __m128i win = _mm_or_si128(lt, _mm_and_si128(eq, idlt));
            int mask = _mm_movemask_ps(_mm_castsi128_ps(win));
            if (!mask)
                continue;
            __m128 wf = _mm_castsi128_ps(win);
            _mm_storeu_ps(dep + i, _mm_or_ps(_mm_and_ps(wf, z), _mm_andnot_ps(wf, zb)));
            _mm_storeu_si128((__m128i *)(ids + i),
                             _mm_or_si128(_mm_and_si128(win, vid), _mm_andnot_si128(win, ib)));
            n += (uint64_t)((0x4332322132212110ULL >> (4 * mask)) & 15);   /* popcount of 4 bits */
        }
    }
#endif
    for (; i < xb; i++) {
        float z = plane_at(p, zr, i);
        if (hsr_wins(z, id, dep[i], ids[i])) {
            dep[i] = z;
            ids[i] = id;
            n++;
        }
    }
    return n;
}

/* A triangle with few samples in its box: the edge functions of
 * raster.h per sample, no division. */
static uint64_t draw_small_triangle(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    TriEdges t;
    if (!tri_edges_setup(&t, v, p->x0, ya))
        return 0;
    int64_t *e_row = t.e, *step_x = t.step_x, *step_y = t.step_y, *bias = t.bias;
    uint64_t n = 0;
    int w = fb->w;
    int32_t id = p->face;
    for (int j = ya; j < yb; j++) {
        int64_t e0 = e_row[0], e1 = e_row[1], e2 = e_row[2];
        int32_t *ids = fb->ids + (size_t)j * w;
        float *dep = fb->depth + (size_t)j * w;
        float zr = plane_row(p, j);
        for (int i = p->x0; i < p->x1; i++) {
            if (e0 >= bias[0] && e1 >= bias[1] && e2 >= bias[2]) {
                float z = plane_at(p, zr, i);
                if (hsr_wins(z, id, dep[i], ids[i])) {
                    dep[i] = z;
                    ids[i] = id;
                    n++;
                }
            }
            e0 += step_x[0];
            e1 += step_x[1];
            e2 += step_x[2];
        }
        e_row[0] += step_y[0];
        e_row[1] += step_y[1];
        e_row[2] += step_y[2];
    }
    return n;
}

/* Boxes of at most this many samples take the edge-function path. */
#define SMALL_BOX 24

/* A triangle: sorted by y, the long edge against the two short ones. */
static uint64_t draw_triangle(const ScreenPolys *sp, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    const ScreenVert *v = &sp->verts[p->first];
    if ((p->x1 - p->x0) * (yb - ya) <= SMALL_BOX)
        return draw_small_triangle(v, p, fb, ya, yb);
    const ScreenVert *t = &v[0], *m = &v[1], *b = &v[2], *x;
    if (m->y < t->y) { x = t; t = m; m = x; }
    if (b->y < m->y) { x = m; m = b; b = x; }
    if (m->y < t->y) { x = t; t = m; m = x; }
    EdgeWalk lg, sh;
    if (!edge_setup(&lg, t, b, ya))
        return 0;
    uint64_t n = 0;
    int w = fb->w;
    int rm = sample_ceil(m->y);
    /* upper part: long edge and top->mid; lower part: long and mid->bottom */
    for (int part = 0; part < 2; part++) {
        const ScreenVert *s0 = part ? m : t, *s1 = part ? b : m;
        int r0 = part ? rm : lg.row0, r1 = part ? lg.row1 : rm;
        if (r0 < ya) r0 = ya;
        if (r1 > yb) r1 = yb;
        if (r0 >= r1 || !edge_setup(&sh, s0, s1, r0))
            continue;
        for (int j = r0; j < r1; j++) {
            int32_t xa = lg.xi < sh.xi ? lg.xi : sh.xi, xb = lg.xi < sh.xi ? sh.xi : lg.xi;
            xa = clamp_col(xa, w);
            xb = clamp_col(xb, w);
            if (xa < xb)
                n += span_test(p, fb, j, xa, xb);
            edge_step(&lg);
            edge_step(&sh);
        }
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
