/* test_pipeline.c: one frame through every stage; supersampling is the
 * exact render at the higher resolution, averaged. */

#include <criterion/criterion.h>
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
