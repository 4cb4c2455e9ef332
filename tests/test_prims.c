/* test_prims.c: points, lines and the wireframe (prims.c), their loaders
 * (OBJ p and l, XYZ, PLY clouds, --points), lenient loading, and why an
 * empty frame is empty.
 *
 * The agreement tests render scenes of faces, points and lines from
 * seeded views with every algorithm on one and two threads and require
 * the z-buffer's buffers byte for byte; the reduction test renders dense
 * clouds with every point drawn and with one per sample box and requires
 * the same buffers. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "testlib.h"

static char E[512];

static uint32_t rng_state = 12345;
static uint32_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}
static float frand(void) { return (float)(rng() & 0xffffff) / (float)0x1000000; }

/* A growing text buffer for generated OBJ files. */
typedef struct {
    char  *p;
    size_t n, cap;
} Text;

static void put(Text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(Text *t, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        int k = vsnprintf(t->p ? t->p + t->n : NULL, t->p ? t->cap - t->n : 0, fmt, ap);
        va_end(ap);
        if (t->p && t->n + (size_t)k < t->cap) {
            t->n += (size_t)k;
            return;
        }
        t->cap = (t->cap + (size_t)k + 1) * 2;
        t->p = realloc(t->p, t->cap);
        cr_assert_not_null(t->p);
    }
}

/* A scene of faces, points and lines in several objects: a rough height
 * field of quads (some not planar), points on its vertices and strewn
 * about (several at one position), polylines over it and through it,
 * and a second object of a few triangles crossing it. */
static void mixed_scene(Scene *s, uint32_t seed)
{
    rng_state = seed * 2654435761u + 1;
    Text t = { 0 };
    int g = 6;
    put(&t, "o field\n");
    for (int j = 0; j <= g; j++)
        for (int i = 0; i <= g; i++)
            put(&t, "v %g %g %g\n", i - g / 2.0, j - g / 2.0, 0.4 * (frand() - 0.5));
    for (int j = 0; j < g; j++)
        for (int i = 0; i < g; i++) {
            int a = j * (g + 1) + i + 1;
            put(&t, "f %d %d %d %d\n", a, a + 1, a + g + 2, a + g + 1);
        }
    /* points on the field's corners, and a cloud above it, with repeats */
    for (int k = 1; k <= (g + 1) * (g + 1); k += 3)
        put(&t, "p %d\n", k);
    int base = (g + 1) * (g + 1);
    for (int k = 0; k < 300; k++)
        put(&t, "v %g %g %g\n", 6 * (frand() - 0.5), 6 * (frand() - 0.5), 2 * frand() - 0.5);
    for (int k = 0; k < 300; k++)
        put(&t, "p %d %d\n", base + 1 + k, base + 1 + (int)(rng() % 300));
    /* polylines: along the field's rows, and zigzags through the cloud */
    put(&t, "l");
    for (int i = 1; i <= g + 1; i++)
        put(&t, " %d", i + (g + 1) * 3);
    put(&t, "\n");
    for (int k = 0; k < 10; k++) {
        put(&t, "l");
        for (int c = 0; c < 2 + k % 4; c++)
            put(&t, " %d", base + 1 + (int)(rng() % 300));
        put(&t, "\n");
    }
    put(&t, "o crossing\n");
    int b2 = base + 300;
    for (int k = 0; k < 9; k++)
        put(&t, "v %g %g %g\n", 5 * (frand() - 0.5), 5 * (frand() - 0.5), 2 * (frand() - 0.5));
    put(&t, "f %d %d %d\nf %d %d %d\nf %d %d %d\n", b2 + 1, b2 + 2, b2 + 3, b2 + 4, b2 + 5, b2 + 6, b2 + 7,
        b2 + 8, b2 + 9);
    put(&t, "l %d %d %d %d\n", b2 + 1, b2 + 5, b2 + 9, b2 + 1);
    put(&t, "p %d %d\n", b2 + 2, b2 + 3);
    cr_assert_eq(tl_scene_from_text(s, "mixed.obj", t.p), 0);
    free(t.p);
    cr_assert_gt(s->npoints, 600);
    cr_assert_gt(s->nsegs, 10);
}

static const PrimStyle styles[] = {
    { 1, 1, 0, 0, 0, 0 }, { 2, 1, 1, 0, 2, 0 }, { 3, 2, 0, 0, 0, 0 }, { 5, 3, 1, 0, 0, 0 }, { 1, 1, 1, 1, 0, 0 }, { 6, 3, 0, 0, 3, 0 },
};

/* Every algorithm against the z-buffer on the scene's seeded views. */
static void agree_views(Scene *s, const char *what, int nviews, int wire)
{
    static const int sizes[3][2] = { { 64, 40 }, { 160, 96 }, { 333, 190 } };
    TlAgree a = { 0 };
    char msg[512];
    int k = 0;
    for (uint32_t seed = 1; seed <= (uint32_t)nviews; seed++)
        for (int persp = 0; persp <= 1; persp++) {
            tl_random_view(s, seed * 31 + (uint32_t)persp, persp);
            const int *sz = sizes[seed % 3];
            Viewport vp = { sz[0], sz[1], seed % 2 ? 2.0f : 1.0f, (int)(seed % 4 == 3) };
            a.style = styles[k++ % (int)(sizeof styles / sizeof styles[0])];
            a.style.wire |= wire;
            for (int threads = 1; threads <= 2; threads++) {
                long n = tl_agree(&a, s, &vp, threads, msg, sizeof msg);
                cr_assert_eq(n, 0, "%s, view %u %s, size %d width %d wire %d: %s", what, seed,
                             persp ? "persp" : "ortho", a.style.point_size, a.style.line_width, a.style.wire, msg);
            }
            cr_assert_gt(a.sp.npolys, a.sp.prim_first, "%s: points and lines reached the algorithms", what);
        }
    tl_agree_free(&a);
}

Test(prims, every_algorithm_agrees_on_points_and_lines)
{
    for (uint32_t seed = 1; seed <= 3; seed++) {
        Scene s;
        mixed_scene(&s, seed);
        agree_views(&s, "mixed", 6, 0);
        scene_free(&s);
    }
}

Test(prims, every_algorithm_agrees_with_the_wireframe_of_the_assets)
{
    static const char *const assets[] = { "assets/cube.obj", "assets/knot.obj", "assets/star-pierce.obj",
                                          "assets/concave.obj" };
    for (size_t i = 0; i < sizeof assets / sizeof assets[0]; i++) {
        Scene s;
        cr_assert_eq(tl_scene_from_file(&s, assets[i]), 0);
        agree_views(&s, assets[i], 4, 1);
        scene_free(&s);
    }
}

Test(prims, every_algorithm_agrees_on_grid_copies_of_points)
{
    Scene s;
    mixed_scene(&s, 9);
    cr_assert_eq(scene_make_grid(&s, 2, E, sizeof E), 0, "%s", E);
    cr_assert_eq(s.npoints, 8 * s.objs[0].point_count + 8 * s.objs[1].point_count);
    agree_views(&s, "grid", 3, 0);
    scene_free(&s);
}

/* --order after the points and lines: the octree finds them anywhere. */
Test(prims, octree_finds_points_and_lines_reordered)
{
    Scene s;
    mixed_scene(&s, 4);
    for (int order = ORDER_FRONT; order < ORDER_COUNT; order++) {
        tl_random_view(&s, 7, order == ORDER_BACK);
        Viewport vp = { 120, 80, 1.0f, 0 };
        ScreenPolys sp = { 0 };
        PrimWork *w = NULL;
        ReorderScratch rs = { 0 };
        PrimStyle st = { 2, 1, 1, 0, 0, 0 };
        cr_assert_eq(tl_project(&sp, &s, &vp, &st, &w), 0);
        cr_assert_eq(screen_reorder(&sp, (PolyOrder)order, 3, &rs), 0);
        HsrInput in = { .sp = &sp, .scene = &s, .vp = &vp };
        FrameBufs ref = { 0 }, fb = { 0 };
        HsrStats st2;
        HsrRunner r;
        cr_assert_eq(hsr_runner_init(&r, &hsr_zbuffer, 1), 0);
        cr_assert_eq(hsr_run(&r, &in, &ref, &st2), 0);
        hsr_runner_free(&r);
        cr_assert_eq(hsr_runner_init(&r, hsr_find("hzb-octree"), 2), 0);
        cr_assert_eq(hsr_run(&r, &in, &fb, &st2), 0);
        hsr_runner_free(&r);
        int fx, fy;
        cr_assert_eq(tl_diff(&ref, &fb, &fx, &fy), 0, "order %d: first difference at (%d,%d)", order, fx, fy);
        fbuf_free(&ref);
        fbuf_free(&fb);
        reorder_free(&rs);
        prims_free(&w);
        screen_free(&sp);
    }
    scene_free(&s);
}

/* ==== the one-square-per-box reduction ==== */

/* A cloud of n points on a coarse grid (many at one position, more in
 * one sample box), some with colours. */
static void cloud_scene(Scene *s, int n, float step, uint32_t seed)
{
    rng_state = seed;
    Text t = { 0 };
    for (int k = 0; k < n; k++)
        put(&t, "v %g %g %g\n", step * (int)(rng() % 11) - 5 * step, step * (int)(rng() % 11) - 5 * step,
            step * (int)(rng() % 11) - 5 * step);
    cr_assert_eq(tl_scene_from_text(s, "cloud.obj", t.p), 0);
    free(t.p);
    cr_assert_eq(s->npoints, (uint32_t)n, "vertices alone are a cloud");
}

Test(prims, one_square_per_box_gives_the_buffers_of_every_point)
{
    Scene s;
    cloud_scene(&s, 20000, 0.2f, 77);
    static const int sizes[3][2] = { { 40, 24 }, { 160, 96 }, { 320, 192 } };
    for (uint32_t seed = 1; seed <= 8; seed++) {
        int persp = seed % 2;
        tl_random_view(&s, seed, persp);
        const int *sz = sizes[seed % 3];
        Viewport vp = { sz[0], sz[1], seed % 3 ? 1.0f : 2.0f, 0 };
        int size = 1 + (int)(seed % 4);
        /* squares on whole pixels of 2 or 3 samples too */
        int pixel = size % 3 == 0 ? 3 : size % 2 == 0 && seed % 4 ? 2 : 1;
        ScreenPolys all = { 0 }, kept = { 0 };
        PrimWork *w = NULL;
        PrimStyle st_all = { size, 1, 0, 1, pixel, 0 }, st_kept = { size, 1, 0, 0, pixel, 0 };
        FrameBufs ref = { 0 }, fb = { 0 };
        HsrStats hs;
        cr_assert_eq(tl_project(&all, &s, &vp, &st_all, &w), 0);
        cr_assert_eq(tl_project(&kept, &s, &vp, &st_kept, &w), 0);
        cr_assert_eq(all.points_in, kept.points_in);
        cr_assert_eq(all.points_drawn, all.points_in);
        cr_assert_lt(kept.points_drawn, kept.points_in / 2, "view %u: %u of %u kept", seed, kept.points_drawn,
                     kept.points_in);
        for (int a = 0; a < hsr_nalgos; a++) {
            HsrInput ia = { .sp = &all, .scene = &s, .vp = &vp };
            HsrInput ik = { .sp = &kept, .scene = &s, .vp = &vp };
            HsrRunner r;
            cr_assert_eq(hsr_runner_init(&r, &hsr_zbuffer, 1), 0);
            cr_assert_eq(hsr_run(&r, &ia, &ref, &hs), 0);
            hsr_runner_free(&r);
            cr_assert_eq(hsr_runner_init(&r, hsr_algos[a], 1 + a % 2), 0);
            cr_assert_eq(hsr_run(&r, &ik, &fb, &hs), 0);
            hsr_runner_free(&r);
            int fx, fy;
            long d = tl_diff(&ref, &fb, &fx, &fy);
            cr_assert_eq(d, 0, "view %u size %d: %s on the kept squares differs from every point drawn in %ld "
                               "pixels, first (%d,%d)", seed, size, hsr_algos[a]->name, d, fx, fy);
        }
        fbuf_free(&ref);
        fbuf_free(&fb);
        screen_free(&all);
        screen_free(&kept);
        prims_free(&w);
    }
    scene_free(&s);
}

Test(prims, the_reduction_splits_between_threads_alike)
{
    /* enough points for helper threads: the boxes are merged by the same
     * minimum, so the squares are the same on one thread or four */
    Scene s;
    Mesh *m = calloc(1, sizeof *m);
    cr_assert_eq(tl_mesh_init(m, "big"), 0);
    rng_state = 5;
    for (int k = 0; k < 600000; k++)
        cr_assert_eq(tl_mesh_vertex(m, frand(), frand(), frand()), 0);
    cr_assert_eq(tl_mesh_finish(m), 0);
    cr_assert_eq(scene_build(&s, m, 1, E, sizeof E), 0, "%s", E);
    tl_random_view(&s, 3, 1);
    Viewport vp = { 200, 120, 1.0f, 0 };
    ScreenPolys a = { 0 }, b = { 0 };
    a.threads = 1;
    b.threads = 4;
    PrimWork *wa = NULL, *wb = NULL;
    cr_assert_eq(tl_project(&a, &s, &vp, NULL, &wa), 0);
    cr_assert_eq(tl_project(&b, &s, &vp, NULL, &wb), 0);
    cr_assert_eq(a.npolys, b.npolys);
    cr_assert_eq(memcmp(a.polys, b.polys, a.npolys * sizeof *a.polys), 0);
    cr_assert_eq(memcmp(a.verts, b.verts, a.nverts * sizeof *a.verts), 0);
    screen_free(&a);
    screen_free(&b);
    prims_free(&wa);
    prims_free(&wb);
    scene_free(&s);
}

/* ==== geometry ==== */

static int covered(const FrameBufs *fb, int32_t id)
{
    int n = 0;
    for (int i = 0; i < fb->w * fb->h; i++)
        n += fb->ids[i] == id;
    return n;
}

Test(prims, a_point_covers_size_by_size_samples)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "p.obj", "v 0 0 0\nv 1 1 1\nv -1 -1 -1\np 1\n"), 0);
    cr_assert_eq(s.npoints, 1);
    tl_random_view(&s, 2, 0);
    s.cam.yaw = s.cam.pitch = s.cam.roll = 0;
    s.cam.pan = v3(0, 0, 0);
    for (int size = 1; size <= 6; size++) {
        ScreenPolys sp = { 0 };
        PrimWork *w = NULL;
        FrameBufs fb = { 0 };
        HsrStats hs;
        Viewport vp = { 41, 31, 1.0f, 0 };
        PrimStyle st = { size, 1, 0, 0, 0, 0 };
        cr_assert_eq(tl_project(&sp, &s, &vp, &st, &w), 0);
        HsrInput in = { .sp = &sp, .scene = &s, .vp = &vp };
        HsrRunner r;
        cr_assert_eq(hsr_runner_init(&r, &hsr_zbuffer, 1), 0);
        cr_assert_eq(hsr_run(&r, &in, &fb, &hs), 0);
        hsr_runner_free(&r);
        cr_assert_eq(covered(&fb, 0), size * size, "size %d", size);
        fbuf_free(&fb);
        prims_free(&w);
        screen_free(&sp);
    }
    scene_free(&s);
}

Test(prims, ids_follow_the_faces_in_load_order)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "ids.obj",
                                    "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\np 1 2\nl 1 2 3\n"
                                    "o b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\nf 4 6 5\np 6\nl 4 5\n"),
                 0);
    cr_assert_eq(s.nfaces, 3);
    cr_assert_eq(s.npoints, 3);
    cr_assert_eq(s.nlines, 2);
    cr_assert_eq(s.nsegs, 3);
    cr_assert_eq(s.nprims, 6);
    /* faces 0..2, then a's points 3 4, b's point 5, a's segments 6 7, b's 8 */
    int obj;
    uint32_t k;
    cr_assert_eq(scene_prim_of(&s, 2, &obj, &k), PRIM_FACE);
    cr_assert_eq(obj, 1);
    cr_assert_eq(scene_prim_of(&s, 4, &obj, &k), PRIM_POINT);
    cr_assert(obj == 0 && k == 1);
    cr_assert_eq(scene_prim_of(&s, 5, &obj, &k), PRIM_POINT);
    cr_assert(obj == 1 && k == 0);
    cr_assert_eq(object_point_vert(&s.objs[1], 0), 5);
    cr_assert_eq(scene_prim_of(&s, 7, &obj, &k), PRIM_SEG);
    cr_assert(obj == 0 && k == 1);
    uint32_t v[2];
    scene_edge_verts(&s, &s.objs[0], PRIM_SEG, 1, v);
    cr_assert(v[0] == 1 && v[1] == 2);
    cr_assert_eq(scene_prim_of(&s, 8, &obj, &k), PRIM_SEG);
    cr_assert(obj == 1 && k == 0);
    cr_assert_eq(scene_prim_of(&s, 9, &obj, &k), PRIM_NONE);
    cr_assert_eq(scene_prim_of(&s, -1, &obj, &k), PRIM_NONE);
    /* the wireframe's edges come last: a's 3, b's 3 (its two faces share them) */
    cr_assert_eq(scene_wire_build(&s, E, sizeof E), 0, "%s", E);
    cr_assert_eq(s.nwire, 6);
    cr_assert_eq(scene_prim_of(&s, 9, &obj, &k), PRIM_WIRE);
    cr_assert(obj == 0 && k == 0);
    cr_assert_eq(scene_prim_of(&s, 14, &obj, &k), PRIM_WIRE);
    cr_assert(obj == 1 && k == 2);
    scene_free(&s);
}

Test(prims, wireframe_edges_are_the_faces_outlines_once)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/cube.obj"), 0);
    cr_assert_eq(scene_wire_build(&s, E, sizeof E), 0, "%s", E);
    cr_assert_eq(s.nwire, 12, "a cube has 12 edges");
    scene_free(&s);
    /* a quad that is not planar is split into two triangles: their
     * diagonal is no edge of the face */
    cr_assert_eq(tl_scene_from_text(&s, "q.obj", "v 0 0 0\nv 1 0 0\nv 1 1 1\nv 0 1 0\nf 1 2 3 4\n"), 0);
    cr_assert_eq(s.npolys, 2);
    cr_assert_eq(scene_wire_build(&s, E, sizeof E), 0, "%s", E);
    cr_assert_eq(s.nwire, 4);
    scene_free(&s);
}

Test(prims, a_wireframe_edge_wins_against_its_own_face)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "t.obj", "v -1 -1 0\nv 1 -1 0.5\nv 0 1 -0.3\nf 1 2 3\n"), 0);
    TlView v = { 0.3f, 0.2f, 0, 0.3f, 0.2f, 0, 0.8f, 0, 0, 0, 50 };
    tl_set_view(&s, &v);
    ScreenPolys sp = { 0 };
    PrimWork *w = NULL;
    FrameBufs fb = { 0 };
    HsrStats hs;
    Viewport vp = { 120, 90, 1.0f, 0 };
    PrimStyle st = { 1, 1, 1, 0, 0, 0 };
    cr_assert_eq(tl_project(&sp, &s, &vp, &st, &w), 0);
    HsrInput in = { .sp = &sp, .scene = &s, .vp = &vp };
    HsrRunner r;
    cr_assert_eq(hsr_runner_init(&r, &hsr_zbuffer, 1), 0);
    cr_assert_eq(hsr_run(&r, &in, &fb, &hs), 0);
    hsr_runner_free(&r);
    /* each edge shows along its whole length, over the face inside */
    for (int e = 0; e < 3; e++)
        cr_assert_gt(covered(&fb, 1 + e), 40, "edge %d: %d pixels", e, covered(&fb, 1 + e));
    cr_assert_gt(covered(&fb, 0), 500);
    fbuf_free(&fb);
    prims_free(&w);
    screen_free(&sp);
    scene_free(&s);
}

/* The lines of obj rendered under view v at 120 x 90 by the z-buffer into fb; sp kept for its
 * projection. */
static void line_frame(const char *obj, const TlView *v, ScreenPolys *sp, FrameBufs *fb)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "l.obj", obj), 0);
    tl_set_view(&s, v);
    PrimWork *w = NULL;
    Viewport vp = { 120, 90, 1.0f, 0 };
    PrimStyle st = { 1, 1, 0, 0, 0, 0 };
    cr_assert_eq(tl_project(sp, &s, &vp, &st, &w), 0);
    HsrInput in = { .sp = sp, .scene = &s, .vp = &vp };
    cr_assert_eq(tl_render_poisoned(&hsr_zbuffer, 1, &in, fb), 0);
    prims_free(&w);
    scene_free(&s);
}

Test(prims, a_line_through_the_near_plane_is_cut_there_not_turned)
{
    /* A (z -1) and M (z 0.5) in front of the eye, B (z 1) behind it, on
     * one line off the axis. Both scenes fit the same box (the second
     * line, at z 1 behind the eye, draws nothing): centre 0, the eye at
     * 0.81 at zoom 4.2, the near plane 0.017 before it. The part of
     * A -> B the camera sees is A -> M and on past M (off the picture's
     * right edge, M at x 155): every sample of A -> M is one of A -> B,
     * at its depth, and A -> B has no more. A far end left behind the
     * eye projects to the other side: the line would turn back through
     * the centre. */
    const char *pts = "v 0.3 0.2 -1\nv 0.3 0.2 0.5\nv 0.3 0.2 1\nv -1 -1 1\nv 1 1 1\nl 4 5\n";
    char ab[160], am[160];
    snprintf(ab, sizeof ab, "%sl 1 3\n", pts);
    snprintf(am, sizeof am, "%sl 1 2\n", pts);
    TlView v = { 0, 0, 0, 0, 0, 0, 4.2f, 0, 0, 1, 50 };
    ScreenPolys spb = { 0 }, spm = { 0 };
    FrameBufs fb = { 0 }, fm = { 0 };
    line_frame(ab, &v, &spb, &fb);
    line_frame(am, &v, &spm, &fm);
    /* the view is as said: B behind the eye, M in front of the near plane */
    cr_assert(spb.persp && spb.eye_z < 1 && spb.eye_z - 0.5f > spb.near_z, "eye %g near %g", spb.eye_z, spb.near_z);
    int nm = 0, both = 0, nb = 0;
    for (int i = 0; i < fm.w * fm.h; i++) {
        nb += fb.ids[i] == 1;
        if (fm.ids[i] != 1)
            continue;
        nm++;
        if (fb.ids[i] == 1 && fabsf(fb.depth[i] - fm.depth[i]) <= 1e-4f * fabsf(fm.depth[i]))
            both++;
    }
    cr_assert_gt(nm, 30, "A -> M crosses the picture from A to its right edge: %d samples", nm);
    cr_assert_geq(both, nm - 2, "A -> B covers %d of A -> M's %d samples at their depth", both, nm);
    cr_assert_leq(nb, nm + 2, "A -> B has %d samples, A -> M %d: it goes no further on the picture", nb, nm);
    fbuf_free(&fb);
    fbuf_free(&fm);
    screen_free(&spb);
    screen_free(&spm);
}

/* ==== shading ==== */

Test(prims, points_take_their_vertex_colours)
{
    Scene s;
    Pipeline p;
    cr_assert_eq(tl_scene_from_text(&s, "c.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\np 1 2 3\n"), 0);
    cr_assert_eq(pipeline_init(&p, &s, &hsr_zbuffer, 1), 0);
    p.point_size = 3;
    cr_assert_eq(pipeline_render(&p, 30, 30, 1.0f, 0, 1), 0);
    int seen[3] = { 0 };
    for (int i = 0; i < 900; i++) {
        const uint8_t *c = &p.img.rgb[3 * i];
        if (!p.img.lit[i])
            continue;
        for (int k = 0; k < 3; k++)
            if (c[k] == 255 && c[(k + 1) % 3] == 0 && c[(k + 2) % 3] == 0)
                seen[k]++;
    }
    cr_assert(seen[0] == 9 && seen[1] == 9 && seen[2] == 9, "red %d green %d blue %d", seen[0], seen[1], seen[2]);
    cr_assert_null(frame_empty_reason(&p));
    pipeline_free(&p);
    scene_free(&s);
}

Test(prims, uncoloured_points_fade_with_depth)
{
    Scene s;
    Pipeline p;
    cr_assert_eq(tl_scene_from_text(&s, "d.obj", "v 0 0 1\nv 1 0 0\nv 2 0 -1\n"), 0);
    cr_assert_eq(pipeline_init(&p, &s, &hsr_zbuffer, 1), 0);
    p.samples = 1;
    cr_assert_eq(pipeline_render(&p, 40, 20, 1.0f, 0, 1), 0);
    int lo = 255, hi = 0;
    for (int i = 0; i < 800; i++)
        if (p.img.lit[i]) {
            lo = p.img.rgb[3 * i] < lo ? p.img.rgb[3 * i] : lo;
            hi = p.img.rgb[3 * i] > hi ? p.img.rgb[3 * i] : hi;
        }
    cr_assert_eq(hi, 204, "the nearest at the default colour");
    cr_assert_eq(lo, (int)lroundf(204 * PRIM_FAR_SHADE), "the farthest at 40%%");
    pipeline_free(&p);
    scene_free(&s);
}

/* ==== loaders ==== */

static Mesh M;

static void teardown(void) { mesh_free(&M); }

static int lenient(const char *path, const char *text)
{
    MeshLoadOpts o = { .strict = 0 };
    mesh_free(&M);
    return mesh_parse_buffer_ex(&M, path, &o, text, strlen(text), E, sizeof E);
}

static int strict(const char *path, const char *text)
{
    mesh_free(&M);
    return mesh_parse_buffer(&M, path, NULL, text, strlen(text), E, sizeof E);
}

TestSuite(load, .fini = teardown);

Test(load, obj_points_and_lines)
{
    cr_assert_eq(strict("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\np 1 -1\nl 1/1 2/2 3\nl 4 1\nf 1 2 3\n"), 0, "%s", E);
    cr_assert_eq(M.npoints, 2);
    cr_assert_eq(M.point[0], 0);
    cr_assert_eq(M.point[1], 3);
    cr_assert_eq(M.nlines, 2);
    cr_assert_eq(M.line_start[1], 3);
    cr_assert_eq(M.line_start[2], 5);
    cr_assert_eq(M.line_corner[3], 3);
    cr_assert_eq(M.objs[0].point_count, 2);
    cr_assert_eq(M.objs[0].line_count, 2);
    cr_assert_eq(M.objs[0].vert_max, 3);
    cr_assert_eq(strict("t.obj", "v 0 0 0\nl 1\n"), -1);
    cr_assert_str_eq(E, "t.obj:2: line has fewer than 2 vertices (1)");
    cr_assert_eq(strict("t.obj", "v 0 0 0\np 2\n"), -1);
    cr_assert_str_eq(E, "t.obj:2: vertex index 2 out of range (1 vertices)");
}

Test(load, an_object_of_points_only_is_kept)
{
    cr_assert_eq(strict("t.obj", "o faces\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no dots\np 1 2\no empty\n"), 0, "%s", E);
    cr_assert_eq(M.nobjs, 2);
    cr_assert_str_eq(M.objs[1].name, "dots");
    cr_assert_eq(M.objs[1].point_first, 0);
    cr_assert_eq(M.objs[1].point_count, 2);
    cr_assert_eq(M.objs[1].face_count, 0);
}

Test(load, lenient_obj_skips_and_counts, .init = cr_redirect_stderr)
{
    const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf\nwhatever 1 2\nf 1 2 40\nl 1 50\np 1 60 2\nv 1 x 0\n"
                       "v 1 1 0\nf 1 2 5\nf 1 4 5\n";
    /* strict: the first, as before */
    cr_assert_eq(strict("x.obj", text), -1);
    cr_assert_str_eq(E, "x.obj:5: face has fewer than 3 vertices (0)");
    /* lenient: the empty face, the unknown keyword, the three statements
     * with indices past the end, the unreadable vertex and the face
     * using it (face 1 2 5 still means what the file meant: the
     * unreadable vertex itself goes, vertex 5 becomes the fourth) */
    cr_assert_eq(lenient("x.obj", text), 0, "%s", E);
    cr_assert_eq(M.info.skipped, 7);
    cr_assert_str_eq(M.info.first_skipped, "x.obj:5: face has fewer than 3 vertices (0)");
    cr_assert_eq(M.nverts, 4);
    cr_assert_eq(M.nfaces, 2);
    cr_assert_eq(M.npoints, 0);
    cr_assert_eq(M.nlines, 0);
    cr_assert_eq(M.corner[5], 3);
    cr_assert(M.pos[9] == 1 && M.pos[10] == 1 && M.pos[11] == 0, "vertex 5 of the file (1 1 0)");
    fflush(stderr);
    cr_assert_stderr_eq_str("zview: warning: x.obj: 7 statements skipped (first: x.obj:5: face has fewer "
                            "than 3 vertices (0))\n");
}

Test(load, lenient_obj_with_nothing_left_fails_naming_the_first)
{
    cr_assert_eq(lenient("x.obj", "v 0 0 0\nf 1 2 3\nf 1 1\n"), -1);
    cr_assert_str_eq(E, "x.obj:2: vertex index 3 out of range (1 vertices) (2 statements skipped, nothing left to show)");
}

Test(load, xyz_colours_normals_and_headers)
{
    cr_assert_eq(strict("s.xyz", "# scan\n0 0 0 255 0 0\n1,2,3,0,128,255\n2;0;1 ; 10 ; 20 ; 30\n"), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "xyz");
    cr_assert_eq(M.nverts, 3);
    cr_assert_eq(M.npoints, 3);
    cr_assert_null(M.point);
    cr_assert_not_null(M.rgb);
    cr_assert_eq(M.rgb[0], 1.0f);
    cr_assert_eq(M.rgb[1], 0.0f);
    cr_assert_float_eq(M.rgb[5], 1.0f, 1e-6);
    cr_assert_eq(M.pos[3], 1.0f);
    cr_assert_eq(M.pos[5], 3.0f);
    /* 0..1 colours stay */
    cr_assert_eq(strict("s.xyz", "0 0 0 0.5 0.25 1\n1 1 1\n"), 0, "%s", E);
    cr_assert_eq(M.rgb[0], 0.5f);
    cr_assert_eq(M.rgb[3], 1.0f, "a point without colour is white");
    /* normals (some negative) are not colours */
    cr_assert_eq(strict("s.xyz", "0 0 0 0 0 1\n1 0 0 0 -1 0\n"), 0, "%s", E);
    cr_assert_null(M.rgb);
    /* .pts: a count, then x y z intensity r g b */
    cr_assert_eq(strict("s.pts", "2\n0 0 0 -1200 10 20 30\n1 1 1 300 40 50 60\n"), 0, "%s", E);
    cr_assert_eq(M.nverts, 2);
    cr_assert_float_eq(M.rgb[3], 40 / 255.0f, 1e-6);
    /* a header of column names */
    cr_assert_eq(strict("s.xyz", "X Y Z\n1 2 3\n"), 0, "%s", E);
    cr_assert_eq(M.nverts, 1);
}

Test(load, xyz_bad_lines, .init = cr_redirect_stderr)
{
    const char *text = "0 0 0\n1 1\n2 2 nan\n3 3 3\n";
    cr_assert_eq(strict("b.xyz", text), -1);
    cr_assert_str_eq(E, "b.xyz:2: a point needs x y z, got 2 numbers");
    cr_assert_eq(lenient("b.xyz", text), 0, "%s", E);
    cr_assert_eq(M.nverts, 2);
    cr_assert_eq(M.info.skipped, 2);
    cr_assert_eq(strict("b.xyz", "# nothing\n"), -1);
}

Test(load, xyz_told_by_content_or_name)
{
    /* numbers a line and no extension: plausibly xyz; a name that says so */
    cr_assert_eq(mesh_parse_buffer(&M, "scan", NULL, "1 2 3\n4 5 6\n", 12, E, sizeof E), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "xyz");
    mesh_free(&M);
    /* an OFF without its keyword has lines of different widths: not xyz */
    const char *off = "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    cr_assert_eq(mesh_parse_buffer(&M, "bare", NULL, off, strlen(off), E, sizeof E), -1);
    cr_assert_not_null(strstr(E, "not a model zview can read"), "%s", E);
    cr_assert(mesh_format_valid("xyz"));
}

Test(load, ply_cloud_colours_points)
{
    const char *ply = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                      "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n0 0 0 255 0 0\n1 1 1 0 0 255\n";
    cr_assert_eq(strict("c.ply", ply), 0, "%s", E);
    cr_assert_eq(M.npoints, 2);
    cr_assert_eq(M.rgb[0], 1.0f);
    cr_assert_eq(M.rgb[5], 1.0f);
}

Test(load, points_option_makes_every_vertex_a_point)
{
    cr_assert_eq(mesh_load(&M, "assets/cube.obj", E, sizeof E), 0, "%s", E);
    mesh_as_points(&M);
    cr_assert_eq(M.nfaces, 0);
    cr_assert_eq(M.npoints, 8);
    cr_assert_eq(M.nobjs, 1);
    cr_assert_eq(M.objs[0].point_count, 8);
    Scene s;
    Mesh *m = malloc(sizeof *m);
    *m = M;
    memset(&M, 0, sizeof M);
    cr_assert_eq(scene_build(&s, m, 1, E, sizeof E), 0, "%s", E);
    cr_assert_eq(s.npoints, 8);
    cr_assert_eq(s.nfaces, 0);
    scene_free(&s);
}

Test(load, points_option_keeps_the_objects)
{
    /* a and b share vertex 2; vertex 6 is used by nothing */
    const char *obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 5 1 0\nv 9 9 9\n"
                      "o a\nf 1 2 3\no b\nf 2 4 5\n";
    cr_assert_eq(strict("two.obj", obj), 0, "%s", E);
    cr_assert_eq(M.nobjs, 2);
    mesh_as_points(&M);
    cr_assert_eq(M.nfaces, 0);
    cr_assert_eq(M.npoints, 6, "every vertex a point, once");
    cr_assert_eq(M.nobjs, 2, "the objects stay");
    cr_assert_str_eq(M.objs[0].name, "a");
    cr_assert_eq(M.objs[0].point_count, 3);
    cr_assert_eq(M.objs[1].point_count, 3, "4, 5 and the unused 6 (2 went to a)");
    uint32_t want[6] = { 0, 1, 2, 3, 4, 5 };
    for (int i = 0; i < 6; i++)
        cr_assert_eq(M.point[i], want[i], "point %d", i);
    cr_assert_eq(M.objs[1].vert_min, 3);
    cr_assert_eq(M.objs[1].vert_max, 5);
}

/* ==== empty frames ==== */

static const char *empty_reason(const char *obj, float yaw, float pitch, int cull, float zoom, float pan, int persp)
{
    static char out[256];
    Scene s;
    Pipeline p;
    cr_assert_eq(tl_scene_from_text(&s, "e.obj", obj), 0);
    TlView v = { yaw, pitch, 0, yaw, pitch, 0, zoom, pan, 0, persp, 50 };
    tl_set_view(&s, &v);
    cr_assert_eq(pipeline_init(&p, &s, &hsr_zbuffer, 1), 0);
    cr_assert_eq(pipeline_render(&p, 40, 20, 1.0f, cull, 1), 0);
    const char *r = frame_empty_reason(&p);
    snprintf(out, sizeof out, "%s", r ? r : "(drawn)");
    pipeline_free(&p);
    scene_free(&s);
    return out;
}

Test(prims, an_empty_frame_says_why)
{
    const char *square = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
    cr_assert_str_eq(empty_reason(square, 0, 0, 0, 1, 0, 0), "(drawn)");
    cr_assert_str_eq(empty_reason(square, 1.5707964f, 0, 0, 1, 0, 0),
                     "the model is edge-on: try --view iso or turn with the arrow keys");
    cr_assert_not_null(strstr(empty_reason(square, 3.1415927f, 0, 1, 1, 0, 0), "culled as a back face"));
    cr_assert_not_null(strstr(empty_reason(square, 0, 0, 0, 1, 50, 0), "outside the picture"));
    cr_assert_not_null(strstr(empty_reason(square, 0, 0, 0, 0.001f, 0, 0), "covers no sample"));
}

Test(load, lenient_ply_and_off_skip_bad_faces, .init = cr_redirect_stderr)
{
    const char *head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
    char ply[1024];
    snprintf(ply, sizeof ply, "%s3 0 1 2\n3 0 1 7\n2 0 1\n3 0 x 2\n", head);
    cr_assert_eq(strict("a.ply", ply), -1);
    cr_assert_str_eq(E, "a.ply:14: vertex index 7 out of range (3 vertices)");
    cr_assert_eq(lenient("a.ply", ply), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_eq(M.info.skipped, 3);
    /* a file that ends inside the faces keeps those read */
    snprintf(ply, sizeof ply, "%s3 0 1 2\n3 0 1", head);
    cr_assert_eq(strict("a.ply", ply), -1);
    cr_assert_eq(lenient("a.ply", ply), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_geq(M.info.skipped, 1);
    /* binary, little endian: a face with an index past the end */
    char bin[512];
    int n = snprintf(bin, sizeof bin, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                      "property float y\nproperty float z\nelement face 2\n"
                                      "property list uchar int vertex_indices\nend_header\n");
    float v[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    memcpy(bin + n, v, sizeof v);
    n += (int)sizeof v;
    const int32_t f1[3] = { 0, 1, 2 }, f2[3] = { 0, 5, 2 };
    bin[n++] = 3;
    memcpy(bin + n, f1, sizeof f1);
    n += (int)sizeof f1;
    bin[n++] = 3;
    memcpy(bin + n, f2, sizeof f2);
    n += (int)sizeof f2;
    MeshLoadOpts o = { .strict = 0 };
    mesh_free(&M);
    cr_assert_eq(mesh_parse_buffer_ex(&M, "b.ply", &o, bin, (size_t)n, E, sizeof E), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_eq(M.info.skipped, 1);
    mesh_free(&M);
    cr_assert_eq(mesh_parse_buffer(&M, "b.ply", NULL, bin, (size_t)n, E, sizeof E), -1);
    cr_assert_not_null(strstr(E, "vertex index 5 out of range"), "%s", E);
    /* OFF */
    const char *off = "OFF\n3 3 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n1 0\n";
    cr_assert_eq(strict("c.off", off), -1);
    cr_assert_str_eq(E, "c.off:7: vertex index 3 out of range (3 vertices)");
    cr_assert_eq(lenient("c.off", off), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_eq(M.info.skipped, 2);
}

/* More than INT32_MAX faces and edges cannot be numbered: the wireframe
 * is refused, saying so, and every object is left without wire edges.
 * A scene that big takes gigabytes, so an object's mark count stands in
 * for the rest of them; a sentinel object past the end of the scene's
 * array must come out as it went in (the reset touches the scene's
 * objects only). */
Test(prims, a_wireframe_past_the_ids_is_refused_and_leaves_no_edges)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/cube.obj"), 0);
    Object *o = realloc(s.objs, ((size_t)s.nobjs + 1) * sizeof *o);
    cr_assert(o);
    s.objs = o;
    memset(&o[s.nobjs], 0, sizeof o[s.nobjs]);
    o[s.nobjs].wire_count = 77;
    o[0].mark_count = INT32_MAX;
    char err[128] = "";
    cr_assert_eq(scene_wire_build(&s, err, sizeof err), -1);
    cr_assert_str_eq(err, "--wireframe: more than 2147483647 faces and edges");
    for (int k = 0; k < s.nobjs; k++)
        cr_assert_eq(s.objs[k].wire_count, 0);
    cr_assert_null(s.wire);
    cr_assert_eq(s.nwire_edges, 0);
    cr_assert_eq(o[s.nobjs].wire_count, 77, "the object past the scene's was written");
    o[0].mark_count = 0;
    scene_free(&s);
}
