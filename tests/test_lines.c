/* test_lines.c: segments and wireframe edges given as their samples
 * (prims.c, issue 28). A quad of a few samples, and every quad past one
 * per 4 samples of the picture, becomes one-sample squares at the
 * nearest (depth, id) per sample. The reference is every quad drawn
 * whole (PrimStyle.all_prims), rendered by the z-buffer: every
 * algorithm on the reduced polygons must give its buffers byte for
 * byte. The bound: what reaches the algorithms is bounded by the
 * picture, however many copies of however many lines. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "testlib.h"

static char E[512];

static uint32_t rng_state = 1;
static uint32_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}
static float frand(void) { return (float)(rng() & 0xffffff) / (float)0x1000000; }

/* A sword of quads: a blade 1 long and 0.06 wide, 0.01 thick, in
 * `stations` rings of 4 vertices joined by quads (its faces' edges are
 * long and thin, as sword-quads.obj's are), and a cross-guard box. */
static void sword_mesh(Mesh *m, int stations)
{
    cr_assert_eq(tl_mesh_init(m, "sword.obj"), 0);
    cr_assert_eq(tl_mesh_object(m, "blade"), 0);
    for (int k = 0; k < stations; k++) {
        float y = (float)k / (float)(stations - 1), taper = 1 - 0.8f * y * y;
        float w = 0.03f * taper, t = 0.005f * taper;
        cr_assert_eq(tl_mesh_vertex(m, -w, y, 0), 0);
        cr_assert_eq(tl_mesh_vertex(m, 0, y, t), 0);
        cr_assert_eq(tl_mesh_vertex(m, w, y, 0), 0);
        cr_assert_eq(tl_mesh_vertex(m, 0, y, -t), 0);
    }
    for (int k = 0; k + 1 < stations; k++)
        for (int c = 0; c < 4; c++) {
            uint32_t q[4] = { (uint32_t)(4 * k + c), (uint32_t)(4 * k + (c + 1) % 4),
                              (uint32_t)(4 * (k + 1) + (c + 1) % 4), (uint32_t)(4 * (k + 1) + c) };
            cr_assert_eq(tl_mesh_face(m, q, 4), 0);
        }
    cr_assert_eq(tl_mesh_object(m, "guard"), 0);
    uint32_t b = (uint32_t)(4 * stations);
    for (int k = 0; k < 8; k++)
        cr_assert_eq(tl_mesh_vertex(m, k & 1 ? 0.15f : -0.15f, k & 2 ? 0.02f : -0.02f, k & 4 ? 0.02f : -0.02f), 0);
    static const uint32_t box[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 },
                                        { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
    for (int f = 0; f < 6; f++) {
        uint32_t q[4] = { b + box[f][0], b + box[f][1], b + box[f][2], b + box[f][3] };
        cr_assert_eq(tl_mesh_face(m, q, 4), 0);
    }
    cr_assert_eq(tl_mesh_finish(m), 0);
}

static void sword_scene(Scene *s, int stations, int grid)
{
    Mesh *m = calloc(1, sizeof *m);
    cr_assert_not_null(m);
    sword_mesh(m, stations);
    cr_assert_eq(scene_build(s, m, 1, E, sizeof E), 0, "%s", E);
    if (grid > 1)
        cr_assert_eq(scene_make_grid(s, grid, E, sizeof E), 0, "%s", E);
}

/* The view zview --wireframe --grid N -s 8x6 gives (yaw 60, pitch 25,
 * fitted there), orthographic or with a wide perspective. */
static void sword_view(Scene *s, int persp, float fov)
{
    float yaw = 60 * (float)M_PI / 180, pitch = 25 * (float)M_PI / 180;
    TlView v = { yaw, pitch, 0, yaw, pitch, 0, 1, 0, 0, persp, fov };
    tl_set_view(s, &v);
}

/* Project s at vp with style st, reduced and with every quad whole;
 * render every quad whole with the z-buffer on one thread, and the
 * reduced polygons with every algorithm on one and two threads; fail
 * on the first difference. *out gets the reduced projection's counts. */
static void reduced_draws_every_quad(Scene *s, const Viewport *vp, const PrimStyle *st, const char *what,
                                     ScreenPolys *out)
{
    ScreenPolys red = { 0 }, all = { 0 };
    PrimWork *wr = NULL, *wa = NULL;
    PrimStyle sa = *st;
    sa.all_prims = 1;
    cr_assert_eq(tl_project(&red, s, vp, st, &wr), 0);
    cr_assert_eq(tl_project(&all, s, vp, &sa, &wa), 0);
    cr_assert_eq(red.edges_in, all.edges_in);
    cr_assert_eq(all.edges_sampled, 0);
    cr_assert_eq(all.edge_squares, 0);
    FrameBufs ref = { 0 }, fb = { 0 };
    HsrInput ia = { .sp = &all, .scene = s, .vp = vp }, ir = { .sp = &red, .scene = s, .vp = vp };
    cr_assert_eq(tl_render_poisoned(&hsr_zbuffer, 1, &ia, &ref), 0);
    for (int a = 0; a < hsr_nalgos; a++)
        for (int threads = 1; threads <= 2; threads++) {
            cr_assert_eq(tl_render_poisoned(hsr_algos[a], threads, &ir, &fb), 0);
            int fx, fy;
            long d = tl_diff(&ref, &fb, &fx, &fy);
            size_t i = d ? (size_t)fy * (size_t)vp->w + (size_t)fx : 0;
            cr_assert_eq(d, 0,
                         "%s, %dx%d: %s on %d thread(s) over the lines given as samples differs from the "
                         "z-buffer over every quad in %ld samples; first (%d,%d): id %d depth %.9g, want id %d "
                         "depth %.9g (%u quads, %u as samples)",
                         what, vp->w, vp->h, hsr_algos[a]->name, threads, d, fx, fy, fb.ids[i], (double)fb.depth[i],
                         ref.ids[i], (double)ref.depth[i], red.edges_drawn, red.edges_sampled);
        }
    *out = red;
    out->verts = NULL;
    out->polys = NULL;
    out->map = NULL;
    out->map_first = NULL;
    out->work = NULL;
    fbuf_free(&ref);
    fbuf_free(&fb);
    prims_free(&wr);
    prims_free(&wa);
    screen_free(&red);
    screen_free(&all);
}

/* Issue 28: --wireframe --grid 8 of a sword of quads at -s 8x6 took
 * 2-6.5 GB and 6-45 s in every algorithm: every edge of the 512 copies
 * became a quad of its own, and the algorithms drew them all on 48
 * samples. Now the polygons the lines add are bounded by the picture:
 * at most a square per sample and a quad per 4 samples, whatever the
 * copies; and every algorithm still gives the buffers of every quad. */
Test(lines, copies_of_lines_on_a_tiny_picture_cost_the_picture)
{
    Scene s;
    sword_scene(&s, 120, 8);
    cr_assert_eq(s.nobjs, 2 * 512);
    PrimStyle st = { 1, 1, 1, 0, 0, 0 };
    for (int persp = 0; persp <= 1; persp++) {
        sword_view(&s, persp, 150);
        Viewport vp = { 8, 6, 1.0f, 0 };
        ScreenPolys r;
        reduced_draws_every_quad(&s, &vp, &st, persp ? "persp 150" : "ortho", &r);
        uint32_t samples = (uint32_t)(vp.w * vp.h), lines = r.edges_drawn + r.edge_squares;
        cr_assert_gt(r.edges_in, 200000, "%u edges on the screen", r.edges_in);
        cr_assert_leq(lines, samples + samples / 4, "%u polygons for the lines of a %u-sample picture", lines,
                      samples);
        cr_assert_eq(r.npolys - r.prim_first, lines);
    }
    scene_free(&s);
}

/* The bound does not grow with the copies: a grid of 2 and of 8 give at
 * most the same number of polygons for the lines. */
Test(lines, the_polygons_do_not_grow_with_the_copies)
{
    uint32_t most = 0;
    for (int grid = 2; grid <= 8; grid += 6) {
        Scene s;
        sword_scene(&s, 60, grid);
        sword_view(&s, 1, 90);
        ScreenPolys sp = { 0 };
        PrimWork *w = NULL;
        Viewport vp = { 16, 12, 2.0f, 0 };
        PrimStyle st = { 1, 1, 1, 0, 0, 0 };
        cr_assert_eq(tl_project(&sp, &s, &vp, &st, &w), 0);
        uint32_t lines = sp.npolys - sp.prim_first;
        cr_assert_leq(lines, 16 * 12 + 16 * 12 / 4, "grid %d: %u polygons", grid, lines);
        most = lines > most ? lines : most;
        if (grid == 8)
            cr_assert_gt(sp.edges_in, 40 * most, "%u edges on the screen for %u polygons", sp.edges_in, most);
        prims_free(&w);
        screen_free(&sp);
        scene_free(&s);
    }
}

/* Many long lines over a small picture: past one whole quad per 4
 * samples, long quads are given as their samples too (rows of several
 * crossings' intervals), and draw what they drew. */
Test(lines, past_the_budget_long_quads_are_given_as_samples)
{
    for (uint32_t seed = 1; seed <= 6; seed++) {
        rng_state = seed * 7919;
        Scene s;
        Mesh *m = calloc(1, sizeof *m);
        cr_assert_eq(tl_mesh_init(m, "long.obj"), 0);
        for (int k = 0; k < 2000; k++)
            cr_assert_eq(tl_mesh_vertex(m, 2 * frand() - 1, 2 * frand() - 1, 2 * frand() - 1), 0);
        for (uint32_t k = 0; k + 1 < 2000; k += 2) {
            uint32_t l[2] = { k, k + 1 };
            cr_assert_eq(tl_mesh_line(m, l, 2), 0);
        }
        uint32_t tri[3] = { 0, 2, 4 };
        cr_assert_eq(tl_mesh_face(m, tri, 3), 0);
        cr_assert_eq(tl_mesh_finish(m), 0);
        cr_assert_eq(scene_build(&s, m, 1, E, sizeof E), 0, "%s", E);
        tl_random_view(&s, seed, seed % 2);
        Viewport vp = { 16 + (int)(seed * 3), 10 + (int)(seed * 2), seed % 3 ? 1.0f : 2.0f, 0 };
        PrimStyle st = { 1, 1 + (int)(seed % 4), 0, 0, 1 + (int)(seed % 3 == 2), 0 };
        ScreenPolys r;
        char what[64];
        snprintf(what, sizeof what, "seed %u, width %d", seed, st.line_width);
        reduced_draws_every_quad(&s, &vp, &st, what, &r);
        uint32_t samples = (uint32_t)(vp.w * vp.h);
        cr_assert_eq(r.edges_drawn, samples / 4, "%s: whole quads up to the budget (%u)", what, r.edges_drawn);
        cr_assert_gt(r.edges_sampled, 300, "%s: %u as samples of %u", what, r.edges_sampled, r.edges_in);
        cr_assert_leq(r.edge_squares, samples);
        scene_free(&s);
    }
}

/* Scenes of lines of every width, supersampled or not, at sizes where
 * some quads are small and some are not: the mixed front end draws
 * what every quad whole draws. */
Test(lines, quads_given_as_samples_draw_what_they_drew)
{
    static const char *const assets[] = { "assets/knot.obj", "assets/cube.obj", "assets/star-pierce.obj" };
    static const int sizes[4][2] = { { 7, 5 }, { 33, 21 }, { 80, 50 }, { 161, 97 } };
    for (size_t f = 0; f < sizeof assets / sizeof assets[0]; f++) {
        Scene s;
        cr_assert_eq(tl_scene_from_file(&s, assets[f]), 0);
        for (uint32_t seed = 1; seed <= 8; seed++) {
            tl_random_view(&s, seed * 13 + (uint32_t)f, seed % 2);
            const int *sz = sizes[seed % 4];
            Viewport vp = { sz[0], sz[1], seed % 3 ? 1.0f : 2.0f, (int)(seed % 5 == 4) };
            PrimStyle st = { 1, 1 + (int)(seed % 3), 1, 0, 1 + (int)(seed % 4 == 1), 0 };
            ScreenPolys r;
            char what[96];
            snprintf(what, sizeof what, "%s view %u width %d", assets[f], seed, st.line_width);
            reduced_draws_every_quad(&s, &vp, &st, what, &r);
        }
        scene_free(&s);
    }
}

/* The per-sample keys are left empty for the next frame: a frame after
 * another gives the polygons a first frame gives. */
Test(lines, a_frame_after_another_gives_the_same_polygons)
{
    Scene s;
    sword_scene(&s, 40, 3);
    PrimWork *w = NULL;
    ScreenPolys sp = { 0 };
    PrimStyle st = { 1, 1, 1, 0, 0, 0 };
    Viewport big = { 20, 14, 1.0f, 0 }, vp = { 12, 9, 1.0f, 0 };
    sword_view(&s, 0, 0);
    cr_assert_eq(tl_project(&sp, &s, &big, &st, &w), 0);
    cr_assert_gt(sp.edge_squares, 0);
    sword_view(&s, 1, 100);
    cr_assert_eq(tl_project(&sp, &s, &vp, &st, &w), 0);
    ScreenPolys fresh = { 0 };
    PrimWork *wf = NULL;
    cr_assert_eq(tl_project(&fresh, &s, &vp, &st, &wf), 0);
    cr_assert_gt(fresh.edge_squares, 0);
    cr_assert_eq(sp.npolys, fresh.npolys);
    cr_assert_eq(sp.nverts, fresh.nverts);
    cr_assert_eq(memcmp(sp.polys, fresh.polys, sp.npolys * sizeof *sp.polys), 0);
    cr_assert_eq(memcmp(sp.verts, fresh.verts, sp.nverts * sizeof *sp.verts), 0);
    prims_free(&w);
    prims_free(&wf);
    screen_free(&sp);
    screen_free(&fresh);
    scene_free(&s);
}
