/* child.c: a sandboxed child, from the fork or the fork server to its
 * end. It takes the descriptors of its request (its parent's standard
 * input, error and working folder when it comes from the server), closes
 * every other, maps its inputs (the bytes to parse, the progress page,
 * the picture-while-loading prefix), opens the library a load may need,
 * confines its reads (Landlock), lowers its limits, installs the seccomp
 * filter, and only then touches the untrusted bytes: the unchanged
 * loader, or the texture decoder. It writes the result into the memfd
 * (wire.c), says so, and waits for the parent to read it.
 *
 * The limits: the memory it may add (the budget) is its soft limit on
 * address space and on private writable data, counted from what it maps
 * at the start (the server's copy of zview, a sanitizer's shadow, the
 * model's file mapped read-only, its threads' room); the hard limit is
 * what the machine has, up to which the parent raises the soft one as
 * the model's files are counted. The filter denies the child any change
 * of its own limits. */

#define _GNU_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <link.h>
#include <pthread.h>
#include <stddef.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "meshprefix.h"
#include "sandbox_internal.h"

/* The child's address space and its private writable part (VmData)
 * now, in bytes: its limits are these plus the budget, so that what the
 * process already maps (a sanitizer's shadow memory, reserved but never
 * touched) is not counted against the model. Both: AddressSanitizer's
 * allocator carves its heap out of space reserved at start, which
 * RLIMIT_AS never sees grow, but each piece it maps writable counts in
 * VmData (RLIMIT_DATA). */
static void vm_now(uint64_t *as, uint64_t *data)
{
    FILE *f = fopen("/proc/self/status", "re");
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

static uint64_t add_sat(uint64_t a, uint64_t b)
{
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

/* soft and hard, never above what the process was given */
static void set_limit(int what, uint64_t soft, uint64_t hard)
{
    struct rlimit rl;
    if (getrlimit(what, &rl) != 0)
        return;
    uint64_t max = rl.rlim_max;
    rl.rlim_max = hard < max ? hard : max;
    rl.rlim_cur = soft < rl.rlim_max ? soft : rl.rlim_max;
    setrlimit(what, &rl);
}

static int threads_of(const Req *r)
{
    long n = r->threads > 0 ? r->threads : sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 64 ? 64 : (int)n;
}

static void limits(const Req *r)
{
    uint64_t as, data, tas = 0, tdata = 0;
    vm_now(&as, &data);
    /* the reader maps the model's file (read-only: address space, not
     * VmData), whatever its size, and copies windows of it: room for the
     * file besides the budget */
    struct stat st;
    uint64_t file = r->kind == REQ_LOAD && !r->data_len && r->path[0] && strcmp(r->path, "-") &&
                    stat(r->path, &st) == 0 && S_ISREG(st.st_mode) ? (uint64_t)st.st_size : 0;
    if (r->kind == REQ_LOAD)
        sandbox_thread_room(threads_of(r), &tas, &tdata);
    uint64_t as0 = add_sat(add_sat(as, file), tas), data0 = add_sat(data, tdata);
    set_limit(RLIMIT_AS, add_sat(as0, r->budget), add_sat(as0, r->ceiling));
    set_limit(RLIMIT_DATA, add_sat(data0, r->budget), add_sat(data0, r->ceiling));
    set_limit(RLIMIT_CPU, r->cpu, r->cpu + 1);     /* SIGXCPU, then SIGKILL a second later */
    set_limit(RLIMIT_CORE, 0, 0);
}

static void replace_fd(int *fd, int with)
{
    if (*fd < 0)
        return;
    if (with >= 0)
        dup2(*fd, with);
    else
        fchdir(*fd);
    close(*fd);
    *fd = -1;
}

static int cmp_int(const void *a, const void *b)
{
    return *(const int *)a - *(const int *)b;
}

/* Standard input and error and the working folder from the request;
 * every descriptor but those of the request closed (the parent's files,
 * sockets, the terminal). */
static void take_fds(Req *r)
{
    replace_fd(&r->fd[RQ_STDIN], STDIN_FILENO);
    replace_fd(&r->fd[RQ_STDERR], STDERR_FILENO);
    replace_fd(&r->fd[RQ_CWD], -1);
    if (r->fd[RQ_STATUS] >= 0)
        close(r->fd[RQ_STATUS]);
    r->fd[RQ_STATUS] = -1;
    int keep[RQ_NFD], n = 0;
    for (int i = 0; i < RQ_NFD; i++)
        if (r->fd[i] > STDERR_FILENO)
            keep[n++] = r->fd[i];
    qsort(keep, (size_t)n, sizeof keep[0], cmp_int);
    unsigned from = STDERR_FILENO + 1;
    for (int i = 0; i < n; i++) {
        if ((unsigned)keep[i] > from)
            syscall(SYS_close_range, from, (unsigned)keep[i] - 1, 0u);
        from = (unsigned)keep[i] + 1;
    }
    syscall(SYS_close_range, from, ~0u, 0u);
}

typedef struct {
    MeshProgress *progress;     /* shared with the parent, or NULL */
    MeshPrefix   *prefix;
    int           has_data;     /* bytes came to parse or decode ... */
    const void   *data;         /* ... here (NULL: they could not be mapped) */
} Inputs;

/* Map what the request brings, and close its descriptors. */
static void map_inputs(Req *r, Inputs *in)
{
    memset(in, 0, sizeof *in);
    int *fd = r->fd;
    if (fd[RQ_PROGRESS] >= 0) {
        void *p = mmap(NULL, sizeof *in->progress, PROT_READ | PROT_WRITE, MAP_SHARED, fd[RQ_PROGRESS], 0);
        in->progress = p == MAP_FAILED ? NULL : p;
    }
    if (fd[RQ_PREFIX] >= 0)
        in->prefix = mesh_prefix_attach(fd[RQ_PREFIX], r->prefix_bytes);
    if (fd[RQ_DATA] >= 0) {
        in->has_data = 1;
        void *p = r->data_len ? mmap(NULL, r->data_len, PROT_READ, MAP_PRIVATE, fd[RQ_DATA], 0) : (void *)"";
        in->data = p == MAP_FAILED ? NULL : p;
    }
    for (int k = RQ_PROGRESS; k <= RQ_DATA; k++)
        if (fd[k] >= 0) {
            close(fd[k]);
            fd[k] = -1;
        }
}

/* ==== Files the model names, counted by the parent ==== */

typedef struct {
    int             alive, go;
    pthread_mutex_t mu;         /* loader threads may name files at once */
} RefLink;

/* Tell the parent of a file about to be read, and wait for its word:
 * by then it has raised the limits for it. */
static void tell_ref(void *arg, const char *path, int image)
{
    RefLink *l = arg;
    size_t n = strlen(path);
    if (n > REF_PATH_MAX)
        return;                 /* no such path opens */
    char msg[4 + REF_PATH_MAX];
    msg[0] = 'f';
    msg[1] = (char)(image != 0);
    msg[2] = (char)(n & 255);
    msg[3] = (char)(n >> 8);
    memcpy(msg + 4, path, n);
    pthread_mutex_lock(&l->mu);
    char c = 0;
    /* one write of at most PIPE_BUF bytes: whole, never interleaved */
    if (write(l->alive, msg, 4 + n) == (ssize_t)(4 + n))
        (void)!read(l->go, &c, 1);
    pthread_mutex_unlock(&l->mu);
}

/* ==== The work ==== */

static int do_load(const Req *r, const Inputs *in, RefLink *link, Mesh *m, char *err, size_t errlen)
{
    MeshLoadOpts lo = { .format = r->has_format ? r->format : NULL, .strict = r->strict, .quiet = r->quiet,
                        .max_polys = r->max_polys, .max_bytes = r->max_bytes, .tex_defer_side = r->tex_defer_side,
                        .no_textures = r->no_textures, .threads = r->threads, .piece_bytes = r->piece_bytes,
                        .tessellation = r->tessellation, .progress = in->progress, .prefix = in->prefix,
                        .on_ref = r->on_ref ? tell_ref : NULL, .on_ref_arg = link };
    const char *path = r->path[0] ? r->path : NULL;
    if (!in->has_data)
        return mesh_load_ex(m, path, &lo, err, errlen);
    if (in->data)
        return mesh_parse_buffer_ex(m, path, &lo, in->data, r->data_len, err, errlen);
    memset(m, 0, sizeof *m);
    snprintf(err, errlen, "%.300s: the sandbox cannot map the bytes", path ? path : "(input)");
    return -1;
}

/* A texture's decode as a mesh of that one texture: what the wire
 * carries and checks. */
static int do_texture(const Req *r, const Inputs *in, Mesh *m, MeshTexture *t, char *err, size_t errlen)
{
    MeshTexture src = { .name = (char *)r->path, .data = (void *)in->data, .len = r->data_len };
    src.img.wrap_u = (TexWrap)r->wrap_u;
    src.img.wrap_v = (TexWrap)r->wrap_v;
    memset(m, 0, sizeof *m);
    memset(t, 0, sizeof *t);
    int halved = 0;
    int rc = in->data ? mesh_texture_decode(&src, r->max_bytes, &t->img, &halved, err, errlen) : -1;
    if (!in->data)
        snprintf(err, errlen, "the sandbox cannot map the bytes");
    if (rc == 0) {
        t->name = (char *)r->path;
        t->state = MTEX_OK;
        t->halved = halved;
        m->tex = t;
        m->ntex = 1;
    }
    return rc;
}

/* A library opened with dlopen (assimp, its C++ runtime, draco) has its
 * thread-local data made at the thread's first use of it. At the bound
 * that first use can be the throw of std::bad_alloc (the C++ runtime
 * keeps the exception there), the data cannot be had, and glibc aborts
 * with a line of its own ("cannot allocate memory for thread-local
 * data") where the loader would have said "out of memory". Each block
 * is made now, before the limits (the ABI's __tls_get_addr of each
 * module that has one and none yet in this thread). */
typedef struct {
    unsigned long module, offset;
} TlsIndex;
extern void *__tls_get_addr(TlsIndex *ti);

static int make_tls(struct dl_phdr_info *info, size_t size, void *arg)
{
    (void)arg;
    if (size >= offsetof(struct dl_phdr_info, dlpi_tls_data) + sizeof info->dlpi_tls_data &&
        info->dlpi_tls_modid && !info->dlpi_tls_data) {
        TlsIndex ti = { info->dlpi_tls_modid, 0 };
        __tls_get_addr(&ti);
    }
    return 0;
}

void sandbox_child_main(Req *r, const SandboxFilter *filter)
{
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    /* default signal handling (the viewer's handlers touch the terminal) */
    for (int s = 1; s < NSIG; s++)
        if (s != SIGKILL && s != SIGSTOP)
            signal(s, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);
    take_fds(r);
    /* a quiet load (the viewer's, under curses) keeps the child's stderr
     * off the terminal too: a crashing library's last words, a
     * sanitizer's report */
    int null = r->quiet ? open("/dev/null", O_WRONLY | O_CLOEXEC) : -1;
    if (null >= 0) {
        dup2(null, STDERR_FILENO);
        close(null);
    }
    Inputs in;
    map_inputs(r, &in);
    RefLink link = { .alive = r->fd[RQ_ALIVE], .go = r->fd[RQ_GO] };
    pthread_mutex_init(&link.mu, NULL);
    /* dlopen reads the library's files, wherever they are: before reads
     * are confined */
    if (r->kind == REQ_LOAD) {
        mesh_library_preload(r->path[0] ? r->path : NULL, r->has_format ? r->format : NULL);
        dl_iterate_phdr(make_tls, NULL);
    }
    /* the limits count from what is mapped now, read in /proc: before
     * reads are confined */
    limits(r);
    int abi = sandbox_landlock_abi();
    if (abi > 0 && sandbox_landlock_restrict(r->kind == REQ_LOAD && r->path[0] ? r->path : NULL, abi) != 0)
        abi = -errno;
    Mesh m;
    MeshTexture t;
    char err[512] = "";
    int rc;
    if (sandbox_filter_apply(filter, r->fd[RQ_RESULT], r->fd[RQ_ALIVE]) != 0) {
        memset(&m, 0, sizeof m);
        snprintf(err, sizeof err, "%.300s: the sandbox's filter cannot be installed",
                 r->path[0] ? r->path : "(input)");
        rc = -1;
    } else if (r->kind == REQ_TEXTURE) {
        rc = do_texture(r, &in, &m, &t, err, sizeof err);
    } else {
        rc = do_load(r, &in, &link, &m, err, sizeof err);
    }
    m.info.landlock = abi;
    int memfd = r->fd[RQ_RESULT];
    if (sandbox_wire_write(memfd, &m, rc, err, 1) != 0 || write(r->fd[RQ_ALIVE], "r", 1) != 1)
        _exit(3);
    char c = 0;
    while (read(r->fd[RQ_GO], &c, 1) == 1)
        if (c == 'w')
            _exit(sandbox_wire_write(memfd, &m, rc, err, 0) == 0 ? 0 : 3);
    _exit(0);
}
