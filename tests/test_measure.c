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
        reached[p.marks.cur_v] = 1;
        /* from every vertex reached, every arrow, until nothing new */
        for (int round = 0; round < 8; round++)
            for (uint32_t v = 0; v < 8; v++) {
                if (!reached[v])
                    continue;
                static const int dir[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
                for (int d = 0; d < 4; d++) {
                    p.marks.cur_v = v;
                    double a[2], b[2];
                    screen_of(&p, v, a);
                    if (app_measure_step(&p, dir[d][0], dir[d][1]))
                        continue;
                    screen_of(&p, p.marks.cur_v, b);
                    cr_assert_gt((b[0] - a[0]) * dir[d][0] + (b[1] - a[1]) * dir[d][1], 0.5,
                                 "view %d: a step from v%u goes the arrow's way", vi, v + 1);
                    reached[p.marks.cur_v] = 1;
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
    p.marks = (MeasureMarks){ .n = 3, .obj = { 0, 0, 0 }, .v = { 1, 0, 3 } };     /* (1,0,0) (0,0,0) (0,1,0) */
    char words[160];
    app_measure_words(&s, &p.marks, words, sizeof words);
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
