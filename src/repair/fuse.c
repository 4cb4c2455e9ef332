/* fuse.c: the weld. Vertices at one position become one vertex, object
 * by object: the corners of each object's faces are moved to the first
 * vertex (the smallest index) at their point that the object's faces
 * use, so that an object keeps to its own vertices (through an array
 * per point, or a hash table when colours must agree too). Two vertices at one
 * position whose colours differ stay two (a colour seam is kept; the
 * check takes them as one point all the same). Texture coordinates are
 * the corners' own by now (repair.c), so a seam of them is kept too.
 *
 * With a distance (RepairOpts.weld_eps), positions within it are made
 * one first: vertices in index order, each moved onto the nearest
 * earlier vertex it is within eps of that stayed where it was (a
 * grid of cells eps wide, the 27 around a vertex searched), so that the
 * vertices that stay are more than eps apart and a chain of close
 * vertices does not drift. Only vertices that faces use move. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

/* ==== Within a distance ==== */

typedef struct {
    int64_t   *key;             /* 3 per slot: the cell */
    uint32_t  *head;            /* the first vertex kept in the cell, RP_NONE: empty slot */
    uint32_t  *next;            /* per vertex: the next kept in its cell */
    size_t     size;
} Grid;

static int64_t cell_of(double x, double eps)
{
    double q = floor(x / eps);
    const double lim = 4.0e18;
    return q > lim ? (int64_t)lim : q < -lim ? -(int64_t)lim : (int64_t)q;
}

static size_t cell_hash(const int64_t k[3], size_t mask)
{
    uint64_t h = (uint64_t)k[0] * 0x9E3779B97F4A7C15ull;
    h ^= (h >> 29) ^ ((uint64_t)k[1] * 0xC2B2AE3D27D4EB4Full);
    h ^= (h >> 31) ^ ((uint64_t)k[2] * 0x165667B19E3779F9ull);
    h *= 0xFF51AFD7ED558CCDull;
    return (size_t)(h ^ (h >> 32)) & mask;
}

/* The slot of cell k: its own, or the empty one where it would go. */
static size_t grid_slot(const Grid *g, const int64_t k[3])
{
    size_t mask = g->size - 1, h = cell_hash(k, mask);
    /* invariant: at most half full, so a probe ends */
    while (g->head[h] != RP_NONE && memcmp(g->key + 3 * h, k, 3 * sizeof *k))
        h = (h + 1) & mask;
    return h;
}

/* The kept vertex nearest p within eps (RP_NONE: none). */
static uint32_t grid_near(const Grid *g, const Rep *r, const float *p, const int64_t c[3], double eps)
{
    uint32_t best = RP_NONE;
    double bestd = eps * eps;
    for (int dx = -1; dx <= 1; dx++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dz = -1; dz <= 1; dz++) {
                int64_t k[3] = { c[0] + dx, c[1] + dy, c[2] + dz };
                size_t h = grid_slot(g, k);
                for (uint32_t w = g->head[h]; w != RP_NONE; w = g->next[w]) {
                    const float *q = rp_vpos(r, w);
                    double d = 0;
                    for (int i = 0; i < 3; i++)
                        d += ((double)p[i] - q[i]) * ((double)p[i] - q[i]);
                    if (d < bestd || (d == bestd && (best == RP_NONE || w < best))) {
                        bestd = d;
                        best = w;
                    }
                }
            }
    return best;
}

/* Move every face vertex within eps of a kept one onto it; moved[v] set. */
static int snap(Rep *r, uint8_t *moved)
{
    Mesh *m = &r->w;
    double eps = r->opt->weld_eps;
    uint32_t nv = m->nverts;
    uint8_t *used = calloc((size_t)nv + 1, 1);
    Grid g = { .size = 64 };
    while (g.size < 2 * (size_t)nv + 2)
        g.size *= 2;
    g.key = malloc(3 * g.size * sizeof *g.key);
    g.head = malloc(g.size * sizeof *g.head);
    g.next = malloc(((size_t)nv + 1) * sizeof *g.next);
    int rc = -1;
    if (!used || !g.key || !g.head || !g.next)
        goto out;
    memset(g.head, 0xff, g.size * sizeof *g.head);
    for (uint32_t i = 0; i < m->nobjs; i++)
        for (uint32_t c = m->face_start[m->objs[i].face_first];
             r->level[i] < RP_LEVEL_UNTOUCHED && c < m->face_start[m->objs[i].face_first + m->objs[i].face_count]; c++)
            used[m->corner[c]] = 1;
    for (uint32_t v = 0; v < nv; v++) {
        if (!used[v])
            continue;
        const float *p = rp_vpos(r, v);
        int64_t k[3] = { cell_of(p[0], eps), cell_of(p[1], eps), cell_of(p[2], eps) };
        uint32_t w = grid_near(&g, r, p, k, eps);
        if (w != RP_NONE) {
            if (memcmp(p, rp_vpos(r, w), 3 * sizeof *p)) {
                if (rp_pos_own(r))
                    goto out;
                p = rp_vpos(r, v);
                memcpy(r->w.pos + 3 * (size_t)v, rp_vpos(r, w), 3 * sizeof *p);
                moved[v] = 1;
            }
            continue;
        }
        size_t h = grid_slot(&g, k);
        if (g.head[h] == RP_NONE)
            memcpy(g.key + 3 * h, k, sizeof k);
        g.next[v] = g.head[h];
        g.head[h] = v;
    }
    rc = 0;
out:
    free(used);
    free(g.key);
    free(g.head);
    free(g.next);
    return rc;
}

/* ==== One position, one vertex ==== */

/* Vertices a and b the same for the weld: one point, one colour. */
static int same_vertex(const Rep *r, uint32_t a, uint32_t b)
{
    return r->pid[a] == r->pid[b] && (!r->w.rgb || !memcmp(r->w.rgb + 3 * (size_t)a, r->w.rgb + 3 * (size_t)b,
                                                           3 * sizeof *r->w.rgb));
}

static size_t vertex_hash(const Rep *r, uint32_t v, size_t mask)
{
    uint64_t h = (uint64_t)(r->pid[v] + 1) * 0x9E3779B97F4A7C15ull;
    if (r->w.rgb)
        for (int i = 0; i < 3; i++)
            h = (h ^ rp_coord_bits(r->w.rgb[3 * (size_t)v + i])) * 0xFF51AFD7ED558CCDull;
    return (size_t)(h ^ (h >> 29)) & mask;
}

/* The slot of v's kind in the object's table. */
static size_t kind_slot(const Rep *r, const uint32_t *slot, size_t size, uint32_t v)
{
    size_t mask = size - 1, h = vertex_hash(r, v, mask);
    /* invariant: at most half full */
    while (slot[h] != RP_NONE && !same_vertex(r, slot[h], v))
        h = (h + 1) & mask;
    return h;
}

/* The corners of object i moved to the smallest vertex of their kind:
 * through minv (per point, RP_NONE between objects) when the mesh has
 * no colours, else through a table of (point, colour). */
static int weld_object(Rep *r, uint32_t i, uint8_t *moved, uint32_t *minv)
{
    Mesh *m = &r->w;
    const MeshObject *o = &m->objs[i];
    uint32_t c0 = m->face_start[o->face_first], c1 = m->face_start[o->face_first + o->face_count];
    if (minv) {
        for (uint32_t c = c0; c < c1; c++) {
            uint32_t v = m->corner[c], p = r->pid[v];
            minv[p] = v < minv[p] ? v : minv[p];
        }
        for (uint32_t c = c0; c < c1; c++) {
            uint32_t v = m->corner[c], w = minv[r->pid[v]];
            if (w != v) {
                m->corner[c] = w;
                moved[v] = 1;
            }
        }
        for (uint32_t c = c0; c < c1; c++)
            minv[r->pid[m->corner[c]]] = RP_NONE;
        return 0;
    }
    size_t size = 64;
    while (size < 2 * (size_t)(c1 - c0) + 2)
        size *= 2;
    uint32_t *slot = malloc(size * sizeof *slot);
    if (!slot)
        return -1;
    memset(slot, 0xff, size * sizeof *slot);
    for (uint32_t c = c0; c < c1; c++) {
        uint32_t v = m->corner[c];
        size_t h = kind_slot(r, slot, size, v);
        if (slot[h] == RP_NONE || v < slot[h])
            slot[h] = v;
    }
    for (uint32_t c = c0; c < c1; c++) {
        uint32_t v = m->corner[c], w = slot[kind_slot(r, slot, size, v)];
        if (w != v) {
            m->corner[c] = w;
            moved[v] = 1;
        }
    }
    free(slot);
    return 0;
}

int rp_weld(Rep *r)
{
    uint8_t *moved = rp_big((size_t)r->w.nverts + 1, 1);
    if (!moved)
        return -1;
    int rc = 0;
    if (r->opt->weld_eps > 0)
        rc = snap(r, moved) || rp_points_build(r);
    /* every vertex its own point: nothing to weld */
    uint32_t *minv = NULL;
    if (rc == 0 && r->npts < r->w.nverts && !r->w.rgb) {
        if (!(minv = rp_big(((size_t)r->npts + 1) * sizeof *minv, 0)))
            rc = -1;
        else
            memset(minv, 0xff, ((size_t)r->npts + 1) * sizeof *minv);
    }
    for (uint32_t i = 0; rc == 0 && r->npts < r->w.nverts && i < r->w.nobjs; i++)
        if (r->level[i] < RP_LEVEL_UNTOUCHED)
            rc = weld_object(r, i, moved, minv);
    for (uint32_t v = 0; rc == 0 && v < r->w.nverts; v++)
        r->rep->welded += moved[v];
    free(minv);
    free(moved);
    return rc;
}
