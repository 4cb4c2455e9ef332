/* save.c: the front door of the writers: which format, the files opened
 * whole-or-nothing (safefile.h), the writer run, every write checked,
 * and the one message that names the file that failed. An OBJ with
 * materials is two files, the model and its MTL beside it (the model's
 * name with .mtl): both are written to temporary names and take their
 * names only when both are complete. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "safefile.h"
#include "save_internal.h"

static const char *const format_names[SAVE_COUNT] = { "stl", "obj", "ply" };

const char *save_format_name(SaveFormat f)
{
    return f < SAVE_COUNT ? format_names[f] : "?";
}

int save_format_from_name(const char *name)
{
    for (int i = 0; i < SAVE_COUNT; i++)
        if (!strcasecmp(name, format_names[i]))
            return i;
    return -1;
}

int save_format_of_path(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash))
        return -1;
    return save_format_from_name(dot + 1);
}

int so_flush(SaveOut *o)
{
    if (o->err)
        return -1;
    errno = 0;
    if (o->n && fwrite(o->buf, 1, o->n, o->f) != o->n) {
        o->err = errno ? errno : EIO;
        return -1;
    }
    o->n = 0;
    return 0;
}

/* Everything buffered out, stdio's buffer too; the first failure kept. */
static int so_finish(SaveOut *o)
{
    so_flush(o);
    errno = 0;
    if (!o->err && (fflush(o->f) != 0 || ferror(o->f)))
        o->err = errno ? errno : EIO;
    return o->err ? -1 : 0;
}

/* One file being written: where, and how it goes. */
typedef struct {
    const char *path;           /* as the caller named it (messages) */
    SafeFile    sf;
    FILE       *f;
    int         to_stdout;
    int         existed;        /* a file was at path before */
    SaveOut     out;
} Target;

static int target_open(Target *t, const char *path, char *buf, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    t->path = path;
    t->out.buf = buf;
    t->to_stdout = !strcmp(path, "-");
    if (t->to_stdout) {
        t->f = stdout;
    } else {
        struct stat st;
        t->existed = stat(path, &st) == 0;
        t->f = safefile_open(&t->sf, path, "wb");
        if (!t->f) {
            snprintf(err, errlen, "%s: %s", path, strerror(errno));
            return -1;
        }
    }
    t->out.f = t->f;
    return 0;
}

/* Close (or, failed, remove what was written). 0, or -1 with the
 * message when err is still empty. */
static int target_close(Target *t, int failed, char *err, size_t errlen)
{
    if (!t->f)
        return 0;
    int rc = 0;
    if (t->to_stdout) {
        rc = failed ? -1 : 0;
    } else {
        errno = t->out.err;
        rc = safefile_close(&t->sf, t->f, failed);
        if (rc && !failed && !err[0])
            snprintf(err, errlen, "%s: %s", t->path, strerror(errno ? errno : EIO));
    }
    t->f = NULL;
    return rc;
}

/* The MTL beside an OBJ: its name with .obj replaced by .mtl (or .mtl
 * added). -1 when it does not fit. */
static int mtl_path_of(const char *path, char *out, size_t n)
{
    size_t len = strlen(path);
    size_t stem = len >= 4 && !strcasecmp(path + len - 4, ".obj") ? len - 4 : len;
    if (stem + 5 > n)
        return -1;
    memcpy(out, path, stem);
    memcpy(out + stem, ".mtl", 5);
    return 0;
}

int save_mesh(const Mesh *m, const char *path, SaveFormat fmt, SaveReport *rep, char *err, size_t errlen)
{
    SaveReport local;
    if (!rep)
        rep = &local;
    memset(rep, 0, sizeof *rep);
    rep->format = fmt;
    err[0] = 0;
    int with_mtl = fmt == SAVE_OBJ && m->nmats > 0 && strcmp(path, "-");
    char (*names)[SAVE_NAME] = NULL;
    char *bufs = malloc(2 * (size_t)SAVE_BUF);
    if (fmt == SAVE_OBJ && m->nmats)
        names = malloc((size_t)m->nmats * sizeof *names);
    if (!bufs || (fmt == SAVE_OBJ && m->nmats && (!names || save_obj_names(m, names)))) {
        free(bufs);
        free(names);
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    if (with_mtl && mtl_path_of(path, rep->mtl_path, sizeof rep->mtl_path)) {
        free(bufs);
        free(names);
        snprintf(err, errlen, "%s: name too long", path);
        return -1;
    }
    Target model, mtl = { 0 };
    int failed = target_open(&model, path, bufs, err, errlen) ||
                 (with_mtl && target_open(&mtl, rep->mtl_path, bufs + SAVE_BUF, err, errlen));
    if (!failed) {
        const char *slash = strrchr(rep->mtl_path, '/');
        switch (fmt) {
        case SAVE_STL: save_stl(m, &model.out, rep); break;
        case SAVE_PLY: save_ply(m, &model.out, rep); break;
        default:
            save_obj(m, &model.out, with_mtl ? (slash ? slash + 1 : rep->mtl_path) : NULL, names, rep);
            if (with_mtl)
                save_mtl(m, &mtl.out, names);
            break;
        }
        if (so_finish(&model.out)) {
            snprintf(err, errlen, "%s: %s", model.to_stdout ? "standard output" : path, strerror(model.out.err));
            failed = 1;
        } else if (with_mtl && so_finish(&mtl.out)) {
            snprintf(err, errlen, "%s: %s", rep->mtl_path, strerror(mtl.out.err));
            failed = 1;
        }
    }
    rep->bytes = model.out.bytes;
    /* the library first: the model then never names one that is not there */
    if (target_close(&mtl, failed, err, errlen))
        failed = 1;
    if (target_close(&model, failed, err, errlen)) {
        failed = 1;
        if (with_mtl && !mtl.existed)
            unlink(rep->mtl_path);      /* written for a model that is not */
    }
    if (failed && !with_mtl)
        rep->mtl_path[0] = 0;
    free(bufs);
    free(names);
    return failed ? -1 : 0;
}
