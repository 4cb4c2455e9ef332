/* zbuffer.c: the plain per-pixel z-buffer, the reference every other
 * algorithm is compared with. Each polygon is walked row by row with the
 * exact edge walkers of raster.h and its samples are depth-tested one by
 * one against the (depth, id) pair stored there. At the frame's SIMD
 * level (HsrInput.simd, simd.h) spans are tested four samples at a time
 * (SSE2) and small triangles eight at a time by edge functions (AVX2);
 * both write the scalar loop's bytes.
 *
 * Implements the depth buffer of E. Catmull, "A Subdivision Algorithm
 * for Computer Display of Curved Surfaces", PhD thesis, University of
 * Utah, 1974 (found independently by W. Strasser the same year). The
 * AVX2 triangle path steps the edge functions of J. Pineda, "A Parallel
 * Algorithm for Polygon Rasterization", SIGGRAPH 1988.
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "invariant.h"
#include "raster.h"
#include "hsr.h"
#include "simd.h"
#include "zbuffer.h"

typedef struct {
    PolyWalk walk;          /* general polygons */
    int32_t *xs;            /* crossings of one row */
    int      xs_cap;
    int      simd;          /* the frame's SimdLevel, resolved: set where a frame
                               starts (zb_render, zbuffer_begin), so that the
                               per-polygon calls carry no extra argument */
} ZState;

static void *zb_create(void)
{
    return calloc(1, sizeof(ZState));
}

void zbuffer_begin(void *st, int simd)
{
    ((ZState *)st)->simd = simd;
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
    /* the same stores at every level: no SimdLevel to pass */
#ifdef ZV_SSE2
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
static inline uint64_t span_test(int simd, const ScreenPoly *p, FrameBufs *fb, int j, int xa, int xb)
{
    /* The exact walk never leaves the sample box the front end gave the
     * polygon (its crossings lie between its corners): the plane is
     * referenced to that box, and hzb's and span's depth bounds are
     * taken over it, so a span outside it would be a sample no bound
     * accounted for. */
    ZV_ASSERT(j >= p->y0 && j < p->y1 && xa >= p->x0 && xa < xb && xb <= p->x1);
    int32_t *ids = fb->ids + (size_t)j * fb->w;
    float *dep = fb->depth + (size_t)j * fb->w;
    float zr = plane_row(p, j);
    int32_t id = p->face;
    uint64_t n = 0;
    int i = xa;
#ifdef ZV_SSE2
    /* Four samples at a time: the same IEEE operations as plane_at()
     * (a convert, a multiply, an add), so bit-equal depths; the (depth,
     * id) comparison of hsr_wins() without branches. */
    if (simd >= SIMD_SSE2 && xb - xa >= 4) {
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
#else
    (void)simd;
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

#ifdef ZV_AVX2
/* Triangles whose corners lie within this many pixels of each other, each
 * way, take the AVX2 path: relative to the first sample of their box,
 * every edge function value it meets (eight columns past the box
 * included) stays below 2^31, so 32-bit lanes hold them exactly. */
#define AVX2_SPAN 64

/* A triangle's edges as raster.h's TriEdges (exactly the crossing rule),
 * in 32-bit lanes: e at the sample of each lane, its step to the next
 * block, and the bias (inside where e > lim, i.e. e >= bias). */
typedef struct {
    __m256i e[3], step[3], lim[3];
    int32_t sx[3], sy[3];       /* per column, per row */
} Edges8;

/* Set up the edges of triangle v at sample (x0, ya) for lanes that sit
 * at column x0 + (l % wl), row ya + (l / wl), stepping rows by 8 / wl a
 * block (wl = 8: a block steps columns instead, by 8). 0: no area. */
ZV_AVX2_FN static inline __attribute__((always_inline)) int
edges8_setup(Edges8 *t, const ScreenVert *v, int32_t x0, int32_t ya, int wl)
{
    int32_t ox = 256 * x0 + 128, oy = 256 * ya + 128;
    int32_t ax = v[0].x - ox, ay = v[0].y - oy, bx = v[1].x - ox, by = v[1].y - oy, cx = v[2].x - ox,
            cy = v[2].y - oy;
    /* twice the signed area: within 2^31 at these spans */
    int32_t orient = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (orient == 0)
        return 0;
    if (orient < 0) {           /* walk the edges the other way round */
        int32_t q = bx;
        bx = cx;
        cx = q;
        q = by;
        by = cy;
        cy = q;
    }
    const int32_t px[4] = { ax, bx, cx, ax }, py[4] = { ay, by, cy, ay };
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    __m256i col = lane, row = _mm256_setzero_si256();
    if (wl < 8) {
        int sh = wl == 4 ? 2 : 1;
        col = _mm256_and_si256(lane, _mm256_set1_epi32(wl - 1));
        row = _mm256_srli_epi32(lane, sh);
    }
    for (int k = 0; k < 3; k++) {
        int32_t dx = px[k + 1] - px[k], dy = py[k + 1] - py[k];
        t->sx[k] = -dy * 256;
        t->sy[k] = dx * 256;
        /* e at the sample itself: dx (0 - ay) - dy (0 - ax) */
        int32_t e0 = dy * px[k] - dx * py[k];
        t->e[k] = _mm256_add_epi32(_mm256_set1_epi32(e0),
                                   _mm256_add_epi32(_mm256_mullo_epi32(_mm256_set1_epi32(t->sx[k]), col),
                                                    _mm256_mullo_epi32(_mm256_set1_epi32(t->sy[k]), row)));
        t->step[k] = _mm256_set1_epi32(wl < 8 ? t->sy[k] * (8 / wl) : t->sx[k] * 8);
        t->lim[k] = _mm256_set1_epi32((-dy > 0 || (dy == 0 && dx > 0)) ? -1 : 0);
    }
    return 1;
}

ZV_AVX2_FN static inline __m256i edges8_in(const Edges8 *t, __m256i e0, __m256i e1, __m256i e2)
{
    return _mm256_and_si256(_mm256_and_si256(_mm256_cmpgt_epi32(e0, t->lim[0]), _mm256_cmpgt_epi32(e1, t->lim[1])),
                            _mm256_cmpgt_epi32(e2, t->lim[2]));
}

/* Two 32-bit values (a float or id pair of one row) at p and at q, as the
 * low and high halves of a vector; and the low pair of v stored at p.
 * 64-bit moves through the unaligned integer intrinsics: the pairs sit
 * at any 4-byte boundary. */
ZV_AVX2_FN static inline __m128i load2x2(const void *p, const void *q)
{
    return _mm_unpacklo_epi64(_mm_loadl_epi64((const __m128i *)p), _mm_loadl_epi64((const __m128i *)q));
}

ZV_AVX2_FN static inline void store2(void *p, __m128i v)
{
    _mm_storel_epi64((__m128i *)p, v);
}

/* hsr_wins() of (z, id) against (zb, ib), eight lanes, within in. */
ZV_AVX2_FN static inline __m256i wins8(__m256 z, __m256i vidb, __m256 zb, __m256i ib, __m256i in)
{
    const __m256i bias = _mm256_set1_epi32(INT32_MIN);
    __m256i lt = _mm256_castps_si256(_mm256_cmp_ps(z, zb, _CMP_LT_OQ));
    __m256i eq = _mm256_castps_si256(_mm256_cmp_ps(z, zb, _CMP_EQ_OQ));
    __m256i idlt = _mm256_cmpgt_epi32(_mm256_xor_si256(ib, bias), vidb);    /* id < ib, unsigned */
    return _mm256_and_si256(in, _mm256_or_si256(lt, _mm256_and_si256(eq, idlt)));
}

/* A triangle by edge functions, eight samples of a row a block: three
 * adds step the edges, compares with the top-left bias give coverage, and
 * the depth test is span_test()'s (plane_at()'s convert, multiply and
 * add; hsr_wins() on (depth, id)), eight wide. Blocks reaching past the
 * image's right edge finish one sample at a time. Returns the samples
 * written. */
ZV_AVX2_FN static uint64_t draw_tri_rows8(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    Edges8 t;
    if (!edges8_setup(&t, v, p->x0, ya, 8))
        return 0;
    int w = fb->w, x0 = p->x0, x1 = p->x1;
    int32_t id = p->face;
    const __m256 va = _mm256_set1_ps(p->a);
    const __m256i vid = _mm256_set1_epi32(id), vidb = _mm256_xor_si256(vid, _mm256_set1_epi32(INT32_MIN));
    const __m256i xend = _mm256_set1_epi32(x1 - x0), lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256i step_y[3] = { _mm256_set1_epi32(t.sy[0]), _mm256_set1_epi32(t.sy[1]), _mm256_set1_epi32(t.sy[2]) };
    uint64_t n = 0;
    for (int j = ya; j < yb; j++) {
        int32_t *ids = fb->ids + (size_t)j * w;
        float *dep = fb->depth + (size_t)j * w;
        const __m256 vzr = _mm256_set1_ps(plane_row(p, j));
        __m256i e0 = t.e[0], e1 = t.e[1], e2 = t.e[2];
        for (int x = x0; x < x1; x += 8) {
            __m256i rel = _mm256_add_epi32(_mm256_set1_epi32(x - x0), lane);    /* i - x0 */
            __m256i in = _mm256_and_si256(edges8_in(&t, e0, e1, e2), _mm256_cmpgt_epi32(xend, rel));
            e0 = _mm256_add_epi32(e0, t.step[0]);
            e1 = _mm256_add_epi32(e1, t.step[1]);
            e2 = _mm256_add_epi32(e2, t.step[2]);
            if (_mm256_testz_si256(in, in))
                continue;
            __m256 z = _mm256_add_ps(vzr, _mm256_mul_ps(va, _mm256_cvtepi32_ps(rel)));
            if (x + 8 > w) {
                /* the image's right edge: sample by sample */
                float zs[8];
                int32_t m[8];
                _mm256_storeu_ps(zs, z);
                _mm256_storeu_si256((__m256i *)m, in);
                for (int l = 0; l < 8 && x + l < w; l++)
                    if (m[l] && hsr_wins(zs[l], id, dep[x + l], ids[x + l])) {
                        dep[x + l] = zs[l];
                        ids[x + l] = id;
                        n++;
                    }
                continue;
            }
            __m256 zb = _mm256_loadu_ps(dep + x);
            __m256i ib = _mm256_loadu_si256((const __m256i *)(ids + x));
            __m256i win = wins8(z, vidb, zb, ib, in);
            int mask = _mm256_movemask_ps(_mm256_castsi256_ps(win));
            if (!mask)
                continue;
            _mm256_storeu_ps(dep + x, _mm256_blendv_ps(zb, z, _mm256_castsi256_ps(win)));
            _mm256_storeu_si256((__m256i *)(ids + x), _mm256_blendv_epi8(ib, vid, win));
            n += (uint64_t)__builtin_popcount((unsigned)mask);
        }
        t.e[0] = _mm256_add_epi32(t.e[0], step_y[0]);
        t.e[1] = _mm256_add_epi32(t.e[1], step_y[1]);
        t.e[2] = _mm256_add_epi32(t.e[2], step_y[2]);
    }
    return n;
}

/* draw_tri_rows8() of a triangle whose sample box is at most 8 columns
 * wide and wholly inside the image's width: one block a row, so no
 * column loop and no right-edge case; the box mask and a (i - x0) of
 * each lane are made once (the same product rows8 makes every row), so
 * every sample gets the same bits. Most triangles of a mesh of tens of
 * thousands at 1920x1080 are this size. */
ZV_AVX2_FN static uint64_t draw_tri_col8(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    Edges8 t;
    if (!edges8_setup(&t, v, p->x0, ya, 8))
        return 0;
    int w = fb->w;
    int32_t id = p->face;
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256i inbox = _mm256_cmpgt_epi32(_mm256_set1_epi32(p->x1 - p->x0), lane);
    const __m256 za = _mm256_mul_ps(_mm256_set1_ps(p->a), _mm256_cvtepi32_ps(lane));
    const __m256i vid = _mm256_set1_epi32(id), vidb = _mm256_xor_si256(vid, _mm256_set1_epi32(INT32_MIN));
    const __m256i step_y[3] = { _mm256_set1_epi32(t.sy[0]), _mm256_set1_epi32(t.sy[1]), _mm256_set1_epi32(t.sy[2]) };
    int32_t *ids = fb->ids + (size_t)ya * w + p->x0;
    float *dep = fb->depth + (size_t)ya * w + p->x0;
    uint64_t n = 0;
    for (int j = ya; j < yb; j++, ids += w, dep += w) {
        __m256i in = _mm256_and_si256(edges8_in(&t, t.e[0], t.e[1], t.e[2]), inbox);
        t.e[0] = _mm256_add_epi32(t.e[0], step_y[0]);
        t.e[1] = _mm256_add_epi32(t.e[1], step_y[1]);
        t.e[2] = _mm256_add_epi32(t.e[2], step_y[2]);
        if (_mm256_testz_si256(in, in))
            continue;
        __m256 z = _mm256_add_ps(_mm256_set1_ps(plane_row(p, j)), za);
        __m256 zb = _mm256_loadu_ps(dep);
        __m256i ib = _mm256_loadu_si256((const __m256i *)ids);
        __m256i win = wins8(z, vidb, zb, ib, in);
        int mask = _mm256_movemask_ps(_mm256_castsi256_ps(win));
        if (!mask)
            continue;
        _mm256_storeu_ps(dep, _mm256_blendv_ps(zb, z, _mm256_castsi256_ps(win)));
        _mm256_storeu_si256((__m256i *)ids, _mm256_blendv_epi8(ib, vid, win));
        n += (uint64_t)__builtin_popcount((unsigned)mask);
    }
    return n;
}

/* A triangle whose sample box is at most wl (2 or 4) columns wide and
 * wholly inside the image's width: 8 / wl rows a block, lane l at column
 * x0 + l % wl of row j + l / wl. Rows past yb are neither read nor
 * written (they may belong to another band, or lie past the image). */
ZV_AVX2_FN static inline __attribute__((always_inline)) uint64_t
draw_tri_narrow(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya, int yb, const int wl)
{
    Edges8 t;
    if (!edges8_setup(&t, v, p->x0, ya, wl))
        return 0;
    const int rows = 8 / wl;
    int w = fb->w, x0 = p->x0;
    int32_t id = p->face;
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256i col = _mm256_and_si256(lane, _mm256_set1_epi32(wl - 1));
    const __m256i row = _mm256_srli_epi32(lane, wl == 4 ? 2 : 1);
    const __m256i inbox = _mm256_cmpgt_epi32(_mm256_set1_epi32(p->x1 - x0), col);
    const __m256 za = _mm256_mul_ps(_mm256_set1_ps(p->a), _mm256_cvtepi32_ps(col));   /* a (i - x0) */
    const __m256 vzc = _mm256_set1_ps(p->zc), vb = _mm256_set1_ps(p->b);
    const __m256i vid = _mm256_set1_epi32(id), vidb = _mm256_xor_si256(vid, _mm256_set1_epi32(INT32_MIN));
    uint64_t n = 0;
    for (int j = ya; j < yb; j += rows) {
        int left = yb - j < rows ? yb - j : rows;
        __m256i in = _mm256_and_si256(edges8_in(&t, t.e[0], t.e[1], t.e[2]),
                                      _mm256_and_si256(inbox, _mm256_cmpgt_epi32(_mm256_set1_epi32(left), row)));
        t.e[0] = _mm256_add_epi32(t.e[0], t.step[0]);
        t.e[1] = _mm256_add_epi32(t.e[1], t.step[1]);
        t.e[2] = _mm256_add_epi32(t.e[2], t.step[2]);
        if (_mm256_testz_si256(in, in))
            continue;
        /* plane_row() of each lane's row, then plane_at()'s add: the
         * same float operations in the same order, lane by lane */
        __m256i jrow = _mm256_add_epi32(_mm256_set1_epi32(j - p->y0), row);
        __m256 z = _mm256_add_ps(_mm256_add_ps(vzc, _mm256_mul_ps(vb, _mm256_cvtepi32_ps(jrow))), za);
        float *dr[4];
        int32_t *ir[4];
        for (int r = 0; r < rows; r++) {
            int jr = r < left ? j + r : j;          /* a row past yb: read row j again, masked out */
            dr[r] = fb->depth + (size_t)jr * w + x0;
            ir[r] = fb->ids + (size_t)jr * w + x0;
        }
        __m256 zb;
        __m256i ib;
        if (wl == 4) {
            zb = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(dr[0])), _mm_loadu_ps(dr[1]), 1);
            ib = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128((const __m128i *)ir[0])),
                                         _mm_loadu_si128((const __m128i *)ir[1]), 1);
        } else {
            zb = _mm256_castsi256_ps(_mm256_inserti128_si256(_mm256_castsi128_si256(load2x2(dr[0], dr[1])),
                                                             load2x2(dr[2], dr[3]), 1));
            ib = _mm256_inserti128_si256(_mm256_castsi128_si256(load2x2(ir[0], ir[1])), load2x2(ir[2], ir[3]), 1);
        }
        __m256i win = wins8(z, vidb, zb, ib, in);
        int mask = _mm256_movemask_ps(_mm256_castsi256_ps(win));
        if (!mask)
            continue;
        n += (uint64_t)__builtin_popcount((unsigned)mask);
        __m256 zn = _mm256_blendv_ps(zb, z, _mm256_castsi256_ps(win));
        __m256i in_ = _mm256_blendv_epi8(ib, vid, win);
        if (wl == 4) {
            _mm_storeu_ps(dr[0], _mm256_castps256_ps128(zn));
            _mm_storeu_si128((__m128i *)ir[0], _mm256_castsi256_si128(in_));
            if (left > 1) {
                _mm_storeu_ps(dr[1], _mm256_extractf128_ps(zn, 1));
                _mm_storeu_si128((__m128i *)ir[1], _mm256_extracti128_si256(in_, 1));
            }
        } else {
            __m128i zl = _mm256_castsi256_si128(_mm256_castps_si256(zn)), zh = _mm256_extracti128_si256(_mm256_castps_si256(zn), 1);
            __m128i il = _mm256_castsi256_si128(in_), ih = _mm256_extracti128_si256(in_, 1);
            store2(dr[0], zl);
            store2(ir[0], il);
            if (left > 1) {
                store2(dr[1], _mm_unpackhi_epi64(zl, zl));
                store2(ir[1], _mm_unpackhi_epi64(il, il));
            }
            if (left > 2) {
                store2(dr[2], zh);
                store2(ir[2], ih);
            }
            if (left > 3) {
                store2(dr[3], _mm_unpackhi_epi64(zh, zh));
                store2(ir[3], _mm_unpackhi_epi64(ih, ih));
            }
        }
    }
    return n;
}

/* A triangle whose sample box fits one block: at most wl (2 or 4) columns
 * and 8 / wl rows, inside the image's width. No loop and no stepping:
 * each lane's edge functions straight from its sample's offset (the
 * products stay within 2^31 at these sizes), then one depth test. Rows
 * past yb are neither read nor written. */
ZV_AVX2_FN static inline __attribute__((always_inline)) uint64_t
draw_tri_block(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya, int yb, const int wl)
{
    int32_t x0 = p->x0, ox = 256 * x0 + 128, oy = 256 * ya + 128;
    int32_t ax = v[0].x - ox, ay = v[0].y - oy, bx = v[1].x - ox, by = v[1].y - oy, cx = v[2].x - ox,
            cy = v[2].y - oy;
    int32_t orient = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (orient == 0)
        return 0;
    if (orient < 0) {           /* walk the edges the other way round */
        int32_t q = bx;
        bx = cx;
        cx = q;
        q = by;
        by = cy;
        cy = q;
    }
    const int rows = 8 / wl, left = yb - ya;
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256i col = _mm256_and_si256(lane, _mm256_set1_epi32(wl - 1));
    const __m256i row = _mm256_srli_epi32(lane, wl == 4 ? 2 : 1);
    const __m256i sx = _mm256_slli_epi32(col, SUBPIX_BITS), sy = _mm256_slli_epi32(row, SUBPIX_BITS);
    __m256i in = _mm256_and_si256(_mm256_cmpgt_epi32(_mm256_set1_epi32(p->x1 - x0), col),
                                  _mm256_cmpgt_epi32(_mm256_set1_epi32(left), row));
    const int32_t px[4] = { ax, bx, cx, ax }, py[4] = { ay, by, cy, ay };
    for (int k = 0; k < 3; k++) {
        int32_t dx = px[k + 1] - px[k], dy = py[k + 1] - py[k];
        /* e = dx (y - ay) - dy (x - ax) at the lane's sample */
        __m256i e = _mm256_sub_epi32(_mm256_mullo_epi32(_mm256_set1_epi32(dx), _mm256_sub_epi32(sy, _mm256_set1_epi32(py[k]))),
                                     _mm256_mullo_epi32(_mm256_set1_epi32(dy), _mm256_sub_epi32(sx, _mm256_set1_epi32(px[k]))));
        int32_t lim = (-dy > 0 || (dy == 0 && dx > 0)) ? -1 : 0;
        in = _mm256_and_si256(in, _mm256_cmpgt_epi32(e, _mm256_set1_epi32(lim)));
    }
    if (_mm256_testz_si256(in, in))
        return 0;
    /* plane_row() of each lane's row, then plane_at()'s add */
    __m256i jrow = _mm256_add_epi32(_mm256_set1_epi32(ya - p->y0), row);
    __m256 z = _mm256_add_ps(_mm256_add_ps(_mm256_set1_ps(p->zc), _mm256_mul_ps(_mm256_set1_ps(p->b), _mm256_cvtepi32_ps(jrow))),
                             _mm256_mul_ps(_mm256_set1_ps(p->a), _mm256_cvtepi32_ps(col)));
    int w = fb->w;
    float *dr[4];
    int32_t *ir[4];
    for (int r = 0; r < rows; r++) {
        int jr = r < left ? ya + r : ya;        /* a row past yb: read row ya again, masked out */
        dr[r] = fb->depth + (size_t)jr * w + x0;
        ir[r] = fb->ids + (size_t)jr * w + x0;
    }
    __m256 zb;
    __m256i ib;
    if (wl == 4) {
        zb = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(dr[0])), _mm_loadu_ps(dr[1]), 1);
        ib = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128((const __m128i *)ir[0])),
                                     _mm_loadu_si128((const __m128i *)ir[1]), 1);
    } else {
        zb = _mm256_castsi256_ps(_mm256_inserti128_si256(_mm256_castsi128_si256(load2x2(dr[0], dr[1])),
                                                         load2x2(dr[2], dr[3]), 1));
        ib = _mm256_inserti128_si256(_mm256_castsi128_si256(load2x2(ir[0], ir[1])), load2x2(ir[2], ir[3]), 1);
    }
    int32_t id = p->face;
    const __m256i vid = _mm256_set1_epi32(id), vidb = _mm256_xor_si256(vid, _mm256_set1_epi32(INT32_MIN));
    __m256i win = wins8(z, vidb, zb, ib, in);
    int mask = _mm256_movemask_ps(_mm256_castsi256_ps(win));
    if (!mask)
        return 0;
    __m256 zn = _mm256_blendv_ps(zb, z, _mm256_castsi256_ps(win));
    __m256i idn = _mm256_blendv_epi8(ib, vid, win);
    /* store only the rows that won something (the rows past yb never do) */
    if (wl == 4) {
        if (mask & 0x0f) {
            _mm_storeu_ps(dr[0], _mm256_castps256_ps128(zn));
            _mm_storeu_si128((__m128i *)ir[0], _mm256_castsi256_si128(idn));
        }
        if (mask & 0xf0) {
            _mm_storeu_ps(dr[1], _mm256_extractf128_ps(zn, 1));
            _mm_storeu_si128((__m128i *)ir[1], _mm256_extracti128_si256(idn, 1));
        }
    } else {
        __m128i zl = _mm256_castsi256_si128(_mm256_castps_si256(zn)), zh = _mm256_extracti128_si256(_mm256_castps_si256(zn), 1);
        __m128i il = _mm256_castsi256_si128(idn), ih = _mm256_extracti128_si256(idn, 1);
        if (mask & 0x03) {
            store2(dr[0], zl);
            store2(ir[0], il);
        }
        if (mask & 0x0c) {
            store2(dr[1], _mm_unpackhi_epi64(zl, zl));
            store2(ir[1], _mm_unpackhi_epi64(il, il));
        }
        if (mask & 0x30) {
            store2(dr[2], zh);
            store2(ir[2], ih);
        }
        if (mask & 0xc0) {
            store2(dr[3], _mm_unpackhi_epi64(zh, zh));
            store2(ir[3], _mm_unpackhi_epi64(ih, ih));
        }
    }
    return (uint64_t)__builtin_popcount((unsigned)mask);
}

/* draw_tri_narrow made once for each width, so that the lane layout is
 * known to the compiler. */
ZV_AVX2_FN static uint64_t draw_tri_narrow2(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    return draw_tri_narrow(v, p, fb, ya, yb, 2);
}

ZV_AVX2_FN static uint64_t draw_tri_narrow4(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    return draw_tri_narrow(v, p, fb, ya, yb, 4);
}

/* The AVX2 path for triangle v: the narrowest layout its box fits (the
 * one-block cases inlined where the frame's loop calls it: most of a
 * dense mesh's triangles at any size, where a call's cost counts). */
ZV_AVX2_FN static inline __attribute__((always_inline)) uint64_t
draw_triangle_avx2(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    int bw = p->x1 - p->x0, bh = yb - ya;
    if (bw <= 2 && bh <= 4 && p->x0 + 2 <= fb->w)
        return draw_tri_block(v, p, fb, ya, yb, 2);
    if (bw <= 4 && bh <= 2 && p->x0 + 4 <= fb->w)
        return draw_tri_block(v, p, fb, ya, yb, 4);
    if (bw <= 2 && p->x0 + 2 <= fb->w)
        return draw_tri_narrow2(v, p, fb, ya, yb);
    if (bw <= 4 && p->x0 + 4 <= fb->w)
        return draw_tri_narrow4(v, p, fb, ya, yb);
    if (bw <= 8 && p->x0 + 8 <= fb->w)
        return draw_tri_col8(v, p, fb, ya, yb);
    return draw_tri_rows8(v, p, fb, ya, yb);
}

/* The same for callers outside the AVX2 code (draw_triangle). */
ZV_AVX2_FN static uint64_t draw_triangle_avx2_call(const ScreenVert *v, const ScreenPoly *p, FrameBufs *fb, int ya,
                                                   int yb)
{
    return draw_triangle_avx2(v, p, fb, ya, yb);
}

/* Do triangle v's corners lie within AVX2_SPAN pixels of each other? */
static inline int avx2_span(const ScreenVert *v)
{
    int32_t xlo = v[0].x < v[1].x ? v[0].x : v[1].x, xhi = v[0].x < v[1].x ? v[1].x : v[0].x;
    int32_t ylo = v[0].y < v[1].y ? v[0].y : v[1].y, yhi = v[0].y < v[1].y ? v[1].y : v[0].y;
    xlo = v[2].x < xlo ? v[2].x : xlo;
    xhi = v[2].x > xhi ? v[2].x : xhi;
    ylo = v[2].y < ylo ? v[2].y : ylo;
    yhi = v[2].y > yhi ? v[2].y : yhi;
    return xhi - xlo <= AVX2_SPAN * SUBPIX && yhi - ylo <= AVX2_SPAN * SUBPIX;
}

/* zb_render's loop at the AVX2 level: the small triangles' path called
 * from the loop itself, not through zbuffer_draw_poly and draw_triangle
 * (three calls a triangle were a tenth of the dragon's z-buffer at
 * 1920x1080); the rest as zbuffer_draw_poly draws them. */
ZV_AVX2_FN static uint64_t zb_polys_avx2(ZState *z, const ScreenPolys *sp, FrameBufs *fb, int y0, int y1,
                                         uint64_t *polys)
{
    uint64_t written = 0, np = 0;
    for (uint32_t i = 0; i < sp->npolys; i++) {
        const ScreenPoly *p = &sp->polys[i];
        if (p->y1 <= y0 || p->y0 >= y1)
            continue;
        np++;
        const ScreenVert *v = &sp->verts[p->first];
        if (p[1].first - p->first == 3 && avx2_span(v)) {
            int ya = p->y0 > y0 ? p->y0 : y0, yb = p->y1 < y1 ? p->y1 : y1;
            written += draw_triangle_avx2(v, p, fb, ya, yb);
        } else {
            written += zbuffer_draw_poly(z, sp, i, fb, y0, y1);
        }
    }
    *polys = np;
    return written;
}
#endif

/* A triangle: sorted by y, the long edge against the two short ones. */
static uint64_t draw_triangle(int simd, const ScreenPolys *sp, const ScreenPoly *p, FrameBufs *fb, int ya, int yb)
{
    const ScreenVert *v = &sp->verts[p->first];
#ifdef ZV_AVX2
    if (simd >= SIMD_AVX2 && avx2_span(v))
        return draw_triangle_avx2_call(v, p, fb, ya, yb);
#endif
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
                n += span_test(simd, p, fb, j, xa, xb);
            edge_step(&lg);
            edge_step(&sh);
        }
    }
    return n;
}

static uint64_t draw_polygon(ZState *z, int simd, const ScreenPolys *sp, uint32_t pi, FrameBufs *fb, int ya, int yb)
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
                n += span_test(simd, p, fb, j, xa, xb);
        }
    }
    return n;
}

uint64_t zbuffer_draw_poly(void *st, const ScreenPolys *sp, uint32_t pi, FrameBufs *fb, int y0, int y1)
{
    int simd = ((const ZState *)st)->simd;
    const ScreenPoly *p = &sp->polys[pi];
    int ya = p->y0 > y0 ? p->y0 : y0, yb = p->y1 < y1 ? p->y1 : y1;
    if (ya >= yb)
        return 0;
    if (screen_poly_nverts(sp, pi) == 3)
        return draw_triangle(simd, sp, p, fb, ya, yb);
    return draw_polygon(st, simd, sp, pi, fb, ya, yb);
}

static void zb_render(void *st, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    const ScreenPolys *sp = in->sp;
    zbuffer_begin(st, simd_use(in->simd));
    fbuf_clear_rows(fb, y0, y1);
    uint64_t written = 0, polys = 0;
#ifdef ZV_AVX2
    if (((ZState *)st)->simd >= SIMD_AVX2) {
        written = zb_polys_avx2(st, sp, fb, y0, y1, &polys);
        stats->polys_in += polys;
        stats->pixels_written += written;
        return;
    }
#endif
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
