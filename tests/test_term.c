/* Tests of the terminal layer (term.c) on a real pty: keys come through
 * the key parser (whatever else the terminal sends), and a frame never
 * keeps the keys waiting, however slowly the other side reads. */

#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE
#include <criterion/criterion.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "tty.h"

typedef struct {
    int m, s;                   /* master (the terminal's side), slave (ours) */
    FILE *out, *in;
} Pty;

/* A pty of cols x rows with the terminal open on its slave. */
static void pty_open(Pty *p, int cols, int rows, int mouse)
{
    p->m = posix_openpt(O_RDWR | O_NOCTTY);
    cr_assert(p->m >= 0);
    cr_assert_eq(grantpt(p->m), 0);
    cr_assert_eq(unlockpt(p->m), 0);
    p->s = open(ptsname(p->m), O_RDWR | O_NOCTTY);
    cr_assert(p->s >= 0);
    struct winsize ws = { .ws_row = (unsigned short)rows, .ws_col = (unsigned short)cols };
    ioctl(p->s, TIOCSWINSZ, &ws);
    p->out = fdopen(p->s, "w");
    p->in = fdopen(dup(p->s), "r");
    cr_assert(p->out && p->in);
    char err[128];
    TermConfig cfg = { .out = p->out, .in = p->in, .termname = "xterm-256color", .colour = COLOUR_TRUE,
                       .mouse = mouse };
    if (term_open(&cfg, err, sizeof err))
        cr_skip_test("no xterm-256color description: %s", err);
}

static void pty_close(Pty *p)
{
    term_restore();
    fclose(p->out);
    fclose(p->in);
    close(p->m);
}

/* Everything the terminal's side can read now. */
static size_t drain(int m, char *buf, size_t cap)
{
    size_t n = 0;
    int fl = fcntl(m, F_GETFL);
    fcntl(m, F_SETFL, fl | O_NONBLOCK);
    for (;;) {
        struct pollfd pf = { .fd = m, .events = POLLIN };
        if (poll(&pf, 1, 50) <= 0)
            break;
        char tmp[4096];
        ssize_t r = read(m, tmp, sizeof tmp);
        if (r <= 0)
            break;
        size_t k = (size_t)r < cap - n ? (size_t)r : cap - n;
        memcpy(buf + n, tmp, k);
        n += k;
    }
    fcntl(m, F_SETFL, fl);
    return n;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

static int has(const char *buf, size_t n, const char *needle)
{
    size_t k = strlen(needle);
    for (size_t i = 0; i + k <= n; i++)
        if (!memcmp(buf + i, needle, k))
            return 1;
    return 0;
}

/* ==== Keys ==== */

/* What the terminal sends, read back as events: sequences we do not
 * know (focus, a paste) are dropped whole, the keys around them stay. */
Test(term, keys_come_through_the_parser, .timeout = 30)
{
    Pty p;
    pty_open(&p, 80, 24, 1);
    static const char in[] = "\033[I\033[4~\033[200~qqq\033[201~\033[1;5H\033[<0;3;4Mq";
    cr_assert_eq(write(p.m, in, sizeof in - 1), (ssize_t)(sizeof in - 1));
    TermEvent ev;
    int want[] = { TK_END, TK_HOME, -1, 'q' };     /* -1: the click */
    for (int i = 0; i < 4; i++) {
        cr_assert_eq(term_read(&ev, 2000), 1, "event %d", i);
        if (want[i] < 0)
            cr_expect(ev.type == TE_CLICK && ev.x == 2 && ev.y == 3, "event %d: type %d", i, ev.type);
        else
            cr_expect(ev.type == TE_KEY && ev.key == want[i], "event %d: type %d key %#x", i, ev.type, ev.key);
    }
    cr_expect_eq(term_read(&ev, 100), 0, "nothing more: type %d key %#x", ev.type, ev.key);
    pty_close(&p);
}

/* A lone ESC is Esc once nothing follows it for a moment. */
Test(term, a_lone_esc_is_esc, .timeout = 30)
{
    Pty p;
    pty_open(&p, 80, 24, 0);
    cr_assert_eq(write(p.m, "\033", 1), 1);
    TermEvent ev;
    double t0 = now_s();
    cr_assert_eq(term_read(&ev, 2000), 1);
    cr_expect(ev.type == TE_KEY && ev.key == TK_ESC);
    cr_expect_lt(now_s() - t0, 1.0, "the Esc came late: %.2f s", now_s() - t0);
    pty_close(&p);
}

/* The rest of a sequence came while the viewer was busy (drawing) after
 * it had read the ESC: the viewer reads it before it decides on the
 * quiet, and the sequence is whole (issue 28: read after the decision,
 * an answer's ESC was the Esc key, which quits). */
Test(term, a_sequence_whose_rest_came_while_busy_is_whole, .timeout = 30)
{
    Pty p;
    pty_open(&p, 80, 24, 0);
    TermEvent ev;
    cr_assert_eq(write(p.m, "\033", 1), 1);
    cr_expect_eq(term_read(&ev, 10), 0, "the ESC read, too soon to decide: type %d key %#x", ev.type, ev.key);
    cr_assert_eq(write(p.m, "[A", 2), 2);
    usleep(100 * 1000);         /* busy: longer than KP_ESC_MS */
    cr_assert_eq(term_read(&ev, 1000), 1);
    cr_expect(ev.type == TE_KEY && ev.key == TK_UP, "type %d key %#x", ev.type, ev.key);
    pty_close(&p);
}

/* A frame's status request is an answer awaited: its answer split after
 * the ESC (a slow link) is the frame's acknowledgement, no Esc. */
Test(term, a_status_answer_split_after_its_esc_is_no_esc, .timeout = 30)
{
    Pty p;
    pty_open(&p, 80, 24, 0);
    term_draw_bar(0, "a frame");
    cr_assert_eq(term_update(0), 0);
    char buf[4096];
    size_t n = drain(p.m, buf, sizeof buf);
    cr_assert(has(buf, n, "\033[5n"), "the status request went");
    cr_assert_eq(write(p.m, "\033", 1), 1);
    TermEvent ev;
    int got = term_read(&ev, 100);      /* well past KP_ESC_MS */
    cr_expect(got == 0 || ev.type != TE_KEY, "the answer's ESC read as key %#x", ev.key);
    cr_assert_eq(write(p.m, "[0n", 3), 3);
    cr_assert_eq(term_read(&ev, 2000), 1);
    cr_expect_eq(ev.type, TE_READY, "type %d key %#x", ev.type, ev.key);
    pty_close(&p);
}

/* ==== Frames on a stalled line ==== */

/* A frame far larger than the line holds, and nobody reading: the
 * update returns at once with the rest kept, a key is read while it
 * waits, and the terminal is put back at once (the queued frame dropped,
 * the reset sent). A blocking write would never return here. */
Test(term, a_frame_never_keeps_the_keys_waiting, .timeout = 30)
{
    enum { COLS = 200, ROWS = 60 };
    Pty p;
    pty_open(&p, COLS, ROWS, 1);
    Cell *cells = calloc((size_t)COLS * ROWS, sizeof *cells);
    cr_assert_not_null(cells);
    unsigned seed = 1;
    for (int i = 0; i < COLS * (ROWS - 1); i++) {
        cells[i] = (Cell){ .ch = 0x2580, .flags = CELL_FG | CELL_BG };
        for (int k = 0; k < 3; k++) {
            seed = seed * 1103515245u + 12345u;
            cells[i].fg[k] = (uint8_t)(seed >> 16);
            cells[i].bg[k] = (uint8_t)(seed >> 8);
        }
    }
    CellGrid g = { .cols = COLS, .rows = ROWS - 1, .cells = cells, .cap = (size_t)COLS * ROWS };
    term_draw_cells(&g, 0);
    double t0 = now_s();
    cr_assert_eq(term_update(0), 0);
    size_t frame = term_last_bytes();
    cr_expect_gt(frame, 200000, "a frame bigger than any tty buffer (%zu bytes)", frame);
    cr_expect_lt(now_s() - t0, 2.0, "the update waited for the terminal");
    cr_expect(!term_ready(), "the frame is still being written: no next one");
    /* the user presses q while the frame waits */
    cr_assert_eq(write(p.m, "q", 1), 1);
    TermEvent ev;
    t0 = now_s();
    int got = term_read(&ev, 3000);
    while (got == 1 && ev.type == TE_READY)
        got = term_read(&ev, 3000);
    cr_expect(got == 1 && ev.type == TE_KEY && ev.key == 'q', "q read (got %d, type %d)", got, ev.type);
    cr_expect_lt(now_s() - t0, 2.0, "q took %.2f s", now_s() - t0);
    t0 = now_s();
    term_restore();
    cr_expect_lt(now_s() - t0, 2.0, "the restore waited for the frame");
    static char buf[1 << 20];
    size_t n = drain(p.m, buf, sizeof buf);
    cr_expect_lt(n, frame / 4, "the queued frame was dropped (%zu bytes read)", n);
    cr_expect(has(buf, n, "\033[?1002l"), "the mouse mode is reset");
    cr_expect(has(buf, n, "\033[?1049l"), "the alternate screen is left");
    fclose(p.out);
    fclose(p.in);
    close(p.m);
    free(cells);
}

/* The same frame, read as the terminal takes it: term_read writes it
 * while it waits, says when it is through, and the next may go. */
Test(term, a_waiting_frame_goes_out_while_keys_are_read, .timeout = 60)
{
    enum { COLS = 200, ROWS = 60 };
    Pty p;
    pty_open(&p, COLS, ROWS, 0);
    Cell *cells = calloc((size_t)COLS * ROWS, sizeof *cells);
    cr_assert_not_null(cells);
    for (int i = 0; i < COLS * (ROWS - 1); i++) {
        cells[i] = (Cell){ .ch = 0x2580, .flags = CELL_FG | CELL_BG };
        cells[i].fg[0] = (uint8_t)i;
        cells[i].bg[1] = (uint8_t)(i / 7);
    }
    CellGrid g = { .cols = COLS, .rows = ROWS - 1, .cells = cells, .cap = (size_t)COLS * ROWS };
    term_draw_cells(&g, 0);
    cr_assert_eq(term_update(0), 0);
    size_t frame = term_last_bytes();
    cr_expect(!term_ready());
    static char buf[1 << 21];
    size_t n = 0;
    int ready = 0;
    int fl = fcntl(p.m, F_GETFL);
    fcntl(p.m, F_SETFL, fl | O_NONBLOCK);
    for (int k = 0; k < 2000 && !ready; k++) {
        TermEvent ev;
        if (term_read(&ev, 10) == 1 && ev.type == TE_READY)
            ready = 1;
        ssize_t r = read(p.m, buf + n, sizeof buf - n);
        if (r > 0)
            n += (size_t)r;
    }
    fcntl(p.m, F_SETFL, fl);
    cr_expect(ready, "the frame was written while waiting for keys");
    n += drain(p.m, buf + n, sizeof buf - n);
    cr_expect_geq(n, frame, "the whole frame reached the terminal (%zu of %zu)", n, frame);
    cr_expect(has(buf, n, "\033[5n"), "the status request follows the frame");
    pty_close(&p);
    free(cells);
}

/* Quitting right after a frame: the terminal's answer to the status
 * request that followed it is read, not left for the shell to show as
 * "^[[0n" on its command line. */
Test(term, the_last_answer_is_not_left_for_the_shell, .timeout = 30)
{
    Pty p;
    pty_open(&p, 40, 10, 0);
    Cell cells[40 * 9];
    for (int i = 0; i < 40 * 9; i++)
        cells[i] = (Cell){ .ch = 'a' + i % 26 };
    CellGrid g = { .cols = 40, .rows = 9, .cells = cells, .cap = 40 * 9 };
    static char buf[1 << 16];
    term_draw_cells(&g, 0);
    cr_assert_eq(term_update(0), 0);
    drain(p.m, buf, sizeof buf);
    cr_assert_eq(write(p.m, "\033[0n", 4), 4);      /* a terminal that answers */
    TermEvent ev;
    cr_assert_eq(term_read(&ev, 2000), 1);
    cr_assert_eq(ev.type, TE_READY);
    cells[0].ch = 'Z';
    term_draw_cells(&g, 0);
    cr_assert_eq(term_update(0), 0);
    size_t n = drain(p.m, buf, sizeof buf);
    cr_assert(has(buf, n, "\033[5n"), "a status request follows the frame");
    cr_assert_eq(write(p.m, "\033[0n", 4), 4);      /* its answer, not read before the quit */
    term_restore();
    /* the shell's canonical mode counts only whole lines as readable */
    struct termios t;
    cr_assert_eq(tcgetattr(p.s, &t), 0);
    t.c_lflag &= ~(tcflag_t)ICANON;
    cr_assert_eq(tcsetattr(p.s, TCSANOW, &t), 0);
    int left = -1;
    cr_assert_eq(ioctl(p.s, FIONREAD, &left), 0);
    cr_expect_eq(left, 0, "%d bytes of the answer left for the shell", left);
    fclose(p.out);
    fclose(p.in);
    close(p.m);
}
