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
 * colour), and no per-point array. */
#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "mesh_internal.h"

/* ==== The header ==== */

typedef enum { T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64, T_NONE } PlyType;

static const unsigned type_size[] = { 1, 1, 2, 2, 4, 4, 4, 8 };
static const double type_max[] = { 127, 255, 32767, 65535, 2147483647.0, 4294967295.0, 1, 1 };

enum { R_NONE, R_X, R_Y, R_Z, R_RED, R_GREEN, R_BLUE, R_ALPHA, R_INDICES };
enum { EL_OTHER, EL_VERTEX, EL_FACE };
enum { FMT_ASCII, FMT_LE, FMT_BE };

typedef struct {
    PlyType  type;        /* scalar type, or the list's item type */
    PlyType  count_type;  /* a list's count type; T_NONE: a scalar */
    int      role;
    unsigned offset;      /* in a record of fixed size (binary, no lists) */
} PlyProp;

typedef struct {
    char     name[32];
    uint64_t count;
    int      kind;
    PlyProp *props;
    uint32_t nprops, cap;
    int      has_list;
    uint64_t fixed;       /* record size without lists */
    uint64_t min_size;    /* the least bytes a record can take (binary) */
    uint64_t min_tokens;  /* the least numbers a record holds (ascii) */
} PlyElem;

typedef struct {
    MeshCtx   *c;
    MeshErr   *e;
    MeshBuild *b;
    int        fmt;
    PlyElem   *el;
    uint32_t   nel, elcap;
    const char *data, *body, *end;
    uint64_t   body_line;  /* ascii: the line the body starts on */
    uint64_t   nverts;     /* the vertex element's count */
    int        ended;      /* the file ended inside the faces (kept so far) */
} Ply;

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
    PlyElem *cur = NULL;
    for (;;) {
        if (!lr_next(&lr, &ls, &le))
            return me_fail_line(e, lr.line, "the header has no end_header");
        uint64_t line = lr.line;
        if (mesh_has_binary(ls, le))
            return me_fail_line(e, line, "binary or unreadable data in the header");
        const char *p = ls, *ks, *ke;
        if (!word(&p, le, &ks, &ke))
            continue;
        if (eq(ks, ke, "comment") || eq(ks, ke, "obj_info"))
            continue;
        if (eq(ks, ke, "end_header")) {
            ply->body = cr_only && le < lr.end && *le == '\r' ? le + 1 : lr.p;
            ply->body_line = lr.line + 1;
            break;
        }
        const char *a, *ae;
        if (eq(ks, ke, "format")) {
            if (!word(&p, le, &a, &ae))
                return me_fail_line(e, line, "format needs a name");
            if (eq(a, ae, "ascii"))
                ply->fmt = FMT_ASCII;
            else if (eq(a, ae, "binary_little_endian"))
                ply->fmt = FMT_LE;
            else if (eq(a, ae, "binary_big_endian"))
                ply->fmt = FMT_BE;
            else
                return me_fail_line(e, line, "unknown format '%.*s'", (int)(ae - a), a);
            have_format = 1;
            continue;
        }
        if (eq(ks, ke, "element")) {
            const char *n, *ne;
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
            cur = &ply->el[ply->nel++];
            memset(cur, 0, sizeof *cur);
            size_t nl = (size_t)(ne - n) < sizeof cur->name - 1 ? (size_t)(ne - n) : sizeof cur->name - 1;
            memcpy(cur->name, n, nl);
            cur->count = (uint64_t)count;
            cur->kind = eq(n, ne, "vertex") ? EL_VERTEX : eq(n, ne, "face") ? EL_FACE : EL_OTHER;
            for (uint32_t i = 0; i + 1 < ply->nel; i++)
                if (cur->kind != EL_OTHER && ply->el[i].kind == cur->kind)
                    return me_fail_line(e, line, "a second '%s' element", cur->name);
            continue;
        }
        if (eq(ks, ke, "property")) {
            if (!cur)
                return me_fail_line(e, line, "property before any element");
            PlyProp pr = { .count_type = T_NONE };
            const char *ts = NULL, *te = NULL;   /* the item type, for messages */
            if (!word(&p, le, &a, &ae))
                return me_fail_line(e, line, "property needs a type and a name");
            if (eq(a, ae, "list")) {
                const char *t2, *t2e;
                if (!word(&p, le, &a, &ae) || !word(&p, le, &t2, &t2e))
                    return me_fail_line(e, line, "list needs a count type and an item type");
                if (type_of(a, ae, &pr.count_type) || pr.count_type >= T_F32)
                    return me_fail_line(e, line, "bad list count type '%.*s'", (int)(ae - a), a);
                if (type_of(t2, t2e, &pr.type))
                    return me_fail_line(e, line, "unknown type '%.*s'", (int)(t2e - t2), t2);
                ts = t2;
                te = t2e;
            } else if (type_of(a, ae, &pr.type)) {
                return me_fail_line(e, line, "unknown type '%.*s'", (int)(ae - a), a);
            } else {
                ts = a;
                te = ae;
            }
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
            continue;
        }
        return me_fail_line(e, line, "unknown header line '%.*s'", mesh_tok_len(ks, le), ks);
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
                el->fixed += type_size[pr->type];
                el->min_size += type_size[pr->type];
                el->min_tokens++;
            } else {
                el->has_list = 1;
                /* a face needs 3 indices; other lists may be empty */
                uint64_t items = pr->role == R_INDICES ? 3 : 0;
                el->min_size += type_size[pr->count_type] + items * type_size[pr->type];
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
            /* a file cut short in its faces shows what it has (not
             * strict): the faces are read until the bytes run out */
            if (el->kind != EL_FACE || me_skip(e, 0))
                return -1;
            el->count = left / unit;
        }
        used += unit * el->count;
    }
    if (!have_vertex)
        return me_fail(e, "no vertex element");
    return 0;
}

/* ==== Binary ==== */

typedef struct {
    const unsigned char *p, *end, *base;
    int swap;
} Bin;

/* Loads of 1, 2, 4 and 8 bytes in the file's byte order. Constant-size
 * copies compile to single moves (a size known only at run time would
 * call memcpy for every value). */
static inline uint16_t ld16(const unsigned char *p, int swap)
{
    uint16_t v;
    memcpy(&v, p, 2);
    return swap ? __builtin_bswap16(v) : v;
}
static inline uint32_t ld32(const unsigned char *p, int swap)
{
    uint32_t v;
    memcpy(&v, p, 4);
    return swap ? __builtin_bswap32(v) : v;
}
static inline uint64_t ld64(const unsigned char *p, int swap)
{
    uint64_t v;
    memcpy(&v, p, 8);
    return swap ? __builtin_bswap64(v) : v;
}

/* A scalar as double (exact for every integer type). */
static inline double get_num(const unsigned char *p, PlyType t, int swap)
{
    switch (t) {
    case T_I8: return (int8_t)p[0];
    case T_U8: return p[0];
    case T_I16: return (int16_t)ld16(p, swap);
    case T_U16: return ld16(p, swap);
    case T_I32: return (int32_t)ld32(p, swap);
    case T_U32: return ld32(p, swap);
    case T_F32: {
        uint32_t u = ld32(p, swap);
        float f;
        memcpy(&f, &u, 4);
        return f;
    }
    default: {
        uint64_t u = ld64(p, swap);
        double d;
        memcpy(&d, &u, 8);
        return d;
    }
    }
}

/* An integer-typed value (list counts, indices) as int64. */
static inline int64_t get_int(const unsigned char *p, PlyType t, int swap)
{
    switch (t) {
    case T_I8: return (int8_t)p[0];
    case T_U8: return p[0];
    case T_I16: return (int16_t)ld16(p, swap);
    case T_U16: return ld16(p, swap);
    case T_I32: return (int32_t)ld32(p, swap);
    default: return ld32(p, swap);
    }
}

static float colour_of(double v, PlyType t)
{
    float f = (float)(t >= T_F32 ? v : v / type_max[t]);
    return f < 0 ? 0 : f > 1 ? 1 : f;
}

/* A coordinate as float; -1 when not finite (or past a float's range). */
static inline int to_coord(double v, float *out)
{
    if (!(fabs(v) <= 3.4028234663852886e38))
        return -1;
    *out = (float)v;
    return 0;
}

static int bin_vertices(Ply *ply, PlyElem *el, Bin *bn)
{
    MeshBuild *b = ply->b;
    Mesh *m = b->m;
    int swap = bn->swap;
    const PlyProp *px = NULL, *py = NULL, *pz = NULL, *pc[3] = { NULL, NULL, NULL };
    for (uint32_t k = 0; k < el->nprops; k++) {
        const PlyProp *pr = &el->props[k];
        if (pr->role == R_X) px = pr;
        if (pr->role == R_Y) py = pr;
        if (pr->role == R_Z) pz = pr;
        if (pr->role >= R_RED && pr->role <= R_BLUE) pc[pr->role - R_RED] = pr;
    }
    int rgb = pc[0] || pc[1] || pc[2];
    if (rgb && mb_want_rgb(b))
        return -1;
    uint32_t n = (uint32_t)el->count;
    if (n == 0)
        return 0;           /* no vertex: no array to point into (it may be NULL) */
    float *pos = m->pos + 3 * (size_t)m->nverts;
    float *col = rgb ? m->rgb + 3 * (size_t)m->nverts : NULL;
    if (!el->has_list) {
        /* Records of one size: each property at a fixed offset. */
        size_t rs = (size_t)el->fixed;
        const unsigned char *r = bn->p;
        int fast = px->type == T_F32 && py->type == T_F32 && pz->type == T_F32;
        /* a scan's colours: three uchar, each through a table (a
         * conversion and a division per channel cost more than the rest
         * of the record) */
        int rgb8 = col && pc[0] && pc[1] && pc[2] && pc[0]->type == T_U8 && pc[1]->type == T_U8 &&
                   pc[2]->type == T_U8;
        float lut[256];
        for (int k = 0; rgb8 && k < 256; k++)
            lut[k] = colour_of(k, T_U8);
        MeshFile *file = ply->c->file;
        for (uint32_t i = 0; i < n; i++, r += rs) {
            mf_need(file, r, r + rs);
            if (fast) {
                uint32_t u[3] = { ld32(r + px->offset, swap), ld32(r + py->offset, swap),
                                  ld32(r + pz->offset, swap) };
                if (bits_nonfinite(u[0]) || bits_nonfinite(u[1]) || bits_nonfinite(u[2]))
                    return me_fail_at(ply->e, (uint64_t)(r - bn->base),
                                      "NaN or infinite coordinate (vertex %u)", i + 1);
                memcpy(pos + 3 * (size_t)i, u, sizeof u);
            } else {
                float *d = pos + 3 * (size_t)i;
                if (to_coord(get_num(r + px->offset, px->type, swap), &d[0]) ||
                    to_coord(get_num(r + py->offset, py->type, swap), &d[1]) ||
                    to_coord(get_num(r + pz->offset, pz->type, swap), &d[2]))
                    return me_fail_at(ply->e, (uint64_t)(r - bn->base),
                                      "NaN, infinite or out-of-range coordinate (vertex %u)", i + 1);
            }
            if (rgb8) {
                float *c = col + 3 * (size_t)i;
                c[0] = lut[r[pc[0]->offset]];
                c[1] = lut[r[pc[1]->offset]];
                c[2] = lut[r[pc[2]->offset]];
            } else if (col) {
                for (int k = 0; k < 3; k++)
                    col[3 * (size_t)i + k] =
                        pc[k] ? colour_of(get_num(r + pc[k]->offset, pc[k]->type, swap), pc[k]->type) : 1.0f;
            }
        }
        bn->p = r;
    } else {
        /* Lists in the vertex element (rare): property by property. */
        const unsigned char *r = bn->p;
        MeshFile *file = ply->c->file;
        for (uint32_t i = 0; i < n; i++) {
            float v[3] = { 0, 0, 0 }, c3[3] = { 1, 1, 1 };
            for (uint32_t k = 0; k < el->nprops; k++) {
                const PlyProp *pr = &el->props[k];
                mf_need(file, r, r + (bn->end - r < 8 ? bn->end - r : 8));
                if (pr->count_type != T_NONE) {
                    if ((size_t)(bn->end - r) < type_size[pr->count_type])
                        return me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside vertex %u", i + 1);
                    int64_t cnt = get_int(r, pr->count_type, swap);
                    r += type_size[pr->count_type];
                    if (cnt < 0 || (uint64_t)cnt > (uint64_t)(bn->end - r) / type_size[pr->type])
                        return me_fail_at(ply->e, (uint64_t)(r - bn->base), "bad list count %lld (vertex %u)",
                                          (long long)cnt, i + 1);
                    r += (size_t)cnt * type_size[pr->type];
                    continue;
                }
                if ((size_t)(bn->end - r) < type_size[pr->type])
                    return me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside vertex %u", i + 1);
                double x = get_num(r, pr->type, swap);
                if (pr->role >= R_X && pr->role <= R_Z && to_coord(x, &v[pr->role - R_X]))
                    return me_fail_at(ply->e, (uint64_t)(r - bn->base),
                                      "NaN, infinite or out-of-range coordinate (vertex %u)", i + 1);
                if (pr->role >= R_RED && pr->role <= R_BLUE)
                    c3[pr->role - R_RED] = colour_of(x, pr->type);
                r += type_size[pr->type];
            }
            memcpy(pos + 3 * (size_t)i, v, sizeof v);
            if (col)
                memcpy(col + 3 * (size_t)i, c3, sizeof c3);
        }
        bn->p = r;
    }
    m->nverts += n;
    return 0;
}

static int face_colour(Ply *ply, const float c3[3], int32_t *mat)
{
    uint8_t q[3];
    for (int k = 0; k < 3; k++)
        q[k] = (uint8_t)(c3[k] * 255.0f + 0.5f);
    *mat = mb_colour(ply->b, q[0], q[1], q[2], 255);
    return *mat < 0 ? -1 : 0;
}

static int bad_index(Ply *ply, uint64_t at, int64_t v, uint32_t face)
{
    return me_fail_at(ply->e, at, "vertex index %lld out of range (%llu vertices; face %u)",
                      (long long)v, (unsigned long long)ply->nverts, face + 1);
}

/* The faces read so far are kept when the file ends inside one (not
 * strict): the rest of the file is one skipped statement. Returns 0 to
 * go on (with ply->ended set), -1 to fail. */
static int ended_early(Ply *ply)
{
    if (me_skip(ply->e, 0))
        return -1;
    ply->ended = 1;
    return 0;
}

static int bin_faces(Ply *ply, PlyElem *el, Bin *bn)
{
    MeshBuild *b = ply->b;
    Mesh *m = b->m;
    int swap = bn->swap;
    uint32_t n = (uint32_t)el->count;
    int coloured = 0;
    for (uint32_t k = 0; k < el->nprops; k++)
        coloured |= el->props[k].role >= R_RED && el->props[k].role <= R_BLUE;
    const unsigned char *r = bn->p, *end = bn->end;
    uint64_t nv = ply->nverts;
    /* The common layout: the index list alone, no colours. */
    const PlyProp *only = el->nprops == 1 ? &el->props[0] : NULL;
    MeshFile *file = ply->c->file;
    for (uint32_t i = 0; i < n; i++) {
        size_t first = b->ncorner;
        float c3[3] = { 1, 1, 1 };
        /* a face that cannot be read whole but whose size is known is
         * skipped (counted; strict fails on it) */
        int skip = 0;
        if (only) {
            unsigned cs = type_size[only->count_type], is = type_size[only->type];
            mf_need(file, r, r + ((size_t)(end - r) < 8 ? (size_t)(end - r) : 8));
            if ((size_t)(end - r) < cs) {
                me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside face %u", i + 1);
                return ended_early(ply);
            }
            int64_t cnt = get_int(r, only->count_type, swap);
            r += cs;
            if (cnt < 0)
                return me_fail_at(ply->e, (uint64_t)(r - cs - bn->base),
                                  "face %u has %lld vertices (at least 3)", i + 1, (long long)cnt);
            if ((uint64_t)cnt > (uint64_t)(end - r) / is) {
                me_fail_at(ply->e, (uint64_t)(r - cs - bn->base),
                           "face %u of %lld vertices goes past the end of the file", i + 1, (long long)cnt);
                return ended_early(ply);
            }
            const unsigned char *fe = r + (size_t)cnt * is;
            mf_need(file, r, fe);
            if (cnt < 3) {
                me_fail_at(ply->e, (uint64_t)(r - cs - bn->base), "face %u has %lld vertices (at least 3)",
                           i + 1, (long long)cnt);
                if (me_skip(ply->e, (uint64_t)(r - cs - bn->base)))
                    return -1;
                r = fe;
                continue;
            }
            if (b->ncorner + (size_t)cnt > b->ccap && mb_room_corners(b, (size_t)cnt))
                return -1;
            uint32_t *dst = m->corner + b->ncorner;
            if (is == 4) {
                /* int and uint indices: one unsigned compare rejects
                 * negative ones too (they wrap past any count) */
                for (int64_t k = 0; k < cnt; k++, r += 4) {
                    uint32_t v = ld32(r, swap);
                    if (v >= nv) {
                        bad_index(ply, (uint64_t)(r - bn->base), get_int(r, only->type, swap), i);
                        skip = 1;
                        break;
                    }
                    dst[k] = v;
                }
            } else {
                for (int64_t k = 0; k < cnt; k++, r += is) {
                    int64_t v = get_int(r, only->type, swap);
                    if ((uint64_t)v >= nv) {
                        bad_index(ply, (uint64_t)(r - bn->base), v, i);
                        skip = 1;
                        break;
                    }
                    dst[k] = (uint32_t)v;
                }
            }
            if (skip) {
                if (me_skip(ply->e, (uint64_t)(r - bn->base)))
                    return -1;
                r = fe;
                continue;
            }
            b->ncorner += (size_t)cnt;
        } else {
            uint64_t at = 0;
            for (uint32_t k = 0; k < el->nprops; k++) {
                const PlyProp *pr = &el->props[k];
                mf_need(file, r, r + ((size_t)(end - r) < 8 ? (size_t)(end - r) : 8));
                if (pr->count_type != T_NONE) {
                    unsigned cs = type_size[pr->count_type], is = type_size[pr->type];
                    if ((size_t)(end - r) < cs) {
                        me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside face %u", i + 1);
                        b->ncorner = first;
                        return ended_early(ply);
                    }
                    int64_t cnt = get_int(r, pr->count_type, swap);
                    r += cs;
                    if (cnt < 0)
                        return me_fail_at(ply->e, (uint64_t)(r - cs - bn->base),
                                          "list of %lld (face %u)", (long long)cnt, i + 1);
                    if ((uint64_t)cnt > (uint64_t)(end - r) / is) {
                        me_fail_at(ply->e, (uint64_t)(r - cs - bn->base),
                                   "list of %lld goes past the end of the file (face %u)", (long long)cnt, i + 1);
                        b->ncorner = first;
                        return ended_early(ply);
                    }
                    const unsigned char *le = r + (size_t)cnt * is;
                    mf_need(file, r, le);
                    if (pr->role != R_INDICES || skip) {
                        r = le;
                        continue;
                    }
                    if (cnt < 3) {
                        me_fail_at(ply->e, at = (uint64_t)(r - cs - bn->base),
                                   "face %u has %lld vertices (at least 3)", i + 1, (long long)cnt);
                        skip = 1;
                        r = le;
                        continue;
                    }
                    for (int64_t q = 0; q < cnt; q++, r += is) {
                        int64_t v = get_int(r, pr->type, swap);
                        if ((uint64_t)v >= nv) {
                            bad_index(ply, at = (uint64_t)(r - bn->base), v, i);
                            skip = 1;
                            break;
                        }
                        if (mb_corner(b, (uint32_t)v))
                            return -1;
                    }
                    r = le;
                    continue;
                }
                if ((size_t)(end - r) < type_size[pr->type]) {
                    me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside face %u", i + 1);
                    b->ncorner = first;
                    return ended_early(ply);
                }
                if (pr->role >= R_RED && pr->role <= R_BLUE)
                    c3[pr->role - R_RED] = colour_of(get_num(r, pr->type, swap), pr->type);
                r += type_size[pr->type];
            }
            if (skip || b->ncorner == first) {
                /* a face without an index list reads as one of no vertices */
                if (!skip)
                    me_fail_at(ply->e, at = (uint64_t)(r - bn->base), "face %u has no vertices", i + 1);
                b->ncorner = first;
                if (me_skip(ply->e, at))
                    return -1;
                continue;
            }
        }
        int32_t mat = -1;
        if (coloured && face_colour(ply, c3, &mat))
            return -1;
        if (mb_face_end(b, first, mat))
            return -1;
        bn->p = r;
    }
    bn->p = r;
    return 0;
}

static int bin_skip(Ply *ply, PlyElem *el, Bin *bn)
{
    if (!el->has_list) {
        /* counts were checked against the size (the bytes are not read) */
        bn->p += el->count * el->fixed;
        return 0;
    }
    const unsigned char *r = bn->p;
    MeshFile *file = ply->c->file;
    for (uint64_t i = 0; i < el->count; i++) {
        for (uint32_t k = 0; k < el->nprops; k++) {
            const PlyProp *pr = &el->props[k];
            mf_need(file, r, r + ((size_t)(bn->end - r) < 8 ? (size_t)(bn->end - r) : 8));
            if (pr->count_type == T_NONE) {
                if ((size_t)(bn->end - r) < type_size[pr->type])
                    goto short_;
                r += type_size[pr->type];
                continue;
            }
            if ((size_t)(bn->end - r) < type_size[pr->count_type])
                goto short_;
            int64_t cnt = get_int(r, pr->count_type, bn->swap);
            r += type_size[pr->count_type];
            if (cnt < 0 || (uint64_t)cnt > (uint64_t)(bn->end - r) / type_size[pr->type])
                return me_fail_at(ply->e, (uint64_t)(r - bn->base), "list of %lld goes past the end "
                                  "of the file (element '%s')", (long long)cnt, el->name);
            r += (size_t)cnt * type_size[pr->type];
        }
    }
    bn->p = r;
    return 0;
short_:
    return me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside element '%s'", el->name);
}

/* ==== ASCII ==== */

/* The ascii body. end is where reading may go without asking the
 * paging window (the file's end, or the window's); a token is read only
 * with TXT_ROOM bytes in after it, so one longer than that is refused. */
typedef struct {
    const char *p, *end, *real_end;
    uint64_t    line;
    MeshFile   *file;
} Txt;

#define TXT_ROOM ((size_t)1 << 20)

static inline void txt_room(Txt *t)
{
    if ((size_t)(t->end - t->p) < TXT_ROOM && t->end < t->real_end) {
        size_t room = (size_t)(t->real_end - t->p) < TXT_ROOM ? (size_t)(t->real_end - t->p) : TXT_ROOM;
        mf_need(t->file, t->p, t->p + room);
        t->end = mf_limit(t->file, t->real_end);
    }
}

/* Skip white space, counting lines (LF, CRLF or CR). 0 at the end. */
static inline int txt_ws(Txt *t)
{
    for (;;) {
        txt_room(t);
        const char *p = t->p, *end = t->end;
        while (p < end && mesh_is_ws(*p)) {
            if (*p == '\n' || (*p == '\r' && (p + 1 == t->real_end || p[1] != '\n')))
                t->line++;
            p++;
        }
        t->p = p;
        if (p < end || end == t->real_end)
            return p < end;
    }
}

/* A token that ran into the window's end is longer than TXT_ROOM. */
static inline int txt_cut(const Txt *t)
{
    return t->p == t->end && t->end < t->real_end;
}

static int txt_bad(Ply *ply, Txt *t, int code, const char *what, const char *elname)
{
    const char *p = t->p;
    if (p >= t->real_end)
        return me_fail_line(ply->e, t->line, "file ends inside element '%s' (a %s missing)", elname, what);
    const char *le = p;
    while (le < t->end && *le != '\n' && *le != '\r')
        le++;
    if (mesh_has_binary(p, le))
        return me_fail_line(ply->e, t->line, "binary or unreadable data");
    int n = mesh_tok_len(p, t->end);
    if (code == MESH_NUM_NONFINITE)
        return me_fail_line(ply->e, t->line, "NaN or infinite number '%.*s'", n, p);
    if (code == MESH_NUM_RANGE)
        return me_fail_line(ply->e, t->line, "number out of range '%.*s'", n, p);
    return me_fail_line(ply->e, t->line, "malformed %s '%.*s'", what, n, p);
}

static inline int txt_num(Ply *ply, Txt *t, PlyType type, double *out, const char *elname)
{
    txt_ws(t);
    int r;
    if (type >= T_F32) {
        float f;
        r = mesh_parse_float(&t->p, t->end, &f);
        *out = f;
    } else {
        int64_t v;
        r = mesh_parse_int(&t->p, t->end, &v);
        *out = (double)v;
    }
    if (!r && txt_cut(t))
        r = MESH_NUM_BAD;
    return r ? txt_bad(ply, t, r, type >= T_F32 ? "number" : "integer", elname) : 0;
}

static inline int txt_int(Ply *ply, Txt *t, int64_t *out, const char *elname)
{
    txt_ws(t);
    int r = mesh_parse_int(&t->p, t->end, out);
    if (!r && txt_cut(t))
        r = MESH_NUM_BAD;
    return r ? txt_bad(ply, t, r, "integer", elname) : 0;
}

/* The rest of a face's line (ascii records are a line each). */
static void txt_skip_line(Txt *t)
{
    for (;;) {
        txt_room(t);
        while (t->p < t->end && *t->p != '\n' && *t->p != '\r')
            t->p++;
        if (t->p < t->end || t->end == t->real_end)
            break;
    }
}

/* A number of a face could not be read (the message is written): at
 * the end of the file the faces so far are kept; else, unless strict,
 * the face's line is skipped. Elsewhere it fails the load. */
#define FACE_UNREADABLE()                                                   \
    do {                                                                    \
        if (!face)                                                          \
            return -1;                                                      \
        b->ncorner = first;                                                 \
        if (t->p >= t->real_end)                                                \
            return ended_early(ply);                                        \
        if (me_skip(ply->e, t->line))                                       \
            return -1;                                                      \
        txt_skip_line(t);                                                   \
        goto next_record;                                                   \
    } while (0)

static int txt_element(Ply *ply, PlyElem *el, Txt *t)
{
    MeshBuild *b = ply->b;
    Mesh *m = b->m;
    int vertex = el->kind == EL_VERTEX, face = el->kind == EL_FACE;
    int coloured = 0;
    for (uint32_t k = 0; k < el->nprops; k++)
        coloured |= el->props[k].role >= R_RED && el->props[k].role <= R_BLUE;
    if (vertex && coloured && mb_want_rgb(b))
        return -1;
    for (uint64_t i = 0; i < el->count; i++) {
        float v[3] = { 0, 0, 0 }, c3[3] = { 1, 1, 1 };
        size_t first = b->ncorner;
        /* a face that cannot be used but can be read past is skipped
         * (counted; strict fails on it); at its first problem's line */
        int skip = 0;
        uint64_t skip_line = 0;
        for (uint32_t k = 0; k < el->nprops; k++) {
            const PlyProp *pr = &el->props[k];
            if (pr->count_type != T_NONE) {
                int64_t cnt;
                txt_ws(t);
                uint64_t line = t->line;
                if (txt_int(ply, t, &cnt, el->name))
                    FACE_UNREADABLE();
                if (cnt < 0 || (uint64_t)cnt > (uint64_t)(t->real_end - t->p) / 2 + 1)
                    return me_fail_line(ply->e, line, "bad list count %lld", (long long)cnt);
                if (pr->role == R_INDICES && cnt < 3 && !skip) {
                    me_fail_line(ply->e, line, "face has %lld vertices (at least 3)", (long long)cnt);
                    skip = 1;
                    skip_line = line;
                }
                for (int64_t q = 0; q < cnt; q++) {
                    if (pr->role == R_INDICES) {
                        int64_t idx;
                        if (txt_int(ply, t, &idx, el->name))
                            FACE_UNREADABLE();
                        if (skip)
                            continue;
                        if (idx < 0 || (uint64_t)idx >= ply->nverts) {
                            me_fail_line(ply->e, t->line, "vertex index %lld out of range (%llu vertices)",
                                         (long long)idx, (unsigned long long)ply->nverts);
                            skip = 1;
                            skip_line = t->line;
                            continue;
                        }
                        if (mb_corner(b, (uint32_t)idx))
                            return -1;
                    } else {
                        double d;
                        if (txt_num(ply, t, pr->type, &d, el->name))
                            return -1;
                    }
                }
                continue;
            }
            double d;
            if (txt_num(ply, t, pr->type, &d, el->name))
                FACE_UNREADABLE();
            if (pr->role >= R_X && pr->role <= R_Z && vertex && to_coord(d, &v[pr->role - R_X]))
                return me_fail_line(ply->e, t->line, "coordinate out of range");
            if (pr->role >= R_RED && pr->role <= R_BLUE)
                c3[pr->role - R_RED] = colour_of(d, pr->type);
        }
        if (vertex) {
            float *d = m->pos + 3 * (size_t)m->nverts;
            memcpy(d, v, sizeof v);
            if (m->rgb)
                memcpy(m->rgb + 3 * (size_t)m->nverts, c3, sizeof c3);
            m->nverts++;
        } else if (face && skip) {
            b->ncorner = first;
            if (me_skip(ply->e, skip_line))
                return -1;
        } else if (face) {
            int32_t mat = -1;
            if (coloured && face_colour(ply, c3, &mat))
                return -1;
            if (mb_face_end(b, first, mat))
                return -1;
        }
    next_record:;
    }
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
                          ? sat_add(rec, type_size[pr->type])
                          : sat_add(rec, sat_add(type_size[pr->count_type],
                                                 sat_mul(list_max[pr->count_type], type_size[pr->type])));
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
    if (ply.fmt == FMT_ASCII) {
        Txt t = { ply.body, mf_limit(c->file, ply.end), ply.end, ply.body_line, c->file };
        for (uint32_t i = 0; i < ply.nel; i++) {
            PlyElem *el = &ply.el[i];
            if (el->nprops == 0)
                continue;
            if (txt_element(&ply, el, &t))
                goto out;
            if (ply.ended)
                break;
        }
        if (!ply.ended && txt_ws(&t))
            me_warn(&c->err, NULL, t.line, "data after the last element ignored");
    } else {
        Bin bn = { (const unsigned char *)ply.body, (const unsigned char *)ply.end,
                   (const unsigned char *)data,
                   (ply.fmt == FMT_BE) == (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__) };
        for (uint32_t i = 0; i < ply.nel; i++) {
            PlyElem *el = &ply.el[i];
            int rr = el->kind == EL_VERTEX ? bin_vertices(&ply, el, &bn)
                   : el->kind == EL_FACE   ? bin_faces(&ply, el, &bn)
                                           : bin_skip(&ply, el, &bn);
            if (rr)
                goto out;
            if (ply.ended)
                break;
        }
        if (!ply.ended && bn.p < bn.end)
            me_warn(&c->err, NULL, 0, "%zu bytes after the last element ignored",
                    (size_t)(bn.end - bn.p));
    }
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
