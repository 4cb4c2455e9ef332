/* scene.c: meshes -> objects, the polygon list, per-face shading data
 * (face normals: normals.c; the up axis, matrices and fitting the
 * camera: transform.c; the wireframe's edges: wire.c). */

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "invariant.h"
#include "scene.h"
#include "scene_internal.h"
#include "simd.h"

/* A face whose corners stray from its plane by more than this fraction
 * of its size is split into triangles. */
#define PLANAR_TOL 1e-4

const uint8_t scene_default_rgb[3] = { 204, 204, 196 };

/* ==== per-face geometry ==== */

static int face_is_planar(const Mesh *m, uint32_t f, const double n[3])
{
    uint32_t a = m->face_start[f], b = m->face_start[f + 1];
    if (b - a <= 3)
        return 1;
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len == 0)
        return 1;   /* degenerate: nothing to split */
    double c[3] = { 0, 0, 0 }, lo[3] = { DBL_MAX, DBL_MAX, DBL_MAX }, hi[3] = { -DBL_MAX, -DBL_MAX, -DBL_MAX };
    for (uint32_t k = a; k < b; k++) {
        const float *p = &m->pos[3 * m->corner[k]];
        for (int i = 0; i < 3; i++) {
            c[i] += p[i];
            if (p[i] < lo[i]) lo[i] = p[i];
            if (p[i] > hi[i]) hi[i] = p[i];
        }
    }
    double size = 0;
    for (int i = 0; i < 3; i++) {
        c[i] /= (b - a);
        size += (hi[i] - lo[i]) * (hi[i] - lo[i]);
    }
    size = sqrt(size);
    for (uint32_t k = a; k < b; k++) {
        const float *p = &m->pos[3 * m->corner[k]];
        double d = ((p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1] + (p[2] - c[2]) * n[2]) / len;
        if (fabs(d) > PLANAR_TOL * size)
            return 0;
    }
    return 1;
}

/* The face's own colour (material, else its corners' colours); returns
 * 0 when it has none and gets the default. */
static int face_base_rgb(const Mesh *m, uint32_t f, uint8_t out[3])
{
    int32_t mat = m->face_mat ? m->face_mat[f] : -1;
    if (mat >= 0 && (uint32_t)mat < m->nmats) {
        for (int i = 0; i < 3; i++) {
            float c = m->mats[mat].kd[i];
            out[i] = (uint8_t)(c <= 0 ? 0 : c >= 1 ? 255 : c * 255.0f + 0.5f);
        }
        return 1;
    }
    if (m->rgb) {
        uint32_t a = m->face_start[f], b = m->face_start[f + 1];
        float s[3] = { 0, 0, 0 };
        for (uint32_t k = a; k < b; k++)
            for (int i = 0; i < 3; i++)
                s[i] += m->rgb[3 * m->corner[k] + i];
        for (int i = 0; i < 3; i++) {
            float c = s[i] / (float)(b - a);
            out[i] = (uint8_t)(c <= 0 ? 0 : c >= 1 ? 255 : c * 255.0f + 0.5f);
        }
        return 1;
    }
    memcpy(out, scene_default_rgb, 3);
    return 0;
}

/* ==== building ==== */

void scene_free(Scene *s)
{
    scene_marks_release(&s->marks);
    for (int i = 0; i < s->nmeshes; i++)
        mesh_free(&s->meshes[i]);
    free(s->meshes);
    free(s->objs);
    free(s->poly_start);
    free(s->poly_corner);
    free(s->poly_lface);
    free(s->face_normal);
    free(s->face_rgb);
    free(s->face_own);
    free(s->face_obj);
    free(s->seg_corner);
    free(s->wire);
    free(s->face_surf);
    free(s->surf);
    free(s->poly_uv);
    memset(s, 0, sizeof *s);
}

int scene_number_prims(Scene *s)
{
    uint64_t id = s->nfaces, np = 0, ns = 0, nw = 0, nl = 0;
    for (int i = 0; i < s->nobjs; i++) {
        s->objs[i].point_id0 = (int32_t)(id < INT32_MAX ? id : INT32_MAX);
        id += s->objs[i].point_count;
        np += s->objs[i].point_count;
        nl += s->objs[i].line_count;
    }
    for (int i = 0; i < s->nobjs; i++) {
        s->objs[i].seg_id0 = (int32_t)(id < INT32_MAX ? id : INT32_MAX);
        id += s->objs[i].seg_count;
        ns += s->objs[i].seg_count;
    }
    for (int i = 0; i < s->nobjs; i++) {
        s->objs[i].wire_id0 = (int32_t)(id < INT32_MAX ? id : INT32_MAX);
        id += s->objs[i].wire_count;
        nw += s->objs[i].wire_count;
    }
    uint64_t nm = 0;
    for (int i = 0; i < s->nobjs; i++) {
        s->objs[i].mark_id0 = (int32_t)(id < INT32_MAX ? id : INT32_MAX);
        id += s->objs[i].mark_count;
        nm += s->objs[i].mark_count;
    }
    if (id > INT32_MAX)
        return -1;
    s->npoints = (uint32_t)np;
    s->nsegs = (uint32_t)ns;
    s->nwire = (uint32_t)nw;
    s->nlines = nl > UINT32_MAX ? UINT32_MAX : (uint32_t)nl;
    s->nprims = (uint32_t)(np + ns + nw + nm);
    return 0;
}

/* The last object whose first id of this kind is at most id (objects'
 * first ids rise with their index). */
static int object_at(const Scene *s, int32_t id, size_t field)
{
    int lo = 0, hi = s->nobjs - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo + 1) / 2;
        int32_t f;
        memcpy(&f, (const char *)&s->objs[mid] + field, sizeof f);
        if (f <= id)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

PrimKind scene_prim_of(const Scene *s, int32_t id, int *obj, uint32_t *local)
{
    *obj = -1;
    *local = 0;
    if (id < 0 || s->nobjs <= 0)
        return PRIM_NONE;
    if ((uint32_t)id < s->nfaces) {
        int o = s->face_obj ? s->face_obj[id] : 0;
        *obj = o;
        *local = (uint32_t)(id - s->objs[o].face_base);
        return PRIM_FACE;
    }
    if ((uint64_t)id >= (uint64_t)s->nfaces + s->nprims)
        return PRIM_NONE;
    static const struct {
        PrimKind kind;
        size_t   id0, count;
    } kinds[4] = {
        { PRIM_MARK, offsetof(Object, mark_id0), offsetof(Object, mark_count) },
        { PRIM_WIRE, offsetof(Object, wire_id0), offsetof(Object, wire_count) },
        { PRIM_SEG, offsetof(Object, seg_id0), offsetof(Object, seg_count) },
        { PRIM_POINT, offsetof(Object, point_id0), offsetof(Object, point_count) },
    };
    /* the kinds follow one another: the last whose range starts at or
     * before id holds it */
    for (int k = 0; k < 4; k++) {
        int o = object_at(s, id, kinds[k].id0);
        int32_t f;
        uint32_t n;
        memcpy(&f, (const char *)&s->objs[o] + kinds[k].id0, sizeof f);
        memcpy(&n, (const char *)&s->objs[o] + kinds[k].count, sizeof n);
        if (f <= id && (uint32_t)(id - f) < n) {
            *obj = o;
            *local = (uint32_t)(id - f);
            return kinds[k].kind;
        }
    }
    return PRIM_NONE;
}

void scene_edge_verts(const Scene *s, const Object *o, PrimKind kind, uint32_t k, uint32_t v[2])
{
    if (kind == PRIM_MARK) {
        const uint32_t *w = &s->marks.edge[2 * ((size_t)o->mark_first + k)];
        v[0] = w[0];
        v[1] = w[1];
        return;
    }
    if (kind == PRIM_WIRE) {
        const uint32_t *w = &s->wire[2 * ((size_t)o->wire_first + k)];
        v[0] = w[0];
        v[1] = w[1];
        return;
    }
    uint32_t c = s->seg_corner[o->seg_first + k];
    v[0] = o->mesh->line_corner[c];
    v[1] = o->mesh->line_corner[c + 1];
}

static inline void bounds_add(float lo[3], float hi[3], const float *p)
{
    for (int i = 0; i < 3; i++) {
        if (p[i] < lo[i]) lo[i] = p[i];
        if (p[i] > hi[i]) hi[i] = p[i];
    }
}

/* The box of what the object draws: its faces' corners, its points and
 * its lines' corners. The face lists are passed in: scene_build may have
 * taken them from the mesh. */
static void object_bounds(Object *o, const MeshObject *mo, const uint32_t *face_start, const uint32_t *corner)
{
    const Mesh *m = o->mesh;
    float lo[3] = { FLT_MAX, FLT_MAX, FLT_MAX }, hi[3] = { -FLT_MAX, -FLT_MAX, -FLT_MAX };
    /* face_start NULL: the taken-over lists of triangles (3 corners a face) */
    uint32_t f0 = o->face_first, f1 = o->face_first + o->face_count;
    uint32_t k0 = face_start ? face_start[f0] : 3 * f0, k1 = face_start ? face_start[f1] : 3 * f1;
    for (uint32_t k = k0; k < k1; k++)
        bounds_add(lo, hi, &m->pos[3 * (size_t)corner[k]]);
    for (uint32_t k = 0; k < o->point_count; k++)
        bounds_add(lo, hi, &m->pos[3 * (size_t)object_point_vert(o, k)]);
    if (mo->line_count)
        for (uint32_t c = m->line_start[mo->line_first]; c < m->line_start[mo->line_first + mo->line_count]; c++)
            bounds_add(lo, hi, &m->pos[3 * (size_t)m->line_corner[c]]);
    if (lo[0] > hi[0]) {
        o->centre = o->half = v3(0, 0, 0);
        return;
    }
    /* in double: lo + hi and hi - lo of finite floats can pass FLT_MAX */
    o->centre = v3((float)(((double)lo[0] + hi[0]) * 0.5), (float)(((double)lo[1] + hi[1]) * 0.5),
                   (float)(((double)lo[2] + hi[2]) * 0.5));
    o->half = v3((float)(((double)hi[0] - lo[0]) * 0.5), (float)(((double)hi[1] - lo[1]) * 0.5),
                 (float)(((double)hi[2] - lo[2]) * 0.5));
}

/* Coordinates beyond this turn a rotation's sums of products past
 * FLT_MAX (a corner at 3e38 on every axis lies 5.2e38 from the origin). */
#define HUGE_COORD 0x1p120f

/* Scale every mesh's positions by 2^-k when any object reaches past
 * HUGE_COORD: a power of two scales finite floats exactly, so the model
 * keeps its shape, and the transforms stay finite. Returns k (0 for
 * ordinary models, which are not touched). */
static double scene_reach(const Scene *s)
{
    /* in double: centre + half of finite floats can pass FLT_MAX */
    double big = 0;
    for (int i = 0; i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        big = fmax(big, fmax(fabs(o->centre.x), fmax(fabs(o->centre.y), fabs(o->centre.z))) +
                            fmax(o->half.x, fmax(o->half.y, o->half.z)));
    }
    return big;
}

static int shrink_huge_meshes(Scene *s, int take_over)
{
    double big = scene_reach(s);
    if (!(big > HUGE_COORD))
        return 0;
    int k = 0;
    while (big > HUGE_COORD) {       /* at most 2 FLT_MAX: a few steps */
        big *= 0x1p-8;
        k += 8;
    }
    float f = ldexpf(1, -k);
    for (int mi = 0; mi < s->nmeshes; mi++) {
        Mesh *m = &s->meshes[mi];
        for (size_t v = 0; v < 3 * (size_t)m->nverts; v++)
            m->pos[v] *= f;
    }
    int oi = 0;
    for (int mi = 0; mi < s->nmeshes; mi++) {
        const Mesh *m = &s->meshes[mi];
        for (uint32_t j = 0; j < m->nobjs; j++, oi++)
            object_bounds(&s->objs[oi], &m->objs[j], take_over ? s->poly_start : m->face_start,
                          take_over ? s->poly_corner : m->corner);
    }
    return k;
}

void scene_files_text(const Mesh *meshes, int n, char *buf, size_t len)
{
    const char *first = n > 0 && meshes[0].path ? meshes[0].path : "the scene";
    if (n <= 1)
        snprintf(buf, len, "%s", first);
    else if (n == 2)
        snprintf(buf, len, "%s and %s", first, meshes[1].path ? meshes[1].path : "?");
    else
        snprintf(buf, len, "%s and %d more files", first, n - 1);
}

void scene_too_large(const Mesh *meshes, int n, uint64_t nobjs, uint64_t nfaces, char *err, size_t errlen)
{
    char files[320];
    scene_files_text(meshes, n, files, sizeof files);
    if (nobjs > 65535)
        snprintf(err, errlen, "%s: too many objects for one scene (%llu; at most 65535)", files,
                 (unsigned long long)nobjs);
    else
        snprintf(err, errlen, "%s: too large for one scene (%llu faces; at most %d faces, points and "
                              "segments together)", files, (unsigned long long)nfaces, INT32_MAX);
}

/* What scene_build works out before it writes the polygon lists. */
typedef struct {
    uint64_t nobjs, nfaces, nsegs;   /* over every mesh */
    uint64_t npolys, ncorners;       /* after splitting non-planar faces */
    int      all_tris;               /* every face of every mesh a triangle */
    int      plain;                  /* one object, no face with a colour of its own:
                                        no face_rgb, face_own, face_obj */
    uint8_t *planar;                 /* per face: kept whole (NULL with all_tris: all) */
    int      take_over;              /* the polygon lists are the mesh's face lists */
    SurfBuild surf;                  /* textured and vertex-coloured faces */
} SceneCounts;

/* Does some face of m have a colour of its own (face_base_rgb)? */
static int mesh_has_own_colour(const Mesh *m)
{
    if (m->rgb)
        return 1;
    for (uint32_t f = 0; m->face_mat && f < m->nfaces; f++)
        if (m->face_mat[f] >= 0 && (uint32_t)m->face_mat[f] < m->nmats)
            return 1;
    return 0;
}

/* Objects, faces and segments over every mesh; -1 with the message
 * when they pass what a scene's ids and indices can hold. */
static int count_meshes(const Mesh *meshes, int nmeshes, SceneCounts *c, char *err, size_t errlen)
{
    c->all_tris = 1;
    int own = 0;
    for (int mi = 0; mi < nmeshes; mi++) {
        const Mesh *m = &meshes[mi];
        c->nobjs += m->nobjs;
        c->nfaces += m->nfaces;
        if (m->nlines)
            c->nsegs += m->line_start[m->nlines] - m->nlines;
        /* every face has 3 corners or more: 3 a face on average is 3 each */
        if (m->nfaces && !(m->face_start && m->face_start[m->nfaces] == 3 * (uint64_t)m->nfaces))
            c->all_tris = 0;
        own |= mesh_has_own_colour(m);
    }
    c->plain = c->nobjs == 1 && !own;
    if (c->nobjs > 65535 || c->nfaces > INT32_MAX || c->nsegs > INT32_MAX) {
        scene_too_large(meshes, nmeshes, c->nobjs, c->nfaces, err, errlen);
        return -1;
    }
    return 0;
}

/* The per-object and per-face arrays the scene needs (and c->planar);
 * the normals wait for alloc_polys. -1 out of memory. */
static int alloc_face_arrays(Scene *s, SceneCounts *c)
{
    uint64_t nfaces = c->nfaces;
    s->objs = calloc(c->nobjs ? c->nobjs : 1, sizeof *s->objs);
    s->seg_corner = malloc((c->nsegs ? c->nsegs : 1) * sizeof *s->seg_corner);
    if (!s->objs || !s->seg_corner)
        return -1;
    if (!c->plain) {
        s->face_rgb = malloc((nfaces ? nfaces : 1) * 3);
        s->face_own = malloc(nfaces ? nfaces : 1);
        if (!s->face_rgb || !s->face_own)
            return -1;
        bigmem_advise(s->face_rgb, nfaces * 3, 1);
    }
    if (c->nobjs > 1) {
        if (!(s->face_obj = malloc((nfaces ? nfaces : 1) * sizeof(uint16_t))))
            return -1;
        bigmem_advise(s->face_obj, nfaces * sizeof(uint16_t), 1);
    }
    if (!c->all_tris) {
        if (!(c->planar = malloc(nfaces ? nfaces : 1)))
            return -1;
        bigmem_advise(c->planar, nfaces, 1);
    }
    return 0;
}

/* Each face's colour and whether it stays whole, and the polygons and
 * corners that makes; -1 with the message when they pass what 32-bit
 * offsets hold. */
static int face_data(Scene *s, const Mesh *meshes, int nmeshes, SceneCounts *c, char *err,
                     size_t errlen)
{
    uint32_t gface = 0;
    uint64_t npolys = 0, ncorners = 0;
    uint8_t *planar = c->planar;
    for (int mi = 0; mi < nmeshes; mi++) {
        const Mesh *m = &meshes[mi];
        surf_build_mesh(&c->surf, m);
        for (uint32_t f = 0; f < m->nfaces; f++, gface++) {
            uint8_t rgb[3];
            uint8_t *col = s->face_rgb ? &s->face_rgb[3 * (size_t)gface] : rgb;
            int own = face_base_rgb(m, f, col);
            surf_of_face(&c->surf, s, f, gface, col);
            if (s->face_own)
                s->face_own[gface] = (uint8_t)own;
            uint32_t nc = m->face_start[f + 1] - m->face_start[f];
            if (planar) {
                double n[3] = { 0, 0, 1 };
                if (nc > 3)
                    scene_face_newell(m, f, n);
                planar[gface] = (uint8_t)face_is_planar(m, f, n);
            }
            if (!planar || planar[gface]) {
                npolys += 1;
                ncorners += nc;
            } else {
                npolys += nc - 2;
                ncorners += 3 * (nc - 2);
            }
        }
    }
    c->npolys = npolys;
    c->ncorners = ncorners;
    if (npolys > UINT32_MAX / 2 || ncorners > UINT32_MAX / 2) {
        char files[320];
        scene_files_text(meshes, nmeshes, files, sizeof files);
        snprintf(err, errlen, "%s: too large for one scene (%llu triangles and polygons; at most %u)", files,
                 (unsigned long long)npolys, UINT32_MAX / 2);
        return -1;
    }
    return 0;
}

/* One mesh whose faces all stay whole polygons (every triangle mesh),
 * its objects' faces in order: the polygon lists are the mesh's face
 * lists. Taking them over instead of copying into fresh arrays, on a
 * 5M-triangle model, leaves 80 MB unwritten and 20k page faults not
 * taken before the first picture. */
static int can_take_over(const Mesh *meshes, int nmeshes, const SceneCounts *c)
{
    if (!(nmeshes == 1 && meshes[0].nfaces && meshes[0].face_start && meshes[0].corner &&
          c->npolys == meshes[0].nfaces && c->ncorners == meshes[0].face_start[meshes[0].nfaces]))
        return 0;
    uint32_t next = 0;
    for (uint32_t k = 0; k < meshes[0].nobjs; k++) {
        if (meshes[0].objs[k].face_first != next)
            return 0;
        next += meshes[0].objs[k].face_count;
    }
    return next == meshes[0].nfaces;
}

/* Every face's unit normal (scenes whose polygons are not the faces one
 * for one: the compact form computes them when asked). */
static void store_normals(Scene *s, const Mesh *meshes, int nmeshes)
{
    size_t g = 0;
    for (int mi = 0; mi < nmeshes; mi++)
        for (uint32_t f = 0; f < meshes[mi].nfaces; f++, g++) {
            double n[3];
            scene_face_newell(&meshes[mi], f, n);
            scene_unit_normal(n, &s->face_normal[3 * g]);
        }
}

/* The polygon lists: taken over from the mesh (the compact form: no
 * normals, no face of each polygon, and for triangles no offsets), or
 * allocated to be written, with the normals. -1 out of memory. */
static int alloc_polys(Scene *s, Mesh *meshes, int nmeshes, SceneCounts *c, int keep)
{
    uint64_t npolys = c->npolys, ncorners = c->ncorners, nfaces = c->nfaces;
    c->take_over = !keep && can_take_over(meshes, nmeshes, c);     /* keep: the caller's lists stay its own */
    if (c->take_over) {
        s->poly_start = meshes[0].face_start;
        s->poly_corner = meshes[0].corner;
        meshes[0].face_start = meshes[0].corner = NULL;
        if (ncorners == 3 * npolys) {   /* triangles: offsets 3k */
            free(s->poly_start);
            s->poly_start = NULL;
        }
    } else {
        s->poly_start = malloc((npolys + 1) * sizeof(uint32_t));
        s->poly_corner = malloc((ncorners ? ncorners : 1) * sizeof(uint32_t));
        s->poly_lface = malloc((npolys ? npolys : 1) * sizeof(uint32_t));
        s->face_normal = malloc((nfaces ? nfaces : 1) * 3 * sizeof(float));
        if (!s->poly_start || !s->poly_corner || !s->poly_lface || !s->face_normal)
            return -1;
        bigmem_advise(s->poly_start, (npolys + 1) * sizeof(uint32_t), 1);
        bigmem_advise(s->poly_corner, ncorners * sizeof(uint32_t), 1);
        bigmem_advise(s->poly_lface, npolys * sizeof(uint32_t), 1);
        bigmem_advise(s->face_normal, nfaces * 3 * sizeof(float), 1);
        store_normals(s, meshes, nmeshes);
    }
    if (surf_want_uv(s)) {
        if (!(s->poly_uv = malloc((ncorners ? ncorners : 1) * 2 * sizeof(float))))
            return -1;
        bigmem_advise(s->poly_uv, ncorners * 2 * sizeof(float), 1);
    }
    return 0;
}

/* Where the polygon and segment lists have been written to. */
typedef struct {
    uint32_t pi, ci, si;   /* polygons, corners, segments */
} ScenePos;

/* Object oi from mesh object mo (faces from global face gface on): its
 * fields, its segments (each polyline's corners but the last), its
 * bounds. */
static void object_from_mesh(Scene *s, const Mesh *m, const MeshObject *mo, uint32_t oi, uint32_t gface,
                             const SceneCounts *c, ScenePos *at)
{
    Object *o = &s->objs[oi];
    memcpy(o->name, mo->name, sizeof o->name);
    o->name[sizeof o->name - 1] = 0;
    o->mesh = m;
    o->face_first = mo->face_first;
    o->face_count = mo->face_count;
    o->vert_min = mo->vert_min;
    o->vert_max = mo->vert_max;
    o->face_base = (int32_t)(gface + mo->face_first);
    o->poly_first = at->pi;
    o->scale = o->home_scale = 1;
    o->up = m->info.up > UP_Y && m->info.up < UP_COUNT ? m->info.up : UP_Y;   /* as its file stands */
    o->point_first = mo->point_first;
    o->point_count = mo->point_count;
    o->line_count = mo->line_count;
    uint32_t si = at->si;
    o->seg_first = si;
    for (uint32_t l = mo->line_first; l < mo->line_first + mo->line_count; l++)
        for (uint32_t c2 = m->line_start[l]; c2 + 1 < m->line_start[l + 1]; c2++)
            s->seg_corner[si++] = c2;
    o->seg_count = si - o->seg_first;
    at->si = si;
    object_bounds(o, mo, c->take_over ? s->poly_start : m->face_start,
                  c->take_over ? s->poly_corner : m->corner);
}

/* Object oi's faces: their object, their colour when they have none of
 * their own and the scene has several objects, and their polygons (a
 * planar face whole, any other as a fan of triangles; taken over: the
 * polygons are there already). */
static void object_polys(Scene *s, const Mesh *m, const MeshObject *mo, uint32_t oi, uint32_t gface,
                         const SceneCounts *c, ScenePos *at)
{
    const uint8_t *planar = c->planar;
    uint32_t pi = at->pi, ci = at->ci;
    uint32_t f0 = mo->face_first, f1 = mo->face_first + mo->face_count;
    for (uint32_t f = f0; f < f1 && (s->face_obj || s->face_own); f++) {
        uint32_t g = gface + f;
        if (s->face_obj)
            s->face_obj[g] = (uint16_t)oi;
        if (s->face_own && !s->face_own[g] && c->nobjs > 1)
            object_colour((int)oi, &s->face_rgb[3 * (size_t)g]);
    }
    if (c->take_over) {
        at->pi = pi + mo->face_count;
        return;
    }
    for (uint32_t f = f0; f < f1; f++) {
        uint32_t a = m->face_start[f], b = m->face_start[f + 1];
        float *uv = s->poly_uv;
        if (!planar || planar[gface + f]) {
            s->poly_start[pi] = ci;
            s->poly_lface[pi++] = f - mo->face_first;
            for (uint32_t k = a; k < b; k++) {
                if (uv)
                    surf_corner_uv(m, k, &uv[2 * (size_t)ci]);
                s->poly_corner[ci++] = m->corner[k];
            }
        } else {
            for (uint32_t k = a + 1; k + 1 < b; k++) {
                s->poly_start[pi] = ci;
                s->poly_lface[pi++] = f - mo->face_first;
                const uint32_t fan[3] = { a, k, k + 1 };
                for (int q = 0; q < 3; q++) {
                    if (uv)
                        surf_corner_uv(m, fan[q], &uv[2 * (size_t)ci]);
                    s->poly_corner[ci++] = m->corner[fan[q]];
                }
            }
        }
    }
    at->pi = pi;
    at->ci = ci;
}

/* Every mesh's objects into the scene's, with their polygons. */
static void build_objects(Scene *s, const Mesh *meshes, int nmeshes, const SceneCounts *c)
{
    ScenePos at = { 0, 0, 0 };
    uint32_t oi = 0, gface = 0;
    for (int mi = 0; mi < nmeshes; mi++) {
        const Mesh *m = &meshes[mi];
        for (uint32_t k = 0; k < m->nobjs; k++, oi++) {
            object_from_mesh(s, m, &m->objs[k], oi, gface, c, &at);
            object_polys(s, m, &m->objs[k], oi, gface, c, &at);
            s->objs[oi].poly_count = at.pi - s->objs[oi].poly_first;
        }
        gface += m->nfaces;
    }
    /* The fill wrote exactly what face_data counted: the arrays were
     * sized by those counts, and the sentinel below closes the last
     * polygon at the last corner. */
    ZV_ASSERT(at.pi == c->npolys && (c->take_over || at.ci == c->ncorners) && at.si == c->nsegs);
    if (!c->take_over)
        s->poly_start[at.pi] = at.ci;
    s->npolys = at.pi;
    s->nobjs = (int)oi;
    s->nbase_objs = oi;
    s->nfaces = gface;
}

/* The scene keeps its own polygon lists and per-face data: the meshes'
 * face arrays are no longer needed (a third of a big model's memory). */
static void release_mesh_faces(Mesh *meshes, int nmeshes)
{
    for (int mi = 0; mi < nmeshes; mi++) {
        Mesh *m = &meshes[mi];
        free(m->face_start);
        free(m->corner);
        free(m->face_mat);
        free(m->corner_uv);
        free(m->uv);
        m->face_start = m->corner = m->corner_uv = NULL;
        m->face_mat = NULL;
        m->uv = NULL;
    }
}

/* Taken over, the polygon corners are the mesh's corners: their texture
 * coordinates in order (a per-vertex entry through the corner's vertex). */
static void take_over_uv(Scene *s, const Mesh *m)
{
    uint32_t nc = scene_ncorners(s);
    for (uint32_t c = 0; c < nc; c++) {
        uint32_t i = m->corner_uv ? m->corner_uv[c] : s->poly_corner[c];
        float *out = &s->poly_uv[2 * (size_t)c];
        if (!m->uv || i == MESH_NO_UV || i >= m->nuv) {
            out[0] = out[1] = 0;
        } else {
            out[0] = m->uv[2 * (size_t)i];
            out[1] = m->uv[2 * (size_t)i + 1];
        }
    }
}

/* A build that failed: what it made freed, the meshes left to the caller. */
static void build_failed(Scene *s, SceneCounts *c, int oom, char *err, size_t errlen)
{
    free(c->planar);
    free(c->surf.matsurf);
    s->meshes = NULL;   /* the caller still owns them on failure */
    s->nmeshes = 0;
    scene_free(s);
    if (oom)
        snprintf(err, errlen, "out of memory building the scene");
}

/* The objects and their polygon lists (take: a mesh's face lists may be
 * taken over). A function of its own, so that the flag is not held
 * across the loops over the faces. 0, or -1 (failed, undone). */
static __attribute__((noinline)) int build_lists(Scene *s, Mesh *meshes, int nmeshes, int take, SceneCounts *c,
                                                 char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    s->meshes = meshes;
    s->nmeshes = nmeshes;
    if (count_meshes(meshes, nmeshes, c, err, errlen))
        return -1;
    int oom = alloc_face_arrays(s, c);
    if (!oom)
        oom = surf_build_start(&c->surf, s, meshes, nmeshes, c->nfaces);
    if (oom || face_data(s, meshes, nmeshes, c, err, errlen) || (oom = alloc_polys(s, meshes, nmeshes, c, !take))) {
        build_failed(s, c, oom, err, errlen);
        return -1;
    }
    build_objects(s, meshes, nmeshes, c);
    if (c->take_over && s->poly_uv)
        take_over_uv(s, &meshes[0]);
    surf_build_end(&c->surf, s);
    free(c->planar);
    c->planar = NULL;
    return 0;
}

/* The rest, once the positions are final: ids, light, view; the
 * meshes' face lists released unless kept. */
static int build_end(Scene *s, Mesh *meshes, int nmeshes, SceneCounts *c, int keep, char *err, size_t errlen)
{
    if (scene_number_prims(s)) {
        scene_too_large(meshes, nmeshes, 0, (uint64_t)INT32_MAX + 1, err, errlen);
        build_failed(s, c, 0, err, errlen);
        return -1;
    }
    if (!keep)
        release_mesh_faces(meshes, nmeshes);
    light_set(&s->light, LIGHT_YAW, LIGHT_PITCH, LIGHT_AMBIENT);
    scene_reset(s);
    return 0;
}

int scene_build(Scene *s, Mesh *meshes, int nmeshes, char *err, size_t errlen)
{
    SceneCounts c = { 0 };
    if (build_lists(s, meshes, nmeshes, 1, &c, err, errlen))
        return -1;
    s->pos_exp = shrink_huge_meshes(s, c.take_over);
    return build_end(s, meshes, nmeshes, &c, 0, err, errlen);
}

int scene_build_kept(Scene *s, Mesh *meshes, int nmeshes, char *err, size_t errlen)
{
    /* the meshes are only read: their faces stay, none is taken over,
     * and a model the shrink would scale is left (1): it writes the
     * positions the caller's other threads read */
    SceneCounts c = { 0 };
    if (build_lists(s, meshes, nmeshes, 0, &c, err, errlen))
        return -1;
    if (scene_reach(s) > HUGE_COORD) {
        build_failed(s, &c, 0, err, errlen);
        return 1;
    }
    return build_end(s, meshes, nmeshes, &c, 1, err, errlen);
}

void scene_release_faces(Scene *s)
{
    release_mesh_faces(s->meshes, s->nmeshes);
}

int scene_make_grid(Scene *s, int n, char *err, size_t errlen)
{
    if (n <= 1)
        return 0;
    uint64_t copies = (uint64_t)n * n * n;
    uint64_t nobjs = (uint64_t)s->nobjs * copies, nfaces = (uint64_t)s->nfaces * copies;
    if (nobjs > 65535 || nfaces + (uint64_t)s->nprims * copies > INT32_MAX) {
        snprintf(err, errlen, "--grid %d: too many objects or faces", n);
        return -1;
    }
    /* A scene of points or lines only has no faces: realloc(p, 0) would
     * free the arrays (and return NULL), so every size is at least 1. */
    size_t nf1 = nfaces ? (size_t)nfaces : 1;
    Object *objs = realloc(s->objs, (nobjs ? nobjs : 1) * sizeof *objs);
    if (objs)
        s->objs = objs;
    /* the compact form's missing arrays stay missing (the copies share
     * the polygons the normals are computed from, and the one colour),
     * but for the objects, which now differ */
    float *fn = s->face_normal ? realloc(s->face_normal, nf1 * 3 * sizeof(float)) : NULL;
    if (fn)
        s->face_normal = fn;
    uint8_t *fc = s->face_rgb ? realloc(s->face_rgb, nf1 * 3) : NULL;
    if (fc)
        s->face_rgb = fc;
    uint16_t *fo = s->face_obj ? realloc(s->face_obj, nf1 * sizeof(uint16_t)) : calloc(nf1, sizeof(uint16_t));
    if (fo)
        s->face_obj = fo;
    uint8_t *own = s->face_own ? realloc(s->face_own, nf1) : NULL;
    if (own)
        s->face_own = own;
    uint16_t *surf = s->face_surf ? realloc(s->face_surf, nf1 * sizeof *surf) : NULL;
    if (surf)
        s->face_surf = surf;
    if (!objs || (s->face_normal && !fn) || (s->face_rgb && !fc) || !fo || (s->face_own && !own) ||
        (s->face_surf && !surf)) {
        snprintf(err, errlen, "--grid %d: out of memory", n);
        return -1;
    }
    scene_fit(s);
    float step = 2.2f * s->cam.radius;
    int nb = s->nobjs;
    uint32_t nf = s->nfaces;
    for (uint64_t c = 1; c < copies; c++) {
        int gx = (int)(c % n), gy = (int)(c / n % n), gz = (int)(c / n / n);
        Vec3 off = v3((float)gx * step, (float)gy * step, -(float)gz * step);
        for (int k = 0; k < nb; k++) {
            Object *o = &s->objs[c * nb + k];
            *o = s->objs[k];
            o->face_base = (int32_t)(s->objs[k].face_base + c * nf);
            o->offset = o->home = off;
        }
        if (s->face_normal)
            memcpy(&s->face_normal[3 * c * nf], s->face_normal, 3 * (size_t)nf * sizeof(float));
        if (s->face_rgb)
            memcpy(&s->face_rgb[3 * c * nf], s->face_rgb, 3 * (size_t)nf);
        if (s->face_own)
            memcpy(&s->face_own[c * nf], s->face_own, nf);
        if (s->face_surf)   /* the copies share the polygons and their texture coordinates */
            memcpy(&s->face_surf[c * nf], s->face_surf, (size_t)nf * sizeof *s->face_surf);
        for (uint32_t f = 0; f < nf; f++)
            s->face_obj[c * nf + f] = (uint16_t)(s->face_obj[f] + c * nb);
    }
    s->nobjs = (int)nobjs;
    s->nfaces = (uint32_t)nfaces;
    s->gen++;
    scene_number_prims(s);        /* fits: checked above */
    scene_fit(s);
    return 0;
}
