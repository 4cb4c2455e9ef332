/* mux.c: the terminal multiplexer zview may run in (tmux, GNU screen),
 * and images through tmux's passthrough.
 *
 * tmux answers the device attributes itself and, unless it draws sixel
 * itself (3.4+ built with it, whose answer then lists 4), keeps images
 * from the outer terminal; with allow-passthrough on, the body of
 * "DCS tmux; ... ST" goes to the outer terminal as it is, its ESCs
 * doubled. The outer terminal draws the image at its own cursor, not at
 * the pane's, so the body first moves that cursor to the pane's top left
 * (the pane's place on the client, which tmux tells: `display -p`), and
 * puts it back after. tmux asked the same way says whether passthrough
 * is on and whether the pane shows at all (its window the current one,
 * no other pane zoomed): an image goes only to a pane that shows.
 * GNU screen passes no images that we can place: cells. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "clock.h"
#include "tty.h"

extern char **environ;

/* What tmux is asked: the pane's place, the option, whether it shows */
#define MUX_FORMAT "#{pane_top} #{pane_left} #{allow-passthrough} #{window_active} " \
                   "#{window_zoomed_flag} #{pane_active} #{session_attached}"

MuxKind mux_from_env(void)
{
    /* screen first: inside or outside tmux, it passes no images on */
    const char *term = getenv("TERM"), *tmux = getenv("TMUX"), *sty = getenv("STY");
    if (sty && *sty)
        return MUX_SCREEN;
    if ((tmux && *tmux) || (term && !strncmp(term, "tmux", 4)))
        return MUX_TMUX;
    if (term && !strncmp(term, "screen", 6))
        return MUX_SCREEN;
    return MUX_NONE;
}

int mux_parse_pane(const char *s, MuxPane *m)
{
    int top, left, pass, active, zoomed, pane_active, clients, used = 0;
    if (sscanf(s, "%d %d %d %d %d %d %d%n", &top, &left, &pass, &active, &zoomed, &pane_active, &clients, &used) != 7 ||
        top < 0 || left < 0 || top > 9999 || left > 9999 || (s[used] && s[used] != '\n'))
        return -1;
    m->top = top;
    m->left = left;
    m->pass = pass == 1;
    m->shows = active == 1 && (zoomed != 1 || pane_active == 1);
    m->attached = clients > 0;
    return 0;
}

/* The pane named by TMUX_PANE ("%12"), or NULL when it is not one. */
static const char *own_pane(void)
{
    const char *p = getenv("TMUX_PANE");
    if (!p || p[0] != '%' || !p[1] || strlen(p) > 12)
        return NULL;
    for (const char *c = p + 1; *c; c++)
        if (*c < '0' || *c > '9')
            return NULL;
    return p;
}

int mux_tmux_pane(MuxPane *m, int wait_ms)
{
    const char *pane = own_pane();
    if (!pane)
        return -1;
    int fds[2];
    if (pipe(fds))
        return -1;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    char *argv[] = { "tmux", "display-message", "-p", "-t", (char *)pane, MUX_FORMAT, NULL };
    pid_t pid;
    int bad = posix_spawnp(&pid, "tmux", &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(fds[1]);
    char buf[128];
    size_t len = 0;
    int ended = 0;
    double until = now_ms() + wait_ms;
    while (!bad && !ended && len < sizeof buf - 1) {
        double rest = until - now_ms();
        struct pollfd pf = { .fd = fds[0], .events = POLLIN };
        if (rest <= 0 || poll(&pf, 1, (int)rest + 1) <= 0)
            break;
        ssize_t r = read(fds[0], buf + len, sizeof buf - 1 - len);
        if (r < 0 && errno == EINTR)
            continue;
        ended = r <= 0;
        len += r > 0 ? (size_t)r : 0;
    }
    close(fds[0]);
    buf[len] = 0;
    if (!bad) {
        if (!ended) {
            kill(pid, SIGKILL);     /* a tmux that hangs: the answer is no */
            len = 0;
        }
        int status;
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
            ;
    }
    return bad || !len ? -1 : mux_parse_pane(buf, m);
}

int mux_wrap(ByteBuf *out, const MuxPane *m, const unsigned char *b, size_t n)
{
    char at[40];
    /* the outer cursor saved, moved to the pane's corner, put back */
    int k = snprintf(at, sizeof at, "\033\0337\033\033[%d;%dH", m->top + 1, m->left + 1);
    bytebuf_puts(out, "\033Ptmux;");
    bytebuf_put(out, at, (size_t)k);
    size_t from = 0;
    for (size_t i = 0; i < n; i++)
        if (b[i] == 0x1b) {
            bytebuf_put(out, b + from, i + 1 - from);
            from = i;           /* the ESC again, with what follows */
        }
    bytebuf_put(out, b + from, n - from);
    bytebuf_puts(out, "\033\0338\033\\");
    return out->err ? -1 : 0;
}

const char *mux_why_cells(MuxKind k, const MuxPane *m, int brief)
{
    if (k == MUX_SCREEN)
        return brief ? "screen: cells, no images" : "GNU screen passes no images to the terminal";
    if (k == MUX_TMUX && m && !m->pass && m->attached)
        return brief ? "tmux: set -g allow-passthrough on" : "tmux passes no images: set -g allow-passthrough on";
    return NULL;
}
