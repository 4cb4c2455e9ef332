/* bvh.c: a bounding-volume hierarchy over triangles (include/bvh.h).
 *
 * Built as a linear BVH: the triangles sorted along a Morton curve of
 * their boxes' centres (30 bits, 10 an axis, in the box of all the
 * centres; a radix sort), then split top down at the highest bit where a
 * range's first and last codes differ, so that each node is a cell of
 * the curve's octree (C. Lauterbach, M. Garland, S. Sengupta, D. Luebke
 * and D. Manocha, "Fast BVH Construction on GPUs", Eurographics 2009;
 * the Morton order after G. M. Morton, 1966). A range of one code (a
 * thousand triangles in one cell of a big scan, or on one point) is
 * halved at the median of its centres along its widest axis. The build
 * is linear but for those medians, and the leaves lie in the curve's
 * order, so triangles near in space are near in memory. Depth: 30
 * levels of bits, then halvings, at most BVH_DEPTH_MAX.
 *
 * An inner node holds its four children's boxes (two levels of splits
 * at once), so a step of a walk reads two cache lines and decides four
 * children, in float, four at a time with SSE2 (the same operations as
 * the scalar code: the same bits). A box is passed over only past a
 * margin that covers float's rounding and the query point's.
 *
 * The nearest point: a depth-first walk, nearer child first, passing
 * over any box farther than the best distance so far (the box's distance
 * is a lower bound of its triangles'). The point-triangle distance is
 * the classic one by the Voronoi regions of the corners and sides (C.
 * Ericson, "Real-Time Collision Detection", 2005, 5.1.5), in double. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "bvh.h"
#include "simd.h"

#define STACK_MAX (3 * BVH_DEPTH_MAX + 8)

/* ==== Distances ==== */

static inline double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void sub3(double out[3], const double a[3], const double b[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static inline double dist2(const double a[3], const double b[3])
{
    double d[3];
    sub3(d, a, b);
    return dot3(d, d);
}

/* The point of segment a b nearest to q (a b may coincide). */
static double point_segment(const double q[3], const double a[3], const double b[3], double out[3])
{
    double ab[3], aq[3];
    sub3(ab, b, a);
    sub3(aq, q, a);
    double len2 = dot3(ab, ab), t = len2 > 0 ? dot3(aq, ab) / len2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int k = 0; k < 3; k++)
        out[k] = a[k] + t * ab[k];
    return dist2(q, out);
}

/* Point (1 - t) x + t y. */
static inline void lerp3(double out[3], const double x[3], const double y[3], double t)
{
    for (int k = 0; k < 3; k++)
        out[k] = x[k] + t * (y[k] - x[k]);
}

double bvh_point_triangle(const double q[3], const double a[3], const double b[3], const double c[3],
                          double out[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    sub3(ab, b, a);
    sub3(ac, c, a);
    sub3(ap, q, a);
    double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0) {                           /* corner a */
        memcpy(out, a, 3 * sizeof *out);
        return dist2(q, out);
    }
    sub3(bp, q, b);
    double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3) {                          /* corner b */
        memcpy(out, b, 3 * sizeof *out);
        return dist2(q, out);
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {                /* side a b */
        double den = d1 - d3;
        lerp3(out, a, b, den > 0 ? d1 / den : 0);
        return dist2(q, out);
    }
    sub3(cp, q, c);
    double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6) {                          /* corner c */
        memcpy(out, c, 3 * sizeof *out);
        return dist2(q, out);
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {                /* side a c */
        double den = d2 - d6;
        lerp3(out, a, c, den > 0 ? d2 / den : 0);
        return dist2(q, out);
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {     /* side b c */
        double den = (d4 - d3) + (d5 - d6);
        lerp3(out, b, c, den > 0 ? (d4 - d3) / den : 0);
        return dist2(q, out);
    }
    double sum = va + vb + vc;
    if (!(sum > 0) || !isfinite(sum)) {
        /* no area (or rounding made it seem so): the nearest of its sides */
        double s[3], best = point_segment(q, a, b, out);
        double d = point_segment(q, b, c, s);
        if (d < best) {
            best = d;
            memcpy(out, s, sizeof s);
        }
        d = point_segment(q, c, a, s);
        if (d < best) {
            best = d;
            memcpy(out, s, sizeof s);
        }
        return best;
    }
    double v = vb / sum, w = vc / sum;                  /* the inside: barycentric */
    for (int k = 0; k < 3; k++)
        out[k] = a[k] + ab[k] * v + ac[k] * w;
    return dist2(q, out);
}

/* A box is passed over when farther than this from the best: the box's
 * and the triangle's distances are each a few roundings from exact, so
 * the triangle nearest in exact arithmetic is never passed over when its
 * computed distance is the least. */
static inline double prune_at(double best)
{
    return best + best * 0x1p-20;
}

/* Triangle t's corners in double (exact: they are floats). */
static inline void tri_corners(const Bvh *b, uint32_t t, double A[3], double B[3], double C[3])
{
    const float *c = &b->corner[9 * (size_t)t];
    A[0] = c[0], A[1] = c[1], A[2] = c[2];
    B[0] = c[3], B[1] = c[4], B[2] = c[5];
    C[0] = c[6], C[1] = c[7], C[2] = c[8];
}

static inline double tri_dist2(const Bvh *b, uint32_t t, const double q[3], double out[3])
{
    double A[3], B[3], C[3];
    tri_corners(b, t, A, B, C);
    return bvh_point_triangle(q, A, B, C, out);
}

/* Is the plane of triangle A B C farther from q than the squared
 * distance lim? Then so is the triangle: a cheap test before the exact
 * one, with a margin that rounding cannot close. */
static inline int plane_beyond(const double A[3], const double B[3], const double C[3], const double q[3], double lim)
{
    double u[3] = { B[0] - A[0], B[1] - A[1], B[2] - A[2] };
    double v[3] = { C[0] - A[0], C[1] - A[1], C[2] - A[2] };
    double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
    double h = (q[0] - A[0]) * n[0] + (q[1] - A[1]) * n[1] + (q[2] - A[2]) * n[2];
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    return h * h > lim * nn * (1 + 0x1p-16);
}

/* The query point in float, and how far rounding moved it. */
typedef struct {
    float  q[3];
    double err;                 /* max over the axes of |q - (float)q| */
} QueryF;

static void query_f(const double q[3], QueryF *f)
{
    f->err = 0;
    for (int k = 0; k < 3; k++) {
        f->q[k] = (float)q[k];
        double e = fabs(q[k] - f->q[k]);      /* never NaN: the points are finite */
        f->err = e > f->err ? e : f->err;
    }
}

/* The least float squared box distance that may hold a triangle nearer
 * than best: the float distances are within 2^-21 of the exact ones for
 * the rounded point, which is within sqrt(3) err of the query, so a box
 * past this is farther than prune_at(best) exactly. */
static float box_limit(double best, const QueryF *f)
{
    if (!(best < INFINITY))
        return INFINITY;
    double r = sqrt(best) * (1 + 0x1p-19) + 2 * f->err;
    double lim = r * r * (1 + 0x1p-18) + 0x1p-120;
    if (lim >= 0x1p127)
        return INFINITY;
    /* nextafterf((float)lim, INFINITY) without the call (a query asks
     * this at each nearer triangle): lim is at least 2^-120, so its
     * float is positive, normal and finite, and the next float up is
     * the next bit pattern */
    float f32 = (float)lim;
    uint32_t u;
    memcpy(&u, &f32, sizeof u);
    u++;
    memcpy(&f32, &u, sizeof f32);
    return f32;
}

/* The squared distances from the point to a node's four children's
 * boxes (0 inside): max(lo - q, 0) + max(q - hi, 0) an axis, at most
 * one of the two not 0; an empty box's is infinite. */
static inline void child_dist2(const BvhNode *n, const float q[3], float out[BVH_WIDTH])
{
#ifdef ZV_SSE2
    __m128 s = _mm_setzero_ps(), zero = _mm_setzero_ps();
    for (int k = 0; k < 3; k++) {
        __m128 qk = _mm_set1_ps(q[k]);
        __m128 d = _mm_add_ps(_mm_max_ps(_mm_sub_ps(_mm_loadu_ps(n->lo[k]), qk), zero),
                              _mm_max_ps(_mm_sub_ps(qk, _mm_loadu_ps(n->hi[k])), zero));
        s = _mm_add_ps(s, _mm_mul_ps(d, d));
    }
    _mm_storeu_ps(out, s);
#else
    for (int c = 0; c < BVH_WIDTH; c++) {
        float s = 0;
        for (int k = 0; k < 3; k++) {
            float lo = n->lo[k][c] - q[k], hi = q[k] - n->hi[k][c];
            float d = (lo > 0 ? lo : 0) + (hi > 0 ? hi : 0);
            s = s + d * d;
        }
        out[c] = s;
    }
#endif
}

/* The children of n whose boxes' distances e[] are within lim into idx,
 * the farthest first (the nearest is popped first), those at one
 * distance in child order; returns how many. Mostly one or two: a mask
 * and a swap, not a sort. */
static inline int children_within(const BvhNode *n, const float e[BVH_WIDTH], float lim, int idx[BVH_WIDTH])
{
    unsigned mask;
#ifdef ZV_SSE2
    mask = (unsigned)_mm_movemask_ps(_mm_cmple_ps(_mm_loadu_ps(e), _mm_set1_ps(lim)));
    __m128i none = _mm_cmpeq_epi32(_mm_loadu_si128((const __m128i *)(const void *)n->child), _mm_set1_epi32(-1));
    mask &= ~(unsigned)_mm_movemask_ps(_mm_castsi128_ps(none));
#else
    mask = 0;
    for (int c = 0; c < BVH_WIDTH; c++)
        mask |= (unsigned)(e[c] <= lim && n->child[c] != BVH_NONE) << c;
#endif
    int k = 0;
    for (; mask; mask &= mask - 1)
        idx[k++] = __builtin_ctz(mask);
    if (k == 2) {
        if (e[idx[0]] < e[idx[1]]) {
            int t = idx[0];
            idx[0] = idx[1];
            idx[1] = t;
        }
    } else if (k > 2) {
        for (int i = 1; i < k; i++) {
            int c = idx[i], j = i;
            for (; j > 0 && e[idx[j - 1]] < e[c]; j--)
                idx[j] = idx[j - 1];
            idx[j] = c;
        }
    }
    return k;
}

void bvh_closest(const Bvh *b, const double q[3], BvhHit *hit)
{
    bvh_closest_from(b, q, BVH_NONE, hit);
}

void bvh_closest_from(const Bvh *b, const double q[3], uint32_t hint, BvhHit *hit)
{
    double best = INFINITY, p[3];
    uint32_t bt = BVH_NONE;
    QueryF qf;
    query_f(q, &qf);
    if (hint < b->ntris) {
        /* the guess first: its distance bounds the walk from the root
         * on, and the walk still meets every triangle as near (below),
         * so the answer is the one without it */
        best = tri_dist2(b, hint, q, hit->p);
        bt = hint;
    }
    float lim = box_limit(best, &qf);
    /* invariant: each entry on the stack is a child (a node, or a leaf's
     * first triangle and count) with its box's distance, which was within
     * the limit when it was pushed. The nearest child of a node is not
     * pushed but walked at once (cur): it would be the next popped, and
     * within the limit, which has not moved since */
    struct {
        uint32_t child, count;
        float    d2;
    } stack[STACK_MAX];
    int top = 0, have = b->nnodes > 0;
    uint32_t cur = 0, cur_count = 0;
    while (have) {
        if (cur_count) {
            for (uint32_t t = cur; t < cur + cur_count; t++) {
                if (t == hint)
                    continue;
                /* the corners read once for both tests */
                double A[3], B[3], C[3];
                tri_corners(b, t, A, B, C);
                if (plane_beyond(A, B, C, q, prune_at(best)))
                    continue;
                double d = bvh_point_triangle(q, A, B, C, p);
                if (d < best || (d == best && t < bt)) {
                    best = d;
                    bt = t;
                    memcpy(hit->p, p, sizeof p);
                    lim = box_limit(best, &qf);
                }
            }
        } else {
            const BvhNode *n = &b->node[cur];
            float e[BVH_WIDTH];
            child_dist2(n, qf.q, e);
            int idx[BVH_WIDTH], k = children_within(n, e, lim, idx);
            if (k > 0) {
                for (int j = 0; j + 1 < k; j++) {
                    stack[top].child = n->child[idx[j]];
                    stack[top].count = n->count[idx[j]];
                    stack[top++].d2 = e[idx[j]];
                }
                cur = n->child[idx[k - 1]];
                cur_count = n->count[idx[k - 1]];
                continue;
            }
        }
        /* the next one on the stack still within the limit */
        have = 0;
        while (top > 0) {
            top--;
            if (stack[top].d2 <= lim) {
                cur = stack[top].child;
                cur_count = stack[top].count;
                have = 1;
                break;
            }
        }
    }
    hit->d2 = best;
    hit->tri = bt;
}

/* ==== Building ==== */

/* A triangle while building: its Morton code, then its index. */
typedef struct {
    uint32_t code, t;
} Keyed;

/* 10 bits spread to every third bit. */
static inline uint32_t spread3(uint32_t v)
{
    v &= 0x3ff;
    v = (v | (v << 16)) & 0x030000ff;
    v = (v | (v << 8)) & 0x0300f00f;
    v = (v | (v << 4)) & 0x030c30c3;
    v = (v | (v << 2)) & 0x09249249;
    return v;
}

static inline void tri_box(const float *pos, const uint32_t *tri, uint32_t t, float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int i = 0; i < 3; i++) {
        const float *p = &pos[3 * (size_t)tri[3 * (size_t)t + i]];
        for (int k = 0; k < 3; k++) {
            lo[k] = p[k] < lo[k] ? p[k] : lo[k];
            hi[k] = p[k] > hi[k] ? p[k] : hi[k];
        }
    }
}

/* Sort by code, stable: four passes of a byte (a pass whose byte is the
 * same for all is left out). tmp holds n. Returns the sorted array. */
static Keyed *radix_sort(Keyed *a, Keyed *tmp, uint32_t n)
{
    for (int shift = 0; shift < 32; shift += 8) {
        uint32_t count[256] = { 0 };
        for (uint32_t i = 0; i < n; i++)
            count[(a[i].code >> shift) & 255]++;
        if (count[(a[0].code >> shift) & 255] == n)
            continue;
        uint32_t at = 0;
        for (int d = 0; d < 256; d++) {
            uint32_t c = count[d];
            count[d] = at;
            at += c;
        }
        for (uint32_t i = 0; i < n; i++)
            tmp[count[(a[i].code >> shift) & 255]++] = a[i];
        Keyed *x = a;
        a = tmp;
        tmp = x;
    }
    return a;
}

/* Put the median of a[0, n) by centre along axis k at n / 2, the lower
 * ones before it (quickselect, the middle element the pivot); c holds
 * each input triangle's centre. */
static void median_split(Keyed *a, uint32_t n, const float *c, int k)
{
    uint32_t lo = 0, hi = n, m = n / 2;
    while (hi - lo > 1) {
        float pv = c[3 * (size_t)a[lo + (hi - lo) / 2].t + k];
        /* invariant: [lo, i) < pv, [i, j) == pv, [g, hi) > pv */
        uint32_t i = lo, j = lo, g = hi;
        while (j < g) {
            float v = c[3 * (size_t)a[j].t + k];
            Keyed x;
            if (v < pv) {
                x = a[i];
                a[i++] = a[j];
                a[j++] = x;
            } else if (v > pv) {
                x = a[--g];
                a[g] = a[j];
                a[j] = x;
            } else {
                j++;
            }
        }
        if (m < i)
            hi = i;
        else if (m >= g)
            lo = g;
        else
            return;
    }
}

/* The widest axis of the centres of a[0, n). */
static int widest_axis(const Keyed *a, uint32_t n, const float *c)
{
    float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            float v = c[3 * (size_t)a[i].t + k];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if ((double)hi[k] - lo[k] > (double)hi[axis] - lo[axis])
            axis = k;
    return axis;
}

/* Where [begin, end) splits: the first code with the highest differing
 * bit set; for one code throughout, the median along the widest axis. */
static uint32_t split_at(Keyed *a, uint32_t begin, uint32_t end, const float *c)
{
    uint32_t x = a[begin].code ^ a[end - 1].code;
    if (!x) {
        median_split(a + begin, end - begin, c, widest_axis(a + begin, end - begin, c));
        return begin + (end - begin) / 2;
    }
    uint32_t bit = 1u << (31 - __builtin_clz(x));
    uint32_t lo = begin, hi = end - 1;       /* a[lo] lacks the bit, a[hi] has it */
    while (hi - lo > 1) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (a[mid].code & bit)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}

int bvh_order(const float *pos, uint32_t n, const float *box, uint32_t *order, uint32_t *code)
{
    if (n == 0)
        return 0;
    Keyed *a = bigmem_alloc((size_t)n * sizeof *a), *tmp = bigmem_alloc((size_t)n * sizeof *tmp);
    if (!a || !tmp) {
        free(a);
        free(tmp);
        return -1;
    }
    float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    if (box) {
        memcpy(lo, box, sizeof lo);
        memcpy(hi, box + 3, sizeof hi);
    } else {
        for (uint32_t v = 0; v < n; v++)
            for (int k = 0; k < 3; k++) {
                float x = pos[3 * (size_t)v + k];
                lo[k] = x < lo[k] ? x : lo[k];
                hi[k] = x > hi[k] ? x : hi[k];
            }
    }
    double scale[3];
    for (int k = 0; k < 3; k++)
        scale[k] = (double)hi[k] - lo[k] > 0 ? 1023.0 / ((double)hi[k] - lo[k]) : 0;
    for (uint32_t v = 0; v < n; v++) {
        uint32_t c = 0;
        for (int k = 0; k < 3; k++) {
            double x = ((double)pos[3 * (size_t)v + k] - lo[k]) * scale[k];
            uint32_t q = !(x > 0) ? 0 : x >= 1023 ? 1023 : (uint32_t)x;
            c |= spread3(q) << (2 - k);
        }
        a[v].code = c;
        a[v].t = v;
    }
    Keyed *sorted = radix_sort(a, tmp, n);
    for (uint32_t v = 0; v < n; v++) {
        order[v] = sorted[v].t;
        if (code)
            code[v] = sorted[v].code;
    }
    free(a);
    free(tmp);
    return 0;
}

typedef struct {
    uint32_t node, begin, end, depth;
} BuildTask;

/* Room for more nodes, 64-byte aligned (a node is a cache line). */
static int grow_nodes(Bvh *b, uint32_t *cap, uint32_t need)
{
    if (need <= *cap)
        return 0;
    uint32_t n = *cap ? *cap : 256;
    while (n < need)
        n = n > UINT32_MAX / 3 * 2 ? need : n + n / 2;
    BvhNode *q = aligned_alloc(64, (size_t)n * sizeof *q);
    if (!q)
        return -1;
    bigmem_advise(q, (size_t)n * sizeof *q, 1);
    if (b->nnodes)
        memcpy(q, b->node, (size_t)b->nnodes * sizeof *q);
    free(b->node);
    b->node = q;
    *cap = n;
    return 0;
}

/* The tree over the sorted a[0, n): the nodes' links; boxes after. A
 * node's range is split twice (each half again when it is more than a
 * leaf), so it has up to four children. */
static int build_links(Bvh *b, Keyed *a, uint32_t n, const float *c)
{
    uint32_t cap = 0;
    if (grow_nodes(b, &cap, n / 6 + 1))
        return -1;
    b->nnodes = 1;
    BuildTask stack[STACK_MAX];
    int top = 0;
    stack[top++] = (BuildTask){ 0, 0, n, 1 };
    while (top > 0) {
        BuildTask k = stack[--top];
        uint32_t range[BVH_WIDTH][2], nr = 0;
        uint32_t mid = k.end - k.begin > 1 ? split_at(a, k.begin, k.end, c) : k.end;
        uint32_t half[2][2] = { { k.begin, mid }, { mid, k.end } };
        for (int h = 0; h < 2; h++) {
            uint32_t hb = half[h][0], he = half[h][1];
            if (he - hb > BVH_LEAF_MAX) {
                uint32_t m2 = split_at(a, hb, he, c);
                range[nr][0] = hb;
                range[nr++][1] = m2;
                range[nr][0] = m2;
                range[nr++][1] = he;
            } else if (he > hb) {
                range[nr][0] = hb;
                range[nr++][1] = he;
            }
        }
        b->depth = k.depth > b->depth ? k.depth : b->depth;
        for (uint32_t ci = 0; ci < BVH_WIDTH; ci++) {
            uint32_t cn = ci < nr ? range[ci][1] - range[ci][0] : 0;
            if (cn <= BVH_LEAF_MAX) {
                /* a leaf, or no child */
                b->node[k.node].child[ci] = cn ? range[ci][0] : BVH_NONE;
                b->node[k.node].count[ci] = cn;
                continue;
            }
            if (grow_nodes(b, &cap, b->nnodes + 1))
                return -1;
            uint32_t idx = b->nnodes++;
            b->node[k.node].child[ci] = idx;
            b->node[k.node].count[ci] = 0;
            stack[top++] = (BuildTask){ idx, range[ci][0], range[ci][1], k.depth + 1 };
        }
    }
    return 0;
}

/* Each node's children's boxes, children first (a child's index is
 * always past its parent's). */
static void build_boxes(Bvh *b)
{
    for (uint32_t i = b->nnodes; i-- > 0;) {
        BvhNode *n = &b->node[i];
        for (int c = 0; c < BVH_WIDTH; c++) {
            float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
            if (n->count[c]) {
                for (uint32_t t = n->child[c]; t < n->child[c] + n->count[c]; t++)
                    for (int v = 0; v < 3; v++)
                        for (int k = 0; k < 3; k++) {
                            float x = b->corner[9 * (size_t)t + 3 * v + k];
                            lo[k] = x < lo[k] ? x : lo[k];
                            hi[k] = x > hi[k] ? x : hi[k];
                        }
            } else if (n->child[c] != BVH_NONE) {
                const BvhNode *ch = &b->node[n->child[c]];
                for (int g = 0; g < BVH_WIDTH; g++)
                    for (int k = 0; k < 3; k++) {
                        lo[k] = ch->lo[k][g] < lo[k] ? ch->lo[k][g] : lo[k];
                        hi[k] = ch->hi[k][g] > hi[k] ? ch->hi[k][g] : hi[k];
                    }
            }
            for (int k = 0; k < 3; k++) {
                n->lo[k][c] = lo[k];
                n->hi[k][c] = hi[k];
            }
        }
    }
}

uint64_t bvh_build_bytes(uint64_t ntris)
{
    /* the sort's two arrays, then the corners and ids; nodes: a line for
     * every two triangles at most in practice (leaves of 1 to 4) */
    uint64_t sort = 2 * ntris * sizeof(Keyed), kept = ntris * (9 * sizeof(float) + sizeof(uint32_t));
    return sort + kept + (ntris / 2 + 1) * sizeof(BvhNode);
}

void bvh_free(Bvh *b)
{
    free(b->node);
    free(b->corner);
    free(b->id);
    memset(b, 0, sizeof *b);
}

int bvh_build(Bvh *b, const float *pos, uint32_t nverts, const uint32_t *tri, const uint32_t *id,
              uint32_t ntris, char *err, size_t errlen)
{
    memset(b, 0, sizeof *b);
    if (ntris == 0)
        return 0;
    for (uint64_t i = 0; i < 3 * (uint64_t)ntris; i++)
        if (tri[i] >= nverts) {
            snprintf(err, errlen, "triangle %llu names vertex %u of %u", (unsigned long long)(i / 3), tri[i], nverts);
            return -1;
        }
    Keyed *a = bigmem_alloc((size_t)ntris * sizeof *a), *tmp = bigmem_alloc((size_t)ntris * sizeof *tmp);
    float *c = bigmem_alloc((size_t)ntris * 3 * sizeof *c);
    if (!a || !tmp || !c)
        goto oom;
    /* each box's centre (halfway, in float: the order it gives is all
     * that matters), and the box of the centres */
    float clo[3] = { INFINITY, INFINITY, INFINITY }, chi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t t = 0; t < ntris; t++) {
        float lo[3], hi[3];
        tri_box(pos, tri, t, lo, hi);
        for (int k = 0; k < 3; k++) {
            float v = c[3 * (size_t)t + k] = 0.5f * lo[k] + 0.5f * hi[k];
            clo[k] = v < clo[k] ? v : clo[k];
            chi[k] = v > chi[k] ? v : chi[k];
        }
    }
    double scale[3];
    for (int k = 0; k < 3; k++)
        scale[k] = (double)chi[k] - clo[k] > 0 ? 1023.0 / ((double)chi[k] - clo[k]) : 0;
    for (uint32_t t = 0; t < ntris; t++) {
        uint32_t code = 0;
        for (int k = 0; k < 3; k++) {
            double x = ((double)c[3 * (size_t)t + k] - clo[k]) * scale[k];
            uint32_t q = !(x > 0) ? 0 : x >= 1023 ? 1023 : (uint32_t)x;
            code |= spread3(q) << (2 - k);
        }
        a[t].code = code;
        a[t].t = t;
    }
    Keyed *sorted = radix_sort(a, tmp, ntris);
    if (build_links(b, sorted, ntris, c))
        goto oom;
    free(c);
    c = NULL;
    b->id = bigmem_alloc((size_t)ntris * sizeof *b->id);
    b->corner = bigmem_alloc((size_t)ntris * 9 * sizeof *b->corner);
    if (!b->id || !b->corner)
        goto oom;
    for (uint32_t i = 0; i < ntris; i++) {
        uint32_t t = sorted[i].t;
        for (int v = 0; v < 3; v++)
            memcpy(&b->corner[9 * (size_t)i + 3 * v], &pos[3 * (size_t)tri[3 * (size_t)t + v]], 3 * sizeof(float));
        b->id[i] = id ? id[t] : t;
    }
    free(a);
    free(tmp);
    b->ntris = ntris;
    build_boxes(b);
    return 0;
oom:
    free(a);
    free(tmp);
    free(c);
    bvh_free(b);
    snprintf(err, errlen, "out of memory");
    return -1;
}
