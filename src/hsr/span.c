/* span.c: the interval (span) scanline algorithm. No depth row: each row
 * is cut into intervals of samples covered by one constant set of
 * polygons, and each interval is decided as a whole where that is
 * provably what the z-buffer would pick.
 *
 * Per band of rows [y0, y1):
 *  - Polygon table: the band's polygons counting-sorted by their first
 *    row and copied (plane, triangle corners) in that order, so the scan
 *    reads it front to back. When a polygon's row comes it takes a slot
 *    (its plane, depth bounds, in/out state; slots are reused as polygons
 *    finish, so they stay in cache) and its edges are set up with the
 *    exact walkers of raster.h in a reusable edge pool; edges that start
 *    lower down (a triangle's second short edge, n-gon local tops) wait
 *    in their first row's pending list.
 *  - Active edge list: (clamped column, edge) pairs sorted by column.
 *    The row's entering edges are sorted (insertion or 2-pass radix) and
 *    merged in; after edge_step the next row's list is kept sorted by
 *    insertion as it is written, which is near-linear because the order
 *    changes little from one row to the next.
 *  - Each row is one pass over the crossings, left to right. A polygon's
 *    in/out flag toggles at each of its crossings (even-odd), so between
 *    two distinct clamped crossing columns lies an interval [xa, xb)
 *    whose covering set is constant; it is exactly the set of polygons
 *    the z-buffer would test at those samples (rule 3). Every sample of
 *    the band is written once (background included).
 *
 * Deciding an interval (the only place depth matters):
 *  - no polygon: background; one polygon: it wins every sample (the
 *    z-buffer's (inf, -1) background always loses to a non-NaN depth;
 *    polygons whose plane could give NaN or overflow never take a fast
 *    path).
 *  - several, one of whose depth range over its sample box lies wholly
 *    before every other's (hi < lo, bounds with a rounding margin, see
 *    slot_take): it wins every sample strictly, no plane is evaluated.
 *    This settles the front and back of a closed surface at once.
 *  - otherwise evaluate every plane with plane_row/plane_at at xa and
 *    xb - 1. The computed value f differs from the exact affine value g
 *    of the same float coefficients by at most u(|a k| + |f|), u = 2^-24
 *    (one rounding in the product, one in the sum); both magnitudes are
 *    affine in the column, so their maxima M over the interval sit at the
 *    ends. If one polygon w beats every other q at both ends by more than
 *    T = 2^-19 M (four times the 2^-21 M needed: two errors at the end
 *    plus two inside), then g_q - g_w, being affine and above 2E at both
 *    ends, stays above it inside, so f_q > f_w strictly at every sample:
 *    w is the z-buffer's (depth, id) minimum everywhere and fills the
 *    interval (depth = its own plane_at value, as the z-buffer stores).
 *  - otherwise, if the end winners differ (polygons pierce each other),
 *    the interval is split where the two winners' planes cross and both
 *    parts are decided again; if only one end is unsafe it is halved;
 *    small pieces, near-ties at both ends and deep recursion fall back to
 *    a per-sample minimum with hsr_wins over the set, the z-buffer's own
 *    comparison. The split points are heuristics only: correctness rests
 *    on the leaf decisions above.
 * Cyclic overlap needs nothing special: decisions are per interval.
 *
 * Implements the interval scanline of G. S. Watkins, "A Real-Time
 * Visible Surface Algorithm", PhD thesis, University of Utah, 1970:
 * spans between edge crossings decided once each, with exact fallbacks
 * where a span's winner is not provable (piercing, near-ties).
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "invariant.h"
#include "grow.h"
#include "clock.h"
#include "raster.h"
#include "hsr.h"
#include "simd.h"
#include "span.h"
#include "zbuffer.h"

/* A polygon of the table, in first-row order: its index in sp->polys
 * (an index, not a copy: a copy of a big model's polygons and corners
 * would cost tens of MB per frame for little speed). */
typedef struct {
    uint32_t   pi;              /* index in sp->polys */
} PolyRec;

/* A polygon with live edges: its plane and its place in the covering
 * set. Slots are reused as polygons finish, so they stay in cache. */
typedef struct {
    ScreenPoly p;
    int32_t    live;            /* edges active or pending */
    int32_t    inpos;           /* index in the covering set, -1 = out */
    int32_t    ok;              /* plane finite and small: fast paths allowed */
    int32_t    next_free;
    float      lo, hi;          /* bounds of every plane_at() value in the sample box */
} Slot;

/* An edge: the exact walker and its polygon's slot. Edges live in a
 * pool and are reused; sorting moves only (column, edge) pairs. */
typedef struct {
    EdgeWalk e;
    int32_t  slot;
    int32_t  next;              /* pending list of its first row / free list */
} SpanEdge;

/* A crossing: the clamped column clamp_col(xi, w) and the edge. */
typedef struct {
    int32_t key;
    int32_t edge;
} Cross;

/* A polygon currently "in", with its plane row value at this row. */
typedef struct {
    const ScreenPoly *p;        /* the slot's plane (slots do not move during a row) */
    float      zrow;            /* plane_row() at the current row */
    int32_t    face;
    int32_t    slot;
    int32_t    ok;
    float      lo, hi;          /* the slot's depth bounds */
} InPoly;

typedef struct {
    /* polygon table */
    uint32_t *row_start;        /* band rows + 2 offsets into recs */
    int       rows_cap;
    PolyRec  *recs;
    uint32_t  recs_cap;
    /* slots */
    Slot     *slots;
    int       slots_n, slots_cap, slots_free;
    /* edges, and the per-row lists of edges waiting for their first row */
    SpanEdge *edges;
    int       edges_n, edges_cap, edges_free;
    int32_t  *pend_head;
    int       pend_cap;
    /* crossings: active (sorted), next row's, entering, merged */
    Cross    *act, *nxt, *mrg;
    int       act_n, act_cap;
    Cross    *fresh, *fresh_tmp;  /* both hold fresh_cap entries */
    int       fresh_n, fresh_cap;
    /* the covering set */
    InPoly   *in;
    int       in_n, in_cap;
    /* a row of +inf for background fills */
    float    *inf_row;
    int       inf_cap;
    /* per-sample decisions taken on intervals of 2+ samples (analysis) */
    uint64_t  fallback;
    uint64_t  resorted;       /* rows whose next list was radix-sorted (row_pass) */
    uint64_t  covered;
    int       simd;             /* this frame's SimdLevel, resolved (simd_use) */
} SpanState;

static void *span_create(void)
{
    return calloc(1, sizeof(SpanState));
}

static void span_destroy(void *st)
{
    SpanState *s = st;
    if (!s)
        return;
    free(s->row_start);
    free(s->recs);
    free(s->slots);
    free(s->edges);
    free(s->pend_head);
    free(s->act);
    free(s->nxt);
    free(s->mrg);
    free(s->fresh);
    free(s->fresh_tmp);
    free(s->in);
    free(s->inf_row);
    free(s);
}

uint64_t span_fallback_samples(const void *st)
{
    return ((const SpanState *)st)->fallback;
}

uint64_t span_resorted_rows(const void *st)
{
    return ((const SpanState *)st)->resorted;
}

/* grow_array for this file's int counts (never shrinks). */
static int grow(void **p, int *cap, int n, size_t sz)
{
    uint32_t c = (uint32_t)*cap;
    if (n > INT32_MAX / 2 || grow_array(p, &c, (uint32_t)n, sz))
        return -1;
    *cap = c > INT32_MAX ? INT32_MAX : (int)c;
    return 0;
}

/* ==== filling ==== */

static void fill_bg(const SpanState *s, int32_t *ids, float *dep, int xa, int xb)
{
    memset(ids + xa, 0xff, (size_t)(xb - xa) * sizeof *ids);     /* -1 */
    memcpy(dep + xa, s->inf_row, (size_t)(xb - xa) * sizeof *dep);
}

/* Samples [xa, xb) to polygon q (s: for the frame's SIMD level, read only
 * for a run long enough to use it: most are a few samples). */
static void fill_poly(int32_t *ids, float *dep, const InPoly *q, int xa, int xb, const SpanState *s)
{
    ScreenPoly p = *q->p;       /* a local copy: stores cannot alias it */
    float zr = q->zrow;
    int32_t face = q->face;
    int i = xa;
#ifdef ZV_SSE2
    /* plane_at() four samples at a time: the same IEEE operations
     * (convert, multiply, add; no fused multiply-add), so the same bits */
    if (xb - xa >= 8 && s->simd >= SIMD_SSE2) {
        const __m128 va = _mm_set1_ps(p.a), vzr = _mm_set1_ps(zr);
        const __m128i vid = _mm_set1_epi32(face), four = _mm_set1_epi32(4);
        int k0 = xa - p.x0;
        __m128i vk = _mm_setr_epi32(k0, k0 + 1, k0 + 2, k0 + 3);
        for (; i + 4 <= xb; i += 4) {
            _mm_storeu_ps(dep + i, _mm_add_ps(vzr, _mm_mul_ps(va, _mm_cvtepi32_ps(vk))));
            _mm_storeu_si128((__m128i *)(ids + i), vid);
            vk = _mm_add_epi32(vk, four);
        }
    }
#else
    (void)s;
#endif
    for (; i < xb; i++) {
        ids[i] = face;
        dep[i] = plane_at(&p, zr, i);
    }
}

/* The z-buffer's own decision, sample by sample. */
static void fill_per_sample(SpanState *s, int32_t *ids, float *dep, int xa, int xb)
{
    const InPoly *in = s->in;
    int n = s->in_n;
    for (int i = xa; i < xb; i++) {
        float bz = INFINITY;
        int32_t bid = -1;
        for (int k = 0; k < n; k++) {
            float z = plane_at(in[k].p, in[k].zrow, i);
            if (hsr_wins(z, in[k].face, bz, bid)) {
                bz = z;
                bid = in[k].face;
            }
        }
        ids[i] = bid;
        dep[i] = bz;
    }
    s->fallback += (uint64_t)(xb - xa);
}

/* ==== deciding an interval covered by several polygons ==== */

#define SPAN_MAX_DEPTH 24
#define SPAN_MIN_SPLIT 4

static inline float maxf(float a, float b)
{
    return a > b ? a : b;
}

static void resolve(SpanState *s, int32_t *ids, float *dep, int xa, int xb, int depth)
{
    const InPoly *in = s->in;
    int n = s->in_n;
    int xl = xb - 1;
    if (xb - xa <= 1 || depth > SPAN_MAX_DEPTH) {
        fill_per_sample(s, ids, dep, xa, xb);
        return;
    }
    /* end values, end winners and the magnitude bound M */
    int wa = 0, wb = 0;
    float za = INFINITY, zb = INFINITY, mag = 0;
    for (int k = 0; k < n; k++) {
        if (!in[k].ok) {
            fill_per_sample(s, ids, dep, xa, xb);
            return;
        }
        const ScreenPoly *p = in[k].p;
        float pa = p->a * (float)(xa - p->x0), pb = p->a * (float)(xl - p->x0);
        float fa = plane_at(p, in[k].zrow, xa), fb = plane_at(p, in[k].zrow, xl);
        if (k == 0 || hsr_wins(fa, in[k].face, za, in[wa].face)) {
            wa = k;
            za = fa;
        }
        if (k == 0 || hsr_wins(fb, in[k].face, zb, in[wb].face)) {
            wb = k;
            zb = fb;
        }
        float m = maxf(maxf(fabsf(pa), fabsf(pb)), maxf(fabsf(fa), fabsf(fb)));
        mag = maxf(mag, m);
    }
    float t = mag * (1.0f / (1 << 19)) + 1e-30f;
    if (wa == wb) {
        /* safe at each end against every other polygon? */
        int safe_a = 1, safe_b = 1;
        for (int k = 0; k < n; k++) {
            if (k == wa)
                continue;
            float fa = plane_at(in[k].p, in[k].zrow, xa), fb = plane_at(in[k].p, in[k].zrow, xl);
            if (!(fa - za > t))
                safe_a = 0;
            if (!(fb - zb > t))
                safe_b = 0;
        }
        if (safe_a && safe_b) {
            fill_poly(ids, dep, &in[wa], xa, xb, s);
            return;
        }
        if ((!safe_a && !safe_b) || xb - xa <= SPAN_MIN_SPLIT) {
            /* near-equal at both ends: near-equal throughout */
            fill_per_sample(s, ids, dep, xa, xb);
            return;
        }
        int c = xa + (xb - xa) / 2;
        resolve(s, ids, dep, xa, c, depth + 1);
        resolve(s, ids, dep, c, xb, depth + 1);
        return;
    }
    if (xb - xa <= SPAN_MIN_SPLIT) {
        fill_per_sample(s, ids, dep, xa, xb);
        return;
    }
    /* wa wins at xa, wb at xl: split where their planes cross */
    float da = plane_at(in[wb].p, in[wb].zrow, xa) - za;     /* >= 0 */
    float db = zb - plane_at(in[wa].p, in[wa].zrow, xl);     /* <= 0 */
    float den = da - db;
    int c = xa + (xb - xa) / 2;
    if (den > 0 && isfinite(den)) {
        float f = da / den * (float)(xl - xa);
        if (f >= 0 && f < (float)(xl - xa))
            c = xa + (int)f + 1;
    }
    if (c <= xa)
        c = xa + 1;
    if (c >= xb)
        c = xb - 1;
    resolve(s, ids, dep, xa, c, depth + 1);
    resolve(s, ids, dep, c, xb, depth + 1);
}

/* One sample: the z-buffer's minimum, directly. */
static inline void decide_sample(const SpanState *s, int32_t *ids, float *dep, int i)
{
    const InPoly *in = s->in;
    float bz = INFINITY;
    int32_t bid = -1;
    for (int k = 0; k < s->in_n; k++) {
        float z = plane_at(in[k].p, in[k].zrow, i);
        if (hsr_wins(z, in[k].face, bz, bid)) {
            bz = z;
            bid = in[k].face;
        }
    }
    ids[i] = bid;
    dep[i] = bz;
}

/* Two polygons: the test of resolve() written out for the common case
 * (front and back of a closed surface). Returns 0 when undecided. */
static inline int decide_two(const SpanState *s, int32_t *ids, float *dep, int xa, int xb)
{
    const InPoly *u = &s->in[0], *v = &s->in[1];
    if (!u->ok || !v->ok)
        return 0;
    int xl = xb - 1;
    float ua = plane_at(u->p, u->zrow, xa), ub = plane_at(u->p, u->zrow, xl);
    float va = plane_at(v->p, v->zrow, xa), vb = plane_at(v->p, v->zrow, xl);
    float pu = maxf(fabsf(u->p->a * (float)(xa - u->p->x0)), fabsf(u->p->a * (float)(xl - u->p->x0)));
    float pv = maxf(fabsf(v->p->a * (float)(xa - v->p->x0)), fabsf(v->p->a * (float)(xl - v->p->x0)));
    float mag = maxf(maxf(maxf(fabsf(ua), fabsf(ub)), maxf(fabsf(va), fabsf(vb))), maxf(pu, pv));
    float t = mag * (1.0f / (1 << 19)) + 1e-30f;
    if (va - ua > t && vb - ub > t)
        fill_poly(ids, dep, u, xa, xb, s);
    else if (ua - va > t && ub - vb > t)
        fill_poly(ids, dep, v, xa, xb, s);
    else
        return 0;
    return 1;
}

/* Does [xa, xb) lie in the sample box of every polygon covering it?
 * The slots' depth bounds (slot_take) hold over the box only, so the
 * separation test below is sound only inside it. */
static ZV_CHECK_FN int in_boxes(const SpanState *s, int xa, int xb)
{
    for (int k = 0; k < s->in_n; k++)
        if (xa < s->in[k].p->x0 || xb > s->in[k].p->x1)
            return 0;
    return 1;
}

static inline void emit(SpanState *s, int32_t *ids, float *dep, int xa, int xb)
{
    ZV_ASSERT(in_boxes(s, xa, xb));
    int n = s->in_n;
    if (n == 0) {
        fill_bg(s, ids, dep, xa, xb);
        return;
    }
    s->covered += (uint64_t)(xb - xa);
    if (n == 1 && s->in[0].ok) {
        fill_poly(ids, dep, &s->in[0], xa, xb, s);
        return;
    }
    /* one polygon's whole depth range before every other's: it wins
     * every sample strictly (hi < lo), without evaluating a plane */
    const InPoly *in = s->in;
    int best = 0;
    for (int k = 1; k < n; k++)
        if (in[k].hi < in[best].hi)
            best = k;
    int sep = in[best].ok;
    for (int k = 0; k < n && sep; k++)
        sep = k == best || in[best].hi < in[k].lo;
    if (sep)
        fill_poly(ids, dep, &in[best], xa, xb, s);
    else if (xb - xa == 1)
        decide_sample(s, ids, dep, xa);
    else if (n != 2 || !decide_two(s, ids, dep, xa, xb))
        resolve(s, ids, dep, xa, xb, 0);
}

/* Flip a polygon's in/out flag at row j. Returns -1 on OOM. */
static inline int toggle(SpanState *s, int32_t slot, int j)
{
    Slot *sl = &s->slots[slot];
    int n = s->in_n;
    if (sl->inpos >= 0) {
        int k = sl->inpos;
        s->in[k] = s->in[n - 1];
        s->slots[s->in[k].slot].inpos = k;
        sl->inpos = -1;
        s->in_n = n - 1;
        return 0;
    }
    if (n + 1 > s->in_cap && grow((void **)&s->in, &s->in_cap, n + 1, sizeof *s->in))
        return -1;
    InPoly *q = &s->in[n];
    q->p = &sl->p;
    q->face = sl->p.face;
    q->zrow = plane_row(&sl->p, j);
    q->slot = slot;
    q->ok = sl->ok;
    q->lo = sl->lo;
    q->hi = sl->hi;
    sl->inpos = n;
    s->in_n = n + 1;
    return 0;
}

/* ==== edge tables ==== */

/* Sort crossings f[0 .. n) by column, stably, with tmp[n] as scratch:
 * an LSD radix sort in two 8-bit passes (clamped columns are at most
 * SCREEN_MAX = 2^14); the result is back in f. */
static void radix_sort_cross(Cross *f, Cross *t, int n)
{
    uint32_t cnt[256];
    for (int sh = 0; sh < 16; sh += 8) {
        memset(cnt, 0, sizeof cnt);
        for (int i = 0; i < n; i++)
            cnt[(f[i].key >> sh) & 255]++;
        uint32_t sum = 0;
        for (int b = 0; b < 256; b++) {
            uint32_t c = cnt[b];
            cnt[b] = sum;
            sum += c;
        }
        for (int i = 0; i < n; i++)
            t[cnt[(f[i].key >> sh) & 255]++] = f[i];
        Cross *x = f;
        f = t;
        t = x;
    }
    /* two passes: the result is back where it started */
}

/* Sort the entering crossings by column: insertion sort when short,
 * else the radix sort. */
static void sort_fresh(SpanState *s)
{
    int n = s->fresh_n;
    Cross *f = s->fresh;
    if (n < 48) {
        for (int i = 1; i < n; i++) {
            Cross c = f[i];
            int q = i;
            while (q > 0 && f[q - 1].key > c.key) {
                f[q] = f[q - 1];
                q--;
            }
            f[q] = c;
        }
        return;
    }
    radix_sort_cross(f, s->fresh_tmp, n);
}

static int fresh_push(SpanState *s, int32_t key, int32_t edge)
{
    if (s->fresh_n >= s->fresh_cap) {
        int c = s->fresh_cap;
        if (grow((void **)&s->fresh, &c, s->fresh_n + 1, sizeof *s->fresh))
            return -1;
        Cross *t = realloc(s->fresh_tmp, (size_t)c * sizeof *t);
        if (!t)
            return -1;
        s->fresh_tmp = t;
        s->fresh_cap = c;
    }
    s->fresh[s->fresh_n].key = key;
    s->fresh[s->fresh_n].edge = edge;
    s->fresh_n++;
    return 0;
}

static inline void edge_free(SpanState *s, int32_t k)
{
    s->edges[k].next = s->edges_free;
    s->edges_free = k;
}

/* Take a free slot for polygon rec. Returns its index, -1 on OOM. */
static int32_t slot_take(SpanState *s, const ScreenPoly *p)
{
    int32_t k = s->slots_free;
    if (k >= 0) {
        s->slots_free = s->slots[k].next_free;
    } else {
        if (grow((void **)&s->slots, &s->slots_cap, s->slots_n + 1, sizeof *s->slots))
            return -1;
        k = s->slots_n++;
    }
    Slot *sl = &s->slots[k];
    sl->p = *p;
    sl->live = 0;
    sl->inpos = -1;
    sl->ok = fabsf(p->a) < 1e30f && fabsf(p->b) < 1e30f && fabsf(p->zc) < 1e30f;
    /* Depth bounds over the sample box. The exact plane of the float
     * coefficients lies in [zc + min terms, zc + max terms] there; each
     * plane_at() value is within 3u M of it and these sums within 3u M
     * of their exact values (u = 2^-24, M = |zc| + |a| dx + |b| dy), so a
     * 2^-20 M margin (16u M) bounds every value the polygon produces. */
    float ax = p->a * (float)(p->x1 - p->x0), by = p->b * (float)(p->y1 - p->y0);
    float mag = fabsf(p->zc) + fabsf(ax) + fabsf(by);
    float m = mag * (1.0f / (1 << 20)) + 1e-30f;
    sl->hi = (p->zc + (ax > 0 ? ax : 0) + (by > 0 ? by : 0)) + m;
    sl->lo = (p->zc + (ax < 0 ? ax : 0) + (by < 0 ? by : 0)) - m;
    if (!sl->ok) {
        sl->hi = INFINITY;
        sl->lo = -INFINITY;
    }
    return k;
}

static inline void slot_release(SpanState *s, int32_t k)
{
    if (--s->slots[k].live == 0) {
        s->slots[k].next_free = s->slots_free;
        s->slots_free = k;
    }
}

/* Set up a polygon's edges from row j: the ones counting at j enter
 * now, lower ones wait in their first row's pending list. */
static int activate(SpanState *s, const ScreenPolys *sp, const PolyRec *rec, int j, int y0, int y1, int32_t w)
{
    const ScreenPoly *p = &sp->polys[rec->pi];
    uint32_t nv = screen_poly_nverts(sp, rec->pi);
    const ScreenVert *v = &sp->verts[p->first];
    int32_t slot = slot_take(s, p);
    if (slot < 0)
        return -1;
    int live = 0;
    for (uint32_t k = 0; k < nv; k++) {
        EdgeWalk e;
        if (!edge_setup(&e, &v[k], &v[k + 1 < nv ? k + 1 : 0], j) || e.row1 <= j || e.row0 >= y1)
            continue;
        int32_t q = s->edges_free;
        if (q >= 0) {
            s->edges_free = s->edges[q].next;
        } else {
            if (grow((void **)&s->edges, &s->edges_cap, s->edges_n + 1, sizeof *s->edges))
                return -1;
            q = s->edges_n++;
        }
        SpanEdge *se = &s->edges[q];
        se->e = e;
        se->slot = slot;
        live++;
        if (e.row0 <= j) {
            if (fresh_push(s, clamp_col(e.xi, w), q))
                return -1;
        } else {
            se->next = s->pend_head[e.row0 - y0];
            s->pend_head[e.row0 - y0] = q;
        }
    }
    s->slots[slot].live = live + 1;
    slot_release(s, slot);      /* frees it at once when no edge counts */
    return 0;
}

/* Counting sort of the band's polygons by first row, copied into recs. */
static int build_table(SpanState *s, const ScreenPolys *sp, int y0, int y1, uint64_t *npolys)
{
    int rows = y1 - y0;
    if (grow((void **)&s->row_start, &s->rows_cap, rows + 2, sizeof *s->row_start) ||
        grow((void **)&s->pend_head, &s->pend_cap, rows, sizeof *s->pend_head))
        return -1;
    uint32_t *rs = s->row_start;
    memset(rs, 0, (size_t)(rows + 2) * sizeof *rs);
    for (int r = 0; r < rows; r++)
        s->pend_head[r] = -1;
    uint32_t n = 0;
    for (uint32_t i = 0; i < sp->npolys; i++) {
        const ScreenPoly *p = &sp->polys[i];
        if (p->y1 <= y0 || p->y0 >= y1)
            continue;
        int r = p->y0 > y0 ? p->y0 - y0 : 0;
        rs[r + 2]++;
        n++;
    }
    if (n > s->recs_cap) {
        PolyRec *q = realloc(s->recs, (size_t)n * sizeof *q);
        if (!q)
            return -1;
        s->recs = q;
        s->recs_cap = n;
    }
    for (int r = 2; r < rows + 2; r++)
        rs[r] += rs[r - 1];
    /* rs[r + 1] is now the start of row r; placing advances it to the end */
    for (uint32_t i = 0; i < sp->npolys; i++) {
        const ScreenPoly *p = &sp->polys[i];
        if (p->y1 <= y0 || p->y0 >= y1)
            continue;
        int r = p->y0 > y0 ? p->y0 - y0 : 0;
        s->recs[rs[r + 1]++].pi = i;
    }
    *npolys = n;
    return 0;
}

/* ==== the scan ==== */

/* The row's entering crossings (sorted) merged into the active ones
 * (sorted): *m_out the row's crossings in column order, *total their
 * count (the active list itself when none enter, which may be no array
 * at all on an empty row). -1 out of memory. */
static int merge_fresh(SpanState *s, const Cross **m_out, int *total)
{
    int na = s->act_n, nf = s->fresh_n;
    *total = na + nf;
    if (*total > s->act_cap) {
        int cap = s->act_cap, c2 = cap, c3 = cap;
        if (grow((void **)&s->act, &cap, *total, sizeof *s->act) ||
            grow((void **)&s->nxt, &c2, *total, sizeof *s->nxt) ||
            grow((void **)&s->mrg, &c3, *total, sizeof *s->mrg))
            return -1;
        s->act_cap = cap;
    }
    const Cross *act = s->act, *fresh = s->fresh;
    *m_out = act;
    if (nf == 0)
        return 0;
    /* few entering among many active: copy runs of active ones */
    Cross *mrg = s->mrg;
    int ia = 0, k = 0;
    for (int f = 0; f < nf; f++) {
        int32_t key = fresh[f].key;
        int a0 = ia;
        while (ia < na && act[ia].key <= key)
            ia++;
        memcpy(mrg + k, act + a0, (size_t)(ia - a0) * sizeof *mrg);
        k += ia - a0;
        mrg[k++] = fresh[f];
    }
    memcpy(mrg + k, act + ia, (size_t)(na - ia) * sizeof *mrg);
    *m_out = mrg;
    return 0;
}

/* Row j: one pass over its crossings m[0 .. total), left to right, each
 * interval between two decided and written; the edges that go on are
 * stepped into the next row's list, kept sorted. -1 out of memory. */
static int row_pass(SpanState *s, int32_t *ids, float *dep, int j, int32_t w, const Cross *m, int total)
{
    Cross *nxt = s->nxt;
    SpanEdge *edges = s->edges;
    int nb = 0, cur = 0;
    /* Insertion keeps the next row sorted in near-linear time while the
     * order changes little; where many edges cross each other (a
     * wireframe in a small picture) its moves grow with the square of
     * the row's crossings, so past a budget the rest is appended and the
     * whole list radix-sorted at the end. Both sorts are stable, so the
     * list is the same either way. */
    long moves = 0, budget = 16L * total + 1024;
    int sorted = 1;
    for (int k = 0; k < total; k++) {
        int x = m[k].key;
        int32_t ei = m[k].edge;
        /* sorted by column: each [cur, x) has one covering set, and the
         * row's intervals tile it, every sample written once */
        ZV_ASSERT(x >= cur);
        if (x > cur) {
            emit(s, ids, dep, cur, x);
            cur = x;
        }
        SpanEdge *e = &edges[ei];
        if (toggle(s, e->slot, j))
            return -1;
        if (e->e.row1 > j + 1) {
            edge_step(&e->e);
            /* keep sorted: the order changes little from row to row */
            int32_t kx = clamp_col(e->e.xi, w);
            int q = nb++;
            if (sorted) {
                while (q > 0 && nxt[q - 1].key > kx) {
                    nxt[q] = nxt[q - 1];
                    q--;
                }
                moves += nb - 1 - q;
                sorted = moves <= budget;
            }
            nxt[q].key = kx;
            nxt[q].edge = ei;
        } else {
            slot_release(s, e->slot);
            edge_free(s, ei);
        }
    }
    /* every polygon's crossings of the row pair up (even-odd): past the
     * last one none is in, and the next row starts from none */
    ZV_ASSERT(s->in_n == 0);
    if (cur < w)
        emit(s, ids, dep, cur, w);
    /* m (which may be s->mrg) is read to the end: mrg is free scratch */
    if (!sorted) {
        radix_sort_cross(nxt, s->mrg, nb);
        s->resorted++;
    }
    s->nxt = s->act;
    s->act = nxt;
    s->act_n = nb;
    return 0;
}

/* Row j's entering crossings: the polygons whose first row it is, set
 * up (fetching a few ahead), and the edges pending for it. -1 out of
 * memory. */
static int enter_row(SpanState *s, const ScreenPolys *sp, int j, int y0, int y1, int32_t w)
{
    int r = j - y0;
    s->fresh_n = 0;
    for (uint32_t k = s->row_start[r]; k < s->row_start[r + 1]; k++) {
        /* the table holds indices: fetch a few polygons ahead */
        if (k + 8 < s->row_start[r + 1]) {
            const ScreenPoly *ahead = &sp->polys[s->recs[k + 8].pi];
            __builtin_prefetch(ahead);
            __builtin_prefetch(&sp->verts[ahead->first]);
        }
        if (activate(s, sp, &s->recs[k], j, y0, y1, w))
            return -1;
    }
    for (int32_t q = s->pend_head[r]; q >= 0; q = s->edges[q].next)
        if (fresh_push(s, clamp_col(s->edges[q].e.xi, w), q))
            return -1;
    sort_fresh(s);
    return 0;
}

static void span_render(void *st, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    SpanState *s = st;
    const ScreenPolys *sp = in->sp;
    int32_t w = fb->w;
    double t0 = now_ms();
    uint64_t npolys = 0;
    s->act_n = 0;
    s->in_n = 0;
    s->edges_n = 0;
    s->edges_free = -1;
    s->slots_n = 0;
    s->slots_free = -1;
    s->covered = 0;
    s->simd = simd_use(in->simd);
    if (w > s->inf_cap) {
        float *r = realloc(s->inf_row, (size_t)w * sizeof *r);
        if (!r)
            goto oom;
        s->inf_row = r;
        s->inf_cap = w;
        for (int i = 0; i < w; i++)
            r[i] = INFINITY;
    }
    if (build_table(s, sp, y0, y1, &npolys))
        goto oom;
    stats->build_ms += now_ms() - t0;
    stats->polys_in += npolys;

    for (int j = y0; j < y1; j++) {
        int total;
        const Cross *m;
        if (enter_row(s, sp, j, y0, y1, w) || merge_fresh(s, &m, &total) ||
            row_pass(s, fb->ids + (size_t)j * w, fb->depth + (size_t)j * w, j, w, m, total))
            goto oom;
    }
    stats->pixels_written += s->covered;
    return;
oom:
    /* out of memory: leave a defined image (background) */
    fbuf_clear_rows(fb, y0, y1);
}

const HsrAlgo hsr_span = {
    .name = "span",
    .summary = "interval scanline: whole spans decided at their ends",
    .create = span_create,
    .destroy = span_destroy,
    .render = span_render,
};
