#ifndef ZV_REPAIR_H
#define ZV_REPAIR_H
/* repair: fix a loaded Mesh in place, so that --check finds the
 * problems it can fix gone (issue 30). The steps, each optional through
 * RepairOpts.steps, on each object alone (the check's definitions:
 * topology on positions bit for bit, -0 = +0; degenerate = every corner
 * on one line, exactly; duplicate = the same points as an earlier face
 * of its object):
 *
 *   weld      vertices at one position (within weld_eps, when set) become one
 *   clean     degenerate faces, a point repeated in a row within a
 *             face, and vertices nothing uses are dropped, and duplicate
 *             faces where no edge is left with one face (a two-sided
 *             flap goes whole)
 *   manifold  an edge of three or more faces is split so that each edge
 *             has at most two, and a point where separate fans of faces
 *             meet gets a vertex per fan; a stray fin (a part of at
 *             most RP_FIN_FACES faces cut loose from such an edge, that
 *             no fill closes) is dropped
 *   winding   the fewest faces flipped so that each part agrees; then,
 *             after the holes, closed parts that are inside out turned
 *             outward
 *   holes     every boundary loop filled (its own faces, added at the
 *             end of its object), unless it has more than max_hole edges
 *             or no fill of it avoids crossing the model
 *
 * They run weld, clean, manifold, winding, holes, outward. Crossing
 * faces are reported (the check's count after the repair), not changed.
 * No figure of the check comes out worse than it was: an object the
 * full repair would make worse is repaired again less boldly
 * (RepairReport.held_back); a stray fin dropped lowers the count of
 * faces, which is no problem figure. Positions of the vertices kept are
 * kept bit for bit (a split's copies and a fan's centre are new
 * vertices); the faces that were not dropped keep their order, material, colours and
 * texture coordinates; object ranges stay valid. doc/design.md (The
 * repair) says why the steps run in this order and which algorithm
 * each uses. */

#include <stddef.h>
#include <stdint.h>

#include "mesh.h"
#include "meshcheck.h"

enum {
    REPAIR_WELD     = 1,
    REPAIR_CLEAN    = 2,
    REPAIR_WINDING  = 4,
    REPAIR_HOLES    = 8,
    REPAIR_MANIFOLD = 16,
    REPAIR_DEFAULT  = 31,
};

typedef struct {
    unsigned steps;             /* REPAIR_* or'ed; 0 changes nothing */
    double   weld_eps;          /* file units; 0: bit-identical positions only */
    uint32_t max_hole;          /* 0: no limit; else loops of more edges stay open */
    int      threads;           /* <= 1: the caller alone */
    int      intersections;     /* count the crossing pairs (the check's crossing test), before and after */
    int      keep_checks;       /* check the input first and keep that check and the check of the
                                 * result in the report (RepairReport.before, .after): a caller
                                 * that shows both need not check again */
    const int *cancel;          /* NULL, or set (atomically) to stop: repair_mesh fails "cancelled" */
    /* NULL, or called once the repaired arrays are in the mesh for good
     * (repair_mesh then succeeds, and changes the mesh no more), before
     * the check of the result when that check reads the mesh in place:
     * a caller may start writing the mesh beside that check (--repair
     * on two threads or more) */
    void (*installed)(const Mesh *m, void *arg);
    void    *installed_arg;
} RepairOpts;

/* Why a loop was left open. */
typedef enum {
    REPAIR_OPEN_TOO_BIG = 1,    /* more edges than max_hole */
    REPAIR_OPEN_CROSSING,       /* every fill tried crossed the model or made an edge of three faces */
    REPAIR_OPEN_UNORIENTED,     /* its edges do not run one way round (a non-orientable part's rim) */
    REPAIR_OPEN_LONE_FACE,      /* the rim of one face alone: its fill would be the face again */
} RepairOpenWhy;

/* A loop left open: its object, its length and a vertex on it. */
typedef struct {
    uint32_t object;
    uint32_t edges;
    uint32_t vertex;            /* a mesh vertex of the repaired mesh on the loop */
    RepairOpenWhy why;
} RepairHole;

#define REPAIR_HOLES_MAX 1000u   /* open loops listed (all are counted) */

/* Phases timed (wall ms), for the benchmark: the weld, the clean, the
 * splits, winding and holes object by object, the vertices put in
 * order, the check of what is left, and the check of the input (when
 * the guard or RepairOpts.keep_checks asked for it). */
enum { REPAIR_T_WELD, REPAIR_T_CLEAN, REPAIR_T_OBJECTS, REPAIR_T_ORDER, REPAIR_T_CHECK, REPAIR_T_BEFORE,
       REPAIR_T_COUNT };

/* What each step did, and what is left. */
typedef struct {
    /* weld */
    uint32_t welded;            /* vertices merged into an earlier one */
    /* clean */
    uint32_t degenerate;        /* degenerate faces dropped */
    uint32_t duplicate;         /* duplicate faces dropped */
    uint32_t flaps;             /* faces dropped with their copies: a two-sided flap, either alone would leave an edge of one face */
    uint32_t dup_kept;          /* duplicate faces kept: dropping them would leave an edge of one face */
    uint32_t repeated;          /* corners dropped: a point again right after itself */
    uint32_t unused;            /* vertices dropped that nothing used */
    /* manifold */
    uint32_t nm_edges;          /* edges of three or more faces split */
    uint32_t nm_vertices;       /* points where separate fans met, split */
    uint32_t split_vertices;    /* vertices the splits added */
    uint32_t cuts_undone;       /* faces of an odd fin cut loose, then put back: no fill closed the cut */
    uint32_t fins;              /* faces of stray fins dropped (fins.c: a small open part cut loose) */
    /* winding */
    uint32_t flipped;           /* faces flipped to agree with their part */
    uint32_t outward;           /* closed parts turned outward */
    /* holes */
    uint32_t filled;            /* loops filled */
    uint32_t fill_faces;        /* triangles the fills added */
    uint32_t fill_vertices;     /* vertices they added (the centres of fans) */
    uint32_t fans;              /* loops filled by a fan from a new centre */
    uint32_t open;              /* loops left open */
    uint32_t open_largest;      /* edges of the largest of them */
    uint32_t open_too_big;      /* of them, for max_hole */
    /* objects repaired less boldly: the full repair left a figure of
     * the check worse than before (src/repair/guard.c) */
    uint32_t held_back;
    /* what is left, as the check counts it in the repaired mesh; counted
     * 0: that check could not run (out of memory, cancelled: the mesh is
     * repaired all the same) and the left_ figures are 0 */
    int      counted;
    uint32_t left_holes;
    uint32_t left_nm_edges;
    uint32_t left_nm_vertices;
    uint32_t left_flipped;
    uint32_t left_nonorientable; /* parts no flip can make agree (a Moebius strip) */
    uint32_t left_inside_out;   /* objects */
    uint32_t left_degenerate;
    uint32_t left_duplicate;
    uint64_t left_crossings;    /* pairs of faces that cross (RepairOpts.intersections) */
    int      crossings_tested;
    int      crossings_stopped; /* the crossing test stopped on its budget: at least left_crossings */
    int      crossings_same;    /* the repair changed none of the triangles the crossing test reads:
                                 * the input's crossing figures are the result's, not counted again */
    /* the mesh before and after */
    uint32_t faces_before, faces_after, verts_before, verts_after;
    /* the loops left open, the first REPAIR_HOLES_MAX (repair_report_free) */
    RepairHole *holes;
    uint32_t    nholes;
    double      ms;             /* wall time of repair_mesh, the check of what is left included */
    double      ms_phase[REPAIR_T_COUNT];
    /* RepairOpts.keep_checks: the check of the input (has_before) and of
     * the result (counted), with the crossing test when
     * RepairOpts.intersections; repair_report_free frees them */
    int         has_before;
    MeshCheck   before, after;
} RepairReport;

/* Repair m in place by opt's steps (NULL: REPAIR_DEFAULT, no weld
 * distance, no hole limit, one thread), filling *rep (zeroed first).
 * Returns 0, or -1 with "path: reason" in err (out of memory,
 * cancelled, a mesh too big for 32-bit indices after the repair): m is
 * then unchanged. Memory: the input, a copy of its faces and corners
 * (positions are copied only when they change) and about 12 bytes a
 * corner of work (doc/benchmarks.md: The repair). */
int  repair_mesh(Mesh *m, const RepairOpts *opt, RepairReport *rep, char *err, size_t errlen);
/* Frees the holes listed and the checks kept. */
void repair_report_free(RepairReport *rep);

/* ==== The figures as data ====
 *
 * Every count of RepairReport is one row of repair_rows (repairrows.c), in
 * the order a report says them: its member, its step (a REPAIR_* bit;
 * 0: what is left), its JSON name and its words after the number. A
 * report (text or JSON) reads the rows. */

typedef struct {
    const char *field;          /* the RepairReport member */
    size_t      offset, size;   /* offsetof and sizeof (4: uint32_t, 8: uint64_t) */
    unsigned    step;           /* REPAIR_* it belongs to; 0: left after the repair */
    const char *json;           /* the JSON member */
    const char *one, *many;     /* "vertex welded", "vertices welded" */
    int         problem;        /* left: a problem the check reports */
} RepairRow;

extern const RepairRow repair_rows[];
extern const int       repair_nrows;

/* Row r's figure in rep. */
uint64_t repair_value(const RepairRow *r, const RepairReport *rep);
/* "3 vertices welded" ("" when the figure is 0). */
void repair_say(const RepairRow *r, const RepairReport *rep, char *buf, size_t n);
/* Why a loop stayed open, in words ("more edges than the limit on holes"). */
const char *repair_open_why(RepairOpenWhy why);

#endif
