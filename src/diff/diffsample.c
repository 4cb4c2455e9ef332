/* diffsample.c: one side of a diff: a model's surface sampled and each
 * sample's distance to the other model (include/diff.h says what the
 * samples are and what is exact). The vertices first, in the order of a
 * Morton curve (queries near one another walk the same nodes), a
 * vertex at the very position of a vertex of the other model's faces
 * being at distance 0 without a query; then the faces. Each pass runs in
 * chunks of a fixed size, as tasks for any thread (diff.c hands them
 * out); a chunk's sums are its own and are added in chunk order, so the
 * figures do not depend on the threads. Each query starts from the
 * answer of the one before it in the chunk (the samples of a chunk are
 * near one another): the answer is the same, found sooner. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "diff.h"
#include "pool.h"

#define VERT_CHUNK 8192
#define FACE_CHUNK 4096
#define R_MAX      4096         /* a triangle's cuts a side at most: 16M samples */

/* What a chunk adds up. */
typedef struct DiffAcc {
    double   sum_dw, sum_w;     /* distance times area, and area */
    double   max, max_at[3], bound, over;
    uint64_t vs, es, fs;
    uint32_t tris;
} Acc;

static int cancelled(const int *cancel)
{
    return cancel && __atomic_load_n(cancel, __ATOMIC_RELAXED);
}

static void acc_init(Acc *a)
{
    memset(a, 0, sizeof *a);
    a->max = -1;
}

static void acc_max(Acc *a, double d, const double p[3])
{
    if (d > a->max) {
        a->max = d;
        memcpy(a->max_at, p, sizeof a->max_at);
    }
}

/* ==== The vertices ==== */

/* The distance of point p to the other model; *link its face. */
static double measure(const DiffSideRun *w, const double p[3], BvhHit *hit, uint32_t *link)
{
    bvh_closest_from(w->bvh, p, hit->tri, hit);
    *link = hit->tri < w->bvh->ntris ? w->bvh->id[hit->tri] : 0;
    double d = sqrt(hit->d2);
    return d < w->d->zero ? 0 : d;
}

void diff_side_verts(DiffSideRun *w, uint32_t task)
{
    const Mesh *m = w->m;
    DiffSide *s = w->s;
    Acc *a = &w->acc[task];
    acc_init(a);
    if (cancelled(w->cancel))
        return;
    const DiffVerts *vs = w->verts;
    uint32_t i0 = task * VERT_CHUNK, i1 = i0 + VERT_CHUNK < vs->nused ? i0 + VERT_CHUNK : vs->nused;
    BvhHit hit = { .tri = BVH_NONE };
    for (uint32_t i = i0; i < i1; i++) {
        uint32_t v = vs->order[i];
        const float *f = &m->pos[3 * (size_t)v];
        double p[3] = { f[0], f[1], f[2] }, d = 0;
        if (vs->on[v] != UINT32_MAX)
            s->vert_link[v] = vs->on[v];    /* a corner of the other's: on its surface */
        else
            d = measure(w, p, &hit, &s->vert_link[v]);
        s->vert_dist[v] = (float)d;
        acc_max(a, d, p);
        if (d > a->bound)
            a->bound = d;
        a->vs++;
    }
}

/* ==== The faces ==== */

typedef struct {
    double   max;               /* the face's farthest sample */
    uint32_t link;
    double   over, area;
} FaceAcc;

static void sample(const DiffSideRun *w, Acc *a, FaceAcc *fa, BvhHit *hit, const double p[3], double weight, double rho)
{
    uint32_t link;
    double d = measure(w, p, hit, &link);
    acc_max(a, d, p);
    if (d + rho > a->bound)
        a->bound = d + rho;
    if (d > fa->max) {
        fa->max = d;
        fa->link = link;
    }
    if (weight > 0) {
        a->sum_dw += d * weight;
        a->sum_w += weight;
        if (d > w->d->tolerance) {
            a->over += weight;
            fa->over += weight;
        }
        a->fs++;
    } else {
        a->es++;
    }
}

static inline double len3(const double u[3])
{
    return sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
}

/* The larger and the smaller, inline: libm's fmax and fmin are calls,
 * five a face. Their values for numbers that are not NaN, which these
 * are (lengths and distances of finite points, zeros all +0). */
static inline double max2(double a, double b)
{
    return a > b ? a : b;
}

static inline double min2(double a, double b)
{
    return a < b ? a : b;
}

/* floor(x) for x >= 0.5 without the call: an integral x below 2^52
 * converts back exactly; past it (or infinite), libm's. */
static inline double floor_pos(double x)
{
    return x < 0x1p52 ? (double)(uint64_t)x : floor(x);
}

/* The share of a triangle where the linear function of its corner
 * values d[] is above t (d sorted here). */
static double share_above(double d0, double d1, double d2, double t)
{
    double x;
    if (d0 > d1) {
        x = d0;
        d0 = d1;
        d1 = x;
    }
    if (d1 > d2) {
        x = d1;
        d1 = d2;
        d2 = x;
    }
    if (d0 > d1) {
        x = d0;
        d0 = d1;
        d1 = x;
    }
    if (t >= d2)
        return 0;
    if (t < d0)
        return 1;
    if (t >= d1)    /* the corner at d2 is above: a small triangle there */
        return (d2 - t) * (d2 - t) / ((d2 - d0) * (d2 - d1));
    return 1 - (t - d0) * (t - d0) / ((d1 - d0) * (d2 - d0));
}

/* Triangle of corners V[] (their distances dv[]): the centres of its
 * r x r small triangles and the points that cut its sides, r for its
 * share of the samples by area; r = 0, its corners alone. */
static void tri_samples(const DiffSideRun *w, Acc *a, FaceAcc *fa, BvhHit *hit, const double *V[3], const double dv[3])
{
    double ab[3], ac[3], bc[3], g[3];
    for (int k = 0; k < 3; k++) {
        ab[k] = V[1][k] - V[0][k];
        ac[k] = V[2][k] - V[0][k];
        bc[k] = V[2][k] - V[1][k];
    }
    double n[3] = { ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0] };
    double area = 0.5 * len3(n);
    fa->area += area;
    a->tris++;
    double r = w->unit > 0 && area > 0 ? floor_pos(sqrt(area / w->unit) + 0.5) : 0;
    uint32_t cuts = r > R_MAX ? R_MAX : (uint32_t)r;
    if (cuts == 0) {
        /* its corners cover it: no point of it is farther from them than
         * its circumradius (abc / 4 area), nor than its longest side */
        double la = len3(ab), lb = len3(ac), lc = len3(bc), lmax = max2(la, max2(lb, lc));
        double rho = area > 0 ? min2(la * lb * lc / (4 * area), lmax) : lmax;
        double dmax = max2(dv[0], max2(dv[1], dv[2]));
        if (dmax + rho > a->bound)
            a->bound = dmax + rho;
        a->sum_dw += area * (dv[0] + dv[1] + dv[2]) / 3;
        a->sum_w += area;
        double over = area * share_above(dv[0], dv[1], dv[2], w->d->tolerance);
        a->over += over;
        fa->over += over;
        return;
    }
    /* the centre, for the samples' reach (a face of no samples needs none) */
    for (int k = 0; k < 3; k++)
        g[k] = (V[0][k] + V[1][k] + V[2][k]) / 3;
    double rho = 0;
    for (int i = 0; i < 3; i++) {
        double e[3] = { V[i][0] - g[0], V[i][1] - g[1], V[i][2] - g[2] };
        rho = fmax(rho, len3(e));
    }
    rho /= cuts;
    double weight = area / ((double)cuts * cuts), inv = 1.0 / (3.0 * cuts);
    for (uint32_t i = 0; i < cuts; i++)
        for (uint32_t j = 0; i + j < cuts; j++) {
            /* the small triangle pointing as the big one, then the one
             * pointing the other way beside it */
            for (int down = 0; down < 2; down++) {
                if (down && i + j + 2 > cuts)
                    break;
                double u = (3.0 * i + 1 + down) * inv, v = (3.0 * j + 1 + down) * inv, p[3];
                for (int k = 0; k < 3; k++)
                    p[k] = V[0][k] + u * ab[k] + v * ac[k];
                sample(w, a, fa, hit, p, weight, rho);
            }
        }
    for (uint32_t k = 1; k < cuts; k++) {
        double t = (double)k / cuts, p[3];
        for (int side = 0; side < 3; side++) {
            const double *x = V[side], *y = V[(side + 1) % 3];
            for (int c = 0; c < 3; c++)
                p[c] = x[c] + t * (y[c] - x[c]);
            sample(w, a, fa, hit, p, 0, 0);
        }
    }
}

static inline void vert_of(const Mesh *m, uint32_t v, double out[3])
{
    const float *f = &m->pos[3 * (size_t)v];
    out[0] = f[0];
    out[1] = f[1];
    out[2] = f[2];
}

void diff_side_faces(DiffSideRun *w, uint32_t task)
{
    const Mesh *m = w->m;
    DiffSide *s = w->s;
    Acc *a = &w->acc[w->nvchunks + task];
    acc_init(a);
    if (cancelled(w->cancel))
        return;
    uint32_t f0 = task * FACE_CHUNK, f1 = f0 + FACE_CHUNK < m->nfaces ? f0 + FACE_CHUNK : m->nfaces;
    double tol = w->d->tolerance;
    BvhHit hit = { .tri = BVH_NONE };
    for (uint32_t f = f0; f < f1; f++) {
        uint32_t c0 = m->face_start[f], c1 = m->face_start[f + 1];
        FaceAcc fa = { .max = -1, .link = 0 };
        int near = 0, far = 0;
        for (uint32_t c = c0; c < c1; c++) {
            uint32_t v = m->corner[c];
            double d = s->vert_dist[v];
            if (d > fa.max) {
                fa.max = d;
                fa.link = s->vert_link[v];
            }
            if (d > tol)
                far = 1;
            else
                near = 1;
        }
        double A[3], B[3], C[3];
        vert_of(m, m->corner[c0], A);
        for (uint32_t c = c0 + 1; c + 1 < c1; c++) {
            vert_of(m, m->corner[c], B);
            vert_of(m, m->corner[c + 1], C);
            const double *V[3] = { A, B, C };
            double dv[3] = { s->vert_dist[m->corner[c0]], s->vert_dist[m->corner[c]], s->vert_dist[m->corner[c + 1]] };
            tri_samples(w, a, &fa, &hit, V, dv);
        }
        s->face_dist[f] = (float)(fa.max < 0 ? 0 : fa.max);
        s->face_link[f] = fa.link;
        s->face_over[f] = (float)fa.over;
        s->face_class[f] = near && far ? DIFF_STRADDLE
                         : far || fa.over > 0.5 * fa.area || (fa.area == 0 && fa.max > tol) ? DIFF_OVER
                                                                                            : DIFF_SAME;
    }
}

/* ==== The side ==== */

void diff_side_free(DiffSide *s)
{
    free(s->vert_dist);
    free(s->vert_link);
    free(s->face_dist);
    free(s->face_link);
    free(s->face_over);
    free(s->face_class);
    memset(s, 0, sizeof *s);
}

/* The surface's area, for the samples' share. */
static double mesh_area(const Mesh *m)
{
    double sum = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t c0 = m->face_start[f], c1 = m->face_start[f + 1];
        double A[3], B[3], C[3];
        vert_of(m, m->corner[c0], A);
        for (uint32_t c = c0 + 1; c + 1 < c1; c++) {
            vert_of(m, m->corner[c], B);
            vert_of(m, m->corner[c + 1], C);
            double u[3] = { B[0] - A[0], B[1] - A[1], B[2] - A[2] }, v[3] = { C[0] - A[0], C[1] - A[1], C[2] - A[2] };
            double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
            sum += 0.5 * len3(n);
        }
    }
    return sum;
}

/* Sum the chunks in order into s. */
static void side_sums(DiffSide *s, const Acc *acc, uint32_t n)
{
    Acc all;
    acc_init(&all);
    for (uint32_t i = 0; i < n; i++) {
        const Acc *a = &acc[i];
        all.sum_dw += a->sum_dw;
        all.sum_w += a->sum_w;
        all.over += a->over;
        all.vs += a->vs;
        all.es += a->es;
        all.fs += a->fs;
        all.tris += a->tris;
        all.bound = fmax(all.bound, a->bound);
        acc_max(&all, a->max, a->max_at);      /* the first chunk's on a tie */
    }
    s->max = all.max > 0 ? all.max : 0;
    memcpy(s->max_at, all.max_at, sizeof s->max_at);
    s->bound = fmax(all.bound, s->max);
    s->mean = all.sum_w > 0 ? all.sum_dw / all.sum_w : 0;
    s->area_over = all.over;
    s->vertex_samples = all.vs;
    s->edge_samples = all.es;
    s->face_samples = all.fs;
    s->triangles = all.tris;
}

void diff_side_chunks(const Mesh *m, uint32_t *nvchunks, uint32_t *nfchunks)
{
    /* as many vertex chunks as the vertices could fill, so that the
     * count is known before the match says which are used: those past
     * the used ones are empty, and add nothing */
    *nvchunks = (uint32_t)(((uint64_t)m->nverts + VERT_CHUNK - 1) / VERT_CHUNK);
    *nfchunks = (uint32_t)(((uint64_t)m->nfaces + FACE_CHUNK - 1) / FACE_CHUNK);
}

int diff_side_begin(DiffSideRun *w, DiffSide *s, const Mesh *m, const DiffVerts *verts, const Diff *d,
                    const int *cancel, char *err, size_t errlen)
{
    memset(w, 0, sizeof *w);
    memset(s, 0, sizeof *s);
    s->nverts = m->nverts;
    s->nfaces = m->nfaces;
    size_t nv = m->nverts ? m->nverts : 1, nf = m->nfaces ? m->nfaces : 1;
    s->vert_dist = bigmem_alloc(nv * sizeof *s->vert_dist);
    s->vert_link = bigmem_alloc(nv * sizeof *s->vert_link);
    s->face_dist = bigmem_alloc(nf * sizeof *s->face_dist);
    s->face_link = bigmem_alloc(nf * sizeof *s->face_link);
    s->face_over = bigmem_alloc(nf * sizeof *s->face_over);
    s->face_class = bigmem_alloc(nf);
    diff_side_chunks(m, &w->nvchunks, &w->nfchunks);
    w->acc = calloc((size_t)w->nvchunks + w->nfchunks + 1, sizeof(Acc));
    if (!s->vert_dist || !s->vert_link || !s->face_dist || !s->face_link || !s->face_over || !s->face_class ||
        !w->acc) {
        free(w->acc);
        w->acc = NULL;
        diff_side_free(s);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    w->m = m;
    w->verts = verts;
    w->d = d;
    w->s = s;
    w->cancel = cancel;
    /* the vertices no face uses stay -1 */
    for (uint32_t v = 0; v < m->nverts; v++) {
        s->vert_dist[v] = -1;
        s->vert_link[v] = 0;
    }
    s->area = mesh_area(m);
    w->unit = s->area / d->samples;
    return 0;
}

int diff_side_end(DiffSideRun *w, char *err, size_t errlen)
{
    DiffSide *s = w->s;
    if (cancelled(w->cancel)) {
        free(w->acc);
        w->acc = NULL;
        diff_side_free(s);
        snprintf(err, errlen, "cancelled");
        return -1;
    }
    side_sums(s, w->acc, w->nvchunks + w->nfchunks);
    free(w->acc);
    w->acc = NULL;
    return 0;
}

void diff_side_abort(DiffSideRun *w)
{
    free(w->acc);
    w->acc = NULL;
    if (w->s)
        diff_side_free(w->s);
}

static void vert_task(void *arg, int task, int worker)
{
    (void)worker;
    diff_side_verts(arg, (uint32_t)task);
}

static void face_task(void *arg, int task, int worker)
{
    (void)worker;
    diff_side_faces(arg, (uint32_t)task);
}

int diff_side(DiffSide *s, const Mesh *m, const DiffVerts *verts, const Bvh *bvh, const Diff *d, int threads,
              const int *cancel, char *err, size_t errlen)
{
    DiffSideRun w;
    if (diff_side_begin(&w, s, m, verts, d, cancel, err, errlen))
        return -1;
    Pool *pool = threads > 1 ? pool_create(threads - 1) : NULL;
    if (threads > 1 && !pool) {
        diff_side_abort(&w);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    w.bvh = bvh;
    pool_run(pool, (int)w.nvchunks, vert_task, &w);
    pool_run(pool, (int)w.nfchunks, face_task, &w);
    pool_free(pool);
    return diff_side_end(&w, err, errlen);
}

int diff_fan(const Mesh *m, uint32_t **tri_out, uint32_t **face_out, uint32_t *n, char *err, size_t errlen)
{
    uint64_t t = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t k = m->face_start[f + 1] - m->face_start[f];
        t += k > 2 ? k - 2 : 0;
    }
    if (t >= UINT32_MAX) {
        snprintf(err, errlen, "%s: %llu triangles (at most %u)", m->path ? m->path : "?", (unsigned long long)t,
                 UINT32_MAX - 1);
        return -1;
    }
    uint32_t *tri = malloc((t ? t : 1) * 3 * sizeof *tri), *face = malloc((t ? t : 1) * sizeof *face);
    if (!tri || !face) {
        free(tri);
        free(face);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    uint32_t k = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t c0 = m->face_start[f], c1 = m->face_start[f + 1];
        for (uint32_t c = c0 + 1; c + 1 < c1; c++, k++) {
            tri[3 * (size_t)k] = m->corner[c0];
            tri[3 * (size_t)k + 1] = m->corner[c];
            tri[3 * (size_t)k + 2] = m->corner[c + 1];
            face[k] = f;
        }
    }
    *tri_out = tri;
    *face_out = face;
    *n = k;
    return 0;
}
