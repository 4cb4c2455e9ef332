/* watch.c: --watch, the files read again when they change on disk.
 *
 * inotify watches each file's folder, not the file: an exporter that
 * writes a temporary file and renames it over the model replaces the
 * inode a watch on the file would hold, and the rename shows in the
 * folder as the model's name moved to. A change is the name written and
 * closed, written to, created or moved to; changes within WATCH_SETTLE_MS
 * of each other are read once, after the last (a writer that pauses
 * longer mid-file gives a half file: the loader refuses it, the last
 * good model stays, and the close that ends the write reads it again).
 *
 * The viewer polls (every BUSY_TICK_MS): the descriptor is non-blocking
 * and its events are read until none is left. A file whose change is
 * due is read again through a load job (loadjob.c), whose part then
 * takes the old file's place (live.c: reload_file). Only a regular
 * file is read again: a FIFO (or a device, a folder) put in the model's
 * place is passed over with a note, never opened (a FIFO would wait for
 * a writer, and the changes after it would wait behind that load); the
 * watch goes on, and the next file there is read. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/inotify.h>
#include <unistd.h>

#include "clock.h"
#include "viewer_app.h"

#define WATCH_SETTLE_MS 100.0

typedef struct {
    char   base[256];       /* the file's name in its folder ("" not watched) */
    int    wd;              /* its folder's watch */
    double due;             /* when to read it again (0: no change pending) */
} Watched;

struct Watch {
    int      fd;
    Watched  f[MAX_FILES];
    int      n;
    uint32_t gen;           /* the scene's generation the files were set for */
    int      set;
};

Watch *watch_start(char *err, size_t errlen)
{
    Watch *w = calloc(1, sizeof *w);
    if (!w) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    w->fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (w->fd < 0) {
        snprintf(err, errlen, "--watch: %s", strerror(errno));
        free(w);
        return NULL;
    }
    return w;
}

void watch_free(Watch *w)
{
    if (!w)
        return;
    close(w->fd);       /* its watches go with it */
    free(w);
}

/* Watch path's folder for its name. */
static void watch_one(Watch *w, Watched *f, const char *path)
{
    /* a change pending for the same name stays pending */
    char was[sizeof f->base];
    memcpy(was, f->base, sizeof was);
    double due = f->due;
    f->base[0] = 0;
    f->due = 0;
    if (!strcmp(path, "-"))
        return;     /* standard input is read once */
    char dir[PATH_MAX];
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    const char *base = slash ? slash + 1 : path;
    if (!*base || strlen(base) >= sizeof f->base)
        return;
    f->wd = inotify_add_watch(w->fd, dir, IN_CLOSE_WRITE | IN_MOVED_TO | IN_CREATE | IN_MODIFY);
    if (f->wd >= 0) {
        snprintf(f->base, sizeof f->base, "%s", base);
        f->due = strcmp(was, f->base) ? 0 : due;
    }
}

void watch_files(Watch *w, const char *const *paths, int n)
{
    /* the same folder twice gives the same watch: only what is new is
     * added, and a folder no file is in any more just sends events no
     * name matches */
    w->n = n < MAX_FILES ? n : MAX_FILES;
    for (int i = 0; i < w->n; i++)
        watch_one(w, &w->f[i], paths[i]);
}

/* Every event waiting: a change of a watched name makes it due. */
static void drain(Watch *w, double now)
{
    char buf[4096] __attribute__((aligned(__alignof__(struct inotify_event))));
    for (;;) {
        ssize_t r = read(w->fd, buf, sizeof buf);
        if (r <= 0)
            return;     /* EAGAIN: none left */
        for (char *p = buf; p < buf + r;) {
            const struct inotify_event *ev = (const struct inotify_event *)p;
            for (int i = 0; ev->len && i < w->n; i++)
                if (w->f[i].base[0] && w->f[i].wd == ev->wd && !strcmp(w->f[i].base, ev->name))
                    w->f[i].due = now + WATCH_SETTLE_MS;
            p += sizeof *ev + ev->len;
        }
    }
}

int watch_due(Watch *w, double now)
{
    drain(w, now);
    for (int i = 0; i < w->n; i++)
        if (w->f[i].due > 0 && w->f[i].due <= now) {
            w->f[i].due = 0;
            return i;
        }
    return -1;
}

void watch_again(Watch *w, int i, double now)
{
    if (i >= 0 && i < w->n)
        w->f[i].due = now + WATCH_SETTLE_MS;
}

/* ==== The viewer's side ==== */

Reaction viewer_watch_poll(App *a)
{
    if (!a->watch)
        return RE_NONE;
    Scene *s = a->s;
    if (!a->watch_set || a->watch_gen != s->gen) {
        /* the files changed (O, X, E, a file read again): watch those */
        watch_files(a->watch, (const char *const *)a->live.files, a->live.nfiles);
        a->watch_set = 1;
        a->watch_gen = s->gen;
    }
    double now = now_ms();
    int f = watch_due(a->watch, now);
    if (f < 0 || a->sk.on)
        return RE_NONE;
    if (a->job) {
        watch_again(a->watch, f, now);      /* after the load under way */
        return RE_NONE;
    }
    if (f >= s->nmeshes || a->live.nfiles != s->nmeshes)
        return RE_NONE;
    char err[256];
    a->job = loadjob_reload(a->live.files[f], a->opt, err, sizeof err);
    if (!a->job) {
        /* the short name: a narrow bar would cut a path before the reason */
        const char *slash = strrchr(a->live.files[f], '/');
        viewer_note(a, "%s: %s; still watching", slash && slash[1] ? slash + 1 : a->live.files[f], err);
        return RE_DRAW;
    }
    a->reload = f;
    return RE_DRAW;
}
