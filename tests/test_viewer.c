/* Tests of the viewer's logic without a terminal: the keys' effects on
 * the view, the command line shown for a view, and the frame-file
 * patterns of --turntable. */

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../src/app/viewer.h"
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
    for (int i = 0; i < 7; i++) {
        float y, p;
        cr_assert_eq(view_from_name(view_name(i), &y, &p), 0);
        cr_expect_eq(app_key(&app, '1' + i), RE_RENDER);
        cr_expect_float_eq(scene.cam.yaw, remainderf(deg2rad(y), 2 * ZV_PI), 1e-6, "key %d yaw", i + 1);
        cr_expect_float_eq(scene.cam.pitch, deg2rad(p), 1e-6, "key %d pitch", i + 1);
        /* fitted from the view: the command line needs no --fit-from */
        cr_expect_eq(scene.cam.fit_yaw, scene.cam.yaw);
        cr_expect(strstr(app.note, view_name(i)) != NULL, "note '%s'", app.note);
    }
    float y, p;
    scene_pick_view(&scene, &y, &p);
    app_key(&app, '8');
    cr_expect_float_eq(scene.cam.yaw, remainderf(deg2rad(y), 2 * ZV_PI), 1e-6);
    cr_expect_float_eq(scene.cam.pitch, deg2rad(p), 1e-6);
}

Test(viewer, bracket_keys_turn_the_light)
{
    float y0 = scene.light.yaw, p0 = scene.light.pitch;
    app_key(&app, ']');
    cr_expect_float_eq(scene.light.yaw, y0 + 15, 1e-4);
    app_key(&app, '[');
    app_key(&app, '[');
    cr_expect_float_eq(scene.light.yaw, y0 - 15, 1e-4);
    app_key(&app, '{');
    cr_expect_float_eq(scene.light.pitch, p0 + 15, 1e-4);
    for (int i = 0; i < 12; i++)
        app_key(&app, '{');
    cr_expect_float_eq(scene.light.pitch, 90, 1e-4, "the light stops straight above");
    for (int i = 0; i < 30; i++)
        app_key(&app, ']');
    cr_expect(scene.light.yaw > -180 && scene.light.yaw <= 180, "yaw wraps: %g", scene.light.yaw);
    cr_expect_float_eq(scene.light.ambient, LIGHT_AMBIENT, 1e-6, "the ambient share stays");
}

Test(viewer, e_toggles_outlines_and_S_cycles_samples)
{
    app_key(&app, 'e');
    cr_expect(app.p.edges);
    app_key(&app, 'e');
    cr_expect(!app.p.edges);
    int want[] = { 9, 16, 1, 4 };
    for (int i = 0; i < 4; i++) {
        app_key(&app, 'S');
        cr_expect_eq(app.p.samples, want[i]);
    }
}

Test(viewer, v_cycles_every_shading)
{
    int seen = 0;
    for (int i = 0; i < SHADE_COUNT; i++) {
        seen |= 1 << app.p.shade;
        app_key(&app, 'v');
    }
    cr_expect_eq(seen, (1 << SHADE_COUNT) - 1, "smooth included");
}

/* The command shown wraps at the width with " \" and, joined, is the
 * view's command line. */
Test(viewer, command_lines_wrap_and_join_back)
{
    app_key(&app, '3');
    app_key(&app, 'e');
    app_key(&app, ']');
    char want[CMD_MAX];
    cr_assert_eq(app_view_command(&app, want, sizeof want), 0);
    cr_expect(strstr(want, "--edges") && strstr(want, "--light -19,37"), "%s", want);
    for (int cols = 24; cols <= 120; cols += 16) {
        char buf[2 * CMD_MAX];
        const char *lines[HELP_LINES_MAX];
        int n = app_command_layout(&app, cols, buf, sizeof buf, lines, HELP_LINES_MAX);
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
    app_key(&app, 'C');
    cr_expect(app.cmd);
    float yaw = scene.cam.yaw;
    cr_expect_eq(app_key(&app, 'l'), RE_DRAW);
    cr_expect(!app.cmd);
    cr_expect_eq(scene.cam.yaw, yaw);
    cr_expect_neq(app_key(&app, 'q') & RE_QUIT, 0, "then q quits");
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
