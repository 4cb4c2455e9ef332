/* Tests of the screen model (vt.c): what the encoder sends, played on a
 * small terminal emulator written here from the standards (ECMA-48 /
 * xterm), must leave the screen looking as wanted, frame after frame,
 * whatever the terminal can do; and it sends little. Also the frame
 * pacing, on a real pty whose reader stalls. */

#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE
#include <criterion/criterion.h>
#include <fcntl.h>
#include <locale.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include "tty.h"

/* The Criterion runner itself leaks 48 bytes in parallel runs with
 * timeouts (libcriterion.so.3, nothing of ours on the stack, seen on
 * main before this file); LeakSanitizer reads this hook in the asan
 * build, so `make asan` reports only our leaks. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libcriterion.so\n";
}

#define UPPER 0x2580u
#define LOWER 0x2584u
#define FULL  0x2588u

/* ==== A terminal emulator ==== */

typedef struct {
    int cols, rows;
    VtCell *cell;
    int y, x, pending;          /* cursor; pending: at the margin, wrap on the next glyph */
    uint32_t fg, bg;
    uint8_t attr;
    int am, xenl;
    int scrolled;               /* it scrolled: the encoder must never make it */
    int unknown;                /* an escape it does not know */
} Emu;

static void emu_init(Emu *e, int cols, int rows, int am, int xenl)
{
    memset(e, 0, sizeof *e);
    e->cols = cols;
    e->rows = rows;
    e->am = am;
    e->xenl = xenl;
    e->cell = calloc((size_t)cols * rows, sizeof *e->cell);
    cr_assert_not_null(e->cell);
    for (int i = 0; i < cols * rows; i++)
        e->cell[i] = (VtCell){ 'Z', CK_PAL(9), CK_PAL(9), 0 };     /* garbage before the clear */
}

static void emu_erase(Emu *e, int y, int x0, int x1)
{
    for (int x = x0; x < x1 && x < e->cols; x++)
        e->cell[y * e->cols + x] = (VtCell){ ' ', CK_DEFAULT, e->bg, 0 };   /* bce */
}

static void emu_glyph(Emu *e, uint32_t ch)
{
    if (e->pending) {
        e->pending = 0;
        e->x = 0;
        if (++e->y >= e->rows) {
            e->scrolled = 1;
            e->y = e->rows - 1;
        }
    }
    e->cell[e->y * e->cols + e->x] = (VtCell){ ch, e->fg, e->bg, e->attr };
    if (e->x + 1 < e->cols) {
        e->x++;
    } else if (e->am && e->xenl) {
        e->pending = 1;
    } else if (e->am) {
        e->x = 0;
        if (++e->y >= e->rows) {
            e->scrolled = 1;
            e->y = e->rows - 1;
        }
    }
}

static uint32_t emu_colour(const int *p, int n, int *i)
{
    if (p[*i] % 10 == 8) {
        if (*i + 2 < n && p[*i + 1] == 5) {
            uint32_t k = CK_PAL(p[*i + 2]);
            *i += 2;
            return k;
        }
        if (*i + 4 < n && p[*i + 1] == 2) {
            uint32_t k = CK_RGB(p[*i + 2], p[*i + 3], p[*i + 4]);
            *i += 4;
            return k;
        }
        cr_assert_fail("bad extended colour");
    }
    int v = p[*i];
    if (v >= 90)
        return CK_PAL(v >= 100 ? v - 100 + 8 : v - 90 + 8);
    return CK_PAL(v % 10);
}

static void emu_sgr(Emu *e, const int *p, int n)
{
    if (n == 0) {
        e->fg = e->bg = CK_DEFAULT;
        e->attr = 0;
    }
    for (int i = 0; i < n; i++) {
        int v = p[i];
        if (v == 0) {
            e->fg = e->bg = CK_DEFAULT;
            e->attr = 0;
        } else if (v == 7) {
            e->attr = VT_REVERSE;
        } else if (v == 27) {
            e->attr = 0;
        } else if (v == 39) {
            e->fg = CK_DEFAULT;
        } else if (v == 49) {
            e->bg = CK_DEFAULT;
        } else if ((v >= 30 && v <= 38) || (v >= 90 && v <= 97)) {
            e->fg = emu_colour(p, n, &i);
        } else if ((v >= 40 && v <= 48) || (v >= 100 && v <= 107)) {
            e->bg = emu_colour(p, n, &i);
        } else {
            e->unknown = 1;
        }
    }
}

static int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

static void emu_csi(Emu *e, const int *p, int n, char f)
{
    int a = n > 0 && p[0] ? p[0] : 1;
    if (f != 'm')
        e->pending = f == 'X' || f == 'K' ? e->pending : 0;
    switch (f) {
    case 'm': emu_sgr(e, p, n); break;
    case 'H':
        e->y = clampi((n > 0 && p[0] ? p[0] : 1) - 1, 0, e->rows - 1);
        e->x = clampi((n > 1 && p[1] ? p[1] : 1) - 1, 0, e->cols - 1);
        break;
    case 'G': e->x = clampi(a - 1, 0, e->cols - 1); break;
    case 'd': e->y = clampi(a - 1, 0, e->rows - 1); break;
    case 'A': e->y = clampi(e->y - a, 0, e->rows - 1); break;
    case 'B': e->y = clampi(e->y + a, 0, e->rows - 1); break;
    case 'C': e->x = clampi(e->x + a, 0, e->cols - 1); break;
    case 'D': e->x = clampi(e->x - a, 0, e->cols - 1); break;
    case 'X': emu_erase(e, e->y, e->x, e->x + a); break;
    case 'K': emu_erase(e, e->y, e->x, e->cols); break;
    case 'J':
        emu_erase(e, e->y, e->x, e->cols);
        for (int y = e->y + 1; y < e->rows; y++)
            emu_erase(e, y, 0, e->cols);
        break;
    default: e->unknown = 1; break;
    }
}

static void emu_feed(Emu *e, const char *s, size_t len)
{
    const unsigned char *p = (const unsigned char *)s, *end = p + len;
    while (p < end) {
        unsigned c = *p;
        if (c == 0x1b) {
            cr_assert(p + 1 < end && p[1] == '[', "ESC not followed by [");
            p += 2;
            int par[16], n = 0, v = 0, have = 0;
            if (p < end && *p == '2' && p + 1 < end && p[1] == 'J') {
                /* the clear's "\e[2J": everything */
                for (int y = 0; y < e->rows; y++)
                    emu_erase(e, y, 0, e->cols);
                p += 2;
                continue;
            }
            while (p < end && ((*p >= '0' && *p <= '9') || *p == ';')) {
                if (*p == ';') {
                    cr_assert(n < 15);
                    par[n++] = v;
                    v = 0;
                    have = 0;
                } else {
                    v = v * 10 + (*p - '0');
                    have = 1;
                }
                p++;
            }
            if (have || n)
                par[n++] = v;
            cr_assert(p < end, "escape cut short");
            emu_csi(e, par, n, (char)*p++);
        } else if (c == '\r') {
            e->x = 0;
            e->pending = 0;
            p++;
        } else if (c == '\n') {
            e->pending = 0;
            if (++e->y >= e->rows) {
                e->scrolled = 1;
                e->y = e->rows - 1;
            }
            p++;
        } else if (c == '\b') {
            e->pending = 0;
            if (e->x > 0)
                e->x--;
            p++;
        } else {
            uint32_t ch = c;
            int k = c < 0x80 ? 0 : c >= 0xf0 ? 3 : c >= 0xe0 ? 2 : 1;
            if (k)
                ch &= 0x3f >> k;
            for (int i = 1; i <= k; i++)
                ch = ch << 6 | (p[i] & 0x3f);
            p += k + 1;
            cr_assert(ch >= 0x20, "control character %u sent", ch);
            emu_glyph(e, ch);
        }
    }
}

/* ==== Frames ==== */

static uint32_t rnd(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

/* A frame like the viewer's: a picture of half blocks in a few colours
 * (a dithered surface), blank areas, a status bar in reverse video. */
static void random_frame(Vt *v, uint32_t *seed, int ncolours, int rgb)
{
    vt_clear(v);
    int x0 = (int)(rnd(seed) % 6), x1 = v->cols - (int)(rnd(seed) % 6);
    for (int y = 0; y < v->rows - 1; y++)
        for (int x = x0; x < x1; x++) {
            if (rnd(seed) % 8 == 0)
                continue;
            VtCell *c = vt_at(v, y, x);
            static const uint32_t glyphs[] = { UPPER, LOWER, FULL, ' ', 'a', 0x2847 };
            uint32_t g = glyphs[rnd(seed) % 6];
            uint32_t f = rgb ? CK_RGB(rnd(seed) % ncolours * 6, 7, 9) : CK_PAL(16 + rnd(seed) % ncolours);
            uint32_t b = rnd(seed) % 5 == 0 ? CK_DEFAULT
                       : rgb ? CK_RGB(rnd(seed) % ncolours * 6, 7, 9) : CK_PAL(16 + rnd(seed) % ncolours);
            if (rnd(seed) % 7 == 0)
                f = CK_DEFAULT;
            *c = (VtCell){ g, f, b, 0 };
        }
    char bar[64];
    snprintf(bar, sizeof bar, " file.obj | %u ms | ? help", rnd(seed) % 1000);
    int n = vt_text(v, v->rows - 1, 0, bar, v->cols, VT_REVERSE);
    for (int x = n; x < v->cols; x++)
        vt_text(v, v->rows - 1, x, " ", 1, VT_REVERSE);
}

/* Encode, play, and check every cell looks as wanted. */
static void play_and_check(Vt *v, Emu *e, int frame)
{
    cr_assert_eq(vt_encode(v), 0);
    emu_feed(e, v->buf, v->len);
    cr_assert(!e->scrolled, "frame %d scrolled the screen", frame);
    cr_assert(!e->unknown, "frame %d sent an escape the emulator does not know", frame);
    for (int y = 0; y < v->rows; y++)
        for (int x = 0; x < v->cols; x++) {
            if (y == v->rows - 1 && x == v->cols - 1 && e->am && !e->xenl)
                continue;       /* left alone: writing it would scroll */
            const VtCell *w = vt_at(v, y, x), *s = &e->cell[y * e->cols + x];
            cr_assert(vt_same_look(w, s),
                      "frame %d cell (%d,%d): want U+%04X fg %x bg %x attr %d, shows U+%04X fg %x bg %x attr %d",
                      frame, y, x, w->ch, w->fg, w->bg, w->attr, s->ch, s->fg, s->bg, s->attr);
        }
}

static void run_frames(VtCaps caps, int cols, int rows, int rgb)
{
    Vt v;
    vt_init(&v, &caps);
    cr_assert_eq(vt_resize(&v, cols, rows), 0);
    Emu e;
    emu_init(&e, cols, rows, caps.am, caps.xenl);
    uint32_t seed = 12345;
    for (int f = 0; f < 40; f++) {
        /* a few colours (a dithered surface), or many */
        random_frame(&v, &seed, f % 3 == 0 ? 40 : 3, rgb);
        play_and_check(&v, &e, f);
        if (f == 20) {
            vt_invalidate(&v);      /* Ctrl-L */
        }
    }
    vt_free(&v);
    free(e.cell);
}

static VtCaps xterm_caps(void)
{
    VtCaps c = { .ech = 1, .el = 1, .rel = 1, .hpa = 1, .vpa = 1, .lf = 1, .am = 1, .xenl = 1 };
    snprintf(c.clear, sizeof c.clear, "\033[H\033[2J");
    return c;
}

Test(vt, frames_land_as_wanted_on_xterm)
{
    run_frames(xterm_caps(), 37, 11, 0);
    run_frames(xterm_caps(), 37, 11, 1);
}

Test(vt, frames_land_as_wanted_without_relative_moves_or_erases)
{
    VtCaps c = xterm_caps();
    c.ech = c.el = c.rel = c.hpa = c.vpa = c.lf = 0;
    run_frames(c, 23, 9, 0);
}

Test(vt, frames_land_as_wanted_when_writing_the_margin_wraps_at_once)
{
    VtCaps c = xterm_caps();
    c.xenl = 0;                 /* am without xenl: the bottom-right cell would scroll */
    run_frames(c, 19, 7, 0);
    c.am = 0;
    run_frames(c, 19, 7, 1);
}

/* ==== What is sent ==== */

static int count(const char *s, size_t n, const char *what)
{
    int k = 0;
    size_t m = strlen(what);
    for (size_t i = 0; i + m <= n; i++)
        if (!memcmp(s + i, what, m))
            k++;
    return k;
}

Test(vt, nothing_is_sent_for_an_unchanged_frame)
{
    VtCaps c = xterm_caps();
    Vt v;
    vt_init(&v, &c);
    cr_assert_eq(vt_resize(&v, 20, 5), 0);
    vt_text(&v, 2, 3, "hello", 20, 0);
    cr_assert_eq(vt_encode(&v), 0);
    cr_expect(count(v.buf, v.len, "\033[H\033[2J") == 1, "the first frame clears");
    cr_assert_eq(vt_encode(&v), 0);
    cr_expect_eq(v.len, 0);
    /* one cell changed: a move there and the glyph */
    vt_text(&v, 2, 4, "a", 1, 0);
    cr_assert_eq(vt_encode(&v), 0);
    cr_expect(v.len > 0 && v.len <= 8, "%zu bytes for one cell", v.len);
    cr_expect_eq(v.buf[v.len - 1], 'a');
    vt_free(&v);
}

/* A surface dithered from two colours: after the first cell, not one
 * colour change, the half blocks turned as needed. */
Test(vt, a_two_colour_dither_needs_no_colour_changes)
{
    VtCaps c = xterm_caps();
    Vt v;
    vt_init(&v, &c);
    cr_assert_eq(vt_resize(&v, 40, 2), 0);
    cr_assert_eq(vt_encode(&v), 0);
    uint32_t a = CK_PAL(244), b = CK_PAL(250), seed = 7;
    for (int x = 0; x < 40; x++) {
        uint32_t t = rnd(&seed) & 1 ? a : b, u = rnd(&seed) & 1 ? a : b;
        *vt_at(&v, 0, x) = (VtCell){ UPPER, t, u, 0 };
    }
    cr_assert_eq(vt_encode(&v), 0);
    cr_expect_leq(count(v.buf, v.len, "m"), 2, "colour changes: %d", count(v.buf, v.len, "m"));
    vt_free(&v);
}

Test(vt, blank_runs_are_erased)
{
    VtCaps c = xterm_caps();
    Vt v;
    vt_init(&v, &c);
    cr_assert_eq(vt_resize(&v, 60, 3), 0);
    for (int x = 0; x < 60; x++)
        vt_text(&v, 1, x, "#", 1, 0);
    cr_assert_eq(vt_encode(&v), 0);
    vt_clear(&v);
    vt_text(&v, 1, 30, "#", 1, 0);
    cr_assert_eq(vt_encode(&v), 0);
    cr_expect_eq(count(v.buf, v.len, "X"), 1, "the left part erased by ECH");
    cr_expect_eq(count(v.buf, v.len, "\033[K"), 1, "the right part by EL");
    cr_expect_lt(v.len, 24, "%zu bytes", v.len);
    vt_free(&v);
}

Test(vt, text_keeps_one_column_per_character)
{
    /* the viewer runs in the user's locale; widths need a UTF-8 one */
    if (!setlocale(LC_ALL, "C.UTF-8") && !setlocale(LC_ALL, "en_US.UTF-8"))
        cr_skip_test("no UTF-8 locale");
    VtCaps c = xterm_caps();
    Vt v;
    vt_init(&v, &c);
    cr_assert_eq(vt_resize(&v, 10, 1), 0);
    cr_expect_eq(vt_text(&v, 0, 0, "a\xe6\x97\xa5\xc3\xa9\tb", 10, 0), 8);
    cr_expect_eq(vt_at(&v, 0, 1)->ch, (uint32_t)'?', "a wide character shows as ?");
    cr_expect_eq(vt_at(&v, 0, 2)->ch, 0xe9u, "e acute is one column");
    char row[8];
    for (int x = 0; x < 5; x++)
        row[x] = (char)vt_at(&v, 0, 3 + x)->ch;
    row[5] = 0;
    cr_expect_str_eq(row, "\\x09b", "a tab shows by its byte");
    cr_expect_eq(vt_text_cols("a\xe6\x97\xa5\xc3\xa9\tb", 9), 8, "the columns vt_text takes");
    cr_expect_eq(vt_text(&v, 0, 8, "xyz", 10, 0), 2, "cut at the edge");
    vt_free(&v);
}

/* Issue 28: a name from a file with OSC 52 (the clipboard) and CSI 2J
 * (clear the screen): drawn as text, no ESC or BEL reaches the terminal,
 * in a line or a box. */
Test(vt, controls_in_text_never_reach_the_terminal)
{
    VtCaps c = xterm_caps();
    Vt v;
    vt_init(&v, &c);
    cr_assert_eq(vt_resize(&v, 60, 6), 0);
    const char *evil = "x\x1b]52;c;aGk=\x07\x1b[2J\xc2\x9by";
    cr_expect_eq(vt_text(&v, 0, 0, evil, 60, 0), 35);
    const char *lines[] = { evil };
    vt_box(&v, lines, 1, 0, 2);
    cr_assert_eq(vt_encode(&v), 0);
    char row[40];
    for (int x = 0; x < 35; x++)
        row[x] = (char)vt_at(&v, 0, x)->ch;
    row[35] = 0;
    cr_expect_str_eq(row, "x\\x1b]52;c;aGk=\\x07\\x1b[2J\\xc2\\x9by");
    for (int x = 0; x < 35; x++)
        cr_expect_eq(vt_at(&v, 3, 2 + x)->ch, vt_at(&v, 0, x)->ch, "the box draws the same text");
    /* the encoder's own escapes start with ESC [ (SGR, moves, erases):
     * no OSC, no BEL, no C1 */
    for (size_t i = 0; i < v.len; i++) {
        unsigned char b = (unsigned char)v.buf[i];
        cr_expect(b != 0x07 && !(b >= 0x80 && b < 0xa0 && (i == 0 || (unsigned char)v.buf[i - 1] == 0xc2)),
                  "byte %02x at %zu", b, i);
        if (b == 0x1b)
            cr_expect_eq(v.buf[i + 1], '[', "ESC %c at %zu", v.buf[i + 1], i);
    }
    vt_free(&v);
}

/* row_text V Y OUT: row Y's characters as a string (ASCII cells) */
static void row_text(Vt *v, int y, char *out)
{
    int x = 0;
    for (; x < v->cols; x++)
        out[x] = (char)vt_at(v, y, x)->ch;
    out[x] = 0;
}

/* A box is its lines framed with a column of margin each side; in a
 * window narrower than that, the box takes the window's width and each
 * line is cut where the right frame begins, the margin given up, no
 * column short (the screens below are drawn by hand). */
Test(vt, a_box_cuts_its_lines_at_its_frame)
{
    VtCaps c = xterm_caps();
    Vt v;
    vt_init(&v, &c);
    cr_assert_eq(vt_resize(&v, 12, 6), 0);
    char row[16];
    const char *fits[] = { "ab", "abcd" };
    vt_box(&v, fits, 2, -2, -2);
    const char *want_fits[] = { "  +------+  ", "  | ab   |  ", "  | abcd |  ", "  +------+  ", "            " };
    for (int y = 0; y < 5; y++) {
        row_text(&v, y, row);
        cr_expect_str_eq(row, want_fits[y], "row %d", y);
    }
    vt_clear(&v);
    const char *wide[] = { "abcdefghijklmnop" };
    vt_box(&v, wide, 1, -2, -2);
    const char *want_wide[] = { "            ", "+----------+", "| abcdefghi|", "+----------+" };
    for (int y = 0; y < 4; y++) {
        row_text(&v, y, row);
        cr_expect_str_eq(row, want_wide[y], "row %d", y);
    }
    vt_free(&v);
}

Test(vt, looks)
{
    VtCell up = { UPPER, CK_PAL(1), CK_PAL(2), 0 }, low = { LOWER, CK_PAL(2), CK_PAL(1), 0 };
    cr_expect(vt_same_look(&up, &low));
    VtCell sp = { ' ', CK_PAL(5), CK_PAL(3), 0 }, full = { FULL, CK_PAL(3), CK_PAL(6), 0 };
    cr_expect(vt_same_look(&sp, &full));
    VtCell dup = { UPPER, CK_DEFAULT, CK_DEFAULT, 0 }, dlow = { LOWER, CK_DEFAULT, CK_DEFAULT, 0 };
    cr_expect(!vt_same_look(&dup, &dlow), "default fg and bg are different colours");
    VtCell rev = { ' ', CK_DEFAULT, CK_DEFAULT, VT_REVERSE }, plain = { ' ', CK_DEFAULT, CK_DEFAULT, 0 };
    cr_expect(!vt_same_look(&rev, &plain));
    VtCell a1 = { 'a', CK_PAL(1), CK_DEFAULT, 0 }, a2 = { 'a', CK_PAL(1), CK_PAL(4), 0 };
    cr_expect(!vt_same_look(&a1, &a2));
}

/* ==== Pacing ==== */

Test(vt, a_frame_waits_for_the_last_one)
{
    cr_expect(vt_may_send(0, 1, -1), "idle line: send");
    cr_expect(vt_may_send(VT_QUEUE_SLACK, 1, -1), "a few bytes left: send");
    cr_expect(!vt_may_send(VT_QUEUE_SLACK + 1, 1, -1), "the last frame still queued: wait");
    cr_expect(!vt_may_send(0, 0, -1), "the line full: wait");
    cr_expect(!vt_may_send(0, 1, 10), "no answer yet to the last frame: wait");
    cr_expect(vt_may_send(0, 1, VT_ACK_PATIENCE_MS), "an answer this late is lost: send");
}

/* On a pty whose reader stalls (a slow link): frames stop once the line
 * is full, and go again when it drains; once the terminal has answered
 * a status request, a frame waits for the answer to the last one. */
Test(vt, frames_wait_on_a_stalled_pty, .timeout = 60)
{
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    cr_assert(m >= 0);
    cr_assert_eq(grantpt(m), 0);
    cr_assert_eq(unlockpt(m), 0);
    int s = open(ptsname(m), O_RDWR | O_NOCTTY);
    cr_assert(s >= 0);
    struct winsize ws = { .ws_row = 40, .ws_col = 120 };
    ioctl(s, TIOCSWINSZ, &ws);
    FILE *out = fdopen(s, "w"), *in = fdopen(dup(s), "r");
    cr_assert(out && in);
    char err[128];
    TermConfig cfg = { .out = out, .in = in, .termname = "xterm-256color", .colour = COLOUR_TRUE };
    if (term_open(&cfg, err, sizeof err))
        cr_skip_test("no xterm-256color description: %s", err);
    /* small frames (one cell changes: a write never outgrows the room
     * left, so none blocks) until the unread line takes no more */
    Cell *cells = calloc(120 * 39, sizeof *cells);
    cr_assert_not_null(cells);
    for (int i = 0; i < 120 * 39; i++)
        cells[i] = (Cell){ .ch = ' ' };
    CellGrid g = { .cols = 120, .rows = 39, .cells = cells, .cap = 120 * 39 };
    int frames = 0;
    while (term_ready() && frames < 20000) {
        cells[0] = (Cell){ .ch = UPPER, .flags = CELL_FG | CELL_BG };
        cells[0].fg[0] = (uint8_t)frames;
        cells[0].bg[1] = (uint8_t)(frames >> 8);
        term_draw_cells(&g, 0);
        cr_assert_eq(term_update(0), 0);
        frames++;
    }
    cr_expect(frames > 1 && frames < 20000, "frames went on into a stalled line (%d)", frames);
    cr_expect(!term_ready());
    /* while the line is busy the viewer looks again after term_pace_ms:
     * each wait twice the last, up to a cap it never passes (the cap is
     * where the waits stop growing) */
    int w[10];
    for (int i = 0; i < 10; i++)
        w[i] = term_pace_ms();
    cr_expect_gt(w[0], 0);
    for (int i = 0; i + 1 < 10; i++)
        cr_expect(w[i] <= w[9] && w[i + 1] == (2 * w[i] < w[9] ? 2 * w[i] : w[9]), "wait %d: %d ms, then %d (cap %d)",
                  i, w[i], w[i + 1], w[9]);
    /* the reader catches up: the line drains */
    int fl = fcntl(m, F_GETFL);
    fcntl(m, F_SETFL, fl | O_NONBLOCK);
    char buf[65536];
    for (int k = 0; k < 100 && !term_ready(); k++) {
        struct pollfd pf = { .fd = m, .events = POLLIN };
        poll(&pf, 1, 100);
        while (read(m, buf, sizeof buf) > 0) {
        }
    }
    cr_expect(term_ready(), "the drained line takes a frame");
    /* the terminal answers the status request: from now on a frame
     * waits for the answer to the last one */
    cr_assert_eq(write(m, "\033[0n", 4), 4);
    TermEvent ev;
    int got = term_read(&ev, 2000);
    cr_expect(got == 1 && ev.type == TE_READY, "the answer reads as TE_READY (got %d, type %d)", got, ev.type);
    cells[0].fg[2] ^= 0xff;
    term_draw_cells(&g, 0);
    cr_assert_eq(term_update(0), 0);
    while (read(m, buf, sizeof buf) > 0) {
    }
    cr_expect(!term_ready(), "sent, not answered yet: wait");
    cr_assert_eq(write(m, "\033[0n", 4), 4);
    got = term_read(&ev, 2000);
    cr_expect(got == 1 && ev.type == TE_READY);
    cr_expect(term_ready(), "answered: the next frame may go");
    term_restore();
    free(cells);
    fclose(out);
    fclose(in);
    close(m);
}
