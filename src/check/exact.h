#ifndef ZV_CHECK_EXACT_H
#define ZV_CHECK_EXACT_H
/* exact: orientation predicates whose sign is always right, on float
 * coordinates (what a Mesh holds). A double evaluation answers when its
 * error bound says the sign is certain; otherwise the determinant is
 * summed exactly as an expansion of doubles. Used by the check's
 * degenerate-face and intersection tests (src/check/). */

#include <float.h>
#include <math.h>

/* The sign (+1, 0, -1) of det[a-d; b-d; c-d]: positive when d lies on
 * the side of the plane (a, b, c) that sees a, b, c clockwise. Only the
 * sign's consistency matters to the callers. */
int exact_orient3d(const float *a, const float *b, const float *c, const float *d);

/* Shewchuk's bound on the double evaluation's error of orient3d,
 * relative to the permanent (eps = 2^-53): the "A" bound of his paper,
 * which covers the rounding of the nine differences too. */
#define EXACT_O3D_BOUND ((7.0 + 56.0 * (DBL_EPSILON / 2)) * (DBL_EPSILON / 2))

/* One plane (a, b, c) for several exact_orient3d(a, b, c, d): the
 * triangle tests ask each triangle's plane about two or three points.
 * det[a-d; b-d; c-d] is det[a-d; b-a; c-a] (rows subtracted, exact),
 * and expanded along its first row it is Shewchuk's evaluation of
 * orient3d on those rows with the columns turned cyclically: the same
 * operations on nine rounded differences of the coordinates, so his
 * bound holds as it stands, and the cofactors of the first row, the
 * cross product (b - a) x (c - a) and the sums of its products'
 * magnitudes, serve every d. */
typedef struct {
    const float *a, *b, *c;
    double n[3];                /* (b - a) x (c - a), as orient3d computes its minors */
    double m[3];                /* each component's two products' magnitudes, summed */
} ExactPlane;

static inline void exact_plane(ExactPlane *pl, const float *a, const float *b, const float *c)
{
    double ux = (double)b[0] - a[0], uy = (double)b[1] - a[1], uz = (double)b[2] - a[2];
    double vx = (double)c[0] - a[0], vy = (double)c[1] - a[1], vz = (double)c[2] - a[2];
    double p0 = uy * vz, q0 = uz * vy, p1 = uz * vx, q1 = ux * vz, p2 = ux * vy, q2 = uy * vx;
    pl->a = a;
    pl->b = b;
    pl->c = c;
    pl->n[0] = p0 - q0;
    pl->n[1] = p1 - q1;
    pl->n[2] = p2 - q2;
    pl->m[0] = fabs(p0) + fabs(q0);
    pl->m[1] = fabs(p1) + fabs(q1);
    pl->m[2] = fabs(p2) + fabs(q2);
}

/* exact_orient3d(a, b, c, d) for the plane's a, b, c: the same sign
 * always (exact_orient3d itself answers when the bound cannot). */
static inline int exact_plane_side(const ExactPlane *pl, const float *d)
{
    double rx = (double)pl->a[0] - d[0], ry = (double)pl->a[1] - d[1], rz = (double)pl->a[2] - d[2];
    double det = rx * pl->n[0] + ry * pl->n[1] + rz * pl->n[2];
    double bound = EXACT_O3D_BOUND * (pl->m[0] * fabs(rx) + pl->m[1] * fabs(ry) + pl->m[2] * fabs(rz));
    if (det > bound)
        return 1;
    if (det < -bound)
        return -1;
    return exact_orient3d(pl->a, pl->b, pl->c, d);
}

/* The sign of the 2D orientation of a, b, c projected on the axes i and
 * j (0 = x, 1 = y, 2 = z): +1 counter-clockwise, 0 on one line. */
int exact_orient2d(const float *a, const float *b, const float *c, int i, int j);

/* Are a, b, c on one line (or equal)? Exactly: all three projections
 * have zero orientation. */
int exact_collinear(const float *a, const float *b, const float *c);

/* Shewchuk's bound for orient2d's double evaluation (his "A" bound). */
#define EXACT_O2D_BOUND ((3.0 + 16.0 * (DBL_EPSILON / 2)) * (DBL_EPSILON / 2))

/* exact_collinear, its commonest answer without the call: the first
 * projection's orientation evaluated as exact_orient2d's filter does
 * (the same operations), nonzero for sure when past the bound. Every
 * face of the model asks this once. */
static inline int exact_collinear_quick(const float *a, const float *b, const float *c)
{
    double l = ((double)a[0] - c[0]) * ((double)b[1] - c[1]);
    double r = ((double)a[1] - c[1]) * ((double)b[0] - c[0]);
    double det = l - r, bound = EXACT_O2D_BOUND * (fabs(l) + fabs(r));
    if (det > bound || det < -bound)
        return 0;
    return exact_collinear(a, b, c);
}

#endif
