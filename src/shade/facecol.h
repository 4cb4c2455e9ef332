/* facecol.h: what shade.c and slots.c share (private to src/shade): the
 * per-face colours of a frame and how they are made, and the per-pixel
 * paths that keep no per-face arrays (slots.c). */
#ifndef ZV_FACECOL_H
#define ZV_FACECOL_H

#include "shade.h"

/* The linear part of view * object for one object: rotates (and scales)
 * object-space normals into view space. */
typedef struct {
    int   obj;          /* -1 = empty slot */
    float m[3][3];
} NormalMat;

#define NMAT_SLOTS 64   /* direct-mapped by object index, lives on the stack */

void shade_normal_mat(const Scene *s, const Mat4 *view, int obj, NormalMat *out);
/* Lambert colour of one face, two-sided (|n.l|) so faces seen from the
 * back are lit like their fronts. nrm: the faces' normals when at hand
 * (NULL: computed, scene.h). */
void shade_lambert_face(const Scene *s, const float *nrm, const NormalMat *nm, uint32_t face, uint8_t out[3]);

/* What the per-pixel loops need: the per-face colours (computed once a
 * frame, on first sight, stamped with the frame) and how to make them. */
typedef struct {
    const Scene *s;
    ShadeMode    mode;
    uint32_t     frame;
    uint32_t    *stamp;
    uint8_t     *crgb;          /* 3 per face, and one byte more (4-byte loads) */
    int          current;       /* every face the pixels can show is coloured: no stamp checks */
    Mat4         view;
    NormalMat    nmat[NMAT_SLOTS];
    const float *nrm;           /* the faces' normals when at hand (dense_normals), else NULL */
} FaceColours;

/* Face id's colour into c. */
static inline void face_make(FaceColours *fc, int32_t id, uint8_t *c)
{
    if (fc->mode == SHADE_ID) {
        shade_id_colour(id, c);
    } else {
        const Scene *s = fc->s;
        int obj = s->face_obj ? s->face_obj[id] : 0;
        NormalMat *nm = &fc->nmat[obj & (NMAT_SLOTS - 1)];
        if (nm->obj != obj)
            shade_normal_mat(s, &fc->view, obj, nm);
        shade_lambert_face(s, fc->nrm, nm, (uint32_t)id, c);
    }
}

/* Pixels [i0, i1) one at a time, through the stamped per-face colours. */
void shade_pixels_range(FaceColours *fc, const int32_t *ids, size_t i0, size_t i1, uint8_t *rgb, uint8_t *lit);

/* slots.c: does a frame of nfaces faces and n pixels colour through the
 * slot table; the pixels through it (-1 out of memory); and Lambert
 * shading straight from the faces, no colour cache. */
int  shade_slots_pay(uint32_t nfaces, size_t n);
int  shade_pixels_slots(FaceColours *fc, ShadeCache *cache, const int32_t *ids, size_t n, uint8_t *rgb, uint8_t *lit);
void shade_pixels_direct(FaceColours *fc, const int32_t *ids, size_t n, uint8_t *rgb, uint8_t *lit);

#endif
