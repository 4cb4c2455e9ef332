/* test_span.c: the interval scanline against the z-buffer on hand-made
 * screen polygons that stress its interval decisions: planes piercing
 * inside an interval, exact ties (the id rule), near-ties a few ulps
 * apart, many polygons over one interval, n-gons with local tops and
 * bottoms, edges leaving the screen, and bands rendered separately.
 * Face-id and depth buffers must be bit-identical. */

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hsr.h"
#include "raster.h"
#include "../src/hsr/span.h"

extern const HsrAlgo hsr_zbuffer, hsr_span;

/* ==== building ScreenPolys by hand, as the front end would ==== */

typedef struct {
    ScreenPolys sp;
    uint32_t    vcap, pcap;
} Builder;

static void b_init(Builder *b, int w, int h)
{
    memset(b, 0, sizeof *b);
    b->sp.w = w;
    b->sp.h = h;
    b->vcap = 1 << 16;
    b->pcap = 1 << 14;
    b->sp.verts = calloc(b->vcap, sizeof *b->sp.verts);
    b->sp.polys = calloc(b->pcap + 1, sizeof *b->sp.polys);
    cr_assert(b->sp.verts && b->sp.polys);
}

static void b_free(Builder *b)
{
    free(b->sp.verts);
    free(b->sp.polys);
}

/* Add a polygon with corners (x, y) in 24.8 fixed point and the plane
 * z = zc + a (i - x0) + b (j - y0). Returns 0 when it covers no sample
 * box (dropped, as the front end does). */
static int b_poly(Builder *b, int n, const int32_t *xy, int32_t face, float a, float bb, float zc)
{
    ScreenPolys *sp = &b->sp;
    cr_assert(sp->nverts + n <= b->vcap && sp->npolys < b->pcap);
    int32_t xmin = xy[0], xmax = xy[0], ymin = xy[1], ymax = xy[1];
    for (int k = 1; k < n; k++) {
        xmin = xy[2 * k] < xmin ? xy[2 * k] : xmin;
        xmax = xy[2 * k] > xmax ? xy[2 * k] : xmax;
        ymin = xy[2 * k + 1] < ymin ? xy[2 * k + 1] : ymin;
        ymax = xy[2 * k + 1] > ymax ? xy[2 * k + 1] : ymax;
    }
    int32_t x0 = sample_ceil(xmin), x1 = sample_ceil(xmax);
    int32_t y0 = sample_ceil(ymin), y1 = sample_ceil(ymax);
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > sp->w ? sp->w : x1;
    y1 = y1 > sp->h ? sp->h : y1;
    if (x0 >= x1 || y0 >= y1)
        return 0;
    ScreenPoly *p = &sp->polys[sp->npolys];
    p->first = sp->nverts;
    p->face = face;
    p->x0 = x0;
    p->x1 = x1;
    p->y0 = y0;
    p->y1 = y1;
    p->a = a;
    p->b = bb;
    p->zc = zc;
    p->zmin = -INFINITY;
    for (int k = 0; k < n; k++) {
        sp->verts[sp->nverts].x = xy[2 * k];
        sp->verts[sp->nverts].y = xy[2 * k + 1];
        sp->verts[sp->nverts].z = 0;
        sp->nverts++;
    }
    sp->npolys++;
    sp->polys[sp->npolys].first = sp->nverts;
    return 1;
}

static uint32_t rng_state = 12345;

static uint32_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

static int32_t rnd_in(int32_t lo, int32_t hi)   /* [lo, hi) */
{
    return lo + (int32_t)(rnd() % (uint32_t)(hi - lo));
}

static float rnd_f(float lo, float hi)
{
    return lo + (hi - lo) * (float)(rnd() & 0xffffff) / (float)0x1000000;
}

/* ==== comparing ==== */

/* Render rows [0, h) with algo in nb bands (separate renders, as the
 * runner's threads would do). */
static void render_bands(const HsrAlgo *algo, void *st, const ScreenPolys *sp, FrameBufs *fb, int nb)
{
    Viewport vp = { sp->w, sp->h, 1.0f, 0 };
    HsrInput in = { .sp = sp, .scene = NULL, .vp = &vp };
    cr_assert_eq(fbuf_resize(fb, sp->w, sp->h), 0);
    for (int k = 0; k < nb; k++) {
        HsrStats st_ = { 0 };
        int y0 = sp->h * k / nb, y1 = sp->h * (k + 1) / nb;
        if (y0 < y1)
            algo->render(st, &in, fb, y0, y1, &st_);
    }
}

/* Span in nb bands against the z-buffer: ids and depth bit for bit.
 * Returns the number of covered samples. */
static long check_same(const ScreenPolys *sp, int nb, const char *what, uint64_t *fallback_out)
{
    FrameBufs ref = { 0 }, fb = { 0 };
    void *zs = hsr_zbuffer.create(), *ss = hsr_span.create();
    cr_assert(zs && ss);
    render_bands(&hsr_zbuffer, zs, sp, &ref, 1);
    /* render twice with one state: buffers are reused across frames */
    render_bands(&hsr_span, ss, sp, &fb, nb);
    memset(fb.ids, 0x55, (size_t)sp->w * sp->h * sizeof *fb.ids);
    render_bands(&hsr_span, ss, sp, &fb, nb);
    long covered = 0;
    for (int j = 0; j < sp->h; j++) {
        for (int i = 0; i < sp->w; i++) {
            size_t k = (size_t)j * sp->w + i;
            covered += ref.ids[k] >= 0;
            if (ref.ids[k] != fb.ids[k] || memcmp(&ref.depth[k], &fb.depth[k], sizeof(float)) != 0)
                cr_assert_fail("%s (%d bands): sample (%d,%d): span id %d depth %.9g, zbuffer id %d depth %.9g",
                               what, nb, i, j, fb.ids[k], (double)fb.depth[k], ref.ids[k],
                               (double)ref.depth[k]);
        }
    }
    if (fallback_out)
        *fallback_out = span_fallback_samples(ss);
    hsr_zbuffer.destroy(zs);
    hsr_span.destroy(ss);
    fbuf_free(&ref);
    fbuf_free(&fb);
    return covered;
}

/* ==== scenes ==== */

/* Random triangles and quads (some convex, some bow ties) with random
 * planes: many pierce each other inside intervals. */
static void random_scene(Builder *b, int npolys, int maxsize, float slope)
{
    int w = b->sp.w, h = b->sp.h;
    for (int f = 0; f < npolys; f++) {
        int n = (rnd() % 4 == 0) ? 4 + (int)(rnd() % 4) : 3;
        int32_t cx = rnd_in(-maxsize * 64, (w + maxsize / 4) * 256);
        int32_t cy = rnd_in(-maxsize * 64, (h + maxsize / 4) * 256);
        int32_t xy[16];
        for (int k = 0; k < n; k++) {
            xy[2 * k] = cx + rnd_in(-maxsize * 128, maxsize * 128);
            xy[2 * k + 1] = cy + rnd_in(-maxsize * 128, maxsize * 128);
        }
        b_poly(b, n, xy, f, rnd_f(-slope, slope), rnd_f(-slope, slope), rnd_f(0, 10));
    }
}

Test(span, random_piercing_polygons)
{
    static const int sz[][2] = { { 80, 48 }, { 317, 239 }, { 640, 360 } };
    for (int s = 0; s < 3; s++) {
        for (int rep = 0; rep < 4; rep++) {
            Builder b;
            b_init(&b, sz[s][0], sz[s][1]);
            random_scene(&b, 200 + 300 * rep, 8 + sz[s][0] / 4, rep % 2 ? 0.5f : 0.02f);
            char what[64];
            snprintf(what, sizeof what, "random %dx%d #%d", sz[s][0], sz[s][1], rep);
            long cov = check_same(&b.sp, 1, what, NULL);
            cr_assert_gt(cov, 0);
            check_same(&b.sp, 3, what, NULL);
            b_free(&b);
        }
    }
}

/* Two big triangles crossing along a line inside the interval, at many
 * slopes: the split must follow the planes exactly. */
Test(span, two_planes_pierce_mid_interval)
{
    for (int rep = 0; rep < 200; rep++) {
        Builder b;
        b_init(&b, 200, 40);
        int32_t t1[] = { -2560, -2560, 60000, 5120, -2560, 20000 };
        int32_t t2[] = { 60000, -2560, 60000, 20000, -5000, 5000 };
        float a1 = rnd_f(-0.01f, 0.01f), a2 = rnd_f(-0.01f, 0.01f);
        float zc = rnd_f(0.2f, 0.8f);
        float b1 = rnd_f(-0.01f, 0.01f);
        /* the second plane equals the first at some column inside */
        float ic = (float)rnd_in(5, 190);
        b_poly(&b, 3, t1, (int32_t)(rnd() % 3), a1, b1, zc);
        b_poly(&b, 3, t2, 1 + (int32_t)(rnd() % 3), a2, b1, zc + (a1 - a2) * ic);
        check_same(&b.sp, 1, "pierce", NULL);
        b_free(&b);
    }
}

/* Equal planes (the id rule decides) and planes a few ulps apart: the
 * fast decision must not be taken where rounding could flip it. */
Test(span, ties_and_near_ties_fall_back_exactly)
{
    Builder b;
    b_init(&b, 300, 60);
    int32_t quad[] = { -1000, -1000, 80000, -1000, 80000, 17000, -1000, 17000 };
    int32_t tri[] = { 5000, 2000, 70000, 3000, 30000, 15000 };
    float z = 0.5f;
    b_poly(&b, 4, quad, 7, 1e-4f, 2e-4f, z);
    b_poly(&b, 3, tri, 3, 1e-4f, 2e-4f, z);                   /* exact tie: id 3 wins */
    b_poly(&b, 3, tri, 9, 1e-4f, 2e-4f, nextafterf(z, 0));    /* one ulp nearer */
    b_poly(&b, 4, quad, 2, 1.0001e-4f, 2e-4f, nextafterf(z, 1));
    uint64_t fb = 0;
    long cov = check_same(&b.sp, 1, "ties", &fb);
    cr_assert_eq(cov, 300 * 60);
    cr_assert_gt(fb, 0, "near-ties must be decided sample by sample");
    check_same(&b.sp, 4, "ties", NULL);
    b_free(&b);
}

/* Many layers over the same interval, most far behind: one fast fill. */
Test(span, deep_stack_is_decided_at_the_ends)
{
    Builder b;
    b_init(&b, 400, 30);
    int32_t quad[] = { -1000, -1000, 110000, -1000, 110000, 9000, -1000, 9000 };
    for (int k = 0; k < 40; k++)
        b_poly(&b, 4, quad, 40 - k, rnd_f(-1e-3f, 1e-3f), rnd_f(-1e-3f, 1e-3f), 1.0f + (float)k);
    uint64_t fb = 0;
    check_same(&b.sp, 1, "stack", &fb);
    cr_assert_eq(fb, 0, "well separated layers need no per-sample decisions (got %llu)",
                 (unsigned long long)fb);
    b_free(&b);
}

/* Concave n-gons with several local tops and bottoms (edges that start
 * below the polygon's first row), stars, and a polygon larger than the
 * screen. */
Test(span, ngons_with_local_tops)
{
    Builder b;
    b_init(&b, 160, 120);
    int32_t comb[] = { 1000, 28000, 1000, 3000, 6000, 20000, 11000, 2000, 16000, 22000, 21000, 4000,
                       26000, 27000 };
    int32_t star[] = { 20000, 1000, 26000, 29000, 3000, 11000, 37000, 11000, 14000, 29000 };
    int32_t big[] = { -90000, -90000, 300000, -80000, 200000, 300000 };
    b_poly(&b, 7, comb, 0, 0.01f, -0.02f, 0.5f);
    b_poly(&b, 5, star, 1, -0.01f, 0.01f, 0.4f);
    b_poly(&b, 3, big, 2, 0.001f, 0.001f, 0.45f);
    check_same(&b.sp, 1, "ngons", NULL);
    check_same(&b.sp, 7, "ngons", NULL);
    b_free(&b);
}

/* Thin triangles running corner to corner in two directions, so that
 * every pair of opposite ones crosses: each row's order of crossings is
 * far from the last row's. Keeping it sorted by insertion would cost the
 * square of the crossings (a hostile file made span take 60x the
 * z-buffer); past a budget the row is radix-sorted instead, which must
 * give the same list, so the same picture. */
Test(span, many_crossing_edges_resort_rows)
{
    Builder b;
    b_init(&b, 200, 120);
    int n = 3000;
    for (int k = 0; k < n; k++) {
        int32_t y = (int32_t)((int64_t)k * 60 * 256 / n);
        int32_t up[] = { 0, y, 200 * 256, y + 60 * 256, 200 * 256, y + 60 * 256 + 40 };
        int32_t down[] = { 0, y + 60 * 256, 200 * 256, y, 200 * 256, y + 40 };
        if (k % 2)
            b_poly(&b, 3, up, k, 1e-4f, -1e-4f, 1.0f + (float)(k % 7));
        else
            b_poly(&b, 3, down, k, -1e-4f, 1e-4f, 1.0f + (float)(k % 5));
    }
    check_same(&b.sp, 1, "crossing", NULL);
    check_same(&b.sp, 4, "crossing", NULL);
    /* the budget was passed: the radix path drew that picture */
    FrameBufs fb = { 0 };
    void *ss = hsr_span.create();
    cr_assert(ss);
    render_bands(&hsr_span, ss, &b.sp, &fb, 1);
    cr_assert_gt(span_resorted_rows(ss), 10, "rows re-sorted: %llu",
                 (unsigned long long)span_resorted_rows(ss));
    hsr_span.destroy(ss);
    fbuf_free(&fb);
    b_free(&b);
}
