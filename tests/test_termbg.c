/* Tests of the background query (termbg.c): the answer's colour forms,
 * the answers found in any split of the input, and the question asked of
 * a fake terminal on a pty that answers, answers only the attributes (as
 * tmux does when it does not know the colour), or says nothing: the
 * colour when there is one, a wait of one round trip (or the timeout,
 * for silence), no byte of an answer on the screen, and the keys typed
 * meanwhile kept as keys. */

#define _GNU_SOURCE         /* memmem */
#include <criterion/criterion.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "clock.h"
#include "tty.h"

/* ==== The colour forms ==== */

Test(termbg, colour_forms)
{
    uint8_t c[3];
    cr_assert_eq(termbg_parse_colour("rgb:ffff/ffff/ffff", c), 0);
    cr_expect(c[0] == 255 && c[1] == 255 && c[2] == 255);
    cr_assert_eq(termbg_parse_colour("rgb:0000/8080/ffff", c), 0);
    cr_expect(c[0] == 0 && c[1] == 128 && c[2] == 255, "got %d,%d,%d", c[0], c[1], c[2]);
    cr_assert_eq(termbg_parse_colour("rgb:ff/80/0", c), 0);     /* digits per channel may differ */
    cr_expect(c[0] == 255 && c[1] == 128 && c[2] == 0, "got %d,%d,%d", c[0], c[1], c[2]);
    cr_assert_eq(termbg_parse_colour("rgb:f/8/0", c), 0);       /* one digit: 8 of 15 */
    cr_expect(c[0] == 255 && c[1] == 136 && c[2] == 0, "got %d,%d,%d", c[0], c[1], c[2]);
    cr_assert_eq(termbg_parse_colour("rgb:fff/800/000", c), 0); /* three digits: 0x800 of 0xfff */
    cr_expect(c[0] == 255 && c[1] == 128 && c[2] == 0, "got %d,%d,%d", c[0], c[1], c[2]);
    cr_assert_eq(termbg_parse_colour("rgba:2828/2828/2828/ffff", c), 0);   /* rxvt's, with alpha */
    cr_expect(c[0] == 40 && c[1] == 40 && c[2] == 40, "got %d,%d,%d", c[0], c[1], c[2]);
    static const char *const bad[] = { "rgb:ffff/ffff", "rgb:fffff/0/0", "rgb:gg/00/00", "#ffffff", "rgb:/0/0",
                                       "rgb:0/0/0/0", "rgba:0/0/0", "rgb:0/0/", "", "rgb:0/0/0 " };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        cr_expect_eq(termbg_parse_colour(bad[i], c), -1, "'%s' parsed", bad[i]);
}

/* ==== Finding the answers ==== */

static BgScan scan_all(const char *input, size_t piece)
{
    BgScan s;
    termbg_scan_init(&s);
    size_t n = strlen(input);
    for (size_t i = 0; i < n; i += piece)
        termbg_scan(&s, (const unsigned char *)input + i, i + piece <= n ? piece : n - i);
    return s;
}

Test(termbg, answers_in_any_split)
{
    static const char *const ends[] = { "\033\\", "\007" };       /* ST and BEL */
    for (int e = 0; e < 2; e++)
        for (size_t piece = 1; piece <= 8; piece++) {
            char in[128];
            snprintf(in, sizeof in, "q\033[A\033]11;rgb:fafa/f4f4/eded%s\033[?62;22c", ends[e]);
            BgScan s = scan_all(in, piece);
            cr_expect(s.got_bg && s.got_da, "end %d, pieces of %zu: bg %d, da %d", e, piece, s.got_bg, s.got_da);
            cr_expect(s.bg[0] == 250 && s.bg[1] == 244 && s.bg[2] == 237);
        }
}

Test(termbg, other_answers_are_not_the_background)
{
    /* the foreground's answer (OSC 10), a cursor report, a plain DA
     * request echoed back, a cancelled string */
    BgScan s = scan_all("\033]10;rgb:ffff/ffff/ffff\033\\\033[12;40R\033[c\033]11;rgb:0/0/0\030", 1);
    cr_expect(!s.got_bg, "an answer that is not OSC 11 taken for the background");
    cr_expect(!s.got_da, "a CSI without '?' taken for the attributes' answer");
    s = scan_all("\033[?1;2c", 3);
    cr_expect(s.got_da && !s.got_bg, "tmux's answer when it does not know the colour");
}

Test(termbg, the_sgr_report_says_the_colours)
{
    /* real xterm's answer (its direct colour), the same with ';' and no
     * colour-space field, a palette index, a refusal, an SGR without the
     * colour, and a colour that is not the one set */
    static const struct {
        const char *in;
        ColourDepth want;
    } cases[] = {
        { "\033P1$r0;38:2::1:2:3m\033\\", COLOUR_TRUE },  { "\033P1$r38;2;1;2;3m\033\\", COLOUR_TRUE },
        { "\033P1$r0;38:2:0:1:2:3m\033\\", COLOUR_TRUE }, { "\033P1$r0;38;5;16m\033\\", COLOUR_256 },
        { "\033P0$r\033\\", 0 },                        { "\033P1$r0m\033\\", 0 },
        { "\033P1$r38;2;1;2;4m\033\\", 0 },              { "\033]1$r38;2;1;2;3m\033\\", 0 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (size_t piece = 1; piece <= 5; piece += 4) {
            BgScan s = scan_all(cases[i].in, piece);
            cr_expect_eq(s.colour, cases[i].want, "case %zu in pieces of %zu: %d", i, piece, (int)s.colour);
            cr_expect(!s.got_bg, "the SGR report taken for the background");
        }
    BgScan s = scan_all("\033P1$r0;38:2::1:2:3m\033\\\033]11;rgb:0/0/0\007\033[?64;1c", 2);
    cr_expect(s.colour == COLOUR_TRUE && s.got_bg && s.got_da, "all three answers in one read");
}

/* ==== Asking a fake terminal ==== */

/* ANSWER_LATE: both answers after the wait, each with its ESC alone 40 ms
 * before the rest, as a slow ssh link brings them */
/* COLOUR_LATE: the SGR report and the attributes after the wait, as an
 * ssh link slower than the wait brings every answer */
typedef enum { ANSWER_BOTH, ANSWER_DA, SILENT, ANSWER_LATE, COLOUR_LATE } Reply;

typedef struct {
    int     m;              /* the pty's master: the terminal's side */
    Reply   reply;
    char    seen[256];      /* what the program wrote, as the terminal read it */
    size_t  nseen;
} FakeTerm;

/* Read what the program sends; after its question, type "x" and answer
 * as told. Stops at the attributes request (or after a second). */
static void *fake_terminal(void *arg)
{
    FakeTerm *t = arg;
    double until = now_ms() + 1000;
    while (now_ms() < until && !memmem(t->seen, t->nseen, "\033[c", 3)) {
        struct pollfd pf = { .fd = t->m, .events = POLLIN };
        if (poll(&pf, 1, 50) <= 0)
            continue;
        ssize_t r = read(t->m, t->seen + t->nseen, sizeof t->seen - 1 - t->nseen);
        if (r > 0)
            t->nseen += (size_t)r;
    }
    if (t->reply == COLOUR_LATE) {
        ssize_t w = write(t->m, "x", 1);
        usleep((useconds_t)(TERM_ASK_MS + 200) * 1000);
        const char *late = "\033P1$r0;38:2::1:2:3m\033\\\033[?1;2c";
        w = write(t->m, late, strlen(late));
        (void)w;
        return NULL;
    }
    if (t->reply == ANSWER_LATE) {
        static const char *const pieces[] = { "x", "\033", "]11;rgb:ffff/ffff/ffff\033\\\033", "[?1;2c" };
        static const int after_ms[] = { 0, TERMBG_WAIT_MS + 100, 40, 40 };
        for (int i = 0; i < 4; i++) {
            usleep((useconds_t)after_ms[i] * 1000);
            ssize_t w = write(t->m, pieces[i], strlen(pieces[i]));
            (void)w;
        }
        return NULL;
    }
    const char *answer = t->reply == ANSWER_BOTH ? "x\033]11;rgb:ffff/ffff/ffff\033\\\033[?1;2c"
                       : t->reply == ANSWER_DA   ? "x\033[?1;2c"
                                                 : "x";
    ssize_t w = write(t->m, answer, strlen(answer));
    (void)w;
    return NULL;
}

typedef struct {
    int m, s;
    FILE *out, *in;
} Pty;

static void pty_make(Pty *p)
{
    p->m = posix_openpt(O_RDWR | O_NOCTTY);
    cr_assert(p->m >= 0);
    cr_assert_eq(grantpt(p->m), 0);
    cr_assert_eq(unlockpt(p->m), 0);
    p->s = open(ptsname(p->m), O_RDWR | O_NOCTTY);
    cr_assert(p->s >= 0);
    struct winsize ws = { .ws_row = 24, .ws_col = 80 };
    ioctl(p->s, TIOCSWINSZ, &ws);
    p->out = fdopen(p->s, "w");
    p->in = fdopen(dup(p->s), "r");
    cr_assert(p->out && p->in);
}

/* Everything the terminal's side can read within 100 ms. */
static size_t drain(int m, char *buf, size_t cap)
{
    size_t n = 0;
    for (;;) {
        struct pollfd pf = { .fd = m, .events = POLLIN };
        if (poll(&pf, 1, 100) <= 0 || n >= cap)
            break;
        ssize_t r = read(m, buf + n, cap - n);
        if (r <= 0)
            break;
        n += (size_t)r;
    }
    return n;
}

typedef struct {
    int    told;
    uint8_t rgb[3];
    double waited_ms;
    char   screen[8192];    /* what reached the terminal after the question */
    size_t nscreen;
    int    keys[8];         /* the events term_read gave afterwards: keys (-1: another event) */
    int    nkeys;
} Outcome;

/* The viewer's terminal opened as cfg says (its descriptors and TERM
 * filled in) on a pty p whose other side, t on thread th, replies as
 * t->reply says. */
static void open_on_fake(Pty *p, FakeTerm *t, pthread_t *th, TermConfig cfg)
{
    pty_make(p);
    t->m = p->m;
    cr_assert_eq(pthread_create(th, NULL, fake_terminal, t), 0);
    char err[128];
    cfg.out = p->out;
    cfg.in = p->in;
    cfg.termname = "xterm-256color";
    if (term_open(&cfg, err, sizeof err)) {
        pthread_join(*th, NULL);
        cr_skip_test("no xterm-256color description: %s", err);
    }
}

/* The viewer's terminal opened on a pty whose other side replies as
 * told, waiting ask_ms for the answers (0: the viewer's TERM_ASK_MS);
 * then the events that follow. The tests that need an answer in time
 * wait seconds: a shared machine may not run the fake terminal's thread
 * for longer than the viewer's wait. */
static Outcome open_and_ask(Reply reply, int ask_ms)
{
    Pty p;
    FakeTerm t = { .reply = reply };
    pthread_t th;
    open_on_fake(&p, &t, &th, (TermConfig){ .colour = COLOUR_TRUE, .ask_bg = 1, .ask_ms = ask_ms });
    Outcome o = { 0 };
    o.told = term_background(o.rgb, &o.waited_ms);
    /* the answers read by the parser, the keys left: nothing but x (the
     * late answers come while the events are read) */
    TermEvent ev;
    while (o.nkeys < 8 && term_read(&ev, reply == ANSWER_LATE ? 1000 : 120) == 1)
        o.keys[o.nkeys++] = ev.type == TE_KEY ? ev.key : -1;
    pthread_join(th, NULL);
    cr_assert(memmem(t.seen, t.nseen, "\033]11;?", 6), "the question was not asked");
    o.nscreen = drain(p.m, o.screen, sizeof o.screen - 1);
    term_restore();
    fclose(p.out);
    fclose(p.in);
    close(p.m);
    return o;
}

/* The waits of the tests: an answer ends a long wait long before its
 * end; silence costs the whole of a short one, once. */
enum { ANSWER_WAIT_MS = 5000, SILENT_WAIT_MS = 400 };

/* No byte of an answer came back to the screen (the input does not echo). */
static void expect_nothing_echoed(const Outcome *o)
{
    cr_expect_null(memmem(o->screen, o->nscreen, "rgb:", 4), "the answer was echoed to the screen");
    cr_expect_null(memmem(o->screen, o->nscreen, "?1;2c", 5), "the attributes' answer was echoed");
}

static void expect_only_x(const Outcome *o)
{
    cr_expect_eq(o->nkeys, 1, "%d events after the question, wanted the one key typed", o->nkeys);
    cr_expect_eq(o->nkeys ? o->keys[0] : 0, 'x', "the key typed during the question");
}

Test(termbg, a_terminal_that_answers, .timeout = 30)
{
    Outcome o = open_and_ask(ANSWER_BOTH, ANSWER_WAIT_MS);
    cr_expect(o.told, "the answer was not read");
    cr_expect(o.rgb[0] == 255 && o.rgb[1] == 255 && o.rgb[2] == 255);
    cr_expect_lt(o.waited_ms, ANSWER_WAIT_MS / 2, "an answering terminal kept us %.1f ms", o.waited_ms);
    expect_nothing_echoed(&o);
    expect_only_x(&o);
}

Test(termbg, a_terminal_that_answers_only_the_attributes, .timeout = 30)
{
    Outcome o = open_and_ask(ANSWER_DA, ANSWER_WAIT_MS);
    cr_expect(!o.told);
    cr_expect_lt(o.waited_ms, ANSWER_WAIT_MS / 2, "the attributes' answer did not end the wait (%.1f ms)",
                 o.waited_ms);
    expect_nothing_echoed(&o);
    expect_only_x(&o);
}

Test(termbg, a_silent_terminal_costs_the_timeout_once, .timeout = 30)
{
    Outcome o = open_and_ask(SILENT, SILENT_WAIT_MS);
    cr_expect(!o.told);
    /* every question of the start in one write, one wait (issue 33):
     * the whole wait, and not a second (the slack is a loaded machine's) */
    cr_expect(o.waited_ms >= SILENT_WAIT_MS - 1 && o.waited_ms < 2 * SILENT_WAIT_MS,
              "a silent terminal kept us %.1f ms (timeout %d)", o.waited_ms, SILENT_WAIT_MS);
    expect_only_x(&o);
}

/* Issue 28: the answers after the wait, each split after its ESC by a
 * gap longer than the Esc key's: the ESC was read as Esc (which quits),
 * the rest as keys. Awaited answers wait for their rest. */
Test(termbg, late_answers_split_after_their_esc_are_no_keys, .timeout = 30)
{
    Outcome o = open_and_ask(ANSWER_LATE, 0);
    cr_expect(!o.told, "the colour came after the wait");
    expect_nothing_echoed(&o);
    expect_only_x(&o);
}

Test(termbg, an_answer_after_the_wait_is_dropped_whole, .timeout = 30)
{
    /* the parser alone: a late answer among keys gives the keys only */
    KeyParser kp;
    kp_init(&kp, 1);
    const char late[] = "a\033]11;rgb:ffff/ffff/ffff\033\\\033[?62;22cb";
    kp_push(&kp, late, sizeof late - 1, 0);
    TermEvent ev;
    int keys[8], n = 0;
    while (n < 8 && kp_next(&kp, &ev, 1000))
        keys[n++] = ev.type == TE_KEY ? ev.key : -1;
    cr_expect_eq(n, 2, "%d events from a late answer between two keys", n);
    cr_expect(n == 2 && keys[0] == 'a' && keys[1] == 'b');
}

/* The colour question's answer after the wait (a link slower than
 * TERM_ASK_MS): the frames before it are in the environment's 256
 * colours; when it comes, the viewer hears of it as of a new window and
 * draws in 24 bits from then on. Nothing of it is a key. */
Test(termbg, a_late_colour_answer_is_taken_when_it_comes, .timeout = 30)
{
    Pty p;
    FakeTerm t = { .reply = COLOUR_LATE };
    pthread_t th;
    open_on_fake(&p, &t, &th, (TermConfig){ .colour = COLOUR_256, .colour_env = 1 });
    cr_expect(memmem(t.seen, t.nseen, "\033P$qm", 5), "the SGR was asked back");
    cr_expect_eq(term_colour(), COLOUR_256, "before the answer: the environment's");
    TermEvent ev;
    int keys = 0, resized = 0, other = 0;
    while (term_read(&ev, 1500) == 1 && !resized) {
        if (ev.type == TE_KEY)
            keys += ev.key == 'x' ? 1 : 100;
        else if (ev.type == TE_RESIZE)
            resized = 1;
        else if (ev.type != TE_READY)
            other++;
    }
    pthread_join(th, NULL);
    cr_expect(resized, "the late answer is told as a new window");
    cr_expect_eq(term_colour(), COLOUR_TRUE, "after it: 24 bits");
    cr_expect(term_colour_answered());
    while (term_read(&ev, 200) == 1)
        if (ev.type == TE_KEY)
            keys += ev.key == 'x' ? 1 : 100;
    cr_expect_eq(keys, 1, "the key typed, and no key of the answer (%d)", keys);
    cr_expect_eq(other, 0);
    term_restore();
    fclose(p.out);
    fclose(p.in);
    close(p.m);
}
