/* plybin.c: the body of a binary PLY (little or big endian), element by
 * element: vertices (records of one size read at fixed offsets, the
 * common case, or property by property when the element has lists),
 * faces (the lone index list, the common case, or property by
 * property), and any other element skipped by its size. The counts were
 * checked against the bytes after the header (ply.c); a list's count is
 * checked against the bytes left before it is read. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ply.h"

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

/* The paging window: the next 8 bytes (or what is left) safe to read,
 * enough for any scalar or list count. */
static inline void need8(MeshFile *file, const unsigned char *r, const unsigned char *end)
{
    mf_need(file, r, r + ((size_t)(end - r) < 8 ? (size_t)(end - r) : 8));
}

/* ==== Vertices ==== */

/* The vertex element's x, y, z and colour channels. */
typedef struct {
    const PlyProp *x, *y, *z, *c[3];
} VertProps;

/* n vertices of one record size each, every property at its fixed
 * offset, into pos (and col, when the mesh has colours). 0 or -1. */
static int bin_vertices_fixed(Ply *ply, const PlyElem *el, Bin *bn, const VertProps *vp,
                              uint32_t n, float *pos, float *col)
{
    int swap = bn->swap;
    const PlyProp *px = vp->x, *py = vp->y, *pz = vp->z, *const *pc = vp->c;
    size_t rs = (size_t)el->fixed;
    const unsigned char *r = bn->p;
    int fast = px->type == T_F32 && py->type == T_F32 && pz->type == T_F32;
    /* a scan's colours: three uchar, each through a table (a conversion
     * and a division per channel cost more than the rest of the record) */
    int rgb8 = col && pc[0] && pc[1] && pc[2] && pc[0]->type == T_U8 && pc[1]->type == T_U8 &&
               pc[2]->type == T_U8;
    float lut[256];
    for (int k = 0; rgb8 && k < 256; k++)
        lut[k] = ply_colour_of(k, T_U8);
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
            if (ply_to_coord(get_num(r + px->offset, px->type, swap), &d[0]) ||
                ply_to_coord(get_num(r + py->offset, py->type, swap), &d[1]) ||
                ply_to_coord(get_num(r + pz->offset, pz->type, swap), &d[2]))
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
                    pc[k] ? ply_colour_of(get_num(r + pc[k]->offset, pc[k]->type, swap), pc[k]->type)
                          : 1.0f;
        }
    }
    bn->p = r;
    return 0;
}

/* n vertices of an element with lists (rare): property by property, the
 * lists skipped. 0 or -1. */
static int bin_vertices_lists(Ply *ply, const PlyElem *el, Bin *bn, uint32_t n, float *pos,
                              float *col)
{
    const unsigned char *r = bn->p;
    MeshFile *file = ply->c->file;
    for (uint32_t i = 0; i < n; i++) {
        float v[3] = { 0, 0, 0 }, c3[3] = { 1, 1, 1 };
        for (uint32_t k = 0; k < el->nprops; k++) {
            const PlyProp *pr = &el->props[k];
            need8(file, r, bn->end);
            if (pr->count_type != T_NONE) {
                if ((size_t)(bn->end - r) < ply_type_size[pr->count_type])
                    return me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside vertex %u", i + 1);
                int64_t cnt = get_int(r, pr->count_type, bn->swap);
                r += ply_type_size[pr->count_type];
                if (cnt < 0 || (uint64_t)cnt > (uint64_t)(bn->end - r) / ply_type_size[pr->type])
                    return me_fail_at(ply->e, (uint64_t)(r - bn->base), "bad list count %lld (vertex %u)",
                                      (long long)cnt, i + 1);
                r += (size_t)cnt * ply_type_size[pr->type];
                continue;
            }
            if ((size_t)(bn->end - r) < ply_type_size[pr->type])
                return me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside vertex %u", i + 1);
            double x = get_num(r, pr->type, bn->swap);
            if (pr->role >= R_X && pr->role <= R_Z && ply_to_coord(x, &v[pr->role - R_X]))
                return me_fail_at(ply->e, (uint64_t)(r - bn->base),
                                  "NaN, infinite or out-of-range coordinate (vertex %u)", i + 1);
            if (pr->role >= R_RED && pr->role <= R_BLUE)
                c3[pr->role - R_RED] = ply_colour_of(x, pr->type);
            r += ply_type_size[pr->type];
        }
        memcpy(pos + 3 * (size_t)i, v, sizeof v);
        if (col)
            memcpy(col + 3 * (size_t)i, c3, sizeof c3);
    }
    bn->p = r;
    return 0;
}

/* The vertex element, written straight into the arrays reserved for
 * the header's count. 0 or -1. */
static int bin_vertices(Ply *ply, const PlyElem *el, Bin *bn)
{
    MeshBuild *b = ply->b;
    Mesh *m = b->m;
    VertProps vp = { 0 };
    for (uint32_t k = 0; k < el->nprops; k++) {
        const PlyProp *pr = &el->props[k];
        if (pr->role == R_X) vp.x = pr;
        if (pr->role == R_Y) vp.y = pr;
        if (pr->role == R_Z) vp.z = pr;
        if (pr->role >= R_RED && pr->role <= R_BLUE) vp.c[pr->role - R_RED] = pr;
    }
    int rgb = vp.c[0] || vp.c[1] || vp.c[2];
    if (rgb && mb_want_rgb(b))
        return -1;
    uint32_t n = (uint32_t)el->count;
    if (n == 0)
        return 0;           /* no vertex: no array to point into (it may be NULL) */
    float *pos = m->pos + 3 * (size_t)m->nverts;
    float *col = rgb ? m->rgb + 3 * (size_t)m->nverts : NULL;
    int r = el->has_list ? bin_vertices_lists(ply, el, bn, n, pos, col)
                         : bin_vertices_fixed(ply, el, bn, &vp, n, pos, col);
    if (r)
        return -1;
    m->nverts += n;
    return 0;
}

/* ==== Faces ==== */

/* What reading one face record came to. */
enum {
    FACE_READ,   /* its corners are added (from the caller's `first` on) */
    FACE_SKIP,   /* it cannot be used but was read past (counted; strict fails) */
    FACE_ENDED   /* the file ends inside it: the faces so far are kept */
};

static int bad_index(Ply *ply, uint64_t at, int64_t v, uint32_t face)
{
    return me_fail_at(ply->e, at, "vertex index %lld out of range (%llu vertices; face %u)",
                      (long long)v, (unsigned long long)ply->nverts, face + 1);
}

/* Face i's corners from the index list at *rp, whose count (cnt, at
 * least 3) was read and whose items fit in the file, added to the
 * build. FACE_READ, FACE_SKIP with the message written (an index out of
 * range; *rp is then where it was met), or -1. */
static int list_indices(Ply *ply, const PlyProp *pr, Bin *bn, const unsigned char **rp,
                        int64_t cnt, uint32_t i)
{
    MeshBuild *b = ply->b;
    uint64_t nv = ply->nverts;
    const unsigned char *r = *rp;
    int swap = bn->swap;
    if (b->ncorner + (size_t)cnt > b->ccap && mb_room_corners(b, (size_t)cnt))
        return -1;
    uint32_t *dst = b->m->corner + b->ncorner;
    if (ply_type_size[pr->type] == 4) {
        /* int and uint indices: one unsigned compare rejects negative
         * ones too (they wrap past any count) */
        for (int64_t k = 0; k < cnt; k++, r += 4) {
            uint32_t v = ld32(r, swap);
            if (v >= nv) {
                *rp = r;
                bad_index(ply, (uint64_t)(r - bn->base), get_int(r, pr->type, swap), i);
                return FACE_SKIP;
            }
            dst[k] = v;
        }
    } else {
        unsigned is = ply_type_size[pr->type];
        for (int64_t k = 0; k < cnt; k++, r += is) {
            int64_t v = get_int(r, pr->type, swap);
            if ((uint64_t)v >= nv) {
                *rp = r;
                bad_index(ply, (uint64_t)(r - bn->base), v, i);
                return FACE_SKIP;
            }
            dst[k] = (uint32_t)v;
        }
    }
    b->ncorner += (size_t)cnt;
    *rp = r;
    return FACE_READ;
}

/* Face i of the common layout, the index list alone, from *rp (moved
 * past it). FACE_READ, FACE_SKIP (counted), FACE_ENDED, or -1. */
static int face_of_list(Ply *ply, const PlyProp *only, Bin *bn, const unsigned char **rp, uint32_t i)
{
    const unsigned char *r = *rp, *end = bn->end;
    unsigned cs = ply_type_size[only->count_type], is = ply_type_size[only->type];
    need8(ply->c->file, r, end);
    if ((size_t)(end - r) < cs) {
        me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside face %u", i + 1);
        return ply_ended_early(ply) ? -1 : FACE_ENDED;
    }
    int64_t cnt = get_int(r, only->count_type, bn->swap);
    r += cs;
    uint64_t at = (uint64_t)(r - cs - bn->base);
    if (cnt < 0)
        return me_fail_at(ply->e, at, "face %u has %lld vertices (at least 3)", i + 1, (long long)cnt);
    /* cnt * is > bytes left is cnt > (bytes left) / is without a
     * division a face (cnt < 2^32 and is <= 8: no overflow) */
    if ((uint64_t)cnt * is > (uint64_t)(end - r)) {
        me_fail_at(ply->e, at, "face %u of %lld vertices goes past the end of the file", i + 1,
                   (long long)cnt);
        return ply_ended_early(ply) ? -1 : FACE_ENDED;
    }
    const unsigned char *fe = r + (size_t)cnt * is;
    mf_need(ply->c->file, r, fe);
    *rp = fe;
    int k;
    if (cnt < 3) {
        me_fail_at(ply->e, at, "face %u has %lld vertices (at least 3)", i + 1, (long long)cnt);
    } else if ((k = list_indices(ply, only, bn, &r, cnt, i)) != FACE_SKIP) {
        return k;
    } else {
        at = (uint64_t)(r - bn->base);
    }
    return me_skip(ply->e, at) ? -1 : FACE_SKIP;
}

/* A face record read property by property. */
typedef struct {
    size_t   first;    /* its first corner */
    float    c3[3];    /* its colour channels, 1 where not given */
    int      skip;     /* it cannot be used; its message written */
    uint64_t at;       /* that message's byte */
} FaceRec;

/* A list property of face i at *rp: the index list is added (unless the
 * face is already skipped), any other list read past. FACE_READ (the
 * face may be marked skipped), FACE_ENDED, or -1. */
static int face_list_prop(Ply *ply, const PlyProp *pr, Bin *bn, const unsigned char **rp,
                          uint32_t i, FaceRec *f)
{
    MeshBuild *b = ply->b;
    const unsigned char *r = *rp, *end = bn->end;
    unsigned cs = ply_type_size[pr->count_type], is = ply_type_size[pr->type];
    if ((size_t)(end - r) < cs) {
        me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside face %u", i + 1);
        b->ncorner = f->first;
        return ply_ended_early(ply) ? -1 : FACE_ENDED;
    }
    int64_t cnt = get_int(r, pr->count_type, bn->swap);
    r += cs;
    if (cnt < 0)
        return me_fail_at(ply->e, (uint64_t)(r - cs - bn->base), "list of %lld (face %u)",
                          (long long)cnt, i + 1);
    if ((uint64_t)cnt > (uint64_t)(end - r) / is) {
        me_fail_at(ply->e, (uint64_t)(r - cs - bn->base),
                   "list of %lld goes past the end of the file (face %u)", (long long)cnt, i + 1);
        b->ncorner = f->first;
        return ply_ended_early(ply) ? -1 : FACE_ENDED;
    }
    const unsigned char *le = r + (size_t)cnt * is;
    mf_need(ply->c->file, r, le);
    *rp = le;
    if (pr->role != R_INDICES || f->skip)
        return FACE_READ;
    if (cnt < 3) {
        me_fail_at(ply->e, f->at = (uint64_t)(r - cs - bn->base),
                   "face %u has %lld vertices (at least 3)", i + 1, (long long)cnt);
        f->skip = 1;
        return FACE_READ;
    }
    for (int64_t q = 0; q < cnt; q++, r += is) {
        int64_t v = get_int(r, pr->type, bn->swap);
        if ((uint64_t)v >= ply->nverts) {
            bad_index(ply, f->at = (uint64_t)(r - bn->base), v, i);
            f->skip = 1;
            break;
        }
        if (mb_corner(b, (uint32_t)v))
            return -1;
    }
    return FACE_READ;
}

/* Face i of any other layout (colours, other properties, lists in any
 * order) from *rp, property by property. FACE_READ with f's colour,
 * FACE_SKIP (counted), FACE_ENDED, or -1. */
static int face_of_props(Ply *ply, const PlyElem *el, Bin *bn, const unsigned char **rp,
                         uint32_t i, FaceRec *f)
{
    MeshBuild *b = ply->b;
    const unsigned char *end = bn->end;
    for (uint32_t k = 0; k < el->nprops; k++) {
        const PlyProp *pr = &el->props[k];
        const unsigned char *r = *rp;
        need8(ply->c->file, r, end);
        if (pr->count_type != T_NONE) {
            int res = face_list_prop(ply, pr, bn, rp, i, f);
            if (res != FACE_READ)
                return res;
            continue;
        }
        if ((size_t)(end - r) < ply_type_size[pr->type]) {
            me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside face %u", i + 1);
            b->ncorner = f->first;
            return ply_ended_early(ply) ? -1 : FACE_ENDED;
        }
        if (pr->role >= R_RED && pr->role <= R_BLUE)
            f->c3[pr->role - R_RED] = ply_colour_of(get_num(r, pr->type, bn->swap), pr->type);
        *rp = r + ply_type_size[pr->type];
    }
    if (!f->skip && b->ncorner > f->first)
        return FACE_READ;
    /* a face without an index list reads as one of no vertices */
    if (!f->skip)
        me_fail_at(ply->e, f->at = (uint64_t)(*rp - bn->base), "face %u has no vertices", i + 1);
    b->ncorner = f->first;
    return me_skip(ply->e, f->at) ? -1 : FACE_SKIP;
}

/* The faces of the common layout, the index list alone (no colours):
 * each face read and closed. 0 or -1 (0 too when the file ends inside a
 * face: ply->ended is then set). */
static int bin_faces_list(Ply *ply, const PlyElem *el, Bin *bn)
{
    MeshBuild *b = ply->b;
    uint32_t n = (uint32_t)el->count;
    const unsigned char *r = bn->p;
    for (uint32_t i = 0; i < n; i++) {
        size_t first = b->ncorner;
        int res = face_of_list(ply, &el->props[0], bn, &r, i);
        if (res < 0 || (res == FACE_READ && mb_face_end(b, first, -1)))
            return -1;
        if (res == FACE_ENDED)
            return 0;
    }
    bn->p = r;
    return 0;
}

/* The faces of any other layout, property by property, each closed with
 * its colour's material. As bin_faces_list. */
static int bin_faces_props(Ply *ply, const PlyElem *el, Bin *bn)
{
    MeshBuild *b = ply->b;
    uint32_t n = (uint32_t)el->count;
    int coloured = ply_coloured(el);
    const unsigned char *r = bn->p;
    for (uint32_t i = 0; i < n; i++) {
        FaceRec f = { .first = b->ncorner, .c3 = { 1, 1, 1 } };
        int res = face_of_props(ply, el, bn, &r, i, &f);
        if (res < 0)
            return -1;
        if (res == FACE_ENDED)
            return 0;
        if (res == FACE_SKIP)
            continue;
        int32_t mat = -1;
        if (coloured && ply_face_colour(ply, f.c3, &mat))
            return -1;
        if (mb_face_end(b, f.first, mat))
            return -1;
    }
    bn->p = r;
    return 0;
}

/* ==== Other elements ==== */

/* An element not used, read past: at once when its records have one
 * size (the counts were checked against the size: the bytes are not
 * read), else record by record through its lists' counts. 0 or -1. */
static int bin_skip(Ply *ply, const PlyElem *el, Bin *bn)
{
    if (!el->has_list) {
        bn->p += el->count * el->fixed;
        return 0;
    }
    const unsigned char *r = bn->p;
    MeshFile *file = ply->c->file;
    for (uint64_t i = 0; i < el->count; i++) {
        for (uint32_t k = 0; k < el->nprops; k++) {
            const PlyProp *pr = &el->props[k];
            need8(file, r, bn->end);
            if (pr->count_type == T_NONE) {
                if ((size_t)(bn->end - r) < ply_type_size[pr->type])
                    goto short_;
                r += ply_type_size[pr->type];
                continue;
            }
            if ((size_t)(bn->end - r) < ply_type_size[pr->count_type])
                goto short_;
            int64_t cnt = get_int(r, pr->count_type, bn->swap);
            r += ply_type_size[pr->count_type];
            if (cnt < 0 || (uint64_t)cnt > (uint64_t)(bn->end - r) / ply_type_size[pr->type])
                return me_fail_at(ply->e, (uint64_t)(r - bn->base), "list of %lld goes past the end "
                                  "of the file (element '%s')", (long long)cnt, el->name);
            r += (size_t)cnt * ply_type_size[pr->type];
        }
    }
    bn->p = r;
    return 0;
short_:
    return me_fail_at(ply->e, (uint64_t)(r - bn->base), "file ends inside element '%s'", el->name);
}

/* ==== The body ==== */

int ply_read_binary(Ply *ply, const char *data)
{
    Bin bn = { (const unsigned char *)ply->body, (const unsigned char *)ply->end,
               (const unsigned char *)data,
               (ply->fmt == FMT_BE) == (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__) };
    for (uint32_t i = 0; i < ply->nel; i++) {
        const PlyElem *el = &ply->el[i];
        int r = el->kind == EL_VERTEX ? bin_vertices(ply, el, &bn)
              : el->kind == EL_FACE   ? (el->nprops == 1 ? bin_faces_list : bin_faces_props)(ply, el, &bn)
                                      : bin_skip(ply, el, &bn);
        if (r)
            return -1;
        if (ply->ended)
            return 0;
    }
    if (bn.p < bn.end)
        me_warn(ply->e, NULL, 0, "%zu bytes after the last element ignored", (size_t)(bn.end - bn.p));
    return 0;
}
