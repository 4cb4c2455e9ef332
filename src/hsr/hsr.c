/* hsr.c: the algorithm registry, frame buffers, and the runner that
 * splits a frame into bands of rows, one per thread. The exact rules are
 * written in hsr.h, raster.h and screen.h. */

#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "invariant.h"
#include "clock.h"
#include "hsr.h"
#include "pool.h"

extern const HsrAlgo hsr_zbuffer, hsr_scanline, hsr_span, hsr_hzb, hsr_hzb_octree;

const HsrAlgo *const hsr_algos[] = {
    &hsr_zbuffer, &hsr_scanline, &hsr_span, &hsr_hzb, &hsr_hzb_octree,
};
const int hsr_nalgos = (int)(sizeof hsr_algos / sizeof hsr_algos[0]);

const HsrAlgo *hsr_find(const char *name)
{
    for (int i = 0; i < hsr_nalgos; i++)
        if (strcmp(hsr_algos[i]->name, name) == 0)
            return hsr_algos[i];
    return NULL;
}

/* ==== frame buffers ==== */

int fbuf_resize(FrameBufs *fb, int w, int h)
{
    size_t n = (size_t)w * h;
    if (n > fb->cap) {
        int32_t *ids = realloc(fb->ids, n * sizeof *ids);
        if (!ids)
            return -1;
        fb->ids = ids;
        float *d = realloc(fb->depth, n * sizeof *d);
        if (!d)
            return -1;
        fb->depth = d;
        fb->cap = n;
    }
    fb->w = w;
    fb->h = h;
    return 0;
}

void fbuf_free(FrameBufs *fb)
{
    free(fb->ids);
    free(fb->depth);
    memset(fb, 0, sizeof *fb);
}

/* ==== the runner: one band per thread on a persistent pool ==== */

/* Band t on worker `worker`, with that worker's state. */
static void run_band(void *arg, int t, int worker)
{
    HsrRunner *r = arg;
    memset(&r->st[t], 0, sizeof r->st[t]);
    if (r->band[t] < r->band[t + 1])
        r->algo->render(r->state[worker], r->in, r->fb, r->band[t], r->band[t + 1], &r->st[t]);
}

int hsr_runner_init(HsrRunner *r, const HsrAlgo *algo, int nthreads)
{
    memset(r, 0, sizeof *r);
    if (nthreads < 1)
        nthreads = 1;
    if (nthreads > 64)
        nthreads = 64;
    r->algo = algo;
    r->nthreads = nthreads;
    for (int t = 0; t < nthreads; t++) {
        r->state[t] = algo->create ? algo->create() : NULL;
        if (algo->create && !r->state[t]) {
            hsr_runner_free(r);
            return -1;
        }
    }
    if (algo->create_shared) {
        r->shared = algo->create_shared(nthreads);
        if (!r->shared) {
            hsr_runner_free(r);
            return -1;
        }
        for (int t = 0; t < nthreads && algo->share; t++)
            algo->share(r->state[t], r->shared);
    }
    if (nthreads > 1) {
        r->pool = pool_create(nthreads - 1);
        if (!r->pool || pool_helpers(r->pool) < nthreads - 1) {
            hsr_runner_free(r);
            return -1;
        }
    }
    return 0;
}

void hsr_runner_free(HsrRunner *r)
{
    pool_free(r->pool);
    free(r->hist);
    if (r->shared && r->algo->destroy_shared)
        r->algo->destroy_shared(r->shared);
    for (int t = 0; t < r->nthreads; t++)
        if (r->state[t] && r->algo->destroy)
            r->algo->destroy(r->state[t]);
    memset(r, 0, sizeof *r);
}

static void stats_add(HsrStats *a, const HsrStats *b)
{
    a->polys_in += b->polys_in;
    a->polys_culled += b->polys_culled;
    a->nodes_visited += b->nodes_visited;
    a->nodes_culled += b->nodes_culled;
    a->pixels_written += b->pixels_written;
    a->building |= b->building;
    if (b->build_ms > a->build_ms)   /* bands build in parallel: the slowest counts */
        a->build_ms = b->build_ms;
}

/* Polygons split_bands reads at most (about). */
#define BAND_SAMPLES 65536

/* Row boundaries that give each band about the same number of polygon
 * rows plus pixel rows, so that a model in one part of the image still
 * splits evenly. */
static void split_bands(HsrRunner *pool, const ScreenPolys *sp, int h, int n, int *band)
{
    band[0] = 0;
    band[n] = h;
    if (n == 1)
        return;
    /* weight per row: polygons starting there (their setup dominates) + 1 */
    if (h + 1 > pool->hist_cap) {
        uint32_t *q = realloc(pool->hist, (size_t)(h + 1) * sizeof *q);
        if (!q) {
            for (int t = 1; t < n; t++)
                band[t] = h * t / n;
            return;
        }
        pool->hist = q;
        pool->hist_cap = h + 1;
    }
    uint32_t *hist = pool->hist;
    memset(hist, 0, (size_t)h * sizeof *hist);
    uint64_t total = 0;
    /* a big frame's polygons sampled, one in `step` (its weight `step`
     * times): reading every one was a serial millisecond before the
     * bands start (the dragon at 1920x1080, 870k polygons); the bands
     * only share the work by it, every pixel is the same whatever the
     * split */
    uint32_t step = sp->npolys / BAND_SAMPLES + 1;
    for (uint32_t i = 0; i < sp->npolys; i += step) {
        const ScreenPoly *p = &sp->polys[i];
        uint32_t rows = (uint32_t)(p->y1 - p->y0);
        /* spread the polygon's weight over its rows, coarsely */
        hist[(p->y0 + p->y1) / 2] += (4 + rows) * step;
        total += (4 + rows) * step;
    }
    for (int j = 0; j < h; j++)
        hist[j] += (uint32_t)(sp->w / 8 + 1);
    total += (uint64_t)h * (sp->w / 8 + 1);
    uint64_t acc = 0;
    int t = 1;
    for (int j = 0; j < h && t < n; j++) {
        acc += hist[j];
        while (t < n && acc * n >= total * t)
            band[t++] = j + 1;
    }
    while (t < n)
        band[t++] = h;
}

/* Rows 0 = band[0] <= band[1] <= ... <= band[n] = h: every row in
 * exactly one band. Each band writes every pixel of its rows and only
 * those (HsrAlgo.render), so this is what makes the bands together
 * write the whole image once, with no two threads on one row. */
static ZV_CHECK_FN int bands_tile(const int *band, int n, int h)
{
    if (band[0] != 0 || band[n] != h)
        return 0;
    for (int t = 0; t < n; t++)
        if (band[t] > band[t + 1])
            return 0;
    return 1;
}

/* What the front end promises every algorithm of each polygon: 3
 * corners or more, in order and in the vertex array (polys[npolys].first
 * the sentinel), and a sample box [x0, x1) x [y0, y1) inside the image
 * and not empty (polygons that cover no sample were dropped). The
 * algorithms index rows and columns by these boxes unclamped (table
 * buckets, band tests, pyramid tiles), so a box outside the image would
 * write outside the buffers, and an empty one would mean a polygon let
 * through that covers nothing. */
static ZV_CHECK_FN int polys_in_image(const ScreenPolys *sp)
{
    if (sp->npolys && sp->polys[sp->npolys].first > sp->nverts)
        return 0;
    for (uint32_t i = 0; i < sp->npolys; i++) {
        const ScreenPoly *p = &sp->polys[i];
        if (p[1].first < p->first + 3 || p->x0 < 0 || p->x0 >= p->x1 || p->x1 > sp->w || p->y0 < 0 ||
            p->y0 >= p->y1 || p->y1 > sp->h)
            return 0;
    }
    return 1;
}

int hsr_run(HsrRunner *r, const HsrInput *in, FrameBufs *fb, HsrStats *stats)
{
    ZV_ASSERT(polys_in_image(in->sp));
    double t0 = now_ms();
    memset(stats, 0, sizeof *stats);
    if (fbuf_resize(fb, in->sp->w, in->sp->h))
        return -1;
    double tb = 0;
    if (r->algo->frame_begin) {
        double t1 = now_ms();
        r->algo->frame_begin(r->shared, in);
        tb = now_ms() - t1;     /* structures built before the bands (one thread) */
    }
    int h = in->sp->h;
    if (r->nthreads == 1 || !r->pool) {
        r->algo->render(r->state[0], in, fb, 0, h, stats);
        stats->build_ms += tb;
        stats->scan_ms = now_ms() - t0 - stats->build_ms;
        return 0;
    }
    r->in = in;
    r->fb = fb;
    split_bands(r, in->sp, h, r->nthreads, r->band);
    ZV_ASSERT(bands_tile(r->band, r->nthreads, h));
    pool_run(r->pool, r->nthreads, run_band, r);
    for (int t = 0; t < r->nthreads; t++)
        stats_add(stats, &r->st[t]);
    stats->build_ms += tb;
    stats->scan_ms = now_ms() - t0 - stats->build_ms;
    return 0;
}
