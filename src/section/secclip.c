/* secclip.c: the kept part of a polygon cut by section planes.
 *
 * One plane: the polygon clipped to the kept side by the reentrant
 * clipper of I. Sutherland and G. Hodgman, "Reentrant Polygon
 * Clipping", CACM 17(1), 1974. Several planes remove the region where
 * all their positive sides meet (a corner cut-away), which can leave a
 * polygon that is not convex: it is given as one outline for the
 * even-odd rule that every algorithm fills by (raster.h): the polygon
 * with each edge split where a plane crosses it, then, by a bridge
 * walked there and back, the removed part (the polygon clipped to the
 * positive side of each plane in turn). Where the removed part runs
 * along the polygon's edge its edges are the same sub-edges, between
 * the same points, so the two cancel exactly.
 *
 * A crossing on an edge of the polygon is always section_edge_point of
 * that edge's two corners (the kept one first), never of a piece of it:
 * the neighbouring face and the cap compute the same float point, so no
 * crack opens between them. */

#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "section.h"

/* A point of a polygon being clipped, and where it lies on the
 * original polygon: its corner e, inside its edge e (from corner e to
 * e + 1), or inside it. */
typedef struct {
    float   p[3];
    int32_t e;
    int8_t  kind;               /* ON_CORNER, ON_EDGE, INSIDE */
    int8_t  plane;              /* the plane it was made on, -1: a corner */
} ClipPt;

enum { ON_CORNER, ON_EDGE, INSIDE };

void section_clip_free(SectionClip *c)
{
    free(c->pts);
    free(c->tmp);
    memset(c, 0, sizeof *c);
}

static int push(SectionClip *c, const float p[3])
{
    if (grow_array((void **)&c->pts, &c->room, c->npts + 1, 3 * sizeof(float)))
        return -1;
    memcpy(c->pts + 3 * (size_t)c->npts++, p, 3 * sizeof(float));
    return 0;
}

/* Which plane side point u is on: the corner's mask, 0 on its own
 * plane, else the exact sign. 1: removed side. */
static int removed(const SectionPlane *planes, int i, const ClipPt *u, const uint8_t *masks)
{
    if (u->kind == ON_CORNER)
        return masks[u->e] >> i & 1;
    if (u->plane == i)
        return 0;
    return section_side(&planes[i], u->p) > 0;
}

/* The edge of the original polygon (n corners) that u and v both lie
 * on, -1 if none. */
static int32_t common_edge(const ClipPt *u, const ClipPt *v, uint32_t n)
{
    if (u->kind == INSIDE || v->kind == INSIDE)
        return -1;
    int32_t ue[2] = { u->e, u->kind == ON_CORNER ? (int32_t)((u->e + n - 1) % n) : -1 };
    int32_t ve[2] = { v->e, v->kind == ON_CORNER ? (int32_t)((v->e + n - 1) % n) : -1 };
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            if (ue[a] >= 0 && ue[a] == ve[b])
                return ue[a];
    return -1;
}

/* Where edge u -> v crosses plane i (u and v on opposite sides). */
static ClipPt crossing(const SectionPlane *planes, int i, const ClipPt *u, const ClipPt *v, const float *pts,
                       const uint8_t *masks, uint32_t n)
{
    ClipPt x = { { 0, 0, 0 }, -1, INSIDE, (int8_t)i };
    int32_t e = common_edge(u, v, n);
    if (e >= 0) {
        uint32_t a = (uint32_t)e, b = (a + 1) % n;
        int ra = masks[a] >> i & 1, rb = masks[b] >> i & 1;
        if (ra != rb) {
            if (ra)
                section_edge_point(&planes[i], pts + 3 * (size_t)b, pts + 3 * (size_t)a, x.p);
            else
                section_edge_point(&planes[i], pts + 3 * (size_t)a, pts + 3 * (size_t)b, x.p);
            x.e = e;
            x.kind = ON_EDGE;
            return x;
        }
    }
    if (removed(planes, i, u, masks))
        section_edge_point(&planes[i], v->p, u->p, x.p);
    else
        section_edge_point(&planes[i], u->p, v->p, x.p);
    return x;
}

/* in[0 .. m) clipped to the side of plane i where removed() is keep
 * (1: the removed side, 0: the kept side), into out; returns the count. */
static uint32_t clip_one(const SectionPlane *planes, int i, int keep, const ClipPt *in, uint32_t m, ClipPt *out,
                         const float *pts, const uint8_t *masks, uint32_t n)
{
    uint32_t k = 0;
    for (uint32_t a = 0; a < m; a++) {
        const ClipPt *u = &in[a], *v = &in[(a + 1) % m];
        int iu = removed(planes, i, u, masks) == keep, iv = removed(planes, i, v, masks) == keep;
        if (iu)
            out[k++] = *u;
        if (iu != iv)
            out[k++] = crossing(planes, i, u, v, pts, masks, n);
    }
    return k;
}

/* The polygon's corners as clip points. */
static void corners(const float *pts, uint32_t n, ClipPt *out)
{
    for (uint32_t k = 0; k < n; k++) {
        memcpy(out[k].p, pts + 3 * (size_t)k, sizeof out[k].p);
        out[k].e = (int32_t)k;
        out[k].kind = ON_CORNER;
        out[k].plane = -1;
    }
}

/* The polygon with each edge split where a plane crosses it, the
 * crossings in order along the edge. */
static int split_outline(const SectionPlane *planes, int np, const float *pts, const uint8_t *masks, uint32_t n,
                         SectionClip *c)
{
    for (uint32_t a = 0; a < n; a++) {
        uint32_t b = (a + 1) % n;
        const float *pa = pts + 3 * (size_t)a, *pb = pts + 3 * (size_t)b;
        if (push(c, pa))
            return -1;
        float x[SECTION_MAX][3];
        double t[SECTION_MAX];
        int nx = 0;
        double d[3] = { (double)pb[0] - pa[0], (double)pb[1] - pa[1], (double)pb[2] - pa[2] };
        for (int i = 0; i < np; i++) {
            int ra = masks[a] >> i & 1, rb = masks[b] >> i & 1;
            if (ra == rb)
                continue;
            if (ra)
                section_edge_point(&planes[i], pb, pa, x[nx]);
            else
                section_edge_point(&planes[i], pa, pb, x[nx]);
            t[nx] = (x[nx][0] - pa[0]) * d[0] + (x[nx][1] - pa[1]) * d[1] + (x[nx][2] - pa[2]) * d[2];
            /* insertion by t: at most SECTION_MAX of them */
            for (int k = nx; k > 0 && t[k - 1] > t[k]; k--) {
                double tt = t[k];
                t[k] = t[k - 1];
                t[k - 1] = tt;
                float xx[3];
                memcpy(xx, x[k], sizeof xx);
                memcpy(x[k], x[k - 1], sizeof xx);
                memcpy(x[k - 1], xx, sizeof xx);
            }
            nx++;
        }
        for (int k = 0; k < nx; k++)
            if (push(c, x[k]))
                return -1;
    }
    return 0;
}

int section_clip_poly(const SectionPlane *planes, int np, const float *pts, const uint8_t *masks, uint32_t n,
                      SectionClip *c)
{
    c->npts = 0;
    if (n < 3)
        return 0;
    /* each clip at most doubles a polygon's points (one not convex) */
    uint64_t room64 = ((uint64_t)n << (np + 1)) + 8;
    if (room64 > UINT32_MAX / 4)
        return -1;
    uint32_t room = (uint32_t)room64;
    if (grow_array(&c->tmp, &c->tmp_room, 2 * room, sizeof(ClipPt)))
        return -1;
    ClipPt *a = c->tmp, *b = a + room;
    corners(pts, n, a);
    if (np == 1) {
        uint32_t m = clip_one(planes, 0, 0, a, n, b, pts, masks, n);
        for (uint32_t k = 0; k < m; k++)
            if (push(c, b[k].p))
                return -1;
        return (int)c->npts;
    }
    uint32_t m = n;
    for (int i = 0; i < np && m >= 3; i++) {
        m = clip_one(planes, i, 1, a, m, b, pts, masks, n);
        ClipPt *t = a;
        a = b;
        b = t;
    }
    if (m < 3) {                /* nothing removed after all: the polygon */
        for (uint32_t k = 0; k < n; k++)
            if (push(c, pts + 3 * (size_t)k))
                return -1;
        return (int)c->npts;
    }
    if (split_outline(planes, np, pts, masks, n, c) || push(c, pts))
        return -1;
    for (uint32_t k = 0; k < m; k++)
        if (push(c, a[k].p))
            return -1;
    if (push(c, a[0].p))
        return -1;
    return (int)c->npts;
}
