/* secplane.c: a section plane: read from its text and written back,
 * moved along its normal, which side of it a point lies on (exactly),
 * and where an edge crosses it.
 *
 * The side test is the sign of (p - q) . n with p a float (a mesh's
 * position) and q, n doubles. A double evaluation answers when its
 * error bound says the sign is certain; otherwise the six products
 * n_i p_i and n_i q_i are split exactly (a product and its rounding
 * error, by fma) and summed as an expansion of doubles (Shewchuk's
 * grow-expansion, "Adaptive Precision Floating-Point Arithmetic and
 * Fast Robust Geometric Predicates", 1997), whose largest component
 * has the sign. An axis plane compares one coordinate, exactly. So
 * every vertex is on one side, whichever face asks. */

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "section.h"

/* Numbers a plane may be given: at most this in size; smaller than
 * its inverse is 0 (so that no product of the side test underflows). */
#define NUM_MAX 1e30

/* ==== reading and writing ==== */

/* A finite number of at most NUM_MAX in size, tiny ones made 0. */
static int read_num(const char *s, const char *end, double *out)
{
    char buf[64];
    size_t n = (size_t)(end - s);
    if (n == 0 || n >= sizeof buf)
        return -1;
    memcpy(buf, s, n);
    buf[n] = 0;
    char *e;
    errno = 0;
    double v = strtod(buf, &e);
    if (*e || e == buf || !isfinite(v) || fabs(v) > NUM_MAX)
        return -1;
    *out = fabs(v) < 1 / NUM_MAX ? 0 : v;
    return 0;
}

/* n numbers separated by commas, s .. end. */
static int read_nums(const char *s, const char *end, double *out, int n)
{
    for (int k = 0; k < n; k++) {
        const char *c = k + 1 < n ? memchr(s, ',', (size_t)(end - s)) : end;
        if (!c || read_num(s, c, &out[k]))
            return -1;
        s = c + 1;
    }
    return 0;
}

SectionPlane section_axis_plane(int axis, int neg, double v)
{
    SectionPlane pl = { { 0, 0, 0 }, { 0, 0, 0 }, axis };
    pl.q[axis] = v;
    pl.n[axis] = neg ? -1 : 1;
    return pl;
}

int section_parse(const char *s, SectionPlane *out, char *err, size_t errlen)
{
    const char *eq = strchr(s, '=');
    if (eq) {
        int neg = s[0] == '-', a = s[neg] - 'x';
        double v;
        if (eq != s + neg + 1 || a < 0 || a > 2 || read_num(eq + 1, eq + strlen(eq), &v)) {
            snprintf(err, errlen, "AXIS=VALUE with AXIS x, y, z, -x, -y or -z and VALUE at most 1e30 in size");
            return -1;
        }
        *out = section_axis_plane(a, neg, v);
        return 0;
    }
    const char *colon = strchr(s, ':');
    SectionPlane pl = { { 0, 0, 0 }, { 0, 0, 0 }, -1 };
    if (!colon || read_nums(s, colon, pl.q, 3) || read_nums(colon + 1, colon + strlen(colon), pl.n, 3) ||
        (pl.n[0] == 0 && pl.n[1] == 0 && pl.n[2] == 0)) {
        snprintf(err, errlen, "X,Y,Z:NX,NY,NZ, a point and a normal that is not 0, at most 1e30 in size");
        return -1;
    }
    *out = pl;
    return 0;
}

/* v in the fewest significant digits that strtod gives back exactly. */
static void shortest(double v, char *buf, size_t len)
{
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, len, "%.*g", p, v);
        if (strtod(buf, NULL) == v)
            return;
    }
}

void section_text(const SectionPlane *pl, char *buf, size_t len)
{
    char t[6][32];
    if (pl->axis >= 0) {
        shortest(pl->q[pl->axis], t[0], sizeof t[0]);
        snprintf(buf, len, "%s%c=%s", pl->n[pl->axis] < 0 ? "-" : "", 'x' + pl->axis, t[0]);
        return;
    }
    for (int k = 0; k < 3; k++) {
        shortest(pl->q[k], t[k], sizeof t[k]);
        shortest(pl->n[k], t[3 + k], sizeof t[k]);
    }
    snprintf(buf, len, "%s,%s,%s:%s,%s,%s", t[0], t[1], t[2], t[3], t[4], t[5]);
}

static double norm3(const double n[3])
{
    return sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

double section_offset(const SectionPlane *pl)
{
    if (pl->axis >= 0)
        return pl->n[pl->axis] < 0 ? -pl->q[pl->axis] : pl->q[pl->axis];
    return (pl->q[0] * pl->n[0] + pl->q[1] * pl->n[1] + pl->q[2] * pl->n[2]) / norm3(pl->n);
}

void section_slide(SectionPlane *pl, double d)
{
    if (pl->axis >= 0) {
        pl->q[pl->axis] += pl->n[pl->axis] < 0 ? -d : d;
        return;
    }
    double len = norm3(pl->n);
    for (int k = 0; k < 3; k++)
        pl->q[k] += d * pl->n[k] / len;
}

/* ==== the side of a point, exactly ==== */

/* a + b = s + e exactly (Knuth's two-sum). */
static inline void two_sum(double a, double b, double *s, double *e)
{
    double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* Add b to the expansion e[0 .. *n) (components non-overlapping,
 * increasing in size), exactly; zeros are left out. */
static void grow(double *e, int *n, double b)
{
    int m = 0;
    double q = b;
    for (int i = 0; i < *n; i++) {
        double s, h;
        two_sum(q, e[i], &s, &h);
        if (h != 0)
            e[m++] = h;
        q = s;
    }
    if (q != 0)
        e[m++] = q;
    *n = m;
}

static int side_exact(const SectionPlane *pl, const float p[3])
{
    double e[16];
    int n = 0;
    for (int k = 0; k < 3; k++) {
        double a = pl->n[k] * (double)p[k], b = -pl->n[k] * pl->q[k];
        grow(e, &n, a);
        grow(e, &n, fma(pl->n[k], (double)p[k], -a));
        grow(e, &n, b);
        grow(e, &n, fma(-pl->n[k], pl->q[k], -b));
    }
    return n == 0 ? 0 : e[n - 1] > 0 ? 1 : -1;
}

/* (p - q) . n in double, approximately. */
static inline double plane_f(const SectionPlane *pl, const float p[3])
{
    if (pl->axis >= 0)
        return ((double)p[pl->axis] - pl->q[pl->axis]) * pl->n[pl->axis];
    return pl->n[0] * ((double)p[0] - pl->q[0]) + pl->n[1] * ((double)p[1] - pl->q[1]) +
           pl->n[2] * ((double)p[2] - pl->q[2]);
}

int section_side(const SectionPlane *pl, const float p[3])
{
    if (pl->axis >= 0) {
        double v = p[pl->axis], q = pl->q[pl->axis];
        int s = v > q ? 1 : v < q ? -1 : 0;
        return pl->n[pl->axis] < 0 ? -s : s;
    }
    double d = plane_f(pl, p);
    /* each term's two roundings and the two sums' stay under 4.1 units
     * in the last place of the sum of magnitudes: 1e-15 of it is more */
    double mag = 0;
    for (int k = 0; k < 3; k++)
        mag += fabs(pl->n[k]) * (fabs((double)p[k]) + fabs(pl->q[k]));
    if (fabs(d) > 1e-15 * mag)
        return d > 0 ? 1 : -1;
    return side_exact(pl, p);
}

void section_edge_point(const SectionPlane *pl, const float a[3], const float b[3], float out[3])
{
    double fa = plane_f(pl, a), fb = plane_f(pl, b);
    double t = fb > fa ? -fa / (fb - fa) : 0;
    t = t > 0 ? (t < 1 ? t : 1) : 0;
    for (int k = 0; k < 3; k++)
        out[k] = (float)((double)a[k] + t * ((double)b[k] - a[k]));
    /* an axis plane's points lie on it to the float: the caps are flat
     * (the float nearest V lies between the ends, which are floats) */
    if (pl->axis >= 0)
        out[pl->axis] = (float)pl->q[pl->axis];
}

void section_masks(const SectionPlane *planes, int np, const float *pos, uint32_t n, uint8_t *mask)
{
    for (uint32_t v = 0; v < n; v++) {
        uint8_t m = 0;
        for (int i = 0; i < np; i++)
            m |= (uint8_t)((section_side(&planes[i], pos + 3 * (size_t)v) > 0) << i);
        mask[v] = m;
    }
}

int section_segment_cut(const SectionPlane *planes, int np, const float a[3], const float b[3], double *lo_out,
                        double *hi_out)
{
    double lo = 0, hi = 1;
    for (int i = 0; i < np; i++) {
        double fa = plane_f(&planes[i], a), fb = plane_f(&planes[i], b);
        if (fa > 0 && fb > 0)
            continue;
        if (fa <= 0 && fb <= 0)
            return 0;
        double t = fa / (fa - fb);
        if (fa > 0)
            hi = t < hi ? t : hi;
        else
            lo = t > lo ? t : lo;
    }
    if (!(lo < hi))
        return 0;
    *lo_out = lo;
    *hi_out = hi;
    return 1;
}
