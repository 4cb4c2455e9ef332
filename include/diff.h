#ifndef ZV_DIFF_H
#define ZV_DIFF_H
/* diff: how two models differ (--diff A B). The distance from each
 * model's surface to the other's, sampled (Metro's way: P. Cignoni, C.
 * Rocchini and R. Scopigno, "Metro: Measuring Error on Simplified
 * Surfaces", Computer Graphics Forum 17(2), 1998), each distance a
 * nearest-point query through a bounding-volume hierarchy (bvh.h); the
 * symmetric Hausdorff distance, the mean distance each way, the changed
 * regions; and, for the picture, the faces coloured by it in the
 * scene the two models make together. Knows nothing of terminals: the
 * reports are oneshot/'s, the keys the viewer's.
 *
 * What is exact and what is sampled (diffsample.c): the distance of
 * every sample is exact but for double rounding (the nearest point of
 * every triangle of the other model, passed over only where a box
 * proves it farther). The samples of a surface are every vertex a face
 * uses, and about DIFF_SAMPLES more spread over its faces by area:
 * each triangle of a face (a fan from its first corner, as the picture
 * draws it) is cut into r x r similar small ones, r the whole number
 * nearest to the square root of its area times DIFF_SAMPLES / the
 * surface's area; each small triangle's centre is a sample, and for r >
 * 1 the r - 1 points that cut each side of the triangle. A triangle of
 * less than a quarter of its share (r = 0: most of a scan's) is sampled
 * at its corners alone. The maximum over the samples is a lower bound of
 * the one-sided Hausdorff distance; since a point's distance to a
 * surface changes no faster than the point moves, no point of a small
 * triangle is farther than its centre's distance plus the centre's
 * distance to its corners, nor a point of a triangle of r = 0 farther
 * than its farthest corner's distance plus its circumradius (or its
 * longest side), which gives the upper bound reported beside it. The
 * mean weights each small triangle's centre by its area (the midpoint
 * rule), and a triangle of r = 0 by its area times its corners' mean
 * (the linear interpolant's). */

#include <stdint.h>

#include "app.h"
#include "bvh.h"
#include "mesh.h"
#include "meshcheck.h"

#define DIFF_SAMPLES 65536          /* face samples a side beside the vertices, about (see above) */
#define DIFF_TOL_FRACTION 1e-3      /* the default tolerance: this part of the bounding box's diagonal */
#define DIFF_REGIONS_LISTED 1000    /* regions the reports list (the count is of all) */

/* What a face of one side is for the picture. */
enum {
    DIFF_SAME = 0,                  /* within the tolerance */
    DIFF_OVER = 1,                  /* farther: most of its area over the tolerance */
    DIFF_STRADDLE = 2,              /* its corners on both sides of the tolerance: coloured per pixel */
};

/* One side: a model's surface measured against the other's. */
typedef struct {
    uint32_t  nverts, nfaces;
    float    *vert_dist;            /* per vertex: its distance to the other model; -1 for a vertex no face uses */
    uint32_t *vert_link;            /* per vertex: the other's face nearest to it */
    float    *face_dist;            /* per face: the farthest of its samples (its corners too) */
    uint32_t *face_link;            /* per face: the other's face nearest to that sample */
    float    *face_over;            /* per face: its area over the tolerance */
    uint8_t  *face_class;           /* per face: DIFF_SAME, DIFF_OVER, DIFF_STRADDLE */
    double    max;                  /* the farthest sample's distance: the one-sided Hausdorff distance, sampled */
    double    max_at[3];            /* ... where it is */
    double    bound;                /* no point of the surface is farther than this (see above) */
    double    mean;                 /* area-weighted mean distance; 0 without area */
    double    area;                 /* the surface's area (its triangles') */
    double    area_over;            /* ... of it over the tolerance */
    uint64_t  vertex_samples, edge_samples, face_samples;
    uint32_t  triangles;
} DiffSide;

/* A changed region: faces over the tolerance joined by a shared corner
 * (vertices at one position are one), on either model, and across the
 * two where one's farthest sample is nearest to the other's. */
typedef struct {
    float    lo[3], hi[3];          /* the box of its faces */
    double   added, removed;        /* area over the tolerance: of B (added, moved out), of A (removed) */
    double   max;                   /* its farthest sample */
    uint32_t faces_a, faces_b;
} DiffRegion;

typedef struct {
    int        threads;             /* <= 0: one per core */
    double     tolerance;           /* >= 0: given; < 0: DIFF_TOL_FRACTION of the diagonal */
    const int *cancel;              /* NULL, or set (atomically) to stop: diff_compute fails "cancelled" */
    uint32_t   samples;             /* face samples a side about; 0: DIFF_SAMPLES (the fuzzer asks fewer) */
    int        checks;              /* check each model too (Diff.check) */
    /* NULL, or the caller's task run beside the diff's on several
     * threads (one of the queue's, once A is measured and B's hierarchy
     * freed), never on one: it may read the meshes, not write them
     * (--diff's picture) */
    void     (*beside)(void *arg);
    void      *beside_arg;
} DiffOpts;

typedef struct {
    DiffSide    a, b;               /* a: A's surface to B; b: B's to A */
    double      tolerance;
    int         tol_given;
    double      diag;               /* the diagonal of the box of both models' faces */
    double      zero;               /* distances under this are rounding, and 0 */
    double      hausdorff;          /* max(a.max, b.max) */
    DiffRegion *regions;            /* sorted by max, the farthest first */
    uint32_t    nregions;
    double      ms;                 /* wall time of diff_compute */
    uint32_t    samples;            /* face samples a side about (DiffOpts.samples) */
    CheckCounts check[2];           /* DiffOpts.checks: --check's figures of each, the crossing test left out
                                       (it is the check's costly part; zview --check runs it) */
} Diff;

/* Measure a against b and b against a (and check each, when asked).
 * On one thread the work runs in turn, one hierarchy at a time (B's
 * while A is measured, then A's): the memory beyond the models is one
 * hierarchy and the figures. On more, everything is one queue of tasks
 * (diff.c): the hierarchies and the vertices' match, the checks beside
 * them and beside the samples, the samples in chunks; the figures are
 * the same bit for bit whatever the threads. The meshes are read, not changed. 0,
 * or -1 with the reason in err (out of memory, cancelled, more than
 * 2^32 - 1 triangles); a model without faces has nothing to measure:
 * the caller refuses it first. */
int  diff_compute(Diff *d, const Mesh *a, const Mesh *b, const DiffOpts *o, char *err, size_t errlen);
void diff_free(Diff *d);
/* The changed regions of d (diffregion.c), from its sides and the two
 * meshes (their positions, for the boxes and to weld corners). */
int  diff_regions(Diff *d, const Mesh *a, const Mesh *b, char *err, size_t errlen);
/* Do the two differ beyond the tolerance? */
static inline int diff_differ(const Diff *d)
{
    return d->hausdorff > d->tolerance;
}

/* ==== The vertices of both (diffmatch.c) ==== */

/* One model's vertices: those its faces use, in the order of a Morton
 * curve through the box of both models, and each one's match: a face of
 * the other model with a corner at the very same position (the vertex
 * is on that surface). */
typedef struct {
    uint32_t *order;                /* the used vertices in curve order (nused of them) */
    uint32_t *code;                 /* ... their codes */
    uint32_t  nused;
    uint32_t *first;                /* per vertex: the first face that uses it, UINT32_MAX none */
    uint32_t *on;                   /* per vertex: the other's face with a corner there, UINT32_MAX none */
} DiffVerts;
/* Both at once (box: low x y z, high x y z of both). 0, or -1 out of
 * memory; diff_verts_free either way. */
int  diff_match(DiffVerts *va, DiffVerts *vb, const Mesh *a, const Mesh *b, const float box[6]);
void diff_verts_free(DiffVerts *v);

/* ==== One side's distances (diffsample.c) ==== */

/* The samples of mesh m (its vertices as verts has them) measured
 * against the other model, through its hierarchy (whose triangles carry
 * their face as id), into side s, with the tolerance and the zero of d.
 * 0, or -1 out of memory or cancelled. */
int  diff_side(DiffSide *s, const Mesh *m, const DiffVerts *verts, const Bvh *bvh, const Diff *d, int threads,
               const int *cancel, char *err, size_t errlen);

/* The same in pieces, for a scheduler that runs other work beside them
 * (diff.c): diff_side_begin (the arrays, the area; no hierarchy needed
 * yet), then with bvh set, every chunk of the vertices
 * (diff_side_verts, 0 .. nvchunks - 1, in any order, on any threads),
 * then, once all of those are done, every chunk of the faces; then
 * diff_side_end (the sums, in chunk order: the same figures however the
 * chunks ran), or diff_side_abort. */
typedef struct {
    const Mesh      *m;
    const Bvh       *bvh;           /* the other model's hierarchy: set before the chunks run */
    const DiffVerts *verts;         /* m's vertices in curve order, and those on the other */
    const Diff      *d;
    DiffSide        *s;
    double           unit;          /* the area a face sample stands for, at most */
    const int       *cancel;
    struct DiffAcc  *acc;           /* one a chunk: vertex chunks, then face chunks */
    uint32_t         nvchunks, nfchunks;
} DiffSideRun;
void diff_side_chunks(const Mesh *m, uint32_t *nvchunks, uint32_t *nfchunks);   /* how many of each, for m */
int  diff_side_begin(DiffSideRun *w, DiffSide *s, const Mesh *m, const DiffVerts *verts, const Diff *d,
                     const int *cancel, char *err, size_t errlen);
void diff_side_verts(DiffSideRun *w, uint32_t chunk);
void diff_side_faces(DiffSideRun *w, uint32_t chunk);
int  diff_side_end(DiffSideRun *w, char *err, size_t errlen);     /* 0, or -1 "cancelled" (s freed) */
void diff_side_abort(DiffSideRun *w);                              /* s freed */
void diff_side_free(DiffSide *s);
/* The fan triangles of m's faces, 3 corners each, and the face of each
 * (malloc'd; *n of them). 0, or -1 with the reason. A mesh of triangles
 * alone needs none: its corner list is its triangles. */
int  diff_fan(const Mesh *m, uint32_t **tri_out, uint32_t **face_out, uint32_t *n, char *err, size_t errlen);

/* ==== Two files: loaded, checked, measured, drawn (diffload.c) ==== */

/* What the picture shows (--show, the viewer's V key): both models
 * overlaid, A alone, B alone (each coloured by its distance to the
 * other: grey within the tolerance, A's far faces red, B's green), or
 * both as a heat map of the distance (a perceptual ramp, 0 to the
 * largest distance). */
typedef enum { DIFF_SHOW_BOTH, DIFF_SHOW_A, DIFF_SHOW_B, DIFF_SHOW_HEAT, DIFF_SHOW_COUNT } DiffShow;
extern const char *const diff_show_names[DIFF_SHOW_COUNT];  /* --show's words: both a b heat */
int diff_show_from_name(const char *name);                  /* -1 if none */

typedef struct DiffSet {
    const char *path[2];            /* as given */
    char        format[2][32];      /* what read each */
    char        unit[2][8];         /* the unit each format states, "" none */
    uint32_t    nverts[2], nfaces[2];   /* as loaded */
    Diff        d;
    /* the picture: both models in one scene, each in its own
     * coordinates (no layout), A's objects first, standing as A's format
     * (or --up) says; its faces coloured by the distance (diff_show) */
    Scene       scene;
    int         has_scene;
    int         nobjs_a;            /* the scene's objects of A */
    int         show;               /* DiffShow drawn */
    uint32_t   *obj_counts;         /* per object: its polygons, points, segments (hidden ones are 0) */
    uint32_t    gen;                /* the scene's generation after the last diff_show: another
                                       means the scene was edited and the colours are off */
} DiffSet;

/* Load o's two files (sandboxed, through app_load_opts), check each,
 * measure them and, when scene is asked for, build the picture's scene,
 * coloured as o->show says (both by default). 0; 1 when a file cannot
 * be read or has no faces (the message in err: exit status 1); -1 for
 * another failure (out of memory). */
int  diff_load(DiffSet *ds, const Options *o, int scene, char *err, size_t errlen);
void diff_set_free(DiffSet *ds);
/* Colour the scene's faces for show (diffcolour.c): written in the
 * scene's own face colours and surfaces, the meshes' vertex colours
 * (for faces coloured per pixel), and the hidden model's objects left
 * without polygons. p, when the scene is in a pipeline's hands: told
 * first (pipeline_scene_changing). 0, or -1 out of memory. */
int  diff_show(DiffSet *ds, Pipeline *p, int show);
/* The headline in a few words for the report's last line and the
 * status bar: "max 1.2 mm · 3 regions changed" (sep between the parts), "the same (max 0)", the
 * check's change first when one side is watertight and the other not
 * ("no longer watertight (2 holes) · ..."). brief: the shortest form
 * ("3 changed", "same"). */
void diff_headline(const DiffSet *ds, int brief, const char *sep, char *buf, size_t len);
/* The status bar's: the headline, and the heat map's scale after it
 * when it shows ("heat: blue 0 to yellow 1.2 mm"). */
void diff_status(const DiffSet *ds, int brief, const char *sep, char *buf, size_t len);
/* The figures as lines of the viewer's info panel (report.c's
 * labels): the distance each way, the regions, each model's verdict. */
int  diff_report_lines(const DiffSet *ds, ReportLine *lines, int max);
/* A distance in the shortest words ("1.2 mm", "0.0035"). */
void diff_length(const DiffSet *ds, double v, char *buf, size_t len);
/* The heat map's colour of t in [0, 1] (dark blue to light yellow,
 * lightness rising evenly), sRGB bytes. */
void diff_ramp(double t, uint8_t rgb_out[3]);

#endif
