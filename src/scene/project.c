/* project.c: the one front end. Scene -> screen-space polygons.
 *
 * Per object: vertices to view space and, where in front of the near
 * plane and inside the guard band, straight to snapped 24.8 screen
 * coordinates (each vertex once). Per polygon: the fast path copies its
 * snapped corners; a polygon crossing the near plane or the guard band is
 * clipped (Sutherland-Hodgman) and snapped on the slow path. Then the
 * sample box, back-face test, and the depth plane from the snapped
 * corners. A big object's polygons are split between the caller and up
 * to ScreenPolys.threads - 1 helper threads, and the helpers' parts are
 * appended in order: the output is the same as one thread's. Every
 * scratch buffer belongs to the ScreenPolys being filled (ScreenWork), so
 * the front end keeps no state of its own between calls. */

#define _DEFAULT_SOURCE
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hsr.h"
#include "grow.h"
#include "raster.h"
#include "screen.h"

/* Vertices farther than this outside the image (pixels) are clipped, so
 * that fixed-point values stay below 2^23 and edge products fit int64. */
#define GUARD_PX 8192.0

/* A thread is worth starting for at least this many polygons of one
 * object (below it, creating and joining costs more than it saves). */
#define PART_MIN 8192

typedef struct {
    double x, y, z;         /* view space (persp) or screen (guard clip): px, px, depth */
} CVert;

/* Per-vertex scratch of the object being projected, reused across frames. */
typedef struct {
    float   *view;          /* 3 per vertex, view space */
    ScreenVert *sv;         /* snapped, valid when ok */
    uint8_t *ok;            /* 1: in front of near and inside the guard band */
    uint32_t cap_view, cap_sv, cap_ok;
} Scratch;

/* Clip polygon buffers, one set per worker. */
typedef struct {
    CVert   *buf[2];
    uint32_t cap;
} ClipBuf;

struct ScreenWork {
    Scratch sc;
    ClipBuf clip[SCREEN_MAX_THREADS];   /* [0] the caller's, [i] helper i's */
    int     ncpus;                      /* cores online, read once */
};

static ScreenWork *work_get(ScreenPolys *sp)
{
    if (!sp->work) {
        sp->work = calloc(1, sizeof *sp->work);
        if (sp->work) {
            long c = sysconf(_SC_NPROCESSORS_ONLN);
            sp->work->ncpus = c < 1 ? 1 : c > SCREEN_MAX_THREADS ? SCREEN_MAX_THREADS : (int)c;
        }
    }
    return sp->work;
}

static void work_free(ScreenWork *w)
{
    if (!w)
        return;
    free(w->sc.view);
    free(w->sc.sv);
    free(w->sc.ok);
    for (int i = 0; i < SCREEN_MAX_THREADS; i++) {
        free(w->clip[i].buf[0]);
        free(w->clip[i].buf[1]);
    }
    free(w);
}

/* Everything but the caller's settings goes. */
void screen_free(ScreenPolys *sp)
{
    int threads = sp->threads;
    free(sp->verts);
    free(sp->polys);
    free(sp->map);
    free(sp->map_first);
    work_free(sp->work);
    memset(sp, 0, sizeof *sp);
    sp->threads = threads;
}

/* ==== projection parameters ==== */

typedef struct {
    int     persp;
    double  cx, cy;         /* image centre, px */
    double  fx, fy;         /* px per unit (ortho) or focal px (persp) */
    double  eye;            /* persp: eye on +z view axis */
    double  n, f;           /* persp: near, far distances */
    double  dscale, dbias;  /* ortho depth */
    double  gx0, gx1, gy0, gy1; /* guard band, px */
} Proj;

static void proj_setup(Proj *p, const Scene *s, const Viewport *vp)
{
    const Camera *c = &s->cam;
    double aspect = vp->pixel_aspect > 0 ? vp->pixel_aspect : 1;
    double r = c->radius > 0 ? c->radius : 1;
    double zoom = c->zoom > 0 ? c->zoom : 1;
    /* the fitted half extents, 90% of the image at zoom 1 (x-pixel units) */
    double hx = c->fit_half.x > 0 ? c->fit_half.x : r, hy = c->fit_half.y > 0 ? c->fit_half.y : r;
    double hz = c->fit_half.z > 0 ? c->fit_half.z : r;
    double half_w = 0.5 * vp->w, half_h = 0.5 * vp->h * aspect;
    p->persp = c->persp;
    p->cx = vp->w * 0.5;
    p->cy = vp->h * 0.5;
    if (!c->persp) {
        p->fx = zoom * 0.9 * fmin(half_w / hx, half_h / hy);
        p->dscale = 0.25 / r;       /* view z in [-2r, 2r] -> depth [0, 1] */
        p->dbias = 0.5;
    } else {
        double fov = (c->fov_deg > 1 && c->fov_deg < 179 ? c->fov_deg : 50) * 3.14159265358979323846 / 180;
        p->fx = fmin(half_w, half_h) / tan(fov / 2);
        /* at zoom 1 the box's front face fills 90%; zoom moves the eye
         * towards the centre (and into the scene past the box's front) */
        p->eye = (hz + fmax(hx * p->fx / half_w, hy * p->fx / half_h) / 0.9) / zoom;
        p->n = fmax(0.5 * (p->eye - r), 0.01 * r);
        p->f = p->eye + 3 * r;
    }
    p->fy = p->fx / aspect;
    p->gx0 = -GUARD_PX;
    p->gx1 = vp->w + GUARD_PX;
    p->gy0 = -GUARD_PX;
    p->gy1 = vp->h + GUARD_PX;
}

/* View space -> screen px and depth. Persp: the point must be in front. */
static inline void proj_point(const Proj *p, double x, double y, double z, double out[3])
{
    if (!p->persp) {
        out[0] = p->cx + p->fx * x;
        out[1] = p->cy - p->fy * y;
        out[2] = p->dbias - p->dscale * z;
    } else {
        double ze = p->eye - z;     /* distance in front of the eye */
        out[0] = p->cx + p->fx * x / ze;
        out[1] = p->cy - p->fy * y / ze;
        out[2] = p->f / (p->f - p->n) * (1 - p->n / ze);   /* NDC z in [0, 1] */
    }
}

/* Round to the nearest 1/256 px (halves up). floor() without the libm
 * call: truncate, then step down for negatives that were cut up. */
static inline int32_t snap(double v)
{
    double t = v * SUBPIX + 0.5;
    /* only vertices inside the guard band are kept; clamp the others (and
     * NaN) so that the conversion stays defined */
    if (!(t > -1073741824.0))
        t = -1073741824.0;
    if (t > 1073741824.0)
        t = 1073741824.0;
    int32_t i = (int32_t)t;
    return i - (t < (double)i);
}

static inline int in_guard(const Proj *p, const double s[3])
{
    return s[0] >= p->gx0 && s[0] <= p->gx1 && s[1] >= p->gy0 && s[1] <= p->gy1;
}

/* ==== clipping (slow path) ==== */

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

/* ==== polygon emission ==== */

/* Finish polygon whose snapped corners are verts[first .. nverts):
 * sample box, culling, plane. Returns 1 if kept. */
static int finish_poly(ScreenPolys *sp, uint32_t first, int32_t face)
{
    ScreenVert *v = &sp->verts[first];
    uint32_t n = sp->nverts - first;
    if (n < 3)
        return 0;
    int32_t xmin = v[0].x, xmax = v[0].x, ymin = v[0].y, ymax = v[0].y;
    for (uint32_t k = 1; k < n; k++) {
        if (v[k].x < xmin) xmin = v[k].x;
        if (v[k].x > xmax) xmax = v[k].x;
        if (v[k].y < ymin) ymin = v[k].y;
        if (v[k].y > ymax) ymax = v[k].y;
    }
    /* samples (i, j) with xmin <= 256i+128 < xmax could be covered */
    int32_t x0 = sample_ceil(xmin), x1 = sample_ceil(xmax);
    int32_t y0 = sample_ceil(ymin), y1 = sample_ceil(ymax);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > sp->w) x1 = sp->w;
    if (y1 > sp->h) y1 = sp->h;
    if (x0 >= x1 || y0 >= y1) {
        sp->culled_empty++;
        return 0;
    }
    /* Twice the signed area, y down: negative = counter-clockwise seen
     * with y up = front face for CCW-from-outside models. */
    int64_t area2 = 0;
    for (uint32_t k = 0; k < n; k++) {
        const ScreenVert *a = &v[k], *b = &v[k + 1 < n ? k + 1 : 0];
        area2 += (int64_t)a->x * b->y - (int64_t)b->x * a->y;
    }
    if (sp->cull && area2 >= 0) {
        sp->culled_back++;
        return 0;
    }
    /* A triangle whose few candidate samples all lie outside it covers
     * nothing: drop it here rather than in every algorithm (much of a big
     * model in a small image). */
    if (n == 3 && (x1 - x0) * (y1 - y0) <= 4) {
        int hit = 0;
        for (int32_t j = y0; j < y1 && !hit; j++)
            for (int32_t i = x0; i < x1 && !hit; i++)
                hit = tri_covers_sample(v, i, j);
        if (!hit) {
            sp->culled_empty++;
            return 0;
        }
    }
    /* The plane z = z0 + a (x - X0) + b (y - Y0) from the snapped corners,
     * in double: Newell's normal of (x, y, z); a best-area triangle when
     * the outline's net area vanishes (a symmetric bow tie). */
    double X0 = v[0].x / (double)SUBPIX, Y0 = v[0].y / (double)SUBPIX, Z0 = v[0].z;
    double nx = 0, ny = 0, nz = 0;
    if (n == 3) {
        double x1d = v[1].x / (double)SUBPIX - X0, y1d = v[1].y / (double)SUBPIX - Y0, z1d = v[1].z - Z0;
        double x2d = v[2].x / (double)SUBPIX - X0, y2d = v[2].y / (double)SUBPIX - Y0, z2d = v[2].z - Z0;
        nx = y1d * z2d - z1d * y2d;
        ny = z1d * x2d - x1d * z2d;
        nz = x1d * y2d - y1d * x2d;
    } else {
        for (uint32_t k = 0; k < n; k++) {
            const ScreenVert *p = &v[k], *q = &v[k + 1 < n ? k + 1 : 0];
            double px = p->x / (double)SUBPIX - X0, py = p->y / (double)SUBPIX - Y0, pz = p->z - Z0;
            double qx = q->x / (double)SUBPIX - X0, qy = q->y / (double)SUBPIX - Y0, qz = q->z - Z0;
            nx += (py - qy) * (pz + qz);
            ny += (pz - qz) * (px + qx);
            nz += (px - qx) * (py + qy);
        }
        if (fabs(nz) < 1e-9) {
            double best = 0;
            for (uint32_t k = 1; k + 1 < n; k++) {
                double x1d = v[k].x / (double)SUBPIX - X0, y1d = v[k].y / (double)SUBPIX - Y0, z1d = v[k].z - Z0;
                double x2d = v[k + 1].x / (double)SUBPIX - X0, y2d = v[k + 1].y / (double)SUBPIX - Y0,
                       z2d = v[k + 1].z - Z0;
                double cz = x1d * y2d - y1d * x2d;
                if (fabs(cz) > fabs(best)) {
                    best = cz;
                    nx = y1d * z2d - z1d * y2d;
                    ny = z1d * x2d - x1d * z2d;
                    nz = cz;
                }
            }
        }
    }
    if (nz == 0) {          /* no area at all: covers no sample */
        sp->culled_empty++;
        return 0;
    }
    double a = -nx / nz, b = -ny / nz;
    ScreenPoly *p = &sp->polys[sp->npolys];
    p->first = first;
    p->face = face;
    p->x0 = x0; p->x1 = x1; p->y0 = y0; p->y1 = y1;
    double zc = Z0 + a * (x0 + 0.5 - X0) + b * (y0 + 0.5 - Y0);
    p->a = (float)a;
    p->b = (float)b;
    p->zc = (float)zc;
    /* A lower bound of every depth plane_at() can return inside: the
     * plane's least corner value, less a margin for float rounding. */
    double lo, mag = fabs(zc) + fabs(a) * (x1 - x0) + fabs(b) * (y1 - y0);
    if (n == 3) {
        /* the plane passes through the corners */
        double z1 = v[1].z, z2 = v[2].z;
        lo = Z0 < z1 ? Z0 : z1;
        lo = z2 < lo ? z2 : lo;
    } else {
        lo = 1e300;
        for (uint32_t k = 0; k < n; k++) {
            double z = Z0 + a * (v[k].x / (double)SUBPIX - X0) + b * (v[k].y / (double)SUBPIX - Y0);
            if (z < lo)
                lo = z;
        }
    }
    p->zmin = (float)(lo - (fabs(lo) + mag) * (1.0 / (1 << 20)));
    sp->npolys++;
    return 1;
}

/* Project the polygons [k0, k1) of object o (its vertices are in vs) into
 * j->out, and record where each went in map (an index into j->out). */
typedef struct {
    ScreenPolys   *out;
    const Scene   *s;
    const Object  *o;
    const Proj    *pj;
    const Scratch *vs;
    ClipBuf       *cb;
    uint32_t       k0, k1, inst0;
    int32_t       *map;
    int            fixed;       /* out's arrays are a window of another's: never grow */
    int            rc;          /* 0, -1 out of memory, -2 window full */
} RangeJob;

/* Room for `need` vertices in j->out: grow, or in a fixed window report
 * that it is full (the caller then redoes the work on one thread). */
static int vert_room(RangeJob *j, uint32_t need)
{
    ScreenPolys *sp = j->out;
    if (need <= sp->cap_verts)
        return 0;
    if (j->fixed)
        return -2;
    return grow_array((void **)&sp->verts, &sp->cap_verts, need, sizeof *sp->verts);
}

static int project_range(RangeJob *j)
{
    ScreenPolys *sp = j->out;
    const Scene *s = j->s;
    const Object *o = j->o;
    const Proj *pj = j->pj;
    const Scratch *sc = j->vs;
    ClipBuf *cb = j->cb;
    int32_t *map = j->map;
    uint32_t inst = j->inst0;
    for (uint32_t k = j->k0; k < j->k1; k++, inst++) {
        uint32_t c0 = s->poly_start[k], c1 = s->poly_start[k + 1], nc = c1 - c0;
        int32_t face = o->face_base + (int32_t)s->poly_lface[k];
        sp->in_polys++;
        map[inst] = -1;
        if (nc == 3) {
            /* Fast reject of a triangle that covers no sample centre
             * (most of a big model in a small image), before copying. */
            uint32_t i0 = s->poly_corner[c0] - o->vert_min, i1 = s->poly_corner[c0 + 1] - o->vert_min,
                     i2 = s->poly_corner[c0 + 2] - o->vert_min;
            if (sc->ok[i0] & sc->ok[i1] & sc->ok[i2]) {
                const ScreenVert *a = &sc->sv[i0], *b = &sc->sv[i1], *c = &sc->sv[i2];
                int32_t xmin = a->x < b->x ? a->x : b->x, xmax = a->x < b->x ? b->x : a->x;
                int32_t ymin = a->y < b->y ? a->y : b->y, ymax = a->y < b->y ? b->y : a->y;
                xmin = c->x < xmin ? c->x : xmin;
                xmax = c->x > xmax ? c->x : xmax;
                ymin = c->y < ymin ? c->y : ymin;
                ymax = c->y > ymax ? c->y : ymax;
                int32_t x0 = sample_ceil(xmin), x1 = sample_ceil(xmax);
                int32_t y0 = sample_ceil(ymin), y1 = sample_ceil(ymax);
                if (x0 >= x1 || y0 >= y1 || x1 <= 0 || y1 <= 0 || x0 >= sp->w || y0 >= sp->h) {
                    sp->culled_empty++;
                    continue;
                }
            }
        }
        /* room for the clipped outline: each plane adds at most one vertex */
        int rv = vert_room(j, sp->nverts + nc + 8);
        if (rv)
            return rv;
        int all_ok = 1;
        for (uint32_t c = c0; c < c1; c++)
            all_ok &= sc->ok[s->poly_corner[c] - o->vert_min];
        uint32_t first = sp->nverts;
        if (all_ok) {
            ScreenVert *dst = &sp->verts[first];
            for (uint32_t c = c0; c < c1; c++)
                *dst++ = sc->sv[s->poly_corner[c] - o->vert_min];
            sp->nverts += nc;
        } else {
            /* Slow path: near plane in view space, then the guard band
             * in screen space (depth is affine there). */
            /* Each clip stage at most doubles the outline (a concave or
             * self-crossing one can gain a vertex per edge): room for
             * five stages. */
            uint64_t need64 = (uint64_t)nc << 5;
            if (need64 > UINT32_MAX / 4)
                continue;
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
            CVert *in = cb->buf[0], *out = cb->buf[1];
            uint32_t n = 0;
            for (uint32_t c = c0; c < c1; c++) {
                const float *q = &sc->view[3 * (s->poly_corner[c] - o->vert_min)];
                in[n].x = q[0]; in[n].y = q[1]; in[n].z = q[2];
                n++;
            }
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
            rv = vert_room(j, sp->nverts + n + 1);
            if (rv)
                return rv;
            for (uint32_t i = 0; i < n; i++) {
                ScreenVert *d = &sp->verts[sp->nverts++];
                d->x = snap(in[i].x);
                d->y = snap(in[i].y);
                d->z = (float)in[i].z;
            }
        }
        if (finish_poly(sp, first, face))
            map[inst] = (int32_t)(sp->npolys - 1);
        else
            sp->nverts = first;
    }
    return 0;
}

static void *range_thread(void *arg)
{
    RangeJob *j = arg;
    j->rc = project_range(j);
    return NULL;
}

/* Move a helper's part, written in a window further up sp's arrays
 * (polygons at pb, vertices at vb, instances inst0 .. inst0 + n), down to
 * right after what sp holds. */
static void compact_part(ScreenPolys *sp, const ScreenPolys *part, uint32_t pb, uint32_t vb,
                         uint32_t inst0, uint32_t n)
{
    uint32_t bv = sp->nverts, bp = sp->npolys;
    memmove(sp->verts + bv, sp->verts + vb, (size_t)part->nverts * sizeof *sp->verts);
    memmove(sp->polys + bp, sp->polys + pb, (size_t)part->npolys * sizeof *sp->polys);
    for (uint32_t i = 0; i < part->npolys; i++)
        sp->polys[bp + i].first += bv;
    for (uint32_t i = inst0; i < inst0 + n; i++)
        if (sp->map[i] >= 0)
            sp->map[i] += (int32_t)bp;
    sp->nverts += part->nverts;
    sp->npolys += part->npolys;
    sp->in_polys += part->in_polys;
    sp->culled_back += part->culled_back;
    sp->culled_empty += part->culled_empty;
}

/* How many threads to split object o over: sp->threads (0 = every core),
 * and no more than one per PART_MIN polygons. 1 = the caller alone. */
static int object_parts(const ScreenPolys *sp, const Object *o)
{
    int t = sp->threads > 0 ? sp->threads : sp->work->ncpus;
    if (t > SCREEN_MAX_THREADS)
        t = SCREEN_MAX_THREADS;
    uint32_t most = o->poly_count / PART_MIN;
    return most < (uint32_t)t ? (most ? (int)most : 1) : t;
}

/* Transform object o's vertices once each: view space, and the snapped
 * screen point where it is in front of the near plane and in the band. */
static void project_vertices(Scratch *sc, const Object *o, const Mat4 *mv, const Proj *pj)
{
    uint32_t nv = o->vert_max - o->vert_min + 1;
    const float *pos = o->mesh->pos + 3 * (size_t)o->vert_min;
    for (uint32_t i = 0; i < nv; i++) {
        Vec3 q = m4_point(mv, v3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
        sc->view[3 * i] = q.x;
        sc->view[3 * i + 1] = q.y;
        sc->view[3 * i + 2] = q.z;
        int ok = !pj->persp || pj->eye - q.z >= pj->n;
        if (ok) {
            double scr[3];
            proj_point(pj, q.x, q.y, q.z, scr);
            ok = in_guard(pj, scr);
            sc->sv[i].x = snap(scr[0]);
            sc->sv[i].y = snap(scr[1]);
            sc->sv[i].z = (float)scr[2];
        }
        sc->ok[i] = (uint8_t)ok;
    }
}

/* Object o's polygons in `parts` consecutive parts: part 0 on the caller,
 * the others on helper threads. Each part writes into its own window of
 * sp's arrays, past the room the parts before it can need; then the parts
 * move down in order: no second set of buffers. Returns 0 when done, 1
 * when a part's clipping outgrew its window (rare: sp is as it was and
 * the caller projects the object again on one thread), -1 on out of
 * memory. */
static int project_parts(ScreenPolys *sp, const Scene *s, const Object *o, const Proj *pj,
                         ScreenWork *w, uint32_t inst, int parts)
{
    uint32_t k[SCREEN_MAX_THREADS + 1], vb[SCREEN_MAX_THREADS + 1];
    uint64_t end = sp->nverts;
    for (int i = 0; i <= parts; i++)
        k[i] = o->poly_first + (uint32_t)((uint64_t)o->poly_count * (uint32_t)i / (uint32_t)parts);
    for (int i = 0; i < parts; i++) {
        uint32_t corners = s->poly_start[k[i + 1]] - s->poly_start[k[i]];
        vb[i] = (uint32_t)end;
        end += (uint64_t)corners + corners / 16 + 64;
    }
    if (end > UINT32_MAX / 2 ||
        grow_array((void **)&sp->verts, &sp->cap_verts, (uint32_t)end, sizeof *sp->verts))
        return -1;
    vb[parts] = (uint32_t)end;
    ScreenPolys win[SCREEN_MAX_THREADS];
    RangeJob job[SCREEN_MAX_THREADS];
    pthread_t th[SCREEN_MAX_THREADS];
    int started[SCREEN_MAX_THREADS] = { 0 };
    for (int i = 0; i < parts; i++) {
        win[i] = *sp;
        if (i == 0) {
            win[i].cap_verts = vb[1];   /* part 0 continues sp and may not reach part 1 */
        } else {
            win[i].verts = sp->verts + vb[i];
            win[i].polys = sp->polys + sp->npolys + (k[i] - o->poly_first);
            win[i].cap_verts = vb[i + 1] - vb[i];
            win[i].cap_polys = k[i + 1] - k[i] + 1;
            win[i].nverts = win[i].npolys = 0;
            win[i].in_polys = win[i].culled_back = win[i].culled_empty = 0;
        }
        job[i] = (RangeJob){ &win[i], s, o, pj, &w->sc, &w->clip[i], k[i], k[i + 1],
                             inst + (k[i] - o->poly_first), sp->map, 1, 0 };
    }
    for (int i = 1; i < parts; i++)
        if (pthread_create(&th[i], NULL, range_thread, &job[i]) == 0) {
            started[i] = 1;
            sp->helpers++;
        }
    job[0].rc = project_range(&job[0]);
    int rc = job[0].rc;
    for (int i = 1; i < parts; i++) {
        if (started[i])
            pthread_join(th[i], NULL);
        else
            job[i].rc = project_range(&job[i]);   /* no thread to be had: do it here */
        if (job[i].rc == -1 || (job[i].rc && rc != -1))
            rc = job[i].rc;
    }
    if (rc == -1)
        return -1;
    if (rc)
        return 1;
    uint32_t pb0 = sp->npolys;
    sp->nverts = win[0].nverts;
    sp->npolys = win[0].npolys;
    sp->in_polys = win[0].in_polys;
    sp->culled_back = win[0].culled_back;
    sp->culled_empty = win[0].culled_empty;
    for (int i = 1; i < parts; i++)
        compact_part(sp, &win[i], pb0 + (k[i] - o->poly_first), vb[i], job[i].inst0, k[i + 1] - k[i]);
    return 0;
}

/* Set sp's size, projection and statistics for a new frame. */
static void frame_begin(ScreenPolys *sp, const Viewport *vp, const Proj *pj)
{
    sp->w = vp->w;
    sp->h = vp->h;
    sp->pixel_aspect = vp->pixel_aspect;
    sp->cull = vp->cull;
    sp->nverts = sp->npolys = 0;
    sp->in_polys = sp->culled_back = sp->culled_empty = sp->helpers = 0;
    sp->persp = pj->persp;
    sp->focal_x = (float)pj->fx;
    sp->focal_y = (float)pj->fy;
    sp->eye_z = (float)pj->eye;
    sp->near_z = (float)pj->n;
    sp->far_z = (float)pj->f;
    sp->depth_scale = (float)pj->dscale;
    sp->depth_bias = (float)pj->dbias;
}

/* Room for every polygon instance and corner of the scene. */
static int frame_room(ScreenPolys *sp, const Scene *s)
{
    uint64_t ninst = 0, ncorners = 0;
    for (int oi = 0; oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        ninst += o->poly_count;
        ncorners += s->poly_start[o->poly_first + o->poly_count] - s->poly_start[o->poly_first];
    }
    if (ninst > INT32_MAX || ncorners + 64 > UINT32_MAX / 2)
        return -1;
    if (s->nobjs > sp->cap_objs) {
        uint32_t *q = realloc(sp->map_first, (size_t)s->nobjs * sizeof *q);
        if (!q)
            return -1;
        sp->map_first = q;
        sp->cap_objs = s->nobjs;
    }
    /* every corner at most once, plus a little for clipped outlines */
    if (grow_array((void **)&sp->verts, &sp->cap_verts, (uint32_t)(ncorners + ncorners / 64 + 64), sizeof *sp->verts) ||
        grow_array((void **)&sp->map, &sp->cap_map, (uint32_t)ninst + 1, sizeof *sp->map) ||
        grow_array((void **)&sp->polys, &sp->cap_polys, (uint32_t)ninst + 1, sizeof *sp->polys))
        return -1;
    return 0;
}

int screen_project(ScreenPolys *sp, const Scene *s, const Viewport *vp)
{
    double t0 = now_ms();
    ScreenWork *w = work_get(sp);
    if (!w)
        return -1;
    Scratch *sc = &w->sc;
    Proj pj = { 0 };
    proj_setup(&pj, s, vp);
    frame_begin(sp, vp, &pj);
    if (frame_room(sp, s))
        return -1;
    Mat4 view = camera_view(&s->cam);
    uint32_t inst = 0;
    for (int oi = 0; oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        sp->map_first[oi] = inst;
        if (!o->poly_count)
            continue;
        Mat4 mv = m4_mul(view, object_matrix(o));
        uint32_t nv = o->vert_max - o->vert_min + 1;
        if (grow_array((void **)&sc->view, &sc->cap_view, nv, 3 * sizeof(float)) ||
            grow_array((void **)&sc->sv, &sc->cap_sv, nv, sizeof(ScreenVert)) ||
            grow_array((void **)&sc->ok, &sc->cap_ok, nv, 1))
            return -1;
        project_vertices(sc, o, &mv, &pj);
        int parts = object_parts(sp, o), rc = 1;
        if (parts > 1 && (rc = project_parts(sp, s, o, &pj, w, inst, parts)) < 0)
            return -1;
        if (rc) {
            RangeJob j = { sp, s, o, &pj, sc, &w->clip[0], o->poly_first,
                           o->poly_first + o->poly_count, inst, sp->map, 0, 0 };
            if (project_range(&j))
                return -1;
        }
        inst += o->poly_count;
    }
    sp->polys[sp->npolys].first = sp->nverts;   /* sentinel */
    sp->nmap = inst;
    sp->face_sorted = 1;
    sp->ms = now_ms() - t0;
    return 0;
}

/* fprintf unless an earlier write failed; the first failure's errno
 * stays in *err. */
static void put(FILE *f, int *err, const char *fmt, ...)
{
    if (*err)
        return;
    va_list ap;
    va_start(ap, fmt);
    if (vfprintf(f, fmt, ap) < 0)
        *err = errno ? errno : EIO;
    va_end(ap);
}

/* Every write is checked: a full disk must not pass for a short dump.
 * On failure errno is the first failure's. */
int screen_dump_obj(const ScreenPolys *sp, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    int err = 0;
    put(f, &err, "# zview screen %d %d\n", sp->w, sp->h);
    for (uint32_t i = 0; i < sp->nverts && !err; i++)
        put(f, &err, "v %.9g %.9g %.9g\n", sp->verts[i].x / (double)SUBPIX,
            sp->verts[i].y / (double)SUBPIX, (double)sp->verts[i].z);
    for (uint32_t p = 0; p < sp->npolys && !err; p++) {
        put(f, &err, "f");
        for (uint32_t k = sp->polys[p].first; k < sp->polys[p + 1].first; k++)
            put(f, &err, " %u", k + 1);
        put(f, &err, " # %d\n", sp->polys[p].face);
    }
    if (!err && (fflush(f) != 0 || ferror(f)))
        err = errno ? errno : EIO;
    if (fclose(f) != 0 && !err)
        err = errno ? errno : EIO;
    errno = err;
    return err ? -1 : 0;
}
