/* test_options.c: the option table (src/app/options.c) against every
 * place an option is written down: --help, the man page, the bash and
 * zsh completions, the docs and the view command; and the key tables
 * (src/viewer/action.c, sketchui.c) against the ? help's labels, the
 * man page and the README. Each test names the option or key and the
 * file that lags, so a new one cannot be half documented, and a removed
 * one cannot linger in the docs. */

#define _POSIX_C_SOURCE 200809L   /* strtok_r */
#include <criterion/criterion.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "tty.h"
#include "../src/viewer/viewer_app.h"

/* ==== Reading the files ==== */

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s (tests run from the top folder)", path);
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len + 4096 + 1 > cap) {
            cap = cap ? 2 * cap : 65536;
            buf = realloc(buf, cap);
            cr_assert_not_null(buf);
        }
        size_t n = fread(buf + len, 1, 4096, f);
        len += n;
        if (n < 4096)
            break;
    }
    fclose(f);
    buf[len] = 0;
    return buf;
}

static char *usage_text(void)
{
    FILE *f = tmpfile();
    cr_assert_not_null(f);
    cli_usage(f);
    long n = ftell(f);
    rewind(f);
    char *buf = malloc((size_t)n + 1);
    cr_assert_eq(fread(buf, 1, (size_t)n, f), (size_t)n);
    buf[n] = 0;
    fclose(f);
    return buf;
}

static int is_opt_char(int c) { return isalnum(c) || c == '-' || c == '_'; }

/* Call fn for each "--name" in text (a word: not inside a longer one). */
static void each_long_option(const char *text, void (*fn)(const char *name, void *ctx), void *ctx)
{
    for (const char *p = strstr(text, "--"); p; p = strstr(p + 2, "--")) {
        if (p > text && is_opt_char((unsigned char)p[-1]))
            continue;
        const char *q = p + 2;
        if (!islower((unsigned char)*q))
            continue;
        char name[64];
        size_t n = 0;
        while (is_opt_char((unsigned char)q[n]) && n + 1 < sizeof name) {
            name[n] = q[n];
            n++;
        }
        while (n > 0 && name[n - 1] == '-')    /* "--foo-" at a line's end is no name */
            n--;
        name[n] = 0;
        fn(name, ctx);
    }
}

typedef struct {
    const char *file;
    const char *const *allowed;    /* words that are not zview options (other tools' flags) */
} UnknownCtx;

static void expect_known(const char *name, void *ctx)
{
    const UnknownCtx *u = ctx;
    for (const char *const *a = u->allowed; a && *a; a++)
        if (!strcmp(*a, name))
            return;
    cr_expect_not_null(cli_option(name), "%s names --%s, which is no option of zview", u->file, name);
}

/* The word list in "word word word" as a sorted, single-spaced string,
 * to compare two lists whatever their order. */
static void canon_words(const char *in, size_t len, char *out, size_t outlen)
{
    char buf[512], *w[64];
    int n = 0;
    snprintf(buf, sizeof buf, "%.*s", (int)len, in);
    for (char *t = strtok(buf, " \t\n"); t && n < 64; t = strtok(NULL, " \t\n"))
        w[n++] = t;
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && strcmp(w[j - 1], w[j]) > 0; j--) {
            char *t = w[j];
            w[j] = w[j - 1];
            w[j - 1] = t;
        }
    out[0] = 0;
    for (int i = 0; i < n; i++)
        snprintf(out + strlen(out), outlen - strlen(out), "%s%s", i ? " " : "", w[i]);
}

/* ==== The table itself ==== */

Test(options, the_table_is_consistent)
{
    for (int i = 0; i < cli_noptions; i++) {
        const OptSpec *s = &cli_options[i];
        cr_expect_eq(cli_option(s->name), s, "--%s is in the table twice", s->name);
        if (s->traits & OPT_ALIAS) {
            int found = 0;
            for (int k = 0; k < i; k++)
                found |= cli_options[k].set == s->set && !(cli_options[k].traits & OPT_ALIAS);
            cr_expect(found, "alias --%s comes after the option it spells differently", s->name);
            continue;
        }
        cr_expect(s->help && *s->help, "--%s has no help line", s->name);
        cr_expect(s->set || !opt_has_value(s), "--%s takes a value but has no setter", s->name);
        cr_expect(s->set || s->flag > 0 || !strcmp(s->name, "help"), "flag --%s sets nothing", s->name);
        for (int k = 0; k < i; k++)
            cr_expect(!s->letter || cli_options[k].letter != s->letter, "-%c twice", s->letter);
    }
}

/* The words the table gives for a value are words the parser takes. */
Test(options, every_value_word_parses)
{
    for (int i = 0; i < cli_noptions; i++) {
        const OptSpec *s = &cli_options[i];
        if (!s->values)
            continue;
        char words[256], opt[64], err[256];
        snprintf(words, sizeof words, "%s", s->values);
        snprintf(opt, sizeof opt, "--%s", s->name);
        /* an option "with --diff" is parsed with it (and its two files) */
        int diff = s->help && !strncmp(s->help, "with --diff", 11);
        for (char *w = strtok(words, " "); w; w = strtok(NULL, " ")) {
            char *argv[] = { "zview", diff ? "--diff" : "--bench", opt, w, "a", "b", NULL };
            Options o;
            cr_expect_eq(cli_parse(diff ? 6 : 4, argv, &o, err, sizeof err), 0, "--%s %s: %s", s->name, w, err);
        }
    }
    /* --algo's words are the registry's names, and all */
    char names[256] = "";
    for (int i = 0; i < hsr_nalgos; i++)
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s ", hsr_algos[i]->name);
    strcat(names, "all");
    char a[256], b[256];
    canon_words(names, strlen(names), a, sizeof a);
    canon_words(cli_option("algo")->values, strlen(cli_option("algo")->values), b, sizeof b);
    cr_expect_str_eq(b, a, "--algo's words against the algorithms there are");
}

/* ==== --help ==== */

Test(options, help_lists_every_option_within_80_columns)
{
    char *u = usage_text();
    for (int i = 0; i < cli_noptions; i++) {
        const OptSpec *s = &cli_options[i];
        if (s->traits & OPT_ALIAS)
            continue;
        char line[80];
        if (s->letter)
            snprintf(line, sizeof line, "\n  -%c, --%s", s->letter, s->name);
        else
            snprintf(line, sizeof line, "\n  --%s", s->name);
        const char *at = strstr(u, line);
        while (at && is_opt_char((unsigned char)at[strlen(line)]))     /* --format in --formats */
            at = strstr(at + 1, line);
        cr_expect_not_null(at, "--help lacks --%s", s->name);
    }
    UnknownCtx ctx = { "--help", NULL };
    each_long_option(u, expect_known, &ctx);
    int row = 1;
    for (const char *p = u; *p; row++) {
        size_t n = strcspn(p, "\n");
        cr_expect_leq(n, 80, "--help line %d is %zu columns: %.*s", row, n, (int)n, p);
        p += n + (p[n] == '\n');
    }
    free(u);
}

/* ==== The man page ==== */

/* A man page line with the escapes that matter here undone: \- is a
 * dash, \fB \fR \fI \fP \& \% and the quotes go. */
static void unroff(const char *in, size_t len, char *out, size_t outlen)
{
    size_t o = 0;
    for (size_t i = 0; i < len && o + 1 < outlen; i++) {
        if (in[i] == '\\' && i + 1 < len) {
            char c = in[i + 1];
            if (c == '-' || c == 'e') {
                out[o++] = c == '-' ? '-' : '\\';
                i++;
            } else if (c == 'f' && i + 2 < len) {
                i += 2;
            } else if (c == '&' || c == '%') {
                i++;
            } else if (c == '(' && i + 3 < len) {
                out[o++] = '?';
                i += 3;
            }
            continue;
        }
        out[o++] = in[i] == '"' ? ' ' : in[i];
    }
    out[o] = 0;
}

typedef struct {
    char section[64];   /* the .SS it sits in */
    char tag[512];      /* the line after .TP, unroffed */
    char body[4096];    /* the lines up to the next .TP, .SS or .SH, unroffed */
} ManEntry;

/* The .TP entries of the man page's section `sh` (e.g. "OPTIONS").
 * Returns how many. */
static int man_entries(const char *man, const char *sh, ManEntry *e, int max)
{
    int n = 0, in = 0, want_tag = 0;
    char ss[64] = "";
    for (const char *p = man; *p;) {
        size_t len = strcspn(p, "\n");
        char line[1024];
        unroff(p, len, line, sizeof line);
        if (!strncmp(line, ".SH ", 4)) {
            in = !strcmp(line + 4, sh);
            ss[0] = 0;
            want_tag = 0;
        } else if (in && !strncmp(line, ".SS ", 4)) {
            snprintf(ss, sizeof ss, "%.63s", line + 4);
            want_tag = 0;
        } else if (in && !strncmp(line, ".TP", 3)) {
            want_tag = n < max;
        } else if (in && want_tag) {
            snprintf(e[n].section, sizeof e[n].section, "%s", ss);
            snprintf(e[n].tag, sizeof e[n].tag, "%.511s", line);
            e[n].body[0] = 0;
            n++;
            want_tag = 0;
        } else if (in && n > 0 && strncmp(line, ".PP", 3)) {
            size_t b = strlen(e[n - 1].body);
            snprintf(e[n - 1].body + b, sizeof e[n - 1].body - b, " %s", line);
        }
        p += len + (p[len] == '\n');
    }
    return n;
}

/* Whether `word` is a whole word of text (split at blanks, commas, |, /). */
static int has_word(const char *text, const char *word)
{
    size_t n = strlen(word);
    for (const char *p = strstr(text, word); p; p = strstr(p + 1, word)) {
        int before = p == text || strchr(" \t\n,|/(", p[-1]);
        int after = !p[n] || strchr(" \t\n,|/).;:", p[n]);
        if (before && after)
            return 1;
    }
    return 0;
}

#define MAN_MAX 160

Test(options, man_page_lists_every_option_in_its_section)
{
    char *man = slurp("doc/zview.1");
    ManEntry *e = calloc(MAN_MAX, sizeof *e);
    int n = man_entries(man, "OPTIONS", e, MAN_MAX);
    cr_assert_gt(n, 40, "the man page's OPTIONS read as %d entries", n);
    for (int i = 0; i < cli_noptions; i++) {
        const OptSpec *s = &cli_options[i];
        if (s->traits & OPT_ALIAS)
            continue;
        char want[64];
        snprintf(want, sizeof want, "--%s", s->name);
        int k = 0;
        while (k < n && !has_word(e[k].tag, want))
            k++;
        if (k == n) {
            cr_expect_fail("doc/zview.1 has no entry for --%s (OPTIONS, %s)", s->name,
                           cli_section_names[s->section]);
            continue;
        }
        cr_expect_str_eq(e[k].section, cli_section_names[s->section], "--%s sits in OPTIONS/%s of the man page",
                         s->name, e[k].section);
        if (s->letter) {
            char shrt[4] = { '-', s->letter, 0, 0 };
            cr_expect(has_word(e[k].tag, shrt), "the man page's --%s entry lacks %s", s->name, shrt);
        }
        if (s->values) {
            char words[256], all[4096 + 512];
            snprintf(words, sizeof words, "%s", s->values);
            snprintf(all, sizeof all, "%s %s", e[k].tag, e[k].body);
            for (char *w = strtok(words, " "); w; w = strtok(NULL, " "))
                cr_expect(has_word(all, w), "the man page's --%s entry does not name '%s'", s->name, w);
        }
    }
    free(e);
    free(man);
}

Test(options, man_page_names_no_option_that_does_not_exist)
{
    char *man = slurp("doc/zview.1");
    char *plain = malloc(strlen(man) + 1);
    unroff(man, strlen(man), plain, strlen(man) + 1);
    UnknownCtx ctx = { "doc/zview.1", NULL };
    each_long_option(plain, expect_known, &ctx);
    free(plain);
    free(man);
}

/* ==== The completions ==== */

/* The bash file's `case $prev in` arm naming --name: its patterns and
 * its body; NULL when no arm names it. */
static const char *bash_arm(const char *bash, const char *name, const char **body_out)
{
    const char *c = strstr(bash, "case $prev in");
    cr_assert_not_null(c, "zview.bash: no 'case $prev in'");
    const char *end = strstr(c, "esac");
    char want[64];
    snprintf(want, sizeof want, "--%s", name);
    for (const char *p = strchr(c, '\n') + 1; p && p < end;) {
        /* an arm: patterns up to ')', its body up to ';;' */
        const char *close = strchr(p, ')');
        const char *stop = strstr(p, ";;");
        if (!close || !stop || stop > end)
            break;
        char pat[512];
        snprintf(pat, sizeof pat, "%.*s", (int)(close - p), p);
        for (char *t = strtok(pat, " \t\n|\\"); t; t = strtok(NULL, " \t\n|\\"))
            if (!strcmp(t, want)) {
                *body_out = close + 1;
                return p;
            }
        p = stop + 2;
    }
    return NULL;
}

Test(options, bash_completion_knows_every_option_and_its_words)
{
    const char *path = "tools/completion/zview.bash";
    char *bash = slurp(path);
    for (int i = 0; i < cli_noptions; i++) {
        const OptSpec *s = &cli_options[i];
        char want[64];
        snprintf(want, sizeof want, "--%s", s->name);
        const char *words = strstr(bash, "compgen -W \"--help");
        cr_assert_not_null(words, "%s: no list of the options", path);
        const char *words_end = strchr(words + 12, '"');
        char list[2048];
        snprintf(list, sizeof list, "%.*s", (int)(words_end - words - 12), words + 12);
        cr_expect(has_word(list, want) || (s->traits & OPT_ALIAS), "%s does not offer %s", path, want);
        const char *body = NULL;
        const char *arm = bash_arm(bash, s->name, &body);
        if (!opt_has_value(s)) {
            cr_expect_null(arm, "%s: flag %s completes a value", path, want);
            continue;
        }
        if (!arm) {
            cr_expect_fail("%s: %s takes a value, but no 'case $prev' arm names it (bash would offer files)",
                           path, want);
            continue;
        }
        if (s->letter) {
            char shrt[4] = { '-', s->letter, 0, 0 };
            char pat[256];
            snprintf(pat, sizeof pat, "%.*s", (int)(body - arm), arm);
            cr_expect(strstr(pat, shrt), "%s: the arm of %s lacks %s", path, want, shrt);
        }
        if (s->values) {
            const char *w = strstr(body, "compgen -W \"");
            const char *stop = strstr(body, ";;");
            cr_assert(w && w < stop, "%s: the arm of %s offers no words", path, want);
            w += 12;
            char got[256], exp[256];
            canon_words(w, strcspn(w, "\""), got, sizeof got);
            canon_words(s->values, strlen(s->values), exp, sizeof exp);
            cr_expect_str_eq(got, exp, "%s: the words of %s", path, want);
        }
    }
    UnknownCtx ctx = { path, NULL };
    each_long_option(bash, expect_known, &ctx);
    free(bash);
}

Test(options, zsh_completion_knows_every_option_and_its_words)
{
    const char *path = "tools/completion/_zview";
    char *zsh = slurp(path);
    for (int i = 0; i < cli_noptions; i++) {
        const OptSpec *s = &cli_options[i];
        char with[64], flag1[64], flag2[64];
        snprintf(with, sizeof with, "--%s=", s->name);
        snprintf(flag1, sizeof flag1, "--%s[", s->name);
        snprintf(flag2, sizeof flag2, "--%s}", s->name);
        const char *at = strstr(zsh, with);
        if (!opt_has_value(s)) {
            cr_expect(strstr(zsh, flag1) || strstr(zsh, flag2), "%s lacks the flag --%s", path, s->name);
            cr_expect_null(at, "%s: flag --%s takes a value there", path, s->name);
            continue;
        }
        if (!at) {
            cr_expect_fail("%s lacks --%s= (an option with a value)", path, s->name);
            continue;
        }
        if (s->letter) {
            char shrt[8];
            snprintf(shrt, sizeof shrt, "-%c+", s->letter);
            cr_expect(strstr(zsh, shrt), "%s lacks %s", path, shrt);
        }
        if (s->values) {
            /* the spec's last ':(words)' on its line */
            const char *eol = strchr(at, '\n');
            const char *open = NULL;
            for (const char *p = at; p < eol; p++)
                if (p[0] == ':' && p[1] == '(')
                    open = p + 2;
            cr_assert_not_null(open, "%s: --%s offers no words", path, s->name);
            char got[256], exp[256];
            canon_words(open, strcspn(open, ")"), got, sizeof got);
            canon_words(s->values, strlen(s->values), exp, sizeof exp);
            cr_expect_str_eq(got, exp, "%s: the words of --%s", path, s->name);
        }
    }
    UnknownCtx ctx = { path, NULL };
    each_long_option(zsh, expect_known, &ctx);
    free(zsh);
}

/* ==== The README and the other docs ==== */

Test(options, the_docs_name_no_option_that_does_not_exist)
{
    /* flags of other tools the docs show (the test runner, libFuzzer, f3d,
     * valgrind and its callgrind) */
    static const char *const others[] = { "filter",    "jobs",      "verbose", "help",
                                          "fail-fast", "no-render", "tool", "separate-threads", NULL };
    static const char *const docs[] = { "README.md", "CONTRIBUTING.md", "doc/design.md", "doc/benchmarks.md" };
    for (int i = 0; i < 4; i++) {
        FILE *f = fopen(docs[i], "rb");
        if (!f && i > 0)
            continue;       /* written by the docs of issue 17 */
        if (f)
            fclose(f);
        char *text = slurp(docs[i]);
        UnknownCtx ctx = { docs[i], others };
        each_long_option(text, expect_known, &ctx);
        free(text);
    }
}

/* ==== The view command ==== */

/* A view with every setting away from its default: the view command
 * writes only options of the table marked OPT_VIEWCMD, and every one of
 * them. */
Test(options, the_view_command_writes_the_options_marked_for_it)
{
    Options o;
    cli_defaults(&o);
    o.files[0] = "assets/scene.obj";
    o.files[1] = "assets/torus.obj";
    o.nfiles = 2;
    char err[256];
    Scene s;
    cr_assert_eq(app_load_scene(&o, &s, err, sizeof err), 0, "%s", err);
    o.points = o.flip = 1;
    o.format = "obj";
    o.layout = LAYOUT_GRID;
    o.grid = 2;
    o.bg = "white";
    o.contrast = 0.3f;
    o.diff = 1;
    o.tolerance = 0.5;
    o.show = 3;
    s.cam.persp = 1;
    s.cam.fov_deg = 40;
    s.cam.yaw = 0.5f;
    s.cam.roll = 0.25f;
    s.cam.zoom = 2;
    s.cam.pan = v3(0.1f, 0.2f, 0);
    s.objs[0].offset = v3_add(s.objs[0].home, v3(1, 0, 0));
    s.objs[0].yaw = 0.5f;
    s.objs[0].scale = s.objs[0].home_scale * 2;
    s.objs[0].up = UP_Z;
    light_set(&s.light, 10, 20, 0.5f);
    MeasureMarks mk = { .n = 2, .mark = { { .a = 4 }, { .obj = 1, .a = 2 } } };
    SectionPlane plane = section_axis_plane(2, 0, 0.5);
    ViewSettings v = { MODE_ASCII, SHADE_SMOOTH, 45, 1, 9, "span", 1, 1, 3, 2, 1, 1, 1, 1, 30, 1, &mk, &plane, 1 };
    char cmd[4096];
    cr_assert_eq(view_command(cmd, sizeof cmd, &o, &s, &v), 0);
    scene_free(&s);

    int seen[CLI_OPTIONS_MAX] = { 0 };
    char *save = NULL;
    for (char *w = strtok_r(cmd, " ", &save); w; w = strtok_r(NULL, " ", &save)) {
        if (!strcmp(w, "--"))
            break;          /* the files */
        if (strncmp(w, "--", 2))
            continue;       /* a value */
        char *eq = strchr(w, '=');
        if (eq)
            *eq = 0;        /* --overhang=30: an optional value */
        const OptSpec *sp = cli_option(w + 2);
        cr_assert_not_null(sp, "the view command writes %s, which is no option", w);
        cr_expect(sp->traits & OPT_VIEWCMD, "the view command writes %s: mark it OPT_VIEWCMD", w);
        seen[sp - cli_options] = 1;
    }
    for (int i = 0; i < cli_noptions; i++)
        cr_expect(!(cli_options[i].traits & OPT_VIEWCMD) || seen[i],
                  "--%s is marked OPT_VIEWCMD but the view command does not write it", cli_options[i].name);
}

/* ==== The key tables ==== */

/* Names of keys in any case ("space", "Space"), but a letter as it is:
 * g and G are two keys. */
static int same_word_nocase(const char *a, const char *b)
{
    if (!a[0] || !a[1] || !b[0] || !b[1])
        return !strcmp(a, b);
    for (; *a && *b; a++, b++)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b))
            return 0;
    return *a == *b;
}

/* Whether the words of text (split at blanks and commas) hold name, in
 * any case; "arrows" stands for the four arrow keys. */
static int names_key(const char *text, int key)
{
    char buf[1024], nb[8];
    const char *name = key_name(key, nb, sizeof nb);
    int arrow = key == TK_LEFT || key == TK_RIGHT || key == TK_UP || key == TK_DOWN;
    int shift_arrow = key == TK_SLEFT || key == TK_SRIGHT || key == TK_SUP || key == TK_SDOWN;
    snprintf(buf, sizeof buf, "%s", text);
    char *save = NULL;
    /* words apart by blanks; a comma after a word parts it from the
     * next ("Tab, n"), a comma alone is the key , */
    for (char *w = strtok_r(buf, " \t", &save); w; w = strtok_r(NULL, " \t", &save)) {
        size_t n = strlen(w);
        if (n > 1 && w[n - 1] == ',')
            w[n - 1] = 0;
        if (same_word_nocase(w, name) || (arrow && same_word_nocase(w, "arrows"))
            || (shift_arrow && same_word_nocase(w, "Shift-arrows")))
            return 1;
    }
    return 0;
}

static void rows_name_their_keys(const KeyRow *rows, int n, const char *table)
{
    for (int r = 0; r < n; r++)
        for (const KeyBind *b = rows[r].bind; b < rows[r].bind + KEY_ROW_BINDS && b->key; b++) {
            char nb[8];
            cr_expect(names_key(rows[r].keys, b->key), "%s: the help row '%s' does not name %s", table,
                      rows[r].keys, key_name(b->key, nb, sizeof nb));
            cr_expect_eq(key_find(rows, n, b->key), b, "%s: %s is bound twice", table,
                         key_name(b->key, nb, sizeof nb));
        }
}

Test(keytable, each_help_row_names_its_keys_once)
{
    rows_name_their_keys(viewer_keys, viewer_keys_n, "action.c");
    rows_name_their_keys(sketch_keys, sketch_keys_n, "sketchui.c");
    /* sketch mode passes a key on only to a key the viewer has */
    for (int r = 0; r < sketch_keys_n; r++)
        for (const KeyBind *b = sketch_keys[r].bind; b < sketch_keys[r].bind + KEY_ROW_BINDS && b->key; b++)
            cr_expect(b->act || key_find(viewer_keys, viewer_keys_n, b->key), "sketch mode passes on a key the viewer lacks");
}

/* Every key of a table has a .TP entry naming it in the man page's
 * section sh. */
static void man_lists_keys(const char *man, const char *sh, const KeyRow *rows, int n)
{
    ManEntry *e = calloc(MAN_MAX, sizeof *e);
    int ne = man_entries(man, sh, e, MAN_MAX);
    cr_assert_gt(ne, 10, "the man page's %s read as %d entries", sh, ne);
    for (int r = 0; r < n; r++)
        for (const KeyBind *b = rows[r].bind; b < rows[r].bind + KEY_ROW_BINDS && b->key; b++) {
            int k = 0;
            while (k < ne && !names_key(e[k].tag + 3, b->key))     /* past the .B / .BR */
                k++;
            char nb[8];
            cr_expect_lt(k, ne, "doc/zview.1 does not list the key %s in %s (%s: %s)", key_name(b->key, nb, sizeof nb),
                         sh, rows[r].keys, rows[r].what);
        }
    free(e);
}

Test(keytable, the_man_page_lists_every_key)
{
    char *man = slurp("doc/zview.1");
    man_lists_keys(man, "KEYS", viewer_keys, viewer_keys_n);
    man_lists_keys(man, "SKETCH", sketch_keys, sketch_keys_n);
    free(man);
}

/* The README's short list of keys names keys the viewer has. */
Test(keytable, the_readme_names_only_keys_that_exist)
{
    char *readme = slurp("README.md");
    const char *sec = strstr(readme, "\n## Keys");
    cr_assert_not_null(sec, "README.md has no Keys section");
    const char *end = strstr(sec + 1, "\n## ");
    int named = 0;
    for (const char *p = sec; p && p < end; p = strchr(p + 1, '\n')) {
        if (strncmp(p, "\n| ", 3) || !strncmp(p, "\n| key", 6) || !strncmp(p, "\n|---", 5))
            continue;
        const char *cell_end = strchr(p + 3, '|');
        for (const char *b = strchr(p + 3, '`'); b && b < cell_end; b = strchr(b + 1, '`')) {
            const char *e = strchr(b + 1, '`');
            char word[16];
            snprintf(word, sizeof word, "%.*s", (int)(e - b - 1), b + 1);
            int found = 0;
            for (int r = 0; r < viewer_keys_n && !found; r++)
                for (const KeyBind *k = viewer_keys[r].bind; k < viewer_keys[r].bind + KEY_ROW_BINDS && k->key; k++) {
                    char nb[8];
                    found |= same_word_nocase(word, key_name(k->key, nb, sizeof nb));
                }
            cr_expect(found, "README.md's Keys name `%s`, which the viewer does not bind", word);
            named++;
            b = e;
        }
    }
    cr_expect_gt(named, 10, "README.md's Keys name %d keys", named);
    free(readme);
}
