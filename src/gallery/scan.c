/* scan.c: the gallery's files. A folder given is read once, one level:
 * its subfolders and the links to folders are not entered (a link loop
 * cannot be followed, and a tree of links cannot multiply the count);
 * each entry is looked at with lstat, and a link with stat once, so
 * that a link that loops (ELOOP) or dangles is a tile saying so, never
 * a wait. A FIFO or a device named like a model is a tile too, refused
 * without opening it (opening a FIFO would wait for its writer). At
 * most GALLERY_MAX_FILES are listed: past it entries are counted only,
 * so that a folder of a million files costs its readdir and no more. */

#define _DEFAULT_SOURCE

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "gallery.h"
#include "grow.h"
#include "mesh.h"

int gallery_is_model_name(const char *name)
{
    return mesh_path_is_model(name);
}

/* Room for one more tile (at most GALLERY_MAX_FILES: the int holds
 * it): 0, or -1 out of memory. */
static int grow(GalleryList *l)
{
    uint32_t cap = (uint32_t)l->cap;
    void *p = l->tile;
    if (grow_array(&p, &cap, (uint32_t)l->n + 1, sizeof *l->tile))
        return -1;
    l->tile = p;
    l->cap = (int)cap;
    return 0;
}

/* A tile for path (copied), its state and size from st (NULL: why says
 * it cannot be read). 0, or -1 out of memory. */
static int add(GalleryList *l, const char *path, const struct stat *st, const char *why)
{
    if (l->n >= GALLERY_MAX_FILES) {
        l->over++;
        return 0;
    }
    if (grow(l))
        return -1;
    GalleryTile *t = &l->tile[l->n];
    memset(t, 0, sizeof *t);
    if (!(t->path = strdup(path)))
        return -1;
    const char *slash = strrchr(t->path, '/');
    t->name = slash && slash[1] ? slash + 1 : t->path;
    t->state = GS_PENDING;
    if (st && S_ISREG(st->st_mode))
        t->size = (uint64_t)st->st_size;
    else {
        t->state = GS_UNREADABLE;
        snprintf(t->verdict, sizeof t->verdict, "unreadable: %s", why ? why : "not a regular file");
    }
    l->n++;
    return 0;
}

/* One entry of a folder: its tile, or nothing (a folder, a link to
 * one, a file not a model's). 0, or -1 out of memory. */
static int entry(GalleryList *l, const char *path, const char *name, int all)
{
    struct stat st;
    int model = gallery_is_model_name(name);
    if (lstat(path, &st) != 0)
        return model || all ? add(l, path, NULL, strerror(errno)) : 0;
    if (S_ISDIR(st.st_mode))
        return 0;
    if (S_ISLNK(st.st_mode)) {
        if (stat(path, &st) != 0) {
            const char *why = errno == ELOOP ? "a link that loops" : errno == ENOENT ? "a link to nothing"
                                                                                      : strerror(errno);
            return model || all ? add(l, path, NULL, why) : 0;
        }
        if (S_ISDIR(st.st_mode))
            return 0;           /* a link to a folder is not entered */
    }
    if (!model && !all) {
        l->skipped++;
        return 0;
    }
    return add(l, path, &st, S_ISFIFO(st.st_mode) ? "a FIFO" : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                                  : NULL);
}

static int folder(GalleryList *l, const char *dir, int all, char *err, size_t errlen)
{
    DIR *d = opendir(dir);
    if (!d) {
        snprintf(err, errlen, "%s: %s", dir, strerror(errno));
        return -1;
    }
    size_t dn = strlen(dir);
    while (dn > 1 && dir[dn - 1] == '/')
        dn--;
    char path[4096];
    struct dirent *e;
    int rc = 0;
    while (!rc && (e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        if (l->n >= GALLERY_MAX_FILES) {
            l->over++;          /* counted, not looked at */
            continue;
        }
        if ((size_t)snprintf(path, sizeof path, "%.*s/%s", (int)dn, dir, e->d_name) >= sizeof path)
            continue;           /* a path longer than any the system opens */
        rc = entry(l, path, e->d_name, all);
    }
    closedir(d);
    if (rc)
        snprintf(err, errlen, "%s: out of memory", dir);
    return rc;
}

static int by_name(const void *a, const void *b)
{
    const GalleryTile *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    return c ? c : strcmp(x->path, y->path);
}

int gallery_scan(GalleryList *l, const char *const *args, int nargs, int all, char *err, size_t errlen)
{
    memset(l, 0, sizeof *l);
    if (errlen)
        err[0] = '\0';
    for (int i = 0; i < nargs; i++) {
        struct stat st;
        int rc;
        if (stat(args[i], &st) == 0 && S_ISDIR(st.st_mode))
            rc = folder(l, args[i], all, err, errlen);
        else if (stat(args[i], &st) == 0)
            rc = add(l, args[i], &st, S_ISFIFO(st.st_mode) ? "a FIFO" : NULL);
        else
            rc = add(l, args[i], NULL, strerror(errno));
        if (rc) {
            if (!err[0])
                snprintf(err, errlen, "%s: out of memory", args[i]);
            gallery_list_free(l);
            return -1;
        }
    }
    if (l->n > 1)
        qsort(l->tile, (size_t)l->n, sizeof *l->tile, by_name);
    /* the names point into the paths, which moved with their tiles: no fix needed */
    return 0;
}

void gallery_list_free(GalleryList *l)
{
    for (int i = 0; i < l->n; i++) {
        free(l->tile[i].path);
        image_free(&l->tile[i].pic);
    }
    free(l->tile);
    memset(l, 0, sizeof *l);
}
