/* Tests of the background and the contrast rule (backdrop.h): --bg's
 * words, lightness, the rule on single colours (the minimum holds, far
 * colours keep their bytes, order and hue are kept, 0 turns it off), on
 * whole images (the memo and the fast test agree with the rule colour by
 * colour), the background an image gets, and the text cells on a light
 * or painted background. */

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "backdrop.h"
#include "present.h"

#define MIN CONTRAST_DEFAULT

static const Backdrop on_black = { { 0, 0, 0 }, 0, BD_GIVEN };
static const Backdrop on_white = { { 255, 255, 255 }, 0, BD_GIVEN };
static const Backdrop on_grey = { { 128, 128, 128 }, 0, BD_GIVEN };

static float L(const uint8_t c[3]) { return backdrop_lightness(c); }

/* One colour under the rule for background b and the default minimum. */
static void lifted(const Backdrop *b, uint8_t r, uint8_t g, uint8_t bl, uint8_t out[3])
{
    Contrast c = { 0 };
    cr_assert_eq(contrast_prepare(&c, b, MIN), 0);
    contrast_colour(&c, (const uint8_t[3]){ r, g, bl }, out);
    contrast_free(&c);
}

/* ==== --bg's words, lightness ==== */

Test(backdrop, parses_names_and_hex)
{
    uint8_t c[3];
    cr_assert_eq(backdrop_parse("white", c), 0);
    cr_expect(c[0] == 255 && c[1] == 255 && c[2] == 255);
    cr_assert_eq(backdrop_parse("black", c), 0);
    cr_expect(c[0] == 0 && c[1] == 0 && c[2] == 0);
    cr_assert_eq(backdrop_parse("#1a2B3c", c), 0);
    cr_expect(c[0] == 0x1a && c[1] == 0x2b && c[2] == 0x3c, "#1a2B3c read as %d,%d,%d", c[0], c[1], c[2]);
    cr_assert_eq(backdrop_parse("#f80", c), 0);
    cr_expect(c[0] == 0xff && c[1] == 0x88 && c[2] == 0x00, "#f80 read as %d,%d,%d", c[0], c[1], c[2]);
    static const char *const bad[] = { "", "#", "#12", "#1234", "#12345g", "navy", "White", "default", "ffffff" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        cr_expect_eq(backdrop_parse(bad[i], c), -1, "'%s' parsed", bad[i]);
    cr_expect_eq(backdrop_parse(NULL, c), -1);
}

Test(backdrop, every_listed_name_parses)
{
    char names[256];
    snprintf(names, sizeof names, "%s", backdrop_names);
    uint8_t c[3];
    int n = 0;
    for (char *w = strtok(names, ", "); w; w = strtok(NULL, ", "), n++)
        cr_expect_eq(backdrop_parse(w, c), 0, "'%s' is listed but does not parse", w);
    cr_expect_geq(n, 4);
}

Test(backdrop, lightness_runs_from_black_to_white)
{
    cr_expect_float_eq(L((const uint8_t[3]){ 0, 0, 0 }), 0.0f, 1e-4f);
    cr_expect_float_eq(L((const uint8_t[3]){ 255, 255, 255 }), 1.0f, 1e-4f);
    /* a mid grey: OKLab's published value for sRGB 128 */
    cr_expect_float_eq(L((const uint8_t[3]){ 128, 128, 128 }), 0.5999f, 1e-3f);
    /* blue is darker than green at the same byte */
    cr_expect_lt(L((const uint8_t[3]){ 0, 0, 200 }), L((const uint8_t[3]){ 0, 200, 0 }));
    /* the primaries and secondaries: OKLab's published L of sRGB's pure
     * colours (Ottosson 2020), each weighing the three cone rows apart */
    static const struct {
        uint8_t rgb[3];
        float l;
    } pure[] = { { { 255, 0, 0 }, 0.62796f },   { { 0, 255, 0 }, 0.86644f },   { { 0, 0, 255 }, 0.45201f },
                 { { 0, 255, 255 }, 0.90540f }, { { 255, 0, 255 }, 0.70167f }, { { 255, 255, 0 }, 0.96798f } };
    for (size_t i = 0; i < sizeof pure / sizeof pure[0]; i++)
        cr_expect_float_eq(L(pure[i].rgb), pure[i].l, 1e-4f, "(%d,%d,%d): %.5f, not %.5f", pure[i].rgb[0],
                           pure[i].rgb[1], pure[i].rgb[2], L(pure[i].rgb), pure[i].l);
    cr_expect(!backdrop_is_light(&on_black));
    cr_expect(backdrop_is_light(&on_white));
    cr_expect(!backdrop_is_light(NULL), "no backdrop: a dark terminal's");
}

/* ==== The rule on colours ==== */

Test(backdrop, navy_and_near_black_on_black_reach_the_minimum)
{
    /* navy lit and in shade, ConcavePolygon.dae's navy, assimp's default
     * grey in shade, near black, black */
    static const uint8_t dark[][3] = { { 0, 0, 128 }, { 0, 0, 28 }, { 10, 13, 29 }, { 17, 17, 17 }, { 3, 3, 3 }, { 0, 0, 0 } };
    for (size_t i = 0; i < sizeof dark / sizeof dark[0]; i++) {
        uint8_t out[3];
        lifted(&on_black, dark[i][0], dark[i][1], dark[i][2], out);
        cr_expect_lt(L(dark[i]), MIN + CONTRAST_KNEE, "(%d,%d,%d) is dark to begin with", dark[i][0], dark[i][1],
                     dark[i][2]);
        cr_expect_geq(L(out), MIN, "(%d,%d,%d) -> (%d,%d,%d): lightness %.4f on black, below %.2f", dark[i][0],
                      dark[i][1], dark[i][2], out[0], out[1], out[2], L(out), MIN);
        cr_expect_leq(L(out), MIN + CONTRAST_KNEE + 1e-3f, "lifted past the band: %.4f", L(out));
    }
    /* navy stays blue: its blue channel leads, red and green stay equal */
    uint8_t navy[3];
    lifted(&on_black, 0, 0, 128, navy);
    cr_expect(navy[2] > navy[0] && navy[2] > navy[1] && navy[0] == navy[1], "navy became (%d,%d,%d)", navy[0],
              navy[1], navy[2]);
}

Test(backdrop, light_colours_on_white_are_darkened_to_the_minimum)
{
    static const uint8_t light[][3] = { { 255, 255, 255 }, { 235, 235, 235 }, { 255, 255, 0 }, { 255, 205, 60 } };
    for (size_t i = 0; i < sizeof light / sizeof light[0]; i++) {
        uint8_t out[3];
        lifted(&on_white, light[i][0], light[i][1], light[i][2], out);
        cr_expect_leq(L(out), 1 - MIN, "(%d,%d,%d) -> (%d,%d,%d): lightness %.4f on white", light[i][0],
                      light[i][1], light[i][2], out[0], out[1], out[2], L(out));
    }
}

Test(backdrop, colours_far_from_the_background_keep_their_bytes)
{
    /* every colour on a coarse grid whose lightness is past the band
     * comes out as it went in, on black and on white */
    int kept = 0;
    for (int r = 0; r < 256; r += 17)
        for (int g = 0; g < 256; g += 17)
            for (int b = 0; b < 256; b += 17) {
                uint8_t in[3] = { (uint8_t)r, (uint8_t)g, (uint8_t)b }, out[3];
                float l = L(in);
                if (l >= MIN + CONTRAST_KNEE + 1e-3f) {
                    lifted(&on_black, in[0], in[1], in[2], out);
                    cr_expect(!memcmp(in, out, 3), "(%d,%d,%d) at %.3f changed on black", r, g, b, l);
                    kept++;
                }
                if (l <= 1 - MIN - CONTRAST_KNEE - 1e-3f) {
                    lifted(&on_white, in[0], in[1], in[2], out);
                    cr_expect(!memcmp(in, out, 3), "(%d,%d,%d) at %.3f changed on white", r, g, b, l);
                }
            }
    cr_expect_gt(kept, 1000);
    /* the ambient side of the default grey (200 x 0.22) is just inside
     * the band: it moves, but little */
    uint8_t shade[3];
    lifted(&on_black, 44, 44, 44, shade);
    cr_expect(shade[0] > 44 && shade[0] < 56, "grey 44 on black became %d", shade[0]);
}

Test(backdrop, order_is_kept_and_nothing_jumps)
{
    /* the greys from black to white, on black and on white: lightness
     * never goes down, and neighbours never part by more than they did
     * (the curve's slope is at most 1; a byte's rounding aside) */
    const Backdrop *bds[2] = { &on_black, &on_white };
    for (int k = 0; k < 2; k++) {
        float last = -1, last_in = 0;
        for (int v = 0; v < 256; v++) {
            uint8_t out[3], in[3] = { (uint8_t)v, (uint8_t)v, (uint8_t)v };
            lifted(bds[k], in[0], in[1], in[2], out);
            float l = L(out);
            cr_expect_geq(l, last - 1e-3f, "grey %d on %s: %.4f after %.4f", v, k ? "white" : "black", l, last);
            if (last >= 0)
                cr_expect_leq(l - last, L(in) - last_in + 0.006f, "grey %d on %s jumps from %.4f to %.4f", v,
                              k ? "white" : "black", last, l);
            last = l;
            last_in = L(in);
        }
    }
}

Test(backdrop, a_mid_grey_background_sends_each_side_its_own_way)
{
    float bg = L(on_grey.rgb);
    uint8_t up[3], down[3];
    lifted(&on_grey, 140, 140, 140, up);     /* a little lighter than the background */
    lifted(&on_grey, 118, 118, 118, down);   /* a little darker */
    cr_expect_geq(L(up), bg + MIN, "lighter grey on grey: %.4f, background %.4f", L(up), bg);
    cr_expect_leq(L(down), bg - MIN, "darker grey on grey: %.4f, background %.4f", L(down), bg);
}

Test(backdrop, zero_keeps_every_colour)
{
    Image im = { 0 };
    cr_assert_eq(image_resize(&im, 64, 64), 0);
    for (int i = 0; i < 64 * 64; i++) {
        im.rgb[3 * i] = (uint8_t)(i * 7);
        im.rgb[3 * i + 1] = (uint8_t)(i / 64);
        im.rgb[3 * i + 2] = (uint8_t)(i % 5);
        im.lit[i] = 1;
    }
    uint8_t *before = malloc(3 * 64 * 64);
    memcpy(before, im.rgb, 3 * 64 * 64);
    Contrast c = { 0 };
    cr_assert_eq(contrast_apply(&c, &on_black, 0, &im), 0);
    cr_expect(!memcmp(before, im.rgb, 3 * 64 * 64), "--contrast 0 changed a colour");
    cr_assert_eq(contrast_apply(&c, &on_black, MIN, &im), 0);
    cr_expect(memcmp(before, im.rgb, 3 * 64 * 64), "the rule changed nothing: the test shows nothing");
    contrast_free(&c);
    free(before);
    image_free(&im);
}

/* ==== The rule on images ==== */

/* Every colour of a grid, one a pixel, the grid's last row unlit. */
static void grid_image(Image *im, int step)
{
    int n = 256 / step + 1, k = 0;
    cr_assert_eq(image_resize(im, n * n, n + 1), 0);
    for (int r = 0; r < n; r++)
        for (int g = 0; g < n; g++)
            for (int b = 0; b < n; b++, k++) {
                im->rgb[3 * k] = (uint8_t)(r * step > 255 ? 255 : r * step);
                im->rgb[3 * k + 1] = (uint8_t)(g * step > 255 ? 255 : g * step);
                im->rgb[3 * k + 2] = (uint8_t)(b * step > 255 ? 255 : b * step);
                im->lit[k] = 1;
            }
    for (; k < im->w * im->h; k++) {
        im->rgb[3 * k] = im->rgb[3 * k + 1] = im->rgb[3 * k + 2] = 0;
        im->lit[k] = 0;
    }
}

Test(backdrop, an_image_gets_what_each_colour_gets)
{
    /* the fast test and the memo must agree with the rule colour by
     * colour, and the minimum must hold for every drawn pixel; twice, so
     * that the second pass comes from the memo */
    const Backdrop *bds[3] = { &on_black, &on_white, &on_grey };
    for (int k = 0; k < 3; k++) {
        Image im = { 0 }, ref = { 0 };
        grid_image(&im, 5);
        grid_image(&ref, 5);
        Contrast c = { 0 }, one = { 0 };
        cr_assert_eq(contrast_prepare(&one, bds[k], MIN), 0);
        for (int pass = 0; pass < 2; pass++) {
            grid_image(&im, 5);
            cr_assert_eq(contrast_apply(&c, bds[k], MIN, &im), 0);
        }
        float bg = L(bds[k]->rgb);
        int bad = 0, unlit_changed = 0;
        for (int i = 0; i < im.w * im.h; i++) {
            if (!im.lit[i]) {
                unlit_changed += im.rgb[3 * i] != 0;
                continue;
            }
            uint8_t want[3];
            contrast_colour(&one, ref.rgb + 3 * i, want);
            if (memcmp(want, im.rgb + 3 * i, 3) && bad++ < 3)
                cr_expect_fail("background %d: (%d,%d,%d) became (%d,%d,%d) in the image, (%d,%d,%d) alone", k,
                               ref.rgb[3 * i], ref.rgb[3 * i + 1], ref.rgb[3 * i + 2], im.rgb[3 * i],
                               im.rgb[3 * i + 1], im.rgb[3 * i + 2], want[0], want[1], want[2]);
            float d = fabsf(L(im.rgb + 3 * i) - bg);
            if (d < MIN - 1e-4f && bad++ < 3)
                cr_expect_fail("background %d: (%d,%d,%d) ends %.4f from it", k, im.rgb[3 * i], im.rgb[3 * i + 1],
                               im.rgb[3 * i + 2], d);
        }
        cr_expect_eq(bad, 0);
        cr_expect_eq(unlit_changed, 0, "the rule touched the background's pixels");
        contrast_free(&c);
        contrast_free(&one);
        image_free(&im);
        image_free(&ref);
    }
}

/* ==== The background an image gets ==== */

static void fill(Image *im, int w, int h, const uint8_t rgb[3], int lit_share_percent)
{
    cr_assert_eq(image_resize(im, w, h), 0);
    for (int i = 0; i < w * h; i++) {
        memcpy(im->rgb + 3 * i, rgb, 3);
        im->lit[i] = i % 100 < lit_share_percent;
    }
}

Test(backdrop, a_dark_model_gets_white_and_a_light_one_black)
{
    Image im = { 0 };
    fill(&im, 20, 10, (const uint8_t[3]){ 10, 13, 29 }, 50);
    Backdrop b = backdrop_pick(&im, MIN);
    cr_expect(b.rgb[0] == 255 && b.rgb[1] == 255 && b.rgb[2] == 255 && b.paint && b.source == BD_PICKED,
              "navy got (%d,%d,%d)", b.rgb[0], b.rgb[1], b.rgb[2]);
    fill(&im, 20, 10, (const uint8_t[3]){ 200, 200, 200 }, 50);
    b = backdrop_pick(&im, MIN);
    cr_expect(b.rgb[0] == 0 && b.rgb[1] == 0 && b.rgb[2] == 0, "light grey got (%d,%d,%d)", b.rgb[0], b.rgb[1],
              b.rgb[2]);
    /* a mid grey is near neither: black, as an empty picture */
    fill(&im, 20, 10, (const uint8_t[3]){ 128, 128, 128 }, 50);
    cr_expect_eq(backdrop_pick(&im, MIN).rgb[0], 0);
    fill(&im, 20, 10, (const uint8_t[3]){ 0, 0, 0 }, 0);
    cr_expect_eq(backdrop_pick(&im, MIN).rgb[0], 0, "nothing drawn: black");
    image_free(&im);
}

Test(backdrop, painting_fills_only_the_background)
{
    Image im = { 0 };
    fill(&im, 10, 10, (const uint8_t[3]){ 1, 2, 3 }, 30);
    backdrop_paint(&im, &on_white);
    for (int i = 0; i < 100; i++) {
        const uint8_t *p = im.rgb + 3 * i;
        if (im.lit[i])
            cr_expect(p[0] == 1 && p[1] == 2 && p[2] == 3, "drawn pixel %d painted", i);
        else
            cr_expect(p[0] == 255 && p[1] == 255 && p[2] == 255, "background pixel %d not painted", i);
    }
    image_free(&im);
}

/* ==== Text cells on a light or painted background ==== */

Test(backdrop, ascii_on_a_light_background_draws_darkness)
{
    Image im = { 0 };
    cr_assert_eq(image_resize(&im, 2, 1), 0);
    memset(im.rgb, 0, 6);
    memset(im.rgb + 3, 255, 3);        /* black, white */
    im.lit[0] = im.lit[1] = 1;
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image_on(&im, MODE_ASCII, COLOUR_NONE, &on_black, &g), 0);
    uint32_t dark_on_dark = g.cells[0].ch, light_on_dark = g.cells[1].ch;
    cr_assert_eq(cells_from_image_on(&im, MODE_ASCII, COLOUR_NONE, &on_white, &g), 0);
    uint32_t dark_on_light = g.cells[0].ch, light_on_light = g.cells[1].ch;
    cr_expect_eq(light_on_dark, (uint32_t)'@', "white on a dark terminal: the densest glyph");
    cr_expect_eq(dark_on_light, (uint32_t)'@', "black on a light terminal: the densest glyph");
    cr_expect_eq(dark_on_dark, light_on_light, "the faintest glyph for what is like the paper");
    cr_expect_neq(dark_on_dark, (uint32_t)'@');
    cells_free(&g);
    image_free(&im);
}

/* Dots set by the mono dither over a uniform patch of colour rgb. */
static int mono_dots(const uint8_t rgb[3], const Backdrop *bd)
{
    Image im = { 0 };
    fill(&im, 16, 16, rgb, 100);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image_on(&im, MODE_BRAILLE, COLOUR_NONE, bd, &g), 0);
    int dots = 0;
    for (int i = 0; i < g.cols * g.rows; i++)
        dots += __builtin_popcount(g.cells[i].ch >= 0x2800u ? g.cells[i].ch - 0x2800u : 0);
    cells_free(&g);
    image_free(&im);
    return dots;
}

Test(backdrop, mono_dots_follow_the_ink)
{
    static const uint8_t dark[3] = { 40, 40, 40 }, light[3] = { 220, 220, 220 };
    cr_expect_gt(mono_dots(light, &on_black), mono_dots(dark, &on_black), "on black a light face is the denser");
    cr_expect_gt(mono_dots(dark, &on_white), mono_dots(light, &on_white), "on white a dark face is the denser");
}

Test(backdrop, a_painted_background_fills_every_cell)
{
    Image im = { 0 };
    cr_assert_eq(image_resize(&im, 3, 2), 0);
    memset(im.rgb, 90, 18);
    memset(im.lit, 0, 6);
    im.lit[0] = 1;                      /* only the first cell's top half */
    Backdrop paper = { { 250, 240, 230 }, 1, BD_GIVEN };
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image_on(&im, MODE_HALF, COLOUR_TRUE, &paper, &g), 0);
    for (int i = 0; i < g.cols * g.rows; i++)
        cr_expect((g.cells[i].flags & CELL_BG) && g.cells[i].bg[0] == 250 && g.cells[i].bg[2] == 230,
                  "cell %d: flags %d, bg (%d,%d,%d)", i, g.cells[i].flags, g.cells[i].bg[0], g.cells[i].bg[1],
                  g.cells[i].bg[2]);
    cr_expect_eq(g.cells[0].ch, 0x2580u);
    cr_expect_eq(g.cells[0].fg[0], 90);
    /* the terminal's own background: nothing painted */
    Backdrop own = paper;
    own.paint = 0;
    cr_assert_eq(cells_from_image_on(&im, MODE_HALF, COLOUR_TRUE, &own, &g), 0);
    cr_expect(!(g.cells[1].flags & CELL_BG), "an unpainted background was painted");
    cells_free(&g);
    image_free(&im);
}
