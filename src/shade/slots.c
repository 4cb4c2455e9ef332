/* slots.c: the per-pixel Lambert and id paths that keep no per-face
 * arrays, for a huge mesh in a small picture (issue 21): a slot table
 * the size of the picture's, or each pixel straight from its face. Both
 * give shade.c's cached colours' bytes (the same shade_lambert_face).
 */

#include <stdlib.h>
#include <string.h>
#include "invariant.h"
#include "facecol.h"

/* The slot table for a frame of n pixels: a power of two at least twice
 * n (at most every pixel a face of its own, the table half full). */
static uint32_t slots_for(size_t n)
{
    uint64_t cap = 64;
    while (cap < 2 * (uint64_t)n)
        cap *= 2;
    return cap > ((uint64_t)1 << 31) ? 0 : (uint32_t)cap;
}

/* Do the frame's colours go through the slots? When the per-face arrays
 * (7 bytes a face, and whichever faces the polygons show touch their
 * pages: a 5M-face model drawn into a few hundred thousand samples
 * touched all 36 MB) outweigh the slots (8 bytes each): the memory a
 * frame touches is then the picture's, not the mesh's (issue 21). */
int shade_slots_pay(uint32_t nfaces, size_t n)
{
    uint32_t cap = slots_for(n);
    return cap && (uint64_t)cap * sizeof(ShadeSlot) < (uint64_t)nfaces * 7;
}

/* Distances (in pixels) the slots' loop fetches a face's corners and,
 * later, their positions ahead. */
#define SLOT_FAR  32
#define SLOT_NEAR 12

/* The pixels through the slots (shade_pixels' bytes): a face seen first,
 * or whose slot another face took, has its colour made again. */
int shade_pixels_slots(FaceColours *fc, ShadeCache *cache, const int32_t *ids, size_t n, uint8_t *rgb,
                       uint8_t *lit)
{
    uint32_t cap = slots_for(n);
    if (cap > cache->nslot) {
        ShadeSlot *t = realloc(cache->slot, (size_t)cap * sizeof *t);
        if (!t)
            return -1;
        cache->slot = t;
        cache->nslot = cap;
    }
    memset(cache->slot, 0xff, (size_t)cap * sizeof *cache->slot);     /* ids -1: empty */
    int shift = 32 - __builtin_ctz(cap);
    uint32_t nfaces = fc->s->nfaces;
    int32_t last = -1;
    const uint8_t *c = NULL;
    /* a computed normal (compact form, one object) is two dependent
     * scattered reads: each new face's slot and corners fetched SLOT_FAR
     * pixels ahead, and SLOT_NEAR ahead, unless its slot holds it, its
     * corners' positions (the dragon at 160x96, 4 samples: 2.0 -> 0.9 ms a
     * frame). The arrays are taken out of the scene first: GCC 12 drops
     * a prefetch whose address goes through the scene's structs. */
    const Scene *s = fc->s;
    const uint32_t *corner = NULL;
    const float *pos = NULL;
    if (fc->mode == SHADE_LAMBERT && !fc->nrm && !s->face_obj && !s->poly_start && s->nobjs == 1 &&
        s->objs[0].face_base == 0 && s->objs[0].poly_first == 0) {
        corner = s->poly_corner;
        pos = s->objs[0].mesh->pos;
    }
    for (size_t i = 0; i < n; i++) {
        if (corner && i + SLOT_FAR < n) {
            uint32_t f = (uint32_t)ids[i + SLOT_FAR];
            if (f < nfaces && f != (uint32_t)ids[i + SLOT_FAR - 1]) {
                __builtin_prefetch(&cache->slot[(f * 2654435769u) >> shift]);
                __builtin_prefetch(&corner[3 * (size_t)f]);
            }
            f = (uint32_t)ids[i + SLOT_NEAR];
            if (f < nfaces && f != (uint32_t)ids[i + SLOT_NEAR - 1] &&
                cache->slot[(f * 2654435769u) >> shift].id != (int32_t)f) {
                const uint32_t *c = &corner[3 * (size_t)f];
                __builtin_prefetch(&pos[3 * (size_t)c[0]]);
                __builtin_prefetch(&pos[3 * (size_t)c[1]]);
                __builtin_prefetch(&pos[3 * (size_t)c[2]]);
            }
        }
        int32_t id = ids[i];
        uint8_t *px = rgb + 3 * i;
        if (id < 0 || (uint32_t)id >= nfaces) {
            shade_pixels_range(fc, ids, i, i + 1, rgb, lit);      /* background, points and lines */
            continue;
        }
        if (id != last) {
            /* the hash's top bits index the table: cap is a power of
             * two, shift 32 - log2 cap */
            ZV_ASSERT((((uint32_t)id * 2654435769u) >> shift) < cap);
            ShadeSlot *sl = &cache->slot[((uint32_t)id * 2654435769u) >> shift];
            if (sl->id != id) {
                face_make(fc, id, sl->rgb);
                sl->id = id;
            }
            c = sl->rgb;
            last = id;
        }
        px[0] = c[0];
        px[1] = c[1];
        px[2] = c[2];
        lit[i] = 1;
    }
    return 0;
}

/* Distance (in pixels) the pixel pre-pass fetches ahead. */
#define PIXEL_AHEAD 24

/* Lambert shading of pixels [0, n) straight from the faces, no colour
 * cache: for a huge mesh in a small picture, where nearly every pixel
 * shows a face of its own and the cache's stamp and colour would be two
 * more scattered lines a pixel to read and write. The same colours as
 * the cache's (lambert_face), a face shown by neighbouring pixels
 * coloured once. */
void shade_pixels_direct(FaceColours *fc, const int32_t *ids, size_t n, uint8_t *rgb, uint8_t *lit)
{
    const Scene *s = fc->s;
    uint32_t nfaces = s->nfaces;
    int32_t last = -1;
    uint8_t c[3] = { 0, 0, 0 };
    for (size_t i = 0; i < n; i++) {
        if (i + PIXEL_AHEAD < n) {
            uint32_t f = (uint32_t)ids[i + PIXEL_AHEAD];
            if (f < nfaces) {
                if (fc->nrm)
                    __builtin_prefetch(&fc->nrm[3 * (size_t)f]);
                if (s->face_rgb)
                    __builtin_prefetch(&s->face_rgb[3 * (size_t)f]);
                if (s->face_obj)
                    __builtin_prefetch(&s->face_obj[f]);
            }
        }
        int32_t id = ids[i];
        uint8_t *px = rgb + 3 * i;
        if (id < 0 || (uint32_t)id >= nfaces) {
            px[0] = px[1] = px[2] = 0;
            lit[i] = 0;
            continue;
        }
        if (id != last) {
            face_make(fc, id, c);       /* Lambert: the caller's mode */
            last = id;
        }
        px[0] = c[0];
        px[1] = c[1];
        px[2] = c[2];
        lit[i] = 1;
    }
}
