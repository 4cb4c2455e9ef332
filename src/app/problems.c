/* problems.c: the check of a scene's files, for the picture (--problems,
 * --parts, the viewer's ! key, --watch): each file as the scene holds it
 * (scene_check_meshes) checked with the lists an overlay draws, the
 * files' figures summed, the verdict in a word or two for the status bar
 * and the counts for the info panel. The report of --check is
 * oneshot/check.c's. */

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

/* The files' figures together, as check.c sums a file's objects. */
static void sum_files(SceneCheck *sc)
{
    CheckCounts *a = &sc->all;
    memset(a, 0, sizeof *a);
    int any = 0;
    a->closed = a->watertight = a->has_volume = a->intersections_tested = 1;
    for (int i = 0; i < sc->nfiles; i++) {
        const CheckCounts *c = &sc->files[i].file;
        a->vertices += c->vertices;
        a->unused_vertices += c->unused_vertices;
        if (!c->faces)
            continue;
        a->faces += c->faces;
        a->components += c->components;
        a->boundary_edges += c->boundary_edges;
        a->holes += c->holes;
        a->nonmanifold_edges += c->nonmanifold_edges;
        a->nonmanifold_vertices += c->nonmanifold_vertices;
        a->inconsistent_faces += c->inconsistent_faces;
        a->nonorientable += c->nonorientable;
        a->degenerate_faces += c->degenerate_faces;
        a->duplicate_faces += c->duplicate_faces;
        a->self_intersections += c->self_intersections;
        a->intersections_tested &= c->intersections_tested;
        a->intersections_stopped |= c->intersections_stopped;
        a->pair_tests += c->pair_tests;
        a->pair_budget += c->pair_budget;
        a->closed &= c->closed;
        a->watertight &= c->watertight;
        a->has_volume &= c->has_volume;
        a->inside_out |= c->inside_out;
        a->area += c->area;
        a->volume += c->volume;
        any = 1;
    }
    if (!any)
        a->closed = a->watertight = a->has_volume = a->intersections_tested = 0;
}

int app_check_meshes(const Mesh *m, int n, int threads, const int *cancel, SceneCheck *out, char *err,
                     size_t errlen)
{
    memset(out, 0, sizeof *out);
    out->files = calloc(n > 0 ? (size_t)n : 1, sizeof *out->files);
    if (!out->files) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    CheckOpts co = { .threads = threads > 0 ? threads : default_threads(), .intersections = 1, .detail = 1,
                     .cancel = cancel };
    for (int i = 0; i < n; i++) {
        if (meshcheck_run(&out->files[i], &m[i], &co, err, errlen)) {
            scene_check_free(out);
            return -1;
        }
        out->nfiles = i + 1;
    }
    out->nfiles = n;
    sum_files(out);
    return 0;
}

void scene_check_free(SceneCheck *sc)
{
    for (int i = 0; sc->files && i < sc->nfiles; i++)
        meshcheck_free(&sc->files[i]);
    free(sc->files);
    memset(sc, 0, sizeof *sc);
}

int app_check_scene(Scene *s, int threads, char *err, size_t errlen)
{
    Mesh *m;
    int n;
    if (scene_check_meshes(s, &m, &n, err, errlen))
        return -1;
    SceneCheck sc;
    int rc = app_check_meshes(m, n, threads, NULL, &sc, err, errlen);
    scene_check_meshes_free(m, n);
    if (rc)
        return -1;
    rc = scene_marks_set(s, sc.files, sc.nfiles, err, errlen);
    scene_check_free(&sc);
    return rc;
}

/* ==== In words ==== */

static void add(char *buf, size_t len, const char *sep, const char *fmt, unsigned long long n)
{
    size_t o = strlen(buf);
    if (o + 1 >= len)
        return;
    if (o)
        snprintf(buf + o, len - o, "%s", sep);
    o = strlen(buf);
    snprintf(buf + o, len - o, fmt, n);
}

/* Append item k of the verdict unless max items are in already; count
 * it either way. */
static void item(char *buf, size_t len, const char *sep, int *k, int max, const char *fmt, unsigned long long n)
{
    if ((*k)++ < max)
        add(buf, len, sep, fmt, n);
}

int check_verdict_items(const CheckCounts *c, const char *sep, int max, char *buf, size_t len)
{
    buf[0] = 0;
    int k = 0;
    if (!c->faces) {
        snprintf(buf, len, "no faces");
        return 1;
    }
    if (c->boundary_edges)
        item(buf, len, sep, &k, max, c->holes == 1 ? "%llu hole" : "%llu holes", c->holes);
    if (c->nonmanifold_edges)
        item(buf, len, sep, &k, max, "%llu non-manifold", c->nonmanifold_edges);
    if (c->nonmanifold_vertices)
        item(buf, len, sep, &k, max,
             c->nonmanifold_vertices == 1 ? "%llu pinched vertex" : "%llu pinched vertices",
             c->nonmanifold_vertices);
    if (c->nonorientable)
        item(buf, len, sep, &k, max, "%llu non-orientable", c->nonorientable);
    if (c->inconsistent_faces)
        item(buf, len, sep, &k, max, "%llu flipped", c->inconsistent_faces);
    if (c->inside_out)
        item(buf, len, sep, &k, max, "inside out", 0);
    if (c->intersections_stopped)      /* a lower bound: the test stopped */
        item(buf, len, sep, &k, max, "%llu+ crossing", c->self_intersections);
    else if (c->self_intersections)
        item(buf, len, sep, &k, max, "%llu crossing", c->self_intersections);
    if (c->degenerate_faces)
        item(buf, len, sep, &k, max, "%llu degenerate", c->degenerate_faces);
    if (c->duplicate_faces)
        item(buf, len, sep, &k, max, "%llu duplicate", c->duplicate_faces);
    if (k > max)        /* the rest as a count: "6 holes · +3" */
        add(buf, len, sep, max > 0 ? "+%llu" : "%llu problems", (unsigned long long)(k - max));
    if (!k)
        snprintf(buf, len, "watertight");
    return k;
}

int check_verdict_short(const CheckCounts *c, const char *sep, char *buf, size_t len)
{
    return check_verdict_items(c, sep, INT_MAX, buf, len);
}

int check_report(const SceneCheck *sc, ReportLine *lines, int max)
{
    const CheckCounts *c = &sc->all;
    int n = 0;
    if (n < max) {
        lines[n].label = "check:";
        char words[REPORT_TEXT - 32];
        meshcheck_verdict(c, words, sizeof words);
        snprintf(lines[n++].text, REPORT_TEXT, "%s", words);
    }
    if (n < max) {
        lines[n].label = "parts:";
        snprintf(lines[n++].text, REPORT_TEXT, "%u, %u faces, %u vertices (%u unused)", c->components, c->faces,
                 c->vertices, c->unused_vertices);
    }
    if (n < max) {
        lines[n].label = "edges:";
        snprintf(lines[n++].text, REPORT_TEXT, "%u boundary in %u hole%s, %u non-manifold, %u non-manifold vertices",
                 c->boundary_edges, c->holes, c->holes == 1 ? "" : "s", c->nonmanifold_edges,
                 c->nonmanifold_vertices);
    }
    if (n < max) {
        lines[n].label = "faces:";
        snprintf(lines[n++].text, REPORT_TEXT, "%u flipped%s, %s%llu crossing pairs, %u degenerate, %u duplicate",
                 c->inconsistent_faces, c->inside_out ? ", inside out" : "",
                 c->intersections_stopped ? "at least " : "", (unsigned long long)c->self_intersections,
                 c->degenerate_faces, c->duplicate_faces);
    }
    if (n < max) {
        lines[n].label = "volume:";
        if (c->has_volume)
            snprintf(lines[n++].text, REPORT_TEXT, "%g, area %g", c->volume, c->area);
        else
            snprintf(lines[n++].text, REPORT_TEXT, "none (%s), area %g", c->closed ? "not orientable" : "not closed",
                     c->area);
    }
    return n;
}
