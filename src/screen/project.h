#ifndef ZV_SCREEN_PROJECT_H
#define ZV_SCREEN_PROJECT_H
/* Internal to screen/: the front end's pieces shared by its files.
 * project.c drives a frame (pass 1, the vertices; threads; the output's
 * room); polys.c is pass 2's reference (screening, the fast path, the
 * sample box, culling and plane of each polygon); clip.c the slow path
 * (Sutherland-Hodgman against the near plane and the guard band);
 * project_sse2.c and project_avx2.c the SIMD loops, each matching the
 * scalar code here bit for bit. Which loops run is the frame's SimdLevel
 * (simd.h), carried in VertJob.simd and RangeJob.simd. */

#include <stdint.h>

#include "grow.h"
#include "raster.h"
#include "screen.h"
#include "section.h"
#include "simd.h"

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

/* Clip polygon buffers, one set per worker; and its scratch for the
 * polygons a section plane cuts (cut.c). */
typedef struct {
    CVert   *buf[2];
    uint32_t cap;
    SectionClip sec;        /* the kept part of a cut polygon */
    float   *cpts;          /* its corners, 3 floats each */
    uint8_t *cmask;         /* and their masks */
    uint32_t ccap;
} ClipBuf;

/* For each 8-bit mask, the numbers of its set bits in order, one a byte,
 * and how many there are: packs kept lanes to the front. */
typedef struct {
    uint64_t lanes[256];
    uint8_t  count[256];
} KeepLut;
/* The projection of a frame (proj_setup in project.c). */
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

/* View space -> screen px and depth. Persp: the point must be in front.
 * The SIMD vertex loops repeat these operations in this order. */
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

/* Vertices [a, b) of an object's range, or its part `part` of `parts`. */
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
#endif

/* The SIMD loops over vertices [a, b): every vertex as vert_one() gives
 * it. */
#ifdef ZV_SSE2
void project_verts_sse2(const VertJob *j, uint32_t a, uint32_t b);
#endif
#ifdef ZV_AVX2
void project_verts_avx2(const VertJob *j, uint32_t a, uint32_t b);
#endif

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
uint32_t project_screen_tris(const uint32_t *corner, uint32_t a, uint32_t n, const uint32_t *idx, uint32_t vmin,
                             int32_t w, int32_t h, uint32_t *keep, uint32_t nk);

/* ==== pass 2: polygons ==== */

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
    int32_t       *map;         /* NULL: none kept (ScreenPolys.no_map) */
    int            fixed;       /* out's arrays are a window of another's: never grow */
    int            simd;
    int            rc;          /* 0, -1 out of memory, -2 window full */
    const KeepLut *lut;
    const SectionCut *cut;      /* NULL: the object is not cut (ScreenPolys.cut) */
    const uint8_t *cmask;       /* the cut's masks of the object's mesh */
} RangeJob;

/* Room for `need` vertices in j->out: grow, or in a fixed window report
 * that it is full (the caller then redoes the work on one thread). */
static inline int vert_room(RangeJob *j, uint32_t need)
{
    ScreenPolys *sp = j->out;
    if (need <= sp->cap_verts)
        return 0;
    if (j->fixed)
        return -2;
    return grow_array((void **)&sp->verts, &sp->cap_verts, need, sizeof *sp->verts);
}

/* Record kept polygon sp->polys[npolys - 1]: its face id (read only now:
 * most polygons screened in are dropped after all) and where it went. */
static inline void kept_poly(RangeJob *j, uint32_t k, uint32_t inst)
{
    ScreenPolys *sp = j->out;
    sp->polys[sp->npolys - 1].face = j->o->face_base + (int32_t)scene_poly_lface(j->s, j->o, k);
    if (j->map)
        j->map[inst] = (int32_t)(sp->npolys - 1);
}

/* Pass 2 over polygons [j->k0, j->k1) of the object (polys.c): 0, -1 out
 * of memory, -2 window full (RangeJob.rc). */
int project_range(RangeJob *j);

/* Polygon k of the scene (corners c0 .. c1, instance inst) through the
 * fast or slow path into j->out (polys.c). Returns 0 or an error of
 * vert_room or project_clip. */
int project_emit_poly(RangeJob *j, uint32_t k, uint32_t c0, uint32_t c1, uint32_t inst);

/* The slow path (clip.c): clip polygon k (corners c0 .. c1) against the
 * near plane and the guard band and append its snapped outline to
 * j->out. Returns 0, 1 to skip it, or vert_room's error. */
int project_clip(RangeJob *j, uint32_t c0, uint32_t c1);
/* The same of an outline of object-space points pts[0 .. n) (3 floats
 * each), each taken as pass 1 takes a vertex. */
int project_clip_points(RangeJob *j, const float *pts, uint32_t n);

/* cut.c: the polygons a section cuts. keep[0 .. nk) (chunk indices from
 * polygon k, KEEP_HIT marks allowed) loses the polygons with a corner on
 * a removed side, which go to cutk[0 .. *ncut) (indices alone); the
 * count left is returned. */
uint32_t project_cut_split(const RangeJob *j, uint32_t k, uint32_t *keep, uint32_t nk, uint32_t *cutk,
                           uint32_t *ncut);
/* Polygon k (corners c0 .. c1, instance inst) less its removed part:
 * dropped, or one outline appended and finished (polys.c's
 * project_finish) in its place. 0 or an error of vert_room. */
int project_emit_cut(RangeJob *j, uint32_t k, uint32_t c0, uint32_t c1, uint32_t inst);
/* polys.c: finish the outline verts[first .. nverts) (sample box,
 * culling, plane); 1 if kept. */
int project_finish(ScreenPolys *sp, uint32_t first);
/* The caps of sp->cut after the faces, ids section_cap_id0 on. 0, or -1
 * out of memory. */
int project_caps(ScreenPolys *sp, const Scene *s, const Proj *pj, ClipBuf *cb);

/* A mark on a keep[] entry (project_avx2.c's second screening). */
#define KEEP_HIT 0x80000000u

#ifdef ZV_AVX2
/* project_avx2.c: the screening of a chunk of triangles eight at a
 * time (keep[] with room for n + 8: it stores eight at a time); the
 * second screening of the kept ones whose box is at most four samples,
 * which marks those it found covering one KEEP_HIT (a bit above every
 * chunk index: readers of keep[] mask it off); and the kept ones
 * finished four at a time. Each gives what polys.c's scalar code gives. */
uint32_t project_screen_tris_avx2(const uint32_t *corner, uint32_t n, const uint32_t *idx, uint32_t vmin, int32_t w,
                                  int32_t h, uint32_t *keep, const KeepLut *lut);
uint32_t project_sift_small_avx2(const uint32_t *corner, const ScreenVert *sv, uint32_t vmin, int32_t w, int32_t h,
                                 int cull, uint32_t *keep, uint32_t nk, const KeepLut *lut, uint32_t *empty,
                                 uint32_t *back);
int      project_emit_tris_avx2(RangeJob *j, uint32_t k, uint32_t c0, uint32_t inst, const uint32_t *keep,
                                uint32_t nk);
#endif

#endif
