/* raster.c: walking a whole polygon row by row under the coverage rule
 * of raster.h (any number of corners, concave or self-overlapping). */

#include <stdlib.h>

#include "invariant.h"
#include "raster.h"

int polywalk_begin(PolyWalk *w, const ScreenPolys *sp, uint32_t pi, int32_t start_row)
{
    const ScreenPoly *p = &sp->polys[pi];
    uint32_t n = screen_poly_nverts(sp, pi);
    if ((int)n > w->cap) {
        EdgeWalk *e = realloc(w->e, (size_t)n * 2 * sizeof *e);
        if (!e)
            return -1;
        w->e = e;
        w->cap = (int)n * 2;
    }
    const ScreenVert *v = &sp->verts[p->first];
    ZV_ASSERT(n >= 3);     /* the front end's polygons have 3 corners or more */
    w->n = 0;
    for (uint32_t k = 0; k < n; k++) {
        EdgeWalk *e = &w->e[w->n];
        if (edge_setup(e, &v[k], &v[k + 1 < n ? k + 1 : 0], start_row) && e->row1 > start_row)
            w->n++;
    }
    return w->n;
}

static int cmp_i32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

void raster_sort_crossings(int32_t *xs, int m)
{
    if (m > 24) {
        qsort(xs, (size_t)m, sizeof *xs, cmp_i32);
        return;
    }
    for (int i = 1; i < m; i++) {
        int32_t x = xs[i];
        int q = i;
        while (q > 0 && xs[q - 1] > x) {
            xs[q] = xs[q - 1];
            q--;
        }
        xs[q] = x;
    }
}

int polywalk_row(PolyWalk *w, int32_t j, int32_t *xs)
{
    int m = 0;
    for (int k = 0; k < w->n; k++) {
        EdgeWalk *e = &w->e[k];
        if (j < e->row0 || j >= e->row1)
            continue;
        xs[m++] = e->xi;
        edge_step(e);
    }
    /* A closed polygon crosses every row centre an even number of times
     * under the half-open rule: crossings pair up into the even-odd
     * rule's intervals, and an odd count would mean an edge lost or
     * walked on the wrong row. */
    ZV_ASSERT((m & 1) == 0);
    raster_sort_crossings(xs, m);
    return m;
}

void polywalk_free(PolyWalk *w)
{
    free(w->e);
    w->e = NULL;
    w->n = w->cap = 0;
}
