#ifndef ZV_IMAGE_H
#define ZV_IMAGE_H
/* image: an RGB picture and which of its pixels show the model; what
 * shading writes (src/shade/) and every presenter reads. A plain struct,
 * so that a presenter needs nothing else of the stages before it. */

#include <stddef.h>
#include <stdint.h>

typedef struct {
    int      w, h;
    uint8_t *rgb;       /* 3 * w * h, rows from the top */
    uint8_t *lit;       /* w * h: 1 where a face was drawn, 0 = background */
    size_t   cap;       /* pixels allocated */
} Image;

int  image_resize(Image *im, int w, int h);
void image_free(Image *im);
/* Supersampling's last step: each k x k block of src becomes one pixel
 * of dst ((src->w / k) x (src->h / k)), lit when at least half of its
 * samples are, coloured by the mean of its lit samples (the background's
 * colour is the terminal's, unknown here, so it is not mixed in). */
int  image_downsample(const Image *src, int k, Image *dst);

/* overlay.c: drawn over a finished picture, no depth test (the
 * problem in focus): a line from (x0, y0) to (x1, y1) and a circle of
 * radius r about (cx, cy), in pixels (y down), `width` pixels wide, in
 * one colour, the pixels lit. What falls outside the picture is left
 * out. */
void image_line(Image *im, double x0, double y0, double x1, double y1, const uint8_t rgb[3], int width);
void image_ring(Image *im, double cx, double cy, double r, const uint8_t rgb[3], int width);

#endif
