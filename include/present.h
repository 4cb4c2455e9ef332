#ifndef ZV_PRESENT_H
#define ZV_PRESENT_H
/* present: an RGB image in, bytes out. cells.c turns pixels into
 * terminal cells (half blocks, ascii ramp, braille); print.c writes a
 * cell grid with ANSI colours in one write; png.c / ppm writers save the
 * image. No terminal here: the viewer's is tty/ (tty.h). */

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "backdrop.h"
#include "image.h"

typedef enum { MODE_HALF = 0, MODE_ASCII, MODE_BRAILLE, MODE_COUNT } DisplayMode;
typedef enum { COLOUR_NONE = 0, COLOUR_8, COLOUR_16, COLOUR_256, COLOUR_TRUE } ColourDepth;

extern const char *const mode_names[MODE_COUNT];
int mode_from_name(const char *name);           /* -1 if unknown */
int colour_from_name(const char *name);          /* -1 if unknown */
const char *colour_name(ColourDepth c);

/* Default colour depth from the environment: NO_COLOR -> none;
 * COLORTERM truecolor/24bit or TERM *-direct -> true; TERM *256colour* ->
 * 256; other TERM -> 16; TERM unset or dumb -> none. */
ColourDepth colour_from_env(void);
/* Which variable colour_from_env went by: "NO_COLOR", "COLORTERM" or "TERM". */
const char *colour_env_reason(void);
/* Default display mode: half on a UTF-8 locale, else ascii. Call after
 * setlocale(LC_ALL, ""). */
DisplayMode mode_from_locale(void);
/* The terminal's background from COLORFGBG ("15;0": palette colour 0,
 * as rxvt and konsole set it) into rgb_out (xterm's palette). Returns
 * 0, or -1 when it is unset or says nothing. */
int bg_from_env(uint8_t rgb_out[3]);

#define CELL_FG 1       /* fg colour set (else terminal default) */
#define CELL_BG 2       /* bg colour set (else terminal default) */

typedef struct {
    uint32_t ch;        /* Unicode code point (' ' for empty) */
    uint8_t  fg[3], bg[3];
    uint8_t  flags;     /* CELL_FG | CELL_BG */
} Cell;

typedef struct {
    int   cols, rows;
    Cell *cells;        /* cols * rows */
    size_t cap;
} CellGrid;

/* Pixels per cell of a mode (half 1x2, ascii 1x1, braille 2x4) and the
 * pixel aspect (pixel height / width) given cells twice as tall as wide. */
void  mode_cell_pixels(DisplayMode m, int *px_w, int *px_h);
float mode_pixel_aspect(DisplayMode m);

/* Image of (cols * px_w) x (rows * px_h) pixels -> cells. Under
 * COLOUR_NONE the shading goes into the glyphs (dithered blocks and dots). */
int  cells_from_image(const Image *im, DisplayMode m, ColourDepth depth, CellGrid *out);
/* The same for a picture seen on bd (NULL: a dark terminal's own
 * background): on a light one the glyphs carry darkness (cells.c), and
 * a painted one fills the background of every cell. */
int  cells_from_image_on(const Image *im, DisplayMode m, ColourDepth depth, const Backdrop *bd, CellGrid *out);
void cells_free(CellGrid *g);

/* The xterm palette (the first 16 at xterm's defaults). */
void palette_256_rgb(int idx, uint8_t rgb_out[3]);
void palette_rgb(ColourDepth depth, int idx, uint8_t rgb_out[3]);
/* Plain nearest palette index in RGB (kept to measure against). */
int  palette_256(const uint8_t rgb[3]);         /* 16..255, nearest of cube + greys */
int  palette_16(const uint8_t rgb[3]);          /* 0..15, nearest ANSI colour */

/* Colour quantizer for 256, 16 and 8 colours (quant.c): the nearest
 * palette colour in OKLab, ordered-dithered with the partner that best
 * mixes towards the wanted colour. Keep one across frames: it memoises
 * the pairs (a lazily filled 1 MB table). */
typedef struct {
    ColourDepth depth;
    int        n;               /* palette entries searched */
    uint8_t    num[240];        /* their palette numbers */
    float      plin[240][3];    /* their linear RGB */
    float      plab[240][3];    /* their OKLab */
    float      lin[256];        /* sRGB byte -> linear */
    uint32_t  *lut;             /* pair per colour rounded to 6 bits a channel */
} Quantizer;

int   quant_init(Quantizer *q, ColourDepth depth);   /* 0, or -1 out of memory */
void  quant_free(Quantizer *q);
/* The palette number to show for rgb at pixel (x, y); -1 under
 * truecolor or no colour. */
int   quant_pick(Quantizer *q, const uint8_t rgb[3], int x, int y);
/* The ordered-dither threshold at pixel (x, y), in (0, 1). */
float quant_threshold(int x, int y);
void  quant_rgb_to_oklab(const uint8_t rgb[3], float lab_out[3]);

/* A colour as the terminal is told it: its default, a palette number, or
 * 24-bit RGB. --print and the viewer both go through colour_key(), so
 * the same cell at the same place gets the same colour in both. */
#define CK_DEFAULT     0u
#define CK_PAL(n)      (1u + (uint32_t)(n))                 /* palette 0..255 */
#define CK_RGB_FLAG    0x1000000u
#define CK_RGB(r, g, b) (CK_RGB_FLAG | (uint32_t)(r) << 16 | (uint32_t)(g) << 8 | (uint32_t)(b))

/* The key for a cell colour (set = 0: the terminal's default) at pixel
 * (x, y) under the quantizer's depth: exact RGB under truecolor, the
 * dithered palette number under 256/16/8, the default without colour.
 * A cell's foreground sits at pixel row 2 * row, its background at
 * 2 * row + 1 (the half-block mode's two pixels). */
uint32_t colour_key(Quantizer *q, const uint8_t rgb[3], int set, int x, int y);
/* The SGR parameters selecting key k as foreground (bg = 0) or
 * background, in their shortest form ("39", "31", "97", "38;5;200",
 * "48;2;1;2;3"), written at p (at most SGR_COLOUR_MAX bytes, no NUL).
 * Returns the end. */
#define SGR_COLOUR_MAX 16
char *sgr_colour(char *p, uint32_t k, int bg);

/* The grid as text with ANSI SGR colours (none: plain text), each row
 * ending in a reset and "\n". Built in one buffer, written with one
 * fwrite, then flushed. Returns 0, or -1 on a write error (errno says
 * which) or out of memory (ENOMEM). */
int  print_cells(FILE *f, const CellGrid *g, ColourDepth c);
/* Same bytes into a malloc'd buffer (*len_out), for tests. */
char *print_cells_to_string(const CellGrid *g, ColourDepth c, size_t *len_out);

/* Checked output: every write of a report or a file goes through one of
 * these. The first failure is kept (its errno); later calls then write
 * nothing and return -1. name is what a message calls the stream: a path,
 * or "standard output". */
typedef struct {
    FILE       *f;
    const char *name;
    int         err;        /* errno of the first failure, 0 = none */
} Out;

void out_init(Out *o, FILE *f, const char *name);
int  out_printf(Out *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int  out_write(Out *o, const void *p, size_t n);
/* One line of a report that names files or quotes them (--info): fmt
 * formatted, all of it made safe (safetext.h), then a newline. */
int  out_line(Out *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Flush, and fail too when the stream has an error from any write. */
int  out_flush(Out *o);
/* Flush and fclose (not for stdout). */
int  out_close(Out *o);
/* The reason of the first failure (strerror). */
const char *out_error(const Out *o);

/* Image writers. Return 0, or -1 with "path: reason" in err. */
int  write_png(const char *path, const Image *im, char *err, size_t errlen);
int  write_ppm(const char *path, const Image *im, char *err, size_t errlen);

#endif
