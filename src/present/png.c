/* png: save an Image as an 8-bit RGB PNG through libpng. libpng reports
 * errors by longjmp; the handler below copies its message into our own
 * buffer first, so the caller gets "path: reason" like every writer. */

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <string.h>
#include "invariant.h"
#include "pixels.h"
#include "present.h"
#include "safefile.h"

typedef struct {
    jmp_buf  jmp;
    char     msg[160];
    FILE    *f;
    ByteBuf *mem;           /* png_encode's destination (f is NULL) */
    int      write_errno;   /* why a write failed (libpng only says "Write Error") */
} PngErr;

/* libpng's own writer drops errno; this one keeps it for the message. */
static void png_write_cb(png_structp png, png_bytep data, size_t len)
{
    PngErr *e = png_get_error_ptr(png);
    errno = 0;
    if (fwrite(data, 1, len, e->f) != len) {
        e->write_errno = errno ? errno : EIO;
        png_error(png, strerror(e->write_errno));
    }
}

static void png_flush_cb(png_structp png)
{
    PngErr *e = png_get_error_ptr(png);
    errno = 0;
    if (fflush(e->f) != 0) {
        e->write_errno = errno ? errno : EIO;
        png_error(png, strerror(e->write_errno));
    }
}

static void png_on_error(png_structp png, png_const_charp msg)
{
    PngErr *e = png_get_error_ptr(png);
    snprintf(e->msg, sizeof e->msg, "%s", msg ? msg : "libpng error");
    longjmp(e->jmp, 1);
}

static void png_on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;      /* warnings do not stop the write; keep stderr quiet */
}

int write_png(const char *path, const Image *im, char *err, size_t errlen)
{
    if (im->w <= 0 || im->h <= 0) {
        snprintf(err, errlen, "%s: empty image", path);
        return -1;
    }
    SafeFile sf;
    FILE *f = safefile_open(&sf, path, "wb");
    if (!f) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    /* png, info and f are not changed after setjmp, so they stay valid
     * when libpng longjmps back. */
    PngErr e;
    e.msg[0] = '\0';
    e.f = f;
    e.mem = NULL;
    e.write_errno = 0;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &e,
                                              png_on_error, png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(png ? &png : NULL, NULL);
        safefile_close(&sf, f, 1);
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    if (setjmp(e.jmp)) {
        png_destroy_write_struct(&png, &info);
        safefile_close(&sf, f, 1);
        snprintf(err, errlen, "%s: %s", path, e.msg);
        return -1;
    }
    png_set_write_fn(png, &e, png_write_cb, png_flush_cb);
    png_set_IHDR(png, info, (png_uint_32)im->w, (png_uint_32)im->h, 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    /* libpng reads 3 w bytes a row: the image holds its w x h pixels */
    ZV_ASSERT((size_t)im->w * (size_t)im->h <= im->cap);
    for (int y = 0; y < im->h; y++)
        png_write_row(png, im->rgb + 3 * (size_t)y * (size_t)im->w);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    /* A full disk shows up only when the buffered bytes are flushed. */
    Out out;
    out_init(&out, f, path);
    out_flush(&out);
    errno = out.err;
    if (safefile_close(&sf, f, out.err != 0)) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno ? errno : EIO));
        return -1;
    }
    return 0;
}

/* png_encode's writer: into memory, an allocation failure as libpng's
 * error. */
static void png_mem_cb(png_structp png, png_bytep data, size_t len)
{
    PngErr *e = png_get_error_ptr(png);
    bytebuf_put(e->mem, data, len);
    if (e->mem->err)
        png_error(png, "out of memory");
}

static void png_mem_flush(png_structp png)
{
    (void)png;
}

int png_encode(const Image *im, int level, ByteBuf *out, char *err, size_t errlen)
{
    if (im->w <= 0 || im->h <= 0) {
        snprintf(err, errlen, "empty image");
        return -1;
    }
    PngErr e;
    e.msg[0] = '\0';
    e.f = NULL;
    e.mem = out;
    e.write_errno = 0;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &e, png_on_error, png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(png ? &png : NULL, NULL);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    if (setjmp(e.jmp)) {
        png_destroy_write_struct(&png, &info);
        snprintf(err, errlen, "%s", e.msg);
        return -1;
    }
    png_set_write_fn(png, &e, png_mem_cb, png_mem_flush);
    /* a terminal's picture is sent each time the model stops: speed
     * over size (level 1 is about a third the time of the default) */
    png_set_compression_level(png, level);
    png_set_IHDR(png, info, (png_uint_32)im->w, (png_uint_32)im->h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    ZV_ASSERT((size_t)im->w * (size_t)im->h <= im->cap);      /* as write_png's */
    for (int y = 0; y < im->h; y++)
        png_write_row(png, im->rgb + 3 * (size_t)y * (size_t)im->w);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 0;
}
