/* tritri.c: do two triangles meet beyond the corners they share? Exact,
 * with the orientation predicates of exact.c alone.
 *
 * Method: the orientation-predicate formulation of triangle overlap of
 * O. Devillers and P. Guigue, "Faster Triangle-Triangle Intersection
 * Tests" (INRIA RR-4488, 2002): reject when one triangle lies strictly
 * on one side of the other's plane; coplanar triangles are tested in
 * the projection on an axis plane where they stay triangles. Where they
 * go further case by case, we use a shorter argument that needs no
 * orientation bookkeeping: two closed triangles in different planes
 * meet iff an edge of one meets the other (the planes meet in a line,
 * and the two segments it cuts from the triangles, when they overlap,
 * end on an edge of one of them), and a segment meets a triangle iff it
 * reaches the plane and the line through it passes inside the three
 * edges (three orient3d of one sign: the Pluecker side test).
 *
 * Corners shared by index (the same point) are the mesh's own joints,
 * not crossings:
 *   - one shared corner v, T1 = (v, a, b), T2 = (v, c, d): they meet
 *     beyond v iff segment ab meets T2 or segment cd meets T1. (Their
 *     common part is convex and holds v; any other point of it lies on
 *     a side of it that is not through v, and that side lies on ab or
 *     cd; a common part that is a segment from v ends on ab or cd too.)
 *     In one plane, iff their wedges at v share a ray (fewer tests).
 *   - two shared corners a, b: in different planes the triangles meet
 *     in ab alone; in one plane they overlap iff the third corners lie
 *     on the same side of ab.
 * Every triangle here is non-degenerate (the caller skips the others). */

#include "exact.h"
#include "check_internal.h"

/* ==== In one plane: 2D tests on the axes (i, j) ==== */

/* The axes of the projection where the non-degenerate triangle (a, b, c)
 * stays a triangle: drop z, else x, else y. Returns its orientation
 * there (nonzero). */
static int pick_plane(const float *a, const float *b, const float *c, int *i, int *j)
{
    static const int ax[3][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 } };
    for (int k = 0; k < 3; k++) {
        int o = exact_orient2d(a, b, c, ax[k][0], ax[k][1]);
        if (o) {
            *i = ax[k][0];
            *j = ax[k][1];
            return o;
        }
    }
    return 0;   /* degenerate: the caller promised otherwise */
}

/* Do the closed segments pq and rs meet? */
static int seg_seg_2d(const float *p, const float *q, const float *r, const float *s, int i, int j)
{
    int o1 = exact_orient2d(p, q, r, i, j), o2 = exact_orient2d(p, q, s, i, j);
    if (o1 * o2 > 0)
        return 0;
    int o3 = exact_orient2d(r, s, p, i, j), o4 = exact_orient2d(r, s, q, i, j);
    if (o3 * o4 > 0)
        return 0;
    if (o1 == 0 && o2 == 0) {
        /* on one line: overlap along an axis the line is not constant on */
        int k = p[i] != q[i] ? i : j;
        float lo1 = p[k] < q[k] ? p[k] : q[k], hi1 = p[k] < q[k] ? q[k] : p[k];
        float lo2 = r[k] < s[k] ? r[k] : s[k], hi2 = r[k] < s[k] ? s[k] : r[k];
        return (lo1 > lo2 ? lo1 : lo2) <= (hi1 < hi2 ? hi1 : hi2);
    }
    return 1;
}

/* Is p in the closed triangle (a, b, c) of orientation o (nonzero)? */
static int in_tri_2d(const float *p, const float *a, const float *b, const float *c, int o, int i, int j)
{
    return exact_orient2d(a, b, p, i, j) * o >= 0 && exact_orient2d(b, c, p, i, j) * o >= 0 &&
           exact_orient2d(c, a, p, i, j) * o >= 0;
}

/* Does the closed segment pq meet the closed triangle t, all in the
 * triangle's plane (projected on i, j where t has orientation o)? */
static int seg_tri_2d(const float *p, const float *q, const float *const t[3], int o, int i, int j)
{
    if (in_tri_2d(p, t[0], t[1], t[2], o, i, j) || in_tri_2d(q, t[0], t[1], t[2], o, i, j))
        return 1;
    for (int k = 0; k < 3; k++)
        if (seg_seg_2d(p, q, t[k], t[(k + 1) % 3], i, j))
            return 1;
    return 0;
}

/* Two triangles in one plane: an edge of one crosses an edge of the
 * other, or one holds a corner of the other. */
static int tri_tri_2d(const float *const a[3], const float *const b[3])
{
    int i = 0, j = 1;
    int oa = pick_plane(a[0], a[1], a[2], &i, &j);
    int ob = exact_orient2d(b[0], b[1], b[2], i, j);
    /* both non-degenerate (collect leaves the others out), and b in
     * a's plane, so both stay triangles on a's axes: a 0 here would
     * call a real overlap apart */
    ZV_ASSERT(oa && ob);
    if (!oa || !ob)
        return 0;
    for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++)
            if (seg_seg_2d(a[k], a[(k + 1) % 3], b[l], b[(l + 1) % 3], i, j))
                return 1;
    return in_tri_2d(a[0], b[0], b[1], b[2], ob, i, j) || in_tri_2d(b[0], a[0], a[1], a[2], oa, i, j);
}

/* ==== In space ==== */

/* Does the closed segment pq meet the closed triangle t? op and oq are
 * orient3d(t, p) and orient3d(t, q). */
static int seg_tri(const float *p, const float *q, int op, int oq, const float *const t[3])
{
    if (op * oq > 0)
        return 0;                       /* one side of the plane */
    if (op == 0 && oq == 0) {
        int i, j;
        int o = pick_plane(t[0], t[1], t[2], &i, &j);
        return o && seg_tri_2d(p, q, t, o, i, j);
    }
    /* the segment reaches the plane: where the line passes it is inside
     * the triangle iff no two of these signs are opposite */
    int s1 = exact_orient3d(p, q, t[0], t[1]);
    int s2 = exact_orient3d(p, q, t[1], t[2]);
    if (s1 * s2 < 0)
        return 0;
    int s3 = exact_orient3d(p, q, t[2], t[0]);
    return s1 * s3 >= 0 && s2 * s3 >= 0;
}

/* No shared corner. */
static int tri_tri_apart(const float *const a[3], const float *const b[3])
{
    int ob[3], oa[3];
    ExactPlane pl;
    exact_plane(&pl, a[0], a[1], a[2]);
    for (int k = 0; k < 3; k++)
        ob[k] = exact_plane_side(&pl, b[k]);
    if ((ob[0] > 0 && ob[1] > 0 && ob[2] > 0) || (ob[0] < 0 && ob[1] < 0 && ob[2] < 0))
        return 0;
    /* in one plane: a's corners are on b's plane too, no need to ask
     * (in a coplanar stack each orient3d is exact arithmetic) */
    if (ob[0] == 0 && ob[1] == 0 && ob[2] == 0)
        return tri_tri_2d(a, b);
    exact_plane(&pl, b[0], b[1], b[2]);
    for (int k = 0; k < 3; k++)
        oa[k] = exact_plane_side(&pl, a[k]);
    if ((oa[0] > 0 && oa[1] > 0 && oa[2] > 0) || (oa[0] < 0 && oa[1] < 0 && oa[2] < 0))
        return 0;
    for (int k = 0; k < 3; k++) {
        int l = (k + 1) % 3;
        if (seg_tri(a[k], a[l], oa[k], oa[l], b) || seg_tri(b[k], b[l], ob[k], ob[l], a))
            return 1;
    }
    return 0;
}

/* Is the ray from v through x in the closed wedge from v between the
 * rays through p and q, of orientation o (nonzero: narrower than a half
 * turn)? */
static int ray_in_wedge_2d(const float *v, const float *p, const float *q, const float *x, int o, int i, int j)
{
    return exact_orient2d(v, p, x, i, j) * o >= 0 && exact_orient2d(v, x, q, i, j) * o >= 0;
}

/* a[0] is b[0], and all five corners are in one plane: the triangles
 * meet beyond the shared corner v iff their wedges at v share a ray
 * (their common part is convex and holds v, so a point of it beyond v
 * brings the segment to v, which starts in both wedges; the other way
 * the ray's first stretch is in both triangles). Two closed wedges
 * narrower than a half turn share a ray iff one holds a side of the
 * other: at most six orient2d, where the general test took some forty
 * (a planar fan of 40k triangles is all such pairs). */
static int tri_tri_vertex_2d(const float *const a[3], const float *const b[3])
{
    int i = 0, j = 1;
    int oa = pick_plane(a[0], a[1], a[2], &i, &j);
    int ob = exact_orient2d(b[0], b[1], b[2], i, j);
    if (!oa || !ob)
        return 0;
    return ray_in_wedge_2d(a[0], a[1], a[2], b[1], oa, i, j) || ray_in_wedge_2d(a[0], a[1], a[2], b[2], oa, i, j) ||
           ray_in_wedge_2d(b[0], b[1], b[2], a[1], ob, i, j);
}

/* a[0] is b[0]: does a's far side a[1]a[2] meet b, or b[1]b[2] meet a?
 * When a's far corners lie strictly on one side of b's plane, all of a
 * but the shared corner does, and neither can (and the other way). */
static int tri_tri_vertex(const float *const a[3], const float *const b[3])
{
    ExactPlane pl;
    exact_plane(&pl, b[0], b[1], b[2]);
    int o1 = exact_plane_side(&pl, a[1]), o2 = exact_plane_side(&pl, a[2]);
    if (o1 * o2 > 0)
        return 0;
    if (o1 == 0 && o2 == 0)
        return tri_tri_vertex_2d(a, b);
    exact_plane(&pl, a[0], a[1], a[2]);
    int o3 = exact_plane_side(&pl, b[1]), o4 = exact_plane_side(&pl, b[2]);
    if (o3 * o4 > 0)
        return 0;
    return seg_tri(a[1], a[2], o1, o2, b) || seg_tri(b[1], b[2], o3, o4, a);
}

/* a[0], a[1] are b's corners too; a[2] and the third corner d of b. */
static int tri_tri_edge(const float *const a[3], const float *d)
{
    if (exact_orient3d(a[0], a[1], a[2], d) != 0)
        return 0;
    int i = 0, j = 1;
    int o = pick_plane(a[0], a[1], a[2], &i, &j);
    return o != 0 && exact_orient2d(a[0], a[1], d, i, j) == o;
}

int check_tri_pair(const float *const a[3], const uint32_t ia[3], const float *const b[3], const uint32_t ib[3])
{
    /* k + 1 and k + 2 mod 3, from a table (the division was a tenth
     * of this function's time) */
    static const int mod3[5] = { 0, 1, 2, 0, 1 };
    int sa[3];                      /* b's corner that is a's corner k, -1 none */
    int n = 0;
    /* three points a triangle: the shared-corner cases (l = 3 - ...)
     * count on it, and a corner of a is then at most one of b's */
    ZV_ASSERT(ia[0] != ia[1] && ia[1] != ia[2] && ia[0] != ia[2] && ib[0] != ib[1] && ib[1] != ib[2] &&
              ib[0] != ib[2]);
    for (int k = 0; k < 3; k++) {
        sa[k] = ia[k] == ib[0] ? 0 : ia[k] == ib[1] ? 1 : ia[k] == ib[2] ? 2 : -1;
        n += sa[k] >= 0;
    }
    if (n == 0)
        return tri_tri_apart(a, b);
    if (n >= 3)
        return CHECK_SAME_TRI;
    if (n == 1) {
        /* turn both so that the shared corner comes first (orientation
         * does not matter to the test) */
        int k = sa[0] >= 0 ? 0 : sa[1] >= 0 ? 1 : 2, l = sa[k];
        const float *ra[3] = { a[k], a[mod3[k + 1]], a[mod3[k + 2]] };
        const float *rb[3] = { b[l], b[mod3[l + 1]], b[mod3[l + 2]] };
        return tri_tri_vertex(ra, rb);
    }
    /* two shared: a's free corner, and b's (the one no sa names) */
    int k = sa[0] < 0 ? 0 : sa[1] < 0 ? 1 : 2;
    int l = 3 - (sa[mod3[k + 1]] + sa[mod3[k + 2]]);
    const float *ra[3] = { a[mod3[k + 1]], a[mod3[k + 2]], a[k] };
    return tri_tri_edge(ra, b[l]);
}
