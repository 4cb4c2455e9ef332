/* overlay.c: lines and rings drawn over a finished picture (image.h),
 * for the problem in focus (app/focus.c): after the shading, the
 * contrast rule and the averaging of samples, so that the problem shows
 * over whatever hides it, in its own colour, at the picture's own
 * pixels. A line is stamped as squares of width x width pixels every
 * half pixel along it, once clipped to the picture (a point far off
 * screen costs nothing). */

#include <math.h>
#include <string.h>

#include "image.h"

static void stamp(Image *im, double x, double y, const uint8_t rgb[3], int width)
{
    int x0 = (int)floor(x - width * 0.5 + 0.5), y0 = (int)floor(y - width * 0.5 + 0.5);
    for (int j = y0; j < y0 + width; j++)
        for (int i = x0; i < x0 + width; i++) {
            if (i < 0 || j < 0 || i >= im->w || j >= im->h)
                continue;
            size_t k = (size_t)j * (size_t)im->w + (size_t)i;
            memcpy(im->rgb + 3 * k, rgb, 3);
            im->lit[k] = 1;
        }
}

/* Clip the line p + t (q - p), t in [*t0, *t1], to the box [lo, hi] on
 * one axis (Liang-Barsky); 0 when nothing is left. */
static int clip_axis(double p, double q, double lo, double hi, double *t0, double *t1)
{
    double d = q - p;
    if (d == 0)
        return p >= lo && p <= hi;
    double a = (lo - p) / d, b = (hi - p) / d;
    if (a > b) {
        double t = a;
        a = b;
        b = t;
    }
    *t0 = a > *t0 ? a : *t0;
    *t1 = b < *t1 ? b : *t1;
    return *t0 <= *t1;
}

void image_line(Image *im, double x0, double y0, double x1, double y1, const uint8_t rgb[3], int width)
{
    if (!(isfinite(x0) && isfinite(y0) && isfinite(x1) && isfinite(y1)) || width < 1)
        return;
    double t0 = 0, t1 = 1, m = width + 1;
    if (!clip_axis(x0, x1, -m, im->w + m, &t0, &t1) || !clip_axis(y0, y1, -m, im->h + m, &t0, &t1))
        return;
    double ax = x0 + t0 * (x1 - x0), ay = y0 + t0 * (y1 - y0);
    double bx = x0 + t1 * (x1 - x0), by = y0 + t1 * (y1 - y0);
    double len = hypot(bx - ax, by - ay);
    int steps = (int)ceil(len * 2);
    for (int s = 0; s <= steps; s++) {
        double t = steps ? (double)s / steps : 0;
        stamp(im, ax + t * (bx - ax), ay + t * (by - ay), rgb, width);
    }
}

void image_ring(Image *im, double cx, double cy, double r, const uint8_t rgb[3], int width)
{
    if (!(isfinite(cx) && isfinite(cy) && isfinite(r)) || r <= 0 || width < 1)
        return;
    if (cx + r < -width || cy + r < -width || cx - r > im->w + width || cy - r > im->h + width)
        return;
    int n = (int)ceil(2 * 3.14159265358979323846 * r * 2);
    n = n < 16 ? 16 : n;
    for (int s = 0; s < n; s++) {
        double a = 2 * 3.14159265358979323846 * s / n;
        stamp(im, cx + r * cos(a), cy + r * sin(a), rgb, width);
    }
}
