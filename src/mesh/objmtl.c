/* objmtl.c: the materials of an OBJ. usemtl names are collected as
 * they come (faces keep the name's index); mtllib libraries are read
 * through mtl.c, each file once however often and however it is named,
 * with bounds on how many and how much; after the last line each name
 * becomes the index of the first material defined with it. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "obj.h"
#include "sysmem.h"

/* ==== Name sets ==== */

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

/* ==== Libraries read, by name and by file ==== */

/* A library is looked at once: a name repeated on every line of a
 * hostile file, or two names of one file (the LibSet), read it once. */

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
            uint32_t j = name_hash(ls->names[i]) & (nc - 1);
            while (ns[j])
                j = (j + 1) & (nc - 1);
            ns[j] = i + 1;
        }
        free(ls->slot);
        ls->slot = ns;
        ls->slotcap = nc;
    }
    uint32_t mask = ls->slotcap - 1, j = name_hash(name) & mask;
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

/* ==== usemtl ==== */

/* Copy the rest of a statement, trimmed, into a name buffer. */
static void take_name(char *dst, const char *p, const char *e)
{
    obj_trim(&p, &e);
    size_t n = (size_t)(e - p);
    if (n > MESH_NAME_MAX - 1)
        n = MESH_NAME_MAX - 1;
    memcpy(dst, p, n);
    dst[n] = '\0';
}

int obj_use_material(Parser *ps, const char *p, const char *e)
{
    char name[MESH_NAME_MAX];
    take_name(name, p, e);
    if (!name[0]) {                 /* bare usemtl: back to the default */
        ps->cur_use = -1;
        return 0;
    }
    int32_t i = obj_use_index(ps, name, ps->line);
    if (i < 0)
        return obj_oom(ps);
    ps->cur_use = i;
    return 0;
}

int32_t obj_use_index(Parser *ps, const char *name, uint64_t line)
{
    int32_t i = name_find(&ps->use_index, ps->uses, sizeof(UseName), name);
    if (i >= 0)
        return i;
    if (ps->nuse == ps->usecap) {
        size_t cap = ps->usecap;
        if (grow_size((void **)&ps->uses, &cap, (size_t)ps->nuse + 1, sizeof(UseName)))
            return -1;
        ps->usecap = (uint32_t)cap;
    }
    UseName *u = &ps->uses[ps->nuse];
    snprintf(u->name, sizeof u->name, "%s", name);
    u->line = line;
    if (name_add(&ps->use_index, ps->uses, sizeof(UseName), ps->nuse))
        return -1;
    return (int32_t)ps->nuse++;
}

/* ==== mtllib ==== */

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
        return obj_oom(ps);
    memcpy(full, ps->path, dl);
    memcpy(full + dl, name, n);
    full[dl + n] = '\0';
    /* A name given before (every line of a hostile file can name the
     * same library, even the OBJ itself) is not looked at again. */
    int r = libset_add_name(&ps->libs, full);
    if (r <= 0)
        return r < 0 ? obj_oom(ps) : 0;
    if (++ps->lib_tries > MTL_MAX_LIBS) {
        ps->lib_failed++;
        return 0;
    }
    MeshFile f;
    char msg[160];
    /* Regular files beneath the model's folder only: a FIFO or
     * /dev/stdin would block for ever, ../../secret.mtl is not the
     * model's to show (mesh_ref_open). */
    char why[200];
    char ref[120];
    int fd = me_ref_open(ps->e, ps->e->model, full, 0, ref, sizeof ref);
    if (fd < 0)
        snprintf(msg, sizeof msg, "%s%s", strncmp(ref, "refused", 7) ? "cannot open: " : "", ref);
    if (fd < 0 || mf_open_fd(&f, fd, MF_REGULAR_ONLY, msg, sizeof msg)) {
        snprintf(why, sizeof why, "(%s)", msg);
        return lib_unread(ps, name, n, "cannot open material library", why);
    }
    r = libset_add_file(&ps->libs, f.dev, f.ino);
    if (r <= 0) {
        mf_close(&f);
        return r < 0 ? obj_oom(ps) : 0;
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
    r = mesh_mtl_parse(&ps->b, full, &f, f.data, f.len);
    int changed = mf_changed(&f);
    mf_close(&f);
    if (r < 0)
        return obj_oom(ps);
    if (changed) {
        ps->m->nmats = had;     /* what was read of it cannot be trusted */
        return lib_unread(ps, name, n, "material library", "changed while reading: not used");
    }
    ps->mtl_loaded = 1;
    return 0;
}

int obj_mtllib(Parser *ps, const char *p, const char *e)
{
    /* libraries are read in the order the file names them: not by a
     * piece (the serial parser reads on from it) */
    if (ps->piece)
        return obj_fail(ps, "mtllib in a piece");
    obj_trim(&p, &e);
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

/* ==== After the last line ==== */

int obj_resolve_materials(Parser *ps)
{
    Mesh *m = ps->m;
    if (!ps->nuse)
        return 0;
    /* usemtl names -> material indices, first definition wins. */
    int32_t *map = malloc(ps->nuse * sizeof *map);
    NameIndex mi = {0};
    if (!map)
        return obj_oom(ps);
    for (uint32_t i = 0; i < m->nmats; i++) {
        if (name_find(&mi, m->mats, sizeof(Material), m->mats[i].name) < 0 &&
            name_add(&mi, m->mats, sizeof(Material), i)) {
            free(map);
            free(mi.slot);
            return obj_oom(ps);
        }
    }
    for (uint32_t i = 0; i < ps->nuse; i++) {
        map[i] = name_find(&mi, m->mats, sizeof(Material), ps->uses[i].name);
        if (map[i] < 0 && ps->mtl_loaded)
            me_warn(ps->e, NULL, ps->uses[i].line, "unknown material '%s'", ps->uses[i].name);
    }
    for (uint32_t f = 0; m->face_mat && f < m->nfaces; f++)
        if (m->face_mat[f] >= 0)
            m->face_mat[f] = map[m->face_mat[f]];
    free(map);
    free(mi.slot);
    return 0;
}

void obj_libs_warn(Parser *ps)
{
    if (ps->lib_failed > MTL_WARN_LIBS) {
        char more[32], named[32];
        mesh_count_str(ps->lib_failed - MTL_WARN_LIBS, more, sizeof more);
        mesh_count_str(ps->libs.nnames, named, sizeof named);
        me_warn(ps->e, NULL, 0, "%s more material librar%s could not be read (%s named%s)", more,
                ps->lib_failed - MTL_WARN_LIBS == 1 ? "y" : "ies", named,
                ps->lib_tries > MTL_MAX_LIBS ? "; only the first 1,024 are looked for" : "");
    }
}

void obj_materials_free(Parser *ps)
{
    free(ps->uses);
    free(ps->use_index.slot);
    libset_free(&ps->libs);
}
