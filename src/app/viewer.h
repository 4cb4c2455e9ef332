#ifndef ZV_VIEWER_H
#define ZV_VIEWER_H
/* viewer (private to src/app): the interactive viewer's state, and the
 * key table in action.c that changes it. Each action is tiny and returns
 * what the loop in viewer.c has to redo. */

#include "app.h"

typedef enum {
    RE_NONE   = 0,
    RE_DRAW   = 1,          /* draw the screen again from the current cells */
    RE_RENDER = 2 | 1,      /* render a new frame, then draw */
    RE_CLEAR  = 4,          /* repaint the whole terminal (Ctrl-L) */
    RE_QUIT   = 8,
} Reaction;

typedef struct App {
    Scene      *s;
    Pipeline    p;
    int         algo;       /* index into hsr_algos */
    DisplayMode mode;
    int         utf8;       /* half and braille need a UTF-8 locale */
    int         cull;
    int         sel;        /* selected object, -1 = the whole scene */
    int         spin;       /* auto-rotate (turntable) */
    int         help;       /* help overlay shown */
    char        name[96];   /* file name(s) for the status line */
    char        note[80];   /* a one-off note for the status line */
} App;

/* The effect of a key (term.h codes), a drag of dx, dy cells with button
 * 1 (left: turn) or 3 (right: move), or a wheel step (dy < 0: up). */
Reaction app_key(App *a, int key);
Reaction app_drag(App *a, int button, int dx, int dy);
Reaction app_wheel(App *a, int dy);
/* Turn the scene (or the selected object) about the vertical axis. */
void     app_spin(App *a, float radians);

/* The help overlay, one line per key group. */
extern const char *const app_help[];
extern const int app_help_lines;

#endif
