/* termgfx.c: does this terminal draw pixels, and in which protocol?
 *
 * Asked, not guessed from the environment: the kitty graphics query (a
 * one-pixel image that is only checked, a=q, which a terminal speaking
 * the protocol answers "OK"), the terminal's name (XTVERSION: iTerm2
 * says its own, and its inline images are the one protocol with no
 * query) and then the primary device attributes (ESC [ c), which every
 * terminal since the VT100 answers, a 4 among them meaning sixel
 * graphics. kitty's protocol is preferred (PNG, replaced in place), then
 * iTerm2's, then sixel. The attributes' answer comes last, so once
 * it is in, the kitty answer is in too or is not coming: one round trip.
 * Multiplexers are the exception: tmux and screen answer the attributes
 * themselves and pass no images by default. Inside screen the answer is
 * cells without a question; inside tmux, tmux's own attributes are asked
 * (3.4 built with sixel draws it) and, when its passthrough is on, the
 * questions go through it to the outer terminal (mux.c). */

#include <errno.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "clock.h"
#include "tty.h"

/* kitty's query, the terminal's name and version (XTVERSION, which
 * iTerm2, WezTerm, kitty, foot and xterm answer), the device attributes */
#define QUESTION "\033_Gi=31,s=1,v=1,a=q,t=d,f=24;AAAA\033\\\033[>0q\033[c"

/* APC and DCS strings are read alike: their body up to ST */
enum { S_GROUND, S_ESC, S_CSI, S_APC, S_APC_ESC };

int pixels_cell_size(int fd, int *cw, int *ch)
{
    struct winsize ws;
    if (ioctl(fd, TIOCGWINSZ, &ws) != 0 || !ws.ws_col || !ws.ws_row || !ws.ws_xpixel || !ws.ws_ypixel)
        return 0;
    *cw = ws.ws_xpixel / ws.ws_col;
    *ch = ws.ws_ypixel / ws.ws_row;
    return *cw > 0 && *ch > 0;
}

void pixels_scan_init(PixelScan *s, int c1)
{
    memset(s, 0, sizeof *s);
    s->c1 = c1;
}

/* The attributes' answer "ESC [ ? 6 2 ; 4 ; 2 2 c": is 4 among them? */
static void da_done(PixelScan *s)
{
    s->body[s->len < sizeof s->body ? s->len : sizeof s->body - 1] = 0;
    int four = 0;
    const char *p = s->body + (s->body[0] == '?');
    while (*p) {
        char *end;
        long v = strtol(p, &end, 10);
        if (end != p && v == 4)
            four = 1;
        p = *end ? end + 1 : end;
    }
    /* tmux answers its own question at once, before the outer terminal's
     * answer to the one passed through can be back */
    if (s->mux_das > 0) {
        s->mux_das--;
        s->mux_sixel |= four;
        return;
    }
    s->got_da = 1;
    s->sixel |= four;
}

/* A kitty answer "ESC _ G i=31 ; OK ESC \", or the name's "ESC P > |
 * iTerm2 3.5.0 ESC \" */
static void apc_done(PixelScan *s)
{
    s->body[s->len < sizeof s->body ? s->len : sizeof s->body - 1] = 0;
    if (s->body[0] == 'G' && strstr(s->body, "i=31") && strstr(s->body, ";OK"))
        s->kitty = 1;
    if (!strncmp(s->body, ">|iTerm2", 8))
        s->iterm = 1;
}

static void scan_byte(PixelScan *s, unsigned char c)
{
    switch (s->state) {
    case S_GROUND:
        s->len = 0;
        s->state = c == 0x1b ? S_ESC : !s->c1 ? S_GROUND : c == 0x9b ? S_CSI : c == 0x90 || c == 0x9f ? S_APC : S_GROUND;
        break;
    case S_ESC:
        s->len = 0;
        s->state = c == '[' ? S_CSI : c == '_' || c == 'P' ? S_APC : c == 0x1b ? S_ESC : S_GROUND;
        break;
    case S_CSI:
        if (c >= 0x40 && c <= 0x7e) {
            if (c == 'c' && s->len && s->body[0] == '?')
                da_done(s);
            s->state = S_GROUND;
        } else if (c < 0x20 || c > 0x7e) {
            s->state = c == 0x1b ? S_ESC : S_GROUND;
        } else if (s->len < sizeof s->body - 1) {
            s->body[s->len++] = (char)c;
        }
        break;
    case S_APC:
        if (c == 0x1b) {
            s->state = S_APC_ESC;
        } else if (c == 0x9c && s->c1) {
            apc_done(s);
            s->state = S_GROUND;
        }
        else if (c == 0x18 || c == 0x1a)
            s->state = S_GROUND;
        else if (s->len < sizeof s->body - 1)
            s->body[s->len++] = (char)c;
        break;
    default:    /* S_APC_ESC */
        if (c == '\\')
            apc_done(s);
        s->len = 0;
        s->state = c == '[' ? S_CSI : c == '_' || c == 'P' ? S_APC : S_GROUND;
        break;
    }
}

void pixels_scan(PixelScan *s, const unsigned char *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        scan_byte(s, b[i]);
}

PixelProto pixels_from_env(void)
{
    const char *term = getenv("TERM");
    if (!term || !*term || !strcmp(term, "dumb") || !strcmp(term, "linux"))
        return PIX_CELLS;   /* would show the question, or knows no images */
    if ((getenv("TMUX") && *getenv("TMUX")) || (getenv("STY") && *getenv("STY")) ||
        !strncmp(term, "screen", 6) || !strncmp(term, "tmux", 4))
        return PIX_CELLS;
    return PIX_AUTO;
}

PixelProto pixels_scanned(const PixelScan *s)
{
    if (s->mux_sixel)
        return PIX_SIXEL;       /* a tmux that draws sixel itself: no passthrough needed */
    return s->kitty ? PIX_KITTY : s->iterm ? PIX_ITERM : s->sixel ? PIX_SIXEL : PIX_CELLS;
}

int pixels_through_mux(const PixelScan *s)
{
    return s->via_mux && !s->mux_sixel && pixels_scanned(s) != PIX_CELLS;
}

/* Write the questions q[0..left) and read the answers until the
 * attributes' (the last) or wait_ms. */
static PixelProto ask(int out_fd, int in_fd, const char *q, size_t left, int wait_ms, PixelSink sink, void *ctx,
                      PixelScan *s)
{
    double until = now_ms() + wait_ms;
    while (left) {
        ssize_t w = write(out_fd, q, left);
        if (w > 0) {
            q += w;
            left -= (size_t)w;
        } else if (!(w < 0 && (errno == EINTR || errno == EAGAIN)) || now_ms() > until) {
            return PIX_CELLS;
        }
    }
    while (!s->got_da) {
        double rest = until - now_ms();
        struct pollfd pf = { .fd = in_fd, .events = POLLIN };
        if (rest <= 0 || poll(&pf, 1, (int)rest + 1) <= 0)
            break;
        unsigned char buf[256];
        ssize_t r = read(in_fd, buf, sizeof buf);
        if (r <= 0) {
            if (r < 0 && (errno == EINTR || errno == EAGAIN))
                continue;
            break;
        }
        pixels_scan(s, buf, (size_t)r);
        if (sink)
            sink(ctx, buf, (size_t)r);
    }
    return pixels_scanned(s);
}

PixelProto pixels_detect(int out_fd, int in_fd, int wait_ms, PixelSink sink, void *ctx, PixelScan *s)
{
    if (pixels_from_env() == PIX_CELLS)
        return PIX_CELLS;
    return ask(out_fd, in_fd, QUESTION, sizeof QUESTION - 1, wait_ms, sink, ctx, s);
}

/* tmux's own attributes first (3.4 built with sixel lists 4), then, with
 * passthrough, the questions again for the outer terminal, its ESCs
 * doubled: one write */
#define TMUX_OWN  "\033[c"
#define TMUX_PASS "\033Ptmux;\033\033_Gi=31,s=1,v=1,a=q,t=d,f=24;AAAA\033\033\\\033\033[>0q\033\033[c\033\\"

const char *pixels_question(PixelAsk how)
{
    return how == PIXQ_TMUX_PASS ? TMUX_OWN TMUX_PASS : how == PIXQ_TMUX ? TMUX_OWN : QUESTION;
}

void pixels_scan_expect(PixelScan *s, PixelAsk how)
{
    s->mux_das = s->via_mux = how == PIXQ_TMUX_PASS;
}
