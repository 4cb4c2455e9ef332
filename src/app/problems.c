/* problems.c: the check of a scene's files, for the picture (--problems,
 * --parts, the viewer's ! key, --watch): each file as the scene holds it
 * (scene_check_meshes) checked with the lists an overlay draws, the
 * files' figures summed (meshcheck_sum, as a file's objects), the
 * verdict in a word or two for the status bar and the counts for the
 * info panel. The report of --check is
 * oneshot/checkreport.c's. */

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

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
                     .locations = APP_CHECK_LOCATIONS, .cancel = cancel };
    for (int i = 0; i < n; i++) {
        if (meshcheck_run(&out->files[i], &m[i], &co, err, errlen)) {
            scene_check_free(out);
            return -1;
        }
        out->nfiles = i + 1;
        /* the problems as shapes, while the mesh's faces are at hand */
        if (meshcheck_items_add(&out->items, &out->files[i], &m[i], i)) {
            scene_check_free(out);
            snprintf(err, errlen, "out of memory");
            return -1;
        }
    }
    meshcheck_items_order(&out->items);
    out->nfiles = n;
    meshcheck_sum(&out->all, &out->files[0].file, (size_t)n, sizeof *out->files);   /* as a file's objects */
    return 0;
}

void scene_check_free(SceneCheck *sc)
{
    for (int i = 0; sc->files && i < sc->nfiles; i++)
        meshcheck_free(&sc->files[i]);
    free(sc->files);
    meshcheck_items_free(&sc->items);
    memset(sc, 0, sizeof *sc);
}

int app_check_scene(Scene *s, int threads, SceneCheck *keep, char *err, size_t errlen)
{
    Mesh *m;
    int n;
    if (keep)
        memset(keep, 0, sizeof *keep);
    if (scene_check_meshes(s, &m, &n, err, errlen))
        return -1;
    SceneCheck sc;
    int rc = app_check_meshes(m, n, threads, NULL, &sc, err, errlen);
    scene_check_meshes_free(m, n);
    if (rc)
        return -1;
    rc = scene_marks_set(s, sc.files, sc.nfiles, err, errlen);
    if (rc == 0 && keep) {
        /* the items and the figures; the files' lists are the marks' now */
        keep->all = sc.all;
        keep->items = sc.items;
        memset(&sc.items, 0, sizeof sc.items);
    }
    scene_check_free(&sc);
    return rc;
}

/* ==== In words ==== */

/* Append text to the verdict in buf, after sep unless it is the first. */
static void add(char *buf, size_t len, const char *sep, const char *text)
{
    size_t o = strlen(buf);
    if (o + 1 >= len)
        return;
    if (o)
        snprintf(buf + o, len - o, "%s", sep);
    o = strlen(buf);
    snprintf(buf + o, len - o, "%s", text);
}

/* The problems in the status bar's words and order (counts.c's rows);
 * past max, the rest as a count. */
int check_verdict_items(const CheckCounts *c, const char *sep, int max, char *buf, size_t len)
{
    buf[0] = 0;
    if (!c->faces) {
        snprintf(buf, len, "no faces");
        return 1;
    }
    char item[CHECK_PROBLEMS_MAX][CHECK_PROBLEM_LEN];
    int k = meshcheck_problems_as(c, CHECK_SAY_SHORT, item, CHECK_PROBLEMS_MAX);
    for (int i = 0; i < k && i < max && i < CHECK_PROBLEMS_MAX; i++)
        add(buf, len, sep, item[i]);
    if (k > max) {      /* the rest as a count: "6 holes · +3" */
        char rest[32];
        snprintf(rest, sizeof rest, max > 0 ? "+%d" : "%d problems", k - max);
        add(buf, len, sep, rest);
    }
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

/* ==== A problem in words ==== */

void check_item_words(const CheckItems *it, uint32_t i, const CheckCounts *all, const char *unit, double scale,
                      const char *sep, int brief, char *buf, size_t len)
{
    static const char *const name[CHECK_LOC_KINDS] = {
        [CHECK_LOC_HOLES] = "hole",
        [CHECK_LOC_NM_EDGES] = "non-manifold edge",
        [CHECK_LOC_NM_VERTICES] = "non-manifold vertex",
        [CHECK_LOC_FLIPPED] = "flipped face",
        [CHECK_LOC_DEGENERATE] = "degenerate face",
        [CHECK_LOC_DUPLICATE] = "duplicate face",
        [CHECK_LOC_CROSSING] = "crossing",
    };
    buf[0] = 0;
    if (i >= it->n)
        return;
    const CheckItem *e = &it->item[i];
    unsigned long long total = meshcheck_loc_total(all, e->kind);
    total = total > e->num ? total : e->num;
    if (brief) {
        snprintf(buf, len, "%s %u/%llu", name[e->kind], e->num, total);
        return;
    }
    int n = snprintf(buf, len, "%s %u of %llu", name[e->kind], e->num, total);
    size_t o = n > 0 && (size_t)n < len ? (size_t)n : len - 1;
    switch (e->kind) {
    case CHECK_LOC_HOLES:
        snprintf(buf + o, len - o, "%s%u edges%s%.3g%s%s", sep, e->count, sep, e->length * scale, unit[0] ? " " : "",
                 unit);
        break;
    case CHECK_LOC_NM_EDGES:
        snprintf(buf + o, len - o, "%s%u faces", sep, e->count);
        break;
    case CHECK_LOC_FLIPPED:
    case CHECK_LOC_DEGENERATE:
    case CHECK_LOC_DUPLICATE:
        snprintf(buf + o, len - o, "%sface %u", sep, e->face[0]);
        break;
    case CHECK_LOC_CROSSING:
        snprintf(buf + o, len - o, "%sfaces %u and %u", sep, e->face[0], e->face[1]);
        break;
    default:
        break;
    }
}
