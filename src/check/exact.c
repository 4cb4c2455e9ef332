/* exact.c: orientation predicates with an always-right sign, on float
 * coordinates.
 *
 * Method: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic
 * and Fast Robust Geometric Predicates", Discrete & Computational
 * Geometry 18 (1997). The fast stage evaluates the determinant in
 * doubles and trusts its sign when it exceeds the paper's error bound
 * (its orient2d and orient3d "A" bounds). The exact stage is ours and
 * simpler than the paper's adaptive stages: with float inputs a product
 * of two coordinates has at most 48 significant bits and is exact in a
 * double, so each monomial of the determinant expanded in the original
 * coordinates (6 of two factors for orient2d, 24 of three for orient3d)
 * is one exact double, or two after one exact product (Dekker's split).
 * The monomials are summed into a nonoverlapping expansion with the
 * paper's Two-Sum and Grow-Expansion (zero components dropped), whose
 * largest component has the sign of the exact sum. The range of floats
 * keeps every product far from double overflow and underflow (|x y z|
 * < 2^385, and a nonzero product is > 2^-447), so nothing is lost.
 *
 * The exact stage runs only for (nearly) degenerate inputs: coplanar
 * faces of a flat part, collinear corners. orient3d tries 128-bit
 * integers first (orient3d_fixed), which cover coordinates of one
 * magnitude, before the expansion. */

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "exact.h"

/* ==== Expansion arithmetic ==== */

/* a + b = *s + *e exactly, *s the rounded sum (Knuth's Two-Sum). */
static inline void two_sum(double a, double b, double *s, double *e)
{
    double x = a + b;
    double bv = x - a;
    double av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* a = hi + lo, each with at most 26 significant bits (Veltkamp). */
static inline void split(double a, double *hi, double *lo)
{
    double c = 134217729.0 * a;     /* 2^27 + 1 */
    double big = c - a;
    *hi = c - big;
    *lo = a - *hi;
}

/* a * b = *p + *e exactly (Dekker's Two-Product). */
static inline void two_product(double a, double b, double *p, double *e)
{
    double x = a * b, ah, al, bh, bl;
    split(a, &ah, &al);
    split(b, &bh, &bl);
    double e1 = x - ah * bh;
    double e2 = e1 - al * bh;
    double e3 = e2 - ah * bl;
    *p = x;
    *e = al * bl - e3;
}

/* An expansion: components of increasing magnitude that do not overlap,
 * summing exactly to the value. 48 monomials of two components each
 * make at most 96 components. */
#define EXP_MAX 100

typedef struct {
    double c[EXP_MAX];
    int    n;
} Expansion;

/* e += b exactly (Grow-Expansion), zeros dropped; in place is safe: the
 * k-th component written never passes the i-th read. */
static void exp_add(Expansion *e, double b)
{
    double q = b;
    int k = 0;
    for (int i = 0; i < e->n; i++) {
        double s, t;
        two_sum(q, e->c[i], &s, &t);
        if (t != 0)
            e->c[k++] = t;
        q = s;
    }
    if (q != 0)
        e->c[k++] = q;
    e->n = k;
}

/* The sign of the exact value: its largest component's. */
static int exp_sign(const Expansion *e)
{
    if (e->n == 0)
        return 0;
    double top = e->c[e->n - 1];
    return top > 0 ? 1 : top < 0 ? -1 : 0;
}

/* e += s x y z exactly, s = +-1: x y is exact (48 bits), then one
 * Two-Product. */
static void exp_add_monomial(Expansion *e, int s, double x, double y, double z)
{
    double p, err;
    two_product(x * y, z, &p, &err);
    exp_add(e, s * err);
    exp_add(e, s * p);
}

/* e += s det[p; q; r] (rows), its six monomials. */
static void exp_add_det3(Expansion *e, int s, const float *p, const float *q, const float *r)
{
    exp_add_monomial(e, s, p[0], q[1], r[2]);
    exp_add_monomial(e, -s, p[0], q[2], r[1]);
    exp_add_monomial(e, -s, p[1], q[0], r[2]);
    exp_add_monomial(e, s, p[1], q[2], r[0]);
    exp_add_monomial(e, s, p[2], q[0], r[1]);
    exp_add_monomial(e, -s, p[2], q[1], r[0]);
}

/* ==== Predicates ==== */

/* Shewchuk's bounds on the double evaluation's error, relative to the
 * permanent (the sum of the absolute products): exact.h, which the
 * callers' own filters share. */
#define O3D_BOUND EXACT_O3D_BOUND
#define O2D_BOUND EXACT_O2D_BOUND

/* The same determinant in 128-bit integers, when the coordinates allow:
 * a float is M 2^(e-150) with M < 2^24 (e its exponent field), so when
 * the twelve fields span at most 16, every coordinate is an integer
 * multiple of 2^(lo-150) below 2^40, the differences are below 2^41,
 * their triple products below 2^123 and the determinant below 2^126.
 * That is the common case of a nearly flat neighbourhood of a mesh (its
 * coordinates of one magnitude), and much faster than the expansion.
 * Returns 0 when the coordinates do not allow (a range too wide, a
 * subnormal), else 1 with the sign in *sign. */
#ifdef __SIZEOF_INT128__
static int orient3d_fixed(const float *a, const float *b, const float *c, const float *d, int *sign)
{
    const float *p[4] = { a, b, c, d };
    int lo = 256, hi = -1;
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t u;
            memcpy(&u, &p[i][k], sizeof u);
            int e = (int)(u >> 23 & 0xff);
            if ((e == 0 && (u & 0x7fffff)) || e == 255)
                return 0;               /* subnormal, or not finite */
            if (e == 0)
                continue;               /* zero: any multiple */
            lo = e < lo ? e : lo;
            hi = e > hi ? e : hi;
        }
    if (hi < 0) {
        *sign = 0;                      /* every coordinate zero */
        return 1;
    }
    if (hi - lo > 16)
        return 0;
    /* each coordinate times 2^(150 - lo), from its bits (ldexp was most
     * of the time of a coplanar pair): the significand with its hidden
     * bit, shifted by its exponent's distance to lo, an integer below
     * 2^40 */
    int64_t q[4][3];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t u;
            memcpy(&u, &p[i][k], sizeof u);
            int e = (int)(u >> 23 & 0xff);
            int64_t m = e ? (int64_t)((u & 0x7fffff) | 0x800000) << (e - lo) : 0;
            q[i][k] = u >> 31 ? -m : m;
        }
    int64_t adx = q[0][0] - q[3][0], ady = q[0][1] - q[3][1], adz = q[0][2] - q[3][2];
    int64_t bdx = q[1][0] - q[3][0], bdy = q[1][1] - q[3][1], bdz = q[1][2] - q[3][2];
    int64_t cdx = q[2][0] - q[3][0], cdy = q[2][1] - q[3][1], cdz = q[2][2] - q[3][2];
    __int128 bc = (__int128)bdx * cdy - (__int128)cdx * bdy;
    __int128 ca = (__int128)cdx * ady - (__int128)adx * cdy;
    __int128 ab = (__int128)adx * bdy - (__int128)bdx * ady;
    __int128 det = bc * adz + ca * bdz + ab * cdz;
    *sign = det > 0 ? 1 : det < 0 ? -1 : 0;
    return 1;
}
#else
/* No 128-bit integers on this compiler: the expansion does it all. */
static int orient3d_fixed(const float *a, const float *b, const float *c, const float *d, int *sign)
{
    (void)a, (void)b, (void)c, (void)d, (void)sign;
    return 0;
}
#endif

/* det[a-d; b-d; c-d] = det(a,b,c) - det(a,b,d) + det(a,c,d) - det(b,c,d):
 * the 4x4 determinant of the points with a column of ones, expanded
 * along that column. */
static int orient3d_exact(const float *a, const float *b, const float *c, const float *d)
{
    Expansion e = { .n = 0 };
    exp_add_det3(&e, 1, a, b, c);
    exp_add_det3(&e, -1, a, b, d);
    exp_add_det3(&e, 1, a, c, d);
    exp_add_det3(&e, -1, b, c, d);
    return exp_sign(&e);
}

int exact_orient3d(const float *a, const float *b, const float *c, const float *d)
{
    double adx = (double)a[0] - d[0], ady = (double)a[1] - d[1], adz = (double)a[2] - d[2];
    double bdx = (double)b[0] - d[0], bdy = (double)b[1] - d[1], bdz = (double)b[2] - d[2];
    double cdx = (double)c[0] - d[0], cdy = (double)c[1] - d[1], cdz = (double)c[2] - d[2];
    double bc = bdx * cdy, cb = cdx * bdy;
    double ca = cdx * ady, ac = adx * cdy;
    double ab = adx * bdy, ba = bdx * ady;
    double det = adz * (bc - cb) + bdz * (ca - ac) + cdz * (ab - ba);
    double perm = (fabs(bc) + fabs(cb)) * fabs(adz) + (fabs(ca) + fabs(ac)) * fabs(bdz) +
                  (fabs(ab) + fabs(ba)) * fabs(cdz);
    double bound = O3D_BOUND * perm;
    if (det > bound)
        return 1;
    if (det < -bound)
        return -1;
    /* every term zero (points in an axis plane): a difference of floats
     * rounds to zero only when it is zero, and a product of nonzero ones
     * is far above the underflow (|x| >= 2^-149 each), so each term is
     * exactly zero */
    if (perm == 0)
        return 0;
    int sign;
    if (orient3d_fixed(a, b, c, d, &sign))
        return sign;
    return orient3d_exact(a, b, c, d);
}

/* (a_i - c_i)(b_j - c_j) - (a_j - c_j)(b_i - c_i) expanded: six exact
 * products of two floats. */
static int orient2d_exact(const float *a, const float *b, const float *c, int i, int j)
{
    Expansion e = { .n = 0 };
    exp_add(&e, (double)a[i] * b[j]);
    exp_add(&e, -((double)a[j] * b[i]));
    exp_add(&e, (double)b[i] * c[j]);
    exp_add(&e, -((double)b[j] * c[i]));
    exp_add(&e, (double)c[i] * a[j]);
    exp_add(&e, -((double)c[j] * a[i]));
    return exp_sign(&e);
}

int exact_orient2d(const float *a, const float *b, const float *c, int i, int j)
{
    double l = ((double)a[i] - c[i]) * ((double)b[j] - c[j]);
    double r = ((double)a[j] - c[j]) * ((double)b[i] - c[i]);
    double det = l - r;
    double bound = O2D_BOUND * (fabs(l) + fabs(r));
    if (det > bound)
        return 1;
    if (det < -bound)
        return -1;
    return orient2d_exact(a, b, c, i, j);
}

int exact_collinear(const float *a, const float *b, const float *c)
{
    return exact_orient2d(a, b, c, 0, 1) == 0 && exact_orient2d(a, b, c, 1, 2) == 0 &&
           exact_orient2d(a, b, c, 2, 0) == 0;
}
