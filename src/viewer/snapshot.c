/* snapshot.c: the viewer's snapshot key. The picture on screen is written
 * twice: as the text --print gives (the same bytes: the cells on screen
 * in the colours in use), and as a PNG of 8 x 16 pixels a cell (the text
 * picture's shape, cells being twice as tall as wide), rendered with 2 x 2
 * samples a pixel, on the background the picture was kept visible on
 * (--bg, the terminal's, or black). Names are zview-<model>-NNN.png / .txt with the first
 * number for which neither exists, claimed with O_EXCL so nothing is ever
 * overwritten, in the current directory or, when files cannot be made
 * there, next to the model. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tty.h"
#include "viewer_app.h"

#define SNAP_CELL_W   8         /* PNG pixels per cell */
#define SNAP_CELL_H   16
#define SNAP_MAX_SIDE 4096
#define SNAP_SAMPLES  4
#define SNAP_MAX_N    999

/* The model's name for the files: the first file's, less folder and
 * extension. */
static void model_stem(const App *a, char *buf, size_t len)
{
    const char *path = a->opt->nfiles ? a->opt->files[0] : "demo";
    if (strcmp(path, "-") == 0)
        path = "stdin";         /* a model from standard input */
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    int n = dot && dot != base ? (int)(dot - base) : (int)strlen(base);
    snprintf(buf, len, "%.*s", n, base);
}

/* The folder of the model (the demo's when no file was given). */
static void model_dir(const App *a, char *buf, size_t len)
{
    const char *path = a->opt->nfiles ? a->opt->files[0] : app_demo_path();
    if (strcmp(path, "-") == 0)
        path = "./-";           /* standard input: the current folder */
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(buf, len, ".");
    else if (slash == path)
        snprintf(buf, len, "/");
    else
        snprintf(buf, len, "%.*s", (int)(slash - path), path);
}

/* Claim the next free pair of names in dir: both files made empty with
 * O_EXCL. Returns the text file's descriptor (the PNG's is closed) with
 * the paths filled, or -1 with errno (EEXIST: all numbers taken). */
static int claim(const char *dir, const char *stem, char *png, char *txt, size_t len)
{
    const char *sep = strcmp(dir, ".") ? "/" : "";
    const char *d = strcmp(dir, ".") ? dir : "";
    for (int n = 1; n <= SNAP_MAX_N; n++) {
        snprintf(png, len, "%s%szview-%s-%03d.png", d, sep, stem, n);
        snprintf(txt, len, "%s%szview-%s-%03d.txt", d, sep, stem, n);
        int fp = open(png, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fp < 0) {
            if (errno == EEXIST)
                continue;
            return -1;
        }
        close(fp);
        int ft = open(txt, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (ft >= 0)
            return ft;
        int e = errno;
        unlink(png);
        if (e != EEXIST) {
            errno = e;
            return -1;
        }
    }
    errno = EEXIST;
    return -1;
}

/* The text frame into fd (closed). Returns 0, or -1 with errno. */
static int write_text(int fd, const CellGrid *g, ColourDepth depth)
{
    size_t len;
    char *s = print_cells_to_string(g, depth, &len);
    FILE *f = fdopen(fd, "w");
    if (!s || !f) {
        int e = s ? errno : ENOMEM;
        free(s);
        if (f)
            fclose(f);
        else
            close(fd);
        errno = e;
        return -1;
    }
    Out o;
    out_init(&o, f, NULL);
    out_write(&o, s, len);
    out_close(&o);
    free(s);
    if (o.err) {
        errno = o.err;
        return -1;
    }
    return 0;
}

/* The PNG's size: SNAP_CELL_W x SNAP_CELL_H a cell, at most
 * SNAP_MAX_SIDE on a side (the shape kept). */
static void png_size(const CellGrid *g, int *w, int *h)
{
    double W = (double)g->cols * SNAP_CELL_W, H = (double)g->rows * SNAP_CELL_H;
    double k = W > SNAP_MAX_SIDE || H > SNAP_MAX_SIDE ? SNAP_MAX_SIDE / (W > H ? W : H) : 1;
    *w = (int)(W * k) > 0 ? (int)(W * k) : 1;
    *h = (int)(H * k) > 0 ? (int)(H * k) : 1;
}

/* The status bar's note (a long path is cut: the bar shows what fits). */
static void note(App *a, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void note(App *a, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(a->note, sizeof a->note, fmt, ap);
    va_end(ap);
}

Reaction viewer_snapshot(App *a)
{
    const CellGrid *g = &a->p.cells;
    if (g->cols <= 0 || g->rows <= 0) {
        note(a, "snapshot: no picture yet");
        return RE_DRAW;
    }
    if (a->s->nfaces == 0 && a->s->nprims == 0) {
        note(a, "snapshot: the scene is empty, nothing to save");
        return RE_DRAW;
    }
    char stem[128], dir[1024], png[1200], txt[1200];
    model_stem(a, stem, sizeof stem);
    model_dir(a, dir, sizeof dir);
    int fd = claim(".", stem, png, txt, sizeof png);
    if (fd < 0 && errno != EEXIST)
        fd = claim(dir, stem, png, txt, sizeof png);
    if (fd < 0) {
        note(a, "snapshot failed: %s: %s", dir, strerror(errno));
        return RE_DRAW;
    }
    if (write_text(fd, g, term_colour())) {
        note(a, "snapshot failed: %s: %s", txt, strerror(errno));
        unlink(txt);
        unlink(png);
        return RE_DRAW;
    }
    int w, h, samples = a->p.samples;
    png_size(g, &w, &h);
    a->p.samples = SNAP_SAMPLES;
    char err[512];
    int bad = pipeline_render(&a->p, w, h, 1.0f, a->cull, 1);
    a->p.samples = samples;
    if (!bad)
        backdrop_paint(&a->p.img, &a->p.bd);    /* the background the screen shows (or is taken to) */
    if (bad || write_png(png, &a->p.img, err, sizeof err)) {
        note(a, "snapshot failed: %s", bad ? "out of memory" : err);
        unlink(txt);
        unlink(png);
        return RE_RENDER;
    }
    /* the name first: a narrow status bar cuts the note's end */
    const char *slash = strrchr(png, '/');
    if (slash)
        note(a, "wrote %s %dx%d, .txt in %.*s", slash + 1, w, h, (int)(slash - png), png);
    else
        note(a, "wrote %s %dx%d, .txt", png, w, h);
    return RE_RENDER;     /* the pipeline holds the PNG's render now */
}
