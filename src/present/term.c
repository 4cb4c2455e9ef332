/* term: the viewer's screen on ncursesw. The only file that includes
 * curses. Everything that changes the terminal's state goes through
 * term_open() and is undone by term_restore(), the one restore path:
 * called on quit, registered with atexit, and from the quit signals.
 *
 * Colour pairs: under 256 colours every (fg, bg) pair of the cube and grey
 * ramp (plus the default colour) is defined once at start and indexed
 * directly, so a pair never changes meaning and curses only sends cells
 * that really changed. Under 16 colours likewise (17 x 17 pairs). Under
 * truecolor, or when the terminal has too few pairs, colours go through
 * a bounded set-associative cache of pairs (truecolor quantised to 6
 * bits a channel so that slowly shading faces keep their pair). */

#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE
#define NCURSES_WIDECHAR 1

#include <curses.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
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

/* ==== State ==== */

static SCREEN *scr;
static FILE *scr_out;
static int in_fd = -1;          /* where keys come from (ncurses keeps it private) */
static volatile sig_atomic_t term_on;
static int mouse_on;
static int signals_on;
static int atexit_done;
static ColorDepth depth;

typedef enum { PAIRS_NONE, PAIRS_16, PAIRS_256, PAIRS_CACHE } PairKind;
static PairKind pair_kind;
static int fold16;              /* 8-colour terminal: bright colours fold onto 0..7 */
static int def_fg = -1, def_bg = -1;   /* the terminal's default colours, or white/black */

/* Bounded pair cache: WAYS pairs per set, the least recently used
 * (by frame stamp) is redefined on a miss. Pair number = 1 + slot. */
#define WAYS 8
static uint64_t *cache_key;     /* (fg + 1) << 32 | (bg + 1), 0 = empty */
static uint32_t *cache_stamp;
static uint32_t  cache_sets;
static uint32_t  frame_stamp;

/* Under 256 colours a cell keeps the index it had last frame, or takes
 * its left neighbour's, when that colour is within STICKY (squared RGB
 * distance) of the nearest one: a slowly shading surface then keeps its
 * colours from frame to frame and along a row, and curses has fewer
 * cells and colour changes to send. prev256 holds fg | bg << 8 per cell
 * (0 = none). */
#define STICKY 300
static uint16_t *prev256;
static int prev_cols, prev_rows;
static uint8_t pal_rgb[256][3];

static cchar_t *row_buf;        /* one row of cells for term_draw_cells */
static size_t   row_cap;

/* Mouse drag state: ncurses reports motion without the button. */
static int drag_button, drag_x, drag_y;

static struct sigaction old_int, old_term, old_hup, old_tstp;

#define DRAG_ON  "\033[?1002h"
#define DRAG_OFF "\033[?1002l"

/* ==== Restore and signals ==== */

/* One byte to the terminal, now. */
static int send_byte(int c)
{
    unsigned char b = (unsigned char)c;
    return write(fileno(scr_out), &b, 1) == 1 ? c : EOF;
}

/* Send a capability (or an escape of our own) to the terminal now.
 * Curses keeps its output in a buffer of its own that every update
 * empties, so between updates this lands in order. putp() would not: it
 * goes through stdio's stdout buffer, which nothing flushes until exit
 * (the drag reporting asked for at start reached the terminal only as
 * zview quit). */
static void send_cap(const char *cap)
{
    if (cap && cap != (const char *)-1 && scr_out)
        tputs(cap, 1, send_byte);
}

/* Blank the terminal before leaving curses: a terminal whose window grew
 * while in the alternate screen (tmux) keeps the part beyond the old size
 * when it switches back, and a terminal without one keeps everything.
 * Sent to the terminal, not drawn in stdscr: curses' copy of the screen
 * stays for a resume after Ctrl-Z. */
static void blank_terminal(void)
{
    send_cap(tigetstr("clear"));
}

void term_restore(void)
{
    if (!term_on)
        return;
    term_on = 0;
    if (mouse_on)
        send_cap(DRAG_OFF);
    blank_terminal();
    endwin();           /* cursor back, alternate screen left, modes reset */
    if (scr_out)
        fflush(scr_out);
}

/* ==== Crashes ====
 * A fatal signal (a bug) must not leave the shell in the alternate screen
 * with echo off. Its handler may only use async-signal-safe calls, so the
 * bytes that undo our modes and the terminal's original settings are
 * prepared at open: the handler writes them, restores the termios, and
 * dies of the same signal with the default action. */

static char crash_reset[256];
static size_t crash_reset_len;
static struct termios crash_tios;
static int crash_fd = -1, crash_tios_ok;
static struct sigaction old_crash[5];
static const int crash_sigs[5] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT };

static void crash_add(const char *cap)
{
    if (!cap || cap == (const char *)-1)
        return;
    size_t n = strlen(cap);
    if (crash_reset_len + n < sizeof crash_reset) {
        memcpy(crash_reset + crash_reset_len, cap, n);
        crash_reset_len += n;
    }
}

/* Undo our modes: only write(2) and tcsetattr(3), both signal-safe. */
static void crash_write(void)
{
    if (term_on && crash_fd >= 0) {
        ssize_t w = write(crash_fd, crash_reset, crash_reset_len);
        (void)w;
        if (crash_tios_ok)
            tcsetattr(crash_fd, TCSANOW, &crash_tios);
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
    crash_fd = fd;
    crash_tios_ok = tcgetattr(fd, &crash_tios) == 0;
    crash_reset_len = 0;
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
        sigaction(crash_sigs[i], &sa, &old_crash[i]);
}

static void restore_handlers(void)
{
    if (!signals_on)
        return;
    signals_on = 0;
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    sigaction(SIGHUP, &old_hup, NULL);
    sigaction(SIGTSTP, &old_tstp, NULL);
}

/* Quit signals: put the terminal back with the async-signal-safe bytes
 * prepared at open (crash_write below; endwin() is not safe here), then
 * die of the same signal so the parent sees the real cause. */
static void crash_write(void);
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

/* Ctrl-Z: leave curses (and drag reporting) before stopping, come back
 * with a full repaint on SIGCONT. */
static void on_tstp(int sig)
{
    int was_on = term_on;
    if (was_on) {
        if (mouse_on)
            send_cap(DRAG_OFF);
        blank_terminal();
        endwin();
        fflush(scr_out);
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
        if (mouse_on)
            send_cap(DRAG_ON);
        clearok(curscr, TRUE);
        doupdate();
    }
}

static void install_handlers(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_handler = on_quit;
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    sigaction(SIGHUP, &sa, &old_hup);
    sa.sa_handler = on_tstp;
    sa.sa_flags = SA_RESTART;
    sigaction(SIGTSTP, &sa, &old_tstp);
    signals_on = 1;
}

/* ==== Colour pairs ==== */

static int fg_or_default(int c) { return c < 0 ? def_fg : c; }
static int bg_or_default(int c) { return c < 0 ? def_bg : c; }

static int cache_init(int npairs)
{
    if (npairs > 32768)
        npairs = 32768;
    cache_sets = (uint32_t)(npairs / WAYS);
    if (cache_sets == 0)
        return -1;
    size_t n = (size_t)cache_sets * WAYS;
    free(cache_key);
    free(cache_stamp);
    cache_key = calloc(n, sizeof *cache_key);
    cache_stamp = calloc(n, sizeof *cache_stamp);
    if (!cache_key || !cache_stamp) {
        free(cache_key);
        free(cache_stamp);
        cache_key = NULL;
        cache_stamp = NULL;
        cache_sets = 0;
        return -1;
    }
    return 0;
}

/* The pair showing colour numbers fg on bg (-1 = default). */
static int cache_pair(int fg, int bg)
{
    if (fg < 0 && bg < 0)
        return 0;
    uint64_t key = ((uint64_t)(uint32_t)(fg + 1) << 32) | (uint32_t)(bg + 1);
    uint32_t set = (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> 40) % cache_sets;
    uint32_t base = set * WAYS, victim = base;
    for (uint32_t i = base; i < base + WAYS; i++) {
        if (cache_key[i] == key) {
            cache_stamp[i] = frame_stamp;
            return (int)i + 1;
        }
        if (cache_key[i] == 0 || cache_stamp[i] < cache_stamp[victim])
            victim = i;
        if (cache_key[i] == 0)
            break;
    }
    cache_key[victim] = key;
    cache_stamp[victim] = frame_stamp;
    init_extended_pair((int)victim + 1, fg_or_default(fg), bg_or_default(bg));
    return (int)victim + 1;
}

static inline int dist2(const uint8_t a[3], const uint8_t b[3])
{
    int dr = a[0] - b[0], dg = a[1] - b[1], db = a[2] - b[2];
    return dr * dr + dg * dg + db * db;
}

/* The 256-colour index for rgb, preferring the cell's previous index,
 * then its left neighbour's, when they are nearly as close. */
static inline int pick256(const uint8_t rgb[3], int prev, int left)
{
    int best = palette_256(rgb);
    if (best == prev || best == left)
        return best;
    int lim = dist2(rgb, pal_rgb[best]) + STICKY;
    if (prev && dist2(rgb, pal_rgb[prev]) <= lim)
        return prev;
    if (left && dist2(rgb, pal_rgb[left]) <= lim)
        return left;
    return best;
}

static inline int c16(const uint8_t rgb[3])
{
    if (!fold16)
        return palette_16(rgb);
    /* 8 colours: the nearest of those (folding bright grey onto black
     * would lose every grey surface) */
    int best = 0, bestd = 1 << 30;
    for (int i = 0; i < 8; i++) {
        int d = dist2(rgb, pal_rgb[i]);
        if (d < bestd) {
            bestd = d;
            best = i;
        }
    }
    return best;
}

/* Colour number of a cell colour under the depth in use (-1 = unset). */
static inline int colour_number(const uint8_t rgb[3], int set)
{
    if (!set)
        return -1;
    switch (depth) {
    case COLOR_TRUE:
        /* 6 bits a channel, widened back to 8 */
        return ((rgb[0] & 0xfc) | rgb[0] >> 6) << 16 | ((rgb[1] & 0xfc) | rgb[1] >> 6) << 8 |
               ((rgb[2] & 0xfc) | rgb[2] >> 6);
    case COLOR_256: return palette_256(rgb);
    case COLOR_16:  return c16(rgb);
    default:        return -1;
    }
}

static inline int cell_pair(const Cell *c)
{
    switch (pair_kind) {
    case PAIRS_16: {
        int f = c->flags & CELL_FG ? c16(c->fg) + 1 : 0;
        int b = c->flags & CELL_BG ? c16(c->bg) + 1 : 0;
        return f * 17 + b;
    }
    case PAIRS_CACHE:
        return cache_pair(colour_number(c->fg, c->flags & CELL_FG),
                          colour_number(c->bg, c->flags & CELL_BG));
    default:
        return 0;
    }
}

static void colours_init(ColorDepth want)
{
    depth = COLOR_NONE;
    pair_kind = PAIRS_NONE;
    if (want == COLOR_NONE || !has_colors() || start_color() == ERR)
        return;
    if (use_default_colors() == ERR) {
        def_fg = COLOR_WHITE;
        def_bg = COLOR_BLACK;
    }
    int colors = COLORS, pairs = COLOR_PAIRS;
    if (want == COLOR_TRUE && colors >= 0x1000000)
        depth = COLOR_TRUE;
    else if (want >= COLOR_256 && colors >= 256)
        depth = COLOR_256;
    else if (colors >= 8)
        depth = COLOR_16;
    else
        return;
    fold16 = colors < 16;
    for (int i = 0; i < 256; i++)
        palette_256_rgb(i, pal_rgb[i]);
    if (depth == COLOR_256 && pairs > 241 * 241) {
        pair_kind = PAIRS_256;
        for (int f = 0; f <= 240; f++)
            for (int b = 0; b <= 240; b++)
                if (f || b)
                    init_extended_pair(f * 241 + b, fg_or_default(f ? f + 15 : -1),
                                       bg_or_default(b ? b + 15 : -1));
    } else if (depth == COLOR_16 && pairs > 17 * 17) {
        pair_kind = PAIRS_16;
        int top = fold16 ? 8 : 16;
        for (int f = 0; f <= 16; f++)
            for (int b = 0; b <= 16; b++)
                if ((f || b) && f <= top && b <= top)
                    init_extended_pair(f * 17 + b, fg_or_default(f - 1), bg_or_default(b - 1));
    } else if (cache_init(pairs - 1) == 0) {
        pair_kind = PAIRS_CACHE;
    } else {
        depth = COLOR_NONE;
    }
}

/* ==== Start ==== */

int term_open(const TermConfig *cfg, char *err, size_t errlen)
{
    if (term_on) {
        snprintf(err, errlen, "terminal already open");
        return -1;
    }
    FILE *out = cfg->out ? cfg->out : stdout, *in = cfg->in ? cfg->in : stdin;
    /* Our handlers go in first: ncurses then leaves SIGINT/SIGTERM/SIGTSTP
     * alone (it only catches signals still at their default) and keeps
     * SIGWINCH, which becomes KEY_RESIZE. */
    if (cfg->signals)
        install_handlers();
    fflush(out);
    /* Look the terminal up first: newterm() leaks when it fails. */
    int found = 0;
    if (setupterm(cfg->termname, fileno(out), &found) != OK || found != 1) {
        restore_handlers();
        snprintf(err, errlen, "unknown terminal type '%s'",
                 cfg->termname ? cfg->termname : getenv("TERM") ? getenv("TERM") : "");
        return -1;
    }
    if (cfg->signals)
        crash_prepare(fileno(out));   /* termios as the shell left it */
    del_curterm(set_curterm(NULL));
    SCREEN *s = newterm(cfg->termname, out, in);
    if (!s) {
        restore_handlers();
        snprintf(err, errlen, "unknown terminal type '%s'",
                 cfg->termname ? cfg->termname : getenv("TERM") ? getenv("TERM") : "");
        return -1;
    }
    set_term(s);
    const char *cup = tigetstr("cup");
    if (!cup || cup == (const char *)-1) {
        endwin();
        delscreen(s);
        restore_handlers();
        snprintf(err, errlen, "the terminal cannot move the cursor");
        return -1;
    }
    scr = s;
    scr_out = out;
    in_fd = fileno(in);
    term_on = 1;
    if (!atexit_done) {
        atexit(term_restore);
        atexit_done = 1;
    }
    cbreak();
    noecho();
    nonl();
    intrflush(stdscr, FALSE);
    keypad(stdscr, TRUE);
    leaveok(stdscr, TRUE);      /* no cursor moves back after each update */
    curs_set(0);
    set_escdelay(25);
    colours_init(cfg->color);
    mouse_on = 0;
    drag_button = 0;
    if (cfg->mouse) {
        mmask_t want = BUTTON1_PRESSED | BUTTON1_RELEASED | BUTTON3_PRESSED | BUTTON3_RELEASED |
                       BUTTON4_PRESSED | BUTTON5_PRESSED | REPORT_MOUSE_POSITION;
        if (mousemask(want, NULL) != 0) {
            mouseinterval(0);   /* presses and releases as they come, no clicks */
            send_cap(DRAG_ON);      /* ncurses never asks for drag reports itself */
            mouse_on = 1;
        }
    }
    return 0;
}

ColorDepth term_color(void) { return depth; }

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

/* ==== Drawing ==== */

void term_draw_cells(const CellGrid *g, int top)
{
    int H, W;
    getmaxyx(stdscr, H, W);
    frame_stamp++;
    int cols = g->cols < W ? g->cols : W;
    if (cols <= 0)
        return;
    /* A row is built as cchar_t and copied in one call: much cheaper
     * than adding cell by cell (no cursor, wrap or attribute logic). */
    if ((size_t)cols > row_cap) {
        cchar_t *nb = realloc(row_buf, (size_t)cols * sizeof *nb);
        if (!nb)
            return;
        row_buf = nb;
        row_cap = (size_t)cols;
    }
    if (pair_kind == PAIRS_256 && (g->cols != prev_cols || g->rows != prev_rows || !prev256)) {
        free(prev256);
        prev256 = calloc((size_t)g->cols * g->rows + 1, sizeof *prev256);
        prev_cols = g->cols;
        prev_rows = g->rows;
    }
    wchar_t wc[2] = { 0, 0 };
    for (int r = 0; r < g->rows && top + r < H; r++) {
        const Cell *c = g->cells + (size_t)r * g->cols;
        uint16_t *pv = prev256 ? prev256 + (size_t)r * g->cols : NULL;
        int lf = 0, lb = 0;
        for (int x = 0; x < cols; x++, c++) {
            int pair;
            if (pair_kind == PAIRS_256 && pv) {
                int f = c->flags & CELL_FG ? pick256(c->fg, pv[x] & 0xff, lf) : 0;
                int b = c->flags & CELL_BG ? pick256(c->bg, pv[x] >> 8, lb) : 0;
                pv[x] = (uint16_t)(f | b << 8);
                lf = f;
                lb = b;
                pair = (f ? f - 15 : 0) * 241 + (b ? b - 15 : 0);
            } else {
                pair = cell_pair(c);
            }
            wc[0] = (wchar_t)c->ch;
            setcchar(&row_buf[x], wc, A_NORMAL, 0, &pair);
        }
        mvwadd_wchnstr(stdscr, top + r, 0, row_buf, cols);
    }
}

void term_draw_bar(int y, const char *text)
{
    int H, W;
    getmaxyx(stdscr, H, W);
    if (y < 0 || y >= H)
        return;
    int pair = 0;
    wattr_set(stdscr, A_REVERSE, 0, &pair);
    wmove(stdscr, y, 0);
    int n = (int)strlen(text);
    if (n > W)
        n = W;
    waddnstr(stdscr, text, n);
    for (int x = n; x < W; x++)
        waddch(stdscr, ' ');    /* the bottom-right cell returns ERR but is written */
    wattr_set(stdscr, A_NORMAL, 0, &pair);
}

void term_draw_box(const char *const *lines, int n)
{
    int H, W;
    getmaxyx(stdscr, H, W);
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
    int x0 = (W - w) / 2, y0 = (H - 1 - h) / 2;
    int pair = 0;
    wattr_set(stdscr, A_NORMAL, 0, &pair);
    for (int r = 0; r < h; r++) {
        wmove(stdscr, y0 + r, x0);
        int edge = r == 0 || r == h - 1;
        const char *t = !edge && r - 1 < n ? lines[r - 1] : "";
        int len = (int)strlen(t);
        for (int x = 0; x < w; x++) {
            char ch;
            if (edge)
                ch = x == 0 || x == w - 1 ? '+' : '-';
            else if (x == 0 || x == w - 1)
                ch = '|';
            else
                ch = x - 2 >= 0 && x - 2 < len ? t[x - 2] : ' ';
            waddch(stdscr, (chtype)(unsigned char)ch);
        }
    }
}

void term_erase(void)
{
    werase(stdscr);
}

void term_message(const char *text)
{
    int H, W;
    getmaxyx(stdscr, H, W);
    werase(stdscr);
    int n = (int)strlen(text);
    if (n > W)
        n = W;
    mvwaddnstr(stdscr, H / 2, (W - n) / 2, text, n);
}

void term_update(int full)
{
    if (full)
        clearok(curscr, TRUE);
    wnoutrefresh(stdscr);
    doupdate();
}

/* ==== Input ==== */

/* Mouse reports that arrive together come out of ncurses as one KEY_MOUSE
 * with several queued events: they are drained into this queue. */
#define MQ_MAX 16
static TermEvent mq[MQ_MAX];
static int mq_head, mq_len;

static void mq_push(const TermEvent *ev)
{
    if (mq_len < MQ_MAX)
        mq[(mq_head + mq_len++) % MQ_MAX] = *ev;
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
        drag_button = b & BUTTON1_PRESSED ? 1 : 3;
        drag_x = me->x;
        drag_y = me->y;
        return 0;
    }
    int release = (b & (BUTTON1_RELEASED | BUTTON3_RELEASED)) != 0;
    if (!drag_button || !(release || (b & REPORT_MOUSE_POSITION)))
        return 0;
    ev->type = TE_DRAG;
    ev->button = drag_button;
    ev->dx = me->x - drag_x;
    ev->dy = me->y - drag_y;
    drag_x = me->x;
    drag_y = me->y;
    if (release)
        drag_button = 0;
    return ev->dx || ev->dy;
}

static int mq_pop(TermEvent *ev)
{
    if (!mq_len)
        return 0;
    *ev = mq[mq_head];
    mq_head = (mq_head + 1) % MQ_MAX;
    mq_len--;
    return 1;
}

static void mouse_drain(void)
{
    MEVENT me;
    TermEvent ev;
    while (getmouse(&me) == OK)
        if (mouse_event(&me, &ev))
            mq_push(&ev);
}

/* wget_wch gave ERR: a timeout, a signal, or the end of the input (a
 * hung-up terminal, a file or pipe at its end), where every read returns
 * at once and waiting again would spin. The end shows as input that
 * polls readable with no byte waiting. */
static int input_ended(void)
{
    struct pollfd p = { .fd = in_fd, .events = POLLIN };
    if (in_fd < 0 || poll(&p, 1, 0) <= 0)
        return 0;       /* nothing pending: a timeout or a signal */
    int n = 0;
    if (ioctl(in_fd, FIONREAD, &n) == 0 && n > 0)
        return 0;       /* a key came just after the timeout */
    return 1;
}

int term_read(TermEvent *ev, int timeout_ms)
{
    memset(ev, 0, sizeof *ev);
    if (mq_pop(ev))
        return 1;
    wtimeout(stdscr, timeout_ms);
    for (;;) {
        wint_t wc;
        int r = wget_wch(stdscr, &wc);
        if (r == ERR)
            return input_ended() ? -1 : 0;
        if (r != KEY_CODE_YES) {
            ev->type = TE_KEY;
            ev->key = (int)wc;
            return 1;
        }
        ev->type = TE_KEY;
        switch (wc) {
        case KEY_UP:     ev->key = TK_UP; return 1;
        case KEY_DOWN:   ev->key = TK_DOWN; return 1;
        case KEY_LEFT:   ev->key = TK_LEFT; return 1;
        case KEY_RIGHT:  ev->key = TK_RIGHT; return 1;
        case KEY_BTAB:   ev->key = TK_BTAB; return 1;
        case KEY_RESIZE: ev->type = TE_RESIZE; return 1;
        case KEY_MOUSE:
            mouse_drain();
            if (mq_pop(ev))
                return 1;
            break;
        default:
            break;      /* other function keys mean nothing here */
        }
        memset(ev, 0, sizeof *ev);
    }
}
