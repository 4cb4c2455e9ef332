/* items.c: the located problems one by one (meshcheck.h: CheckItems),
 * for the viewer's problem keys and --problem K: each a shape to frame
 * and to draw over the model, made from the check's locations and the
 * mesh's faces while the mesh is at hand. */

#include <stdlib.h>
#include <string.h>

#include "check_internal.h"
#include "grow.h"

/* ==== Building ==== */

static int add_point(CheckItems *it, const float *p)
{
    if (grow_size((void **)&it->pt, &it->cap_pt, it->npt + 3, sizeof *it->pt))
        return -1;
    memcpy(it->pt + it->npt, p, 3 * sizeof *p);
    it->npt += 3;
    return 0;
}

/* Close the line begun at the last line_start: its points are those
 * added since. */
static int end_line(CheckItems *it, CheckItem *e, int closed)
{
    if (grow_size((void **)&it->line_closed, &it->cap_closed, (size_t)it->nlines + 1, 1))
        return -1;
    it->line_closed[it->nlines++] = (uint8_t)closed;
    e->nlines++;
    return check_push(&it->line_start, &(size_t){ it->nlines }, &it->cap_lines, (uint32_t)(it->npt / 3));
}

/* Face f's outline as a closed line, and its centre into *centre. */
static int face_line(CheckItems *it, CheckItem *e, const Mesh *m, uint32_t f, float centre[3])
{
    double sum[3] = { 0, 0, 0 };
    uint32_t s = m->face_start[f], n = m->face_start[f + 1] - s;
    for (uint32_t c = s; c < s + n; c++) {
        const float *p = m->pos + 3 * (size_t)m->corner[c];
        for (int k = 0; k < 3; k++)
            sum[k] += p[k];
        if (add_point(it, p))
            return -1;
    }
    for (int k = 0; k < 3; k++)
        centre[k] = n ? (float)(sum[k] / n) : 0;
    return end_line(it, e, 1);
}

static int line_of(CheckItems *it, CheckItem *e, const float *pts, uint32_t n, int closed)
{
    for (uint32_t i = 0; i < n; i++)
        if (add_point(it, pts + 3 * (size_t)i))
            return -1;
    return end_line(it, e, closed);
}

/* Item k of kind `kind` of one object's locations l. */
static int item_make(CheckItems *it, CheckItem *e, const CheckLocations *l, const Mesh *m, uint32_t k)
{
    float centre[3];
    switch (e->kind) {
    case CHECK_LOC_HOLES: {
        uint32_t s = l->loop_start[k], n = l->loop_start[k + 1] - s;
        e->count = n;
        e->length = l->loop_length[k];
        return line_of(it, e, l->loop_pt + 3 * (size_t)s, n, 1);
    }
    case CHECK_LOC_NM_EDGES:
        e->count = l->edge_start[k + 1] - l->edge_start[k];
        if (line_of(it, e, l->edge_pt + 6 * (size_t)k, 2, 0))
            return -1;
        for (uint32_t f = l->edge_start[k]; f < l->edge_start[k + 1]; f++)
            if (face_line(it, e, m, l->edge_face[f], centre))
                return -1;
        return 0;
    case CHECK_LOC_NM_VERTICES:
        e->has_ring = 1;
        memcpy(e->ring, l->vert_pt + 3 * (size_t)k, sizeof e->ring);
        return 0;
    case CHECK_LOC_FLIPPED:
    case CHECK_LOC_DEGENERATE:
    case CHECK_LOC_DUPLICATE:
        e->face[0] = l->face[e->kind - CHECK_LOC_FLIPPED][k];
        if (face_line(it, e, m, e->face[0], centre))
            return -1;
        /* a flipped face shows; a degenerate one has no area, a
         * duplicate lies on its original: a ring finds them */
        e->has_ring = e->kind != CHECK_LOC_FLIPPED;
        memcpy(e->ring, centre, sizeof e->ring);
        return 0;
    case CHECK_LOC_CROSSING:
        e->face[0] = l->pair_face[2 * k];
        e->face[1] = l->pair_face[2 * k + 1];
        if (face_line(it, e, m, e->face[0], centre) || face_line(it, e, m, e->face[1], centre))
            return -1;
        e->has_ring = 1;
        for (int c = 0; c < 3; c++)
            e->ring[c] = (float)l->pair_pt[3 * (size_t)k + c];
        return 0;
    case CHECK_LOC_KINDS:
        break;
    }
    return 0;
}

int meshcheck_items_add(CheckItems *it, const MeshCheck *mc, const Mesh *m, int file)
{
    if (!it->line_start && check_push(&it->line_start, &(size_t){ 0 }, &it->cap_lines, 0))
        return -1;
    for (uint32_t o = 0; o < mc->nobjs; o++) {
        const CheckLocations *l = &mc->objs[o].loc;
        for (int kind = 0; kind < CHECK_LOC_KINDS; kind++) {
            uint32_t n = meshcheck_loc_located(l, (CheckLocKind)kind);
            for (uint32_t k = 0; k < n; k++) {
                if (grow_size((void **)&it->item, &it->cap, (size_t)it->n + 1, sizeof *it->item))
                    return -1;
                CheckItem *e = &it->item[it->n];
                memset(e, 0, sizeof *e);
                e->kind = (CheckLocKind)kind;
                e->file = file;
                e->face_first = mc->objs[o].face_first;
                e->line0 = it->nlines;
                if (item_make(it, e, l, m, k))
                    return -1;
                it->n++;
            }
        }
    }
    return 0;
}

/* ==== Order ==== */

void meshcheck_items_order(CheckItems *it)
{
    if (it->n == 0)
        return; /* nothing to order, and item may be NULL */
    /* a stable counting sort by kind: files and objects stay in order */
    uint32_t count[CHECK_LOC_KINDS + 1] = { 0 };
    for (uint32_t i = 0; i < it->n; i++)
        count[it->item[i].kind + 1]++;
    for (int k = 0; k < CHECK_LOC_KINDS; k++)
        count[k + 1] += count[k];
    CheckItem *sorted = malloc(((size_t)it->n + 1) * sizeof *sorted);
    if (sorted) {
        uint32_t at[CHECK_LOC_KINDS];
        memcpy(at, count, sizeof at);
        for (uint32_t i = 0; i < it->n; i++)
            sorted[at[it->item[i].kind]++] = it->item[i];
        memcpy(it->item, sorted, (size_t)it->n * sizeof *sorted);
        free(sorted);
    } else {
        /* no memory for the copy: insertion, stable, in place */
        for (uint32_t i = 1; i < it->n; i++) {
            CheckItem e = it->item[i];
            uint32_t j = i;
            for (; j > 0 && it->item[j - 1].kind > e.kind; j--)
                it->item[j] = it->item[j - 1];
            it->item[j] = e;
        }
    }
    for (uint32_t i = 0; i < it->n; i++)
        it->item[i].num = i > 0 && it->item[i - 1].kind == it->item[i].kind ? it->item[i - 1].num + 1 : 1;
}

void meshcheck_items_free(CheckItems *it)
{
    free(it->item);
    free(it->line_start);
    free(it->line_closed);
    free(it->pt);
    memset(it, 0, sizeof *it);
}

void meshcheck_item_box(const CheckItems *it, uint32_t i, float lo[3], float hi[3])
{
    const CheckItem *e = &it->item[i];
    int any = 0;
    for (uint32_t l = e->line0; l < e->line0 + e->nlines; l++)
        for (uint32_t p = it->line_start[l]; p < it->line_start[l + 1]; p++)
            for (int k = 0; k < 3; k++) {
                float v = it->pt[3 * (size_t)p + k];
                lo[k] = !any || v < lo[k] ? v : lo[k];
                hi[k] = !any || v > hi[k] ? v : hi[k];
                any = k == 2 ? 1 : any;
            }
    if (e->has_ring)
        for (int k = 0; k < 3; k++) {
            lo[k] = !any || e->ring[k] < lo[k] ? e->ring[k] : lo[k];
            hi[k] = !any || e->ring[k] > hi[k] ? e->ring[k] : hi[k];
        }
}
