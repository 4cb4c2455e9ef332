/* off.c: OFF (Geomview's Object File Format) and its variants, text:
 *
 *   [ST][C][N][4][n]OFF      the keyword (optional; its letters say what
 *                            columns vertex lines carry)
 *   [dim]                    with the n prefix: the dimension
 *   nverts nfaces [nedges]   (may follow the keyword on its line)
 *   x y z [w] [nx ny nz] [r g b [a]] [s t]     one line a vertex
 *   n v1 .. vn [colour]      one line a face, indices from 0
 *
 * Only x y z (divided by w for 4OFF) are needed: the extra columns are
 * skipped, except colours, read where they are cheap: the C variant's
 * vertex colours and a face's trailing r g b [a] (integers 0..255 or
 * floats 0..1, as the numbers are written; a lone colour-map index is
 * skipped). '#' starts a comment anywhere. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "mesh_internal.h"

typedef struct {
    int st, c, n, four, ndim;   /* the keyword's prefixes */
} OffKind;

/* Parse the keyword [p, e) into k; 0 if it is not one. */
static int off_keyword(const char *p, const char *e, OffKind *k)
{
    memset(k, 0, sizeof *k);
    if (e - p >= 2 && p[0] == 'S' && p[1] == 'T') {
        k->st = 1;
        p += 2;
    }
    if (p < e && *p == 'C') { k->c = 1; p++; }
    if (p < e && *p == 'N') { k->n = 1; p++; }
    if (p < e && *p == '4') { k->four = 1; p++; }
    if (p < e && *p == 'n') { k->ndim = 1; p++; }
    return e - p == 3 && memcmp(p, "OFF", 3) == 0;
}

/* The first word that is not in a comment. */
static int first_word(const char *h, size_t n, const char **ws, const char **we)
{
    const char *p = h, *end = h + n;
    for (;;) {
        while (p < end && mesh_is_ws(*p))
            p++;
        if (p >= end)
            return 0;
        if (*p == '#') {
            while (p < end && *p != '\n' && *p != '\r')
                p++;
            continue;
        }
        *ws = p;
        while (p < end && !mesh_is_ws(*p) && *p != '#')
            p++;
        *we = p;
        return 1;
    }
}

static int off_probe(const char *head, size_t n, uint64_t size)
{
    (void)size;
    const char *w, *we;
    OffKind k;
    size_t bom = mesh_bom_len(head, n);
    head += bom;
    n -= bom;
    if (mesh_has_binary(head, head + n) || !first_word(head, n, &w, &we))
        return PROBE_NO;
    return off_keyword(w, we, &k) ? PROBE_SURE : PROBE_NO;
}

typedef struct {
    MeshCtx    *c;
    MeshErr    *e;
    MeshBuild  *b;
    LineReader  lr;
    const char *ls, *le;     /* the current line, comment cut */
    OffKind     kind;        /* the keyword's prefixes (all 0 without one) */
    int64_t     cnt[3];      /* vertices, faces, edges as the header states them */
} Off;

/* The next line holding something, with its comment cut. 0 at the end. */
static int next_line(Off *o)
{
    while (lr_next(&o->lr, &o->ls, &o->le)) {
        const char *h = memchr(o->ls, '#', (size_t)(o->le - o->ls));
        if (h)
            o->le = h;
        const char *p = o->ls;
        while (p < o->le && mesh_is_blank(*p))
            p++;
        if (p < o->le) {
            o->ls = p;
            return 1;
        }
    }
    return 0;
}

static int bad_number(Off *o, int code, const char *p, const char *what)
{
    int n = mesh_tok_len(p, o->le);
    if (mesh_has_binary(o->ls, o->le))
        return me_fail_line(o->e, o->lr.line, "binary or unreadable data");
    if (p >= o->le)
        return me_fail_line(o->e, o->lr.line, "%s: too few numbers", what);
    if (code == MESH_NUM_NONFINITE)
        return me_fail_line(o->e, o->lr.line, "NaN or infinite number '%.*s'", n, p);
    if (code == MESH_NUM_RANGE)
        return me_fail_line(o->e, o->lr.line, "number out of range '%.*s'", n, p);
    return me_fail_line(o->e, o->lr.line, "%s: malformed number '%.*s'", what, n, p);
}

static inline void blanks(const char **p, const char *e)
{
    while (*p < e && mesh_is_blank(**p))
        (*p)++;
}

/* Up to max numbers from *p to the end of the line; how many, or -1
 * with the error written. */
static int numbers(Off *o, const char **pp, float *v, int max, const char *what)
{
    int n = 0;
    for (; n < max; n++) {
        blanks(pp, o->le);
        if (*pp >= o->le)
            break;
        const char *t = *pp;
        int r = mesh_parse_float(pp, o->le, &v[n]);
        if (r) {
            bad_number(o, r, t, what);
            return -1;
        }
    }
    return n;
}

/* Do the next n numbers look like floats (a '.' or exponent)? */
static int written_as_floats(const char *p, const char *e)
{
    for (; p < e; p++)
        if (*p == '.' || *p == 'e' || *p == 'E')
            return 1;
    return 0;
}

/* The text after the keyword [w, p): nOFF's dimension, the refusal of
 * binary OFF, and the step to the next line when the counts are not on
 * the keyword's. On return *pp is where the counts start. 0, or -1 with
 * the error written (1: the file ends here). */
static int after_keyword(Off *o, const OffKind *k, const char **pp)
{
    const char *p = *pp;
    if (k->ndim) {
        /* nOFF: the dimension follows; only 3 (4 with the 4 prefix) */
        int64_t dim;
        blanks(&p, o->le);
        if (p >= o->le) {
            if (!next_line(o))
                return 1;
            p = o->ls;
        }
        if (mesh_parse_int(&p, o->le, &dim) || dim != 3)
            return me_fail_line(o->e, o->lr.line, "only 3-dimensional nOFF files are read");
    }
    blanks(&p, o->le);
    if (p < o->le && mesh_word_is(p, o->le, "binary"))
        return me_fail_line(o->e, o->lr.line, "binary OFF is not read (only text OFF)");
    if (p >= o->le) {
        if (!next_line(o))
            return 1;
        p = o->ls;
    }
    *pp = p;
    return 0;
}

/* nverts nfaces [nedges] from *pp into o->cnt. 0, or -1 with the error
 * written. */
static int read_counts(Off *o, const char *p)
{
    int ncnt;
    for (ncnt = 0; ncnt < 3; ncnt++) {
        blanks(&p, o->le);
        if (p >= o->le)
            break;
        const char *t = p;
        int r = mesh_parse_int(&p, o->le, &o->cnt[ncnt]);
        if (r || o->cnt[ncnt] < 0) {
            if (mesh_has_binary(o->ls, o->le))
                return me_fail_line(o->e, o->lr.line, "binary or unreadable data");
            return me_fail_line(o->e, o->lr.line, "bad count '%.*s' (expected vertices faces edges)",
                                mesh_tok_len(t, o->le), t);
        }
    }
    if (ncnt < 2)
        return me_fail_line(o->e, o->lr.line, "expected the counts: vertices faces [edges]");
    /* Checked against the size before anything is allocated: a vertex
     * line takes 6 bytes or more ("0 0 0\n"), a face line 8; the bound
     * is looser (4 and 6) so that a short line gets its own message. */
    uint64_t rest = (uint64_t)(o->lr.end - o->lr.p) + 1;
    if ((uint64_t)o->cnt[0] > rest / 4 || (uint64_t)o->cnt[1] > rest / 6 ||
        (uint64_t)o->cnt[0] * 4 + (uint64_t)o->cnt[1] * 6 > rest)
        return me_fail_line(o->e, o->lr.line, "%lld vertices and %lld faces cannot fit in the %llu "
                            "bytes left", (long long)o->cnt[0], (long long)o->cnt[1],
                            (unsigned long long)rest - 1);
    return 0;
}

/* The keyword line (optional) and the counts, into o->kind and o->cnt.
 * 0, or -1 with the error written (1: the file ends before the counts). */
static int off_header(Off *o)
{
    Mesh *m = o->b->m;
    if (!next_line(o))
        return me_fail(o->e, m->info.bytes ? "no faces (only comments and blank lines)"
                                              : "no faces (empty file)");
    const char *p = o->ls, *w = p;
    while (p < o->le && !mesh_is_blank(*p))
        p++;
    if (off_keyword(w, p, &o->kind)) {
        if (p - w > 3)
            snprintf(m->info.format, sizeof m->info.format, "off (%.*s)", (int)(p - w), w);
        int r = after_keyword(o, &o->kind, &p);
        if (r)
            return r;
    } else {
        p = o->ls;   /* no keyword: the counts come first */
    }
    return read_counts(o, p);
}

/* A C variant's vertex colour from the numbers v[0..2], written from
 * cs on: integers 0..255 unless written as floats. */
static void vertex_colour(const Off *o, const float *v, const char *cs, float *col)
{
    float s = written_as_floats(cs, o->le) ? 1.0f : 255.0f;
    for (int q = 0; q < 3; q++) {
        float x = v[q] / s;
        col[q] = x < 0 ? 0 : x > 1 ? 1 : x;
    }
}

/* Vertex i: x y z [w], then normals (N), then the colour (C). 0, or -1
 * with the error written (1: the file ends here). */
static int off_vertex(Off *o, uint32_t i)
{
    const OffKind *k = &o->kind;
    Mesh *m = o->b->m;
    int ncoord = k->four ? 4 : 3;
    int colour_at = ncoord + (k->n ? 3 : 0);
    if (!next_line(o))
        return 1;
    float v[11];
    const char *p = o->ls;
    int n = numbers(o, &p, v, k->c ? colour_at : ncoord, "vertex");
    if (n < 0)
        return -1;
    const char *cs = p;
    if (k->c && n == colour_at) {
        int nc = numbers(o, &p, v + colour_at, 4, "vertex colour");
        if (nc < 0)
            return -1;
        n += nc;
    }
    if (n < ncoord)
        return me_fail_line(o->e, o->lr.line, "vertex needs %s, got %d number%s",
                            k->four ? "x y z w" : "x y z", n, n == 1 ? "" : "s");
    if (k->four && v[3] != 0.0f)
        for (int q = 0; q < 3; q++)
            v[q] /= v[3];
    float *d = m->pos + 3 * (size_t)i;
    d[0] = v[0];
    d[1] = v[1];
    d[2] = v[2];
    if (k->c) {
        float *col = m->rgb + 3 * (size_t)i;
        if (n >= colour_at + 3)
            vertex_colour(o, v + colour_at, cs, col);
        else
            col[0] = col[1] = col[2] = 1.0f;
    }
    m->nverts++;
    return 0;
}

/* A face's corner indices after its count n, from *pp, added to the
 * build. 0, 1 when the face cannot be read (the error written), -1 out
 * of memory. */
static int face_corners(Off *o, const char **pp, int64_t n, uint32_t nv)
{
    const char *p = *pp;
    for (int64_t q = 0; q < n; q++) {
        blanks(&p, o->le);
        int64_t idx;
        const char *t = p;
        if (p >= o->le) {
            me_fail_line(o->e, o->lr.line, "face of %lld vertices lists %lld", (long long)n,
                         (long long)q);
            return 1;
        }
        int r = mesh_parse_int(&p, o->le, &idx);
        if (r) {
            bad_number(o, r, t, "face");
            return 1;
        }
        if (idx < 0 || (uint64_t)idx >= nv) {
            me_fail_line(o->e, o->lr.line, "vertex index %lld out of range (%u vertices)",
                         (long long)idx, nv);
            return 1;
        }
        if (mb_corner(o->b, (uint32_t)idx))
            return -1;
    }
    *pp = p;
    return 0;
}

/* The colour after a face's corners, from p: its material in *mat (-1:
 * none). 0, 1 when it cannot be read (the error written), -1 out of
 * memory. */
static int face_colour(Off *o, const char *p, int32_t *mat)
{
    float col[4];
    const char *cs = p;
    int nc = numbers(o, &p, col, 4, "face colour");
    if (nc < 0)
        return 1;
    *mat = -1;
    if (nc >= 3) {
        float s = written_as_floats(cs, o->le) ? 1.0f : 255.0f;
        uint8_t q8[3];
        for (int q = 0; q < 3; q++) {
            float x = col[q] / s;
            x = x < 0 ? 0 : x > 1 ? 1 : x;
            q8[q] = (uint8_t)(x * 255.0f + 0.5f);
        }
        if ((*mat = mb_colour(o->b, q8[0], q8[1], q8[2], 255)) < 0)
            return -1;
    }
    return 0;
}

/* One face line: n indices, then maybe a colour. 0; 1 when it cannot be
 * read (the error written, nothing of it kept); -1 out of memory. */
static int off_face(Off *o, uint32_t nv)
{
    const char *p = o->ls, *t = p;
    size_t first = o->b->ncorner;
    int64_t n;
    int r = mesh_parse_int(&p, o->le, &n);
    if (r) {
        bad_number(o, r, t, "face");
        return 1;
    }
    if (n < 3) {
        me_fail_line(o->e, o->lr.line, "face has %lld vertices (at least 3)", (long long)n);
        return 1;
    }
    int32_t mat = -1;
    if ((r = face_corners(o, &p, n, nv)) || (r = face_colour(o, p, &mat))) {
        if (r > 0)
            o->b->ncorner = first;
        return r;
    }
    return mb_face_end(o->b, first, mat) ? -1 : 0;
}

/* The message of a file that ends before its stated counts. */
static int ends_early(Off *o)
{
    Mesh *m = o->b->m;
    return me_fail_line(o->e, o->lr.line, "file ends early (%lld vertices and %lld faces stated; "
                        "%u vertices and %u faces read)", (long long)o->cnt[0],
                        (long long)o->cnt[1], m->nverts, m->nfaces);
}

/* The faces. A face line that cannot be read is skipped (counted; strict
 * fails on it); a file that ends early keeps the faces read (not
 * strict). 0 or -1. */
static int off_faces(Off *o, uint32_t nv, uint32_t nf)
{
    for (uint32_t i = 0; i < nf; i++) {
        if (!next_line(o)) {
            ends_early(o);
            return me_skip(o->e, 0);
        }
        int r = off_face(o, nv);
        if (r < 0 || (r > 0 && me_skip(o->e, o->lr.line)))
            return -1;
    }
    return 0;
}

/* The header, then the vertices (their count allocated once), then the
 * faces. */
static int off_parse(MeshCtx *c, const char *data, size_t len)
{
    MeshBuild b;
    if (mb_start(&b, c->m, &c->err, c->err.name))
        return -1;
    Mesh *m = c->m;
    m->info.bytes = len;
    snprintf(m->info.format, sizeof m->info.format, "off");
    Off o = { .c = c, .e = &c->err, .b = &b };
    size_t bom = mesh_bom_len(data, len);
    lr_init(&o.lr, data + bom, len - bom, c->file);

    int r = off_header(&o);
    if (r)
        goto out;
    uint32_t nv = (uint32_t)o.cnt[0], nf = (uint32_t)o.cnt[1];
    if (mb_afford_counts(&b, nv, o.kind.c, nf) || mb_reserve(&b, nv, nf, 3 * (size_t)nf) ||
        (o.kind.c && mb_want_rgb(&b))) {
        r = -1;
        goto out;
    }
    for (uint32_t i = 0; i < nv; i++)
        if ((r = off_vertex(&o, i)))
            goto out;
    if ((r = off_faces(&o, nv, nf)) == 0)
        r = mb_finish(&b, 1);
out:
    if (r > 0)
        ends_early(&o);
    if (r)
        mb_abort(&b);
    return r ? -1 : 0;
}

const MeshLoader mesh_loader_off = {
    .name = "off",
    .exts = "off coff noff",
    .what = "OFF, and COFF, NOFF, 4OFF, ... (+ vertex and face colours)",
    .probe = off_probe,
    .parse = off_parse,
    .text = 1,
};
