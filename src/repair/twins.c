/* twins.c: which duplicate faces the clean drops.
 *
 * The check calls a face a duplicate when an earlier face of its object
 * is on the same points (in any order or winding); they are found here
 * the same way, through a hash table of sorted point lists (the lists
 * compared only when their hashes are equal). Dropping one is not
 * always a repair: a face and its copy wound the other way make a
 * two-sided flap, and dropping the copy alone would open the flap's
 * free edges (boundary the check would count, no hole to fill). So for
 * each set of equal faces the clean counts the faces on each of their
 * edges (the object's faces, degenerate ones already gone) and takes
 * the first of:
 *
 *   the first face kept, its copies dropped, when that leaves no edge
 *   with one face that had more;
 *   the whole set dropped (a flap: its free edges go with it), when
 *   that leaves none either and the object keeps a face;
 *   the set kept (the check still counts its duplicates).
 *
 * Sets are taken in the order of their first faces, each seeing the
 * counts the earlier ones left. */

#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return a < b ? -1 : a > b;
}

/* Face f's points, sorted, into buf. */
static uint32_t sorted_points(const Rep *r, uint32_t f, uint32_t *buf)
{
    const Mesh *m = &r->w;
    uint32_t s = m->face_start[f], n = m->face_start[f + 1] - s;
    if (n == 3) {
        uint32_t x = r->pid[m->corner[s]], y = r->pid[m->corner[s + 1]], z = r->pid[m->corner[s + 2]], t;
        if (x > y)
            t = x, x = y, y = t;
        if (y > z)
            t = y, y = z, z = t;
        if (x > y)
            t = x, x = y, y = t;
        buf[0] = x;
        buf[1] = y;
        buf[2] = z;
        return 3;
    }
    for (uint32_t i = 0; i < n; i++) {
        uint32_t p = r->pid[m->corner[s + i]], j = i;
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
    uint64_t *pair;             /* first face << 32 | its copy */
    uint32_t  n, cap;
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

/* Each face of object i on the points of an earlier one, with the first
 * face of its set. */
static int find_twins(const Rep *r, uint32_t i, Twins *tw, uint32_t *a, uint32_t *b)
{
    const MeshObject *o = &r->w.objs[i];
    size_t size = 64;
    while (size < 2 * (size_t)o->face_count + 2)
        size *= 2;
    uint32_t *slot = malloc(2 * size * sizeof *slot);     /* face, hash */
    if (!slot)
        return -1;
    for (size_t h = 0; h < size; h++)
        slot[2 * h] = RP_NONE;
    int rc = 0;
    for (uint32_t f = o->face_first; rc == 0 && f < o->face_first + o->face_count; f++) {
        uint32_t n = sorted_points(r, f, a), key = list_hash(a, n);
        /* invariant: the table is at most half full, so a probe ends */
        for (size_t h = key & (size - 1);; h = (h + 1) & (size - 1)) {
            if (slot[2 * h] == RP_NONE) {
                slot[2 * h] = f;
                slot[2 * h + 1] = key;
                break;
            }
            if (slot[2 * h + 1] == key && sorted_points(r, slot[2 * h], b) == n && !memcmp(a, b, n * sizeof *a)) {
                rc = twin_add(tw, slot[2 * h], f);
                break;
            }
        }
    }
    free(slot);
    return rc;
}

/* ==== The faces on each of their edges ==== */

typedef struct {
    uint64_t *key;              /* smaller point << 32 | larger, UINT64_MAX empty */
    uint32_t *count;            /* faces on it (half-edges) */
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

static uint64_t edge_of(const Rep *r, uint32_t va, uint32_t vb)
{
    uint32_t p = r->pid[va], q = r->pid[vb];
    return p < q ? (uint64_t)p << 32 | q : (uint64_t)q << 32 | p;
}

/* Call fn on each edge of face f (two different points in a row). */
#define FOR_EDGES(r, f, k, body)                                                          \
    do {                                                                                  \
        const Mesh *m_ = &(r)->w;                                                         \
        uint32_t s_ = m_->face_start[f], e_ = m_->face_start[(f) + 1];                    \
        for (uint32_t c_ = s_; c_ < e_; c_++) {                                           \
            uint32_t a_ = m_->corner[c_], b_ = m_->corner[c_ + 1 < e_ ? c_ + 1 : s_];     \
            if ((r)->pid[a_] == (r)->pid[b_])                                             \
                continue;                                                                 \
            uint64_t k = edge_of(r, a_, b_);                                              \
            body;                                                                         \
        }                                                                                 \
    } while (0)

/* The counts of every edge of the sets' faces, over the object's faces. */
static int counts_build(const Rep *r, const MeshObject *o, const Twins *tw, Counts *ct)
{
    size_t edges = 0;
    for (uint32_t k = 0; k < tw->n; k++)
        for (int j = 0; j < 2; j++) {
            uint32_t f = j ? (uint32_t)tw->pair[k] : (uint32_t)(tw->pair[k] >> 32);
            edges += r->w.face_start[f + 1] - r->w.face_start[f];
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
            FOR_EDGES(r, f, k, ct->key[count_slot(ct, k)] = k);
        }
    for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++)
        FOR_EDGES(r, f, k, {
            size_t h = count_slot(ct, k);
            if (ct->key[h] == k)
                ct->count[h]++;
        });
    return 0;
}

/* Take the faces list[0..n) off the counts; undo: put them back. 1 when
 * an edge that had two faces or more is left with one. */
static int take(const Rep *r, Counts *ct, const uint32_t *list, uint32_t n, int undo)
{
    int opens = 0;
    for (uint32_t i = 0; i < n; i++)
        FOR_EDGES(r, list[i], k, {
            size_t h = count_slot(ct, k);
            ct->count[h] += undo ? 1u : (uint32_t)-1;
        });
    for (uint32_t i = 0; i < n && !undo; i++)
        FOR_EDGES(r, list[i], k, {
            /* one face left now where the faces taken made it more */
            if (ct->count[count_slot(ct, k)] == 1)
                opens = 1;
        });
    return opens;
}

/* ==== Deciding ==== */

/* One set: first, then its copies; dup[] marks what goes. */
static void decide(Rep *r, Counts *ct, uint32_t *set, uint32_t n, uint32_t *faces_left, uint8_t *dup)
{
    if (!take(r, ct, set + 1, n - 1, 0)) {
        for (uint32_t i = 1; i < n; i++)
            dup[set[i]] = 1;
        r->rep->duplicate += n - 1;
        *faces_left -= n - 1;
        return;
    }
    /* the first face too: a flap goes whole, if something stays */
    if (*faces_left > n && !take(r, ct, set, 1, 0)) {
        for (uint32_t i = 0; i < n; i++)
            dup[set[i]] = 1;
        r->rep->duplicate += n - 1;
        r->rep->flaps++;
        *faces_left -= n;
        return;
    }
    if (*faces_left > n)
        take(r, ct, set, 1, 1);
    take(r, ct, set + 1, n - 1, 1);
    r->rep->dup_kept += n - 1;
}

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

static int object_twins(Rep *r, uint32_t i, uint8_t *dup, uint32_t *a, uint32_t *b)
{
    Twins tw = { 0 };
    Counts ct = { 0 };
    uint32_t *set = NULL;
    int rc = find_twins(r, i, &tw, a, b);
    if (rc || !tw.n)
        goto out;
    rc = -1;
    if (counts_build(r, &r->w.objs[i], &tw, &ct) || !(set = malloc(((size_t)tw.n + 1) * sizeof *set)))
        goto out;
    qsort(tw.pair, tw.n, sizeof *tw.pair, cmp_u64);
    uint32_t left = r->w.objs[i].face_count;
    for (uint32_t k = 0; k < tw.n;) {
        uint32_t first = (uint32_t)(tw.pair[k] >> 32), n = 1;
        set[0] = first;
        for (; k < tw.n && (uint32_t)(tw.pair[k] >> 32) == first; k++)
            set[n++] = (uint32_t)tw.pair[k];
        decide(r, &ct, set, n, &left, dup);
    }
    rc = 0;
out:
    free(tw.pair);
    free(ct.key);
    free(ct.count);
    free(set);
    return rc;
}

int rp_duplicates(Rep *r, uint8_t *dup)
{
    Mesh *m = &r->w;
    uint32_t maxn = 0;
    for (uint32_t f = 0; f < m->nfaces; f++)
        if (m->face_start[f + 1] - m->face_start[f] > maxn)
            maxn = m->face_start[f + 1] - m->face_start[f];
    uint32_t *a = malloc(((size_t)maxn + 1) * sizeof *a), *b = malloc(((size_t)maxn + 1) * sizeof *b);
    int rc = a && b ? 0 : -1;
    for (uint32_t i = 0; rc == 0 && i < m->nobjs; i++)
        if (r->level[i] < RP_LEVEL_UNTOUCHED)
            rc = object_twins(r, i, dup, a, b);
    free(a);
    free(b);
    return rc;
}
