#ifndef ZV_SCENECODE_H
#define ZV_SCENECODE_H
/* scenecode: the differential fuzzer's input format. Bytes in, a scene
 * (meshes, objects and their placements, camera) plus a viewport and a
 * thread count out. Every byte string decodes (reads past the end give
 * 0), and the work is bounded, so each input renders fast.
 *
 * Little-endian, in this order:
 *   u8  w - 1, u8 h - 1           image 1..256 x 1..256 pixels
 *   u8  flags                     SC_PERSP SC_CULL SC_THREADS2 SC_REFIT SC_GRID,
 *                                 bits 5-7: pixel aspect sc_aspects[], 7 = custom:
 *   [u8 a]                        custom aspect 0.25 + a / 32
 *   u8  fov                       2 + fov * 176 / 255 degrees
 *   i16 yaw, pitch, roll          camera turn, v * 180 / 32768 degrees
 *   [i16 yaw, pitch, roll]        SC_REFIT: the turn the view was fitted at
 *   u16 zoom                      10^(-3 + 6 v / 65535): 0.001 .. 1000
 *   u8  pan scale                 sc_pan_scales[v & 3] (fit radii)
 *   i16 pan x, y                  v / 32768 * scale
 *   u8  meshes                    1 + v % SC_MAX_MESHES
 *   per mesh: u8 objects          1 + v % SC_MAX_MESH_OBJS, each:
 *     u8  oflags                  SO_PLACED SO_SHARE SO_WIDE SO_RAW SO_GEN
 *     coord x, y, z               the object's base point (see below)
 *     u8  unit                    2^(v % 64 - 40): the vertex grid step
 *     SO_GEN: u8 kind, u8 n, u16 seed: a generated object of up to a few
 *             hundred faces (enough for an octree of several levels),
 *             vertices within +-127 units of the base:
 *             kind % 3 = 0: a height field of (2 + n % 15)^2 quads,
 *                           heights up to (n >> 4) * 8 units, some quads
 *                           split in two, the rest mostly not planar
 *                        1: 8 + n triangles strewn about, each up to
 *                           2^(seed % 8) units across
 *                        2: a closed sphere of 3 + n % 22 segments and
 *                           2 + n / 22 % 10 rings (quads, pole triangles)
 *             the seed drives a xorshift generator; then, as for others:
 *     u8  vertices                3 + v % 30, each three deltas from the
 *                                 base in units: i8 (i16 with SO_WIDE)
 *     u8  faces                   1 + v % 16, each:
 *       u8 corners                < 160: 3, < 224: 4, else 5 + v % 12
 *       u8 per corner             index mod the object's vertices
 *                                 (SO_SHARE: mod all of the mesh's so far)
 *                                 (SO_GEN: the generated faces come first,
 *                                 then these)
 *     SO_BIG: u16 n, u16 seed     one more face of 25 + n % 4000 corners,
 *                                 each a vertex of the object's at random
 *                                 (a row crosses it hundreds of times)
 *     SO_PLACED: i16 yaw, pitch, roll; coord x, y, z offset;
 *                u8 scale 10^(-3 + 6 v / 255)
 *   coord: SO_RAW: f32 bits (not finite: 0); else i16 m, u8 e:
 *          m / 32768 * 2^(e % 64 - 24)
 * Objects stop at SC_MAX_OBJS and faces at SC_MAX_FACES (8 times that
 * with SC_GRID's 2 x 2 x 2 copies).
 *
 * Then points and lines (an input that ends before this part has none,
 * so inputs made before it decode as they did):
 *   u8  style                     bits 0-2: point size - 1 (samples),
 *                                 bits 3-5: line width - 1, bit 6: the
 *                                 wireframe of the faces, bit 7: every
 *                                 point drawn (no one-per-box reduction)
 *   u8  prim meshes               v % (SC_MAX_PRIM_MESHES + 1), each a mesh
 *                                 of its own after the others, one object;
 *                                 bits 4-5: samples a pixel's side, 1 +
 *                                 v % 3 (points on whole pixels when their
 *                                 size is a multiple):
 *     u8  pflags                  PF_PLACED PF_COPY PF_WIDE PF_RAW PF_CLOUD
 *     coord x, y, z; u8 unit      as for objects
 *     PF_COPY: u8 mesh            the vertices of that earlier mesh (v % its
 *                                 count), bit for bit: points and lines on
 *                                 faces' corners and edges
 *     else: u8 vertices           1 + v % 30, deltas as for objects
 *     PF_CLOUD: u8 n, u16 seed    16 (n + 1) more vertices on a coarse grid
 *                                 in +-127 units (many share a sample box),
 *                                 and every vertex is a point (no list)
 *     else: u8 points             v % 64, each u8 vertex index (mod count)
 *     u8  lines                   v % 8, each u8 corners (2 + v % 6) and
 *                                 u8 vertex indices (mod count)
 *     PF_PLACED: placement as for objects
 *
 * Then how the frame is run, and a large mesh (an input that ends before
 * this part renders in the file's order, the hidden surfaces at every
 * SIMD level, with no large mesh, as it did before the part existed):
 *   u8  run                       bits 0-1: the polygons' order (PolyOrder,
 *                                 --order), bits 2-3: the hidden-surface
 *                                 SIMD level: 0 every level, else the
 *                                 SimdLevel v (at most the CPU's best)
 *   u16 seed                      ORDER_SHUFFLE's seed
 *   u8  big                       0: none; else a mesh of its own, after
 *                                 the others, one object, not placed:
 *     u8 kind, u8 n, u16 seed     sc_big_mesh: kind % 4 = 0 a terrain, 1 a
 *                                 sphere, 2 a soup of small triangles (up
 *                                 to 8,192), 3
 *                                 layers one behind another, up to
 *                                 SC_MAX_BIG_FACES triangles (a tenth of
 *                                 that with SC_GRID, a tenth with the
 *                                 wireframe, a hundredth with both: span
 *                                 is quadratic in the crossings of a row,
 *                                 and a 10,000-triangle sphere's wireframe
 *                                 at 64x59 took a minute under the
 *                                 fuzzer); n its size
 *     coord x, y, z               its centre, as for objects (not raw)
 *     u8  size                    its half extent, 2^(v % 64 - 32)
 *   u8  planes                    section planes (section.h), v % 5 (an
 *                                 input that ends before: none), each:
 *     u8 kind                     bit 0: slanted, else an axis plane of
 *                                 axis (v >> 1) % 3, bit 3: its negative;
 *     u8 x, y, z                  the point, across the first mesh's box
 *                                 (0 its least, 255 its most; an axis
 *                                 plane reads its own axis's)
 *     i8 nx, ny, nz               a slanted plane's normal (0, 0, 0: +z) */

#include <stddef.h>
#include <stdint.h>

#include "scene.h"
#include "screen.h"
#include "section.h"

enum {
    SC_PERSP = 1, SC_CULL = 2, SC_THREADS2 = 4, SC_REFIT = 8, SC_GRID = 16
};
enum {
    SO_PLACED = 1, SO_SHARE = 2, SO_WIDE = 4, SO_RAW = 8, SO_GEN = 16, SO_BIG = 32
};
#define SC_MAX_MESHES    3
#define SC_MAX_MESH_OBJS 4
#define SC_MAX_OBJS      12
#define SC_MAX_FACES     2048
#define SC_MAX_PRIM_MESHES 3
#define SC_MAX_BIG_FACES 60000     /* under the octree's background build (65,536) */
enum {
    PF_PLACED = 1, PF_COPY = 2, PF_WIDE = 4, PF_RAW = 8, PF_CLOUD = 16
};

extern const float sc_aspects[7];
extern const float sc_pan_scales[4];

/* Decode data into *s (built, placed, fitted, turned, zoomed and panned),
 * *vp and *threads. Returns 0, or -1 when out of memory (s is then
 * empty). */
int sc_decode(const uint8_t *data, size_t size, Scene *s, Viewport *vp, int *threads);
/* The same, with the points' and lines' style. */
int sc_decode_style(const uint8_t *data, size_t size, Scene *s, Viewport *vp, int *threads,
                    PrimStyle *style);

/* How the frame is run (the part after the points and lines). */
typedef struct {
    int      order;         /* a PolyOrder */
    uint32_t seed;          /* for ORDER_SHUFFLE */
    int      hsr_simd;      /* SIMD_AUTO: every level; else that SimdLevel */
    SectionPlane plane[SECTION_MAX];    /* the section planes (nplanes 0: no cut) */
    int      nplanes;
} ScRun;

/* The same, with how the frame is run. */
int sc_decode_run(const uint8_t *data, size_t size, Scene *s, Viewport *vp, int *threads, PrimStyle *style,
                  ScRun *run);

/* scenebig.c: a large mesh (see above) into m, an object begun: kind
 * and n as the input gives them, seeded, centred at centre, of half
 * extent size, at most max_faces triangles. 0, or -1 when out of
 * memory. */
int sc_big_mesh(Mesh *m, unsigned kind, unsigned n, unsigned seed, const double centre[3], double size,
                uint32_t max_faces);

#endif
