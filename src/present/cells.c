/* cells: an RGB image -> a grid of terminal cells.
 *
 * half:    one cell = 1x2 pixels, U+2580 upper half block with the top
 *          pixel as fg and the bottom one as bg (U+2584 when only the
 *          bottom is lit, so the unlit half keeps the terminal's own bg).
 * ascii:   one cell = one pixel, a glyph from a luminance ramp.
 * braille: one cell = 2x4 pixels, one dot per lit pixel, fg = the mean
 *          colour of the lit dots.
 * Pixels past the image edge (an image that is not a whole number of
 * cells) count as background.
 *
 * Without colour (COLOUR_NONE) the colours are lost on the way out, so the
 * shading goes into the glyphs instead: half blocks and braille dots are
 * set per pixel by an ordered dither of the pixel's lightness (kept above
 * a floor, so that dark faces still show the silhouette); the ascii ramp
 * already carries it.
 *
 * On a light background (backdrop.h) ink is darker than the paper: the
 * glyphs then carry darkness, not lightness (a dark face gets the dense
 * ramp glyph and the most dots), as a dark terminal shows a light face
 * most. A background that is painted (--bg COLOR) fills every cell's
 * background the model leaves. */

#include <stdlib.h>
#include <string.h>
#include "backdrop.h"
#include "invariant.h"
#include "present.h"

#define CH_UPPER_HALF 0x2580u
#define CH_LOWER_HALF 0x2584u
#define CH_FULL_BLOCK 0x2588u
#define MONO_FLOOR    0.2f      /* the darkest lit pixel still lights a fifth of its dots */
#define CH_BRAILLE    0x2800u

/* Lit pixels use ramp[1..]: a dark face never vanishes into ' '. */
static const char ascii_ramp[] = " .:-=+*#%@";
#define RAMP_LEN ((int)sizeof ascii_ramp - 1)

/* Braille dot bit of pixel (x, y) in a 2x4 cell: dots 1,2,3,7 run down
 * the left column, 4,5,6,8 down the right. */
static const uint8_t braille_bit[4][2] = {
    { 0x01, 0x08 },
    { 0x02, 0x10 },
    { 0x04, 0x20 },
    { 0x40, 0x80 },
};

void mode_cell_pixels(DisplayMode m, int *px_w, int *px_h)
{
    int w = 1, h = 1;
    if (m == MODE_HALF) {
        h = 2;
    } else if (m == MODE_BRAILLE) {
        w = 2;
        h = 4;
    }
    if (px_w)
        *px_w = w;
    if (px_h)
        *px_h = h;
}

float mode_pixel_aspect(DisplayMode m)
{
    /* A cell is 1 wide and 2 tall; its pixels split that. */
    int pw, ph;
    mode_cell_pixels(m, &pw, &ph);
    return (2.0f / (float)ph) / (1.0f / (float)pw);
}

void cells_free(CellGrid *g)
{
    free(g->cells);
    memset(g, 0, sizeof *g);
}

static int grid_resize(CellGrid *g, int cols, int rows)
{
    size_t n = (size_t)cols * (size_t)rows;
    if (n > g->cap || !g->cells) {
        size_t cap = n ? n : 1;
        Cell *c = realloc(g->cells, cap * sizeof *c);
        if (!c)
            return -1;
        g->cells = c;
        g->cap = cap;
    }
    g->cols = cols;
    g->rows = rows;
    return 0;
}

static inline void set_fg(Cell *c, const uint8_t *p)
{
    c->fg[0] = p[0];
    c->fg[1] = p[1];
    c->fg[2] = p[2];
}

static inline void set_empty(Cell *c)
{
    memset(c, 0, sizeof *c);
    c->ch = ' ';
}

/* Rec. 709 luma of a pixel, 0..1. */
static inline float luma(const uint8_t *p)
{
    return (float)(54u * p[0] + 183u * p[1] + 19u * p[2]) / (256.0f * 255.0f);
}

/* How much ink a pixel wants, 0..1: its lightness, or on a light
 * background its darkness. */
static inline float ink(const uint8_t *p, int light)
{
    float v = luma(p);
    return light ? 1 - v : v;
}

/* Without colour: is pixel i at (x, y) drawn (a dithered share of its
 * ink)? */
static inline int mono_on(const Image *im, size_t i, int x, int y, int light)
{
    if (!im->lit[i])
        return 0;
    float v = MONO_FLOOR + (1 - MONO_FLOOR) * ink(im->rgb + 3 * i, light);
    return v > quant_threshold(x, y);
}

static void cells_half_mono(const Image *im, CellGrid *g, int light)
{
    int w = im->w, h = im->h;
    for (int r = 0; r < g->rows; r++) {
        Cell *c = g->cells + (size_t)r * g->cols;
        for (int x = 0; x < w; x++, c++) {
            int yt = 2 * r, yb = 2 * r + 1;
            int t = mono_on(im, (size_t)yt * w + x, x, yt, light);
            int b = yb < h && mono_on(im, (size_t)yb * w + x, x, yb, light);
            set_empty(c);
            if (t || b)
                c->ch = t && b ? CH_FULL_BLOCK : t ? CH_UPPER_HALF : CH_LOWER_HALF;
        }
    }
}

static void cells_half(const Image *im, CellGrid *g)
{
    int w = im->w, h = im->h;
    for (int r = 0; r < g->rows; r++) {
        int yt = 2 * r, yb = 2 * r + 1;
        const uint8_t *top = im->rgb + 3 * (size_t)yt * w, *tl = im->lit + (size_t)yt * w;
        const uint8_t *bot = yb < h ? im->rgb + 3 * (size_t)yb * w : NULL;
        const uint8_t *bl = yb < h ? im->lit + (size_t)yb * w : NULL;
        Cell *c = g->cells + (size_t)r * g->cols;
        for (int x = 0; x < w; x++, c++) {
            int lt = tl[x], lb = bl ? bl[x] : 0;
            if (lt) {
                c->ch = CH_UPPER_HALF;
                set_fg(c, top + 3 * x);
                if (lb) {
                    const uint8_t *p = bot + 3 * x;
                    c->bg[0] = p[0];
                    c->bg[1] = p[1];
                    c->bg[2] = p[2];
                    c->flags = CELL_FG | CELL_BG;
                } else {
                    c->bg[0] = c->bg[1] = c->bg[2] = 0;
                    c->flags = CELL_FG;
                }
            } else if (lb) {
                c->ch = CH_LOWER_HALF;
                set_fg(c, bot + 3 * x);
                c->bg[0] = c->bg[1] = c->bg[2] = 0;
                c->flags = CELL_FG;
            } else {
                set_empty(c);
            }
        }
    }
}

static void cells_ascii(const Image *im, CellGrid *g, int light)
{
    size_t n = (size_t)im->w * (size_t)im->h;
    for (size_t i = 0; i < n; i++) {
        Cell *c = g->cells + i;
        if (!im->lit[i]) {
            set_empty(c);
            continue;
        }
        const uint8_t *p = im->rgb + 3 * i;
        /* Rec. 709 luma in 8.8 fixed point (weights sum to 256). */
        unsigned lum = (54u * p[0] + 183u * p[1] + 19u * p[2]) >> 8;
        if (light)
            lum = 255 - lum;
        c->ch = (uint32_t)(unsigned char)ascii_ramp[1 + lum * (RAMP_LEN - 1) / 256];
        set_fg(c, p);
        c->bg[0] = c->bg[1] = c->bg[2] = 0;
        c->flags = CELL_FG;
    }
}

static void cells_braille(const Image *im, CellGrid *g, int mono, int light)
{
    int w = im->w, h = im->h;
    for (int r = 0; r < g->rows; r++) {
        Cell *c = g->cells + (size_t)r * g->cols;
        for (int col = 0; col < g->cols; col++, c++) {
            unsigned bits = 0, nlit = 0, sr = 0, sg = 0, sb = 0;
            for (int dy = 0; dy < 4; dy++) {
                int y = 4 * r + dy;
                if (y >= h)
                    break;
                for (int dx = 0; dx < 2; dx++) {
                    int x = 2 * col + dx;
                    size_t i = (size_t)y * w + x;
                    if (x >= w || !im->lit[i] || (mono && !mono_on(im, i, x, y, light)))
                        continue;
                    const uint8_t *p = im->rgb + 3 * i;
                    bits |= braille_bit[dy][dx];
                    nlit++;
                    sr += p[0];
                    sg += p[1];
                    sb += p[2];
                }
            }
            if (!bits) {
                set_empty(c);
                continue;
            }
            c->ch = CH_BRAILLE + bits;
            c->fg[0] = (uint8_t)((sr + nlit / 2) / nlit);
            c->fg[1] = (uint8_t)((sg + nlit / 2) / nlit);
            c->fg[2] = (uint8_t)((sb + nlit / 2) / nlit);
            c->bg[0] = c->bg[1] = c->bg[2] = 0;
            c->flags = mono ? 0 : CELL_FG;
        }
    }
}

/* The painted background behind every cell whose own is the terminal's. */
static void paint_cells(CellGrid *g, const uint8_t rgb[3])
{
    size_t n = (size_t)g->cols * (size_t)g->rows;
    for (size_t i = 0; i < n; i++) {
        Cell *c = g->cells + i;
        if (c->flags & CELL_BG)
            continue;
        memcpy(c->bg, rgb, 3);
        c->flags |= CELL_BG;
    }
}

int cells_from_image(const Image *im, DisplayMode m, ColourDepth depth, CellGrid *out)
{
    return cells_from_image_on(im, m, depth, NULL, out);
}

int cells_from_image_on(const Image *im, DisplayMode m, ColourDepth depth, const Backdrop *bd, CellGrid *out)
{
    int pw, ph;
    if ((unsigned)m >= MODE_COUNT || im->w < 0 || im->h < 0)
        return -1;
    mode_cell_pixels(m, &pw, &ph);
    int cols = (im->w + pw - 1) / pw, rows = (im->h + ph - 1) / ph;
    if (grid_resize(out, cols, rows) != 0)
        return -1;
    int mono = depth == COLOUR_NONE, light = backdrop_is_light(bd);
    /* half and ascii are a pixel wide (mode_cell_pixels): they walk a
     * row of cells by the image's width, ascii the cells by its pixels */
    ZV_ASSERT((m == MODE_BRAILLE || cols == im->w) && (size_t)cols * (size_t)rows <= out->cap);
    switch (m) {
    case MODE_HALF:
        if (mono)
            cells_half_mono(im, out, light);
        else
            cells_half(im, out);
        break;
    case MODE_ASCII:   cells_ascii(im, out, light); break;
    case MODE_BRAILLE: cells_braille(im, out, mono, light); break;
    default:           return -1;
    }
    if (bd && bd->paint && !mono)
        paint_cells(out, bd->rgb);     /* without colour there is nothing to paint with */
    return 0;
}
