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
