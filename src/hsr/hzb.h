#ifndef ZV_HSR_HZB_H
#define ZV_HSR_HZB_H
/* Internal to hsr/: the hierarchical z-buffer (z-pyramid) of one band of
 * rows, shared by hzb.c (polygons in scene order) and octree.c (octree
 * nodes front to back).
 *
 * Level 0 is the band's own depth buffer; texel (tx, ty) of level k >= 1
 * holds an upper bound of the depths of the pixels it covers, columns
 * [tx << k, (tx + 1) << k) and band rows [ty << k, (ty + 1) << k), up to
 * a level of one texel. Depths only ever decrease as polygons are drawn,
 * so a stale texel is merely too large: the test stays safe (it culls
 * less), which lets updates stop as soon as a level stops changing. */

#include <stdint.h>

#include "hsr.h"

#define HZB_MAX_LEVELS 32

typedef struct {
    int     w, y0, h;               /* band: columns [0, w), rows [y0, y0 + h) */
    int     nlev;                   /* levels 0 .. nlev - 1; the last is 1 x 1 (0: none) */
    int     lw[HZB_MAX_LEVELS];     /* texels per row of each level */
    int     lh[HZB_MAX_LEVELS];     /* texel rows of each level */
    size_t  off[HZB_MAX_LEVELS];    /* start of level k >= 1 in tex */
    float  *tex;                    /* levels 1 .. nlev - 1, row major */
    size_t  cap;
    float  *d0;                     /* level 0: fb->depth at row y0 (stride w) */
} HzbPyramid;

/* Size the pyramid for rows [y0, y1) of fb and reset it, clearing those
 * rows of fb (ids -1, depth +inf). Returns -1 on out of memory. */
int  hzb_pyr_begin(HzbPyramid *p, FrameBufs *fb, int y0, int y1);
void hzb_pyr_free(HzbPyramid *p);

/* Lower every texel above the pixels [x0, x1) x [ya, yb) (image rows,
 * inside the band) to the max of its children, level by level, stopping
 * at the first level where nothing changed. */
void hzb_pyr_update(HzbPyramid *p, int x0, int x1, int ya, int yb);

/* Is everything deeper than z hidden in [x0, x1) x [ya, yb) (image rows,
 * non-empty, inside the band)? Tested at the finest level where the box
 * spans at most 2 x 2 texels: true when z is strictly greater than each
 * of them (a tie could still win on the face id). */
static inline int hzb_pyr_hidden(const HzbPyramid *p, int x0, int x1, int ya, int yb, float z)
{
    int bx0 = x0, bx1 = x1 - 1, by0 = ya - p->y0, by1 = yb - 1 - p->y0;
    int d = bx1 - bx0 > by1 - by0 ? bx1 - bx0 : by1 - by0;
    /* 2^k > d: the box spans at most two texels each way; one level finer may too */
    int k = d ? 32 - __builtin_clz((unsigned)d) : 0;
    if (k > 0 && (bx1 >> (k - 1)) - (bx0 >> (k - 1)) <= 1 && (by1 >> (k - 1)) - (by0 >> (k - 1)) <= 1)
        k--;
    if (k >= p->nlev) {
        if (p->nlev == 0)       /* no pyramid (out of memory): cull nothing */
            return 0;
        k = p->nlev - 1;        /* the top level is one texel */
    }
    const float *t;
    int stride;
    if (k == 0) {
        t = p->d0;
        stride = p->w;
    } else {
        t = p->tex + p->off[k];
        stride = p->lw[k];
    }
    int tx0 = bx0 >> k, tx1 = bx1 >> k, ty0 = by0 >> k, ty1 = by1 >> k;
    const float *r0 = t + (size_t)ty0 * stride, *r1 = t + (size_t)ty1 * stride;
    /* !(z > m) also keeps a NaN from culling anything */
    return z > r0[tx0] && z > r0[tx1] && z > r1[tx0] && z > r1[tx1];
}

/* The per-polygon step both algorithms share: clip polygon pi's box to
 * the band, skip it when the pyramid hides it (zmin strictly farther),
 * else depth-test it like the z-buffer and update the pyramid over the
 * samples it wrote. zstate comes from hsr_zbuffer.create(). Adds to
 * polys_in, polys_culled and pixels_written. */
void hzb_draw_poly(HzbPyramid *p, void *zstate, const ScreenPolys *sp, uint32_t pi,
                   FrameBufs *fb, int y0, int y1, HsrStats *stats);

#endif
