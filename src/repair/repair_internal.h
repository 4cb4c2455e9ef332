#ifndef ZV_REPAIR_INTERNAL_H
#define ZV_REPAIR_INTERNAL_H
/* repair_internal: what the repair's steps share (src/repair/).
 *
 * The repair works on a copy of the mesh's arrays (Rep.w), so that a
 * failure leaves the caller's mesh as it was; repair.c puts the copy in
 * place at the end. Topology is taken on points, as the check takes it:
 * vertices at one position (bit for bit, -0 = +0) are one point
 * (Rep.pid). The steps after cleaning work object by object on an
 * ObjTopo: the object's corners with their points renumbered from 0,
 * and the pairing of its half-edges (a corner is also the half-edge
 * from its point to the next corner's). */

#include <stddef.h>
#include <stdint.h>

#include <pthread.h>

#include "invariant.h"
#include "meshcheck.h"
#include "repair.h"

#define RP_NONE UINT32_MAX

/* mate[c] of a half-edge without a single partner */
#define RP_BOUNDARY UINT32_MAX          /* the only face on its edge */
#define RP_NONMANIF (UINT32_MAX - 1)    /* three or more faces on its edge */
#define RP_SELF     (UINT32_MAX - 2)    /* from a point to itself: no edge */
#define RP_SKIPPED  (UINT32_MAX - 3)    /* of a degenerate face: out of the topology */
#define RP_SPECIAL  RP_SKIPPED          /* corners stay below this */

/* ==== The repair under way ==== */

/* Positions hashed: a table of vertex indices, a vertex for each point. */
typedef struct {
    uint32_t *slot;             /* RP_NONE: empty */
    size_t    size;             /* a power of two, at least twice the points */
} PosHash;

/* How boldly an object is repaired (guard.c): 0 every step asked; then
 * less at each level, until RP_LEVEL_UNTOUCHED leaves it as it was. */
enum { RP_LEVEL_NO_CUTS = 1, RP_LEVEL_NO_SPLITS = 2, RP_LEVEL_NO_WINDING = 3, RP_LEVEL_UNTOUCHED = 4 };

typedef struct {
    const RepairOpts *opt;
    RepairReport     *rep;
    const uint8_t    *level;    /* per object */
    Mesh      w;                /* the working copy (its arrays the repair's own) */
    uint32_t  nverts0;          /* vertices of the input: those after are new */
    size_t    vcap;             /* room in w.pos, w.rgb, pid, anchor */
    uint32_t *pid;              /* vertex -> point */
    uint32_t  npts;
    PosHash   ph;               /* point -> a vertex there */
    uint32_t *anchor;           /* per new vertex (index - nverts0): the vertex it follows in the output */
    uint32_t *loc;              /* point -> the current object's point, RP_NONE (reset after each object) */
    size_t    loccap;
    int       clean;            /* no degenerate face is left (the clean ran) */
    uint32_t  dup_unsettled;    /* objects that lost duplicates and do not end settled (rp_outward) */
    uint32_t  poly_flips;       /* faces of four corners or more flipped */
    /* w.pos and w.rgb are the input's own until something changes them
     * (rp_pos_own): most repairs move and add no vertex */
    int       pos_borrowed;
    int       pos_changed;      /* a position moved or a vertex was added (rp_pos_own) */
} Rep;

/* ==== Not worse (guard.c) ==== */

typedef struct {
    const Mesh *m;
    CheckOpts   co;
    MeshCheck   mc;
    int         rc;
    char        err[256];
    pthread_t   th;
    int         threaded;
} Before;

/* The check of the input: on a helper thread when opt allows two
 * threads or more and now is 0 (its crossing test on that thread
 * alone), else now (on opt's threads). rp_before_wait returns its
 * result. */
int  rp_before_start(Before *b, const Mesh *m, const RepairOpts *opt, int now);
int  rp_before_wait(Before *b);
void rp_before_free(Before *b);
/* Each object whose figures are worse after than before goes up a
 * level (up to RP_LEVEL_UNTOUCHED); how many did. */
uint32_t rp_worse(const MeshCheck *before, const MeshCheck *after, uint8_t *level);

/* Cancelled (RepairOpts.cancel)? */
int  rp_cancelled(const Rep *r);

/* Mesh face f's corners are [face_start[f], face_start[f + 1]). */
static inline const float *rp_vpos(const Rep *r, uint32_t v) { return r->w.pos + 3 * (size_t)v; }

/* ==== Points (posmap.c) ==== */

/* Make w.pos and w.rgb the repair's own copies (room for vcap
 * vertices), before they change (pos_changed set). 0 or -1 out of memory. */
int  rp_pos_own(Rep *r);

/* The coordinate's bits with -0 made +0. */
uint32_t rp_coord_bits(float f);
/* Number every vertex's point (vertices at one position share one, in
 * vertex order): r->pid, r->npts, r->ph. 0 or -1 out of memory. */
int  rp_points_build(Rep *r);
/* The point at position p, or RP_NONE (RP_NONE - 1: out of memory). */
uint32_t rp_point_find(Rep *r, const float p[3]);
/* Free the table until a new vertex needs it again. */
void rp_points_drop_table(Rep *r);
/* A new vertex at p (on the point there, if there is one: the callers
 * see that a new position is free first) with colour rgb (NULL: white
 * where the mesh has colours), placed after vertex anchor in the
 * output. Its index, or RP_NONE (out of memory, or 32-bit indices
 * full). */
uint32_t rp_vertex_add(Rep *r, const float p[3], const float *rgb, uint32_t anchor);
void rp_points_free(Rep *r);

/* ==== Exactly (exactsign.c) ==== */

/* Are a, b and c on one line, exactly (the check's test of a degenerate face)? */
int  rp_collinear(const float *a, const float *b, const float *c);
/* Is mesh face f degenerate (fewer than three corners, or every corner
 * on one line), as the check decides? */
int  rp_face_degenerate(const Rep *r, uint32_t f);
/* The same for the polygon of the n vertices v, and for n positions. */
int  rp_poly_degenerate(const Rep *r, const uint32_t *v, uint32_t n);
int  rp_pos_degenerate(const float *const *p, uint32_t n);

/* ==== The steps over the whole mesh ==== */

int  rp_weld(Rep *r);                           /* fuse.c */
int  rp_clean(Rep *r);                          /* tidy.c */
/* The vertices in output order: new ones after their anchors, unused
 * ones dropped when drop_unused (counted in rep->unused); every index
 * renumbered, object vertex ranges made exact. */
int  rp_renumber(Rep *r, int drop_unused);      /* tidy.c */

/* ==== One object's topology (halfedge.c) ==== */

typedef struct {
    uint32_t  obj;              /* its index */
    uint32_t  f0, nf;           /* its faces in the mesh */
    uint32_t  c0, nc;           /* its corners */
    int       tris;             /* every face a triangle: the face of corner c is c / 3 */
    uint32_t *cface;            /* relative corner -> relative face (NULL when tris: rp_cface) */
    /* relative corner -> its point (rp_cpt): numbered from 0 for the
     * object (cpt) when it is a small part of the mesh; the mesh's own
     * points (cpt NULL: no array) when it is most of it, where arrays of
     * the mesh's points cost no more than the object's */
    uint32_t *cpt;
    uint32_t  npts;             /* its points (the mesh's when cpt is NULL) */
    uint32_t *gpt;              /* the object's point -> the mesh's point (cpt only) */
    uint8_t  *skip;             /* per relative face: degenerate, out of the topology */
    uint32_t *mate;             /* relative corner -> the other half-edge of its edge, or RP_* */
    uint32_t *nm_half;          /* the half-edges of the non-manifold edges, edge by edge */
    uint32_t *nm_group;         /* start of each edge's run in nm_half, then the end */
    uint32_t  nm_ngroup;        /* edges (nm_group has one more entry) */
    uint32_t  nm_nhalf;
    uint32_t  nboundary;        /* half-edges with RP_BOUNDARY */
} ObjTopo;

/* Object i of r's working mesh: its points, its degenerate faces and the
 * pairing of its half-edges. 0 or -1 out of memory (t freed). */
int  rp_topo_build(Rep *r, uint32_t i, ObjTopo *t);
/* The pairing again, after the corners' points changed (the points
 * again first when points is set). */
int  rp_topo_pair(Rep *r, ObjTopo *t, int points);
void rp_topo_free(Rep *r, ObjTopo *t);
/* The faces newly marked skip leave the pairing (their edges' other
 * faces pair again), without building it again. */
int  rp_topo_unpair(Rep *r, ObjTopo *t);

static inline uint32_t rp_start(const Rep *r, const ObjTopo *t, uint32_t f)
{
    return t->tris ? 3 * f : r->w.face_start[t->f0 + f] - t->c0;
}

/* The relative face of relative corner c. */
static inline uint32_t rp_cface(const ObjTopo *t, uint32_t c)
{
    return t->tris ? c / 3 : t->cface[c];
}

/* The corner after c in its face (the end of half-edge c). */
static inline uint32_t rp_next(const Rep *r, const ObjTopo *t, uint32_t c)
{
    if (t->tris)
        return c % 3 == 2 ? c - 2 : c + 1;
    uint32_t f = t->cface[c];
    return c + 1 < rp_start(r, t, f + 1) ? c + 1 : rp_start(r, t, f);
}

static inline uint32_t rp_prev(const Rep *r, const ObjTopo *t, uint32_t c)
{
    if (t->tris)
        return c % 3 == 0 ? c + 2 : c - 1;
    uint32_t f = t->cface[c], s = rp_start(r, t, f);
    return c > s ? c - 1 : rp_start(r, t, f + 1) - 1;
}

/* Mesh vertex of relative corner c, and its point. */
static inline uint32_t rp_cvert(const Rep *r, const ObjTopo *t, uint32_t c) { return r->w.corner[t->c0 + c]; }

static inline uint32_t rp_cpt(const Rep *r, const ObjTopo *t, uint32_t c)
{
    return t->cpt ? t->cpt[c] : r->pid[r->w.corner[t->c0 + c]];
}

/* A big array: malloc (or calloc when zero) and, as a loaded mesh's
 * arrays are, huge pages asked for and the pages faulted in by one call
 * (bigmem.h): a first touch a page costs more than the work on it.
 * Free with free(). */
void *rp_big(size_t bytes, int zero);

/* Union-find over [0, n) (the smaller root wins, path halving). */
uint32_t *rp_uf_new(size_t n);
uint32_t rp_uf_find(uint32_t *p, uint32_t i);
int      rp_uf_union(uint32_t *p, uint32_t a, uint32_t b);

/* Face f's normal by Newell's method (not unit; zero for no area). */
void rp_face_normal(const Rep *r, uint32_t f, double n[3]);

/* ==== The steps on one object ==== */

/* twins.c: the duplicate faces that go leave t's topology (skip) and are
 * marked in drop[] (per mesh face), counted in the report. */
int  rp_twins(Rep *r, ObjTopo *t, uint8_t *drop);

/* fins.c: split the non-manifold edges and vertices; t's pairing is
 * rebuilt when anything changed. The faces cut loose from a fin of an
 * odd number are listed in *cuts (each by the two vertices its cut edge
 * ends on): rp_cuts_settle puts back those the holes did not close
 * (fills: the object's fills taken), or drops them with their part when
 * it is a stray fin. */
typedef struct {
    uint32_t *v;                /* 2 per cut */
    uint32_t *he;               /* per cut: the half-edge cut loose (relative corner) */
    uint32_t  n, cap;
    uint32_t  vbase;            /* vertices from here on are the split's copies */
    /* loops left open that run along a cut: listed only if the cut stays */
    RepairHole *pend;
    uint32_t   *pend_cut;
    uint32_t    npend, pendcap;
} Cuts;
int  rp_manifold(Rep *r, ObjTopo *t, Cuts *cuts);
/* orient.c: flip the fewest faces so that each orientable patch
 * agrees (t's pairing follows the flips); rp_outward turns the closed
 * parts that are inside out. */
int  rp_winding(Rep *r, ObjTopo *t);
/* *settled (when not NULL): every part agrees (no non-manifold edge, no
 * non-orientable patch), so that the check can find none inside out */
int  rp_outward(Rep *r, ObjTopo *t, int *settled);
/* Flip face f (mesh index), keeping its first corner: the same fan of
 * triangles, each the other way round. */
void rp_flip_face(Rep *r, uint32_t f);

/* ==== Holes (loops.c, fill.c, fillcheck.c) ==== */

/* A fill: triangles of mesh vertices, for one loop of one object. */
typedef struct {
    uint32_t  loop;             /* its loop (Holes.loop) */
    uint32_t *tri;              /* 3 mesh vertices a triangle */
    uint32_t  ntri;
    int32_t   mat;              /* the material of the faces around it */
} Fill;

/* The boundary loops of one object, each a cycle of its points in the
 * order a fill runs them (against the faces around it). */
typedef struct {
    uint32_t *pts;              /* the loops' points (the object's), one after another */
    uint32_t *vert;             /* per loop point: a mesh vertex there (of a face on the loop) */
    uint32_t *face;             /* per loop point i: the mesh face on the edge from point i to i + 1 */
    uint32_t  npts, ptcap;
    uint32_t *start;            /* nloops + 1 offsets into pts */
    uint32_t  nloops, startcap;
    /* the boundary that makes no cycle (edges that do not run one way
     * round): each group's edges and a mesh vertex on it */
    uint32_t *stray_edges, *stray_vertex;
    uint32_t  nstray, straycap;
} Loops;

int  rp_loops_find(Rep *r, ObjTopo *t, Loops *l);
void rp_loops_free(Loops *l);

/* Fill the loops of one object; the fills that pass (fillcheck.c) go
 * to *out (out_n of them), the rest are counted open. */
int  rp_holes(Rep *r, ObjTopo *t, Cuts *cuts, Fill **out, uint32_t *out_n, uint64_t *dp_budget);

/* How a loop is filled: the methods in the order tried. */
typedef enum { FILL_DP, FILL_EAR, FILL_FAN, FILL_NONE } FillMethod;

/* Loops of up to this many edges are triangulated by the dynamic
 * program (O(n^3) time, O(n^2) memory); up to RP_EAR_MAX by ear
 * clipping (O(n^2)); larger ones by a fan. RP_DP_BUDGET bounds the
 * dynamic program's triangles over one repair. */
#define RP_DP_MAX     128u
#define RP_EAR_MAX    8192u
#define RP_DP_BUDGET  (1ull << 27)

/* fill.c: a triangulation of loop k by method m into f (ntri 0: the
 * method found none). Edges of the object (EdgeSet) the fill must not
 * use again. */
typedef struct EdgeSet EdgeSet;
int  rp_fill_make(Rep *r, ObjTopo *t, const Loops *l, uint32_t k, FillMethod m, const EdgeSet *es,
                  uint64_t *dp_budget, Fill *f);

/* The edges of one object as point pairs, to ask whether an edge exists. */
EdgeSet *rp_edges_new(const ObjTopo *t, const Rep *r);
int  rp_edges_has(const EdgeSet *es, uint32_t a, uint32_t b);
void rp_edges_free(EdgeSet *es);

/* fillcheck.c: which of the candidate fills fills[nfixed..n) cross the
 * object's faces, the fills taken (fills[0..nfixed)) or each other,
 * or make a duplicate or non-manifold face (the check's own tests on
 * the fills and the faces near them): bad[i - nfixed] set for each. 0
 * or -1 (out of memory, cancelled). */
int  rp_fills_cross(Rep *r, const ObjTopo *t, Fill *fills, uint32_t nfixed, uint32_t n, uint8_t *bad);

/* The crossing pairs each group of faces moved by a split takes part in
 * (against the object's other faces near them and the other groups;
 * face: relative faces, group[i] face i's group), with the faces where
 * they are (original 0) or where they were (original 1: each vertex
 * from vbase on at the vertex it copies, its anchor). count[g] for each
 * group; *unsure when the crossing test stopped on its budget. */
int  rp_moved_cross(Rep *r, const ObjTopo *t, const uint32_t *face, const uint32_t *group, uint32_t n,
                    uint32_t vbase, int original, uint32_t *count, uint32_t ngroup, int *unsure);

/* holes.c: the open loops found so far are listed here (up to
 * REPAIR_HOLES_MAX). */
int  rp_hole_open(Rep *r, uint32_t obj, uint32_t edges, uint32_t vertex, RepairOpenWhy why);

/* The most faces a stray fin has (fins.c: a small open part cut loose
 * from a non-manifold edge, that no fill closes, is dropped). */
#define RP_FIN_FACES 4u

/* After the holes: the cuts no fill closed are put back, or, where what
 * was cut loose is a stray fin, its faces marked in drop[] (per mesh
 * face) and skipped in t. */
int  rp_cuts_settle(Rep *r, ObjTopo *t, Cuts *cuts, const Fill *fills, uint32_t nfills, uint8_t *drop);
void rp_cuts_free(Cuts *cuts);

/* repair.c: the faces marked in drop (NULL: none) gone, and the fills
 * in place, each after its object's faces. */
int  rp_faces_rebuild(Rep *r, const uint8_t *drop, Fill *const *fills, const uint32_t *nfills);

#endif
