#ifndef ZV_SCREEN_H
#define ZV_SCREEN_H
/* screen: the one front end every hidden-surface algorithm starts from.
 * Scene + camera + viewport in, screen-space polygons out: transformed,
 * projected, clipped (near plane, guard band), vertices snapped to a
 * 24.8 fixed-point grid, and one depth plane per polygon computed from
 * the snapped vertices. Polygons that cover no sample centre are dropped
 * here, so no algorithm pays for them.
 *
 * Coordinates: pixels, x right, y down; sample (i, j) sits at
 * (i + 0.5, j + 0.5), i.e. at fixed-point (256 i + 128, 256 j + 128). */

#include <stdint.h>
#include <stdio.h>
#include "scene.h"

#define SUBPIX_BITS 8
#define SUBPIX      (1 << SUBPIX_BITS)   /* 256 sub-pixel steps per pixel */
#define SCREEN_MAX  16384                /* largest W or H accepted */
#define SCREEN_MAX_THREADS 64            /* most threads one projection uses */

/* The front end's scratch (per-vertex arrays, clip buffers), private to
 * project.c. Each ScreenPolys owns one, so projections into different
 * ScreenPolys may run at the same time. */
typedef struct ScreenWork ScreenWork;

typedef struct {
    int32_t x, y;       /* 24.8 fixed-point pixels */
    float   z;          /* depth at the vertex (for --dump-screen) */
} ScreenVert;

/* Depth plane: depth(i, j) = zc + b * (j - y0) + a * (i - x0) at sample
 * (i, j), evaluated in float in exactly that order by plane_row() and
 * plane_at(). Smaller is nearer. */
typedef struct {
    uint32_t first;     /* verts[first .. next polygon's first) */
    int32_t  face;      /* source face id */
    int32_t  x0, x1;    /* sample columns [x0, x1) the polygon may cover, clamped to the screen */
    int32_t  y0, y1;    /* sample rows [y0, y1), clamped */
    float    a, b, zc;  /* the plane, referenced to sample (x0, y0) */
    float    zmin;      /* smallest vertex depth (hierarchical tests) */
} ScreenPoly;

typedef struct {
    /* set by the caller, kept across frames */
    int         threads;        /* threads the front end may use: 1 = the caller
                                   alone, 0 = one per core (at most SCREEN_MAX_THREADS) */
    int         simd;           /* a SimdLevel (simd.h) for the vertex, screening and
                                   point loops: SIMD_AUTO (0) = the level in use, else at
                                   most that one (every level gives the same bits) */
    /* The section planes' cut (section.h), NULL: none. The polygons it
     * cuts are projected as their kept parts, in their places; its caps
     * follow the faces, before the points and lines (cut.c). */
    const struct SectionCut *cut;
    int         no_map;         /* keep no map below (nmap 0): the algorithms that do
                                   not read it (HsrAlgo.uses_map) save 4 bytes a polygon
                                   written every frame (issue 21) */
    /* set by screen_project */
    int         w, h;
    float       pixel_aspect;   /* pixel height / width (2 for terminal cells) */
    int         cull;           /* drop back faces */
    ScreenVert *verts;
    uint32_t    nverts, cap_verts;
    ScreenPoly *polys;          /* polys[npolys].first is a sentinel = nverts */
    uint32_t    npolys, cap_polys;
    /* Scene polygon instance -> screen polygon index, -1 when dropped.
     * Instance of polygon k (scene index) of object o is
     * map_first[o] + (k - objs[o].poly_first). */
    int32_t    *map;
    uint32_t    cap_map, nmap;  /* nmap: entries in use (polygon instances) */
    int         face_sorted;    /* polys are in face-id order (as projected; --order undoes it) */
    uint32_t   *map_first;          /* per object */
    int         cap_objs;
    /* projection used, for object-space tests (octree node boxes) */
    float       focal_x, focal_y;   /* pixels per view unit (ortho) or per unit/distance (persp) */
    float       eye_z;              /* persp: eye position on the view z axis */
    float       near_z, far_z;      /* persp: clip distances in front of the eye */
    float       depth_scale, depth_bias; /* ortho depth = bias - scale * z_view */
    int         persp;
    /* statistics of the last projection */
    uint32_t    in_polys;       /* scene polygons considered */
    uint32_t    culled_back;    /* dropped as back faces */
    uint32_t    culled_empty;   /* dropped: clipped away or cover no sample */
    uint32_t    helpers;        /* helper threads that took part (most for one object) */
    double      ms;             /* time spent projecting */
    ScreenWork *work;           /* scratch, made on first use, freed by screen_free */
    /* Points, line segments and wireframe edges (prims.c): appended by
     * screen_prims after the faces' polygons, polys[prim_first ..
     * npolys), ids past the faces' (scene_prim_of). They are in no
     * object's map. */
    uint32_t    prim_first;
    uint32_t    points_in;      /* points in front of the eye and on screen */
    uint32_t    points_drawn;   /* squares kept: one per sample box (see prims.c) */
    uint32_t    edges_in;       /* segments and wireframe edges considered */
    uint32_t    edges_drawn;    /* quads kept whole */
    uint32_t    edges_sampled;  /* quads given as their samples (small, or past
                                   one whole quad per 4 samples of the picture) */
    uint32_t    edge_squares;   /* the one-sample squares they became: one per
                                   sample they cover, the nearest (see prims.c) */
    double      prim_ms;        /* time spent on them */
} ScreenPolys;

typedef struct {
    int   w, h;                 /* image size in pixels */
    float pixel_aspect;         /* pixel height / width */
    int   cull;                 /* back-face culling */
} Viewport;

/* Project every polygon of the scene. Buffers in *sp grow as needed and
 * are reused across frames (no allocation once grown). A big object is
 * split between the caller and up to sp->threads - 1 helper threads, with
 * the same result as one thread. All state lives in *sp: calls on
 * different ScreenPolys may run at the same time (the scene is only
 * read). Returns 0, or -1 on out of memory. */
int  screen_project(ScreenPolys *sp, const Scene *s, const Viewport *vp);
/* Free the buffers and the scratch; sp->threads is kept. */
void screen_free(ScreenPolys *sp);

static inline uint32_t screen_poly_nverts(const ScreenPolys *sp, uint32_t i)
{
    return sp->polys[i + 1].first - sp->polys[i].first;
}

/* The depth rule, written once: every algorithm evaluates depth through
 * these two, so equal inputs give bit-equal depths. */
static inline float plane_row(const ScreenPoly *p, int j)
{
    return p->zc + p->b * (float)(j - p->y0);
}
static inline float plane_at(const ScreenPoly *p, float zrow, int i)
{
    return zrow + p->a * (float)(i - p->x0);
}

/* prims.c: points and lines as polygons. Each point becomes a square
 * of point_size x point_size samples, aligned to the sample grid (to
 * the pixel grid when supersampled), placed by its projected centre, at
 * its depth; each segment (and
 * wireframe edge) a quad line_width samples wide along it, with square
 * ends half as long as it is wide, its depth varying along it as the
 * segment's does. Wireframe edges are brought nearer by PRIM_WIRE_BIAS,
 * so that an edge wins against its own faces. They are ordinary
 * polygons for every algorithm, with ids past the faces'. */
#define PRIM_SIZE_MAX  64          /* largest point size and line width, in samples */
#define PRIM_WIRE_BIAS (1.0f / 4096) /* depth units (the fitted scene spans about 0.5) */

typedef struct {
    int point_size;         /* samples a side, 1 .. PRIM_SIZE_MAX */
    int line_width;         /* samples, 1 .. PRIM_SIZE_MAX */
    int wire;               /* the wireframe edges too (scene_wire_build first) */
    int all_prims;          /* every point as a square and every segment as its
                               quad, none dropped (tests: the reductions give
                               the same buffers) */
    int pixel;              /* samples a pixel's side (supersampling): squares
                               of whole pixels start on a pixel (0, 1: any sample) */
    int marks;              /* the problem edges too (Scene.marks, --problems) */
} PrimStyle;

typedef struct PrimWork PrimWork;   /* per-frame scratch, kept across frames */

/* A view-space point (x right, y up, z to the viewer) through the
 * projection of sp's last frame: out = pixels x, y (y down) and depth,
 * as the front end maps the corners of polygons. -1 when it is behind
 * the near plane (perspective). */
int  screen_view_point(const ScreenPolys *sp, double x, double y, double z, double out[3]);

/* Append the scene's points, segments (and wireframe edges) to sp, as
 * screen_project left it for the same scene and viewport. Of the points
 * whose squares cover the same samples only the nearest (by depth, then
 * id) can show anywhere, so only it is kept: exactly the picture of all
 * of them, at a cost bounded by the screen. Likewise a quad of a few
 * samples, and every quad past one per 4 samples of the picture, is
 * given as its samples: each sample such quads cover becomes one square
 * of one sample at the nearest (depth, id) they give it. *work is made
 * on first use. Returns 0, or -1 on out of memory. */
int  screen_prims(ScreenPolys *sp, const Scene *s, const PrimStyle *st, PrimWork **work);
void prims_free(PrimWork **work);

/* order.c: the order polygons reach the algorithm (--order). The ids
 * and the picture do not change; the hierarchical z-buffer's speed does. */
typedef enum { ORDER_FILE = 0, ORDER_FRONT, ORDER_BACK, ORDER_SHUFFLE, ORDER_COUNT } PolyOrder;
extern const char *const order_names[ORDER_COUNT];
int order_from_name(const char *name);          /* -1 if unknown */

/* Second arrays the polygons are copied into, kept across frames. */
typedef struct {
    ScreenVert *verts;
    ScreenPoly *polys;
    uint64_t   *key;
    int32_t    *newpos;
    uint32_t    cap_verts, cap_polys, cap_key, cap_newpos;
} ReorderScratch;

/* Put sp's polygons in the given order (front-to-back and back-to-front
 * by their least depth; shuffle seeded), map following. 0, or -1 on out
 * of memory (sp is then unchanged). */
int  screen_reorder(ScreenPolys *sp, PolyOrder order, uint32_t seed, ReorderScratch *rs);
void reorder_free(ReorderScratch *rs);

/* Write the polygons as OBJ text ("# zview screen W H", v x y z, f ... # id)
 * to f, flushed. Returns 0, or -1 with errno set (a write failed). */
int  screen_dump_obj(const ScreenPolys *sp, FILE *f);

#endif
