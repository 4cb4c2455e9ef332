/* plyascii.c: the body of an ascii PLY, element by element: every
 * record is read property by property as numbers separated by white
 * space (a record is a line, but only faces rely on that, to skip one
 * that cannot be used). The counts were checked against the bytes after
 * the header (ply.c); a list's count against the bytes left. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ply.h"

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
        if (t->p >= t->real_end)                                            \
            return ply_ended_early(ply);                                    \
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
    int coloured = ply_coloured(el);
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
            if (pr->role >= R_X && pr->role <= R_Z && vertex && ply_to_coord(d, &v[pr->role - R_X]))
                return me_fail_line(ply->e, t->line, "coordinate out of range");
            if (pr->role >= R_RED && pr->role <= R_BLUE)
                c3[pr->role - R_RED] = ply_colour_of(d, pr->type);
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
            if (coloured && ply_face_colour(ply, c3, &mat))
                return -1;
            if (mb_face_end(b, first, mat))
                return -1;
        }
    next_record:;
    }
    return 0;
}

int ply_read_ascii(Ply *ply)
{
    MeshFile *file = ply->c->file;
    Txt t = { ply->body, mf_limit(file, ply->end), ply->end, ply->body_line, file };
    for (uint32_t i = 0; i < ply->nel; i++) {
        PlyElem *el = &ply->el[i];
        if (el->nprops == 0)
            continue;
        if (txt_element(ply, el, &t))
            return -1;
        if (ply->ended)
            return 0;
    }
    if (txt_ws(&t))
        me_warn(ply->e, NULL, t.line, "data after the last element ignored");
    return 0;
}
