#ifndef ZV_TTY_TERM_INTERNAL_H
#define ZV_TTY_TERM_INTERNAL_H
/* Internal to src/tty/: the viewer's terminal session, which the three
 * files behind tty.h's term_* functions share: term.c starts it, puts
 * the terminal back and handles the signals (the only file that includes
 * curses); termdraw.c composes the screen model and sends frames as fast
 * as the terminal takes them; termread.c reads the input. One session a
 * process, as curses has one: term_open makes it, term_restore frees it,
 * and term.c keeps it beside the little state its signal handlers reach
 * (term_session() hands it to the other two). */

#include <stdio.h>

#include "outq.h"
#include "tty.h"

/* Every kitty image placed, gone (kitty's images are not cells: a clear
 * leaves them). */
#define KITTY_DELETE_ALL "\033_Ga=d,q=2\033\\"
/* ... through tmux's passthrough (mux.c), its ESCs doubled */
#define KITTY_DELETE_ALL_TMUX "\033Ptmux;\033\033_Ga=d,q=2\033\033\\\033\\"
/* The first wait for a busy line; it doubles up to termdraw.c's
 * PACE_MAX_MS, and is back here after each frame. */
#define PACE_MIN_MS 4

typedef struct {
    FILE       *out;
    OutQueue    q;              /* the output: its descriptor, flags and what waits */
    int         in_fd;
    void       *pad;            /* curses' WINDOW that sets the keypad mode; never refreshed */
    int         mouse_on;
    int         cols, rows;     /* the window */
    ColourDepth depth;
    int         depth_answered; /* depth is what the terminal answered, more than its environment said */
    Quantizer   quant;
    Vt          vt;
    int         out_errno;      /* a write failed (sticky): the next update says so */
    /* input */
    KeyParser   kp;
    int         in_ended;       /* the input is at its end (a hung-up terminal) */
    int         wake_fd;        /* the read end of the pipe the signal handlers wake the reader with */
    /* pacing: the answer to the last status request */
    int         ask;            /* requests are sent (the output is a terminal) */
    int         ack_wait;       /* a request is outstanding */
    int         ack_told;       /* the key parser knows it went (its answer is awaited) */
    int         acks_seen;      /* the terminal has answered at least once */
    int         unanswered;
    double      ack_sent_ms;
    int         pace_ms;
    /* what the terminal said at the start */
    int         bg_known;       /* it told its background (termbg.c) */
    uint8_t     bg[3];
    double      bg_wait_ms;     /* how long the question took */
    int         answered;       /* the questions' last answer came within the wait; -1: none asked */
    PixelProto  pix;            /* the pixels it takes (PIX_CELLS: none, or not wanted) */
    PixelScan   pix_scan;       /* its answers to the pixels' questions, read so far */
    int         pix_late;       /* the input is read for them too (a slow link's come late) */
    double      pix_asked_ms;   /* when they were asked */
    int         late_news;      /* answers came late naming better pixels or more colours: the viewer is told
                                   (TE_RESIZE) */
    BgScan      colour_scan;    /* the colour question's answers, read on when it came late */
    int         colour_late;    /* the input is read for it too (until the attributes' answer) */
    int         pix_shown;      /* an image is on the screen */
    int         pix_wanted;     /* pixels were not turned off (--mode) */
    MuxKind     mux;            /* the multiplexer zview runs in */
    MuxPane     pane;           /* inside tmux: its pane, as tmux last said (pane_known) */
    int         pane_known;
    double      pane_asked_ms;  /* when tmux was last asked */
} Term;

/* term.c: the terminal said it draws more colours than the environment
 * did: their quantizer from now on. */
void  term_colour_said(Term *t, ColourDepth said);
/* term.c: the open session, NULL when there is none. */
Term *term_session(void);
/* term.c: back from Ctrl-Z, or a new window size (the handlers noted
 * it): 1 with a TE_RESIZE in ev, everything to be drawn again; else 0. */
int   term_signalled(Term *t, TermEvent *ev);

/* termdraw.c: write what waits in the output queue, as much as the
 * terminal takes now (0, or -1 with errno); and forget it (leaving, or
 * a full repaint follows). */
int   term_out_pump(Term *t);
void  term_out_drop(Term *t);

/* termread.c: on leaving, the answer to the last status request read
 * (left unread it would be typed into the shell). */
void  term_take_last_answer(Term *t);

#endif
