/* loadjob.c: a file loaded on a thread of its own while the viewer keeps
 * drawing and taking keys (the O key). The thread parses the file and
 * builds its part of the scene (scene_build: normals, polygon lists),
 * the slow steps; the UI thread only joins the part to its scene
 * (scene_add), which copies arrays. The thread touches nothing but the
 * job: the viewer's scene is never read off the UI thread.
 *
 * A job the viewer no longer wants (Esc cancels it, or the viewer quits
 * mid-load) is abandoned: the thread is detached and frees the job
 * itself when it ends, so neither waits for a big file; it skips what
 * is left to do once it sees the job is cancelled.
 *
 * What the prompt names must be a file: a FIFO is read here, its writer
 * waited for in poll(2) beside the cancel pipe (opening it as the loader
 * does would wait in open(2) for a writer that may never come, where
 * nothing can cancel it); standard input (the keyboard here) and devices
 * (/dev/urandom, /dev/zero, a terminal) are refused at once. A file read
 * again (--watch) must be a regular file: a FIFO put in its place is
 * refused too, since waiting for its writer would hold the watch. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "clock.h"
#include "thread.h"
#include "viewer_app.h"

/* A FIFO's content is held in memory for the parser: at most this much. */
#define FIFO_MAX ((size_t)1 << 30)

enum { JOB_WAITING, JOB_READING, JOB_BUILDING, JOB_DONE };

struct LoadJob {
    pthread_mutex_t mu;
    pthread_t    th;
    int          phase;         /* JOB_*, under mu */
    int          abandoned;     /* under mu: the thread frees the job */
    int          cancelled;     /* under mu: the viewer no longer wants it */
    int          stop;          /* the same, stored atomically for the loader
                                   (MeshLoadOpts.cancel): it stops reading */
    int          cancel[2];     /* a byte in cancel[1] wakes a thread waiting on a FIFO */
    int          fifo;          /* the path is a FIFO: read here */
    char         path[4096];
    MeshLoadOpts lo;
    SandboxOpts  so;            /* the load runs in a child (sandbox.h): Esc kills it */
    MeshProgress prog;
    Options      o;             /* the command line's (app_after_load) */
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

static int cancelled(LoadJob *j)
{
    pthread_mutex_lock(&j->mu);
    int c = j->cancelled;
    pthread_mutex_unlock(&j->mu);
    return c;
}

static void job_free(LoadJob *j)
{
    scene_free(&j->part);
    for (int i = 0; i < 2; i++)
        if (j->cancel[i] >= 0)
            close(j->cancel[i]);
    pthread_mutex_destroy(&j->mu);
    free(j);
}

/* ==== A FIFO ==== */

/* Room for more of the stream: 0, or -1 with the message. */
static int grow(char **data, size_t *cap, size_t len, char *err, size_t errlen)
{
    if (len < *cap)
        return 0;
    if (*cap >= FIFO_MAX) {
        snprintf(err, errlen, "more than %zu MB from a FIFO", FIFO_MAX >> 20);
        return -1;
    }
    size_t nc = *cap ? *cap * 2 : (size_t)1 << 16;
    char *nd = realloc(*data, nc);
    if (!nd) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    *data = nd;
    *cap = nc;
    return 0;
}

/* One read of what the FIFO has: 1 more may come, 0 its end, -1 an
 * error (message in j->err). */
static int fifo_read(LoadJob *j, int fd, char **data, size_t *cap, size_t *len)
{
    if (grow(data, cap, *len, j->err, sizeof j->err))
        return -1;
    ssize_t r = read(fd, *data + *len, *cap - *len);
    if (r < 0 && (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK))
        return 1;
    if (r < 0) {
        snprintf(j->err, sizeof j->err, "cannot read: %s", strerror(errno));
        return -1;
    }
    if (r == 0)
        return 0;
    if (*len == 0)
        set_phase(j, JOB_READING);      /* a writer came */
    *len += (size_t)r;
    __atomic_store_n(&j->prog.done, (uint64_t)*len, __ATOMIC_RELAXED);
    return 1;
}

/* The whole stream of the FIFO at fd into *data_out (the caller frees),
 * waiting for its writer as long as it takes, or until cancelled.
 * Returns 0, or -1 with j->err. */
static int fifo_slurp(LoadJob *j, int fd, char **data_out, size_t *len_out)
{
    char *data = NULL;
    size_t cap = 0, len = 0;
    int more = 1;
    while (more > 0) {
        /* Linux reports no hang-up on a FIFO opened before any writer:
         * poll waits for one to come (and write or close) */
        struct pollfd pf[2] = { { .fd = fd, .events = POLLIN }, { .fd = j->cancel[0], .events = POLLIN } };
        if (poll(pf, 2, -1) < 0 && errno != EINTR) {
            snprintf(j->err, sizeof j->err, "cannot wait for the FIFO: %s", strerror(errno));
            more = -1;
        } else if (pf[1].revents || cancelled(j)) {
            snprintf(j->err, sizeof j->err, "cancelled");
            more = -1;
        } else if (pf[0].revents) {
            more = fifo_read(j, fd, &data, &cap, &len);
        }
    }
    if (more < 0) {
        free(data);
        return -1;
    }
    *data_out = data;
    *len_out = len;
    return 0;
}

/* Parse the FIFO at j->path into m: 0, or -1 with j->err. The loader is
 * given the bytes and the path (its extension picks the format, its
 * folder holds what the model names). */
static int fifo_load(LoadJob *j, Mesh *m)
{
    int fd = open(j->path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);     /* never waits for a writer */
    if (fd < 0) {
        snprintf(j->err, sizeof j->err, "%.300s: cannot open: %s", j->path, strerror(errno));
        return -1;
    }
    char *data;
    size_t len;
    int rc = fifo_slurp(j, fd, &data, &len);
    close(fd);
    if (rc) {
        char why[160];
        snprintf(why, sizeof why, "%.150s", j->err);
        snprintf(j->err, sizeof j->err, "%.300s: %s", j->path, why);
        return -1;
    }
    rc = sandbox_parse_buffer(m, j->path, &j->lo, &j->so, data, len, j->err, sizeof j->err);
    free(data);
    return rc;
}

/* ==== The thread ==== */

static void *job_main(void *arg)
{
    LoadJob *j = arg;
    Mesh *m = calloc(1, sizeof *m);
    j->rc = -1;
    if (!m) {
        snprintf(j->err, sizeof j->err, "out of memory");
    } else if (j->fifo ? fifo_load(j, m) : sandbox_load(m, j->path, &j->lo, &j->so, j->err, sizeof j->err)) {
        free(m);
    } else if (cancelled(j)) {
        mesh_free(m);           /* nobody wants it: no scene built */
        free(m);
    } else {
        app_after_load(&j->o, m);
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

static const char *kind_of(mode_t m)
{
    return S_ISFIFO(m) ? "a FIFO" : S_ISCHR(m) ? "a character device" : S_ISBLK(m) ? "a block device"
         : S_ISSOCK(m) ? "a socket" : S_ISDIR(m) ? "a folder" : "a special file";
}

/* What the prompt named, looked at without opening it (opening a FIFO
 * or a device can wait, or do things): 0 to go on (a file, a FIFO, or
 * nothing there: the loader's message says so), -1 with a reason. A
 * reload (regular) takes a regular file only, and nothing there is
 * said here. */
static int loadable(const char *path, int regular, struct stat *st, char *err, size_t errlen)
{
    if (!strcmp(path, "-")) {
        /* the loader's name for standard input, which is the keyboard here
         * (or a stream read at start) */
        snprintf(err, errlen, "standard input is read on the command line only");
        return -1;
    }
    if (stat(path, st) != 0) {
        if (!regular)
            return 0;
        snprintf(err, errlen, "cannot open: %s", strerror(errno));
        return -1;
    }
    if (S_ISREG(st->st_mode) || (!regular && (S_ISDIR(st->st_mode) || S_ISFIFO(st->st_mode))))
        return 0;
    snprintf(err, errlen, "not a %sfile (%s)", regular ? "regular " : "", kind_of(st->st_mode));
    return -1;
}

/* Start the thread with every signal blocked (thread.h): a signal for
 * the process (Ctrl-Z, a resize) goes to the viewer's thread, whose
 * handlers touch the terminal. */
static int start_thread(LoadJob *j)
{
    return thread_start(&j->th, job_main, j);
}

static LoadJob *job_start(const char *path, const Options *o, int regular, char *err, size_t errlen)
{
    struct stat st;
    if (loadable(path, regular, &st, err, errlen))
        return NULL;
    LoadJob *j = calloc(1, sizeof *j);
    if (!j) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    j->cancel[0] = j->cancel[1] = -1;
    if (snprintf(j->path, sizeof j->path, "%s", path) >= (int)sizeof j->path) {
        snprintf(err, errlen, "path too long");
        free(j);
        return NULL;
    }
    j->fifo = S_ISFIFO(st.st_mode);
    if (j->fifo && pipe(j->cancel) != 0) {
        snprintf(err, errlen, "cannot make a pipe: %s", strerror(errno));
        free(j);
        return NULL;
    }
    if (j->fifo) {
        fcntl(j->cancel[1], F_SETFL, O_NONBLOCK);
        fcntl(j->cancel[0], F_SETFD, FD_CLOEXEC);
        fcntl(j->cancel[1], F_SETFD, FD_CLOEXEC);
    }
    j->phase = j->fifo ? JOB_WAITING : JOB_READING;
    if (S_ISREG(st.st_mode))
        j->size = (uint64_t)st.st_size;
    j->o = *o;
    j->lo = app_load_opts(o);   /* the viewer's: big images after the file shows (texjob.c) */
    j->so = app_sandbox_opts(o);
    j->lo.quiet = 1;            /* curses owns the terminal: warnings go to the status bar */
    j->lo.progress = &j->prog;
    j->lo.cancel = &j->stop;
    j->lo.regular_only = regular;   /* replaced since the look above: refused, not waited on */
    j->t0 = now_ms();
    pthread_mutex_init(&j->mu, NULL);
    if (start_thread(j)) {
        snprintf(err, errlen, "cannot start a thread to load it");
        j->part = (Scene){ 0 };
        job_free(j);
        return NULL;
    }
    return j;
}

LoadJob *loadjob_start(const char *path, const Options *o, char *err, size_t errlen)
{
    return job_start(path, o, 0, err, errlen);
}

LoadJob *loadjob_reload(const char *path, const Options *o, char *err, size_t errlen)
{
    return job_start(path, o, 1, err, errlen);
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
    /* read before the lock is released: an abandoned job's thread frees
     * the job as soon as it sees the flag, so j->th may be gone by the
     * time it is detached below */
    pthread_t th = j->th;
    pthread_mutex_lock(&j->mu);
    int done = j->phase == JOB_DONE;
    j->abandoned = !done;
    j->cancelled = 1;
    __atomic_store_n(&j->stop, 1, __ATOMIC_RELAXED);
    if (!done && j->cancel[1] >= 0) {
        /* under the lock: once it is released the thread may free the job */
        ssize_t w = write(j->cancel[1], "c", 1);
        (void)w;                /* the pipe is empty: the byte fits */
    }
    pthread_mutex_unlock(&j->mu);
    if (done) {
        pthread_join(th, NULL);
        job_free(j);
    } else {
        pthread_detach(th);
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
    /* a FIFO has no size: what came so far */
    size_text(j->fifo ? done : j->size, sz, sizeof sz);
    if (phase == JOB_WAITING)
        snprintf(buf, len, "waiting for a writer to %s %c %.1fs (Esc cancels)", name, spin[(int)(s * 8) & 3], s);
    else if (phase != JOB_READING)
        snprintf(buf, len, "building %s %c %.1fs", name, spin[(int)(s * 8) & 3], s);
    else if (total > 0 && done > 0 && !j->fifo)
        snprintf(buf, len, "loading %s %d%%", name, (int)(100.0 * (double)done / (double)total));
    else
        snprintf(buf, len, "loading %s %c %.1fs %s", name, spin[(int)(s * 8) & 3], s, sz);
}
