/* bvhray.c: a ray's first hit through the BVH of bvh.c (include/bvh.h),
 * for wall thickness. A depth-first walk, nearer child first, passing
 * over any child whose box the ray enters past the best hit so far (the
 * slab test of Kay and Kajiya, 1986, in double, on boxes padded by a
 * margin that covers the floats' rounding), and each triangle by Moller
 * and Trumbore's test (1997) in double from the float corners. */

#include <math.h>
#include <string.h>

#include "bvh.h"

#define STACK_MAX (3 * BVH_DEPTH_MAX + 8)
#define BARY_MARGIN 0x1p-30

/* The ray's t where it meets triangle t (+inf: it does not, or only at
 * t <= 0 or past tmax). */
static double ray_triangle(const Bvh *b, uint32_t t, const double o[3], const double d[3], double tmax)
{
    const float *c = &b->corner[9 * (size_t)t];
    double e1[3] = { (double)c[3] - c[0], (double)c[4] - c[1], (double)c[5] - c[2] };
    double e2[3] = { (double)c[6] - c[0], (double)c[7] - c[1], (double)c[8] - c[2] };
    double p[3] = { d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0] };
    double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (det == 0 || !isfinite(det))
        return INFINITY;
    double inv = 1 / det;
    double s[3] = { o[0] - c[0], o[1] - c[1], o[2] - c[2] };
    double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < -BARY_MARGIN || u > 1 + BARY_MARGIN)
        return INFINITY;
    double q[3] = { s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0] };
    double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < -BARY_MARGIN || u + v > 1 + BARY_MARGIN)
        return INFINITY;
    double tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    return tt > 0 && tt <= tmax ? tt : INFINITY;
}

/* Where the ray enters child c's box (its t, at least 0), +inf when it
 * misses it or enters past best. The box is padded by 2^-20 of its
 * coordinates' size: a hit on a triangle lies within its float box, and
 * the padding keeps rounding from losing it. */
static double enter_box(const BvhNode *n, int c, const double o[3], const double inv[3], double best)
{
    double t0 = 0, t1 = best;
    for (int k = 0; k < 3; k++) {
        double lo = n->lo[k][c], hi = n->hi[k][c];
        if (lo > hi)
            return INFINITY;
        double pad = (fabs(lo) + fabs(hi)) * 0x1p-20 + 0x1p-100;
        lo -= pad;
        hi += pad;
        if (isinf(inv[k])) {        /* parallel to this slab: inside it or never */
            if (o[k] < lo || o[k] > hi)
                return INFINITY;
            continue;
        }
        double a = (lo - o[k]) * inv[k], z = (hi - o[k]) * inv[k];
        if (a > z) {
            double tmp = a;
            a = z;
            z = tmp;
        }
        t0 = a > t0 ? a : t0;
        t1 = z < t1 ? z : t1;
        if (t0 > t1)
            return INFINITY;
    }
    return t0;
}

void bvh_ray(const Bvh *b, const double origin[3], const double dir[3], double tmax, uint32_t skip,
             BvhRayHit *hit)
{
    double best = tmax, inv[3];
    uint32_t bt = BVH_NONE;
    for (int k = 0; k < 3; k++)
        inv[k] = dir[k] != 0 ? 1 / dir[k] : INFINITY;
    /* invariant: each entry is a child the ray enters at t, which was at
     * most the best hit when it was pushed */
    struct {
        uint32_t child, count;
        double   t;
    } stack[STACK_MAX];
    int top = 0;
    if (b->nnodes) {
        stack[0].child = 0;
        stack[0].count = 0;
        stack[0].t = 0;
        top = 1;
    }
    while (top > 0) {
        top--;
        if (stack[top].t > best)
            continue;
        if (stack[top].count) {
            uint32_t t0 = stack[top].child;
            for (uint32_t t = t0; t < t0 + stack[top].count; t++) {
                if (skip != BVH_NONE && b->id[t] == skip)
                    continue;
                double h = ray_triangle(b, t, origin, dir, best);
                if (h < best || (h == best && bt != BVH_NONE && t < bt)) {
                    best = h;
                    bt = t;
                }
            }
            continue;
        }
        const BvhNode *n = &b->node[stack[top].child];
        double e[BVH_WIDTH];
        int k = 0, idx[BVH_WIDTH];
        for (int c = 0; c < BVH_WIDTH; c++) {
            if (n->child[c] == BVH_NONE || isinf(e[c] = enter_box(n, c, origin, inv, best)))
                continue;
            int j = k++;                /* farthest first on the stack: nearest popped first */
            while (j > 0 && e[idx[j - 1]] < e[c]) {
                idx[j] = idx[j - 1];
                j--;
            }
            idx[j] = c;
        }
        for (int j = 0; j < k; j++) {
            stack[top].child = n->child[idx[j]];
            stack[top].count = n->count[idx[j]];
            stack[top++].t = e[idx[j]];
        }
    }
    hit->t = bt == BVH_NONE ? INFINITY : best;
    hit->tri = bt;
}
