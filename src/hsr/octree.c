/* octree.c: the hierarchical z-buffer, complete mode: an object-space
 * octree walked front to back against the z-pyramid of hzb.h.
 *
 * Once per model (cached in the per-thread state, keyed by the Scene and
 * its polygon and object counts), the polygons of each loaded object are
 * sorted into an octree over their mesh vertex positions: a node splits
 * its polygons by centroid into the octants about the middle of their
 * centroids' box, until a leaf holds at most LEAF_POLYS; every node keeps
 * the tight box of all the vertices of the polygons below it, and its
 * polygons are one contiguous run of a flat index array. Grid copies of an
 * object share its polygon range, so they share its tree.
 *
 * Each frame, per band: objects are taken nearest first (by the nearest
 * corner of their root box in view space), and each tree is walked with a
 * stack, children nearest first (by the view depth of their box centres).
 * A node's 8 box corners are projected with the front end's formulas
 * (project.c proj_point) to the sample rows and columns whose centres lie
 * in their bounding rectangle (widened by SAMPLE_EPS pixels) and to the
 * depth of the nearest corner, lowered by DEPTH_MARGIN: every sample any
 * of its polygons can cover lies in that box, and every depth plane_at()
 * can give there is at least that depth (the box is convex, the projected
 * depth is monotonic in view z, and the margins dwarf the float rounding
 * of the transforms, of the snapping and of the plane). So when the
 * pyramid holds a strictly nearer depth everywhere in the box, no polygon
 * of the node can win a sample and the whole node is skipped; a node with
 * a corner behind the near plane is never culled (its projection is not
 * bounded), one that covers no sample centre of the band is skipped.
 * Leaves draw their polygons through hzb_draw_poly() (the per-polygon
 * zmin test, the z-buffer's exact rasterization, the pyramid marks),
 * finding each one's screen polygon through ScreenPolys.map. An object
 * with few polygons on screen (small or far: most of its map reads -1) is
 * not walked: its root is tested, then its screen polygons, a contiguous
 * run found by face id, are taken in order. Every sample that is written
 * is decided by hsr_wins() on (depth, id), so the front-to-back order
 * changes nothing in the result, which stays byte-identical to the
 * z-buffer's.
 *
 * It wins on deep scenes (many objects one behind another, --grid) and on
 * closed models with culling off: near geometry fills the pyramid first
 * and whole far objects or subtrees are rejected with one test each,
 * without touching their polygons. It loses some of that to memory: a
 * leaf's polygons lie anywhere in the screen polygon array, which the
 * z-buffer reads in order (they are fetched ahead a chunk at a time). */

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "hsr.h"
#include "hzb.h"
#include "scene.h"
#include "zbuffer.h"


#define LEAF_POLYS  128     /* a node with more polygons is split */
#define MAX_DEPTH   20      /* and never deeper than this */
#define FLAT_RATIO  4       /* walk objects flat when under 1/4 of their polygons are on screen */
#define CHUNK       64      /* polygons fetched ahead together */
#define STACK_MAX   (MAX_DEPTH * 7 + 16)
#define NO_TREE     UINT32_MAX

typedef struct {
    float    lo[3], hi[3];  /* object-space box of every vertex of its polygons */
    uint32_t first, count;  /* its polygons (whole subtree): order[first .. first + count) */
    uint32_t child;         /* first child, children contiguous; 0 = leaf (0 is a root) */
    uint32_t nchild;
} OctNode;

/* An object's view for this frame: object space -> view space. */
typedef struct {
    double m[3][4];
    double zfront;          /* view z of its root box's nearest corner */
    int    obj;
    uint32_t root;
    uint32_t sfirst, send;  /* its screen polygons, when known (flat) */
    int    flat;            /* 1: few of its polygons reached the screen: no tree walk */
} ObjView;

typedef struct {
    HzbBase    hz;          /* the z-buffer's state and the pyramid */
    /* the octree, built once per model */
    const Scene *key;
    uint32_t   key_npolys;
    int        key_nobjs;
    const uint32_t *key_corner;
    OctNode   *nodes;
    uint32_t   nnodes, cap_nodes;
    uint32_t  *order;       /* polygon index within its object, per node run */
    uint32_t  *roots;       /* per loaded object, NO_TREE if it has no polygons */
    int        nroots;
    int        built_ok;
    int        lface_sorted;    /* each object's polygons are in face order */
    /* per frame */
    ObjView   *views;
    int        cap_views;
} OctState;

/* ==== building ==== */

static pthread_mutex_t build_lock = PTHREAD_MUTEX_INITIALIZER;

typedef struct {
    float *cen;             /* 3 per polygon: centroid */
    uint32_t *tmp;          /* partition scratch */
    /* the object being built: node boxes come straight from its corners
     * (no per-polygon box array: a big model's build stays small) */
    const Scene *sc;
    const float *pos;
    uint32_t poly_first;
} BuildScratch;

static int new_nodes(OctState *s, uint32_t n, uint32_t *first_out)
{
    if (s->nnodes + n > s->cap_nodes) {
        uint32_t cap = s->cap_nodes ? s->cap_nodes : 256;
        while (cap < s->nnodes + n)
            cap *= 2;
        OctNode *q = realloc(s->nodes, (size_t)cap * sizeof *q);
        if (!q)
            return -1;
        s->nodes = q;
        s->cap_nodes = cap;
    }
    *first_out = s->nnodes;
    memset(&s->nodes[s->nnodes], 0, n * sizeof *s->nodes);
    s->nnodes += n;
    return 0;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* Fill node ni over order[first .. first + count) (polygon indices local
 * to the object, scratch indexed by them) and split it when large. */
static int build_node(OctState *s, BuildScratch *b, uint32_t ni, uint32_t first, uint32_t count, int depth)
{
    uint32_t *ord = s->order + first;
    float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    float clo[3] = { INFINITY, INFINITY, INFINITY }, chi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (uint32_t i = 0; i < count; i++) {
        const float *c = &b->cen[3 * (size_t)ord[i]];
        uint32_t pk = b->poly_first + ord[i];
        for (uint32_t q = b->sc->poly_start[pk]; q < b->sc->poly_start[pk + 1]; q++) {
            const float *v = &b->pos[3 * (size_t)b->sc->poly_corner[q]];
            for (int a = 0; a < 3; a++) {
                lo[a] = fminf(lo[a], v[a]);
                hi[a] = fmaxf(hi[a], v[a]);
            }
        }
        for (int a = 0; a < 3; a++) {
            clo[a] = fminf(clo[a], c[a]);
            chi[a] = fmaxf(chi[a], c[a]);
        }
    }
    OctNode *n = &s->nodes[ni];
    memcpy(n->lo, lo, sizeof lo);
    memcpy(n->hi, hi, sizeof hi);
    n->first = first;
    n->count = count;
    n->child = 0;
    n->nchild = 0;
    if (count <= LEAF_POLYS || depth >= MAX_DEPTH) {
        /* ascending, so that a leaf reads the screen polygons in order */
        qsort(ord, count, sizeof *ord, cmp_u32);
        return 0;
    }
    float mid[3];
    for (int a = 0; a < 3; a++)
        mid[a] = 0.5f * (clo[a] + chi[a]);
    /* octant of each polygon's centroid; counting sort by octant */
    uint32_t cnt[8] = { 0 };
    for (uint32_t i = 0; i < count; i++) {
        const float *c = &b->cen[3 * (size_t)ord[i]];
        int o = (c[0] > mid[0]) | (c[1] > mid[1]) << 1 | (c[2] > mid[2]) << 2;
        cnt[o]++;
    }
    int used = 0;
    for (int o = 0; o < 8; o++)
        used += cnt[o] > 0;
    if (used < 2) {         /* all centroids coincide: nothing to split */
        qsort(ord, count, sizeof *ord, cmp_u32);
        return 0;
    }
    uint32_t start[8], acc = 0;
    for (int o = 0; o < 8; o++) {
        start[o] = acc;
        acc += cnt[o];
    }
    for (uint32_t i = 0; i < count; i++) {
        const float *c = &b->cen[3 * (size_t)ord[i]];
        int o = (c[0] > mid[0]) | (c[1] > mid[1]) << 1 | (c[2] > mid[2]) << 2;
        b->tmp[start[o]++] = ord[i];
    }
    memcpy(ord, b->tmp, count * sizeof *ord);
    uint32_t kids;
    if (new_nodes(s, (uint32_t)used, &kids))
        return -1;
    s->nodes[ni].child = kids;
    s->nodes[ni].nchild = (uint32_t)used;
    uint32_t at = first, k = 0;
    for (int o = 0; o < 8; o++) {
        if (!cnt[o])
            continue;
        if (build_node(s, b, kids + k, at, cnt[o], depth + 1))
            return -1;
        at += cnt[o];
        k++;
    }
    return 0;
}

static void tree_free(OctState *s)
{
    free(s->nodes);
    free(s->order);
    free(s->roots);
    s->nodes = NULL;
    s->order = NULL;
    s->roots = NULL;
    s->nnodes = s->cap_nodes = 0;
    s->nroots = 0;
    s->built_ok = 0;
}

/* Build the trees of every loaded object of the scene. */
static int tree_build(OctState *s, const Scene *sc)
{
    tree_free(s);
    s->key = sc;
    s->key_npolys = sc->npolys;
    s->key_nobjs = sc->nobjs;
    s->key_corner = sc->poly_corner;
    int nb = (int)sc->nbase_objs;
    if (nb <= 0 || nb > sc->nobjs)
        nb = sc->nobjs;
    uint64_t total = 0;
    uint32_t maxp = 0;
    for (int k = 0; k < nb; k++) {
        total += sc->objs[k].poly_count;
        if (sc->objs[k].poly_count > maxp)
            maxp = sc->objs[k].poly_count;
    }
    BuildScratch b = { 0 };
    s->roots = malloc((size_t)(nb > 0 ? nb : 1) * sizeof *s->roots);
    s->order = malloc((size_t)(total > 0 ? total : 1) * sizeof *s->order);
    b.cen = malloc((size_t)(maxp > 0 ? maxp : 1) * 3 * sizeof(float));
    b.tmp = malloc((size_t)(maxp > 0 ? maxp : 1) * sizeof(uint32_t));
    int rc = -1;
    if (!s->roots || !s->order || !b.cen || !b.tmp)
        goto out;
    s->nroots = nb;
    /* the flat walk finds an object's screen polygons by face id */
    s->lface_sorted = 1;
    for (int k = 0; k < nb; k++) {
        const Object *o = &sc->objs[k];
        for (uint32_t i = 1; i < o->poly_count; i++)
            if (sc->poly_lface[o->poly_first + i] < sc->poly_lface[o->poly_first + i - 1])
                s->lface_sorted = 0;
    }
    uint32_t at = 0;
    for (int k = 0; k < nb; k++) {
        const Object *o = &sc->objs[k];
        s->roots[k] = NO_TREE;
        if (!o->poly_count || !o->mesh)
            continue;
        const float *pos = o->mesh->pos;
        b.sc = sc;
        b.pos = pos;
        b.poly_first = o->poly_first;
        for (uint32_t i = 0; i < o->poly_count; i++) {
            uint32_t pk = o->poly_first + i;
            float *c = &b.cen[3 * (size_t)i];
            c[0] = c[1] = c[2] = 0;
            uint32_t c0 = sc->poly_start[pk], c1 = sc->poly_start[pk + 1];
            for (uint32_t q = c0; q < c1; q++) {
                const float *v = &pos[3 * (size_t)sc->poly_corner[q]];
                for (int a = 0; a < 3; a++)
                    c[a] += v[a];
            }
            float inv = c1 > c0 ? 1.0f / (float)(c1 - c0) : 0;
            for (int a = 0; a < 3; a++)
                c[a] *= inv;
            s->order[at + i] = i;
        }
        uint32_t root;
        if (new_nodes(s, 1, &root) || build_node(s, &b, root, at, o->poly_count, 0))
            goto out;
        s->roots[k] = root;
        at += o->poly_count;
    }
    s->built_ok = 1;
    rc = 0;
out:
    free(b.cen);
    free(b.tmp);
    if (rc)
        tree_free(s);
    return rc;
}

/* ==== projecting a node ==== */

/* The front end's projection (project.c proj_point), in double. */
typedef struct {
    int    persp;
    double cx, cy, fx, fy;
    double eye, n, f;       /* persp */
    double dscale, dbias;   /* ortho */
    int    w, y0, y1;       /* the band */
} NodeProj;

/* Depths are lowered by this fraction of (1 + |depth|): far more than the
 * float rounding of the vertex transform, the projection and plane_at()
 * (a few units of 2^-24), far less than depth steps between objects. */
#define DEPTH_MARGIN (1.0 / 4096)
/* Screen positions are widened by this many pixels: some hundred times
 * the float rounding of the vertex transform and the 1/512 pixel of the
 * snapping. */
#define SAMPLE_EPS   0.05

enum { NODE_OFF, NODE_BOX, NODE_OPEN };

/* Screen box [x0, x1) x [ya, yb) of node nd clipped to the band and its
 * conservative least depth. NODE_OFF: it covers no sample of the band;
 * NODE_OPEN: a corner is behind the near plane, no bound (never culled). */
static int node_project(const NodeProj *pp, const ObjView *ov, const OctNode *nd, int box[4], float *zmin_out)
{
    double c[3], h[3], vc[3], e[3];
    for (int a = 0; a < 3; a++) {
        c[a] = 0.5 * ((double)nd->lo[a] + nd->hi[a]);
        h[a] = 0.5 * ((double)nd->hi[a] - nd->lo[a]);
    }
    for (int r = 0; r < 3; r++) {
        const double *m = ov->m[r];
        vc[r] = m[0] * c[0] + m[1] * c[1] + m[2] * c[2] + m[3];
        e[r] = fabs(m[0]) * h[0] + fabs(m[1]) * h[1] + fabs(m[2]) * h[2];
    }
    double xlo, xhi, ylo, yhi, dmin;
    if (!pp->persp) {
        /* affine: the box's extents are those of its centre +- half sizes */
        xlo = pp->cx + pp->fx * (vc[0] - e[0]);
        xhi = pp->cx + pp->fx * (vc[0] + e[0]);
        ylo = pp->cy - pp->fy * (vc[1] + e[1]);
        yhi = pp->cy - pp->fy * (vc[1] - e[1]);
        dmin = pp->dbias - pp->dscale * (vc[2] + e[2]);
    } else {
        /* the convex box projects inside the hull of its projected corners */
        double zmax = vc[2] + e[2];
        if (pp->eye - zmax < pp->n * (1 + 1e-6))
            return NODE_OPEN;
        xlo = ylo = INFINITY;
        xhi = yhi = -INFINITY;
        double ax[3], ay[3];
        for (int a = 0; a < 3; a++) {
            ax[a] = ov->m[0][a] * h[a];
            ay[a] = ov->m[1][a] * h[a];
        }
        double az[3] = { ov->m[2][0] * h[0], ov->m[2][1] * h[1], ov->m[2][2] * h[2] };
        for (int k = 0; k < 8; k++) {
            double sx = k & 1 ? 1 : -1, sy = k & 2 ? 1 : -1, sz = k & 4 ? 1 : -1;
            double x = vc[0] + sx * ax[0] + sy * ax[1] + sz * ax[2];
            double y = vc[1] + sx * ay[0] + sy * ay[1] + sz * ay[2];
            double z = vc[2] + sx * az[0] + sy * az[1] + sz * az[2];
            double ze = pp->eye - z;
            if (ze < pp->n * (1 + 1e-6))
                return NODE_OPEN;
            double px = pp->cx + pp->fx * x / ze, py = pp->cy - pp->fy * y / ze;
            xlo = fmin(xlo, px);
            xhi = fmax(xhi, px);
            ylo = fmin(ylo, py);
            yhi = fmax(yhi, py);
        }
        double ze = pp->eye - zmax;
        dmin = pp->f / (pp->f - pp->n) * (1 - pp->n / ze);
    }
    /* samples i with xlo <= i + 0.5 <= xhi, widened by SAMPLE_EPS for the
     * rounding of the vertices and of their snapping (1/512 pixel) */
    const double big = 1e8;
    xlo = fmax(fmin(xlo, big), -big);
    xhi = fmax(fmin(xhi, big), -big);
    ylo = fmax(fmin(ylo, big), -big);
    yhi = fmax(fmin(yhi, big), -big);
    int x0 = (int)ceil(xlo - 0.5 - SAMPLE_EPS), x1 = (int)floor(xhi - 0.5 + SAMPLE_EPS) + 1;
    int ya = (int)ceil(ylo - 0.5 - SAMPLE_EPS), yb = (int)floor(yhi - 0.5 + SAMPLE_EPS) + 1;
    if (x0 < 0) x0 = 0;
    if (x1 > pp->w) x1 = pp->w;
    if (ya < pp->y0) ya = pp->y0;
    if (yb > pp->y1) yb = pp->y1;
    if (x0 >= x1 || ya >= yb)
        return NODE_OFF;
    box[0] = x0;
    box[1] = x1;
    box[2] = ya;
    box[3] = yb;
    *zmin_out = (float)(dmin - (1 + fabs(dmin)) * DEPTH_MARGIN);
    return NODE_BOX;
}

static inline double view_z(const ObjView *ov, const OctNode *nd)
{
    const double *m = ov->m[2];
    return 0.5 * (m[0] * ((double)nd->lo[0] + nd->hi[0]) + m[1] * ((double)nd->lo[1] + nd->hi[1]) +
                  m[2] * ((double)nd->lo[2] + nd->hi[2])) + m[3];
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
        s = NULL;
    }
    return s;
}

static void oct_destroy(void *st)
{
    OctState *s = st;
    if (!s)
        return;
    hzb_base_free(&s->hz);
    tree_free(s);
    free(s->views);
    free(s);
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
static void draw_node_polys(OctState *s, const ScreenPolys *sp, const int32_t *map, const OctNode *nd,
                            FrameBufs *fb, int y0, int y1, HsrStats *st)
{
    const uint32_t *ord = s->order + nd->first;
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

static void walk_object(OctState *s, const HsrInput *in, const NodeProj *pp, const ObjView *ov,
                        FrameBufs *fb, HsrStats *st)
{
    const ScreenPolys *sp = in->sp;
    const int32_t *map = sp->map + sp->map_first[ov->obj];
    if (ov->flat) {
        /* Most of its polygons cover no sample (a far or small object):
         * the tree would mostly read their -1 in the map. Test the root,
         * then take its screen polygons in order. */
        const OctNode *nd = &s->nodes[ov->root];
        int box[4];
        float zmin;
        st->nodes_visited++;
        int kind = node_project(pp, ov, nd, box, &zmin);
        if (kind == NODE_OFF)
            return;
        if (kind == NODE_BOX && hzb_pyr_hidden(&s->hz.pyr, box[0], box[1], box[2], box[3], zmin)) {
            st->nodes_culled++;
            st->polys_culled += ov->send - ov->sfirst;
            st->polys_in += ov->send - ov->sfirst;
            return;
        }
        for (uint32_t i = ov->sfirst; i < ov->send; i++)
            hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, i, fb, pp->y0, pp->y1, st);
        return;
    }
    uint32_t stack[STACK_MAX];
    int top = 0;
    stack[top++] = ov->root;
    while (top > 0) {
        const OctNode *nd = &s->nodes[stack[--top]];
        st->nodes_visited++;
        int box[4];
        float zmin;
        int kind = node_project(pp, ov, nd, box, &zmin);
        if (kind == NODE_OFF)
            continue;
        if (kind == NODE_BOX && hzb_pyr_hidden(&s->hz.pyr, box[0], box[1], box[2], box[3], zmin)) {
            st->nodes_culled++;
            st->polys_culled += nd->count;
            st->polys_in += nd->count;
            continue;
        }
        if (!nd->nchild) {
            draw_node_polys(s, sp, map, nd, fb, pp->y0, pp->y1, st);
            continue;
        }
        /* children far to near onto the stack, so the nearest pops first */
        uint32_t kid[8];
        double kz[8];
        int nk = (int)nd->nchild;
        for (int k = 0; k < nk; k++) {
            uint32_t c = nd->child + (uint32_t)k;
            double z = view_z(ov, &s->nodes[c]);
            int at = k;
            while (at > 0 && kz[at - 1] > z) {
                kz[at] = kz[at - 1];
                kid[at] = kid[at - 1];
                at--;
            }
            kz[at] = z;
            kid[at] = c;
        }
        for (int k = 0; k < nk; k++) {
            const OctNode *c = &s->nodes[kid[k]];
            if (top == STACK_MAX) {
                /* cannot happen (depth <= MAX_DEPTH holds at most 7
                 * pending siblings a level), but never drop polygons */
                draw_node_polys(s, sp, map, c, fb, pp->y0, pp->y1, st);
                continue;
            }
            stack[top++] = kid[k];
            /* a leaf's map entries are scattered: fetch them before it pops */
            if (!c->nchild)
                for (uint32_t i = 0; i < c->count; i += 2)
                    __builtin_prefetch(&map[s->order[c->first + i]]);
        }
    }
}

static void oct_render(void *st, const HsrInput *in, FrameBufs *fb, int y0, int y1, HsrStats *stats)
{
    OctState *s = st;
    const Scene *sc = in->scene;
    const ScreenPolys *sp = in->sp;
    double t0 = now_ms();
    hzb_pyr_begin(&s->hz.pyr, fb, y0, y1);
    if (sc && (s->key != sc || s->key_npolys != sc->npolys || s->key_nobjs != sc->nobjs ||
               s->key_corner != sc->poly_corner)) {
        /* Bands build their trees one at a time, so that only one build's
         * scratch (tens of MB on a big model) is alive at once. */
        pthread_mutex_lock(&build_lock);
        tree_build(s, sc);
        pthread_mutex_unlock(&build_lock);
    }
    stats->build_ms += now_ms() - t0;

    if (!sc || !s->built_ok || sc->nobjs == 0) {
        /* no scene to build from: the plain hzb over every polygon */
        for (uint32_t i = 0; i < sp->npolys; i++)
            hzb_draw_poly(&s->hz.pyr, s->hz.zb, sp, i, fb, y0, y1, stats);
        return;
    }
    if (sc->nobjs > s->cap_views) {
        ObjView *v = realloc(s->views, (size_t)sc->nobjs * sizeof *v);
        if (!v)
            return;
        s->views = v;
        s->cap_views = sc->nobjs;
    }
    NodeProj pp = {
        .persp = sp->persp, .cx = sp->w * 0.5, .cy = sp->h * 0.5,
        .fx = sp->focal_x, .fy = sp->focal_y, .eye = sp->eye_z, .n = sp->near_z, .f = sp->far_z,
        .dscale = sp->depth_scale, .dbias = sp->depth_bias, .w = sp->w, .y0 = y0, .y1 = y1,
    };
    Mat4 view = camera_view(&sc->cam);
    /* The front end emits objects in order and each object's polygons in
     * face order, so when face ids grow with the object index, an
     * object's screen polygons are the run of faces in its range. */
    int ordered = s->lface_sorted;
    for (int oi = 1; oi < sc->nobjs && ordered; oi++)
        ordered = sc->objs[oi].face_base >= sc->objs[oi - 1].face_base + (int32_t)sc->objs[oi - 1].face_count;
    uint32_t run = 0;
    int nv = 0;
    for (int oi = 0; oi < sc->nobjs; oi++) {
        const Object *o = &sc->objs[oi];
        if (!o->poly_count)
            continue;
        ObjView *ov = &s->views[nv++];
        ov->obj = oi;
        ov->root = NO_TREE;
        int b = oi % s->nroots;
        const Object *base = &sc->objs[b];
        if (s->roots[b] != NO_TREE && base->poly_first == o->poly_first &&
            base->poly_count == o->poly_count && base->mesh == o->mesh)
            ov->root = s->roots[b];
        /* the front end's float matrix, widened */
        Mat4 mv = m4_mul(view, object_matrix(o));
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                ov->m[r][c] = mv.m[r][c];
        ov->flat = 0;
        if (ov->root == NO_TREE) {
            ov->zfront = INFINITY;
            continue;
        }
        if (ordered) {
            ov->sfirst = run = first_face_at(sp, run, o->face_base);
            ov->send = run = first_face_at(sp, run, o->face_base + (int32_t)o->face_count);
            ov->flat = (uint64_t)(ov->send - ov->sfirst) * FLAT_RATIO < o->poly_count;
        }
        const OctNode *nd = &s->nodes[ov->root];
        double zc = view_z(ov, nd), ez = 0;
        for (int a = 0; a < 3; a++)
            ez += fabs(ov->m[2][a]) * 0.5 * ((double)nd->hi[a] - nd->lo[a]);
        ov->zfront = zc + ez;
    }
    qsort(s->views, (size_t)nv, sizeof *s->views, cmp_front);
    for (int k = 0; k < nv; k++) {
        const ObjView *ov = &s->views[k];
        if (ov->root == NO_TREE)
            draw_object_flat(s, in, ov->obj, fb, y0, y1, stats);
        else
            walk_object(s, in, &pp, ov, fb, stats);
    }
}

const HsrAlgo hsr_hzb_octree = {
    .name = "hzb-octree",
    .summary = "hierarchical z-buffer with an object-space octree walked front to back",
    .create = oct_create,
    .destroy = oct_destroy,
    .render = oct_render,
};
