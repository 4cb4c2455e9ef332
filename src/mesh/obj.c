/* obj.c: Wavefront OBJ. The text is parsed in place, line by line,
 * with explicit end pointers (a mapping has no terminating NUL); arrays
 * grow geometrically and nothing is allocated per line. This file reads
 * the lines (joining `\` continuations), the statements of numbers (v,
 * vt, vn) and of names (o, g, s), and dispatches the rest: f, p and l
 * to objface.c, usemtl and mtllib to objmtl.c. A statement that cannot
 * be read is undone and skipped (strict: the load fails on it). */
#define _DEFAULT_SOURCE

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "grow.h"
#include "meshprefix.h"
#include "obj.h"
#include "sysmem.h"

/* ==== Messages ==== */

int obj_fail(Parser *ps, const char *fmt, ...)
{
    char msg[256];
    ps->stmt_failed = 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return me_fail_line(ps->e, ps->line, "%s", msg);
}

static int fail_number(Parser *ps, int code, const char *ls, const char *p,
                       const char *e)
{
    if (mesh_has_binary(ls, e))
        return obj_fail(ps, "binary or unreadable data");
    int n = mesh_tok_len(p, e);
    switch (code) {
    case MESH_NUM_NONFINITE:
        return obj_fail(ps, "NaN or infinite number '%.*s'", n, p);
    case MESH_NUM_RANGE:
        return obj_fail(ps, "number out of range '%.*s'", n, p);
    default:
        return obj_fail(ps, "malformed number '%.*s'", n, p);
    }
}

/* ==== Statements ==== */

static int parse_vertex(Parser *ps, const char *ls, const char *p, const char *e)
{
    Mesh *m = ps->m;
    ps->stmt_vertex = 1;
    float v[7];
    int n = 0;
    for (;;) {
        while (p < e && is_space(*p))
            p++;
        if (p >= e || *p == '#')    /* trailing comment */
            break;
        if (n == 7)
            return obj_fail(ps, "too many numbers in vertex");
        int r = mesh_parse_float(&p, e, &v[n]);
        if (r)
            return fail_number(ps, r, ls, p, e);
        n++;
    }
    if (n < 3)
        return obj_fail(ps, "vertex needs x y z, got %d number%s", n, n == 1 ? "" : "s");
    if (n == 5 || n == 7)
        return obj_fail(ps, "vertex has %d numbers, expected x y z [w] or x y z r g b", n);
    if (n == 4 && v[3] != 0.0f) {
        for (int i = 0; i < 3; i++) {
            v[i] /= v[3];
            if (!isfinite(v[i]))
                return obj_fail(ps, "vertex out of range after dividing by w");
        }
    }
    if (n == 6 && !m->rgb && mb_want_rgb(&ps->b))   /* earlier ones white */
        return -1;
    if (mb_vertex(&ps->b, v[0], v[1], v[2]))
        return -1;
    if (n == 6) {
        float *c = m->rgb + 3 * (size_t)(m->nverts - 1);
        c[0] = v[3];
        c[1] = v[4];
        c[2] = v[5];
    }
    return 0;
}

/* vt u [v [w]]: kept, v turned to run down the image (texture.h). */
static int parse_texcoord(Parser *ps, const char *ls, const char *p, const char *e)
{
    float t[3] = { 0, 0, 0 };
    int n = 0;
    for (;;) {
        while (p < e && is_space(*p))
            p++;
        if (p >= e || *p == '#')
            break;
        float f;
        int r = mesh_parse_float(&p, e, &f);
        if (r)
            return fail_number(ps, r, ls, p, e);
        if (n < 3)
            t[n] = f;
        n++;
    }
    if (n < 1 || n > 3)
        return obj_fail(ps, "texture coordinate has %d number%s, expected 1 to 3", n, n == 1 ? "" : "s");
    ps->m->info.texcoords++;
    return mb_uv(&ps->b, t[0], 1.0f - t[1]);
}

/* vn: counted, and its numbers checked, but not stored. */
static int check_numbers(Parser *ps, const char *what, int lo, int hi,
                         const char *ls, const char *p, const char *e)
{
    int n = 0;
    for (;;) {
        while (p < e && is_space(*p))
            p++;
        if (p >= e || *p == '#')
            break;
        float f;
        int r = mesh_parse_float(&p, e, &f);
        if (r)
            return fail_number(ps, r, ls, p, e);
        n++;
    }
    if (n < lo || n > hi)
        return obj_fail(ps, "%s has %d number%s, expected %d to %d", what, n,
                    n == 1 ? "" : "s", lo, hi);
    return 0;
}

static int start_object(Parser *ps, const char *p, const char *e)
{
    obj_trim(&p, &e);
    const Mesh *m = ps->m;
    /* a piece's first object is the one current where it starts, unless
     * an `o` comes before any face, point or line of it */
    if (m->nobjs == 1 && m->nfaces == 0 && m->npoints == 0 && m->nlines == 0)
        ps->renamed0 = 1;
    return mb_object(&ps->b, p, (size_t)(e - p));
}

/* Free-form geometry and rendering statements of the OBJ format that
 * zview does not draw: counted and named once in a warning, not
 * errors (a file full of curves is a valid OBJ). */
static const char *const undrawn_kw[] = {
    "vp", "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv",
    "sp", "end", "con", "mg", "bevel", "c_interp", "d_interp", "lod", "shadow_obj", "trace_obj",
    "maplib", "usemap", "call", "csh", "ctech", "stech", "res",
};

static int kw_is(const char *k, size_t n, const char *w)
{
    return strlen(w) == n && memcmp(k, w, n) == 0;
}

/* One logical line [ls, e). */
static int parse_line(Parser *ps, const char *ls, const char *e)
{
    const char *p = ls;
    while (p < e && is_space(*p))
        p++;
    if (p >= e)
        return 0;
    /* The two statements that make up nearly all of a big file. */
    if (p + 1 < e && (p[1] == ' ' || p[1] == '\t')) {
        if (p[0] == 'v')
            return parse_vertex(ps, ls, p + 2, e);
        if (p[0] == 'f') {
            ps->saw_elements = 1;
            return obj_face(ps, ls, p + 2, e);
        }
    }
    if (*p == '#') {
        if (mesh_has_binary(p, e))
            return obj_fail(ps, "binary or unreadable data");
        return 0;
    }
    const char *k = p;
    while (p < e && !is_space(*p))
        p++;
    size_t kn = (size_t)(p - k);
    int ok = (k[0] >= 'a' && k[0] <= 'z') || (k[0] >= 'A' && k[0] <= 'Z') || k[0] == '_';
    for (size_t i = 1; ok && i < kn; i++) {
        char c = k[i];
        ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || is_digit(c) || c == '_';
    }
    if (!ok)
        return obj_fail(ps, "binary or unreadable data");

    if (kw_is(k, kn, "v"))
        return parse_vertex(ps, ls, p, e);
    if (kw_is(k, kn, "f") || kw_is(k, kn, "p") || kw_is(k, kn, "l"))
        ps->saw_elements = 1;
    if (kw_is(k, kn, "f"))
        return obj_face(ps, ls, p, e);
    if (kw_is(k, kn, "vt"))
        return parse_texcoord(ps, ls, p, e);
    if (kw_is(k, kn, "vn")) {
        ps->m->info.normals++;
        return check_numbers(ps, "normal", 3, 3, ls, p, e);
    }
    /* The rest carry names or nothing we use; a control byte in them
     * means the file is not text. */
    if (mesh_has_binary(p, e))
        return obj_fail(ps, "binary or unreadable data");
    if (kw_is(k, kn, "o"))
        return start_object(ps, p, e);
    if (kw_is(k, kn, "g")) {
        ps->m->info.groups++;
        return 0;
    }
    if (kw_is(k, kn, "s"))
        return 0;
    if (kw_is(k, kn, "usemtl"))
        return obj_use_material(ps, p, e);
    if (kw_is(k, kn, "mtllib"))
        return obj_mtllib(ps, p, e);
    if (kw_is(k, kn, "p"))
        return obj_points(ps, ls, p, e);
    if (kw_is(k, kn, "l"))
        return obj_polyline(ps, ls, p, e);
    MeshInfo *info = &ps->m->info;
    if (info->unknown++ == 0) {
        size_t n = kn < sizeof info->first_unknown - 1 ? kn : sizeof info->first_unknown - 1;
        memcpy(info->first_unknown, k, n);
        info->first_unknown[n] = '\0';
    }
    for (size_t i = 0; i < sizeof undrawn_kw / sizeof undrawn_kw[0]; i++)
        if (kw_is(k, kn, undrawn_kw[i])) {
            if (ps->undrawn++ == 0)
                ps->first_undrawn = undrawn_kw[i];
            return 0;
        }
    return obj_fail(ps, "unknown statement '%.*s'", (int)(kn < 40 ? kn : 40), k);
}

/* Append [p, e) to the scratch buffer at *n. */
static int scratch_put(Parser *ps, size_t *n, const char *p, size_t len)
{
    if (len == 0)
        return 0;
    if (*n + len > ps->scap &&
        grow_size((void **)&ps->scratch, &ps->scap, *n + len, 1))
        return obj_oom(ps);
    memcpy(ps->scratch + *n, p, len);
    *n += len;
    return 0;
}

/* ==== The loader ==== */

void obj_parser_free(Parser *ps)
{
    free(ps->fwd);
    free(ps->bad_vert);
    free(ps->scratch);
    obj_materials_free(ps);
}

/* Where a statement's additions start, to take back a statement that
 * fails halfway (the vertex is the last thing a `v` adds). */
typedef struct {
    size_t   ncorner, nlcorner;
    uint32_t npoints;
} Undo;

static Undo undo_mark(const Parser *ps)
{
    return (Undo){ ps->b.ncorner, ps->b.nlcorner, ps->m->npoints };
}

int obj_statement(Parser *ps, const char *ls, const char *e)
{
    Undo u = undo_mark(ps);
    ps->stmt_failed = ps->stmt_vertex = 0;
    if (!parse_line(ps, ls, e))
        return 0;
    if (!ps->stmt_failed || me_skip(ps->e, ps->line))
        return -1;      /* out of memory, a limit, or --strict */
    ps->b.ncorner = u.ncorner;
    ps->b.nlcorner = u.nlcorner;
    ps->m->npoints = u.npoints;
    if (ps->stmt_vertex) {
        if (ps->nbad == ps->badcap) {
            size_t cap = ps->badcap;
            if (grow_size((void **)&ps->bad_vert, &cap, (size_t)ps->nbad + 1, sizeof *ps->bad_vert))
                return obj_oom(ps);
            ps->badcap = (uint32_t)cap;
        }
        ps->bad_vert[ps->nbad++] = ps->m->nverts;
        if (mb_vertex(&ps->b, 0, 0, 0))     /* placed at the end (drop_unreadable) */
            return -1;
    }
    return 0;
}

/* A line ending in `\` and the lines it continues, joined (each
 * backslash replaced by a blank) in scratch, read as one statement;
 * errors name the first line. Returns -1 to stop. */
static int continued_statement(Parser *ps, LineReader *lr, const char *ls, const char *le)
{
    size_t n = 0;
    const char *q = ls, *qe = le;
    for (;;) {
        if (scratch_put(ps, &n, q, (size_t)(qe - 1 - q)) || scratch_put(ps, &n, " ", 1))
            return -1;
        if (!lr_next(lr, &q, &qe))
            break;
        if (!(qe > q && qe[-1] == '\\')) {
            if (scratch_put(ps, &n, q, (size_t)(qe - q)))
                return -1;
            break;
        }
    }
    return obj_statement(ps, ps->scratch, ps->scratch + n);
}

/* ==== What a big file will need ==== */

/* Files from this size on are judged before they are parsed. */
#define OBJ_JUDGE_BYTES ((size_t)8 << 20)
/* The lines looked at: this much of the start and of the end. */
#define OBJ_SAMPLE ((size_t)1 << 20)

/* What the whole lines of a sample hold. */
typedef struct {
    uint64_t verts, faces, corners, bytes, vbytes;
    uint64_t maxidx;        /* the largest positive vertex index a face names */
} Sample;

static void sample_lines(Sample *st, const char *p, const char *e)
{
    memset(st, 0, sizeof *st);
    while (p < e) {
        const char *q = memchr(p, '\n', (size_t)(e - p));
        if (!q)
            break;
        const char *s = p;
        while (s < q && is_space(*s))
            s++;
        if (q - s > 2 && (s[1] == ' ' || s[1] == '\t') && (s[0] == 'v' || s[0] == 'f')) {
            if (s[0] == 'v') {
                st->verts++;
                st->vbytes += (uint64_t)(q + 1 - p);
            } else {
                st->faces++;
                for (const char *t = s + 1; t < q; t++) {
                    if (!is_space(t[-1]) || is_space(*t))
                        continue;
                    st->corners++;
                    uint64_t v = 0;
                    for (const char *d = t; d < q && is_digit(*d) && v < ((uint64_t)1 << 40); d++)
                        v = v * 10 + (uint64_t)(*d - '0');
                    st->maxidx = v > st->maxidx ? v : st->maxidx;
                }
            }
        }
        st->bytes += (uint64_t)(q + 1 - p);
        p = q + 1;
    }
}

/* The memory a byte of the sample makes: the mesh's arrays and what the
 * scene adds (mb_estimate), per byte. -1 when it has no line. */
static double sample_rate(const Sample *st)
{
    if (!st->bytes)
        return -1;
    return (double)mb_estimate(st->verts, 0, st->faces, st->corners, 0) / (double)st->bytes;
}

/* The estimate for a file of len bytes whose start and end look like
 * hs and ts. An OBJ lists its vertices first and its faces last: the
 * largest index its last faces name is (about) the vertex count, whose
 * lines are as long as the start's; the rest of the file costs what
 * the end does. Without that (no face at the end, relative indices, a
 * vertex count the file could not hold), a floor: the rate of the start
 * or of the end, whichever is less. */
static double size_estimate(const Sample *hs, const Sample *ts, uint64_t len)
{
    double head = sample_rate(hs), end = sample_rate(ts);
    double floor = head < 0 ? end : end < 0 ? head : head < end ? head : end;
    if (hs->verts && ts->faces && ts->maxidx) {
        double vlen = (double)hs->vbytes / (double)hs->verts;
        double vb = vlen * (double)ts->maxidx;
        if (vb < (double)len)
            return (double)mb_estimate(ts->maxidx, 0, 0, 0, 0) + ((double)len - vb) * end;
    }
    return floor * (double)len;
}

/* A file that cannot fit is refused before it is parsed (seconds for a
 * big one), with the estimate and the memory there is. The estimate
 * leans low (size_estimate), so that nothing that fits is refused; what
 * it lets through is still bounded as the arrays grow. */
static int judge_size(MeshCtx *c, const char *text, size_t len)
{
    if (len < OBJ_JUDGE_BYTES)
        return 0;
    Sample hs, ts;
    sample_lines(&hs, text, text + OBJ_SAMPLE);     /* in the first window */
    char *buf = NULL;
    const char *tail = text + len - OBJ_SAMPLE;
    if (c->file && c->file->map) {
        /* the end is not in the window: read, never touched in place */
        buf = malloc(OBJ_SAMPLE);
        if (!buf)
            return me_oom(&c->err);
        ssize_t r = pread(c->file->fd, buf, OBJ_SAMPLE, (off_t)(len - OBJ_SAMPLE));
        tail = buf;
        if (r != (ssize_t)OBJ_SAMPLE) {
            free(buf);
            return 0;       /* the parse will find out what happened */
        }
    }
    /* the tail's first line is a piece: start after its end */
    const char *t0 = memchr(tail, '\n', OBJ_SAMPLE);
    sample_lines(&ts, t0 ? t0 + 1 : tail + OBJ_SAMPLE, tail + OBJ_SAMPLE);
    free(buf);
    /* four fifths: lines grow longer down a file (bigger indices), so
     * that the start's vertex lines can be shorter than the average and
     * the estimate high; a refusal must not be wrong */
    double est = 0.8 * size_estimate(&hs, &ts, len);
    uint64_t avail = c->err.max_bytes ? c->err.max_bytes : sysmem_available();
    if (est <= 0 || !avail || est <= (double)avail)
        return 0;
    char size[32], need[32], have[32];
    sysmem_format(len, size, sizeof size);
    sysmem_format((uint64_t)est, need, sizeof need);
    sysmem_format(avail, have, sizeof have);
    return me_fail(&c->err, "%s of OBJ need at least about %s for the mesh (judged from lines of its start and end); "
                   "%s available", size, need, have);
}

int obj_parser_init(Parser *ps, MeshCtx *c, int piece)
{
    memset(ps, 0, sizeof *ps);
    ps->m = c->m;
    ps->e = &c->err;
    ps->path = piece ? NULL : c->path;
    ps->cur_use = piece ? OBJ_INHERIT : -1;
    ps->piece = piece;
    return mb_start(&ps->b, c->m, &c->err, c->err.name);
}

int obj_lines(Parser *ps, LineReader *lr, const char *file_end)
{
    const char *ls, *le;
    MeshPrefix *pre = ps->piece ? NULL : ps->e->prefix;
    while (lr_next(lr, &ls, &le)) {
        ps->line = lr->line;
        /* what is parsed so far, for a picture while loading: between
         * statements, every 64k lines (a few milliseconds of parsing) */
        if (pre && (lr->line & 0xffff) == 0)
            mesh_prefix_publish(pre, ps->m, ps->b.ncorner);
        if (le > ls && le[-1] == '\\') {
            if (continued_statement(ps, lr, ls, le))
                return -1;
        } else if (obj_statement(ps, ls, le)) {
            return -1;
        } else if (le > ls && le[-1] == '\0') {
            /* a NUL (the line ends with the run of them): no text goes
             * on past binary data, so the rest is not read */
            me_warn(ps->e, NULL, lr->line, "binary data: the rest of the file (%llu bytes) is not read",
                    (unsigned long long)(file_end - le));
            return 1;
        }
    }
    return 0;
}

int obj_finish(Parser *ps)
{
    if (obj_drop_unreadable(ps) || obj_resolve_materials(ps) || mb_finish(&ps->b, !ps->saw_elements))
        return -1;
    obj_libs_warn(ps);
    if (ps->undrawn)
        me_warn(ps->e, NULL, 0, "%u free-form statement%s (curves, surfaces) not drawn, first '%s'",
                ps->undrawn, ps->undrawn == 1 ? "" : "s", ps->first_undrawn);
    return 0;
}

static int obj_parse(MeshCtx *c, const char *text, size_t len)
{
    Parser ps;
    Mesh *m = c->m;
    if (obj_parser_init(&ps, c, 0))
        return -1;
    m->info.bytes = len;
    snprintf(m->info.format, sizeof m->info.format, "obj");
    if (judge_size(c, text, len))
        goto fail;

    /* Reserve for the densest plausible file (a vertex or a triangle per
     * 24 bytes) so that big meshes are not copied while growing; pages
     * never written are never made resident, and the finish trims. Past
     * 256 MB the arrays grow instead (big blocks grow by remapping, not
     * copying): a huge file that fails on its first lines reserves
     * little. */
    if (len >= ((size_t)1 << 20)) {
        size_t guess = (len < ((size_t)256 << 20) ? len : ((size_t)256 << 20)) / 24;
        /* a guess is address space, but one bigger than the memory there
         * is is cut to it: past it, the arrays are judged as they grow */
        uint64_t avail = c->err.max_bytes ? c->err.max_bytes : sysmem_available();
        if (avail && (uint64_t)guess * (12 + 8 + 12) > avail)
            guess = (size_t)(avail / (12 + 8 + 12));
        if (mb_reserve_ex(&ps.b, guess, guess, 3 * guess, 0))
            goto fail;
    }
    if (obj_parse_parallel(&ps, c, text, mesh_bom_len(text, len), len) < 0 || obj_finish(&ps))
        goto fail;
    obj_parser_free(&ps);
    return 0;

fail:
    obj_parser_free(&ps);
    mb_abort(&ps.b);
    return -1;
}

/* OBJ is text whose statements start with a few keywords: sure when
 * the first statement of the head is one of them (no other format here
 * starts so), plausible when the head is all comments. */
static int obj_probe(const char *head, size_t n, uint64_t size)
{
    (void)size;
    const char *p = head, *end = head + n;
    if (n >= 3 && memcmp(p, "\xEF\xBB\xBF", 3) == 0)
        p += 3;
    if (mesh_has_binary(p, end))
        return PROBE_NO;
    static const char *const kw[] = { "v", "vt", "vn", "vp", "f", "o", "g", "s", "l", "p",
                                      "mtllib", "usemtl", "cstype", "deg", "curv", "surf" };
    while (p < end) {
        while (p < end && mesh_is_ws(*p))
            p++;
        if (p >= end)
            break;
        if (*p == '#') {
            while (p < end && *p != '\n' && *p != '\r')
                p++;
            continue;
        }
        const char *k = p;
        while (p < end && !mesh_is_ws(*p))
            p++;
        for (size_t i = 0; i < sizeof kw / sizeof kw[0]; i++)
            if (strlen(kw[i]) == (size_t)(p - k) && memcmp(k, kw[i], (size_t)(p - k)) == 0)
                return PROBE_FAIR;
        return PROBE_NO;
    }
    return n ? PROBE_MAYBE : PROBE_NO;
}

const MeshLoader mesh_loader_obj = {
    .name = "obj",
    .exts = "obj",
    .what = "Wavefront OBJ (+ MTL materials: Kd, d/Tr; v colours)",
    .probe = obj_probe,
    .parse = obj_parse,
    .text = 1,
};
