/* fins.c: the non-manifold edges and vertices, split.
 *
 * An edge of three or more faces (a fin, two solids sharing an edge) is
 * resolved by choosing which of its faces go together: they are sorted
 * by angle around the edge, and two neighbours in that order go
 * together when the wedge between them lies behind both (the inside of
 * one solid), the pairing a solid's faces make when they are wound
 * consistently; faces left over are paired with a neighbour of the
 * other direction, then with any neighbour, and an odd one out is cut
 * loose (its edge becomes a boundary). Then, as in the check, the
 * corners around each point fall into fans (corners joined across each
 * paired edge); a point where two fans or more meet keeps its vertex
 * for the first fan and gets a new vertex for each other, which splits
 * the fins and the points where solids touch (two cones tip to tip).
 *
 * The check takes vertices at one position as one point, so a copy at
 * the same place would change nothing: each copy is moved off the
 * point, by the least that makes it a point of its own (a few units in
 * the last place, growing by fours up to an eighth of its shortest
 * edge), towards the middle of the fan's other corners (the fan shrinks
 * into itself, away from the fans it met: into the solid whose corner
 * it is), and only where no face of the fan becomes degenerate.
 * MeshLab's "split non-manifold vertices" moves its copies likewise (by
 * a fraction of the edges). A fan no move fits keeps its point (the
 * check still reports it). The check's crossing test is exact, so a
 * move of next to nothing can still make faces cross: moves_settle
 * puts back every fan whose faces cross more pairs than before. */

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "repair_internal.h"

/* ==== Pairing the faces around a non-manifold edge ==== */

typedef struct {
    double   angle;             /* of the face around the edge */
    uint32_t he;                /* its half-edge */
    int      dir;               /* +1: runs from the edge's smaller point */
    int      paired;
} Wing;

static int cmp_wing(const void *x, const void *y)
{
    const Wing *a = x, *b = y;
    return a->angle < b->angle ? -1 : a->angle > b->angle ? 1 : a->he < b->he ? -1 : a->he > b->he;
}

static void sub3(const float *a, const float *b, double d[3])
{
    for (int i = 0; i < 3; i++)
        d[i] = (double)a[i] - b[i];
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The faces' angles around the edge of half-edge h0, from its smaller
 * point a. */
static void wings_measure(const Rep *r, const ObjTopo *t, uint32_t h0, Wing *w, uint32_t k)
{
    uint32_t n0 = rp_next(r, t, h0), a = rp_cpt(r, t, h0) < rp_cpt(r, t, n0) ? rp_cpt(r, t, h0) : rp_cpt(r, t, n0);
    const float *pa = rp_vpos(r, rp_cvert(r, t, rp_cpt(r, t, h0) == a ? h0 : n0));
    const float *pb = rp_vpos(r, rp_cvert(r, t, rp_cpt(r, t, h0) == a ? n0 : h0));
    double d[3], axis[3] = { 0, 0, 0 }, e1[3], e2[3];
    sub3(pb, pa, d);
    int least = fabs(d[0]) <= fabs(d[1]) && fabs(d[0]) <= fabs(d[2]) ? 0 : fabs(d[1]) <= fabs(d[2]) ? 1 : 2;
    axis[least] = 1;
    cross3(d, axis, e1);
    cross3(d, e1, e2);
    for (uint32_t i = 0; i < k; i++) {
        uint32_t h = w[i].he, wing = rp_next(r, t, rp_next(r, t, h));
        double u[3];
        sub3(rp_vpos(r, rp_cvert(r, t, wing)), pa, u);
        w[i].angle = atan2(dot3(u, e2), dot3(u, e1));
        w[i].dir = rp_cpt(r, t, h) == a ? 1 : -1;
        w[i].paired = 0;
    }
}

static void pair_two(ObjTopo *t, Wing *x, Wing *y)
{
    x->paired = y->paired = 1;
    t->mate[x->he] = y->he;
    t->mate[y->he] = x->he;
}

/* The faces of one non-manifold edge paired (mates), the rest cut loose:
 * half-edge h cut, its ends a and b. */
static int cut_add(Cuts *cu, uint32_t h, uint32_t a, uint32_t b)
{
    if (cu->n == cu->cap) {
        uint32_t c = cu->cap ? cu->cap * 2 : 16;
        uint32_t *v = realloc(cu->v, 2 * (size_t)c * sizeof *v);
        if (!v)
            return -1;
        cu->v = v;
        uint32_t *he = realloc(cu->he, (size_t)c * sizeof *he);
        if (!he)
            return -1;
        cu->he = he;
        cu->cap = c;
    }
    cu->he[cu->n] = h;
    cu->v[2 * cu->n] = a;
    cu->v[2 * cu->n++ + 1] = b;
    return 0;
}

static int pair_group(const Rep *r, ObjTopo *t, const uint32_t *he, uint32_t k, Wing *w, uint32_t *rest, Cuts *cu)
{
    for (uint32_t i = 0; i < k; i++)
        w[i].he = he[i];
    wings_measure(r, t, he[0], w, k);
    qsort(w, k, sizeof *w, cmp_wing);
    /* the wedges behind both their faces: a face whose back faces the
     * way the angle grows (dir -1), then one whose back faces back */
    for (uint32_t i = 0; i < k; i++) {
        Wing *x = &w[i], *y = &w[(i + 1) % k];
        if (!x->paired && !y->paired && x->dir < 0 && y->dir > 0)
            pair_two(t, x, y);
    }
    for (int pass = 0; pass < 2; pass++) {
        uint32_t n = 0;
        for (uint32_t i = 0; i < k; i++)
            if (!w[i].paired)
                rest[n++] = i;
        for (uint32_t i = 0; i + 1 < n;) {
            Wing *x = &w[rest[i]], *y = &w[rest[i + 1]];
            if (pass == 1 || x->dir != y->dir) {
                pair_two(t, x, y);
                i += 2;
            } else {
                i++;
            }
        }
    }
    /* the odd one out (one at most): its half-edge, until the split says
     * which vertices it ends on */
    for (uint32_t i = 0; i < k; i++)
        if (!w[i].paired) {
            t->mate[w[i].he] = RP_BOUNDARY;
            if (cut_add(cu, w[i].he, w[i].he, RP_NONE))
                return -1;
        }
    return 0;
}

static int pair_groups(const Rep *r, ObjTopo *t, Cuts *cu)
{
    uint32_t maxk = 0;
    for (uint32_t g = 0; g < t->nm_ngroup; g++)
        if (t->nm_group[g + 1] - t->nm_group[g] > maxk)
            maxk = t->nm_group[g + 1] - t->nm_group[g];
    Wing *w = malloc(((size_t)maxk + 1) * sizeof *w);
    uint32_t *rest = malloc(((size_t)maxk + 1) * sizeof *rest);
    if (!w || !rest) {
        free(w);
        free(rest);
        return -1;
    }
    int rc = 0, odd_whole = r->level[t->obj] >= RP_LEVEL_NO_CUTS;
    for (uint32_t g = 0; rc == 0 && g < t->nm_ngroup; g++) {
        uint32_t k = t->nm_group[g + 1] - t->nm_group[g];
        /* held back (guard.c): a fin of an odd number stays whole */
        if (!(odd_whole && k % 2))
            rc = pair_group(r, t, t->nm_half + t->nm_group[g], k, w, rest, cu);
    }
    free(w);
    free(rest);
    return rc;
}

/* ==== Fans ==== */

/* Join the corners at each end of the paired edge of half-edges c and m. */
static void join_pair(const Rep *r, const ObjTopo *t, uint32_t *uf, uint32_t c, uint32_t m)
{
    uint32_t n1 = rp_next(r, t, c), n2 = rp_next(r, t, m);
    if (rp_cpt(r, t, c) != rp_cpt(r, t, m)) {
        rp_uf_union(uf, c, n2);
        rp_uf_union(uf, n1, m);
    } else {
        rp_uf_union(uf, c, m);
        rp_uf_union(uf, n1, n2);
    }
}

/* The fans: corners joined across every paired edge (and, with groups,
 * all the corners at each end of each non-manifold edge still unpaired,
 * as the check counts non-manifold vertices). */
static uint32_t *fans(const Rep *r, const ObjTopo *t, int groups)
{
    uint32_t *uf = rp_uf_new(t->nc);
    if (!uf)
        return NULL;
    for (uint32_t c = 0; c < t->nc; c++) {
        uint32_t m = t->mate[c];
        if (m < RP_SPECIAL && c < m)
            join_pair(r, t, uf, c, m);
        else if (m == RP_SELF)
            rp_uf_union(uf, c, rp_next(r, t, c));
    }
    for (uint32_t g = 0; groups && g < t->nm_ngroup; g++) {
        const uint32_t *h = t->nm_half + t->nm_group[g];
        if (t->mate[h[0]] != RP_NONMANIF)
            continue;           /* paired: its faces are joined pair by pair */
        uint32_t n = t->nm_group[g + 1] - t->nm_group[g], a = rp_cpt(r, t, h[0]);
        for (uint32_t k = 1; k < n; k++) {
            uint32_t nk = rp_next(r, t, h[k]), n0 = rp_next(r, t, h[0]);
            int from_a = rp_cpt(r, t, h[k]) == a;
            rp_uf_union(uf, h[0], from_a ? h[k] : nk);
            rp_uf_union(uf, n0, from_a ? nk : h[k]);
        }
    }
    for (uint32_t c = 0; c < t->nc; c++)
        uf[c] = rp_uf_find(uf, c);
    return uf;
}

/* ==== Splitting a point ==== */

/* The fans moved: each one's faces, and the copies it made. */
typedef struct {
    uint32_t *face, *group;     /* per entry: a relative face of a fan, and the fan */
    uint32_t  n, cap;
    uint32_t *first, *count;    /* per fan: its copies (consecutive vertices) */
    uint8_t  *dead;             /* per fan: put back */
    uint32_t  nfans, fcap;
} Moved;

typedef struct {
    Moved    *mv;
    uint32_t *off, *list;       /* each point's corners (counting sort) */
    uint64_t *key;              /* scratch: (fan, corner) of one point's corners */
    uint8_t  *in;               /* per corner: in the fan being moved */
    const float **fp;           /* scratch: one face's corner positions */
    uint32_t *verts;            /* scratch: a fan's distinct vertices and their copies */
} Split;

/* Does every face of the fan (corners c[0..n)) keep three points off one
 * line with its point at q? */
static int fan_faces_sound(const Rep *r, const ObjTopo *t, Split *s, const uint32_t *c, uint32_t n, const float *q)
{
    for (uint32_t i = 0; i < n; i++) {
        uint32_t f = rp_cface(t, c[i]), a = rp_start(r, t, f), e = rp_start(r, t, f + 1);
        for (uint32_t k = a; k < e; k++)
            s->fp[k - a] = s->in[k] ? q : rp_vpos(r, rp_cvert(r, t, k));
        if (rp_pos_degenerate(s->fp, e - a))
            return 0;
    }
    return 1;
}

/* Where the fan's copy of point P goes: *out, or 0 when no move fits. */
static int fan_place(Rep *r, const ObjTopo *t, Split *s, const uint32_t *c, uint32_t n, float out[3])
{
    const float *P = rp_vpos(r, rp_cvert(r, t, c[0]));
    double dir[3] = { 0, 0, 0 }, cen[3] = { 0, 0, 0 }, shortest = INFINITY;
    for (uint32_t i = 0; i < n; i++) {
        double a[3], b[3], x[3];
        sub3(rp_vpos(r, rp_cvert(r, t, rp_next(r, t, c[i]))), P, a);
        sub3(rp_vpos(r, rp_cvert(r, t, rp_prev(r, t, c[i]))), P, b);
        cross3(a, b, x);
        for (int k = 0; k < 3; k++) {
            dir[k] -= x[k];
            cen[k] += a[k] + b[k];
        }
        double la = sqrt(dot3(a, a)), lb = sqrt(dot3(b, b));
        shortest = la > 0 && la < shortest ? la : shortest;
        shortest = lb > 0 && lb < shortest ? lb : shortest;
    }
    /* towards the middle of the fan's own corners: the fan shrinks into
     * itself, away from the fans it met; behind it (against its normals)
     * when its corners balance out */
    double len = sqrt(dot3(cen, cen));
    if (len > 0) {
        memcpy(dir, cen, sizeof dir);
    } else {
        len = sqrt(dot3(dir, dir));
    }
    if (!(len > 0) || !isfinite(shortest))
        return 0;
    double big = fmax(fabs(P[0]), fmax(fabs(P[1]), fabs(P[2])));
    double ulp = big > 0 ? ldexp(1.0, ilogb(big) - 23) : FLT_TRUE_MIN;
    double step = fmax(4 * ulp, shortest * 0x1p-24);
    for (int tries = 0; tries < 16 && step <= shortest / 8; tries++, step *= 4) {
        for (int k = 0; k < 3; k++)
            out[k] = (float)(P[k] + step * dir[k] / len);
        if ((out[0] != P[0] || out[1] != P[1] || out[2] != P[2]) && isfinite(out[0]) && isfinite(out[1]) &&
            isfinite(out[2]) && rp_point_find(r, out) == RP_NONE && fan_faces_sound(r, t, s, c, n, out))
            return 1;
    }
    return 0;
}

static int moved_add(Moved *mv, uint32_t face, uint32_t group)
{
    if (mv->n == mv->cap) {
        uint32_t c = mv->cap ? mv->cap * 2 : 64;
        uint32_t *a = realloc(mv->face, (size_t)c * sizeof *a);
        if (!a)
            return -1;
        mv->face = a;
        uint32_t *b = realloc(mv->group, (size_t)c * sizeof *b);
        if (!b)
            return -1;
        mv->group = b;
        mv->cap = c;
    }
    mv->face[mv->n] = face;
    mv->group[mv->n++] = group;
    return 0;
}

static int moved_fan(Moved *mv, uint32_t first)
{
    if (mv->nfans == mv->fcap) {
        uint32_t c = mv->fcap ? mv->fcap * 2 : 16;
        uint32_t *a = realloc(mv->first, (size_t)c * sizeof *a);
        if (!a)
            return -1;
        mv->first = a;
        uint32_t *b = realloc(mv->count, (size_t)c * sizeof *b);
        if (!b)
            return -1;
        mv->count = b;
        uint8_t *d = realloc(mv->dead, c);
        if (!d)
            return -1;
        mv->dead = d;
        mv->fcap = c;
    }
    mv->first[mv->nfans] = first;
    mv->count[mv->nfans] = 0;
    mv->dead[mv->nfans++] = 0;
    return 0;
}

static void moved_free(Moved *mv)
{
    free(mv->face);
    free(mv->group);
    free(mv->first);
    free(mv->count);
    free(mv->dead);
}

/* Give the fan of corners c[0..n) (all at one point) a new point:
 * each vertex of it a copy there. 1 split, 0 no move fits, -1 out of memory. */
static int fan_split(Rep *r, ObjTopo *t, Split *s, const uint32_t *c, uint32_t n)
{
    float q[3];
    for (uint32_t i = 0; i < n; i++)
        s->in[c[i]] = 1;
    int ok = fan_place(r, t, s, c, n, q);
    if (ok > 0 && moved_fan(s->mv, r->w.nverts))
        ok = -1;
    uint32_t nv = 0, g = s->mv->nfans - 1;
    for (uint32_t i = 0; ok && i < n; i++) {
        uint32_t v = rp_cvert(r, t, c[i]), k = 0;
        while (k < nv && s->verts[2 * k] != v)
            k++;
        if (k == nv) {
            uint32_t copy = rp_vertex_add(r, q, r->w.rgb ? r->w.rgb + 3 * (size_t)v : NULL, v);
            if (copy == RP_NONE) {
                ok = -1;
                break;
            }
            s->verts[2 * k] = v;
            s->verts[2 * k + 1] = copy;
            nv++;
            s->mv->count[g]++;
            r->rep->split_vertices++;
        }
        r->w.corner[t->c0 + c[i]] = s->verts[2 * k + 1];
        if (moved_add(s->mv, rp_cface(t, c[i]), g))
            ok = -1;
    }
    for (uint32_t i = 0; i < n; i++)
        s->in[c[i]] = 0;
    return ok;
}

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

/* Point p's corners by fan; every fan but the first split off. 1 when
 * any was, -1 out of memory. */
static int point_split(Rep *r, ObjTopo *t, Split *s, const uint32_t *uf, uint32_t p)
{
    const uint32_t *c = s->list + s->off[p];
    uint32_t n = s->off[p + 1] - s->off[p], i = 1;
    while (i < n && uf[c[i]] == uf[c[0]])
        i++;
    if (i >= n)
        return 0;
    for (uint32_t k = 0; k < n; k++)
        s->key[k] = (uint64_t)uf[c[k]] << 32 | c[k];
    qsort(s->key, n, sizeof *s->key, cmp_u64);
    for (uint32_t k = 0; k < n; k++)
        s->list[s->off[p] + k] = (uint32_t)s->key[k];
    int any = 0;
    /* the fan of the smallest root (the first in corner order) stays */
    for (uint32_t a = 0; a < n;) {
        uint32_t b = a + 1;
        while (b < n && s->key[b] >> 32 == s->key[a] >> 32)
            b++;
        if (a > 0) {
            int rc = fan_split(r, t, s, s->list + s->off[p] + a, b - a);
            if (rc < 0)
                return -1;
            any |= rc;
        }
        a = b;
    }
    return any;
}

static int split_points(Rep *r, ObjTopo *t, const uint32_t *uf, const uint8_t *nmv, Moved *mv)
{
    Split s = { .mv = mv };
    uint32_t maxf = 0, maxdeg = 0;
    for (uint32_t f = 0; f < t->nf; f++)
        maxf = rp_start(r, t, f + 1) - rp_start(r, t, f) > maxf ? rp_start(r, t, f + 1) - rp_start(r, t, f) : maxf;
    s.off = rp_big(((size_t)t->npts + 2) * sizeof *s.off, 1);
    s.list = rp_big(((size_t)t->nc + 1) * sizeof *s.list, 0);
    s.in = rp_big((size_t)t->nc + 1, 1);
    s.fp = malloc(((size_t)maxf + 1) * sizeof *s.fp);
    int rc = -1;
    if (!s.off || !s.list || !s.in || !s.fp)
        goto out;
    for (uint32_t c = 0; c < t->nc; c++)
        if (t->mate[c] != RP_SKIPPED)
            s.off[rp_cpt(r, t, c) + 1]++;
    for (uint32_t p = 0; p < t->npts; p++) {
        maxdeg = s.off[p + 1] > maxdeg ? s.off[p + 1] : maxdeg;
        s.off[p + 1] += s.off[p];
    }
    for (uint32_t c = 0; c < t->nc; c++)
        if (t->mate[c] != RP_SKIPPED)
            s.list[s.off[rp_cpt(r, t, c)]++] = c;
    memmove(s.off + 1, s.off, (size_t)t->npts * sizeof *s.off);
    s.off[0] = 0;
    s.key = malloc(((size_t)maxdeg + 1) * sizeof *s.key);
    s.verts = malloc(2 * ((size_t)maxdeg + 1) * sizeof *s.verts);
    if (!s.key || !s.verts)
        goto out;
    rc = 0;
    for (uint32_t p = 0; p < t->npts && rc >= 0; p++) {
        rc = point_split(r, t, &s, uf, p);
        if (rc > 0 && nmv[p])
            r->rep->nm_vertices++;
    }
    rc = rc < 0 ? -1 : 0;
out:
    free(s.off);
    free(s.list);
    free(s.in);
    free(s.fp);
    free(s.key);
    free(s.verts);
    return rc;
}

/* ==== Moves that cross ==== */

/* Fan g's copies back to the vertices they copy. */
static void fan_back(Rep *r, ObjTopo *t, Moved *mv, uint32_t g)
{
    for (uint32_t i = 0; i < mv->n; i++) {
        if (mv->group[i] != g)
            continue;
        uint32_t f = mv->face[i];
        for (uint32_t c = rp_start(r, t, f); c < rp_start(r, t, f + 1); c++) {
            uint32_t *v = &r->w.corner[t->c0 + c];
            if (*v >= mv->first[g] && *v - mv->first[g] < mv->count[g])
                *v = r->anchor[*v];
        }
    }
    mv->dead[g] = 1;
    r->rep->split_vertices -= mv->count[g];
}

/* A copy moves by next to nothing, but the check's crossing test is
 * exact: each fan whose faces cross more pairs (the object's faces near
 * them, the other fans) where they are now than where they were goes
 * back, fans at a time, until none does (four rounds, then every fan
 * left goes back). */
static int moves_settle(Rep *r, ObjTopo *t, Moved *mv, uint32_t vbase)
{
    uint32_t *face = malloc(((size_t)mv->n + 1) * sizeof *face), *group = malloc(((size_t)mv->n + 1) * sizeof *group);
    uint32_t *was = malloc(((size_t)mv->nfans + 1) * sizeof *was), *now = malloc(((size_t)mv->nfans + 1) * sizeof *now);
    int rc = -1;
    if (!face || !group || !was || !now)
        goto out;
    for (int round = 0; round < 5; round++) {
        uint32_t n = 0, alive = 0;
        for (uint32_t i = 0; i < mv->n; i++)
            if (!mv->dead[mv->group[i]]) {
                face[n] = mv->face[i];
                group[n++] = mv->group[i];
            }
        for (uint32_t g = 0; g < mv->nfans; g++)
            alive += !mv->dead[g];
        if (!alive)
            break;
        int unsure0 = 0, unsure1 = 0, worse = 0;
        if (round == 4 || rp_moved_cross(r, t, face, group, n, vbase, 1, was, mv->nfans, &unsure0) ||
            rp_moved_cross(r, t, face, group, n, vbase, 0, now, mv->nfans, &unsure1)) {
            if (round < 4)
                goto out;
            unsure0 = 1;        /* the last round: whatever is left goes back */
        }
        for (uint32_t g = 0; g < mv->nfans; g++)
            if (!mv->dead[g] && (unsure0 || unsure1 || now[g] > was[g])) {
                fan_back(r, t, mv, g);
                worse = 1;
            }
        if (!worse)
            break;
    }
    rc = 0;
out:
    free(face);
    free(group);
    free(was);
    free(now);
    return rc;
}

/* ==== The step ==== */

/* Points with two fans or more in uf: nm[p] set (when nm), and how many. */
static int multi_fans(const Rep *r, const ObjTopo *t, const uint32_t *uf, uint8_t *nm, uint32_t *count)
{
    uint32_t *first = rp_big(((size_t)t->npts + 1) * sizeof *first, 0), n = 0;
    if (!first)
        return -1;
    memset(first, 0xff, ((size_t)t->npts + 1) * sizeof *first);
    for (uint32_t c = 0; c < t->nc; c++) {
        if (t->mate[c] == RP_SKIPPED)
            continue;
        uint32_t p = rp_cpt(r, t, c);
        if (first[p] == RP_NONE) {
            first[p] = uf[c];
        } else if (first[p] != uf[c] && first[p] != RP_NONE - 1) {
            first[p] = RP_NONE - 1;     /* counted */
            n++;
            if (nm)
                nm[p] = 1;
        }
    }
    free(first);
    *count = n;
    return 0;
}

int rp_manifold(Rep *r, ObjTopo *t, Cuts *cu)
{
    uint32_t groups = t->nm_ngroup, added = r->w.nverts, multi = 0;
    uint8_t *nmv = rp_big((size_t)t->npts + 1, 1);
    Moved mv = { 0 };
    /* the points the check calls non-manifold: two fans or more with
     * the corners at each end of a non-manifold edge joined */
    uint32_t *uf = nmv ? fans(r, t, 1) : NULL;
    int rc = -1;
    memset(cu, 0, sizeof *cu);
    cu->vbase = r->w.nverts;
    if (!uf || multi_fans(r, t, uf, nmv, &multi))
        goto out;
    if (groups) {
        free(uf);
        uf = NULL;
        if (pair_groups(r, t, cu) || !(uf = fans(r, t, 1)) || multi_fans(r, t, uf, NULL, &multi))
            goto out;
    }
    if (multi && (split_points(r, t, uf, nmv, &mv) || (mv.nfans && moves_settle(r, t, &mv, cu->vbase))))
        goto out;
    /* each cut half-edge by the vertices it now ends on */
    for (uint32_t k = 0; k < cu->n; k++) {
        uint32_t h = cu->v[2 * k];
        cu->v[2 * k] = rp_cvert(r, t, h);
        cu->v[2 * k + 1] = rp_cvert(r, t, rp_next(r, t, h));
    }
    rc = 0;
    if (r->w.nverts != added || groups) {
        rc = rp_topo_pair(r, t, 1);
        if (rc == 0 && groups > t->nm_ngroup)
            r->rep->nm_edges += groups - t->nm_ngroup;
    }
out:
    free(uf);
    free(nmv);
    moved_free(&mv);
    return rc;
}

/* ==== Cuts the holes did not close ==== */

typedef struct {
    uint64_t *key;
    size_t    size;
} KeySet;

static size_t key_slot(const KeySet *ks, uint64_t k)
{
    size_t mask = ks->size - 1, h = (size_t)((k * 0x9E3779B97F4A7C15ull) >> 21) & mask;
    /* invariant: at most half full */
    while (ks->key[h] != UINT64_MAX && ks->key[h] != k)
        h = (h + 1) & mask;
    return h;
}

static void key_put(KeySet *ks, uint64_t k)
{
    ks->key[key_slot(ks, k)] = k;
}

static int key_has(const KeySet *ks, uint64_t k)
{
    return ks->key[key_slot(ks, k)] == k;
}

static uint64_t vpair(uint32_t a, uint32_t b)
{
    return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
}

/* ==== Stray fins ====
 *
 * A cut loose face that no fill closed is a stray fin when the part it
 * is in (its faces joined by paired edges) is small (RP_FIN_FACES faces
 * at most), has no edge of three faces left, and is open all round: its
 * every boundary edge is on a loop left open along its cuts (the loops
 * holes.c put aside for them), none closed by a fill and none listed
 * open apart (with the holes step not asked, no loop is either). Such a part encloses nothing and stands on what it was cut
 * from by an edge alone: the cube's fin of tests/e2e/brokenstl.py, a
 * stray triangle on an edge, as admesh deletes it. It is dropped, and
 * what it stood on is as if it had never been there; put back, it
 * would leave the edge non-manifold and its rim open. A part of more
 * faces, or one that a fill closed, is kept (a model's own thin wall,
 * a tiny solid). */

/* The faces of cut k's part into part[] (room for RP_FIN_FACES) and
 * its boundary half-edges into *nb, when it is small, manifold and
 * no fill closes an edge of it: how many faces, else 0. */
static uint32_t fin_part(const Rep *r, const ObjTopo *t, const Cuts *cu, uint32_t k, const KeySet *ks, uint32_t *part,
                         uint32_t *nb)
{
    uint32_t n = 0;
    part[n++] = rp_cface(t, cu->he[k]);
    *nb = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t f = part[i];
        for (uint32_t c = rp_start(r, t, f); c < rp_start(r, t, f + 1); c++) {
            uint32_t m = t->mate[c];
            if (m == RP_SELF)
                continue;
            if (m == RP_NONMANIF || m == RP_SKIPPED)
                return 0;
            if (m == RP_BOUNDARY) {
                if (key_has(ks, vpair(rp_cvert(r, t, c), rp_cvert(r, t, rp_next(r, t, c)))))
                    return 0;
                (*nb)++;
                continue;
            }
            uint32_t g = rp_cface(t, m), j = 0;
            while (j < n && part[j] != g)
                j++;
            if (j < n)
                continue;
            if (n == RP_FIN_FACES)
                return 0;
            part[n++] = g;
        }
    }
    return n;
}

/* Mark fin[k] for each cut no fill closed whose part is a stray fin
 * (every cut of that part), and its faces in t->skip and drop[]; the
 * faces marked are counted in *faces. */
static void stray_fins(Rep *r, ObjTopo *t, const Cuts *cu, const KeySet *ks, uint8_t *fin, uint8_t *drop,
                       uint32_t *faces)
{
    uint32_t part[RP_FIN_FACES];
    *faces = 0;
    for (uint32_t k = 0; k < cu->n; k++) {
        if (fin[k] || key_has(ks, vpair(cu->v[2 * k], cu->v[2 * k + 1])))
            continue;
        uint32_t nb, n = fin_part(r, t, cu, k, ks, part, &nb), open = 0;
        if (!n || t->skip[part[0]])
            continue;
        /* its rim: the loops left open along its cuts, all of it (the
         * holes not asked, no loop was filled or listed) */
        for (uint32_t i = 0; i < cu->npend; i++) {
            uint32_t f = rp_cface(t, cu->he[cu->pend_cut[i]]), j = 0;
            while (j < n && part[j] != f)
                j++;
            open += j < n ? cu->pend[i].edges : 0;
        }
        if ((r->opt->steps & REPAIR_HOLES) && open != nb)
            continue;
        for (uint32_t q = 0; q < cu->n; q++)
            for (uint32_t j = 0; j < n; j++)
                fin[q] |= rp_cface(t, cu->he[q]) == part[j];
        for (uint32_t j = 0; j < n; j++) {
            t->skip[part[j]] = 1;
            drop[t->f0 + part[j]] = 1;
        }
        *faces += n;
    }
}

int rp_cuts_settle(Rep *r, ObjTopo *t, Cuts *cu, const Fill *fills, uint32_t nfills, uint8_t *drop)
{
    if (!cu->n)
        return 0;
    uint64_t nkeys = 4 * (uint64_t)cu->n;
    for (uint32_t i = 0; i < nfills; i++)
        nkeys += 6 * (uint64_t)fills[i].ntri;
    KeySet ks = { NULL, 64 };
    while (ks.size < 2 * nkeys + 2)
        ks.size *= 2;
    ks.key = malloc(ks.size * sizeof *ks.key);
    uint8_t *gone = calloc(cu->n + 1, 1), *fin = calloc(cu->n + 1, 1);
    if (!ks.key || !gone || !fin) {
        free(ks.key);
        free(gone);
        free(fin);
        return -1;
    }
    memset(ks.key, 0xff, ks.size * sizeof *ks.key);
    /* the fills' edges (vertex pairs) and vertices (UINT32_MAX << 32 | v) */
    for (uint32_t i = 0; i < nfills; i++)
        for (uint32_t k = 0; k < 3 * fills[i].ntri; k++) {
            uint32_t a = fills[i].tri[k], b = fills[i].tri[k % 3 == 2 ? k - 2 : k + 1];
            key_put(&ks, vpair(a, b));
            key_put(&ks, (uint64_t)UINT32_MAX << 32 | a);
        }
    /* the stray fins go (their faces skipped from here on) */
    uint32_t fin_faces = 0;
    stray_fins(r, t, cu, &ks, fin, drop, &fin_faces);
    /* the copies on cuts left open go back to the vertex they copy, when
     * no fill uses them: the edge is the fin it was (or, the fin
     * dropped, the edge it stood on) */
    uint32_t undone = 0, fins = 0, back = 0;
    for (uint32_t k = 0; k < cu->n; k++) {
        uint32_t a = cu->v[2 * k], b = cu->v[2 * k + 1];
        fins += fin[k];
        if (key_has(&ks, vpair(a, b)))
            continue;
        for (int j = 0; j < 2; j++) {
            uint32_t v = j ? b : a;
            if (v >= cu->vbase && !key_has(&ks, (uint64_t)UINT32_MAX << 32 | v)) {
                uint64_t key = (uint64_t)(UINT32_MAX - 1) << 32 | v;
                back += !key_has(&ks, key);
                key_put(&ks, key);
                gone[k] = 1;
            }
        }
        undone += gone[k] && !fin[k];
    }
    uint32_t moved = 0;
    for (uint32_t c = 0; back && c < t->nc; c++) {
        uint32_t *v = &r->w.corner[t->c0 + c];
        if (*v >= cu->vbase && key_has(&ks, (uint64_t)(UINT32_MAX - 1) << 32 | *v)) {
            *v = r->anchor[*v];
            moved++;
        }
    }
    /* the loops left open along a cut: listed if it stays; an open
     * boundary listed at a copy put back names the vertex it copied */
    int rc = 0;
    for (uint32_t i = 0; i < cu->npend && rc == 0; i++)
        if (!gone[cu->pend_cut[i]] && !fin[cu->pend_cut[i]])
            rc = rp_hole_open(r, cu->pend[i].object, cu->pend[i].edges, cu->pend[i].vertex, cu->pend[i].why);
    for (uint32_t i = 0; i < r->rep->nholes; i++) {
        uint32_t *v = &r->rep->holes[i].vertex;
        if (r->rep->holes[i].object == t->obj && *v >= cu->vbase &&
            key_has(&ks, (uint64_t)(UINT32_MAX - 1) << 32 | *v))
            *v = r->anchor[*v];
    }
    free(gone);
    free(fin);
    free(ks.key);
    /* an edge a fin was cut from and put back on, or whose fin went, was
     * not split; the copies put back were not added */
    uint32_t unsplit = undone + fins;
    r->rep->nm_edges -= unsplit < r->rep->nm_edges ? unsplit : r->rep->nm_edges;
    r->rep->split_vertices -= back < r->rep->split_vertices ? back : r->rep->split_vertices;
    r->rep->cuts_undone += undone;
    r->rep->fins += fin_faces;
    if (rc)
        return rc;
    /* the pairing again: the copies put back (the fins' faces out of it,
     * skipped), or only the fins' faces leaving it */
    return moved ? rp_topo_pair(r, t, 1) : fin_faces ? rp_topo_unpair(r, t) : 0;
}

void rp_cuts_free(Cuts *cu)
{
    free(cu->v);
    free(cu->he);
    free(cu->pend);
    free(cu->pend_cut);
    memset(cu, 0, sizeof *cu);
}
