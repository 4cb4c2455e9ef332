/* mip.c: the mipmap chain. Level k + 1 is level k with each 2 x 2 block
 * averaged in linear light (an odd last row or column is averaged with
 * itself, so every texel of level k counts), then encoded back to sRGB
 * bytes. Averaging the bytes instead would darken every fine pattern: a
 * black and white checker would fade to sRGB 128 (linear 0.22) instead
 * of linear 0.5 (sRGB 188). */

#include <string.h>

#include "texture_internal.h"

/* Level dst (dw x dh) from level src (sw x sh). */
static void halve(const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh)
{
    for (int y = 0; y < dh; y++) {
        int y0 = 2 * y < sh ? 2 * y : sh - 1, y1 = 2 * y + 1 < sh ? 2 * y + 1 : y0;
        for (int x = 0; x < dw; x++) {
            int x0 = 2 * x < sw ? 2 * x : sw - 1, x1 = 2 * x + 1 < sw ? 2 * x + 1 : x0;
            const uint8_t *p[4] = { src + 4 * ((size_t)y0 * sw + x0), src + 4 * ((size_t)y0 * sw + x1),
                                    src + 4 * ((size_t)y1 * sw + x0), src + 4 * ((size_t)y1 * sw + x1) };
            uint8_t *o = dst + 4 * ((size_t)y * dw + x);
            for (int c = 0; c < 3; c++)
                o[c] = linear_to_srgb(0.25f * (srgb_to_linear(p[0][c]) + srgb_to_linear(p[1][c]) +
                                               srgb_to_linear(p[2][c]) + srgb_to_linear(p[3][c])));
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
    for (int i = 1; i < t->levels; i++)
        halve(t->rgba + 4 * t->off[i - 1], t->lw[i - 1], t->lh[i - 1], t->rgba + 4 * t->off[i], t->lw[i],
              t->lh[i]);
}
