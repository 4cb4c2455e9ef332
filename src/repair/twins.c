/* twins.c: which duplicate faces the clean drops, one object at a time.
 *
 * The check calls a face a duplicate when an earlier face of its object
 * is on the same points (in any order or winding). Two such faces share
 * every edge, so the pairing already says where to look (as the check's
 * dups.c does): a face whose first edge is manifold can only duplicate
 * the face across it, one on a boundary edge duplicates none, and only
 * the faces whose first edge is non-manifold go through a hash table of
 * sorted point lists. The first of each set of equal faces is the
 * original.
 *
 * Dropping a duplicate is not always a repair: a face and its copy
 * wound the other way make a two-sided flap, and dropping the copy alone
 * would open the flap's free edges (boundary the check would count, no
 * hole to fill). So for each set the faces on each of its edges are
 * counted (from the pairing: two on a manifold edge, the group's on a
 * non-manifold one) and the first of these is taken:
 *
 *   the first face kept, its copies dropped, when that leaves no edge
 *   with one face that had more;
 *   the whole set dropped (a flap: its free edges go with it), when
 *   that leaves none either and the object keeps a face;
 *   the set kept (the check still counts its duplicates).
 *
 * Sets are taken in the order of their first faces, each seeing the
 * counts the earlier ones left. A face dropped leaves the topology at
 * once (ObjTopo.skip) and the mesh's arrays when the objects are done
 * (repair.c). */

#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return a < b ? -1 : a > b;
}

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

/* Relative face f's points, sorted, into buf. */
static uint32_t sorted_points(const Rep *r, const ObjTopo *t, uint32_t f, uint32_t *buf)
{
    uint32_t s = rp_start(r, t, f), n = rp_start(r, t, f + 1) - s;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t p = rp_cpt(r, t, s + i), j = i;
        if (n > 16) {
            buf[i] = p;
            continue;
        }
        for (; j > 0 && buf[j - 1] > p; j--)
            buf[j] = buf[j - 1];
        buf[j] = p;
    }
    if (n > 16)
        qsort(buf, n, sizeof *buf, cmp_u32);
    return n;
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

/* ==== Finding the sets ==== */

typedef struct {
    uint64_t *pair;             /* first face << 32 | its copy (relative faces) */
    uint32_t  n, cap;
    uint32_t *a, *b;            /* two faces' sorted points */
} Twins;

static int twin_add(Twins *tw, uint32_t first, uint32_t copy)
{
    if (tw->n == tw->cap) {
        uint32_t c = tw->cap ? tw->cap * 2 : 64;
        uint64_t *p = realloc(tw->pair, (size_t)c * sizeof *p);
        if (!p)
            return -1;
        tw->pair = p;
        tw->cap = c;
    }
    tw->pair[tw->n++] = (uint64_t)first << 32 | copy;
    return 0;
}

static int same_points(const Rep *r, const ObjTopo *t, Twins *tw, uint32_t f, uint32_t g)
{
    uint32_t n = sorted_points(r, t, f, tw->a);
    return sorted_points(r, t, g, tw->b) == n && !memcmp(tw->a, tw->b, n * sizeof *tw->a);
}

/* The faces of cand[0..n) (in face order) against each other. */
static int by_hash(const Rep *r, const ObjTopo *t, Twins *tw, const uint32_t *cand, uint32_t n)
{
    size_t size = 64;
    while (size < 2 * (size_t)n + 2)
        size *= 2;
    uint32_t *slot = malloc(2 * size * sizeof *slot);     /* face, hash */
    if (!slot)
        return -1;
    for (size_t h = 0; h < size; h++)
        slot[2 * h] = RP_NONE;
    int rc = 0;
    for (uint32_t i = 0; i < n && rc == 0; i++) {
        uint32_t f = cand[i], k = sorted_points(r, t, f, tw->a), key = list_hash(tw->a, k);
        /* invariant: the table is at most half full, so a probe ends */
        for (size_t h = key & (size - 1);; h = (h + 1) & (size - 1)) {
            if (slot[2 * h] == RP_NONE) {
                slot[2 * h] = f;
                slot[2 * h + 1] = key;
                break;
            }
            if (slot[2 * h + 1] == key && same_points(r, t, tw, f, slot[2 * h])) {
                rc = twin_add(tw, slot[2 * h], f);
                break;
            }
        }
    }
    free(slot);
    return rc;
}

/* Each face on the points of an earlier one, with the first of its set. */
static int find_twins(const Rep *r, const ObjTopo *t, Twins *tw)
{
    uint32_t *cand = NULL, ncand = 0, cap = 0;
    int rc = 0;
    for (uint32_t f = 0; f < t->nf && rc == 0; f++) {
        if (t->skip[f])
            continue;
        uint32_t c = rp_start(r, t, f), e = rp_start(r, t, f + 1);
        while (c < e && t->mate[c] == RP_SELF)
            c++;
        uint32_t m = c < e ? t->mate[c] : RP_NONMANIF;
        if (m == RP_BOUNDARY)
            continue;
        if (m == RP_NONMANIF) {
            if (ncand == cap) {
                cap = cap ? 2 * cap : 64;
                uint32_t *q = realloc(cand, (size_t)cap * sizeof *q);
                if (!q) {
                    rc = -1;
                    break;
                }
                cand = q;
            }
            cand[ncand++] = f;
            continue;
        }
        /* two faces alone on the edge: the later one is the copy */
        uint32_t g = rp_cface(t, m);
        if (g < f && same_points(r, t, tw, f, g))
            rc = twin_add(tw, g, f);
    }
    if (rc == 0 && ncand)
        rc = by_hash(r, t, tw, cand, ncand);
    free(cand);
    return rc;
}

/* ==== The faces on each of their edges ==== */

typedef struct {
    uint64_t *key;              /* smaller point << 32 | larger, UINT64_MAX empty */
    uint32_t *count;            /* faces on it */
    size_t    size;
} Counts;

static size_t count_slot(const Counts *ct, uint64_t k)
{
    size_t mask = ct->size - 1, h = (size_t)((k * 0x9E3779B97F4A7C15ull) >> 20) & mask;
    /* invariant: at most half full */
    while (ct->key[h] != UINT64_MAX && ct->key[h] != k)
        h = (h + 1) & mask;
    return h;
}

/* The edge of half-edge c (no edge when it runs from a point to itself). */
static uint64_t edge_of(const Rep *r, const ObjTopo *t, uint32_t c)
{
    uint32_t p = rp_cpt(r, t, c), q = rp_cpt(r, t, rp_next(r, t, c));
    return p == q ? UINT64_MAX : p < q ? (uint64_t)p << 32 | q : (uint64_t)q << 32 | p;
}

/* The faces on every edge of the sets' faces, from the pairing: two on a
 * manifold edge, the group's on a non-manifold one. */
static int counts_build(const Rep *r, const ObjTopo *t, const Twins *tw, Counts *ct)
{
    size_t edges = 0;
    for (uint32_t k = 0; k < tw->n; k++)
        for (int j = 0; j < 2; j++) {
            uint32_t f = j ? (uint32_t)tw->pair[k] : (uint32_t)(tw->pair[k] >> 32);
            edges += rp_start(r, t, f + 1) - rp_start(r, t, f);
        }
    ct->size = 64;
    while (ct->size < 2 * edges + 2)
        ct->size *= 2;
    ct->key = malloc(ct->size * sizeof *ct->key);
    ct->count = calloc(ct->size, sizeof *ct->count);
    if (!ct->key || !ct->count)
        return -1;
    memset(ct->key, 0xff, ct->size * sizeof *ct->key);
    for (uint32_t i = 0; i < tw->n; i++)
        for (int j = 0; j < 2; j++) {
            uint32_t f = j ? (uint32_t)tw->pair[i] : (uint32_t)(tw->pair[i] >> 32);
            for (uint32_t c = rp_start(r, t, f); c < rp_start(r, t, f + 1); c++) {
                uint64_t k = edge_of(r, t, c);
                if (k == UINT64_MAX)
                    continue;
                size_t h = count_slot(ct, k);
                ct->key[h] = k;
                ct->count[h] = t->mate[c] == RP_BOUNDARY ? 1 : 2;
            }
        }
    for (uint32_t g = 0; g < t->nm_ngroup; g++) {
        size_t h = count_slot(ct, edge_of(r, t, t->nm_half[t->nm_group[g]]));
        if (ct->key[h] != UINT64_MAX)
            ct->count[h] = t->nm_group[g + 1] - t->nm_group[g];
    }
    return 0;
}

/* Take the faces list[0..n) off the counts; undo: put them back. 1 when
 * an edge that had two faces or more is left with one. */
static int take(const Rep *r, const ObjTopo *t, Counts *ct, const uint32_t *list, uint32_t n, int undo)
{
    int opens = 0;
    for (int pass = 0; pass < (undo ? 1 : 2); pass++)
        for (uint32_t i = 0; i < n; i++)
            for (uint32_t c = rp_start(r, t, list[i]); c < rp_start(r, t, list[i] + 1); c++) {
                uint64_t k = edge_of(r, t, c);
                if (k == UINT64_MAX)
                    continue;
                size_t h = count_slot(ct, k);
                if (pass == 0)
                    ct->count[h] += undo ? 1u : (uint32_t)-1;
                else if (ct->count[h] == 1)
                    opens = 1;  /* one face left where the faces taken made it more */
            }
    return opens;
}

/* ==== Deciding ==== */

/* One set: first, then its copies; skip[] marks what goes. */
static void decide(Rep *r, ObjTopo *t, Counts *ct, uint32_t *set, uint32_t n, uint32_t *faces_left)
{
    if (!take(r, t, ct, set + 1, n - 1, 0)) {
        for (uint32_t i = 1; i < n; i++)
            t->skip[set[i]] = 1;
        r->rep->duplicate += n - 1;
        *faces_left -= n - 1;
        return;
    }
    /* the first face too: a flap goes whole, if something stays */
    if (*faces_left > n && !take(r, t, ct, set, 1, 0)) {
        for (uint32_t i = 0; i < n; i++)
            t->skip[set[i]] = 1;
        r->rep->duplicate += n - 1;
        r->rep->flaps++;
        *faces_left -= n;
        return;
    }
    if (*faces_left > n)
        take(r, t, ct, set, 1, 1);
    take(r, t, ct, set + 1, n - 1, 1);
    r->rep->dup_kept += n - 1;
}

int rp_twins(Rep *r, ObjTopo *t, uint8_t *drop)
{
    uint32_t maxn = 0;
    for (uint32_t f = 0; f < t->nf; f++)
        maxn = rp_start(r, t, f + 1) - rp_start(r, t, f) > maxn ? rp_start(r, t, f + 1) - rp_start(r, t, f) : maxn;
    Twins tw = { .a = malloc(((size_t)maxn + 1) * sizeof *tw.a), .b = malloc(((size_t)maxn + 1) * sizeof *tw.b) };
    Counts ct = { 0 };
    uint32_t *set = NULL, dropped = 0;
    int rc = -1;
    if (!tw.a || !tw.b || find_twins(r, t, &tw))
        goto out;
    rc = 0;
    if (!tw.n)
        goto out;
    rc = -1;
    if (counts_build(r, t, &tw, &ct) || !(set = malloc(((size_t)tw.n + 2) * sizeof *set)))
        goto out;
    qsort(tw.pair, tw.n, sizeof *tw.pair, cmp_u64);
    uint32_t left = 0;
    for (uint32_t f = 0; f < t->nf; f++)
        left += !t->skip[f];
    for (uint32_t k = 0; k < tw.n;) {
        uint32_t first = (uint32_t)(tw.pair[k] >> 32), n = 1;
        set[0] = first;
        for (; k < tw.n && (uint32_t)(tw.pair[k] >> 32) == first; k++)
            set[n++] = (uint32_t)tw.pair[k];
        decide(r, t, &ct, set, n, &left);
    }
    for (uint32_t k = 0; k < tw.n; k++)
        for (int j = 0; j < 2; j++) {
            uint32_t f = j ? (uint32_t)tw.pair[k] : (uint32_t)(tw.pair[k] >> 32);
            if (t->skip[f] && !drop[t->f0 + f]) {
                drop[t->f0 + f] = 1;
                dropped++;
            }
        }
    /* the faces dropped leave the pairing */
    rc = dropped ? rp_topo_unpair(r, t) : 0;
out:
    free(tw.pair);
    free(tw.a);
    free(tw.b);
    free(ct.key);
    free(ct.count);
    free(set);
    return rc;
}
