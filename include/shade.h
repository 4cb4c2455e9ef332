#ifndef ZV_SHADE_H
#define ZV_SHADE_H
/* shade: face ids + depths + the scene's normals, colours and light in,
 * an RGB image out. Knows nothing of terminals or file formats. */

#include <stddef.h>
#include <stdint.h>
#include "hsr.h"
#include "scene.h"

typedef enum { SHADE_LAMBERT = 0, SHADE_DEPTH, SHADE_ID, SHADE_COUNT } ShadeMode;

extern const char *const shade_names[SHADE_COUNT];
int shade_from_name(const char *name);          /* -1 if unknown */

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

/* Per-face colour cache, reused across frames (grows to the face count). */
typedef struct {
    uint32_t *stamp;    /* frame stamp per face: colour below is current */
    uint8_t  *rgb;      /* 3 per face */
    uint32_t  cap, frame;
} ShadeCache;

void shade_cache_free(ShadeCache *c);

/* Colour every pixel: lambert (ambient + two-sided Lambert from
 * scene->light on the face's base colour), depth (near white, far black,
 * over the frame's depth range) or id (a distinct colour per face id).
 * Background pixels get rgb 0 and lit 0. */
int  shade_frame(const Scene *s, const FrameBufs *fb, ShadeMode mode,
                 ShadeCache *cache, Image *out);

/* Distinct colour for a face id (also used by tests). */
void shade_id_colour(int32_t id, uint8_t rgb_out[3]);

#endif
