/* termcaps.c: what the terminal's description (terminfo) says, for the
 * viewer: which description to use, the escapes our screen model may
 * send (vt.c writes the ANSI forms itself when the description has
 * them), and the colours. */

#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE
#define NCURSES_WIDECHAR 1

#include <curses.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "termcaps.h"

/* From ncurses' <term.h>, which is not included: its capability macros
 * (lines, columns, ...) clash with plain names. */
struct term;
extern int setupterm(const char *name, int fd, int *err_out);
extern struct term *set_curterm(struct term *t);
extern int del_curterm(struct term *t);

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

int termcaps_is(const char *name, const char *ansi)
{
    const char *s = tigetstr(name);
    return s && s != (const char *)-1 && strncmp(s, ansi, strlen(ansi)) == 0;
}

static int flag(const char *name)
{
    return tigetflag(name) > 0;
}

void termcaps_read(VtCaps *c)
{
    memset(c, 0, sizeof *c);
    c->ech = termcaps_is("ech", "\033[%p1%dX");
    c->el = termcaps_is("el", "\033[K");
    c->rel = termcaps_is("cuf", "\033[%p1%dC") && termcaps_is("cub", "\033[%p1%dD") &&
             termcaps_is("cud", "\033[%p1%dB") && termcaps_is("cuu", "\033[%p1%dA");
    c->hpa = termcaps_is("hpa", "\033[%i%p1%dG");
    c->vpa = termcaps_is("vpa", "\033[%i%p1%dd");
    c->am = flag("am");
    c->xenl = flag("xenl");
    const char *cl = tigetstr("clear");
    /* padding ($<...>) means nothing to a terminal emulator: the plain form */
    if (cl && cl != (const char *)-1 && strncmp(cl, "\033[H\033[2J", 7) == 0)
        snprintf(c->clear, sizeof c->clear, "\033[H\033[2J");
    else
        snprintf(c->clear, sizeof c->clear, "\033[H\033[J");
}

ColourDepth termcaps_depth(ColourDepth want, int colours)
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
