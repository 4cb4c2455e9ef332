/* clip.c: the front end's slow path. A polygon with a corner behind
 * the near plane or outside the guard band is recomputed from the mesh
 * in view space, clipped against the near plane there, projected, and
 * clipped against the four sides of the guard band in screen space
 * (where depth is affine), then snapped.
 *
 * Implements the reentrant polygon clipper of I. Sutherland and
 * G. Hodgman, "Reentrant Polygon Clipping", CACM 17(1), 1974: one plane
 * at a time, each edge keeping its inside end and its crossing.
 */

#include <stdlib.h>

#include "project.h"

/* Keep the part of polygon in[0..n) where dist(v) >= 0; returns count. */
static uint32_t clip_poly(const CVert *in, uint32_t n, CVert *out, int axis, double k, double sign)
{
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; i++) {
        const CVert *a = &in[i], *b = &in[(i + 1) % n];
        double va = axis == 0 ? a->x : axis == 1 ? a->y : a->z;
        double vb = axis == 0 ? b->x : axis == 1 ? b->y : b->z;
        double da = sign * (va - k), db = sign * (vb - k);
        if (da >= 0)
            out[m++] = *a;
        if ((da >= 0) != (db >= 0)) {
            double t = da / (da - db);
            out[m].x = a->x + t * (b->x - a->x);
            out[m].y = a->y + t * (b->y - a->y);
            out[m].z = a->z + t * (b->z - a->z);
            m++;
        }
    }
    return m;
}

/* Room in the clip buffers for an outline of nc corners; 1: too many. */
static int clip_room(ClipBuf *cb, uint32_t nc)
{
    /* Each clip stage at most doubles the outline (a concave or
     * self-crossing one can gain a vertex per edge): room for five
     * stages. */
    uint64_t need64 = (uint64_t)nc << 5;
    if (need64 > UINT32_MAX / 4)
        return 1;
    uint32_t need = (uint32_t)need64 + 8;
    if (need > cb->cap) {
        CVert *a = realloc(cb->buf[0], need * sizeof(CVert));
        CVert *b = realloc(cb->buf[1], need * sizeof(CVert));
        if (a) cb->buf[0] = a;
        if (b) cb->buf[1] = b;
        if (!a || !b)
            return -1;
        cb->cap = need;
    }
    return 0;
}

/* The view-space outline cb->buf[0][0 .. n) clipped against the near
 * plane, projected, clipped against the guard band and appended
 * snapped. */
static int clip_view(RangeJob *j, uint32_t n)
{
    ScreenPolys *sp = j->out;
    const Proj *pj = j->pj;
    CVert *in = j->cb->buf[0], *out = j->cb->buf[1];
    if (pj->persp) {
        /* keep eye - z >= near, i.e. z <= eye - near */
        n = clip_poly(in, n, out, 2, pj->eye - pj->n, -1);
        CVert *t = in; in = out; out = t;
    }
    for (uint32_t i = 0; i < n; i++) {
        double scr[3];
        proj_point(pj, in[i].x, in[i].y, in[i].z, scr);
        in[i].x = scr[0]; in[i].y = scr[1]; in[i].z = scr[2];
    }
    n = clip_poly(in, n, out, 0, pj->gx0, 1);
    n = clip_poly(out, n, in, 0, pj->gx1, -1);
    n = clip_poly(in, n, out, 1, pj->gy0, 1);
    n = clip_poly(out, n, in, 1, pj->gy1, -1);
    int rv = vert_room(j, sp->nverts + n + 1);
    if (rv)
        return rv;
    for (uint32_t i = 0; i < n; i++) {
        ScreenVert *d = &sp->verts[sp->nverts++];
        d->x = snap(in[i].x);
        d->y = snap(in[i].y);
        d->z = (float)in[i].z;
    }
    return 0;
}

/* Clip polygon k (corners c0 .. c1) against the near plane in view space
 * (recomputed from the mesh exactly as pass 1 computed it), then the
 * guard band in screen space (depth is affine there), and append its
 * snapped outline. Returns 0, 1 to skip it, or vert_room's error. */
int project_clip(RangeJob *j, uint32_t c0, uint32_t c1)
{
    int rv = clip_room(j->cb, c1 - c0);
    if (rv)
        return rv;
    CVert *in = j->cb->buf[0];
    uint32_t n = 0;
    const float *pos = j->o->mesh->pos;
    for (uint32_t c = c0; c < c1; c++) {
        const float *p = pos + 3 * (size_t)j->s->poly_corner[c];
        Vec3 q = m4_point(j->mv, v3(p[0], p[1], p[2]));
        in[n].x = q.x; in[n].y = q.y; in[n].z = q.z;
        n++;
    }
    return clip_view(j, n);
}

/* project.h */
int project_clip_points(RangeJob *j, const float *pts, uint32_t n)
{
    int rv = clip_room(j->cb, n);
    if (rv)
        return rv;
    CVert *in = j->cb->buf[0];
    for (uint32_t c = 0; c < n; c++) {
        const float *p = pts + 3 * (size_t)c;
        /* as pass 1 takes a vertex: the same bits where it is a mesh's */
        Vec3 q = m4_point(j->mv, v3(p[0], p[1], p[2]));
        in[c].x = q.x; in[c].y = q.y; in[c].z = q.z;
    }
    return clip_view(j, n);
}
