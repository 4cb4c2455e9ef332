/* samplerow.c: texture_lookup for a run of samples that share their
 * levels (the samples of a face seen flat on), several at a time. The
 * coordinates' wrapping, the texel indices and the bilinear weights are
 * computed across samples, one sample a lane (4 lanes with SSE2, 8 with
 * AVX2); each sample's texels are then fetched and summed with its
 * channels in lanes, as texture_lookup does. Every lane performs
 * texture_lookup's IEEE operations in its order, so the results are its
 * bits (tests/test_texture.c compares them sample by sample). A group
 * holding a coordinate texture_lookup tames (past 1e6, infinite, NaN)
 * goes through texture_lookup itself, as does mirroring. */

#include "simd.h"
#include "texture.h"

/* One group's indices and weights: per level and lane, the texels'
 * columns a, b and rows a, b; per level, corner (a a, b a, a b, b b:
 * quad_at's order) and lane, the weight. */
#define ROW_MAX 8
typedef struct {
    int32_t xa[2][ROW_MAX], xb[2][ROW_MAX], ya[2][ROW_MAX], yb[2][ROW_MAX];
    float   w[2][4][ROW_MAX];
} RowPrep;

#ifdef ZV_SSE2
/* floor(x) of tame lanes as integers: truncated, less one where that
 * rounded up (x negative and not whole). */
static inline __m128i floor4(__m128 x)
{
    __m128i i = _mm_cvttps_epi32(x);
    return _mm_add_epi32(i, _mm_castps_si128(_mm_cmpgt_ps(_mm_cvtepi32_ps(i), x)));
}

/* The lanes' coordinate c wrapped as wrap_coord does (c tame). */
static inline __m128 wrap4(__m128 c, int repeat)
{
    if (!repeat)
        return _mm_min_ps(_mm_max_ps(c, _mm_set1_ps(-1.0f)), _mm_set1_ps(2.0f));
    return _mm_sub_ps(c, _mm_cvtepi32_ps(floor4(c)));
}

/* texel_pair_w on lanes: the indices into a, b; returns the fraction. */
static inline __m128 axis4(__m128 c, int n, int repeat, int32_t *a, int32_t *b)
{
    __m128 x = _mm_sub_ps(_mm_mul_ps(c, _mm_set1_ps((float)n)), _mm_set1_ps(0.5f));
    __m128i i = floor4(x);
    __m128 f = _mm_sub_ps(x, _mm_cvtepi32_ps(i));
    __m128i vn = _mm_set1_epi32(n), last = _mm_set1_epi32(n - 1), zero = _mm_setzero_si128();
    __m128i i1 = _mm_add_epi32(i, _mm_set1_epi32(1)), ia, ib;
    if (repeat) {
        ia = _mm_add_epi32(i, _mm_and_si128(_mm_cmplt_epi32(i, zero), vn));
        ib = _mm_sub_epi32(i1, _mm_and_si128(_mm_cmpgt_epi32(i1, last), vn));
    } else {
        /* clamp to [0, n - 1]: max with 0, then min with the last */
        __m128i lo = _mm_cmplt_epi32(i, zero), hi;
        ia = _mm_andnot_si128(lo, i);
        hi = _mm_cmpgt_epi32(ia, last);
        ia = _mm_or_si128(_mm_and_si128(hi, last), _mm_andnot_si128(hi, ia));
        lo = _mm_cmplt_epi32(i1, zero);
        ib = _mm_andnot_si128(lo, i1);
        hi = _mm_cmpgt_epi32(ib, last);
        ib = _mm_or_si128(_mm_and_si128(hi, last), _mm_andnot_si128(hi, ib));
    }
    _mm_storeu_si128((__m128i *)(void *)a, ia);
    _mm_storeu_si128((__m128i *)(void *)b, ib);
    return f;
}

/* A group of 4 into p: 0, or -1 when a coordinate is not tame (the
 * group then goes through texture_lookup). */
static inline int prep4(const TexLod *l, const float *u, const float *v, RowPrep *p)
{
    __m128 cu = _mm_loadu_ps(u), cv = _mm_loadu_ps(v), big = _mm_set1_ps(1e6f), abs = _mm_set1_ps(-0.0f);
    __m128 ok = _mm_and_ps(_mm_cmple_ps(_mm_andnot_ps(abs, cu), big), _mm_cmple_ps(_mm_andnot_ps(abs, cv), big));
    if (_mm_movemask_ps(ok) != 0xf)
        return -1;
    cu = wrap4(cu, l->wrap_u == TEX_REPEAT);
    cv = wrap4(cv, l->wrap_v == TEX_REPEAT);
    __m128 one = _mm_set1_ps(1.0f);
    for (int k = 0; k < l->n; k++) {
        __m128 fx = axis4(cu, l->w[k], l->wrap_u == TEX_REPEAT, p->xa[k], p->xb[k]);
        __m128 fy = axis4(cv, l->h[k], l->wrap_v == TEX_REPEAT, p->ya[k], p->yb[k]);
        __m128 gx = _mm_sub_ps(one, fx), gy = _mm_sub_ps(one, fy);
        _mm_storeu_ps(p->w[k][0], _mm_mul_ps(gx, gy));
        _mm_storeu_ps(p->w[k][1], _mm_mul_ps(fx, gy));
        _mm_storeu_ps(p->w[k][2], _mm_mul_ps(gx, fy));
        _mm_storeu_ps(p->w[k][3], _mm_mul_ps(fx, fy));
    }
    return 0;
}

static inline __m128 texel4(const uint16_t *p)
{
    __m128i v = _mm_loadl_epi64((const __m128i *)(const void *)p);
    return _mm_cvtepi32_ps(_mm_unpacklo_epi16(v, _mm_setzero_si128()));
}

/* Level k's bilinear sum for lane j of p (quad_add's order). */
static inline __m128 sum4(const TexLod *l, const RowPrep *p, int k, int j)
{
    const uint16_t *px = l->px[k];
    size_t s = 3 * (size_t)l->w[k];
    const uint16_t *r0 = px + (size_t)p->ya[k][j] * s, *r1 = px + (size_t)p->yb[k][j] * s;
    int xa = 3 * p->xa[k][j], xb = 3 * p->xb[k][j];
    __m128 t = _mm_mul_ps(_mm_set1_ps(p->w[k][0][j]), texel4(r0 + xa));
    t = _mm_add_ps(t, _mm_mul_ps(_mm_set1_ps(p->w[k][1][j]), texel4(r0 + xb)));
    t = _mm_add_ps(t, _mm_mul_ps(_mm_set1_ps(p->w[k][2][j]), texel4(r1 + xa)));
    return _mm_add_ps(t, _mm_mul_ps(_mm_set1_ps(p->w[k][3][j]), texel4(r1 + xb)));
}

/* Groups of 4, the last one padded (u and v hold whole groups). */
static void row_sse2(const TexLod *l, const float *u, const float *v, int n, float *out)
{
    RowPrep p;
    __m128 unit = _mm_set1_ps(1.0f / 65535.0f), wt0 = _mm_set1_ps(l->wt[0]), wt1 = _mm_set1_ps(l->wt[1]);
    for (int i = 0; i < n; i += 4) {
        int m = n - i < 4 ? n - i : 4;
        if (prep4(l, u + i, v + i, &p) < 0) {
            for (int j = 0; j < m; j++)
                texture_lookup(l, u[i + j], v[i + j], SIMD_SSE2, out + 4 * (i + j));
            continue;
        }
        for (int j = 0; j < m; j++) {
            __m128 acc = _mm_mul_ps(wt0, sum4(l, &p, 0, j));
            if (l->n == 2)
                acc = _mm_add_ps(acc, _mm_mul_ps(wt1, sum4(l, &p, 1, j)));
            _mm_storeu_ps(out + 4 * (i + j), _mm_mul_ps(acc, unit));
        }
    }
}
#endif

#ifdef ZV_AVX2
/* AVX2's group: per level, corner and lane, the texel's element offset
 * in its level (a multiply a lane) and its weight. */
typedef struct {
    int32_t o[2][4][8];
    float   w[2][4][8];
} RowPrep8;

/* Both levels' sums for lane j at once: level 0 in the low half, level
 * 1 in the high, each half quad_add's operations in its order. */
static ZV_AVX2_FN inline __m128 sum8(const TexLod *l, const RowPrep8 *p, int j, __m256 wt)
{
    const uint16_t *q0 = l->px[0], *q1 = l->px[1];
#define ZV_CORNER(c)                                                                                         \
    _mm256_mul_ps(_mm256_set_m128(_mm_set1_ps(p->w[1][c][j]), _mm_set1_ps(p->w[0][c][j])),                  \
                  _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_castpd_si128(_mm_loadh_pd(                    \
                      _mm_castsi128_pd(_mm_loadl_epi64((const __m128i *)(const void *)(q0 + p->o[0][c][j]))), \
                      (const double *)(const void *)(q1 + p->o[1][c][j]))))))
    __m256 s = ZV_CORNER(0);
    s = _mm256_add_ps(s, ZV_CORNER(1));
    s = _mm256_add_ps(s, ZV_CORNER(2));
    s = _mm256_add_ps(s, ZV_CORNER(3));
#undef ZV_CORNER
    s = _mm256_mul_ps(wt, s);
    __m128 lo = _mm256_castps256_ps128(s);
    return l->n == 2 ? _mm_add_ps(lo, _mm256_extractf128_ps(s, 1)) : lo;
}

/* floor4 on eight lanes. */
static ZV_AVX2_FN inline __m256i floor8(__m256 x)
{
    __m256i i = _mm256_cvttps_epi32(x);
    return _mm256_add_epi32(i, _mm256_castps_si256(_mm256_cmp_ps(_mm256_cvtepi32_ps(i), x, _CMP_GT_OQ)));
}

static ZV_AVX2_FN inline __m256 wrap8(__m256 c, int repeat)
{
    if (!repeat)
        return _mm256_min_ps(_mm256_max_ps(c, _mm256_set1_ps(-1.0f)), _mm256_set1_ps(2.0f));
    return _mm256_sub_ps(c, _mm256_cvtepi32_ps(floor8(c)));
}

/* texel_pair_w on lanes: the indices a, b (times mul); returns the
 * fraction. */
static ZV_AVX2_FN inline __m256 axis8(__m256 c, int n, int repeat, int mul, __m256i *a, __m256i *b)
{
    __m256 x = _mm256_sub_ps(_mm256_mul_ps(c, _mm256_set1_ps((float)n)), _mm256_set1_ps(0.5f));
    __m256i i = floor8(x);
    __m256 f = _mm256_sub_ps(x, _mm256_cvtepi32_ps(i));
    __m256i vn = _mm256_set1_epi32(n), last = _mm256_set1_epi32(n - 1), zero = _mm256_setzero_si256();
    __m256i i1 = _mm256_add_epi32(i, _mm256_set1_epi32(1)), ia, ib;
    if (repeat) {
        ia = _mm256_add_epi32(i, _mm256_and_si256(_mm256_cmpgt_epi32(zero, i), vn));
        ib = _mm256_sub_epi32(i1, _mm256_and_si256(_mm256_cmpgt_epi32(i1, last), vn));
    } else {
        ia = _mm256_min_epi32(_mm256_max_epi32(i, zero), last);
        ib = _mm256_min_epi32(_mm256_max_epi32(i1, zero), last);
    }
    *a = _mm256_mullo_epi32(ia, _mm256_set1_epi32(mul));
    *b = _mm256_mullo_epi32(ib, _mm256_set1_epi32(mul));
    return f;
}

/* A group of 8 into p: 0, or -1 when a coordinate is not tame. */
static ZV_AVX2_FN int prep8(const TexLod *l, const float *u, const float *v, RowPrep8 *p)
{
    __m256 cu = _mm256_loadu_ps(u), cv = _mm256_loadu_ps(v), big = _mm256_set1_ps(1e6f), abs = _mm256_set1_ps(-0.0f);
    __m256 ok = _mm256_and_ps(_mm256_cmp_ps(_mm256_andnot_ps(abs, cu), big, _CMP_LE_OQ),
                              _mm256_cmp_ps(_mm256_andnot_ps(abs, cv), big, _CMP_LE_OQ));
    if (_mm256_movemask_ps(ok) != 0xff)
        return -1;
    cu = wrap8(cu, l->wrap_u == TEX_REPEAT);
    cv = wrap8(cv, l->wrap_v == TEX_REPEAT);
    __m256 one = _mm256_set1_ps(1.0f);
    /* level 1 too when it is not blended: sum8 reads both (its texels
     * are in the image, its sum is dropped) */
    for (int k = 0; k < 2; k++) {
        __m256i xa, xb, ya, yb;
        __m256 fx = axis8(cu, l->w[k], l->wrap_u == TEX_REPEAT, 3, &xa, &xb);
        __m256 fy = axis8(cv, l->h[k], l->wrap_v == TEX_REPEAT, 3 * l->w[k], &ya, &yb);
        __m256 gx = _mm256_sub_ps(one, fx), gy = _mm256_sub_ps(one, fy);
        _mm256_storeu_si256((__m256i *)(void *)p->o[k][0], _mm256_add_epi32(ya, xa));
        _mm256_storeu_si256((__m256i *)(void *)p->o[k][1], _mm256_add_epi32(ya, xb));
        _mm256_storeu_si256((__m256i *)(void *)p->o[k][2], _mm256_add_epi32(yb, xa));
        _mm256_storeu_si256((__m256i *)(void *)p->o[k][3], _mm256_add_epi32(yb, xb));
        _mm256_storeu_ps(p->w[k][0], _mm256_mul_ps(gx, gy));
        _mm256_storeu_ps(p->w[k][1], _mm256_mul_ps(fx, gy));
        _mm256_storeu_ps(p->w[k][2], _mm256_mul_ps(gx, fy));
        _mm256_storeu_ps(p->w[k][3], _mm256_mul_ps(fx, fy));
    }
    return 0;
}

/* Groups of 8, the last one padded (u and v hold whole groups). */
static ZV_AVX2_FN void row_avx2(const TexLod *l, const float *u, const float *v, int n, float *out)
{
    RowPrep8 p;
    __m128 unit = _mm_set1_ps(1.0f / 65535.0f);
    __m256 wt = _mm256_set_m128(_mm_set1_ps(l->wt[1]), _mm_set1_ps(l->wt[0]));
    for (int i = 0; i < n; i += 8) {
        int m = n - i < 8 ? n - i : 8;
        if (prep8(l, u + i, v + i, &p) < 0) {
            for (int j = 0; j < m; j++)
                texture_lookup(l, u[i + j], v[i + j], SIMD_AVX2, out + 4 * (i + j));
            continue;
        }
        for (int j = 0; j < m; j++)
            _mm_storeu_ps(out + 4 * (i + j), _mm_mul_ps(sum8(l, &p, j, wt), unit));
    }
}
#endif

void texture_lookup_row(const TexLod *l, const float *u, const float *v, int n, int simd, float *out)
{
#ifdef ZV_SSE2
    if (simd >= SIMD_SSE2 && l->vec) {
#ifdef ZV_AVX2
        if (simd >= SIMD_AVX2) {
            row_avx2(l, u, v, n, out);
            return;
        }
#endif
        row_sse2(l, u, v, n, out);
        return;
    }
#endif
    for (int i = 0; i < n; i++)
        texture_lookup(l, u[i], v[i], simd, out + 4 * i);
}
