#ifndef ZV_RASTER_H
#define ZV_RASTER_H
/* raster: the coverage rule, written once and used by every algorithm.
 *
 * An edge from (xa, ya) to (xb, yb) in 24.8 fixed point counts for the
 * rows j whose centre yc = 256 j + 128 satisfies y_top <= yc < y_bottom
 * (horizontal edges count for none). Where it counts, its crossing is
 * c = x_top + (yc - y_top) * dx / dy, and the walker keeps
 *     xi = ceil((c - 128) / 256),
 * the first column whose centre is at or right of the crossing, as an
 * exact integer quotient plus remainder (no float, no drift). A row's
 * crossings sorted as xi_0 <= xi_1 <= ... cover the columns
 * [xi_0, xi_1), [xi_2, xi_3), ...: the even-odd rule with half-open
 * intervals, which is the top-left rule.
 *
 * Crossings are the scanline walk of Bouknight (1970); the triangle test
 * below is the edge function of J. Pineda, "A Parallel Algorithm for
 * Polygon Rasterization", SIGGRAPH 1988, with the top-left tie rule.
 */

#include <stdint.h>
#include "invariant.h"
#include "screen.h"

typedef struct {
    int32_t row0, row1;   /* rows [row0, row1) where the edge counts */
    int32_t xi;           /* column of the crossing at the current row */
    int32_t q;            /* whole columns added per row */
    int64_t r;            /* remainder, 0 <= r < den */
    int64_t rs;           /* remainder added per row, 0 <= rs < den */
    int64_t den;          /* 256 * dy */
} EdgeWalk;

/* floor(n / d) and its remainder for d > 0 and |n| < 2^52: a double
 * division (exact operands, correctly rounded quotient, so off by at most
 * one after truncation) fixed up with exact integer arithmetic. Several
 * times faster than a 64-bit idiv, and just as exact. */
static inline int64_t floordiv64_rem(int64_t n, int64_t d, int64_t *rem_out)
{
    /* Past 2^52 the operands are no longer exact in a double, the
     * quotient can be off by many, and the one-step fix-ups below would
     * take that many steps. The front end's guard band keeps every
     * fixed-point coordinate, so every walker's numerator, well inside. */
    ZV_ASSERT(d > 0 && n < ((int64_t)1 << 52) && n > -((int64_t)1 << 52));
    int64_t q = (int64_t)((double)n / (double)d);
    int64_t r = n - q * d;
    while (r < 0) {
        q--;
        r += d;
    }
    while (r >= d) {
        q++;
        r -= d;
    }
    *rem_out = r;
    return q;
}

/* First sample index whose centre 256 k + 128 is >= fixed-point v:
 * ceil((v - 128) / 256) = floor((v + 127) / 256), an arithmetic shift
 * (GCC and Clang shift signed values arithmetically). Rows and columns
 * alike. */
static inline int32_t sample_ceil(int32_t v)
{
    return (v + 127) >> SUBPIX_BITS;
}

/* Set up the edge a->b. Returns 0 when it counts for no row. The walker
 * starts at row max(row0, start_row). */
static inline int edge_setup(EdgeWalk *e, const ScreenVert *a, const ScreenVert *b, int32_t start_row)
{
    if (a->y == b->y)
        return 0;
    const ScreenVert *t = a->y < b->y ? a : b;   /* top */
    const ScreenVert *m = a->y < b->y ? b : a;   /* bottom */
    e->row0 = sample_ceil(t->y);
    e->row1 = sample_ceil(m->y);
    if (e->row0 >= e->row1)
        return 0;
    int64_t dy = (int64_t)m->y - t->y, dx = (int64_t)m->x - t->x;
    int32_t row = e->row0 > start_row ? e->row0 : start_row;
    e->den = 256 * dy;
    int64_t yc = (int64_t)row * 256 + 128;
    int64_t num = (int64_t)t->x * dy + (yc - t->y) * dx - 128 * dy + e->den - 1;
    e->xi = (int32_t)floordiv64_rem(num, e->den, &e->r);
    /* per row: 256 dx / (256 dy) = dx / dy, remainder scaled back by 256 */
    int64_t rs;
    e->q = (int32_t)floordiv64_rem(dx, dy, &rs);
    e->rs = 256 * rs;
    return 1;
}

/* Advance one row down. */
static inline void edge_step(EdgeWalk *e)
{
    e->xi += e->q;
    e->r += e->rs;
    if (e->r >= e->den) {
        e->r -= e->den;
        e->xi++;
    }
}

/* ---- The same rule as edge functions, for small triangles ----
 * Triangle v[0..2] covers a sample where every edge function is > 0, or
 * 0 on a left edge (interior at larger x) or a top edge (horizontal,
 * interior below): exactly the samples of the crossing rule above, as
 * the tests check against a brute-force reference. Exact integers, no
 * division; the values step by whole samples. */
typedef struct {
    int64_t e[3];         /* edge functions at the sample the setup named */
    int64_t step_x[3];    /* added per column */
    int64_t step_y[3];    /* added per row */
    int64_t bias[3];      /* inside where e >= bias: 0 on top-left edges, else 1 */
} TriEdges;

/* Set up at sample (i, j). Returns 0 for a triangle without area. */
static inline int tri_edges_setup(TriEdges *t, const ScreenVert *v, int32_t i, int32_t j)
{
    const ScreenVert *a = &v[0], *b = &v[1], *c = &v[2];
    int64_t orient = (int64_t)(b->x - a->x) * (c->y - a->y) - (int64_t)(b->y - a->y) * (c->x - a->x);
    if (orient == 0)
        return 0;
    if (orient < 0) {           /* walk the edges the other way round */
        const ScreenVert *x = b;
        b = c;
        c = x;
    }
    const ScreenVert *ea[3] = { a, b, c }, *eb[3] = { b, c, a };
    int64_t px = 256LL * i + 128, py = 256LL * j + 128;
    for (int k = 0; k < 3; k++) {
        int64_t dx = eb[k]->x - ea[k]->x, dy = eb[k]->y - ea[k]->y;
        t->e[k] = dx * (py - ea[k]->y) - dy * (px - ea[k]->x);
        t->step_x[k] = -dy * 256;
        t->step_y[k] = dx * 256;
        t->bias[k] = (-dy > 0 || (dy == 0 && dx > 0)) ? 0 : 1;
    }
    return 1;
}

/* Does triangle v[0..2] cover sample (i, j)? The front end uses it to drop
 * triangles whose few candidate samples all lie outside them. */
static inline int tri_covers_sample(const ScreenVert *v, int32_t i, int32_t j)
{
    TriEdges t;
    return tri_edges_setup(&t, v, i, j) && t.e[0] >= t.bias[0] && t.e[1] >= t.bias[1] &&
           t.e[2] >= t.bias[2];
}

/* Columns covered by a triangle-like span are clamped to the image. */
static inline int32_t clamp_col(int32_t x, int32_t w)
{
    return x < 0 ? 0 : (x > w ? w : x);
}

/* ---- A whole polygon, row by row (any number of corners, even-odd) ---- */

typedef struct {
    EdgeWalk *e;          /* the polygon's non-horizontal edges */
    int       n;
    int       cap;
} PolyWalk;

/* Set up every edge of polygon pi for rows from start_row on. Returns the
 * number of edges (0: covers nothing). Grows w->e as needed (-1 on OOM). */
int polywalk_begin(PolyWalk *w, const ScreenPolys *sp, uint32_t pi, int32_t start_row);

/* Crossings of row j (which must be the walker's current row) into xs[],
 * sorted ascending, then step every counting edge to row j + 1. Returns
 * the count (always even). xs must hold w->n entries. */
int polywalk_row(PolyWalk *w, int32_t j, int32_t *xs);

void polywalk_free(PolyWalk *w);

/* Sort a row's m crossings ascending. Rows of ordinary polygons have a
 * handful, where insertion sort is fastest; a polygon of thousands of
 * corners can cross one row thousands of times (a comb, a face that
 * lists the same corners over and over), where insertion sort is
 * quadratic per row: beyond a few dozen, O(m log m). */
void raster_sort_crossings(int32_t *xs, int m);

#endif
