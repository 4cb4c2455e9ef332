/* stl.c: STL, binary and ASCII, told apart by content: a binary file is
 * exactly 84 + 50 n bytes for the n triangles its header states (many
 * start with "solid" nonetheless), an ASCII one is text that starts with
 * "solid" and goes on with "facet".
 *
 * STL repeats every corner's position; equal positions (exact bit
 * patterns) are merged in one hash pass as they are read, so the front
 * end transforms each point once and the mesh is as small as an OBJ's.
 * Face colours of binary files are read in both conventions: VisCAM /
 * SolidView (attribute bit 15 set = a valid 5:5:5 colour, red in the
 * high bits) and Materialise Magics (a "COLOR=" part colour in the
 * header; bit 15 clear = the face's own colour, red in the low bits).
 * Each distinct colour becomes one material.
 *
 * STL says nothing of axes, but 3D printing, its main use, builds along
 * z: slicers and printers take z as up, and so does zview (--up
 * overrides it for a file exported y-up). */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "mesh_internal.h"

#define STL_HEADER 80
#define STL_TRI    50   /* normal, 3 corners (12 floats), attribute word */
#ifndef STL_FILE_AHEAD
#define STL_FILE_AHEAD 2048
#endif

/* ==== Telling binary from ASCII ==== */

/* "solid" at the start (after blanks), as a word. */
static const char *after_solid(const char *p, const char *end)
{
    p += mesh_bom_len(p, (size_t)(end - p));
    while (p < end && mesh_is_ws(*p))
        p++;
    if (!mesh_word_is(p, end, "solid"))
        return NULL;
    return p + 5;
}

/* Text that starts "solid ...", whose next statement is "facet" or
 * "endsolid": an ASCII STL. */
static int looks_ascii(const char *h, size_t n)
{
    const char *end = h + n, *p = after_solid(h, end);
    if (!p || mesh_has_binary(h, end))
        return 0;
    while (p < end && *p != '\n' && *p != '\r')
        p++;
    while (p < end && mesh_is_ws(*p))
        p++;
    return mesh_word_is(p, end, "facet") || mesh_word_is(p, end, "endsolid");
}

static int stl_probe(const char *head, size_t n, uint64_t size)
{
    if (n >= STL_HEADER + 4 && size == STL_HEADER + 4 + (uint64_t)STL_TRI * rd_u32le(head + 80))
        return PROBE_SURE;
    if (looks_ascii(head, n))
        return PROBE_SURE;
    const char *p = after_solid(head, head + n);
    return p && !mesh_has_binary(head, head + n) ? PROBE_MAYBE : PROBE_NO;
}

/* z up, the 3D-printing convention (see the top); no front. */
static void stl_stance(Mesh *m)
{
    m->info.up = UP_Z;
    m->info.front = -1;
    snprintf(m->info.up_why, sizeof m->info.up_why, "STL: the 3D-printing convention");
}

/* ==== Binary ==== */

/* Materialise's part colour: "COLOR=" and 4 bytes R G B A in the header. */
static int header_colour(const char *h, uint8_t rgba[4])
{
    for (int i = 0; i + 6 + 4 <= STL_HEADER; i++)
        if (memcmp(h + i, "COLOR=", 6) == 0) {
            memcpy(rgba, h + i + 6, 4);
            return 1;
        }
    return 0;
}

static inline uint8_t c5to8(unsigned v) { return (uint8_t)((v * 255 + 15) / 31); }

static int stl_binary(MeshCtx *c, MeshBuild *b, const char *data, size_t len)
{
    Mesh *m = c->m;
    if (len < STL_HEADER + 4)
        return me_fail(&c->err, "too short for a binary STL (%zu bytes; the header alone is 84)",
                       len);
    uint32_t n = rd_u32le(data + 80);
    uint64_t need = STL_HEADER + 4 + (uint64_t)STL_TRI * n;
    if (need > len) {
        /* the count is checked against the size before anything is
         * allocated: a lying header costs nothing */
        uint64_t whole = (len - STL_HEADER - 4) / STL_TRI;
        me_fail_at(&c->err, STL_HEADER + 4 + whole * STL_TRI,
                   "file ends inside triangle %llu of %u (%u triangles need %llu "
                   "bytes, the file has %zu)",
                   (unsigned long long)whole + 1, n, n, (unsigned long long)need, len);
        /* a file cut short (a copy that stopped) shows the whole
         * triangles it has, as PLY and OFF do; --strict refuses it */
        if (whole == 0 || me_skip(&c->err, STL_HEADER + 4 + whole * STL_TRI))
            return -1;
        n = (uint32_t)whole;
        need = STL_HEADER + 4 + (uint64_t)STL_TRI * n;
    } else if (len - need >= STL_TRI)
        /* a whole triangle more or beyond: the count is wrong, and what
         * follows it cannot be trusted either */
        return me_fail(&c->err, "the header's count, %u triangles, makes %llu bytes; the file has %zu",
                       n, (unsigned long long)need, len);
    if (need < len && !c->err.skipped)
        me_warn(&c->err, NULL, 0, "%llu bytes after the last of %u triangles ignored",
                (unsigned long long)(len - need), n);
    snprintf(m->info.format, sizeof m->info.format, "stl binary");
    stl_stance(m);
    if (n == 0)
        return me_fail(&c->err, "no faces (a binary STL of 0 triangles)");

    uint8_t part[4];
    int magics = header_colour(data, part);
    int32_t part_mat = -1;
    if (magics && (part_mat = mb_colour(b, part[0], part[1], part[2], 255)) < 0)
        return -1;

    /* Closed meshes have about n / 2 vertices (more grows the array),
     * merged through a table of 16 bytes a vertex */
    char what[48];
    mesh_count_str(n, what, sizeof what);
    strcat(what, " triangles");
    if (mb_afford(b, n, mb_estimate(n / 2, 0, n, 3 * (uint64_t)n, 0) + 8 * (uint64_t)n, what) ||
        mb_reserve(b, n / 2 + 1024, n, 3 * (size_t)n))
        return -1;
    VertMerge vm;
    if (vm_init(&vm, n / 2 + 1024))
        return me_oom(&c->err);

    const char *tri = data + STL_HEADER + 4;
    uint32_t *corner = m->corner;
    uint32_t *face_start = m->face_start;
    int32_t *face_mat = m->face_mat;
    enum { AHEAD = 8 };   /* triangles between a slot's prefetch and its use */
    for (uint32_t i = 0; i < n; i++, tri += STL_TRI) {
        if (i + AHEAD < n) {
            uint32_t nb[9];
            memcpy(nb, tri + AHEAD * STL_TRI + 12, sizeof nb);
            for (int k = 0; k < 3; k++)
                vm_prefetch(&vm, vm_hash(nb[3 * k], nb[3 * k + 1], nb[3 * k + 2]));
        }
        if ((i & 0x3fff) == 0)
            mf_progress(c->file, tri);
        /* the file's bytes too: the hardware prefetcher stops at each
         * 4 KB page, and a miss on the file is a third of the time */
        if ((size_t)(tri - data) + STL_FILE_AHEAD < len)
            __builtin_prefetch(tri + STL_FILE_AHEAD);
        uint32_t v[9];
        memcpy(v, tri + 12, sizeof v);
#if __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
        for (int k = 0; k < 9; k++)
            v[k] = __builtin_bswap32(v[k]);
#endif
        for (int k = 0; k < 9; k++)
            if (bits_nonfinite(v[k])) {
                vm_free(&vm);
                return me_fail_at(&c->err, (uint64_t)(tri - data) + 12 + 4 * (uint64_t)k,
                                  "NaN or infinite coordinate (triangle %u)", i + 1);
            }
        for (int k = 0; k < 3; k++) {
            const uint32_t *p = v + 3 * k;
            if (vm_add(&vm, b, p, vm_hash(p[0], p[1], p[2]), &corner[3 * (size_t)i + k])) {
                vm_free(&vm);
                return -1;
            }
        }
        face_start[i] = 3 * i;
        unsigned attr = rd_u16le(tri + 48);
        int32_t mat = -1;
        if (magics) {
            mat = attr & 0x8000 ? part_mat
                : mb_colour(b, c5to8(attr & 31), c5to8(attr >> 5 & 31), c5to8(attr >> 10 & 31), 255);
        } else if (attr & 0x8000) {
            mat = mb_colour(b, c5to8(attr >> 10 & 31), c5to8(attr >> 5 & 31), c5to8(attr & 31), 255);
        }
        if (mat < -1 || (mat == -1 && (magics || (attr & 0x8000))) ||
            (mat != -1 && !face_mat && !(face_mat = mb_face_mats(b)))) {
            vm_free(&vm);
            return -1;
        }
        if (face_mat)
            face_mat[i] = mat;
    }
    vm_free(&vm);
    m->nfaces = n;
    b->ncorner = 3 * (size_t)n;
    m->info.triangles = n;
    m->info.corners_read = 3 * (uint64_t)n;
    return 0;
}

/* ==== ASCII ==== */

/* A facet's corners (coordinate bits) waiting to be merged. Facets are
 * merged one facet late: the merge table's slots for a facet are
 * prefetched when it ends and looked up after the next one is parsed,
 * so the memory latency of the table hides behind the parsing. */
typedef struct {
    uint32_t *bits;      /* 3 a corner */
    size_t    n, cap;    /* corners */
} Pending;

static int pend_add(Pending *pd, const uint32_t bits[3])
{
    if (pd->n == pd->cap) {
        size_t nc = pd->cap ? pd->cap * 2 : 8;
        uint32_t *nb = realloc(pd->bits, nc * 3 * sizeof *nb);
        if (!nb)
            return -1;
        pd->bits = nb;
        pd->cap = nc;
    }
    memcpy(pd->bits + 3 * pd->n++, bits, 3 * sizeof *bits);
    return 0;
}

/* Merge a pending facet's corners and close it as a face. */
static int pend_flush(Pending *pd, VertMerge *vm, MeshBuild *b)
{
    if (!pd->n)
        return 0;
    size_t first = b->ncorner;
    for (size_t k = 0; k < pd->n; k++) {
        const uint32_t *p = pd->bits + 3 * k;
        uint32_t idx = 0;
        if (vm_add(vm, b, p, vm_hash(p[0], p[1], p[2]), &idx) || mb_corner(b, idx))
            return -1;
    }
    pd->n = 0;
    return mb_face_end(b, first, -1);
}

/* An ASCII STL being read: the line reader, where the statements are
 * (solid > facet > outer loop), and the facets waiting to be merged. */
typedef struct {
    MeshErr    *e;
    MeshBuild  *b;
    LineReader  lr;
    const char *ls, *le;   /* the current line */
    VertMerge   vm;
    int         in_facet, in_loop;
    uint64_t    facet_line;
    Pending     cur, prev; /* the facet being read; the one before, to merge */
} StlText;

/* The message for a vertex's number t that did not parse (nr). */
static int bad_coord(StlText *s, int nr, const char *t, int i)
{
    MeshErr *e = s->e;
    int tl = mesh_tok_len(t, s->le);
    if (mesh_has_binary(s->ls, s->le))
        return me_fail_line(e, s->lr.line, "binary or unreadable data");
    if (nr == MESH_NUM_NONFINITE)
        return me_fail_line(e, s->lr.line, "NaN or infinite number '%.*s'", tl, t);
    if (nr == MESH_NUM_RANGE)
        return me_fail_line(e, s->lr.line, "number out of range '%.*s'", tl, t);
    if (t >= s->le)
        return me_fail_line(e, s->lr.line, "vertex needs x y z, got %d number%s", i,
                            i == 1 ? "" : "s");
    return me_fail_line(e, s->lr.line, "malformed number '%.*s'", tl, t);
}

/* "vertex x y z" (the keyword read up to p): the corner's bits join the
 * current facet. 0 or -1. */
static int st_vertex(StlText *s, const char *p)
{
    const char *le = s->le;
    if (!s->in_facet)
        return me_fail_line(s->e, s->lr.line, "vertex outside a facet");
    uint32_t bits[3];
    for (int i = 0; i < 3; i++) {
        while (p < le && mesh_is_blank(*p))
            p++;
        float f;
        const char *t = p;
        int nr = p < le ? mesh_parse_float(&p, le, &f) : MESH_NUM_BAD;
        if (nr)
            return bad_coord(s, nr, t, i);
        memcpy(&bits[i], &f, 4);
    }
    while (p < le && mesh_is_blank(*p))
        p++;
    if (p < le)
        return me_fail_line(s->e, s->lr.line, "vertex has more than x y z ('%.*s')",
                            mesh_tok_len(p, le), p);
    if (pend_add(&s->cur, bits))
        return me_oom(s->e);
    s->b->m->info.corners_read++;
    return 0;
}

/* "facet [normal ...]": a facet starts. 0 or -1. */
static int st_facet(StlText *s, const char *p)
{
    if (s->in_facet)
        return me_fail_line(s->e, s->lr.line, "facet inside a facet (endfacet missing before)");
    /* The normal is not needed (faces get theirs from the corners): the
     * rest of the line is only checked for bytes no text has. */
    if (mesh_has_binary(p, s->le))
        return me_fail_line(s->e, s->lr.line, "binary or unreadable data");
    s->in_facet = 1;
    s->facet_line = s->lr.line;
    s->cur.n = 0;
    return 0;
}

/* "endfacet": the facet's merge slots are prefetched, the facet before
 * it merged, and this one waits for the next. 0 or -1. */
static int st_endfacet(StlText *s)
{
    if (!s->in_facet)
        return me_fail_line(s->e, s->lr.line, "endfacet without a facet");
    if (s->cur.n < 3)
        return me_fail_line(s->e, s->facet_line, "facet has fewer than 3 vertices (%zu)",
                            s->cur.n);
    for (size_t k = 0; k < s->cur.n; k++) {
        const uint32_t *q = s->cur.bits + 3 * k;
        vm_prefetch(&s->vm, vm_hash(q[0], q[1], q[2]));
    }
    if (pend_flush(&s->prev, &s->vm, s->b))
        return -1;
    Pending t = s->prev;
    s->prev = s->cur;
    s->cur = t;
    s->in_facet = s->in_loop = 0;
    return 0;
}

/* "solid [name]": each solid of the file is an object, named as it
 * says. 0 or -1. */
static int st_solid(StlText *s, const char *p)
{
    const char *le = s->le;
    if (s->in_facet)
        return me_fail_line(s->e, s->lr.line, "solid inside a facet");
    while (p < le && mesh_is_blank(*p))
        p++;
    const char *ne = le;
    while (ne > p && mesh_is_blank(ne[-1]))
        ne--;
    if (mesh_has_binary(p, ne))
        return me_fail_line(s->e, s->lr.line, "binary or unreadable data");
    return pend_flush(&s->prev, &s->vm, s->b) || mb_object(s->b, p, (size_t)(ne - p)) ? -1 : 0;
}

/* One statement, keyword [k, p). 0 or -1. */
static int st_statement(StlText *s, const char *k, const char *p)
{
    const char *le = s->le;
    size_t kn = (size_t)(p - k);
    /* By frequency: vertex, then the facet's other lines. */
    if (kn == 6 && mesh_word_is(k, le, "vertex"))
        return st_vertex(s, p);
    if (kn == 5 && mesh_word_is(k, le, "facet"))
        return st_facet(s, p);
    if (kn == 5 && mesh_word_is(k, le, "outer")) {
        if (!s->in_facet || s->in_loop)
            return me_fail_line(s->e, s->lr.line, "'outer loop' outside a facet");
        s->in_loop = 1;
        return 0;
    }
    if (kn == 7 && mesh_word_is(k, le, "endloop")) {
        s->in_loop = 0;
        return 0;
    }
    if (kn == 8 && mesh_word_is(k, le, "endfacet"))
        return st_endfacet(s);
    if (kn == 5 && mesh_word_is(k, le, "solid"))
        return st_solid(s, p);
    /* a missing final endsolid is common and harmless: endsolid only
     * checks it closes no facet */
    if (kn == 8 && mesh_word_is(k, le, "endsolid"))
        return s->in_facet ? me_fail_line(s->e, s->lr.line, "endsolid inside a facet") : 0;
    if (mesh_has_binary(s->ls, le))
        return me_fail_line(s->e, s->lr.line, "binary or unreadable data");
    return me_fail_line(s->e, s->lr.line, "unknown statement '%.*s' (expected facet, vertex, ...)",
                        mesh_tok_len(k, le), k);
}

/* The statements line by line, then the last facet merged. 0 or -1. */
static int st_lines(StlText *s)
{
    while (lr_next(&s->lr, &s->ls, &s->le)) {
        const char *p = s->ls, *le = s->le;
        while (p < le && mesh_is_blank(*p))
            p++;
        if (p >= le)
            continue;
        const char *k = p;
        while (p < le && !mesh_is_blank(*p))
            p++;
        if (st_statement(s, k, p))
            return -1;
    }
    if (s->in_facet)
        return me_fail_line(s->e, s->facet_line, "file ends inside this facet");
    return pend_flush(&s->prev, &s->vm, s->b);
}

static int stl_ascii(MeshCtx *c, MeshBuild *b, const char *data, size_t len)
{
    snprintf(c->m->info.format, sizeof c->m->info.format, "stl ascii");
    stl_stance(c->m);
    /* About 250 bytes a triangle; a guess only (arrays grow past it). */
    size_t guess = len / 250 + 64;
    if (mb_reserve_ex(b, guess / 2, guess, 3 * guess, 0))
        return -1;
    StlText s = { .e = &c->err, .b = b };
    if (vm_init(&s.vm, guess / 2))
        return me_oom(&c->err);
    size_t bom = mesh_bom_len(data, len);
    lr_init(&s.lr, data + bom, len - bom, c->file);
    int r = st_lines(&s);
    free(s.cur.bits);
    free(s.prev.bits);
    vm_free(&s.vm);
    return r;
}

static int stl_parse(MeshCtx *c, const char *data, size_t len)
{
    MeshBuild b;
    if (mb_start(&b, c->m, &c->err, c->err.name))
        return -1;
    c->m->info.bytes = len;
    /* Binary when the size says so, unless the text says ASCII; ASCII
     * when it starts with "solid" and holds no binary bytes (a truncated
     * binary file that starts with "solid" still reads as binary). */
    size_t hn = len < MESH_HEAD ? len : MESH_HEAD;
    int sized = len >= 84 && len == STL_HEADER + 4 + (uint64_t)STL_TRI * rd_u32le(data + 80);
    int ascii = sized ? looks_ascii(data, hn)
                      : after_solid(data, data + hn) &&
                            (!mesh_has_binary(data, data + hn) || len < STL_HEADER + 4);
    int r = ascii ? stl_ascii(c, &b, data, len) : stl_binary(c, &b, data, len);
    if (r || mb_finish(&b, 0)) {
        mb_abort(&b);
        return -1;
    }
    return 0;
}

const MeshLoader mesh_loader_stl = {
    .name = "stl",
    .exts = "stl",
    .what = "STL, binary and ASCII (+ VisCAM/SolidView and Materialise face colours)",
    .probe = stl_probe,
    .parse = stl_parse,
};
