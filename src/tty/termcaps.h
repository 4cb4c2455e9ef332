#ifndef ZV_TTY_TERMCAPS_H
#define ZV_TTY_TERMCAPS_H
/* Internal to src/tty/: the terminal's description, read for term.c
 * (term_resolve itself is public, in tty.h). Call after setupterm. */

#include "tty.h"

/* Is capability `name` the ANSI form we write ourselves (padding aside)? */
int         termcaps_is(const char *name, const char *ansi);
/* The escapes of c the description has in the ANSI form vt.c writes. */
void        termcaps_read(VtCaps *c);
/* The colours to use: what is asked, lowered to what the description
 * has; except 24-bit, which a description can only tell through a
 * *-direct entry that most servers lack, so it is taken as asked. */
ColourDepth termcaps_depth(ColourDepth want, int colours);

#endif
