/* test_scene.c: objects, polygons after the planarity split, fitting,
 * the projection (aspect, perspective, near-plane clipping), snapping
 * and back-face culling. */

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "testlib.h"

static const char *cube_obj =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

Test(scene, planar_faces_stay_whole_non_planar_are_split)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "faces",
                                    "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 1 1 0\nv 0 2 0\n"   /* concave planar */
                                    "v 0 0 1\nv 1 0 1\nv 1 1 1.5\nv 0 1 1\n"           /* non-planar quad */
                                    "f 1 2 3 4 5\nf 6 7 8 9\n"),
                 0);
    cr_assert_eq(s.nfaces, 2);
    cr_assert_eq(s.npolys, 3, "the concave pentagon whole, the warped quad as two triangles");
    cr_assert_eq(s.poly_start[1] - s.poly_start[0], 5);
    cr_assert_eq(s.poly_lface[0], 0);
    cr_assert_eq(s.poly_lface[1], 1);
    cr_assert_eq(s.poly_lface[2], 1, "both halves keep the source face id");
    scene_free(&s);
}

Test(scene, objects_and_face_ids_follow_load_order)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "objs",
                                    "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n"
                                    "o second\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf 4 5 6\n"),
                 0);
    cr_assert_eq(s.nobjs, 2);
    cr_assert_str_eq(s.objs[0].name, "first");
    cr_assert_str_eq(s.objs[1].name, "second");
    cr_assert_eq(s.objs[0].face_base, 0);
    cr_assert_eq(s.objs[1].face_base, 2);
    cr_assert_eq(s.face_obj[2], 1);
    scene_free(&s);
}

/* Bounds of the projected vertices of polygons, in pixels. */
static void screen_bounds(const ScreenPolys *sp, float *x0, float *x1, float *y0, float *y1)
{
    *x0 = *y0 = 1e30f;
    *x1 = *y1 = -1e30f;
    for (uint32_t i = 0; i < sp->nverts; i++) {
        float x = sp->verts[i].x / 256.0f, y = sp->verts[i].y / 256.0f;
        *x0 = fminf(*x0, x);
        *x1 = fmaxf(*x1, x);
        *y0 = fminf(*y0, y);
        *y1 = fmaxf(*y1, y);
    }
}

Test(scene, fit_fills_about_90_percent_and_centres)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "cube", cube_obj), 0);
    /* move the cube far off the origin: fit must still centre it */
    for (int i = 0; i < 8; i++)
        ((Mesh *)s.objs[0].mesh)->pos[3 * i] += 100;
    s.objs[0].centre.x += 100;
    scene_reset(&s);
    ScreenPolys sp = { 0 };
    Viewport vp = { 200, 100, 1.0f, 0 };
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    float x0, x1, y0, y1;
    screen_bounds(&sp, &x0, &x1, &y0, &y1);
    /* straight on, the cube is a square of side 0.9 * 100 px, centred */
    cr_assert_float_eq(y1 - y0, 90.0f, 0.6f);
    cr_assert_float_eq(x1 - x0, 90.0f, 0.6f);
    cr_assert_float_eq((x0 + x1) / 2, 100.0f, 0.6f);
    cr_assert_float_eq((y0 + y1) / 2, 50.0f, 0.6f);
    screen_free(&sp);
    scene_free(&s);
}

Test(scene, pixel_aspect_keeps_shapes_square)
{
    /* cells twice as tall as wide: the cube is half as many pixels tall */
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "cube", cube_obj), 0);
    ScreenPolys sp = { 0 };
    Viewport vp = { 160, 48, 2.0f, 0 };
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    float x0, x1, y0, y1;
    screen_bounds(&sp, &x0, &x1, &y0, &y1);
    cr_assert_float_eq((x1 - x0) / (y1 - y0), 2.0f, 0.05f);
    screen_free(&sp);
    scene_free(&s);
}

Test(scene, vertices_are_snapped_to_the_subpixel_grid)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "tri", "v 0 0 0\nv 1 0.3333 0\nv 0.1 1 0\nf 1 2 3\n"), 0);
    ScreenPolys sp = { 0 };
    Viewport vp = { 97, 61, 1.0f, 0 };
    s.cam.yaw = 0.3f;
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    cr_assert_eq(sp.npolys, 1);
    /* the plane is through the snapped corners: evaluate it there */
    const ScreenPoly *p = &sp.polys[0];
    for (int k = 0; k < 3; k++) {
        const ScreenVert *v = &sp.verts[p->first + k];
        double x = v->x / 256.0 - 0.5, y = v->y / 256.0 - 0.5;
        double z = p->zc + p->b * (y - p->y0) + p->a * (x - p->x0);
        cr_assert_float_eq(z, v->z, 1e-4, "corner %d off the plane", k);
        cr_assert_leq(p->zmin, v->z, "zmin is not a lower bound");
    }
    screen_free(&sp);
    scene_free(&s);
}

Test(scene, back_faces_are_culled_only_when_asked)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "cube", cube_obj), 0);
    s.cam.yaw = 0.5f;
    s.cam.pitch = 0.4f;
    scene_fit(&s);
    ScreenPolys sp = { 0 };
    Viewport vp = { 120, 90, 1.0f, 0 };
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    cr_assert_eq(sp.npolys, 6);
    cr_assert_eq(sp.culled_back, 0);
    vp.cull = 1;
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    cr_assert_eq(sp.npolys, 3, "three faces face the viewer");
    cr_assert_eq(sp.culled_back, 3);
    /* culling removes only hidden faces: the picture is the same */
    FrameBufs a = { 0 }, b = { 0 };
    HsrStats st;
    cr_assert_eq(tl_render(&s, &hsr_zbuffer, 1, 120, 90, 0, &sp, &a, &st), 0);
    cr_assert_eq(tl_render(&s, &hsr_zbuffer, 1, 120, 90, 1, &sp, &b, &st), 0);
    cr_assert_eq(memcmp(a.ids, b.ids, 120 * 90 * sizeof(int32_t)), 0);
    fbuf_free(&a);
    fbuf_free(&b);
    screen_free(&sp);
    scene_free(&s);
}

Test(scene, perspective_clips_at_the_near_plane)
{
    /* a floor running from far in front to far behind the eye */
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "floor",
                                    "v -1 -1 -50\nv 1 -1 -50\nv 1 -1 50\nv -1 -1 50\nf 1 2 3 4\n"
                                    "v -1 1 -1\nv 1 1 -1\nv 0 1.5 -1\nf 5 6 7\n"),
                 0);
    s.cam.persp = 1;
    s.cam.fov_deg = 60;
    scene_reset(&s);
    s.cam.zoom = 20;    /* the eye deep inside the scene */
    ScreenPolys sp = { 0 };
    Viewport vp = { 100, 80, 1.0f, 0 };
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    cr_assert_geq(sp.npolys, 1);
    int clipped = 0;
    for (uint32_t i = 0; i < sp.npolys; i++) {
        cr_assert_geq(sp.polys[i].zmin, -1e-4f);
        /* a polygon cut by the near plane has corners on it: depth 0 */
        for (uint32_t k = sp.polys[i].first; k < sp.polys[i + 1].first; k++)
            if (sp.polys[i].face == 0 && fabsf(sp.verts[k].z) < 1e-4f)
                clipped++;
    }
    for (uint32_t i = 0; i < sp.nverts; i++) {
        cr_assert_geq(sp.verts[i].z, -1e-5f, "vertex %u in front of the near plane", i);
        cr_assert(fabsf(sp.verts[i].x / 256.0f) < 100000.0f);
    }
    cr_assert_geq(clipped, 1, "the floor crosses the near plane and must be clipped");
    screen_free(&sp);
    scene_free(&s);
}

Test(scene, nothing_behind_the_eye_is_drawn)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "two",
                                    "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n"
                                    "v -1 -1 40\nv 1 -1 40\nv 0 1 40\nf 4 5 6\n"),
                 0);
    s.cam.persp = 1;
    s.cam.fov_deg = 60;
    scene_reset(&s);
    /* put the eye between the two triangles, looking at the first */
    s.cam.zoom = 1000;
    ScreenPolys sp = { 0 };
    Viewport vp = { 64, 64, 1.0f, 0 };
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    for (uint32_t i = 0; i < sp.npolys; i++)
        cr_assert_neq(sp.polys[i].face, 1, "the triangle behind the eye was drawn");
    screen_free(&sp);
    scene_free(&s);
}

Test(scene, grid_copies_get_their_own_face_ids)
{
    Scene s;
    char err[256];
    cr_assert_eq(tl_scene_from_text(&s, "cube", cube_obj), 0);
    cr_assert_eq(scene_make_grid(&s, 2, err, sizeof err), 0);
    cr_assert_eq(s.nobjs, 8);
    cr_assert_eq(s.nfaces, 48);
    cr_assert_eq(s.objs[7].face_base, 42);
    ScreenPolys sp = { 0 };
    Viewport vp = { 64, 64, 1.0f, 0 };
    s.cam.yaw = 0.6f;
    s.cam.pitch = 0.5f;
    scene_fit(&s);
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    int seen[48] = { 0 };
    for (uint32_t i = 0; i < sp.npolys; i++) {
        cr_assert(sp.polys[i].face >= 0 && sp.polys[i].face < 48);
        seen[sp.polys[i].face]++;
    }
    for (int f = 0; f < 48; f++)
        cr_assert_leq(seen[f], 1);
    screen_free(&sp);
    scene_free(&s);
}

/* ==== first view ==== */

Test(view, picks_the_long_side_of_a_long_model)
{
    /* a box 10 long in x, 1 in y and z, wound CCW from outside */
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "bar.obj",
                                    "v -5 -0.5 -0.5\nv 5 -0.5 -0.5\nv 5 0.5 -0.5\nv -5 0.5 -0.5\n"
                                    "v -5 -0.5 0.5\nv 5 -0.5 0.5\nv 5 0.5 0.5\nv -5 0.5 0.5\n"
                                    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n"),
                 0);
    float yaw, pitch;
    scene_pick_view(&s, &yaw, &pitch);
    cr_expect(fabsf(yaw) <= 30.5f || fabsf(yaw) >= 149.5f, "seen from its long side, yaw %g", yaw);
    cr_expect(pitch > 0, "from above");
    cr_expect(fabsf(yaw) < 90, "from the front side when both long sides tie: %g", yaw);
    scene_free(&s);
}

Test(view, looks_into_an_open_box)
{
    /* a box open towards -z (no back face), faces wound to be seen from
     * inside: the view must come from behind, through the opening */
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "room.obj",
                                    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                                    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                                    "f 8 7 6 5\n"           /* the wall at +z, facing -z */
                                    "f 1 2 6 5\nf 4 8 7 3\n" /* floor up, ceiling down */
                                    "f 1 5 8 4\nf 2 3 7 6\n"),
                 0);
    float yaw, pitch;
    scene_pick_view(&s, &yaw, &pitch);
    cr_expect(fabsf(yaw) > 90, "seen through the opening at -z, yaw %g", yaw);
    scene_free(&s);
}

Test(view, named_views)
{
    float y, p;
    cr_assert_eq(view_from_name("front", &y, &p), 0);
    cr_expect(y == 0 && p == 0);
    cr_assert_eq(view_from_name("top", &y, &p), 0);
    cr_expect(p == 90);
    cr_assert_eq(view_from_name("right", &y, &p), 0);
    cr_expect(y == -90);
    cr_expect_eq(view_from_name("sideways", &y, &p), -1);
    for (int i = 0; view_name(i); i++)
        cr_expect_eq(view_from_name(view_name(i), &y, &p), 0);
}
