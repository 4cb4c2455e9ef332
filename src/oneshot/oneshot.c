/* oneshot.c: --print, -o, --dump-ids, --dump-screen: one frame, no curses.
 *
 * The backgrounds (backdrop.h): text is seen on the terminal's own, as
 * the terminal answers the colour query when --print writes to one;
 * an image is painted with --bg's colour, or black, or white behind a
 * dark model (picked on the first frame, kept for a turntable's). */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include "oneshot.h"
#include "pixels.h"
#include "safefile.h"
#include "safetext.h"
#include "tty.h"

/* The two backgrounds of a run, found once. */
typedef struct {
    Backdrop image, text;
    int      image_known, text_known;
    int      proto;             /* --print's PixelProto, -1 = not asked yet (a turntable asks once) */
} Backdrops;

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

/* Flush and close a file written through out; it takes its name only
 * when complete. Returns 0, or -1 after a message naming it. */
static int close_written(SafeFile *sf, Out *out)
{
    out_flush(out);
    errno = out->err;
    if (safefile_close(sf, out->f, out->err != 0)) {
        safetext_line(stderr, "zview: %s: %s", out->name, strerror(errno ? errno : EIO));
        return -1;
    }
    return 0;
}

/* The face ids as little-endian int32 on any host. Returns 0, or -1
 * after a message naming the file. */
static int write_ids(const char *path, const FrameBufs *fb)
{
    SafeFile sf;
    FILE *f = safefile_open(&sf, path, "wb");
    if (!f) {
        safetext_line(stderr, "zview: %s: %s", path, strerror(errno));
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
    return close_written(&sf, &out);
}

/* -o FILE or -o - (standard output): PNG or PPM by --image-format, else
 * by the name (standard output: PNG). The writers take a path, so
 * standard output gets the image through a temporary file, copied: that
 * works for pipes and files alike (opening /dev/stdout again would
 * truncate a file the shell opened for appending). */
static int write_image(const Options *o, const char *path, const Image *img, char *err, size_t errlen)
{
    size_t n = strlen(path);
    int to_stdout = !strcmp(path, "-");
    int png = o->image_format ? o->image_format == IMG_PNG
                              : to_stdout || (n >= 4 && !strcmp(path + n - 4, ".png"));
    int (*writer)(const char *, const Image *, char *, size_t) = png ? write_png : write_ppm;
    if (!to_stdout)
        return writer(path, img, err, errlen);
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
        /* the first failure's errno is the reason: stdio's buffering
         * shows a full device only at a later write or the flush */
        Out out;
        out_init(&out, stdout, "standard output");
        char buf[65536];
        size_t k;
        while ((k = fread(buf, 1, sizeof buf, f)) > 0 && out_write(&out, buf, k) == 0)
            ;
        int read_failed = ferror(f);
        if (out_flush(&out) || read_failed) {
            snprintf(err, errlen, "-o -: cannot write to standard output: %s",
                     read_failed && !out.err ? "cannot read back the image" : out_error(&out));
            rc = -1;
        }
        fclose(f);
    }
    unlink(tmp);
    return rc;
}

/* --dump-screen: the screen polygons as OBJ text, whole or not at all. */
static int dump_screen(const ScreenPolys *sp, const char *path)
{
    SafeFile sf;
    FILE *f = safefile_open(&sf, path, "w");
    if (!f) {
        safetext_line(stderr, "zview: %s: %s", path, strerror(errno));
        return -1;
    }
    Out out;
    out_init(&out, f, path);
    if (screen_dump_obj(sp, f))
        out.err = errno ? errno : EIO;
    return close_written(&sf, &out);
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && !strcmp(s + n - m, suffix);
}

/* The text's background: --bg, else the terminal's when --print shows
 * the picture on one that says, else COLORFGBG's or black. */
static const Backdrop *text_backdrop(const Options *o, Backdrops *b)
{
    if (!b->text_known) {
        uint8_t asked[3];
        int told = !o->bg && o->print && isatty(STDOUT_FILENO) && termbg_ask_tty(TERMBG_WAIT_MS, asked);
        b->text = pipeline_text_backdrop(o, told ? asked : NULL);
        b->text_known = 1;
    }
    return &b->text;
}

/* The text frame of the options into p->cells (what --print shows).
 * Returns 0, or -1 out of memory. */
static int render_text(const Options *o, Pipeline *p, Backdrops *b, ColourDepth *depth)
{
    DisplayMode mode = o->mode >= 0 ? (DisplayMode)o->mode : mode_from_locale();
    *depth = o->colour >= 0 ? (ColourDepth)o->colour : colour_from_env();
    int cols, rows, pw, ph;
    print_size(o, &cols, &rows);
    int samples = p->samples;
    p->samples = o->samples > 0 ? o->samples : TEXT_SAMPLES;   /* as the viewer draws */
    mode_cell_pixels(mode, &pw, &ph);
    pipeline_set_backdrop(p, text_backdrop(o, b));
    int rc = pipeline_render(p, cols * pw, rows * ph, mode_pixel_aspect(mode), o->cull, 1) ||
             cells_from_image_on(&p->img, mode, *depth, &p->bd, &p->cells);
    p->samples = samples;
    return rc ? -1 : 0;
}

/* The image of the options into p->img (what -o writes); shade_too 0:
 * only the buffers (for the dumps). */
static int render_image(const Options *o, Pipeline *p, int shade_too)
{
    int w = o->w > 0 ? o->w : 640, h = o->h > 0 ? o->h : 480;
    return pipeline_render(p, w, h, 1.0f, o->cull, shade_too);
}

/* The image of the options on its background, painted: --bg's, or the
 * one picked for the first frame (rendered as given, then kept visible
 * on what was picked). Returns 0, or -1 out of memory. */
static int render_painted(const Options *o, Pipeline *p, Backdrops *b)
{
    if (!b->image_known && o->bg) {
        b->image = pipeline_text_backdrop(o, NULL);     /* --bg's colour, painted */
        b->image_known = 1;
    }
    p->has_bd = b->image_known;
    if (b->image_known)
        pipeline_set_backdrop(p, &b->image);
    if (render_image(o, p, 1))
        return -1;
    if (!b->image_known) {
        b->image = backdrop_pick(&p->img, p->contrast > 0 ? p->contrast : CONTRAST_DEFAULT);
        b->image_known = 1;
        pipeline_set_backdrop(p, &b->image);
        if (contrast_apply(&p->rule, &b->image, p->contrast, &p->img))
            return -1;
    }
    backdrop_paint(&p->img, &b->image);
    return 0;
}

/* The protocol --print draws in: the one given, or (auto) the one the
 * terminal on standard output answers for; PIX_CELLS for text. */
static PixelProto print_protocol(const Options *o)
{
    if (o->pixels != PIX_AUTO)
        return o->pixels > 0 ? (PixelProto)o->pixels : PIX_CELLS;
    if (!isatty(STDOUT_FILENO))
        return PIX_CELLS;
    int fd = open("/dev/tty", O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (fd < 0)
        return PIX_CELLS;
    /* as for the background: only in the foreground, without echo */
    struct termios old, raw;
    PixelProto p = PIX_CELLS;
    if (tcgetpgrp(fd) == getpgrp() && tcgetattr(fd, &old) == 0) {
        raw = old;
        raw.c_lflag &= (tcflag_t) ~(ICANON | ECHO);
        raw.c_cc[VMIN] = 1;
        raw.c_cc[VTIME] = 0;
        if (tcsetattr(fd, TCSANOW, &raw) == 0) {
            PixelScan scan;
            pixels_scan_init(&scan, 0);
            p = pixels_detect(fd, fd, TERMBG_WAIT_MS, NULL, NULL, &scan);
            tcsetattr(fd, TCSANOW, &old);
        }
    }
    close(fd);
    return p;
}

/* --print in the terminal's pixels: the picture at the text's size in
 * cells times the cell's size in pixels (what the terminal says, else
 * 10 x 20), on the text's background, painted. Returns 0, or 1 after a
 * message. */
static int print_pixels(const Options *o, Pipeline *p, Backdrops *b, PixelProto proto)
{
    int cols, rows, cw = PIXELS_CELL_W, ch = PIXELS_CELL_H;
    print_size(o, &cols, &rows);
    if (isatty(STDOUT_FILENO))
        pixels_cell_size(STDOUT_FILENO, &cw, &ch);
    pipeline_set_backdrop(p, text_backdrop(o, b));
    if (pipeline_render(p, cols * cw, rows * ch, 1.0f, o->cull, 1)) {
        safetext_line(stderr, "zview: out of memory");
        return 1;
    }
    backdrop_paint(&p->img, &p->bd);
    ByteBuf out = { 0 };
    if (pixels_encode(proto, &p->img, 0, 0, 0, &out)) {
        bytebuf_free(&out);
        safetext_line(stderr, "zview: out of memory");
        return 1;
    }
    bytebuf_put(&out, "\n", 1);
    int bad = out.err || fwrite(out.b, 1, out.len, stdout) != out.len || fflush(stdout) != 0;
    bytebuf_free(&out);
    if (bad) {
        safetext_line(stderr, "zview: standard output: %s", strerror(errno ? errno : ENOMEM));
        return 1;
    }
    return 0;
}

/* The text frame into a file. Returns 0, or -1 after a message. */
static int write_text(const char *path, const CellGrid *g, ColourDepth depth)
{
    SafeFile sf;
    FILE *f = safefile_open(&sf, path, "w");
    if (!f) {
        safetext_line(stderr, "zview: %s: %s", path, strerror(errno));
        return -1;
    }
    Out out;
    out_init(&out, f, path);
    if (print_cells(f, g, depth))
        out.err = errno ? errno : EIO;
    return close_written(&sf, &out);
}

/* -o names a text file: FILE.txt, unless --image-format says otherwise. */
static int text_file(const Options *o, const char *file)
{
    return file && !o->image_format && ends_with(file, ".txt");
}

/* One frame of the view as it stands to -o FILE (image or text) and/or
 * stdout (--print). Returns 0, or 1 after a message. */
static int one_frame(const Options *o, Pipeline *p, Backdrops *b, const char *file)
{
    char err[512];
    ColourDepth depth;
    if (file && !text_file(o, file)) {
        if (render_painted(o, p, b)) {
            safetext_line(stderr, "zview: out of memory");
            return 1;
        }
        if (write_image(o, file, &p->img, err, sizeof err)) {
            safetext_line(stderr, "zview: %s", err);
            return 1;
        }
    }
    int to_file = text_file(o, file);
    if (o->print && b->proto < 0)
        b->proto = (int)print_protocol(o);
    PixelProto proto = o->print ? (PixelProto)b->proto : PIX_CELLS;
    if (proto != PIX_CELLS && print_pixels(o, p, b, proto))
        return 1;
    if (to_file || (o->print && proto == PIX_CELLS)) {
        if (render_text(o, p, b, &depth)) {
            safetext_line(stderr, "zview: out of memory");
            return 1;
        }
        if (to_file && write_text(file, &p->cells, depth))
            return 1;
        if (o->print && print_cells(stdout, &p->cells, depth)) {
            safetext_line(stderr, "zview: standard output: %s", strerror(errno));
            return 1;
        }
    }
    return 0;
}

/* --turntable N: frame k turned 360 k / N degrees about the vertical
 * from the view given, as the viewer's auto-rotate turns (the fit stays
 * the first frame's), written to the pattern with k in it. */
static int turntable(const Options *o, Scene *s, Pipeline *p, Backdrops *b)
{
    float yaw0 = s->cam.yaw;
    char path[4096];
    for (int k = 0; k < o->turntable; k++) {
        s->cam.yaw = yaw0 + deg2rad(360.0f * (float)k / (float)o->turntable);
        const char *file = NULL;
        if (o->out) {
            /* the pattern has exactly one integer conversion (cli.c) */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
            int n = snprintf(path, sizeof path, o->out, k);
#pragma GCC diagnostic pop
            if (n < 0 || (size_t)n >= sizeof path) {
                safetext_line(stderr, "zview: %s: the file name is too long", o->out);
                return 1;
            }
            file = path;
        }
        /* frames on standard output each start at the top left (cursor
         * home, the first on a cleared screen): `cat` plays them back in
         * place in a terminal, where run together they would scroll by
         * as one long picture */
        if (o->print && fputs(k ? "\033[H" : "\033[H\033[2J", stdout) == EOF) {
            safetext_line(stderr, "zview: standard output: %s", strerror(errno));
            return 1;
        }
        if (one_frame(o, p, b, file))
            return 1;
    }
    return 0;
}

int oneshot_check_output(const Options *o, char *err, size_t errlen)
{
    char what[96];
    int text = o->print || text_file(o, o->out) || (!o->out && !o->dump_ids && !o->dump_screen);
    if (o->out && !text_file(o, o->out)) {
        int w = o->w > 0 ? o->w : 640, h = o->h > 0 ? o->h : 480;
        snprintf(what, sizeof what, "--size %dx%d", w, h);
        if (pipeline_check_frame(w, h, o->samples > 0 ? o->samples : 1, 0, what, err, errlen))
            return -1;
    } else if (!text) {
        int w = o->w > 0 ? o->w : 640, h = o->h > 0 ? o->h : 480;     /* the dumps alone */
        snprintf(what, sizeof what, "--size %dx%d", w, h);
        if (pipeline_check_frame(w, h, 1, 0, what, err, errlen))
            return -1;
    }
    if (text) {
        DisplayMode mode = o->mode >= 0 ? (DisplayMode)o->mode : mode_from_locale();
        int cols, rows, pw, ph;
        print_size(o, &cols, &rows);
        mode_cell_pixels(mode, &pw, &ph);
        snprintf(what, sizeof what, "--size %dx%d in %s mode", cols, rows, mode_names[mode]);
        if (pipeline_check_frame(cols * pw, rows * ph, o->samples > 0 ? o->samples : TEXT_SAMPLES,
                                 (uint64_t)cols * rows, what, err, errlen))
            return -1;
    }
    return 0;
}

/* --problem K: the camera framed on the K-th problem the check found
 * (found), for the picture -o writes, else the text's, and the problem
 * put in focus. 0, or 1 after a message. */
static int focus_problem(const Options *o, Scene *s, Pipeline *p, const SceneCheck *found)
{
    uint32_t k = (uint32_t)o->problem - 1;
    if (k >= found->items.n) {
        if (found->items.n)
            safetext_line(stderr, "zview: --problem %d: the check found %u problem%s", o->problem,
                          found->items.n, found->items.n == 1 ? "" : "s");
        else
            safetext_line(stderr, "zview: --problem %d: the check found no problem to show", o->problem);
        return 1;
    }
    int obj = app_focus_object(s, &found->items, k);
    int w, h;
    float aspect = 1.0f;
    if (o->out && !text_file(o, o->out)) {
        w = o->w > 0 ? o->w : 640;
        h = o->h > 0 ? o->h : 480;
    } else {
        DisplayMode mode = o->mode >= 0 ? (DisplayMode)o->mode : mode_from_locale();
        int cols, rows, pw, ph;
        print_size(o, &cols, &rows);
        mode_cell_pixels(mode, &pw, &ph);
        w = cols * pw;
        h = rows * ph;
        aspect = mode_pixel_aspect(mode);
    }
    if (obj < 0 || app_focus_frame(s, &found->items, k, obj, w, h, aspect, o->threads, NULL)) {
        safetext_line(stderr, "zview: %s", obj < 0 ? "--problem: the problem is on no object" : "out of memory");
        return 1;
    }
    p->problems = 1;
    p->focus = (ProblemFocus){ &found->items, k, obj };
    return 0;
}

int oneshot_run(const Options *o, Scene *s)
{
    char err[512];
    SceneCheck found = { 0 };
    /* what the check finds, on the model (--problem: one by one too) */
    if ((o->problems || o->parts || o->problem) && !s->marks.set &&
        app_check_scene(s, o->threads, o->problem ? &found : NULL, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    const HsrAlgo *algo = hsr_find(o->algo ? o->algo : "zbuffer");
    Pipeline p;
    if (pipeline_init(&p, s, algo, o->threads)) {
        safetext_line(stderr, "zview: out of memory");
        scene_check_free(&found);
        return 1;
    }
    pipeline_apply_options(&p, o);     /* images: 1 sample unless asked, full resolution already */
    int rc = 0;
    if (o->problem && (rc = focus_problem(o, s, &p, &found)))
        goto out;
    Backdrops b = { .image_known = 0, .text_known = 0, .proto = -1 };
    if (o->turntable) {
        rc = turntable(o, s, &p, &b);
        goto out;
    }
    /* no output named: the text frame to stdout */
    Options text = *o;
    text.print = o->print || (!o->out && !o->dump_ids && !o->dump_screen);
    if (o->out || text.print)
        rc = one_frame(&text, &p, &b, o->out);
    if (rc)
        goto out;
    /* the dumps are of the last render: the image's, else the text's,
     * else one of their own at the image size */
    if ((o->dump_ids || o->dump_screen) && !o->out && !text.print && render_image(o, &p, 0)) {
        safetext_line(stderr, "zview: out of memory");
        rc = 1;
        goto out;
    }
    const char *why = frame_empty_reason(&p);     /* an empty picture says why */
    if (why)
        safetext_line(stderr, "zview: nothing drawn: %s", why);
    if (o->dump_ids && write_ids(o->dump_ids, &p.fb))
        rc = 1;
    if (o->dump_screen && dump_screen(&p.sp, o->dump_screen))
        rc = 1;
out:
    pipeline_free(&p);
    scene_check_free(&found);
    return rc;
}
