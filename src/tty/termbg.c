/* termbg: asking the terminal for its background colour.
 *
 * The question is xterm's colour query, OSC 11 with "?" for the colour
 * (ESC ] 11 ; ? ST); a terminal that knows answers ESC ] 11 ; rgb:R/G/B
 * and BEL or ST, each channel 1 to 4 hex digits (XParseColor's form;
 * rxvt adds an alpha, rgba:R/G/B/A). Many terminals do not answer it,
 * and silence cannot be told from slowness. So a second question follows
 * the first: primary device attributes (ESC [ c), which every terminal
 * since the VT100 answers (ESC [ ? ... c), and in order: once its answer
 * is in, the colour's answer is in too or will never come. The wait ends
 * there, or after wait_ms for a terminal that answers neither.
 *
 * tmux answers both itself: the colour only when it knows the pane's
 * (window-style, select-pane -P, or what the outer terminal told it),
 * the attributes always; so under tmux the colour is known or not, and
 * either way the wait is one round trip.
 *
 * Nothing read is lost or shown: the bytes go to the key parser (keys
 * the user typed meanwhile stay keys; the answers are strings and a CSI
 * sequence it drops whole, also when they come after the wait). */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include "clock.h"
#include "tty.h"

#define ESC 0x1b
#define Q_BG     "\033]11;?\033\\"
/* a 24-bit colour set, the SGR asked back (DECRQSS), the SGR reset: a
 * terminal that draws 24 bits answers DCS 1 $ r ... 38:2::1:2:3 m ST */
#define Q_COLOUR "\033[38;2;1;2;3m\033P$qm\033\\\033[m"
#define Q_DA     "\033[c"

/* ==== The answer ==== */

static int hex_digit(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                                                                                      : -1;
}

/* One channel of 1 to 4 hex digits up to stop (or the end), scaled to a
 * byte as XParseColor scales it (h / (16^n - 1)). Returns the end, or
 * NULL. */
static const char *channel(const char *s, char stop, uint8_t *out)
{
    unsigned v = 0, top = 1;
    int n = 0;
    for (; *s && *s != stop; s++, n++) {
        int d = hex_digit(*s);
        if (d < 0 || n == 4)
            return NULL;
        v = v * 16 + (unsigned)d;
        top *= 16;
    }
    if (n == 0)
        return NULL;
    *out = (uint8_t)((v * 255 + (top - 1) / 2) / (top - 1));
    return s;
}

int termbg_parse_colour(const char *spec, uint8_t rgb_out[3])
{
    const char *s;
    int alpha = 0;
    if (!strncmp(spec, "rgb:", 4))
        s = spec + 4;
    else if (!strncmp(spec, "rgba:", 5))
        s = spec + 5, alpha = 1;
    else
        return -1;
    uint8_t rgb[3], a;
    for (int k = 0; k < 3; k++) {
        int last = k == 2 && !alpha;
        s = channel(s, last ? 0 : '/', &rgb[k]);
        if (!s || (last ? *s != 0 : *s != '/'))
            return -1;
        if (!last)
            s++;
    }
    if (alpha && (!(s = channel(s, 0, &a)) || *s))
        return -1;
    memcpy(rgb_out, rgb, 3);
    return 0;
}

/* ==== Reading the answers out of the input ==== */

enum { S_GROUND, S_ESC, S_CSI, S_OSC, S_OSC_ESC };

void termbg_scan_init(BgScan *s)
{
    memset(s, 0, sizeof *s);
}

/* The SGR report "1$r0;38:2::1:2:3m" (or with ';', with or without the
 * colour space's empty field): the 24-bit colour set before came back
 * as set (COLOUR_TRUE), as a palette index (38;5;N: COLOUR_256), or not
 * at all (0). */
static ColourDepth sgr_report(const char *body)
{
    if (strncmp(body, "1$r", 3))
        return 0;
    long tok[16];
    int n = 0;
    for (const char *p = body + 3; *p && *p != 'm' && n < 16;) {
        char *end;
        long v = strtol(p, &end, 10);
        tok[n++] = end == p ? -1 : v;       /* an empty field: -1 */
        p = end;
        if (*p == ';' || *p == ':')
            p++;
        else if (*p != 'm')
            return 0;                       /* not an SGR list */
    }
    for (int i = 0; i + 1 < n; i++) {
        if (tok[i] != 38)
            continue;
        if (tok[i + 1] == 5)
            return COLOUR_256;
        if (tok[i + 1] != 2)
            continue;
        /* 38:2::1:2:3 has the colour space's field (empty or a number) */
        for (int at = i + 2; at <= i + 3 && at + 2 < n; at++)
            if (tok[at] == 1 && tok[at + 1] == 2 && tok[at + 2] == 3)
                return COLOUR_TRUE;
    }
    return 0;
}

/* A string has ended: is it the background's answer, or the SGR's? */
static void osc_done(BgScan *s)
{
    s->body[s->len] = 0;
    if (s->dcs) {
        ColourDepth c = sgr_report(s->body);
        if (c > s->colour)
            s->colour = c;
    } else if (!strncmp(s->body, "11;", 3) && termbg_parse_colour(s->body + 3, s->bg) == 0) {
        s->got_bg = 1;
    }
}

/* One byte of the input. A CSI sequence that starts with '?' and ends in
 * 'c' is the attributes' answer; the body of a string is kept (its
 * first TERMBG_BODY_MAX bytes) until BEL or ST. */
static void scan_byte(BgScan *s, unsigned char c)
{
    switch (s->state) {
    case S_GROUND:
        s->state = c == ESC ? S_ESC : S_GROUND;
        break;
    case S_ESC:
        s->len = 0;
        s->csi_private = 0;
        s->dcs = c == 'P';
        s->state = c == '[' ? S_CSI : c == ']' || c == 'P' ? S_OSC : c == ESC ? S_ESC : S_GROUND;
        break;
    case S_CSI:
        if (s->len++ == 0 && c == '?')
            s->csi_private = 1;
        if (c >= 0x40 && c <= 0x7e) {
            if (c == 'c' && s->csi_private)
                s->got_da = 1;
            s->state = S_GROUND;
        } else if (c < 0x20 || c > 0x7e) {
            s->state = c == ESC ? S_ESC : S_GROUND;     /* not a CSI sequence after all */
        }
        break;
    case S_OSC:
        if (c == 7) {
            osc_done(s);
            s->state = S_GROUND;
        } else if (c == ESC) {
            s->state = S_OSC_ESC;
        } else if (c == 0x18 || c == 0x1a) {
            s->state = S_GROUND;                        /* CAN, SUB: cancelled */
        } else if (s->len < TERMBG_BODY_MAX) {
            s->body[s->len++] = (char)c;
        }
        break;
    default:    /* S_OSC_ESC */
        if (c == '\\')
            osc_done(s);
        s->len = 0;
        s->csi_private = 0;
        s->dcs = c == 'P';
        s->state = c == '\\' ? S_GROUND : c == '[' ? S_CSI : c == ']' || c == 'P' ? S_OSC : S_GROUND;
        break;
    }
}

void termbg_scan(BgScan *s, const unsigned char *b, size_t n)
{
    for (size_t i = 0; i < n; i++)
        scan_byte(s, b[i]);
}

/* ==== Asking ==== */

/* The questions, whole, to a descriptor that may be non-blocking. */
static int send_question(int fd, int wait_ms, const char *p, size_t left)
{
    while (left) {
        ssize_t w = write(fd, p, left);
        if (w > 0) {
            p += w;
            left -= (size_t)w;
            continue;
        }
        if (w < 0 && errno == EINTR)
            continue;
        struct pollfd pf = { .fd = fd, .events = POLLOUT };
        if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) && poll(&pf, 1, wait_ms) > 0)
            continue;
        return -1;
    }
    return 0;
}

int termbg_ask(int out_fd, int in_fd, int wait_ms, KeyParser *kp, const TermQuestions *q, TermAnswers *ans)
{
    double t0 = now_ms(), until = t0 + wait_ms;
    BgScan s;
    termbg_scan_init(&s);
    /* one write: the background, the colours, the pixels' questions,
     * whose last is the attributes' (else the attributes alone) */
    char buf[512];
    const char *pq = q->pix != PIXQ_NONE ? pixels_question(q->pix) : Q_DA;
    int n = snprintf(buf, sizeof buf, "%s%s%s", q->ask_bg ? Q_BG : "", q->ask_colour ? Q_COLOUR : "", pq);
    PixelScan *pix = q->pix != PIXQ_NONE ? q->scan : NULL;
    if (pix)
        pixels_scan_expect(pix, q->pix);
    int sent = n > 0 && (size_t)n < sizeof buf && send_question(out_fd, wait_ms, buf, (size_t)n) == 0;
    /* the attributes' answers (tmux's and the outer terminal's), however
     * late, are no Esc */
    if (sent && kp)
        kp_expect(kp, 1 + (q->pix == PIXQ_TMUX_PASS), now_ms());
    while (sent && !(pix ? pix->got_da : s.got_da)) {
        double left = until - now_ms();
        struct pollfd pf = { .fd = in_fd, .events = POLLIN };
        if (left <= 0 || poll(&pf, 1, (int)left + 1) <= 0)
            break;
        unsigned char rb[256];
        size_t room = kp ? sizeof kp->b - kp->len : sizeof rb;
        ssize_t r = read(in_fd, rb, room < sizeof rb ? room : sizeof rb);
        if (r <= 0) {
            if (r < 0 && (errno == EINTR || errno == EAGAIN))
                continue;
            break;              /* the input's end: term_read finds it too */
        }
        termbg_scan(&s, rb, (size_t)r);
        if (pix)
            pixels_scan(pix, rb, (size_t)r);
        if (kp)
            kp_push(kp, rb, (size_t)r, now_ms());
    }
    memset(ans, 0, sizeof *ans);
    ans->waited_ms = now_ms() - t0;
    ans->got_bg = s.got_bg;
    memcpy(ans->bg, s.bg, 3);
    ans->colour = s.colour;
    ans->answered = pix ? pix->got_da : s.got_da;
    ans->scan = s;
    return s.got_bg;
}

int termbg_ask_tty(int wait_ms, uint8_t rgb_out[3])
{
    /* a terminal that says it knows no escapes would show the question */
    const char *term = getenv("TERM");
    if (!term || !*term || !strcmp(term, "dumb"))
        return 0;
    int fd = open("/dev/tty", O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (fd < 0)
        return 0;
    /* only in the foreground: a job in the background that touched the
     * terminal's modes would be stopped (SIGTTOU) */
    struct termios old, raw;
    int got = 0;
    if (tcgetpgrp(fd) == getpgrp() && tcgetattr(fd, &old) == 0) {
        raw = old;
        raw.c_lflag &= (tcflag_t) ~(ICANON | ECHO);     /* the answer neither waits for a line nor shows */
        raw.c_cc[VMIN] = 1;
        raw.c_cc[VTIME] = 0;
        if (tcsetattr(fd, TCSANOW, &raw) == 0) {
            TermAnswers ans;
            TermQuestions q = { .ask_bg = 1 };
            got = termbg_ask(fd, fd, wait_ms, NULL, &q, &ans);
            if (got)
                memcpy(rgb_out, ans.bg, 3);
            tcsetattr(fd, TCSANOW, &old);
        }
    }
    close(fd);
    return got;
}
