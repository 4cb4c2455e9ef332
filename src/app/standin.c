/* standin.c: a small stand-in for a huge scene, for the first view's
 * renders (firstview.c).
 *
 * Vertex clustering (Rossignac and Borrel, "Multi-resolution 3D
 * approximations for rendering complex scenes", 1993): the world box of
 * the scene is cut into a grid of STANDIN_GRID cells along its longest
 * side, the vertices in a cell become one at their mean, and a triangle
 * whose corners fall in fewer than three cells goes. What remains keeps
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
        if (!o->poly_count)
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

typedef struct {
    Cells     cells;
    uint32_t *vmap;         /* per vertex of the object being walked: its cluster */
    uint32_t *tri;          /* 3 clusters per triangle */
    size_t    ntri, cap;
} Build;

static int add_tri(Build *b, uint32_t a, uint32_t c, uint32_t d)
{
    if (a == c || c == d || a == d)
        return 0;               /* collapsed into a line or a point */
    if (b->ntri == b->cap) {
        size_t nc = b->cap ? 2 * b->cap : 65536;
        uint32_t *t = realloc(b->tri, 3 * nc * sizeof *t);
        if (!t)
            return -1;
        b->tri = t;
        b->cap = nc;
    }
    uint32_t *t = &b->tri[3 * b->ntri++];
    t[0] = a;
    t[1] = c;
    t[2] = d;
    return 0;
}

/* Object o's vertices into clusters, then its polygons (as fans). */
static int add_object(Build *b, const Scene *s, const Object *o, Vec3 lo, float inv_cell)
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
    for (uint32_t p = o->poly_first; p < o->poly_first + o->poly_count; p++) {
        uint32_t c0 = s->poly_start[p], c1 = s->poly_start[p + 1];
        uint32_t a = b->vmap[s->poly_corner[c0] - o->vert_min];
        for (uint32_t c = c0 + 1; c + 1 < c1; c++)
            if (add_tri(b, a, b->vmap[s->poly_corner[c] - o->vert_min],
                        b->vmap[s->poly_corner[c + 1] - o->vert_min]))
                return -1;
    }
    return 0;
}

/* The clusters and triangles as a one-object mesh (arrays taken over). */
static int to_mesh(Build *b, Mesh *m)
{
    memset(m, 0, sizeof *m);
    uint32_t n = b->cells.n;
    m->path = strdup("stand-in");
    m->pos = malloc(3 * (size_t)(n ? n : 1) * sizeof *m->pos);
    m->face_start = malloc((b->ntri + 1) * sizeof *m->face_start);
    m->objs = calloc(1, sizeof *m->objs);
    if (!m->path || !m->pos || !m->face_start || !m->objs)
        return -1;
    for (uint32_t k = 0; k < n; k++)
        for (int j = 0; j < 3; j++)
            m->pos[3 * (size_t)k + j] = (float)(b->cells.sum[3 * (size_t)k + j] / b->cells.count[k]);
    m->nverts = n;
    for (size_t f = 0; f <= b->ntri; f++)
        m->face_start[f] = (uint32_t)(3 * f);
    m->corner = b->tri;
    b->tri = NULL;
    m->nfaces = (uint32_t)b->ntri;
    m->nobjs = 1;
    snprintf(m->objs[0].name, sizeof m->objs[0].name, "stand-in");
    m->objs[0].face_count = m->nfaces;
    m->objs[0].vert_max = n ? n - 1 : 0;
    m->info.triangles = m->nfaces;
    m->info.front = -1;
    return 0;
}

int app_standin(const Scene *s, Scene *out)
{
    uint64_t polys = 0;
    uint32_t span = 0;
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++) {
        polys += s->objs[i].poly_count;
        if (s->objs[i].poly_count && s->objs[i].vert_max - s->objs[i].vert_min + 1 > span)
            span = s->objs[i].vert_max - s->objs[i].vert_min + 1;
    }
    if (polys < FV_STANDIN_POLYS || s->npoints || s->nsegs)
        return -1;      /* small enough to render as it is (or points and lines, kept whole) */
    Vec3 lo, hi;
    world_box(s, &lo, &hi);
    float side = fmaxf(hi.x - lo.x, fmaxf(hi.y - lo.y, hi.z - lo.z));
    if (!(side > 0) || !isfinite(side))
        return -1;
    Build b = { 0 };
    Mesh *m = calloc(1, sizeof *m);
    int rc = -1;
    b.vmap = malloc((size_t)span * sizeof *b.vmap);
    if (!m || !b.vmap || cluster_init(&b.cells))
        goto out;
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++)
        if (s->objs[i].poly_count && s->objs[i].mesh &&
            add_object(&b, s, &s->objs[i], lo, STANDIN_GRID / side))
            goto out;
    if (b.ntri == 0 || to_mesh(&b, m))
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
    free(b.tri);
    free(b.vmap);
    cluster_free(&b.cells);
    return rc;
}
