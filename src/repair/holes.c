/* holes.c: the holes of one object filled, loop by loop.
 *
 * Each loop (loops.c) is given the methods of fill.c in turn: Liepa's
 * dynamic program up to RP_DP_MAX edges, ear clipping on its plane up
 * to RP_EAR_MAX, then a fan from a new centre. Every method's fill is
 * checked (fillcheck.c: the check's crossing test on the fills and the
 * faces near them), all the object's loops in one round; a fill that
 * crosses the model, another fill, or makes a face the check would call
 * duplicate or non-manifold is dropped and its loop goes on to the next
 * method in the next round. A loop no method fills, one longer than
 * RepairOpts.max_hole, the rim of a lone face (its fill would be the
 * face again) and the stray boundary (the rim of a non-orientable part)
 * stay open, each listed with why. */

#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

int rp_hole_open(Rep *r, uint32_t obj, uint32_t edges, uint32_t vertex, RepairOpenWhy why)
{
    RepairReport *rep = r->rep;
    rep->open++;
    rep->open_largest = edges > rep->open_largest ? edges : rep->open_largest;
    rep->open_too_big += why == REPAIR_OPEN_TOO_BIG;
    if (rep->nholes >= REPAIR_HOLES_MAX)
        return 0;
    if (!rep->holes && !(rep->holes = malloc(REPAIR_HOLES_MAX * sizeof *rep->holes)))
        return -1;
    rep->holes[rep->nholes++] = (RepairHole){ .object = obj, .edges = edges, .vertex = vertex, .why = why };
    return 0;
}

/* Is loop k the rim of one face alone (every edge of it that face's,
 * and the face no more)? */
static int lone_face(const Rep *r, const Loops *l, uint32_t k)
{
    uint32_t s = l->start[k], n = l->start[k + 1] - s, f = l->face[s];
    for (uint32_t i = 1; i < n; i++)
        if (l->face[s + i] != f)
            return 0;
    return r->w.face_start[f + 1] - r->w.face_start[f] == n;
}

static FillMethod first_method(uint32_t n)
{
    return n <= RP_DP_MAX ? FILL_DP : n <= RP_EAR_MAX ? FILL_EAR : FILL_FAN;
}

typedef struct {
    Fill     *fill;             /* the fills taken first, then the candidates */
    uint32_t  ntaken;
    uint32_t *cand;             /* the loops with a candidate */
    uint32_t  ncand;
    FillMethod *method;         /* per loop */
    uint8_t  *bad;
} Rounds;

/* A candidate for every loop still open from its current method on;
 * the loops no method fills are listed open. */
static int candidates(Rep *r, ObjTopo *t, const Loops *l, const EdgeSet *es, uint64_t *budget, Rounds *rd)
{
    uint32_t kept = 0;
    for (uint32_t i = 0; i < rd->ncand; i++) {
        uint32_t k = rd->cand[i];
        Fill *f = &rd->fill[rd->ntaken + kept];
        memset(f, 0, sizeof *f);
        while (rd->method[k] != FILL_NONE) {
            if (rp_fill_make(r, t, l, k, rd->method[k], es, budget, f))
                return -1;
            if (f->ntri)
                break;
            rd->method[k]++;
        }
        if (f->ntri) {
            rd->cand[kept++] = k;
        } else if (rp_hole_open(r, t->obj, l->start[k + 1] - l->start[k], l->vert[l->start[k]],
                                REPAIR_OPEN_CROSSING)) {
            return -1;
        }
    }
    rd->ncand = kept;
    return 0;
}

/* Keep the candidates the check passed (after the fills taken); the rest
 * go on to their next method. */
static void settle(Rep *r, Rounds *rd)
{
    uint32_t left = 0, base = rd->ntaken;
    for (uint32_t i = 0; i < rd->ncand; i++) {
        Fill f = rd->fill[base + i];
        uint32_t k = rd->cand[i];
        if (!rd->bad[i]) {
            rd->fill[rd->ntaken++] = f;     /* ntaken <= base + i: nothing unread is overwritten */
            r->rep->filled++;
            r->rep->fill_faces += f.ntri;
            if (rd->method[k] == FILL_FAN) {
                r->rep->fans++;
                r->rep->fill_vertices++;
            }
            continue;
        }
        free(f.tri);
        rd->method[k]++;
        rd->cand[left++] = k;
    }
    rd->ncand = left;
}

int rp_holes(Rep *r, ObjTopo *t, Fill **out, uint32_t *out_n, uint64_t *budget)
{
    Loops l;
    *out = NULL;
    *out_n = 0;
    if (rp_loops_find(r, t, &l))
        return -1;
    int rc = -1;
    Rounds rd = { 0 };
    EdgeSet *es = NULL;
    for (uint32_t g = 0; g < l.nstray; g++)
        if (rp_hole_open(r, t->obj, l.stray_edges[g], l.stray_vertex[g], REPAIR_OPEN_UNORIENTED))
            goto out;
    if (!l.nloops) {
        rc = 0;
        goto out;
    }
    rd.fill = calloc(l.nloops, sizeof *rd.fill);
    rd.cand = malloc(l.nloops * sizeof *rd.cand);
    rd.method = malloc(l.nloops * sizeof *rd.method);
    rd.bad = malloc(l.nloops);
    es = rp_edges_new(t, r);
    if (!rd.fill || !rd.cand || !rd.method || !rd.bad || !es)
        goto out;
    for (uint32_t k = 0; k < l.nloops; k++) {
        uint32_t n = l.start[k + 1] - l.start[k];
        rd.method[k] = first_method(n);
        if (r->opt->max_hole && n > r->opt->max_hole) {
            if (rp_hole_open(r, t->obj, n, l.vert[l.start[k]], REPAIR_OPEN_TOO_BIG))
                goto out;
        } else if (lone_face(r, &l, k)) {
            if (rp_hole_open(r, t->obj, n, l.vert[l.start[k]], REPAIR_OPEN_LONE_FACE))
                goto out;
        } else {
            rd.cand[rd.ncand++] = k;
        }
    }
    while (rd.ncand) {
        if (candidates(r, t, &l, es, budget, &rd))
            goto out;
        if (!rd.ncand)
            break;
        if (rp_fills_cross(r, t, rd.fill, rd.ntaken, rd.ntaken + rd.ncand, rd.bad)) {
            for (uint32_t i = 0; i < rd.ncand; i++)
                free(rd.fill[rd.ntaken + i].tri);
            goto out;
        }
        settle(r, &rd);
    }
    *out = rd.fill;
    *out_n = rd.ntaken;
    rd.fill = NULL;
    rc = 0;
out:
    if (rd.fill)
        for (uint32_t i = 0; i < rd.ntaken; i++)
            free(rd.fill[i].tri);
    free(rd.fill);
    free(rd.cand);
    free(rd.method);
    free(rd.bad);
    rp_edges_free(es);
    rp_loops_free(&l);
    return rc;
}
