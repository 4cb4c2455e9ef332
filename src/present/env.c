/* env: option names of the presenters and defaults from the environment
 * (colour depth from NO_COLOR / COLORTERM / TERM, display mode from the
 * locale's character set, the background from COLORFGBG). */

#define _XOPEN_SOURCE 700       /* nl_langinfo */
#include <langinfo.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "present.h"

const char *const mode_names[MODE_COUNT] = { "half", "ascii", "braille" };

static const char *const colour_names[] = { "none", "8", "16", "256", "truecolor" };

int mode_from_name(const char *name)
{
    if (!name)
        return -1;
    for (int i = 0; i < MODE_COUNT; i++)
        if (strcmp(name, mode_names[i]) == 0)
            return i;
    return -1;
}

int colour_from_name(const char *name)
{
    if (!name)
        return -1;
    for (int i = 0; i <= COLOUR_TRUE; i++)
        if (strcmp(name, colour_names[i]) == 0)
            return i;
    /* The spellings COLORTERM uses are accepted too. */
    if (strcmp(name, "24bit") == 0 || strcmp(name, "true") == 0)
        return COLOUR_TRUE;
    return -1;
}

const char *colour_name(ColourDepth c)
{
    return (unsigned)c <= COLOUR_TRUE ? colour_names[c] : "?";
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

ColourDepth colour_from_env(void)
{
    /* https://no-colour.org: present and non-empty disables colour. */
    const char *no = getenv("NO_COLOR");
    if (no && *no)
        return COLOUR_NONE;
    const char *ct = getenv("COLORTERM");
    if (ct && (strcmp(ct, "truecolor") == 0 || strcmp(ct, "24bit") == 0))
        return COLOUR_TRUE;
    const char *term = getenv("TERM");
    if (term && ends_with(term, "-direct"))
        return COLOUR_TRUE;
    if (term && strstr(term, "256color"))
        return COLOUR_256;
    if (!term || !*term || strcmp(term, "dumb") == 0)
        return COLOUR_NONE;
    return COLOUR_16;
}

const char *colour_env_reason(void)
{
    /* colour_from_env's branches, in its order */
    const char *no = getenv("NO_COLOR");
    if (no && *no)
        return "NO_COLOR";
    const char *ct = getenv("COLORTERM");
    if (ct && (strcmp(ct, "truecolor") == 0 || strcmp(ct, "24bit") == 0))
        return "COLORTERM";
    return "TERM";
}

DisplayMode mode_from_locale(void)
{
    const char *cs = nl_langinfo(CODESET);
    if (cs && (strcasecmp(cs, "UTF-8") == 0 || strcasecmp(cs, "UTF8") == 0))
        return MODE_HALF;
    return MODE_ASCII;
}

int bg_from_env(uint8_t rgb_out[3])
{
    /* "fg;bg" or "fg;default;bg" (rxvt, konsole): the last field is the
     * background's palette number; "default" says nothing */
    const char *v = getenv("COLORFGBG");
    const char *last = v ? strrchr(v, ';') : NULL;
    if (!last || !last[1])
        return -1;
    char *end;
    long n = strtol(last + 1, &end, 10);
    if (*end || end == last + 1 || n < 0 || n > 15)
        return -1;
    palette_rgb(COLOUR_16, (int)n, rgb_out);
    return 0;
}
