/* test_section.c: section planes (section.h) against known answers:
 * the unit cube cut at z = 0.5 (area 1, perimeter 4, one loop), the
 * bundled torus cut through its hole (two 64-gons: their area and
 * perimeter from the tube's radius), an open box (an open chain, its
 * two ends where the missing face was), the exact side of points on
 * and next to a plane, the parse and the text back; and in pictures:
 * a corner cut-away seen from above shows the cap exactly where the
 * top face was taken away, and the five algorithms give the same
 * buffers with planes on (random views and planes, one and two
 * threads). */

#define _DEFAULT_SOURCE
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "section.h"
#include "testlib.h"

/* The cube [0, 1]^3 as 6 quads wound counter-clockwise from outside;
 * without the x = 1 face when open. */
static void cube(Scene *s, int open)
{
    char text[1024];
    snprintf(text, sizeof text,
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 1 5 8 4\n%s",
             open ? "" : "f 2 3 7 6\n");
    cr_assert_eq(tl_scene_from_text(s, "cube.obj", text), 0);
}

static SectionPlane plane(const char *text)
{
    SectionPlane p;
    char err[160];
    cr_assert_eq(section_parse(text, &p, err, sizeof err), 0, "%s: %s", text, err);
    return p;
}

/* The section of the scene's object 0 by planes[i]. */
static SectionFigures figures(const Scene *s, const SectionPlane *planes, int np, int i, SectionClip *cap)
{
    const Object *o = &s->objs[0];
    uint8_t *mask = malloc(o->mesh->nverts + 1);
    cr_assert_not_null(mask);
    section_masks(planes, np, o->mesh->pos, o->mesh->nverts, mask);
    SectionPolys in = { o->mesh->pos, s->poly_start, s->poly_corner, o->poly_first, o->poly_count, mask };
    SectionWork *w = NULL;
    SectionFigures f;
    cr_assert_eq(section_loops(&in, planes, np, i, &w, &f, cap), 0);
    section_work_free(&w);
    free(mask);
    return f;
}

Test(section, parse_and_text_back)
{
    SectionPlane p = plane("z=0.5");
    cr_assert(p.axis == 2 && p.q[2] == 0.5 && p.n[2] == 1 && p.n[0] == 0);
    p = plane("-x=-2");
    cr_assert(p.axis == 0 && p.q[0] == -2 && p.n[0] == -1);
    p = plane("1,2,3:0,0.5,-1");
    cr_assert(p.axis == -1 && p.q[1] == 2 && p.n[1] == 0.5 && p.n[2] == -1);
    const char *good[] = { "z=0.5", "-x=-2", "y=1e-07", "1,2,3:0,0.5,-1", "0.1,0,0:1,1,1" };
    for (size_t k = 0; k < sizeof good / sizeof *good; k++) {
        char t[SECTION_TEXT];
        p = plane(good[k]);
        section_text(&p, t, sizeof t);
        cr_assert_str_eq(t, good[k]);
    }
    const char *bad[] = { "w=1", "z=", "z=abc", "zz=1", "1,2:0,0,1", "0,0,0:0,0,0", "z=1e99", "0,0,0:1,1" };
    char err[160];
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
        cr_assert_eq(section_parse(bad[k], &p, err, sizeof err), -1, "%s was taken", bad[k]);
}

/* The side of a point is exact: points on a slanted plane are on it,
 * and the float next to one is on the side it lies. */
Test(section, side_is_exact)
{
    SectionPlane p = plane("0,0,0.1:1,1,1");
    /* 0.1 as a double is not 0.1f: the float is above it by a little */
    float on[3] = { 0, 0, 0.1f };
    int want = (double)0.1f > 0.1 ? 1 : -1;
    cr_assert_eq(section_side(&p, on), want);
    float a[3] = { 0.25f, -0.25f, 0 };
    SectionPlane o = plane("0,0,0:1,1,1");
    cr_assert_eq(section_side(&o, a), 0);
    /* the plane's own point: every term 0, so is the bound of its error */
    cr_assert_eq(section_side(&o, (float[3]){ 0, 0, 0 }), 0);
    /* a sum that cancels in double: 1e8 + 1 - 1e8 on a normal 1, 1e-8 */
    SectionPlane big = plane("0,0,0:1,1e-08,0");
    float b[3] = { -1e-8f, 1, 0 };
    double exact = (double)-1e-8f + 1e-8;   /* both exact in double: the sign of their sum */
    cr_assert_eq(section_side(&big, b), exact > 0 ? 1 : exact < 0 ? -1 : 0);
    float c[3] = { 0, 0, 0.5f };
    cr_assert_eq(section_side(&o, c), 1);
    cr_assert_eq(section_side(&(SectionPlane){ { 0, 0, 0 }, { 0, 0, -1 }, 2 }, c), -1);
}

Test(section, unit_cube_at_half)
{
    Scene s;
    cube(&s, 0);
    const char *planes[] = { "z=0.5", "x=0.5", "0.5,0.5,0.5:0,1,0", "-y=0.5" };
    for (int k = 0; k < 4; k++) {
        SectionPlane p = plane(planes[k]);
        SectionClip cap = { 0 };
        SectionFigures f = figures(&s, &p, 1, 0, &cap);
        cr_assert_float_eq(f.area, 1.0, 1e-12, "%s: area %.17g", planes[k], f.area);
        cr_assert_float_eq(f.perimeter, 4.0, 1e-12, "%s", planes[k]);
        cr_assert_eq(f.loops, 1, "%s: %u loops", planes[k], f.loops);
        cr_assert_eq(f.chains, 0);
        cr_assert_geq(cap.npts, 4);
        section_clip_free(&cap);
    }
    /* through no face: nothing */
    SectionPlane p = plane("z=2");
    SectionFigures f = figures(&s, &p, 1, 0, NULL);
    cr_assert(f.loops == 0 && f.area == 0 && f.perimeter == 0);
    scene_free(&s);
}

/* The torus of assets/ (ring radius 1, tube 0.4, 96 x 64 cells, turned
 * about x): the plane x = 0 holds its axis and cuts the tube twice,
 * through vertices, in two regular 64-gons of radius 0.4. */
Test(section, torus_through_its_hole)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/torus.obj"), 0);
    SectionPlane p = plane("x=0");
    SectionFigures f = figures(&s, &p, 1, 0, NULL);
    double r = 0.4, gon_area = 0.5 * 64 * r * r * sin(2 * M_PI / 64), gon_len = 64 * 2 * r * sin(M_PI / 64);
    cr_assert_eq(f.loops, 2, "%u loops", f.loops);
    cr_assert_eq(f.chains, 0);
    cr_assert_float_eq(f.area, 2 * gon_area, 1e-5, "area %.9g, want %.9g", f.area, 2 * gon_area);
    cr_assert_float_eq(f.perimeter, 2 * gon_len, 1e-5, "perimeter %.9g", f.perimeter);
    /* and not through vertices: still two loops, near the circles' figures */
    p = plane("x=0.013");
    f = figures(&s, &p, 1, 0, NULL);
    cr_assert_eq(f.loops, 2);
    cr_assert_float_eq(f.area, 2 * M_PI * r * r, 0.02);
    scene_free(&s);
}

Test(section, open_box_reports_its_open_chain)
{
    Scene s;
    cube(&s, 1);
    SectionPlane p = plane("z=0.5");
    SectionClip cap = { 0 };
    SectionFigures f = figures(&s, &p, 1, 0, &cap);
    cr_assert_eq(f.loops, 0);
    cr_assert_eq(f.chains, 1);
    cr_assert_eq(f.nends, 1);
    cr_assert_float_eq(f.perimeter, 3.0, 1e-12);
    cr_assert_eq(f.area, 0);
    cr_assert_eq(cap.npts, 0, "an open chain is not filled");
    /* its ends are where the missing face x = 1 was, at z = 0.5 */
    for (int e = 0; e < 2; e++) {
        cr_assert_eq(f.ends[0][e][0], 1.0f);
        cr_assert_eq(f.ends[0][e][2], 0.5f);
    }
    cr_assert_neq(f.ends[0][0][1], f.ends[0][1][1]);
    section_clip_free(&cap);
    scene_free(&s);
}

/* Render the scene cut by planes with algo; the cut stays in *c. */
static void render_cut(Scene *s, SectionCut *c, const SectionPlane *planes, int np, const HsrAlgo *algo,
                       int threads, int w, int h, int cull, ScreenPolys *sp, FrameBufs *fb)
{
    char err[160];
    cr_assert_eq(section_cut_update(c, s, planes, np, err, sizeof err), 0);
    sp->cut = c;
    HsrStats st;
    cr_assert_eq(tl_render(s, algo, threads, w, h, cull, sp, fb, &st), 0);
}

/* From straight above, a corner cut-away (z > 0.5 and x > 0.5 go) shows
 * the cap of z = 0.5 where the top face's half x > 0.5 was, and the top
 * face's other half: the same number of pixels, and nothing else. */
Test(section, corner_cut_from_above)
{
    Scene s;
    cube(&s, 0);
    TlView v = { 0 };
    v.zoom = 1;
    tl_set_view(&s, &v);     /* looking down -z: the top face z = 1 faces the viewer */
    SectionPlane planes[2] = { plane("z=0.5"), plane("x=0.5") };
    SectionCut c = { 0 };
    ScreenPolys sp = { 0 };
    FrameBufs fb = { 0 };
    render_cut(&s, &c, planes, 2, &hsr_zbuffer, 1, 200, 200, 0, &sp, &fb);
    int64_t cap0 = section_cap_id0(&s);
    long top = 0, capz = 0, other = 0;
    for (int i = 0; i < fb.w * fb.h; i++) {
        int32_t id = fb.ids[i];
        if (id == 1)
            top++;
        else if (id == cap0)
            capz++;
        else if (id >= 0)
            other++;
    }
    cr_assert_gt(top, 1000);
    cr_assert_eq(other, 0, "%ld pixels of other faces", other);
    cr_assert(labs(top - capz) <= 200 / 50 * 200 / 10, "top %ld, cap %ld", top, capz);
    /* without the cut: the top face alone, both halves */
    render_cut(&s, &c, planes, 0, &hsr_zbuffer, 1, 200, 200, 0, &sp, &fb);
    long whole = 0;
    for (int i = 0; i < fb.w * fb.h; i++)
        whole += fb.ids[i] == 1;
    cr_assert_eq(whole, top + capz);
    section_cut_free(&c);
    screen_free(&sp);
    fbuf_free(&fb);
    scene_free(&s);
}

/* Every algorithm gives the z-buffer's buffers with section planes on:
 * seeded views and planes (one to three, axis and slanted), ortho and
 * perspective, culling on and off, one and two threads. */
Test(section, five_algorithms_agree)
{
    const char *files[] = { "assets/torus.obj", "assets/knot.obj", "assets/concave.obj", "assets/cube.obj" };
    const char *sets[][3] = { { "z=0", NULL, NULL },
                              { "x=0.1", "y=-0.05", NULL },
                              { "0.1,0.2,0:1,2,3", "-z=0", "0,0,0:-1,1,0.5" },
                              { "0,0,0:0.3,-1,0.2", NULL, NULL } };
    ScreenPolys sp = { 0 };
    FrameBufs ref = { 0 }, fb = { 0 };
    SectionCut c = { 0 };
    int frames = 0;
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        Scene s;
        cr_assert_eq(tl_scene_from_file(&s, files[f]), 0);
        for (int k = 0; k < 4; k++) {
            SectionPlane pl[3];
            int np = 0;
            for (int i = 0; i < 3 && sets[k][i]; i++)
                pl[np++] = plane(sets[k][i]);
            for (int view = 0; view < 4; view++) {
                tl_random_view(&s, (uint32_t)(f * 16 + k * 4 + view), view & 1);
                int cull = view >> 1 & 1;
                render_cut(&s, &c, pl, np, &hsr_zbuffer, 1, 160, 96, cull, &sp, &ref);
                for (int a = 0; a < hsr_nalgos; a++)
                    for (int t = 1; t <= 2; t++) {
                        render_cut(&s, &c, pl, np, hsr_algos[a], t, 160, 96, cull, &sp, &fb);
                        int fx, fy;
                        long n = tl_diff(&ref, &fb, &fx, &fy);
                        cr_assert_eq(n, 0, "%s planes %d view %d: %s on %d threads differs in %ld pixels, first (%d,%d)",
                                     files[f], k, view, hsr_algos[a]->name, t, n, fx, fy);
                        frames++;
                    }
            }
        }
        scene_free(&s);
    }
    cr_assert_gt(frames, 100);
    section_cut_free(&c);
    screen_free(&sp);
    fbuf_free(&ref);
    fbuf_free(&fb);
}

/* Points and lines are cut too: a line from x = -1 to 1 and a point at
 * each end, cut at x = 0.25, seen from the front: the line's samples
 * stop a quarter of the way past the middle, the point at x = 1 is gone. */
Test(section, points_and_lines_are_cut)
{
    Scene s;
    cr_assert_eq(tl_scene_from_text(&s, "line.obj", "v -1 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 1\np 2\np 3\n"), 0);
    TlView v = { 0 };
    v.zoom = 1;
    tl_set_view(&s, &v);
    SectionPlane pl = plane("x=0.25");
    SectionCut c = { 0 };
    ScreenPolys sp = { 0 };
    FrameBufs fb = { 0 };
    int32_t seg = -1, pt_right = -1;
    for (int32_t id = (int32_t)s.nfaces; id < (int32_t)(s.nfaces + s.nprims); id++) {
        int obj;
        uint32_t k;
        PrimKind kind = scene_prim_of(&s, id, &obj, &k);
        if (kind == PRIM_SEG)
            seg = id;
        if (kind == PRIM_POINT && k == 1)
            pt_right = id;
    }
    cr_assert(seg >= 0 && pt_right >= 0);
    int xmax[2] = { -1, -1 }, right_seen[2] = { 0, 0 };
    for (int cut = 0; cut < 2; cut++) {
        render_cut(&s, &c, &pl, cut, &hsr_zbuffer, 1, 200, 100, 0, &sp, &fb);
        for (int y = 0; y < fb.h; y++)
            for (int x = 0; x < fb.w; x++) {
                int32_t id = fb.ids[y * fb.w + x];
                if (id == seg && x > xmax[cut])
                    xmax[cut] = x;
                right_seen[cut] |= id == pt_right;
            }
    }
    cr_assert(right_seen[0] && !right_seen[1], "the point at x = 1: seen %d uncut, %d cut", right_seen[0],
              right_seen[1]);
    /* the whole line spans [xl, xmax[0]] about the middle: cut, it ends
     * five eighths of the way across */
    int mid = fb.w / 2, want = mid + (xmax[0] - mid) / 4;
    cr_assert(abs(xmax[1] - want) <= 2, "the cut line ends at column %d, want about %d", xmax[1], want);
    section_cut_free(&c);
    screen_free(&sp);
    fbuf_free(&fb);
    scene_free(&s);
}

/* Two planes, x = 1 and y = 1, take the corner x > 1, y > 1 out of the
 * square 0..4 (z = 0): the kept part is the square split where each of
 * its four edges crosses a plane, (1 0) (4 1) (1 4) (0 1), back to its
 * first corner, then the removed corner's outline (section.h). */
Test(section, two_planes_split_every_edge_they_cross)
{
    SectionPlane pl[2];
    char err[128];
    cr_assert_eq(section_parse("x=1", &pl[0], err, sizeof err), 0, "%s", err);
    cr_assert_eq(section_parse("y=1", &pl[1], err, sizeof err), 0, "%s", err);
    const float sq[4][3] = { { 0, 0, 0 }, { 4, 0, 0 }, { 4, 4, 0 }, { 0, 4, 0 } };
    uint8_t masks[4];
    section_masks(pl, 2, &sq[0][0], 4, masks);
    cr_assert(masks[0] == 0 && masks[1] == 1 && masks[2] == 3 && masks[3] == 2);
    SectionClip c = { 0 };
    int n = section_clip_poly(pl, 2, &sq[0][0], masks, 4, &c);
    const float want[9][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 4, 0, 0 }, { 4, 1, 0 }, { 4, 4, 0 },
                               { 1, 4, 0 }, { 0, 4, 0 }, { 0, 1, 0 }, { 0, 0, 0 } };
    cr_assert_geq(n, 9 + 4, "the outline, its first corner again, and the removed corner: %d points", n);
    for (int k = 0; k < 9; k++)
        cr_assert(c.pts[3 * k] == want[k][0] && c.pts[3 * k + 1] == want[k][1] && c.pts[3 * k + 2] == want[k][2],
                  "point %d: (%g %g %g), not (%g %g %g)", k, c.pts[3 * k], c.pts[3 * k + 1], c.pts[3 * k + 2],
                  want[k][0], want[k][1], want[k][2]);
    section_clip_free(&c);
}
