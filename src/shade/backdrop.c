/* backdrop.c: the colour a picture is seen on (backdrop.h): --bg's
 * words, the lightness that decides which way ink goes, the background
 * an image gets. The contrast rule that uses it is contrast.c. */

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "backdrop.h"
#include "texture.h"

/* ==== --bg's words ==== */

typedef struct {
    const char *name;
    uint8_t     rgb[3];
} NamedColour;

/* The plain names a user types; anything finer is #rrggbb. */
static const NamedColour named[] = {
    { "black", { 0, 0, 0 } },       { "white", { 255, 255, 255 } }, { "grey", { 128, 128, 128 } },
    { "gray", { 128, 128, 128 } },  { "red", { 255, 0, 0 } },       { "green", { 0, 128, 0 } },
    { "blue", { 0, 0, 255 } },      { "yellow", { 255, 255, 0 } },  { "cyan", { 0, 255, 255 } },
    { "magenta", { 255, 0, 255 } },
};

const char backdrop_names[] = "black, white, grey, gray, red, green, blue, yellow, cyan, magenta";

static int hex_digit(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                                                                                      : -1;
}

/* #rgb (each digit doubled, as CSS reads it) or #rrggbb. */
static int parse_hex(const char *s, uint8_t rgb_out[3])
{
    size_t n = strlen(s);
    if (n != 3 && n != 6)
        return -1;
    int d[6];
    for (size_t i = 0; i < n; i++)
        if ((d[i] = hex_digit(s[i])) < 0)
            return -1;
    for (int a = 0; a < 3; a++)
        rgb_out[a] = (uint8_t)(n == 3 ? d[a] * 17 : d[2 * a] * 16 + d[2 * a + 1]);
    return 0;
}

int backdrop_parse(const char *s, uint8_t rgb_out[3])
{
    if (!s)
        return -1;
    if (s[0] == '#')
        return parse_hex(s + 1, rgb_out);
    for (size_t i = 0; i < sizeof named / sizeof named[0]; i++)
        if (!strcmp(s, named[i].name)) {
            memcpy(rgb_out, named[i].rgb, 3);
            return 0;
        }
    return -1;
}

/* ==== Lightness ==== */

float backdrop_lightness(const uint8_t rgb[3])
{
    float lin[3] = { srgb_to_linear(rgb[0]), srgb_to_linear(rgb[1]), srgb_to_linear(rgb[2]) };
    return contrast_lightness(lin);
}

int backdrop_is_light(const Backdrop *b)
{
    return b && backdrop_lightness(b->rgb) > 0.5f;
}

/* ==== Images ==== */

void backdrop_paint(Image *im, const Backdrop *b)
{
    size_t n = (size_t)im->w * (size_t)im->h;
    for (size_t i = 0; i < n; i++)
        if (!im->lit[i])
            memcpy(im->rgb + 3 * i, b->rgb, 3);
}

void backdrop_describe(const Backdrop *b, char *buf, size_t len)
{
    static const char *const why[] = {
        [BD_ASSUMED] = "assumed: the terminal did not say",
        [BD_GIVEN] = "--bg",
        [BD_ASKED] = "the terminal's, asked",
        [BD_ENV] = "the terminal's, from COLORFGBG",
        [BD_PICKED] = "picked to show the model",
    };
    snprintf(buf, len, "#%02x%02x%02x (%s)", b->rgb[0], b->rgb[1], b->rgb[2],
             b->source <= BD_PICKED ? why[b->source] : "?");
}
