#ifndef ZV_HSR_ZBUFFER_H
#define ZV_HSR_ZBUFFER_H
/* Internal to hsr/: the z-buffer's pieces that other algorithms reuse. */

#include "hsr.h"

/* Rows [y0, y1): ids = -1, depth = +inf. */
void fbuf_clear_rows(FrameBufs *fb, int y0, int y1);

/* Depth-test polygon pi into rows [y0, y1) of fb (state from the z-buffer's
 * create()) at SIMD level simd (a SimdLevel the caller resolved with
 * simd_use: every level writes the same bytes). Returns the samples
 * written. */
uint64_t zbuffer_draw_poly(void *zstate, int simd, const ScreenPolys *sp, uint32_t pi,
                           FrameBufs *fb, int y0, int y1);

#endif
