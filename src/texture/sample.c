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

/* Keep coordinates where int conversion is defined and the period still
 * resolves texels (floats past 2^23 have no fraction left anyway). */
static inline float tame(float x)
{
    if (!(x == x))
        return 0;
    return x > 1e6f ? fmodf(x, 1e6f) : x < -1e6f ? -fmodf(-x, 1e6f) : x;
}

/* Bilinear lookup on level k, accumulated into out with weight wt. */
static void bilinear(const Texture *t, int k, float u, float v, float wt, float out[3])
{
    int w = t->lw[k], h = t->lh[k];
    const uint8_t *px = t->rgba + 4 * t->off[k];
    /* texel centres at (i + 0.5) / w */
    float x = tame(u) * (float)w - 0.5f, y = tame(v) * (float)h - 0.5f;
    float fx0 = floorf(x), fy0 = floorf(y);
    float fx = x - fx0, fy = y - fy0;
    int x0 = (int)fx0, y0 = (int)fy0;
    int xa = wrap_index(x0, w, t->wrap_u), xb = wrap_index(x0 + 1, w, t->wrap_u);
    int ya = wrap_index(y0, h, t->wrap_v), yb = wrap_index(y0 + 1, h, t->wrap_v);
    const uint8_t *p00 = px + 4 * ((size_t)ya * w + xa), *p10 = px + 4 * ((size_t)ya * w + xb);
    const uint8_t *p01 = px + 4 * ((size_t)yb * w + xa), *p11 = px + 4 * ((size_t)yb * w + xb);
    float w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
    for (int c = 0; c < 3; c++)
        out[c] += wt * (w00 * srgb_to_linear(p00[c]) + w10 * srgb_to_linear(p10[c]) +
                        w01 * srgb_to_linear(p01[c]) + w11 * srgb_to_linear(p11[c]));
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
