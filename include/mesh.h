#ifndef ZV_MESH_H
#define ZV_MESH_H
/* mesh: model files in, plain arrays out. Native loaders for Wavefront
 * OBJ (+ MTL), STL (binary and ASCII), PLY (ascii and binary), OFF and
 * the XYZ text of scanners (x y z [r g b] a line);
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

#include "texture.h"

#define MESH_NAME_MAX 64

/* An axis of the model's coordinates: which one points up (--up, the
 * viewer's U key, what a file's format says) or which way its front
 * faces. The scene turns the model by quarter turns so that the up axis
 * points up, exactly (scene.h). */
typedef enum { UP_Y, UP_Z, UP_X, UP_NEG_Y, UP_NEG_Z, UP_NEG_X, UP_COUNT } UpAxis;

typedef struct {
    char  name[MESH_NAME_MAX];
    float kd[3];        /* diffuse (base) colour, linear 0..1 */
    float alpha;        /* `d`, or 1 - `Tr`; 1 = opaque */
    /* The base-colour texture (MTL map_Kd, glTF baseColorTexture): an
     * index into Mesh.tex, -1 = none. It multiplies kd. Texture
     * coordinates are transformed first: uv * tex_scale + tex_off (MTL
     * -s and -o, KHR_texture_transform). */
    int32_t tex;
    float   tex_off[2], tex_scale[2];
} Material;

/* A texture a model names. Decoded while loading (img), or, when it is
 * big and the load was asked to defer such (MeshLoadOpts.tex_defer_side),
 * left pending with its source for mesh_texture_decode on another
 * thread: the picture does not wait for a 16k x 16k image. */
typedef enum { MTEX_OK = 0, MTEX_FAILED, MTEX_PENDING } MeshTexState;

typedef struct {
    char        *name;      /* as the model names it: a path, "*0" (embedded), "data:" URI (shortened) */
    MeshTexState state;
    Texture      img;       /* the texels when MTEX_OK */
    int          src_w, src_h;  /* the image's own size (0: unknown) */
    int          halved;    /* img is the image halved this many times (to TEX_FIT_SIDE) */
    /* MTEX_PENDING: where the image is, a file or a copy of its bytes */
    char        *path;
    void        *data;
    size_t       len;
} MeshTexture;

/* Images are decoded to at most this many texels a side (halved until
 * they fit): more detail than a picture of 4096 samples can show is not
 * kept, and 16k x 16k texels would take 1.4 GB. */
#define TEX_FIT_SIDE 4096

typedef struct {
    char     name[MESH_NAME_MAX]; /* from `o`, else the file's base name */
    uint32_t face_first;          /* first face of this object */
    uint32_t face_count;
    uint32_t vert_min, vert_max;  /* vertex index range its faces, points and lines use (inclusive) */
    uint32_t point_first, point_count;  /* its points (Mesh.point) */
    uint32_t line_first, line_count;    /* its polylines (Mesh.line_start) */
} MeshObject;

typedef struct {
    char     format[32];    /* what read it: "obj", "stl binary", "ply ascii", "gltf (assimp)" */
    uint64_t bytes;         /* size of the input */
    uint64_t corners_read;  /* STL: corners in the file, before merging equal vertices */
    uint32_t texcoords;     /* OBJ: `vt` lines; assimp: vertices that carry them */
    uint32_t normals;       /* OBJ: `vn` lines; assimp: vertices that carry them */
    uint32_t unknown;       /* unknown keywords (each also a skipped statement) */
    char     first_unknown[32]; /* the first unknown keyword, for --info */
    uint32_t triangles;     /* sum of (corners - 2) over faces */
    uint32_t groups;        /* `g` statements */
    double   load_ms;       /* wall time of mesh_load, MTL included */
    double   load_cpu_ms;   /* the loading thread's CPU time over the same */
    /* Statements skipped because they could not be read (a face with no
     * vertices, an index out of range, an unknown keyword): the rest of
     * the file is shown, and a warning names the count and the first. */
    uint32_t skipped;
    char     first_skipped[256];    /* "x.obj:12: vertex index 40 out of range ..." */
    /* Warnings (the skipped statements' summary, a material library that
     * cannot be opened, bytes after the end): how many, and the first as
     * stderr would show it without "zview: warning: ", so that the viewer
     * can show it where stderr cannot be seen. */
    uint32_t warnings;
    char     first_warning[256];
    /* How the model stands, where its format says: the axis that points
     * up (UP_Y when the format does not say), the axis its front faces
     * (an UpAxis; -1 when the format has no forward axis), and why, for
     * --info ("STL: the 3D-printing convention"). */
    int      up;
    int      front;
    char     up_why[96];
    /* Textures that could not be read (each also a warning): faces then
     * show their base colour. The first one's message. */
    uint32_t tex_failed;
    char     first_tex_failed[256];
    /* The length unit the format states, "" when it states none (OBJ,
     * STL, PLY, OFF): "m" for glTF, "mm" for 3MF and AMF (their
     * default). --check names it beside the sizes. */
    char     unit[8];
    /* What guarded the load (sandbox.h; all 0 in-process): a child under
     * the seccomp filter, the Landlock ABI that confined its reads (0 or
     * -errno: none), and the memory it could add. */
    int32_t  sandboxed;
    int32_t  landlock;
    uint64_t mem_bound;
} MeshInfo;

typedef struct Mesh {
    char      *path;        /* as given on the command line */
    uint32_t   nverts;
    float     *pos;         /* 3 * nverts: x y z (divided by w when w given) */
    float     *rgb;         /* 3 * nverts vertex colours 0..1, or NULL if none */
    uint32_t   nfaces;
    uint32_t  *face_start;  /* nfaces + 1 offsets into corner[] */
    uint32_t  *corner;      /* 0-based vertex index per face corner */
    int32_t   *face_mat;    /* material index per face, -1 = default colour; NULL:
                               every face -1 (a file without materials keeps no
                               array: 4 bytes a face; read it through mesh_face_mat) */
    Material  *mats;
    uint32_t   nmats;
    MeshObject *objs;       /* at least one */
    uint32_t   nobjs;
    /* Points and polylines (OBJ p and l, PLY and XYZ point clouds, glTF
     * POINTS and LINES), beside the faces. A point is a vertex; a
     * polyline a run of vertices (k corners, k - 1 segments), stored as
     * faces are. Objects own contiguous runs of each. */
    uint32_t   npoints;
    uint32_t  *point;       /* vertex index per point; NULL: point i is vertex i
                               (a cloud: no array for millions of points) */
    uint32_t   nlines;
    uint32_t  *line_start;  /* nlines + 1 offsets into line_corner */
    uint32_t  *line_corner; /* vertex index per polyline corner */
    /* Texture coordinates (u right, v down the image: texture.h), 2 per
     * entry; NULL when the file has none. corner_uv gives each face
     * corner's entry (MESH_NO_UV: none); corner_uv NULL with uv set: one
     * entry per vertex, the corner's vertex (PLY, assimp). */
    float     *uv;
    uint32_t   nuv;
    uint32_t  *corner_uv;
    MeshTexture *tex;       /* the textures materials name */
    uint32_t   ntex;
    MeshInfo   info;
} Mesh;

#define MESH_NO_UV UINT32_MAX

/* Face f's material index (-1: the default colour). */
static inline int32_t mesh_face_mat(const Mesh *m, uint32_t f)
{
    return m->face_mat ? m->face_mat[f] : -1;
}

/* The decoded texture of material mat, or NULL (none, failed, pending). */
const Texture *mesh_material_texture(const Mesh *m, int32_t mat);
/* Decode a pending texture (on any thread: it touches only *out and
 * reads t's source). 0, or -1 with "name: reason" in err. */
int  mesh_texture_decode(const MeshTexture *t, uint64_t max_bytes, Texture *out, int *halved_out, char *err,
                         size_t errlen);
/* Put what mesh_texture_decode made in place (rc its result): the
 * source is freed, the state becomes MTEX_OK or MTEX_FAILED. */
void mesh_texture_install(MeshTexture *t, int rc, Texture *img, int halved);
/* Bytes of every decoded texture of m. */
uint64_t mesh_texture_bytes(const Mesh *m);

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

/* How to load: format NULL detects; strict refuses a file with any
 * statement it cannot read (exit 1, "path:line: message") where the
 * default skips such statements, shows the rest and warns once on
 * stderr ("zview: warning: x.obj: 3 statements skipped (first: ...)"),
 * the count and first message also in info.skipped and
 * info.first_skipped. */
/* How far a load has come, for a progress bar on another thread: bytes
 * of the file parsed so far, of total (0: unknown). Written with atomic
 * stores every few MB by the loading thread; read atomically. Formats
 * read by a library (assimp) report nothing. */
typedef struct {
    uint64_t done, total;
} MeshProgress;

/* quiet keeps warnings off stderr (they are still counted in info, the
 * first kept): the viewer loads while curses owns the terminal. */
/* max_polys and max_bytes bound what a load may build: counts a header
 * states are checked before anything is allocated ("big.stl: 180,000,000
 * triangles need about 9.1 GB; 7.2 GB available"), and arrays that grow
 * stop at them. Faces and points count as polygons. */
typedef struct {
    const char   *format;
    int           strict;
    int           quiet;
    MeshProgress *progress;     /* NULL: none */
    uint64_t      max_polys;    /* 0: no limit (the app passes --max-polys) */
    uint64_t      max_bytes;    /* memory a load may take; 0: what the machine has available */
    /* for tests: called each time a mapped file's reading window moves,
     * with the byte reached (a test truncates the file there) */
    void        (*on_window)(void *arg, uint64_t pos);
    void         *on_window_arg;
    /* NULL, or a flag another thread sets (atomically) when the load is no
     * longer wanted: a mapped file's load then stops within a few MB and
     * fails "cancelled" (the viewer's Esc). Streams read on. */
    const int    *cancel;
    /* Textures with a side longer than this (> 0) are left pending
     * (MeshTexture): the viewer decodes them on a thread of its own after
     * the first picture. 0: every texture is decoded while loading. */
    int           tex_defer_side;
    int           no_textures;  /* --no-textures: no image is even opened */
    /* The path must name a regular file: it is opened without waiting
     * (a FIFO would wait for a writer) and anything else is refused
     * ("not a regular file (a FIFO)"). --watch's reloads. */
    int           regular_only;
    /* OBJ parses in pieces on this many threads (0: every core; 1:
     * serially), the same mesh either way; piece_bytes (0: the loader's
     * own) is for tests, which make pieces small. */
    int           threads;
    uint64_t      piece_bytes;
    /* CAD formats (STEP, IGES, BREP): the tessellation's linear
     * deflection over the bounding box's diagonal; 0: the default (0.001) */
    double        tessellation;
    /* NULL, or where the loader publishes what it has parsed so far, for
     * a picture while it loads (meshprefix.h; OBJ only) */
    struct MeshPrefix *prefix;
    /* NULL, or told of each file the model names (material libraries,
     * images, buffers) once mesh_ref_open has let it through and before
     * it is read; image: it is a texture. The sandbox's child has its
     * parent count it in its memory bound (budget.c). */
    void        (*on_ref)(void *arg, const char *path, int image);
    void         *on_ref_arg;
} MeshLoadOpts;

int  mesh_load_ex(Mesh *m, const char *path, const MeshLoadOpts *opt, char *err, size_t errlen);

/* Parse a model already in memory (what a fuzz harness calls): `path`
 * names it in messages, gives the extension, and is what files it
 * refers to (mtllib) are resolved against; path NULL: named "(input)",
 * and no other file is opened. format NULL: detected as mesh_load does.
 * No state outside *m and the arguments. Same contract as mesh_load. */
int  mesh_parse_buffer(Mesh *m, const char *path, const char *format, const void *data,
                       size_t len, char *err, size_t errlen);

int  mesh_parse_buffer_ex(Mesh *m, const char *path, const MeshLoadOpts *opt, const void *data,
                          size_t len, char *err, size_t errlen);

/* OBJ text in memory: mesh_parse_buffer with format "obj". */
int  mesh_parse(Mesh *m, const char *path, const char *text, size_t len,
                char *err, size_t errlen);

void mesh_free(Mesh *m);

/* Is `name` a format this build reads (obj, stl, ply, off; with assimp
 * also "assimp" and every extension assimp reads)? */
int  mesh_format_valid(const char *name);
/* Open for reading `full`, a file the model at `model` names, as the
 * loader composed it (the referring file's folder and the name, or the
 * name alone when absolute): only a regular file beneath the model's
 * folder (refopen.c). model NULL or "-": nothing may be opened. A
 * descriptor, or -1 with the reason in why ("refused: ..." for a
 * reference out of bounds, else the system's message). */
int  mesh_ref_open(const char *model, const char *full, char *why, size_t whylen);

/* Does the format forced (NULL: none), else path's extension, name a
 * native loader (not assimp)? */
int  mesh_format_is_native(const char *path, const char *format);
/* Does path's extension (under a .gz, the one before it) name a format
 * this build reads, natively or through assimp? (The gallery's listing:
 * by name alone, nothing opened.) */
int  mesh_path_is_model(const char *path);
/* Open the library a load of path (format forced, or NULL) may need now:
 * assimp, unless the format or the extension names a native loader.
 * Opening it reads files beside the program's: the sandbox's child does
 * this before it confines its reads to the model's folder. */
void mesh_library_preload(const char *path, const char *format);
/* One line per format, for --formats: name, native or assimp, what. */
void mesh_formats_print(FILE *f);
/* The short list for messages: "obj stl ply off + assimp: glb gltf ...". */
void mesh_formats_short(char *buf, size_t n);

/* Reverse every face's corner order (--flip: the other winding). */
void mesh_flip_winding(Mesh *m);

/* --points: every vertex becomes a point and the faces and lines go
 * (one object of the whole mesh, named after the file). */
void mesh_as_points(Mesh *m);

#endif
