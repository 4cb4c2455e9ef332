#ifndef ZV_CHECK_EXACT_H
#define ZV_CHECK_EXACT_H
/* exact: orientation predicates whose sign is always right, on float
 * coordinates (what a Mesh holds). A double evaluation answers when its
 * error bound says the sign is certain; otherwise the determinant is
 * summed exactly as an expansion of doubles. Used by the check's
 * degenerate-face and intersection tests (src/check/). */

/* The sign (+1, 0, -1) of det[a-d; b-d; c-d]: positive when d lies on
 * the side of the plane (a, b, c) that sees a, b, c clockwise. Only the
 * sign's consistency matters to the callers. */
int exact_orient3d(const float *a, const float *b, const float *c, const float *d);

/* The sign of the 2D orientation of a, b, c projected on the axes i and
 * j (0 = x, 1 = y, 2 = z): +1 counter-clockwise, 0 on one line. */
int exact_orient2d(const float *a, const float *b, const float *c, int i, int j);

/* Are a, b, c on one line (or equal)? Exactly: all three projections
 * have zero orientation. */
int exact_collinear(const float *a, const float *b, const float *c);

#endif
