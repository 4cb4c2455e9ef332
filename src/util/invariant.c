/* invariant.c: what a broken invariant does in a checked build (invariant.h). */

#include <stdio.h>
#include <stdlib.h>

#include "invariant.h"

/* Defined in every build (release builds never call it), so a library
 * built with checks links with code built without. */
void zv_check_failed(const char *cond, const char *file, int line, const char *func)
{
    fprintf(stderr, "zview: %s:%d: %s: invariant broken: %s\n", file, line, func, cond);
    fflush(stderr);
    abort();
}
