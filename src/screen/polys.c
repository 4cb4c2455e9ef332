/* polys.c: pass 2 of the front end (project.c), the scalar reference:
 * a chunk of polygons screened by their corners' sample indices, then
 * each kept one copied (the fast path) or clipped (clip.c), and finished:
 * its sample box, the back-face test, a last look at the few samples of
 * a tiny triangle, and the depth plane from its snapped corners. Under
 * AVX2 whole chunks of triangles take project_avx2.c's loops instead,
 * which give the same polygons, counts and map. */

#include <math.h>
#include <string.h>

#include "project.h"

/* Polygons per chunk of pass 2: the survivors' list lives on the stack. */
#define CHUNK 2048

/* ==== screening ==== */

/* project.h */
uint32_t project_screen_tris(const uint32_t *corner, uint32_t a, uint32_t n, const uint32_t *idx, uint32_t vmin,
                             int32_t w, int32_t h, uint32_t *keep, uint32_t nk)
{
    for (uint32_t i = a; i < n; i++) {
        keep[nk] = i;
        nk += tri_keeps(corner + 3 * (size_t)i, idx, vmin, w, h);
    }
    return nk;
}

/* keep[] needs room for n + 8 entries (the AVX2 loop stores eight at a time). */
static uint32_t screen_tris(int simd, const uint32_t *corner, uint32_t n, const uint32_t *idx, uint32_t vmin,
                            int32_t w, int32_t h, uint32_t *keep, const KeepLut *lut)
{
#ifdef ZV_AVX2
    if (simd >= SIMD_AVX2)
        return project_screen_tris_avx2(corner, n, idx, vmin, w, h, keep, lut);
#endif
    (void)simd;
    (void)lut;
    return project_screen_tris(corner, 0, n, idx, vmin, w, h, keep, 0);
}

/* ==== polygon emission ==== */

/* The sample box of snapped corners, clamped to the screen; 0 when empty. */
static inline int sample_box(const ScreenPolys *sp, int32_t xmin, int32_t xmax, int32_t ymin, int32_t ymax,
                             int32_t box[4])
{
    /* samples (i, j) with xmin <= 256i+128 < xmax could be covered */
    int32_t x0 = sample_ceil(xmin), x1 = sample_ceil(xmax);
    int32_t y0 = sample_ceil(ymin), y1 = sample_ceil(ymax);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > sp->w) x1 = sp->w;
    if (y1 > sp->h) y1 = sp->h;
    box[0] = x0;
    box[1] = x1;
    box[2] = y0;
    box[3] = y1;
    return x0 < x1 && y0 < y1;
}

/* Store the polygon of corners verts[first ..] with its box and plane
 * z = Z0 + a (x - X0) + b (y - Y0); lo is the least depth of the plane at
 * its corners. The caller sets its face. */
static void store_poly(ScreenPolys *sp, uint32_t first, const int32_t box[4], double X0, double Y0, double Z0,
                       double a, double b, double lo)
{
    int32_t x0 = box[0], x1 = box[1], y0 = box[2], y1 = box[3];
    ScreenPoly *p = &sp->polys[sp->npolys];
    p->first = first;
    p->x0 = x0; p->x1 = x1; p->y0 = y0; p->y1 = y1;
    double zc = Z0 + a * (x0 + 0.5 - X0) + b * (y0 + 0.5 - Y0);
    p->a = (float)a;
    p->b = (float)b;
    p->zc = (float)zc;
    /* A lower bound of every depth plane_at() can return inside: the
     * plane's least corner value, less a margin for float rounding. */
    double mag = fabs(zc) + fabs(a) * (x1 - x0) + fabs(b) * (y1 - y0);
    p->zmin = (float)(lo - (fabs(lo) + mag) * (1.0 / (1 << 20)));
    sp->npolys++;
}

/* One edge a -> b of a triangle (wound so that its inside is at e > 0) at
 * sample centre (px, py): raster.h's edge function, and whether it
 * covers there (e > 0, or e == 0 on a top or left edge). Exact. */
static inline int edge_covers(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t px, int64_t py)
{
    int64_t dx = bx - ax, dy = by - ay;
    int64_t e = dx * (py - ay) - dy * (px - ax);
    return e > 0 || (e == 0 && (dy < 0 || (dy == 0 && dx > 0)));
}

/* A triangle whose few candidate samples all lie outside it covers
 * nothing: drop it here rather than in every algorithm (much of a big
 * model in a small image). tri_covers_sample()'s rule (tests check the
 * two agree), with the orientation given: area2 is twice the signed
 * area, which is tri_edges_setup's orient. */
static int tri_hits_box(const ScreenVert *v, const int32_t box[4], int64_t area2)
{
    if (area2 == 0)
        return 0;
    int64_t ax = v[0].x, ay = v[0].y, bx = v[1].x, by = v[1].y, cx = v[2].x, cy = v[2].y;
    if (area2 < 0) {            /* walk the edges the other way round */
        int64_t t = bx;
        bx = cx;
        cx = t;
        t = by;
        by = cy;
        cy = t;
    }
    for (int32_t j = box[2]; j < box[3]; j++)
        for (int32_t i = box[0]; i < box[1]; i++) {
            int64_t px = 256 * (int64_t)i + 128, py = 256 * (int64_t)j + 128;
            if (edge_covers(ax, ay, bx, by, px, py) && edge_covers(bx, by, cx, cy, px, py) &&
                edge_covers(cx, cy, ax, ay, px, py))
                return 1;
        }
    return 0;
}

/* Finish the triangle whose snapped corners are verts[first .. first + 3):
 * finish_poly() for three corners, straight-line. Returns 1 if kept. */
static int finish_tri(ScreenPolys *sp, uint32_t first)
{
    const ScreenVert *v = &sp->verts[first];
    int32_t box[4];
    if (!sample_box(sp, min3(v[0].x, v[1].x, v[2].x), max3(v[0].x, v[1].x, v[2].x), min3(v[0].y, v[1].y, v[2].y),
                    max3(v[0].y, v[1].y, v[2].y), box)) {
        sp->culled_empty++;
        return 0;
    }
    /* twice the signed area, y down: negative = front face (see finish_poly) */
    int64_t area2 = ((int64_t)v[0].x * v[1].y - (int64_t)v[1].x * v[0].y) +
                    ((int64_t)v[1].x * v[2].y - (int64_t)v[2].x * v[1].y) +
                    ((int64_t)v[2].x * v[0].y - (int64_t)v[0].x * v[2].y);
    if (sp->cull && area2 >= 0) {
        sp->culled_back++;
        return 0;
    }
    if ((box[1] - box[0]) * (box[3] - box[2]) <= 4 && !tri_hits_box(v, box, area2)) {
        sp->culled_empty++;
        return 0;
    }
    double X0 = v[0].x / (double)SUBPIX, Y0 = v[0].y / (double)SUBPIX, Z0 = v[0].z;
    double x1d = v[1].x / (double)SUBPIX - X0, y1d = v[1].y / (double)SUBPIX - Y0, z1d = v[1].z - Z0;
    double x2d = v[2].x / (double)SUBPIX - X0, y2d = v[2].y / (double)SUBPIX - Y0, z2d = v[2].z - Z0;
    double nx = y1d * z2d - z1d * y2d;
    double ny = z1d * x2d - x1d * z2d;
    double nz = x1d * y2d - y1d * x2d;
    if (nz == 0) {          /* no area at all: covers no sample */
        sp->culled_empty++;
        return 0;
    }
    /* the plane passes through the corners */
    double z1 = v[1].z, z2 = v[2].z;
    double lo = Z0 < z1 ? Z0 : z1;
    lo = z2 < lo ? z2 : lo;
    store_poly(sp, first, box, X0, Y0, Z0, -nx / nz, -ny / nz, lo);
    return 1;
}

/* Finish polygon whose snapped corners are verts[first .. nverts):
 * sample box, culling, plane. Returns 1 if kept. */
static int finish_poly(ScreenPolys *sp, uint32_t first)
{
    ScreenVert *v = &sp->verts[first];
    uint32_t n = sp->nverts - first;
    if (n < 3)
        return 0;
    if (n == 3)
        return finish_tri(sp, first);
    int32_t xmin = v[0].x, xmax = v[0].x, ymin = v[0].y, ymax = v[0].y;
    for (uint32_t k = 1; k < n; k++) {
        if (v[k].x < xmin) xmin = v[k].x;
        if (v[k].x > xmax) xmax = v[k].x;
        if (v[k].y < ymin) ymin = v[k].y;
        if (v[k].y > ymax) ymax = v[k].y;
    }
    int32_t box[4];
    if (!sample_box(sp, xmin, xmax, ymin, ymax, box)) {
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
    /* The plane z = z0 + a (x - X0) + b (y - Y0) from the snapped corners,
     * in double: Newell's normal of (x, y, z); a best-area triangle when
     * the outline's net area vanishes (a symmetric bow tie). */
    double X0 = v[0].x / (double)SUBPIX, Y0 = v[0].y / (double)SUBPIX, Z0 = v[0].z;
    double nx = 0, ny = 0, nz = 0;
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
    if (nz == 0) {          /* no area at all: covers no sample */
        sp->culled_empty++;
        return 0;
    }
    double a = -nx / nz, b = -ny / nz;
    double lo = 1e300;
    for (uint32_t k = 0; k < n; k++) {
        double z = Z0 + a * (v[k].x / (double)SUBPIX - X0) + b * (v[k].y / (double)SUBPIX - Y0);
        if (z < lo)
            lo = z;
    }
    store_poly(sp, first, box, X0, Y0, Z0, a, b, lo);
    return 1;
}

/* project.h */
int project_finish(ScreenPolys *sp, uint32_t first)
{
    return finish_poly(sp, first);
}

/* project.h */
int project_emit_poly(RangeJob *j, uint32_t k, uint32_t c0, uint32_t c1, uint32_t inst)
{
    ScreenPolys *sp = j->out;
    uint32_t nc = c1 - c0;
    /* room for the clipped outline: each plane adds at most one vertex */
    int rv = vert_room(j, sp->nverts + nc + 8);
    if (rv)
        return rv;
    const ScreenVert *sv = j->vs->sv;
    const uint32_t *corner = j->s->poly_corner, vmin = j->o->vert_min;
    int all_ok = 1;
    for (uint32_t c = c0; c < c1; c++)
        all_ok &= sv[corner[c] - vmin].x != VERT_OUT;
    uint32_t first = sp->nverts;
    int kept;
    if (all_ok) {
        ScreenVert *dst = &sp->verts[first];
        for (uint32_t c = c0; c < c1; c++)
            *dst++ = sv[corner[c] - vmin];
        sp->nverts += nc;
        kept = nc == 3 ? finish_tri(sp, first) : finish_poly(sp, first);
    } else {
        rv = project_clip(j, c0, c1);
        if (rv > 0)
            return 0;           /* too many corners to clip: dropped */
        if (rv)
            return rv;
        kept = finish_poly(sp, first);
    }
    if (kept)
        kept_poly(j, k, inst);
    else
        sp->nverts = first;
    return 0;
}

/* The kept polygons keep[0 .. nk) of the chunk from polygon k
 * (instance inst): triangles at corners c0 + 3 keep[i] when c0 is not
 * UINT32_MAX (AVX2 takes them four at a time), else any polygons. */
static int emit_kept(RangeJob *j, uint32_t k, uint32_t c0, uint32_t inst, const uint32_t *keep, uint32_t nk)
{
    const Scene *s = j->s;
#ifdef ZV_AVX2
    if (c0 != UINT32_MAX && j->simd >= SIMD_AVX2)
        return project_emit_tris_avx2(j, k, c0, inst, keep, nk);
#endif
    for (uint32_t i = 0; i < nk; i++) {
        uint32_t q = k + keep[i];
        uint32_t a = c0 != UINT32_MAX ? c0 + 3 * keep[i] : scene_poly_c0(s, q);
        uint32_t b = c0 != UINT32_MAX ? a + 3 : scene_poly_c0(s, q + 1);
        int rv = project_emit_poly(j, q, a, b, inst + keep[i]);
        if (rv)
            return rv;
    }
    return 0;
}

/* project.h */
int project_range(RangeJob *j)
{
    ScreenPolys *sp = j->out;
    const Scene *s = j->s;
    const Object *o = j->o;
    const uint32_t *idx = j->vs->idx;
    uint32_t vmin = o->vert_min, empty = 0;
    uint32_t keep[CHUNK + 8];
    for (uint32_t k = j->k0; k < j->k1; k += CHUNK) {
        uint32_t n = j->k1 - k < CHUNK ? j->k1 - k : CHUNK, inst = j->inst0 + (k - j->k0);
        uint32_t c0 = scene_poly_c0(s, k);
        /* every polygon starts dropped; project_emit_poly records the kept ones */
        if (j->map)
            memset(j->map + inst, 0xff, (size_t)n * sizeof *j->map);
        sp->in_polys += n;
        int tris = scene_poly_c0(s, k + n) - c0 == 3 * n;
        uint32_t nk;
        if (tris) {
            /* n polygons of at least three corners each and 3 n corners
             * in all: triangles only, at corners c0 + 3 i */
            nk = screen_tris(j->simd, s->poly_corner + c0, n, idx, vmin, sp->w, sp->h, keep, j->lut);
            empty += n - nk;
        } else {
            /* a mixed chunk: triangles screened one by one */
            nk = 0;
            for (uint32_t i = 0; i < n; i++) {
                uint32_t a = scene_poly_c0(s, k + i);
                keep[nk] = i;
                nk += scene_poly_c0(s, k + i + 1) - a != 3 || tri_keeps(s->poly_corner + a, idx, vmin, sp->w, sp->h);
            }
            empty += n - nk;
        }
        uint32_t cutk[CHUNK], ncut = 0;
        if (j->cmask)
            /* the polygons a plane cuts or removes, drawn below in their
             * places (cut.c); taken out before the second screening,
             * which would judge a triangle whole where its kept part,
             * with corners of its own, may cover a sample it misses */
            nk = project_cut_split(j, k, keep, nk, cutk, &ncut);
        if (tris) {
            /* the kept ones' points are read next, scattered over an
             * array too big for the caches: ask for all of them at once
             * (dragon at 160x96: the second screening 0.9 -> 0.3 ms) */
            for (uint32_t i = 0; i < nk; i++) {
                const uint32_t *c = s->poly_corner + c0 + 3 * keep[i];
                __builtin_prefetch(&j->vs->sv[c[0] - vmin]);
                __builtin_prefetch(&j->vs->sv[c[1] - vmin]);
                __builtin_prefetch(&j->vs->sv[c[2] - vmin]);
            }
#ifdef ZV_AVX2
            if (j->simd >= SIMD_AVX2)
                nk = project_sift_small_avx2(s->poly_corner + c0, j->vs->sv, vmin, sp->w, sp->h, sp->cull, keep, nk,
                                             j->lut, &empty, &sp->culled_back);
#endif
            /* the face ids of the kept ones are read below, scattered
             * over a big array (one kept in twenty at small sizes: a
             * line each): start fetching every one now (none in the
             * compact form, where the id is the polygon's own) */
            for (uint32_t i = 0; s->poly_lface && i < nk; i++)
                __builtin_prefetch(&s->poly_lface[k + (keep[i] & ~KEEP_HIT)]);
        }
        /* in polygon order, every thread count alike (a part's chunks
         * start where the part does): the kept ones up to each cut one,
         * then the cut one's kept part */
        for (uint32_t c = 0, at = 0;; c++) {
            uint32_t lim = c < ncut ? cutk[c] : UINT32_MAX, e = c < ncut ? at : nk;
            while (e < nk && (keep[e] & ~KEEP_HIT) < lim)
                e++;
            int rv = emit_kept(j, k, tris ? c0 : UINT32_MAX, inst, keep + at, e - at);
            if (!rv && c < ncut)
                rv = project_emit_cut(j, k + lim, scene_poly_c0(s, k + lim), scene_poly_c0(s, k + lim + 1), inst + lim);
            if (rv) {
                sp->culled_empty += empty;
                return rv;
            }
            if (c == ncut)
                break;
            at = e;
        }
    }
    sp->culled_empty += empty;
    return 0;
}
