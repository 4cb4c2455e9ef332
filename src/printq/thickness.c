/* thickness.c: how thick the walls are. From each face's centroid one
 * ray goes along the reversed normal (into the material, when the
 * surface faces out) to the first other face it meets: that distance
 * is the face's thickness. This is the single-ray, "ray-based"
 * thickness; the shape diameter function (L. Shapira, A. Shamir and D.
 * Cohen-Or, "Consistent mesh partitioning and skeletonisation using the
 * shape diameter function", The Visual Computer 24, 2008) casts a cone
 * of rays and keeps a filtered median, which smooths over ribs and
 * corners a single ray reads as they are. The faces are fanned into
 * triangles (each carrying its face's id) in a BVH (geom/bvh.c), and
 * the rays (bvh_ray) are shared among the threads in chunks. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "pool.h"
#include "printq.h"

#define CHUNK 4096              /* faces a task */

typedef struct {
    const Mesh *m;
    const Bvh  *bvh;
    float      *out;
} RayJob;

/* Face f's centroid (the mean of its corners) and unit Newell normal;
 * 0 when it has no area. */
static int face_frame(const Mesh *m, uint32_t f, double c[3], double n[3])
{
    uint32_t c0 = m->face_start[f], k = m->face_start[f + 1] - c0;
    c[0] = c[1] = c[2] = n[0] = n[1] = n[2] = 0;
    for (uint32_t i = 0; i < k; i++) {
        const float *a = &m->pos[3 * (size_t)m->corner[c0 + i]];
        const float *b = &m->pos[3 * (size_t)m->corner[c0 + (i + 1) % k]];
        n[0] += ((double)a[1] - b[1]) * ((double)a[2] + b[2]);
        n[1] += ((double)a[2] - b[2]) * ((double)a[0] + b[0]);
        n[2] += ((double)a[0] - b[0]) * ((double)a[1] + b[1]);
        for (int j = 0; j < 3; j++)
            c[j] += a[j];
    }
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!k || !(len > 0))
        return 0;
    for (int j = 0; j < 3; j++) {
        c[j] /= k;
        n[j] /= len;
    }
    return 1;
}

static void rays_task(void *arg, int task, int worker)
{
    (void)worker;
    const RayJob *j = arg;
    uint32_t f0 = (uint32_t)task * CHUNK, f1 = f0 + CHUNK < j->m->nfaces ? f0 + CHUNK : j->m->nfaces;
    for (uint32_t f = f0; f < f1; f++) {
        double c[3], n[3];
        j->out[f] = -1;
        if (!face_frame(j->m, f, c, n))
            continue;
        double d[3] = { -n[0], -n[1], -n[2] };
        BvhRayHit h;
        bvh_ray(j->bvh, c, d, INFINITY, f, &h);
        if (h.tri != BVH_NONE)
            j->out[f] = (float)h.t;
    }
}

/* Every face fanned into triangles (c0, ck, ck+1), each with its face's
 * id. -1 out of memory. */
static int fan(const Mesh *m, uint32_t **tri_out, uint32_t **id_out, uint32_t *ntris)
{
    uint64_t n = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t k = m->face_start[f + 1] - m->face_start[f];
        n += k >= 3 ? k - 2 : 0;
    }
    if (n > UINT32_MAX / 3)
        return -1;
    uint32_t *tri = malloc((n ? n : 1) * 3 * sizeof *tri), *id = malloc((n ? n : 1) * sizeof *id);
    if (!tri || !id) {
        free(tri);
        free(id);
        return -1;
    }
    uint32_t t = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t c0 = m->face_start[f], k = m->face_start[f + 1] - c0;
        for (uint32_t i = 1; i + 1 < k; i++, t++) {
            tri[3 * (size_t)t] = m->corner[c0];
            tri[3 * (size_t)t + 1] = m->corner[c0 + i];
            tri[3 * (size_t)t + 2] = m->corner[c0 + i + 1];
            id[t] = f;
        }
    }
    *tri_out = tri;
    *id_out = id;
    *ntris = t;
    return 0;
}

/* The k-th least of v[0 .. n) (from 0), v reordered so that what is
 * before k is no more than it (Hoare's selection, the middle of three as
 * the pivot): linear on average. Sorting the whole array for the median
 * cost a tenth of --thickness's instructions on the dragon, serially. */
static float kth_least(float *v, int64_t n, int64_t k)
{
    int64_t lo = 0, hi = n - 1;
    while (lo < hi) {
        float a = v[lo], b = v[lo + (hi - lo) / 2], c = v[hi];
        float p = a < b ? (b < c ? b : a < c ? c : a) : (a < c ? a : b < c ? c : b);
        int64_t i = lo, j = hi;
        while (i <= j) {
            while (v[i] < p)
                i++;
            while (v[j] > p)
                j--;
            if (i <= j) {
                float t = v[i];
                v[i++] = v[j];
                v[j--] = t;
            }
        }
        /* [lo, j] <= p, [i, hi] >= p, and what lies between is p */
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return v[k];
    }
    return v[k];
}

/* The least, where and the median of the faces measured. -1 out of memory. */
static int summarise(const Mesh *m, PrintqThickness *t)
{
    float *v = malloc((t->nfaces ? t->nfaces : 1) * sizeof *v);
    if (!v)
        return -1;
    uint32_t k = 0;
    t->min = INFINITY;
    for (uint32_t f = 0; f < t->nfaces; f++)
        if (t->face[f] >= 0) {
            v[k++] = t->face[f];
            if (t->face[f] < t->min) {
                t->min = t->face[f];
                t->min_face = f;
            }
        }
    t->measured = k;
    if (k) {
        double n[3];
        face_frame(m, t->min_face, t->min_at, n);
        float hi = kth_least(v, k, k / 2), lo = hi;
        /* an even count: the other middle one is the most of those before */
        for (uint32_t i = 0; k % 2 == 0 && i < k / 2; i++)
            lo = i ? fmaxf(lo, v[i]) : v[i];
        t->median = k % 2 ? hi : ((double)lo + hi) / 2;
    } else {
        t->min = 0;
    }
    free(v);
    return 0;
}

int printq_thickness(const Mesh *m, int threads, PrintqThickness *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    uint32_t *tri = NULL, *id = NULL, ntris = 0;
    Bvh bvh;
    memset(&bvh, 0, sizeof bvh);
    out->nfaces = m->nfaces;
    out->face = malloc((m->nfaces ? m->nfaces : 1) * sizeof *out->face);
    if (!out->face || fan(m, &tri, &id, &ntris)) {
        snprintf(err, errlen, "out of memory");
        goto fail;
    }
    int r = bvh_build(&bvh, m->pos, m->nverts, tri, id, ntris, err, errlen);
    free(tri);
    free(id);
    if (r)
        goto fail;
    RayJob j = { m, &bvh, out->face };
    Pool *pool = threads > 1 ? pool_create(threads - 1) : NULL;
    pool_run(pool, (int)((m->nfaces + CHUNK - 1) / CHUNK), rays_task, &j);
    pool_free(pool);
    bvh_free(&bvh);
    if (summarise(m, out)) {
        snprintf(err, errlen, "out of memory");
        goto fail;
    }
    return 0;
fail:
    printq_thickness_free(out);
    return -1;
}

void printq_thickness_free(PrintqThickness *t)
{
    free(t->face);
    memset(t, 0, sizeof *t);
}

double printq_thin_area(const Mesh *m, const PrintqThickness *t, double limit)
{
    double area = 0;
    for (uint32_t f = 0; f < t->nfaces && f < m->nfaces; f++)
        if (t->face[f] >= 0 && t->face[f] < limit) {
            double nv[3];
            printq_newell(m, f, nv);
            area += sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]) / 2;
        }
    return area;
}
