/* image.c: the RGB picture shading makes and the presenters read
 * (image.h). */

#include <stdlib.h>
#include <string.h>

#include "image.h"

int image_resize(Image *im, int w, int h)
{
    if (w < 0 || h < 0)
        return -1;
    size_t n = (size_t)w * (size_t)h;
    if (n > im->cap || !im->rgb || !im->lit) {
        size_t cap = n ? n : 1;
        uint8_t *rgb = malloc(3 * cap);
        uint8_t *lit = malloc(cap);
        if (!rgb || !lit) {
            free(rgb);
            free(lit);
            return -1;
        }
        free(im->rgb);
        free(im->lit);
        im->rgb = rgb;
        im->lit = lit;
        im->cap = cap;
    }
    im->w = w;
    im->h = h;
    return 0;
}

void image_free(Image *im)
{
    free(im->rgb);
    free(im->lit);
    memset(im, 0, sizeof *im);
}

int image_downsample(const Image *src, int k, Image *dst)
{
    if (k < 1 || image_resize(dst, src->w / k, src->h / k) != 0)
        return -1;
    const int need = (k * k + 1) / 2;   /* lit when at least half its samples are */
    for (int y = 0; y < dst->h; y++)
        for (int x = 0; x < dst->w; x++) {
            unsigned n = 0, r = 0, g = 0, b = 0;
            for (int j = 0; j < k; j++) {
                size_t i = (size_t)(y * k + j) * src->w + (size_t)x * k;
                for (int q = 0; q < k; q++, i++) {
                    if (!src->lit[i])
                        continue;
                    n++;
                    r += src->rgb[3 * i];
                    g += src->rgb[3 * i + 1];
                    b += src->rgb[3 * i + 2];
                }
            }
            size_t o = (size_t)y * dst->w + x;
            uint8_t *px = dst->rgb + 3 * o;
            if ((int)n < need) {
                px[0] = px[1] = px[2] = 0;
                dst->lit[o] = 0;
                continue;
            }
            px[0] = (uint8_t)((r + n / 2) / n);
            px[1] = (uint8_t)((g + n / 2) / n);
            px[2] = (uint8_t)((b + n / 2) / n);
            dst->lit[o] = 1;
        }
    return 0;
}
