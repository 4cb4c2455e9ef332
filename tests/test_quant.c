/* test_quant.c: the colour quantizer (perceptual nearest colour and
 * ordered dithering) and the glyph shading without colour. OKLab and the
 * Bayer matrix are checked against references of their own (the
 * published matrices and test values, the bit-interleave formula), and
 * the quantizer's results are judged in the reference OKLab. */

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

/* ==== OKLab, the reference: not the quantizer's own ====
 * B. Ottosson, "A perceptual color space for image processing" (2020)
 * defines OKLab from CIE XYZ (D65): lms = M1 xyz, cube roots, Lab = M2
 * lms'. The quantizer starts from linear sRGB with M1 folded into the
 * sRGB matrix; here linear sRGB goes to XYZ by the matrix of IEC
 * 61966-2-1 (four digits), then through the post's M1 and M2, in double. */
static void xyz_to_oklab(const double xyz[3], double lab[3])
{
    static const double m1[3][3] = { { 0.8189330101, 0.3618667424, -0.1288597137 },
                                     { 0.0329845436, 0.9293118715, 0.0361456387 },
                                     { 0.0482003018, 0.2643662691, 0.6338517070 } };
    static const double m2[3][3] = { { 0.2104542553, 0.7936177850, -0.0040720468 },
                                     { 1.9779984951, -2.4285922050, 0.4505937099 },
                                     { 0.0259040371, 0.7827717662, -0.8086757660 } };
    double lms[3];
    for (int r = 0; r < 3; r++)
        lms[r] = cbrt(m1[r][0] * xyz[0] + m1[r][1] * xyz[1] + m1[r][2] * xyz[2]);
    for (int r = 0; r < 3; r++)
        lab[r] = m2[r][0] * lms[0] + m2[r][1] * lms[1] + m2[r][2] * lms[2];
}

static void linear_to_oklab_ref(const double rgb[3], float lab_out[3])
{
    static const double srgb_xyz[3][3] = { { 0.4124, 0.3576, 0.1805 },
                                           { 0.2126, 0.7152, 0.0722 },
                                           { 0.0193, 0.1192, 0.9505 } };
    double xyz[3], lab[3];
    for (int r = 0; r < 3; r++)
        xyz[r] = srgb_xyz[r][0] * rgb[0] + srgb_xyz[r][1] * rgb[1] + srgb_xyz[r][2] * rgb[2];
    xyz_to_oklab(xyz, lab);
    for (int a = 0; a < 3; a++)
        lab_out[a] = (float)lab[a];
}

static void srgb_to_oklab_ref(const uint8_t rgb[3], float lab_out[3])
{
    double l[3] = { lin(rgb[0]), lin(rgb[1]), lin(rgb[2]) };
    linear_to_oklab_ref(l, lab_out);
}

static float lab_dist(const float a[3], const float b[3])
{
    return sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* The OKLab colour of the linear-light average of an 8x8 dithered block
 * of rgb (the whole Bayer period: what the eye sees from afar). */
static void block_mean_lab(Quantizer *q, ColourDepth d, const uint8_t rgb[3], float lab_out[3])
{
    double acc[3] = { 0 };
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) {
            uint8_t p[3];
            palette_rgb(d, quant_pick(q, rgb, x, y), p);
            for (int a = 0; a < 3; a++)
                acc[a] += lin(p[a]) / 64.0;
        }
    linear_to_oklab_ref(acc, lab_out);
}

Test(quant, oklab_reference_gives_the_published_pairs)
{
    /* the post's table of XYZ values and their OKLab (three decimals):
     * the reference above is transcribed right */
    static const double pairs[4][6] = {
        { 0.950, 1.000, 1.089, 1.000, 0.000, 0.000 },
        { 1.000, 0.000, 0.000, 0.450, 1.236, -0.019 },
        { 0.000, 1.000, 0.000, 0.922, -0.671, 0.263 },
        { 0.000, 0.000, 1.000, 0.153, -1.415, -0.449 },
    };
    for (int k = 0; k < 4; k++) {
        double lab[3];
        xyz_to_oklab(pairs[k], lab);
        for (int a = 0; a < 3; a++)
            cr_assert(fabs(lab[a] - pairs[k][3 + a]) < 0.0011, "XYZ %g %g %g: component %d is %.4f, the post says %.3f",
                      pairs[k][0], pairs[k][1], pairs[k][2], a, lab[a], pairs[k][3 + a]);
    }
}

Test(quant, oklab_of_srgb_white_black_and_a_lattice)
{
    /* sRGB white is the D65 white point: L = 1, a = b = 0 */
    float lab[3], ref[3];
    quant_rgb_to_oklab((const uint8_t[3]){ 255, 255, 255 }, lab);
    cr_assert(fabsf(lab[0] - 1) < 1e-4f && fabsf(lab[1]) < 1e-4f && fabsf(lab[2]) < 1e-4f,
              "white: %.6f %.6f %.6f", (double)lab[0], (double)lab[1], (double)lab[2]);
    quant_rgb_to_oklab((const uint8_t[3]){ 0, 0, 0 }, lab);
    cr_assert(fabsf(lab[0]) < 1e-6f && fabsf(lab[1]) < 1e-6f && fabsf(lab[2]) < 1e-6f);
    /* every colour of a lattice against the XYZ route (the IEC matrix's
     * four digits leave about 1e-4 between the two) */
    for (int r = 0; r < 256; r += 17)
        for (int g = 0; g < 256; g += 17)
            for (int b = 0; b < 256; b += 17) {
                uint8_t c[3] = { (uint8_t)r, (uint8_t)g, (uint8_t)b };
                quant_rgb_to_oklab(c, lab);
                srgb_to_oklab_ref(c, ref);
                for (int a = 0; a < 3; a++) {
                    float d = fabsf(lab[a] - ref[a]);
                    cr_assert_lt(d, 3e-4f, "rgb %d %d %d, component %d: %.6f, reference %.6f", r, g, b, a,
                                 (double)lab[a], (double)ref[a]);
                }
            }
}

/* ==== ordered dither: Bayer's matrix ==== */

/* Entry (x, y) of the 2^n x 2^n Bayer matrix: the bits of x XOR y and of
 * y interleaved (x XOR y in the even places, y in the odd ones, lowest
 * bits first), then the 2n bits read in reverse. */
static int bayer_entry(int x, int y, int n)
{
    int v = 0, r = 0;
    for (int b = 0; b < n; b++) {
        v |= ((x ^ y) >> b & 1) << (2 * b);
        v |= (y >> b & 1) << (2 * b + 1);
    }
    for (int b = 0; b < 2 * n; b++)
        r |= (v >> b & 1) << (2 * n - 1 - b);
    return r;
}

Test(quant, thresholds_are_bayers_matrix)
{
    /* the formula gives Bayer's 2 x 2 matrix, 0 2 / 3 1 */
    cr_assert(bayer_entry(0, 0, 1) == 0 && bayer_entry(1, 0, 1) == 2 && bayer_entry(0, 1, 1) == 3 &&
              bayer_entry(1, 1, 1) == 1);
    int seen[64] = { 0 };
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            int m = bayer_entry(x & 7, y & 7, 3);
            float want = ((float)m + 0.5f) / 64.0f;
            cr_assert_eq(quant_threshold(x, y), want, "(%d,%d): %g, Bayer's entry %d gives %g", x, y,
                         (double)quant_threshold(x, y), m, (double)want);
            if (x < 8 && y < 8)
                seen[m]++;
        }
    for (int m = 0; m < 64; m++)
        cr_assert_eq(seen[m], 1, "level %d used %d times", m, seen[m]);
}

Test(quant, palette_colours_map_to_themselves_everywhere)
{
    static const ColourDepth depths[] = { COLOUR_256, COLOUR_16, COLOUR_8 };
    for (int k = 0; k < 3; k++) {
        ColourDepth d = depths[k];
        Quantizer q;
        cr_assert_eq(quant_init(&q, d), 0);
        int first = d == COLOUR_256 ? 16 : 0, last = d == COLOUR_256 ? 255 : d == COLOUR_16 ? 15 : 7;
        for (int i = first; i <= last; i++) {
            uint8_t c[3];
            palette_rgb(d, i, c);
            for (int y = 0; y < 8; y++)
                for (int x = 0; x < 8; x++)
                    cr_assert_eq(quant_pick(&q, c, x, y), i, "%s: entry %d at (%d,%d) -> %d", colour_name(d), i,
                                 x, y, quant_pick(&q, c, x, y));
        }
        quant_free(&q);
    }
}

Test(quant, greys_stay_grey_under_8_and_16_colours)
{
    /* The nearest entry to a mid grey may be a colour; the dither must
     * use neutral entries only (0 black, 7 and 15 greys/white, 8 grey). */
    static const ColourDepth depths[] = { COLOUR_16, COLOUR_8 };
    for (int k = 0; k < 2; k++) {
        Quantizer q;
        cr_assert_eq(quant_init(&q, depths[k]), 0);
        for (int v = 0; v < 256; v += 5) {
            uint8_t c[3] = { (uint8_t)v, (uint8_t)v, (uint8_t)v };
            for (int y = 0; y < 8; y++)
                for (int x = 0; x < 8; x++) {
                    int i = quant_pick(&q, c, x, y);
                    cr_assert(i == 0 || i == 7 || i == 8 || i == 15, "%s: grey %d -> colour %d",
                              colour_name(depths[k]), v, i);
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
    static const ColourDepth depths[] = { COLOUR_256, COLOUR_16, COLOUR_8 };
    for (int k = 0; k < 3; k++) {
        ColourDepth d = depths[k];
        Quantizer q;
        cr_assert_eq(quant_init(&q, d), 0);
        double before = 0, after = 0;
        int n = 0;
        for (int r = 10; r < 256; r += 40)
            for (int g = 5; g < 256; g += 40)
                for (int b = 0; b < 256; b += 40) {
                    uint8_t c[3] = { (uint8_t)r, (uint8_t)g, (uint8_t)b }, p[3];
                    float want[3], got[3], near[3];
                    srgb_to_oklab_ref(c, want);
                    int old = d == COLOUR_256 ? palette_256(c) : palette_16(c);
                    if (d == COLOUR_8 && old > 7)
                        old -= 8;   /* the plain map folded onto the first 8 */
                    palette_rgb(d, old, p);
                    srgb_to_oklab_ref(p, near);
                    block_mean_lab(&q, d, c, got);
                    before += lab_dist(want, near);
                    after += lab_dist(want, got);
                    n++;
                }
        cr_expect_lt(after, 0.8 * before, "%s: dithered mean error %.4f, nearest %.4f", colour_name(d),
                     after / n, before / n);
        quant_free(&q);
    }
}

Test(quant, sixteen_colours_search_every_pair)
{
    /* Dark green, olive and teal: under 16 colours the nearest entry to
     * each (in the reference OKLab) is the mid grey 8, yet black and the
     * entry of their own hue mix to within a hair of them. Every pair is
     * searched, so their 8x8 blocks come that close and never use the
     * grey. */
    static const uint8_t colours[3][3] = { { 0, 102, 0 }, { 102, 102, 0 }, { 0, 102, 102 } };
    Quantizer q;
    cr_assert_eq(quant_init(&q, COLOUR_16), 0);
    for (int c = 0; c < 3; c++) {
        float want[3], got[3], best = INFINITY;
        int nearest = -1;
        srgb_to_oklab_ref(colours[c], want);
        for (int i = 0; i < 16; i++) {
            uint8_t p[3];
            float lab[3];
            palette_rgb(COLOUR_16, i, p);
            srgb_to_oklab_ref(p, lab);
            if (lab_dist(lab, want) < best) {
                best = lab_dist(lab, want);
                nearest = i;
            }
        }
        cr_assert_eq(nearest, 8, "colour %d: the nearest entry is %d, not the grey", c, nearest);
        block_mean_lab(&q, COLOUR_16, colours[c], got);
        cr_expect_lt(lab_dist(got, want), 0.005f, "rgb %d %d %d: the block is %.4f away (the grey %.4f)",
                     colours[c][0], colours[c][1], colours[c][2], (double)lab_dist(got, want), (double)best);
        for (int y = 0; y < 8; y++)
            for (int x = 0; x < 8; x++)
                cr_expect_neq(quant_pick(&q, colours[c], x, y), 8, "rgb %d %d %d at (%d,%d): the grey",
                              colours[c][0], colours[c][1], colours[c][2], x, y);
    }
    quant_free(&q);
}

Test(quant, dither_depends_on_position_only)
{
    Quantizer a, b;
    cr_assert_eq(quant_init(&a, COLOUR_256), 0);
    cr_assert_eq(quant_init(&b, COLOUR_256), 0);
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
    cr_assert_eq(quant_init(&q, COLOUR_TRUE), 0);
    cr_expect_eq(quant_pick(&q, c, 0, 0), -1);
    quant_free(&q);
    cr_assert_eq(quant_init(&q, COLOUR_NONE), 0);
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
    cr_assert_eq(cells_from_image(&im, m, COLOUR_NONE, &g), 0);
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

Test(quant, half_blocks_without_colour_put_each_pixel_in_its_half)
{
    /* white pixels are drawn at every threshold: a lit top pixel is the
     * upper half block, a lit bottom one the lower, both the full block */
    Image im;
    memset(&im, 0, sizeof im);
    cr_assert_eq(image_resize(&im, 3, 2), 0);
    memset(im.rgb, 255, 3 * 3 * 2);
    static const uint8_t lit[6] = { 1, 0, 1, /* top row */ 0, 1, 1 };
    memcpy(im.lit, lit, 6);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, MODE_HALF, COLOUR_NONE, &g), 0);
    cr_assert_eq(g.cols, 3);
    cr_assert_eq(g.rows, 1);
    cr_expect_eq(g.cells[0].ch, 0x2580u, "top pixel only: U+2580, not U+%04X", (unsigned)g.cells[0].ch);
    cr_expect_eq(g.cells[1].ch, 0x2584u, "bottom pixel only: U+2584, not U+%04X", (unsigned)g.cells[1].ch);
    cr_expect_eq(g.cells[2].ch, 0x2588u, "both: U+2588, not U+%04X", (unsigned)g.cells[2].ch);
    cells_free(&g);
    image_free(&im);
}

Test(quant, colour_keeps_every_lit_pixel)
{
    /* with colour the glyphs show coverage only: every pixel drawn */
    Image im;
    ramp_image(&im, 16, 8);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, MODE_HALF, COLOUR_256, &g), 0);
    for (size_t i = 0; i < (size_t)g.cols * g.rows; i++)
        cr_expect_eq(g.cells[i].ch, 0x2580u);
    cells_free(&g);
    image_free(&im);
}
