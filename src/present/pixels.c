/* pixels.c: a picture in the terminal's own pixels. Three encoders:
 *
 * - sixel (DEC's, from the LA50 printer and the VT240/VT340): bands of
 *   six pixel rows; each colour of a band is one line of characters
 *   '?' + six bits, run-length coded ("!n"), "$" back to the band's
 *   start for the next colour, "-" to the next band. Colours are
 *   registers defined as percentages. The pixels are mapped to the
 *   xterm 256-colour cube and greys by the same OKLab quantizer with
 *   ordered dithering that the 256-colour text uses (quant.c), so a
 *   sixel picture and a 256-colour one agree.
 * - kitty's graphics protocol: the PNG in base64, in chunks of 4096
 *   bytes, each an APC string "ESC _ G keys ; data ESC \".
 * - iTerm2's inline images: the PNG in base64 in one OSC 1337 string.
 *
 * Sixel: DEC STD 070 and the VT330/VT340 Programmer Reference Manual;
 * kitty: the protocol as kitty's documentation describes it; iTerm2:
 * its "Inline Images Protocol" page. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "invariant.h"
#include "pixels.h"
#include "present.h"

const char *const pixel_proto_names[PIX_COUNT] = { "cells", "sixel", "kitty", "iterm", "auto" };

/* ==== Bytes ==== */

static int bytebuf_room(ByteBuf *o, size_t n)
{
    if (o->err)
        return -1;
    if (o->len + n <= o->cap)
        return 0;
    size_t cap = o->cap ? o->cap : 4096;
    while (cap < o->len + n) {
        if (cap > SIZE_MAX / 2) {
            o->err = 1;
            return -1;
        }
        cap *= 2;
    }
    uint8_t *b = realloc(o->b, cap);
    if (!b) {
        o->err = 1;
        return -1;
    }
    o->b = b;
    o->cap = cap;
    return 0;
}

void bytebuf_put(ByteBuf *o, const void *p, size_t n)
{
    if (n && bytebuf_room(o, n) == 0) {
        memcpy(o->b + o->len, p, n);
        o->len += n;
    }
}

void bytebuf_puts(ByteBuf *o, const char *s)
{
    bytebuf_put(o, s, strlen(s));
}

void bytebuf_free(ByteBuf *o)
{
    free(o->b);
    memset(o, 0, sizeof *o);
}

void base64_put(ByteBuf *o, const uint8_t *p, size_t n)
{
    static const char abc[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    if (bytebuf_room(o, (n + 2) / 3 * 4))
        return;
    char *d = (char *)o->b + o->len, *d0 = d;
    size_t i = 0;
    for (; i + 3 <= n; i += 3) {
        uint32_t v = (uint32_t)p[i] << 16 | (uint32_t)p[i + 1] << 8 | p[i + 2];
        *d++ = abc[v >> 18];
        *d++ = abc[(v >> 12) & 63];
        *d++ = abc[(v >> 6) & 63];
        *d++ = abc[v & 63];
    }
    if (i < n) {
        uint32_t v = (uint32_t)p[i] << 16 | (i + 1 < n ? (uint32_t)p[i + 1] << 8 : 0);
        *d++ = abc[v >> 18];
        *d++ = abc[(v >> 12) & 63];
        *d++ = i + 1 < n ? abc[(v >> 6) & 63] : '=';
        *d++ = '=';
    }
    /* what bytebuf_room made room for, no more: 4 characters a 3 bytes */
    ZV_ASSERT((size_t)(d - d0) == (n + 2) / 3 * 4);
    o->len = (size_t)(d - (char *)o->b);
}

/* ==== Sixel ==== */

/* One colour's line of a band: the run of sixel characters for the
 * pixels of colour c, run-length coded, without the run of empty ones
 * at the end (the "$" that follows returns anyway). */
static void sixel_line(ByteBuf *o, const uint8_t *band, int rows, int w, int c)
{
    int last = -1, run = 0, covered = 0;
    char buf[16];
    int end = w;
    ZV_ASSERT(rows >= 1 && rows <= 6);     /* a sixel is six pixels tall */
    /* trailing pixels without c need no characters */
    while (end > 0) {
        int any = 0;
        for (int k = 0; k < rows && !any; k++)
            any = band[(size_t)k * w + end - 1] == c;
        if (any)
            break;
        end--;
    }
    for (int x = 0; x <= end; x++) {
        int bits = -1;
        if (x < end) {
            bits = 0;
            for (int k = 0; k < rows; k++)
                bits |= (band[(size_t)k * w + x] == c) << k;
        }
        if (bits == last) {
            run++;
            continue;
        }
        /* a character is '?' + six bits: 63 .. 126 */
        ZV_ASSERT(run == 0 || (last >= 0 && last < 64));
        covered += run;
        if (run > 3) {
            int n = snprintf(buf, sizeof buf, "!%d%c", run, 63 + last);
            bytebuf_put(o, buf, (size_t)n);
        } else {
            for (int i = 0; i < run; i++)
                buf[i] = (char)(63 + last);
            bytebuf_put(o, buf, (size_t)run);
        }
        last = bits;
        run = 1;
    }
    /* the runs cover the line's pixels up to its last of colour c,
     * exactly: one short would shift every later pixel of the colour */
    ZV_ASSERT(covered == end);
}

static int sixel_encode(const Image *im, ByteBuf *o)
{
    Quantizer q;
    if (quant_init(&q, COLOUR_256))
        return -1;
    int w = im->w, h = im->h;
    uint8_t *idx = malloc((size_t)w * (size_t)h);
    if (!idx) {
        quant_free(&q);
        return -1;
    }
    uint8_t used[256] = { 0 };
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            int n = quant_pick(&q, im->rgb + 3 * i, x, y);
            idx[i] = (uint8_t)(n < 0 ? 16 : n);
            used[idx[i]] = 1;
        }
    quant_free(&q);
    char buf[64];
    /* P2 = 1: pixels not drawn keep what is there; raster attributes:
     * square pixels, the image's size */
    int n = snprintf(buf, sizeof buf, "\033P0;1;0q\"1;1;%d;%d", w, h);
    bytebuf_put(o, buf, (size_t)n);
    for (int c = 0; c < 256; c++)
        if (used[c]) {
            uint8_t rgb[3];
            palette_256_rgb(c, rgb);
            n = snprintf(buf, sizeof buf, "#%d;2;%d;%d;%d", c, (rgb[0] * 100 + 127) / 255,
                         (rgb[1] * 100 + 127) / 255, (rgb[2] * 100 + 127) / 255);
            bytebuf_put(o, buf, (size_t)n);
        }
    for (int y = 0; y < h; y += 6) {
        int rows = h - y < 6 ? h - y : 6;
        const uint8_t *band = idx + (size_t)y * w;
        uint8_t in_band[256] = { 0 };
        for (size_t i = 0; i < (size_t)rows * w; i++)
            in_band[band[i]] = 1;
        int first = 1;
        for (int c = 0; c < 256; c++) {
            if (!in_band[c])
                continue;
            if (!first)
                bytebuf_put(o, "$", 1);
            first = 0;
            n = snprintf(buf, sizeof buf, "#%d", c);
            bytebuf_put(o, buf, (size_t)n);
            sixel_line(o, band, rows, w, c);
        }
        if (y + 6 < h)
            bytebuf_put(o, "-", 1);
    }
    bytebuf_puts(o, "\033\\");
    free(idx);
    return o->err ? -1 : 0;
}

/* ==== kitty and iTerm2: PNG in base64 ==== */

#define KITTY_CHUNK 4096        /* the protocol's largest chunk of base64 */

static int kitty_encode(const Image *im, uint32_t id, int cols, int rows, ByteBuf *o)
{
    ByteBuf png = { 0 }, b64 = { 0 };
    char err[160];
    if (png_encode(im, 1, &png, err, sizeof err)) {
        bytebuf_free(&png);
        return -1;
    }
    base64_put(&b64, png.b, png.len);
    bytebuf_free(&png);
    if (b64.err)
        return -1;
    char head[96];
    for (size_t at = 0; at < b64.len || at == 0; at += KITTY_CHUNK) {
        size_t n = b64.len - at < KITTY_CHUNK ? b64.len - at : KITTY_CHUNK;
        int more = at + n < b64.len;
        /* every chunk whole base64 quanta (the terminal decodes each on
         * its own), all but the last full */
        ZV_ASSERT(n % 4 == 0 && (!more || n == KITTY_CHUNK));
        int k;
        /* the first chunk carries the keys: transmit and show (a=T), PNG
         * (f=100), no answer (q=2); a numbered image (the viewer's, over
         * its own screen) leaves the cursor where it is (C=1), an
         * unnumbered one (--print) moves it below, scrolling as text would */
        char fit[32] = "";
        if (cols > 0 && rows > 0)
            snprintf(fit, sizeof fit, ",c=%d,r=%d", cols, rows);     /* scaled to fill those cells */
        if (at == 0 && id)
            k = snprintf(head, sizeof head, "\033_Ga=T,f=100,q=2,C=1,i=%u%s,m=%d;", id, fit, more);
        else if (at == 0)
            k = snprintf(head, sizeof head, "\033_Ga=T,f=100,q=2%s,m=%d;", fit, more);
        else
            k = snprintf(head, sizeof head, "\033_Gm=%d;", more);
        bytebuf_put(o, head, (size_t)k);
        bytebuf_put(o, b64.b + at, n);
        bytebuf_puts(o, "\033\\");
        if (!more)
            break;
    }
    bytebuf_free(&b64);
    return o->err ? -1 : 0;
}

static int iterm_encode(const Image *im, int cols, int rows, ByteBuf *o)
{
    ByteBuf png = { 0 };
    char err[160], head[160];
    if (png_encode(im, 1, &png, err, sizeof err)) {
        bytebuf_free(&png);
        return -1;
    }
    int k = cols > 0 && rows > 0
          ? snprintf(head, sizeof head, "\033]1337;File=inline=1;size=%zu;width=%d;height=%d;preserveAspectRatio=0:",
                     png.len, cols, rows)
          : snprintf(head, sizeof head, "\033]1337;File=inline=1;size=%zu;width=%dpx;height=%dpx;preserveAspectRatio=0:",
                     png.len, im->w, im->h);
    bytebuf_put(o, head, (size_t)k);
    base64_put(o, png.b, png.len);
    bytebuf_put(o, "\a", 1);
    bytebuf_free(&png);
    return o->err ? -1 : 0;
}

int pixels_encode(PixelProto p, const Image *im, uint32_t kitty_id, int cols, int rows, ByteBuf *out)
{
    if (im->w <= 0 || im->h <= 0)
        return -1;
    switch (p) {
    case PIX_SIXEL: return sixel_encode(im, out);
    case PIX_KITTY: return kitty_encode(im, kitty_id, cols, rows, out);
    case PIX_ITERM: return iterm_encode(im, cols, rows, out);
    default:        return -1;
    }
}
