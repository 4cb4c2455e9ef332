/* cli.c: argv -> Options, GNU style (getopt_long): --size=80x24 or
 * --size 80x24, -oout.png or -o out.png, clusters of short flags, `--`
 * ends the options. getopt's table and --help both come from the option
 * table (options.c); what is checked here is what no single option can
 * see (the files, options that go together or not). Reports errors,
 * never exits. */

#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "app.h"
#include "save.h"

/* ==== --help, from the option table ==== */

#define USAGE_COL 24        /* where the help text starts; a longer left column gets a line of its own */

/* --help's heading of each section of the table. */
static const char *const usage_headings[OPTSEC_COUNT] = {
    [OPTSEC_GENERAL] = "General:",
    [OPTSEC_INPUT] = "Input:",
    [OPTSEC_OUTPUT] = "Output (default: the interactive viewer; --print when stdout is no terminal):",
    [OPTSEC_VIEW] = "View:",
    [OPTSEC_BENCH] = "Benchmark and performance:",
};

/* The left column: "  -s, --size WxH", or with the value's words
 * "  --mode half|ascii|braille". */
static int usage_left(const OptSpec *s, char *buf, size_t n)
{
    int k = snprintf(buf, n, "  ");
    if (s->letter)
        k += snprintf(buf + k, n - (size_t)k, "-%c, ", s->letter);
    k += snprintf(buf + k, n - (size_t)k, "--%s", s->name);
    if (s->arg && (s->traits & OPT_OPTIONAL))
        k += snprintf(buf + k, n - (size_t)k, "[=%s]", s->arg);
    else if (s->arg)
        k += snprintf(buf + k, n - (size_t)k, " %s", s->arg);
    else if (s->values) {
        k += snprintf(buf + k, n - (size_t)k, " %s", s->values);
        for (char *c = buf + k - strlen(s->values); *c; c++)
            if (*c == ' ')
                *c = '|';
    }
    return k;
}

static void usage_option(FILE *f, const OptSpec *s)
{
    char left[128];
    int k = usage_left(s, left, sizeof left);
    fputs(left, f);
    int col = k;
    if (k >= USAGE_COL - 1) {
        fputc('\n', f);
        col = 0;
    }
    for (const char *h = s->help; *h;) {
        size_t len = strcspn(h, "\n");
        fprintf(f, "%*s%.*s\n", USAGE_COL - col, "", (int)len, h);
        col = 0;
        h += len + (h[len] == '\n');
    }
}

void cli_usage(FILE *f)
{
    fputs("usage: zview [OPTIONS] [FILE ...]\n"
          "A fast, exact 3D model viewer for the terminal. With no file, opens the\n"
          "bundled demo scene. Several files make one scene of several objects.\n"
          "FILE is a model in any format zview reads (--formats), told by its\n"
          "content; - reads one from standard input.\n", f);
    for (int sec = 0; sec < OPTSEC_COUNT; sec++) {
        fprintf(f, "\n%s\n", usage_headings[sec]);
        for (int i = 0; i < cli_noptions; i++)
            if (cli_options[i].section == (OptSection)sec && !(cli_options[i].traits & OPT_ALIAS))
                usage_option(f, &cli_options[i]);
    }
    fputs("\nExit status: 0 ok, 1 runtime error, 2 usage error, 3 --check found problems\n"
          "(--repair: problems remain).\n"
          "Every option and key in full: man zview (doc/zview.1 in the source).\n", f);
}

int frame_pattern_check(const char *pat)
{
    int n = 0;
    for (const char *p = pat; *p; p++) {
        if (*p != '%')
            continue;
        p++;
        if (*p == '%')
            continue;
        /* flags, width, precision: then the conversion, an integer one */
        while (*p && strchr("-+ #0", *p))
            p++;
        while (*p >= '0' && *p <= '9')
            p++;
        if (*p == '.') {
            p++;
            while (*p >= '0' && *p <= '9')
                p++;
        }
        if (!*p || !strchr("diuxXo", *p))
            return -1;
        n++;
    }
    return n;
}

/* ==== Parsing ==== */

void cli_defaults(Options *o)
{
    memset(o, 0, sizeof *o);
    o->mode = -1;
    o->pixels = -1;
    o->colour = -1;
    o->shade = SHADE_LAMBERT;
    o->zoom = 1;
    o->fov = 50;
    o->views = 8;
    o->fps = 30;
    o->grid = 1;
    o->max_polys = 0;               /* none: what memory holds (app_check_size) */
    o->crease = SHADE_CREASE_DEFAULT;
    o->light[0] = LIGHT_YAW;
    o->light[1] = LIGHT_PITCH;
    o->ambient = LIGHT_AMBIENT;
    o->point_size = 1;
    o->line_width = 1;
    o->up = -1;
    o->contrast = CONTRAST_DEFAULT;
    o->max_locations = CHECK_LOCATIONS_JSON;
    o->tolerance = -1;
}

/* getopt's tables from the option table: a long option with a letter
 * returns the letter, as its short form does; the others return
 * OPT_FIRST + their row, an alias its option's row (so that getopt
 * takes an abbreviation such as --col for either spelling). A leading
 * ':' in the short options (and opterr = 0) lets cli_parse word the
 * errors itself. */
#define OPT_FIRST 256

/* The row an alias spells differently: the first with its setter. */
static int row_of(int i)
{
    if (!(cli_options[i].traits & OPT_ALIAS))
        return i;
    for (int k = 0; k < i; k++)
        if (cli_options[k].set == cli_options[i].set)
            return k;
    return i;
}

static void getopt_tables(struct option *lo, char *shorts)
{
    char *sp = shorts;
    *sp++ = ':';
    for (int i = 0; i < cli_noptions; i++) {
        const OptSpec *s = &cli_options[i];
        int val = !opt_has_value(s) ? no_argument : s->traits & OPT_OPTIONAL ? optional_argument : required_argument;
        lo[i] = (struct option){ s->name, val, NULL, s->letter ? s->letter : OPT_FIRST + row_of(i) };
        if (s->letter) {
            *sp++ = s->letter;
            if (val != no_argument)
                *sp++ = ':';
            if (val == optional_argument)
                *sp++ = ':';
        }
    }
    lo[cli_noptions] = (struct option){ NULL, 0, NULL, 0 };
    *sp = 0;
}

/* The row getopt_long's return value c stands for. */
static const OptSpec *spec_of(int c)
{
    if (c >= OPT_FIRST)
        return &cli_options[c - OPT_FIRST];
    for (int i = 0; i < cli_noptions; i++)
        if (cli_options[i].letter == c)
            return &cli_options[i];
    return NULL;
}

/* getopt_long returned '?' (unknown) or ':' (no value): say which word. */
static int getopt_error(int c, int argc, char **argv, char *err, size_t errlen)
{
    /* optind has moved past the faulty word */
    const char *word = optind > 0 && optind <= argc ? argv[optind - 1] : "?";
    if (c == ':')
        snprintf(err, errlen, "option '%s' needs a value", word);
    else if (optopt && word[0] == '-' && word[1] != '-')
        snprintf(err, errlen, "unknown option '-%c' (see --help)", optopt);
    else
        snprintf(err, errlen, "unknown option '%s' (see --help)", word);
    return -1;
}

/* One option, as the user wrote it (long_name NULL: the short form). */
static int apply_option(Options *o, const OptSpec *s, const char *long_name, const char *val, char *err,
                        size_t errlen)
{
    if (!s->set) {
        *(int *)((char *)o + s->flag) = 1;
        return 0;
    }
    char name[64];
    if (long_name)
        snprintf(name, sizeof name, "--%s", long_name);
    else
        snprintf(name, sizeof name, "-%c", s->letter);
    OptCall call = { val, name, err, errlen };
    return s->set(o, &call);
}

/* The words after the options: the files, standard input at most once. */
static int take_files(int argc, char **argv, Options *o, char *err, size_t errlen)
{
    int stdin_files = 0;
    for (int i = optind; i < argc; i++) {
        if (o->nfiles >= MAX_FILES) {
            snprintf(err, errlen, "too many files (at most %d)", MAX_FILES);
            return -1;
        }
        /* --measure A B [C]: the points after its first are words too */
        if (o->nmeasure && o->nmeasure < 3 && printq_point_parse(argv[i], &o->measure[o->nmeasure]) == 0) {
            o->nmeasure++;
            continue;
        }
        if (strcmp(argv[i], "-") == 0 && stdin_files++) {
            snprintf(err, errlen, "- (standard input) given twice");
            return -1;
        }
        o->files[o->nfiles++] = argv[i];
    }
    return 0;
}

/* --check: files, no other mode, and with --json nothing else on
 * standard output. */
static int check_with(const Options *o, char *err, size_t errlen)
{
    const char *other = o->info ? "--info" : o->bench ? "--bench" : o->bench_tty ? "--bench-tty"
                      : o->sketch ? "--sketch" : o->turntable ? "--turntable" : o->points ? "--points"
                      : o->dump_ids ? "--dump-ids" : o->dump_screen ? "--dump-screen" : NULL;
    if (other) {
        snprintf(err, errlen, "--check does not go with %s", other);
        return -1;
    }
    if (o->nfiles == 0) {
        snprintf(err, errlen, "--check needs the files to check");
        return -1;
    }
    if (o->json && (o->print || (o->out && !strcmp(o->out, "-")))) {
        snprintf(err, errlen, "--check --json writes one JSON document to standard output: the picture "
                              "would go into it (use -o FILE)");
        return -1;
    }
    return 0;
}

/* --repair: one file, -o OUT in a format zview writes (by its name, or
 * --format, which here names the format written), no other mode. */
static int repair_with(const Options *o, char *err, size_t errlen)
{
    const char *other = o->check ? "--check" : o->info ? "--info" : o->bench ? "--bench"
                      : o->bench_tty ? "--bench-tty" : o->print ? "--print" : o->sketch ? "--sketch"
                      : o->turntable ? "--turntable" : o->points ? "--points" : o->dump_ids ? "--dump-ids"
                      : o->dump_screen ? "--dump-screen" : o->image_format ? "--image-format"
                      : o->watch ? "--watch" : o->diff ? "--diff" : NULL;
    if (other) {
        snprintf(err, errlen, "--repair does not go with %s", other);
        return -1;
    }
    if (o->nfiles != 1) {
        snprintf(err, errlen, "--repair takes one model (%d given): zview --repair IN -o OUT", o->nfiles);
        return -1;
    }
    if (!o->out) {
        snprintf(err, errlen, "--repair needs -o OUT, the repaired copy (.stl, .obj or .ply; - with --format "
                              "for standard output): the input is never written");
        return -1;
    }
    int named = o->format ? save_format_from_name(o->format) : -1;
    int ext = strcmp(o->out, "-") ? save_format_of_path(o->out) : -1;
    if (o->format && named < 0) {
        snprintf(err, errlen, "--repair writes stl, obj or ply: --format %s is none of them", o->format);
        return -1;
    }
    if (o->format && ext >= 0 && ext != named) {
        snprintf(err, errlen, "-o %s names a .%s file, but --format says %s", o->out, save_format_name(ext),
                 o->format);
        return -1;
    }
    if (!o->format && !strcmp(o->out, "-")) {
        snprintf(err, errlen, "-o - needs --format stl, obj or ply: the format written to standard output");
        return -1;
    }
    if (!o->format && ext < 0) {
        snprintf(err, errlen, "bad value '%s' for -o (the repaired copy's name ends in .stl, .obj or .ply, "
                              "or give --format)", o->out);
        return -1;
    }
    return 0;
}

/* --diff: two files, a picture or a report, none of the other modes. */
static int diff_with(const Options *o, char *err, size_t errlen)
{
    const char *other = o->check ? "--check" : o->info ? "--info" : o->bench ? "--bench" : o->bench_tty ? "--bench-tty"
                      : o->sketch ? "--sketch" : o->watch ? "--watch" : o->points ? "--points"
                      : o->grid > 1 ? "--grid" : o->problems ? "--problems" : o->parts ? "--parts"
                      : o->dump_ids ? "--dump-ids" : o->dump_screen ? "--dump-screen" : NULL;
    if (other) {
        snprintf(err, errlen, "--diff does not go with %s", other);
        return -1;
    }
    if (o->nfiles != 2) {
        snprintf(err, errlen, "--diff compares two files (zview --diff A B), not %d", o->nfiles);
        return -1;
    }
    if (o->json && (o->print || (o->out && !strcmp(o->out, "-")))) {
        snprintf(err, errlen, "--diff --json writes one JSON document to standard output: the picture "
                              "would go into it (use -o FILE)");
        return -1;
    }
    return 0;
}

/* --measure A B [C]: one file, two or three points, nothing else. */
static int measure_with(const Options *o, char *err, size_t errlen)
{
    const char *other = o->check ? "--check" : o->info ? "--info" : o->bench ? "--bench" : o->bench_tty ? "--bench-tty"
                      : o->print ? "--print" : o->out ? "-o" : o->sketch ? "--sketch" : o->diff ? "--diff"
                      : o->turntable ? "--turntable" : o->dump_ids ? "--dump-ids" : o->dump_screen ? "--dump-screen"
                      : o->watch ? "--watch" : NULL;
    if (other) {
        snprintf(err, errlen, "--measure prints its figures alone: it does not go with %s", other);
        return -1;
    }
    if (o->nmeasure < 2) {
        snprintf(err, errlen, "--measure needs two or three points (X,Y,Z or vN): --measure A B [C]");
        return -1;
    }
    if (o->nfiles != 1) {
        snprintf(err, errlen, "--measure measures one model (%d given)", o->nfiles);
        return -1;
    }
    return 0;
}

/* What a single option cannot see: the options that go together or not. */
static int check_combinations(const Options *o, char *err, size_t errlen)
{
    if (!o->repair && (o->weld > 0 || o->max_hole)) {
        snprintf(err, errlen, "%s goes with --repair", o->weld > 0 ? "--weld" : "--max-hole");
        return -1;
    }
    if ((o->bed[0] > 0 || o->min_thickness > 0) && (o->repair || o->diff || o->nmeasure)) {
        snprintf(err, errlen, "%s goes with --check, not %s", o->bed[0] > 0 ? "--bed" : "--min-thickness",
                 o->repair ? "--repair" : o->diff ? "--diff" : "--measure");
        return -1;
    }
    if (o->repair)
        return repair_with(o, err, errlen);
    if (o->nmeasure)
        return measure_with(o, err, errlen);
    if (o->out) {
        size_t len = strlen(o->out);
        int ext = len >= 5 && (!strcmp(o->out + len - 4, ".png") || !strcmp(o->out + len - 4, ".ppm") ||
                               !strcmp(o->out + len - 4, ".txt"));
        if (!ext && !o->image_format && strcmp(o->out, "-")) {
            snprintf(err, errlen, "bad value '%s' for -o (the file must end in .png, .ppm or .txt, "
                                  "or give --image-format)", o->out);
            return -1;
        }
        if (!strcmp(o->out, "-") && o->print) {
            snprintf(err, errlen, "-o - and --print both write to standard output: choose one");
            return -1;
        }
    }
    if (o->turntable && !o->out && !o->print) {
        snprintf(err, errlen, "--turntable needs -o PATTERN (e.g. out-%%03d.png) or --print");
        return -1;
    }
    if (o->turntable && o->out && frame_pattern_check(o->out) != 1) {
        snprintf(err, errlen, "--turntable: the file name '%s' needs exactly one integer conversion "
                 "for the frame number (e.g. out-%%03d.png; %%%% for a %%)", o->out);
        return -1;
    }
    if (o->sketch && (o->print || o->out || o->info || o->bench || o->bench_tty || o->turntable || o->dump_ids ||
                      o->dump_screen)) {
        snprintf(err, errlen, "--sketch draws in the viewer: it does not go with %s",
                 o->print ? "--print" : o->out ? "-o" : o->info ? "--info" : o->bench ? "--bench"
                 : o->bench_tty ? "--bench-tty" : o->turntable ? "--turntable" : o->dump_ids ? "--dump-ids"
                 : "--dump-screen");
        return -1;
    }
    /* --info and --bench write their report only, --turntable frames
     * only: an output asked beside them would be silently left out */
    const char *only = o->info ? "--info" : o->bench ? "--bench" : NULL;
    const char *out = o->out ? "-o" : o->print ? "--print" : o->dump_ids ? "--dump-ids"
                    : o->dump_screen ? "--dump-screen" : o->turntable ? "--turntable" : NULL;
    if (only && out && !o->check) {
        snprintf(err, errlen, "%s writes its report alone: %s goes without it (run them apart)", only, out);
        return -1;
    }
    if (o->info && o->bench) {
        snprintf(err, errlen, "--info and --bench each write a report of their own: choose one");
        return -1;
    }
    if (o->turntable && (o->dump_ids || o->dump_screen)) {
        snprintf(err, errlen, "--turntable writes pictures only: %s goes without it",
                 o->dump_ids ? "--dump-ids" : "--dump-screen");
        return -1;
    }
    if (o->check && check_with(o, err, errlen))
        return -1;
    if (o->problem && (o->turntable || o->info || o->bench || o->bench_tty || o->sketch)) {
        snprintf(err, errlen, "--problem frames one picture (or the viewer): it does not go with %s",
                 o->turntable ? "--turntable" : o->info ? "--info" : o->bench ? "--bench"
                 : o->bench_tty ? "--bench-tty" : "--sketch");
        return -1;
    }
    if (o->diff && diff_with(o, err, errlen))
        return -1;
    const char *diff_only = o->tolerance >= 0 ? "--tolerance" : o->show ? "--show" : o->quiet ? "--quiet" : NULL;
    if (diff_only && !o->diff) {
        snprintf(err, errlen, "%s goes with --diff", diff_only);
        return -1;
    }
    if (o->preview && (o->nfiles != 1 || o->check || o->info || o->bench || o->diff || o->repair || o->out ||
                       o->turntable || o->dump_ids || o->dump_screen || o->nmeasure || o->json)) {
        snprintf(err, errlen, "--preview WxH shows one FILE%s", o->nfiles != 1 ? "" : ", alone (no other output)");
        return -1;
    }
    if (o->textconv && !o->check) {
        snprintf(err, errlen, "--textconv goes with --check");
        return -1;
    }
    if (o->json && !o->check && !o->bench && !o->diff && !o->nmeasure) {
        /* a script that asked for JSON would read a picture instead */
        snprintf(err, errlen, "--json goes with --check, --diff, --bench or --repair");
        return -1;
    }
    if (o->algo && !o->bench && !hsr_find(o->algo)) {
        size_t n = (size_t)snprintf(err, errlen, "unknown algorithm '%s' (", o->algo);
        for (int i = 0; i < hsr_nalgos && n < errlen; i++)
            n += (size_t)snprintf(err + n, errlen - n, "%s%s", hsr_algos[i]->name, i + 1 < hsr_nalgos ? ", " : ")");
        return -1;
    }
    return 0;
}

int cli_parse(int argc, char **argv, Options *o, char *err, size_t errlen)
{
    struct option lo[CLI_OPTIONS_MAX + 1];
    char shorts[2 * CLI_OPTIONS_MAX + 2];
    getopt_tables(lo, shorts);
    cli_defaults(o);
    /* getopt keeps its place in globals: start afresh on every call */
    optind = 0;
    opterr = 0;
    for (;;) {
        int li = -1;
        int c = getopt_long(argc, argv, shorts, lo, &li);
        if (c == -1)
            break;
        if (c == '?' || c == ':')
            return getopt_error(c, argc, argv, err, errlen);
        const OptSpec *s = spec_of(c);
        if (!s) {
            snprintf(err, errlen, "unknown option (see --help)");
            return -1;
        }
        if (apply_option(o, s, li >= 0 ? lo[li].name : NULL, optarg, err, errlen))
            return -1;
    }
    if (take_files(argc, argv, o, err, errlen))
        return -1;
    o->problems |= o->problem > 0;  /* a problem in focus is drawn with the rest */
    /* --bed and --min-thickness are figures of the check's report */
    o->check |= (o->bed[0] > 0 || o->min_thickness > 0) && !o->repair && !o->diff && !o->nmeasure;
    return check_combinations(o, err, errlen);
}
