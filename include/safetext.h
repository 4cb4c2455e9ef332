#ifndef ZV_SAFETEXT_H
#define ZV_SAFETEXT_H
/* safetext: any bytes as text that is safe to print. A file's name, an
 * object's name, a texture's uri echoed in assimp's error: text that
 * came from a file or a name may hold a terminal's escape sequences
 * (OSC 52 writes the clipboard, CSI 2J clears the screen) or reorder
 * what the reader sees (a bidirectional override). Every printer of such
 * text passes it through here: standard error, --info, --check, the
 * viewer's status bar, prompt and boxes as text, --check --json and
 * --bench --json as JSON.
 *
 * The rule, one character at a time: a printable UTF-8 character is
 * itself. Anything else is shown by its bytes, each as \xNN: the C0
 * controls (ESC, BEL, tab and newline too: such text is one line), DEL,
 * the C1 controls (U+0080..U+009F), the bidirectional controls (U+200E,
 * U+200F, U+202A..U+202E, U+2066..U+2069), the line and paragraph
 * separators (U+2028, U+2029), and every byte that begins no well-formed
 * UTF-8 sequence (an overlong form, a surrogate, past U+10FFFF, cut
 * short, a stray continuation byte). A backslash stays itself: the text
 * is for reading; JSON is the exact form. In JSON the same characters
 * are \u escapes (U+001B as \u001b), '"' and '\' are escaped, and a
 * byte that is not UTF-8 is U+FFFD (JSON text is UTF-8), so a parser
 * gives back every name that is valid UTF-8 exactly. */

#include <stddef.h>
#include <stdio.h>

/* One character's text at most: "\xe2\x80\xae" (12) and its NUL. */
#define SAFETEXT_PIECE 16

typedef enum { SAFETEXT_TEXT, SAFETEXT_JSON } SafeTextMode;

/* The character at s (s must not be at its NUL) as safe text in piece,
 * NUL-terminated. Returns the bytes of s it stands for (1 to 4). */
size_t safetext_next(const char *s, char piece[SAFETEXT_PIECE], SafeTextMode mode);

/* Whether the character at s prints as itself (safetext_next's piece
 * is its own bytes); *len gets its length. */
int safetext_plain(const char *s, size_t *len);

/* A buffer for a name made safe: a path of PATH_MAX bytes of plain text
 * fits (one of escapes is cut). */
#define SAFETEXT_NAME 4096

/* All of src as safe text in dst (cap bytes, cap >= 1), cut at a whole
 * character when it does not fit. Returns dst. */
char *safetext(char *dst, size_t cap, const char *src);

/* One line on f: fmt formatted (at most SAFETEXT_LINE bytes), made safe
 * as a whole (a newline inside shows as \x0a), then a newline, in one
 * write. For messages that carry a name or a loader's words. */
#define SAFETEXT_LINE 2048
void safetext_line(FILE *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
