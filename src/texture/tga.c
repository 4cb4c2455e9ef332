/* tga.c: Truevision TGA images (the Truevision TGA File Format
 * Specification, version 2.0, 1991): image types 2 (true colour), 3
 * (grey), 10 and 11 (the same run-length encoded), 8, 24 or 32 bits a
 * pixel, either origin. Colour-mapped images are not read. The format
 * has no magic number, so the probe accepts a header only when every
 * field is one of these and an unencoded body fits the bytes. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "texture_internal.h"

/* The header's 18 bytes. */
typedef struct {
    int idlen, cmap, type, w, h, bpp, top;      /* top: row 0 is the top row */
} TgaHead;

static int tga_head(const uint8_t *b, size_t len, TgaHead *th)
{
    if (len < 18)
        return -1;
    th->idlen = b[0];
    th->cmap = b[1];
    th->type = b[2];
    th->w = b[12] | b[13] << 8;
    th->h = b[14] | b[15] << 8;
    th->bpp = b[16];
    th->top = (b[17] >> 5) & 1;
    int grey = th->type == 3 || th->type == 11, rle = th->type == 10 || th->type == 11;
    if (th->cmap != 0 || !(th->type == 2 || th->type == 3 || rle) || th->w == 0 || th->h == 0)
        return -1;
    if (grey ? th->bpp != 8 : !(th->bpp == 24 || th->bpp == 32))
        return -1;
    uint64_t body = (uint64_t)th->w * th->h * (th->bpp / 8);
    if (!rle && 18 + (uint64_t)th->idlen + body > len)
        return -1;
    if (rle && 18 + (uint64_t)th->idlen >= len)
        return -1;
    return 0;
}

int texture_tga_probe(const uint8_t *b, size_t len, int *w_out, int *h_out)
{
    TgaHead th;
    if (tga_head(b, len, &th))
        return -1;
    *w_out = th.w;
    *h_out = th.h;
    return 0;
}

/* One pixel of n bytes (B G R [A], or grey) as RGBA. */
static inline void pixel(const uint8_t *p, int n, uint8_t *o)
{
    if (n == 1) {
        o[0] = o[1] = o[2] = p[0];
        o[3] = 255;
        return;
    }
    o[0] = p[2];
    o[1] = p[1];
    o[2] = p[0];
    o[3] = n == 4 ? p[3] : 255;
}

/* Where the reading stands: the next byte, and within a packet. */
typedef struct {
    const uint8_t *p;
    size_t         left;        /* pixels left in the packet (0: a packet header comes next) */
    int            run;         /* the packet repeats one pixel (at p) */
} TgaAt;

/* Up to n pixels into o (RGBA; NULL: skipped), from at; how many there were. */
static size_t tga_pixels(const TgaHead *th, TgaAt *at, const uint8_t *end, uint8_t *o, size_t n)
{
    int bytes = th->bpp / 8, rle = th->type >= 9;
    size_t i = 0;
    while (i < n) {
        if (!rle) {
            size_t have = (size_t)(end - at->p) / (size_t)bytes, k = n - i < have ? n - i : have;
            if (o)
                for (size_t q = 0; q < k; q++)
                    pixel(at->p + q * bytes, bytes, o + 4 * (i + q));
            at->p += k * bytes;
            return i + k;
        }
        if (!at->left) {
            if (at->p >= end)
                break;
            at->run = *at->p >> 7;
            at->left = (size_t)(*at->p++ & 0x7f) + 1;
        }
        size_t k = n - i < at->left ? n - i : at->left;
        if (at->run) {
            if (at->p + bytes > end) {
                at->p = end;    /* cut short: nothing more for any row */
                at->left = 0;
                break;
            }
            if (o)
                for (size_t q = 0; q < k; q++)
                    pixel(at->p, bytes, o + 4 * (i + q));
            if (k == at->left)
                at->p += bytes;
        } else {
            if ((size_t)(end - at->p) < k * (size_t)bytes) {
                k = (size_t)(end - at->p) / (size_t)bytes;
                if (o)
                    for (size_t q = 0; q < k; q++)
                        pixel(at->p + q * bytes, bytes, o + 4 * (i + q));
                at->p = end;    /* cut short: nothing more for any row */
                at->left = 0;
                return i + k;
            }
            if (o)
                for (size_t q = 0; q < k; q++)
                    pixel(at->p + q * bytes, bytes, o + 4 * (i + q));
            at->p += k * bytes;
        }
        at->left -= k;
        i += k;
    }
    return i;
}

/* The rows arrive top first (shrink.c halves them as they come). A file
 * that stores the bottom row first is read from each row's start: found
 * by position when unencoded, by a first pass over the packets (one
 * TgaAt a row) when run-length encoded. */
int texture_decode_tga(Texture *t, const uint8_t *b, size_t len, const char *name, uint64_t max_bytes, int halve,
                       char *err, size_t errlen)
{
    TgaHead th;
    memset(t, 0, sizeof *t);
    if (tga_head(b, len, &th)) {
        snprintf(err, errlen, "%s: not a TGA image zview can read", name);
        return -1;
    }
    if (th.w > TEX_MAX_SIDE || th.h > TEX_MAX_SIDE) {
        snprintf(err, errlen, "%s: a %dx%d image (1 to %d per side)", name, th.w, th.h, TEX_MAX_SIDE);
        return -1;
    }
    int kw, kh, rle = th.type >= 9, flip = !th.top;
    texture_kept_size(th.w, th.h, halve, &kw, &kh);
    uint64_t working = (rle && flip ? (uint64_t)th.h * sizeof(TgaAt) : 0) + texture_shrink_bytes(th.w, th.h, halve);
    if (texture_check_budget(name, "TGA", th.w, th.h, kw, kh, working, max_bytes, err, errlen))
        return -1;
    const uint8_t *body = b + 18 + th.idlen, *end = b + len;
    TgaAt *rows = NULL;
    if (rle && flip) {
        rows = malloc((size_t)th.h * sizeof *rows);
        if (!rows) {
            snprintf(err, errlen, "%s: out of memory", name);
            return -1;
        }
        TgaAt at = { body, 0, 0 };
        for (int y = 0; y < th.h; y++) {
            rows[y] = at;
            tga_pixels(&th, &at, end, NULL, (size_t)th.w);
        }
    }
    TexShrink s;
    if (texture_shrink_begin(&s, t, th.w, th.h, halve)) {
        free(rows);
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    size_t rowbytes = (size_t)th.w * (size_t)(th.bpp / 8);
    TgaAt at = { body, 0, 0 };
    int black = 0;                              /* rows past the file's end, not yet given */
    for (int y = 0; y < th.h; y++) {
        int fy = flip ? th.h - 1 - y : y;       /* the row's place in the file */
        if (flip && rle)
            at = rows[fy];
        else if (flip)
            at.p = (size_t)(end - body) / rowbytes > (size_t)fy ? body + (size_t)fy * rowbytes : end;
        if (!at.left && end - at.p < th.bpp / 8 + rle) {
            black++;
            continue;
        }
        texture_shrink_black(&s, black);
        black = 0;
        uint8_t *o = texture_shrink_row(&s);
        size_t got = tga_pixels(&th, &at, end, o, (size_t)th.w);
        /* what the file holds is shown; the rest stays black */
        memset(o + 4 * got, 0, 4 * ((size_t)th.w - got));
        texture_shrink_push(&s);
    }
    free(rows);
    texture_shrink_finish(&s);
    return 0;
}
