/* fill.c: one loop triangulated, three ways.
 *
 * The dynamic program of Liepa ("Filling Holes in Meshes", SGP 2003,
 * after Barequet and Sharir's minimum-area triangulation of a polygon
 * in space, 1995): over every run i..j of the loop, the triangulation
 * that minimises first the largest dihedral angle between neighbouring
 * triangles (the faces around the loop included), then the area. O(n^3)
 * time and O(n^2) memory, so only for loops of up to RP_DP_MAX edges
 * and within RP_DP_BUDGET triangles tried over one repair. It follows a
 * twisted loop well, which a plane cannot.
 *
 * Ear clipping on the loop's best-fit plane (Newell's normal): the loop
 * projected, and a convex corner whose triangle holds no other corner
 * cut off until three are left (Meisters' two-ears theorem says a simple
 * polygon always has one). O(n^2); it fails when the projection is not
 * a simple polygon.
 *
 * A fan from a new vertex at the loop's centroid (moved along the
 * normal when a triangle would be degenerate or the point taken), for
 * any loop.
 *
 * None of them uses an edge the object already has between two loop
 * points (a third face on it), nor makes a degenerate triangle (decided
 * exactly); whether the fill crosses the model is fillcheck.c's. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

/* ==== The object's edges ==== */

struct EdgeSet {
    uint64_t *key;              /* smaller point << 32 | larger; UINT64_MAX empty */
    size_t    size;
};

static size_t edge_slot(const EdgeSet *es, uint64_t k)
{
    size_t mask = es->size - 1, h = (size_t)((k * 0x9E3779B97F4A7C15ull) >> 17) & mask;
    /* invariant: at most half full */
    while (es->key[h] != UINT64_MAX && es->key[h] != k)
        h = (h + 1) & mask;
    return h;
}

static uint64_t edge_key(uint32_t a, uint32_t b)
{
    return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
}

EdgeSet *rp_edges_new(const ObjTopo *t, const Rep *r)
{
    EdgeSet *es = calloc(1, sizeof *es);
    if (!es)
        return NULL;
    es->size = 64;
    while (es->size < 2 * (size_t)t->nc + 2)
        es->size *= 2;
    es->key = malloc(es->size * sizeof *es->key);
    if (!es->key) {
        free(es);
        return NULL;
    }
    memset(es->key, 0xff, es->size * sizeof *es->key);
    for (uint32_t c = 0; c < t->nc; c++)
        if (t->mate[c] != RP_SKIPPED && t->mate[c] != RP_SELF) {
            uint64_t k = edge_key(rp_cpt(r, t, c), rp_cpt(r, t, rp_next(r, t, c)));
            es->key[edge_slot(es, k)] = k;
        }
    return es;
}

int rp_edges_has(const EdgeSet *es, uint32_t a, uint32_t b)
{
    uint64_t k = edge_key(a, b);
    return es->key[edge_slot(es, k)] == k;
}

void rp_edges_free(EdgeSet *es)
{
    if (es)
        free(es->key);
    free(es);
}

/* ==== Shared ==== */

typedef struct {
    uint32_t        n;
    const uint32_t *pts, *vert, *face;
    double         (*p)[3];     /* positions */
} Loop;

static void tri_normal(const double *a, const double *b, const double *c, double nrm[3])
{
    double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    nrm[0] = u[1] * v[2] - u[2] * v[1];
    nrm[1] = u[2] * v[0] - u[0] * v[2];
    nrm[2] = u[0] * v[1] - u[1] * v[0];
}

static double norm3(const double *v)
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* Is the triangle of loop corners i, j, k degenerate (exactly)? */
static int tri_flat(const Rep *r, const Loop *lp, uint32_t i, uint32_t j, uint32_t k)
{
    return rp_collinear(rp_vpos(r, lp->vert[i]), rp_vpos(r, lp->vert[j]), rp_vpos(r, lp->vert[k]));
}

static int fill_room(Fill *f, uint32_t ntri)
{
    f->tri = malloc(3 * ((size_t)ntri + 1) * sizeof *f->tri);
    f->ntri = 0;
    return f->tri ? 0 : -1;
}

static void fill_tri(Fill *f, uint32_t a, uint32_t b, uint32_t c)
{
    f->tri[3 * f->ntri] = a;
    f->tri[3 * f->ntri + 1] = b;
    f->tri[3 * f->ntri + 2] = c;
    f->ntri++;
}

/* ==== Liepa's dynamic program ==== */

typedef struct {
    double   ang, area;         /* the largest (1 - cos dihedral), the area; ang < 0: none */
    double   nrm[3];            /* the unit normal of the run's top triangle */
    uint32_t apex;
} Cell;

/* Is the chord between loop corners i < j allowed (a loop edge, or an
 * edge the object does not have)? */
static int chord_ok(const Loop *lp, const EdgeSet *es, uint32_t i, uint32_t j)
{
    return j == i + 1 || (i == 0 && j == lp->n - 1) || !rp_edges_has(es, lp->pts[i], lp->pts[j]);
}

static double bend(const double *a, const double *b)
{
    return 1 - (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

/* The best triangle on run i..j given the runs inside it. */
static void dp_cell(const Rep *r, const Loop *lp, Cell *W, const double (*fn)[3], uint32_t i, uint32_t j)
{
    uint32_t n = lp->n;
    Cell *best = &W[i * n + j];
    best->ang = -1;
    for (uint32_t m = i + 1; m < j; m++) {
        const Cell *a = &W[i * n + m], *b = &W[m * n + j];
        if ((m > i + 1 && a->ang < 0) || (j > m + 1 && b->ang < 0))
            continue;
        double nrm[3];
        tri_normal(lp->p[i], lp->p[m], lp->p[j], nrm);
        double len = norm3(nrm);
        if (!(len > 0) || tri_flat(r, lp, i, m, j))
            continue;
        for (int k = 0; k < 3; k++)
            nrm[k] /= len;
        double ang = fmax(m > i + 1 ? a->ang : 0, j > m + 1 ? b->ang : 0);
        ang = fmax(ang, bend(nrm, m == i + 1 ? fn[i] : a->nrm));
        ang = fmax(ang, bend(nrm, j == m + 1 ? fn[m] : b->nrm));
        if (i == 0 && j == n - 1)
            ang = fmax(ang, bend(nrm, fn[n - 1]));
        double area = (m > i + 1 ? a->area : 0) + (j > m + 1 ? b->area : 0) + len / 2;
        if (best->ang < 0 || ang < best->ang || (ang == best->ang && area < best->area)) {
            best->ang = ang;
            best->area = area;
            memcpy(best->nrm, nrm, sizeof nrm);
            best->apex = m;
        }
    }
}

static int fill_dp(const Rep *r, const Loop *lp, const EdgeSet *es, Fill *f)
{
    uint32_t n = lp->n;
    Cell *W = malloc((size_t)n * n * sizeof *W);
    double (*fn)[3] = malloc((size_t)n * sizeof *fn);
    uint32_t *stack = malloc(2 * (size_t)n * sizeof *stack);
    int rc = -1;
    if (!W || !fn || !stack)
        goto out;
    for (uint32_t i = 0; i < n; i++) {
        rp_face_normal(r, lp->face[i], fn[i]);
        double len = norm3(fn[i]);
        for (int k = 0; k < 3; k++)
            fn[i][k] = len > 0 ? fn[i][k] / len : 0;
    }
    for (uint32_t len = 2; len < n; len++)
        for (uint32_t i = 0; i + len < n; i++) {
            uint32_t j = i + len;
            if (chord_ok(lp, es, i, j))
                dp_cell(r, lp, W, (const double (*)[3])fn, i, j);
            else
                W[i * n + j].ang = -1;
        }
    rc = 0;
    if (W[n - 1].ang < 0)
        goto out;
    if (fill_room(f, n - 2)) {
        rc = -1;
        goto out;
    }
    uint32_t top = 0;
    stack[top++] = 0;
    stack[top++] = n - 1;
    while (top) {
        uint32_t j = stack[--top], i = stack[--top], m = W[i * n + j].apex;
        fill_tri(f, lp->vert[i], lp->vert[m], lp->vert[j]);
        if (m > i + 1) {
            stack[top++] = i;
            stack[top++] = m;
        }
        if (j > m + 1) {
            stack[top++] = m;
            stack[top++] = j;
        }
    }
out:
    free(W);
    free(fn);
    free(stack);
    return rc;
}

/* ==== Ear clipping ==== */

/* Newell's normal of the loop, about its centroid (cen). */
static void loop_plane(const Loop *lp, double nrm[3], double cen[3])
{
    memset(cen, 0, 3 * sizeof *cen);
    for (uint32_t i = 0; i < lp->n; i++)
        for (int k = 0; k < 3; k++)
            cen[k] += lp->p[i][k] / lp->n;
    memset(nrm, 0, 3 * sizeof *nrm);
    for (uint32_t i = 0; i < lp->n; i++) {
        const double *a = lp->p[i], *b = lp->p[(i + 1) % lp->n];
        double ax = a[0] - cen[0], ay = a[1] - cen[1], az = a[2] - cen[2];
        double bx = b[0] - cen[0], by = b[1] - cen[1], bz = b[2] - cen[2];
        nrm[0] += ay * bz - az * by;
        nrm[1] += az * bx - ax * bz;
        nrm[2] += ax * by - ay * bx;
    }
}

static double orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

typedef struct {
    double   (*q)[2];           /* the corners projected */
    uint32_t *prev, *next;
} Ring;

/* Is corner i (between p and q) an ear: convex, its chord allowed, no
 * other corner in or on its triangle, not degenerate? */
static int is_ear(const Rep *r, const Loop *lp, const EdgeSet *es, const Ring *g, uint32_t i, uint64_t *work)
{
    uint32_t p = g->prev[i], q = g->next[i];
    if (orient2(g->q[p], g->q[i], g->q[q]) <= 0 || rp_edges_has(es, lp->pts[p], lp->pts[q]))
        return 0;
    for (uint32_t k = g->next[q]; k != p; k = g->next[k]) {
        ++*work;
        if (orient2(g->q[p], g->q[i], g->q[k]) >= 0 && orient2(g->q[i], g->q[q], g->q[k]) >= 0 &&
            orient2(g->q[q], g->q[p], g->q[k]) >= 0)
            return 0;
    }
    return !tri_flat(r, lp, p, i, q);
}

static int fill_ear(const Rep *r, const Loop *lp, const EdgeSet *es, uint64_t *budget, Fill *f)
{
    uint32_t n = lp->n;
    double nrm[3], cen[3], u[3], v[3], len;
    loop_plane(lp, nrm, cen);
    if (!((len = norm3(nrm)) > 0))
        return 0;
    for (int k = 0; k < 3; k++)
        nrm[k] /= len;
    double axis[3] = { 0, 0, 0 };
    axis[fabs(nrm[0]) <= fabs(nrm[1]) && fabs(nrm[0]) <= fabs(nrm[2]) ? 0 : fabs(nrm[1]) <= fabs(nrm[2]) ? 1 : 2] = 1;
    tri_normal((double[3]){ 0, 0, 0 }, axis, nrm, u);     /* u = axis x nrm */
    len = norm3(u);
    for (int k = 0; k < 3; k++)
        u[k] /= len;
    tri_normal((double[3]){ 0, 0, 0 }, nrm, u, v);        /* v = nrm x u: (u, v, nrm) right-handed */
    Ring g = { malloc((size_t)n * sizeof *g.q), malloc((size_t)n * sizeof *g.prev), malloc((size_t)n * sizeof *g.next) };
    int rc = -1;
    if (!g.q || !g.prev || !g.next || fill_room(f, n - 2))
        goto out;
    for (uint32_t i = 0; i < n; i++) {
        double d[3] = { lp->p[i][0] - cen[0], lp->p[i][1] - cen[1], lp->p[i][2] - cen[2] };
        g.q[i][0] = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
        g.q[i][1] = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
        g.prev[i] = (i + n - 1) % n;
        g.next[i] = (i + 1) % n;
    }
    uint64_t work = 0;
    uint32_t left = n, i = 0, tried = 0;
    while (left > 3 && tried < left && work <= *budget) {
        if (!is_ear(r, lp, es, &g, i, &work)) {
            i = g.next[i];
            tried++;
            continue;
        }
        uint32_t p = g.prev[i], q = g.next[i];
        fill_tri(f, lp->vert[p], lp->vert[i], lp->vert[q]);
        g.next[p] = q;
        g.prev[q] = p;
        left--;
        tried = 0;
        i = p;
    }
    *budget = work < *budget ? *budget - work : 0;
    rc = 0;
    if (left == 3 && !tri_flat(r, lp, g.prev[i], i, g.next[i]))
        fill_tri(f, lp->vert[g.prev[i]], lp->vert[i], lp->vert[g.next[i]]);
    else
        f->ntri = 0;
out:
    free(g.q);
    free(g.prev);
    free(g.next);
    return rc;
}

/* ==== The fan ==== */

static int fan_sound(const Rep *r, const Loop *lp, const float *c)
{
    for (uint32_t i = 0; i < lp->n; i++)
        if (rp_collinear(rp_vpos(r, lp->vert[i]), rp_vpos(r, lp->vert[(i + 1) % lp->n]), c))
            return 0;
    return 1;
}

static int fill_fan(Rep *r, const Loop *lp, Fill *f)
{
    double nrm[3], cen[3], size = 0;
    loop_plane(lp, nrm, cen);
    double len = norm3(nrm);
    for (uint32_t i = 0; i < lp->n; i++)
        for (int k = 0; k < 3; k++)
            size = fmax(size, fabs(lp->p[i][k] - cen[k]));
    float c[3];
    int found = 0;
    static const double lift[] = { 0, 1e-6, 1e-4, 1e-2, -1e-2 };
    for (size_t t = 0; t < sizeof lift / sizeof *lift && !found; t++) {
        for (int k = 0; k < 3; k++)
            c[k] = (float)(cen[k] + (len > 0 ? lift[t] * size * nrm[k] / len : 0));
        found = rp_point_find(r, c) == RP_NONE && fan_sound(r, lp, c);
    }
    if (!found)
        return 0;
    float rgb[3] = { 0, 0, 0 };
    for (uint32_t i = 0; r->w.rgb && i < lp->n; i++)
        for (int k = 0; k < 3; k++)
            rgb[k] += r->w.rgb[3 * (size_t)lp->vert[i] + k] / (float)lp->n;
    uint32_t v = rp_vertex_add(r, c, r->w.rgb ? rgb : NULL, lp->vert[0]);
    if (v == RP_NONE || fill_room(f, lp->n))
        return -1;
    for (uint32_t i = 0; i < lp->n; i++)
        fill_tri(f, lp->vert[i], lp->vert[(i + 1) % lp->n], v);
    return 0;
}

/* ==== One loop ==== */

int rp_fill_make(Rep *r, ObjTopo *t, const Loops *l, uint32_t k, FillMethod m, const EdgeSet *es,
                 uint64_t *dp_budget, Fill *f)
{
    (void)t;
    uint32_t s = l->start[k];
    Loop lp = { l->start[k + 1] - s, l->pts + s, l->vert + s, l->face + s, NULL };
    free(f->tri);
    f->tri = NULL;
    f->ntri = 0;
    f->loop = k;
    f->mat = mesh_face_mat(&r->w, lp.face[0]);
    lp.p = malloc(((size_t)lp.n + 1) * sizeof *lp.p);
    if (!lp.p)
        return -1;
    for (uint32_t i = 0; i < lp.n; i++)
        for (int j = 0; j < 3; j++)
            lp.p[i][j] = rp_vpos(r, lp.vert[i])[j];
    int rc = 0;
    uint64_t cost = (uint64_t)lp.n * lp.n * lp.n / 6 + 1;
    if (m == FILL_DP && cost <= *dp_budget) {
        *dp_budget -= cost;
        rc = fill_dp(r, &lp, es, f);
    } else if (m == FILL_EAR) {
        rc = fill_ear(r, &lp, es, dp_budget, f);
    } else if (m == FILL_FAN) {
        rc = fill_fan(r, &lp, f);
    }
    free(lp.p);
    if (rc || !f->ntri) {
        free(f->tri);
        f->tri = NULL;
        f->ntri = 0;
    }
    return rc;
}
