/* diff.c: how two models differ: each model's surface against the
 * other's (diffsample.c, include/diff.h), each model's check, then the
 * changed regions (diffregion.c). The hierarchy a model is measured
 * against is the other's, its triangles carrying their face. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "clock.h"
#include "diff.h"
#include "pool.h"

void diff_free(Diff *d)
{
    diff_side_free(&d->a);
    diff_side_free(&d->b);
    free(d->regions);
    memset(d, 0, sizeof *d);
}

/* The box of the vertices m's faces use into lo, hi (grown); -1 with
 * the reason for a vertex that is not a finite point. */
static int faces_box(const Mesh *m, double lo[3], double hi[3], char *err, size_t errlen)
{
    for (uint32_t c = 0; m->face_start && c < m->face_start[m->nfaces]; c++) {
        const float *p = &m->pos[3 * (size_t)m->corner[c]];
        for (int k = 0; k < 3; k++) {
            if (!isfinite(p[k])) {
                snprintf(err, errlen, "%s: vertex %u is not a finite point", m->path ? m->path : "?",
                         m->corner[c] + 1);
                return -1;
            }
            lo[k] = p[k] < lo[k] ? p[k] : lo[k];
            hi[k] = p[k] > hi[k] ? p[k] : hi[k];
        }
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

/* What comes before the samples, as tasks: each model's check, each
 * hierarchy (B's, against which A is measured, then A's), the
 * vertices' match; the biggest first, so that two threads end together. */
enum { PREP_CHECK_A, PREP_CHECK_B, PREP_BVH_B, PREP_BVH_A, PREP_MATCH, PREP_TASKS };

typedef struct {
    const Mesh *m[2];
    Diff       *d;
    const float *box;
    int         checks;
    Bvh         bvh[2];         /* [0]: B's; [1]: A's */
    DiffVerts   v[2];
    int         rc[PREP_TASKS];
    char        err[PREP_TASKS][256];
} Prep;

static void prep_task(void *arg, int task, int worker)
{
    (void)worker;
    Prep *p = arg;
    char *err = p->err[task];
    switch (task) {
    case PREP_CHECK_A:
    case PREP_CHECK_B:
        if (p->checks)
            p->rc[task] = check_of(&p->d->check[task == PREP_CHECK_B], p->m[task == PREP_CHECK_B], err, 256);
        break;
    case PREP_BVH_B:
    case PREP_BVH_A:
        p->rc[task] = build_of(&p->bvh[task == PREP_BVH_A], p->m[task == PREP_BVH_B], err, 256);
        break;
    default:
        if ((p->rc[task] = diff_match(&p->v[0], &p->v[1], p->m[0], p->m[1], p->box)))
            snprintf(err, 256, "out of memory");
        break;
    }
}

/* The first failure's message. */
static int prep_failed(const Prep *p, char *err, size_t errlen)
{
    for (int i = 0; i < PREP_TASKS; i++)
        if (p->rc[i]) {
            snprintf(err, errlen, "%s", p->err[i]);
            return 1;
        }
    return 0;
}

/* One thread: one hierarchy at a time. */
static int measure_in_turn(Prep *p, const DiffOpts *o, char *err, size_t errlen)
{
    Diff *d = p->d;
    for (int t = PREP_CHECK_A; t <= PREP_CHECK_B; t++)
        prep_task(p, t, 0);
    prep_task(p, PREP_MATCH, 0);
    if (prep_failed(p, err, errlen))
        return -1;
    for (int side = 0; side < 2; side++) {
        prep_task(p, side ? PREP_BVH_A : PREP_BVH_B, 0);
        if (prep_failed(p, err, errlen))
            return -1;
        int rc = diff_side(side ? &d->b : &d->a, p->m[side], &p->v[side], &p->bvh[side], d, 1, o->cancel, err, errlen);
        bvh_free(&p->bvh[side]);
        if (rc)
            return -1;
    }
    return 0;
}

/* More threads: everything before the samples side by side, then each
 * model's samples shared out. */
static int measure_together(Prep *p, const DiffOpts *o, int threads, char *err, size_t errlen)
{
    Pool *pool = pool_create(threads - 1);
    if (!pool) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    pool_run(pool, PREP_TASKS, prep_task, p);
    pool_free(pool);
    if (prep_failed(p, err, errlen))
        return -1;
    Diff *d = p->d;
    return diff_side(&d->a, p->m[0], &p->v[0], &p->bvh[0], d, threads, o->cancel, err, errlen) ||
           diff_side(&d->b, p->m[1], &p->v[1], &p->bvh[1], d, threads, o->cancel, err, errlen);
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
    Prep p;
    memset(&p, 0, sizeof p);
    p.m[0] = a;
    p.m[1] = b;
    p.d = d;
    p.box = box;
    p.checks = o->checks;
    int rc = threads > 1 ? measure_together(&p, o, threads, err, errlen) : measure_in_turn(&p, o, err, errlen);
    rc = rc || diff_regions(d, a, b, err, errlen);
    for (int i = 0; i < 2; i++) {
        bvh_free(&p.bvh[i]);
        diff_verts_free(&p.v[i]);
    }
    if (rc) {
        diff_free(d);
        return -1;
    }
    d->hausdorff = fmax(d->a.max, d->b.max);
    d->ms = now_ms() - t0;
    return 0;
}
