#ifndef ZV_SCENE_INTERNAL_H
#define ZV_SCENE_INTERNAL_H
/* scene internals shared by scene.c and edit.c. Not part of the public
 * API. */

#include "scene.h"

/* The colour of a face with none of its own in a scene of one object. */
extern const uint8_t scene_default_rgb[3];

/* Number the points, segments and wireframe edges after the faces: every
 * object's points, then every object's segments, then every object's
 * edges. -1 when the ids would pass INT32_MAX. */
int scene_number_prims(Scene *s);

/* "scene too large" messages: the files, then what passes which limit. */
void scene_too_large(const Mesh *meshes, int n, uint64_t nobjs, uint64_t nfaces, char *err, size_t errlen);

#endif
