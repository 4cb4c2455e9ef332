/* counts.c: the check's figures as data. check_rows lists each figure
 * of CheckCounts once (the measures aside): how it adds up, its --json
 * member, its place and words in the text report, whether it is a
 * problem and the words of the verdicts. Everything that sums, writes
 * or judges the figures reads these rows: meshcheck_sum (a file's
 * objects, a scene's files), oneshot/checkreport.c (the text report and the
 * JSON), the verdicts here and app/problems.c's status bar. A new check
 * is its pass and a row. */

#include <stdio.h>
#include <string.h>

#include "check_internal.h"

/* ==== Words that do not fit the plain forms ==== */

/* Boundary edges are a problem said as the holes they make. */
static int say_holes(const CheckCounts *c, CheckSay form, char *buf, size_t n)
{
    if (form == CHECK_SAY_PROBLEM)
        snprintf(buf, n, "%u hole%s (%u boundary edge%s)", c->holes, c->holes == 1 ? "" : "s", c->boundary_edges,
                 c->boundary_edges == 1 ? "" : "s");
    else if (form == CHECK_SAY_SHORT)
        snprintf(buf, n, "%u hole%s", c->holes, c->holes == 1 ? "" : "s");
    else
        return 0;
    return 1;
}

/* A crossing test that stopped on its budget found at least so many,
 * and says where it stopped. */
static int say_crossing(const CheckCounts *c, CheckSay form, char *buf, size_t n)
{
    unsigned long long x = c->self_intersections;
    const char *s = x == 1 ? "" : "s";
    if (!c->intersections_stopped)
        return 0;
    if (form == CHECK_SAY_TEXT)
        snprintf(buf, n, "at least %llu pair%s of faces (stopped after %llu pair tests: the bound is %llu)", x, s,
                 (unsigned long long)c->pair_tests, (unsigned long long)c->pair_budget);
    else if (form == CHECK_SAY_PROBLEM)
        snprintf(buf, n, "at least %llu intersecting face pair%s (stopped after %llu pair tests)", x, s,
                 (unsigned long long)c->pair_tests);
    else
        snprintf(buf, n, "%llu+ crossing", x);
    return 1;
}

/* ==== The rows ==== */

#define FIELD(f, t) .field = #f, .offset = offsetof(CheckCounts, f), .size = sizeof(((CheckCounts *)0)->f), .type = (t)
#define BOUND(f)    .bound = 1, .bound_at = offsetof(CheckCounts, f)

/* In the order of the JSON members. The text report's lines: 1 parts,
 * 2 faces, 3 vertices, 4 edges, 5 winding, 6 crossing. */
const CheckRow check_rows[] = {
    { FIELD(faces, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "faces",
      .line = 2, .label = "faces", .text_one = "",
      .bad = CHECK_BAD_ZERO, .rank = 1, .short_rank = 1, .one = "no faces", .short_one = "no faces" },
    { FIELD(vertices, CHECK_U32), .sum = CHECK_SUM_EVERY, .json = "vertices",
      .line = 3, .label = "vertices", .text_one = "" },
    { FIELD(components, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "components",
      .line = 1, .label = "parts", .text_one = "" },
    { FIELD(boundary_edges, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "boundary_edges",
      .line = 4, .label = "edges", .text_one = "boundary",
      .bad = CHECK_BAD_SET, .rank = 2, .short_rank = 2, .say = say_holes },
    { FIELD(holes, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "holes",
      .line = 4, .label = "edges", .sep = " in ", .text_one = "hole", .text_many = "holes" },
    { FIELD(nonmanifold_edges, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "nonmanifold_edges",
      .line = 4, .label = "edges", .text_one = "non-manifold",
      .bad = CHECK_BAD_SET, .rank = 3, .short_rank = 3, .one = "non-manifold edge", .many = "non-manifold edges",
      .short_one = "non-manifold" },
    { FIELD(nonmanifold_vertices, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "nonmanifold_vertices",
      .line = 3, .label = "vertices", .text_one = "non-manifold",
      .bad = CHECK_BAD_SET, .rank = 4, .short_rank = 4, .one = "non-manifold vertex", .many = "non-manifold vertices",
      .short_one = "pinched vertex", .short_many = "pinched vertices" },
    { FIELD(inconsistent_faces, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "inconsistent_faces",
      .line = 5, .label = "winding", .text_one = "flipped face", .text_many = "flipped faces",
      .bad = CHECK_BAD_SET, .rank = 6, .short_rank = 6, .one = "flipped face", .many = "flipped faces",
      .short_one = "flipped" },
    { FIELD(nonorientable, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "non_orientable", .json_bool = 1,
      .line = 5, .label = "winding", .text_alone = 1,
      .text_one = "non-orientable part: no flip makes it agree",
      .text_many = "non-orientable parts: no flip makes it agree",
      .bad = CHECK_BAD_SET, .rank = 5, .short_rank = 5, .one = "non-orientable part", .many = "non-orientable parts",
      .short_one = "non-orientable" },
    { FIELD(inside_out, CHECK_FLAG), .sum = CHECK_SUM_ANY, .json = "inside_out",
      .line = 5, .label = "winding", .text_one = "inside out",
      .bad = CHECK_BAD_SET, .rank = 7, .short_rank = 7, .one = "inside out", .short_one = "inside out" },
    { FIELD(degenerate_faces, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "degenerate_faces",
      .line = 2, .label = "faces", .text_one = "degenerate",
      .bad = CHECK_BAD_SET, .rank = 8, .short_rank = 9, .one = "degenerate face", .many = "degenerate faces",
      .short_one = "degenerate" },
    { FIELD(duplicate_faces, CHECK_U32), .sum = CHECK_SUM_ADD, .json = "duplicate_faces",
      .line = 2, .label = "faces", .text_one = "duplicate",
      .bad = CHECK_BAD_SET, .rank = 9, .short_rank = 10, .one = "duplicate face", .many = "duplicate faces",
      .short_one = "duplicate" },
    { FIELD(unused_vertices, CHECK_U32), .sum = CHECK_SUM_EVERY, .json = "unused_vertices",
      .line = 3, .label = "vertices", .text_one = "unused" },
    { FIELD(self_intersections, CHECK_U64), .sum = CHECK_SUM_ADD, .json = "self_intersections",
      .line = 6, .label = "crossing", .text_one = "pair of faces", .text_many = "pairs of faces",
      .bad = CHECK_BAD_SET, BOUND(intersections_stopped), .rank = 10, .short_rank = 8,
      .one = "intersecting face pair", .many = "intersecting face pairs", .short_one = "crossing",
      .say = say_crossing },
    /* said in the crossing's words */
    { FIELD(intersections_stopped, CHECK_FLAG), .sum = CHECK_SUM_ANY, .json = "intersections_stopped",
      .line = 6, .label = "crossing" },
    { FIELD(pair_tests, CHECK_U64), .sum = CHECK_SUM_ADD, .json = "pair_tests", .line = 6, .label = "crossing" },
    { FIELD(pair_budget, CHECK_U64), .sum = CHECK_SUM_ADD, .json = "pair_budget", .line = 6, .label = "crossing" },
    { FIELD(watertight, CHECK_FLAG), .sum = CHECK_SUM_ALL, .json = "watertight",
      .line = 4, .label = "edges", .sep = " ", .text_one = "(watertight)" },
    /* not written: what the measures and the reports read */
    { FIELD(intersections_tested, CHECK_FLAG), .sum = CHECK_SUM_ALL },
    { FIELD(closed, CHECK_FLAG), .sum = CHECK_SUM_ALL },
    { FIELD(has_volume, CHECK_FLAG), .sum = CHECK_SUM_ALL },
};
const int check_nrows = (int)(sizeof check_rows / sizeof *check_rows);

/* ==== One row ==== */

uint64_t meshcheck_value(const CheckRow *r, const CheckCounts *c)
{
    const char *p = (const char *)c + r->offset;
    switch (r->type) {
    case CHECK_U32:
        return *(const uint32_t *)p;
    case CHECK_U64:
        return *(const uint64_t *)p;
    case CHECK_FLAG:
        break;
    }
    return *(const int *)p != 0;
}

int meshcheck_bad(const CheckRow *r, const CheckCounts *c)
{
    uint64_t v = meshcheck_value(r, c);
    switch (r->bad) {
    case CHECK_FINE:
        return 0;
    case CHECK_BAD_ZERO:
        return v == 0;
    case CHECK_BAD_SET:
        break;
    }
    /* a lower bound proves nothing: a problem even at 0 */
    return v != 0 || (r->bound && *(const int *)((const char *)c + r->bound_at));
}

/* "12 flipped faces"; a flag, or a count without words after it, as the
 * word alone or the number alone. */
static void plain(uint64_t v, int count, const char *one, const char *many, char *buf, size_t n)
{
    const char *w = v == 1 || !many ? one : many;
    if (!count)
        snprintf(buf, n, "%s", w);
    else if (!w[0])
        snprintf(buf, n, "%llu", (unsigned long long)v);
    else
        snprintf(buf, n, "%llu %s", (unsigned long long)v, w);
}

void meshcheck_say(const CheckRow *r, const CheckCounts *c, CheckSay form, char *buf, size_t n)
{
    uint64_t v = meshcheck_value(r, c);
    int count = r->type != CHECK_FLAG;
    buf[0] = 0;
    if (r->say && r->say(c, form, buf, n))
        return;
    switch (form) {
    case CHECK_SAY_TEXT:
        if (r->line && r->text_one && (count && !r->text_alone ? 1 : v != 0))
            plain(v, count, r->text_one, r->text_many, buf, n);
        break;
    case CHECK_SAY_PROBLEM:
        if (r->one)
            plain(v, count && r->bad != CHECK_BAD_ZERO, r->one, r->many, buf, n);
        break;
    case CHECK_SAY_SHORT:
        if (r->short_one)
            plain(v, count && r->bad != CHECK_BAD_ZERO, r->short_one, r->short_many, buf, n);
        break;
    }
}

/* ==== Adding up ==== */

void check_counts_empty(CheckCounts *c)
{
    memset(c, 0, sizeof *c);
    for (int k = 0; k < 3; k++) {
        c->lo[k] = 1;
        c->hi[k] = -1;
    }
}

static void row_add(const CheckRow *r, CheckCounts *t, const CheckCounts *c)
{
    char *p = (char *)t + r->offset;
    uint64_t v = meshcheck_value(r, c);
    if (r->type == CHECK_FLAG) {
        int *f = (int *)p;
        *f = r->sum == CHECK_SUM_ALL ? *f && v : *f || v;
    } else if (r->type == CHECK_U64) {
        *(uint64_t *)p += v;
    } else {
        *(uint32_t *)p += (uint32_t)v;
    }
}

static void rows_set(CheckCounts *t, CheckSum sum, int v)
{
    for (int i = 0; i < check_nrows; i++)
        if (check_rows[i].sum == sum)
            *(int *)((char *)t + check_rows[i].offset) = v;
}

void meshcheck_sum(CheckCounts *t, const CheckCounts *first, size_t n, size_t stride)
{
    check_counts_empty(t);
    rows_set(t, CHECK_SUM_ALL, 1);
    int any = 0;
    double mom[3] = { 0, 0, 0 };
    for (size_t i = 0; i < n; i++) {
        const CheckCounts *c = (const CheckCounts *)((const char *)first + i * stride);
        for (int k = 0; k < check_nrows; k++)
            if (c->faces || check_rows[k].sum == CHECK_SUM_EVERY)
                row_add(&check_rows[k], t, c);
        if (!c->faces)
            continue;
        t->area += c->area;
        t->volume += c->volume;
        for (int k = 0; k < 3; k++) {
            mom[k] += c->volume * c->centre[k];
            t->lo[k] = !any || c->lo[k] < t->lo[k] ? c->lo[k] : t->lo[k];
            t->hi[k] = !any || c->hi[k] > t->hi[k] ? c->hi[k] : t->hi[k];
        }
        any = 1;
    }
    if (!any)
        rows_set(t, CHECK_SUM_ALL, 0);
    if (!t->has_volume)
        t->volume = 0;
    for (int k = 0; k < 3; k++)
        t->centre[k] = t->has_volume && t->volume > 0 ? mom[k] / t->volume : 0;
}

/* ==== In words ==== */

int meshcheck_lines(const CheckCounts *c, CheckLine *line, int max)
{
    int last = 0, n = 0;
    for (int i = 0; i < check_nrows; i++)
        last = check_rows[i].line > last ? check_rows[i].line : last;
    for (int l = 1; l <= last && n < max; l++) {
        CheckLine *out = &line[n];
        out->label = NULL;
        out->line = l;
        out->text[0] = 0;
        const CheckRow *alone = NULL;
        for (int i = 0; i < check_nrows; i++) {
            const CheckRow *r = &check_rows[i];
            if (r->line != l)
                continue;
            out->label = out->label ? out->label : r->label;
            if (r->text_alone && meshcheck_value(r, c))
                alone = alone ? alone : r;
        }
        if (!out->label)
            continue;
        size_t len = 0;
        for (int i = 0; i < check_nrows; i++) {
            const CheckRow *r = &check_rows[i];
            char phrase[CHECK_LINE_LEN];
            if (r->line != l || (alone && r != alone))
                continue;
            meshcheck_say(r, c, CHECK_SAY_TEXT, phrase, sizeof phrase);
            if (!phrase[0])
                continue;
            int w = snprintf(out->text + len, sizeof out->text - len, "%s%s", len ? r->sep ? r->sep : ", " : "",
                             phrase);
            len = w > 0 && len + (size_t)w < sizeof out->text ? len + (size_t)w : sizeof out->text - 1;
        }
        n++;
    }
    return n;
}

int meshcheck_sound(const CheckCounts *c)
{
    for (int i = 0; i < check_nrows; i++)
        if (meshcheck_bad(&check_rows[i], c))
            return 0;
    return 1;
}

int meshcheck_problems_as(const CheckCounts *c, CheckSay form, char (*item)[CHECK_PROBLEM_LEN], int max)
{
    int k = 0;
    for (int rank = 1; rank <= check_nrows; rank++)
        for (int i = 0; i < check_nrows; i++) {
            const CheckRow *r = &check_rows[i];
            if ((form == CHECK_SAY_SHORT ? r->short_rank : r->rank) != rank || !meshcheck_bad(r, c))
                continue;
            if (k < max)
                meshcheck_say(r, c, form, item[k], CHECK_PROBLEM_LEN);
            k++;
        }
    return k;
}

int meshcheck_problems(const CheckCounts *c, char (*item)[CHECK_PROBLEM_LEN], int max)
{
    return meshcheck_problems_as(c, CHECK_SAY_PROBLEM, item, max);
}

int meshcheck_verdict(const CheckCounts *c, char *buf, size_t n)
{
    char item[CHECK_PROBLEMS_MAX][CHECK_PROBLEM_LEN];
    int k = meshcheck_problems(c, item, CHECK_PROBLEMS_MAX);
    if (!n)
        return k;
    snprintf(buf, n, "%s", k ? "" : "sound");
    size_t len = strlen(buf);
    for (int i = 0; i < k && i < CHECK_PROBLEMS_MAX && len + 1 < n; i++) {
        int w = snprintf(buf + len, n - len, "%s%s", i ? ", " : "", item[i]);
        len = w > 0 && len + (size_t)w < n ? len + (size_t)w : n - 1;
    }
    return k;
}

/* ==== The kinds of location ==== */

const CheckRow *meshcheck_loc_row(CheckLocKind k)
{
    static const char *const field[CHECK_LOC_KINDS] = {
        [CHECK_LOC_HOLES] = "holes",
        [CHECK_LOC_NM_EDGES] = "nonmanifold_edges",
        [CHECK_LOC_NM_VERTICES] = "nonmanifold_vertices",
        [CHECK_LOC_FLIPPED] = "inconsistent_faces",
        [CHECK_LOC_DEGENERATE] = "degenerate_faces",
        [CHECK_LOC_DUPLICATE] = "duplicate_faces",
        [CHECK_LOC_CROSSING] = "self_intersections",
    };
    for (int i = 0; k < CHECK_LOC_KINDS && i < check_nrows; i++)
        if (!strcmp(check_rows[i].field, field[k]))
            return &check_rows[i];
    return NULL;
}

uint64_t meshcheck_loc_total(const CheckCounts *c, CheckLocKind k)
{
    const CheckRow *r = meshcheck_loc_row(k);
    return r ? meshcheck_value(r, c) : 0;
}

uint32_t meshcheck_loc_located(const CheckLocations *l, CheckLocKind k)
{
    switch (k) {
    case CHECK_LOC_HOLES:
        return l->nloops;
    case CHECK_LOC_NM_EDGES:
        return l->nedges;
    case CHECK_LOC_NM_VERTICES:
        return l->nverts;
    case CHECK_LOC_FLIPPED:
    case CHECK_LOC_DEGENERATE:
    case CHECK_LOC_DUPLICATE:
        return l->nfaces[k - CHECK_LOC_FLIPPED];
    case CHECK_LOC_CROSSING:
        return l->npairs;
    case CHECK_LOC_KINDS:
        break;
    }
    return 0;
}
