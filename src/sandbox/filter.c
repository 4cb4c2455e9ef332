/* filter.c: the seccomp-bpf filter of a loading child (libseccomp).
 *
 * An allow list, because a parser needs few system calls: reading what
 * it opens (read-only opens only), mapping memory, threads and their
 * futexes, clocks, and writing to standard error (warnings, a
 * sanitizer's report), to the pipe that tells the parent the result is
 * ready, and to the memfd that carries the result (pwrite, and shared
 * mappings of it only). What an
 * exploited parser would do next kills the child at once, so that the
 * parent can say so: opens that could create or write, exec, sockets,
 * ptrace, new processes, signals to other processes, mount and the
 * like. Everything else fails with EPERM: glibc and the C++ runtime ask
 * for odds and ends (ioctl on a terminal, prctl, sched_setaffinity) and
 * cope with a refusal, where killing for them would fail real files.
 *
 * Mapping executable memory stays allowed (a library may map code), and
 * so do read-only opens of any file: what may be read is Landlock's to
 * say (landlock.c), where the kernel has it, and refopen.c's.
 *
 * The rules name three numbers of the child's own: the result's memfd,
 * the pipe it may write, its pid. libseccomp's compiling of the rules
 * cost each child 1.4 ms and 48 page faults (issue 34), so the fork
 * server compiles them once with a marker in place of each number
 * (sandbox_filter_make), and each child puts its numbers in place of
 * the markers in a copy and installs that (sandbox_filter_apply): the
 * very program libseccomp makes for those numbers, which the unit
 * tests compare instruction by instruction. */

#define _GNU_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sched.h>
#include <seccomp.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/mman.h>
#include <unistd.h>

#include "sandbox_internal.h"

/* O_TMPFILE without the O_DIRECTORY it includes (a read-only open of a
 * folder is fine) */
#define TMPFILE_BIT (O_TMPFILE & ~O_DIRECTORY)
/* open flags that make or change a file: refused (the child dies) */
#define WRITE_FLAGS (O_WRONLY | O_RDWR | O_CREAT | O_TRUNC | O_APPEND | TMPFILE_BIT)

static const int write_bits[] = { O_WRONLY, O_RDWR, O_CREAT, O_TRUNC, O_APPEND, TMPFILE_BIT };

static const int allowed[] = {
    SCMP_SYS(read), SCMP_SYS(pread64), SCMP_SYS(readv), SCMP_SYS(preadv), SCMP_SYS(lseek),
    SCMP_SYS(close), SCMP_SYS(fstat), SCMP_SYS(newfstatat), SCMP_SYS(stat), SCMP_SYS(lstat),
    SCMP_SYS(statx), SCMP_SYS(fstatfs), SCMP_SYS(statfs), SCMP_SYS(access), SCMP_SYS(faccessat),
    SCMP_SYS(faccessat2), SCMP_SYS(readlink), SCMP_SYS(readlinkat), SCMP_SYS(getdents64),
    SCMP_SYS(getcwd), SCMP_SYS(fcntl), SCMP_SYS(dup), SCMP_SYS(poll), SCMP_SYS(ppoll),
    SCMP_SYS(munmap), SCMP_SYS(mremap), SCMP_SYS(mprotect), SCMP_SYS(madvise),
    SCMP_SYS(brk), SCMP_SYS(futex), SCMP_SYS(set_robust_list), SCMP_SYS(get_robust_list),
    SCMP_SYS(rseq), SCMP_SYS(set_tid_address), SCMP_SYS(exit), SCMP_SYS(exit_group),
    SCMP_SYS(rt_sigreturn), SCMP_SYS(rt_sigprocmask), SCMP_SYS(rt_sigaction), SCMP_SYS(sigaltstack),
    SCMP_SYS(getpid), SCMP_SYS(gettid), SCMP_SYS(getppid), SCMP_SYS(getuid), SCMP_SYS(geteuid),
    SCMP_SYS(getgid), SCMP_SYS(getegid), SCMP_SYS(clock_gettime), SCMP_SYS(clock_getres),
    SCMP_SYS(gettimeofday), SCMP_SYS(nanosleep), SCMP_SYS(clock_nanosleep), SCMP_SYS(sched_yield),
    SCMP_SYS(sched_getaffinity), SCMP_SYS(getrandom), SCMP_SYS(getrusage), SCMP_SYS(times),
    SCMP_SYS(sysinfo), SCMP_SYS(uname), SCMP_SYS(getrlimit),
    SCMP_SYS(membarrier), SCMP_SYS(restart_syscall), SCMP_SYS(sched_getparam),
    SCMP_SYS(sched_getscheduler), SCMP_SYS(mincore), SCMP_SYS(fadvise64),
};

/* What an attacker wants: the child dies (SIGSYS) and the parent says so. */
static const int fatal[] = {
    SCMP_SYS(execve), SCMP_SYS(execveat), SCMP_SYS(fork), SCMP_SYS(vfork), SCMP_SYS(socket),
    SCMP_SYS(socketpair), SCMP_SYS(connect), SCMP_SYS(bind), SCMP_SYS(listen), SCMP_SYS(accept),
    SCMP_SYS(accept4), SCMP_SYS(sendto), SCMP_SYS(sendmsg), SCMP_SYS(recvfrom), SCMP_SYS(recvmsg),
    SCMP_SYS(ptrace), SCMP_SYS(process_vm_readv), SCMP_SYS(process_vm_writev), SCMP_SYS(creat),
    SCMP_SYS(unlink), SCMP_SYS(unlinkat), SCMP_SYS(rename), SCMP_SYS(renameat), SCMP_SYS(renameat2),
    SCMP_SYS(mkdir), SCMP_SYS(mkdirat), SCMP_SYS(rmdir), SCMP_SYS(link), SCMP_SYS(linkat),
    SCMP_SYS(symlink), SCMP_SYS(symlinkat), SCMP_SYS(chmod), SCMP_SYS(fchmod), SCMP_SYS(fchmodat),
    SCMP_SYS(chown), SCMP_SYS(fchown), SCMP_SYS(lchown), SCMP_SYS(fchownat), SCMP_SYS(truncate),
    SCMP_SYS(mknod), SCMP_SYS(mknodat), SCMP_SYS(mount), SCMP_SYS(umount2), SCMP_SYS(chroot),
    SCMP_SYS(setuid), SCMP_SYS(setgid), SCMP_SYS(unshare), SCMP_SYS(setns), SCMP_SYS(pivot_root),
    SCMP_SYS(bpf), SCMP_SYS(perf_event_open), SCMP_SYS(init_module), SCMP_SYS(finit_module),
    SCMP_SYS(kexec_load), SCMP_SYS(memfd_create), SCMP_SYS(pwritev),
    SCMP_SYS(io_uring_setup), SCMP_SYS(userfaultfd), SCMP_SYS(keyctl), SCMP_SYS(add_key),
};

static int add_rules(scmp_filter_ctx f, uint32_t memfd, uint32_t pipefd, uint32_t self)
{
    int r = 0;
    for (size_t i = 0; i < sizeof allowed / sizeof allowed[0]; i++)
        r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, allowed[i], 0);
    for (size_t i = 0; i < sizeof fatal / sizeof fatal[0]; i++)
        r |= seccomp_rule_add(f, SCMP_ACT_KILL_PROCESS, fatal[i], 0);
    /* opens: read-only ones pass, any that could make or write a file kill */
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(openat), 1, SCMP_A2(SCMP_CMP_MASKED_EQ, WRITE_FLAGS, 0));
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(open), 1, SCMP_A1(SCMP_CMP_MASKED_EQ, WRITE_FLAGS, 0));
    for (size_t i = 0; i < sizeof write_bits / sizeof write_bits[0]; i++) {
        scmp_datum_t b = (scmp_datum_t)write_bits[i];
        r |= seccomp_rule_add(f, SCMP_ACT_KILL_PROCESS, SCMP_SYS(openat), 1, SCMP_A2(SCMP_CMP_MASKED_EQ, b, b));
        r |= seccomp_rule_add(f, SCMP_ACT_KILL_PROCESS, SCMP_SYS(open), 1, SCMP_A1(SCMP_CMP_MASKED_EQ, b, b));
    }
    /* a shared mapping of a writable file would write it: shared maps of
     * the result's memfd only (private ones are memory like any other) */
    const scmp_datum_t sh = MAP_SHARED, sa = MAP_SHARED | MAP_ANONYMOUS, mfd = (scmp_datum_t)memfd;
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(mmap), 1, SCMP_A3(SCMP_CMP_MASKED_EQ, sh, 0));
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(mmap), 1, SCMP_A3(SCMP_CMP_MASKED_EQ, sa, sa));
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(mmap), 2, SCMP_A3(SCMP_CMP_MASKED_EQ, sa, sh),
                          SCMP_A4(SCMP_CMP_EQ, mfd));
    r |= seccomp_rule_add(f, SCMP_ACT_KILL_PROCESS, SCMP_SYS(mmap), 2, SCMP_A3(SCMP_CMP_MASKED_EQ, sa, sh),
                          SCMP_A4(SCMP_CMP_NE, mfd));
    /* openat2's flags are behind a pointer, out of a filter's reach: the
     * caller falls back to openat (ENOSYS is what an old kernel says) */
    r |= seccomp_rule_add(f, SCMP_ACT_ERRNO(ENOSYS), SCMP_SYS(openat2), 0);
    /* clone3's flags too: glibc then uses clone, whose flags are seen */
    r |= seccomp_rule_add(f, SCMP_ACT_ERRNO(ENOSYS), SCMP_SYS(clone3), 0);
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(clone), 1,
                          SCMP_A0(SCMP_CMP_MASKED_EQ, CLONE_THREAD, CLONE_THREAD));
    r |= seccomp_rule_add(f, SCMP_ACT_KILL_PROCESS, SCMP_SYS(clone), 1, SCMP_A0(SCMP_CMP_MASKED_EQ, CLONE_THREAD, 0));
    /* writes: standard error and the result's memfd only */
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(write), 1, SCMP_A0(SCMP_CMP_EQ, STDERR_FILENO));
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(writev), 1, SCMP_A0(SCMP_CMP_EQ, STDERR_FILENO));
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(write), 1, SCMP_A0(SCMP_CMP_EQ, (scmp_datum_t)pipefd));
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(pwrite64), 1, SCMP_A0(SCMP_CMP_EQ, (scmp_datum_t)memfd));
    r |= seccomp_rule_add(f, SCMP_ACT_KILL_PROCESS, SCMP_SYS(pwrite64), 1, SCMP_A0(SCMP_CMP_NE, (scmp_datum_t)memfd));
    /* limits: read, never changed (the parent raises its memory limit as
     * the model's files are counted: sandbox.c); setrlimit is refused */
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(prlimit64), 1, SCMP_A2(SCMP_CMP_EQ, 0));
    /* signals: to itself only (abort(), a sanitizer's report) */
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(tgkill), 1, SCMP_A0(SCMP_CMP_EQ, (scmp_datum_t)self));
    r |= seccomp_rule_add(f, SCMP_ACT_ALLOW, SCMP_SYS(kill), 1, SCMP_A0(SCMP_CMP_EQ, (scmp_datum_t)self));
    r |= seccomp_rule_add(f, SCMP_ACT_KILL_PROCESS, SCMP_SYS(kill), 1, SCMP_A0(SCMP_CMP_NE, (scmp_datum_t)self));
    return r;
}

/* The rules for these numbers, compiled: a context, or NULL. */
static scmp_filter_ctx rules(uint32_t memfd, uint32_t pipefd, uint32_t self)
{
    scmp_filter_ctx f = seccomp_init(SCMP_ACT_ERRNO(EPERM));
    if (f && add_rules(f, memfd, pipefd, self) != 0) {
        seccomp_release(f);
        f = NULL;
    }
    return f;
}

int sandbox_filter_install(int memfd, int pipefd)
{
    scmp_filter_ctx f = rules((uint32_t)memfd, (uint32_t)pipefd, (uint32_t)getpid());
    if (!f)
        return -1;
    int r = seccomp_load(f);    /* sets no_new_privs first (libseccomp's default) */
    seccomp_release(f);
    return r == 0 ? 0 : -1;
}

int sandbox_filter_compile(SandboxFilter *out, uint32_t memfd, uint32_t pipefd, uint32_t self)
{
    memset(out, 0, sizeof *out);
    scmp_filter_ctx f = rules(memfd, pipefd, self);
    /* libseccomp 2.5 writes the program to a descriptor only */
    int fd = f ? memfd_create("zview-filter", MFD_CLOEXEC) : -1;
    int ok = fd >= 0 && seccomp_export_bpf(f, fd) == 0;
    if (f)
        seccomp_release(f);
    off_t len = ok ? lseek(fd, 0, SEEK_END) : -1;
    size_t n = len > 0 ? (size_t)len / sizeof(struct sock_filter) : 0;
    ok = ok && n > 0 && n <= BPF_MAXINSNS && (size_t)len == n * sizeof(struct sock_filter);
    out->ins = ok ? malloc((size_t)len) : NULL;
    ok = out->ins && pread(fd, out->ins, (size_t)len, 0) == len;
    if (fd >= 0)
        close(fd);
    if (!ok) {
        free(out->ins);
        out->ins = NULL;
        return -1;
    }
    out->len = n;
    return 0;
}

/* What stands for each number in the program made once; none is a
 * constant the rules have otherwise (system call numbers, flags, the
 * architecture's token), nor a pid or descriptor the kernel gives. */
#define MARK_MEMFD 0x7a760001u
#define MARK_PIPE  0x7a760002u
#define MARK_SELF  0x7a760003u

/* A comparison with a marker (the program's only use of them). */
static int is_mark(const struct sock_filter *in)
{
    return BPF_CLASS(in->code) == BPF_JMP && BPF_SRC(in->code) == BPF_K && in->k - MARK_MEMFD < 3;
}

int sandbox_filter_make(SandboxFilter *f)
{
    if (sandbox_filter_compile(f, MARK_MEMFD, MARK_PIPE, MARK_SELF) != 0)
        return -1;
    /* each marker is there (else the program does not say what the
     * rules do once patched: it is not used) */
    int seen[3] = { 0, 0, 0 };
    for (size_t i = 0; i < f->len; i++)
        if (is_mark(&f->ins[i]))
            seen[f->ins[i].k - MARK_MEMFD] = 1;
    if (seen[0] && seen[1] && seen[2])
        return 0;
    sandbox_filter_free(f);
    return -1;
}

int sandbox_filter_patch(const SandboxFilter *f, SandboxFilter *out, uint32_t memfd, uint32_t pipefd, uint32_t self)
{
    out->len = 0;
    out->ins = f->len ? malloc(f->len * sizeof *out->ins) : NULL;
    if (!out->ins)
        return -1;
    const uint32_t value[3] = { memfd, pipefd, self };
    for (size_t i = 0; i < f->len; i++) {
        out->ins[i] = f->ins[i];
        if (is_mark(&f->ins[i]))
            out->ins[i].k = value[f->ins[i].k - MARK_MEMFD];
    }
    out->len = f->len;
    return 0;
}

int sandbox_filter_apply(const SandboxFilter *f, int memfd, int pipefd)
{
    SandboxFilter mine;
    if (!f || !f->len)
        return sandbox_filter_install(memfd, pipefd);
    if (sandbox_filter_patch(f, &mine, (uint32_t)memfd, (uint32_t)pipefd, (uint32_t)getpid()) != 0)
        return -1;
    struct sock_fprog prog = { .len = (unsigned short)mine.len, .filter = mine.ins };
    /* as seccomp_load does it: no_new_privs, then the filter, no flags */
    int r = prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0);
    if (r == 0)
        r = (int)syscall(SYS_seccomp, SECCOMP_SET_MODE_FILTER, 0, &prog);
    if (r != 0 && errno == ENOSYS)
        r = prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &prog, 0, 0);
    sandbox_filter_free(&mine);
    return r == 0 ? 0 : -1;
}

void sandbox_filter_free(SandboxFilter *f)
{
    free(f->ins);
    f->ins = NULL;
    f->len = 0;
}
