/* test_scene.c: objects, polygons after the planarity split, fitting,
 * the projection (aspect, perspective, near-plane clipping), snapping
 * and back-face culling. */

#define _DEFAULT_SOURCE  /* mkdtemp, M_PI */

#include <criterion/criterion.h>
#include <pthread.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "testlib.h"
#include "simd.h"
#include "writers.h"

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

/* A scene with lines or points and no faces: the face arrays have no
 * elements, and copying them must neither free them (realloc to 0 bytes
 * does) nor fail; every copy's points and segments are there. */
Test(scene, grid_copies_of_a_scene_without_faces)
{
    static const char *const texts[] = { "v 0 0 0\nv 1 1 0\nl 1 2\n", "v 0 0 0\n" };
    for (int t = 0; t < 2; t++) {
        Scene s;
        char err[256];
        cr_assert_eq(tl_scene_from_text(&s, "noface.obj", texts[t]), 0);
        cr_assert_eq(s.nfaces, 0);
        uint32_t np = s.npoints, nl = s.nprims;
        cr_assert_eq(scene_make_grid(&s, 2, err, sizeof err), 0, "%s", err);
        cr_assert_eq(s.nobjs, 8);
        cr_assert_eq(s.nfaces, 0);
        cr_assert_eq(s.npoints, 8 * np);
        cr_assert_eq(s.nprims, 8 * nl);
        scene_free(&s);
    }
}

/* A model with its coordinates scaled by a power of two is the same
 * model: the fit scales with it, and every algorithm draws the same face
 * ids at 2^0, 2^66 (where squares pass FLT_MAX) and 2^127 (where a turn's
 * sums do), turned, in perspective and not. */
static void knot_scaled(Scene *s, int e)
{
    Scene src;
    cr_assert_eq(tl_scene_from_file(&src, "assets/knot.obj"), 0);
    const Mesh *m0 = &src.meshes[0];
    Mesh m;
    cr_assert_eq(tl_mesh_init(&m, "scaled.obj"), 0);
    for (uint32_t v = 0; v < m0->nverts; v++)
        cr_assert_eq(tl_mesh_vertex(&m, ldexpf(m0->pos[3 * v], e), ldexpf(m0->pos[3 * v + 1], e),
                                    ldexpf(m0->pos[3 * v + 2], e)), 0);
    for (uint32_t p = 0; p < src.npolys; p++)
        cr_assert_eq(tl_mesh_face(&m, &src.poly_corner[scene_poly_c0(&src, p)],
                                  scene_poly_c0(&src, p + 1) - scene_poly_c0(&src, p)), 0);
    cr_assert_eq(tl_mesh_finish(&m), 0);
    scene_free(&src);
    Mesh *one = malloc(sizeof *one);
    *one = m;
    char err[256];
    cr_assert_eq(scene_build(s, one, 1, err, sizeof err), 0, "%s", err);
}

Test(scene, a_model_scaled_by_a_power_of_two_draws_the_same_up_to_float_max)
{
    static const int exps[] = { 66, 100, 127 };
    for (int persp = 0; persp <= 1; persp++) {
        Scene ref;
        knot_scaled(&ref, 0);
        TlView v = { .yaw = 0.7f, .pitch = 0.4f, .roll = 0.1f, .fit_yaw = 0.7f, .fit_pitch = 0.4f,
                     .fit_roll = 0.1f, .zoom = 1, .persp = persp, .fov_deg = 50 };
        tl_set_view(&ref, &v);
        ScreenPolys sp = { 0 };
        FrameBufs want = { 0 }, got = { 0 };
        HsrStats st;
        cr_assert_eq(tl_render(&ref, &hsr_zbuffer, 1, 96, 64, 0, &sp, &want, &st), 0);
        long drawn = 0;
        for (int i = 0; i < 96 * 64; i++)
            drawn += want.ids[i] >= 0;
        cr_assert_gt(drawn, 96 * 64 / 8, "the reference draws little (%ld pixels)", drawn);
        for (size_t e = 0; e < sizeof exps / sizeof exps[0]; e++) {
            Scene s;
            knot_scaled(&s, exps[e]);
            tl_set_view(&s, &v);
            for (int a = 0; a < hsr_nalgos; a++) {
                cr_assert_eq(tl_render(&s, hsr_algos[a], 2, 96, 64, 0, &sp, &got, &st), 0);
                int fx, fy;
                long n = tl_diff(&want, &got, &fx, &fy);
                cr_assert_eq(n, 0, "2^%d %s persp=%d: %ld pixels differ, first (%d,%d)", exps[e],
                             hsr_algos[a]->name, persp, n, fx, fy);
            }
            scene_free(&s);
        }
        fbuf_free(&want);
        fbuf_free(&got);
        screen_free(&sp);
        scene_free(&ref);
    }
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
/* ==== threads and reentrancy ==== */

/* A wavy n x n grid of quads split into triangles: one object big enough
 * for the front end to split over several threads. */
static char *wavy_grid_obj(int n)
{
    size_t cap = (size_t)(n + 1) * (n + 1) * 48 + (size_t)n * n * 2 * 40 + 1;
    char *t = malloc(cap), *p = t;
    cr_assert(t);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            p += snprintf(p, cap - (size_t)(p - t), "v %d %d %.4f\n", i, j,
                          2.0 * sin(i * 0.21) * cos(j * 0.17));
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
            p += snprintf(p, cap - (size_t)(p - t), "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c);
        }
    return t;
}

static void expect_same_polys(const ScreenPolys *a, const ScreenPolys *b, const Scene *s)
{
    cr_assert_eq(a->npolys, b->npolys);
    cr_assert_eq(a->nverts, b->nverts);
    cr_assert_eq(a->culled_empty, b->culled_empty);
    cr_assert_eq(memcmp(a->verts, b->verts, a->nverts * sizeof *a->verts), 0);
    cr_assert_eq(memcmp(a->polys, b->polys, (a->npolys + 1) * sizeof *a->polys), 0);
    cr_assert_eq(memcmp(a->map, b->map, s->npolys * sizeof *a->map), 0);
}

typedef struct {
    const Scene *s;
    Viewport     vp;
    ScreenPolys  sp;
    int          rounds, rc;
} ProjectJob;

static void *project_rounds(void *arg)
{
    ProjectJob *j = arg;
    for (int r = 0; r < j->rounds && !j->rc; r++)
        j->rc = screen_project(&j->sp, j->s, &j->vp);
    return NULL;
}

Test(scene, two_projections_at_once_equal_one)
{
    char *text = wavy_grid_obj(120);   /* 28,800 triangles */
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "wavy", text), 0);
    free(text);
    tl_random_view(&s, 7, 1);
    s.cam.zoom = 3.5f;                 /* the near plane cuts: the clipping path runs too */
    Viewport vp = { 320, 200, 1.0f, 0 };
    ScreenPolys ref = { 0 };
    ref.threads = 1;
    cr_assert_eq(screen_project(&ref, &s, &vp), 0);
    cr_assert_gt(ref.npolys, 1000);
    /* alternately: two ScreenPolys, each keeps its own scratch */
    ScreenPolys a = { 0 }, b = { 0 };
    a.threads = b.threads = 2;
    Viewport small = { 97, 61, 2.0f, 1 };
    for (int r = 0; r < 3; r++) {
        cr_assert_eq(screen_project(&a, &s, &vp), 0);
        cr_assert_eq(screen_project(&b, &s, &small), 0);
    }
    expect_same_polys(&ref, &a, &s);
    screen_free(&a);
    screen_free(&b);
    /* concurrently: two threads, each with its own ScreenPolys */
    ProjectJob j[2] = { { &s, vp, { 0 }, 20, 0 }, { &s, vp, { 0 }, 20, 0 } };
    j[0].sp.threads = 2;    /* with helper threads of its own */
    j[1].sp.threads = 1;
    pthread_t th[2];
    for (int i = 0; i < 2; i++)
        cr_assert_eq(pthread_create(&th[i], NULL, project_rounds, &j[i]), 0);
    for (int i = 0; i < 2; i++) {
        pthread_join(th[i], NULL);
        cr_assert_eq(j[i].rc, 0);
        expect_same_polys(&ref, &j[i].sp, &s);
        screen_free(&j[i].sp);
    }
    screen_free(&ref);
    scene_free(&s);
}

Test(scene, one_thread_means_no_helper_thread)
{
    char *text = wavy_grid_obj(120);
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "wavy", text), 0);
    free(text);
    tl_random_view(&s, 3, 0);
    Viewport vp = { 200, 150, 1.0f, 0 };
    ScreenPolys one = { 0 }, three = { 0 };
    one.threads = 1;
    three.threads = 3;
    cr_assert_eq(screen_project(&one, &s, &vp), 0);
    cr_assert_eq(one.helpers, 0, "threads = 1 started %u helper threads", one.helpers);
    /* the count is real: more threads on the same object do start helpers */
    cr_assert_eq(screen_project(&three, &s, &vp), 0);
    cr_assert_eq(three.helpers, 2);
    expect_same_polys(&one, &three, &s);
    screen_free(&one);
    screen_free(&three);
    scene_free(&s);
}

/* ==== the front end's SIMD levels ==== */

/* Every level of the front end's loops (plain C, SSE2, AVX2 where the CPU
 * has it) gives the same polygons, bit for bit, on one thread and two:
 * triangles small and large, general polygons, corners behind the near
 * plane and outside the guard band, culling on and off. */
Test(scene, simd_levels_give_the_same_polygons)
{
    char *grid = wavy_grid_obj(90);    /* 16,200 triangles, two parts on two threads */
    size_t n = strlen(grid);
    /* a warped quad, a triangle, a concave pentagon (relative indices) */
    const char *more = "o quads\nv 0 0 5\nv 9 0 5\nv 9 9 6\nv 0 9 5\nv 4 4 9\n"
                       "f -5 -4 -3 -2\nf -5 -4 -1\n"
                       "o star\nv 20 20 0\nv 40 20 0\nv 22 35 0\nv 30 10 0\nv 38 35 0\nf -5 -4 -3 -2 -1\n";
    char *text = malloc(n + strlen(more) + 1);
    cr_assert(text);
    strcpy(text, grid);
    strcat(text, more);
    free(grid);
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "mix", text), 0);
    free(text);
    static const int sizes[][2] = { { 160, 96 }, { 7, 5 }, { 331, 199 } };
    static const float zooms[] = { 1.0f, 0.04f, 3.5f, 40.0f };
    ScreenPolys ref = { 0 }, sp = { 0 };
    ref.threads = 1;
    ref.simd = SIMD_SCALAR;
    int cases = 0;
    for (uint32_t seed = 0; seed < 6; seed++)
        for (int zi = 0; zi < 4; zi++)
            for (int si = 0; si < 3; si++) {
                tl_random_view(&s, seed, (int)(seed & 1));
                s.cam.zoom = zooms[zi];
                Viewport vp = { sizes[si][0], sizes[si][1], si == 1 ? 2.0f : 1.0f, (int)(seed % 3 == 0) };
                cr_assert_eq(screen_project(&ref, &s, &vp), 0);
                for (int level = SIMD_SSE2; level <= SIMD_AVX2; level++)
                    for (int th = 1; th <= 2; th++) {
                        sp.simd = level;
                        sp.threads = th;
                        cr_assert_eq(screen_project(&sp, &s, &vp), 0);
                        cr_assert_eq(sp.culled_back, ref.culled_back);
                        cr_assert_eq(sp.in_polys, ref.in_polys);
                        expect_same_polys(&ref, &sp, &s);
                        cases++;
                    }
            }
    cr_assert_gt(cases, 0);
    screen_free(&ref);
    screen_free(&sp);
    scene_free(&s);
}

/* Tiny triangles with corners on half-pixel positions, so that sample
 * centres fall exactly on their corners and edges: the top-left rule
 * decides, and each SIMD level must decide as plain C does. The view is
 * set by hand (front, 8 pixels a unit, centred on the origin). */
Test(scene, simd_levels_agree_where_samples_touch_edges)
{
    size_t cap = 1 << 20;
    char *text = malloc(cap), *p = text;
    cr_assert(text);
    const int n = 48;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            p += snprintf(p, cap - (size_t)(p - text), "v %.6f %.6f %.6f\n", i / 16.0 - 1.5, j / 16.0 - 1.5,
                          0.01 * ((i * 7 + j * 3) % 5));
    for (int j = 0; j + 2 <= n; j++)
        for (int i = 0; i + 2 <= n; i++) {
            int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1, e = a + 2 * (n + 1) + 2;
            if ((i + j) % 3 == 0)
                p += snprintf(p, cap - (size_t)(p - text), "f %d %d %d\n", a, b, c);
            else if ((i + j) % 3 == 1)
                p += snprintf(p, cap - (size_t)(p - text), "f %d %d %d\n", d, c, b);
            else
                p += snprintf(p, cap - (size_t)(p - text), "f %d %d %d\n", a, e, c + 1);
        }
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "lattice", text), 0);
    free(text);
    ScreenPolys ref = { 0 }, sp = { 0 };
    ref.threads = sp.threads = 1;
    ref.simd = SIMD_SCALAR;
    for (int cull = 0; cull < 2; cull++)
        for (int shift = 0; shift < 4; shift++) {
            s.cam.persp = 0;
            s.cam.yaw = s.cam.pitch = s.cam.roll = 0;
            s.cam.centre = v3(0.03125f * shift, 0.015625f * shift, 0);    /* quarter and eighth pixels */
            s.cam.pan = v3(0, 0, 0);
            s.cam.zoom = 1;
            s.cam.radius = 4;
            s.cam.fit_half = v3(3.6f, 3.6f, 3.6f);
            Viewport vp = { 64, 64, 1.0f, cull };
            cr_assert_eq(screen_project(&ref, &s, &vp), 0);
            cr_assert_gt(ref.culled_empty, 100, "tiny triangles that miss their sample");
            for (int level = SIMD_SSE2; level <= SIMD_AVX2; level++) {
                sp.simd = level;
                cr_assert_eq(screen_project(&sp, &s, &vp), 0);
                cr_assert_eq(sp.culled_back, ref.culled_back);
                expect_same_polys(&ref, &sp, &s);
            }
        }
    screen_free(&ref);
    screen_free(&sp);
    scene_free(&s);
}

/* ==== The compact form (scene.h, issue 21) ==== */

/* OBJ text of a torus of nu x nv cells, its vertices jittered: triangles
 * (each cell split), or quads (warped: not planar). */
static char *torus_obj(int nu, int nv, int tris)
{
    size_t cap = (size_t)(nu * nv) * 96 + 64, at = 0;
    char *t = malloc(cap);
    cr_assert(t);
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double a = 2 * M_PI * i / nu, b = 2 * M_PI * j / nv, r = 1 + 0.4 * cos(b);
            double jit = 0.03 * ((i * 7 + j * 3) % 5 - 2);
            at += (size_t)snprintf(t + at, cap - at, "v %.6f %.6f %.6f\n", r * cos(a), 0.4 * sin(b) + jit, r * sin(a));
        }
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            int p = i * nv + j + 1, q = (i + 1) % nu * nv + j + 1, r = (i + 1) % nu * nv + (j + 1) % nv + 1,
                u = i * nv + (j + 1) % nv + 1;
            if (tris)
                at += (size_t)snprintf(t + at, cap - at, "f %d %d %d\nf %d %d %d\n", p, q, r, p, r, u);
            else
                at += (size_t)snprintf(t + at, cap - at, "f %d %d %d %d\n", p, q, r, u);
        }
    return t;
}

/* A cube whose sides are 3 x 3 planar quads. */
static char *grid_cube_obj(void)
{
    size_t cap = 16384, at = 0;
    char *t = malloc(cap);
    cr_assert(t);
    int nv = 0;
    for (int side = 0; side < 6; side++) {
        int ax = side % 3, sg = side < 3 ? 1 : -1, u = (ax + 1) % 3, w = (ax + 2) % 3;
        for (int i = 0; i <= 3; i++)
            for (int j = 0; j <= 3; j++) {
                double p[3];
                p[ax] = sg;
                p[u] = -1 + 2.0 * i / 3;
                p[w] = -1 + 2.0 * j / 3;
                at += (size_t)snprintf(t + at, cap - at, "v %g %g %g\n", p[0], p[1], p[2]);
            }
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                int a = nv + i * 4 + j + 1, b = a + 4, c = b + 1, d = a + 1;
                if (sg > 0)
                    at += (size_t)snprintf(t + at, cap - at, "f %d %d %d %d\n", a, b, c, d);
                else
                    at += (size_t)snprintf(t + at, cap - at, "f %d %d %d %d\n", a, d, c, b);
            }
        nv += 16;
    }
    return t;
}

static void parse_into(Mesh *m, const char *name, const char *text)
{
    char err[256];
    cr_assert_eq(mesh_parse(m, name, text, strlen(text), err, sizeof err), 0, "%s", err);
}

/* The scene of `text` as scene_build makes it of the file alone, and the
 * same file's objects written out in full: built beside another file
 * (two meshes: no lists taken over) and that file removed. */
static void compact_and_full(const char *text, Scene *c, Scene *f)
{
    char err[256];
    Mesh *one = calloc(1, sizeof *one), *two = calloc(2, sizeof *two);
    cr_assert(one && two);
    parse_into(one, "a.obj", text);
    parse_into(&two[0], "a.obj", text);
    parse_into(&two[1], "b.obj", "v 9 9 9\nv 10 9 9\nv 9 10 9\nf 1 2 3\n");
    cr_assert_eq(scene_build(c, one, 1, err, sizeof err), 0, "%s", err);
    cr_assert_eq(scene_build(f, two, 2, err, sizeof err), 0, "%s", err);
    cr_assert_eq(scene_remove(f, 1, err, sizeof err), 0, "%s", err);
    cr_assert(f->poly_start && f->poly_lface && f->face_normal && f->face_rgb && f->face_obj,
              "the reference keeps every array");
}

/* The compact scene gives what the full one gives: the same polygons
 * and faces through the accessors, and with every algorithm the same
 * face ids and the same shaded picture, Lambert and smooth, with
 * outlines, turned and in perspective. */
static void expect_same_pictures(Scene *c, Scene *f)
{
    char msg[256];
    cr_expect_eq(tl_scene_faces_differ(c, f, msg, sizeof msg), 0, "%s", msg);
    TlView v = { .yaw = 0.6f, .pitch = 0.5f, .roll = 0.1f, .fit_yaw = 0.6f, .fit_pitch = 0.5f, .zoom = 1.3f,
                 .persp = 1, .fov_deg = 50 };
    tl_set_view(c, &v);
    tl_set_view(f, &v);
    for (int a = 0; a < hsr_nalgos; a++)
        for (int mode = 0; mode < 2; mode++) {
            Pipeline pc, pf;
            cr_assert_eq(pipeline_init(&pc, c, hsr_algos[a], 1), 0);
            cr_assert_eq(pipeline_init(&pf, f, hsr_algos[a], 1), 0);
            pc.shade = pf.shade = mode ? SHADE_SMOOTH : SHADE_LAMBERT;
            pc.edges = pf.edges = 1;
            cr_assert_eq(pipeline_render(&pc, 90, 60, 1.0f, 0, 1), 0);
            cr_assert_eq(pipeline_render(&pf, 90, 60, 1.0f, 0, 1), 0);
            long drawn = 0;
            for (int i = 0; i < 90 * 60; i++)
                drawn += pc.fb.ids[i] >= 0;
            cr_expect_gt(drawn, 90 * 60 / 10, "%s: the model is in the picture", hsr_algos[a]->name);
            cr_expect_eq(memcmp(pc.fb.ids, pf.fb.ids, 90 * 60 * sizeof(int32_t)), 0, "%s: ids", hsr_algos[a]->name);
            cr_expect_eq(memcmp(pc.img.rgb, pf.img.rgb, 90 * 60 * 3), 0, "%s, shading %d: colours",
                         hsr_algos[a]->name, mode);
            pipeline_free(&pc);
            pipeline_free(&pf);
        }
}

Test(scene, a_file_of_triangles_takes_the_compact_form_and_draws_as_the_full_one)
{
    char *t = torus_obj(24, 12, 1);
    Scene c, f;
    compact_and_full(t, &c, &f);
    cr_expect_eq(c.npolys, 24 * 12 * 2);
    cr_expect(!c.poly_start, "corners 3k");
    cr_expect(!c.poly_lface, "one polygon a face");
    cr_expect(!c.face_normal, "normals computed");
    cr_expect(!c.face_rgb && !c.face_own && !c.face_obj, "one object, no colour of its own");
    cr_expect(!c.meshes[0].face_start && !c.meshes[0].face_mat, "nothing left in the mesh");
    expect_same_pictures(&c, &f);
    /* the compact scene edited (a grid of copies) still draws the same */
    char err[256];
    cr_assert_eq(scene_make_grid(&c, 2, err, sizeof err), 0, "%s", err);
    cr_assert_eq(scene_make_grid(&f, 2, err, sizeof err), 0, "%s", err);
    cr_expect(!c.face_normal && c.face_obj, "copies: normals still computed, objects stored");
    expect_same_pictures(&c, &f);
    scene_free(&c);
    scene_free(&f);
    free(t);
}

Test(scene, planar_quads_keep_their_offsets_warped_ones_the_full_form)
{
    char *q = grid_cube_obj();
    Scene c, f;
    compact_and_full(q, &c, &f);
    cr_expect_eq(c.npolys, 54, "planar quads whole");
    cr_expect(c.poly_start && !c.poly_lface && !c.face_normal, "offsets kept, faces and normals derived");
    expect_same_pictures(&c, &f);
    scene_free(&c);
    scene_free(&f);
    free(q);
    char *w = torus_obj(16, 10, 0);
    compact_and_full(w, &c, &f);
    cr_expect_gt(c.npolys, 16 * 10, "warped quads split");
    cr_expect(c.poly_start && c.poly_lface && c.face_normal, "the full form");
    expect_same_pictures(&c, &f);
    scene_free(&c);
    scene_free(&f);
    free(w);
}

/* A file of triangles with materials: the lists and normals compact,
 * the colours kept. */
Test(scene, colours_of_their_own_are_kept_in_the_compact_form)
{
    char *t = torus_obj(12, 8, 1);
    char dir[] = "/tmp/zv-compact-XXXXXX";
    cr_assert(mkdtemp(dir));
    char mtl[64], obj[64];
    snprintf(mtl, sizeof mtl, "%s/c.mtl", dir);
    snprintf(obj, sizeof obj, "%s/c.obj", dir);
    FILE *fp = fopen(mtl, "w");
    cr_assert(fp);
    fputs("newmtl red\nKd 0.8 0.1 0.1\n", fp);
    cr_assert_eq(fclose(fp), 0);
    fp = fopen(obj, "w");
    cr_assert(fp);
    fprintf(fp, "mtllib c.mtl\nusemtl red\n%s", t);
    cr_assert_eq(fclose(fp), 0);
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, obj), 0);
    cr_expect(!s.poly_start && !s.poly_lface && !s.face_normal);
    cr_assert(s.face_rgb, "the material's colour");
    cr_expect_eq(s.face_rgb[0], 204);
    cr_expect_eq(s.face_rgb[1], 26);
    scene_free(&s);
    remove(mtl);
    remove(obj);
    rmdir(dir);
    free(t);
}

/* The normals of a block of faces at every SIMD level are the stored
 * ones of the full form, bit for bit: random triangles of every size
 * (1e-30 to 1e30), slivers, degenerate ones (a repeated corner: +z). */
Test(scene, computed_normals_are_the_stored_ones_at_every_simd_level)
{
    enum { NT = 203 };
    size_t cap = 200000, at = 0;
    char *t = malloc(cap);
    cr_assert(t);
    uint32_t seed = 7;
    for (int i = 0; i < 3 * NT; i++) {
        double c[3];
        for (int a = 0; a < 3; a++) {
            seed = seed * 1664525u + 1013904223u;
            c[a] = ((double)(seed >> 8) / 16777216.0 - 0.5) * pow(10.0, (double)((i / 3) % 61 - 30));
        }
        at += (size_t)snprintf(t + at, cap - at, "v %.9g %.9g %.9g\n", c[0], c[1], c[2]);
    }
    for (int f = 0; f < NT; f++) {
        int a = 3 * f + 1, b = f % 17 == 5 ? a : a + 1, d = f % 23 == 7 ? a + 1 : a + 2;
        at += (size_t)snprintf(t + at, cap - at, "f %d %d %d\n", a, b, d);
    }
    Scene c, full;
    compact_and_full(t, &c, &full);
    cr_assert(!c.face_normal && !c.poly_start);
    static float got[3 * NT];
    for (int lv = SIMD_SCALAR; lv < SIMD_LEVELS; lv++) {
        memset(got, 0xff, sizeof got);
        scene_face_normals(&c, 0, NT, got, lv);
        cr_expect_eq(memcmp(got, full.face_normal, sizeof got), 0, "SIMD level %s", simd_name(lv));
        /* a block starting mid-way, of a length no multiple of four */
        scene_face_normals(&c, 5, 11, got, lv);
        cr_expect_eq(memcmp(got, &full.face_normal[15], 11 * 3 * sizeof(float)), 0, "%s, faces 5..15", simd_name(lv));
    }
    int degenerate = 0;
    for (int f = 0; f < NT; f++)
        degenerate += full.face_normal[3 * f] == 0 && full.face_normal[3 * f + 1] == 0 && full.face_normal[3 * f + 2] == 1;
    cr_expect_geq(degenerate, NT / 23, "degenerate faces' +z is among them");
    scene_free(&c);
    scene_free(&full);
    free(t);
}

/* A textured face's corners keep their texture coordinates, u and v,
 * in the polygons a planar quad stays whole in and those a warped one
 * is fanned into: here each vertex has its own, (0.1 k, 0.05 k + 0.3)
 * for vertex k, so every corner of a polygon is checked by its vertex.
 * v is counted from the image's top row, as its rows are stored: the
 * file's v (OBJ's, from the bottom) taken from 1. */
Test(scene, texture_coordinates_follow_their_corners_whole_and_fanned)
{
    char dir[] = "/tmp/zv-scene-XXXXXX", p[600];
    cr_assert(mkdtemp(dir));
    size_t n;
    char *tga = w_tga_rle(4, 4, 1, &n);
    cr_assert(tga);
    snprintf(p, sizeof p, "%s/tex.tga", dir);
    cr_assert_eq(w_save(p, tga, n), 0);
    free(tga);
    static const char mtl[] = "newmtl t\nmap_Kd tex.tga\n";
    snprintf(p, sizeof p, "%s/q.mtl", dir);
    cr_assert_eq(w_save(p, mtl, sizeof mtl - 1), 0);
    static const char obj[] = "mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0.5\nv 2 1 0\n"
                              "vt 0.1 0.35\nvt 0.2 0.4\nvt 0.3 0.45\nvt 0.4 0.5\nvt 0.5 0.55\nvt 0.6 0.6\n"
                              "usemtl t\nf 1/1 2/2 3/3 4/4\nf 2/2 5/5 6/6 3/3\n";
    snprintf(p, sizeof p, "%s/q.obj", dir);
    cr_assert_eq(w_save(p, obj, sizeof obj - 1), 0);
    Mesh *m = calloc(1, sizeof *m);
    char err[512];
    cr_assert(m);
    cr_assert_eq(mesh_load(m, p, err, sizeof err), 0, "%s", err);
    Scene s;
    cr_assert_eq(scene_build(&s, m, 1, err, sizeof err), 0, "%s", err);
    cr_assert(s.poly_uv, "a textured scene keeps texture coordinates");
    cr_assert_eq(s.npolys, 3, "the planar quad whole, the warped one as two triangles");
    for (uint32_t c = 0; c < s.poly_start[s.npolys]; c++) {
        uint32_t k = s.poly_corner[c] + 1;
        cr_assert_float_eq(s.poly_uv[2 * c], 0.1f * k, 1e-6, "corner %u (vertex %u): u %g", c, k, s.poly_uv[2 * c]);
        cr_assert_float_eq(s.poly_uv[2 * c + 1], 1 - (0.05f * k + 0.3f), 1e-6, "corner %u (vertex %u): v %g", c, k,
                           s.poly_uv[2 * c + 1]);
    }
    scene_free(&s);
    snprintf(p, sizeof p, "rm -rf '%s'", dir);
    cr_assert_eq(system(p), 0);
}
