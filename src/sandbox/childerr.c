/* childerr.c: the loading child's standard error, read by the parent a
 * line at a time and passed on made safe (safetext.h). The child writes
 * its loader's warnings there, and so does a library on its own: assimp
 * prints what it likes ("nullptr returned by creating DDLNode."), and
 * what it prints may quote the file. A line of zview's ("zview: ...") is
 * passed on; a library's own is dropped, so that a refusal is the one
 * line naming the file, except in the checking builds (ZV_CHECKS: make
 * asan), where a sanitizer's report is what the line says. Everything
 * passed on is made safe here: a child taken over by its file may write
 * any bytes at all. */

#define _GNU_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "safetext.h"
#include "sandbox.h"

int childerr_open(ChildErr *ce, int *child_end)
{
    int p[2];
    ce->fd = -1;
    ce->n = 0;
    ce->over = 0;
    *child_end = -1;
    if (pipe2(p, O_CLOEXEC | O_NONBLOCK) != 0)
        return -1;
    /* the child's end blocks: a library that writes much waits for the
     * parent, which reads while it waits for the result */
    fcntl(p[1], F_SETFL, 0);
    ce->fd = p[0];
    *child_end = p[1];
    return 0;
}

/* One line of the child's, without its newline. */
static void pass_on(ChildErr *ce)
{
    ce->line[ce->n] = '\0';
#ifndef ZV_CHECKS
    if (strncmp(ce->line, "zview: ", 7) != 0)
        return;
#endif
    safetext_line(stderr, "%s", ce->line);
}

void childerr_read(ChildErr *ce)
{
    if (ce->fd < 0)
        return;
    char buf[4096];
    for (;;) {
        ssize_t r = read(ce->fd, buf, sizeof buf);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return;     /* nothing more now */
        if (r == 0) {
            /* the child's end closed: the last line, and no more polling */
            if (ce->n && !ce->over)
                pass_on(ce);
            close(ce->fd);
            ce->fd = -1;
            return;
        }
        for (ssize_t i = 0; i < r; i++) {
            if (buf[i] == '\n') {
                if (!ce->over)
                    pass_on(ce);
                ce->n = 0;
                ce->over = 0;
            } else if (buf[i] == '\0' || ce->over) {
                continue;   /* a NUL would end the line early: left out */
            } else if (ce->n + 1 < sizeof ce->line) {
                ce->line[ce->n++] = buf[i];
            } else {
                /* a line past the buffer: its start is passed on, cut */
                pass_on(ce);
                ce->n = 0;
                ce->over = 1;
            }
        }
    }
}

void childerr_close(ChildErr *ce)
{
    if (ce->fd < 0)
        return;
    childerr_read(ce);
    if (ce->fd < 0)
        return;
    /* still open: the child's end lives on somewhere (a fork of another
     * thread's in between); what is there was read */
    if (ce->n && !ce->over)
        pass_on(ce);
    close(ce->fd);
    ce->fd = -1;
}
