/* diff.c: how two models differ: each model's surface against the
 * other's (diffsample.c, include/diff.h), each model's check, then the
 * changed regions (diffregion.c). The hierarchy a model is measured
 * against is the other's, its triangles carrying their face. */

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "clock.h"
#include "diff.h"
#include "pool.h"

#include <pthread.h>

void diff_free(Diff *d)
{
    diff_side_free(&d->a);
    diff_side_free(&d->b);
    free(d->regions);
    memset(d, 0, sizeof *d);
}

/* The box of the vertices m's faces use into lo, hi (grown); -1 with
 * the reason for a vertex that is not a finite point. The corners mark
 * the vertices they use, and the box is of the vertices marked, each
 * once (a vertex has about six corners): min and max of the same floats,
 * in float, so the same box as corner by corner, but for the sign of a
 * zero, which neither the diagonal nor the curve's codes can see. A
 * vertex that is not finite is named as the corners meet it, the first
 * in corner order, so the message is the one a pass over the corners
 * gives. */
static int faces_box(const Mesh *m, double lo[3], double hi[3], char *err, size_t errlen)
{
    const float *pos = m->pos;
    const uint32_t *corner = m->corner;
    uint32_t n = m->face_start ? m->face_start[m->nfaces] : 0;
    uint8_t *used = calloc((size_t)m->nverts + 1, 1);
    if (!used) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (uint32_t c = 0; c < n; c++)
        used[corner[c]] = 1;
    float l[3] = { INFINITY, INFINITY, INFINITY }, h[3] = { -INFINITY, -INFINITY, -INFINITY };
    int finite = 1;
    for (uint32_t v = 0; v < m->nverts; v++) {
        if (!used[v])
            continue;
        const float *p = &pos[3 * (size_t)v];
        /* a NaN fails every comparison, an infinity the bound */
        finite &= fabsf(p[0]) <= FLT_MAX && fabsf(p[1]) <= FLT_MAX && fabsf(p[2]) <= FLT_MAX;
        for (int k = 0; k < 3; k++) {
            l[k] = p[k] < l[k] ? p[k] : l[k];
            h[k] = p[k] > h[k] ? p[k] : h[k];
        }
    }
    free(used);
    for (uint32_t c = 0; !finite && c < n; c++) {
        const float *p = &pos[3 * (size_t)corner[c]];
        if (!(fabsf(p[0]) <= FLT_MAX && fabsf(p[1]) <= FLT_MAX && fabsf(p[2]) <= FLT_MAX)) {
            snprintf(err, errlen, "%s: vertex %u is not a finite point", m->path ? m->path : "?", corner[c] + 1);
            return -1;
        }
    }
    for (int k = 0; k < 3; k++) {
        lo[k] = l[k] < lo[k] ? l[k] : lo[k];
        hi[k] = h[k] > hi[k] ? h[k] : hi[k];
    }
    return 0;
}

/* Are all of m's faces triangles? Then its corner list is its triangles. */
static int all_triangles(const Mesh *m)
{
    for (uint32_t f = 0; f <= m->nfaces; f++)
        if (m->face_start[f] != 3 * f)
            return 0;
    return 1;
}

/* The hierarchy of m's triangles, each carrying its face. */
static int build_of(Bvh *bvh, const Mesh *m, char *err, size_t errlen)
{
    uint32_t *tri = NULL, *face = NULL, n = m->nfaces;
    if (!all_triangles(m) && diff_fan(m, &tri, &face, &n, err, errlen))
        return -1;
    int rc = bvh_build(bvh, m->pos, m->nverts, tri ? tri : m->corner, face, n, err, errlen);
    free(tri);
    free(face);
    return rc;
}

static int check_of(CheckCounts *out, const Mesh *m, char *err, size_t errlen)
{
    MeshCheck mc;
    CheckOpts co = { .threads = 1, .intersections = 0 };
    if (meshcheck_run(&mc, m, &co, err, errlen))
        return -1;
    *out = mc.file;
    meshcheck_free(&mc);
    return 0;
}

/* The work of a diff, as tasks: each model's check, each hierarchy (B's,
 * against which A is measured, and A's), the vertices' match, the
 * sides' arrays, then the chunks of samples (diffsample.c): A's
 * vertices, A's faces, the caller's task (DiffOpts.beside, several
 * threads only), B's vertices, B's faces. On several threads they are
 * taken in that order from one queue (pool.h), each after what it
 * needs: the checks need nothing and run beside the rest, so the
 * threads stay busy until the last chunk. A task that needs another
 * waits for it, and what it waits for was taken before it (every need
 * comes earlier in the queue), so the wait ends. B's hierarchy is freed
 * once A's faces are done; the caller's task comes then, so what it
 * makes (the picture's scene) and that hierarchy are not held at once,
 * and B's chunks, after it, keep the other threads busy meanwhile. */
enum {
    T_BVH_B,        /* first: A's vertices need it */
    T_MATCH,
    T_SIDES,        /* both sides' arrays and areas */
    T_CHECK_A,
    T_CHECK_B,
    T_BVH_A,
    T_CHUNKS,       /* then the chunks: the groups below */
    G_VERTS_A = T_CHUNKS,
    G_FACES_A,
    G_BESIDE,       /* one task: the caller's */
    G_VERTS_B,
    G_FACES_B,
    NGROUPS
};

typedef struct {
    const Mesh *m[2];
    Diff       *d;
    const float *box;
    int         checks;
    const int  *cancel;
    void      (*beside)(void *arg);
    void       *beside_arg;
    Bvh         bvh[2];         /* [0]: B's, for A's samples; [1]: A's */
    DiffVerts   v[2];
    DiffSideRun side[2];
    int         rc[T_CHUNKS];
    char        err[T_CHUNKS][256];
    /* several threads: who is done */
    uint32_t    first[NGROUPS + 1]; /* the queue: group g's tasks are [first[g], first[g + 1]) */
    uint32_t    left[NGROUPS];      /* tasks of each group not yet done */
    pthread_mutex_t mu;
    pthread_cond_t  cv;
} Work;

static void prep_task(Work *w, int task)
{
    char *err = w->err[task];
    switch (task) {
    case T_CHECK_A:
    case T_CHECK_B:
        if (w->checks)
            w->rc[task] = check_of(&w->d->check[task == T_CHECK_B], w->m[task == T_CHECK_B], err, 256);
        break;
    case T_BVH_B:
    case T_BVH_A:
        w->rc[task] = build_of(&w->bvh[task == T_BVH_A], w->m[task == T_BVH_B], err, 256);
        break;
    case T_SIDES:
        for (int i = 0; i < 2 && !w->rc[task]; i++)
            w->rc[task] = diff_side_begin(&w->side[i], i ? &w->d->b : &w->d->a, w->m[i], &w->v[i], w->d,
                                          w->cancel, err, 256);
        w->side[0].bvh = &w->bvh[0];
        w->side[1].bvh = &w->bvh[1];
        break;
    default:
        if ((w->rc[task] = diff_match(&w->v[0], &w->v[1], w->m[0], w->m[1], w->box)))
            snprintf(err, 256, "out of memory");
        break;
    }
}

/* The first failure's message. */
static int work_failed(const Work *w, char *err, size_t errlen)
{
    for (int i = 0; i < T_CHUNKS; i++)
        if (w->rc[i]) {
            snprintf(err, errlen, "%s", w->err[i]);
            return 1;
        }
    return 0;
}

/* One thread: in turn, one hierarchy at a time (B's while A is
 * measured, then A's): the memory beyond the models is one hierarchy
 * and the figures. */
static int measure_in_turn(Work *w, char *err, size_t errlen)
{
    prep_task(w, T_CHECK_A);
    prep_task(w, T_CHECK_B);
    prep_task(w, T_MATCH);
    if (work_failed(w, err, errlen))
        return -1;
    prep_task(w, T_SIDES);
    if (work_failed(w, err, errlen))
        return -1;
    for (int side = 0; side < 2; side++) {
        prep_task(w, side ? T_BVH_A : T_BVH_B);
        if (work_failed(w, err, errlen))
            return -1;
        DiffSideRun *r = &w->side[side];
        for (uint32_t c = 0; c < r->nvchunks; c++)
            diff_side_verts(r, c);
        for (uint32_t c = 0; c < r->nfchunks; c++)
            diff_side_faces(r, c);
        bvh_free(&w->bvh[side]);
        if (diff_side_end(r, err, errlen))
            return -1;
    }
    return 0;
}

/* Wait until the groups in need (a bit each) are done; 0, or -1 when
 * one of the tasks before failed (nothing to measure with). */
static int wait_for(Work *w, unsigned need)
{
    pthread_mutex_lock(&w->mu);
    for (int g = 0; g < NGROUPS; g++)
        while ((need >> g & 1) && w->left[g])
            pthread_cond_wait(&w->cv, &w->mu);
    pthread_mutex_unlock(&w->mu);
    for (int t = 0; t < T_CHUNKS; t++)
        if ((need >> t & 1) && w->rc[t])
            return -1;
    return 0;
}

static void task_done(Work *w, int g)
{
    pthread_mutex_lock(&w->mu);
    int last = --w->left[g] == 0;
    if (last)
        pthread_cond_broadcast(&w->cv);
    pthread_mutex_unlock(&w->mu);
    /* A's samples all taken: nothing reads B's hierarchy again */
    if (last && g == G_FACES_A)
        bvh_free(&w->bvh[0]);
}

#define NEED(g) (1u << (g))

static void queue_task(void *arg, int task, int worker)
{
    (void)worker;
    Work *w = arg;
    int g = 0;
    while ((uint32_t)task >= w->first[g + 1])
        g++;
    uint32_t chunk = (uint32_t)task - w->first[g];
    /* what each needs: a side's vertices the other's hierarchy, the
     * match and its arrays; its faces all its vertices */
    static const unsigned need[NGROUPS] = {
        [G_VERTS_A] = NEED(T_BVH_B) | NEED(T_MATCH) | NEED(T_SIDES),
        [G_VERTS_B] = NEED(T_BVH_A) | NEED(T_MATCH) | NEED(T_SIDES),
        [G_FACES_A] = NEED(G_VERTS_A) | NEED(T_BVH_B) | NEED(T_MATCH) | NEED(T_SIDES),
        [G_FACES_B] = NEED(G_VERTS_B) | NEED(T_BVH_A) | NEED(T_MATCH) | NEED(T_SIDES),
    };
    if (g < T_CHUNKS)
        prep_task(w, g);
    else if (g == G_BESIDE) {
        if (w->beside)
            w->beside(w->beside_arg);
    } else if (!wait_for(w, need[g])) {
        DiffSideRun *r = &w->side[g == G_VERTS_B || g == G_FACES_B];
        if (g == G_VERTS_A || g == G_VERTS_B)
            diff_side_verts(r, chunk);
        else
            diff_side_faces(r, chunk);
    }
    task_done(w, g);
}
/* Several threads: the one queue. */
static int measure_together(Work *w, int threads, char *err, size_t errlen)
{
    uint32_t nv[2], nf[2];
    for (int i = 0; i < 2; i++)
        diff_side_chunks(w->m[i], &nv[i], &nf[i]);
    uint32_t count[NGROUPS];
    for (int g = 0; g < T_CHUNKS; g++)
        count[g] = 1;
    count[G_VERTS_A] = nv[0];
    count[G_VERTS_B] = nv[1];
    count[G_FACES_A] = nf[0];
    count[G_FACES_B] = nf[1];
    count[G_BESIDE] = 1;
    uint64_t total = 0;
    for (int g = 0; g < NGROUPS; g++) {
        w->first[g] = (uint32_t)total;
        w->left[g] = count[g];
        total += count[g];
    }
    w->first[NGROUPS] = (uint32_t)total;
    if (total > INT32_MAX) {
        snprintf(err, errlen, "too many faces");
        return -1;
    }
    Pool *pool = pool_create(threads - 1);
    if (!pool) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    pthread_mutex_init(&w->mu, NULL);
    pthread_cond_init(&w->cv, NULL);
    pool_run(pool, (int)total, queue_task, w);
    pool_free(pool);
    pthread_cond_destroy(&w->cv);
    pthread_mutex_destroy(&w->mu);
    if (work_failed(w, err, errlen))
        return -1;
    return diff_side_end(&w->side[0], err, errlen) || diff_side_end(&w->side[1], err, errlen) ? -1 : 0;
}

int diff_compute(Diff *d, const Mesh *a, const Mesh *b, const DiffOpts *o, char *err, size_t errlen)
{
    double t0 = now_ms();
    memset(d, 0, sizeof *d);
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    if (faces_box(a, lo, hi, err, errlen) || faces_box(b, lo, hi, err, errlen))
        return -1;
    double mag = 0, diag2 = 0;
    for (int k = 0; k < 3; k++) {
        double e = hi[k] >= lo[k] ? hi[k] - lo[k] : 0;
        diag2 += e * e;
        mag = fmax(mag, fmax(fabs(lo[k]), fabs(hi[k])));
    }
    d->diag = sqrt(diag2);
    /* the arithmetic's rounding, at the coordinates' magnitude: a point
     * on a plane the other model draws differently is 1e-17 off it */
    d->zero = ldexp(mag + d->diag, -40);
    d->tol_given = o->tolerance >= 0;
    d->tolerance = d->tol_given ? o->tolerance : DIFF_TOL_FRACTION * d->diag;
    d->samples = o->samples ? o->samples : DIFF_SAMPLES;
    int threads = o->threads > 0 ? o->threads : default_threads();
    float box[6];
    for (int k = 0; k < 3; k++) {
        box[k] = (float)lo[k];
        box[3 + k] = (float)hi[k];
    }
    Work *w = calloc(1, sizeof *w);
    if (!w) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    w->m[0] = a;
    w->m[1] = b;
    w->d = d;
    w->box = box;
    w->checks = o->checks;
    w->cancel = o->cancel;
    w->beside = o->beside;
    w->beside_arg = o->beside_arg;
    int rc = threads > 1 ? measure_together(w, threads, err, errlen) : measure_in_turn(w, err, errlen);
    rc = rc || diff_regions(d, a, b, err, errlen);
    for (int i = 0; i < 2; i++) {
        if (w->side[i].acc)
            diff_side_abort(&w->side[i]);   /* a failure before the sums */
        bvh_free(&w->bvh[i]);
        diff_verts_free(&w->v[i]);
    }
    free(w);
    if (rc) {
        diff_free(d);
        return -1;
    }
    d->hausdorff = fmax(d->a.max, d->b.max);
    d->ms = now_ms() - t0;
    return 0;
}
