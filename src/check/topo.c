/* topo.c: the topology of one object on its points. Which faces share
 * each edge (the half-edge pairing), and from it the boundary edges and
 * holes, the non-manifold edges and vertices (the parts are counted
 * with the winding, in shape.c).
 *
 * Edges are found without a hash table: the half-edges are bucketed by
 * the point they leave (a counting sort), each bucket sorted by the
 * point they reach, and the edge {a, b} is the run a -> b in a's bucket
 * with the run b -> a in b's (found by binary search). An edge with one
 * half-edge is a boundary edge, with two a manifold one (its half-edges
 * are each other's mate), with more a non-manifold one.
 *
 * Holes are the independent cycles of the graph of boundary edges
 * (edges - points + connected pieces, by union-find over points): one
 * per closed loop, two where two loops touch at a point. A vertex is
 * non-manifold when the corners around it fall into more than one fan:
 * corners are joined across each edge at its two ends (union-find over
 * corners), and a point whose corners make two sets or more is where
 * separate fans meet (two cones tip to tip, two cubes touching at a
 * corner). */

#include <stdlib.h>
#include <string.h>

#include "check_internal.h"

/* ==== The half-edge buckets ==== */

typedef struct {
    uint32_t *off;      /* npts + 1: point a's half-edges are [off[a], off[a + 1]) */
    uint32_t *to;       /* the point each reaches */
    uint32_t *he;       /* the half-edge (relative corner) */
} Buckets;

static void buckets_free(Buckets *b)
{
    free(b->off);
    free(b->to);
    free(b->he);
    memset(b, 0, sizeof *b);
}

/* Sort one bucket by the point reached, keeping corner order within a
 * run (so that the runs list their faces in file order). Short buckets,
 * nearly all of them, by insertion; a long one (the centre of a fan of
 * thousands) through packed keys and qsort, in `scratch`. */
static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

static void bucket_sort(uint32_t *to, uint32_t *he, uint32_t n, uint64_t *scratch)
{
    if (n <= 32) {
        for (uint32_t i = 1; i < n; i++) {
            uint32_t t = to[i], h = he[i], j = i;
            for (; j > 0 && to[j - 1] > t; j--) {
                to[j] = to[j - 1];
                he[j] = he[j - 1];
            }
            to[j] = t;
            he[j] = h;
        }
        return;
    }
    for (uint32_t i = 0; i < n; i++)
        scratch[i] = (uint64_t)to[i] << 32 | he[i];
    qsort(scratch, n, sizeof *scratch, cmp_u64);
    for (uint32_t i = 0; i < n; i++) {
        to[i] = (uint32_t)(scratch[i] >> 32);
        he[i] = (uint32_t)scratch[i];
    }
}

/* The buckets sorted, in runs of points by the pool (each bucket is its
 * own: how they are shared out changes nothing), a scratch for a long
 * bucket per worker. */
#define TOPO_SPLIT 8

typedef struct {
    Buckets   *b;
    uint32_t   np, maxdeg;
    uint64_t **scratch;         /* per worker, when maxdeg > 32 */
} SortRun;

static void sort_run(void *arg, int task, int worker)
{
    SortRun *s = arg;
    const Buckets *b = s->b;
    uint32_t lo = (uint32_t)((uint64_t)s->np * (uint32_t)task / TOPO_SPLIT);
    uint32_t hi = (uint32_t)((uint64_t)s->np * ((uint32_t)task + 1) / TOPO_SPLIT);
    for (uint32_t p = lo; p < hi; p++)
        bucket_sort(b->to + b->off[p], b->he + b->off[p], b->off[p + 1] - b->off[p],
                    s->maxdeg > 32 ? s->scratch[worker] : NULL);
}

static int sort_buckets(ObjCheck *o, Buckets *b, uint32_t maxdeg)
{
    int workers = pool_helpers(o->pool) + 1, r = 0;
    uint64_t *scratch[64] = { 0 };
    for (int w = 0; maxdeg > 32 && w < workers && w < 64; w++)
        if (!(scratch[w] = malloc((size_t)maxdeg * sizeof *scratch[w])))
            r = -1;
    if (r == 0) {
        SortRun s = { b, o->npts, maxdeg, scratch };
        pool_run(o->pool, TOPO_SPLIT, sort_run, &s);
    }
    for (int w = 0; w < 64; w++)
        free(scratch[w]);
    return r;
}

/* Bucket every half-edge of a non-degenerate face that joins two
 * different points; mate[] of the others is MATE_DEGENERATE, of a
 * degenerate face's corners MATE_SKIPPED. mate[] first holds each
 * corner's point, so that the counting and the filling passes look each
 * up once. */
static int buckets_build(ObjCheck *o, Buckets *b)
{
    uint32_t np = o->npts, nc = o->nc, *pt = o->mate;
    b->off = check_big(((size_t)np + 1) * sizeof *b->off, 1);
    if (!b->off)
        return -1;
    for (uint32_t c = 0; c < nc; c++)
        pt[c] = oc_pt(o, c);
    uint32_t nhe = 0;
    for (uint32_t c = 0; c < nc; c++)
        if (pt[c] != pt[oc_next(o, c)] && !(o->flags[oc_face(o, c)] & CHECK_DEGENERATE)) {
            b->off[pt[c] + 1]++;
            nhe++;
        }
    uint32_t maxdeg = 0;
    for (uint32_t p = 0; p < np; p++) {
        if (b->off[p + 1] > maxdeg)
            maxdeg = b->off[p + 1];
        b->off[p + 1] += b->off[p];
    }
    b->to = check_big(((size_t)nhe + 1) * sizeof *b->to, 0);
    b->he = check_big(((size_t)nhe + 1) * sizeof *b->he, 0);
    if (!b->to || !b->he)
        return -1;
    /* fill with off[p] as the cursor, then shift it back one bucket;
     * a face's points are read before its mate[] entries are set */
    for (uint32_t f = 0; f < o->nf; f++) {
        uint32_t s = oc_start(o, f), e = oc_start(o, f + 1), first = e > s ? pt[s] : 0;
        if (o->flags[f] & CHECK_DEGENERATE) {
            for (uint32_t c = s; c < e; c++)
                pt[c] = MATE_SKIPPED;
            continue;
        }
        for (uint32_t c = s; c < e; c++) {
            uint32_t p = pt[c], q = c + 1 < e ? pt[c + 1] : first;
            if (p == q) {
                pt[c] = MATE_DEGENERATE;
                continue;
            }
            uint32_t k = b->off[p]++;
            b->to[k] = q;
            b->he[k] = c;
            pt[c] = MATE_BOUNDARY;      /* until a partner turns up */
        }
    }
    /* the filling pass met the half-edges the counting pass counted:
     * the last bucket's cursor ends at their total (one more would
     * have written past to[] and he[], one fewer left a slot unset) */
    ZV_ASSERT(np == 0 || b->off[np - 1] == nhe);
    memmove(b->off + 1, b->off, (size_t)np * sizeof *b->off);
    b->off[0] = 0;
    return sort_buckets(o, b, maxdeg);
}

/* The run of half-edges reaching `a` in point p's sorted bucket:
 * [*lo, *hi), empty when there is none. */
static void find_run(const Buckets *b, uint32_t p, uint32_t a, uint32_t *lo, uint32_t *hi)
{
    uint32_t l = b->off[p], h = b->off[p + 1];
    while (l < h) {
        uint32_t mid = l + (h - l) / 2;
        if (b->to[mid] < a)
            l = mid + 1;
        else
            h = mid;
    }
    uint32_t e = l;
    while (e < b->off[p + 1] && b->to[e] == a)
        e++;
    *lo = l;
    *hi = e;
}

/* ==== Classifying the edges ==== */

static int push_edge(ObjCheck *o, uint32_t **list, size_t *n, size_t *cap, uint32_t c)
{
    if (!o->opt->detail)
        return 0;
    return check_push(list, n, cap, oc_vert(o, c)) || check_push(list, n, cap, oc_vert(o, oc_next(o, c)));
}

typedef struct {
    size_t nb, capb, nn, capn;      /* the detail lists' lengths and capacities */
} EdgeLists;

/* The edge whose half-edges are same[0..ns) (a -> b) and opp[0..no)
 * (b -> a). */
static int edge_group(ObjCheck *o, EdgeLists *l, const uint32_t *same, uint32_t ns, const uint32_t *opp,
                      uint32_t no)
{
    uint32_t n = ns + no;
    uint32_t first = ns ? same[0] : opp[0];
    if (n == 1) {
        o->c->boundary_edges++;
        o->flags[oc_face(o, first)] |= CHECK_OPEN;
        return push_edge(o, &o->out->boundary, &l->nb, &l->capb, first);
    }
    if (n == 2) {
        uint32_t h1 = first, h2 = ns == 2 ? same[1] : no == 2 ? opp[1] : opp[0];
        /* every edge is met once: a half-edge paired twice would leave
         * its first partner's mate pointing at a face that is not */
        ZV_ASSERT(h1 != h2 && o->mate[h1] == MATE_BOUNDARY && o->mate[h2] == MATE_BOUNDARY);
        o->mate[h1] = h2;
        o->mate[h2] = h1;
        return 0;
    }
    o->c->nonmanifold_edges++;
    if (check_push(&o->nm_group, &o->nm_ngroup, &o->nm_group_cap, (uint32_t)o->nm_nhalf))
        return -1;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t h = k < ns ? same[k] : opp[k - ns];
        o->mate[h] = MATE_NONMANIF;
        o->flags[oc_face(o, h)] |= CHECK_NONMANIFOLD;
        if (check_push(&o->nm_half, &o->nm_nhalf, &o->nm_half_cap, h))
            return -1;
    }
    return push_edge(o, &o->out->nm_edges, &l->nn, &l->capn, first);
}

/* ==== Classifying in runs of points ====
 *
 * Without the detail lists, the edges are classified by the pool in
 * runs of points: each edge is met once, in the bucket of one point, so
 * its half-edges' mates are that run's alone; the counts and the
 * non-manifold groups are the run's own, joined in run order after (the
 * groups then in the order one pass makes them), and the faces' flags,
 * which two runs may share, are set atomically. */

typedef struct {
    uint32_t  boundary, nonmanifold;
    uint32_t *half, *group;     /* the run's non-manifold groups (group: starts in half) */
    size_t    nhalf, halfcap, ngroup, groupcap;
    int       rc;
} EdgeRun;

typedef struct {
    ObjCheck      *o;
    const Buckets *b;
    EdgeRun        run[TOPO_SPLIT];
} Classify;

static void edge_group_run(ObjCheck *o, EdgeRun *e, const uint32_t *same, uint32_t ns, const uint32_t *opp,
                           uint32_t no)
{
    uint32_t n = ns + no;
    uint32_t first = ns ? same[0] : opp[0];
    if (n == 1) {
        e->boundary++;
        __atomic_fetch_or(&o->flags[oc_face(o, first)], CHECK_OPEN, __ATOMIC_RELAXED);
        return;
    }
    if (n == 2) {
        uint32_t h1 = first, h2 = ns == 2 ? same[1] : no == 2 ? opp[1] : opp[0];
        /* every edge is met once (see edge_group) */
        ZV_ASSERT(h1 != h2 && o->mate[h1] == MATE_BOUNDARY && o->mate[h2] == MATE_BOUNDARY);
        o->mate[h1] = h2;
        o->mate[h2] = h1;
        return;
    }
    e->nonmanifold++;
    if (check_push(&e->group, &e->ngroup, &e->groupcap, (uint32_t)e->nhalf))
        e->rc = -1;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t h = k < ns ? same[k] : opp[k - ns];
        o->mate[h] = MATE_NONMANIF;
        __atomic_fetch_or(&o->flags[oc_face(o, h)], CHECK_NONMANIFOLD, __ATOMIC_RELAXED);
        if (check_push(&e->half, &e->nhalf, &e->halfcap, h))
            e->rc = -1;
    }
}

static void classify_run(void *arg, int task, int worker)
{
    (void)worker;
    Classify *cl = arg;
    ObjCheck *o = cl->o;
    const Buckets *b = cl->b;
    EdgeRun *e = &cl->run[task];
    uint32_t lo = (uint32_t)((uint64_t)o->npts * (uint32_t)task / TOPO_SPLIT);
    uint32_t hi = (uint32_t)((uint64_t)o->npts * ((uint32_t)task + 1) / TOPO_SPLIT);
    for (uint32_t a = lo; a < hi && e->rc == 0; a++) {
        uint32_t j = b->off[a], end = b->off[a + 1];
        while (j < end) {
            uint32_t pb = b->to[j], j1 = j + 1;
            while (j1 < end && b->to[j1] == pb)
                j1++;
            uint32_t k0, k1;
            find_run(b, pb, a, &k0, &k1);
            if (!(pb < a && k1 > k0))
                edge_group_run(o, e, b->he + j, j1 - j, b->he + k0, k1 - k0);
            j = j1;
        }
    }
}

static int classify_runs(ObjCheck *o, const Buckets *b)
{
    Classify *cl = calloc(1, sizeof *cl);
    if (!cl)
        return -1;
    cl->o = o;
    cl->b = b;
    pool_run(o->pool, TOPO_SPLIT, classify_run, cl);
    int r = 0;
    for (int t = 0; t < TOPO_SPLIT; t++) {
        EdgeRun *e = &cl->run[t];
        r |= e->rc;
        o->c->boundary_edges += e->boundary;
        o->c->nonmanifold_edges += e->nonmanifold;
        for (size_t g = 0; r == 0 && g < e->ngroup; g++)
            r = check_push(&o->nm_group, &o->nm_ngroup, &o->nm_group_cap, (uint32_t)(o->nm_nhalf + e->group[g]));
        for (size_t h = 0; r == 0 && h < e->nhalf; h++)
            r = check_push(&o->nm_half, &o->nm_nhalf, &o->nm_half_cap, e->half[h]);
        free(e->half);
        free(e->group);
    }
    free(cl);
    return r ? -1 : check_push(&o->nm_group, &o->nm_ngroup, &o->nm_group_cap, (uint32_t)o->nm_nhalf);
}

/* Every edge once: from the bucket of its smaller point, or from the
 * only bucket that has it. */
static int classify(ObjCheck *o, const Buckets *b)
{
    if (!o->opt->detail)
        return classify_runs(o, b);
    EdgeLists l = { 0 };
    for (uint32_t a = 0; a < o->npts; a++) {
        uint32_t j = b->off[a], end = b->off[a + 1];
        while (j < end) {
            uint32_t pb = b->to[j], j1 = j + 1;
            while (j1 < end && b->to[j1] == pb)
                j1++;
            /* buckets sorted by the point reached: each run is an edge
             * whole, and find_run's binary search finds the opposite */
            ZV_ASSERT(j1 == end || b->to[j1] > pb);
            uint32_t k0, k1;
            find_run(b, pb, a, &k0, &k1);
            if (!(pb < a && k1 > k0) && edge_group(o, &l, b->he + j, j1 - j, b->he + k0, k1 - k0))
                return -1;
            j = j1;
        }
    }
    return check_push(&o->nm_group, &o->nm_ngroup, &o->nm_group_cap, (uint32_t)o->nm_nhalf);
}

/* ==== Holes, fans, parts ==== */

static int count_holes(ObjCheck *o)
{
    uint32_t *uf = check_identity(o->npts);
    if (!uf)
        return -1;
    uint32_t merged = 0, open = 0;
    for (uint32_t c = 0; c < o->nc; c++)
        if (o->mate[c] == MATE_BOUNDARY) {
            merged += (uint32_t)check_union(uf, oc_pt(o, c), oc_pt(o, oc_next(o, c)));
            open++;
        }
    /* one boundary half-edge per boundary edge counted: else holes
     * (edges - merged) would count the wrong graph, or wrap below 0 */
    ZV_ASSERT(open == o->c->boundary_edges && merged <= open);
    o->c->holes = o->c->boundary_edges - merged;
    free(uf);
    return 0;
}

/* Join the corners at each end of the manifold edge of half-edges h1 and
 * h2: h1 runs a -> b; h2 runs b -> a when the two agree, a -> b when
 * they do not. */
static void join_pair(ObjCheck *o, uint32_t *uf, uint32_t h1, uint32_t h2)
{
    uint32_t n1 = oc_next(o, h1), n2 = oc_next(o, h2);
    if (oc_pt(o, h1) != oc_pt(o, h2)) {
        check_union(uf, h1, n2);
        check_union(uf, n1, h2);
    } else {
        check_union(uf, h1, h2);
        check_union(uf, n1, n2);
    }
}

/* The corners at each end of a non-manifold edge, all joined. */
static void join_group(ObjCheck *o, uint32_t *uf, const uint32_t *h, uint32_t n)
{
    uint32_t a = oc_pt(o, h[0]), at_a = h[0], at_b = oc_next(o, h[0]);
    for (uint32_t k = 1; k < n; k++) {
        uint32_t nk = oc_next(o, h[k]);
        int from_a = oc_pt(o, h[k]) == a;
        check_union(uf, at_a, from_a ? h[k] : nk);
        check_union(uf, at_b, from_a ? nk : h[k]);
    }
}

static int count_fans(ObjCheck *o)
{
    uint32_t *uf = check_identity(o->nc);
    uint8_t *fans = check_big((size_t)o->npts + 1, 1);
    if (!uf || !fans) {
        free(uf);
        free(fans);
        return -1;
    }
    for (uint32_t c = 0; c < o->nc; c++) {
        uint32_t m = o->mate[c];
        /* mates are each other's and in range: join_pair reads both */
        ZV_ASSERT(m >= MATE_FIRST_SPECIAL || (m < o->nc && o->mate[m] == c));
        if (m < MATE_FIRST_SPECIAL && c < m)
            join_pair(o, uf, c, m);
        else if (m == MATE_DEGENERATE)
            check_union(uf, c, oc_next(o, c));  /* a point repeated in a row is one corner */
    }
    for (size_t g = 0; g + 1 < o->nm_ngroup; g++)
        join_group(o, uf, o->nm_half + o->nm_group[g], o->nm_group[g + 1] - o->nm_group[g]);
    for (uint32_t c = 0; c < o->nc; c++)
        if (o->mate[c] != MATE_SKIPPED && check_find(uf, c) == c) {
            uint32_t p = oc_pt(o, c);
            if (fans[p] < 2)
                fans[p]++;
        }
    free(uf);
    size_t n = 0, cap = 0, loc_cap = 0;
    int r = 0;
    for (uint32_t p = 0; p < o->npts && !r; p++)
        if (fans[p] >= 2) {
            o->c->nonmanifold_vertices++;
            if (o->opt->detail)
                r = check_push(&o->out->nm_verts, &n, &cap, o->prep[p]);
            if (!r && o->opt->locations)
                r = check_locate_vertex(o, p, &loc_cap);
        }
    free(fans);
    return r;
}

/* Flag and count the degenerate faces, before anything leaves them out. */
typedef struct {
    ObjCheck *o;
    uint32_t  count[TOPO_SPLIT];
} Degenerate;

static void degenerate_run(void *arg, int task, int worker)
{
    (void)worker;
    Degenerate *d = arg;
    ObjCheck *o = d->o;
    uint32_t lo = (uint32_t)((uint64_t)o->nf * (uint32_t)task / TOPO_SPLIT);
    uint32_t hi = (uint32_t)((uint64_t)o->nf * ((uint32_t)task + 1) / TOPO_SPLIT);
    for (uint32_t f = lo; f < hi; f++)
        if (check_face_degenerate(o, f)) {
            o->flags[f] |= CHECK_DEGENERATE;
            d->count[task]++;
        }
}

/* In runs of faces by the pool: each face is its own. */
static void find_degenerate(ObjCheck *o)
{
    Degenerate d = { .o = o };
    pool_run(o->pool, TOPO_SPLIT, degenerate_run, &d);
    for (int t = 0; t < TOPO_SPLIT; t++)
        o->c->degenerate_faces += d.count[t];
}

int check_pairing(ObjCheck *o)
{
    Buckets b = { 0 };
    find_degenerate(o);
    int r = buckets_build(o, &b) || classify(o, &b) ? -1 : 0;
    buckets_free(&b);
    return r;
}

int check_vertices(ObjCheck *o)
{
    return count_holes(o) || count_fans(o) || check_locate_topology(o) ? -1 : 0;
}
