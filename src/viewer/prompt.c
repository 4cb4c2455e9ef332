/* prompt.c: the one-line prompt's editing (prompt.h). The line is UTF-8;
 * the cursor moves and deletes by whole characters. */

#include <stdio.h>
#include <string.h>

#include "prompt.h"
#include "tty.h"

#define CTRL(c) ((c) & 0x1f)

void prompt_start(Prompt *p, const char *label)
{
    memset(p, 0, sizeof *p);
    snprintf(p->label, sizeof p->label, "%s", label);
}

/* The start of the character before byte i, and the end of the one at i. */
static int char_before(const Prompt *p, int i)
{
    if (i <= 0)
        return 0;
    i--;
    while (i > 0 && (p->buf[i] & 0xc0) == 0x80)
        i--;
    return i;
}

static int char_after(const Prompt *p, int i)
{
    if (i >= p->len)
        return p->len;
    i++;
    while (i < p->len && (p->buf[i] & 0xc0) == 0x80)
        i++;
    return i;
}

static void cut(Prompt *p, int a, int b)
{
    memmove(p->buf + a, p->buf + b, (size_t)(p->len - b) + 1);
    p->len -= b - a;
    if (p->cur > b)
        p->cur -= b - a;
    else if (p->cur > a)
        p->cur = a;
}

static void insert(Prompt *p, const char *s, int n)
{
    if (p->len + n >= PROMPT_MAX)
        return;
    memmove(p->buf + p->cur + n, p->buf + p->cur, (size_t)(p->len - p->cur) + 1);
    memcpy(p->buf + p->cur, s, (size_t)n);
    p->len += n;
    p->cur += n;
}

/* A code point as UTF-8; 0 bytes for what is not one. */
static int utf8(int c, char *o)
{
    if (c < 0x80) {
        o[0] = (char)c;
        return 1;
    }
    if (c < 0x800) {
        o[0] = (char)(0xc0 | c >> 6);
        o[1] = (char)(0x80 | (c & 0x3f));
        return 2;
    }
    if (c >= 0xd800 && c < 0xe000)
        return 0;
    if (c < 0x10000) {
        o[0] = (char)(0xe0 | c >> 12);
        o[1] = (char)(0x80 | (c >> 6 & 0x3f));
        o[2] = (char)(0x80 | (c & 0x3f));
        return 3;
    }
    if (c < 0x110000) {
        o[0] = (char)(0xf0 | c >> 18);
        o[1] = (char)(0x80 | (c >> 12 & 0x3f));
        o[2] = (char)(0x80 | (c >> 6 & 0x3f));
        o[3] = (char)(0x80 | (c & 0x3f));
        return 4;
    }
    return 0;
}

/* Tab: complete the text before the cursor; in a row, list. */
static void complete(Prompt *p)
{
    char head[PROMPT_MAX], done[PROMPT_MAX];
    memcpy(head, p->buf, (size_t)p->cur);
    head[p->cur] = 0;
    int n = path_complete(head, done, sizeof done, p->list, sizeof p->list);
    int grew = n >= 0 && strcmp(done, head) != 0;
    if (n >= 0 && (size_t)p->len - (size_t)p->cur + strlen(done) < PROMPT_MAX) {
        /* the completed text replaces what was before the cursor */
        char tail[PROMPT_MAX];
        memcpy(tail, p->buf + p->cur, (size_t)(p->len - p->cur) + 1);
        p->len = snprintf(p->buf, sizeof p->buf, "%s%s", done, tail);
        p->cur = (int)strlen(done);
    }
    p->nlist = n > 0 ? n : 0;
    /* the list shows on a Tab right after a Tab that could not add
     * anything more (as a shell's second Tab) */
    if (grew || n < 2 || !p->last_tab)
        p->list[0] = 0;
    p->last_tab = 1;
}

PromptResult prompt_key(Prompt *p, int key)
{
    int was_tab = key == TK_TAB;
    if (!was_tab) {
        p->last_tab = 0;
        p->list[0] = 0;
        p->nlist = 0;
    }
    switch (key) {
    case TK_ESC:
        return PR_CANCEL;
    case '\r':
    case '\n':
        return PR_DONE;
    case TK_TAB:
        complete(p);
        return PR_EDIT;
    case CTRL('H'):
    case TK_BACKSPACE:
        cut(p, char_before(p, p->cur), p->cur);
        return PR_EDIT;
    case TK_DEL:
    case CTRL('D'):
        cut(p, p->cur, char_after(p, p->cur));
        return PR_EDIT;
    case CTRL('U'):
        cut(p, 0, p->len);
        return PR_EDIT;
    case TK_LEFT:
    case CTRL('B'):
        p->cur = char_before(p, p->cur);
        return PR_EDIT;
    case TK_RIGHT:
    case CTRL('F'):
        p->cur = char_after(p, p->cur);
        return PR_EDIT;
    case TK_HOME:
    case CTRL('A'):
        p->cur = 0;
        return PR_EDIT;
    case TK_END:
    case CTRL('E'):
        p->cur = p->len;
        return PR_EDIT;
    default:
        break;
    }
    if (key >= 0x20 && key != 127 && key < 0x110000) {
        char u[4];
        int n = utf8(key, u);
        if (n)
            insert(p, u, n);
    }
    return PR_EDIT;
}
