/* octree.c: the hierarchical z-buffer, complete mode: an object-space
 * octree walked front to back against the z-pyramid of hzb.h.
 *
 * Once per model (octree_build.c; cached in the runner's shared state,
 * keyed by the Scene, its generation (Scene.gen: the viewer adds and
 * removes objects in place) and its polygon and object counts), the
 * polygons of each loaded object are sorted into an octree over their
 * mesh vertex positions: a node splits
 * its polygons by centroid into the octants about the middle of their
 * centroids' box, until a leaf holds at most LEAF_POLYS; a node's
 * polygons are one contiguous run of a flat index array, and every
 * polygon knows its leaf. Grid copies of an object share its polygon
 * range, so they share its tree.
 *
 * Each frame, per band, objects are taken nearest first (by the nearest
 * corner of their box in view space). Before an object's tree is walked,
 * its node bounds are gathered from the front end's own output: one pass
 * over the object's screen polygons in order puts each polygon's sample
 * box (clipped to the band) and its zmin (the front end's safe lower
 * bound of every depth plane_at() can give inside it) into its leaf, and
 * one pass over the nodes, children before parents, folds them upwards.
 * A node's bound is therefore exactly the union of its polygons' own
 * bounds: when the pyramid holds a strictly nearer depth everywhere in
 * its box, each of its polygons would fail the per-polygon test of
 * hzb_draw_poly() too, so the whole node is skipped without changing the
 * result. No margin or projection of object-space boxes is involved: an
 * earlier version projected each node's box and widened it by fixed
 * margins, which the float rounding of the vertex transform outgrew on
 * small objects far from the origin (a nearer face was lost).
 *
 * The walk is a stack, children nearest first (by their zmin). Leaves
 * draw their polygons through hzb_draw_poly() (the per-polygon zmin
 * test, the z-buffer's exact rasterization, the pyramid marks). An
 * object with few polygons on screen (small or far: most of its map reads
 * -1) is not walked: its screen polygons, a contiguous run found by face
 * id, are drawn in order. Every sample that is written is decided by
 * hsr_wins() on (depth, id), so the order changes nothing in the result,
 * which stays byte-identical to the z-buffer's.
 *
 * It wins on deep scenes (many objects one behind another, --grid) and on
 * closed models with culling off: near geometry fills the pyramid first
 * and whole far subtrees are rejected with one test each, without
 * rasterizing their polygons.
 *
 * The trees belong to the runner, not to a band: every band walks the
 * same trees (with bounds of its own). For a big scene with more than one
 * thread they are built on a thread of their own, started by the first
 * frame that needs them; until they are ready, frames draw every polygon
 * through hzb_draw_poly() in scene order (the plain hzb: the same
 * picture) and say so in HsrStats.building. A small scene (they take a
 * few milliseconds), or one thread (no thread may be started), builds
 * them before the first frame's bands. The builder is told to stop and
 * joined when the runner goes, or when a frame brings another scene.
 *
 * Implements the complete mode of N. Greene, M. Kass and G. Miller,
 * "Hierarchical Z-Buffer Visibility", SIGGRAPH 1993: object-space octree
 * cubes tested against the z-pyramid front to back, a hidden cube
 * culling all it holds. Octree subdivision as in D. Meagher, "Geometric
 * Modeling Using Octree Encoding", CGIP 19(2), 1982.
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "hsr.h"
#include "hzb.h"
#include "octree.h"
#include "simd.h"
#include "zbuffer.h"

#define FLAT_RATIO  4       /* draw objects flat when under 1/4 of their polygons are on screen */
#define CHUNK       64      /* polygons fetched ahead together */
#define STACK_MAX   (MAX_DEPTH * 7 + 16)

/* A node's bound in this band, gathered from its screen polygons. */
typedef struct {
    int32_t  x0, x1, y0, y1;    /* union of their sample boxes; empty when x0 >= x1 */
    float    zmin;              /* least of their zmin */
    uint32_t n;                 /* how many */
} NodeBound;

/* An object's place in this frame's front-to-back order. */
typedef struct {
    double   zfront;        /* view z of its box's nearest corner (larger is nearer) */
    int      obj;
    int      tree;          /* index of its loaded object's tree, -1 for none */
    uint32_t sfirst, send;  /* its screen polygons: list positions, or of sidx when reordered */
    const uint32_t *sidx;   /* NULL: the list is in face order */
    int      flat;          /* 1: few of its polygons reached the screen: no tree walk */
} ObjView;

/* Per band. */
typedef struct {
    HzbBase    hz;          /* the z-buffer's state and the pyramid */
    OctShared *shared;      /* the runner's, or NULL */
    OctShared  own;         /* when rendered without a runner's shared state */
    ObjView   *views;
    int        cap_views;
    NodeBound *bound;       /* per node of the object being walked */
    uint32_t   cap_bound;
    /* a reordered list (--order): list positions grouped by object, each
     * group in the list's order; NULL when the list is in face order */
    uint32_t  *sidx;
    uint32_t   cap_sidx;
    uint32_t  *ostart;      /* nobjs + 1 group starts */
    int        cap_ostart;
} OctState;

/* ==== the bounds of one object's nodes in a band ==== */

static inline void bound_add(NodeBound *b, int32_t x0, int32_t x1, int32_t y0, int32_t y1, float zmin, uint32_t n)
{
    if (x0 < b->x0) b->x0 = x0;
    if (x1 > b->x1) b->x1 = x1;
    if (y0 < b->y0) b->y0 = y0;
    if (y1 > b->y1) b->y1 = y1;
    /* a NaN bound must not be lost: it culls nothing */
    if (!(zmin >= b->zmin))
        b->zmin = zmin == zmin ? zmin : -INFINITY;
    b->n += n;
}

/* Gather the bounds of tree t's nodes for object instance oi from its
 * screen polygons that reach rows [y0, y1): each into its leaf, then the
 * leaves up to the root (children come after their parent). */
static void gather_bounds(OctState *s, const OctTree *tr, const ScreenPolys *sp, const Object *o, int oi, int t,
                          int y0, int y1)
{
    uint32_t r = tr->roots[t], e = tr->node_end[t];
    NodeBound *bd = s->bound;
    for (uint32_t n = r; n < e; n++)
        bd[n] = (NodeBound){ INT32_MAX, INT32_MIN, INT32_MAX, INT32_MIN, INFINITY, 0 };
    const int32_t *map = sp->map + sp->map_first[oi];
    const uint32_t *leaf = tr->leaf + tr->base[t];
    for (uint32_t i = 0; i < o->poly_count; i++) {
        int32_t q = map[i];
        if (q < 0)
            continue;
        const ScreenPoly *p = &sp->polys[q];
        int32_t ya = p->y0 > y0 ? p->y0 : y0, yb = p->y1 < y1 ? p->y1 : y1;
        if (ya >= yb)
            continue;
        bound_add(&bd[leaf[i]], p->x0, p->x1, ya, yb, p->zmin, 1);
    }
    for (uint32_t n = e; n-- > r;) {
        const OctNode *nd = &tr->nodes[n];
        for (uint32_t c = nd->child; c < nd->child + nd->nchild; c++)
            if (bd[c].n)
                bound_add(&bd[n], bd[c].x0, bd[c].x1, bd[c].y0, bd[c].y1, bd[c].zmin, bd[c].n);
    }
}

/* First screen polygon at or after lo whose face id is >= face (they are
 * sorted by face id). */
static uint32_t first_face_at(const ScreenPolys *sp, uint32_t lo, int32_t face)
{
    uint32_t hi = sp->npolys;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (sp->polys[mid].face < face)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

static int cmp_front(const void *a, const void *b)
{
    const ObjView *p = a, *q = b;
    if (p->zfront != q->zfront)
        return p->zfront > q->zfront ? -1 : 1;     /* larger view z is nearer */
    return p->obj - q->obj;
}

/* ==== the algorithm ==== */

static void *oct_create(void)
{
    OctState *s = calloc(1, sizeof *s);
    if (s && hzb_base_init(&s->hz)) {
        free(s);
        return NULL;
    }
    if (s)
        octree_shared_init(&s->own, 0);
    return s;
}

static void oct_destroy(void *st)
{
    OctState *s = st;
    if (!s)
        return;
    hzb_base_free(&s->hz);
    octree_shared_free(&s->own);
    free(s->views);
    free(s->bound);
    free(s->sidx);
    free(s->ostart);
    free(s);
}

static void *oct_create_shared(int nthreads)
{
    OctShared *sh = malloc(sizeof *sh);
    if (sh)
        octree_shared_init(sh, nthreads > 1);
    return sh;
}

static void oct_destroy_shared(void *p)
{
    if (!p)
        return;
    octree_shared_free(p);
    free(p);
}

static void oct_share(void *st, void *sh)
{
    ((OctState *)st)->shared = sh;
}

static void oct_frame_begin(void *p, const HsrInput *in)
{
    octree_shared_frame_begin(p, in->scene, simd_use(in->simd));
}

/* Every polygon of object oi, in order: the fallback when it has no tree. */
static void draw_object_flat(OctState *s, const HsrInput *in, int oi, FrameBufs *fb, int y0, int y1, HsrStats *st)
{
    const ScreenPolys *sp = in->sp;
    const Object *o = &in->scene->objs[oi];
    const int32_t *map = sp->map + sp->map_first[oi];
    for (uint32_t i = 0; i < o->poly_count; i++)
        if (map[i] >= 0)
            hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, (uint32_t)map[i], fb, y0, y1, st);
}

/* Every polygon of node nd's subtree. The screen polygons are gathered
 * first and fetched (then their corners) ahead, a chunk at a time: they
 * lie anywhere in the object's range. */
static void draw_node_polys(OctState *s, const OctTree *tr, const ScreenPolys *sp, const int32_t *map,
                            const OctNode *nd, FrameBufs *fb, int y0, int y1, HsrStats *st)
{
    const uint32_t *ord = tr->order + nd->first;
    for (uint32_t c = 0; c < nd->count; c += CHUNK) {
        uint32_t e = nd->count - c < CHUNK ? nd->count : c + CHUNK;
        int32_t idx[CHUNK];
        uint32_t n = 0;
        for (uint32_t i = c; i < e; i++) {
            int32_t q = map[ord[i]];
            if (q >= 0) {
                __builtin_prefetch(&sp->polys[q]);
                idx[n++] = q;
            }
        }
        for (uint32_t i = 0; i < n; i++)
            __builtin_prefetch(&sp->verts[sp->polys[idx[i]].first]);
        for (uint32_t i = 0; i < n; i++)
            hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, (uint32_t)idx[i], fb, y0, y1, st);
    }
}

/* Is node n (its bound gathered) hidden? Counts it either way. */
static int node_hidden(OctState *s, uint32_t n, HsrStats *st)
{
    const NodeBound *b = &s->bound[n];
    st->nodes_visited++;
    if (!hzb_pyr_hidden(&s->hz.pyr, b->x0, b->x1, b->y0, b->y1, b->zmin))
        return 0;
    st->nodes_culled++;
    st->polys_culled += b->n;
    st->polys_in += b->n;
    return 1;
}

static void walk_object(OctState *s, const OctTree *tr, const HsrInput *in, const ObjView *ov, FrameBufs *fb,
                        int y0, int y1, HsrStats *st)
{
    const ScreenPolys *sp = in->sp;
    if (ov->flat) {
        /* Most of its polygons cover no sample (a far or small object):
         * the tree would mostly read their -1 in the map. Take its
         * screen polygons in order, each tested on its own. */
        for (uint32_t i = ov->sfirst; i < ov->send; i++)
            hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, ov->sidx ? ov->sidx[i] : i, fb, y0, y1, st);
        return;
    }
    const Object *o = &in->scene->objs[ov->obj];
    double tg = now_ms();
    gather_bounds(s, tr, sp, o, ov->obj, ov->tree, y0, y1);
    st->build_ms += now_ms() - tg;      /* per-frame upkeep of the structure */
    const int32_t *map = sp->map + sp->map_first[ov->obj];
    const NodeBound *bd = s->bound;
    uint32_t root = tr->roots[ov->tree];
    if (!bd[root].n)
        return;
    uint32_t stack[STACK_MAX];
    int top = 0;
    stack[top++] = root;
    while (top > 0) {
        uint32_t ni = stack[--top];
        const OctNode *nd = &tr->nodes[ni];
        if (node_hidden(s, ni, st))
            continue;
        if (!nd->nchild) {
            draw_node_polys(s, tr, sp, map, nd, fb, y0, y1, st);
            continue;
        }
        /* children with polygons in the band, far to near onto the stack,
         * so that the nearest pops first */
        uint32_t kid[8];
        float kz[8];
        int nk = 0;
        for (uint32_t c = nd->child; c < nd->child + nd->nchild; c++) {
            if (!bd[c].n)
                continue;
            float z = bd[c].zmin;
            int at = nk++;
            while (at > 0 && kz[at - 1] < z) {
                kz[at] = kz[at - 1];
                kid[at] = kid[at - 1];
                at--;
            }
            kz[at] = z;
            kid[at] = c;
        }
        for (int k = 0; k < nk; k++) {
            const OctNode *c = &tr->nodes[kid[k]];
            if (top == STACK_MAX) {
                /* cannot happen (depth <= MAX_DEPTH holds at most 7
                 * pending siblings a level), but never drop polygons */
                draw_node_polys(s, tr, sp, map, c, fb, y0, y1, st);
                continue;
            }
            stack[top++] = kid[k];
        }
    }
}

/* Points and lines (prims.c) are in no object's map: their polygons
 * follow the faces' at the end of the list, with ids past every face's.
 * Each is drawn through the per-polygon test. When the list was
 * reordered (--order), stragglers anywhere are found by their ids. */
static void draw_unmapped(OctState *s, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *st)
{
    const ScreenPolys *sp = in->sp;
    uint32_t nf = in->scene->nfaces, i = sp->npolys;
    while (i > 0 && (uint32_t)sp->polys[i - 1].face >= nf)
        i--;
    if (!sp->face_sorted)
        for (uint32_t k = 0; k < i; k++)
            if ((uint32_t)sp->polys[k].face >= nf)
                hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, k, fb, y0, y1, st);
    for (; i < sp->npolys; i++)
        hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, i, fb, y0, y1, st);
}

/* View z of the nearest corner of object o's box (larger is nearer). */
static double object_front(const Mat4 *view, const Object *o)
{
    Mat4 mv = m4_mul(*view, object_matrix(o));
    const float *m = mv.m[2];
    double z = m[0] * (double)o->centre.x + m[1] * (double)o->centre.y + m[2] * (double)o->centre.z + m[3];
    return z + fabs(m[0]) * o->half.x + fabs(m[1]) * o->half.y + fabs(m[2]) * o->half.z;
}

/* A reordered list (--order): each object's screen polygons gathered, in
 * the list's order, by one counting sort over the objects. Without it the
 * objects' runs are unknown, every object walks its whole tree (gathering
 * bounds over every node), and a sparse one costs many times what its few
 * polygons drawn one by one do: the octree's time would then measure this
 * bookkeeping, not the order. Returns -1 out of memory (no groups). */
static int group_by_object(OctState *s, const Scene *sc, const ScreenPolys *sp)
{
    if (sp->npolys > s->cap_sidx) {
        uint32_t *q = realloc(s->sidx, (size_t)sp->npolys * sizeof *q);
        if (!q)
            return -1;
        s->sidx = q;
        s->cap_sidx = sp->npolys;
    }
    if (sc->nobjs + 1 > s->cap_ostart) {
        uint32_t *q = realloc(s->ostart, (size_t)(sc->nobjs + 1) * sizeof *q);
        if (!q)
            return -1;
        s->ostart = q;
        s->cap_ostart = sc->nobjs + 1;
    }
    uint32_t *start = s->ostart;
    memset(start, 0, (size_t)(sc->nobjs + 1) * sizeof *start);
    for (uint32_t i = 0; i < sp->npolys; i++) {
        uint32_t f = (uint32_t)sp->polys[i].face;
        if (f < sc->nfaces)
            start[scene_face_obj(sc, f) + 1]++;
    }
    for (int o = 0; o < sc->nobjs; o++)
        start[o + 1] += start[o];
    /* scatter with start[o] as the cursor: afterwards start[o] is the
     * group's end, the next group's start; shifted back below */
    for (uint32_t i = 0; i < sp->npolys; i++) {
        uint32_t f = (uint32_t)sp->polys[i].face;
        if (f < sc->nfaces)
            s->sidx[start[scene_face_obj(sc, f)]++] = i;
    }
    memmove(start + 1, start, (size_t)sc->nobjs * sizeof *start);
    start[0] = 0;
    return 0;
}

static void oct_render(void *st, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    OctState *s = st;
    const Scene *sc = in->scene;
    const ScreenPolys *sp = in->sp;
    double t0 = now_ms();
    int simd = simd_use(in->simd);
    hzb_base_begin(&s->hz, fb, y0, y1, simd);
    OctShared *sh = s->shared;
    if (!sh) {
        /* rendered without a runner (a band on its own): trees of its own */
        sh = &s->own;
        octree_shared_frame_begin(sh, sc, simd);
    }
    const OctTree *tr = sh->use;
    stats->build_ms += now_ms() - t0;
    if (!tr) {
        /* no trees (yet, or no scene to build from): the plain hzb over
         * every polygon, the same picture */
        stats->building |= sh->building;
        for (uint32_t i = 0; i < sp->npolys; i++)
            hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, i, fb, y0, y1, stats);
        return;
    }
    if (tr->nnodes > s->cap_bound) {
        NodeBound *q = realloc(s->bound, (size_t)tr->nnodes * sizeof *q);
        if (!q) {
            for (uint32_t i = 0; i < sp->npolys; i++)
                hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, i, fb, y0, y1, stats);
            return;
        }
        s->bound = q;
        s->cap_bound = tr->nnodes;
    }
    if (sc->nobjs > s->cap_views) {
        ObjView *v = realloc(s->views, (size_t)sc->nobjs * sizeof *v);
        if (!v)
            return;
        s->views = v;
        s->cap_views = sc->nobjs;
    }
    Mat4 view = camera_view(&sc->cam);
    /* The front end emits objects in order and each object's polygons in
     * face order (unless --order changed it), so when face ids grow with
     * the object index, an object's screen polygons are the run of faces
     * in its range. */
    int ordered = tr->lface_sorted && sp->face_sorted;
    for (int oi = 1; oi < sc->nobjs && ordered; oi++)
        ordered = sc->objs[oi].face_base >= sc->objs[oi - 1].face_base + (int32_t)sc->objs[oi - 1].face_count;
    int grouped = !ordered && group_by_object(s, sc, sp) == 0;
    uint32_t run = 0;
    int nv = 0;
    for (int oi = 0; oi < sc->nobjs; oi++) {
        const Object *o = &sc->objs[oi];
        if (!o->poly_count)
            continue;
        ObjView *ov = &s->views[nv++];
        ov->obj = oi;
        ov->tree = -1;
        ov->flat = 0;
        ov->sidx = NULL;
        int b = oi % tr->nroots;
        const Object *base = &sc->objs[b];
        if (tr->roots[b] != NO_TREE && base->poly_first == o->poly_first &&
            base->poly_count == o->poly_count && base->mesh == o->mesh)
            ov->tree = b;
        if (ov->tree < 0) {
            ov->zfront = INFINITY;
            continue;
        }
        if (ordered) {
            ov->sfirst = run = first_face_at(sp, run, o->face_base);
            ov->send = run = first_face_at(sp, run, o->face_base + (int32_t)o->face_count);
            ov->flat = (uint64_t)(ov->send - ov->sfirst) * FLAT_RATIO < o->poly_count;
        } else if (grouped) {
            ov->sidx = s->sidx;
            ov->sfirst = s->ostart[oi];
            ov->send = s->ostart[oi + 1];
            ov->flat = (uint64_t)(ov->send - ov->sfirst) * FLAT_RATIO < o->poly_count;
        }
        ov->zfront = object_front(&view, o);
    }
    qsort(s->views, (size_t)nv, sizeof *s->views, cmp_front);
    for (int k = 0; k < nv; k++) {
        const ObjView *ov = &s->views[k];
        if (ov->tree < 0)
            draw_object_flat(s, in, ov->obj, fb, y0, y1, stats);
        else
            walk_object(s, tr, in, ov, fb, y0, y1, stats);
    }
    draw_unmapped(s, in, fb, y0, y1, stats);
}

const HsrAlgo hsr_hzb_octree = {
    .name = "hzb-octree",
    .summary = "hierarchical z-buffer with an object-space octree walked front to back",
    .create = oct_create,
    .destroy = oct_destroy,
    .render = oct_render,
    .create_shared = oct_create_shared,
    .destroy_shared = oct_destroy_shared,
    .share = oct_share,
    .frame_begin = oct_frame_begin,
    .uses_map = 1,
};

