/* Tests of the presenters: pixels -> cells in each mode, cells -> bytes
 * in each colour depth, the palettes, the environment defaults, and the
 * PNG / PPM writers read back. */

#define _POSIX_C_SOURCE 200809L
#include <criterion/criterion.h>
#include <errno.h>
#include <locale.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "present.h"
#include "tty.h"

/* ==== Helpers ==== */

static void img_init(Image *im, int w, int h)
{
    memset(im, 0, sizeof *im);
    cr_assert_eq(image_resize(im, w, h), 0);
    memset(im->rgb, 0, 3 * (size_t)w * h);
    memset(im->lit, 0, (size_t)w * h);
}

static void img_set(Image *im, int x, int y, uint8_t r, uint8_t g, uint8_t b)
{
    size_t i = (size_t)y * im->w + x;
    im->rgb[3 * i] = r;
    im->rgb[3 * i + 1] = g;
    im->rgb[3 * i + 2] = b;
    im->lit[i] = 1;
}

#define EXPECT_RGB(c, r, g, b) \
    cr_expect((c)[0] == (r) && (c)[1] == (g) && (c)[2] == (b), \
              "%s = %d,%d,%d, want %d,%d,%d", #c, (c)[0], (c)[1], (c)[2], r, g, b)

/* Prints the bytes escaped, so a failing comparison shows both sides. */
static void expect_bytes(const char *got, size_t len, const char *want)
{
    size_t wl = strlen(want);
    if (len == wl && memcmp(got, want, wl) == 0)
        return;
    char a[1024], b[1024];
    size_t ia = 0, ib = 0;
    for (size_t i = 0; i < len && ia < sizeof a - 5; i++)
        ia += (size_t)snprintf(a + ia, sizeof a - ia, (unsigned char)got[i] < 32 || (unsigned char)got[i] > 126 ? "\\x%02x" : "%c", (unsigned char)got[i]);
    for (size_t i = 0; i < wl && ib < sizeof b - 5; i++)
        ib += (size_t)snprintf(b + ib, sizeof b - ib, (unsigned char)want[i] < 32 || (unsigned char)want[i] > 126 ? "\\x%02x" : "%c", (unsigned char)want[i]);
    cr_expect_fail("got  %s\nwant %s", a, b);
}

static Cell cell(uint32_t ch, int fr, int fg_, int fb, int br, int bg_, int bb, int flags)
{
    Cell c;
    memset(&c, 0, sizeof c);
    c.ch = ch;
    c.fg[0] = (uint8_t)fr; c.fg[1] = (uint8_t)fg_; c.fg[2] = (uint8_t)fb;
    c.bg[0] = (uint8_t)br; c.bg[1] = (uint8_t)bg_; c.bg[2] = (uint8_t)bb;
    c.flags = (uint8_t)flags;
    return c;
}

/* ==== Modes ==== */

Test(present, mode_geometry)
{
    int w, h;
    mode_cell_pixels(MODE_HALF, &w, &h);
    cr_expect(w == 1 && h == 2);
    mode_cell_pixels(MODE_ASCII, &w, &h);
    cr_expect(w == 1 && h == 1);
    mode_cell_pixels(MODE_BRAILLE, &w, &h);
    cr_expect(w == 2 && h == 4);
    cr_expect_float_eq(mode_pixel_aspect(MODE_HALF), 1.0f, 1e-6);
    cr_expect_float_eq(mode_pixel_aspect(MODE_ASCII), 2.0f, 1e-6);
    cr_expect_float_eq(mode_pixel_aspect(MODE_BRAILLE), 1.0f, 1e-6);
}

/* ==== Half blocks ==== */

Test(present, half_blocks)
{
    Image im;
    img_init(&im, 4, 2);
    img_set(&im, 0, 0, 255, 0, 0);          /* top red, bottom blue */
    img_set(&im, 0, 1, 0, 0, 255);
    img_set(&im, 1, 1, 0, 200, 0);          /* only the bottom lit */
    img_set(&im, 3, 0, 9, 8, 7);            /* only the top lit */
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, MODE_HALF, COLOUR_TRUE, &g), 0);
    cr_assert_eq(g.cols, 4);
    cr_assert_eq(g.rows, 1);

    cr_expect_eq(g.cells[0].ch, 0x2580u);
    cr_expect_eq(g.cells[0].flags, CELL_FG | CELL_BG);
    EXPECT_RGB(g.cells[0].fg, 255, 0, 0);
    EXPECT_RGB(g.cells[0].bg, 0, 0, 255);

    cr_expect_eq(g.cells[1].ch, 0x2584u);
    cr_expect_eq(g.cells[1].flags, CELL_FG);
    EXPECT_RGB(g.cells[1].fg, 0, 200, 0);

    cr_expect_eq(g.cells[2].ch, (uint32_t)' ');
    cr_expect_eq(g.cells[2].flags, 0);

    cr_expect_eq(g.cells[3].ch, 0x2580u);
    cr_expect_eq(g.cells[3].flags, CELL_FG);
    EXPECT_RGB(g.cells[3].fg, 9, 8, 7);
    cells_free(&g);
    image_free(&im);
}

Test(present, half_odd_height_pads_with_background)
{
    Image im;
    img_init(&im, 1, 3);
    img_set(&im, 0, 2, 1, 2, 3);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, MODE_HALF, COLOUR_TRUE, &g), 0);
    cr_assert_eq(g.rows, 2);
    cr_expect_eq(g.cells[0].ch, (uint32_t)' ');
    cr_expect_eq(g.cells[1].ch, 0x2580u);
    cr_expect_eq(g.cells[1].flags, CELL_FG);
    EXPECT_RGB(g.cells[1].fg, 1, 2, 3);
    cells_free(&g);
    image_free(&im);
}

/* ==== Ascii ==== */

Test(present, ascii_ramp)
{
    Image im;
    img_init(&im, 5, 1);
    img_set(&im, 0, 0, 255, 255, 255);
    img_set(&im, 1, 0, 1, 1, 1);            /* nearly black but lit */
    img_set(&im, 2, 0, 60, 60, 60);
    img_set(&im, 3, 0, 160, 160, 160);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, MODE_ASCII, COLOUR_TRUE, &g), 0);
    cr_assert_eq(g.cols, 5);
    cr_assert_eq(g.rows, 1);
    cr_expect_eq(g.cells[0].ch, (uint32_t)'@');
    cr_expect_neq(g.cells[1].ch, (uint32_t)' ', "a lit pixel never vanishes");
    cr_expect_eq(g.cells[4].ch, (uint32_t)' ');
    cr_expect_eq(g.cells[4].flags, 0);
    /* Brighter pixels use glyphs further along the ramp. */
    const char *ramp = " .:-=+*#%@";
    int pos[4];
    for (int i = 0; i < 4; i++) {
        const char *q = strchr(ramp, (int)g.cells[i].ch);
        cr_assert_not_null(q, "cell %d: '%c' not in the ramp", i, (int)g.cells[i].ch);
        pos[i] = (int)(q - ramp);
        cr_expect_eq(g.cells[i].flags, CELL_FG);
    }
    cr_expect(pos[1] < pos[2] && pos[2] < pos[3] && pos[3] < pos[0], "%d %d %d %d",
              pos[1], pos[2], pos[3], pos[0]);
    EXPECT_RGB(g.cells[2].fg, 60, 60, 60);
    cells_free(&g);
    image_free(&im);
}

/* ==== Braille ==== */

static uint32_t braille_of(const int lit[4][2])
{
    Image im;
    img_init(&im, 2, 4);
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 2; x++)
            if (lit[y][x])
                img_set(&im, x, y, 10, 20, 30);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, MODE_BRAILLE, COLOUR_TRUE, &g), 0);
    cr_assert_eq(g.cols, 1);
    cr_assert_eq(g.rows, 1);
    uint32_t ch = g.cells[0].ch;
    cells_free(&g);
    image_free(&im);
    return ch;
}

Test(present, braille_dot_bits)
{
    static const int none[4][2] = { { 0 } };
    static const int all[4][2] = { { 1, 1 }, { 1, 1 }, { 1, 1 }, { 1, 1 } };
    static const int dot1[4][2] = { { 1, 0 } };
    static const int dot4[4][2] = { { 0, 1 } };
    static const int dot7[4][2] = { { 0, 0 }, { 0, 0 }, { 0, 0 }, { 1, 0 } };
    static const int dot8[4][2] = { { 0, 0 }, { 0, 0 }, { 0, 0 }, { 0, 1 } };
    static const int left[4][2] = { { 1, 0 }, { 1, 0 }, { 1, 0 }, { 1, 0 } };
    static const int right[4][2] = { { 0, 1 }, { 0, 1 }, { 0, 1 }, { 0, 1 } };
    static const int diag[4][2] = { { 1, 0 }, { 0, 1 }, { 1, 0 }, { 0, 1 } };
    cr_expect_eq(braille_of(none), (uint32_t)' ');
    cr_expect_eq(braille_of(all), 0x28ffu);
    cr_expect_eq(braille_of(dot1), 0x2801u);
    cr_expect_eq(braille_of(dot4), 0x2808u);
    cr_expect_eq(braille_of(dot7), 0x2840u);
    cr_expect_eq(braille_of(dot8), 0x2880u);
    cr_expect_eq(braille_of(left), 0x2847u);    /* dots 1 2 3 7 */
    cr_expect_eq(braille_of(right), 0x28b8u);   /* dots 4 5 6 8 */
    cr_expect_eq(braille_of(diag), 0x2800u + 0x01 + 0x10 + 0x04 + 0x80);
}

Test(present, braille_colour_is_mean_of_lit_dots)
{
    Image im;
    img_init(&im, 4, 4);                    /* two cells side by side */
    img_set(&im, 0, 0, 100, 0, 0);
    img_set(&im, 1, 3, 200, 30, 1);
    img_set(&im, 0, 2, 0, 90, 2);
    CellGrid g = { 0 };
    cr_assert_eq(cells_from_image(&im, MODE_BRAILLE, COLOUR_TRUE, &g), 0);
    cr_assert_eq(g.cols, 2);
    cr_assert_eq(g.rows, 1);
    cr_expect_eq(g.cells[0].ch, 0x2800u + 0x01 + 0x80 + 0x04);
    cr_expect_eq(g.cells[0].flags, CELL_FG);
    EXPECT_RGB(g.cells[0].fg, 100, 40, 1);
    cr_expect_eq(g.cells[1].ch, (uint32_t)' ');
    cr_expect_eq(g.cells[1].flags, 0);
    cells_free(&g);
    image_free(&im);
}

/* ==== Printing ==== */

/* Row 0: two identical red-on-blue half blocks (one escape pair), row 1:
 * an empty cell (no escapes, no reset). */
static CellGrid two_rows(Cell *store)
{
    store[0] = cell(0x2580, 255, 0, 0, 0, 0, 255, CELL_FG | CELL_BG);
    store[1] = store[0];
    store[2] = cell(' ', 0, 0, 0, 0, 0, 0, 0);
    store[3] = cell('x', 0, 0, 0, 0, 0, 0, 0);
    CellGrid g = { .cols = 2, .rows = 2, .cells = store, .cap = 4 };
    return g;
}

static void expect_print(const CellGrid *g, ColourDepth c, const char *want)
{
    size_t len = 0;
    char *s = print_cells_to_string(g, c, &len);
    cr_assert_not_null(s);
    expect_bytes(s, len, want);
    free(s);
}

Test(present, print_each_depth)
{
    Cell st[4];
    CellGrid g = two_rows(st);
    expect_print(&g, COLOUR_TRUE,
                 "\x1b[38;2;255;0;0m\x1b[48;2;0;0;255m\xe2\x96\x80\xe2\x96\x80\x1b[0m\n x\n");
    expect_print(&g, COLOUR_256,
                 "\x1b[38;5;196m\x1b[48;5;21m\xe2\x96\x80\xe2\x96\x80\x1b[0m\n x\n");
    expect_print(&g, COLOUR_16,
                 "\x1b[91m\x1b[44m\xe2\x96\x80\xe2\x96\x80\x1b[0m\n x\n");
    expect_print(&g, COLOUR_NONE, "\xe2\x96\x80\xe2\x96\x80\n x\n");
}

Test(present, print_changes_only)
{
    Cell st[4] = {
        cell('a', 255, 0, 0, 0, 0, 0, CELL_FG),
        cell('b', 0, 255, 0, 0, 0, 0, CELL_FG),
        cell(' ', 0, 0, 0, 0, 0, 0, 0),          /* back to the default fg */
        cell(0x2847, 0, 255, 0, 0, 0, 0, CELL_FG),
    };
    CellGrid g = { .cols = 4, .rows = 1, .cells = st, .cap = 4 };
    expect_print(&g, COLOUR_TRUE,
                 "\x1b[38;2;255;0;0ma\x1b[38;2;0;255;0mb\x1b[39m \x1b[38;2;0;255;0m\xe2\xa1\x87\x1b[0m\n");
    /* 256: two reds one index apart in RGB but the same index: one escape. */
    st[1] = cell('b', 250, 5, 5, 0, 0, 0, CELL_FG);
    expect_print(&g, COLOUR_256,
                 "\x1b[38;5;196mab\x1b[39m \x1b[38;5;46m\xe2\xa1\x87\x1b[0m\n");
    /* 16: dim colours use 30-37. */
    st[0] = cell('a', 205, 0, 0, 0, 0, 0, CELL_FG);
    st[1] = cell('b', 0, 0, 0, 0, 205, 205, CELL_FG | CELL_BG);
    st[3] = cell('c', 255, 255, 255, 0, 0, 0, CELL_FG);
    expect_print(&g, COLOUR_16,
                 "\x1b[31ma\x1b[30m\x1b[46mb\x1b[39m\x1b[49m \x1b[97mc\x1b[0m\n");
}

Test(present, print_cells_writes_the_same_bytes)
{
    Cell st[4];
    CellGrid g = two_rows(st);
    FILE *f = tmpfile();
    cr_assert_not_null(f);
    cr_assert_eq(print_cells(f, &g, COLOUR_TRUE), 0);
    long n = ftell(f);
    rewind(f);
    char buf[256];
    size_t got = fread(buf, 1, sizeof buf, f);
    fclose(f);
    size_t len;
    char *s = print_cells_to_string(&g, COLOUR_TRUE, &len);
    cr_assert_eq((size_t)n, len);
    cr_assert_eq(got, len);
    cr_expect_eq(memcmp(buf, s, len), 0);
    free(s);
}

/* ==== Palettes ==== */

static int sqd(const uint8_t a[3], const uint8_t b[3])
{
    int d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

Test(present, palette_256_known_values)
{
    static const struct { uint8_t rgb[3]; int idx; } k[] = {
        { { 255, 0, 0 }, 196 }, { { 0, 255, 0 }, 46 }, { { 0, 0, 255 }, 21 },
        { { 255, 255, 255 }, 231 }, { { 0, 0, 0 }, 16 }, { { 255, 255, 0 }, 226 },
        { { 95, 135, 175 }, 67 }, { { 128, 128, 128 }, 244 }, { { 8, 8, 8 }, 232 },
        { { 238, 238, 238 }, 255 }, { { 100, 100, 100 }, 241 }, { { 50, 50, 50 }, 236 },
    };
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        cr_expect_eq(palette_256(k[i].rgb), k[i].idx, "%d,%d,%d -> %d, want %d",
                     k[i].rgb[0], k[i].rgb[1], k[i].rgb[2], palette_256(k[i].rgb), k[i].idx);
    /* Every entry maps to itself. */
    for (int i = 16; i < 256; i++) {
        uint8_t c[3];
        palette_256_rgb(i, c);
        cr_expect_eq(palette_256(c), i, "index %d", i);
    }
}

Test(present, palette_256_is_nearest)
{
    /* Compare with an exhaustive search over a lattice of colours. */
    uint8_t pal[256][3];
    for (int i = 0; i < 256; i++)
        palette_256_rgb(i, pal[i]);
    for (int r = 0; r < 256; r += 7)
        for (int g = 0; g < 256; g += 11)
            for (int b = 0; b < 256; b += 13) {
                uint8_t c[3] = { (uint8_t)r, (uint8_t)g, (uint8_t)b };
                int best = 1 << 30;
                for (int i = 16; i < 256; i++)
                    if (sqd(c, pal[i]) < best)
                        best = sqd(c, pal[i]);
                int got = palette_256(c);
                cr_assert(got >= 16 && got <= 255);
                cr_assert_eq(sqd(c, pal[got]), best, "%d,%d,%d -> %d", r, g, b, got);
            }
}

Test(present, palette_16)
{
    uint8_t red[3] = { 255, 0, 0 }, black[3] = { 0, 0, 0 }, white[3] = { 255, 255, 255 };
    uint8_t dimred[3] = { 200, 10, 0 }, grey[3] = { 120, 125, 130 }, blue[3] = { 0, 0, 255 };
    cr_expect_eq(palette_16(red), 9);
    cr_expect_eq(palette_16(black), 0);
    cr_expect_eq(palette_16(white), 15);
    cr_expect_eq(palette_16(dimred), 1);
    cr_expect_eq(palette_16(grey), 8);
    cr_expect_eq(palette_16(blue), 4);
    for (int i = 0; i < 16; i++) {
        uint8_t c[3];
        palette_256_rgb(i, c);
        cr_expect_eq(palette_16(c), i);
    }
}

/* ==== Names and environment ==== */

Test(present, names)
{
    for (int i = 0; i < MODE_COUNT; i++)
        cr_expect_eq(mode_from_name(mode_names[i]), i);
    cr_expect_str_eq(mode_names[MODE_HALF], "half");
    cr_expect_str_eq(mode_names[MODE_ASCII], "ascii");
    cr_expect_str_eq(mode_names[MODE_BRAILLE], "braille");
    cr_expect_eq(mode_from_name("sixel"), -1);
    cr_expect_eq(colour_from_name("none"), COLOUR_NONE);
    cr_expect_eq(colour_from_name("16"), COLOUR_16);
    cr_expect_eq(colour_from_name("256"), COLOUR_256);
    cr_expect_eq(colour_from_name("truecolor"), COLOUR_TRUE);
    cr_expect_eq(colour_from_name("17"), -1);
    cr_expect_eq(colour_from_name(NULL), -1);
    for (int c = COLOUR_NONE; c <= COLOUR_TRUE; c++)
        cr_expect_eq(colour_from_name(colour_name((ColourDepth)c)), c);
}

static ColourDepth env_case(const char *no_colour, const char *colourterm, const char *term)
{
    if (no_colour) setenv("NO_COLOR", no_colour, 1); else unsetenv("NO_COLOR");
    if (colourterm) setenv("COLORTERM", colourterm, 1); else unsetenv("COLORTERM");
    if (term) setenv("TERM", term, 1); else unsetenv("TERM");
    return colour_from_env();
}

Test(present, colour_from_env)
{
    cr_expect_eq(env_case("1", "truecolor", "xterm-256color"), COLOUR_NONE);
    cr_expect_eq(env_case("", NULL, "xterm-256color"), COLOUR_256, "empty NO_COLOR is ignored");
    cr_expect_eq(env_case(NULL, "truecolor", "xterm"), COLOUR_TRUE);
    cr_expect_eq(env_case(NULL, "24bit", "screen"), COLOUR_TRUE);
    cr_expect_eq(env_case(NULL, NULL, "xterm-direct"), COLOUR_TRUE);
    cr_expect_eq(env_case(NULL, NULL, "xterm-256color"), COLOUR_256);
    cr_expect_eq(env_case(NULL, "yes", "screen-256color"), COLOUR_256);
    cr_expect_eq(env_case(NULL, NULL, "xterm"), COLOUR_16);
    cr_expect_eq(env_case(NULL, NULL, "linux"), COLOUR_16);
    cr_expect_eq(env_case(NULL, NULL, "dumb"), COLOUR_NONE);
    cr_expect_eq(env_case(NULL, NULL, ""), COLOUR_NONE);
    cr_expect_eq(env_case(NULL, NULL, NULL), COLOUR_NONE);
}

Test(present, mode_from_locale)
{
    cr_assert_not_null(setlocale(LC_ALL, "C"));
    cr_expect_eq(mode_from_locale(), MODE_ASCII);
    if (setlocale(LC_ALL, "C.UTF-8") || setlocale(LC_ALL, "en_US.UTF-8"))
        cr_expect_eq(mode_from_locale(), MODE_HALF);
    else
        cr_log_warn("no UTF-8 locale installed; half-mode default not checked");
    setlocale(LC_ALL, "C");
}

/* ==== Image writers ==== */

static void tmp_path(char *buf, size_t n, const char *ext)
{
    const char *dir = getenv("TMPDIR");
    snprintf(buf, n, "%s/zview-test-%ld%s", dir && *dir ? dir : "/tmp", (long)getpid(), ext);
}

static void gradient(Image *im, int w, int h)
{
    img_init(im, w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            img_set(im, x, y, (uint8_t)(x * 40), (uint8_t)(y * 70), (uint8_t)(x * 7 + y * 31 + 1));
}

Test(present, png_round_trip)
{
    Image im;
    gradient(&im, 5, 3);
    char path[512], err[256] = "";
    tmp_path(path, sizeof path, ".png");
    cr_assert_eq(write_png(path, &im, err, sizeof err), 0, "%s", err);

    png_image rd;
    memset(&rd, 0, sizeof rd);
    rd.version = PNG_IMAGE_VERSION;
    cr_assert(png_image_begin_read_from_file(&rd, path), "%s", rd.message);
    cr_expect_eq(rd.width, 5u);
    cr_expect_eq(rd.height, 3u);
    rd.format = PNG_FORMAT_RGB;
    uint8_t back[5 * 3 * 3];
    cr_assert_eq(PNG_IMAGE_SIZE(rd), sizeof back);
    cr_assert(png_image_finish_read(&rd, NULL, back, 0, NULL), "%s", rd.message);
    cr_expect_eq(memcmp(back, im.rgb, sizeof back), 0, "pixels differ after the round trip");
    unlink(path);
    image_free(&im);
}

Test(present, ppm_header_and_bytes)
{
    Image im;
    gradient(&im, 3, 2);
    char path[512], err[256] = "";
    tmp_path(path, sizeof path, ".ppm");
    cr_assert_eq(write_ppm(path, &im, err, sizeof err), 0, "%s", err);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f);
    char buf[64];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    const char *hdr = "P6\n3 2\n255\n";
    size_t hl = strlen(hdr);
    cr_assert_eq(n, hl + 18);
    cr_expect_eq(memcmp(buf, hdr, hl), 0);
    cr_expect_eq(memcmp(buf + hl, im.rgb, 18), 0);
    unlink(path);
    image_free(&im);
}

Test(present, writers_report_path_and_reason)
{
    Image im;
    gradient(&im, 2, 2);
    const char *bad = "/nonexistent-zview-dir/out.png";
    char err[256] = "";
    cr_expect_eq(write_png(bad, &im, err, sizeof err), -1);
    cr_expect_str_eq(err, "/nonexistent-zview-dir/out.png: No such file or directory");
    err[0] = '\0';
    cr_expect_eq(write_ppm("/nonexistent-zview-dir/out.ppm", &im, err, sizeof err), -1);
    cr_expect_str_eq(err, "/nonexistent-zview-dir/out.ppm: No such file or directory");
    image_free(&im);
}

/* ==== Checked output ==== */

Test(present, checked_output_keeps_the_first_failure)
{
    FILE *f = fopen("/dev/full", "w");
    if (!f)
        cr_skip_test("no /dev/full");
    Out o;
    out_init(&o, f, "/dev/full");
    /* buffered: the write itself may pass, the flush cannot */
    out_printf(&o, "%s", "hello");
    cr_expect_eq(out_flush(&o), -1);
    cr_expect_eq(o.err, ENOSPC);
    /* a later success must not hide it, nor a later failure change it */
    errno = EINTR;
    cr_expect_eq(out_write(&o, "x", 1), -1);
    cr_expect_eq(o.err, ENOSPC);
    cr_expect_eq(out_close(&o), -1);
    cr_expect_str_eq(out_error(&o), strerror(ENOSPC));
}

Test(present, checked_output_passes_good_writes)
{
    FILE *f = tmpfile();
    cr_assert_not_null(f);
    Out o;
    out_init(&o, f, "tmp");
    cr_expect_eq(out_printf(&o, "%d-%s", 42, "ok"), 0);
    cr_expect_eq(out_write(&o, "!", 1), 0);
    cr_expect_eq(out_flush(&o), 0);
    rewind(f);
    char buf[16] = "";
    cr_expect_eq(fread(buf, 1, sizeof buf - 1, f), 6);
    cr_expect_str_eq(buf, "42-ok!");
    cr_expect_eq(out_close(&o), 0);
}

Test(present, print_cells_reports_a_full_device)
{
    FILE *f = fopen("/dev/full", "w");
    if (!f)
        cr_skip_test("no /dev/full");
    Cell st[4];
    CellGrid g = two_rows(st);
    errno = 0;
    cr_expect_eq(print_cells(f, &g, COLOUR_256), -1);
    cr_expect_eq(errno, ENOSPC);
    fclose(f);
}

/* ==== The viewer's input ==== */

/* Input at its end (here /dev/null) makes every read return at once: the
 * viewer must learn that no key will come, or it spins waiting. */
Test(present, term_read_reports_the_end_of_input)
{
    FILE *out = tmpfile(), *in = fopen("/dev/null", "r");
    cr_assert(out && in);
    char err[128];
    TermConfig cfg = { .out = out, .in = in, .termname = "xterm-256color", .colour = COLOUR_256 };
    if (term_open(&cfg, err, sizeof err))
        cr_skip_test("no xterm-256color description: %s", err);
    TermEvent ev;
    int forever = term_read(&ev, -1), timed = term_read(&ev, 20), now = term_read(&ev, 0);
    term_restore();
    cr_expect_eq(forever, -1, "a blocking read at the end of input returned %d", forever);
    cr_expect_eq(timed, -1, "a timed read at the end of input returned %d", timed);
    cr_expect_eq(now, -1, "a poll at the end of input returned %d", now);
    fclose(out);
    fclose(in);
}
