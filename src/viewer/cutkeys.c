/* cutkeys.c: the section planes in the viewer (section.h): the keys
 * that cut, slide, turn and pick them, and their words in the status
 * bar. The planes live in the pipeline (Pipeline.planes), which makes
 * the cut again when they change. */

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "viewer_app.h"

/* The loaded objects' box in file units: centre and largest half side. */
static void model_box(const Scene *s, double centre[3], double *half)
{
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    int n = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    for (int i = 0; i < n && i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        double c[3] = { o->centre.x, o->centre.y, o->centre.z }, h[3] = { o->half.x, o->half.y, o->half.z };
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], ldexp(c[k] - h[k], s->pos_exp));
            hi[k] = fmax(hi[k], ldexp(c[k] + h[k], s->pos_exp));
        }
    }
    *half = 0;
    for (int k = 0; k < 3; k++) {
        int empty = !(hi[k] >= lo[k]);
        centre[k] = empty ? 0 : 0.5 * (lo[k] + hi[k]);
        *half = fmax(*half, empty ? 0 : 0.5 * (hi[k] - lo[k]));
    }
    if (!(*half > 0))
        *half = 1;
}

/* What the note says of the plane in use. */
static void say_plane(App *a, const char *what)
{
    char t[SECTION_TEXT];
    section_text(&a->p.planes[a->cut_plane], t, sizeof t);
    snprintf(a->note, sizeof a->note, "%s %s", what, t);
}

Reaction viewer_cut_toggle(App *a)
{
    Pipeline *p = &a->p;
    if (!p->nplanes) {
        double c[3], half;
        model_box(a->s, c, &half);
        p->planes[0] = section_axis_plane(2, 0, c[2]);
        p->nplanes = 1;
        p->cut_off = 0;
        a->cut_plane = 0;
        say_plane(a, "cut at");
        return RE_RENDER;
    }
    p->cut_off = !p->cut_off;
    if (p->cut_off)
        snprintf(a->note, sizeof a->note, "cut off (/ cuts again)");
    else
        say_plane(a, "cut at");
    return RE_RENDER;
}

Reaction viewer_cut_slide(App *a, int dir)
{
    Pipeline *p = &a->p;
    if (!p->nplanes)
        return viewer_cut_toggle(a);
    double c[3], half;
    model_box(a->s, c, &half);
    section_slide(&p->planes[a->cut_plane], dir * half / 25);
    p->cut_off = 0;
    say_plane(a, "cut at");
    return RE_RENDER;
}

Reaction viewer_cut_turn(App *a)
{
    Pipeline *p = &a->p;
    if (!p->nplanes)
        return viewer_cut_toggle(a);
    SectionPlane *pl = &p->planes[a->cut_plane];
    int axis = pl->axis >= 0 ? (pl->axis + 1) % 3 : 0;
    double c[3], half;
    model_box(a->s, c, &half);
    *pl = section_axis_plane(axis, 0, c[axis]);
    p->cut_off = 0;
    say_plane(a, "cut at");
    return RE_RENDER;
}

Reaction viewer_cut_next(App *a)
{
    Pipeline *p = &a->p;
    if (!p->nplanes)
        return viewer_cut_toggle(a);
    a->cut_plane = (a->cut_plane + 1) % p->nplanes;
    char t[32];
    snprintf(t, sizeof t, "plane %d/%d:", a->cut_plane + 1, p->nplanes);
    say_plane(a, t);
    return RE_DRAW;
}

void viewer_cut_status(const App *a, char *buf, size_t len, char *brief, size_t brief_len)
{
    const Pipeline *p = &a->p;
    buf[0] = brief[0] = 0;
    if (!p->nplanes)
        return;
    if (p->cut_off) {
        snprintf(buf, len, "cut off");
        return;
    }
    int i = a->cut_plane < p->nplanes ? a->cut_plane : 0;
    char t[SECTION_TEXT];
    section_text(&p->planes[i], t, sizeof t);
    SectionFigures f = { 0 };
    if (p->cut.key == a->s && p->cut.nplanes == p->nplanes)
        section_total(&p->cut, a->s, i, &f);
    snprintf(buf, len, "cut %s area %.4g%s", t, f.area, f.chains ? " (open)" : "");
    snprintf(brief, brief_len, "%s %.3g", t, f.area);
}
