/* exactsign.c: is a face degenerate, decided exactly, as the check
 * decides it (its corners on one line).
 *
 * Three points of float coordinates are on one line when the cross
 * product (b - a) x (c - a) is zero. Each of its components, expanded,
 * is a sum of six products of two coordinates; a product of two floats
 * is exact in a double (24 + 24 bits < 53), so only the sum can round.
 * A floating-point filter decides nearly every case (a sum far from
 * zero against the bound of its rounding error); the rest are summed
 * exactly as a non-overlapping expansion (Shewchuk, "Adaptive Precision
 * Floating-Point Arithmetic and Fast Robust Geometric Predicates",
 * 1997: TwoSum and Grow-Expansion with zero elimination), which is zero
 * only when the sum is. */

#include <float.h>
#include <math.h>

#include "repair_internal.h"

/* a + b = s + e exactly (Knuth's TwoSum: no branch, any magnitudes). */
static inline void two_sum(double a, double b, double *s, double *e)
{
    double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* Is t[0] + ... + t[n-1] (n <= 6) exactly zero? */
static int sum_is_zero(const double *t, int n)
{
    double approx = 0, mag = 0;
    for (int i = 0; i < n; i++) {
        approx += t[i];
        mag += fabs(t[i]);
    }
    /* the rounding error of n - 1 additions is below n eps times the
     * magnitudes' sum (generously): beyond it, not zero */
    if (fabs(approx) > 8 * n * DBL_EPSILON * mag)
        return 0;
    if (mag == 0)
        return 1;
    double e[8];
    int m = 0;
    for (int i = 0; i < n; i++) {
        double q = t[i];
        int k = 0;
        for (int j = 0; j < m; j++) {
            double s, err;
            two_sum(q, e[j], &s, &err);
            if (err != 0)
                e[k++] = err;
            q = s;
        }
        if (q != 0)
            e[k++] = q;
        m = k;
    }
    /* zero eliminated: the expansion is empty exactly when the sum is 0 */
    return m == 0;
}

int rp_collinear(const float *a, const float *b, const float *c)
{
    /* component (i, j) of (b - a) x (c - a):
     * b_i c_j - b_j c_i - a_i c_j + a_j c_i - b_i a_j + b_j a_i */
    static const int axis[3][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 } };
    for (int k = 0; k < 3; k++) {
        int i = axis[k][0], j = axis[k][1];
        double t[6] = {
            (double)b[i] * c[j], -(double)b[j] * c[i], -(double)a[i] * c[j],
            (double)a[j] * c[i], -(double)b[i] * a[j], (double)b[j] * a[i],
        };
        if (!sum_is_zero(t, 6))
            return 0;
    }
    return 1;
}

/* As the check: the first corner's point p, the first other point q,
 * then every further point on the line pq. */
int rp_poly_degenerate(const Rep *r, const uint32_t *v, uint32_t n)
{
    if (n < 3)
        return 1;
    uint32_t p = r->pid[v[0]], q = RP_NONE, qv = 0;
    for (uint32_t c = 1; c < n; c++) {
        uint32_t pt = r->pid[v[c]];
        if (pt == p || pt == q)
            continue;
        if (q == RP_NONE) {
            q = pt;
            qv = v[c];
            continue;
        }
        if (!rp_collinear(rp_vpos(r, v[0]), rp_vpos(r, qv), rp_vpos(r, v[c])))
            return 0;
    }
    return 1;
}

int rp_face_degenerate(const Rep *r, uint32_t f)
{
    const Mesh *m = &r->w;
    return rp_poly_degenerate(r, m->corner + m->face_start[f], m->face_start[f + 1] - m->face_start[f]);
}

/* The same on positions: corners at one position are one point. */
static int same_pos(const float *a, const float *b)
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

int rp_pos_degenerate(const float *const *p, uint32_t n)
{
    if (n < 3)
        return 1;
    const float *q = NULL;
    for (uint32_t c = 1; c < n; c++) {
        if (same_pos(p[c], p[0]) || (q && same_pos(p[c], q)))
            continue;
        if (!q) {
            q = p[c];
            continue;
        }
        if (!rp_collinear(p[0], q, p[c]))
            return 0;
    }
    return 1;
}
