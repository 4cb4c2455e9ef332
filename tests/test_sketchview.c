/* test_sketchview.c: the sketch on screen: picture <-> canvas, the
 * drawing as a scene, and the camera that puts every corner where the
 * mapping says, at any picture size and pixel aspect. */

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "sketch.h"
#include "testlib.h"

/* A square from (-0.8, -0.5) to (0.2, 0.5), then one from (-0.2, -0.3)
 * to (0.8, 0.7) over its right half. */
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

Test(sketchview, the_canvas_fills_the_shorter_side_centred)
{
    /* 80 x 48 pixels of aspect 1: the height is shorter */
    float px, py;
    sketch_pixel_at(80, 48, 1, (SketchPt){ 0, 0 }, &px, &py);
    cr_expect_float_eq(px, 40, 1e-5);
    cr_expect_float_eq(py, 24, 1e-5);
    sketch_pixel_at(80, 48, 1, (SketchPt){ -1, 1 }, &px, &py);
    cr_expect_float_eq(py, 24 - 0.95f * 24, 1e-4, "top edge at 95%% of the half height");
    cr_expect_float_eq(px, 40 - 0.95f * 24, 1e-4, "square: as wide as tall");
    /* pixels twice as tall as wide (ascii cells): the canvas is half as
     * many rows as columns, and the narrow window makes width the limit */
    sketch_pixel_at(30, 40, 2, (SketchPt){ 1, 1 }, &px, &py);
    cr_expect_float_eq(px, 15 + 0.95f * 15, 1e-4);
    cr_expect_float_eq(py, 20 - 0.95f * 15 / 2, 1e-4);
}

Test(sketchview, picture_to_canvas_and_back)
{
    const int sizes[][2] = { { 80, 48 }, { 100, 58 }, { 31, 77 }, { 200, 9 } };
    const float aspects[] = { 1, 2, 0.5f };
    for (unsigned s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
        for (unsigned a = 0; a < 3; a++)
            for (float x = -1; x <= 1; x += 0.25f) {
                SketchPt c = { x, -0.5f * x + 0.1f };
                float px, py;
                sketch_pixel_at(sizes[s][0], sizes[s][1], aspects[a], c, &px, &py);
                SketchPt b = sketch_canvas_at(sizes[s][0], sizes[s][1], aspects[a], px, py);
                cr_expect_float_eq(b.x, c.x, 1e-5, "%dx%d aspect %g", sizes[s][0], sizes[s][1], aspects[a]);
                cr_expect_float_eq(b.y, c.y, 1e-5, "%dx%d aspect %g", sizes[s][0], sizes[s][1], aspects[a]);
            }
}

/* Every corner of the drawing projects where sketch_pixel_at says, for
 * a drawing anywhere on the canvas (the camera's fit follows the
 * drawing's box; zoom and pan bring the canvas back). */
static void corners_land(const Sketch *k, int w, int h, float aspect)
{
    Scene s;
    char err[256];
    cr_assert_eq(sketch_scene(k, &s, err, sizeof err), 0, "%s", err);
    sketch_camera(&s, w, h, aspect);
    ScreenPolys sp = { 0 };
    Viewport vp = { w, h, aspect, 0 };
    PrimWork *work = NULL;
    cr_assert_eq(tl_project(&sp, &s, &vp, NULL, &work), 0);
    prims_free(&work);
    cr_assert_eq(sp.npolys, k->npolys);
    for (uint32_t p = 0; p < sp.npolys; p++) {
        uint32_t a = k->start[sp.polys[p].face], n = sp.polys[p + 1].first - sp.polys[p].first;
        cr_assert_eq(n, k->start[sp.polys[p].face + 1] - a);
        for (uint32_t i = 0; i < n; i++) {
            float px, py;
            sketch_pixel_at(w, h, aspect, k->pts[a + i], &px, &py);
            const ScreenVert *v = &sp.verts[sp.polys[p].first + i];
            cr_expect_float_eq(v->x / 256.0f, px, 2e-2, "%dx%d: polygon %u corner %u x", w, h, p, i);
            cr_expect_float_eq(v->y / 256.0f, py, 2e-2, "%dx%d: polygon %u corner %u y", w, h, p, i);
        }
    }
    screen_free(&sp);
    scene_free(&s);
}

Test(sketchview, corners_land_where_the_mapping_says)
{
    Sketch k;
    two_squares(&k);
    corners_land(&k, 80, 48, 1);
    corners_land(&k, 120, 29, 2);
    corners_land(&k, 50, 200, 0.5f);
    /* a small drawing off the centre: a fit of its own box would fill
     * the picture with it */
    Sketch t;
    sketch_init(&t);
    cr_assert_eq(sketch_add_point(&t, 0.5f, 0.5f), 0);
    cr_assert_eq(sketch_add_point(&t, 0.7f, 0.55f), 0);
    cr_assert_eq(sketch_add_point(&t, 0.6f, 0.8f), 0);
    cr_assert_eq(sketch_close(&t), 0);
    corners_land(&t, 80, 48, 1);
    /* tilted: the corners leave the plane z = const, the picture's x and y stay */
    cr_assert_eq(sketch_tilt(&k, 45, -30), 0);
    corners_land(&k, 80, 48, 1);
    sketch_free(&k);
    sketch_free(&t);
}

Test(sketchview, the_nearer_polygon_shows_where_clicked)
{
    Sketch k;
    two_squares(&k);
    Scene s;
    char err[256];
    cr_assert_eq(sketch_scene(&k, &s, err, sizeof err), 0, "%s", err);
    enum { W = 90, H = 60 };
    sketch_camera(&s, W, H, 1);
    ScreenPolys sp = { 0 };
    FrameBufs fb = { 0 };
    HsrStats st;
    cr_assert_eq(tl_render(&s, &hsr_zbuffer, 1, W, H, 0, &sp, &fb, &st), 0);
    /* B (drawn second) covers A where they overlap; flipped, A does */
    const struct { float x, y; int32_t id, flipped; } at[] = {
        { -0.6f, 0, 0, 0 }, { 0, 0, 1, 0 }, { 0.6f, 0.6f, 1, 1 }, { 0.9f, -0.9f, -1, -1 }, { -0.5f, 0.6f, -1, -1 },
    };
    for (int flip = 0; flip < 2; flip++) {
        for (unsigned i = 0; i < sizeof at / sizeof at[0]; i++) {
            float px, py;
            sketch_pixel_at(W, H, 1, (SketchPt){ at[i].x, at[i].y }, &px, &py);
            int32_t id = fb.ids[(int)py * W + (int)px];
            cr_expect_eq(id, flip ? at[i].flipped : at[i].id, "%s at %g,%g", flip ? "flipped" : "drawn",
                         (double)at[i].x, (double)at[i].y);
        }
        /* every algorithm gives the same buffers */
        for (int a = 0; a < hsr_nalgos; a++) {
            ScreenPolys sp2 = { 0 };
            FrameBufs fb2 = { 0 };
            cr_assert_eq(tl_render(&s, hsr_algos[a], 2, W, H, 0, &sp2, &fb2, &st), 0);
            int fx, fy;
            cr_expect_eq(tl_diff(&fb, &fb2, &fx, &fy), 0, "%s differs at %d,%d", hsr_algos[a]->name, fx, fy);
            screen_free(&sp2);
            fbuf_free(&fb2);
        }
        if (flip)
            break;
        sketch_flip(&k);
        scene_free(&s);
        cr_assert_eq(sketch_scene(&k, &s, err, sizeof err), 0, "%s", err);
        sketch_camera(&s, W, H, 1);
        cr_assert_eq(tl_render(&s, &hsr_zbuffer, 1, W, H, 0, &sp, &fb, &st), 0);
    }
    scene_free(&s);
    screen_free(&sp);
    fbuf_free(&fb);
    sketch_free(&k);
}

Test(sketchview, an_empty_drawing_is_an_empty_scene)
{
    Sketch k;
    sketch_init(&k);
    Scene s;
    char err[256];
    cr_assert_eq(sketch_scene(&k, &s, err, sizeof err), 0, "%s", err);
    cr_expect_eq(s.nfaces, 0u);
    sketch_camera(&s, 40, 20, 2);
    ScreenPolys sp = { 0 };
    FrameBufs fb = { 0 };
    HsrStats st;
    cr_assert_eq(tl_render(&s, &hsr_zbuffer, 1, 40, 20, 0, &sp, &fb, &st), 0);
    for (int i = 0; i < 40 * 20; i++)
        cr_assert_eq(fb.ids[i], -1);
    scene_free(&s);
    screen_free(&sp);
    fbuf_free(&fb);
    sketch_free(&k);
}
