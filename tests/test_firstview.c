/* test_firstview.c: the automatic first view (app/firstview.c): an open
 * box is seen through its opening (its blocks fill a third of the
 * picture, not a few pixels), a solid from its front (the format's
 * forward axis, else the side more faces face), a long one from its
 * side; inside-out models, point clouds and huge scenes (the stand-in)
 * get a view too. The view command's round trip, which relies on the
 * choice being the same every time, is in test_viewcmd.c. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "testlib.h"
#include "writers.h"

/* ==== Helpers ==== */

/* Render the view fv chose at w x h; the share of the drawn pixels whose
 * face belongs to an object whose name starts with one of `names`
 * (a comma list), and the share of the picture drawn. */
static double share_of(Scene *s, const FirstView *fv, int w, int h, const char *names, double *drawn_out)
{
    s->cam.yaw = deg2rad(fv->yaw);
    s->cam.pitch = deg2rad(fv->pitch);
    s->cam.roll = 0;
    scene_fit(s);
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, s, hsr_find("zbuffer"), 1), 0);
    cr_assert_eq(pipeline_render(&p, w, h, 1.0f, 0, 0), 0);
    long drawn = 0, hit = 0;
    for (int k = 0; k < w * h; k++) {
        int32_t id = p.fb.ids[k];
        if (id < 0)
            continue;
        drawn++;
        int o;
        uint32_t local;
        if (scene_prim_of(s, id, &o, &local) != PRIM_FACE)
            continue;
        const char *n = s->objs[o].name;
        for (const char *q = names; *q;) {
            size_t len = strcspn(q, ",");
            if (strncmp(n, q, len) == 0) {
                hit++;
                break;
            }
            q += len + (q[len] == ',');
        }
    }
    pipeline_free(&p);
    if (drawn_out)
        *drawn_out = (double)drawn / (w * h);
    return drawn ? (double)hit / drawn : 0;
}

/* The viewer stands on the -z side (looks towards +z) for yaws past 90. */
static int from_minus_z(const FirstView *fv) { return view_dir(fv->yaw, fv->pitch).z < 0; }

/* ==== Open shells ==== */

/* A room 10 wide, deep and tall whose walls face inwards, open at z = 0
 * (the Cornell box's layout, its front wall left out), with two closed
 * blocks on its floor. */
static const char open_box[] =
    "v 0 0 0\nv 10 0 0\nv 10 0 10\nv 0 0 10\nv 0 10 0\nv 10 10 0\nv 10 10 10\nv 0 10 10\n"
    "o floor\nf 1 4 3 2\n"
    "o ceiling\nf 5 6 7 8\n"
    "o back\nf 4 8 7 3\n"
    "o left\nf 1 5 8 4\n"
    "o right\nf 2 3 7 6\n"
    /* short block: x 2..5, y 0..3, z 2..5, faces outwards */
    "v 2 0 2\nv 5 0 2\nv 5 3 2\nv 2 3 2\nv 2 0 5\nv 5 0 5\nv 5 3 5\nv 2 3 5\n"
    "o short_block\nf 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 12 16 15 11\nf 9 13 16 12\nf 10 11 15 14\n"
    /* tall block: x 6..9, y 0..7, z 5..8 */
    "v 6 0 5\nv 9 0 5\nv 9 7 5\nv 6 7 5\nv 6 0 8\nv 9 0 8\nv 9 7 8\nv 6 7 8\n"
    "o tall_block\nf 17 20 19 18\nf 21 22 23 24\nf 17 18 22 21\nf 20 24 23 19\nf 17 21 24 20\nf 18 19 23 22\n";

Test(firstview, looks_into_an_open_box_through_its_opening)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "room.obj", open_box), 0);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect(from_minus_z(&fv), "seen from the open side (-z): yaw %g pitch %g", fv.yaw, fv.pitch);
    cr_expect_eq(fv.back, 0, "no wall seen from behind: %g", fv.back);
    double blocks = share_of(&s, &fv, 160, 96, "short_block,tall_block", NULL);
    cr_expect_gt(blocks, 0.25, "the blocks are a quarter of the picture or more: %.3f", blocks);
    /* what the geometry alone chose before: the blocks hidden behind a wall */
    FirstView old = fv;
    scene_pick_view(&s, &old.yaw, &old.pitch);
    double hidden = share_of(&s, &old, 160, 96, "short_block,tall_block", NULL);
    cr_expect_lt(hidden, blocks / 2, "the geometry's view shows less of them: %.3f", hidden);
    scene_free(&s);
}

/* The Cornell box of ../shared/models: its front wall is commented out;
 * issue 18 measured 2% of blocks from outside, 32% through the opening. */
Test(models, cornell_box_through_its_opening)
{
    const char *p = tl_shared_model("cornell_box.obj");
    if (!p)
        cr_skip_test("../shared/models/cornell_box.obj not found");
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, p), 0);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect(from_minus_z(&fv), "its opening is at z = 0: yaw %g", fv.yaw);
    double blocks = share_of(&s, &fv, 160, 96, "short_block,tall_block", NULL);
    cr_expect_gt(blocks, 0.30, "the blocks: %.3f of the model drawn", blocks);
    scene_free(&s);
}

/* ==== Solids: the front ==== */

/* A 2 x 2 x 2 box whose -z side is made of 8 x 8 quads (128 triangles)
 * and every other side of 2: its outline is the same from +z and -z,
 * more of its faces face -z. */
static char *detailed_box(void)
{
    static char buf[16384];
    size_t at = 0;
#define PUT(...) at += (size_t)snprintf(buf + at, sizeof buf - at, __VA_ARGS__)
    for (int j = 0; j <= 8; j++)
        for (int i = 0; i <= 8; i++)
            PUT("v %g %g -1\n", -1 + i / 4.0, -1 + j / 4.0);
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 8; i++) {
            int a = 1 + j * 9 + i;
            /* seen from -z, counter-clockwise */
            PUT("f %d %d %d\nf %d %d %d\n", a, a + 9, a + 10, a, a + 10, a + 1);
        }
    int b = 82; /* the box's corners after the grid's 81 vertices */
    PUT("v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n");
    int f[5][4] = { { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 3, 7, 6, 2 }, { 0, 4, 7, 3 }, { 1, 2, 6, 5 } };
    for (int k = 0; k < 5; k++)
        PUT("f %d %d %d\nf %d %d %d\n", b + f[k][0], b + f[k][1], b + f[k][2], b + f[k][0], b + f[k][2],
            b + f[k][3]);
#undef PUT
    return buf;
}

Test(firstview, a_solid_from_the_side_more_faces_face)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "box.obj", detailed_box()), 0);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect_eq(fv.front.from, FRONT_FACES);
    cr_expect_lt(fv.front.dir.z, -0.99f, "the faces lean to -z: %g", fv.front.dir.z);
    cr_expect(from_minus_z(&fv), "an OBJ says nothing: seen from its detailed side, yaw %g", fv.yaw);
    scene_free(&s);
}

#ifdef ZV_ASSIMP
/* The same box as glTF, whose front faces +z whatever the faces say. */
Test(firstview, a_gltf_from_its_front)
{
    Mesh m;
    char err[256], path[] = "/tmp/zview-firstview-XXXXXX.glb";
    const char *text = detailed_box();
    cr_assert_eq(mesh_parse(&m, "box.obj", text, strlen(text), err, sizeof err), 0, "%s", err);
    size_t n;
    char *glb = w_glb(&m, &n);
    mesh_free(&m);
    cr_assert_not_null(glb);
    int fd = mkstemps(path, 4);
    cr_assert_geq(fd, 0);
    close(fd);
    cr_assert_eq(w_save(path, glb, n), 0);
    free(glb);
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, path), 0);
    unlink(path);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect_eq(fv.front.from, FRONT_FORMAT);
    cr_expect_gt(fv.front.dir.z, 0.99f, "glTF's front: +z (%g)", fv.front.dir.z);
    cr_expect(!from_minus_z(&fv), "seen from the +z side: yaw %g", fv.yaw);
    scene_free(&s);
}
#endif

/* Lucy, whose back is towards +z (../shared/models/README.md). */
Test(models, lucy_from_the_front)
{
    const char *p = tl_shared_model("lucy-100k.obj");
    if (!p)
        cr_skip_test("../shared/models/lucy-100k.obj not found");
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, p), 0);
    FirstView fv;
    app_first_view(&s, 0, &fv);
    cr_expect(from_minus_z(&fv), "not from behind: yaw %g", fv.yaw);
    scene_free(&s);
}

/* ==== Shapes ==== */

static const char bar[] =
    "v -5 -0.5 -0.5\nv 5 -0.5 -0.5\nv 5 0.5 -0.5\nv -5 0.5 -0.5\n"
    "v -5 -0.5 0.5\nv 5 -0.5 0.5\nv 5 0.5 0.5\nv -5 0.5 0.5\n";

Test(firstview, a_long_model_from_its_long_side)
{
    char text[512];
    snprintf(text, sizeof text, "%sf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n", bar);
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "bar.obj", text), 0);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect(fabsf(fv.yaw) <= 30.5f, "from its long side, towards +z (the tie's side): yaw %g", fv.yaw);
    cr_expect_gt(fv.pitch, 0, "from above: a solid gets a three-quarter view");
    cr_expect_eq(fv.front.from, FRONT_NONE, "a box's faces lean nowhere");
    cr_expect_eq(fv.rendered, FV_VIEWS);
    cr_expect_gt(fv.seen, 0.1, "the picture shows it: %g", fv.seen);
    scene_free(&s);
}

/* A panel 4 wide, 3 tall and 0.2 thick, facing +z: a level view sees
 * all of its face, a three-quarter view 0.78 of it; the level views'
 * handicap keeps the three-quarter view for a solid. */
Test(firstview, a_flat_solid_gets_a_three_quarter_view)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "panel.obj",
                                    "v -2 -1.5 -0.1\nv 2 -1.5 -0.1\nv 2 1.5 -0.1\nv -2 1.5 -0.1\n"
                                    "v -2 -1.5 0.1\nv 2 -1.5 0.1\nv 2 1.5 0.1\nv -2 1.5 0.1\n"
                                    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n"),
                 0);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect_eq(fv.pitch, 25, "from above, not level: yaw %g pitch %g", fv.yaw, fv.pitch);
    cr_expect(fabsf(fv.yaw) <= 30.5f, "at its face: yaw %g", fv.yaw);
    scene_free(&s);
}

Test(firstview, an_inside_out_model_is_seen_as_a_solid)
{
    char text[512];
    /* the bar with every face wound the other way */
    snprintf(text, sizeof text, "%sf 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n", bar);
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "inside-out.obj", text), 0);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect(fv.inside_out, "every face seen from behind");
    cr_expect(fabsf(fv.yaw) <= 30.5f || fabsf(fv.yaw) >= 149.5f, "still from its long side: yaw %g", fv.yaw);
    cr_expect_gt(fv.seen, 0.1, "%g", fv.seen);
    scene_free(&s);
}

Test(firstview, a_point_cloud_gets_a_view)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "cloud.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\np 1 2 3 4\n"), 0);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect_eq(fv.rendered, FV_VIEWS);
    cr_expect_gt(fv.seen, 0, "points count as seen");
    cr_expect_eq(fv.back, 0);
    scene_free(&s);
}

/* ==== Huge scenes: the stand-in ==== */

/* A closed bar 4 long and 2 across, its long sides cut into n x n quads
 * each (as triangles): 8 n^2 + 4 triangles. */
static char *fine_bar(int n)
{
    size_t cap = (size_t)n * n * 400 + 4096, at = 0;
    char *buf = malloc(cap);
    cr_assert_not_null(buf);
#define PUT(...) at += (size_t)snprintf(buf + at, cap - at, __VA_ARGS__)
    /* the four long sides: a grid of (n+1)^2 vertices each, along x */
    for (int side = 0; side < 4; side++) {
        for (int j = 0; j <= n; j++)
            for (int i = 0; i <= n; i++) {
                float x = -2 + 4.0f * i / n, t = -1 + 2.0f * j / n;
                float y = side == 0 ? -1 : side == 1 ? t : side == 2 ? 1 : -t;
                float z = side == 0 ? -t : side == 1 ? -1 : side == 2 ? t : 1;
                PUT("v %g %g %g\n", x, y, z);
            }
        int base = 1 + side * (n + 1) * (n + 1);
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                int a = base + j * (n + 1) + i;
                PUT("f %d %d %d\nf %d %d %d\n", a, a + n + 2, a + 1, a, a + n + 1, a + n + 2);
            }
    }
    /* the ends */
    int e = 1 + 4 * (n + 1) * (n + 1);
    PUT("v -2 -1 -1\nv -2 1 -1\nv -2 1 1\nv -2 -1 1\n");
    PUT("v 2 -1 -1\nv 2 1 -1\nv 2 1 1\nv 2 -1 1\n");
    PUT("f %d %d %d\nf %d %d %d\n", e, e + 3, e + 2, e, e + 2, e + 1);
    PUT("f %d %d %d\nf %d %d %d\n", e + 4, e + 5, e + 6, e + 4, e + 6, e + 7);
#undef PUT
    return buf;
}

Test(firstview, a_huge_scene_is_scored_on_a_stand_in)
{
    char *text = fine_bar(120);         /* 115,204 triangles */
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "fine-bar.obj", text), 0);
    free(text);
    cr_assert_geq(s.npolys, FV_STANDIN_POLYS);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect(fv.standin, "a stand-in was rendered");
    cr_expect_lt(fv.polys, s.npolys / 4, "of far fewer polygons: %u of %u", fv.polys, s.npolys);
    cr_expect(fabsf(fv.yaw) <= 30.5f || fabsf(fv.yaw) >= 149.5f, "from its long side: yaw %g", fv.yaw);
    cr_expect_lt(fv.back, 0.01, "its faces keep their sides (a sliver may turn): %g", fv.back);
    /* the stand-in's outline is the model's, to a cell */
    Scene st;
    cr_assert_eq(app_standin(&s, &st), 0);
    FirstView at = fv;
    double cover_model, cover_standin;
    share_of(&s, &at, 64, 48, "", &cover_model);
    share_of(&st, &at, 64, 48, "", &cover_standin);
    cr_expect_float_eq(cover_standin, cover_model, 0.05 * cover_model, "covered: %g against %g", cover_standin,
                       cover_model);
    scene_free(&st);
    scene_free(&s);
}

/* 120,000 points on the faces of a bar 8 long, 1 across. */
Test(firstview, a_huge_cloud_is_scored_on_a_stand_in)
{
    const int n = 120000;
    size_t cap = (size_t)n * 40 + 64, at = 0;
    char *text = malloc(cap);
    cr_assert_not_null(text);
    uint32_t r = 12345;
    for (int i = 0; i < n; i++) {
        float u[3];
        for (int k = 0; k < 3; k++) {
            r = r * 1664525u + 1013904223u;
            u[k] = (float)(r >> 8) / (1 << 24) - 0.5f;
        }
        u[1 + i % 2] = i % 4 < 2 ? -0.5f : 0.5f;     /* onto one of the four long faces */
        at += (size_t)snprintf(text + at, cap - at, "v %g %g %g\n", 8 * u[0], u[1], u[2]);
    }
    at += (size_t)snprintf(text + at, cap - at, "p");
    for (int i = 0; i < n && at + 16 < cap; i++)
        at += (size_t)snprintf(text + at, cap - at, " %d", i + 1);
    snprintf(text + at, cap - at, "\n");
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "cloud.obj", text), 0);
    free(text);
    cr_assert_eq(s.npoints, (uint32_t)n);
    FirstView fv;
    app_first_view(&s, 1, &fv);
    cr_expect(fv.standin, "a stand-in was rendered");
    cr_expect_lt(fv.prims, (uint32_t)n / 4, "of far fewer points: %u", fv.prims);
    cr_expect(fabsf(fv.yaw) <= 30.5f || fabsf(fv.yaw) >= 149.5f, "from its long side: yaw %g", fv.yaw);
    scene_free(&s);
}

Test(firstview, a_small_scene_needs_no_stand_in)
{
    Scene s, st;
    cr_assert_eq(tl_scene_from_text(&s, "room.obj", open_box), 0);
    cr_expect_eq(app_standin(&s, &st), -1);
    scene_free(&s);
}
