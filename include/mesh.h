#ifndef ZV_MESH_H
#define ZV_MESH_H
/* mesh: model files in, plain arrays out. Native loaders for Wavefront
 * OBJ (+ MTL), STL (binary and ASCII), PLY (ascii and binary) and OFF;
 * the long tail (glTF, FBX, 3DS, COLLADA, 3MF, ...) through assimp when
 * the build has it. Knows nothing of cameras, screens or terminals.
 *
 * A Mesh is one file. Its faces keep their polygon form (any number of
 * corners); corner indices are resolved to 0-based absolute vertex
 * indices at load time (negative OBJ indices included). Face ids are
 * face indices in load order in every format. Objects (OBJ `o`, the
 * nodes of a glTF scene) are contiguous ranges of faces. */

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define MESH_NAME_MAX 64

typedef struct {
    char  name[MESH_NAME_MAX];
    float kd[3];        /* diffuse (base) colour, linear 0..1 */
    float alpha;        /* `d`, or 1 - `Tr`; 1 = opaque */
} Material;

typedef struct {
    char     name[MESH_NAME_MAX]; /* from `o`, else the file's base name */
    uint32_t face_first;          /* first face of this object */
    uint32_t face_count;
    uint32_t vert_min, vert_max;  /* vertex index range its faces use (inclusive) */
} MeshObject;

typedef struct {
    char     format[32];    /* what read it: "obj", "stl binary", "ply ascii", "gltf (assimp)" */
    uint64_t bytes;         /* size of the input */
    uint64_t corners_read;  /* STL: corners in the file, before merging equal vertices */
    uint32_t points, lines; /* point and line primitives not kept (see Mesh) */
    uint32_t texcoords;     /* `vt` count */
    uint32_t normals;       /* `vn` count */
    uint32_t unknown;       /* statements skipped (unknown keywords) */
    char     first_unknown[32]; /* the first unknown keyword, for --info */
    uint32_t triangles;     /* sum of (corners - 2) over faces */
    uint32_t groups;        /* `g` statements */
    double   load_ms;       /* wall time of mesh_load, MTL included */
    double   load_cpu_ms;   /* the loading thread's CPU time over the same */
} MeshInfo;

typedef struct Mesh {
    char      *path;        /* as given on the command line */
    uint32_t   nverts;
    float     *pos;         /* 3 * nverts: x y z (divided by w when w given) */
    float     *rgb;         /* 3 * nverts vertex colours 0..1, or NULL if none */
    uint32_t   nfaces;
    uint32_t  *face_start;  /* nfaces + 1 offsets into corner[] */
    uint32_t  *corner;      /* 0-based vertex index per face corner */
    int32_t   *face_mat;    /* material index per face, -1 = default colour */
    Material  *mats;
    uint32_t   nmats;
    MeshObject *objs;       /* at least one */
    uint32_t   nobjs;
    /* Points and polylines (OBJ p and l, PLY point clouds, glTF POINTS
     * and LINES) belong here, beside the faces: a later change adds
     * `uint32_t nlines; uint32_t *line_start, *line_corner;` (polylines
     * as runs of vertex indices, as faces are) and draws the vertices no
     * face or line uses as points. Loaders already keep such vertices (a
     * PLY without faces loads its vertices and no faces, its object
     * spanning them) and count what they drop in info.points and
     * info.lines. */
    MeshInfo   info;
} Mesh;

/* Load `path` into *m (zeroed first); "-" reads standard input. The
 * format is told by content first (magic bytes, header), by extension
 * second; `format` (a name mesh_format_valid accepts) forces one, NULL
 * detects. Returns 0 on success. On failure returns -1, leaves *m
 * empty, and writes "path:line: message" (text), "path: byte N:
 * message" (binary) or "path: message" into err; a file no loader
 * accepts gets "path: not a model zview can read (gzip data; formats:
 * ...)". Warnings (a missing MTL file) go to stderr prefixed
 * "zview: warning: ". */
int  mesh_load(Mesh *m, const char *path, char *err, size_t errlen);
int  mesh_load_as(Mesh *m, const char *path, const char *format, char *err, size_t errlen);

/* Parse a model already in memory (what a fuzz harness calls): `path`
 * names it in messages, gives the extension, and is what files it
 * refers to (mtllib) are resolved against; path NULL: named "(input)",
 * and no other file is opened. format NULL: detected as mesh_load does.
 * No state outside *m and the arguments. Same contract as mesh_load. */
int  mesh_parse_buffer(Mesh *m, const char *path, const char *format, const void *data,
                       size_t len, char *err, size_t errlen);

/* OBJ text in memory: mesh_parse_buffer with format "obj". */
int  mesh_parse(Mesh *m, const char *path, const char *text, size_t len,
                char *err, size_t errlen);

void mesh_free(Mesh *m);

/* Is `name` a format this build reads (obj, stl, ply, off; with assimp
 * also "assimp" and every extension assimp reads)? */
int  mesh_format_valid(const char *name);
/* One line per format, for --formats: name, native or assimp, what. */
void mesh_formats_print(FILE *f);
/* The short list for messages: "obj stl ply off + assimp: glb gltf ...". */
void mesh_formats_short(char *buf, size_t n);

/* Reverse every face's corner order (--flip: the other winding). */
void mesh_flip_winding(Mesh *m);

#endif
