/* diffreport.c: --diff A B without a terminal: the picture when --print
 * or -o asks for one (the diff's scene, coloured: diffcolour.c), then
 * the report, in words or (--json) as one JSON document with names
 * that stay (the man page's DIFF section lists them); --quiet leaves
 * the report out. Exit status: 0 the same within the tolerance, 3 they
 * differ, 1 the output could not be written. */

#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "diff.h"
#include "oneshot.h"
#include "safetext.h"

/* ==== Words ==== */

/* 1234567 -> "1,234,567" */
static const char *count(uint64_t v, char *buf, size_t len)
{
    char tmp[32];
    int n = snprintf(tmp, sizeof tmp, "%llu", (unsigned long long)v);
    size_t o = 0;
    for (int i = 0; i < n && o + 2 < len; i++) {
        if (i && (n - i) % 3 == 0)
            buf[o++] = ',';
        buf[o++] = tmp[i];
    }
    buf[o] = 0;
    return buf;
}

static void text_side(Out *out, const DiffSet *ds, int i)
{
    char path[SAFETEXT_NAME], format[4 * sizeof ds->format[0]], words[512], f[32], v[32];
    const CheckCounts *c = &ds->d.check[i];
    meshcheck_verdict(c, words, sizeof words);
    out_printf(out, "%c  %s (%s): %s faces, %s vertices, %s\n", 'A' + i, safetext(path, sizeof path, ds->path[i]),
               safetext(format, sizeof format, ds->format[i]), count(c->faces, f, sizeof f),
               count(c->vertices, v, sizeof v), c->watertight && !strcmp(words, "sound") ? "watertight" : words);
}

/* "1 -> 2 (+1)" */
static void change(Out *out, const char *label, double a, double b)
{
    out_printf(out, "%-14s%.6g -> %.6g (%+.6g)\n", label, a, b, b - a);
}

static void text_side_distance(Out *out, const DiffSet *ds, const DiffSide *s, const char *what)
{
    char mx[48], mean[48], bound[48];
    diff_length(ds, s->max, mx, sizeof mx);
    diff_length(ds, s->mean, mean, sizeof mean);
    diff_length(ds, s->bound, bound, sizeof bound);
    char at[96] = "";
    if (s->max > 0)
        snprintf(at, sizeof at, " at %.6g %.6g %.6g", s->max_at[0], s->max_at[1], s->max_at[2]);
    out_printf(out, "  %s  max %s%s (at most %s), mean %s\n", what, mx, at, bound, mean);
}

static void text_report(Out *out, const DiffSet *ds)
{
    const Diff *d = &ds->d;
    char t[48], s1[32], s2[32], s3[32];
    text_side(out, ds, 0);
    text_side(out, ds, 1);
    diff_length(ds, d->tolerance, t, sizeof t);
    if (d->tol_given)
        out_printf(out, "%-14s%s (--tolerance)\n", "tolerance", t);
    else
        out_printf(out, "%-14s%s (0.1%% of the bounding box's diagonal; --tolerance sets it)\n", "tolerance", t);
    const CheckCounts *a = &ds->d.check[0], *b = &ds->d.check[1];
    out_printf(out, "%-14s%.6g x %.6g x %.6g -> %.6g x %.6g x %.6g\n", "size", (double)a->hi[0] - a->lo[0],
               (double)a->hi[1] - a->lo[1], (double)a->hi[2] - a->lo[2], (double)b->hi[0] - b->lo[0],
               (double)b->hi[1] - b->lo[1], (double)b->hi[2] - b->lo[2]);
    change(out, "area", a->area, b->area);
    if (a->has_volume && b->has_volume)
        change(out, "volume", a->volume, b->volume);
    else
        out_printf(out, "%-14snone: %s not closed\n", "volume", !a->has_volume && !b->has_volume ? "A and B"
                                                              : !a->has_volume                  ? "A"
                                                                                                : "B");
    char mx[48];
    diff_length(ds, d->hausdorff, mx, sizeof mx);
    out_printf(out, "%-14smax %s (Hausdorff, sampled), each way:\n", "distance", mx);
    text_side_distance(out, ds, &d->b, "B to A");
    text_side_distance(out, ds, &d->a, "A to B");
    out_printf(out, "%-14sA %s, B %s (vertices, points on the sides, centres in the faces)\n", "samples",
               count(d->a.vertex_samples + d->a.edge_samples + d->a.face_samples, s1, sizeof s1),
               count(d->b.vertex_samples + d->b.edge_samples + d->b.face_samples, s2, sizeof s2));
    out_printf(out, "%-14sadded %.6g, removed %.6g (area farther than the tolerance)\n", "changed", d->b.area_over,
               d->a.area_over);
    out_printf(out, "%-14s%s\n", "regions", count(d->nregions, s3, sizeof s3));
    for (uint32_t i = 0; i < d->nregions && i < DIFF_REGIONS_LISTED; i++) {
        const DiffRegion *r = &d->regions[i];
        diff_length(ds, r->max, mx, sizeof mx);
        out_printf(out, "  %u  max %s, added %.6g, removed %.6g, box %.6g %.6g %.6g to %.6g %.6g %.6g\n", i + 1, mx,
                   r->added, r->removed, r->lo[0], r->lo[1], r->lo[2], r->hi[0], r->hi[1], r->hi[2]);
    }
    if (d->nregions > DIFF_REGIONS_LISTED)
        out_printf(out, "  (the first %d listed)\n", DIFF_REGIONS_LISTED);
    char head[256];
    diff_headline(ds, 0, mode_from_locale() == MODE_HALF ? " \xc2\xb7 " : ", ", head, sizeof head);
    out_printf(out, "verdict: %s\n", head);
}

/* ==== JSON ==== */

static void json_xyz(Out *out, const char *name, double x, double y, double z)
{
    out_printf(out, ",\n      \"%s\": [%.9g, %.9g, %.9g]", name, x, y, z);
}

static void json_side(Out *out, const DiffSet *ds, int i)
{
    const DiffSide *s = i ? &ds->d.b : &ds->d.a;
    const CheckCounts *c = &ds->d.check[i];
    out_printf(out, "  \"%c\": {\n      \"path\": ", 'a' + i);
    oneshot_json_str(out, ds->path[i]);
    out_printf(out, ",\n      \"format\": ");
    oneshot_json_str(out, ds->format[i]);
    out_printf(out, ",\n      \"unit\": ");
    if (ds->unit[i][0])
        oneshot_json_str(out, ds->unit[i]);
    else
        out_printf(out, "null");
    out_printf(out, ",\n      \"ok\": %s,\n      \"crossings_tested\": false", meshcheck_sound(c) ? "true" : "false");
    check_json_counts(out, c, "      ");
    out_printf(out, ",\n      \"distance_max\": %.9g", s->max);
    json_xyz(out, "distance_max_at", s->max_at[0], s->max_at[1], s->max_at[2]);
    out_printf(out, ",\n      \"distance_bound\": %.9g,\n      \"distance_mean\": %.9g", s->bound, s->mean);
    out_printf(out, ",\n      \"area_over\": %.9g", s->area_over);
    out_printf(out, ",\n      \"samples\": {\"vertices\": %llu, \"edges\": %llu, \"faces\": %llu}\n    }",
               (unsigned long long)s->vertex_samples, (unsigned long long)s->edge_samples,
               (unsigned long long)s->face_samples);
}

static void json_report(Out *out, const DiffSet *ds)
{
    const Diff *d = &ds->d;
    const CheckCounts *a = &ds->d.check[0], *b = &ds->d.check[1];
    out_printf(out, "{\n  \"same\": %s,\n  \"tolerance\": %.9g,\n  \"tolerance_given\": %s,\n",
               diff_differ(d) ? "false" : "true", d->tolerance, d->tol_given ? "true" : "false");
    out_printf(out, "  \"hausdorff\": %.9g,\n  \"hausdorff_bound\": %.9g,\n", d->hausdorff, fmax(d->a.bound, d->b.bound));
    out_printf(out, "  \"area_change\": %.9g,\n  \"volume_change\": ", b->area - a->area);
    if (a->has_volume && b->has_volume)
        out_printf(out, "%.9g,\n", b->volume - a->volume);
    else
        out_printf(out, "null,\n");
    out_printf(out, "  \"added_area\": %.9g,\n  \"removed_area\": %.9g,\n", d->b.area_over, d->a.area_over);
    json_side(out, ds, 0);
    out_printf(out, ",\n");
    json_side(out, ds, 1);
    out_printf(out, ",\n  \"regions_count\": %u,\n  \"regions\": [", d->nregions);
    for (uint32_t i = 0; i < d->nregions && i < DIFF_REGIONS_LISTED; i++) {
        const DiffRegion *r = &d->regions[i];
        out_printf(out, "%s\n    {\"max\": %.9g, \"added_area\": %.9g, \"removed_area\": %.9g, \"faces_a\": %u, "
                        "\"faces_b\": %u, \"box_min\": [%.9g, %.9g, %.9g], \"box_max\": [%.9g, %.9g, %.9g]}",
                   i ? "," : "", r->max, r->added, r->removed, r->faces_a, r->faces_b, r->lo[0], r->lo[1], r->lo[2],
                   r->hi[0], r->hi[1], r->hi[2]);
    }
    out_printf(out, "%s]\n}\n", d->nregions ? "\n  " : "");
}

/* ==== The front door ==== */

int oneshot_diff(const Options *o, DiffSet *ds)
{
    int rc = 0;
    if (o->print || o->out) {
        char err[512];
        if (oneshot_check_output(o, err, sizeof err)) {
            safetext_line(stderr, "zview: %s", err);
            return 1;
        }
        rc = oneshot_run(o, &ds->scene);
        fflush(stdout);
    }
    if (!o->quiet) {
        Out out;
        out_init(&out, stdout, "standard output");
        if (o->json)
            json_report(&out, ds);
        else
            text_report(&out, ds);
        if (out_flush(&out)) {
            safetext_line(stderr, "zview: standard output: %s", out_error(&out));
            rc = 1;
        }
    }
    return rc ? 1 : diff_differ(&ds->d) ? 3 : 0;
}
