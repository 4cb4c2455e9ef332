/* keys: the terminal's input, bytes to events. Characters (UTF-8), the
 * control keys, the cursor and editing keys in every form xterm, rxvt,
 * screen, tmux and the Linux console send them (CSI and SS3, with or
 * without modifiers), mouse reports (SGR, and the older X10 form a
 * terminal without SGR falls back to) turned into clicks, drags and the
 * wheel, and the answer to a status request.
 *
 * Anything else a terminal may send is dropped whole: focus events,
 * reports nobody asked for, keys without a meaning here, the answers to
 * the questions zview asks (the background colour, OSC 11; the device
 * attributes, CSI ? ... c; the kitty graphics query, APC G ... ; the
 * terminal's name, DCS > | ...), every string (OSC, DCS, APC, PM, SOS,
 * ended by BEL or ST, tmux's passthrough with its doubled ESCs among
 * them), and the content of a bracketed paste. Reading such a sequence
 * as its Esc followed by text would quit the viewer (Esc) and then act
 * on the text as keys: kitty's answer to the graphics query, read as
 * Esc, quit the viewer before its first frame. ESC and a plain character
 * is no such sequence: it is Esc typed just before the key (or the key
 * with Alt), read as both. ESC and _ ^ X P ] always start a string, so
 * Esc typed just before one of those five keys loses the key.
 *
 * The grammar is ECMA-48's: CSI is ESC [, then parameter bytes 0x30-0x3f,
 * intermediate bytes 0x20-0x2f and one final byte 0x40-0x7e; SS3 is ESC O
 * and one final byte (some terminals put parameters between); a string
 * runs from its introducer to ST (ESC \), or BEL as xterm allows, and
 * CAN or SUB cancel it. Two forms break it and are special-cased: the X10
 * mouse report, ESC [ M and three raw bytes, and the Linux console's
 * F1-F5, ESC [ [ and a letter. The 8-bit forms (CSI as one byte 0x9b,
 * ST as 0x9c, ...) come only from a terminal told to send them (S8C1T,
 * which zview never sends), and are read as the terminal would encode
 * them: in a UTF-8 locale as the characters U+0080-U+009F (C2 9B for
 * CSI; a lone byte 0x9b there is part of no character and is dropped),
 * otherwise as the bytes themselves.
 *
 * The parser keeps at most one unfinished sequence (a CSI sequence is
 * bounded; a string is dropped as it comes, however long, keeping only
 * an ESC or C2 that may begin its terminator), so it survives a
 * sequence split at any byte. A lone Esc is only known by the silence
 * after it: an unfinished sequence that stays unfinished for KP_ESC_MS
 * is decided (a lone ESC is the Esc key, anything longer is dropped).
 * A slow link splits an answer after its ESC by more than that, so
 * while an answer is awaited (kp_expect: the caller asked the terminal
 * something whose answer has not come) the wait is KP_REPLY_MS, as
 * tmux's escape-time. A string or an overlong CSI sequence is bounded
 * too: after KP_STRING_MAX bytes it is no answer, and what follows is
 * read afresh (a terminal that never ends one would otherwise hold the
 * keys forever; one that floods garbage could send keys anyway). Pure:
 * bytes and times in, events out; term.c reads the bytes and the clock. */

#include <string.h>

#include "tty.h"

#define ESC 0x1b
#define SEQ_MAX 64              /* a sequence this long is garbage: dropped up to its end */
#define NPARAM 8
/* the C1 controls zview reads, as their 8-bit codes */
#define C1_DCS 0x90
#define C1_SOS 0x98
#define C1_CSI 0x9b
#define C1_ST  0x9c
#define C1_OSC 0x9d
#define C1_PM  0x9e
#define C1_APC 0x9f
#define C1_SS3 0x8f

enum { R_MORE, R_DROP, R_EVENT };       /* what one step did */

void kp_init(KeyParser *p, int utf8)
{
    memset(p, 0, sizeof *p);
    p->utf8 = utf8;
}

/* The input was quiet for KP_IDLE_MS: a paste, string or overlong
 * sequence still open has lost its end, and what comes now is keys. */
static void lost_end(KeyParser *p)
{
    p->string = p->paste = p->skip = 0;
    p->run = 0;
}

size_t kp_push(KeyParser *p, const void *bytes, size_t n, double now_ms)
{
    if (now_ms - p->last_ms >= KP_IDLE_MS)
        lost_end(p);
    p->last_ms = now_ms;
    size_t room = sizeof p->b - p->len;
    if (n > room)
        n = room;
    memcpy(p->b + p->len, bytes, n);
    p->len += n;
    return n;
}

static void consume(KeyParser *p, size_t n)
{
    if (n > p->len)
        n = p->len;
    memmove(p->b, p->b + n, p->len - n);
    p->len -= n;
}

static int key(TermEvent *ev, int k)
{
    ev->type = TE_KEY;
    ev->key = k;
    return R_EVENT;
}

/* ==== Characters ==== */

/* One UTF-8 character at b[0..len): its code point in *cp and length in
 * *used; R_MORE when it is cut short, R_DROP (one byte) when invalid. */
static int utf8_char(const unsigned char *b, size_t len, int *cp, size_t *used)
{
    unsigned c = b[0];
    size_t n = c >= 0xf0 && c <= 0xf4 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
    *used = 1;
    if (n == 0 || c > 0xf4)
        return R_DROP;
    uint32_t v = c & (0x7f >> n);
    for (size_t i = 1; i < n; i++) {
        if (i >= len)
            return R_MORE;
        if ((b[i] & 0xc0) != 0x80)
            return R_DROP;
        v = v << 6 | (b[i] & 0x3f);
    }
    /* overlong forms and surrogates are not characters */
    if ((n == 3 && v < 0x800) || (n == 4 && (v < 0x10000 || v > 0x10ffff)) ||
        (v >= 0xd800 && v <= 0xdfff))
        return R_DROP;
    *cp = (int)v;
    *used = n;
    return R_EVENT;
}

/* A byte that is not ESC: a control key or the start of a character. */
static int plain(KeyParser *p, TermEvent *ev, size_t *used)
{
    unsigned c = p->b[0];
    *used = 1;
    if (c == '\r' || c == '\n')
        return key(ev, TK_ENTER);      /* Return, whatever the tty's CR/NL mapping */
    if (c == 8 || c == 127)
        return key(ev, TK_BACKSPACE);  /* whichever of ^H and DEL the terminal sends */
    if (c < 0x80 || !p->utf8)
        return key(ev, (int)c);
    int cp;
    int r = utf8_char(p->b, p->len, &cp, used);
    return r == R_EVENT ? key(ev, cp) : r;
}

/* ==== The mouse ==== */

/* A report, as xterm numbers it: b the button code (low two bits the
 * button, 0 left, 1 middle, 2 right, 3 released in the X10 form; +32
 * motion; +64 the wheel; +4 Shift, +8 Meta, +16 Ctrl held), x and y
 * the cell from 0. A press is a click (the sketch places a corner there,
 * the measuring mode its cursor) and starts a drag; motion with the
 * button held moves it by whole cells; the release ends it. */
static int mouse(KeyParser *p, int b, int x, int y, int release, TermEvent *ev)
{
    x = x < 0 ? 0 : x;          /* a report of cell 0 (none is) reads as the first */
    y = y < 0 ? 0 : y;
    ev->mods = (b & 4 ? TE_SHIFT : 0) | (b & 8 ? TE_META : 0) | (b & 16 ? TE_CTRL : 0);
    if (b & 64) {
        if (release || (b & 3) > 1)
            return R_DROP;      /* wheels report no release; 66, 67 are the sideways wheel */
        ev->type = TE_WHEEL;
        ev->dy = (b & 3) ? 1 : -1;
        return R_EVENT;
    }
    if ((b & 32) || release || (b & 3) == 3) {
        if (!p->drag_button)
            return R_DROP;
        ev->type = TE_DRAG;
        ev->button = p->drag_button;
        ev->dx = x - p->drag_x;
        ev->dy = y - p->drag_y;
        p->drag_x = ev->x = x;
        p->drag_y = ev->y = y;
        if (!(b & 32))
            p->drag_button = 0;         /* the release: the drag ends where it is */
        return ev->dx || ev->dy ? R_EVENT : R_DROP;
    }
    if ((b & 3) == 1)
        return R_DROP;                  /* the middle button means nothing here */
    p->drag_button = (b & 3) == 0 ? 1 : 3;
    p->drag_x = x;
    p->drag_y = y;
    ev->type = TE_CLICK;
    ev->button = p->drag_button;
    ev->x = x;
    ev->y = y;
    return R_EVENT;
}

/* ==== Sequences ==== */

typedef struct {
    int  priv;                  /* a private marker first (< = > ?), else 0 */
    int  n;                     /* parameters given */
    int  v[NPARAM];             /* their values (missing: 0) */
    int  inter;                 /* intermediate bytes present */
    int  final;
} Seq;

static void params(const unsigned char *s, size_t len, Seq *q)
{
    size_t i = 0;
    if (len && s[0] >= 0x3c && s[0] <= 0x3f)
        q->priv = s[i++];
    if (i == len)
        return;
    q->n = 1;
    for (; i < len; i++) {
        if (s[i] >= '0' && s[i] <= '9') {
            if (q->n <= NPARAM && q->v[q->n - 1] < 100000)
                q->v[q->n - 1] = q->v[q->n - 1] * 10 + (s[i] - '0');
        } else if (s[i] == ';' || s[i] == ':') {
            q->n++;             /* sub-parameters (:) are counted alike: none is used */
        }
    }
    if (q->n > NPARAM)
        q->n = NPARAM;
}

/* ESC [ number ~ : the editing keys. 1 and 4 are Home and End as screen,
 * tmux and the Linux console send them (Find and Select on a VT220), 7
 * and 8 rxvt's. 200 starts a bracketed paste. */
static int tilde(KeyParser *p, int code, TermEvent *ev)
{
    switch (code) {
    case 1: case 7: return key(ev, TK_HOME);
    case 4: case 8: return key(ev, TK_END);
    case 2:         return key(ev, TK_INS);
    case 3:         return key(ev, TK_DEL);
    case 5:         return key(ev, TK_PGUP);
    case 6:         return key(ev, TK_PGDN);
    case 200:
        p->paste = 1;
        return R_DROP;
    default:        return R_DROP;      /* function keys, a stray paste end */
    }
}

/* An answer awaited has come (the attributes', or a status report). */
static void answered(KeyParser *p)
{
    if (p->pending > 0)
        p->pending--;
}

/* A whole CSI sequence. Of the modifiers (the second parameter) only
 * Shift on an arrow counts; the rest are ignored: Ctrl-Home is Home. */
static int csi_meaning(KeyParser *p, const Seq *q, TermEvent *ev)
{
    if (q->inter)
        return R_DROP;
    if (q->priv == '<' && (q->final == 'M' || q->final == 'm') && q->n >= 3)
        return mouse(p, q->v[0], q->v[1] - 1, q->v[2] - 1, q->final == 'm', ev);
    if (q->priv == '?' && q->final == 'c')
        answered(p);            /* the primary attributes: the last answer of its questions */
    if (q->priv)
        return R_DROP;
    /* the arrows with Shift: xterm's modifier parameter (ESC [ 1 ; 2 A,
     * Shift in bit 0 of the value less one), or rxvt's lower-case finals */
    int shift = q->n >= 2 && q->v[1] >= 2 && ((q->v[1] - 1) & 1);
    switch (q->final) {
    case 'A': return key(ev, shift ? TK_SUP : TK_UP);
    case 'B': return key(ev, shift ? TK_SDOWN : TK_DOWN);
    case 'C': return key(ev, shift ? TK_SRIGHT : TK_RIGHT);
    case 'D': return key(ev, shift ? TK_SLEFT : TK_LEFT);
    case 'a': return q->n == 0 ? key(ev, TK_SUP) : R_DROP;
    case 'b': return q->n == 0 ? key(ev, TK_SDOWN) : R_DROP;
    case 'c': return q->n == 0 ? key(ev, TK_SRIGHT) : R_DROP;
    case 'd': return q->n == 0 ? key(ev, TK_SLEFT) : R_DROP;
    case 'H': return key(ev, TK_HOME);
    case 'F': return key(ev, TK_END);
    case 'Z': return key(ev, TK_BTAB);
    case '~':
    case '^':               /* rxvt: with Ctrl */
    case '@':               /* rxvt: with Ctrl and Shift */
    case '$':               /* rxvt: with Shift (see rxvt_shift) */
        return q->n >= 1 ? tilde(p, q->v[0], ev) : R_DROP;
    case 'n':
        /* the answer to a status request (0 ok, 3 a malfunction: answered all the same) */
        if (q->n == 1 && (q->v[0] == 0 || q->v[0] == 3)) {
            answered(p);
            ev->type = TE_READY;
            return R_EVENT;
        }
        return R_DROP;
    default:
        return R_DROP;  /* focus (I, O), position reports (R), F1-F4 (P-S), ... */
    }
}

/* rxvt ends its shifted editing keys in '$' (ESC [ 7 $: Shift-Home),
 * which ECMA-48 reads as an intermediate byte: a '$' right after plain
 * digits, with no final byte after it, ends the key. b[o..pend) are the
 * parameters, b[pend..end) the intermediates. */
static int rxvt_shift(const unsigned char *b, size_t o, size_t pend, size_t end)
{
    if (end != pend + 1 || b[pend] != '$' || pend == o)
        return 0;
    for (size_t k = o; k < pend; k++)
        if (b[k] < '0' || b[k] > '9')
            return 0;
    return 1;
}

/* ESC [ at b[0..o): the rest of a CSI sequence from b[o]. */
static int csi(KeyParser *p, size_t o, TermEvent *ev, size_t *used)
{
    const unsigned char *b = p->b;
    size_t len = p->len, i = o;
    if (i < len && b[i] == '[') {
        /* the Linux console's F1-F5: ESC [ [ A..E */
        if (i + 1 >= len)
            return R_MORE;
        *used = i + 2;
        return R_DROP;
    }
    if (i < len && b[i] == 'M') {
        /* X10 mouse: three bytes, each value + 32 (cells from 1) */
        if (i + 3 >= len)
            return R_MORE;
        *used = i + 4;
        int bt = b[i + 1] - 32;
        return mouse(p, bt, b[i + 2] - 33, b[i + 3] - 33, (bt & 3) == 3 && !(bt & 64), ev);
    }
    while (i < len && b[i] >= 0x30 && b[i] <= 0x3f)
        i++;
    size_t pend = i;
    while (i < len && b[i] >= 0x20 && b[i] <= 0x2f)
        i++;
    if (i == len) {
        if (i <= SEQ_MAX)
            return R_MORE;
        p->skip = 1;            /* garbage: dropped up to its final byte */
        p->run = 0;
        *used = i;
        return R_DROP;
    }
    Seq q = { 0 };
    params(b + o, pend - o, &q);
    if (b[i] < 0x40 || b[i] > 0x7e) {
        if (rxvt_shift(b, o, pend, i)) {
            *used = i;
            q.final = '$';
            return csi_meaning(p, &q, ev);
        }
        /* not a sequence after all: what came so far goes, the byte that
         * broke it is read afresh (an ESC starts the next one) */
        *used = i;
        return R_DROP;
    }
    *used = i + 1;
    q.inter = i > pend;
    q.final = b[i];
    return csi_meaning(p, &q, ev);
}

/* SS3 (ESC O and a final byte): the cursor keys in the terminal's
 * application mode, Home and End, and the numeric keypad's keys in its
 * application mode, which are read as the characters on them. */
static int ss3(KeyParser *p, size_t o, TermEvent *ev, size_t *used)
{
    static const char pad[] = "*+,-./0123456789";   /* ESC O j .. ESC O y */
    const unsigned char *b = p->b;
    size_t len = p->len, i = o;
    while (i < len && i - o < 8 && ((b[i] >= '0' && b[i] <= '9') || b[i] == ';'))
        i++;                    /* modifiers, as some terminals send (ESC O 5 A) */
    if (i == len)
        return R_MORE;
    *used = i + 1;
    int f = b[i];
    if (f < 0x40 || f > 0x7e) {
        *used = i;
        return R_DROP;
    }
    switch (f) {
    case 'A': return key(ev, TK_UP);
    case 'B': return key(ev, TK_DOWN);
    case 'C': return key(ev, TK_RIGHT);
    case 'D': return key(ev, TK_LEFT);
    case 'H': return key(ev, TK_HOME);
    case 'F': return key(ev, TK_END);
    case 'M': return key(ev, TK_ENTER);
    case 'I': return key(ev, TK_TAB);
    case 'X': return key(ev, '=');
    default:
        if (f >= 'j' && f <= 'y')
            return key(ev, pad[f - 'j']);
        return R_DROP;          /* F1-F4 (P-S) and the rest */
    }
}

/* The CSI sequence from b[o] (after ESC ESC [): 1 when it is a key
 * (Alt with an arrow or an editing key: a final the keys use, no '?',
 * '>' or '<' before its parameters), 0 when it is something else (a
 * terminal's answer), -1 when it has not ended yet. */
static int alt_key_csi(const unsigned char *b, size_t o, size_t len)
{
    if (o >= len)
        return -1;
    int priv = b[o] == '?' || b[o] == '>' || b[o] == '<' || b[o] == '=';
    for (size_t i = o; i < len; i++) {
        unsigned char c = b[i];
        if (c >= 0x40 && c <= 0x7e)
            return !priv && c != 'M' && strchr("ABCDHFZ~$^@abcd", c) != NULL;
        if (c < 0x20 || c > 0x3f)
            return 0;           /* not a CSI sequence: no key either */
    }
    return -1;
}

/* A string's introducer (its kind: ']' '_' ...), intro bytes long. */
static int string_start(KeyParser *p, int kind, size_t intro, size_t *used)
{
    p->string = kind;
    p->run = 0;
    *used = intro;
    return R_DROP;
}

/* An ESC at b[0]. */
static int escape(KeyParser *p, TermEvent *ev, size_t *used)
{
    const unsigned char *b = p->b;
    if (p->len < 2)
        return R_MORE;
    switch (b[1]) {
    case '[':
        return csi(p, 2, ev, used);
    case 'O':
        return ss3(p, 2, ev, used);
    case ']': case 'P': case '_': case '^': case 'X':
        /* OSC, DCS, APC, PM, SOS: the strings a terminal answers
         * questions with (a colour, its name, kitty's graphics), dropped
         * to their end */
        return string_start(p, b[1], 2, used);
    case '\\':
        /* ST with no string open: the end of one given up (or cut by a
         * lost byte), no Esc */
        *used = 2;
        return R_DROP;
    case ESC:
        /* ESC ESC [ ...: a key with Alt (rxvt), dropped whole; but an
         * answer of the terminal's (a status or attributes report, a
         * mouse report) right after a lone Esc is not a key: the Esc is
         * the user's and the answer is read afresh (on a loaded machine
         * the two arrive together, and the Esc was lost). ESC ESC
         * otherwise (a string after it too): the first is an Esc of its
         * own */
        if (p->len < 3)
            return R_MORE;
        if (b[2] == '[') {
            int k = alt_key_csi(b, 3, p->len);
            if (k < 0)
                return R_MORE;
            if (!k) {
                *used = 1;
                return key(ev, TK_ESC);
            }
        }
        if (b[2] == '[' || b[2] == 'O') {
            int r = b[2] == '[' ? csi(p, 3, ev, used) : ss3(p, 3, ev, used);
            return r == R_MORE ? R_MORE : R_DROP;
        }
        *used = 1;
        return key(ev, TK_ESC);
    default:
        /* ESC and a character: no sequence a terminal sends but Alt (or
         * Meta) with the key, and what Esc typed just before the key
         * looks like when both arrive together (tmux joins them when
         * they come within its escape-time, 500 ms by default): read as
         * Esc, then the key, as curses did */
        *used = 1;
        return key(ev, TK_ESC);
    }
}

/* ==== The 8-bit forms ==== */

/* A C1 control at b[0]: its 8-bit code with its length in *intro, 0 when
 * b[0] starts none, -1 when the next byte decides. In a UTF-8 locale a
 * C1 control is the character U+0080-U+009F (C2 80 .. C2 9F); otherwise
 * the byte 0x80-0x9f itself, which is no character in Latin-1. */
static int c1_at(const KeyParser *p, size_t *intro)
{
    const unsigned char *b = p->b;
    if (!p->utf8) {
        *intro = 1;
        return b[0] >= 0x80 && b[0] <= 0x9f ? b[0] : 0;
    }
    if (b[0] != 0xc2)
        return 0;
    if (p->len < 2)
        return -1;
    *intro = 2;
    return b[1] >= 0x80 && b[1] <= 0x9f ? b[1] : 0;
}

/* The C1 control c (intro bytes at b[0]) as its 7-bit ESC form would read. */
static int c1(KeyParser *p, int c, size_t intro, TermEvent *ev, size_t *used)
{
    switch (c) {
    case C1_CSI: return csi(p, intro, ev, used);
    case C1_SS3: return ss3(p, intro, ev, used);
    case C1_OSC: return string_start(p, ']', intro, used);
    case C1_DCS: return string_start(p, 'P', intro, used);
    case C1_APC: return string_start(p, '_', intro, used);
    case C1_PM:  return string_start(p, '^', intro, used);
    case C1_SOS: return string_start(p, 'X', intro, used);
    default:
        *used = intro;          /* ST with no string, and the rest: no key */
        return R_DROP;
    }
}

/* ==== Things dropped whole ==== */

/* A string has ended (or was cancelled, or given up) at b[end). */
static int string_end(KeyParser *p, size_t end, size_t *used)
{
    p->string = 0;
    p->run = 0;
    *used = end;
    return R_DROP;
}

/* Inside a string: up to BEL or ST (ESC \, or the 8-bit ST); CAN and
 * SUB cancel it, an ESC of anything else ends it and starts a sequence.
 * ESC ESC is one ESC of the string's: tmux's passthrough (DCS tmux; ...)
 * doubles each ESC of what it wraps, ST too. The body is dropped as it
 * comes; after KP_STRING_MAX bytes the string is given up. */
static int skip_string(KeyParser *p, size_t *used)
{
    const unsigned char *b = p->b;
    size_t len = p->len;
    for (size_t i = 0; i < len; i++) {
        unsigned c = b[i];
        if (c == 7 || c == 0x18 || c == 0x1a)
            return string_end(p, i + 1, used);
        if (c == ESC || (c == 0xc2 && p->utf8)) {
            if (i + 1 == len) {
                *used = i;      /* keep it: its terminator's second byte may follow */
                return i ? R_DROP : R_MORE;
            }
            if (c == ESC && b[i + 1] == ESC) {
                i++;
                p->run++;
            } else if (c == ESC) {
                return string_end(p, b[i + 1] == '\\' ? i + 2 : i, used);
            } else if (b[i + 1] == C1_ST) {
                return string_end(p, i + 2, used);
            }
        } else if (c == C1_ST && !p->utf8) {
            return string_end(p, i + 1, used);
        }
        if (++p->run > KP_STRING_MAX)
            return string_end(p, i + 1, used);  /* no answer is this long: the rest is read afresh */
    }
    *used = len;
    return R_DROP;
}

/* Inside a bracketed paste: everything up to ESC [ 201 ~. Pasted text
 * would otherwise be read as keys (a pasted q quits). */
static int skip_paste(KeyParser *p, size_t *used)
{
    static const unsigned char end[] = "\033[201~";
    const size_t n = sizeof end - 1;
    for (size_t i = 0; i < p->len; i++) {
        size_t k = 0;
        while (k < n && i + k < p->len && p->b[i + k] == end[k])
            k++;
        if (k == n) {
            p->paste = 0;
            *used = i + n;
            return R_DROP;
        }
        if (i + k == p->len) {
            *used = i;          /* the end may be arriving: keep its start */
            return i ? R_DROP : R_MORE;
        }
    }
    *used = p->len;
    return R_DROP;
}

/* The rest of an overlong CSI sequence, up to its final byte (or
 * KP_STRING_MAX bytes: then what follows is read afresh). */
static int skip_csi(KeyParser *p, size_t *used)
{
    for (size_t i = 0; i < p->len; i++) {
        unsigned c = p->b[i];
        if (c >= 0x20 && c <= 0x3f && ++p->run <= KP_STRING_MAX)
            continue;
        p->skip = 0;
        p->run = 0;
        *used = c >= 0x40 && c <= 0x7e ? i + 1 : i;
        return R_DROP;
    }
    *used = p->len;
    return R_DROP;
}

/* ==== Events ==== */

/* The input went quiet with b[0..len) unfinished: a lone ESC is the Esc
 * key, any other start of a sequence or character is dropped. */
static int decide(KeyParser *p, TermEvent *ev)
{
    if (p->len >= 4 && p->b[0] == ESC && p->b[1] == '[' && rxvt_shift(p->b, 2, p->len - 1, p->len)) {
        Seq q = { .final = '$' };
        params(p->b + 2, p->len - 3, &q);
        consume(p, p->len);
        return csi_meaning(p, &q, ev);
    }
    if (p->len == 1 && p->b[0] == ESC) {
        consume(p, 1);
        return key(ev, TK_ESC);
    }
    if (p->len >= 2 && p->b[0] == ESC && p->b[1] == ESC) {
        consume(p, 1);          /* Esc twice */
        return key(ev, TK_ESC);
    }
    consume(p, p->len);
    return R_DROP;
}

/* One step at b[0]: what it is, and its length in *used. */
static int step(KeyParser *p, TermEvent *ev, size_t *used)
{
    if (p->string)
        return skip_string(p, used);
    if (p->paste)
        return skip_paste(p, used);
    if (p->skip)
        return skip_csi(p, used);
    if (p->b[0] == ESC)
        return escape(p, ev, used);
    size_t intro = 1;
    int c = c1_at(p, &intro);
    if (c < 0)
        return R_MORE;
    if (c > 0)
        return c1(p, c, intro, ev, used);
    return plain(p, ev, used);
}

int kp_awaiting(const KeyParser *p, double now_ms)
{
    return now_ms - p->asked_ms < KP_LATE_MS ? p->pending : 0;
}

/* The quiet after which what is left is decided. */
static int quiet_needed(const KeyParser *p, double now_ms)
{
    if (p->string || p->paste || p->skip)
        return KP_IDLE_MS;
    return kp_awaiting(p, now_ms) ? KP_REPLY_MS : KP_ESC_MS;
}

int kp_next(KeyParser *p, TermEvent *ev, double now_ms)
{
    memset(ev, 0, sizeof *ev);
    double quiet = now_ms - p->last_ms;
    if (p->pending && !kp_awaiting(p, now_ms))
        p->pending = 0;         /* too late: not coming */
    for (;;) {
        if (p->len == 0) {
            if ((p->string || p->paste || p->skip) && quiet >= KP_IDLE_MS)
                lost_end(p);
            return 0;
        }
        size_t used = 0;
        int r = step(p, ev, &used);
        if (r == R_MORE) {
            if (quiet < quiet_needed(p, now_ms))
                return 0;
            if (p->string || p->paste) {
                /* a terminator lost (or never sent): the input is keys again */
                lost_end(p);
                consume(p, p->len);
                continue;
            }
            if (decide(p, ev) == R_EVENT)
                return 1;
            continue;
        }
        consume(p, used);
        if (r == R_EVENT)
            return 1;
        memset(ev, 0, sizeof *ev);
    }
}

int kp_wait_ms(const KeyParser *p, double now_ms)
{
    if (!p->len && !p->string && !p->paste && !p->skip)
        return -1;
    double left = p->last_ms + quiet_needed(p, now_ms) - now_ms;
    return left > 0 ? (int)left + (left > (int)left) : 0;
}

void kp_expect(KeyParser *p, int more, double now_ms)
{
    if (!kp_awaiting(p, now_ms))
        p->pending = 0;
    p->pending += more;
    p->asked_ms = now_ms;
}
