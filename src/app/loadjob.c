/* loadjob.c: a file loaded on a thread of its own while the viewer keeps
 * drawing and taking keys (the O key). The thread parses the file and
 * builds its part of the scene (scene_build: normals, polygon lists),
 * the slow steps; the UI thread only joins the part to its scene
 * (scene_add), which copies arrays. The thread touches nothing but the
 * job: the viewer's scene is never read off the UI thread.
 *
 * A job the viewer no longer wants (it quits mid-load) is abandoned:
 * the thread is detached and frees the job itself when it ends, so
 * quitting never waits for a big file. */

#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "viewer.h"

enum { JOB_READING, JOB_BUILDING, JOB_DONE };

struct LoadJob {
    pthread_mutex_t mu;
    pthread_t    th;
    int          phase;         /* JOB_*, under mu */
    int          abandoned;     /* under mu: the thread frees the job */
    char         path[4096];
    MeshLoadOpts lo;
    MeshProgress prog;
    int          flip, points;
    uint64_t     size;          /* the file's size, 0 unknown */
    double       t0;            /* now_ms() at the start */
    /* the result, read after JOB_DONE */
    int          rc;
    char         err[512];
    Scene        part;
};

static void set_phase(LoadJob *j, int phase)
{
    pthread_mutex_lock(&j->mu);
    j->phase = phase;
    pthread_mutex_unlock(&j->mu);
}

static void job_free(LoadJob *j)
{
    scene_free(&j->part);
    pthread_mutex_destroy(&j->mu);
    free(j);
}

static void *job_main(void *arg)
{
    LoadJob *j = arg;
    Mesh *m = calloc(1, sizeof *m);
    j->rc = -1;
    if (!m) {
        snprintf(j->err, sizeof j->err, "out of memory");
    } else if (mesh_load_ex(m, j->path, &j->lo, j->err, sizeof j->err)) {
        free(m);
    } else {
        if (j->flip)
            mesh_flip_winding(m);
        if (j->points)
            mesh_as_points(m);
        set_phase(j, JOB_BUILDING);
        if (scene_build(&j->part, m, 1, j->err, sizeof j->err)) {
            mesh_free(m);
            free(m);
        } else {
            j->rc = 0;
        }
    }
    pthread_mutex_lock(&j->mu);
    j->phase = JOB_DONE;
    int gone = j->abandoned;
    pthread_mutex_unlock(&j->mu);
    if (gone)
        job_free(j);
    return NULL;
}

LoadJob *loadjob_start(const char *path, const Options *o, char *err, size_t errlen)
{
    LoadJob *j = calloc(1, sizeof *j);
    if (!j) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    if (snprintf(j->path, sizeof j->path, "%s", path) >= (int)sizeof j->path) {
        snprintf(err, errlen, "path too long");
        free(j);
        return NULL;
    }
    struct stat st;
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode))
        j->size = (uint64_t)st.st_size;
    j->lo.format = o->format;
    j->lo.strict = o->strict;
    j->lo.max_polys = o->max_polys;
    j->lo.quiet = 1;            /* curses owns the terminal: warnings go to the status bar */
    j->lo.progress = &j->prog;
    j->flip = o->flip;
    j->points = o->points;
    j->t0 = now_ms();
    pthread_mutex_init(&j->mu, NULL);
    if (pthread_create(&j->th, NULL, job_main, j)) {
        snprintf(err, errlen, "cannot start a thread to load it");
        pthread_mutex_destroy(&j->mu);
        free(j);
        return NULL;
    }
    return j;
}

int loadjob_done(LoadJob *j)
{
    pthread_mutex_lock(&j->mu);
    int done = j->phase == JOB_DONE;
    pthread_mutex_unlock(&j->mu);
    return done;
}

int loadjob_finish(LoadJob *j, Scene *part_out, char *err, size_t errlen)
{
    pthread_join(j->th, NULL);
    int rc = j->rc;
    if (rc)
        snprintf(err, errlen, "%s", j->err);
    else {
        *part_out = j->part;
        memset(&j->part, 0, sizeof j->part);
    }
    job_free(j);
    return rc;
}

void loadjob_abandon(LoadJob *j)
{
    pthread_mutex_lock(&j->mu);
    int done = j->phase == JOB_DONE;
    j->abandoned = !done;
    pthread_mutex_unlock(&j->mu);
    if (done) {
        pthread_join(j->th, NULL);
        job_free(j);
    } else {
        pthread_detach(j->th);
    }
}

const char *loadjob_path(const LoadJob *j)
{
    return j->path;
}

/* "12.3 MB" */
static void size_text(uint64_t b, char *buf, size_t len)
{
    if (b >= 1000000)
        snprintf(buf, len, "%.1f MB", (double)b / 1e6);
    else
        snprintf(buf, len, "%.0f kB", (double)b / 1e3);
}

void loadjob_status(LoadJob *j, char *buf, size_t len)
{
    static const char spin[4] = { '|', '/', '-', '\\' };
    pthread_mutex_lock(&j->mu);
    int phase = j->phase;
    pthread_mutex_unlock(&j->mu);
    double s = (now_ms() - j->t0) / 1000.0;
    const char *slash = strrchr(j->path, '/');
    const char *name = slash && slash[1] ? slash + 1 : j->path;
    uint64_t done = __atomic_load_n(&j->prog.done, __ATOMIC_RELAXED);
    uint64_t total = __atomic_load_n(&j->prog.total, __ATOMIC_RELAXED);
    char sz[32];
    size_text(j->size, sz, sizeof sz);
    if (phase != JOB_READING)
        snprintf(buf, len, "building %s %c %.1fs", name, spin[(int)(s * 8) & 3], s);
    else if (total > 0 && done > 0)
        snprintf(buf, len, "loading %s %d%%", name, (int)(100.0 * (double)done / (double)total));
    else
        snprintf(buf, len, "loading %s %c %.1fs %s", name, spin[(int)(s * 8) & 3], s, sz);
}
