/* test_quant.c: the colour quantizer (perceptual nearest colour and
 * ordered dithering) and the glyph shading without colour. */

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "present.h"

static float lin(uint8_t v)
{
    float c = v / 255.0f;
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static float lab_dist(const float a[3], const float b[3])
{
    return sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* The OKLab colour of the linear-light average of an 8x8 dithered block
 * of rgb (the whole Bayer period: what the eye sees from afar). */
static void block_mean_lab(Quantizer *q, ColorDepth d, const uint8_t rgb[3], float lab_out[3])
{
    float acc[3] = { 0 };
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) {
            uint8_t p[3];
            palette_rgb(d, quant_pick(q, rgb, x, y), p);
            for (int a = 0; a < 3; a++)
                acc[a] += lin(p[a]) / 64;
        }
    /* back to sRGB bytes, then to OKLab through the library's path */
    uint8_t m[3];
    for (int a = 0; a < 3; a++) {
        float c = acc[a] <= 0.0031308f ? 12.92f * acc[a] : 1.055f * powf(acc[a], 1 / 2.4f) - 0.055f;
        m[a] = (uint8_t)lrintf(fminf(fmaxf(c, 0), 1) * 255);
    }
    quant_rgb_to_oklab(m, lab_out);
}

Test(quant, palette_colours_map_to_themselves_everywhere)
{
    static const ColorDepth depths[] = { COLOR_256, COLOR_16, COLOR_8 };
    for (int k = 0; k < 3; k++) {
        ColorDepth d = depths[k];
        Quantizer q;
        cr_assert_eq(quant_init(&q, d), 0);
        int first = d == COLOR_256 ? 16 : 0, last = d == COLOR_256 ? 255 : d == COLOR_16 ? 15 : 7;
        for (int i = first; i <= last; i++) {
            uint8_t c[3];
            palette_rgb(d, i, c);
            for (int y = 0; y < 8; y++)
                for (int x = 0; x < 8; x++)
                    cr_assert_eq(quant_pick(&q, c, x, y), i, "%s: entry %d at (%d,%d) -> %d", color_name(d), i,
                                 x, y, quant_pick(&q, c, x, y));
        }
        quant_free(&q);
    }
}

Test(quant, greys_stay_grey_under_8_and_16_colours)
{
    /* The nearest entry to a mid grey may be a colour; the dither must
     * use neutral entries only (0 black, 7 and 15 greys/white, 8 grey). */
    static const ColorDepth depths[] = { COLOR_16, COLOR_8 };
    for (int k = 0; k < 2; k++) {
        Quantizer q;
        cr_assert_eq(quant_init(&q, depths[k]), 0);
        for (int v = 0; v < 256; v += 5) {
            uint8_t c[3] = { (uint8_t)v, (uint8_t)v, (uint8_t)v };
            for (int y = 0; y < 8; y++)
                for (int x = 0; x < 8; x++) {
                    int i = quant_pick(&q, c, x, y);
                    cr_assert(i == 0 || i == 7 || i == 8 || i == 15, "%s: grey %d -> colour %d",
                              color_name(depths[k]), v, i);
                }
        }
        quant_free(&q);
    }
}

Test(quant, dithered_blocks_come_closer_than_the_nearest_colour)
{
    /* Over a lattice of colours, the average of an 8x8 dithered block is
     * nearer (in OKLab) to the wanted colour than the plain nearest
     * palette colour in RGB, on average, at every depth. */
    static const ColorDepth depths[] = { COLOR_256, COLOR_16, COLOR_8 };
    for (int k = 0; k < 3; k++) {
        ColorDepth d = depths[k];
        Quantizer q;
        cr_assert_eq(quant_init(&q, d), 0);
        double before = 0, after = 0;
        int n = 0;
        for (int r = 10; r < 256; r += 40)
            for (int g = 5; g < 256; g += 40)
                for (int b = 0; b < 256; b += 40) {
                    uint8_t c[3] = { (uint8_t)r, (uint8_t)g, (uint8_t)b }, p[3];
                    float want[3], got[3], near[3];
                    quant_rgb_to_oklab(c, want);
                    int old = d == COLOR_256 ? palette_256(c) : palette_16(c);
                    if (d == COLOR_8 && old > 7)
                        old -= 8;   /* the plain map folded onto the first 8 */
                    palette_rgb(d, old, p);
                    quant_rgb_to_oklab(p, near);
                    block_mean_lab(&q, d, c, got);
                    before += lab_dist(want, near);
                    after += lab_dist(want, got);
                    n++;
                }
        cr_expect_lt(after, 0.8 * before, "%s: dithered mean error %.4f, nearest %.4f", color_name(d),
                     after / n, before / n);
        quant_free(&q);
    }
}

Test(quant, dither_depends_on_position_only)
{
    Quantizer a, b;
    cr_assert_eq(quant_init(&a, COLOR_256), 0);
    cr_assert_eq(quant_init(&b, COLOR_256), 0);
    uint8_t c[3] = { 200, 120, 40 }, other[3] = { 10, 200, 90 };
    /* b sees another colour first: memoising must not change answers */
    quant_pick(&b, other, 3, 3);
    int distinct = 0, first = quant_pick(&a, c, 0, 0);
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            int i = quant_pick(&a, c, x, y);
            cr_assert_eq(i, quant_pick(&b, c, x, y));
            cr_assert_eq(i, quant_pick(&a, c, x + 8, y + 8), "period 8");
            distinct |= i != first;
        }
    cr_expect(distinct, "an orange between palette entries is dithered");
    quant_free(&a);
    quant_free(&b);
}

Test(quant, no_palette_under_truecolor_or_none)
{
    Quantizer q;
    uint8_t c[3] = { 1, 2, 3 };
    cr_assert_eq(quant_init(&q, COLOR_TRUE), 0);
    cr_expect_eq(quant_pick(&q, c, 0, 0), -1);
    quant_free(&q);
    cr_assert_eq(quant_init(&q, COLOR_NONE), 0);
    cr_expect_eq(quant_pick(&q, c, 0, 0), -1);
    quant_free(&q);
}

/* ==== shading in glyphs, no colour ==== */

/* A W x H image lit everywhere, lightness rising left to right. */
static void ramp_image(Image *im, int w, int h)
{
    memset(im, 0, sizeof *im);
    cr_assert_eq(image_resize(im, w, h), 0);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            uint8_t v = (uint8_t)(255 * x / (w - 1));
            im->rgb[3 * i] = im->rgb[3 * i + 1] = im->rgb[3 * i + 2] = v;
            im->lit[i] = 1;
        }
}

static int pixels_on_half(const Cell *c)
{
    return c->ch == 0x2588u ? 2 : c->ch == 0x2580u || c->ch == 0x2584u ? 1 : 0;
}

static int pixels_on_braille(const Cell *c)
{
    return c->ch >= 0x2800u && c->ch <= 0x28ffu ? __builtin_popcount(c->ch - 0x2800u) : 0;
}

static void check_mono_ramp(DisplayMode m, int (*on)(const Cell *))
{
    Image im;
    ramp_image(&im, 64, 32);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, m, COLOR_NONE, &g), 0);
    /* pixels drawn in the dark and the light quarter */
    int dark = 0, light = 0, glyphs[4] = { 0 };
    for (int r = 0; r < g.rows; r++)
        for (int c = 0; c < g.cols; c++) {
            const Cell *cell = &g.cells[(size_t)r * g.cols + c];
            cr_expect_eq(cell->flags, 0, "no colour is set");
            int n = on(cell);
            if (c < g.cols / 4)
                dark += n;
            if (c >= 3 * g.cols / 4)
                light += n;
            glyphs[n > 3 ? 3 : n] = 1;
        }
    cr_expect_gt(dark, 0, "dark lit pixels still show (the silhouette)");
    cr_expect_gt(light, 2 * dark, "lighter areas draw more pixels: %d vs %d", light, dark);
    cr_expect_gt(glyphs[0] + glyphs[1] + glyphs[2] + glyphs[3], 1, "more than one glyph level");
    cells_free(&g);
    image_free(&im);
}

Test(quant, half_blocks_shade_without_colour)
{
    check_mono_ramp(MODE_HALF, pixels_on_half);
}

Test(quant, braille_dots_shade_without_colour)
{
    check_mono_ramp(MODE_BRAILLE, pixels_on_braille);
}

Test(quant, colour_keeps_every_lit_pixel)
{
    /* with colour the glyphs show coverage only: every pixel drawn */
    Image im;
    ramp_image(&im, 16, 8);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, MODE_HALF, COLOR_256, &g), 0);
    for (size_t i = 0; i < (size_t)g.cols * g.rows; i++)
        cr_expect_eq(g.cells[i].ch, 0x2580u);
    cells_free(&g);
    image_free(&im);
}
