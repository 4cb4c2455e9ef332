/* quant: a cell colour -> the palette number a terminal of 256, 16 or 8
 * colours should show at a given pixel.
 *
 * Nearest colour is judged in OKLab, a space where equal distances look
 * about equally different, so a shade neither jumps to a brighter grey
 * nor shifts hue the way the nearest colour in RGB can (a dim orange
 * became dark red). Between the nearest palette colour and the partner
 * whose mix with it comes closest to the wanted colour, an 8x8 ordered
 * (Bayer) dither picks per pixel, with the partner's share computed in
 * linear light, which is how the eye averages neighbouring pixels: a
 * smooth shade becomes a fine pattern of two colours instead of bands.
 *
 * Choosing the pair is the costly part, so it is memoised per colour
 * rounded to 6 bits a channel (a 1 MB table filled lazily, kept across
 * frames); the share is computed exactly per pixel from a table of
 * linear values. Exact palette colours always map to themselves.
 *
 * OKLab: B. Ottosson, "A perceptual color space for image processing",
 * 2020 (bottosson.github.io/posts/oklab). Ordered dither: B. E. Bayer,
 * "An optimum method for two-level rendition of continuous-tone
 * pictures", IEEE International Conference on Communications, 1973. sRGB
 * transfer: IEC 61966-2-1:1999.
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "invariant.h"
#include "present.h"

#define LUT_BITS   6
#define LUT_SIZE   (1u << (3 * LUT_BITS))
#define LUT_FILLED 0x80000000u

/* 8x8 Bayer matrix: thresholds (v + 0.5) / 64 spread evenly in space. */
static const uint8_t bayer8[8][8] = {
    {  0, 32,  8, 40,  2, 34, 10, 42 },
    { 48, 16, 56, 24, 50, 18, 58, 26 },
    { 12, 44,  4, 36, 14, 46,  6, 38 },
    { 60, 28, 52, 20, 62, 30, 54, 22 },
    {  3, 35, 11, 43,  1, 33,  9, 41 },
    { 51, 19, 59, 27, 49, 17, 57, 25 },
    { 15, 47,  7, 39, 13, 45,  5, 37 },
    { 63, 31, 55, 23, 61, 29, 53, 21 },
};

static float srgb_to_linear(int v)
{
    float c = (float)v / 255.0f;
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

/* Linear sRGB -> OKLab (Björn Ottosson's published matrices). */
static void linear_to_oklab(const float rgb[3], float lab[3])
{
    float l = 0.4122214708f * rgb[0] + 0.5363325363f * rgb[1] + 0.0514459929f * rgb[2];
    float m = 0.2119034982f * rgb[0] + 0.6806995451f * rgb[1] + 0.1073969566f * rgb[2];
    float s = 0.0883024619f * rgb[0] + 0.2817188376f * rgb[1] + 0.6299787005f * rgb[2];
    l = cbrtf(l);
    m = cbrtf(m);
    s = cbrtf(s);
    lab[0] = 0.2104542553f * l + 0.7936177850f * m - 0.0040720468f * s;
    lab[1] = 1.9779984951f * l - 2.4285922050f * m + 0.4505937099f * s;
    lab[2] = 0.0259040371f * l + 0.7827717662f * m - 0.8086757660f * s;
}

void quant_rgb_to_oklab(const uint8_t rgb[3], float lab_out[3])
{
    float lin[3] = { srgb_to_linear(rgb[0]), srgb_to_linear(rgb[1]), srgb_to_linear(rgb[2]) };
    linear_to_oklab(lin, lab_out);
}

int quant_init(Quantizer *q, ColourDepth depth)
{
    memset(q, 0, sizeof *q);
    q->depth = depth;
    for (int v = 0; v < 256; v++)
        q->lin[v] = srgb_to_linear(v);
    /* the palette searched: under 256 colours the cube and the greys
     * (the first 16 are themable, their real colour unknown) */
    int first = depth == COLOUR_256 ? 16 : 0;
    int last = depth == COLOUR_256 ? 255 : depth == COLOUR_16 ? 15 : depth == COLOUR_8 ? 7 : -1;
    for (int i = first; i <= last; i++) {
        uint8_t rgb[3];
        palette_rgb(depth, i, rgb);
        int k = q->n++;
        ZV_ASSERT(k < (int)(sizeof q->num / sizeof *q->num));  /* the palette searched fits its arrays */
        q->num[k] = (uint8_t)i;
        for (int a = 0; a < 3; a++)
            q->plin[k][a] = q->lin[rgb[a]];
        linear_to_oklab(q->plin[k], q->plab[k]);
    }
    if (q->n > 0) {
        q->lut = calloc(LUT_SIZE, sizeof *q->lut);
        if (!q->lut)
            return -1;
    }
    return 0;
}

void quant_free(Quantizer *q)
{
    free(q->lut);
    q->lut = NULL;
}

/* Squared OKLab distance with hue (a, b) counted HUE_WEIGHT times: a
 * shade that comes out a little light or dark reads as lighting, one that
 * comes out another hue reads as a wrong colour. */
#define HUE_WEIGHT 2.0f
static inline float dist2(const float a[3], const float b[3])
{
    float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + HUE_WEIGHT * (d1 * d1 + d2 * d2);
}

/* The pair to dither between for the colour lab. The cost of a pair
 * (p1, p2) is how far their best mix lies from lab, plus the pattern's
 * own visibility: a share t of p2 among p1 varies by t (1 - t) |p2 - p1|^2,
 * weighted far more in hue (a, b) than in lightness, so that a grey is
 * dithered from black and white rather than from red and cyan, whose mix
 * is grey too. Under 256 colours p1 is the nearest
 * entry (the palette is dense); under 16 and 8 every pair is tried, as
 * the nearest entry to a mid grey may well be a green. */
#define NOISE_L  0.1f     /* a pattern of light and dark reads as shading */
#define NOISE_AB 0.7f     /* one of two hues reads as speckle */

/* Cost of mixing a and b towards lab (and the share of b). */
static float pair_cost(const float a[3], const float b[3], const float lab[3])
{
    float ab[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    float ac[3] = { lab[0] - a[0], lab[1] - a[1], lab[2] - a[2] };
    float len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    float t = len2 > 0 ? (ac[0] * ab[0] + ac[1] * ab[1] + ac[2] * ab[2]) / len2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    float m[3] = { a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2] };
    float noise = NOISE_L * ab[0] * ab[0] + NOISE_AB * (ab[1] * ab[1] + ab[2] * ab[2]);
    return dist2(lab, m) + t * (1 - t) * noise;
}

static uint32_t choose_pair(const Quantizer *q, const float lab[3])
{
    int p1 = 0, p2 = 0;
    float best = INFINITY;
    for (int k = 0; k < q->n; k++) {
        float d = dist2(lab, q->plab[k]);
        if (d < best) {
            best = d;
            p1 = p2 = k;
        }
    }
    int all = q->n <= 16;
    for (int i = all ? 0 : p1; i < (all ? q->n : p1 + 1); i++)
        for (int k = 0; k < q->n; k++) {
            if (k == i)
                continue;
            float c = pair_cost(q->plab[i], q->plab[k], lab);
            if (c < best) {
                best = c;
                p1 = i;
                p2 = k;
            }
        }
    /* the pair is stored in a byte each and indexes num[], plin[]: in
     * the palette searched */
    ZV_ASSERT(p1 >= 0 && p2 >= 0 && p1 < q->n && p2 < q->n && q->n <= 256);
    return LUT_FILLED | (uint32_t)p1 | (uint32_t)p2 << 8;
}

float quant_threshold(int x, int y)
{
    return ((float)bayer8[y & 7][x & 7] + 0.5f) / 64.0f;
}

int quant_pick(Quantizer *q, const uint8_t rgb[3], int x, int y)
{
    if (q->n == 0)
        return -1;
    uint32_t key = (uint32_t)(rgb[0] >> (8 - LUT_BITS)) << (2 * LUT_BITS) |
                   (uint32_t)(rgb[1] >> (8 - LUT_BITS)) << LUT_BITS | (uint32_t)(rgb[2] >> (8 - LUT_BITS));
    uint32_t e = q->lut[key];
    if (!e) {
        /* the middle of the table cell, so that its pair suits all of it */
        const int half = 1 << (7 - LUT_BITS);
        uint8_t mid[3] = { (uint8_t)((rgb[0] & ~(2 * half - 1)) | half),
                           (uint8_t)((rgb[1] & ~(2 * half - 1)) | half),
                           (uint8_t)((rgb[2] & ~(2 * half - 1)) | half) };
        float lab[3];
        quant_rgb_to_oklab(mid, lab);
        e = q->lut[key] = choose_pair(q, lab);
    }
    int p1 = (int)(e & 0xff), p2 = (int)(e >> 8 & 0xff);
    if (p1 == p2)
        return q->num[p1];
    /* the partner's share in linear light: the projection of the wanted
     * colour on the segment between the two */
    const float *a = q->plin[p1], *b = q->plin[p2];
    float c[3] = { q->lin[rgb[0]], q->lin[rgb[1]], q->lin[rgb[2]] };
    float ab[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    float len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    if (!(len2 > 0))
        return q->num[p1];
    float t = ((c[0] - a[0]) * ab[0] + (c[1] - a[1]) * ab[1] + (c[2] - a[2]) * ab[2]) / len2;
    return q->num[t > quant_threshold(x, y) ? p2 : p1];
}

