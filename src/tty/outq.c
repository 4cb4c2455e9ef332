/* outq.c: the viewer's output queue, written without blocking (outq.h). */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "outq.h"

int outq_send_all(const OutQueue *q, const char *p, size_t n)
{
    while (n) {
        ssize_t w = write(q->fd, p, n);
        if (w > 0) {
            p += w;
            n -= (size_t)w;
        } else if (w < 0 && errno == EINTR) {
            continue;
        } else if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            struct pollfd pf = { .fd = q->fd, .events = POLLOUT };
            poll(&pf, 1, 1000);
        } else {
            if (w == 0)
                errno = EIO;
            return -1;
        }
    }
    return 0;
}

/* O_NONBLOCK on the output only for the call. The flag belongs to the
 * open file description, which the shell shares (and often standard
 * input with it): left set, the shell's reads would fail. The signal
 * handlers put the flags back should one come in between. */
ssize_t outq_write_now(const OutQueue *q, const char *p, size_t n)
{
    if (q->flags < 0 || (q->flags & O_NONBLOCK))
        return write(q->fd, p, n);
    if (fcntl(q->fd, F_SETFL, q->flags | O_NONBLOCK) != 0)
        return write(q->fd, p, n);
    ssize_t w = write(q->fd, p, n);
    int e = errno;
    fcntl(q->fd, F_SETFL, q->flags);
    errno = e;
    return w;
}

void outq_flags_back(const OutQueue *q)
{
    if (q->flags >= 0 && q->fd >= 0)
        fcntl(q->fd, F_SETFL, q->flags);
}

int outq_pending(const OutQueue *q)
{
    return q->off < q->len;
}

int outq_add(OutQueue *q, const char *p, size_t n)
{
    if (q->len + n > q->cap) {
        size_t cap = q->cap ? q->cap : 4096;
        while (cap < q->len + n)
            cap *= 2;
        char *b = realloc(q->buf, cap);
        if (!b)
            return -1;
        q->buf = b;
        q->cap = cap;
    }
    memcpy(q->buf + q->len, p, n);
    q->len += n;
    return 0;
}

int outq_pump(OutQueue *q, int *emptied)
{
    *emptied = 0;
    while (outq_pending(q)) {
        ssize_t w = outq_write_now(q, q->buf + q->off, q->len - q->off);
        if (w > 0) {
            q->off += (size_t)w;
        } else if (w < 0 && errno == EINTR) {
            continue;
        } else if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            return 0;
        } else {
            if (w == 0)
                errno = EIO;
            return -1;
        }
    }
    if (q->len) {
        q->off = q->len = 0;
        *emptied = 1;
    }
    return 0;
}

void outq_drop(OutQueue *q)
{
    q->off = q->len = 0;
}

void outq_free(OutQueue *q)
{
    free(q->buf);
    q->buf = NULL;
    q->off = q->len = q->cap = 0;
}
