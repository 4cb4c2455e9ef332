#ifndef ZV_OCCTSHIM_H
#define ZV_OCCTSHIM_H
/* occtshim: the plain C face of the OpenCASCADE shim (occtshim.cpp, a
 * shared library zview opens at run time: src/mesh/step.c). OCCT has no
 * C API; the shim reads a STEP, IGES or BREP file, tessellates its faces
 * and hands back triangles grouped by object, with the objects' names,
 * the colours the file gives and its length unit. Included by C and C++. */

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped when the struct or the functions change: a shim of another
 * version is refused by name. */
#define ZV_OCCT_ABI 1

enum { ZV_OCCT_STEP = 0, ZV_OCCT_IGES = 1, ZV_OCCT_BREP = 2 };

/* The default linear deflection, a fraction of the model's bounding-box
 * diagonal, and the angular one (radians). */
#define ZV_OCCT_DEFLECTION 0.001
#define ZV_OCCT_ANGULAR 0.5

typedef struct {
    uint32_t  nverts;
    float    *pos;          /* 3 per vertex, in the file's unit; each B-rep face has its own */
    uint32_t  ntris;
    uint32_t *tri;          /* 3 vertex indices per triangle, outward winding */
    uint32_t *tri_obj;      /* per triangle: its object; objects come in order, each one run */
    int32_t  *tri_colour;   /* per triangle: its colour, -1 none */
    uint32_t  nobjs;
    char    **obj_name;     /* per object, UTF-8 as the file has it ("" none) */
    uint32_t  ncolours;
    float    *colour;       /* 4 per colour: r g b a in 0..1 (sRGB as the file states them) */
    char      unit[8];      /* "mm", "in", "m", ...; "" when the format states none (BREP) */
    double    deflection;   /* the linear deflection used, in the file's unit */
    double    diagonal;     /* the bounding box's diagonal, in the file's unit */
    uint32_t  faces;        /* B-rep faces */
    uint32_t  bare_faces;   /* faces the mesher gave no triangles */
} ZvOcctMesh;

/* What the shim is, for --formats: "OCCT 7.6.3". */
typedef const char *(*ZvOcctVersionFn)(void);
/* Everything the reading needs at first use (its statics, the XCAF
 * application), done before the sandbox confines the process. 0 or -1. */
typedef int (*ZvOcctInitFn)(void);
/* Read the file at path as kind (ZV_OCCT_*), tessellated with linear
 * deflection rel_deflection times the bounding box's diagonal (<= 0:
 * ZV_OCCT_DEFLECTION). 0 with *out filled (free it with zv_occt_free),
 * or -1 with one line in err (no file name: the caller adds it). */
typedef int (*ZvOcctReadFn)(const char *path, int kind, double rel_deflection, ZvOcctMesh *out, char *err,
                            size_t errlen);
typedef void (*ZvOcctFreeFn)(ZvOcctMesh *m);
typedef int (*ZvOcctAbiFn)(void);

int         zv_occt_abi(void);
const char *zv_occt_version(void);
int         zv_occt_init(void);
int         zv_occt_read(const char *path, int kind, double rel_deflection, ZvOcctMesh *out, char *err,
                         size_t errlen);
void        zv_occt_free(ZvOcctMesh *m);

#ifdef __cplusplus
}
#endif

#endif
