/* Multiplexers (src/tty/mux.c, and termgfx.c's questions inside tmux):
 * the passthrough's wrapping undone by a reader written here, tmux's
 * answer about its pane parsed, tmux (a stand-in script in PATH)
 * asked, and the answers of tmux and of the outer terminal told apart
 * over pipes standing for the pane. */

#define _GNU_SOURCE
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../src/tty/term_internal.h"
#include "clock.h"
#include "tty.h"

/* The environment a test changes, put back after it. */
#define ENV_N 5
static const char *env_names[ENV_N] = { "TMUX", "STY", "TERM", "TMUX_PANE", "PATH" };
typedef struct {
    char *v[ENV_N];
} EnvSaved;

static EnvSaved env_save(void)
{
    EnvSaved e;
    for (int i = 0; i < ENV_N; i++)
        e.v[i] = getenv(env_names[i]) ? strdup(getenv(env_names[i])) : NULL;
    return e;
}

static void env_restore(EnvSaved *e)
{
    for (int i = 0; i < ENV_N; i++) {
        if (e->v[i])
            setenv(env_names[i], e->v[i], 1);
        else
            unsetenv(env_names[i]);
        free(e->v[i]);
    }
}

/* ==== The passthrough ==== */

/* What the outer terminal gets from "ESC P tmux ; body ESC \": the body
 * with each ESC ESC back to one ESC; -1 when it is not that shape or an
 * ESC in the body is not doubled (tmux would end the string there). */
static long unwrap(const ByteBuf *b, char *out, size_t cap)
{
    const char *s = (const char *)b->b;
    size_t n = b->len, k = 0;
    if (n < 9 || memcmp(s, "\033Ptmux;", 7) || memcmp(s + n - 2, "\033\\", 2))
        return -1;
    for (size_t i = 7; i < n - 2; i++) {
        if (s[i] == 0x1b) {
            if (i + 1 >= n - 2 || s[i + 1] != 0x1b)
                return -1;
            i++;
        }
        if (k + 1 >= cap)
            return -1;
        out[k++] = s[i];
    }
    out[k] = 0;
    return (long)k;
}

Test(mux, the_wrapped_image_reaches_the_outer_terminal_at_the_pane)
{
    /* a sixel image's shape: DCS q ... ST, with ESCs of its own */
    const char img[] = "\033Pq\"1;1;2;6#0;2;0;0;0#0~~\033\\";
    MuxPane m = { .top = 11, .left = 40, .pass = 1, .shows = 1 };
    ByteBuf b = { 0 };
    cr_assert_eq(mux_wrap(&b, &m, (const unsigned char *)img, sizeof img - 1), 0);
    char body[256];
    long n = unwrap(&b, body, sizeof body);
    cr_assert_gt(n, 0, "a passthrough string with every inner ESC doubled");
    char want[256];
    snprintf(want, sizeof want, "\0337\033[12;41H%s\0338", img);
    cr_expect_str_eq(body, want, "the outer cursor saved, at the pane's corner (1-based), the image, put back");
    /* a payload without ESCs, and an empty one, the same way */
    b.len = 0;
    cr_assert_eq(mux_wrap(&b, &m, (const unsigned char *)"abc", 3), 0);
    cr_expect_eq(unwrap(&b, body, sizeof body), (long)strlen("\0337\033[12;41Habc\0338"));
    m.top = m.left = 0;
    b.len = 0;
    cr_assert_eq(mux_wrap(&b, &m, (const unsigned char *)"\033\033", 2), 0);
    cr_expect_eq(unwrap(&b, body, sizeof body), 12);
    cr_expect_str_eq(body, "\0337\033[1;1H\033\033\0338", "ESCs in a row each doubled");
    bytebuf_free(&b);
}

Test(mux, kitty_images_are_deleted_through_the_passthrough)
{
    /* the viewer's end and a hidden image: kitty's delete, which tmux
     * drops unless passed through */
    ByteBuf b = { .b = (uint8_t *)KITTY_DELETE_ALL_TMUX, .len = sizeof KITTY_DELETE_ALL_TMUX - 1 };
    char body[64];
    cr_assert_gt(unwrap(&b, body, sizeof body), 0);
    cr_expect_str_eq(body, KITTY_DELETE_ALL);
}

/* ==== tmux's answer about the pane ==== */

Test(mux, the_pane_answer_is_parsed)
{
    MuxPane m;
    cr_assert_eq(mux_parse_pane("11 40 1 1 0 1 1\n", &m), 0);
    cr_expect(m.top == 11 && m.left == 40 && m.pass && m.shows && m.attached);
    cr_assert_eq(mux_parse_pane("0 0 0 1 0 0 2", &m), 0);
    cr_expect(!m.pass && m.shows && m.attached, "passthrough off; a pane not active shows when nothing is zoomed");
    cr_assert_eq(mux_parse_pane("0 0 1 0 0 1 1", &m), 0);
    cr_expect(!m.shows, "its window is not the current one");
    cr_assert_eq(mux_parse_pane("0 0 1 1 1 0 1", &m), 0);
    cr_expect(!m.shows, "another pane zoomed");
    cr_assert_eq(mux_parse_pane("0 0 1 1 1 1 1", &m), 0);
    cr_expect(m.shows, "this pane zoomed");
    cr_assert_eq(mux_parse_pane("0 0 1 1 0 1 0", &m), 0);
    cr_expect(!m.attached, "no client attached");
    const char *bad[] = { "", "1 2 3", "a b c d e f g", "-1 0 1 1 0 1 1", "0 0 1 1 0 1 1 junk", "0 99999 1 1 0 1 1" };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        cr_expect_eq(mux_parse_pane(bad[i], &m), -1, "'%s' is no answer", bad[i]);
}

/* A stand-in tmux: a script in a folder put first in PATH. */
static void fake_tmux(char *dir, size_t cap, const char *body)
{
    snprintf(dir, cap, "/tmp/zv-mux-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/tmux", dir);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f, "#!/bin/sh\n%s\n", body);
    cr_assert_eq(fclose(f), 0);
    cr_assert_eq(chmod(path, 0700), 0);
    char p[1024];
    snprintf(p, sizeof p, "%s:%s", dir, getenv("PATH") ? getenv("PATH") : "/usr/bin:/bin");
    setenv("PATH", p, 1);
}

static void fake_tmux_gone(const char *dir)
{
    char path[256];
    snprintf(path, sizeof path, "%s/tmux", dir);
    unlink(path);
    rmdir(dir);
}

Test(mux, tmux_is_asked_about_its_pane)
{
    EnvSaved e = env_save();
    char dir[64];
    /* the script answers only when asked about the pane in TMUX_PANE */
    fake_tmux(dir, sizeof dir, "[ \"$4\" = '%7' ] && [ \"$1\" = display-message ] && echo '3 41 1 1 0 1 1'");
    setenv("TMUX_PANE", "%7", 1);
    MuxPane m = { 0 };
    cr_expect_eq(mux_tmux_pane(&m, 2000), 0);
    cr_expect(m.top == 3 && m.left == 41 && m.pass && m.shows);
    setenv("TMUX_PANE", "%8", 1);
    cr_expect_eq(mux_tmux_pane(&m, 2000), -1, "no answer about another pane");
    setenv("TMUX_PANE", "7; rm -rf", 1);
    cr_expect_eq(mux_tmux_pane(&m, 2000), -1, "TMUX_PANE that is not a pane: tmux is not asked");
    fake_tmux_gone(dir);
    /* a tmux that hangs costs the wait, not its 10 s (the bound leaves a
     * loaded machine seconds) */
    fake_tmux(dir, sizeof dir, "exec sleep 10");
    setenv("TMUX_PANE", "%7", 1);
    double t0 = now_ms();
    cr_expect_eq(mux_tmux_pane(&m, 100), -1);
    cr_expect_lt(now_ms() - t0, 5000, "a hung tmux is given up after the wait");
    fake_tmux_gone(dir);
    env_restore(&e);
}

Test(mux, the_environment_names_the_multiplexer)
{
    EnvSaved e = env_save();
    unsetenv("TMUX");
    unsetenv("STY");
    setenv("TERM", "xterm-256color", 1);
    cr_expect_eq(mux_from_env(), MUX_NONE);
    setenv("TMUX", "/tmp/tmux-0/default,1,0", 1);
    cr_expect_eq(mux_from_env(), MUX_TMUX);
    setenv("STY", "123.pts-0.host", 1);
    cr_expect_eq(mux_from_env(), MUX_SCREEN, "screen inside tmux (or around it) passes no images");
    unsetenv("TMUX");
    unsetenv("STY");
    setenv("TERM", "screen.xterm-256color", 1);
    cr_expect_eq(mux_from_env(), MUX_SCREEN);
    setenv("TERM", "tmux-256color", 1);
    cr_expect_eq(mux_from_env(), MUX_TMUX);
    MuxPane off = { .pass = 0, .attached = 1 }, on = { .pass = 1, .attached = 1 }, alone = { .pass = 0 };
    cr_expect_not_null(strstr(mux_why_cells(MUX_TMUX, &off, 0), "set -g allow-passthrough on"));
    cr_expect_not_null(strstr(mux_why_cells(MUX_TMUX, &off, 1), "set -g allow-passthrough on"));
    cr_expect_null(mux_why_cells(MUX_TMUX, &on, 0), "passthrough on: not tmux's doing");
    cr_expect_null(mux_why_cells(MUX_TMUX, &alone, 0), "no client: no terminal to draw pixels, nothing to say");
    cr_expect_not_null(strstr(mux_why_cells(MUX_SCREEN, NULL, 0), "screen"));
    cr_expect_null(mux_why_cells(MUX_NONE, NULL, 0));
    env_restore(&e);
}

/* ==== The questions inside tmux ==== */

/* The pixels' questions inside tmux (termbg_ask, as the viewer asks
 * them) over pipes: the answers waiting, the questions asked back in q. */
static PixelProto detect_tmux(const char *answer, int pass, PixelScan *scan, char *q, size_t qlen)
{
    int out[2], in[2];
    cr_assert_eq(pipe(out), 0);
    cr_assert_eq(pipe(in), 0);
    if (answer)
        cr_assert_eq(write(in[1], answer, strlen(answer)), (ssize_t)strlen(answer));
    pixels_scan_init(scan, 0);
    TermQuestions tq = { .pix = pass ? PIXQ_TMUX_PASS : PIXQ_TMUX, .scan = scan };
    TermAnswers ans;
    termbg_ask(out[1], in[0], 60, NULL, &tq, &ans);
    PixelProto p = pixels_scanned(scan);
    close(out[1]);
    ssize_t n = read(out[0], q, qlen - 1);
    q[n > 0 ? n : 0] = 0;
    close(out[0]);
    close(in[0]);
    close(in[1]);
    return p;
}

Test(mux, tmux_and_the_outer_terminal_are_told_apart)
{
    PixelScan s;
    char q[512];
    /* tmux 3.3 answers without 4; xterm -ti vt340 through it with 4 */
    cr_expect_eq(detect_tmux("\033[?1;2c\033[?63;1;2;4;6c", 1, &s, q, sizeof q), PIX_SIXEL);
    cr_expect(pixels_through_mux(&s), "the outer terminal's sixel: through the passthrough");
    cr_expect_eq(strncmp(q, "\033[c\033Ptmux;", 10), 0, "tmux's own attributes, then the passthrough");
    cr_expect_not_null(strstr(q, "\033\033[c\033\\"), "the outer terminal's attributes asked, ESC doubled, last");
    cr_expect_not_null(strstr(q, "\033\033_Gi=31"), "and kitty's query");
    /* the same answers in the other order would be tmux's sixel: the
     * order is what tells them apart */
    cr_expect_eq(detect_tmux("\033[?1;2;4c\033[?62;22c", 1, &s, q, sizeof q), PIX_SIXEL);
    cr_expect(!pixels_through_mux(&s), "tmux's own sixel (3.4): drawn by tmux, no passthrough");
    cr_expect_eq(detect_tmux("\033[?1;2c\033_Gi=31;OK\033\\\033[?62;22c", 1, &s, q, sizeof q), PIX_KITTY);
    cr_expect(pixels_through_mux(&s), "kitty outside: through the passthrough");
    cr_expect_eq(detect_tmux("\033[?1;2c\033[?62;22c", 1, &s, q, sizeof q), PIX_CELLS, "a VT220 outside");
    cr_expect(!pixels_through_mux(&s));
    cr_expect_eq(detect_tmux("\033[?1;2c", 1, &s, q, sizeof q), PIX_CELLS, "tmux alone answers: cells after the wait");
    cr_expect(!s.got_da, "the outer terminal's answer is still awaited");
    /* passthrough off: only tmux is asked */
    cr_expect_eq(detect_tmux("\033[?1;2c", 0, &s, q, sizeof q), PIX_CELLS);
    cr_expect(s.got_da);
    cr_expect_str_eq(q, "\033[c", "nothing for the outer terminal");
    cr_expect_eq(detect_tmux("\033[?1;2;4c", 0, &s, q, sizeof q), PIX_SIXEL, "tmux 3.4 with sixel, passthrough off");
    cr_expect(!pixels_through_mux(&s));
}

/* ==== The start's one write ==== */

Test(mux, the_start_asks_everything_in_one_write_and_waits_once)
{
    int out[2], in[2];
    cr_assert_eq(pipe(out), 0);
    cr_assert_eq(pipe(in), 0);
    /* xterm over ssh answering all: its background, the SGR as set,
     * its name and attributes (sixel) */
    const char *answer = "\033]11;rgb:ffff/ffff/ffff\007\033P1$r0;38:2::1:2:3m\033\\"
                         "\033P>|XTerm(379)\033\\\033[?63;1;2;4;6c";
    cr_assert_eq(write(in[1], answer, strlen(answer)), (ssize_t)strlen(answer));
    PixelScan scan;
    pixels_scan_init(&scan, 0);
    TermQuestions q = { .ask_bg = 1, .ask_colour = 1, .pix = PIXQ_PLAIN, .scan = &scan };
    TermAnswers ans;
    cr_expect_eq(termbg_ask(out[1], in[0], 5000, NULL, &q, &ans), 1, "the background said");
    cr_expect(ans.answered && ans.waited_ms < 2500, "the attributes' answer ended the wait (%.0f ms)", ans.waited_ms);
    cr_expect_eq(ans.colour, COLOUR_TRUE);
    cr_expect_eq(pixels_scanned(&scan), PIX_SIXEL);
    close(out[1]);
    char asked[512];
    ssize_t n = read(out[0], asked, sizeof asked - 1);
    asked[n > 0 ? n : 0] = 0;
    cr_expect_eq(strncmp(asked, "\033]11;?", 6), 0, "the background first");
    const char *da = strstr(asked, "\033[c");
    cr_expect(da && !strstr(da + 1, "\033[c") && da[3] == 0, "one attributes' question, last");
    cr_expect_not_null(strstr(asked, "\033P$qm"), "the SGR asked back");
    cr_expect_not_null(strstr(asked, "a=q"), "kitty's query");
    close(out[0]);
    /* silence: the wait once, no more */
    cr_assert_eq(pipe(out), 0);
    pixels_scan_init(&scan, 0);
    /* the whole wait, and not a second (the slack is a loaded machine's) */
    double t0 = now_ms();
    termbg_ask(out[1], in[0], 400, NULL, &q, &ans);
    double took = now_ms() - t0;
    cr_expect(!ans.answered);
    cr_expect(took >= 399 && took < 800, "a silent terminal: one wait of 400 ms, not %.0f", took);
    close(out[0]);
    close(out[1]);
    close(in[0]);
    close(in[1]);
}
