/* decode.c: the front door of the image decoders: PNG (pngread.c), JPEG
 * (jpeg.c) and TGA (tga.c), told apart by their first bytes (TGA, which
 * has no magic, when its header makes sense); each halves the image to
 * the size asked as its rows arrive (shrink.c), then the chain is
 * mipmapped (mip.c). Sizes and the memory a decode will take are
 * checked before anything big is allocated (the budget, here). */

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sysmem.h"
#include "texture.h"
#include "texture_internal.h"

/* ==== size checks ==== */

uint64_t texture_bytes_for(int w, int h)
{
    uint64_t n = 0;
    for (;;) {
        n += (uint64_t)w * (uint64_t)h * 4;
        if (w == 1 && h == 1)
            return n;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
}

int texture_check_size(int w, int h, const char *name, uint64_t max_bytes, char *err, size_t errlen)
{
    if (w < 1 || h < 1 || w > TEX_MAX_SIDE || h > TEX_MAX_SIDE) {
        snprintf(err, errlen, "%s: a %dx%d image (1 to %d per side)", name, w, h, TEX_MAX_SIDE);
        return -1;
    }
    uint64_t need = texture_bytes_for(w, h) + texture_lin_bytes_for(w, h), avail = sysmem_available();
    if (max_bytes && max_bytes < avail)
        avail = max_bytes;
    if (need > avail) {
        char n[32], a[32];
        sysmem_format(need, n, sizeof n);
        sysmem_format(avail, a, sizeof a);
        snprintf(err, errlen, "%s: a %dx%d image needs about %s; %s available", name, w, h, n, a);
        return -1;
    }
    return 0;
}

/* ==== the budget ==== */

void texture_kept_size(int w, int h, int halve, int *kw, int *kh)
{
    for (int j = 0; j < halve; j++) {
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    *kw = w;
    *kh = h;
}

/* why_out: 0 the default budget, 1 the caller's bound, 2 the machine's memory */
static uint64_t budget_of(int kw, int kh, uint64_t max_bytes, int *why_out)
{
    uint64_t b = max_bytes;
    *why_out = 1;
    if (!b) {
        *why_out = 0;
        b = TEX_BUDGET_FACTOR * (uint64_t)kw * (uint64_t)kh * 4;
        if (b < TEX_BUDGET_FLOOR)
            b = TEX_BUDGET_FLOOR;
    }
    uint64_t avail = sysmem_available();
    if (avail && avail < b) {
        *why_out = 2;
        b = avail;
    }
    return b;
}

uint64_t texture_budget(int kw, int kh, uint64_t max_bytes)
{
    int why;
    return budget_of(kw, kh, max_bytes, &why);
}

int texture_check_budget(const char *name, const char *what, int w, int h, int kw, int kh, uint64_t working,
                         uint64_t max_bytes, char *err, size_t errlen)
{
    int why;
    uint64_t need = working + texture_bytes_for(kw, kh) + texture_lin_bytes_for(kw, kh);
    uint64_t budget = budget_of(kw, kh, max_bytes, &why);
    if (need <= budget)
        return 0;
    char n[32], b[32];
    sysmem_format(need, n, sizeof n);
    sysmem_format(budget, b, sizeof b);
    if (why == 0)
        snprintf(err, errlen, "%s: a %dx%d %s needs about %s to decode; the budget for a texture kept at %dx%d is %s",
                 name, w, h, what, n, kw, kh, b);
    else
        snprintf(err, errlen, "%s: a %dx%d %s needs about %s to decode; %s %s", name, w, h, what, n, b,
                 why == 1 ? "allowed" : "available");
    return -1;
}

uint8_t *texture_alloc_levels(Texture *t, int w, int h)
{
    memset(t, 0, sizeof *t);
    t->rgba = malloc(texture_bytes_for(w, h));
    if (!t->rgba)
        return NULL;
    t->w = w;
    t->h = h;
    return t->rgba;
}

/* ==== the front door ==== */

static int is_png(const uint8_t *b, size_t len) { return len >= 8 && memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0; }
static int is_jpeg(const uint8_t *b, size_t len) { return len >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF; }

int texture_peek(const void *data, size_t len, int *w_out, int *h_out)
{
    const uint8_t *b = data;
    *w_out = *h_out = 0;
    if (is_jpeg(data, len))
        return texture_jpeg_peek(data, len, w_out, h_out);
    if (!is_png(data, len))
        return texture_tga_probe(data, len, w_out, h_out);
    /* the IHDR chunk, which comes first, read here: libpng would read
     * every chunk before the pixels, and 250 zTXt chunks of 4 KB that
     * each inflate to 4 MB took it 40 s */
    if (len < 24 || memcmp(b + 12, "IHDR", 4) != 0)
        return -1;
    uint32_t w = (uint32_t)b[16] << 24 | (uint32_t)b[17] << 16 | (uint32_t)b[18] << 8 | b[19];
    uint32_t h = (uint32_t)b[20] << 24 | (uint32_t)b[21] << 16 | (uint32_t)b[22] << 8 | b[23];
    if (!w || !h)
        return -1;
    *w_out = w > INT32_MAX ? INT32_MAX : (int)w;
    *h_out = h > INT32_MAX ? INT32_MAX : (int)h;
    return 0;
}

int texture_decode_fit(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes,
                       int max_side, int *halved_out, char *err, size_t errlen)
{
    const uint8_t *b = data;
    int rc, w = 0, h = 0, halve = 0;
    memset(t, 0, sizeof *t);
    if (halved_out)
        *halved_out = 0;
    if (max_side > 0 && texture_peek(data, len, &w, &h) == 0) {
        while (((w - 1) >> halve) + 1 > max_side || ((h - 1) >> halve) + 1 > max_side)
            halve++;
        /* a 1 x 1 level halves to itself: no more than the chain has */
        int kw, kh;
        while (halve > 0 && (texture_kept_size(w, h, halve - 1, &kw, &kh), kw == 1 && kh == 1))
            halve--;
    }
    if (is_png(b, len)) {
        rc = texture_decode_png(t, data, len, name, max_bytes, halve, err, errlen);
    } else if (is_jpeg(b, len)) {
        rc = texture_decode_jpeg(t, data, len, name, max_bytes, halve, err, errlen);
    } else if (texture_tga_probe(data, len, &w, &h) == 0) {
        rc = texture_decode_tga(t, data, len, name, max_bytes, halve, err, errlen);
    } else {
        snprintf(err, errlen, "%s: not a PNG, JPEG or TGA image", name);
        return -1;
    }
    if (rc)
        return -1;
    if (halved_out)
        *halved_out = halve;
    texture_build_lin(t);
    return 0;
}

int texture_from_rgba(Texture *t, const uint8_t *rgba, int w, int h, const char *name, uint64_t max_bytes,
                      char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    if (texture_check_size(w, h, name, max_bytes, err, errlen))
        return -1;
    uint8_t *px = texture_alloc_levels(t, w, h);
    if (!px) {
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    memcpy(px, rgba, (size_t)w * (size_t)h * 4);
    texture_build_levels(t);
    texture_build_lin(t);
    return 0;
}

int texture_decode(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes,
                   char *err, size_t errlen)
{
    return texture_decode_fit(t, data, len, name, max_bytes, 0, NULL, err, errlen);
}

int texture_load_file(Texture *t, const char *path, uint64_t max_bytes, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    /* compressed images are far smaller than their texels: a file larger
     * than the texels of the biggest image allowed is not one */
    uint64_t cap = texture_bytes_for(TEX_MAX_SIDE, TEX_MAX_SIDE);
    size_t n = 0, have = 0;
    uint8_t *buf = NULL;
    for (;;) {
        if (n == have) {
            size_t more = have ? have * 2 : 1 << 16;
            uint8_t *nb = more > cap ? NULL : realloc(buf, more);
            if (!nb) {
                free(buf);
                fclose(f);
                snprintf(err, errlen, "%s: %s", path, more > cap ? "too large for an image" : "out of memory");
                return -1;
            }
            buf = nb;
            have = more;
        }
        size_t r = fread(buf + n, 1, have - n, f);
        n += r;
        if (r == 0)
            break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        snprintf(err, errlen, "%s: read error", path);
        return -1;
    }
    int rc = texture_decode(t, buf, n, path, max_bytes, err, errlen);
    free(buf);
    return rc;
}

void texture_free(Texture *t)
{
    free(t->rgba);
    free(t->lin);
    memset(t, 0, sizeof *t);
}

void texture_make_lin(Texture *t)
{
    if (t->rgba && !t->lin)
        texture_build_lin(t);
}

size_t texture_bytes(const Texture *t)
{
    return (t->rgba ? (size_t)texture_bytes_for(t->w, t->h) : 0) + (t->lin ? (size_t)texture_lin_bytes_for(t->w, t->h) : 0);
}
