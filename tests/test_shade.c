/* Tests of the shading stage: lambert (two-sided, rotated normals, the
 * per-frame face cache), depth and id colours, image buffers, speed. */

#define _POSIX_C_SOURCE 200809L
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "present.h"
#include "shade.h"

/* ==== A hand-made scene: one object, faces with given normals ==== */

#define MAXF 4096

typedef struct {
    Scene    s;
    Object   obj[2];
    float    normal[3 * MAXF];
    uint8_t  rgb[3 * MAXF];
    uint16_t fobj[MAXF];
} TestScene;

static void scene_init(TestScene *t, uint32_t nfaces)
{
    memset(t, 0, sizeof *t);
    for (int i = 0; i < 2; i++)
        t->obj[i].scale = 1;
    for (uint32_t f = 0; f < nfaces; f++) {
        t->normal[3 * f + 2] = 1;                  /* +z: towards the viewer */
        t->rgb[3 * f + 0] = 200;
        t->rgb[3 * f + 1] = 100;
        t->rgb[3 * f + 2] = 50;
    }
    t->s.objs = t->obj;
    t->s.nobjs = 1;
    t->s.nfaces = nfaces;
    t->s.face_normal = t->normal;
    t->s.face_rgb = t->rgb;
    t->s.face_obj = t->fobj;
    t->s.cam.zoom = 1;
    t->s.cam.radius = 1;
    t->s.light.dir = v3(0, 0, 1);
    t->s.light.ambient = 0.2f;
}

static void set_normal(TestScene *t, uint32_t f, float x, float y, float z)
{
    Vec3 n = v3_norm(v3(x, y, z));
    t->normal[3 * f + 0] = n.x;
    t->normal[3 * f + 1] = n.y;
    t->normal[3 * f + 2] = n.z;
}

/* A w x h frame whose pixels show ids[] (and depths, +inf if NULL). */
static void frame_init(FrameBufs *fb, int w, int h, const int32_t *ids, const float *depth)
{
    size_t n = (size_t)w * h;
    fb->w = w;
    fb->h = h;
    fb->cap = n;
    fb->ids = malloc(n * sizeof *fb->ids);
    fb->depth = malloc(n * sizeof *fb->depth);
    for (size_t i = 0; i < n; i++) {
        fb->ids[i] = ids[i];
        fb->depth[i] = depth ? depth[i] : (ids[i] >= 0 ? 0.5f : INFINITY);
    }
}

static void frame_done(FrameBufs *fb)
{
    free(fb->ids);
    free(fb->depth);
}

static int px(const Image *im, int i, int c) { return im->rgb[3 * i + c]; }

/* ==== Lambert ==== */

Test(shade, lambert_facing_light_is_brightest_and_two_sided)
{
    static TestScene t;
    scene_init(&t, 3);
    set_normal(&t, 1, 1, 0, 1);        /* tilted 45 degrees */
    set_normal(&t, 2, 0, 0, -1);       /* facing away: two-sided */
    int32_t ids[4] = { 0, 1, 2, -1 };
    FrameBufs fb;
    frame_init(&fb, 4, 1, ids, NULL);
    Image im = { 0 };
    ShadeCache cache = { 0 };
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_assert_eq(im.w, 4);
    cr_assert_eq(im.h, 1);

    /* Facing the light: the full base colour. */
    cr_expect_eq(px(&im, 0, 0), 200);
    cr_expect_eq(px(&im, 0, 1), 100);
    cr_expect_eq(px(&im, 0, 2), 50);
    /* 45 degrees: ambient + (1 - ambient) cos 45. */
    float k = 0.2f + 0.8f * sqrtf(0.5f);
    for (int c = 0; c < 3; c++) {
        cr_expect_lt(px(&im, 1, c), px(&im, 0, c));
        cr_expect_leq(abs(px(&im, 1, c) - (int)lroundf(t.rgb[c] * k)), 1,
                      "channel %d: got %d want %f", c, px(&im, 1, c), t.rgb[c] * k);
        cr_expect_eq(px(&im, 2, c), px(&im, 0, c), "flipped normal differs");
        cr_expect_eq(px(&im, 3, c), 0);
    }
    cr_expect_eq(im.lit[0], 1);
    cr_expect_eq(im.lit[1], 1);
    cr_expect_eq(im.lit[2], 1);
    cr_expect_eq(im.lit[3], 0);
    frame_done(&fb);
    image_free(&im);
    shade_cache_free(&cache);
}

Test(shade, lambert_edge_on_face_gets_ambient_only)
{
    static TestScene t;
    scene_init(&t, 1);
    set_normal(&t, 0, 0, 1, 0);        /* perpendicular to the light */
    int32_t ids[1] = { 0 };
    FrameBufs fb;
    frame_init(&fb, 1, 1, ids, NULL);
    Image im = { 0 };
    ShadeCache cache = { 0 };
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_expect_eq(px(&im, 0, 0), 40);   /* 200 * 0.2 */
    cr_expect_eq(px(&im, 0, 1), 20);
    cr_expect_eq(px(&im, 0, 2), 10);
    frame_done(&fb);
    image_free(&im);
    shade_cache_free(&cache);
}

/* The normal is turned by the object's placement and by the camera: a
 * +z face turned a quarter turn about y is edge-on to a +z light. */
Test(shade, lambert_uses_object_and_camera_rotation)
{
    static TestScene t;
    scene_init(&t, 2);
    t.s.nobjs = 2;
    t.fobj[1] = 1;
    t.obj[1].yaw = ZV_PI / 2;
    int32_t ids[2] = { 0, 1 };
    FrameBufs fb;
    frame_init(&fb, 2, 1, ids, NULL);
    Image im = { 0 };
    ShadeCache cache = { 0 };
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_expect_eq(px(&im, 0, 0), 200);
    cr_expect_eq(px(&im, 1, 0), 40, "rotated object: got %d", px(&im, 1, 0));

    /* Now turn the camera instead: both faces go edge-on... */
    t.obj[1].yaw = 0;
    t.s.cam.yaw = ZV_PI / 2;
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_expect_eq(px(&im, 0, 0), 40);
    cr_expect_eq(px(&im, 1, 0), 40);
    /* ...and the scale of an object does not change its brightness. */
    t.s.cam.yaw = 0;
    t.obj[1].scale = 3;
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_expect_eq(px(&im, 1, 0), 200);
    frame_done(&fb);
    image_free(&im);
    shade_cache_free(&cache);
}

Test(shade, cache_is_per_frame)
{
    static TestScene t;
    scene_init(&t, 5);
    int32_t ids[6] = { 3, 3, 1, 3, -1, 1 };
    FrameBufs fb;
    frame_init(&fb, 3, 2, ids, NULL);
    Image im = { 0 };
    ShadeCache cache = { 0 };
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_assert_geq(cache.cap, 5);
    uint32_t f1 = cache.frame;
    cr_expect_eq(cache.stamp[1], f1);
    cr_expect_eq(cache.stamp[3], f1);
    cr_expect_neq(cache.stamp[0], f1, "face 0 is not visible");
    cr_expect_neq(cache.stamp[2], f1);
    cr_expect_neq(cache.stamp[4], f1);
    cr_expect_eq(px(&im, 0, 0), 200);

    /* A new frame sees the new light: nothing stale is reused. */
    t.s.light.dir = v3(0, 1, 0);
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_expect_neq(cache.frame, f1);
    cr_expect_eq(px(&im, 0, 0), 40);
    cr_expect_eq(px(&im, 5, 0), 40);

    /* The cache grows with the scene. */
    static TestScene big;
    scene_init(&big, 3000);
    int32_t ids2[2000];
    for (int i = 0; i < 2000; i++)
        ids2[i] = i == 0 ? 2999 : i % 7 == 0 ? -1 : 0;
    FrameBufs fb2;
    frame_init(&fb2, 2000, 1, ids2, NULL);
    cr_assert_eq(shade_frame(&big.s, NULL, &fb2, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_expect_geq(cache.cap, 3000);
    cr_expect_eq(cache.stamp[2999], cache.frame);
    cr_expect_eq(px(&im, 0, 0), 200);
    frame_done(&fb2);

    /* But not for a picture whose pixels are few beside the faces: its
     * colours go through a table of the picture's size (issue 21). */
    ShadeCache small = { 0 };
    frame_init(&fb2, 2, 1, ids2, NULL);
    cr_assert_eq(shade_frame(&big.s, NULL, &fb2, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &small, &im), 0);
    cr_expect_eq(small.cap, 0, "no per-face arrays");
    cr_expect_geq(small.nslot, 4);
    cr_expect_lt(small.nslot, 3000);
    cr_expect_eq(px(&im, 0, 0), 200);
    cr_expect_eq(px(&im, 1, 0), 200);
    shade_cache_free(&small);
    frame_done(&fb);
    frame_done(&fb2);
    image_free(&im);
    shade_cache_free(&cache);
}

/* ==== Depth ==== */

Test(shade, depth_near_white_far_black)
{
    static TestScene t;
    scene_init(&t, 3);
    int32_t ids[4] = { 0, 1, 2, -1 };
    float depth[4] = { 0.5f, 0.2f, 0.8f, INFINITY };
    FrameBufs fb;
    frame_init(&fb, 2, 2, ids, depth);
    Image im = { 0 };
    ShadeCache cache = { 0 };
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_DEPTH, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_expect_eq(px(&im, 1, 0), 255, "nearest is white");
    cr_expect_eq(px(&im, 2, 0), 0, "farthest is black");
    cr_expect(px(&im, 0, 0) >= 126 && px(&im, 0, 0) <= 129, "middle: %d", px(&im, 0, 0));
    cr_expect_eq(px(&im, 0, 0), px(&im, 0, 1));
    cr_expect_eq(px(&im, 0, 0), px(&im, 0, 2));
    cr_expect_eq(px(&im, 3, 0), 0);
    cr_expect_eq(im.lit[2], 1, "far black pixel is still lit");
    cr_expect_eq(im.lit[3], 0);

    /* One depth in the whole frame: white. */
    fb.depth[0] = fb.depth[1] = fb.depth[2] = 0.3f;
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_DEPTH, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    for (int i = 0; i < 3; i++)
        cr_expect_eq(px(&im, i, 0), 255);
    frame_done(&fb);
    image_free(&im);
    shade_cache_free(&cache);
}

/* ==== Id colours ==== */

Test(shade, id_colours_distinct_and_never_black)
{
    static uint8_t c[1000][3];
    for (int i = 0; i < 1000; i++) {
        shade_id_colour(i, c[i]);
        int mx = c[i][0] > c[i][1] ? c[i][0] : c[i][1];
        mx = mx > c[i][2] ? mx : c[i][2];
        cr_assert_geq(mx, 128, "id %d too dark: %d %d %d", i, c[i][0], c[i][1], c[i][2]);
    }
    int same = 0, close = 0;
    for (int i = 0; i < 1000; i++)
        for (int j = i + 1; j < 1000; j++) {
            int d0 = c[i][0] - c[j][0], d1 = c[i][1] - c[j][1], d2 = c[i][2] - c[j][2];
            if (!d0 && !d1 && !d2)
                same++;
            if (abs(j - i) == 1 && d0 * d0 + d1 * d1 + d2 * d2 < 60 * 60)
                close++;
        }
    cr_expect_leq(same, 5, "%d identical pairs among 1000 ids", same);
    cr_expect_eq(close, 0, "%d neighbouring ids look alike", close);
    /* Deterministic. */
    uint8_t again[3];
    shade_id_colour(417, again);
    cr_expect_eq(memcmp(again, c[417], 3), 0);
}

Test(shade, id_mode_paints_id_colours)
{
    static TestScene t;
    scene_init(&t, 10);
    int32_t ids[4] = { 7, -1, 7, 9 };
    FrameBufs fb;
    frame_init(&fb, 4, 1, ids, NULL);
    Image im = { 0 };
    ShadeCache cache = { 0 };
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_ID, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    uint8_t c7[3], c9[3];
    shade_id_colour(7, c7);
    shade_id_colour(9, c9);
    cr_expect_eq(memcmp(im.rgb + 0, c7, 3), 0);
    cr_expect_eq(memcmp(im.rgb + 6, c7, 3), 0);
    cr_expect_eq(memcmp(im.rgb + 9, c9, 3), 0);
    cr_expect_eq(im.lit[1], 0);
    cr_expect_eq(px(&im, 1, 0) + px(&im, 1, 1) + px(&im, 1, 2), 0);

    /* Lambert next frame on the same cache: no id colour is left over. */
    cr_assert_eq(shade_frame(&t.s, NULL, &fb, &(ShadeSettings){ .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 }, &cache, &im), 0);
    cr_expect_eq(px(&im, 0, 0), 200);
    frame_done(&fb);
    image_free(&im);
    shade_cache_free(&cache);
}

/* ==== Buffers and names ==== */

Test(shade, image_resize_reuses_memory)
{
    Image im = { 0 };
    cr_assert_eq(image_resize(&im, 10, 10), 0);
    uint8_t *rgb = im.rgb;
    cr_assert_geq(im.cap, 100);
    cr_assert_eq(image_resize(&im, 5, 20), 0);
    cr_expect_eq(im.rgb, rgb, "same pixel count must not reallocate");
    cr_expect_eq(im.w, 5);
    cr_expect_eq(im.h, 20);
    cr_assert_eq(image_resize(&im, 30, 30), 0);
    cr_expect_geq(im.cap, 900);
    image_free(&im);
    cr_expect_null(im.rgb);
}

Test(shade, names)
{
    cr_expect_eq(shade_from_name("lambert"), SHADE_LAMBERT);
    cr_expect_eq(shade_from_name("depth"), SHADE_DEPTH);
    cr_expect_eq(shade_from_name("id"), SHADE_ID);
    cr_expect_eq(shade_from_name("phong"), -1);
    cr_expect_eq(shade_from_name(NULL), -1);
    for (int i = 0; i < SHADE_COUNT; i++)
        cr_expect_eq(shade_from_name(shade_names[i]), i);
}


/* ==== supersampling ==== */

Test(shade, downsample_lit_by_majority_coloured_by_lit_mean)
{
    Image src = { 0 }, dst = { 0 };
    cr_assert_eq(image_resize(&src, 4, 2), 0);
    memset(src.rgb, 0, 3 * 8);
    memset(src.lit, 0, 8);
    /* left 2x2 block: two lit samples (red 200 and 100): lit, mean 150 */
    src.lit[0] = src.lit[5] = 1;
    src.rgb[0] = 200;
    src.rgb[3 * 5] = 100;
    /* right block: one lit sample: under half, background */
    src.lit[3] = 1;
    src.rgb[3 * 3 + 1] = 255;
    cr_assert_eq(image_downsample(&src, 2, &dst), 0);
    cr_assert_eq(dst.w, 2);
    cr_assert_eq(dst.h, 1);
    cr_expect_eq(dst.lit[0], 1);
    cr_expect_eq(dst.rgb[0], 150);
    cr_expect_eq(dst.rgb[1], 0);
    cr_expect_eq(dst.lit[1], 0);
    cr_expect_eq(dst.rgb[3 + 1], 0, "the background stays black");
    /* k = 1 is a copy */
    cr_assert_eq(image_downsample(&src, 1, &dst), 0);
    cr_expect_eq(dst.w, 4);
    cr_expect_eq(memcmp(dst.rgb, src.rgb, 24), 0);
    cr_expect_eq(memcmp(dst.lit, src.lit, 8), 0);
    image_free(&src);
    image_free(&dst);
}

/* ==== The eight-face Lambert loop against the face-by-face one ==== */

static float rnd(uint32_t *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (float)(*seed >> 8) / 16777216.0f;
}

/* lambert_face()'s formula, written out here: the reference. */
static void lambert_ref(const Scene *s, int obj, uint32_t f, uint8_t out[3])
{
    Mat4 m = m4_mul(camera_view(&s->cam), object_matrix(&s->objs[obj]));
    const float *n = s->face_normal + 3 * (size_t)f;
    Vec3 v = v3(m.m[0][0] * n[0] + m.m[0][1] * n[1] + m.m[0][2] * n[2],
                m.m[1][0] * n[0] + m.m[1][1] * n[1] + m.m[1][2] * n[2],
                m.m[2][0] * n[0] + m.m[2][1] * n[1] + m.m[2][2] * n[2]);
    v = v3_norm(v);
    float amb = s->light.ambient;
    float k = amb + (1.0f - amb) * fabsf(v3_dot(v, s->light.dir));
    static const uint8_t grey[3] = { 204, 204, 196 };   /* scene.c's default colour */
    const uint8_t *base = s->face_rgb ? s->face_rgb + 3 * (size_t)f : grey;
    for (int c = 0; c < 3; c++) {
        float x = (float)base[c] * k + 0.5f;
        out[c] = x <= 0.0f ? 0 : x >= 255.0f ? 255 : (uint8_t)x;
    }
}

/* Two objects of 1001 and 1002 faces (runs that end mid-block), random
 * normals (zero, tiny, huge, non-unit, negative), turns, scales, light and
 * ambient, base colours or none: the colours of every face pass (the
 * polygons are most of the faces: object by object, eight at a time) and
 * of the pixel pass (face by face) equal the reference, byte for byte. */
Test(shade, lambert_eight_at_a_time_equals_face_by_face)
{
    static TestScene t;
    const uint32_t na = 1001, nf = 2003;
    uint32_t seed = 12345;
    for (int round = 0; round < 12; round++) {
        scene_init(&t, nf);
        t.s.nobjs = 2;
        t.obj[0].face_base = 0;
        t.obj[0].face_count = na;
        t.obj[1].face_base = (int32_t)na;
        t.obj[1].face_count = nf - na;
        for (int o = 0; o < 2; o++) {
            t.obj[o].poly_count = 1;
            t.obj[o].yaw = 6.3f * rnd(&seed);
            t.obj[o].pitch = 6.3f * rnd(&seed);
            t.obj[o].roll = 6.3f * rnd(&seed);
            t.obj[o].scale = round % 3 == 0 ? 1e-3f + rnd(&seed) : 1 + 100 * rnd(&seed);
        }
        t.s.cam.yaw = 6.3f * rnd(&seed);
        t.s.cam.pitch = 3 * rnd(&seed) - 1.5f;
        light_set(&t.s.light, 360 * rnd(&seed) - 180, 180 * rnd(&seed) - 90, round == 1 ? 0 : round == 2 ? 1 : rnd(&seed));
        for (uint32_t f = 0; f < nf; f++) {
            t.fobj[f] = f >= na;
            float sc = f % 7 == 0 ? 1e-20f : f % 7 == 1 ? 1e20f : 1;
            for (int c = 0; c < 3; c++)
                t.normal[3 * f + c] = f % 13 == 0 ? 0 : sc * (2 * rnd(&seed) - 1);
            if (f % 17 == 3) {          /* axis-aligned: exact ties of the dot product */
                t.normal[3 * f] = t.normal[3 * f + 1] = 0;
                t.normal[3 * f + 2] = f % 2 ? 1 : -1;
            }
            for (int c = 0; c < 3; c++)
                t.rgb[3 * f + c] = (uint8_t)(f % 11 == 0 ? 255 * (c & 1) : 256 * rnd(&seed));
        }
        if (round % 4 == 3)
            t.s.face_rgb = NULL;
        /* every face on screen once, and some background */
        int w = 64, h = (int)(nf + w - 1) / w + 1;
        int32_t *ids = malloc((size_t)w * h * sizeof *ids);
        for (int i = 0; i < w * h; i++)
            ids[i] = i < (int)nf && i % 29 != 5 ? i : -1;
        FrameBufs fb;
        frame_init(&fb, w, h, ids, NULL);
        ScreenPolys sp = { 0 };
        sp.polys = calloc(nf + 1, sizeof *sp.polys);
        for (uint32_t f = 0; f < nf; f++)
            sp.polys[f].face = (int32_t)f;
        sp.npolys = nf;
        Image a = { 0 }, b = { 0 };
        ShadeCache ca = { 0 }, cb = { 0 };
        ShadeSettings set = { .mode = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT, .highlight = -1 };
        cr_assert_eq(shade_frame(&t.s, &sp, &fb, &set, &ca, &a), 0);
        cr_assert_eq(shade_frame(&t.s, NULL, &fb, &set, &cb, &b), 0);
        for (int i = 0; i < w * h; i++) {
            uint8_t want[3] = { 0, 0, 0 };
            if (ids[i] >= 0)
                lambert_ref(&t.s, t.fobj[ids[i]], (uint32_t)ids[i], want);
            for (int c = 0; c < 3; c++) {
                cr_assert_eq(px(&a, i, c), want[c], "round %d face %d channel %d: %d, want %d", round, ids[i], c,
                             px(&a, i, c), want[c]);
                cr_assert_eq(px(&b, i, c), want[c], "round %d face %d channel %d (pixel pass)", round, ids[i], c);
            }
            cr_assert_eq(a.lit[i], ids[i] >= 0);
            cr_assert_eq(b.lit[i], ids[i] >= 0);
        }
        free(sp.polys);
        free(ids);
        frame_done(&fb);
        image_free(&a);
        image_free(&b);
        shade_cache_free(&ca);
        shade_cache_free(&cb);
    }
}

/* The colours of a picture with few pixels beside the faces (through
 * the slot table, where two faces may take one slot) are the per-face
 * cache's: the same ids in the first rows of a picture big enough for
 * the per-face arrays give the same bytes, Lambert and id colours, with
 * random normals and colours and faces seen again and again. */
Test(shade, few_pixels_many_faces_shade_as_the_per_face_cache)
{
    static TestScene t;
    const uint32_t nf = 3000;
    uint32_t seed = 99;
    scene_init(&t, nf);
    for (uint32_t f = 0; f < nf; f++) {
        set_normal(&t, f, 2 * rnd(&seed) - 1, 2 * rnd(&seed) - 1, 2 * rnd(&seed) - 1);
        for (int c = 0; c < 3; c++)
            t.rgb[3 * f + c] = (uint8_t)(256 * rnd(&seed));
    }
    light_set(&t.s.light, 30, 20, 0.3f);
    /* 32 x 32 pixels: a table of 2048 slots (16 kB, under the arrays'
     * 21 kB); 32 x 64: 4096 slots would not be, so the arrays are used */
    int w = 32, h = 64;
    int32_t *ids = malloc((size_t)w * h * sizeof *ids);
    for (int i = 0; i < w * h; i++)
        ids[i] = i % 11 == 0 ? -1 : i % 5 == 0 ? (int32_t)(i / 5) : (int32_t)(rnd(&seed) * nf);
    for (int mode = 0; mode < 2; mode++) {
        ShadeSettings set = { .mode = mode ? SHADE_ID : SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT,
                              .highlight = -1 };
        FrameBufs small, big;
        frame_init(&small, w, h / 2, ids, NULL);
        frame_init(&big, w, h, ids, NULL);
        ShadeCache cs = { 0 }, cb = { 0 };
        Image a = { 0 }, b = { 0 };
        cr_assert_eq(shade_frame(&t.s, NULL, &small, &set, &cs, &a), 0);
        cr_assert_eq(shade_frame(&t.s, NULL, &big, &set, &cb, &b), 0);
        cr_expect(cs.nslot > 0 && cs.cap == 0, "the small picture through the slots");
        cr_expect(cb.cap >= nf, "the big one through the per-face arrays");
        cr_expect_eq(memcmp(a.rgb, b.rgb, 3 * (size_t)w * (h / 2)), 0, "mode %d: colours differ", mode);
        cr_expect_eq(memcmp(a.lit, b.lit, (size_t)w * (h / 2)), 0, "mode %d: lit differs", mode);
        frame_done(&small);
        frame_done(&big);
        image_free(&a);
        image_free(&b);
        shade_cache_free(&cs);
        shade_cache_free(&cb);
    }
    free(ids);
}
