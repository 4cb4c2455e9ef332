/* obj.c: Wavefront OBJ. The text is parsed in place, line by line,
 * with explicit end pointers (a mapping has no terminating NUL); arrays
 * grow geometrically and nothing is allocated per line. Material
 * libraries (mtllib) are read through mtl.c, each file once. */
#define _DEFAULT_SOURCE

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "mesh.h"
#include "mesh_internal.h"

static inline int is_digit(char c) { return mesh_is_digit(c); }
static inline int is_space(char c) { return mesh_is_blank(c); }

/* ==== Name sets ==== */

/* Open-addressing index over an array of names, so that usemtl and the
 * final material lookup stay linear however many materials a file has.
 * Slots hold index + 1; 0 is empty. */
typedef struct {
    uint32_t *slot;
    uint32_t  cap;   /* power of two, or 0 */
    uint32_t  used;
} NameIndex;

static uint32_t name_hash(const char *s)
{
    uint32_t h = 2166136261u;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 16777619u;
    return h;
}

/* names: base of an array of records `stride` bytes apart, each
 * starting with a NUL-terminated name. Returns index or -1. */
static int32_t name_find(const NameIndex *ni, const void *names, size_t stride,
                         const char *name)
{
    if (!ni->cap)
        return -1;
    uint32_t mask = ni->cap - 1;
    for (uint32_t i = name_hash(name) & mask;; i = (i + 1) & mask) {
        uint32_t s = ni->slot[i];
        if (!s)
            return -1;
        const char *cand = (const char *)names + (size_t)(s - 1) * stride;
        if (strcmp(cand, name) == 0)
            return (int32_t)(s - 1);
    }
}

/* Adds entry `idx` (whose name must not be present yet). -1 on OOM. */
static int name_add(NameIndex *ni, const void *names, size_t stride, uint32_t idx)
{
    if ((ni->used + 1) * 2 > ni->cap) {
        uint32_t nc = ni->cap ? ni->cap * 2 : 16;
        uint32_t *ns = calloc(nc, sizeof *ns);
        if (!ns)
            return -1;
        for (uint32_t i = 0; i < ni->cap; i++) {
            uint32_t s = ni->slot[i];
            if (!s)
                continue;
            const char *nm = (const char *)names + (size_t)(s - 1) * stride;
            uint32_t j = name_hash(nm) & (nc - 1);
            while (ns[j])
                j = (j + 1) & (nc - 1);
            ns[j] = s;
        }
        free(ni->slot);
        ni->slot = ns;
        ni->cap = nc;
    }
    const char *nm = (const char *)names + (size_t)idx * stride;
    uint32_t mask = ni->cap - 1, j = name_hash(nm) & mask;
    while (ni->slot[j])
        j = (j + 1) & mask;
    ni->slot[j] = idx + 1;
    ni->used++;
    return 0;
}

/* ==== Material libraries, each read once ==== */

/* The names mtllib lines gave (resolved against the OBJ's folder), so
 * that a name repeated on every line is looked at once, and the files
 * read (device and inode), so that two names of one file read it once. */
typedef struct {
    char    **names;
    uint32_t  nnames, namecap;
    uint32_t *slot;              /* name index + 1, open addressing; 0 = empty */
    uint32_t  slotcap;
    uint64_t *files;             /* dev, ino pairs */
    uint32_t  nfiles, filecap;
} LibSet;

static uint32_t str_hash(const char *s)
{
    uint32_t h = 2166136261u;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 16777619u;
    return h;
}

/* Adds `name` (taking ownership) unless present. 1 = new, 0 = seen (name
 * freed), -1 out of memory (name freed). */
static int libset_add_name(LibSet *ls, char *name)
{
    if ((ls->nnames + 1) * 2 > ls->slotcap) {
        uint32_t nc = ls->slotcap ? ls->slotcap * 2 : 16;
        uint32_t *ns = calloc(nc, sizeof *ns);
        if (!ns) {
            free(name);
            return -1;
        }
        for (uint32_t i = 0; i < ls->nnames; i++) {
            uint32_t j = str_hash(ls->names[i]) & (nc - 1);
            while (ns[j])
                j = (j + 1) & (nc - 1);
            ns[j] = i + 1;
        }
        free(ls->slot);
        ls->slot = ns;
        ls->slotcap = nc;
    }
    uint32_t mask = ls->slotcap - 1, j = str_hash(name) & mask;
    for (; ls->slot[j]; j = (j + 1) & mask)
        if (strcmp(ls->names[ls->slot[j] - 1], name) == 0) {
            free(name);
            return 0;
        }
    if (ls->nnames == ls->namecap) {
        uint32_t nc = ls->namecap ? ls->namecap * 2 : 8;
        char **nn = realloc(ls->names, nc * sizeof *nn);
        if (!nn) {
            free(name);
            return -1;
        }
        ls->names = nn;
        ls->namecap = nc;
    }
    ls->names[ls->nnames] = name;
    ls->slot[j] = ++ls->nnames;
    return 1;
}

/* 1 = a file not read before (now recorded), 0 = read, -1 out of memory. */
static int libset_add_file(LibSet *ls, uint64_t dev, uint64_t ino)
{
    for (uint32_t i = 0; i < ls->nfiles; i++)
        if (ls->files[2 * i] == dev && ls->files[2 * i + 1] == ino)
            return 0;
    if (ls->nfiles == ls->filecap) {
        uint32_t nc = ls->filecap ? ls->filecap * 2 : 4;
        uint64_t *nf = realloc(ls->files, 2 * nc * sizeof *nf);
        if (!nf)
            return -1;
        ls->files = nf;
        ls->filecap = nc;
    }
    ls->files[2 * ls->nfiles] = dev;
    ls->files[2 * ls->nfiles + 1] = ino;
    ls->nfiles++;
    return 1;
}

static void libset_free(LibSet *ls)
{
    for (uint32_t i = 0; i < ls->nnames; i++)
        free(ls->names[i]);
    free(ls->names);
    free(ls->slot);
    free(ls->files);
    memset(ls, 0, sizeof *ls);
}

/* ==== Parser state ==== */

typedef struct {
    char     name[MESH_NAME_MAX];
    uint64_t line;               /* first usemtl naming it */
} UseName;

/* A statement with an index past the vertices read so far; for a `p`
 * statement, the points it added (all dropped when it is skipped). */
typedef struct {
    uint64_t line, max;
    uint32_t point_first, point_count;
} FwdRef;

/* Free-form geometry and rendering statements of the OBJ format that
 * zview does not draw: counted and named once in a warning, not
 * errors (a file full of curves is a valid OBJ). */
static const char *const undrawn_kw[] = {
    "vp", "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv",
    "sp", "end", "con", "mg", "bevel", "c_interp", "d_interp", "lod", "shadow_obj", "trace_obj",
    "maplib", "usemap", "call", "csh", "ctech", "stech", "res",
};

typedef struct {
    Mesh       *m;
    MeshBuild   b;
    MeshErr    *e;
    const char *path;            /* on disk, for mtllib; NULL: open nothing */
    uint64_t    line;            /* current (first physical) line, 1-based */

    int32_t     cur_use;         /* index into uses, -1 before any usemtl */
    UseName    *uses;
    uint32_t    nuse, usecap;
    NameIndex   use_index;
    int         mtl_loaded;      /* some mtllib opened: unknown names warn */
    LibSet      libs;
    /* Material libraries that could not be read: the first few warn by
     * name, the rest are counted into one warning at the end (a file can
     * name 50,000 missing ones). Opening them is bounded too. */
    uint32_t    lib_tries;       /* libraries looked for */
    uint32_t    lib_failed;      /* ... that could not be read */
    uint64_t    lib_bytes;       /* bytes of libraries read */

    /* Positive indices may point past the vertices read so far; they
     * are checked once the whole file is read, against the largest.
     * Leniently, each statement that had one is kept in fwd[] (its
     * line and largest index), so that the bad ones can be skipped. */
    uint64_t    fwd_max;
    uint64_t    fwd_line;
    FwdRef     *fwd;
    uint32_t    nfwd, fwdcap;
    int         stmt_failed;     /* the statement being read could not be */
    int         stmt_vertex;     /* ... and it is a `v` */
    int         saw_elements;    /* some f, l or p statement, read or not */
    uint32_t    undrawn;         /* free-form statements (undrawn_kw) */
    const char *first_undrawn;
    /* Vertices whose statement could not be read keep their number (so
     * later indices still mean what the file meant): a stand-in is
     * added, and whatever uses it is dropped at the end. */
    uint32_t   *bad_vert;
    uint32_t    nbad, badcap;

    char       *scratch;         /* joined `\` continuation lines */
    size_t      scap;
} Parser;

static int fail(Parser *ps, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(Parser *ps, const char *fmt, ...)
{
    char msg[256];
    ps->stmt_failed = 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return me_fail_line(ps->e, ps->line, "%s", msg);
}

static int fail_oom(Parser *ps) { return me_oom(ps->e); }

static int fail_number(Parser *ps, int code, const char *ls, const char *p,
                       const char *e)
{
    if (mesh_has_binary(ls, e))
        return fail(ps, "binary or unreadable data");
    int n = mesh_tok_len(p, e);
    switch (code) {
    case MESH_NUM_NONFINITE:
        return fail(ps, "NaN or infinite number '%.*s'", n, p);
    case MESH_NUM_RANGE:
        return fail(ps, "number out of range '%.*s'", n, p);
    default:
        return fail(ps, "malformed number '%.*s'", n, p);
    }
}

/* The rest of a statement, trimmed: [*p, *e). */
static void trim(const char **p, const char **e)
{
    while (*p < *e && is_space(**p))
        (*p)++;
    while (*e > *p && is_space((*e)[-1]))
        (*e)--;
}

/* Copy the rest of a statement, trimmed, into a name buffer. */
static void take_name(char *dst, const char *p, const char *e)
{
    trim(&p, &e);
    size_t n = (size_t)(e - p);
    if (n > MESH_NAME_MAX - 1)
        n = MESH_NAME_MAX - 1;
    memcpy(dst, p, n);
    dst[n] = '\0';
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
            return fail(ps, "too many numbers in vertex");
        int r = mesh_parse_float(&p, e, &v[n]);
        if (r)
            return fail_number(ps, r, ls, p, e);
        n++;
    }
    if (n < 3)
        return fail(ps, "vertex needs x y z, got %d number%s", n, n == 1 ? "" : "s");
    if (n == 5 || n == 7)
        return fail(ps, "vertex has %d numbers, expected x y z [w] or x y z r g b", n);
    if (n == 4 && v[3] != 0.0f) {
        for (int i = 0; i < 3; i++) {
            v[i] /= v[3];
            if (!isfinite(v[i]))
                return fail(ps, "vertex out of range after dividing by w");
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

/* vt and vn: counted, and their numbers checked, but not stored. */
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
        return fail(ps, "%s has %d number%s, expected %d to %d", what, n,
                    n == 1 ? "" : "s", lo, hi);
    return 0;
}

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

/* The next corner of an f, l or p statement at *pp (v, v/vt, v/vt/vn
 * or v//vn), resolved to a 0-based vertex index. Returns 1 with *idx
 * set, 0 at the end of the statement, -1 on a bad corner. A positive
 * index past the vertices so far raises *fwd (checked at the end). */
static int read_corner(Parser *ps, const char *what, const char *ls, const char **pp, const char *e,
                       uint32_t *idx, uint64_t *fwd)
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
    if (ok && p < e && *p == '/') {
        p++;
        if (p < e && *p != '/' && !is_space(*p))
            ok = skip_int(&p, e);          /* vt */
        if (ok && p < e && *p == '/') {
            p++;
            if (p < e && !is_space(*p))
                ok = skip_int(&p, e);      /* vn */
        }
    }
    if (!ok || (p < e && !is_space(*p))) {
        if (mesh_has_binary(ls, e))
            return fail(ps, "binary or unreadable data");
        return fail(ps, "malformed %s '%.*s'", what, mesh_tok_len(tok, e), tok);
    }
    *pp = p;

    /* Messages print the index as written (the value saturates). */
    int nd = (int)(d1 - d0);
    if (val == 0)
        return fail(ps, "vertex index 0 is invalid (indices start at 1; %u vertices)", m->nverts);
    if (neg) {
        if (val > m->nverts)
            return fail(ps, "vertex index -%.*s out of range (%u vertices so far)", nd, d0, m->nverts);
        *idx = m->nverts - (uint32_t)val;
        return 1;
    }
    if (val > m->nverts) {
        if (val >= UINT32_MAX)
            return fail(ps, "vertex index %.*s out of range (%u vertices)", nd, d0, m->nverts);
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
    if (fwd > ps->fwd_max) {
        ps->fwd_max = fwd;
        ps->fwd_line = ps->line;
    }
    if (ps->e->strict)
        return 0;           /* the first bad one fails the load at the end */
    if (ps->nfwd == ps->fwdcap) {
        size_t cap = ps->fwdcap;
        if (grow_size((void **)&ps->fwd, &cap, (size_t)ps->nfwd + 1, sizeof *ps->fwd))
            return fail_oom(ps);
        ps->fwdcap = (uint32_t)cap;
    }
    ps->fwd[ps->nfwd++] = (FwdRef){ ps->line, fwd, point_first, ps->m->npoints - point_first };
    return 0;
}

static int parse_face(Parser *ps, const char *ls, const char *p, const char *e)
{
    size_t start = ps->b.ncorner;
    uint64_t fwd = 0;
    uint32_t idx;
    int r;
    while ((r = read_corner(ps, "face corner", ls, &p, e, &idx, &fwd)) > 0)
        if (mb_corner(&ps->b, idx))
            return -1;
    if (r < 0)
        return -1;
    size_t n = ps->b.ncorner - start;
    if (n < 3)
        return fail(ps, "face has fewer than 3 vertices (%zu)", n);
    if (note_forward(ps, fwd, ps->m->npoints))
        return -1;
    return mb_face_end(&ps->b, start, ps->cur_use);
}

/* p v1 v2 ...: a point at each vertex. */
static int parse_points(Parser *ps, const char *ls, const char *p, const char *e)
{
    uint32_t start = ps->m->npoints, idx;
    uint64_t fwd = 0;
    int r;
    while ((r = read_corner(ps, "point", ls, &p, e, &idx, &fwd)) > 0)
        if (mb_point(&ps->b, idx))
            return -1;
    if (r < 0)
        return -1;
    if (ps->m->npoints == start)
        return fail(ps, "point statement without a vertex");
    return note_forward(ps, fwd, start);
}

/* l v1 v2 ...: a polyline through the vertices. */
static int parse_polyline(Parser *ps, const char *ls, const char *p, const char *e)
{
    size_t start = ps->b.nlcorner;
    uint64_t fwd = 0;
    uint32_t idx;
    int r;
    while ((r = read_corner(ps, "line corner", ls, &p, e, &idx, &fwd)) > 0)
        if (mb_line_corner(&ps->b, idx))
            return -1;
    if (r < 0)
        return -1;
    size_t n = ps->b.nlcorner - start;
    if (n < 2)
        return fail(ps, "line has fewer than 2 vertices (%zu)", n);
    if (note_forward(ps, fwd, ps->m->npoints))
        return -1;
    return mb_line_end(&ps->b, start);
}

static int start_object(Parser *ps, const char *p, const char *e)
{
    trim(&p, &e);
    return mb_object(&ps->b, p, (size_t)(e - p));
}

static int use_material(Parser *ps, const char *p, const char *e)
{
    char name[MESH_NAME_MAX];
    take_name(name, p, e);
    if (!name[0]) {                 /* bare usemtl: back to the default */
        ps->cur_use = -1;
        return 0;
    }
    int32_t i = name_find(&ps->use_index, ps->uses, sizeof(UseName), name);
    if (i < 0) {
        if (ps->nuse == ps->usecap) {
            size_t cap = ps->usecap;
            if (grow_size((void **)&ps->uses, &cap, (size_t)ps->nuse + 1, sizeof(UseName)))
                return fail_oom(ps);
            ps->usecap = (uint32_t)cap;
        }
        UseName *u = &ps->uses[ps->nuse];
        memcpy(u->name, name, sizeof name);
        u->line = ps->line;
        if (name_add(&ps->use_index, ps->uses, sizeof(UseName), ps->nuse))
            return fail_oom(ps);
        i = (int32_t)ps->nuse++;
    }
    ps->cur_use = i;
    return 0;
}

static int ends_with_mtl(const char *p, const char *e)
{
    return e - p >= 4 && e[-4] == '.' && (e[-3] | 0x20) == 'm' &&
           (e[-2] | 0x20) == 't' && (e[-1] | 0x20) == 'l';
}

/* Material libraries one OBJ may name: more are not read. */
#define MTL_MAX_LIBS 1024
/* Libraries that could not be read warn by name up to this many. */
#define MTL_WARN_LIBS 3

/* Library `name` could not be read: a warning for the first few, as
 * "<before> 'name' <after>". Returns 0. */
static int lib_unread(Parser *ps, const char *name, size_t n, const char *before, const char *after)
{
    if (ps->lib_failed++ < MTL_WARN_LIBS)
        me_warn(ps->e, NULL, ps->line, "%s '%.*s' %s", before, (int)n, name, after);
    return 0;
}

static int load_library(Parser *ps, const char *name, size_t n)
{
    if (!ps->path)
        return 0;                   /* a buffer with no file system behind it */
    /* Relative names are resolved against the OBJ's folder. */
    const char *slash = strrchr(ps->path, '/');
    size_t dl = (name[0] != '/' && slash) ? (size_t)(slash - ps->path) + 1 : 0;
    char *full = malloc(dl + n + 1);
    if (!full)
        return fail_oom(ps);
    memcpy(full, ps->path, dl);
    memcpy(full + dl, name, n);
    full[dl + n] = '\0';
    /* A name given before (every line of a hostile file can name the
     * same library, even the OBJ itself) is not looked at again. */
    int r = libset_add_name(&ps->libs, full);
    if (r <= 0)
        return r < 0 ? fail_oom(ps) : 0;
    if (++ps->lib_tries > MTL_MAX_LIBS) {
        ps->lib_failed++;
        return 0;
    }
    MeshFile f;
    char msg[160];
    /* Regular files only: a FIFO or /dev/stdin would block for ever. */
    char why[200];
    if (mf_open(&f, full, MF_REGULAR_ONLY, msg, sizeof msg)) {
        snprintf(why, sizeof why, "(%s)", msg);
        return lib_unread(ps, name, n, "cannot open material library", why);
    }
    r = libset_add_file(&ps->libs, f.dev, f.ino);
    if (r <= 0) {
        mf_close(&f);
        return r < 0 ? fail_oom(ps) : 0;
    }
    /* the bounds and the first look of a model: a big or binary file is
     * refused before it is read */
    const char *h = f.head + mesh_bom_len(f.head, f.nhead);
    if (f.size + ps->lib_bytes > MESH_MTL_MAX_BYTES) {
        char sz[32], most[32];
        sysmem_format(f.size, sz, sizeof sz);
        sysmem_format(MESH_MTL_MAX_BYTES, most, sizeof most);
        snprintf(why, sizeof why, "too large, not read (%s; material libraries may have %s in all)", sz, most);
        mf_close(&f);
        return lib_unread(ps, name, n, "material library", why);
    }
    if (mesh_has_binary(h, f.head + f.nhead)) {
        mf_close(&f);
        return lib_unread(ps, name, n, "material library", "is binary data, not text: not read");
    }
    ps->lib_bytes += f.size;
    if (mf_load(&f, NULL, msg, sizeof msg)) {
        mf_close(&f);
        snprintf(why, sizeof why, "(%s)", msg);
        return lib_unread(ps, name, n, "cannot read material library", why);
    }
    uint32_t had = ps->m->nmats;
    r = mesh_mtl_parse(ps->e, full, &f, f.data, f.len, &ps->m->mats, &ps->m->nmats, &ps->b.mcap);
    int changed = mf_changed(&f);
    mf_close(&f);
    if (r < 0)
        return fail_oom(ps);
    if (changed) {
        ps->m->nmats = had;     /* what was read of it cannot be trusted */
        return lib_unread(ps, name, n, "material library", "changed while reading: not used");
    }
    ps->mtl_loaded = 1;
    return 0;
}

static int parse_mtllib(Parser *ps, const char *p, const char *e)
{
    trim(&p, &e);
    /* Several names are separated by blanks, but some exporters write
     * one name containing spaces: take the whole rest as one name when
     * it ends in .mtl and a blank-separated piece does not. */
    int whole = 0;
    if (ends_with_mtl(p, e)) {
        for (const char *q = p; q < e;) {
            const char *t = q;
            while (q < e && !is_space(*q))
                q++;
            if (!ends_with_mtl(t, q)) {
                whole = 1;
                break;
            }
            while (q < e && is_space(*q))
                q++;
        }
    }
    if (whole)
        return load_library(ps, p, (size_t)(e - p));
    while (p < e) {
        const char *t = p;
        while (p < e && !is_space(*p))
            p++;
        if (load_library(ps, t, (size_t)(p - t)))
            return -1;
        while (p < e && is_space(*p))
            p++;
    }
    return 0;
}

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
            return parse_face(ps, ls, p + 2, e);
        }
    }
    if (*p == '#') {
        if (mesh_has_binary(p, e))
            return fail(ps, "binary or unreadable data");
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
        return fail(ps, "binary or unreadable data");

    if (kw_is(k, kn, "v"))
        return parse_vertex(ps, ls, p, e);
    if (kw_is(k, kn, "f") || kw_is(k, kn, "p") || kw_is(k, kn, "l"))
        ps->saw_elements = 1;
    if (kw_is(k, kn, "f"))
        return parse_face(ps, ls, p, e);
    if (kw_is(k, kn, "vt")) {
        ps->m->info.texcoords++;
        return check_numbers(ps, "texture coordinate", 1, 3, ls, p, e);
    }
    if (kw_is(k, kn, "vn")) {
        ps->m->info.normals++;
        return check_numbers(ps, "normal", 3, 3, ls, p, e);
    }
    /* The rest carry names or nothing we use; a control byte in them
     * means the file is not text. */
    if (mesh_has_binary(p, e))
        return fail(ps, "binary or unreadable data");
    if (kw_is(k, kn, "o"))
        return start_object(ps, p, e);
    if (kw_is(k, kn, "g")) {
        ps->m->info.groups++;
        return 0;
    }
    if (kw_is(k, kn, "s"))
        return 0;
    if (kw_is(k, kn, "usemtl"))
        return use_material(ps, p, e);
    if (kw_is(k, kn, "mtllib"))
        return parse_mtllib(ps, p, e);
    if (kw_is(k, kn, "p"))
        return parse_points(ps, ls, p, e);
    if (kw_is(k, kn, "l"))
        return parse_polyline(ps, ls, p, e);
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
    return fail(ps, "unknown statement '%.*s'", (int)(kn < 40 ? kn : 40), k);
}

/* Append [p, e) to the scratch buffer at *n. */
static int scratch_put(Parser *ps, size_t *n, const char *p, size_t len)
{
    if (len == 0)
        return 0;
    if (*n + len > ps->scap &&
        grow_size((void **)&ps->scratch, &ps->scap, *n + len, 1))
        return fail_oom(ps);
    memcpy(ps->scratch + *n, p, len);
    *n += len;
    return 0;
}

/* ==== After the last line ==== */

static int resolve_materials(Parser *ps)
{
    Mesh *m = ps->m;
    if (!ps->nuse)
        return 0;
    /* usemtl names -> material indices, first definition wins. */
    int32_t *map = malloc(ps->nuse * sizeof *map);
    NameIndex mi = {0};
    if (!map)
        return fail_oom(ps);
    for (uint32_t i = 0; i < m->nmats; i++) {
        if (name_find(&mi, m->mats, sizeof(Material), m->mats[i].name) < 0 &&
            name_add(&mi, m->mats, sizeof(Material), i)) {
            free(map);
            free(mi.slot);
            return fail_oom(ps);
        }
    }
    for (uint32_t i = 0; i < ps->nuse; i++) {
        map[i] = name_find(&mi, m->mats, sizeof(Material), ps->uses[i].name);
        if (map[i] < 0 && ps->mtl_loaded)
            me_warn(ps->e, NULL, ps->uses[i].line, "unknown material '%s'", ps->uses[i].name);
    }
    for (uint32_t f = 0; f < m->nfaces; f++)
        if (m->face_mat[f] >= 0)
            m->face_mat[f] = map[m->face_mat[f]];
    free(map);
    free(mi.slot);
    return 0;
}

/* ==== The loader ==== */

static void parser_free(Parser *ps)
{
    free(ps->fwd);
    free(ps->bad_vert);
    free(ps->uses);
    free(ps->use_index.slot);
    free(ps->scratch);
    libset_free(&ps->libs);
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

/* One logical line; a statement that cannot be read is skipped (undone
 * and counted) unless the load is strict. Returns -1 to stop. */
static int statement(Parser *ps, const char *ls, const char *e)
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
                return fail_oom(ps);
            ps->badcap = (uint32_t)cap;
        }
        ps->bad_vert[ps->nbad++] = ps->m->nverts;
        if (mb_vertex(&ps->b, 0, 0, 0))     /* placed at the end (drop_unreadable) */
            return -1;
    }
    return 0;
}

/* Is vertex v usable: read, and not a stand-in? */
static inline int vert_ok(const uint8_t *bad, uint32_t nv, uint32_t v)
{
    return v < nv && !(bad && bad[v >> 3] >> (v & 7) & 1);
}

/* What could not be resolved until the end: positive indices past the
 * last vertex (strict: the load fails on the largest; otherwise each
 * statement that had one is skipped) and the stand-ins of unreadable
 * vertices. Faces, points and lines using either are dropped (each
 * counted as a skipped statement once), and the objects' ranges closed
 * up. */
static int drop_unreadable(Parser *ps)
{
    Mesh *m = ps->m;
    MeshBuild *b = &ps->b;
    int fwd = ps->fwd_max > m->nverts;
    if (!fwd && !ps->nbad)
        return 0;
    if (fwd && ps->e->strict) {
        ps->line = ps->fwd_line;
        return fail(ps, "vertex index %llu out of range (%u vertices)", (unsigned long long)ps->fwd_max,
                    m->nverts);
    }
    for (uint32_t i = 0; i < ps->nfwd; i++) {
        if (ps->fwd[i].max <= m->nverts)
            continue;
        ps->line = ps->fwd[i].line;
        fail(ps, "vertex index %llu out of range (%u vertices)", (unsigned long long)ps->fwd[i].max,
             m->nverts);
        me_skip(ps->e, ps->fwd[i].line);
    }
    uint32_t nv = m->nverts, ob = 0, more = 0;
    uint8_t *bad = NULL;
    if (ps->nbad) {
        bad = calloc((size_t)nv / 8 + 1, 1);
        if (!bad)
            return fail_oom(ps);
        for (uint32_t i = 0; i < ps->nbad; i++) {
            uint32_t v = ps->bad_vert[i];
            bad[v >> 3] |= (uint8_t)(1u << (v & 7));
        }
        /* a stand-in sits on a vertex that was read (the one before it,
         * else the first), so that bounds and fits ignore it */
        uint32_t good = 0;
        while (good < nv && !vert_ok(bad, nv, good))
            good++;
        for (uint32_t v = 0; v < nv && good < nv; v++) {
            if (vert_ok(bad, nv, v))
                good = v;
            else
                memcpy(&m->pos[3 * (size_t)v], &m->pos[3 * (size_t)good], 3 * sizeof(float));
        }
    }
    /* faces */
    uint32_t nf = 0;
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
            more += !past;      /* those past the end were counted above */
            m->info.triangles -= (uint32_t)(c1 - c0 - 2);
            continue;
        }
        memmove(&m->corner[nc], &m->corner[c0], (c1 - c0) * sizeof *m->corner);
        m->face_start[nf] = (uint32_t)nc;
        m->face_mat[nf++] = m->face_mat[f];
        nc += c1 - c0;
    }
    for (; ob < m->nobjs; ob++)
        m->objs[ob].face_first = nf;
    m->nfaces = nf;
    b->ncorner = nc;
    /* points: a skipped `p` statement takes all its points along (fwd[]
     * lists the statements in order, so their runs rise with k) */
    uint32_t np = 0, fi = 0;
    ob = 0;
    for (uint32_t k = 0; k < m->npoints; k++) {
        for (; ob < m->nobjs && m->objs[ob].point_first == k; ob++)
            m->objs[ob].point_first = np;
        while (fi < ps->nfwd && (ps->fwd[fi].point_count == 0 || ps->fwd[fi].max <= nv ||
                                 ps->fwd[fi].point_first + ps->fwd[fi].point_count <= k))
            fi++;
        if (fi < ps->nfwd && ps->fwd[fi].point_first <= k)
            continue;       /* counted with its statement above */
        if (vert_ok(bad, nv, m->point[k]))
            m->point[np++] = m->point[k];
        else
            more++;
    }
    for (; ob < m->nobjs; ob++)
        m->objs[ob].point_first = np;
    m->npoints = np;
    /* polylines */
    uint32_t nl = 0;
    size_t nlc = 0;
    ob = 0;
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
    free(bad);
    ps->e->skipped = ps->e->skipped + more < ps->e->skipped ? UINT32_MAX : ps->e->skipped + more;
    return 0;
}

static int obj_parse(MeshCtx *c, const char *text, size_t len)
{
    Parser ps = {0};
    ps.m = c->m;
    ps.e = &c->err;
    ps.path = c->path;
    ps.cur_use = -1;
    Mesh *m = c->m;
    if (mb_start(&ps.b, m, &c->err, c->err.name))
        return -1;
    m->info.bytes = len;
    snprintf(m->info.format, sizeof m->info.format, "obj");

    /* Reserve for the densest plausible file (a vertex or a triangle per
     * 24 bytes) so that big meshes are not copied while growing; pages
     * never written are never made resident, and the finish trims. Past
     * 256 MB the arrays grow instead (big blocks grow by remapping, not
     * copying): a huge file that fails on its first lines reserves
     * little. */
    if (len >= ((size_t)1 << 20)) {
        size_t guess = (len < ((size_t)256 << 20) ? len : ((size_t)256 << 20)) / 24;
        if (mb_reserve_ex(&ps.b, guess, guess, 3 * guess, 0))
            goto fail;
    }

    const char *p = text, *end = text + len;
    if (len >= 3 && memcmp(p, "\xEF\xBB\xBF", 3) == 0)   /* UTF-8 BOM */
        p += 3;
    LineReader lr;
    lr_init(&lr, p, (size_t)(end - p), c->file);
    const char *ls, *le;
    while (lr_next(&lr, &ls, &le)) {
        ps.line = lr.line;
        if (le > ls && le[-1] == '\\') {
            /* Continuation: join the physical lines, backslash replaced
             * by a blank, into scratch. Errors name the first line. */
            size_t n = 0;
            const char *q = ls, *qe = le;
            for (;;) {
                if (scratch_put(&ps, &n, q, (size_t)(qe - 1 - q)) ||
                    scratch_put(&ps, &n, " ", 1))
                    goto fail;
                if (!lr_next(&lr, &q, &qe))
                    break;
                if (!(qe > q && qe[-1] == '\\')) {
                    if (scratch_put(&ps, &n, q, (size_t)(qe - q)))
                        goto fail;
                    break;
                }
            }
            if (statement(&ps, ps.scratch, ps.scratch + n))
                goto fail;
        } else if (statement(&ps, ls, le)) {
            goto fail;
        } else if (le > ls && le[-1] == '\0') {
            /* a NUL (the line ends with the run of them): no text goes
             * on past binary data, so the rest is not read */
            me_warn(&c->err, NULL, lr.line, "binary data: the rest of the file (%llu bytes) is not read",
                    (unsigned long long)(end - le));
            break;
        }
    }
    if (drop_unreadable(&ps) || resolve_materials(&ps) || mb_finish(&ps.b, !ps.saw_elements))
        goto fail;
    if (ps.lib_failed > MTL_WARN_LIBS) {
        char more[32], named[32];
        mesh_count_str(ps.lib_failed - MTL_WARN_LIBS, more, sizeof more);
        mesh_count_str(ps.libs.nnames, named, sizeof named);
        me_warn(&c->err, NULL, 0, "%s more material librar%s could not be read (%s named%s)", more,
                ps.lib_failed - MTL_WARN_LIBS == 1 ? "y" : "ies", named,
                ps.lib_tries > MTL_MAX_LIBS ? "; only the first 1,024 are looked for" : "");
    }
    if (ps.undrawn)
        me_warn(&c->err, NULL, 0, "%u free-form statement%s (curves, surfaces) not drawn, first '%s'",
                ps.undrawn, ps.undrawn == 1 ? "" : "s", ps.first_undrawn);
    parser_free(&ps);
    return 0;

fail:
    parser_free(&ps);
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
                return PROBE_SURE;
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
