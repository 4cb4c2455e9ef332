/* test_measure.c: the measuring mode's cursor and marks
 * (src/app/measuremarks.c). On a cube seen from three quarters, the
 * cursor's steps reach every vertex of a face turned to the viewer and
 * never the one hidden behind (a vertex of a convex solid shows when
 * one of its faces faces the viewer: an answer from the normals, not
 * from the depth buffer the cursor reads); each step goes the way of
 * its arrow on the screen; the marks measure what printq_measure says;
 * and the marks are drawn on the picture and stay on their vertices. */

#define _DEFAULT_SOURCE         /* M_PI */

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "app.h"
#include "testlib.h"

static const char *cube =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

static void look(Scene *s, float yaw_deg, float pitch_deg)
{
    s->cam.yaw = yaw_deg * (float)M_PI / 180;
    s->cam.pitch = pitch_deg * (float)M_PI / 180;
    s->cam.roll = 0;
    s->cam.zoom = 1;
    s->cam.pan = v3(0, 0, 0);
    scene_fit(s);
}

/* The vertices on a face turned to the viewer (view-space normal z > 0),
 * from the scene's polygons (the cube's quads stay whole). */
static int facing_vertices(const Scene *s, int shown[8])
{
    Mat4 mv = m4_mul(camera_view(&s->cam), object_matrix(&s->objs[0]));
    const Mesh *m = &s->meshes[0];
    int n = 0;
    memset(shown, 0, 8 * sizeof *shown);
    cr_assert_eq(s->npolys, 6);
    for (uint32_t f = 0; f < s->npolys; f++) {
        const uint32_t *c = &s->poly_corner[scene_poly_c0(s, f)];
        uint32_t nc = scene_poly_c0(s, f + 1) - scene_poly_c0(s, f);
        cr_assert_eq(nc, 4);
        Vec3 p[3];
        for (int k = 0; k < 3; k++) {
            const float *q = &m->pos[3 * c[k]];
            p[k] = m4_point(&mv, v3(q[0], q[1], q[2]));
        }
        Vec3 nrm = v3_cross(v3_sub(p[1], p[0]), v3_sub(p[2], p[0]));
        if (nrm.z > 1e-6f)
            for (int k = 0; k < 4; k++)
                shown[c[k]] = 1;
    }
    for (int i = 0; i < 8; i++)
        n += shown[i];
    return n;
}

static void screen_of(Pipeline *p, uint32_t v, double out[2])
{
    const Scene *s = p->scene;
    Mat4 mv = m4_mul(camera_view(&s->cam), object_matrix(&s->objs[0]));
    const float *q = &s->meshes[0].pos[3 * v];
    Vec3 w = m4_point(&mv, v3(q[0], q[1], q[2]));
    double sp[3];
    cr_assert_eq(screen_view_point(&p->sp, w.x, w.y, w.z, sp), 0);
    out[0] = sp[0];
    out[1] = sp[1];
}

Test(measure, the_cursor_reaches_every_shown_vertex_and_no_hidden_one)
{
    const float views[3][2] = { { 30, 25 }, { -50, -20 }, { 140, 35 } };
    for (int vi = 0; vi < 3; vi++) {
        Scene s;
        cr_assert_eq(tl_scene_from_text(&s, "c.obj", cube), 0);
        look(&s, views[vi][0], views[vi][1]);
        Pipeline p;
        cr_assert_eq(pipeline_init(&p, &s, hsr_algos[0], 1), 0);
        cr_assert_eq(pipeline_render(&p, 160, 120, 1, 0, 1), 0);
        int shown[8], reached[8] = { 0 };
        int nshown = facing_vertices(&s, shown);
        cr_assert_eq(nshown, 7, "three faces turned to the viewer: %d vertices", nshown);
        cr_assert_eq(app_measure_step(&p, 0, 0), 0);
        reached[p.marks.cur.a] = 1;
        /* from every vertex reached, every arrow, until nothing new */
        for (int round = 0; round < 8; round++)
            for (uint32_t v = 0; v < 8; v++) {
                if (!reached[v])
                    continue;
                static const int dir[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
                for (int d = 0; d < 4; d++) {
                    p.marks.cur.a = v;
                    double a[2], b[2];
                    screen_of(&p, v, a);
                    if (app_measure_step(&p, dir[d][0], dir[d][1]))
                        continue;
                    screen_of(&p, p.marks.cur.a, b);
                    cr_assert_gt((b[0] - a[0]) * dir[d][0] + (b[1] - a[1]) * dir[d][1], 0.5,
                                 "view %d: a step from v%u goes the arrow's way", vi, v + 1);
                    reached[p.marks.cur.a] = 1;
                }
            }
        for (int i = 0; i < 8; i++)
            cr_assert_eq(reached[i], shown[i], "view %d: vertex %d %s", vi, i + 1,
                         shown[i] ? "shown, never reached" : "hidden, reached");
        pipeline_free(&p);
        scene_free(&s);
    }
}

Test(measure, marks_measure_and_are_drawn_on_their_vertices)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "c.obj", cube), 0);
    look(&s, 30, 25);
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, &s, hsr_algos[0], 1), 0);
    p.marks = (MeasureMarks){ .n = 3, .mark = { { .a = 1 }, { .a = 0 }, { .a = 3 } } };     /* (1,0,0) (0,0,0) (0,1,0) */
    char words[160];
    app_measure_words(&s, &p.marks, 0, words, sizeof words);
    cr_assert(strstr(words, "AB 1 (dx -1 dy 0 dz 0), BC 1, angle ABC 90"), "%s", words);
    char opt[64];
    app_measure_option(&p.marks, opt, sizeof opt);
    cr_assert_str_eq(opt, "v2,v1,v4");
    /* drawn: cyan pixels where the picture has none without the marks */
    for (int turn = 0; turn < 2; turn++) {
        int cyan[2];
        for (int k = 0; k < 2; k++) {
            p.marks.n = k ? 3 : 0;
            cr_assert_eq(pipeline_render(&p, 160, 120, 1, 0, 1), 0);
            cyan[k] = 0;
            for (int i = 0; i < p.img.w * p.img.h; i++) {
                const uint8_t *c = &p.img.rgb[3 * i];
                cyan[k] += c[0] < 40 && c[1] > 200 && c[2] > 200;
            }
        }
        cr_assert_eq(cyan[0], 0);
        cr_assert_gt(cyan[1], 40, "turn %d: %d cyan pixels", turn, cyan[1]);
        look(&s, 100, 10);      /* turned: the marks follow their vertices */
    }
    pipeline_free(&p);
    scene_free(&s);
}

/* A point of the cube (model space) in samples of the last frame. */
static void screen_of_point(Pipeline *p, const double q[3], double out[2])
{
    const Scene *s = p->scene;
    Mat4 mv = m4_mul(camera_view(&s->cam), object_matrix(&s->objs[0]));
    Vec3 w = m4_point(&mv, v3((float)q[0], (float)q[1], (float)q[2]));
    double sp[3];
    cr_assert_eq(screen_view_point(&p->sp, w.x, w.y, w.z, sp), 0);
    out[0] = sp[0];
    out[1] = sp[1];
}

/* The cube's face f (0-based) faces the viewer: from the normals, not
 * from the depth buffer the cursor reads. */
static int face_facing(const Scene *s, uint32_t f)
{
    Mat4 mv = m4_mul(camera_view(&s->cam), object_matrix(&s->objs[0]));
    const Mesh *m = &s->meshes[0];
    Vec3 p[3];
    for (int k = 0; k < 3; k++) {
        const float *q = &m->pos[3 * s->poly_corner[scene_poly_c0(s, f) + (uint32_t)k]];
        p[k] = m4_point(&mv, v3(q[0], q[1], q[2]));
    }
    return v3_cross(v3_sub(p[1], p[0]), v3_sub(p[2], p[0])).z > 1e-6f;
}

/* A click (app_measure_pick) on a face's centre or an edge's midpoint
 * of a cube seen from three quarters: wide, the cursor lands on that
 * very point when a face of it faces the viewer, and never on a hidden
 * one; narrow (vertices only) it lands on a vertex. The centres of the
 * bottom and top faces are 1 apart, straight up. */
Test(measure, a_wide_click_snaps_to_shown_face_centres_and_edge_midpoints)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "c.obj", cube), 0);
    look(&s, 30, 25);
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, &s, hsr_algos[0], 1), 0);
    cr_assert_eq(pipeline_render(&p, 160, 120, 1, 0, 1), 0);
    const Mesh *m = &s.meshes[0];
    int faces_seen = 0, edges_seen = 0;
    for (uint32_t f = 0; f < 6; f++) {
        const uint32_t *c = &s.poly_corner[scene_poly_c0(&s, f)];     /* the cube's quads stay whole */
        double q[3] = { 0, 0, 0 }, at[2];
        for (int k = 0; k < 4; k++)
            for (int j = 0; j < 3; j++)
                q[j] += m->pos[3 * c[k] + (uint32_t)j] / 4.0;
        screen_of_point(&p, q, at);
        cr_assert_eq(app_measure_pick(&p, at[0], at[1], 0), 0);
        cr_expect_eq(p.marks.cur.kind, MEASURE_VERTEX, "narrow: a vertex");
        cr_assert_eq(app_measure_pick(&p, at[0], at[1], 1), 0);
        int facing = face_facing(&s, f);
        int got = p.marks.cur.kind == MEASURE_FACE && p.marks.cur.a == f;
        cr_expect_eq(got, facing, "face %u: %s", f + 1, facing ? "shown, its centre not taken" : "hidden, taken");
        faces_seen += got;
        /* its edges' midpoints: shown when this face or its neighbour faces the viewer */
        for (int k = 0; k < 4; k++) {
            uint32_t a = c[k], b = c[(k + 1) % 4], lo = a < b ? a : b, hi = a < b ? b : a;
            int other_facing = 0;
            for (uint32_t g = 0; g < 6; g++) {
                const uint32_t *d = &s.poly_corner[scene_poly_c0(&s, g)];
                for (int i = 0; g != f && i < 4; i++)
                    if ((d[i] == a && d[(i + 1) % 4] == b) || (d[i] == b && d[(i + 1) % 4] == a))
                        other_facing = face_facing(&s, g);
            }
            double e[3];
            for (int j = 0; j < 3; j++)
                e[j] = (m->pos[3 * a + (uint32_t)j] + m->pos[3 * b + (uint32_t)j]) / 2.0;
            screen_of_point(&p, e, at);
            cr_assert_eq(app_measure_pick(&p, at[0], at[1], 1), 0);
            int on = p.marks.cur.kind == MEASURE_EDGE && p.marks.cur.a == lo && p.marks.cur.b == hi;
            cr_expect_eq(on, facing || other_facing, "edge v%u-v%u of face %u", lo + 1, hi + 1, f + 1);
            edges_seen += on;
        }
    }
    cr_expect_eq(faces_seen, 3, "three faces turned to the viewer");
    cr_expect_eq(edges_seen, 2 * 9, "nine edges shown, each met from both of its faces");
    /* the centres of the bottom (f1, z 0) and top (f2, z 1) faces */
    p.marks = (MeasureMarks){ .n = 2, .mark = { { .kind = MEASURE_FACE, .a = 0 }, { .kind = MEASURE_FACE, .a = 1 } },
                              .cursor = 1, .cur = { .kind = MEASURE_EDGE, .a = 0, .b = 1 }, .wide = 1 };
    char words[200];
    app_measure_words(&s, &p.marks, 0, words, sizeof words);
    cr_expect_str_eq(words, "wide snap: e1-2 0.5 0 0, AB 1 (dx 0 dy 0 dz 1)");
    app_measure_words(&s, &p.marks, 1, words, sizeof words);
    cr_expect_str_eq(words, "wide snap: e1-2, AB 1 (dx 0 dy 0 dz 1)");
    char opt[64];
    app_measure_option(&p.marks, opt, sizeof opt);
    cr_expect_str_eq(opt, "f1,f2");
    pipeline_free(&p);
    scene_free(&s);
}

/* Cut at z = 0.5, the cube's top vertices are gone: a click where one
 * shows uncut never lands on it (the depth buffer alone would take it:
 * it is in front of the cap). */
Test(measure, a_click_never_lands_on_a_cut_away_vertex)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "c.obj", cube), 0);
    look(&s, 30, 25);
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, &s, hsr_algos[0], 1), 0);
    char err[160];
    cr_assert_eq(section_parse("z=0.5", &p.planes[0], err, sizeof err), 0, "%s", err);
    for (int cut = 0; cut < 2; cut++) {
        p.nplanes = cut;
        cr_assert_eq(pipeline_render(&p, 160, 120, 1, 0, 1), 0);
        int top = 0;
        for (uint32_t v = 4; v < 8; v++) {
            double at[2];
            screen_of(&p, v, at);
            for (int wide = 0; wide < 2; wide++) {
                cr_assert_eq(app_measure_pick(&p, at[0], at[1], wide), 0);
                if (p.marks.cur.kind == MEASURE_VERTEX)
                    top += p.marks.cur.a == v;
            }
        }
        int shown[8], top_shown = 0;
        facing_vertices(&s, shown);
        for (int v = 4; v < 8; v++)
            top_shown += shown[v];
        cr_assert_gt(top_shown, 2);
        cr_expect_eq(top, cut ? 0 : 2 * top_shown, "cut %d: %d clicks on a top vertex land on it", cut, top);
    }
    pipeline_free(&p);
    scene_free(&s);
}

/* ==== --overhang and --thickness on the picture (app/printtint.c) ==== */

Test(measure, the_tint_colours_the_overhanging_faces_only)
{
    /* the 3-4-5 plate of test_printq (z up): only its underside (face
     * 3) overhangs past 45 degrees; past 30 its low end (face 6) too */
    static const char *plate =
        "v 0 0 0\nv 8 0 6\nv 5 0 10\nv -3 0 4\nv 0 10 0\nv 8 10 6\nv 5 10 10\nv -3 10 4\n"
        "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n";
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "plate.obj", plate), 0);
    scene_set_up(&s, UP_Z);
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, &s, hsr_algos[0], 1), 0);
    p.overhang = 1;
    p.overhang_deg = 45;
    char err[160];
    cr_assert_eq(app_print_tint(&p, err, sizeof err), 1, "%s", err);
    cr_assert_eq(p.tint.ft.nfaces, 6);
    uint8_t red[3];
    shade_overhang_colour(red);
    for (int f = 0; f < 6; f++) {
        const uint8_t *c = &p.tint.ft.rgba[4 * f];
        cr_assert_eq(c[3], f == 2, "face %d", f + 1);
        if (c[3])
            cr_assert(!memcmp(c, red, 3));
    }
    cr_assert_float_eq(p.tint.overhang_area, 100, 1e-9);
    p.overhang_deg = 30;        /* made again for the new angle */
    cr_assert_eq(app_print_tint(&p, err, sizeof err), 1, "%s", err);
    cr_assert_eq(p.tint.ft.rgba[4 * 5 + 3], 1, "the low end past 30");
    cr_assert_float_eq(p.tint.overhang_area, 150, 1e-9);
    p.overhang = 0;
    cr_assert_eq(app_print_tint(&p, err, sizeof err), 0, "nothing asked: no tint");
    pipeline_free(&p);
    scene_free(&s);
}

Test(measure, the_thickness_ramp_runs_red_to_blue)
{
    uint8_t c[3];
    shade_thickness_colour(0, c);
    cr_assert(c[0] > 200 && c[1] < 80 && c[2] < 80, "0 red: %d %d %d", c[0], c[1], c[2]);
    shade_thickness_colour(1, c);
    cr_assert(c[2] > 200 && c[0] < 80, "1 blue: %d %d %d", c[0], c[1], c[2]);
    shade_thickness_colour(5, c);
    cr_assert(c[2] > 200 && c[0] < 80, "past 1 blue");
    shade_thickness_colour(2 / 3.0, c);
    cr_assert(c[1] > 150 && c[0] < 80 && c[2] < 100, "2/3 green: %d %d %d", c[0], c[1], c[2]);
}

/* The centre of a face is the mean of its corners as the file gives
 * them, whatever polygons the scene splits it into and whichever object
 * it is in: two objects, each with a quad bent out of its plane (two
 * triangles of one face) and faces after it, marked on the first
 * object's quad, the second object's third face and the first's
 * triangle. The distances are those of the corners' means. */
Test(measure, a_face_mark_is_the_mean_of_its_corners_in_any_object)
{
    static const char *obj = "o a\nv 0 0 0\nv 2 0 0\nv 2 2 1\nv 0 2 0\nv 4 0 0\nf 1 2 3 4\nf 2 5 3\n"
                             "o b\nv 10 0 0\nv 12 0 0\nv 12 3 1\nv 10 3 0\nv 14 0 0\nv 14 3 2\n"
                             "f 6 7 8 9\nf 7 10 8\nf 10 11 8\n";
    /* the corners of each face marked, from the text above */
    static const double corners[3][4][3] = {
        { { 0, 0, 0 }, { 2, 0, 0 }, { 2, 2, 1 }, { 0, 2, 0 } },
        { { 14, 0, 0 }, { 14, 3, 2 }, { 12, 3, 1 } },
        { { 2, 0, 0 }, { 4, 0, 0 }, { 2, 2, 1 } },
    };
    static const int ncorners[3] = { 4, 3, 3 };
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "two.obj", obj), 0);
    cr_assert_eq(s.nobjs, 2);
    cr_assert(s.poly_lface && s.npolys == 7, "the bent quads are split: %u polygons", s.npolys);
    double c[3][3] = { { 0 } };
    for (int m = 0; m < 3; m++)
        for (int i = 0; i < ncorners[m]; i++)
            for (int j = 0; j < 3; j++)
                c[m][j] += corners[m][i][j] / ncorners[m];
    double ab = sqrt(pow(c[1][0] - c[0][0], 2) + pow(c[1][1] - c[0][1], 2) + pow(c[1][2] - c[0][2], 2));
    double bc = sqrt(pow(c[2][0] - c[1][0], 2) + pow(c[2][1] - c[1][1], 2) + pow(c[2][2] - c[1][2], 2));
    MeasureMarks mk = { .n = 3,
                        .mark = { { .obj = 0, .kind = MEASURE_FACE, .a = 0 },
                                  { .obj = 1, .kind = MEASURE_FACE, .a = 2 },
                                  { .obj = 0, .kind = MEASURE_FACE, .a = 1 } } };
    char words[200];
    app_measure_words(&s, &mk, 0, words, sizeof words);
    double got_ab, dx, dy, dz, got_bc;
    cr_assert_eq(sscanf(words, "AB %lf (dx %lf dy %lf dz %lf), BC %lf", &got_ab, &dx, &dy, &dz, &got_bc), 5, "%s",
                 words);
    cr_assert(fabs(got_ab - ab) <= 1e-5 * ab && fabs(got_bc - bc) <= 1e-5 * bc, "%s: AB %g BC %g", words, ab, bc);
    double want[3] = { c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2] }, d[3] = { dx, dy, dz };
    for (int j = 0; j < 3; j++)
        cr_assert(fabs(fabs(d[j]) - fabs(want[j])) <= 1e-3 * fabs(want[j]), "%s: axis %d %g", words, j, want[j]);
    /* a face past the object's last is no point of the scene */
    mk.mark[1].a = 3;
    app_measure_words(&s, &mk, 0, words, sizeof words);
    cr_assert(strstr(words, "a mark is on no point of the scene"), "%s", words);
    scene_free(&s);
}
