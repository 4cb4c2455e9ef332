/* loops.c: the boundary of one object as loops to fill.
 *
 * Each boundary half-edge runs from its point to the next; on a surface
 * that agrees and is manifold every boundary point has one boundary
 * half-edge in and one out, and following them gives the loops. Where
 * loops touch at a point (several out), the walk takes any, and a walk
 * that comes back to a point it passed is cut there into a simple cycle
 * (a loop never visits a point twice: its fill could not be manifold).
 * A walk that finds no way on (the rim of a non-orientable part, whose
 * half-edges do not run one way round) leaves its half-edges as the
 * stray boundary: counted, not filled. A loop is given in the order a
 * fill runs it, against the faces on its edges. */

#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

static int loop_point(Loops *l, uint32_t pt, uint32_t face, uint32_t vert)
{
    if (l->npts == l->ptcap) {
        uint32_t c = l->ptcap ? l->ptcap * 2 : 64;
        uint32_t *a = realloc(l->pts, (size_t)c * sizeof *a);
        if (!a)
            return -1;
        l->pts = a;
        uint32_t *b = realloc(l->face, (size_t)c * sizeof *b);
        if (!b)
            return -1;
        l->face = b;
        uint32_t *d = realloc(l->vert, (size_t)c * sizeof *d);
        if (!d)
            return -1;
        l->vert = d;
        l->ptcap = c;
    }
    l->pts[l->npts] = pt;
    l->face[l->npts] = face;
    l->vert[l->npts++] = vert;
    return 0;
}

static int loop_end(Loops *l)
{
    if (l->nloops + 1 >= l->startcap) {
        uint32_t c = l->startcap ? l->startcap * 2 : 64;
        uint32_t *a = realloc(l->start, (size_t)c * sizeof *a);
        if (!a)
            return -1;
        l->start = a;
        l->startcap = c;
    }
    l->start[++l->nloops] = l->npts;
    return 0;
}

typedef struct {
    uint32_t *off, *cur, *he;   /* each point's boundary half-edges out [off[p], off[p+1]); the next unused */
    uint32_t *pos;              /* per point: its place on the walk, RP_NONE */
    uint32_t *path;             /* the walk's half-edges */
    uint32_t  npath;
} Walk;

/* The cycle path[from..npath) (boundary direction) as a loop, in fill
 * order: point i of the loop is the start of half-edge (n - i) mod n,
 * and the edge from loop point i to i + 1 is half-edge n - 1 - i's. */
static int emit(const Rep *r, const ObjTopo *t, Loops *l, Walk *w, uint32_t from)
{
    uint32_t n = w->npath - from, *h = w->path + from;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t a = h[(n - i) % n], e = h[n - 1 - i];
        if (loop_point(l, rp_cpt(r, t, a), t->f0 + rp_cface(t, e), rp_cvert(r, t, a)))
            return -1;
    }
    for (uint32_t i = 0; i < n; i++)
        w->pos[rp_cpt(r, t, h[i])] = RP_NONE;
    w->npath = from;
    return loop_end(l);
}

/* The walk so far goes nowhere: stray boundary. */
static int stray(const Rep *r, const ObjTopo *t, Loops *l, Walk *w)
{
    for (uint32_t i = 0; i < w->npath; i++)
        w->pos[rp_cpt(r, t, w->path[i])] = RP_NONE;
    if (l->nstray == l->straycap) {
        uint32_t c = l->straycap ? l->straycap * 2 : 16;
        uint32_t *a = realloc(l->stray_edges, (size_t)c * sizeof *a);
        if (!a)
            return -1;
        l->stray_edges = a;
        uint32_t *b = realloc(l->stray_vertex, (size_t)c * sizeof *b);
        if (!b)
            return -1;
        l->stray_vertex = b;
        l->straycap = c;
    }
    l->stray_edges[l->nstray] = w->npath;
    l->stray_vertex[l->nstray++] = rp_cvert(r, t, w->path[0]);
    w->npath = 0;
    return 0;
}

static int walk(const Rep *r, const ObjTopo *t, Loops *l, Walk *w)
{
    for (uint32_t s = 0; s < t->npts; s++)
        while (w->cur[s] < w->off[s + 1] || w->npath) {
            /* on from the end of the last half-edge, or a new walk from s */
            uint32_t p = w->npath ? rp_cpt(r, t, rp_next(r, t, w->path[w->npath - 1])) : s;
            if (w->cur[p] == w->off[p + 1]) {
                if (stray(r, t, l, w))
                    return -1;
                continue;
            }
            uint32_t h = w->he[w->cur[p]++], q = rp_cpt(r, t, rp_next(r, t, h));
            w->pos[p] = w->npath;
            w->path[w->npath++] = h;
            /* back at a point of the walk: the cycle from there */
            if (w->pos[q] != RP_NONE && emit(r, t, l, w, w->pos[q]))
                return -1;
        }
    return 0;
}

int rp_loops_find(Rep *r, ObjTopo *t, Loops *l)
{
    memset(l, 0, sizeof *l);
    Walk w = { 0 };
    int rc = -1;
    size_t np = (size_t)t->npts + 2;
    w.off = calloc(np, sizeof *w.off);
    w.cur = malloc(np * sizeof *w.cur);
    w.he = malloc(((size_t)t->nboundary + 1) * sizeof *w.he);
    w.pos = malloc(np * sizeof *w.pos);
    w.path = malloc(((size_t)t->nboundary + 1) * sizeof *w.path);
    l->start = malloc(64 * sizeof *l->start);
    if (!w.off || !w.cur || !w.he || !w.pos || !w.path || !l->start)
        goto out;
    l->startcap = 64;
    l->start[0] = 0;
    memset(w.pos, 0xff, np * sizeof *w.pos);
    for (uint32_t c = 0; c < t->nc; c++)
        if (t->mate[c] == RP_BOUNDARY)
            w.off[rp_cpt(r, t, c) + 1]++;
    for (uint32_t p = 0; p < t->npts; p++)
        w.off[p + 1] += w.off[p];
    memcpy(w.cur, w.off, np * sizeof *w.cur);
    for (uint32_t c = 0; c < t->nc; c++)
        if (t->mate[c] == RP_BOUNDARY)
            w.he[w.cur[rp_cpt(r, t, c)]++] = c;
    memcpy(w.cur, w.off, np * sizeof *w.cur);
    rc = walk(r, t, l, &w);
out:
    free(w.off);
    free(w.cur);
    free(w.he);
    free(w.pos);
    free(w.path);
    return rc;
}

void rp_loops_free(Loops *l)
{
    free(l->pts);
    free(l->start);
    free(l->face);
    free(l->vert);
    free(l->stray_edges);
    free(l->stray_vertex);
    memset(l, 0, sizeof *l);
}
