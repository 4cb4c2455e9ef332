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

#include <stddef.h>
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

/* Where one object's problems are (CheckOpts.locations): of each kind
 * the first `locations` of them, so that a script (--check --json), the
 * text report and the viewer's problem keys can go to each. Faces are
 * mesh face indices: the file's faces from 0 in file order across its
 * objects. Points are positions as the file gives them (welded points
 * have no one vertex index). The kinds, in the verdict's order: */
typedef enum {
    CHECK_LOC_HOLES,            /* a closed loop of boundary edges a hole */
    CHECK_LOC_NM_EDGES,         /* an edge of three or more faces: its ends and the faces on it */
    CHECK_LOC_NM_VERTICES,      /* a point where separate fans of faces meet */
    CHECK_LOC_FLIPPED,          /* a face among the fewest whose flip makes the winding agree */
    CHECK_LOC_DEGENERATE,       /* a face of zero area */
    CHECK_LOC_DUPLICATE,        /* a face on the same points as an earlier one */
    CHECK_LOC_CROSSING,         /* a pair of faces that cross, and a point on both */
    CHECK_LOC_KINDS
} CheckLocKind;

typedef struct {
    /* holes: the independent cycles of the boundary edges (one per
     * closed loop; where loops touch at a point, one each), c.holes of
     * them; each loop its points in order, the last joined to the first */
    uint32_t  nloops;
    uint32_t *loop_start;       /* nloops + 1: loop i's points are [loop_start[i], loop_start[i + 1]) */
    float    *loop_pt;          /* 3 per point */
    double   *loop_length;      /* per loop: its perimeter, file units */
    /* non-manifold edges: both ends, and the faces on the edge (ascending) */
    uint32_t  nedges;
    float    *edge_pt;          /* 6 per edge */
    uint32_t *edge_start;       /* nedges + 1 into edge_face */
    uint32_t *edge_face;
    /* non-manifold vertices */
    uint32_t  nverts;
    float    *vert_pt;          /* 3 per vertex */
    /* flipped, degenerate and duplicate faces, ascending */
    uint32_t  nfaces[3];        /* [k - CHECK_LOC_FLIPPED] */
    uint32_t *face[3];
    /* crossing pairs, as c.self_intersections counts them (the lower face first, pairs ascending) */
    uint32_t  npairs;
    uint32_t *pair_face;        /* 2 per pair */
    double   *pair_pt;          /* 3 per pair: a point on both faces */
} CheckLocations;

/* One object: its counts, and (CheckOpts.detail) where the problems are,
 * as mesh vertex and face indices an overlay can draw. */
typedef struct {
    char        name[MESH_NAME_MAX];
    uint32_t    face_first, face_count;     /* its faces in the mesh */
    CheckCounts c;
    CheckLocations loc;         /* CheckOpts.locations */
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
    uint32_t   locations;       /* locate the first this many problems of each kind (CheckObject.loc); 0 none */
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

/* The most problems of one kind --check --json locates by default
 * (--max-locations), and the text report lists. */
#define CHECK_LOCATIONS_JSON 100
#define CHECK_LOCATIONS_TEXT 3

/* Check every object of m. Returns 0, or -1 out of memory or cancelled
 * (the message in err, *mc left empty). m is not changed. */
int  meshcheck_run(MeshCheck *mc, const Mesh *m, const CheckOpts *opt, char *err, size_t errlen);
void meshcheck_free(MeshCheck *mc);

/* ==== The figures as data ====
 *
 * Every figure of CheckCounts but the measures (area, volume, centre,
 * box) is one row of check_rows (counts.c): how it adds up over objects
 * and files, its --json member, where the text report says it, whether
 * it is a problem and the words for that. The sums, the JSON, the text
 * report, the verdicts and the exit status read the rows, so a new
 * check is its pass and one row. */

typedef enum {
    CHECK_U32,                  /* uint32_t count */
    CHECK_U64,                  /* uint64_t count */
    CHECK_FLAG,                 /* int, 0 or 1 */
} CheckType;

/* How the figure of several parts (a file's objects, a scene's files)
 * comes from theirs. A part without faces adds nothing but its
 * CHECK_SUM_EVERY figures. */
typedef enum {
    CHECK_SUM_ADD,              /* the parts' with faces added */
    CHECK_SUM_EVERY,            /* every part's added, with faces or not */
    CHECK_SUM_ALL,              /* a flag: every part with faces has it, and there is one */
    CHECK_SUM_ANY,              /* a flag: some part has it */
} CheckSum;

/* When the figure is a problem (not sound, exit status 3). */
typedef enum {
    CHECK_FINE,                 /* never: a figure to know */
    CHECK_BAD_SET,              /* when not zero */
    CHECK_BAD_ZERO,             /* when zero (no faces: nothing was checked) */
} CheckBad;

/* The forms a figure is said in. */
typedef enum {
    CHECK_SAY_TEXT,             /* its phrase in the text report's line: "4 boundary" */
    CHECK_SAY_PROBLEM,          /* the verdict (--check, --json, the info panel): "1 hole (4 boundary edges)" */
    CHECK_SAY_SHORT,            /* the status bar's: "1 hole" */
} CheckSay;

typedef struct CheckRow CheckRow;
struct CheckRow {
    const char *field;          /* the CheckCounts member */
    size_t      offset, size;   /* offsetof and sizeof that member */
    CheckType   type;
    CheckSum    sum;
    const char *json;           /* the --json member, in row order; NULL: not written */
    int         json_bool;      /* a count written as a bool: whether there is any */
    /* The text report: the row's line (1 the first, after the
     * measures; 0 none) with its label, and its phrase there: the
     * number then text_one or text_many ("" the number alone), or for
     * a flag text_one when set; after sep (NULL ", ") unless first on
     * the line. text_one NULL: said by another row's words. */
    int         line;
    const char *label;
    const char *sep;
    const char *text_one, *text_many;
    int         text_alone;     /* when set, it alone is its line; unset, it says nothing */
    /* A problem: when, the problem's place in the verdict (1 first) and
     * in the status bar's, and its words (the number first for a count;
     * singular, plural). */
    CheckBad    bad;
    int         bound;          /* bound_at is a flag that makes this count a lower bound, and a problem */
    size_t      bound_at;
    int         rank, short_rank;
    const char *one, *many;
    const char *short_one, *short_many;
    /* words where the forms above do not fit: 1 when it wrote buf, 0
     * for the form above (NULL: always those) */
    int       (*say)(const CheckCounts *c, CheckSay form, char *buf, size_t n);
};

extern const CheckRow check_rows[];
extern const int      check_nrows;

/* Row r's figure in c (a flag 0 or 1). */
uint64_t meshcheck_value(const CheckRow *r, const CheckCounts *c);
/* Is row r's figure in c a problem? */
int  meshcheck_bad(const CheckRow *r, const CheckCounts *c);
/* Row r of c in words in form into buf ("" when it says nothing there). */
void meshcheck_say(const CheckRow *r, const CheckCounts *c, CheckSay form, char *buf, size_t n);

/* total = the figures of n parts together: parts[i] at (const char *)
 * first + i * stride (a file's objects, a scene's files). The rows by
 * their CheckSum; the area and volume added, the centre of mass
 * weighted by volume, the box the parts' together. A file's vertices
 * and unused vertices are its own, not its objects' (objects share
 * points, and a vertex between their ranges is the file's alone): its
 * caller sets them after. */
void meshcheck_sum(CheckCounts *total, const CheckCounts *first, size_t n, size_t stride);

/* The kinds of location by their rows: kind k's count is the row
 * meshcheck_loc_row(k) (holes, nonmanifold_edges, ..., inconsistent_faces,
 * ..., self_intersections), whose --json member names its locations too
 * and whose text line lists them. meshcheck_loc_total is that count (a
 * lower bound where the crossing test stopped), meshcheck_loc_located
 * how many of them l holds. */
const CheckRow *meshcheck_loc_row(CheckLocKind k);
uint64_t meshcheck_loc_total(const CheckCounts *c, CheckLocKind k);
uint32_t meshcheck_loc_located(const CheckLocations *l, CheckLocKind k);

/* ==== The problems one by one (items.c) ====
 *
 * The located problems of checks as one list to step through (the
 * viewer's . and , keys, --problem K): kind by kind in the verdict's
 * order, each kind file by file, object by object, as located. Each item
 * is a shape in its mesh's coordinates, to frame and to draw over the
 * model: lines (a hole's loop, a non-manifold edge and the outlines of
 * its faces, a face's outline, a crossing pair's two) and a point to
 * ring (a non-manifold vertex, the middle of a degenerate or duplicate
 * face, where a pair crosses). */
typedef struct {
    CheckLocKind kind;
    int         file;           /* the caller's number of its mesh */
    uint32_t    face_first;     /* its object's first face (which object of the mesh it is on) */
    uint32_t    num;            /* its number among the list's items of its kind, from 1 */
    uint32_t    line0, nlines;  /* its lines: CheckItems lines [line0, line0 + nlines) */
    int         has_ring;
    float       ring[3];
    uint32_t    count;          /* a hole's edges, a non-manifold edge's faces */
    double      length;         /* a hole's perimeter (the mesh's units) */
    uint32_t    face[2];        /* the face it is (flipped, degenerate, duplicate), the pair's two */
} CheckItem;

typedef struct {
    CheckItem *item;
    uint32_t   n;
    size_t     cap;
    uint32_t  *line_start;      /* nlines + 1: line k's points are pt[line_start[k] .. line_start[k + 1]) */
    uint8_t   *line_closed;     /* per line: its last point joined to its first */
    uint32_t   nlines;
    size_t     cap_lines, cap_closed;
    float     *pt;              /* 3 per point */
    size_t     npt, cap_pt;     /* floats */
} CheckItems;

/* Add the located problems of mc (a check of m, with CheckOpts.locations)
 * as file `file`; then meshcheck_items_order once every file is in:
 * the items kind by kind (files and objects in the order added) and
 * numbered within each kind. 0, or -1 out of memory. */
int  meshcheck_items_add(CheckItems *it, const MeshCheck *mc, const Mesh *m, int file);
void meshcheck_items_order(CheckItems *it);
void meshcheck_items_free(CheckItems *it);
/* The box of item i's points (lines and ring), the mesh's coordinates. */
void meshcheck_item_box(const CheckItems *it, uint32_t i, float lo[3], float hi[3]);

/* The text report's lines of the rows (the measures before them are
 * the caller's): a label and the phrases. Returns how many. */
#define CHECK_LINE_LEN   256
#define CHECK_LINES_MAX  16
typedef struct {
    const char *label;
    int         line;           /* the rows' line number (CheckRow.line) */
    char        text[CHECK_LINE_LEN];
} CheckLine;
int  meshcheck_lines(const CheckCounts *c, CheckLine *line, int max);

/* Nothing wrong: no row a problem (faces, closed, manifold, agreeing,
 * outward, no degenerate or duplicate faces, no crossing when tested; a
 * crossing test that stopped on its budget proved none). Several parts
 * and unused vertices are not problems. */
int  meshcheck_sound(const CheckCounts *c);

/* The problems in words, most serious first ("1 hole (4 boundary
 * edges)", "12 flipped faces"), at most max into item; returns how many
 * there are (0: sound). The _as form gives the status bar's words in
 * its order (form CHECK_SAY_SHORT: "1 hole", "12 flipped"). */
#define CHECK_PROBLEM_LEN  96
#define CHECK_PROBLEMS_MAX 10       /* there are no more kinds (test_checkrows holds the rows to it) */
int  meshcheck_problems(const CheckCounts *c, char (*item)[CHECK_PROBLEM_LEN], int max);
int  meshcheck_problems_as(const CheckCounts *c, CheckSay form, char (*item)[CHECK_PROBLEM_LEN], int max);

/* The same on one line, ", " between them, or "sound"; cut to fit n
 * bytes. Returns the number of problems. */
int  meshcheck_verdict(const CheckCounts *c, char *buf, size_t n);

#endif
