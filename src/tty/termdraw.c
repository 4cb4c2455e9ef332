/* termdraw: the viewer's frames. What the viewer draws (the picture's
 * cells, the status bar, boxes, a message, an image in pixels) goes
 * into the screen model (vt.c), and term_update() sends the bytes that
 * take the terminal from what it shows to that.
 *
 * A frame never blocks the keys: it is written only as fast as the
 * terminal takes it, the rest kept in the output queue (outq.c) and sent
 * while termread.c waits for input, so that on a slow link q still
 * quits at once; no frame is sent while the last one is still on its way
 * (the viewer draws the newest state when the line is free).
 *
 * Colours are SGR escapes of our own: 24-bit whenever COLORTERM or --color asks for it
 * (no *-direct terminfo entry needed), and under 256/16/8 colours the
 * very palette numbers --print writes (the same quantizer, dithered by
 * position), so the screen equals --print. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <poll.h>
#include <string.h>
#include <sys/ioctl.h>

#include "clock.h"
#include "term_internal.h"

/* Device status request: the terminal answers "\e[0n" once it has
 * handled every byte before it, which is how we know a frame arrived. */
#define STATUS_ASK "\033[5n"
#define ACK_GIVE_UP 8           /* unanswered requests before we stop asking */
#define PACE_MAX_MS 100         /* the longest wait for a busy line */

/* ==== The output queue ==== (the queue itself: outq.c) */

static int out_add(Term *t, const char *p, size_t n)
{
    return outq_add(&t->q, p, n);
}

/* Write what waits; once it has all gone, the status request that went
 * last is timed from then. */
int term_out_pump(Term *t)
{
    int emptied;
    if (outq_pump(&t->q, &emptied))
        return -1;
    if (emptied && t->ack_wait) {
        t->ack_sent_ms = now_ms();
        if (!t->ack_told)
            kp_expect(&t->kp, 1, t->ack_sent_ms);    /* an ESC alone now may be its answer's */
        t->ack_told = 1;
    }
    return 0;
}

/* A status request still in what is forgotten was never sent whole: no
 * answer is waited for. */
void term_out_drop(Term *t)
{
    if (outq_pending(&t->q))
        t->ack_wait = 0;
    outq_drop(&t->q);
}

/* ==== Images ==== */

int term_show_image(const ByteBuf *b)
{
    Term *t = term_session();
    if (!t) {
        errno = EBADF;
        return -1;
    }
    if (t->out_errno || b->err)
        return -1;
    if (pixels_through_mux(&t->pix_scan)) {
        /* through tmux to the outer terminal, at the pane's place now,
         * and only when the pane shows (term_pane_moved says when it
         * shows again) */
        t->pane_known = mux_tmux_pane(&t->pane, MUX_ASK_MS) == 0;
        t->pane_asked_ms = now_ms();
        if (!t->pane_known || !t->pane.pass || !t->pane.shows)
            return 0;
        ByteBuf w = { 0 };
        int bad = mux_wrap(&w, &t->pane, b->b, b->len) || out_add(t, (const char *)w.b, w.len);
        bytebuf_free(&w);
        if (bad) {
            errno = ENOMEM;
            return -1;
        }
    } else if (out_add(t, "\033[H\033[0m", 7) || out_add(t, (const char *)b->b, b->len)) {
        /* from the top left. The cells under the image stay as the screen
         * model has them (the status bar's changes still go out alone); only
         * the cursor and the colours are unknown after it */
        errno = ENOMEM;
        return -1;
    }
    t->vt.cy = -1;
    t->vt.sgr_ok = 0;
    t->pix_shown = 1;
    if (term_out_pump(t)) {
        t->out_errno = errno;
        term_out_drop(t);
        return -1;
    }
    return 0;
}

void term_hide_image(void)
{
    Term *t = term_session();
    if (!t || !t->pix_shown)
        return;
    if (t->pix == PIX_KITTY && pixels_through_mux(&t->pix_scan))
        out_add(t, KITTY_DELETE_ALL_TMUX, sizeof KITTY_DELETE_ALL_TMUX - 1);
    else if (t->pix == PIX_KITTY)
        out_add(t, KITTY_DELETE_ALL, sizeof KITTY_DELETE_ALL - 1);
    vt_invalidate(&t->vt);      /* sixel and iTerm2 images are covered by the cells, all of them */
    t->pix_shown = 0;
}

int term_pane_moved(void)
{
    Term *t = term_session();
    if (!t || !pixels_through_mux(&t->pix_scan) || now_ms() - t->pane_asked_ms < MUX_POLL_MS)
        return 0;
    MuxPane was = t->pane;
    int known = t->pane_known;
    t->pane_known = mux_tmux_pane(&t->pane, MUX_ASK_MS) == 0;
    t->pane_asked_ms = now_ms();
    if (!t->pane_known)
        return 0;
    return !known || was.top != t->pane.top || was.left != t->pane.left || was.shows != t->pane.shows ||
           was.pass != t->pane.pass;
}

int term_pane_poll_ms(void)
{
    Term *t = term_session();
    if (!t || !pixels_through_mux(&t->pix_scan))
        return -1;
    double left = t->pane_asked_ms + MUX_POLL_MS - now_ms();
    return left > 0 ? (int)(left + 0.999) : 0;
}

int term_image_shown(void)
{
    Term *t = term_session();
    return t && t->pix_shown;
}

/* ==== Drawing into the model ==== */

/* The session, its model following the window's size (a new size
 * repaints everything); NULL when there is no session or no memory. */
static Term *fit(void)
{
    Term *t = term_session();
    if (!t)
        return NULL;
    if (t->cols == t->vt.cols && t->rows == t->vt.rows && t->vt.want)
        return t;
    return vt_resize(&t->vt, t->cols, t->rows) ? NULL : t;
}

void term_draw_cells(const CellGrid *g, int top)
{
    Term *t = fit();
    if (!t)
        return;
    for (int r = 0; r < g->rows; r++) {
        const Cell *c = g->cells + (size_t)r * g->cols;
        VtCell *d = vt_at(&t->vt, top + r, 0);
        if (!d)
            break;
        int n = g->cols < t->vt.cols ? g->cols : t->vt.cols;
        /* the same colour keys at the same pixels as --print */
        for (int x = 0; x < n; x++, c++, d++) {
            d->ch = c->ch;
            d->fg = colour_key(&t->quant, c->fg, c->flags & CELL_FG, x, 2 * r);
            d->bg = colour_key(&t->quant, c->bg, c->flags & CELL_BG, x, 2 * r + 1);
            d->attr = 0;
        }
    }
}

void term_draw_bar(int y, const char *text)
{
    Term *t = fit();
    if (!t)
        return;
    int n = vt_text(&t->vt, y, 0, text, t->vt.cols, VT_REVERSE);
    for (int x = n; x < t->vt.cols; x++)
        vt_text(&t->vt, y, x, " ", 1, VT_REVERSE);
}

void term_draw_box(const char *const *lines, int n)
{
    term_draw_box_at(lines, n, -2, -2);
}

void term_bar_cursor(int y, int x)
{
    Term *t = fit();
    if (!t)
        return;
    VtCell *c = vt_at(&t->vt, y, x);
    if (c)
        c->attr = 0;
}

void term_draw_box_at(const char *const *lines, int n, int bx, int by)
{
    Term *t = fit();
    if (t)
        vt_box(&t->vt, lines, n, bx, by);
}

void term_erase(void)
{
    Term *t = fit();
    if (t)
        vt_clear(&t->vt);
}

void term_message(const char *text)
{
    Term *t = fit();
    if (!t)
        return;
    vt_clear(&t->vt);
    int n = (int)strlen(text);
    if (n > t->vt.cols)
        n = t->vt.cols;
    vt_text(&t->vt, t->vt.rows / 2, (t->vt.cols - n) / 2, text, n, 0);
}

/* ==== Sending ==== */

/* The frame joins what waits (nothing, when the caller asked
 * term_ready() first) and goes as far as the terminal takes it now; the
 * rest goes while term_read() waits for keys. */
int term_update(int full)
{
    Term *t = term_session();
    if (!t) {
        errno = EBADF;
        return -1;
    }
    if (t->out_errno) {
        errno = t->out_errno;
        return -1;
    }
    if (!fit()) {
        errno = ENOMEM;
        return -1;
    }
    if (full)
        vt_invalidate(&t->vt);
    if (vt_encode(&t->vt)) {
        errno = ENOMEM;
        return -1;
    }
    if (t->vt.len == 0)
        return 0;
    if (out_add(t, t->vt.buf, t->vt.len)) {
        vt_invalidate(&t->vt);  /* the model took the frame as shown: it is not */
        errno = ENOMEM;
        return -1;
    }
    /* ask for an answer once the frame is through, while the terminal
     * answers at all */
    if (t->ask && !t->ack_wait && (t->acks_seen || t->unanswered < ACK_GIVE_UP) &&
        out_add(t, STATUS_ASK, sizeof STATUS_ASK - 1) == 0) {
        t->ack_wait = 1;
        t->ack_told = 0;
        t->ack_sent_ms = now_ms();      /* again when it has gone (term_out_pump) */
        t->unanswered++;
    }
    t->pace_ms = PACE_MIN_MS;
    if (term_out_pump(t)) {
        t->out_errno = errno;
        term_out_drop(t);
        return -1;
    }
    return 0;
}

size_t term_last_bytes(void)
{
    Term *t = term_session();
    return t ? t->vt.len : 0;
}

int term_ready(void)
{
    Term *t = term_session();
    if (!t || t->out_errno)
        return 1;               /* the next update reports it */
    if (outq_pending(&t->q))
        return 0;               /* the last frame is still being written */
    int queued = 0;
    if (ioctl(t->q.fd, TIOCOUTQ, &queued) != 0)
        queued = 0;             /* not a terminal (the tty benchmark's file) */
    struct pollfd pf = { .fd = t->q.fd, .events = POLLOUT };
    int writable = poll(&pf, 1, 0) != 0;        /* an error: let the write report it */
    double waited = t->ack_wait && t->acks_seen ? now_ms() - t->ack_sent_ms : -1;
    return vt_may_send(queued, writable, waited);
}

int term_pace_ms(void)
{
    Term *t = term_session();
    if (!t)
        return PACE_MIN_MS;
    if (outq_pending(&t->q))
        return PACE_MAX_MS;     /* term_read writes it and says when it is through */
    if (t->ack_wait && t->acks_seen) {
        /* the answer wakes the reader; this is the wait for a lost one */
        double left = VT_ACK_PATIENCE_MS - (now_ms() - t->ack_sent_ms);
        return left > 0 ? (int)left + 1 : 0;
    }
    /* the line is busy: look again soon, less often the longer it is */
    int ms = t->pace_ms;
    t->pace_ms = ms * 2 < PACE_MAX_MS ? ms * 2 : PACE_MAX_MS;
    return ms;
}
