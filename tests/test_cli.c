/* test_cli.c: the command line, GNU style: both spellings of values,
 * short clusters, `--`, the view-state options and their errors. */

#include <criterion/criterion.h>
#include <string.h>

#include "app.h"
#include "hsr.h"
#include "pixels.h"
#include "repair.h"

static int parse(Options *o, char *err, int n, const char **args)
{
    char *argv[32];
    argv[0] = "zview";
    for (int i = 0; i < n; i++)
        argv[i + 1] = (char *)args[i];
    argv[n + 1] = NULL;
    return cli_parse(n + 1, argv, o, err, 256);
}
#define PARSE(o, err, ...)                                                      \
    parse(o, err, (int)(sizeof((const char *[]){ __VA_ARGS__ }) / sizeof(char *)), \
          (const char *[]){ __VA_ARGS__ })

Test(cli, equals_and_separate_values_agree)
{
    Options a, b;
    char err[256];
    cr_assert_eq(PARSE(&a, err, "--size=80x24", "--yaw=30", "-oout.png", "m.obj"), 0, "%s", err);
    cr_assert_eq(PARSE(&b, err, "--size", "80x24", "--yaw", "30", "-o", "out.png", "m.obj"), 0, "%s", err);
    cr_assert_eq(a.w, 80);
    cr_assert_eq(a.h, 24);
    cr_assert_eq(a.w, b.w);
    cr_assert_eq(a.h, b.h);
    cr_assert_float_eq(a.yaw, 30.0f, 1e-6);
    cr_assert_float_eq(b.yaw, 30.0f, 1e-6);
    cr_assert_str_eq(a.out, "out.png");
    cr_assert_str_eq(b.out, "out.png");
    cr_assert_eq(a.nfiles, 1);
    cr_assert_str_eq(a.files[0], "m.obj");
}

Test(cli, short_clusters_and_files_anywhere)
{
    Options o;
    char err[256];
    cr_assert_eq(PARSE(&o, err, "a.obj", "-pVs10x5", "b.obj"), 0, "%s", err);
    cr_assert(o.print && o.version);
    cr_assert_eq(o.w, 10);
    cr_assert_eq(o.nfiles, 2);
    cr_assert_str_eq(o.files[1], "b.obj");
}

Test(cli, double_dash_ends_options)
{
    Options o;
    char err[256];
    cr_assert_eq(PARSE(&o, err, "--print", "--", "--weird-name.obj", "-"), 0, "%s", err);
    cr_assert(o.print);
    cr_assert_eq(o.nfiles, 2);
    cr_assert_str_eq(o.files[0], "--weird-name.obj");
    cr_assert_str_eq(o.files[1], "-");
}

Test(cli, view_state_options)
{
    Options o;
    char err[256];
    cr_assert_eq(PARSE(&o, err, "--pan", "0.25,-1.5", "--fit-from=10,20,30", "--move", "2:1,2,3",
                       "--turn=1:5,6,7", "--scale", "3:0.5", "--zoom", "2"),
                 0, "%s", err);
    cr_assert_float_eq(o.pan[0], 0.25f, 1e-6);
    cr_assert_float_eq(o.pan[1], -1.5f, 1e-6);
    cr_assert(o.has_fit_from);
    cr_assert_float_eq(o.fit_from[2], 30.0f, 1e-6);
    cr_assert_eq(o.nplace, 3);
    cr_assert_eq(o.place[0].kind, PLACE_MOVE);
    cr_assert_eq(o.place[0].obj, 1);
    cr_assert_float_eq(o.place[0].v[2], 3.0f, 1e-6);
    cr_assert_eq(o.place[1].kind, PLACE_TURN);
    cr_assert_eq(o.place[1].obj, 0);
    cr_assert_eq(o.place[2].kind, PLACE_SCALE);
    cr_assert_float_eq(o.place[2].v[0], 0.5f, 1e-6);
}

Test(cli, errors_name_the_option_and_the_limit)
{
    Options o;
    char err[256];
    cr_assert_neq(PARSE(&o, err, "--pan", "1"), 0);
    cr_assert(strstr(err, "--pan"), "%s", err);
    cr_assert_neq(PARSE(&o, err, "--move", "0:1,2,3"), 0);
    cr_assert(strstr(err, "--move"), "%s", err);
    cr_assert_neq(PARSE(&o, err, "--zoom", "1e38"), 0);
    cr_assert(strstr(err, "1000"), "the real limit is named: %s", err);
    cr_assert_neq(PARSE(&o, err, "--size"), 0);
    cr_assert(strstr(err, "needs a value"), "%s", err);
    cr_assert_neq(PARSE(&o, err, "-q"), 0);
    cr_assert(strstr(err, "-q"), "%s", err);
    cr_assert_neq(PARSE(&o, err, "--frobnicate"), 0);
    cr_assert(strstr(err, "--frobnicate"), "%s", err);
    cr_assert_neq(PARSE(&o, err, "--max-polys", "0"), 0);
    cr_assert_neq(PARSE(&o, err, "--scale", "1:0"), 0);
    /* a number is the whole value: nothing after it, nor nothing at all */
    const char *junk[] = { "--ambient", "0.5x", "--ambient", "", "--weld", "0.1mm", "--tolerance", "", "--zoom", "2 " };
    for (int i = 0; i < 10; i += 2) {
        cr_assert_neq(PARSE(&o, err, junk[i], junk[i + 1]), 0, "%s '%s' taken", junk[i], junk[i + 1]);
        cr_assert(strstr(err, junk[i]), "%s", err);
    }
    /* the parser starts afresh each time */
    cr_assert_eq(PARSE(&o, err, "--print", "x.obj"), 0, "%s", err);
    cr_assert_eq(o.nfiles, 1);
}

Test(cli, sketch_is_for_the_viewer)
{
    Options o;
    char err[256];
    cr_assert_eq(PARSE(&o, err, "--sketch"), 0, "%s", err);
    cr_expect(o.sketch);
    cr_expect_eq(o.nfiles, 0);
    cr_assert_eq(PARSE(&o, err, "--sketch", "--algo", "span", "--print-view", "m.obj"), 0, "%s", err);
    cr_expect(o.sketch && o.print_view && o.nfiles == 1);
    const char *clash[][2] = { { "--print", "--print" }, { "-ox.png", "-o" }, { "--info", "--info" },
                               { "--bench", "--bench" }, { "--dump-ids=x", "--dump-ids" } };
    for (int i = 0; i < 5; i++) {
        cr_expect_eq(PARSE(&o, err, "--sketch", clash[i][0]), -1, "%s", clash[i][0]);
        cr_expect(strstr(err, clash[i][1]) != NULL, "%s: %s", clash[i][0], err);
    }
}

/* An option that takes a word from a table: its refusal lists the words
 * (taken apart here at ", " and " or "), and every word listed is
 * accepted; the list holds every name of the table it comes from. */
static void words_round_trip(const char *opt, const char *const *table, int ntable)
{
    Options o;
    char err[256];
    cr_assert_neq(PARSE(&o, err, opt, "no-such-word", "--print", "m.obj"), 0);
    const char *open = strchr(err, '('), *close = strrchr(err, ')');
    cr_assert(open && close && close > open, "%s: %s", opt, err);
    char list[256];
    snprintf(list, sizeof list, "%.*s", (int)(close - open - 1), open + 1);
    char *or = strstr(list, " or ");
    cr_assert(or, "%s: '%s' ends in 'or'", opt, list);
    memcpy(or, ", ", 2);
    memmove(or + 2, or + 4, strlen(or + 4) + 1);
    char words[16][64];
    int n = 0;
    for (char *w = strtok(list, ","); w && n < 16; w = strtok(NULL, ","), n++) {
        while (*w == ' ')
            w++;
        snprintf(words[n], sizeof words[n], "%s", w);
        cr_assert_eq(PARSE(&o, err, opt, words[n], "--print", "m.obj"), 0, "%s %s: %s", opt, words[n], err);
    }
    for (int i = 0; i < ntable; i++) {
        int found = 0;
        for (int k = 0; k < n; k++)
            found |= strcmp(words[k], table[i]) == 0;
        cr_assert(found, "%s lists %s", opt, table[i]);
    }
}

Test(cli, option_words_come_from_their_tables)
{
    words_round_trip("--mode", mode_names, MODE_COUNT);
    words_round_trip("--mode", pixel_proto_names, PIX_COUNT);
    words_round_trip("--shade", shade_names, SHADE_COUNT);
    words_round_trip("--order", order_names, ORDER_COUNT);
    words_round_trip("--layout", layout_names, LAYOUT_COUNT);
    const char *up[UP_COUNT], *colour[COLOUR_TRUE + 1], *view[16];
    for (int i = 0; i < UP_COUNT; i++)
        up[i] = up_axis_name(i);
    words_round_trip("--up", up, UP_COUNT);
    for (int i = 0; i <= COLOUR_TRUE; i++)
        colour[i] = colour_name((ColourDepth)i);
    words_round_trip("--color", colour, COLOUR_TRUE + 1);
    int nv = 0;
    while (nv < 15 && view_name(nv))
        view[nv] = view_name(nv), nv++;
    view[nv++] = "auto";
    words_round_trip("--view", view, nv);
}

Test(cli, an_unknown_algorithm_lists_every_algorithm)
{
    Options o;
    char err[256];
    cr_assert_neq(PARSE(&o, err, "--algo", "nope", "--print", "m.obj"), 0);
    for (int i = 0; i < hsr_nalgos; i++)
        cr_assert(strstr(err, hsr_algos[i]->name), "%s missing from: %s", hsr_algos[i]->name, err);
}

/* --repair[=STEPS]: the value only after '=' (the word after --repair is
 * the model), the steps as bits, --weld and --max-hole beside it. */
Test(cli, repair_steps_and_its_options)
{
    Options o;
    char err[256];
    cr_assert_eq(PARSE(&o, err, "--repair", "in.stl", "-o", "out.obj"), 0, "%s", err);
    cr_assert_eq(o.repair, REPAIR_DEFAULT);
    cr_assert_eq(o.nfiles, 1);
    cr_assert_str_eq(o.files[0], "in.stl");
    cr_assert_eq(PARSE(&o, err, "--repair=holes,weld", "in.stl", "-o", "out.ply", "--weld", "0.5", "--max-hole", "40"),
                 0, "%s", err);
    cr_assert_eq(o.repair, REPAIR_HOLES | REPAIR_WELD);
    cr_assert_eq(o.weld, 0.5);
    cr_assert_eq(o.max_hole, 40);
    cr_assert_eq(PARSE(&o, err, "--repair=all", "in.stl", "-o", "-", "--format", "stl"), 0, "%s", err);
    cr_assert_eq(o.repair, REPAIR_DEFAULT);
    cr_assert_eq(PARSE(&o, err, "--repair=manifold,clean,winding", "in.stl", "-o", "x.STL"), 0, "%s", err);
    cr_assert_eq(o.repair, REPAIR_MANIFOLD | REPAIR_CLEAN | REPAIR_WINDING);
    cr_assert_eq(PARSE(&o, err, "--repair=", "in.stl", "-o", "x.stl"), -1);
    cr_assert_eq(PARSE(&o, err, "--repair=weld,", "in.stl", "-o", "x.stl"), -1);
    cr_assert_not_null(strstr(err, "bad value 'weld,' for --repair"), "%s", err);
    cr_assert_eq(PARSE(&o, err, "--repair", "in.stl", "-o", "x.off"), -1);
    cr_assert_eq(PARSE(&o, err, "--repair", "in.stl", "-o", "x.obj", "--format", "stl"), -1);
    cr_assert_not_null(strstr(err, "-o x.obj names a .obj file, but --format says stl"), "%s", err);
    cr_assert_eq(PARSE(&o, err, "--max-hole", "0", "--repair", "in.stl", "-o", "x.stl"), -1);
    cr_assert_eq(PARSE(&o, err, "--weld", "nan", "--repair", "in.stl", "-o", "x.stl"), -1);
}
