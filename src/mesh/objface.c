/* objface.c: the OBJ statements that list vertices (f faces, p points,
 * l polylines), their corners resolved to 0-based indices (negative
 * ones count back from the last vertex read); and, after the last
 * line, what could only be judged then: indices past the last vertex,
 * and statements using a vertex whose own statement could not be read. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "obj.h"

/* ==== Corners ==== */

/* Optional signed integer of a v/vt/vn corner; returns 0 if malformed. */
static int skip_int(const char **pp, const char *e)
{
    const char *p = *pp;
    if (p < e && (*p == '-' || *p == '+'))
        p++;
    if (p >= e || !is_digit(*p))
        return 0;
    while (p < e && is_digit(*p))
        p++;
    *pp = p;
    return 1;
}

/* A corner's vt index (at *pp, syntax checked by skip_int) as a 0-based
 * texture coordinate entry: negative ones count back from the last vt
 * read; one that does not resolve (0, too far back) is none, since the
 * face still shows without it. Positive ones past the entries so far
 * are checked when the file has been read (mb_finish). */
static uint32_t corner_texcoord(const Parser *ps, const char *p, const char *q)
{
    int neg = *p == '-';
    if (*p == '-' || *p == '+')
        p++;
    uint64_t val = 0;
    for (; p < q && val < ((uint64_t)1 << 40); p++)
        val = val * 10 + (uint64_t)(*p - '0');
    uint32_t nuv = ps->m->nuv;
    if (ps->piece && val && !neg && val > OBJ_LOCAL)
        return OBJ_UNKNOWN;     /* a piece cannot tell (see read_corner) */
    if (ps->piece && neg && val > nuv)      /* before the piece: the merge resolves it */
        return OBJ_EXTERN | (uint32_t)(val - nuv < OBJ_FAR_MAX ? val - nuv : OBJ_FAR_MAX);
    if (val == 0 || (neg && val > nuv) || (!neg && val >= UINT32_MAX))
        return MESH_NO_UV;
    if (neg && ps->piece)
        return (nuv - (uint32_t)val) | OBJ_LOCAL;
    return neg ? nuv - (uint32_t)val : (uint32_t)(val - 1);
}

/* The next corner of an f, l or p statement at *pp (v, v/vt, v/vt/vn
 * or v//vn), resolved to a 0-based vertex index. Returns 1 with *idx
 * set, 0 at the end of the statement, -1 on a bad corner. A positive
 * index past the vertices so far raises *fwd (checked at the end).
 * uvi (NULL: not wanted) gets the corner's texture coordinate entry,
 * MESH_NO_UV when it names none. */
static int read_corner(Parser *ps, const char *what, const char *ls, const char **pp, const char *e,
                       uint32_t *idx, uint64_t *fwd, uint32_t *uvi)
{
    Mesh *m = ps->m;
    const char *p = *pp;
    while (p < e && is_space(*p))
        p++;
    if (p >= e || *p == '#')
        return 0;
    const char *tok = p;
    int neg = 0;
    if (*p == '-' || *p == '+') {
        neg = *p == '-';
        p++;
    }
    uint64_t val = 0;
    const char *d0 = p;
    while (p < e && is_digit(*p)) {
        if (val < ((uint64_t)1 << 40))    /* saturate: still out of range */
            val = val * 10 + (uint64_t)(*p - '0');
        p++;
    }
    const char *d1 = p;
    int ok = p > d0;
    if (uvi)
        *uvi = MESH_NO_UV;
    if (ok && p < e && *p == '/') {
        p++;
        const char *t0 = p;
        if (p < e && *p != '/' && !is_space(*p)) {
            ok = skip_int(&p, e);          /* vt */
            if (ok && uvi)
                *uvi = corner_texcoord(ps, t0, p);
            /* a piece: an entry before its start, or one no file holds */
            if (ok && uvi && *uvi == OBJ_UNKNOWN)
                return obj_fail(ps, "texture coordinate index beyond the piece");
        }
        if (ok && p < e && *p == '/') {
            p++;
            if (p < e && !is_space(*p))
                ok = skip_int(&p, e);      /* vn */
        }
    }
    if (!ok || (p < e && !is_space(*p))) {
        if (mesh_has_binary(ls, e))
            return obj_fail(ps, "binary or unreadable data");
        return obj_fail(ps, "malformed %s '%.*s'", what, mesh_tok_len(tok, e), tok);
    }
    *pp = p;

    /* Messages print the index as written (the value saturates). */
    int nd = (int)(d1 - d0);
    if (val == 0)
        return obj_fail(ps, "vertex index 0 is invalid (indices start at 1; %u vertices)", m->nverts);
    if (neg && ps->piece && val > m->nverts && val - m->nverts <= OBJ_FAR_MAX) {
        /* before the piece: the merge resolves it, or the serial parser
         * reads on from the piece when there are not so many before */
        uint32_t far = (uint32_t)(val - m->nverts);
        ps->ext_max = far > ps->ext_max ? far : ps->ext_max;
        *idx = OBJ_EXTERN | far;
        return 1;
    }
    if (neg) {
        if (val > m->nverts)
            return obj_fail(ps, "vertex index -%.*s out of range (%u vertices so far)", nd, d0, m->nverts);
        *idx = (m->nverts - (uint32_t)val) | (ps->piece ? OBJ_LOCAL : 0);
        return 1;
    }
    if (ps->piece && val > OBJ_LOCAL)
        return obj_fail(ps, "vertex index %.*s out of range", nd, d0);
    if (val > m->nverts) {
        if (val >= UINT32_MAX)
            return obj_fail(ps, "vertex index %.*s out of range (%u vertices)", nd, d0, m->nverts);
        if (val > *fwd)
            *fwd = val;
    }
    *idx = (uint32_t)(val - 1);
    return 1;
}

/* A statement read whole had an index past the vertices so far (a `p`
 * statement: its points start at point_first). */
static int note_forward(Parser *ps, uint64_t fwd, uint32_t point_first)
{
    if (!fwd)
        return 0;
    if (ps->piece) {
        /* only the largest matters: the merge judges it */
        ps->fwd_max = fwd > ps->fwd_max ? fwd : ps->fwd_max;
        return 0;
    }
    if (fwd > ps->fwd_max) {
        ps->fwd_max = fwd;
        ps->fwd_line = ps->line;
    }
    if (ps->e->strict)
        return 0;           /* the first bad one fails the load at the end */
    if (ps->nfwd == ps->fwdcap) {
        size_t cap = ps->fwdcap;
        if (grow_size((void **)&ps->fwd, &cap, (size_t)ps->nfwd + 1, sizeof *ps->fwd))
            return obj_oom(ps);
        ps->fwdcap = (uint32_t)cap;
    }
    ps->fwd[ps->nfwd++] = (FwdRef){ ps->line, fwd, point_first, ps->m->npoints - point_first };
    return 0;
}

int obj_face(Parser *ps, const char *ls, const char *p, const char *e)
{
    size_t start = ps->b.ncorner;
    uint64_t fwd = 0;
    uint32_t idx, uvi;
    int r;
    while ((r = read_corner(ps, "face corner", ls, &p, e, &idx, &fwd, &uvi)) > 0)
        if (mb_corner(&ps->b, idx) || mb_corner_uv(&ps->b, uvi))
            return -1;
    if (r < 0)
        return -1;
    size_t n = ps->b.ncorner - start;
    if (n < 3)
        return obj_fail(ps, "face has fewer than 3 vertices (%zu)", n);
    if (note_forward(ps, fwd, ps->m->npoints))
        return -1;
    return mb_face_end(&ps->b, start, ps->cur_use);
}

/* p v1 v2 ...: a point at each vertex. */
int obj_points(Parser *ps, const char *ls, const char *p, const char *e)
{
    uint32_t start = ps->m->npoints, idx;
    uint64_t fwd = 0;
    int r;
    while ((r = read_corner(ps, "point", ls, &p, e, &idx, &fwd, NULL)) > 0)
        if (mb_point(&ps->b, idx))
            return -1;
    if (r < 0)
        return -1;
    if (ps->m->npoints == start)
        return obj_fail(ps, "point statement without a vertex");
    return note_forward(ps, fwd, start);
}

/* l v1 v2 ...: a polyline through the vertices. */
int obj_polyline(Parser *ps, const char *ls, const char *p, const char *e)
{
    size_t start = ps->b.nlcorner;
    uint64_t fwd = 0;
    uint32_t idx;
    int r;
    while ((r = read_corner(ps, "line corner", ls, &p, e, &idx, &fwd, NULL)) > 0)
        if (mb_line_corner(&ps->b, idx))
            return -1;
    if (r < 0)
        return -1;
    size_t n = ps->b.nlcorner - start;
    if (n < 2)
        return obj_fail(ps, "line has fewer than 2 vertices (%zu)", n);
    if (note_forward(ps, fwd, ps->m->npoints))
        return -1;
    return mb_line_end(&ps->b, start);
}

/* ==== After the last line ==== */

/* Is vertex v usable: read, and not a stand-in? */
static inline int vert_ok(const uint8_t *bad, uint32_t nv, uint32_t v)
{
    return v < nv && !(bad && bad[v >> 3] >> (v & 7) & 1);
}

/* Strict: the load fails on the largest index past the last vertex.
 * Otherwise each statement that had one is skipped (its message and
 * count now; what it added goes with the rest below). 0 or -1. */
static int forward_statements(Parser *ps)
{
    Mesh *m = ps->m;
    if (ps->fwd_max > m->nverts && ps->e->strict) {
        ps->line = ps->fwd_line;
        return obj_fail(ps, "vertex index %llu out of range (%u vertices)",
                        (unsigned long long)ps->fwd_max, m->nverts);
    }
    for (uint32_t i = 0; i < ps->nfwd; i++) {
        if (ps->fwd[i].max <= m->nverts)
            continue;
        ps->line = ps->fwd[i].line;
        obj_fail(ps, "vertex index %llu out of range (%u vertices)", (unsigned long long)ps->fwd[i].max,
                 m->nverts);
        me_skip(ps->e, ps->fwd[i].line);
    }
    return 0;
}

/* The stand-ins of unreadable vertices as a bit set (*bad_out; NULL
 * when there are none), each stand-in moved onto a vertex that was read
 * (the one before it, else the first), so that bounds and fits ignore
 * it. 0 or -1. */
static int mark_standins(Parser *ps, uint8_t **bad_out)
{
    Mesh *m = ps->m;
    uint32_t nv = m->nverts;
    *bad_out = NULL;
    if (!ps->nbad)
        return 0;
    uint8_t *bad = calloc((size_t)nv / 8 + 1, 1);
    if (!bad)
        return obj_oom(ps);
    for (uint32_t i = 0; i < ps->nbad; i++) {
        uint32_t v = ps->bad_vert[i];
        bad[v >> 3] |= (uint8_t)(1u << (v & 7));
    }
    uint32_t good = 0;
    while (good < nv && !vert_ok(bad, nv, good))
        good++;
    for (uint32_t v = 0; v < nv && good < nv; v++) {
        if (vert_ok(bad, nv, v))
            good = v;
        else
            memcpy(&m->pos[3 * (size_t)v], &m->pos[3 * (size_t)good], 3 * sizeof(float));
    }
    *bad_out = bad;
    return 0;
}

/* Faces using a vertex that is not usable are dropped, the rest and the
 * objects' face ranges closed up. Returns how many were dropped that
 * forward_statements did not count (those past the end it did). */
static uint32_t drop_faces(Parser *ps, const uint8_t *bad)
{
    Mesh *m = ps->m;
    MeshBuild *b = &ps->b;
    uint32_t nv = m->nverts, nf = 0, ob = 0, more = 0;
    size_t nc = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        for (; ob < m->nobjs && m->objs[ob].face_first == f; ob++)
            m->objs[ob].face_first = nf;
        size_t c0 = m->face_start[f], c1 = f + 1 < m->nfaces ? m->face_start[f + 1] : b->ncorner;
        int ok = 1, past = 0;
        for (size_t c = c0; c < c1; c++) {
            ok &= vert_ok(bad, nv, m->corner[c]);
            past |= m->corner[c] >= nv;
        }
        if (!ok) {
            more += !past;
            m->info.triangles -= (uint32_t)(c1 - c0 - 2);
            continue;
        }
        memmove(&m->corner[nc], &m->corner[c0], (c1 - c0) * sizeof *m->corner);
        if (m->corner_uv)
            memmove(&m->corner_uv[nc], &m->corner_uv[c0], (c1 - c0) * sizeof *m->corner_uv);
        m->face_start[nf] = (uint32_t)nc;
        if (m->face_mat)
            m->face_mat[nf] = m->face_mat[f];
        nf++;
        nc += c1 - c0;
    }
    for (; ob < m->nobjs; ob++)
        m->objs[ob].face_first = nf;
    m->nfaces = nf;
    b->ncorner = nc;
    return more;
}

/* The same for points: a skipped `p` statement takes all its points
 * along (fwd[] lists the statements in order, so their runs rise with
 * k). */
static uint32_t drop_points(Parser *ps, const uint8_t *bad)
{
    Mesh *m = ps->m;
    uint32_t nv = m->nverts, np = 0, fi = 0, ob = 0, more = 0;
    for (uint32_t k = 0; k < m->npoints; k++) {
        for (; ob < m->nobjs && m->objs[ob].point_first == k; ob++)
            m->objs[ob].point_first = np;
        while (fi < ps->nfwd && (ps->fwd[fi].point_count == 0 || ps->fwd[fi].max <= nv ||
                                 ps->fwd[fi].point_first + ps->fwd[fi].point_count <= k))
            fi++;
        if (fi < ps->nfwd && ps->fwd[fi].point_first <= k)
            continue;       /* counted with its statement */
        if (vert_ok(bad, nv, m->point[k]))
            m->point[np++] = m->point[k];
        else
            more++;
    }
    for (; ob < m->nobjs; ob++)
        m->objs[ob].point_first = np;
    m->npoints = np;
    return more;
}

/* The same for polylines. */
static uint32_t drop_lines(Parser *ps, const uint8_t *bad)
{
    Mesh *m = ps->m;
    MeshBuild *b = &ps->b;
    uint32_t nv = m->nverts, nl = 0, ob = 0, more = 0;
    size_t nlc = 0;
    for (uint32_t l = 0; l < m->nlines; l++) {
        for (; ob < m->nobjs && m->objs[ob].line_first == l; ob++)
            m->objs[ob].line_first = nl;
        size_t c0 = m->line_start[l], c1 = l + 1 < m->nlines ? m->line_start[l + 1] : b->nlcorner;
        int ok = 1, past = 0;
        for (size_t c = c0; c < c1; c++) {
            ok &= vert_ok(bad, nv, m->line_corner[c]);
            past |= m->line_corner[c] >= nv;
        }
        if (!ok) {
            more += !past;
            continue;
        }
        memmove(&m->line_corner[nlc], &m->line_corner[c0], (c1 - c0) * sizeof *m->line_corner);
        m->line_start[nl++] = (uint32_t)nlc;
        nlc += c1 - c0;
    }
    for (; ob < m->nobjs; ob++)
        m->objs[ob].line_first = nl;
    m->nlines = nl;
    b->nlcorner = nlc;
    return more;
}

/* The stand-ins themselves go, once nothing uses them: a file of
 * vertices alone is a cloud of every vertex (and --points draws every
 * vertex), where a stand-in would be a point no statement gave. The
 * vertices after each move down, and the indices with them. */
static void drop_standins(Parser *ps, const uint8_t *bad)
{
    Mesh *m = ps->m;
    uint32_t nv = m->nverts, k = 0;
    /* to[v]: vertex v's index once the stand-ins before it are gone */
    uint32_t *to = malloc((size_t)(nv ? nv : 1) * sizeof *to);
    if (!to) {
        /* not enough memory for the table: leave them (they sit on a
         * good vertex's position, mark_standins) */
        return;
    }
    for (uint32_t v = 0; v < nv; v++) {
        to[v] = k;
        if (!vert_ok(bad, nv, v))
            continue;
        if (k != v) {
            memmove(&m->pos[3 * (size_t)k], &m->pos[3 * (size_t)v], 3 * sizeof(float));
            if (m->rgb)
                memmove(&m->rgb[3 * (size_t)k], &m->rgb[3 * (size_t)v], 3 * sizeof(float));
        }
        k++;
    }
    for (size_t c = 0; c < ps->b.ncorner; c++)
        m->corner[c] = to[m->corner[c]];
    if (m->point)
        for (uint32_t p = 0; p < m->npoints; p++)
            m->point[p] = to[m->point[p]];
    for (size_t c = 0; c < ps->b.nlcorner; c++)
        m->line_corner[c] = to[m->line_corner[c]];
    m->nverts = k;
    free(to);
}

/* What could not be resolved until the end: positive indices past the
 * last vertex (strict: the load fails on the largest; otherwise each
 * statement that had one is skipped) and the stand-ins of unreadable
 * vertices. Faces, points and lines using either are dropped (each
 * counted as a skipped statement once), and the objects' ranges closed
 * up. */
int obj_drop_unreadable(Parser *ps)
{
    if (ps->fwd_max <= ps->m->nverts && !ps->nbad)
        return 0;
    uint8_t *bad;
    if (forward_statements(ps) || mark_standins(ps, &bad))
        return -1;
    uint32_t more = drop_faces(ps, bad);
    more += drop_points(ps, bad);
    more += drop_lines(ps, bad);
    if (bad)
        drop_standins(ps, bad);
    free(bad);
    MeshErr *e = ps->e;
    e->skipped = e->skipped + more < e->skipped ? UINT32_MAX : e->skipped + more;
    return 0;
}
