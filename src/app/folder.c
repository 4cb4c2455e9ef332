/* folder.c: the command line's folders as the model files in them, for
 * the checks of a whole folder (--check DIR, -r into its subfolders). A
 * file named on the command line stays as it is; a folder gives its
 * entries sorted by name, those named as models (mesh_path_is_model)
 * unless --all, regular files only (a FIFO or a device in a folder is
 * never opened: opening a FIFO waits for its writer). Each folder is
 * entered once, however many links lead to it (a set of the folders
 * entered, by device and inode): a link that loops, or a tree of links
 * that would multiply the count, costs one look and is counted. */

#define _DEFAULT_SOURCE

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app.h"
#include "grow.h"
#include "mesh.h"

/* The folders entered, by device and inode: open addressing. */
typedef struct {
    dev_t   *dev;
    ino_t   *ino;
    uint8_t *used;
    size_t   n, cap;
} DirSet;

/* Add (dev, ino): 1 when new, 0 when there already, -1 out of memory. */
static int dirset_add(DirSet *s, dev_t dev, ino_t ino)
{
    if (2 * (s->n + 1) > s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 64;
        DirSet t = { calloc(cap, sizeof *t.dev), calloc(cap, sizeof *t.ino), calloc(cap, 1), 0, cap };
        if (!t.dev || !t.ino || !t.used) {
            free(t.dev);
            free(t.ino);
            free(t.used);
            return -1;
        }
        for (size_t i = 0; i < s->cap; i++)
            if (s->used[i])
                dirset_add(&t, s->dev[i], s->ino[i]);
        free(s->dev);
        free(s->ino);
        free(s->used);
        *s = t;
    }
    size_t h = ((uint64_t)ino * 0x9e3779b97f4a7c15ull ^ (uint64_t)dev) & (s->cap - 1);
    for (; s->used[h]; h = (h + 1) & (s->cap - 1))
        if (s->dev[h] == dev && s->ino[h] == ino)
            return 0;
    s->used[h] = 1;
    s->dev[h] = dev;
    s->ino[h] = ino;
    s->n++;
    return 1;
}

static int add_path(FolderList *l, const char *path)
{
    uint32_t cap = (uint32_t)l->cap;
    void *p = l->path;
    if (grow_array(&p, &cap, (uint32_t)l->n + 1, sizeof *l->path))
        return -1;
    l->path = p;
    l->cap = (int)cap;
    if (!(l->path[l->n] = strdup(path)))
        return -1;
    l->n++;
    return 0;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

typedef struct {
    FolderList *l;
    DirSet      seen;
    int         recursive, all;
    char       *err;
    size_t      errlen;
} Walk;

static int walk_dir(Walk *w, const char *dir, int depth);

/* Entry `name` of folder dir: a model file listed, a folder entered
 * (with -r), anything else counted as skipped. */
static int walk_entry(Walk *w, const char *dir, const char *name, int depth)
{
    char path[4096];
    if ((size_t)snprintf(path, sizeof path, "%s%s%s", dir, dir[strlen(dir) - 1] == '/' ? "" : "/", name) >=
        sizeof path) {
        w->l->skipped++;
        return 0;
    }
    struct stat st;
    if (stat(path, &st)) {
        /* a link that loops or dangles, an entry gone since readdir */
        w->l->skipped++;
        return 0;
    }
    if (S_ISDIR(st.st_mode))
        return w->recursive ? walk_dir(w, path, depth + 1) : 0;
    if (!S_ISREG(st.st_mode) || (!w->all && !mesh_path_is_model(name))) {
        w->l->skipped++;
        return 0;
    }
    return add_path(w->l, path);
}

static int walk_dir(Walk *w, const char *dir, int depth)
{
    struct stat st;
    if (stat(dir, &st)) {
        snprintf(w->err, w->errlen, "%s: %s", dir, strerror(errno));
        return -1;
    }
    int fresh = dirset_add(&w->seen, st.st_dev, st.st_ino);
    if (fresh < 0)
        goto nomem;
    if (!fresh || depth > FOLDER_MAX_DEPTH) {
        w->l->loops++;
        return 0;
    }
    DIR *d = opendir(dir);
    if (!d) {
        if (depth == 0) {
            snprintf(w->err, w->errlen, "%s: %s", dir, strerror(errno));
            return -1;
        }
        w->l->skipped++;    /* a subfolder that cannot be read */
        return 0;
    }
    char **names = NULL;
    size_t n = 0, cap = 0;
    struct dirent *e;
    int rc = 0;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 64;
            char **p = realloc(names, cap * sizeof *p);
            if (!p) {
                rc = -1;
                break;
            }
            names = p;
        }
        if (!(names[n] = strdup(e->d_name))) {
            rc = -1;
            break;
        }
        n++;
    }
    closedir(d);
    if (!rc) {
        qsort(names, n, sizeof *names, by_name);
        for (size_t i = 0; i < n && !rc; i++)
            rc = walk_entry(w, dir, names[i], depth);
    }
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
    if (rc && !w->err[0])
        goto nomem;
    return rc;
nomem:
    snprintf(w->err, w->errlen, "out of memory listing %s", dir);
    return -1;
}

int folder_list(FolderList *l, const char *const *args, int nargs, int recursive, int all, char *err,
                size_t errlen)
{
    memset(l, 0, sizeof *l);
    err[0] = 0;
    Walk w = { l, { 0 }, recursive, all, err, errlen };
    int rc = 0;
    for (int i = 0; i < nargs && !rc; i++) {
        struct stat st;
        if (strcmp(args[i], "-") && !stat(args[i], &st) && S_ISDIR(st.st_mode)) {
            l->folders++;
            rc = walk_dir(&w, args[i], 0);
        } else if (add_path(l, args[i])) {
            snprintf(err, errlen, "out of memory");
            rc = -1;
        }
    }
    free(w.seen.dev);
    free(w.seen.ino);
    free(w.seen.used);
    if (rc)
        folder_list_free(l);
    return rc;
}

void folder_list_free(FolderList *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->path[i]);
    free(l->path);
    memset(l, 0, sizeof *l);
}
