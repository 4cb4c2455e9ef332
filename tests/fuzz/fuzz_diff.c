/* fuzz_diff.c: the differential harness. The input decodes to a scene
 * (faces, points and lines, maybe a large generated mesh), a view, a
 * viewport, a thread count, a polygon order (--order) and a SIMD level
 * (scenecode.h). Two things must hold, byte for byte:
 *  - the front end: the screen polygons (vertices, polygons with their
 *    planes, the map from the scene's) are the same at every SIMD level
 *    this CPU runs and on one thread or more; and in the file's order,
 *    the same as the reference's;
 *  - the hidden surfaces: every algorithm, given the polygons in the
 *    input's order, at the input's SIMD level (or at each), gives the
 *    face-id and depth buffers of the z-buffer on one thread at the
 *    scalar level in the file's order;
 *  - with section planes (the input's last part), all of this holds of
 *    the cut polygons and the caps too;
 *  - the reductions: with the points and lines reduced (one square per
 *    point box, small and surplus quads given as their samples), the
 *    z-buffer's buffers are those of every point and quad drawn whole.
 * A difference aborts, so libFuzzer keeps the input. FUZZ_DIFF_SAY=1
 * build/replay-diff FILE says what FILE decodes to. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "scenecode.h"
#include "simd.h"
#include "testlib.h"

/* One projection and what it keeps across calls. */
typedef struct {
    ScreenPolys    sp;
    ReorderScratch rs;
    PrimWork      *prims;
} Front;

/* The buffers live as long as the process: libFuzzer calls this
 * thousands of times a second, and fresh large buffers each time (mapped,
 * faulted in, unmapped) cost more than the rendering. Reachable at exit,
 * so no leak. ref: file order, scalar, one thread; at[level]: the
 * input's order and threads at that level. */
static struct {
    Front      ref, at[SIMD_LEVELS], whole;
    FrameBufs  ref_fb, fb;
    SectionCut cut;
} bufs;

/* The front end as pipeline_render runs it: the wireframe's lines (once:
 * the caps' ids come after every line's), project, reorder, then the
 * points and lines. */
static int front(Front *f, Scene *s, const Viewport *vp, const PrimStyle *style, int level, int threads,
                 const ScRun *run)
{
    f->sp.simd = level;
    f->sp.threads = threads;
    char err[160];
    if ((style->wire && !s->wire_built && scene_wire_build(s, err, sizeof err)) || screen_project(&f->sp, s, vp) ||
        (run->order != ORDER_FILE && screen_reorder(&f->sp, (PolyOrder)run->order, run->seed, &f->rs)))
        return -1;
    PrimStyle st = *style;
    st.point_size = st.point_size > 0 ? st.point_size : 1;
    st.line_width = st.line_width > 0 ? st.line_width : 1;
    return screen_prims(&f->sp, s, &st, &f->prims);
}

/* NULL when a and b hold the same polygons, byte for byte; else what
 * differs first. */
static const char *polys_differ(const ScreenPolys *a, const ScreenPolys *b)
{
    if (a->w != b->w || a->h != b->h || a->nverts != b->nverts || a->npolys != b->npolys ||
        a->prim_first != b->prim_first || a->nmap != b->nmap || a->face_sorted != b->face_sorted)
        return "the counts";
    if (a->nverts && memcmp(a->verts, b->verts, a->nverts * sizeof *a->verts))
        return "the vertices";
    /* the polygons (ScreenPoly has no padding), and the sentinel's first
     * (its only field set) */
    if ((a->npolys && memcmp(a->polys, b->polys, a->npolys * sizeof *a->polys)) ||
        a->polys[a->npolys].first != b->polys[b->npolys].first)
        return "the polygons or their planes";
    if (a->nmap && memcmp(a->map, b->map, a->nmap * sizeof *a->map))
        return "the map from scene polygons";
    if (a->culled_back != b->culled_back || a->culled_empty != b->culled_empty ||
        a->points_drawn != b->points_drawn || a->edges_drawn != b->edges_drawn ||
        a->edges_sampled != b->edges_sampled || a->edge_squares != b->edge_squares)
        return "the statistics";
    return NULL;
}

static void fail(const char *what, const Viewport *vp, int threads, const ScRun *run)
{
    fprintf(stderr, "fuzz_diff: %dx%d aspect %g cull %d, %d thread%s, order %s: %s\n", vp->w, vp->h,
            (double)vp->pixel_aspect, vp->cull, threads, threads == 1 ? "" : "s", order_names[run->order],
            what);
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    Scene s;
    Viewport vp;
    int threads;
    PrimStyle style;
    ScRun run;
    if (sc_decode_run(data, size, &s, &vp, &threads, &style, &run))
        return 0;
    char msg[512];
    /* the wireframe's lines, then the section planes: one cut of this
     * scene for every front end (made again: a new scene may sit where
     * the last one did), as pipeline_render orders them (the caps' ids
     * come after every line's) */
    bufs.cut.key = NULL;
    char werr[160];
    if ((style.wire && scene_wire_build(&s, werr, sizeof werr)) ||
        section_cut_update(&bufs.cut, &s, run.plane, run.nplanes, msg, sizeof msg))
        goto out;
    for (int level = 0; level < SIMD_LEVELS; level++)
        bufs.at[level].sp.cut = &bufs.cut;
    bufs.ref.sp.cut = bufs.whole.sp.cut = &bufs.cut;
    ScRun file = run;
    file.order = ORDER_FILE;
    int best = simd_best();
    if (front(&bufs.ref, &s, &vp, &style, SIMD_SCALAR, 1, &file))
        goto out;
    if (getenv("FUZZ_DIFF_SAY"))   /* what a seed decodes to, for whoever writes one */
        fprintf(stderr, "%dx%d, %d thread(s), order %s, hidden surfaces at %s, %d section plane(s): %u objects, %u polygons on screen\n",
                vp.w, vp.h, threads, order_names[run.order], run.hsr_simd ? simd_name(run.hsr_simd) : "every level", run.nplanes,
                (unsigned)s.nobjs, bufs.ref.sp.npolys);
    for (int k = 0; getenv("FUZZ_DIFF_SAY") && k < s.nobjs; k++)
        fprintf(stderr, "  object %d: %u polygons%s\n", k, (unsigned)s.objs[k].poly_count, k ? "" : style.wire ? ", wireframe" : "");
    for (int level = SIMD_SCALAR; level <= best; level++) {
        if (front(&bufs.at[level], &s, &vp, &style, level, threads, &run))
            goto out;
        const ScreenPolys *want = run.order == ORDER_FILE ? &bufs.ref.sp : &bufs.at[SIMD_SCALAR].sp;
        const char *what = polys_differ(want, &bufs.at[level].sp);
        if (what) {
            snprintf(msg, sizeof msg, "the front end at %s differs from %s in %s", simd_name(level),
                     want == &bufs.ref.sp ? "one thread at scalar" : "scalar", what);
            fail(msg, &vp, threads, &run);
        }
    }
    HsrInput in = { .sp = &bufs.ref.sp, .scene = &s, .vp = &vp, .simd = SIMD_SCALAR };
    if (tl_render_poisoned(&hsr_zbuffer, 1, &in, &bufs.ref_fb))
        goto out;
    if (!style.all_prims && s.nprims) {
        /* every point and quad whole: the same buffers */
        PrimStyle whole = style;
        whole.all_prims = 1;
        in.sp = &bufs.whole.sp;
        if (front(&bufs.whole, &s, &vp, &whole, SIMD_SCALAR, 1, &file) ||
            tl_render_poisoned(&hsr_zbuffer, 1, &in, &bufs.fb))
            goto out;
        int fx, fy;
        long n = tl_diff(&bufs.fb, &bufs.ref_fb, &fx, &fy);
        if (n) {
            size_t i = (size_t)fy * vp.w + fx;
            snprintf(msg, sizeof msg,
                     "the reduced points and lines (%u quads, %u as samples) differ from every one drawn whole "
                     "in %ld pixels; first (%d,%d): id %d depth %.9g, whole id %d depth %.9g",
                     bufs.ref.sp.edges_drawn, bufs.ref.sp.edges_sampled, n, fx, fy, bufs.ref_fb.ids[i],
                     (double)bufs.ref_fb.depth[i], bufs.fb.ids[i], (double)bufs.fb.depth[i]);
            fail(msg, &vp, 1, &file);
        }
    }
    in.sp = &bufs.at[SIMD_SCALAR].sp;
    int lo = run.hsr_simd ? (run.hsr_simd < best ? run.hsr_simd : best) : SIMD_SCALAR;
    int hi = run.hsr_simd ? lo : best;
    for (int k = 0; k < hsr_nalgos; k++)
        for (int level = lo; level <= hi; level++) {
            if (hsr_algos[k] == &hsr_zbuffer && level == SIMD_SCALAR && threads == 1 && run.order == ORDER_FILE)
                continue;   /* the reference itself */
            in.simd = level;
            if (tl_render_poisoned(hsr_algos[k], threads, &in, &bufs.fb))
                goto out;
            int fx, fy;
            long n = tl_diff(&bufs.ref_fb, &bufs.fb, &fx, &fy);
            if (n) {
                size_t i = (size_t)fy * vp.w + fx;
                snprintf(msg, sizeof msg,
                         "%u polygons: %s at %s differs from zbuffer in %ld pixels; first (%d,%d): "
                         "id %d depth %.9g, zbuffer id %d depth %.9g",
                         in.sp->npolys, hsr_algos[k]->name, simd_name(level), n, fx, fy, bufs.fb.ids[i],
                         (double)bufs.fb.depth[i], bufs.ref_fb.ids[i], (double)bufs.ref_fb.depth[i]);
                fail(msg, &vp, threads, &run);
            }
        }
out:
    scene_free(&s);
    return 0;
}
