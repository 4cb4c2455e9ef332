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
        cr_assert_eq(kp_push(p, s + off, n, 0), n);
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
    kp_push(&p, "\033", 1, 0);
    cr_expect_eq(kp_next(&p, &ev, 0), 0, "an ESC just read may start a sequence");
    cr_expect_eq(kp_wait_ms(&p, 0), KP_ESC_MS);
    cr_expect_eq(kp_wait_ms(&p, 10), KP_ESC_MS - 10);
    cr_expect_eq(kp_next(&p, &ev, KP_ESC_MS - 1), 0, "not quiet long enough yet");
    cr_expect_eq(kp_next(&p, &ev, KP_ESC_MS), 1);
    cr_expect(ev.type == TE_KEY && ev.key == TK_ESC);
    cr_expect_eq(kp_wait_ms(&p, KP_ESC_MS), -1, "nothing left to wait for");
    EXPECT_KEYS("Esc twice", "\033\033", TK_ESC, TK_ESC);
    EXPECT_KEYS("Esc, then q later", "\033", TK_ESC);
}

/* Esc typed just before a key arrives with it (tmux joins the two when
 * they come within its escape-time): both are read, as curses did. */
Test(keys, esc_and_a_character_are_esc_then_the_key)
{
    EXPECT_KEYS("Esc q", "\033q", TK_ESC, 'q');
    EXPECT_KEYS("Esc Y", "\033Yj", TK_ESC, 'Y', 'j');
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
    kp_push(&p, "\033[200~text", 10, 0);
    cr_expect_eq(kp_next(&p, &ev, 0), 0);
    cr_expect_eq(kp_wait_ms(&p, 0), KP_IDLE_MS, "the paste ends after a quiet");
    cr_expect(p.paste, "still inside the paste");
    kp_push(&p, "q", 1, KP_IDLE_MS - 1);
    cr_expect_eq(kp_next(&p, &ev, KP_IDLE_MS - 1), 0, "a byte before the quiet is the paste's");
    kp_push(&p, "q", 1, 2 * KP_IDLE_MS);      /* the input went quiet for KP_IDLE_MS, then: */
    cr_expect_eq(kp_next(&p, &ev, 2 * KP_IDLE_MS), 1, "a key after the quiet is a key");
    cr_expect_eq(ev.key, 'q');
    /* a partial end marker left at the end goes once quiet long enough */
    kp_init(&p, 1);
    kp_push(&p, "\033[200~ab\033[2", 11, 0);
    cr_expect_eq(kp_next(&p, &ev, 0), 0);
    cr_expect_eq(kp_wait_ms(&p, 0), KP_IDLE_MS);
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

/* The modifiers a report carries (+4 Shift, +8 Meta, +16 Ctrl: the
 * measuring mode's wide snap), and where a drag has reached */
Test(keys, clicks_and_drags_carry_their_modifiers_and_cell)
{
    Events e = FEED("\033[<16;10;5M\033[<16;10;5m\033[<4;3;2M\033[<36;6;9M\033[<4;6;9m\033[<24;1;1M\033[<0;7;7M");
    cr_assert_eq(e.n, 5, "%s", show(&e));
    cr_expect(e.ev[0].type == TE_CLICK && e.ev[0].button == 1 && e.ev[0].mods == TE_CTRL && e.ev[0].x == 9,
              "Ctrl: %s", show(&e));
    cr_expect(e.ev[1].type == TE_CLICK && e.ev[1].mods == TE_SHIFT, "Shift: %s", show(&e));
    cr_expect(e.ev[2].type == TE_DRAG && e.ev[2].x == 5 && e.ev[2].y == 8 && e.ev[2].dx == 3 && e.ev[2].dy == 7,
              "the drag's cell: %s", show(&e));
    cr_expect(e.ev[3].type == TE_CLICK && e.ev[3].mods == (TE_CTRL | TE_META), "Ctrl-Meta: %s", show(&e));
    cr_expect(e.ev[4].type == TE_CLICK && e.ev[4].mods == 0, "none: %s", show(&e));
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

/* ==== Answers to questions (issue 28) ====
 * Every answer a terminal gives, in every form (CSI with private and
 * intermediate bytes, OSC, DCS, APC, PM, SOS, BEL or ST, 7-bit or
 * 8-bit), split anywhere, with the gaps a slow link puts between its
 * pieces: dropped whole, the keys around it exactly kept. Time is the
 * parser's argument, so the gaps cost nothing here. */

typedef struct {
    const char *name;
    const char *s;
    size_t      len;
    int         mode;           /* 2: both locales; 1: UTF-8 only; 0: Latin-1 only */
} Form;

#define FORM(name, lit, mode) { name, lit, sizeof lit - 1, mode }

static const Form answers[] = {
    FORM("DA1 of xterm -ti vt340 (sixel)", "\033[?63;1;2;4;6;9;15;16;17;18;21;22;28c", 2),
    FORM("DA1 of kitty", "\033[?62;c", 2),
    FORM("DA1 of foot", "\033[?62;4;22c", 2),
    FORM("DA1 of tmux", "\033[?1;2c", 2),
    FORM("DA2", "\033[>1;4000;29c", 2),
    FORM("a cursor position report", "\033[12;40R", 2),
    FORM("DECRPM (private and intermediate bytes)", "\033[?2026;2$y", 2),
    FORM("kitty's keyboard flags", "\033[?0u", 2),
    FORM("XTWINOPS, the window in pixels", "\033[4;600;800t", 2),
    FORM("focus in", "\033[I", 2),
    FORM("an SS3 function key", "\033OP", 2),
    FORM("OSC 11 with ST (kitty, foot)", "\033]11;rgb:0000/0000/0000\033\\", 2),
    FORM("OSC 11 with BEL (xterm)", "\033]11;rgb:ffff/ffff/dddd\007", 2),
    FORM("OSC 11 rgba (rxvt)", "\033]11;rgba:0000/0000/0000/ffff\007", 2),
    FORM("OSC 4, a palette colour", "\033]4;1;rgb:cdcd/0000/0000\033\\", 2),
    FORM("OSC 52, the clipboard", "\033]52;c;cXVpdCBub3c=\007", 2),
    FORM("OSC 2 with UTF-8 holding a byte 0x9c", "\033]2;\xc4\x9c title\033\\", 1),
    FORM("DCS XTVERSION of kitty", "\033P>|kitty(0.26.5)\033\\", 2),
    FORM("DCS XTVERSION of xterm", "\033P>|XTerm(379)\033\\", 2),
    FORM("DCS XTGETTCAP", "\033P1+r736d6b78=1b5b3f31682c1b3d\033\\", 2),
    FORM("DCS DECRQSS", "\033P1$r0;1m\033\\", 2),
    FORM("DCS with BEL", "\033P>|foot(1.13.1)\007", 2),
    FORM("APC: kitty's graphics OK", "\033_Gi=31;OK\033\\", 2),
    FORM("APC: kitty's graphics error", "\033_Gi=31;ENODATA:Insufficient image data\033\\", 2),
    FORM("APC with BEL", "\033_Gi=31;OK\007", 2),
    FORM("PM", "\033^a private message\033\\", 2),
    FORM("SOS", "\033Xa string\033\\", 2),
    FORM("SOS with BEL", "\033Xsos\007", 2),
    FORM("tmux's passthrough of kitty's answer", "\033Ptmux;\033\033_Gi=31;OK\033\033\\\033\\", 2),
    FORM("a stray ST", "\033\\", 2),
    FORM("8-bit CSI: DA1", "\x9b?62;4c", 0),
    FORM("8-bit CSI: a position report", "\x9b" "12;40R", 0),
    FORM("8-bit OSC 11 with 8-bit ST", "\x9d" "11;rgb:0000/0000/0000\x9c", 0),
    FORM("8-bit OSC 11 with BEL", "\x9d" "11;rgb:0000/0000/0000\007", 0),
    FORM("8-bit DCS", "\x90>|XTerm(379)\x9c", 0),
    FORM("8-bit APC", "\x9fGi=31;OK\x9c", 0),
    FORM("8-bit APC with 7-bit ST", "\x9fGi=31;OK\033\\", 0),
    FORM("8-bit PM", "\x9e" "pm\x9c", 0),
    FORM("8-bit SOS", "\x98sos\x9c", 0),
    FORM("8-bit SS3", "\x8fP", 0),
    FORM("8-bit ST alone", "\x9c", 0),
    FORM("C1 CSI in UTF-8: DA1", "\xc2\x9b?62;4c", 1),
    FORM("C1 OSC 11 in UTF-8", "\xc2\x9d" "11;rgb:0000/0000/0000\xc2\x9c", 1),
    FORM("C1 DCS in UTF-8", "\xc2\x90>|foot(1.13.1)\xc2\x9c", 1),
    FORM("C1 APC in UTF-8", "\xc2\x9fGi=31;OK\xc2\x9c", 1),
    FORM("C1 PM in UTF-8", "\xc2\x9e" "pm\xc2\x9c", 1),
    FORM("C1 SOS in UTF-8 with 7-bit ST", "\xc2\x98sos\033\\", 1),
};
#define NANSWERS (sizeof answers / sizeof *answers)

/* The locales a form is tried in: bit 0 Latin-1, bit 1 UTF-8. */
static int locales(const Form *f)
{
    return f->mode == 2 ? 3 : f->mode == 1 ? 2 : 1;
}

/* A piece of input and when it comes (ms). */
typedef struct {
    const char *s;
    size_t      len;
    double      at;
} Piece;

static void take(KeyParser *p, Events *e, double at)
{
    TermEvent ev;
    while (e->n < MAXEV && kp_next(p, &ev, at))
        e->ev[e->n++] = ev;
}

/* The pieces pushed in order to a parser that awaits `pending` answers
 * (asked at time 0), events taken just before each piece comes (the
 * longest quiet a reader could have seen) and as it comes, then after a
 * long quiet. */
static Events play(int utf8, int pending, const Piece *pc, int n)
{
    KeyParser p;
    kp_init(&p, utf8);
    if (pending)
        kp_expect(&p, pending, 0);
    Events e = { .n = 0 };
    double last = 0;
    for (int i = 0; i < n; i++) {
        take(&p, &e, pc[i].at - 1);
        cr_assert_eq(kp_push(&p, pc[i].s, pc[i].len, pc[i].at), pc[i].len);
        take(&p, &e, pc[i].at);
        last = pc[i].at;
    }
    take(&p, &e, last + 1e6);
    cr_assert_leq(p.len, sizeof p.b);
    return e;
}

/* "a", the form, "b": two keys, whatever the form. */
static int just_a_and_b(const Events *e)
{
    return e->n == 2 && e->ev[0].type == TE_KEY && e->ev[0].key == 'a' && e->ev[1].type == TE_KEY &&
           e->ev[1].key == 'b';
}

/* "a" + f[0..k) at time 0, f[k..) + "b" at `gap`. */
static Events split_once(const Form *f, int utf8, int pending, size_t k, double gap)
{
    char first[256], second[256];
    cr_assert_lt(f->len + 2, sizeof first);
    first[0] = 'a';
    memcpy(first + 1, f->s, k);
    memcpy(second, f->s + k, f->len - k);
    second[f->len - k] = 'b';
    Piece pc[2] = { { first, k + 1, 0 }, { second, f->len - k + 1, gap } };
    return play(utf8, pending, pc, 2);
}

Test(keys, every_answer_whole_is_dropped)
{
    for (size_t i = 0; i < NANSWERS; i++)
        for (int utf8 = 0; utf8 < 2; utf8++) {
            if (!(locales(&answers[i]) >> utf8 & 1))
                continue;
            Events e = split_once(&answers[i], utf8, 0, 0, 0);
            cr_expect(just_a_and_b(&e), "%s (%s): %s", answers[i].name, utf8 ? "UTF-8" : "Latin-1", show(&e));
        }
}

/* Split at every byte with a gap of 300 ms while the answer is awaited
 * (a slow link: the ESC alone, the rest 300 ms later), and of 0 ms. */
Test(keys, every_answer_split_at_every_byte_is_dropped)
{
    static const double gaps[] = { 0, 30, 300, KP_REPLY_MS - 1 };
    int cases = 0;
    for (size_t i = 0; i < NANSWERS; i++)
        for (int utf8 = 0; utf8 < 2; utf8++) {
            if (!(locales(&answers[i]) >> utf8 & 1))
                continue;
            for (size_t k = 1; k < answers[i].len; k++)
                for (size_t g = 0; g < sizeof gaps / sizeof *gaps; g++, cases++) {
                    Events e = split_once(&answers[i], utf8, 1, k, gaps[g]);
                    cr_expect(just_a_and_b(&e), "%s (%s) split after byte %zu, %.0f ms apart: %s",
                              answers[i].name, utf8 ? "UTF-8" : "Latin-1", k, gaps[g], show(&e));
                }
        }
    cr_expect_gt(cases, 3000, "%d cases", cases);
}

/* A late answer (nothing awaited any more) split inside: a string waits
 * for its end however it is split once it has begun, a CSI sequence
 * for the usual KP_ESC_MS. */
Test(keys, a_late_answer_split_inside_is_dropped)
{
    for (size_t i = 0; i < NANSWERS; i++) {
        const Form *f = &answers[i];
        int utf8 = f->mode != 0;
        size_t intro = f->s[0] == '\033' ? 2 : utf8 ? 2 : 1;
        int string = strchr("]P_^X", f->s[1]) != NULL || (unsigned char)f->s[intro - 1] >= 0x90;
        if (!string || f->len < intro + 2 || !strcmp(f->name, "a stray ST") ||
            (unsigned char)f->s[intro - 1] == 0x9b || (unsigned char)f->s[intro - 1] == 0x8f)
            continue;
        for (size_t k = intro; k < f->len; k++) {
            Events e = split_once(f, utf8, 0, k, KP_IDLE_MS - 1);
            cr_expect(just_a_and_b(&e), "%s split after byte %zu, %d ms apart: %s", f->name, k, KP_IDLE_MS - 1,
                      show(&e));
        }
    }
    Events e = split_once(&answers[0], 0, 0, 3, KP_ESC_MS - 1);
    cr_expect(just_a_and_b(&e), "DA1 split within KP_ESC_MS: %s", show(&e));
}

/* A slow link's worst: every byte alone, 30 ms apart, and the leading
 * ESC (or C1 introducer) alone 300 ms before the rest. */
Test(keys, every_answer_byte_by_byte_on_a_slow_link_is_dropped)
{
    for (size_t i = 0; i < NANSWERS; i++)
        for (int utf8 = 0; utf8 < 2; utf8++) {
            const Form *f = &answers[i];
            if (!(locales(f) >> utf8 & 1))
                continue;
            Piece pc[128];
            int n = 0;
            double t = 0;
            pc[n++] = (Piece){ "a", 1, t };
            for (size_t k = 0; k < f->len; k++) {
                t += k == 1 ? 300 : 30;
                pc[n++] = (Piece){ f->s + k, 1, t };
            }
            pc[n++] = (Piece){ "b", 1, t + 30 };
            cr_assert_leq(n, 128);
            Events e = play(utf8, 1, pc, n);
            cr_expect(just_a_and_b(&e), "%s (%s) byte by byte: %s", f->name, utf8 ? "UTF-8" : "Latin-1", show(&e));
        }
}

/* The reproductions of issue 28. kitty answers the graphics query as its
 * protocol says; the viewer read the answer's ESC as Esc and quit before
 * its first frame. */
Test(keys, kittys_answer_to_the_graphics_query_is_no_esc)
{
    EXPECT_NONE("kitty's OK", "\033_Gi=31;OK\033\\");
    EXPECT_NONE("the answers kitty gives the viewer's questions, as they came",
                "\033]11;rgb:0000/0000/0000\033\\\033[?62;c\033_Gi=31;OK\033\\\033P>|kitty(0.26.5)\033\\\033[?62;c");
}

/* An OSC 11 and an attributes' answer whose ESC comes 30 ms before the
 * rest (as over a slow ssh link): no Esc, and no keys from the rest. */
Test(keys, an_osc11_answer_split_after_its_esc_is_no_esc)
{
    static const Form f = FORM("OSC 11", "\033]11;rgb:1e1e/1e1e/2e2e\033\\", 2);
    Events e = split_once(&f, 1, 1, 1, 30);
    cr_expect(just_a_and_b(&e), "%s", show(&e));
}

Test(keys, a_da_answer_split_after_its_esc_is_no_esc)
{
    static const Form f = FORM("DA1", "\033[?62;4;22c", 2);
    Events e = split_once(&f, 1, 1, 1, 30);
    cr_expect(just_a_and_b(&e), "%s", show(&e));
}

/* Keys around and between the answers come out exactly: every split of
 * the whole stream in two, and byte by byte. */
Test(keys, answers_between_keys_leave_the_keys_exactly)
{
    static const char s[] = "j\033_Gi=31;OK\033\\k\033]11;rgb:0000/0000/0000\007\033[?62;c\033[A"
                            "\033P>|kitty(0.26.5)\033\\l\033[0n\033Ptmux;\033\033_Gi=31;OK\033\033\\\033\\q";
    const size_t n = sizeof s - 1;
    for (size_t k = 0; k <= n; k++) {
        for (int how = 0; how < 2; how++) {
            Piece pc[2] = { { s, k, 0 }, { s + k, n - k, how ? 300 : 0 } };
            Events e = play(1, 3, pc, 2);     /* the last answer, tmux's, awaited too */
            int ok = e.n == 6 && e.ev[0].key == 'j' && e.ev[1].key == 'k' && e.ev[2].key == TK_UP &&
                     e.ev[3].key == 'l' && e.ev[4].type == TE_READY && e.ev[5].key == 'q';
            cr_expect(ok, "split after byte %zu, %d ms apart: %s", k, how ? 300 : 0, show(&e));
        }
    }
}

/* ==== Esc while answers are awaited ==== */

Test(keys, a_lone_esc_waits_longer_while_an_answer_is_awaited)
{
    KeyParser p;
    TermEvent ev;
    kp_init(&p, 1);
    kp_expect(&p, 1, 0);
    cr_expect_eq(kp_awaiting(&p, 0), 1);
    kp_push(&p, "\033", 1, 0);
    cr_expect_eq(kp_wait_ms(&p, 0), KP_REPLY_MS);
    cr_expect_eq(kp_next(&p, &ev, KP_ESC_MS), 0, "the rest of an answer may come");
    cr_expect_eq(kp_next(&p, &ev, KP_REPLY_MS - 1), 0);
    cr_expect_eq(kp_next(&p, &ev, KP_REPLY_MS), 1, "a person's Esc, half a second late");
    cr_expect(ev.type == TE_KEY && ev.key == TK_ESC);
    /* nothing awaited: the usual wait */
    kp_init(&p, 1);
    kp_push(&p, "\033", 1, 0);
    cr_expect_eq(kp_wait_ms(&p, 0), KP_ESC_MS);
    cr_expect_eq(kp_next(&p, &ev, KP_ESC_MS), 1);
    cr_expect(ev.type == TE_KEY && ev.key == TK_ESC);
}

/* The answer that was awaited ends the longer wait: the attributes', a
 * status report; two questions need two answers. */
Test(keys, the_awaited_answer_ends_the_longer_wait)
{
    KeyParser p;
    TermEvent ev;
    kp_init(&p, 1);
    kp_expect(&p, 1, 0);
    kp_expect(&p, 1, 5);
    kp_push(&p, "\033]11;rgb:0/0/0\007\033[?62;c", 22, 10);
    cr_expect_eq(kp_next(&p, &ev, 10), 0);
    cr_expect_eq(kp_awaiting(&p, 10), 1, "one answer of two came");
    kp_push(&p, "\033[?62;c", 7, 20);
    cr_expect_eq(kp_next(&p, &ev, 20), 0);
    cr_expect_eq(kp_awaiting(&p, 20), 0);
    kp_push(&p, "\033", 1, 30);
    cr_expect_eq(kp_next(&p, &ev, 30 + KP_ESC_MS), 1, "Esc after the usual wait");
    cr_expect_eq(ev.key, TK_ESC);
    kp_expect(&p, 1, 100);
    kp_push(&p, "\033[0n", 4, 110);
    cr_expect_eq(kp_next(&p, &ev, 110), 1);
    cr_expect_eq(ev.type, TE_READY);
    cr_expect_eq(kp_awaiting(&p, 110), 0, "the status report was the awaited answer");
    /* a question that only went out now (queued first): its time restarts */
    kp_expect(&p, 1, 200);
    kp_expect(&p, 0, 200 + KP_LATE_MS - 1);
    cr_expect_eq(kp_awaiting(&p, 200 + KP_LATE_MS + 1), 1);
}

/* Answers that never come (a terminal that ignores the question) stop
 * being awaited KP_LATE_MS after the last question. */
Test(keys, answers_that_never_come_stop_being_awaited)
{
    KeyParser p;
    TermEvent ev;
    kp_init(&p, 1);
    kp_expect(&p, 1, 0);
    cr_expect_eq(kp_awaiting(&p, KP_LATE_MS - 1), 1);
    cr_expect_eq(kp_awaiting(&p, KP_LATE_MS), 0);
    kp_push(&p, "\033", 1, KP_LATE_MS);
    cr_expect_eq(kp_next(&p, &ev, KP_LATE_MS + KP_ESC_MS), 1);
    cr_expect_eq(ev.key, TK_ESC);
    kp_expect(&p, 1, 2 * KP_LATE_MS);
    cr_expect_eq(kp_awaiting(&p, 2 * KP_LATE_MS), 1, "the one lost before does not count");
}

/* Esc typed while an answer is on its way, the answer after it: Esc,
 * and the answer dropped (also a string answer). */
Test(keys, esc_then_an_answer_while_awaited_is_esc)
{
    Piece pc[2] = { { "\033", 1, 0 }, { "\033[?62;c", 7, 100 } };
    Events e = play(1, 1, pc, 2);
    cr_expect(e.n == 1 && e.ev[0].key == TK_ESC, "%s", show(&e));
    static const char answer[] = "\033_Gi=31;OK\033\\q";
    Piece ps[2] = { { "\033", 1, 0 }, { answer, sizeof answer - 1, 100 } };
    e = play(1, 1, ps, 2);
    cr_expect(e.n == 2 && e.ev[0].key == TK_ESC && e.ev[1].key == 'q', "%s", show(&e));
    EXPECT_KEYS("Esc and an OSC answer together", "\033\033]11;rgb:0/0/0\033\\", TK_ESC);
}

/* ==== Bounds ==== */

/* A string that never ends holds no memory and not the keys forever:
 * after KP_STRING_MAX bytes it is given up and the input is read afresh;
 * an endless CSI sequence alike. */
Test(keys, an_endless_string_is_bounded)
{
    static const char *starts[] = { "\033]11;", "\033P", "\033_G", "\033^", "\033X", "\033[1" };
    for (size_t s = 0; s < sizeof starts / sizeof *starts; s++) {
        KeyParser p;
        kp_init(&p, 1);
        kp_push(&p, starts[s], strlen(starts[s]), 0);
        char body[512];
        memset(body, s == 5 ? ';' : 'A', sizeof body);
        TermEvent ev;
        long events = 0, keys_a = 0, pushed = 0;
        for (int i = 0; i < 2048; i++) {     /* 1 MB, no quiet */
            cr_assert_eq(kp_push(&p, body, sizeof body, i), sizeof body);
            pushed += (long)sizeof body;
            while (kp_next(&p, &ev, i)) {
                events++;
                keys_a += ev.type == TE_KEY && ev.key == body[0];
            }
            cr_assert_leq(p.len, sizeof p.b);
        }
        kp_push(&p, "q", 1, 2048);
        int got_q = kp_next(&p, &ev, 2048) && ev.key == 'q';
        cr_expect(got_q, "%s: the key after a megabyte", starts[s]);
        /* what follows the bound is read afresh: the body's bytes are keys
         * (a ';' too). A string drops KP_STRING_MAX bytes of its body (its
         * start's among them) and the one that broke the bound; a CSI
         * sequence what it held when it became overlong (at most the
         * parser's buffer), then KP_STRING_MAX */
        long start_body = (long)strlen(starts[s]) - 2;
        if (s < 5)
            cr_expect_eq(keys_a, pushed - (KP_STRING_MAX + 1 - start_body), "%s: %ld keys of %ld bytes",
                         starts[s], keys_a, pushed);
        else
            cr_expect(keys_a <= pushed - KP_STRING_MAX && keys_a >= pushed - KP_STRING_MAX - (long)sizeof p.b,
                      "%s: %ld keys of %ld bytes", starts[s], keys_a, pushed);
        cr_expect_eq(events, keys_a);
    }
}

/* A string whose end is lost ends when the input has been quiet for
 * KP_IDLE_MS; before that its bytes are its own. */
Test(keys, a_string_whose_end_is_lost_ends_after_a_quiet)
{
    KeyParser p;
    TermEvent ev;
    kp_init(&p, 1);
    kp_push(&p, "\033_Gi=31;O", 9, 0);
    cr_expect_eq(kp_next(&p, &ev, 0), 0);
    cr_expect_eq(kp_wait_ms(&p, 0), KP_IDLE_MS, "an open string waits for its end, then is given up");
    cr_expect_eq(kp_next(&p, &ev, KP_IDLE_MS - 1), 0);
    cr_expect(p.string == '_', "still inside the APC");
    cr_expect_eq(kp_next(&p, &ev, KP_IDLE_MS), 0);
    cr_expect(!p.string, "given up after the quiet");
    kp_push(&p, "q", 1, KP_IDLE_MS + 1);
    cr_expect_eq(kp_next(&p, &ev, KP_IDLE_MS + 1), 1);
    cr_expect_eq(ev.key, 'q');
    /* the same when nobody asked in time: the next bytes say so (the
     * reader parses what it read before it reads again) */
    kp_init(&p, 1);
    kp_push(&p, "\033]11;rgb", 8, 0);
    cr_expect_eq(kp_next(&p, &ev, 0), 0);
    kp_push(&p, "q", 1, KP_IDLE_MS);
    cr_expect_eq(kp_next(&p, &ev, KP_IDLE_MS), 1);
    cr_expect_eq(ev.key, 'q');
}
