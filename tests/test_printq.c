/* test_printq.c: will it print, and its measures (src/printq/,
 * include/printq.h), against answers worked out by hand: a 10 mm cube
 * on a 5 mm bed fits in no order of its axes, a 10 x 20 x 5 part fits a
 * 21 x 11 x 6 bed turned a quarter about the vertical only; the unit a
 * size suggests; a plate tilted on a 3-4-5 slope whose overhanging area
 * is exact at three angles; a hollow box with 2-unit walls measured 2
 * at every face, subdivided or not; the BVH's ray against every
 * triangle tried on random soups; and distances and angles between
 * vertices, exact to the double's precision. */

#define _DEFAULT_SOURCE         /* M_PI */

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "printq.h"
#include "testlib.h"

/* ==== Models ==== */

/* An axis-aligned box from lo to hi, each side an n x n grid of quads,
 * facing out (or in: a cavity). */
static void add_box(Mesh *m, const double lo[3], const double hi[3], int n, int inward)
{
    for (int ax = 0; ax < 3; ax++)
        for (int side = 0; side < 2; side++) {
            int u = (ax + 1) % 3, v = (ax + 2) % 3;
            uint32_t base = m->nverts;
            for (int i = 0; i <= n; i++)
                for (int j = 0; j <= n; j++) {
                    double p[3];
                    p[ax] = side ? hi[ax] : lo[ax];
                    p[u] = lo[u] + (hi[u] - lo[u]) * i / n;
                    p[v] = lo[v] + (hi[v] - lo[v]) * j / n;
                    cr_assert_eq(tl_mesh_vertex(m, (float)p[0], (float)p[1], (float)p[2]), 0);
                }
            /* u x v = ax: counter-clockwise about +ax on the high side */
            int out = side ^ inward;
            for (int i = 0; i < n; i++)
                for (int j = 0; j < n; j++) {
                    uint32_t a = base + (uint32_t)(i * (n + 1) + j), b = a + (uint32_t)(n + 1), c = b + 1, d = a + 1;
                    uint32_t q[4] = { a, b, c, d }, r[4] = { a, d, c, b };
                    cr_assert_eq(tl_mesh_face(m, out ? q : r, 4), 0);
                }
        }
}

static void box_mesh(Mesh *m, double x, double y, double z)
{
    const double lo[3] = { 0, 0, 0 }, hi[3] = { x, y, z };
    tl_mesh_init(m, "box.obj");
    add_box(m, lo, hi, 1, 0);
    cr_assert_eq(tl_mesh_finish(m), 0);
}

static double mesh_size(const Mesh *m, double size[3])
{
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t i = 0; i < m->nverts; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->pos[3 * i + k]);
            hi[k] = fmax(hi[k], m->pos[3 * i + k]);
        }
    for (int k = 0; k < 3; k++)
        size[k] = hi[k] - lo[k];
    return 0;
}

/* ==== The bed ==== */

Test(printq, cube_of_10_does_not_fit_a_bed_of_5)
{
    const double size[3] = { 10, 10, 10 }, bed[3] = { 5, 5, 5 };
    PrintqOrders o;
    int fits[PRINTQ_ORDERS];
    for (int up = 0; up < UP_COUNT; up++) {
        printq_bed_orders(up, &o);
        cr_assert_eq(printq_bed_fit(size, bed, &o, fits), -1);
        for (int k = 0; k < PRINTQ_ORDERS; k++)
            cr_assert_eq(fits[k], 0);
    }
    /* and exactly its size fits (touching the bed's walls) */
    const double same[3] = { 10, 10, 10 };
    printq_bed_orders(UP_Z, &o);
    cr_assert_eq(printq_bed_fit(size, same, &o, fits), 0);
}

Test(printq, part_fits_after_a_quarter_turn_only)
{
    const double size[3] = { 10, 20, 5 }, bed[3] = { 21, 11, 6 };
    PrintqOrders o;
    int fits[PRINTQ_ORDERS];
    printq_bed_orders(UP_Z, &o);
    cr_assert_eq(printq_bed_fit(size, bed, &o, fits), 1);
    int want[PRINTQ_ORDERS] = { 0, 1, 0, 0, 0, 0 };
    for (int k = 0; k < PRINTQ_ORDERS; k++)
        cr_assert_eq(fits[k], want[k], "order %d", k);
    char w[16];
    printq_order_words(o.axis[1], w, sizeof w);
    cr_assert_str_eq(w, "y x z");
    /* y up: the level axes are x and z, so the same part stands 20 high */
    printq_bed_orders(UP_Y, &o);
    printq_order_words(o.axis[0], w, sizeof w);
    cr_assert_str_eq(w, "x z y");
    /* it fits lying on its z side with y along W: order 3, y x z */
    cr_assert_eq(printq_bed_fit(size, bed, &o, fits), 3);
    printq_order_words(o.axis[3], w, sizeof w);
    cr_assert_str_eq(w, "y x z");
}

Test(printq, the_six_orders_are_the_six_permutations)
{
    for (int up = 0; up < UP_COUNT; up++) {
        PrintqOrders o;
        printq_bed_orders(up, &o);
        int seen = 0;
        for (int k = 0; k < PRINTQ_ORDERS; k++) {
            int code = o.axis[k][0] * 9 + o.axis[k][1] * 3 + o.axis[k][2];
            cr_assert_eq(o.axis[k][0] + o.axis[k][1] + o.axis[k][2], 3);
            cr_assert(o.axis[k][0] != o.axis[k][1]);
            cr_assert_eq(seen & (1 << code), 0, "order %d twice", k);
            seen |= 1 << code;
        }
        int upax = up % 3 == 0 ? 1 : up % 3 == 1 ? 2 : 0;
        cr_assert_eq(o.axis[0][2], upax, "order 0 stands on its up axis");
        cr_assert_eq(o.axis[1][2], upax);
    }
}

/* ==== Units ==== */

Test(printq, sizes_that_suggest_a_unit)
{
    const double inches[3] = { 1.5, 0.75, 0.25 }, mm[3] = { 10, 10, 10 }, metres[3] = { 0.2, 0.15, 0.1 };
    const double big[3] = { 120, 80, 40 }, odd[3] = { 1.37, 0.75, 0.25 }, small_in[3] = { 0.375, 0.25, 0.125 };
    cr_assert_str_eq(printq_unit_guess(inches), "in");
    cr_assert_null(printq_unit_guess(mm), "whole numbers: nothing suggests inches");
    cr_assert_str_eq(printq_unit_guess(metres), "m");
    cr_assert_null(printq_unit_guess(big));
    cr_assert_null(printq_unit_guess(odd), "1.37 is no sixteenth");
    cr_assert_str_eq(printq_unit_guess(small_in), "m", "under 0.5: metres, not inches");
    cr_assert_float_eq(printq_unit_mm("in"), 25.4, 0);
    cr_assert_float_eq(printq_unit_mm("m"), 1000, 0);
    cr_assert_float_eq(printq_unit_mm("mm"), 1, 0);
    cr_assert_float_eq(printq_unit_mm("ft"), 0, 0);
}

/* ==== Overhangs ==== */

/* A plate on a 3-4-5 slope, z up: its long side (8, 0, 6) (10 long),
 * its thickness (-3, 0, 4) (5), 10 wide along y. Its underside faces
 * (3, 0, -4) / 5 (down 0.8: 53.13 degrees past the vertical), its low
 * end (-0.8, 0, -0.6) (down 0.6: 36.87 degrees); the coordinates are
 * small integers, so the areas are exact: 100 and 50. */
static void tilted_plate(Mesh *m)
{
    tl_mesh_init(m, "plate.obj");
    static const float p[8][3] = {
        { 0, 0, 0 }, { 8, 0, 6 }, { 5, 0, 10 }, { -3, 0, 4 },          /* y = 0: the side outline */
        { 0, 10, 0 }, { 8, 10, 6 }, { 5, 10, 10 }, { -3, 10, 4 },      /* y = 10 */
    };
    for (int i = 0; i < 8; i++)
        tl_mesh_vertex(m, p[i][0], p[i][1], p[i][2]);
    /* outward: the y = 0 side faces -y, the outline 0 1 2 3 runs
     * counter-clockwise seen from +y */
    static const uint32_t f[6][4] = {
        { 0, 1, 2, 3 }, { 4, 7, 6, 5 },     /* y = 0 (-y), y = 10 (+y) */
        { 0, 4, 5, 1 },                     /* the underside */
        { 1, 5, 6, 2 }, { 2, 6, 7, 3 },     /* the high end, the top */
        { 3, 7, 4, 0 },                     /* the low end */
    };
    for (int i = 0; i < 6; i++)
        tl_mesh_face(m, f[i], 4);
    cr_assert_eq(tl_mesh_finish(m), 0);
}

Test(printq, tilted_plate_overhang_area_is_exact)
{
    Mesh m;
    tilted_plate(&m);
    /* the faces point out: the y = 0 side's Newell normal is -y; the
     * underside's is twice its area (100) times (0.6, 0, -0.8) */
    double nv[3];
    printq_newell(&m, 0, nv);
    cr_assert(nv[1] < 0 && nv[0] == 0 && nv[2] == 0, "%g %g %g", nv[0], nv[1], nv[2]);
    printq_newell(&m, 2, nv);
    cr_assert(nv[0] == 120 && nv[1] == 0 && nv[2] == -160, "underside %g %g %g", nv[0], nv[1], nv[2]);
    uint8_t flag[6];
    cr_assert_eq(printq_overhang(&m, UP_Z, 45, flag), 100);
    uint8_t want45[6] = { 0, 0, 1, 0, 0, 0 };
    cr_assert_eq(memcmp(flag, want45, 6), 0);
    cr_assert_eq(printq_overhang(&m, UP_Z, 30, flag), 150, "the low end too (36.87 > 30)");
    cr_assert_eq(printq_overhang(&m, UP_Z, 60, flag), 0, "53.13 is not past 60");
    cr_assert_eq(printq_overhang(&m, UP_Z, 53, flag), 100);
    /* upside down (-z up) the top (down 0.8 then) overhangs: 10 x 10 */
    cr_assert_eq(printq_overhang(&m, UP_NEG_Z, 45, flag), 100);
    cr_assert_eq(flag[4], 1);
    mesh_free(&m);
}

Test(printq, a_face_on_the_bed_is_no_overhang)
{
    Mesh m;
    box_mesh(&m, 10, 20, 5);
    uint8_t flag[6];
    cr_assert_eq(printq_overhang(&m, UP_Z, 45, flag), 0, "the bottom rests on the bed");
    /* y up: the bottom is y = 0, resting too; the z sides are vertical */
    cr_assert_eq(printq_overhang(&m, UP_Y, 45, flag), 0);
    mesh_free(&m);
    /* a box over a cavity: the cavity's ceiling overhangs, 16 x 16 */
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 20, 20, 20 }, clo[3] = { 2, 2, 2 }, chi[3] = { 18, 18, 18 };
    tl_mesh_init(&m, "hollow.obj");
    add_box(&m, lo, hi, 1, 0);
    add_box(&m, clo, chi, 1, 1);
    cr_assert_eq(tl_mesh_finish(&m), 0);
    cr_assert_eq(printq_overhang(&m, UP_Z, 45, NULL), 256);
    cr_assert_eq(printq_overhang(&m, UP_X, 45, NULL), 256);
    mesh_free(&m);
}

/* ==== Wall thickness ==== */

/* A hollow box: 20 a side, a 16 cavity: walls 2 thick everywhere. */
static void hollow_box(Mesh *m, int n)
{
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 20, 20, 20 }, clo[3] = { 2, 2, 2 }, chi[3] = { 18, 18, 18 };
    tl_mesh_init(m, "hollow.obj");
    add_box(m, lo, hi, n, 0);
    add_box(m, clo, chi, n, 1);
    cr_assert_eq(tl_mesh_finish(m), 0);
}

Test(printq, hollow_box_walls_are_2_everywhere)
{
    for (int n = 1; n <= 4; n += 3)
        for (int threads = 1; threads <= 2; threads++) {
            Mesh m;
            hollow_box(&m, n);
            PrintqThickness t;
            char err[160];
            cr_assert_eq(printq_thickness(&m, threads, &t, err, sizeof err), 0, "%s", err);
            cr_assert_eq(t.measured, m.nfaces);
            for (uint32_t f = 0; f < m.nfaces; f++)
                cr_assert(fabs(t.face[f] - 2) <= 0.02, "face %u of %u: %g", f, m.nfaces, t.face[f]);
            cr_assert(fabs(t.min - 2) <= 0.02 && fabs(t.median - 2) <= 0.02);
            /* every face is 2 thick: all of the area is thinner than 2.5, none than 1.5 */
            cr_assert_float_eq(printq_thin_area(&m, &t, 2.5), 6 * 400 + 6 * 256, 1e-9);
            cr_assert_float_eq(printq_thin_area(&m, &t, 1.5), 0, 0);
            printq_thickness_free(&t);
            mesh_free(&m);
        }
}

Test(printq, a_solid_box_is_as_thick_as_it_is_across)
{
    Mesh m;
    box_mesh(&m, 10, 20, 5);
    PrintqThickness t;
    char err[160];
    cr_assert_eq(printq_thickness(&m, 1, &t, err, sizeof err), 0, "%s", err);
    /* faces in add_box's order: x sides, y sides, z sides */
    const float want[6] = { 10, 10, 20, 20, 5, 5 };
    for (int f = 0; f < 6; f++)
        cr_assert_float_eq(t.face[f], want[f], 1e-5, "face %d: %g", f, t.face[f]);
    cr_assert_float_eq(t.min, 5, 1e-5);
    cr_assert_float_eq(t.min_at[2], 0, 1e-9, "the thinnest is at a z side's centre");
    cr_assert_float_eq(t.min_at[0], 5, 1e-9);
    printq_thickness_free(&t);
    mesh_free(&m);
}

/* --min-thickness T: "the area of the faces thinner than T" (zview.1),
 * so a wall exactly T thick is not counted. The thicknesses are given,
 * not measured, so that they are exactly 10, 20 and 5: the box's x
 * sides (20 x 5 each), y sides (10 x 5) and z sides (10 x 20). */
Test(printq, a_wall_exactly_as_thick_as_the_limit_is_not_thinner)
{
    Mesh m;
    box_mesh(&m, 10, 20, 5);
    float face[6] = { 10, 10, 20, 20, 5, 5 };
    PrintqThickness t = { .face = face, .nfaces = 6, .measured = 6 };
    cr_assert_float_eq(printq_thin_area(&m, &t, 5), 0, 0, "the z sides, 5 thick, are not thinner than 5");
    cr_assert_float_eq(printq_thin_area(&m, &t, 5.0001), 2 * 200, 1e-9);
    cr_assert_float_eq(printq_thin_area(&m, &t, 10), 2 * 200, 1e-9, "nor the x sides, 10 thick, than 10");
    cr_assert_float_eq(printq_thin_area(&m, &t, 20), 2 * 200 + 2 * 100, 1e-9);
    cr_assert_float_eq(printq_thin_area(&m, &t, 20.5), 2 * 200 + 2 * 100 + 2 * 50, 1e-9);
    mesh_free(&m);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of the faces measured, against a sort: two solid boxes
 * (10 x 20 x 5 and 3 x 7 x 1 apart: 1 1 3 3 5 5 7 7 10 10 20 20, the
 * median between 5 and 7: 6), and the first with a lone square 3 above
 * it, facing up (3 5 5 10 10 20 20: the middle one, 10). */
Test(printq, the_median_is_the_middle_of_the_faces_measured)
{
    const double lo1[3] = { 0, 0, 0 }, hi1[3] = { 10, 20, 5 }, lo2[3] = { 30, 0, 0 }, hi2[3] = { 33, 7, 1 };
    const double want[2] = { 6, 10 };
    for (int c = 0; c < 2; c++) {
        Mesh m;
        tl_mesh_init(&m, "boxes.obj");
        add_box(&m, lo1, hi1, 1, 0);
        if (c == 0) {
            add_box(&m, lo2, hi2, 1, 0);
        } else {
            uint32_t b = m.nverts, q[4] = { b, b + 1, b + 2, b + 3 };
            cr_assert_eq(tl_mesh_vertex(&m, 2, 2, 8), 0);
            cr_assert_eq(tl_mesh_vertex(&m, 8, 2, 8), 0);
            cr_assert_eq(tl_mesh_vertex(&m, 8, 8, 8), 0);
            cr_assert_eq(tl_mesh_vertex(&m, 2, 8, 8), 0);
            cr_assert_eq(tl_mesh_face(&m, q, 4), 0);
        }
        cr_assert_eq(tl_mesh_finish(&m), 0);
        PrintqThickness t;
        char err[160];
        cr_assert_eq(printq_thickness(&m, 2, &t, err, sizeof err), 0, "%s", err);
        double v[16];
        uint32_t k = 0;
        for (uint32_t f = 0; f < t.nfaces && k < 16; f++)
            if (t.face[f] >= 0)
                v[k++] = t.face[f];
        cr_assert_eq(k, c ? 7u : 12u, "faces measured: %u", k);
        qsort(v, k, sizeof *v, cmp_double);
        double ref = k % 2 ? v[k / 2] : (v[k / 2 - 1] + v[k / 2]) / 2;
        cr_expect_float_eq(ref, want[c], 1e-5, "case %d: the sort's median %g", c, ref);
        cr_expect_eq(t.median, ref, "case %d: median %g, the sort's %g", c, t.median, ref);
        printq_thickness_free(&t);
        mesh_free(&m);
    }
}

Test(printq, an_open_face_has_no_thickness)
{
    Mesh m;
    tl_mesh_init(&m, "quad.obj");
    tl_mesh_vertex(&m, 0, 0, 0);
    tl_mesh_vertex(&m, 1, 0, 0);
    tl_mesh_vertex(&m, 1, 1, 0);
    uint32_t f[3] = { 0, 1, 2 };
    tl_mesh_face(&m, f, 3);
    cr_assert_eq(tl_mesh_finish(&m), 0);
    PrintqThickness t;
    char err[160];
    cr_assert_eq(printq_thickness(&m, 1, &t, err, sizeof err), 0);
    cr_assert_eq(t.measured, 0);
    cr_assert(t.face[0] < 0);
    printq_thickness_free(&t);
    mesh_free(&m);
}

/* ==== The BVH's ray against every triangle ==== */

static uint64_t rng = 0x2545F4914F6CDD1Dull;

static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

Test(printq, ray_meets_the_triangle_every_triangle_tried_says)
{
    enum { NT = 3000, NR = 2000 };
    float *pos = malloc(9 * NT * sizeof *pos);
    uint32_t *tri = malloc(3 * NT * sizeof *tri);
    for (int t = 0; t < NT; t++) {
        double c[3] = { urand() * 10, urand() * 10, urand() * 10 };
        for (int k = 0; k < 3; k++) {
            for (int a = 0; a < 3; a++)
                pos[9 * t + 3 * k + a] = (float)(c[a] + (urand() - 0.5));
            tri[3 * t + k] = (uint32_t)(3 * t + k);
        }
    }
    Bvh b;
    char err[160];
    cr_assert_eq(bvh_build(&b, pos, 3 * NT, tri, NULL, NT, err, sizeof err), 0, "%s", err);
    /* the brute force: the same test on every triangle (a soup with no
     * bvh ids: id is the index) through a BVH of one triangle each, made
     * once for every ray */
    Bvh *one = calloc(NT, sizeof *one);
    cr_assert_not_null(one);
    for (int t = 0; t < NT; t++) {
        uint32_t c3[3] = { 0, 1, 2 };
        cr_assert_eq(bvh_build(&one[t], &pos[9 * t], 3, c3, NULL, 1, err, sizeof err), 0);
    }
    int hits = 0;
    for (int r = 0; r < NR; r++) {
        double o[3] = { urand() * 10, urand() * 10, urand() * 10 }, d[3];
        double len = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = urand() - 0.5;
            len += d[k] * d[k];
        }
        for (int k = 0; k < 3; k++)
            d[k] /= sqrt(len);
        if (r % 7 == 0)
            d[0] = d[1] = 0, d[2] = 1;          /* parallel to two slabs */
        uint32_t skip = r % 5 == 0 ? (uint32_t)(r % NT) : BVH_NONE;
        BvhRayHit h;
        bvh_ray(&b, o, d, INFINITY, skip, &h);
        double best = INFINITY;
        for (int t = 0; t < NT; t++) {
            if ((uint32_t)t == skip)
                continue;
            BvhRayHit h1;
            bvh_ray(&one[t], o, d, INFINITY, BVH_NONE, &h1);
            best = fmin(best, h1.t);
        }
        cr_assert(h.t == best, "ray %d: %.17g against %.17g", r, h.t, best);
        hits += isfinite(best);
        if (isfinite(best))
            cr_assert(b.id[h.tri] != skip);
    }
    cr_assert(hits > NR / 4, "the test meets something: %d", hits);
    for (int t = 0; t < NT; t++)
        bvh_free(&one[t]);
    free(one);
    bvh_free(&b);
    free(pos);
    free(tri);
}

/* ==== Measuring ==== */

Test(printq, points_parse_as_numbers_or_vertices)
{
    PrintqPoint p;
    cr_assert_eq(printq_point_parse("1.5,-2,3e2", &p), 0);
    cr_assert(p.p[0] == 1.5 && p.p[1] == -2 && p.p[2] == 300 && p.vertex == 0);
    cr_assert_eq(printq_point_parse("v12", &p), 0);
    cr_assert_eq(p.vertex, 12);
    const char *bad[] = { "1,2", "1,2,3,4", "v0", "v", "v1x", "a,b,c", "1,,3", "", "1,2,nan", "v-3" };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        cr_assert_eq(printq_point_parse(bad[i], &p), -1, "%s", bad[i]);
}

Test(printq, distances_and_angles_between_known_vertices)
{
    Mesh m;
    box_mesh(&m, 10, 20, 5);
    double size[3];
    mesh_size(&m, size);
    /* find the corners (0,0,0), (10,0,0), (10,20,5) among the vertices */
    uint32_t o = 0, x = 0, far = 0;
    for (uint32_t i = 0; i < m.nverts; i++) {
        const float *p = &m.pos[3 * i];
        if (p[0] == 0 && p[1] == 0 && p[2] == 0)
            o = i + 1;
        if (p[0] == 10 && p[1] == 0 && p[2] == 0)
            x = i + 1;
        if (p[0] == 10 && p[1] == 20 && p[2] == 5)
            far = i + 1;
    }
    cr_assert(o && x && far);
    PrintqPoint pt[3] = { { .vertex = o }, { .vertex = x }, { .vertex = far } };
    char err[160];
    cr_assert_eq(printq_points_resolve(&m, pt, 3, err, sizeof err), 0);
    PrintqMeasure r;
    printq_measure(pt, 2, &r);
    cr_assert(r.dist == 10 && r.d[0] == 10 && r.d[1] == 0 && r.d[2] == 0);
    printq_measure(pt, 3, &r);
    cr_assert(r.dist2 == sqrt(425.0), "%.17g", r.dist2);
    cr_assert_float_eq(r.angle, 90, 1e-12, "%.17g", r.angle);
    /* the diagonal from the origin, and the angle at the far corner */
    PrintqPoint d[3] = { pt[0], pt[2], pt[1] };
    printq_measure(d, 3, &r);
    cr_assert(r.dist == sqrt(525.0) && r.d[0] == 10 && r.d[1] == 20 && r.d[2] == 5);
    /* at (10,20,5) between (-10,-20,-5) and (0,-20,-5): cos = 425 / (sqrt(525) sqrt(425)) */
    cr_assert_float_eq(r.angle, acos(425 / (sqrt(525.0) * sqrt(425.0))) * 180 / M_PI, 1e-12);
    /* a vertex past the mesh's */
    PrintqPoint past = { .vertex = m.nverts + 1 };
    cr_assert_eq(printq_points_resolve(&m, &past, 1, err, sizeof err), -1);
    cr_assert(strstr(err, "vertices"), "%s", err);
    mesh_free(&m);
}
