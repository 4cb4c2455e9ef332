#ifndef ZV_TESTLIB_H
#define ZV_TESTLIB_H
/* testlib: scenes from OBJ text or files, seeded random views, and a
 * render of one frame with any algorithm, for the Criterion tests. */

#include "hsr.h"
#include "scene.h"
#include "screen.h"

extern const HsrAlgo hsr_zbuffer;

/* 0 on success; a failure message goes to stderr. */
int  tl_scene_from_text(Scene *s, const char *name, const char *obj_text);
int  tl_scene_from_file(Scene *s, const char *path);

/* A reproducible view: turns, zoom 0.7..2.5, a small pan; persp with a
 * field of view of 30..100 degrees, sometimes close enough that polygons
 * cross the near plane. */
void tl_random_view(Scene *s, uint32_t seed, int persp);

/* Project at w x h and render with algo on `threads` threads. */
int  tl_render(Scene *s, const HsrAlgo *algo, int threads, int w, int h, int cull,
               ScreenPolys *sp, FrameBufs *fb, HsrStats *st);

/* Compare fb with ref; returns differing pixels and the first of them. */
long tl_diff(const FrameBufs *ref, const FrameBufs *fb, int *first_x, int *first_y);

/* Path to ../shared/models/NAME if that folder exists, else NULL. */
const char *tl_shared_model(const char *name);

#endif
