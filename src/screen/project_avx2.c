/* project_avx2.c: the front end's loops eight lanes wide, compiled for
 * AVX2 (ZV_AVX2_FN) in a baseline build and run when the frame's level
 * is SIMD_AVX2: the vertex loop of pass 1, the screening of a chunk of
 * triangles eight at a time, the second screening of triangles whose box
 * holds at most four samples, and finish_tri() four triangles at a time
 * (skipping the sample test for those the second screening found
 * covering one). Each performs
 * the scalar code's operations (project.h, polys.c) in its order, so
 * the polygons, counts and map are the scalar ones bit for bit.
 *
 * The edge functions are those of J. Pineda, "A Parallel Algorithm for
 * Polygon Rasterization", SIGGRAPH 1988, with the top-left tie rule. */

#include "project.h"

#ifdef ZV_AVX2

/* The AVX2 loop: the same operations eight floats and four doubles wide;
 * floor by rounding (exact) instead of the truncation fix-up. Every
 * constant is broadcast once, before the loop: the vector stores may
 * alias anything, so the compiler would otherwise load them again on
 * every step. */
typedef struct {
    __m256  m[3][4];
    __m256d cx, cy, fx, fy, dbias, dscale, eye, n, dk, one, gx0, gx1, gy0, gy1, sub, half;
} Avx2Proj;

/* snap() without its clamp: a vertex inside the guard band is far inside
 * the clamp's range, and the others' lanes (NaN too: every compare
 * false) are replaced by VERT_OUT after, so their conversion, defined
 * for vectors whatever the value, is never seen. */
ZV_AVX2_FN static inline __m128i snap4_avx2(const Avx2Proj *c, __m256d v)
{
    __m256d t = _mm256_add_pd(_mm256_mul_pd(v, c->sub), c->half);
    return _mm256_cvttpd_epi32(_mm256_round_pd(t, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
}

/* proj_point(), in_guard() and snap() on four points, stored with store4. */
ZV_AVX2_FN static inline void proj4_avx2(const VertJob *j, const Avx2Proj *c, int persp, uint32_t at, __m128 hx,
                                         __m128 hy, __m128 hz)
{
    __m256d x = _mm256_cvtps_pd(hx), y = _mm256_cvtps_pd(hy), z = _mm256_cvtps_pd(hz);
    __m256d sx, sy, sz, ok;
    if (!persp) {
        sx = _mm256_add_pd(c->cx, _mm256_mul_pd(c->fx, x));
        sy = _mm256_sub_pd(c->cy, _mm256_mul_pd(c->fy, y));
        sz = _mm256_sub_pd(c->dbias, _mm256_mul_pd(c->dscale, z));
        ok = _mm256_and_pd(_mm256_cmp_pd(sx, c->gx0, _CMP_GE_OQ), _mm256_cmp_pd(sx, c->gx1, _CMP_LE_OQ));
    } else {
        __m256d ze = _mm256_sub_pd(c->eye, z);
        sx = _mm256_add_pd(c->cx, _mm256_div_pd(_mm256_mul_pd(c->fx, x), ze));
        sy = _mm256_sub_pd(c->cy, _mm256_div_pd(_mm256_mul_pd(c->fy, y), ze));
        sz = _mm256_mul_pd(c->dk, _mm256_sub_pd(c->one, _mm256_div_pd(c->n, ze)));
        ok = _mm256_and_pd(_mm256_cmp_pd(ze, c->n, _CMP_GE_OQ),
                           _mm256_and_pd(_mm256_cmp_pd(sx, c->gx0, _CMP_GE_OQ), _mm256_cmp_pd(sx, c->gx1, _CMP_LE_OQ)));
    }
    ok = _mm256_and_pd(ok, _mm256_and_pd(_mm256_cmp_pd(sy, c->gy0, _CMP_GE_OQ), _mm256_cmp_pd(sy, c->gy1, _CMP_LE_OQ)));
    /* the four 64-bit masks as four 32-bit ones */
    __m128i okm = _mm256_castsi256_si128(
        _mm256_permutevar8x32_epi32(_mm256_castpd_si256(ok), _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7)));
    const __m128i out = _mm_set1_epi32(VERT_OUT);
    __m128i ix = _mm_blendv_epi8(out, snap4_avx2(c, sx), okm);
    __m128i iy = _mm_blendv_epi8(out, snap4_avx2(c, sy), okm);
    store4(j, at, ix, iy, _mm256_cvtpd_ps(sz), okm);
}

ZV_AVX2_FN static inline void verts_avx2_loop(const VertJob *j, const Avx2Proj *c, int persp, uint32_t a, uint32_t b)
{
    for (uint32_t i = a; i < b; i += 8) {
        /* vertices 0-3 in the low lanes, 4-7 in the high ones: the
         * in-lane shuffles of load4_xyz (project_sse2.c) then work on
         * both at once */
        const float *p = j->pos + 3 * (size_t)i;
        __m256 va = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p)), _mm_loadu_ps(p + 12), 1);
        __m256 vb = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4)), _mm_loadu_ps(p + 16), 1);
        __m256 vc = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 8)), _mm_loadu_ps(p + 20), 1);
        __m256 t = _mm256_shuffle_ps(vb, vc, _MM_SHUFFLE(2, 1, 3, 2));
        __m256 u = _mm256_shuffle_ps(va, vb, _MM_SHUFFLE(1, 0, 2, 1));
        __m256 x = _mm256_shuffle_ps(va, t, _MM_SHUFFLE(2, 0, 3, 0));
        __m256 y = _mm256_shuffle_ps(u, t, _MM_SHUFFLE(3, 1, 2, 0));
        __m256 z = _mm256_shuffle_ps(u, vc, _MM_SHUFFLE(3, 0, 3, 1));
        __m256 q[3];
        for (int r = 0; r < 3; r++) {
            /* m4_point's row r: ((m0 x + m1 y) + m2 z) + m3 in float */
            __m256 s = _mm256_add_ps(_mm256_mul_ps(c->m[r][0], x), _mm256_mul_ps(c->m[r][1], y));
            s = _mm256_add_ps(s, _mm256_mul_ps(c->m[r][2], z));
            q[r] = _mm256_add_ps(s, c->m[r][3]);
        }
        proj4_avx2(j, c, persp, i, _mm256_castps256_ps128(q[0]), _mm256_castps256_ps128(q[1]),
                   _mm256_castps256_ps128(q[2]));
        proj4_avx2(j, c, persp, i + 4, _mm256_extractf128_ps(q[0], 1), _mm256_extractf128_ps(q[1], 1),
                   _mm256_extractf128_ps(q[2], 1));
    }
}

/* project.h */
ZV_AVX2_FN void project_verts_avx2(const VertJob *j, uint32_t a, uint32_t b)
{
    const Proj *pj = j->pj;
    Avx2Proj c;
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 4; k++)
            c.m[r][k] = _mm256_set1_ps(j->mv.m[r][k]);
    c.cx = _mm256_set1_pd(pj->cx);
    c.cy = _mm256_set1_pd(pj->cy);
    c.fx = _mm256_set1_pd(pj->fx);
    c.fy = _mm256_set1_pd(pj->fy);
    c.dbias = _mm256_set1_pd(pj->dbias);
    c.dscale = _mm256_set1_pd(pj->dscale);
    c.eye = _mm256_set1_pd(pj->eye);
    c.n = _mm256_set1_pd(pj->n);
    c.dk = _mm256_set1_pd(pj->dk);
    c.one = _mm256_set1_pd(1.0);
    c.gx0 = _mm256_set1_pd(pj->gx0);
    c.gx1 = _mm256_set1_pd(pj->gx1);
    c.gy0 = _mm256_set1_pd(pj->gy0);
    c.gy1 = _mm256_set1_pd(pj->gy1);
    c.sub = _mm256_set1_pd((double)SUBPIX);
    c.half = _mm256_set1_pd(0.5);
    /* whole groups of eight, stopping short of b (store4's spill) */
    uint32_t e = b - a > 8 ? a + (b - a - 1) / 8 * 8 : a;
    if (pj->persp)
        verts_avx2_loop(j, &c, 1, a, e);
    else
        verts_avx2_loop(j, &c, 0, a, e);
    for (uint32_t i = e; i < b; i++)
        vert_one(j, i);
}

/* Bytes ahead of the screening's corner reads to fetch (6 KB: a few
 * dozen steps of the loop). */
#define CORNER_AHEAD 6144

/* Corner k (0, 1, 2) of eight consecutive triangles (corners c[0 ..]):
 * its sample indices idx[corner - vmin]. */
ZV_AVX2_FN static inline __m256i corner8(const uint32_t *idx, uint32_t vmin, const uint32_t *c, int k)
{
#define ZV_IDX(q) (int)idx[c[(q) + k] - vmin]
    return _mm256_setr_epi32(ZV_IDX(0), ZV_IDX(3), ZV_IDX(6), ZV_IDX(9), ZV_IDX(12), ZV_IDX(15), ZV_IDX(18),
                             ZV_IDX(21));
#undef ZV_IDX
}

/* Eight triangles a step: each corner's sample indices fetched by plain
 * loads (on the AMD cores measured, 24 loads and inserts beat three
 * gathers by ~15%), and tri_keeps() on the x and y halves side by side
 * (16-bit lanes). */
ZV_AVX2_FN uint32_t project_screen_tris_avx2(const uint32_t *corner, uint32_t n, const uint32_t *idx, uint32_t vmin,
                                             int32_t w, int32_t h, uint32_t *keep, const KeepLut *lut)
{
    const __m256i zero = _mm256_setzero_si256();
    const __m256i ones = _mm256_set1_epi32(-1), out = _mm256_set1_epi32((int32_t)0x80008000u);
    const __m256i lim = _mm256_set1_epi32((int32_t)((uint32_t)h << 16 | (uint32_t)w));
    uint32_t nk = 0, i = 0;
    for (; i + 8 <= n; i += 8) {
        const uint32_t *c = corner + 3 * (size_t)i;
        /* the corners stream in faster fetched well ahead by hand (the
         * hardware's prefetch fell behind: 1.5 -> 0.85 ms a frame on the
         * dragon at 160x96); no dereference, so past the end is harmless */
        __builtin_prefetch((const void *)((uintptr_t)c + CORNER_AHEAD));
        __builtin_prefetch((const void *)((uintptr_t)c + CORNER_AHEAD + 64));
        __m256i g0 = corner8(idx, vmin, c, 0), g1 = corner8(idx, vmin, c, 1), g2 = corner8(idx, vmin, c, 2);
        __m256i mn = _mm256_min_epi16(_mm256_min_epi16(g0, g1), g2);
        __m256i mx = _mm256_max_epi16(_mm256_max_epi16(g0, g1), g2);
        __m256i ok = _mm256_and_si256(_mm256_cmpgt_epi16(mx, mn),
                                      _mm256_and_si256(_mm256_cmpgt_epi16(mx, zero), _mm256_cmpgt_epi16(lim, mn)));
        ok = _mm256_or_si256(_mm256_cmpeq_epi32(ok, ones), _mm256_cmpeq_epi32(mn, out));
        unsigned m = (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(ok));
        /* append the kept ones without a branch (most steps keep none at
         * small sizes, most of them at large ones): their lane numbers
         * packed to the front by a table, all eight stored, the count
         * advanced by the kept ones */
        __m256i lanes = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128((long long)lut->lanes[m]));
        _mm256_storeu_si256((__m256i *)(keep + nk), _mm256_add_epi32(_mm256_set1_epi32((int32_t)i), lanes));
        nk += lut->count[m];
    }
    return project_screen_tris(corner, i, n, idx, vmin, w, h, keep, nk);
}

/* The snapped corners of the eight triangles t[0..8) (corners at
 * corner[3 t ..], points sv[corner - vmin]): x[k], y[k] of corner k.
 * Plain loads, a point's x and y in one: faster than gathers here, and
 * the points are scattered (each load likely a miss). */
ZV_AVX2_FN static inline void corners8_xy(const uint32_t *corner, const ScreenVert *sv, uint32_t vmin,
                                          const uint32_t *t, __m256i x[3], __m256i y[3])
{
    for (int k = 0; k < 3; k++) {
        __m128i p[8];
        for (int l = 0; l < 8; l++)
            p[l] = _mm_loadl_epi64((const __m128i *)&sv[corner[3 * (size_t)t[l] + k] - vmin]);
        /* (x, y) pairs of lanes 0-3 | 4-7 -> x of all eight, y of all eight */
        __m256i lo = _mm256_set_m128i(_mm_unpacklo_epi64(p[4], p[5]), _mm_unpacklo_epi64(p[0], p[1]));
        __m256i hi = _mm256_set_m128i(_mm_unpacklo_epi64(p[6], p[7]), _mm_unpacklo_epi64(p[2], p[3]));
        /* lo: x0 y0 x1 y1 | x4 y4 x5 y5, hi: x2 y2 x3 y3 | x6 y6 x7 y7 */
        __m256 fl = _mm256_castsi256_ps(lo), fh = _mm256_castsi256_ps(hi);
        x[k] = _mm256_castps_si256(_mm256_shuffle_ps(fl, fh, _MM_SHUFFLE(2, 0, 2, 0)));
        y[k] = _mm256_castps_si256(_mm256_shuffle_ps(fl, fh, _MM_SHUFFLE(3, 1, 3, 1)));
    }
}

/* The three edges of eight triangles (corners relative to the sample
 * (px, py) of their box's first column and row, b and c swapped where
 * the triangle is wound the other way) against the box's samples at
 * most four (bw x bh, lanes where small): edge_covers() on each. An
 * edge's function at the sample c columns right and r rows down is
 * e + 256 (r dx - c dy), and the top-left rule is folded in as e + 1 > 0
 * (integers), so every sample is a few adds and compares. Exact: small
 * boxes keep every corner within 2^11 of the sample, so every product
 * fits 32 bits. The mask of the lanes that cover one of the samples. */
ZV_AVX2_FN static inline __m256i hits8_small(const __m256i ex[3], const __m256i ey[3], __m256i bw, __m256i bh)
{
    const __m256i zero = _mm256_setzero_si256();
    __m256i e[3], DX[3], DY[3];
    for (int k = 0; k < 3; k++) {
        int m = k == 2 ? 0 : k + 1;
        __m256i dx = _mm256_sub_epi32(ex[m], ex[k]), dy = _mm256_sub_epi32(ey[m], ey[k]);
        __m256i tl = _mm256_or_si256(_mm256_cmpgt_epi32(zero, dy),
                                     _mm256_and_si256(_mm256_cmpeq_epi32(dy, zero), _mm256_cmpgt_epi32(dx, zero)));
        /* dx (0 - ay) - dy (0 - ax), plus one on a top or left edge */
        e[k] = _mm256_sub_epi32(_mm256_sub_epi32(_mm256_mullo_epi32(dy, ex[k]), _mm256_mullo_epi32(dx, ey[k])), tl);
        DX[k] = _mm256_slli_epi32(dx, SUBPIX_BITS);
        DY[k] = _mm256_slli_epi32(dy, SUBPIX_BITS);
    }
    /* the eight places a sample of a box of at most four can be, (c, r):
     * (0..3, 0), (0, 1..3) and (1, 1), each edge's function stepped there */
    __m256i at[8][3];
    for (int k = 0; k < 3; k++) {
        at[0][k] = e[k];
        at[1][k] = _mm256_sub_epi32(at[0][k], DY[k]);
        at[2][k] = _mm256_sub_epi32(at[1][k], DY[k]);
        at[3][k] = _mm256_sub_epi32(at[2][k], DY[k]);
        at[4][k] = _mm256_add_epi32(at[0][k], DX[k]);
        at[5][k] = _mm256_add_epi32(at[4][k], DX[k]);
        at[6][k] = _mm256_add_epi32(at[5][k], DX[k]);
        at[7][k] = _mm256_add_epi32(at[1][k], DX[k]);
    }
    const __m256i c1 = _mm256_set1_epi32(1), c2 = _mm256_set1_epi32(2), c3 = _mm256_set1_epi32(3);
    const __m256i wide[4] = { _mm256_cmpeq_epi32(zero, zero), _mm256_cmpgt_epi32(bw, c1), _mm256_cmpgt_epi32(bw, c2),
                              _mm256_cmpgt_epi32(bw, c3) };
    const __m256i tall[4] = { wide[0], _mm256_cmpgt_epi32(bh, c1), _mm256_cmpgt_epi32(bh, c2),
                              _mm256_cmpgt_epi32(bh, c3) };
    const __m256i valid[8] = { wide[0], wide[1], wide[2], wide[3], tall[1], tall[2], tall[3],
                               _mm256_and_si256(wide[1], tall[1]) };
    __m256i hit = zero;
    for (int q = 0; q < 8; q++) {
        __m256i in = _mm256_and_si256(_mm256_cmpgt_epi32(at[q][0], zero), _mm256_cmpgt_epi32(at[q][1], zero));
        in = _mm256_and_si256(in, _mm256_cmpgt_epi32(at[q][2], zero));
        hit = _mm256_or_si256(hit, _mm256_and_si256(in, valid[q]));
    }
    return hit;
}

/* Second screening of the kept triangles keep[0 .. nk) (corners at
 * corner[3 keep[i] ..], points sv[corner - vmin]), eight at a time: a
 * triangle with no corner to clip whose sample box lies on the screen
 * and holds at most four samples is decided here as finish_tri()
 * decides it (corners relative to the box's first sample fit 32-bit
 * lanes exactly): back-facing when culling (culled_back), else missing
 * every sample (culled_empty) drops it, else it is kept and marked
 * KEEP_HIT (finish need not look at its samples again). The others stay
 * for finish_tri. Returns the new count; keep[] is compacted in place
 * (a store never passes the entries still to be read). */
ZV_AVX2_FN uint32_t project_sift_small_avx2(const uint32_t *corner, const ScreenVert *sv, uint32_t vmin, int32_t w,
                                            int32_t h, int cull, uint32_t *keep, uint32_t nk, const KeepLut *lut,
                                            uint32_t *empty, uint32_t *back)
{
    const __m256i one = _mm256_set1_epi32(1), five = _mm256_set1_epi32(5);
    const __m256i k127 = _mm256_set1_epi32(127), k128 = _mm256_set1_epi32(128);
    const __m256i out = _mm256_set1_epi32(VERT_OUT), zero = _mm256_setzero_si256();
    const __m256i vw = _mm256_set1_epi32(w + 1), vh = _mm256_set1_epi32(h + 1);
    const __m256i vcull = _mm256_set1_epi32(cull ? -1 : 0), flag = _mm256_set1_epi32((int32_t)KEEP_HIT);
    uint32_t n = 0, i = 0;
    for (; i + 8 <= nk; i += 8) {
        __m256i t = _mm256_loadu_si256((const __m256i *)(keep + i));
        __m256i x[3], y[3];
        corners8_xy(corner, sv, vmin, keep + i, x, y);
        __m256i xmn = _mm256_min_epi32(_mm256_min_epi32(x[0], x[1]), x[2]);
        __m256i xmx = _mm256_max_epi32(_mm256_max_epi32(x[0], x[1]), x[2]);
        __m256i ymn = _mm256_min_epi32(_mm256_min_epi32(y[0], y[1]), y[2]);
        __m256i ymx = _mm256_max_epi32(_mm256_max_epi32(y[0], y[1]), y[2]);
        __m256i sx0 = _mm256_srai_epi32(_mm256_add_epi32(xmn, k127), SUBPIX_BITS);
        __m256i sy0 = _mm256_srai_epi32(_mm256_add_epi32(ymn, k127), SUBPIX_BITS);
        __m256i sx1 = _mm256_srai_epi32(_mm256_add_epi32(xmx, k127), SUBPIX_BITS);
        __m256i sy1 = _mm256_srai_epi32(_mm256_add_epi32(ymx, k127), SUBPIX_BITS);
        __m256i bw = _mm256_sub_epi32(sx1, sx0), bh = _mm256_sub_epi32(sy1, sy0);
        /* no corner to clip (then every sample index is small), the box
         * on the screen (clamping leaves it as it is: 0 <= sx0, sx1 <= w)
         * and of one to four samples (the first screening made it not
         * empty) */
        __m256i on = _mm256_and_si256(_mm256_and_si256(_mm256_cmpgt_epi32(sx0, _mm256_set1_epi32(-1)),
                                                       _mm256_cmpgt_epi32(sy0, _mm256_set1_epi32(-1))),
                                      _mm256_and_si256(_mm256_cmpgt_epi32(vw, sx1), _mm256_cmpgt_epi32(vh, sy1)));
        __m256i small = _mm256_and_si256(on, _mm256_cmpgt_epi32(five, _mm256_mullo_epi32(bw, bh)));
        small = _mm256_and_si256(small, _mm256_and_si256(_mm256_cmpgt_epi32(five, bw), _mm256_cmpgt_epi32(five, bh)));
        small = _mm256_andnot_si256(_mm256_cmpeq_epi32(xmn, out), small);
        __m256i px = _mm256_add_epi32(_mm256_slli_epi32(sx0, SUBPIX_BITS), k128);
        __m256i py = _mm256_add_epi32(_mm256_slli_epi32(sy0, SUBPIX_BITS), k128);
        __m256i ax = _mm256_sub_epi32(x[0], px), ay = _mm256_sub_epi32(y[0], py);
        __m256i bx = _mm256_sub_epi32(x[1], px), by = _mm256_sub_epi32(y[1], py);
        __m256i cx = _mm256_sub_epi32(x[2], px), cy = _mm256_sub_epi32(y[2], py);
        /* twice the signed area (finish_tri's area2; translation moves it not) */
        __m256i area2 = _mm256_sub_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(bx, ax), _mm256_sub_epi32(cy, ay)),
                                         _mm256_mullo_epi32(_mm256_sub_epi32(by, ay), _mm256_sub_epi32(cx, ax)));
        __m256i faces_away = _mm256_and_si256(vcull, _mm256_cmpgt_epi32(_mm256_add_epi32(area2, one), zero));
        __m256i neg = _mm256_cmpgt_epi32(zero, area2);      /* walk b and c the other way round */
        __m256i ex[3] = { ax, _mm256_blendv_epi8(bx, cx, neg), _mm256_blendv_epi8(cx, bx, neg) };
        __m256i ey[3] = { ay, _mm256_blendv_epi8(by, cy, neg), _mm256_blendv_epi8(cy, by, neg) };
        __m256i hit = _mm256_andnot_si256(_mm256_cmpeq_epi32(area2, zero), hits8_small(ex, ey, bw, bh));
        __m256i gone_back = _mm256_and_si256(small, faces_away);
        __m256i decided = _mm256_andnot_si256(faces_away, small);
        __m256i gone_empty = _mm256_andnot_si256(hit, decided);
        t = _mm256_or_si256(t, _mm256_and_si256(flag, _mm256_and_si256(hit, decided)));
        unsigned mb = (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(gone_back));
        unsigned me = (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(gone_empty));
        unsigned m = ~(mb | me) & 0xff;
        *back += lut->count[mb];
        *empty += lut->count[me];
        __m256i lanes = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128((long long)lut->lanes[m]));
        _mm256_storeu_si256((__m256i *)(keep + n), _mm256_permutevar8x32_epi32(t, lanes));
        n += lut->count[m];
    }
    for (; i < nk; i++)
        keep[n++] = keep[i];
    return n;
}

/* Four triangles' finish_tri(), lane by lane the same operations: the
 * sample box in 32-bit lanes, twice the signed area and, for a box of at
 * most four samples, tri_hits_box()'s edge functions in 64-bit ones
 * (exact products), the plane in double. A lane's state: kept (its box,
 * plane and zmin filled in), or dropped as empty or as facing away. */
enum { FIN_KEPT, FIN_EMPTY, FIN_BACK };

/* edge_covers() in four 64-bit lanes: e = dx (py - ay) - dy (px - ax) > 0,
 * or == 0 on a top or left edge (tl). Every factor fits 32 bits. */
ZV_AVX2_FN static inline __m256i edge4_covers(__m256i ax, __m256i ay, __m256i dx, __m256i dy, __m256i tl, __m256i px,
                                              __m256i py)
{
    __m256i e = _mm256_sub_epi64(_mm256_mul_epi32(dx, _mm256_sub_epi64(py, ay)),
                                 _mm256_mul_epi32(dy, _mm256_sub_epi64(px, ax)));
    const __m256i zero = _mm256_setzero_si256();
    return _mm256_or_si256(_mm256_cmpgt_epi64(e, zero), _mm256_and_si256(_mm256_cmpeq_epi64(e, zero), tl));
}

typedef struct {
    int32_t x0[4], x1[4], y0[4], y1[4];
    float   a[4], b[4], zc[4], zmin[4];
    int     state[4];
} Finish4;

/* The pieces of finish_tris4, inlined into it. */
#define FIN_INLINE ZV_AVX2_FN static inline __attribute__((always_inline))

/* sample_box() of four triangles: box[0..3] = x0, x1, y0, y1, clamped to
 * the screen. */
FIN_INLINE void tris4_box(const ScreenPolys *sp, const __m128i X[3], const __m128i Y[3], __m128i box[4])
{
    const __m128i k127 = _mm_set1_epi32(127), zero = _mm_setzero_si128();
    __m128i x0 = _mm_srai_epi32(_mm_add_epi32(_mm_min_epi32(_mm_min_epi32(X[0], X[1]), X[2]), k127), SUBPIX_BITS);
    __m128i x1 = _mm_srai_epi32(_mm_add_epi32(_mm_max_epi32(_mm_max_epi32(X[0], X[1]), X[2]), k127), SUBPIX_BITS);
    __m128i y0 = _mm_srai_epi32(_mm_add_epi32(_mm_min_epi32(_mm_min_epi32(Y[0], Y[1]), Y[2]), k127), SUBPIX_BITS);
    __m128i y1 = _mm_srai_epi32(_mm_add_epi32(_mm_max_epi32(_mm_max_epi32(Y[0], Y[1]), Y[2]), k127), SUBPIX_BITS);
    box[0] = _mm_max_epi32(x0, zero);
    box[1] = _mm_min_epi32(x1, _mm_set1_epi32(sp->w));
    box[2] = _mm_max_epi32(y0, zero);
    box[3] = _mm_min_epi32(y1, _mm_set1_epi32(sp->h));
}

/* Twice the signed area, (x0 y1 - x1 y0) + (x1 y2 - x2 y1) + (x2 y0 - x0 y2),
 * in 64-bit lanes (xl, yl: the corners widened). */
FIN_INLINE __m256i tris4_area2(const __m256i xl[3], const __m256i yl[3])
{
    __m256i area2 = _mm256_setzero_si256();
    for (int k = 0; k < 3; k++) {
        int m = k == 2 ? 0 : k + 1;
        area2 = _mm256_add_epi64(area2,
                                 _mm256_sub_epi64(_mm256_mul_epi32(xl[k], yl[m]), _mm256_mul_epi32(xl[m], yl[k])));
    }
    return area2;
}

/* tri_hits_box() of the four: b and c swapped where the area is
 * negative, then the box's samples (nsamp, at most four where it
 * matters) against the three edges. The mask of the lanes that cover
 * one of them. */
FIN_INLINE int tris4_hits(const __m256i xl[3], const __m256i yl[3], __m256i area2, __m128i x0, __m128i y0,
                          __m128i bw, __m128i nsamp)
{
    const __m256i zero4 = _mm256_setzero_si256();
    __m256i neg = _mm256_cmpgt_epi64(zero4, area2);
    __m256i ex[3] = { xl[0], _mm256_blendv_epi8(xl[1], xl[2], neg), _mm256_blendv_epi8(xl[2], xl[1], neg) };
    __m256i ey[3] = { yl[0], _mm256_blendv_epi8(yl[1], yl[2], neg), _mm256_blendv_epi8(yl[2], yl[1], neg) };
    __m256i dx[3], dy[3], tl[3];
    for (int k = 0; k < 3; k++) {
        int m = k == 2 ? 0 : k + 1;
        dx[k] = _mm256_sub_epi64(ex[m], ex[k]);
        dy[k] = _mm256_sub_epi64(ey[m], ey[k]);
        tl[k] = _mm256_or_si256(_mm256_cmpgt_epi64(zero4, dy[k]),
                                _mm256_and_si256(_mm256_cmpeq_epi64(dy[k], zero4), _mm256_cmpgt_epi64(dx[k], zero4)));
    }
    __m256i hit = zero4;
    for (int smp = 0; smp < 4; smp++) {
        /* sample smp of each lane's box, row by row: row = how many
         * whole box widths fit in smp, col = what is left */
        __m128i vs = _mm_set1_epi32(smp), bw1 = _mm_max_epi32(bw, _mm_set1_epi32(1));
        __m128i row = _mm_setzero_si128(), lim = bw1;
        for (int r = 1; r < 4; r++) {
            row = _mm_sub_epi32(row, _mm_cmpgt_epi32(_mm_add_epi32(vs, _mm_set1_epi32(1)), lim));
            lim = _mm_add_epi32(lim, bw1);
        }
        __m128i col = _mm_sub_epi32(vs, _mm_mullo_epi32(row, bw1));
        __m128i ok32 = _mm_cmpgt_epi32(nsamp, vs);
        __m128i px32 = _mm_add_epi32(_mm_slli_epi32(_mm_add_epi32(x0, col), SUBPIX_BITS), _mm_set1_epi32(128));
        __m128i py32 = _mm_add_epi32(_mm_slli_epi32(_mm_add_epi32(y0, row), SUBPIX_BITS), _mm_set1_epi32(128));
        __m256i vx = _mm256_cvtepi32_epi64(px32), vy = _mm256_cvtepi32_epi64(py32);
        __m256i in = _mm256_cvtepi32_epi64(ok32);
        for (int k = 0; k < 3; k++)
            in = _mm256_and_si256(in, edge4_covers(ex[k], ey[k], dx[k], dy[k], tl[k], vx, vy));
        hit = _mm256_or_si256(hit, in);
    }
    hit = _mm256_andnot_si256(_mm256_cmpeq_epi64(area2, zero4), hit);
    return _mm256_movemask_pd(_mm256_castsi256_pd(hit));
}

/* store_poly()'s plane and zmin of the four, in double, into f (bw, bh:
 * the boxes' width and height); the mask of the lanes with no area
 * (nz == 0). */
FIN_INLINE int tris4_plane(const __m128i X[3], const __m128i Y[3], const __m128 Z[3], const __m128i box[4],
                           __m128i bw, __m128i bh, Finish4 *f)
{
    const __m256d inv = _mm256_set1_pd(1.0 / SUBPIX);
    __m256d Xd[3], Yd[3], Zd[3];
    for (int k = 0; k < 3; k++) {
        Xd[k] = _mm256_mul_pd(_mm256_cvtepi32_pd(X[k]), inv);
        Yd[k] = _mm256_mul_pd(_mm256_cvtepi32_pd(Y[k]), inv);
        Zd[k] = _mm256_cvtps_pd(Z[k]);
    }
    __m256d x1d = _mm256_sub_pd(Xd[1], Xd[0]), y1d = _mm256_sub_pd(Yd[1], Yd[0]), z1d = _mm256_sub_pd(Zd[1], Zd[0]);
    __m256d x2d = _mm256_sub_pd(Xd[2], Xd[0]), y2d = _mm256_sub_pd(Yd[2], Yd[0]), z2d = _mm256_sub_pd(Zd[2], Zd[0]);
    __m256d nx = _mm256_sub_pd(_mm256_mul_pd(y1d, z2d), _mm256_mul_pd(z1d, y2d));
    __m256d ny = _mm256_sub_pd(_mm256_mul_pd(z1d, x2d), _mm256_mul_pd(x1d, z2d));
    __m256d nz = _mm256_sub_pd(_mm256_mul_pd(x1d, y2d), _mm256_mul_pd(y1d, x2d));
    __m256d flat = _mm256_cmp_pd(nz, _mm256_setzero_pd(), _CMP_EQ_OQ);
    const __m256d sign = _mm256_set1_pd(-0.0), half = _mm256_set1_pd(0.5);
    __m256d a = _mm256_div_pd(_mm256_xor_pd(nx, sign), nz), b = _mm256_div_pd(_mm256_xor_pd(ny, sign), nz);
    __m256d zc = _mm256_add_pd(
        _mm256_add_pd(Zd[0], _mm256_mul_pd(a, _mm256_sub_pd(_mm256_add_pd(_mm256_cvtepi32_pd(box[0]), half), Xd[0]))),
        _mm256_mul_pd(b, _mm256_sub_pd(_mm256_add_pd(_mm256_cvtepi32_pd(box[2]), half), Yd[0])));
    __m256d mag = _mm256_add_pd(_mm256_add_pd(_mm256_andnot_pd(sign, zc),
                                              _mm256_mul_pd(_mm256_andnot_pd(sign, a), _mm256_cvtepi32_pd(bw))),
                                _mm256_mul_pd(_mm256_andnot_pd(sign, b), _mm256_cvtepi32_pd(bh)));
    __m256d lo = _mm256_min_pd(Zd[2], _mm256_min_pd(Zd[0], Zd[1]));     /* min_pd(p, q) is p < q ? p : q */
    __m256d zmin = _mm256_sub_pd(lo, _mm256_mul_pd(_mm256_add_pd(_mm256_andnot_pd(sign, lo), mag),
                                                   _mm256_set1_pd(1.0 / (1 << 20))));
    _mm_storeu_ps(f->a, _mm256_cvtpd_ps(a));
    _mm_storeu_ps(f->b, _mm256_cvtpd_ps(b));
    _mm_storeu_ps(f->zc, _mm256_cvtpd_ps(zc));
    _mm_storeu_ps(f->zmin, _mm256_cvtpd_ps(zmin));
    return _mm256_movemask_pd(flat);
}

ZV_AVX2_FN static void finish_tris4(const ScreenPolys *sp, const ScreenVert *v[4][3], int known, Finish4 *f)
{
    __m128i X[3], Y[3];
    __m128 Z[3];
    for (int k = 0; k < 3; k++) {
        X[k] = _mm_setr_epi32(v[0][k]->x, v[1][k]->x, v[2][k]->x, v[3][k]->x);
        Y[k] = _mm_setr_epi32(v[0][k]->y, v[1][k]->y, v[2][k]->y, v[3][k]->y);
        Z[k] = _mm_setr_ps(v[0][k]->z, v[1][k]->z, v[2][k]->z, v[3][k]->z);
    }
    __m128i box[4];
    tris4_box(sp, X, Y, box);
    __m128i bw = _mm_sub_epi32(box[1], box[0]), bh = _mm_sub_epi32(box[3], box[2]);
    __m128i empty = _mm_or_si128(_mm_cmpgt_epi32(_mm_set1_epi32(1), bw), _mm_cmpgt_epi32(_mm_set1_epi32(1), bh));
    __m256i xl[3], yl[3];
    for (int k = 0; k < 3; k++) {
        xl[k] = _mm256_cvtepi32_epi64(X[k]);
        yl[k] = _mm256_cvtepi32_epi64(Y[k]);
    }
    __m256i area2 = tris4_area2(xl, yl);
    __m256i back = _mm256_cmpgt_epi64(area2, _mm256_set1_epi64x(-1));     /* area2 >= 0 */
    __m128i nsamp = _mm_mullo_epi32(bw, bh);
    /* the lanes the second screening found covering a sample need no look */
    int mt = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(_mm_set1_epi32(5), nsamp))) & ~known;
    int hits = mt ? tris4_hits(xl, yl, area2, box[0], box[2], bw, nsamp) : 0;
    int mf = tris4_plane(X, Y, Z, box, bw, bh, f);
    _mm_storeu_si128((__m128i *)f->x0, box[0]);
    _mm_storeu_si128((__m128i *)f->x1, box[1]);
    _mm_storeu_si128((__m128i *)f->y0, box[2]);
    _mm_storeu_si128((__m128i *)f->y1, box[3]);
    int me = _mm_movemask_ps(_mm_castsi128_ps(empty)), mb = _mm256_movemask_pd(_mm256_castsi256_pd(back));
    for (int l = 0; l < 4; l++)
        f->state[l] = me >> l & 1 ? FIN_EMPTY
                    : sp->cull && (mb >> l & 1) ? FIN_BACK
                    : (mt >> l & 1) && !(hits >> l & 1) ? FIN_EMPTY
                    : mf >> l & 1 ? FIN_EMPTY : FIN_KEPT;
}

/* The kept triangles keep[0 .. nk) of a chunk of triangles (polygon k +
 * keep[i], corners c0 + 3 keep[i], instance inst + keep[i]), four at a
 * time through finish_tris4, in order; those with a corner to clip go
 * through project_emit_poly. */
ZV_AVX2_FN int project_emit_tris_avx2(RangeJob *j, uint32_t k, uint32_t c0, uint32_t inst, const uint32_t *keep,
                                      uint32_t nk)
{
    ScreenPolys *sp = j->out;
    const ScreenVert *sv = j->vs->sv;
    const uint32_t *corner = j->s->poly_corner, vmin = j->o->vert_min;
    uint32_t i = 0;
    for (; i + 4 <= nk; i += 4) {
        int rv = vert_room(j, sp->nverts + 4 * 11);
        if (rv)
            return rv;
        const ScreenVert *v[4][3];
        int out[4], known = 0;
        for (int l = 0; l < 4; l++) {
            known |= (keep[i + l] >> 31) << l;     /* KEEP_HIT */
            const uint32_t *c = corner + c0 + 3 * (keep[i + l] & ~KEEP_HIT);
            v[l][0] = &sv[c[0] - vmin];
            v[l][1] = &sv[c[1] - vmin];
            v[l][2] = &sv[c[2] - vmin];
            out[l] = (v[l][0]->x == VERT_OUT) | (v[l][1]->x == VERT_OUT) | (v[l][2]->x == VERT_OUT);
        }
        Finish4 f;
        finish_tris4(sp, v, known, &f);
        for (int l = 0; l < 4; l++) {
            uint32_t q = keep[i + l] & ~KEEP_HIT;
            if (out[l]) {
                rv = project_emit_poly(j, k + q, c0 + 3 * q, c0 + 3 * q + 3, inst + q);
                if (rv)
                    return rv;
                continue;
            }
            if (f.state[l] == FIN_EMPTY) {
                sp->culled_empty++;
                continue;
            }
            if (f.state[l] == FIN_BACK) {
                sp->culled_back++;
                continue;
            }
            ScreenVert *dst = &sp->verts[sp->nverts];
            dst[0] = *v[l][0];
            dst[1] = *v[l][1];
            dst[2] = *v[l][2];
            ScreenPoly *p = &sp->polys[sp->npolys++];
            p->first = sp->nverts;
            sp->nverts += 3;
            p->x0 = f.x0[l];
            p->x1 = f.x1[l];
            p->y0 = f.y0[l];
            p->y1 = f.y1[l];
            p->a = f.a[l];
            p->b = f.b[l];
            p->zc = f.zc[l];
            p->zmin = f.zmin[l];
            kept_poly(j, k + q, inst + q);
        }
    }
    for (; i < nk; i++) {
        uint32_t q = keep[i] & ~KEEP_HIT;
        int rv = project_emit_poly(j, k + q, c0 + 3 * q, c0 + 3 * q + 3, inst + q);
        if (rv)
            return rv;
    }
    return 0;
}

#endif
