#ifndef ZV_HSR_H
#define ZV_HSR_H
/* hsr: hidden-surface removal. Screen-space polygons in, face-id + depth
 * buffers out. Knows nothing of glyphs, colours or terminals.
 *
 * THE EXACT RULES (every algorithm obeys them; tests compare the
 * algorithms pixel by pixel against the plain z-buffer):
 *  1. The image is W x H pixels; pixel (i, j) is sampled at its centre
 *     (i + 0.5, j + 0.5), x to the right, y down.
 *  2. One front end (screen.h) makes the polygons: vertices snapped to
 *     24.8 fixed point, one plane per polygon from the snapped vertices.
 *     Depth is affine in screen space (NDC z under perspective).
 *  3. Coverage is even-odd with half-open intervals (raster.h): an edge
 *     counts for rows with y_top <= yc < y_bottom; between an entering and
 *     a leaving crossing the samples with x_enter <= xc < x_leave are in.
 *     Computed exactly on the fixed-point values.
 *  4. Depth at a sample is the polygon's plane there, evaluated by
 *     plane_row()/plane_at() (screen.h). Smaller depth is nearer; equal
 *     depths go to the lower face id: samples compare (depth, face id)
 *     pairs, so the result does not depend on drawing order.
 *  5. The result is a face-id buffer (int32, -1 = background, ids are
 *     face indices in scene load order) and a depth buffer (+inf where
 *     background).
 */

#include <stddef.h>
#include <stdint.h>
#include "screen.h"

typedef struct {
    int      w, h;
    int32_t *ids;           /* w * h, row major from the top */
    float   *depth;         /* w * h */
    size_t   cap;           /* pixels allocated */
} FrameBufs;

typedef struct {
    uint64_t polys_in;            /* polygons given to the algorithm */
    uint64_t polys_culled;        /* skipped whole by a hierarchical test */
    uint64_t nodes_visited;       /* octree nodes walked */
    uint64_t nodes_culled;        /* octree nodes hidden by the pyramid */
    uint64_t pixels_written;      /* sample writes (overdraw = this / covered) */
    double   build_ms;            /* tables, pyramid, octree */
    int      building;            /* structures still being built in the background:
                                     this frame was drawn without them (same picture) */
    double   scan_ms;             /* the scan itself */
} HsrStats;

/* What an algorithm sees of a frame. */
typedef struct {
    const ScreenPolys *sp;
    const struct Scene *scene;    /* for object-space structures (octree) */
    const Viewport *vp;
    int simd;                     /* a SimdLevel (simd.h): SIMD_AUTO (0) = the level in use,
                                     else at most that one (the same bytes at every level) */
} HsrInput;

/* One hidden-surface algorithm. An algorithm renders bands of rows
 * [y0, y1) independently, each with its own state, so bands can run in
 * parallel. It writes every pixel of its band (background included). */
typedef struct HsrAlgo {
    const char *name;             /* --algo value */
    const char *summary;          /* one line for --help */
    void *(*create)(void);        /* per-thread state (NULL is allowed) */
    void  (*destroy)(void *st);
    void  (*render)(void *st, const HsrInput *in, FrameBufs *fb,
                    int y0, int y1, HsrStats *stats);
    /* Optional: state shared by the bands of one runner (made with it, for
     * its thread count, and handed to each band's state by share()), and
     * a step before each frame's bands start, on the caller's thread. A
     * state used without a runner is never given one. A runner's scene
     * must outlive the frames and structures it renders or builds from it
     * (hsr_runner_free first). */
    void *(*create_shared)(int nthreads);
    void  (*destroy_shared)(void *sh);
    void  (*share)(void *st, void *sh);
    void  (*frame_begin)(void *sh, const HsrInput *in);
    int   uses_map;               /* reads ScreenPolys.map (else it need not be kept) */
} HsrAlgo;

/* Registry, in the order the viewer cycles through them. */
extern const HsrAlgo *const hsr_algos[];
extern const int hsr_nalgos;
const HsrAlgo *hsr_find(const char *name);

/* Size the buffers (no allocation when they already fit). */
int  fbuf_resize(FrameBufs *fb, int w, int h);
void fbuf_free(FrameBufs *fb);

/* A renderer: one algorithm with per-thread states. */
typedef struct {
    const HsrAlgo *algo;
    int            nthreads;
    void          *state[64];
    struct Pool   *pool;          /* helper threads when nthreads > 1 (pool.h) */
    void          *shared;        /* algo->create_shared(), or NULL */
    /* the frame being rendered, for the bands */
    const HsrInput *in;
    FrameBufs     *fb;
    int            band[65];      /* row boundaries */
    HsrStats       st[64];
    uint32_t      *hist;          /* split_bands' row weights */
    int            hist_cap;
} HsrRunner;

int  hsr_runner_init(HsrRunner *r, const HsrAlgo *algo, int nthreads);
void hsr_runner_free(HsrRunner *r);
/* Render a frame: bands of rows, one per thread; stats are summed. */
int  hsr_run(HsrRunner *r, const HsrInput *in, FrameBufs *fb, HsrStats *stats);

/* The sample comparison of rule 4: does (z, id) beat (zb, idb)? */
static inline int hsr_wins(float z, int32_t id, float zb, int32_t idb)
{
    return z < zb || (z == zb && (uint32_t)id < (uint32_t)idb);
}

#endif
