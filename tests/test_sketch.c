/* test_sketch.c: drawing polygons by hand: order, flip, tilt, undo, the
 * OBJ they become, and every algorithm's picture of it. */

#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "sketch.h"
#include "testlib.h"

/* Two squares crossing: A then B, B overlapping A's right half. */
static void two_squares(Sketch *k)
{
    sketch_init(k);
    const float a[4][2] = { { -0.8f, -0.5f }, { 0.2f, -0.5f }, { 0.2f, 0.5f }, { -0.8f, 0.5f } };
    const float b[4][2] = { { -0.2f, -0.3f }, { 0.8f, -0.3f }, { 0.8f, 0.7f }, { -0.2f, 0.7f } };
    for (int i = 0; i < 4; i++)
        cr_assert_eq(sketch_add_point(k, a[i][0], a[i][1]), 0);
    cr_assert_eq(sketch_close(k), 0);
    for (int i = 0; i < 4; i++)
        cr_assert_eq(sketch_add_point(k, b[i][0], b[i][1]), 0);
    cr_assert_eq(sketch_close(k), 0);
}

/* The face seen at canvas point (x, y) of the sketch rendered straight
 * on with algo (ids: polygon order); also checks every algorithm agrees. */
static int32_t seen_at(const Sketch *k, float x, float y)
{
    char *obj = sketch_to_text(k, NULL);
    cr_assert_not_null(obj);
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "sketch.obj", obj), 0, "%s", obj);
    free(obj);
    s.cam.yaw = s.cam.pitch = s.cam.roll = 0;
    scene_fit(&s);
    enum { W = 120, H = 120 };
    ScreenPolys sp = { 0 };
    FrameBufs ref = { 0 }, fb = { 0 };
    HsrStats st;
    cr_assert_eq(tl_render(&s, &hsr_zbuffer, 1, W, H, 0, &sp, &ref, &st), 0);
    for (int a = 0; a < hsr_nalgos; a++) {
        ScreenPolys sp2 = { 0 };
        cr_assert_eq(tl_render(&s, hsr_algos[a], 2, W, H, 0, &sp2, &fb, &st), 0);
        int fx, fy;
        cr_assert_eq(tl_diff(&ref, &fb, &fx, &fy), 0, "%s differs at %d,%d", hsr_algos[a]->name, fx, fy);
        screen_free(&sp2);
    }
    /* canvas -> pixel: the fit centres the drawing's box; find the pixel
     * by projecting through the same camera instead of guessing */
    Mat4 view = camera_view(&s.cam);
    Vec3 v = m4_point(&view, v3(x, y, 0.15f));
    float half = fmaxf(s.cam.fit_half.x, s.cam.fit_half.y);
    float f = 0.9f * 0.5f * W / half;
    int px = (int)(W * 0.5f + f * v.x), py = (int)(H * 0.5f - f * v.y);
    cr_assert(px >= 0 && px < W && py >= 0 && py < H);
    int32_t id = ref.ids[py * W + px];
    fbuf_free(&ref);
    fbuf_free(&fb);
    screen_free(&sp);
    scene_free(&s);
    return id;
}

Test(sketch, the_last_drawn_is_nearest_and_flip_reverses)
{
    Sketch k;
    two_squares(&k);
    cr_expect_gt(sketch_depth_at(&k, 1, 0, 0), sketch_depth_at(&k, 0, 0, 0));
    cr_expect_eq(seen_at(&k, 0, 0), 1, "B covers A where they overlap");
    cr_expect_eq(seen_at(&k, -0.6f, 0), 0, "A shows where alone");
    sketch_flip(&k);
    cr_expect_eq(seen_at(&k, 0, 0), 0, "flipped: A in front");
    sketch_free(&k);
}

Test(sketch, a_tilted_polygon_pierces_the_other)
{
    Sketch k;
    two_squares(&k);
    /* B leans back about the vertical: its left edge goes behind A */
    cr_assert_eq(k.sel, 1);
    cr_assert_eq(sketch_tilt(&k, 15, 0), 0);
    cr_expect_lt(sketch_depth_at(&k, 1, -0.15f, 0.2f), sketch_depth_at(&k, 0, -0.15f, 0.2f));
    cr_expect_gt(sketch_depth_at(&k, 1, 0.15f, 0.2f), sketch_depth_at(&k, 0, 0.15f, 0.2f));
    cr_expect_eq(seen_at(&k, -0.15f, 0.2f), 0, "A in front left of the crossing");
    cr_expect_eq(seen_at(&k, 0.15f, 0.2f), 1, "B in front right of it");
    sketch_free(&k);
}

Test(sketch, undo_clear_and_bad_points)
{
    Sketch k;
    two_squares(&k);
    cr_expect_eq(sketch_add_point(&k, 1.5f, 0), -1, "off the canvas");
    cr_assert_eq(sketch_add_point(&k, 0.1f, 0.1f), 0);
    cr_expect_eq(sketch_close(&k), -1, "one corner does not close");
    cr_assert_eq(sketch_undo(&k), 0);
    cr_expect_eq(sketch_open_points(&k), 0u);
    cr_expect_eq(k.npolys, 2u);
    cr_assert_eq(sketch_undo(&k), 0);
    cr_expect_eq(k.npolys, 1u, "then the last polygon goes");
    sketch_clear(&k);
    cr_expect_eq(k.npolys, 0u);
    cr_expect_eq(sketch_undo(&k), -1, "nothing left to undo");
    cr_expect_eq(sketch_tilt(&k, 10, 0), -1, "nothing selected");
    sketch_free(&k);
}

/* A cleared sketch starts again: the squares drawn after a flip and a
 * clear make the OBJ a fresh sketch of them makes, the last drawn in
 * front. Its arrays hold what few polygons it has (grow_array's first
 * 64 entries), not room for billions. */
Test(sketch, a_cleared_sketch_draws_as_a_new_one)
{
    Sketch fresh, k;
    two_squares(&fresh);
    two_squares(&k);
    sketch_flip(&k);
    sketch_clear(&k);
    const float a[4][2] = { { -0.8f, -0.5f }, { 0.2f, -0.5f }, { 0.2f, 0.5f }, { -0.8f, 0.5f } };
    const float b[4][2] = { { -0.2f, -0.3f }, { 0.8f, -0.3f }, { 0.8f, 0.7f }, { -0.2f, 0.7f } };
    for (int i = 0; i < 4; i++)
        cr_assert_eq(sketch_add_point(&k, a[i][0], a[i][1]), 0);
    cr_assert_eq(sketch_close(&k), 0);
    for (int i = 0; i < 4; i++)
        cr_assert_eq(sketch_add_point(&k, b[i][0], b[i][1]), 0);
    cr_assert_eq(sketch_close(&k), 0);
    char *want = sketch_to_text(&fresh, NULL), *got = sketch_to_text(&k, NULL);
    cr_assert(want && got);
    cr_expect_str_eq(got, want);
    cr_expect_eq(seen_at(&k, 0, 0), 1, "B, drawn last, in front");
    cr_expect_leq(fresh.cap_start, 64u, "%u entries for 2 polygons", fresh.cap_start);
    free(want);
    free(got);
    sketch_free(&fresh);
    sketch_free(&k);
}

Test(sketch, two_corners_do_not_close)
{
    /* a polygon needs an area: two corners are a line */
    Sketch k;
    sketch_init(&k);
    cr_assert_eq(sketch_add_point(&k, -0.5f, -0.5f), 0);
    cr_assert_eq(sketch_add_point(&k, 0.5f, -0.5f), 0);
    cr_expect_eq(sketch_close(&k), -1);
    cr_expect_eq(k.npolys, 0u);
    cr_assert_eq(sketch_add_point(&k, 0.5f, 0.5f), 0);
    cr_expect_eq(sketch_close(&k), 0, "the third corner closes it");
    cr_expect_eq(k.npolys, 1u);
    sketch_free(&k);
}

Test(sketch, undoing_the_selected_polygon_selects_the_last_one_left)
{
    /* the tilt keys act on the selection: after the selected polygon is
     * undone they reach the one that is now last, not a polygon gone */
    Sketch k;
    two_squares(&k);
    cr_assert_eq(k.sel, 1);
    cr_assert_eq(sketch_undo(&k), 0);
    cr_assert_eq(k.npolys, 1u);
    cr_expect_eq(k.sel, 0);
    cr_expect_eq(sketch_tilt(&k, 10, 0), 0, "the polygon left tilts");
    cr_expect_gt(sketch_depth_at(&k, 0, 0.1f, 0), sketch_depth_at(&k, 0, -0.1f, 0), "and leans");
    sketch_free(&k);
}

Test(sketch, obj_text_reloads_with_one_object_per_polygon)
{
    Sketch k;
    two_squares(&k);
    char *obj = sketch_to_text(&k, NULL);
    cr_assert_not_null(obj);
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "sketch.obj", obj), 0);
    cr_expect_eq(s.nobjs, 2);
    cr_expect_eq(s.nfaces, 2u);
    cr_expect(memcmp(&s.face_rgb[0], &s.face_rgb[3], 3) != 0, "each polygon its own colour");
    scene_free(&s);
    free(obj);
    sketch_free(&k);
}
