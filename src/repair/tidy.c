/* tidy.c: the clean (what the check counts as degenerate or duplicate
 * goes) and the vertices put in their final order.
 *
 * The clean runs over the faces in place, in one pass that only
 * shrinks the arrays: it drops a point repeated right after
 * itself within a face (the last corner against the first too: a face
 * a b b c is the triangle a b c) and the degenerate faces (every corner
 * on one line, decided exactly: exactsign.c). The duplicates go later,
 * object by object (twins.c). Face order, materials and texture
 * coordinates of the faces kept are kept. */

#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

/* ==== Dropping faces in place ==== */

/* Where the faces kept are written: faces and corners so far. */
typedef struct {
    uint32_t nf, wc;            /* faces and corners written */
} Writer;

static void face_keep(Mesh *m, Writer *wr, uint32_t f, uint32_t n, const uint32_t *uvs)
{
    /* corners are already at [wr->wc, wr->wc + n) */
    if (m->corner_uv && uvs)
        memmove(m->corner_uv + wr->wc, uvs, n * sizeof *uvs);
    if (m->face_mat)
        m->face_mat[wr->nf] = m->face_mat[f];
    m->face_start[wr->nf] = wr->wc;
    wr->wc += n;
    wr->nf++;
}

/* Objects' face ranges after a pass: object i's faces now start at
 * first_new[i]. */
static void objects_after(Mesh *m, const Writer *wr, uint32_t *first_new)
{
    for (uint32_t i = 0; i < m->nobjs; i++) {
        uint32_t a = first_new[i], b = i + 1 < m->nobjs ? first_new[i + 1] : wr->nf;
        m->objs[i].face_first = a;
        m->objs[i].face_count = b - a;
    }
    m->face_start[wr->nf] = wr->wc;
    m->nfaces = wr->nf;
}

/* Pass one: repeated points and degenerate faces. */
static int drop_degenerate(Rep *r)
{
    Mesh *m = &r->w;
    uint32_t *first_new = malloc(((size_t)m->nobjs + 1) * sizeof *first_new);
    if (!first_new)
        return -1;
    Writer wr = { 0, 0 };
    uint32_t obj = 0, s = m->nfaces ? m->face_start[0] : 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        /* objects are consecutive runs of faces, in order */
        while (obj < m->nobjs && m->objs[obj].face_first <= f)
            first_new[obj++] = wr.nf;
        uint32_t e = m->face_start[f + 1], n = e - s;
        if (r->level[obj - 1] >= RP_LEVEL_UNTOUCHED) {
            memmove(m->corner + wr.wc, m->corner + s, n * sizeof *m->corner);
            face_keep(m, &wr, f, n, m->corner_uv ? m->corner_uv + s : NULL);
            s = e;
            continue;
        }
        if (rp_poly_degenerate(r, m->corner + s, n)) {
            r->rep->degenerate++;
            s = e;
            continue;
        }
        /* the corners kept move down to wr.wc (never past where they are read) */
        uint32_t k = 0;
        for (uint32_t c = s; c < e; c++) {
            uint32_t v = m->corner[c];
            if (k > 0 && r->pid[v] == r->pid[m->corner[wr.wc + k - 1]]) {
                r->rep->repeated++;
                continue;
            }
            if (m->corner_uv)
                m->corner_uv[wr.wc + k] = m->corner_uv[c];
            m->corner[wr.wc + k++] = v;
        }
        while (k > 1 && r->pid[m->corner[wr.wc + k - 1]] == r->pid[m->corner[wr.wc]]) {
            k--;
            r->rep->repeated++;
        }
        /* a face not degenerate has three points that are not on one line */
        ZV_ASSERT(k >= 3);
        face_keep(m, &wr, f, k, NULL);
        s = e;
    }
    while (obj < m->nobjs)
        first_new[obj++] = wr.nf;
    objects_after(m, &wr, first_new);
    free(first_new);
    return 0;
}

int rp_clean(Rep *r)
{
    return drop_degenerate(r);
}

/* ==== The vertices in their final order ==== */

/* Which vertices faces, points and lines use. */
static uint8_t *vertices_used(const Mesh *m)
{
    uint8_t *used = rp_big((size_t)m->nverts + 1, 1);
    if (!used)
        return NULL;
    uint32_t nc = m->nfaces ? m->face_start[m->nfaces] : 0, nl = m->nlines ? m->line_start[m->nlines] : 0;
    for (uint32_t c = 0; c < nc; c++)
        used[m->corner[c]] = 1;
    for (uint32_t i = 0; i < m->npoints; i++)
        used[m->point ? m->point[i] : i] = 1;
    for (uint32_t c = 0; c < nl; c++)
        used[m->line_corner[c]] = 1;
    return used;
}

/* New index of every vertex: the input's in order (those unused dropped
 * when drop), each followed by the new vertices anchored to it (new
 * ones unused always dropped). RP_NONE: dropped. Returns the count. */
static uint32_t new_order(Rep *r, const uint8_t *used, int drop, uint32_t *idx)
{
    uint32_t n0 = r->nverts0, nv = r->w.nverts, k = 0;
    /* new vertices by anchor (an anchor that is new itself: its own anchor) */
    uint32_t *head = idx, *next = r->pid;  /* scratch: pid is not read after this */
    for (uint32_t v = 0; v < n0; v++)
        head[v] = RP_NONE;
    for (uint32_t u = nv; u-- > n0;) {
        uint32_t a = r->anchor[u];
        while (a != RP_NONE && a >= n0)
            a = r->anchor[a];
        a = a == RP_NONE ? (n0 ? n0 - 1 : RP_NONE) : a;
        next[u] = a == RP_NONE ? RP_NONE : head[a];
        if (a != RP_NONE)
            head[a] = u;
    }
    /* idx doubles as head[] below n0: read each head before writing idx[v] */
    for (uint32_t v = 0; v < n0; v++) {
        uint32_t h = head[v];
        if (used[v] || !drop) {
            idx[v] = k++;
        } else {
            idx[v] = RP_NONE;
            r->rep->unused++;
        }
        for (uint32_t u = h; u != RP_NONE; u = next[u])
            idx[u] = used[u] ? k++ : RP_NONE;
    }
    return k;
}

/* Object i's vertex range from what it uses. */
static void object_range(Mesh *m, MeshObject *o)
{
    uint32_t lo = UINT32_MAX, hi = 0;
#define SEE(v)                          \
    do {                                \
        uint32_t v_ = (v);              \
        lo = v_ < lo ? v_ : lo;         \
        hi = v_ > hi ? v_ : hi;         \
    } while (0)
    for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++)
        for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++)
            SEE(m->corner[c]);
    for (uint32_t p = o->point_first; p < o->point_first + o->point_count; p++)
        SEE(m->point ? m->point[p] : p);
    for (uint32_t l = o->line_first; l < o->line_first + o->line_count; l++)
        for (uint32_t c = m->line_start[l]; c < m->line_start[l + 1]; c++)
            SEE(m->line_corner[c]);
#undef SEE
    o->vert_min = lo == UINT32_MAX ? 0 : lo;
    o->vert_max = lo == UINT32_MAX ? 0 : hi;
}

static int remap(Rep *r, const uint32_t *idx, uint32_t k)
{
    Mesh *m = &r->w;
    float *pos = rp_big(3 * ((size_t)k + 1) * sizeof *pos, 0);
    float *rgb = m->rgb ? rp_big(3 * ((size_t)k + 1) * sizeof *rgb, 0) : NULL;
    uint32_t *point = NULL;
    if (!m->point && m->npoints) {
        /* a cloud's points are its first vertices: kept so only if they stay put */
        uint32_t moved = 0;
        for (uint32_t i = 0; i < m->npoints; i++)
            moved |= idx[i] != i;
        if (moved && !(point = malloc((size_t)m->npoints * sizeof *point))) {
            free(pos);
            free(rgb);
            return -1;
        }
        for (uint32_t i = 0; point && i < m->npoints; i++)
            point[i] = idx[i];
    }
    if (!pos || (m->rgb && !rgb)) {
        free(pos);
        free(rgb);
        free(point);
        return -1;
    }
    for (uint32_t v = 0; v < m->nverts; v++)
        if (idx[v] != RP_NONE) {
            memcpy(pos + 3 * (size_t)idx[v], m->pos + 3 * (size_t)v, 3 * sizeof *pos);
            if (rgb)
                memcpy(rgb + 3 * (size_t)idx[v], m->rgb + 3 * (size_t)v, 3 * sizeof *rgb);
        }
    uint32_t nc = m->nfaces ? m->face_start[m->nfaces] : 0, nl = m->nlines ? m->line_start[m->nlines] : 0;
    for (uint32_t c = 0; c < nc; c++)
        m->corner[c] = idx[m->corner[c]];
    for (uint32_t i = 0; m->point && i < m->npoints; i++)
        m->point[i] = idx[m->point[i]];
    for (uint32_t c = 0; c < nl; c++)
        m->line_corner[c] = idx[m->line_corner[c]];
    for (uint32_t h = 0; h < r->rep->nholes; h++) {
        /* a hole's vertex is on its loop: used, so kept */
        ZV_ASSERT(idx[r->rep->holes[h].vertex] != RP_NONE);
        r->rep->holes[h].vertex = idx[r->rep->holes[h].vertex];
    }
    if (point)
        m->point = point;
    if (!r->pos_borrowed) {
        free(m->pos);
        free(m->rgb);
    }
    r->pos_borrowed = 0;
    m->pos = pos;
    m->rgb = rgb;
    m->nverts = k;
    r->vcap = k;
    return 0;
}

int rp_renumber(Rep *r, int drop_unused)
{
    Mesh *m = &r->w;
    uint8_t *used = vertices_used(m);
    uint32_t *idx = rp_big(((size_t)m->nverts + 1) * sizeof *idx, 0);
    int rc = -1;
    if (!used || !idx)
        goto out;
    uint32_t k = new_order(r, used, drop_unused, idx), same = k == m->nverts;
    for (uint32_t v = 0; same && v < m->nverts; v++)
        same = idx[v] == v;
    rc = same ? 0 : remap(r, idx, k);
    for (uint32_t i = 0; rc == 0 && i < m->nobjs; i++)
        object_range(m, &m->objs[i]);
out:
    free(used);
    free(idx);
    return rc;
}
