/* diffcolour.c: a diff in colour, through the shading every picture
 * goes through: the colours are written in the diff scene's own arrays
 * (each face's colour and surface kind, each mesh vertex's colour), and
 * shading draws them as it draws any model's, so every algorithm gives
 * the same ids and the same picture. A face within the tolerance is the
 * model's grey; a face farther is A's red or B's green, one colour for
 * the face; a face whose corners lie on both sides of the tolerance is
 * coloured per pixel, its corners' colours (grey or red or green)
 * interpolated across it (texel.c's vertex colours). The heat map
 * colours every corner by its distance on a ramp of rising lightness
 * (in OKLab: B. Ottosson, "A perceptual color space for image
 * processing", 2020), 0 dark blue, the largest distance light yellow,
 * interpolated across each face. Showing one model leaves the other's
 * objects without polygons (their counts kept in the DiffSet), so
 * nothing of it is drawn and nothing of it hides the other. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diff.h"

static const uint8_t removed_rgb[3] = { 225, 45, 45 };     /* A's surface far from B: red */
static const uint8_t added_rgb[3] = { 40, 190, 75 };       /* B's surface far from A: green */

/* ==== The ramp ==== */

static double srgb_encode(double x)
{
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
}

void diff_ramp(double t, uint8_t rgb_out[3])
{
    t = !(t > 0) ? 0 : t > 1 ? 1 : t;
    /* OKLCh: lightness 0.45 to 0.95 evenly, hue from blue (265 degrees)
     * down through teal and green to yellow (100), chroma a little
     * lower at the dark end, where sRGB holds less */
    double L = 0.45 + 0.5 * t, C = 0.1 + 0.05 * t, h = (265 - 165 * t) * (3.14159265358979323846 / 180);
    double a = C * cos(h), b = C * sin(h);
    /* OKLab to linear sRGB (Ottosson's matrices) */
    double l_ = L + 0.3963377774 * a + 0.2158037573 * b;
    double m_ = L - 0.1055613458 * a - 0.0638541728 * b;
    double s_ = L - 0.0894841775 * a - 1.2914855480 * b;
    double l = l_ * l_ * l_, m = m_ * m_ * m_, s = s_ * s_ * s_;
    double rgb[3] = { 4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s,
                      -1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s,
                      -0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s };
    for (int k = 0; k < 3; k++)
        rgb_out[k] = (uint8_t)(srgb_encode(rgb[k]) * 255 + 0.5);
}

/* ==== The colours ==== */

typedef struct {
    const DiffSide *side;
    int             b;          /* the side is B's */
    int             heat;
    double          tol, scale; /* the heat map's 1 */
} Colouring;

static void vert_colour(const Colouring *c, uint32_t v, uint8_t rgb[3])
{
    double d = c->side->vert_dist[v];
    if (c->heat)
        diff_ramp(d / c->scale, rgb);
    else
        memcpy(rgb, d > c->tol ? (c->b ? added_rgb : removed_rgb) : scene_default_rgb, 3);
}

static void face_colour(const Colouring *c, uint32_t f, uint8_t rgb[3], uint16_t *surf)
{
    if (c->heat) {
        diff_ramp(c->side->face_dist[f] / c->scale, rgb);
        *surf = SURF_VCOLOUR;
        return;
    }
    int k = c->side->face_class[f];
    const uint8_t *far = c->b ? added_rgb : removed_rgb;
    if (k == DIFF_STRADDLE) {
        for (int i = 0; i < 3; i++)     /* its one colour (where one is read): half way */
            rgb[i] = (uint8_t)((far[i] + scene_default_rgb[i] + 1) / 2);
        *surf = SURF_VCOLOUR;
        return;
    }
    memcpy(rgb, k == DIFF_OVER ? far : scene_default_rgb, 3);
    *surf = SURF_PLAIN;
}

/* The arrays the colours go in, made where the scene has none. */
static int arrays(Scene *s)
{
    size_t nf = s->nfaces ? s->nfaces : 1;
    if (!s->face_rgb && !(s->face_rgb = malloc(3 * nf + 1)))
        return -1;
    if (!s->face_surf && !(s->face_surf = malloc(nf * sizeof *s->face_surf)))
        return -1;
    for (int i = 0; i < s->nmeshes; i++) {
        Mesh *m = &s->meshes[i];
        if (!m->rgb && !(m->rgb = malloc(3 * (size_t)(m->nverts ? m->nverts : 1) * sizeof *m->rgb)))
            return -1;
    }
    return 0;
}

int diff_show(DiffSet *ds, Pipeline *p, int show)
{
    Scene *s = &ds->scene;
    if (!ds->has_scene || s->nmeshes != 2)
        return 0;
    if (p && pipeline_scene_changing(p))
        return -1;
    if (arrays(s))
        return -1;
    show = show >= 0 && show < DIFF_SHOW_COUNT ? show : DIFF_SHOW_BOTH;
    double scale = ds->d.hausdorff > 0 ? ds->d.hausdorff : 1;
    for (int i = 0; i < 2; i++) {
        Colouring c = { i ? &ds->d.b : &ds->d.a, i, show == DIFF_SHOW_HEAT, ds->d.tolerance, scale };
        Mesh *m = &s->meshes[i];
        for (uint32_t v = 0; v < m->nverts && v < c.side->nverts; v++) {
            uint8_t rgb[3];
            vert_colour(&c, v, rgb);
            for (int k = 0; k < 3; k++)
                m->rgb[3 * (size_t)v + k] = rgb[k] / 255.0f;
        }
    }
    for (int i = 0; i < s->nobjs; i++) {
        Object *ob = &s->objs[i];
        int b = ob->mesh == &s->meshes[1];
        int hidden = (show == DIFF_SHOW_A && b) || (show == DIFF_SHOW_B && !b);
        ob->poly_count = hidden ? 0 : ds->obj_counts[3 * i];
        ob->point_count = hidden ? 0 : ds->obj_counts[3 * i + 1];
        ob->seg_count = hidden ? 0 : ds->obj_counts[3 * i + 2];
        Colouring c = { b ? &ds->d.b : &ds->d.a, b, show == DIFF_SHOW_HEAT, ds->d.tolerance, scale };
        for (uint32_t lf = 0; lf < ob->face_count; lf++) {
            uint32_t f = ob->face_first + lf, g = (uint32_t)ob->face_base + lf;
            if (f < c.side->nfaces && g < s->nfaces)
                face_colour(&c, f, &s->face_rgb[3 * (size_t)g], &s->face_surf[g]);
        }
    }
    s->gen++;
    ds->gen = s->gen;
    ds->show = show;
    return 0;
}

/* ==== In words ==== */

void diff_length(const DiffSet *ds, double v, char *buf, size_t len)
{
    int unit = ds->unit[0][0] && !strcmp(ds->unit[0], ds->unit[1]);
    snprintf(buf, len, "%.3g%s%s", v, unit ? " " : "", unit ? ds->unit[0] : "");
}

/* "no longer watertight (2 holes) · ", "now watertight · " or "". */
static void watertight_change(const DiffSet *ds, const char *sep, char *buf, size_t len)
{
    const CheckCounts *a = &ds->d.check[0], *b = &ds->d.check[1];
    buf[0] = 0;
    if (a->watertight && !b->watertight) {
        if (b->holes)
            snprintf(buf, len, "no longer watertight (%u hole%s)%s", b->holes, b->holes == 1 ? "" : "s", sep);
        else
            snprintf(buf, len, "no longer watertight (%u non-manifold edge%s)%s", b->nonmanifold_edges,
                     b->nonmanifold_edges == 1 ? "" : "s", sep);
    } else if (!a->watertight && b->watertight) {
        snprintf(buf, len, "now watertight%s", sep);
    }
}

void diff_headline(const DiffSet *ds, int brief, const char *sep, char *buf, size_t len)
{
    const Diff *d = &ds->d;
    if (brief) {
        if (diff_differ(d))
            snprintf(buf, len, "%u changed", d->nregions);
        else
            snprintf(buf, len, "same");
        return;
    }
    char pre[96], mx[48];
    watertight_change(ds, sep, pre, sizeof pre);
    diff_length(ds, d->hausdorff, mx, sizeof mx);
    if (!diff_differ(d))
        snprintf(buf, len, "%sthe same (max %s)", pre, mx);
    else
        snprintf(buf, len, "%smax %s%s%u region%s changed", pre, mx, sep, d->nregions, d->nregions == 1 ? "" : "s");
}

void diff_status(const DiffSet *ds, int brief, const char *sep, char *buf, size_t len)
{
    diff_headline(ds, brief, sep, buf, len);
    size_t n = strlen(buf);
    if (ds->show == DIFF_SHOW_HEAT && !brief && n + 1 < len) {
        char mx[48];
        diff_length(ds, ds->d.hausdorff, mx, sizeof mx);
        snprintf(buf + n, len - n, "%sheat: blue 0 to yellow %s", sep, mx);
    } else if (ds->show == DIFF_SHOW_A || ds->show == DIFF_SHOW_B) {
        snprintf(buf + n, len - n, "%s%s alone", sep, ds->show == DIFF_SHOW_A ? "A" : "B");
    }
}

int diff_report_lines(const DiffSet *ds, ReportLine *lines, int max)
{
    const Diff *d = &ds->d;
    char mx[48], t[48], ma[48], mb[48];
    diff_length(ds, d->hausdorff, mx, sizeof mx);
    diff_length(ds, d->tolerance, t, sizeof t);
    diff_length(ds, d->b.mean, mb, sizeof mb);
    diff_length(ds, d->a.mean, ma, sizeof ma);
    int n = 0;
    if (n < max) {
        lines[n].label = "diff:";
        snprintf(lines[n++].text, REPORT_TEXT, "max %s, tolerance %s, mean B to A %s, A to B %s", mx, t, mb, ma);
    }
    if (n < max) {
        lines[n].label = "changed:";
        snprintf(lines[n++].text, REPORT_TEXT, "%u region%s, area added %.6g, removed %.6g", d->nregions,
                 d->nregions == 1 ? "" : "s", d->b.area_over, d->a.area_over);
    }
    for (int i = 0; i < 2 && n < max; i++) {
        char words[REPORT_TEXT - 16];
        meshcheck_verdict(&d->check[i], words, sizeof words);
        lines[n].label = i ? "B:" : "A:";
        snprintf(lines[n++].text, REPORT_TEXT, "%u faces, %s", d->check[i].faces,
                 d->check[i].watertight && !strcmp(words, "sound") ? "watertight" : words);
    }
    return n;
}
