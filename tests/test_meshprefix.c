/* test_meshprefix.c: what a load publishes while it parses (issue 21:
 * the viewer's picture while loading) is, held after H faces, the mesh
 * a load of the file cut after its H-th face makes: every vertex,
 * face start and corner, parsed serially and in pieces. Before any
 * face, the vertices are points, as in a file of vertices alone. What
 * the reader takes is checked: a face naming a vertex not published is
 * left out, nothing published is nothing to show. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <stdint.h>
#include <sys/mman.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "meshprefix.h"

/* An n x n grid's vertices, then its cells as triangles and quads (one
 * in five a quad, some with relative indices): returns the text; *cut
 * gets, for each face k, the byte after its line (cut[k]). */
static char *grid_obj(int n, size_t *len, size_t **cut, int *nfaces)
{
    size_t cap = (size_t)n * n * 120 + 64;
    char *t = malloc(cap);
    size_t *c = malloc((size_t)2 * n * n * sizeof *c);
    cr_assert(t && c);
    size_t o = 0;
    int f = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            o += (size_t)snprintf(t + o, cap - o, "v %d %d %.3f\n", i, j, (double)((i * 7 + j * 3) % 11) / 10);
    for (int j = 0; j + 1 < n; j++)
        for (int i = 0; i + 1 < n; i++) {
            int a = j * n + i + 1;
            if ((i + j) % 5 == 0) {
                o += (size_t)snprintf(t + o, cap - o, "f %d %d %d %d\n", a, a + 1, a + n + 1, a + n);
                c[f++] = o;
            } else if ((i + j) % 5 == 1) {
                /* relative: counted back from the last vertex */
                int nv = n * n;
                o += (size_t)snprintf(t + o, cap - o, "f %d %d %d\n", a - nv - 1, a + n - nv - 1, a + 1 - nv - 1);
                c[f++] = o;
                o += (size_t)snprintf(t + o, cap - o, "f %d %d %d\n", a + 1, a + n, a + n + 1);
                c[f++] = o;
            } else {
                o += (size_t)snprintf(t + o, cap - o, "f %d %d %d\n", a, a + n, a + 1);
                c[f++] = o;
                o += (size_t)snprintf(t + o, cap - o, "f %d %d %d\n", a + 1, a + n, a + n + 1);
                c[f++] = o;
            }
        }
    *len = o;
    *cut = c;
    *nfaces = f;
    return t;
}

static void expect_same(const Mesh *a, const Mesh *b, const char *what)
{
    cr_assert_eq(a->nverts, b->nverts, "%s: vertices %u, the cut file %u", what, a->nverts, b->nverts);
    cr_assert_eq(a->nfaces, b->nfaces, "%s: faces %u, the cut file %u", what, a->nfaces, b->nfaces);
    cr_assert_eq(a->npoints, b->npoints, "%s: points", what);
    cr_expect(memcmp(a->pos, b->pos, 3 * sizeof(float) * a->nverts) == 0, "%s: positions", what);
    if (a->nfaces) {
        cr_expect(memcmp(a->face_start, b->face_start, sizeof(uint32_t) * (a->nfaces + 1)) == 0, "%s: starts", what);
        cr_expect(memcmp(a->corner, b->corner, sizeof(uint32_t) * a->face_start[a->nfaces]) == 0, "%s: corners",
                  what);
    }
    cr_expect_eq(a->info.triangles, b->info.triangles, "%s: triangles", what);
}

/* Load text with the writer held after `hold` faces ("/" exists: the
 * hold lets go at once, and nothing more is published), then compare
 * what was published with the cut file's mesh. */
static void check_hold(const char *text, size_t len, const size_t *cut, int hold, int threads, uint64_t piece)
{
    char what[96];
    snprintf(what, sizeof what, "held at %d faces, %d thread(s), pieces of %llu", hold, threads,
             (unsigned long long)piece);
    MeshPrefix *p = mesh_prefix_new(len);
    cr_assert_not_null(p);
    mesh_prefix_hold(p, (uint64_t)hold, "/");
    MeshLoadOpts lo = { .format = "obj", .threads = threads, .piece_bytes = piece, .prefix = p, .quiet = 1 };
    Mesh whole, pre, ref;
    char err[256];
    cr_assert_eq(mesh_parse_buffer_ex(&whole, "grid.obj", &lo, text, len, err, sizeof err), 0, "%s", err);
    uint64_t nv, nf;
    mesh_prefix_counts(p, &nv, &nf);
    cr_assert_eq(nf, (uint64_t)hold, "%s: %llu faces published", what, (unsigned long long)nf);
    cr_assert_eq(mesh_prefix_take(p, "grid.obj", &pre), 0, "%s", what);
    cr_assert_eq(mesh_parse(&ref, "grid.obj", text, cut[hold - 1], err, sizeof err), 0, "%s", err);
    expect_same(&pre, &ref, what);
    mesh_free(&whole);
    mesh_free(&pre);
    mesh_free(&ref);
    mesh_prefix_free(p);
}

Test(meshprefix, held_prefix_is_the_cut_file)
{
    size_t len, *cut;
    int nf;
    /* 200 x 200: past 64k lines, where the serial parse publishes */
    char *text = grid_obj(200, &len, &cut, &nf);
    check_hold(text, len, cut, 10000, 1, 0);
    for (int k = 0; k < 4; k++) {
        const int holds[4] = { 1, 17, nf / 2 + 1, nf - 1 };
        check_hold(text, len, cut, holds[k], 2, 65536);
        check_hold(text, len, cut, holds[k], 3, 100000);
    }
    free(cut);
    free(text);
}

/* A hand-made mesh, as a loader holds it while parsing. */
static Mesh tri_mesh(float *pos, uint32_t nverts, uint32_t *start, uint32_t *corner, uint32_t nfaces)
{
    Mesh m = { .nverts = nverts, .pos = pos, .nfaces = nfaces, .face_start = start, .corner = corner };
    return m;
}

Test(meshprefix, vertices_alone_are_points)
{
    float pos[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    MeshPrefix *p = mesh_prefix_new(1000);
    cr_assert_not_null(p);
    Mesh pre, ref, m = tri_mesh(pos, 3, NULL, NULL, 0);
    cr_expect_eq(mesh_prefix_take(p, "x.obj", &pre), 1, "nothing published: nothing to show");
    mesh_prefix_publish(p, &m, 0);
    cr_assert_eq(mesh_prefix_take(p, "x.obj", &pre), 0);
    char err[256];
    const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    cr_assert_eq(mesh_parse(&ref, "x.obj", text, strlen(text), err, sizeof err), 0, "%s", err);
    cr_expect_eq(pre.npoints, 3);
    expect_same(&pre, &ref, "three vertices");
    mesh_free(&pre);
    mesh_free(&ref);
    mesh_prefix_free(p);
}

Test(meshprefix, faces_past_the_vertices_are_left_out)
{
    float pos[12] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0 };
    uint32_t start[4] = { 0, 3, 6, 9 };
    /* the second face names vertex 7, not (yet) there */
    uint32_t corner[9] = { 0, 1, 2, 1, 7, 2, 1, 3, 2 };
    MeshPrefix *p = mesh_prefix_new(1000);
    cr_assert_not_null(p);
    Mesh pre, m = tri_mesh(pos, 4, start, corner, 3);
    mesh_prefix_publish(p, &m, 9);
    cr_assert_eq(mesh_prefix_take(p, "x.obj", &pre), 0);
    cr_expect_eq(pre.nfaces, 2, "the face naming vertex 7 is left out: %u faces", pre.nfaces);
    cr_expect_eq(pre.corner[3], 1);
    cr_expect_eq(pre.corner[4], 3);
    mesh_free(&pre);
    /* more published later: only what is new is added */
    float pos2[24] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0, 2, 1, 0, 3, 0, 0, 3, 1, 0 };
    uint32_t start2[5] = { 0, 3, 6, 9, 12 };
    uint32_t corner2[12] = { 0, 1, 2, 1, 7, 2, 1, 3, 2, 4, 5, 6 };
    m = tri_mesh(pos2, 8, start2, corner2, 4);
    mesh_prefix_publish(p, &m, 12);
    cr_assert_eq(mesh_prefix_take(p, "x.obj", &pre), 0);
    cr_expect_eq(pre.nfaces, 4, "vertex 7 is there now: %u faces", pre.nfaces);
    mesh_free(&pre);
    mesh_prefix_free(p);
}

/* Resident pages of [a, a + len) (whole pages inside it). */
static size_t resident_pages(const void *a, size_t len)
{
    uintptr_t page = 4096, s = ((uintptr_t)a + page - 1) & ~(page - 1), e = ((uintptr_t)a + len) & ~(page - 1);
    if (e <= s)
        return 0;
    size_t n = (e - s) / page, k = 0;
    unsigned char *v = malloc(n);
    cr_assert(v);
    cr_assert_eq(mincore((void *)s, e - s, v), 0);
    for (size_t i = 0; i < n; i++)
        k += v[i] & 1;
    free(v);
    return k;
}

/* Once the reader stops, the copy is given back at once (on the 31M
 * model it held up to 700 MB when the whole mesh arrived): the pages of
 * what was published are no longer resident, and a take has nothing. */
Test(meshprefix, stop_gives_the_copy_back)
{
    size_t len, *cut;
    int nf;
    char *text = grid_obj(300, &len, &cut, &nf);
    MeshPrefix *p = mesh_prefix_new(len);
    cr_assert_not_null(p);
    MeshLoadOpts lo = { .format = "obj", .threads = 1, .prefix = p, .quiet = 1 };
    Mesh whole, pre;
    char err[256];
    cr_assert_eq(mesh_parse_buffer_ex(&whole, "grid.obj", &lo, text, len, err, sizeof err), 0, "%s", err);
    uint64_t v, f;
    mesh_prefix_counts(p, &v, &f);
    /* published every 64k lines: the vertices' floats (the first
     * 50,000 of 90,000 are 600,000 bytes) sit at the mapping's start */
    cr_assert_geq(v, 50000, "vertices published: %llu", (unsigned long long)v);
    size_t maplen;
    const char *base = mesh_prefix_data(p, &maplen);
    cr_assert_gt(maplen, 500000);
    size_t before = resident_pages(base, 500000);
    cr_assert_geq(before, 100, "published pages resident: %zu", before);
    cr_assert_eq(mesh_prefix_take(p, "grid.obj", &pre), 0);
    mesh_free(&pre);
    mesh_prefix_stop(p);
    size_t after = resident_pages(base, 500000);
    cr_expect_eq(after, 0, "pages still resident after the stop: %zu of %zu", after, before);
    cr_expect_eq(mesh_prefix_take(p, "grid.obj", &pre), 1, "a take after the stop has nothing");
    mesh_free(&whole);
    mesh_prefix_free(p);
    free(text);
    free(cut);
}
