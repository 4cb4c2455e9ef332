/* test_bvh.c: the bounding-volume hierarchy (src/geom/bvh.c).
 *
 * The point-triangle distance against answers worked out by hand (a
 * point over the inside, beyond each side and each corner, triangles of
 * no area); then the hierarchy's nearest point against every triangle
 * tried (the least of bvh_point_triangle over all of them, bit for bit)
 * on random triangle soups, the bundled models, far from the origin
 * (where the boxes' float test needs its margin), and inputs that make
 * a build degenerate (every triangle on one point, on one line, a
 * single triangle); its depth stays within BVH_DEPTH_MAX, every
 * triangle is in exactly one leaf, and every leaf's box holds its
 * triangles. A query started from a guess (bvh_closest_from) gives the
 * same answer, bit for bit and triangle for triangle, whatever the
 * guess. */

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "mesh.h"

static uint64_t rng = 0x9E3779B97F4A7C15ull;

static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* ==== The point-triangle distance ==== */

static const double A[3] = { 0, 0, 0 }, B[3] = { 2, 0, 0 }, C[3] = { 0, 2, 0 };

static double dist(double x, double y, double z, double out[3])
{
    double q[3] = { x, y, z };
    return sqrt(bvh_point_triangle(q, A, B, C, out));
}

Test(bvh, point_over_the_inside_is_its_height)
{
    double p[3];
    cr_assert_float_eq(dist(0.5, 0.5, 3, p), 3, 1e-15);
    cr_assert(p[0] == 0.5 && p[1] == 0.5 && p[2] == 0, "%g %g %g", p[0], p[1], p[2]);
    cr_assert_float_eq(dist(0.25, 1.5, -0.125, p), 0.125, 1e-15);
}

Test(bvh, point_beyond_a_side_or_a_corner)
{
    double p[3];
    /* beyond the side a b (y < 0): the distance in the plane and out of it */
    cr_assert_float_eq(dist(1, -3, 4, p), 5, 1e-14);
    cr_assert(p[0] == 1 && p[1] == 0 && p[2] == 0);
    /* beyond the long side b c: from (2, 2, 0) to the side's middle (1, 1, 0) */
    cr_assert_float_eq(dist(2, 2, 0, p), sqrt(2), 1e-14);
    cr_assert_float_eq(p[0], 1, 1e-15);
    cr_assert_float_eq(p[1], 1, 1e-15);
    /* beyond each corner */
    cr_assert_float_eq(dist(-1, -1, 0, p), sqrt(2), 1e-15);
    cr_assert(p[0] == 0 && p[1] == 0);
    cr_assert_float_eq(dist(5, -4, 0, p), 5, 1e-14);
    cr_assert(p[0] == 2 && p[1] == 0);
    cr_assert_float_eq(dist(-3, 6, 0, p), 5, 1e-14);
    cr_assert(p[0] == 0 && p[1] == 2);
}

Test(bvh, a_triangle_of_no_area_is_its_longest_side)
{
    double q[3] = { 1, 1, 0 }, p[3];
    const double a[3] = { 0, 0, 0 }, b[3] = { 4, 0, 0 }, c[3] = { 2, 0, 0 };
    cr_assert_float_eq(bvh_point_triangle(q, a, b, c, p), 1, 1e-15);
    cr_assert(p[0] == 1 && p[1] == 0);
    const double pt[3] = { 3, 4, 0 };
    double o[3] = { 0, 0, 0 };
    cr_assert_float_eq(bvh_point_triangle(o, pt, pt, pt, p), 25, 1e-13);
    cr_assert(p[0] == 3 && p[1] == 4);
}

/* ==== The hierarchy against every triangle ==== */

typedef struct {
    float    *pos;
    uint32_t *tri;
    uint32_t  nv, nt;
} Soup;

static void soup_free(Soup *s)
{
    free(s->pos);
    free(s->tri);
    memset(s, 0, sizeof *s);
}

/* n triangles, each of three fresh vertices: a random corner in the
 * box [off, off + span)^3 and two more within size of it */
static void soup(Soup *s, uint32_t n, double off, double span, double size)
{
    s->nv = 3 * n;
    s->nt = n;
    s->pos = malloc(9 * (size_t)n * sizeof *s->pos);
    s->tri = malloc(3 * (size_t)n * sizeof *s->tri);
    cr_assert(s->pos && s->tri);
    for (uint32_t t = 0; t < n; t++) {
        double c[3] = { off + urand() * span, off + urand() * span, off + urand() * span };
        for (int v = 0; v < 3; v++) {
            for (int k = 0; k < 3; k++)
                s->pos[9 * t + 3 * v + k] = (float)(c[k] + (v ? (urand() - 0.5) * size : 0));
            s->tri[3 * t + v] = 3 * t + v;
        }
    }
}

/* The least distance over every triangle, and the first in index order
 * that has it (the hierarchy's own order may differ: only the distance
 * is compared). */
static double brute(const Soup *s, const double q[3])
{
    double best = INFINITY, p[3];
    for (uint32_t t = 0; t < s->nt; t++) {
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; k++) {
            a[k] = s->pos[3 * s->tri[3 * t] + k];
            b[k] = s->pos[3 * s->tri[3 * t + 1] + k];
            c[k] = s->pos[3 * s->tri[3 * t + 2] + k];
        }
        double d = bvh_point_triangle(q, a, b, c, p);
        best = d < best ? d : best;
    }
    return best;
}

/* The tree holds each triangle once, each leaf's box holds its
 * triangles, an inner child's box holds its node's, and it is no deeper
 * than promised. */
static void tree_sound(const Bvh *b, const Soup *s)
{
    cr_assert_leq(b->depth, BVH_DEPTH_MAX);
    uint8_t *seen = calloc(s->nt ? s->nt : 1, 1);
    cr_assert(seen);
    uint64_t leaves = 0;
    for (uint32_t i = 0; i < b->nnodes; i++)
        for (int c = 0; c < BVH_WIDTH; c++) {
            const BvhNode *n = &b->node[i];
            if (n->child[c] == BVH_NONE)
                continue;
            if (!n->count[c]) {
                const BvhNode *ch = &b->node[n->child[c]];
                cr_assert_gt(n->child[c], i, "a child comes after its parent");
                for (int g = 0; g < BVH_WIDTH; g++)
                    for (int k = 0; k < 3; k++)
                        if (ch->child[g] != BVH_NONE)
                            cr_assert(ch->lo[k][g] >= n->lo[k][c] && ch->hi[k][g] <= n->hi[k][c]);
                continue;
            }
            cr_assert_leq(n->count[c], BVH_LEAF_MAX);
            for (uint32_t t = n->child[c]; t < n->child[c] + n->count[c]; t++) {
                cr_assert_lt(t, b->ntris);
                cr_assert_eq(seen[b->id[t]], 0, "triangle %u twice", b->id[t]);
                seen[b->id[t]] = 1;
                leaves++;
                for (int v = 0; v < 3; v++)
                    for (int k = 0; k < 3; k++) {
                        float x = b->corner[9 * (size_t)t + 3 * v + k];
                        cr_assert(x >= n->lo[k][c] && x <= n->hi[k][c]);
                        cr_assert(x == s->pos[3 * s->tri[3 * b->id[t] + v] + k], "corner of %u", b->id[t]);
                    }
            }
        }
    cr_assert_eq(leaves, s->nt);
    free(seen);
}

/* Queries near and far from the soup against every triangle. */
static void against_brute(const Soup *s, int nq, double off, double span)
{
    Bvh b;
    char err[128];
    cr_assert_eq(bvh_build(&b, s->pos, s->nv, s->tri, NULL, s->nt, err, sizeof err), 0, "%s", err);
    tree_sound(&b, s);
    uint32_t last = BVH_NONE;
    for (int i = 0; i < nq; i++) {
        double q[3];
        if (i % 3 == 1 && s->nt) {
            /* inside a triangle, then off it along its normal by up to
             * span / 200: near enough that float's rounding of the point
             * (1/16 at 1e6) decides between boxes */
            uint32_t t = (uint32_t)(urand() * s->nt) % s->nt;
            double u = urand(), v = urand() * (1 - u), c[3][3], n[3];
            for (int k = 0; k < 3; k++)
                for (int j = 0; j < 3; j++)
                    c[k][j] = s->pos[3 * s->tri[3 * t + k] + j];
            double e1[3] = { c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2] };
            double e2[3] = { c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2] };
            n[0] = e1[1] * e2[2] - e1[2] * e2[1];
            n[1] = e1[2] * e2[0] - e1[0] * e2[2];
            n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), h = urand() * span / 200;
            for (int k = 0; k < 3; k++)
                q[k] = c[0][k] + u * e1[k] + v * e2[k] + (l > 0 ? n[k] / l * h : 0);
        } else if (i % 3 == 0 && s->nt) {
            /* on or just off a corner or the inside of a triangle */
            uint32_t t = (uint32_t)(urand() * s->nt) % s->nt, v = s->tri[3 * t + i % 9 / 3];
            for (int k = 0; k < 3; k++)
                q[k] = s->pos[3 * v + k] + (i % 2 ? (urand() - 0.5) * 1e-6 * span : 0);
        } else {
            for (int k = 0; k < 3; k++)
                q[k] = off + (urand() * 1.4 - 0.2) * span;
        }
        BvhHit h;
        bvh_closest(&b, q, &h);
        double want = brute(s, q);
        cr_assert(h.d2 == want, "query %d: %.17g, every triangle says %.17g", i, h.d2, want);
        cr_assert(h.tri < b.ntris);
        /* the point given is on that triangle, at that distance */
        double p[3], a[3], bb[3], c[3];
        for (int k = 0; k < 3; k++) {
            a[k] = b.corner[9 * (size_t)h.tri + k];
            bb[k] = b.corner[9 * (size_t)h.tri + 3 + k];
            c[k] = b.corner[9 * (size_t)h.tri + 6 + k];
        }
        cr_assert(bvh_point_triangle(q, a, bb, c, p) == h.d2);
        cr_assert(p[0] == h.p[0] && p[1] == h.p[1] && p[2] == h.p[2]);
        /* started from any guess (the answer, the last query's, one at
         * random, none, one out of range), the same answer bit for bit:
         * of triangles at the least distance (many, where all lie on one
         * point), the first in leaf order */
        uint32_t hints[5] = { h.tri, last, b.ntris ? (uint32_t)(urand() * b.ntris) % b.ntris : 0, BVH_NONE,
                              b.ntris };
        for (int k = 0; k < 5; k++) {
            BvhHit g;
            bvh_closest_from(&b, q, hints[k], &g);
            cr_assert(g.d2 == h.d2 && g.tri == h.tri, "query %d from %u: %.17g at %u, not %.17g at %u", i, hints[k],
                      g.d2, g.tri, h.d2, h.tri);
            cr_assert(g.p[0] == h.p[0] && g.p[1] == h.p[1] && g.p[2] == h.p[2]);
        }
        last = h.tri;
    }
    bvh_free(&b);
}

Test(bvh, nearest_equals_every_triangle_tried_on_soups)
{
    for (int round = 0; round < 6; round++) {
        Soup s;
        uint32_t n = round < 3 ? 1 + round * 37 : 2000 + 1000 * round;
        soup(&s, n, 0, 1, round % 2 ? 0.3 : 0.02);
        against_brute(&s, 300, 0, 1);
        soup_free(&s);
    }
}

Test(bvh, nearest_far_from_the_origin)
{
    /* coordinates of 1e6 with triangles of 1e-2: float's steps there are
     * 0.06, so the query point's rounding to float is what the boxes'
     * margin must cover */
    Soup s;
    soup(&s, 3000, 1e6, 10, 0.5);
    against_brute(&s, 400, 1e6, 10);
    soup_free(&s);
}

Test(bvh, the_box_test_covers_the_points_rounding)
{
    /* at x = 1e6 floats are 1/16 apart: the query's x rounds 0.04 away
     * from T1's side, to 1/16 from it, past T2, which is 0.05 away in y
     * (where floats are fine): T2's box comes first, and T1's, truly
     * nearer, must not be passed over for its rounded distance */
    const float X = 1e6f;
    float pos[18] = { X, 0, 0, X + 1, 0, 0, X, 1, 0,                      /* T1: x from X */
                      X - 8, 0.55f, -1, X + 8, 0.55f, -1, X, 0.55f, 1 };  /* T2: the plane y = 0.55 */
    uint32_t tri[6] = { 0, 1, 2, 3, 4, 5 };
    Bvh b;
    char err[64];
    cr_assert_eq(bvh_build(&b, pos, 6, tri, NULL, 2, err, sizeof err), 0);
    double q[3] = { (double)X - 0.04, 0.5, 0 };
    BvhHit h;
    bvh_closest(&b, q, &h);
    cr_assert_eq(b.id[h.tri], 0, "T1 is the nearer");
    cr_assert_float_eq(sqrt(h.d2), 0.04, 1e-9, "%.17g", sqrt(h.d2));
    bvh_free(&b);
}

Test(bvh, degenerate_builds_stay_shallow_and_exact)
{
    /* every triangle on one point: one Morton code, halved by count */
    Soup s;
    soup(&s, 20000, 0, 1, 0.1);
    for (uint32_t i = 0; i < 3 * s.nt * 3; i++)
        s.pos[i] = 0.25f;
    against_brute(&s, 30, 0, 1);
    soup_free(&s);
    /* all on one line, one triangle, no triangle */
    soup(&s, 5000, 0, 1, 0.1);
    for (uint32_t v = 0; v < s.nv; v++)
        s.pos[3 * v + 1] = s.pos[3 * v + 2] = 0;
    against_brute(&s, 60, 0, 1);
    soup_free(&s);
    soup(&s, 1, 0, 1, 0.5);
    against_brute(&s, 60, 0, 1);
    soup_free(&s);
    Bvh b;
    char err[64];
    cr_assert_eq(bvh_build(&b, NULL, 0, NULL, NULL, 0, err, sizeof err), 0);
    BvhHit h;
    double q[3] = { 0, 0, 0 };
    bvh_closest(&b, q, &h);
    cr_assert(isinf(h.d2) && h.tri == BVH_NONE);
    bvh_closest_from(&b, q, 0, &h);
    cr_assert(isinf(h.d2) && h.tri == BVH_NONE, "a guess past the triangles is no guess");
    bvh_free(&b);
}

Test(bvh, a_bad_index_is_refused)
{
    float pos[9] = { 0 };
    uint32_t tri[3] = { 0, 1, 3 };
    Bvh b;
    char err[128];
    cr_assert_eq(bvh_build(&b, pos, 3, tri, NULL, 1, err, sizeof err), -1);
    cr_assert(strstr(err, "vertex 3 of 3"), "%s", err);
}

Test(bvh, nearest_on_the_bundled_models)
{
    static const char *const names[] = { "assets/knot.obj", "assets/torus.obj", "assets/demo.obj" };
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        Mesh m;
        char err[512];
        cr_assert_eq(mesh_load(&m, names[i], err, sizeof err), 0, "%s", err);
        /* the faces as a fan of triangles */
        Soup s = { m.pos, NULL, m.nverts, 0 };
        uint64_t nt = 0;
        for (uint32_t f = 0; f < m.nfaces; f++)
            nt += m.face_start[f + 1] - m.face_start[f] - 2;
        s.tri = malloc(3 * nt * sizeof *s.tri);
        for (uint32_t f = 0; f < m.nfaces; f++)
            for (uint32_t c = m.face_start[f] + 1; c + 1 < m.face_start[f + 1]; c++) {
                s.tri[3 * s.nt] = m.corner[m.face_start[f]];
                s.tri[3 * s.nt + 1] = m.corner[c];
                s.tri[3 * s.nt + 2] = m.corner[c + 1];
                s.nt++;
            }
        float lo = INFINITY, hi = -INFINITY;
        for (uint32_t k = 0; k < 3 * m.nverts; k++) {
            lo = fminf(lo, m.pos[k]);
            hi = fmaxf(hi, m.pos[k]);
        }
        against_brute(&s, 200, lo, hi - lo);
        free(s.tri);
        mesh_free(&m);
    }
}

Test(bvh, order_follows_the_curve)
{
    Soup s;
    soup(&s, 3000, 0, 1, 0.3);
    uint32_t *order = malloc(s.nv * sizeof *order), *code = malloc(s.nv * sizeof *code);
    cr_assert_eq(bvh_order(s.pos, s.nv, NULL, order, code), 0);
    uint8_t *seen = calloc(s.nv, 1);
    for (uint32_t i = 0; i < s.nv; i++) {
        cr_assert_lt(order[i], s.nv);
        cr_assert_eq(seen[order[i]]++, 0);
        if (i)
            cr_assert_leq(code[i - 1], code[i]);
    }
    /* one position, one code, in a box given */
    float box[6] = { -1, -1, -1, 2, 2, 2 }, two[6] = { 0.3f, 0.6f, 0.9f, 0.3f, 0.6f, 0.9f };
    uint32_t o2[2], c2[2];
    cr_assert_eq(bvh_order(two, 2, box, o2, c2), 0);
    cr_assert_eq(c2[0], c2[1]);
    free(seen);
    free(order);
    free(code);
    soup_free(&s);
}
