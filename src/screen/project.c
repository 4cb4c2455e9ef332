/* project.c: the one front end. Scene -> screen-space polygons.
 *
 * Per object, two passes:
 *  1. Vertices (here): each once to view space and, where in front of
 *     the near plane and inside the guard band, straight to snapped 24.8
 *     screen coordinates (x, y pairs in one array, depths in another); a
 *     vertex that needs clipping gets x = y = VERT_OUT instead. A
 *     branch-free SIMD loop (project_sse2.c, project_avx2.c: the frame's
 *     SimdLevel) performs exactly the scalar IEEE operations in the
 *     scalar order, so every level gives the same bits.
 *  2. Polygons, a chunk at a time (polys.c): the chunk's map entries
 *     start at -1; a chunk of triangles is first screened by a box test
 *     (eight at a time under AVX2) that keeps only triangles whose
 *     sample box is non-empty and on screen, or that have a corner to
 *     clip (at a small size most of a big model covers no sample centre,
 *     and this is the whole cost of those triangles); under AVX2 a second
 *     screening then settles the survivors whose box holds at most four
 *     samples by their edge functions. The survivors, and
 *     every polygon of other chunks, take the fast path (copy the snapped
 *     corners) or the slow one (clip.c: clip against the near plane and
 *     the guard band, then snap), then the sample box, back-face test and
 *     the depth plane from the snapped corners (finish_tri for triangles
 *     on the fast path, finish_poly otherwise: the same arithmetic).
 *
 * A big object is split over the caller and up to ScreenPolys.threads - 1
 * helpers of a persistent pool, in both passes; the parts of pass 2 write
 * into windows of the output arrays and move down in order, so the output
 * is the same as one thread's. Every scratch buffer belongs to the
 * ScreenPolys being filled (ScreenWork), so the front end keeps no state
 * of its own between calls.
 */

#define _DEFAULT_SOURCE
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "pool.h"
#include "project.h"

/* Vertices farther than this outside the image (pixels) are clipped, so
 * that fixed-point values stay below 2^23 and edge products fit int64. */
#define GUARD_PX 8192.0

/* A thread is worth waking for at least this many polygons of one
 * object (below it, the hand-over costs more than it saves). */
#define PART_MIN 8192

/* Vertices per task of pass 1 on several threads. */
#define VERT_CHUNK 65536

struct ScreenWork {
    Scratch sc;
    KeepLut lut;
    ClipBuf clip[SCREEN_MAX_THREADS];   /* [0] the caller's, [i] helper i's */
    int     ncpus;                      /* cores online, read once */
    Pool   *pool;                       /* helpers, made on first need */
    int     pool_want;                  /* helpers it was made for */
};

static ScreenWork *work_get(ScreenPolys *sp)
{
    if (!sp->work) {
        sp->work = calloc(1, sizeof *sp->work);
        if (sp->work) {
            long c = sysconf(_SC_NPROCESSORS_ONLN);
            sp->work->ncpus = c < 1 ? 1 : c > SCREEN_MAX_THREADS ? SCREEN_MAX_THREADS : (int)c;
            KeepLut *l = &sp->work->lut;
            for (unsigned m = 0; m < 256; m++) {
                unsigned n = 0;
                for (unsigned b = 0; b < 8; b++)
                    if (m >> b & 1)
                        l->lanes[m] |= (uint64_t)b << (8 * n++);
                l->count[m] = (uint8_t)n;
            }
        }
    }
    return sp->work;
}

static void work_free(ScreenWork *w)
{
    if (!w)
        return;
    pool_free(w->pool);
    free(w->sc.sv);
    free(w->sc.idx);
    for (int i = 0; i < SCREEN_MAX_THREADS; i++) {
        free(w->clip[i].buf[0]);
        free(w->clip[i].buf[1]);
        section_clip_free(&w->clip[i].sec);
        free(w->clip[i].cpts);
        free(w->clip[i].cmask);
    }
    free(w);
}

/* Everything but the caller's settings goes. */
void screen_free(ScreenPolys *sp)
{
    int threads = sp->threads, simd = sp->simd;
    const struct SectionCut *cut = sp->cut;
    free(sp->verts);
    free(sp->polys);
    free(sp->map);
    free(sp->map_first);
    work_free(sp->work);
    memset(sp, 0, sizeof *sp);
    sp->threads = threads;
    sp->simd = simd;
    sp->cut = cut;
}

/* ==== projection parameters ==== */

static void proj_setup(Proj *p, const Scene *s, const Viewport *vp)
{
    const Camera *c = &s->cam;
    double aspect = vp->pixel_aspect > 0 ? vp->pixel_aspect : 1;
    double r = c->radius > 0 ? c->radius : 1;
    double zoom = c->zoom > 0 ? c->zoom : 1;
    /* the fitted half extents, 90% of the image at zoom 1 (x-pixel units) */
    double hx = c->fit_half.x > 0 ? c->fit_half.x : r, hy = c->fit_half.y > 0 ? c->fit_half.y : r;
    double hz = c->fit_half.z > 0 ? c->fit_half.z : r;
    double half_w = 0.5 * vp->w, half_h = 0.5 * vp->h * aspect;
    p->persp = c->persp;
    p->cx = vp->w * 0.5;
    p->cy = vp->h * 0.5;
    if (!c->persp) {
        p->fx = zoom * 0.9 * fmin(half_w / hx, half_h / hy);
        p->dscale = 0.25 / r;       /* view z in [-2r, 2r] -> depth [0, 1] */
        p->dbias = 0.5;
    } else {
        double fov = (c->fov_deg > 1 && c->fov_deg < 179 ? c->fov_deg : 50) * 3.14159265358979323846 / 180;
        p->fx = fmin(half_w, half_h) / tan(fov / 2);
        /* at zoom 1 the box's front face fills 90%; zoom moves the eye
         * towards the centre (and into the scene past the box's front) */
        p->eye = (hz + fmax(hx * p->fx / half_w, hy * p->fx / half_h) / 0.9) / zoom;
        p->n = fmax(0.5 * (p->eye - r), 0.01 * r);
        p->f = p->eye + 3 * r;
        p->dk = p->f / (p->f - p->n);
    }
    p->fy = p->fx / aspect;
    p->gx0 = -GUARD_PX;
    p->gx1 = vp->w + GUARD_PX;
    p->gy0 = -GUARD_PX;
    p->gy1 = vp->h + GUARD_PX;
}

/* ==== pass 1: vertices ==== */

/* Vertices [a, b) at the job's level. */
static void verts_range(const VertJob *j, uint32_t a, uint32_t b)
{
#ifdef ZV_AVX2
    if (j->simd >= SIMD_AVX2) {
        project_verts_avx2(j, a, b);
        return;
    }
#endif
#ifdef ZV_SSE2
    if (j->simd >= SIMD_SSE2) {
        project_verts_sse2(j, a, b);
        return;
    }
#endif
    for (uint32_t i = a; i < b; i++)
        vert_one(j, i);
}

static void verts_part(void *arg, int part, int worker)
{
    const VertJob *j = arg;
    (void)worker;
    uint32_t a = (uint32_t)((uint64_t)j->nv * (uint32_t)part / (uint32_t)j->parts);
    uint32_t b = (uint32_t)((uint64_t)j->nv * (uint32_t)(part + 1) / (uint32_t)j->parts);
    verts_range(j, a, b);
}

/* ==== an object over several threads ==== */

/* The helpers' parts, written in windows further up sp's arrays, moved
 * down after part 0: the vertices on one thread, the polygons (their
 * first corner shifted) and the map entries on another. Within an array
 * the parts move in order, each into room the ones before it left. */
typedef struct {
    ScreenPolys       *sp;
    const ScreenPolys *win;     /* each part's counts */
    const uint32_t    *pb, *vb; /* where each part was written */
    const uint32_t    *inst0, *ninst;
    uint32_t           bv[SCREEN_MAX_THREADS], bp[SCREEN_MAX_THREADS];  /* where each part goes */
    int                parts;
} CompactJob;

static void compact_task(void *arg, int task, int worker)
{
    (void)worker;
    CompactJob *c = arg;
    ScreenPolys *sp = c->sp;
    for (int i = 1; i < c->parts; i++) {
        const ScreenPolys *part = &c->win[i];
        if (task == 0) {
            memmove(sp->verts + c->bv[i], sp->verts + c->vb[i], (size_t)part->nverts * sizeof *sp->verts);
            continue;
        }
        uint32_t bp = c->bp[i], bv = c->bv[i];
        if (bp <= c->pb[i]) {
            /* down (always, as each part keeps at most its polygons): in
             * order, each shifted as it moves, one pass over them, not
             * two (the dragon at 1920x1080 on two threads moves 260k) */
            ScreenPoly *dst = sp->polys + bp;
            const ScreenPoly *src = sp->polys + c->pb[i];
            for (uint32_t q = 0; q < part->npolys; q++) {
                ScreenPoly p = src[q];
                p.first += bv;
                dst[q] = p;
            }
        } else {
            memmove(sp->polys + bp, sp->polys + c->pb[i], (size_t)part->npolys * sizeof *sp->polys);
            for (uint32_t q = 0; q < part->npolys; q++)
                sp->polys[bp + q].first += bv;
        }
        for (uint32_t q = c->inst0[i]; !sp->no_map && q < c->inst0[i] + c->ninst[i]; q++)
            if (sp->map[q] >= 0)
                sp->map[q] += (int32_t)bp;
    }
}

/* How many threads to split object o over: sp->threads (0 = every core),
 * and no more than one per PART_MIN polygons. 1 = the caller alone. */
static int object_parts(const ScreenPolys *sp, const Object *o)
{
    int t = sp->threads > 0 ? sp->threads : sp->work->ncpus;
    if (t > SCREEN_MAX_THREADS)
        t = SCREEN_MAX_THREADS;
    uint32_t most = o->poly_count / PART_MIN;
    return most < (uint32_t)t ? (most ? (int)most : 1) : t;
}

/* The pool of helpers for `parts` parts, made (again) when the thread
 * count asks for more than it has; NULL: the caller does every part. */
static Pool *work_pool(ScreenWork *w, int parts)
{
    if (parts < 2)
        return NULL;
    if (!w->pool || w->pool_want < parts - 1) {
        pool_free(w->pool);
        w->pool = pool_create(parts - 1);
        w->pool_want = parts - 1;
    }
    return w->pool;
}

/* The cut of object o, when a plane cuts it, for its polygons' job. */
static void object_cut(RangeJob *j, const ScreenPolys *sp, const Scene *s, const Object *o)
{
    const SectionCut *c = sp->cut;
    int oi = (int)(o - s->objs);
    if (c && c->nplanes && c->key == s && c->touched[oi]) {
        j->cut = c;
        j->cmask = c->mask[o->mesh - s->meshes];
    }
}

/* Part `part` (its window and clip buffers are its own, whichever worker
 * takes it). */
static void range_part(void *arg, int part, int worker)
{
    (void)worker;
    RangeJob *j = (RangeJob *)arg + part;
    j->rc = project_range(j);
}

/* Object o's polygons in `parts` consecutive parts: part 0 on the caller,
 * the others on helpers. Each part writes into its own window of sp's
 * arrays, past the room the parts before it can need; then the parts
 * move down in order: no second set of buffers. Returns 0 when done, 1
 * when a part's clipping outgrew its window (rare: sp is as it was and
 * the caller projects the object again on one thread), -1 on out of
 * memory. */
static int project_parts(ScreenPolys *sp, const Scene *s, const Object *o, const Proj *pj, const Mat4 *mv,
                         ScreenWork *w, Pool *pool, uint32_t inst, int parts, int simd)
{
    uint32_t k[SCREEN_MAX_THREADS + 1], vb[SCREEN_MAX_THREADS + 1];
    uint64_t end = sp->nverts;
    for (int i = 0; i <= parts; i++)
        k[i] = o->poly_first + (uint32_t)((uint64_t)o->poly_count * (uint32_t)i / (uint32_t)parts);
    for (int i = 0; i < parts; i++) {
        uint32_t corners = scene_poly_c0(s, k[i + 1]) - scene_poly_c0(s, k[i]);
        vb[i] = (uint32_t)end;
        end += (uint64_t)corners + corners / 16 + 64;
    }
    if (end > UINT32_MAX / 2 ||
        grow_array((void **)&sp->verts, &sp->cap_verts, (uint32_t)end, sizeof *sp->verts))
        return -1;
    vb[parts] = (uint32_t)end;
    ScreenPolys win[SCREEN_MAX_THREADS];
    RangeJob job[SCREEN_MAX_THREADS];
    for (int i = 0; i < parts; i++) {
        win[i] = *sp;
        if (i == 0) {
            win[i].cap_verts = vb[1];   /* part 0 continues sp and may not reach part 1 */
        } else {
            win[i].verts = sp->verts + vb[i];
            win[i].polys = sp->polys + sp->npolys + (k[i] - o->poly_first);
            win[i].cap_verts = vb[i + 1] - vb[i];
            win[i].cap_polys = k[i + 1] - k[i] + 1;
            win[i].nverts = win[i].npolys = 0;
            win[i].in_polys = win[i].culled_back = win[i].culled_empty = 0;
        }
        job[i] = (RangeJob){ &win[i], s, o, pj, mv, &w->sc, &w->clip[i], k[i], k[i + 1],
                             inst + (k[i] - o->poly_first), sp->no_map ? NULL : sp->map, 1, simd, 0, &w->lut,
                             NULL, NULL };
        object_cut(&job[i], sp, s, o);
    }
    pool_run(pool, parts, range_part, job);
    int rc = 0;
    for (int i = 0; i < parts; i++)
        if (job[i].rc == -1 || (job[i].rc && rc != -1))
            rc = job[i].rc;
    if (rc == -1)
        return -1;
    if (rc)
        return 1;
    uint32_t pb[SCREEN_MAX_THREADS], inst0[SCREEN_MAX_THREADS], ninst[SCREEN_MAX_THREADS];
    CompactJob cj = { .sp = sp, .win = win, .pb = pb, .vb = vb, .inst0 = inst0, .ninst = ninst, .parts = parts };
    uint32_t nv = win[0].nverts, np = win[0].npolys;
    for (int i = 1; i < parts; i++) {
        pb[i] = sp->npolys + (k[i] - o->poly_first);
        inst0[i] = job[i].inst0;
        ninst[i] = k[i + 1] - k[i];
        cj.bv[i] = nv;
        cj.bp[i] = np;
        nv += win[i].nverts;
        np += win[i].npolys;
    }
    pool_run(pool, 2, compact_task, &cj);
    sp->nverts = nv;
    sp->npolys = np;
    sp->in_polys = win[0].in_polys;
    sp->culled_back = win[0].culled_back;
    sp->culled_empty = win[0].culled_empty;
    for (int i = 1; i < parts; i++) {
        sp->in_polys += win[i].in_polys;
        sp->culled_back += win[i].culled_back;
        sp->culled_empty += win[i].culled_empty;
    }
    return 0;
}

/* Set sp's size, projection and statistics for a new frame. */
static void frame_begin(ScreenPolys *sp, const Viewport *vp, const Proj *pj)
{
    sp->w = vp->w;
    sp->h = vp->h;
    sp->pixel_aspect = vp->pixel_aspect;
    sp->cull = vp->cull;
    sp->nverts = sp->npolys = 0;
    sp->in_polys = sp->culled_back = sp->culled_empty = sp->helpers = 0;
    sp->persp = pj->persp;
    sp->focal_x = (float)pj->fx;
    sp->focal_y = (float)pj->fy;
    sp->eye_z = (float)pj->eye;
    sp->near_z = (float)pj->n;
    sp->far_z = (float)pj->f;
    sp->depth_scale = (float)pj->dscale;
    sp->depth_bias = (float)pj->dbias;
}

/* Room for every polygon instance and corner of the scene. */
static int frame_room(ScreenPolys *sp, const Scene *s)
{
    uint64_t ninst = 0, ncorners = 0;
    for (int oi = 0; oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        ninst += o->poly_count;
        ncorners += scene_poly_c0(s, o->poly_first + o->poly_count) - scene_poly_c0(s, o->poly_first);
    }
    if (ninst > INT32_MAX || ncorners + 64 > UINT32_MAX / 2)
        return -1;
    if (s->nobjs > sp->cap_objs) {
        uint32_t *q = realloc(sp->map_first, (size_t)s->nobjs * sizeof *q);
        if (!q)
            return -1;
        sp->map_first = q;
        sp->cap_objs = s->nobjs;
    }
    /* every corner at most once, plus a little for clipped outlines */
    if (grow_array((void **)&sp->verts, &sp->cap_verts, (uint32_t)(ncorners + ncorners / 64 + 64), sizeof *sp->verts) ||
        (!sp->no_map && grow_array((void **)&sp->map, &sp->cap_map, (uint32_t)ninst + 1, sizeof *sp->map)) ||
        grow_array((void **)&sp->polys, &sp->cap_polys, (uint32_t)ninst + 1, sizeof *sp->polys))
        return -1;
    return 0;
}

int screen_project(ScreenPolys *sp, const Scene *s, const Viewport *vp)
{
    double t0 = now_ms();
    ScreenWork *w = work_get(sp);
    if (!w)
        return -1;
    Scratch *sc = &w->sc;
    int simd = simd_use(sp->simd);
    Proj pj = { 0 };
    proj_setup(&pj, s, vp);
    frame_begin(sp, vp, &pj);
    if (frame_room(sp, s))
        return -1;
    Mat4 view = camera_view(&s->cam);
    uint32_t inst = 0;
    for (int oi = 0; oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        sp->map_first[oi] = inst;
        if (!o->poly_count)
            continue;
        VertJob vj;
        vj.pos = o->mesh->pos + 3 * (size_t)o->vert_min;
        vj.mv = m4_mul(view, object_matrix(o));
        vj.pj = &pj;
        vj.nv = o->vert_max - o->vert_min + 1;
        if (grow_array((void **)&sc->sv, &sc->cap_sv, vj.nv, sizeof(ScreenVert)) ||
            grow_array((void **)&sc->idx, &sc->cap_idx, vj.nv, sizeof(uint32_t)))
            return -1;
        vj.sv = sc->sv;
        vj.idx = sc->idx;
        vj.simd = simd;
        int parts = object_parts(sp, o), rc = 1;
        Pool *pool = work_pool(w, parts);
        int have = 1 + pool_helpers(pool);
        if (parts > have)
            parts = have;           /* no more threads to be had: fewer parts */
        if (parts > 1)
            sp->helpers = (uint32_t)(parts - 1) > sp->helpers ? (uint32_t)(parts - 1) : sp->helpers;
        /* vertices in chunks of about VERT_CHUNK, taken by whichever
         * thread is free */
        vj.parts = parts > 1 ? (int)(vj.nv / VERT_CHUNK) + parts : 1;
        if (vj.parts > 4 * SCREEN_MAX_THREADS)
            vj.parts = 4 * SCREEN_MAX_THREADS;
        pool_run(pool, vj.parts, verts_part, &vj);
        if (parts > 1 && (rc = project_parts(sp, s, o, &pj, &vj.mv, w, pool, inst, parts, simd)) < 0)
            return -1;
        if (rc) {
            RangeJob j = { sp, s, o, &pj, &vj.mv, sc, &w->clip[0], o->poly_first,
                           o->poly_first + o->poly_count, inst, sp->no_map ? NULL : sp->map, 0, simd, 0, &w->lut,
                           NULL, NULL };
            object_cut(&j, sp, s, o);
            if (project_range(&j))
                return -1;
        }
        inst += o->poly_count;
    }
    if (sp->cut && sp->cut->nplanes && project_caps(sp, s, &pj, &w->clip[0]))
        return -1;
    sp->polys[sp->npolys].first = sp->nverts;   /* sentinel */
    sp->nmap = sp->no_map ? 0 : inst;
    sp->face_sorted = 1;
    sp->ms = now_ms() - t0;
    return 0;
}

/* fprintf unless an earlier write failed; the first failure's errno
 * stays in *err. */
static void put(FILE *f, int *err, const char *fmt, ...)
{
    if (*err)
        return;
    va_list ap;
    va_start(ap, fmt);
    if (vfprintf(f, fmt, ap) < 0)
        *err = errno ? errno : EIO;
    va_end(ap);
}

/* Every write is checked: a full disk must not pass for a short dump.
 * On failure errno is the first failure's. */
int screen_dump_obj(const ScreenPolys *sp, FILE *f)
{
    int err = 0;
    put(f, &err, "# zview screen %d %d\n", sp->w, sp->h);
    for (uint32_t i = 0; i < sp->nverts && !err; i++)
        put(f, &err, "v %.9g %.9g %.9g\n", sp->verts[i].x / (double)SUBPIX,
            sp->verts[i].y / (double)SUBPIX, (double)sp->verts[i].z);
    for (uint32_t p = 0; p < sp->npolys && !err; p++) {
        put(f, &err, "f");
        for (uint32_t k = sp->polys[p].first; k < sp->polys[p + 1].first; k++)
            put(f, &err, " %u", k + 1);
        put(f, &err, " # %d\n", sp->polys[p].face);
    }
    if (!err && (fflush(f) != 0 || ferror(f)))
        err = errno ? errno : EIO;
    errno = err;
    return err ? -1 : 0;
}

