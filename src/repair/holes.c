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
    Cuts     *cuts;
    uint32_t *loop_cut;         /* per loop: a cut it runs along, RP_NONE */
    Fill     *fill;             /* the fills taken first, then the candidates */
    uint32_t  ntaken;
    uint32_t *cand;             /* the loops with a candidate */
    uint32_t  ncand;
    FillMethod *method;         /* per loop */
    uint8_t  *bad;
} Rounds;

/* Loop k is left open: listed now, or when it runs along a cut, only if
 * the cut stays (fins.c puts back the cuts no fill closed). */
static int loop_open(Rep *r, const ObjTopo *t, const Loops *l, Rounds *rd, uint32_t k, RepairOpenWhy why)
{
    RepairHole h = { .object = t->obj, .edges = l->start[k + 1] - l->start[k], .vertex = l->vert[l->start[k]],
                     .why = why };
    uint32_t cut = rd->loop_cut ? rd->loop_cut[k] : RP_NONE;
    if (cut == RP_NONE)
        return rp_hole_open(r, h.object, h.edges, h.vertex, why);
    Cuts *cu = rd->cuts;
    if (cu->npend == cu->pendcap) {
        uint32_t c = cu->pendcap ? cu->pendcap * 2 : 16;
        RepairHole *p = realloc(cu->pend, c * sizeof *p);
        if (!p)
            return -1;
        cu->pend = p;
        uint32_t *q = realloc(cu->pend_cut, c * sizeof *q);
        if (!q)
            return -1;
        cu->pend_cut = q;
        cu->pendcap = c;
    }
    cu->pend[cu->npend] = h;
    cu->pend_cut[cu->npend++] = cut;
    return 0;
}

/* Which loops run along a cut (an edge of theirs is a cut's). */
static int loops_on_cuts(const Loops *l, Rounds *rd)
{
    const Cuts *cu = rd->cuts;
    if (!cu || !cu->n)
        return 0;
    if (!(rd->loop_cut = malloc(l->nloops * sizeof *rd->loop_cut)))
        return -1;
    for (uint32_t k = 0; k < l->nloops; k++) {
        rd->loop_cut[k] = RP_NONE;
        uint32_t s = l->start[k], n = l->start[k + 1] - s;
        for (uint32_t i = 0; i < n && rd->loop_cut[k] == RP_NONE; i++) {
            uint32_t a = l->vert[s + i], b = l->vert[s + (i + 1) % n];
            /* few cuts: a fin of an odd number is rare */
            for (uint32_t c = 0; c < cu->n; c++)
                if ((cu->v[2 * c] == a && cu->v[2 * c + 1] == b) || (cu->v[2 * c] == b && cu->v[2 * c + 1] == a)) {
                    rd->loop_cut[k] = c;
                    break;
                }
        }
    }
    return 0;
}

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
        if (f->ntri)
            rd->cand[kept++] = k;
        else if (loop_open(r, t, l, rd, k, REPAIR_OPEN_CROSSING))
            return -1;
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

int rp_holes(Rep *r, ObjTopo *t, Cuts *cuts, Fill **out, uint32_t *out_n, uint64_t *budget)
{
    Loops l;
    *out = NULL;
    *out_n = 0;
    if (rp_loops_find(r, t, &l))
        return -1;
    int rc = -1;
    Rounds rd = { .cuts = cuts };
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
    if (!rd.fill || !rd.cand || !rd.method || !rd.bad || !es || loops_on_cuts(&l, &rd))
        goto out;
    for (uint32_t k = 0; k < l.nloops; k++) {
        uint32_t n = l.start[k + 1] - l.start[k];
        rd.method[k] = first_method(n);
        if (r->opt->max_hole && n > r->opt->max_hole) {
            if (loop_open(r, t, &l, &rd, k, REPAIR_OPEN_TOO_BIG))
                goto out;
        } else if (lone_face(r, &l, k)) {
            if (loop_open(r, t, &l, &rd, k, REPAIR_OPEN_LONE_FACE))
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
    free(rd.loop_cut);
    rp_edges_free(es);
    rp_loops_free(&l);
    return rc;
}
