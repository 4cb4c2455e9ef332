/* test_hsr.c: the exact rules. Coverage against a brute-force even-odd
 * reference on the fixed-point values, the top-left rule on shared edges
 * and fans, the depth rule on piercing polygons, and every algorithm
 * against the z-buffer, byte for byte. */

#define _POSIX_C_SOURCE 200809L   /* nanosleep */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hsr.h"
#include "testlib.h"
#include "raster.h"

/* ==== brute force: the rule as written, one sample at a time ==== */

/* Is sample (i, j) inside polygon verts[0..n) by the even-odd rule with
 * half-open rows and columns? Exact: compares c * dy with xc * dy. */
static int brute_inside(const ScreenVert *v, int n, int i, int j)
{
    int64_t xc = 256LL * i + 128, yc = 256LL * j + 128;
    int crossings = 0;
    for (int k = 0; k < n; k++) {
        const ScreenVert *a = &v[k], *b = &v[(k + 1) % n];
        if (a->y == b->y)
            continue;
        const ScreenVert *t = a->y < b->y ? a : b, *m = a->y < b->y ? b : a;
        if (!(t->y <= yc && yc < m->y))
            continue;
        int64_t dy = m->y - t->y, dx = m->x - t->x;
        /* crossing c = t.x + (yc - t.y) dx / dy; counts when c <= xc */
        if (t->x * dy + (yc - t->y) * dx <= xc * dy)
            crossings++;
    }
    return crossings & 1;
}

/* ==== hand-made screen polygons ==== */

typedef struct {
    ScreenPolys sp;
} Polys;

static void polys_init(Polys *p, int w, int h)
{
    memset(p, 0, sizeof *p);
    p->sp.w = w;
    p->sp.h = h;
    p->sp.verts = calloc(4096, sizeof(ScreenVert));
    p->sp.polys = calloc(1025, sizeof(ScreenPoly));
    p->sp.cap_verts = 4096;
    p->sp.cap_polys = 1025;
}

static void polys_free(Polys *p)
{
    free(p->sp.verts);
    free(p->sp.polys);
}

/* Add a polygon at constant depth z (a = b = 0). Returns 0 if it covers
 * no sample box (then it is not added, as the front end would drop it). */
static int polys_add(Polys *p, const ScreenVert *v, int n, int face, float z)
{
    ScreenPolys *sp = &p->sp;
    int32_t xmin = v[0].x, xmax = v[0].x, ymin = v[0].y, ymax = v[0].y;
    for (int k = 0; k < n; k++) {
        if (v[k].x < xmin) xmin = v[k].x;
        if (v[k].x > xmax) xmax = v[k].x;
        if (v[k].y < ymin) ymin = v[k].y;
        if (v[k].y > ymax) ymax = v[k].y;
    }
    int x0 = sample_ceil(xmin), x1 = sample_ceil(xmax), y0 = sample_ceil(ymin), y1 = sample_ceil(ymax);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > sp->w) x1 = sp->w;
    if (y1 > sp->h) y1 = sp->h;
    if (x0 >= x1 || y0 >= y1)
        return 0;
    ScreenPoly *q = &sp->polys[sp->npolys++];
    q->first = sp->nverts;
    q->face = face;
    q->x0 = x0; q->x1 = x1; q->y0 = y0; q->y1 = y1;
    q->a = q->b = 0;
    q->zc = q->zmin = z;
    for (int k = 0; k < n; k++)
        sp->verts[sp->nverts++] = v[k];
    sp->polys[sp->npolys].first = sp->nverts;
    return 1;
}

static void polys_clear(Polys *p)
{
    p->sp.nverts = p->sp.npolys = 0;
    p->sp.polys[0].first = 0;
}

/* Render with the z-buffer and count, per sample, how many of the
 * polygons cover it (each polygon rendered alone). */
static void coverage_count(Polys *p, const HsrAlgo *algo, uint8_t *count)
{
    int w = p->sp.w, h = p->sp.h;
    memset(count, 0, (size_t)w * h);
    ScreenPolys one = p->sp;
    ScreenPoly tmp[2];
    for (uint32_t k = 0; k < p->sp.npolys; k++) {
        tmp[0] = p->sp.polys[k];
        tmp[1].first = p->sp.polys[k + 1].first;
        one.polys = tmp;
        one.npolys = 1;
        FrameBufs fb = { 0 };
        HsrRunner r;
        cr_assert_eq(hsr_runner_init(&r, algo, 1), 0);
        Viewport vp = { w, h, 1, 0 };
        HsrInput in = { .sp = &one, .scene = NULL, .vp = &vp };
        HsrStats st;
        cr_assert_eq(hsr_run(&r, &in, &fb, &st), 0);
        for (int i = 0; i < w * h; i++)
            if (fb.ids[i] >= 0)
                count[i]++;
        hsr_runner_free(&r);
        fbuf_free(&fb);
    }
}

static uint32_t rng_state = 12345;
static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}
/* Fixed-point coordinate in [lo, hi) px; one in four lands exactly on a
 * sample centre or pixel corner to exercise the ties. */
static int32_t rnd_coord(int lo, int hi)
{
    int32_t v = (int32_t)(lo * 256 + rnd() % (uint32_t)((hi - lo) * 256));
    switch (rnd() % 4) {
    case 0: return (v & ~255) | 128;    /* sample centre */
    case 1: return v & ~255;            /* pixel corner */
    default: return v;
    }
}

/* ==== coverage: brute force agreement ==== */

static void check_brute(Polys *p, const char *what)
{
    int w = p->sp.w, h = p->sp.h;
    uint8_t *count = malloc((size_t)w * h);
    coverage_count(p, &hsr_zbuffer, count);
    /* with one polygon in p, count is its coverage */
    const ScreenVert *v = &p->sp.verts[p->sp.polys[0].first];
    int n = (int)screen_poly_nverts(&p->sp, 0);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            int want = brute_inside(v, n, i, j);
            if (count[j * w + i] != want)
                cr_assert_fail("%s: sample (%d,%d) covered %d, rule says %d", what, i, j,
                         count[j * w + i], want);
        }
    free(count);
}

Test(coverage, random_polygons_match_the_rule)
{
    Polys p;
    polys_init(&p, 48, 40);
    for (int t = 0; t < 300; t++) {
        polys_clear(&p);
        int n = 3 + (int)(rnd() % 8);  /* triangles to concave / self-crossing 10-gons */
        ScreenVert v[16];
        for (int k = 0; k < n; k++) {
            v[k].x = rnd_coord(-6, 54);
            v[k].y = rnd_coord(-6, 46);
            v[k].z = 0;
        }
        if (!polys_add(&p, v, n, 0, 0.5f))
            continue;
        char what[64];
        snprintf(what, sizeof what, "polygon %d (%d corners)", t, n);
        check_brute(&p, what);
    }
    polys_free(&p);
}

/* Polygons of hundreds and thousands of corners cross a row hundreds of
 * times (where the crossings are sorted some other way than by insertion
 * and the edge tables likewise): every algorithm against the rule. */
Test(coverage, many_corner_polygons_match_the_rule_in_every_algorithm)
{
    static const int corners[] = { 25, 26, 60, 400, 4000 };
    Polys p;
    polys_init(&p, 48, 40);
    int w = p.sp.w, h = p.sp.h;
    uint8_t *count = malloc((size_t)w * h);
    for (size_t t = 0; t < sizeof corners / sizeof corners[0]; t++) {
        polys_clear(&p);
        int n = corners[t];
        ScreenVert v[4096];
        for (int k = 0; k < n; k++) {
            v[k].x = rnd_coord(-6, 54);
            v[k].y = rnd_coord(-6, 46);
            v[k].z = 0;
        }
        cr_assert(polys_add(&p, v, n, 0, 0.5f));
        long inside = 0;
        for (int a = 0; a < hsr_nalgos; a++) {
            coverage_count(&p, hsr_algos[a], count);
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++) {
                    int want = brute_inside(v, n, i, j);
                    inside += want;
                    if (count[j * w + i] != want)
                        cr_assert_fail("%s, %d corners: sample (%d,%d) covered %d, rule says %d",
                                       hsr_algos[a]->name, n, i, j, count[j * w + i], want);
                }
        }
        cr_assert_gt(inside, 0, "%d corners: the polygon covers nothing (a weak test)", n);
    }
    free(count);
    polys_free(&p);
}

Test(coverage, subpixel_polygons)
{
    Polys p;
    polys_init(&p, 16, 16);
    int covered = 0;
    for (int t = 0; t < 400; t++) {
        polys_clear(&p);
        /* around a sample centre, nudged by under half a pixel */
        int32_t cx = (rnd_coord(2, 14) & ~255) + 128 + (int32_t)(rnd() % 160) - 80;
        int32_t cy = (rnd_coord(2, 14) & ~255) + 128 + (int32_t)(rnd() % 160) - 80;
        ScreenVert v[3];
        for (int k = 0; k < 3; k++) {
            v[k].x = cx + (int32_t)(rnd() % 200) - 100;
            v[k].y = cy + (int32_t)(rnd() % 200) - 100;
            v[k].z = 0;
        }
        if (!polys_add(&p, v, 3, 0, 0.5f))
            continue;
        check_brute(&p, "sub-pixel triangle");
        covered++;
    }
    cr_assert_gt(covered, 50, "too few sub-pixel triangles had a sample box");
    polys_free(&p);
}

Test(coverage, square_on_sample_centres_is_top_left)
{
    /* Corners exactly on centres (1.5,1.5)-(3.5,3.5): the left and top
     * edges are in, the right and bottom out: samples 1..2 x 1..2. */
    Polys p;
    polys_init(&p, 6, 6);
    ScreenVert v[4] = { { 384, 384, 0 }, { 896, 384, 0 }, { 896, 896, 0 }, { 384, 896, 0 } };
    cr_assert(polys_add(&p, v, 4, 0, 0.5f));
    uint8_t count[36];
    coverage_count(&p, &hsr_zbuffer, count);
    for (int j = 0; j < 6; j++)
        for (int i = 0; i < 6; i++)
            cr_assert_eq(count[j * 6 + i], (i >= 1 && i <= 2 && j >= 1 && j <= 2),
                         "sample (%d,%d)", i, j);
    polys_free(&p);
}

Test(coverage, horizontal_edges_count_for_no_row)
{
    /* A triangle whose bottom is horizontal exactly on row 3's centre:
     * row 3 is out (y < y_bottom). Its apex sits on row 1's centre: both
     * edges count there, but cross at the same x, so the interval
     * x_enter <= x < x_leave is empty and the apex sample is out too. */
    Polys p;
    polys_init(&p, 8, 8);
    ScreenVert v[3] = { { 4 * 256 + 128, 1 * 256 + 128, 0 }, { 7 * 256 + 128, 3 * 256 + 128, 0 },
                        { 1 * 256 + 128, 3 * 256 + 128, 0 } };
    cr_assert(polys_add(&p, v, 3, 0, 0.5f));
    uint8_t count[64];
    coverage_count(&p, &hsr_zbuffer, count);
    for (int i = 0; i < 8; i++)
        cr_assert_eq(count[3 * 8 + i], 0, "row 3 sample %d must be out", i);
    cr_assert_eq(count[1 * 8 + 4], 0, "an empty interval at the apex covers nothing");
    cr_assert_eq(count[2 * 8 + 4], 1, "row 2 is inside");
    cr_assert_eq(count[1 * 8 + 3], 0);
    cr_assert_eq(count[1 * 8 + 5], 0);
    check_brute(&p, "flat-bottom triangle");
    polys_free(&p);
}

Test(coverage, shared_edges_cover_exactly_once)
{
    /* A random convex quad split along a diagonal: the two triangles
     * together cover exactly the quad's samples, none twice. */
    Polys p, q;
    polys_init(&p, 40, 40);
    polys_init(&q, 40, 40);
    uint8_t *c2 = malloc(1600), *c1 = malloc(1600);
    int tested = 0;
    for (int t = 0; t < 200; t++) {
        /* convex: corners on a circle at increasing angles */
        double cx = 20 + (rnd() % 1000) / 100.0 - 5, cy = 20 + (rnd() % 1000) / 100.0 - 5;
        double r = 4 + (rnd() % 2000) / 100.0, ang = (rnd() % 628) / 100.0;
        ScreenVert v[4];
        for (int k = 0; k < 4; k++) {
            ang += 0.3 + (rnd() % 100) / 100.0;
            v[k].x = (int32_t)lround((cx + r * cos(ang)) * 256);
            v[k].y = (int32_t)lround((cy + r * sin(ang)) * 256);
            if (rnd() % 3 == 0) {
                v[k].x = (v[k].x & ~255) | 128;
                v[k].y = (v[k].y & ~255) | 128;
            }
            v[k].z = 0;
        }
        polys_clear(&p);
        polys_clear(&q);
        ScreenVert t1[3] = { v[0], v[1], v[2] }, t2[3] = { v[0], v[2], v[3] };
        int a = polys_add(&p, t1, 3, 0, 0.5f);
        int b = polys_add(&p, t2, 3, 1, 0.5f);
        if (!polys_add(&q, v, 4, 0, 0.5f))
            continue;
        coverage_count(&q, &hsr_zbuffer, c1);
        if (a || b)
            coverage_count(&p, &hsr_zbuffer, c2);
        else
            memset(c2, 0, 1600);
        for (int i = 0; i < 1600; i++)
            cr_assert_eq(c2[i], c1[i], "quad %d: sample (%d,%d) covered %d times by the halves, %d by the quad",
                         t, i % 40, i / 40, c2[i], c1[i]);
        tested++;
    }
    cr_assert_gt(tested, 100);
    free(c1);
    free(c2);
    polys_free(&p);
    polys_free(&q);
}

Test(coverage, fans_around_a_vertex_cover_exactly_once)
{
    /* Triangles around a centre (on a sample centre or not) closing a
     * disc: every sample of the outline polygon is covered exactly once. */
    Polys p, q;
    polys_init(&p, 40, 40);
    polys_init(&q, 40, 40);
    uint8_t *cf = malloc(1600), *co = malloc(1600);
    for (int t = 0; t < 60; t++) {
        int n = 3 + (int)(rnd() % 14);
        ScreenVert c = { rnd_coord(14, 26), rnd_coord(14, 26), 0 };
        ScreenVert ring[17];
        double r = 3 + (rnd() % 1600) / 100.0, ang0 = (rnd() % 628) / 100.0;
        for (int k = 0; k < n; k++) {
            double ang = ang0 + 2 * 3.14159265358979323846 * k / n;
            ring[k].x = c.x + (int32_t)lround(r * cos(ang) * 256);
            ring[k].y = c.y + (int32_t)lround(r * sin(ang) * 256);
            ring[k].z = 0;
        }
        polys_clear(&p);
        polys_clear(&q);
        for (int k = 0; k < n; k++) {
            ScreenVert tri[3] = { c, ring[k], ring[(k + 1) % n] };
            polys_add(&p, tri, 3, k, 0.5f);
        }
        polys_add(&q, ring, n, 0, 0.5f);
        coverage_count(&p, &hsr_zbuffer, cf);
        coverage_count(&q, &hsr_zbuffer, co);
        for (int i = 0; i < 1600; i++)
            cr_assert_eq(cf[i], co[i], "fan %d of %d: sample (%d,%d) covered %d times, outline %d",
                         t, n, i % 40, i / 40, cf[i], co[i]);
    }
    free(cf);
    free(co);
    polys_free(&p);
    polys_free(&q);
}

Test(coverage, polygons_outside_the_image_are_clamped)
{
    Polys p;
    polys_init(&p, 10, 8);
    /* a triangle far larger than the image: covers everything on its side */
    ScreenVert big[3] = { { -100000, -100000, 0 }, { 200000, -100000, 0 }, { -100000, 200000, 0 } };
    cr_assert(polys_add(&p, big, 3, 0, 0.5f));
    check_brute(&p, "huge triangle");
    polys_clear(&p);
    ScreenVert out[3] = { { -5000, 100, 0 }, { -256, 900, 0 }, { -3000, 1500, 0 } };
    cr_assert_eq(polys_add(&p, out, 3, 0, 0.5f), 0, "wholly left of the image: no sample box");
    polys_free(&p);
}

/* ==== exact ties: equal depths go to the lower id, whatever the order ==== */

/* Flat polygons drawn in every order: face 5 over the whole image, faces
 * 2 and 7 one 38 x 38 pixel rectangle (the hierarchical z-buffer tests
 * boxes that size on its pyramid's texels), face 1 a 6 x 6 square (tested
 * on the depth buffer itself), all at one depth; and face 9, the same
 * rectangle farther away. A polygon that ties everywhere it covers must
 * still win where its id is lower. 9 after 5 is culled on the pyramid,
 * whose texels it leaves clean and equal to the tie's depth; 7 after 5
 * loses every tie and writes nothing: either way a 2 that follows meets
 * texels its depth merely equals. The reference is the rule itself: at
 * each sample the least (depth, id) among the polygons covering it (by
 * the brute-force coverage above). */
Test(depth, coincident_flat_polygons_in_every_order)
{
    enum { W = 64, H = 48, N = 5 };
    static const ScreenVert full[4] = { { -256, -256, 0 }, { 65 * 256, -256, 0 }, { 65 * 256, 49 * 256, 0 },
                                        { -256, 49 * 256, 0 } };
    static const ScreenVert rect[4] = { { 2 * 256, 2 * 256, 0 }, { 40 * 256, 2 * 256, 0 },
                                        { 40 * 256, 40 * 256, 0 }, { 2 * 256, 40 * 256, 0 } };
    static const ScreenVert small[4] = { { 45 * 256, 10 * 256, 0 }, { 51 * 256, 10 * 256, 0 },
                                         { 51 * 256, 16 * 256, 0 }, { 45 * 256, 16 * 256, 0 } };
    const ScreenVert *shape[N] = { full, rect, small, rect, rect };
    const int face[N] = { 5, 2, 1, 7, 9 };
    const float depth[N] = { 0.25f, 0.25f, 0.25f, 0.25f, 0.5f };
    int32_t want[W * H];
    int seen[10] = { 0 };
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            int best = -1;
            for (int k = 0; k < N; k++)
                if (brute_inside(shape[k], 4, i, j) &&
                    (best < 0 || depth[k] < depth[best] || (depth[k] == depth[best] && face[k] < face[best])))
                    best = k;
            cr_assert_geq(best, 0);
            want[j * W + i] = face[best];
            seen[face[best]]++;
        }
    cr_assert_eq(seen[1], 36);
    cr_assert_eq(seen[2], 38 * 38);
    cr_assert_eq(seen[5], W * H - 36 - 38 * 38);
    Polys p;
    polys_init(&p, W, H);
    int orders = 0;
    /* every order: the N-digit base-N numbers whose digits all differ */
    for (int code = 0; code < 5 * 5 * 5 * 5 * 5; code++) {
        int ord[N], used = 0;
        for (int k = 0, c = code; k < N; k++, c /= N) {
            ord[k] = c % N;
            used |= 1 << ord[k];
        }
        if (used != (1 << N) - 1)
            continue;
        orders++;
        polys_clear(&p);
        for (int k = 0; k < N; k++)
            cr_assert(polys_add(&p, shape[ord[k]], 4, face[ord[k]], depth[ord[k]]));
        for (int a = 0; a < hsr_nalgos; a++)
            for (int threads = 1; threads <= 2; threads++) {
                FrameBufs fb = { 0 };
                HsrRunner r;
                HsrStats st;
                Viewport vp = { W, H, 1, 0 };
                HsrInput in = { .sp = &p.sp, .vp = &vp };
                cr_assert_eq(hsr_runner_init(&r, hsr_algos[a], threads), 0);
                cr_assert_eq(hsr_run(&r, &in, &fb, &st), 0);
                hsr_runner_free(&r);
                for (int s = 0; s < W * H; s++)
                    if (fb.ids[s] != want[s] || fb.depth[s] != 0.25f)
                        cr_assert_fail("%s, %d threads, drawn %d %d %d %d %d: sample (%d,%d) has id %d depth %g, "
                                       "the least (depth, id) covering it is id %d at 0.25",
                                       hsr_algos[a]->name, threads, face[ord[0]], face[ord[1]], face[ord[2]],
                                       face[ord[3]], face[ord[4]], s % W, s / W, fb.ids[s], (double)fb.depth[s],
                                       want[s]);
                fbuf_free(&fb);
            }
    }
    cr_assert_eq(orders, 120);
    polys_free(&p);
}

/* ==== every algorithm obeys the same coverage rule ==== */

Test(coverage, every_algorithm_covers_like_the_reference)
{
    Polys p;
    polys_init(&p, 48, 40);
    uint8_t *ref = malloc(48 * 40), *got = malloc(48 * 40);
    for (int t = 0; t < 80; t++) {
        polys_clear(&p);
        int n = 3 + (int)(rnd() % 6);
        ScreenVert v[12];
        for (int k = 0; k < n; k++) {
            v[k].x = rnd_coord(-6, 54);
            v[k].y = rnd_coord(-6, 46);
            v[k].z = 0;
        }
        if (!polys_add(&p, v, n, 0, 0.5f))
            continue;
        coverage_count(&p, &hsr_zbuffer, ref);
        for (int a = 0; a < hsr_nalgos; a++) {
            coverage_count(&p, hsr_algos[a], got);
            cr_assert_eq(memcmp(ref, got, 48 * 40), 0, "%s covers differently (polygon %d)",
                         hsr_algos[a]->name, t);
        }
    }
    free(ref);
    free(got);
    polys_free(&p);
}

Test(coverage, small_triangles_with_corners_on_centres)
{
    /* boxes of a few samples (the z-buffer's edge-function path) with
     * corners on sample centres and pixel corners half the time */
    Polys p;
    polys_init(&p, 12, 12);
    int tested = 0;
    for (int t = 0; t < 1500; t++) {
        polys_clear(&p);
        int ox = 2 + (int)(rnd() % 4), oy = 2 + (int)(rnd() % 4);
        ScreenVert v[3];
        for (int k = 0; k < 3; k++) {
            v[k].x = rnd_coord(ox, ox + 5);
            v[k].y = rnd_coord(oy, oy + 5);
            v[k].z = 0;
        }
        if (!polys_add(&p, v, 3, 0, 0.5f))
            continue;
        check_brute(&p, "small triangle");
        tested++;
    }
    cr_assert_gt(tested, 500);
    polys_free(&p);
}

Test(coverage, single_sample_test_matches_the_rule)
{
    /* tri_covers_sample (the front end's early drop) agrees with the
     * brute-force rule on random triangles, both orientations, corners on
     * sample centres half the time */
    int inside = 0;
    for (int t = 0; t < 20000; t++) {
        ScreenVert v[3];
        for (int k = 0; k < 3; k++) {
            v[k].x = rnd_coord(0, 4);
            v[k].y = rnd_coord(0, 4);
            v[k].z = 0;
        }
        int i = (int)(rnd() % 4), j = (int)(rnd() % 4);
        int want = brute_inside(v, 3, i, j);
        cr_assert_eq(tri_covers_sample(v, i, j), want, "triangle %d, sample (%d,%d)", t, i, j);
        inside += want;
    }
    cr_assert_gt(inside, 1000);
}

/* ==== the complete hierarchical z-buffer's trees, built in the background ==== */

/* A wavy n x n grid of quads, each split into two triangles. */
static char *wavy_obj(int n)
{
    size_t cap = (size_t)(n + 1) * (n + 1) * 48 + (size_t)n * n * 2 * 40 + 1;
    char *t = malloc(cap), *p = t;
    cr_assert(t);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            p += snprintf(p, cap - (size_t)(p - t), "v %d %d %.4f\n", i, j, 9.0 * sin(i * 0.11) * cos(j * 0.07));
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
            p += snprintf(p, cap - (size_t)(p - t), "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c);
        }
    return t;
}

static void render_with(HsrRunner *r, Scene *s, ScreenPolys *sp, const Viewport *vp, FrameBufs *fb, HsrStats *st)
{
    HsrInput in = { .sp = sp, .scene = s, .vp = vp };
    cr_assert_eq(hsr_run(r, &in, fb, st), 0);
}

static void expect_same_buffers(const FrameBufs *a, const FrameBufs *b, const char *what)
{
    size_t n = (size_t)a->w * a->h;
    cr_assert_eq(memcmp(a->ids, b->ids, n * sizeof *a->ids), 0, "%s: ids", what);
    cr_assert_eq(memcmp(a->depth, b->depth, n * sizeof *a->depth), 0, "%s: depths", what);
}

/* On two threads a big scene's trees are built on a thread of their own:
 * the first frames draw without them (and say so), every frame equals the
 * z-buffer's, and once they are ready the walk culls with them. */
Test(octree, built_in_the_background_same_picture_before_and_after)
{
    char *text = wavy_obj(200);         /* 80,000 triangles: built in the background */
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "wavy", text), 0);
    free(text);
    tl_random_view(&s, 5, 0);
    ScreenPolys sp = { 0 };
    sp.threads = 2;
    Viewport vp = { 240, 160, 1.0f, 0 };
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    HsrRunner ref, oct;
    FrameBufs fr = { 0 }, fo = { 0 };
    HsrStats st;
    cr_assert_eq(hsr_runner_init(&ref, &hsr_zbuffer, 1), 0);
    cr_assert_eq(hsr_runner_init(&oct, hsr_find("hzb-octree"), 2), 0);
    render_with(&ref, &s, &sp, &vp, &fr, &st);
    render_with(&oct, &s, &sp, &vp, &fo, &st);
    cr_expect_eq(st.building, 1, "the first frame is drawn while the trees are built");
    cr_expect_eq(st.nodes_visited, 0);
    expect_same_buffers(&fr, &fo, "while building");
    /* frames until the trees are in (a frame each millisecond; the cap is
     * only there so that a builder that never ends fails the test) */
    int frames = 0;
    while (st.building && frames++ < 600000) {
        struct timespec ms = { 0, 1000000 };
        nanosleep(&ms, NULL);
        render_with(&oct, &s, &sp, &vp, &fo, &st);
        expect_same_buffers(&fr, &fo, "while building");
    }
    cr_assert_eq(st.building, 0);
    render_with(&oct, &s, &sp, &vp, &fo, &st);
    cr_expect_gt(st.nodes_visited, 0, "the trees are walked once built");
    expect_same_buffers(&fr, &fo, "with the trees");
    /* and on other views with them */
    for (uint32_t seed = 6; seed < 12; seed++) {
        tl_random_view(&s, seed, (int)(seed & 1));
        cr_assert_eq(screen_project(&sp, &s, &vp), 0);
        render_with(&ref, &s, &sp, &vp, &fr, &st);
        render_with(&oct, &s, &sp, &vp, &fo, &st);
        cr_assert_eq(st.building, 0);
        expect_same_buffers(&fr, &fo, "another view");
    }
    hsr_runner_free(&ref);
    hsr_runner_free(&oct);
    fbuf_free(&fr);
    fbuf_free(&fo);
    screen_free(&sp);
    scene_free(&s);
}

/* A runner freed while its builder runs stops and joins it (the sanitizer
 * build checks that nothing leaks or is touched after). */
Test(octree, freed_while_building)
{
    char *text = wavy_obj(200);
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "wavy", text), 0);
    free(text);
    tl_random_view(&s, 3, 1);
    ScreenPolys sp = { 0 };
    Viewport vp = { 120, 80, 1.0f, 0 };
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    for (int k = 0; k < 3; k++) {
        HsrRunner oct;
        FrameBufs fb = { 0 };
        HsrStats st;
        cr_assert_eq(hsr_runner_init(&oct, hsr_find("hzb-octree"), 2), 0);
        render_with(&oct, &s, &sp, &vp, &fb, &st);
        hsr_runner_free(&oct);
        fbuf_free(&fb);
    }
    screen_free(&sp);
    scene_free(&s);
}

/* A small scene's trees are built before the first frame, on any number
 * of threads: no frame is drawn without them. */
Test(octree, small_scenes_build_at_once)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/torus.obj"), 0);
    tl_random_view(&s, 1, 0);
    ScreenPolys sp = { 0 };
    Viewport vp = { 160, 100, 1.0f, 0 };
    cr_assert_eq(screen_project(&sp, &s, &vp), 0);
    for (int th = 1; th <= 2; th++) {
        HsrRunner oct;
        FrameBufs fb = { 0 };
        HsrStats st;
        cr_assert_eq(hsr_runner_init(&oct, hsr_find("hzb-octree"), th), 0);
        render_with(&oct, &s, &sp, &vp, &fb, &st);
        cr_expect_eq(st.building, 0);
        cr_expect_gt(st.nodes_visited, 0);
        hsr_runner_free(&oct);
        fbuf_free(&fb);
    }
    screen_free(&sp);
    scene_free(&s);
}

/* The statistic --info --algo and --bench give: with polygons that do not
 * overlap, every algorithm writes each covered sample once, so its count
 * of samples written is the brute force's count of samples inside. */
Test(hsr, samples_written_are_the_samples_covered)
{
    Polys p;
    polys_init(&p, 48, 32);
    /* a concave hexagon (a general polygon, not a triangle), a triangle
     * apart from it, and a quad */
    ScreenVert hex[6] = { { 256 * 2, 256 * 2, 0.5f }, { 256 * 20, 256 * 3, 0.5f }, { 256 * 12, 256 * 10, 0.5f },
                          { 256 * 22, 256 * 28, 0.5f }, { 256 * 3, 256 * 30, 0.5f }, { 256 * 8, 256 * 12, 0.5f } };
    ScreenVert tri[3] = { { 256 * 26 + 77, 256 * 2, 0.4f }, { 256 * 46, 256 * 5 + 31, 0.4f }, { 256 * 30, 256 * 14, 0.4f } };
    ScreenVert quad[4] = { { 256 * 28, 256 * 18, 0.3f }, { 256 * 45, 256 * 17, 0.3f }, { 256 * 44, 256 * 30, 0.3f },
                           { 256 * 27, 256 * 29, 0.3f } };
    cr_assert(polys_add(&p, hex, 6, 0, 0.5f) && polys_add(&p, tri, 3, 1, 0.4f) && polys_add(&p, quad, 4, 2, 0.3f));
    uint64_t inside = 0;
    for (int j = 0; j < 32; j++)
        for (int i = 0; i < 48; i++)
            inside += brute_inside(hex, 6, i, j) + brute_inside(tri, 3, i, j) + brute_inside(quad, 4, i, j);
    cr_assert_gt(inside, 300);
    for (int k = 0; k < hsr_nalgos; k++) {
        FrameBufs fb = { 0 };
        HsrRunner r;
        cr_assert_eq(hsr_runner_init(&r, hsr_algos[k], 1), 0);
        Viewport vp = { 48, 32, 1, 0 };
        HsrInput in = { .sp = &p.sp, .scene = NULL, .vp = &vp };
        HsrStats st;
        cr_assert_eq(hsr_run(&r, &in, &fb, &st), 0);
        cr_expect_eq(st.pixels_written, inside, "%s: %llu written, %llu inside", hsr_algos[k]->name,
                     (unsigned long long)st.pixels_written, (unsigned long long)inside);
        hsr_runner_free(&r);
        fbuf_free(&fb);
    }
    polys_free(&p);
}

/* ==== a row's crossings, sorted ==== */

static int cmp_int32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* raster_sort_crossings against the C library's qsort, on the rows a
 * rasterizer meets (a few crossings, or tens of thousands at a handful
 * of places) and the orders that break naive quicksorts: sorted,
 * reversed, all equal, organ pipe, sawtooth, random over the full range. */
Test(hsr, crossings_sort_as_qsort_does)
{
    static const int sizes[] = { 0, 1, 2, 3, 24, 25, 26, 100, 1001, 100000 };
    int32_t *a = malloc(100000 * sizeof *a), *ref = malloc(100000 * sizeof *ref);
    cr_assert(a && ref);
    uint32_t r = 12345;
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++)
        for (int pat = 0; pat < 8; pat++) {
            int n = sizes[si];
            for (int i = 0; i < n; i++) {
                r = r * 1664525u + 1013904223u;
                int32_t v = pat == 0 ? (int32_t)r                       /* the full range, negatives too */
                          : pat == 1 ? (int32_t)(r >> 30)               /* four values: a face listed over and over */
                          : pat == 2 ? i
                          : pat == 3 ? n - i
                          : pat == 4 ? 7
                          : pat == 5 ? (i < n / 2 ? i : n - i)          /* organ pipe */
                          : pat == 6 ? i % 17
                                     : (i & 1 ? i : -i);
                a[i] = ref[i] = v;
            }
            qsort(ref, (size_t)n, sizeof *ref, cmp_int32);
            raster_sort_crossings(a, n);
            cr_assert(n == 0 || !memcmp(a, ref, (size_t)n * sizeof *a), "n %d, pattern %d", n, pat);
        }
    free(a);
    free(ref);
}
