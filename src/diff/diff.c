/* diff.c: how two models differ: each model's surface against the
 * other's (diffsample.c, include/diff.h), then the changed regions
 * (diffregion.c). One hierarchy at a time is kept (the other model's,
 * whose triangles carry their face): B's while A is measured, then A's,
 * so the memory beyond the two models is one hierarchy and the per-face
 * and per-vertex figures. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "clock.h"
#include "diff.h"

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

/* Side s: mesh m against the other mesh's hierarchy, built here and
 * freed before returning. */
static int measure_side(DiffSide *s, const Mesh *m, const DiffVerts *verts, const Mesh *other, Diff *d,
                        const DiffOpts *o, int threads, char *err, size_t errlen)
{
    uint32_t *tri = NULL, *face = NULL, n = other->nfaces;
    if (!all_triangles(other) && diff_fan(other, &tri, &face, &n, err, errlen))
        return -1;
    Bvh bvh;
    int rc = bvh_build(&bvh, other->pos, other->nverts, tri ? tri : other->corner, face, n, err, errlen);
    free(tri);
    free(face);
    if (rc)
        return -1;
    rc = diff_side(s, m, verts, &bvh, d, threads, o->cancel, err, errlen);
    bvh_free(&bvh);
    return rc;
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
    DiffVerts va, vb;
    int rc = diff_match(&va, &vb, a, b, box);
    if (rc)
        snprintf(err, errlen, "out of memory");
    rc = rc || measure_side(&d->a, a, &va, b, d, o, threads, err, errlen) ||
         measure_side(&d->b, b, &vb, a, d, o, threads, err, errlen) || diff_regions(d, a, b, err, errlen);
    diff_verts_free(&va);
    diff_verts_free(&vb);
    if (rc) {
        diff_free(d);
        return -1;
    }
    d->hausdorff = fmax(d->a.max, d->b.max);
    d->ms = now_ms() - t0;
    return 0;
}
