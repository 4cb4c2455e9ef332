/* server.c: the fork server. fork() copies only the calling thread, and
 * whatever lock another thread held at that moment stays held in the
 * child for ever: glibc makes its own malloc safe across fork, but not
 * every allocator does (GCC 12's AddressSanitizer hung one viewer run in
 * three), nor every library. So main() starts this server while zview
 * still has one thread, and every sandboxed child is forked from it, a
 * single-threaded copy of zview as it started.
 *
 * A request is one message on a SOCK_SEQPACKET socketpair (atomic, so
 * that any thread may send one): a Req and its descriptors (SCM_RIGHTS),
 * with the requester's standard input, error and working folder, and
 * one end of a socketpair of its own for the answer. For each the
 * server forks the child, sends its pid and a pidfd (to signal it by: no
 * pid reused in between), and keeps a pidfd of its own, which polls
 * readable when the child ends: it then waits for it (WNOHANG) and sends
 * its wait status and resource use. So the server never blocks on a
 * child and serves requests as fast as it forks, with one fork a child
 * (a waiter process between them, forked for each, cost as much CPU
 * again: 1,000 cubes --check --jsonl, 8.9 to 10.1 s of CPU with
 * it, 6.2 to 8.3 s without, at load 14). The
 * result itself never passes here: the requester reads it straight out
 * of the child (sandbox.c), which is its descendant.
 *
 * The child dies with the server (PR_SET_PDEATHSIG), the server with
 * zview, and when zview closes its end of the socket: nothing outlives a
 * zview that quits or crashes. */

#define _GNU_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sandbox_internal.h"

/* The waiter's reports: the child started (pid > 0, or -errno), then
 * its end. */
typedef struct {
    pid_t pid;
} Started;

typedef struct {
    int           status;
    struct rusage ru;
} Ended;

/* ==== Messages with descriptors ==== */

static int send_fds(int sock, const void *buf, size_t len, const int *fds, int n)
{
    union {
        struct cmsghdr h;
        char           b[CMSG_SPACE(sizeof(int) * RQ_NFD)];
    } ctl;
    struct iovec iov = { (void *)buf, len };
    struct msghdr mh = { .msg_iov = &iov, .msg_iovlen = 1 };
    if (n > 0) {
        memset(&ctl, 0, sizeof ctl);
        mh.msg_control = ctl.b;
        mh.msg_controllen = CMSG_SPACE(sizeof(int) * (size_t)n);
        struct cmsghdr *c = CMSG_FIRSTHDR(&mh);
        c->cmsg_level = SOL_SOCKET;
        c->cmsg_type = SCM_RIGHTS;
        c->cmsg_len = CMSG_LEN(sizeof(int) * (size_t)n);
        memcpy(CMSG_DATA(c), fds, sizeof(int) * (size_t)n);
    }
    ssize_t w;
    while ((w = sendmsg(sock, &mh, MSG_NOSIGNAL)) < 0 && errno == EINTR)
        ;
    return w == (ssize_t)len ? 0 : -1;
}

/* One message of exactly len bytes; its descriptors (at most max) into
 * fds, their count into *n. 0; -1 the peer is gone; -2 it is not a
 * message of ours. */
static int recv_fds(int sock, void *buf, size_t len, int *fds, int max, int *n)
{
    union {
        struct cmsghdr h;
        char           b[CMSG_SPACE(sizeof(int) * RQ_NFD)];
    } ctl;
    struct iovec iov = { buf, len };
    struct msghdr mh = { .msg_iov = &iov, .msg_iovlen = 1, .msg_control = ctl.b, .msg_controllen = sizeof ctl.b };
    ssize_t r;
    while ((r = recvmsg(sock, &mh, MSG_CMSG_CLOEXEC)) < 0 && errno == EINTR)
        ;
    *n = 0;
    for (struct cmsghdr *c = CMSG_FIRSTHDR(&mh); c; c = CMSG_NXTHDR(&mh, c))
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_RIGHTS) {
            int k = (int)((c->cmsg_len - CMSG_LEN(0)) / sizeof(int));
            for (int i = 0; i < k; i++) {
                int fd;
                memcpy(&fd, CMSG_DATA(c) + i * sizeof(int), sizeof fd);
                if (*n < max)
                    fds[(*n)++] = fd;
                else
                    close(fd);
            }
        }
    if (r <= 0)
        return -1;
    return r == (ssize_t)len && !(mh.msg_flags & (MSG_TRUNC | MSG_CTRUNC)) ? 0 : -2;
}

/* ==== The server's side ==== */

static void close_all(int *fd, int n)
{
    for (int i = 0; i < n; i++)
        if (fd[i] >= 0) {
            close(fd[i]);
            fd[i] = -1;
        }
}

/* A child of the server, until it ends: its pid, a pidfd that polls
 * readable at its end (-1: none, the kernel has no pidfd_open: it is
 * then looked at every POLL_MS), and the socket its end is reported on. */
typedef struct {
    pid_t pid;
    int   pidfd;
    int   st;
} Kid;

typedef struct {
    Kid           *kid;
    struct pollfd *pf;          /* room for the request socket and each pidfd */
    int            n, cap;
} Kids;

/* How often children without a pidfd are looked at. */
#define POLL_MS 50

/* Fork r's child, say so on its status socket, and keep it in k. The
 * request's descriptors are closed here (the child holds its own). */
static void spawn(Kids *k, Req *r, const SandboxFilter *filter)
{
    int st = r->fd[RQ_STATUS];
    if (k->n == k->cap) {
        int cap = k->cap ? 2 * k->cap : 16;
        Kid *kid = realloc(k->kid, sizeof *kid * (size_t)cap);
        if (kid)
            k->kid = kid;
        struct pollfd *pf = kid ? realloc(k->pf, sizeof *pf * (size_t)(cap + 1)) : NULL;
        if (pf)
            k->pf = pf;
        if (!pf) {
            close_all(r->fd, RQ_NFD);   /* the requester forks it itself */
            return;
        }
        k->cap = cap;
    }
    pid_t pid = fork();
    if (pid == 0)
        sandbox_child_main(r, filter);
    Started s = { .pid = pid > 0 ? pid : -errno };
    /* the child holds its ends now: the requester must see ALIVE's end
     * of file when the child ends, and no copy of it may stay here */
    r->fd[RQ_STATUS] = -1;
    close_all(r->fd, RQ_NFD);
    int pidfd = pid > 0 ? (int)syscall(SYS_pidfd_open, pid, 0) : -1;
    send_fds(st, &s, sizeof s, &pidfd, pidfd >= 0);
    if (pid <= 0) {
        close(st);
        return;
    }
    k->kid[k->n++] = (Kid){ pid, pidfd, st };
}

/* Report the end of every child that has ended, and forget it. */
static void reap_kids(Kids *k)
{
    for (int i = 0; i < k->n;) {
        Kid *c = &k->kid[i];
        Ended e;
        memset(&e, 0, sizeof e);
        pid_t r = wait4(c->pid, &e.status, WNOHANG, &e.ru);
        if (r == 0 || (r < 0 && errno == EINTR)) {
            i++;
            continue;
        }
        if (r == c->pid)
            send_fds(c->st, &e, sizeof e, NULL, 0);
        /* else it is not ours to wait for (cannot be): the requester
         * sees the socket close and says the child is gone */
        close(c->st);
        if (c->pidfd >= 0)
            close(c->pidfd);
        *c = k->kid[--k->n];
    }
}

/* The request's descriptors, sent in order, put back in their slots. */
static int unpack(Req *r, const int *fds, int n)
{
    int k = 0;
    for (int i = 0; i < RQ_NFD; i++) {
        if (r->fd[i] < 0)
            continue;
        r->fd[i] = k < n ? fds[k] : -1;
        k++;
    }
    return k == n && r->fd[RQ_STATUS] >= 0 ? 0 : -1;
}

static void serve(int sock)
{
    prctl(PR_SET_NAME, "zview-sandbox");
    /* its standard input and output are not its own to hold open (a
     * pipe's reader waits for their end); standard error is kept for a
     * child's last words when a request brings none */
    int null = open("/dev/null", O_RDWR | O_CLOEXEC);
    if (null >= 0) {
        dup2(null, STDIN_FILENO);
        dup2(null, STDOUT_FILENO);
        close(null);
    }
    if (sock != STDERR_FILENO + 1) {
        dup2(sock, STDERR_FILENO + 1);
        close(sock);
        sock = STDERR_FILENO + 1;
    }
    syscall(SYS_close_range, sock + 1, ~0u, 0u);
    /* the server is each child's parent, and waits for it: when its
     * pidfd says it ended */
    signal(SIGCHLD, SIG_DFL);
    /* the terminal's signals are zview's to act on (the server ends with
     * it: the socket's end, PR_SET_PDEATHSIG); a child resets them all */
    static const int quiet[] = { SIGPIPE, SIGINT, SIGQUIT, SIGHUP, SIGTSTP, SIGTTIN, SIGTTOU };
    for (size_t i = 0; i < sizeof quiet / sizeof quiet[0]; i++)
        signal(quiet[i], SIG_IGN);
    /* the children's seccomp program, compiled once (else each child
     * compiles its own) */
    SandboxFilter filter;
    sandbox_filter_make(&filter);
    Kids k = { 0 };
    struct pollfd one;
    for (;;) {
        /* the request socket first, then each child's pidfd */
        struct pollfd *pf = k.pf ? k.pf : &one;
        int np = 0, blind = 0;
        pf[np++] = (struct pollfd){ .fd = sock, .events = POLLIN };
        for (int i = 0; i < k.n; i++) {
            if (k.kid[i].pidfd >= 0)
                pf[np++] = (struct pollfd){ .fd = k.kid[i].pidfd, .events = POLLIN };
            else
                blind = 1;
        }
        int n = poll(pf, (nfds_t)np, blind ? POLL_MS : -1);
        if (n < 0 && errno != EINTR)
            _exit(1);
        if (k.n && (n > 0 || blind))
            reap_kids(&k);
        if (n <= 0 || !pf[0].revents)
            continue;
        Req r;
        int fds[RQ_NFD], nfd;
        int got = recv_fds(sock, &r, sizeof r, fds, RQ_NFD, &nfd);
        if (got == -1)
            _exit(0);           /* zview is gone (its children die with this) */
        if (got != 0 || unpack(&r, fds, nfd) != 0) {
            close_all(fds, nfd);
            continue;
        }
        spawn(&k, &r, &filter);
    }
}

int sandbox_server_start(SandboxServer *s)
{
    int sv[2];
    memset(s, 0, sizeof *s);
    if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, sv) != 0)
        return -1;
    pid_t parent = getpid();
    pid_t pid = fork();
    if (pid == 0) {
        close(sv[0]);
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent)
            _exit(0);           /* zview ended before the line above */
        serve(sv[1]);
    }
    close(sv[1]);
    if (pid < 0) {
        close(sv[0]);
        return -1;
    }
    s->sock = sv[0];
    s->pid = pid;
    return 0;
}

void sandbox_server_stop(SandboxServer *s)
{
    if (s->pid <= 0)
        return;
    close(s->sock);
    while (waitpid(s->pid, NULL, 0) < 0 && errno == EINTR)
        ;
    s->pid = 0;
}

/* ==== The requester's side ==== */

int sandbox_server_spawn(const SandboxServer *s, Req *r, Child *c)
{
    int sp[2];
    if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, sp) != 0)
        return -1;
    int cwd = open(".", O_PATH | O_CLOEXEC);
    /* standard error: the requester's, unless the request has its own
     * (the pipe of childerr.c, which the requester closes) */
    int own_err = r->fd[RQ_STDERR] < 0;
    r->fd[RQ_STDIN] = STDIN_FILENO;
    if (own_err)
        r->fd[RQ_STDERR] = STDERR_FILENO;
    r->fd[RQ_CWD] = cwd;
    r->fd[RQ_STATUS] = sp[1];
    int fds[RQ_NFD], n = 0;
    for (int i = 0; i < RQ_NFD; i++)
        if (r->fd[i] >= 0)
            fds[n++] = r->fd[i];
    int rc = send_fds(s->sock, r, sizeof *r, fds, n);
    close(sp[1]);
    if (cwd >= 0)
        close(cwd);
    r->fd[RQ_STDIN] = r->fd[RQ_CWD] = r->fd[RQ_STATUS] = -1;
    if (own_err)
        r->fd[RQ_STDERR] = -1;
    Started st = { 0 };
    int pidfd = -1, got = 0;
    if (rc == 0 && recv_fds(sp[0], &st, sizeof st, &pidfd, 1, &got) == 0 && st.pid > 0) {
        c->pid = st.pid;
        c->pidfd = got ? pidfd : -1;
        c->status = sp[0];
        return 0;
    }
    if (got)
        close(pidfd);
    close(sp[0]);
    return -1;
}

int sandbox_server_reap(Child *c, int *status, struct rusage *ru)
{
    Ended e;
    int got = 0;
    int rc = recv_fds(c->status, &e, sizeof e, NULL, 0, &got);
    close(c->status);
    c->status = -1;
    if (c->pidfd >= 0)
        close(c->pidfd);
    c->pidfd = -1;
    if (rc != 0)
        return -1;
    *status = e.status;
    *ru = e.ru;
    return 0;
}
