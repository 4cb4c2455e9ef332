/* main.c: parse options, load the scene, then one of: info, benchmark,
 * one-shot output, or the interactive viewer. */

#define _DEFAULT_SOURCE         /* mallopt */

#include <errno.h>
#include <fcntl.h>
#include <locale.h>
#include <malloc.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "oneshot.h"
#include "safetext.h"
#include "simd.h"
#include "viewer.h"

/* A standard descriptor the shell left closed (`>&-`) would be taken by
 * the next open(): the model file, or the PNG, would become "standard
 * output". Hold each with /dev/null instead, opened so that writes to
 * standard output still fail (read-only: EBADF, as a closed one would)
 * and the error is reported. */
static void hold_closed_std_fds(void)
{
    static const int modes[3] = { O_RDONLY, O_RDONLY, O_WRONLY };
    for (int fd = 0; fd <= 2; fd++)
        if (fcntl(fd, F_GETFD) == -1 && errno == EBADF) {
            int got = open("/dev/null", modes[fd]);
            if (got >= 0 && got != fd) {
                dup2(got, fd);
                close(got);
            }
        }
}

/* Flush standard output; on failure say why (exit status 1). errno is
 * cleared first: a text longer than stdio's buffer fails in the middle,
 * and the errno of that write is the reason the flush then reports. */
static int finish_stdout(void)
{
    Out out;
    out_init(&out, stdout, "standard output");
    int e = errno;
    if (out_flush(&out) == 0)
        return 0;
    if (out.err == EIO && e)
        out.err = e;
    safetext_line(stderr, "zview: standard output: %s", out_error(&out));
    return 1;
}

int main(int argc, char **argv)
{
    char err[512];
    Options o;
    hold_closed_std_fds();
    setlocale(LC_ALL, "");
    /* Big buffers (meshes, screen polygons, build scratch) come from mmap
     * and go back to the system when freed: a fixed threshold keeps glibc
     * from raising it after the first free and keeping freed scratch. */
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    /* a ZV_SIMD the frames cannot honour is said once, before anything
     * (the viewer's screen) covers standard error */
    simd_warn(stderr);
    if (cli_parse(argc, argv, &o, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 2;
    }
    if (o.help) {
        errno = 0;
        cli_usage(stdout);
        return finish_stdout();
    }
    if (o.version) {
        printf("zview %s\n", ZV_VERSION);
        return finish_stdout();
    }
    /* Sandboxed loads are forked from a server started now, while zview
     * has one thread: a fork copies only the thread that calls it, and a
     * lock another held would stay held in the child (server.c) */
    if (!o.no_sandbox && sandbox_available())
        sandbox_server_start(&o.sandbox);
    int rc;
    if (o.bench || o.bench_tty) {
        /* each model loaded on its own; --bench-tty drives the viewer */
        rc = o.bench_tty ? viewer_bench_tty(&o) : oneshot_bench(&o, NULL);
        return rc ? rc : finish_stdout();
    }
    if (o.formats) {
        mesh_formats_print(stdout);
        return finish_stdout();
    }
    if (o.preview) {
        /* a file manager's pane: the picture and the verdict, or why not */
        rc = oneshot_preview(&o);
        return rc ? rc : finish_stdout();
    }
    if (o.repair) {
        /* IN loaded, repaired, written to OUT, OUT read back and checked */
        rc = oneshot_repair(&o);
        return rc == 1 || rc == 2 ? rc : finish_stdout() ? 1 : rc;
    }
    if (o.diff) {
        /* the two files loaded, checked and measured; the viewer on a
         * terminal, else the picture asked for and the report */
        int view = !o.quiet && !o.json && !o.print && !o.out && isatty(STDOUT_FILENO);
        DiffSet ds;
        if (diff_load(&ds, &o, view || o.print || o.out, err, sizeof err)) {
            safetext_line(stderr, "zview: %s", err);
            diff_set_free(&ds);
            return 1;
        }
        rc = view ? viewer_run_diff(&o, &ds) : oneshot_diff(&o, &ds);
        diff_set_free(&ds);
        return rc == 1 ? rc : finish_stdout() ? 1 : rc;
    }
    if (o.nmeasure) {
        /* the model loaded, the points' figures printed */
        rc = oneshot_measure(&o);
        return rc ? rc : finish_stdout();
    }
    if (o.check) {
        /* each file loaded and checked on its own; the picture, if asked, inside */
        rc = oneshot_check(&o);
        return rc == 1 ? rc : finish_stdout() ? 1 : rc;
    }
    Scene scene;
    if (o.sketch && o.nfiles == 0) {
        /* nothing to load: the canvas is the scene (sketchui.c); this
         * empty one holds the light it is drawn in */
        if (scene_build(&scene, NULL, 0, err, sizeof err)) {
            safetext_line(stderr, "zview: %s", err);
            return 1;
        }
        light_set(&scene.light, o.light[0], o.light[1], o.ambient);
        rc = viewer_run(&o, &scene);
        scene_free(&scene);
        return rc ? rc : finish_stdout();
    }
    int oneshot = !o.info && (o.print || o.out || o.dump_ids || o.dump_screen ||
                              (!isatty(STDOUT_FILENO) && !o.print_view && !o.sketch));
    if (oneshot && oneshot_check_output(&o, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    if (oneshot)
        o.tex_skip = o.no_textures;
    else if (!o.info)
        o.tex_defer = TEX_DEFER_SIDE;
    if (!oneshot && !o.info && viewer_loads_first(&o)) {
        /* a big file: the viewer starts at once and shows what is
         * parsed so far (firstload.c); it starts on an empty scene */
        if (scene_build(&scene, NULL, 0, err, sizeof err)) {
            safetext_line(stderr, "zview: %s", err);
            return 1;
        }
        light_set(&scene.light, o.light[0], o.light[1], o.ambient);
        rc = viewer_run_loading(&o, &scene);
        scene_free(&scene);
        return rc ? rc : finish_stdout();
    }
    FirstView fv;
    if (app_load_scene_ex(&o, &scene, &fv, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    if (o.info)
        rc = oneshot_info(&o, &scene, &fv);
    else if (oneshot)
        rc = oneshot_run(&o, &scene);
    else
        rc = viewer_run(&o, &scene);
    scene_free(&scene);
    /* every path checks its own writes; this catches any left in the buffer */
    return rc ? rc : finish_stdout();
}
