/* print: a cell grid -> text with ANSI SGR colours, built in one buffer
 * and written with one fwrite (a frame never reaches the terminal half
 * drawn). Under 256, 16 and 8 colours the quantizer (quant.c) picks the
 * palette number, dithered by position: a cell's foreground sits at pixel
 * row 2 * row and its background at 2 * row + 1 (the half-block mode's
 * two pixels). An escape is emitted only when a colour differs from the
 * previous cell's as the terminal would show it. */

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "present.h"

/* Longest escapes: "\x1b[38;2;255;255;255m" is 19 bytes, a UTF-8 code
 * point 4, the row reset "\x1b[0m" 4 and the newline 1. */
#define SGR_MAX  19
#define CELL_MAX (2 * SGR_MAX + 4)

/* The colour key of a cell colour at pixel (x, y): see present.h. */
uint32_t colour_key(Quantizer *q, const uint8_t rgb[3], int set, int x, int y)
{
    if (!set || q->depth == COLOUR_NONE)
        return CK_DEFAULT;
    if (q->depth == COLOUR_TRUE)
        return CK_RGB(rgb[0], rgb[1], rgb[2]);
    return CK_PAL(quant_pick(q, rgb, x, y));
}

static inline char *put_str(char *p, const char *s)
{
    while (*s)
        *p++ = *s++;
    return p;
}

static inline char *put_uint(char *p, unsigned v)
{
    char tmp[10];
    int n = 0;
    do {
        tmp[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    while (n)
        *p++ = tmp[--n];
    return p;
}

char *sgr_colour(char *p, uint32_t k, int bg)
{
    if (k == CK_DEFAULT)
        return put_str(p, bg ? "49" : "39");
    if (k & CK_RGB_FLAG) {
        p = put_str(p, bg ? "48;2;" : "38;2;");
        p = put_uint(p, k >> 16 & 0xff);
        *p++ = ';';
        p = put_uint(p, k >> 8 & 0xff);
        *p++ = ';';
        return put_uint(p, k & 0xff);
    }
    unsigned n = k - 1;
    if (n < 8)                  /* the 8 colours: 30-37, 40-47 */
        return put_uint(p, (bg ? 40 : 30) + n);
    if (n < 16)                 /* their bright forms: 90-97, 100-107 */
        return put_uint(p, (bg ? 100 : 90) + n - 8);
    p = put_str(p, bg ? "48;5;" : "38;5;");
    return put_uint(p, n);
}

/* The SGR selecting key k as foreground (bg = 0) or background (bg = 1). */
static char *put_sgr(char *p, uint32_t k, int bg)
{
    p = put_str(p, "\x1b[");
    p = sgr_colour(p, k, bg);
    *p++ = 'm';
    return p;
}

static inline char *put_utf8(char *p, uint32_t cp)
{
    if (cp < 0x80) {
        *p++ = (char)cp;
    } else if (cp < 0x800) {
        *p++ = (char)(0xc0 | (cp >> 6));
        *p++ = (char)(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
        *p++ = (char)(0xe0 | (cp >> 12));
        *p++ = (char)(0x80 | ((cp >> 6) & 0x3f));
        *p++ = (char)(0x80 | (cp & 0x3f));
    } else if (cp < 0x110000) {
        *p++ = (char)(0xf0 | (cp >> 18));
        *p++ = (char)(0x80 | ((cp >> 12) & 0x3f));
        *p++ = (char)(0x80 | ((cp >> 6) & 0x3f));
        *p++ = (char)(0x80 | (cp & 0x3f));
    } else {
        *p++ = '?';
    }
    return p;
}

char *print_cells_to_string(const CellGrid *g, ColourDepth c, size_t *len_out)
{
    size_t ncells = (size_t)g->cols * (size_t)g->rows;
    size_t cap = ncells * CELL_MAX + (size_t)g->rows * 5 + 1;
    Quantizer q;
    if (quant_init(&q, c))
        return NULL;
    char *buf = malloc(cap);
    if (!buf) {
        quant_free(&q);
        return NULL;
    }
    char *p = buf;
    for (int r = 0; r < g->rows; r++) {
        const Cell *cell = g->cells + (size_t)r * g->cols;
        /* Each row starts from the terminal's default colours. */
        uint32_t fg = CK_DEFAULT, bg = CK_DEFAULT;
        int coloured = 0;
        for (int x = 0; x < g->cols; x++, cell++) {
            if (c != COLOUR_NONE) {
                uint32_t kf = colour_key(&q, cell->fg, cell->flags & CELL_FG, x, 2 * r);
                uint32_t kb = colour_key(&q, cell->bg, cell->flags & CELL_BG, x, 2 * r + 1);
                if (kf != fg) {
                    p = put_sgr(p, kf, 0);
                    fg = kf;
                    coloured = 1;
                }
                if (kb != bg) {
                    p = put_sgr(p, kb, 1);
                    bg = kb;
                    coloured = 1;
                }
            }
            p = put_utf8(p, cell->ch);
        }
        if (coloured)
            p = put_str(p, "\x1b[0m");
        *p++ = '\n';
    }
    *p = '\0';
    quant_free(&q);
    if (len_out)
        *len_out = (size_t)(p - buf);
    return buf;
}

int print_cells(FILE *f, const CellGrid *g, ColourDepth c)
{
    size_t len;
    char *buf = print_cells_to_string(g, c, &len);
    if (!buf) {
        errno = ENOMEM;
        return -1;
    }
    Out o;
    out_init(&o, f, NULL);
    out_write(&o, buf, len);
    out_flush(&o);
    free(buf);
    if (o.err) {
        errno = o.err;
        return -1;
    }
    return 0;
}
