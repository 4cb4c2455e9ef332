/* test_pipeline.c: one frame through every stage; supersampling is the
 * exact render at the higher resolution, averaged. */

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "testlib.h"

Test(pipeline, supersampling_is_the_big_render_averaged)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/demo.obj"), 0);
    static const int counts[] = { 4, 9 };
    for (int c = 0; c < 2; c++) {
        int samples = counts[c];
        int k = pipeline_samples_side(samples);
        cr_assert_eq(k * k, samples);
        for (int a = 0; a < hsr_nalgos; a++) {
            Pipeline ss, big;
            cr_assert_eq(pipeline_init(&ss, &s, hsr_algos[a], 1), 0);
            cr_assert_eq(pipeline_init(&big, &s, hsr_find("zbuffer"), 2), 0);
            ss.samples = samples;
            cr_assert_eq(pipeline_render(&ss, 50, 30, 2.0f, 0, 1), 0);
            cr_assert_eq(pipeline_render(&big, 50 * k, 30 * k, 2.0f, 0, 1), 0);
            /* the same exact buffers at the higher resolution */
            cr_assert_eq(ss.fb.w, 50 * k);
            cr_assert_eq(memcmp(ss.fb.ids, big.fb.ids, (size_t)ss.fb.w * ss.fb.h * 4), 0, "%s",
                         hsr_algos[a]->name);
            Image avg = { 0 };
            cr_assert_eq(image_downsample(&big.img, k, &avg), 0);
            cr_assert_eq(ss.img.w, 50);
            cr_assert_eq(ss.img.h, 30);
            cr_assert_eq(memcmp(ss.img.rgb, avg.rgb, 50 * 30 * 3), 0);
            cr_assert_eq(memcmp(ss.img.lit, avg.lit, 50 * 30), 0);
            image_free(&avg);
            pipeline_free(&ss);
            pipeline_free(&big);
        }
    }
    scene_free(&s);
}

Test(pipeline, one_sample_renders_at_the_size_asked)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/cube.obj"), 0);
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, &s, hsr_find("zbuffer"), 1), 0);
    cr_assert_eq(pipeline_render(&p, 33, 17, 1.0f, 0, 1), 0);
    cr_expect_eq(p.fb.w, 33);
    cr_expect_eq(p.img.w, 33);
    cr_expect_eq(p.img.h, 17);
    pipeline_free(&p);
    scene_free(&s);
}

/* ==== smooth shading ==== */

static void render_shade(Scene *s, ShadeMode mode, float crease, Pipeline *p)
{
    cr_assert_eq(pipeline_init(p, s, hsr_find("zbuffer"), 1), 0);
    p->shade = mode;
    p->crease = crease;
    cr_assert_eq(pipeline_render(p, 120, 90, 1.0f, 0, 1), 0);
}

Test(pipeline, smooth_keeps_sharp_edges_sharp)
{
    /* a cube's faces meet at 90 degrees: under the default crease each
     * corner keeps its own face's normal, so smooth equals flat */
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/cube.obj"), 0);
    s.cam.yaw = 0.6f;
    s.cam.pitch = 0.4f;
    Pipeline flat, smooth, round;
    render_shade(&s, SHADE_LAMBERT, SHADE_CREASE_DEFAULT, &flat);
    render_shade(&s, SHADE_SMOOTH, SHADE_CREASE_DEFAULT, &smooth);
    render_shade(&s, SHADE_SMOOTH, 180, &round);
    int lit = 0, maxd = 0, differ = 0;
    for (int i = 0; i < 120 * 90; i++) {
        cr_assert_eq(flat.img.lit[i], smooth.img.lit[i]);
        if (!flat.img.lit[i])
            continue;
        lit++;
        for (int a = 0; a < 3; a++) {
            int d = abs(flat.img.rgb[3 * i + a] - smooth.img.rgb[3 * i + a]);
            maxd = d > maxd ? d : maxd;
            differ += flat.img.rgb[3 * i + a] != round.img.rgb[3 * i + a];
        }
    }
    cr_assert_gt(lit, 1000);
    cr_expect_leq(maxd, 1, "smooth with a 60-degree crease differs from flat by %d", maxd);
    cr_expect_gt(differ, lit / 2, "a 180-degree crease rounds the cube's shading");
    pipeline_free(&flat);
    pipeline_free(&smooth);
    pipeline_free(&round);
    scene_free(&s);
}

/* A coarse UV sphere: 16 x 8 quads, big on the screen. */
static char *uv_sphere(void)
{
    char *t = malloc(1 << 16);
    size_t n = 0;
    for (int j = 0; j <= 8; j++)
        for (int i = 0; i < 16; i++) {
            double th = 3.14159265358979 * j / 8, ph = 2 * 3.14159265358979 * i / 16;
            n += (size_t)sprintf(t + n, "v %.6f %.6f %.6f\n", sin(th) * cos(ph), cos(th), sin(th) * sin(ph));
        }
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 16; i++) {
            int a = j * 16 + i + 1, b = j * 16 + (i + 1) % 16 + 1;
            n += (size_t)sprintf(t + n, "f %d %d %d %d\n", a, b, b + 16, a + 16);
        }
    return t;
}

Test(pipeline, smooth_varies_within_faces_and_changes_slowly)
{
    Scene s;
    char *obj = uv_sphere();
    cr_assert_eq(tl_scene_from_text(&s, "sphere.obj", obj), 0);
    free(obj);
    s.cam.pitch = 0.3f;
    Pipeline flat, smooth;
    render_shade(&s, SHADE_LAMBERT, SHADE_CREASE_DEFAULT, &flat);
    render_shade(&s, SHADE_SMOOTH, SHADE_CREASE_DEFAULT, &smooth);
    /* along rows, between neighbours on the same face: flat never
     * changes, smooth does, by small steps; and smooth's steps across
     * face edges are smaller than flat's */
    long inside = 0, inside_changes = 0, big_inside = 0;
    double edge_flat = 0, edge_smooth = 0;
    for (int y = 0; y < 90; y++)
        for (int x = 0; x + 1 < 120; x++) {
            int i = y * 120 + x;
            int32_t a = smooth.fb.ids[i], b = smooth.fb.ids[i + 1];
            if (a < 0 || b < 0)
                continue;
            int ds = abs(smooth.img.rgb[3 * i] - smooth.img.rgb[3 * i + 3]);
            int df = abs(flat.img.rgb[3 * i] - flat.img.rgb[3 * i + 3]);
            if (a == b) {
                inside++;
                cr_assert_eq(df, 0);
                inside_changes += ds > 0;
                big_inside += ds > 12;
            } else if (fabsf(smooth.fb.depth[i] - smooth.fb.depth[i + 1]) < 0.005f) {
                /* neighbouring faces of one surface, not a silhouette */
                edge_flat += df;
                edge_smooth += ds;
            }
        }
    cr_assert_gt(inside, 500);
    cr_expect_gt(inside_changes, inside / 10, "smooth shading varies inside faces");
    cr_expect_lt(big_inside, inside / 50, "and changes slowly there");
    cr_expect_lt(edge_smooth, 0.6 * edge_flat, "face edges blend: %.0f vs flat %.0f", edge_smooth, edge_flat);
    pipeline_free(&flat);
    pipeline_free(&smooth);
    scene_free(&s);
}

/* ==== several files ==== */

static void load_files(Scene *s, int layout, int n, const char **files)
{
    Options o;
    cli_defaults(&o);
    o.layout = layout;
    for (int i = 0; i < n; i++)
        o.files[i] = files[i];
    o.nfiles = n;
    char err[512];
    cr_assert_eq(app_load_scene(&o, s, err, sizeof err), 0, "%s", err);
}

/* World box of object i at its current placement. */
static void world_box(const Scene *s, int i, Vec3 *lo, Vec3 *hi)
{
    const Object *o = &s->objs[i];
    Vec3 c = v3_add(o->centre, o->offset), h = v3_scale(o->half, o->scale);
    *lo = v3_sub(c, h);
    *hi = v3_add(c, h);
}

Test(pipeline, row_layout_sets_files_apart_at_one_size)
{
    const char *files[] = { "assets/cube.obj", "assets/knot.obj" };
    Scene s;
    load_files(&s, LAYOUT_ROW, 2, files);
    cr_assert_eq(s.nobjs, 2);
    Vec3 alo, ahi, blo, bhi;
    world_box(&s, 0, &alo, &ahi);
    world_box(&s, 1, &blo, &bhi);
    int overlap = alo.x < bhi.x && blo.x < ahi.x && alo.y < bhi.y && blo.y < ahi.y && alo.z < bhi.z && blo.z < ahi.z;
    cr_expect(!overlap, "the two files' boxes are apart");
    float da = v3_len(v3_sub(ahi, alo)), db = v3_len(v3_sub(bhi, blo));
    cr_expect_float_eq(da, db, 1e-3f * da, "a common size: %g vs %g", da, db);
    /* a reset comes back to the layout */
    Vec3 before = s.objs[1].offset;
    s.objs[1].offset = v3(9, 9, 9);
    s.objs[1].scale = 5;
    scene_reset(&s);
    cr_expect(s.objs[1].offset.x == before.x && s.objs[1].offset.y == before.y && s.objs[1].scale != 5);
    scene_free(&s);
}

Test(pipeline, layout_none_keeps_coordinates)
{
    const char *files[] = { "assets/cube.obj", "assets/knot.obj" };
    Scene s;
    load_files(&s, LAYOUT_NONE, 2, files);
    for (int i = 0; i < 2; i++) {
        cr_expect(s.objs[i].offset.x == 0 && s.objs[i].offset.y == 0 && s.objs[i].offset.z == 0);
        cr_expect_eq(s.objs[i].scale, 1.0f);
    }
    scene_free(&s);
}

Test(pipeline, objects_without_colour_get_distinct_ones_and_the_selection_shows)
{
    const char *files[] = { "assets/cube.obj", "assets/torus.obj" };
    Scene s;
    load_files(&s, LAYOUT_ROW, 2, files);
    const uint8_t *a = &s.face_rgb[3 * (size_t)s.objs[0].face_base];
    const uint8_t *b = &s.face_rgb[3 * (size_t)s.objs[1].face_base];
    cr_expect(memcmp(a, b, 3) != 0, "two uncoloured objects, two colours");
    Pipeline plain, sel;
    cr_assert_eq(pipeline_init(&plain, &s, hsr_find("zbuffer"), 1), 0);
    cr_assert_eq(pipeline_init(&sel, &s, hsr_find("zbuffer"), 1), 0);
    sel.highlight = 1;
    cr_assert_eq(pipeline_render(&plain, 120, 60, 1.0f, 0, 1), 0);
    cr_assert_eq(pipeline_render(&sel, 120, 60, 1.0f, 0, 1), 0);
    long same0 = 0, n0 = 0, diff1 = 0, n1 = 0;
    for (int i = 0; i < 120 * 60; i++) {
        int32_t id = plain.fb.ids[i];
        if (id < 0)
            continue;
        int obj = s.face_obj[id];
        int d = memcmp(plain.img.rgb + 3 * i, sel.img.rgb + 3 * i, 3) != 0;
        if (obj == 0) {
            n0++;
            same0 += !d;
        } else {
            n1++;
            diff1 += d;
        }
    }
    cr_assert_gt(n0, 100);
    cr_assert_gt(n1, 100);
    cr_expect_eq(same0, n0, "the other object is untouched");
    cr_expect_eq(diff1, n1, "every pixel of the selected object is tinted");
    pipeline_free(&plain);
    pipeline_free(&sel);
    scene_free(&s);
}

/* ==== outlines ==== */

/* Pixels whose colour --edges changed, in a w x h render of s. */
static int outline_mask(Scene *s, int w, int h, uint8_t *mask, int32_t *ids)
{
    Pipeline a, b;
    cr_assert_eq(pipeline_init(&a, s, hsr_find("zbuffer"), 1), 0);
    cr_assert_eq(pipeline_init(&b, s, hsr_find("span"), 2), 0);
    b.edges = 1;
    cr_assert_eq(pipeline_render(&a, w, h, 1.0f, 0, 1), 0);
    cr_assert_eq(pipeline_render(&b, w, h, 1.0f, 0, 1), 0);
    int n = 0;
    for (int i = 0; i < w * h; i++) {
        mask[i] = memcmp(a.img.rgb + 3 * i, b.img.rgb + 3 * i, 3) != 0;
        n += mask[i];
        ids[i] = a.fb.ids[i];
    }
    pipeline_free(&a);
    pipeline_free(&b);
    return n;
}

/* Is pixel i at least r pixels from any pixel with another id? */
static int deep_inside(const int32_t *ids, int w, int h, int x, int y, int r)
{
    for (int dy = -r; dy <= r; dy++)
        for (int dx = -r; dx <= r; dx++) {
            int u = x + dx, v = y + dy;
            if (u < 0 || v < 0 || u >= w || v >= h || ids[v * w + u] != ids[y * w + x])
                return 0;
        }
    return 1;
}

Test(pipeline, outlines_follow_silhouettes_and_creases_only)
{
    enum { W = 120, H = 90 };
    uint8_t mask[W * H];
    int32_t ids[W * H];
    /* the cube: its visible faces meet at creases and the background */
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/cube.obj"), 0);
    s.cam.yaw = 0.6f;
    s.cam.pitch = 0.5f;
    int n = outline_mask(&s, W, H, mask, ids);
    cr_assert_gt(n, 100, "the cube has outlines");
    int deep = 0, near_crease = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            if (ids[i] < 0)
                cr_assert_eq(mask[i], 0, "nothing is drawn on the background");
            else if (deep_inside(ids, W, H, x, y, 2))
                deep += mask[i];
            else if (x + 1 < W && ids[i + 1] >= 0 && ids[i + 1] != ids[i])
                near_crease += mask[i] || mask[i + 1];
        }
    cr_expect_eq(deep, 0, "face interiors stay clean");
    cr_expect_gt(near_crease, 20, "the creases between faces are drawn");
    scene_free(&s);

    /* a smooth sphere: no crease inside, only the silhouette */
    char *obj = uv_sphere();
    cr_assert_eq(tl_scene_from_text(&s, "sphere.obj", obj), 0);
    free(obj);
    n = outline_mask(&s, W, H, mask, ids);
    int inner = 0;
    for (int y = 1; y + 1 < H; y++)
        for (int x = 1; x + 1 < W; x++) {
            int i = y * W + x;
            int by_bg = ids[i - 1] < 0 || ids[i + 1] < 0 || ids[i - W] < 0 || ids[i + W] < 0;
            inner += mask[i] && !by_bg;
        }
    cr_assert_gt(n, 50, "the sphere's silhouette is drawn");
    cr_expect_eq(inner, 0, "and nothing inside it (faces meet at under 25 degrees)");
    scene_free(&s);
}

Test(pipeline, outlines_mark_the_front_of_a_depth_step)
{
    /* a small square floating in front of a big one, parallel */
    enum { W = 100, H = 100 };
    uint8_t mask[W * H];
    int32_t ids[W * H];
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "step.obj",
                                    "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\n"
                                    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                                    "f 1 2 3 4\nf 5 6 7 8\n"),
                 0);
    s.cam.yaw = 0;
    s.cam.pitch = 0;
    scene_fit(&s);
    outline_mask(&s, W, H, mask, ids);
    int front = 0, back = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x + 1 < W; x++) {
            int i = y * W + x;
            if (ids[i] >= 0 && ids[i + 1] >= 0 && ids[i] != ids[i + 1]) {
                int fi = ids[i] == 1 ? i : i + 1, bi = ids[i] == 1 ? i + 1 : i;
                front += mask[fi];
                back += mask[bi];
            }
        }
    cr_expect_gt(front, 20, "the near square's rim is outlined");
    cr_expect_eq(back, 0, "the far square is not, beside it");
    scene_free(&s);
}

/* ==== polygon order ==== */

Test(pipeline, every_order_gives_the_same_buffers)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/demo.obj"), 0);
    s.cam.yaw = 0.4f;
    s.cam.pitch = 0.3f;
    Pipeline ref;
    cr_assert_eq(pipeline_init(&ref, &s, hsr_find("zbuffer"), 1), 0);
    cr_assert_eq(pipeline_render(&ref, 200, 120, 1.0f, 0, 0), 0);
    size_t n = 200 * 120;
    for (int ord = 0; ord < ORDER_COUNT; ord++)
        for (int a = 0; a < hsr_nalgos; a++) {
            Pipeline p;
            cr_assert_eq(pipeline_init(&p, &s, hsr_algos[a], 1 + (a & 1)), 0);
            p.order = (PolyOrder)ord;
            cr_assert_eq(pipeline_render(&p, 200, 120, 1.0f, 0, 0), 0);
            cr_expect_eq(p.sp.face_sorted, ord == ORDER_FILE);
            cr_assert_eq(memcmp(p.fb.ids, ref.fb.ids, n * 4), 0, "%s under %s", hsr_algos[a]->name,
                         order_names[ord]);
            cr_assert_eq(memcmp(p.fb.depth, ref.fb.depth, n * 4), 0, "%s under %s", hsr_algos[a]->name,
                         order_names[ord]);
            pipeline_free(&p);
        }
    pipeline_free(&ref);
    scene_free(&s);
}

/* A polygon's whole content as a string: face, box, plane, corners. Two
 * orders must hold the same multiset of these. */
static void poly_text(const ScreenPolys *sp, uint32_t i, char *buf, size_t cap)
{
    const ScreenPoly *p = &sp->polys[i];
    int n = snprintf(buf, cap, "%d %d %d %d %d %a %a %a %a:", p->face, p->x0, p->x1, p->y0, p->y1,
                     (double)p->a, (double)p->b, (double)p->zc, (double)p->zmin);
    for (uint32_t k = p->first; k < sp->polys[i + 1].first && (size_t)n < cap; k++)
        n += snprintf(buf + n, cap - (size_t)n, " %d,%d,%a", sp->verts[k].x, sp->verts[k].y,
                      (double)sp->verts[k].z);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static char **poly_texts(const ScreenPolys *sp)
{
    char **t = calloc(sp->npolys, sizeof *t);
    cr_assert(t);
    for (uint32_t i = 0; i < sp->npolys; i++) {
        t[i] = malloc(512);
        cr_assert(t[i]);
        poly_text(sp, i, t[i], 512);
    }
    return t;
}

/* The order itself, checked from its definition rather than from what the
 * algorithms make of it (which is the same under any order, right or
 * wrong): front to back is non-decreasing least depth, back to front
 * non-increasing; every order is a permutation of the file order's
 * polygons, corners and all; and the map still leads each scene polygon
 * to a screen polygon of the same face. */
Test(pipeline, each_order_sorts_as_it_says_and_keeps_every_polygon)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/demo.obj"), 0);
    s.cam.yaw = 0.4f;
    s.cam.pitch = 0.3f;
    Pipeline ref;
    cr_assert_eq(pipeline_init(&ref, &s, hsr_find("hzb-octree"), 1), 0);
    cr_assert_eq(pipeline_render(&ref, 200, 120, 1.0f, 0, 0), 0);
    uint32_t n = ref.sp.npolys;
    cr_assert_gt(n, 100, "the demo scene gives many polygons");
    char **want = poly_texts(&ref.sp);
    qsort(want, n, sizeof *want, cmp_str);
    for (int ord = ORDER_FRONT; ord < ORDER_COUNT; ord++) {
        Pipeline p;
        cr_assert_eq(pipeline_init(&p, &s, hsr_find("hzb-octree"), 1), 0);
        p.order = (PolyOrder)ord;
        cr_assert_eq(pipeline_render(&p, 200, 120, 1.0f, 0, 0), 0);
        cr_assert_eq(p.sp.npolys, n);
        uint32_t moved = 0;
        for (uint32_t i = 0; i < n; i++) {
            moved += p.sp.polys[i].face != ref.sp.polys[i].face;
            if (i + 1 < n && ord == ORDER_FRONT)
                cr_assert_leq(p.sp.polys[i].zmin, p.sp.polys[i + 1].zmin, "%s at %u", order_names[ord], i);
            if (i + 1 < n && ord == ORDER_BACK)
                cr_assert_geq(p.sp.polys[i].zmin, p.sp.polys[i + 1].zmin, "%s at %u", order_names[ord], i);
        }
        cr_expect_gt(moved, n / 4, "%s moves most polygons (%u of %u)", order_names[ord], moved, n);
        char **got = poly_texts(&p.sp);
        qsort(got, n, sizeof *got, cmp_str);
        for (uint32_t i = 0; i < n; i++)
            cr_assert_str_eq(got[i], want[i], "%s keeps every polygon whole", order_names[ord]);
        cr_assert_eq(p.sp.nmap, ref.sp.nmap);
        cr_assert_gt(p.sp.nmap, 0, "the octree keeps the map");
        for (uint32_t k = 0; k < p.sp.nmap; k++) {
            cr_assert_eq(p.sp.map[k] < 0, ref.sp.map[k] < 0);
            if (p.sp.map[k] >= 0)
                cr_assert_eq(p.sp.polys[p.sp.map[k]].face, ref.sp.polys[ref.sp.map[k]].face,
                             "%s: the map follows polygon %u", order_names[ord], k);
        }
        for (uint32_t i = 0; i < n; i++)
            free(got[i]);
        free(got);
        pipeline_free(&p);
    }
    for (uint32_t i = 0; i < n; i++)
        free(want[i]);
    free(want);
    pipeline_free(&ref);
    scene_free(&s);
}

Test(pipeline, front_to_back_helps_the_pyramid_most)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/torus.obj"), 0);
    char err[256];
    cr_assert_eq(scene_make_grid(&s, 3, err, sizeof err), 0, "%s", err);
    uint64_t culled[ORDER_COUNT];
    for (int ord = 0; ord < ORDER_COUNT; ord++) {
        Pipeline p;
        cr_assert_eq(pipeline_init(&p, &s, hsr_find("hzb"), 1), 0);
        p.order = (PolyOrder)ord;
        cr_assert_eq(pipeline_render(&p, 320, 240, 1.0f, 0, 0), 0);
        culled[ord] = p.st.polys_culled;
        pipeline_free(&p);
    }
    cr_expect_gt(culled[ORDER_FRONT], culled[ORDER_FILE]);
    cr_expect_gt(culled[ORDER_FRONT], culled[ORDER_SHUFFLE]);
    cr_expect_lt(culled[ORDER_BACK], culled[ORDER_SHUFFLE], "back to front culls least");
    scene_free(&s);
}

/* Under a reordered list the octree still finds each object's few screen
 * polygons (grouped by object) and draws a sparse object polygon by
 * polygon, as in file order, instead of walking its whole tree: the same
 * nodes are visited under every order, and the buffers are the z-buffer's. */
Test(pipeline, octree_treats_sparse_objects_alike_under_every_order)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/torus.obj"), 0);
    char err[256];
    cr_assert_eq(scene_make_grid(&s, 3, err, sizeof err), 0, "%s", err);
    s.cam.yaw = 0.5f;
    s.cam.pitch = 0.4f;
    enum { W = 48, H = 36 };
    Pipeline ref;
    cr_assert_eq(pipeline_init(&ref, &s, hsr_find("zbuffer"), 1), 0);
    cr_assert_eq(pipeline_render(&ref, W, H, 1.0f, 0, 0), 0);
    uint64_t visited[ORDER_COUNT];
    for (int ord = 0; ord < ORDER_COUNT; ord++) {
        Pipeline p;
        cr_assert_eq(pipeline_init(&p, &s, hsr_find("hzb-octree"), 1), 0);
        p.order = (PolyOrder)ord;
        cr_assert_eq(pipeline_render(&p, W, H, 1.0f, 0, 0), 0);
        visited[ord] = p.st.nodes_visited;
        cr_assert_eq(memcmp(p.fb.ids, ref.fb.ids, W * H * 4), 0, "under %s", order_names[ord]);
        pipeline_free(&p);
    }
    for (int ord = 1; ord < ORDER_COUNT; ord++)
        cr_expect_eq(visited[ord], visited[ORDER_FILE], "%s visits %llu nodes, file order %llu", order_names[ord],
                     (unsigned long long)visited[ord], (unsigned long long)visited[ORDER_FILE]);
    pipeline_free(&ref);
    scene_free(&s);
}
