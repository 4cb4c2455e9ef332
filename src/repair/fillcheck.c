/* fillcheck.c: does a fill cross the model? Asked of the check itself.
 *
 * The candidate fills of one object, the fills already taken and the
 * object's faces near them (boxes that meet a candidate's box, found
 * through a grid over the candidates' boxes) are put in a small mesh of
 * their own, and meshcheck_run tests it for crossing faces with its
 * exact predicates, the same test --check makes, on the same positions:
 * a candidate is refused when one of its triangles crosses anything
 * (pairs between the object's own faces were there before: they are
 * not the fill's), or when the check finds one of its triangles
 * duplicate, degenerate or on an edge of three faces. A crossing test
 * that stopped on its budget proves nothing: every candidate is then
 * refused. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "meshcheck.h"
#include "repair_internal.h"

typedef struct {
    float lo[3], hi[3];
} Box;

static void box_empty(Box *b)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = INFINITY;
        b->hi[k] = -INFINITY;
    }
}

static void box_add(Box *b, const float *p)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = p[k] < b->lo[k] ? p[k] : b->lo[k];
        b->hi[k] = p[k] > b->hi[k] ? p[k] : b->hi[k];
    }
}

static int box_meet(const Box *a, const Box *b)
{
    for (int k = 0; k < 3; k++)
        if (a->lo[k] > b->hi[k] || b->lo[k] > a->hi[k])
            return 0;
    return 1;
}

/* ==== The grid of the candidates' boxes ==== */

typedef struct {
    Box       all;              /* every candidate's box together */
    int       g;                /* cells a side */
    double    cell[3];
    uint32_t *off, *list;       /* per cell: the candidates whose box meets it */
    uint32_t *big;              /* candidates over too many cells: met against every face */
    uint32_t  nbig;
    const Box *box;
} Grid;

static void cell_range(const Grid *gr, const Box *b, int lo[3], int hi[3])
{
    for (int k = 0; k < 3; k++) {
        double a = gr->cell[k] > 0 ? (b->lo[k] - gr->all.lo[k]) / gr->cell[k] : 0;
        double z = gr->cell[k] > 0 ? (b->hi[k] - gr->all.lo[k]) / gr->cell[k] : 0;
        lo[k] = a < 0 ? 0 : a >= gr->g ? gr->g - 1 : (int)a;
        hi[k] = z < 0 ? 0 : z >= gr->g ? gr->g - 1 : (int)z;
    }
}

static uint64_t range_cells(const int lo[3], const int hi[3])
{
    return (uint64_t)(hi[0] - lo[0] + 1) * (uint64_t)(hi[1] - lo[1] + 1) * (uint64_t)(hi[2] - lo[2] + 1);
}

#define GRID_SPAN_MAX 512u      /* a box over more cells goes to the big list */

static int grid_build(Grid *gr, const Box *box, uint32_t n)
{
    memset(gr, 0, sizeof *gr);
    gr->box = box;
    box_empty(&gr->all);
    for (uint32_t i = 0; i < n; i++) {
        box_add(&gr->all, box[i].lo);
        box_add(&gr->all, box[i].hi);
    }
    gr->g = (int)ceil(cbrt((double)n)) * 2;
    gr->g = gr->g < 1 ? 1 : gr->g > 32 ? 32 : gr->g;
    for (int k = 0; k < 3; k++)
        gr->cell[k] = ((double)gr->all.hi[k] - gr->all.lo[k]) / gr->g;
    size_t ncell = (size_t)gr->g * gr->g * gr->g;
    gr->off = calloc(ncell + 2, sizeof *gr->off);
    gr->big = malloc(((size_t)n + 1) * sizeof *gr->big);
    if (!gr->off || !gr->big)
        return -1;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t i = 0; i < n; i++) {
            int lo[3], hi[3];
            cell_range(gr, &box[i], lo, hi);
            if (range_cells(lo, hi) > GRID_SPAN_MAX) {
                if (pass == 0)
                    gr->big[gr->nbig++] = i;
                continue;
            }
            for (int x = lo[0]; x <= hi[0]; x++)
                for (int y = lo[1]; y <= hi[1]; y++)
                    for (int z = lo[2]; z <= hi[2]; z++) {
                        size_t c = ((size_t)x * gr->g + y) * gr->g + z;
                        if (pass == 0)
                            gr->off[c + 1]++;
                        else
                            gr->list[gr->off[c]++] = i;
                    }
        }
        if (pass == 0) {
            for (size_t c = 0; c < ncell; c++)
                gr->off[c + 1] += gr->off[c];
            if (!(gr->list = malloc(((size_t)gr->off[ncell] + 1) * sizeof *gr->list)))
                return -1;
        } else {
            memmove(gr->off + 1, gr->off, ncell * sizeof *gr->off);
            gr->off[0] = 0;
        }
    }
    return 0;
}

/* Does box b meet a candidate's box? */
static int grid_near(const Grid *gr, const Box *b, uint32_t n)
{
    if (!box_meet(b, &gr->all))
        return 0;
    for (uint32_t i = 0; i < gr->nbig; i++)
        if (box_meet(b, &gr->box[gr->big[i]]))
            return 1;
    int lo[3], hi[3];
    cell_range(gr, b, lo, hi);
    if (range_cells(lo, hi) > GRID_SPAN_MAX) {
        for (uint32_t i = 0; i < n; i++)
            if (box_meet(b, &gr->box[i]))
                return 1;
        return 0;
    }
    for (int x = lo[0]; x <= hi[0]; x++)
        for (int y = lo[1]; y <= hi[1]; y++)
            for (int z = lo[2]; z <= hi[2]; z++) {
                size_t c = ((size_t)x * gr->g + y) * gr->g + z;
                for (uint32_t k = gr->off[c]; k < gr->off[c + 1]; k++)
                    if (box_meet(b, &gr->box[gr->list[k]]))
                        return 1;
            }
    return 0;
}

static void grid_free(Grid *gr)
{
    free(gr->off);
    free(gr->list);
    free(gr->big);
}

/* ==== The small mesh ==== */

typedef struct {
    Mesh      m;
    uint32_t *owner;            /* per face: the candidate it belongs to, RP_NONE: the model's */
    uint32_t  fcap, ccap, vcap;
    uint32_t *vkey, *vval;      /* mesh vertex -> its vertex here (hash), RP_NONE empty */
    size_t    vsize;
} Sub;

static uint32_t sub_vertex(Sub *s, const Rep *r, uint32_t v)
{
    size_t mask = s->vsize - 1, h = (size_t)(v * 0x9E3779B1u) & mask;
    /* invariant: at most half full (sized for every corner) */
    while (s->vkey[h] != RP_NONE && s->vkey[h] != v)
        h = (h + 1) & mask;
    if (s->vkey[h] == RP_NONE) {
        s->vkey[h] = v;
        s->vval[h] = s->m.nverts;
        memcpy(s->m.pos + 3 * (size_t)s->m.nverts++, rp_vpos(r, v), 3 * sizeof(float));
    }
    return s->vval[h];
}

static void sub_face(Sub *s, const Rep *r, const uint32_t *v, uint32_t n, uint32_t owner)
{
    uint32_t c = s->m.face_start[s->m.nfaces];
    for (uint32_t i = 0; i < n; i++)
        s->m.corner[c + i] = sub_vertex(s, r, v[i]);
    s->owner[s->m.nfaces++] = owner;
    s->m.face_start[s->m.nfaces] = c + n;
}

/* Room for what the faces marked near and the fills hold. */
static int sub_alloc(Sub *s, uint32_t faces, uint32_t corners)
{
    s->vsize = 64;
    while (s->vsize < 2 * (size_t)corners + 2)
        s->vsize *= 2;
    s->m.face_start = malloc(((size_t)faces + 1) * sizeof *s->m.face_start);
    s->m.corner = malloc(((size_t)corners + 1) * sizeof *s->m.corner);
    s->m.pos = malloc(3 * ((size_t)corners + 1) * sizeof *s->m.pos);
    s->owner = malloc(((size_t)faces + 1) * sizeof *s->owner);
    s->vkey = malloc(s->vsize * sizeof *s->vkey);
    s->vval = malloc(s->vsize * sizeof *s->vval);
    s->m.objs = calloc(1, sizeof *s->m.objs);
    if (!s->m.face_start || !s->m.corner || !s->m.pos || !s->owner || !s->vkey || !s->vval || !s->m.objs)
        return -1;
    memset(s->vkey, 0xff, s->vsize * sizeof *s->vkey);
    s->m.face_start[0] = 0;
    s->m.nobjs = 1;
    s->m.path = NULL;
    return 0;
}

static void sub_free(Sub *s)
{
    free(s->m.face_start);
    free(s->m.corner);
    free(s->m.pos);
    free(s->m.objs);
    free(s->owner);
    free(s->vkey);
    free(s->vval);
}

/* Mark what the check says of the small mesh against the candidates: a
 * candidate that crosses the model or a fill taken, or makes a face the
 * check calls duplicate, degenerate or non-manifold, is refused; of
 * candidates that cross only each other, the first in loop order is
 * kept and the others refused (they try their next method). */
static int judge(const Sub *s, const MeshCheck *mc, uint32_t nfixed, uint32_t ncand, uint8_t *bad)
{
    const CheckObject *o = &mc->objs[0];
    int unsure = o->c.intersections_stopped || o->npairs < o->c.self_intersections;
    uint32_t *among = malloc(2 * ((size_t)o->npairs + 1) * sizeof *among), nam = 0;
    if (!among)
        return -1;
    for (uint32_t i = 0; i < ncand; i++)
        bad[i] = (uint8_t)unsure;
    for (uint32_t k = 0; k < o->npairs; k++) {
        uint32_t a = s->owner[o->pairs[2 * k]], b = s->owner[o->pairs[2 * k + 1]];
        int ca = a != RP_NONE && a >= nfixed, cb = b != RP_NONE && b >= nfixed;
        if (ca && cb && a != b) {
            among[2 * nam] = a - nfixed;
            among[2 * nam++ + 1] = b - nfixed;
        } else if (ca || cb) {
            bad[(ca ? a : b) - nfixed] = 1;
        }
    }
    for (uint32_t f = 0; f < s->m.nfaces; f++) {
        uint32_t w = s->owner[f];
        if (w != RP_NONE && w >= nfixed && (mc->face_flags[f] & (CHECK_DUPLICATE | CHECK_DEGENERATE | CHECK_NONMANIFOLD)))
            bad[w - nfixed] = 1;
    }
    /* in loop order: a candidate still good is kept, and every candidate
     * it crosses is refused (bit 1: crossed a kept one) */
    for (uint32_t i = 0; i < ncand; i++) {
        if (bad[i])
            continue;
        for (uint32_t k = 0; k < nam; k++) {
            uint32_t x = among[2 * k], y = among[2 * k + 1];
            if (x == i || y == i)
                bad[x == i ? y : x] |= 2;
        }
    }
    free(among);
    return 0;
}

int rp_fills_cross(Rep *r, const ObjTopo *t, Fill *fills, uint32_t nfixed, uint32_t n, uint8_t *bad)
{
    uint32_t ncand = n - nfixed;
    Box *box = malloc(((size_t)n + 1) * sizeof *box);
    uint8_t *near = calloc((size_t)t->nf + 1, 1);
    Grid gr = { 0 };
    Sub s = { 0 };
    int rc = -1;
    if (!box || !near)
        goto out;
    for (uint32_t i = 0; i < n; i++) {
        box_empty(&box[i]);
        for (uint32_t k = 0; k < 3 * fills[i].ntri; k++)
            box_add(&box[i], rp_vpos(r, fills[i].tri[k]));
    }
    if (grid_build(&gr, box + nfixed, ncand))
        goto out;
    uint32_t faces = 0, corners = 0;
    const Mesh *m = &r->w;
    for (uint32_t f = 0; f < t->nf; f++) {
        uint32_t a = m->face_start[t->f0 + f], e = m->face_start[t->f0 + f + 1];
        if (t->skip[f])
            continue;           /* degenerate, or a duplicate that goes */
        Box b;
        box_empty(&b);
        for (uint32_t c = a; c < e; c++)
            box_add(&b, rp_vpos(r, m->corner[c]));
        if (grid_near(&gr, &b, ncand)) {
            near[f] = 1;
            faces++;
            corners += e - a;
        }
    }
    for (uint32_t i = 0; i < n; i++) {
        faces += fills[i].ntri;
        corners += 3 * fills[i].ntri;
    }
    if (sub_alloc(&s, faces, corners))
        goto out;
    for (uint32_t f = 0; f < t->nf; f++)
        if (near[f]) {
            uint32_t a = m->face_start[t->f0 + f];
            sub_face(&s, r, m->corner + a, m->face_start[t->f0 + f + 1] - a, RP_NONE);
        }
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t k = 0; k < fills[i].ntri; k++)
            if (i >= nfixed || grid_near(&gr, &box[i], ncand))
                sub_face(&s, r, fills[i].tri + 3 * k, 3, i);
    s.m.nfaces = s.m.nfaces;
    s.m.objs[0].face_count = s.m.nfaces;
    s.m.objs[0].vert_max = s.m.nverts ? s.m.nverts - 1 : 0;
    MeshCheck mc;
    CheckOpts co = { .threads = r->opt->threads, .intersections = 1, .detail = 1, .cancel = r->opt->cancel };
    char err[256];
    if (meshcheck_run(&mc, &s.m, &co, err, sizeof err))
        goto out;
    rc = judge(&s, &mc, nfixed, ncand, bad);
    meshcheck_free(&mc);
out:
    free(box);
    free(near);
    grid_free(&gr);
    sub_free(&s);
    return rc;
}

/* ==== Moved faces ==== */

int rp_moved_cross(Rep *r, const ObjTopo *t, const uint32_t *face, const uint32_t *group, uint32_t n,
                   uint32_t vbase, int original, uint32_t *count, uint32_t ngroup, int *unsure)
{
    const Mesh *m = &r->w;
    uint32_t *cand = calloc((size_t)t->nf + 1, sizeof *cand), maxc = 0;
    Box *box = malloc(((size_t)n + 1) * sizeof *box);
    uint8_t *near = calloc((size_t)t->nf + 1, 1);
    uint32_t *vs = NULL;
    Grid gr = { 0 };
    Sub s = { 0 };
    int rc = -1;
    if (!cand || !box || !near)
        goto out;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t f = t->f0 + face[i];
        cand[face[i]] = group[i] + 1;
        box_empty(&box[i]);
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++) {
            uint32_t v = m->corner[c];
            box_add(&box[i], rp_vpos(r, v));
            box_add(&box[i], rp_vpos(r, v >= vbase ? r->anchor[v] : v));
        }
        maxc = m->face_start[f + 1] - m->face_start[f] > maxc ? m->face_start[f + 1] - m->face_start[f] : maxc;
    }
    if (!(vs = malloc(((size_t)maxc + 1) * sizeof *vs)) || grid_build(&gr, box, n))
        goto out;
    uint32_t faces = 0, corners = 0;
    for (uint32_t f = 0; f < t->nf; f++) {
        uint32_t a = m->face_start[t->f0 + f], e = m->face_start[t->f0 + f + 1];
        if (t->skip[f])
            continue;
        Box b;
        box_empty(&b);
        for (uint32_t c = a; c < e; c++)
            box_add(&b, rp_vpos(r, m->corner[c]));
        if (cand[f] || grid_near(&gr, &b, n)) {
            near[f] = 1;
            faces++;
            corners += e - a;
        }
    }
    if (sub_alloc(&s, faces, corners))
        goto out;
    for (uint32_t f = 0; f < t->nf; f++)
        if (near[f]) {
            uint32_t a = m->face_start[t->f0 + f], k = m->face_start[t->f0 + f + 1] - a;
            for (uint32_t j = 0; j < k; j++) {
                uint32_t v = m->corner[a + j];
                vs[j] = original && cand[f] && v >= vbase ? r->anchor[v] : v;
            }
            sub_face(&s, r, vs, k, cand[f] ? cand[f] - 1 : RP_NONE);
        }
    s.m.objs[0].face_count = s.m.nfaces;
    s.m.objs[0].vert_max = s.m.nverts ? s.m.nverts - 1 : 0;
    MeshCheck mc;
    CheckOpts co = { .threads = r->opt->threads, .intersections = 1, .detail = 1, .cancel = r->opt->cancel };
    char err[256];
    if (meshcheck_run(&mc, &s.m, &co, err, sizeof err))
        goto out;
    const CheckObject *o = &mc.objs[0];
    *unsure = o->c.intersections_stopped || o->npairs < o->c.self_intersections;
    memset(count, 0, ngroup * sizeof *count);
    for (uint32_t k = 0; k < o->npairs; k++) {
        uint32_t a = s.owner[o->pairs[2 * k]], b = s.owner[o->pairs[2 * k + 1]];
        if (a != RP_NONE)
            count[a]++;
        if (b != RP_NONE && b != a)
            count[b]++;
    }
    meshcheck_free(&mc);
    rc = 0;
out:
    free(cand);
    free(box);
    free(near);
    free(vs);
    grid_free(&gr);
    sub_free(&s);
    return rc;
}
