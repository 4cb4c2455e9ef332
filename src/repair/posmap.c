/* posmap.c: points, the positions the topology is taken on. Vertices at
 * one position (bit for bit, -0 = +0, as the check takes them) are one
 * point, numbered in vertex order, found through a hash table with
 * linear probing over vertex indices; new vertices (the copies a split
 * makes, the centres of fans) are added to it as they are made, and the
 * table doubles when it is half full. The table goes once the points
 * are numbered, and comes back only when a new vertex needs it (most
 * models need none): its memory is the repair's peak's. */

#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

uint32_t rp_coord_bits(float f)
{
    uint32_t u;
    if (f == 0)
        return 0;
    memcpy(&u, &f, sizeof u);
    return u;
}

static uint32_t pos_hash(const float p[3])
{
    uint64_t h = rp_coord_bits(p[0]) * 0x9E3779B97F4A7C15ull;
    h ^= (h >> 29) ^ (rp_coord_bits(p[1]) * 0xC2B2AE3D27D4EB4Full);
    h ^= (h >> 31) ^ (rp_coord_bits(p[2]) * 0x165667B19E3779F9ull);
    h *= 0xFF51AFD7ED558CCDull;
    return (uint32_t)(h ^ (h >> 32));
}

static int same_pos(const float *a, const float *b)
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/* The slot of position p: the one holding a vertex there, or the empty
 * one where it would go. */
static size_t slot_of(const PosHash *ph, const float *pos, const float p[3])
{
    size_t mask = ph->size - 1, h = pos_hash(p) & mask;
    /* invariant: the table is at most half full, so a probe ends */
    while (ph->slot[h] != RP_NONE && !same_pos(pos + 3 * (size_t)ph->slot[h], p))
        h = (h + 1) & mask;
    return h;
}

static int table_alloc(PosHash *ph, size_t points)
{
    size_t size = 64;
    while (size < 2 * points + 2)
        size *= 2;
    ph->slot = rp_big(size * sizeof *ph->slot, 0);
    if (!ph->slot)
        return -1;
    memset(ph->slot, 0xff, size * sizeof *ph->slot);
    ph->size = size;
    return 0;
}

int rp_points_build(Rep *r)
{
    free(r->ph.slot);
    r->ph.slot = NULL;
    if (!r->pid && !(r->pid = rp_big((r->vcap ? r->vcap : 1) * sizeof *r->pid, 0)))
        return -1;
    if (table_alloc(&r->ph, r->w.nverts))
        return -1;
    uint32_t np = 0;
    for (uint32_t v = 0; v < r->w.nverts; v++) {
        const float *p = rp_vpos(r, v);
        size_t h = slot_of(&r->ph, r->w.pos, p);
        if (r->ph.slot[h] == RP_NONE) {
            r->ph.slot[h] = v;
            r->pid[v] = np++;
        } else {
            r->pid[v] = r->pid[r->ph.slot[h]];
        }
    }
    r->npts = np;
    return 0;
}

/* The table again from pid (after rp_points_drop_table): a vertex of
 * each point. */
static int table_again(Rep *r)
{
    if (r->ph.slot)
        return 0;
    if (table_alloc(&r->ph, r->npts))
        return -1;
    for (uint32_t v = 0; v < r->w.nverts; v++) {
        size_t h = slot_of(&r->ph, r->w.pos, rp_vpos(r, v));
        if (r->ph.slot[h] == RP_NONE)
            r->ph.slot[h] = v;
    }
    return 0;
}

uint32_t rp_point_find(Rep *r, const float p[3])
{
    if (table_again(r))
        return RP_NONE - 1;
    size_t h = slot_of(&r->ph, r->w.pos, p);
    return r->ph.slot[h] == RP_NONE ? RP_NONE : r->pid[r->ph.slot[h]];
}

void rp_points_drop_table(Rep *r)
{
    free(r->ph.slot);
    r->ph.slot = NULL;
}

/* Twice the room, every point again. */
static int table_grow(Rep *r)
{
    PosHash old = r->ph;
    if (table_alloc(&r->ph, old.size / 2 + 1))
        return (r->ph = old), -1;
    for (size_t i = 0; i < old.size; i++)
        if (old.slot[i] != RP_NONE)
            r->ph.slot[slot_of(&r->ph, r->w.pos, rp_vpos(r, old.slot[i]))] = old.slot[i];
    free(old.slot);
    return 0;
}

int rp_pos_own(Rep *r)
{
    r->pos_changed = 1;
    if (!r->pos_borrowed)
        return 0;
    size_t n = 3 * (r->vcap > r->w.nverts ? r->vcap : r->w.nverts);
    float *pos = malloc((n ? n : 1) * sizeof *pos), *rgb = r->w.rgb ? malloc((n ? n : 1) * sizeof *rgb) : NULL;
    if (!pos || (r->w.rgb && !rgb)) {
        free(pos);
        free(rgb);
        return -1;
    }
    memcpy(pos, r->w.pos, 3 * (size_t)r->w.nverts * sizeof *pos);
    if (rgb)
        memcpy(rgb, r->w.rgb, 3 * (size_t)r->w.nverts * sizeof *rgb);
    r->w.pos = pos;
    r->w.rgb = rgb;
    r->pos_borrowed = 0;
    return 0;
}

/* Room for one more vertex in every per-vertex array. */
static int vertex_room(Rep *r)
{
    if (rp_pos_own(r))
        return -1;
    if (r->w.nverts < r->vcap)
        return 0;
    if (r->vcap >= UINT32_MAX - 2)
        return -1;
    size_t cap = r->vcap + r->vcap / 2 + 64;
    if (cap > UINT32_MAX - 2)
        cap = UINT32_MAX - 2;
    float *pos = realloc(r->w.pos, cap * 3 * sizeof *pos);
    if (!pos)
        return -1;
    r->w.pos = pos;
    if (r->w.rgb) {
        float *rgb = realloc(r->w.rgb, cap * 3 * sizeof *rgb);
        if (!rgb)
            return -1;
        r->w.rgb = rgb;
    }
    uint32_t *pid = realloc(r->pid, cap * sizeof *pid), *anchor;
    if (!pid)
        return -1;
    r->pid = pid;
    anchor = realloc(r->anchor, cap * sizeof *anchor);
    if (!anchor)
        return -1;
    r->anchor = anchor;
    r->vcap = cap;
    return 0;
}

uint32_t rp_vertex_add(Rep *r, const float p[3], const float *rgb, uint32_t anchor)
{
    if (table_again(r) || vertex_room(r) || (2 * ((size_t)r->npts + 1) + 2 > r->ph.size && table_grow(r)))
        return RP_NONE;
    uint32_t v = r->w.nverts;
    memcpy(r->w.pos + 3 * (size_t)v, p, 3 * sizeof *p);
    if (r->w.rgb) {
        static const float white[3] = { 1, 1, 1 };
        memcpy(r->w.rgb + 3 * (size_t)v, rgb ? rgb : white, 3 * sizeof *rgb);
    }
    size_t h = slot_of(&r->ph, r->w.pos, p);
    if (r->ph.slot[h] == RP_NONE) {
        r->ph.slot[h] = v;
        r->pid[v] = r->npts++;
    } else {
        /* the copies of a fan's vertices (a colour seam) share its new point */
        r->pid[v] = r->pid[r->ph.slot[h]];
    }
    r->anchor[v] = anchor;
    r->w.nverts++;
    return v;
}

void rp_points_free(Rep *r)
{
    free(r->ph.slot);
    r->ph.slot = NULL;
}
