/* obj.c: Wavefront OBJ loader. The file is mapped once and parsed in
 * place, line by line, with explicit end pointers (a mapping has no
 * terminating NUL). Numbers go through a hand-written parser because
 * strtod per coordinate would dominate the load time of a large mesh;
 * arrays grow geometrically and nothing is allocated per line. */
#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "mesh.h"
#include "mesh_internal.h"

/* Larger inputs than this are refused rather than risking 32-bit
 * overflow of the corner offsets; a pipe that never ends (/dev/zero)
 * also stops here instead of eating all memory. */
#define OBJ_MAX_BYTES ((size_t)1 << 32)

/* ==== Whole-file input ==== */

int mesh_file_open(MeshFile *f, const char *path, char *msg, size_t msglen)
{
    memset(f, 0, sizeof *f);
    f->data = "";
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        snprintf(msg, msglen, "cannot open: %s", strerror(errno));
        return -1;
    }
    struct stat st;
    if (fstat(fd, &st) < 0) {
        snprintf(msg, msglen, "cannot open: %s", strerror(errno));
        close(fd);
        return -1;
    }
    if (S_ISDIR(st.st_mode)) {
        snprintf(msg, msglen, "is a directory");
        close(fd);
        return -1;
    }
    if (S_ISREG(st.st_mode)) {
        if (st.st_size == 0) {
            close(fd);
            return 0;
        }
        if ((uint64_t)st.st_size > OBJ_MAX_BYTES) {
            snprintf(msg, msglen, "file too large");
            close(fd);
            return -1;
        }
        size_t len = (size_t)st.st_size;
        int flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
        flags |= MAP_POPULATE;  /* fault the pages in up front, in bulk */
#endif
        void *map = mmap(NULL, len, PROT_READ, flags, fd, 0);
        if (map != MAP_FAILED) {
#ifdef MADV_SEQUENTIAL
            madvise(map, len, MADV_SEQUENTIAL);
#endif
            close(fd);
            f->map = map;
            f->data = map;
            f->len = len;
            return 0;
        }
        /* Some file systems cannot map: fall through to plain reads. */
    }

    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap);
    for (;;) {
        if (!buf) {
            snprintf(msg, msglen, "out of memory");
            close(fd);
            return -1;
        }
        if (len == cap) {
            if (cap >= OBJ_MAX_BYTES) {
                snprintf(msg, msglen, "file too large");
                free(buf);
                close(fd);
                return -1;
            }
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                free(buf);
                buf = NULL;
                continue;
            }
            buf = nb;
            cap *= 2;
        }
        ssize_t r = read(fd, buf + len, cap - len);
        if (r < 0) {
            if (errno == EINTR)
                continue;
            snprintf(msg, msglen, "cannot read: %s", strerror(errno));
            free(buf);
            close(fd);
            return -1;
        }
        if (r == 0)
            break;
        /* A NUL already makes the text invalid; stop there so that an
         * endless binary stream (/dev/zero) ends in an error, not in
         * exhausted memory. */
        const char *nul = memchr(buf + len, '\0', (size_t)r);
        len += (size_t)r;
        if (nul) {
            len = (size_t)(nul - buf) + 1;
            break;
        }
    }
    close(fd);
    f->heap = buf;
    f->data = buf;
    f->len = len;
    return 0;
}

void mesh_file_close(MeshFile *f)
{
    if (f->map)
        munmap(f->map, f->len);
    free(f->heap);
    memset(f, 0, sizeof *f);
}

/* ==== Numbers ==== */

static const double obj_pow10[23] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

static inline int is_digit(char c) { return (unsigned char)(c - '0') < 10; }
static inline int is_space(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/* Case-insensitive match of a lower-case word at p. */
static int match_word(const char *p, const char *end, const char *w)
{
    for (; *w; w++, p++)
        if (p >= end || (*p | 0x20) != *w)
            return 0;
    return p == end || is_space(*p);
}

int mesh_parse_float(const char **pp, const char *end, float *out)
{
    const char *p = *pp;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) {
        neg = *p == '-';
        p++;
    }
    /* Up to 19 significant digits fit a uint64 exactly; later digits
     * only move the decimal exponent. Leading zeros are not significant
     * and do not use up the budget. */
    uint64_t mant = 0;
    int nd = 0, exp10 = 0, any = 0;
    while (p < end && *p == '0') {
        p++;
        any = 1;
    }
    while (p < end && is_digit(*p)) {
        if (nd < 19) {
            mant = mant * 10 + (uint64_t)(*p - '0');
            nd++;
        } else {
            exp10++;
        }
        p++;
        any = 1;
    }
    if (p < end && *p == '.') {
        p++;
        if (nd == 0) {
            while (p < end && *p == '0') {
                p++;
                exp10--;
                any = 1;
            }
        }
        while (p < end && is_digit(*p)) {
            if (nd < 19) {
                mant = mant * 10 + (uint64_t)(*p - '0');
                nd++;
                exp10--;
            }
            p++;
            any = 1;
        }
    }
    if (!any) {
        /* Recognised only so that they can be refused by name. */
        if (match_word(p, end, "nan") || match_word(p, end, "infinity") ||
            match_word(p, end, "inf"))
            return MESH_NUM_NONFINITE;
        return MESH_NUM_BAD;
    }
    if (p < end && (*p | 0x20) == 'e') {
        p++;
        int eneg = 0;
        if (p < end && (*p == '-' || *p == '+')) {
            eneg = *p == '-';
            p++;
        }
        if (p >= end || !is_digit(*p))
            return MESH_NUM_BAD;
        int ev = 0;
        while (p < end && is_digit(*p)) {
            if (ev < 100000)          /* far past any float; no overflow */
                ev = ev * 10 + (*p - '0');
            p++;
        }
        exp10 += eneg ? -ev : ev;
    }
    if (p < end && !is_space(*p))
        return MESH_NUM_BAD;

    double v = (double)mant;
    if (mant == 0 || exp10 < -400) {
        v = 0.0;
    } else if (exp10 > 400) {
        return MESH_NUM_RANGE;
    } else if (exp10 >= 0) {
        /* Exact when exp10 <= 22 and mant < 2^53; otherwise a few
         * roundings in double, still far below a float's ulp. */
        while (exp10 > 22) {
            v *= 1e22;
            exp10 -= 22;
        }
        v *= obj_pow10[exp10];
    } else {
        while (exp10 < -22) {
            v /= 1e22;
            exp10 += 22;
        }
        v /= obj_pow10[-exp10];
    }
    /* Converting a double beyond FLT_MAX is undefined in C, so the
     * rounding boundary (FLT_MAX + half an ulp) is tested in double. */
    float f;
    if (v >= 3.4028235677973366e38)
        return MESH_NUM_RANGE;
    f = v > 3.4028234663852886e38 ? 3.4028234663852886e38f : (float)v;
    *out = neg ? -f : f;
    *pp = p;
    return MESH_NUM_OK;
}

int mesh_has_binary(const char *p, const char *end)
{
    for (; p < end; p++) {
        unsigned char c = (unsigned char)*p;
        if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f)
            return 1;
    }
    return 0;
}

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

/* ==== Parser state ==== */

typedef struct {
    char     name[MESH_NAME_MAX];
    uint32_t line;               /* first usemtl naming it */
} UseName;

typedef struct {
    Mesh       *m;
    const char *path;
    char       *err;
    size_t      errlen;
    uint32_t    line;            /* current (first physical) line, 1-based */

    size_t      vcap;            /* vertices pos/rgb can hold */
    size_t      ncorner, ccap;
    size_t      fcap;            /* faces; face_start holds fcap + 1 */
    size_t      ocap;
    uint32_t    mcap;

    int32_t     cur_use;         /* index into uses, -1 before any usemtl */
    UseName    *uses;
    uint32_t    nuse, usecap;
    NameIndex   use_index;
    int         mtl_loaded;      /* some mtllib opened: unknown names warn */

    /* Positive indices may point past the vertices read so far; they
     * are checked once the whole file is read, against the largest. */
    uint64_t    fwd_max;
    uint32_t    fwd_line;

    char       *scratch;         /* joined `\` continuation lines */
    size_t      scap;
    char        basename[MESH_NAME_MAX];
} Parser;

static int fail(Parser *ps, const char *fmt, ...)
{
    int n = snprintf(ps->err, ps->errlen, "%s:%u: ", ps->path, ps->line);
    if (n >= 0 && (size_t)n < ps->errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(ps->err + n, ps->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return -1;
}

static int fail_oom(Parser *ps)
{
    snprintf(ps->err, ps->errlen, "%s: out of memory", ps->path);
    return -1;
}

/* Grow *arr (elements of `elem` bytes, `*cap` of them) to hold `need`. */
static int grow(void **arr, size_t *cap, size_t need, size_t elem)
{
    size_t nc = *cap ? *cap : 256;
    while (nc < need) {
        if (nc > SIZE_MAX / 2 / elem)
            return -1;
        nc *= 2;
    }
    void *p = realloc(*arr, nc * elem);
    if (!p)
        return -1;
    *arr = p;
    *cap = nc;
    return 0;
}

/* The token at p (up to whitespace), at most 32 bytes, for messages. */
static int tok_len(const char *p, const char *e)
{
    const char *q = p;
    while (q < e && !is_space(*q) && q - p < 32)
        q++;
    return (int)(q - p);
}

static int fail_number(Parser *ps, int code, const char *ls, const char *p,
                       const char *e)
{
    if (mesh_has_binary(ls, e))
        return fail(ps, "binary or unreadable data");
    int n = tok_len(p, e);
    switch (code) {
    case MESH_NUM_NONFINITE:
        return fail(ps, "NaN or infinite number '%.*s'", n, p);
    case MESH_NUM_RANGE:
        return fail(ps, "number out of range '%.*s'", n, p);
    default:
        return fail(ps, "malformed number '%.*s'", n, p);
    }
}

/* Copy the rest of a statement, trimmed, into a name buffer. */
static void take_name(char *dst, const char *p, const char *e)
{
    while (p < e && is_space(*p))
        p++;
    while (e > p && is_space(e[-1]))
        e--;
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
    if (m->nverts >= UINT32_MAX - 1)
        return fail(ps, "too many vertices");
    if (m->nverts == ps->vcap) {
        size_t cap = ps->vcap;
        if (grow((void **)&m->pos, &cap, (size_t)m->nverts + 1, 3 * sizeof(float)))
            return fail_oom(ps);
        if (m->rgb) {
            float *q = realloc(m->rgb, cap * 3 * sizeof(float));
            if (!q)
                return fail_oom(ps);
            m->rgb = q;
        }
        ps->vcap = cap;
    }
    float *d = m->pos + 3 * (size_t)m->nverts;
    d[0] = v[0];
    d[1] = v[1];
    d[2] = v[2];
    if (n == 6 && !m->rgb) {
        /* First coloured vertex: the ones before it were white. */
        m->rgb = malloc(ps->vcap * 3 * sizeof(float));
        if (!m->rgb)
            return fail_oom(ps);
        for (size_t i = 0; i < 3 * (size_t)m->nverts; i++)
            m->rgb[i] = 1.0f;
    }
    if (m->rgb) {
        float *c = m->rgb + 3 * (size_t)m->nverts;
        if (n == 6) {
            c[0] = v[3];
            c[1] = v[4];
            c[2] = v[5];
        } else {
            c[0] = c[1] = c[2] = 1.0f;
        }
    }
    m->nverts++;
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

static int parse_face(Parser *ps, const char *ls, const char *p, const char *e)
{
    Mesh *m = ps->m;
    size_t start = ps->ncorner;
    for (;;) {
        while (p < e && is_space(*p))
            p++;
        if (p >= e || *p == '#')
            break;
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
            return fail(ps, "malformed face corner '%.*s'", tok_len(tok, e), tok);
        }

        uint32_t idx;
        if (val == 0)
            return fail(ps, "vertex index 0 is invalid (indices start at 1; %u vertices)",
                        m->nverts);
        if (neg) {
            if (val > m->nverts)
                return fail(ps, "vertex index -%llu out of range (%u vertices so far)",
                            (unsigned long long)val, m->nverts);
            idx = m->nverts - (uint32_t)val;
        } else {
            if (val > m->nverts) {
                if (val >= UINT32_MAX)
                    return fail(ps, "vertex index %llu out of range (%u vertices)",
                                (unsigned long long)val, m->nverts);
                if (val > ps->fwd_max) {
                    ps->fwd_max = val;
                    ps->fwd_line = ps->line;
                }
            }
            idx = (uint32_t)(val - 1);
        }
        if (ps->ncorner == ps->ccap) {
            if (ps->ncorner >= UINT32_MAX - 1)
                return fail(ps, "too many face corners");
            if (grow((void **)&m->corner, &ps->ccap, ps->ncorner + 1, sizeof(uint32_t)))
                return fail_oom(ps);
        }
        m->corner[ps->ncorner++] = idx;
    }
    size_t n = ps->ncorner - start;
    if (n < 3)
        return fail(ps, "face has fewer than 3 vertices (%zu)", n);
    if (m->nfaces == ps->fcap) {
        if (m->nfaces >= UINT32_MAX - 1)
            return fail(ps, "too many faces");
        size_t cap = ps->fcap;
        if (grow((void **)&m->face_mat, &cap, (size_t)m->nfaces + 1, sizeof(int32_t)))
            return fail_oom(ps);
        uint32_t *q = realloc(m->face_start, (cap + 1) * sizeof(uint32_t));
        if (!q)
            return fail_oom(ps);
        m->face_start = q;
        ps->fcap = cap;
    }
    m->face_start[m->nfaces] = (uint32_t)start;
    m->face_mat[m->nfaces] = ps->cur_use;
    m->nfaces++;
    m->info.triangles += (uint32_t)(n - 2);
    return 0;
}

static int start_object(Parser *ps, const char *p, const char *e)
{
    Mesh *m = ps->m;
    MeshObject *cur = &m->objs[m->nobjs - 1];
    if (cur->face_first != m->nfaces) {
        if (m->nobjs == ps->ocap &&
            grow((void **)&m->objs, &ps->ocap, (size_t)m->nobjs + 1, sizeof(MeshObject)))
            return fail_oom(ps);
        cur = &m->objs[m->nobjs++];
    }
    /* An object that got no faces is renamed rather than kept. */
    memset(cur, 0, sizeof *cur);
    cur->face_first = m->nfaces;
    take_name(cur->name, p, e);
    if (!cur->name[0])
        memcpy(cur->name, ps->basename, sizeof cur->name);
    return 0;
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
            if (grow((void **)&ps->uses, &cap, (size_t)ps->nuse + 1, sizeof(UseName)))
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

static int load_library(Parser *ps, const char *name, size_t n)
{
    /* Relative names are resolved against the OBJ's folder. */
    const char *slash = strrchr(ps->path, '/');
    size_t dl = (name[0] != '/' && slash) ? (size_t)(slash - ps->path) + 1 : 0;
    char *full = malloc(dl + n + 1);
    if (!full)
        return fail_oom(ps);
    memcpy(full, ps->path, dl);
    memcpy(full + dl, name, n);
    full[dl + n] = '\0';
    int r = mesh_mtl_load(full, &ps->m->mats, &ps->m->nmats, &ps->mcap);
    free(full);
    if (r == -2)
        return fail_oom(ps);
    if (r < 0)
        fprintf(stderr, "zview: warning: %s:%u: cannot open material library '%.*s'\n",
                ps->path, ps->line, (int)n, name);
    else
        ps->mtl_loaded = 1;
    return 0;
}

static int parse_mtllib(Parser *ps, const char *p, const char *e)
{
    while (p < e && is_space(*p))
        p++;
    while (e > p && is_space(e[-1]))
        e--;
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
        if (p[0] == 'f')
            return parse_face(ps, ls, p + 2, e);
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
    MeshInfo *info = &ps->m->info;
    if (info->unknown++ == 0) {
        size_t n = kn < sizeof info->first_unknown - 1 ? kn : sizeof info->first_unknown - 1;
        memcpy(info->first_unknown, k, n);
        info->first_unknown[n] = '\0';
    }
    return 0;
}

/* Append [p, e) to the scratch buffer at *n. */
static int scratch_put(Parser *ps, size_t *n, const char *p, size_t len)
{
    if (len == 0)
        return 0;
    if (*n + len > ps->scap &&
        grow((void **)&ps->scratch, &ps->scap, *n + len, 1))
        return fail_oom(ps);
    memcpy(ps->scratch + *n, p, len);
    *n += len;
    return 0;
}

/* ==== After the last line ==== */

static int finish(Parser *ps)
{
    Mesh *m = ps->m;
    if (ps->fwd_max > m->nverts) {
        ps->line = ps->fwd_line;
        return fail(ps, "vertex index %llu out of range (%u vertices)",
                    (unsigned long long)ps->fwd_max, m->nverts);
    }
    if (m->nfaces == 0) {
        snprintf(ps->err, ps->errlen, "%s: no faces%s", ps->path,
                 m->info.bytes == 0 ? " (empty file)" : "");
        return -1;
    }
    m->face_start[m->nfaces] = (uint32_t)ps->ncorner;

    /* Close the objects; only the last can be empty (see start_object). */
    for (uint32_t i = 0; i < m->nobjs; i++) {
        uint32_t next = i + 1 < m->nobjs ? m->objs[i + 1].face_first : m->nfaces;
        m->objs[i].face_count = next - m->objs[i].face_first;
    }
    if (m->objs[m->nobjs - 1].face_count == 0)
        m->nobjs--;
    for (uint32_t i = 0; i < m->nobjs; i++) {
        MeshObject *o = &m->objs[i];
        uint32_t lo = UINT32_MAX, hi = 0;
        uint32_t c0 = m->face_start[o->face_first];
        uint32_t c1 = m->face_start[o->face_first + o->face_count];
        for (uint32_t c = c0; c < c1; c++) {
            uint32_t v = m->corner[c];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        o->vert_min = lo;
        o->vert_max = hi;
    }

    /* usemtl names -> material indices, first definition wins. */
    if (ps->nuse) {
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
                fprintf(stderr, "zview: warning: %s:%u: unknown material '%s'\n",
                        ps->path, ps->uses[i].line, ps->uses[i].name);
        }
        for (uint32_t f = 0; f < m->nfaces; f++)
            if (m->face_mat[f] >= 0)
                m->face_mat[f] = map[m->face_mat[f]];
        free(map);
        free(mi.slot);
    }

    /* Give back the growth slack; a failed shrink keeps the old block. */
    void *q;
    if ((q = realloc(m->pos, (size_t)m->nverts * 3 * sizeof(float))))
        m->pos = q;
    if (m->rgb && (q = realloc(m->rgb, (size_t)m->nverts * 3 * sizeof(float))))
        m->rgb = q;
    if ((q = realloc(m->corner, ps->ncorner * sizeof(uint32_t))))
        m->corner = q;
    if ((q = realloc(m->face_start, ((size_t)m->nfaces + 1) * sizeof(uint32_t))))
        m->face_start = q;
    if ((q = realloc(m->face_mat, (size_t)m->nfaces * sizeof(int32_t))))
        m->face_mat = q;
    return 0;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

/* ==== Public API ==== */

int mesh_parse(Mesh *m, const char *path, const char *text, size_t len,
               char *err, size_t errlen)
{
    double t0 = now_ms();
    char dummy[1];
    if (!err || errlen == 0) {
        err = dummy;
        errlen = sizeof dummy;
    }
    err[0] = '\0';
    memset(m, 0, sizeof *m);
    if (!path)
        path = "(input)";
    if (!text)
        len = 0;

    Parser ps = {0};
    ps.m = m;
    ps.path = path;
    ps.err = err;
    ps.errlen = errlen;
    ps.cur_use = -1;

    /* The default object is named after the file, without folder or
     * extension. */
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    const char *dot = strrchr(b, '.');
    size_t bn = dot && dot > b ? (size_t)(dot - b) : strlen(b);
    if (bn > MESH_NAME_MAX - 1)
        bn = MESH_NAME_MAX - 1;
    memcpy(ps.basename, b, bn);
    ps.basename[bn] = '\0';

    m->path = strdup(path);
    if (!m->path || grow((void **)&m->objs, &ps.ocap, 1, sizeof(MeshObject))) {
        fail_oom(&ps);
        goto fail;
    }
    m->nobjs = 1;
    memset(&m->objs[0], 0, sizeof m->objs[0]);
    memcpy(m->objs[0].name, ps.basename, sizeof ps.basename);
    m->info.bytes = len;

    /* Reserve for the densest plausible file (a vertex or a triangle per
     * 24 bytes) so that big meshes are not copied while growing; pages
     * never written are never made resident, and finish() trims. */
    if (len >= ((size_t)1 << 20)) {
        size_t guess = len / 24;
        if (grow((void **)&m->pos, &ps.vcap, guess, 3 * sizeof(float)) ||
            grow((void **)&m->face_mat, &ps.fcap, guess, sizeof(int32_t)) ||
            !(m->face_start = malloc((ps.fcap + 1) * sizeof(uint32_t))) ||
            grow((void **)&m->corner, &ps.ccap, 3 * guess, sizeof(uint32_t))) {
            fail_oom(&ps);
            goto fail;
        }
    }

    const char *p = text, *end = text + len;
    if (len >= 3 && memcmp(p, "\xEF\xBB\xBF", 3) == 0)   /* UTF-8 BOM */
        p += 3;
    uint32_t line = 0;
    while (p < end) {
        line++;
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        const char *next = nl ? nl + 1 : end;
        const char *t = le;
        if (t > p && t[-1] == '\r')
            t--;
        ps.line = line;
        if (t > p && t[-1] == '\\') {
            /* Continuation: join the physical lines, backslash replaced
             * by a blank, into scratch. Errors name the first line. */
            size_t n = 0;
            const char *q = p;
            for (;;) {
                if (scratch_put(&ps, &n, q, (size_t)(t - 1 - q)) ||
                    scratch_put(&ps, &n, " ", 1))
                    goto fail;
                if (next >= end)
                    break;
                q = next;
                line++;
                nl = memchr(q, '\n', (size_t)(end - q));
                le = nl ? nl : end;
                next = nl ? nl + 1 : end;
                t = le;
                if (t > q && t[-1] == '\r')
                    t--;
                if (!(t > q && t[-1] == '\\')) {
                    if (scratch_put(&ps, &n, q, (size_t)(le - q)))
                        goto fail;
                    break;
                }
            }
            if (parse_line(&ps, ps.scratch, ps.scratch + n))
                goto fail;
        } else if (parse_line(&ps, p, le)) {
            goto fail;
        }
        p = next;
    }
    if (finish(&ps))
        goto fail;
    free(ps.uses);
    free(ps.use_index.slot);
    free(ps.scratch);
    m->info.load_ms = now_ms() - t0;
    return 0;

fail:
    free(ps.uses);
    free(ps.use_index.slot);
    free(ps.scratch);
    mesh_free(m);
    return -1;
}

int mesh_load(Mesh *m, const char *path, char *err, size_t errlen)
{
    double t0 = now_ms();
    memset(m, 0, sizeof *m);
    MeshFile f;
    char msg[256];
    if (mesh_file_open(&f, path, msg, sizeof msg)) {
        if (err && errlen)
            snprintf(err, errlen, "%s: %s", path, msg);
        return -1;
    }
    int r = mesh_parse(m, path, f.data, f.len, err, errlen);
    mesh_file_close(&f);
    if (r == 0)
        m->info.load_ms = now_ms() - t0;
    return r;
}

void mesh_free(Mesh *m)
{
    if (!m)
        return;
    free(m->path);
    free(m->pos);
    free(m->rgb);
    free(m->face_start);
    free(m->corner);
    free(m->face_mat);
    free(m->mats);
    free(m->objs);
    memset(m, 0, sizeof *m);
}
