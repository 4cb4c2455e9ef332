/* test_focus.c: one problem in focus (app/focus.c, check/items.c, the
 * viewer's . and , keys): the items a check of a scene gives, in the
 * order of the kinds and numbered within each; the camera framed on one
 * (its box's middle at the picture's middle, the turn kept while it
 * shows, a turn only when faces hide it, and then one from which it
 * shows); the problem drawn over the picture in its warning colour at
 * text and pixel sizes alike; the status bar's words; and the keys
 * stepping through them, wrapping, with --problems turned on first. */

#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "testlib.h"
#include "../src/viewer/viewer_app.h"

/* ==== Scenes ==== */

/* An open cube (its top, y = 1, left out) at x = 0, and a closed one
 * at x = 3 with its back face (z = 0) flipped. */
static const char *two_cubes =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 1 5 8\nf 2 3 7 6\n"
    "o second\n"
    "v 3 0 0\nv 4 0 0\nv 4 1 0\nv 3 1 0\nv 3 0 1\nv 4 0 1\nv 4 1 1\nv 3 1 1\n"
    "f 9 10 11 12\nf 13 14 15 16\nf 9 10 14 13\nf 12 9 13 16\nf 10 11 15 14\nf 11 12 16 15\n";

static void checked(Scene *s, SceneCheck *sc, const char *text)
{
    char err[256];
    cr_assert_eq(tl_scene_from_text(s, "t.obj", text), 0);
    cr_assert_eq(app_check_scene(s, 1, sc, err, sizeof err), 0, "%s", err);
}

static void look(Scene *s, float yaw_deg, float pitch_deg)
{
    s->cam.yaw = deg2rad(yaw_deg);
    s->cam.pitch = deg2rad(pitch_deg);
    s->cam.roll = 0;
    s->cam.zoom = 1;
    s->cam.pan = v3(0, 0, 0);
    scene_fit(s);
}

/* Item i's box's middle, projected with the camera as it stands, for a
 * w x h picture: pixels. */
static void projected_middle(Scene *s, const CheckItems *it, uint32_t i, int obj, int w, int h, float aspect,
                             double out[2])
{
    float lo[3], hi[3];
    meshcheck_item_box(it, i, lo, hi);
    Mat4 m = object_matrix(&s->objs[obj]);
    Mat4 turn = m4_rotate_ypr(s->cam.yaw, s->cam.pitch, s->cam.roll);
    /* the box as the camera sees it: its 8 corners turned */
    double vlo[3] = { INFINITY, INFINITY, INFINITY }, vhi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int k = 0; k < 8; k++) {
        Vec3 p = m4_point(&m, v3(k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]));
        Vec3 q = m4_dir(&turn, v3_sub(p, s->cam.centre));
        double v[3] = { q.x, q.y, q.z };
        for (int j = 0; j < 3; j++) {
            vlo[j] = fmin(vlo[j], v[j]);
            vhi[j] = fmax(vhi[j], v[j]);
        }
    }
    /* the middle of that box, in world space, through a real projection */
    Mat4 back = turn;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            back.m[a][b] = turn.m[b][a];
    Vec3 mid = v3_add(s->cam.centre, m4_dir(&back, v3((float)(0.5 * (vlo[0] + vhi[0])), (float)(0.5 * (vlo[1] + vhi[1])),
                                                     (float)(0.5 * (vlo[2] + vhi[2])))));
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, s, hsr_algos[0], 1), 0);
    cr_assert_eq(pipeline_render(&p, w, h, aspect, 0, 0), 0);
    Mat4 view = camera_view(&s->cam);
    Vec3 q = m4_point(&view, mid);
    double sp[3];
    cr_assert_eq(screen_view_point(&p.sp, q.x, q.y, q.z, sp), 0);
    out[0] = sp[0];
    out[1] = sp[1];
    pipeline_free(&p);
}

/* ==== The items ==== */

Test(focus, items_come_kind_by_kind_numbered_within_each)
{
    Scene s;
    SceneCheck sc;
    checked(&s, &sc, two_cubes);
    cr_assert_eq(sc.items.n, 2);
    const CheckItem *a = &sc.items.item[0], *b = &sc.items.item[1];
    cr_assert_eq(a->kind, CHECK_LOC_HOLES);
    cr_assert_eq(a->num, 1);
    cr_assert_eq(a->count, 4);
    cr_assert(fabs(a->length - 4) < 1e-9);
    cr_assert_eq(a->nlines, 1);
    cr_assert_eq(b->kind, CHECK_LOC_FLIPPED);
    cr_assert_eq(b->face[0], 5, "the second object's first face is the file's sixth");
    cr_assert_eq(app_focus_object(&s, &sc.items, 0), 0);
    cr_assert_eq(app_focus_object(&s, &sc.items, 1), 1);
    char words[128];
    check_item_words(&sc.items, 0, &sc.all, "mm", 1, " · ", 0, words, sizeof words);
    cr_assert_str_eq(words, "hole 1 of 1 · 4 edges · 4 mm");
    check_item_words(&sc.items, 1, &sc.all, "", 1, ", ", 0, words, sizeof words);
    cr_assert_str_eq(words, "flipped face 1 of 1, face 5");
    check_item_words(&sc.items, 1, &sc.all, "", 1, ", ", 1, words, sizeof words);
    cr_assert_str_eq(words, "flipped face 1/1");
    scene_check_free(&sc);
    scene_free(&s);
}

Test(focus, kinds_come_first_whatever_the_objects_order)
{
    /* a flipped face in the first object, then two open cubes: the
     * holes go first, numbered 1 and 2, then the flip */
    Scene s;
    SceneCheck sc;
    char text[2048];
    snprintf(text, sizeof text, "%s%s%s",
             "v 3 0 0\nv 4 0 0\nv 4 1 0\nv 3 1 0\nv 3 0 1\nv 4 0 1\nv 4 1 1\nv 3 1 1\n"
             "f 1 2 3 4\nf 5 6 7 8\nf 1 2 6 5\nf 4 1 5 8\nf 2 3 7 6\nf 3 4 8 7\n",
             "o a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
             "f 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 12 9 13 16\nf 10 11 15 14\n",
             "o b\nv 6 0 0\nv 7 0 0\nv 7 1 0\nv 6 1 0\nv 6 0 1\nv 7 0 1\nv 7 1 1\nv 6 1 1\n"
             "f 17 20 19 18\nf 21 22 23 24\nf 17 18 22 21\nf 20 17 21 24\nf 18 19 23 22\n");
    checked(&s, &sc, text);
    cr_assert_eq(sc.items.n, 3);
    cr_assert_eq(sc.items.item[0].kind, CHECK_LOC_HOLES);
    cr_assert_eq(sc.items.item[0].num, 1);
    cr_assert_eq(sc.items.item[0].face_first, 6, "the first hole is object a's");
    cr_assert_eq(sc.items.item[1].kind, CHECK_LOC_HOLES);
    cr_assert_eq(sc.items.item[1].num, 2);
    cr_assert_eq(sc.items.item[1].face_first, 11);
    cr_assert_eq(sc.items.item[2].kind, CHECK_LOC_FLIPPED);
    cr_assert_eq(sc.items.item[2].num, 1);
    char words[128];
    check_item_words(&sc.items, 1, &sc.all, "", 1, ", ", 0, words, sizeof words);
    cr_assert_str_eq(words, "hole 2 of 2, 4 edges, 4");
    scene_check_free(&sc);
    scene_free(&s);
}

/* A flipped face shows, so its outline is enough; a degenerate face has
 * no area and a duplicate lies on its original, so each gets a ring at
 * its corners' mean as well (check/items.c). */
Test(focus, a_degenerate_or_duplicate_face_gets_a_ring_a_flipped_one_does_not)
{
    Scene s;
    SceneCheck sc;
    /* the closed cube of two_cubes with its first face flipped, a
     * triangle on one line, and a triangle twice */
    checked(&s, &sc,
            "v 3 0 0\nv 4 0 0\nv 4 1 0\nv 3 1 0\nv 3 0 1\nv 4 0 1\nv 4 1 1\nv 3 1 1\n"
            "f 1 2 3 4\nf 5 6 7 8\nf 1 2 6 5\nf 4 1 5 8\nf 2 3 7 6\nf 3 4 8 7\n"
            "o flat\nv 10 0 0\nv 11 0 0\nv 13 0 0\nf 9 10 11\n"
            "o twice\nv 20 0 0\nv 21 0 0\nv 20 1 0\nf 12 13 14\nf 12 13 14\n");
    int seen[CHECK_LOC_KINDS] = { 0 };
    for (uint32_t i = 0; i < sc.items.n; i++) {
        const CheckItem *e = &sc.items.item[i];
        seen[e->kind]++;
        if (e->kind == CHECK_LOC_FLIPPED)
            cr_expect_eq(e->has_ring, 0, "a flipped face needs no ring");
        if (e->kind == CHECK_LOC_DEGENERATE) {
            cr_expect_eq(e->has_ring, 1, "a degenerate face has no area to show: a ring");
            /* the mean of (10,0,0), (11,0,0) and (13,0,0) */
            cr_expect(fabsf(e->ring[0] - 34.0f / 3) < 1e-5f && e->ring[1] == 0 && e->ring[2] == 0,
                      "ring at (%g %g %g)", (double)e->ring[0], (double)e->ring[1], (double)e->ring[2]);
        }
        if (e->kind == CHECK_LOC_DUPLICATE) {
            cr_expect_eq(e->has_ring, 1, "a duplicate lies on its original: a ring");
            cr_expect(fabsf(e->ring[0] - 61.0f / 3) < 1e-5f && fabsf(e->ring[1] - 1.0f / 3) < 1e-6f && e->ring[2] == 0,
                      "ring at (%g %g %g)",
                      (double)e->ring[0], (double)e->ring[1], (double)e->ring[2]);
        }
    }
    cr_assert(seen[CHECK_LOC_FLIPPED] >= 1 && seen[CHECK_LOC_DEGENERATE] == 1 && seen[CHECK_LOC_DUPLICATE] == 1,
              "flipped %d, degenerate %d, duplicate %d", seen[CHECK_LOC_FLIPPED], seen[CHECK_LOC_DEGENERATE],
              seen[CHECK_LOC_DUPLICATE]);
    scene_check_free(&sc);
    scene_free(&s);
}

/* ==== Framing ==== */

static void framed_in_the_middle(int persp)
{
    Scene s;
    SceneCheck sc;
    checked(&s, &sc, two_cubes);
    s.cam.persp = persp;
    s.cam.fov_deg = 40;
    look(&s, 30, 25);        /* from above: the open top shows */
    float yaw = s.cam.yaw, pitch = s.cam.pitch;
    int turned = -1;
    cr_assert_eq(app_focus_frame(&s, &sc.items, 0, 0, 160, 96, 2.0f, 1, &turned), 0);
    cr_assert_eq(turned, 0, "the hole shows from above: no turn");
    cr_assert(s.cam.yaw == yaw && s.cam.pitch == pitch, "the turn is kept");
    cr_assert_gt(s.cam.zoom, 1.05f, "zoomed in on the hole (%g)", s.cam.zoom);
    double mid[2];
    projected_middle(&s, &sc.items, 0, 0, 160, 96, 2.0f, mid);
    cr_assert(fabs(mid[0] - 80) < 1.5 && fabs(mid[1] - 48) < 1.5, "the hole's middle at (%g, %g), not (80, 48)",
              mid[0], mid[1]);
    scene_check_free(&sc);
    scene_free(&s);
}

Test(focus, the_problem_goes_to_the_middle_turn_kept)
{
    framed_in_the_middle(0);
}

Test(focus, the_problem_goes_to_the_middle_in_perspective)
{
    framed_in_the_middle(1);
}

Test(focus, a_hidden_problem_turns_the_camera_to_show_it)
{
    Scene s;
    SceneCheck sc;
    checked(&s, &sc, two_cubes);
    look(&s, 0, 0);          /* from the front (+z): the flipped back face (z = 0) is hidden */
    int turned = 0;
    cr_assert_eq(app_focus_frame(&s, &sc.items, 1, 1, 160, 120, 1.0f, 1, &turned), 0);
    cr_assert_eq(turned, 1, "the back face is hidden from the front");
    /* from where it turned, the back face is seen: the view comes from -z */
    Mat4 turn = m4_rotate_ypr(s.cam.yaw, s.cam.pitch, s.cam.roll);
    cr_assert_lt(turn.m[2][2], -0.5f, "the camera looks from z %g", turn.m[2][2]);
    /* and then framing again keeps that turn */
    float yaw = s.cam.yaw, pitch = s.cam.pitch;
    cr_assert_eq(app_focus_frame(&s, &sc.items, 1, 1, 160, 120, 1.0f, 1, &turned), 0);
    cr_assert_eq(turned, 0);
    cr_assert(s.cam.yaw == yaw && s.cam.pitch == pitch);
    scene_check_free(&sc);
    scene_free(&s);
}

/* ==== Drawing ==== */

/* Pixels of p's picture in rgb, and their mean position. */
static int coloured(const Image *im, const uint8_t rgb[3], double *mx, double *my)
{
    int n = 0;
    double sx = 0, sy = 0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++)
            if (!memcmp(im->rgb + 3 * ((size_t)y * im->w + x), rgb, 3)) {
                n++;
                sx += x;
                sy += y;
            }
    *mx = n ? sx / n : -1;
    *my = n ? sy / n : -1;
    return n;
}

static void drawn_over(int w, int h, float aspect, int samples)
{
    Scene s;
    SceneCheck sc;
    checked(&s, &sc, two_cubes);
    look(&s, 30, 25);
    cr_assert_eq(app_focus_frame(&s, &sc.items, 0, 0, w, h, aspect, 1, NULL), 0);
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, &s, hsr_algos[0], 1), 0);
    p.samples = samples;
    uint8_t red[3];
    shade_problem_colour(CHECK_LOC_HOLES, red);
    double mx, my;
    cr_assert_eq(pipeline_render(&p, w, h, aspect, 0, 1), 0);
    cr_assert_eq(coloured(&p.img, red, &mx, &my), 0, "no focus: nothing in its colour");
    p.focus = (ProblemFocus){ &sc.items, 0, 0 };
    cr_assert_eq(pipeline_render(&p, w, h, aspect, 0, 1), 0);
    int n = coloured(&p.img, red, &mx, &my);
    cr_assert_gt(n, 2 * (w + h) / 10, "%dx%d: %d pixels of the hole's red", w, h, n);
    /* a loop round the middle: its pixels' mean there */
    cr_assert(fabs(mx - w / 2.0) < w / 10.0 && fabs(my - h / 2.0) < h / 10.0, "%dx%d: the loop's pixels about (%g, %g)",
              w, h, mx, my);
    pipeline_free(&p);
    scene_check_free(&sc);
    scene_free(&s);
}

Test(focus, drawn_over_text_pictures)
{
    drawn_over(160, 96, 2.0f, 4);      /* 80 x 48 cells' half blocks, as the viewer draws them */
}

Test(focus, drawn_over_pixel_pictures)
{
    drawn_over(640, 480, 1.0f, 1);     /* a terminal's pixels, -o */
}

/* ==== The keys ==== */

Test(focus, the_keys_step_through_and_wrap)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "t.obj", two_cubes), 0);
    Options o;
    cli_defaults(&o);
    o.threads = 1;
    App a;
    cr_assert_eq(viewer_app_init(&a, &o, &s, 0), 0);
    cr_assert_eq(viewer_render(&a, 80, 24), 0);
    cr_assert_eq(a.p.problems, 0);
    viewer_key(&a, '.');
    cr_assert_eq(a.p.problems, 1, ". turns --problems on");
    cr_assert_eq(a.focus, -1, "the check is not done yet");
    for (int i = 0; i < 6000 && a.focus < 0; i++) {     /* 30 s at least */
        viewer_check_poll(&a);
        usleep(5000);
    }
    cr_assert_eq(a.focus, 0, "the step is taken once the check is done");
    char bar[128];
    viewer_check_status(&a, 8, bar, sizeof bar);
    cr_assert(strstr(bar, "hole 1 of 1"), "%s", bar);
    viewer_key(&a, '.');
    cr_assert_eq(a.focus, 1);
    viewer_check_status(&a, 8, bar, sizeof bar);
    cr_assert(strstr(bar, "flipped face 1 of 1"), "%s", bar);
    viewer_key(&a, '.');
    cr_assert_eq(a.focus, 0, "past the last: the first");
    viewer_key(&a, ',');
    cr_assert_eq(a.focus, 1, "before the first: the last");
    viewer_key(&a, '!');
    cr_assert_eq(a.focus, -1, "! off: nothing in focus");
    cr_assert_null(a.p.focus.items);
    viewer_app_free(&a);
    scene_free(&s);
}

Test(focus, problem_k_goes_there_once_checked)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "t.obj", two_cubes), 0);
    Options o;
    char *argv[] = { "zview", "--problem", "2", "t.obj" };
    char err[256];
    cr_assert_eq(cli_parse(4, argv, &o, err, sizeof err), 0, "%s", err);
    cr_assert(o.problems, "--problem turns --problems on");
    o.threads = 1;
    App a;
    cr_assert_eq(viewer_app_init(&a, &o, &s, 0), 0);
    cr_assert_eq(viewer_render(&a, 80, 24), 0);
    for (int i = 0; i < 6000 && a.focus < 0; i++) {     /* 30 s at least */
        viewer_check_poll(&a);
        usleep(5000);
    }
    cr_assert_eq(a.focus, 1, "--problem 2: the second, the flipped face");
    cr_assert_eq(a.p.focus.item, 1);
    viewer_app_free(&a);
    scene_free(&s);
}
