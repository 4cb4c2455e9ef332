/* format.c: which loader reads an input. By content first (magic bytes,
 * a header), by extension second; --format forces one. A file no loader
 * accepts is named for what it looks like ("gzip data") in one line.
 * The first bytes are read before anything else, so that a 2 GB file of
 * zeros is refused without being paged in. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "clock.h"
#include "mesh.h"
#include "mesh_internal.h"

static const MeshLoader *const natives[] = {
    &mesh_loader_obj, &mesh_loader_stl, &mesh_loader_ply, &mesh_loader_off, &mesh_loader_xyz,
    &mesh_loader_step, &mesh_loader_iges, &mesh_loader_brep,
};
#define NNATIVE (sizeof natives / sizeof natives[0])

/* Formats assimp reads that a short message names (the full list is
 * zview --formats). */
#define ASSIMP_SHORT "glb gltf fbx dae 3ds 3mf x3d blend ..."

/* ==== What bytes are ==== */

static int starts(const char *h, size_t n, const char *magic, size_t m)
{
    return n >= m && memcmp(h, magic, m) == 0;
}

/* Formats of no loader here, recognised only to be named. Returns NULL
 * when nothing matches. */
static const char *known_other(const char *h, size_t n)
{
    static const struct {
        const char *magic;
        size_t      len;
        const char *what;
    } tab[] = {
        { "\x1f\x8b", 2, "gzip data" },
        { "PK\x03\x04", 4, "zip archive" },
        { "\x89PNG", 4, "PNG image" },
        { "\xff\xd8\xff", 3, "JPEG image" },
        { "GIF8", 4, "GIF image" },
        { "%PDF", 4, "PDF document" },
        { "\x7f" "ELF", 4, "ELF executable" },
        { "BZh", 3, "bzip2 data" },
        { "\xfd" "7zXZ\0", 6, "xz data" },
        { "\x28\xb5\x2f\xfd", 4, "zstd data" },
        { "7z\xbc\xaf\x27\x1c", 6, "7-zip archive" },
        { "Rar!", 4, "RAR archive" },
        { "glTF", 4, "glTF binary" },
        { "Kaydara FBX Binary", 18, "FBX binary" },
        { "BLENDER", 7, "Blender file" },
    };
    for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++)
        if (starts(h, n, tab[i].magic, tab[i].len))
            return tab[i].what;
    return NULL;
}

static int has_nul(const char *h, size_t n) { return memchr(h, '\0', n) != NULL; }

#ifdef ZV_ASSIMP
/* A head of zeros (a sparse file, a disk image's gap) is no format
 * assimp reads either: it is not handed the whole file to find that. */
static int all_zero(const char *h, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (h[i])
            return 0;
    return 1;
}
#endif

/* For the refusal: what the bytes look like. */
static const char *describe(const char *h, size_t n)
{
    if (n == 0)
        return "empty file";
    const char *k = known_other(h, n);
    if (k)
        return k;
    if (mesh_has_binary(h, h + n))
        return "binary data";
    const char *p = h;
    while (p < h + n && mesh_is_ws(*p))
        p++;
    if (p < h + n && *p == '<')
        return "XML or HTML text";
    if (p < h + n && *p == '{')
        return "JSON text";
    return "text";
}

/* The extension of path's file name, lower case, without the dot. */
static void extension(const char *path, char *ext, size_t n)
{
    ext[0] = '\0';
    if (!path)
        return;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.'), *end = base + strlen(base);
    /* part.stl.gz is an STL: the content is decompressed (reader.c), and
     * the name before the .gz says what it holds */
    if (dot && dot > base && strcasecmp(dot, ".gz") == 0) {
        end = dot;
        dot = NULL;
        for (const char *p = base + 1; p < end; p++)
            if (*p == '.')
                dot = p;
    }
    if (!dot || dot == base || (size_t)(end - dot - 1) >= n)
        return;
    size_t i = 0;
    for (const char *p = dot + 1; p < end; p++)
        ext[i++] = (char)(*p >= 'A' && *p <= 'Z' ? *p + 32 : *p);
    ext[i] = '\0';
}

static int in_list(const char *list, const char *word)
{
    size_t wl = strlen(word);
    if (!wl)
        return 0;
    for (const char *p = list; *p;) {
        while (*p == ' ')
            p++;
        const char *q = p;
        while (*q && *q != ' ')
            q++;
        if ((size_t)(q - p) == wl && strncasecmp(p, word, wl) == 0)
            return 1;
        p = q;
    }
    return 0;
}

static const MeshLoader *native_by_name(const char *name)
{
    for (size_t i = 0; i < NNATIVE; i++)
        if (strcasecmp(natives[i]->name, name) == 0)
            return natives[i];
    return NULL;
}

static const MeshLoader *native_by_ext(const char *ext)
{
    for (size_t i = 0; i < NNATIVE; i++)
        if (in_list(natives[i]->exts, ext))
            return natives[i];
    return NULL;
}

/* ==== Format names ==== */

int mesh_format_valid(const char *name)
{
    if (!name || !*name)
        return 0;
    if (native_by_name(name))
        return 1;
#ifdef ZV_ASSIMP
    if ((strcasecmp(name, "assimp") == 0 && mesh_assimp_available()) || mesh_assimp_has_ext(name))
        return 1;
#endif
    return 0;
}

/* The loader of this --format, or this path's extension; NULL: none of
 * zview's own. */
static const MeshLoader *named_loader(const char *path, const char *format)
{
    char ext[16];
    extension(path && strcmp(path, "-") ? path : NULL, ext, sizeof ext);
    return format ? native_by_name(format) : native_by_ext(ext);
}

int mesh_format_is_native(const char *path, const char *format)
{
    const MeshLoader *l = named_loader(path, format);
    return l && !l->library;
}

int mesh_path_is_model(const char *path)
{
    char ext[16];
    extension(path, ext, sizeof ext);
    if (native_by_ext(ext))
        return 1;
#ifdef ZV_ASSIMP
    if (ext[0] && mesh_assimp_has_ext(ext))
        return 1;
#endif
    return 0;
}

void mesh_library_preload(const char *path, const char *format)
{
    const MeshLoader *l = named_loader(path, format);
    if (l && l->library) {
        mesh_occt_available();
        return;
    }
#ifdef ZV_ASSIMP
    if (!l)
        mesh_assimp_available();
#endif
}

void mesh_formats_short(char *buf, size_t n)
{
    size_t k = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < NNATIVE && k < n; i++)
        k += (size_t)snprintf(buf + k, n - k, "%s%s", i ? " " : "", natives[i]->name);
#ifdef ZV_ASSIMP
    if (k < n && mesh_assimp_available())
        snprintf(buf + k, n - k, " + assimp: " ASSIMP_SHORT);
#endif
}

#ifdef ZV_ASSIMP
typedef struct {
    char ext[32], what[72];
} ExtRow;

typedef struct {
    ExtRow *rows;
    size_t  n, cap;
} ExtList;

static void collect(const char *ext, const char *what, void *ctx)
{
    ExtList *l = ctx;
    if (native_by_ext(ext))
        return;             /* read natively; --format assimp still forces assimp */
    for (size_t i = 0; i < l->n; i++)
        if (!strcmp(l->rows[i].ext, ext))
            return;         /* several importers: the first is named */
    if (l->n == l->cap) {
        size_t nc = l->cap ? l->cap * 2 : 64;
        ExtRow *r = realloc(l->rows, nc * sizeof *r);
        if (!r)
            return;
        l->rows = r;
        l->cap = nc;
    }
    snprintf(l->rows[l->n].ext, sizeof l->rows[0].ext, "%s", ext);
    snprintf(l->rows[l->n].what, sizeof l->rows[0].what, "%s", what);
    l->n++;
}

static int row_cmp(const void *a, const void *b)
{
    return strcmp(((const ExtRow *)a)->ext, ((const ExtRow *)b)->ext);
}
#endif

void mesh_formats_print(FILE *f)
{
    char occtv[48];
    for (size_t i = 0; i < NNATIVE; i++)
        if (natives[i]->library)
            fprintf(f, "%-8s occt    %s (%s)\n", natives[i]->name, natives[i]->what,
                    mesh_occt_version(occtv, sizeof occtv));
        else
            fprintf(f, "%-8s native  %s\n", natives[i]->name, natives[i]->what);
#ifdef ZV_ASSIMP
    char ver[32];
    ExtList l = { 0 };
    mesh_assimp_list(collect, &l);
    qsort(l.rows, l.n, sizeof *l.rows, row_cmp);
    mesh_assimp_version(ver, sizeof ver);
    for (size_t i = 0; i < l.n; i++)
        fprintf(f, "%-8s assimp  %s (assimp %s)\n", l.rows[i].ext, l.rows[i].what, ver);
    free(l.rows);
#endif
}

/* ==== Choosing the loader ==== */

/* The loader for these bytes (head: the first n of `size`), or NULL
 * with a description of them in *what. */
static const MeshLoader *pick(const char *head, size_t n, uint64_t size, const char *ext,
                              const char *forced, const char **what, int *try_assimp)
{
    (void)try_assimp;   /* used with assimp only */
    *what = NULL;
    if (forced) {
        const MeshLoader *l = native_by_name(forced);
#ifdef ZV_ASSIMP
        if (!l)
            l = &mesh_loader_assimp;   /* "assimp" or one of its extensions */
#endif
        return l;
    }
    /* 1. a format's own magic or header; a probe only fairly sure (OBJ's
     * first keyword: NFF and others start with `v` too) yields to an
     * extension that names another reader */
    const MeshLoader *maybe = NULL, *fair = NULL;
    for (size_t i = 0; i < NNATIVE; i++) {
        int p = natives[i]->probe ? natives[i]->probe(head, n, size) : PROBE_NO;
        if (p == PROBE_SURE)
            return natives[i];
        if (p == PROBE_FAIR && !fair)
            fair = natives[i];
        if (p == PROBE_MAYBE && !maybe)
            maybe = natives[i];
    }
    if (fair) {
        const MeshLoader *by = native_by_ext(ext);
        int other = by ? by != fair && !by->needs_magic && !(by->text && has_nul(head, n)) &&
                             (!by->probe || by->probe(head, n, size) != PROBE_NO)
                       : 0;
#ifdef ZV_ASSIMP
        if (!by && !other)
            other = mesh_assimp_has_ext(ext);
#endif
        if (!other)
            return fair;
        maybe = fair;
    }
#ifdef ZV_ASSIMP
    if (mesh_loader_assimp.probe(head, n, size) == PROBE_SURE)
        return &mesh_loader_assimp;
#endif
    /* 2. bytes that are clearly something else (a zip is a 3MF when the
     * name says so) */
    const char *other = known_other(head, n);
#ifdef ZV_ASSIMP
    if (!native_by_ext(ext) && (!other || strcmp(other, "zip archive") == 0) &&
        mesh_assimp_has_ext(ext))   /* last: this opens the library */
        return &mesh_loader_assimp;
#endif
    if (other) {
        *what = other;
        return NULL;
    }
    /* 3. the extension; a text format is not given binary bytes, nor a
     * format with a magic bytes without it */
    const MeshLoader *l = native_by_ext(ext);
    if (l && !(l->text && has_nul(head, n)) && !l->needs_magic)
        return l;
    /* 4. text that could be OBJ */
    if (maybe)
        return maybe;
    *what = describe(head, n);
#ifdef ZV_ASSIMP
    /* 5. assimp tells many formats by content (3DS, X, ASE, AC3D): let
     * it try bytes nothing here knows; if it fails too, the refusal is
     * ours (*what) */
    if (n && try_assimp && !all_zero(head, n) && mesh_assimp_available()) {
        *try_assimp = 1;
        return &mesh_loader_assimp;
    }
#endif
    return NULL;
}

static int refuse(MeshErr *e, const char *what)
{
    char list[160];
    mesh_formats_short(list, sizeof list);
#ifndef ZV_ASSIMP
    /* formats assimp would read: say why this build does not */
    if (!strcmp(what, "glTF binary") || !strcmp(what, "FBX binary") || !strcmp(what, "Blender file"))
        return me_fail(e, "not a model zview can read (%s: this build has no assimp; formats: %s)",
                       what, list);
#endif
    return me_fail(e, "not a model zview can read (%s; formats: %s)", what, list);
}

/* A loader whose format says how its models stand (STL, glTF, ...)
 * fills MeshInfo's up, front and up_why; every other format says
 * nothing, and the model stands y-up (the usual default) with no front. */
static void default_stance(Mesh *m, const MeshLoader *l)
{
    if (m->info.up_why[0])
        return;
    m->info.up = UP_Y;
    m->info.front = -1;
    snprintf(m->info.up_why, sizeof m->info.up_why, "%.40s: the format does not say",
             m->info.format[0] ? m->info.format : l->name);
}

/* A load that skipped statements says so once, and keeps the count and
 * the first for the status bar and --info. */
static void report_skipped(MeshCtx *c)
{
    MeshErr *e = &c->err;
    if (e->skipped) {
        c->m->info.skipped = e->skipped;
        snprintf(c->m->info.first_skipped, sizeof c->m->info.first_skipped, "%s", e->first);
        me_warn(e, NULL, 0, "%u statement%s skipped (first: %s)", e->skipped, e->skipped == 1 ? "" : "s",
                e->first);
        if (e->buf && e->len)
            e->buf[0] = '\0';
    }
    c->m->info.warnings = e->warned;
    snprintf(c->m->info.first_warning, sizeof c->m->info.first_warning, "%s", e->warning);
}

/* Run the loader on bytes in memory. The summary of what was skipped is
 * the caller's to report (report_skipped), once it knows the bytes were
 * the file's: a file that changed while read says only that. */
static int run(const MeshLoader *l, MeshCtx *c, const char *data, size_t len)
{
    if (!l->parse)
        return me_fail(&c->err, "%s is read from a named file only, not standard input", l->name);
    int r = l->parse(c, data, len);
    if (r)
        mesh_free(c->m);
    return r;
}

int mesh_parse_buffer(Mesh *m, const char *path, const char *format, const void *data,
                      size_t len, char *err, size_t errlen)
{
    MeshLoadOpts opt = { .format = format, .strict = 1 };
    return mesh_parse_buffer_ex(m, path, &opt, data, len, err, errlen);
}

int mesh_parse_buffer_ex(Mesh *m, const char *path, const MeshLoadOpts *opt, const void *data,
                         size_t len, char *err, size_t errlen)
{
    const char *format = opt ? opt->format : NULL;
    double t0 = now_ms(), c0 = thread_cpu_ms();
    char dummy[1];
    if (!err || !errlen) {
        err = dummy;
        errlen = sizeof dummy;
    }
    err[0] = '\0';
    memset(m, 0, sizeof *m);
    if (!data)
        len = 0;
    MeshCtx c = { .m = m, .err = { .name = path ? path : "(input)", .buf = err, .len = errlen,
                                   .strict = opt ? opt->strict : 1, .quiet = opt && opt->quiet,
                                   .max_polys = opt ? opt->max_polys : 0, .max_bytes = opt ? opt->max_bytes : 0,
                                   .tex_defer_side = opt ? opt->tex_defer_side : 0,
                                   .no_textures = opt && opt->no_textures, .model = path,
                                   .threads = opt ? opt->threads : 0, .piece_bytes = opt ? opt->piece_bytes : 0,
                                   .prefix = opt ? opt->prefix : NULL,
                                   .on_ref = opt ? opt->on_ref : NULL, .on_ref_arg = opt ? opt->on_ref_arg : NULL },
                  .path = path, .tessellation = opt ? opt->tessellation : 0 };
    char ext[16];
    extension(path, ext, sizeof ext);
    c.hint = format ? format : ext;
    if (format && !mesh_format_valid(format))
        return me_fail(&c.err, "unknown format '%s'", format);
    const char *what;
    const MeshLoader *l = pick(data ? data : "", len < MESH_HEAD ? len : MESH_HEAD, len, ext,
                               format, &what, NULL);
    if (!l)
        return refuse(&c.err, what);
    int r = run(l, &c, data ? data : "", len);
    if (r == 0) {
        report_skipped(&c);
        default_stance(m, l);
    }
    if (r == 0) {
        m->info.load_ms = now_ms() - t0;
        m->info.load_cpu_ms = thread_cpu_ms() - c0;
    }
    return r;
}

int mesh_parse(Mesh *m, const char *path, const char *text, size_t len, char *err,
               size_t errlen)
{
    return mesh_parse_buffer(m, path, "obj", text, len, err, errlen);
}

/* A stream's head that could be a binary STL (the only format without
 * a magic): a refusal written into msg (0 to read it), and the size its
 * triangle count gives, and a byte more, in *max. Streams are decided
 * from their first kilobytes: the triangles there must have finite
 * coordinates (a binary STL with any other is refused anyway; random
 * bytes hold a NaN or an infinity every 256 floats), and the count must
 * fit the limits. */
static int stl_stream(const MeshFile *f, const MeshErr *e, uint64_t mem, uint64_t *max, char *msg,
                      size_t msglen)
{
    const char *h = f->head;
    size_t n = f->nhead;
    if (n < 84) {
        *max = n + 1;
        return 0;
    }
    uint32_t tris = rd_u32le(h + 80);
    *max = 84 + 50 * (uint64_t)tris + 1;
    for (size_t t = 84; t + 50 <= n; t += 50)
        for (int k = 0; k < 12; k++)
            if (bits_nonfinite(rd_u32le(h + t + 4 * k))) {
                snprintf(msg, msglen, "not a model zview can read (binary data; not a binary STL, whose "
                         "numbers would be finite: byte %zu)", t + 4 * (size_t)k);
                return -1;
            }
    char cnt[32], lim[32];
    mesh_count_str(tris, cnt, sizeof cnt);
    if (e->max_polys && tris > e->max_polys) {
        mesh_count_str(e->max_polys, lim, sizeof lim);
        snprintf(msg, msglen, "a binary STL of %s triangles, more than the limit of %s polygons "
                 "(--max-polys raises it)", cnt, lim);
        return -1;
    }
    if (mem && *max > mem) {
        char need[32], have[32];
        sysmem_format(*max, need, sizeof need);
        sysmem_format(mem, have, sizeof have);
        snprintf(msg, msglen, "a binary STL of %s triangles needs a stream of %s held in memory; %s "
                 "available for it", cnt, need, have);
        return -1;
    }
    return 0;
}

/* How much of a stream to read, judged from its head, or a refusal in
 * msg (-1). Text stops at a NUL; a PLY header bounds its body; a binary
 * STL stops past the size its triangle count gives; and no stream holds
 * more than half the memory the load may take (the mesh needs the rest). */
static int stream_limits(const MeshFile *f, const MeshErr *e, const char *forced, MfLimits *lim,
                         char *msg, size_t msglen)
{
    memset(lim, 0, sizeof *lim);
    const char *h = f->head;
    size_t n = f->nhead, bom = mesh_bom_len(h, n);
    uint64_t avail = e->max_bytes ? e->max_bytes : sysmem_available();
    lim->mem = avail / 2;
    const MeshLoader *l = forced ? native_by_name(forced) : NULL;
    int ply = forced ? l == &mesh_loader_ply : n - bom >= 3 && memcmp(h + bom, "ply", 3) == 0;
    if (ply) {
        int ascii = 0;
        lim->max = mesh_ply_stream_max(h, n, &ascii);
        lim->stop_at_nul = ascii;
        return 0;
    }
    if (forced) {
        /* a forced STL is binary unless its head reads as ASCII */
        if (l == &mesh_loader_stl && mesh_loader_stl.probe(h, n, UINT64_MAX) != PROBE_SURE)
            return stl_stream(f, e, lim->mem, &lim->max, msg, msglen);
        lim->stop_at_nul = l && l->text;
        return 0;
    }
    if (!has_nul(h, n)) {
        lim->stop_at_nul = !known_other(h, n);   /* text */
        return 0;
    }
    if (known_other(h, n))
        return 0;
    return stl_stream(f, e, lim->mem, &lim->max, msg, msglen);
}

int mesh_load_as(Mesh *m, const char *path, const char *format, char *err, size_t errlen)
{
    MeshLoadOpts opt = { .format = format, .strict = 1 };
    return mesh_load_ex(m, path, &opt, err, errlen);
}

int mesh_load_ex(Mesh *m, const char *path, const MeshLoadOpts *opt, char *err, size_t errlen)
{
    const char *format = opt ? opt->format : NULL;
    double t0 = now_ms(), c0 = thread_cpu_ms();
    char dummy[1];
    if (!err || !errlen) {
        err = dummy;
        errlen = sizeof dummy;
    }
    err[0] = '\0';
    memset(m, 0, sizeof *m);
    int is_stdin = strcmp(path, "-") == 0;
    const char *name = is_stdin ? "stdin" : path;
    MeshCtx c = { .m = m, .err = { .name = name, .buf = err, .len = errlen, .strict = opt ? opt->strict : 1,
                                   .quiet = opt && opt->quiet, .max_polys = opt ? opt->max_polys : 0,
                                   .max_bytes = opt ? opt->max_bytes : 0,
                                   .tex_defer_side = opt ? opt->tex_defer_side : 0,
                                   .no_textures = opt && opt->no_textures,
                                   .model = is_stdin ? NULL : path,
                                   .threads = opt ? opt->threads : 0, .piece_bytes = opt ? opt->piece_bytes : 0,
                                   .prefix = opt ? opt->prefix : NULL,
                                   .on_ref = opt ? opt->on_ref : NULL, .on_ref_arg = opt ? opt->on_ref_arg : NULL },
                  .path = path, .tessellation = opt ? opt->tessellation : 0 };
    char ext[16];
    extension(is_stdin ? NULL : path, ext, sizeof ext);
    c.hint = format ? format : ext;
    if (format && !mesh_format_valid(format))
        return me_fail(&c.err, "unknown format '%s'", format);

    MeshFile f;
    char msg[256];
    if (mf_open(&f, path, opt && opt->regular_only ? MF_REGULAR_ONLY : 0, msg, sizeof msg))
        return me_fail(&c.err, "%s", msg);
    if (opt && opt->progress) {
        __atomic_store_n(&opt->progress->total, f.regular ? f.size : 0, __ATOMIC_RELAXED);
        f.progress = &opt->progress->done;
    }
    if (opt) {
        f.on_window = opt->on_window;
        f.on_window_arg = opt->on_window_arg;
        f.cancel = opt->cancel;
    }
    if (!f.regular) {
        /* a stream is read whole before it is judged (its size is part
         * of what tells a binary STL), within what its head allows */
        MfLimits lim;
        if (stream_limits(&f, &c.err, format, &lim, msg, sizeof msg)) {
            mf_close(&f);
            return me_fail(&c.err, "%s", msg);
        }
        if (mf_load(&f, &lim, msg, sizeof msg)) {
            mf_close(&f);
            return me_fail(&c.err, "%s", msg);
        }
        /* bytes after the last gzip member: ignored with a warning, as
         * zcat does; --strict refuses the file */
        uint64_t junk = mf_gz_trailing(&f);
        if (junk && c.err.strict) {
            mf_close(&f);
            return me_fail(&c.err, "bytes that are not gzip data after the last member (compressed byte %llu; "
                           "--strict refuses them)", (unsigned long long)(junk - 1));
        }
        if (junk)
            me_warn(&c.err, NULL, 0, "trailing garbage after the gzip data ignored (from compressed byte %llu)",
                    (unsigned long long)(junk - 1));
    }
    const char *what;
    /* only a file on disk is offered to assimp by content: bytes in
     * memory (a pipe, the fuzzers) stay with the native loaders */
    int try_assimp = 0;
    const MeshLoader *l = pick(f.head, f.nhead, f.size, ext, format, &what,
                               f.regular && !is_stdin ? &try_assimp : NULL);
    if (!l) {
        mf_close(&f);
        return refuse(&c.err, what);
    }
    int r;
    /* standard input, even redirected from a file, has no name a
     * library could open: it is read from memory */
    if (l->parse_path && f.regular && !is_stdin) {
        uint64_t size = f.size;
        mf_close(&f);
        r = l->parse_path(&c, path);
        if (r && try_assimp) {
            c.err.buf[0] = '\0';
            r = refuse(&c.err, what);
        }
        if (r) {
            mesh_free(m);
        } else {
            m->info.bytes = size;
            report_skipped(&c);
        }
    } else {
        if (f.regular && mf_load(&f, NULL, msg, sizeof msg)) {
            mf_close(&f);
            return me_fail(&c.err, "%s", msg);
        }
        c.file = &f;
        f.mute = &c.err.quiet;
        r = run(l, &c, f.data, f.len);
        if (f.cancelled) {
            if (r == 0)
                mesh_free(m);
            r = me_fail(&c.err, "cancelled");
        } else if (mf_changed(&f)) {
            /* whatever the parser made of it is not the file */
            if (r == 0)
                mesh_free(m);
            r = me_fail(&c.err, "changed while reading");
        } else if (r == 0) {
            report_skipped(&c);
        }
        mf_close(&f);
    }
    if (r == 0) {
        default_stance(m, l);
        m->info.load_ms = now_ms() - t0;
        m->info.load_cpu_ms = thread_cpu_ms() - c0;
    }
    return r;
}

int mesh_load(Mesh *m, const char *path, char *err, size_t errlen)
{
    return mesh_load_as(m, path, NULL, err, errlen);
}
