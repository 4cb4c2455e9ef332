/* oneshot.c: --print, -o, --dump-ids, --dump-screen: one frame, no curses. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "app.h"

/* Cells for --print: --size, else the terminal's size, else 80x24. */
static void print_size(const Options *o, int *cols, int *rows)
{
    if (o->w > 0) {
        *cols = o->w;
        *rows = o->h;
        return;
    }
    struct winsize ws;
    if (isatty(STDOUT_FILENO) && ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 &&
        ws.ws_row > 1) {
        *cols = ws.ws_col;
        *rows = ws.ws_row - 1;   /* leave the prompt's line */
        return;
    }
    *cols = 80;
    *rows = 24;
}

/* The face ids as little-endian int32 on any host. Returns 0, or -1
 * after a message naming the file. */
static int write_ids(const char *path, const FrameBufs *fb)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "zview: %s: %s\n", path, strerror(errno));
        return -1;
    }
    Out out;
    out_init(&out, f, path);
    size_t n = (size_t)fb->w * fb->h;
    unsigned char buf[4096];
    size_t k = 0;
    for (size_t i = 0; i < n && !out.err; i++) {
        uint32_t v = (uint32_t)fb->ids[i];
        buf[k++] = (unsigned char)v;
        buf[k++] = (unsigned char)(v >> 8);
        buf[k++] = (unsigned char)(v >> 16);
        buf[k++] = (unsigned char)(v >> 24);
        if (k == sizeof buf) {
            out_write(&out, buf, k);
            k = 0;
        }
    }
    out_write(&out, buf, k);
    if (out_close(&out)) {
        fprintf(stderr, "zview: %s: %s\n", path, out_error(&out));
        return -1;
    }
    return 0;
}

/* -o FILE or -o - (standard output): PNG or PPM by --image-format, else
 * by the name (standard output: PNG). The writers take a path, so
 * standard output gets the image through a temporary file, copied: that
 * works for pipes and files alike (opening /dev/stdout again would
 * truncate a file the shell opened for appending). */
static int write_image(const Options *o, const Image *img, char *err, size_t errlen)
{
    size_t n = strlen(o->out);
    int to_stdout = !strcmp(o->out, "-");
    int png = o->image_format ? o->image_format == IMG_PNG
                              : to_stdout || (n >= 4 && !strcmp(o->out + n - 4, ".png"));
    int (*writer)(const char *, const Image *, char *, size_t) = png ? write_png : write_ppm;
    if (!to_stdout)
        return writer(o->out, img, err, errlen);
    if (isatty(STDOUT_FILENO)) {
        snprintf(err, errlen, "-o -: standard output is a terminal (pipe the image on, e.g. "
                              "| img2sixel)");
        return -1;
    }
    const char *dir = getenv("TMPDIR");
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s/zview-XXXXXX", dir && *dir ? dir : "/tmp");
    int fd = mkstemp(tmp);
    if (fd < 0) {
        snprintf(err, errlen, "-o -: cannot make a temporary file in %s", dir && *dir ? dir : "/tmp");
        return -1;
    }
    close(fd);
    int rc = writer(tmp, img, err, errlen);
    FILE *f = rc ? NULL : fopen(tmp, "rb");
    if (!rc && !f)
        rc = -1;
    if (f) {
        char buf[65536];
        size_t k;
        while ((k = fread(buf, 1, sizeof buf, f)) > 0)
            if (fwrite(buf, 1, k, stdout) != k)
                break;
        if (ferror(f) || fflush(stdout) != 0 || ferror(stdout)) {
            snprintf(err, errlen, "-o -: cannot write to standard output");
            rc = -1;
        }
        fclose(f);
    }
    unlink(tmp);
    return rc;
}

int app_oneshot(const Options *o, Scene *s)
{
    const HsrAlgo *algo = hsr_find(o->algo ? o->algo : "zbuffer");
    char err[512];
    Pipeline p;
    if (pipeline_init(&p, s, algo, o->threads)) {
        fprintf(stderr, "zview: out of memory\n");
        return 1;
    }
    pipeline_apply_options(&p, o);     /* images: 1 sample unless asked, full resolution already */
    int rc = 0;
    int text = o->print || (!o->out && !o->dump_ids && !o->dump_screen);
    if (o->out || ((o->dump_ids || o->dump_screen) && !text)) {
        int w = o->w > 0 ? o->w : 640, h = o->h > 0 ? o->h : 480;
        if (pipeline_render(&p, w, h, 1.0f, o->cull, o->out != NULL)) {
            fprintf(stderr, "zview: out of memory\n");
            rc = 1;
            goto out;
        }
        if (o->out) {
            if (write_image(o, &p.img, err, sizeof err)) {
                fprintf(stderr, "zview: %s\n", err);
                rc = 1;
                goto out;
            }
        }
    }
    if (text) {
        DisplayMode mode = o->mode >= 0 ? (DisplayMode)o->mode : mode_from_locale();
        ColorDepth color = o->color >= 0 ? (ColorDepth)o->color : color_from_env();
        int cols, rows, pw, ph;
        print_size(o, &cols, &rows);
        p.samples = o->samples > 0 ? o->samples : TEXT_SAMPLES;   /* as the viewer draws */
        mode_cell_pixels(mode, &pw, &ph);
        if (pipeline_render(&p, cols * pw, rows * ph, mode_pixel_aspect(mode), o->cull, 1) ||
            cells_from_image(&p.img, mode, color, &p.cells)) {
            fprintf(stderr, "zview: out of memory\n");
            rc = 1;
            goto out;
        }
        if (print_cells(stdout, &p.cells, color)) {
            fprintf(stderr, "zview: standard output: %s\n", strerror(errno));
            rc = 1;
            goto out;
        }
    }
    const char *why = frame_empty_reason(&p);     /* an empty picture says why */
    if (why)
        fprintf(stderr, "zview: nothing drawn: %s\n", why);
    if (o->dump_ids && write_ids(o->dump_ids, &p.fb))
        rc = 1;
    if (o->dump_screen && screen_dump_obj(&p.sp, o->dump_screen)) {
        fprintf(stderr, "zview: %s: %s\n", o->dump_screen, strerror(errno));
        rc = 1;
    }
out:
    pipeline_free(&p);
    return rc;
}
