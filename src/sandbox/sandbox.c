/* sandbox.c: a load, or a texture's decode, in a child process
 * (sandbox.h): the parent's side. It makes a memfd for the result, two
 * pipes to hear from the child and to answer it, a page for progress,
 * and starts the child: from the fork server (server.c), else by a fork
 * of its own. It waits for the child's word, polling the pipe the child
 * holds open, so that a cancel (the viewer's Esc) can kill it, progress
 * can be copied out, and each file the model names can be counted into
 * the child's memory bound as the child opens it (budget.c); then reads
 * the result back, checking it (wire.c). The child's side is child.c. */

#define _GNU_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clock.h"
#include "meshprefix.h"
#include "sandbox_internal.h"
#include "sysmem.h"

/* How often the parent looks at the cancel flag and copies progress
 * while the child works: quick enough for Esc to feel immediate. */
#define POLL_MS 50
/* Files counted into one load's bound; past them, no more is granted. */
#define MAX_REFS 256

typedef struct {
    dev_t dev;
    ino_t ino;
    int   image;
} Seen;

typedef struct {
    Req           rq;           /* what the child does */
    const char   *name;         /* what messages call it */
    const MeshLoadOpts *lo;     /* the caller's: cancel, progress */
    MeshProgress *progress;     /* the child's, mapped here; NULL: none */
    int           fixed;        /* --max-memory: the bound is not raised */
    int           native;       /* zview's own loaders read it (budget.c) */
    uint64_t      input;        /* bytes of input counted */
    uint64_t      allowance;    /* what they may take */
    int           nseen;
    Seen          seen[MAX_REFS];
    int           alive, go;    /* the parent's ends */
    ChildErr      cerr;         /* the child's standard error (childerr.c): -1 when quiet */
} Job;

int sandbox_available(void)
{
    /* EINVAL: a kernel built without seccomp */
    return prctl(PR_GET_SECCOMP, 0, 0, 0, 0) >= 0;
}

static void kill_child(const Child *c)
{
    if (c->pidfd < 0 || syscall(SYS_pidfd_send_signal, c->pidfd, SIGKILL, NULL, 0) != 0)
        kill(c->pid, SIGKILL);
}

/* Wait for the child to end, reading its standard error meanwhile: a
 * report written as it dies (a sanitizer's) must not fill the pipe and
 * hold it up. */
static int reap(Job *j, Child *c, int *status, struct rusage *ru)
{
    for (;;) {
        if (j->cerr.fd < 0) {
            if (c->status >= 0)
                return sandbox_server_reap(c, status, ru);
            while (wait4(c->pid, status, 0, ru) < 0)
                if (errno != EINTR)
                    return -1;
            return 0;
        }
        if (c->status < 0) {
            pid_t r = wait4(c->pid, status, WNOHANG, ru);
            if (r == c->pid)
                return 0;
            if (r < 0 && errno != EINTR)
                return -1;
        }
        struct pollfd pf[2] = { { .fd = j->cerr.fd, .events = POLLIN }, { .fd = c->status, .events = POLLIN } };
        int n = poll(pf, c->status >= 0 ? 2 : 1, POLL_MS);
        if (n > 0 && pf[0].revents)
            childerr_read(&j->cerr);    /* at its end it closes: the loop above then waits */
        if (c->status >= 0 && n > 0 && pf[1].revents)
            return sandbox_server_reap(c, status, ru);
    }
}

/* ==== The memory bound ==== */

/* A bound as --max-memory takes it (M and G of 2^20 and 2^30 bytes). */
static void say_bound(uint64_t b, char *buf, size_t len)
{
    if (b >= (uint64_t)1 << 30)
        snprintf(buf, len, "%.1f GB", (double)b / (double)(1 << 30));
    else
        snprintf(buf, len, "%.0f MB", (double)b / (double)(1 << 20));
}

/* After a failure about memory, the bound and how to raise it: the
 * message says memory, or the child died (a signal, a sanitizer's
 * exit) having come near its bound. */
static void bound_note(const Job *j, int died, long maxrss_kb, char *err, size_t errlen)
{
    if (!strstr(err, "memory") && !strstr(err, "available") &&
        !(died && (uint64_t)maxrss_kb * 1024 >= j->rq.budget / 2))
        return;
    char b[32], in[32], note[160];
    say_bound(j->rq.budget, b, sizeof b);
    if (j->fixed) {
        snprintf(note, sizeof note, " (the sandbox's bound: %s, --max-memory)", b);
    } else {
        if (j->input < 10000)
            snprintf(in, sizeof in, "%u bytes", (unsigned)j->input);
        else
            sysmem_format(j->input, in, sizeof in);
        snprintf(note, sizeof note, " (the sandbox's bound: %s for %s; --max-memory raises it)", b, in);
    }
    size_t n = strlen(err);
    snprintf(err + n, errlen - n, "%s", note);
}

/* A file the child opened, counted once: its bound grows by what the
 * file may take, and its soft limits with it (prlimit: the child may not
 * change its own). The parent opens the file as the loader does, beneath
 * the model's folder, and trusts nothing else the child says. */
static void count_ref(Job *j, pid_t pid, const char *path, int image)
{
    const char *model = j->rq.path[0] && strcmp(j->rq.path, "-") ? j->rq.path : NULL;
    char why[160];
    struct stat st;
    int fd = mesh_ref_open(model, path, why, sizeof why);
    if (fd < 0)
        return;
    int ok = fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    close(fd);
    for (int i = 0; ok && i < j->nseen; i++)
        if (j->seen[i].dev == st.st_dev && j->seen[i].ino == st.st_ino && j->seen[i].image == image)
            ok = 0;
    if (!ok || j->nseen == MAX_REFS)
        return;
    j->seen[j->nseen++] = (Seen){ st.st_dev, st.st_ino, image };
    uint64_t size = (uint64_t)st.st_size;
    j->input += size;
    j->allowance += image ? sandbox_image_allowance(size) : sandbox_input_allowance(size, j->native);
    uint64_t now = sandbox_budget_of(j->allowance);
    if (now > j->rq.ceiling)
        now = j->rq.ceiling;
    if (now <= j->rq.budget)
        return;
    uint64_t more = now - j->rq.budget;
    j->rq.budget = now;
    static const int res[2] = { RLIMIT_AS, RLIMIT_DATA };
    for (int i = 0; i < 2; i++) {
        struct rlimit rl;
        if (prlimit(pid, res[i], NULL, &rl) != 0 || rl.rlim_cur == RLIM_INFINITY)
            continue;
        rl.rlim_cur = rl.rlim_max - rl.rlim_cur > more ? rl.rlim_cur + more : rl.rlim_max;
        prlimit(pid, res[i], &rl, NULL);
    }
}

static int read_all(int fd, void *buf, size_t len)
{
    for (size_t got = 0; got < len;) {
        ssize_t r = read(fd, (char *)buf + got, len - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return -1;
        got += (size_t)r;
    }
    return 0;
}

/* The child names a file ('f' read already): count it, answer. 0, or
 * -1 when the message is not one (the child is then killed). */
static int ref_message(Job *j, const Child *c)
{
    unsigned char h[3];
    char path[REF_PATH_MAX + 1];
    if (j->rq.kind != REQ_LOAD || read_all(j->alive, h, sizeof h) != 0)
        return -1;
    size_t n = (size_t)h[1] | (size_t)h[2] << 8;
    if (n == 0 || n > REF_PATH_MAX || read_all(j->alive, path, n) != 0)
        return -1;
    path[n] = '\0';
    if (!j->fixed && strlen(path) == n)
        count_ref(j, c->pid, path, h[0] != 0);
    return write(j->go, "k", 1) == 1 ? 0 : -1;
}

/* ==== Waiting ==== */

enum { CHILD_GONE, CHILD_CANCELLED, CHILD_READY, CHILD_BAD };

static void copy_progress(const Job *j)
{
    if (!j->lo->progress || !j->progress)
        return;
    __atomic_store_n(&j->lo->progress->done, __atomic_load_n(&j->progress->done, __ATOMIC_RELAXED),
                     __ATOMIC_RELAXED);
    __atomic_store_n(&j->lo->progress->total, __atomic_load_n(&j->progress->total, __ATOMIC_RELAXED),
                     __ATOMIC_RELAXED);
}

/* Wait for the child's word, killing it on cancel, copying progress,
 * counting the files it names: ready (its result waits to be read),
 * gone (it ended: crashed, or killed by a limit or the filter),
 * cancelled, or bad (it broke the protocol, and is killed). */
static int wait_child(Job *j, const Child *c)
{
    int cancelled = 0;
    for (;;) {
        struct pollfd pf[2] = { { .fd = j->alive, .events = POLLIN }, { .fd = j->cerr.fd, .events = POLLIN } };
        int n = poll(pf, j->cerr.fd >= 0 ? 2 : 1, j->lo->cancel || j->lo->progress ? POLL_MS : -1);
        if (n > 0 && j->cerr.fd >= 0 && pf[1].revents) {
            childerr_read(&j->cerr);
            if (!pf[0].revents)
                continue;
        }
        copy_progress(j);
        if (!cancelled && j->lo->cancel && __atomic_load_n(j->lo->cancel, __ATOMIC_RELAXED)) {
            kill_child(c);
            cancelled = 1;
        }
        if (n > 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) {
            char w = 0;
            if (cancelled || read(j->alive, &w, 1) != 1)
                return cancelled ? CHILD_CANCELLED : CHILD_GONE;
            if (w == 'r')
                return CHILD_READY;
            if (w != 'f' || ref_message(j, c) != 0) {
                kill_child(c);
                return CHILD_BAD;
            }
        }
    }
}

/* The message for a child that did not finish: what ended it. */
static void died(const Job *j, int state, int status, const struct rusage *ru, char *err, size_t errlen)
{
    double cpu = (double)ru->ru_utime.tv_sec + (double)ru->ru_stime.tv_sec +
                 ((double)ru->ru_utime.tv_usec + (double)ru->ru_stime.tv_usec) / 1e6;
    int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    const char *nm = j->name;
    if (state == CHILD_CANCELLED)
        snprintf(err, errlen, "%s: cancelled", nm);
    else if (state == CHILD_BAD)
        snprintf(err, errlen, "%s: the sandboxed loader broke the sandbox's protocol and was stopped", nm);
    else if (sig == SIGSYS)
        snprintf(err, errlen, "%s: the loader tried something the sandbox forbids (writing a file, running a "
                 "program, a network connection, ...) and was stopped", nm);
    else if (sig == SIGXCPU || (sig == SIGKILL && cpu >= j->rq.cpu))
        snprintf(err, errlen, "%s: the load took more than %u s of CPU time and was stopped", nm, j->rq.cpu);
    else if (sig == SIGKILL)
        snprintf(err, errlen, "%s: the loader was killed (out of memory?)", nm);
    else if (sig == SIGABRT)
        snprintf(err, errlen, "%s: the loader gave up (aborted: out of memory, or a malformed file)", nm);
    else if (sig)
        snprintf(err, errlen, "%s: the loader crashed (%s) in the sandbox: a malformed file", nm, strsignal(sig));
    else
        snprintf(err, errlen, "%s: the loader failed in the sandbox (exit status %d)", nm, WEXITSTATUS(status));
    if (state != CHILD_CANCELLED && state != CHILD_BAD && sig != SIGSYS)
        bound_note(j, 1, ru->ru_maxrss, err, errlen);
}

/* Read the child's result: from its memory (pid), else from the memfd. */
static int collect(const Job *j, pid_t pid, Mesh *m, char *err, size_t errlen)
{
    struct stat st;
    int memfd = j->rq.fd[RQ_RESULT];
    if (fstat(memfd, &st) != 0 || st.st_size <= 0) {
        snprintf(err, errlen, "%s: the sandboxed loader returned nothing", j->name);
        return -1;
    }
    int rc = -1;
    char why[400];
    if (sandbox_wire_read(memfd, (size_t)st.st_size, pid, m, &rc, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s: %s", j->name, why);
        return -2;
    }
    if (rc) {
        snprintf(err, errlen, "%s", why);
        bound_note(j, 0, 0, err, errlen);
    }
    return rc;
}

/* The child is ready: its result, read from its memory, or (when that
 * is not allowed) from the memfd once it has written it there. */
static void close_fd(int *fd)
{
    if (*fd >= 0)
        close(*fd);
    *fd = -1;
}

static int finish(Job *j, Child *c, Mesh *m, char *err, size_t errlen)
{
    int rc = collect(j, c->pid, m, err, errlen), status = 0;
    struct rusage ru = { 0 };
    if (rc == -2 && write(j->go, "w", 1) == 1) {
        close_fd(&j->go);
        if (reap(j, c, &status, &ru) == 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0)
            rc = collect(j, 0, m, err, errlen);
        else
            died(j, CHILD_GONE, status, &ru, err, errlen);
        return rc < 0 ? -1 : rc;
    }
    close_fd(&j->go);
    reap(j, c, &status, &ru);
    return rc < 0 ? -1 : rc;
}

/* ==== Starting ==== */

/* A memfd holding len bytes of data, sealed, or -1. */
static int bytes_fd(const void *data, size_t len)
{
    int fd = memfd_create("zview-bytes", MFD_CLOEXEC | MFD_ALLOW_SEALING);
    for (size_t put = 0; fd >= 0 && put < len;) {
        ssize_t w = write(fd, (const char *)data + put, len - put);
        if (w <= 0) {
            close(fd);
            return -1;
        }
        put += (size_t)w;
    }
    if (fd >= 0)
        fcntl(fd, F_ADD_SEALS, F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_WRITE | F_SEAL_SEAL);
    return fd;
}

/* The page the child writes its progress on, mapped here too. */
static int progress_fd(Job *j)
{
    int fd = memfd_create("zview-progress", MFD_CLOEXEC | MFD_ALLOW_SEALING);
    if (fd < 0 || ftruncate(fd, sizeof *j->progress) != 0 ||
        fcntl(fd, F_ADD_SEALS, F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_SEAL) != 0) {
        if (fd >= 0)
            close(fd);
        return -1;
    }
    void *p = mmap(NULL, sizeof *j->progress, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    j->progress = p == MAP_FAILED ? NULL : p;
    return fd;
}

/* The child, from the server, else forked here. */
static int start(Job *j, const SandboxServer *server, Child *c)
{
    *c = (Child){ .pid = -1, .pidfd = -1, .status = -1 };
    if (server && server->pid > 0 && sandbox_server_spawn(server, &j->rq, c) == 0)
        return 0;
    c->pid = fork();
    if (c->pid == 0)
        sandbox_child_main(&j->rq, NULL);  /* it compiles its filter */
    return c->pid > 0 ? 0 : -1;
}

static int run(Job *j, const SandboxServer *server, const void *data, size_t len, Mesh *m, char *err, size_t errlen)
{
    double t0 = now_ms();
    int alive[2] = { -1, -1 }, go[2] = { -1, -1 }, *fd = j->rq.fd;
    for (int i = 0; i < RQ_NFD; i++)
        fd[i] = -1;
    fd[RQ_RESULT] = memfd_create("zview-load", MFD_CLOEXEC);
    if (data)
        fd[RQ_DATA] = bytes_fd(data, len);
    if (j->lo->progress)
        fd[RQ_PROGRESS] = progress_fd(j);
    if (j->lo->prefix)
        fd[RQ_PREFIX] = mesh_prefix_fd(j->lo->prefix, &j->rq.prefix_bytes);
    /* the child's standard error through a pipe here, which passes
     * zview's lines on made safe; a quiet load's goes nowhere (child.c) */
    j->cerr.fd = -1;
    if (!j->rq.quiet)
        childerr_open(&j->cerr, &fd[RQ_STDERR]);
    int ok = fd[RQ_RESULT] >= 0 && (!data || fd[RQ_DATA] >= 0) && pipe2(alive, O_CLOEXEC) == 0 &&
             pipe2(go, O_CLOEXEC) == 0;
    fd[RQ_ALIVE] = alive[1];
    fd[RQ_GO] = go[0];
    j->alive = alive[0];
    j->go = go[1];
    Child c;
    if (ok)
        ok = start(j, server, &c) == 0;
    if (!ok)
        snprintf(err, errlen, "%s: cannot start the sandbox: %s", j->name, strerror(errno));
    /* the child's ends are the child's (the prefix's is the caller's) */
    fd[RQ_PREFIX] = -1;
    for (int i = RQ_ALIVE; i < RQ_NFD; i++)
        close_fd(&fd[i]);
    int rc = -1;
    if (ok) {
        int state = wait_child(j, &c);
        if (state == CHILD_READY) {
            rc = finish(j, &c, m, err, errlen);
        } else {
            int status = 0;
            struct rusage ru = { 0 };
            close_fd(&j->go);
            reap(j, &c, &status, &ru);
            died(j, state, status, &ru, err, errlen);
        }
    }
    if (rc == 0) {
        m->info.load_ms = now_ms() - t0;    /* the sandbox's cost included */
        m->info.sandboxed = 1;
        m->info.mem_bound = j->rq.budget;
        if (m->info.landlock < -4095 || m->info.landlock > 99)
            m->info.landlock = 0;           /* (the child's word, for --info only) */
    }
    childerr_close(&j->cerr);
    close_fd(&j->go);
    close_fd(&j->alive);
    close_fd(&fd[RQ_RESULT]);
    if (j->progress)
        munmap(j->progress, sizeof *j->progress);
    return rc;
}

/* The job's request from the options: the bound is --max-memory, else
 * what the input may take (budget.c), never above what the machine has. */
static Job *make_job(const char *name, const char *path, const MeshLoadOpts *lo, const SandboxOpts *so,
                     uint64_t input, int native)
{
    Job *j = calloc(1, sizeof *j);
    if (!j)
        return NULL;
    Req *r = &j->rq;
    j->name = name;
    j->lo = lo;
    snprintf(r->path, sizeof r->path, "%s", path ? path : "");
    if (lo->format) {
        r->has_format = 1;
        snprintf(r->format, sizeof r->format, "%s", lo->format);
    }
    r->strict = lo->strict;
    r->quiet = lo->quiet;
    r->tex_defer_side = lo->tex_defer_side;
    r->no_textures = lo->no_textures;
    r->threads = lo->threads;
    r->max_polys = lo->max_polys;
    r->piece_bytes = lo->piece_bytes;
    r->tessellation = lo->tessellation;
    r->cpu = so && so->cpu_seconds ? so->cpu_seconds : SANDBOX_CPU_SECONDS;
    uint64_t fixed = so && so->max_memory ? so->max_memory : lo->max_bytes;
    /* the loaders' own estimates judge against the bound and refuse
     * first, with a better message; unset, they ask the machine, which
     * in the child is its limits, raised as files are counted */
    r->max_bytes = fixed;
    j->fixed = fixed != 0;
    j->native = native;
    j->input = input;
    j->allowance = native < 0 ? sandbox_image_allowance(input) : sandbox_input_allowance(input, native);
    r->ceiling = fixed ? fixed : sandbox_ceiling();
    r->budget = fixed ? fixed : sandbox_budget_of(j->allowance);
    if (r->budget > r->ceiling)
        r->budget = r->ceiling;
    r->on_ref = !j->fixed;
    return j;
}

static int load(Mesh *m, const char *path, const MeshLoadOpts *lo, const SandboxOpts *so, const void *data,
                size_t len, char *err, size_t errlen)
{
    MeshLoadOpts def = { 0 };
    if (!lo)
        lo = &def;
    int off = (so && so->off) || !sandbox_available();
    if (off)
        return data ? mesh_parse_buffer_ex(m, path, lo, data, len, err, errlen)
                    : mesh_load_ex(m, path, lo, err, errlen);
    memset(m, 0, sizeof *m);
    /* the input's size: a pipe's is not known before it is read (its
     * bound is the floor; a bigger stream is refused naming it) */
    struct stat st;
    int known = path && (strcmp(path, "-") ? stat(path, &st) : fstat(STDIN_FILENO, &st)) == 0 && S_ISREG(st.st_mode);
    uint64_t input = data ? len : known ? (uint64_t)st.st_size : 0;
    const char *name = !path ? "(input)" : strcmp(path, "-") ? path : "stdin";
    Job *j = make_job(name, path, lo, so, input, mesh_format_is_native(path, lo->format));
    if (!j) {
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    if (known && !data)         /* the model's file is counted: a library opening it again is not */
        j->seen[j->nseen++] = (Seen){ st.st_dev, st.st_ino, 0 };
    j->rq.kind = REQ_LOAD;
    if (data)
        j->rq.data_len = len;
    int rc = run(j, so ? &so->server : NULL, data, len, m, err, errlen);
    free(j);
    return rc;
}

int sandbox_load(Mesh *m, const char *path, const MeshLoadOpts *lo, const SandboxOpts *so, char *err,
                 size_t errlen)
{
    return load(m, path, lo, so, NULL, 0, err, errlen);
}

int sandbox_parse_buffer(Mesh *m, const char *path, const MeshLoadOpts *lo, const SandboxOpts *so,
                         const void *data, size_t len, char *err, size_t errlen)
{
    return load(m, path, lo, so, data ? data : "", len, err, errlen);
}

int sandbox_texture_decode(const MeshTexture *t, const SandboxOpts *so, const int *cancel, Texture *out,
                           int *halved_out, char *err, size_t errlen)
{
    uint64_t max = so ? so->max_memory : 0;
    /* no bytes: nothing is decoded (a pending path opens nothing) */
    if ((so && so->off) || !sandbox_available() || !t->data)
        return mesh_texture_decode(t, max, out, halved_out, err, errlen);
    memset(out, 0, sizeof *out);
    *halved_out = 0;
    /* quiet: the viewer decodes these under curses; what went wrong
     * comes back as the message */
    MeshLoadOpts lo = { .cancel = cancel, .max_bytes = max, .quiet = 1 };
    Job *j = make_job(t->name, t->name, &lo, so, t->len, -1);
    if (!j) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    j->rq.kind = REQ_TEXTURE;
    j->rq.data_len = t->len;
    j->rq.wrap_u = t->img.wrap_u;
    j->rq.wrap_v = t->img.wrap_v;
    j->rq.on_ref = 0;
    Mesh m;
    memset(&m, 0, sizeof m);
    int rc = run(j, so ? &so->server : NULL, t->data, t->len, &m, err, errlen);
    if (rc == 0 && m.ntex == 1 && m.tex[0].state == MTEX_OK && m.tex[0].img.rgba) {
        *out = m.tex[0].img;
        *halved_out = m.tex[0].halved;
        memset(&m.tex[0].img, 0, sizeof m.tex[0].img);
    } else if (rc == 0) {
        snprintf(err, errlen, "the sandboxed decoder returned no image");
        rc = -1;
    }
    if (rc == 0)
        mesh_free(&m);
    /* the messages of a child that died name the texture: the caller
     * names it itself */
    size_t n = strlen(t->name);
    if (rc && strncmp(err, t->name, n) == 0 && err[n] == ':' && err[n + 1] == ' ')
        memmove(err, err + n + 2, strlen(err + n + 2) + 1);
    free(j);
    return rc;
}

void sandbox_describe(const MeshInfo *in, int no_sandbox, char *buf, size_t len)
{
    if (!in->sandboxed) {
        snprintf(buf, len, "%s", no_sandbox ? "none (--no-sandbox)" : "none (this system has no seccomp filters)");
        return;
    }
    char ll[64], mem[32];
    sandbox_landlock_say(in->landlock, ll, sizeof ll);
    say_bound(in->mem_bound, mem, sizeof mem);
    snprintf(buf, len, "seccomp, %s, memory %s", ll, mem);
}
