/* test_diff.c: --diff's measure (src/diff/): known answers, and a
 * brute-force reference.
 *
 * A model against itself is 0 and the same; a copy with one convex
 * vertex moved by d along its normal is d away at that vertex, one
 * region; a cube against the cube with a second cube added has 6 added
 * (the second's area), nothing removed, one region, 3 away (its far
 * side from the first's); a model scaled by 1.01 about its centre is
 * 0.01 times its farthest point's distance from the centre away (the
 * Stanford bunny when ../shared/models has it, the bundled knot
 * always); a planar quad against its two triangles on the other
 * diagonal, the same model as STL and OBJ, and the model with its
 * vertices and faces shuffled are 0. Every vertex's distance equals the
 * least over every triangle of the other model; the two directions
 * swap when the models do; the sampled maximum lies within its bound
 * (and, in the suite "models", on the dragon and an edited copy); every
 * figure is the same bit for bit on one thread and several.
 * A plane against a tilted one has the mean of its middle, and the
 * corners alone measure its area over the tolerance exactly, whatever
 * the sampling. Then the files through diff_load: the check's verdicts, the
 * headline, and the picture's colours: every algorithm gives the same
 * face ids for each of --show's pictures. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "diff.h"
#include "testlib.h"
#include "writers.h"

static Mesh MA, MB;
static Diff D;
static char E[512];

static void teardown(void)
{
    diff_free(&D);
    mesh_free(&MA);
    mesh_free(&MB);
}
TestSuite(diff, .fini = teardown);

/* ==== Models ==== */

/* The unit cube at (x, y, z), six quads wound outwards, appended. */
static void cube(Mesh *m, float x, float y, float z)
{
    uint32_t v0 = m->nverts;
    for (int i = 0; i < 8; i++)
        cr_assert_eq(tl_mesh_vertex(m, x + (i & 1), y + (i >> 1 & 1), z + (i >> 2 & 1)), 0);
    static const uint32_t q[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 },
                                      { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
    for (int f = 0; f < 6; f++) {
        uint32_t c[4] = { v0 + q[f][0], v0 + q[f][1], v0 + q[f][2], v0 + q[f][3] };
        cr_assert_eq(tl_mesh_face(m, c, 4), 0);
    }
}

static void load(Mesh *m, const char *path)
{
    cr_assert_eq(mesh_load(m, path, E, sizeof E), 0, "%s", E);
}

/* A copy of src: positions through f (NULL: as they are). */
static void copy_mesh(Mesh *dst, const Mesh *src, void (*f)(float *p, const void *ctx), const void *ctx)
{
    cr_assert_eq(tl_mesh_init(dst, "copy.obj"), 0);
    for (uint32_t v = 0; v < src->nverts; v++) {
        float p[3] = { src->pos[3 * v], src->pos[3 * v + 1], src->pos[3 * v + 2] };
        if (f)
            f(p, ctx);
        cr_assert_eq(tl_mesh_vertex(dst, p[0], p[1], p[2]), 0);
    }
    for (uint32_t fc = 0; fc < src->nfaces; fc++)
        cr_assert_eq(tl_mesh_face(dst, &src->corner[src->face_start[fc]], src->face_start[fc + 1] - src->face_start[fc]),
                     0);
    cr_assert_eq(tl_mesh_finish(dst), 0);
}

static const Diff *run_tol(double tol)
{
    DiffOpts o = { 2, tol, NULL, 0, 1, NULL, NULL };
    diff_free(&D);
    cr_assert_eq(diff_compute(&D, &MA, &MB, &o, E, sizeof E), 0, "%s", E);
    return &D;
}

static const Diff *run(void)
{
    return run_tol(-1);
}

/* A triangle of the brute force below, and its box (lo x y z, hi x y z). */
typedef struct {
    double box[6], c[3][3];
} BruteTri;

static int by_low_x(const void *a, const void *b)
{
    double x = ((const BruteTri *)a)->box[0], y = ((const BruteTri *)b)->box[0];
    return (x > y) - (x < y);
}

/* Every used vertex's distance is the least over the other's triangles.
 * No triangle is left out on a guess: the search starts at the one
 * nearest to the vertex before (usually near), and passes over those
 * that cannot be nearer than the best so far by more than rounding (the
 * margin): the ones whose box is farther, and, the triangles sorted by
 * their box's low x, the ones whose low x lies too far on either side
 * (no box is wider than the widest). A knot against a knot took 19 s of
 * CPU weighing every triangle, 1 s so. */
static void vertices_against_brute(const DiffSide *s, const Mesh *m, const Mesh *other)
{
    uint32_t ntri = 0;
    for (uint32_t f = 0; f < other->nfaces; f++)
        ntri += other->face_start[f + 1] - other->face_start[f] - 2;
    BruteTri *tri = malloc(((size_t)ntri + 1) * sizeof *tri);
    cr_assert(tri);
    uint32_t t = 0;
    double wide = 0;
    for (uint32_t f = 0; f < other->nfaces; f++) {
        uint32_t c0 = other->face_start[f];
        for (uint32_t c = c0 + 1; c + 1 < other->face_start[f + 1]; c++, t++) {
            for (int k = 0; k < 3; k++) {
                tri[t].c[0][k] = other->pos[3 * other->corner[c0] + k];
                tri[t].c[1][k] = other->pos[3 * other->corner[c] + k];
                tri[t].c[2][k] = other->pos[3 * other->corner[c + 1] + k];
                tri[t].box[k] = fmin(tri[t].c[0][k], fmin(tri[t].c[1][k], tri[t].c[2][k]));
                tri[t].box[3 + k] = fmax(tri[t].c[0][k], fmax(tri[t].c[1][k], tri[t].c[2][k]));
            }
            wide = fmax(wide, tri[t].box[3] - tri[t].box[0]);
        }
    }
    qsort(tri, ntri, sizeof *tri, by_low_x);
    double margin = 1e-9 * D.diag * D.diag;
    uint32_t last = 0;
    for (uint32_t v = 0; v < m->nverts; v++) {
        if (s->vert_dist[v] < 0)
            continue;
        double q[3] = { m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2] }, p[3];
        double best = ntri ? bvh_point_triangle(q, tri[last].c[0], tri[last].c[1], tri[last].c[2], p) : INFINITY;
        /* the first triangle whose low x is past q.x - reach - wide */
        double reach = sqrt(best * (1 + 1e-9) + margin) * (1 + 1e-9);
        uint32_t lo = 0, hi = ntri;
        while (lo < hi) {
            uint32_t mid = lo + (hi - lo) / 2;
            if (tri[mid].box[0] < q[0] - reach - wide)
                lo = mid + 1;
            else
                hi = mid;
        }
        for (t = lo; t < ntri; t++) {
            if (tri[t].box[0] > q[0] + reach)
                break;      /* and so are all after it */
            double b2 = 0;
            for (int k = 0; k < 3; k++) {
                double out = fmax(tri[t].box[k] - q[k], q[k] - tri[t].box[3 + k]);
                b2 += out > 0 ? out * out : 0;
            }
            if (b2 > best * (1 + 1e-9) + margin)
                continue;
            double d2 = bvh_point_triangle(q, tri[t].c[0], tri[t].c[1], tri[t].c[2], p);
            if (d2 < best) {
                best = d2;
                last = t;
                reach = sqrt(best * (1 + 1e-9) + margin) * (1 + 1e-9);
            }
        }
        double d = sqrt(best);
        d = d < D.zero ? 0 : d;
        cr_assert(s->vert_dist[v] == (float)d, "vertex %u: %.9g, every triangle says %.9g", v, s->vert_dist[v], d);
        cr_assert_leq(d, s->max);
    }
    free(tri);
    cr_assert_leq(s->max, s->bound);
}

/* ==== Known answers ==== */

Test(diff, a_model_against_itself_is_the_same)
{
    load(&MA, "assets/knot.obj");
    load(&MB, "assets/knot.obj");
    const Diff *d = run();
    cr_assert_eq(d->hausdorff, 0);
    cr_assert_eq(d->a.mean, 0);
    cr_assert_eq(d->nregions, 0);
    cr_assert(!diff_differ(d));
    cr_assert_float_eq(d->tolerance, DIFF_TOL_FRACTION * d->diag, 1e-12);
    cr_assert_gt(d->a.vertex_samples, 0);
    cr_assert_geq(d->a.face_samples, DIFF_SAMPLES / 2, "%llu", (unsigned long long)d->a.face_samples);
}

/* The outer equator's vertex of the torus (farthest from its axis),
 * and its normal: the mean of its faces' (locally convex there, so the
 * normal's line meets the surface first at the vertex). */
static uint32_t outer_vertex(const Mesh *m, double n[3])
{
    uint32_t best = 0;
    double far = -1;
    for (uint32_t v = 0; v < m->nverts; v++) {
        double r = hypot(m->pos[3 * v], m->pos[3 * v + 2]);
        if (r > far) {
            far = r;
            best = v;
        }
    }
    n[0] = n[1] = n[2] = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        int has = 0;
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++)
            has |= m->corner[c] == best;
        if (!has)
            continue;
        const float *a = &m->pos[3 * m->corner[m->face_start[f]]], *b = &m->pos[3 * m->corner[m->face_start[f] + 1]],
                    *c = &m->pos[3 * m->corner[m->face_start[f] + 2]];
        double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, w[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
        double x[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
        double l = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        for (int k = 0; k < 3; k++)
            n[k] += x[k] / l;
    }
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] /= l;
    return best;
}

Test(diff, one_vertex_moved_along_its_normal)
{
    load(&MA, "assets/torus.obj");
    copy_mesh(&MB, &MA, NULL, NULL);
    double n[3];
    uint32_t v = outer_vertex(&MA, n);
    double dmove = 0.05;
    for (int k = 0; k < 3; k++)
        MB.pos[3 * v + k] = (float)(MA.pos[3 * v + k] + dmove * n[k]);
    /* the distance the float position really moved */
    double moved = 0;
    for (int k = 0; k < 3; k++)
        moved += ((double)MB.pos[3 * v + k] - MA.pos[3 * v + k]) * ((double)MB.pos[3 * v + k] - MA.pos[3 * v + k]);
    moved = sqrt(moved);
    const Diff *d = run();
    double size = d->diag;
    cr_assert(fabs(d->hausdorff - moved) <= 1e-6 * size, "max %.9g, moved %.9g", d->hausdorff, moved);
    cr_assert(fabs(d->b.max - moved) <= 1e-6 * size);
    for (int k = 0; k < 3; k++)
        cr_assert_float_eq(d->b.max_at[k], MB.pos[3 * v + k], 1e-6 * size, "the farthest point is the vertex");
    cr_assert_lt(d->a.max, d->b.max, "A's surface under the bump is nearer to B than the bump's top to A");
    cr_assert_eq(d->nregions, 1, "%u regions", d->nregions);
    cr_assert(d->regions[0].faces_a > 0 && d->regions[0].faces_b > 0, "the bump and what it covers: one region");
    cr_assert(diff_differ(d));
    vertices_against_brute(&d->a, &MA, &MB);
    vertices_against_brute(&d->b, &MB, &MA);
}

Test(diff, a_cube_added)
{
    cr_assert_eq(tl_mesh_init(&MA, "a.obj"), 0);
    cube(&MA, 0, 0, 0);
    cr_assert_eq(tl_mesh_finish(&MA), 0);
    cr_assert_eq(tl_mesh_init(&MB, "b.obj"), 0);
    cube(&MB, 0, 0, 0);
    cube(&MB, 3, 0, 0);
    cr_assert_eq(tl_mesh_finish(&MB), 0);
    const Diff *d = run();
    cr_assert_float_eq(d->b.area_over, 6, 1e-9, "added %.12g", d->b.area_over);
    cr_assert_eq(d->a.area_over, 0);
    cr_assert_eq(d->a.max, 0);
    cr_assert_eq(d->hausdorff, 3);
    /* the mean of B's surface: 0 on the first cube, 2 and 3 on the
     * second's near and far sides, 2 to 3 along its other four: 15 / 12 */
    cr_assert_float_eq(d->b.mean, 1.25, 1e-9, "%.12g", d->b.mean);
    cr_assert_eq(d->nregions, 1);
    cr_assert_float_eq(d->regions[0].added, 6, 1e-9);
    cr_assert_eq(d->regions[0].removed, 0);
    cr_assert_eq(d->regions[0].faces_b, 6);
    cr_assert_eq(d->regions[0].lo[0], 3);
    cr_assert_eq(d->regions[0].hi[0], 4);
    for (uint32_t f = 0; f < 12; f++)
        cr_assert_eq(d->b.face_class[f], f < 6 ? DIFF_SAME : DIFF_OVER, "face %u", f);
    vertices_against_brute(&d->b, &MB, &MA);
    /* the other way round: removed, the sides swapped */
    Mesh t = MA;
    MA = MB;
    MB = t;
    d = run();
    cr_assert_float_eq(d->a.area_over, 6, 1e-9);
    cr_assert_eq(d->b.area_over, 0);
    cr_assert_eq(d->hausdorff, 3);
}

/* Positions scaled by 1.01 about a centre. */
static void scale_about(float *p, const void *ctx)
{
    const double *c = ctx;
    for (int k = 0; k < 3; k++)
        p[k] = (float)(c[k] + 1.01 * ((double)p[k] - c[k]));
}

static void scaled_by_1_01(const char *path)
{
    load(&MA, path);
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY }, c[3], far = 0;
    for (uint32_t v = 0; v < MA.nverts; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], MA.pos[3 * v + k]);
            hi[k] = fmax(hi[k], MA.pos[3 * v + k]);
        }
    for (int k = 0; k < 3; k++)
        c[k] = (lo[k] + hi[k]) / 2;
    for (uint32_t v = 0; v < MA.nverts; v++) {
        double r = 0;
        for (int k = 0; k < 3; k++)
            r += ((double)MA.pos[3 * v + k] - c[k]) * ((double)MA.pos[3 * v + k] - c[k]);
        far = fmax(far, sqrt(r));
    }
    copy_mesh(&MB, &MA, scale_about, c);
    const Diff *d = run();
    cr_assert(fabs(d->hausdorff - 0.01 * far) <= 0.01 * 0.01 * far, "%s: max %.9g, 0.01 x farthest %.9g", path,
              d->hausdorff, 0.01 * far);
    cr_assert_leq(d->a.max, d->b.max * 1.0001, "nothing moved more than the farthest point");
}

Test(diff, scaled_by_1_01_about_its_centre)
{
    scaled_by_1_01("assets/knot.obj");
    teardown();
    const char *bunny = tl_shared_model("stanford-bunny.obj");
    if (bunny)
        scaled_by_1_01(bunny);
}

/* A's surface: the unit square z = 0 cut into 16 x 16 cells of two
 * triangles; B's: the plane z = H + S x over a square far wider, so
 * that every point of A is nearest to B's inside. A point (x, y, 0) is
 * (H + S x) / sqrt(1 + S^2) from B: linear in x, so its mean over A is
 * its value at x = 1/2, and it passes tol on the strip x > X0, of area
 * 1 - X0. Every sampling holds that mean (the corners' mean over a
 * triangle and a small triangle's centre are both exact for a linear
 * function); the corners' share above tol is exact too. */
#define TILT_H 0.5
#define TILT_S 0.25
#define TILT_N 16
static void tilted_planes(void)
{
    cr_assert_eq(tl_mesh_init(&MA, "grid.obj"), 0);
    for (int j = 0; j <= TILT_N; j++)
        for (int i = 0; i <= TILT_N; i++)
            cr_assert_eq(tl_mesh_vertex(&MA, (float)i / TILT_N, (float)j / TILT_N, 0), 0);
    for (uint32_t j = 0; j < TILT_N; j++)
        for (uint32_t i = 0; i < TILT_N; i++) {
            uint32_t v = j * (TILT_N + 1) + i;
            uint32_t t1[3] = { v, v + 1, v + TILT_N + 2 }, t2[3] = { v, v + TILT_N + 2, v + TILT_N + 1 };
            cr_assert_eq(tl_mesh_face(&MA, t1, 3), 0);
            cr_assert_eq(tl_mesh_face(&MA, t2, 3), 0);
        }
    cr_assert_eq(tl_mesh_finish(&MA), 0);
    cr_assert_eq(tl_mesh_init(&MB, "plane.obj"), 0);
    for (int k = 0; k < 4; k++) {
        float x = k & 1 ? 11 : -10, y = k & 2 ? 11 : -10;
        cr_assert_eq(tl_mesh_vertex(&MB, x, y, (float)(TILT_H + TILT_S * x)), 0);
    }
    uint32_t q[4] = { 0, 1, 3, 2 };
    cr_assert_eq(tl_mesh_face(&MB, q, 4), 0);
    cr_assert_eq(tl_mesh_finish(&MB), 0);
}

Test(diff, a_tilted_plane_has_the_mean_of_its_middle_at_any_sampling)
{
    tilted_planes();
    double slope = sqrt(1 + TILT_S * TILT_S), x0 = 0.3;
    double tol = (TILT_H + TILT_S * x0) / slope, mean = (TILT_H + TILT_S * 0.5) / slope;
    /* 512 triangles of area 1/512: a sample budget of 64 gives each
     * r = 0 (its corners alone), 512 gives r = 1 (its centre), 4608
     * r = 3 */
    static const uint32_t budget[3] = { 64, 512, 4608 };
    for (int k = 0; k < 3; k++) {
        DiffOpts o = { 1, tol, NULL, budget[k], 0, NULL, NULL };
        diff_free(&D);
        cr_assert_eq(diff_compute(&D, &MA, &MB, &o, E, sizeof E), 0, "%s", E);
        cr_assert_float_eq(D.a.area, 1.0, 1e-9);
        cr_assert(fabs(D.a.mean - mean) <= 1e-6 * mean, "%u samples: mean %.9g, the middle's distance %.9g",
                  budget[k], D.a.mean, mean);
        cr_assert(fabs(D.a.max - (TILT_H + TILT_S) / slope) <= 1e-6, "%u samples: max %.9g", budget[k], D.a.max);
        if (k == 0)
            cr_assert(fabs(D.a.area_over - (1 - x0)) <= 1e-6, "corners alone: area over %.9g, the strip's %.9g",
                      D.a.area_over, 1 - x0);
        else
            cr_assert(fabs(D.a.area_over - (1 - x0)) <= 1.0 / TILT_N, "%u samples: area over %.9g", budget[k],
                      D.a.area_over);
    }
}

Test(diff, a_quad_against_its_two_triangles)
{
    cr_assert_eq(tl_mesh_init(&MA, "quad.obj"), 0);
    cr_assert_eq(tl_mesh_init(&MB, "tris.obj"), 0);
    float p[4][3] = { { 0, 0, 0 }, { 3, 0, 1 }, { 3, 2, 1 }, { 0, 2, 0 } };    /* planar, tilted */
    for (int i = 0; i < 4; i++) {
        cr_assert_eq(tl_mesh_vertex(&MA, p[i][0], p[i][1], p[i][2]), 0);
        cr_assert_eq(tl_mesh_vertex(&MB, p[i][0], p[i][1], p[i][2]), 0);
    }
    uint32_t q[4] = { 0, 1, 2, 3 }, t1[3] = { 1, 2, 3 }, t2[3] = { 1, 3, 0 };    /* the other diagonal */
    cr_assert_eq(tl_mesh_face(&MA, q, 4), 0);
    cr_assert_eq(tl_mesh_face(&MB, t1, 3), 0);
    cr_assert_eq(tl_mesh_face(&MB, t2, 3), 0);
    cr_assert_eq(tl_mesh_finish(&MA), 0);
    cr_assert_eq(tl_mesh_finish(&MB), 0);
    const Diff *d = run_tol(0);
    cr_assert_eq(d->hausdorff, 0, "%.17g", d->hausdorff);
    cr_assert(!diff_differ(d), "the same even at tolerance 0");
    cr_assert_gt(d->a.face_samples + d->a.edge_samples, 1000, "the faces' insides were sampled");
}

Test(diff, stl_against_the_obj_it_came_from)
{
    load(&MA, "assets/knot.obj");
    size_t len;
    char *stl = w_stl_binary(&MA, &len);
    cr_assert(stl);
    cr_assert_eq(mesh_parse_buffer(&MB, "knot.stl", "stl", stl, len, E, sizeof E), 0, "%s", E);
    free(stl);
    cr_assert_neq(MB.nverts, MA.nverts * 3, "STL's corners were merged into vertices");
    const Diff *d = run_tol(0);
    cr_assert_eq(d->hausdorff, 0);
    cr_assert_eq(d->nregions, 0);
}

Test(diff, another_vertex_and_face_order_is_the_same)
{
    load(&MA, "assets/torus.obj");
    cr_assert_eq(tl_mesh_init(&MB, "shuffled.obj"), 0);
    uint32_t n = MA.nverts, *perm = malloc(n * sizeof *perm), *inv = malloc(n * sizeof *inv);
    for (uint32_t i = 0; i < n; i++)
        perm[i] = i;
    srand(7);
    for (uint32_t i = n - 1; i > 0; i--) {
        uint32_t j = (uint32_t)rand() % (i + 1), t = perm[i];
        perm[i] = perm[j];
        perm[j] = t;
    }
    for (uint32_t i = 0; i < n; i++) {
        inv[perm[i]] = i;
        cr_assert_eq(tl_mesh_vertex(&MB, MA.pos[3 * perm[i]], MA.pos[3 * perm[i] + 1], MA.pos[3 * perm[i] + 2]), 0);
    }
    for (uint32_t f = MA.nfaces; f-- > 0;) {     /* the faces backwards, each turned one corner on */
        uint32_t c0 = MA.face_start[f], k = MA.face_start[f + 1] - c0, c[16];
        for (uint32_t i = 0; i < k; i++)
            c[i] = inv[MA.corner[c0 + (i + 1) % k]];
        cr_assert_eq(tl_mesh_face(&MB, c, k), 0);
    }
    cr_assert_eq(tl_mesh_finish(&MB), 0);
    free(perm);
    free(inv);
    const Diff *d = run_tol(0);
    cr_assert_eq(d->hausdorff, 0, "%.17g", d->hausdorff);
}

Test(diff, the_directions_swap_with_the_models)
{
    load(&MA, "assets/knot.obj");
    double c[3] = { 0.3, -0.2, 0.1 };
    copy_mesh(&MB, &MA, scale_about, c);
    const Diff *d = run();
    double ab = d->a.max, ba = d->b.max, h = d->hausdorff, ma = d->a.mean;
    vertices_against_brute(&d->a, &MA, &MB);
    vertices_against_brute(&d->b, &MB, &MA);
    Mesh t = MA;
    MA = MB;
    MB = t;
    d = run();
    cr_assert_eq(d->a.max, ba);
    cr_assert_eq(d->b.max, ab);
    cr_assert_eq(d->b.mean, ma);
    cr_assert_eq(d->hausdorff, h);
}

Test(diff, two_bumps_are_two_regions)
{
    load(&MA, "assets/torus.obj");
    copy_mesh(&MB, &MA, NULL, NULL);
    /* the outer vertex and the one opposite it, moved out */
    double n[3];
    uint32_t v = outer_vertex(&MA, n), w = 0;
    double far = -1;
    for (uint32_t i = 0; i < MA.nverts; i++) {
        double dx = MA.pos[3 * i] + MA.pos[3 * v], dz = MA.pos[3 * i + 2] + MA.pos[3 * v + 2], y = MA.pos[3 * i + 1];
        double r = -(dx * dx + dz * dz) - y * y;    /* nearest to the opposite point */
        if (r > far || far < -1e29) {
            far = r;
            w = i;
        }
    }
    for (int k = 0; k < 3; k++) {
        MB.pos[3 * v + k] = (float)(MA.pos[3 * v + k] + 0.05 * n[k]);
        MB.pos[3 * w + k] = (float)(MA.pos[3 * w + k] * 1.05);
    }
    const Diff *d = run();
    cr_assert_eq(d->nregions, 2, "%u regions", d->nregions);
    cr_assert_geq(d->regions[0].max, d->regions[1].max, "the farthest first");
}

/* A wavy sheet of n x n quads, each corner raised by h(x, y) and the
 * mesh's own wobble (seeded by st, 0: none): big enough for several
 * chunks of vertices and faces. */
static void sheet(Mesh *m, uint32_t n, uint64_t st)
{
    cr_assert_eq(tl_mesh_init(m, "sheet.obj"), 0);
    for (uint32_t j = 0; j <= n; j++)
        for (uint32_t i = 0; i <= n; i++) {
            double x = (double)i / n, y = (double)j / n, z = 0.05 * sin(9 * x) * cos(7 * y);
            if (st) {
                st ^= st << 13;
                st ^= st >> 7;
                st ^= st << 17;
                z += ((double)(st >> 11) / 9007199254740992.0 - 0.5) * 2e-3;
                if (i > n / 3 && i < n / 2 && j > n / 3 && j < n / 2)
                    z += 0.01;     /* a raised patch: a region */
            }
            cr_assert_eq(tl_mesh_vertex(m, (float)x, (float)y, (float)z), 0);
        }
    for (uint32_t j = 0; j < n; j++)
        for (uint32_t i = 0; i < n; i++) {
            uint32_t v = j * (n + 1) + i, c[4] = { v, v + 1, v + n + 2, v + n + 1 };
            cr_assert_eq(tl_mesh_face(m, c, 4), 0);
        }
    cr_assert_eq(tl_mesh_finish(m), 0);
}

static void same_side(const DiffSide *x, const DiffSide *y, const char *what)
{
    cr_assert(x->max == y->max && x->bound == y->bound && x->mean == y->mean && x->area_over == y->area_over &&
              !memcmp(x->max_at, y->max_at, sizeof x->max_at), "%s: the figures", what);
    cr_assert(x->vertex_samples == y->vertex_samples && x->edge_samples == y->edge_samples &&
              x->face_samples == y->face_samples, "%s: the samples", what);
    cr_assert(!memcmp(x->vert_dist, y->vert_dist, x->nverts * sizeof *x->vert_dist), "%s: vertex distances", what);
    cr_assert(!memcmp(x->vert_link, y->vert_link, x->nverts * sizeof *x->vert_link), "%s: vertex links", what);
    cr_assert(!memcmp(x->face_dist, y->face_dist, x->nfaces * sizeof *x->face_dist), "%s: face distances", what);
    cr_assert(!memcmp(x->face_link, y->face_link, x->nfaces * sizeof *x->face_link), "%s: face links", what);
    cr_assert(!memcmp(x->face_over, y->face_over, x->nfaces * sizeof *x->face_over), "%s: face areas over", what);
    cr_assert(!memcmp(x->face_class, y->face_class, x->nfaces), "%s: face classes", what);
}

Test(diff, the_same_bits_on_any_threads)
{
    /* 40,401 vertices and 40,000 quads a side: several chunks of
     * vertices and of faces, handed out beside the checks and the
     * builds; every figure, every vertex's and face's distance and link
     * and every region the same on 1, 2, 3 and 4 threads */
    sheet(&MA, 200, 0);
    sheet(&MB, 200, 0x2545F4914F6CDD1Dull);
    Diff one;
    DiffOpts o1 = { 1, -1, NULL, 0, 1, NULL, NULL };
    cr_assert_eq(diff_compute(&one, &MA, &MB, &o1, E, sizeof E), 0, "%s", E);
    cr_assert_gt(one.hausdorff, 0.005);
    cr_assert_geq(one.nregions, 1);
    for (int threads = 2; threads <= 4; threads++) {
        DiffOpts o = { threads, -1, NULL, 0, 1, NULL, NULL };
        diff_free(&D);
        cr_assert_eq(diff_compute(&D, &MA, &MB, &o, E, sizeof E), 0, "%s", E);
        same_side(&one.a, &D.a, "A");
        same_side(&one.b, &D.b, "B");
        cr_assert(D.hausdorff == one.hausdorff && D.nregions == one.nregions, "%d threads", threads);
        cr_assert(!memcmp(D.regions, one.regions, one.nregions * sizeof *one.regions), "%d threads: regions", threads);
        cr_assert(!memcmp(D.check, one.check, sizeof one.check), "%d threads: the checks", threads);
    }
    diff_free(&one);
}

Test(diff, a_vertex_not_a_finite_point_is_refused)
{
    /* a NaN, then an infinity, at the third corner of the first face */
    const float bad[2] = { NAN, INFINITY };
    for (int i = 0; i < 2; i++) {
        load(&MA, "assets/knot.obj");
        copy_mesh(&MB, &MA, NULL, NULL);
        MB.pos[3 * MB.corner[2] + 1] = bad[i];
        DiffOpts o = { 2, -1, NULL, 0, 1, NULL, NULL };
        diff_free(&D);
        cr_assert_eq(diff_compute(&D, &MA, &MB, &o, E, sizeof E), -1);
        char want[64];
        snprintf(want, sizeof want, "vertex %u is not a finite point", MB.corner[2] + 1);
        cr_assert(strstr(E, want), "%s", E);
        mesh_free(&MA);
        mesh_free(&MB);
    }
}

/* ==== The files, the headline, the picture ==== */

static DiffSet S;

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    cr_assert(f);
    fputs(text, f);
    cr_assert_eq(fclose(f), 0);
}

static const char *const CUBE = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n";

/* The set of files a and b into set (threads: 0, one per core). */
static void load_set_on(DiffSet *set, const char *a, const char *b, const char *show, int scene, int threads)
{
    char pa[64], pb[64];
    snprintf(pa, sizeof pa, "/tmp/zv-diff-%d-a.obj", (int)getpid());
    snprintf(pb, sizeof pb, "/tmp/zv-diff-%d-b.obj", (int)getpid());
    write_file(pa, a);
    write_file(pb, b);
    char *argv[] = { "zview", "--diff", "--show", (char *)show, pa, pb, NULL };
    Options o;
    cr_assert_eq(cli_parse(6, argv, &o, E, sizeof E), 0, "%s", E);
    o.no_sandbox = 1;
    if (threads)
        o.threads = threads;
    cr_assert_eq(diff_load(set, &o, scene, E, sizeof E), 0, "%s", E);
    unlink(pa);
    unlink(pb);
}

static void load_set(const char *a, const char *b, const char *show, int scene)
{
    load_set_on(&S, a, b, show, scene, 0);
}

Test(diff, a_hole_made_is_the_headline)
{
    char closed[512], open[512];
    snprintf(closed, sizeof closed, "%sf 4 1 5 8\n", CUBE);
    snprintf(open, sizeof open, "%s", CUBE);
    load_set(closed, open, "both", 0);
    cr_assert(S.d.check[0].watertight && !S.d.check[1].watertight);
    char h[256];
    diff_headline(&S, 0, " | ", h, sizeof h);
    cr_assert_str_eq(h, "no longer watertight (1 hole) | max 0.5 | 1 region changed");
    cr_assert(diff_differ(&S.d), "A's face B lacks is half a side from B's others");
    cr_assert_float_eq(S.d.a.area_over, 1, 0.02, "%g: the face, but a band along its sides within the tolerance",
                       S.d.a.area_over);
    diff_set_free(&S);
    load_set(open, closed, "both", 0);
    diff_headline(&S, 0, " | ", h, sizeof h);
    cr_assert(!strncmp(h, "now watertight | max 0.5", 24), "%s", h);
    diff_headline(&S, 1, " | ", h, sizeof h);
    cr_assert_str_eq(h, "1 changed");
    diff_set_free(&S);
}

/* The picture's ids: every algorithm's the z-buffer's, for a view. */
static void algorithms_agree(Scene *s, int show)
{
    FrameBufs ref = { 0 }, fb = { 0 };
    ScreenPolys sp = { 0 };
    HsrStats st;
    cr_assert_eq(tl_render(s, hsr_algos[0], 1, 96, 64, 0, &sp, &ref, &st), 0);
    long drawn = 0;
    for (size_t i = 0; i < (size_t)ref.w * ref.h; i++)
        drawn += ref.ids[i] >= 0;
    cr_assert_gt(drawn, 100, "show %d: something is drawn", show);
    for (int a = 1; a < hsr_nalgos; a++)
        for (int threads = 1; threads <= 2; threads++) {
            cr_assert_eq(tl_render(s, hsr_algos[a], threads, 96, 64, 0, &sp, &fb, &st), 0);
            int x, y;
            cr_assert_eq(tl_diff(&ref, &fb, &x, &y), 0, "show %d: %s differs at %d,%d", show, hsr_algos[a]->name, x,
                         y);
        }
    fbuf_free(&ref);
    fbuf_free(&fb);
    screen_free(&sp);
}

Test(diff, the_picture_colours_and_every_algorithm_agrees)
{
    char two[1024];
    snprintf(two, sizeof two,
             "%sf 4 1 5 8\nv 3 0 0\nv 4 0 0\nv 4 1 0\nv 3 1 0\nv 3 0 1\nv 4 0 1\nv 4 1 1\nv 3 1 1\n"
             "f 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 10 11 15 14\nf 11 12 16 15\nf 12 9 13 16\n",
             CUBE);
    char one[512];
    snprintf(one, sizeof one, "%sf 4 1 5 8\n", CUBE);
    load_set(one, two, "both", 1);
    Scene *s = &S.scene;
    cr_assert_eq(s->nfaces, 18);
    cr_assert_eq(S.nobjs_a, 1);
    /* A's faces and B's first cube grey, B's second cube green */
    for (uint32_t g = 0; g < 18; g++) {
        const uint8_t *c = &s->face_rgb[3 * g];
        int green = c[1] > c[0] + 60 && c[1] > c[2] + 60;
        cr_assert_eq(green, g >= 12, "face %u: %d %d %d", g, c[0], c[1], c[2]);
        cr_assert_eq(s->face_surf[g], SURF_PLAIN);
    }
    for (int show = 0; show < DIFF_SHOW_COUNT; show++) {
        cr_assert_eq(diff_show(&S, NULL, show), 0);
        cr_assert_eq(s->gen, S.gen);
        uint32_t polys_a = 0, polys_b = 0;
        for (int i = 0; i < s->nobjs; i++)
            *(i < S.nobjs_a ? &polys_a : &polys_b) += s->objs[i].poly_count;
        cr_assert_eq(polys_a > 0, show != DIFF_SHOW_B, "show %d", show);
        cr_assert_eq(polys_b > 0, show != DIFF_SHOW_A, "show %d", show);
        if (show == DIFF_SHOW_HEAT)
            for (uint32_t g = 0; g < 18; g++)
                cr_assert_eq(s->face_surf[g], SURF_VCOLOUR, "the heat map varies across each face");
        tl_random_view(s, 11 + (uint32_t)show, show & 1);
        algorithms_agree(s, show);
    }
    diff_set_free(&S);
}

Test(diff, the_scene_made_beside_the_measures_is_the_one_made_after)
{
    /* on one thread the scene is made after the diff, on two beside it
     * (DiffOpts.beside): the same objects, colours, camera and picture,
     * and either way the meshes' faces are gone once it is made */
    char two[1024];
    snprintf(two, sizeof two,
             "%sf 4 1 5 8\nv 3 0 0\nv 4 0 0\nv 4 1 0\nv 3 1 0\nv 3 0 1\nv 4 0 1\nv 4 1 1\nv 3 1 1\n"
             "f 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 10 11 15 14\nf 11 12 16 15\nf 12 9 13 16\n",
             CUBE);
    DiffSet one;
    load_set_on(&one, CUBE, two, "both", 1, 1);
    load_set_on(&S, CUBE, two, "both", 1, 2);
    Scene *a = &one.scene, *b = &S.scene;
    cr_assert(one.has_scene && S.has_scene);
    cr_assert_eq(a->nfaces, b->nfaces);
    cr_assert_eq(a->nobjs, b->nobjs);
    cr_assert_eq(one.nobjs_a, S.nobjs_a);
    cr_assert(!memcmp(a->face_rgb, b->face_rgb, 3 * (size_t)a->nfaces), "the colours");
    cr_assert(!memcmp(&a->cam, &b->cam, sizeof a->cam), "the camera");
    for (int i = 0; i < 2; i++) {
        cr_assert_null(a->meshes[i].face_start, "mesh %d's faces", i);
        cr_assert_null(b->meshes[i].face_start, "mesh %d's faces, made beside", i);
        cr_assert_null(b->meshes[i].corner);
    }
    FrameBufs fa = { 0 }, fb = { 0 };
    ScreenPolys sp = { 0 };
    HsrStats st;
    cr_assert_eq(tl_render(a, hsr_algos[0], 1, 96, 64, 0, &sp, &fa, &st), 0);
    cr_assert_eq(tl_render(b, hsr_algos[0], 1, 96, 64, 0, &sp, &fb, &st), 0);
    int x, y;
    cr_assert_eq(tl_diff(&fa, &fb, &x, &y), 0, "the pictures differ at %d,%d", x, y);
    fbuf_free(&fa);
    fbuf_free(&fb);
    screen_free(&sp);
    diff_set_free(&one);
    diff_set_free(&S);
}

static void count_call(void *arg)
{
    ++*(int *)arg;
}

Test(diff, the_callers_task_runs_once_beside_on_several_threads_only)
{
    cr_assert_eq(tl_mesh_init(&MA, "a.obj"), 0);
    cube(&MA, 0, 0, 0);
    cr_assert_eq(tl_mesh_finish(&MA), 0);
    cr_assert_eq(tl_mesh_init(&MB, "b.obj"), 0);
    cube(&MB, 0.5f, 0, 0);
    cr_assert_eq(tl_mesh_finish(&MB), 0);
    for (int threads = 1; threads <= 3; threads++) {
        int calls = 0;
        DiffOpts o = { threads, -1, NULL, 0, 1, count_call, &calls };
        diff_free(&D);
        cr_assert_eq(diff_compute(&D, &MA, &MB, &o, E, sizeof E), 0, "%s", E);
        cr_assert_eq(calls, threads > 1, "%d threads: %d calls", threads, calls);
    }
}

Test(diff, a_model_the_scene_shrinks_is_not_made_beside)
{
    /* scene_build scales a model past 2^120 down, writing the positions
     * the diff reads: scene_build_kept leaves it (1), untouched, and
     * makes an ordinary one keeping the faces */
    cr_assert_eq(tl_mesh_init(&MA, "a.obj"), 0);
    cube(&MA, 1e38f, 0, 0);
    cr_assert_eq(tl_mesh_finish(&MA), 0);
    Mesh *m = calloc(1, sizeof *m);
    cr_assert(m);
    *m = MA;
    memset(&MA, 0, sizeof MA);
    float before = m->pos[0];
    Scene s;
    cr_assert_eq(scene_build_kept(&s, m, 1, E, sizeof E), 1);
    cr_assert(m->pos[0] == before && m->face_start && m->corner, "the mesh as it was");
    cr_assert_eq(tl_mesh_init(&MB, "b.obj"), 0);
    cube(&MB, 0, 0, 0);
    cr_assert_eq(tl_mesh_finish(&MB), 0);
    Mesh *k = calloc(1, sizeof *k);
    cr_assert(k);
    *k = MB;
    memset(&MB, 0, sizeof MB);
    cr_assert_eq(scene_build_kept(&s, k, 1, E, sizeof E), 0, "%s", E);
    cr_assert(k->face_start && k->corner, "the faces kept");
    cr_assert_eq(s.nfaces, 6);
    cr_assert(s.poly_corner != k->corner, "none taken over");
    scene_release_faces(&s);
    cr_assert_null(k->face_start);
    scene_free(&s);         /* frees k */
    mesh_free(m);
    free(m);
}

Test(diff, the_ramp_rises_in_lightness)
{
    double last = -1;
    for (int i = 0; i <= 20; i++) {
        uint8_t c[3];
        diff_ramp(i / 20.0, c);
        /* luma of the sRGB bytes: a rough lightness, enough for the order */
        double y = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        cr_assert_gt(y, last, "step %d", i);
        last = y;
    }
    uint8_t lo[3], hi[3];
    diff_ramp(0, lo);
    diff_ramp(1, hi);
    cr_assert(lo[2] > lo[0] && hi[0] > hi[2], "blue to yellow: %d %d %d, %d %d %d", lo[0], lo[1], lo[2], hi[0], hi[1],
              hi[2]);
}

/* ==== The shared models (make test-models) ==== */

/* Every vertex moved by up to 1e-4 of the diagonal, pseudo-randomly. */
static void wobble(float *p, const void *ctx)
{
    uint64_t *st = (uint64_t *)ctx;
    for (int k = 0; k < 3; k++) {
        *st ^= *st << 13;
        *st ^= *st >> 7;
        *st ^= *st << 17;
        p[k] = (float)(p[k] + ((double)(*st >> 11) / 9007199254740992.0 - 0.5) * 5e-5);
    }
}

/* The dragon against itself (0, at once: every vertex is the other's)
 * and against a copy with every vertex moved: a sample of its vertices
 * against every triangle, and the same figures on one thread and two. */
Test(models, diff_of_the_dragon, .timeout = 900)
{
    const char *p = tl_shared_model("dragon.obj");
    if (!p)
        cr_skip_test("no ../shared/models/dragon.obj");
    load(&MA, p);
    load(&MB, p);
    const Diff *d = run();
    cr_assert_eq(d->hausdorff, 0);
    mesh_free(&MB);
    static uint64_t st = 0x9E3779B97F4A7C15ull;
    copy_mesh(&MB, &MA, wobble, &st);
    DiffOpts o1 = { 1, -1, NULL, 0, 1, NULL, NULL };
    Diff one;
    cr_assert_eq(diff_compute(&one, &MA, &MB, &o1, E, sizeof E), 0, "%s", E);
    d = run();
    cr_assert(one.hausdorff == d->hausdorff && one.a.mean == d->a.mean && one.b.mean == d->b.mean &&
              one.nregions == d->nregions && one.a.bound == d->a.bound,
              "one thread and two give the same figures");
    cr_assert(!memcmp(one.a.face_dist, d->a.face_dist, MA.nfaces * sizeof *d->a.face_dist));
    diff_free(&one);
    cr_assert_gt(d->hausdorff, 0);
    cr_assert_leq(d->hausdorff, 5e-5 * sqrt(3) / 2 * 1.01, "no point moved farther than its wobble");
    /* 60 vertices of each against every triangle of the other */
    for (int side = 0; side < 2; side++) {
        const Mesh *m = side ? &MB : &MA, *other = side ? &MA : &MB;
        const DiffSide *s = side ? &d->b : &d->a;
        for (uint32_t i = 0; i < 60; i++) {
            uint32_t v = (uint32_t)(((uint64_t)i * 2654435761u) % m->nverts);
            if (s->vert_dist[v] < 0)
                continue;
            double q[3] = { m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2] }, best = INFINITY, pt[3];
            for (uint32_t f = 0; f < other->nfaces; f++) {
                double a[3], b[3], c[3];
                for (int k = 0; k < 3; k++) {
                    a[k] = other->pos[3 * other->corner[3 * f] + k];
                    b[k] = other->pos[3 * other->corner[3 * f + 1] + k];
                    c[k] = other->pos[3 * other->corner[3 * f + 2] + k];
                }
                best = fmin(best, bvh_point_triangle(q, a, b, c, pt));
            }
            double want = sqrt(best) < d->zero ? 0 : sqrt(best);
            cr_assert(s->vert_dist[v] == (float)want, "side %d vertex %u: %.9g, every triangle says %.9g", side, v,
                      s->vert_dist[v], want);
        }
    }
}
