/* main.c: parse options, load the scene, then one of: info, benchmark,
 * one-shot output, or the interactive viewer. */

#include <locale.h>
#include <malloc.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "app.h"

int main(int argc, char **argv)
{
    char err[512];
    Options o;
    setlocale(LC_ALL, "");
    /* Big buffers (meshes, screen polygons, build scratch) come from mmap
     * and go back to the system when freed: a fixed threshold keeps glibc
     * from raising it after the first free and keeping freed scratch. */
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    if (cli_parse(argc, argv, &o, err, sizeof err)) {
        fprintf(stderr, "zview: %s\n", err);
        return 2;
    }
    if (o.help) {
        cli_usage(stdout);
        return 0;
    }
    if (o.version) {
        printf("zview %s\n", ZV_VERSION);
        return 0;
    }
    if (o.formats) {
        mesh_formats_print(stdout);
        return 0;
    }
    if (o.bench || o.bench_tty)
        return app_bench(&o, NULL);   /* loads each model on its own */
    Scene scene;
    if (app_load_scene(&o, &scene, err, sizeof err)) {
        fprintf(stderr, "zview: %s\n", err);
        return 1;
    }
    int rc;
    if (o.info)
        rc = app_info(&o, &scene);
    else if (o.print || o.out || o.dump_ids || o.dump_screen || !isatty(STDOUT_FILENO))
        rc = app_oneshot(&o, &scene);
    else
        rc = app_viewer(&o, &scene);
    scene_free(&scene);
    return rc;
}
