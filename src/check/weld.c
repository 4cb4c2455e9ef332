/* weld.c: vertices at the same position become one point, and the
 * small helpers the passes share (lists, union-find).
 *
 * Topology is taken on positions, as slicers take it: a format that
 * splits a vertex along a texture or normal seam (glTF, PLY from some
 * exporters) would otherwise show a hole along every seam. Equal means
 * equal coordinates (-0 = +0; loaders refuse NaN), found through a hash
 * table with linear probing over the vertex indices. */

#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "check_internal.h"

/* ==== Shared helpers ==== */

int check_push(uint32_t **a, size_t *n, size_t *cap, uint32_t v)
{
    if (*n == *cap) {
        size_t c = *cap ? *cap * 2 : 64;
        uint32_t *q = realloc(*a, c * sizeof *q);
        if (!q)
            return -1;
        *a = q;
        *cap = c;
    }
    (*a)[(*n)++] = v;
    return 0;
}

void *check_big(size_t bytes, int zero)
{
    void *p = zero ? calloc(bytes ? bytes : 1, 1) : malloc(bytes ? bytes : 1);
    bigmem_advise(p, bytes, 1);
    return p;
}

uint32_t *check_identity(size_t n)
{
    uint32_t *p = check_big((n ? n : 1) * sizeof *p, 0);
    if (p)
        for (size_t i = 0; i < n; i++)
            p[i] = (uint32_t)i;
    return p;
}

/* Path halving: every node on the walk skips to its grandparent, which
 * keeps the trees flat without a second pass. */
uint32_t check_find(uint32_t *p, uint32_t i)
{
    while (p[i] != i) {
        /* parents point to smaller indices (check_union links the larger
         * root under the smaller): the walk ends, and a set's root is
         * its first member, which the labellings in index order read */
        ZV_ASSERT(p[i] < i);
        p[i] = p[p[i]];
        i = p[i];
    }
    return i;
}

/* The smaller root wins: the root of a set is then its first member,
 * which makes labels in index order cheap. */
int check_union(uint32_t *p, uint32_t a, uint32_t b)
{
    a = check_find(p, a);
    b = check_find(p, b);
    if (a == b)
        return 0;
    if (a < b)
        p[b] = a;
    else
        p[a] = b;
    return 1;
}

/* ==== Welding ==== */

/* The coordinate's bits with -0 made +0, so that equal numbers hash and
 * compare alike. */
static inline uint32_t coord_bits(float f)
{
    uint32_t u;
    if (f == 0)
        return 0;
    memcpy(&u, &f, sizeof u);
    return u;
}

static inline uint32_t pos_hash(const uint32_t k[3])
{
    /* multiply-xorshift mixing of the three words (any good mix will do:
     * coordinates of scans differ in their low bits) */
    uint64_t h = k[0] * 0x9E3779B97F4A7C15ull;
    h ^= (h >> 29) ^ (k[1] * 0xC2B2AE3D27D4EB4Full);
    h ^= (h >> 31) ^ (k[2] * 0x165667B19E3779F9ull);
    h *= 0xFF51AFD7ED558CCDull;
    return (uint32_t)(h ^ (h >> 32));
}

static inline void pos_key(const Mesh *m, uint32_t v, uint32_t k[3])
{
    for (int i = 0; i < 3; i++)
        k[i] = coord_bits(m->pos[3 * (size_t)v + i]);
}

int check_weld(const Mesh *m, uint32_t *pid, uint32_t *npts_out)
{
    uint32_t nv = m->nverts;
    size_t size = 64;
    while (size < 2 * (size_t)nv)
        size *= 2;
    uint32_t *slot = check_big(size * sizeof *slot, 0);   /* a vertex of each point, CHECK_NONE empty */
    if (!slot)
        return -1;
    memset(slot, 0xff, size * sizeof *slot);
    uint32_t np = 0;
    for (uint32_t v = 0; v < nv; v++) {
        uint32_t k[3], q[3];
        pos_key(m, v, k);
        size_t h = pos_hash(k) & (size - 1);
        /* invariant: the table is at most half full, so a probe ends */
        for (;; h = (h + 1) & (size - 1)) {
            uint32_t w = slot[h];
            if (w == CHECK_NONE) {
                slot[h] = v;
                pid[v] = np++;
                /* at most half full (size >= 2 nverts): an empty slot
                 * always ends the probe */
                ZV_ASSERT(2 * (size_t)np <= size);
                break;
            }
            pos_key(m, w, q);
            if (q[0] == k[0] && q[1] == k[1] && q[2] == k[2]) {
                /* a slot holds an earlier vertex, already numbered: the
                 * points stay numbered in vertex order, below np */
                ZV_ASSERT(w < v && pid[w] < np);
                pid[v] = pid[w];
                break;
            }
        }
    }
    free(slot);
    *npts_out = np;
    return 0;
}
