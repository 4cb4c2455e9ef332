#ifndef ZV_TEXTURE_INTERNAL_H
#define ZV_TEXTURE_INTERNAL_H
/* Internal to src/texture/. */

#include "texture.h"

/* Level 0 is in t->rgba (with room for all levels): fill in every
 * level's size and offset and compute levels 1.. from it (mip.c). */
void texture_build_levels(Texture *t);

#endif
