/* Tests of the viewer's logic without a terminal: the keys' effects on
 * the view, the command line shown for a view, the frame-file patterns
 * of --turntable, and loads in the background (O) that wait or are
 * refused. */

#define _DEFAULT_SOURCE          /* mkdtemp */
#include <criterion/criterion.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../src/viewer/viewer_app.h"
#include "clock.h"
#include "tty.h"

static Options opt;
static Scene scene;
static App app;

static void setup(void)
{
    char err[512];
    const char *argv[] = { "zview", "assets/knot.obj", NULL };
    cr_assert_eq(cli_parse(2, (char **)argv, &opt, err, sizeof err), 0, "%s", err);
    cr_assert_eq(app_load_scene(&opt, &scene, err, sizeof err), 0, "%s", err);
    memset(&app, 0, sizeof app);
    app.opt = &opt;
    app.s = &scene;
    app.sel = -1;
    app.mode = MODE_HALF;
    app.utf8 = 1;
    cr_assert_eq(pipeline_init(&app.p, &scene, hsr_find("zbuffer"), 1), 0);
    app.p.samples = TEXT_SAMPLES;
    pipeline_apply_options(&app.p, &opt);
}

static void teardown(void)
{
    pipeline_free(&app.p);
    scene_free(&scene);
}

TestSuite(viewer, .init = setup, .fini = teardown);

Test(viewer, number_keys_are_the_named_views)
{
    /* the order the README and the man page give */
    static const char *const doc[7] = { "front", "back", "left", "right", "top", "bottom", "iso" };
    for (int i = 0; i < 7; i++) {
        float y, p;
        cr_assert_str_eq(view_name(i), doc[i]);
        cr_assert_eq(view_from_name(doc[i], &y, &p), 0);
        cr_expect_eq(viewer_key(&app, '1' + i), RE_RENDER);
        cr_expect_float_eq(scene.cam.yaw, remainderf(deg2rad(y), 2 * ZV_PI), 1e-6, "key %d yaw", i + 1);
        cr_expect_float_eq(scene.cam.pitch, deg2rad(p), 1e-6, "key %d pitch", i + 1);
        /* fitted from the view: the command line needs no --fit-from */
        cr_expect_eq(scene.cam.fit_yaw, scene.cam.yaw);
        cr_expect(strstr(app.note, doc[i]) != NULL, "key %d: note '%s'", i + 1, app.note);
    }
    FirstView fv;
    app_first_view(&scene, 1, &fv);
    viewer_key(&app, '8');
    cr_expect_float_eq(scene.cam.yaw, remainderf(deg2rad(fv.yaw), 2 * ZV_PI), 1e-6);
    cr_expect_float_eq(scene.cam.pitch, deg2rad(fv.pitch), 1e-6);
}

Test(viewer, bracket_keys_turn_the_light)
{
    float y0 = scene.light.yaw, p0 = scene.light.pitch;
    viewer_key(&app, ']');
    cr_expect_float_eq(scene.light.yaw, y0 + 15, 1e-4);
    viewer_key(&app, '[');
    viewer_key(&app, '[');
    cr_expect_float_eq(scene.light.yaw, y0 - 15, 1e-4);
    viewer_key(&app, '{');
    cr_expect_float_eq(scene.light.pitch, p0 + 15, 1e-4);
    for (int i = 0; i < 12; i++)
        viewer_key(&app, '{');
    cr_expect_float_eq(scene.light.pitch, 90, 1e-4, "the light stops straight above");
    for (int i = 0; i < 30; i++)
        viewer_key(&app, ']');
    cr_expect(scene.light.yaw > -180 && scene.light.yaw <= 180, "yaw wraps: %g", scene.light.yaw);
    cr_expect_float_eq(scene.light.ambient, LIGHT_AMBIENT, 1e-6, "the ambient share stays");
}

Test(viewer, e_toggles_outlines_and_S_cycles_samples)
{
    viewer_key(&app, 'e');
    cr_expect(app.p.edges);
    viewer_key(&app, 'e');
    cr_expect(!app.p.edges);
    int want[] = { 9, 16, 1, 4 };
    for (int i = 0; i < 4; i++) {
        viewer_key(&app, 'S');
        cr_expect_eq(app.p.samples, want[i]);
    }
}

Test(viewer, v_cycles_every_shading)
{
    int seen = 0;
    for (int i = 0; i < SHADE_COUNT; i++) {
        seen |= 1 << app.p.shade;
        viewer_key(&app, 'v');
    }
    cr_expect_eq(seen, (1 << SHADE_COUNT) - 1, "smooth included");
}

/* The command shown wraps at the width with " \" and, joined, is the
 * view's command line. */
Test(viewer, command_lines_wrap_and_join_back)
{
    viewer_key(&app, '3');
    viewer_key(&app, 'e');
    viewer_key(&app, ']');
    char want[CMD_MAX];
    cr_assert_eq(viewer_view_command(&app, want, sizeof want), 0);
    cr_expect(strstr(want, "--edges") && strstr(want, "--light -19,37"), "%s", want);
    for (int cols = 24; cols <= 120; cols += 16) {
        char buf[2 * CMD_MAX];
        const char *lines[HELP_LINES_MAX];
        int n = viewer_command_layout(&app, cols, buf, sizeof buf, lines, HELP_LINES_MAX);
        cr_assert_gt(n, 1);
        char joined[CMD_MAX] = "";
        for (int i = 1; i < n; i++) {
            size_t len = strlen(lines[i]);
            cr_expect_leq((int)len, cols - 4, "line %d wider than the box at %d columns", i, cols);
            int more = i + 1 < n;
            cr_expect_eq(more, len >= 2 && !strcmp(lines[i] + len - 2, " \\"), "continuation marks at %d columns", cols);
            strncat(joined, lines[i], more ? len - 2 : len);
            if (more)
                strcat(joined, " ");
        }
        cr_expect_str_eq(joined, want, "at %d columns", cols);
    }
}

Test(viewer, a_key_closes_the_command_line_and_does_nothing_else)
{
    viewer_key(&app, 'C');
    cr_expect(app.cmd);
    float yaw = scene.cam.yaw;
    cr_expect_eq(viewer_key(&app, 'l'), RE_DRAW);
    cr_expect(!app.cmd);
    cr_expect_eq(scene.cam.yaw, yaw);
    cr_expect_neq(viewer_key(&app, 'q') & RE_QUIT, 0, "then q quits");
}

Test(viewer, frame_patterns)
{
    cr_expect_eq(frame_pattern_check("out-%03d.png"), 1);
    cr_expect_eq(frame_pattern_check("%d.txt"), 1);
    cr_expect_eq(frame_pattern_check("a%%b-%-4i.ppm"), 1);
    cr_expect_eq(frame_pattern_check("%x.png"), 1);
    cr_expect_eq(frame_pattern_check("out.png"), 0);
    cr_expect_eq(frame_pattern_check("100%%.png"), 0);
    cr_expect_eq(frame_pattern_check("%d-%d.png"), 2);
    cr_expect_eq(frame_pattern_check("%s.png"), -1);
    cr_expect_eq(frame_pattern_check("%ld.png"), -1, "a length modifier: we pass an int");
    cr_expect_eq(frame_pattern_check("%n.png"), -1);
    cr_expect_eq(frame_pattern_check("%1$d.png"), -1);
    cr_expect_eq(frame_pattern_check("end%"), -1);
}

/* ==== Loads in the background ==== */

/* A FIFO in a fresh folder; *dir_out to remove after. */
static void make_fifo(char *dir_out, size_t dlen, char *fifo_out, size_t flen)
{
    snprintf(dir_out, dlen, "/tmp/zv-fifo-XXXXXX");
    cr_assert_not_null(mkdtemp(dir_out));
    snprintf(fifo_out, flen, "%s/pipe.obj", dir_out);
    cr_assert_eq(mkfifo(fifo_out, 0600), 0);
}

/* Does this process (the load job is a thread of it) hold the FIFO
 * open? Read from /proc/self/fd: a probe that opened the FIFO to write
 * would be a writer, and its close the end of the stream the job waits
 * for (the job would then go on, or not, as the threads happen to run).
 * Waits 10 s at least for `want` (a loaded machine may be slow to run the job). */
static int fifo_read_by_someone(const char *fifo, int want)
{
    for (int k = 0; k < 1000; k++) {
        int has = 0;
        DIR *d = opendir("/proc/self/fd");
        cr_assert_not_null(d, "/proc/self/fd: %s", strerror(errno));
        struct dirent *e;
        while (!has && (e = readdir(d))) {
            char link[300], target[256];
            snprintf(link, sizeof link, "/proc/self/fd/%s", e->d_name);
            ssize_t n = readlink(link, target, sizeof target - 1);
            if (n > 0) {
                target[n] = 0;
                has = strcmp(target, fifo) == 0;
            }
        }
        closedir(d);
        if (has == want)
            return has;
        struct timespec ts = { 0, 10 * 1000 * 1000 };
        nanosleep(&ts, NULL);
    }
    return !want;
}

Test(viewer, esc_cancels_a_load_waiting_on_a_fifo_then_quits)
{
    char dir[64], fifo[128], err[256];
    make_fifo(dir, sizeof dir, fifo, sizeof fifo);
    app.job = loadjob_start(fifo, &opt, err, sizeof err);
    cr_assert_not_null(app.job, "%s", err);
    cr_expect(fifo_read_by_someone(fifo, 1), "the load waits on the FIFO (not in open)");
    cr_expect(!loadjob_done(app.job), "no writer: still waiting");
    char st[128];
    loadjob_status(app.job, st, sizeof st);
    cr_expect(strstr(st, "waiting for a writer to pipe.obj"), "status: %s", st);
    cr_expect(strstr(st, "Esc cancels"), "status: %s", st);
    Reaction r = viewer_key(&app, TK_ESC);
    cr_expect_eq(r & RE_QUIT, 0, "Esc with a load going cancels it, it does not quit");
    cr_expect_null(app.job);
    cr_expect(strstr(app.note, "cancelled loading pipe.obj"), "note: %s", app.note);
    cr_expect(!fifo_read_by_someone(fifo, 0), "the cancelled load let go of the FIFO");
    cr_expect_neq(viewer_key(&app, TK_ESC) & RE_QUIT, 0, "Esc again quits");
    unlink(fifo);
    rmdir(dir);
}

Test(viewer, a_fifo_loads_once_its_writer_comes, .timeout = 30)
{
    char dir[64], fifo[128], err[256];
    make_fifo(dir, sizeof dir, fifo, sizeof fifo);
    LoadJob *j = loadjob_start(fifo, &opt, err, sizeof err);
    cr_assert_not_null(j, "%s", err);
    int fd = open(fifo, O_WRONLY);     /* waits for the job's reader */
    cr_assert(fd >= 0);
    static const char obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
    cr_assert_eq(write(fd, obj, sizeof obj - 1), (ssize_t)(sizeof obj - 1));
    close(fd);
    for (int k = 0; k < 2000 && !loadjob_done(j); k++) {      /* 20 s at least */
        struct timespec ts = { 0, 10 * 1000 * 1000 };
        nanosleep(&ts, NULL);
    }
    cr_assert(loadjob_done(j), "the load ends with its writer");
    Scene part;
    cr_assert_eq(loadjob_finish(j, &part, err, sizeof err), 0, "%s", err);
    cr_expect_eq(part.nfaces, 2);
    scene_free(&part);
    unlink(fifo);
    rmdir(dir);
}

Test(viewer, devices_and_standard_input_are_refused_at_once)
{
    char err[256];
    static const char *const devs[] = { "/dev/urandom", "/dev/zero", "/dev/null" };
    for (int i = 0; i < 3; i++) {
        err[0] = 0;
        LoadJob *j = loadjob_start(devs[i], &opt, err, sizeof err);
        cr_expect_null(j, "%s is loaded", devs[i]);
        if (j)
            loadjob_abandon(j);
        cr_expect(strstr(err, "not a file (a character device)"), "%s: %s", devs[i], err);
    }
    err[0] = 0;
    cr_expect_null(loadjob_start("-", &opt, err, sizeof err));
    cr_expect(strstr(err, "standard input"), "-: %s", err);
}

/* ==== The prompt's scrolling ==== */

/* A line longer than the screen shows its end with the cursor on it:
 * the fewest characters dropped from the left that bring the cursor to
 * column cols - 2 or before (brute force: each count tried in turn, the
 * columns counted by hand, an escape shown as the four columns of
 * \x1b), every width from one column to past the line. */
Test(viewer, a_long_prompt_drops_the_fewest_characters_that_show_the_cursor)
{
    static const char *lines[] = { " Open: models/teapot.obj", " Open: a\x1b" "b/c.obj" };
    for (int l = 0; l < 2; l++) {
        const char *bar = lines[l];
        /* each character's columns */
        int n = 0, w[64];
        for (const char *p = bar; *p; p++)
            w[n++] = *p == 0x1b ? 4 : 1;
        int total = 0;
        for (int i = 0; i < n; i++)
            total += w[i];
        for (int cols = 1; cols <= total + 4; cols++) {
            int drop = 0, at = total;
            while (drop < n && at > cols - 2)
                at -= w[drop++];
            int got = total;
            const char *show = viewer_prompt_scroll(bar, cols, &got);
            cr_assert_eq(show - bar, drop, "line %d, %d columns: %td dropped, not %d", l, cols, show - bar, drop);
            cr_assert_eq(got, at, "line %d, %d columns: the cursor at %d, not %d", l, cols, got, at);
        }
    }
}

/* ==== The help overlay's scrolling ==== */

Test(viewer, page_keys_home_and_end_scroll_a_help_that_does_not_fit)
{
    const char *lines[HELP_LINES_MAX];
    viewer_key(&app, '?');
    cr_assert(app.help);
    viewer_help_layout(&app, 40, 12, lines);       /* a small window: the help does not fit */
    cr_assert_gt(app.help_hidden, 0);
    cr_assert_gt(app.help_page, 2);
    cr_expect_eq(viewer_key(&app, TK_PGDN), RE_DRAW);
    cr_expect_eq(app.help_top, app.help_page - 1, "a page down, one row kept");
    viewer_key(&app, TK_END);
    cr_expect_eq(app.help_top, app.help_hidden, "End: the last rows");
    viewer_key(&app, TK_PGDN);
    cr_expect_eq(app.help_top, app.help_hidden, "no further than the end");
    viewer_key(&app, TK_PGUP);
    cr_expect_eq(app.help_top, app.help_hidden - (app.help_page - 1));
    viewer_key(&app, TK_HOME);
    cr_expect_eq(app.help_top, 0, "Home: the first rows");
    cr_expect(app.help, "the scroll keys keep the help open");
    viewer_key(&app, TK_INS);
    cr_expect(!app.help, "another key closes it");
}

Test(viewer, the_editing_keys_do_not_quit)
{
    static const int keys[] = { TK_HOME, TK_END, TK_INS, TK_PGUP, TK_PGDN };
    for (int i = 0; i < 5; i++)
        cr_expect_eq(viewer_key(&app, keys[i]) & RE_QUIT, 0, "key %d", i);
}

/* The modes stack in one order: the open prompt over E's question over
 * the help over the command line over sketch mode over the viewer; the
 * one on top takes the key, whatever else is on. */
Test(viewer, the_mode_on_top_takes_the_key)
{
    cr_expect_eq(viewer_mode(&app), VM_VIEW);
    app.cmd = 1;
    cr_expect_eq(viewer_mode(&app), VM_COMMAND);
    app.help = 1;
    cr_expect_eq(viewer_mode(&app), VM_HELP);
    app.confirm = 1;
    cr_expect_eq(viewer_mode(&app), VM_CONFIRM);
    /* n answers the question (and nothing under it sees the key) */
    float yaw = scene.cam.yaw;
    viewer_key(&app, 'n');
    cr_expect(!app.confirm, "the question is answered");
    cr_expect(app.help && app.cmd, "the modes under it stay");
    cr_expect_str_eq(app.note, "the scene stays");
    /* then the help takes keys: l does not turn the model */
    cr_expect_eq(viewer_mode(&app), VM_HELP);
    viewer_key(&app, 'l');
    cr_expect_eq(scene.cam.yaw, yaw);
    app.help = 0;
    app.cmd = 0;
    cr_expect_eq(viewer_mode(&app), VM_VIEW);
    viewer_key(&app, 'l');
    cr_expect_neq(scene.cam.yaw, yaw, "with nothing on top, l turns");
    cr_expect(viewer_mode_boxed(VM_HELP) && viewer_mode_boxed(VM_COMMAND) && !viewer_mode_boxed(VM_PROMPT) &&
              !viewer_mode_boxed(VM_SKETCH));
}

/* r goes back to the view the model opened with (the automatic view or
 * what the command line asked), objects where they opened: not to a
 * plain view from the front. */
Test(viewer, r_goes_back_to_the_opening_view)
{
    scene.cam.yaw = 0.7f;
    scene.cam.pitch = 0.3f;
    scene.cam.zoom = 1.3f;
    scene.cam.pan = v3(0.1f, 0, 0);
    scene.objs[0].open_yaw = scene.objs[0].yaw = 0.25f;
    app.opening = scene.cam;
    Camera want = scene.cam;
    viewer_key(&app, 'l');
    viewer_key(&app, 'j');
    viewer_key(&app, '+');
    cr_assert(scene.cam.yaw != want.yaw || scene.cam.pitch != want.pitch, "the keys turned");
    viewer_key(&app, 'r');
    cr_expect_eq(scene.cam.yaw, want.yaw);
    cr_expect_eq(scene.cam.pitch, want.pitch);
    cr_expect_eq(scene.cam.zoom, want.zoom);
    cr_expect_eq(scene.cam.pan.x, want.pan.x);
    cr_expect_eq(memcmp(&scene.cam.centre, &want.centre, sizeof want.centre), 0, "fitted as it opened");
    cr_expect_eq(scene.objs[0].yaw, 0.25f, "the object turned as it opened");
}

/* A selected object moves along the screen's axes whatever the turn of
 * the camera: through the camera's own view matrix, w moves it straight
 * up the screen and d straight right, neither toward the eye. */
Test(viewer, w_and_d_move_the_selected_object_up_and_right_on_the_screen)
{
    app.sel = 0;
    scene.cam.yaw = 0.5f;
    scene.cam.pitch = 0.7f;
    scene.cam.roll = 0.3f;
    const int keys[2] = { 'w', 'd' };
    for (int k = 0; k < 2; k++) {
        Vec3 before = scene.objs[0].offset;
        cr_assert_eq(viewer_key(&app, keys[k]) & RE_RENDER, RE_RENDER);
        Vec3 d = v3_sub(scene.objs[0].offset, before);
        Mat4 view = camera_view(&scene.cam);
        Vec3 v = m4_dir(&view, d);
        float len = sqrtf(v3_dot(d, d));
        cr_assert(len > 0, "key %c moved nothing", keys[k]);
        float along = k == 0 ? v.y : v.x, across = k == 0 ? v.x : v.y;
        cr_expect(along > 0.999f * len && fabsf(across) < 1e-3f * len && fabsf(v.z) < 1e-3f * len,
                  "key %c: (%g %g %g) on the screen, %g long", keys[k], (double)v.x, (double)v.y, (double)v.z,
                  (double)len);
    }
}

/* ==== The status bar ==== */

/* As the window narrows the rank 0 fields take their brief forms, the
 * help's one character ("?") among them: in a window exactly as wide as
 * the brief bar, that bar whole, nothing of the name cut. The bars are
 * written out here from the scene's counts. */
Test(viewer, a_narrow_status_bar_takes_the_brief_forms)
{
    snprintf(app.name, sizeof app.name, "knot.obj");
    char bar[512], brief[128];
    viewer_status_text(&app, bar, sizeof bar, 0, 30, 400);
    char faces[64];
    snprintf(faces, sizeof faces, " | faces %u drawn %u | ", scene.nfaces, app.p.sp.npolys);
    cr_expect(strncmp(bar, " knot.obj | ", 12) == 0 && strstr(bar, faces), "wide: %s", bar);
    cr_expect(strlen(bar) > 6 && strcmp(bar + strlen(bar) - 9, " | ? help") == 0, "wide: %s", bar);
    snprintf(brief, sizeof brief, " knot.obj | %u/%u | zbuffer %.2fms | ?", app.p.sp.npolys, scene.nfaces,
             app.p.hsr_ms);
    viewer_status_text(&app, bar, sizeof bar, 0, 30, (int)strlen(brief));
    cr_expect_str_eq(bar, brief);
}

/* The info panel's output time includes the cells' making, timed around
 * that call: within the render's own time (the same monotonic clock,
 * read around it here), never negative. */
Test(viewer, the_cells_time_is_within_the_render)
{
    double t0 = now_ms();
    cr_assert_eq(viewer_render(&app, 80, 24), 0);
    double took = now_ms() - t0;
    cr_expect(app.p.cells_ms >= 0 && app.p.cells_ms <= took, "cells %g ms of a render of %g ms", app.p.cells_ms,
              took);
}
