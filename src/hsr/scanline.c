/* scanline.c: the scanline z-buffer. The band is rendered one row at a
 * time, top to bottom, and only the polygons that cross the current row
 * are looked at.
 *
 * Tables, built once per band:
 *  - the polygon table: every polygon meeting the band, bucketed by the
 *    first band row it covers (a counting sort into one entry array, no
 *    per-polygon allocation). An entry carries the polygon's index and
 *    where its corners are, so both can be prefetched a few entries
 *    ahead: the table visits polygons out of memory order;
 *  - the edge table: a polygon's non-horizontal edges, each set up with
 *    edge_setup() at the first row it counts for in the band. A triangle
 *    keeps its long edge plus the one short edge that counts for the
 *    current row, and sets up its lower short edge only when the row
 *    reaches the middle corner; a general polygon keeps its edges sorted
 *    by first row.
 * Active lists, updated as rows advance:
 *  - active triangles (a plain array of records with their left and
 *    right walkers and a copy of the plane, removed by swapping in the
 *    last one when they end), and
 *  - active general polygons with their active edges in one shared pool,
 *    compacted in order every row as edges and polygons finish.
 * A triangle covering a single row of the band never enters the active
 * list: its span is drawn when it is taken from the polygon table. An
 * edge needed for one row only keeps just its crossing (no per-row step).
 *
 * For each row every active polygon's crossings are sorted (a triangle's
 * left and right are known once: its middle corner's side of the long
 * edge) and the pairs [x_a, x_b) are depth-tested, four samples at a time
 * with SSE2, against the row's depth/id buffer. That buffer is the frame
 * buffer's own row: it stays in L1 while the row is scanned, is written
 * once as background and then only where samples win, so the frame
 * buffer is walked once, in order, with no copy.
 *
 * Why it is exact: coverage comes only from the walkers of raster.h,
 * whose crossings are exact integer quotients; a walker set up at a later
 * row holds the same crossing as one set up earlier and stepped, so
 * setting edges up lazily changes nothing. Each row sees exactly the
 * edges that count for it (a triangle's long edge and one short edge;
 * every active edge of a polygon, even-odd), so spans are the z-buffer's.
 * Depth is plane_row() then plane_at() (the SSE2 path performs the same
 * IEEE single operations in the same order) and samples compare (depth,
 * id) as hsr_wins() does, so the order polygons are visited in does not
 * matter and ids and depths are bit-identical to the z-buffer's.
 *
 * Implements the scanline approach of C. Wylie, G. Romney, D. Evans and
 * A. Erdahl, "Half-tone Perspective Drawings by Computer", AFIPS FJCC
 * 1967, and W. J. Bouknight, "A Procedure for Generation of
 * Three-dimensional Half-toned Computer Graphics Presentations", CACM
 * 13(9), 1970 (polygon and edge tables, an active list), with a depth
 * row per scanline in place of their span comparisons.
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "invariant.h"
#include "clock.h"
#include "raster.h"
#include "grow.h"
#include "hsr.h"
#include "simd.h"

/* An active triangle: e[0] is its left edge, e[1] its right one (the
 * long edge on one side, the short edge counting now on the other), a
 * copy of its plane, and where the lower short edge takes over. */
typedef struct {
    EdgeWalk e[2];
    float    a, b, zc;          /* ScreenPoly's plane, referenced to (x0, y0) */
    int32_t  x0, y0, face;
    int32_t  ymid;              /* row the lower short edge starts at (INT32_MAX: none) */
    int32_t  yend;              /* one past the last row in the band */
    uint32_t vm, vb;            /* middle and bottom corners (by y), verts[] indices */
    int16_t  side;              /* which of e[] is the short edge */
    int16_t  clip;              /* may cross the image's left or right side */
} ScanTri;

/* An active general polygon: edges pool[off .. off + n), sorted by the
 * first row they count for. */
typedef struct {
    const ScreenPoly *p;
    uint32_t          off, n;
    int32_t           yend;
} ScanGon;

/* A polygon table entry: the polygon, and where its corners are, so the
 * corners can be fetched ahead without reading the polygon first. */
typedef struct {
    uint32_t poly;              /* index << 1 | 1 when not a triangle */
    uint32_t first;             /* its first corner in verts[] */
} ScanEntry;

typedef struct {
    uint16_t *key;              /* per polygon: bucket row in the band, KEY_NONE outside */
    uint32_t  key_cap;
    uint32_t *first;            /* per polygon: its first corner (copied in memory order) */
    uint32_t  first_cap;
    ScanEntry *order;           /* the polygon table: entries by first row */
    uint32_t  order_cap;
    uint32_t *start;            /* bucket boundaries: rows + 1 */
    uint32_t  start_cap;
    ScanTri  *tri;              /* active triangles */
    uint32_t  ntri, tri_cap;
    ScanGon  *gon;              /* active general polygons */
    uint32_t  ngon, gon_cap;
    EdgeWalk *pool;             /* their edges */
    uint32_t  npool, pool_cap;
    int32_t  *xs;               /* one polygon's crossings on one row */
    uint32_t  xs_cap;
    float    *inf;              /* a row of +inf: the background depth */
    uint32_t  inf_cap;
    int       simd;             /* this frame's SimdLevel, resolved (simd_use) */
} ScanState;

#define KEY_NONE    0xFFFFu     /* key: polygon outside the band */
#define KEY_GON_BIT 15          /* key: not a triangle */
#define KEY_GON     (1u << KEY_GON_BIT)
#define KEY_ROW     0x7FFFu     /* key: first band row (SCREEN_MAX rows fit) */
#define PF_AHEAD    12          /* prefetch distance, in table entries */

static void *scan_create(void)
{
    return calloc(1, sizeof(ScanState));
}

static void scan_destroy(void *st)
{
    ScanState *s = st;
    if (!s)
        return;
    free(s->key);
    free(s->first);
    free(s->order);
    free(s->start);
    free(s->tri);
    free(s->gon);
    free(s->pool);
    free(s->xs);
    free(s->inf);
    free(s);
}

/* ==== the spans ==== */

/* Depth-test samples [xa, xb) of row j (ids/dep point at that row) for
 * polygon p. Returns the samples written. The scalar loop is the rule
 * itself: plane_row(), plane_at(), hsr_wins(). */
static inline uint32_t span_scalar(const ScreenPoly *p, int32_t *restrict ids, float *restrict dep,
                                   float zr, int xa, int xb)
{
    int32_t id = p->face;
    uint32_t n = 0;
    for (int i = xa; i < xb; i++) {
        float z = plane_at(p, zr, i);
        if (hsr_wins(z, id, dep[i], ids[i])) {
            dep[i] = z;
            ids[i] = id;
            n++;
        }
    }
    return n;
}

#ifdef ZV_SSE2

/* Four samples at a time. Bit-identical to span_scalar(): the packed
 * instructions are the same IEEE single operations as the scalar ones
 * (int -> float, then a * that, then zrow + that: plane_at()'s order, no
 * fused multiply-add), and the win mask is hsr_wins() lane by lane (the
 * unsigned id comparison as a signed one on sign-flipped values). Lanes
 * outside [xa, xb) store back what they loaded, so a group may run past
 * xb as long as it stays inside the row (this band's own memory). */
static const uint8_t popcount4[16] = { 0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4 };

static inline uint32_t span_sse2(float pa, int32_t px0, int32_t face, int32_t *restrict ids,
                          float *restrict dep, float zr, int xa, int xb, int w)
{
    uint32_t n = 0;
    const __m128i lane = _mm_setr_epi32(0, 1, 2, 3), flip = _mm_set1_epi32(INT32_MIN);
    const __m128 va = _mm_set1_ps(pa), vzr = _mm_set1_ps(zr);
    const __m128i vid = _mm_set1_epi32(face), vidf = _mm_xor_si128(vid, flip);
    const __m128i vend = _mm_set1_epi32(xb), four = _mm_set1_epi32(4);
    __m128i vi = _mm_add_epi32(_mm_set1_epi32(xa), lane);             /* columns */
    __m128i vrel = _mm_sub_epi32(vi, _mm_set1_epi32(px0));            /* i - x0 */
    int i = xa;
    for (; i < xb && i + 4 <= w; i += 4) {
        __m128 z = _mm_add_ps(vzr, _mm_mul_ps(va, _mm_cvtepi32_ps(vrel)));
        __m128 zb = _mm_loadu_ps(dep + i);
        __m128i idb = _mm_loadu_si128((const __m128i *)(ids + i));
        __m128 idlt = _mm_castsi128_ps(_mm_cmplt_epi32(vidf, _mm_xor_si128(idb, flip)));
        __m128 win = _mm_or_ps(_mm_cmplt_ps(z, zb), _mm_and_ps(_mm_cmpeq_ps(z, zb), idlt));
        win = _mm_and_ps(win, _mm_castsi128_ps(_mm_cmplt_epi32(vi, vend)));
        /* stored even when nothing wins: a branch here mispredicts */
        _mm_storeu_ps(dep + i, _mm_or_ps(_mm_and_ps(win, z), _mm_andnot_ps(win, zb)));
        __m128i wi = _mm_castps_si128(win);
        _mm_storeu_si128((__m128i *)(ids + i),
                         _mm_or_si128(_mm_and_si128(wi, vid), _mm_andnot_si128(wi, idb)));
        n += popcount4[_mm_movemask_ps(win)];
        vi = _mm_add_epi32(vi, four);
        vrel = _mm_add_epi32(vrel, four);
    }
    if (i < xb) {   /* the last few columns of the image */
        ScreenPoly p;
        p.a = pa;
        p.x0 = px0;
        p.face = face;
        n += span_scalar(&p, ids, dep, zr, i, xb);
    }
    return n;
}
#endif

/* span_scalar() as a call of its own: the scalar level's spans, kept out
 * of span_test() so that it stays as small as the SSE2 loop alone. It
 * takes the three fields it reads, as span_sse2() does: a pointer would
 * make the callers build the whole plane in memory. */
static __attribute__((noinline)) uint32_t span_scalar_call(float pa, int32_t px0, int32_t face,
                                                           int32_t *restrict ids, float *restrict dep, float zr,
                                                           int xa, int xb)
{
    ScreenPoly p;
    p.a = pa;
    p.x0 = px0;
    p.face = face;
    return span_scalar(&p, ids, dep, zr, xa, xb);
}

/* Depth-test samples [xa, xb) of row j, xa < xb, at SIMD level simd.
 * Inlined into each caller, as it was before there was a choice (as a
 * call it costs the scanline some 5% more instructions). */
static inline __attribute__((always_inline)) uint32_t span_test(int simd, const ScreenPoly *p, int32_t *restrict ids,
                                                                float *restrict dep, int j, int xa, int xb, int w)
{
    /* tri_start and tri_row clamp a triangle's crossings only when its
     * sample box touches a side of the image: the exact walk stays in
     * the box (its crossings lie between its corners), so inside the
     * image no clamp is needed. A span past the row would write into
     * the next one. (A triangle's plane copy carries the box's corner
     * only, hence x0 and y0 alone.) */
    ZV_ASSERT(j >= p->y0 && xa >= p->x0 && xa < xb && xb <= w);
    float zr = plane_row(p, j);
#ifdef ZV_SSE2
    if (simd >= SIMD_SSE2)
        return span_sse2(p->a, p->x0, p->face, ids, dep, zr, xa, xb, w);
#endif
    (void)simd;
    (void)w;
    return span_scalar_call(p->a, p->x0, p->face, ids, dep, zr, xa, xb);
}

/* The span between two crossings, clamped to the row. */
static inline uint32_t span_pair(int simd, const ScreenPoly *p, int32_t *restrict ids, float *restrict dep,
                                 int j, int32_t x0, int32_t x1, int32_t w)
{
    int32_t xa = x0 < x1 ? x0 : x1, xb = x0 < x1 ? x1 : x0;
    xa = clamp_col(xa, w);
    xb = clamp_col(xb, w);
    return xa < xb ? span_test(simd, p, ids, dep, j, xa, xb, w) : 0;
}

/* ==== triangles ==== */

/* Set up edge a-b at row j. When it is needed for row j only (more = 0)
 * just its crossing is kept: the per-row step (a second division) is
 * then dead code, and the walker is never stepped. */
static inline void edge_start(EdgeWalk *e, const ScreenVert *a, const ScreenVert *b, int32_t j,
                              int more)
{
    if (more) {
        (void)edge_setup(e, a, b, j);
        return;
    }
    EdgeWalk one;
    e->xi = edge_setup(&one, a, b, j) ? one.xi : 0;
}

/* edge_step() on a copy of the walker's live fields: in registers the
 * compiler makes the carry branch-free (it is as random as the slope),
 * where on the record itself it keeps a mispredicting branch. */
static inline void walk_step(EdgeWalk *e)
{
    EdgeWalk l;
    l.xi = e->xi;
    l.q = e->q;
    l.r = e->r;
    l.rs = e->rs;
    l.den = e->den;
    edge_step(&l);
    e->xi = l.xi;
    e->r = l.r;
}

/* The depth plane of an active triangle, as the ScreenPoly the depth
 * rule reads (only the plane fields are used). */
static inline ScreenPoly tri_plane(const ScanTri *a)
{
    ScreenPoly p;
    p.a = a->a;
    p.b = a->b;
    p.zc = a->zc;
    p.x0 = a->x0;
    p.y0 = a->y0;
    p.face = a->face;
    return p;
}

/* Take triangle pi from the polygon table at row j (its first row in
 * the band; rows [j, yend) remain). A single row is drawn at once;
 * otherwise the triangle joins the active list, which draws row j next. */
static inline uint32_t tri_start(ScanState *s, const ScreenPolys *sp, const ScreenPoly *p, int j,
                                 int yend, int32_t *ids, float *dep, int32_t w)
{
    /* Corners copied into locals (nothing the walkers write can alias
     * them), sorted by y, remembering where the middle and bottom ones
     * live for the lower edge's setup later. */
    uint32_t it = p->first, im = it + 1, ib = it + 2, ix;
    const ScreenVert *v = sp->verts;
    int32_t yt = v[it].y, ym = v[im].y, yb = v[ib].y, yx;
    if (ym < yt) { yx = yt; yt = ym; ym = yx; ix = it; it = im; im = ix; }
    if (yb < ym) { yx = ym; ym = yb; yb = yx; ix = im; im = ib; ib = ix; }
    if (ym < yt) { yx = yt; yt = ym; ym = yx; ix = it; it = im; im = ix; }
    ScreenVert t = { .x = v[it].x, .y = yt }, m = { .x = v[im].x, .y = ym },
               b = { .x = v[ib].x, .y = yb };
    /* Rows [row(t), row(m)) see the long edge t-b and the upper edge t-m;
     * rows [row(m), row(b)) the long edge and the lower edge m-b. Both
     * count for row j (row(t) <= j < row(b)), so neither setup fails. */
    int32_t rm = sample_ceil(m.y);
    int upper = j < rm;
    const ScreenVert *sa = upper ? &t : &m, *sb = upper ? &m : &b;
    /* The middle corner is on one side of the long edge for the whole
     * triangle, and so is the short edge's crossing on every row (exact
     * crossings only meet at corners; the rounding to columns is
     * monotonic), so left and right are decided once. */
    int64_t cross = ((int64_t)b.x - t.x) * ((int64_t)m.y - t.y) -
                    ((int64_t)b.y - t.y) * ((int64_t)m.x - t.x);
    int side = cross < 0;          /* m right of the long edge */
    if (yend - j == 1) {
        /* One row: only the crossings are needed, and the walkers stay
         * local so the compiler drops their per-row steps. Most such
         * triangles (small ones) cover no sample: when the left crossing
         * is right of the box's last column, the span is empty whatever
         * the right one is, and the second setup is skipped. */
        EdgeWalk el, er;
        const ScreenVert *la = side ? &t : sa, *lb = side ? &b : sb;
        const ScreenVert *ra = side ? sa : &t, *rb = side ? sb : &b;
        if (!edge_setup(&el, la, lb, j) || el.xi >= p->x1 || !edge_setup(&er, ra, rb, j))
            return 0;
        int32_t xa = el.xi, xb = er.xi;
        if (p->x0 == 0 || p->x1 == w) {
            xa = clamp_col(xa, w);
            xb = clamp_col(xb, w);
        }
        return xa < xb ? span_test(s->simd, p, ids, dep, j, xa, xb, w) : 0;
    }
    ScanTri *a = &s->tri[s->ntri++];
    (void)edge_setup(&a->e[!side], &t, &b, j);
    edge_start(&a->e[side], sa, sb, j, (upper ? rm : yend) - j > 1);
    a->side = (int16_t)side;
    a->clip = p->x0 == 0 || p->x1 == w;
    a->a = p->a;
    a->b = p->b;
    a->zc = p->zc;
    a->x0 = p->x0;
    a->y0 = p->y0;
    a->face = p->face;
    a->vm = im;
    a->vb = ib;
    a->ymid = upper ? rm : INT32_MAX;
    a->yend = yend;
    return 0;
}

/* Row j of every active triangle. Steps the walkers to row j + 1 and
 * drops the triangles that end at j. */
static uint64_t tri_row(ScanState *s, const ScreenVert *verts, int j, int32_t *ids, float *dep,
                        int32_t w)
{
    uint64_t n = 0;
    uint32_t k = 0;
    const int simd = s->simd;   /* a local: the stores to ids could alias s */
    while (k < s->ntri) {
        ScanTri *a = &s->tri[k];
        int32_t xa = a->e[0].xi, xb = a->e[1].xi;
        if (a->clip) {
            xa = clamp_col(xa, w);
            xb = clamp_col(xb, w);
        }
        if (xa < xb) {
            ScreenPoly p = tri_plane(a);
            n += span_test(simd, &p, ids, dep, j, xa, xb, w);
        }
        if (j + 1 == a->yend) {
            *a = s->tri[--s->ntri];
            continue;
        }
        if (j + 1 != a->ymid) {
            walk_step(&a->e[0]);
            walk_step(&a->e[1]);
        } else {
            /* the lower short edge takes over */
            int sd = a->side;
            walk_step(&a->e[!sd]);
            edge_start(&a->e[sd], &verts[a->vm], &verts[a->vb], j + 1, a->yend - j > 2);
            a->ymid = INT32_MAX;
        }
        k++;
    }
    return n;
}

/* ==== general polygons (any corner count, concave, self-overlapping) ==== */

static int cmp_edge_row0(const void *a, const void *b)
{
    int32_t x = ((const EdgeWalk *)a)->row0, y = ((const EdgeWalk *)b)->row0;
    return (x > y) - (x < y);
}

/* The edge table of one polygon: its edges by the first row they count
 * for. Insertion sort for the few edges of ordinary polygons, O(n log n)
 * for a polygon of thousands of corners. Edges starting on the same row
 * may land in any order: a row's crossings are sorted anyway. */
static void sort_edges_by_row(EdgeWalk *e, uint32_t n)
{
    if (n > 24) {
        qsort(e, n, sizeof *e, cmp_edge_row0);
        return;
    }
    for (uint32_t i = 1; i < n; i++) {
        EdgeWalk w = e[i];
        uint32_t q = i;
        while (q > 0 && e[q - 1].row0 > w.row0) {
            e[q] = e[q - 1];
            q--;
        }
        e[q] = w;
    }
}

/* Take polygon pi from the polygon table at row j: set up its edges at
 * the first row each counts for and append it to the active list. */
static int gon_start(ScanState *s, const ScreenPolys *sp, uint32_t pi, int j, int yend)
{
    const ScreenPoly *p = &sp->polys[pi];
    uint32_t nv = screen_poly_nverts(sp, pi);
    if (grow_array((void **)&s->pool, &s->pool_cap, s->npool + nv, sizeof *s->pool) ||
        grow_array((void **)&s->xs, &s->xs_cap, nv, sizeof *s->xs) ||
        grow_array((void **)&s->gon, &s->gon_cap, s->ngon + 1, sizeof *s->gon))
        return -1;
    const ScreenVert *v = &sp->verts[p->first];
    EdgeWalk *e = &s->pool[s->npool];
    uint32_t n = 0;
    for (uint32_t k = 0; k < nv; k++) {
        EdgeWalk w;
        if (!edge_setup(&w, &v[k], &v[k + 1 < nv ? k + 1 : 0], j) || w.row1 <= j)
            continue;
        e[n++] = w;
    }
    sort_edges_by_row(e, n);
    if (n < 2)
        return 0;
    s->gon[s->ngon++] = (ScanGon){ .p = p, .off = s->npool, .n = n, .yend = yend };
    s->npool += n;
    return 0;
}

/* Row j of every active general polygon: crossings of its counting edges
 * sorted, pairs filled; edges and polygons that end at j dropped, the
 * pool and the list compacted in order. */
static uint64_t gon_row(ScanState *s, int j, int32_t *ids, float *dep, int32_t w)
{
    uint64_t written = 0;
    uint32_t gout = 0, eout = 0;
    int32_t *xs = s->xs;
    const int simd = s->simd;   /* a local: the stores to ids could alias s */
    for (uint32_t g = 0; g < s->ngon; g++) {
        ScanGon a = s->gon[g];
        EdgeWalk *e = &s->pool[a.off];
        int m = 0;
        uint32_t k = 0;
        /* active edges: the leading ones that have started */
        for (; k < a.n && e[k].row0 <= j; k++)
            xs[m++] = e[k].xi;
        /* the active edges are exactly those counting for row j: their
         * crossings pair up (even-odd), as polywalk_row's do */
        ZV_ASSERT((m & 1) == 0);
        raster_sort_crossings(xs, m);
        for (int i = 0; i + 1 < m; i += 2)
            written += span_pair(simd, a.p, ids, dep, j, xs[i], xs[i + 1], w);
        if (j + 1 == a.yend)
            continue;
        /* step the active edges, keep the unfinished ones and the ones
         * still to come, moving them down to the pool's write point */
        uint32_t off = eout;
        for (uint32_t q = 0; q < a.n; q++) {
            EdgeWalk ew = e[q];
            if (q < k) {
                if (ew.row1 == j + 1)
                    continue;
                edge_step(&ew);
            }
            s->pool[eout++] = ew;
        }
        a.off = off;
        a.n = eout - off;
        s->gon[gout++] = a;
    }
    s->ngon = gout;
    s->npool = eout;
    return written;
}

/* ==== the band ==== */

/* Bucket the polygons meeting rows [y0, y1) by their first row there.
 * Returns -1 on out of memory. */
static int build_table(ScanState *s, const ScreenPolys *sp, int y0, int y1, uint64_t *polys)
{
    uint32_t np = sp->npolys, rows = (uint32_t)(y1 - y0);
    if (grow_array((void **)&s->key, &s->key_cap, np, sizeof *s->key) ||
        grow_array((void **)&s->first, &s->first_cap, np, sizeof *s->first) ||
        grow_array((void **)&s->start, &s->start_cap, rows + 1, sizeof *s->start))
        return -1;
    uint32_t *start = s->start;
    memset(start, 0, (size_t)(rows + 1) * sizeof *start);
    uint16_t *key = s->key;
    uint32_t *first = s->first;
    const ScreenPoly *P = sp->polys;
    for (uint32_t i = 0; i < np; i++) {
        int32_t a = P[i].y0, b = P[i].y1;
        if (b <= y0 || a >= y1) {
            key[i] = KEY_NONE;
            continue;
        }
        uint32_t r = (uint32_t)((a > y0 ? a : y0) - y0);
        /* the corner count rides along (read here in memory order,
         * rather than later at random) */
        key[i] = (uint16_t)(r | (P[i + 1].first - P[i].first == 3 ? 0 : KEY_GON));
        first[i] = P[i].first;
        start[r + 1]++;
    }
    for (uint32_t r = 0; r < rows; r++)
        start[r + 1] += start[r];
    uint32_t total = start[rows];
    *polys += total;
    if (grow_array((void **)&s->order, &s->order_cap, total, sizeof *s->order))
        return -1;
    /* start[r] becomes the fill point of bucket r; after the scatter it is
     * the end of bucket r, i.e. the start of bucket r + 1 */
    ScanEntry *order = s->order;
    for (uint32_t i = 0; i < np; i++) {
        uint32_t k = key[i];
        if (k != KEY_NONE)
            order[start[k & KEY_ROW]++] = (ScanEntry){ i << 1 | (k >> KEY_GON_BIT), first[i] };
    }
    return 0;
}

static void scan_render(void *st, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    ScanState *s = st;
    const ScreenPolys *sp = in->sp;
    int32_t w = fb->w;
    if (y0 >= y1)
        return;
    double t0 = now_ms();
    uint64_t polys = 0, written = 0;
    s->simd = simd_use(in->simd);
    int ok = build_table(s, sp, y0, y1, &polys) == 0;
    if (s->inf_cap < (uint32_t)w && grow_array((void **)&s->inf, &s->inf_cap, (uint32_t)w, sizeof *s->inf) == 0)
        for (uint32_t i = 0; i < s->inf_cap; i++)
            s->inf[i] = INFINITY;
    stats->build_ms += now_ms() - t0;
    stats->polys_in += polys;
    s->ntri = s->ngon = s->npool = 0;
    uint32_t next = 0, total = ok ? s->start[y1 - y0 - 1] : 0;
    for (int j = y0; j < y1; j++) {
        int32_t *ids = fb->ids + (size_t)j * w;
        float *dep = fb->depth + (size_t)j * w;
        memset(ids, 0xff, (size_t)w * sizeof *ids);            /* -1 */
        if (s->inf_cap >= (uint32_t)w)
            memcpy(dep, s->inf, (size_t)w * sizeof *dep);
        else
            for (int32_t i = 0; i < w; i++)
                dep[i] = INFINITY;
        if (!ok)
            continue;   /* out of memory: the rest of the band stays background */
        uint32_t end = s->start[j - y0];
        for (; next < end; next++) {
            /* The table visits polygons out of memory order: fetch the
             * polygon (both lines it may straddle) and its corners
             * PF_AHEAD entries ahead. */
            if (next + PF_AHEAD < total) {
                const ScanEntry *f = &s->order[next + PF_AHEAD];
                const char *q = (const char *)&sp->polys[f->poly >> 1];
                __builtin_prefetch(q);
                __builtin_prefetch(q + sizeof(ScreenPoly) - 1);
                __builtin_prefetch(&sp->verts[f->first]);
            }
            uint32_t o = s->order[next].poly, pi = o >> 1;
            const ScreenPoly *p = &sp->polys[pi];
            int yend = p->y1 < y1 ? p->y1 : y1;
            if (!(o & 1)) {
                if (s->ntri == s->tri_cap && grow_array((void **)&s->tri, &s->tri_cap, s->ntri + 1, sizeof *s->tri)) {
                    ok = 0;
                    break;
                }
                written += tri_start(s, sp, p, j, yend, ids, dep, w);
            } else if (gon_start(s, sp, pi, j, yend)) {
                ok = 0;
                break;
            }
        }
        written += tri_row(s, sp->verts, j, ids, dep, w);
        if (s->ngon)
            written += gon_row(s, j, ids, dep, w);
    }
    stats->pixels_written += written;
}

const HsrAlgo hsr_scanline = {
    .name = "scanline",
    .summary = "scanline z-buffer: polygon and edge tables, active lists, one row at a time",
    .create = scan_create,
    .destroy = scan_destroy,
    .render = scan_render,
};
