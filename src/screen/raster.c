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

/* Sorting a row's crossings. Ordinary rows have a handful: insertion
 * sort. A polygon of thousands of corners can cross a row thousands of
 * times, mostly at a few places (a face listing the same corners over
 * and over): an introsort in place, inlined comparisons, no allocation
 * (qsort compared through a call and took a buffer from malloc, in the
 * rasterizers' row loop), equal keys splitting evenly (Hoare's
 * partition), heapsort where the splits go bad. */
static void insertion_sort(int32_t *a, int n)
{
    for (int i = 1; i < n; i++) {
        int32_t x = a[i];
        int q = i;
        while (q > 0 && a[q - 1] > x) {
            a[q] = a[q - 1];
            q--;
        }
        a[q] = x;
    }
}

static void sift_down(int32_t *a, int root, int n)
{
    int32_t x = a[root];
    for (int c; (c = 2 * root + 1) < n; root = c) {
        if (c + 1 < n && a[c + 1] > a[c])
            c++;
        if (a[c] <= x)
            break;
        a[root] = a[c];
    }
    a[root] = x;
}

static void heap_sort(int32_t *a, int n)
{
    for (int i = n / 2 - 1; i >= 0; i--)
        sift_down(a, i, n);
    for (int i = n - 1; i > 0; i--) {
        int32_t t = a[0];
        a[0] = a[i];
        a[i] = t;
        sift_down(a, 0, i);
    }
}

static void swap_i32(int32_t *a, int i, int j)
{
    int32_t t = a[i];
    a[i] = a[j];
    a[j] = t;
}

static void intro_sort(int32_t *a, int n, int depth)
{
    while (n > 24) {
        if (depth-- == 0) {
            heap_sort(a, n);
            return;
        }
        /* the median of three to a[0], the pivot: Hoare's partition then
         * ends with 0 <= j < n - 1, both parts non-empty */
        int mid = n / 2;
        if (a[mid] < a[0])
            swap_i32(a, mid, 0);
        if (a[n - 1] < a[0])
            swap_i32(a, n - 1, 0);
        if (a[n - 1] < a[mid])
            swap_i32(a, n - 1, mid);
        swap_i32(a, 0, mid);
        int32_t p = a[0];
        int i = -1, j = n;
        for (;;) {
            do
                i++;
            while (a[i] < p);
            do
                j--;
            while (a[j] > p);
            if (i >= j)
                break;
            swap_i32(a, i, j);
        }
        /* the smaller part by recursion (depth at most log2 n), the
         * larger by the loop */
        if (j + 1 < n - j - 1) {
            intro_sort(a, j + 1, depth);
            a += j + 1;
            n -= j + 1;
        } else {
            intro_sort(a + j + 1, n - j - 1, depth);
            n = j + 1;
        }
    }
    insertion_sort(a, n);
}

void raster_sort_crossings(int32_t *xs, int m)
{
    int depth = 0;
    for (int k = m; k > 1; k >>= 1)
        depth += 2;
    intro_sort(xs, m, depth);
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
