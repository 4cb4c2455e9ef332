/* sandbox.c: a load in a child process (sandbox.h). The parent makes a
 * memfd for the result and a shared page for progress, forks, and waits
 * for the child to end, polling a pipe the child holds open so that a
 * cancel (the viewer's Esc) can kill it and progress can be copied out.
 * The child lowers its limits, closes what it does not need, installs
 * the filter (filter.c), runs the unchanged loader and writes the mesh
 * into the memfd (wire.c); the parent reads it back, checking it. */

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
#include <sys/uio.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clock.h"
#include "sandbox.h"

#define SANDBOX_SLACK (256ull << 20)     /* bytes beyond the memory available, without --max-memory */
#include "sysmem.h"

/* How often the parent looks at the cancel flag and copies progress
 * while the child works: quick enough for Esc to feel immediate. */
#define POLL_MS 50

typedef struct {
    const char         *path;   /* what is loaded */
    const char         *name;   /* what messages call it */
    const MeshLoadOpts *lo;
    const void         *data;   /* the bytes, or NULL to read path */
    size_t              len;
    uint64_t            budget; /* address space the child may add */
    unsigned            cpu;    /* seconds */
    int                 memfd;
    int                 alive;  /* the child's end: 'r' when its result is ready; closed when it ends */
    int                 go;     /* the child's end: 'w' asks for the arrays in the memfd; EOF ends it */
    MeshProgress       *progress;   /* shared with the parent, or NULL */
    int                 errfd;  /* the child's end of its standard error (childerr.c), or -1 */
    ChildErr            cerr;   /* the parent's end */
} Job;

int sandbox_available(void)
{
    /* EINVAL: a kernel built without seccomp */
    return prctl(PR_GET_SECCOMP, 0, 0, 0, 0) >= 0;
}

/* The child's address space and its private writable part (VmData)
 * now, in bytes: its limits are these plus the budget, so that what the
 * process already maps (a viewer's scene, a sanitizer's shadow memory,
 * reserved but never touched) is not counted against the model. Both:
 * AddressSanitizer's allocator carves its heap out of space reserved at
 * start, which RLIMIT_AS never sees grow, but each piece it maps
 * writable counts in VmData (RLIMIT_DATA). */
static void vm_now(uint64_t *as, uint64_t *data)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[128];
    unsigned long long kb;
    *as = *data = 0;
    while (f && fgets(line, sizeof line, f)) {
        if (sscanf(line, "VmSize: %llu kB", &kb) == 1)
            *as = (uint64_t)kb << 10;
        else if (sscanf(line, "VmData: %llu kB", &kb) == 1)
            *data = (uint64_t)kb << 10;
    }
    if (f)
        fclose(f);
}

static void set_limit(int what, uint64_t soft, uint64_t hard)
{
    struct rlimit rl;
    if (getrlimit(what, &rl) == 0) {
        /* never above what the parent was given */
        rl.rlim_cur = rl.rlim_max != RLIM_INFINITY && hard > rl.rlim_max ? rl.rlim_max : soft;
        rl.rlim_max = rl.rlim_max != RLIM_INFINITY && hard > rl.rlim_max ? rl.rlim_max : hard;
        if (rl.rlim_cur > rl.rlim_max)
            rl.rlim_cur = rl.rlim_max;
        setrlimit(what, &rl);
    }
}

static int cmp_int(const void *a, const void *b)
{
    return *(const int *)a - *(const int *)b;
}

/* Everything before the filter: default signal handling (the viewer's
 * handlers touch the terminal), the parent's descriptors closed but for
 * standard input (a model piped in), output, the memfd and the two
 * pipes, and the limits. */
static void child_prepare(Job *j)
{
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    for (int s = 1; s < NSIG; s++)
        if (s != SIGKILL && s != SIGSTOP)
            signal(s, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);
    /* standard error is the parent's pipe, which passes zview's lines on
     * made safe (childerr.c); a quiet load (the viewer's, under curses)
     * keeps it off the terminal: a crashing library's last words, a
     * sanitizer's report */
    int null = j->lo->quiet ? open("/dev/null", O_WRONLY | O_CLOEXEC) : -1;
    if (null >= 0 || j->errfd >= 0)
        dup2(null >= 0 ? null : j->errfd, STDERR_FILENO);
    int keep[3] = { j->memfd, j->alive, j->go };
    qsort(keep, 3, sizeof keep[0], cmp_int);
    unsigned from = 3;
    for (int i = 0; i < 3; i++) {
        if ((unsigned)keep[i] > from)
            syscall(SYS_close_range, from, (unsigned)keep[i] - 1, 0u);
        from = (unsigned)keep[i] + 1;
    }
    syscall(SYS_close_range, from, ~0u, 0u);
    uint64_t as, data;
    vm_now(&as, &data);
    /* the reader maps the model's file (read-only: address space, not
     * VmData), whatever its size, and copies windows of it: the address
     * space has room for the file besides the budget */
    struct stat st;
    uint64_t file = j->path && strcmp(j->path, "-") && stat(j->path, &st) == 0 && S_ISREG(st.st_mode)
                  ? (uint64_t)st.st_size : 0;
    if (j->budget < (uint64_t)RLIM_INFINITY - as - file) {      /* else nothing is known of the machine's memory */
        set_limit(RLIMIT_AS, as + file + j->budget, as + file + j->budget);
        set_limit(RLIMIT_DATA, data + j->budget, data + j->budget);
    }
    set_limit(RLIMIT_CPU, j->cpu, j->cpu + 1);     /* SIGXCPU, then SIGKILL a second later */
    set_limit(RLIMIT_CORE, 0, 0);
}

/* Load, say where the result is, and wait: the parent copies the arrays
 * out of this process's memory (one copy, none through the memfd), or,
 * where it may not read another process (ptrace rules), asks for them
 * in the memfd. */
static void child_main(Job *j)
{
    child_prepare(j);
    Mesh m;
    char err[512] = "";
    int rc;
    MeshLoadOpts lo = *j->lo;
    lo.cancel = NULL;           /* the parent kills the child instead */
    lo.progress = j->progress;
    if (sandbox_filter_install(j->memfd, j->alive) != 0) {
        snprintf(err, sizeof err, "%s: the sandbox's filter cannot be installed", j->name);
        rc = -1;
    } else if (j->data) {
        rc = mesh_parse_buffer_ex(&m, j->path, &lo, j->data, j->len, err, sizeof err);
    } else {
        rc = mesh_load_ex(&m, j->path, &lo, err, sizeof err);
    }
    if (sandbox_wire_write(j->memfd, &m, rc, err, 1) != 0 || write(j->alive, "r", 1) != 1)
        _exit(3);
    char c = 0;
    if (read(j->go, &c, 1) == 1 && c == 'w')
        _exit(sandbox_wire_write(j->memfd, &m, rc, err, 0) == 0 ? 0 : 3);
    _exit(0);
}

/* The message for a child that did not finish: what ended it. */
static void died(const Job *j, int status, const struct rusage *ru, int cancelled, char *err, size_t errlen)
{
    double cpu = (double)ru->ru_utime.tv_sec + (double)ru->ru_stime.tv_sec +
                 ((double)ru->ru_utime.tv_usec + (double)ru->ru_stime.tv_usec) / 1e6;
    int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    char mem[32];
    sysmem_format(j->budget, mem, sizeof mem);
    if (cancelled)
        snprintf(err, errlen, "%s: cancelled", j->name);
    else if (sig == SIGSYS)
        snprintf(err, errlen, "%s: the loader tried something the sandbox forbids (writing a file, running a "
                 "program, a network connection, ...) and was stopped", j->name);
    else if (sig == SIGXCPU || (sig == SIGKILL && cpu >= j->cpu))
        snprintf(err, errlen, "%s: the load took more than %u s of CPU time and was stopped", j->name, j->cpu);
    else if (sig == SIGKILL)
        snprintf(err, errlen, "%s: the loader was killed (out of memory?)", j->name);
    else if (sig == SIGABRT)
        snprintf(err, errlen, "%s: the loader gave up (aborted; more than its %s of memory, or a malformed "
                 "file)", j->name, mem);
    else if (sig)
        snprintf(err, errlen, "%s: the loader crashed (%s) in the sandbox: a malformed file", j->name,
                 strsignal(sig));
    else
        snprintf(err, errlen, "%s: the loader failed in the sandbox (exit status %d)", j->name,
                 WEXITSTATUS(status));
}

enum { CHILD_GONE, CHILD_CANCELLED, CHILD_READY };

/* Wait for the child's word, killing it on cancel, copying progress:
 * ready (its result waits to be read), gone (it ended: crashed, or
 * killed by a limit or the filter), or cancelled. */
static int wait_child(Job *j, pid_t pid, int alive)
{
    int cancelled = 0;
    for (;;) {
        struct pollfd pf[2] = { { .fd = alive, .events = POLLIN }, { .fd = j->cerr.fd, .events = POLLIN } };
        int n = poll(pf, j->cerr.fd >= 0 ? 2 : 1, j->lo->cancel || j->lo->progress ? POLL_MS : -1);
        if (n > 0 && pf[1].revents) {
            childerr_read(&j->cerr);
            if (!pf[0].revents)
                continue;
        }
        if (j->lo->progress && j->progress) {
            __atomic_store_n(&j->lo->progress->done, __atomic_load_n(&j->progress->done, __ATOMIC_RELAXED),
                             __ATOMIC_RELAXED);
            __atomic_store_n(&j->lo->progress->total, __atomic_load_n(&j->progress->total, __ATOMIC_RELAXED),
                             __ATOMIC_RELAXED);
        }
        if (!cancelled && j->lo->cancel && __atomic_load_n(j->lo->cancel, __ATOMIC_RELAXED)) {
            kill(pid, SIGKILL);
            cancelled = 1;
        }
        if (n > 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) {
            char c = 0;
            if (!cancelled && read(alive, &c, 1) == 1 && c == 'r')
                return CHILD_READY;
            return cancelled ? CHILD_CANCELLED : CHILD_GONE;
        }
    }
}

/* Wait for the child to end, reading its standard error meanwhile: a
 * report written as it dies (a sanitizer's) must not fill the pipe and
 * hold it up. */
static int reap(Job *j, pid_t pid, int *status, struct rusage *ru)
{
    for (;;) {
        pid_t r = wait4(pid, status, j->cerr.fd >= 0 ? WNOHANG : 0, ru);
        if (r == pid)
            return 0;
        if (r < 0 && errno != EINTR)
            return -1;
        if (r == 0) {
            struct pollfd pf = { .fd = j->cerr.fd, .events = POLLIN };
            poll(&pf, 1, POLL_MS);
            childerr_read(&j->cerr);
        }
    }
}

/* Read the child's result: from its memory (pid), else from the memfd. */
static int collect(const Job *j, pid_t pid, Mesh *m, char *err, size_t errlen)
{
    struct stat st;
    if (fstat(j->memfd, &st) != 0 || st.st_size <= 0) {
        snprintf(err, errlen, "%s: the sandboxed loader returned nothing", j->name);
        return -1;
    }
    int rc = -1;
    char why[400];
    if (sandbox_wire_read(j->memfd, (size_t)st.st_size, pid, m, &rc, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s: %s", j->name, why);
        return -2;
    }
    if (rc)
        snprintf(err, errlen, "%s", why);
    return rc;
}

/* The child is ready: its result, read from its memory, or (when that
 * is not allowed) from the memfd once it has written it there. */
static int finish(Job *j, pid_t pid, int go, Mesh *m, char *err, size_t errlen)
{
    int rc = collect(j, pid, m, err, errlen), status = 0;
    struct rusage ru = { 0 };
    if (rc == -2 && write(go, "w", 1) == 1) {
        close(go);
        if (reap(j, pid, &status, &ru) == 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0)
            rc = collect(j, 0, m, err, errlen);
        else
            died(j, status, &ru, 0, err, errlen);
        return rc < 0 ? -1 : rc;
    }
    close(go);
    reap(j, pid, &status, &ru);
    return rc < 0 ? -1 : rc;
}

static int run(Job *j, Mesh *m, char *err, size_t errlen)
{
    double t0 = now_ms();
    int alive[2] = { -1, -1 }, go[2] = { -1, -1 };
    j->memfd = memfd_create("zview-load", MFD_CLOEXEC);
    if (j->memfd < 0 || pipe2(alive, O_CLOEXEC) != 0 || pipe2(go, O_CLOEXEC) != 0) {
        snprintf(err, errlen, "%s: cannot start the sandbox: %s", j->name, strerror(errno));
        for (int i = 0; i < 2; i++) {
            if (alive[i] >= 0)
                close(alive[i]);
            if (go[i] >= 0)
                close(go[i]);
        }
        if (j->memfd >= 0)
            close(j->memfd);
        return -1;
    }
    j->progress = mmap(NULL, sizeof *j->progress, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (j->progress == MAP_FAILED)
        j->progress = NULL;
    j->alive = alive[1];
    j->go = go[0];
    j->errfd = -1;
    j->cerr.fd = -1;
    if (!j->lo->quiet)
        childerr_open(&j->cerr, &j->errfd);     /* none: the child writes to standard error itself */
    pid_t pid = fork();
    if (pid == 0) {
        close(alive[0]);
        close(go[1]);
        child_main(j);
    }
    close(alive[1]);
    close(go[0]);
    if (j->errfd >= 0)
        close(j->errfd);
    int rc = -1;
    if (pid < 0) {
        snprintf(err, errlen, "%s: cannot start the sandbox: %s", j->name, strerror(errno));
        close(go[1]);
    } else {
        int state = wait_child(j, pid, alive[0]);
        if (state == CHILD_READY) {
            rc = finish(j, pid, go[1], m, err, errlen);
        } else {
            int status = 0;
            struct rusage ru = { 0 };
            close(go[1]);
            reap(j, pid, &status, &ru);
            died(j, status, &ru, state == CHILD_CANCELLED, err, errlen);
        }
    }
    childerr_close(&j->cerr);
    if (rc == 0)
        m->info.load_ms = now_ms() - t0;    /* the sandbox's cost included */
    close(alive[0]);
    close(j->memfd);
    if (j->progress)
        munmap(j->progress, sizeof *j->progress);
    return rc;
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
    Job j = { .path = path, .name = !path ? "(input)" : strcmp(path, "-") ? path : "stdin", .lo = lo,
              .data = data, .len = len, .cpu = so && so->cpu_seconds ? so->cpu_seconds : SANDBOX_CPU_SECONDS };
    /* without --max-memory the bound is what is available and some slack:
     * the loaders' own estimates judge against what is available and
     * refuse first, with the estimate in the message; the bound is for
     * what they cannot foresee (a parser gone wrong) */
    j.budget = so && so->max_memory ? so->max_memory
             : lo->max_bytes ? lo->max_bytes : sysmem_available() + SANDBOX_SLACK;
    MeshLoadOpts lo2 = *lo;
    if (!lo2.max_bytes && so && so->max_memory)
        lo2.max_bytes = so->max_memory;     /* the loaders' own estimates refuse first, with a better message */
    j.lo = &lo2;
    return run(&j, m, err, errlen);
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
