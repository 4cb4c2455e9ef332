/* summary.c: zview --summary FILE.jsonl...: what many --check --jsonl
 * runs found, summed up (a folder checked on several machines, a run
 * resumed): the files counted by verdict and by kind of problem, and the
 * worst ones named. Each line is read as JSON only as far as it needs
 * (the members path, ok, error and problems; any other value skipped
 * whole), and memory stays a few tables whatever the number of lines:
 * the worst files kept are SUMMARY_WORST. A line that is no such object
 * is counted and named, never trusted. Exit status as --check's: 0 all
 * sound, 3 problems, 1 a file or a line not read. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oneshot.h"
#include "safetext.h"

#define SUMMARY_WORST 10
#define SUMMARY_KINDS 64
#define SUMMARY_TEXT  512

typedef struct {
    char path[SUMMARY_TEXT], what[SUMMARY_TEXT];
    int  ok, has_ok, nproblems, unread;
} Entry;

typedef struct {
    long   files, sound, bad, unread, badlines;
    char   kind[SUMMARY_KINDS][64];
    long   kind_files[SUMMARY_KINDS];
    int    nkinds;
    Entry  worst[SUMMARY_WORST];
    int    nworst;
} Tally;

/* ==== Just enough JSON ==== */

static const char *ws(const char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
        s++;
    return s;
}

/* A string at s (at its quote) into out (cut to cap, escapes decoded;
 * \u escapes past ASCII kept as '?'); the text after it, or NULL. */
static const char *string(const char *s, char *out, size_t cap)
{
    if (*s != '"')
        return NULL;
    size_t k = 0;
    for (s++; *s && *s != '"'; s++) {
        char c = *s;
        if (c == '\\') {
            c = *++s;
            if (!c)
                return NULL;
            if (c == 'u') {
                unsigned v = 0;
                for (int i = 0; i < 4; i++) {
                    char h = *++s;
                    int d = h >= '0' && h <= '9' ? h - '0' : h >= 'a' && h <= 'f' ? h - 'a' + 10
                          : h >= 'A' && h <= 'F' ? h - 'A' + 10 : -1;
                    if (d < 0)
                        return NULL;
                    v = v * 16 + (unsigned)d;
                }
                c = v < 0x80 ? (char)v : '?';
            } else
                c = c == 'n' ? '\n' : c == 't' ? '\t' : c == 'r' ? '\r' : c == 'b' ? '\b' : c == 'f' ? '\f' : c;
        }
        if (out && k + 1 < cap)
            out[k++] = c;
    }
    if (out && cap)
        out[k] = 0;
    return *s == '"' ? s + 1 : NULL;
}

/* Past any value at s; NULL when it is none. */
static const char *skip(const char *s, int depth)
{
    s = ws(s);
    if (*s == '"')
        return string(s, NULL, 0);
    if ((*s == '{' || *s == '[') && depth < 64) {
        char close = *s == '{' ? '}' : ']';
        s = ws(s + 1);
        if (*s == close)
            return s + 1;
        for (;;) {
            if (close == '}') {
                if (!(s = string(ws(s), NULL, 0)) || *(s = ws(s)) != ':')
                    return NULL;
                s++;
            }
            if (!(s = skip(s, depth + 1)))
                return NULL;
            s = ws(s);
            if (*s == close)
                return s + 1;
            if (*s != ',')
                return NULL;
            s++;
        }
    }
    const char *t = s;
    while (*s && strchr(",}] \t\r\n", *s) == NULL)
        s++;
    return s > t ? s : NULL;
}

/* The kind of a problem: "5 holes (39 boundary edges)" is "holes", "1
 * flipped face" "flipped faces", "inside out" itself. */
static void kind_of(const char *problem, char *out, size_t cap)
{
    const char *s = problem;
    int one = s[0] == '1' && s[1] == ' ';
    while (*s >= '0' && *s <= '9')
        s++;
    while (*s == ',' || (*s >= '0' && *s <= '9'))
        s++;
    s = ws(s);
    size_t n = strcspn(s, "(");
    while (n && s[n - 1] == ' ')
        n--;
    snprintf(out, cap, "%.*s", (int)n, s);
    size_t m = strlen(out);
    if (one && m >= 6 && !strcmp(out + m - 6, "vertex"))
        snprintf(out + m - 6, cap - (m - 6), "vertices");
    else if (one && m + 1 < cap)
        strcat(out, "s");
}

static void add_kind(Tally *t, const char *problem)
{
    char k[64];
    kind_of(problem, k, sizeof k);
    for (int i = 0; i < t->nkinds; i++)
        if (!strcmp(t->kind[i], k)) {
            t->kind_files[i]++;
            return;
        }
    if (t->nkinds < SUMMARY_KINDS) {
        snprintf(t->kind[t->nkinds], sizeof t->kind[0], "%s", k);
        t->kind_files[t->nkinds++] = 1;
    }
}

/* Worse first: not read, then more problems, then by path. */
static int worse(const Entry *a, const Entry *b)
{
    if (a->unread != b->unread)
        return a->unread > b->unread;
    if (a->nproblems != b->nproblems)
        return a->nproblems > b->nproblems;
    return strcmp(a->path, b->path) < 0;
}

static void keep_worst(Tally *t, const Entry *e)
{
    int i = t->nworst < SUMMARY_WORST ? t->nworst++ : SUMMARY_WORST;
    if (i == SUMMARY_WORST) {
        if (!worse(e, &t->worst[SUMMARY_WORST - 1]))
            return;
        i = SUMMARY_WORST - 1;
    }
    while (i > 0 && worse(e, &t->worst[i - 1])) {
        t->worst[i] = t->worst[i - 1];
        i--;
    }
    t->worst[i] = *e;
}

/* One line: 0 read and counted, -1 no file's object. */
static int read_line(Tally *t, const char *line)
{
    Entry e;
    memset(&e, 0, sizeof e);
    const char *s = ws(line);
    if (*s != '{')
        return -1;
    s = ws(s + 1);
    char key[32];
    int have_path = 0;
    while (*s != '}') {
        if (!(s = string(s, key, sizeof key)) || *(s = ws(s)) != ':')
            return -1;
        s = ws(s + 1);
        if (!strcmp(key, "path") && *s == '"') {
            s = string(s, e.path, sizeof e.path);
            have_path = 1;
        } else if (!strcmp(key, "ok") && (!strncmp(s, "true", 4) || !strncmp(s, "false", 5))) {
            e.ok = *s == 't';
            e.has_ok = 1;
            s += e.ok ? 4 : 5;
        } else if (!strcmp(key, "error") && *s == '"') {
            s = string(s, e.what, sizeof e.what);
            e.unread = 1;
        } else if (!strcmp(key, "problems") && *s == '[') {
            s = ws(s + 1);
            while (s && *s == '"') {
                char p[SUMMARY_TEXT];
                if (!(s = string(s, p, sizeof p)))
                    break;
                add_kind(t, p);
                if (e.nproblems++ == 0)
                    snprintf(e.what, sizeof e.what, "%s", p);
                else if (strlen(e.what) + strlen(p) + 3 < sizeof e.what)
                    strcat(strcat(e.what, ", "), p);
                s = ws(s);
                if (*s == ',')
                    s = ws(s + 1);
            }
            if (!s || *s != ']')
                return -1;
            s++;
        } else
            s = skip(s, 0);
        if (!s)
            return -1;
        s = ws(s);
        if (*s == ',')
            s = ws(s + 1);
        else if (*s != '}')
            return -1;
    }
    if (!have_path || !e.has_ok)
        return -1;
    /* an error names its file first: once is enough */
    size_t pl = strlen(e.path);
    if (e.unread && !strncmp(e.what, e.path, pl) && !strncmp(e.what + pl, ": ", 2))
        memmove(e.what, e.what + pl + 2, strlen(e.what + pl + 2) + 1);
    t->files++;
    if (e.unread)
        t->unread++;
    else if (e.ok)
        t->sound++;
    else
        t->bad++;
    if (!e.ok)
        keep_worst(t, &e);
    return 0;
}

/* ==== The report ==== */

static void report(Out *out, const Tally *t, int nfiles)
{
    out_printf(out, "files       %ld, from %d JSONL file%s\n", t->files, nfiles, nfiles == 1 ? "" : "s");
    out_printf(out, "sound       %ld\n", t->sound);
    out_printf(out, "problems    %ld\n", t->bad);
    out_printf(out, "not read    %ld\n", t->unread);
    if (t->badlines)
        out_printf(out, "bad lines   %ld (no file's check: see standard error)\n", t->badlines);
    /* the kinds, the most files first */
    int order[SUMMARY_KINDS];
    for (int i = 0; i < t->nkinds; i++) {
        int j = i;
        for (; j > 0 && t->kind_files[order[j - 1]] < t->kind_files[i]; j--)
            order[j] = order[j - 1];
        order[j] = i;
    }
    for (int i = 0; i < t->nkinds; i++)
        out_line(out, "%-11s %ld file%s with %s", i ? "" : "by problem", t->kind_files[order[i]],
                 t->kind_files[order[i]] == 1 ? "" : "s", t->kind[order[i]]);
    for (int i = 0; i < t->nworst; i++)
        out_line(out, "%-11s %s: %s%s", i ? "" : "worst", t->worst[i].path, t->worst[i].unread ? "not read: " : "",
                 t->worst[i].what);
}

int oneshot_summary(const Options *o)
{
    Tally *t = calloc(1, sizeof *t);
    char *line = malloc(1 << 20);
    if (!t || !line) {
        safetext_line(stderr, "zview: out of memory");
        free(t);
        free(line);
        return 1;
    }
    int rc = 0;
    for (int f = 0; f < o->nfiles; f++) {
        FILE *in = strcmp(o->files[f], "-") ? fopen(o->files[f], "r") : stdin;
        if (!in) {
            safetext_line(stderr, "zview: %s: cannot open", o->files[f]);
            rc = 1;
            continue;
        }
        long no = 0;
        while (fgets(line, 1 << 20, in)) {
            no++;
            size_t n = strlen(line);
            if (n == (1u << 20) - 1 && line[n - 1] != '\n') {
                /* a line past 1 MB is no line --jsonl wrote: its rest is skipped */
                int c;
                while ((c = fgetc(in)) != EOF && c != '\n')
                    ;
                line[0] = 0;
            }
            if (!*ws(line))
                continue;
            if (read_line(t, line)) {
                if (t->badlines++ < 5)
                    safetext_line(stderr, "zview: %s:%ld: not a file's check of --check --jsonl", o->files[f], no);
                rc = 1;
            }
        }
        if (ferror(in)) {
            safetext_line(stderr, "zview: %s: read error", o->files[f]);
            rc = 1;
        }
        if (in != stdin)
            fclose(in);
    }
    Out out;
    out_init(&out, stdout, "standard output");
    report(&out, t, o->nfiles);
    if (out_flush(&out)) {
        safetext_line(stderr, "zview: standard output: %s", out_error(&out));
        rc = 1;
    }
    int worst = rc || t->unread ? 1 : t->bad ? 3 : 0;
    free(t);
    free(line);
    return worst;
}
