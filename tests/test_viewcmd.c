/* test_viewcmd.c: the command line written for a view gives that view
 * back: parsed and loaded, the same camera, placements and picture. */

#define _DEFAULT_SOURCE          /* mkstemps */

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "writers.h"

/* Split a command line as a POSIX shell would for our quoting: plain
 * words and '...' (with '\'' for a quote). Returns argc. */
static int split(char *line, char **argv, int max)
{
    int n = 0;
    char *p = line, *w = line;
    while (*p && n < max) {
        while (*p == ' ')
            p++;
        if (!*p)
            break;
        argv[n++] = w;
        while (*p && *p != ' ') {
            if (*p == '\'') {
                p++;
                while (*p && *p != '\'')
                    *w++ = *p++;
                if (*p)
                    p++;
            } else if (*p == '\\' && p[1]) {
                *w++ = p[1];
                p += 2;
            } else {
                *w++ = *p++;
            }
        }
        if (*p)
            p++;
        *w++ = 0;
    }
    return n;
}

static void load(Options *o, Scene *s)
{
    char err[512];
    cr_assert_eq(app_load_scene(o, s, err, sizeof err), 0, "%s", err);
}

static void render_ids(Scene *s, int cull, const SectionPlane *planes, int nplanes, int32_t *out)
{
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, s, hsr_find("zbuffer"), 1), 0);
    memcpy(p.planes, planes, (size_t)nplanes * sizeof *planes);
    p.nplanes = nplanes;
    cr_assert_eq(pipeline_render(&p, 160, 96, 1.0f, cull, 0), 0);
    memcpy(out, p.fb.ids, 160 * 96 * sizeof *out);
    pipeline_free(&p);
}

static void round_trip(int persp)
{
    Options o;
    cli_defaults(&o);
    o.files[0] = "assets/scene.obj";
    o.files[1] = "assets/torus.obj";
    o.nfiles = 2;
    Scene s;
    load(&o, &s);
    cr_assert_geq(s.nobjs, 3);
    /* a session in the viewer: turn, refit from there, turn on, zoom,
     * pan, move, turn and scale objects, change the light */
    s.cam.persp = persp;
    s.cam.fov_deg = 47;
    s.cam.yaw = 0.7f;
    s.cam.pitch = -0.3f;
    scene_fit(&s);
    s.cam.yaw = 1.234567f;
    s.cam.pitch = 0.456f;
    s.cam.roll = -0.1f;
    s.cam.zoom = 1.15f * 1.15f * 1.15f;
    s.cam.pan = v3(0.05f / s.cam.zoom, -0.15f, 0);
    s.objs[1].offset = v3_add(s.objs[1].home, v3(0.25f, -0.5f, 0.125f));
    s.objs[2].yaw = 0.3f;
    s.objs[2].roll = -1.2f;
    s.objs[0].scale = s.objs[0].home_scale * 1.15f;
    light_set(&s.light, 20, 10, 0.3f);
    /* a vertex, an edge's midpoint on the second object, a face's centre */
    MeasureMarks mk = { .n = 3,
                        .mark = { { .a = 6 },
                                  { .obj = 1, .kind = MEASURE_EDGE, .a = 2, .b = 7 },
                                  { .kind = MEASURE_FACE, .a = 11 } } };
    /* the cut: an axis plane, one that keeps what lies above it (its
     * words start with '-'), a slanted one */
    SectionPlane planes[3];
    char err[160];
    const char *words[3] = { "z=0.25", "-x=-0.5", "0,0.1,0:0,1,0.25" };
    for (int i = 0; i < 3; i++)
        cr_assert_eq(section_parse(words[i], &planes[i], err, sizeof err), 0, "%s", err);
    ViewSettings v = { MODE_HALF, SHADE_SMOOTH, 45, 1, 9, "span", 1, 1, 3, 2, 1, 0, 0, 1, 20, 1, &mk, planes, 3 };
    char cmd[4096];
    cr_assert_eq(view_command(cmd, sizeof cmd, &o, &s, &v), 0);
    cr_assert(strncmp(cmd, "zview ", 6) == 0, "%s", cmd);
    cr_expect(strstr(cmd, " --marks v7,2:e3-8,f12 "), "the marks in words: %s", cmd);
    cr_expect(strstr(cmd, " --section z=0.25 --section=-x=-0.5 --section 0,0.1,0:0,1,0.25 "), "the planes: %s", cmd);

    char *argv[128];
    int argc = split(cmd, argv, 128);
    Options o2;
    cr_assert_eq(cli_parse(argc, argv, &o2, err, sizeof err), 0, "%s: %s", err, cmd);
    cr_assert_eq(o2.nsections, 3, "%s", cmd);
    for (int i = 0; i < 3; i++)
        cr_expect(memcmp(o2.section[i].q, planes[i].q, sizeof planes[i].q) == 0 &&
                      memcmp(o2.section[i].n, planes[i].n, sizeof planes[i].n) == 0 && o2.section[i].axis == planes[i].axis,
                  "plane %d comes back: %s", i, cmd);
    cr_expect_eq(o2.mode, MODE_HALF);
    cr_expect_eq(o2.shade, SHADE_SMOOTH);
    cr_expect_eq(o2.crease, 45);
    cr_expect(o2.cull);
    cr_expect_eq(o2.samples, 9);
    cr_expect_str_eq(o2.algo, "span");
    cr_expect(o2.edges, "outlines");
    cr_expect(o2.wireframe, "wireframe");
    cr_expect_eq(o2.point_size, 3);
    cr_expect_eq(o2.line_width, 2);
    cr_expect(o2.no_textures, "textures hidden");
    cr_expect(o2.overhang && o2.overhang_deg == 20, "overhangs past 20 degrees: %s", cmd);
    cr_expect(o2.thickness, "thickness");
    cr_expect(o2.marks.n == 3 && memcmp(o2.marks.mark, mk.mark, sizeof mk.mark) == 0, "the marks: %s", cmd);
    cr_assert_eq(o2.nfiles, 2);
    Scene t;
    load(&o2, &t);
    const Camera *a = &s.cam, *b = &t.cam;
    cr_expect(a->yaw == b->yaw && a->pitch == b->pitch && a->roll == b->roll, "turn");
    cr_expect(a->fit_yaw == b->fit_yaw && a->fit_pitch == b->fit_pitch, "fit turn");
    cr_expect(memcmp(&a->centre, &b->centre, sizeof a->centre) == 0, "fitted centre");
    cr_expect(memcmp(&a->fit_half, &b->fit_half, sizeof a->fit_half) == 0, "fitted extents");
    cr_expect(a->radius == b->radius && a->zoom == b->zoom, "radius, zoom");
    cr_expect(a->pan.x == b->pan.x && a->pan.y == b->pan.y, "pan");
    cr_expect(a->persp == b->persp && (!persp || a->fov_deg == b->fov_deg), "projection");
    cr_expect(s.light.dir.x == t.light.dir.x && s.light.ambient == t.light.ambient, "light");
    for (int i = 0; i < s.nobjs; i++) {
        const Object *p = &s.objs[i], *q = &t.objs[i];
        cr_expect(p->yaw == q->yaw && p->pitch == q->pitch && p->roll == q->roll, "object %d turn", i);
        cr_expect(memcmp(&p->offset, &q->offset, sizeof p->offset) == 0, "object %d place: %s", i, cmd);
        cr_expect(p->scale == q->scale, "object %d scale: %s", i, cmd);
    }
    int32_t *ia = malloc(160 * 96 * 4), *ib = malloc(160 * 96 * 4), *ic = malloc(160 * 96 * 4);
    render_ids(&s, 1, planes, 3, ia);
    render_ids(&t, 1, o2.section, o2.nsections, ib);
    render_ids(&s, 1, planes, 0, ic);
    cr_expect_eq(memcmp(ia, ib, 160 * 96 * 4), 0, "the same picture from: %s", cmd);
    cr_expect_neq(memcmp(ia, ic, 160 * 96 * 4), 0, "the cut shows in the picture");
    free(ia);
    free(ib);
    free(ic);
    scene_free(&s);
    scene_free(&t);
}

Test(viewcmd, orthographic_view_comes_back)
{
    round_trip(0);
}

Test(viewcmd, perspective_view_comes_back)
{
    round_trip(1);
}

Test(viewcmd, defaults_are_left_out_and_odd_file_names_quoted)
{
    Options o;
    cli_defaults(&o);
    o.files[0] = "it's here.obj";
    o.nfiles = 1;
    Scene s;
    memset(&s, 0, sizeof s);
    s.cam.zoom = 1;
    light_set(&s.light, LIGHT_YAW, LIGHT_PITCH, LIGHT_AMBIENT);
    ViewSettings v = { -1, SHADE_LAMBERT, SHADE_CREASE_DEFAULT, 0, 0, NULL, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, NULL, NULL, 0 };
    char cmd[512];
    cr_assert_eq(view_command(cmd, sizeof cmd, &o, &s, &v), 0);
    cr_expect_str_eq(cmd, "zview 'it'\\''s here.obj' --yaw 0 --pitch 0");
    cr_expect_eq(view_command(cmd, 10, &o, &s, &v), -1, "too small a buffer is reported");
    /* issue 28: a name with controls is printed with the command: $'...'
     * with its bytes as \xNN, which bash and zsh turn back into the name
     * (test_hostile.sh runs it), and no ESC reaches the terminal */
    o.files[0] = "e\x1b]52;c;aGk=\x07v'il\\\xff.obj";
    cr_assert_eq(view_command(cmd, sizeof cmd, &o, &s, &v), 0);
    cr_expect_str_eq(cmd, "zview $'e\\x1b]52;c;aGk=\\x07v\\'il\\\\\\xff.obj' --yaw 0 --pitch 0");
}

/* The shortest numbers that give the view back: a turn of -25 degrees is
 * "-25", not "-25.0000019"; a zoom of 1.15 "1.15", not "1.14999998". */
Test(viewcmd, numbers_are_the_shortest_that_come_back)
{
    Options o;
    cli_defaults(&o);
    o.files[0] = "m.obj";
    o.nfiles = 1;
    Scene s;
    memset(&s, 0, sizeof s);
    s.cam.yaw = deg2rad(-25);
    s.cam.pitch = deg2rad(30);
    s.cam.fit_yaw = s.cam.yaw;
    s.cam.fit_pitch = s.cam.pitch;
    s.cam.zoom = 1.15f;
    s.cam.pan = v3(0.1f, -0.3f, 0);
    light_set(&s.light, -34.5f, LIGHT_PITCH, 0.3f);
    ViewSettings v = { -1, SHADE_LAMBERT, SHADE_CREASE_DEFAULT, 0, 0, NULL, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, NULL, NULL, 0 };
    char cmd[512];
    cr_assert_eq(view_command(cmd, sizeof cmd, &o, &s, &v), 0);
    cr_expect_str_eq(cmd, "zview m.obj --yaw -25 --pitch 30 --zoom 1.15 --pan 0.1,-0.3 --light -34.5,37 --ambient 0.3");
}

/* A file whose name starts with '-' comes first as ./-name, so that no
 * option parser takes it for an option and options can follow it. */
Test(viewcmd, files_come_first_and_a_dash_name_is_a_path)
{
    Options o;
    cli_defaults(&o);
    o.files[0] = "-odd.obj";
    o.files[1] = "-";
    o.nfiles = 2;
    Scene s;
    memset(&s, 0, sizeof s);
    s.cam.zoom = 1;
    light_set(&s.light, LIGHT_YAW, LIGHT_PITCH, LIGHT_AMBIENT);
    ViewSettings v = { .mode = -1, .shade = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT };
    char cmd[512];
    cr_assert_eq(view_command(cmd, sizeof cmd, &o, &s, &v), 0);
    cr_expect_str_eq(cmd, "zview ./-odd.obj - --yaw 0 --pitch 0");
    /* parsed back, with an option appended */
    strcat(cmd, " -o out.png");
    char *argv[16];
    int argc = split(cmd, argv, 16);
    Options o2;
    char err[256];
    cr_assert_eq(cli_parse(argc, argv, &o2, err, sizeof err), 0, "%s", err);
    cr_expect_eq(o2.nfiles, 2);
    cr_expect_str_eq(o2.files[0], "./-odd.obj");
    cr_expect_str_eq(o2.files[1], "-");
    cr_expect_str_eq(o2.out, "out.png");
}

/* The view command of a scene, parsed and loaded again. */
static void reload(const Options *o, Scene *s, Scene *t, char *cmd, size_t len)
{
    ViewSettings v = { .mode = -1, .shade = SHADE_LAMBERT, .crease = SHADE_CREASE_DEFAULT };
    cr_assert_eq(view_command(cmd, len, o, s, &v), 0);
    char line[4096], *argv[64];
    snprintf(line, sizeof line, "%s", cmd);
    int argc = split(line, argv, 64);
    Options o2;
    char err[256];
    cr_assert_eq(cli_parse(argc, argv, &o2, err, sizeof err), 0, "%s: %s", err, cmd);
    load(&o2, t);
}

/* Files stand as their formats say (an STL z-up, an OBJ y-up) with no
 * --up written; an axis set for all (U, --up) is written and comes back. */
Test(viewcmd, up_axes_come_back)
{
    Mesh m;
    char err[256];
    cr_assert_eq(mesh_load(&m, "assets/knot.obj", err, sizeof err), 0, "%s", err);
    size_t n;
    char *stl = w_stl_binary(&m, &n);
    mesh_free(&m);
    char path[] = "/tmp/zview-viewcmd-XXXXXX.stl";
    int fd = mkstemps(path, 4);
    cr_assert_geq(fd, 0);
    close(fd);
    cr_assert_eq(w_save(path, stl, n), 0);
    free(stl);
    Options o;
    cli_defaults(&o);
    o.files[0] = path;
    o.files[1] = "assets/torus.obj";
    o.nfiles = 2;
    Scene s, t;
    load(&o, &s);
    cr_assert_eq(s.objs[0].up, UP_Z, "the STL stands z-up");
    cr_assert_eq(s.objs[s.nobjs - 1].up, UP_Y, "the OBJ y-up");
    char cmd[4096];
    reload(&o, &s, &t, cmd, sizeof cmd);
    cr_expect_null(strstr(cmd, "--up"), "each file's own axis needs no --up: %s", cmd);
    for (int i = 0; i < s.nobjs; i++)
        cr_expect_eq(t.objs[i].up, s.objs[i].up, "object %d: %s", i, cmd);
    cr_expect(memcmp(&s.cam.fit_half, &t.cam.fit_half, sizeof s.cam.fit_half) == 0, "the same fit: %s", cmd);
    scene_free(&t);
    scene_set_up(&s, UP_X);
    reload(&o, &s, &t, cmd, sizeof cmd);
    const char *up = strstr(cmd, " --up x");
    cr_expect(up && (up[7] == ' ' || up[7] == 0), "an axis set for all is written: %s", cmd);
    for (int i = 0; i < t.nobjs; i++)
        cr_expect_eq(t.objs[i].up, UP_X, "object %d: %s", i, cmd);
    scene_free(&t);
    scene_free(&s);
    unlink(path);
}
