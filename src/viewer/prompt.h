#ifndef ZV_PROMPT_H
#define ZV_PROMPT_H
/* prompt (private to src/viewer): the viewer's one-line prompt in the
 * status line (O asks for a file), and the path completion its Tab
 * does. Pure logic on plain structs: keys in, the line and what to show
 * out; nothing here draws. */

#include <stddef.h>

#define PROMPT_MAX   1024       /* bytes of the line */
#define PROMPT_LIST  2048       /* bytes of the candidates a second Tab lists */

typedef enum { PR_EDIT, PR_DONE, PR_CANCEL } PromptResult;

typedef struct {
    char label[32];             /* "open: " */
    char buf[PROMPT_MAX];       /* the line, UTF-8, NUL-terminated */
    int  len, cur;              /* bytes; the cursor's byte offset */
    int  last_tab;              /* the key before was a Tab */
    char list[PROMPT_LIST];     /* candidates to show ("" = none): names, '\n' between */
    int  nlist;                 /* how many matched (the list may hold fewer) */
} Prompt;

void prompt_start(Prompt *p, const char *label);
/* One key (tty.h codes): printable characters insert at the cursor;
 * Backspace (127, 8) deletes before it, Delete at it, Ctrl-U the whole
 * line; Left/Right, Ctrl-A/Home and Ctrl-E/End move; Tab completes the
 * path (see path_complete), a second Tab in a row lists the candidates;
 * Enter ends (PR_DONE), Esc cancels (PR_CANCEL). */
PromptResult prompt_key(Prompt *p, int key);

/* Complete the path `in` (a leading ~/ or a lone ~ is the home directory,
 * and is expanded in out): the longest common prefix of the names in its
 * directory that start with its last component (hidden names only when
 * that starts with a dot), a directory's with a trailing '/' when it is
 * the only match. The names matched go into list ('\n' between,
 * directories with a trailing '/', sorted; cut when it is full) when
 * list is not NULL. Returns the number of matches (0: out is in, ~
 * expanded), or -1 when out is too small. */
int  path_complete(const char *in, char *out, size_t outlen, char *list, size_t listlen);

/* in with a leading ~ expanded to $HOME into out. Returns 0, or -1 when
 * out is too small. */
int  path_expand_home(const char *in, char *out, size_t outlen);

#endif
