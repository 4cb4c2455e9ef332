/* prims.c: points, line segments and wireframe edges as screen-space
 * polygons, appended after the faces' (screen.h, screen_prims).
 *
 * They use the projection screen_project left in ScreenPolys (focal
 * lengths, eye, near and far, the orthographic depth map), the same
 * formulas and the same snapping (round to 1/256 pixel, halves up), so
 * a point drawn at a face's vertex lands where the face's corner does
 * (up to the rounding of the focal lengths to float).
 *
 * A point of size s (samples) is the square of s x s samples whose
 * corner sample is fixed by its snapped centre c: columns
 * [ceil((c.x - 128 s - 128) / 256), + s), rows likewise (supersampled
 * with k x k samples a pixel and s a multiple of k: the first whole
 * pixel instead, so that a one-pixel point lights one pixel of the
 * averaged picture); its corners lie on sample boundaries and its depth
 * plane is flat (a = b = 0, zc = its depth, which plane_at() returns
 * exactly). Two points with
 * the same corner sample cover the same samples, and at each of them
 * the one with the smaller (depth, id) wins; so of all the points in
 * one box only that one can show anywhere, and keeping only it gives
 * exactly the buffers of drawing them all (tests check this against
 * PrimStyle.all_prims). One pass keeps, per box, the least
 * (depth, id) packed in a 64-bit key that orders as the pair does; the
 * boxes that got a point become squares. The work is one transform and
 * one compare per point, and the polygons are bounded by the screen
 * (about W x H for size 1), not by the cloud: a 10M-point scan gives a
 * few tens of thousands of squares in a terminal. Big clouds are split
 * between threads, each with its own boxes, merged by the same minimum.
 *
 * A segment of width w (samples) is clipped to the near plane (in view
 * space) and to the screen widened by w / 2 + 2 pixels (in screen
 * space, where depth is affine), then becomes the parallelogram
 * E0 + o, E1 + o, E1 - o, E0 - o with E0, E1 its ends moved out by w / 2
 * along it (square ends, so the segments of a polyline meet without a
 * notch) and o its half width across it, each snapped: an exact
 * parallelogram in fixed point. Its depth plane is the one through it
 * that is constant across the width and takes the segment's depths
 * (extended linearly to E0 and E1) at its ends. Wireframe edges, and
 * the problem edges of --problems (Scene.marks), are the same with their
 * depths less PRIM_WIRE_BIAS.
 *
 * Many quads on few samples (a wireframe's copies in a small picture:
 * --grid 8 of a 22k-quad model at 8x6 made 22.9M of them, and every
 * algorithm drew them all) are reduced as points are: a quad whose
 * sample box is small, and every quad past one per SAMPLES_PER_QUAD
 * samples of the picture, is given as its samples, each with the depth
 * plane_at() gives the quad there, and per sample only the least
 * (depth, id) is kept. Each sample that got one becomes a square of one
 * sample whose flat plane gives exactly that depth: the buffers of
 * drawing every quad whole (tests check this against
 * PrimStyle.all_prims), with at most a square per sample and a quad per
 * SAMPLES_PER_QUAD samples for the algorithms. */

#define _DEFAULT_SOURCE
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "thread.h"
#include "grow.h"
#include "raster.h"
#include "screen.h"
#include "section.h"
#include "simd.h"

/* Points worth a helper thread each (below it, starting one costs more). */
#define POINTS_PER_THREAD (1u << 18)
/* Points whose boxes are fetched ahead together. */
#define CHUNK 256

struct PrimWork {
    uint64_t *box[SCREEN_MAX_THREADS];      /* per thread: the best key per sample box */
    uint32_t  cap[SCREEN_MAX_THREADS];
    int       ncpus;
    uint64_t *keys;         /* the least key per sample of the quads given as samples:
                               all empty (UINT64_MAX) between frames */
    uint32_t  cap_keys;
};

void prims_free(PrimWork **work)
{
    if (!*work)
        return;
    for (int t = 0; t < SCREEN_MAX_THREADS; t++)
        free((*work)->box[t]);
    free((*work)->keys);
    free(*work);
    *work = NULL;
}

/* The projection screen_project used, from what it left in sp. */
typedef struct {
    int    persp, w, h;
    double cx, cy, fx, fy;
    double eye, n, f;           /* persp */
    double dscale, dbias;       /* ortho */
} PProj;

static void pproj_from(PProj *p, const ScreenPolys *sp)
{
    p->persp = sp->persp;
    p->w = sp->w;
    p->h = sp->h;
    p->cx = sp->w * 0.5;
    p->cy = sp->h * 0.5;
    p->fx = sp->focal_x;
    p->fy = sp->focal_y;
    p->eye = sp->eye_z;
    p->n = sp->near_z;
    p->f = sp->far_z;
    p->dscale = sp->depth_scale;
    p->dbias = sp->depth_bias;
}

/* View space -> screen pixels and depth, as project.c's proj_point (under
 * perspective the point must be in front of the near plane). */
static inline void pproj_point(const PProj *p, double x, double y, double z, double out[3])
{
    if (!p->persp) {
        out[0] = p->cx + p->fx * x;
        out[1] = p->cy - p->fy * y;
        out[2] = p->dbias - p->dscale * z;
    } else {
        double ze = p->eye - z;
        out[0] = p->cx + p->fx * x / ze;
        out[1] = p->cy - p->fy * y / ze;
        out[2] = p->f / (p->f - p->n) * (1 - p->n / ze);
    }
}

int screen_view_point(const ScreenPolys *sp, double x, double y, double z, double out[3])
{
    PProj p;
    pproj_from(&p, sp);
    if (p.persp && !(p.eye - z >= p.n))
        return -1;
    pproj_point(&p, x, y, z, out);
    return 0;
}

/* Round to the nearest 1/256 pixel, halves up (the front end's rule);
 * callers keep v within a few screens of the image. The floor by hand:
 * without SSE4.1 floor() is a call, and a line makes six of these (the
 * truncation is exact, and one below when it went up). */
static inline int32_t snap(double v)
{
    double x = v * SUBPIX + 0.5;
    int64_t t = (int64_t)x;
    return (int32_t)(t - ((double)t > x));
}

/* A key that orders as the (depth, id) pair does under hsr_wins: the
 * depth's bits made to order as unsigned (finite depths, -0 made +0 by
 * the caller), then the id. */
static inline uint64_t point_key(float z, int32_t id)
{
    uint32_t u;
    memcpy(&u, &z, sizeof u);
    u = u & 0x80000000u ? ~u : u | 0x80000000u;
    return (uint64_t)u << 32 | (uint32_t)id;
}

static inline float key_depth(uint64_t k)
{
    uint32_t u = (uint32_t)(k >> 32);
    u = u & 0x80000000u ? u & 0x7fffffffu : ~u;
    float z;
    memcpy(&z, &u, sizeof z);
    return z;
}

/* ==== points ==== */

/* One object's points straight from object space to the screen: the
 * object-to-view matrix and the projection folded into one affine map
 * per coordinate, in float (a point is one of millions: this loop is
 * the cost of a cloud). The map gives U = 256 x + 0.5 and V = 256 y +
 * 0.5 (x, y in pixels), whose floors are the snapped centre, and the
 * depth; under perspective x and y are divided by the distance first.
 * Any fixed rule would do for exactness (every point is placed by this
 * one, whether kept or not); this one rounds like the front end. */
typedef struct {
    int   persp, size, w, h;
    int   align;            /* squares start on multiples of this many samples (a pixel's side) */
    float r[3][4];          /* ortho: U, V, depth; persp: view x, view y, distance */
    float u0, v0, fu, fv;   /* persp: U = u0 + fu x / d, V = v0 + fv y / d */
    float near, dk;         /* persp: depth = dk (1 - near / d) */
    float umin, umax, vmin, vmax;   /* beyond these the square misses the screen */
} PointMap;

static void point_map(PointMap *pm, const PProj *pj, const Mat4 *mv, int size, int align)
{
    pm->persp = pj->persp;
    pm->size = size;
    pm->align = align;
    pm->w = pj->w;
    pm->h = pj->h;
    double u0 = 256 * pj->cx + 0.5, v0 = 256 * pj->cy + 0.5;
    for (int j = 0; j < 4; j++) {
        double m0 = mv->m[0][j], m1 = mv->m[1][j], m2 = mv->m[2][j];
        int t = j == 3;
        if (!pj->persp) {
            pm->r[0][j] = (float)(256 * pj->fx * m0 + (t ? u0 : 0));
            pm->r[1][j] = (float)(-256 * pj->fy * m1 + (t ? v0 : 0));
            pm->r[2][j] = (float)(-pj->dscale * m2 + (t ? pj->dbias : 0));
        } else {
            pm->r[0][j] = (float)m0;
            pm->r[1][j] = (float)m1;
            pm->r[2][j] = (float)(-m2 + (t ? pj->eye : 0));
        }
    }
    pm->u0 = (float)u0;
    pm->v0 = (float)v0;
    pm->fu = (float)(256 * pj->fx);
    pm->fv = (float)(-256 * pj->fy);
    pm->near = (float)pj->n;
    pm->dk = (float)(pj->f / (pj->f - pj->n));
    /* a square of any size near the screen lies within size + 2 pixels */
    pm->umin = (float)(-256.0 * (size + 2));
    pm->umax = (float)(256.0 * (pj->w + size + 2));
    pm->vmin = (float)(-256.0 * (size + 2));
    pm->vmax = (float)(256.0 * (pj->h + size + 2));
}

/* The first column (row) of a square of the map's size whose snapped
 * centre is at fixed-point c: the first sample whose centre is at or
 * right of its edge; with supersampling, the first whole pixel (align
 * samples a side) whose centre is: a one-pixel point then lights one
 * pixel of the averaged picture, where a square astride four pixels'
 * samples would light none of them fully. The quotient of integers
 * below 2^26 by 256 align is floored exactly in double. */
static inline int32_t box_start(const PointMap *pm, int32_t c)
{
    int32_t edge = c - 128 * pm->size;
    if (pm->align == 1)
        return sample_ceil(edge);
    int32_t k = pm->align;
    return k * (int32_t)floor((double)(edge + 128 * k - 1) / (256.0 * k));
}

/* floor of a float known to lie well within int32 */
static inline int32_t floor_i32(float x)
{
    int32_t t = (int32_t)x;
    return t - (x < (float)t);
}

/* A point's sample box (its corner sample) and depth. Returns 0 when it
 * draws nothing: behind the near plane, off the screen, not finite. */
static inline __attribute__((always_inline)) int point_box(const PointMap *pm, const float *p, int32_t *i0,
                                                           int32_t *j0, float *depth)
{
    float x = p[0], y = p[1], z = p[2];
    float a = pm->r[0][0] * x + pm->r[0][1] * y + pm->r[0][2] * z + pm->r[0][3];
    float b = pm->r[1][0] * x + pm->r[1][1] * y + pm->r[1][2] * z + pm->r[1][3];
    float c = pm->r[2][0] * x + pm->r[2][1] * y + pm->r[2][2] * z + pm->r[2][3];
    if (pm->persp) {
        if (!(c >= pm->near))
            return 0;
        float inv = 1.0f / c;
        a = pm->u0 + pm->fu * a * inv;
        b = pm->v0 + pm->fv * b * inv;
        c = pm->dk - pm->dk * pm->near * inv;
    }
    if (!(a > pm->umin && a < pm->umax && b > pm->vmin && b < pm->vmax))
        return 0;           /* off the screen, or NaN */
    float d = c + 0.0f;     /* -0 becomes +0: equal depths compare equal */
    if (!(d - d == 0))
        return 0;
    /* the snapped centre, then the first sample whose centre is at or
     * right of (below) the square's edge */
    int size = pm->size;
    *i0 = box_start(pm, floor_i32(a));
    *j0 = box_start(pm, floor_i32(b));
    *depth = d;
    return *i0 < pm->w && *i0 + size > 0 && *j0 < pm->h && *j0 + size > 0;
}

#ifdef ZV_SSE2
/* point_box for four consecutive points at p (12 floats), in SSE2: the
 * same operations in the same order as point_box (so the same bits:
 * -ffp-contract=off, no fused multiply-add), four lanes at a time; the
 * boxes' checks and the keys per lane. Returns a mask of the points that
 * reach a box. A cloud's points are consecutive vertices: this is its
 * loop. */
static inline __attribute__((always_inline)) int point_box4(const PointMap *pm, const float *p, int32_t i0[4],
                                                            int32_t j0[4], float depth[4])
{
    __m128 v0 = _mm_loadu_ps(p), v1 = _mm_loadu_ps(p + 4), v2 = _mm_loadu_ps(p + 8);
    /* x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3  ->  X, Y, Z */
    __m128 B = _mm_shuffle_ps(v1, v2, _MM_SHUFFLE(1, 0, 2, 2));
    __m128 X = _mm_shuffle_ps(v0, B, _MM_SHUFFLE(3, 0, 3, 0));
    __m128 C = _mm_shuffle_ps(v0, v1, _MM_SHUFFLE(0, 0, 1, 1));
    __m128 D = _mm_shuffle_ps(v1, v2, _MM_SHUFFLE(2, 2, 3, 3));
    __m128 Y = _mm_shuffle_ps(C, D, _MM_SHUFFLE(2, 0, 2, 0));
    __m128 E = _mm_shuffle_ps(v0, v1, _MM_SHUFFLE(1, 1, 2, 2));
    __m128 F = _mm_shuffle_ps(v2, v2, _MM_SHUFFLE(3, 3, 0, 0));
    __m128 Z = _mm_shuffle_ps(E, F, _MM_SHUFFLE(2, 0, 2, 0));
    __m128 r[3];
    for (int k = 0; k < 3; k++)
        r[k] = _mm_add_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(pm->r[k][0]), X),
                                                _mm_mul_ps(_mm_set1_ps(pm->r[k][1]), Y)),
                                     _mm_mul_ps(_mm_set1_ps(pm->r[k][2]), Z)),
                          _mm_set1_ps(pm->r[k][3]));
    __m128 a = r[0], b = r[1], c = r[2], ok = _mm_castsi128_ps(_mm_set1_epi32(-1));
    if (pm->persp) {
        ok = _mm_cmpge_ps(c, _mm_set1_ps(pm->near));
        __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), c);
        a = _mm_add_ps(_mm_set1_ps(pm->u0), _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(pm->fu), a), inv));
        b = _mm_add_ps(_mm_set1_ps(pm->v0), _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(pm->fv), b), inv));
        c = _mm_sub_ps(_mm_set1_ps(pm->dk), _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(pm->dk), _mm_set1_ps(pm->near)), inv));
    }
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(a, _mm_set1_ps(pm->umin)), _mm_cmplt_ps(a, _mm_set1_ps(pm->umax))));
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(b, _mm_set1_ps(pm->vmin)), _mm_cmplt_ps(b, _mm_set1_ps(pm->vmax))));
    __m128 d = _mm_add_ps(c, _mm_setzero_ps());
    ok = _mm_and_ps(ok, _mm_cmpeq_ps(_mm_sub_ps(d, d), _mm_setzero_ps()));
    int mask = _mm_movemask_ps(ok);
    if (!mask)
        return 0;
    /* floors of the lanes that passed (the others' values are not used) */
    __m128i ta = _mm_cvttps_epi32(a), tb = _mm_cvttps_epi32(b);
    ta = _mm_add_epi32(ta, _mm_castps_si128(_mm_cmplt_ps(a, _mm_cvtepi32_ps(ta))));
    tb = _mm_add_epi32(tb, _mm_castps_si128(_mm_cmplt_ps(b, _mm_cvtepi32_ps(tb))));
    if (pm->align == 1) {
        __m128i off = _mm_set1_epi32(127 - 128 * pm->size);
        _mm_storeu_si128((__m128i *)i0, _mm_srai_epi32(_mm_add_epi32(ta, off), SUBPIX_BITS));
        _mm_storeu_si128((__m128i *)j0, _mm_srai_epi32(_mm_add_epi32(tb, off), SUBPIX_BITS));
    } else {
        _mm_storeu_si128((__m128i *)i0, ta);
        _mm_storeu_si128((__m128i *)j0, tb);
        for (int k = 0; k < 4; k++)
            if (mask >> k & 1) {
                i0[k] = box_start(pm, i0[k]);
                j0[k] = box_start(pm, j0[k]);
            }
    }
    _mm_storeu_ps(depth, d);
    for (int k = 0; k < 4; k++)
        if (!(i0[k] < pm->w && i0[k] + pm->size > 0 && j0[k] < pm->h && j0[k] + pm->size > 0))
            mask &= ~(1 << k);
    return mask;
}
#endif

/* Append the square of size s with corner sample (i0, j0). */
static void emit_square(ScreenPolys *sp, int32_t i0, int32_t j0, int size, float z, int32_t id)
{
    ScreenVert *v = &sp->verts[sp->nverts];
    int32_t xa = i0 * SUBPIX, xb = (i0 + size) * SUBPIX, ya = j0 * SUBPIX, yb = (j0 + size) * SUBPIX;
    v[0] = (ScreenVert){ xa, ya, z };
    v[1] = (ScreenVert){ xb, ya, z };
    v[2] = (ScreenVert){ xb, yb, z };
    v[3] = (ScreenVert){ xa, yb, z };
    ScreenPoly *p = &sp->polys[sp->npolys++];
    p->first = sp->nverts;
    p->face = id;
    p->x0 = i0 > 0 ? i0 : 0;
    p->x1 = i0 + size < sp->w ? i0 + size : sp->w;
    p->y0 = j0 > 0 ? j0 : 0;
    p->y1 = j0 + size < sp->h ? j0 + size : sp->h;
    p->a = p->b = 0;
    p->zc = z;
    p->zmin = z;            /* the plane is flat: exactly its depth everywhere */
    sp->nverts += 4;
}

typedef struct {
    const Scene *s;
    const PProj *pj;
    Mat4         view;
    uint64_t    *box;       /* gw * gh keys, UINT64_MAX = empty */
    int32_t      gw, gh;    /* boxes: corner samples [1 - size, w) x [1 - size, h) */
    int          size, align;
    uint32_t     g0, g1;    /* global point numbers this job takes */
    uint32_t     in;        /* points that reached a box */
    int          simd;      /* the frame's SimdLevel, resolved (simd_use) */
    const SectionCut *cut;  /* a section cut: its removed points are left out */
} PointJob;

/* The cut's masks of object oi's mesh when a plane removes some of it,
 * else NULL. */
static const uint8_t *cut_mask(const SectionCut *c, const Scene *s, int oi)
{
    if (!c || !c->nplanes || c->key != s || !c->touched[oi])
        return NULL;
    return c->mask[s->objs[oi].mesh - s->meshes];
}

/* Keep the least key per box over points g0 .. g1 (numbered over all
 * objects in order, as their ids are). */
static void points_reduce(PointJob *j)
{
    const Scene *s = j->s;
    int size = j->size;
    uint32_t in = 0;
    for (int oi = 0; oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        uint32_t a = (uint32_t)o->point_id0 - s->nfaces, b = a + o->point_count;
        uint32_t lo = a > j->g0 ? a : j->g0, hi = b < j->g1 ? b : j->g1;
        if (lo >= hi)
            continue;
        Mat4 mv = m4_mul(j->view, object_matrix(o));
        PointMap pm;
        point_map(&pm, j->pj, &mv, size, j->align);
        const float *pos = o->mesh->pos;
        const uint32_t *pt = o->mesh->point;
        const uint8_t *cm = cut_mask(j->cut, s, oi);
        uint8_t all = cm ? section_all(j->cut) : 0;
        /* A chunk at a time: first each point's box and key, its box's
         * line asked for ahead (boxes are met in no order a cache can
         * guess), then the minima, by then mostly in L1. */
        for (uint32_t g0 = lo; g0 < hi; g0 += CHUNK) {
            uint32_t g1 = hi - g0 < CHUNK ? hi : g0 + CHUNK, n = 0;
            uint32_t cell[CHUNK];
            uint64_t keys[CHUNK];
            uint32_t g = g0;
#ifdef ZV_SSE2
            /* a cloud (consecutive vertices): four at a time */
            for (; !pt && !cm && j->simd >= SIMD_SSE2 && g + 4 <= g1; g += 4) {
                uint32_t k = g - a;
                int32_t i4[4], j4[4];
                float z4[4];
                int mask = point_box4(&pm, &pos[3 * ((size_t)o->point_first + k)], i4, j4, z4);
                for (int q = 0; q < 4; q++)
                    if (mask >> q & 1) {
                        cell[n] = (uint32_t)((j4[q] + size - 1) * j->gw + (i4[q] + size - 1));
                        keys[n] = point_key(z4[q], o->point_id0 + (int32_t)(k + (uint32_t)q));
                        __builtin_prefetch(&j->box[cell[n]], 1);
                        n++;
                    }
            }
#endif
            for (; g < g1; g++) {
                uint32_t k = g - a, v = pt ? pt[o->point_first + k] : o->point_first + k;
                int32_t i0, j0;
                float z;
                if ((cm && cm[v] == all) || !point_box(&pm, &pos[3 * (size_t)v], &i0, &j0, &z))
                    continue;
                cell[n] = (uint32_t)((j0 + size - 1) * j->gw + (i0 + size - 1));
                keys[n] = point_key(z, o->point_id0 + (int32_t)k);
                __builtin_prefetch(&j->box[cell[n]], 1);
                n++;
            }
            in += n;
            for (uint32_t q = 0; q < n; q++) {
                /* a select, not a branch: whether a point is nearer than
                 * its box's best so far is a coin toss */
                uint64_t *c = &j->box[cell[q]], old = *c;
                *c = keys[q] < old ? keys[q] : old;
            }
        }
    }
    j->in = in;
}

static void *points_thread(void *arg)
{
    points_reduce(arg);
    return NULL;
}

/* Every point as its own square (PrimStyle.all_prims). */
static int points_all(ScreenPolys *sp, const Scene *s, const PProj *pj, const Mat4 *view, int size, int align)
{
    for (int oi = 0; oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        Mat4 mv = m4_mul(*view, object_matrix(o));
        PointMap pm;
        point_map(&pm, pj, &mv, size, align);
        const uint8_t *cm = cut_mask(sp->cut, s, oi);
        for (uint32_t k = 0; k < o->point_count; k++) {
            int32_t i0, j0;
            float z;
            uint32_t v = object_point_vert(o, k);
            if ((cm && cm[v] == section_all(sp->cut)) || !point_box(&pm, &o->mesh->pos[3 * (size_t)v], &i0, &j0, &z))
                continue;
            sp->points_in++;
            if (grow_array((void **)&sp->polys, &sp->cap_polys, sp->npolys + 2, sizeof *sp->polys) ||
                grow_array((void **)&sp->verts, &sp->cap_verts, sp->nverts + 4, sizeof *sp->verts))
                return -1;
            emit_square(sp, i0, j0, size, z, o->point_id0 + (int32_t)k);
            sp->points_drawn++;
        }
    }
    return 0;
}

static int points_reduced(ScreenPolys *sp, const Scene *s, const PProj *pj, const Mat4 *view, int size, int align,
                          PrimWork *w)
{
    int32_t gw = sp->w + size - 1, gh = sp->h + size - 1;
    uint64_t nbox = (uint64_t)gw * gh;
    if (nbox > UINT32_MAX)
        return -1;
    int t = sp->threads > 0 ? sp->threads : w->ncpus;
    if (t > SCREEN_MAX_THREADS)
        t = SCREEN_MAX_THREADS;
    if ((uint64_t)t > s->npoints / POINTS_PER_THREAD)
        t = (int)(s->npoints / POINTS_PER_THREAD);
    if (t < 1)
        t = 1;
    PointJob job[SCREEN_MAX_THREADS];
    pthread_t th[SCREEN_MAX_THREADS];
    int started[SCREEN_MAX_THREADS] = { 0 };
    int simd = simd_use(sp->simd);
    for (int i = 0; i < t; i++) {
        if (grow_array((void **)&w->box[i], &w->cap[i], (uint32_t)nbox, sizeof *w->box[i]))
            return -1;
        memset(w->box[i], 0xff, nbox * sizeof *w->box[i]);
        job[i] = (PointJob){ s, pj, *view, w->box[i], gw, gh, size, align,
                             (uint32_t)((uint64_t)s->npoints * (uint32_t)i / (uint32_t)t),
                             (uint32_t)((uint64_t)s->npoints * (uint32_t)(i + 1) / (uint32_t)t), 0, simd, sp->cut };
    }
    for (int i = 1; i < t; i++)
        started[i] = thread_start(&th[i], points_thread, &job[i]) == 0;
    points_reduce(&job[0]);
    uint64_t *box = w->box[0];
    for (int i = 1; i < t; i++) {
        if (started[i])
            pthread_join(th[i], NULL);
        else
            points_reduce(&job[i]);     /* no thread to be had: here */
        const uint64_t *other = w->box[i];
        for (uint64_t k = 0; k < nbox; k++)
            box[k] = other[k] < box[k] ? other[k] : box[k];
    }
    for (int i = 0; i < t; i++)
        sp->points_in += job[i].in;
    uint32_t kept = 0;
    for (uint64_t k = 0; k < nbox; k++)
        kept += box[k] != UINT64_MAX;
    if (grow_array((void **)&sp->polys, &sp->cap_polys, sp->npolys + kept + 1, sizeof *sp->polys) ||
        grow_array((void **)&sp->verts, &sp->cap_verts, sp->nverts + 4 * kept, sizeof *sp->verts))
        return -1;
    for (int32_t r = 0; r < gh; r++) {
        const uint64_t *row = box + (size_t)r * gw;
        for (int32_t c = 0; c < gw; c++)
            if (row[c] != UINT64_MAX)
                emit_square(sp, c - size + 1, r - size + 1, size, key_depth(row[c]), (int32_t)(uint32_t)row[c]);
    }
    sp->points_drawn += kept;
    return 0;
}

/* ==== segments and wireframe edges ==== */

/* A quad whose sample box holds at most this many samples is given as
 * its samples: it covers at most as many, so it never makes more than
 * that many squares, and many such quads on one sample make one. */
#define SMALL_QUAD 4
/* Whole quads kept at most: one per this many samples of the picture.
 * Past it the picture is covered many times over, and every further
 * quad is given as its samples, so that what reaches the algorithms
 * (and the memory it takes) is bounded by the picture, not by the
 * copies times the lines. */
#define SAMPLES_PER_QUAD 4

/* A segment's quad as the algorithms would get it: its snapped corners
 * and its polygon (first not set). */
typedef struct {
    ScreenVert v[4];
    ScreenPoly p;
} EdgeQuad;

/* Clip the screen segment a -> b (x, y, depth) to [lo, hi] on axis k:
 * the parameter range [*t0, *t1] shrinks; 0 when nothing is left. */
static int clip_axis(const double *a, const double *b, int k, double lo, double hi, double *t0, double *t1)
{
    double d = b[k] - a[k];
    if (d == 0)
        return a[k] >= lo && a[k] <= hi;
    double ta = (lo - a[k]) / d, tb = (hi - a[k]) / d;
    if (ta > tb) {
        double x = ta;
        ta = tb;
        tb = x;
    }
    if (ta > *t0)
        *t0 = ta;
    if (tb < *t1)
        *t1 = tb;
    return *t0 <= *t1;
}

/* The quad of view-space segment p -> q, width samples wide, depths
 * less bias, into *eq. Returns 0 when it reaches no sample box. */
static int edge_quad(const ScreenPolys *sp, const PProj *pj, Vec3 p, Vec3 q, int width, double bias, int32_t id,
                     EdgeQuad *eq)
{
    double a[3] = { p.x, p.y, p.z }, b[3] = { q.x, q.y, q.z };
    if (pj->persp) {
        /* keep eye - z >= near: z <= eye - near */
        double lim = pj->eye - pj->n;
        int ina = a[2] <= lim, inb = b[2] <= lim;
        if (!ina && !inb)
            return 0;
        if (ina != inb) {
            double *out = ina ? b : a, *in = ina ? a : b;
            double t = (lim - in[2]) / (out[2] - in[2]);
            for (int k = 0; k < 2; k++)
                out[k] = in[k] + t * (out[k] - in[k]);
            out[2] = lim;
        }
    }
    double sa[3], sb[3];
    pproj_point(pj, a[0], a[1], a[2], sa);
    pproj_point(pj, b[0], b[1], b[2], sb);
    for (int k = 0; k < 3; k++)
        if (!isfinite(sa[k]) || !isfinite(sb[k]))
            return 0;
    /* the screen widened past what the quad's half width and ends can
     * reach into it: no sample changes */
    double half = width * 0.5, m = half + 2, t0 = 0, t1 = 1;
    /* both ends inside: clip_axis would leave [0, 1] as it is (its
     * quotients are <= 0 and >= 1 then, rounding being monotonic), so
     * its four divisions are skipped */
    int inside = sa[0] >= -m && sa[0] <= pj->w + m && sb[0] >= -m && sb[0] <= pj->w + m && sa[1] >= -m &&
                 sa[1] <= pj->h + m && sb[1] >= -m && sb[1] <= pj->h + m;
    if (!inside &&
        (!clip_axis(sa, sb, 0, -m, pj->w + m, &t0, &t1) || !clip_axis(sa, sb, 1, -m, pj->h + m, &t0, &t1)))
        return 0;
    double e0[3], e1[3];
    for (int k = 0; k < 3; k++) {
        e0[k] = sa[k] + t0 * (sb[k] - sa[k]);
        e1[k] = sa[k] + t1 * (sb[k] - sa[k]);
    }
    e0[2] -= bias;
    e1[2] -= bias;
    double dx = e1[0] - e0[0], dy = e1[1] - e0[1], len = sqrt(dx * dx + dy * dy);
    double ux = 1, uy = 0, ext = 0;
    if (len > 1e-9) {
        ux = dx / len;
        uy = dy / len;
        ext = half / len;
    }
    /* the ends moved out by half the width, depth following the line */
    double z0 = e0[2] - ext * (e1[2] - e0[2]), z1 = e1[2] + ext * (e1[2] - e0[2]);
    int32_t E0x = snap(e0[0] - ux * half), E0y = snap(e0[1] - uy * half);
    int32_t E1x = snap(e1[0] + ux * half), E1y = snap(e1[1] + uy * half);
    int32_t ox = snap(-uy * half), oy = snap(ux * half);
    /* the plane: constant across (along o), z0 -> z1 from E0 to E1 */
    double Dx = (double)(E1x - E0x) / SUBPIX, Dy = (double)(E1y - E0y) / SUBPIX;
    double Ox = (double)ox / SUBPIX, Oy = (double)oy / SUBPIX;
    double det = Ox * Dy - Oy * Dx, dz = z1 - z0;
    if (det == 0)
        return 0;
    double ga = -Oy * dz / det, gb = Ox * dz / det;
    int32_t cx[4] = { E0x + ox, E1x + ox, E1x - ox, E0x - ox }, cy[4] = { E0y + oy, E1y + oy, E1y - oy, E0y - oy };
    int32_t xmin = cx[0], xmax = cx[0], ymin = cy[0], ymax = cy[0];
    for (int k = 1; k < 4; k++) {
        xmin = cx[k] < xmin ? cx[k] : xmin;
        xmax = cx[k] > xmax ? cx[k] : xmax;
        ymin = cy[k] < ymin ? cy[k] : ymin;
        ymax = cy[k] > ymax ? cy[k] : ymax;
    }
    int32_t x0 = sample_ceil(xmin), x1 = sample_ceil(xmax), y0 = sample_ceil(ymin), y1 = sample_ceil(ymax);
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > sp->w ? sp->w : x1;
    y1 = y1 > sp->h ? sp->h : y1;
    if (x0 >= x1 || y0 >= y1)
        return 0;
    float zf[4] = { (float)z0, (float)z1, (float)z1, (float)z0 };
    for (int k = 0; k < 4; k++)
        eq->v[k] = (ScreenVert){ cx[k], cy[k], zf[k] };
    double X0 = (double)E0x / SUBPIX, Y0 = (double)E0y / SUBPIX;
    double zc = z0 + ga * (x0 + 0.5 - X0) + gb * (y0 + 0.5 - Y0);
    ScreenPoly *poly = &eq->p;
    poly->face = id;
    poly->x0 = x0;
    poly->x1 = x1;
    poly->y0 = y0;
    poly->y1 = y1;
    poly->a = (float)ga;
    poly->b = (float)gb;
    poly->zc = (float)zc;
    /* a lower bound of every depth plane_at() can give inside: the
     * least corner depth (an affine function over a convex quad), less
     * the front end's margin for float rounding */
    double lo = z0 < z1 ? z0 : z1;
    double mag = fabs(zc) + fabs(ga) * (x1 - x0) + fabs(gb) * (y1 - y0);
    poly->zmin = (float)(lo - (fabs(lo) + mag) * (1.0 / (1 << 20)));
    return 1;
}

/* Append the quad as a polygon. Returns -1 on out of memory. */
static int emit_quad(ScreenPolys *sp, const EdgeQuad *eq)
{
    if (grow_array((void **)&sp->polys, &sp->cap_polys, sp->npolys + 2, sizeof *sp->polys) ||
        grow_array((void **)&sp->verts, &sp->cap_verts, sp->nverts + 4, sizeof *sp->verts))
        return -1;
    memcpy(&sp->verts[sp->nverts], eq->v, sizeof eq->v);
    ScreenPoly *poly = &sp->polys[sp->npolys++];
    *poly = eq->p;
    poly->first = sp->nverts;
    sp->nverts += 4;
    sp->edges_drawn++;
    return 0;
}

/* Can the quad be given as its samples? Each sample's depth becomes a
 * square's flat plane, which gives back exactly the float plane_at()
 * gave the quad there, and the samples' (depth, id) pairs are ordered
 * by point_key as hsr_wins orders them, when every depth is finite and
 * none is -0 (point_key puts -0 before +0, hsr_wins calls them equal;
 * a square's plane makes -0 into +0). plane_at() is a sum of zc and
 * two products: it is finite when the terms' magnitudes are far below
 * FLT_MAX, and it is -0 only when zc is (a float sum is -0 only when
 * both terms are). */
static int quad_samplable(const ScreenPoly *p)
{
    double mag = fabs((double)p->zc) + fabs((double)p->a) * (p->x1 - p->x0) + fabs((double)p->b) * (p->y1 - p->y0);
    return mag < 1e30 && !(p->zc == 0 && signbit(p->zc));
}

/* The least (depth, id) key per sample of the quads given as their
 * samples, w x h, all empty (UINT64_MAX) between frames; the box
 * written since (rows [y0, y1), columns [x0, x1)). */
typedef struct {
    uint64_t *key;
    int32_t   w;
    int32_t   x0, x1, y0, y1;
} SampleKeys;

/* Where edge a -> b crosses row j under raster.h's rule: 0 when it
 * does not count for the row, else *xi, the column edge_setup() would
 * give a walker started at row j (the same quotient, taken at once). */
static inline int edge_crossing(const ScreenVert *a, const ScreenVert *b, int32_t j, int32_t *xi)
{
    if (a->y == b->y)
        return 0;
    const ScreenVert *t = a->y < b->y ? a : b, *m = a->y < b->y ? b : a;
    if (j < sample_ceil(t->y) || j >= sample_ceil(m->y))
        return 0;
    int64_t dy = (int64_t)m->y - t->y, dx = (int64_t)m->x - t->x, den = 256 * dy, rem;
    int64_t yc = (int64_t)j * 256 + 128;
    *xi = (int32_t)floordiv64_rem((int64_t)t->x * dy + (yc - t->y) * dx - 128 * dy + den - 1, den, &rem);
    return 1;
}

/* Give quad eq's samples to the keys: those it covers by raster.h's
 * crossing rule, the rule every algorithm draws a polygon by (the
 * crossings of each row, paired into intervals), each with the depth
 * plane_at() gives there. The work is a row of the quad's box and a
 * sample it covers at a time. */
static void quad_samples(SampleKeys *sk, const EdgeQuad *eq)
{
    const ScreenPoly *p = &eq->p;
    for (int32_t j = p->y0; j < p->y1; j++) {
        int32_t xs[4];
        int m = 0;
        for (int k = 0; k < 4; k++)
            m += edge_crossing(&eq->v[k], &eq->v[(k + 1) & 3], j, &xs[m]);
        raster_sort_crossings(xs, m);
        float zrow = plane_row(p, j);
        uint64_t *row = sk->key + (size_t)j * (size_t)sk->w;
        for (int t = 0; t + 1 < m; t += 2) {
            int32_t i0 = xs[t] > p->x0 ? xs[t] : p->x0, i1 = xs[t + 1] < p->x1 ? xs[t + 1] : p->x1;
            for (int32_t i = i0; i < i1; i++) {
                uint64_t k = point_key(plane_at(p, zrow, i), p->face), old = row[i];
                row[i] = k < old ? k : old;
            }
        }
    }
    sk->x0 = p->x0 < sk->x0 ? p->x0 : sk->x0;
    sk->x1 = p->x1 > sk->x1 ? p->x1 : sk->x1;
    sk->y0 = p->y0 < sk->y0 ? p->y0 : sk->y0;
    sk->y1 = p->y1 > sk->y1 ? p->y1 : sk->y1;
}

/* The keys' samples as squares of one sample, each at its least
 * (depth, id); the keys left empty again, even when out of memory
 * (-1). */
static int sample_squares(ScreenPolys *sp, SampleKeys *sk)
{
    uint32_t kept = 0;
    for (int32_t j = sk->y0; j < sk->y1; j++)
        for (int32_t i = sk->x0; i < sk->x1; i++)
            kept += sk->key[(size_t)j * (size_t)sk->w + (size_t)i] != UINT64_MAX;
    int rc = grow_array((void **)&sp->polys, &sp->cap_polys, sp->npolys + kept + 1, sizeof *sp->polys) ||
             grow_array((void **)&sp->verts, &sp->cap_verts, sp->nverts + 4 * kept, sizeof *sp->verts);
    for (int32_t j = sk->y0; j < sk->y1; j++) {
        uint64_t *row = sk->key + (size_t)j * (size_t)sk->w;
        for (int32_t i = sk->x0; i < sk->x1; i++)
            if (row[i] != UINT64_MAX) {
                if (!rc)
                    emit_square(sp, i, j, 1, key_depth(row[i]), (int32_t)(uint32_t)row[i]);
                row[i] = UINT64_MAX;
            }
    }
    if (!rc)
        sp->edge_squares += kept;
    sk->x0 = sk->y0 = INT32_MAX;
    sk->x1 = sk->y1 = INT32_MIN;
    return rc ? -1 : 0;
}

/* The per-sample keys for n samples, all empty; made on first use (a
 * frame with no quad given as samples needs none). NULL when out of
 * memory: the quads are then kept whole, the same picture. */
static uint64_t *sample_keys(PrimWork *w, uint32_t n)
{
    if (w->cap_keys < n) {
        /* made empty once; sample_squares leaves it so */
        free(w->keys);
        w->cap_keys = 0;
        w->keys = malloc((size_t)n * sizeof *w->keys);
        if (!w->keys)
            return NULL;
        memset(w->keys, 0xff, (size_t)n * sizeof *w->keys);
        w->cap_keys = n;
    }
    return w->keys;
}

/* Every segment, wireframe edge and problem edge: a quad kept whole, or
 * given as its samples (see SMALL_QUAD, SAMPLES_PER_QUAD). */
/* The pieces of segment a b (mesh vertices v) that a section cut keeps,
 * into piece[]: 0, 1 (a b itself when nothing is removed) or 2. */
static int cut_segment(const SectionCut *c, const Scene *s, int oi, const uint32_t v[2], const float *a,
                       const float *b, float piece[2][2][3])
{
    memcpy(piece[0][0], a, sizeof piece[0][0]);
    memcpy(piece[0][1], b, sizeof piece[0][1]);
    const uint8_t *m = cut_mask(c, s, oi);
    if (!m)
        return 1;
    uint8_t all = section_all(c);
    if ((m[v[0]] | m[v[1]]) != all)
        return 1;                   /* some plane keeps both ends: all of it */
    if ((m[v[0]] & m[v[1]]) == all)
        return 0;                   /* both ends removed: all of it (the region is convex) */
    double lo, hi;
    if (!section_segment_cut(c->plane, c->nplanes, a, b, &lo, &hi))
        return 1;
    int n = 0;
    for (int e = 0; e < 2; e++) {
        double t0 = e ? hi : 0, t1 = e ? 1 : lo;
        if (!(t1 > t0))
            continue;
        for (int k = 0; k < 3; k++) {
            piece[n][0][k] = (float)(a[k] + t0 * ((double)b[k] - a[k]));
            piece[n][1][k] = (float)(a[k] + t1 * ((double)b[k] - a[k]));
        }
        n++;
    }
    return n;
}

static int edges_all(ScreenPolys *sp, const Scene *s, const PProj *pj, const Mat4 *view, const PrimStyle *st,
                     PrimWork *w)
{
    uint32_t nkeys = (uint32_t)sp->w * (uint32_t)sp->h, most = nkeys / SAMPLES_PER_QUAD;
    SampleKeys sk = { NULL, sp->w, INT32_MAX, INT32_MIN, INT32_MAX, INT32_MIN };
    int rc = 0;
    for (int kind = PRIM_SEG; kind <= PRIM_MARK && !rc; kind++) {
        if ((kind == PRIM_WIRE && !(st->wire && s->wire_built)) || (kind == PRIM_MARK && !st->marks))
            continue;
        double bias = kind == PRIM_SEG ? 0 : PRIM_WIRE_BIAS;
        for (int oi = 0; oi < s->nobjs && !rc; oi++) {
            const Object *o = &s->objs[oi];
            uint32_t n = kind == PRIM_SEG ? o->seg_count : kind == PRIM_WIRE ? o->wire_count : o->mark_count;
            if (!n)
                continue;
            int32_t id0 = kind == PRIM_SEG ? o->seg_id0 : kind == PRIM_WIRE ? o->wire_id0 : o->mark_id0;
            Mat4 mv = m4_mul(*view, object_matrix(o));
            const float *pos = o->mesh->pos;
            for (uint32_t k = 0; k < n && !rc; k++) {
                uint32_t v[2];
                scene_edge_verts(s, o, (PrimKind)kind, k, v);
                const float *a = &pos[3 * (size_t)v[0]], *b = &pos[3 * (size_t)v[1]];
                Vec3 p = m4_point(&mv, v3(a[0], a[1], a[2])), q = m4_point(&mv, v3(b[0], b[1], b[2]));
                sp->edges_in++;
                /* a section cut (section.h): the part on the removed side
                 * goes, what is left is one or two pieces */
                float piece[2][2][3];
                int npiece = cut_segment(sp->cut, s, oi, v, a, b, piece);
                for (int c = 0; c < npiece && !rc; c++) {
                    Vec3 pc = p, qc = q;
                    if (npiece != 1 || memcmp(piece[0][0], a, sizeof piece[0][0]) || memcmp(piece[0][1], b, sizeof piece[0][1])) {
                        pc = m4_point(&mv, v3(piece[c][0][0], piece[c][0][1], piece[c][0][2]));
                        qc = m4_point(&mv, v3(piece[c][1][0], piece[c][1][1], piece[c][1][2]));
                    }
                    EdgeQuad eq;
                    if (!edge_quad(sp, pj, pc, qc, st->line_width, bias, id0 + (int32_t)k, &eq))
                        continue;
                    const ScreenPoly *qp = &eq.p;
                    if (!st->all_prims && quad_samplable(qp) &&
                        ((qp->x1 - qp->x0) * (qp->y1 - qp->y0) <= SMALL_QUAD || sp->edges_drawn >= most) &&
                        (sk.key || (sk.key = sample_keys(w, nkeys)))) {
                        quad_samples(&sk, &eq);
                        sp->edges_sampled++;
                    } else {
                        rc = emit_quad(sp, &eq);
                    }
                }
            }
        }
    }
    if (sk.x0 < sk.x1 && sample_squares(sp, &sk))
        rc = -1;
    return rc;
}

int screen_prims(ScreenPolys *sp, const Scene *s, const PrimStyle *st, PrimWork **work)
{
    double t0 = now_ms();
    sp->prim_first = sp->npolys;
    sp->points_in = sp->points_drawn = sp->edges_in = sp->edges_drawn = sp->edges_sampled = sp->edge_squares = 0;
    sp->prim_ms = 0;
    if (s->nprims == 0 || sp->w <= 0 || sp->h <= 0)
        return 0;
    if (!*work) {
        *work = calloc(1, sizeof **work);
        if (!*work)
            return -1;
        long c = sysconf(_SC_NPROCESSORS_ONLN);
        (*work)->ncpus = c < 1 ? 1 : c > SCREEN_MAX_THREADS ? SCREEN_MAX_THREADS : (int)c;
    }
    PProj pj;
    pproj_from(&pj, sp);
    Mat4 view = camera_view(&s->cam);
    int size = st->point_size < 1 ? 1 : st->point_size > PRIM_SIZE_MAX ? PRIM_SIZE_MAX : st->point_size;
    /* squares on whole pixels when a pixel is several samples a side
     * (and the size is a whole number of pixels) */
    int align = st->pixel > 1 && size % st->pixel == 0 ? st->pixel : 1;
    PrimStyle style = *st;
    style.line_width = st->line_width < 1 ? 1 : st->line_width > PRIM_SIZE_MAX ? PRIM_SIZE_MAX : st->line_width;
    int rc = 0;
    if (s->npoints)
        rc = st->all_prims ? points_all(sp, s, &pj, &view, size, align)
                           : points_reduced(sp, s, &pj, &view, size, align, *work);
    if (!rc)
        rc = edges_all(sp, s, &pj, &view, &style, *work);
    if (grow_array((void **)&sp->polys, &sp->cap_polys, sp->npolys + 1, sizeof *sp->polys))
        rc = -1;
    else
        sp->polys[sp->npolys].first = sp->nverts;   /* the sentinel */
    sp->prim_ms = now_ms() - t0;
    return rc;
}
