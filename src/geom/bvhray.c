/* bvhray.c: a ray's first hit through the BVH of bvh.c (include/bvh.h),
 * for wall thickness. A depth-first walk, nearer child first, passing
 * over any child whose box the ray enters past the best hit so far (the
 * slab test of Kay and Kajiya, 1986, in float, four children at a time,
 * on boxes padded by a margin that covers the float's rounding), and
 * each triangle by Moller and Trumbore's test (1997) in double from the
 * float corners. */

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

/* The ray in float for the box tests, and the margin they keep. */
typedef struct {
    float o[3], inv[3];         /* origin; 1 / direction (1e30 for a 0: the slab is never left) */
    float pad;                  /* the boxes grown by this: covers the origin's rounding and the
                                   slabs' (2^-20 of the largest coordinate of the root's box) */
} RayF;

/* Where the ray enters each of a node's four children's boxes (its t,
 * at least 0) into t_out; the mask of those it enters at most at best.
 * In float, four at a time: the boxes padded by f->pad and the entry
 * and exit compared with a relative margin of 2^-20, so that rounding
 * never passes over a box the exact ray enters (the triangle test, in
 * double, then decides). */
static inline int enter_boxes(const BvhNode *n, const RayF *f, float best, float t_out[BVH_WIDTH])
{
    float t0[BVH_WIDTH], t1[BVH_WIDTH];
    for (int c = 0; c < BVH_WIDTH; c++) {
        t0[c] = 0;
        t1[c] = best;
    }
    for (int k = 0; k < 3; k++)
        for (int c = 0; c < BVH_WIDTH; c++) {
            float a = (n->lo[k][c] - f->pad - f->o[k]) * f->inv[k];
            float z = (n->hi[k][c] + f->pad - f->o[k]) * f->inv[k];
            float lo = a < z ? a : z, hi = a < z ? z : a;
            t0[c] = lo > t0[c] ? lo : t0[c];
            t1[c] = hi < t1[c] ? hi : t1[c];
        }
    int mask = 0;
    for (int c = 0; c < BVH_WIDTH; c++) {
        t_out[c] = t0[c];
        mask |= (t0[c] * (1 - 0x1p-20f) <= t1[c] * (1 + 0x1p-20f) && n->child[c] != BVH_NONE) << c;
    }
    return mask;
}

void bvh_ray(const Bvh *b, const double origin[3], const double dir[3], double tmax, uint32_t skip,
             BvhRayHit *hit)
{
    double best = tmax;
    uint32_t bt = BVH_NONE;
    RayF f;
    float big = 0;
    if (b->nnodes)
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < BVH_WIDTH; c++)
                if (b->node[0].child[c] != BVH_NONE)
                    big = fmaxf(big, fmaxf(fabsf(b->node[0].lo[k][c]), fabsf(b->node[0].hi[k][c])));
    for (int k = 0; k < 3; k++) {
        f.o[k] = (float)origin[k];
        f.inv[k] = dir[k] != 0 ? (float)(1 / dir[k]) : 1e30f;
        big = fmaxf(big, fabsf(f.o[k]));
    }
    f.pad = big * 0x1p-20f + 0x1p-100f;
    /* invariant: each entry is a child the ray enters at t, which was at
     * most the best hit when it was pushed */
    struct {
        uint32_t child, count;
        float    t;
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
        if (stack[top].t * (1 - 0x1p-20f) > best)
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
        float e[BVH_WIDTH];
        int k = 0, idx[BVH_WIDTH];
        int mask = enter_boxes(n, &f, best < 3e38 ? (float)best * (1 + 0x1p-20f) : 3e38f, e);
        for (int c = 0; c < BVH_WIDTH; c++) {
            if (!(mask >> c & 1))
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
