/* pngread.c: PNG images through libpng, a row at a time into shrink.c, so
 * that an image kept at a quarter of its size never lies whole in
 * memory (a 16k x 16k PNG took 1.4 GB for its own chain before halving).
 *
 * The transformations are those of libpng's simplified API asked for
 * 8-bit RGBA (png_image_finish_read with PNG_FORMAT_RGBA), which zview
 * used before, so every image gives the bytes it gave: palette, grey
 * and low bit depths expanded, transparency to alpha, a 16-bit file
 * taken as linear light unless it says otherwise (gAMA, sRGB) and
 * encoded to sRGB, alpha added as 255 where there is none. Benign
 * errors are warnings, as there.
 *
 * Bounds: libpng's own (user limits of TEX_MAX_SIDE a side; 1 MB for an
 * ancillary chunk, 64 of them kept; the chunks sampling needs nothing
 * of skipped), and the budget: an interlaced image must be whole before
 * its rows are known, so it counts its full size. */

#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "texture_internal.h"

typedef struct {
    const uint8_t *data;
    size_t         len, at;
    const char    *name;
    char           msg[200];
    jmp_buf        jmp;
} PngIn;

static void png_on_error(png_structp p, png_const_charp msg)
{
    PngIn *in = png_get_error_ptr(p);
    snprintf(in->msg, sizeof in->msg, "%s", msg);
    longjmp(in->jmp, 1);
}

static void png_quiet(png_structp p, png_const_charp msg)
{
    (void)p;
    (void)msg;
}

static void png_from_memory(png_structp p, png_bytep out, size_t n)
{
    PngIn *in = png_get_io_ptr(p);
    if (n > in->len - in->at)
        png_error(p, "unexpected end of file");
    memcpy(out, in->data + in->at, n);
    in->at += n;
}

/* The chunks the colours depend on (as the simplified API keeps them);
 * every other ancillary chunk is skipped unread. */
static void skip_chunks(png_structp p)
{
    static const png_byte keep[] = { 'b', 'K', 'G', 'D', 0, 'c', 'H', 'R', 'M', 0, 'g', 'A', 'M', 'A', 0,
                                     'i', 'C', 'C', 'P', 0, 's', 'B', 'I', 'T', 0, 's', 'R', 'G', 'B', 0 };
    png_set_keep_unknown_chunks(p, PNG_HANDLE_CHUNK_NEVER, NULL, -1);
    png_set_keep_unknown_chunks(p, PNG_HANDLE_CHUNK_AS_DEFAULT, keep, 6);
}

/* 8-bit sRGB RGBA whatever the file holds (see the top of the file). */
static void to_rgba8(png_structp p, png_infop info)
{
    int type = png_get_color_type(p, info), depth = png_get_bit_depth(p, info);
    int alpha = (type & PNG_COLOR_MASK_ALPHA) || png_get_valid(p, info, PNG_INFO_tRNS);
    png_set_expand(p);
    if (!(type & PNG_COLOR_MASK_COLOR))
        png_set_gray_to_rgb(p);
    png_set_alpha_mode_fixed(p, PNG_ALPHA_PNG, depth == 16 ? PNG_GAMMA_LINEAR : PNG_DEFAULT_sRGB);
    if (depth == 16)
        png_set_scale_16(p);
    if (!alpha)
        png_set_add_alpha(p, 255, PNG_FILLER_AFTER);
    png_set_alpha_mode_fixed(p, PNG_ALPHA_PNG, PNG_DEFAULT_sRGB);
}

int texture_decode_png(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes, int halve,
                       char *err, size_t errlen)
{
    PngIn in = { .data = data, .len = len, .name = name };
    png_structp p = png_create_read_struct(PNG_LIBPNG_VER_STRING, &in, png_on_error, png_quiet);
    png_infop info = p ? png_create_info_struct(p) : NULL;
    TexShrink s;
    uint8_t *volatile whole = NULL;
    volatile int started = 0;
    memset(t, 0, sizeof *t);
    if (!info) {
        png_destroy_read_struct(&p, NULL, NULL);
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    if (setjmp(in.jmp)) {
        if (started)
            texture_shrink_abort(&s);
        free(whole);
        png_destroy_read_struct(&p, &info, NULL);
        memset(t, 0, sizeof *t);
        snprintf(err, errlen, "%s: %s", name, in.msg);
        return -1;
    }
    png_set_read_fn(p, &in, png_from_memory);
    png_set_user_limits(p, TEX_MAX_SIDE, TEX_MAX_SIDE);
    png_set_chunk_malloc_max(p, 1 << 20);
    png_set_chunk_cache_max(p, 64);
    png_set_benign_errors(p, 1);
    skip_chunks(p);
    /* the size first, for a message of ours rather than libpng's */
    png_uint_32 w32 = 0, h32 = 0;
    if (len >= 24 && memcmp((const uint8_t *)data + 12, "IHDR", 4) == 0) {
        const uint8_t *b = (const uint8_t *)data + 16;
        w32 = (png_uint_32)b[0] << 24 | (png_uint_32)b[1] << 16 | (png_uint_32)b[2] << 8 | b[3];
        h32 = (png_uint_32)b[4] << 24 | (png_uint_32)b[5] << 16 | (png_uint_32)b[6] << 8 | b[7];
        if (w32 < 1 || h32 < 1 || w32 > TEX_MAX_SIDE || h32 > TEX_MAX_SIDE) {
            png_destroy_read_struct(&p, &info, NULL);
            snprintf(err, errlen, "%s: a %lux%lu image (1 to %d per side)", name, (unsigned long)w32,
                     (unsigned long)h32, TEX_MAX_SIDE);
            return -1;
        }
    }
    png_read_info(p, info);
    int w = (int)png_get_image_width(p, info), h = (int)png_get_image_height(p, info), kw, kh;
    int interlaced = png_get_interlace_type(p, info) != PNG_INTERLACE_NONE;
    texture_kept_size(w, h, halve, &kw, &kh);
    /* libpng's two rows of the file's bytes (8 a pixel at most), the
     * whole image when interlaced, the rows shrink.c halves */
    uint64_t working = 2 * ((uint64_t)w * 8 + 1) + (interlaced ? (uint64_t)w * h * 4 : 0) +
                       texture_shrink_bytes(w, h, halve);
    if (texture_check_budget(name, interlaced ? "interlaced PNG" : "PNG", w, h, kw, kh, working, max_bytes, err,
                             errlen)) {
        png_destroy_read_struct(&p, &info, NULL);
        return -1;
    }
    to_rgba8(p, info);
    int passes = png_set_interlace_handling(p);
    png_read_update_info(p, info);
    if (png_get_rowbytes(p, info) != (size_t)w * 4)
        png_error(p, "unexpected row size");
    if (texture_shrink_begin(&s, t, w, h, halve)) {
        png_destroy_read_struct(&p, &info, NULL);
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    started = 1;
    if (passes > 1) {
        /* each pass adds pixels to rows written before: the whole image */
        whole = malloc((size_t)w * (size_t)h * 4);
        if (!whole)
            png_error(p, "out of memory");
        for (int pass = 0; pass < passes; pass++)
            for (int y = 0; y < h; y++)
                png_read_row(p, whole + (size_t)y * w * 4, NULL);
        for (int y = 0; y < h; y++) {
            memcpy(texture_shrink_row(&s), whole + (size_t)y * w * 4, (size_t)w * 4);
            texture_shrink_push(&s);
        }
        free(whole);
        whole = NULL;
    } else {
        for (int y = 0; y < h; y++) {
            png_read_row(p, texture_shrink_row(&s), NULL);
            texture_shrink_push(&s);
        }
    }
    png_destroy_read_struct(&p, &info, NULL);
    texture_shrink_finish(&s);
    return 0;
}
