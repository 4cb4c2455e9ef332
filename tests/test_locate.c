/* test_locate.c: where the check says each problem is (CheckLocations,
 * src/check/locate.c), each location held to the problem it names by a
 * computation of its own here, on positions (points at one position
 * are one, as the check takes them):
 *
 *   - a hole's loop: every step (the last back to the first) is an edge
 *     that exactly one face uses, its points distinct, its perimeter the
 *     sum of its steps, and as many loops as holes;
 *   - a non-manifold edge: three or more faces use it, and the faces
 *     listed are exactly those;
 *   - a non-manifold vertex: a point whose faces fall into two fans or
 *     more (faces joined across the edges they share at it);
 *   - flipped faces: once every listed face is turned round, no edge of
 *     two faces is run twice the same way;
 *   - a degenerate face: its corners on one line; a duplicate face: the
 *     points of an earlier face;
 *   - a crossing pair: the point lies on a fan triangle of each face,
 *     within a millionth of the model's size.
 *
 * On meshes made here (a cube less a face, a cube with a face flipped,
 * two cubes sharing an edge or a corner, a duplicate and a degenerate
 * face, crossing triangles and quads, two holes touching at a point, a
 * sheet of many holes), on the bundled assets, and (make test-models)
 * on the teapot of ../shared/models: its 6 holes, 1 non-manifold vertex
 * and 161 crossing pairs. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "meshcheck.h"
#include "testlib.h"

static Mesh M;
static MeshCheck C;
static char E[512];

static void teardown(void)
{
    meshcheck_free(&C);
    mesh_free(&M);
}
TestSuite(locate, .fini = teardown);

/* ==== Building meshes ==== */

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

/* A cube of side s at (x, y, z) (testlib's); `skip` a face left out (-1
 * none), `flip` a mask of faces wound the other way. */
static void cube(float x, float y, float z, float s, int skip, unsigned flip)
{
    cr_assert_eq(tl_mesh_cube(&M, x, y, z, s, skip, flip, 0), 0);
}

static void run(uint32_t locations)
{
    cr_assert_eq(tl_mesh_finish(&M), 0);
    CheckOpts o = { .threads = 1, .intersections = 1, .locations = locations };
    cr_assert_eq(meshcheck_run(&C, &M, &o, E, sizeof E), 0, "%s", E);
}

/* ==== The reference: faces on positions ====
 *
 * Its own weld (the vertices sorted by position, -0 as +0) and its own
 * table of the steps faces take from point to point, sorted by edge,
 * for one object at a time: what uses an edge is a binary search. */

static int same_pos(const float *a, const float *b)
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];   /* -0 == +0, as the check welds */
}

static const float *corner_pos(const Mesh *m, uint32_t f, uint32_t k)
{
    return m->pos + 3 * (size_t)m->corner[m->face_start[f] + k];
}

static uint32_t corners(const Mesh *m, uint32_t f)
{
    return m->face_start[f + 1] - m->face_start[f];
}

/* Are face f's corners on one line (exactly, for the small coordinates
 * of these meshes; the check's own test is exact)? */
static int on_one_line(const Mesh *m, uint32_t f)
{
    uint32_t n = corners(m, f);
    const float *a = corner_pos(m, f, 0);
    for (uint32_t i = 1; i < n; i++) {
        const float *b = corner_pos(m, f, i);
        if (same_pos(a, b))
            continue;
        for (uint32_t j = 1; j < n; j++) {
            const float *c = corner_pos(m, f, j);
            double u[3], v[3];
            for (int k = 0; k < 3; k++) {
                u[k] = (double)b[k] - a[k];
                v[k] = (double)c[k] - a[k];
            }
            if (u[1] * v[2] - u[2] * v[1] != 0 || u[2] * v[0] - u[0] * v[2] != 0 || u[0] * v[1] - u[1] * v[0] != 0)
                return 0;
        }
        return 1;
    }
    return 1;
}

static int cmp_pos(const void *x, const void *y)
{
    const float *a = M.pos + 3 * (size_t)*(const uint32_t *)x, *b = M.pos + 3 * (size_t)*(const uint32_t *)y;
    for (int k = 0; k < 3; k++) {
        float p = a[k] + 0.0f, q = b[k] + 0.0f;    /* -0 as +0 */
        if (p != q)
            return p < q ? -1 : 1;
    }
    return 0;
}

typedef struct {
    uint32_t lo, hi;        /* the edge: its points, lo < hi */
    uint32_t face;
    int      fwd;           /* the face runs it lo -> hi */
} Step;

static int cmp_step(const void *x, const void *y)
{
    const Step *a = x, *b = y;
    if (a->lo != b->lo)
        return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi)
        return a->hi < b->hi ? -1 : 1;
    return a->face < b->face ? -1 : a->face > b->face;
}

typedef struct {
    uint32_t *sorted;       /* vertices by position */
    uint32_t *pt;           /* vertex -> its point */
    Step     *step;         /* the object's faces' steps, not degenerate faces', by edge */
    size_t    nstep;
} Ref;

static Ref R;

static void ref_free(void)
{
    free(R.sorted);
    free(R.pt);
    free(R.step);
    memset(&R, 0, sizeof R);
}

static void ref_build(const CheckObject *o)
{
    ref_free();
    R.sorted = malloc(((size_t)M.nverts + 1) * sizeof *R.sorted);
    R.pt = malloc(((size_t)M.nverts + 1) * sizeof *R.pt);
    for (uint32_t v = 0; v < M.nverts; v++)
        R.sorted[v] = v;
    qsort(R.sorted, M.nverts, sizeof *R.sorted, cmp_pos);
    for (uint32_t i = 0, id = 0; i < M.nverts; i++) {
        if (i && cmp_pos(&R.sorted[i - 1], &R.sorted[i]))
            id++;
        R.pt[R.sorted[i]] = id;
    }
    size_t cap = 0;
    for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++)
        cap += corners(&M, f);
    R.step = malloc((cap + 1) * sizeof *R.step);
    for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++) {
        if (on_one_line(&M, f))
            continue;
        uint32_t n = corners(&M, f);
        for (uint32_t k = 0; k < n; k++) {
            uint32_t a = R.pt[M.corner[M.face_start[f] + k]], b = R.pt[M.corner[M.face_start[f] + (k + 1) % n]];
            if (a != b)
                R.step[R.nstep++] = (Step){ a < b ? a : b, a < b ? b : a, f, a < b };
        }
    }
    qsort(R.step, R.nstep, sizeof *R.step, cmp_step);
}

/* The point at position p (CHECK_NONE: no vertex there). */
static uint32_t point_at(const float *p)
{
    size_t lo = 0, hi = M.nverts;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        const float *q = M.pos + 3 * (size_t)R.sorted[mid];
        int c = 0;
        for (int k = 0; k < 3 && !c; k++)
            c = q[k] + 0.0f < p[k] + 0.0f ? -1 : q[k] + 0.0f > p[k] + 0.0f ? 1 : 0;
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < M.nverts && same_pos(M.pos + 3 * (size_t)R.sorted[lo], p) ? R.pt[R.sorted[lo]] : UINT32_MAX;
}

/* The steps on the edge between points a and b: [*first, *first + n). */
static size_t steps_on(uint32_t a, uint32_t b, size_t *first)
{
    Step key = { a < b ? a : b, a < b ? b : a, 0, 0 };
    size_t lo = 0, hi = R.nstep;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (cmp_step(&R.step[mid], &key) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    size_t e = lo;
    while (e < R.nstep && R.step[e].lo == key.lo && R.step[e].hi == key.hi)
        e++;
    *first = lo;
    return e - lo;
}

static const CheckObject *object_of(uint32_t f)
{
    for (uint32_t i = 0; i < C.nobjs; i++)
        if (f >= C.objs[i].face_first && f < C.objs[i].face_first + C.objs[i].face_count)
            return &C.objs[i];
    return NULL;
}

static double dist(const float *a, const float *b)
{
    double s = 0;
    for (int k = 0; k < 3; k++)
        s += ((double)a[k] - b[k]) * ((double)a[k] - b[k]);
    return sqrt(s);
}

/* ==== Each kind against the reference ==== */

static void holes_hold(const CheckObject *o)
{
    const CheckLocations *l = &o->loc;
    for (uint32_t i = 0; i < l->nloops; i++) {
        uint32_t s = l->loop_start[i], e = l->loop_start[i + 1];
        cr_assert_geq(e - s, 3, "loop %u of %u points", i, e - s);
        double len = 0;
        for (uint32_t p = s; p < e; p++) {
            const float *a = l->loop_pt + 3 * (size_t)p, *b = l->loop_pt + 3 * (size_t)(p + 1 < e ? p + 1 : s);
            size_t first;
            size_t uses = steps_on(point_at(a), point_at(b), &first);
            cr_assert_eq(uses, 1, "loop %u step %u: (%g %g %g)-(%g %g %g) is used %zu times, not once", i, p - s,
                         a[0], a[1], a[2], b[0], b[1], b[2], uses);
            for (uint32_t q = s; q < p; q++)
                cr_assert(!same_pos(a, l->loop_pt + 3 * (size_t)q), "loop %u passes a point twice", i);
            len += dist(a, b);
        }
        cr_assert(fabs(len - l->loop_length[i]) <= 1e-9 * (len + 1), "loop %u: perimeter %.17g, steps sum to %.17g",
                  i, l->loop_length[i], len);
    }
}

static void nm_edges_hold(const CheckObject *o)
{
    const CheckLocations *l = &o->loc;
    for (uint32_t i = 0; i < l->nedges; i++) {
        size_t first, n = steps_on(point_at(l->edge_pt + 6 * (size_t)i), point_at(l->edge_pt + 6 * (size_t)i + 3),
                                   &first);
        cr_assert_geq(n, 3, "non-manifold edge %u has %zu faces", i, n);
        /* the faces on it, each once, in order (the steps are by face) */
        uint32_t k = l->edge_start[i];
        for (size_t j = first; j < first + n; j++) {
            if (j > first && R.step[j].face == R.step[j - 1].face)
                continue;
            cr_assert(k < l->edge_start[i + 1] && l->edge_face[k] == R.step[j].face,
                      "edge %u: face %u is on it but not listed where it should be", i, R.step[j].face);
            k++;
        }
        cr_assert_eq(k, l->edge_start[i + 1], "edge %u lists faces that are not on it", i);
    }
}

static uint32_t find(uint32_t *p, uint32_t i)
{
    while (p[i] != i)
        i = p[i] = p[p[i]];
    return i;
}

/* The faces at point x, in fans: joined when they share an edge at x.
 * Returns the number of fans. */
static uint32_t fans_at(const CheckObject *o, uint32_t x)
{
    uint32_t *uf = malloc(((size_t)o->face_count + 1) * sizeof *uf);
    uint8_t *at = calloc((size_t)o->face_count + 1, 1);
    for (uint32_t i = 0; i < o->face_count; i++)
        uf[i] = i;
    for (size_t j = 0; j < R.nstep; j++) {
        const Step *s = &R.step[j];
        if (s->lo != x && s->hi != x)
            continue;
        at[s->face - o->face_first] = 1;
        if (j > 0 && R.step[j - 1].lo == s->lo && R.step[j - 1].hi == s->hi)
            uf[find(uf, s->face - o->face_first)] = find(uf, R.step[j - 1].face - o->face_first);
    }
    uint32_t fans = 0;
    for (uint32_t i = 0; i < o->face_count; i++)
        fans += at[i] && find(uf, i) == i;
    free(uf);
    free(at);
    return fans;
}

static void nm_vertices_hold(const CheckObject *o)
{
    const CheckLocations *l = &o->loc;
    for (uint32_t i = 0; i < l->nverts; i++) {
        const float *x = l->vert_pt + 3 * (size_t)i;
        uint32_t p = point_at(x);
        cr_assert_neq(p, UINT32_MAX, "non-manifold vertex (%g %g %g) is no vertex", x[0], x[1], x[2]);
        uint32_t fans = fans_at(o, p);
        cr_assert_geq(fans, 2, "non-manifold vertex (%g %g %g): %u fans", x[0], x[1], x[2], fans);
    }
}

/* Every listed face turned round: no edge of two faces run twice the
 * same way (all of them listed: the caller asks for that many). */
static void flips_hold(const CheckObject *o)
{
    const CheckLocations *l = &o->loc;
    if (l->nfaces[0] < o->c.inconsistent_faces || o->c.nonorientable)
        return;
    uint8_t *flip = calloc((size_t)M.nfaces + 1, 1);
    for (uint32_t i = 0; i < l->nfaces[0]; i++)
        flip[l->face[0][i]] = 1;
    for (size_t j = 0; j < R.nstep;) {
        size_t first, n = steps_on(R.step[j].lo, R.step[j].hi, &first);
        if (n == 2) {
            const Step *a = &R.step[first], *b = &R.step[first + 1];
            int fa = a->fwd ^ flip[a->face], fb = b->fwd ^ flip[b->face];
            cr_assert_neq(fa, fb, "faces %u and %u run one edge the same way once the listed faces are flipped",
                          a->face, b->face);
        }
        j = first + n;
    }
    free(flip);
}

static void faces_hold(const CheckObject *o)
{
    const CheckLocations *l = &o->loc;
    for (uint32_t i = 0; i < l->nfaces[1]; i++)
        cr_assert(on_one_line(&M, l->face[1][i]), "face %u is listed as degenerate", l->face[1][i]);
    for (uint32_t i = 0; i < l->nfaces[2]; i++) {
        uint32_t f = l->face[2][i], n = corners(&M, f), found = 0;
        for (uint32_t g = o->face_first; g < f && !found; g++) {
            if (corners(&M, g) != n)
                continue;
            uint32_t all = 1;
            for (uint32_t a = 0; a < n && all; a++) {
                int in = 0;
                for (uint32_t b = 0; b < n && !in; b++)
                    in = same_pos(corner_pos(&M, f, a), corner_pos(&M, g, b));
                all = in;
            }
            found = all;
        }
        cr_assert(found, "face %u is listed as a duplicate, but no earlier face has its points", f);
    }
    /* listed faces are in order, each once, and of this object */
    for (int k = 0; k < 3; k++)
        for (uint32_t i = 0; i < l->nfaces[k]; i++) {
            cr_assert_eq(object_of(l->face[k][i]), o);
            cr_assert(i == 0 || l->face[k][i - 1] < l->face[k][i]);
        }
}

/* Distance from p to triangle (a, b, c), by the closest point. */
static double point_tri_dist(const double p[3], const float *a, const float *b, const float *c)
{
    double ab[3], ac[3], ap[3], best = INFINITY;
    for (int k = 0; k < 3; k++) {
        ab[k] = (double)b[k] - a[k];
        ac[k] = (double)c[k] - a[k];
        ap[k] = p[k] - a[k];
    }
    /* the projection inside the triangle, else the nearest edge */
    double d00 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2], d01 = ab[0] * ac[0] + ab[1] * ac[1] + ab[2] * ac[2];
    double d11 = ac[0] * ac[0] + ac[1] * ac[1] + ac[2] * ac[2];
    double d20 = ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2], d21 = ap[0] * ac[0] + ap[1] * ac[1] + ap[2] * ac[2];
    double den = d00 * d11 - d01 * d01;
    if (den > 0) {
        double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
        if (v >= 0 && w >= 0 && v + w <= 1) {
            double s = 0;
            for (int k = 0; k < 3; k++) {
                double q = a[k] + v * ab[k] + w * ac[k] - p[k];
                s += q * q;
            }
            return sqrt(s);
        }
    }
    const float *e[3][2] = { { a, b }, { b, c }, { c, a } };
    for (int i = 0; i < 3; i++) {
        double d[3], w[3], dd = 0, t = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = (double)e[i][1][k] - e[i][0][k];
            w[k] = p[k] - e[i][0][k];
            dd += d[k] * d[k];
            t += d[k] * w[k];
        }
        t = dd > 0 ? fmin(1, fmax(0, t / dd)) : 0;
        double s = 0;
        for (int k = 0; k < 3; k++)
            s += (w[k] - t * d[k]) * (w[k] - t * d[k]);
        best = fmin(best, sqrt(s));
    }
    return best;
}

/* How far p is from face f (its fan of triangles). */
static double face_dist(uint32_t f, const double p[3])
{
    double best = INFINITY;
    for (uint32_t k = 1; k + 1 < corners(&M, f); k++)
        best = fmin(best, point_tri_dist(p, corner_pos(&M, f, 0), corner_pos(&M, f, k), corner_pos(&M, f, k + 1)));
    return best;
}

static double model_size(void)
{
    double s = 0;
    for (int k = 0; k < 3; k++)
        s = fmax(s, (double)C.file.hi[k] - C.file.lo[k]);
    return s;
}

static void crossings_hold(const CheckObject *o)
{
    const CheckLocations *l = &o->loc;
    double tol = 1e-6 * model_size();
    for (uint32_t i = 0; i < l->npairs; i++) {
        uint32_t a = l->pair_face[2 * i], b = l->pair_face[2 * i + 1];
        const double *p = l->pair_pt + 3 * (size_t)i;
        cr_assert(a < b && object_of(a) == o && object_of(b) == o, "pair %u: faces %u %u", i, a, b);
        double da = face_dist(a, p), db = face_dist(b, p);
        cr_assert(da <= tol && db <= tol, "pair %u (faces %u, %u): the point (%g %g %g) is %g from one, %g from "
                                          "the other", i, a, b, p[0], p[1], p[2], da, db);
    }
}

/* Every location of every object holds, and each kind has
 * min(count, asked) of them. */
static void all_hold(uint32_t asked)
{
    for (uint32_t i = 0; i < C.nobjs; i++) {
        const CheckObject *o = &C.objs[i];
        ref_build(o);
        for (int k = 0; k < CHECK_LOC_KINDS; k++) {
            uint64_t total = meshcheck_loc_total(&o->c, (CheckLocKind)k);
            uint32_t n = meshcheck_loc_located(&o->loc, (CheckLocKind)k);
            cr_assert_eq(n, total < asked ? total : asked, "object %u kind %d: %u located of %llu, asked %u", i, k,
                         n, (unsigned long long)total, asked);
        }
        holes_hold(o);
        nm_edges_hold(o);
        nm_vertices_hold(o);
        flips_hold(o);
        faces_hold(o);
        crossings_hold(o);
    }
    ref_free();
}

/* ==== Meshes made here ==== */

Test(locate, nothing_unless_asked)
{
    start();
    cube(0, 0, 0, 1, 2, 0x8);
    run(0);
    cr_assert_eq(C.file.holes, 1);
    cr_assert_eq(C.file.inconsistent_faces, 1);
    for (int k = 0; k < CHECK_LOC_KINDS; k++)
        cr_assert_eq(meshcheck_loc_located(&C.objs[0].loc, (CheckLocKind)k), 0);
    cr_assert_null(C.objs[0].loc.loop_pt);
    cr_assert_null(C.objs[0].pairs, "no pairs kept for nothing");
}

Test(locate, cube_less_a_face_is_one_square_loop)
{
    start();
    cube(0, 0, 0, 2, 1, 0);     /* the top (z = 2) left out */
    run(100);
    const CheckLocations *l = &C.objs[0].loc;
    cr_assert_eq(l->nloops, 1);
    cr_assert_eq(l->loop_start[1] - l->loop_start[0], 4);
    cr_assert(fabs(l->loop_length[0] - 8) < 1e-12, "perimeter %g", l->loop_length[0]);
    for (uint32_t p = 0; p < 4; p++)
        cr_assert_eq(l->loop_pt[3 * p + 2], 2, "the loop is the open top");
    all_hold(100);
}

Test(locate, cube_with_a_flipped_face_names_it)
{
    start();
    cube(0, 0, 0, 1, -1, 1u << 4);
    run(100);
    const CheckLocations *l = &C.objs[0].loc;
    cr_assert_eq(l->nfaces[0], 1);
    cr_assert_eq(l->face[0][0], 4);
    all_hold(100);
}

Test(locate, four_flipped_of_six_is_the_other_two)
{
    start();
    cube(0, 0, 0, 1, -1, 0x0f);
    run(100);
    const CheckLocations *l = &C.objs[0].loc;
    cr_assert_eq(l->nfaces[0], 2);
    cr_assert_eq(l->face[0][0], 4);
    cr_assert_eq(l->face[0][1], 5);
    all_hold(100);
}

Test(locate, two_cubes_sharing_an_edge_list_its_four_faces)
{
    start();
    cube(0, 0, 0, 1, -1, 0);
    cube(1, 1, 0, 1, -1, 0);
    run(100);
    const CheckLocations *l = &C.objs[0].loc;
    cr_assert_eq(l->nedges, 1);
    cr_assert_eq(l->edge_start[1], 4);
    /* the edge from (1 1 0) to (1 1 1), either way round */
    const float *a = l->edge_pt, *b = l->edge_pt + 3;
    cr_assert(a[0] == 1 && a[1] == 1 && b[0] == 1 && b[1] == 1 && a[2] + b[2] == 1);
    all_hold(100);
}

Test(locate, two_cubes_touching_at_a_corner_name_it)
{
    start();
    cube(0, 0, 0, 1, -1, 0);
    cube(1, 1, 1, 1, -1, 0);
    run(100);
    const CheckLocations *l = &C.objs[0].loc;
    cr_assert_eq(l->nverts, 1);
    cr_assert(l->vert_pt[0] == 1 && l->vert_pt[1] == 1 && l->vert_pt[2] == 1);
    all_hold(100);
}

Test(locate, duplicate_and_degenerate_faces_by_index)
{
    start();
    cube(0, 0, 0, 1, -1, 0);
    uint32_t a = vert(0, 0, 0), b = vert(2, 0, 0), c = vert(5, 0, 0);
    tri(a, b, c);                           /* face 6: on one line */
    face(4, (uint32_t[]){ 1, 2, 6, 5 });    /* face 7: face 5 again */
    face(4, (uint32_t[]){ 6, 5, 1, 2 });    /* face 8: and again, turned */
    run(100);
    const CheckLocations *l = &C.objs[0].loc;
    cr_assert_eq(l->nfaces[1], 1);
    cr_assert_eq(l->face[1][0], 6);
    cr_assert_eq(l->nfaces[2], 2);
    cr_assert_eq(l->face[2][0], 7);
    cr_assert_eq(l->face[2][1], 8);
    all_hold(100);
}

Test(locate, crossing_triangles_meet_at_the_point_given)
{
    start();
    tri(vert(0, 0, 0), vert(4, 0, 0), vert(0, 4, 0));
    tri(vert(1, 1, -1), vert(1, 1, 3), vert(2, 1.5f, 1));
    /* a small one through a big one, whose edges pass its plane
     * outside it (at (11 0 0) and (11 3 0)) */
    tri(vert(10, 0, 0), vert(14, 0, 0), vert(10, 4, 0));
    tri(vert(11, 1, -1), vert(11, 1.25f, -1), vert(11, 1.125f, 1));
    run(100);
    const CheckLocations *l = &C.objs[0].loc;
    cr_assert_eq(l->npairs, 2);
    cr_assert_eq(l->pair_face[0], 0);
    cr_assert_eq(l->pair_face[1], 1);
    cr_assert_eq(l->pair_face[2], 2);
    cr_assert_eq(l->pair_face[3], 3);
    /* each pierces its big one's plane z = 0 */
    cr_assert(fabs(l->pair_pt[2]) < 1e-12, "z %g", l->pair_pt[2]);
    cr_assert(fabs(l->pair_pt[5]) < 1e-12 && l->pair_pt[4] > 1 && l->pair_pt[4] < 1.25, "(%g %g %g)", l->pair_pt[3],
              l->pair_pt[4], l->pair_pt[5]);
    all_hold(100);
}

Test(locate, crossing_quads_and_coplanar_overlaps)
{
    start();
    /* two quads through each other, split in fans */
    face(4, (uint32_t[]){ vert(0, 0, 0), vert(2, 0, 0), vert(2, 2, 0), vert(0, 2, 0) });
    face(4, (uint32_t[]){ vert(1, -1, -1), vert(1, 3, -1), vert(1, 3, 1), vert(1, -1, 1) });
    /* and two triangles of one plane overlapping, apart from them */
    tri(vert(10, 0, 0), vert(14, 0, 0), vert(10, 4, 0));
    tri(vert(11, 1, 0), vert(15, 1, 0), vert(11, 5, 0));
    run(100);
    const CheckLocations *l = &C.objs[0].loc;
    cr_assert_eq(l->npairs, 2);
    cr_assert_eq(l->pair_face[2], 2);
    cr_assert_eq(l->pair_face[3], 3);
    all_hold(100);
}

Test(locate, two_holes_touching_at_a_point_are_two_loops)
{
    start();
    /* a 3 x 3 quad grid less its two diagonal middle-corner cells: the
     * holes meet at the grid point (1, 1)... made as a 2 x 2 grid less
     * cells (0,0) and (1,1), whose boundary pinches at (1, 1) */
    uint32_t g[4][4];
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++)
            g[y][x] = vert((float)x, (float)y, 0);
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 3; x++)
            if (!((x == 1 && y == 1) || (x == 2 && y == 2)))
                face(4, (uint32_t[]){ g[y][x], g[y][x + 1], g[y + 1][x + 1], g[y + 1][x] });
    run(100);
    cr_assert_geq(C.file.holes, 2);
    cr_assert_eq(C.objs[0].loc.nloops, C.file.holes);
    all_hold(100);
}

Test(locate, many_holes_are_counted_whole_and_located_to_the_cap)
{
    start();
    /* a 9 x 9 grid of cells less every other cell of the odd rows and
     * columns: 16 square holes */
    uint32_t g[10][10];
    for (int y = 0; y < 10; y++)
        for (int x = 0; x < 10; x++)
            g[y][x] = vert((float)x, (float)y, 0);
    for (int y = 0; y < 9; y++)
        for (int x = 0; x < 9; x++)
            if (!(x % 2 && y % 2))
                face(4, (uint32_t[]){ g[y][x], g[y][x + 1], g[y + 1][x + 1], g[y + 1][x] });
    run(5);
    cr_assert_eq(C.file.holes, 17, "16 cells and the outline");
    cr_assert_eq(C.objs[0].loc.nloops, 5);
    all_hold(5);
}

Test(locate, objects_index_faces_across_the_file)
{
    start();
    cube(0, 0, 0, 1, -1, 0);
    cr_assert_eq(tl_mesh_object(&M, "b"), 0);
    cube(3, 0, 0, 1, -1, 1u << 2);
    run(100);
    cr_assert_eq(C.nobjs, 2);
    cr_assert_eq(C.objs[1].loc.nfaces[0], 1);
    cr_assert_eq(C.objs[1].loc.face[0][0], 6 + 2, "the second object's third face is the file's ninth");
    all_hold(100);
}

/* ==== Models ==== */

static void model_holds(const char *path, uint32_t asked)
{
    mesh_free(&M);
    meshcheck_free(&C);
    cr_assert_eq(mesh_load(&M, path, E, sizeof E), 0, "%s", E);
    CheckOpts o = { .threads = 2, .intersections = 1, .locations = asked };
    cr_assert_eq(meshcheck_run(&C, &M, &o, E, sizeof E), 0, "%s", E);
    all_hold(asked);
}

Test(locate, bundled_assets_hold, .timeout = 120)
{
    static const char *const assets[] = { "assets/cube.obj", "assets/concave.obj", "assets/cyclic.obj",
                                          "assets/demo.obj", "assets/knot.obj",    "assets/scene.obj",
                                          "assets/torus.obj", "assets/star-pierce.obj" };
    for (size_t i = 0; i < sizeof assets / sizeof *assets; i++)
        model_holds(assets[i], 1000);
}

Test(models, teapot_locations_hold, .timeout = 120)
{
    const char *p = tl_shared_model("teapot.obj");
    if (!p)
        cr_skip_test("no ../shared/models");
    char path[512];
    snprintf(path, sizeof path, "%s", p);
    model_holds(path, 1000);
    cr_assert_eq(C.file.holes, 6);
    cr_assert_eq(C.file.nonmanifold_vertices, 1);
    cr_assert_eq(C.file.self_intersections, 161);
    uint32_t loops = 0, pairs = 0;
    for (uint32_t i = 0; i < C.nobjs; i++) {
        loops += C.objs[i].loc.nloops;
        pairs += C.objs[i].loc.npairs;
    }
    cr_assert_eq(loops, 6);
    cr_assert_eq(pairs, 161);
}
