#ifndef ZV_SCENE_H
#define ZV_SCENE_H
/* scene: objects placed in the world, a camera and a light, and the
 * polygon list every frame starts from. Meshes in, the world out; the
 * projection to screen-space polygons lives in project.c (screen.h). */

#include <stdint.h>
#include "mesh.h"
#include "meshcheck.h"
#include "vec.h"

/* Which model axis points up (UpAxis, mesh.h): each object is turned by
 * quarter turns so that it does, exactly (entries of 0 and +-1). It
 * starts as its file says (MeshInfo.up); --up and the viewer's U key set
 * one for every object. */
const char *up_axis_name(int up);          /* "y", "z", "x", "-y", "-z", "-x" */
int         up_axis_from_name(const char *s);   /* -1 if none */

typedef struct {
    char       name[MESH_NAME_MAX];
    const Mesh *mesh;         /* geometry owner (several objects may share one) */
    uint32_t   face_first;    /* face range in the mesh */
    uint32_t   face_count;
    uint32_t   vert_min, vert_max; /* mesh vertex range used (inclusive) */
    int32_t    face_base;     /* global face id of its first face */
    uint32_t   poly_first;    /* polygon range in Scene.poly_* */
    uint32_t   poly_count;
    Vec3       centre;        /* object-space centre of its bounding box; it turns about this */
    Vec3       half;          /* object-space half extents of that box */
    /* placement, changed by the viewer */
    float      yaw, pitch, roll;   /* radians */
    Vec3       offset;        /* world translation (moves by the viewer) */
    Vec3       home;          /* offset after a reset (grid copies, laid-out files sit apart) */
    float      scale;         /* uniform, 1 = as loaded */
    float      home_scale;    /* scale after a reset (a laid-out file's common size) */
    /* The placement the model opened with (--move, --turn, --scale), which
     * a reset goes back to: relative to home, so that it survives the
     * layout moving home; zero for objects opened later (open_scale 0
     * stands for 1). */
    Vec3       open_move;
    float      open_yaw, open_pitch, open_roll, open_scale;
    int        up;            /* UpAxis: applied first, about the centre */
    /* Points, line segments and wireframe edges (screen-aligned squares
     * and quads made each frame by prims.c): ids past every face's, in
     * load order: all objects' points, then their segments, then their
     * wireframe edges (see scene_prim_of). */
    uint32_t   point_first, point_count;  /* its points in the mesh (Mesh.point, or vertices) */
    uint32_t   seg_first, seg_count;      /* its segments in Scene.seg_corner */
    uint32_t   wire_first, wire_count;    /* its edges in Scene.wire (when built) */
    uint32_t   mark_first, mark_count;    /* its problem edges in Scene.marks (when set) */
    int32_t    point_id0, seg_id0, wire_id0, mark_id0; /* global id of its first of each */
    uint32_t   line_count;                /* polylines (for counts) */
} Object;

typedef struct {
    float yaw, pitch, roll;   /* radians, the whole scene's turn about its centre */
    Vec3  pan;                /* view-space translation in fit radii (x right, y up) */
    float zoom;               /* 1 = fitted */
    int   persp;              /* 0 = orthographic */
    float fov_deg;            /* vertical field of view under perspective */
    /* set by scene_fit() */
    float fit_yaw, fit_pitch, fit_roll;   /* the turn it fitted from (radians) */
    Vec3  centre;             /* world point that maps to the image centre */
    float radius;             /* world radius of the scene about centre (depth range) */
    Vec3  fit_half;           /* view-space half extents of the scene when fitted:
                                 the projection scales these to 90% of the image */
} Camera;

typedef struct {
    Vec3  dir;                /* unit vector towards the light, view space (x right, y up, z to viewer) */
    float yaw, pitch;         /* degrees: dir turned right of the viewer, and up (light_set) */
    float ambient;            /* 0..1 */
} Light;

/* The default light: over the viewer's upper left. */
#define LIGHT_YAW     (-34.0f)
#define LIGHT_PITCH   37.0f
#define LIGHT_AMBIENT 0.22f

/* A light yaw degrees to the right of the view direction and pitch
 * degrees up (0, 0: from the viewer), ambient clamped to 0..1. The light
 * stays fixed to the view when the scene turns, and a reset keeps it. */
void light_set(Light *l, float yaw_deg, float pitch_deg, float ambient);

/* A textured surface: a mesh's material with a base-colour texture.
 * Faces refer to it through Scene.face_surf. */
typedef struct {
    const MeshTexture *tex;   /* its mesh's texture (decoded when tex->state is MTEX_OK) */
    float factor[3];          /* the base colour it multiplies, linear light */
    float off[2], scale[2];   /* texture coordinates used: uv * scale + off */
} SceneSurf;

/* What a face's colour comes from (Scene.face_surf). */
enum {
    SURF_PLAIN = 0,           /* its face_rgb, one colour */
    SURF_VCOLOUR = 1,         /* its corners' colours, interpolated across it */
    SURF_TEX0 = 2,            /* 2 + k: textured as surf[k] says */
};
#define SCENE_SURF_MAX 65000  /* surfaces a scene holds (face_surf is 16 bits) */

/* The problems a check found, as the picture draws them (marks.c): the
 * problem edges (boundary and non-manifold) as lines, numbered after the
 * wireframe's, and per loaded face its MARK_* bits and its part. */
enum { MARK_BOUNDARY = 1, MARK_NONMANIFOLD = 2 };      /* SceneMarks.edge_kind */
enum { MARK_FLIPPED = 1, MARK_CROSSING = 2 };          /* SceneMarks.face */
typedef struct {
    int       set;            /* a check's findings are here */
    uint32_t *edge;           /* 2 mesh vertex indices per problem edge, object by object */
    uint8_t  *edge_kind;      /* MARK_BOUNDARY or MARK_NONMANIFOLD per edge */
    uint32_t  nedges;
    uint32_t  nfaces;         /* faces the arrays below cover: the loaded objects' */
    uint8_t  *face;           /* per face: MARK_FLIPPED (seen from inside), MARK_CROSSING */
    uint32_t *face_part;      /* per face: its part, numbered across the scene from 0 */
    uint32_t  nparts;
    uint32_t  nflagged;       /* faces with a MARK_* bit */
    uint32_t  gen;            /* bumped by every set and clear: what is made from the marks is keyed by it */
} SceneMarks;

typedef struct Scene {
    Mesh     *meshes;         /* owned */
    int       nmeshes;
    Object   *objs;
    int       nobjs;
    uint32_t  nfaces;         /* all faces, all objects: face ids are 0..nfaces-1 */
    /* Polygons every frame projects: a face kept whole when planar, else
     * split into triangles that keep the face's id. */
    uint32_t  npolys;
    uint32_t *poly_start;     /* npolys + 1 offsets into poly_corner; NULL: all triangles */
    uint32_t *poly_corner;    /* mesh vertex index (of the polygon's object's mesh) */
    uint32_t *poly_lface;     /* face index within its object: id = face_base + lface;
                                 NULL: one polygon a face (scene_poly_lface) */
    /* Objects refer to polygon ranges; copies made by scene_make_grid
     * share the ranges of the object they copy. */
    /* Per global face, for shading (read through the accessors below:
     * the compact form leaves them NULL). */
    float    *face_normal;    /* 3 * nfaces, object space, unit (Newell); NULL:
                                 computed when asked (scene_face_normal) */
    uint8_t  *face_rgb;       /* 3 * nfaces, base colour (Kd, vertex colours, or default);
                                 NULL: every face scene_default_rgb, none its own */
    uint8_t  *face_own;       /* per face: 1 = its colour is its own (material, vertex
                                 colours), 0 = its object's (recoloured when objects
                                 come or go); NULL = all own (with face_rgb) */
    uint16_t *face_obj;       /* object index per face; NULL: all object 0 */
    /* Colours that vary across a face (texture, vertex colours): per
     * global face its SURF_* (NULL: every face plain), the textured
     * surfaces, and per scene polygon corner (as poly_corner) its
     * texture coordinate (NULL: no face is textured). face_rgb stays
     * the face's one colour: the texture's mean times its base colour
     * (the base colour alone when the texture failed), the mean of its
     * corners' colours. */
    uint16_t *face_surf;
    SceneSurf *surf;
    uint32_t  nsurf;
    float    *poly_uv;        /* 2 per polygon corner: u, v */
    uint32_t  nbase_objs;     /* objects loaded (before grid copies) */
    Camera    cam;
    Light     light;
    /* Points and lines, beside the faces (all objects, grid copies
     * counted): ids nfaces .. nfaces + nprims - 1 (scene_prim_of). */
    uint32_t  npoints;        /* point primitives */
    uint32_t  nlines;         /* polylines */
    uint32_t  nsegs;          /* their segments (a polyline of k corners has k - 1) */
    uint32_t *seg_corner;     /* per segment of the loaded objects: its first corner
                                 in the mesh's line_corner (the second follows) */
    /* The wireframe (--wireframe): every edge of the loaded objects' faces
     * once per object, as mesh vertex pairs; made by scene_wire_build. */
    uint32_t *wire;           /* 2 per edge */
    uint32_t  nwire_edges;    /* edges of the loaded objects */
    uint32_t  nwire;          /* wireframe edges drawn, grid copies counted (0: not built) */
    int       wire_built;
    /* What --check found, drawn on the model (--problems, --parts; marks.c):
     * set by scene_marks_set, dropped by any edit. */
    SceneMarks marks;
    uint32_t  nprims;         /* npoints + nsegs + nwire + marks.nedges: the ids after the faces' */
    /* Bumped whenever objects are added or removed (edit.c) or copied
     * (--grid): what is built from a scene and kept across frames (the
     * octree, smooth normals) is keyed by it as well as by the pointer,
     * which stays the same when the viewer edits its scene in place. */
    uint32_t  gen;
    /* The meshes' positions were multiplied by 2^-pos_exp when built (0
     * but for coordinates past 2^120, whose rotations would overflow a
     * float; a power of two keeps them exact): --info multiplies back. */
    int       pos_exp;
} Scene;

/* The compact form (scene_build makes it of one file of triangles whose
 * faces all stay whole): no array holds what can be derived. The mesh's
 * corner list is the polygon list, polygon k is a triangle of corners
 * 3k .. 3k + 2 (poly_start NULL) and is face k of the file (poly_lface
 * NULL: lface is k - poly_first of its object); its normal is computed
 * from its corners when shading asks (face_normal NULL), in the same
 * double-precision arithmetic the stored normals were made with, so the
 * same bits; and a scene of one object with no colour of its own has no
 * face_rgb, face_own or face_obj. What is left resident is the positions
 * (12 bytes a vertex) and the corners (12 bytes a triangle). Every reader
 * goes through these accessors. */
extern const uint8_t scene_default_rgb[3];    /* a face without a colour of its own */

static inline uint32_t scene_poly_c0(const Scene *s, uint32_t k)
{
    return s->poly_start ? s->poly_start[k] : 3 * k;
}
/* Polygon k's face within object o (the object whose range holds k). */
static inline uint32_t scene_poly_lface(const Scene *s, const Object *o, uint32_t k)
{
    return s->poly_lface ? s->poly_lface[k] : k - o->poly_first;
}
static inline int scene_face_obj(const Scene *s, uint32_t id)
{
    return s->face_obj ? s->face_obj[id] : 0;
}
static inline const uint8_t *scene_face_rgb(const Scene *s, uint32_t id)
{
    return s->face_rgb ? s->face_rgb + 3 * (size_t)id : scene_default_rgb;
}
/* Face id's unit normal in object space (stored or computed). */
void scene_face_normal(const Scene *s, uint32_t id, float n[3]);
/* The same of faces [f0, f0 + n) of one object, 3 floats each into out;
 * simd a SimdLevel (simd.h: SIMD_AUTO the level in use), the same bits
 * at every level. */
void scene_face_normals(const Scene *s, uint32_t f0, uint32_t n, float *out, int simd);
/* Corners of every polygon (the end of the corner list). */
static inline uint32_t scene_ncorners(const Scene *s)
{
    return scene_poly_c0(s, s->npolys);
}

/* The textures of every mesh: how many, how many could not be read,
 * how many wait to be decoded, and the bytes of those decoded. */
typedef struct {
    uint32_t count, failed, pending;
    uint64_t bytes;
} TextureCount;
void scene_texture_count(const Scene *s, TextureCount *out);

/* What a message calls the files of meshes[0..n): "a.obj", "a.obj and
 * b.stl", "a.obj and 4 more files". */
void scene_files_text(const Mesh *meshes, int n, char *buf, size_t len);

/* What an id of the face-id buffer is. */
typedef enum { PRIM_NONE = -1, PRIM_FACE = 0, PRIM_POINT, PRIM_SEG, PRIM_WIRE, PRIM_MARK } PrimKind;

/* The kind of id, its object (*obj) and its index among that object's
 * points, segments or wireframe edges (*local; for a face, the face
 * index within the object). PRIM_NONE for the background and ids past
 * the scene's. */
PrimKind scene_prim_of(const Scene *s, int32_t id, int *obj, uint32_t *local);

/* The two mesh vertices of a segment or wireframe edge (local index k
 * of object o). */
void scene_edge_verts(const Scene *s, const Object *o, PrimKind kind, uint32_t k, uint32_t v[2]);

/* The mesh vertex of point k of object o. */
static inline uint32_t object_point_vert(const Object *o, uint32_t k)
{
    const uint32_t *pt = o->mesh->point;
    return pt ? pt[o->point_first + k] : o->point_first + k;
}

/* marks.c: what --check found, on the model. scene_check_meshes gives
 * each file back as a Mesh the check can read (the scene dropped the
 * meshes' face lists: they are made again from its polygons, a split
 * face whole again), owning all its arrays, so that the check can run on
 * another thread while the scene changes. scene_marks_set takes the
 * checks of those meshes (checks[i] of file i, made with
 * CheckOpts.detail) as marks; scene_marks_clear drops them. 0, or -1
 * out of memory (or too many ids) with the message. */
int  scene_check_meshes(const Scene *s, Mesh **out, int *n, char *err, size_t errlen);
void scene_check_meshes_free(Mesh *m, int n);
int  scene_marks_set(Scene *s, const MeshCheck *checks, int n, char *err, size_t errlen);
void scene_marks_clear(Scene *s);

/* Make the wireframe's edges (once; later calls return at once).
 * Returns 0, or -1 with a message (out of memory, too many ids). */
int  scene_wire_build(Scene *s, char *err, size_t errlen);

/* Build a scene from loaded meshes (ownership of the array and the meshes
 * moves to the scene). Every `o` object of every mesh becomes one Object.
 * The meshes' face arrays (face_start, corner, face_mat) are released:
 * the scene's polygon lists and per-face arrays replace them.
 * Returns 0, or -1 with a message in err (out of memory). */
int  scene_build(Scene *s, Mesh *meshes, int nmeshes, char *err, size_t errlen);
/* scene_build for a caller whose other threads read the meshes while it
 * runs (--diff's picture made beside its measures): the meshes are not
 * written, their face arrays stay until scene_release_faces (the scene
 * never reads them once built). The same scene; but 1, nothing built,
 * for a model whose coordinates scene_build would scale down (it
 * writes the positions): the caller builds it with scene_build once the
 * readers are done. On failure (-1, 1) the meshes stay the caller's. */
int  scene_build_kept(Scene *s, Mesh *meshes, int nmeshes, char *err, size_t errlen);
void scene_release_faces(Scene *s);

/* edit.c: the viewer's open, remove and clear. Every one keeps the
 * scene as scene_build would have made it from the files that remain:
 * face ids in load order, objects without colours of their own coloured
 * by their index, the wireframe to be built again; grid copies (--grid)
 * are dropped (the caller makes them again). Placements, camera and
 * light stay; the caller lays out and fits. gen is bumped.
 *
 * scene_add appends the objects of `part` (a scene built by scene_build
 * from the new files alone, on any thread) after s's; part's meshes move
 * into s and part is left empty. Returns 0, or -1 with a message (too
 * many objects or faces, out of memory): s and part unchanged.
 * scene_remove removes loaded object i (a file whose last object goes
 * goes with it); -1 on a bad index or out of memory, s unchanged.
 * scene_clear leaves no object (camera and light kept). */
int  scene_add(Scene *s, Scene *part, char *err, size_t errlen);
int  scene_remove(Scene *s, int i, char *err, size_t errlen);
/* scene_replace_file puts part's objects where file f's were (--watch:
 * the file read again), in the same place among the files; part is
 * left empty. -1 with a message, s and part unchanged. */
int  scene_replace_file(Scene *s, int f, Scene *part, char *err, size_t errlen);
void scene_clear(Scene *s);
/* The file (index into meshes) that object i comes from, -1 if none. */
int  scene_object_file(const Scene *s, int i);

/* Add copies of object 0..n-1 laid out as an N x N x N grid (for the deep
 * scene benchmark): the scene then has nobjs * N^3 objects. */
int  scene_make_grid(Scene *s, int n, char *err, size_t errlen);

void scene_free(Scene *s);

/* Turn every object so that its `up` axis points up, then fit. */
void scene_set_up(Scene *s, int up);
/* The up axis set for every object (scene_set_up) when it is not what
 * their files say (MeshInfo.up), else -1: what --up must say to give the
 * scene back. */
int  scene_up_forced(const Scene *s);

/* Reset the camera and put the objects back where the model opened
 * (Object.open_*), then fit. The light stays. */
void scene_reset(Scene *s);
/* The view of camera c (its turn, the turn it was fitted at, zoom, pan)
 * on s as it is now: fitted at c's fit turn, then turned, zoomed and
 * panned as c. The projection stays s's. */
void scene_view_like(Scene *s, const Camera *c);
/* Fit: centre the scene (its objects at home) as seen from the camera's
 * current turn and set its view-space extents, which the projection
 * scales to about 90% of the viewport (pan and zoom are reset). */
void scene_fit(Scene *s);

/* view.c: the named views (front back left right top bottom iso), as a
 * yaw and pitch in degrees; -1 for an unknown name. */
int  view_from_name(const char *name, float *yaw_out, float *pitch_out);
const char *view_name(int i);           /* the i-th name, NULL past the end */
/* The direction from the model towards a viewer looking from yaw and
 * pitch (degrees): the inverse turn of (0, 0, 1). */
Vec3 view_dir(float yaw_deg, float pitch_deg);

/* Which way the loaded objects' front faces in the world (view.c's
 * opening comment): the format's forward axis, else the way more of the
 * faces point, else +z. */
typedef enum { FRONT_NONE, FRONT_FORMAT, FRONT_FACES } FrontFrom;
typedef struct {
    Vec3      dir;              /* unit and horizontal (y = 0) */
    float     weight;           /* 0..1: how sure (the format: 1) */
    float     lean;             /* the faces' lean towards dir: |sum of unit normals| / faces */
    FrontFrom from;
} SceneFront;
void  scene_front(const Scene *s, SceneFront *out);
/* How much a view from yaw and pitch (degrees) is preferred for facing
 * the front: 1 + 0.3 * weight * the cosine of the horizontal angle
 * between the view's direction and the front (1.3 straight at a sure
 * front, 0.7 from behind it). */
float front_factor(const SceneFront *f, float yaw_deg, float pitch_deg);
/* A first view from the geometry alone, without rendering: of eight
 * three-quarter views from above, the one that sees the most surface
 * facing it, times front_factor (yaw and pitch, degrees). */
void scene_pick_view(const Scene *s, float *yaw_out, float *pitch_out);

/* layout.c: several files side by side (row, grid) at a common size,
 * level and across the screen of a view turned by yaw (radians), or as
 * their coordinates place them (none); sets the objects' homes. */
typedef enum { LAYOUT_ROW = 0, LAYOUT_GRID, LAYOUT_NONE, LAYOUT_COUNT } LayoutKind;
extern const char *const layout_names[LAYOUT_COUNT];
int  layout_from_name(const char *name);        /* -1 if unknown */
void scene_layout(Scene *s, LayoutKind kind, float yaw);
/* The colour of the i-th object when it has none of its own. */
void object_colour(int i, uint8_t rgb_out[3]);

/* Object-to-world matrix: the up axis, turn and scale about the
 * object's centre, then offset. */
Mat4 object_matrix(const Object *o);
/* World-to-view matrix (rotation + pan, before projection). */
Mat4 camera_view(const Camera *c);

#endif
