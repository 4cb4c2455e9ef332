#ifndef ZV_TEXTURE_INTERNAL_H
#define ZV_TEXTURE_INTERNAL_H
/* Internal to src/texture/. */

#include "texture.h"

/* Level 0 is in t->rgba (with room for all levels): fill in every
 * level's size and offset and compute levels 1.. from it (mip.c). */
void texture_build_levels(Texture *t);
/* t->lin from t->rgba's levels (mip.c), once the levels are final; left
 * NULL when out of memory. */
void texture_build_lin(Texture *t);
/* Bytes t->lin takes for a w x h level 0 (its padding included). */
uint64_t texture_lin_bytes_for(int w, int h);

/* Refuse a w x h image before decoding it: too big a side, or more
 * memory than the caller allows or the machine has ("name: a 20000x20
 * image (1 to 16384 per side)"). 0 or -1. */
int  texture_check_size(int w, int h, const char *name, uint64_t max_bytes, char *err, size_t errlen);
/* Level 0's texels for a w x h image, with room for every level (t
 * zeroed first). NULL out of memory. */
uint8_t *texture_alloc_levels(Texture *t, int w, int h);

/* tga.c: Truevision TGA, true colour or grey, plain or run-length
 * encoded (what COLLADA and 3DS models often carry). The probe: 0 with
 * the size when the header is one, else -1. */
int  texture_tga_probe(const uint8_t *b, size_t len, int *w_out, int *h_out);
int  texture_decode_tga(Texture *t, const uint8_t *b, size_t len, const char *name, uint64_t max_bytes, char *err,
                        size_t errlen);

#endif
