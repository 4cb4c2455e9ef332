/* printreport.c: will it print, in --check's report (printq.h): the
 * unit, the fit on a bed, the overhangs, the walls' thickness. Worked
 * out per file while checkreport.c holds its mesh, then written as
 * lines of the text report and members of the file's JSON. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oneshot.h"

int print_figures_run(const Options *o, const Mesh *m, const CheckCounts *c, PrintFigures *pf, char *err,
                      size_t errlen)
{
    memset(pf, 0, sizeof *pf);
    pf->fit = -1;
    int up = o->up >= 0 ? o->up : m->info.up;
    double size[3] = { 0, 0, 0 };
    if (c->faces)
        for (int k = 0; k < 3; k++)
            size[k] = (double)c->hi[k] - c->lo[k];
    if (o->unit)
        snprintf(pf->unit_given, sizeof pf->unit_given, "%s", o->unit);
    else if (!m->info.unit[0] && c->faces)
        pf->unit_guess = printq_unit_guess(size);
    if (o->bed[0] > 0 && c->faces) {
        pf->has_bed = 1;
        memcpy(pf->bed, o->bed, sizeof pf->bed);
        printq_bed_orders(up, &pf->orders);
        pf->fit = printq_bed_fit(size, pf->bed, &pf->orders, pf->fits);
    }
    if (o->overhang) {
        pf->has_overhang = 1;
        pf->overhang_deg = o->overhang_deg;
        pf->overhang_area = printq_overhang(m, up, o->overhang_deg, NULL);
    }
    if (o->thickness || o->min_thickness > 0) {
        int threads = o->threads > 0 ? o->threads : default_threads();
        if (printq_thickness(m, threads, &pf->thick, err, errlen))
            return -1;
        pf->has_thickness = 1;
        pf->thin_limit = o->min_thickness;
        if (o->min_thickness > 0)
            pf->thin_area = printq_thin_area(m, &pf->thick, o->min_thickness);
        free(pf->thick.face);           /* the summary is what the report says */
        pf->thick.face = NULL;
    }
    return 0;
}

/* ==== Text ==== */

static const char *const order_how[PRINTQ_ORDERS] = {
    "as it stands", "turned a quarter about the vertical", "on a side", "on a side", "on a side", "on a side",
};

void print_figures_text(Out *out, const PrintFigures *pf, const char *unit, const char *ind)
{
    char u[48];
    snprintf(u, sizeof u, "%s%s", unit[0] ? " " : "", unit);
    if (pf->unit_given[0])
        out_printf(out, "%s%-14s%s (--unit %s), the figures in mm\n", ind, "unit", printq_unit_words(pf->unit_given),
                   pf->unit_given);
    else if (pf->unit_guess)
        out_printf(out, "%s%-14snone stated; the size suggests %s (--unit %s takes them so)\n", ind, "unit",
                   printq_unit_words(pf->unit_guess), pf->unit_guess);
    if (pf->has_bed) {
        char axes[16];
        out_printf(out, "%s%-14s%g x %g x %g%s: ", ind, "bed", pf->bed[0], pf->bed[1], pf->bed[2], u);
        if (pf->fit < 0) {
            out_printf(out, "does not fit in any order of its axes\n");
        } else {
            printq_order_words(pf->orders.axis[pf->fit], axes, sizeof axes);
            out_printf(out, "fits %s (%s along the bed's W D H)", order_how[pf->fit], axes);
            int others = 0;
            for (int k = pf->fit + 1; k < PRINTQ_ORDERS; k++)
                others += pf->fits[k];
            out_printf(out, others ? "; %d other order%s too\n" : "\n", others, others == 1 ? "" : "s");
        }
    }
    if (pf->has_overhang)
        out_printf(out, "%s%-14s%g%s%s of faces past %g degrees from the vertical\n", ind, "overhang",
                   pf->overhang_area, u, unit[0] ? "^2" : "", pf->overhang_deg);
    if (pf->has_thickness) {
        const PrintqThickness *t = &pf->thick;
        if (!t->measured) {
            out_printf(out, "%s%-14snone measured: no face's inward ray meets the surface\n", ind, "thickness");
            return;
        }
        out_printf(out, "%s%-14sthinnest %g%s at %g %g %g (face %u), median %g; %u of %u faces measured\n", ind,
                   "thickness", t->min, u, t->min_at[0], t->min_at[1], t->min_at[2], t->min_face + 1, t->median,
                   t->measured, t->nfaces);
        if (pf->thin_limit > 0)
            out_printf(out, "%s%-14s%g%s%s thinner than %g\n", ind, "thin walls", pf->thin_area, u,
                       unit[0] ? "^2" : "", pf->thin_limit);
    }
}

/* ==== JSON ==== */

void print_figures_json(Out *out, const PrintFigures *pf, const char *ind)
{
    out_printf(out, ",\n%s\"unit_given\": ", ind);
    if (pf->unit_given[0])
        oneshot_json_str(out, pf->unit_given);
    else
        out_printf(out, "null");
    out_printf(out, ",\n%s\"unit_guess\": ", ind);
    if (pf->unit_guess)
        oneshot_json_str(out, pf->unit_guess);
    else
        out_printf(out, "null");
    if (pf->has_bed) {
        char axes[16];
        out_printf(out, ",\n%s\"bed\": {\"size\": [%.9g, %.9g, %.9g], \"fits\": %s, \"orders\": [", ind, pf->bed[0],
                   pf->bed[1], pf->bed[2], pf->fit >= 0 ? "true" : "false");
        for (int k = 0; k < PRINTQ_ORDERS; k++) {
            printq_order_words(pf->orders.axis[k], axes, sizeof axes);
            out_printf(out, "%s{\"axes\": \"%s\", \"fits\": %s}", k ? ", " : "", axes, pf->fits[k] ? "true" : "false");
        }
        out_printf(out, "]}");
    }
    if (pf->has_overhang)
        out_printf(out, ",\n%s\"overhang\": {\"degrees\": %.9g, \"area\": %.9g}", ind, pf->overhang_deg,
                   pf->overhang_area);
    if (pf->has_thickness) {
        const PrintqThickness *t = &pf->thick;
        out_printf(out, ",\n%s\"thickness\": {\"faces\": %u, \"measured\": %u", ind, t->nfaces, t->measured);
        if (t->measured)
            out_printf(out, ", \"min\": %.9g, \"min_at\": [%.9g, %.9g, %.9g], \"min_face\": %u, \"median\": %.9g",
                       t->min, t->min_at[0], t->min_at[1], t->min_at[2], t->min_face + 1, t->median);
        else
            out_printf(out, ", \"min\": null, \"min_at\": null, \"min_face\": null, \"median\": null");
        if (pf->thin_limit > 0)
            out_printf(out, ", \"thinner_than\": %.9g, \"thin_area\": %.9g", pf->thin_limit, pf->thin_area);
        out_printf(out, "}");
    }
}
