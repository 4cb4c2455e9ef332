/* test_load.c: loading for the viewer's O key: the progress a load
 * reports, warnings kept off stderr but counted, and the job that loads
 * a file on a thread of its own. */

#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../src/viewer/viewer_app.h"

/* A big OBJ (a strip of triangles) in a temporary file; its path. */
static void big_obj(char *path, size_t len, int tris)
{
    snprintf(path, len, "/tmp/zv-load-XXXXXX");
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    FILE *f = fdopen(fd, "w");
    cr_assert(f);
    for (int i = 0; i <= tris / 2; i++)
        fprintf(f, "v %d.000001 0.000001 0.000001\nv %d.000001 1.000001 0.000001\n", i, i);
    for (int i = 0; i < tris / 2; i++)
        fprintf(f, "f %d %d %d\nf %d %d %d\n", 2 * i + 1, 2 * i + 3, 2 * i + 2, 2 * i + 2, 2 * i + 3, 2 * i + 4);
    fprintf(f, "f 1 2 999999999\n");        /* one statement skipped: a warning */
    cr_assert_eq(fclose(f), 0);
}

Test(load, progress_and_quiet_warnings)
{
    char path[64], err[256];
    big_obj(path, sizeof path, 200000);
    struct stat st;
    cr_assert_eq(stat(path, &st), 0);
    MeshProgress prog = { 0, 0 };
    MeshLoadOpts lo = { .strict = 0, .quiet = 1, .progress = &prog };
    Mesh m;
    cr_assert_eq(mesh_load_ex(&m, path, &lo, err, sizeof err), 0, "%s", err);
    cr_expect_eq(prog.total, (uint64_t)st.st_size, "the total is the file's size");
    cr_expect_geq(prog.done, (uint64_t)2 << 20, "progress came every few MB (%llu of %llu)",
                  (unsigned long long)prog.done, (unsigned long long)prog.total);
    cr_expect_leq(prog.done, prog.total);
    cr_expect_eq(m.info.skipped, 1);
    cr_expect_eq(m.info.warnings, 1, "the skipped statement's warning, counted");
    cr_expect(strstr(m.info.first_warning, "1 statement skipped"), "%s", m.info.first_warning);
    mesh_free(&m);
    unlink(path);
}

/* Wait (bounded) for a job to finish. */
static int wait_job(LoadJob *j)
{
    for (int i = 0; i < 6000; i++) {        /* 30 s at least */
        if (loadjob_done(j))
            return 1;
        struct timespec ts = { 0, 5000000 };
        nanosleep(&ts, NULL);
    }
    return 0;
}

Test(load, a_job_loads_a_file_on_its_own_thread)
{
    Options o;
    cli_defaults(&o);
    char err[256], status[96];
    LoadJob *j = loadjob_start("assets/cube.obj", &o, err, sizeof err);
    cr_assert(j, "%s", err);
    loadjob_status(j, status, sizeof status);
    cr_expect(strstr(status, "cube.obj"), "%s", status);
    cr_assert(wait_job(j));
    Scene part;
    cr_assert_eq(loadjob_finish(j, &part, err, sizeof err), 0, "%s", err);
    cr_expect_eq(part.nobjs, 1);
    cr_expect_eq(part.nfaces, 6);
    scene_free(&part);
    /* a missing file: the loader's message */
    j = loadjob_start("assets/no-such.obj", &o, err, sizeof err);
    cr_assert(j, "%s", err);
    cr_assert(wait_job(j));
    cr_expect_eq(loadjob_finish(j, &part, err, sizeof err), -1);
    cr_expect(strstr(err, "no-such.obj") && strstr(err, "cannot open"), "%s", err);
    /* abandoned mid-load: the thread cleans up by itself */
    j = loadjob_start("assets/knot.obj", &o, err, sizeof err);
    cr_assert(j, "%s", err);
    loadjob_abandon(j);
}

/* The viewer's O loads as the command line does: --strict refuses a
 * file with a statement it cannot read (the message names file and
 * line), where the default shows the rest. */
Test(load, a_job_obeys_strict)
{
    char path[] = "/tmp/zv-strict-XXXXXX", err[256];
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    FILE *f = fdopen(fd, "w");
    cr_assert(f);
    fputs("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 9\n", f);
    cr_assert_eq(fclose(f), 0);
    Options o;
    cli_defaults(&o);
    Scene part;
    LoadJob *j = loadjob_start(path, &o, err, sizeof err);
    cr_assert(j, "%s", err);
    cr_assert(wait_job(j));
    cr_assert_eq(loadjob_finish(j, &part, err, sizeof err), 0, "lenient: %s", err);
    cr_expect_eq(part.nfaces, 1, "the good face is shown");
    scene_free(&part);
    o.strict = 1;
    j = loadjob_start(path, &o, err, sizeof err);
    cr_assert(j, "%s", err);
    cr_assert(wait_job(j));
    cr_assert_eq(loadjob_finish(j, &part, err, sizeof err), -1, "--strict: the file is refused");
    cr_expect(strstr(err, ":6: vertex index 9 out of range"), "%s", err);
    unlink(path);
}

/* --watch's reload (issue 28): a FIFO or a device in the model's place
 * is refused at once, looked at and never opened, where a reader would
 * wait for a writer; a regular file loads. And the loader itself, told
 * regular_only, opens without waiting and refuses a FIFO put in the
 * file's place after that look. alarm(): were anything opened to wait,
 * the test's process ends. */
Test(load, a_reload_takes_a_regular_file_only)
{
    alarm(60);
    char dir[] = "/tmp/zv-reload-XXXXXX", fifo[64], dev[64], err[256];
    cr_assert(mkdtemp(dir));
    snprintf(fifo, sizeof fifo, "%s/m.obj", dir);
    snprintf(dev, sizeof dev, "%s/d.obj", dir);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    cr_assert_eq(symlink("/dev/zero", dev), 0);
    Options o;
    cli_defaults(&o);
    cr_assert_null(loadjob_reload(fifo, &o, err, sizeof err));
    cr_expect_str_eq(err, "not a regular file (a FIFO)");
    cr_assert_null(loadjob_reload(dev, &o, err, sizeof err));
    cr_expect_str_eq(err, "not a regular file (a character device)");
    cr_assert_null(loadjob_reload(dir, &o, err, sizeof err));
    cr_expect_str_eq(err, "not a regular file (a folder)");
    cr_assert_null(loadjob_reload("assets/no-such.obj", &o, err, sizeof err));
    cr_expect(strstr(err, "cannot open"), "%s", err);
    /* the O key's job still reads a FIFO (its writer waited for in poll) */
    LoadJob *j = loadjob_start(fifo, &o, err, sizeof err);
    cr_assert(j, "%s", err);
    loadjob_abandon(j);
    j = loadjob_reload("assets/cube.obj", &o, err, sizeof err);
    cr_assert(j, "%s", err);
    cr_assert(wait_job(j));
    Scene part;
    cr_assert_eq(loadjob_finish(j, &part, err, sizeof err), 0, "%s", err);
    cr_expect_eq(part.nfaces, 6);
    scene_free(&part);
    MeshLoadOpts lo = { .strict = 0, .quiet = 1, .regular_only = 1 };
    Mesh m;
    cr_assert_eq(mesh_load_ex(&m, fifo, &lo, err, sizeof err), -1);
    cr_expect(strstr(err, "not a regular file (a FIFO)"), "%s", err);
    unlink(fifo);
    unlink(dev);
    rmdir(dir);
}
