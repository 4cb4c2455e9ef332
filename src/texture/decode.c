/* decode.c: PNG (libpng's simplified API) and JPEG (libjpeg-turbo) images
 * into RGBA texels, told apart by their first bytes (TGA, which has no
 * magic, when its header makes sense: tga.c); then mipmapped (mip.c).
 * Sizes are checked before anything big is allocated. */

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
/* jpeglib.h needs FILE and size_t declared first */
#include <jpeglib.h>

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

/* ==== PNG ==== */

static int decode_png(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes,
                      char *err, size_t errlen)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&img, data, len)) {
        snprintf(err, errlen, "%s: %s", name, img.message);
        return -1;
    }
    if (texture_check_size((int)(img.width > INT32_MAX ? 0 : img.width), (int)(img.height > INT32_MAX ? 0 : img.height),
                   name, max_bytes, err, errlen)) {
        png_image_free(&img);
        return -1;
    }
    /* 8-bit sRGB RGBA whatever the file holds (palette, grey, 16 bits,
     * a gAMA chunk): libpng converts */
    img.format = PNG_FORMAT_RGBA;
    uint8_t *px = texture_alloc_levels(t, (int)img.width, (int)img.height);
    if (!px) {
        png_image_free(&img);
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    if (!png_image_finish_read(&img, NULL, px, 0, NULL)) {
        snprintf(err, errlen, "%s: %s", name, img.message);
        texture_free(t);
        return -1;
    }
    return 0;
}

/* ==== JPEG ==== */

typedef struct {
    struct jpeg_error_mgr mgr;      /* first: libjpeg's pointer is to it */
    jmp_buf               jmp;
    char                  msg[JMSG_LENGTH_MAX];
} JpegErr;

static void jpeg_on_error(j_common_ptr c)
{
    JpegErr *e = (JpegErr *)c->err;
    c->err->format_message(c, e->msg);
    longjmp(e->jmp, 1);
}

/* Warnings (a truncated file, bad data the decoder gets past) are not
 * written to stderr: the image shows what could be read. */
static void jpeg_quiet(j_common_ptr c, int level)
{
    (void)c;
    (void)level;
}

/* denom: 1, 2, 4 or 8, the reduction libjpeg decodes at. */
static int decode_jpeg(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes,
                       int denom, char *err, size_t errlen)
{
    struct jpeg_decompress_struct c;
    JpegErr e;
    memset(t, 0, sizeof *t);
    c.err = jpeg_std_error(&e.mgr);
    e.mgr.error_exit = jpeg_on_error;
    e.mgr.emit_message = jpeg_quiet;
    e.msg[0] = 0;
    /* t is written after setjmp only through its pointer: what it holds
     * when libjpeg gives up is freed below */
    if (setjmp(e.jmp)) {
        jpeg_destroy_decompress(&c);
        texture_free(t);
        snprintf(err, errlen, "%s: %s", name, e.msg[0] ? e.msg : "not a JPEG image zview can read");
        return -1;
    }
    jpeg_create_decompress(&c);
    jpeg_mem_src(&c, data, (unsigned long)len);
    jpeg_read_header(&c, TRUE);
    c.scale_num = 1;
    c.scale_denom = (unsigned)denom;
    jpeg_calc_output_dimensions(&c);
    if (texture_check_size((int)c.output_width, (int)c.output_height, name, max_bytes, err, errlen)) {
        jpeg_destroy_decompress(&c);
        return -1;
    }
    c.out_color_space = JCS_EXT_RGBA;       /* libjpeg-turbo: grey and CMYK converted too */
    jpeg_start_decompress(&c);
    uint8_t *px = texture_alloc_levels(t, (int)c.output_width, (int)c.output_height);
    if (!px) {
        jpeg_destroy_decompress(&c);
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    while (c.output_scanline < c.output_height) {
        JSAMPROW row = px + (size_t)c.output_scanline * (size_t)t->w * 4;
        jpeg_read_scanlines(&c, &row, 1);
    }
    jpeg_finish_decompress(&c);
    jpeg_destroy_decompress(&c);
    return 0;
}

/* ==== the front door ==== */

static int is_png(const uint8_t *b, size_t len) { return len >= 8 && memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0; }
static int is_jpeg(const uint8_t *b, size_t len) { return len >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF; }

int texture_peek(const void *data, size_t len, int *w_out, int *h_out)
{
    *w_out = *h_out = 0;
    if (!is_png(data, len) && !is_jpeg(data, len))
        return texture_tga_probe(data, len, w_out, h_out);
    if (is_png(data, len)) {
        png_image img;
        memset(&img, 0, sizeof img);
        img.version = PNG_IMAGE_VERSION;
        if (!png_image_begin_read_from_memory(&img, data, len))
            return -1;
        *w_out = img.width > INT32_MAX ? INT32_MAX : (int)img.width;
        *h_out = img.height > INT32_MAX ? INT32_MAX : (int)img.height;
        png_image_free(&img);
        return 0;
    }
    if (!is_jpeg(data, len))
        return -1;
    struct jpeg_decompress_struct c;
    JpegErr e;
    c.err = jpeg_std_error(&e.mgr);
    e.mgr.error_exit = jpeg_on_error;
    e.mgr.emit_message = jpeg_quiet;
    if (setjmp(e.jmp)) {
        jpeg_destroy_decompress(&c);
        return -1;
    }
    jpeg_create_decompress(&c);
    jpeg_mem_src(&c, data, (unsigned long)len);
    jpeg_read_header(&c, TRUE);
    *w_out = (int)c.image_width;
    *h_out = (int)c.image_height;
    jpeg_destroy_decompress(&c);
    return 0;
}

/* Drop the first k levels: level k becomes level 0, the texels moved to
 * the start of the block and the rest given back. */
static void drop_levels(Texture *t, int k)
{
    if (k <= 0 || k >= t->levels)
        return;
    size_t off = t->off[k], total = texture_bytes_for(t->w, t->h) / 4;
    memmove(t->rgba, t->rgba + 4 * off, 4 * (total - off));
    uint8_t *q = realloc(t->rgba, 4 * (total - off));
    if (q)
        t->rgba = q;
    for (int i = 0; i + k < t->levels; i++) {
        t->lw[i] = t->lw[i + k];
        t->lh[i] = t->lh[i + k];
        t->off[i] = t->off[i + k] - off;
    }
    t->levels -= k;
    t->w = t->lw[0];
    t->h = t->lh[0];
}

int texture_decode_fit(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes,
                       int max_side, int *halved_out, char *err, size_t errlen)
{
    const uint8_t *b = data;
    int rc, w = 0, h = 0, halve = 0;
    memset(t, 0, sizeof *t);
    if (halved_out)
        *halved_out = 0;
    if (max_side > 0 && texture_peek(data, len, &w, &h) == 0)
        while (((w - 1) >> halve) + 1 > max_side || ((h - 1) >> halve) + 1 > max_side)
            halve++;
    if (is_png(b, len)) {
        rc = decode_png(t, data, len, name, max_bytes, err, errlen);
    } else if (is_jpeg(b, len)) {
        int j = halve < 3 ? halve : 3;      /* libjpeg reduces by 8 at most */
        rc = decode_jpeg(t, data, len, name, max_bytes, 1 << j, err, errlen);
        halve -= j;
        if (halved_out)
            *halved_out = j;
    } else if (texture_tga_probe(data, len, &w, &h) == 0) {
        rc = texture_decode_tga(t, data, len, name, max_bytes, err, errlen);
    } else {
        snprintf(err, errlen, "%s: not a PNG, JPEG or TGA image", name);
        return -1;
    }
    if (rc)
        return -1;
    texture_build_levels(t);
    /* what the decoder could not reduce: the finest levels go */
    if (halve > 0) {
        int k = halve < t->levels - 1 ? halve : t->levels - 1;
        drop_levels(t, k);
        if (halved_out)
            *halved_out += k;
    }
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
