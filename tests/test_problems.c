/* test_problems.c: what the check finds, on the model (--problems,
 * --parts): the marks set from a check (scene/marks.c) against answers
 * known by construction (an open cube's boundary is the missing side's
 * four edges), the faces given back to the check equal to the loader's,
 * the pictures with and without the overlay compared buffer for buffer,
 * every algorithm agreeing with the problem edges drawn, a file read
 * again in its place (scene_replace_file), and the words and colours. */

#define _DEFAULT_SOURCE      /* mkstemp */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "backdrop.h"
#include "testlib.h"
#include "../src/viewer/viewer_app.h"

static const char *cube_v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
/* outward faces; the last is the x = 0 side (vertices 4 1 5 8) */
static const char *cube_f[6] = { "f 1 4 3 2\n", "f 5 6 7 8\n", "f 1 2 6 5\n", "f 2 3 7 6\n", "f 3 4 8 7\n",
                                 "f 4 1 5 8\n" };

/* The cube's text: nfaces of its faces (6 closed, 5 open), face `flip`
 * written backwards (-1 none), every face backwards when all_flipped. */
static void cube_text(char *buf, size_t n, int nfaces, int flip, int all_flipped)
{
    snprintf(buf, n, "%s", cube_v);
    for (int i = 0; i < nfaces; i++) {
        int a, b, c, d;
        sscanf(cube_f[i], "f %d %d %d %d", &a, &b, &c, &d);
        size_t len = strlen(buf);
        if (i == flip || all_flipped)
            snprintf(buf + len, n - len, "f %d %d %d %d\n", d, c, b, a);
        else
            snprintf(buf + len, n - len, "%s", cube_f[i]);
    }
}

static void checked_scene(Scene *s, const char *text)
{
    char err[256];
    cr_assert_eq(tl_scene_from_text(s, "t.obj", text), 0);
    cr_assert_eq(app_check_scene(s, 1, NULL, err, sizeof err), 0, "%s", err);
    cr_assert(s->marks.set);
}

Test(problems, an_open_cube_marks_the_four_edges_of_its_missing_side)
{
    char t[1024];
    cube_text(t, sizeof t, 5, -1, 0);
    Scene s;
    checked_scene(&s, t);
    cr_assert_eq(s.marks.nedges, 4);
    cr_assert_eq(s.objs[0].mark_count, 4);
    cr_assert_eq(s.nprims, 4, "the marks are the scene's only primitives");
    /* the missing side 4 1 5 8 (0-based 3 0 4 7): its four edges, once each */
    static const uint32_t want[4][2] = { { 0, 3 }, { 0, 4 }, { 4, 7 }, { 3, 7 } };
    int seen[4] = { 0 };
    for (uint32_t k = 0; k < 4; k++) {
        cr_assert_eq(s.marks.edge_kind[k], MARK_BOUNDARY);
        uint32_t v[2];
        scene_edge_verts(&s, &s.objs[0], PRIM_MARK, k, v);
        uint32_t lo = v[0] < v[1] ? v[0] : v[1], hi = v[0] ^ v[1] ^ lo;
        for (int w = 0; w < 4; w++)
            if (want[w][0] == lo && want[w][1] == hi)
                seen[w]++;
    }
    for (int w = 0; w < 4; w++)
        cr_expect_eq(seen[w], 1, "edge %u-%u marked %d times", want[w][0], want[w][1], seen[w]);
    cr_assert_eq(s.marks.nflagged, 0, "an open cube's faces agree");
    /* an id of the overlay names its kind */
    int obj;
    uint32_t local;
    cr_assert_eq(scene_prim_of(&s, (int32_t)s.nfaces + 2, &obj, &local), PRIM_MARK);
    cr_assert_eq(local, 2);
    scene_free(&s);
}

Test(problems, a_closed_cube_marks_nothing)
{
    char t[1024];
    cube_text(t, sizeof t, 6, -1, 0);
    Scene s;
    checked_scene(&s, t);
    cr_assert_eq(s.marks.nedges, 0);
    cr_assert_eq(s.marks.nflagged, 0);
    cr_assert_eq(s.marks.nparts, 1);
    cr_assert_eq(s.nprims, 0);
    scene_free(&s);
}

Test(problems, flipped_faces_and_an_inside_out_cube)
{
    char t[1024];
    cube_text(t, sizeof t, 6, 3, 0);
    Scene s;
    checked_scene(&s, t);
    for (uint32_t f = 0; f < 6; f++)
        cr_expect_eq(s.marks.face[f], f == 3 ? MARK_FLIPPED : 0, "face %u", f);
    scene_free(&s);
    /* inside out: every face is seen from inside, none is "the one" */
    cube_text(t, sizeof t, 6, -1, 1);
    checked_scene(&s, t);
    cr_assert_eq(s.marks.nflagged, 6);
    for (uint32_t f = 0; f < 6; f++)
        cr_expect_eq(s.marks.face[f], MARK_FLIPPED, "face %u", f);
    scene_free(&s);
}

Test(problems, parts_are_numbered_across_objects)
{
    /* object a: two separate triangles (2 parts); object b: one triangle */
    const char *t = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\n"
                    "o a\nf 1 2 3\nf 4 5 6\no b\nf 1 2 3\n";
    Scene s;
    checked_scene(&s, t);
    cr_assert_eq(s.marks.nparts, 3);
    cr_assert_neq(s.marks.face_part[0], s.marks.face_part[1]);
    cr_assert_eq(s.marks.face_part[2], 2, "object b's part comes after a's two");
    scene_free(&s);
}

/* A file of planar and non-planar polygons: the check is given back the
 * faces the loader read, corner for corner, though the scene split the
 * non-planar ones into fans. */
Test(problems, the_check_gets_the_loaders_faces_back)
{
    const char *t = "v 0 0 0\nv 2 0 0\nv 2 2 0.5\nv 0 2 0\nv 1 3 -0.3\nv 3 3 0\nv 4 1 1\n"
                    "o a\nf 1 2 3 4 5\nf 2 6 7\no b\nf 3 6 7 4\nf 1 2 4\n";
    char path[] = "/tmp/zv-problems-XXXXXX";
    int fd = mkstemp(path);
    cr_assert_geq(fd, 0);
    FILE *f = fdopen(fd, "w");
    fputs(t, f);
    fclose(f);
    Mesh m;
    char err[256];
    cr_assert_eq(mesh_load_as(&m, path, "obj", err, sizeof err), 0, "%s", err);
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "t.obj", t), 0);
    cr_assert_gt(s.npolys, s.nfaces, "some face was split into a fan");
    Mesh *back;
    int n;
    cr_assert_eq(scene_check_meshes(&s, &back, &n, err, sizeof err), 0);
    cr_assert_eq(n, 1);
    cr_assert_eq(back[0].nfaces, m.nfaces);
    cr_assert_eq(back[0].nverts, m.nverts);
    for (uint32_t k = 0; k <= m.nfaces; k++)
        cr_assert_eq(back[0].face_start[k], m.face_start[k], "face %u", k);
    for (uint32_t k = 0; k < m.face_start[m.nfaces]; k++)
        cr_assert_eq(back[0].corner[k], m.corner[k], "corner %u", k);
    cr_assert_eq(memcmp(back[0].pos, m.pos, 3 * sizeof(float) * m.nverts), 0);
    scene_check_meshes_free(back, n);
    mesh_free(&m);
    scene_free(&s);
    unlink(path);
}

/* ==== The pictures ==== */

/* A frame through the pipeline, as --print and -o make it. */
static void frame(Scene *s, int problems, int parts, FrameBufs *ids, Image *img)
{
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, s, hsr_find("zbuffer"), 1), 0);
    p.problems = problems;
    p.parts = parts;
    p.samples = 1;
    s->cam.yaw = -1.2f;     /* the open side (x = 0) in view */
    s->cam.pitch = 0.4f;
    cr_assert_eq(pipeline_render(&p, 96, 64, 1.0f, 0, 1), 0);
    size_t n = (size_t)p.fb.w * p.fb.h;
    ids->w = p.fb.w;
    ids->h = p.fb.h;
    ids->ids = malloc(n * sizeof *ids->ids);
    memcpy(ids->ids, p.fb.ids, n * sizeof *ids->ids);
    img->w = p.img.w;
    img->h = p.img.h;
    img->rgb = malloc(3 * n);
    memcpy(img->rgb, p.img.rgb, 3 * n);
    pipeline_free(&p);
}

static void frame_free(FrameBufs *ids, Image *img)
{
    free(ids->ids);
    free(img->rgb);
}

Test(problems, a_sound_model_is_drawn_as_without_the_overlay)
{
    char t[1024];
    cube_text(t, sizeof t, 6, -1, 0);
    Scene s;
    checked_scene(&s, t);
    FrameBufs a, b;
    Image ia, ib;
    frame(&s, 0, 0, &a, &ia);
    frame(&s, 1, 0, &b, &ib);
    size_t n = (size_t)a.w * a.h;
    cr_assert_eq(memcmp(a.ids, b.ids, n * sizeof *a.ids), 0, "the ids differ");
    cr_assert_eq(memcmp(ia.rgb, ib.rgb, 3 * n), 0, "the colours differ");
    frame_free(&a, &ia);
    frame_free(&b, &ib);
    scene_free(&s);
}

Test(problems, the_holes_edges_are_drawn_in_their_colour)
{
    char t[1024];
    cube_text(t, sizeof t, 5, -1, 0);
    Scene s;
    checked_scene(&s, t);
    FrameBufs a, b;
    Image ia, ib;
    frame(&s, 0, 0, &a, &ia);
    frame(&s, 1, 0, &b, &ib);
    uint8_t red[3];
    shade_mark_edge_colour(MARK_BOUNDARY, red);
    size_t n = (size_t)a.w * a.h, marked = 0;
    for (size_t i = 0; i < n; i++) {
        int obj;
        uint32_t k;
        if (scene_prim_of(&s, b.ids[i], &obj, &k) != PRIM_MARK) {
            /* elsewhere the same face shows, in the same colour */
            cr_assert_eq(a.ids[i], b.ids[i], "pixel %zu", i);
            cr_assert_eq(memcmp(&ia.rgb[3 * i], &ib.rgb[3 * i], 3), 0, "pixel %zu", i);
            continue;
        }
        cr_assert_eq(memcmp(&ib.rgb[3 * i], red, 3), 0, "pixel %zu of the hole's edge", i);
        marked++;
    }
    cr_assert_gt(marked, 40, "the hole's edges show (%zu pixels)", marked);
    /* without the overlay the marks' ids are never drawn */
    for (size_t i = 0; i < n; i++)
        cr_assert_lt(a.ids[i], (int32_t)s.nfaces);
    frame_free(&a, &ia);
    frame_free(&b, &ib);
    scene_free(&s);
}

Test(problems, parts_take_their_colours_and_flipped_faces_theirs)
{
    char t[1024];
    cube_text(t, sizeof t, 6, -1, 1);   /* inside out: every face marked */
    Scene s;
    checked_scene(&s, t);
    MarkColours mc = { 0 };
    cr_assert_eq(shade_mark_colours(&mc, &s, 1, NULL), 1);
    uint8_t blue[3], part0[3];
    shade_mark_face_colour(MARK_FLIPPED, blue);
    for (uint32_t f = 0; f < 6; f++)
        cr_assert_eq(memcmp(&mc.rgb[3 * f], blue, 3), 0, "face %u", f);
    cr_assert_eq(shade_mark_colours(&mc, &s, 2, NULL), 1);
    shade_part_colour(0, part0);
    for (uint32_t f = 0; f < 6; f++)
        cr_assert_eq(memcmp(&mc.rgb[3 * f], part0, 3), 0, "face %u", f);
    mark_colours_free(&mc);
    scene_free(&s);
    /* a sound cube under --problems keeps the scene's own colours */
    cube_text(t, sizeof t, 6, -1, 0);
    checked_scene(&s, t);
    cr_assert_eq(shade_mark_colours(&mc, &s, 1, NULL), 0);
    mark_colours_free(&mc);
    scene_free(&s);
}

Test(problems, every_algorithm_agrees_with_the_problems_drawn)
{
    char t[1024];
    cube_text(t, sizeof t, 5, 2, 0);
    const char *files[] = { NULL, "assets/star-pierce.obj", "assets/concave.obj" };
    for (int i = 0; i < 3; i++) {
        Scene s;
        char err[256];
        cr_assert_eq(i ? tl_scene_from_file(&s, files[i]) : tl_scene_from_text(&s, "open.obj", t), 0);
        cr_assert_eq(app_check_scene(&s, 1, NULL, err, sizeof err), 0, "%s", err);
        TlAgree a = { 0 };
        a.style.marks = 1;
        for (uint32_t seed = 1; seed <= 6; seed++) {
            tl_random_view(&s, seed, seed & 1);
            Viewport vp = { 120 + 7 * (int)seed, 80, 1.0f, 0 };
            a.style.line_width = 1 + (int)(seed % 3);
            for (int threads = 1; threads <= 2; threads++) {
                char msg[512];
                long n = tl_agree(&a, &s, &vp, threads, msg, sizeof msg);
                cr_assert_eq(n, 0, "%s view %u: %s", i ? files[i] : "open cube", seed, msg);
            }
        }
        tl_agree_free(&a);
        scene_free(&s);
    }
}

/* ==== A file read again ==== */

Test(problems, a_file_read_again_keeps_its_place)
{
    Options o;
    cli_defaults(&o);
    o.files[0] = "assets/cube.obj";
    o.files[1] = "assets/torus.obj";
    o.files[2] = "assets/concave.obj";
    o.nfiles = 3;
    char err[256];
    Scene s, part;
    cr_assert_eq(app_load_scene(&o, &s, err, sizeof err), 0, "%s", err);
    uint32_t gen = s.gen, cube = s.meshes[0].nfaces, concave = s.meshes[2].nfaces;
    cr_assert_eq(tl_scene_from_file(&part, "assets/knot.obj"), 0);
    uint32_t knot = part.nfaces;
    cr_assert_eq(scene_replace_file(&s, 1, &part, err, sizeof err), 0, "%s", err);
    cr_assert_eq(s.nmeshes, 3);
    cr_assert_str_eq(s.meshes[0].path, "assets/cube.obj");
    cr_assert_str_eq(s.meshes[1].path, "assets/knot.obj");
    cr_assert_str_eq(s.meshes[2].path, "assets/concave.obj");
    cr_assert_eq(s.nfaces, cube + knot + concave);
    cr_assert_eq(scene_object_file(&s, 1), 1);
    cr_assert_eq(s.objs[1].face_base, (int32_t)cube);
    cr_assert_neq(s.gen, gen);
    cr_assert_eq(part.nmeshes, 0, "the part went into the scene");
    scene_free(&s);
}

/* ==== Words and colours ==== */

Test(problems, the_verdict_in_a_word_or_two)
{
    CheckCounts c = { 0 };
    char buf[96];
    c.faces = 12;
    c.closed = c.watertight = 1;
    cr_assert_eq(check_verdict_short(&c, " · ", buf, sizeof buf), 0);
    cr_assert_str_eq(buf, "watertight");
    c.boundary_edges = 20;
    c.holes = 3;
    c.inconsistent_faces = 12;
    cr_assert_eq(check_verdict_short(&c, " · ", buf, sizeof buf), 2);
    cr_assert_str_eq(buf, "3 holes · 12 flipped");
    c = (CheckCounts){ 0 };
    c.faces = 1;
    c.holes = 1;
    c.boundary_edges = 3;
    c.self_intersections = 1;
    check_verdict_short(&c, ", ", buf, sizeof buf);
    cr_assert_str_eq(buf, "1 hole, 1 crossing");
    /* the crossing test stopped on its budget: a lower bound, a problem
     * even when it found none */
    c = (CheckCounts){ 0 };
    c.faces = 40000;
    c.closed = c.watertight = 1;
    c.intersections_stopped = 1;
    cr_assert_eq(check_verdict_short(&c, ", ", buf, sizeof buf), 1);
    cr_assert_str_eq(buf, "0+ crossing");
}

Test(problems, part_colours_differ_and_stay_off_black_and_white)
{
    uint8_t c[24][3];
    for (uint32_t i = 0; i < 24; i++) {
        shade_part_colour(i, c[i]);
        float l = backdrop_lightness(c[i]);
        cr_expect(l > 0.5f && l < 0.9f, "part %u: lightness %g", i, l);
        for (uint32_t j = 0; j < i; j++)
            cr_expect(memcmp(c[i], c[j], 3) != 0, "parts %u and %u share a colour", i, j);
    }
}

/* ==== --watch's events (watch.c) ==== */

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f, "%s", path);
    fputs(text, f);
    cr_assert_eq(fclose(f), 0);
}

/* The times are given, not read: a change is due WATCH_SETTLE_MS (0.1 s)
 * after the last event of its name. */
Test(watch, a_rename_over_the_file_and_a_write_in_place_are_changes)
{
    char dir[] = "/tmp/zv-watch-XXXXXX", a[64], b[64], tmp[64], other[64];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(a, sizeof a, "%s/a.obj", dir);
    snprintf(b, sizeof b, "%s/b.obj", dir);
    snprintf(tmp, sizeof tmp, "%s/.a.obj.tmp", dir);
    snprintf(other, sizeof other, "%s/c.obj", dir);
    write_file(a, "v 0 0 0\n");
    write_file(b, "v 0 0 0\n");
    char err[160];
    Watch *w = watch_start(err, sizeof err);
    cr_assert_not_null(w, "%s", err);
    const char *files[2] = { a, b };
    watch_files(w, files, 2);
    cr_assert_eq(watch_due(w, 0), -1, "nothing changed yet");
    /* an exporter's way: a temporary file renamed over a.obj */
    write_file(tmp, "v 1 1 1\n");
    cr_assert_eq(rename(tmp, a), 0);
    cr_assert_eq(watch_due(w, 1000), -1, "not before it settled");
    cr_assert_eq(watch_due(w, 1099), -1);
    cr_assert_eq(watch_due(w, 1100), 0, "a.obj, once it settled");
    cr_assert_eq(watch_due(w, 5000), -1, "once");
    /* a file of no interest changes nothing; b.obj written in place does */
    write_file(other, "v 2 2 2\n");
    cr_assert_eq(watch_due(w, 6000), -1);
    cr_assert_eq(watch_due(w, 7000), -1);
    write_file(b, "v 3 3 3\n");
    cr_assert_eq(watch_due(w, 8000), -1);
    cr_assert_eq(watch_due(w, 8200), 1, "b.obj");
    /* a change met while a load runs comes back later */
    watch_again(w, 0, 9000);
    cr_assert_eq(watch_due(w, 9050), -1);
    cr_assert_eq(watch_due(w, 9100), 0);
    watch_free(w);
    unlink(a);
    unlink(b);
    unlink(other);
    rmdir(dir);
}
