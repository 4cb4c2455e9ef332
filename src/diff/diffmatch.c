/* diffmatch.c: the vertices of both models in the order of one Morton
 * curve (through the box of both), and the vertices of one at the very
 * position of a vertex of the other's faces: such a vertex lies on the
 * other surface, its distance 0 without a query (an edited copy shares
 * most of its vertices with its original, an STL of an OBJ all of
 * them). Points at one position have one code, so the two lists, each
 * sorted by code, are merged in one pass; within a code, positions are
 * compared bit for bit (-0 as +0). */

#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "diff.h"

void diff_verts_free(DiffVerts *v)
{
    free(v->order);
    free(v->code);
    free(v->first);
    free(v->on);
    memset(v, 0, sizeof *v);
}

/* A position as three words, -0 as +0. */
static void pos_bits(const float *p, uint32_t k[3])
{
    for (int i = 0; i < 3; i++) {
        float v = p[i] == 0 ? 0.0f : p[i];
        memcpy(&k[i], &v, sizeof k[i]);
    }
}

/* m's used vertices (each with the first face that uses it) in curve order. */
static int verts_order(DiffVerts *v, const Mesh *m, const float box[6])
{
    size_t n = m->nverts ? m->nverts : 1;
    v->order = bigmem_alloc(n * sizeof *v->order);
    v->code = bigmem_alloc(n * sizeof *v->code);
    v->first = bigmem_alloc(n * sizeof *v->first);
    v->on = bigmem_alloc(n * sizeof *v->on);
    if (!v->order || !v->code || !v->first || !v->on || bvh_order(m->pos, m->nverts, box, v->order, v->code))
        return -1;
    memset(v->first, 0xff, (size_t)m->nverts * sizeof *v->first);
    memset(v->on, 0xff, (size_t)m->nverts * sizeof *v->on);
    for (uint32_t f = 0; f < m->nfaces; f++)
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++)
            if (v->first[m->corner[c]] == UINT32_MAX)
                v->first[m->corner[c]] = f;
    /* keep the used ones, in order */
    uint32_t k = 0;
    for (uint32_t i = 0; i < m->nverts; i++)
        if (v->first[v->order[i]] != UINT32_MAX) {
            v->order[k] = v->order[i];
            v->code[k++] = v->code[i];
        }
    v->nused = k;
    return 0;
}

/* The ones of a run of one code, by position (qsort's context in a
 * static would be state; the run is sorted as keys beside the index). */
typedef struct {
    uint32_t k[3];
    uint32_t v;
} Keyed;

static int by_key(const void *x, const void *y)
{
    return memcmp(((const Keyed *)x)->k, ((const Keyed *)y)->k, sizeof((const Keyed *)x)->k);
}

/* Match the vertices of A's run [i0, i1) with B's [j0, j1), one code. */
static int match_run(DiffVerts *va, DiffVerts *vb, const Mesh *a, const Mesh *b, uint32_t i0, uint32_t i1, uint32_t j0,
                     uint32_t j1)
{
    uint32_t na = i1 - i0, nb = j1 - j0;
    if (na == 1 && nb == 1) {       /* most runs: one vertex each */
        uint32_t x = va->order[i0], y = vb->order[j0], kx[3], ky[3];
        pos_bits(&a->pos[3 * (size_t)x], kx);
        pos_bits(&b->pos[3 * (size_t)y], ky);
        if (!memcmp(kx, ky, sizeof kx)) {
            va->on[x] = vb->first[y];
            vb->on[y] = va->first[x];
        }
        return 0;
    }
    Keyed *ka = malloc((size_t)na * sizeof *ka), *kb = malloc((size_t)nb * sizeof *kb);
    if (!ka || !kb) {
        free(ka);
        free(kb);
        return -1;
    }
    for (uint32_t i = 0; i < na; i++) {
        ka[i].v = va->order[i0 + i];
        pos_bits(&a->pos[3 * (size_t)ka[i].v], ka[i].k);
    }
    for (uint32_t j = 0; j < nb; j++) {
        kb[j].v = vb->order[j0 + j];
        pos_bits(&b->pos[3 * (size_t)kb[j].v], kb[j].k);
    }
    if (na > 1)
        qsort(ka, na, sizeof *ka, by_key);
    if (nb > 1)
        qsort(kb, nb, sizeof *kb, by_key);
    for (uint32_t i = 0, j = 0; i < na && j < nb;) {
        int c = memcmp(ka[i].k, kb[j].k, sizeof ka[i].k);
        if (c < 0) {
            i++;
        } else if (c > 0) {
            j++;
        } else {
            /* every vertex of one at this position meets the other's first */
            uint32_t ie = i, je = j;
            while (ie < na && !memcmp(ka[ie].k, ka[i].k, sizeof ka[i].k))
                ie++;
            while (je < nb && !memcmp(kb[je].k, kb[j].k, sizeof kb[j].k))
                je++;
            for (uint32_t x = i; x < ie; x++)
                va->on[ka[x].v] = vb->first[kb[j].v];
            for (uint32_t y = j; y < je; y++)
                vb->on[kb[y].v] = va->first[ka[i].v];
            i = ie;
            j = je;
        }
    }
    free(ka);
    free(kb);
    return 0;
}

int diff_match(DiffVerts *va, DiffVerts *vb, const Mesh *a, const Mesh *b, const float box[6])
{
    memset(va, 0, sizeof *va);
    memset(vb, 0, sizeof *vb);
    if (verts_order(va, a, box) || verts_order(vb, b, box))
        return -1;
    for (uint32_t i = 0, j = 0; i < va->nused && j < vb->nused;) {
        if (va->code[i] < vb->code[j]) {
            i++;
        } else if (va->code[i] > vb->code[j]) {
            j++;
        } else {
            uint32_t ie = i, je = j;
            while (ie < va->nused && va->code[ie] == va->code[i])
                ie++;
            while (je < vb->nused && vb->code[je] == vb->code[j])
                je++;
            if (match_run(va, vb, a, b, i, ie, j, je))
                return -1;
            i = ie;
            j = je;
        }
    }
    return 0;
}
