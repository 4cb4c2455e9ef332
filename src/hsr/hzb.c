/* TEMPORARY forwarder to the z-buffer until the real algorithm lands. */
#include "hsr.h"
extern const HsrAlgo hsr_zbuffer;
static void *cr(void) { return hsr_zbuffer.create(); }
static void de(void *s) { hsr_zbuffer.destroy(s); }
static void re(void *s, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *st) { hsr_zbuffer.render(s, in, fb, y0, y1, st); }
const HsrAlgo hsr_hzb = { .name = "hzb", .summary = "TODO", .create = cr, .destroy = de, .render = re };
const HsrAlgo hsr_hzb_octree = { .name = "hzb-octree", .summary = "TODO", .create = cr, .destroy = de, .render = re };
