#ifndef ZV_MESH_H
#define ZV_MESH_H
/* mesh: Wavefront OBJ + MTL loading. A file in, plain arrays out.
 * Knows nothing of cameras, screens or terminals.
 *
 * A Mesh is one file. Its faces keep their polygon form (any number of
 * corners); corner indices are resolved to 0-based absolute vertex
 * indices at load time (negative OBJ indices included). `o` statements
 * split the file into objects, each a contiguous range of faces. */

#include <stddef.h>
#include <stdint.h>

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
    uint64_t bytes;         /* size of the OBJ text */
    uint32_t texcoords;     /* `vt` count */
    uint32_t normals;       /* `vn` count */
    uint32_t unknown;       /* statements skipped (unknown keywords) */
    char     first_unknown[32]; /* the first unknown keyword, for --info */
    uint32_t triangles;     /* sum of (corners - 2) over faces */
    uint32_t groups;        /* `g` statements */
    double   load_ms;       /* wall time of mesh_load, MTL included */
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
    MeshInfo   info;
} Mesh;

/* Load `path` into *m (zeroed first). Returns 0 on success. On failure
 * returns -1, leaves *m empty, and writes "path:line: message" (or
 * "path: message" when no line applies) into err. Warnings (a missing
 * MTL file) go to stderr prefixed "zview: warning: ". */
int  mesh_load(Mesh *m, const char *path, char *err, size_t errlen);

/* Parse OBJ text already in memory; `path` names it in errors and is
 * the folder mtllib is resolved against. Same contract as mesh_load. */
int  mesh_parse(Mesh *m, const char *path, const char *text, size_t len,
                char *err, size_t errlen);

void mesh_free(Mesh *m);

#endif
