/* bench.c: --bench. Each model from N fixed views with each algorithm;
 * the first frame (choosing the algorithm and building its structures
 * included: what a switch costs), then medians of the projection, the
 * hidden-surface step (and its minimum), the shading and the whole frame.
 * Timing lives here, never in tests. */

#define _POSIX_C_SOURCE 200809L     /* strtok_r */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "clock.h"
#include "oneshot.h"
#include "safetext.h"

#define MAX_VIEWS 4096
/* Frames the benchmark waits at most for an algorithm's structures
 * built in the background (first_ms then says how long that took). */
#define READY_FRAMES 1000

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* View k of n: a turn around the model with a gentle nod. */
/* --section: view k of n has the planes slid along their normals, from
 * a quarter of the first object's size before where they were given to
 * a quarter past it, so that every frame cuts the model again (what
 * sliding the cut in the viewer costs). */
static void slide_planes(Pipeline *p, const Options *o, const Scene *s, int k, int n)
{
    if (!o->nsections || !s->nobjs)
        return;
    const Object *ob = &s->objs[0];
    double size = 2 * fmax(ob->half.x, fmax(ob->half.y, ob->half.z)) * ldexp(1, s->pos_exp);
    for (int i = 0; i < o->nsections; i++) {
        p->planes[i] = o->section[i];
        section_slide(&p->planes[i], size * (0.5 * k / (n > 1 ? n - 1 : 1) - 0.25));
    }
}

static void set_view(Scene *s, const Options *o, int k, int n)
{
    s->cam.yaw = deg2rad(o->yaw + 360.0f * k / n + 17.0f);
    s->cam.pitch = deg2rad(o->pitch + 25.0f * ((k % 3) - 1));
    s->cam.roll = deg2rad(o->roll);
}

typedef struct {
    const char *algos[16];
    int         n;
} AlgoList;

static int parse_algos(const char *spec, AlgoList *l)
{
    l->n = 0;
    if (!spec || !strcmp(spec, "all")) {
        for (int i = 0; i < hsr_nalgos && i < 16; i++)
            l->algos[l->n++] = hsr_algos[i]->name;
        return 0;
    }
    char buf[256], *save = NULL;
    snprintf(buf, sizeof buf, "%s", spec);
    for (char *t = strtok_r(buf, ",", &save); t && l->n < 16; t = strtok_r(NULL, ",", &save)) {
        const HsrAlgo *a = hsr_find(t);
        if (!a) {
            safetext_line(stderr, "zview: unknown algorithm '%s'", t);
            return -1;
        }
        l->algos[l->n++] = a->name;   /* the registry's string outlives buf */
    }
    return l->n ? 0 : -1;
}

/* The rows so far went out, or a message says why not. */
static int report_ok(Out *out)
{
    if (out_flush(out) == 0)
        return 1;
    safetext_line(stderr, "zview: %s: %s", out->name, out_error(out));
    return 0;
}

static int bench_model(Out *out, const Options *o, const char *file, const AlgoList *al, int *first_json)
{
    char err[512];
    Options one = *o;
    one.nfiles = file ? 1 : 0;
    one.files[0] = file;
    Scene s;
    if (app_load_scene(&one, &s, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    const char *name = file ? file : app_demo_path();
    const char *base = strrchr(name, '/');
    base = base ? base + 1 : name;
    char raw[128], label[4 * sizeof raw], jlabel[6 * sizeof raw];
    if (o->grid > 1)
        snprintf(raw, sizeof raw, "%s x%d^3", base, o->grid);
    else
        snprintf(raw, sizeof raw, "%s", base);
    /* the file's name made safe: as text for the table, escaped for JSON */
    safetext(label, sizeof label, raw);
    size_t jn = 0;
    for (const char *c = raw; *c;) {
        char piece[SAFETEXT_PIECE];
        c += safetext_next(c, piece, SAFETEXT_JSON);
        jn += (size_t)snprintf(jlabel + jn, sizeof jlabel - jn, "%s", piece);
    }
    jlabel[jn] = 0;
    int w = o->w > 0 ? o->w : 1920, h = o->h > 0 ? o->h : 1080;
    /* polygons of every object (grid copies share their source's lists) */
    uint64_t npolys = 0;
    for (int k = 0; k < s.nobjs; k++)
        npolys += s.objs[k].poly_count;
    int views = o->views < MAX_VIEWS ? o->views : MAX_VIEWS;
    double *hsr = malloc(sizeof(double) * views * 5);
    if (!hsr) {
        scene_free(&s);
        return 1;
    }
    double *frame = hsr + views, *proj = frame + views, *shade = proj + views, *cpu = shade + views;
    int rc = 0;
    for (int a = 0; a < al->n && !rc; a++) {
        Pipeline p;
        /* The first frame after choosing the algorithm, its structures
         * built (or started in the background) included: what switching
         * to it costs the viewer. Then frames until they are ready. */
        set_view(&s, o, 0, views);
        double t0 = now_ms();
        if (pipeline_init(&p, &s, hsr_find(al->algos[a]), o->threads)) {
            safetext_line(stderr, "zview: out of memory");
            rc = 1;
            break;
        }
        pipeline_apply_options(&p, o);
        pipeline_render(&p, w, h, 1.0f, o->cull, 1);
        double first = now_ms() - t0, ready = first;
        for (int k = 0; p.st.building && k < READY_FRAMES; k++) {
            pipeline_render(&p, w, h, 1.0f, o->cull, 1);
            ready = now_ms() - t0;
        }
        uint64_t culled = 0, given = 0, written = 0, covered = 0;
        for (int k = 0; k < views; k++) {
            set_view(&s, o, k, views);
            slide_planes(&p, o, &s, k, views);
            double t1 = now_ms(), c1 = process_cpu_ms();
            if (pipeline_render(&p, w, h, 1.0f, o->cull, 1)) {
                safetext_line(stderr, "zview: out of memory");
                rc = 1;
                break;
            }
            frame[k] = now_ms() - t1;
            cpu[k] = process_cpu_ms() - c1;
            hsr[k] = p.hsr_ms;
            proj[k] = p.project_ms;
            shade[k] = p.shade_ms;
            culled += p.st.polys_culled;
            given += p.st.polys_in;
            written += p.st.pixels_written;
            for (size_t i = 0; i < (size_t)p.fb.w * p.fb.h; i++)
                covered += p.fb.ids[i] >= 0;
        }
        if (rc) {
            pipeline_free(&p);
            break;
        }
        double hmin = hsr[0];
        for (int k = 1; k < views; k++)
            if (hsr[k] < hmin)
                hmin = hsr[k];
        double hmed = median(hsr, views), fmed = median(frame, views);
        double pmed = median(proj, views), smed = median(shade, views), cmed = median(cpu, views);
        double culled_pct = given ? 100.0 * culled / given : 0;
        double overdraw = covered ? (double)written / covered : 0;
        if (o->json) {
            out_printf(out, "%s\n  {\"model\": \"%s\", \"polygons\": %llu, \"algo\": \"%s\", \"width\": %d, "
                   "\"height\": %d, \"samples\": %d, \"threads\": %d, \"views\": %d, \"median_ms\": %.3f, "
                   "\"min_ms\": %.3f, \"project_median_ms\": %.3f, \"shade_median_ms\": %.3f, "
                   "\"frame_median_ms\": %.3f, \"cpu_median_ms\": %.3f, \"first_frame_ms\": %.3f, \"ready_ms\": %.3f, "
                   "\"culled_pct\": %.1f, \"overdraw\": %.2f}",
                   *first_json ? "" : ",", jlabel, (unsigned long long)npolys, al->algos[a], w, h, p.samples,
                   p.threads, views, hmed, hmin, pmed, smed, fmed, cmed, first, ready, culled_pct, overdraw);
            *first_json = 0;
        } else {
            char size[32];
            snprintf(size, sizeof size, "%dx%d%s", w, h, p.samples > 1 ? (p.samples == 4 ? "x4" : p.samples == 9 ? "x9" : "x16") : "");
            out_printf(out, "%-24s %9llu %-11s %-12s %2d %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.1f %8.1f %7.1f %8.2f\n", label,
                   (unsigned long long)npolys, al->algos[a], size, p.threads, pmed, hmed, hmin, smed, fmed, cmed, first,
                   ready, culled_pct, overdraw);
        }
        pipeline_free(&p);
        if (!report_ok(out))
            rc = 1;     /* nobody sees the rest: stop */
    }
    free(hsr);
    scene_free(&s);
    return rc;
}

int oneshot_bench(const Options *o, Scene *s)
{
    (void)s;   /* models are loaded one at a time */
    AlgoList al;
    if (parse_algos(o->algo, &al))
        return 2;
    Out out;
    out_init(&out, stdout, "standard output");
    int first = 1, rc = 0;
    if (o->json)
        out_printf(&out, "[");
    else
        out_printf(&out, "%-24s %9s %-11s %-12s %2s %8s %8s %8s %8s %8s %8s %8s %8s %7s %8s\n", "model", "polygons", "algo",
               "size", "th", "proj_ms", "hsr_ms", "hsr_min", "shade_ms", "frame_ms", "cpu_ms", "first_ms", "ready_ms",
               "culled%", "overdraw");
    if (!report_ok(&out))
        return 1;
    if (o->nfiles == 0)
        rc |= bench_model(&out, o, NULL, &al, &first);
    for (int i = 0; i < o->nfiles && !out.err; i++)
        rc |= bench_model(&out, o, o->files[i], &al, &first);
    if (out.err)
        return 1;       /* said already */
    if (o->json)
        out_printf(&out, "\n]\n");
    return report_ok(&out) ? rc : 1;
}
