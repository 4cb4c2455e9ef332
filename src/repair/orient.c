/* orient.c: the winding made to agree, and closed parts turned outward.
 *
 * Agreeing: two faces on a manifold edge agree when they run it in
 * opposite directions. A union-find with parity over the manifold edges
 * (as the check's: each face's parity relative to its root) gives each
 * patch of faces joined by manifold edges two classes whose faces agree
 * among themselves; the smaller class is flipped (the fewest flips; on a
 * tie, the class whose flip leaves the patch's volume positive). A
 * patch where a face would need both parities is non-orientable (a
 * Moebius strip): it is left as it is, and the check still says so.
 *
 * Outward, after the holes are filled: the parts (patches joined across
 * non-manifold edges) that are closed and agree get their volume by the
 * divergence theorem (the signed volumes of the tetrahedra each fan
 * triangle makes with a point, summed). A part inside an odd number of
 * other closed parts is a cavity, which faces inward; every other part
 * faces outward; a part whose volume has the wrong sign is flipped
 * whole. Nesting is told by the parity of the crossings of a ray from a
 * point inside one of its faces with the other parts (tried only
 * against parts whose box holds its box, and only while the work stays
 * within RP_NEST_BUDGET: past it, every part faces outward). */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

#define RP_NEST_BUDGET(nf) (32 * (uint64_t)(nf) + (1u << 20))

void rp_flip_face(Rep *r, uint32_t f)
{
    Mesh *m = &r->w;
    uint32_t s = m->face_start[f], e = m->face_start[f + 1];
    for (uint32_t *a = m->corner + s + 1, *z = m->corner + e - 1; a < z; a++, z--) {
        uint32_t x = *a;
        *a = *z;
        *z = x;
    }
    if (m->corner_uv)
        for (uint32_t *a = m->corner_uv + s + 1, *z = m->corner_uv + e - 1; a < z; a++, z--) {
            uint32_t x = *a;
            *a = *z;
            *z = x;
        }
}

/* Face f's signed volume about ref (its fan of triangles). */
static double face_volume(const Rep *r, uint32_t f, const double ref[3])
{
    const Mesh *m = &r->w;
    uint32_t s = m->face_start[f], e = m->face_start[f + 1];
    double a[3], b[3], c[3], v = 0;
    const float *pa = rp_vpos(r, m->corner[s]);
    for (int k = 0; k < 3; k++)
        a[k] = pa[k] - ref[k];
    for (uint32_t i = s + 1; i + 1 < e; i++) {
        const float *pb = rp_vpos(r, m->corner[i]), *pc = rp_vpos(r, m->corner[i + 1]);
        for (int k = 0; k < 3; k++) {
            b[k] = pb[k] - ref[k];
            c[k] = pc[k] - ref[k];
        }
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
              a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    }
    return v;
}

/* The middle of the object's box: volumes are summed about it. */
static void object_ref(const Rep *r, const ObjTopo *t, double ref[3])
{
    float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t c = 0; c < t->nc; c++) {
        const float *q = rp_vpos(r, rp_cvert(r, t, c));
        for (int k = 0; k < 3; k++) {
            lo[k] = q[k] < lo[k] ? q[k] : lo[k];
            hi[k] = q[k] > hi[k] ? q[k] : hi[k];
        }
    }
    for (int k = 0; k < 3; k++)
        ref[k] = t->nc ? ((double)lo[k] + hi[k]) / 2 : 0;
}

/* ==== Agreeing ==== */

typedef struct {
    uint32_t *up;
    uint8_t  *bits;             /* bit 0: parity to the parent; bit 1 (roots): a conflict */
} ParityFind;

static uint32_t pfind(ParityFind *u, uint32_t f, int *parity)
{
    uint32_t r = f;
    int p = 0;
    while (u->up[r] != r) {
        p ^= u->bits[r] & 1;
        r = u->up[r];
    }
    /* the path straight to the root, each with its parity there */
    for (uint32_t x = f, q = (uint32_t)p; x != r;) {
        uint32_t next = u->up[x], px = u->bits[x] & 1u;
        u->up[x] = r;
        u->bits[x] = (uint8_t)((u->bits[x] & 2u) | q);
        q ^= px;
        x = next;
    }
    *parity = p;
    return r;
}

static void punion(ParityFind *u, uint32_t f, uint32_t g, int rel)
{
    int pf, pg;
    uint32_t rf = pfind(u, f, &pf), rg = pfind(u, g, &pg);
    if (rf == rg) {
        if ((pf ^ pg) != rel)
            u->bits[rf] |= 2;
        return;
    }
    uint32_t lo = rf < rg ? rf : rg, hi = rf < rg ? rg : rf;
    u->up[hi] = lo;
    u->bits[lo] |= u->bits[hi] & 2;
    u->bits[hi] = (uint8_t)((u->bits[hi] & 2) | (pf ^ pg ^ rel));
}

int rp_winding(Rep *r, ObjTopo *t)
{
    uint32_t nf = t->nf;
    ParityFind u = { rp_big(((size_t)nf + 1) * sizeof *u.up, 0), rp_big((size_t)nf + 1, 1) };
    uint32_t *count = rp_big(2 * ((size_t)nf + 1) * sizeof *count, 1);
    double *vol = NULL, ref[3];
    int rc = -1;
    if (!u.up || !u.bits || !count)
        goto out;
    for (uint32_t f = 0; f < nf; f++)
        u.up[f] = f;
    for (uint32_t c = 0; c < t->nc; c++) {
        uint32_t m = t->mate[c];
        if (m < RP_SPECIAL && c < m)
            punion(&u, rp_cface(t, c), rp_cface(t, m), rp_cpt(r, t, c) == rp_cpt(r, t, m));
    }
    int p;
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t root = pfind(&u, f, &p);
        count[2 * root + (uint32_t)p]++;
    }
    /* a tie: the class whose flip leaves the volume positive */
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t root = pfind(&u, f, &p);
        if (count[2 * root] != count[2 * root + 1] || (u.bits[root] & 2))
            continue;
        if (!vol) {
            if (!(vol = calloc(2 * ((size_t)nf + 1), sizeof *vol)))
                goto out;
            object_ref(r, t, ref);
        }
        vol[2 * root + (uint32_t)p] += face_volume(r, t->f0 + f, ref);
    }
    uint32_t flipped = 0;
    for (uint32_t f = 0; f < nf; f++) {
        uint32_t root = pfind(&u, f, &p);
        if (u.bits[root] & 2)
            continue;
        uint32_t c0 = count[2 * root], c1 = count[2 * root + 1];
        int flip = c1 < c0 ? 1 : c0 < c1 ? 0 : vol[2 * root] - vol[2 * root + 1] >= 0 ? 1 : 0;
        if (p == flip && !t->skip[f]) {
            rp_flip_face(r, t->f0 + f);
            flipped++;
        }
    }
    r->rep->flipped += flipped;
    rc = flipped ? rp_topo_pair(r, t, 1) : 0;
out:
    free(u.up);
    free(u.bits);
    free(count);
    free(vol);
    return rc;
}

/* ==== Outward ==== */

typedef struct {
    double   vol;               /* signed, about the object's reference */
    float    lo[3], hi[3];
    uint32_t first;             /* its first face */
    uint32_t nfaces;
    uint8_t  closed, agrees;
    uint8_t  depth;             /* inside so many other closed parts (mod 2) */
} Part;

/* Does the ray from x along d cross triangle (a, b, c)? (Moeller and
 * Trumbore's test.) */
static int ray_hits(const double x[3], const double d[3], const float *a, const float *b, const float *c)
{
    double e1[3], e2[3], pv[3], tv[3], qv[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
        tv[k] = x[k] - a[k];
    }
    pv[0] = d[1] * e2[2] - d[2] * e2[1];
    pv[1] = d[2] * e2[0] - d[0] * e2[2];
    pv[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (det == 0)
        return 0;
    double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    if (u < 0 || u > 1)
        return 0;
    qv[0] = tv[1] * e1[2] - tv[2] * e1[1];
    qv[1] = tv[2] * e1[0] - tv[0] * e1[2];
    qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
    double v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
    if (v < 0 || u + v > 1)
        return 0;
    return (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det > 0;
}

/* Crossings of the ray from x with the faces list[0..n) (mod 2). */
static int ray_parity(const Rep *r, const ObjTopo *t, const double x[3], const uint32_t *list, uint32_t n)
{
    /* a direction off the axes, so that the ray meets few edges head on */
    static const double d[3] = { 0.8451542547285166, 0.4170288281141495, 0.3342392587693357 };
    int odd = 0;
    const Mesh *m = &r->w;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t f = t->f0 + list[i], s = m->face_start[f], e = m->face_start[f + 1];
        for (uint32_t k = s + 1; k + 1 < e; k++)
            odd ^= ray_hits(x, d, rp_vpos(r, m->corner[s]), rp_vpos(r, m->corner[k]), rp_vpos(r, m->corner[k + 1]));
    }
    return odd;
}

static int box_holds(const Part *q, const Part *p)
{
    for (int k = 0; k < 3; k++)
        if (q->lo[k] > p->lo[k] || q->hi[k] < p->hi[k])
            return 0;
    return 1;
}

/* Each closed part's depth: inside how many others (mod 2). 0 for all
 * when the work would pass the budget. */
static int nesting(const Rep *r, const ObjTopo *t, Part *pt, uint32_t np, const uint32_t *label)
{
    uint32_t *off = calloc((size_t)np + 2, sizeof *off), *list = malloc(((size_t)t->nf + 1) * sizeof *list);
    if (!off || !list) {
        free(off);
        free(list);
        return -1;
    }
    for (uint32_t f = 0; f < t->nf; f++)
        if (label[f] != RP_NONE)
            off[label[f] + 1]++;
    for (uint32_t p = 0; p < np; p++)
        off[p + 1] += off[p];
    for (uint32_t f = 0; f < t->nf; f++)
        if (label[f] != RP_NONE)
            list[off[label[f]]++] = f;
    memmove(off + 1, off, (size_t)np * sizeof *off);
    off[0] = 0;
    uint64_t work = 0, budget = RP_NEST_BUDGET(t->nf);
    for (uint32_t p = 0; p < np && work <= budget; p++) {
        if (!pt[p].closed || !pt[p].agrees)
            continue;
        /* a point inside the part's first face (its first fan triangle) */
        const Mesh *m = &r->w;
        uint32_t f = t->f0 + pt[p].first, s = m->face_start[f];
        double x[3];
        for (int k = 0; k < 3; k++)
            x[k] = ((double)rp_vpos(r, m->corner[s])[k] + rp_vpos(r, m->corner[s + 1])[k] +
                    rp_vpos(r, m->corner[s + 2])[k]) / 3;
        for (uint32_t q = 0; q < np && work <= budget; q++) {
            if (q == p || !pt[q].closed || !pt[q].agrees || !box_holds(&pt[q], &pt[p]))
                continue;
            work += off[q + 1] - off[q];
            pt[p].depth ^= (uint8_t)ray_parity(r, t, x, list + off[q], off[q + 1] - off[q]);
        }
    }
    if (work > budget)
        for (uint32_t p = 0; p < np; p++)
            pt[p].depth = 0;
    free(off);
    free(list);
    return 0;
}

/* The parts, numbered in face order (label per face, RP_NONE: degenerate). */
static uint32_t *parts_label(const Rep *r, const ObjTopo *t, uint32_t *np)
{
    uint32_t *uf = rp_uf_new(t->nf);
    if (!uf)
        return NULL;
    for (uint32_t c = 0; c < t->nc; c++)
        if (t->mate[c] < RP_SPECIAL)
            rp_uf_union(uf, rp_cface(t, c), rp_cface(t, t->mate[c]));
    for (uint32_t g = 0; g < t->nm_ngroup; g++)
        for (uint32_t k = t->nm_group[g] + 1; k < t->nm_group[g + 1]; k++)
            rp_uf_union(uf, rp_cface(t, t->nm_half[t->nm_group[g]]), rp_cface(t, t->nm_half[k]));
    uint32_t n = 0;
    (void)r;
    /* every face straight to its root first: the labels below overwrite
     * the roots, which a later find must not walk */
    for (uint32_t f = 0; f < t->nf; f++)
        uf[f] = rp_uf_find(uf, f);
    for (uint32_t f = 0; f < t->nf; f++) {
        uint32_t root = uf[f];
        /* the root is the part's first face: labelled before the rest */
        uf[f] = t->skip[f] ? RP_NONE : root == f ? n++ : uf[root];
    }
    *np = n;
    return uf;
}

int rp_outward(Rep *r, ObjTopo *t, int *settled)
{
    uint32_t np = 0, *label = parts_label(r, t, &np);
    Part *pt = label ? rp_big(((size_t)np + 1) * sizeof *pt, 1) : NULL;
    if (!pt) {
        free(label);
        return -1;
    }
    double ref[3];
    object_ref(r, t, ref);
    for (uint32_t p = 0; p < np; p++) {
        pt[p].closed = pt[p].agrees = 1;
        pt[p].first = RP_NONE;
        for (int k = 0; k < 3; k++) {
            pt[p].lo[k] = INFINITY;
            pt[p].hi[k] = -INFINITY;
        }
    }
    for (uint32_t c = 0; c < t->nc; c++) {
        uint32_t f = rp_cface(t, c), m = t->mate[c];
        if (label[f] == RP_NONE)
            continue;
        Part *q = &pt[label[f]];
        if (m == RP_BOUNDARY || m == RP_NONMANIF)
            q->closed &= m != RP_BOUNDARY;
        else if (m < RP_SPECIAL && rp_cpt(r, t, c) == rp_cpt(r, t, m))
            q->agrees = 0;
        if (m == RP_NONMANIF)
            q->agrees = 0;      /* no winding to agree on across a fin */
        const float *x = rp_vpos(r, rp_cvert(r, t, c));
        for (int k = 0; k < 3; k++) {
            q->lo[k] = x[k] < q->lo[k] ? x[k] : q->lo[k];
            q->hi[k] = x[k] > q->hi[k] ? x[k] : q->hi[k];
        }
    }
    for (uint32_t f = 0; f < t->nf; f++)
        if (label[f] != RP_NONE) {
            Part *q = &pt[label[f]];
            q->first = q->first == RP_NONE ? f : q->first;
            q->nfaces++;
            q->vol += face_volume(r, t->f0 + f, ref);
        }
    uint32_t closed = 0, agree = 0;
    for (uint32_t p = 0; p < np; p++) {
        closed += pt[p].closed && pt[p].agrees;
        agree += pt[p].agrees;
    }
    if (settled)
        *settled = agree == np;
    int rc = closed > 1 ? nesting(r, t, pt, np, label) : 0;
    for (uint32_t p = 0; rc == 0 && p < np; p++) {
        Part *q = &pt[p];
        /* depth's bit 1 now: turn this part */
        if (q->closed && q->agrees && q->vol != 0 && (q->vol < 0) != (q->depth & 1)) {
            q->depth |= 2;
            r->rep->outward++;
        }
    }
    for (uint32_t f = 0; rc == 0 && f < t->nf; f++)
        if (label[f] != RP_NONE && (pt[label[f]].depth & 2))
            rp_flip_face(r, t->f0 + f);
    free(label);
    free(pt);
    return rc;
}
