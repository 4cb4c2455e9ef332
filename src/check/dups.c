/* dups.c: duplicate faces, on the same points as an earlier face of the
 * object (in any order or winding).
 *
 * Two such faces share every edge, so the pairing already knows where
 * to look: a face whose first edge is manifold can only duplicate the
 * face across it, and one on a boundary edge duplicates none. Only the
 * faces whose first edge is non-manifold (a doubled face on a closed
 * mesh makes all its edges so) and the degenerate faces (out of the
 * pairing) go through a hash table of sorted point lists. Of each set
 * of equal faces the first in the file is the original and the others
 * are flagged and counted. */

#include <stdlib.h>
#include <string.h>

#include "check_internal.h"

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return a < b ? -1 : a > b;
}

/* Face f's points, sorted, into buf (room for o->max_corners):
 * insertion for the triangles and quads of nearly every face, qsort for
 * a long polygon. */
static uint32_t sorted_points(const ObjCheck *o, uint32_t f, uint32_t *buf)
{
    uint32_t s = oc_start(o, f), n = oc_start(o, f + 1) - s;
    if (n > 16) {
        for (uint32_t i = 0; i < n; i++)
            buf[i] = oc_pt(o, s + i);
        qsort(buf, n, sizeof *buf, cmp_u32);
        return n;
    }
    for (uint32_t i = 0; i < n; i++) {
        uint32_t v = oc_pt(o, s + i), j = i;
        for (; j > 0 && buf[j - 1] > v; j--)
            buf[j] = buf[j - 1];
        buf[j] = v;
    }
    return n;
}

typedef struct {
    uint32_t *a, *b;            /* two faces' sorted points */
} Scratch;

/* s->a holds n sorted points: has face g the same? */
static int same_points(const ObjCheck *o, Scratch *s, uint32_t g, uint32_t n)
{
    return sorted_points(o, g, s->b) == n && !memcmp(s->a, s->b, n * sizeof *s->a);
}

/* The later of two equal faces is the duplicate (once, however found). */
static void mark(ObjCheck *o, uint32_t f, uint32_t g)
{
    uint32_t later = f > g ? f : g;
    if (!(o->flags[later] & CHECK_DUPLICATE)) {
        o->flags[later] |= CHECK_DUPLICATE;
        o->c->duplicate_faces++;
    }
}

static uint32_t list_hash(const uint32_t *p, uint32_t n)
{
    uint64_t h = 0x9E3779B97F4A7C15ull ^ n;
    for (uint32_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0xFF51AFD7ED558CCDull;
        h ^= h >> 33;
    }
    return (uint32_t)h;
}

/* The faces of `cand` (in face order) against each other. */
static int by_hash(ObjCheck *o, Scratch *s, const uint32_t *cand, size_t n)
{
    size_t size = 64;
    while (size < 2 * n)
        size *= 2;
    uint32_t *slot = malloc(size * sizeof *slot);
    if (!slot)
        return -1;
    memset(slot, 0xff, size * sizeof *slot);
    for (size_t i = 0; i < n; i++) {
        uint32_t f = cand[i], k = sorted_points(o, f, s->a);
        /* invariant: the table is at most half full, so a probe ends */
        for (size_t h = list_hash(s->a, k) & (size - 1);; h = (h + 1) & (size - 1)) {
            if (slot[h] == CHECK_NONE) {
                slot[h] = f;
                break;
            }
            if (same_points(o, s, slot[h], k)) {
                mark(o, f, slot[h]);
                break;
            }
        }
    }
    free(slot);
    return 0;
}

int check_duplicates(ObjCheck *o)
{
    Scratch s = { malloc(((size_t)o->max_corners + 1) * sizeof *s.a),
                  malloc(((size_t)o->max_corners + 1) * sizeof *s.b) };
    uint32_t *cand = NULL;
    size_t ncand = 0, cap = 0;
    int r = -1;
    if (!s.a || !s.b)
        goto out;
    for (uint32_t f = 0; f < o->nf; f++) {
        uint32_t c = oc_start(o, f), e = oc_start(o, f + 1);
        while (c < e && (o->mate[c] == MATE_DEGENERATE || o->mate[c] == MATE_SKIPPED))
            c++;
        uint32_t m = c < e ? o->mate[c] : MATE_NONMANIF;
        if (m == MATE_BOUNDARY)
            continue;
        if (m == MATE_NONMANIF) {
            if (check_push(&cand, &ncand, &cap, f))
                goto out;
            continue;
        }
        uint32_t g = oc_face(o, m);
        if (g == f)
            continue;
        /* two triangles on one edge are equal when their third points are */
        if (o->tris ? oc_pt(o, oc_next(o, oc_next(o, c))) == oc_pt(o, oc_next(o, oc_next(o, m)))
                    : same_points(o, &s, f, sorted_points(o, g, s.a)))
            mark(o, f, g);
    }
    r = by_hash(o, &s, cand, ncand);
out:
    free(s.a);
    free(s.b);
    free(cand);
    return r;
}
