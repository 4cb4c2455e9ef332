/* units.c: the unit a model's size suggests when its format states
 * none, and --unit's words. A guess is only ever said, beside the
 * figures, never acted on: the figures stay in the file's units until
 * --unit states one. */

#include <math.h>
#include <string.h>

#include "printq.h"

/* Within 0.2% (or 0.001) of a multiple of 1/16; *whole when of 1. */
static int near_sixteenth(double v, int *whole)
{
    double k = round(v * 16);
    double tol = fmax(0.002 * v, 0.001);
    if (fabs(v - k / 16) > tol)
        return 0;
    *whole = fabs(v - round(v)) <= tol;
    return 1;
}

const char *printq_unit_guess(const double size[3])
{
    double longest = fmax(size[0], fmax(size[1], size[2]));
    if (longest >= 0.001 && longest < 0.5)
        return "m";
    if (longest < 0.5 || longest > 20)
        return NULL;
    int fractions = 0;
    for (int k = 0; k < 3; k++) {
        int whole;
        if (!near_sixteenth(size[k], &whole))
            return NULL;
        fractions += !whole;
    }
    return fractions ? "in" : NULL;
}

double printq_unit_mm(const char *unit)
{
    return !strcmp(unit, "mm") ? 1 : !strcmp(unit, "in") ? 25.4 : !strcmp(unit, "m") ? 1000 : 0;
}

const char *printq_unit_words(const char *unit)
{
    return !strcmp(unit, "mm") ? "millimetres" : !strcmp(unit, "in") ? "inches" : !strcmp(unit, "m") ? "metres"
                                                                               : unit;
}
