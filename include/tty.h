#ifndef ZV_TTY_H
#define ZV_TTY_H
/* tty: the viewer's terminal, the room src/tty/. The session (term.c)
 * owns curses (the only file that includes it), for the terminal's
 * modes and its description: start and the one restore path (atexit,
 * SIGINT/SIGTERM/SIGHUP, SIGTSTP and back). What is drawn (a cell grid,
 * the status line, overlays) goes into a screen model (vt.c) whose
 * changes term_update() sends (termdraw.c); the input is read as plain
 * events (keys, mouse drags) through our key parser (keys.c, termread.c).
 * termbg.c and termgfx.c ask the terminal its background and which
 * pixels it draws. */

#include <stddef.h>
#include <stdio.h>
#include "pixels.h"
#include "present.h"

/* Keys: characters are their code point; the rest sit above Unicode. */
enum {
    TK_TAB = 9,
    TK_ENTER = 10,      /* Return and the keypad's Enter, whatever the tty's CR/NL mapping */
    TK_BACKSPACE = 127, /* whichever of ^H and DEL the terminal sends */
    TK_CTRL_L = 12,
    TK_ESC = 27,
    TK_UP = 0x110000,
    TK_DOWN,
    TK_LEFT,
    TK_RIGHT,
    TK_BTAB,            /* shift-Tab */
    TK_DEL,             /* Delete */
    TK_HOME,
    TK_END,
    TK_INS,             /* Insert */
    TK_PGUP,            /* Page Up */
    TK_PGDN,            /* Page Down */
    TK_SUP,             /* the arrows with Shift */
    TK_SDOWN,
    TK_SLEFT,
    TK_SRIGHT,
    TK_LAST = TK_SRIGHT,
};

typedef enum {
    TE_KEY = 1,         /* key */
    TE_RESIZE,          /* the window changed size */
    TE_DRAG,            /* button 1 (left) or 3 (right) held, moved dx, dy cells */
    TE_WHEEL,           /* dy = -1 up (away from the user), +1 down */
    TE_READY,           /* the terminal has taken the last frame: the next may go
                           (from the key parser: the answer to a status request) */
    TE_CLICK,           /* button 1 (left) or 3 (right) pressed on cell x, y (a drag may follow) */
} TermEventType;

typedef struct {
    TermEventType type;
    int key;            /* TE_KEY */
    int button;         /* TE_DRAG: 1 left, 3 right */
    int dx, dy;         /* TE_DRAG, TE_WHEEL */
    int x, y;           /* TE_CLICK, TE_DRAG: the cell (a drag's: where it reached),
                           from the window's top left */
    int mods;           /* TE_CLICK, TE_DRAG: TE_SHIFT | TE_META | TE_CTRL, as the
                           terminal reports them (many keep Shift for selecting) */
} TermEvent;

enum { TE_SHIFT = 1, TE_META = 2, TE_CTRL = 4 };

typedef struct {
    FILE       *out, *in;       /* NULL: stdout, stdin */
    const char *termname;       /* NULL: $TERM */
    ColourDepth  colour;          /* wanted; lowered to what the terminal has */
    int         colour_env;     /* colour is the environment's guess (no --color): below 24 bits,
                                   the terminal is asked what it draws (termbg.c) */
    int         mouse;          /* report clicks, drags and the wheel */
    int         signals;        /* restore on SIGINT/SIGTERM/SIGHUP, handle SIGTSTP */
    int         ask_bg;         /* ask the terminal for its background (termbg.c) */
    int         pixels;         /* PixelProto to draw stills in; PIX_AUTO: ask (pixels.h) */
    int         ask_ms;         /* the one wait for the answers; 0: TERM_ASK_MS (the tests
                                   give a loaded machine longer) */
} TermConfig;

/* The terminal description to use for name (NULL: $TERM): name itself
 * when it is installed, else the first installed of xterm-256colour,
 * xterm, vt100 and ansi; NULL when none is. */
const char *term_resolve(const char *name);

/* Start curses. Returns 0, or -1 with a reason in err when the terminal
 * cannot be driven (unknown TERM, no ANSI cursor addressing): the caller
 * falls back to --print. The terminal is then untouched. Colours: 24-bit
 * when asked (cfg->colour), else what is asked lowered to what the
 * description has. */
int  term_open(const TermConfig *cfg, char *err, size_t errlen);
/* Leave curses and put the terminal back as it was. Idempotent; also
 * registered with atexit and called from the quit signals. */
void term_restore(void);

ColourDepth term_colour(void);            /* the depth actually used */
int  term_colour_answered(void);          /* ... is what the terminal answered, above its environment's */
/* Pixels: the protocol the terminal takes (PIX_CELLS: none, or not
 * wanted), its cell size in pixels (0 when it does not say), an image
 * drawn from the top left over the picture, and taken away again (the
 * next term_update draws every cell). Quitting, Ctrl-Z and a resize's
 * full redraw clear images too. */
PixelProto term_pixels(void);
int  term_cell_pixels(int *cw, int *ch);
int  term_show_image(const ByteBuf *b);
void term_hide_image(void);
/* Images through tmux's passthrough: has the pane moved, or come to show
 * or stopped showing (another window, another pane zoomed), since tmux
 * was last asked? Asks at most every MUX_POLL_MS (else 0). */
int  term_pane_moved(void);
/* The ms until term_pane_moved asks again, -1 when it never does. */
int  term_pane_poll_ms(void);
/* Why the pixels are cells when a multiplexer is the reason (and how to
 * change it), else NULL. */
const char *term_mux_hint(int brief);
int  term_image_shown(void);
/* The terminal's background as it answered at open: 1 with rgb_out, 0
 * when it did not (or was not asked); waited_ms_out (may be NULL): how
 * long the question took. */
int  term_background(uint8_t rgb_out[3], double *waited_ms_out);
/* The start's questions: 1 when their last answer came within the wait
 * (*waited_ms_out: how long they took), 0 when it did not, -1 when none
 * were asked (not a terminal, nothing to ask). */
int  term_answered(double *waited_ms_out);
void term_size(int *cols_out, int *rows_out);
/* Pretend the window is cols x rows (the tty benchmark writes to a file). */
void term_set_size(int cols, int rows);

/* Draw a grid with its top-left cell at (0, top); clipped to the window. */
void term_draw_cells(const CellGrid *g, int top);
/* One line of text in reverse video on row y, padded to the width. */
void term_draw_bar(int y, const char *text);
/* A framed box of lines centred in the window (the help overlay). */
void term_draw_box(const char *const *lines, int n);
/* The same box with its top-left corner at column x, row y; x < 0: its
 * right edge at the window's, y < 0: its bottom just above the status
 * line (the info panel, the open prompt's candidates). */
void term_draw_box_at(const char *const *lines, int n, int x, int y);
/* Show a cursor at column x of row y: that cell out of reverse video
 * (the status line's prompt; the terminal's own cursor stays hidden). */
void term_bar_cursor(int y, int x);
/* Blank the window and centre a short message (window too small). */
void term_message(const char *text);
/* Blank the window (before a redraw at a new size). */
void term_erase(void);
/* Send the changes since the last update; everything when full (Ctrl-L).
 * Returns 0, or -1 with errno when the terminal cannot be written. */
int  term_update(int full);
size_t term_last_bytes(void);           /* bytes the last update sent */
/* Frame pacing (see vt_may_send): may a frame go now? If not, read
 * input for at most term_pace_ms() and ask again; a TE_READY event comes
 * when the terminal has taken the last frame. */
int  term_ready(void);
int  term_pace_ms(void);

/* Wait up to timeout_ms (< 0: forever, 0: poll) for an event. Returns 1
 * with *ev filled, 0 when none came, -1 when the input has ended (a
 * hung-up terminal, a file at its end): no key will ever come, and
 * waiting again would return at once. */
int  term_read(TermEvent *ev, int timeout_ms);

/* ==== The key parser (keys.c) ====
 * The terminal's input bytes -> TermEvents (keys, mouse, the answer to a
 * status request); every sequence it does not know, and every answer a
 * terminal gives (CSI, OSC, DCS, APC, PM, SOS strings, with BEL or ST,
 * 7-bit or 8-bit), is dropped whole, however it is split. No I/O and no
 * clock: term.c pushes what it reads with the time it read it, says when
 * it has asked the terminal something, and asks for events at a time;
 * the quiet after an ESC is how a lone Esc is told from the start of a
 * sequence, longer while an answer is on its way. */

#define KP_ESC_MS   25          /* an unfinished sequence this long quiet is decided: a lone ESC is Esc */
#define KP_REPLY_MS 500         /* ... while an answer is awaited (a slow link splits one after its ESC) */
#define KP_IDLE_MS  1000        /* a paste or string still open after this much quiet has ended */
#define KP_LATE_MS  10000       /* answers awaited this long after the last question are not coming */
#define KP_STRING_MAX 4096      /* a string (or CSI) this long is no answer: given up, the input read afresh */

typedef struct {
    unsigned char b[1024];      /* bytes pushed, not yet parsed */
    size_t   len;
    int      utf8;              /* decode UTF-8 (C1 controls as U+0080-U+009F); else a byte is
                                   its own code point (C1 controls as bytes 0x80-0x9f) */
    int      paste;             /* inside a bracketed paste: dropped to its end */
    int      string;            /* inside a string: its kind (']' OSC, 'P' DCS, '_' APC, '^' PM,
                                   'X' SOS), dropped to its end; 0 none */
    int      skip;              /* inside an overlong CSI sequence: dropped to its final byte */
    size_t   run;               /* bytes of the string or overlong CSI dropped so far */
    int      pending;           /* answers awaited (kp_expect), each the last of its questions */
    double   asked_ms;          /* when the last question went */
    double   last_ms;           /* when bytes last came */
    int      drag_button;       /* the mouse button held (1 left, 3 right), 0 none */
    int      drag_x, drag_y;    /* the cell the drag reached */
} KeyParser;

void   kp_init(KeyParser *p, int utf8);
/* Append input that came at now_ms; returns how many bytes fit (the rest
 * must wait). After KP_IDLE_MS without input a paste or string still open
 * has lost its end: what comes now is keys. */
size_t kp_push(KeyParser *p, const void *bytes, size_t n, double now_ms);
/* The next event in what was pushed: 1 with *ev, or 0 when nothing is
 * complete at now_ms. An unfinished sequence is decided once the input
 * has been quiet for kp_wait_ms(); the caller reads what is waiting
 * first (a decision on bytes not yet read would split a sequence). */
int    kp_next(KeyParser *p, TermEvent *ev, double now_ms);
/* The ms from now_ms until kp_next decides what is left (0: now), -1 when
 * it waits for nothing. */
int    kp_wait_ms(const KeyParser *p, double now_ms);
/* The caller has sent questions whose last answer is the attributes'
 * (ESC [ ? ... c) or a status report (ESC [ 0 n): `more` answers more
 * are awaited (0: the question only went out now, after queueing). Until
 * they come (or KP_LATE_MS after the last question), a lone ESC waits
 * KP_REPLY_MS for the rest of an answer before it is the Esc key. */
void   kp_expect(KeyParser *p, int more, double now_ms);
/* The answers still awaited at now_ms. */
int    kp_awaiting(const KeyParser *p, double now_ms);

/* ==== The terminal's background (termbg.c) ====
 * The colour query (OSC 11) and the device-attributes request after it,
 * whose answer says that no other is coming. */

#define TERMBG_WAIT_MS  200     /* a terminal that answers neither (none known) costs this once */
#define TERM_ASK_MS     100     /* the viewer's start: every question at once, answered within this or late */
#define TERMBG_BODY_MAX 63      /* a string's bytes kept: "11;rgba:ffff/ffff/ffff/ffff" fits */

/* "rgb:RRRR/GGGG/BBBB" (1 to 4 hex digits a channel) or rgba: with an
 * alpha after, as terminals answer -> rgb_out. Returns 0, or -1. */
int  termbg_parse_colour(const char *spec, uint8_t rgb_out[3]);

/* The answers found in the input, byte by byte (any split). */
typedef struct {
    int      state;
    char     body[TERMBG_BODY_MAX + 1];
    size_t   len;
    int      csi_private;       /* the CSI sequence began with '?' */
    int      dcs;               /* the string is a DCS (P), not an OSC (]) */
    int      got_bg;            /* an OSC 11 answer with a colour came: bg */
    uint8_t  bg[3];
    ColourDepth colour;         /* the SGR report (DECRQSS) after a 24-bit colour was set: COLOUR_TRUE
                                   when it came back as set, COLOUR_256 as a palette index, else 0 */
    int      got_da;            /* the attributes' answer came: no other will */
} BgScan;

void termbg_scan_init(BgScan *s);
void termbg_scan(BgScan *s, const unsigned char *b, size_t n);

/* What the terminal said to termbg_ask. */
typedef struct {
    int         got_bg;         /* it said its background: bg */
    uint8_t     bg[3];
    ColourDepth colour;         /* asked: the colours its SGR report showed (0: no answer) */
    double      waited_ms;      /* how long the questions took */
    int         answered;       /* the last answer came within the wait */
    BgScan      scan;           /* the answers as read so far: a late one's start may be in it */
} TermAnswers;

/* Which of the pixels' questions (termgfx.c) go with the rest: none,
 * the terminal's, tmux's own attributes, tmux's and (through its
 * passthrough) the outer terminal's. */
typedef enum { PIXQ_NONE, PIXQ_PLAIN, PIXQ_TMUX, PIXQ_TMUX_PASS } PixelAsk;
struct PixelScan;

typedef struct {
    int               ask_bg;           /* its background (OSC 11) */
    int               ask_colour;       /* the colours it draws (a 24-bit colour set, the SGR asked
                                           back with DECRQSS, then reset) */
    PixelAsk          pix;
    struct PixelScan *scan;             /* pix's answers are read into it (pixels_scan_init'd) */
} TermQuestions;

/* Ask the terminal on out_fd the questions q, all in one write, and read
 * its answers from in_fd until the attributes' answer (the last: with
 * PIXQ_TMUX_PASS the outer terminal's) or wait_ms; every byte read goes
 * on to kp (NULL: dropped), so the key parser sees the keys typed
 * meanwhile and drops the answers. The input must not echo (the viewer's
 * curses mode). Returns 1 when the terminal said its background, else 0. */
int  termbg_ask(int out_fd, int in_fd, int wait_ms, KeyParser *kp, const TermQuestions *q, TermAnswers *ans);
/* The same on the controlling terminal (/dev/tty) for --print, put in a
 * mode without echo for the question and back; not from a job in the
 * background, nor on TERM=dumb (or none). Returns 1 with rgb_out, else 0. */
int  termbg_ask_tty(int wait_ms, uint8_t rgb_out[3]);

/* ==== Pixels the terminal takes (termgfx.c) ====
 * The encoders are present/'s (pixels.h); here the questions. */

/* The terminal's cell size in pixels from the window size the kernel
 * keeps for fd (TIOCGWINSZ's pixel fields, which xterm, kitty, foot,
 * WezTerm and others fill); 0 when it does not say. */
int  pixels_cell_size(int fd, int *cw, int *ch);

/* The answers' reader, byte by byte (any split). */
typedef struct PixelScan {
    int    state;
    char   body[64];
    size_t len;
    int    got_da;          /* the attributes' answer came */
    int    sixel;           /* ... and it lists 4 */
    int    kitty;           /* the kitty query was answered OK */
    int    iterm;           /* the terminal's name is iTerm2 */
    int    mux_das;         /* attributes' answers still to come from tmux itself (not the outer terminal) */
    int    mux_sixel;       /* ... and tmux's own listed 4: it draws sixel itself */
    int    via_mux;         /* the other answers are the outer terminal's, through tmux's passthrough */
    int    c1;              /* 8-bit controls too (a locale that is not UTF-8, where they are no
                               text): 0x9b CSI, 0x90 DCS, 0x9f APC, 0x9c ST */
} PixelScan;

/* Which protocol the terminal on out_fd/in_fd takes (PIX_CELLS: none
 * known). Inside tmux or screen, cells without asking (they pass no
 * images by default); else the kitty query and the primary device
 * attributes (attribute 4: sixel) are asked, and the answers read until
 * the attributes' answer or wait_ms. Every byte read is handed to sink
 * (NULL: dropped), so that keys typed meanwhile are not lost. */
typedef void (*PixelSink)(void *ctx, const unsigned char *b, size_t n);
/* s (made by pixels_scan_init) keeps what was read: answers that come
 * after the wait (a slow link) can still be fed to it (term.c does). */
PixelProto pixels_detect(int out_fd, int in_fd, int wait_ms, PixelSink sink, void *ctx, PixelScan *s);
/* The pixels' questions for how, the attributes' last (for termbg_ask's
 * one write). */
const char *pixels_question(PixelAsk how);
/* s is to read the answers to how's questions (tmux's own first). */
void pixels_scan_expect(PixelScan *s, PixelAsk how);
/* What the answers read so far say (PIX_CELLS: no images). */
PixelProto pixels_scanned(const PixelScan *s);
/* Those pixels are the outer terminal's, drawn through tmux's passthrough. */
int pixels_through_mux(const PixelScan *s);

void pixels_scan_init(PixelScan *s, int c1);
void pixels_scan(PixelScan *s, const unsigned char *b, size_t n);
/* What the environment says before any question: PIX_CELLS inside a
 * multiplexer or on a terminal that would show the questions, else
 * PIX_AUTO (ask). */
PixelProto pixels_from_env(void);

/* ==== Multiplexers (mux.c) ====
 * tmux and GNU screen, and images through tmux's passthrough. */

#define MUX_ASK_MS  200         /* tmux's answer about its pane (a few ms) is waited for this long */
#define MUX_POLL_MS 500         /* how often the viewer asks again whether the pane moved or shows */

typedef enum { MUX_NONE, MUX_TMUX, MUX_SCREEN } MuxKind;

/* What tmux says of the pane zview runs in. */
typedef struct {
    int top, left;              /* its top left corner on the outer terminal, cells from 0 */
    int pass;                   /* allow-passthrough is on for it */
    int shows;                  /* its window is the current one and no other pane is zoomed */
    int attached;               /* a client (an outer terminal) is attached to its session */
} MuxPane;

/* The multiplexer the environment names (TMUX, STY, TERM). */
MuxKind mux_from_env(void);
/* Ask tmux (the program, with TMUX_PANE's pane) about the pane, waiting
 * at most wait_ms. Returns 0, or -1 when tmux did not say. */
int  mux_tmux_pane(MuxPane *m, int wait_ms);
/* tmux's answer "top left passthrough window_active zoomed pane_active
 * clients" -> m. Returns 0, or -1 when it is not that. */
int  mux_parse_pane(const char *s, MuxPane *m);
/* b[0..n) for the outer terminal, wrapped in tmux's passthrough (ESCs
 * doubled), drawn from the pane's top left corner, the outer cursor put
 * back after. Appends to out; returns 0, or -1 out of memory. */
int  mux_wrap(ByteBuf *out, const MuxPane *m, const unsigned char *b, size_t n);
/* Why there are cells and not pixels in this multiplexer (what to do
 * about it), or NULL when it is not the multiplexer's doing; brief: in
 * few words, for the status bar. */
const char *mux_why_cells(MuxKind k, const MuxPane *m, int brief);

/* ==== The screen model (vt.c) ====
 * What the terminal should show (want) and what it shows (shown), cell
 * by cell, and the bytes that take it from one to the other: only the
 * cells that look different, in the shortest escapes. No curses here:
 * term.c composes the picture, the status bar and the overlays into
 * want and writes the bytes. */

#define VT_REVERSE 1            /* VtCell.attr: reverse video (the status bar) */

typedef struct {
    uint32_t ch;                /* code point, one column wide */
    uint32_t fg, bg;            /* colour keys (CK_*, present.h) */
    uint8_t  attr;              /* VT_REVERSE or 0 */
} VtCell;

/* What the terminal can do beyond ANSI cursor addressing and SGR, from
 * its terminfo description. */
typedef struct {
    int ech;                    /* \e[nX erases n characters */
    int el;                     /* \e[K erases to the end of the line */
    int rel;                    /* \e[nA..D move relative */
    int hpa, vpa;               /* \e[nG, \e[nd: to a column, to a row */
    int lf;                     /* a line feed keeps the column (no ONLCR) */
    int am, xenl;               /* auto margins; the newline glitch (writing the
                                   last column leaves the cursor there) */
    char clear[32];             /* clears the screen, cursor home */
} VtCaps;

typedef struct {
    int      cols, rows;
    VtCell  *want, *shown;
    int     *blank;             /* scratch: blank cells from each column on */
    size_t   ncap;
    int      valid;             /* shown is what the terminal shows */
    VtCaps   caps;
    char    *buf;               /* the bytes of the last vt_encode */
    size_t   len, cap;
    int      oom;
    /* the terminal as the bytes so far leave it */
    int      cy, cx;            /* cursor (cy < 0: unknown; cx == cols: wrap pending) */
    uint32_t fg, bg;
    uint8_t  attr;
    int      sgr_ok;            /* fg, bg, attr known */
} Vt;

void vt_init(Vt *v, const VtCaps *caps);
void vt_free(Vt *v);
/* A new size: want blank, and the next encode repaints everything.
 * Returns 0, or -1 out of memory. */
int  vt_resize(Vt *v, int cols, int rows);
void vt_clear(Vt *v);           /* want all blank */
void vt_invalidate(Vt *v);      /* the terminal's content is unknown: repaint all */
VtCell *vt_at(Vt *v, int y, int x);     /* a cell of want, NULL outside */
/* Text into row y from column x, at most maxw columns, made safe first
 * (safetext.h: a control shows as \x1b, four columns); a character that
 * is not one column wide shows as '?'. Returns the columns used. */
int  vt_text(Vt *v, int y, int x, const char *s, int maxw, uint8_t attr);
/* The columns vt_text gives the first `bytes` bytes of s. */
int  vt_text_cols(const char *s, size_t bytes);
/* A framed box of lines into want (term_draw_box_at says where). */
void vt_box(Vt *v, const char *const *lines, int n, int bx, int by);
/* The bytes from shown to want into buf/len; shown is then want.
 * Returns 0, or -1 out of memory. */
int  vt_encode(Vt *v);
/* Two cells that the terminal shows alike (an upper half block of a on
 * b is a lower half block of b on a; a space on c is a full block of c). */
int  vt_same_look(const VtCell *a, const VtCell *b);

/* Frame pacing: may a new frame be sent while `queued` bytes still wait
 * in the terminal's output queue, the line being writable or not, and an
 * answer to the last frame's status request outstanding for waited_ms
 * (waited_ms < 0: none outstanding)? A frame sent while the last one is
 * still on its way only queues behind it: the viewer waits and renders
 * the newest state instead. */
int  vt_may_send(long queued, int writable, double waited_ms);
#define VT_QUEUE_SLACK 256      /* bytes still queued that count as drained */
#define VT_ACK_PATIENCE_MS 1000 /* an answer this late is taken as lost */

#endif
