/* test_simd: the one SIMD switch (simd.h). Which level runs and how
 * ZV_SIMD forces one; then every SIMD path against the scalar reference,
 * byte for byte, on every bundled model (every .obj in assets/) from random
 * views: the front end's polygons, the points' squares, each
 * hidden-surface algorithm's buffers (the z-buffer's AVX2 triangles and
 * SSE2 spans; the SSE2 spans of scanline and span; hzb's pyramid; the
 * octree's build) and the shaded pixels. Built with -DZV_NO_SIMD (make
 * nosimd) every level is the scalar one and the comparisons hold
 * trivially; the first tests then check that nothing else is offered. */

#define _DEFAULT_SOURCE         /* setenv, unsetenv */

#include <criterion/criterion.h>
#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hsr.h"
#include "shade.h"
#include "simd.h"
#include "testlib.h"

/* ==== which level runs ==== */

#ifdef ZV_AVX2
/* Does /proc/cpuinfo list the flag? The kernel's view of the CPU: a
 * reference that does not come from simd.c. -1 when it cannot be read. */
static int cpuinfo_has(const char *flag)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return -1;
    char line[8192];
    int found = 0;
    while (!found && fgets(line, sizeof line, f))
        if (strncmp(line, "flags", 5) == 0) {
            for (char *t = strtok(line, " \t\n"); t && !found; t = strtok(NULL, " \t\n"))
                found = strcmp(t, flag) == 0;
            break;      /* every core lists the same flags */
        }
    fclose(f);
    return found;
}
#endif

Test(simd, the_best_level_is_the_cpus_and_the_builds)
{
    unsetenv("ZV_SIMD");
#if defined(ZV_AVX2)
    int avx2 = cpuinfo_has("avx2");
    if (avx2 < 0)
        cr_skip_test("no /proc/cpuinfo to check against");
    cr_assert_eq(simd_best(), avx2 ? SIMD_AVX2 : SIMD_SSE2, "best %s, /proc/cpuinfo avx2: %d",
                 simd_name(simd_best()), avx2);
#elif defined(ZV_SSE2)
    cr_assert_eq(simd_best(), SIMD_SSE2);
#else
    cr_assert_eq(simd_best(), SIMD_SCALAR, "a -DZV_NO_SIMD build offers %s", simd_name(simd_best()));
#endif
    cr_assert_eq(simd_level(), simd_best(), "no ZV_SIMD: the best level");
    cr_assert_eq(simd_use(SIMD_AUTO), simd_best());
    cr_assert_eq(simd_use(SIMD_SCALAR), SIMD_SCALAR, "scalar runs everywhere");
    cr_assert_eq(simd_use(SIMD_AVX2), simd_best(), "a level above the best is the best");
    cr_assert_str_eq(simd_name(SIMD_SCALAR), "scalar");
    cr_assert_str_eq(simd_name(SIMD_SSE2), "sse2");
    cr_assert_str_eq(simd_name(SIMD_AVX2), "avx2");
}

/* simd_warn's output for the current environment, and whether it warned. */
static int warn_text(char *buf, size_t len)
{
    FILE *f = tmpfile();
    cr_assert(f);
    int warned = simd_warn(f);
    rewind(f);
    size_t n = fread(buf, 1, len - 1, f);
    buf[n] = '\0';
    fclose(f);
    return warned;
}

Test(simd, zv_simd_forces_a_level_and_warns_when_it_cannot)
{
    char text[256];
    SimdLevel best = simd_best();
    for (int l = SIMD_SCALAR; l < SIMD_LEVELS; l++) {
        cr_assert_eq(setenv("ZV_SIMD", simd_name(l), 1), 0);
        SimdLevel want = l <= (int)best ? (SimdLevel)l : best;
        cr_assert_eq(simd_level(), want, "ZV_SIMD=%s runs %s", simd_name(l), simd_name(simd_level()));
        cr_assert_eq(simd_use(SIMD_AUTO), want);
        cr_assert_eq(simd_use(SIMD_SCALAR), SIMD_SCALAR, "a stage's own setting wins over ZV_SIMD");
        int warned = warn_text(text, sizeof text);
        if (l <= (int)best) {
            cr_assert_eq(warned, 0, "ZV_SIMD=%s: '%s'", simd_name(l), text);
            cr_assert_str_empty(text);
            continue;
        }
        /* a level this CPU or build lacks: one line, naming the variable
         * and the level used instead */
        char want_text[64];
        snprintf(want_text, sizeof want_text, "using %s\n", simd_name(best));
        cr_assert_eq(warned, 1);
        cr_assert(strstr(text, "ZV_SIMD=") != NULL, "'%s'", text);
        cr_assert(strstr(text, want_text) != NULL, "'%s'", text);
        cr_assert_eq(strchr(text, '\n'), text + strlen(text) - 1, "one line: '%s'", text);
    }
    cr_assert_eq(setenv("ZV_SIMD", "avx512", 1), 0);
    cr_assert_eq(simd_level(), best, "an unknown level: the best");
    cr_assert_eq(warn_text(text, sizeof text), 1);
    cr_assert(strstr(text, "ZV_SIMD=avx512") != NULL, "'%s'", text);
    cr_assert(strstr(text, simd_name(best)) != NULL, "'%s'", text);
    cr_assert_eq(setenv("ZV_SIMD", "", 1), 0);
    cr_assert_eq(simd_level(), best, "empty: as unset");
    cr_assert_eq(warn_text(text, sizeof text), 0, "'%s'", text);
}

/* ==== the bundled models from random views ==== */

#define VIEWS 8

static const int sizes[][2] = { { 160, 96 }, { 331, 199 }, { 64, 48 } };

/* One case: a model seen from one view. */
typedef struct {
    Scene      *s;
    const char *name;
    Viewport    vp;
    uint32_t    seed;
} Case;

/* A wavy grid of triangles whose every face comes twice, the copies in
 * the reverse order: each sample of a copy ties in depth with the
 * original, bit for bit, and the lower face id must win at every level
 * (the bundled models have next to no exact ties). */
static char *twice_obj(int n)
{
    size_t cap = (size_t)(n + 1) * (n + 1) * 48 + (size_t)n * n * 2 * 2 * 40 + 64, len = 0;
    char *t = malloc(cap);
    cr_assert(t);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            len += (size_t)snprintf(t + len, cap - len, "v %d %d %.4f\n", i, j, 0.7 * sin(0.9 * i) * cos(0.6 * j));
    for (int copy = 0; copy < 2; copy++)
        for (int q = 0; q < 2 * n * n; q++) {
            int c = copy ? 2 * n * n - 1 - q : q, cell = c / 2, i = cell % n, j = cell / n;
            int a = j * (n + 1) + i + 1, b = a + 1, d = a + n + 1, e = d + 1;
            len += (size_t)(c & 1 ? snprintf(t + len, cap - len, "f %d %d %d\n", b, e, d)
                                  : snprintf(t + len, cap - len, "f %d %d %d\n", a, b, d));
        }
    return t;
}

/* A grid of points, each twice (the second copy of the grid after the
 * first): drawn as squares (every point its own), the copies are flat
 * polygons at exactly the same depth, where a test of the hierarchical
 * z-buffer that culled on equal depths would drop the lower id. */
static void points_twice(Scene *s, int n)
{
    Mesh *m = calloc(1, sizeof *m);
    cr_assert(m);
    cr_assert_eq(tl_mesh_init(m, "points twice"), 0);
    for (int copy = 0; copy < 2; copy++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++)
                cr_assert_eq(tl_mesh_vertex(m, (float)i, (float)j, (float)(0.5 * sin(0.7 * i + 0.3 * j))), 0);
    cr_assert_eq(tl_mesh_finish(m), 0);
    char err[256];
    cr_assert_eq(scene_build(s, m, 1, err, sizeof err), 0, "%s", err);
}

/* check on one model from the random views views[0]..views[1]-1 (odd sizes, pixel aspect 1
 * and 2, culling on and off, perspective half the time with the near
 * plane cutting now and then). */
static void each_view(Scene *s, const char *name, const int views[2], void (*check)(const Case *c, void *arg),
                      void *arg)
{
    for (uint32_t seed = (uint32_t)views[0]; seed < (uint32_t)views[1]; seed++) {
        tl_random_view(s, seed, (int)(seed & 1));
        const int *sz = sizes[seed % 3];
        Case c = { s, name, { sz[0], sz[1], seed % 4 == 1 ? 2.0f : 1.0f, seed % 3 == 0 }, seed };
        check(&c, arg);
    }
}

/* Calls check on every bundled model, on the grid of faces twice and on
 * the points twice, from the random views views[0]..views[1]-1 of each.
 * Returns the cases. make test takes the first half of the VIEWS (FIRST),
 * make test-long the second (suite "long": SECOND). */
static const int FIRST[2] = { 0, VIEWS / 2 }, SECOND[2] = { VIEWS / 2, VIEWS };

static int each_case(const int views[2], void (*check)(const Case *c, void *arg), void *arg)
{
    glob_t g;
    cr_assert_eq(glob("assets/*.obj", 0, NULL, &g), 0, "no assets/*.obj (run from the source tree)");
    cr_assert_geq(g.gl_pathc, 5, "the bundled models");
    for (size_t k = 0; k < g.gl_pathc; k++) {
        Scene s;
        cr_assert_eq(tl_scene_from_file(&s, g.gl_pathv[k]), 0, "%s", g.gl_pathv[k]);
        each_view(&s, g.gl_pathv[k], views, check, arg);
        scene_free(&s);
    }
    Scene s;
    char *text = twice_obj(24);
    cr_assert_eq(tl_scene_from_text(&s, "twice", text), 0);
    free(text);
    each_view(&s, "every face twice", views, check, arg);
    scene_free(&s);
    points_twice(&s, 40);
    each_view(&s, "points twice", views, check, arg);
    scene_free(&s);
    int cases = (int)(g.gl_pathc + 2) * (views[1] - views[0]);
    globfree(&g);
    return cases;
}

/* The levels compared with the scalar one: every level above it this
 * CPU and build run (simd_use would quietly run a lower one). */
static int top_level(void)
{
    return (int)simd_best();
}

/* ==== the front end ==== */

static void expect_same_screen(const ScreenPolys *ref, const ScreenPolys *sp, const Case *c, int level)
{
    const char *lv = simd_name(level);
    cr_assert_eq(sp->npolys, ref->npolys, "%s view %u at %s: %u polygons, scalar %u", c->name, c->seed, lv,
                 sp->npolys, ref->npolys);
    cr_assert_eq(sp->nverts, ref->nverts, "%s view %u at %s: corners", c->name, c->seed, lv);
    cr_assert_eq(sp->nmap, ref->nmap);
    cr_assert_eq(sp->in_polys, ref->in_polys);
    cr_assert_eq(sp->culled_back, ref->culled_back, "%s view %u at %s", c->name, c->seed, lv);
    cr_assert_eq(sp->culled_empty, ref->culled_empty, "%s view %u at %s", c->name, c->seed, lv);
    cr_assert_eq(memcmp(sp->verts, ref->verts, ref->nverts * sizeof *ref->verts), 0, "%s view %u at %s: corners",
                 c->name, c->seed, lv);
    cr_assert_eq(memcmp(sp->polys, ref->polys, ref->npolys * sizeof *ref->polys), 0,
                 "%s view %u at %s: polygons", c->name, c->seed, lv);
    cr_assert_eq(sp->polys[sp->npolys].first, ref->polys[ref->npolys].first, "the sentinel");
    cr_assert_eq(memcmp(sp->map, ref->map, ref->nmap * sizeof *ref->map), 0, "%s view %u at %s: map", c->name,
                 c->seed, lv);
}

static void front_end_case(const Case *c, void *arg)
{
    int *drawn = arg;
    ScreenPolys ref = { 0 };
    ref.threads = 1;
    ref.simd = SIMD_SCALAR;
    cr_assert_eq(screen_project(&ref, c->s, &c->vp), 0);
    *drawn += ref.npolys > 0;
    for (int level = SIMD_SSE2; level <= top_level(); level++)
        for (int th = 1; th <= 2; th++) {
            ScreenPolys sp = { 0 };
            sp.threads = th;
            sp.simd = level;
            cr_assert_eq(screen_project(&sp, c->s, &c->vp), 0);
            expect_same_screen(&ref, &sp, c, level);
            screen_free(&sp);
        }
    screen_free(&ref);
}

static void front_end_levels_agree(const int views[2])
{
    int drawn = 0;
    int cases = each_case(views, front_end_case, &drawn);
    cr_assert_gt(drawn, cases / 2, "most views show something (%d of %d)", drawn, cases);
}

Test(simd, front_end_levels_give_the_same_polygons) { front_end_levels_agree(FIRST); }
Test(long, simd_front_end_levels_give_the_same_polygons) { front_end_levels_agree(SECOND); }

/* ==== points ==== */

/* The model's vertices as a cloud (consecutive vertices, no index
 * array: the SSE2 loop's case), seen as the model was. */
static void cloud_of(const Scene *from, Scene *cloud)
{
    Mesh *m = calloc(1, sizeof *m);
    cr_assert(m);
    cr_assert_eq(tl_mesh_init(m, "cloud"), 0);
    for (int k = 0; k < from->nmeshes; k++) {
        const Mesh *src = &from->meshes[k];
        for (uint32_t v = 0; v < src->nverts; v++)
            cr_assert_eq(tl_mesh_vertex(m, src->pos[3 * v], src->pos[3 * v + 1], src->pos[3 * v + 2]), 0);
    }
    cr_assert_eq(tl_mesh_finish(m), 0);
    char err[256];
    cr_assert_eq(scene_build(cloud, m, 1, err, sizeof err), 0, "%s", err);
}

static void points_case(const Case *c, void *arg)
{
    int *squares = arg;
    Scene cloud;
    cloud_of(c->s, &cloud);
    tl_random_view(&cloud, c->seed, (int)(c->seed & 1));
    /* a point per sample, a bigger square, squares of whole pixels of 2 x 2 samples */
    static const PrimStyle styles[] = { { 1, 1, 0, 0, 1, 0 }, { 3, 1, 0, 0, 1, 0 }, { 4, 2, 0, 0, 2, 0 } };
    for (int k = 0; k < 3; k++) {
        ScreenPolys ref = { 0 };
        PrimWork *rw = NULL;
        ref.threads = 1;
        ref.simd = SIMD_SCALAR;
        cr_assert_eq(tl_project(&ref, &cloud, &c->vp, &styles[k], &rw), 0);
        *squares += (int)ref.points_drawn;
        for (int level = SIMD_SSE2; level <= top_level(); level++) {
            ScreenPolys sp = { 0 };
            PrimWork *w = NULL;
            sp.threads = 1;
            sp.simd = level;
            cr_assert_eq(tl_project(&sp, &cloud, &c->vp, &styles[k], &w), 0);
            cr_assert_eq(sp.points_in, ref.points_in, "%s view %u style %d at %s", c->name, c->seed, k,
                         simd_name(level));
            cr_assert_eq(sp.points_drawn, ref.points_drawn);
            expect_same_screen(&ref, &sp, c, level);
            screen_free(&sp);
            prims_free(&w);
        }
        screen_free(&ref);
        prims_free(&rw);
    }
    scene_free(&cloud);
}

static void point_levels_agree(const int views[2])
{
    int squares = 0;
    each_case(views, points_case, &squares);
    cr_assert_gt(squares, 1000, "the clouds drew squares");
}

Test(simd, point_levels_give_the_same_squares) { point_levels_agree(FIRST); }
Test(long, simd_point_levels_give_the_same_squares) { point_levels_agree(SECOND); }

/* ==== hidden surfaces ==== */

/* Render sp with algo at one level on `threads` threads, into fb (its
 * statistics into *st). A fresh runner, so that state kept across frames
 * (the octree's trees) is made at this level too. */
static void render_at(const HsrAlgo *algo, int threads, int level, const Case *c, const ScreenPolys *sp,
                      FrameBufs *fb, HsrStats *st)
{
    HsrRunner r;
    cr_assert_eq(hsr_runner_init(&r, algo, threads), 0);
    HsrInput in = { .sp = sp, .scene = c->s, .vp = &c->vp, .simd = level };
    cr_assert_eq(fbuf_resize(fb, sp->w, sp->h), 0);
    memset(st, 0, sizeof *st);
    cr_assert_eq(hsr_run(&r, &in, fb, st), 0);
    hsr_runner_free(&r);
}

/* The counts of a frame are the same at every level too: the levels
 * test, cull and write the same (hzb's fine test reads the same pixels
 * at each; the octree is the same tree), so a level that built another
 * tree shows here even where the picture cannot. */
static void expect_same_counts(const HsrStats *ref, const HsrStats *st, const Case *c, const char *algo, int level,
                               int th)
{
    cr_assert_eq(st->polys_in, ref->polys_in, "%s view %u: %s at %s on %d thread(s)", c->name, c->seed, algo,
                 simd_name(level), th);
    cr_assert_eq(st->polys_culled, ref->polys_culled, "%s view %u: %s at %s on %d thread(s): culled %llu, scalar "
                 "%llu", c->name, c->seed, algo, simd_name(level), th, (unsigned long long)st->polys_culled,
                 (unsigned long long)ref->polys_culled);
    cr_assert_eq(st->nodes_visited, ref->nodes_visited, "%s view %u: %s at %s on %d thread(s): octree nodes",
                 c->name, c->seed, algo, simd_name(level), th);
    cr_assert_eq(st->nodes_culled, ref->nodes_culled);
    cr_assert_eq(st->pixels_written, ref->pixels_written, "%s view %u: %s at %s on %d thread(s): samples written",
                 c->name, c->seed, algo, simd_name(level), th);
}

/* The case's polygons as the pipeline makes them: faces, then points as
 * squares of 2 x 2 samples, every point its own (no two of the points
 * twice merged), at the scalar level; in the order given (--order: a
 * shuffle puts a copy before its original now and then). */
static void project_case(const Case *c, PolyOrder order, ScreenPolys *sp)
{
    static const PrimStyle every_point = { 2, 1, 0, 1, 1, 0 };
    PrimWork *w = NULL;
    ReorderScratch rs = { 0 };
    sp->threads = 1;
    sp->simd = SIMD_SCALAR;
    cr_assert_eq(tl_project(sp, c->s, &c->vp, &every_point, &w), 0);
    if (order != ORDER_FILE)
        cr_assert_eq(screen_reorder(sp, order, c->seed, &rs), 0);
    prims_free(&w);
    reorder_free(&rs);
}

typedef struct {
    const HsrAlgo *algo;
    long           covered;     /* samples covered over every case */
} AlgoArg;

static void algo_order(AlgoArg *a, const Case *c, PolyOrder order)
{
    ScreenPolys sp = { 0 };
    project_case(c, order, &sp);
    /* the reference: the plain z-buffer's scalar loops */
    FrameBufs ref = { 0 }, fb = { 0 };
    HsrStats ref_st, st, own[3];
    render_at(&hsr_zbuffer, 1, SIMD_SCALAR, c, &sp, &ref, &ref_st);
    for (size_t i = 0; i < (size_t)ref.w * ref.h; i++)
        a->covered += ref.ids[i] >= 0;
    for (int level = SIMD_SCALAR; level <= top_level(); level++)
        for (int th = 1; th <= 2; th++) {
            render_at(a->algo, th, level, c, &sp, &fb, &st);
            if (level == SIMD_SCALAR)
                own[th] = st;
            else
                expect_same_counts(&own[th], &st, c, a->algo->name, level, th);
            int fx, fy;
            long d = tl_diff(&ref, &fb, &fx, &fy);
            cr_assert_eq(d, 0, "%s view %u (%dx%d cull %d, %s order): %s at %s on %d thread(s) differs from "
                               "the scalar z-buffer in %ld pixels, first (%d,%d)",
                         c->name, c->seed, c->vp.w, c->vp.h, c->vp.cull, order_names[order], a->algo->name,
                         simd_name(level), th, d, fx, fy);
        }
    fbuf_free(&ref);
    fbuf_free(&fb);
    screen_free(&sp);
}

static void algo_case(const Case *c, void *arg)
{
    algo_order(arg, c, ORDER_FILE);
    algo_order(arg, c, ORDER_SHUFFLE);
}

static void algo_levels_agree(const char *name, const int views[2])
{
    AlgoArg a = { hsr_find(name), 0 };
    cr_assert(a.algo, "%s", name);
    each_case(views, algo_case, &a);
    cr_assert_gt(a.covered, 10000, "the views covered samples");
}

Test(simd, zbuffer_levels_give_the_same_buffers) { algo_levels_agree("zbuffer", FIRST); }
Test(long, simd_zbuffer_levels_give_the_same_buffers) { algo_levels_agree("zbuffer", SECOND); }

Test(simd, scanline_levels_give_the_same_buffers) { algo_levels_agree("scanline", FIRST); }
Test(long, simd_scanline_levels_give_the_same_buffers) { algo_levels_agree("scanline", SECOND); }

Test(simd, span_levels_give_the_same_buffers) { algo_levels_agree("span", FIRST); }
Test(long, simd_span_levels_give_the_same_buffers) { algo_levels_agree("span", SECOND); }

Test(simd, hzb_levels_give_the_same_buffers) { algo_levels_agree("hzb", FIRST); }
Test(long, simd_hzb_levels_give_the_same_buffers) { algo_levels_agree("hzb", SECOND); }

Test(simd, hzb_octree_levels_give_the_same_buffers) { algo_levels_agree("hzb-octree", FIRST); }
Test(long, simd_hzb_octree_levels_give_the_same_buffers) { algo_levels_agree("hzb-octree", SECOND); }

/* ==== shading ==== */

static void expect_same_image(const Image *ref, const Image *img, const Case *c, const char *what, int level)
{
    size_t n = (size_t)ref->w * ref->h;
    cr_assert_eq(img->w, ref->w);
    cr_assert_eq(img->h, ref->h);
    for (size_t i = 0; i < n; i++) {
        cr_assert_eq(memcmp(img->rgb + 3 * i, ref->rgb + 3 * i, 3), 0,
                     "%s view %u, %s at %s: pixel %zu is %d %d %d, scalar %d %d %d", c->name, c->seed, what,
                     simd_name(level), i, img->rgb[3 * i], img->rgb[3 * i + 1], img->rgb[3 * i + 2],
                     ref->rgb[3 * i], ref->rgb[3 * i + 1], ref->rgb[3 * i + 2]);
        cr_assert_eq(img->lit[i], ref->lit[i], "%s view %u, %s at %s: pixel %zu lit", c->name, c->seed, what,
                     simd_name(level), i);
    }
}

/* Shade the frame at one level, twice with one cache (the second frame
 * finds colours of the first) and, where the mode needs no projection,
 * once without the polygons (the per-pixel colour pass; smooth shading
 * reads the projection, so it shades the frame a third time). */
static void shade_at(const Case *c, const ScreenPolys *sp, const FrameBufs *fb, ShadeMode mode, int level,
                     Image out[3])
{
    ShadeCache cache = { 0 };
    ShadeSettings set = { .mode = mode, .crease = SHADE_CREASE_DEFAULT, .highlight = -1, .simd = level };
    cr_assert_eq(shade_frame(c->s, sp, fb, &set, &cache, &out[0]), 0);
    cr_assert_eq(shade_frame(c->s, sp, fb, &set, &cache, &out[1]), 0);
    cr_assert_eq(shade_frame(c->s, mode == SHADE_SMOOTH ? sp : NULL, fb, &set, &cache, &out[2]), 0);
    shade_cache_free(&cache);
}

static void shade_case(const Case *c, void *arg)
{
    long *lit = arg;
    ScreenPolys sp = { 0 };
    FrameBufs fb = { 0 };
    project_case(c, ORDER_FILE, &sp);
    HsrStats st;
    render_at(&hsr_zbuffer, 1, SIMD_SCALAR, c, &sp, &fb, &st);
    static const char *const pass[3] = { "first frame", "second frame", "pixel pass" };
    for (int mode = 0; mode < SHADE_COUNT; mode++) {
        Image ref[3] = { { 0 } }, img[3] = { { 0 } };
        shade_at(c, &sp, &fb, (ShadeMode)mode, SIMD_SCALAR, ref);
        for (size_t i = 0; i < (size_t)fb.w * fb.h; i++)
            *lit += ref[0].lit[i];
        for (int level = SIMD_SSE2; level <= top_level(); level++) {
            shade_at(c, &sp, &fb, (ShadeMode)mode, level, img);
            for (int k = 0; k < 3; k++) {
                char what[64];
                snprintf(what, sizeof what, "%s shading, %s", shade_names[mode], pass[k]);
                expect_same_image(&ref[k], &img[k], c, what, level);
            }
        }
        for (int k = 0; k < 3; k++) {
            image_free(&ref[k]);
            image_free(&img[k]);
        }
    }
    fbuf_free(&fb);
    screen_free(&sp);
}

static void shading_levels_agree(const int views[2])
{
    long lit = 0;
    each_case(views, shade_case, &lit);
    cr_assert_gt(lit, 10000, "the views lit pixels");
}

Test(simd, shading_levels_give_the_same_pixels) { shading_levels_agree(FIRST); }
Test(long, simd_shading_levels_give_the_same_pixels) { shading_levels_agree(SECOND); }

/* ==== the second screening of small triangles, against brute force ==== */

#ifdef ZV_AVX2
#include "../src/screen/project.h"

/* A corner near sample (i, j) of a w x h screen: on the sample's centre
 * or a pixel corner half the time (ties of the edge functions), else
 * anywhere within a few pixels, past the screen's edges too. */
static int32_t small_coord(uint32_t *r, int32_t lo, int32_t hi)
{
    *r = *r * 1664525u + 1013904223u;
    uint32_t v = *r >> 8;
    int32_t px = lo + (int32_t)(v % (uint32_t)(hi - lo + 1));
    switch (v >> 20 & 3) {
    case 0:
        return 256 * px + 128;
    case 1:
        return 256 * px;
    default:
        return 256 * px + (int32_t)(v >> 12 & 255);
    }
}

Test(simd, second_screening_keeps_exactly_the_small_triangles_that_cover_a_sample)
{
    if (simd_best() < SIMD_AVX2)
        return;     /* nothing to compare on this CPU */
    enum { W = 9, H = 7, NT = 2000 };
    static ScreenVert sv[3 * NT];
    static uint32_t idx[3 * NT], corner[3 * NT], keep[NT + 8];
    KeepLut lut = { { 0 }, { 0 } };
    for (unsigned m = 0; m < 256; m++)
        for (unsigned b = 0; b < 8; b++)
            if (m >> b & 1)
                lut.lanes[m] |= (uint64_t)b << (8 * lut.count[m]++);
    uint32_t r = 7, vmin = 5;  /* corners count from vmin, as an object's do */
    int seen_hit = 0, seen_empty = 0, seen_back = 0, seen_left = 0;
    for (int round = 0; round < 40; round++) {
        int cull = round & 1;
        for (uint32_t t = 0; t < NT; t++) {
            int32_t ox = (int32_t)(r % (W + 4)) - 2, oy = (int32_t)(r / 97 % (H + 4)) - 2;
            int32_t span = 1 + (int32_t)(t % 3);   /* corners within 1 to 3 pixels */
            for (int k = 0; k < 3; k++) {
                ScreenVert *v = &sv[3 * t + k];
                v->x = small_coord(&r, ox, ox + span);
                v->y = small_coord(&r, oy, oy + span);
                v->z = 0;
                /* now and then a corner to clip */
                if (t % 61 == 0 && k == 1)
                    v->x = v->y = VERT_OUT;
                idx[3 * t + k] = v->x == VERT_OUT ? (uint16_t)IDX_OUT * 0x10001u
                                                  : (uint16_t)sample_ceil(v->x) |
                                                        (uint32_t)(uint16_t)sample_ceil(v->y) << 16;
                corner[3 * t + k] = 3 * t + k + vmin;
            }
        }
        uint32_t nk = project_screen_tris(corner, 0, NT, idx, vmin, W, H, keep, 0);
        uint32_t first[NT + 8], nfirst = nk, empty = 0, back = 0;
        memcpy(first, keep, nk * sizeof *keep);
        nk = project_sift_small_avx2(corner, sv, vmin, W, H, cull, keep, nk, &lut, &empty, &back);
        cr_assert_eq(nk + empty + back, nfirst, "every triangle kept or counted once");
        uint32_t at = 0, dropped_empty = 0, dropped_back = 0;
        for (uint32_t q = 0; q < nfirst; q++) {
            uint32_t t = first[q];
            const ScreenVert *v = &sv[3 * t];
            int clip = v[0].x == VERT_OUT || v[1].x == VERT_OUT || v[2].x == VERT_OUT;
            int32_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;
            if (!clip) {
                x0 = sample_ceil(min3(v[0].x, v[1].x, v[2].x));
                x1 = sample_ceil(max3(v[0].x, v[1].x, v[2].x));
                y0 = sample_ceil(min3(v[0].y, v[1].y, v[2].y));
                y1 = sample_ceil(max3(v[0].y, v[1].y, v[2].y));
            }
            int small = !clip && x0 >= 0 && y0 >= 0 && x1 <= W && y1 <= H && (x1 - x0) * (y1 - y0) <= 4;
            int64_t area2 = ((int64_t)v[1].x - v[0].x) * ((int64_t)v[2].y - v[0].y) -
                            ((int64_t)v[1].y - v[0].y) * ((int64_t)v[2].x - v[0].x);
            /* the reference: every sample of the box, one by one */
            int covers = 0;
            for (int32_t j = y0; small && j < y1; j++)
                for (int32_t i = x0; i < x1; i++)
                    covers |= tri_covers_sample(v, i, j);
            int kept = at < nk && (keep[at] & ~KEEP_HIT) == t;
            uint32_t mark = kept ? keep[at] & KEEP_HIT : 0;
            if (!small || q >= nfirst / 8 * 8) {
                /* the tail short of eight is left too */
                cr_assert(kept && !mark, "round %d triangle %u: left for finish_tri", round, t);
                seen_left++;
            } else if (cull && area2 >= 0) {
                cr_assert(!kept, "round %d triangle %u faces away", round, t);
                dropped_back++;
            } else if (!covers) {
                cr_assert(!kept, "round %d triangle %u covers no sample", round, t);
                dropped_empty++;
            } else {
                cr_assert(kept && mark, "round %d triangle %u covers a sample: kept, marked", round, t);
                seen_hit++;
            }
            at += kept;
        }
        cr_assert_eq(at, nk, "the kept ones in order");
        cr_assert_eq(dropped_empty, empty);
        cr_assert_eq(dropped_back, back);
        seen_empty += dropped_empty;
        seen_back += dropped_back;
    }
    cr_assert(seen_hit > 1000 && seen_empty > 1000 && seen_back > 1000 && seen_left > 1000,
              "every outcome tested (%d %d %d %d)", seen_hit, seen_empty, seen_back, seen_left);
}
#endif

/* ==== shading split over threads ==== */

#include "pool.h"

Test(simd, shading_split_over_threads_gives_the_same_pixels)
{
    /* enough faces and pixels for the per-face and per-pixel loops to
     * split (64k a task at least): a grid of 180 k faces at 640 x 400 */
    Scene s;
    char *text = twice_obj(200);
    cr_assert_eq(tl_scene_from_text(&s, "twice", text), 0);
    free(text);
    Pool *pool[2] = { pool_create(1), pool_create(3) };
    cr_assert(pool[0] && pool[1]);
    int tested = 0;
    for (uint32_t seed = 0; seed < 4; seed++) {
        /* the whole grid in view, turned a random way about its normal;
         * small now and then (fewer polygons than a quarter of the faces:
         * the faces coloured polygon by polygon) */
        tl_random_view(&s, seed, (int)(seed & 1));
        s.cam.pitch = 0.3f;
        s.cam.zoom = seed < 2 ? 0.9f : 0.45f;
        s.cam.pan = v3(0, 0, 0);
        Case c = { &s, "grid", { 640, 400, 1.0f, 0 }, seed };
        ScreenPolys sp = { 0 };
        FrameBufs fb = { 0 };
        project_case(&c, ORDER_FILE, &sp);
        HsrStats st;
        render_at(&hsr_zbuffer, 1, SIMD_SCALAR, &c, &sp, &fb, &st);
        for (int level = SIMD_SCALAR; level <= top_level(); level++)
            for (int k = 0; k < 4; k++) {
                ShadeCache c0 = { 0 }, c1 = { 0 };
                ShadeSettings one = { .mode = k < 2 ? SHADE_LAMBERT : SHADE_ID, .crease = SHADE_CREASE_DEFAULT,
                                      .highlight = -1, .simd = level };
                ShadeSettings many = one;
                many.pool = pool[k & 1];
                Image ref = { 0 }, img = { 0 };
                cr_assert_eq(shade_frame(&s, &sp, &fb, &one, &c0, &ref), 0);
                /* a second frame, its cached colours scribbled over: every
                 * face shown must be coloured again, by one task or another */
                cr_assert_eq(shade_frame(&s, &sp, &fb, &many, &c1, &img), 0);
                memset(c1.rgb, 0x5a, (size_t)c1.cap * 3);
                cr_assert_eq(shade_frame(&s, &sp, &fb, &many, &c1, &img), 0);
                char what[64];
                snprintf(what, sizeof what, "%s shading with %d helpers (%u polygons)", shade_names[one.mode],
                         pool_helpers(pool[k & 1]), sp.npolys);
                expect_same_image(&ref, &img, &c, what, level);
                size_t lit = 0;
                for (size_t i = 0; i < (size_t)fb.w * fb.h; i++)
                    lit += ref.lit[i];
                tested += lit > 40000;
                image_free(&ref);
                image_free(&img);
                shade_cache_free(&c0);
                shade_cache_free(&c1);
            }
        fbuf_free(&fb);
        screen_free(&sp);
    }
    cr_assert_gt(tested, 3, "views that show the grid");
    pool_free(pool[0]);
    pool_free(pool[1]);
    scene_free(&s);
}

Test(simd, shading_a_huge_mesh_in_a_small_picture_gives_the_cached_colours)
{
    /* far more faces than pixels: Lambert shading colours the pixels
     * straight from their faces, and must give what the per-pixel pass
     * through the colour cache (no polygons given) gives */
    Scene s;
    char *text = twice_obj(200);
    cr_assert_eq(tl_scene_from_text(&s, "twice", text), 0);
    free(text);
    int tested = 0;
    for (uint32_t seed = 0; seed < 4; seed++) {
        tl_random_view(&s, seed, (int)(seed & 1));
        Case c = { &s, "grid", { 48, 30, seed & 2 ? 2.0f : 1.0f, 0 }, seed };
        ScreenPolys sp = { 0 };
        FrameBufs fb = { 0 };
        project_case(&c, ORDER_FILE, &sp);
        cr_assert_lt((uint64_t)sp.npolys * 16, s.nfaces, "polygons few against the faces: %u", sp.npolys);
        HsrStats st;
        render_at(&hsr_zbuffer, 1, SIMD_SCALAR, &c, &sp, &fb, &st);
        for (int level = SIMD_SCALAR; level <= top_level(); level++) {
            ShadeCache cache = { 0 };
            ShadeSettings set = { .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1,
                                  .simd = level };
            Image ref = { 0 }, img = { 0 };
            cr_assert_eq(shade_frame(&s, NULL, &fb, &set, &cache, &ref), 0);
            cr_assert_eq(shade_frame(&s, &sp, &fb, &set, &cache, &img), 0);
            expect_same_image(&ref, &img, &c, "lambert shading from the faces", level);
            size_t lit = 0;
            for (size_t i = 0; i < (size_t)fb.w * fb.h; i++)
                lit += ref.lit[i];
            tested += lit > 200;
            image_free(&ref);
            image_free(&img);
            shade_cache_free(&cache);
        }
        fbuf_free(&fb);
        screen_free(&sp);
    }
    cr_assert_gt(tested, 3, "views that show the grid");
    scene_free(&s);
}
