/* Tests of the key parser (keys.c): byte strings as terminals send them
 * in, events out. Every form of the cursor and editing keys, mouse
 * reports, and the sequences that must be dropped whole (never read as
 * an Esc, which quits, followed by keys). */

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "tty.h"

#define MAXEV 64

typedef struct {
    TermEvent ev[MAXEV];
    int n;
} Events;

/* Feed s in pieces of `chunk` bytes (0: all at once), taking the events
 * after each piece as they come (the input not quiet), then once more
 * after a long quiet (what a lone ESC or an unfinished sequence becomes). */
static Events feed_chunked(KeyParser *p, const char *s, size_t len, size_t chunk)
{
    Events e = { .n = 0 };
    TermEvent ev;
    size_t off = 0;
    if (!chunk)
        chunk = len ? len : 1;
    while (off < len) {
        size_t n = len - off < chunk ? len - off : chunk;
        cr_assert_eq(kp_push(p, s + off, n), n);
        off += n;
        while (e.n < MAXEV && kp_next(p, &ev, 0))
            e.ev[e.n++] = ev;
    }
    while (e.n < MAXEV && kp_next(p, &ev, 1e9))
        e.ev[e.n++] = ev;
    return e;
}

static Events feed(const char *s, size_t len)
{
    KeyParser p;
    kp_init(&p, 1);
    return feed_chunked(&p, s, len, 0);
}

#define FEED(lit) feed(lit, sizeof lit - 1)

/* The events as text, for failure messages. */
static const char *show(const Events *e)
{
    static char buf[1024];
    size_t o = 0;
    buf[0] = 0;
    for (int i = 0; i < e->n && o < sizeof buf - 64; i++) {
        const TermEvent *v = &e->ev[i];
        o += (size_t)snprintf(buf + o, sizeof buf - o, "%s{t%d k%#x b%d d%d,%d at %d,%d}", i ? " " : "",
                              v->type, (unsigned)v->key, v->button, v->dx, v->dy, v->x, v->y);
    }
    return e->n ? buf : "(none)";
}

static void expect_keys(const char *what, Events e, const int *keys, int n)
{
    cr_expect_eq(e.n, n, "%s: %d events, wanted %d: %s", what, e.n, n, show(&e));
    for (int i = 0; i < e.n && i < n; i++)
        cr_expect(e.ev[i].type == TE_KEY && e.ev[i].key == keys[i], "%s: event %d is %s, wanted key %#x",
                  what, i, show(&e), (unsigned)keys[i]);
}

#define EXPECT_KEYS(what, lit, ...)                                               \
    do {                                                                          \
        const int want_[] = { __VA_ARGS__ };                                      \
        expect_keys(what, FEED(lit), want_, (int)(sizeof want_ / sizeof *want_)); \
    } while (0)

#define EXPECT_NONE(what, lit)                                                    \
    do {                                                                          \
        Events e_ = FEED(lit);                                                    \
        cr_expect_eq(e_.n, 0, "%s: dropped whole, got %s", what, show(&e_));      \
    } while (0)

/* ==== Characters and control keys ==== */

Test(keys, characters_and_control_keys)
{
    EXPECT_KEYS("letters", "qO", 'q', 'O');
    EXPECT_KEYS("Return is Enter either way", "\r\n", TK_ENTER, TK_ENTER);
    EXPECT_KEYS("^H and DEL are Backspace", "\b\x7f", TK_BACKSPACE, TK_BACKSPACE);
    EXPECT_KEYS("Tab, Ctrl-L, Ctrl-U", "\t\x0c\x15", TK_TAB, TK_CTRL_L, 0x15);
    EXPECT_KEYS("UTF-8", "\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80", 0xe9, 0x20ac, 0x1f600);
    EXPECT_KEYS("invalid UTF-8 bytes are dropped, the rest kept", "a\xff\xc0\x80" "b", 'a', 'b');
}

Test(keys, a_character_split_across_reads_is_one_key)
{
    KeyParser p;
    kp_init(&p, 1);
    Events e = feed_chunked(&p, "\xe2\x82\xac", 3, 1);
    expect_keys("one byte at a time", e, (int[]){ 0x20ac }, 1);
}

Test(keys, without_utf8_a_byte_is_its_code_point)
{
    KeyParser p;
    kp_init(&p, 0);
    Events e = feed_chunked(&p, "\xe9" "a", 2, 0);
    expect_keys("latin-1", e, (int[]){ 0xe9, 'a' }, 2);
}

/* ==== Esc ==== */

Test(keys, a_lone_esc_is_esc_once_the_input_is_quiet)
{
    KeyParser p;
    kp_init(&p, 1);
    TermEvent ev;
    kp_push(&p, "\033", 1);
    cr_expect_eq(kp_next(&p, &ev, 0), 0, "an ESC just read may start a sequence");
    cr_expect_eq(kp_wait_ms(&p), KP_ESC_MS);
    cr_expect_eq(kp_next(&p, &ev, KP_ESC_MS - 1), 0, "not quiet long enough yet");
    cr_expect_eq(kp_next(&p, &ev, KP_ESC_MS), 1);
    cr_expect(ev.type == TE_KEY && ev.key == TK_ESC);
    cr_expect_eq(kp_wait_ms(&p), -1, "nothing left to wait for");
    EXPECT_KEYS("Esc twice", "\033\033", TK_ESC, TK_ESC);
    EXPECT_KEYS("Esc, then q later", "\033", TK_ESC);
}

/* Esc typed just before a key arrives with it (tmux joins the two when
 * they come within its escape-time): both are read, as curses did. */
Test(keys, esc_and_a_character_are_esc_then_the_key)
{
    EXPECT_KEYS("Esc q", "\033q", TK_ESC, 'q');
    EXPECT_KEYS("Esc X (not a string start)", "\033Xj", TK_ESC, 'X', 'j');
    EXPECT_KEYS("Esc Return", "\033\r", TK_ESC, TK_ENTER);
    EXPECT_KEYS("Esc and a UTF-8 character", "\033\xc3\xa9", TK_ESC, 0xe9);
    EXPECT_NONE("Alt-Up as rxvt sends it: a sequence, dropped whole", "\033\033[A");
    EXPECT_NONE("Alt-Home as rxvt sends it", "\033\033[7~");
}

/* ==== The cursor and editing keys ==== */

Test(keys, arrows_in_every_mode)
{
    EXPECT_KEYS("normal mode", "\033[A\033[B\033[C\033[D", TK_UP, TK_DOWN, TK_RIGHT, TK_LEFT);
    EXPECT_KEYS("application mode", "\033OA\033OB\033OC\033OD", TK_UP, TK_DOWN, TK_RIGHT, TK_LEFT);
    EXPECT_KEYS("with Ctrl or Alt", "\033[1;5A\033[1;3B", TK_UP, TK_DOWN);
    EXPECT_KEYS("with Shift (xterm)", "\033[1;2A\033[1;2B\033[1;2C\033[1;2D", TK_SUP, TK_SDOWN, TK_SRIGHT, TK_SLEFT);
    EXPECT_KEYS("with Shift and Ctrl", "\033[1;6D", TK_SLEFT);
    EXPECT_KEYS("with Shift (rxvt)", "\033[a\033[b\033[c\033[d", TK_SUP, TK_SDOWN, TK_SRIGHT, TK_SLEFT);
    EXPECT_KEYS("shift-Tab", "\033[Z", TK_BTAB);
}

Test(keys, home_end_in_every_form)
{
    EXPECT_KEYS("xterm", "\033[H\033[F", TK_HOME, TK_END);
    EXPECT_KEYS("xterm application mode", "\033OH\033OF", TK_HOME, TK_END);
    EXPECT_KEYS("screen, tmux, the Linux console", "\033[1~\033[4~", TK_HOME, TK_END);
    EXPECT_KEYS("rxvt", "\033[7~\033[8~", TK_HOME, TK_END);
    EXPECT_KEYS("with Ctrl (xterm)", "\033[1;5H\033[1;5F", TK_HOME, TK_END);
    EXPECT_KEYS("with Shift (tmux)", "\033[1;2~\033[4;2~", TK_HOME, TK_END);
    EXPECT_KEYS("with Shift, Ctrl, both (rxvt)", "\033[7$\033[8^\033[7@", TK_HOME, TK_END, TK_HOME);
    EXPECT_KEYS("rxvt's Shift-End the last thing read", "\033[8$", TK_END);
}

Test(keys, insert_delete_and_the_page_keys)
{
    EXPECT_KEYS("plain", "\033[2~\033[3~\033[5~\033[6~", TK_INS, TK_DEL, TK_PGUP, TK_PGDN);
    EXPECT_KEYS("with modifiers", "\033[3;2~\033[5;5~\033[6;3~", TK_DEL, TK_PGUP, TK_PGDN);
}

Test(keys, the_keypad_in_application_mode_is_its_characters)
{
    EXPECT_KEYS("digits and operators", "\033Op\033Oy\033Ok\033Om\033OM", '0', '9', '+', '-', TK_ENTER);
}

Test(keys, function_keys_mean_nothing)
{
    EXPECT_NONE("F1-F4 (SS3)", "\033OP\033OQ\033OR\033OS");
    EXPECT_NONE("F5-F12", "\033[15~\033[17~\033[24~");
    EXPECT_NONE("Ctrl-F1 (xterm)", "\033[1;5P");
    EXPECT_NONE("the Linux console's F1-F5", "\033[[A\033[[E");
    EXPECT_KEYS("and a key after them is still a key", "\033[[Aq", 'q');
}

/* Keys split at every byte come out the same. */
Test(keys, sequences_split_across_reads_are_whole)
{
    static const char s[] = "\033[1;5H\033OF\033[3~\033[<0;5;6M\033[<0;5;6m" "q";
    for (size_t chunk = 1; chunk <= 4; chunk++) {
        KeyParser p;
        kp_init(&p, 1);
        Events e = feed_chunked(&p, s, sizeof s - 1, chunk);
        cr_expect_eq(e.n, 5, "chunks of %zu: %s", chunk, show(&e));
        if (e.n == 5) {
            cr_expect_eq(e.ev[0].key, TK_HOME);
            cr_expect_eq(e.ev[1].key, TK_END);
            cr_expect_eq(e.ev[2].key, TK_DEL);
            cr_expect_eq(e.ev[3].type, TE_CLICK);
            cr_expect_eq(e.ev[4].key, 'q');
        }
    }
}

/* ==== Dropped whole ==== */

Test(keys, unknown_sequences_are_dropped_whole)
{
    EXPECT_NONE("focus in and out", "\033[I\033[O");
    EXPECT_NONE("a cursor position report", "\033[12;40R");
    EXPECT_NONE("device attributes", "\033[?64;1;2;6;22c");
    EXPECT_NONE("a mode report", "\033[?1002;1$y");
    EXPECT_NONE("kitty's key protocol", "\033[97;5u");
    EXPECT_NONE("a sequence with intermediate bytes", "\033[2 q");
    EXPECT_KEYS("keys around them stay keys", "a\033[Ib\033[12;40Rc", 'a', 'b', 'c');
}

Test(keys, strings_are_dropped_to_their_end)
{
    EXPECT_NONE("OSC ended by BEL", "\033]11;rgb:0000/0000/0000\007");
    EXPECT_NONE("OSC ended by ST", "\033]10;rgb:ffff/ffff/ffff\033\\");
    EXPECT_NONE("DCS", "\033P1+r6b6370=1b4f41\033\\");
    EXPECT_KEYS("keys after it", "\033]0;title q\007q", 'q');
    EXPECT_KEYS("an ESC that is not ST ends it and is read", "\033]0;x\033[A", TK_UP);
}

Test(keys, a_bracketed_paste_is_dropped)
{
    EXPECT_NONE("a pasted line", "\033[200~quit now\033\r\n\033[201~");
    EXPECT_KEYS("keys after the paste", "\033[200~qqq\033[201~j", 'j');
    /* the end marker split across reads */
    KeyParser p;
    kp_init(&p, 1);
    static const char s[] = "\033[200~q\033[20q\033[201~k";
    Events e = feed_chunked(&p, s, sizeof s - 1, 1);
    expect_keys("split end", e, (int[]){ 'k' }, 1);
}

Test(keys, a_paste_whose_end_is_lost_ends_after_a_quiet)
{
    KeyParser p;
    kp_init(&p, 1);
    TermEvent ev;
    kp_push(&p, "\033[200~text", 10);
    cr_expect_eq(kp_next(&p, &ev, 0), 0);
    cr_expect_eq(kp_wait_ms(&p), -1, "nothing buffered: nothing to decide");
    cr_expect(p.paste, "still inside the paste");
    kp_quiet(&p);           /* the input went quiet for KP_IDLE_MS, then: */
    kp_push(&p, "q", 1);
    cr_expect_eq(kp_next(&p, &ev, 0), 1, "a key after the quiet is a key");
    cr_expect_eq(ev.key, 'q');
    /* a partial end marker left at the end goes once quiet long enough */
    kp_init(&p, 1);
    kp_push(&p, "\033[200~ab\033[2", 11);
    cr_expect_eq(kp_next(&p, &ev, 0), 0);
    cr_expect_eq(kp_wait_ms(&p), KP_IDLE_MS);
    cr_expect_eq(kp_next(&p, &ev, KP_ESC_MS), 0, "an Esc's wait does not end a paste");
    cr_expect_eq(kp_next(&p, &ev, KP_IDLE_MS), 0);
    cr_expect(!p.paste && p.len == 0);
}

Test(keys, an_unfinished_sequence_is_dropped_after_a_quiet)
{
    EXPECT_NONE("ESC [ 1 ; cut off", "\033[1;");
    EXPECT_NONE("ESC O cut off", "\033O");
    EXPECT_NONE("an X10 report cut off", "\033[M ");
}

Test(keys, an_overlong_sequence_is_dropped_to_its_end)
{
    char s[400];
    size_t n = 0;
    s[n++] = '\033';
    s[n++] = '[';
    for (; n < 300; n++)
        s[n] = n % 2 ? ';' : '7';
    s[n++] = 'H';
    s[n++] = 'x';
    KeyParser p;
    kp_init(&p, 1);
    Events e = feed_chunked(&p, s, n, 16);
    expect_keys("only the key after it", e, (int[]){ 'x' }, 1);
}

Test(keys, a_broken_sequence_keeps_the_byte_that_broke_it)
{
    /* a control byte inside a CSI: the CSI goes, the control is a key */
    EXPECT_KEYS("ESC [ 1 then Return", "\033[1\r", TK_ENTER);
    EXPECT_KEYS("ESC [ 1 then a new sequence", "\033[1\033[B", TK_DOWN);
}

/* ==== Status answers ==== */

Test(keys, the_answer_to_a_status_request_is_ready)
{
    Events e = FEED("\033[0n\033[3n\033[5n");
    cr_expect_eq(e.n, 2, "%s", show(&e));
    cr_expect(e.ev[0].type == TE_READY && e.ev[1].type == TE_READY);
}

/* Esc typed while an answer is on its way: on a busy machine the two
 * arrive in one read, and the Esc is the user's (it was taken for Alt
 * with the answer and dropped: Esc could not stop a load under load) */
Test(keys, esc_just_before_an_answer_is_esc)
{
    Events e = FEED("\033\033[0n");
    cr_expect_eq(e.n, 2, "%s", show(&e));
    cr_expect(e.ev[0].type == TE_KEY && e.ev[0].key == TK_ESC, "%s", show(&e));
    cr_expect(e.ev[1].type == TE_READY, "%s", show(&e));
    EXPECT_KEYS("before the attributes' answer", "\033\033[?62;22c", TK_ESC);
    EXPECT_KEYS("before an answer, then a key", "\033\033[?62;22cq", TK_ESC, 'q');
    /* Alt with a key (rxvt: ESC ESC [ A) is still dropped whole */
    EXPECT_NONE("Alt-Up", "\033\033[A");
    EXPECT_NONE("Alt-Delete", "\033\033[3~");
}

/* ==== The mouse ==== */

Test(keys, sgr_press_drag_release)
{
    Events e = FEED("\033[<0;10;5M\033[<32;13;5M\033[<32;13;7M\033[<0;14;8m");
    cr_assert_eq(e.n, 4, "%s", show(&e));
    cr_expect(e.ev[0].type == TE_CLICK && e.ev[0].button == 1 && e.ev[0].x == 9 && e.ev[0].y == 4, "%s", show(&e));
    cr_expect(e.ev[1].type == TE_DRAG && e.ev[1].dx == 3 && e.ev[1].dy == 0, "%s", show(&e));
    cr_expect(e.ev[2].type == TE_DRAG && e.ev[2].dx == 0 && e.ev[2].dy == 2, "%s", show(&e));
    cr_expect(e.ev[3].type == TE_DRAG && e.ev[3].dx == 1 && e.ev[3].dy == 1, "the release moves the last bit: %s", show(&e));
    EXPECT_NONE("motion after the release is no drag", "\033[<35;20;20M");
}

Test(keys, the_right_button_drags_and_the_middle_means_nothing)
{
    Events e = FEED("\033[<2;1;1M\033[<34;3;1M\033[<2;3;1m\033[<1;5;5M\033[<33;9;9M\033[<1;9;9m");
    cr_assert_eq(e.n, 2, "%s", show(&e));
    cr_expect(e.ev[0].type == TE_CLICK && e.ev[0].button == 3);
    cr_expect(e.ev[1].type == TE_DRAG && e.ev[1].button == 3 && e.ev[1].dx == 2);
}

Test(keys, the_wheel)
{
    Events e = FEED("\033[<64;5;5M\033[<65;5;5M\033[<66;5;5M");
    cr_assert_eq(e.n, 2, "%s (the sideways wheel means nothing)", show(&e));
    cr_expect(e.ev[0].type == TE_WHEEL && e.ev[0].dy == -1);
    cr_expect(e.ev[1].type == TE_WHEEL && e.ev[1].dy == 1);
}

Test(keys, x10_reports)
{
    /* ESC [ M, then button + 32, column + 32, row + 32 (cells from 1) */
    Events e = FEED("\033[M *%\033[M@-%\033[M#.%\033[M`**q");
    cr_assert_eq(e.n, 5, "%s", show(&e));
    cr_expect(e.ev[0].type == TE_CLICK && e.ev[0].button == 1 && e.ev[0].x == 9 && e.ev[0].y == 4, "%s", show(&e));
    cr_expect(e.ev[1].type == TE_DRAG && e.ev[1].dx == 3, "%s", show(&e));
    cr_expect(e.ev[2].type == TE_DRAG && e.ev[2].dx == 1, "the release: %s", show(&e));
    cr_expect(e.ev[3].type == TE_WHEEL && e.ev[3].dy == -1, "%s", show(&e));
    cr_expect(e.ev[4].type == TE_KEY && e.ev[4].key == 'q');
}

Test(keys, an_unasked_for_report_is_no_key)
{
    /* SGR reports of modes we never turn on (any-motion), urxvt's form */
    EXPECT_NONE("motion with no button", "\033[<35;50;15M");
    EXPECT_NONE("urxvt 1015", "\033[32;50;15M");
}
