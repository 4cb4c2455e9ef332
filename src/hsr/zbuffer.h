#ifndef ZV_HSR_ZBUFFER_H
#define ZV_HSR_ZBUFFER_H
/* Internal to hsr/: the z-buffer's pieces that other algorithms reuse. */

#include "hsr.h"

/* Rows [y0, y1): ids = -1, depth = +inf. */
void fbuf_clear_rows(FrameBufs *fb, int y0, int y1);

/* The SIMD level the frame's polygons are drawn at (a SimdLevel the
 * caller resolved with simd_use: every level writes the same bytes),
 * set where a frame starts, before zbuffer_draw_poly. */
void zbuffer_begin(void *zstate, int simd);

/* Depth-test polygon pi into rows [y0, y1) of fb (state from the z-buffer's
 * create(), begun for this frame). Returns the samples written. */
uint64_t zbuffer_draw_poly(void *zstate, const ScreenPolys *sp, uint32_t pi,
                           FrameBufs *fb, int y0, int y1);

#endif
