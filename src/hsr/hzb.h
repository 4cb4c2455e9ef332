#ifndef ZV_HSR_HZB_H
#define ZV_HSR_HZB_H
/* Internal to hsr/: the hierarchical z-buffer (z-pyramid) of one band of
 * rows, shared by hzb.c (polygons in scene order) and octree.c (octree
 * nodes front to back).
 *
 * Level 0 is the band's own depth buffer; texel (tx, ty) of level
 * k >= HZB_FIRST (4) holds an upper bound of the depths of the pixels it
 * covers, columns [tx << k, (tx + 1) << k) and band rows
 * [ty << k, (ty + 1) << k), up to a level of one texel. Levels 1 to
 * HZB_FIRST - 1 are not kept: a box of at most HZB_FINE (16) pixels a
 * side is tested on the depth buffer itself (4-wide loads along each row),
 * which is both tighter than any texel and free of upkeep; level HZB_FIRST
 * (16 x 16 pixels) is computed straight from the depth buffer.
 *
 * Depths only ever decrease as polygons are drawn, so a stale texel is
 * merely too large: a test against it stays safe (it culls less). That
 * makes the pyramid lazy: drawing only flags the level-HZB_FIRST texels it wrote
 * under, and their ancestors, dirty; a test first compares with the
 * stored (possibly stale) values, and only when that fails to cull
 * recomputes the dirty texels it reads, from their dirty descendants
 * down. Each flag is cleared once, so the upkeep never exceeds an eager
 * update, and it is paid only where large boxes are tested. */

#include <stdint.h>

#include "hsr.h"
#include "simd.h"

#define HZB_MAX_LEVELS 32
#ifndef HZB_FIRST
#define HZB_FIRST      4     /* the finest level kept above the depth buffer */
#endif
#define HZB_FINE       (1 << HZB_FIRST) /* boxes up to this many pixels a side test level 0 */

typedef struct {
    int      w, y0, h;              /* band: columns [0, w), rows [y0, y0 + h) */
    int      nlev;                  /* levels 0 .. nlev - 1; the last is 1 x 1 (0: none) */
    int      lw[HZB_MAX_LEVELS];    /* texels per row of each level */
    int      lh[HZB_MAX_LEVELS];    /* texel rows of each level */
    size_t   off[HZB_MAX_LEVELS];   /* start of level k >= HZB_FIRST in tex and dirty */
    float   *tex;                   /* levels HZB_FIRST .. nlev - 1, row major */
    uint8_t *dirty;                 /* 1: tex may be above the max of its children */
    size_t   cap;
    float   *d0;                    /* level 0: fb->depth at row y0 (stride w) */
    int      simd;                  /* the frame's SimdLevel, resolved (simd_use), for
                                       the maxima and the fine test */
} HzbPyramid;

/* Size the pyramid for rows [y0, y1) of fb and reset it, clearing those
 * rows of fb (ids -1, depth +inf); its loops run at SIMD level simd
 * (simd_use(HsrInput.simd)). Returns -1 on out of memory (then nothing
 * is culled). */
int  hzb_pyr_begin(HzbPyramid *p, FrameBufs *fb, int y0, int y1, int simd);
void hzb_pyr_free(HzbPyramid *p);

/* Depths in [x0, x1) x [ya, yb) (image rows, inside the band) may have
 * decreased: flag the texels above them dirty. */
void hzb_pyr_mark(HzbPyramid *p, int x0, int x1, int ya, int yb);

/* Recompute dirty texel (tx, ty) of level k >= HZB_FIRST from its dirty
 * descendants down, clearing their flags; returns its value. */
float hzb_pyr_refresh(HzbPyramid *p, int k, int tx, int ty);

/* Is texel (tx, ty) of level k >= HZB_FIRST nearer than z everywhere? */
static inline int hzb_texel_hides(HzbPyramid *p, int k, int tx, int ty, float z)
{
    size_t i = p->off[k] + (size_t)ty * p->lw[k] + tx;
    if (z > p->tex[i])
        return 1;
    return p->dirty[i] && z > hzb_pyr_refresh(p, k, tx, ty);
}

/* Level 0: is every pixel of [x0, x1) x band rows [by0, by1] (at most
 * HZB_FINE a side) nearer than z? Rows at least 4 wide are read in
 * groups of four, from xa on and one at xb, which cover [x0, x1) inside
 * the row; the few pixels around the box they read too can only make
 * the answer more cautious. The SSE2 loop and the scalar one read the
 * same pixels, so every level culls the same polygons (and counts the
 * same in HsrStats). */
static inline int hzb_fine_hides(const HzbPyramid *p, int x0, int x1, int by0, int by1, float z)
{
    const float *row = p->d0 + (size_t)by0 * p->w;
    if (p->w < 4) {
        for (int j = by0; j <= by1; j++, row += p->w)
            for (int i = x0; i < x1; i++)
                if (!(z > row[i]))
                    return 0;
        return 1;
    }
    int xa = x0 < p->w - 4 ? x0 : p->w - 4, xb = x1 - 4 > 0 ? x1 - 4 : 0;
#ifdef ZV_SSE2
    if (p->simd >= SIMD_SSE2) {
        const __m128 vz = _mm_set1_ps(z);
        for (int j = by0; j <= by1; j++, row += p->w) {
            __m128 m = _mm_loadu_ps(row + xb);
            for (int x = xa; x < xb; x += 4)
                m = _mm_max_ps(m, _mm_loadu_ps(row + x));
            /* z > every max (false for a NaN z); most visible polygons
             * leave at their first row */
            if (_mm_movemask_ps(_mm_cmpgt_ps(vz, m)) != 15)
                return 0;
        }
        return 1;
    }
#endif
    for (int j = by0; j <= by1; j++, row += p->w) {
        for (int k = 0; k < 4; k++)
            if (!(z > row[xb + k]))
                return 0;
        for (int x = xa; x < xb; x += 4)
            for (int k = 0; k < 4; k++)
                if (!(z > row[x + k]))
                    return 0;
    }
    return 1;
}

/* Is everything deeper than z hidden in [x0, x1) x [ya, yb) (image rows,
 * non-empty, inside the band)? A box of at most HZB_FINE pixels a side is
 * tested on the depth buffer; a larger one at the finest level where it
 * spans at most 2 x 2 texels. True when z is strictly greater than every
 * value read (a tie could still win on the face id; a NaN culls nothing). */
static inline int hzb_pyr_hidden(HzbPyramid *p, int x0, int x1, int ya, int yb, float z)
{
    int bx0 = x0, bx1 = x1 - 1, by0 = ya - p->y0, by1 = yb - 1 - p->y0;
    int d = bx1 - bx0 > by1 - by0 ? bx1 - bx0 : by1 - by0;
    if (d < HZB_FINE)
        return hzb_fine_hides(p, x0, x1, by0, by1, z);
    if (p->nlev == 0)           /* no pyramid (out of memory): cull nothing */
        return 0;
    /* 2^k > d: the box spans at most two texels each way; one level finer may too */
    int k = 32 - __builtin_clz((unsigned)d);
    if ((bx1 >> (k - 1)) - (bx0 >> (k - 1)) <= 1 && (by1 >> (k - 1)) - (by0 >> (k - 1)) <= 1)
        k--;
    if (k < HZB_FIRST)          /* coarser texels: still at most 2 x 2 */
        k = HZB_FIRST;
    if (k >= p->nlev)
        k = p->nlev - 1;        /* the top level is one texel */
    int tx0 = bx0 >> k, tx1 = bx1 >> k, ty0 = by0 >> k, ty1 = by1 >> k;
    if (!hzb_texel_hides(p, k, tx0, ty0, z))
        return 0;
    if (tx1 != tx0 && !hzb_texel_hides(p, k, tx1, ty0, z))
        return 0;
    if (ty1 != ty0) {
        if (!hzb_texel_hides(p, k, tx0, ty1, z))
            return 0;
        if (tx1 != tx0 && !hzb_texel_hides(p, k, tx1, ty1, z))
            return 0;
    }
    return 1;
}

/* What both hierarchical algorithms keep per thread: the z-buffer's
 * state (its edge walkers draw the polygons that pass) and the pyramid. */
typedef struct {
    void      *zb;
    HzbPyramid pyr;
} HzbBase;

int  hzb_base_init(HzbBase *b);     /* 0, or -1 on out of memory */
/* A frame's band: the pyramid begun (hzb_pyr_begin) and the z-buffer's
 * state set to the frame's SIMD level; hzb_pyr_begin's result. */
int  hzb_base_begin(HzbBase *b, FrameBufs *fb, int y0, int y1, int simd);
void hzb_base_free(HzbBase *b);

/* The per-polygon step both algorithms share: clip polygon pi's box to
 * the band, skip it when the pyramid hides it (zmin strictly farther),
 * else depth-test it like the z-buffer and mark the pyramid dirty over
 * the samples it wrote. zstate comes from hsr_zbuffer.create(). Adds to
 * polys_in, polys_culled and pixels_written. */
void hzb_draw_poly(HzbPyramid *p, void *zstate, const ScreenPolys *sp, uint32_t pi,
                   FrameBufs *fb, int y0, int y1, HsrStats *stats);

#endif
