#ifndef ZV_TTY_H
#define ZV_TTY_H
/* tty: the viewer's screen (src/present/term.c). Owns curses (only term.c includes it): start
 * and the one restore path (atexit, SIGINT/SIGTERM/SIGHUP, SIGTSTP and
 * back), colour pairs, drawing a cell grid and the status line, and
 * reading keys and mouse drags as plain events. */

#include <stddef.h>
#include <stdio.h>
#include "present.h"

/* Keys: characters are their code point; the rest sit above Unicode. */
enum {
    TK_TAB = 9,
    TK_CTRL_L = 12,
    TK_ESC = 27,
    TK_UP = 0x110000,
    TK_DOWN,
    TK_LEFT,
    TK_RIGHT,
    TK_BTAB,            /* shift-Tab */
};

typedef enum {
    TE_KEY = 1,         /* key */
    TE_RESIZE,          /* the window changed size */
    TE_DRAG,            /* button 1 (left) or 3 (right) held, moved dx, dy cells */
    TE_WHEEL,           /* dy = -1 up (away from the user), +1 down */
} TermEventType;

typedef struct {
    TermEventType type;
    int key;            /* TE_KEY */
    int button;         /* TE_DRAG: 1 left, 3 right */
    int dx, dy;         /* TE_DRAG, TE_WHEEL */
} TermEvent;

typedef struct {
    FILE       *out, *in;       /* NULL: stdout, stdin */
    const char *termname;       /* NULL: $TERM */
    ColorDepth  color;          /* wanted; lowered to what the terminal has */
    int         mouse;          /* report clicks, drags and the wheel */
    int         signals;        /* restore on SIGINT/SIGTERM/SIGHUP, handle SIGTSTP */
} TermConfig;

/* Start curses. Returns 0, or -1 with a reason in err when the terminal
 * cannot be driven (unknown TERM, no cursor addressing): the caller falls
 * back to --print. The terminal is then untouched. */
int  term_open(const TermConfig *cfg, char *err, size_t errlen);
/* Leave curses and put the terminal back as it was. Idempotent; also
 * registered with atexit and called from the quit signals. */
void term_restore(void);

ColorDepth term_color(void);            /* the depth actually used */
void term_size(int *cols_out, int *rows_out);
/* Pretend the window is cols x rows (the tty benchmark writes to a file). */
void term_set_size(int cols, int rows);

/* Draw a grid with its top-left cell at (0, top); clipped to the window. */
void term_draw_cells(const CellGrid *g, int top);
/* One line of text in reverse video on row y, padded to the width. */
void term_draw_bar(int y, const char *text);
/* A framed box of lines centred in the window (the help overlay). */
void term_draw_box(const char *const *lines, int n);
/* Blank the window and centre a short message (window too small). */
void term_message(const char *text);
/* Blank the window (before a redraw at a new size). */
void term_erase(void);
/* Send the changes since the last update; everything when full (Ctrl-L). */
void term_update(int full);

/* Wait up to timeout_ms (< 0: forever, 0: poll) for an event. Returns 1
 * with *ev filled, 0 when none came, -1 when the input has ended (a
 * hung-up terminal, a file at its end): no key will ever come, and
 * waiting again would return at once. */
int  term_read(TermEvent *ev, int timeout_ms);

#endif
