#ifndef ZV_SAVE_H
#define ZV_SAVE_H
/* save: a Mesh written back as a model file: binary STL, OBJ (with its
 * MTL when it has materials) or binary little-endian PLY. Knows nothing
 * of scenes, screens or terminals; --repair writes its result through it.
 *
 * What each format keeps of a mesh:
 *   stl  the faces as triangles (a polygon as the triangles that cover
 *        what zview draws of it: its fan, or cut by ear clipping when
 *        concave); positions only
 *   obj  every vertex in order (vertex colours as `v x y z r g b`), the
 *        faces as polygons, objects (`o`), points (`p`) and polylines
 *        (`l`), texture coordinates, and materials in an MTL beside it
 *        (Kd, d, map_Kd with its -o, -s and -clamp)
 *   ply  every vertex in order with its colour, the faces as polygons;
 *        a face colour each when every face has a material
 * Positions are the loaded floats bit for bit: binary formats store
 * them, and OBJ prints each as the shortest decimal that reads back to
 * the same float (savenum.c). Whatever a format cannot carry is counted
 * in SaveReport, so that the caller can say so.
 *
 * Every write is checked. A file is written to a temporary name beside
 * it and renamed when complete (safefile.h): a full disk leaves no half
 * file, and the old one, if any, as it was. */

#include <stddef.h>
#include <stdint.h>

#include "mesh.h"

typedef enum { SAVE_STL, SAVE_OBJ, SAVE_PLY, SAVE_COUNT } SaveFormat;

/* The format's name ("stl", "obj", "ply"). */
const char *save_format_name(SaveFormat f);
/* The format of a name (as --format gives it), or -1. */
int  save_format_from_name(const char *name);
/* The format a path's extension names (case aside: .stl .obj .ply), or -1. */
int  save_format_of_path(const char *path);

/* What a save wrote, and what the format could not carry. */
typedef struct {
    SaveFormat format;
    uint64_t   bytes;               /* of the model file (the MTL aside) */
    uint32_t   vertices, faces;     /* as written: STL's faces are triangles */
    uint32_t   polygons_split;      /* STL: faces of more than 3 corners, each written as triangles */
    uint32_t   faces_dropped;       /* STL: faces of fewer than 3 corners (no triangle) */
    uint32_t   points_dropped;      /* points the format cannot hold */
    uint32_t   lines_dropped;       /* polylines the format cannot hold */
    uint32_t   objects_merged;      /* objects beyond the first, written as one (STL, PLY) */
    uint32_t   materials_dropped;   /* materials the format cannot hold */
    int        colours_dropped;     /* vertex colours the format cannot hold */
    int        uvs_dropped;         /* texture coordinates the format cannot hold */
    int        ply_float_colours;   /* PLY: colours as floats (not every one was a byte's k/255) */
    char       mtl_path[4096];      /* OBJ: the material library written, "" none */
} SaveReport;

/* Write m to path in format f; "-" is standard output (an OBJ's
 * materials then go without their MTL, counted as dropped). Returns 0,
 * or -1 with "path: reason" in err (nothing left at path that was not
 * there; a file that was there untouched). rep may be NULL. */
int  save_mesh(const Mesh *m, const char *path, SaveFormat f, SaveReport *rep, char *err, size_t errlen);

/* ==== Numbers as text (savenum.c) ==== */

/* The longest text save_float writes, its NUL aside ("-1.17549435e-38"). */
#define SAVE_FLOAT_MAX 16

/* x as the shortest decimal (at most 9 significant digits) that a
 * correctly rounding reader turns back into x, bit for bit (-0 too):
 * "0.1", "-2.5e-07", "1e+20". NaN and infinities as "nan", "inf".
 * Writes no NUL; returns the length. */
int  save_float(char *buf, float x);
/* v in decimal; no NUL; returns the length (at most 10). */
int  save_u32(char *buf, uint32_t v);

#endif
