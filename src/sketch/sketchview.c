/* sketchview.c: the sketch on screen. The drawing becomes a scene the
 * way a saved sketch does when zview opens it (its OBJ text through the
 * ordinary loader), and the camera pins the canvas to the picture, so a
 * click lands where the pointer is and the picture is the one `zview
 * --print` gives of the saved file with the view's --zoom and --pan. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sketch.h"

/* ==== Picture <-> canvas ==== */

float sketch_px_per_unit(int w, int h, float aspect)
{
    /* half the shorter side, in x-pixel units (a pixel is aspect times
     * as tall as wide), holds one canvas unit */
    double half_w = 0.5 * w, half_h = 0.5 * h * (aspect > 0 ? aspect : 1);
    return (float)(SKETCH_FILL * fmin(half_w, half_h));
}

SketchPt sketch_canvas_at(int w, int h, float aspect, float px, float py)
{
    float f = sketch_px_per_unit(w, h, aspect), a = aspect > 0 ? aspect : 1;
    SketchPt c = { (px - 0.5f * (float)w) / f, (0.5f * (float)h - py) * a / f };
    return c;
}

void sketch_pixel_at(int w, int h, float aspect, SketchPt c, float *px_out, float *py_out)
{
    float f = sketch_px_per_unit(w, h, aspect), a = aspect > 0 ? aspect : 1;
    *px_out = 0.5f * (float)w + f * c.x;
    *py_out = 0.5f * (float)h - f * c.y / a;
}

/* ==== The scene ==== */

int sketch_scene(const Sketch *k, Scene *out, char *err, size_t errlen)
{
    if (k->npolys == 0)     /* the loader refuses a file without faces */
        return scene_build(out, NULL, 0, err, errlen);
    size_t len;
    char *text = sketch_to_text(k, &len);
    Mesh *m = calloc(1, sizeof *m);
    if (!text || !m) {
        free(text);
        free(m);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    int rc = mesh_parse(m, "sketch.obj", text, len, err, errlen);
    free(text);
    if (rc) {
        free(m);
        return -1;
    }
    if (scene_build(out, m, 1, err, errlen)) {
        mesh_free(m);
        free(m);
        return -1;
    }
    return 0;
}

void sketch_camera(Scene *s, int w, int h, float aspect)
{
    Camera *c = &s->cam;
    c->yaw = c->pitch = c->roll = 0;
    c->persp = 0;
    scene_fit(s);
    /* the projection puts fit_half at 90% of the picture at zoom 1
     * (project.c); the canvas wants sketch_px_per_unit per unit */
    double half_w = 0.5 * w, half_h = 0.5 * h * (aspect > 0 ? aspect : 1);
    double fitted = 0.9 * fmin(half_w / c->fit_half.x, half_h / c->fit_half.y);
    c->zoom = (float)(sketch_px_per_unit(w, h, aspect) / fitted);
    /* the view is centred on the fit's centre: pan it back to the origin
     * (pan is in radii, the z of the pan left 0 as the command line does) */
    c->pan = v3(c->centre.x / c->radius, c->centre.y / c->radius, 0);
}
