/* locate.c: where each problem is (CheckOpts.locations), as the passes
 * leave what they found: the first `locations` problems of each kind of
 * one object into its CheckLocations, for --check --json, the text
 * report and the viewer's problem keys. Nothing here runs unless asked.
 *
 * Holes are the independent cycles of the graph of boundary edges, as
 * topo.c counts them (edges - points + connected pieces): a spanning
 * forest of the graph by breadth-first search from the points in corner
 * order, and each edge left out of it closes one loop, the edge and the
 * two paths from its ends to where they meet. A lone loop is then the
 * loop itself, two loops touching at a point are two, and the count is
 * topo.c's exactly. A point on two crossing faces is the mean of where
 * each edge of one passes through the other (their common part is
 * convex, so the mean of points of it is in it), or, for faces in one
 * plane, of the corners of each inside the other and the crossings of
 * their edges. */

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_internal.h"
#include "exact.h"
#include "grow.h"

/* ==== Growing lists ==== */

static int push_floats(float **a, size_t *n, size_t *cap, const float *v, size_t k)
{
    if (grow_size((void **)a, cap, *n + k, sizeof **a))
        return -1;
    memcpy(*a + *n, v, k * sizeof **a);
    *n += k;
    return 0;
}

static uint32_t located_max(const ObjCheck *o)
{
    return o->opt->locations;
}

/* ==== Holes ==== */

/* The boundary graph of one object: its edges (two points each, in
 * corner order) and, per point, the edges at it. */
typedef struct {
    uint32_t  ne;
    uint32_t *end;              /* 2 per edge: the object's points */
    uint32_t *off;              /* npts + 1: point p's edges are at[off[p] .. off[p + 1]) */
    uint32_t *at;
    uint32_t *parent;           /* per point: its parent in the forest, CHECK_NONE a root or unseen */
    uint32_t *depth;            /* per point: steps from its root; CHECK_NONE unseen */
    uint8_t  *done;             /* per edge: taken into the forest or closed a loop */
    uint32_t *queue;
} Bgraph;

static void bgraph_free(Bgraph *g)
{
    free(g->end);
    free(g->off);
    free(g->at);
    free(g->parent);
    free(g->depth);
    free(g->done);
    free(g->queue);
}

static int bgraph_build(const ObjCheck *o, Bgraph *g)
{
    uint32_t np = o->npts, ne = o->c->boundary_edges;
    g->ne = 0;
    g->end = malloc(2 * ((size_t)ne + 1) * sizeof *g->end);
    g->off = calloc((size_t)np + 2, sizeof *g->off);
    g->at = malloc(2 * ((size_t)ne + 1) * sizeof *g->at);
    g->parent = malloc(((size_t)np + 1) * sizeof *g->parent);
    g->depth = malloc(((size_t)np + 1) * sizeof *g->depth);
    g->done = calloc((size_t)ne + 1, 1);
    g->queue = malloc(((size_t)np + 1) * sizeof *g->queue);
    if (!g->end || !g->off || !g->at || !g->parent || !g->depth || !g->done || !g->queue)
        return -1;
    for (uint32_t c = 0; c < o->nc && g->ne < ne; c++)
        if (o->mate[c] == MATE_BOUNDARY) {
            uint32_t a = oc_pt(o, c), b = oc_pt(o, oc_next(o, c));
            g->end[2 * g->ne] = a;
            g->end[2 * g->ne + 1] = b;
            g->off[a + 2]++;
            g->off[b + 2]++;
            g->ne++;
        }
    /* one boundary half-edge per boundary edge (topo.c counted them so) */
    ZV_ASSERT(g->ne == ne);
    for (uint32_t p = 0; p < np; p++)
        g->off[p + 2] += g->off[p + 1];
    for (uint32_t e = 0; e < g->ne; e++)
        for (int k = 0; k < 2; k++)
            g->at[g->off[g->end[2 * e + k] + 1]++] = e;
    memset(g->parent, 0xff, ((size_t)np + 1) * sizeof *g->parent);
    memset(g->depth, 0xff, ((size_t)np + 1) * sizeof *g->depth);
    return 0;
}

typedef struct {
    size_t npt, cappt, nstart, capstart;
    uint32_t *path;             /* scratch: the second half of a loop, reversed */
    uint64_t  work;             /* points written so far: bounded (see loop_budget) */
} LoopOut;

/* Write the loop that edge (u, w) closes: u up to where the two paths
 * meet, then down to w. */
static int loop_emit(ObjCheck *o, const Bgraph *g, LoopOut *lo, uint32_t u, uint32_t w)
{
    CheckLocations *l = &o->out->loc;
    uint32_t a = u, b = w, nb = 0;
    size_t first = lo->npt;
    double len = 0;
    const float *prev = NULL, *p0 = NULL;
    while (g->depth[b] > g->depth[a]) {
        lo->path[nb++] = b;
        b = g->parent[b];
    }
    for (;;) {
        const float *p = oc_vpos(o, o->prep[a]);
        if (push_floats(&l->loop_pt, &lo->npt, &lo->cappt, p, 3))
            return -1;
        if (prev)
            len += sqrt(((double)p[0] - prev[0]) * ((double)p[0] - prev[0]) +
                        ((double)p[1] - prev[1]) * ((double)p[1] - prev[1]) +
                        ((double)p[2] - prev[2]) * ((double)p[2] - prev[2]));
        else
            p0 = p;
        prev = p;
        if (a == b)
            break;
        if (g->depth[a] > g->depth[b]) {
            a = g->parent[a];
        } else {
            /* at one depth and apart: both climb */
            lo->path[nb++] = b;
            b = g->parent[b];
            a = g->parent[a];
        }
    }
    while (nb > 0) {
        const float *p = oc_vpos(o, o->prep[lo->path[--nb]]);
        if (push_floats(&l->loop_pt, &lo->npt, &lo->cappt, p, 3))
            return -1;
        len += sqrt(((double)p[0] - prev[0]) * ((double)p[0] - prev[0]) +
                    ((double)p[1] - prev[1]) * ((double)p[1] - prev[1]) +
                    ((double)p[2] - prev[2]) * ((double)p[2] - prev[2]));
        prev = p;
    }
    len += sqrt(((double)p0[0] - prev[0]) * ((double)p0[0] - prev[0]) +
                ((double)p0[1] - prev[1]) * ((double)p0[1] - prev[1]) +
                ((double)p0[2] - prev[2]) * ((double)p0[2] - prev[2]));
    lo->work += (lo->npt - first) / 3;
    l->loop_length[l->nloops] = len;
    l->nloops++;
    return check_push(&l->loop_start, &lo->nstart, &lo->capstart, (uint32_t)(lo->npt / 3));
}

/* Breadth first from root: tree edges, and a loop for each other edge. */
static int loop_search(ObjCheck *o, Bgraph *g, LoopOut *lo, uint32_t root, uint32_t *cycles)
{
    uint32_t head = 0, tail = 0, want = located_max(o);
    /* a pathological graph (thousands of loops on a deep tree) would
     * make the written loops long: past this many points, loops are
     * counted but no more are written */
    uint64_t budget = 8 * (uint64_t)g->ne + (1u << 20);
    g->depth[root] = 0;
    g->queue[tail++] = root;
    while (head < tail) {
        uint32_t u = g->queue[head++];
        for (uint32_t k = g->off[u]; k < g->off[u + 1]; k++) {
            uint32_t e = g->at[k];
            if (g->done[e])
                continue;
            g->done[e] = 1;
            uint32_t w = g->end[2 * e] == u ? g->end[2 * e + 1] : g->end[2 * e];
            if (g->depth[w] == CHECK_NONE) {
                g->parent[w] = u;
                g->depth[w] = g->depth[u] + 1;
                g->queue[tail++] = w;
                continue;
            }
            (*cycles)++;
            if (o->out->loc.nloops < want && lo->work < budget && loop_emit(o, g, lo, u, w))
                return -1;
        }
    }
    return 0;
}

static int locate_holes(ObjCheck *o)
{
    CheckLocations *l = &o->out->loc;
    uint32_t want = located_max(o), holes = o->c->holes;
    if (!o->c->boundary_edges || !holes)
        return 0;
    Bgraph g = { 0 };
    LoopOut lo = { 0 };
    uint32_t cycles = 0;
    uint32_t n = holes < want ? holes : want;
    l->loop_length = malloc(((size_t)n + 1) * sizeof *l->loop_length);
    lo.path = malloc(((size_t)o->npts + 1) * sizeof *lo.path);
    int r = -1;
    if (!l->loop_length || !lo.path || bgraph_build(o, &g) ||
        check_push(&l->loop_start, &lo.nstart, &lo.capstart, 0))
        goto out;
    for (uint32_t e = 0; e < g.ne; e++)
        if (g.depth[g.end[2 * e]] == CHECK_NONE && loop_search(o, &g, &lo, g.end[2 * e], &cycles))
            goto out;
    /* one loop per edge left out of the forest: topo.c's count */
    ZV_ASSERT(cycles == holes && l->nloops <= n);
    r = 0;
out:
    bgraph_free(&g);
    free(lo.path);
    return r;
}

/* ==== Non-manifold edges ==== */

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return a < b ? -1 : a > b;
}

static int locate_nm_edges(ObjCheck *o)
{
    CheckLocations *l = &o->out->loc;
    uint32_t want = located_max(o);
    size_t npt = 0, cappt = 0, ns = 0, caps = 0, nf = 0, capf = 0;
    if (o->nm_ngroup < 2)
        return 0;
    if (check_push(&l->edge_start, &ns, &caps, 0))
        return -1;
    for (size_t g = 0; g + 1 < o->nm_ngroup && l->nedges < want; g++) {
        const uint32_t *h = o->nm_half + o->nm_group[g];
        uint32_t n = o->nm_group[g + 1] - o->nm_group[g];
        if (push_floats(&l->edge_pt, &npt, &cappt, oc_vpos(o, oc_vert(o, h[0])), 3) ||
            push_floats(&l->edge_pt, &npt, &cappt, oc_vpos(o, oc_vert(o, oc_next(o, h[0]))), 3))
            return -1;
        size_t first = nf;
        for (uint32_t k = 0; k < n; k++)
            if (check_push(&l->edge_face, &nf, &capf, o->f0 + oc_face(o, h[k])))
                return -1;
        /* ascending, each face once (a face may run the edge twice) */
        qsort(l->edge_face + first, nf - first, sizeof *l->edge_face, cmp_u32);
        size_t w = first;
        for (size_t k = first; k < nf; k++)
            if (k == first || l->edge_face[k] != l->edge_face[w - 1])
                l->edge_face[w++] = l->edge_face[k];
        nf = w;
        l->nedges++;
        if (check_push(&l->edge_start, &ns, &caps, (uint32_t)nf))
            return -1;
    }
    return 0;
}

int check_locate_topology(ObjCheck *o)
{
    if (!located_max(o))
        return 0;
    return locate_holes(o) || locate_nm_edges(o) ? -1 : 0;
}

int check_locate_vertex(ObjCheck *o, uint32_t p, size_t *cap)
{
    CheckLocations *l = &o->out->loc;
    size_t n = 3 * (size_t)l->nverts;
    if (l->nverts >= located_max(o))
        return 0;
    if (push_floats(&l->vert_pt, &n, cap, oc_vpos(o, o->prep[p]), 3))
        return -1;
    l->nverts++;
    return 0;
}

/* ==== Faces ==== */

int check_locate_faces(ObjCheck *o)
{
    static const uint8_t flag[3] = { CHECK_FLIPPED, CHECK_DEGENERATE, CHECK_DUPLICATE };
    CheckLocations *l = &o->out->loc;
    uint32_t want = located_max(o);
    if (!want)
        return 0;
    for (int k = 0; k < 3; k++) {
        size_t n = 0, cap = 0;
        for (uint32_t f = 0; f < o->nf && n < want; f++)
            if ((o->flags[f] & flag[k]) && check_push(&l->face[k], &n, &cap, o->f0 + f))
                return -1;
        l->nfaces[k] = (uint32_t)n;
    }
    /* the faces flagged are the faces counted */
    ZV_ASSERT(l->nfaces[0] <= o->c->inconsistent_faces && l->nfaces[1] <= o->c->degenerate_faces &&
              l->nfaces[2] <= o->c->duplicate_faces);
    return 0;
}

/* ==== A point where two triangles cross ==== */

typedef struct {
    double sum[3];
    int    n;
} Mean;

static void mean_add(Mean *m, const double p[3])
{
    for (int k = 0; k < 3; k++)
        m->sum[k] += p[k];
    m->n++;
}

static void sub3(const float *a, const float *b, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = (double)a[k] - b[k];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Is p (in t's plane, or nearly) inside triangle t, on the axes (i, j)
 * where t is widest? A little slack: p comes from a rounded division. */
static int inside(const double p[3], const float *const t[3], int i, int j)
{
    double s[3], area = 0;
    for (int e = 0; e < 3; e++) {
        const float *a = t[e], *b = t[(e + 1) % 3];
        s[e] = ((double)b[i] - a[i]) * (p[j] - a[j]) - ((double)b[j] - a[j]) * (p[i] - a[i]);
        area += s[e];
    }
    double slack = 1e-9 * fabs(area);
    return (s[0] >= -slack && s[1] >= -slack && s[2] >= -slack) ||
           (s[0] <= slack && s[1] <= slack && s[2] <= slack);
}

/* The axes of t's widest projection. */
static void axes_of(const double n[3], int *i, int *j)
{
    double ax = fabs(n[0]), ay = fabs(n[1]), az = fabs(n[2]);
    if (az >= ax && az >= ay) {
        *i = 0;
        *j = 1;
    } else if (ax >= ay) {
        *i = 1;
        *j = 2;
    } else {
        *i = 2;
        *j = 0;
    }
}

/* Where edges of a pass through triangle b (planes apart). */
static void edges_through(const float *const a[3], const float *const b[3], Mean *m)
{
    double u[3], v[3], n[3];
    sub3(b[1], b[0], u);
    sub3(b[2], b[0], v);
    cross3(u, v, n);
    int i, j;
    axes_of(n, &i, &j);
    for (int e = 0; e < 3; e++) {
        const float *p = a[e], *q = a[(e + 1) % 3];
        double dp[3], dq[3];
        sub3(p, b[0], dp);
        sub3(q, b[0], dq);
        double sp = dot3(n, dp), sq = dot3(n, dq);
        if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0) || sp == sq)
            continue;
        double t = sp / (sp - sq), x[3];
        for (int k = 0; k < 3; k++)
            x[k] = p[k] + t * ((double)q[k] - p[k]);
        if (inside(x, b, i, j))
            mean_add(m, x);
    }
}

/* Two triangles in one plane: corners of each inside the other, and
 * where their edges cross. */
static void in_plane(const float *const a[3], const float *const b[3], Mean *m)
{
    double u[3], v[3], n[3];
    sub3(a[1], a[0], u);
    sub3(a[2], a[0], v);
    cross3(u, v, n);
    int i, j;
    axes_of(n, &i, &j);
    for (int k = 0; k < 3; k++) {
        double pa[3] = { a[k][0], a[k][1], a[k][2] }, pb[3] = { b[k][0], b[k][1], b[k][2] };
        if (inside(pa, b, i, j))
            mean_add(m, pa);
        if (inside(pb, a, i, j))
            mean_add(m, pb);
    }
    for (int e = 0; e < 3; e++)
        for (int f = 0; f < 3; f++) {
            const float *p = a[e], *q = a[(e + 1) % 3], *r = b[f], *s = b[(f + 1) % 3];
            double d1[2] = { (double)q[i] - p[i], (double)q[j] - p[j] };
            double d2[2] = { (double)s[i] - r[i], (double)s[j] - r[j] };
            double den = d1[0] * d2[1] - d1[1] * d2[0];
            if (den == 0)
                continue;
            double t = (((double)r[i] - p[i]) * d2[1] - ((double)r[j] - p[j]) * d2[0]) / den;
            double w = (((double)r[i] - p[i]) * d1[1] - ((double)r[j] - p[j]) * d1[0]) / den;
            if (t < 0 || t > 1 || w < 0 || w > 1)
                continue;
            double x[3];
            for (int k = 0; k < 3; k++)
                x[k] = p[k] + t * ((double)q[k] - p[k]);
            mean_add(m, x);
        }
}

void check_tri_point(const float *const a[3], const float *const b[3], double out[3])
{
    Mean m = { { 0, 0, 0 }, 0 };
    int coplanar = 1;
    for (int k = 0; k < 3 && coplanar; k++)
        coplanar = exact_orient3d(b[0], b[1], b[2], a[k]) == 0;
    if (coplanar) {
        in_plane(a, b, &m);
    } else {
        edges_through(a, b, &m);
        edges_through(b, a, &m);
    }
    if (m.n == 0) {
        /* rounding left no point (they meet at a hair): a's corner
         * nearest b's centroid, on a at least */
        double best = DBL_MAX;
        for (int k = 0; k < 3; k++) {
            double d = 0;
            for (int c = 0; c < 3; c++) {
                double g = ((double)b[0][c] + b[1][c] + b[2][c]) / 3 - a[k][c];
                d += g * g;
            }
            if (d < best) {
                best = d;
                for (int c = 0; c < 3; c++)
                    out[c] = a[k][c];
            }
        }
        return;
    }
    for (int k = 0; k < 3; k++)
        out[k] = m.sum[k] / m.n;
}

/* ==== Crossing pairs ==== */

/* Fan triangle k (1 ..) of relative face f: three points, not on one
 * line (as cross.c takes them). */
static int fan_tri(const ObjCheck *o, uint32_t f, uint32_t k, const float *t[3], uint32_t id[3])
{
    uint32_t s = oc_start(o, f), c[3] = { s, s + k, s + k + 1 };
    for (int i = 0; i < 3; i++) {
        id[i] = oc_pt(o, c[i]);
        t[i] = oc_vpos(o, oc_vert(o, c[i]));
    }
    return id[0] != id[1] && id[1] != id[2] && id[0] != id[2] && !exact_collinear(t[0], t[1], t[2]);
}

/* A point on both faces: at their first crossing pair of fan triangles
 * (where cross.c counted them). */
static void pair_point(const ObjCheck *o, uint32_t fa, uint32_t fb, double out[3])
{
    uint32_t na = oc_start(o, fa + 1) - oc_start(o, fa), nb = oc_start(o, fb + 1) - oc_start(o, fb);
    for (uint32_t i = 1; i + 1 < na; i++)
        for (uint32_t j = 1; j + 1 < nb; j++) {
            const float *ta[3], *tb[3];
            uint32_t ia[3], ib[3];
            if (!fan_tri(o, fa, i, ta, ia) || !fan_tri(o, fb, j, tb, ib))
                continue;
            if (check_tri_pair(ta, ia, tb, ib)) {
                check_tri_point(ta, tb, out);
                return;
            }
        }
    /* not met again (cannot happen: the pair was counted so): a's first corner */
    const float *p = oc_vpos(o, oc_vert(o, oc_start(o, fa)));
    for (int k = 0; k < 3; k++)
        out[k] = p[k];
}

int check_locate_crossings(ObjCheck *o)
{
    CheckObject *out = o->out;
    CheckLocations *l = &out->loc;
    uint32_t n = out->npairs < located_max(o) ? out->npairs : located_max(o);
    if (n) {
        l->pair_face = malloc(2 * (size_t)n * sizeof *l->pair_face);
        l->pair_pt = malloc(3 * (size_t)n * sizeof *l->pair_pt);
        if (!l->pair_face || !l->pair_pt)
            return -1;
        memcpy(l->pair_face, out->pairs, 2 * (size_t)n * sizeof *l->pair_face);
        for (uint32_t i = 0; i < n; i++)
            pair_point(o, out->pairs[2 * i] - o->f0, out->pairs[2 * i + 1] - o->f0, l->pair_pt + 3 * (size_t)i);
        l->npairs = n;
    }
    if (!o->opt->detail) {
        /* kept for this alone */
        free(out->pairs);
        out->pairs = NULL;
        out->npairs = 0;
    }
    return 0;
}

void check_locations_free(CheckLocations *l)
{
    free(l->loop_start);
    free(l->loop_pt);
    free(l->loop_length);
    free(l->edge_pt);
    free(l->edge_start);
    free(l->edge_face);
    free(l->vert_pt);
    for (int k = 0; k < 3; k++)
        free(l->face[k]);
    free(l->pair_face);
    free(l->pair_pt);
    memset(l, 0, sizeof *l);
}
