/* test_check.c: meshcheck (src/check/), the analysis behind --check.
 *
 * Meshes with known answers, built here vertex by vertex: the unit cube
 * (volume 1, area 6, centre of mass at its middle), the cube with a face
 * missing, two cubes apart, touching at a corner or along an edge, or
 * crossing, flipped and inside-out windings, a fin, zero-area and
 * duplicate faces, a Moebius strip, a cube split along UV seams, unused
 * vertices. Then an independent reference written here (edges counted
 * by sorting, parts and holes by a union-find, the volume by the
 * divergence theorem about the origin) compared with meshcheck on the
 * bundled assets and, in the suite "models" (make test-models), on
 * ../shared/models; and the crossing pairs the BVH finds compared with
 * every pair tested, on any number of threads. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../src/check/check_internal.h"
#include "../src/check/exact.h"
#include "mesh.h"
#include "meshcheck.h"
#include "testlib.h"

/* ==== Building meshes ==== */

static Mesh M;
static MeshCheck C;
static char E[512];

static void teardown(void)
{
    meshcheck_free(&C);
    mesh_free(&M);
}
TestSuite(check, .fini = teardown);

static void start(void)
{
    cr_assert_eq(tl_mesh_init(&M, "t.obj"), 0);
}

static uint32_t vert(float x, float y, float z)
{
    cr_assert_eq(tl_mesh_vertex(&M, x, y, z), 0);
    return M.nverts - 1;
}

static void face(uint32_t n, const uint32_t *c)
{
    cr_assert_eq(tl_mesh_face(&M, c, n), 0);
}

static void tri(uint32_t a, uint32_t b, uint32_t c)
{
    face(3, (uint32_t[]){ a, b, c });
}

static void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    face(4, (uint32_t[]){ a, b, c, d });
}

/* The cube of testlib (tl_mesh_cube): its corners' first index; whole,
 * less face `skip` (-1 none), faces of mask `flip` turned, as triangles
 * when tris. */
static uint32_t cube_verts(float x, float y, float z, float s)
{
    uint32_t v;
    cr_assert_eq(tl_mesh_cube_verts(&M, x, y, z, s, &v), 0);
    return v;
}

static void cube_ex(float x, float y, float z, float s, int skip, unsigned flip, int tris)
{
    cr_assert_eq(tl_mesh_cube(&M, x, y, z, s, skip, flip, tris), 0);
}

static void cube(float x, float y, float z, float s)
{
    cube_ex(x, y, z, s, -1, 0, 0);
}

static void run_opts(int threads, int intersections)
{
    cr_assert_eq(tl_mesh_finish(&M), 0);
    CheckOpts o = { .threads = threads, .intersections = intersections, .detail = 1 };
    cr_assert_eq(meshcheck_run(&C, &M, &o, E, sizeof E), 0, "%s", E);
}

static const CheckCounts *run(void)
{
    run_opts(1, 1);
    return &C.file;
}

static char *verdict(const CheckCounts *c)
{
    static char buf[256];
    meshcheck_verdict(c, buf, sizeof buf);
    return buf;
}

#define NEAR(a, b) cr_assert(fabs((double)(a) - (double)(b)) < 1e-9, "%s = %.17g, wanted %.17g", #a, (double)(a), \
                             (double)(b))

/* Nothing at all wrong beyond what the caller asserts. */
static void assert_clean_topology(const CheckCounts *c)
{
    cr_assert_eq(c->boundary_edges, 0);
    cr_assert_eq(c->holes, 0);
    cr_assert_eq(c->nonmanifold_edges, 0);
    cr_assert_eq(c->nonmanifold_vertices, 0);
    cr_assert_eq(c->nonorientable, 0);
    cr_assert_eq(c->degenerate_faces, 0);
    cr_assert_eq(c->duplicate_faces, 0);
}

/* Closed, manifold and agreeing (degenerate faces aside). */
static void assert_manifold(const CheckCounts *c)
{
    cr_assert_eq(c->boundary_edges, 0);
    cr_assert_eq(c->holes, 0);
    cr_assert_eq(c->nonmanifold_edges, 0);
    cr_assert_eq(c->nonmanifold_vertices, 0);
    cr_assert_eq(c->nonorientable, 0);
    cr_assert_eq(c->inconsistent_faces, 0);
}

/* ==== Known answers ==== */

Test(check, unit_cube)
{
    start();
    cube(0, 0, 0, 1);
    const CheckCounts *c = run();
    assert_clean_topology(c);
    cr_assert_eq(c->faces, 6);
    cr_assert_eq(c->vertices, 8);
    cr_assert_eq(c->components, 1);
    cr_assert_eq(c->inconsistent_faces, 0);
    cr_assert_eq(c->unused_vertices, 0);
    cr_assert_eq(c->self_intersections, 0);
    cr_assert(c->intersections_tested);
    cr_assert(c->closed && c->watertight && c->has_volume && !c->inside_out);
    NEAR(c->area, 6);
    NEAR(c->volume, 1);
    for (int k = 0; k < 3; k++) {
        NEAR(c->centre[k], 0.5);
        cr_assert_eq(c->lo[k], 0);
        cr_assert_eq(c->hi[k], 1);
    }
    cr_assert(meshcheck_sound(c));
    cr_assert_str_eq(verdict(c), "sound");
    cr_assert_eq(meshcheck_problems(c, NULL, 0), 0);
    for (uint32_t f = 0; f < 6; f++) {
        cr_assert_eq(C.face_flags[f], 0, "face %u flags %#x", f, C.face_flags[f]);
        cr_assert_eq(C.face_part[f], 0);
    }
    /* the object's figures are the file's */
    cr_assert_eq(C.nobjs, 1);
    cr_assert_eq(memcmp(&C.objs[0].c, &C.file, sizeof C.file), 0);
}

Test(check, unit_cube_as_triangles_far_from_the_origin)
{
    start();
    cube_ex(1000, -2000, 500, 2, -1, 0, 1);
    const CheckCounts *c = run();
    assert_clean_topology(c);
    cr_assert_eq(c->faces, 12);
    cr_assert(c->watertight && meshcheck_sound(c));
    NEAR(c->area, 24);
    NEAR(c->volume, 8);
    NEAR(c->centre[0], 1001);
    NEAR(c->centre[1], -1999);
    NEAR(c->centre[2], 501);
}

Test(check, cube_missing_a_face)
{
    start();
    cube_ex(0, 0, 0, 1, 1, 0, 0);
    const CheckCounts *c = run();
    cr_assert_eq(c->boundary_edges, 4);
    cr_assert_eq(c->holes, 1);
    cr_assert_eq(c->nonmanifold_edges, 0);
    cr_assert_eq(c->inconsistent_faces, 0);
    cr_assert(!c->closed && !c->watertight && !c->has_volume && !c->inside_out);
    cr_assert_eq(c->volume, 0);
    NEAR(c->area, 5);
    cr_assert(!meshcheck_sound(c));
    cr_assert_str_eq(verdict(c), "1 hole (4 boundary edges)");
    /* the boundary edges are the missing top's, each once */
    cr_assert_eq(C.objs[0].c.boundary_edges, 4);
    int seen[4] = { 0 };
    for (int e = 0; e < 4; e++) {
        uint32_t a = C.objs[0].boundary[2 * e], b = C.objs[0].boundary[2 * e + 1];
        cr_assert(a >= 4 && a < 8 && b >= 4 && b < 8, "edge %u-%u is not the top's", a, b);
        cr_assert((a - 4 + 1) % 4 == b - 4 || (b - 4 + 1) % 4 == a - 4, "%u-%u is no side of the top", a, b);
        seen[(a - 4 + 1) % 4 == b - 4 ? a - 4 : b - 4]++;
    }
    for (int k = 0; k < 4; k++)
        cr_assert_eq(seen[k], 1);
    /* the four side faces are open, the bottom is not */
    cr_assert_eq(C.face_flags[0] & CHECK_OPEN, 0);
    for (uint32_t f = 1; f < 5; f++)
        cr_assert(C.face_flags[f] & CHECK_OPEN);
}

Test(check, open_box_with_two_holes)
{
    start();
    /* top and bottom both missing: a tube, two loops */
    uint32_t v = cube_verts(0, 0, 0, 1);
    for (int f = 2; f < 6; f++)
        quad(v + tl_cube_faces[f][0], v + tl_cube_faces[f][1], v + tl_cube_faces[f][2], v + tl_cube_faces[f][3]);
    const CheckCounts *c = run();
    cr_assert_eq(c->boundary_edges, 8);
    cr_assert_eq(c->holes, 2);
    cr_assert_eq(c->components, 1);
    cr_assert_str_eq(verdict(c), "2 holes (8 boundary edges)");
}

Test(check, two_separate_cubes_are_sound)
{
    start();
    cube(0, 0, 0, 1);
    cube(3, 0, 0, 2);
    const CheckCounts *c = run();
    assert_clean_topology(c);
    cr_assert_eq(c->components, 2);
    cr_assert_eq(c->self_intersections, 0);
    cr_assert(c->watertight && meshcheck_sound(c));
    NEAR(c->volume, 9);
    NEAR(c->area, 30);
    /* the centre of mass weighs the big cube eight times */
    NEAR(c->centre[0], (0.5 + 8 * 4.0) / 9);
    NEAR(c->centre[1], (0.5 + 8 * 1.0) / 9);
    for (uint32_t f = 0; f < 12; f++)
        cr_assert_eq(C.face_part[f], f / 6);
}

Test(check, one_flipped_face)
{
    start();
    cube_ex(0, 0, 0, 1, -1, 1u << 3, 0);
    const CheckCounts *c = run();
    assert_clean_topology(c);
    cr_assert_eq(c->inconsistent_faces, 1);
    cr_assert(!c->inside_out);
    cr_assert(c->watertight);
    /* the volume with the winding made to agree */
    NEAR(c->volume, 1);
    cr_assert_str_eq(verdict(c), "1 flipped face");
    for (uint32_t f = 0; f < 6; f++)
        cr_assert_eq(!!(C.face_flags[f] & CHECK_FLIPPED), f == 3, "face %u", f);
}

Test(check, fewest_flips_four_of_six_flipped_is_two_and_inside_out)
{
    start();
    /* flipping the other two is fewer: then the cube is inside out */
    cube_ex(0, 0, 0, 1, -1, 0x0f, 0);
    const CheckCounts *c = run();
    cr_assert_eq(c->inconsistent_faces, 2);
    cr_assert(c->inside_out);
    NEAR(c->volume, 1);
    for (uint32_t f = 0; f < 6; f++)
        cr_assert_eq(!!(C.face_flags[f] & CHECK_FLIPPED), f >= 4, "face %u", f);
    cr_assert_str_eq(verdict(c), "2 flipped faces, inside out");
}

Test(check, three_of_six_flipped_is_three_and_outward)
{
    start();
    /* a tie: the flip that leaves the volume positive */
    cube_ex(0, 0, 0, 1, -1, 0x15, 0);
    const CheckCounts *c = run();
    cr_assert_eq(c->inconsistent_faces, 3);
    cr_assert(!c->inside_out);
    NEAR(c->volume, 1);
    for (uint32_t f = 0; f < 6; f++)
        cr_assert_eq(!!(C.face_flags[f] & CHECK_FLIPPED), (0x15 >> f) & 1, "face %u", f);
}

Test(check, ties_settled_in_each_part_of_an_object)
{
    start();
    /* three cubes, one object: the second and third each a tie (three of
     * six faces flipped), each settled by its own volume */
    cube_ex(0, 0, 0, 1, -1, 0, 0);
    cube_ex(3, 0, 0, 1, -1, 0x15, 0);
    cube_ex(6, 0, 0, 1, -1, 0x2a, 0);
    const CheckCounts *c = run();
    cr_assert_eq(c->inconsistent_faces, 6);
    cr_assert(!c->inside_out);
    NEAR(c->volume, 3);
    for (uint32_t f = 0; f < 18; f++)
        cr_assert_eq(!!(C.face_flags[f] & CHECK_FLIPPED), f < 6 ? 0 : f < 12 ? (0x15 >> (f - 6)) & 1 : (0x2a >> (f - 12)) & 1,
                     "face %u", f);
}

Test(check, cube_inside_out)
{
    start();
    cube_ex(0, 0, 0, 1, -1, 0x3f, 1);
    const CheckCounts *c = run();
    assert_clean_topology(c);
    cr_assert_eq(c->inconsistent_faces, 0);
    cr_assert(c->inside_out && c->watertight && c->has_volume);
    NEAR(c->volume, 1);
    for (int k = 0; k < 3; k++)
        NEAR(c->centre[k], 0.5);
    cr_assert(!meshcheck_sound(c));
    cr_assert_str_eq(verdict(c), "inside out");
}

Test(check, fin_three_faces_on_one_edge)
{
    start();
    uint32_t a = vert(0, 0, 0), b = vert(0, 0, 1);
    uint32_t p = vert(1, 0, 0), q = vert(-1, 0, 0), r = vert(0, 1, 0);
    tri(a, b, p);
    tri(b, a, q);
    tri(a, b, r);
    const CheckCounts *c = run();
    cr_assert_eq(c->nonmanifold_edges, 1);
    cr_assert_eq(c->boundary_edges, 6);
    cr_assert_eq(c->components, 1);
    cr_assert(!c->watertight);
    /* holes are independent loops: the boundary a-p-b-q-a-r-b makes two */
    cr_assert_eq(c->holes, 2);
    cr_assert_str_eq(verdict(c), "2 holes (6 boundary edges), 1 non-manifold edge");
    cr_assert_eq(C.objs[0].c.nonmanifold_edges, 1);
    uint32_t e0 = C.objs[0].nm_edges[0], e1 = C.objs[0].nm_edges[1];
    cr_assert((e0 == a && e1 == b) || (e0 == b && e1 == a));
    for (uint32_t f = 0; f < 3; f++)
        cr_assert(C.face_flags[f] & CHECK_NONMANIFOLD);
}

Test(check, fin_on_a_closed_cube)
{
    start();
    cube(0, 0, 0, 1);
    /* a triangle hanging off the edge from corner 0 to corner 1 */
    tri(0, 1, vert(0.5f, -1, -1));
    const CheckCounts *c = run();
    cr_assert_eq(c->nonmanifold_edges, 1);
    cr_assert_eq(c->boundary_edges, 2);
    cr_assert_eq(c->holes, 0, "the fin's two open edges close no loop");
    cr_assert_eq(c->components, 1, "faces joined by a non-manifold edge are one part");
    cr_assert(!c->closed && !c->watertight);
}

Test(check, two_cubes_touching_at_one_vertex)
{
    start();
    cube(0, 0, 0, 1);
    cube(1, 1, 1, 1);
    const CheckCounts *c = run();
    cr_assert_eq(c->nonmanifold_vertices, 1);
    cr_assert_eq(c->nonmanifold_edges, 0);
    cr_assert_eq(c->boundary_edges, 0);
    cr_assert_eq(c->components, 2);
    cr_assert_eq(c->vertices, 15);
    cr_assert_eq(c->self_intersections, 0, "touching at a shared corner is no crossing");
    cr_assert(c->watertight);
    NEAR(c->volume, 2);
    cr_assert_str_eq(verdict(c), "1 non-manifold vertex");
    /* the vertex listed is at (1, 1, 1) */
    const float *p = M.pos + 3 * (size_t)C.objs[0].nm_verts[0];
    cr_assert(p[0] == 1 && p[1] == 1 && p[2] == 1);
}

Test(check, two_cubes_sharing_an_edge)
{
    start();
    cube(0, 0, 0, 1);
    cube(1, 1, 0, 1);
    const CheckCounts *c = run();
    cr_assert_eq(c->nonmanifold_edges, 1);
    cr_assert_eq(c->self_intersections, 0, "touching along a shared edge is no crossing");
    cr_assert_eq(c->boundary_edges, 0);
    cr_assert(c->closed && !c->watertight);
}

Test(check, cone_tips_touching_is_a_nonmanifold_vertex)
{
    start();
    /* two tetrahedra sharing their apex: a bow tie of fans at one point */
    uint32_t t = vert(0, 0, 0);
    uint32_t a = vert(1, 0, -1), b = vert(-1, 1, -1), d = vert(-1, -1, -1);
    uint32_t e = vert(1, 0, 1), f = vert(-1, 1, 1), g = vert(-1, -1, 1);
    tri(t, a, b);
    tri(t, b, d);
    tri(t, d, a);
    tri(a, d, b);
    tri(t, f, e);
    tri(t, g, f);
    tri(t, e, g);
    tri(e, f, g);
    const CheckCounts *c = run();
    cr_assert_eq(c->nonmanifold_vertices, 1);
    cr_assert_eq(c->nonmanifold_edges, 0);
    cr_assert_eq(c->boundary_edges, 0);
    cr_assert_eq(c->self_intersections, 0);
}

Test(check, corner_pressed_into_a_face_is_a_crossing)
{
    start();
    /* the rule: faces meeting anywhere but at the points they share
     * cross, touching included (a slicer would fuse them) */
    cube(0, 0, 0, 1);
    cube(0.25f, 0.25f, 1, 0.5f);
    const CheckCounts *c = run();
    cr_assert_gt(c->self_intersections, 0);
    cr_assert_eq(c->nonmanifold_vertices, 0);
}

Test(check, cubes_a_hair_apart_do_not_cross)
{
    start();
    cube(0, 0, 0, 1);
    cube(nextafterf(1, 2), 0, 0, 1);
    const CheckCounts *c = run();
    cr_assert_eq(c->self_intersections, 0);
    cr_assert(meshcheck_sound(c));
}

Test(check, two_intersecting_cubes)
{
    start();
    cube(0, 0, 0, 1);
    cube(0.5f, 0.5f, 0.5f, 1);
    const CheckCounts *c = run();
    assert_clean_topology(c);
    /* each of the first cube's faces x=1, y=1, z=1 crosses two of the
     * second's x=.5, y=.5, z=.5: the ones not parallel to it */
    cr_assert_eq(c->self_intersections, 6);
    cr_assert_eq(C.objs[0].npairs, 6);
    static const uint32_t want[6][2] = { { 1, 8 }, { 1, 10 }, { 3, 6 }, { 3, 10 }, { 5, 6 }, { 5, 8 } };
    for (int i = 0; i < 6; i++) {
        cr_assert_eq(C.objs[0].pairs[2 * i], want[i][0], "pair %d", i);
        cr_assert_eq(C.objs[0].pairs[2 * i + 1], want[i][1], "pair %d", i);
    }
    for (uint32_t f = 0; f < 12; f++)
        cr_assert_eq(!!(C.face_flags[f] & CHECK_INTERSECTS), f == 1 || f == 3 || f == 5 || f == 6 || f == 8 || f == 10,
                     "face %u", f);
    cr_assert_str_eq(verdict(c), "6 intersecting face pairs");
    cr_assert(c->watertight && !meshcheck_sound(c));
}

Test(check, intersections_not_tested_when_not_asked)
{
    start();
    cube(0, 0, 0, 1);
    cube(0.5f, 0.5f, 0.5f, 1);
    run_opts(1, 0);
    cr_assert_eq(C.file.self_intersections, 0);
    cr_assert(!C.file.intersections_tested);
}

Test(check, zero_area_faces)
{
    start();
    cube(0, 0, 0, 1);
    /* on one line: three points of the bottom edge, and a face of one
     * point repeated */
    uint32_t m = vert(0.5f, 0, 0);
    tri(0, m, 1);
    tri(2, 2, 2);
    const CheckCounts *c = run();
    cr_assert_eq(c->degenerate_faces, 2);
    NEAR(c->area, 6);
    cr_assert(C.face_flags[6] & CHECK_DEGENERATE);
    cr_assert(C.face_flags[7] & CHECK_DEGENERATE);
    for (uint32_t f = 0; f < 6; f++)
        cr_assert_eq(C.face_flags[f] & CHECK_DEGENERATE, 0);
    cr_assert(!meshcheck_sound(c));
    /* out of the topology: the cube is still one closed manifold part
     * (the dragon's 108 such faces had made 99 non-manifold edges, 9
     * non-manifold vertices and 9 parts more, which CGAL and the
     * slicers, setting them aside, do not report) */
    assert_manifold(c);
    cr_assert_eq(c->components, 1);
    cr_assert(c->watertight);
    cr_assert_eq(C.face_part[6], UINT32_MAX);
    cr_assert_eq(C.face_part[7], UINT32_MAX);
}

Test(check, degenerate_faces_on_an_edge_are_not_a_fin)
{
    start();
    cube(0, 0, 0, 1);
    /* (a, a, b) on the cube's edges 0-1 and 1-2, and (a, b, a): each
     * had made its edge one of three faces */
    tri(0, 0, 1);
    tri(1, 2, 1);
    tri(2, 2, 2);
    const CheckCounts *c = run();
    cr_assert_eq(c->degenerate_faces, 3);
    assert_manifold(c);
    cr_assert_eq(c->components, 1);
    cr_assert_eq(c->duplicate_faces, 0);
    char *v = verdict(c);
    cr_assert_str_eq(v, "3 degenerate faces");
}

Test(check, a_triangle_collapsed_to_two_points_is_not_watertight)
{
    start();
    uint32_t a = vert(0, 0, 0), b = vert(1, 0, 0);
    tri(a, b, a);
    const CheckCounts *c = run();
    cr_assert_eq(c->degenerate_faces, 1);
    cr_assert_eq(c->components, 0);
    cr_assert_eq(c->boundary_edges, 0);
    cr_assert(!c->closed);
    cr_assert(!c->watertight);
    cr_assert(!c->has_volume);
    cr_assert(!meshcheck_sound(c));
}

Test(check, thin_sliver_is_not_degenerate)
{
    start();
    tri(vert(0, 0, 0), vert(1, 0, 0), vert(0.5f, 1e-30f, 0));
    const CheckCounts *c = run();
    cr_assert_eq(c->degenerate_faces, 0);
}

Test(check, duplicate_faces)
{
    start();
    cube(0, 0, 0, 1);
    /* the top again, in another order, and the front reversed */
    quad(5, 6, 7, 4);
    quad(1, 0, 4, 5);
    const CheckCounts *c = run();
    cr_assert_eq(c->duplicate_faces, 2);
    cr_assert_eq(c->self_intersections, 0, "a duplicate is not a crossing");
    cr_assert(C.face_flags[6] & CHECK_DUPLICATE);
    cr_assert(C.face_flags[7] & CHECK_DUPLICATE);
    for (uint32_t f = 0; f < 6; f++)
        cr_assert_eq(C.face_flags[f] & CHECK_DUPLICATE, 0, "face %u", f);
    cr_assert(!meshcheck_sound(c));
}

Test(check, duplicate_triangles_on_an_open_sheet)
{
    start();
    uint32_t a = vert(0, 0, 0), b = vert(1, 0, 0), d = vert(0, 1, 0), e = vert(1, 1, 0);
    tri(a, b, e);
    tri(a, e, d);
    tri(e, d, a);   /* the second again, turned */
    const CheckCounts *c = run();
    cr_assert_eq(c->duplicate_faces, 1);
    cr_assert(C.face_flags[2] & CHECK_DUPLICATE);
}

/* A Moebius strip of n quads: the last joins the first turned over. */
static void moebius(int n)
{
    uint32_t v0 = M.nverts;
    for (int i = 0; i < n; i++) {
        double t = 2 * M_PI * i / n, h = t / 2;
        for (int s = -1; s <= 1; s += 2) {
            double r = 2 + 0.5 * s * cos(h);
            vert((float)(r * cos(t)), (float)(r * sin(t)), (float)(0.5 * s * sin(h)));
        }
    }
    for (int i = 0; i < n; i++) {
        uint32_t a = v0 + 2 * i, b = a + 1, c, d;
        if (i + 1 < n) {
            c = a + 2;
            d = a + 3;
        } else {
            c = v0 + 1;     /* turned over */
            d = v0;
        }
        quad(a, c, d, b);
    }
}

Test(check, moebius_strip_is_not_orientable)
{
    start();
    moebius(24);
    const CheckCounts *c = run();
    cr_assert_eq(c->nonorientable, 1);
    cr_assert_eq(c->inconsistent_faces, 0);
    cr_assert_eq(c->boundary_edges, 48, "one edge running twice round");
    cr_assert_eq(c->holes, 1);
    cr_assert_eq(c->nonmanifold_edges, 0);
    cr_assert_eq(c->components, 1);
    cr_assert(!c->has_volume);
    cr_assert_eq(c->self_intersections, 0);
    for (uint32_t f = 0; f < 24; f++)
        cr_assert(C.face_flags[f] & CHECK_NONORIENT);
    cr_assert_str_eq(verdict(c), "1 hole (48 boundary edges), 1 non-orientable part");
}

Test(check, uv_seam_cube_is_watertight)
{
    start();
    /* every face on four vertices of its own, as a format that splits
     * vertices along texture seams writes it */
    uint32_t v = cube_verts(0, 0, 0, 1);
    for (int f = 0; f < 6; f++) {
        uint32_t q[4];
        for (int k = 0; k < 4; k++) {
            const float *p = M.pos + 3 * (size_t)(v + tl_cube_faces[f][k]);
            q[k] = vert(p[0], p[1], p[2]);
        }
        face(4, q);
    }
    const CheckCounts *c = run();
    assert_clean_topology(c);
    cr_assert_eq(c->vertices, 8);
    cr_assert_eq(c->unused_vertices, 8, "the first eight corners are used by nothing");
    cr_assert(c->watertight && meshcheck_sound(c));
    NEAR(c->volume, 1);
}

Test(check, minus_zero_is_zero)
{
    start();
    cube(0, 0, 0, 1);
    /* a second copy of the bottom face's corner 0 at -0 */
    uint32_t z = vert(-0.0f, -0.0f, -0.0f);
    M.corner[0] = z;    /* face 0 starts at corner 0 */
    const CheckCounts *c = run();
    cr_assert(c->watertight && meshcheck_sound(c));
    cr_assert_eq(c->vertices, 8);
}

Test(check, unused_vertices_are_counted_not_a_problem)
{
    start();
    cube(0, 0, 0, 1);
    vert(5, 5, 5);
    vert(6, 6, 6);
    vert(7, 7, 7);
    const CheckCounts *c = run();
    cr_assert_eq(c->unused_vertices, 3);
    cr_assert_eq(c->vertices, 8);
    /* the box is of what the faces use */
    cr_assert_eq(c->hi[0], 1);
    cr_assert(meshcheck_sound(c));
}

Test(check, points_and_lines_use_their_vertices)
{
    start();
    cube(0, 0, 0, 1);
    uint32_t p = vert(5, 5, 5), a = vert(6, 6, 6), b = vert(7, 7, 7);
    vert(8, 8, 8);
    cr_assert_eq(tl_mesh_point(&M, p), 0);
    cr_assert_eq(tl_mesh_line(&M, (uint32_t[]){ a, b }, 2), 0);
    const CheckCounts *c = run();
    cr_assert_eq(c->unused_vertices, 1);
}

Test(check, objects_are_checked_apart)
{
    start();
    /* two cubes crossing, but in separate objects: no pair across them;
     * one object closed, one open: the file has no volume */
    cr_assert_eq(tl_mesh_object(&M, "a"), 0);
    cube(0, 0, 0, 1);
    cr_assert_eq(tl_mesh_object(&M, "b"), 0);
    cube_ex(0.5f, 0.5f, 0.5f, 1, 0, 0, 0);
    const CheckCounts *c = run();
    cr_assert_eq(C.nobjs, 2);
    cr_assert_str_eq(C.objs[0].name, "a");
    cr_assert_str_eq(C.objs[1].name, "b");
    cr_assert(meshcheck_sound(&C.objs[0].c));
    NEAR(C.objs[0].c.volume, 1);
    cr_assert_eq(C.objs[1].c.holes, 1);
    cr_assert(!C.objs[1].c.has_volume);
    cr_assert_eq(C.objs[0].face_first, 0);
    cr_assert_eq(C.objs[1].face_first, 6);
    cr_assert_eq(C.objs[1].face_count, 5);
    cr_assert_eq(c->faces, 11);
    cr_assert_eq(c->components, 2);
    cr_assert_eq(c->holes, 1);
    cr_assert_eq(c->self_intersections, 0);
    cr_assert(!c->has_volume && !c->closed);
    cr_assert_eq(c->volume, 0);
    NEAR(c->area, 11);
    cr_assert_eq(c->lo[0], 0);
    cr_assert_eq(c->hi[0], 1.5f);
}

Test(check, objects_volumes_add_up)
{
    start();
    cr_assert_eq(tl_mesh_object(&M, "a"), 0);
    cube(0, 0, 0, 1);
    cr_assert_eq(tl_mesh_object(&M, "b"), 0);
    cube(2, 0, 0, 1);
    const CheckCounts *c = run();
    cr_assert(meshcheck_sound(c));
    NEAR(c->volume, 2);
    NEAR(c->centre[0], 1.5);
    cr_assert_eq(C.objs[1].c.vertices, 8);
    cr_assert_eq(c->vertices, 16);
}

Test(check, same_position_in_two_objects_is_two_points)
{
    start();
    /* each object on its own: cubes touching at a corner in different
     * objects are both manifold */
    cr_assert_eq(tl_mesh_object(&M, "a"), 0);
    cube(0, 0, 0, 1);
    cr_assert_eq(tl_mesh_object(&M, "b"), 0);
    cube(1, 1, 1, 1);
    const CheckCounts *c = run();
    cr_assert_eq(c->nonmanifold_vertices, 0);
    cr_assert(meshcheck_sound(c));
}

Test(check, a_square_hole_in_a_quad_grid)
{
    start();
    /* a 4 x 4 grid of quads without its middle four: two loops */
    uint32_t v0 = M.nverts;
    for (int j = 0; j <= 4; j++)
        for (int i = 0; i <= 4; i++)
            vert((float)i, (float)j, 0);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            if ((i == 1 || i == 2) && (j == 1 || j == 2))
                continue;
            uint32_t a = v0 + (uint32_t)(5 * j + i);
            quad(a, a + 1, a + 6, a + 5);
        }
    const CheckCounts *c = run();
    cr_assert_eq(c->boundary_edges, 16 + 8);
    cr_assert_eq(c->holes, 2);
    cr_assert_eq(c->components, 1);
    cr_assert_eq(c->nonmanifold_vertices, 0);
    NEAR(c->area, 12);
}

Test(check, no_faces_is_not_sound)
{
    start();
    vert(0, 0, 0);
    vert(1, 0, 0);
    const CheckCounts *c = run();
    cr_assert_eq(c->faces, 0);
    cr_assert(!meshcheck_sound(c));
    cr_assert_str_eq(verdict(c), "no faces");
}

Test(check, verdict_is_cut_to_fit)
{
    CheckCounts c = { .faces = 10, .boundary_edges = 4, .holes = 1, .nonmanifold_edges = 2, .inconsistent_faces = 3 };
    char buf[256];
    cr_assert_eq(meshcheck_verdict(&c, buf, sizeof buf), 3);
    cr_assert_str_eq(buf, "1 hole (4 boundary edges), 2 non-manifold edges, 3 flipped faces");
    char small[12];
    cr_assert_eq(meshcheck_verdict(&c, small, sizeof small), 3);
    cr_assert_eq(strlen(small), sizeof small - 1);
    cr_assert_eq(strncmp(small, buf, sizeof small - 1), 0);
    char item[2][CHECK_PROBLEM_LEN];
    cr_assert_eq(meshcheck_problems(&c, item, 2), 3, "counts past max");
    cr_assert_str_eq(item[1], "2 non-manifold edges");
    CheckCounts all = { .faces = 1, .boundary_edges = 1, .holes = 1, .nonmanifold_edges = 1,
                        .nonmanifold_vertices = 1, .nonorientable = 1, .inconsistent_faces = 1, .inside_out = 1,
                        .degenerate_faces = 1, .duplicate_faces = 1, .self_intersections = 1 };
    char every[CHECK_PROBLEMS_MAX][CHECK_PROBLEM_LEN];
    cr_assert_eq(meshcheck_problems(&all, every, CHECK_PROBLEMS_MAX), 9);
    cr_assert_str_eq(every[0], "1 hole (1 boundary edge)");
    cr_assert_str_eq(every[8], "1 intersecting face pair");
    /* each problem alone makes it unsound */
    uint32_t *field[] = { &all.boundary_edges, &all.nonmanifold_edges, &all.nonmanifold_vertices,
                          &all.nonorientable, &all.inconsistent_faces, &all.degenerate_faces,
                          &all.duplicate_faces };
    for (size_t i = 0; i < sizeof field / sizeof *field; i++) {
        CheckCounts one = { .faces = 1 };
        one.boundary_edges = field[i] == &all.boundary_edges;
        one.nonmanifold_edges = field[i] == &all.nonmanifold_edges;
        one.nonmanifold_vertices = field[i] == &all.nonmanifold_vertices;
        one.nonorientable = field[i] == &all.nonorientable;
        one.inconsistent_faces = field[i] == &all.inconsistent_faces;
        one.degenerate_faces = field[i] == &all.degenerate_faces;
        one.duplicate_faces = field[i] == &all.duplicate_faces;
        cr_assert(!meshcheck_sound(&one), "field %zu", i);
    }
    CheckCounts inside = { .faces = 1, .inside_out = 1 }, crossing = { .faces = 1, .self_intersections = 1 };
    cr_assert(!meshcheck_sound(&inside) && !meshcheck_sound(&crossing));
}

Test(check, cancelled_run_fails_and_leaves_nothing)
{
    start();
    cube(0, 0, 0, 1);
    cr_assert_eq(tl_mesh_finish(&M), 0);
    int stop = 1;
    CheckOpts o = { .threads = 1, .intersections = 1, .detail = 1, .cancel = &stop };
    cr_assert_eq(meshcheck_run(&C, &M, &o, E, sizeof E), -1);
    cr_assert(strstr(E, "cancelled"), "%s", E);
    cr_assert_null(C.objs);
    cr_assert_null(C.face_flags);
}

Test(check, unit_from_the_format)
{
    start();
    cube(0, 0, 0, 1);
    snprintf(M.info.unit, sizeof M.info.unit, "mm");
    run();
    cr_assert_str_eq(C.unit, "mm");
}

/* ==== Crossings: the BVH against every pair ==== */

/* Triangles of a sphere of radius r at c, lat x lon quads cut in two. */
static void sphere(float cx, float cy, float cz, float r, int lat, int lon)
{
    uint32_t v0 = M.nverts;
    for (int i = 0; i <= lat; i++)
        for (int j = 0; j < lon; j++) {
            double th = M_PI * i / lat, ph = 2 * M_PI * j / lon;
            vert(cx + (float)(r * sin(th) * cos(ph)), cy + (float)(r * sin(th) * sin(ph)), cz + (float)(r * cos(th)));
        }
    for (int i = 0; i < lat; i++)
        for (int j = 0; j < lon; j++) {
            uint32_t a = v0 + (uint32_t)(i * lon + j), b = v0 + (uint32_t)(i * lon + (j + 1) % lon);
            tri(a, a + (uint32_t)lon, b);
            tri(b, a + (uint32_t)lon, b + (uint32_t)lon);
        }
}

/* Every pair of faces of object 0 (all triangles, none degenerate)
 * through the exact test, on welded points: how many cross. */
static uint64_t brute_pairs(uint8_t *hit)
{
    uint32_t nf = M.nfaces, *pid = malloc(M.nverts * sizeof *pid), np = 0;
    cr_assert_not_null(pid);
    cr_assert_eq(check_weld(&M, pid, &np), 0);
    uint64_t n = 0;
    for (uint32_t f = 0; f < nf; f++)
        for (uint32_t g = f + 1; g < nf; g++) {
            const float *pa[3], *pb[3];
            uint32_t ia[3], ib[3];
            for (int k = 0; k < 3; k++) {
                ia[k] = pid[M.corner[3 * f + k]];
                ib[k] = pid[M.corner[3 * g + k]];
                pa[k] = M.pos + 3 * (size_t)M.corner[3 * f + k];
                pb[k] = M.pos + 3 * (size_t)M.corner[3 * g + k];
            }
            /* the check leaves zero-area faces out (the poles' here) */
            if (ia[0] == ia[1] || ia[1] == ia[2] || ia[0] == ia[2] || ib[0] == ib[1] || ib[1] == ib[2] ||
                ib[0] == ib[2] || exact_collinear(pa[0], pa[1], pa[2]) || exact_collinear(pb[0], pb[1], pb[2]))
                continue;
            int r = check_tri_pair(pa, ia, pb, ib);
            if (r == 1) {
                n++;
                hit[f] = hit[g] = 1;
            }
        }
    free(pid);
    return n;
}

Test(check, bvh_finds_every_crossing_pair_on_any_threads)
{
    start();
    /* three spheres crossing each other and a cube through them */
    sphere(0, 0, 0, 1, 12, 16);
    sphere(0.9f, 0.3f, 0.1f, 0.8f, 10, 14);
    sphere(-0.5f, 0.7f, -0.4f, 0.6f, 8, 12);
    cube_ex(-0.3f, -0.3f, -0.3f, 1.1f, -1, 0, 1);
    cr_assert_eq(tl_mesh_finish(&M), 0);
    uint8_t *hit = calloc(M.nfaces, 1);
    uint64_t want = brute_pairs(hit);
    cr_assert_gt(want, 100);
    for (int threads = 1; threads <= 3; threads++) {
        CheckOpts o = { .threads = threads, .intersections = 1, .detail = 1 };
        cr_assert_eq(meshcheck_run(&C, &M, &o, E, sizeof E), 0, "%s", E);
        cr_assert_eq(C.file.self_intersections, want, "%d threads: %llu pairs, brute force %llu", threads,
                     (unsigned long long)C.file.self_intersections, (unsigned long long)want);
        cr_assert_eq(C.objs[0].npairs, want);
        for (uint32_t i = 0; i + 1 < C.objs[0].npairs; i++) {
            const uint32_t *p = C.objs[0].pairs + 2 * i;
            cr_assert(p[0] < p[1]);
            cr_assert(p[0] < p[2] || (p[0] == p[2] && p[1] < p[3]), "pairs sorted, each once");
        }
        for (uint32_t f = 0; f < M.nfaces; f++)
            cr_assert_eq(!!(C.face_flags[f] & CHECK_INTERSECTS), hit[f], "face %u", f);
        meshcheck_free(&C);
    }
    free(hit);
}

Test(check, triangle_pair_cases)
{
    /* by hand: crossing, apart, sharing a corner, an edge, coplanar */
    float a0[3] = { 0, 0, 0 }, a1[3] = { 2, 0, 0 }, a2[3] = { 0, 2, 0 };
    float b0[3] = { 0.5f, 0.5f, -1 }, b1[3] = { 0.5f, 0.5f, 1 }, b2[3] = { 1, 0.2f, 1 };
    const float *A[3] = { a0, a1, a2 }, *B[3] = { b0, b1, b2 };
    uint32_t ia[3] = { 0, 1, 2 }, ib[3] = { 3, 4, 5 };
    cr_assert_eq(check_tri_pair(A, ia, B, ib), 1, "pierced");
    float c0[3] = { 0.5f, 0.5f, 0.1f }, c1[3] = { 0.5f, 0.5f, 1 }, c2[3] = { 1, 0.2f, 1 };
    const float *Cc[3] = { c0, c1, c2 };
    cr_assert_eq(check_tri_pair(A, ia, Cc, ib), 0, "above");
    const float *D[3] = { a0, b1, b2 };
    uint32_t id[3] = { 0, 4, 5 };
    cr_assert_eq(check_tri_pair(A, ia, D, id), 0, "a shared corner only");
    float e2[3] = { 0.3f, 0.3f, 0 };
    const float *Ef[3] = { a0, a1, e2 };
    uint32_t ie[3] = { 0, 1, 6 };
    cr_assert_eq(check_tri_pair(A, ia, Ef, ie), 1, "folded onto it across a shared edge");
    float f2[3] = { 0.3f, -0.3f, 0 };
    const float *F[3] = { a0, a1, f2 };
    cr_assert_eq(check_tri_pair(A, ia, F, ie), 0, "the other side of the shared edge");
    float g0[3] = { 0.2f, 0.2f, 0 }, g1[3] = { 3, 0.2f, 0 }, g2[3] = { 0.2f, 3, 0 };
    const float *G[3] = { g0, g1, g2 };
    cr_assert_eq(check_tri_pair(A, ia, G, ib), 1, "coplanar overlap");
    float h0[3] = { 2, 2, 0 }, h1[3] = { 3, 2, 0 }, h2[3] = { 2, 3, 0 };
    const float *H[3] = { h0, h1, h2 };
    cr_assert_eq(check_tri_pair(A, ia, H, ib), 0, "coplanar apart");
    cr_assert_eq(check_tri_pair(A, ia, A, ia), CHECK_SAME_TRI);
}

/* Two triangles in one plane on one shared corner: every pair of small
 * integer triangles at the origin against a brute force of their own,
 * in every axis plane and tilted. They meet beyond the corner iff some
 * direction from it is in both: every cone here is spanned by integer
 * vectors of at most 3 a side, so the directions of the grid [-6, 6]^2
 * hold any ray the two share (one of their sides), and a direction is in
 * a triangle at the origin iff a short step along it is, in integers
 * scaled by 64. */
static int64_t cross2(int64_t ax, int64_t ay, int64_t bx, int64_t by) { return ax * by - ay * bx; }

static int in_tri_int(const int t[3][2], int64_t px, int64_t py)
{
    int64_t s0 = cross2(t[1][0] - t[0][0], t[1][1] - t[0][1], px - t[0][0], py - t[0][1]);
    int64_t s1 = cross2(t[2][0] - t[1][0], t[2][1] - t[1][1], px - t[1][0], py - t[1][1]);
    int64_t s2 = cross2(t[0][0] - t[2][0], t[0][1] - t[2][1], px - t[2][0], py - t[2][1]);
    return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

static int wedges_meet_brute(int a[3][2], int b[3][2])
{
    int sa[3][2], sb[3][2];
    for (int k = 0; k < 3; k++)
        for (int l = 0; l < 2; l++) {
            sa[k][l] = a[k][l] * 64;
            sb[k][l] = b[k][l] * 64;
        }
    for (int dx = -6; dx <= 6; dx++)
        for (int dy = -6; dy <= 6; dy++)
            if ((dx || dy) && in_tri_int(sa, dx, dy) && in_tri_int(sb, dx, dy))
                return 1;
    return 0;
}

Test(check, coplanar_pairs_on_one_corner_against_a_brute_force)
{
    uint32_t seed = 28;
    int tested = 0, met = 0;
    for (int n = 0; n < 4000; n++) {
        int t[2][3][2] = { { { 0, 0 } }, { { 0, 0 } } };
        for (int k = 0; k < 2; k++)
            do {
                for (int c = 1; c < 3; c++)
                    for (int l = 0; l < 2; l++) {
                        seed = seed * 1664525u + 1013904223u;
                        t[k][c][l] = (int)(seed >> 24) % 7 - 3;
                    }
            } while (cross2(t[k][1][0], t[k][1][1], t[k][2][0], t[k][2][1]) == 0);
        /* a far corner shared too is an edge, another case */
        if ((t[0][1][0] == t[1][1][0] && t[0][1][1] == t[1][1][1]) ||
            (t[0][1][0] == t[1][2][0] && t[0][1][1] == t[1][2][1]) ||
            (t[0][2][0] == t[1][1][0] && t[0][2][1] == t[1][1][1]) ||
            (t[0][2][0] == t[1][2][0] && t[0][2][1] == t[1][2][1]))
            continue;
        int want = wedges_meet_brute(t[0], t[1]);
        /* in the planes z = 0, x = 0, y = 0, and x + y + z = 1 moved to
         * pass through (1/4, 1/2, 1/4) */
        for (int plane = 0; plane < 4; plane++) {
            float p[2][3][3];
            for (int k = 0; k < 2; k++)
                for (int c = 0; c < 3; c++) {
                    float u = (float)t[k][c][0], v = (float)t[k][c][1];
                    float *q = p[k][c];
                    if (plane == 0)
                        q[0] = u, q[1] = v, q[2] = 0;
                    else if (plane == 1)
                        q[0] = 0, q[1] = u, q[2] = v;
                    else if (plane == 2)
                        q[0] = v, q[1] = 0, q[2] = u;
                    else
                        q[0] = 0.25f + u, q[1] = 0.5f + v, q[2] = 0.25f - u - v;
                }
            const float *A[3] = { p[0][0], p[0][1], p[0][2] }, *B[3] = { p[1][0], p[1][1], p[1][2] };
            uint32_t ia[3] = { 0, 1, 2 }, ib[3] = { 0, 3, 4 };
            cr_assert_eq(check_tri_pair(A, ia, B, ib), want, "plane %d: (0 0, %d %d, %d %d) and (0 0, %d %d, %d %d)",
                         plane, t[0][1][0], t[0][1][1], t[0][2][0], t[0][2][1], t[1][1][0], t[1][1][1], t[1][2][0],
                         t[1][2][1]);
            /* turned: the shared corner elsewhere in each */
            const float *A2[3] = { p[0][1], p[0][2], p[0][0] }, *B2[3] = { p[1][2], p[1][0], p[1][1] };
            uint32_t ia2[3] = { 1, 2, 0 }, ib2[3] = { 4, 0, 3 };
            cr_assert_eq(check_tri_pair(A2, ia2, B2, ib2), want);
        }
        tested++;
        met += want;
    }
    cr_assert_gt(tested, 2000);
    cr_assert(met > tested / 10 && met < tested - tested / 10, "both answers well represented: %d of %d", met,
              tested);
}

/* ==== Hostile inputs: the crossing test's budget (issue 28) ==== */

/* n triangles around the origin in the plane z = 0, a disk in n slices. */
static void planar_fan(uint32_t n)
{
    uint32_t c = vert(0, 0, 0), v0 = M.nverts;
    for (uint32_t i = 0; i < n; i++) {
        double t = 2 * M_PI * i / n;
        vert((float)cos(t), (float)sin(t), 0);
    }
    for (uint32_t i = 0; i < n; i++)
        tri(c, v0 + i, v0 + (i + 1) % n);
}

/* The budget held (a job adds its work to the total every 4096 tests or
 * so: that much over per thread at most), stopped, and said so. */
static void assert_stopped(const CheckCounts *c, uint32_t tris, int threads)
{
    cr_assert(c->intersections_stopped);
    cr_assert_eq(c->pair_budget, CHECK_PAIR_BUDGET(tris));
    cr_assert_geq(c->pair_tests, c->pair_budget);
    cr_assert_leq(c->pair_tests, c->pair_budget + 8192u * (uint64_t)threads, "%llu pair tests, budget %llu",
                  (unsigned long long)c->pair_tests, (unsigned long long)c->pair_budget);
    cr_assert(!meshcheck_sound(c));
    char want[128];
    snprintf(want, sizeof want, "at least %llu intersecting face pair%s (stopped after %llu pair tests)",
             (unsigned long long)c->self_intersections, c->self_intersections == 1 ? "" : "s",
             (unsigned long long)c->pair_tests);
    cr_assert(strstr(verdict(c), want), "%s", verdict(c));
}

Test(check, planar_fans_stop_at_the_budget, .timeout = 120)
{
    /* 10k, 20k and 40k slices: 24 s, 83 s and over 120 s before */
    for (uint32_t n = 10000; n <= 40000; n *= 2) {
        mesh_free(&M);
        meshcheck_free(&C);
        start();
        planar_fan(n);
        const CheckCounts *c = run();
        assert_stopped(c, n, 1);
        cr_assert_eq(c->self_intersections, 0, "no two slices overlap");
        cr_assert_eq(c->boundary_edges, n);
        cr_assert_eq(c->holes, 1);
    }
}

Test(check, a_sound_spindle_of_many_slices_is_not_sound_unproven)
{
    /* two cones base to base, 20k slices each: closed, manifold and
     * outward, but each apex is a fan of 20k triangles (all pairs
     * candidates): stopped, and a gate must not take that for sound */
    start();
    uint32_t n = 20000, top = vert(0, 0, 1), bot = vert(0, 0, -1), v0 = M.nverts;
    for (uint32_t i = 0; i < n; i++) {
        double t = 2 * M_PI * i / n;
        vert((float)cos(t), (float)sin(t), 0);
    }
    for (uint32_t i = 0; i < n; i++) {
        uint32_t p = v0 + i, q = v0 + (i + 1) % n;
        tri(top, p, q);
        tri(bot, q, p);
    }
    const CheckCounts *c = run();
    assert_stopped(c, 2 * n, 1);
    cr_assert_eq(c->self_intersections, 0);
    cr_assert(c->watertight);
    cr_assert_eq(c->inconsistent_faces, 0);
    cr_assert(!c->inside_out);
    cr_assert_eq(meshcheck_problems(c, NULL, 0), 1, "the stop is its only problem: %s", verdict(c));
}

Test(check, a_small_fan_is_tested_in_full)
{
    /* 1,000 slices: 500k pairs, within the floor of a million */
    start();
    planar_fan(1000);
    /* and one slice folded over its neighbours: a crossing */
    uint32_t c0 = 0, far = vert(0.9f, 0.2f, 0);
    tri(c0, 1, far);
    const CheckCounts *c = run();
    cr_assert(!c->intersections_stopped);
    cr_assert_leq(c->pair_tests, CHECK_PAIR_BUDGET(1001));
    cr_assert_gt(c->self_intersections, 0);
    cr_assert(!strstr(verdict(c), "at least"));
}

Test(check, coincident_triangles_are_duplicates_not_pairs)
{
    /* 16,000 of one triangle: 2.4 s before (128 million pairs) */
    start();
    uint32_t a = vert(0, 0, 0), b = vert(1, 0, 0), d = vert(0, 1, 0);
    for (int i = 0; i < 16000; i++)
        tri(a, b, d);
    const CheckCounts *c = run();
    cr_assert_eq(c->duplicate_faces, 15999);
    cr_assert_eq(c->self_intersections, 0);
    cr_assert_eq(c->pair_tests, 0, "the original alone is tested");
    cr_assert(!c->intersections_stopped);
}

Test(check, a_duplicate_crossing_a_face_is_counted_once)
{
    start();
    uint32_t a = vert(0, 0, 0), b = vert(2, 0, 0), d = vert(0, 2, 0);
    tri(a, b, d);
    tri(d, a, b);   /* the same, turned */
    tri(vert(0.5f, 0.5f, -1), vert(0.5f, 0.5f, 1), vert(1, 0.2f, 1));
    const CheckCounts *c = run();
    cr_assert_eq(c->duplicate_faces, 1);
    cr_assert_eq(c->self_intersections, 1);
    cr_assert(C.face_flags[0] & CHECK_INTERSECTS);
    cr_assert_eq(C.face_flags[1] & CHECK_INTERSECTS, 0);
}

Test(check, a_fin_of_100k_blades_stops_at_the_budget, .timeout = 120)
{
    /* 100k triangles on one edge, each in its own half-plane: over 60 s
     * before */
    start();
    uint32_t a = vert(0, 0, 0), b = vert(1, 0, 0);
    for (int i = 0; i < 100000; i++) {
        double t = 2 * M_PI * i / 100000;
        tri(a, b, vert(0.5f, (float)cos(t), (float)sin(t)));
    }
    cr_assert_eq(tl_mesh_finish(&M), 0);
    for (int threads = 1; threads <= 2; threads++) {
        meshcheck_free(&C);
        CheckOpts o = { .threads = threads, .intersections = 1 };
        cr_assert_eq(meshcheck_run(&C, &M, &o, E, sizeof E), 0, "%s", E);
        const CheckCounts *c = &C.file;
        assert_stopped(c, 100000, threads);
        cr_assert_eq(c->self_intersections, 0);
        cr_assert_eq(c->nonmanifold_edges, 1);
    }
}

Test(check, stacked_coplanar_triangles_stop_at_the_budget, .timeout = 120)
{
    /* 20k in one plane, each a little along from the last: every pair
     * overlaps (200 million), over 60 s before */
    start();
    for (int i = 0; i < 20000; i++) {
        float d = (float)i * 1e-5f;
        tri(vert(d, d, 0), vert(1 + d, d, 0), vert(d, 1 + d, 0));
    }
    const CheckCounts *c = run();
    assert_stopped(c, 20000, 1);
    /* every pair tested crosses, bar none */
    cr_assert_eq(c->self_intersections, c->pair_tests);
}

/* The orientation of points on a small integer grid, moved and scaled
 * by powers of two (which keeps them exact floats and the sign as it
 * was): the sign the integers give, through both exact stages (the
 * 128-bit one for coordinates of one magnitude, the expansion for a
 * wide range, which a far translation makes). */
Test(check, orient3d_sign_is_exact_at_every_scale)
{
    uint32_t seed = 12345;
    int tested = 0, zeros = 0;
    for (int round = 0; round < 4000; round++) {
        int64_t g[4][3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) {
                seed = seed * 1103515245u + 12345u;
                g[i][k] = (int64_t)(seed >> 16 & 15) - 8;
            }
        /* d on the plane of a, b, c, or one step off it */
        seed = seed * 1103515245u + 12345u;
        int64_t s = (int64_t)(seed >> 16 & 3) - 1, t = (int64_t)(seed >> 20 & 3) - 1;
        for (int k = 0; k < 3; k++)
            g[3][k] = g[0][k] + s * (g[1][k] - g[0][k]) + t * (g[2][k] - g[0][k]);
        if (round & 1)
            g[3][(round >> 1) % 3] += (round & 2) ? 1 : -1;
        int64_t m[3][3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                m[i][k] = g[i][k] - g[3][k];
        int64_t det = m[0][2] * (m[1][0] * m[2][1] - m[2][0] * m[1][1]) +
                      m[1][2] * (m[2][0] * m[0][1] - m[0][0] * m[2][1]) +
                      m[2][2] * (m[0][0] * m[1][1] - m[1][0] * m[0][1]);
        int want = det > 0 ? 1 : det < 0 ? -1 : 0;
        static const int scale[] = { -40, -3, 0, 9, 60 };
        /* none, all far (one magnitude), x alone far (a wide range) */
        static const double shift[] = { 0, 1000, 1 << 22 };
        for (int si = 0; si < 5; si++)
            for (int ti = 0; ti < 3; ti++) {
                float f[4][3];
                for (int i = 0; i < 4; i++)
                    for (int k = 0; k < 3; k++)
                        f[i][k] = (float)ldexp((double)g[i][k] + shift[ti] * (ti == 2 ? k == 0 : k == 1 ? -1 : 1),
                                               scale[si]);
                int got = exact_orient3d(f[0], f[1], f[2], f[3]);
                cr_assert_eq(got, want, "round %d, scale 2^%d, shift %g: %d, wanted %d", round, scale[si], shift[ti],
                             got, want);
                tested++;
                zeros += want == 0;
            }
    }
    cr_assert_gt(zeros, 1000, "coplanar cases reach the exact stages");
    cr_assert_gt(tested, 50000);
}

/* One plane asked about many points (ExactPlane, the crossing test's
 * triangles) gives orient3d's sign: points of up to 2^22 on a random
 * plane through three others, or a step off it, whose determinant
 * (three factors of 22 bits) doubles cannot hold, so the double
 * evaluation is noise where the true sign is 0 or tiny, against the
 * sign in 128-bit integers. */
Test(check, plane_side_is_orient3d_where_doubles_round)
{
    uint32_t seed = 777;
    int tested = 0, zeros = 0;
    for (int round = 0; round < 20000; round++) {
        int64_t g[4][3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) {
                seed = seed * 1103515245u + 12345u;
                g[i][k] = (int64_t)(seed >> 8 & 0x1fffff) - 0x100000;      /* |.| <= 2^20 */
            }
        seed = seed * 1103515245u + 12345u;
        int64_t s = (int64_t)(seed >> 16 & 3) - 1, t = (int64_t)(seed >> 20 & 3) - 1;
        for (int k = 0; k < 3; k++)
            g[3][k] = g[0][k] + s * (g[1][k] - g[0][k]) + t * (g[2][k] - g[0][k]);    /* |.| < 2^23 */
        if (round % 3 == 1)
            g[3][round % 7 % 3] += (round & 8) ? 1 : -1;
        __int128 m[3][3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                m[i][k] = g[i][k] - g[3][k];
        __int128 det = m[0][2] * (m[1][0] * m[2][1] - m[2][0] * m[1][1]) +
                       m[1][2] * (m[2][0] * m[0][1] - m[0][0] * m[2][1]) +
                       m[2][2] * (m[0][0] * m[1][1] - m[1][0] * m[0][1]);
        int want = det > 0 ? 1 : det < 0 ? -1 : 0;
        float f[4][3];
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                f[i][k] = (float)g[i][k];       /* exact: below 2^24 */
        ExactPlane pl;
        exact_plane(&pl, f[0], f[1], f[2]);
        int got = exact_plane_side(&pl, f[3]);
        cr_assert_eq(got, want, "round %d: %d, wanted %d", round, got, want);
        tested++;
        zeros += want == 0;
    }
    cr_assert_gt(zeros, 5000, "points on the plane, where doubles leave noise");
    cr_assert_eq(tested, 20000);
}

/* ==== An independent reference ==== */

/* Counted here without meshcheck's code: points by sorting positions,
 * edges by sorting point pairs, parts and holes by a union-find of our
 * own, area and volume by the divergence theorem about the origin. Per
 * object, as meshcheck counts. */
typedef struct {
    uint32_t vertices, boundary, nonmanifold, parts, holes, faces, degenerate;
    double   area, volume;      /* volume signed, as wound */
} Ref;

static float key_of(float f) { return f == 0 ? 0 : f; }

static int cmp_pos(const void *x, const void *y, void *m)
{
    const float *p = ((const Mesh *)m)->pos + 3 * (size_t) * (const uint32_t *)x;
    const float *q = ((const Mesh *)m)->pos + 3 * (size_t) * (const uint32_t *)y;
    for (int k = 0; k < 3; k++)
        if (key_of(p[k]) != key_of(q[k]))
            return key_of(p[k]) < key_of(q[k]) ? -1 : 1;
    return 0;
}

static const Mesh *sort_mesh;
static int cmp_pos_g(const void *x, const void *y) { return cmp_pos(x, y, (void *)sort_mesh); }

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

static uint32_t uf_find(uint32_t *p, uint32_t i)
{
    while (p[i] != i)
        i = p[i] = p[p[i]];
    return i;
}

static int uf_join(uint32_t *p, uint32_t a, uint32_t b)
{
    a = uf_find(p, a);
    b = uf_find(p, b);
    if (a == b)
        return 0;
    p[a > b ? a : b] = a < b ? a : b;
    return 1;
}

static void reference(const Mesh *m, const MeshObject *o, uint32_t *pid, Ref *r)
{
    memset(r, 0, sizeof *r);
    uint32_t f0 = o->face_first, nf = o->face_count;
    uint32_t c0 = m->face_start[f0], nc = m->face_start[f0 + nf] - c0;
    r->faces = nf;
    /* points: pid[] holds each vertex's point over the whole mesh;
     * count those this object's corners use */
    uint8_t *used = calloc(m->nverts + 1, 1);
    uint32_t *fpt = malloc((nc + 1) * sizeof *fpt);
    cr_assert(used && fpt);
    for (uint32_t c = 0; c < nc; c++) {
        uint32_t p = pid[m->corner[c0 + c]];
        r->vertices += !used[p];
        used[p] = 1;
        fpt[c] = p;
    }
    /* degenerate faces (every corner on one line, here: no three of
     * its points off one line) are in no edge and no part: CGAL's
     * polygon-soup repair and the slicers set them aside alike */
    uint8_t *deg = calloc(nf + 1, 1);
    cr_assert_not_null(deg);
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t s = m->face_start[f0 + f] - c0, n = m->face_start[f0 + f + 1] - c0 - s;
        deg[f] = 1;
        for (uint32_t i = 0; i < n && deg[f]; i++)
            for (uint32_t j = 0; j < n && deg[f]; j++)
                for (uint32_t k = 0; k < n && deg[f]; k++) {
                    const float *a = m->pos + 3 * (size_t)m->corner[c0 + s + i];
                    const float *b = m->pos + 3 * (size_t)m->corner[c0 + s + j];
                    const float *c = m->pos + 3 * (size_t)m->corner[c0 + s + k];
                    deg[f] = exact_collinear(a, b, c);
                }
        r->degenerate += deg[f];
    }
    /* edges: (lo << 32 | hi) with the face, sorted */
    uint64_t *e = malloc((nc + 1) * sizeof *e);
    uint32_t *ef = malloc((nc + 1) * sizeof *ef);
    uint32_t ne = 0;
    cr_assert(e && ef);
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t s = m->face_start[f0 + f] - c0, n = m->face_start[f0 + f + 1] - c0 - s;
        for (uint32_t k = 0; k < n && !deg[f]; k++) {
            uint32_t a = fpt[s + k], b = fpt[s + (k + 1) % n];
            if (a != b)
                e[ne++] = (uint64_t)(a < b ? a : b) << 32 | (a < b ? b : a);
        }
    }
    /* each edge's face beside it, then (edge, index) pairs sorted: a
     * run of one key is one edge, its length the faces on it */
    uint64_t *ek = malloc(((size_t)ne + 1) * 2 * sizeof *ek);
    cr_assert_not_null(ek);
    for (uint32_t f = 0, i = 0; f < nf; f++) {
        uint32_t s = m->face_start[f0 + f] - c0, n = m->face_start[f0 + f + 1] - c0 - s;
        for (uint32_t k = 0; k < n && !deg[f]; k++)
            if (fpt[s + k] != fpt[s + (k + 1) % n])
                ef[i++] = f;
    }
    for (uint32_t i = 0; i < ne; i++) {
        ek[2 * i] = e[i];
        ek[2 * i + 1] = i;
    }
    qsort(ek, ne, 2 * sizeof *ek, cmp_u64);
    uint32_t *face_uf = malloc((nf + 1) * sizeof *face_uf), *pt_uf = malloc((m->nverts + 1) * sizeof *pt_uf);
    cr_assert(face_uf && pt_uf);
    for (uint32_t f = 0; f < nf; f++)
        face_uf[f] = f;
    for (uint32_t v = 0; v < m->nverts; v++)
        pt_uf[v] = v;
    uint32_t merged = 0;
    for (uint32_t i = 0; i < ne;) {
        uint32_t j = i;
        while (j < ne && ek[2 * j] == ek[2 * i])
            j++;
        if (j - i == 1) {
            r->boundary++;
            merged += (uint32_t)uf_join(pt_uf, (uint32_t)(ek[2 * i] >> 32), (uint32_t)ek[2 * i]);
        }
        if (j - i >= 3)
            r->nonmanifold++;
        for (uint32_t k = i + 1; k < j; k++)
            uf_join(face_uf, ef[ek[2 * i + 1]], ef[ek[2 * k + 1]]);
        i = j;
    }
    r->holes = r->boundary - merged;
    for (uint32_t f = 0; f < nf; f++)
        r->parts += !deg[f] && uf_find(face_uf, f) == f;
    /* area and volume of each face's fan, about the origin */
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t s = m->face_start[f0 + f], n = m->face_start[f0 + f + 1] - s;
        const float *a = m->pos + 3 * (size_t)m->corner[s];
        for (uint32_t k = 1; k + 1 < n; k++) {
            const float *b = m->pos + 3 * (size_t)m->corner[s + k], *c = m->pos + 3 * (size_t)m->corner[s + k + 1];
            double u[3], w[3];
            for (int i = 0; i < 3; i++) {
                u[i] = (double)b[i] - a[i];
                w[i] = (double)c[i] - a[i];
            }
            double nx = u[1] * w[2] - u[2] * w[1], ny = u[2] * w[0] - u[0] * w[2], nz = u[0] * w[1] - u[1] * w[0];
            r->area += 0.5 * sqrt(nx * nx + ny * ny + nz * nz);
            r->volume += ((double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
                          (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
                          (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0])) / 6;
        }
    }
    free(deg);
    free(used);
    free(fpt);
    free(e);
    free(ef);
    free(ek);
    free(face_uf);
    free(pt_uf);
}

/* Load path, check it (no crossings: the reference has none), and hold
 * every object to the reference. */
static void against_reference(const char *path)
{
    mesh_free(&M);
    meshcheck_free(&C);
    cr_assert_eq(mesh_load(&M, path, E, sizeof E), 0, "%s", E);
    CheckOpts o = { .threads = 2, .intersections = 0, .detail = 0 };
    cr_assert_eq(meshcheck_run(&C, &M, &o, E, sizeof E), 0, "%s", E);
    /* the points: vertices sorted by position, equal runs one point */
    uint32_t *order = malloc((M.nverts + 1) * sizeof *order), *pid = malloc((M.nverts + 1) * sizeof *pid);
    cr_assert(order && pid);
    for (uint32_t v = 0; v < M.nverts; v++)
        order[v] = v;
    sort_mesh = &M;
    qsort(order, M.nverts, sizeof *order, cmp_pos_g);
    for (uint32_t i = 0; i < M.nverts; i++)
        pid[order[i]] = i && cmp_pos(&order[i - 1], &order[i], &M) == 0 ? pid[order[i - 1]] : order[i];
    for (uint32_t i = 0; i < M.nobjs; i++) {
        const CheckCounts *c = &C.objs[i].c;
        if (!M.objs[i].face_count)
            continue;
        Ref r;
        reference(&M, &M.objs[i], pid, &r);
        const char *n = M.objs[i].name;
        cr_assert_eq(c->faces, r.faces, "%s/%s", path, n);
        cr_assert_eq(c->vertices, r.vertices, "%s/%s: vertices %u, reference %u", path, n, c->vertices, r.vertices);
        cr_assert_eq(c->boundary_edges, r.boundary, "%s/%s: boundary %u, reference %u", path, n, c->boundary_edges,
                     r.boundary);
        cr_assert_eq(c->nonmanifold_edges, r.nonmanifold, "%s/%s: non-manifold %u, reference %u", path, n,
                     c->nonmanifold_edges, r.nonmanifold);
        cr_assert_eq(c->holes, r.holes, "%s/%s: holes %u, reference %u", path, n, c->holes, r.holes);
        cr_assert_eq(c->components, r.parts, "%s/%s: parts %u, reference %u", path, n, c->components, r.parts);
        double rel = fabs(c->area - r.area) / (r.area > 0 ? r.area : 1);
        cr_assert(rel < 1e-9, "%s/%s: area %.17g, reference %.17g", path, n, c->area, r.area);
        cr_assert_eq(c->degenerate_faces, r.degenerate, "%s/%s: degenerate %u, reference %u", path, n,
                     c->degenerate_faces, r.degenerate);
        cr_assert_eq(c->closed, r.boundary == 0 && r.faces > r.degenerate, "%s/%s", path, n);
        /* a consistently wound closed part: the same volume, its sign
         * saying inside out (degenerate faces add none to either) */
        if (c->has_volume && c->inconsistent_faces == 0) {
            double vr = fabs(r.volume), tol = 1e-7 * (vr > 1e-30 ? vr : 1) + 1e-12;
            cr_assert(fabs(c->volume - vr) <= tol * 10, "%s/%s: volume %.17g, reference %.17g", path, n,
                      c->volume, vr);
            cr_assert_eq(c->inside_out, r.volume < 0, "%s/%s", path, n);
        }
    }
    free(order);
    free(pid);
}

Test(check, bundled_assets_agree_with_the_reference, .timeout = 120)
{
    static const char *const assets[] = { "assets/cube.obj",  "assets/concave.obj",     "assets/cyclic.obj",
                                          "assets/demo.obj",  "assets/knot.obj",        "assets/scene.obj",
                                          "assets/torus.obj", "assets/star-pierce.obj" };
    for (size_t i = 0; i < sizeof assets / sizeof *assets; i++)
        against_reference(assets[i]);
}

Test(check, generated_meshes_agree_with_the_reference)
{
    start();
    moebius(10);
    cube_ex(5, 0, 0, 1, 2, 0x5, 1);
    sphere(0, 5, 0, 1, 6, 8);
    cube(0, 0, 5, 1);
    cube(1, 1, 6, 1);
    cr_assert_eq(tl_mesh_finish(&M), 0);
    char path[] = "/tmp/zv-check-XXXXXX.obj";
    int fd = mkstemps(path, 4);
    cr_assert_geq(fd, 0);
    FILE *f = fdopen(fd, "w");
    for (uint32_t v = 0; v < M.nverts; v++)
        fprintf(f, "v %.9g %.9g %.9g\n", M.pos[3 * v], M.pos[3 * v + 1], M.pos[3 * v + 2]);
    for (uint32_t i = 0; i < M.nfaces; i++) {
        fprintf(f, "f");
        for (uint32_t c = M.face_start[i]; c < M.face_start[i + 1]; c++)
            fprintf(f, " %u", M.corner[c] + 1);
        fprintf(f, "\n");
    }
    cr_assert_eq(fclose(f), 0);
    against_reference(path);
    unlink(path);
}

/* The shared models (make test-models): every one against the
 * reference, the dragon included. */
Test(models, check_agrees_with_the_reference, .timeout = 600)
{
    static const char *const names[] = { "cube.obj",          "tetrahedron.obj",   "concave-shapes.obj", "teapot.obj",
                                         "spot.obj",          "spot-quads.obj",    "spot-control-mesh.obj",
                                         "suzanne.obj",       "bunny-5k.obj",      "stanford-bunny.obj",
                                         "armadillo.obj",     "nefertiti.obj",     "buddha-100k.obj",
                                         "interpenetrating.obj", "scene-overlap.obj", "armadillo-50k.obj",
                                         "lucy-100k.obj",     "sword-quads.obj",   "cornell_box.obj",
                                         "negative-indices.obj", "dragon.obj" };
    int n = 0;
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        const char *p = tl_shared_model(names[i]);
        if (!p)
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s", p);
        against_reference(path);
        n++;
    }
    if (!n)
        cr_skip_test("no ../shared/models");
}

/* The models README's "Open edges" column (counted on vertex indices by
 * its check_obj.py) is the boundary --check reports, for the models
 * whose vertices are not split at one position (the teapot's are: 1036
 * open edges on indices, 160 on positions; the dragon 4270 and 0). */
Test(models, check_open_edges_match_the_models_readme)
{
    static const struct {
        const char *name;
        uint32_t    open;
    } want[] = { { "bunny-5k.obj", 42 }, { "stanford-bunny.obj", 223 },
                 { "suzanne.obj", 42 },  { "spot.obj", 0 },      { "armadillo.obj", 0 } };
    for (size_t i = 0; i < sizeof want / sizeof *want; i++) {
        const char *p = tl_shared_model(want[i].name);
        if (!p)
            cr_skip_test("no ../shared/models");
        mesh_free(&M);
        meshcheck_free(&C);
        cr_assert_eq(mesh_load(&M, p, E, sizeof E), 0, "%s", E);
        CheckOpts o = { .threads = 1 };
        cr_assert_eq(meshcheck_run(&C, &M, &o, E, sizeof E), 0, "%s", E);
        cr_assert_eq(C.file.boundary_edges, want[i].open, "%s: %u", want[i].name, C.file.boundary_edges);
    }
}
