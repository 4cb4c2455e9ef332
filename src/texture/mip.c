/* mip.c: the mipmap chain. Level k + 1 is level k with each 2 x 2 block
 * averaged in linear light (an odd last row or column is averaged with
 * itself, so every texel of level k counts), then encoded back to sRGB
 * bytes. Averaging the bytes instead would darken every fine pattern: a
 * black and white checker would fade to sRGB 128 (linear 0.22) instead
 * of linear 0.5 (sRGB 188). */

#include <stdlib.h>
#include <string.h>

#include "texture_internal.h"

/* linear_to_srgb by table: th[b] is the least linear value that
 * encodes to b + 1 or more, found by bisection on linear_to_srgb
 * itself, so that the byte of v is the number of thresholds at or
 * below it: its very bytes at a fraction of a power's cost (a 16k
 * image's first level is 200 million encodings). */
static uint8_t encode_search(const TexEncoder *e, float v)
{
    if (!(v > 0))
        return 0;
    int b = 0;
    /* invariant: the answer is in [b, b + step * 2) */
    for (int step = 128; step; step >>= 1)
        if (b + step <= 255 && v >= e->th[b + step - 1])
            b += step;
    return (uint8_t)b;
}

void texture_encoder_init(TexEncoder *e)
{
    for (int b = 0; b < 255; b++) {
        float lo = 0, hi = 1;           /* linear_to_srgb(lo) <= b < linear_to_srgb(hi) */
        for (int i = 0; i < 40; i++) {
            float mid = 0.5f * (lo + hi);
            if (mid == lo || mid == hi)
                break;
            if (linear_to_srgb(mid) > b)
                hi = mid;
            else
                lo = mid;
        }
        e->th[b] = hi;
    }
    for (int k = 0; k <= TEX_ENC_BUCKETS; k++)
        e->start[k] = encode_search(e, (float)k / TEX_ENC_BUCKETS);
}

/* The same byte as encode_search: the one of v's bucket, then the
 * thresholds passed from there, one or two at most (a bucket is
 * narrower than the step between two bytes' thresholds, the darkest
 * included); down first, for a v * TEX_ENC_BUCKETS rounded up into the
 * next bucket. */
static inline uint8_t encode(const TexEncoder *e, float v)
{
    if (!(v > 0))
        return 0;
    float x = v * TEX_ENC_BUCKETS;
    int b = e->start[x < TEX_ENC_BUCKETS ? (int)x : TEX_ENC_BUCKETS];
    while (b > 0 && v < e->th[b - 1])
        b--;
    while (b < 255 && v >= e->th[b])
        b++;
    return (uint8_t)b;
}

/* Level dst (dw x dh) from level src (sw x sh). */
void texture_halve(const TexEncoder *e, const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh)
{
    const float *lin = srgb_table();
    for (int y = 0; y < dh; y++) {
        int y0 = 2 * y < sh ? 2 * y : sh - 1, y1 = 2 * y + 1 < sh ? 2 * y + 1 : y0;
        for (int x = 0; x < dw; x++) {
            int x0 = 2 * x < sw ? 2 * x : sw - 1, x1 = 2 * x + 1 < sw ? 2 * x + 1 : x0;
            const uint8_t *p[4] = { src + 4 * ((size_t)y0 * sw + x0), src + 4 * ((size_t)y0 * sw + x1),
                                    src + 4 * ((size_t)y1 * sw + x0), src + 4 * ((size_t)y1 * sw + x1) };
            uint8_t *o = dst + 4 * ((size_t)y * dw + x);
            for (int c = 0; c < 3; c++)
                o[c] = encode(e, 0.25f * (lin[p[0][c]] + lin[p[1][c]] + lin[p[2][c]] + lin[p[3][c]]));
            o[3] = (uint8_t)((p[0][3] + p[1][3] + p[2][3] + p[3][3] + 2) / 4);
        }
    }
}

void texture_build_levels(Texture *t)
{
    int w = t->w, h = t->h, k = 0;
    size_t off = 0;
    for (;;) {
        t->lw[k] = w;
        t->lh[k] = h;
        t->off[k] = off;
        off += (size_t)w * h;
        if ((w == 1 && h == 1) || k + 1 == TEX_MAX_LEVELS)
            break;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        k++;
    }
    t->levels = k + 1;
    TexEncoder e;
    texture_encoder_init(&e);
    for (int i = 1; i < t->levels; i++)
        texture_halve(&e, t->rgba + 4 * t->off[i - 1], t->lw[i - 1], t->lh[i - 1], t->rgba + 4 * t->off[i], t->lw[i],
              t->lh[i]);
}

/* Sampling reads a texel's three channels with one 8-byte load: the
 * last texel's reads 2 bytes past it, and 8 bytes of padding keep that
 * inside the block. */
#define LIN_PAD 8

uint64_t texture_lin_bytes_for(int w, int h)
{
    /* 6 bytes a texel where texture_bytes_for counts 4 */
    return texture_bytes_for(w, h) / 4 * 6 + LIN_PAD;
}

void texture_build_lin(Texture *t)
{
    free(t->lin);
    t->lin = NULL;
    if (!t->rgba || t->levels < 1)
        return;
    int top = t->levels - 1;
    size_t n = t->off[top] + (size_t)t->lw[top] * t->lh[top];
    uint16_t *l = malloc(6 * n + LIN_PAD);
    if (!l)
        return;             /* sampling falls back to rgba and the table */
    uint16_t q[256];
    const float *lin = srgb_table();
    for (int b = 0; b < 256; b++)
        q[b] = (uint16_t)(lin[b] * 65535.0f + 0.5f);
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            l[3 * i + c] = q[t->rgba[4 * i + c]];
    memset(l + 3 * n, 0, LIN_PAD);
    t->lin = l;
}
