/* edges: outlines where the face-id buffer changes (--edges).
 *
 * The hidden-surface step already knows, per pixel, which face is seen;
 * an outline is where that changes between neighbouring pixels in a way
 * the eye reads as an edge:
 *   - the silhouette: a face next to the background;
 *   - another object;
 *   - a crease: the two faces' normals turn by more than the crease angle;
 *   - an occluding contour: the neighbour is not on the continuation of
 *     this face's plane (a depth step), e.g. an ear in front of a head.
 * A pixel is drawn as outline when it is the nearer of such a pair (the
 * face next to the background, the front of a depth step, the lower id
 * across a crease), so lines are one pixel wide. The plane continuation
 * uses the front end's own depth plane of the face, so the test scales
 * with the resolution and does not mistake a steep surface for a step.
 * Everything is read from the exact buffers: every algorithm gives the
 * same outlines. The colour contrasts with the face: dark on light faces,
 * light on dark ones. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "shade.h"

/* The screen polygon of every face drawn this frame (the first, for a
 * face split into triangles: they share its plane). */
static int face_planes(const Scene *s, const ScreenPolys *sp, EdgeData *ed)
{
    if (ed->cap < s->nfaces || !ed->face_sp) {
        int32_t *m = realloc(ed->face_sp, (size_t)(s->nfaces ? s->nfaces : 1) * sizeof *m);
        if (!m)
            return -1;
        ed->face_sp = m;
        ed->cap = s->nfaces;
    }
    memset(ed->face_sp, 0xff, (size_t)s->nfaces * sizeof *ed->face_sp);
    for (uint32_t i = sp->npolys; i-- > 0;) {
        int32_t f = sp->polys[i].face;
        if (f >= 0 && (uint32_t)f < s->nfaces)
            ed->face_sp[f] = (int32_t)i;
    }
    return 0;
}

void edges_free(EdgeData *ed)
{
    free(ed->face_sp);
    memset(ed, 0, sizeof *ed);
}

/* Depth of face f's plane at sample (x, y) (the front end's plane, in
 * double: only compared with a tolerance). */
static double plane_depth(const ScreenPolys *sp, const EdgeData *ed, int32_t f, int x, int y)
{
    const ScreenPoly *p = &sp->polys[ed->face_sp[f]];
    return p->zc + (double)p->b * (y - p->y0) + (double)p->a * (x - p->x0);
}

/* Is sample (nx, ny) at depth d off face f's plane by more than the
 * plane itself changes over two pixels? (No plane known: say no.) */
static int off_plane(const ScreenPolys *sp, const EdgeData *ed, int32_t f, int nx, int ny, double d)
{
    if (ed->face_sp[f] < 0)
        return 0;
    const ScreenPoly *p = &sp->polys[ed->face_sp[f]];
    double tol = 2.0 * (fabs(p->a) + fabs(p->b)) + 1e-6 * (1 + fabs(d));
    return fabs(plane_depth(sp, ed, f, nx, ny) - d) > tol;
}

/* Is pixel i (x, y) an outline pixel against its neighbour j (nx, ny)? */
static int edge_against(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, const EdgeData *ed,
                        float cos_crease, size_t i, int x, int y, size_t j, int nx, int ny)
{
    int32_t a = fb->ids[i], b = fb->ids[j];
    if (b == a)
        return 0;
    if (b >= 0 && (uint32_t)b >= s->nfaces && (uint32_t)b - s->nfaces < s->nprims)
        return 0;                                   /* a point or line: drawn on its own */
    if (b < 0 || (uint32_t)b >= s->nfaces)
        return 1;                                   /* silhouette */
    double da = fb->depth[i], db = fb->depth[j];
    int nearer = da < db || (da == db && a < b);
    /* a depth step: each is off the other's plane */
    if (off_plane(sp, ed, a, nx, ny, db) && off_plane(sp, ed, b, x, y, da))
        return nearer;
    if (s->face_obj && s->face_obj[a] != s->face_obj[b])
        return nearer;                              /* where two objects meet */
    /* one surface: a crease when the normals turn enough */
    float na[3], nb[3];
    if (ed->nrm) {
        memcpy(na, &ed->nrm[3 * (size_t)a], sizeof na);
        memcpy(nb, &ed->nrm[3 * (size_t)b], sizeof nb);
    } else {
        scene_face_normal(s, (uint32_t)a, na);
        scene_face_normal(s, (uint32_t)b, nb);
    }
    float c = na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2];
    return c < cos_crease && a < b;
}

int shade_edges(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, float crease_deg, EdgeData *ed,
                Image *out)
{
    if (face_planes(s, sp, ed))
        return -1;
    float cos_crease = cosf(deg2rad(crease_deg));
    int w = fb->w, h = fb->h;
    static const int dx[4] = { 1, -1, 0, 0 }, dy[4] = { 0, 0, 1, -1 };
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            int32_t a = fb->ids[i];
            if (a < 0 || (uint32_t)a >= s->nfaces)
                continue;
            int edge = 0;
            for (int k = 0; k < 4 && !edge; k++) {
                int nx = x + dx[k], ny = y + dy[k];
                if (nx < 0 || ny < 0 || nx >= w || ny >= h)
                    continue;
                edge = edge_against(s, sp, fb, ed, cos_crease, i, x, y, (size_t)ny * w + nx, nx, ny);
            }
            if (!edge)
                continue;
            uint8_t *px = out->rgb + 3 * i;
            unsigned lum = (54u * px[0] + 183u * px[1] + 19u * px[2]) >> 8;
            uint8_t v = lum > 110 ? 20 : 240;
            px[0] = px[1] = px[2] = v;
        }
    return 0;
}
