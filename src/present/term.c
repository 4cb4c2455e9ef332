/* term: the viewer's screen. The only file that includes curses, which
 * here drives the terminal's modes (the alternate screen, keypad, the
 * mouse, the tty settings) and decodes its input; every byte of the
 * screen itself comes from the screen model (vt.c), which knows what the
 * terminal shows and sends only what changed. So colours are SGR
 * escapes of our own: 24-bit whenever COLORTERM or --color asks for it
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
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include <wchar.h>

#include "tty.h"

/* From ncurses' <term.h>, which is not included: its capability macros
 * (lines, columns, ...) clash with plain names. */
struct term;
extern int setupterm(const char *name, int fd, int *err_out);
extern struct term *set_curterm(struct term *t);
extern int del_curterm(struct term *t);
extern int tputs(const char *str, int affcnt, int (*putc)(int));

#define DRAG_ON  "\033[?1002h"
#define DRAG_OFF "\033[?1002l"
/* Device status request: the terminal answers "\e[0n" once it has
 * handled every byte before it, which is how we know a frame arrived. */
#define STATUS_ASK "\033[5n"
#define KEY_STATUS_OK  0x7100   /* our key codes for the answers (above ncurses' own) */
#define KEY_STATUS_BAD 0x7101
#define ACK_GIVE_UP 8           /* unanswered requests before we stop asking */
#define PACE_MIN_MS 4           /* first wait for a busy line; doubles up to */
#define PACE_MAX_MS 100

/* Mouse reports that arrive together come out of ncurses as one KEY_MOUSE
 * with several queued events: they are drained into a small queue. */
#define MQ_MAX 16

/* ==== State ====
 * One terminal per process: curses has one too. The signal handlers
 * read term_on, the crash bytes and the descriptors. */
static struct {
    SCREEN     *scr;
    FILE       *out;
    int         out_fd, in_fd;
    WINDOW     *pad;            /* keys are read through a pad: it never refreshes */
    int         mouse_on, signals_on, atexit_done;
    ColorDepth  depth;
    Quantizer   quant;
    Vt          vt;
    /* pacing: the answer to the last status request */
    int         ask;            /* requests are sent (the output is a terminal) */
    int         ack_wait;       /* a request is outstanding */
    int         acks_seen;      /* the terminal has answered at least once */
    int         unanswered;
    double      ack_sent_ms;
    int         pace_ms;
    /* mouse */
    int         drag_button, drag_x, drag_y;
    TermEvent   mq[MQ_MAX];
    int         mq_head, mq_len;
    struct sigaction old_int, old_term, old_hup, old_tstp;
    /* crashes: bytes prepared at open */
    char        crash_reset[256];
    size_t      crash_reset_len;
    struct termios crash_tios;
    int         crash_fd, crash_tios_ok;
    struct sigaction old_crash[5];
} T = { .out_fd = -1, .in_fd = -1, .crash_fd = -1 };

static volatile sig_atomic_t term_on;
static volatile sig_atomic_t repaint;   /* back from Ctrl-Z: paint everything */

static const int crash_sigs[5] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT };

static double mono_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

/* ==== Writing ==== */

/* All of p to the terminal: a signal or a full non-blocking line only
 * delays it. Returns 0, or -1 with errno. */
static int send_all(const char *p, size_t n)
{
    while (n) {
        ssize_t w = write(T.out_fd, p, n);
        if (w > 0) {
            p += w;
            n -= (size_t)w;
        } else if (w < 0 && errno == EINTR) {
            continue;
        } else if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            struct pollfd pf = { .fd = T.out_fd, .events = POLLOUT };
            poll(&pf, 1, 1000);
        } else {
            if (w == 0)
                errno = EIO;
            return -1;
        }
    }
    return 0;
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
    if (cap && cap != (const char *)-1 && T.out_fd >= 0)
        tputs(cap, 1, send_byte);
}

/* ==== Restore and signals ==== */

/* Blank the terminal before leaving curses: a terminal whose window grew
 * while in the alternate screen (tmux) keeps the part beyond the old size
 * when it switches back, and a terminal without one keeps everything. */
static void blank_terminal(void)
{
    send_cap(tigetstr("sgr0"));
    send_cap(tigetstr("clear"));
}

void term_restore(void)
{
    if (!term_on)
        return;
    term_on = 0;
    if (T.mouse_on)
        send_cap(DRAG_OFF);
    blank_terminal();
    /* curses never drew, so it does not know where the cursor is: endwin
     * moves it to the last line by an absolute move */
    endwin();           /* cursor back, alternate screen left, modes reset */
    if (T.out)
        fflush(T.out);
    if (T.pad)
        delwin(T.pad);
    T.pad = NULL;
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

/* Undo our modes: only write(2) and tcsetattr(3), both signal-safe. */
static void crash_write(void)
{
    if (term_on && T.crash_fd >= 0) {
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
    crash_add(DRAG_OFF);
    crash_add("\033[?1006;1000l");   /* the mouse reporting ncurses turns on */
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

/* Ctrl-Z: leave curses (and drag reporting) before stopping; on SIGCONT
 * curses sets its modes again, and the next read reports a repaint (the
 * handler is installed without SA_RESTART, so a waiting read returns). */
static void on_tstp(int sig)
{
    int was_on = term_on;
    if (was_on) {
        if (T.mouse_on)
            send_cap(DRAG_OFF);
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
        if (T.mouse_on)
            send_cap(DRAG_ON);
        doupdate();             /* curses' modes back (an empty screen) */
        repaint = 1;
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
    T.signals_on = 1;
}

/* ==== Terminal descriptions ==== */

static int description_found(const char *name, int fd)
{
    int found = 0;
    if (setupterm(name, fd, &found) != OK || found != 1)
        return 0;
    del_curterm(set_curterm(NULL));
    return 1;
}

const char *term_resolve(const char *name)
{
    static const char *const fallbacks[] = { "xterm-256color", "xterm", "vt100", "ansi" };
    if (!name)
        name = getenv("TERM");
    if (name && *name && description_found(name, -1))
        return name;
    for (size_t i = 0; i < sizeof fallbacks / sizeof fallbacks[0]; i++)
        if (description_found(fallbacks[i], -1))
            return fallbacks[i];
    return NULL;
}

/* A capability is the ANSI form we write ourselves (padding aside). */
static int cap_is(const char *name, const char *ansi)
{
    const char *s = tigetstr(name);
    return s && s != (const char *)-1 && strncmp(s, ansi, strlen(ansi)) == 0;
}

static int flag(const char *name)
{
    return tigetflag(name) > 0;
}

static void read_caps(VtCaps *c)
{
    memset(c, 0, sizeof *c);
    c->ech = cap_is("ech", "\033[%p1%dX");
    c->el = cap_is("el", "\033[K");
    c->rel = cap_is("cuf", "\033[%p1%dC") && cap_is("cub", "\033[%p1%dD") &&
             cap_is("cud", "\033[%p1%dB") && cap_is("cuu", "\033[%p1%dA");
    c->hpa = cap_is("hpa", "\033[%i%p1%dG");
    c->vpa = cap_is("vpa", "\033[%i%p1%dd");
    c->am = flag("am");
    c->xenl = flag("xenl");
    const char *cl = tigetstr("clear");
    /* padding ($<...>) means nothing to a terminal emulator: the plain form */
    if (cl && cl != (const char *)-1 && strncmp(cl, "\033[H\033[2J", 7) == 0)
        snprintf(c->clear, sizeof c->clear, "\033[H\033[2J");
    else
        snprintf(c->clear, sizeof c->clear, "\033[H\033[J");
}

/* The colours to use: what is asked, lowered to what the description
 * has; except 24-bit, which a description can only tell through a
 * *-direct entry that most servers lack, so it is taken as asked. */
static ColorDepth pick_depth(ColorDepth want, int colors)
{
    if (want == COLOR_TRUE)
        return COLOR_TRUE;
    if (want >= COLOR_256 && colors >= 256)
        return COLOR_256;
    if (want >= COLOR_16 && colors >= 16)
        return COLOR_16;
    if (want >= COLOR_8 && colors >= 8)
        return COLOR_8;
    return COLOR_NONE;
}

/* ==== Start ==== */

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
    if (!cap_is("cup", "\033[%i%p1%d;%p2%dH")) {
        open_failed(s, "the terminal cannot move the cursor the ANSI way", err, errlen);
        return -1;
    }
    WINDOW *pad = newpad(1, 1);
    VtCaps caps;
    read_caps(&caps);
    ColorDepth depth = pick_depth(cfg->color, tigetnum("colors"));
    if (!pad || quant_init(&T.quant, depth)) {
        if (pad)
            delwin(pad);
        quant_free(&T.quant);
        open_failed(s, "out of memory", err, errlen);
        return -1;
    }
    T.scr = s;
    T.out = out;
    T.out_fd = fileno(out);
    T.in_fd = fileno(in);
    T.pad = pad;
    T.depth = depth;
    vt_init(&T.vt, &caps);
    term_on = 1;
    repaint = 0;
    if (!T.atexit_done) {
        atexit(term_restore);
        T.atexit_done = 1;
    }
    cbreak();
    noecho();
    nonl();
    intrflush(pad, FALSE);
    keypad(pad, TRUE);          /* also enters the alternate screen */
    curs_set(0);
    set_escdelay(25);
    define_key("\033[0n", KEY_STATUS_OK);
    define_key("\033[3n", KEY_STATUS_BAD);
    /* curses has set the tty: without ONLCR a line feed only goes down
     * (on a file, as the tty benchmark writes, as on a terminal) */
    struct termios tio;
    T.vt.caps.lf = tcgetattr(T.out_fd, &tio) != 0 || !(tio.c_oflag & OPOST) || !(tio.c_oflag & ONLCR);
    T.ask = isatty(T.out_fd);
    T.ack_wait = T.acks_seen = T.unanswered = 0;
    T.pace_ms = PACE_MIN_MS;
    T.mouse_on = 0;
    T.drag_button = 0;
    T.mq_len = 0;
    if (cfg->mouse) {
        mmask_t want = BUTTON1_PRESSED | BUTTON1_RELEASED | BUTTON3_PRESSED | BUTTON3_RELEASED |
                       BUTTON4_PRESSED | BUTTON5_PRESSED | REPORT_MOUSE_POSITION;
        if (mousemask(want, NULL) != 0) {
            mouseinterval(0);   /* presses and releases as they come, no clicks */
            send_cap(DRAG_ON);      /* ncurses never asks for drag reports itself */
            T.mouse_on = 1;
        }
    }
    return 0;
}

ColorDepth term_color(void) { return T.depth; }

void term_size(int *cols_out, int *rows_out)
{
    int r, c;
    getmaxyx(stdscr, r, c);
    *cols_out = c;
    *rows_out = r;
}

void term_set_size(int cols, int rows)
{
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

/* x, y == -2: centred (term_draw_box) */
void term_draw_box_at(const char *const *lines, int n, int bx, int by)
{
    if (fit())
        return;
    int H = T.vt.rows, W = T.vt.cols;
    int w = 0;
    for (int i = 0; i < n; i++) {
        int len = (int)strlen(lines[i]);
        if (len > w)
            w = len;
    }
    w += 4;
    if (w > W)
        w = W;
    int h = n + 2 > H - 1 ? H - 1 : n + 2;
    int x0 = bx == -2 ? (W - w) / 2 : bx < 0 ? W - w : bx;
    int y0 = by == -2 ? (H - 1 - h) / 2 : by < 0 ? H - 1 - h : by;
    for (int r = 0; r < h; r++) {
        int edge = r == 0 || r == h - 1;
        const char *t = !edge && r - 1 < n ? lines[r - 1] : "";
        int len = (int)strlen(t);
        for (int x = 0; x < w; x++) {
            char ch[2] = { 0, 0 };
            if (edge)
                ch[0] = x == 0 || x == w - 1 ? '+' : '-';
            else if (x == 0 || x == w - 1)
                ch[0] = '|';
            else
                ch[0] = x - 2 >= 0 && x - 2 < len ? t[x - 2] : ' ';
            vt_text(&T.vt, y0 + r, x0 + x, ch, 1, 0);
        }
    }
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

int term_update(int full)
{
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
    if (send_all(T.vt.buf, T.vt.len))
        return -1;
    /* ask for an answer once the frame is through, while the terminal
     * answers at all */
    if (T.ask && !T.ack_wait && (T.acks_seen || T.unanswered < ACK_GIVE_UP)) {
        if (send_all(STATUS_ASK, sizeof STATUS_ASK - 1))
            return -1;
        T.ack_wait = 1;
        T.ack_sent_ms = mono_ms();
        T.unanswered++;
    }
    T.pace_ms = PACE_MIN_MS;
    return 0;
}

size_t term_last_bytes(void)
{
    return T.vt.len;
}

int term_ready(void)
{
    int queued = 0;
    if (ioctl(T.out_fd, TIOCOUTQ, &queued) != 0)
        queued = 0;             /* not a terminal (the tty benchmark's file) */
    struct pollfd pf = { .fd = T.out_fd, .events = POLLOUT };
    int writable = poll(&pf, 1, 0) != 0;        /* an error: let the write report it */
    double waited = T.ack_wait && T.acks_seen ? mono_ms() - T.ack_sent_ms : -1;
    return vt_may_send(queued, writable, waited);
}

int term_pace_ms(void)
{
    if (T.ack_wait && T.acks_seen) {
        /* the answer wakes the reader; this is the wait for a lost one */
        double left = VT_ACK_PATIENCE_MS - (mono_ms() - T.ack_sent_ms);
        return left > 0 ? (int)left + 1 : 0;
    }
    /* the line is busy: look again soon, less often the longer it is */
    int ms = T.pace_ms;
    T.pace_ms = ms * 2 < PACE_MAX_MS ? ms * 2 : PACE_MAX_MS;
    return ms;
}

/* ==== Input ==== */

static void mq_push(const TermEvent *ev)
{
    if (T.mq_len < MQ_MAX)
        T.mq[(T.mq_head + T.mq_len++) % MQ_MAX] = *ev;
}

static int mq_pop(TermEvent *ev)
{
    if (!T.mq_len)
        return 0;
    *ev = T.mq[T.mq_head];
    T.mq_head = (T.mq_head + 1) % MQ_MAX;
    T.mq_len--;
    return 1;
}

/* One mouse report -> an event; 0 for reports that only change state. */
static int mouse_event(const MEVENT *me, TermEvent *ev)
{
    mmask_t b = me->bstate;
    memset(ev, 0, sizeof *ev);
    if (b & (BUTTON4_PRESSED | BUTTON5_PRESSED)) {
        ev->type = TE_WHEEL;
        ev->dy = b & BUTTON4_PRESSED ? -1 : 1;
        return 1;
    }
    if (b & (BUTTON1_PRESSED | BUTTON3_PRESSED)) {
        T.drag_button = b & BUTTON1_PRESSED ? 1 : 3;
        T.drag_x = me->x;
        T.drag_y = me->y;
        /* the press itself: the sketch places corners there */
        ev->type = TE_CLICK;
        ev->button = T.drag_button;
        ev->x = me->x;
        ev->y = me->y;
        return 1;
    }
    int release = (b & (BUTTON1_RELEASED | BUTTON3_RELEASED)) != 0;
    if (!T.drag_button || !(release || (b & REPORT_MOUSE_POSITION)))
        return 0;
    ev->type = TE_DRAG;
    ev->button = T.drag_button;
    ev->dx = me->x - T.drag_x;
    ev->dy = me->y - T.drag_y;
    T.drag_x = me->x;
    T.drag_y = me->y;
    if (release)
        T.drag_button = 0;
    return ev->dx || ev->dy;
}

/* ncurses reads every report waiting before the first KEY_MOUSE, and
 * getmouse() hands them back newest first (ncurses 6.4): take them all,
 * then turn them into events oldest first, so that clicks come in the
 * order they were made (the sketch's corners) and drags add up in order. */
static void mouse_drain(void)
{
    MEVENT me[MQ_MAX];
    int n = 0;
    while (n < MQ_MAX && getmouse(&me[n]) == OK)
        n++;
    TermEvent ev;
    while (n-- > 0)
        if (mouse_event(&me[n], &ev))
            mq_push(&ev);
}

/* wget_wch gave ERR: a timeout, a signal, or the end of the input (a
 * hung-up terminal, a file or pipe at its end), where every read returns
 * at once and waiting again would spin. The end shows as input that
 * polls readable with no byte waiting. */
static int input_ended(void)
{
    struct pollfd p = { .fd = T.in_fd, .events = POLLIN };
    if (T.in_fd < 0 || poll(&p, 1, 0) <= 0)
        return 0;       /* nothing pending: a timeout or a signal */
    int n = 0;
    if (ioctl(T.in_fd, FIONREAD, &n) == 0 && n > 0)
        return 0;       /* a key came just after the timeout */
    return 1;
}

/* A repaint after Ctrl-Z reads as a resize: everything is drawn again. */
static int take_repaint(TermEvent *ev)
{
    if (!repaint)
        return 0;
    repaint = 0;
    vt_invalidate(&T.vt);
    ev->type = TE_RESIZE;
    return 1;
}

int term_read(TermEvent *ev, int timeout_ms)
{
    memset(ev, 0, sizeof *ev);
    if (mq_pop(ev) || take_repaint(ev))
        return 1;
    wtimeout(T.pad, timeout_ms);
    for (;;) {
        wint_t wc;
        int r = wget_wch(T.pad, &wc);
        if (take_repaint(ev))
            return 1;
        if (r == ERR)
            return input_ended() ? -1 : 0;
        if (r != KEY_CODE_YES) {
            ev->type = TE_KEY;
            ev->key = wc == '\r' ? TK_ENTER : wc == 8 ? TK_BACKSPACE : (int)wc;
            return 1;
        }
        ev->type = TE_KEY;
        switch (wc) {
        case KEY_UP:     ev->key = TK_UP; return 1;
        case KEY_DOWN:   ev->key = TK_DOWN; return 1;
        case KEY_LEFT:   ev->key = TK_LEFT; return 1;
        case KEY_RIGHT:  ev->key = TK_RIGHT; return 1;
        case KEY_BTAB:   ev->key = TK_BTAB; return 1;
        case KEY_ENTER:  ev->key = TK_ENTER; return 1;
        case KEY_DC:     ev->key = TK_DEL; return 1;
        case KEY_HOME:   ev->key = TK_HOME; return 1;
        case KEY_END:    ev->key = TK_END; return 1;
        case KEY_BACKSPACE: ev->key = TK_BACKSPACE; return 1;
        case KEY_RESIZE: ev->type = TE_RESIZE; return 1;
        case KEY_STATUS_OK:
        case KEY_STATUS_BAD:
            /* the last frame is through: the next may go */
            T.ack_wait = 0;
            T.acks_seen = 1;
            T.unanswered = 0;
            ev->type = TE_READY;
            return 1;
        case KEY_MOUSE:
            mouse_drain();
            if (mq_pop(ev))
                return 1;
            break;
        default:
            break;      /* other function keys mean nothing here */
        }
        memset(ev, 0, sizeof *ev);
        /* a key that means nothing does not end the wait early */
        if (timeout_ms != 0)
            wtimeout(T.pad, timeout_ms);
    }
}
