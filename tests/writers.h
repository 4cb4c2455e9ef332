#ifndef ZV_TEST_WRITERS_H
#define ZV_TEST_WRITERS_H
/* writers: a loaded Mesh written back as every format zview reads
 * natively (and as glTF binary for assimp), so that the tests can load
 * one model in each and compare. Floats are written exactly (binary, or
 * %.9g, which round-trips a float). Each returns a malloc'd buffer and
 * its length, or NULL. */

#include <stddef.h>
#include "mesh.h"

char *w_obj(const Mesh *m, size_t *len);
char *w_stl_binary(const Mesh *m, size_t *len);   /* triangles only */
char *w_stl_ascii(const Mesh *m, size_t *len);    /* triangles only */
char *w_ply_binary(const Mesh *m, int big_endian, size_t *len);
char *w_ply_ascii(const Mesh *m, size_t *len);
char *w_off(const Mesh *m, size_t *len);
char *w_glb(const Mesh *m, size_t *len);          /* triangles only */

/* Write buf to path; 0 on success. */
int  w_save(const char *path, const char *buf, size_t len);

#endif
