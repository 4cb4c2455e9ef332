/* termread: the viewer's input. Every byte the terminal sends goes
 * through our key parser (keys.c), which knows every form of the keys
 * terminals send and drops what it does not know whole (curses read an
 * unknown sequence as Esc, which quits, followed by keys). While it
 * waits for input, term_read() also writes what waits of the last frame
 * (termdraw.c) and takes what the signal handlers noted (term.c): a new
 * window size, the return from Ctrl-Z. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "term_internal.h"

#define LAST_ANSWER_MS 250      /* on quit, the wait for the answer still to come */

/* The answers to the pixels' questions after the start's wait (a slow
 * link), up to KP_LATE_MS after the questions: the pixels an answer names
 * (only ever better: kitty's before iTerm2's before sixel) replace what
 * was chosen, and the viewer hears of it as of a new window (everything
 * drawn again). A DA answer is no end here: the background's, late too,
 * may come before kitty's. */
static void late_pixels(Term *t, const unsigned char *b, size_t n)
{
    if (now_ms() - t->pix_asked_ms > KP_LATE_MS) {
        t->pix_late = 0;
        return;
    }
    pixels_scan(&t->pix_scan, b, n);
    PixelProto p = pixels_scanned(&t->pix_scan);
    if (p != PIX_CELLS && p != t->pix) {
        t->pix = p;
        t->late_news = 1;
    }
    t->pix_late = p != PIX_KITTY;
}

/* The answer to the colour question after the start's wait (an ssh
 * link slower than TERM_ASK_MS: every answer comes late), up to
 * KP_LATE_MS after it or until the attributes' answer, the last: more
 * colours than drawn so far are taken, and the viewer hears of it as of
 * a new window (everything drawn again, in them). */
static void late_colour(Term *t, const unsigned char *b, size_t n)
{
    if (now_ms() - t->pix_asked_ms > KP_LATE_MS) {
        t->colour_late = 0;
        return;
    }
    termbg_scan(&t->colour_scan, b, n);
    if (t->colour_scan.colour > t->depth) {
        term_colour_said(t, t->colour_scan.colour);
        if (t->depth == t->colour_scan.colour)
            t->late_news = 1;
    }
    if (t->colour_scan.got_da || t->colour_scan.colour)
        t->colour_late = 0;
}

/* Read what the input has (poll said so, with these revents) into the
 * parser. */
static void read_input(Term *t, short revents)
{
    unsigned char buf[512];
    size_t room = sizeof t->kp.b - t->kp.len;
    if (room > sizeof buf)
        room = sizeof buf;
    if (room == 0)
        return;                 /* cannot be: the parser keeps at most one unfinished sequence */
    ssize_t r = read(t->in_fd, buf, room);
    if (r > 0) {
        kp_push(&t->kp, buf, (size_t)r, now_ms());
        if (t->pix_late)
            late_pixels(t, buf, (size_t)r);
        if (t->colour_late)
            late_colour(t, buf, (size_t)r);
    } else if (r == 0 || (errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK) ||
               (revents & (POLLERR | POLLNVAL))) {
        /* end of file, a hung-up terminal (EIO), or an input in error
         * that has nothing to read: polling it again would spin */
        t->in_ended = 1;
    }
}

/* The next event the parser has; the input's end decides what is left
 * unfinished at once. Before the parser decides on a quiet, what has come
 * meanwhile is read: the viewer may have been drawing while the rest of
 * a sequence came, and reading it after the decision would split the
 * sequence (an answer's ESC alone is the Esc key, which quits). */
static int parsed(Term *t, TermEvent *ev)
{
    double now = now_ms();
    if (!t->in_ended && kp_wait_ms(&t->kp, now) == 0) {
        struct pollfd pf = { .fd = t->in_fd, .events = POLLIN };
        if (poll(&pf, 1, 0) > 0)
            read_input(t, pf.revents);
        now = now_ms();
    }
    if (!kp_next(&t->kp, ev, t->in_ended ? now + 1e12 : now))
        return 0;
    if (ev->type == TE_READY) {
        /* the answer to a status request: the last frame is through */
        t->ack_wait = 0;
        t->acks_seen = 1;
        t->unanswered = 0;
    }
    return 1;
}

static void drain_wake(Term *t)
{
    char buf[64];
    while (t->wake_fd >= 0 && read(t->wake_fd, buf, sizeof buf) > 0) {
    }
}

/* How long to wait for input: until the caller's deadline (< 0: none),
 * or less when the parser decides something after a quiet. */
static int wait_ms(Term *t, double until)
{
    double now = now_ms();
    double w = until < 0 ? -1 : until > now ? until - now : 0;
    int kw = kp_wait_ms(&t->kp, now);
    if (kw >= 0 && (w < 0 || kw < w))
        w = kw;
    return w < 0 ? -1 : (int)ceil(w);
}

/* Wait up to ms for input, a signal, or room for what waits to go out;
 * read and write what can be. Returns 1 when the output went through. */
static int wait_io(Term *t, int ms)
{
    int pending = outq_pending(&t->q);
    struct pollfd pf[3] = {
        { .fd = t->in_fd, .events = POLLIN },
        { .fd = t->wake_fd, .events = POLLIN },
        { .fd = pending ? t->q.fd : -1, .events = POLLOUT },
    };
    if (poll(pf, 3, ms) <= 0)
        return 0;               /* a timeout, or a signal (the caller looks) */
    if (pf[1].revents)
        drain_wake(t);
    if (pf[2].revents) {
        if (term_out_pump(t)) {
            t->out_errno = errno;       /* the next update reports it */
            term_out_drop(t);           /* and no more waiting to write */
        }
        if (!outq_pending(&t->q))
            return 1;
    }
    if (pf[0].revents)
        read_input(t, pf[0].revents);
    return 0;
}

/* Leaving with a status request answered by a terminal that answers:
 * its answer, left unread, would be typed into the shell ("^[[0n"). It
 * is read here, waiting a moment for it (keys typed meanwhile were for
 * the viewer, which is leaving). */
void term_take_last_answer(Term *t)
{
    if (!t->ack_wait || !t->acks_seen || t->in_ended)
        return;
    double until = now_ms() + LAST_ANSWER_MS;
    TermEvent ev;
    while (t->ack_wait && !t->in_ended) {
        while (t->ack_wait && parsed(t, &ev)) {
        }
        double left = until - now_ms();
        if (!t->ack_wait || left <= 0)
            break;
        struct pollfd pf = { .fd = t->in_fd, .events = POLLIN };
        if (poll(&pf, 1, (int)ceil(left)) <= 0)
            break;
        read_input(t, pf.revents);
    }
}

int term_read(TermEvent *ev, int timeout_ms)
{
    Term *t = term_session();
    if (!t)
        return -1;              /* no terminal: no key will ever come */
    double until = timeout_ms < 0 ? -1 : now_ms() + timeout_ms;
    for (;;) {
        memset(ev, 0, sizeof *ev);
        if (term_signalled(t, ev) || parsed(t, ev))
            return 1;
        if (t->late_news) {
            t->late_news = 0;
            ev->type = TE_RESIZE;       /* drawn again, in the pixels that came late */
            return 1;
        }
        if (t->in_ended)
            return -1;
        int ms = wait_ms(t, until);
        if (wait_io(t, ms)) {
            ev->type = TE_READY;        /* the frame is written: the next may go */
            return 1;
        }
        if (until >= 0 && now_ms() >= until) {
            memset(ev, 0, sizeof *ev);
            if (term_signalled(t, ev) || parsed(t, ev))
                return 1;
            return t->in_ended ? -1 : 0;
        }
    }
}
