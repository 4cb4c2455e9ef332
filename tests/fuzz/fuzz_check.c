/* fuzz_check.c: --check's analysis (src/check/) on whatever a file holds.
 * The first byte picks the format and the check's options, the rest is
 * the file:
 *
 *   bits 0-2   format: obj stl ply off xyz, 5-7 = told by the content
 *   bit 3      lenient (skip what cannot be read) instead of strict
 *   bit 4      the crossing tests on three threads instead of one
 *   bit 5      --flip: every face wound the other way
 *
 * The bytes go through mesh_parse_buffer_ex (no other file is opened);
 * a mesh that loads is checked with the lists kept (detail), and the
 * result must hold together: the per-face flags add up to the counts,
 * the lists name vertices and faces that exist, the file's figures are
 * its objects' summed, the verdict agrees with meshcheck_sound, and the
 * check without the lists, and on another number of threads, gives the
 * same figures. Small meshes are also counted by brute force here (the
 * boundary and non-manifold edges, each pair of corners against every
 * other). Aborts on the first thing that does not hold. */

#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "mesh.h"
#include "meshcheck.h"

static const char *const formats[] = { "obj", "stl", "ply", "off", "xyz" };

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "fuzz_check: %s:%d: %s\n", __FILE__, __LINE__, #cond);   \
            abort();                                                                 \
        }                                                                            \
    } while (0)

/* The figures that must not depend on threads or on the lists. */
static int same_counts(const CheckCounts *a, const CheckCounts *b)
{
    return a->faces == b->faces && a->vertices == b->vertices && a->components == b->components &&
           a->boundary_edges == b->boundary_edges && a->holes == b->holes &&
           a->nonmanifold_edges == b->nonmanifold_edges && a->nonmanifold_vertices == b->nonmanifold_vertices &&
           a->inconsistent_faces == b->inconsistent_faces && a->nonorientable == b->nonorientable &&
           a->degenerate_faces == b->degenerate_faces && a->duplicate_faces == b->duplicate_faces &&
           a->unused_vertices == b->unused_vertices && a->self_intersections == b->self_intersections &&
           a->closed == b->closed && a->watertight == b->watertight && a->inside_out == b->inside_out &&
           a->has_volume == b->has_volume && !memcmp(&a->area, &b->area, sizeof a->area) &&
           !memcmp(&a->volume, &b->volume, sizeof a->volume);
}

/* obj: an object's figures; else a file's, where inside out means an
 * object is (and stays a problem) while another object may be open. */
static void check_counts(const CheckCounts *c, int obj)
{
    CHECK(c->holes <= c->boundary_edges);
    CHECK(!c->watertight || c->closed);
    CHECK(!c->has_volume || c->closed);
    CHECK(!obj || !c->inside_out || c->has_volume);
    CHECK(c->closed == (c->faces > 0 && c->boundary_edges == 0));
    CHECK(c->watertight == (c->closed && c->nonmanifold_edges == 0));
    CHECK(c->components <= c->faces);
    CHECK(c->degenerate_faces <= c->faces && c->duplicate_faces <= c->faces);
    CHECK(c->inconsistent_faces <= c->faces / 2 + 1);
    CHECK(c->area >= 0 && c->volume >= 0);
    CHECK(!c->has_volume || c->volume == c->volume);
    char item[CHECK_PROBLEMS_MAX][CHECK_PROBLEM_LEN], line[256];
    int k = meshcheck_problems(c, item, CHECK_PROBLEMS_MAX);
    CHECK(k <= CHECK_PROBLEMS_MAX);
    CHECK((k == 0) == meshcheck_sound(c));
    CHECK(meshcheck_verdict(c, line, sizeof line) == k);
    CHECK(strlen(line) < sizeof line);
}

/* One object: its flags add up to its counts, its lists are in range. */
static void check_object(const Mesh *m, const MeshCheck *mc, uint32_t i)
{
    const CheckObject *o = &mc->objs[i];
    const CheckCounts *c = &o->c;
    check_counts(c, 1);
    CHECK(o->face_first == m->objs[i].face_first && o->face_count == m->objs[i].face_count);
    CHECK(c->faces == o->face_count);
    uint32_t flipped = 0, degenerate = 0, duplicate = 0, nonorient = 0;
    for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++) {
        uint8_t fl = mc->face_flags[f];
        CHECK(fl < 1u << 7);
        CHECK(!(fl & CHECK_FLIPPED) || !(fl & CHECK_NONORIENT));
        flipped += (fl & CHECK_FLIPPED) != 0;
        degenerate += (fl & CHECK_DEGENERATE) != 0;
        duplicate += (fl & CHECK_DUPLICATE) != 0;
        nonorient += (fl & CHECK_NONORIENT) != 0;
        CHECK(mc->face_part[f] < c->components);
        CHECK(!(fl & CHECK_OPEN) || c->boundary_edges);
        CHECK(!(fl & CHECK_NONMANIFOLD) || c->nonmanifold_edges);
        CHECK(!(fl & CHECK_INTERSECTS) || c->self_intersections);
    }
    CHECK(flipped == c->inconsistent_faces);
    CHECK(degenerate == c->degenerate_faces);
    CHECK(duplicate == c->duplicate_faces);
    CHECK((nonorient > 0) == (c->nonorientable > 0));
    for (uint32_t k = 0; k < 2 * c->boundary_edges; k++)
        CHECK(o->boundary[k] < m->nverts);
    for (uint32_t k = 0; k < 2 * c->nonmanifold_edges; k++)
        CHECK(o->nm_edges[k] < m->nverts);
    for (uint32_t k = 0; k < c->nonmanifold_vertices; k++)
        CHECK(o->nm_verts[k] < m->nverts);
    CHECK(o->npairs == (c->self_intersections < CHECK_PAIRS_MAX ? c->self_intersections : CHECK_PAIRS_MAX));
    for (uint32_t k = 0; k < o->npairs; k++) {
        const uint32_t *p = o->pairs + 2 * k;
        CHECK(p[0] < p[1] && p[0] >= o->face_first && p[1] < o->face_first + o->face_count);
        CHECK(mc->face_flags[p[0]] & mc->face_flags[p[1]] & CHECK_INTERSECTS);
        CHECK(k == 0 || p[-2] < p[0] || (p[-2] == p[0] && p[-1] < p[1]));
    }
}

/* The file's figures are its objects' summed. */
static void check_file(const MeshCheck *mc)
{
    CheckCounts s = { 0 };
    for (uint32_t i = 0; i < mc->nobjs; i++) {
        const CheckCounts *c = &mc->objs[i].c;
        s.faces += c->faces;
        s.components += c->components;
        s.boundary_edges += c->boundary_edges;
        s.nonmanifold_edges += c->nonmanifold_edges;
        s.degenerate_faces += c->degenerate_faces;
        s.duplicate_faces += c->duplicate_faces;
        s.inconsistent_faces += c->inconsistent_faces;
        s.self_intersections += c->self_intersections;
    }
    const CheckCounts *f = &mc->file;
    check_counts(f, 0);
    CHECK(f->faces == s.faces && f->components == s.components && f->boundary_edges == s.boundary_edges);
    CHECK(f->nonmanifold_edges == s.nonmanifold_edges && f->degenerate_faces == s.degenerate_faces);
    CHECK(f->duplicate_faces == s.duplicate_faces && f->inconsistent_faces == s.inconsistent_faces);
    CHECK(f->self_intersections == s.self_intersections);
}

/* Same position (-0 = +0)? */
static int same_pos(const Mesh *m, uint32_t a, uint32_t b)
{
    const float *p = m->pos + 3 * (size_t)a, *q = m->pos + 3 * (size_t)b;
    return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
}

/* Brute force on a small object: each edge (two corners at different
 * positions, next in a face) against every other, counting the faces
 * on it; boundary and non-manifold edges as meshcheck counts them. */
static void brute_edges(const Mesh *m, const CheckObject *o)
{
    uint32_t c0 = m->face_start[o->face_first], c1 = m->face_start[o->face_first + o->face_count];
    if (c1 - c0 > 300)
        return;
    uint32_t boundary = 0, nonmanifold = 0;
    for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++)
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++) {
            uint32_t d = c + 1 < m->face_start[f + 1] ? c + 1 : m->face_start[f];
            uint32_t a = m->corner[c], b = m->corner[d];
            if (same_pos(m, a, b))
                continue;
            /* count the half-edges on {a, b}; this one speaks for its
             * edge when no earlier half-edge is on it */
            uint32_t n = 0, first = 1;
            for (uint32_t g = o->face_first; g < o->face_first + o->face_count; g++)
                for (uint32_t e = m->face_start[g]; e < m->face_start[g + 1]; e++) {
                    uint32_t e2 = e + 1 < m->face_start[g + 1] ? e + 1 : m->face_start[g];
                    uint32_t x = m->corner[e], y = m->corner[e2];
                    if ((same_pos(m, x, a) && same_pos(m, y, b)) || (same_pos(m, x, b) && same_pos(m, y, a))) {
                        n++;
                        if (e < c)
                            first = 0;
                    }
                }
            if (first) {
                boundary += n == 1;
                nonmanifold += n >= 3;
            }
        }
    CHECK(boundary == o->c.boundary_edges);
    CHECK(nonmanifold == o->c.nonmanifold_edges);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    unsigned sel = data[0];
    MeshLoadOpts opt = { .format = (sel & 7) < 5 ? formats[sel & 7] : NULL, .strict = !(sel & 8),
                         .quiet = 1, .max_polys = 100000 };
    Mesh m;
    char err[512];
    if (mesh_parse_buffer_ex(&m, NULL, &opt, data + 1, size - 1, err, sizeof err))
        return 0;
    if (sel & 32)
        mesh_flip_winding(&m);
    int threads = sel & 16 ? 3 : 1;
    CheckOpts co = { .threads = threads, .intersections = 1, .detail = 1 };
    MeshCheck mc, plain;
    CHECK(meshcheck_run(&mc, &m, &co, err, sizeof err) == 0);
    CHECK(mc.nobjs == m.nobjs);
    for (uint32_t i = 0; i < mc.nobjs; i++) {
        check_object(&m, &mc, i);
        brute_edges(&m, &mc.objs[i]);
    }
    check_file(&mc);
    /* no lists, the other number of threads: the same figures */
    co.detail = 0;
    co.threads = threads == 1 ? 3 : 1;
    CHECK(meshcheck_run(&plain, &m, &co, err, sizeof err) == 0);
    CHECK(plain.face_flags == NULL && plain.face_part == NULL);
    CHECK(same_counts(&plain.file, &mc.file));
    for (uint32_t i = 0; i < mc.nobjs; i++)
        CHECK(same_counts(&plain.objs[i].c, &mc.objs[i].c));
    meshcheck_free(&plain);
    meshcheck_free(&mc);
    mesh_free(&m);
    return 0;
}
