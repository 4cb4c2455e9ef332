#ifndef ZV_CHECK_INTERNAL_H
#define ZV_CHECK_INTERNAL_H
/* check_internal: what the check's passes share (src/check/). One
 * object is checked at a time, in an ObjCheck: its faces and corners,
 * its points (positions, renumbered from 0 for the object), and the
 * half-edge pairing the topology pass builds and the later passes read.
 *
 * A corner is also a half-edge: corner c of a face runs from its point
 * to the point of the face's next corner. Corners and faces are counted
 * from the object's first (relative indices). */

#include <stddef.h>
#include <stdint.h>

#include "invariant.h"
#include "meshcheck.h"
#include "pool.h"

#define CHECK_NONE UINT32_MAX

/* mate[c] for a half-edge that has no single partner */
#define MATE_BOUNDARY   UINT32_MAX          /* the only face on its edge */
#define MATE_NONMANIF   (UINT32_MAX - 1)    /* three or more faces on its edge */
#define MATE_DEGENERATE (UINT32_MAX - 2)    /* from a point to itself: no edge */
#define MATE_SKIPPED    (UINT32_MAX - 3)    /* of a degenerate face: out of the topology */
#define MATE_FIRST_SPECIAL MATE_SKIPPED     /* corners of an object stay below this */

typedef struct {
    const Mesh      *m;
    const CheckOpts *opt;
    Pool     *pool;             /* helper threads for the crossing tests, NULL: the caller alone */
    uint32_t  f0, nf;           /* the object's faces in the mesh */
    uint32_t  c0, nc;           /* its corners in the mesh */
    int       tris;             /* every face a triangle: the face of corner c is c / 3 */
    uint32_t *cface;            /* relative corner -> relative face (NULL when tris) */
    uint32_t *vpt;              /* mesh vertex -> the object's point (for the vertices it uses) */
    uint32_t *prep;             /* the object's point -> a mesh vertex at that position */
    uint32_t  npts;
    uint32_t  max_corners;      /* corners of its largest face */
    uint32_t *mate;             /* relative corner -> the other half-edge of its edge, or MATE_* */
    /* the half-edges of the non-manifold edges, edge by edge */
    uint32_t *nm_half;          /* relative corners */
    size_t    nm_nhalf, nm_half_cap;
    uint32_t *nm_group;         /* start of each edge's run in nm_half, plus the end */
    size_t    nm_ngroup, nm_group_cap;
    uint8_t  *flags;            /* per relative face: CHECK_* */
    uint32_t *part;             /* per relative face: its part, from 0 */
    CheckCounts *c;
    CheckObject *out;           /* the lists go here when opt->detail */
    double    ref[3];           /* the bounding box's centre: volumes are summed about it */
} ObjCheck;

static inline const float *oc_vpos(const ObjCheck *o, uint32_t v) { return o->m->pos + 3 * (size_t)v; }

/* The mesh vertex of relative corner c, and its point. */
static inline uint32_t oc_vert(const ObjCheck *o, uint32_t c) { return o->m->corner[o->c0 + c]; }
static inline uint32_t oc_pt(const ObjCheck *o, uint32_t c) { return o->vpt[oc_vert(o, c)]; }

/* Relative face f's corners are [oc_start(f), oc_start(f + 1)). */
static inline uint32_t oc_start(const ObjCheck *o, uint32_t f) { return o->m->face_start[o->f0 + f] - o->c0; }

static inline uint32_t oc_face(const ObjCheck *o, uint32_t c) { return o->tris ? c / 3 : o->cface[c]; }

/* The corner after c in its face (the end of half-edge c). */
static inline uint32_t oc_next(const ObjCheck *o, uint32_t c)
{
    if (o->tris)
        return c % 3 == 2 ? c - 2 : c + 1;
    uint32_t f = o->cface[c];
    return c + 1 < oc_start(o, f + 1) ? c + 1 : oc_start(o, f);
}

/* counts.c: c with nothing counted yet (its box empty: lo > hi). */
void check_counts_empty(CheckCounts *c);

/* Grow a uint32_t list by one; 0, or -1 out of memory. */
int  check_push(uint32_t **a, size_t *n, size_t *cap, uint32_t v);

/* Union-find over [0, n) in one array: p[i] = its parent; a new one
 * (every element alone), NULL out of memory. */
uint32_t *check_identity(size_t n);
/* A big array, malloc'ed (zero: calloc'ed), with huge pages asked for
 * and its pages faulted in by one call (bigmem.h): in a VM a first
 * touch a page costs more than the pass's work on it. free() frees it. */
void *check_big(size_t bytes, int zero);
uint32_t check_find(uint32_t *p, uint32_t i);
/* Join the sets of a and b; 1 when they were apart. */
int      check_union(uint32_t *p, uint32_t a, uint32_t b);

/* weld.c: mesh vertex -> point (vertices at one position are one
 * point, numbered from 0 in vertex order), for the whole mesh. pid gets
 * nverts entries, *npts_out the number of points. Returns 0 or -1 (out
 * of memory). */
int  check_weld(const Mesh *m, uint32_t *pid, uint32_t *npts_out);

/* topo.c: check_pairing: the degenerate faces (flagged and counted
 * first: the rest leaves them out), the half-edge pairing (mate, the
 * non-manifold groups), the boundary and non-manifold edges; then
 * check_vertices: the holes and the non-manifold vertices (and their
 * locations). check_vertices reads mate[] and the groups and writes no
 * flag, so that it may run beside check_shape and check_duplicates
 * when no list or location is asked for (they write their own). */
int  check_pairing(ObjCheck *o);
int  check_vertices(ObjCheck *o);

/* shape.c: the winding (fewest flips, non-orientable parts) and the
 * parts (without the degenerate faces: their part is CHECK_NONE);
 * duplicate faces (dups.c). Both read mate[]. check_measures, after
 * the winding: area, volume and centre of mass (it reads the positions
 * and the flags alone, so it may run beside the crossing test). */
int  check_shape(ObjCheck *o);
void check_measures(ObjCheck *o);
int  check_duplicates(ObjCheck *o);
/* Is relative face f degenerate (all its corners on one line)? */
int  check_face_degenerate(const ObjCheck *o, uint32_t f);

/* cross.c: the pairs of faces that cross, through a BVH. */
int  check_crossings(ObjCheck *o);

/* tritri.c: do the non-degenerate triangles a and b (corner positions,
 * and point ids: equal ids are the same point) meet anywhere beyond the
 * corners they share? 1 yes, 0 no, CHECK_SAME_TRI when they share all
 * three corners (the same triangle: the caller decides). */
#define CHECK_SAME_TRI 2
int  check_tri_pair(const float *const a[3], const uint32_t ia[3], const float *const b[3], const uint32_t ib[3]);

/* locate.c: where the problems are, when CheckOpts.locations asks
 * (each a no-op otherwise). check_locate_topology at the end of the
 * topology (the holes' loops from mate[], the non-manifold edges from
 * their groups); check_locate_vertex for each non-manifold point p as
 * count_fans finds it (*cap: its list's room, 0 at first);
 * check_locate_faces after the duplicates; check_locate_crossings after
 * the crossings (a point on each pair; the pairs list dropped then
 * unless detail keeps it). 0, or -1 out of memory. */
int  check_locate_topology(ObjCheck *o);
int  check_locate_vertex(ObjCheck *o, uint32_t p, size_t *cap);
int  check_locate_faces(ObjCheck *o);
int  check_locate_crossings(ObjCheck *o);
/* A point on both of the triangles a and b, which meet (check_tri_pair
 * said so): in double, on both within rounding. */
void check_tri_point(const float *const a[3], const float *const b[3], double out[3]);
void check_locations_free(CheckLocations *l);

#endif
