/* diffregion.c: the changed regions of a diff. A face is changed when a
 * sample of it is farther from the other model than the tolerance. On
 * each model, changed faces that share a corner are one region (corners
 * at one position are one: the faces of an STL share no index); across
 * the two, a changed face joins the changed face of the other model
 * nearest to its farthest sample, so that a bump (B's faces out, A's
 * faces under them) is one region, not one a model. A union-find over
 * both models' faces, A's first. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "diff.h"

static uint32_t find(uint32_t *parent, uint32_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];      /* path halving */
        i = parent[i];
    }
    return i;
}

static void join(uint32_t *parent, uint32_t i, uint32_t j)
{
    i = find(parent, i);
    j = find(parent, j);
    if (i != j)
        parent[i > j ? i : j] = i < j ? i : j;  /* the lower index is the root: the result does not depend on order */
}

/* A position as a key: -0 taken as +0, so that one point is one key. */
typedef struct {
    uint32_t k[3];
} PosKey;

static PosKey pos_key(const float *p)
{
    PosKey key;
    for (int i = 0; i < 3; i++) {
        float v = p[i] == 0 ? 0.0f : p[i];
        memcpy(&key.k[i], &v, sizeof key.k[i]);
    }
    return key;
}

static uint64_t key_hash(const PosKey *key)
{
    uint64_t h = key->k[0] * 0x9E3779B97F4A7C15ull;
    h ^= (h >> 29) + key->k[1] * 0xBF58476D1CE4E5B9ull;
    h ^= (h >> 31) + key->k[2] * 0x94D049BB133111EBull;
    return h ^ (h >> 32);
}

/* Join m's changed faces (face_dist > tol) that share a corner position;
 * base: the index of m's face 0 in parent. 0, or -1 out of memory. */
static int weld_faces(const Mesh *m, const DiffSide *s, double tol, uint32_t base, uint32_t *parent)
{
    uint64_t corners = 0;
    for (uint32_t f = 0; f < m->nfaces; f++)
        if (s->face_dist[f] > tol)
            corners += m->face_start[f + 1] - m->face_start[f];
    if (!corners)
        return 0;
    uint64_t cap = 16;
    while (cap < 2 * corners)
        cap *= 2;
    PosKey *key = malloc(cap * sizeof *key);
    uint32_t *owner = malloc(cap * sizeof *owner);
    if (!key || !owner) {
        free(key);
        free(owner);
        return -1;
    }
    for (uint64_t i = 0; i < cap; i++)
        owner[i] = UINT32_MAX;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        if (!(s->face_dist[f] > tol))
            continue;
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++) {
            PosKey k = pos_key(&m->pos[3 * (size_t)m->corner[c]]);
            /* linear probing: the table is at most half full */
            for (uint64_t h = key_hash(&k) & (cap - 1);; h = (h + 1) & (cap - 1)) {
                if (owner[h] == UINT32_MAX) {
                    key[h] = k;
                    owner[h] = base + f;
                    break;
                }
                if (!memcmp(&key[h], &k, sizeof k)) {
                    join(parent, owner[h], base + f);
                    break;
                }
            }
        }
    }
    free(key);
    free(owner);
    return 0;
}

/* Join each changed face of side s (its faces from base in parent) to
 * the other's face nearest to its farthest sample, when that one is
 * changed too (the other's faces from obase). */
static void join_across(const DiffSide *s, const DiffSide *other, double tol, uint32_t base, uint32_t obase,
                        uint32_t *parent)
{
    for (uint32_t f = 0; f < s->nfaces; f++) {
        uint32_t g = s->face_link[f];
        if (s->face_dist[f] > tol && g < other->nfaces && other->face_dist[g] > tol)
            join(parent, base + f, obase + g);
    }
}

/* Grow region r by face f of m (side s; added: it is B's). */
static void region_add(DiffRegion *r, const Mesh *m, const DiffSide *s, uint32_t f, int added)
{
    for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++) {
        const float *p = &m->pos[3 * (size_t)m->corner[c]];
        for (int k = 0; k < 3; k++) {
            r->lo[k] = p[k] < r->lo[k] ? p[k] : r->lo[k];
            r->hi[k] = p[k] > r->hi[k] ? p[k] : r->hi[k];
        }
    }
    if (s->face_dist[f] > r->max)
        r->max = s->face_dist[f];
    if (added) {
        r->added += s->face_over[f];
        r->faces_b++;
    } else {
        r->removed += s->face_over[f];
        r->faces_a++;
    }
}

static int by_max(const void *x, const void *y)
{
    const DiffRegion *a = x, *b = y;
    if (a->max != b->max)
        return a->max > b->max ? -1 : 1;
    uint32_t fa = a->faces_a + a->faces_b, fb = b->faces_a + b->faces_b;
    if (fa != fb)
        return fa > fb ? -1 : 1;
    for (int k = 0; k < 3; k++)
        if (a->lo[k] != b->lo[k])
            return a->lo[k] < b->lo[k] ? -1 : 1;
    return 0;
}

int diff_regions(Diff *d, const Mesh *a, const Mesh *b, char *err, size_t errlen)
{
    double tol = d->tolerance;
    uint32_t na = a->nfaces, nb = b->nfaces;
    uint64_t n = (uint64_t)na + nb;
    d->regions = NULL;
    d->nregions = 0;
    if (n >= UINT32_MAX) {
        snprintf(err, errlen, "%llu faces in the two models (at most %u)", (unsigned long long)n, UINT32_MAX - 1);
        return -1;
    }
    uint32_t *parent = bigmem_alloc((n ? n : 1) * sizeof *parent), *region = bigmem_alloc((n ? n : 1) * sizeof *region);
    if (!parent || !region)
        goto oom;
    for (uint32_t i = 0; i < n; i++)
        parent[i] = i;
    if (weld_faces(a, &d->a, tol, 0, parent) || weld_faces(b, &d->b, tol, na, parent))
        goto oom;
    join_across(&d->a, &d->b, tol, 0, na, parent);
    join_across(&d->b, &d->a, tol, na, 0, parent);
    /* number the regions by their root, in face order */
    uint32_t count = 0;
    for (uint32_t i = 0; i < n; i++) {
        region[i] = UINT32_MAX;
        float fd = i < na ? d->a.face_dist[i] : d->b.face_dist[i - na];
        if (fd > tol) {
            uint32_t r = find(parent, i);
            if (r == i)
                region[i] = count++;
        }
    }
    d->regions = calloc(count ? count : 1, sizeof *d->regions);
    if (!d->regions)
        goto oom;
    for (uint32_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) {
            d->regions[i].lo[k] = INFINITY;
            d->regions[i].hi[k] = -INFINITY;
        }
    for (uint32_t i = 0; i < n; i++) {
        float fd = i < na ? d->a.face_dist[i] : d->b.face_dist[i - na];
        if (!(fd > tol))
            continue;
        DiffRegion *r = &d->regions[region[find(parent, i)]];
        if (i < na)
            region_add(r, a, &d->a, i, 0);
        else
            region_add(r, b, &d->b, i - na, 1);
    }
    d->nregions = count;
    qsort(d->regions, count, sizeof *d->regions, by_max);
    free(parent);
    free(region);
    return 0;
oom:
    free(parent);
    free(region);
    free(d->regions);
    d->regions = NULL;
    snprintf(err, errlen, "out of memory");
    return -1;
}
