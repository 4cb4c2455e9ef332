/* project.c: the one front end. Scene -> screen-space polygons.
 *
 * Per object, two passes:
 *  1. Vertices: each once to view space and, where in front of the near
 *     plane and inside the guard band, straight to snapped 24.8 screen
 *     coordinates (x, y pairs in one array, depths in another); a vertex
 *     that needs clipping gets x = y = VERT_OUT instead. A branch-free
 *     SIMD loop (SSE2, or AVX2 when the CPU has it) performs exactly the
 *     scalar IEEE operations in the scalar order, so every level gives
 *     the same bits.
 *  2. Polygons, a chunk at a time: the chunk's map entries start at -1;
 *     a chunk of triangles is first screened by a box test (SIMD with
 *     gathers under AVX2) that keeps only triangles whose sample box is
 *     non-empty and on screen, or that have a corner to clip (at a small
 *     size most of a big model covers no sample centre, and this is the
 *     whole cost of those triangles). The survivors, and every polygon of
 *     other chunks, take the fast path (copy the snapped corners) or the
 *     slow one (clip against the near plane and the guard band,
 *     Sutherland-Hodgman, then snap), then the sample box, back-face
 *     test and the depth plane from the snapped corners (finish_tri for
 *     triangles on the fast path, finish_poly otherwise: the same
 *     arithmetic).
 *
 * A big object is split over the caller and up to ScreenPolys.threads - 1
 * helpers of a persistent pool, in both passes; the parts of pass 2 write
 * into windows of the output arrays and move down in order, so the output
 * is the same as one thread's. Every scratch buffer belongs to the
 * ScreenPolys being filled (ScreenWork), so the front end keeps no state
 * of its own between calls.
 *
 * Clipping against the near plane and the guard band is the reentrant
 * polygon clipper of I. Sutherland and G. Hodgman, "Reentrant Polygon
 * Clipping", CACM 17(1), 1974.
 */

#define _DEFAULT_SOURCE
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "grow.h"
#include "pool.h"
#include "raster.h"
#include "screen.h"
#include "simd.h"

/* Vertices farther than this outside the image (pixels) are clipped, so
 * that fixed-point values stay below 2^23 and edge products fit int64. */
#define GUARD_PX 8192.0

/* A thread is worth waking for at least this many polygons of one
 * object (below it, the hand-over costs more than it saves). */
#define PART_MIN 8192

/* Vertices per task of pass 1 on several threads. */
#define VERT_CHUNK 65536

/* Polygons per chunk of pass 2: the survivors' list lives on the stack. */
#define CHUNK 2048

/* x and y of a vertex that is behind the near plane or outside the guard
 * band. No snapped coordinate comes near it (they stay within 2^23). */
#define VERT_OUT INT32_MIN
/* Its sample indices (both halves of its SampleIdx): none of the guard
 * band's, which lie within [-8192, 16384 + 8193]. */
#define IDX_OUT  INT16_MIN

typedef struct {
    double x, y, z;         /* view space (persp) or screen (guard clip): px, px, depth */
} CVert;

/* Per-vertex results of the object being projected, reused across frames:
 * the snapped point, and for the screening its sample indices
 * sample_ceil(x), sample_ceil(y) as two int16 in 32 bits (x low): the
 * first column and row at or past it. Since sample_ceil never decreases,
 * a triangle's sample box is [min, max) of its corners' indices, so the
 * screening reads 4 bytes a corner (the array is a quarter of the
 * points', and stays in cache better) and never the points. */
typedef struct {
    ScreenVert *sv;         /* snapped x, y, depth (x = y = VERT_OUT: clip it) */
    uint32_t   *idx;        /* sample indices (both IDX_OUT: clip it) */
    uint32_t    cap_sv, cap_idx;
} Scratch;

/* Clip polygon buffers, one set per worker. */
typedef struct {
    CVert   *buf[2];
    uint32_t cap;
} ClipBuf;

/* For each 8-bit mask, the numbers of its set bits in order, one a byte,
 * and how many there are: packs kept lanes to the front. */
typedef struct {
    uint64_t lanes[256];
    uint8_t  count[256];
} KeepLut;

struct ScreenWork {
    Scratch sc;
    KeepLut lut;
    ClipBuf clip[SCREEN_MAX_THREADS];   /* [0] the caller's, [i] helper i's */
    int     ncpus;                      /* cores online, read once */
    Pool   *pool;                       /* helpers, made on first need */
    int     pool_want;                  /* helpers it was made for */
};

static ScreenWork *work_get(ScreenPolys *sp)
{
    if (!sp->work) {
        sp->work = calloc(1, sizeof *sp->work);
        if (sp->work) {
            long c = sysconf(_SC_NPROCESSORS_ONLN);
            sp->work->ncpus = c < 1 ? 1 : c > SCREEN_MAX_THREADS ? SCREEN_MAX_THREADS : (int)c;
            KeepLut *l = &sp->work->lut;
            for (unsigned m = 0; m < 256; m++) {
                unsigned n = 0;
                for (unsigned b = 0; b < 8; b++)
                    if (m >> b & 1)
                        l->lanes[m] |= (uint64_t)b << (8 * n++);
                l->count[m] = (uint8_t)n;
            }
        }
    }
    return sp->work;
}

static void work_free(ScreenWork *w)
{
    if (!w)
        return;
    pool_free(w->pool);
    free(w->sc.sv);
    free(w->sc.idx);
    for (int i = 0; i < SCREEN_MAX_THREADS; i++) {
        free(w->clip[i].buf[0]);
        free(w->clip[i].buf[1]);
    }
    free(w);
}

/* Everything but the caller's settings goes. */
void screen_free(ScreenPolys *sp)
{
    int threads = sp->threads, simd = sp->simd;
    free(sp->verts);
    free(sp->polys);
    free(sp->map);
    free(sp->map_first);
    work_free(sp->work);
    memset(sp, 0, sizeof *sp);
    sp->threads = threads;
    sp->simd = simd;
}

/* ==== projection parameters ==== */

typedef struct {
    int     persp;
    double  cx, cy;         /* image centre, px */
    double  fx, fy;         /* px per unit (ortho) or focal px (persp) */
    double  eye;            /* persp: eye on +z view axis */
    double  n, f;           /* persp: near, far distances */
    double  dk;             /* persp: f / (f - n), the depth's scale */
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
        p->dk = p->f / (p->f - p->n);
    }
    p->fy = p->fx / aspect;
    p->gx0 = -GUARD_PX;
    p->gx1 = vp->w + GUARD_PX;
    p->gy0 = -GUARD_PX;
    p->gy1 = vp->h + GUARD_PX;
}

/* View space -> screen px and depth. Persp: the point must be in front.
 * The SIMD vertex loops below repeat these operations in this order. */
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
        out[2] = p->dk * (1 - p->n / ze);   /* NDC z in [0, 1] */
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

/* ==== pass 1: vertices ==== */

typedef struct {
    const float *pos;       /* the object's vertex vert_min */
    Mat4         mv;        /* object to view */
    const Proj  *pj;
    ScreenVert  *sv;        /* Scratch.sv, indexed from vert_min */
    uint32_t    *idx;
    uint32_t     nv;
    int          parts, simd;
} VertJob;

/* One vertex, the reference every SIMD loop matches bit for bit. */
static inline void vert_one(const VertJob *j, uint32_t i)
{
    const Proj *pj = j->pj;
    const float *p = j->pos + 3 * (size_t)i;
    Vec3 q = m4_point(&j->mv, v3(p[0], p[1], p[2]));
    int32_t x = VERT_OUT, y = VERT_OUT;
    float z = 0;
    if (!pj->persp || pj->eye - q.z >= pj->n) {
        double scr[3];
        proj_point(pj, q.x, q.y, q.z, scr);
        if (in_guard(pj, scr)) {
            x = snap(scr[0]);
            y = snap(scr[1]);
            z = (float)scr[2];
        }
    }
    j->sv[i].x = x;
    j->sv[i].y = y;
    j->sv[i].z = z;
    j->idx[i] = x == VERT_OUT ? (uint16_t)IDX_OUT * 0x10001u
                              : (uint16_t)sample_ceil(x) | (uint32_t)(uint16_t)sample_ceil(y) << 16;
}

#ifdef ZV_SSE2
/* x, y, z of four vertices from 12 consecutive floats. */
static inline void load4_xyz(const float *p, __m128 *x, __m128 *y, __m128 *z)
{
    __m128 a = _mm_loadu_ps(p), b = _mm_loadu_ps(p + 4), c = _mm_loadu_ps(p + 8);
    __m128 t = _mm_shuffle_ps(b, c, _MM_SHUFFLE(2, 1, 3, 2));      /* x2 y2 x3 y3 */
    __m128 u = _mm_shuffle_ps(a, b, _MM_SHUFFLE(1, 0, 2, 1));      /* y0 z0 y1 z1 */
    *x = _mm_shuffle_ps(a, t, _MM_SHUFFLE(2, 0, 3, 0));
    *y = _mm_shuffle_ps(u, t, _MM_SHUFFLE(3, 1, 2, 0));
    *z = _mm_shuffle_ps(u, c, _MM_SHUFFLE(3, 0, 3, 1));
}

/* m4_point's row r on four points: ((m0 x + m1 y) + m2 z) + m3 in float. */
static inline __m128 row4(const Mat4 *m, int r, __m128 x, __m128 y, __m128 z)
{
    __m128 s = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(m->m[r][0]), x), _mm_mul_ps(_mm_set1_ps(m->m[r][1]), y));
    s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(m->m[r][2]), z));
    return _mm_add_ps(s, _mm_set1_ps(m->m[r][3]));
}

/* snap() on two pairs of doubles: four int32. max/min return their
 * second operand for a NaN, which is snap()'s clamp of NaN to the low
 * end; the truncation is corrected down where it rounded up. */
static inline __m128i snap4(__m128d lo, __m128d hi)
{
    const __m128d k = _mm_set1_pd((double)SUBPIX), half = _mm_set1_pd(0.5);
    const __m128d tmin = _mm_set1_pd(-1073741824.0), tmax = _mm_set1_pd(1073741824.0);
    __m128d tl = _mm_add_pd(_mm_mul_pd(lo, k), half), th = _mm_add_pd(_mm_mul_pd(hi, k), half);
    tl = _mm_min_pd(_mm_max_pd(tl, tmin), tmax);
    th = _mm_min_pd(_mm_max_pd(th, tmin), tmax);
    __m128i il = _mm_cvttpd_epi32(tl), ih = _mm_cvttpd_epi32(th);
    __m128d dl = _mm_cmplt_pd(tl, _mm_cvtepi32_pd(il)), dh = _mm_cmplt_pd(th, _mm_cvtepi32_pd(ih));
    __m128i down = _mm_castps_si128(_mm_shuffle_ps(_mm_castpd_ps(dl), _mm_castpd_ps(dh), _MM_SHUFFLE(2, 0, 2, 0)));
    return _mm_add_epi32(_mm_unpacklo_epi64(il, ih), down);     /* adding -1 steps down */
}

/* Two 64-bit masks each of lo and hi as four 32-bit ones. */
static inline __m128i mask4(__m128d lo, __m128d hi)
{
    return _mm_castps_si128(_mm_shuffle_ps(_mm_castpd_ps(lo), _mm_castpd_ps(hi), _MM_SHUFFLE(2, 0, 2, 0)));
}

static inline __m128d guard2(const Proj *pj, __m128d sx, __m128d sy)
{
    __m128d in = _mm_and_pd(_mm_cmpge_pd(sx, _mm_set1_pd(pj->gx0)), _mm_cmple_pd(sx, _mm_set1_pd(pj->gx1)));
    return _mm_and_pd(in, _mm_and_pd(_mm_cmpge_pd(sy, _mm_set1_pd(pj->gy0)), _mm_cmple_pd(sy, _mm_set1_pd(pj->gy1))));
}

/* proj_point() and in_guard() on two view-space points (floats widened). */
static inline void proj2(const Proj *pj, __m128d x, __m128d y, __m128d z, __m128d *sx, __m128d *sy,
                         __m128d *sz, __m128d *ok)
{
    if (!pj->persp) {
        *sx = _mm_add_pd(_mm_set1_pd(pj->cx), _mm_mul_pd(_mm_set1_pd(pj->fx), x));
        *sy = _mm_sub_pd(_mm_set1_pd(pj->cy), _mm_mul_pd(_mm_set1_pd(pj->fy), y));
        *sz = _mm_sub_pd(_mm_set1_pd(pj->dbias), _mm_mul_pd(_mm_set1_pd(pj->dscale), z));
        *ok = guard2(pj, *sx, *sy);
    } else {
        __m128d ze = _mm_sub_pd(_mm_set1_pd(pj->eye), z);
        *sx = _mm_add_pd(_mm_set1_pd(pj->cx), _mm_div_pd(_mm_mul_pd(_mm_set1_pd(pj->fx), x), ze));
        *sy = _mm_sub_pd(_mm_set1_pd(pj->cy), _mm_div_pd(_mm_mul_pd(_mm_set1_pd(pj->fy), y), ze));
        *sz = _mm_mul_pd(_mm_set1_pd(pj->dk), _mm_sub_pd(_mm_set1_pd(1.0), _mm_div_pd(_mm_set1_pd(pj->n), ze)));
        *ok = _mm_and_pd(_mm_cmpge_pd(ze, _mm_set1_pd(pj->n)), guard2(pj, *sx, *sy));
    }
}

/* Store four vertices: the points (x, y, z) with four 16-byte stores
 * 12 bytes apart, each spilling 4 bytes into the next point, which the
 * next store (or, past the fourth, the caller's next group or its tail:
 * the loops stop one vertex short of the range's end) writes again; then
 * the sample indices. okm: all ones where the vertex is in. */
static inline void store4(const VertJob *j, uint32_t i, __m128i ix, __m128i iy, __m128 z, __m128i okm)
{
    __m128 lo = _mm_castsi128_ps(_mm_unpacklo_epi32(ix, iy)), hi = _mm_castsi128_ps(_mm_unpackhi_epi32(ix, iy));
    float *d = (float *)(j->sv + i);
    _mm_storeu_ps(d, _mm_shuffle_ps(lo, z, _MM_SHUFFLE(0, 0, 1, 0)));
    _mm_storeu_ps(d + 3, _mm_shuffle_ps(lo, z, _MM_SHUFFLE(1, 1, 3, 2)));
    _mm_storeu_ps(d + 6, _mm_shuffle_ps(hi, z, _MM_SHUFFLE(2, 2, 1, 0)));
    _mm_storeu_ps(d + 9, _mm_shuffle_ps(hi, z, _MM_SHUFFLE(3, 3, 3, 2)));
    const __m128i k127 = _mm_set1_epi32(127), low16 = _mm_set1_epi32(0xffff);
    __m128i cx = _mm_srai_epi32(_mm_add_epi32(ix, k127), SUBPIX_BITS);
    __m128i cy = _mm_srai_epi32(_mm_add_epi32(iy, k127), SUBPIX_BITS);
    __m128i c = _mm_or_si128(_mm_and_si128(cx, low16), _mm_slli_epi32(cy, 16));
    c = _mm_or_si128(_mm_and_si128(okm, c), _mm_andnot_si128(okm, _mm_set1_epi32((int32_t)0x80008000u)));
    _mm_storeu_si128((__m128i *)(j->idx + i), c);
}

static void verts_sse2(const VertJob *j, uint32_t a, uint32_t b)
{
    const Mat4 *m = &j->mv;
    const __m128i out = _mm_set1_epi32(VERT_OUT);
    uint32_t i = a;
    for (; i + 4 < b; i += 4) {
        __m128 x, y, z;
        load4_xyz(j->pos + 3 * (size_t)i, &x, &y, &z);
        __m128 qx = row4(m, 0, x, y, z), qy = row4(m, 1, x, y, z), qz = row4(m, 2, x, y, z);
        __m128d sx[2], sy[2], sz[2], ok[2];
        proj2(j->pj, _mm_cvtps_pd(qx), _mm_cvtps_pd(qy), _mm_cvtps_pd(qz), &sx[0], &sy[0], &sz[0], &ok[0]);
        proj2(j->pj, _mm_cvtps_pd(_mm_movehl_ps(qx, qx)), _mm_cvtps_pd(_mm_movehl_ps(qy, qy)),
              _mm_cvtps_pd(_mm_movehl_ps(qz, qz)), &sx[1], &sy[1], &sz[1], &ok[1]);
        __m128i okm = mask4(ok[0], ok[1]);
        __m128i ix = snap4(sx[0], sx[1]), iy = snap4(sy[0], sy[1]);
        ix = _mm_or_si128(_mm_and_si128(okm, ix), _mm_andnot_si128(okm, out));
        iy = _mm_or_si128(_mm_and_si128(okm, iy), _mm_andnot_si128(okm, out));
        store4(j, i, ix, iy, _mm_movelh_ps(_mm_cvtpd_ps(sz[0]), _mm_cvtpd_ps(sz[1])), okm);
    }
    for (; i < b; i++)
        vert_one(j, i);
}
#endif

#ifdef ZV_AVX2
/* The AVX2 loop: the same operations eight floats and four doubles wide;
 * floor by rounding (exact) instead of the truncation fix-up. Every
 * constant is broadcast once, before the loop: the vector stores may
 * alias anything, so the compiler would otherwise load them again on
 * every step. */
typedef struct {
    __m256  m[3][4];
    __m256d cx, cy, fx, fy, dbias, dscale, eye, n, dk, one, gx0, gx1, gy0, gy1, sub, half, tmin, tmax;
} Avx2Proj;

ZV_AVX2_FN static inline __m128i snap4_avx2(const Avx2Proj *c, __m256d v)
{
    __m256d t = _mm256_add_pd(_mm256_mul_pd(v, c->sub), c->half);
    t = _mm256_min_pd(_mm256_max_pd(t, c->tmin), c->tmax);
    return _mm256_cvttpd_epi32(_mm256_round_pd(t, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
}

/* proj_point(), in_guard() and snap() on four points, stored with store4. */
ZV_AVX2_FN static inline void proj4_avx2(const VertJob *j, const Avx2Proj *c, int persp, uint32_t at, __m128 hx,
                                      __m128 hy, __m128 hz)
{
    __m256d x = _mm256_cvtps_pd(hx), y = _mm256_cvtps_pd(hy), z = _mm256_cvtps_pd(hz);
    __m256d sx, sy, sz, ok;
    if (!persp) {
        sx = _mm256_add_pd(c->cx, _mm256_mul_pd(c->fx, x));
        sy = _mm256_sub_pd(c->cy, _mm256_mul_pd(c->fy, y));
        sz = _mm256_sub_pd(c->dbias, _mm256_mul_pd(c->dscale, z));
        ok = _mm256_and_pd(_mm256_cmp_pd(sx, c->gx0, _CMP_GE_OQ), _mm256_cmp_pd(sx, c->gx1, _CMP_LE_OQ));
    } else {
        __m256d ze = _mm256_sub_pd(c->eye, z);
        sx = _mm256_add_pd(c->cx, _mm256_div_pd(_mm256_mul_pd(c->fx, x), ze));
        sy = _mm256_sub_pd(c->cy, _mm256_div_pd(_mm256_mul_pd(c->fy, y), ze));
        sz = _mm256_mul_pd(c->dk, _mm256_sub_pd(c->one, _mm256_div_pd(c->n, ze)));
        ok = _mm256_and_pd(_mm256_cmp_pd(ze, c->n, _CMP_GE_OQ),
                           _mm256_and_pd(_mm256_cmp_pd(sx, c->gx0, _CMP_GE_OQ), _mm256_cmp_pd(sx, c->gx1, _CMP_LE_OQ)));
    }
    ok = _mm256_and_pd(ok, _mm256_and_pd(_mm256_cmp_pd(sy, c->gy0, _CMP_GE_OQ), _mm256_cmp_pd(sy, c->gy1, _CMP_LE_OQ)));
    /* the four 64-bit masks as four 32-bit ones */
    __m128i okm = _mm256_castsi256_si128(
        _mm256_permutevar8x32_epi32(_mm256_castpd_si256(ok), _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7)));
    const __m128i out = _mm_set1_epi32(VERT_OUT);
    __m128i ix = _mm_blendv_epi8(out, snap4_avx2(c, sx), okm);
    __m128i iy = _mm_blendv_epi8(out, snap4_avx2(c, sy), okm);
    store4(j, at, ix, iy, _mm256_cvtpd_ps(sz), okm);
}

ZV_AVX2_FN static inline void verts_avx2_loop(const VertJob *j, const Avx2Proj *c, int persp, uint32_t a, uint32_t b)
{
    for (uint32_t i = a; i < b; i += 8) {
        /* vertices 0-3 in the low lanes, 4-7 in the high ones: the
         * in-lane shuffles of load4_xyz then work on both at once */
        const float *p = j->pos + 3 * (size_t)i;
        __m256 va = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p)), _mm_loadu_ps(p + 12), 1);
        __m256 vb = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4)), _mm_loadu_ps(p + 16), 1);
        __m256 vc = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 8)), _mm_loadu_ps(p + 20), 1);
        __m256 t = _mm256_shuffle_ps(vb, vc, _MM_SHUFFLE(2, 1, 3, 2));
        __m256 u = _mm256_shuffle_ps(va, vb, _MM_SHUFFLE(1, 0, 2, 1));
        __m256 x = _mm256_shuffle_ps(va, t, _MM_SHUFFLE(2, 0, 3, 0));
        __m256 y = _mm256_shuffle_ps(u, t, _MM_SHUFFLE(3, 1, 2, 0));
        __m256 z = _mm256_shuffle_ps(u, vc, _MM_SHUFFLE(3, 0, 3, 1));
        __m256 q[3];
        for (int r = 0; r < 3; r++) {
            /* m4_point's row r: ((m0 x + m1 y) + m2 z) + m3 in float */
            __m256 s = _mm256_add_ps(_mm256_mul_ps(c->m[r][0], x), _mm256_mul_ps(c->m[r][1], y));
            s = _mm256_add_ps(s, _mm256_mul_ps(c->m[r][2], z));
            q[r] = _mm256_add_ps(s, c->m[r][3]);
        }
        proj4_avx2(j, c, persp, i, _mm256_castps256_ps128(q[0]), _mm256_castps256_ps128(q[1]),
                   _mm256_castps256_ps128(q[2]));
        proj4_avx2(j, c, persp, i + 4, _mm256_extractf128_ps(q[0], 1), _mm256_extractf128_ps(q[1], 1),
                   _mm256_extractf128_ps(q[2], 1));
    }
}

ZV_AVX2_FN static void verts_avx2(const VertJob *j, uint32_t a, uint32_t b)
{
    const Proj *pj = j->pj;
    Avx2Proj c;
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 4; k++)
            c.m[r][k] = _mm256_set1_ps(j->mv.m[r][k]);
    c.cx = _mm256_set1_pd(pj->cx);
    c.cy = _mm256_set1_pd(pj->cy);
    c.fx = _mm256_set1_pd(pj->fx);
    c.fy = _mm256_set1_pd(pj->fy);
    c.dbias = _mm256_set1_pd(pj->dbias);
    c.dscale = _mm256_set1_pd(pj->dscale);
    c.eye = _mm256_set1_pd(pj->eye);
    c.n = _mm256_set1_pd(pj->n);
    c.dk = _mm256_set1_pd(pj->dk);
    c.one = _mm256_set1_pd(1.0);
    c.gx0 = _mm256_set1_pd(pj->gx0);
    c.gx1 = _mm256_set1_pd(pj->gx1);
    c.gy0 = _mm256_set1_pd(pj->gy0);
    c.gy1 = _mm256_set1_pd(pj->gy1);
    c.sub = _mm256_set1_pd((double)SUBPIX);
    c.half = _mm256_set1_pd(0.5);
    c.tmin = _mm256_set1_pd(-1073741824.0);
    c.tmax = _mm256_set1_pd(1073741824.0);
    /* whole groups of eight, stopping short of b (store4's spill) */
    uint32_t e = b - a > 8 ? a + (b - a - 1) / 8 * 8 : a;
    if (pj->persp)
        verts_avx2_loop(j, &c, 1, a, e);
    else
        verts_avx2_loop(j, &c, 0, a, e);
    for (uint32_t i = e; i < b; i++)
        vert_one(j, i);
}
#endif

static void verts_range(const VertJob *j, uint32_t a, uint32_t b)
{
#ifdef ZV_AVX2
    if (j->simd >= SIMD_AVX2) {
        verts_avx2(j, a, b);
        return;
    }
#endif
#ifdef ZV_SSE2
    if (j->simd >= SIMD_SSE2) {
        verts_sse2(j, a, b);
        return;
    }
#endif
    for (uint32_t i = a; i < b; i++)
        vert_one(j, i);
}

static void verts_part(void *arg, int part, int worker)
{
    const VertJob *j = arg;
    (void)worker;
    uint32_t a = (uint32_t)((uint64_t)j->nv * (uint32_t)part / (uint32_t)j->parts);
    uint32_t b = (uint32_t)((uint64_t)j->nv * (uint32_t)(part + 1) / (uint32_t)j->parts);
    verts_range(j, a, b);
}

/* ==== pass 2, screening: which triangles of a chunk can cover a sample ==== */

static inline int32_t min3(int32_t a, int32_t b, int32_t c)
{
    int32_t m = a < b ? a : b;
    return c < m ? c : m;
}

static inline int32_t max3(int32_t a, int32_t b, int32_t c)
{
    int32_t m = a > b ? a : b;
    return c > m ? c : m;
}

/* The triangle of corners c[0..2] (vertex indices; their sample indices
 * are idx[c - vmin]) is kept when it has a corner to clip, or when its
 * sample box [min, max) is non-empty and meets the screen: exactly the
 * triangles whose sample box (finish_tri) is not empty. Bitwise
 * operators, so the compiler needs no branch. */
static inline uint32_t tri_keeps(const uint32_t *c, const uint32_t *idx, uint32_t vmin, int32_t w, int32_t h)
{
    uint32_t p = idx[c[0] - vmin], q = idx[c[1] - vmin], r = idx[c[2] - vmin];
    int32_t px = (int16_t)p, qx = (int16_t)q, rx = (int16_t)r;
    int32_t py = (int16_t)(p >> 16), qy = (int16_t)(q >> 16), ry = (int16_t)(r >> 16);
    int32_t x0 = min3(px, qx, rx), x1 = max3(px, qx, rx), y0 = min3(py, qy, ry), y1 = max3(py, qy, ry);
    return (uint32_t)(x0 == IDX_OUT) | ((uint32_t)(x0 < x1) & (uint32_t)(y0 < y1) & (uint32_t)(x1 > 0) &
                                         (uint32_t)(y1 > 0) & (uint32_t)(x0 < w) & (uint32_t)(y0 < h));
}

/* Triangles i of [a, n) with corners corner[3 i ..]: the kept ones' i
 * appended to keep[] after its first nk; returns the new count. */
static uint32_t screen_tris_c(const uint32_t *corner, uint32_t a, uint32_t n, const uint32_t *idx, uint32_t vmin,
                              int32_t w, int32_t h, uint32_t *keep, uint32_t nk)
{
    for (uint32_t i = a; i < n; i++) {
        keep[nk] = i;
        nk += tri_keeps(corner + 3 * (size_t)i, idx, vmin, w, h);
    }
    return nk;
}

#ifdef ZV_AVX2
/* Eight triangles a step: their 24 corner indices deinterleaved with the
 * in-lane shuffles of load4_xyz (triangles 0-3 in the low lanes, 4-7 in
 * the high ones), each corner's sample indices fetched by one gather, and
 * tri_keeps() on the x and y halves side by side (16-bit lanes). */
ZV_AVX2_FN static uint32_t screen_tris_avx2(const uint32_t *corner, uint32_t n, const uint32_t *idx, uint32_t vmin,
                                         int32_t w, int32_t h, uint32_t *keep, const KeepLut *lut)
{
    const __m256i vm = _mm256_set1_epi32((int32_t)vmin), zero = _mm256_setzero_si256();
    const __m256i ones = _mm256_set1_epi32(-1), out = _mm256_set1_epi32((int32_t)0x80008000u);
    const __m256i lim = _mm256_set1_epi32((int32_t)((uint32_t)h << 16 | (uint32_t)w));
    const int *base = (const int *)idx;
    uint32_t nk = 0, i = 0;
    for (; i + 8 <= n; i += 8) {
        const float *c = (const float *)(corner + 3 * (size_t)i);  /* indices as float bit patterns, untouched */
        __m256 va = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(c)), _mm_loadu_ps(c + 12), 1);
        __m256 vb = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(c + 4)), _mm_loadu_ps(c + 16), 1);
        __m256 vc = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(c + 8)), _mm_loadu_ps(c + 20), 1);
        __m256 t = _mm256_shuffle_ps(vb, vc, _MM_SHUFFLE(2, 1, 3, 2));
        __m256 u = _mm256_shuffle_ps(va, vb, _MM_SHUFFLE(1, 0, 2, 1));
        __m256i c0 = _mm256_sub_epi32(_mm256_castps_si256(_mm256_shuffle_ps(va, t, _MM_SHUFFLE(2, 0, 3, 0))), vm);
        __m256i c1 = _mm256_sub_epi32(_mm256_castps_si256(_mm256_shuffle_ps(u, t, _MM_SHUFFLE(3, 1, 2, 0))), vm);
        __m256i c2 = _mm256_sub_epi32(_mm256_castps_si256(_mm256_shuffle_ps(u, vc, _MM_SHUFFLE(3, 0, 3, 1))), vm);
        __m256i g0 = _mm256_i32gather_epi32(base, c0, 4);
        __m256i g1 = _mm256_i32gather_epi32(base, c1, 4);
        __m256i g2 = _mm256_i32gather_epi32(base, c2, 4);
        __m256i mn = _mm256_min_epi16(_mm256_min_epi16(g0, g1), g2);
        __m256i mx = _mm256_max_epi16(_mm256_max_epi16(g0, g1), g2);
        __m256i ok = _mm256_and_si256(_mm256_cmpgt_epi16(mx, mn),
                                      _mm256_and_si256(_mm256_cmpgt_epi16(mx, zero), _mm256_cmpgt_epi16(lim, mn)));
        ok = _mm256_or_si256(_mm256_cmpeq_epi32(ok, ones), _mm256_cmpeq_epi32(mn, out));
        unsigned m = (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(ok));
        /* append the kept ones without a branch (most steps keep none at
         * small sizes, most of them at large ones): their lane numbers
         * packed to the front by a table, all eight stored, the count
         * advanced by the kept ones */
        __m256i lanes = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128((long long)lut->lanes[m]));
        _mm256_storeu_si256((__m256i *)(keep + nk), _mm256_add_epi32(_mm256_set1_epi32((int32_t)i), lanes));
        nk += lut->count[m];
    }
    return screen_tris_c(corner, i, n, idx, vmin, w, h, keep, nk);
}
#endif

#ifdef ZV_AVX2
/* One edge a -> b of eight triangles at the sample, all relative to it:
 * e = dx (0 - ay) - dy (0 - ax), covered where e > 0, or e == 0 on a top
 * or left edge (dy < 0, or dy == 0 and dx > 0): edge_covers(). */
ZV_AVX2_FN static inline __m256i edge8(__m256i ax, __m256i ay, __m256i bx, __m256i by)
{
    const __m256i zero = _mm256_setzero_si256();
    __m256i dx = _mm256_sub_epi32(bx, ax), dy = _mm256_sub_epi32(by, ay);
    __m256i e = _mm256_sub_epi32(_mm256_mullo_epi32(dy, ax), _mm256_mullo_epi32(dx, ay));
    __m256i tl = _mm256_or_si256(_mm256_cmpgt_epi32(zero, dy),
                                 _mm256_and_si256(_mm256_cmpeq_epi32(dy, zero), _mm256_cmpgt_epi32(dx, zero)));
    return _mm256_or_si256(_mm256_cmpgt_epi32(e, zero), _mm256_and_si256(_mm256_cmpeq_epi32(e, zero), tl));
}

/* Second screening of the kept triangles keep[0 .. nk) (corners at
 * corner[3 keep[i] ..], points sv[corner - vmin]), eight at a time: a
 * triangle whose sample box is a single sample has its corners within
 * 256 of that sample's centre, so relative to it finish_tri()'s tests
 * fit 32-bit lanes exactly: back-facing when culling (culled_back, as
 * finish_tri counts it), else missing its sample (culled_empty) drops
 * it. The others, and triangles with a corner to clip or a bigger box,
 * stay for finish_tri. Returns the new count; keep[] is compacted in
 * place (a store never passes the entries still to be read). */
ZV_AVX2_FN static uint32_t sift_tiny_avx2(const uint32_t *corner, const ScreenVert *sv, uint32_t vmin, int cull,
                                       uint32_t *keep, uint32_t nk, const KeepLut *lut, uint32_t *empty,
                                       uint32_t *back)
{
    const __m256i vm = _mm256_set1_epi32((int32_t)vmin), one = _mm256_set1_epi32(1);
    const __m256i k127 = _mm256_set1_epi32(127), k128 = _mm256_set1_epi32(128);
    const __m256i out = _mm256_set1_epi32(VERT_OUT), zero = _mm256_setzero_si256();
    const __m256i vcull = _mm256_set1_epi32(cull ? -1 : 0);
    const int *cb = (const int *)corner, *pb = (const int *)sv;
    uint32_t n = 0, i = 0;
    for (; i + 8 <= nk; i += 8) {
        __m256i t = _mm256_loadu_si256((const __m256i *)(keep + i));
        __m256i c3 = _mm256_add_epi32(_mm256_add_epi32(t, t), t);
        __m256i x[3], y[3];
        for (int k = 0; k < 3; k++) {
            __m256i v = _mm256_sub_epi32(_mm256_i32gather_epi32(cb + k, c3, 4), vm);
            __m256i v3 = _mm256_add_epi32(_mm256_add_epi32(v, v), v);      /* 3 ints a point */
            x[k] = _mm256_i32gather_epi32(pb, v3, 4);
            y[k] = _mm256_i32gather_epi32(pb + 1, v3, 4);
        }
        __m256i xmn = _mm256_min_epi32(_mm256_min_epi32(x[0], x[1]), x[2]);
        __m256i xmx = _mm256_max_epi32(_mm256_max_epi32(x[0], x[1]), x[2]);
        __m256i ymn = _mm256_min_epi32(_mm256_min_epi32(y[0], y[1]), y[2]);
        __m256i ymx = _mm256_max_epi32(_mm256_max_epi32(y[0], y[1]), y[2]);
        __m256i sx0 = _mm256_srai_epi32(_mm256_add_epi32(xmn, k127), SUBPIX_BITS);
        __m256i sy0 = _mm256_srai_epi32(_mm256_add_epi32(ymn, k127), SUBPIX_BITS);
        __m256i sx1 = _mm256_srai_epi32(_mm256_add_epi32(xmx, k127), SUBPIX_BITS);
        __m256i sy1 = _mm256_srai_epi32(_mm256_add_epi32(ymx, k127), SUBPIX_BITS);
        /* one sample, no corner to clip (the first screening put the
         * box on screen, so clamping leaves it as it is) */
        __m256i tiny = _mm256_andnot_si256(_mm256_cmpeq_epi32(xmn, out),
                                           _mm256_and_si256(_mm256_cmpeq_epi32(sx1, _mm256_add_epi32(sx0, one)),
                                                            _mm256_cmpeq_epi32(sy1, _mm256_add_epi32(sy0, one))));
        __m256i px = _mm256_add_epi32(_mm256_slli_epi32(sx0, SUBPIX_BITS), k128);
        __m256i py = _mm256_add_epi32(_mm256_slli_epi32(sy0, SUBPIX_BITS), k128);
        __m256i ax = _mm256_sub_epi32(x[0], px), ay = _mm256_sub_epi32(y[0], py);
        __m256i bx = _mm256_sub_epi32(x[1], px), by = _mm256_sub_epi32(y[1], py);
        __m256i cx = _mm256_sub_epi32(x[2], px), cy = _mm256_sub_epi32(y[2], py);
        /* twice the signed area (finish_tri's area2; translation moves it not) */
        __m256i area2 = _mm256_sub_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(bx, ax), _mm256_sub_epi32(cy, ay)),
                                         _mm256_mullo_epi32(_mm256_sub_epi32(by, ay), _mm256_sub_epi32(cx, ax)));
        __m256i faces_away = _mm256_and_si256(vcull, _mm256_cmpgt_epi32(_mm256_add_epi32(area2, one), zero));
        __m256i neg = _mm256_cmpgt_epi32(zero, area2);      /* walk b and c the other way round */
        __m256i bx2 = _mm256_blendv_epi8(bx, cx, neg), by2 = _mm256_blendv_epi8(by, cy, neg);
        __m256i cx2 = _mm256_blendv_epi8(cx, bx, neg), cy2 = _mm256_blendv_epi8(cy, by, neg);
        __m256i hit = _mm256_andnot_si256(_mm256_cmpeq_epi32(area2, zero), edge8(ax, ay, bx2, by2));
        hit = _mm256_and_si256(hit, _mm256_and_si256(edge8(bx2, by2, cx2, cy2), edge8(cx2, cy2, ax, ay)));
        __m256i gone_back = _mm256_and_si256(tiny, faces_away);
        __m256i gone_empty = _mm256_andnot_si256(faces_away, _mm256_andnot_si256(hit, tiny));
        unsigned mb = (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(gone_back));
        unsigned me = (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(gone_empty));
        unsigned m = ~(mb | me) & 0xff;
        *back += lut->count[mb];
        *empty += lut->count[me];
        __m256i lanes = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128((long long)lut->lanes[m]));
        _mm256_storeu_si256((__m256i *)(keep + n), _mm256_permutevar8x32_epi32(t, lanes));
        n += lut->count[m];
    }
    for (; i < nk; i++)
        keep[n++] = keep[i];
    return n;
}
#endif

/* keep[] needs room for n + 8 entries (the AVX2 loop stores eight at a time). */
static uint32_t screen_tris(int simd, const uint32_t *corner, uint32_t n, const uint32_t *idx, uint32_t vmin,
                            int32_t w, int32_t h, uint32_t *keep, const KeepLut *lut)
{
#ifdef ZV_AVX2
    if (simd >= SIMD_AVX2)
        return screen_tris_avx2(corner, n, idx, vmin, w, h, keep, lut);
#endif
    (void)simd;
    (void)lut;
    return screen_tris_c(corner, 0, n, idx, vmin, w, h, keep, 0);
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

/* Project the polygons [k0, k1) of object o (its vertices in vs) into
 * j->out, and record where each went in map (an index into j->out). */
typedef struct {
    ScreenPolys   *out;
    const Scene   *s;
    const Object  *o;
    const Proj    *pj;
    const Mat4    *mv;          /* object to view, for the slow path */
    const Scratch *vs;
    ClipBuf       *cb;
    uint32_t       k0, k1, inst0;
    int32_t       *map;
    int            fixed;       /* out's arrays are a window of another's: never grow */
    int            simd;
    int            rc;          /* 0, -1 out of memory, -2 window full */
    const KeepLut *lut;
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

/* Clip polygon k (corners c0 .. c1) against the near plane in view space
 * (recomputed from the mesh exactly as pass 1 computed it), then the
 * guard band in screen space (depth is affine there), and append its
 * snapped outline. Returns 0, 1 to skip it, or vert_room's error. */
static int clip_slow(RangeJob *j, uint32_t c0, uint32_t c1)
{
    ScreenPolys *sp = j->out;
    const Scene *s = j->s;
    const Object *o = j->o;
    const Proj *pj = j->pj;
    ClipBuf *cb = j->cb;
    uint32_t nc = c1 - c0;
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
    CVert *in = cb->buf[0], *out = cb->buf[1];
    uint32_t n = 0;
    const float *pos = o->mesh->pos;
    for (uint32_t c = c0; c < c1; c++) {
        const float *p = pos + 3 * (size_t)s->poly_corner[c];
        Vec3 q = m4_point(j->mv, v3(p[0], p[1], p[2]));
        in[n].x = q.x; in[n].y = q.y; in[n].z = q.z;
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

/* Record kept polygon sp->polys[npolys - 1]: its face id (read only now:
 * most polygons screened in are dropped after all) and where it went. */
static inline void kept_poly(RangeJob *j, uint32_t k, uint32_t inst)
{
    ScreenPolys *sp = j->out;
    sp->polys[sp->npolys - 1].face = j->o->face_base + (int32_t)j->s->poly_lface[k];
    j->map[inst] = (int32_t)(sp->npolys - 1);
}

/* Polygon k of the scene (corners c0 .. c1, instance inst) through the
 * fast or slow path into j->out. Returns 0 or an error of vert_room or
 * clip_slow. */
static int emit_poly(RangeJob *j, uint32_t k, uint32_t c0, uint32_t c1, uint32_t inst)
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
        rv = clip_slow(j, c0, c1);
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

#ifdef ZV_AVX2
/* Four triangles' finish_tri(), lane by lane the same operations: the
 * sample box in 32-bit lanes, twice the signed area and, for a box of at
 * most four samples, tri_hits_box()'s edge functions in 64-bit ones
 * (exact products), the plane in double. A lane's state: kept (its box,
 * plane and zmin filled in), or dropped as empty or as facing away. */
enum { FIN_KEPT, FIN_EMPTY, FIN_BACK };

/* edge_covers() in four 64-bit lanes: e = dx (py - ay) - dy (px - ax) > 0,
 * or == 0 on a top or left edge (tl). Every factor fits 32 bits. */
ZV_AVX2_FN static inline __m256i edge4_covers(__m256i ax, __m256i ay, __m256i dx, __m256i dy, __m256i tl, __m256i px,
                                           __m256i py)
{
    __m256i e = _mm256_sub_epi64(_mm256_mul_epi32(dx, _mm256_sub_epi64(py, ay)),
                                 _mm256_mul_epi32(dy, _mm256_sub_epi64(px, ax)));
    const __m256i zero = _mm256_setzero_si256();
    return _mm256_or_si256(_mm256_cmpgt_epi64(e, zero), _mm256_and_si256(_mm256_cmpeq_epi64(e, zero), tl));
}

typedef struct {
    int32_t x0[4], x1[4], y0[4], y1[4];
    float   a[4], b[4], zc[4], zmin[4];
    int     state[4];
} Finish4;

ZV_AVX2_FN static void finish_tris4(const ScreenPolys *sp, const ScreenVert *const v[4][3], Finish4 *f)
{
    __m128i X[3], Y[3];
    __m128 Z[3];
    for (int k = 0; k < 3; k++) {
        X[k] = _mm_setr_epi32(v[0][k]->x, v[1][k]->x, v[2][k]->x, v[3][k]->x);
        Y[k] = _mm_setr_epi32(v[0][k]->y, v[1][k]->y, v[2][k]->y, v[3][k]->y);
        Z[k] = _mm_setr_ps(v[0][k]->z, v[1][k]->z, v[2][k]->z, v[3][k]->z);
    }
    /* sample_box() */
    const __m128i k127 = _mm_set1_epi32(127), zero = _mm_setzero_si128();
    __m128i x0 = _mm_srai_epi32(_mm_add_epi32(_mm_min_epi32(_mm_min_epi32(X[0], X[1]), X[2]), k127), SUBPIX_BITS);
    __m128i x1 = _mm_srai_epi32(_mm_add_epi32(_mm_max_epi32(_mm_max_epi32(X[0], X[1]), X[2]), k127), SUBPIX_BITS);
    __m128i y0 = _mm_srai_epi32(_mm_add_epi32(_mm_min_epi32(_mm_min_epi32(Y[0], Y[1]), Y[2]), k127), SUBPIX_BITS);
    __m128i y1 = _mm_srai_epi32(_mm_add_epi32(_mm_max_epi32(_mm_max_epi32(Y[0], Y[1]), Y[2]), k127), SUBPIX_BITS);
    x0 = _mm_max_epi32(x0, zero);
    y0 = _mm_max_epi32(y0, zero);
    x1 = _mm_min_epi32(x1, _mm_set1_epi32(sp->w));
    y1 = _mm_min_epi32(y1, _mm_set1_epi32(sp->h));
    __m128i bw = _mm_sub_epi32(x1, x0), bh = _mm_sub_epi32(y1, y0);
    __m128i empty = _mm_or_si128(_mm_cmpgt_epi32(_mm_set1_epi32(1), bw), _mm_cmpgt_epi32(_mm_set1_epi32(1), bh));
    /* twice the signed area: (x0 y1 - x1 y0) + (x1 y2 - x2 y1) + (x2 y0 - x0 y2) */
    __m256i xl[3], yl[3];
    for (int k = 0; k < 3; k++) {
        xl[k] = _mm256_cvtepi32_epi64(X[k]);
        yl[k] = _mm256_cvtepi32_epi64(Y[k]);
    }
    __m256i area2 = _mm256_setzero_si256();
    for (int k = 0; k < 3; k++) {
        int m = k == 2 ? 0 : k + 1;
        area2 = _mm256_add_epi64(area2, _mm256_sub_epi64(_mm256_mul_epi32(xl[k], yl[m]), _mm256_mul_epi32(xl[m], yl[k])));
    }
    __m256i back = _mm256_cmpgt_epi64(area2, _mm256_set1_epi64x(-1));     /* area2 >= 0 */
    __m128i nsamp = _mm_mullo_epi32(bw, bh);
    __m128i tiny = _mm_cmpgt_epi32(_mm_set1_epi32(5), nsamp);
    int mt = _mm_movemask_ps(_mm_castsi128_ps(tiny)), hits = 0;
    if (mt) {
        /* tri_hits_box(): b and c swapped where the area is negative, then
         * the box's samples (at most four) against the three edges */
        const __m256i zero4 = _mm256_setzero_si256();
        __m256i neg = _mm256_cmpgt_epi64(zero4, area2);
        __m256i ex[3] = { xl[0], _mm256_blendv_epi8(xl[1], xl[2], neg), _mm256_blendv_epi8(xl[2], xl[1], neg) };
        __m256i ey[3] = { yl[0], _mm256_blendv_epi8(yl[1], yl[2], neg), _mm256_blendv_epi8(yl[2], yl[1], neg) };
        __m256i dx[3], dy[3], tl[3];
        for (int k = 0; k < 3; k++) {
            int m = k == 2 ? 0 : k + 1;
            dx[k] = _mm256_sub_epi64(ex[m], ex[k]);
            dy[k] = _mm256_sub_epi64(ey[m], ey[k]);
            tl[k] = _mm256_or_si256(_mm256_cmpgt_epi64(zero4, dy[k]),
                                    _mm256_and_si256(_mm256_cmpeq_epi64(dy[k], zero4), _mm256_cmpgt_epi64(dx[k], zero4)));
        }
        __m256i hit = zero4;
        for (int smp = 0; smp < 4; smp++) {
            /* sample smp of each lane's box, row by row: row = how many
             * whole box widths fit in smp, col = what is left */
            __m128i vs = _mm_set1_epi32(smp), bw1 = _mm_max_epi32(bw, _mm_set1_epi32(1));
            __m128i row = _mm_setzero_si128(), lim = bw1;
            for (int r = 1; r < 4; r++) {
                row = _mm_sub_epi32(row, _mm_cmpgt_epi32(_mm_add_epi32(vs, _mm_set1_epi32(1)), lim));
                lim = _mm_add_epi32(lim, bw1);
            }
            __m128i col = _mm_sub_epi32(vs, _mm_mullo_epi32(row, bw1));
            __m128i ok32 = _mm_cmpgt_epi32(nsamp, vs);
            __m128i px32 = _mm_add_epi32(_mm_slli_epi32(_mm_add_epi32(x0, col), SUBPIX_BITS), _mm_set1_epi32(128));
            __m128i py32 = _mm_add_epi32(_mm_slli_epi32(_mm_add_epi32(y0, row), SUBPIX_BITS), _mm_set1_epi32(128));
            __m256i vx = _mm256_cvtepi32_epi64(px32), vy = _mm256_cvtepi32_epi64(py32);
            __m256i in = _mm256_cvtepi32_epi64(ok32);
            for (int k = 0; k < 3; k++)
                in = _mm256_and_si256(in, edge4_covers(ex[k], ey[k], dx[k], dy[k], tl[k], vx, vy));
            hit = _mm256_or_si256(hit, in);
        }
        hit = _mm256_andnot_si256(_mm256_cmpeq_epi64(area2, zero4), hit);
        hits = _mm256_movemask_pd(_mm256_castsi256_pd(hit));
    }
    /* the plane, in double */
    const __m256d inv = _mm256_set1_pd(1.0 / SUBPIX);
    __m256d Xd[3], Yd[3], Zd[3];
    for (int k = 0; k < 3; k++) {
        Xd[k] = _mm256_mul_pd(_mm256_cvtepi32_pd(X[k]), inv);
        Yd[k] = _mm256_mul_pd(_mm256_cvtepi32_pd(Y[k]), inv);
        Zd[k] = _mm256_cvtps_pd(Z[k]);
    }
    __m256d x1d = _mm256_sub_pd(Xd[1], Xd[0]), y1d = _mm256_sub_pd(Yd[1], Yd[0]), z1d = _mm256_sub_pd(Zd[1], Zd[0]);
    __m256d x2d = _mm256_sub_pd(Xd[2], Xd[0]), y2d = _mm256_sub_pd(Yd[2], Yd[0]), z2d = _mm256_sub_pd(Zd[2], Zd[0]);
    __m256d nx = _mm256_sub_pd(_mm256_mul_pd(y1d, z2d), _mm256_mul_pd(z1d, y2d));
    __m256d ny = _mm256_sub_pd(_mm256_mul_pd(z1d, x2d), _mm256_mul_pd(x1d, z2d));
    __m256d nz = _mm256_sub_pd(_mm256_mul_pd(x1d, y2d), _mm256_mul_pd(y1d, x2d));
    __m256d flat = _mm256_cmp_pd(nz, _mm256_setzero_pd(), _CMP_EQ_OQ);
    const __m256d sign = _mm256_set1_pd(-0.0), half = _mm256_set1_pd(0.5);
    __m256d a = _mm256_div_pd(_mm256_xor_pd(nx, sign), nz), b = _mm256_div_pd(_mm256_xor_pd(ny, sign), nz);
    __m256d zc = _mm256_add_pd(
        _mm256_add_pd(Zd[0], _mm256_mul_pd(a, _mm256_sub_pd(_mm256_add_pd(_mm256_cvtepi32_pd(x0), half), Xd[0]))),
        _mm256_mul_pd(b, _mm256_sub_pd(_mm256_add_pd(_mm256_cvtepi32_pd(y0), half), Yd[0])));
    __m256d mag = _mm256_add_pd(_mm256_add_pd(_mm256_andnot_pd(sign, zc),
                                              _mm256_mul_pd(_mm256_andnot_pd(sign, a), _mm256_cvtepi32_pd(bw))),
                                _mm256_mul_pd(_mm256_andnot_pd(sign, b), _mm256_cvtepi32_pd(bh)));
    __m256d lo = _mm256_min_pd(Zd[2], _mm256_min_pd(Zd[0], Zd[1]));     /* min_pd(p, q) is p < q ? p : q */
    __m256d zmin = _mm256_sub_pd(lo, _mm256_mul_pd(_mm256_add_pd(_mm256_andnot_pd(sign, lo), mag),
                                                   _mm256_set1_pd(1.0 / (1 << 20))));
    _mm_storeu_si128((__m128i *)f->x0, x0);
    _mm_storeu_si128((__m128i *)f->x1, x1);
    _mm_storeu_si128((__m128i *)f->y0, y0);
    _mm_storeu_si128((__m128i *)f->y1, y1);
    _mm_storeu_ps(f->a, _mm256_cvtpd_ps(a));
    _mm_storeu_ps(f->b, _mm256_cvtpd_ps(b));
    _mm_storeu_ps(f->zc, _mm256_cvtpd_ps(zc));
    _mm_storeu_ps(f->zmin, _mm256_cvtpd_ps(zmin));
    int me = _mm_movemask_ps(_mm_castsi128_ps(empty)), mb = _mm256_movemask_pd(_mm256_castsi256_pd(back));
    int mf = _mm256_movemask_pd(flat);
    for (int l = 0; l < 4; l++)
        f->state[l] = me >> l & 1 ? FIN_EMPTY
                    : sp->cull && (mb >> l & 1) ? FIN_BACK
                    : (mt >> l & 1) && !(hits >> l & 1) ? FIN_EMPTY
                    : mf >> l & 1 ? FIN_EMPTY : FIN_KEPT;
}

/* The kept triangles keep[0 .. nk) of a chunk of triangles (polygon k +
 * keep[i], corners c0 + 3 keep[i], instance inst + keep[i]), four at a
 * time through finish_tris4, in order; those with a corner to clip go
 * through emit_poly. */
ZV_AVX2_FN static int emit_tris_avx2(RangeJob *j, uint32_t k, uint32_t c0, uint32_t inst, const uint32_t *keep,
                                  uint32_t nk)
{
    ScreenPolys *sp = j->out;
    const ScreenVert *sv = j->vs->sv;
    const uint32_t *corner = j->s->poly_corner, vmin = j->o->vert_min;
    uint32_t i = 0;
    for (; i + 4 <= nk; i += 4) {
        int rv = vert_room(j, sp->nverts + 4 * 11);
        if (rv)
            return rv;
        const ScreenVert *v[4][3];
        int out[4];
        for (int l = 0; l < 4; l++) {
            const uint32_t *c = corner + c0 + 3 * keep[i + l];
            v[l][0] = &sv[c[0] - vmin];
            v[l][1] = &sv[c[1] - vmin];
            v[l][2] = &sv[c[2] - vmin];
            out[l] = (v[l][0]->x == VERT_OUT) | (v[l][1]->x == VERT_OUT) | (v[l][2]->x == VERT_OUT);
        }
        Finish4 f;
        finish_tris4(sp, v, &f);
        for (int l = 0; l < 4; l++) {
            uint32_t q = keep[i + l];
            if (out[l]) {
                rv = emit_poly(j, k + q, c0 + 3 * q, c0 + 3 * q + 3, inst + q);
                if (rv)
                    return rv;
                continue;
            }
            if (f.state[l] == FIN_EMPTY) {
                sp->culled_empty++;
                continue;
            }
            if (f.state[l] == FIN_BACK) {
                sp->culled_back++;
                continue;
            }
            ScreenVert *dst = &sp->verts[sp->nverts];
            dst[0] = *v[l][0];
            dst[1] = *v[l][1];
            dst[2] = *v[l][2];
            ScreenPoly *p = &sp->polys[sp->npolys++];
            p->first = sp->nverts;
            sp->nverts += 3;
            p->x0 = f.x0[l];
            p->x1 = f.x1[l];
            p->y0 = f.y0[l];
            p->y1 = f.y1[l];
            p->a = f.a[l];
            p->b = f.b[l];
            p->zc = f.zc[l];
            p->zmin = f.zmin[l];
            kept_poly(j, k + q, inst + q);
        }
    }
    for (; i < nk; i++) {
        uint32_t q = keep[i];
        int rv = emit_poly(j, k + q, c0 + 3 * q, c0 + 3 * q + 3, inst + q);
        if (rv)
            return rv;
    }
    return 0;
}
#endif

static int project_range(RangeJob *j)
{
    ScreenPolys *sp = j->out;
    const Scene *s = j->s;
    const Object *o = j->o;
    const uint32_t *idx = j->vs->idx;
    uint32_t vmin = o->vert_min, empty = 0;
    uint32_t keep[CHUNK + 8];
    for (uint32_t k = j->k0; k < j->k1; k += CHUNK) {
        uint32_t n = j->k1 - k < CHUNK ? j->k1 - k : CHUNK, inst = j->inst0 + (k - j->k0);
        uint32_t c0 = s->poly_start[k];
        /* every polygon starts dropped; emit_poly records the kept ones */
        memset(j->map + inst, 0xff, (size_t)n * sizeof *j->map);
        sp->in_polys += n;
        int tris = s->poly_start[k + n] - c0 == 3 * n;
        uint32_t nk;
        if (tris) {
            /* n polygons of at least three corners each and 3 n corners
             * in all: triangles only, at corners c0 + 3 i */
            nk = screen_tris(j->simd, s->poly_corner + c0, n, idx, vmin, sp->w, sp->h, keep, j->lut);
            empty += n - nk;
#ifdef ZV_AVX2
            if (j->simd >= SIMD_AVX2)
                nk = sift_tiny_avx2(s->poly_corner + c0, j->vs->sv, vmin, sp->cull, keep, nk, j->lut, &empty,
                                    &sp->culled_back);
#endif
            /* the face ids of the kept ones are read below, a few lines
             * each out of a big array: start fetching them now */
            for (uint32_t i = 0; i < nk; i += 4)
                __builtin_prefetch(&s->poly_lface[k + keep[i]]);
        } else {
            /* a mixed chunk: triangles screened one by one */
            nk = 0;
            for (uint32_t i = 0; i < n; i++) {
                uint32_t a = s->poly_start[k + i];
                keep[nk] = i;
                nk += s->poly_start[k + i + 1] - a != 3 || tri_keeps(s->poly_corner + a, idx, vmin, sp->w, sp->h);
            }
            empty += n - nk;
        }
#ifdef ZV_AVX2
        if (tris && j->simd >= SIMD_AVX2) {
            int rv = emit_tris_avx2(j, k, c0, inst, keep, nk);
            if (rv) {
                sp->culled_empty += empty;
                return rv;
            }
            continue;
        }
#endif
        for (uint32_t i = 0; i < nk; i++) {
            uint32_t q = k + keep[i];
            uint32_t a = tris ? c0 + 3 * keep[i] : s->poly_start[q], b = tris ? a + 3 : s->poly_start[q + 1];
            int rv = emit_poly(j, q, a, b, inst + keep[i]);
            if (rv) {
                sp->culled_empty += empty;
                return rv;
            }
        }
    }
    sp->culled_empty += empty;
    return 0;
}

/* ==== an object over several threads ==== */

/* The helpers' parts, written in windows further up sp's arrays, moved
 * down after part 0: the vertices on one thread, the polygons (their
 * first corner shifted) and the map entries on another. Within an array
 * the parts move in order, each into room the ones before it left. */
typedef struct {
    ScreenPolys       *sp;
    const ScreenPolys *win;     /* each part's counts */
    const uint32_t    *pb, *vb; /* where each part was written */
    const uint32_t    *inst0, *ninst;
    uint32_t           bv[SCREEN_MAX_THREADS], bp[SCREEN_MAX_THREADS];  /* where each part goes */
    int                parts;
} CompactJob;

static void compact_task(void *arg, int task, int worker)
{
    (void)worker;
    CompactJob *c = arg;
    ScreenPolys *sp = c->sp;
    for (int i = 1; i < c->parts; i++) {
        const ScreenPolys *part = &c->win[i];
        if (task == 0) {
            memmove(sp->verts + c->bv[i], sp->verts + c->vb[i], (size_t)part->nverts * sizeof *sp->verts);
            continue;
        }
        uint32_t bp = c->bp[i], bv = c->bv[i];
        memmove(sp->polys + bp, sp->polys + c->pb[i], (size_t)part->npolys * sizeof *sp->polys);
        for (uint32_t q = 0; q < part->npolys; q++)
            sp->polys[bp + q].first += bv;
        for (uint32_t q = c->inst0[i]; q < c->inst0[i] + c->ninst[i]; q++)
            if (sp->map[q] >= 0)
                sp->map[q] += (int32_t)bp;
    }
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

/* The pool of helpers for `parts` parts, made (again) when the thread
 * count asks for more than it has; NULL: the caller does every part. */
static Pool *work_pool(ScreenWork *w, int parts)
{
    if (parts < 2)
        return NULL;
    if (!w->pool || w->pool_want < parts - 1) {
        pool_free(w->pool);
        w->pool = pool_create(parts - 1);
        w->pool_want = parts - 1;
    }
    return w->pool;
}

/* Part `part` (its window and clip buffers are its own, whichever worker
 * takes it). */
static void range_part(void *arg, int part, int worker)
{
    (void)worker;
    RangeJob *j = (RangeJob *)arg + part;
    j->rc = project_range(j);
}

/* Object o's polygons in `parts` consecutive parts: part 0 on the caller,
 * the others on helpers. Each part writes into its own window of sp's
 * arrays, past the room the parts before it can need; then the parts
 * move down in order: no second set of buffers. Returns 0 when done, 1
 * when a part's clipping outgrew its window (rare: sp is as it was and
 * the caller projects the object again on one thread), -1 on out of
 * memory. */
static int project_parts(ScreenPolys *sp, const Scene *s, const Object *o, const Proj *pj, const Mat4 *mv,
                         ScreenWork *w, Pool *pool, uint32_t inst, int parts, int simd)
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
        job[i] = (RangeJob){ &win[i], s, o, pj, mv, &w->sc, &w->clip[i], k[i], k[i + 1],
                             inst + (k[i] - o->poly_first), sp->map, 1, simd, 0, &w->lut };
    }
    pool_run(pool, parts, range_part, job);
    int rc = 0;
    for (int i = 0; i < parts; i++)
        if (job[i].rc == -1 || (job[i].rc && rc != -1))
            rc = job[i].rc;
    if (rc == -1)
        return -1;
    if (rc)
        return 1;
    uint32_t pb[SCREEN_MAX_THREADS], inst0[SCREEN_MAX_THREADS], ninst[SCREEN_MAX_THREADS];
    CompactJob cj = { .sp = sp, .win = win, .pb = pb, .vb = vb, .inst0 = inst0, .ninst = ninst, .parts = parts };
    uint32_t nv = win[0].nverts, np = win[0].npolys;
    for (int i = 1; i < parts; i++) {
        pb[i] = sp->npolys + (k[i] - o->poly_first);
        inst0[i] = job[i].inst0;
        ninst[i] = k[i + 1] - k[i];
        cj.bv[i] = nv;
        cj.bp[i] = np;
        nv += win[i].nverts;
        np += win[i].npolys;
    }
    pool_run(pool, 2, compact_task, &cj);
    sp->nverts = nv;
    sp->npolys = np;
    sp->in_polys = win[0].in_polys;
    sp->culled_back = win[0].culled_back;
    sp->culled_empty = win[0].culled_empty;
    for (int i = 1; i < parts; i++) {
        sp->in_polys += win[i].in_polys;
        sp->culled_back += win[i].culled_back;
        sp->culled_empty += win[i].culled_empty;
    }
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
    int simd = simd_use(sp->simd);
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
        VertJob vj;
        vj.pos = o->mesh->pos + 3 * (size_t)o->vert_min;
        vj.mv = m4_mul(view, object_matrix(o));
        vj.pj = &pj;
        vj.nv = o->vert_max - o->vert_min + 1;
        if (grow_array((void **)&sc->sv, &sc->cap_sv, vj.nv, sizeof(ScreenVert)) ||
            grow_array((void **)&sc->idx, &sc->cap_idx, vj.nv, sizeof(uint32_t)))
            return -1;
        vj.sv = sc->sv;
        vj.idx = sc->idx;
        vj.simd = simd;
        int parts = object_parts(sp, o), rc = 1;
        Pool *pool = work_pool(w, parts);
        int have = 1 + pool_helpers(pool);
        if (parts > have)
            parts = have;           /* no more threads to be had: fewer parts */
        if (parts > 1)
            sp->helpers = (uint32_t)(parts - 1) > sp->helpers ? (uint32_t)(parts - 1) : sp->helpers;
        /* vertices in chunks of about VERT_CHUNK, taken by whichever
         * thread is free */
        vj.parts = parts > 1 ? (int)(vj.nv / VERT_CHUNK) + parts : 1;
        if (vj.parts > 4 * SCREEN_MAX_THREADS)
            vj.parts = 4 * SCREEN_MAX_THREADS;
        pool_run(pool, vj.parts, verts_part, &vj);
        if (parts > 1 && (rc = project_parts(sp, s, o, &pj, &vj.mv, w, pool, inst, parts, simd)) < 0)
            return -1;
        if (rc) {
            RangeJob j = { sp, s, o, &pj, &vj.mv, sc, &w->clip[0], o->poly_first,
                           o->poly_first + o->poly_count, inst, sp->map, 0, simd, 0, &w->lut };
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
int screen_dump_obj(const ScreenPolys *sp, FILE *f)
{
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
    errno = err;
    return err ? -1 : 0;
}
