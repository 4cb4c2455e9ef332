/* vt: the screen model and its encoder. want is what the terminal should
 * show, shown what it shows; vt_encode writes the bytes between them.
 *
 * Over SSH every byte counts, so the bytes are chosen with some care:
 * - only cells that look different are sent, and "look" is what the eye
 *   sees: an upper half block of a on b looks like a lower half block of
 *   b on a, a space on c like a full block of c. Each cell is written in
 *   whichever of its looks needs the fewest colour changes from the
 *   colours in force: a dithered surface of two colours then needs no
 *   change at all along a row;
 * - a colour change is one SGR sequence in its shortest form (both
 *   colours in one, or a reset and what differs from the defaults);
 * - between changed cells the cursor moves by the shortest of absolute
 *   and relative moves, CR/LF, or by writing the cells in between again
 *   when that is shorter;
 * - runs of blank cells are erased (EL to the end of the line, ECH).
 * The terminal's state (cursor, colours) is followed exactly; where it is
 * not known (after writing the last column without the newline glitch,
 * at the start) absolute forms are used. */

#define _XOPEN_SOURCE 700

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <wchar.h>

#include "safetext.h"
#include "tty.h"

#define CH_UPPER 0x2580u
#define CH_LOWER 0x2584u
#define CH_FULL  0x2588u

#define ANY      0xffffffffu    /* a colour the cell does not show */
/* Colours as seen: the default foreground and background are different
 * colours, and neither can stand in for the other. */
#define SEEN_DFG 0xfffffffeu
#define SEEN_DBG 0xfffffffdu
#define BLOCK    0x80000000u    /* Look.a of the block family */

#define GAP_TRY  12             /* unchanged cells worth trying to rewrite */

/* ==== Looks ==== */

typedef struct {
    uint32_t a, b, c;
} Look;

static inline uint32_t seen_fg(uint32_t k) { return k == CK_DEFAULT ? SEEN_DFG : k; }
static inline uint32_t seen_bg(uint32_t k) { return k == CK_DEFAULT ? SEEN_DBG : k; }

static inline int block_glyph(uint32_t ch)
{
    return ch == ' ' || ch == CH_FULL || ch == CH_UPPER || ch == CH_LOWER;
}

/* Blocks and spaces without attributes: their top and bottom colours.
 * Anything else: the glyph, attributes and both colours. */
static inline Look look(const VtCell *c)
{
    if (!c->attr && block_glyph(c->ch)) {
        uint32_t f = seen_fg(c->fg), b = seen_bg(c->bg);
        switch (c->ch) {
        case ' ':      return (Look){ BLOCK, b, b };
        case CH_FULL:  return (Look){ BLOCK, f, f };
        case CH_UPPER: return (Look){ BLOCK, f, b };
        default:       return (Look){ BLOCK, b, f };
        }
    }
    return (Look){ c->ch | (uint32_t)c->attr << 24, seen_fg(c->fg), seen_bg(c->bg) };
}

int vt_same_look(const VtCell *x, const VtCell *y)
{
    Look a = look(x), b = look(y);
    return a.a == b.a && a.b == b.b && a.c == b.c;
}

static inline int blank_default(const VtCell *c)
{
    return c->ch == ' ' && !c->attr && c->bg == CK_DEFAULT;
}

/* ==== Set-up ==== */

void vt_init(Vt *v, const VtCaps *caps)
{
    memset(v, 0, sizeof *v);
    v->caps = *caps;
    v->cy = v->cx = -1;
}

void vt_free(Vt *v)
{
    free(v->want);
    free(v->shown);
    free(v->blank);
    free(v->buf);
    VtCaps caps = v->caps;
    vt_init(v, &caps);
}

static const VtCell blank_cell = { ' ', CK_DEFAULT, CK_DEFAULT, 0 };

static void fill_blank(VtCell *c, size_t n)
{
    for (size_t i = 0; i < n; i++)
        c[i] = blank_cell;
}

int vt_resize(Vt *v, int cols, int rows)
{
    if (cols < 0 || rows < 0)
        return -1;
    size_t n = (size_t)cols * (size_t)rows;
    if (n > v->ncap || (size_t)cols > v->ncap) {
        size_t cap = n > (size_t)cols ? n : (size_t)cols;
        VtCell *w = realloc(v->want, cap * sizeof *w);
        if (w)
            v->want = w;
        VtCell *s = realloc(v->shown, cap * sizeof *s);
        if (s)
            v->shown = s;
        int *b = realloc(v->blank, (cap + 1) * sizeof *b);
        if (b)
            v->blank = b;
        if (!w || !s || !b)
            return -1;
        v->ncap = cap;
    }
    v->cols = cols;
    v->rows = rows;
    fill_blank(v->want, n);
    v->valid = 0;
    return 0;
}

void vt_clear(Vt *v)
{
    fill_blank(v->want, (size_t)v->cols * (size_t)v->rows);
}

void vt_invalidate(Vt *v)
{
    v->valid = 0;
}

VtCell *vt_at(Vt *v, int y, int x)
{
    if (y < 0 || y >= v->rows || x < 0 || x >= v->cols)
        return NULL;
    return &v->want[(size_t)y * v->cols + x];
}

/* The code point of a well-formed UTF-8 character (safetext_next's
 * piece, which holds nothing else). */
static uint32_t utf8_cp(const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    int n = p[0] < 0x80 ? 0 : p[0] >= 0xf0 ? 3 : p[0] >= 0xe0 ? 2 : 1;
    uint32_t c = p[0] & (n == 0 ? 0x7f : 0x3f >> n);
    for (int i = 1; i <= n; i++)
        c = c << 6 | (p[i] & 0x3f);
    return c;
}

/* The columns a piece of safe text takes: an escape (ASCII) one a
 * byte, a character one (vt_text draws what is not one wide as '?'). */
static int piece_cols(const char *piece)
{
    return (unsigned char)piece[0] < 0x80 ? (int)strlen(piece) : 1;
}

int vt_text_cols(const char *s, size_t bytes)
{
    int n = 0;
    for (size_t i = 0; i < bytes && s[i];) {
        char piece[SAFETEXT_PIECE];
        i += safetext_next(s + i, piece, SAFETEXT_TEXT);
        n += piece_cols(piece);
    }
    return n;
}

int vt_text(Vt *v, int y, int x, const char *s, int maxw, uint8_t attr)
{
    int used = 0;
    while (*s && used < maxw) {
        /* a file's name or a loader's words: controls show by their
         * bytes (safetext.h), never reach the terminal */
        char piece[SAFETEXT_PIECE];
        s += safetext_next(s, piece, SAFETEXT_TEXT);
        if ((unsigned char)piece[0] >= 0x80) {
            VtCell *c = vt_at(v, y, x + used);
            if (!c)
                break;
            /* one column each keeps the model simple: wide and combining
             * characters (rare in file names) show as '?' */
            uint32_t ch = utf8_cp(piece);
            *c = (VtCell){ wcwidth((wchar_t)ch) == 1 ? ch : '?', CK_DEFAULT, CK_DEFAULT, attr };
            used++;
            continue;
        }
        for (const char *p = piece; *p && used < maxw; p++) {
            VtCell *c = vt_at(v, y, x + used);
            if (!c)
                return used;
            *c = (VtCell){ (uint32_t)(unsigned char)*p, CK_DEFAULT, CK_DEFAULT, attr };
            used++;
        }
    }
    return used;
}

/* x, y == -2: centred; x < 0: against the right edge, y < 0: just above
 * the last row (tty.h: term_draw_box_at). Each line is drawn as vt_text
 * draws it; the widths are its columns. */
void vt_box(Vt *v, const char *const *lines, int n, int bx, int by)
{
    int H = v->rows, W = v->cols;
    int w = 0;
    for (int i = 0; i < n; i++) {
        int len = vt_text_cols(lines[i], strlen(lines[i]));
        if (len > w)
            w = len;
    }
    w += 4;
    if (w > W)
        w = W;
    int h = n + 2 > H - 1 ? H - 1 : n + 2;
    int x0 = bx == -2 ? (W - w) / 2 : bx < 0 ? W - w : bx;
    int y0 = by == -2 ? (H - 1 - h) / 2 : by < 0 ? H - 1 - h : by;
    for (int r = 0; r < h; r++) {
        int edge = r == 0 || r == h - 1;
        for (int x = 0; x < w; x++)
            vt_text(v, y0 + r, x0 + x, edge ? (x == 0 || x == w - 1 ? "+" : "-")
                                            : x == 0 || x == w - 1 ? "|" : " ", 1, 0);
        if (!edge && r - 1 < n && w > 3)
            vt_text(v, y0 + r, x0 + 2, lines[r - 1], w - 3, 0);
    }
}

/* ==== Output buffer ==== */

static int need(Vt *v, size_t n)
{
    if (v->oom)
        return -1;
    if (v->len + n <= v->cap)
        return 0;
    size_t cap = v->cap ? v->cap : 4096;
    while (cap < v->len + n)
        cap *= 2;
    char *b = realloc(v->buf, cap);
    if (!b) {
        v->oom = 1;
        return -1;
    }
    v->buf = b;
    v->cap = cap;
    return 0;
}

static void put(Vt *v, const char *s, size_t n)
{
    if (need(v, n) == 0) {
        memcpy(v->buf + v->len, s, n);
        v->len += n;
    }
}

static char *put_uint(char *p, unsigned n)
{
    char tmp[10];
    int k = 0;
    do {
        tmp[k++] = (char)('0' + n % 10);
        n /= 10;
    } while (n);
    while (k)
        *p++ = tmp[--k];
    return p;
}

static int utf8_put(char *p, uint32_t c)
{
    if (c < 0x80) {
        p[0] = (char)c;
        return 1;
    }
    if (c < 0x800) {
        p[0] = (char)(0xc0 | c >> 6);
        p[1] = (char)(0x80 | (c & 0x3f));
        return 2;
    }
    if (c < 0x10000) {
        p[0] = (char)(0xe0 | c >> 12);
        p[1] = (char)(0x80 | (c >> 6 & 0x3f));
        p[2] = (char)(0x80 | (c & 0x3f));
        return 3;
    }
    p[0] = (char)(0xf0 | c >> 18);
    p[1] = (char)(0x80 | (c >> 12 & 0x3f));
    p[2] = (char)(0x80 | (c >> 6 & 0x3f));
    p[3] = (char)(0x80 | (c & 0x3f));
    return 4;
}

/* ==== Colours ==== */

/* The SGR taking the terminal from its colours to fg, bg (ANY: keep
 * what is there) and attr, into p: the shorter of changing what differs
 * and resetting then setting what is not default. Returns its length
 * (0: nothing to change); the state it leaves in *nfg, *nbg. */
static int sgr_build(const Vt *v, uint32_t fg, uint32_t bg, uint8_t attr, char *p, uint32_t *nfg,
                     uint32_t *nbg)
{
    char inc[2 * SGR_COLOUR_MAX + 16], rst[2 * SGR_COLOUR_MAX + 16];
    int ni = -1;
    if (v->sgr_ok) {
        char *q = inc;
        if (attr != v->attr) {
            memcpy(q, attr ? "7;" : "27;", attr ? 2 : 3);
            q += attr ? 2 : 3;
        }
        if (fg != ANY && fg != v->fg) {
            q = sgr_colour(q, fg, 0);
            *q++ = ';';
        }
        if (bg != ANY && bg != v->bg) {
            q = sgr_colour(q, bg, 1);
            *q++ = ';';
        }
        ni = (int)(q - inc);
        if (ni == 0) {
            *nfg = v->fg;
            *nbg = v->bg;
            return 0;
        }
    }
    char *q = rst;
    if (attr) {
        memcpy(q, "7;", 2);
        q += 2;
    }
    if (fg != ANY && fg != CK_DEFAULT) {
        q = sgr_colour(q, fg, 0);
        *q++ = ';';
    }
    if (bg != ANY && bg != CK_DEFAULT) {
        q = sgr_colour(q, bg, 1);
        *q++ = ';';
    }
    /* "\e[m" resets all; "\e[0;...m" resets, then sets */
    int nr = q == rst ? 0 : (int)(q - rst) + 2;
    const char *src;
    int n;
    if (ni >= 0 && ni <= nr) {
        src = inc;
        n = ni - 1;             /* less the last ';' */
        *nfg = fg == ANY ? v->fg : fg;
        *nbg = bg == ANY ? v->bg : bg;
    } else {
        src = rst;
        n = q == rst ? 0 : (int)(q - rst) - 1;
        *nfg = fg == ANY ? CK_DEFAULT : fg;
        *nbg = bg == ANY ? CK_DEFAULT : bg;
    }
    p[0] = '\033';
    p[1] = '[';
    int k = 2;
    if (src == rst && n > 0) {
        p[k++] = '0';
        p[k++] = ';';
    }
    memcpy(p + k, src, (size_t)n);
    k += n;
    p[k++] = 'm';
    return k;
}

static void sgr_to(Vt *v, uint32_t fg, uint32_t bg, uint8_t attr)
{
    char s[2 * SGR_COLOUR_MAX + 24];
    uint32_t nf, nb;
    int n = sgr_build(v, fg, bg, attr, s, &nf, &nb);
    if (n)
        put(v, s, (size_t)n);
    v->fg = nf;
    v->bg = nb;
    v->attr = attr;
    v->sgr_ok = 1;
}

/* ==== Writing a cell ==== */

typedef struct {
    uint32_t ch, fg, bg;
} Rep;

/* The ways to draw a cell's look: a block look as a space or a full
 * block (one colour), an upper or a lower half block (two); anything
 * else only as itself. */
static int reps(const VtCell *c, Rep *r)
{
    if (c->attr || !block_glyph(c->ch)) {
        r[0] = (Rep){ c->ch, c->fg, c->bg };
        return 1;
    }
    Look l = look(c);
    uint32_t t = l.b, b = l.c;
    int n = 0;
    /* a seen colour as a foreground / background key (ANY: impossible) */
#define AS_FG(s) ((s) == SEEN_DBG ? ANY : (s) == SEEN_DFG ? CK_DEFAULT : (s))
#define AS_BG(s) ((s) == SEEN_DFG ? ANY : (s) == SEEN_DBG ? CK_DEFAULT : (s))
    if (t == b) {
        if (AS_BG(t) != ANY)
            r[n++] = (Rep){ ' ', ANY, AS_BG(t) };
        if (AS_FG(t) != ANY)
            r[n++] = (Rep){ CH_FULL, AS_FG(t), ANY };
        return n;
    }
    if (AS_FG(t) != ANY && AS_BG(b) != ANY)
        r[n++] = (Rep){ CH_UPPER, AS_FG(t), AS_BG(b) };
    if (AS_FG(b) != ANY && AS_BG(t) != ANY)
        r[n++] = (Rep){ CH_LOWER, AS_FG(b), AS_BG(t) };
#undef AS_FG
#undef AS_BG
    return n;
}

static inline int utf8_len(uint32_t c)
{
    return c < 0x80 ? 1 : c < 0x800 ? 2 : c < 0x10000 ? 3 : 4;
}

/* The fewest bytes to write cell c from the colours of v. */
static int cheapest(const Vt *v, const VtCell *c)
{
    Rep r[3];
    int n = reps(c, r), best = 1 << 30;
    char s[2 * SGR_COLOUR_MAX + 24];
    for (int k = 0; k < n; k++) {
        uint32_t nf, nb;
        int cost = sgr_build(v, r[k].fg, r[k].bg, c->attr, s, &nf, &nb) + utf8_len(r[k].ch);
        best = cost < best ? cost : best;
    }
    return best;
}

/* Write want's cell x of row y at the cursor (which is there), in the
 * look that costs the fewest bytes from the colours in force, counting
 * what the colours it leaves cost the next cell: a space on a (bg a)
 * and a full block of a (fg a) cost alike, but in a dither of a and b
 * only one of them leaves both colours in force for what follows. */
static void write_cell(Vt *v, int y, int x)
{
    size_t i = (size_t)y * v->cols + x;
    const VtCell *c = &v->want[i], *next = x + 1 < v->cols ? c + 1 : NULL;
    Rep r[3];
    int n = reps(c, r), best = 0, best_cost = 1 << 30;
    char s[2 * SGR_COLOUR_MAX + 24];
    for (int k = 0; k < n; k++) {
        Vt after = *v;
        int cost = sgr_build(v, r[k].fg, r[k].bg, c->attr, s, &after.fg, &after.bg) + utf8_len(r[k].ch);
        if (next && n > 1) {
            after.attr = c->attr;
            after.sgr_ok = 1;
            cost += cheapest(&after, next);
        }
        if (cost < best_cost) {
            best_cost = cost;
            best = k;
        }
    }
    sgr_to(v, r[best].fg, r[best].bg, c->attr);
    char u[4];
    put(v, u, (size_t)utf8_put(u, r[best].ch));
    v->shown[i] = (VtCell){ r[best].ch, v->fg, v->bg, c->attr };
    if (x + 1 < v->cols) {
        v->cx = x + 1;
    } else if (v->caps.xenl) {
        v->cx = v->cols;        /* at the margin, the wrap pending */
    } else {
        v->cy = v->cx = -1;     /* wrapped, or not: unknown */
    }
}

/* ==== Moving the cursor ==== */

/* "\e[" n c, n left out when 1. */
static int csi_n(char *p, unsigned n, char c)
{
    char *q = p;
    *q++ = '\033';
    *q++ = '[';
    if (n != 1)
        q = put_uint(q, n);
    *q++ = c;
    return (int)(q - p);
}

/* Across a row from column c (known) to x: relative (BS for one to the
 * left), or absolute (CHA). Returns the bytes (0: there already), or
 * 99 when the terminal has no way. */
static int across(const Vt *v, int c, int x, char *p)
{
    if (c == x)
        return 0;
    int dx = x - c;
    char t[16];
    int n = 99, k;
    if (dx == -1) {
        p[0] = '\b';
        return 1;
    }
    if (v->caps.rel)
        n = csi_n(p, (unsigned)(dx > 0 ? dx : -dx), dx > 0 ? 'C' : 'D');
    if (v->caps.hpa && (k = csi_n(t, (unsigned)x + 1, 'G')) < n) {
        memcpy(p, t, (size_t)k);
        n = k;
    }
    return n;
}

/* The shortest bytes moving the cursor to (y, x) into p: the absolute
 * move, or a vertical part (none, line feeds, CUD/CUU, VPA), with or
 * without a carriage return, and then a horizontal part. */
static int move_build(const Vt *v, int y, int x, char *p)
{
    char best[48], cand[48], h[16];
    char *q = best;
    *q++ = '\033';
    *q++ = '[';
    if (y || x)
        q = put_uint(q, (unsigned)y + 1);
    if (x) {
        *q++ = ';';
        q = put_uint(q, (unsigned)x + 1);
    }
    *q++ = 'H';
    int nb = (int)(q - best);
    if (v->cy >= 0) {
        int dy = y - v->cy;
        /* a column is known unless the cursor waits at the margin */
        int col_known = v->cx >= 0 && v->cx < v->cols;
        for (int cr = 0; cr < 2; cr++) {
            if (!cr && !col_known)
                continue;
            for (int way = 0; way < 4; way++) {
                int n = 0;
                if (cr)
                    cand[n++] = '\r';
                if (way == 0) {             /* on the row already */
                    if (dy)
                        continue;
                } else if (way == 1) {      /* line feeds: down, same column */
                    if (dy <= 0 || dy > 4 || !v->caps.lf)
                        continue;
                    for (int k = 0; k < dy; k++)
                        cand[n++] = '\n';
                } else if (way == 2) {      /* CUD / CUU */
                    if (!dy || !v->caps.rel)
                        continue;
                    n += csi_n(cand + n, (unsigned)(dy > 0 ? dy : -dy), dy > 0 ? 'B' : 'A');
                } else {                    /* VPA */
                    if (!dy || !v->caps.vpa)
                        continue;
                    n += csi_n(cand + n, (unsigned)y + 1, 'd');
                }
                int k = across(v, cr ? 0 : v->cx, x, h);
                if (k >= 99)
                    continue;
                memcpy(cand + n, h, (size_t)k);
                n += k;
                if (n < nb) {
                    memcpy(best, cand, (size_t)n);
                    nb = n;
                }
            }
        }
    }
    memcpy(p, best, (size_t)nb);
    return nb;
}

static void move_to(Vt *v, int y, int x)
{
    if (v->cy == y && v->cx == x)
        return;
    char s[48];
    put(v, s, (size_t)move_build(v, y, x, s));
    v->cy = y;
    v->cx = x;
}

/* Get the cursor to (y, x), where a changed cell is: by a move, or by
 * writing the unchanged cells between when the cursor is a few cells to
 * the left on the same row and that is no longer. */
static void go_to(Vt *v, int y, int x)
{
    if (v->cy == y && v->cx == x)
        return;
    int gap = x - v->cx;
    if (v->cy != y || v->cx < 0 || gap <= 0 || gap > GAP_TRY) {
        move_to(v, y, x);
        return;
    }
    char s[48];
    int mv = move_build(v, y, x, s);
    if (gap > mv) {
        move_to(v, y, x);       /* each cell costs a byte at least */
        return;
    }
    /* try the rewrite; undo it when the move is shorter */
    size_t mark = v->len;
    uint32_t fg = v->fg, bg = v->bg;
    uint8_t attr = v->attr;
    int ok = v->sgr_ok;
    VtCell saved[GAP_TRY];
    VtCell *sh = &v->shown[(size_t)y * v->cols + v->cx];
    memcpy(saved, sh, (size_t)gap * sizeof *sh);
    int x0 = v->cx;
    for (int k = x0; k < x; k++)
        write_cell(v, y, k);
    if (v->oom || v->len - mark <= (size_t)mv)
        return;
    v->len = mark;
    v->fg = fg;
    v->bg = bg;
    v->attr = attr;
    v->sgr_ok = ok;
    memcpy(sh, saved, (size_t)gap * sizeof *sh);
    v->cy = y;
    v->cx = x0;
    move_to(v, y, x);
}

/* ==== A frame ==== */

/* Erase from the cursor: the terminal fills with the background in
 * force (bce), so that must be the default. */
static void erase(Vt *v, int y, int x, int n, int to_eol)
{
    go_to(v, y, x);
    sgr_to(v, ANY, CK_DEFAULT, 0);
    char s[16];
    put(v, s, (size_t)(to_eol ? csi_n(s, 1, 'K') - 0 : csi_n(s, (unsigned)n, 'X')));
    if (to_eol)
        memcpy(s, "\033[K", 3);
    VtCell *sh = &v->shown[(size_t)y * v->cols];
    for (int k = x; k < x + n; k++)
        sh[k] = blank_cell;
}

static void encode_row(Vt *v, int y)
{
    int W = v->cols;
    VtCell *w = &v->want[(size_t)y * W], *s = &v->shown[(size_t)y * W];
    /* the bottom-right cell scrolls the screen on a terminal that wraps
     * at once: it is left alone there */
    int limit = y == v->rows - 1 && v->caps.am && !v->caps.xenl ? W - 1 : W;
    int *blank = v->blank;
    blank[W] = 0;
    for (int x = W - 1; x >= 0; x--)
        blank[x] = blank_default(&w[x]) ? blank[x + 1] + 1 : 0;
    int x = 0;
    while (!v->oom) {
        while (x < limit && vt_same_look(&w[x], &s[x]))
            x++;
        if (x >= limit)
            break;
        if (blank[x] >= 4) {
            /* a run of blanks: erase it when that is shorter than spaces */
            int n = blank[x], last = x;
            for (int k = x; k < x + n; k++)
                if (!vt_same_look(&w[k], &s[k]))
                    last = k;
            int span = last - x + 1;
            if (x + n == W && v->caps.el && span > 3) {
                erase(v, y, x, W - x, 1);
                break;
            }
            char t[16];
            if (v->caps.ech && v->caps.rel && span > csi_n(t, (unsigned)span, 'X') + csi_n(t, (unsigned)span, 'C')) {
                erase(v, y, x, span, 0);
                x += span;
                continue;
            }
        }
        go_to(v, y, x);
        write_cell(v, y, x);
        x++;
    }
}

int vt_encode(Vt *v)
{
    v->len = 0;
    v->oom = 0;
    if (!v->valid) {
        /* reset the colours first: a clear fills with the background */
        put(v, "\033[m", 3);
        put(v, v->caps.clear, strlen(v->caps.clear));
        v->fg = v->bg = CK_DEFAULT;
        v->attr = 0;
        v->sgr_ok = 1;
        v->cy = v->cx = 0;
        fill_blank(v->shown, (size_t)v->cols * (size_t)v->rows);
        v->valid = 1;
    }
    for (int y = 0; y < v->rows && !v->oom; y++)
        encode_row(v, y);
    if (v->oom) {
        v->valid = 0;           /* shown no longer matches what was sent */
        return -1;
    }
    return 0;
}

/* ==== Pacing ==== */

int vt_may_send(long queued, int writable, double waited_ms)
{
    if (!writable || queued > VT_QUEUE_SLACK)
        return 0;
    return waited_ms < 0 || waited_ms >= VT_ACK_PATIENCE_MS;
}
