#ifndef ZV_MESHCHECK_H
#define ZV_MESHCHECK_H
/* meshcheck: is this model right? The analysis behind --check, on a
 * loaded Mesh in file units (before the scene scales anything): per
 * object and per file, the size, surface area, volume and centre of
 * mass of closed meshes, connected parts, boundary edges and holes,
 * non-manifold edges and vertices, faces whose winding disagrees with
 * their neighbours, inside-out solids, degenerate and duplicate faces,
 * unused vertices and pairs of faces that intersect (exact predicates
 * through a bounding-volume hierarchy). Knows nothing of scenes,
 * screens or terminals: the reports are printed by oneshot/, and the
 * lists and per-face arrays are there for whatever draws them.
 *
 * Topology is taken on positions, as slicers take it: vertices at the
 * same position (bit for bit, -0 = +0) are one point, so a texture seam
 * that splits a vertex is not a hole. Each object is checked on its own
 * (its faces only); the file's figures are the objects' summed. Faces
 * keep their polygon form for the topology; area, volume and the
 * intersection tests take a polygon as the fan of triangles from its
 * first corner, as the rest of zview draws it. Degenerate faces (every
 * corner on one line) are counted as such and left out of the rest of
 * the topology (edges, non-manifold vertices, parts), as CGAL and the
 * slicers set them aside; duplicate faces are counted as such and left
 * out of the crossing test. */

#include <stdint.h>

#include "mesh.h"

/* Per-face flags (MeshCheck.face_flags). */
enum {
    CHECK_FLIPPED     = 1 << 0, /* among the fewest faces whose flip makes its part's winding agree */
    CHECK_DEGENERATE  = 1 << 1, /* zero area: its corners on one line (exactly) */
    CHECK_DUPLICATE   = 1 << 2, /* the same points as an earlier face of its object */
    CHECK_INTERSECTS  = 1 << 3, /* crosses another face of its object */
    CHECK_NONORIENT   = 1 << 4, /* in a non-orientable part (no flip makes it agree) */
    CHECK_OPEN        = 1 << 5, /* has a boundary edge */
    CHECK_NONMANIFOLD = 1 << 6, /* has an edge of three or more faces */
};

/* What the check found in one object, or (summed) in one file. */
typedef struct {
    uint32_t faces;
    uint32_t vertices;              /* distinct positions its faces use */
    uint32_t components;            /* parts: faces joined by shared edges (degenerate faces in none) */
    uint32_t boundary_edges;        /* edges of one face (the edges of non-degenerate faces only) */
    uint32_t holes;                 /* independent closed loops of boundary edges */
    uint32_t nonmanifold_edges;     /* edges of three or more faces */
    uint32_t nonmanifold_vertices;  /* points where separate fans of faces meet */
    uint32_t inconsistent_faces;    /* the fewest faces whose flip makes every orientable part agree */
    uint32_t nonorientable;         /* parts no flip can make agree (a Moebius strip) */
    uint32_t degenerate_faces;      /* zero area */
    uint32_t duplicate_faces;       /* faces on the same points as an earlier one */
    uint32_t unused_vertices;       /* vertices no face, point or line uses: a file's all of them, an
                                     * object's those within the range of vertex indices it uses */
    uint64_t self_intersections;    /* pairs of faces that cross (at least, when intersections_stopped) */
    int      intersections_tested;  /* self_intersections counted (CheckOpts.intersections) */
    int      intersections_stopped; /* the crossing test spent its budget and stopped: a lower bound */
    uint64_t pair_tests;            /* triangle pairs the crossing test decided exactly */
    uint64_t pair_budget;           /* the most it may: CHECK_PAIR_BUDGET of the triangles tested */
    int      closed;                /* has a non-degenerate face, and no boundary edge */
    int      watertight;            /* closed and edge-manifold */
    int      inside_out;            /* closed, and its volume (winding made to agree) is negative */
    int      has_volume;            /* volume and centre of mass mean something: closed and orientable */
    double   area;                  /* file units squared */
    double   volume;                /* enclosed volume, >= 0, file units cubed (has_volume) */
    double   centre[3];             /* centre of mass of the enclosed volume, uniform density (has_volume) */
    float    lo[3], hi[3];          /* bounding box of the positions its faces use; lo > hi: none */
} CheckCounts;

/* One object: its counts, and (CheckOpts.detail) where the problems are,
 * as mesh vertex and face indices an overlay can draw. */
typedef struct {
    char        name[MESH_NAME_MAX];
    uint32_t    face_first, face_count;     /* its faces in the mesh */
    CheckCounts c;
    uint32_t   *boundary;       /* 2 vertex indices per boundary edge (c.boundary_edges) */
    uint32_t   *nm_edges;       /* 2 vertex indices per non-manifold edge (c.nonmanifold_edges) */
    uint32_t   *nm_verts;       /* a vertex index per non-manifold vertex (c.nonmanifold_vertices) */
    uint32_t   *pairs;          /* 2 mesh face indices per intersecting pair, sorted */
    uint32_t    npairs;         /* pairs kept: all of them, up to CHECK_PAIRS_MAX */
} CheckObject;

#define CHECK_PAIRS_MAX 1000000u

/* The crossing test's work is bounded: of an object's n triangles (its
 * faces' fan triangles, degenerate and duplicate ones left out) at most
 * this many pairs go to the exact test, and 16 times as many are
 * compared by box; past that it stops (intersections_stopped). 64 a
 * triangle is 8 times what the dragon needs; a million is the floor for
 * small objects. */
#define CHECK_PAIR_BUDGET(n) (64 * (uint64_t)(n) + (1u << 20))

/* Phases timed (wall ms), for the benchmark. */
enum { CHECK_T_WELD, CHECK_T_EDGES, CHECK_T_SHAPE, CHECK_T_DUPS, CHECK_T_CROSS, CHECK_T_COUNT };

typedef struct {
    int        threads;         /* for the intersection tests; <= 1: the caller alone */
    int        intersections;   /* test pairs of faces for crossing */
    int        detail;          /* keep the lists and per-face arrays */
    const int *cancel;          /* NULL, or set (atomically) to stop: meshcheck_run fails "cancelled" */
} CheckOpts;

typedef struct {
    CheckCounts  file;          /* the objects' figures together */
    CheckObject *objs;          /* one per mesh object */
    uint32_t     nobjs;
    uint8_t     *face_flags;    /* per mesh face, CHECK_* (detail), else NULL */
    uint32_t    *face_part;     /* per mesh face, its part within its object, from 0, UINT32_MAX for a
                                 * degenerate face (detail), else NULL */
    char         unit[8];       /* the unit the format states ("mm", "m"), "" none */
    double       ms[CHECK_T_COUNT];
} MeshCheck;

/* Check every object of m. Returns 0, or -1 out of memory or cancelled
 * (the message in err, *mc left empty). m is not changed. */
int  meshcheck_run(MeshCheck *mc, const Mesh *m, const CheckOpts *opt, char *err, size_t errlen);
void meshcheck_free(MeshCheck *mc);

/* Nothing wrong: faces, closed, manifold, agreeing, outward, no
 * degenerate or duplicate faces, no crossing (when tested; a crossing
 * test that stopped on its budget proved none). Several parts and
 * unused vertices are not problems. */
int  meshcheck_sound(const CheckCounts *c);

/* The problems in words, most serious first ("1 hole (4 boundary
 * edges)", "12 flipped faces"), at most max into item; returns how many
 * there are (0: sound). */
#define CHECK_PROBLEM_LEN  96
#define CHECK_PROBLEMS_MAX 10       /* there are no more kinds */
int  meshcheck_problems(const CheckCounts *c, char (*item)[CHECK_PROBLEM_LEN], int max);

/* The same on one line, ", " between them, or "sound"; cut to fit n
 * bytes. Returns the number of problems. */
int  meshcheck_verdict(const CheckCounts *c, char *buf, size_t n);

#endif
