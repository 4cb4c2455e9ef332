/* ply.c: PLY (Stanford polygon file), ascii, binary_little_endian and
 * binary_big_endian. The header declares elements, each a count of
 * records of typed properties; what is used:
 *   vertex   x y z (any scalar type), red green blue (alpha) as
 *            integers (0..type max) or floats (0..1)
 *   face     the list vertex_indices (or vertex_index), any count and
 *            index type; red green blue as for vertices (face colours)
 * Everything else (other elements, other properties, in any order) is
 * skipped by its size. Every element's count is checked against the
 * bytes after the header before anything is allocated. A file with
 * vertices and no faces is a point cloud: every vertex a point (with its
 * colour), and no per-point array.
 *
 * This file reads the header and is the loader; the bodies are read by
 * plybin.c and plyascii.c (ply.h is what the three share). */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ply.h"

/* ==== The header ==== */

const unsigned ply_type_size[] = { 1, 1, 2, 2, 4, 4, 4, 8 };
const double ply_type_max[] = { 127, 255, 32767, 65535, 2147483647.0, 4294967295.0, 1, 1 };

static int type_of(const char *p, const char *e, PlyType *t)
{
    static const struct {
        const char *name;
        PlyType     t;
    } tab[] = {
        { "char", T_I8 },   { "int8", T_I8 },     { "uchar", T_U8 },   { "uint8", T_U8 },
        { "short", T_I16 }, { "int16", T_I16 },   { "ushort", T_U16 }, { "uint16", T_U16 },
        { "int", T_I32 },   { "int32", T_I32 },   { "uint", T_U32 },   { "uint32", T_U32 },
        { "float", T_F32 }, { "float32", T_F32 }, { "double", T_F64 }, { "float64", T_F64 },
    };
    size_t n = (size_t)(e - p);
    for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++)
        if (strlen(tab[i].name) == n && memcmp(tab[i].name, p, n) == 0) {
            *t = tab[i].t;
            return 0;
        }
    return -1;
}

static int eq(const char *p, const char *e, const char *w)
{
    return strlen(w) == (size_t)(e - p) && memcmp(p, w, (size_t)(e - p)) == 0;
}

/* The next blank-separated word of [*p, e) into [*ws, *we); 0 if none. */
static int word(const char **p, const char *e, const char **ws, const char **we)
{
    while (*p < e && mesh_is_blank(**p))
        (*p)++;
    if (*p >= e)
        return 0;
    *ws = *p;
    while (*p < e && !mesh_is_blank(**p))
        (*p)++;
    *we = *p;
    return 1;
}

static int vertex_role(const char *p, const char *e)
{
    if (eq(p, e, "x")) return R_X;
    if (eq(p, e, "y")) return R_Y;
    if (eq(p, e, "z")) return R_Z;
    if (eq(p, e, "red") || eq(p, e, "r") || eq(p, e, "diffuse_red")) return R_RED;
    if (eq(p, e, "green") || eq(p, e, "g") || eq(p, e, "diffuse_green")) return R_GREEN;
    if (eq(p, e, "blue") || eq(p, e, "b") || eq(p, e, "diffuse_blue")) return R_BLUE;
    if (eq(p, e, "alpha") || eq(p, e, "a") || eq(p, e, "diffuse_alpha")) return R_ALPHA;
    return R_NONE;
}

/* "format NAME VERSION", the words after "format" at p. 0 or -1. */
static int header_format(Ply *ply, const char *p, const char *le, uint64_t line)
{
    const char *a, *ae;
    if (!word(&p, le, &a, &ae))
        return me_fail_line(ply->e, line, "format needs a name");
    if (eq(a, ae, "ascii"))
        ply->fmt = FMT_ASCII;
    else if (eq(a, ae, "binary_little_endian"))
        ply->fmt = FMT_LE;
    else if (eq(a, ae, "binary_big_endian"))
        ply->fmt = FMT_BE;
    else
        return me_fail_line(ply->e, line, "unknown format '%.*s'", (int)(ae - a), a);
    return 0;
}

/* "element NAME COUNT": a new element, the one later properties belong
 * to. A second vertex or face element is refused. 0 or -1. */
static int header_element(Ply *ply, const char *p, const char *le, uint64_t line)
{
    MeshErr *e = ply->e;
    const char *n, *ne, *a, *ae;
    if (!word(&p, le, &n, &ne) || !word(&p, le, &a, &ae))
        return me_fail_line(e, line, "element needs a name and a count");
    const char *q = a;
    int64_t count;
    if (mesh_parse_int(&q, ae, &count) || count < 0)
        return me_fail_line(e, line, "bad element count '%.*s'", (int)(ae - a), a);
    if (ply->nel == ply->elcap) {
        uint32_t nc = ply->elcap ? ply->elcap * 2 : 4;
        PlyElem *ne2 = realloc(ply->el, nc * sizeof *ne2);
        if (!ne2)
            return me_oom(e);
        ply->el = ne2;
        ply->elcap = nc;
    }
    PlyElem *cur = &ply->el[ply->nel++];
    memset(cur, 0, sizeof *cur);
    size_t nl = (size_t)(ne - n) < sizeof cur->name - 1 ? (size_t)(ne - n) : sizeof cur->name - 1;
    memcpy(cur->name, n, nl);
    cur->count = (uint64_t)count;
    cur->kind = eq(n, ne, "vertex") ? EL_VERTEX : eq(n, ne, "face") ? EL_FACE : EL_OTHER;
    for (uint32_t i = 0; i + 1 < ply->nel; i++)
        if (cur->kind != EL_OTHER && ply->el[i].kind == cur->kind)
            return me_fail_line(e, line, "a second '%s' element", cur->name);
    return 0;
}

/* A property's types at *pp: "TYPE" or "list COUNTTYPE ITEMTYPE", into
 * pr; [*ts, *te) the item type, for messages. 0 or -1. */
static int property_types(Ply *ply, const char **pp, const char *le, uint64_t line, PlyProp *pr,
                          const char **ts, const char **te)
{
    MeshErr *e = ply->e;
    const char *a, *ae;
    if (!word(pp, le, &a, &ae))
        return me_fail_line(e, line, "property needs a type and a name");
    if (!eq(a, ae, "list")) {
        if (type_of(a, ae, &pr->type))
            return me_fail_line(e, line, "unknown type '%.*s'", (int)(ae - a), a);
        *ts = a;
        *te = ae;
        return 0;
    }
    const char *t2, *t2e;
    if (!word(pp, le, &a, &ae) || !word(pp, le, &t2, &t2e))
        return me_fail_line(e, line, "list needs a count type and an item type");
    if (type_of(a, ae, &pr->count_type) || pr->count_type >= T_F32)
        return me_fail_line(e, line, "bad list count type '%.*s'", (int)(ae - a), a);
    if (type_of(t2, t2e, &pr->type))
        return me_fail_line(e, line, "unknown type '%.*s'", (int)(t2e - t2), t2);
    *ts = t2;
    *te = t2e;
    return 0;
}

/* "property TYPE NAME" or "property list COUNTTYPE ITEMTYPE NAME" of
 * the element cur: its role (a coordinate, a colour channel, the index
 * list) from its name. 0 or -1. */
static int header_property(Ply *ply, PlyElem *cur, const char *p, const char *le, uint64_t line)
{
    MeshErr *e = ply->e;
    if (!cur)
        return me_fail_line(e, line, "property before any element");
    PlyProp pr = { .count_type = T_NONE };
    const char *ts = NULL, *te = NULL;
    if (property_types(ply, &p, le, line, &pr, &ts, &te))
        return -1;
    const char *n, *ne;
    if (!word(&p, le, &n, &ne))
        return me_fail_line(e, line, "property needs a name");
    if (cur->kind == EL_VERTEX && pr.count_type == T_NONE)
        pr.role = vertex_role(n, ne);
    if (cur->kind == EL_FACE) {
        if (pr.count_type != T_NONE && (eq(n, ne, "vertex_indices") || eq(n, ne, "vertex_index")))
            pr.role = R_INDICES;
        else if (pr.count_type == T_NONE)
            pr.role = vertex_role(n, ne) >= R_RED ? vertex_role(n, ne) : R_NONE;
    }
    if (pr.role == R_INDICES && pr.type >= T_F32)
        return me_fail_line(e, line, "vertex indices of type %.*s (not an integer type)",
                            (int)(te - ts), ts);
    for (uint32_t i = 0; i < cur->nprops; i++)
        if (pr.role != R_NONE && cur->props[i].role == pr.role)
            return me_fail_line(e, line, "property '%.*s' given twice", (int)(ne - n), n);
    if (cur->nprops == cur->cap) {
        uint32_t nc = cur->cap ? cur->cap * 2 : 8;
        PlyProp *np = realloc(cur->props, nc * sizeof *np);
        if (!np)
            return me_oom(e);
        cur->props = np;
        cur->cap = nc;
    }
    cur->props[cur->nprops++] = pr;
    return 0;
}

/* The header, from "ply" to "end_header", into ply's elements, format
 * and body. 0 or -1. */
static int parse_header(Ply *ply, const char *data, size_t len)
{
    MeshErr *e = ply->e;
    LineReader lr;
    lr_init(&lr, data, len, ply->c->file);
    const char *ls, *le;
    if (!lr_next(&lr, &ls, &le) || !eq(ls, le, "ply"))
        return me_fail_line(e, 1, "not a PLY file (the first line is not 'ply')");
    /* the header's lines end as its first does: a lone CR there means
     * that a binary body may start with a LF byte after end_header's CR */
    int cr_only = le < lr.end && *le == '\r' && (le + 1 == lr.end || le[1] != '\n');
    int have_format = 0;
    for (;;) {
        if (!lr_next(&lr, &ls, &le))
            return me_fail_line(e, lr.line, "the header has no end_header");
        uint64_t line = lr.line;
        if (mesh_has_binary(ls, le))
            return me_fail_line(e, line, "binary or unreadable data in the header");
        const char *p = ls, *ks, *ke;
        if (!word(&p, le, &ks, &ke) || eq(ks, ke, "comment") || eq(ks, ke, "obj_info"))
            continue;
        int r;
        if (eq(ks, ke, "end_header")) {
            ply->body = cr_only && le < lr.end && *le == '\r' ? le + 1 : lr.p;
            ply->body_line = lr.line + 1;
            break;
        } else if (eq(ks, ke, "format")) {
            r = header_format(ply, p, le, line);
            have_format = 1;
        } else if (eq(ks, ke, "element")) {
            r = header_element(ply, p, le, line);
        } else if (eq(ks, ke, "property")) {
            r = header_property(ply, ply->nel ? &ply->el[ply->nel - 1] : NULL, p, le, line);
        } else {
            /* writers put their own lines in ("Created by Blender3D 247"):
             * skipped and counted like any statement (--strict refuses) */
            me_fail_line(e, line, "unknown header line '%.*s'", mesh_tok_len(ks, le), ks);
            if (me_skip(e, line))
                return -1;
            continue;
        }
        if (r)
            return -1;
    }
    if (!have_format)
        return me_fail_line(e, 2, "the header has no format line");
    return 0;
}

/* Sizes, and the counts checked against what follows the header. */
static int check_counts(Ply *ply)
{
    MeshErr *e = ply->e;
    uint64_t avail = (uint64_t)(ply->end - ply->body);
    /* ascii: every number takes at least a digit and a separator */
    uint64_t budget = ply->fmt == FMT_ASCII ? avail / 2 + 1 : avail;
    uint64_t used = 0;
    int have_vertex = 0;
    for (uint32_t i = 0; i < ply->nel; i++) {
        PlyElem *el = &ply->el[i];
        el->fixed = 0;
        el->min_size = 0;
        el->min_tokens = 0;
        int has_xyz = 0, has_idx = 0;
        for (uint32_t k = 0; k < el->nprops; k++) {
            PlyProp *pr = &el->props[k];
            if (pr->count_type == T_NONE) {
                pr->offset = (unsigned)el->fixed;
                el->fixed += ply_type_size[pr->type];
                el->min_size += ply_type_size[pr->type];
                el->min_tokens++;
            } else {
                el->has_list = 1;
                /* a face needs 3 indices; other lists may be empty */
                uint64_t items = pr->role == R_INDICES ? 3 : 0;
                el->min_size += ply_type_size[pr->count_type] + items * ply_type_size[pr->type];
                el->min_tokens += 1 + items;
            }
            has_xyz |= pr->role == R_X ? 1 : pr->role == R_Y ? 2 : pr->role == R_Z ? 4 : 0;
            has_idx |= pr->role == R_INDICES;
        }
        if (el->kind == EL_VERTEX) {
            if (has_xyz != 7)
                return me_fail(e, "the vertex element lacks x, y or z");
            if (el->count >= UINT32_MAX)
                return me_fail(e, "too many vertices (%llu)", (unsigned long long)el->count);
            ply->nverts = el->count;
            have_vertex = 1;
        }
        if (el->kind == EL_FACE) {
            if (!has_idx)
                return me_fail(e, "the face element has no vertex_indices list");
            if (el->count >= UINT32_MAX)
                return me_fail(e, "too many faces (%llu)", (unsigned long long)el->count);
        }
        uint64_t unit = ply->fmt == FMT_ASCII ? el->min_tokens : el->min_size;
        uint64_t left = (ply->fmt == FMT_ASCII ? budget : avail) - used;
        if (unit && el->count > left / unit) {
            me_fail(e, "element '%s' of %llu records needs more than the %llu bytes after the header",
                    el->name, (unsigned long long)el->count, (unsigned long long)avail);
            /* a file cut short shows what it has (not strict): the
             * records are read until the bytes run out (the whole
             * vertices there; faces as far as they go; what follows
             * has none) */
            if (me_skip(e, 0))
                return -1;
            el->count = left / unit;
            if (el->kind == EL_VERTEX)
                ply->nverts = el->count;
        }
        used += unit * el->count;
    }
    if (!have_vertex)
        return me_fail(e, "no vertex element");
    return 0;
}

/* ==== Shared by the bodies ==== */

int ply_face_colour(Ply *ply, const float c3[3], int32_t *mat)
{
    uint8_t q[3];
    for (int k = 0; k < 3; k++)
        q[k] = (uint8_t)(c3[k] * 255.0f + 0.5f);
    *mat = mb_colour(ply->b, q[0], q[1], q[2], 255);
    return *mat < 0 ? -1 : 0;
}

int ply_ended_early(Ply *ply)
{
    if (me_skip(ply->e, 0))
        return -1;
    ply->ended = 1;
    return 0;
}

/* ==== Streams ==== */

/* a + b, and a * b, stopping at a bound far past any stream */
#define PLY_HUGE ((uint64_t)1 << 62)
static uint64_t sat_add(uint64_t a, uint64_t b) { return a + b < PLY_HUGE ? a + b : PLY_HUGE; }
static uint64_t sat_mul(uint64_t a, uint64_t b)
{
    return a && b > PLY_HUGE / a ? PLY_HUGE : a * b < PLY_HUGE ? a * b : PLY_HUGE;
}

uint64_t mesh_ply_stream_max(const char *head, size_t n, int *ascii)
{
    static const uint64_t list_max[] = { 127, 255, 32767, 65535, 2147483647u, 4294967295u };
    MeshCtx c = { .err = { .name = "(stream)" } };
    Ply ply = { .c = &c, .e = &c.err, .data = head, .end = head + n };
    size_t bom = mesh_bom_len(head, n);
    uint64_t max = 0;
    *ascii = 0;
    if (parse_header(&ply, head + bom, n - bom) == 0) {
        *ascii = ply.fmt == FMT_ASCII;
        /* binary: the largest record each element's types allow (ascii
         * numbers have no length: only the NUL bounds those) */
        max = *ascii ? 0 : (uint64_t)(ply.body - head) + 1;
        for (uint32_t i = 0; i < ply.nel && max; i++) {
            uint64_t rec = 0;
            for (uint32_t k = 0; k < ply.el[i].nprops; k++) {
                const PlyProp *pr = &ply.el[i].props[k];
                rec = pr->count_type == T_NONE
                          ? sat_add(rec, ply_type_size[pr->type])
                          : sat_add(rec, sat_add(ply_type_size[pr->count_type],
                                                 sat_mul(list_max[pr->count_type], ply_type_size[pr->type])));
            }
            max = sat_add(max, sat_mul(ply.el[i].count, rec));
        }
    }
    for (uint32_t i = 0; i < ply.nel; i++)
        free(ply.el[i].props);
    free(ply.el);
    return max >= PLY_HUGE ? 0 : max;
}

/* ==== The loader ==== */

static int ply_probe(const char *head, size_t n, uint64_t size)
{
    (void)size;
    size_t bom = mesh_bom_len(head, n);
    head += bom;
    n -= bom;
    if (n >= 4 && memcmp(head, "ply", 3) == 0 && (head[3] == '\n' || head[3] == '\r'))
        return PROBE_SURE;
    return PROBE_NO;
}

static int ply_parse(MeshCtx *c, const char *data, size_t len)
{
    MeshBuild b;
    if (mb_start(&b, c->m, &c->err, c->err.name))
        return -1;
    Mesh *m = c->m;
    m->info.bytes = len;
    Ply ply = { .c = c, .e = &c->err, .b = &b, .data = data, .end = data + len };
    int r = -1;
    size_t bom = mesh_bom_len(data, len);
    if (parse_header(&ply, data + bom, len - bom) || check_counts(&ply))
        goto out;
    static const char *const fmt_name[] = { "ply ascii", "ply binary little endian",
                                            "ply binary big endian" };
    snprintf(m->info.format, sizeof m->info.format, "%s", fmt_name[ply.fmt]);
    /* Allocate once: the counts are known and were checked against the
     * size, and now against the limits. */
    uint64_t nfaces = 0;
    int rgb = 0;
    for (uint32_t i = 0; i < ply.nel; i++) {
        if (ply.el[i].kind == EL_FACE)
            nfaces = ply.el[i].count;
        for (uint32_t k = 0; ply.el[i].kind == EL_VERTEX && k < ply.el[i].nprops; k++)
            rgb |= ply.el[i].props[k].role >= R_RED && ply.el[i].props[k].role <= R_BLUE;
    }
    if (mb_afford_counts(&b, ply.nverts, rgb, nfaces) || mb_reserve(&b, ply.nverts, nfaces, 3 * nfaces))
        goto out;
    if (ply.fmt == FMT_ASCII ? ply_read_ascii(&ply) : ply_read_binary(&ply, data))
        goto out;
    /* Vertices of elements before the vertex element were not there
     * when faces were read: indices were checked against the header's
     * count, which the vertex element then filled. */
    r = mb_finish(&b, 1);
out:
    for (uint32_t i = 0; i < ply.nel; i++)
        free(ply.el[i].props);
    free(ply.el);
    if (r)
        mb_abort(&b);
    return r;
}

const MeshLoader mesh_loader_ply = {
    .name = "ply",
    .exts = "ply",
    .what = "PLY: ascii, binary little and big endian (+ vertex and face colours)",
    .probe = ply_probe,
    .parse = ply_parse,
    .needs_magic = 1,
};
