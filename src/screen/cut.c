/* cut.c: the front end's share of a section (section.h). A polygon
 * with a corner on a plane's removed side is taken out of its chunk
 * and replaced in its place (its id, its map entry) by its kept part,
 * projected as the slow path projects a polygon, each point as pass 1
 * takes a vertex: where the kept part has the polygon's corners they
 * land on the same snapped points as its neighbours' do. A polygon on
 * the removed side of every plane is dropped. The screening before
 * this needs no change: the kept part lies inside the polygon, so a
 * polygon screened out for covering no sample keeps none either. The
 * caps follow every object's faces, with ids past the points' and
 * lines', and are drawn by every algorithm as any polygon. */

#include <stdlib.h>

#include "project.h"

uint32_t project_cut_split(const RangeJob *j, uint32_t k, uint32_t *keep, uint32_t nk, uint32_t *cutk,
                           uint32_t *ncut)
{
    const Scene *s = j->s;
    const uint8_t *m = j->cmask;
    uint32_t kept = 0, nc = 0;
    for (uint32_t i = 0; i < nk; i++) {
        uint32_t q = k + (keep[i] & ~KEEP_HIT), c0 = scene_poly_c0(s, q), c1 = scene_poly_c0(s, q + 1);
        uint8_t any = 0;
        for (uint32_t c = c0; c < c1; c++)
            any |= m[s->poly_corner[c]];
        if (any)
            cutk[nc++] = keep[i] & ~KEEP_HIT;
        else
            keep[kept++] = keep[i];
    }
    *ncut = nc;
    return kept;
}

/* Room for n corners in the worker's cut scratch. */
static int corner_room(ClipBuf *cb, uint32_t n)
{
    if (n <= cb->ccap)
        return 0;
    float *p = realloc(cb->cpts, (size_t)n * 3 * sizeof *p);
    if (p)
        cb->cpts = p;
    uint8_t *m = realloc(cb->cmask, n);
    if (m)
        cb->cmask = m;
    if (!p || !m)
        return -1;
    cb->ccap = n;
    return 0;
}

int project_emit_cut(RangeJob *j, uint32_t k, uint32_t c0, uint32_t c1, uint32_t inst)
{
    ScreenPolys *sp = j->out;
    const SectionCut *cut = j->cut;
    ClipBuf *cb = j->cb;
    uint32_t n = c1 - c0;
    if (corner_room(cb, n))
        return -1;
    uint8_t all = section_all(cut), both = all;
    const float *pos = j->o->mesh->pos;
    for (uint32_t c = 0; c < n; c++) {
        uint32_t v = j->s->poly_corner[c0 + c];
        for (int a = 0; a < 3; a++)
            cb->cpts[3 * c + a] = pos[3 * (size_t)v + a];
        cb->cmask[c] = j->cmask[v];
        both &= j->cmask[v];
    }
    if (both == all) {          /* wholly on the removed side */
        sp->culled_empty++;
        return 0;
    }
    int m = section_clip_poly(cut->plane, cut->nplanes, cb->cpts, cb->cmask, n, &cb->sec);
    if (m < 0)
        return -1;
    if (m < 3) {
        sp->culled_empty++;
        return 0;
    }
    uint32_t first = sp->nverts;
    int rv = project_clip_points(j, cb->sec.pts, (uint32_t)m);
    if (rv > 0)
        return 0;               /* too many corners to clip: dropped */
    if (rv)
        return rv;
    if (project_finish(sp, first))
        kept_poly(j, k, inst);
    else
        sp->nverts = first;
    return 0;
}

int project_caps(ScreenPolys *sp, const Scene *s, const Proj *pj, ClipBuf *cb)
{
    const SectionCut *cut = sp->cut;
    int np = cut->nplanes;
    int64_t id0 = section_cap_id0(s);
    if (id0 + (int64_t)s->nobjs * np > INT32_MAX)
        return 0;               /* no ids left for them */
    Mat4 view = camera_view(&s->cam);
    for (int oi = 0; oi < s->nobjs; oi++) {
        if (!cut->touched[oi])
            continue;
        const Object *o = &s->objs[oi];
        Mat4 mv = m4_mul(view, object_matrix(o));
        RangeJob j = { .out = sp, .s = s, .o = o, .pj = pj, .mv = &mv, .cb = cb, .cut = cut };
        for (int i = 0; i < np; i++) {
            const SectionClip *cap = &cut->cap[oi * np + i];
            if (cap->npts < 3)
                continue;
            if (grow_array((void **)&sp->polys, &sp->cap_polys, sp->npolys + 2, sizeof *sp->polys))
                return -1;
            uint32_t first = sp->nverts;
            int rv = project_clip_points(&j, cap->pts, cap->npts);
            if (rv > 0)
                continue;
            if (rv)
                return -1;
            if (project_finish(sp, first))
                sp->polys[sp->npolys - 1].face = (int32_t)(id0 + (int64_t)oi * np + i);
            else
                sp->nverts = first;
        }
    }
    return 0;
}
