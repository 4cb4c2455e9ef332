/* term: the viewer's screen. The only file that includes curses, which
 * here drives the terminal's modes (the alternate screen, keypad, the
 * tty settings) and nothing else. Every byte of the screen comes from
 * the screen model (vt.c), which knows what the terminal shows and sends
 * only what changed; every byte of input goes through our key parser
 * (keys.c), which knows every form of the keys terminals send and drops
 * what it does not know whole (curses read an unknown sequence as Esc,
 * which quits, followed by keys).
 *
 * A frame never blocks the keys: it is written only as fast as the
 * terminal takes it, the rest kept here and sent while waiting for
 * input, so that on a slow link q still quits at once; no frame is sent
 * while the last one is still on its way (the viewer draws the newest
 * state when the line is free).
 *
 * Colours are SGR escapes of our own: 24-bit whenever COLORTERM or --color asks for it
 * (no *-direct terminfo entry needed), and under 256/16/8 colours the
 * very palette numbers --print writes (the same quantizer, dithered by
 * position), so the screen equals --print.
 *
 * Everything that changes the terminal's state goes through term_open()
 * and is undone by term_restore(), the one restore path: called on quit,
 * registered with atexit, and from the quit signals. */

#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE
#define NCURSES_WIDECHAR 1

#include <curses.h>
#include <errno.h>
#include <fcntl.h>
#include <langinfo.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "clock.h"
#include "outq.h"
#include "pixels.h"
#include "termcaps.h"
#include "tty.h"

/* From ncurses' <term.h>, which is not included: its capability macros
 * (lines, columns, ...) clash with plain names. */
struct term;
extern int setupterm(const char *name, int fd, int *err_out);
extern struct term *set_curterm(struct term *t);
extern int del_curterm(struct term *t);
extern int tputs(const char *str, int affcnt, int (*putc)(int));

/* The mouse: presses, releases and motion while a button is held (1002),
 * reported in the SGR form (1006), which has no limit on the column; a
 * terminal without SGR sends the X10 form, which the parser reads too.
 * Set by us, not by curses: its resume from Ctrl-Z would set its own
 * click-only mode (1000) over ours. */
#define MOUSE_ON  "\033[?1002h\033[?1006h"
#define MOUSE_OFF "\033[?1006l\033[?1002l\033[?1000l"
/* Device status request: the terminal answers "\e[0n" once it has
 * handled every byte before it, which is how we know a frame arrived. */
#define STATUS_ASK "\033[5n"
#define KITTY_DELETE_ALL "\033_Ga=d,q=2\033\\"     /* every image placed, gone */
#define ACK_GIVE_UP 8           /* unanswered requests before we stop asking */
#define LAST_ANSWER_MS 250      /* on quit, the wait for the answer still to come */
#define PACE_MIN_MS 4           /* first wait for a busy line; doubles up to */
#define PACE_MAX_MS 100

/* ==== State ====
 * One terminal per process: curses has one too. The signal handlers
 * read term_on, the crash bytes and the descriptors. */
static struct {
    SCREEN     *scr;
    FILE       *out;
    OutQueue    q;              /* the output: its descriptor, flags and what waits */
    int         in_fd;
    WINDOW     *pad;            /* sets the keypad mode; never refreshed */
    int         mouse_on, signals_on, atexit_done;
    int         cols, rows;     /* the window */
    ColourDepth  depth;
    Quantizer   quant;
    Vt          vt;
    int         out_errno;      /* a write failed (sticky): the next update says so */
    /* input */
    KeyParser   kp;
    int         in_ended;       /* the input is at its end (a hung-up terminal) */
    int         wake[2];        /* a pipe the signal handlers write to, waking the reader */
    /* pacing: the answer to the last status request */
    int         ask;            /* requests are sent (the output is a terminal) */
    int         ack_wait;       /* a request is outstanding */
    int         ack_told;       /* the key parser knows it went (its answer is awaited) */
    int         acks_seen;      /* the terminal has answered at least once */
    int         unanswered;
    double      ack_sent_ms;
    int         pace_ms;
    int         bg_known;       /* the terminal told its background (termbg.c) */
    uint8_t     bg[3];
    double      bg_wait_ms;     /* how long the question took */
    PixelProto  pix;            /* the pixels the terminal takes (PIX_CELLS: none, or not wanted) */
    int         pix_shown;      /* an image is on the screen */
    struct sigaction old_int, old_term, old_hup, old_tstp, old_winch;
    /* crashes: bytes prepared at open */
    char        crash_reset[256];
    size_t      crash_reset_len;
    struct termios crash_tios;
    int         crash_fd, crash_tios_ok;
    struct sigaction old_crash[5];
} T = { .q = { .fd = -1, .flags = -1 }, .in_fd = -1, .crash_fd = -1, .wake = { -1, -1 } };

static volatile sig_atomic_t term_on;
static volatile sig_atomic_t repaint;   /* back from Ctrl-Z: paint everything */
static volatile sig_atomic_t resized;     /* the window changed size */

static const int crash_sigs[5] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT };

/* ==== Writing ==== (the queue itself: outq.c) */

static int send_all(const char *p, size_t n)
{
    return outq_send_all(&T.q, p, n);
}

static void flags_back(void)
{
    outq_flags_back(&T.q);
}

static int out_pending(void)
{
    return outq_pending(&T.q);
}

static int out_add(const char *p, size_t n)
{
    return outq_add(&T.q, p, n);
}

/* Write what waits; once it has all gone, the status request that went
 * last is timed from then. */
static int out_pump(void)
{
    int emptied;
    if (outq_pump(&T.q, &emptied))
        return -1;
    if (emptied && T.ack_wait) {
        T.ack_sent_ms = now_ms();
        if (!T.ack_told)
            kp_expect(&T.kp, 1, T.ack_sent_ms);    /* an ESC alone now may be its answer's */
        T.ack_told = 1;
    }
    return 0;
}

/* Forget what waits (leaving, or a full repaint follows). A status
 * request still in it was never sent whole: no answer is waited for. */
static void out_drop(void)
{
    if (out_pending())
        T.ack_wait = 0;
    outq_drop(&T.q);
}

/* One byte to the terminal, now (for tputs). */
static int send_byte(int c)
{
    char b = (char)c;
    return send_all(&b, 1) == 0 ? c : EOF;
}

/* Send a capability (or an escape of our own) to the terminal now.
 * Curses keeps its output in a buffer of its own that its calls empty,
 * so between them this lands in order. putp() would not: it goes through
 * stdio's stdout buffer, which nothing flushes until exit. */
static void send_cap(const char *cap)
{
    if (cap && cap != (const char *)-1 && T.q.fd >= 0)
        tputs(cap, 1, send_byte);
}

/* ==== Restore and signals ==== */

/* The answers to the pixels' questions, and keys typed meanwhile, go to
 * the key parser (which drops the answers). */
static void answers_to_keys(void *ctx, const unsigned char *b, size_t n)
{
    kp_push(ctx, b, n, now_ms());
}

/* Blank the terminal before leaving curses: a terminal whose window grew
 * while in the alternate screen (tmux) keeps the part beyond the old size
 * when it switches back, and a terminal without one keeps everything. */
static void blank_terminal(void)
{
    send_cap(tigetstr("sgr0"));
    send_cap(tigetstr("clear"));
    if (T.pix == PIX_KITTY)
        send_cap(KITTY_DELETE_ALL);     /* kitty's images are not cells: clear leaves them */
    T.pix_shown = 0;
}

/* Frames still queued for a slow link would hold the reset up (and
 * the user's shell) for as long as they take to drain: they are
 * discarded, here and in the kernel, before the terminal is put back.
 * A sequence cut short is ended by the ESC that starts the reset. */
static void drop_queued_output(void)
{
    out_drop();
    if (T.q.fd >= 0 && isatty(T.q.fd))
        tcflush(T.q.fd, TCOFLUSH);
}

static void close_wake(void)
{
    for (int i = 0; i < 2; i++) {
        int fd = T.wake[i];
        T.wake[i] = -1;
        if (fd >= 0)
            close(fd);
    }
}

static void take_last_answer(void);

void term_restore(void)
{
    if (!term_on)
        return;
    term_on = 0;
    drop_queued_output();
    take_last_answer();
    if (T.mouse_on)
        send_cap(MOUSE_OFF);
    blank_terminal();
    /* curses never drew, so it does not know where the cursor is: endwin
     * moves it to the last line by an absolute move */
    endwin();           /* cursor back, alternate screen left, modes reset */
    if (T.out)
        fflush(T.out);
    if (T.signals_on)
        sigaction(SIGWINCH, &T.old_winch, NULL);  /* before its pipe closes */
    close_wake();
    if (T.pad)
        delwin(T.pad);
    T.pad = NULL;
    outq_free(&T.q);
    vt_free(&T.vt);
    quant_free(&T.quant);
}

/* ==== Crashes ====
 * A fatal signal (a bug) must not leave the shell in the alternate screen
 * with echo off. Its handler may only use async-signal-safe calls, so the
 * bytes that undo our modes and the terminal's original settings are
 * prepared at open: the handler writes them, restores the termios, and
 * dies of the same signal with the default action. */

static void crash_add(const char *cap)
{
    if (!cap || cap == (const char *)-1)
        return;
    size_t n = strlen(cap);
    if (T.crash_reset_len + n < sizeof T.crash_reset) {
        memcpy(T.crash_reset + T.crash_reset_len, cap, n);
        T.crash_reset_len += n;
    }
}

/* Undo our modes: only fcntl(2), tcflush(3), write(2) and tcsetattr(3),
 * all async-signal-safe. Queued frames are dropped first, as on a quit. */
static void crash_write(void)
{
    if (term_on && T.crash_fd >= 0) {
        flags_back();
        if (isatty(T.crash_fd))
            tcflush(T.crash_fd, TCOFLUSH);
        ssize_t w = write(T.crash_fd, T.crash_reset, T.crash_reset_len);
        (void)w;
        if (T.crash_tios_ok)
            tcsetattr(T.crash_fd, TCSANOW, &T.crash_tios);
    }
}

static void on_crash(int sig)
{
    crash_write();
    term_on = 0;
    signal(sig, SIG_DFL);
    raise(sig);
}

static void crash_prepare(int fd)
{
    T.crash_fd = fd;
    T.crash_tios_ok = tcgetattr(fd, &T.crash_tios) == 0;
    T.crash_reset_len = 0;
    crash_add(MOUSE_OFF);
    crash_add(tigetstr("sgr0"));
    crash_add(tigetstr("cnorm"));
    crash_add(tigetstr("clear"));    /* as term_restore: nothing left behind */
    crash_add(tigetstr("rmcup"));
    crash_add(tigetstr("rmkx"));
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_handler = on_crash;
    for (int i = 0; i < 5; i++)
        sigaction(crash_sigs[i], &sa, &T.old_crash[i]);
}

static void restore_handlers(void)
{
    if (!T.signals_on)
        return;
    T.signals_on = 0;
    sigaction(SIGINT, &T.old_int, NULL);
    sigaction(SIGTERM, &T.old_term, NULL);
    sigaction(SIGHUP, &T.old_hup, NULL);
    sigaction(SIGTSTP, &T.old_tstp, NULL);
    sigaction(SIGWINCH, &T.old_winch, NULL);
}

/* Wake a reader waiting in poll: a handler may run on any thread (the
 * loader's, the renderer's), where the signal interrupts no poll. */
static void wake_reader(void)
{
    int fd = T.wake[1];
    if (fd >= 0) {
        ssize_t w = write(fd, "w", 1);
        (void)w;                /* full: the reader is already woken */
    }
}

static void on_winch(int sig)
{
    (void)sig;
    resized = 1;
    wake_reader();
}

/* Quit signals: put the terminal back with the async-signal-safe bytes
 * prepared at open (endwin() is not safe here), then die of the same
 * signal so the parent sees the real cause. */
static void on_quit(int sig)
{
    crash_write();
    term_on = 0;
    signal(sig, SIG_DFL);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, sig);
    sigprocmask(SIG_UNBLOCK, &set, NULL);
    raise(sig);
    _exit(128 + sig);
}

/* Ctrl-Z: leave curses (and the mouse modes) before stopping; on SIGCONT
 * curses sets its modes again, we set ours after them (its resume would
 * otherwise leave the mouse reporting clicks only), and the reader is
 * woken to repaint everything. */
static void on_tstp(int sig)
{
    int was_on = term_on;
    if (was_on) {
        flags_back();
        if (isatty(T.q.fd))
            tcflush(T.q.fd, TCOFLUSH);        /* the shell need not wait for a frame */
        if (T.mouse_on)
            send_cap(MOUSE_OFF);
        blank_terminal();
        endwin();
        fflush(T.out);
    }
    struct sigaction dfl, mine;
    memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    sigaction(SIGTSTP, &dfl, &mine);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGTSTP);
    sigprocmask(SIG_UNBLOCK, &set, NULL);
    raise(sig);                 /* stops here until SIGCONT */
    sigprocmask(SIG_BLOCK, &set, NULL);
    sigaction(SIGTSTP, &mine, NULL);
    if (was_on && term_on) {
        doupdate();             /* curses' modes back (an empty screen) */
        /* curses sets the keypad mode again only in its own reads,
         * which keys.c does instead */
        send_cap(tigetstr("smkx"));
        if (T.mouse_on)
            send_cap(MOUSE_ON);
        if (T.out)
            fflush(T.out);
        repaint = 1;
        wake_reader();
    }
}

static void install_handlers(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_handler = on_quit;
    sigaction(SIGINT, &sa, &T.old_int);
    sigaction(SIGTERM, &sa, &T.old_term);
    sigaction(SIGHUP, &sa, &T.old_hup);
    sa.sa_handler = on_tstp;
    sigaction(SIGTSTP, &sa, &T.old_tstp);
    sa.sa_handler = on_winch;
    sigaction(SIGWINCH, &sa, &T.old_winch);
    T.signals_on = 1;
}

/* ==== Start ==== */

static int locale_utf8(void)
{
    const char *cs = nl_langinfo(CODESET);
    return cs && (!strcmp(cs, "UTF-8") || !strcmp(cs, "utf-8") || !strcmp(cs, "UTF8"));
}

/* The self-pipe the signal handlers wake the reader with: both ends
 * non-blocking (a handler must never wait), neither inherited. */
static int open_wake(void)
{
    if (pipe(T.wake) != 0) {
        T.wake[0] = T.wake[1] = -1;
        return -1;
    }
    for (int i = 0; i < 2; i++) {
        fcntl(T.wake[i], F_SETFL, fcntl(T.wake[i], F_GETFL) | O_NONBLOCK);
        fcntl(T.wake[i], F_SETFD, FD_CLOEXEC);
    }
    return 0;
}

/* The window's size from the terminal; curses' idea of it (from
 * terminfo or LINES/COLUMNS) when the output is no terminal. Curses is
 * told too: endwin moves the cursor to what it thinks is the last line. */
static void read_size(void)
{
    struct winsize ws;
    if (ioctl(T.q.fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0) {
        T.cols = ws.ws_col;
        T.rows = ws.ws_row;
        if (T.cols != COLS || T.rows != LINES)
            resizeterm(T.rows, T.cols);
    } else {
        getmaxyx(stdscr, T.rows, T.cols);
    }
}

static void open_failed(SCREEN *s, const char *why, char *err, size_t errlen)
{
    if (s) {
        endwin();
        delscreen(s);
    }
    restore_handlers();
    snprintf(err, errlen, "%s", why);
}

int term_open(const TermConfig *cfg, char *err, size_t errlen)
{
    if (term_on) {
        snprintf(err, errlen, "terminal already open");
        return -1;
    }
    FILE *out = cfg->out ? cfg->out : stdout, *in = cfg->in ? cfg->in : stdin;
    const char *name = cfg->termname ? cfg->termname : getenv("TERM");
    char why[160];
    snprintf(why, sizeof why, "unknown terminal type '%s'", name ? name : "");
    /* Our handlers go in first: ncurses then leaves SIGINT/SIGTERM/SIGTSTP
     * alone (it only catches signals still at their default) and keeps
     * SIGWINCH, which becomes KEY_RESIZE. */
    if (cfg->signals)
        install_handlers();
    fflush(out);
    /* Look the terminal up first: newterm() leaks when it fails. */
    int found = 0;
    if (!name || setupterm(name, fileno(out), &found) != OK || found != 1) {
        open_failed(NULL, why, err, errlen);
        return -1;
    }
    if (cfg->signals)
        crash_prepare(fileno(out));   /* termios as the shell left it (newterm changes it) */
    del_curterm(set_curterm(NULL));
    SCREEN *s = newterm(name, out, in);
    if (!s) {
        open_failed(NULL, why, err, errlen);
        return -1;
    }
    set_term(s);
    /* the screen is written with ANSI cursor addressing */
    if (!termcaps_is("cup", "\033[%i%p1%d;%p2%dH")) {
        open_failed(s, "the terminal cannot move the cursor the ANSI way", err, errlen);
        return -1;
    }
    WINDOW *pad = newpad(1, 1);
    VtCaps caps;
    termcaps_read(&caps);
    ColourDepth depth = termcaps_depth(cfg->colour, tigetnum("colors"));
    if (!pad || quant_init(&T.quant, depth)) {
        if (pad)
            delwin(pad);
        quant_free(&T.quant);
        open_failed(s, "out of memory", err, errlen);
        return -1;
    }
    if (open_wake()) {
        delwin(pad);
        quant_free(&T.quant);
        open_failed(s, "cannot make a pipe", err, errlen);
        return -1;
    }
    T.scr = s;
    T.out = out;
    T.q.fd = fileno(out);
    T.in_fd = fileno(in);
    T.q.flags = fcntl(T.q.fd, F_GETFL);
    T.pad = pad;
    T.depth = depth;
    vt_init(&T.vt, &caps);
    T.q.buf = NULL;
    T.q.off = T.q.len = T.q.cap = 0;
    T.out_errno = 0;
    kp_init(&T.kp, locale_utf8());
    T.in_ended = 0;
    read_size();
    term_on = 1;
    repaint = resized = 0;
    if (!T.atexit_done) {
        atexit(term_restore);
        T.atexit_done = 1;
    }
    cbreak();
    noecho();
    nonl();
    intrflush(pad, FALSE);
    /* curses never reads a key (keys.c does), but its keypad mode is the
     * one terminals expect of full-screen programs; this also enters the
     * alternate screen */
    keypad(pad, TRUE);
    curs_set(0);
    /* curses has set the tty: without ONLCR a line feed only goes down
     * (on a file, as the tty benchmark writes, as on a terminal) */
    struct termios tio;
    T.vt.caps.lf = tcgetattr(T.q.fd, &tio) != 0 || !(tio.c_oflag & OPOST) || !(tio.c_oflag & ONLCR);
    T.ask = isatty(T.q.fd);
    /* its background, before the first frame; the answers go through the
     * key parser, which drops them */
    fflush(out);
    T.bg_wait_ms = 0;
    T.bg_known = cfg->ask_bg && T.ask && isatty(T.in_fd) &&
                 termbg_ask(T.q.fd, T.in_fd, TERMBG_WAIT_MS, &T.kp, T.bg, &T.bg_wait_ms);
    /* which pixels it draws: asked the same way, the answers dropped by
     * the key parser (which waits for them: a late one is no Esc) */
    int ask_pix = cfg->pixels == PIX_AUTO && T.ask && isatty(T.in_fd);
    if (ask_pix && pixels_from_env() != PIX_CELLS)
        kp_expect(&T.kp, 1, now_ms());
    T.pix = ask_pix ? pixels_detect(T.q.fd, T.in_fd, TERMBG_WAIT_MS, answers_to_keys, &T.kp)
                    : cfg->pixels == PIX_AUTO ? PIX_CELLS : (PixelProto)cfg->pixels;
    T.pix_shown = 0;
    T.ack_wait = T.ack_told = T.acks_seen = T.unanswered = 0;
    T.pace_ms = PACE_MIN_MS;
    T.mouse_on = 0;
    /* as curses decides: a description with a mouse key (kmous) is of a
     * terminal that reports the xterm way */
    const char *kmous = tigetstr("kmous");
    if (cfg->mouse && kmous && kmous != (const char *)-1 && *kmous) {
        fflush(out);            /* after curses' own modes */
        send_cap(MOUSE_ON);
        T.mouse_on = 1;
    }
    return 0;
}

ColourDepth term_colour(void) { return T.depth; }

PixelProto term_pixels(void) { return T.pix; }

int term_cell_pixels(int *cw, int *ch)
{
    return pixels_cell_size(T.q.fd, cw, ch);
}

int term_show_image(const ByteBuf *b)
{
    if (T.out_errno || b->err)
        return -1;
    /* from the top left. The cells under the image stay as the screen
     * model has them (the status bar's changes still go out alone); only
     * the cursor and the colours are unknown after it */
    if (out_add("\033[H\033[0m", 7) || out_add((const char *)b->b, b->len)) {
        errno = ENOMEM;
        return -1;
    }
    T.vt.cy = -1;
    T.vt.sgr_ok = 0;
    T.pix_shown = 1;
    if (out_pump()) {
        T.out_errno = errno;
        out_drop();
        return -1;
    }
    return 0;
}

void term_hide_image(void)
{
    if (!T.pix_shown)
        return;
    if (T.pix == PIX_KITTY)
        out_add(KITTY_DELETE_ALL, sizeof KITTY_DELETE_ALL - 1);
    vt_invalidate(&T.vt);       /* sixel and iTerm2 images are covered by the cells, all of them */
    T.pix_shown = 0;
}

int term_image_shown(void) { return T.pix_shown; }

int term_background(uint8_t rgb_out[3], double *waited_ms_out)
{
    if (waited_ms_out)
        *waited_ms_out = T.bg_wait_ms;
    if (T.bg_known)
        memcpy(rgb_out, T.bg, 3);
    return T.bg_known;
}

void term_size(int *cols_out, int *rows_out)
{
    *cols_out = T.cols;
    *rows_out = T.rows;
}

void term_set_size(int cols, int rows)
{
    T.cols = cols;
    T.rows = rows;
    resizeterm(rows, cols);
}

/* ==== Drawing into the model ==== */

/* The model follows the window's size; a new size repaints everything. */
static int fit(void)
{
    int cols, rows;
    term_size(&cols, &rows);
    if (cols == T.vt.cols && rows == T.vt.rows && T.vt.want)
        return 0;
    return vt_resize(&T.vt, cols, rows);
}

void term_draw_cells(const CellGrid *g, int top)
{
    if (fit())
        return;
    for (int r = 0; r < g->rows; r++) {
        const Cell *c = g->cells + (size_t)r * g->cols;
        VtCell *d = vt_at(&T.vt, top + r, 0);
        if (!d)
            break;
        int n = g->cols < T.vt.cols ? g->cols : T.vt.cols;
        /* the same colour keys at the same pixels as --print */
        for (int x = 0; x < n; x++, c++, d++) {
            d->ch = c->ch;
            d->fg = colour_key(&T.quant, c->fg, c->flags & CELL_FG, x, 2 * r);
            d->bg = colour_key(&T.quant, c->bg, c->flags & CELL_BG, x, 2 * r + 1);
            d->attr = 0;
        }
    }
}

void term_draw_bar(int y, const char *text)
{
    if (fit())
        return;
    int n = vt_text(&T.vt, y, 0, text, T.vt.cols, VT_REVERSE);
    for (int x = n; x < T.vt.cols; x++)
        vt_text(&T.vt, y, x, " ", 1, VT_REVERSE);
}

void term_draw_box(const char *const *lines, int n)
{
    term_draw_box_at(lines, n, -2, -2);
}

void term_bar_cursor(int y, int x)
{
    if (fit())
        return;
    VtCell *c = vt_at(&T.vt, y, x);
    if (c)
        c->attr = 0;
}

void term_draw_box_at(const char *const *lines, int n, int bx, int by)
{
    if (fit() == 0)
        vt_box(&T.vt, lines, n, bx, by);
}

void term_erase(void)
{
    if (fit() == 0)
        vt_clear(&T.vt);
}

void term_message(const char *text)
{
    if (fit())
        return;
    vt_clear(&T.vt);
    int n = (int)strlen(text);
    if (n > T.vt.cols)
        n = T.vt.cols;
    vt_text(&T.vt, T.vt.rows / 2, (T.vt.cols - n) / 2, text, n, 0);
}

/* ==== Sending ==== */

/* The frame joins what waits (nothing, when the caller asked
 * term_ready() first) and goes as far as the terminal takes it now; the
 * rest goes while term_read() waits for keys. */
int term_update(int full)
{
    if (T.out_errno) {
        errno = T.out_errno;
        return -1;
    }
    if (fit()) {
        errno = ENOMEM;
        return -1;
    }
    if (full)
        vt_invalidate(&T.vt);
    if (vt_encode(&T.vt)) {
        errno = ENOMEM;
        return -1;
    }
    if (T.vt.len == 0)
        return 0;
    if (out_add(T.vt.buf, T.vt.len)) {
        vt_invalidate(&T.vt);   /* the model took the frame as shown: it is not */
        errno = ENOMEM;
        return -1;
    }
    /* ask for an answer once the frame is through, while the terminal
     * answers at all */
    if (T.ask && !T.ack_wait && (T.acks_seen || T.unanswered < ACK_GIVE_UP) &&
        out_add(STATUS_ASK, sizeof STATUS_ASK - 1) == 0) {
        T.ack_wait = 1;
        T.ack_told = 0;
        T.ack_sent_ms = now_ms();      /* again when it has gone (out_pump) */
        T.unanswered++;
    }
    T.pace_ms = PACE_MIN_MS;
    if (out_pump()) {
        T.out_errno = errno;
        out_drop();
        return -1;
    }
    return 0;
}

size_t term_last_bytes(void)
{
    return T.vt.len;
}

int term_ready(void)
{
    if (T.out_errno)
        return 1;               /* the next update reports it */
    if (out_pending())
        return 0;               /* the last frame is still being written */
    int queued = 0;
    if (ioctl(T.q.fd, TIOCOUTQ, &queued) != 0)
        queued = 0;             /* not a terminal (the tty benchmark's file) */
    struct pollfd pf = { .fd = T.q.fd, .events = POLLOUT };
    int writable = poll(&pf, 1, 0) != 0;        /* an error: let the write report it */
    double waited = T.ack_wait && T.acks_seen ? now_ms() - T.ack_sent_ms : -1;
    return vt_may_send(queued, writable, waited);
}

int term_pace_ms(void)
{
    if (out_pending())
        return PACE_MAX_MS;     /* term_read writes it and says when it is through */
    if (T.ack_wait && T.acks_seen) {
        /* the answer wakes the reader; this is the wait for a lost one */
        double left = VT_ACK_PATIENCE_MS - (now_ms() - T.ack_sent_ms);
        return left > 0 ? (int)left + 1 : 0;
    }
    /* the line is busy: look again soon, less often the longer it is */
    int ms = T.pace_ms;
    T.pace_ms = ms * 2 < PACE_MAX_MS ? ms * 2 : PACE_MAX_MS;
    return ms;
}

/* ==== Input ==== */

/* Back from Ctrl-Z, or a new window size: everything is drawn again, as
 * after a resize. */
static int take_signals(TermEvent *ev)
{
    if (!repaint && !resized)
        return 0;
    if (resized) {
        resized = 0;
        read_size();
    }
    if (repaint) {
        repaint = 0;
        out_drop();             /* the screen was left: what waited is moot */
        vt_invalidate(&T.vt);
    }
    ev->type = TE_RESIZE;
    return 1;
}

static void read_input(short revents);

/* The next event the parser has; the input's end decides what is left
 * unfinished at once. Before the parser decides on a quiet, what has come
 * meanwhile is read: the viewer may have been drawing while the rest of
 * a sequence came, and reading it after the decision would split the
 * sequence (an answer's ESC alone is the Esc key, which quits). */
static int parsed(TermEvent *ev)
{
    double now = now_ms();
    if (!T.in_ended && kp_wait_ms(&T.kp, now) == 0) {
        struct pollfd pf = { .fd = T.in_fd, .events = POLLIN };
        if (poll(&pf, 1, 0) > 0)
            read_input(pf.revents);
        now = now_ms();
    }
    if (!kp_next(&T.kp, ev, T.in_ended ? now + 1e12 : now))
        return 0;
    if (ev->type == TE_READY) {
        /* the answer to a status request: the last frame is through */
        T.ack_wait = 0;
        T.acks_seen = 1;
        T.unanswered = 0;
    }
    return 1;
}

/* Read what the input has (poll said so, with these revents) into the
 * parser. */
static void read_input(short revents)
{
    unsigned char buf[512];
    size_t room = sizeof T.kp.b - T.kp.len;
    if (room > sizeof buf)
        room = sizeof buf;
    if (room == 0)
        return;                 /* cannot be: the parser keeps at most one unfinished sequence */
    ssize_t r = read(T.in_fd, buf, room);
    if (r > 0) {
        kp_push(&T.kp, buf, (size_t)r, now_ms());
    } else if (r == 0 || (errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK) ||
               (revents & (POLLERR | POLLNVAL))) {
        /* end of file, a hung-up terminal (EIO), or an input in error
         * that has nothing to read: polling it again would spin */
        T.in_ended = 1;
    }
}

static void drain_wake(void)
{
    char buf[64];
    while (T.wake[0] >= 0 && read(T.wake[0], buf, sizeof buf) > 0) {
    }
}

/* How long to wait for input: until the caller's deadline (< 0: none),
 * or less when the parser decides something after a quiet. */
static int wait_ms(double until)
{
    double now = now_ms();
    double w = until < 0 ? -1 : until > now ? until - now : 0;
    int kw = kp_wait_ms(&T.kp, now);
    if (kw >= 0 && (w < 0 || kw < w))
        w = kw;
    return w < 0 ? -1 : (int)ceil(w);
}

/* Wait up to ms for input, a signal, or room for what waits to go out;
 * read and write what can be. Returns 1 when the output went through. */
static int wait_io(int ms)
{
    int pending = out_pending();
    struct pollfd pf[3] = {
        { .fd = T.in_fd, .events = POLLIN },
        { .fd = T.wake[0], .events = POLLIN },
        { .fd = pending ? T.q.fd : -1, .events = POLLOUT },
    };
    if (poll(pf, 3, ms) <= 0)
        return 0;               /* a timeout, or a signal (the caller looks) */
    if (pf[1].revents)
        drain_wake();
    if (pf[2].revents) {
        if (out_pump()) {
            T.out_errno = errno;        /* the next update reports it */
            out_drop();                 /* and no more waiting to write */
        }
        if (!out_pending())
            return 1;
    }
    if (pf[0].revents)
        read_input(pf[0].revents);
    return 0;
}

/* Leaving with a status request answered by a terminal that answers:
 * its answer, left unread, would be typed into the shell ("^[[0n"). It
 * is read here, waiting a moment for it (keys typed meanwhile were for
 * the viewer, which is leaving). */
static void take_last_answer(void)
{
    if (!T.ack_wait || !T.acks_seen || T.in_ended)
        return;
    double until = now_ms() + LAST_ANSWER_MS;
    TermEvent ev;
    while (T.ack_wait && !T.in_ended) {
        while (T.ack_wait && parsed(&ev)) {
        }
        double left = until - now_ms();
        if (!T.ack_wait || left <= 0)
            break;
        struct pollfd pf = { .fd = T.in_fd, .events = POLLIN };
        if (poll(&pf, 1, (int)ceil(left)) <= 0)
            break;
        read_input(pf.revents);
    }
}

int term_read(TermEvent *ev, int timeout_ms)
{
    double until = timeout_ms < 0 ? -1 : now_ms() + timeout_ms;
    for (;;) {
        memset(ev, 0, sizeof *ev);
        if (take_signals(ev) || parsed(ev))
            return 1;
        if (T.in_ended)
            return -1;
        int ms = wait_ms(until);
        if (wait_io(ms)) {
            ev->type = TE_READY;        /* the frame is written: the next may go */
            return 1;
        }
        if (until >= 0 && now_ms() >= until) {
            memset(ev, 0, sizeof *ev);
            if (take_signals(ev) || parsed(ev))
                return 1;
            return T.in_ended ? -1 : 0;
        }
    }
}
