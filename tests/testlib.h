#ifndef ZV_TESTLIB_H
#define ZV_TESTLIB_H
/* testlib: scenes from OBJ text or files, seeded random views, and a
 * render of one frame with any algorithm, for the Criterion tests. */

#include "hsr.h"
#include "scene.h"
#include "screen.h"

extern const HsrAlgo hsr_zbuffer;

/* 0 on success; a failure message goes to stderr. */
int  tl_scene_from_text(Scene *s, const char *name, const char *obj_text);
int  tl_scene_from_file(Scene *s, const char *path);

/* A reproducible view: turns, zoom 0.7..2.5, a small pan; persp with a
 * field of view of 30..100 degrees, sometimes close enough that polygons
 * cross the near plane. */
void tl_random_view(Scene *s, uint32_t seed, int persp);

/* Project at w x h and render with algo on `threads` threads. */
int  tl_render(Scene *s, const HsrAlgo *algo, int threads, int w, int h, int cull,
               ScreenPolys *sp, FrameBufs *fb, HsrStats *st);

/* Compare fb with ref; returns differing pixels and the first of them. */
long tl_diff(const FrameBufs *ref, const FrameBufs *fb, int *first_x, int *first_y);

/* ==== Scenes built without OBJ text (the multi-object agreement test
 * and the differential fuzzer) ==== */

/* Fill a Mesh as the loader would: vertices, faces as 0-based corner
 * lists, `o` objects as contiguous face ranges (an object that got no
 * faces is renamed, as the loader does). Each returns 0, or -1 when out
 * of memory (the mesh is then still safe to mesh_free). */
int  tl_mesh_init(Mesh *m, const char *path);
int  tl_mesh_object(Mesh *m, const char *name);
int  tl_mesh_vertex(Mesh *m, float x, float y, float z);
int  tl_mesh_face(Mesh *m, const uint32_t *corner, uint32_t n);
/* A point at vertex v; a polyline through n >= 2 vertices. */
int  tl_mesh_point(Mesh *m, uint32_t v);
int  tl_mesh_line(Mesh *m, const uint32_t *corner, uint32_t n);
/* Close the objects (face, point and line counts, vertex ranges) as the
 * loader's end of file does; -1 when the mesh has nothing to draw. A
 * mesh with vertices and nothing else becomes a point cloud (every
 * vertex a point, no index array), as loaded clouds are. */
int  tl_mesh_finish(Mesh *m);
/* The axis-aligned cube at (x, y, z) of side s: its eight corners (bit 0
 * of the index is x, round the bottom then the top; the first's index in
 * *first) and its faces as quads of those (tl_cube_faces: counter-
 * clockwise seen from outside), face `skip` left out (-1: none), the
 * faces of the mask `flip` wound the other way, as two triangles each
 * when tris. 0 or -1 as above. */
extern const uint32_t tl_cube_faces[6][4];
int  tl_mesh_cube_verts(Mesh *m, float x, float y, float z, float s, uint32_t *first);
int  tl_mesh_cube(Mesh *m, float x, float y, float z, float s, int skip, unsigned flip, int tris);

/* A view as the command line gives it (app_load_scene): fitted at one
 * turn, then turned, zoomed and panned. */
typedef struct {
    float yaw, pitch, roll;             /* the camera's turn, radians */
    float fit_yaw, fit_pitch, fit_roll; /* the turn it was fitted at */
    float zoom;                         /* 1 = fitted */
    float pan_x, pan_y;                 /* in fit radii, right and up */
    int   persp;
    float fov_deg;
} TlView;

/* Set the camera of s to v. Place the objects first: the fit sees them. */
void tl_set_view(Scene *s, const TlView *v);

/* The buffers tl_agree renders into, kept from call to call (the fuzzer
 * makes thousands a second: fresh big buffers each time would cost more
 * than the rendering). Zero-initialise; tl_agree_free when done. */
typedef struct {
    ScreenPolys sp;
    FrameBufs   ref, fb;
    PrimStyle   style;      /* points and lines (zero: size and width 1, no wireframe) */
    PrimWork   *prims;
} TlAgree;

/* The front end as the pipeline runs it: screen_project, then the
 * points and lines (style NULL: size and width 1, no wireframe; the
 * wireframe is built when asked for). */
int  tl_project(ScreenPolys *sp, Scene *s, const Viewport *vp, const PrimStyle *style, PrimWork **work);

/* Render in with algo on `threads` threads into fb, its buffers first
 * filled with ids that no algorithm writes and NaN depths, so that a
 * pixel an algorithm skips cannot match by luck. 0, or -1 when out of
 * memory. */
int  tl_render_poisoned(const HsrAlgo *algo, int threads, const HsrInput *in, FrameBufs *fb);

/* Project the current view at vp, render it with the z-buffer on one
 * thread and with every algorithm on `threads` threads (the buffers
 * poisoned before each run, so a pixel left unwritten shows). Returns 0
 * when every result equals the z-buffer's byte for byte; else the number
 * of pixels of the first one that differs, described in msg; -1 when out
 * of memory. */
long tl_agree(TlAgree *a, Scene *s, const Viewport *vp, int threads, char *msg, size_t msglen);
void tl_agree_free(TlAgree *a);

/* What every loader promises of a mesh it returns (every index in range,
 * objects' runs within the arrays, vertex ranges holding what they use,
 * finite positions): NULL when m keeps them all, else the first promise
 * broken, as C text. */
const char *tl_mesh_broken(const Mesh *m);

/* Do scenes a and b (either in the compact form, scene.h) hold different
 * polygons (corners, faces) or faces (normals, objects, colours, whether
 * the colour is its own), read through the accessors? 0 when they are
 * the same, else 1 with the first difference in msg. */
int tl_scene_faces_differ(const Scene *a, const Scene *b, char *msg, size_t n);

/* The same for a load's whole result: rc 0 and a mesh that keeps the
 * promises, or rc -1, a message that starts with the input's name, and
 * an empty mesh. */
const char *tl_load_broken(int rc, const Mesh *m, const char *err, const char *name);

/* Are a and b the same mesh, array for array and byte for byte (every
 * count, index, position, object, material, texture name, and what info
 * says but the load's times)? NULL when they are, else the first that
 * differs, as C text. */
const char *tl_mesh_differs(const Mesh *a, const Mesh *b);

/* Load the OBJ text [text, text + len) named `name` serially and on
 * `threads` threads in pieces of about `piece` bytes (strict or not),
 * and compare: the result, the message and the mesh. NULL when all
 * agree, else what differs (a static buffer). */
const char *tl_obj_pieces_differ(const char *name, const char *text, size_t len, int threads, uint64_t piece,
                                 int strict);

/* Path to ../shared/models/NAME if that folder exists, else NULL. */
const char *tl_shared_model(const char *name);

#endif
