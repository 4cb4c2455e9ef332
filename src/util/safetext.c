/* safetext.c: any bytes as text safe to print (safetext.h has the rule). */

#include <stdarg.h>
#include <stdint.h>
#include <string.h>

#include "safetext.h"

/* The well-formed UTF-8 sequence at p: its length (1 .. 4) and code
 * point, or 0 when p begins none (overlong, a surrogate, past U+10FFFF,
 * cut short by its end or another byte, a continuation byte). */
static int decode(const unsigned char *p, uint32_t *cp)
{
    if (p[0] < 0x80) {
        *cp = p[0];
        return 1;
    }
    int n = p[0] >= 0xf0 ? 4 : p[0] >= 0xe0 ? 3 : p[0] >= 0xc2 ? 2 : 0;
    if (!n || p[0] > 0xf4)
        return 0;
    uint32_t c = p[0] & (0x7f >> n);
    for (int i = 1; i < n; i++) {
        if ((p[i] & 0xc0) != 0x80)      /* the NUL that ends s too */
            return 0;
        c = c << 6 | (p[i] & 0x3f);
    }
    static const uint32_t least[5] = { 0, 0, 0x80, 0x800, 0x10000 };
    if (c < least[n] || c > 0x10ffff || (c >= 0xd800 && c <= 0xdfff))
        return 0;
    *cp = c;
    return n;
}

/* Shown as itself? Controls, and the characters that move or reorder
 * the text around them, are not. */
static int printable(uint32_t c)
{
    if (c < 0x20 || c == 0x7f || (c >= 0x80 && c <= 0x9f))
        return 0;
    if (c == 0x200e || c == 0x200f || (c >= 0x2028 && c <= 0x202e) || (c >= 0x2066 && c <= 0x2069))
        return 0;
    return 1;
}

static const char hex[] = "0123456789abcdef";

size_t safetext_next(const char *s, char piece[SAFETEXT_PIECE], SafeTextMode mode)
{
    const unsigned char *p = (const unsigned char *)s;
    uint32_t c = 0;
    int n = decode(p, &c);
    char *o = piece;
    if (n && printable(c)) {
        if (mode == SAFETEXT_JSON && (c == '"' || c == '\\'))
            *o++ = '\\';
        memcpy(o, p, (size_t)n);
        o += n;
    } else if (mode == SAFETEXT_JSON) {
        /* every character printable() refuses is in the BMP */
        if (!n)
            c = 0xfffd;
        memcpy(o, "\\u", 2);
        for (int k = 0; k < 4; k++)
            o[2 + k] = hex[(c >> (12 - 4 * k)) & 15];
        o += 6;
    } else {
        for (int i = 0; i < (n ? n : 1); i++) {
            *o++ = '\\';
            *o++ = 'x';
            *o++ = hex[p[i] >> 4];
            *o++ = hex[p[i] & 15];
        }
    }
    *o = '\0';
    return n ? (size_t)n : 1;
}

int safetext_plain(const char *s, size_t *len)
{
    uint32_t c = 0;
    int n = decode((const unsigned char *)s, &c);
    *len = n ? (size_t)n : 1;
    return n && printable(c);
}

char *safetext(char *dst, size_t cap, const char *src)
{
    size_t o = 0;
    while (*src) {
        char piece[SAFETEXT_PIECE];
        size_t took = safetext_next(src, piece, SAFETEXT_TEXT), k = strlen(piece);
        if (o + k >= cap)
            break;
        memcpy(dst + o, piece, k);
        o += k;
        src += took;
    }
    dst[o] = '\0';
    return dst;
}

void safetext_line(FILE *f, const char *fmt, ...)
{
    char msg[SAFETEXT_LINE], line[4 * SAFETEXT_LINE + 2];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    safetext(line, sizeof line - 1, msg);
    size_t n = strlen(line);
    line[n] = '\n';
    /* one write: standard error is unbuffered, and a line in pieces
     * could interleave with another process's (the loading child's) */
    fwrite(line, 1, n + 1, f);
}
