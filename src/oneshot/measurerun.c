/* measurerun.c: zview FILE --measure A B [C]: the model loaded (as
 * --check loads it: positions and faces, --unit applied), the points
 * given as vertices looked up, and the figures printed: each point, the
 * distance and dx, dy, dz from A to B, and with C the distance B to C
 * and the angle at B. --json prints them as one JSON document. */

#include <stdio.h>
#include <string.h>

#include "oneshot.h"
#include "safetext.h"

static void text_report(Out *out, const Options *o, const PrintqMeasure *r, const char *unit)
{
    char u[48];
    snprintf(u, sizeof u, "%s%s", unit[0] ? " " : "", unit);
    for (int i = 0; i < o->nmeasure; i++) {
        const PrintqPoint *p = &o->measure[i];
        out_printf(out, "%c             %.9g %.9g %.9g", 'A' + i, p->p[0], p->p[1], p->p[2]);
        if (p->vertex)
            out_printf(out, " (v%u)", p->vertex);
        out_printf(out, "\n");
    }
    out_printf(out, "distance AB    %.9g%s\n", r->dist, u);
    out_printf(out, "dx dy dz       %.9g %.9g %.9g\n", r->d[0], r->d[1], r->d[2]);
    if (o->nmeasure == 3) {
        out_printf(out, "distance BC    %.9g%s\n", r->dist2, u);
        out_printf(out, "angle ABC      %.9g degrees\n", r->angle);
    }
}

static void json_report(Out *out, const Options *o, const PrintqMeasure *r, const char *unit)
{
    out_printf(out, "{\n  \"unit\": ");
    if (unit[0])
        oneshot_json_str(out, unit);
    else
        out_printf(out, "null");
    out_printf(out, ",\n  \"points\": [");
    for (int i = 0; i < o->nmeasure; i++) {
        const PrintqPoint *p = &o->measure[i];
        out_printf(out, "%s\n    {\"at\": [%.9g, %.9g, %.9g], \"vertex\": ", i ? "," : "", p->p[0], p->p[1], p->p[2]);
        out_printf(out, p->vertex ? "%u}" : "null}", p->vertex);
    }
    out_printf(out, "\n  ],\n  \"distance\": %.9g,\n  \"delta\": [%.9g, %.9g, %.9g]", r->dist, r->d[0], r->d[1],
               r->d[2]);
    if (o->nmeasure == 3)
        out_printf(out, ",\n  \"distance_bc\": %.9g,\n  \"angle\": %.9g", r->dist2, r->angle);
    out_printf(out, "\n}\n");
}

int oneshot_measure(const Options *o)
{
    char err[512];
    MeshLoadOpts lo = app_load_opts(o);
    lo.no_textures = 1;
    SandboxOpts so = app_sandbox_opts(o);
    Mesh m;
    if (sandbox_load(&m, o->files[0], &lo, &so, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    app_after_load(o, &m);
    Options mo = *o;            /* the points, their vertices filled in */
    if (printq_points_resolve(&m, mo.measure, mo.nmeasure, err, sizeof err)) {
        safetext_line(stderr, "zview: %s: %s", o->files[0], err);
        mesh_free(&m);
        return 2;
    }
    /* numbers given are in the file's units; with --unit, in mm as the vertices are */
    char unit[4 * sizeof m.info.unit];
    safetext(unit, sizeof unit, m.info.unit);
    mesh_free(&m);
    PrintqMeasure r;
    printq_measure(mo.measure, mo.nmeasure, &r);
    Out out;
    out_init(&out, stdout, "standard output");
    if (o->json)
        json_report(&out, &mo, &r, unit);
    else
        text_report(&out, &mo, &r, unit);
    if (out_flush(&out)) {
        safetext_line(stderr, "zview: standard output: %s", out_error(&out));
        return 1;
    }
    return 0;
}
