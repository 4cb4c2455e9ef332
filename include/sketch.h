#ifndef ZV_SKETCH_H
#define ZV_SKETCH_H
/* sketch: polygons drawn by hand on a canvas (zview --sketch), each new
 * one nearer than the last, written as OBJ text the loader reads like
 * any model. The viewer owns the keys and the mouse; this owns the
 * drawing. Canvas coordinates: [-1, 1] x [-1, 1], x right, y up. */

#include <stdint.h>
#include <stdio.h>

#include "scene.h"

#define SKETCH_DZ 0.1f          /* depth between one polygon's plane and the next */

typedef struct { float x, y; } SketchPt;

typedef struct {
    SketchPt *pts;              /* every corner, polygon by polygon, then the open one's */
    uint32_t  npts, cap_pts;
    uint32_t *start;            /* polygon p: pts[start[p] .. start[p + 1]); start[npolys]: the open one */
    uint32_t  npolys, cap_start;
    float    *tilt;             /* 2 per polygon: degrees about the vertical and the horizontal */
    uint32_t  cap_tilt;
    int       flipped;          /* depth order reversed: the first drawn is nearest */
    int       sel;              /* polygon the tilt keys act on, -1 none */
} Sketch;

void     sketch_init(Sketch *k);
void     sketch_free(Sketch *k);
/* Add a corner to the open polygon; -1 off the canvas or out of memory. */
int      sketch_add_point(Sketch *k, float x, float y);
/* Close the open polygon (at least 3 corners; it becomes selected). */
int      sketch_close(Sketch *k);
uint32_t sketch_open_points(const Sketch *k);
/* Take back the open polygon's last corner, else the last polygon. */
int      sketch_undo(Sketch *k);
void     sketch_clear(Sketch *k);
/* Reverse the depth order of all polygons. */
void     sketch_flip(Sketch *k);
/* Tilt the selected polygon about its centre (clamped to +-75 degrees). */
int      sketch_tilt(Sketch *k, float dx_deg, float dy_deg);
void     sketch_select_next(Sketch *k);
/* Depth (towards the viewer) of polygon p's plane at canvas point x, y. */
float    sketch_depth_at(const Sketch *k, uint32_t p, float x, float y);
/* The drawing as OBJ text: one `o` per polygon, coloured corners. */
int      sketch_to_obj(const Sketch *k, FILE *f);
char    *sketch_to_text(const Sketch *k, size_t *len_out);   /* malloc'd, NUL-terminated */

/* ==== The sketch on screen (sketchview.c) ====
 * The canvas seen straight on, pinned to a w x h picture of pixel aspect
 * `aspect` (pixel height / width): its centre at the picture's centre,
 * its side SKETCH_FILL of the picture's shorter side, whatever is drawn.
 * Pixel coordinates are continuous: pixel (i, j) covers [i, i+1) x [j, j+1),
 * y down. */

#define SKETCH_FILL 0.95f       /* of the shorter side: the corners stay clickable */

/* Pixels per canvas unit across (the picture's x axis). */
float    sketch_px_per_unit(int w, int h, float aspect);
/* Picture point (px, py) -> canvas point; may lie off the canvas. */
SketchPt sketch_canvas_at(int w, int h, float aspect, float px, float py);
/* Canvas point -> picture point. */
void     sketch_pixel_at(int w, int h, float aspect, SketchPt c, float *px_out, float *py_out);
/* The drawing as a scene, through the OBJ text and the ordinary loader
 * (an empty drawing: a scene with nothing in it). Returns 0, or -1 with
 * a message in err. */
int      sketch_scene(const Sketch *k, Scene *out, char *err, size_t errlen);
/* Point s's camera at the canvas for a w x h picture: the front view,
 * fitted as `zview --view front` fits the saved file, then zoomed and
 * panned so the canvas lands where sketch_pixel_at() says. The view's
 * command line (--zoom, --pan) then gives the same picture of the saved
 * OBJ. */
void     sketch_camera(Scene *s, int w, int h, float aspect);

#endif
