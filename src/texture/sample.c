/* sample.c: filtered texture lookups. A sample's footprint on the
 * texture decides the level: bilinear within a level where the image is
 * magnified, trilinear (two levels blended) where it is minified, so
 * that each sample averages about the texels it covers. Everything is
 * blended in linear light. */

#include <math.h>

#include "simd.h"
#include "texture.h"

/* Texel index i of a row or column of n under the wrap mode. */
static inline int wrap_index(int i, int n, TexWrap m)
{
    if (m == TEX_CLAMP)
        return i < 0 ? 0 : i >= n ? n - 1 : i;
    if (m == TEX_MIRROR) {
        int p = i % (2 * n);
        if (p < 0)
            p += 2 * n;
        return p < n ? p : 2 * n - 1 - p;
    }
    int r = i % n;
    return r < 0 ? r + n : r;
}

/* floorf for |x| < 2^31 without a call into libm (SSE2 has no rounding
 * instruction): truncation, one down for negatives with a fraction. */
static inline int floor_int(float x)
{
    int i = (int)x;
    return (float)i > x ? i - 1 : i;
}

/* Keep coordinates where int conversion is defined and the period still
 * resolves texels (floats past 2^23 have no fraction left anyway). */
static inline float tame(float x)
{
    /* NaN and the infinities (a file's "inf" texture coordinate, a
     * weight of a triangle seen edge-on): fmodf would give NaN, and
     * (int)NaN is undefined: take the texture's corner */
    if (!isfinite(x))
        return 0;
    return x > 1e6f ? fmodf(x, 1e6f) : x < -1e6f ? -fmodf(-x, 1e6f) : x;
}

/* The two texels a coordinate falls between on a side of n texels, and
 * the second's weight. Repeat and clamp, nearly every lookup, take no
 * division: a repeated coordinate is brought into [0, 1] first, where
 * the texel before the first is the last; a clamped one cannot lie far
 * out. Mirror goes through wrap_index. */
static inline __attribute__((always_inline)) float texel_pair(float c, int n, TexWrap m, int *a, int *b)
{
    c = tame(c);
    if (m == TEX_REPEAT)
        c -= (float)floor_int(c);
    else if (m == TEX_CLAMP)
        c = c < -1 ? -1 : c > 2 ? 2 : c;
    /* texel centres at (i + 0.5) / n */
    float x = c * (float)n - 0.5f;
    int i = floor_int(x);
    float f0 = (float)i;
    if (m == TEX_REPEAT) {
        /* i in [-1, n - 1] (c may round up to 1: then n - 1 and 0) */
        *a = i < 0 ? i + n : i;
        *b = i + 1 >= n ? i + 1 - n : i + 1;
    } else if (m == TEX_CLAMP) {
        *a = i < 0 ? 0 : i >= n ? n - 1 : i;
        *b = i + 1 < 0 ? 0 : i + 1 >= n ? n - 1 : i + 1;
    } else {
        *a = wrap_index(i, n, m);
        *b = wrap_index(i + 1, n, m);
    }
    return x - f0;
}

/* Bilinear lookup on level k, accumulated into out with weight wt. */
static void bilinear(const Texture *t, int k, float u, float v, float wt, float out[3])
{
    int w = t->lw[k], h = t->lh[k], xa, xb, ya, yb;
    const uint8_t *px = t->rgba + 4 * t->off[k];
    const float *lin = srgb_table();
    float fx = texel_pair(u, w, t->wrap_u, &xa, &xb), fy = texel_pair(v, h, t->wrap_v, &ya, &yb);
    const uint8_t *p00 = px + 4 * ((size_t)ya * w + xa), *p10 = px + 4 * ((size_t)ya * w + xb);
    const uint8_t *p01 = px + 4 * ((size_t)yb * w + xa), *p11 = px + 4 * ((size_t)yb * w + xb);
    float w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
    for (int c = 0; c < 3; c++)
        out[c] += wt * (w00 * lin[p00[c]] + w10 * lin[p10[c]] + w01 * lin[p01[c]] + w11 * lin[p11[c]]);
}

void texture_sample(const Texture *t, float u, float v, float lod, float out[3])
{
    out[0] = out[1] = out[2] = 0;
    if (!t->rgba) {
        out[0] = out[1] = out[2] = 1;
        return;
    }
    if (!(lod > 0)) {
        bilinear(t, 0, u, v, 1, out);
        return;
    }
    float top = (float)(t->levels - 1);
    if (lod >= top) {
        bilinear(t, t->levels - 1, u, v, 1, out);
        return;
    }
    int k = (int)lod;
    float f = lod - (float)k;
    bilinear(t, k, u, v, 1 - f, out);
    if (f > 0)
        bilinear(t, k + 1, u, v, f, out);
}

/* ==== From the 16-bit linear texels ==== */

/* A coordinate brought into the range its wrap mode reads, once for
 * both levels (what texel_pair does first, so the texels and weights
 * are texel_pair's). */
static inline float wrap_coord(float c, TexWrap m)
{
    c = tame(c);
    if (m == TEX_REPEAT)
        return c - (float)floor_int(c);
    if (m == TEX_CLAMP)
        return c < -1 ? -1 : c > 2 ? 2 : c;
    return c;
}

/* texel_pair after wrap_coord. */
static inline __attribute__((always_inline)) float texel_pair_w(float c, int n, TexWrap m, int *a, int *b)
{
    float x = c * (float)n - 0.5f;
    int i = floor_int(x);
    float f0 = (float)i;
    if (m == TEX_REPEAT) {
        *a = i < 0 ? i + n : i;
        *b = i + 1 >= n ? i + 1 - n : i + 1;
    } else if (m == TEX_CLAMP) {
        *a = i < 0 ? 0 : i >= n ? n - 1 : i;
        *b = i + 1 < 0 ? 0 : i + 1 >= n ? n - 1 : i + 1;
    } else {
        *a = wrap_index(i, n, m);
        *b = wrap_index(i + 1, n, m);
    }
    return x - f0;
}

/* The four texels of a bilinear lookup on level k of l and their
 * weights. */
typedef struct {
    const uint16_t *p[4];       /* (xa, ya), (xb, ya), (xa, yb), (xb, yb) */
    float w[4];
} Quad;

static inline __attribute__((always_inline)) void quad_at(const TexLod *l, int k, float u, float v, Quad *q)
{
    int w = l->w[k], h = l->h[k], xa, xb, ya, yb;
    float fx = texel_pair_w(u, w, l->wrap_u, &xa, &xb), fy = texel_pair_w(v, h, l->wrap_v, &ya, &yb);
    const uint16_t *r0 = l->px[k] + 3 * (size_t)ya * w, *r1 = l->px[k] + 3 * (size_t)yb * w;
    q->p[0] = r0 + 3 * xa;
    q->p[1] = r0 + 3 * xb;
    q->p[2] = r1 + 3 * xa;
    q->p[3] = r1 + 3 * xb;
    q->w[0] = (1 - fx) * (1 - fy);
    q->w[1] = fx * (1 - fy);
    q->w[2] = (1 - fx) * fy;
    q->w[3] = fx * fy;
}

/* acc[c] += wt * (w0 t0 + w1 t1 + w2 t2 + w3 t3), in that order: the
 * reference for quad_add_sse2. */
static inline void quad_add(const Quad *q, float wt, float acc[3])
{
    for (int c = 0; c < 3; c++)
        acc[c] += wt * (q->w[0] * (float)q->p[0][c] + q->w[1] * (float)q->p[1][c] + q->w[2] * (float)q->p[2][c] +
                        q->w[3] * (float)q->p[3][c]);
}

#ifdef ZV_SSE2
/* quad_add on four lanes (the fourth reads the next texel's red and is
 * dropped): the same operations in the same order, so the same bits. */
static inline __m128 texel_sse2(const uint16_t *p)
{
    __m128i v = _mm_loadl_epi64((const __m128i *)(const void *)p);
    return _mm_cvtepi32_ps(_mm_unpacklo_epi16(v, _mm_setzero_si128()));
}

static inline __m128 quad_add_sse2(const Quad *q, float wt, __m128 acc)
{
    __m128 s = _mm_mul_ps(_mm_set1_ps(q->w[0]), texel_sse2(q->p[0]));
    s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(q->w[1]), texel_sse2(q->p[1])));
    s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(q->w[2]), texel_sse2(q->p[2])));
    s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(q->w[3]), texel_sse2(q->p[3])));
    return _mm_add_ps(acc, _mm_mul_ps(_mm_set1_ps(wt), s));
}
#endif

void texture_lod(const Texture *t, float lod, TexLod *l)
{
    /* the levels and their weights as texture_sample has them */
    int k0 = 0, top = t->levels - 1;
    l->n = 1;
    l->wt[0] = 1;
    l->wt[1] = 0;
    if (lod > 0) {
        if (lod >= (float)top) {
            k0 = top;
        } else {
            k0 = (int)lod;
            l->wt[1] = lod - (float)k0;
            l->wt[0] = 1 - l->wt[1];
            l->n = l->wt[1] > 0 ? 2 : 1;
        }
    }
    int k1 = k0 < top ? k0 + 1 : k0;
    l->px[0] = t->lin + 3 * t->off[k0];
    l->px[1] = t->lin + 3 * t->off[k1];
    l->w[0] = t->lw[k0];
    l->h[0] = t->lh[k0];
    l->w[1] = t->lw[k1];
    l->h[1] = t->lh[k1];
    l->wrap_u = t->wrap_u;
    l->wrap_v = t->wrap_v;
    /* the SIMD path's lanes: u0 v0 u1 v1 */
    l->size[0] = (float)l->w[0];
    l->size[1] = (float)l->h[0];
    l->size[2] = (float)l->w[1];
    l->size[3] = (float)l->h[1];
    l->last[0] = l->w[0] - 1;
    l->last[1] = l->h[0] - 1;
    l->last[2] = l->w[1] - 1;
    l->last[3] = l->h[1] - 1;
    l->repeat[0] = l->repeat[2] = t->wrap_u == TEX_REPEAT ? -1 : 0;
    l->repeat[1] = l->repeat[3] = t->wrap_v == TEX_REPEAT ? -1 : 0;
    l->vec = t->wrap_u != TEX_MIRROR && t->wrap_v != TEX_MIRROR;
}

#ifdef ZV_SSE2
/* a ? b : c on each lane, a all ones or zero */
static inline __m128i pick_epi32(__m128i a, __m128i b, __m128i c)
{
    return _mm_or_si128(_mm_and_si128(a, b), _mm_andnot_si128(a, c));
}

/* texel_pair_w's indices for repeat and clamp, lanes u0 v0 u1 v1. */
static inline void wrap_sse2(const TexLod *l, __m128i i, __m128i *a_out, __m128i *b_out)
{
    __m128i last = _mm_loadu_si128((const __m128i *)(const void *)l->last), zero = _mm_setzero_si128();
    __m128i n = _mm_add_epi32(last, _mm_set1_epi32(1)), i1 = _mm_add_epi32(i, _mm_set1_epi32(1));
    /* repeat: i in [-1, n - 1] */
    __m128i ra = _mm_add_epi32(i, _mm_and_si128(_mm_cmplt_epi32(i, zero), n));
    __m128i rb = _mm_sub_epi32(i1, _mm_and_si128(_mm_cmpgt_epi32(i1, last), n));
    __m128i rep = _mm_loadu_si128((const __m128i *)(const void *)l->repeat);
    if (_mm_movemask_epi8(rep) == 0xffff) {
        *a_out = ra;
        *b_out = rb;
        return;
    }
    /* clamp to [0, n - 1] */
    __m128i ca = pick_epi32(_mm_cmplt_epi32(i, zero), zero, pick_epi32(_mm_cmpgt_epi32(i, last), last, i));
    __m128i cb = pick_epi32(_mm_cmplt_epi32(i1, zero), zero, pick_epi32(_mm_cmpgt_epi32(i1, last), last, i1));
    *a_out = pick_epi32(rep, ra, ca);
    *b_out = pick_epi32(rep, rb, cb);
}

/* One level's quad_add_sse2 with its weights in lanes (w0 w1 w2 w3). */
static inline __m128 level_sse2(const uint16_t *r0, const uint16_t *r1, int xa, int xb, __m128 w, float wt, __m128 acc)
{
    __m128 s = _mm_mul_ps(_mm_shuffle_ps(w, w, 0x00), texel_sse2(r0 + 3 * xa));
    s = _mm_add_ps(s, _mm_mul_ps(_mm_shuffle_ps(w, w, 0x55), texel_sse2(r0 + 3 * xb)));
    s = _mm_add_ps(s, _mm_mul_ps(_mm_shuffle_ps(w, w, 0xaa), texel_sse2(r1 + 3 * xa)));
    s = _mm_add_ps(s, _mm_mul_ps(_mm_shuffle_ps(w, w, 0xff), texel_sse2(r1 + 3 * xb)));
    return _mm_add_ps(acc, _mm_mul_ps(_mm_set1_ps(wt), s));
}

/* texture_lookup's texels and sums for repeat and clamp (l->vec), both
 * levels' coordinates at once: texel_pair_w's and quad_at's operations
 * lane by lane, so quad_add's bits. Returns the sum, not yet scaled. */
static inline __m128 lookup_sse2(const TexLod *l, __m128 c)
{
    __m128 x = _mm_sub_ps(_mm_mul_ps(c, _mm_loadu_ps(l->size)), _mm_set1_ps(0.5f));
    __m128i i = _mm_cvttps_epi32(x);
    /* floor_int: one down where truncation went up */
    i = _mm_add_epi32(i, _mm_castps_si128(_mm_cmpgt_ps(_mm_cvtepi32_ps(i), x)));
    __m128 f = _mm_sub_ps(x, _mm_cvtepi32_ps(i));
    __m128i va, vb;
    wrap_sse2(l, i, &va, &vb);
    int32_t a[4], b[4];
    _mm_storeu_si128((__m128i *)(void *)a, va);
    _mm_storeu_si128((__m128i *)(void *)b, vb);
    /* weights: (1 - fx)(1 - fy), fx (1 - fy), (1 - fx) fy, fx fy per level */
    __m128 g = _mm_sub_ps(_mm_set1_ps(1.0f), f);
    __m128 gf = _mm_unpacklo_ps(g, f), gf1 = _mm_unpackhi_ps(g, f);    /* g0x f0x g0y f0y; level 1's */
    __m128 w0 = _mm_mul_ps(_mm_shuffle_ps(gf, gf, _MM_SHUFFLE(1, 0, 1, 0)), _mm_shuffle_ps(gf, gf, _MM_SHUFFLE(3, 3, 2, 2)));
    const uint16_t *p0 = l->px[0];
    size_t s0 = 3 * (size_t)l->w[0];
    __m128 acc = level_sse2(p0 + (size_t)a[1] * s0, p0 + (size_t)b[1] * s0, a[0], b[0], w0, l->wt[0], _mm_setzero_ps());
    if (l->n == 2) {
        __m128 w1 = _mm_mul_ps(_mm_shuffle_ps(gf1, gf1, _MM_SHUFFLE(1, 0, 1, 0)),
                               _mm_shuffle_ps(gf1, gf1, _MM_SHUFFLE(3, 3, 2, 2)));
        const uint16_t *p1 = l->px[1];
        size_t s1 = 3 * (size_t)l->w[1];
        acc = level_sse2(p1 + (size_t)a[3] * s1, p1 + (size_t)b[3] * s1, a[2], b[2], w1, l->wt[1], acc);
    }
    return acc;
}
#endif

#ifdef ZV_SSE2
/* wrap_coord on lanes u v u v, for repeat and clamp; coordinates past
 * tame's range (or NaN) go through wrap_coord itself. */
static inline __m128 wrap_coords_sse2(const TexLod *l, float u, float v)
{
    __m128 c = _mm_setr_ps(u, v, u, v);
    __m128 big = _mm_set1_ps(1e6f);
    /* |c| <= 1e6, false for NaN */
    __m128 ok = _mm_cmple_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), c), big);
    if (_mm_movemask_ps(ok) != 0xf)
        return _mm_setr_ps(wrap_coord(u, l->wrap_u), wrap_coord(v, l->wrap_v), wrap_coord(u, l->wrap_u),
                           wrap_coord(v, l->wrap_v));
    /* repeat: c - floor_int(c) */
    __m128i i = _mm_cvttps_epi32(c);
    __m128 fi = _mm_cvtepi32_ps(i);
    fi = _mm_cvtepi32_ps(_mm_add_epi32(i, _mm_castps_si128(_mm_cmpgt_ps(fi, c))));
    __m128 rep = _mm_sub_ps(c, fi);
    /* clamp: c < -1 ? -1 : c > 2 ? 2 : c (c is not NaN here) */
    __m128 cl = _mm_min_ps(_mm_max_ps(c, _mm_set1_ps(-1.0f)), _mm_set1_ps(2.0f));
    __m128 m = _mm_castsi128_ps(_mm_loadu_si128((const __m128i *)(const void *)l->repeat));
    return _mm_or_ps(_mm_and_ps(m, rep), _mm_andnot_ps(m, cl));
}

/* texture_lookup's SSE2 path for repeat and clamp, kept out of line
 * from the rest (its registers are its own). */
static __attribute__((noinline)) void lookup_vec_sse2(const TexLod *l, float u, float v, float out[3])
{
    __m128 acc = lookup_sse2(l, wrap_coords_sse2(l, u, v));
    float r[4];
    _mm_storeu_ps(r, _mm_mul_ps(acc, _mm_set1_ps(1.0f / 65535.0f)));
    out[0] = r[0];
    out[1] = r[1];
    out[2] = r[2];
}
#endif

void texture_lookup(const TexLod *l, float u, float v, int simd, float out[3])
{
#ifdef ZV_SSE2
    if (simd >= SIMD_SSE2 && l->vec) {
        lookup_vec_sse2(l, u, v, out);
        return;
    }
#endif
    u = wrap_coord(u, l->wrap_u);
    v = wrap_coord(v, l->wrap_v);
    Quad q[2];
    const float unit = 1.0f / 65535.0f;
#ifdef ZV_SSE2
    if (simd >= SIMD_SSE2) {
        /* mirror */
        quad_at(l, 0, u, v, &q[0]);
        __m128 acc = quad_add_sse2(&q[0], l->wt[0], _mm_setzero_ps());
        if (l->n == 2) {
            quad_at(l, 1, u, v, &q[1]);
            acc = quad_add_sse2(&q[1], l->wt[1], acc);
        }
        float r[4];
        _mm_storeu_ps(r, _mm_mul_ps(acc, _mm_set1_ps(unit)));
        out[0] = r[0];
        out[1] = r[1];
        out[2] = r[2];
        return;
    }
#endif
    (void)simd;
    quad_at(l, 0, u, v, &q[0]);
    if (l->n == 2)
        quad_at(l, 1, u, v, &q[1]);
    float acc[3] = { 0, 0, 0 };
    quad_add(&q[0], l->wt[0], acc);
    if (l->n == 2)
        quad_add(&q[1], l->wt[1], acc);
    for (int c = 0; c < 3; c++)
        out[c] = acc[c] * unit;
}

void texture_sample_lin(const Texture *t, float u, float v, float lod, int simd, float out[3])
{
    if (!t->lin) {
        texture_sample(t, u, v, lod, out);
        return;
    }
    TexLod l;
    texture_lod(t, lod, &l);
    texture_lookup(&l, u, v, simd, out);
}
