#ifndef ZV_MESH_INTERNAL_H
#define ZV_MESH_INTERNAL_H
/* mesh internals: the loader interface (one MeshLoader per format file)
 * and the Mesh builder every loader fills its arrays through (build.c).
 * Input, errors and numbers are in reader.h. Not part of the public API. */

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "invariant.h"
#include "mesh.h"
#include "reader.h"

/* ==== Loaders ==== */

/* What a loader is given: the mesh to fill (zeroed), where messages go,
 * and where the input came from. */
typedef struct MeshCtx {
    Mesh       *m;
    MeshErr     err;       /* err.name: the input as messages name it */
    MeshFile   *file;      /* for the paging window; NULL for a memory buffer */
    const char *path;      /* the file on disk, against which files it names
                              (mtllib, glTF buffers) resolve; NULL: open none */
    const char *hint;      /* --format name or the file's extension (assimp) */
    double      tessellation; /* --tessellation: CAD surfaces' deflection over the diagonal, 0 default */
} MeshCtx;

/* PROBE_FAIR: the bytes read as this format but prove it less than a
 * magic does (a text format's first keyword); an extension naming
 * another reader wins over it. */
enum { PROBE_NO = 0, PROBE_MAYBE = 1, PROBE_SURE = 2, PROBE_FAIR = 3 };

typedef struct MeshLoader {
    const char *name;      /* --format name */
    const char *exts;      /* extensions it is chosen by, blank-separated, lower case */
    const char *what;      /* one line for --formats */
    /* Look at the first n bytes of an input of `size` bytes (size is
     * exact: a stream is read whole before probing). PROBE_SURE when the
     * format's magic or header is there, PROBE_MAYBE when the bytes are
     * plausible but prove nothing (text). NULL: chosen by name only. */
    int  (*probe)(const char *head, size_t n, uint64_t size);
    int  (*parse)(MeshCtx *c, const char *data, size_t len);
    /* Optional: read the file itself (libraries that open files a model
     * refers to); used instead of parse for a regular file. */
    int  (*parse_path)(MeshCtx *c, const char *path);
    int  text;             /* a text format: streams are read up to a NUL only */
    int  needs_magic;      /* chosen by extension only when the probe agrees */
    /* read by a library opened at run time (OCCT: step.c): the sandbox's
     * child opens it before it confines itself, and budgets its memory
     * as a library's (budget.c) */
    int  library;
} MeshLoader;

extern const MeshLoader mesh_loader_obj, mesh_loader_stl, mesh_loader_ply, mesh_loader_off,
    mesh_loader_xyz, mesh_loader_step, mesh_loader_iges, mesh_loader_brep;
/* step.c: can OpenCASCADE's shim be opened (it is opened on first use)?
 * Its version ("OCCT 7.6.3"), or "OCCT not found". */
int  mesh_occt_available(void);
const char *mesh_occt_version(char *buf, size_t n);
#ifdef ZV_ASSIMP
extern const MeshLoader mesh_loader_assimp;
/* Can the library be opened (it is opened on first use)? */
int  mesh_assimp_available(void);
/* Does assimp read files of this extension (no dot, any case)? */
int  mesh_assimp_has_ext(const char *ext);
/* Call fn for each extension assimp reads, with its importer's name. */
void mesh_assimp_list(void (*fn)(const char *ext, const char *what, void *ctx), void *ctx);
const char *mesh_assimp_version(char *buf, size_t n);
#endif

/* ==== PLY streams (used by format.c) ==== */

/* From a PLY stream's head: how many bytes the file can have at most
 * (its header and the largest body the header allows, and a byte more;
 * 0, no bound, when the head does not hold the whole header), and
 * whether it is ascii (then only text: a NUL ends the stream). */
uint64_t mesh_ply_stream_max(const char *head, size_t n, int *ascii);

/* ==== MTL (used by obj.c) ==== */

/* Material libraries bigger than this are not read (a warning says
 * so): a real one is kilobytes, and a material takes 80 bytes. */
#define MESH_MTL_MAX_BYTES ((uint64_t)256000000)

struct MeshBuild;
/* Append the materials of MTL text to the mesh b builds (its mats,
 * grown as needed), with the textures they name (map_Kd, a path
 * relative to the library's folder). `name` is the file's path, for
 * warnings (given to b's me_warn) and for those textures: bad lines are
 * skipped with one warning per file, and binary data (a NUL or another
 * control byte) ends the reading with a warning. file: the paging
 * window, or NULL for memory. Returns 0, or -1 out of memory. */
int  mesh_mtl_parse(struct MeshBuild *b, const char *name, MeshFile *file, const char *data, size_t len);

/* ==== Building a Mesh ==== */

typedef struct {
    uint64_t *slot;        /* RGBA key << 32 | material index + 1; 0 = empty */
    uint32_t  cap, used;   /* cap: a power of two, or 0 */
} ColourIndex;

typedef struct MeshBuild {
    Mesh       *m;
    MeshErr    *e;
    size_t      vcap;      /* vertices pos (and rgb) can hold */
    int         vexact;    /* vcap is a count read from a header (prefault rgb too) */
    size_t      fcap;      /* faces face_mat can hold; face_start holds fcap + 1 */
    size_t      ccap;      /* corners */
    size_t      ncorner;
    size_t      pcap;      /* points point[] can hold */
    size_t      lcap;      /* polylines: line_start holds lcap + 1 */
    size_t      lccap;     /* polyline corners */
    size_t      nlcorner;
    size_t      ocap;
    uint32_t    mcap;
    size_t      uvcap;     /* texture coordinates uv can hold (per vertex: vcap) */
    int         uv_per_vertex; /* uv has an entry per vertex (PLY, assimp), else per corner_uv */
    uint32_t    tcap;      /* textures tex can hold */
    ColourIndex colours;   /* face colours -> materials */
    char        basename[MESH_NAME_MAX];
} MeshBuild;

/* Zero m, name it (path copied; the default object is named after the
 * file without folder or extension). -1 out of memory. */
int  mb_start(MeshBuild *b, Mesh *m, MeshErr *e, const char *name);
/* Room for at least this many more vertices, faces and corners, so that
 * loaders that know their counts allocate once (exactly). */
int  mb_reserve(MeshBuild *b, size_t verts, size_t faces, size_t corners);
/* The same; exact = 0 for a guess (its pages are not faulted in ahead). */
int  mb_reserve_ex(MeshBuild *b, size_t verts, size_t faces, size_t corners, int exact);
/* Before allocating for counts a header states: refuse them when the
 * polygons (faces and points) pass the limit, or `bytes` (the estimate
 * of the mesh and the scene built from it) pass the memory the load may
 * take: "what need about 9.1 GB; 7.2 GB available", what being the
 * counts as the message names them ("180,000,000 triangles"). */
int  mb_afford(MeshBuild *b, uint64_t polys, uint64_t bytes, const char *what);
/* The estimate for counts from a header: the mesh's arrays and what the
 * scene adds a face (its normal, colour, object) or a point. */
uint64_t mb_estimate(uint64_t verts, int rgb, uint64_t faces, uint64_t corners, uint64_t points);
/* mb_afford for a header's vertex and face counts (a file without faces
 * is a point cloud: its vertices are points). */
int  mb_afford_counts(MeshBuild *b, uint64_t verts, int rgb, uint64_t faces);
/* Start vertex colours: earlier vertices become white. */
int  mb_want_rgb(MeshBuild *b);
int  mb_grow_verts(MeshBuild *b);
int  mb_grow_faces(MeshBuild *b);
int  mb_grow_corners(MeshBuild *b);
/* The per-face materials, made on the first face with one (earlier
 * faces, and the rest of the capacity, -1): a mesh without materials
 * keeps none (Mesh.face_mat NULL). NULL out of memory. */
int32_t *mb_face_mats(MeshBuild *b);
/* Room for n more corners. */
int  mb_room_corners(MeshBuild *b, size_t n);

static inline int mb_vertex(MeshBuild *b, float x, float y, float z)
{
    Mesh *m = b->m;
    if (m->nverts == b->vcap && mb_grow_verts(b))
        return -1;
    float *d = m->pos + 3 * (size_t)m->nverts;
    d[0] = x;
    d[1] = y;
    d[2] = z;
    if (m->rgb) {
        float *c = m->rgb + 3 * (size_t)m->nverts;
        c[0] = c[1] = c[2] = 1.0f;
    }
    m->nverts++;
    return 0;
}

static inline int mb_corner(MeshBuild *b, uint32_t v)
{
    if (b->ncorner == b->ccap && mb_grow_corners(b))
        return -1;
    b->m->corner[b->ncorner++] = v;
    return 0;
}

/* Close the face whose corners start at corner `first` (the corners
 * added since). The caller checks it has at least 3. */
static inline int mb_face_end(MeshBuild *b, size_t first, int32_t mat)
{
    Mesh *m = b->m;
    /* A face's corners are the run since the previous face ended, at
     * least 3: face_start must rise by 3 or more a face, or the scene
     * would make polygons of fewer corners (or of another face's). */
    ZV_ASSERT(first <= b->ncorner && b->ncorner - first >= 3 &&
              (m->nfaces == 0 || first >= (size_t)m->face_start[m->nfaces - 1] + 3));
    if (m->nfaces == b->fcap && mb_grow_faces(b))
        return -1;
    if (mat != -1 && !m->face_mat && !mb_face_mats(b))
        return -1;
    m->face_start[m->nfaces] = (uint32_t)first;
    if (m->face_mat)
        m->face_mat[m->nfaces] = mat;
    m->nfaces++;
    m->info.triangles += (uint32_t)(b->ncorner - first - 2);
    return 0;
}

/* ==== Texture coordinates and textures (meshtex.c) ==== */

/* Append a texture coordinate (OBJ vt; v already turned to run down). */
int  mb_uv(MeshBuild *b, float u, float v);
/* The texture coordinate entry of the corner just added (MESH_NO_UV:
 * none); the per-corner array is made on first use, earlier corners
 * getting none. */
int  mb_corner_uv(MeshBuild *b, uint32_t uvi);
/* Texture coordinates per vertex from here on (the array grows with the
 * vertices; earlier ones get 0, 0): the caller writes uv[2 v], uv[2 v + 1]
 * after each mb_vertex. */
int  mb_want_vertex_uv(MeshBuild *b);
/* A texture the model names, decoded now or left pending (MeshErr's
 * tex_defer_side), once per name and wrap mode: its index in Mesh.tex,
 * or -1 when none is to be had (--no-textures) or out of memory (*oom
 * set). name: what messages call it; the bytes come from the file at
 * path, or from data (copied when kept). A texture that cannot be read
 * warns once, naming it, and stays in the list as failed (its faces
 * show their base colour). */
int32_t mb_texture(MeshBuild *b, const char *name, const char *path, const void *data, size_t len,
                   TexWrap wrap_u, TexWrap wrap_v, int *oom);
/* The same for texels already decoded (assimp's uncompressed ones):
 * rgba, 4 bytes a texel, sRGB. */
int32_t mb_texture_rgba(MeshBuild *b, const char *name, const uint8_t *rgba, int w, int h, TexWrap wrap_u,
                        TexWrap wrap_v, int *oom);
/* A texture that cannot be had (why says so): listed as failed, with
 * the warning. */
int32_t mb_texture_missing(MeshBuild *b, const char *name, const char *why, TexWrap wrap_u, TexWrap wrap_v,
                           int *oom);
/* A material's texture fields, none set. */
void mb_material_no_texture(Material *mt);

/* datauri.c: glTF JSON with every image data: URI that is not base64
 * replaced by one whose bytes are MESH_BROKEN_IMAGE (assimp refuses a
 * whole model for one such image). A malloc'd copy and its length, and
 * how many were replaced; NULL when none was (or out of memory). */
#define MESH_BROKEN_IMAGE "zview: not base64"
char *mesh_gltf_mend_images(const char *json, size_t len, size_t *len_out, int *n_out);
/* Free the textures and texture coordinates of m. */
void mesh_free_textures(Mesh *m);

int  mb_grow_points(MeshBuild *b);
int  mb_grow_lines(MeshBuild *b);
int  mb_grow_line_corners(MeshBuild *b);

/* A point at vertex v (an index the caller checked, or checks later). */
static inline int mb_point(MeshBuild *b, uint32_t v)
{
    Mesh *m = b->m;
    if (m->npoints == b->pcap && mb_grow_points(b))
        return -1;
    m->point[m->npoints++] = v;
    return 0;
}

static inline int mb_line_corner(MeshBuild *b, uint32_t v)
{
    if (b->nlcorner == b->lccap && mb_grow_line_corners(b))
        return -1;
    b->m->line_corner[b->nlcorner++] = v;
    return 0;
}

/* Close the polyline whose corners start at `first` (the caller checks
 * it has at least 2). */
static inline int mb_line_end(MeshBuild *b, size_t first)
{
    Mesh *m = b->m;
    /* a polyline of k corners is k - 1 segments (scene.c): at least one */
    ZV_ASSERT(first <= b->nlcorner && b->nlcorner - first >= 2);
    if (m->nlines == b->lcap && mb_grow_lines(b))
        return -1;
    m->line_start[m->nlines++] = (uint32_t)first;
    return 0;
}

/* Faces, points and lines from here on belong to a new object (the
 * current one is renamed instead when it has none of them yet). An empty
 * name: the file's. */
int  mb_object(MeshBuild *b, const char *name, size_t len);
/* The same where the counts were nf, np, nl (faces, points, lines):
 * what a merge of pieces of a file places (objpar.c). */
int  mb_object_at(MeshBuild *b, const char *name, size_t len, uint32_t nf, uint32_t np, uint32_t nl);
/* Append a material; returns its index or -1 out of memory. */
int32_t mb_material(MeshBuild *b, const char *name, float r, float g, float bl, float alpha);
/* The material of a face colour (8 bits a channel), made once per
 * distinct colour and named "#rrggbb". -1 out of memory. */
int32_t mb_colour(MeshBuild *b, uint8_t r, uint8_t g, uint8_t bl, uint8_t a);
/* Finish: close faces, lines and objects, vertex ranges, give back
 * slack. With cloud_ok (the file gave vertices and no face, line or
 * point at all), the vertices make a point cloud (every vertex a point,
 * one object spanning them). Nothing to show is an error ("no faces";
 * when statements were skipped, the first one's message). Returns 0 or
 * -1. */
int  mb_finish(MeshBuild *b, int cloud_ok);
/* Free what was built (the mesh is left empty). */
void mb_abort(MeshBuild *b);

/* ==== Merging identical vertices ==== */

/* Loaders of formats that repeat each corner's position (STL) merge
 * equal positions, exact bit patterns, in one hash pass, so that the
 * front end transforms each point once and the mesh is as small as an
 * OBJ's. A slot holds 32 bits of the position's hash and its vertex
 * index + 1 (0 = empty): 8 bytes, so the table stays small enough to
 * live in cache, and a probe compares positions only when the hash
 * bits agree, almost only for the vertex it is looking for, which was
 * usually added recently (its position is still in cache too). */
typedef struct {
    uint64_t *slot;
    uint32_t  mask;           /* capacity - 1, a power of two minus one */
    uint32_t  used;
} VertMerge;

/* Room for about `expect` distinct vertices at most half full. */
int  vm_init(VertMerge *vm, size_t expect);
void vm_free(VertMerge *vm);
int  vm_grow(VertMerge *vm, const float *pos);

static inline uint64_t vm_hash(uint32_t x, uint32_t y, uint32_t z)
{
    uint64_t h = (uint64_t)x * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t)y * 0xC2B2AE3D27D4EB4Full;
    h ^= (uint64_t)z * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 32);
}

static inline void vm_prefetch(const VertMerge *vm, uint64_t h)
{
    __builtin_prefetch(&vm->slot[(uint32_t)(h >> 32) & vm->mask]);
}

/* The index of the vertex with these coordinate bits (h = vm_hash of
 * them), appended to the mesh if new. Returns 0, -1 out of memory. */
static inline __attribute__((always_inline)) int vm_add(VertMerge *vm, MeshBuild *b, const uint32_t bits[3], uint64_t h,
                         uint32_t *idx)
{
    /* grown before the probe (not from inside it), so that this stays
     * a loop the compiler can inline into the loaders' hot loops */
    if ((vm->used + 1) * 2 > vm->mask + 1 && vm_grow(vm, b->m->pos))
        return me_oom(b->e);
    uint32_t tag = (uint32_t)h;
    const float *pos = b->m->pos;
    for (uint32_t i = (uint32_t)(h >> 32) & vm->mask;; i = (i + 1) & vm->mask) {
        uint64_t s = vm->slot[i];
        if (!s) {
            float p[3];
            memcpy(p, bits, sizeof p);
            if (mb_vertex(b, p[0], p[1], p[2]))
                return -1;
            vm->slot[i] = (uint64_t)tag << 32 | b->m->nverts;
            vm->used++;
            *idx = b->m->nverts - 1;
            return 0;
        }
        if ((uint32_t)(s >> 32) == tag && memcmp(pos + 3 * (size_t)((uint32_t)s - 1), bits, 12) == 0) {
            *idx = (uint32_t)s - 1;
            return 0;
        }
    }
}

/* Is this float's bit pattern a NaN or an infinity? */
static inline int bits_nonfinite(uint32_t u) { return (u & 0x7f800000u) == 0x7f800000u; }

#endif
