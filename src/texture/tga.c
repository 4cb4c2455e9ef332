/* tga.c: Truevision TGA images (the Truevision TGA File Format
 * Specification, version 2.0, 1991): image types 2 (true colour), 3
 * (grey), 10 and 11 (the same run-length encoded), 8, 24 or 32 bits a
 * pixel, either origin. Colour-mapped images are not read. The format
 * has no magic number, so the probe accepts a header only when every
 * field is one of these and an unencoded body fits the bytes. */

#include <stdio.h>
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

int texture_decode_tga(Texture *t, const uint8_t *b, size_t len, const char *name, uint64_t max_bytes, char *err,
                       size_t errlen)
{
    TgaHead th;
    memset(t, 0, sizeof *t);
    if (tga_head(b, len, &th)) {
        snprintf(err, errlen, "%s: not a TGA image zview can read", name);
        return -1;
    }
    if (texture_check_size(th.w, th.h, name, max_bytes, err, errlen))
        return -1;
    uint8_t *px = texture_alloc_levels(t, th.w, th.h);
    if (!px) {
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    int n = th.bpp / 8, rle = th.type >= 9;
    const uint8_t *p = b + 18 + th.idlen, *end = b + len;
    size_t total = (size_t)th.w * th.h, i = 0;
    /* invariant: i pixels of the file's order written (rows flipped below) */
    while (i < total) {
        size_t run = 1;
        int packet = 0;
        if (rle) {
            if (p >= end)
                break;
            packet = *p >> 7;
            run = (size_t)(*p++ & 0x7f) + 1;
        }
        if (run > total - i)
            run = total - i;
        for (size_t k = 0; k < run; k++, i++) {
            if (p + n > end)
                goto short_file;
            pixel(p, n, px + 4 * i);
            if (!packet)
                p += n;
        }
        if (packet)
            p += n;
    }
    if (i < total) {
short_file:
        /* what the file holds is shown; the rest stays black */
        memset(px + 4 * i, 0, 4 * (total - i));
    }
    if (!th.top) {
        /* bottom-up in the file: row 0 first is the top here */
        size_t row = (size_t)th.w * 4;
        for (int y = 0; y < th.h / 2; y++) {
            uint8_t *a = px + row * (size_t)y, *z = px + row * (size_t)(th.h - 1 - y);
            for (size_t k = 0; k < row; k++) {
                uint8_t c = a[k];
                a[k] = z[k];
                z[k] = c;
            }
        }
    }
    return 0;
}
