/* wire.c: a loaded Mesh across the process boundary, through a memfd.
 * The child writes the mesh into the memfd (a header, a table of spans,
 * the arrays: pwrite, one copy); the parent reads it into a Mesh of
 * malloc'd arrays (pread into arrays faulted in by huge pages, one copy),
 * which is what mesh_free and every later stage expect. The parent
 * trusts nothing it reads: a child a hostile file took over writes what
 * it likes, so every span is checked against the mapping, every length
 * against the counts, and every index against what it indexes, before a
 * byte of it is used (wire_check). */

#define _GNU_SOURCE

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/uio.h>
#include <unistd.h>

#include "bigmem.h"
#include "sandbox.h"

#define WIRE_MAGIC 0x7a763232u  /* "zv22": the arrays are in the memfd */
#define WIRE_MAGIC_VM 0x7a76766du /* "zvvm": the spans are the child's addresses */

typedef struct {
    uint64_t off, len;
    uint32_t present;           /* the pointer was not NULL */
    uint32_t pad;
} WireSpan;

typedef struct {
    uint32_t magic;
    int32_t  rc;
    char     err[512];
    Mesh     mesh;              /* its scalars; the pointers mean nothing here */
    uint32_t nspans;
    uint32_t pad;
} WireHead;

/* The arrays of a Mesh in wire order: face_start before corner and
 * corner_uv (their lengths come from it), line_start before
 * line_corner, tex before the textures' own arrays (appended after). */
enum { F_PATH, F_POS, F_RGB, F_FSTART, F_CORNER, F_FMAT, F_MATS, F_OBJS, F_POINT, F_LSTART,
       F_LCORNER, F_UV, F_CUV, F_TEX, F_FIXED };
enum { T_NAME, T_PATH, T_DATA, T_RGBA, T_SPANS };

static void **slot(Mesh *m, int k)
{
    switch (k) {
    case F_PATH: return (void **)&m->path;
    case F_POS: return (void **)&m->pos;
    case F_RGB: return (void **)&m->rgb;
    case F_FSTART: return (void **)&m->face_start;
    case F_CORNER: return (void **)&m->corner;
    case F_FMAT: return (void **)&m->face_mat;
    case F_MATS: return (void **)&m->mats;
    case F_OBJS: return (void **)&m->objs;
    case F_POINT: return (void **)&m->point;
    case F_LSTART: return (void **)&m->line_start;
    case F_LCORNER: return (void **)&m->line_corner;
    case F_UV: return (void **)&m->uv;
    case F_CUV: return (void **)&m->corner_uv;
    default: return (void **)&m->tex;
    }
}

static void **tex_slot(MeshTexture *t, int k)
{
    switch (k) {
    case T_NAME: return (void **)&t->name;
    case T_PATH: return (void **)&t->path;
    case T_DATA: return &t->data;
    default: return (void **)&t->img.rgba;
    }
}

static uint64_t corners(const Mesh *m)
{
    return m->face_start ? m->face_start[m->nfaces] : 0;
}

/* The bytes array k of m holds (strings: with their NUL). Lengths that
 * depend on an earlier array (corner on face_start) read it: the reader
 * calls this only after checking that array. */
static uint64_t want_len(const Mesh *m, int k)
{
    switch (k) {
    case F_PATH: return m->path ? strlen(m->path) + 1 : 0;
    case F_POS: case F_RGB: return (uint64_t)m->nverts * 12;
    case F_FSTART: return ((uint64_t)m->nfaces + 1) * 4;
    case F_CORNER: case F_CUV: return corners(m) * 4;
    case F_FMAT: return (uint64_t)m->nfaces * 4;
    case F_MATS: return (uint64_t)m->nmats * sizeof(Material);
    case F_OBJS: return (uint64_t)m->nobjs * sizeof(MeshObject);
    case F_POINT: return (uint64_t)m->npoints * 4;
    case F_LSTART: return ((uint64_t)m->nlines + 1) * 4;
    case F_LCORNER: return m->line_start ? (uint64_t)m->line_start[m->nlines] * 4 : 0;
    case F_UV: return (uint64_t)m->nuv * 8;
    default: return (uint64_t)m->ntex * sizeof(MeshTexture);
    }
}

static uint64_t tex_len(const MeshTexture *t, int k)
{
    switch (k) {
    case T_NAME: return t->name ? strlen(t->name) + 1 : 0;
    case T_PATH: return t->path ? strlen(t->path) + 1 : 0;
    case T_DATA: return t->data ? t->len : 0;
    default: return t->img.rgba ? texture_bytes_for(t->img.w, t->img.h) : 0;   /* the sRGB levels only */
    }
}

static uint64_t round8(uint64_t n)
{
    return (n + 7) & ~(uint64_t)7;
}

/* All of buf at off: 0, or -1. pwrite, not a shared mapping: the kernel
 * copies into the memfd's pages without a page fault for each. */
static int put(int fd, const void *buf, uint64_t len, uint64_t off)
{
    const char *p = buf;
    while (len) {
        ssize_t w = pwrite(fd, p, len, (off_t)off);
        if (w <= 0)
            return -1;
        p += w;
        off += (uint64_t)w;
        len -= (uint64_t)w;
    }
    return 0;
}

int sandbox_wire_write(int fd, const Mesh *m, int rc, const char *err, int in_child)
{
    Mesh mm = rc ? (Mesh){ 0 } : *m;
    uint32_t nspans = F_FIXED + mm.ntex * T_SPANS;
    size_t head = sizeof(WireHead) + (size_t)nspans * sizeof(WireSpan);
    char *hb = calloc(1, head);
    if (!hb)
        return -1;
    WireHead *h = (WireHead *)hb;
    WireSpan *sp = (WireSpan *)(hb + sizeof *h);
    h->rc = rc;
    snprintf(h->err, sizeof h->err, "%s", err ? err : "");
    h->mesh = mm;
    h->nspans = nspans;
    uint64_t at = round8(head);
    int r = 0;
    for (uint32_t s = 0; s < nspans && r == 0; s++) {
        const MeshTexture *t = s >= F_FIXED ? &mm.tex[(s - F_FIXED) / T_SPANS] : NULL;
        int k = t ? (int)((s - F_FIXED) % T_SPANS) : (int)s;
        void *p = t ? *tex_slot((MeshTexture *)t, k) : *slot(&mm, k);
        uint64_t len = !p ? 0 : t ? tex_len(t, k) : want_len(&mm, k);
        sp[s] = (WireSpan){ .off = in_child ? (uint64_t)(uintptr_t)p : at, .len = len, .present = p != NULL };
        if (len && !in_child)
            r = put(fd, p, len, at);
        at += round8(len);
    }
    /* the magic last: a child that died half-way left none (a header
     * written before, of the other kind, is unmarked first) */
    uint32_t magic = 0;
    r |= put(fd, &magic, sizeof magic, offsetof(WireHead, magic));
    if (r == 0)
        r = put(fd, hb, head, 0);
    magic = in_child ? WIRE_MAGIC_VM : WIRE_MAGIC;
    if (r == 0)
        r = put(fd, &magic, sizeof magic, offsetof(WireHead, magic));
    free(hb);
    return r;
}

/* ==== Reading, trusting nothing ==== */

static int bad(char *err, size_t errlen, const char *what)
{
    snprintf(err, errlen, "the sandboxed loader returned a malformed mesh (%s)", what);
    return -1;
}

static int runs_ok(const uint32_t *start, uint32_t n, const uint32_t *idx, uint32_t bound, int allow_none)
{
    if (!start)
        return n == 0;
    if (start[0] != 0)
        return 0;
    for (uint32_t i = 0; i < n; i++)
        if (start[i + 1] < start[i])
            return 0;
    for (uint64_t i = 0; idx && i < start[n]; i++)
        if (idx[i] >= bound && !(allow_none && idx[i] == MESH_NO_UV))
            return 0;
    return 1;
}

static int texture_ok(const Texture *t)
{
    if (!t->rgba)
        return 1;
    if (t->w < 1 || t->h < 1 || t->w > TEX_MAX_SIDE || t->h > TEX_MAX_SIDE || t->levels < 1 ||
        t->levels > TEX_MAX_LEVELS)
        return 0;
    uint64_t bytes = texture_bytes_for(t->w, t->h);
    for (int k = 0; k < t->levels; k++) {
        int lw = t->w >> k > 1 ? t->w >> k : 1, lh = t->h >> k > 1 ? t->h >> k : 1;
        if (t->lw[k] != lw || t->lh[k] != lh || t->off[k] > bytes || bytes - t->off[k] < (uint64_t)lw * lh * 4)
            return 0;
    }
    return 1;
}

/* Every index of m within what it indexes (the arrays are the right
 * lengths already). */
static const char *wire_check(const Mesh *m)
{
    if (!runs_ok(m->face_start, m->nfaces, m->corner, m->nverts, 0) || (m->nfaces && !m->corner))
        return "faces";
    if (m->corner_uv && !runs_ok(m->face_start, m->nfaces, m->corner_uv, m->nuv, 1))
        return "texture coordinates";
    if (!runs_ok(m->line_start, m->nlines, m->line_corner, m->nverts, 0))
        return "lines";
    for (uint32_t i = 0; m->point && i < m->npoints; i++)
        if (m->point[i] >= m->nverts)
            return "points";
    if (!m->point && m->npoints > m->nverts)
        return "points";
    for (uint32_t i = 0; m->face_mat && i < m->nfaces; i++)
        if (m->face_mat[i] < -1 || (m->face_mat[i] >= 0 && (uint32_t)m->face_mat[i] >= m->nmats))
            return "face materials";
    for (uint32_t i = 0; i < m->nmats; i++)
        if (m->mats[i].tex < -1 || (m->mats[i].tex >= 0 && (uint32_t)m->mats[i].tex >= m->ntex))
            return "material textures";
    for (uint32_t i = 0; i < m->nobjs; i++) {
        const MeshObject *o = &m->objs[i];
        if ((uint64_t)o->face_first + o->face_count > m->nfaces ||
            (uint64_t)o->point_first + o->point_count > m->npoints ||
            (uint64_t)o->line_first + o->line_count > m->nlines || o->vert_min > o->vert_max ||
            (m->nverts && o->vert_max >= m->nverts))
            return "objects";
    }
    for (uint32_t i = 0; i < m->ntex; i++)
        if (!texture_ok(&m->tex[i].img) || m->tex[i].state > MTEX_PENDING)
            return "textures";
    return NULL;
}

#define TERMINATE(a) ((a)[sizeof(a) - 1] = 0)

/* The fixed-size strings ended, the enums within range: printed and
 * used as indices later. */
static const char *tidy(Mesh *m)
{
    MeshInfo *in = &m->info;
    TERMINATE(in->format);
    TERMINATE(in->first_unknown);
    TERMINATE(in->first_skipped);
    TERMINATE(in->first_warning);
    TERMINATE(in->up_why);
    TERMINATE(in->first_tex_failed);
    TERMINATE(in->unit);
    for (uint32_t i = 0; i < m->nmats; i++)
        TERMINATE(m->mats[i].name);
    for (uint32_t i = 0; i < m->nobjs; i++)
        TERMINATE(m->objs[i].name);
    if (in->up < 0 || in->up >= UP_COUNT || in->front < -1 || in->front >= UP_COUNT)
        return "axes";
    return NULL;
}

/* Where the arrays are: the memfd (len bytes), or the memory of the
 * child pid, which waits to be read (process_vm_readv: no memfd copy). */
typedef struct {
    int    fd;
    size_t len;
    pid_t  pid;
    int    vm;              /* the header said the spans are addresses */
} Src;

static int src_read(const Src *src, char *dst, uint64_t len, uint64_t off)
{
    for (uint64_t got = 0; got < len;) {
        ssize_t r;
        if (src->vm) {
            struct iovec here = { dst + got, len - got }, there = { (void *)(uintptr_t)(off + got), len - got };
            r = process_vm_readv(src->pid, &here, 1, &there, 1, 0);
        } else {
            r = pread(src->fd, dst + got, len - got, (off_t)(off + got));
        }
        if (r <= 0)
            return -1;
        got += (uint64_t)r;
    }
    return 0;
}

/* Span s into a fresh array at *dst: 0, or -1. Big arrays get huge
 * pages and are faulted in at once (bigmem.h), then filled by one read:
 * the one copy the parent makes. */
static int take(const Src *src, const WireSpan *s, uint64_t want, int is_str, void **dst)
{
    *dst = NULL;
    if (!s->present)
        return 0;
    if ((!src->vm && (s->off > src->len || src->len - s->off < s->len)) || (!is_str && s->len != want) ||
        (is_str && s->len == 0) || s->len > ((uint64_t)1 << 46))
        return -1;
    char *p = malloc(s->len ? s->len : 1);
    if (!p)
        return -1;
    *dst = p;
    bigmem_advise(p, s->len, 1);
    if (src_read(src, p, s->len, s->off))
        return -1;
    if (is_str && memchr(p, 0, s->len) != p + s->len - 1)
        return -1;
    return 0;
}

int sandbox_wire_read(int fd, size_t len, pid_t pid, Mesh *m, int *rc, char *err, size_t errlen)
{
    WireHead hd;
    const WireHead *h = &hd;
    memset(m, 0, sizeof *m);
    if (len < sizeof hd || pread(fd, &hd, sizeof hd, 0) != (ssize_t)sizeof hd ||
        (hd.magic != WIRE_MAGIC && !(pid > 0 && hd.magic == WIRE_MAGIC_VM)))
        return bad(err, errlen, "no result");
    Src src = { .fd = fd, .len = len, .pid = pid, .vm = hd.magic == WIRE_MAGIC_VM };
    *rc = h->rc ? -1 : 0;
    if (h->rc) {
        snprintf(err, errlen, "%.*s", (int)strnlen(h->err, sizeof h->err - 1), h->err);
        return 0;
    }
    Mesh hm = h->mesh;
    if (hm.ntex > ((uint32_t)-1 - F_FIXED) / T_SPANS || h->nspans != F_FIXED + hm.ntex * T_SPANS ||
        (len - sizeof *h) / sizeof(WireSpan) < h->nspans)
        return bad(err, errlen, "span table");
    size_t spbytes = (size_t)h->nspans * sizeof(WireSpan);
    WireSpan *sp = malloc(spbytes);
    if (!sp || pread(fd, sp, spbytes, sizeof hd) != (ssize_t)spbytes) {
        free(sp);
        return bad(err, errlen, "span table");
    }
    *m = hm;
    for (int k = 0; k < F_FIXED; k++)
        *slot(m, k) = NULL;
    for (int k = 0; k < F_FIXED; k++) {
        if (take(&src, &sp[k], want_len(m, k), k == F_PATH, slot(m, k)))
            goto fail;
        if ((k == F_FSTART && !runs_ok(m->face_start, m->nfaces, NULL, 0, 0)) ||
            (k == F_LSTART && !runs_ok(m->line_start, m->nlines, NULL, 0, 0)))
            goto fail;
    }
    for (uint32_t i = 0; m->tex && i < m->ntex; i++) {
        MeshTexture *t = &m->tex[i];
        uint64_t dlen = t->len;
        int w = t->img.w, ht = t->img.h;
        for (int k = 0; k < T_SPANS; k++)
            *tex_slot(t, k) = NULL;
        t->img.lin = NULL;      /* the child's pointer: the 16-bit copy is made here, below */
        m->ntex = i + 1;        /* what mesh_free may look at, should this one fail */
        if (sp[F_FIXED + i * T_SPANS + T_RGBA].present && (w < 1 || ht < 1 || w > TEX_MAX_SIDE || ht > TEX_MAX_SIDE))
            goto fail;
        for (int k = 0; k < T_SPANS; k++) {
            uint64_t want = k == T_DATA ? dlen : k == T_RGBA ? texture_bytes_for(w, ht) : 0;
            if (take(&src, &sp[F_FIXED + i * T_SPANS + k], want, k <= T_PATH, tex_slot(t, k)))
                goto fail;
        }
        if (t->img.rgba && texture_ok(&t->img))
            texture_make_lin(&t->img);      /* sampling's 16-bit linear texels, from the sRGB levels */
        m->ntex = hm.ntex;
    }
    if (!m->tex && m->ntex)
        goto fail;
    const char *what = tidy(m);
    if (!what)
        what = wire_check(m);
    free(sp);
    if (what) {
        mesh_free(m);
        return bad(err, errlen, what);
    }
    return 0;
fail:
    free(sp);
    if (!m->tex)
        m->ntex = 0;
    mesh_free(m);
    return bad(err, errlen, "an array's length");
}
