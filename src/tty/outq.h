#ifndef ZV_TTY_OUTQ_H
#define ZV_TTY_OUTQ_H
/* Internal to src/tty/: the viewer's output queue. Bytes the
 * terminal has not taken yet wait here and are written without ever
 * blocking, so that a slow link never holds up the keys (term.c pumps
 * the queue while it waits for input). */

#include <stddef.h>
#include <sys/types.h>

typedef struct {
    int    fd;              /* the terminal, -1 when closed */
    int    flags;           /* its file status flags (-1 unknown): O_NONBLOCK is
                               added only around our own writes (outq_write_now) */
    char  *buf;             /* waiting: buf[off, len) */
    size_t off, len, cap;
} OutQueue;

/* All of p to the terminal now: a signal or a full line only delays it
 * (for the few bytes of capabilities and the reset). 0, or -1 with errno. */
int     outq_send_all(const OutQueue *q, const char *p, size_t n);
/* One write that never waits. Returns what write(2) does. */
ssize_t outq_write_now(const OutQueue *q, const char *p, size_t n);
/* The output's flags as they were; async-signal-safe (the handlers). */
void    outq_flags_back(const OutQueue *q);
int     outq_pending(const OutQueue *q);
/* Queue bytes behind what waits: 0, or -1 out of memory. */
int     outq_add(OutQueue *q, const char *p, size_t n);
/* Write what waits, as much as the terminal takes now. 0 (sent, or the
 * line is full), or -1 with errno when the terminal cannot be written.
 * *emptied: the queue held bytes and has sent them all. */
int     outq_pump(OutQueue *q, int *emptied);
/* Forget what waits. */
void    outq_drop(OutQueue *q);
void    outq_free(OutQueue *q);

#endif
