/* fuzz_check.c: --check's analysis (src/check/) on whatever a file holds.
 * The first byte picks the format and the check's options, the rest is
 * the file:
 *
 *   bits 0-2   format: obj stl ply off xyz, 5-7 = told by the content
 *   bit 3      lenient (skip what cannot be read) instead of strict
 *   bit 4      the crossing tests on three threads instead of one
 *   bit 5      --flip: every face wound the other way
 *   bit 7      locate the first 5 problems of each kind, not 1 (issue 30)
 *   bit 6      generated (issue 28): no file, but the inputs that once
 *              kept --check busy for hours, built from the next bytes
 *              (gen_obj): a planar fan around one vertex, coincident
 *              triangles, a fin on one edge, a coplanar stack, each of
 *              up to 4,096 triangles, moved, doubled and turned by the
 *              bytes after that. The crossing test must stay within its
 *              budget of pair tests, and say when it stopped.
 *
 * The bytes go through mesh_parse_buffer_ex (no other file is opened);
 * a mesh that loads is checked with the lists kept (detail), and the
 * result must hold together: the per-face flags add up to the counts,
 * the lists name vertices and faces that exist, the file's figures are
 * its objects' summed, the verdict agrees with meshcheck_sound, and the
 * check without the lists, and on another number of threads, gives the
 * same figures (the crossing pairs too, unless the budget stopped the
 * test: then the count is a lower bound, and where it stopped depends on
 * the threads). Small meshes are also counted by brute force here (the
 * boundary and non-manifold edges, each pair of corners against every
 * other, degenerate faces left out). Where the problems are (the first 1
 * or 5 of each kind) must be what the flags and lists say: each step of
 * a hole's loop an edge of the boundary list, the faces listed flagged
 * so. Aborts on the first thing that does not hold. */

#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../src/check/exact.h"
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
           a->unused_vertices == b->unused_vertices && a->intersections_stopped == b->intersections_stopped &&
           (a->intersections_stopped || a->self_intersections == b->self_intersections) &&
           a->pair_budget == b->pair_budget &&
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
    /* a file is closed when each object is: one of degenerate faces alone is not */
    CHECK(obj ? c->closed == (c->faces > c->degenerate_faces && c->boundary_edges == 0)
              : !c->closed || (c->faces > c->degenerate_faces && c->boundary_edges == 0));
    CHECK(c->watertight == (c->closed && c->nonmanifold_edges == 0));
    CHECK(c->components <= c->faces - c->degenerate_faces);
    /* the budget: a job adds its work every 4,096 tests, so each of the
     * (at most 3) threads may be that much past it */
    CHECK(c->pair_tests <= c->pair_budget + 3 * 8192);
    CHECK(c->intersections_stopped || c->pair_tests <= c->pair_budget);
    CHECK(!c->intersections_stopped || c->intersections_tested);
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
        CHECK(fl & CHECK_DEGENERATE ? mc->face_part[f] == UINT32_MAX : mc->face_part[f] < c->components);
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

/* Does the boundary (or non-manifold) list of o hold the edge between
 * positions a and b, either way? */
static int listed_edge(const Mesh *m, const uint32_t *list, uint32_t n, const float *a, const float *b)
{
    for (uint32_t k = 0; k < n; k++) {
        const float *p = m->pos + 3 * (size_t)list[2 * k], *q = m->pos + 3 * (size_t)list[2 * k + 1];
        int pa = p[0] == a[0] && p[1] == a[1] && p[2] == a[2], qb = q[0] == b[0] && q[1] == b[1] && q[2] == b[2];
        int pb = p[0] == b[0] && p[1] == b[1] && p[2] == b[2], qa = q[0] == a[0] && q[1] == a[1] && q[2] == a[2];
        if ((pa && qb) || (pb && qa))
            return 1;
    }
    return 0;
}

/* Where the problems are (CheckOpts.locations = want): of each kind the
 * first want of them, each what the lists and flags of the check say. */
static void check_locations(const Mesh *m, const MeshCheck *mc, uint32_t i, uint32_t want)
{
    const CheckObject *o = &mc->objs[i];
    const CheckLocations *l = &o->loc;
    const CheckCounts *c = &o->c;
    for (int k = 0; k < CHECK_LOC_KINDS; k++) {
        uint64_t total = meshcheck_loc_total(c, (CheckLocKind)k);
        CHECK(meshcheck_loc_located(l, (CheckLocKind)k) == (total < want ? total : want));
    }
    int small = c->boundary_edges + c->nonmanifold_edges <= 300;
    for (uint32_t h = 0; h < l->nloops; h++) {
        uint32_t s = l->loop_start[h], e = l->loop_start[h + 1];
        CHECK(e >= s + 3 && e - s <= c->boundary_edges);
        CHECK(l->loop_length[h] >= 0);
        for (uint32_t p = s; p < e && small; p++)
            CHECK(listed_edge(m, o->boundary, c->boundary_edges, l->loop_pt + 3 * (size_t)p,
                              l->loop_pt + 3 * (size_t)(p + 1 < e ? p + 1 : s)));
    }
    for (uint32_t k = 0; k < l->nedges; k++) {
        CHECK(!small || listed_edge(m, o->nm_edges, c->nonmanifold_edges, l->edge_pt + 6 * (size_t)k,
                                    l->edge_pt + 6 * (size_t)k + 3));
        CHECK(l->edge_start[k + 1] > l->edge_start[k]);
        for (uint32_t f = l->edge_start[k]; f < l->edge_start[k + 1]; f++) {
            CHECK(l->edge_face[f] >= o->face_first && l->edge_face[f] < o->face_first + o->face_count);
            CHECK(f == l->edge_start[k] || l->edge_face[f - 1] < l->edge_face[f]);
            CHECK(mc->face_flags[l->edge_face[f]] & CHECK_NONMANIFOLD);
        }
    }
    /* the points in the order of the detail's list */
    for (uint32_t k = 0; k < l->nverts; k++)
        CHECK(!memcmp(l->vert_pt + 3 * (size_t)k, m->pos + 3 * (size_t)o->nm_verts[k], 3 * sizeof(float)));
    static const uint8_t flag[3] = { CHECK_FLIPPED, CHECK_DEGENERATE, CHECK_DUPLICATE };
    for (int k = 0; k < 3; k++)
        for (uint32_t j = 0; j < l->nfaces[k]; j++) {
            uint32_t f = l->face[k][j];
            CHECK(f >= o->face_first && f < o->face_first + o->face_count && (mc->face_flags[f] & flag[k]));
            CHECK(j == 0 || l->face[k][j - 1] < f);
        }
    for (uint32_t k = 0; k < l->npairs; k++) {
        CHECK(l->pair_face[2 * k] == o->pairs[2 * k] && l->pair_face[2 * k + 1] == o->pairs[2 * k + 1]);
        for (int d = 0; d < 3; d++)
            CHECK(isfinite(l->pair_pt[3 * k + d]));
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

/* Are all of face f's corners on one line (exactly)? */
static int flat(const Mesh *m, uint32_t f)
{
    uint32_t s = m->face_start[f], e = m->face_start[f + 1], a = m->corner[s], b = a;
    for (uint32_t c = s + 1; c < e && same_pos(m, a, b); c++)
        b = m->corner[c];
    for (uint32_t c = s; c < e; c++)
        if (!exact_collinear(m->pos + 3 * (size_t)a, m->pos + 3 * (size_t)b, m->pos + 3 * (size_t)m->corner[c]))
            return 0;
    return 1;
}

/* Brute force on a small object: each edge (two corners at different
 * positions, next in a face) against every other, counting the faces
 * on it; boundary and non-manifold edges as meshcheck counts them (the
 * faces of one line, degenerate, have none). */
static void brute_edges(const Mesh *m, const CheckObject *o)
{
    uint32_t c0 = m->face_start[o->face_first], c1 = m->face_start[o->face_first + o->face_count];
    if (c1 - c0 > 300)
        return;
    uint32_t boundary = 0, nonmanifold = 0;
    uint8_t deg[300];
    for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++)
        deg[f - o->face_first] = (uint8_t)flat(m, f);
    for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++)
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1] && !deg[f - o->face_first]; c++) {
            uint32_t d = c + 1 < m->face_start[f + 1] ? c + 1 : m->face_start[f];
            uint32_t a = m->corner[c], b = m->corner[d];
            if (same_pos(m, a, b))
                continue;
            /* count the half-edges on {a, b}; this one speaks for its
             * edge when no earlier half-edge is on it */
            uint32_t n = 0, first = 1;
            for (uint32_t g = o->face_first; g < o->face_first + o->face_count; g++)
                for (uint32_t e = m->face_start[g]; e < m->face_start[g + 1] && !deg[g - o->face_first]; e++) {
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

/* ==== Generated inputs (bit 6) ==== */

typedef struct {
    char  *s;
    size_t n, cap;
} Text;

static void put(Text *t, const char *fmt, double a, double b, double c)
{
    char line[96];
    int k = snprintf(line, sizeof line, fmt, a, b, c);
    if (t->n + (size_t)k + 1 > t->cap) {
        t->cap = (t->n + (size_t)k + 1) * 2;
        t->s = realloc(t->s, t->cap);
        CHECK(t->s);
    }
    memcpy(t->s + t->n, line, (size_t)k + 1);
    t->n += (size_t)k;
}

/* An OBJ of p[0] kind (fan, coincident, fin, stack) and p[1..2] size (at
 * most 4,096 triangles); each later byte, one a triangle in turn, lifts
 * its far corner off the plane a little (bits 0-1), turns it (bit 2) or
 * doubles it (bit 3). */
static char *gen_obj(const uint8_t *p, size_t n, size_t *len)
{
    if (n < 3)
        return NULL;
    unsigned kind = p[0] & 3, tris = 1 + ((p[1] | (unsigned)p[2] << 8) & 4095);
    const uint8_t *mod = p + 3;
    size_t nmod = n - 3;
    Text t = { 0 };
    put(&t, "v %.9g %.9g %.9g\n", 0, 0, 0);
    put(&t, "v %.9g %.9g %.9g\n", 1, 0, 0);
    for (unsigned i = 0; i < tris; i++) {
        unsigned b = nmod ? mod[i % nmod] : 0;
        double lift = (b & 3) == 3 ? 1e-3 : (b & 3) == 2 ? 1e-30 : 0, a = 2 * M_PI * i / tris;
        double d = i * 1e-5;
        if (kind == 0)          /* fan around vertex 1 (the origin) */
            put(&t, "v %.9g %.9g %.9g\n", cos(a), sin(a), lift);
        else if (kind == 1)     /* the same triangle again */
            put(&t, "v %.9g %.9g %.9g\n", 0, 1, lift);
        else if (kind == 2)     /* a blade on edge 1-2 */
            put(&t, "v %.9g %.9g %.9g\n", 0.5, cos(a), sin(a) + lift);
        else                    /* the stack: (d, d), moved along */
            put(&t, "v %.9g %.9g %.9g\n", d, 1 + d, lift);
    }
    for (unsigned i = 0; i < tris; i++) {
        unsigned b = nmod ? mod[i % nmod] : 0, far = 3 + i, next = 3 + (i + 1) % tris;
        unsigned c[3] = { 1, 2, far };
        if (kind == 0)
            c[1] = far, c[2] = next;
        for (int k = 0; k < (b & 8 ? 2 : 1); k++) {
            if (b & 4)
                put(&t, "f %.0f %.0f %.0f\n", c[2], c[1], c[0]);
            else
                put(&t, "f %.0f %.0f %.0f\n", c[0], c[1], c[2]);
        }
    }
    *len = t.n;
    return t.s;
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
    const uint8_t *file = data + 1;
    size_t flen = size - 1;
    char *gen = NULL;
    if (sel & 64) {
        gen = gen_obj(data + 1, size - 1, &flen);
        if (!gen)
            return 0;
        file = (const uint8_t *)gen;
        opt.format = "obj";
    }
    int bad = mesh_parse_buffer_ex(&m, NULL, &opt, file, flen, err, sizeof err);
    free(gen);
    if (bad)
        return 0;
    if (sel & 32)
        mesh_flip_winding(&m);
    int threads = sel & 16 ? 3 : 1;
    uint32_t want = 1 + (sel >> 7) * 4;         /* where the first 1 or 5 of each kind are */
    CheckOpts co = { .threads = threads, .intersections = 1, .detail = 1, .locations = want };
    MeshCheck mc, plain;
    CHECK(meshcheck_run(&mc, &m, &co, err, sizeof err) == 0);
    CHECK(mc.nobjs == m.nobjs);
    for (uint32_t i = 0; i < mc.nobjs; i++) {
        check_object(&m, &mc, i);
        check_locations(&m, &mc, i, want);
        brute_edges(&m, &mc.objs[i]);
    }
    check_file(&mc);
    /* no lists, the other number of threads: the same figures */
    co.detail = 0;
    co.threads = threads == 1 ? 3 : 1;
    CHECK(meshcheck_run(&plain, &m, &co, err, sizeof err) == 0);
    CHECK(plain.face_flags == NULL && plain.face_part == NULL);
    CHECK(same_counts(&plain.file, &mc.file));
    for (uint32_t i = 0; i < mc.nobjs; i++) {
        CHECK(same_counts(&plain.objs[i].c, &mc.objs[i].c));
        /* located alike without the lists, which are not kept for it */
        const CheckLocations *a = &plain.objs[i].loc, *b = &mc.objs[i].loc;
        for (int k = 0; k < CHECK_LOC_KINDS; k++)
            CHECK(plain.objs[i].c.intersections_stopped ||
                  meshcheck_loc_located(a, (CheckLocKind)k) == meshcheck_loc_located(b, (CheckLocKind)k));
        CHECK(plain.objs[i].pairs == NULL && plain.objs[i].boundary == NULL);
        CHECK(a->nloops == 0 || !memcmp(a->loop_pt, b->loop_pt, 3 * sizeof(float) * a->loop_start[a->nloops]));
    }
    meshcheck_free(&plain);
    meshcheck_free(&mc);
    mesh_free(&m);
    return 0;
}
