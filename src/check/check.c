/* check.c: meshcheck_run, object by object.
 *
 * The passes, for each object: its points (the welded positions its
 * corners use, renumbered from 0 so that every array is the object's
 * size, not the file's), the topology (topo.c), the winding and the
 * measures (shape.c), duplicates, then the crossing pairs (cross.c).
 * Each pass frees what it built before the next starts: the check's
 * memory stays within the mesh's own (the benchmark says how far). With
 * two threads, passes that read nothing the others write run beside
 * them (the vertices beside the winding, the measures beside the
 * crossing test), only where what they hold at once stays below the
 * pairing's buckets, the check's own peak. The
 * objects' figures are summed into the file's, and said in words, by
 * the rows of counts.c. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check_internal.h"
#include "clock.h"
#include "thread.h"

typedef struct {
    const Mesh      *m;
    const CheckOpts *opt;
    Pool            *pool;
    uint32_t        *pid;       /* mesh vertex -> welded point */
    uint32_t         np;
    uint32_t        *loc;       /* welded point -> the object's point, CHECK_NONE */
    uint32_t        *vpt;       /* mesh vertex -> the object's point */
    uint32_t        *prep;      /* the object's point -> a vertex */
    uint8_t         *used;      /* welded point used by a face of any object */
} Run;

/* ==== One object ==== */

/* Its faces and corners, the shape of its faces, its points and box. */
static int obj_prepare(Run *r, ObjCheck *o, const MeshObject *mo, char *err, size_t errlen)
{
    const Mesh *m = r->m;
    o->f0 = mo->face_first;
    o->nf = mo->face_count;
    o->c0 = m->face_start[o->f0];
    uint64_t nc = (uint64_t)m->face_start[o->f0 + o->nf] - o->c0;
    if (nc >= MATE_FIRST_SPECIAL) {
        snprintf(err, errlen, "object '%s': too many corners to check", mo->name);
        return -1;
    }
    o->nc = (uint32_t)nc;
    o->tris = 1;
    o->max_corners = 0;
    for (uint32_t f = 0; f < o->nf; f++) {
        uint32_t n = oc_start(o, f + 1) - oc_start(o, f);
        o->tris &= n == 3;
        o->max_corners = n > o->max_corners ? n : o->max_corners;
    }
    if (!o->tris) {
        o->cface = check_big(((size_t)o->nc + 1) * sizeof *o->cface, 0);
        if (!o->cface)
            return -1;
        for (uint32_t f = 0; f < o->nf; f++)
            for (uint32_t c = oc_start(o, f); c < oc_start(o, f + 1); c++)
                o->cface[c] = f;
    }
    o->vpt = r->vpt;
    o->prep = r->prep;
    o->npts = 0;
    CheckCounts *c = o->c;
    for (uint32_t k = 0; k < o->nc; k++) {
        uint32_t v = oc_vert(o, k), g = r->pid[v];
        /* the weld map is in range: loc[] and used[] have np entries */
        ZV_ASSERT(g < r->np);
        if (r->loc[g] == CHECK_NONE) {
            r->loc[g] = o->npts;
            r->prep[o->npts++] = v;
            r->used[g] = 1;
            const float *p = oc_vpos(o, v);
            for (int i = 0; i < 3; i++) {
                c->lo[i] = o->npts == 1 || p[i] < c->lo[i] ? p[i] : c->lo[i];
                c->hi[i] = o->npts == 1 || p[i] > c->hi[i] ? p[i] : c->hi[i];
            }
        }
        r->vpt[v] = r->loc[g];
    }
    c->faces = o->nf;
    c->vertices = o->npts;
    for (int i = 0; i < 3; i++)
        o->ref[i] = o->npts ? ((double)c->lo[i] + c->hi[i]) / 2 : 0;
    return 0;
}

static int cancelled(const Run *r)
{
    return r->opt->cancel && __atomic_load_n(r->opt->cancel, __ATOMIC_RELAXED);
}

/* The measures on a helper thread, beside the crossing test: they read
 * the positions and the flags, and write figures the crossing test does
 * not; the crossing test's own set-up (the sort, the tree) is on one
 * thread, so the other core has room for them. */
typedef struct {
    ObjCheck *o;
    double    ms;
} Measures;

static void *measures_main(void *arg)
{
    Measures *m = arg;
    double t = now_ms();
    check_measures(m->o);
    m->ms = now_ms() - t;
    return NULL;
}

/* The holes and non-manifold vertices on a helper thread, beside the
 * winding and the duplicates. */
typedef struct {
    ObjCheck *o;
    double    ms;
    int       rc;
} Vertices;

static void *vertices_main(void *arg)
{
    Vertices *v = arg;
    double t = now_ms();
    v->rc = check_vertices(v->o);
    v->ms = now_ms() - t;
    return NULL;
}

/* The passes, each timed into ms[]. */
static int obj_passes(Run *r, ObjCheck *o, double *ms)
{
    double t = now_ms();
    o->mate = check_big(((size_t)o->nc + 1) * sizeof *o->mate, 0);
    if (!o->mate || check_pairing(o))
        return -1;
    /* beside the winding when two threads are allowed and no list or
     * location is asked for (check_vertices writes them too): what they
     * hold at once (the pairing, a union-find over corners and one over
     * faces) is less than the pairing's buckets were */
    Vertices ve = { .o = o };
    pthread_t vth;
    int vbeside = r->opt->threads > 1 && !r->opt->detail && !r->opt->locations &&
                  thread_start(&vth, vertices_main, &ve) == 0;
    if (!vbeside)
        vertices_main(&ve);
    double t2 = now_ms();
    ms[CHECK_T_EDGES] += t2 - t;
    int rs = vbeside ? 0 : ve.rc;  /* beside: its result is read once it is joined */
    if (rs == 0)
        rs = cancelled(r) || check_shape(o) ? -1 : 0;
    t = now_ms();
    ms[CHECK_T_SHAPE] += t - t2;
    if (rs == 0)
        rs = cancelled(r) || check_duplicates(o) || check_locate_faces(o) ? -1 : 0;
    if (vbeside) {
        pthread_join(vth, NULL);
        ms[CHECK_T_EDGES] += ve.ms;
    }
    if (rs || ve.rc)
        return -1;
    free(o->mate);
    free(o->nm_half);
    free(o->nm_group);
    o->mate = o->nm_half = o->nm_group = NULL;
    if (!r->opt->detail) {
        free(o->part);          /* read by nothing after this: memory for the crossings */
        o->part = NULL;
    }
    t2 = now_ms();
    ms[CHECK_T_DUPS] += t2 - t;
    Measures me = { .o = o };
    pthread_t th;
    int beside = r->opt->intersections && r->pool && thread_start(&th, measures_main, &me) == 0;
    if (!beside) {
        measures_main(&me);
        t2 = now_ms();
    }
    int rc = 0;
    if (r->opt->intersections) {
        rc = cancelled(r) || check_crossings(o) || check_locate_crossings(o) ? -1 : 0;
        if (rc == 0)
            o->c->intersections_tested = 1;
        ms[CHECK_T_CROSS] += now_ms() - t2;
    }
    if (beside)
        pthread_join(th, NULL);
    ms[CHECK_T_SHAPE] += me.ms;
    return rc || cancelled(r) ? -1 : 0;
}

static int check_object(Run *r, MeshCheck *mc, uint32_t i, char *err, size_t errlen)
{
    const MeshObject *mo = &r->m->objs[i];
    CheckObject *out = &mc->objs[i];
    snprintf(out->name, sizeof out->name, "%s", mo->name);
    out->face_first = mo->face_first;
    out->face_count = mo->face_count;
    check_counts_empty(&out->c);
    ObjCheck o = { .m = r->m, .opt = r->opt, .pool = r->pool, .c = &out->c, .out = out };
    int rc = -1;
    if (mc->face_flags) {
        o.flags = mc->face_flags + mo->face_first;
        o.part = mc->face_part + mo->face_first;
    } else {
        o.flags = check_big((size_t)mo->face_count + 1, 1);
        o.part = check_big(((size_t)mo->face_count + 1) * sizeof *o.part, 0);
        if (!o.flags || !o.part)
            goto out;
    }
    if (obj_prepare(r, &o, mo, err, errlen) == 0)
        rc = obj_passes(r, &o, mc->ms);
    for (uint32_t p = 0; p < o.npts; p++)
        r->loc[r->pid[o.prep[p]]] = CHECK_NONE;
out:
    free(o.cface);
    free(o.mate);
    free(o.nm_half);
    free(o.nm_group);
    if (!mc->face_flags) {
        free(o.flags);
        free(o.part);
    }
    return rc;
}

/* ==== The file ==== */

/* Vertices no face, point or line of the mesh uses: the file's (*file),
 * and each object's within the range of vertices it uses (obj[i]). It
 * reads the mesh alone, so it may run beside the objects' passes. */
typedef struct {
    const Mesh *m;
    uint32_t    file;
    uint32_t   *obj;            /* per object */
    int         rc;
} Unused;

static void *count_unused(void *arg)
{
    Unused *u = arg;
    const Mesh *m = u->m;
    uint8_t *used = calloc((size_t)m->nverts + 1, 1);
    u->rc = -1;
    if (!used)
        return NULL;
    uint32_t ncorners = m->nfaces ? m->face_start[m->nfaces] : 0;
    for (uint32_t c = 0; c < ncorners; c++)
        used[m->corner[c]] = 1;
    for (uint32_t i = 0; i < m->npoints; i++)
        used[m->point ? m->point[i] : i] = 1;
    uint32_t nl = m->nlines ? m->line_start[m->nlines] : 0;
    for (uint32_t i = 0; i < nl; i++)
        used[m->line_corner[i]] = 1;
    for (uint32_t v = 0; v < m->nverts; v++)
        u->file += !used[v];
    for (uint32_t i = 0; i < m->nobjs; i++) {
        const MeshObject *mo = &m->objs[i];
        if (mo->face_count + mo->point_count + mo->line_count == 0)
            continue;
        for (uint32_t v = mo->vert_min; v <= mo->vert_max && v < m->nverts; v++)
            u->obj[i] += !used[v];
    }
    free(used);
    u->rc = 0;
    return NULL;
}

/* The file's figures: the objects' summed, but its points and unused
 * vertices its own (objects share points; a vertex between the objects'
 * ranges is the file's alone). */
static void file_totals(MeshCheck *mc, uint32_t used_points)
{
    uint32_t unused = mc->file.unused_vertices;
    meshcheck_sum(&mc->file, &mc->objs[0].c, mc->nobjs, sizeof *mc->objs);
    mc->file.vertices = used_points;
    mc->file.unused_vertices = unused;
}

static void run_free(Run *r)
{
    free(r->pid);
    free(r->loc);
    free(r->vpt);
    free(r->prep);
    free(r->used);
    pool_free(r->pool);
}

static int run_start(Run *r, MeshCheck *mc)
{
    const Mesh *m = r->m;
    size_t nv = (size_t)m->nverts + 1;
    double t = now_ms();
    r->pid = check_big(nv * sizeof *r->pid, 0);
    if (!r->pid || check_weld(m, r->pid, &r->np))
        return -1;
    mc->ms[CHECK_T_WELD] = now_ms() - t;
    r->loc = check_big(((size_t)r->np + 1) * sizeof *r->loc, 0);
    r->prep = check_big(((size_t)r->np + 1) * sizeof *r->prep, 0);
    r->used = check_big((size_t)r->np + 1, 1);
    r->vpt = check_big(nv * sizeof *r->vpt, 0);
    if (!r->loc || !r->prep || !r->used || !r->vpt)
        return -1;
    memset(r->loc, 0xff, ((size_t)r->np + 1) * sizeof *r->loc);
    if (r->opt->intersections && r->opt->threads > 1)
        r->pool = pool_create(r->opt->threads - 1);     /* NULL: the caller alone, still right */
    mc->nobjs = m->nobjs;
    mc->objs = calloc((size_t)m->nobjs + 1, sizeof *mc->objs);
    if (!mc->objs)
        return -1;
    if (r->opt->detail) {
        mc->face_flags = calloc((size_t)m->nfaces + 1, 1);
        mc->face_part = calloc((size_t)m->nfaces + 1, sizeof *mc->face_part);
        if (!mc->face_flags || !mc->face_part)
            return -1;
    }
    return 0;
}

int meshcheck_run(MeshCheck *mc, const Mesh *m, const CheckOpts *opt, char *err, size_t errlen)
{
    memset(mc, 0, sizeof *mc);
    snprintf(mc->unit, sizeof mc->unit, "%s", m->info.unit);
    Run r = { .m = m, .opt = opt };
    err[0] = 0;
    int rc = run_start(&r, mc);
    /* the unused vertices on a helper thread beside the objects when
     * two threads are allowed (they read the mesh alone) */
    Unused un = { .m = m, .obj = calloc((size_t)m->nobjs + 1, sizeof *un.obj), .rc = -1 };
    pthread_t th;
    int beside = rc == 0 && un.obj && opt->threads > 1 && thread_start(&th, count_unused, &un) == 0;
    for (uint32_t i = 0; rc == 0 && i < m->nobjs; i++)
        rc = check_object(&r, mc, i, err, errlen);
    if (beside)
        pthread_join(th, NULL);
    else if (rc == 0 && un.obj)
        count_unused(&un);
    if (rc == 0 && un.rc == 0) {
        mc->file.unused_vertices += un.file;
        for (uint32_t i = 0; i < mc->nobjs; i++)
            mc->objs[i].c.unused_vertices += un.obj[i];
    } else if (rc == 0) {
        rc = -1;
    }
    free(un.obj);
    uint32_t used = 0;
    for (uint32_t p = 0; rc == 0 && p < r.np; p++)
        used += r.used[p];
    run_free(&r);
    if (rc) {
        if (!err[0])
            snprintf(err, errlen, "%s: %s", m->path ? m->path : "(input)",
                     cancelled(&r) ? "cancelled" : "out of memory checking the model");
        meshcheck_free(mc);
        return -1;
    }
    file_totals(mc, used);
    return 0;
}

void meshcheck_free(MeshCheck *mc)
{
    for (uint32_t i = 0; mc->objs && i < mc->nobjs; i++) {
        free(mc->objs[i].boundary);
        free(mc->objs[i].nm_edges);
        free(mc->objs[i].nm_verts);
        free(mc->objs[i].pairs);
        check_locations_free(&mc->objs[i].loc);
    }
    free(mc->objs);
    free(mc->face_flags);
    free(mc->face_part);
    memset(mc, 0, sizeof *mc);
}
