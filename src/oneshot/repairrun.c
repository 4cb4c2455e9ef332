/* repairrun.c: --repair IN -o OUT. IN is loaded as every model is (the
 * sandboxed load path, app_load_opts), checked and repaired in memory
 * by the steps asked (repair/: repair_mesh checks the input and the
 * result, crossing tests included, and keeps both checks for the
 * report), written to OUT (save/: whole or not at all) and checked as
 * OUT holds it: read back the same way when the format changed what the
 * check reads (an STL's triangles; objects written as one, whose faces
 * are then checked together), else the repaired mesh itself, which the
 * file holds exactly (test_save.c; the e2e tests count every file
 * written on their own, tests/e2e/meshcount.py): repair_mesh's check of
 * it is that check. The report says what each step did
 * with its counts, what the format could not carry, and the two checks
 * side by side; --json says the same as one document. With -o - the
 * model goes to standard output, the report to standard error.
 *
 * IN is never written: OUT must not be IN, by inode (a link, a symlink,
 * another spelling of its path), nor may an OBJ's MTL be. Exit status:
 * 0 OUT is sound, 3 problems remain (crossing faces among them: they
 * are reported, never moved), 1 IN not read or OUT not written, 2 OUT
 * would be IN. */

#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "clock.h"
#include "meshcheck.h"
#include "oneshot.h"
#include "repair.h"
#include "safetext.h"
#include "save.h"
#include "thread.h"

typedef struct {
    const Options *o;
    const char    *in, *out;
    SaveFormat     fmt;
    char           in_format[32];
    MeshCheck      before, after;
    RepairReport   rep;
    SaveReport     saved;
    int            threads;
    double         ms_load, ms_check, ms_repair, ms_write, ms_after;
    char           err[1024];
} RepairRun;

/* ==== IN is never written ==== */

/* Is path the file IN is (same device and inode)? */
static int is_input(const char *path, const struct stat *in)
{
    struct stat st;
    return stat(path, &st) == 0 && st.st_dev == in->st_dev && st.st_ino == in->st_ino;
}

/* 0, or 2 with the message (OUT or its MTL would overwrite IN). */
static int refuse_in_place(RepairRun *r)
{
    struct stat in;
    if (!strcmp(r->in, "-") || !strcmp(r->out, "-") || stat(r->in, &in))
        return 0;               /* standard input, or IN gone: the load says so */
    char mtl[4096] = "";
    if (r->fmt == SAVE_OBJ) {
        size_t n = strlen(r->out);
        size_t stem = n >= 4 && !strcasecmp(r->out + n - 4, ".obj") ? n - 4 : n;
        if (stem + 5 <= sizeof mtl)
            snprintf(mtl, sizeof mtl, "%.*s.mtl", (int)stem, r->out);
    }
    const char *same = is_input(r->out, &in) ? r->out : mtl[0] && is_input(mtl, &in) ? mtl : NULL;
    if (!same)
        return 0;
    snprintf(r->err, sizeof r->err, "%.400s is the model being repaired (%.400s): --repair writes a copy, never the "
             "input; name another -o", same, r->in);
    return 2;
}

/* ==== The run ==== */

static int load(RepairRun *r, const char *path, int textures, Mesh *m)
{
    MeshLoadOpts lo = app_load_opts(r->o);
    lo.format = NULL;               /* with --repair, --format names what is written */
    lo.no_textures = !textures;
    lo.tex_defer_side = 1;          /* the images' names are kept, their pixels never decoded */
    SandboxOpts so = app_sandbox_opts(r->o);
    return sandbox_load(m, path, &lo, &so, r->err, sizeof r->err);
}

/* The write of the repaired mesh on a helper thread, beside
 * repair_mesh's check of it (two threads or more): both only read the
 * mesh, which the repair no longer changes once it calls installed. */
typedef struct {
    RepairRun *r;
    const Mesh *m;
    pthread_t  th;
    int        started, rc;
    double     ms;
    char       err[1024];
} Writer;

static void *writer_main(void *arg)
{
    Writer *w = arg;
    double t = now_ms();
    w->rc = save_mesh(w->m, w->r->out, w->r->fmt, &w->r->saved, w->err, sizeof w->err);
    w->ms = now_ms() - t;
    return NULL;
}

static void writer_start(const Mesh *m, void *arg)
{
    Writer *w = arg;
    w->m = m;
    if (thread_start(&w->th, writer_main, w) == 0)
        w->started = 1;
}

static int check(RepairRun *r, const Mesh *m, MeshCheck *mc)
{
    CheckOpts co = { .threads = r->threads, .intersections = 1 };
    return meshcheck_run(mc, m, &co, r->err, sizeof r->err);
}

/* Load, repair (repair_mesh checks the input first and the result,
 * crossing tests included, and hands both checks over), write, and
 * check what OUT holds. 0, or 1 with the message in r->err. */
static int run(RepairRun *r)
{
    Mesh m;
    double t0 = now_ms();
    app_sandbox_warn(r->o);
    if (load(r, r->in, 1, &m))
        return 1;
    app_after_load(r->o, &m);
    snprintf(r->in_format, sizeof r->in_format, "%s", m.info.format);
    double t1 = now_ms();
    RepairOpts ro = { .steps = r->o->repair, .weld_eps = r->o->weld, .max_hole = r->o->max_hole,
                      .threads = r->threads, .intersections = 1, .keep_checks = 1 };
    Writer w = { .r = r };
    if (r->threads > 1) {
        ro.installed = writer_start;
        ro.installed_arg = &w;
    }
    int rc = repair_mesh(&m, &ro, &r->rep, r->err, sizeof r->err);
    if (rc == 0) {
        r->before = r->rep.before;
        memset(&r->rep.before, 0, sizeof r->rep.before);
    }
    double t2 = now_ms();
    if (w.started) {
        /* repair_mesh succeeds once it calls installed */
        pthread_join(w.th, NULL);
        if (w.rc)
            snprintf(r->err, sizeof r->err, "%s", w.err);
        rc = rc || w.rc;
    } else {
        rc = rc || save_mesh(&m, r->out, r->fmt, &r->saved, r->err, sizeof r->err);
    }
    double t3 = now_ms();
    /* the check after is of what OUT holds: the repaired mesh itself
     * (repair_mesh's check of it) when the format keeps every polygon
     * and object (an OBJ always: the writers' tests read it back the
     * same), else OUT read back */
    const SaveReport *sr = &r->saved;
    double ms_after = 0;
    if (!rc && (!strcmp(r->out, "-") || !(sr->polygons_split || sr->objects_merged || sr->faces_dropped))) {
        if (r->rep.counted) {
            r->after = r->rep.after;
            memset(&r->rep.after, 0, sizeof r->rep.after);
            ms_after = r->rep.ms_phase[REPAIR_T_CHECK];
        } else {
            rc = check(r, &m, &r->after);   /* its check could not run: again */
        }
        mesh_free(&m);
    } else {
        mesh_free(&m);          /* one model in memory at a time */
        Mesh back;
        if (!rc && !(rc = load(r, r->out, 0, &back))) {
            rc = check(r, &back, &r->after);
            mesh_free(&back);
        }
    }
    double *ph = r->rep.ms_phase;
    r->ms_load = t1 - t0;
    r->ms_check = ph[REPAIR_T_BEFORE];
    r->ms_repair = t2 - t1 - ph[REPAIR_T_BEFORE] - ph[REPAIR_T_CHECK];
    /* written beside the check of the result: the write's own time (the
     * phases then add up to more than the wall time) */
    r->ms_write = w.started ? w.ms : t3 - t2;
    r->ms_after = ms_after + now_ms() - t3;
    return rc ? 1 : 0;
}

/* ==== The text report ==== */

static const char *const step_names[] = { "weld", "clean", "manifold", "winding", "holes" };
static const unsigned step_bits[] = { REPAIR_WELD, REPAIR_CLEAN, REPAIR_MANIFOLD, REPAIR_WINDING, REPAIR_HOLES };
#define NSTEPS 5

static void text_open_holes(Out *out, const RepairRun *r);

/* A step's words: its rows' that are not zero, joined (n: how long). */
static size_t step_words(const RepairRun *r, int s, char *line, size_t cap)
{
    char words[256];
    size_t n = 0;
    line[0] = 0;
    for (int i = 0; i < repair_nrows; i++)
        if (repair_rows[i].step == step_bits[s]) {
            repair_say(&repair_rows[i], &r->rep, words, sizeof words);
            if (words[0] && n < cap)
                n += (size_t)snprintf(line + n, cap - n, "%s%s", n ? ", " : "", words);
        }
    return n;
}

/* The steps: a line for each that did something (the weld's too when
 * --weld gave it a distance, which it says), then those that found
 * nothing to do, then those not asked, a line each. */
static void text_steps(Out *out, const RepairRun *r)
{
    char line[1024], idle[128] = "", skipped[128] = "";
    for (int s = 0; s < NSTEPS; s++) {
        char *list = !(r->o->repair & step_bits[s]) ? skipped : idle;
        int weld = step_bits[s] == REPAIR_WELD && r->o->weld > 0;
        if (list == skipped || (!step_words(r, s, line, sizeof line) && !weld)) {
            snprintf(list + strlen(list), sizeof idle - strlen(list), "%s%s", list[0] ? ", " : "", step_names[s]);
            continue;
        }
        out_printf(out, "  %-10s %s", step_names[s], line[0] ? line : "nothing to weld");
        if (weld)
            out_printf(out, " (vertices up to %g apart: --weld %g)", r->o->weld, r->o->weld);
        out_printf(out, "\n");
        if (step_bits[s] == REPAIR_HOLES)
            text_open_holes(out, r);
    }
    if (idle[0])
        out_printf(out, "  %-10s %s: nothing to do\n", "unchanged", idle);
    if (skipped[0])
        out_printf(out, "  %-10s %s (--repair=STEPS)\n", "not asked", skipped);
}

/* The loops the hole filling left open, the first few. */
static void text_open_holes(Out *out, const RepairRun *r)
{
    for (uint32_t i = 0; i < r->rep.nholes && i < 10; i++) {
        const RepairHole *h = &r->rep.holes[i];
        out_printf(out, "  %-10s a hole of %u edges in object %u, at vertex %u: %s\n", "", h->edges, h->object + 1,
                   h->vertex + 1, repair_open_why(h->why));
    }
    if (r->rep.open > 10)
        out_printf(out, "  %-10s and %u more\n", "", r->rep.open - 10);
}

/* What the format could not carry. */
static void text_dropped(Out *out, const SaveReport *s)
{
    const char *fmt = save_format_name(s->format);
    if (s->polygons_split)
        out_printf(out, "  %-10s %u polygons written as triangles (%s holds triangles only)\n", "", s->polygons_split,
                   fmt);
    if (s->objects_merged)
        out_printf(out, "  %-10s %u objects written as one (%s keeps no objects)\n", "", s->objects_merged + 1, fmt);
    if (s->materials_dropped)
        out_printf(out, "  %-10s %u materials not kept (%s)\n", "", s->materials_dropped,
                   s->format == SAVE_OBJ ? "no MTL beside standard output" : fmt);
    if (s->colours_dropped)
        out_printf(out, "  %-10s vertex colours not kept (%s)\n", "", fmt);
    if (s->uvs_dropped)
        out_printf(out, "  %-10s texture coordinates not kept (%s)\n", "", fmt);
    if (s->points_dropped || s->lines_dropped)
        out_printf(out, "  %-10s %u points and %u lines not kept (%s)\n", "", s->points_dropped, s->lines_dropped, fmt);
    if (s->faces_dropped)
        out_printf(out, "  %-10s %u faces of fewer than 3 corners left out\n", "", s->faces_dropped);
}

/* A check row's value in the table: a number, or yes / no. */
static void cell(const CheckRow *row, const CheckCounts *c, char *buf, size_t n)
{
    uint64_t v = meshcheck_value(row, c);
    if (row->type == CHECK_FLAG)
        snprintf(buf, n, "%s", v ? "yes" : "no");
    else    /* a count that stopped on its budget is a lower bound */
        snprintf(buf, n, "%llu%s", (unsigned long long)v,
                 row->bound && *(const int *)((const char *)c + row->bound_at) ? "+" : "");
}

/* The check before and after, side by side: the rows of the check's
 * table (counts.c) that its text report says and that are not zero on
 * either side (the faces, vertices, parts and watertight always), the
 * volume, then each verdict in full. */
static void text_checks(Out *out, const RepairRun *r)
{
    const CheckCounts *b = &r->before.file, *a = &r->after.file;
    out_printf(out, "  %-22s %-16s %s\n", "check", "before", "after");
    for (int i = 0; i < check_nrows; i++) {
        const CheckRow *row = &check_rows[i];
        if (!row->json || !row->text_one)
            continue;           /* the crossing test's budget: --check --json has it */
        char label[64], vb[32], va[32];
        snprintf(label, sizeof label, "%s", row->json);
        for (char *p = label; *p; p++)
            *p = *p == '_' ? ' ' : *p;
        int always = row->bad == CHECK_BAD_ZERO || !strcmp(row->json, "vertices") ||
                     !strcmp(row->json, "components") || !strcmp(row->json, "watertight");
        if (!always && !meshcheck_value(row, b) && !meshcheck_value(row, a))
            continue;
        cell(row, b, vb, sizeof vb);
        cell(row, a, va, sizeof va);
        out_printf(out, "  %-22s %-16s %s\n", label, vb, va);
    }
    char vb[32] = "none", va[32] = "none";
    if (b->has_volume)
        snprintf(vb, sizeof vb, "%.9g", b->volume);
    if (a->has_volume)
        snprintf(va, sizeof va, "%.9g", a->volume);
    out_printf(out, "  %-22s %-16s %s\n", "volume", vb, va);
    char words[1024];
    meshcheck_verdict(b, words, sizeof words);
    out_printf(out, "  %-22s %s\n", "before", words);
    meshcheck_verdict(a, words, sizeof words);
    out_printf(out, "  %-22s %s\n", "after", words);
}

static void text_report(Out *out, const RepairRun *r)
{
    char in[SAFETEXT_NAME], outp[SAFETEXT_NAME], fmt[4 * 32];
    out_printf(out, "%s (%s) -> %s (%s)\n", safetext(in, sizeof in, r->in), safetext(fmt, sizeof fmt, r->in_format),
               strcmp(r->out, "-") ? safetext(outp, sizeof outp, r->out) : "standard output",
               save_format_name(r->fmt));
    text_steps(out, r);
    const CheckCounts *a = &r->after.file;
    if (a->self_intersections)
        out_printf(out, "  %-10s %llu%s pairs of faces cross: reported, not changed (a repair moves no face)\n",
                   "crossing", (unsigned long long)a->self_intersections, a->intersections_stopped ? "+" : "");
    else
        out_printf(out, "  %-10s no faces cross (crossing faces are reported, never changed)\n", "crossing");
    const SaveReport *s = &r->saved;
    if (s->format == SAVE_STL)
        out_printf(out, "  %-10s %u triangles, %llu bytes", "written", s->faces, (unsigned long long)s->bytes);
    else
        out_printf(out, "  %-10s %u faces, %u vertices, %llu bytes", "written", s->faces, s->vertices,
                   (unsigned long long)s->bytes);
    if (s->mtl_path[0])
        out_printf(out, " (materials in %s)", safetext(outp, sizeof outp, s->mtl_path));
    out_printf(out, "\n");
    text_dropped(out, s);
    text_checks(out, r);
    out_printf(out, "verdict: %s\n", meshcheck_sound(a) ? "sound" : "problems remain");
}

/* ==== JSON ==== */

static void json_steps(Out *out, const RepairRun *r)
{
    out_printf(out, "  \"steps\": [");
    for (int s = 0, k = 0; s < NSTEPS; s++)
        if (r->o->repair & step_bits[s])
            out_printf(out, "%s\"%s\"", k++ ? ", " : "", step_names[s]);
    out_printf(out, "],\n");
    if (r->o->weld > 0)
        out_printf(out, "  \"weld\": %.17g,\n", r->o->weld);
    else
        out_printf(out, "  \"weld\": null,\n");
    if (r->o->max_hole)
        out_printf(out, "  \"max_hole\": %u,\n", r->o->max_hole);
    else
        out_printf(out, "  \"max_hole\": null,\n");
}

static void json_repair(Out *out, const RepairRun *r)
{
    out_printf(out, "  \"repair\": {");
    for (int i = 0; i < repair_nrows; i++)
        out_printf(out, "%s\n    \"%s\": %llu", i ? "," : "", repair_rows[i].json,
                   (unsigned long long)repair_value(&repair_rows[i], &r->rep));
    out_printf(out, ",\n    \"holes_left_open\": [");
    for (uint32_t i = 0; i < r->rep.nholes; i++) {
        const RepairHole *h = &r->rep.holes[i];
        out_printf(out, "%s\n      { \"object\": %u, \"edges\": %u, \"vertex\": %u, \"why\": ", i ? "," : "",
                   h->object + 1, h->edges, h->vertex + 1);
        oneshot_json_str(out, repair_open_why(h->why));
        out_printf(out, " }");
    }
    out_printf(out, "%s]\n  },\n", r->rep.nholes ? "\n    " : "");
}

static void json_written(Out *out, const RepairRun *r)
{
    const SaveReport *s = &r->saved;
    out_printf(out, "  \"written\": {\n    \"path\": ");
    oneshot_json_str(out, r->out);
    out_printf(out, ",\n    \"format\": \"%s\",\n    \"mtl\": ", save_format_name(s->format));
    if (s->mtl_path[0])
        oneshot_json_str(out, s->mtl_path);
    else
        out_printf(out, "null");
    out_printf(out, ",\n    \"bytes\": %llu,\n    \"faces\": %u,\n    \"vertices\": %u,\n    \"polygons_split\": %u,\n"
               "    \"objects_merged\": %u,\n    \"materials_dropped\": %u,\n    \"colours_dropped\": %s,\n"
               "    \"uvs_dropped\": %s,\n    \"points_dropped\": %u,\n    \"lines_dropped\": %u,\n"
               "    \"faces_dropped\": %u\n  },\n",
               (unsigned long long)s->bytes, s->faces, s->vertices, s->polygons_split, s->objects_merged,
               s->materials_dropped, s->colours_dropped ? "true" : "false", s->uvs_dropped ? "true" : "false",
               s->points_dropped, s->lines_dropped, s->faces_dropped);
}

static void json_report(Out *out, const RepairRun *r)
{
    out_printf(out, "{\n  \"ok\": %s,\n  \"input\": ", meshcheck_sound(&r->after.file) ? "true" : "false");
    oneshot_json_str(out, r->in);
    out_printf(out, ",\n  \"input_format\": ");
    oneshot_json_str(out, r->in_format);
    out_printf(out, ",\n");
    json_steps(out, r);
    json_repair(out, r);
    json_written(out, r);
    out_printf(out, "  \"before\": {\n    \"ok\": %s", meshcheck_sound(&r->before.file) ? "true" : "false");
    check_json_counts(out, &r->before.file, "    ");
    out_printf(out, "\n  },\n  \"after\": {\n    \"ok\": %s", meshcheck_sound(&r->after.file) ? "true" : "false");
    check_json_counts(out, &r->after.file, "    ");
    const double *ph = r->rep.ms_phase;
    out_printf(out, "\n  },\n  \"ms\": { \"load\": %.1f, \"check\": %.1f, \"repair\": %.1f, \"write\": %.1f, "
               "\"check_after\": %.1f, \"repair_weld\": %.1f, \"repair_clean\": %.1f, \"repair_objects\": %.1f, "
               "\"repair_order\": %.1f, \"repair_check\": %.1f }\n}\n",
               r->ms_load, r->ms_check, r->ms_repair, r->ms_write, r->ms_after, ph[REPAIR_T_WELD], ph[REPAIR_T_CLEAN],
               ph[REPAIR_T_OBJECTS], ph[REPAIR_T_ORDER], ph[REPAIR_T_CHECK]);
}

/* ==== The front door ==== */

int oneshot_repair(const Options *o)
{
    RepairRun *r = calloc(1, sizeof *r);
    if (!r) {
        safetext_line(stderr, "zview: out of memory");
        return 1;
    }
    r->o = o;
    r->in = o->files[0];
    r->out = o->out;
    r->fmt = (SaveFormat)(o->format ? save_format_from_name(o->format) : save_format_of_path(o->out));
    r->threads = o->threads > 0 ? o->threads : default_threads();
    int rc = refuse_in_place(r);
    if (!rc)
        rc = run(r);
    if (rc) {
        safetext_line(stderr, "zview: %s", r->err);
    } else {
        /* the model may be on standard output: the report goes beside it */
        FILE *f = strcmp(r->out, "-") ? stdout : stderr;
        Out out;
        out_init(&out, f, f == stdout ? "standard output" : "standard error");
        if (o->json)
            json_report(&out, r);
        else
            text_report(&out, r);
        if (out_flush(&out)) {
            safetext_line(stderr, "zview: %s: %s", out.name, out_error(&out));
            rc = 1;
        } else
            rc = meshcheck_sound(&r->after.file) ? 0 : 3;
    }
    meshcheck_free(&r->before);
    meshcheck_free(&r->after);
    repair_report_free(&r->rep);
    free(r);
    return rc;
}
