/* secloops.c: a section of polygons by a plane: the segments where the
 * plane cuts each polygon, chained into loops by their end points, the
 * loops' area and length, and the cap that fills them.
 *
 * A polygon walked in its own order leaves the kept side at an exit
 * point and comes back at an entry point; its segment runs from the
 * entry to the exit. The kept part of the face then runs along the
 * segment the other way, so for a closed, consistently wound surface
 * the segments chain head to tail into loops that turn counter-
 * clockwise seen from the removed side around the solid, and clockwise
 * around a hole: the signed areas sum to the section's area with no
 * nesting test. Every point is section_edge_point of a mesh edge (the
 * kept end first), so the two faces of an edge give the same bits and
 * the chaining matches points exactly, by a hash of their bits. A chain
 * that does not close is an open end of the model: it is counted, and
 * left out of the cap. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "section.h"

typedef struct {
    float a[3], b[3];           /* from the entry to the exit */
} Seg;

typedef struct {
    float p[3];
    double t;                   /* along the section line */
    int   entry;
} Cross;

struct SectionWork {
    Seg      *seg;
    uint32_t  nseg, seg_room;
    uint32_t *table;            /* open addressing: segment + 1 by its start point, 0 empty */
    uint32_t  table_room;
    uint32_t *next;             /* per segment: the one that starts at its end, UINT32_MAX none */
    uint8_t  *state;            /* per segment: bit 0 walked, bit 1 has a predecessor */
    uint32_t  next_room, state_room;
    Cross    *cross;            /* one polygon's crossings (one not convex) */
    uint32_t  cross_room;
    SectionClip clip[2];        /* the cap being clipped by the other planes */
};

void section_work_free(SectionWork **w)
{
    if (!*w)
        return;
    free((*w)->seg);
    free((*w)->table);
    free((*w)->next);
    free((*w)->state);
    free((*w)->cross);
    section_clip_free(&(*w)->clip[0]);
    section_clip_free(&(*w)->clip[1]);
    free(*w);
    *w = NULL;
}

/* ==== the segments ==== */

static int add_seg(SectionWork *w, const float a[3], const float b[3])
{
    /* a face that touches the plane at a corner only (its other corners
     * removed) crosses it at that corner twice: no segment */
    if (memcmp(a, b, 3 * sizeof(float)) == 0)
        return 0;
    if (grow_array((void **)&w->seg, &w->seg_room, w->nseg + 1, sizeof *w->seg))
        return -1;
    Seg *s = &w->seg[w->nseg++];
    memcpy(s->a, a, sizeof s->a);
    memcpy(s->b, b, sizeof s->b);
    return 0;
}

static const float *corner_pos(const SectionPolys *in, uint32_t c)
{
    return in->pos + 3 * (size_t)in->corner[c];
}

/* A polygon with more than one entry: its crossings sorted along the
 * section line (the plane's normal times the face's), paired in turn. */
static int segs_sorted(SectionWork *w, const SectionPolys *in, const SectionPlane *pl, int i, uint32_t c0,
                       uint32_t m)
{
    if (grow_array((void **)&w->cross, &w->cross_room, m, sizeof *w->cross))
        return -1;
    double f[3] = { 0, 0, 0 };
    for (uint32_t k = 0; k < m; k++) {
        const float *p = corner_pos(in, c0 + k), *q = corner_pos(in, c0 + (k + 1) % m);
        f[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
        f[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
        f[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
    }
    double d[3] = { pl->n[1] * f[2] - pl->n[2] * f[1], pl->n[2] * f[0] - pl->n[0] * f[2],
                    pl->n[0] * f[1] - pl->n[1] * f[0] };
    uint32_t nc = 0;
    for (uint32_t k = 0; k < m; k++) {
        uint32_t u = in->corner[c0 + k], v = in->corner[c0 + (k + 1) % m];
        int ru = in->mask[u] >> i & 1, rv = in->mask[v] >> i & 1;
        if (ru == rv)
            continue;
        Cross *x = &w->cross[nc++];
        section_edge_point(pl, in->pos + 3 * (size_t)(ru ? v : u), in->pos + 3 * (size_t)(ru ? u : v), x->p);
        x->t = x->p[0] * d[0] + x->p[1] * d[1] + x->p[2] * d[2];
        x->entry = ru;
    }
    for (uint32_t k = 1; k < nc; k++)       /* insertion: a few crossings */
        for (uint32_t j = k; j > 0 && w->cross[j - 1].t > w->cross[j].t; j--) {
            Cross t = w->cross[j];
            w->cross[j] = w->cross[j - 1];
            w->cross[j - 1] = t;
        }
    for (uint32_t k = 0; k + 1 < nc; k += 2) {
        const Cross *x = &w->cross[k], *y = &w->cross[k + 1];
        if (add_seg(w, x->entry || !y->entry ? x->p : y->p, x->entry || !y->entry ? y->p : x->p))
            return -1;
    }
    return 0;
}

/* The segments of the polygons crossed by plane i. */
static int make_segs(SectionWork *w, const SectionPolys *in, const SectionPlane *pl, int i)
{
    w->nseg = 0;
    for (uint32_t k = in->first; k < in->first + in->count; k++) {
        uint32_t c0 = in->start ? in->start[k] : 3 * k, c1 = in->start ? in->start[k + 1] : 3 * k + 3;
        uint32_t m = c1 - c0, entries = 0, exits = 0, ent = 0, ex = 0;
        for (uint32_t j = 0; j < m; j++) {
            int ru = in->mask[in->corner[c0 + j]] >> i & 1, rv = in->mask[in->corner[c0 + (j + 1) % m]] >> i & 1;
            if (ru && !rv)
                entries++, ent = j;
            else if (!ru && rv)
                exits++, ex = j;
        }
        if (!entries)
            continue;
        if (entries > 1) {
            if (segs_sorted(w, in, pl, i, c0, m))
                return -1;
            continue;
        }
        float a[3], b[3];
        /* entry: corner ent removed, ent + 1 kept; exit: ex kept, ex + 1 removed */
        section_edge_point(pl, corner_pos(in, c0 + (ent + 1) % m), corner_pos(in, c0 + ent), a);
        section_edge_point(pl, corner_pos(in, c0 + ex), corner_pos(in, c0 + (ex + 1) % m), b);
        if (add_seg(w, a, b))
            return -1;
    }
    return 0;
}

/* ==== chaining ==== */

static uint32_t point_hash(const float p[3])
{
    uint32_t b[3];
    memcpy(b, p, sizeof b);
    uint32_t h = b[0] * 0x9e3779b1u ^ (b[1] + 0x7f4a7c15u) * 0x85ebca77u ^ (b[2] + 0x165667b1u) * 0xc2b2ae3du;
    return h ^ h >> 15;
}

static int same_point(const float a[3], const float b[3])
{
    return memcmp(a, b, 3 * sizeof(float)) == 0;
}

/* The segment (not yet taken as a successor) that starts at p, or
 * UINT32_MAX. */
static uint32_t find_start(const SectionWork *w, const float p[3], uint32_t mask)
{
    for (uint32_t h = point_hash(p) & mask;; h = (h + 1) & mask) {
        uint32_t s = w->table[h];
        if (!s)
            return UINT32_MAX;
        if (same_point(w->seg[s - 1].a, p) && !(w->state[s - 1] & 2))
            return s - 1;
    }
}

/* next[] and the predecessor bits: each segment's successor is a
 * segment starting where it ends that no other segment took. */
static int link_segs(SectionWork *w)
{
    uint32_t size = 16;
    while (size < 2 * w->nseg)
        size *= 2;
    if (grow_array((void **)&w->table, &w->table_room, size, sizeof *w->table) ||
        grow_array((void **)&w->next, &w->next_room, w->nseg, sizeof *w->next) ||
        grow_array((void **)&w->state, &w->state_room, w->nseg, 1))
        return -1;
    memset(w->table, 0, size * sizeof *w->table);
    if (w->nseg)
        memset(w->state, 0, w->nseg);     /* (no segments: state may be unmade) */
    uint32_t mask = size - 1;
    for (uint32_t s = 0; s < w->nseg; s++) {
        uint32_t h = point_hash(w->seg[s].a) & mask;
        while (w->table[h])
            h = (h + 1) & mask;
        w->table[h] = s + 1;
    }
    for (uint32_t s = 0; s < w->nseg; s++) {
        uint32_t t = find_start(w, w->seg[s].b, mask);
        w->next[s] = t;
        if (t != UINT32_MAX)
            w->state[t] |= 2;
    }
    return 0;
}

/* Twice the signed area of the loop's projection along the plane's
 * unit normal u, from its first point. */
static double twice_area(const float *p, uint32_t n, const double u[3])
{
    double c[3] = { 0, 0, 0 };
    for (uint32_t k = 1; k + 1 < n; k++) {
        double a[3], b[3];
        for (int j = 0; j < 3; j++) {
            a[j] = (double)p[3 * k + j] - p[j];
            b[j] = (double)p[3 * (k + 1) + j] - p[j];
        }
        c[0] += a[1] * b[2] - a[2] * b[1];
        c[1] += a[2] * b[0] - a[0] * b[2];
        c[2] += a[0] * b[1] - a[1] * b[0];
    }
    return c[0] * u[0] + c[1] * u[1] + c[2] * u[2];
}

static int cap_push(SectionClip *c, const float p[3])
{
    if (grow_array((void **)&c->pts, &c->room, c->npts + 1, 3 * sizeof(float)))
        return -1;
    memcpy(c->pts + 3 * (size_t)c->npts++, p, 3 * sizeof(float));
    return 0;
}

/* Walk the chain from segment s: its points appended to out from
 * point `from`; returns whether it closed, -1 out of memory. */
static int walk(SectionWork *w, uint32_t s, SectionClip *out, double *length)
{
    uint32_t first = s;
    if (cap_push(out, w->seg[s].a))
        return -1;
    for (;;) {
        w->state[s] |= 1;
        const Seg *g = &w->seg[s];
        double d2 = 0;
        for (int j = 0; j < 3; j++)
            d2 += ((double)g->b[j] - g->a[j]) * ((double)g->b[j] - g->a[j]);
        *length += sqrt(d2);
        uint32_t t = w->next[s];
        if (t == first)
            return 1;
        if (t == UINT32_MAX || (w->state[t] & 1)) {
            if (cap_push(out, g->b))
                return -1;
            return 0;
        }
        if (cap_push(out, g->b))
            return -1;
        s = t;
    }
}

/* ==== the cap ==== */

/* The outline c clipped to the removed side of plane j (Sutherland and
 * Hodgman), into d. */
static int clip_removed(const SectionPlane *pl, const SectionClip *c, SectionClip *d)
{
    d->npts = 0;
    for (uint32_t k = 0; k < c->npts; k++) {
        const float *u = c->pts + 3 * (size_t)k, *v = c->pts + 3 * (size_t)((k + 1) % c->npts);
        int iu = section_side(pl, u) > 0, iv = section_side(pl, v) > 0;
        if (iu && cap_push(d, u))
            return -1;
        if (iu != iv) {
            float x[3];
            section_edge_point(pl, iu ? v : u, iu ? u : v, x);
            if (cap_push(d, x))
                return -1;
        }
    }
    return 0;
}

int section_loops(const SectionPolys *in, const SectionPlane *planes, int np, int i, SectionWork **wp,
                  SectionFigures *fig, SectionClip *cap)
{
    memset(fig, 0, sizeof *fig);
    if (cap)
        cap->npts = 0;
    if (!*wp && !(*wp = calloc(1, sizeof **wp)))
        return -1;
    SectionWork *w = *wp;
    const SectionPlane *pl = &planes[i];
    if (make_segs(w, in, pl, i) || link_segs(w))
        return -1;
    double len = sqrt(pl->n[0] * pl->n[0] + pl->n[1] * pl->n[1] + pl->n[2] * pl->n[2]);
    double u[3] = { pl->n[0] / len, pl->n[1] / len, pl->n[2] / len };
    SectionClip *chain = &w->clip[0];
    /* open chains first, from their starts; then what is left is loops */
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t s = 0; s < w->nseg; s++) {
            if ((w->state[s] & 1) || (pass == 0 && (w->state[s] & 2)))
                continue;
            chain->npts = 0;
            int closed = walk(w, s, chain, &fig->perimeter);
            if (closed < 0)
                return -1;
            if (!closed) {
                if (fig->nends < SECTION_ENDS) {
                    memcpy(fig->ends[fig->nends][0], chain->pts, 3 * sizeof(float));
                    memcpy(fig->ends[fig->nends++][1], chain->pts + 3 * (size_t)(chain->npts - 1), 3 * sizeof(float));
                }
                fig->chains++;
                continue;
            }
            fig->loops++;
            fig->area += 0.5 * twice_area(chain->pts, chain->npts, u);
            if (!cap)
                continue;
            /* joined to the first loop by a bridge there and back */
            float first[3];
            if (cap->npts) {
                memcpy(first, cap->pts, sizeof first);
                if (cap_push(cap, first))
                    return -1;
            }
            for (uint32_t k = 0; k < chain->npts; k++)
                if (cap_push(cap, chain->pts + 3 * (size_t)k))
                    return -1;
            if (cap_push(cap, chain->pts))
                return -1;
        }
    if (!cap)
        return 0;
    for (int j = 0; j < np; j++) {
        if (j == i || cap->npts < 3)
            continue;
        SectionClip *d = &w->clip[1];
        if (clip_removed(&planes[j], cap, d))
            return -1;
        cap->npts = 0;
        for (uint32_t k = 0; k < d->npts; k++)
            if (cap_push(cap, d->pts + 3 * (size_t)k))
                return -1;
    }
    return 0;
}
