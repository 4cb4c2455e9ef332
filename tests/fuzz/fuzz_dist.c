/* fuzz_dist.c: --diff's measure (src/diff/ on src/geom/'s hierarchy) on
 * two models from the differential fuzzer's generator (scenebig.c:
 * terrains, spheres, soups of small triangles, stacked layers), against
 * a brute-force reference. The bytes:
 *
 *   u8  kind, u8 n, u16 seed      model A (sc_big_mesh), at most 800 triangles
 *   coord: i16 x, y, z, u8 size   its centre (x / 1024) and half extent 2^(size % 24 - 12)
 *   u8  how                       bits 0-1: B is 0 a copy of A, 1 A with every vertex
 *                                 moved by up to `amount`, 2 A scaled by 1 + amount about
 *                                 its centre, 3 a model of its own (kind, n, seed, coord
 *                                 follow); bit 2: B leaves out every third face;
 *                                 bit 3: two threads; bit 4: tolerance 0 (else the default)
 *   u8  amount                    2^(amount % 32 - 24) of A's half extent
 *
 * Every input decodes (reads past the end give 0). What must hold, each
 * way: a vertex's distance is the least over every triangle of the
 * other (bvh_point_triangle's, bit for bit, then to float: up to 128
 * vertices a model are compared, the brute force being the time), the largest
 * sample is at least every vertex's and at most the bound, the
 * Hausdorff distance is the larger of the two ways, swapping the models
 * swaps the ways exactly, a face is at least as far as its corners, the
 * regions hold what is over the tolerance. Aborts on the first thing
 * that does not. */

#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diff.h"
#include "fuzz.h"
#include "scenecode.h"
#include "testlib.h"

#define CHECK(cond)                                                                 \
    do {                                                                            \
        if (!(cond)) {                                                              \
            fprintf(stderr, "fuzz_dist: %s:%d: %s\n", __FILE__, __LINE__, #cond);   \
            abort();                                                                \
        }                                                                           \
    } while (0)

#define MAX_TRIS 800

typedef struct {
    const uint8_t *p, *end;
} Rd;

static unsigned u8(Rd *r)
{
    return r->p < r->end ? *r->p++ : 0;
}

static unsigned u16(Rd *r)
{
    unsigned lo = u8(r);
    return lo | u8(r) << 8;
}

static int i16(Rd *r)
{
    return (int16_t)u16(r);
}

/* A model of the generator's into m; 0, or -1 when it has no faces. */
static int model(Rd *r, Mesh *m, double *half)
{
    unsigned kind = u8(r), n = u8(r), seed = u16(r);
    double c[3];
    for (int k = 0; k < 3; k++)
        c[k] = i16(r) / 1024.0;
    *half = ldexp(1, (int)(u8(r) % 24) - 12);
    if (tl_mesh_init(m, "fuzz.obj") || tl_mesh_object(m, "fuzz") || sc_big_mesh(m, kind, n, seed, c, *half, MAX_TRIS) ||
        tl_mesh_finish(m) || m->nfaces == 0)
        return -1;
    return 0;
}

/* The least squared distance from q to m's triangles. */
static double brute(const Mesh *m, const double q[3])
{
    double best = INFINITY, p[3];
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t c0 = m->face_start[f];
        for (uint32_t c = c0 + 1; c + 1 < m->face_start[f + 1]; c++) {
            double a[3], b[3], cc[3];
            for (int k = 0; k < 3; k++) {
                a[k] = m->pos[3 * (size_t)m->corner[c0] + k];
                b[k] = m->pos[3 * (size_t)m->corner[c] + k];
                cc[k] = m->pos[3 * (size_t)m->corner[c + 1] + k];
            }
            double d = bvh_point_triangle(q, a, b, cc, p);
            best = d < best ? d : best;
        }
    }
    return best;
}

static void side_holds(const Diff *d, const DiffSide *s, const Mesh *m, const Mesh *other)
{
    double vmax = 0;
    /* at most 128 vertices against every triangle (every one's distance
     * bounds the maximum below, so those are all compared there) */
    uint32_t step = m->nverts > 128 ? m->nverts / 128 : 1;
    for (uint32_t v = 0; v < m->nverts; v++) {
        if (s->vert_dist[v] < 0)
            continue;
        vmax = fmax(vmax, s->vert_dist[v] > d->zero ? (double)s->vert_dist[v] * (1 - 0x1p-23) : 0);
        if (v % step)
            continue;
        double q[3] = { m->pos[3 * (size_t)v], m->pos[3 * (size_t)v + 1], m->pos[3 * (size_t)v + 2] };
        double want = sqrt(brute(other, q));
        want = want < d->zero ? 0 : want;
        CHECK(s->vert_dist[v] == (float)want);
        vmax = fmax(vmax, want);
    }
    CHECK(s->max >= vmax);
    CHECK(s->bound >= s->max);
    CHECK(s->mean >= 0 && s->mean <= s->bound);
    CHECK(s->area_over >= 0 && s->area_over <= s->area * (1 + 1e-9) + 1e-30);
    for (uint32_t f = 0; f < m->nfaces; f++) {
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++)
            CHECK(s->face_dist[f] >= s->vert_dist[m->corner[c]]);
        CHECK(s->face_dist[f] <= (float)s->max);
        CHECK(s->face_link[f] < other->nfaces);
        CHECK(s->face_class[f] <= DIFF_STRADDLE);
    }
}

static void holds(const Diff *d, const Mesh *a, const Mesh *b)
{
    side_holds(d, &d->a, a, b);
    side_holds(d, &d->b, b, a);
    CHECK(d->hausdorff == fmax(d->a.max, d->b.max));
    /* the regions hold every face over the tolerance, and only those */
    uint64_t over_a = 0, over_b = 0, in_a = 0, in_b = 0;
    for (uint32_t f = 0; f < a->nfaces; f++)
        over_a += d->a.face_dist[f] > d->tolerance;
    for (uint32_t f = 0; f < b->nfaces; f++)
        over_b += d->b.face_dist[f] > d->tolerance;
    double added = 0, removed = 0;
    for (uint32_t i = 0; i < d->nregions; i++) {
        const DiffRegion *r = &d->regions[i];
        CHECK(r->faces_a + r->faces_b > 0);
        CHECK(r->max > d->tolerance && r->max <= (float)d->hausdorff);
        CHECK(i == 0 || r->max <= d->regions[i - 1].max);
        in_a += r->faces_a;
        in_b += r->faces_b;
        added += r->added;
        removed += r->removed;
    }
    CHECK(in_a == over_a && in_b == over_b);
    CHECK(fabs(added - d->b.area_over) <= 1e-6 * (d->b.area + 1e-30) + 1e-30);
    CHECK(fabs(removed - d->a.area_over) <= 1e-6 * (d->a.area + 1e-30) + 1e-30);
    CHECK(diff_differ(d) == (over_a + over_b > 0 && d->hausdorff > d->tolerance));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    Rd r = { data, data + size };
    Mesh a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    double half, half_b;
    if (model(&r, &a, &half)) {
        mesh_free(&a);
        return 0;
    }
    unsigned how = u8(&r), amount = u8(&r);
    double amt = ldexp(half, (int)(amount % 32) - 24);
    int ok = 0;
    if ((how & 3) == 3) {
        ok = model(&r, &b, &half_b) == 0;
    } else {
        ok = tl_mesh_init(&b, "b.obj") == 0;
        uint32_t st = 0x9E3779B9u ^ amount;
        for (uint32_t v = 0; ok && v < a.nverts; v++) {
            float p[3] = { a.pos[3 * v], a.pos[3 * v + 1], a.pos[3 * v + 2] };
            for (int k = 0; k < 3; k++) {
                st ^= st << 13;
                st ^= st >> 17;
                st ^= st << 5;
                if ((how & 3) == 1)
                    p[k] = (float)(p[k] + ((double)(st >> 8) / (1 << 23) - 1) * amt);
                else if ((how & 3) == 2)
                    p[k] = (float)(p[k] * (1 + amt / half));
            }
            ok = tl_mesh_vertex(&b, p[0], p[1], p[2]) == 0;
        }
        for (uint32_t f = 0; ok && f < a.nfaces; f++)
            if (!(how & 4) || f % 3)
                ok = tl_mesh_face(&b, &a.corner[a.face_start[f]], a.face_start[f + 1] - a.face_start[f]) == 0;
        ok = ok && tl_mesh_finish(&b) == 0 && b.nfaces > 0;
    }
    if (ok) {
        /* a small sample budget: the brute force is the fuzzer's time */
        DiffOpts o = { how & 8 ? 2 : 1, how & 16 ? 0 : -1, NULL, 512, 0, NULL, NULL };
        Diff d, e;
        char err[256];
        if (diff_compute(&d, &a, &b, &o, err, sizeof err) == 0) {
            holds(&d, &a, &b);
            /* the other way round: the ways swap, bit for bit */
            if (diff_compute(&e, &b, &a, &o, err, sizeof err) == 0) {
                CHECK(e.a.max == d.b.max && e.b.max == d.a.max && e.hausdorff == d.hausdorff);
                CHECK(e.a.mean == d.b.mean && e.b.mean == d.a.mean);
                CHECK(e.nregions == d.nregions);
                diff_free(&e);
            }
            diff_free(&d);
        }
    }
    mesh_free(&a);
    mesh_free(&b);
    return 0;
}
