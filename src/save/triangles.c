/* triangles.c: the triangles a polygon is written as in a format of
 * triangles (STL), chosen to cover what zview draws of it:
 *   - a face that is not planar (a corner off its plane by more than
 *     1e-4 of its size: the scene's rule) is drawn as the fan from its
 *     first corner, and written so;
 *   - a planar convex face is drawn whole, which its fan covers exactly;
 *   - a planar concave face is drawn whole too, but its fan would cover
 *     what lies outside it (and wind some triangles backwards): it is
 *     cut by ear clipping in its plane (Meisters, "Polygons have ears",
 *     1975), each ear a triangle wound as the face. A face ear clipping
 *     cannot cut (it crosses itself; more than EAR_MAX corners) is
 *     fanned.
 * Every triangle keeps the face's winding, so that the writer's triangles
 * of a sound model make a sound model. */

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "save_internal.h"

#define PLANAR_TOL 1e-4         /* as the scene's (scene.c): faces it keeps whole */
#define EAR_MAX    4096         /* corners: ear clipping is quadratic or worse */

/* Newell's normal of the face (not unit): in double, as the scene's. */
static void newell(const Mesh *m, uint32_t a, uint32_t n, double out[3])
{
    out[0] = out[1] = out[2] = 0;
    for (uint32_t k = 0; k < n; k++) {
        const float *p = &m->pos[3 * (size_t)m->corner[a + k]];
        const float *q = &m->pos[3 * (size_t)m->corner[a + (k + 1 < n ? k + 1 : 0)]];
        out[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
        out[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
        out[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
    }
}

static int planar(const Mesh *m, uint32_t a, uint32_t n, const double nrm[3])
{
    double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (len == 0)
        return 1;
    double c[3] = { 0, 0, 0 }, lo[3] = { DBL_MAX, DBL_MAX, DBL_MAX }, hi[3] = { -DBL_MAX, -DBL_MAX, -DBL_MAX };
    for (uint32_t k = 0; k < n; k++) {
        const float *p = &m->pos[3 * (size_t)m->corner[a + k]];
        for (int i = 0; i < 3; i++) {
            c[i] += p[i];
            lo[i] = p[i] < lo[i] ? p[i] : lo[i];
            hi[i] = p[i] > hi[i] ? p[i] : hi[i];
        }
    }
    double size = 0;
    for (int i = 0; i < 3; i++) {
        c[i] /= n;
        size += (hi[i] - lo[i]) * (hi[i] - lo[i]);
    }
    size = sqrt(size);
    for (uint32_t k = 0; k < n; k++) {
        const float *p = &m->pos[3 * (size_t)m->corner[a + k]];
        double d = ((p[0] - c[0]) * nrm[0] + (p[1] - c[1]) * nrm[1] + (p[2] - c[2]) * nrm[2]) / len;
        if (fabs(d) > PLANAR_TOL * size)
            return 0;
    }
    return 1;
}

static double cross2(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static void fan(uint32_t n, uint32_t *tri)
{
    for (uint32_t k = 1; k + 1 < n; k++) {
        *tri++ = 0;
        *tri++ = k;
        *tri++ = k + 1;
    }
}

/* Is the polygon of 2D points xy (counter-clockwise) convex: no corner
 * turns right? */
static int convex(const double *xy, uint32_t n)
{
    for (uint32_t k = 0; k < n; k++) {
        uint32_t p = k ? k - 1 : n - 1, q = k + 1 < n ? k + 1 : 0;
        if (cross2(&xy[2 * p], &xy[2 * k], &xy[2 * q]) < 0)
            return 0;
    }
    return 1;
}

/* Ear clipping of the counter-clockwise polygon xy into tri; 0, or -1
 * when some step finds no ear (the polygon crosses itself). */
static int clip_ears(const double *xy, uint32_t n, uint32_t *next, uint32_t *prev, uint32_t *tri)
{
    for (uint32_t k = 0; k < n; k++) {
        next[k] = k + 1 < n ? k + 1 : 0;
        prev[k] = k ? k - 1 : n - 1;
    }
    uint32_t left = n, i = 0;
    while (left > 3) {
        uint32_t tries = 0;
        for (; tries < left; tries++, i = next[i]) {
            uint32_t p = prev[i], q = next[i];
            const double *a = &xy[2 * p], *b = &xy[2 * i], *c = &xy[2 * q];
            if (cross2(a, b, c) <= 0)
                continue;           /* a reflex (or straight) corner is no ear */
            int empty = 1;
            for (uint32_t j = next[q]; j != p && empty; j = next[j]) {
                const double *x = &xy[2 * j];
                if ((x[0] == a[0] && x[1] == a[1]) || (x[0] == b[0] && x[1] == b[1]) || (x[0] == c[0] && x[1] == c[1]))
                    continue;       /* a corner again (a hole's bridge): not inside */
                empty = !(cross2(a, b, x) >= 0 && cross2(b, c, x) >= 0 && cross2(c, a, x) >= 0);
            }
            if (empty)
                break;
        }
        if (tries == left)
            return -1;
        uint32_t p = prev[i], q = next[i];
        *tri++ = p;
        *tri++ = i;
        *tri++ = q;
        next[p] = q;
        prev[q] = p;
        left--;
        i = q;
    }
    *tri++ = prev[i];
    *tri++ = i;
    *tri++ = next[i];
    return 0;
}

int save_face_triangles(const Mesh *m, uint32_t f, uint32_t *tri, SaveScratch *s)
{
    uint32_t a = m->face_start[f], n = m->face_start[f + 1] - a;
    if (n < 3)
        return 0;
    if (n == 3 || n > EAR_MAX) {
        fan(n, tri);
        return (int)(n - 2);
    }
    double nrm[3];
    newell(m, a, n, nrm);
    if (!planar(m, a, n, nrm)) {
        fan(n, tri);
        return (int)(n - 2);
    }
    if (s->cap < n) {
        size_t cap = n < 64 ? 64 : n;
        free(s->mem);
        s->mem = malloc(cap * (2 * sizeof(double) + 2 * sizeof(uint32_t)));
        s->cap = s->mem ? (uint32_t)cap : 0;
        if (!s->mem) {
            fan(n, tri);
            return (int)(n - 2);
        }
    }
    /* the plane seen along the normal's largest axis, turned so that the
     * face runs counter-clockwise */
    int ax = fabs(nrm[0]) > fabs(nrm[1]) ? (fabs(nrm[0]) > fabs(nrm[2]) ? 0 : 2) : (fabs(nrm[1]) > fabs(nrm[2]) ? 1 : 2);
    int u = (ax + 1) % 3, v = (ax + 2) % 3;
    if (nrm[ax] < 0) {
        int t = u;
        u = v;
        v = t;
    }
    double *xy = s->mem;
    uint32_t *next = (uint32_t *)(xy + 2 * (size_t)s->cap), *prev = next + s->cap;
    for (uint32_t k = 0; k < n; k++) {
        const float *p = &m->pos[3 * (size_t)m->corner[a + k]];
        xy[2 * k] = p[u];
        xy[2 * k + 1] = p[v];
    }
    if (nrm[ax] == 0 || convex(xy, n) || clip_ears(xy, n, next, prev, tri))
        fan(n, tri);
    return (int)(n - 2);
}

void save_scratch_free(SaveScratch *s)
{
    free(s->mem);
    memset(s, 0, sizeof *s);
}
