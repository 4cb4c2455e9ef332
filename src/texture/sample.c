/* sample.c: filtered texture lookups. A sample's footprint on the
 * texture decides the level: bilinear within a level where the image is
 * magnified, trilinear (two levels blended) where it is minified, so
 * that each sample averages about the texels it covers. Everything is
 * blended in linear light. */

#include <math.h>

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
