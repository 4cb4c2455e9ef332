/* term: the viewer's terminal session. The only file that includes
 * curses, which here drives the terminal's modes (the alternate screen,
 * keypad, the tty settings) and reads its description (terminfo), and
 * nothing else. Every byte of the screen comes from the screen model
 * (vt.c), sent by termdraw.c; every byte of input goes through our key
 * parser (keys.c), read by termread.c.
 *
 * Everything that changes the terminal's state goes through term_open()
 * and is undone by term_restore(), the one restore path: called on quit,
 * registered with atexit, and from the quit signals. The session
 * (term_internal.h) is made by the one and freed by the other; what
 * stays in this file's statics is what the signal handlers must reach:
 * whether a session is open, what they noted for the reader, the pipe
 * they wake it with, the bytes that undo our modes after a crash, the
 * handlers they replaced, and the session itself (Ctrl-Z leaves curses
 * and comes back with its modes). */

#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE
#define NCURSES_WIDECHAR 1

#include <curses.h>
#include <fcntl.h>
#include <langinfo.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include "clock.h"
#include "term_internal.h"

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

/* ==== What the signal handlers reach ====
 * One terminal per process: curses has one too. */

static volatile sig_atomic_t term_on;   /* a session is open */
static volatile sig_atomic_t repaint;   /* back from Ctrl-Z: paint everything */
static volatile sig_atomic_t resized;   /* the window changed size */

static struct {
    Term       *t;              /* the open session (set while term_on, and during the restore) */
    int         wake_wr;        /* the write end of the reader's wake pipe (t->wake_fd reads it) */
    int         signals_on;     /* our handlers are in: the ones they replaced below */
    int         atexit_done;    /* term_restore is registered with atexit (once a process) */
    /* the last session's curses screen and its terminal entry, kept
     * past endwin until the next session replaces them (the gallery
     * opens one again after the viewer: each newterm would leak the
     * last; delscreen leaves the entry) */
    SCREEN     *screen;
    struct term *screen_term;
    struct sigaction old_int, old_term, old_hup, old_tstp, old_winch;
    /* crashes: bytes prepared at open */
    char        crash_reset[256];
    size_t      crash_reset_len;
    struct termios crash_tios;
    int         crash_fd, crash_tios_ok;
    struct sigaction old_crash[5];
} S = { .wake_wr = -1, .crash_fd = -1 };

static const int crash_sigs[5] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT };

Term *term_session(void)
{
    return S.t;
}

/* ==== Capabilities to the terminal ==== */

/* One byte to the terminal, now (for tputs, which hands no context:
 * the session's output is reached through S). */
static int send_byte(int c)
{
    char b = (char)c;
    return outq_send_all(&S.t->q, &b, 1) == 0 ? c : EOF;
}

/* Send a capability (or an escape of our own) to the terminal now.
 * Curses keeps its output in a buffer of its own that its calls empty,
 * so between them this lands in order. putp() would not: it goes through
 * stdio's stdout buffer, which nothing flushes until exit. */
static void send_cap(const char *cap)
{
    if (cap && cap != (const char *)-1 && S.t && S.t->q.fd >= 0)
        tputs(cap, 1, send_byte);
}

/* ==== The terminal's description ====
 * What terminfo says, read here beside the rest of curses: which
 * description to use, the escapes the screen model may send (vt.c
 * writes the ANSI forms itself when the description has them), and the
 * colours. */

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

/* Is capability `name` the ANSI form we write ourselves (padding aside)? */
static int caps_is(const char *name, const char *ansi)
{
    const char *s = tigetstr(name);
    return s && s != (const char *)-1 && strncmp(s, ansi, strlen(ansi)) == 0;
}

static int caps_flag(const char *name)
{
    return tigetflag(name) > 0;
}

/* The escapes of c the description has in the ANSI form vt.c writes. */
static void caps_read(VtCaps *c)
{
    memset(c, 0, sizeof *c);
    c->ech = caps_is("ech", "\033[%p1%dX");
    c->el = caps_is("el", "\033[K");
    c->rel = caps_is("cuf", "\033[%p1%dC") && caps_is("cub", "\033[%p1%dD") &&
             caps_is("cud", "\033[%p1%dB") && caps_is("cuu", "\033[%p1%dA");
    c->hpa = caps_is("hpa", "\033[%i%p1%dG");
    c->vpa = caps_is("vpa", "\033[%i%p1%dd");
    c->am = caps_flag("am");
    c->xenl = caps_flag("xenl");
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
static ColourDepth caps_depth(ColourDepth want, int colours)
{
    if (want == COLOUR_TRUE)
        return COLOUR_TRUE;
    if (want >= COLOUR_256 && colours >= 256)
        return COLOUR_256;
    if (want >= COLOUR_16 && colours >= 16)
        return COLOUR_16;
    if (want >= COLOUR_8 && colours >= 8)
        return COLOUR_8;
    return COLOUR_NONE;
}

/* ==== Restore ==== */

/* Blank the terminal before leaving curses: a terminal whose window grew
 * while in the alternate screen (tmux) keeps the part beyond the old size
 * when it switches back, and a terminal without one keeps everything. */
static void blank_terminal(Term *t)
{
    send_cap(tigetstr("sgr0"));
    send_cap(tigetstr("clear"));
    if (t->pix == PIX_KITTY)
        send_cap(pixels_through_mux(&t->pix_scan) ? KITTY_DELETE_ALL_TMUX : KITTY_DELETE_ALL);
    t->pix_shown = 0;
}

/* Frames still queued for a slow link would hold the reset up (and
 * the user's shell) for as long as they take to drain: they are
 * discarded, here and in the kernel, before the terminal is put back.
 * A sequence cut short is ended by the ESC that starts the reset. */
static void drop_queued_output(Term *t)
{
    term_out_drop(t);
    if (t->q.fd >= 0 && isatty(t->q.fd))
        tcflush(t->q.fd, TCOFLUSH);
}

static void close_wake(Term *t)
{
    int fds[2] = { t->wake_fd, S.wake_wr };
    t->wake_fd = S.wake_wr = -1;
    for (int i = 0; i < 2; i++)
        if (fds[i] >= 0)
            close(fds[i]);
}

void term_restore(void)
{
    if (!term_on)
        return;
    term_on = 0;
    Term *t = S.t;
    drop_queued_output(t);
    term_take_last_answer(t);
    if (t->mouse_on)
        send_cap(MOUSE_OFF);
    blank_terminal(t);
    /* curses never drew, so it does not know where the cursor is: endwin
     * moves it to the last line by an absolute move */
    endwin();           /* cursor back, alternate screen left, modes reset */
    if (t->out)
        fflush(t->out);
    if (S.signals_on)
        sigaction(SIGWINCH, &S.old_winch, NULL);  /* before its pipe closes */
    close_wake(t);
    if (t->pad)
        delwin(t->pad);
    outq_free(&t->q);
    vt_free(&t->vt);
    quant_free(&t->quant);
    S.t = NULL;
    free(t);
}

/* ==== Signals and crashes ====
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
    if (S.crash_reset_len + n < sizeof S.crash_reset) {
        memcpy(S.crash_reset + S.crash_reset_len, cap, n);
        S.crash_reset_len += n;
    }
}

/* Undo our modes: only fcntl(2), tcflush(3), write(2) and tcsetattr(3),
 * all async-signal-safe. Queued frames are dropped first, as on a quit. */
static void crash_write(void)
{
    if (term_on && S.crash_fd >= 0) {
        outq_flags_back(&S.t->q);
        if (isatty(S.crash_fd))
            tcflush(S.crash_fd, TCOFLUSH);
        ssize_t w = write(S.crash_fd, S.crash_reset, S.crash_reset_len);
        (void)w;
        if (S.crash_tios_ok)
            tcsetattr(S.crash_fd, TCSANOW, &S.crash_tios);
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
    S.crash_fd = fd;
    S.crash_tios_ok = tcgetattr(fd, &S.crash_tios) == 0;
    S.crash_reset_len = 0;
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
        sigaction(crash_sigs[i], &sa, &S.old_crash[i]);
}

static void restore_handlers(void)
{
    if (!S.signals_on)
        return;
    S.signals_on = 0;
    sigaction(SIGINT, &S.old_int, NULL);
    sigaction(SIGTERM, &S.old_term, NULL);
    sigaction(SIGHUP, &S.old_hup, NULL);
    sigaction(SIGTSTP, &S.old_tstp, NULL);
    sigaction(SIGWINCH, &S.old_winch, NULL);
}

/* Wake a reader waiting in poll: a handler may run on any thread (the
 * loader's, the renderer's), where the signal interrupts no poll. */
static void wake_reader(void)
{
    int fd = S.wake_wr;
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
    Term *t = S.t;
    if (was_on) {
        outq_flags_back(&t->q);
        if (isatty(t->q.fd))
            tcflush(t->q.fd, TCOFLUSH);        /* the shell need not wait for a frame */
        if (t->mouse_on)
            send_cap(MOUSE_OFF);
        blank_terminal(t);
        endwin();
        fflush(t->out);
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
        if (t->mouse_on)
            send_cap(MOUSE_ON);
        if (t->out)
            fflush(t->out);
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
    sigaction(SIGINT, &sa, &S.old_int);
    sigaction(SIGTERM, &sa, &S.old_term);
    sigaction(SIGHUP, &sa, &S.old_hup);
    sa.sa_handler = on_tstp;
    sigaction(SIGTSTP, &sa, &S.old_tstp);
    sa.sa_handler = on_winch;
    sigaction(SIGWINCH, &sa, &S.old_winch);
    S.signals_on = 1;
}

/* ==== Start ==== */

static int locale_utf8(void)
{
    const char *cs = nl_langinfo(CODESET);
    return cs && (!strcmp(cs, "UTF-8") || !strcmp(cs, "utf-8") || !strcmp(cs, "UTF8"));
}

/* The self-pipe the signal handlers wake the reader with: both ends
 * non-blocking (a handler must never wait), neither inherited. */
static int open_wake(Term *t)
{
    int fd[2];
    if (pipe(fd) != 0)
        return -1;
    for (int i = 0; i < 2; i++) {
        fcntl(fd[i], F_SETFL, fcntl(fd[i], F_GETFL) | O_NONBLOCK);
        fcntl(fd[i], F_SETFD, FD_CLOEXEC);
    }
    t->wake_fd = fd[0];
    S.wake_wr = fd[1];
    return 0;
}

/* The window's size from the terminal; curses' idea of it (from
 * terminfo or LINES/COLUMNS) when the output is no terminal. Curses is
 * told too: endwin moves the cursor to what it thinks is the last line. */
static void read_size(Term *t)
{
    struct winsize ws;
    if (ioctl(t->q.fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0) {
        t->cols = ws.ws_col;
        t->rows = ws.ws_row;
        if (t->cols != COLS || t->rows != LINES)
            resizeterm(t->rows, t->cols);
    } else {
        getmaxyx(stdscr, t->rows, t->cols);
    }
}

static void open_failed(Term *t, SCREEN *s, const char *why, char *err, size_t errlen)
{
    if (s) {
        endwin();
        delscreen(s);
        if (S.screen == s)
            S.screen = NULL;    /* its entry, current, goes with the next setupterm's */
    }
    restore_handlers();
    free(t);
    snprintf(err, errlen, "%s", why);
}

/* Curses' modes for a full-screen program that reads its own keys. */
static void set_modes(Term *t)
{
    cbreak();
    noecho();
    nonl();
    intrflush(t->pad, FALSE);
    /* curses never reads a key (keys.c does), but its keypad mode is the
     * one terminals expect of full-screen programs; this also enters the
     * alternate screen */
    keypad(t->pad, TRUE);
    curs_set(0);
    /* curses has set the tty: without ONLCR a line feed only goes down
     * (on a file, as the tty benchmark writes, as on a terminal) */
    struct termios tio;
    t->vt.caps.lf = tcgetattr(t->q.fd, &tio) != 0 || !(tio.c_oflag & OPOST) || !(tio.c_oflag & ONLCR);
}

/* The quantizer for the colours the terminal said (kept as it was when
 * there is no memory). */
void term_colour_said(Term *t, ColourDepth said)
{
    if (said <= t->depth)
        return;
    Quantizer q;
    if (quant_init(&q, said))
        return;
    quant_free(&t->quant);
    t->quant = q;
    t->depth = said;
    t->depth_answered = 1;
}

/* What the terminal is asked before the first frame (its background, the
 * colours it draws when the environment did not say 24 bits, the pixels
 * it draws), and the mouse turned on. */
static void ask_terminal(Term *t, const TermConfig *cfg)
{
    t->ask = isatty(t->q.fd);
    /* its background and colours, before the first frame; the answers go
     * through the key parser, which drops them */
    fflush(t->out);
    t->bg_wait_ms = 0;
    t->bg_known = t->depth_answered = 0;
    int ask_colour = cfg->colour_env && t->depth > COLOUR_NONE && t->depth < COLOUR_TRUE;
    int tty = t->ask && isatty(t->in_fd);
    /* which pixels it draws: inside tmux, tmux itself says first where
     * the pane is and whether images pass (mux.c) */
    int ask_pix = cfg->pixels == PIX_AUTO && tty;
    t->mux = mux_from_env();
    t->pix_wanted = cfg->pixels != PIX_CELLS;
    t->pane_known = t->mux == MUX_TMUX && cfg->pixels != PIX_CELLS && t->ask &&
                    mux_tmux_pane(&t->pane, MUX_ASK_MS) == 0;
    t->pane_asked_ms = now_ms();
    int asks = ask_pix && (t->mux == MUX_NONE ? pixels_from_env() != PIX_CELLS : t->pane_known);
    pixels_scan_init(&t->pix_scan, !t->kp.utf8);
    TermQuestions q = {
        .ask_bg = cfg->ask_bg,
        .ask_colour = ask_colour,
        .pix = !asks ? PIXQ_NONE : t->mux == MUX_NONE ? PIXQ_PLAIN
             : t->pane.pass && t->pane.attached ? PIXQ_TMUX_PASS : PIXQ_TMUX,
        .scan = &t->pix_scan,
    };
    /* all in one write, one wait (TERM_ASK_MS at most); the answers, and
     * keys typed meanwhile, go through the key parser, which drops the
     * answers (and waits for them: a late one is no Esc) */
    t->pix_asked_ms = now_ms();
    t->answered = -1;
    if ((q.ask_bg || q.ask_colour || asks) && tty) {
        TermAnswers ans;
        termbg_ask(t->q.fd, t->in_fd, cfg->ask_ms > 0 ? cfg->ask_ms : TERM_ASK_MS, &t->kp, &q, &ans);
        t->answered = ans.answered;
        t->bg_wait_ms = ans.waited_ms;
        t->bg_known = cfg->ask_bg && ans.got_bg;
        memcpy(t->bg, ans.bg, 3);
        term_colour_said(t, ans.colour);
        /* its answer not in yet (a link slower than the wait): read on */
        t->colour_scan = ans.scan;
        t->colour_late = ask_colour && !ans.scan.got_da && !ans.colour;
    }
    t->pix = asks ? pixels_scanned(&t->pix_scan) : cfg->pixels == PIX_AUTO ? PIX_CELLS : (PixelProto)cfg->pixels;
    /* a slow link (or a loaded terminal) answers after the wait: what
     * comes is still read for pixels until kitty's (the best) or
     * KP_LATE_MS */
    t->pix_late = asks && t->pix != PIX_KITTY;
    t->late_news = 0;
    t->pix_shown = 0;
    t->ack_wait = t->ack_told = t->acks_seen = t->unanswered = 0;
    t->pace_ms = PACE_MIN_MS;
    t->mouse_on = 0;
    /* as curses decides: a description with a mouse key (kmous) is of a
     * terminal that reports the xterm way */
    const char *kmous = tigetstr("kmous");
    if (cfg->mouse && kmous && kmous != (const char *)-1 && *kmous) {
        fflush(t->out);         /* after curses' own modes */
        send_cap(MOUSE_ON);
        t->mouse_on = 1;
    }
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
    Term *t = calloc(1, sizeof *t);
    if (!t) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    t->q.fd = t->q.flags = t->in_fd = t->wake_fd = -1;
    /* Our handlers go in first: ncurses then leaves SIGINT/SIGTERM/SIGTSTP
     * alone (it only catches signals still at their default) and keeps
     * SIGWINCH, which becomes KEY_RESIZE. */
    if (cfg->signals)
        install_handlers();
    fflush(out);
    /* Look the terminal up first: newterm() leaks when it fails. */
    int found = 0;
    if (!name || setupterm(name, fileno(out), &found) != OK || found != 1) {
        open_failed(t, NULL, why, err, errlen);
        return -1;
    }
    if (cfg->signals)
        crash_prepare(fileno(out));   /* termios as the shell left it (newterm changes it) */
    del_curterm(set_curterm(NULL));
    if (S.screen) {
        delscreen(S.screen);    /* ended (endwin) by the last term_restore */
        del_curterm(S.screen_term);
        S.screen = NULL;
        S.screen_term = NULL;
    }
    SCREEN *s = newterm(name, out, in);
    if (!s) {
        open_failed(t, NULL, why, err, errlen);
        return -1;
    }
    set_term(s);
    S.screen = s;
    S.screen_term = set_curterm(NULL);      /* newterm made it the current one */
    set_curterm(S.screen_term);
    /* the screen is written with ANSI cursor addressing */
    if (!caps_is("cup", "\033[%i%p1%d;%p2%dH")) {
        open_failed(t, s, "the terminal cannot move the cursor the ANSI way", err, errlen);
        return -1;
    }
    WINDOW *pad = newpad(1, 1);
    VtCaps caps;
    caps_read(&caps);
    ColourDepth depth = caps_depth(cfg->colour, tigetnum("colors"));
    if (!pad || quant_init(&t->quant, depth)) {
        if (pad)
            delwin(pad);
        quant_free(&t->quant);
        open_failed(t, s, "out of memory", err, errlen);
        return -1;
    }
    if (open_wake(t)) {
        delwin(pad);
        quant_free(&t->quant);
        open_failed(t, s, "cannot make a pipe", err, errlen);
        return -1;
    }
    t->out = out;
    t->q.fd = fileno(out);
    t->in_fd = fileno(in);
    t->q.flags = fcntl(t->q.fd, F_GETFL);
    t->pad = pad;
    t->depth = depth;
    vt_init(&t->vt, &caps);
    kp_init(&t->kp, locale_utf8());
    read_size(t);
    S.t = t;
    term_on = 1;
    repaint = resized = 0;
    if (!S.atexit_done) {
        atexit(term_restore);
        S.atexit_done = 1;
    }
    set_modes(t);
    ask_terminal(t, cfg);
    return 0;
}

/* ==== What the session knows ==== */

int term_signalled(Term *t, TermEvent *ev)
{
    if (!repaint && !resized)
        return 0;
    if (resized) {
        resized = 0;
        read_size(t);
    }
    if (repaint) {
        repaint = 0;
        term_out_drop(t);       /* the screen was left: what waited is moot */
        vt_invalidate(&t->vt);
    }
    ev->type = TE_RESIZE;
    return 1;
}

/* Without a session: what a session that was never opened says (no
 * colour, cells, no size, no background). */
ColourDepth term_colour(void) { return S.t ? S.t->depth : COLOUR_NONE; }

int term_colour_answered(void) { return S.t && S.t->depth_answered; }

PixelProto term_pixels(void) { return S.t ? S.t->pix : PIX_CELLS; }

const char *term_mux_hint(int brief)
{
    if (!S.t || !S.t->pix_wanted || S.t->pix != PIX_CELLS || (S.t->mux == MUX_TMUX && !S.t->pane_known))
        return NULL;
    return mux_why_cells(S.t->mux, &S.t->pane, brief);
}

int term_cell_pixels(int *cw, int *ch)
{
    return pixels_cell_size(S.t ? S.t->q.fd : -1, cw, ch);
}

int term_background(uint8_t rgb_out[3], double *waited_ms_out)
{
    Term *t = S.t;
    if (waited_ms_out)
        *waited_ms_out = t ? t->bg_wait_ms : 0;
    if (t && t->bg_known)
        memcpy(rgb_out, t->bg, 3);
    return t && t->bg_known;
}

int term_answered(double *waited_ms_out)
{
    Term *t = S.t;
    *waited_ms_out = t ? t->bg_wait_ms : 0;
    return t ? t->answered : -1;
}

void term_size(int *cols_out, int *rows_out)
{
    *cols_out = S.t ? S.t->cols : 0;
    *rows_out = S.t ? S.t->rows : 0;
}

void term_set_size(int cols, int rows)
{
    if (!S.t)
        return;
    S.t->cols = cols;
    S.t->rows = rows;
    resizeterm(rows, cols);
}
