#ifndef ZV_MESH_INTERNAL_H
#define ZV_MESH_INTERNAL_H
/* mesh internals shared by obj.c and mtl.c: the whole-file reader, the
 * number parser and the MTL loader. Not part of the public API. */

#include <stddef.h>
#include <stdint.h>

#include "mesh.h"

/* ==== Whole-file input ==== */

/* A file's bytes, mapped (regular files) or read into the heap (pipes,
 * devices). The data is NOT NUL-terminated: always parse with `len`. */
typedef struct {
    const char *data;
    size_t      len;
    void       *map;     /* mmap base, or NULL */
    char       *heap;    /* malloc'd copy, or NULL */
} MeshFile;

/* Open and read `path`. On failure returns -1 and writes a message
 * without the path prefix ("cannot open: ...", "is a directory") into
 * msg. An empty file succeeds with len 0. */
int  mesh_file_open(MeshFile *f, const char *path, char *msg, size_t msglen);
void mesh_file_close(MeshFile *f);

/* ==== Numbers ==== */

enum {
    MESH_NUM_OK = 0,
    MESH_NUM_BAD,        /* not a number, or junk glued to it */
    MESH_NUM_NONFINITE,  /* "nan", "inf", "infinity" (any case, signed) */
    MESH_NUM_RANGE       /* finite text whose value overflows a float */
};

/* Parse one decimal float at *pp (sign, digits, '.', e/E exponent).
 * The number must be followed by the end, a space, a tab or a CR.
 * On success advances *pp past it. Never reads at or past `end`. */
int  mesh_parse_float(const char **pp, const char *end, float *out);

/* True if [p, end) holds a control byte other than tab and CR, which no
 * OBJ or MTL text line can carry. */
int  mesh_has_binary(const char *p, const char *end);

/* ==== MTL ==== */

/* Append the materials of the MTL file at `mtlpath` to *mats (array of
 * *cap entries, *nmats used; grown as needed). Returns 0 on success,
 * -1 if the file cannot be read (the caller warns). Malformed lines are
 * skipped with one warning per file on stderr. Out of memory: -2. */
int  mesh_mtl_load(const char *mtlpath, Material **mats, uint32_t *nmats,
                   uint32_t *cap);

#endif
