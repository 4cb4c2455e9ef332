#ifndef ZV_SECTION_H
#define ZV_SECTION_H
/* section: the model cut open by planes (--section; the viewer's / ' \
 * keys), between the scene and the screen. A plane lies in file units:
 * each object's own coordinates, before its up axis, turn and
 * placement. What lies on the positive side of every plane at once is
 * removed: one plane removes its positive half, two or three the wedge
 * or corner where their positive sides meet (a cut-away). A point
 * exactly on a plane is kept.
 *
 * This room decides in file units: which side of a plane a vertex lies
 * on (an exact sign, so every face that shares a vertex agrees), where
 * an edge crosses a plane (one computation per edge from its two ends,
 * the kept end first, so the faces on either side of the edge and the
 * cap get the same float point), the section's loops chained through
 * those points with their area, perimeter and open ends, the kept part
 * of a polygon, and the caps (each plane's section of what is kept, as
 * one outline filled by the even-odd rule). The front end (screen.h:
 * ScreenPolys.cut) projects the kept parts in place of the polygons
 * they came from and the caps after the faces, as ordinary polygons of
 * the one pipeline, so every algorithm sees the same ones. */

#include <stdint.h>

#include "scene.h"

#define SECTION_MAX   4         /* planes at once */
#define SECTION_TEXT  128       /* a plane as text, with room to spare */
#define SECTION_ENDS  8         /* open chains whose ends a section keeps */

/* One plane: the removed side is where (p - q) . n > 0. */
typedef struct {
    double q[3];                /* a point on it, file units */
    double n[3];                /* its normal (any length but 0) */
    int    axis;                /* 0, 1, 2: n is +-1 along that axis (x=V, -z=V); -1: any */
} SectionPlane;

/* ==== a plane (secplane.c) ==== */

/* "z=0.5", "-x=-2" (the plane of that axis at V; -x removes what lies
 * below V), or "X,Y,Z:NX,NY,NZ" (a point and a normal). 0, or -1 with
 * what it should have been in err. */
int  section_parse(const char *s, SectionPlane *out, char *err, size_t errlen);
/* The plane as section_parse reads it back (the shortest digits that
 * give each number back). */
void section_text(const SectionPlane *pl, char *buf, size_t len);
/* The plane of axis (0, 1, 2; neg: its negative direction) at v. */
SectionPlane section_axis_plane(int axis, int neg, double v);
/* Where along its unit normal a plane lies: q . n / |n| (x=V: V), file units. */
double section_offset(const SectionPlane *pl);
/* The same plane moved by d file units along its normal. */
void section_slide(SectionPlane *pl, double d);
/* The exact sign of (p - q) . n: +1 removed side, 0 on it, -1 kept. */
int  section_side(const SectionPlane *pl, const float p[3]);
/* Where the edge from a (kept: not on the removed side) to b (removed)
 * crosses the plane. Callers pass the kept end first, so every face
 * and cap that meets the edge gets the same bits. */
void section_edge_point(const SectionPlane *pl, const float a[3], const float b[3], float out[3]);
/* The part [*lo, *hi] (fractions of the way from a to b) of the
 * segment a b that lies on the removed side of every plane: 1, or 0
 * when none does. For points and lines (screen/prims.c), which are
 * drawn as quads and need no exact crossing. */
int  section_segment_cut(const SectionPlane *planes, int np, const float a[3], const float b[3], double *lo,
                         double *hi);
/* mask[v] of positions pos[0 .. n): bit i set where pos lies on the
 * removed side of planes[i]. */
void section_masks(const SectionPlane *planes, int np, const float *pos, uint32_t n, uint8_t *mask);

/* ==== the kept part of a polygon (secclip.c) ==== */

/* Scratch for clipping, kept by the caller across calls. */
typedef struct {
    float   *pts;               /* the result: 3 floats a point */
    uint32_t npts, room;
    void    *tmp;               /* private */
    uint32_t tmp_room;
} SectionClip;
void section_clip_free(SectionClip *c);

/* Polygon pts[0 .. n) (3 floats a corner, masks[k] its corners' masks
 * as section_masks gives them) less its part on the removed side of
 * every plane at once, into c->pts as one outline for the even-odd
 * rule. One plane: the kept part (Sutherland and Hodgman). Several:
 * the polygon with each edge split where a plane crosses it, then, by
 * a bridge walked both ways, the removed part's outline, which the
 * even-odd rule takes out. Each crossing of an edge of the polygon is
 * section_edge_point of that edge's two corners. Returns the points
 * (fewer than 3: nothing is kept), or -1 out of memory. */
int  section_clip_poly(const SectionPlane *planes, int np, const float *pts, const uint8_t *masks, uint32_t n,
                       SectionClip *c);

/* ==== a section's loops and figures (secloops.c) ==== */

/* A section of one object by one plane, file units. */
typedef struct {
    double   area;              /* of the closed loops: outer loops add, holes subtract */
    double   perimeter;         /* every loop's and open chain's length */
    uint32_t loops;             /* closed loops */
    uint32_t chains;            /* open chains: where the cut does not close (an open model) */
    uint32_t nends;             /* the first SECTION_ENDS chains' two ends are in ends[] */
    float    ends[SECTION_ENDS][2][3];
} SectionFigures;

/* The polygons to cut: polygon k of [first, first + count) has corners
 * corner[start[k] .. start[k + 1]) (start NULL: 3k .. 3k + 3), mesh
 * vertex indices into pos (3 floats each) and mask. */
typedef struct {
    const float    *pos;
    const uint32_t *start;
    const uint32_t *corner;
    uint32_t        first, count;
    const uint8_t  *mask;       /* section_masks of every vertex */
} SectionPolys;

/* Scratch the loops are chained in, kept across calls. */
typedef struct SectionWork SectionWork;
void section_work_free(SectionWork **w);

/* Plane i of planes[0 .. np) through the polygons: the figures of the
 * whole section (the other planes do not cut it), and, when cap is not
 * NULL, the cap: the closed loops as one outline (3 floats a point;
 * each loop joined to the first by a bridge walked both ways, so the
 * even-odd rule fills the section, holes open), oriented counter-
 * clockwise seen from the removed side, then clipped to the removed
 * side of every other plane (what of the section faces the opening).
 * cap->pts is grown. 0, or -1 out of memory. */
int  section_loops(const SectionPolys *in, const SectionPlane *planes, int np, int i, SectionWork **w,
                   SectionFigures *fig, SectionClip *cap);

/* ==== a scene's cut (seccut.c) ==== */

/* What a scene looks like cut: the planes, each mesh's vertex masks,
 * each object's caps. Made by section_cut_update, kept across frames,
 * read by the front end and shading. */
typedef struct SectionCut {
    SectionPlane plane[SECTION_MAX];
    int          nplanes;       /* 0: nothing is cut */
    uint8_t    **mask;          /* per mesh of the scene: a byte per vertex */
    uint32_t    *mask_room;
    int          nmask;
    SectionClip *cap;           /* per object and plane: cap[o * nplanes + i] */
    SectionFigures *fig;        /* the same: the figures of that section */
    uint8_t     *touched;       /* per object: a plane removes some of it */
    int          ncap_room, nobj_room;
    const Scene *key;           /* made for this scene at this generation, these planes */
    uint32_t     key_gen;
    int          key_np;
    SectionPlane key_plane[SECTION_MAX];
    SectionWork *work;
    SectionClip  clip;          /* the front end's scratch (one thread) */
    double       ms;            /* the last update's time */
} SectionCut;

/* Cut s by planes[0 .. np) (np 0: no cut); nothing is made again when
 * the scene and planes are those of the last call. 0, or -1 with a
 * message (out of memory). */
int  section_cut_update(SectionCut *c, const Scene *s, const SectionPlane *planes, int np, char *err,
                        size_t errlen);
void section_cut_free(SectionCut *c);

/* The removed-side bits of every plane of c. */
static inline uint8_t section_all(const SectionCut *c)
{
    return (uint8_t)((1u << c->nplanes) - 1);
}
/* The first cap id of scene s: after its faces, points and lines. Cap
 * i of object o is section_cap_id0(s) + o * nplanes + i. */
static inline int64_t section_cap_id0(const Scene *s)
{
    return (int64_t)s->nfaces + s->nprims;
}
/* The object and plane of an id; 0 when id is no cap of c. */
int  section_cap_of(const SectionCut *c, const Scene *s, int32_t id, int *obj, int *plane);
/* The figures of plane i summed over the loaded objects (not the grid
 * copies). */
void section_total(const SectionCut *c, const Scene *s, int i, SectionFigures *out);

#endif
