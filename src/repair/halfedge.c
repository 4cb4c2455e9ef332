/* halfedge.c: one object's topology, as the check takes it. Its
 * corners' points renumbered from 0 for the object (so that every
 * array is the object's size), and the pairing of its half-edges: the
 * half-edges of each edge found by bucketing them by their smaller
 * point (a counting sort), each bucket sorted by the larger point, in
 * corner order within a run. A run of one is a boundary edge, of two a
 * manifold edge (the two are each other's mate, whichever way they
 * run), of more a non-manifold one (its half-edges listed together).
 * Degenerate faces are out of the topology, as in the check. */

#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "repair_internal.h"

/* ==== Shared helpers ==== */

void *rp_big(size_t bytes, int zero)
{
    void *p = zero ? calloc(bytes ? bytes : 1, 1) : malloc(bytes ? bytes : 1);
    bigmem_advise(p, bytes, 1);
    return p;
}

uint32_t *rp_uf_new(size_t n)
{
    uint32_t *p = rp_big(n * sizeof *p, 0);
    if (p)
        for (size_t i = 0; i < n; i++)
            p[i] = (uint32_t)i;
    return p;
}

uint32_t rp_uf_find(uint32_t *p, uint32_t i)
{
    while (p[i] != i) {
        p[i] = p[p[i]];
        i = p[i];
    }
    return i;
}

int rp_uf_union(uint32_t *p, uint32_t a, uint32_t b)
{
    a = rp_uf_find(p, a);
    b = rp_uf_find(p, b);
    if (a == b)
        return 0;
    if (a < b)
        p[b] = a;
    else
        p[a] = b;
    return 1;
}

void rp_face_normal(const Rep *r, uint32_t f, double n[3])
{
    const Mesh *m = &r->w;
    uint32_t s = m->face_start[f], e = m->face_start[f + 1];
    n[0] = n[1] = n[2] = 0;
    const float *o = rp_vpos(r, m->corner[s]);
    for (uint32_t c = s; c < e; c++) {
        const float *p = rp_vpos(r, m->corner[c]), *q = rp_vpos(r, m->corner[c + 1 < e ? c + 1 : s]);
        /* about the first corner: fewer digits lost far from the origin */
        double px = (double)p[0] - o[0], py = (double)p[1] - o[1], pz = (double)p[2] - o[2];
        double qx = (double)q[0] - o[0], qy = (double)q[1] - o[1], qz = (double)q[2] - o[2];
        n[0] += py * qz - pz * qy;
        n[1] += pz * qx - px * qz;
        n[2] += px * qy - py * qx;
    }
}

/* ==== Points ==== */

/* The object's points from its corners' vertices: numbered from 0 for
 * the object (cpt), or the mesh's own (no array) when the object is a
 * large part of the mesh. */
static int topo_points(Rep *r, ObjTopo *t)
{
    if (!t->cpt) {
        t->npts = r->npts;
        return 0;
    }
    if (r->loccap < r->npts) {
        uint32_t *l = realloc(r->loc, ((size_t)r->npts + 1) * sizeof *l);
        if (!l)
            return -1;
        memset(l + r->loccap, 0xff, ((size_t)r->npts + 1 - r->loccap) * sizeof *l);
        r->loc = l;
        r->loccap = (size_t)r->npts + 1;
    }
    t->npts = 0;
    for (uint32_t c = 0; c < t->nc; c++) {
        uint32_t g = r->pid[rp_cvert(r, t, c)];
        if (r->loc[g] == RP_NONE) {
            r->loc[g] = t->npts;
            t->gpt[t->npts++] = g;
        }
        t->cpt[c] = r->loc[g];
    }
    for (uint32_t p = 0; p < t->npts; p++)
        r->loc[t->gpt[p]] = RP_NONE;
    return 0;
}

/* ==== The pairing ==== */

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

/* The larger point of half-edge h: what a bucket (of its smaller point)
 * is sorted by. */
static inline uint32_t far_point(const Rep *r, const ObjTopo *t, uint32_t h)
{
    uint32_t p = rp_cpt(r, t, h), q = rp_cpt(r, t, rp_next(r, t, h));
    return p < q ? q : p;
}

/* Sort one bucket's half-edges by their larger point, in corner order
 * within a run (so that the runs list their faces in file order), the
 * keys into hi[] alongside. Short buckets, nearly all, by insertion;
 * a long one (the centre of a fan of thousands) through packed keys. */
static void bucket_sort(const Rep *r, const ObjTopo *t, uint32_t *he, uint32_t *hi, uint32_t n, uint64_t *scratch)
{
    if (n <= 32) {
        for (uint32_t i = 0; i < n; i++) {
            uint32_t a = far_point(r, t, he[i]), h = he[i], j = i;
            for (; j > 0 && (hi[j - 1] > a || (hi[j - 1] == a && he[j - 1] > h)); j--) {
                hi[j] = hi[j - 1];
                he[j] = he[j - 1];
            }
            hi[j] = a;
            he[j] = h;
        }
        return;
    }
    for (uint32_t i = 0; i < n; i++)
        scratch[i] = (uint64_t)far_point(r, t, he[i]) << 32 | he[i];
    qsort(scratch, n, sizeof *scratch, cmp_u64);
    for (uint32_t i = 0; i < n; i++) {
        hi[i] = (uint32_t)(scratch[i] >> 32);
        he[i] = (uint32_t)scratch[i];
    }
}

static int push(uint32_t **a, uint32_t *n, uint32_t *cap, uint32_t v)
{
    if (*n == *cap) {
        uint32_t c = *cap ? *cap * 2 : 64;
        uint32_t *q = realloc(*a, (size_t)c * sizeof *q);
        if (!q)
            return -1;
        *a = q;
        *cap = c;
    }
    (*a)[(*n)++] = v;
    return 0;
}

typedef struct {
    uint32_t *off, *he;         /* the half-edges bucketed by their smaller point */
    uint32_t *hi;               /* one bucket's larger points (room for the longest) */
    uint64_t *scratch;
    uint32_t  gcap, hcap;
} Pairing;

/* One edge: its half-edges he[0..n). */
static int edge_run(ObjTopo *t, Pairing *pg, const uint32_t *he, uint32_t n)
{
    if (n == 1) {
        t->mate[he[0]] = RP_BOUNDARY;
        t->nboundary++;
        return 0;
    }
    if (n == 2) {
        t->mate[he[0]] = he[1];
        t->mate[he[1]] = he[0];
        return 0;
    }
    if (push(&t->nm_group, &t->nm_ngroup, &pg->gcap, t->nm_nhalf))
        return -1;
    for (uint32_t k = 0; k < n; k++) {
        t->mate[he[k]] = RP_NONMANIF;
        if (push(&t->nm_half, &t->nm_nhalf, &pg->hcap, he[k]))
            return -1;
    }
    return 0;
}

static int pairing_fill(Rep *r, ObjTopo *t, Pairing *pg)
{
    uint32_t np = t->npts, nhe = 0, maxdeg = 0;
    if (!(pg->off = rp_big(((size_t)np + 2) * sizeof *pg->off, 1)))
        return -1;
    for (uint32_t c = 0; c < t->nc; c++) {
        uint32_t p = rp_cpt(r, t, c), q = rp_cpt(r, t, rp_next(r, t, c));
        if (t->skip[rp_cface(t, c)]) {
            t->mate[c] = RP_SKIPPED;
        } else if (p == q) {
            t->mate[c] = RP_SELF;
        } else {
            t->mate[c] = RP_BOUNDARY;
            pg->off[(p < q ? p : q) + 1]++;
            nhe++;
        }
    }
    for (uint32_t p = 0; p < np; p++) {
        maxdeg = pg->off[p + 1] > maxdeg ? pg->off[p + 1] : maxdeg;
        pg->off[p + 1] += pg->off[p];
    }
    pg->he = rp_big(((size_t)nhe + 1) * sizeof *pg->he, 0);
    pg->hi = malloc(((size_t)maxdeg + 1) * sizeof *pg->hi);
    pg->scratch = maxdeg > 32 ? malloc((size_t)maxdeg * sizeof *pg->scratch) : NULL;
    if (!pg->hi || !pg->he || (maxdeg > 32 && !pg->scratch))
        return -1;
    for (uint32_t c = 0; c < t->nc; c++)
        if (t->mate[c] == RP_BOUNDARY) {
            uint32_t p = rp_cpt(r, t, c), q = rp_cpt(r, t, rp_next(r, t, c));
            pg->he[pg->off[p < q ? p : q]++] = c;
        }
    /* the cursors went one bucket on: back */
    memmove(pg->off + 1, pg->off, (size_t)np * sizeof *pg->off);
    pg->off[0] = 0;
    ZV_ASSERT(pg->off[np] == nhe);
    return 0;
}

int rp_topo_pair(Rep *r, ObjTopo *t, int points)
{
    if (points && topo_points(r, t))
        return -1;
    Pairing pg = { 0 };
    int rc = -1;
    t->nm_ngroup = t->nm_nhalf = t->nboundary = 0;
    if (pairing_fill(r, t, &pg))
        goto out;
    for (uint32_t p = 0; p < t->npts; p++) {
        uint32_t j = pg.off[p], end = pg.off[p + 1], *hi = pg.hi - j;
        bucket_sort(r, t, pg.he + j, pg.hi, end - j, pg.scratch);
        while (j < end) {
            uint32_t j1 = j + 1;
            while (j1 < end && hi[j1] == hi[j])
                j1++;
            if (edge_run(t, &pg, pg.he + j, j1 - j))
                goto out;
            j = j1;
        }
    }
    rc = push(&t->nm_group, &t->nm_ngroup, &pg.gcap, t->nm_nhalf);
    t->nm_ngroup--;     /* the end entry is not an edge */
out:
    free(pg.off);
    free(pg.hi);
    free(pg.he);
    free(pg.scratch);
    return rc;
}

/* ==== The object ==== */

int rp_topo_build(Rep *r, uint32_t i, ObjTopo *t)
{
    const Mesh *m = &r->w;
    const MeshObject *o = &m->objs[i];
    memset(t, 0, sizeof *t);
    t->obj = i;
    t->f0 = o->face_first;
    t->nf = o->face_count;
    t->c0 = m->face_start[t->f0];
    uint64_t nc = (uint64_t)m->face_start[t->f0 + t->nf] - t->c0;
    if (nc >= RP_SPECIAL)
        return -1;
    t->nc = (uint32_t)nc;
    size_t n = (size_t)t->nc + 1;
    t->tris = t->nc == 3 * (uint64_t)t->nf;
    for (uint32_t f = 0; t->tris && f < t->nf; f++)
        t->tris = m->face_start[t->f0 + f + 1] - m->face_start[t->f0 + f] == 3;
    t->cface = t->tris ? NULL : rp_big(n * sizeof *t->cface, 0);
    /* the mesh's points when the object is a quarter of its corners or more */
    int local = (uint64_t)t->nc * 4 < r->npts;
    t->cpt = local ? rp_big(n * sizeof *t->cpt, 0) : NULL;
    t->gpt = local ? malloc(n * sizeof *t->gpt) : NULL;
    t->mate = rp_big(n * sizeof *t->mate, 0);
    t->skip = rp_big((size_t)t->nf + 1, 1);
    if ((!t->tris && !t->cface) || (local && (!t->cpt || !t->gpt)) || !t->mate || !t->skip)
        goto fail;
    for (uint32_t f = 0; f < t->nf; f++) {
        for (uint32_t c = rp_start(r, t, f); !t->tris && c < rp_start(r, t, f + 1); c++)
            t->cface[c] = f;
        if (!r->clean)
            t->skip[f] = (uint8_t)rp_face_degenerate(r, t->f0 + f);
    }
    if (rp_topo_pair(r, t, 1) == 0)
        return 0;
fail:
    rp_topo_free(r, t);
    return -1;
}

void rp_topo_free(Rep *r, ObjTopo *t)
{
    (void)r;
    free(t->cface);
    free(t->cpt);
    free(t->gpt);
    free(t->mate);
    free(t->skip);
    free(t->nm_half);
    free(t->nm_group);
    memset(t, 0, sizeof *t);
}

/* ==== Faces leaving ==== */

int rp_topo_unpair(Rep *r, ObjTopo *t)
{
    /* their own half-edges leave; a manifold partner left alone is a
     * boundary edge (twins.c lets none be) */
    for (uint32_t f = 0; f < t->nf; f++) {
        if (!t->skip[f])
            continue;
        for (uint32_t c = rp_start(r, t, f); c < rp_start(r, t, f + 1); c++) {
            uint32_t m = t->mate[c];
            if (m == RP_SKIPPED)
                break;          /* out before: the whole face */
            if (m < RP_SPECIAL && !t->skip[rp_cface(t, m)]) {
                t->mate[m] = RP_BOUNDARY;
                t->nboundary++;
            }
            t->nboundary -= m == RP_BOUNDARY;
            t->mate[c] = RP_SKIPPED;
        }
    }
    /* each non-manifold edge without them: two left pair, one is boundary */
    uint32_t ng = 0, nh = 0;
    for (uint32_t g = 0; g < t->nm_ngroup; g++) {
        uint32_t start = nh;
        for (uint32_t k = t->nm_group[g]; k < t->nm_group[g + 1]; k++) {
            uint32_t h = t->nm_half[k];
            if (!t->skip[rp_cface(t, h)])
                t->nm_half[nh++] = h;
        }
        uint32_t n = nh - start;
        if (n >= 3) {
            t->nm_group[ng++] = start;
            continue;
        }
        if (n == 2) {
            t->mate[t->nm_half[start]] = t->nm_half[start + 1];
            t->mate[t->nm_half[start + 1]] = t->nm_half[start];
        } else if (n == 1) {
            t->mate[t->nm_half[start]] = RP_BOUNDARY;
            t->nboundary++;
        }
        nh = start;
    }
    t->nm_group[ng] = nh;
    t->nm_ngroup = ng;
    t->nm_nhalf = nh;
    return 0;
}
