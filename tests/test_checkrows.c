/* test_checkrows: the check's figures as data (src/check/counts.c).
 * Every row of check_rows is in the JSON and the text report, said
 * where it says it is; every problem row makes a model unsound, alone,
 * and is named once in each verdict; the rows and the measures cover
 * CheckCounts; and a multi-object file's figures are its objects'
 * added up (hand-counted totals, and the rows' sums taken here apart
 * from meshcheck_sum), a scene's its files'. */

#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "meshcheck.h"
#include "oneshot.h"

/* ==== Helpers ==== */

static void set(const CheckRow *r, CheckCounts *c, uint64_t v)
{
    char *p = (char *)c + r->offset;
    if (r->type == CHECK_U32)
        *(uint32_t *)p = (uint32_t)v;
    else if (r->type == CHECK_U64)
        *(uint64_t *)p = v;
    else
        *(int *)p = v != 0;
}

/* What check_text_counts or check_json_counts writes, as a string. */
static char *written(const CheckCounts *c, int json)
{
    FILE *f = tmpfile();
    cr_assert(f);
    Out out;
    out_init(&out, f, "test");
    if (json)
        check_json_counts(&out, c, "  ");
    else
        check_text_counts(&out, c, NULL, "", "  ");
    cr_assert_eq(out_flush(&out), 0);
    long n = ftell(f);
    cr_assert(n > 0);
    char *s = calloc((size_t)n + 1, 1);
    rewind(f);
    cr_assert_eq(fread(s, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    return s;
}

/* The rows' lines alone (no measures, no verdict), joined. */
static void lines(const CheckCounts *c, char *buf, size_t n)
{
    CheckLine l[CHECK_LINES_MAX];
    int k = meshcheck_lines(c, l, CHECK_LINES_MAX);
    buf[0] = 0;
    for (int i = 0; i < k; i++) {
        size_t len = strlen(buf);
        snprintf(buf + len, n - len, "%s|%s\n", l[i].label, l[i].text);
    }
}

/* A sound model's figures: faces, nothing else counted. */
static CheckCounts sound(void)
{
    CheckCounts c = { .faces = 10, .vertices = 8, .components = 1, .closed = 1, .watertight = 1, .has_volume = 1,
                      .intersections_tested = 1, .area = 6, .volume = 1 };
    for (int k = 0; k < 3; k++)
        c.hi[k] = 1;
    return c;
}

/* ==== The table ==== */

Test(checkrows, rows_are_well_formed)
{
    int problems = 0;
    for (int i = 0; i < check_nrows; i++) {
        const CheckRow *r = &check_rows[i];
        size_t want = r->type == CHECK_U32 ? 4 : r->type == CHECK_U64 ? 8 : sizeof(int);
        cr_assert_eq(r->size, want, "%s: its type says %zu bytes, the member has %zu", r->field, want, r->size);
        cr_assert(r->sum == CHECK_SUM_ADD || r->sum == CHECK_SUM_EVERY || r->type == CHECK_FLAG,
                  "%s: only a flag is summed by all or any", r->field);
        cr_assert(!r->json_bool || r->type != CHECK_FLAG, "%s", r->field);
        cr_assert(!r->line || r->label, "%s: on a line without a label", r->field);
        for (int j = 0; j < i; j++) {
            const CheckRow *o = &check_rows[j];
            cr_assert_neq(r->offset, o->offset, "%s and %s: one member", r->field, o->field);
            cr_assert(!r->json || !o->json || strcmp(r->json, o->json), "JSON member %s twice", r->json);
            cr_assert(r->line != o->line || !r->line || !strcmp(r->label, o->label),
                      "%s and %s: line %d with two labels", r->field, o->field, r->line);
            cr_assert(!r->rank || r->rank != o->rank, "%s and %s: rank %d", r->field, o->field, r->rank);
            cr_assert(!r->short_rank || r->short_rank != o->short_rank, "%s and %s: short rank", r->field,
                      o->field);
        }
        if (r->bad != CHECK_FINE) {
            problems++;
            cr_assert(r->rank > 0 && r->short_rank > 0, "%s: a problem with no place in the verdicts", r->field);
            cr_assert(r->one || r->say, "%s: a problem without words", r->field);
            cr_assert(r->short_one || r->say, "%s: a problem without short words", r->field);
        } else {
            cr_assert(!r->rank && !r->short_rank && !r->one && !r->short_one, "%s: words for no problem", r->field);
        }
    }
    cr_assert_leq(problems, CHECK_PROBLEMS_MAX);
}

Test(checkrows, rows_and_measures_cover_the_counts)
{
    /* a member of CheckCounts with no row is summed, written and judged
     * by nothing: every byte is a row's or one of the measures' */
    unsigned char owner[sizeof(CheckCounts)] = { 0 };
    for (int i = 0; i < check_nrows; i++)
        for (size_t b = 0; b < check_rows[i].size; b++) {
            cr_assert_eq(owner[check_rows[i].offset + b], 0, "%s overlaps", check_rows[i].field);
            owner[check_rows[i].offset + b] = 1;
        }
    const struct {
        size_t at, size;
    } measures[] = {
        { offsetof(CheckCounts, area), sizeof(double) },
        { offsetof(CheckCounts, volume), sizeof(double) },
        { offsetof(CheckCounts, centre), 3 * sizeof(double) },
        { offsetof(CheckCounts, lo), 3 * sizeof(float) },
        { offsetof(CheckCounts, hi), 3 * sizeof(float) },
    };
    for (size_t m = 0; m < sizeof measures / sizeof *measures; m++)
        for (size_t b = 0; b < measures[m].size; b++) {
            cr_assert_eq(owner[measures[m].at + b], 0);
            owner[measures[m].at + b] = 1;
        }
    for (size_t b = 0; b < sizeof owner; b++)
        cr_assert_eq(owner[b], 1, "byte %zu of CheckCounts is no row's", b);
}

Test(checkrows, every_row_is_in_the_json_and_the_text_report)
{
    CheckCounts base[2] = { sound(), sound() };
    base[1].intersections_stopped = 1;      /* where the pair tests and the budget are said */
    base[1].pair_budget = 1u << 20;
    int json_rows = 0;
    for (int i = 0; i < check_nrows; i++) {
        const CheckRow *r = &check_rows[i];
        CheckCounts c = sound();
        /* a count to a number of its own, a flag the other way */
        uint64_t v = r->type == CHECK_FLAG ? !meshcheck_value(r, &c) : 7654321;
        set(r, &c, v);
        char *json = written(&c, 1), want[128];
        if (r->json) {
            json_rows++;
            if (r->type == CHECK_FLAG || r->json_bool)
                snprintf(want, sizeof want, "\n  \"%s\": %s", r->json, v ? "true" : "false");
            else
                snprintf(want, sizeof want, "\n  \"%s\": %llu", r->json, (unsigned long long)v);
            cr_assert(strstr(json, want), "%s: no '%s' in\n%s", r->field, want + 1, json);
        }
        free(json);
        /* on its line: setting it changes that line (the other lines
         * stay) over one of the bases; off every line: none changes */
        int changed = 0;
        for (int b = 0; b < 2; b++) {
            char before[2048], after[2048];
            c = base[b];
            lines(&c, before, sizeof before);
            set(r, &c, r->type == CHECK_FLAG ? !meshcheck_value(r, &c) : 7654321);
            lines(&c, after, sizeof after);
            changed |= strcmp(before, after) != 0;
            if (r->line && strcmp(before, after)) {
                char label[64];
                snprintf(label, sizeof label, "%s|", r->label);
                /* the first differing line is the row's own */
                size_t k = 0;
                while (before[k] == after[k])
                    k++;
                while (k > 0 && after[k - 1] != '\n')
                    k--;
                cr_assert_eq(strncmp(after + k, label, strlen(label)), 0, "%s changed another line:\n%s", r->field,
                             after);
            }
        }
        cr_assert_eq(changed, r->line != 0, "%s: on line %d, %s the text report", r->field, r->line,
                     changed ? "changes" : "does not change");
    }
    /* the JSON holds the rows' members and the measures', and no others */
    CheckCounts c = sound();
    char *json = written(&c, 1);
    int members = 0;
    for (const char *p = json; (p = strstr(p, "\": ")); p++)
        members++;
    cr_assert_eq(members, json_rows + 6, "members: %d\n%s", members, json);   /* area volume centre size min problems */
    free(json);
    /* the text report prints each line's label, padded as the measures' */
    char *text = written(&c, 0);
    for (int i = 0; i < check_nrows; i++)
        if (check_rows[i].line) {
            char want[64];
            snprintf(want, sizeof want, "\n  %-14s", check_rows[i].label);
            cr_assert(strstr(text, want), "no '%s' in\n%s", check_rows[i].label, text);
        }
    free(text);
}

Test(checkrows, text_report_of_a_cube_as_known)
{
    /* the README's cube with --flip, its lines as printed before the
     * table (a reference not made from the rows) */
    CheckCounts c = sound();
    c.faces = 6;
    c.inside_out = 1;
    c.pair_budget = 1048588;
    char buf[2048];
    lines(&c, buf, sizeof buf);
    cr_assert_str_eq(buf, "parts|1\n"
                          "faces|6, 0 degenerate, 0 duplicate\n"
                          "vertices|8, 0 non-manifold, 0 unused\n"
                          "edges|0 boundary in 0 holes, 0 non-manifold (watertight)\n"
                          "winding|0 flipped faces, inside out\n"
                          "crossing|0 pairs of faces\n");
    c.nonorientable = 2;
    c.inconsistent_faces = 1;
    c.boundary_edges = 1;
    c.holes = 1;
    c.watertight = 0;
    c.intersections_stopped = 1;
    c.self_intersections = 1;
    c.pair_tests = 1048590;
    lines(&c, buf, sizeof buf);
    cr_assert(strstr(buf, "edges|1 boundary in 1 hole, 0 non-manifold\n"), "%s", buf);
    cr_assert(strstr(buf, "winding|2 non-orientable parts: no flip makes it agree\n"), "%s", buf);
    cr_assert(strstr(buf, "crossing|at least 1 pair of faces (stopped after 1048590 pair tests: the bound is "
                          "1048588)\n"),
              "%s", buf);
}

Test(checkrows, each_problem_row_alone_is_one_problem)
{
    CheckCounts ok = sound();
    cr_assert(meshcheck_sound(&ok));
    for (int i = 0; i < check_nrows; i++) {
        const CheckRow *r = &check_rows[i];
        CheckCounts c = sound();
        set(r, &c, r->bad == CHECK_BAD_ZERO ? 0 : r->type == CHECK_FLAG ? 1 : 3);
        if (r->bad == CHECK_FINE) {
            int bound = 0;      /* a bound is a problem through its count's row */
            for (int j = 0; j < check_nrows; j++)
                bound |= check_rows[j].bound && check_rows[j].bound_at == r->offset;
            cr_assert_eq(meshcheck_sound(&c), !bound, "%s is %sa problem", r->field, bound ? "" : "no ");
            continue;
        }
        char item[CHECK_PROBLEMS_MAX][CHECK_PROBLEM_LEN], bar[256];
        cr_assert(!meshcheck_sound(&c), "%s set: not sound", r->field);
        cr_assert_eq(meshcheck_problems(&c, item, CHECK_PROBLEMS_MAX), 1, "%s", r->field);
        cr_assert(item[0][0], "%s: said in no words", r->field);
        cr_assert_eq(check_verdict_short(&c, ", ", bar, sizeof bar), 1, "%s: %s", r->field, bar);
        cr_assert_str_neq(bar, "watertight");
        /* a count is said with its number (unless its words are its own) */
        if (r->type != CHECK_FLAG && r->bad == CHECK_BAD_SET && !r->say)
            cr_assert(strstr(item[0], "3") && strstr(bar, "3"), "%s: '%s', '%s'", r->field, item[0], bar);
        /* a bound makes it a problem at 0 */
        if (r->bound) {
            c = sound();
            *(int *)((char *)&c + r->bound_at) = 1;
            cr_assert(!meshcheck_sound(&c), "%s: a lower bound of 0 proves nothing", r->field);
            cr_assert_eq(meshcheck_problems(&c, item, CHECK_PROBLEMS_MAX), 1);
        }
    }
}

Test(checkrows, the_verdicts_keep_their_orders)
{
    /* every problem at once: the verdict most serious first, the status
     * bar as it was before the table (crossing before the face counts) */
    CheckCounts c = sound();
    c.boundary_edges = 4;
    c.holes = 1;
    c.nonmanifold_edges = 2;
    c.nonmanifold_vertices = 1;
    c.nonorientable = 1;
    c.inconsistent_faces = 5;
    c.inside_out = 1;
    c.degenerate_faces = 6;
    c.duplicate_faces = 7;
    c.self_intersections = 8;
    char buf[512];
    cr_assert_eq(meshcheck_verdict(&c, buf, sizeof buf), 9);
    cr_assert_str_eq(buf, "1 hole (4 boundary edges), 2 non-manifold edges, 1 non-manifold vertex, "
                          "1 non-orientable part, 5 flipped faces, inside out, 6 degenerate faces, "
                          "7 duplicate faces, 8 intersecting face pairs");
    cr_assert_eq(check_verdict_short(&c, ", ", buf, sizeof buf), 9);
    cr_assert_str_eq(buf, "1 hole, 2 non-manifold, 1 pinched vertex, 1 non-orientable, 5 flipped, inside out, "
                          "8 crossing, 6 degenerate, 7 duplicate");
    c.intersections_stopped = 1;
    c.pair_tests = 99;
    check_verdict_items(&c, " · ", 7, buf, sizeof buf);
    cr_assert(strstr(buf, " · 8+ crossing · +2"), "%s", buf);
    meshcheck_verdict(&c, buf, sizeof buf);
    cr_assert(strstr(buf, ", at least 8 intersecting face pairs (stopped after 99 pair tests)"), "%s", buf);
}

/* ==== Adding up ==== */

/* Five objects, each with its own trouble, a stray vertex and points:
 *   a  a unit cube, sound (8 points, 6 quads)
 *   b  the cube without its top (1 hole of 4 edges)
 *   c  two unit cubes crossing (6 pairs of faces cross), 2 parts
 *   d  a cube inside out (every face reversed)
 *   e  a triangle, a degenerate one and the triangle again (turned):
 *      the two close on each other, one of them flipped
 *   p  points only */
static const char MULTI[] =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "o a\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 1 5 8 4\nf 2 3 7 6\n"
    "o b\nf 1 4 3 2\nf 1 2 6 5\nf 3 4 8 7\nf 1 5 8 4\nf 2 3 7 6\n"
    "v .5 .5 .5\nv 1.5 .5 .5\nv 1.5 1.5 .5\nv .5 1.5 .5\nv .5 .5 1.5\nv 1.5 .5 1.5\nv 1.5 1.5 1.5\nv .5 1.5 1.5\n"
    "o c\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 1 5 8 4\nf 2 3 7 6\n"
    "f 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 11 12 16 15\nf 9 13 16 12\nf 10 11 15 14\n"
    "o d\nf 2 3 4 1\nf 8 7 6 5\nf 5 6 2 1\nf 7 8 4 3\nf 4 8 5 1\nf 6 7 3 2\n"
    "v 5 0 0\nv 6 0 0\nv 5 1 0\nv 7 0 0\nv 9 9 9\n"
    "o e\nf 17 18 19\nf 17 18 20\nf 18 19 17\n"
    "v 3 3 3\nv 4 4 4\no p\np 22 23\n";

static void check_text(const char *text, MeshCheck *mc)
{
    Mesh m;
    char err[256];
    cr_assert_eq(mesh_parse(&m, "multi.obj", text, strlen(text), err, sizeof err), 0, "%s", err);
    CheckOpts o = { .threads = 1, .intersections = 1 };
    cr_assert_eq(meshcheck_run(mc, &m, &o, err, sizeof err), 0, "%s", err);
    mesh_free(&m);
}

Test(checkrows, objects_add_up_to_the_file)
{
    MeshCheck mc;
    check_text(MULTI, &mc);
    cr_assert_eq(mc.nobjs, 6);
    const CheckCounts *f = &mc.file;
    /* counted by hand */
    cr_assert_eq(f->faces, 6 + 5 + 12 + 6 + 3);
    cr_assert_eq(f->components, 1 + 1 + 2 + 1 + 1);
    cr_assert_eq(f->boundary_edges, 4);
    cr_assert_eq(f->holes, 1);
    cr_assert_eq(f->inconsistent_faces, 1);
    cr_assert_eq(f->self_intersections, 6);
    cr_assert_eq(f->degenerate_faces, 1);
    cr_assert_eq(f->duplicate_faces, 1);
    cr_assert_eq(f->nonmanifold_edges, 0);
    cr_assert(f->inside_out, "d is inside out");
    cr_assert(!f->closed && !f->watertight && !f->has_volume && f->volume == 0);
    cr_assert(f->intersections_tested && !f->intersections_stopped);
    /* its own: 16 cube corners and 3 triangle corners; 20 (7 0 0) is
     * only the degenerate face's; 21 (9 9 9) nobody's */
    cr_assert_eq(f->vertices, 16 + 4);
    cr_assert_eq(f->unused_vertices, 1);
    cr_assert_float_eq(f->area, 6 + 5 + 12 + 6 + 0.5 + 0.5, 1e-9);      /* the duplicate's area too */
    cr_assert_eq(f->lo[0], 0);
    cr_assert_eq(f->hi[0], 7);

    /* and row by row, each as its sum says, taken here */
    for (int i = 0; i < check_nrows; i++) {
        const CheckRow *r = &check_rows[i];
        uint64_t add = 0;
        int all = 1, any = 0, some = 0;
        for (uint32_t k = 0; k < mc.nobjs; k++) {
            const CheckCounts *c = &mc.objs[k].c;
            uint64_t v = meshcheck_value(r, c);
            if (!c->faces && r->sum != CHECK_SUM_EVERY)
                continue;
            some = 1;
            add += v;
            all &= v != 0;
            any |= v != 0;
        }
        uint64_t got = meshcheck_value(r, f);
        if (!strcmp(r->field, "vertices") || !strcmp(r->field, "unused_vertices"))
            continue;       /* the file's own, checked above */
        if (r->sum == CHECK_SUM_ALL)
            cr_assert_eq(got, (uint64_t)(all && some), "%s", r->field);
        else if (r->sum == CHECK_SUM_ANY)
            cr_assert_eq(got, (uint64_t)any, "%s", r->field);
        else
            cr_assert_eq(got, add, "%s: file %llu, objects %llu", r->field, (unsigned long long)got,
                         (unsigned long long)add);
    }
    meshcheck_free(&mc);
}

Test(checkrows, files_add_up_to_the_scene)
{
    /* the scene's figures (problems.c) sum the files as a file sums its
     * objects, the files' points and unused vertices too */
    Mesh m[3];
    char err[256];
    cr_assert_eq(mesh_parse(&m[0], "multi.obj", MULTI, strlen(MULTI), err, sizeof err), 0, "%s", err);
    const char *cube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nv 3 3 3\n"
                       "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 1 5 8 4\nf 2 3 7 6\n";
    cr_assert_eq(mesh_parse(&m[1], "cube.obj", cube, strlen(cube), err, sizeof err), 0, "%s", err);
    const char *lines = "v 0 0 0\nv 1 0 0\nv 5 5 5\nl 1 2\n";      /* no faces, one vertex unused */
    cr_assert_eq(mesh_parse(&m[2], "lines.obj", lines, strlen(lines), err, sizeof err), 0, "%s", err);
    SceneCheck sc;
    cr_assert_eq(app_check_meshes(m, 3, 1, NULL, &sc, err, sizeof err), 0, "%s", err);
    const CheckCounts *a = &sc.all, *f0 = &sc.files[0].file, *f1 = &sc.files[1].file;
    cr_assert_eq(a->faces, 32 + 6);
    cr_assert_eq(a->vertices, 20 + 8);
    cr_assert_eq(sc.files[2].file.faces, 0);
    cr_assert_eq(a->unused_vertices, 1 + 1 + 1, "the file of lines' too");
    cr_assert_eq(a->self_intersections, 6);
    cr_assert_eq(a->holes, f0->holes + f1->holes);
    cr_assert_eq(a->pair_budget, f0->pair_budget + f1->pair_budget);
    cr_assert(a->inside_out && !a->watertight);
    cr_assert(f1->watertight && meshcheck_sound(f1));
    cr_assert_float_eq(a->area, f0->area + f1->area, 1e-9);
    scene_check_free(&sc);
    for (int i = 0; i < 3; i++)
        mesh_free(&m[i]);
}
