/* seccut.c: a scene's cut. The planes' masks of every mesh's vertices
 * and every cut object's caps, made again only when the planes or the
 * scene change (sliding a plane remakes them: the masks are a compare a
 * vertex, the caps a look at each polygon's corners' masks and a
 * segment where a plane crosses). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "grow.h"
#include "section.h"

void section_cut_free(SectionCut *c)
{
    for (int m = 0; m < c->nmask; m++)
        free(c->mask[m]);
    free(c->mask);
    free(c->mask_room);
    for (int k = 0; k < c->ncap_room; k++)
        section_clip_free(&c->cap[k]);
    free(c->cap);
    free(c->fig);
    free(c->touched);
    section_work_free(&c->work);
    section_clip_free(&c->clip);
    memset(c, 0, sizeof *c);
}

static int same_planes(const SectionCut *c, const Scene *s, const SectionPlane *planes, int np)
{
    return c->key == s && c->key_gen == s->gen && c->key_np == np &&
           memcmp(c->key_plane, planes, (size_t)np * sizeof *planes) == 0;
}

/* The arrays for s's meshes and objects. */
static int cut_room(SectionCut *c, const Scene *s, int np)
{
    if (s->nmeshes > c->nmask) {
        uint8_t **m = realloc(c->mask, (size_t)s->nmeshes * sizeof *m);
        if (m)
            c->mask = m;
        uint32_t *r = realloc(c->mask_room, (size_t)s->nmeshes * sizeof *r);
        if (r)
            c->mask_room = r;
        if (!m || !r)
            return -1;
        for (int k = c->nmask; k < s->nmeshes; k++) {
            c->mask[k] = NULL;
            c->mask_room[k] = 0;
        }
        c->nmask = s->nmeshes;
    }
    for (int k = 0; k < s->nmeshes; k++)
        if (grow_array((void **)&c->mask[k], &c->mask_room[k], s->meshes[k].nverts + 1, 1))
            return -1;
    int ncap = s->nobjs * (np > 0 ? np : 1);
    if (ncap > c->ncap_room) {
        SectionClip *cp = realloc(c->cap, (size_t)ncap * sizeof *cp);
        if (cp)
            c->cap = cp;
        SectionFigures *f = realloc(c->fig, (size_t)ncap * sizeof *f);
        if (f)
            c->fig = f;
        if (!cp || !f)
            return -1;
        memset(c->cap + c->ncap_room, 0, (size_t)(ncap - c->ncap_room) * sizeof *cp);
        c->ncap_room = ncap;
    }
    if (s->nobjs > c->nobj_room) {
        uint8_t *t = realloc(c->touched, (size_t)s->nobjs);
        if (!t)
            return -1;
        c->touched = t;
        c->nobj_room = s->nobjs;
    }
    return 0;
}

/* A plane of file units in the meshes' units (scaled by 2^-pos_exp). */
static SectionPlane mesh_plane(const SectionPlane *pl, int pos_exp)
{
    SectionPlane m = *pl;
    for (int k = 0; k < 3; k++)
        m.q[k] = ldexp(m.q[k], -pos_exp);
    return m;
}

int section_cut_update(SectionCut *c, const Scene *s, const SectionPlane *planes, int np, char *err,
                       size_t errlen)
{
    if (np > SECTION_MAX)
        np = SECTION_MAX;
    if (same_planes(c, s, planes, np))
        return 0;
    double t0 = now_ms();
    c->key = NULL;
    c->nplanes = 0;
    if (cut_room(c, s, np)) {
        snprintf(err, errlen, "out of memory cutting the model");
        return -1;
    }
    for (int i = 0; i < np; i++)
        c->plane[i] = mesh_plane(&planes[i], s->pos_exp);
    c->nplanes = np;
    for (int m = 0; m < s->nmeshes; m++)
        section_masks(c->plane, np, s->meshes[m].pos, s->meshes[m].nverts, c->mask[m]);
    for (int oi = 0; oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        const uint8_t *mask = c->mask[o->mesh - s->meshes];
        uint8_t any = 0;
        /* faces, points and lines alike: the front end cuts all of them */
        for (uint32_t v = o->vert_min; np && o->mesh->nverts && v <= o->vert_max && v < o->mesh->nverts; v++)
            any |= mask[v];
        c->touched[oi] = any != 0;
        for (int i = 0; i < np; i++) {
            SectionClip *cap = &c->cap[oi * np + i];
            SectionFigures *fig = &c->fig[oi * np + i];
            cap->npts = 0;
            memset(fig, 0, sizeof *fig);
            if (!(any >> i & 1))
                continue;
            SectionPolys in = { o->mesh->pos, s->poly_start, s->poly_corner, o->poly_first, o->poly_count, mask };
            if (section_loops(&in, c->plane, np, i, &c->work, fig, cap)) {
                snprintf(err, errlen, "out of memory cutting the model");
                c->nplanes = 0;
                return -1;
            }
            fig->area = ldexp(fig->area, 2 * s->pos_exp);
            fig->perimeter = ldexp(fig->perimeter, s->pos_exp);
        }
    }
    c->key = s;
    c->key_gen = s->gen;
    c->key_np = np;
    if (np)
        memcpy(c->key_plane, planes, (size_t)np * sizeof *planes);
    c->ms = now_ms() - t0;
    return 0;
}

int section_cap_of(const SectionCut *c, const Scene *s, int32_t id, int *obj, int *plane)
{
    int64_t k = (int64_t)id - section_cap_id0(s);
    if (!c || c->nplanes <= 0 || id < 0 || k < 0 || k >= (int64_t)s->nobjs * c->nplanes)
        return 0;
    *obj = (int)(k / c->nplanes);
    *plane = (int)(k % c->nplanes);
    return 1;
}

void section_total(const SectionCut *c, const Scene *s, int i, SectionFigures *out)
{
    memset(out, 0, sizeof *out);
    uint32_t n = s->nbase_objs ? s->nbase_objs : (uint32_t)s->nobjs;
    for (uint32_t o = 0; i < c->nplanes && o < n && (int)o < s->nobjs; o++) {
        const SectionFigures *f = &c->fig[o * (uint32_t)c->nplanes + (uint32_t)i];
        out->area += f->area;
        out->perimeter += f->perimeter;
        out->loops += f->loops;
        out->chains += f->chains;
    }
}
