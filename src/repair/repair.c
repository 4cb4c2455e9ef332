/* repair.c: repair_mesh, the steps in order (include/repair.h).
 *
 * The order: weld, clean, then object by object the non-manifold
 * splits, the winding, the holes, and last the turn outward. The splits
 * come before the winding, because a fin's faces have no winding to
 * agree on until it is split, and before the holes, because a split can
 * open a boundary (a fin's odd face cut loose) that the holes then
 * fill, and a fill must not put a third face on an edge. The winding
 * comes before the holes so that each loop runs one way round and its
 * fill is wound to agree; the turn outward comes after them, because a
 * part is closed, and has an inside, only once its holes are filled.
 *
 * The repair works on copies of the arrays it changes (the positions,
 * colours, faces, corners, their texture coordinates and materials,
 * the objects, points and lines); on success they replace the mesh's,
 * on failure the mesh is as it was. What is left is counted by the
 * check itself (meshcheck_run) on the repaired mesh. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "meshcheck.h"
#include "repair_internal.h"

int rp_cancelled(const Rep *r)
{
    return r->opt->cancel && __atomic_load_n(r->opt->cancel, __ATOMIC_RELAXED);
}

/* ==== The working copy ==== */

/* A copy of the first `bytes` of p in an array of `room` bytes. */
static void *dup_array(const void *p, size_t bytes, size_t room)
{
    void *q = rp_big(room > bytes ? room : bytes, 0);
    if (q && p && bytes)
        memcpy(q, p, bytes);
    return q;
}

/* The arrays the repair changes, copied; per-vertex texture coordinates
 * become the corners' (the vertices are renumbered and split). */
static int copy_in(Rep *r, const Mesh *m)
{
    Mesh *w = &r->w;
    *w = *m;
    w->pos = w->rgb = NULL;
    w->face_start = w->corner = w->corner_uv = w->point = w->line_corner = NULL;
    w->face_mat = NULL;
    w->objs = NULL;
    size_t nc = m->nfaces ? m->face_start[m->nfaces] : 0;
    r->vcap = m->nverts;
    r->nverts0 = m->nverts;
    /* the positions and colours are borrowed until they change */
    w->pos = m->pos;
    w->rgb = m->rgb;
    r->pos_borrowed = 1;
    size_t fs = ((size_t)m->nfaces + 1) * sizeof *m->face_start;
    w->face_start = dup_array(m->face_start, m->face_start ? fs : 0, fs);
    w->corner = dup_array(m->corner, nc * sizeof *m->corner, nc * sizeof *m->corner);
    w->objs = dup_array(m->objs, m->nobjs * sizeof *m->objs, m->nobjs * sizeof *m->objs);
    if (!w->face_start || !w->corner || !w->objs)
        return -1;
    if (!m->face_start)
        w->face_start[0] = 0;
    /* a loader's face_mat has nfaces entries, no more */
    if (m->face_mat &&
        !(w->face_mat = dup_array(m->face_mat, m->nfaces * sizeof *m->face_mat, ((size_t)m->nfaces + 1) * sizeof *m->face_mat)))
        return -1;
    if (m->point && !(w->point = dup_array(m->point, m->npoints * sizeof *m->point, m->npoints * sizeof *m->point)))
        return -1;
    size_t nl = m->nlines ? m->line_start[m->nlines] : 0;
    if (m->nlines && !(w->line_corner = dup_array(m->line_corner, nl * sizeof *m->line_corner, nl * sizeof *m->line_corner)))
        return -1;
    if (m->corner_uv) {
        if (!(w->corner_uv = dup_array(m->corner_uv, nc * sizeof *m->corner_uv, nc * sizeof *m->corner_uv)))
            return -1;
    } else if (m->uv) {
        if (!(w->corner_uv = rp_big(nc * sizeof *w->corner_uv, 0)))
            return -1;
        for (size_t c = 0; c < nc; c++)
            w->corner_uv[c] = m->corner[c] < m->nuv ? m->corner[c] : MESH_NO_UV;
    }
    return 0;
}

static void free_copy(Rep *r)
{
    Mesh *w = &r->w;
    if (!r->pos_borrowed) {
        free(w->pos);
        free(w->rgb);
    }
    free(w->face_start);
    free(w->corner);
    free(w->corner_uv);
    free(w->face_mat);
    free(w->objs);
    free(w->point);
    free(w->line_corner);
    free(r->pid);
    free(r->anchor);
    free(r->loc);
    rp_points_free(r);
}

/* The copy in place of the mesh's arrays. */
static void install(Rep *r, Mesh *m)
{
    Mesh *w = &r->w;
    if (!r->pos_borrowed) {
        free(m->pos);
        free(m->rgb);
    }
    free(m->face_start);
    free(m->corner);
    free(m->corner_uv);
    free(m->face_mat);
    free(m->objs);
    free(m->point);
    free(m->line_corner);
    m->pos = w->pos;
    m->rgb = w->rgb;
    m->nverts = w->nverts;
    m->face_start = w->face_start;
    m->corner = w->corner;
    m->corner_uv = w->corner_uv;
    m->face_mat = w->face_mat;
    m->nfaces = w->nfaces;
    m->objs = w->objs;
    m->point = w->point;
    m->line_corner = w->line_corner;
    uint64_t tris = 0;
    for (uint32_t f = 0; f < m->nfaces; f++)
        tris += m->face_start[f + 1] - m->face_start[f] - 2;
    m->info.triangles = tris > UINT32_MAX ? UINT32_MAX : (uint32_t)tris;
    memset(w, 0, sizeof *w);
    r->pos_borrowed = 0;
}

/* ==== Faces dropped and added ==== */

int rp_faces_rebuild(Rep *r, const uint8_t *drop, Fill *const *fills, const uint32_t *nfills)
{
    Mesh *w = &r->w;
    uint64_t addf = 0, addc = 0, nc = w->nfaces ? w->face_start[w->nfaces] : 0, gone = 0;
    int mats = w->face_mat != NULL;
    for (uint32_t i = 0; i < w->nobjs; i++)
        for (uint32_t k = 0; k < nfills[i]; k++) {
            addf += fills[i][k].ntri;
            mats |= fills[i][k].mat >= 0;
        }
    for (uint32_t f = 0; drop && f < w->nfaces; f++)
        gone += drop[f];
    if (!addf && !gone)
        return 0;
    addc = 3 * addf;
    if ((uint64_t)w->nfaces + addf >= UINT32_MAX - 1 || nc + addc >= UINT32_MAX - 1)
        return -1;
    uint32_t nf = w->nfaces + (uint32_t)addf;
    uint32_t *fs = rp_big(((size_t)nf + 1) * sizeof *fs, 0), *cr = rp_big((nc + addc + 1) * sizeof *cr, 0);
    uint32_t *uv = w->corner_uv ? rp_big((nc + addc + 1) * sizeof *uv, 0) : NULL;
    int32_t *fm = mats ? rp_big(((size_t)nf + 1) * sizeof *fm, 0) : NULL;
    if (!fs || !cr || (w->corner_uv && !uv) || (mats && !fm)) {
        free(fs);
        free(cr);
        free(uv);
        free(fm);
        return -1;
    }
    uint32_t f = 0, c = 0;
    for (uint32_t i = 0; i < w->nobjs; i++) {
        MeshObject *o = &w->objs[i];
        uint32_t first = f;
        for (uint32_t g = o->face_first; g < o->face_first + o->face_count; g++) {
            if (drop && drop[g])
                continue;
            uint32_t s = w->face_start[g], n = w->face_start[g + 1] - s;
            fs[f] = c;
            memcpy(cr + c, w->corner + s, n * sizeof *cr);
            if (uv)
                memcpy(uv + c, w->corner_uv + s, n * sizeof *uv);
            if (fm)
                fm[f] = mesh_face_mat(w, g);
            c += n;
            f++;
        }
        for (uint32_t k = 0; k < nfills[i]; k++)
            for (uint32_t j = 0; j < fills[i][k].ntri; j++, f++) {
                fs[f] = c;
                for (int q = 0; q < 3; q++) {
                    if (uv)
                        uv[c] = MESH_NO_UV;
                    cr[c++] = fills[i][k].tri[3 * j + q];
                }
                if (fm)
                    fm[f] = fills[i][k].mat;
            }
        o->face_first = first;
        o->face_count = f - first;
    }
    fs[f] = c;
    free(w->face_start);
    free(w->corner);
    free(w->corner_uv);
    free(w->face_mat);
    w->face_start = fs;
    w->corner = cr;
    w->corner_uv = uv;
    w->face_mat = fm;
    w->nfaces = f;
    return 0;
}

/* ==== Object by object ==== */

typedef struct {
    Fill     **fills;           /* per object */
    uint32_t  *nfills;
    uint8_t   *drop;            /* per mesh face: a duplicate that goes */
    uint8_t   *dups;            /* per object: duplicates went */
    uint64_t   dp_budget;
} Filled;

static void filled_free(Filled *fd, uint32_t nobjs)
{
    for (uint32_t i = 0; fd->fills && i < nobjs; i++) {
        for (uint32_t k = 0; fd->fills[i] && k < fd->nfills[i]; k++)
            free(fd->fills[i][k].tri);
        free(fd->fills[i]);
    }
    free(fd->fills);
    free(fd->nfills);
    free(fd->drop);
    free(fd->dups);
}

/* The duplicates, splits, winding and holes of object i, each as its
 * level allows; outward too when no hole was filled (else after the
 * fills are in place). */
static int object_steps(Rep *r, uint32_t i, Filled *fd)
{
    unsigned steps = r->opt->steps, lv = r->level[i];
    if (lv >= RP_LEVEL_UNTOUCHED || !(steps & (REPAIR_CLEAN | REPAIR_MANIFOLD | REPAIR_WINDING | REPAIR_HOLES)))
        return 0;
    int split = lv < RP_LEVEL_NO_SPLITS, turn = lv < RP_LEVEL_NO_WINDING && (steps & REPAIR_WINDING);
    ObjTopo t;
    Cuts cuts = { 0 };
    if (rp_topo_build(r, i, &t))
        return -1;
    int rc = 0;
    uint32_t had = r->rep->duplicate + r->rep->flaps;
    if (steps & REPAIR_CLEAN)
        rc = rp_twins(r, &t, fd->drop);
    fd->dups[i] = r->rep->duplicate + r->rep->flaps > had;
    if (rc == 0 && split && (steps & REPAIR_MANIFOLD))
        rc = rp_manifold(r, &t, &cuts);
    if (rc == 0 && turn)
        rc = rp_winding(r, &t);
    if (rc == 0 && split && (steps & REPAIR_HOLES) && t.nboundary)
        rc = rp_holes(r, &t, &cuts, &fd->fills[i], &fd->nfills[i], &fd->dp_budget);
    if (rc == 0)
        rc = rp_cuts_settle(r, &t, &cuts, fd->fills[i], fd->nfills[i], fd->drop);
    int settled = 0;
    if (rc == 0 && turn && !fd->nfills[i])
        rc = rp_outward(r, &t, &settled);
    /* duplicates gone from an object that does not end settled: the
     * guard checks it (repair.c: risky) */
    if (!fd->nfills[i] && fd->dups[i] && !settled)
        r->dup_unsettled++;
    rp_cuts_free(&cuts);
    rp_topo_free(r, &t);
    return rc || rp_cancelled(r) ? -1 : 0;
}

static int objects(Rep *r)
{
    uint32_t n = r->w.nobjs;
    Filled fd = { calloc((size_t)n + 1, sizeof *fd.fills), calloc((size_t)n + 1, sizeof *fd.nfills),
                  rp_big((size_t)r->w.nfaces + 1, 1), calloc((size_t)n + 1, 1), RP_DP_BUDGET };
    int rc = -1;
    if (!fd.fills || !fd.nfills || !fd.drop || !fd.dups)
        goto out;
    for (uint32_t i = 0; i < n; i++)
        if (object_steps(r, i, &fd))
            goto out;
    if (rp_faces_rebuild(r, fd.drop, (Fill *const *)fd.fills, fd.nfills))
        goto out;
    for (uint32_t i = 0; i < n; i++) {
        if (!fd.nfills[i])
            continue;
        if (!(r->opt->steps & REPAIR_WINDING) || r->level[i] >= RP_LEVEL_NO_WINDING) {
            r->dup_unsettled += fd.dups[i];
            continue;
        }
        ObjTopo t;
        if (rp_topo_build(r, i, &t))
            goto out;
        int settled = 0, bad = rp_outward(r, &t, &settled);
        rp_topo_free(r, &t);
        if (bad)
            goto out;
        r->dup_unsettled += fd.dups[i] && !settled;
    }
    rc = 0;
out:
    filled_free(&fd, n);
    return rc;
}

/* ==== What is left ==== */

static void left(RepairReport *rep, const MeshCheck *mc)
{
    const CheckCounts *c = &mc->file;
    rep->left_holes = c->holes;
    rep->left_nm_edges = c->nonmanifold_edges;
    rep->left_nm_vertices = c->nonmanifold_vertices;
    rep->left_flipped = c->inconsistent_faces;
    rep->left_nonorientable = c->nonorientable;
    rep->left_degenerate = c->degenerate_faces;
    rep->left_duplicate = c->duplicate_faces;
    rep->left_crossings = c->self_intersections;
    rep->crossings_tested = c->intersections_tested;
    rep->crossings_stopped = c->intersections_stopped;
    for (uint32_t i = 0; i < mc->nobjs; i++)
        rep->left_inside_out += mc->objs[i].c.inside_out != 0;
}

/* ==== The repair ==== */

static int steps(Rep *r)
{
    unsigned s = r->opt->steps;
    double *ms = r->rep->ms_phase, t = now_ms();
    if (rp_points_build(r) || ((s & REPAIR_WELD) && rp_weld(r)) || rp_cancelled(r))
        return -1;
    rp_points_drop_table(r);
    ms[REPAIR_T_WELD] += now_ms() - t;
    t = now_ms();
    if (s & REPAIR_CLEAN) {
        if (rp_clean(r) || rp_cancelled(r))
            return -1;
        r->clean = 1;
    }
    ms[REPAIR_T_CLEAN] += now_ms() - t;
    t = now_ms();
    if ((s & (REPAIR_CLEAN | REPAIR_MANIFOLD | REPAIR_WINDING | REPAIR_HOLES)) && objects(r))
        return -1;
    ms[REPAIR_T_OBJECTS] += now_ms() - t;
    t = now_ms();
    int rc = rp_renumber(r, (s & REPAIR_CLEAN) != 0);
    ms[REPAIR_T_ORDER] += now_ms() - t;
    return rc;
}

/* ==== The checks ==== */

/* Can the input's crossing figures stand for the result's? The crossing
 * test reads each object's triangles (the fans of its faces that are
 * not degenerate and duplicate no earlier face of it) by their points.
 * A repair that moved and added no position (welds at one position
 * only: the check takes a position as one point however many vertices
 * are there), dropped no face but degenerate ones (which the test
 * leaves out; a degenerate face can be the original only of a
 * degenerate duplicate), dropped no repeated corner and flipped no
 * polygon (a flip keeps a face's first corner, so its fan, but a
 * polygon's first edge is where the check looks for its duplicate)
 * leaves those triangles as they were, object by object, and their
 * count too. A count that stopped on its budget is not taken: where it
 * stopped depends on the order of the work. The fuzzer
 * (tests/fuzz/fuzz_repair.c) counts the result again to hold this. */
static int crossings_same(const Rep *r, const Before *b)
{
    const RepairReport *rep = r->rep;
    return r->opt->intersections && b && b->rc == 0 && !b->threaded && b->mc.file.intersections_tested &&
           !b->mc.file.intersections_stopped && !r->pos_changed && !rep->fill_faces && !rep->duplicate &&
           !rep->flaps && !rep->fins && !rep->repeated && !r->poly_flips;
}

/* The input's crossing figures, object by object, as the result's. */
static void crossings_take(MeshCheck *after, const MeshCheck *before)
{
    for (uint32_t i = 0; i < after->nobjs && i < before->nobjs; i++) {
        CheckCounts *a = &after->objs[i].c;
        const CheckCounts *b = &before->objs[i].c;
        a->self_intersections = b->self_intersections;
        a->intersections_tested = b->intersections_tested;
        a->intersections_stopped = b->intersections_stopped;
        a->pair_tests = b->pair_tests;
        a->pair_budget = b->pair_budget;
    }
    after->file.self_intersections = before->file.self_intersections;
    after->file.intersections_tested = before->file.intersections_tested;
    after->file.intersections_stopped = before->file.intersections_stopped;
    after->file.pair_tests = before->file.pair_tests;
    after->file.pair_budget = before->file.pair_budget;
}

/* The check of mesh w (the repaired copy, or m once it is in place)
 * into *after: the crossing test's figures the input's when the repair
 * left the triangles it reads as they were (b: the input's check, when
 * it is done; else NULL). */
static int check_result(Rep *r, const Mesh *w, const Before *b, MeshCheck *after)
{
    double t = now_ms();
    int same = crossings_same(r, b);
    CheckOpts co = { .threads = r->opt->threads, .intersections = r->opt->intersections && !same,
                     .cancel = r->opt->cancel };
    char err[256];
    int rc = meshcheck_run(after, w, &co, err, sizeof err);
    if (rc == 0 && same) {
        crossings_take(after, &b->mc);
        r->rep->crossings_same = 1;
    }
    r->rep->ms_phase[REPAIR_T_CHECK] += now_ms() - t;
    return rc;
}

/* A fresh report for another go, keeping its times. */
static void report_again(RepairReport *rep)
{
    double ms[REPAIR_T_COUNT];
    memcpy(ms, rep->ms_phase, sizeof ms);
    repair_report_free(rep);
    memset(rep, 0, sizeof *rep);
    memcpy(rep->ms_phase, ms, sizeof ms);
}

/* Did the repair do anything that could make a figure of the check
 * worse? Welds at one position, repeated corners and degenerate faces
 * dropped (the check sets them aside) and flips that make a patch agree
 * (the check makes it agree the same way before it measures) cannot,
 * nor can duplicates dropped from an object that ends settled (twins.c
 * opens no edge; every part agreeing, none is non-orientable, none has
 * a flip left, and the turn outward leaves none inside out). Splits,
 * fills, stray fins dropped, turns outward, moved positions, an object
 * left without faces and duplicates dropped elsewhere might (a
 * duplicate gone can make an edge manifold that joins two patches
 * whose windings disagree), and so might repeated corners dropped when
 * a duplicate is kept (a b b c and a b c c are one face once each is a
 * b c), and flips of polygons of four corners or more: the check looks
 * for a face's duplicate across its first edge, which a flip changes
 * (quads 1 2 6 5 and 5 2 1 6 are on the same points; flipped, 5 6 1 2
 * shares the other's edge 6 5, and the check finds what it did not
 * before). */
static int risky(const Rep *r, const Mesh *m)
{
    const RepairReport *rep = r->rep;
    if (rep->split_vertices || rep->cuts_undone || rep->fins || rep->filled || rep->outward || r->dup_unsettled ||
        r->poly_flips || (r->opt->weld_eps > 0 && rep->welded) || (rep->repeated && rep->dup_kept))
        return 1;
    for (uint32_t i = 0; i < m->nobjs; i++)
        if (m->objs[i].face_count && !r->w.objs[i].face_count)
            return 1;
    return 0;
}

/* Repair m, object by object as boldly as the check of the result
 * allows (guard.c). The input is checked (b) when *have is set already
 * (RepairOpts.keep_checks: before the repair, on every thread), or when
 * the repair did something that might make a figure worse (then on a
 * helper thread, beside the check of the result, when two threads are
 * allowed), and then the result is checked before it replaces m's
 * arrays. Else it replaces them first (the input's arrays go before the
 * check of the result needs its memory), and *counted says whether
 * that check ran. *after: the check of the repaired mesh (when
 * counted). */
static int repair_guarded(Rep *r, Mesh *m, uint8_t *level, Before *b, int *have, MeshCheck *after, int *counted)
{
    int rc = 0;
    *counted = 0;
    for (;;) {
        report_again(r->rep);
        if ((rc = copy_in(r, m) || steps(r) ? -1 : 0))
            break;
        if (!risky(r, m)) {
            install(r, m);
            if (r->opt->installed)
                r->opt->installed(m, r->opt->installed_arg);
            *counted = check_result(r, m, *have ? b : NULL, after) == 0;
            break;
        }
        if (!*have) {
            *have = 1;
            if ((rc = rp_before_start(b, m, r->opt, 0)))
                break;
        }
        /* the input's check is done when it ran first (on one thread, or
         * before the repair): else it runs beside this one */
        if ((rc = check_result(r, &r->w, b->threaded ? NULL : b, after)))
            break;
        double t = now_ms();
        rc = rp_before_wait(b);
        r->rep->ms_phase[REPAIR_T_CHECK] += now_ms() - t;
        if (rc)
            break;
        if (!rp_worse(&b->mc, after, level)) {
            install(r, m);
            if (r->opt->installed)
                r->opt->installed(m, r->opt->installed_arg);
            *counted = 1;
            break;
        }
        meshcheck_free(after);
        free_copy(r);
        *r = (Rep){ .opt = r->opt, .rep = r->rep, .level = level };
    }
    return rc;
}

int repair_mesh(Mesh *m, const RepairOpts *opt, RepairReport *rep, char *err, size_t errlen)
{
    RepairOpts dflt = { .steps = REPAIR_DEFAULT };
    const char *name = m->path ? m->path : "(input)";
    double t0 = now_ms();
    memset(rep, 0, sizeof *rep);
    opt = opt ? opt : &dflt;
    if (!(opt->weld_eps >= 0) || !isfinite(opt->weld_eps)) {
        snprintf(err, errlen, "%s: the weld distance must be a finite number >= 0", name);
        return -1;
    }
    uint32_t faces = m->nfaces, verts = m->nverts;
    uint8_t *level = calloc((size_t)m->nobjs + 1, 1);
    Rep r = { .opt = opt, .rep = rep, .level = level };
    Before b = { .rc = -1 };
    MeshCheck after;
    int counted = 0, have = 0, rc = level ? 0 : -1;
    if (rc == 0 && opt->keep_checks) {
        /* first, on every thread: the repair has its memory to itself */
        double t = now_ms();
        have = 1;
        rc = rp_before_start(&b, m, opt, 1);
        rep->ms_phase[REPAIR_T_BEFORE] = now_ms() - t;
    }
    if (rc == 0)
        rc = repair_guarded(&r, m, level, &b, &have, &after, &counted);
    free_copy(&r);
    if (rc) {
        snprintf(err, errlen, "%s: %s", name,
                 rp_cancelled(&r) ? "cancelled" : "out of memory repairing the model (or more than 2^32 vertices)");
        if (have)
            rp_before_free(&b);
        free(level);
        repair_report_free(rep);
        return -1;
    }
    if (counted) {
        left(rep, &after);
        if (opt->keep_checks)
            rep->after = after;
        else
            meshcheck_free(&after);
    }
    rep->counted = counted;
    if (opt->keep_checks) {
        rep->before = b.mc;     /* b.rc is 0: the repair ran */
        rep->has_before = 1;
    } else if (have) {
        rp_before_free(&b);
    }
    for (uint32_t i = 0; i < m->nobjs; i++)
        rep->held_back += level[i] > 0;
    free(level);
    rep->faces_before = faces;
    rep->verts_before = verts;
    rep->faces_after = m->nfaces;
    rep->verts_after = m->nverts;
    rep->ms = now_ms() - t0;
    return 0;
}

void repair_report_free(RepairReport *rep)
{
    free(rep->holes);
    rep->holes = NULL;
    rep->nholes = 0;
    meshcheck_free(&rep->before);
    meshcheck_free(&rep->after);
    rep->has_before = 0;
}
