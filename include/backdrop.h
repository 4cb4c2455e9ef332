#ifndef ZV_BACKDROP_H
#define ZV_BACKDROP_H
/* backdrop: the colour a picture is seen on, and the contrast rule that
 * keeps a model visible on it. The colour is given (--bg), asked of the
 * terminal (tty/termbg.c), or picked for an image (-o); the rule
 * (contrast.c) moves the lightness of every drawn pixel that comes
 * within a minimum of the background's away from it, in OKLab L
 * (B. Ottosson, "A perceptual color space for image processing", 2020),
 * keeping the pixel's hue. Knows nothing of terminals. */

#include <stddef.h>
#include <stdint.h>
#include "image.h"

/* The least OKLab lightness difference between a drawn pixel and the
 * background (L runs from 0, black, to 1, white): 0.2 is the distance
 * from black of an sRGB grey of 22, faint but a shape on black;
 * ConcavePolygon.dae's navy lies at 0.17. */
#define CONTRAST_DEFAULT 0.2f
#define CONTRAST_MAX     0.4f   /* keeps room on one side of any background */
/* The lightnesses squeezed to make room: within CONTRAST_KNEE beyond the
 * minimum pixels move less the farther out they are, and beyond it they
 * keep their colour exactly (the ambient side of a light grey model on
 * black, L 0.29, moves by 0.03: sRGB grey 44 becomes 52). */
#define CONTRAST_KNEE    0.15f
/* A side of the background with less lightness than this beyond the
 * minimum takes no pixels: on near-black every pixel goes lighter. */
#define CONTRAST_ROOM    0.1f

typedef enum {
    BD_ASSUMED = 0,     /* nothing known: black, as most terminals are */
    BD_GIVEN,           /* --bg COLOR */
    BD_ASKED,           /* the terminal answered the colour query (OSC 11) */
    BD_ENV,             /* COLORFGBG, as rxvt and konsole set it */
    BD_PICKED,          /* -o: black or white, whichever shows the model better */
} BackdropSource;

typedef struct {
    uint8_t rgb[3];     /* sRGB: the colour behind the model */
    uint8_t paint;      /* 1: outputs draw it (--bg COLOR, images); 0: the terminal's own background shows */
    uint8_t source;     /* BackdropSource */
} Backdrop;

/* ==== The colour (backdrop.c) ==== */

/* --bg's COLOR: a name (black, white, grey or gray, red, green, blue,
 * yellow, cyan, magenta) or #rgb / #rrggbb. Returns 0 with rgb_out, or
 * -1. "default" is not a colour: the caller reads it. */
int   backdrop_parse(const char *s, uint8_t rgb_out[3]);
/* The words backdrop_parse knows, space-separated (for messages). */
extern const char backdrop_names[];
/* OKLab L of an sRGB colour, 0 (black) to 1 (white). */
float backdrop_lightness(const uint8_t rgb[3]);
/* OKLab L of linear light (each channel 0 to 1): the one formula of
 * both, in contrast.c, where the rule asks it many times a colour. */
float contrast_lightness(const float lin[3]);
/* Ink is darker than the background on it (its L above one half):
 * the text outputs then draw more of a darker pixel, not less. */
int   backdrop_is_light(const Backdrop *b);
/* Every pixel of im that shows no model takes b's colour (images). */
void  backdrop_paint(Image *im, const Backdrop *b);
/* "#rrggbb (the terminal's)", for --info and the info panel. */
void  backdrop_describe(const Backdrop *b, char *buf, size_t len);

/* ==== The contrast rule (contrast.c) ====
 * A pixel lighter than the background (or any pixel, when the
 * background is within CONTRAST_ROOM + min of black) is kept at least
 * min lighter: lightnesses from the background's up to min + KNEE above
 * it are squeezed linearly onto [min, min + KNEE] above it; a darker
 * pixel, the same way down. The new lightness is reached by scaling the
 * pixel in linear light (hue and saturation kept; OKLab L scales with
 * the cube root), mixed towards white only when a channel would pass
 * its top. A pixel already far enough keeps its bytes. */

#define CONTRAST_SLOTS 4096     /* colours remembered (direct-mapped) */
#define CONTRAST_CELL_BITS 3    /* the fast test's cubes: 8 x 8 x 8 colours */
#define CONTRAST_CELL  (1 << CONTRAST_CELL_BITS)
#define CONTRAST_CELLS (1 << 3 * (8 - CONTRAST_CELL_BITS))

/* The rule for one background and minimum, and the colours it has
 * moved (kept across frames: a frame mostly repeats its colours). */
typedef struct {
    float     bg_l, min;        /* what the table below was made for */
    float     lo, hi;           /* lightnesses kept as they are: <= lo, >= hi (-1, 2: none) */
    float     floor_up, ceil_down;  /* the least lightness above, the most below */
    int       up, down;         /* the background has room above, below */
    float     keep_lo3, keep_hi3;   /* the fast test's thresholds, cubed (see contrast.c) */
    uint8_t  *kept;             /* CONTRAST_CELLS bits: the cubes of colours the fast test keeps whole */
    uint32_t *slot;             /* CONTRAST_SLOTS: input rgb | 1 << 24, 0 = empty */
    uint32_t *value;            /* the rgb it became */
} Contrast;

/* Set the rule up (again, when the background or minimum changed).
 * Returns 0, or -1 out of memory. */
int   contrast_prepare(Contrast *c, const Backdrop *b, float min);
void  contrast_free(Contrast *c);
/* The colour a pixel of rgb becomes. */
void  contrast_colour(Contrast *c, const uint8_t rgb[3], uint8_t out[3]);
/* Every drawn pixel of im under the rule. Returns 0, or -1 out of memory. */
int   contrast_apply(Contrast *c, const Backdrop *b, float min, Image *im);
/* An image's backdrop when none is given: black, unless more of the
 * model's pixels lie within min of black than within min of white (a
 * dark model), then white; either way the fewest pixels need moving. */
Backdrop backdrop_pick(const Image *im, float min);

#endif
