/* cross.c: the pairs of faces of one object that cross each other.
 *
 * The items are triangles: a triangle face, or each triangle of a
 * polygon's fan, leaving out degenerate faces and fan triangles (they
 * are counted as degenerate). Candidates come from a bounding-volume
 * hierarchy built the way linear BVHs are (J. Lauterbach et al., "Fast
 * BVH Construction on GPUs", Eurographics 2009; T. Karras, "Maximizing
 * Parallelism in the Construction of BVHs, Octrees, and k-d Trees", HPG
 * 2012): the triangles sorted along a Morton curve of their box centres
 * (30 bits, a three-pass radix sort), then a balanced tree over that
 * order, each node the box of its run. Here the splits fall on
 * multiples of the leaf size, so that every leaf but the last is full,
 * and the nodes are laid out depth first: a node's left child follows
 * it, its right child is where the left subtree ends. Node boxes are
 * 16-bit integers on the object's box, rounded outwards (a box test may
 * let a pair through, never stop one).
 *
 * The points are renumbered in the order the sorted triangles first use
 * them and their positions copied in that order, so that a leaf's
 * triangles read neighbouring memory: 34 bytes a triangle in all.
 *
 * The tree is tested against itself by simultaneous descent: a node's
 * own pairs are its children's, plus the pairs across them, and two
 * nodes whose boxes do not meet have none across (the usual self-
 * collision traversal). The top of that recursion is unrolled into
 * tasks for the helper threads; the count does not depend on how.
 * A candidate pair is decided exactly by tritri.c (a pair that shares a
 * corner or an edge by the shared element). Two triangles of one face
 * are never a pair; a pair of faces is counted once, at the first of
 * their triangle pairs (in fan order) that crosses; two faces on the
 * same points are duplicates (dups.c), not a crossing, and a face that
 * duplicates an earlier one is left out (16,000 coincident triangles
 * were 128 million pairs).
 *
 * The work is bounded: some inputs make every pair a candidate (a
 * planar fan of 40k triangles around one vertex, 100k triangles on one
 * edge, a stack of coplanar triangles), and no tree helps there. At
 * most CHECK_PAIR_BUDGET(n) triangle pairs, n triangles, go to the exact
 * test, and 16 times as many are compared by box at the leaves; past
 * either the test stops and the count is a lower bound ("at least N",
 * intersections_stopped). An ordinary model needs far fewer: the
 * dragon (871k triangles) 7.4 tests and 37 box comparisons a triangle.
 * Each job counts its work and adds it to the shared total every
 * CROSS_FLUSH units, so that the helpers share no cache line in the
 * hot loop; the total may pass the budget by that much per thread. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_internal.h"
#include "exact.h"

#define LEAF 8                  /* triangles a leaf holds */
#define CROSS_FLUSH 4096        /* a job's work between additions to the shared total */

typedef struct {
    uint16_t lo[3], hi[3];      /* quantized box */
    uint32_t first, end;        /* its triangles, [first, end) in Morton order */
    uint32_t skip;              /* the node after its subtree */
} Node;

typedef struct {
    uint64_t  count;            /* crossing pairs found */
    uint64_t  tests, boxes;     /* exact pair tests and leaf box comparisons, not yet in the total */
    uint64_t *pairs;            /* (face a << 32 | face b), mesh indices, a < b (detail, locations) */
    size_t    n, cap;
    int       oom;
} Found;

typedef struct {
    uint32_t a, b;              /* self(a) when b == CHECK_NONE, else the pairs across a and b */
} Job;

typedef struct {
    ObjCheck *o;
    uint32_t  n;                /* triangles */
    uint32_t *face;             /* Morton order -> relative face */
    uint32_t *fan;              /* Morton order -> its triangle in the face's fan (1 ..), NULL when all are faces */
    uint32_t *id;               /* 3 renumbered points per triangle */
    float    *pos;              /* 3 coordinates per renumbered point */
    uint16_t *qbox;             /* 6 per triangle: its quantized box, lo[3] then hi[3] */
    Node     *node;
    uint32_t  nnodes;
    double    qlo[3], qscale[3];    /* positions to 0 .. 65535 across the object's box */
    Job      *job;
    uint32_t  njobs;
    Found    *found;            /* one per job */
    uint64_t  budget;           /* exact pair tests allowed; box comparisons 16 times as many */
    uint64_t  tests, boxes;     /* the work done (atomic: every job adds to it) */
    int       stop;             /* the budget is spent (atomic) */
} Cross;

/* ==== Boxes and the Morton order ==== */

static uint16_t clamp16(double v)
{
    return v <= 0 ? 0 : v >= 65535 ? 65535 : (uint16_t)v;
}

/* Outwards by a unit each side: the rounding of the scaling cannot then
 * shrink a box past a point it holds. */
static void quantize(const Cross *x, const float *lo, const float *hi, uint16_t *qlo, uint16_t *qhi)
{
    for (int k = 0; k < 3; k++) {
        qlo[k] = clamp16(floor((lo[k] - x->qlo[k]) * x->qscale[k]) - 1);
        qhi[k] = clamp16(ceil((hi[k] - x->qlo[k]) * x->qscale[k]) + 1);
    }
}

static inline int nodes_meet(const Node *a, const Node *b)
{
    return a->lo[0] <= b->hi[0] && b->lo[0] <= a->hi[0] && a->lo[1] <= b->hi[1] && b->lo[1] <= a->hi[1] &&
           a->lo[2] <= b->hi[2] && b->lo[2] <= a->hi[2];
}

/* x's low 10 bits spread to every third bit. */
static uint32_t spread10(uint32_t x)
{
    x &= 0x3ff;
    x = (x | x << 16) & 0x030000ff;
    x = (x | x << 8) & 0x0300f00f;
    x = (x | x << 4) & 0x030c30c3;
    x = (x | x << 2) & 0x09249249;
    return x;
}

static uint32_t morton(const Cross *x, const float *lo, const float *hi)
{
    uint32_t code = 0;
    for (int k = 0; k < 3; k++) {
        double c = ((lo[k] + (double)hi[k]) / 2 - x->qlo[k]) * x->qscale[k] / 64.0;   /* 0 .. 1023 */
        code |= spread10(c <= 0 ? 0 : c >= 1023 ? 1023 : (uint32_t)c) << k;
    }
    return code;
}

/* Sort val by key (30 bits), stably, in three passes of 10 bits; k2
 * and v2 are scratch of n. */
static void radix_sort(uint32_t *key, uint32_t *val, uint32_t *k2, uint32_t *v2, uint32_t n)
{
    for (int shift = 0; shift < 30; shift += 10) {
        uint32_t count[1025] = { 0 };
        for (uint32_t i = 0; i < n; i++)
            count[(key[i] >> shift & 1023) + 1]++;
        for (int d = 0; d < 1024; d++)
            count[d + 1] += count[d];
        for (uint32_t i = 0; i < n; i++) {
            uint32_t at = count[key[i] >> shift & 1023]++;
            k2[at] = key[i];
            v2[at] = val[i];
        }
        memcpy(key, k2, n * sizeof *key);
        memcpy(val, v2, n * sizeof *val);
    }
}

/* ==== The triangles ==== */

/* Fan triangle k (1 ..) of relative face f: its relative corners. */
static void fan_corners(const ObjCheck *o, uint32_t f, uint32_t k, uint32_t c[3])
{
    uint32_t s = oc_start(o, f);
    c[0] = s;
    c[1] = s + k;
    c[2] = s + k + 1;
}

/* A fan triangle of a polygon: three points, not on one line. */
static int fan_ok(const ObjCheck *o, const uint32_t c[3])
{
    uint32_t p = oc_pt(o, c[0]), q = oc_pt(o, c[1]), r = oc_pt(o, c[2]);
    return p != q && q != r && p != r &&
           !exact_collinear(oc_vpos(o, oc_vert(o, c[0])), oc_vpos(o, oc_vert(o, c[1])),
                            oc_vpos(o, oc_vert(o, c[2])));
}

static void box3(const float *a, const float *b, const float *c, float *lo, float *hi)
{
    for (int k = 0; k < 3; k++) {
        lo[k] = a[k] < b[k] ? (a[k] < c[k] ? a[k] : c[k]) : (b[k] < c[k] ? b[k] : c[k]);
        hi[k] = a[k] > b[k] ? (a[k] > c[k] ? a[k] : c[k]) : (b[k] > c[k] ? b[k] : c[k]);
    }
}

static void corners_box(const ObjCheck *o, const uint32_t c[3], float *lo, float *hi)
{
    box3(oc_vpos(o, oc_vert(o, c[0])), oc_vpos(o, oc_vert(o, c[1])), oc_vpos(o, oc_vert(o, c[2])), lo, hi);
}

/* Triangle i (Morton order), from the renumbered points. */
static inline void tri_pos(const Cross *x, uint32_t i, const float *p[3])
{
    const uint32_t *id = x->id + 3 * (size_t)i;
    p[0] = x->pos + 3 * (size_t)id[0];
    p[1] = x->pos + 3 * (size_t)id[1];
    p[2] = x->pos + 3 * (size_t)id[2];
}

/* The triangles to test, as (face, fan triangle) in file order; n set. */
static int collect(Cross *x, uint32_t **face_out, uint32_t **fan_out)
{
    ObjCheck *o = x->o;
    uint32_t n = 0, c[3];
    for (int pass = 0; pass < 2; pass++) {
        if (pass) {
            *face_out = check_big(((size_t)n + 1) * sizeof **face_out, 0);
            *fan_out = o->tris ? NULL : check_big(((size_t)n + 1) * sizeof **fan_out, 0);
            if (!*face_out || (!o->tris && !*fan_out))
                return -1;
            n = 0;
        }
        for (uint32_t f = 0; f < o->nf; f++) {
            if (o->flags[f] & (CHECK_DEGENERATE | CHECK_DUPLICATE))
                continue;
            uint32_t nfan = oc_start(o, f + 1) - oc_start(o, f) - 2;
            for (uint32_t k = 1; k <= nfan; k++) {
                fan_corners(o, f, k, c);
                if (!o->tris && !fan_ok(o, c))
                    continue;
                if (pass) {
                    (*face_out)[n] = f;
                    if (*fan_out)
                        (*fan_out)[n] = k;
                }
                n++;
            }
        }
    }
    x->n = n;
    return 0;
}

/* The set-up's loops over the triangles, each triangle's work its own:
 * split into SPLIT runs for the pool (the results do not depend on how). */
#define SPLIT 8

typedef struct {
    Cross          *x;
    const uint32_t *uface, *ufan;
    uint32_t       *key, *idx;
} Keys;

static void run_range(uint32_t n, int task, uint32_t *lo, uint32_t *hi)
{
    *lo = (uint32_t)((uint64_t)n * (uint32_t)task / SPLIT);
    *hi = (uint32_t)((uint64_t)n * ((uint32_t)task + 1) / SPLIT);
}

/* The Morton keys of triangles [lo, hi) of one run. */
static void keys_run(void *arg, int task, int worker)
{
    (void)worker;
    Keys *k = arg;
    const ObjCheck *o = k->x->o;
    uint32_t lo_i, hi_i;
    run_range(k->x->n, task, &lo_i, &hi_i);
    for (uint32_t i = lo_i; i < hi_i; i++) {
        uint32_t c[3];
        float lo[3], hi[3];
        fan_corners(o, k->uface[i], k->ufan ? k->ufan[i] : 1, c);
        corners_box(o, c, lo, hi);
        k->key[i] = morton(k->x, lo, hi);
        k->idx[i] = i;
    }
}

/* Sort the triangles along the Morton curve: x->face, x->fan. */
static int sort_tris(Cross *x, uint32_t *uface, uint32_t *ufan)
{
    size_t n = (size_t)x->n + 1;
    uint32_t *key = check_big(n * sizeof *key, 0), *idx = check_big(n * sizeof *idx, 0);
    uint32_t *k2 = check_big(n * sizeof *k2, 0), *v2 = check_big(n * sizeof *v2, 0);
    int r = -1;
    if (!key || !idx || !k2 || !v2)
        goto out;
    Keys k = { x, uface, ufan, key, idx };
    pool_run(x->o->pool, SPLIT, keys_run, &k);
    radix_sort(key, idx, k2, v2, x->n);
    free(key);
    free(k2);
    key = k2 = NULL;
    /* v2 becomes the sorted faces, idx the sorted fans */
    for (uint32_t i = 0; i < x->n; i++)
        v2[i] = uface[idx[i]];
    if (ufan)
        for (uint32_t i = 0; i < x->n; i++)
            idx[i] = ufan[idx[i]];
    x->face = v2;
    x->fan = ufan ? idx : NULL;
    v2 = NULL;
    if (ufan)
        idx = NULL;
    r = 0;
out:
    free(key);
    free(idx);
    free(k2);
    free(v2);
    return r;
}

/* Number the points in the order the sorted triangles first use them
 * and copy their positions so: x->id, x->pos. */
static int renumber(Cross *x)
{
    ObjCheck *o = x->o;
    uint32_t *newid = check_big(((size_t)o->npts + 1) * sizeof *newid, 0);
    x->id = check_big((3 * (size_t)x->n + 1) * sizeof *x->id, 0);
    x->pos = check_big((3 * (size_t)o->npts + 1) * sizeof *x->pos, 0);
    if (!newid || !x->id || !x->pos) {
        free(newid);
        return -1;
    }
    memset(newid, 0xff, ((size_t)o->npts + 1) * sizeof *newid);
    uint32_t np = 0;
    for (uint32_t i = 0; i < x->n; i++) {
        uint32_t c[3];
        fan_corners(o, x->face[i], x->fan ? x->fan[i] : 1, c);
        for (int k = 0; k < 3; k++) {
            uint32_t p = oc_pt(o, c[k]);
            ZV_ASSERT(p < o->npts);     /* newid[] and pos[] hold the object's points */
            if (newid[p] == CHECK_NONE) {
                newid[p] = np;
                memcpy(x->pos + 3 * (size_t)np, oc_vpos(o, oc_vert(o, c[k])), 3 * sizeof *x->pos);
                np++;
            }
            x->id[3 * (size_t)i + k] = newid[p];
        }
    }
    free(newid);
    return 0;
}

/* ==== The tree ==== */

/* The quantized boxes of one run of triangles. */
static void boxes_run(void *arg, int task, int worker)
{
    (void)worker;
    Cross *x = arg;
    uint32_t lo_i, hi_i;
    run_range(x->n, task, &lo_i, &hi_i);
    for (uint32_t i = lo_i; i < hi_i; i++) {
        const float *p[3];
        float lo[3], hi[3];
        tri_pos(x, i, p);
        box3(p[0], p[1], p[2], lo, hi);
        quantize(x, lo, hi, x->qbox + 6 * (size_t)i, x->qbox + 6 * (size_t)i + 3);
    }
}

/* Every triangle's box, quantized. */
static int tri_boxes(Cross *x)
{
    x->qbox = check_big((6 * (size_t)x->n + 1) * sizeof *x->qbox, 0);
    if (!x->qbox)
        return -1;
    pool_run(x->o->pool, SPLIT, boxes_run, x);
    return 0;
}

static inline int is_leaf(const Node *n)
{
    return n->end - n->first <= LEAF;
}

/* Node me's box: its children's joined. */
static void join_children(Cross *x, uint32_t me)
{
    Node *nd = &x->node[me];
    uint32_t l = me + 1, r = x->node[l].skip;
    for (int k = 0; k < 3; k++) {
        nd->lo[k] = x->node[l].lo[k] < x->node[r].lo[k] ? x->node[l].lo[k] : x->node[r].lo[k];
        nd->hi[k] = x->node[l].hi[k] > x->node[r].hi[k] ? x->node[l].hi[k] : x->node[r].hi[k];
    }
}

/* Node me over triangles [first, end), but not its box; its leaves (at
 * least 1). The splits fall on multiples of LEAF, half the leaves each
 * side, and every node has two children or none: a subtree of L leaves
 * is 2L - 1 nodes, so where each subtree starts is known before its
 * left neighbour is built, and subtrees can be built at once. */
static uint32_t node_at(Cross *x, uint32_t me, uint32_t first, uint32_t end)
{
    uint32_t leaves = (end - first + LEAF - 1) / LEAF;
    /* every leaf full but the last: the tree has at most 2 ceil(n /
     * LEAF) nodes, the array's size */
    ZV_ASSERT(first % LEAF == 0 && first < end && me + 2 * leaves - 1 <= 2 * ((x->n + LEAF - 1) / LEAF));
    Node *nd = &x->node[me];
    nd->first = first;
    nd->end = end;
    nd->skip = me + 2 * leaves - 1;
    return leaves;
}

/* Node me and its subtree, depth first, boxes included. */
static void build_at(Cross *x, uint32_t me, uint32_t first, uint32_t end)
{
    uint32_t leaves = node_at(x, me, first, end);
    if (leaves == 1) {
        Node *nd = &x->node[me];
        memcpy(nd->lo, x->qbox + 6 * (size_t)first, 6 * sizeof *nd->lo);
        for (uint32_t i = first + 1; i < end; i++) {
            const uint16_t *b = x->qbox + 6 * (size_t)i;
            for (int k = 0; k < 3; k++) {
                nd->lo[k] = b[k] < nd->lo[k] ? b[k] : nd->lo[k];
                nd->hi[k] = b[3 + k] > nd->hi[k] ? b[3 + k] : nd->hi[k];
            }
        }
        return;
    }
    uint32_t half = leaves / 2;
    build_at(x, me + 1, first, first + half * LEAF);
    build_at(x, me + 2 * half, first + half * LEAF, end);
    join_children(x, me);
}

/* The tree: its top two levels laid out first, the four subtrees under
 * them built by the pool, then the top's boxes joined. */
typedef struct {
    Cross   *x;
    uint32_t sub[4][3];         /* node, first, end */
} Tree;

static void tree_run(void *arg, int task, int worker)
{
    (void)worker;
    Tree *t = arg;
    build_at(t->x, t->sub[task][0], t->sub[task][1], t->sub[task][2]);
}

static void build(Cross *x)
{
    uint32_t leaves = (x->n + LEAF - 1) / LEAF;
    x->nnodes = 2 * leaves - 1;
    if (leaves < 4 || !x->o->pool) {
        build_at(x, 0, 0, x->n);
        return;
    }
    Tree t = { x, { { 0 } } };
    uint32_t top[3], k = 0;
    top[0] = 0;
    uint32_t half = node_at(x, 0, 0, x->n) / 2, mid = half * LEAF;
    uint32_t side[2][3] = { { 1, 0, mid }, { 2 * half, mid, x->n } };
    for (int i = 0; i < 2; i++) {
        uint32_t me = side[i][0], first = side[i][1], end = side[i][2];
        top[1 + i] = me;
        uint32_t h = node_at(x, me, first, end) / 2;
        uint32_t sub[2][3] = { { me + 1, first, first + h * LEAF }, { me + 2 * h, first + h * LEAF, end } };
        for (int j = 0; j < 2; j++, k++)
            memcpy(t.sub[k], sub[j], sizeof sub[j]);
    }
    pool_run(x->o->pool, 4, tree_run, &t);
    join_children(x, top[1]);
    join_children(x, top[2]);
    join_children(x, top[0]);
}


/* ==== The budget ==== */

/* Add a job's work to the total; 1 when the budget is spent. */
static int spend(Cross *x, Found *fd)
{
    uint64_t t = __atomic_add_fetch(&x->tests, fd->tests, __ATOMIC_RELAXED);
    uint64_t b = __atomic_add_fetch(&x->boxes, fd->boxes, __ATOMIC_RELAXED);
    fd->tests = fd->boxes = 0;
    if (t > x->budget || b > 16 * x->budget) {
        __atomic_store_n(&x->stop, 1, __ATOMIC_RELAXED);
        return 1;
    }
    return 0;
}

/* Stop here? The job's own work goes to the total once it is large. */
static inline int spent(Cross *x, Found *fd)
{
    if (fd->tests + fd->boxes / 16 >= CROSS_FLUSH && spend(x, fd))
        return 1;
    return __atomic_load_n(&x->stop, __ATOMIC_RELAXED);
}

/* ==== Testing a pair ==== */

/* Do faces fa and fb use the same points, as many times each? */
static int same_points(const ObjCheck *o, uint32_t fa, uint32_t fb)
{
    uint32_t sa = oc_start(o, fa), na = oc_start(o, fa + 1) - sa;
    uint32_t sb = oc_start(o, fb), nb = oc_start(o, fb + 1) - sb;
    if (na != nb)
        return 0;
    for (uint32_t i = 0; i < na; i++) {
        uint32_t p = oc_pt(o, sa + i), in_a = 0, in_b = 0;
        for (uint32_t j = 0; j < na; j++) {
            in_a += oc_pt(o, sa + j) == p;
            in_b += oc_pt(o, sb + j) == p;
        }
        if (in_a != in_b)
            return 0;
    }
    return 1;
}

/* Do fan triangles ka of fa and kb of fb cross (any answer but 0)? An
 * exact test, counted in fd. */
static int fans_cross(const ObjCheck *o, Found *fd, uint32_t fa, uint32_t ka, uint32_t fb, uint32_t kb)
{
    fd->tests++;
    uint32_t ca[3], cb[3], ia[3], ib[3];
    const float *pa[3], *pb[3];
    fan_corners(o, fa, ka, ca);
    fan_corners(o, fb, kb, cb);
    if (!fan_ok(o, ca) || !fan_ok(o, cb))
        return 0;
    for (int k = 0; k < 3; k++) {
        ia[k] = oc_pt(o, ca[k]);
        ib[k] = oc_pt(o, cb[k]);
        pa[k] = oc_vpos(o, oc_vert(o, ca[k]));
        pb[k] = oc_vpos(o, oc_vert(o, cb[k]));
    }
    return check_tri_pair(pa, ia, pb, ib) != 0;
}

/* The pair of polygons fa and fb is counted at their first crossing
 * pair of fan triangles: is (ka, kb) that one? Two long polygons make
 * this long too: the budget stops it (answering no, the count a lower
 * bound then). */
static int first_crossing(Cross *x, Found *fd, uint32_t fa, uint32_t ka, uint32_t fb, uint32_t kb)
{
    const ObjCheck *o = x->o;
    uint32_t nb = oc_start(o, fb + 1) - oc_start(o, fb) - 2;
    for (uint32_t i = 1; i <= ka; i++)
        for (uint32_t j = 1; j <= (i < ka ? nb : kb - 1); j++)
            if (fans_cross(o, fd, fa, i, fb, j) || spent(x, fd))
                return 0;
    return 1;
}

static void found(Cross *x, Found *fd, uint32_t fa, uint32_t fb)
{
    ObjCheck *o = x->o;
    fd->count++;
    __atomic_fetch_or(&o->flags[fa], CHECK_INTERSECTS, __ATOMIC_RELAXED);
    __atomic_fetch_or(&o->flags[fb], CHECK_INTERSECTS, __ATOMIC_RELAXED);
    if (!(o->opt->detail || o->opt->locations) || fd->oom || fd->n >= CHECK_PAIRS_MAX)
        return;
    if (fd->n == fd->cap) {
        size_t cap = fd->cap ? fd->cap * 2 : 256;
        uint64_t *p = realloc(fd->pairs, cap * sizeof *p);
        if (!p) {
            fd->oom = 1;
            return;
        }
        fd->pairs = p;
        fd->cap = cap;
    }
    uint64_t a = o->f0 + (uint64_t)(fa < fb ? fa : fb), b = o->f0 + (uint64_t)(fa < fb ? fb : fa);
    fd->pairs[fd->n++] = a << 32 | b;
}

/* Triangles i and j (Morton order), of different faces, boxes meeting. */
static void test_pair(Cross *x, Found *fd, uint32_t i, uint32_t j)
{
    const float *pa[3], *pb[3];
    tri_pos(x, i, pa);
    tri_pos(x, j, pb);
    fd->tests++;
    int r = check_tri_pair(pa, x->id + 3 * (size_t)i, pb, x->id + 3 * (size_t)j);
    if (!r)
        return;
    uint32_t fa = x->face[i], fb = x->face[j];
    /* faces on the same points are duplicates, whatever their fans do */
    if ((r == CHECK_SAME_TRI || x->fan) && same_points(x->o, fa, fb))
        return;
    if (x->fan && !(fa < fb ? first_crossing(x, fd, fa, x->fan[i], fb, x->fan[j])
                            : first_crossing(x, fd, fb, x->fan[j], fa, x->fan[i])))
        return;
    found(x, fd, fa, fb);
}

/* ==== The traversal ==== */

static inline int qboxes_meet(const uint16_t *a, const uint16_t *b)
{
    return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] && b[2] <= a[5];
}

/* The pairs between the triangles of leaves a and b (a == b: within). */
static void leaf_pairs(Cross *x, Found *fd, const Node *a, const Node *b)
{
    if (spent(x, fd))
        return;
    for (uint32_t i = a->first; i < a->end; i++) {
        const uint16_t *bi = x->qbox + 6 * (size_t)i;
        if (a != b && !qboxes_meet(bi, b->lo))
            continue;
        uint32_t j0 = a == b ? i + 1 : b->first, end = b->end;
        fd->boxes += end - j0;
        /* i's box in locals: a found pair writes face flags (bytes, which
         * may alias anything), and the box would be read again */
        uint16_t lo0 = bi[0], lo1 = bi[1], lo2 = bi[2], hi0 = bi[3], hi1 = bi[4], hi2 = bi[5];
        const uint16_t *bj = x->qbox + 6 * (size_t)j0;
        for (uint32_t j = j0; j < end; j++, bj += 6)
            /* without fans (every face a triangle) i and j are two faces */
            if (lo0 <= bj[3] && bj[0] <= hi0 && lo1 <= bj[4] && bj[1] <= hi1 && lo2 <= bj[5] && bj[2] <= hi2 &&
                (!x->fan || x->face[i] != x->face[j]))
                test_pair(x, fd, i, j);
    }
}

/* The pairs across nodes a and b: the bigger is opened until both are
 * leaves, wherever the boxes meet. */
static void across(Cross *x, Found *fd, uint32_t a, uint32_t b)
{
    const Node *na = &x->node[a], *nb = &x->node[b];
    if (!nodes_meet(na, nb) || __atomic_load_n(&x->stop, __ATOMIC_RELAXED))
        return;
    int la = is_leaf(na), lb = is_leaf(nb);
    if (la && lb) {
        leaf_pairs(x, fd, na, nb);
        return;
    }
    if (la || (!lb && nb->end - nb->first > na->end - na->first)) {
        across(x, fd, a, b + 1);
        across(x, fd, a, x->node[b + 1].skip);
    } else {
        across(x, fd, a + 1, b);
        across(x, fd, x->node[a + 1].skip, b);
    }
}

static int cancelled(const Cross *x)
{
    const int *c = x->o->opt->cancel;
    return c && __atomic_load_n(c, __ATOMIC_RELAXED);
}

/* The pairs within node a. */
static void within(Cross *x, Found *fd, uint32_t a)
{
    const Node *n = &x->node[a];
    if (is_leaf(n)) {
        leaf_pairs(x, fd, n, n);
        return;
    }
    if (cancelled(x) || __atomic_load_n(&x->stop, __ATOMIC_RELAXED))
        return;
    uint32_t l = a + 1, r = x->node[l].skip;
    within(x, fd, l);
    within(x, fd, r);
    across(x, fd, l, r);
}

/* The top of the recursion as jobs, until there are `want` of them or
 * none opens further (a job's count does not depend on the split). */
static int make_jobs(Cross *x, uint32_t want)
{
    size_t n = 1, cap = 16;
    Job *job = malloc(cap * sizeof *job);
    if (!job)
        return -1;
    job[0] = (Job){ 0, CHECK_NONE };
    for (int grew = 1; grew && n < want;) {
        grew = 0;
        size_t m = n;
        for (size_t i = 0; i < m && n < want; i++) {
            if (n + 3 > cap) {
                Job *q = realloc(job, (cap *= 2) * sizeof *job);
                if (!q) {
                    free(job);
                    return -1;
                }
                job = q;
            }
            Job j = job[i];
            const Node *na = &x->node[j.a];
            if (j.b == CHECK_NONE && !is_leaf(na)) {
                uint32_t l = j.a + 1, r = x->node[l].skip;
                job[i] = (Job){ l, CHECK_NONE };
                job[n++] = (Job){ r, CHECK_NONE };
                job[n++] = (Job){ l, r };
                grew = 1;
            } else if (j.b != CHECK_NONE && !is_leaf(na) && nodes_meet(na, &x->node[j.b])) {
                job[i] = (Job){ j.a + 1, j.b };
                job[n++] = (Job){ x->node[j.a + 1].skip, j.b };
                grew = 1;
            }
        }
    }
    x->job = job;
    x->njobs = (uint32_t)n;
    return 0;
}

static void run_job(void *arg, int task, int worker)
{
    (void)worker;
    Cross *x = arg;
    Job j = x->job[task];
    if (j.b == CHECK_NONE)
        within(x, &x->found[task], j.a);
    else
        across(x, &x->found[task], j.a, j.b);
    spend(x, &x->found[task]);
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The jobs' pairs, sorted, into the object's list. */
static int gather(Cross *x)
{
    ObjCheck *o = x->o;
    size_t total = 0;
    /* within the budget, or stopped: a count past the budget that is
     * not flagged would be reported as exact, not "at least" */
    ZV_ASSERT(x->stop || (x->tests <= x->budget && x->boxes <= 16 * x->budget));
    o->c->pair_tests += x->tests;
    o->c->intersections_stopped |= x->stop;
    for (uint32_t t = 0; t < x->njobs; t++) {
        o->c->self_intersections += x->found[t].count;
        total += x->found[t].n;
        if (x->found[t].oom)
            return -1;
    }
    if (!(o->opt->detail || o->opt->locations) || total == 0)
        return 0;
    uint64_t *all = malloc(total * sizeof *all);
    if (!all)
        return -1;
    size_t k = 0;
    for (uint32_t t = 0; t < x->njobs; t++) {
        if (!x->found[t].n)
            continue;           /* a job that found none has no list (memcpy from NULL is undefined) */
        memcpy(all + k, x->found[t].pairs, x->found[t].n * sizeof *all);
        k += x->found[t].n;
    }
    qsort(all, total, sizeof *all, cmp_u64);
    if (total > CHECK_PAIRS_MAX)
        total = CHECK_PAIRS_MAX;
    o->out->pairs = malloc(2 * total * sizeof *o->out->pairs);
    if (!o->out->pairs) {
        free(all);
        return -1;
    }
    for (size_t i = 0; i < total; i++) {
        /* each pair of faces once, the lower first: the traversal meets
         * every pair of leaves once, and a pair of polygons is counted
         * at its first crossing fan pair only */
        ZV_ASSERT((all[i] >> 32) < (uint32_t)all[i] && (i == 0 || all[i - 1] < all[i]));
        o->out->pairs[2 * i] = (uint32_t)(all[i] >> 32);
        o->out->pairs[2 * i + 1] = (uint32_t)all[i];
    }
    o->out->npairs = (uint32_t)total;
    free(all);
    return 0;
}

static void cross_free(Cross *x)
{
    for (uint32_t t = 0; x->found && t < x->njobs; t++)
        free(x->found[t].pairs);
    free(x->found);
    free(x->job);
    free(x->node);
    free(x->id);
    free(x->pos);
    free(x->qbox);
    free(x->fan);
    free(x->face);
}

int check_crossings(ObjCheck *o)
{
    Cross x = { .o = o };
    for (int k = 0; k < 3; k++) {
        double ext = (double)o->c->hi[k] - o->c->lo[k];
        x.qlo[k] = o->c->lo[k];
        x.qscale[k] = ext > 0 ? 65535.0 / ext : 0;
    }
    uint32_t *uface = NULL, *ufan = NULL;
    int r = collect(&x, &uface, &ufan);
    x.budget = CHECK_PAIR_BUDGET((uint64_t)x.n);
    o->c->pair_budget += x.budget;
    if (r == 0)
        r = sort_tris(&x, uface, ufan);
    free(uface);
    free(ufan);
    if (r || x.n < 2) {
        cross_free(&x);
        return r;
    }
    x.node = check_big((2 * (((size_t)x.n + LEAF - 1) / LEAF)) * sizeof *x.node, 0);
    if (renumber(&x) || tri_boxes(&x) || !x.node) {
        cross_free(&x);
        return -1;
    }
    build(&x);
    uint32_t threads = (uint32_t)pool_helpers(o->pool) + 1;
    r = make_jobs(&x, threads > 1 ? 32 * threads : 1);
    if (r == 0 && !(x.found = calloc(x.njobs, sizeof *x.found)))
        r = -1;
    if (r == 0) {
        pool_run(o->pool, (int)x.njobs, run_job, &x);
        r = cancelled(&x) ? -1 : gather(&x);
    }
    cross_free(&x);
    return r;
}
