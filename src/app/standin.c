/* standin.c: a small stand-in for a huge scene, for the first view's
 * renders (firstview.c).
 *
 * Vertex clustering (Rossignac and Borrel, "Multi-resolution 3D
 * approximations for rendering complex scenes", 1993): the world box of
 * the scene is cut into a grid of STANDIN_GRID cells along its longest
 * side, the vertices in a cell become one at their mean, and a triangle
 * whose corners fall in fewer than three cells goes (so does a segment
 * within one cell; points become one a cell). What remains keeps
 * the model's shape to a cell and each face's winding, so a picture of
 * 64 x 48 pixels of it shows what the model's would, at a fraction of
 * the polygons (the 871,414 triangles of the Stanford dragon become
 * 20,304, in 9 ms). Positions are in the world as the objects stand at
 * home; the stand-in is one object standing y-up, whose faces are the
 * stand-in's own (firstview.c needs only their sides). */

#define _DEFAULT_SOURCE         /* strdup */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

#define STANDIN_GRID 64
#define STANDIN_CELLS ((STANDIN_GRID + 1) * (STANDIN_GRID + 1) * (STANDIN_GRID + 1))

/* The grid's cells (every one, a few MB at most: a lookup is one read)
 * and the clusters made in them. */
typedef struct {
    uint32_t *cell;         /* cluster of each cell, UINT32_MAX = none yet */
    uint32_t  n;            /* clusters */
    double   *sum;          /* 3 per cluster: the members' positions summed */
    uint32_t *count;        /* members per cluster */
} Cells;

/* ==== The clusters ==== */

static int cluster_init(Cells *c)
{
    memset(c, 0, sizeof *c);
    c->cell = malloc(STANDIN_CELLS * sizeof *c->cell);
    c->sum = malloc(3 * (size_t)STANDIN_CELLS * sizeof *c->sum);
    c->count = malloc(STANDIN_CELLS * sizeof *c->count);
    if (!c->cell || !c->sum || !c->count)
        return -1;
    memset(c->cell, 0xff, STANDIN_CELLS * sizeof *c->cell);
    return 0;
}

static void cluster_free(Cells *c)
{
    free(c->cell);
    free(c->sum);
    free(c->count);
}

/* The cluster of cell k, made when new. */
static uint32_t cluster_find(Cells *c, uint32_t k)
{
    if (c->cell[k] == UINT32_MAX) {
        c->cell[k] = c->n;
        memset(&c->sum[3 * (size_t)c->n], 0, 3 * sizeof *c->sum);
        c->count[c->n++] = 0;
    }
    return c->cell[k];
}

/* The world box of the loaded objects at home. */
static void world_box(const Scene *s, Vec3 *lo, Vec3 *hi)
{
    *lo = v3(INFINITY, INFINITY, INFINITY);
    *hi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        if (!o->poly_count && !o->point_count && !o->seg_count)
            continue;
        Mat4 m = object_matrix(o);
        for (int k = 0; k < 8; k++) {
            Vec3 c = v3(o->centre.x + (k & 1 ? o->half.x : -o->half.x), o->centre.y + (k & 2 ? o->half.y : -o->half.y),
                        o->centre.z + (k & 4 ? o->half.z : -o->half.z));
            Vec3 w = m4_point(&m, c);
            *lo = v3(fminf(lo->x, w.x), fminf(lo->y, w.y), fminf(lo->z, w.z));
            *hi = v3(fmaxf(hi->x, w.x), fmaxf(hi->y, w.y), fmaxf(hi->z, w.z));
        }
    }
}

/* ==== The stand-in ==== */

/* A growing array of vertex (cluster) indices. */
typedef struct {
    uint32_t *v;
    size_t    n, cap;
} Idx;

static int idx_push(Idx *a, const uint32_t *v, size_t k)
{
    if (a->n + k > a->cap) {
        size_t nc = a->cap ? 2 * a->cap : 65536;
        uint32_t *g = realloc(a->v, nc * sizeof *g);
        if (!g)
            return -1;
        a->v = g;
        a->cap = nc;
    }
    memcpy(&a->v[a->n], v, k * sizeof *v);
    a->n += k;
    return 0;
}

typedef struct {
    Cells     cells;
    uint32_t *vmap;         /* per vertex of the object being walked: its cluster */
    uint8_t  *has_point;    /* per cluster: a point is there already */
    Idx       tri;          /* 3 clusters per triangle */
    Idx       pt;           /* 1 per point */
    Idx       seg;          /* 2 per segment */
} Build;

/* Object o's vertices into clusters (at their world positions). */
static void add_verts(Build *b, const Object *o, Vec3 lo, float inv_cell)
{
    Mat4 m = object_matrix(o);
    const float *pos = o->mesh->pos;
    for (uint32_t v = o->vert_min; v <= o->vert_max; v++) {
        Vec3 w = m4_point(&m, v3(pos[3 * (size_t)v], pos[3 * (size_t)v + 1], pos[3 * (size_t)v + 2]));
        uint32_t ix = (uint32_t)fminf(fmaxf((w.x - lo.x) * inv_cell, 0), STANDIN_GRID);
        uint32_t iy = (uint32_t)fminf(fmaxf((w.y - lo.y) * inv_cell, 0), STANDIN_GRID);
        uint32_t iz = (uint32_t)fminf(fmaxf((w.z - lo.z) * inv_cell, 0), STANDIN_GRID);
        uint32_t k = cluster_find(&b->cells, (ix * (STANDIN_GRID + 1) + iy) * (STANDIN_GRID + 1) + iz);
        b->vmap[v - o->vert_min] = k;
        double *sum = &b->cells.sum[3 * (size_t)k];
        sum[0] += w.x;
        sum[1] += w.y;
        sum[2] += w.z;
        b->cells.count[k]++;
    }
}

/* Object o's polygons (as fans), points and segments, on its clusters:
 * what collapsed to a line or a point goes, points one to a cluster. */
static int add_prims(Build *b, const Scene *s, const Object *o)
{
    const uint32_t *vm = b->vmap, v0 = o->vert_min;
    for (uint32_t p = o->poly_first; p < o->poly_first + o->poly_count; p++) {
        uint32_t c0 = scene_poly_c0(s, p), c1 = scene_poly_c0(s, p + 1);
        for (uint32_t c = c0 + 1; c + 1 < c1; c++) {
            uint32_t t[3] = { vm[s->poly_corner[c0] - v0], vm[s->poly_corner[c] - v0],
                              vm[s->poly_corner[c + 1] - v0] };
            if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2] && idx_push(&b->tri, t, 3))
                return -1;
        }
    }
    for (uint32_t k = 0; k < o->point_count; k++) {
        uint32_t c = vm[object_point_vert(o, k) - v0];
        if (!b->has_point[c] && idx_push(&b->pt, &c, 1))
            return -1;
        b->has_point[c] = 1;
    }
    for (uint32_t k = 0; k < o->seg_count; k++) {
        uint32_t v[2];
        scene_edge_verts(s, o, PRIM_SEG, k, v);
        uint32_t e[2] = { vm[v[0] - v0], vm[v[1] - v0] };
        if (e[0] != e[1] && idx_push(&b->seg, e, 2))
            return -1;
    }
    return 0;
}

/* The clusters, triangles, points and segments (each a polyline of two
 * corners) as a one-object mesh; arrays are taken over. */
static int to_mesh(Build *b, Mesh *m)
{
    memset(m, 0, sizeof *m);
    uint32_t n = b->cells.n, nt = (uint32_t)(b->tri.n / 3), ns = (uint32_t)(b->seg.n / 2);
    m->path = strdup("stand-in");
    m->pos = malloc(3 * (size_t)(n ? n : 1) * sizeof *m->pos);
    m->face_start = malloc(((size_t)nt + 1) * sizeof *m->face_start);
    m->line_start = ns ? malloc(((size_t)ns + 1) * sizeof *m->line_start) : NULL;
    m->objs = calloc(1, sizeof *m->objs);
    if (!m->path || !m->pos || !m->face_start || (ns && !m->line_start) || !m->objs)
        return -1;
    for (uint32_t k = 0; k < n; k++)
        for (int j = 0; j < 3; j++)
            m->pos[3 * (size_t)k + j] = (float)(b->cells.sum[3 * (size_t)k + j] / b->cells.count[k]);
    m->nverts = n;
    for (uint32_t f = 0; f <= nt; f++)
        m->face_start[f] = 3 * f;
    for (uint32_t l = 0; ns && l <= ns; l++)
        m->line_start[l] = 2 * l;
    m->corner = b->tri.v;
    m->point = b->pt.v;
    m->line_corner = b->seg.v;
    b->tri.v = b->pt.v = b->seg.v = NULL;
    m->nfaces = nt;
    m->npoints = (uint32_t)b->pt.n;
    m->nlines = ns;
    m->nobjs = 1;
    MeshObject *o = &m->objs[0];
    snprintf(o->name, sizeof o->name, "stand-in");
    o->face_count = nt;
    o->point_count = m->npoints;
    o->line_count = ns;
    o->vert_max = n ? n - 1 : 0;
    m->info.triangles = nt;
    m->info.front = -1;
    return 0;
}

int app_standin(const Scene *s, Scene *out)
{
    uint64_t prims = 0;
    uint32_t span = 0;
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        prims += (uint64_t)o->poly_count + o->point_count + o->seg_count;
        if (o->mesh && o->vert_max - o->vert_min + 1 > span)
            span = o->vert_max - o->vert_min + 1;
    }
    if (prims < FV_STANDIN_POLYS)
        return -1;      /* small enough to render as it is */
    Vec3 lo, hi;
    world_box(s, &lo, &hi);
    float side = fmaxf(hi.x - lo.x, fmaxf(hi.y - lo.y, hi.z - lo.z));
    if (!(side > 0) || !isfinite(side))
        return -1;
    Build b = { 0 };
    Mesh *m = calloc(1, sizeof *m);
    int rc = -1;
    b.vmap = malloc((size_t)span * sizeof *b.vmap);
    b.has_point = calloc(STANDIN_CELLS, 1);
    if (!m || !b.vmap || !b.has_point || cluster_init(&b.cells))
        goto out;
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        if (!o->mesh || (!o->poly_count && !o->point_count && !o->seg_count))
            continue;
        add_verts(&b, o, lo, STANDIN_GRID / side);
        if (add_prims(&b, s, o))
            goto out;
    }
    if ((b.tri.n == 0 && b.pt.n == 0 && b.seg.n == 0) || to_mesh(&b, m))
        goto out;
    char err[160];
    rc = scene_build(out, m, 1, err, sizeof err);
    if (rc == 0)
        m = NULL;           /* the scene owns it now */
out:
    if (m) {
        mesh_free(m);
        free(m);
    }
    free(b.tri.v);
    free(b.pt.v);
    free(b.seg.v);
    free(b.vmap);
    free(b.has_point);
    cluster_free(&b.cells);
    return rc;
}
