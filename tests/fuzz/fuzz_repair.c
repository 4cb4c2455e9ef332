/* fuzz_repair.c: repair_mesh (src/repair/) on whatever a file holds.
 * The first byte picks the format and the load, the second the repair:
 *
 *   byte 0  bits 0-2  format: obj stl ply off xyz, 5-7 = told by the content
 *           bit 3     lenient (skip what cannot be read) instead of strict
 *           bit 4     two threads (the check of the input on a helper)
 *           bit 5     --flip: every face wound the other way first
 *           bit 6     generated: no file, but a scene built from the
 *                     bytes that follow (gen_scene: cubes with faces
 *                     missing or flipped, triangles and quads on their
 *                     corners, copies of faces either way round, copies
 *                     of vertices, objects), on a coarse grid so that
 *                     points, edges and faces coincide
 *           bit 7     keep_checks: repair_mesh checks the input first
 *                     and hands over both checks
 *   byte 1  bits 0-4  the steps (REPAIR_*); 0 reads as REPAIR_DEFAULT
 *           bit 5     weld within 1/8 (positions within it made one)
 *           bit 6     --max-hole 6
 *           bit 7     no crossing test (before or after)
 *
 * A mesh that loads is checked, repaired and checked again. The repair
 * either fails with a message naming the input, or gives a mesh that
 * keeps every loader's promise (tl_mesh_broken) whose check is no worse
 * in any problem figure, object by object (with the crossing test,
 * unless it stopped on its budget either time); on small objects the
 * boundary and non-manifold edges are also counted by brute force here
 * (each corner pair against every other) and must not grow. The
 * report's "left" figures are the check's, its crossing pairs too
 * (counted again or, where the repair left the triangles the test reads
 * as they were, taken from the input's); with keep_checks, the checks
 * it hands over are figure for figure the ones made here (but the work
 * figure pair_tests). Aborts on the first thing that does not hold. */

#define _DEFAULT_SOURCE

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "mesh.h"
#include "meshcheck.h"
#include "repair.h"
#include "testlib.h"

static const char *const formats[] = { "obj", "stl", "ply", "off", "xyz" };

#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (!(cond)) {                                                                \
            fprintf(stderr, "fuzz_repair: %s:%d: %s\n", __FILE__, __LINE__, #cond);   \
            abort();                                                                  \
        }                                                                             \
    } while (0)

/* ==== Generated scenes (byte 0 bit 6) ==== */

typedef struct {
    char  *s;
    size_t n, cap;
    unsigned nv, nf, nfaces_max;
    unsigned face[256][4], nface_corners[256], nkept;
} Gen;

static void put(Gen *g, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static void put(Gen *g, const char *fmt, ...)
{
    char line[128];
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    if (g->n + (size_t)k + 1 > g->cap) {
        g->cap = (g->n + (size_t)k + 1) * 2;
        g->s = realloc(g->s, g->cap);
        CHECK(g->s);
    }
    memcpy(g->s + g->n, line, (size_t)k + 1);
    g->n += (size_t)k;
}

static void gen_face(Gen *g, unsigned n, const unsigned *v)
{
    put(g, "f");
    for (unsigned i = 0; i < n; i++)
        put(g, " %u", v[i] + 1);
    put(g, "\n");
    unsigned k = g->nf++ % 256;
    g->nface_corners[k] = n;
    memcpy(g->face[k], v, n * sizeof *v);
    g->nkept = g->nf < 256 ? g->nf : 256;
}

static const unsigned CUBE[6][4] = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 },
                                     { 2, 3, 7, 6 }, { 0, 4, 7, 3 }, { 1, 2, 6, 5 } };

/* Each op: a byte of kind, then its arguments. */
static char *gen_scene(const uint8_t *p, size_t n, size_t *len)
{
    Gen g = { 0 };
    size_t i = 0;
#define ARG() (i < n ? p[i++] : 0)
    for (unsigned ops = 0; i < n && ops < 256 && g.nf < 4000; ops++) {
        unsigned op = ARG();
        switch (op & 7) {
        case 0: {           /* a cube on the grid: side, face left out, faces flipped */
            unsigned a = ARG(), b = ARG(), flip = ARG(), v0 = g.nv, s = 1 + (a >> 6);
            for (unsigned k = 0; k < 8; k++) {
                /* the corners as the faces above name them: x goes 0 1 1 0 round each square */
                unsigned x = (k & 3) == 1 || (k & 3) == 2, y = (k & 3) >= 2, z = k >= 4;
                put(&g, "v %u %u %u\n", (a & 7) + s * x, ((a >> 3) & 7) + s * y, (b & 7) + s * z);
                g.nv++;
            }
            for (unsigned f = 0; f < 6; f++) {
                if (f == (op >> 3 & 7))
                    continue;
                unsigned q[4];
                for (unsigned k = 0; k < 4; k++)
                    q[k] = v0 + CUBE[f][flip >> f & 1 ? 3 - k : k];
                gen_face(&g, 4, q);
            }
            break;
        }
        case 1:             /* a triangle or a quad on vertices there are */
        case 2: {
            unsigned k = (op & 7) + 2, q[4];
            if (!g.nv)
                break;
            for (unsigned j = 0; j < k; j++)
                q[j] = ARG() % g.nv;
            gen_face(&g, k, q);
            break;
        }
        case 3: {           /* a vertex on the grid, halves allowed */
            unsigned x = ARG() & 31, y = ARG() & 31, z = ARG() & 31;
            put(&g, "v %g %g %g\n", x / 2.0, y / 2.0, z / 2.0);
            g.nv++;
            break;
        }
        case 4:             /* a face again, either way round */
        case 5: {
            if (!g.nkept)
                break;
            unsigned k = ARG() % g.nkept, c = g.nface_corners[k], q[4];
            for (unsigned j = 0; j < c; j++)
                q[j] = g.face[k][(op & 7) == 5 ? c - 1 - j : j];
            gen_face(&g, c, q);
            break;
        }
        case 6:
            put(&g, "o part%u\n", ops);
            break;
        case 7: {           /* a vertex lifted off the grid a little */
            unsigned x = ARG() & 15, frac = ARG() % 1000, y = ARG() & 15, z = ARG() & 15;
            put(&g, "v %u.%03u %u %u\n", x, frac, y, z);
            g.nv++;
            break;
        }
        }
    }
#undef ARG
    if (!g.nf) {
        free(g.s);
        return NULL;
    }
    *len = g.n;
    return g.s;
}

/* ==== Counting ==== */

static int same_pos(const Mesh *m, uint32_t a, uint32_t b)
{
    const float *p = m->pos + 3 * (size_t)a, *q = m->pos + 3 * (size_t)b;
    return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
}

/* Boundary and non-manifold edges of faces [f0, f1) by brute force
 * (every face's edges: degenerate faces too, which the check sets
 * aside, so the counts are not the check's but must not grow either). */
static int brute(const Mesh *m, uint32_t f0, uint32_t f1, uint32_t *boundary, uint32_t *nonmanifold)
{
    uint32_t c0 = m->face_start[f0], c1 = m->face_start[f1];
    if (c1 - c0 > 600)
        return 0;
    *boundary = *nonmanifold = 0;
    for (uint32_t f = f0; f < f1; f++)
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++) {
            uint32_t d = c + 1 < m->face_start[f + 1] ? c + 1 : m->face_start[f];
            uint32_t a = m->corner[c], b = m->corner[d], n = 0, first = 1;
            if (same_pos(m, a, b))
                continue;
            for (uint32_t g = f0; g < f1; g++)
                for (uint32_t e = m->face_start[g]; e < m->face_start[g + 1]; e++) {
                    uint32_t e2 = e + 1 < m->face_start[g + 1] ? e + 1 : m->face_start[g];
                    uint32_t x = m->corner[e], y = m->corner[e2];
                    if ((same_pos(m, x, a) && same_pos(m, y, b)) || (same_pos(m, x, b) && same_pos(m, y, a))) {
                        n++;
                        first &= e >= c;
                    }
                }
            if (first) {
                *boundary += n == 1;
                *nonmanifold += n >= 3;
            }
        }
    return 1;
}

/* Every figure of a the same as b's (but the crossing test's work; and
 * its bound figures when a count stopped on its budget). */
static int same_check(const MeshCheck *a, const MeshCheck *b, int unsure)
{
    if (a->nobjs != b->nobjs)
        return 0;
    for (uint32_t i = 0; i <= a->nobjs; i++) {
        const CheckCounts *x = i < a->nobjs ? &a->objs[i].c : &a->file, *y = i < a->nobjs ? &b->objs[i].c : &b->file;
        for (int k = 0; k < check_nrows; k++) {
            const CheckRow *r = &check_rows[k];
            if (!strcmp(r->field, "pair_tests") ||
                (unsure && (r->bound || !strcmp(r->field, "intersections_stopped"))))
                continue;
            if (meshcheck_value(r, x) != meshcheck_value(r, y)) {
                fprintf(stderr, "fuzz_repair: a check handed over differs: %s %llu, counted %llu\n", r->field,
                        (unsigned long long)meshcheck_value(r, x), (unsigned long long)meshcheck_value(r, y));
                return 0;
            }
        }
    }
    return 1;
}

/* Is the problem figure of row r worse in after than in before? */
static int worse(const CheckRow *r, const CheckCounts *before, const CheckCounts *after)
{
    if (r->bad == CHECK_FINE)
        return 0;
    if (meshcheck_bad(r, after) && !meshcheck_bad(r, before))
        return 1;
    return r->bad == CHECK_BAD_SET && meshcheck_value(r, after) > meshcheck_value(r, before);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2)
        return 0;
    unsigned sel = data[0], how = data[1];
    MeshLoadOpts lo = { .format = (sel & 7) < 5 ? formats[sel & 7] : NULL, .strict = !(sel & 8), .quiet = 1,
                        .max_polys = 20000 };
    const uint8_t *file = data + 2;
    size_t flen = size - 2;
    char *gen = NULL, err[512];
    if (sel & 64) {
        if (!(gen = gen_scene(data + 2, size - 2, &flen)))
            return 0;
        file = (const uint8_t *)gen;
        lo.format = "obj";
    }
    Mesh m;
    int bad = mesh_parse_buffer_ex(&m, NULL, &lo, file, flen, err, sizeof err);
    free(gen);
    if (bad)
        return 0;
    if (sel & 32)
        mesh_flip_winding(&m);
    int cross = !(how & 128), threads = sel & 16 ? 2 : 1;
    RepairOpts ro = { .steps = how & 31 ? how & 31 : REPAIR_DEFAULT, .weld_eps = how & 32 ? 0.125 : 0,
                      .max_hole = how & 64 ? 6 : 0, .threads = threads, .intersections = cross,
                      .keep_checks = (sel & 128) != 0 };
    CheckOpts co = { .threads = threads, .intersections = cross };
    MeshCheck before, after;
    CHECK(meshcheck_run(&before, &m, &co, err, sizeof err) == 0);
    uint32_t nobjs = m.nobjs, *bb = calloc(2 * (size_t)nobjs + 1, sizeof *bb);
    uint8_t *small = calloc((size_t)nobjs + 1, 1);
    CHECK(bb && small);
    for (uint32_t i = 0; i < nobjs; i++)
        small[i] = (uint8_t)brute(&m, m.objs[i].face_first, m.objs[i].face_first + m.objs[i].face_count, &bb[2 * i],
                                  &bb[2 * i + 1]);
    RepairReport rep;
    if (repair_mesh(&m, &ro, &rep, err, sizeof err)) {
        /* refused: with a reason, naming the input */
        CHECK(!strncmp(err, "(input): ", 9) && strlen(err) > 9);
        meshcheck_free(&before);
        free(bb);
        free(small);
        mesh_free(&m);
        return 0;
    }
    const char *broken = tl_mesh_broken(&m);
    if (broken)
        fprintf(stderr, "fuzz_repair: the repaired mesh breaks: %s\n", broken);
    CHECK(!broken);
    CHECK(m.nobjs == nobjs && rep.faces_after == m.nfaces && rep.verts_after == m.nverts);
    CHECK(rep.nholes <= rep.open && rep.open_too_big <= rep.open);
    for (uint32_t i = 0; i < rep.nholes; i++)
        CHECK(rep.holes[i].object < m.nobjs && rep.holes[i].vertex < m.nverts && rep.holes[i].edges > 0);
    CHECK(meshcheck_run(&after, &m, &co, err, sizeof err) == 0);
    int unsure = before.file.intersections_stopped || after.file.intersections_stopped;
    for (uint32_t i = 0; i < nobjs; i++)
        for (int k = 0; k < check_nrows; k++) {
            const CheckRow *r = &check_rows[k];
            if (unsure && (r->bound || !strcmp(r->field, "intersections_stopped")))
                continue;
            if (worse(r, &before.objs[i].c, &after.objs[i].c)) {
                fprintf(stderr, "fuzz_repair: object %u: %s worse: %llu -> %llu\n", i, r->field,
                        (unsigned long long)meshcheck_value(r, &before.objs[i].c),
                        (unsigned long long)meshcheck_value(r, &after.objs[i].c));
                abort();
            }
        }
    /* with the degenerate faces gone (the brute count takes them in), no
     * edge of the brute count has more faces than before */
    for (uint32_t i = 0; i < nobjs && (ro.steps & REPAIR_CLEAN); i++) {
        uint32_t b, n;
        if (small[i] && brute(&m, m.objs[i].face_first, m.objs[i].face_first + m.objs[i].face_count, &b, &n))
            CHECK(n <= bb[2 * i + 1] || before.objs[i].c.degenerate_faces);
    }
    CHECK(rep.left_holes == after.file.holes && rep.left_nm_edges == after.file.nonmanifold_edges);
    CHECK(rep.left_duplicate == after.file.duplicate_faces && rep.left_degenerate == after.file.degenerate_faces);
    CHECK(rep.left_flipped == after.file.inconsistent_faces);
    if (cross && !unsure)
        CHECK(rep.left_crossings == after.file.self_intersections);
    if (ro.keep_checks) {
        CHECK(rep.has_before && rep.counted);
        CHECK(same_check(&rep.before, &before, unsure) && same_check(&rep.after, &after, unsure));
    }
    meshcheck_free(&before);
    meshcheck_free(&after);
    repair_report_free(&rep);
    free(bb);
    free(small);
    mesh_free(&m);
    return 0;
}
