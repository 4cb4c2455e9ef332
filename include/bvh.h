#ifndef ZV_BVH_H
#define ZV_BVH_H
/* bvh: a bounding-volume hierarchy over triangles, for the geometric
 * questions asked millions of times of one surface: the nearest point
 * of the triangles to a point (--diff's distances, src/diff/). The
 * nodes are boxes and the leaves hold the triangles' corners in leaf
 * order, so that another walk of the same nodes (a ray's first hit, for
 * wall thickness) needs no other data. Knows nothing of files, scenes or
 * screens: triangles in as positions and corner triples.
 *
 * Exactness: the boxes are exact (float corners, float boxes), the
 * distances to triangles are computed in double from the float corners,
 * and a box is passed over only when it is farther than the best
 * distance found by a margin that rounding cannot close (the boxes'
 * distances are taken in float, four at a time, and the margin covers
 * their rounding and the query point's). So a query gives the least of
 * the distances bvh_point_triangle computes over every triangle, bit
 * for bit (tests/test_bvh.c compares it with every triangle tried). */

#include <stddef.h>
#include <stdint.h>

#define BVH_LEAF_MAX  4         /* triangles a leaf holds at most */
#define BVH_DEPTH_MAX 64        /* levels at most (bvh.c: 15 of codes, then halving twice a level) */
#define BVH_NONE      UINT32_MAX

/* An inner node, two cache lines: the boxes of its (up to) four
 * children (x, y, z of their low and high corners, child by child) and
 * what they are: count 0, an inner node (child is its index); else a
 * leaf of count triangles from child on (leaf order). A child that is
 * not there is BVH_NONE, its box empty (lo > hi). */
#define BVH_WIDTH 4
typedef struct {
    float    lo[3][BVH_WIDTH], hi[3][BVH_WIDTH];
    uint32_t child[BVH_WIDTH];
    uint32_t count[BVH_WIDTH];
} BvhNode;

typedef struct {
    BvhNode  *node;             /* node 0 is the root; 64-byte aligned */
    uint32_t  nnodes;
    float    *corner;           /* 9 per triangle in leaf order: the corners' x y z */
    uint32_t *id;               /* per triangle in leaf order: the id it was given */
    uint32_t  ntris;
    uint32_t  depth;            /* levels of the deepest leaf (the root's children are level 1) */
} Bvh;

/* Build over ntris triangles, corners tri[3 t .. 3 t + 2] into pos (3
 * floats a vertex, nverts of them; an index past them is refused), each
 * carrying id[t] (NULL: t) back from a query. Triangles of zero area
 * (segments, points) are kept: they have a nearest point too. 0, or -1
 * with the reason in err (out of memory, a bad index). */
int  bvh_build(Bvh *b, const float *pos, uint32_t nverts, const uint32_t *tri, const uint32_t *id,
               uint32_t ntris, char *err, size_t errlen);
void bvh_free(Bvh *b);
/* Bytes bvh_build holds at most, building for ntris triangles. */
uint64_t bvh_build_bytes(uint64_t ntris);

/* A query's answer. */
typedef struct {
    double   d2;                /* the squared distance; +inf: no triangle */
    double   p[3];              /* the nearest point */
    uint32_t tri;               /* its triangle in leaf order (b->id[tri] is its id), BVH_NONE: no triangle */
} BvhHit;

/* The nearest point of the triangles to q into hit; of triangles at
 * the same least distance, the first in leaf order. */
void bvh_closest(const Bvh *b, const double q[3], BvhHit *hit);
/* The same answer, bit for bit, the walk started from a guess: hint, a
 * triangle in leaf order (BVH_NONE: none) thought near q, such as the
 * answer for a point near q. Its distance bounds the walk from the
 * root on, so a good guess passes over most boxes at their first test;
 * every triangle as near as the best so far is still met, so the least
 * distance and the first of its triangles in leaf order are found
 * whatever the guess. */
void bvh_closest_from(const Bvh *b, const double q[3], uint32_t hint, BvhHit *hit);

/* A ray's first hit (bvhray.c). */
typedef struct {
    double   t;                 /* the hit at origin + t dir; +inf: none */
    uint32_t tri;               /* its triangle in leaf order, BVH_NONE: none */
} BvhRayHit;

/* The first triangle the ray origin + t dir meets for t in (0, tmax],
 * passing over the triangles whose id is skip (BVH_NONE: none; a face
 * cast from itself). Triangles parallel to the ray and of zero area are
 * never met. Moller and Trumbore's test (1997) in double from the float
 * corners, with a margin of 2^-30 of the barycentric range, so that a
 * ray through an edge two triangles share meets one of them. */
void bvh_ray(const Bvh *b, const double origin[3], const double dir[3], double tmax, uint32_t skip,
             BvhRayHit *hit);

/* The n points pos (3 floats each) in the order of a Morton curve
 * (10 bits an axis) through box (low x y z, high x y z; NULL: their
 * own box) into order, and each one's code into code (NULL: not
 * wanted), ascending: points near one another come close together, so
 * queries in that order walk much the same path, and points at one
 * position have one code. 0, or -1 out of memory. */
int bvh_order(const float *pos, uint32_t n, const float *box, uint32_t *order, uint32_t *code);

/* The point of triangle (a, b, c) nearest to q into out; returns the
 * squared distance. Any triangle: one of zero area is taken as its
 * longest side (or a point). */
double bvh_point_triangle(const double q[3], const double a[3], const double b[3], const double c[3],
                          double out[3]);

#endif
