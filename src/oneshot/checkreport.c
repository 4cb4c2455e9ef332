/* checkreport.c: --check FILE...: is each model right? Every file is loaded on
 * its own, checked (check/: meshcheck_run) and freed before the next, so
 * that the memory is one model's; the picture, when --print or -o asks
 * for one, comes first, then the report: a block per file (and per
 * object when a file has several), then one verdict line. --json
 * prints one JSON document instead (the schema is in the man page and
 * the README). Exit status: 0 sound, 3 problems found, 1 a file could
 * not be read (or the output not written); with --textconv (git's
 * textconv driver) 0 once read, and the file named "model". */

#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshcheck.h"
#include "oneshot.h"
#include "safetext.h"

typedef struct {
    const char *path;
    const char *name;           /* as the report names it: the path, or "model" (--textconv) */
    int         read;           /* loaded and checked; else err says why */
    char        err[512];
    char        format[32];
    MeshCheck   mc;
    PrintFigures pf;            /* will it print (printreport.c) */
    SectionFigures sec[SECTION_MAX];    /* --section: each plane's section of the file */
} FileCheck;

/* ==== Checking ==== */

/* Each --section plane's section of the whole file (sections.c's
 * figures: area, perimeter, loops, the open chains' ends). */
static int sections(const Options *o, const Mesh *m, FileCheck *fc)
{
    uint8_t *mask = malloc((size_t)m->nverts + 1);
    if (!mask)
        return -1;
    section_masks(o->section, o->nsections, m->pos, m->nverts, mask);
    SectionPolys in = { m->pos, m->face_start, m->corner, 0, m->nfaces, mask };
    SectionWork *w = NULL;
    int rc = 0;
    for (int i = 0; i < o->nsections && !rc; i++)
        rc = section_loops(&in, o->section, o->nsections, i, &w, &fc->sec[i], NULL);
    section_work_free(&w);
    free(mask);
    return rc;
}

static int check_file(const Options *o, FileCheck *fc)
{
    MeshLoadOpts lo = app_load_opts(o);
    lo.no_textures = 1;         /* the check reads positions and faces only */
    SandboxOpts so = app_sandbox_opts(o);
    Mesh m;
    if (sandbox_load(&m, fc->path, &lo, &so, fc->err, sizeof fc->err))
        return -1;
    app_after_load(o, &m);
    /* the check reads positions and faces only: what else it holds goes
     * first, so that the check's memory comes out of the model's */
    free(m.face_mat);
    m.face_mat = NULL;
    free(m.rgb);
    m.rgb = NULL;
    snprintf(fc->format, sizeof fc->format, "%s", m.info.format);
    /* where the problems are: the JSON's locations, or the text's few */
    CheckOpts co = { .threads = o->threads > 0 ? o->threads : default_threads(), .intersections = 1,
                     .locations = o->json ? o->max_locations : CHECK_LOCATIONS_TEXT };
    int r = meshcheck_run(&fc->mc, &m, &co, fc->err, sizeof fc->err);
    if (r == 0 && print_figures_run(o, &m, &fc->mc.file, &fc->pf, fc->err, sizeof fc->err)) {
        meshcheck_free(&fc->mc);
        r = -1;
    }
    if (!r && o->nsections && sections(o, &m, fc)) {
        snprintf(fc->err, sizeof fc->err, "%s: out of memory cutting it", fc->path);
        r = -1;
    }
    mesh_free(&m);
    if (r)
        return -1;
    fc->read = 1;
    return 0;
}

/* The picture --print or -o asks for, of all the files as one scene, as
 * without --check. */
static int picture(const Options *o)
{
    char err[512];
    Scene s;
    if (oneshot_check_output(o, err, sizeof err) || app_load_scene(o, &s, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    int rc = oneshot_run(o, &s);
    scene_free(&s);
    fflush(stdout);
    return rc;
}

/* ==== The text report ==== */

/* " mm", " mm^2": the unit the format states ("" none), to a power. */
static const char *unit_of(const char *unit, int power, char *buf, size_t n)
{
    if (!unit[0])
        return "";
    if (power == 1)
        snprintf(buf, n, " %s", unit);
    else
        snprintf(buf, n, " %s^%d", unit, power);
    return buf;
}

/* The centre of mass with the rounding of its sums taken off: a
 * component within a billionth of the model's size of zero is zero (a
 * torus about the origin has its centre at 0 0 0, not 1.4e-10 ...). */
static void centre_rounded(const CheckCounts *c, double out[3])
{
    double size = 0;
    for (int k = 0; k < 3; k++) {
        double d = (double)c->hi[k] - c->lo[k];
        size = d > size ? d : size;
    }
    for (int k = 0; k < 3; k++)
        out[k] = fabs(c->centre[k]) <= 1e-9 * size ? 0 : c->centre[k];
}

void check_text_counts(Out *out, const CheckCounts *c, const CheckLocations *loc, const char *unit, const char *ind)
{
    char u1[16], u2[16], u3[16], words[512];
    if (!c->faces) {
        out_printf(out, "%sfaces         none\n", ind);
        return;
    }
    /* the measures, then the rows (counts.c), then the verdict */
    out_printf(out, "%ssize          %g x %g x %g%s\n", ind, (double)c->hi[0] - c->lo[0],
               (double)c->hi[1] - c->lo[1], (double)c->hi[2] - c->lo[2],
               unit[0] ? unit_of(unit, 1, u1, sizeof u1) : " (file units; the format states none)");
    out_printf(out, "%sarea          %g%s\n", ind, c->area, unit_of(unit, 2, u2, sizeof u2));
    double com[3];
    centre_rounded(c, com);
    if (c->has_volume)
        out_printf(out, "%svolume        %g%s, centre of mass %g %g %g\n", ind, c->volume, unit_of(unit, 3, u3, sizeof u3),
                   com[0], com[1], com[2]);
    else
        out_printf(out, "%svolume        none: %s\n", ind, c->closed ? "not orientable" : "not closed");
    CheckLine line[CHECK_LINES_MAX];
    int n = meshcheck_lines(c, line, CHECK_LINES_MAX);
    for (int i = 0; i < n; i++) {
        out_printf(out, "%s%-14s%s\n", ind, line[i].label, line[i].text);
        if (loc)
            check_text_locations(out, loc, c, line[i].line, unit, ind);
    }
    meshcheck_verdict(c, words, sizeof words);
    out_printf(out, "%s%-14s%s\n", ind, meshcheck_sound(c) ? "verdict" : "problems", words);
}

/* --section's figures, a line a plane: area, perimeter, closed loops,
 * open chains and where the first few end (the figures of the JSON's
 * "sections"). */
#define TEXT_ENDS 3
static void text_sections(Out *out, const Options *o, const FileCheck *fc, const char *unit, const char *ind)
{
    char u1[48], u2[48];
    for (int i = 0; i < o->nsections; i++) {
        const SectionFigures *f = &fc->sec[i];
        char text[SECTION_TEXT];
        section_text(&o->section[i], text, sizeof text);
        out_printf(out, "%s%-14s%s: area %g%s, perimeter %g%s, %u closed loop%s, %u open chain%s", ind, "section", text,
                   f->area, unit_of(unit, 2, u2, sizeof u2), f->perimeter, unit_of(unit, 1, u1, sizeof u1), f->loops,
                   f->loops == 1 ? "" : "s", f->chains, f->chains == 1 ? "" : "s");
        for (uint32_t k = 0; k < f->nends && k < TEXT_ENDS; k++) {
            const float *a = f->ends[k][0], *b = f->ends[k][1];
            out_printf(out, "%s%g %g %g to %g %g %g", k ? "; " : " (from ", (double)a[0], (double)a[1], (double)a[2],
                       (double)b[0], (double)b[1], (double)b[2]);
        }
        out_printf(out, "%s\n", f->nends > TEXT_ENDS ? "; ...)" : f->nends ? ")" : "");
    }
}

static void text_file(Out *out, const Options *o, const FileCheck *fc)
{
    /* the file's name and what its loader said, made safe (safetext.h) */
    char path[SAFETEXT_NAME];
    safetext(path, sizeof path, fc->name);
    if (!fc->read) {
        /* the message names the file already */
        size_t n = strlen(fc->path);
        const char *why = !strncmp(fc->err, fc->path, n) && !strncmp(fc->err + n, ": ", 2) ? fc->err + n + 2 : fc->err;
        char safe_why[4 * sizeof fc->err];
        out_printf(out, "%s: not read: %s\n", path, safetext(safe_why, sizeof safe_why, why));
        return;
    }
    const MeshCheck *mc = &fc->mc;
    uint32_t nobj = 0;
    for (uint32_t i = 0; i < mc->nobjs; i++)
        nobj += mc->objs[i].c.faces > 0;
    /* the unit came from the loader's child, as the names did */
    char unit[4 * sizeof mc->unit];
    safetext(unit, sizeof unit, mc->unit);
    char format[4 * sizeof fc->format];
    out_printf(out, "%s (%s)", path, safetext(format, sizeof format, fc->format));
    if (nobj > 1) {
        out_printf(out, ": %u objects\n", nobj);
        for (uint32_t i = 0, k = 0; i < mc->nobjs; i++)
            if (mc->objs[i].c.faces) {
                char name[SAFETEXT_NAME];
                out_printf(out, "  object %u \"%s\"\n", ++k, safetext(name, sizeof name, mc->objs[i].name));
                check_text_counts(out, &mc->objs[i].c, &mc->objs[i].loc, unit, "    ");
            }
        out_printf(out, "  all %u objects\n", nobj);
        check_text_counts(out, &mc->file, NULL, unit, "    ");
        print_figures_text(out, &fc->pf, unit, "    ");
        text_sections(out, o, fc, unit, "    ");
    } else {
        /* one object with faces (or none): the file's figures are its */
        const CheckLocations *loc = NULL;
        for (uint32_t i = 0; i < mc->nobjs; i++)
            if (mc->objs[i].c.faces)
                loc = &mc->objs[i].loc;
        out_printf(out, "\n");
        check_text_counts(out, &mc->file, loc, unit, "  ");
        print_figures_text(out, &fc->pf, unit, "  ");
        text_sections(out, o, fc, unit, "  ");
    }
}

/* The last line: sound, or every file's problems. */
static void text_verdict(Out *out, const FileCheck *fcs, int n)
{
    int bad = 0;
    for (int i = 0; i < n; i++)
        bad += !fcs[i].read || !meshcheck_sound(&fcs[i].mc.file);
    if (!bad) {
        out_printf(out, "verdict: sound\n");
        return;
    }
    out_printf(out, "verdict: ");
    for (int i = 0, k = 0; i < n; i++) {
        char words[512], path[SAFETEXT_NAME];
        if (fcs[i].read && meshcheck_sound(&fcs[i].mc.file))
            continue;
        if (fcs[i].read)
            meshcheck_verdict(&fcs[i].mc.file, words, sizeof words);
        out_printf(out, "%s%s: %s", k++ ? "; " : "", safetext(path, sizeof path, fcs[i].name),
                   fcs[i].read ? words : "not read");
    }
    out_printf(out, "\n");
}

/* ==== JSON ==== */

void oneshot_json_str(Out *out, const char *s)
{
    out_write(out, "\"", 1);
    while (*s) {
        char piece[SAFETEXT_PIECE];
        s += safetext_next(s, piece, SAFETEXT_JSON);
        out_write(out, piece, strlen(piece));
    }
    out_write(out, "\"", 1);
}

static const char *json_bool(int b)
{
    return b ? "true" : "false";
}

void check_json_counts(Out *out, const CheckCounts *c, const char *ind)
{
    for (int i = 0; i < check_nrows; i++) {     /* the rows (counts.c), then the measures */
        const CheckRow *r = &check_rows[i];
        uint64_t v = meshcheck_value(r, c);
        if (!r->json)
            continue;
        if (r->type == CHECK_FLAG || r->json_bool)
            out_printf(out, ",\n%s\"%s\": %s", ind, r->json, json_bool(v > 0));
        else
            out_printf(out, ",\n%s\"%s\": %llu", ind, r->json, (unsigned long long)v);
    }
    out_printf(out, ",\n%s\"area\": %.9g", ind, c->area);
    double com[3];
    centre_rounded(c, com);
    if (c->has_volume)
        out_printf(out, ",\n%s\"volume\": %.9g,\n%s\"center_of_mass\": [%.9g, %.9g, %.9g]", ind, c->volume, ind,
                   com[0], com[1], com[2]);
    else
        out_printf(out, ",\n%s\"volume\": null,\n%s\"center_of_mass\": null", ind, ind);
    if (c->faces)
        out_printf(out, ",\n%s\"size\": [%.9g, %.9g, %.9g],\n%s\"min\": [%.9g, %.9g, %.9g]", ind,
                   (double)c->hi[0] - c->lo[0], (double)c->hi[1] - c->lo[1], (double)c->hi[2] - c->lo[2], ind,
                   c->lo[0], c->lo[1], c->lo[2]);
    else
        out_printf(out, ",\n%s\"size\": null,\n%s\"min\": null", ind, ind);
    char item[CHECK_PROBLEMS_MAX][CHECK_PROBLEM_LEN];
    int k = meshcheck_problems(c, item, CHECK_PROBLEMS_MAX);
    out_printf(out, ",\n%s\"problems\": [", ind);
    for (int i = 0; i < k; i++) {
        out_printf(out, "%s", i ? ", " : "");
        oneshot_json_str(out, item[i]);
    }
    out_printf(out, "]");
}

static void json_point(Out *out, const float p[3])
{
    out_printf(out, "[%.9g, %.9g, %.9g]", (double)p[0], (double)p[1], (double)p[2]);
}

/* --section's figures: each plane's area, perimeter, loops, and where
 * the open chains (an open model) end. */
static void json_sections(Out *out, const Options *o, const FileCheck *fc)
{
    if (!o->nsections)
        return;
    out_printf(out, ",\n      \"sections\": [");
    for (int i = 0; i < o->nsections; i++) {
        const SectionFigures *f = &fc->sec[i];
        char text[SECTION_TEXT];
        section_text(&o->section[i], text, sizeof text);
        out_printf(out, "%s\n        { \"plane\": ", i ? "," : "");
        oneshot_json_str(out, text);
        out_printf(out, ", \"area\": %.9g, \"perimeter\": %.9g, \"loops\": %u, \"open_chains\": %u, \"open_ends\": [",
                   f->area, f->perimeter, f->loops, f->chains);
        for (uint32_t k = 0; k < f->nends; k++) {
            out_printf(out, "%s[", k ? ", " : "");
            json_point(out, f->ends[k][0]);
            out_printf(out, ", ");
            json_point(out, f->ends[k][1]);
            out_printf(out, "]");
        }
        out_printf(out, "] }");
    }
    out_printf(out, "\n      ]");
}

static void json_file(Out *out, const Options *o, const FileCheck *fc, int first)
{
    out_printf(out, "%s\n    {\n      \"path\": ", first ? "" : ",");
    oneshot_json_str(out, fc->name);
    if (!fc->read) {
        out_printf(out, ",\n      \"ok\": false,\n      \"error\": ");
        oneshot_json_str(out, fc->err);
        out_printf(out, "\n    }");
        return;
    }
    out_printf(out, ",\n      \"format\": ");
    oneshot_json_str(out, fc->format);
    out_printf(out, ",\n      \"unit\": ");
    if (fc->mc.unit[0])
        oneshot_json_str(out, fc->mc.unit);
    else
        out_printf(out, "null");
    uint32_t nobj = 0;
    for (uint32_t i = 0; i < fc->mc.nobjs; i++)
        nobj += fc->mc.objs[i].c.faces > 0;
    out_printf(out, ",\n      \"ok\": %s,\n      \"object_count\": %u", json_bool(meshcheck_sound(&fc->mc.file)),
               nobj);
    check_json_counts(out, &fc->mc.file, "      ");
    print_figures_json(out, &fc->pf, "      ");
    json_sections(out, o, fc);
    out_printf(out, "\n    }");
}

/* The objects with faces (a file without any: the file as one). */
static void json_objects(Out *out, const FileCheck *fc, int *first)
{
    const MeshCheck *mc = &fc->mc;
    int any = 0;
    for (uint32_t i = 0; i <= mc->nobjs; i++) {
        const CheckCounts *c = i < mc->nobjs ? &mc->objs[i].c : &mc->file;
        if (i < mc->nobjs ? !c->faces : any)
            continue;
        any = 1;
        out_printf(out, "%s\n    {\n      \"file\": ", *first ? "" : ",");
        oneshot_json_str(out, fc->name);
        out_printf(out, ",\n      \"name\": ");
        oneshot_json_str(out, i < mc->nobjs ? mc->objs[i].name : fc->name);
        out_printf(out, ",\n      \"ok\": %s", json_bool(meshcheck_sound(c)));
        check_json_counts(out, c, "      ");
        CheckLocations none = { 0 };
        check_json_locations(out, i < mc->nobjs ? &mc->objs[i].loc : &none, c, "      ");
        out_printf(out, "\n    }");
        *first = 0;
    }
}

static void json_report(Out *out, const Options *o, const FileCheck *fcs, int n)
{
    int ok = 1;
    for (int i = 0; i < n; i++)
        ok &= fcs[i].read && meshcheck_sound(&fcs[i].mc.file);
    out_printf(out, "{\n  \"ok\": %s,\n  \"files\": [", json_bool(ok));
    for (int i = 0; i < n; i++)
        json_file(out, o, &fcs[i], i == 0);
    out_printf(out, "\n  ],\n  \"objects\": [");
    int first = 1;
    for (int i = 0; i < n; i++)
        if (fcs[i].read)
            json_objects(out, &fcs[i], &first);
    out_printf(out, "\n  ]\n}\n");
}

/* ==== The front door ==== */

int oneshot_check(const Options *o)
{
    FileCheck *fcs = calloc((size_t)o->nfiles + 1, sizeof *fcs);
    if (!fcs) {
        safetext_line(stderr, "zview: out of memory");
        return 1;
    }
    int unread = 0, bad = 0, rc = 0;
    for (int i = 0; i < o->nfiles; i++) {
        fcs[i].path = o->files[i];
        /* git's textconv runs the report on a temporary copy whose name
         * changes every time: the report names no file */
        fcs[i].name = o->textconv ? "model" : o->files[i];
        if (check_file(o, &fcs[i])) {
            safetext_line(stderr, "zview: %s", fcs[i].err);
            unread++;
        } else
            bad += !meshcheck_sound(&fcs[i].mc.file);
    }
    if ((o->print || o->out) && picture(o))
        rc = 1;
    Out out;
    out_init(&out, stdout, "standard output");
    if (o->json)
        json_report(&out, o, fcs, o->nfiles);
    else {
        for (int i = 0; i < o->nfiles; i++)
            text_file(&out, o, &fcs[i]);
        text_verdict(&out, fcs, o->nfiles);
    }
    if (out_flush(&out)) {
        safetext_line(stderr, "zview: standard output: %s", out_error(&out));
        rc = 1;
    }
    for (int i = 0; i < o->nfiles; i++)
        meshcheck_free(&fcs[i].mc);
    free(fcs);
    /* --textconv: the problems are in the text; git takes any other
     * status than 0 for a failure to convert */
    return rc || unread ? 1 : bad && !o->textconv ? 3 : 0;
}
