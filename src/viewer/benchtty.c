/* benchtty.c: --bench-tty, the bytes curses sends a terminal per frame
 * of a scripted turn, and the time each frame takes: the viewer's own
 * render and status bar, drawn into a temporary file that stands in for
 * the terminal. */

#define _DEFAULT_SOURCE         /* tmpfile, fileno */

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "clock.h"
#include "safetext.h"
#include "tty.h"
#include "viewer_app.h"

static int cmp_long(const void *x, const void *y)
{
    long a = *(const long *)x, b = *(const long *)y;
    return a < b ? -1 : a > b;
}

static int cmp_dbl(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}

static long file_bytes(FILE *f)
{
    struct stat st;
    fflush(f);
    return fstat(fileno(f), &st) == 0 ? (long)st.st_size : -1;
}

#define TTY_FRAMES 72   /* a whole turn at 5 degrees a frame */

/* Curses writes into a temporary file standing in for the terminal; the
 * file's growth after each update is what a terminal would receive. */
int viewer_bench_tty(const Options *o)
{
    char err[512];
    Scene s;
    if (app_load_scene(o, &s, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    int cols = o->w > 0 ? o->w : 160, rows = o->h > 0 ? o->h : 48;
    Options opt = *o;
    if (opt.mode < 0)
        opt.mode = MODE_HALF;
    ColourDepth colour = o->colour >= 0 ? (ColourDepth)o->colour : COLOUR_256;
    const char *termname = "xterm-256color";    /* 24-bit colour needs no other entry */
    int rc = 1;
    App a;
    FILE *out = tmpfile(), *in = fopen("/dev/null", "r");
    if (!out || !in || viewer_app_init(&a, &opt, &s, 0)) {
        safetext_line(stderr, "zview: cannot set up the benchmark");
        goto done;
    }
    TermConfig cfg = { .out = out, .in = in, .termname = termname, .colour = colour };
    if (term_open(&cfg, err, sizeof err)) {
        safetext_line(stderr, "zview: %s: %s", termname, err);
        viewer_app_free(&a);
        goto done;
    }
    term_set_size(cols, rows + 1);
    Backdrop bd = pipeline_text_backdrop(o, NULL);      /* as the viewer's, no terminal to ask */
    pipeline_set_backdrop(&a.p, &bd);
    long bytes[TTY_FRAMES + 1];
    double render_ms[TTY_FRAMES + 1], out_ms[TTY_FRAMES + 1];
    long before = file_bytes(out);
    char bar[512];
    for (int k = 0; k <= TTY_FRAMES; k++) {
        if (k > 0)
            s.cam.yaw += deg2rad(5);
        double t0 = now_ms();
        if (viewer_render(&a, cols, rows)) {
            term_restore();
            safetext_line(stderr, "zview: out of memory");
            viewer_app_free(&a);
            goto done;
        }
        double t1 = now_ms();
        term_draw_cells(&a.p.cells, 0);
        viewer_status_text(&a, bar, sizeof bar, k ? render_ms[k - 1] + out_ms[k - 1] : 0, o->fps, cols);
        term_draw_bar(rows, bar);
        if (term_update(0)) {
            int e = errno;
            term_restore();
            safetext_line(stderr, "zview: the benchmark's file: %s", strerror(e));
            viewer_app_free(&a);
            goto done;
        }
        long now = file_bytes(out);
        out_ms[k] = now_ms() - t1;
        render_ms[k] = t1 - t0;
        bytes[k] = now - before;
        before = now;
    }
    ColourDepth used = term_colour();   /* before the session it belongs to ends */
    term_restore();
    /* frame 0 paints the whole screen; the turn is frames 1.. */
    long sum = 0, first = bytes[0];
    double frame[TTY_FRAMES];
    for (int k = 1; k <= TTY_FRAMES; k++) {
        sum += bytes[k];
        frame[k - 1] = render_ms[k] + out_ms[k];
    }
    double rmed[TTY_FRAMES], omed[TTY_FRAMES];
    memcpy(rmed, render_ms + 1, sizeof rmed);
    memcpy(omed, out_ms + 1, sizeof omed);
    qsort(bytes + 1, TTY_FRAMES, sizeof *bytes, cmp_long);
    qsort(frame, TTY_FRAMES, sizeof *frame, cmp_dbl);
    qsort(rmed, TTY_FRAMES, sizeof *rmed, cmp_dbl);
    qsort(omed, TTY_FRAMES, sizeof *omed, cmp_dbl);
    Out rep;
    out_init(&rep, stdout, "standard output");
    out_line(&rep, "bench-tty: %s, %dx%d cells + status line, %s, %s colour (%s), algo %s, %d thread%s",
           a.name, cols, rows, mode_names[a.mode], colour_name(used), termname, a.p.algo->name,
           a.p.threads, a.p.threads == 1 ? "" : "s");
    out_printf(&rep, "turn of %d frames at 5 degrees a frame; first frame (full paint) %ld bytes\n",
           TTY_FRAMES, first);
    out_printf(&rep, "bytes per frame: median %ld, mean %ld, max %ld\n", bytes[1 + TTY_FRAMES / 2],
           sum / TTY_FRAMES, bytes[TTY_FRAMES]);
    out_printf(&rep, "frame time: median %.2f ms (render %.2f ms + terminal output %.2f ms), max %.2f ms\n",
           frame[TTY_FRAMES / 2], rmed[TTY_FRAMES / 2], omed[TTY_FRAMES / 2],
           frame[TTY_FRAMES - 1]);
    if (out_flush(&rep)) {
        safetext_line(stderr, "zview: standard output: %s", out_error(&rep));
        viewer_app_free(&a);
        goto done;
    }
    viewer_app_free(&a);
    rc = 0;
done:
    if (out)
        fclose(out);
    if (in)
        fclose(in);
    scene_free(&s);
    return rc;
}
