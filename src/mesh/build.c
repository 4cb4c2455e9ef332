/* build.c: filling a Mesh, for every loader: arrays that grow
 * geometrically (or are allocated once when a format states its
 * counts), objects, materials made from face colours, the final trim,
 * and the merging of identical vertices. */
#define _DEFAULT_SOURCE

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "bigmem.h"
#include "mesh_internal.h"

/* ==== Bounds ==== */

/* The memory a load may take (MeshErr.max_bytes, else the machine's). */
static uint64_t budget(const MeshErr *e)
{
    return e->max_bytes ? e->max_bytes : sysmem_available();
}

int mb_afford(MeshBuild *b, uint64_t polys, uint64_t bytes, const char *what)
{
    MeshErr *e = b->e;
    char lim[32], need[32], have[32];
    if (e->max_polys && polys > e->max_polys) {
        mesh_count_str(e->max_polys, lim, sizeof lim);
        return me_fail(e, "%s, more than the limit of %s polygons (--max-polys raises it)", what, lim);
    }
    uint64_t avail = budget(e);
    if (avail && bytes > avail) {
        sysmem_format(bytes, need, sizeof need);
        sysmem_format(avail, have, sizeof have);
        return me_fail(e, "%s need about %s; %s available", what, need, have);
    }
    return 0;
}

uint64_t mb_estimate(uint64_t verts, int rgb, uint64_t faces, uint64_t corners, uint64_t points)
{
    /* mesh: position (and colour), face start and material, corners;
     * scene: a face's normal (12), colour (3), object (2), flags (2), a
     * point's screen entry (16) */
    return verts * (rgb ? 24 : 12) + faces * (8 + 19) + corners * 4 + points * 16;
}

int mb_afford_counts(MeshBuild *b, uint64_t verts, int rgb, uint64_t faces)
{
    char v[32], f[32], what[96];
    mesh_count_str(verts, v, sizeof v);
    mesh_count_str(faces, f, sizeof f);
    if (faces)
        snprintf(what, sizeof what, "%s vertices and %s faces", v, f);
    else
        snprintf(what, sizeof what, "%s points", v);
    uint64_t points = faces ? 0 : verts;
    return mb_afford(b, faces + points, mb_estimate(verts, rgb, faces, 3 * faces, points), what);
}

/* Faces and points so far pass the polygon limit: the growing formats
 * (OBJ, ASCII STL, XYZ) stop there instead of at the end. */
static int over_polys(MeshBuild *b, uint64_t polys)
{
    char lim[32];
    if (!b->e->max_polys || polys <= b->e->max_polys)
        return 0;
    mesh_count_str(b->e->max_polys, lim, sizeof lim);
    return me_fail(b->e, "more than the limit of %s polygons (faces and points; --max-polys raises it)",
                   lim);
}

static int over_memory_say(MeshBuild *b, const char *what, uint64_t bytes, uint64_t avail)
{
    char need[32], have[32];
    sysmem_format(bytes, need, sizeof need);
    sysmem_format(avail, have, sizeof have);
    return me_fail(b->e, "the %s need more than %s; %s available", what, need, have);
}

/* An array about to grow to `bytes`: more than the load may take is
 * refused by name, before the allocation (the machine might grant it
 * and then run out). */
static int over_memory(MeshBuild *b, const char *what, uint64_t bytes)
{
    uint64_t avail = budget(b->e);
    if (!avail || bytes <= avail)
        return 0;
    return over_memory_say(b, what, bytes, avail);
}

/* The arrays' capacities, in bytes. */
static uint64_t arrays_bytes(const MeshBuild *b)
{
    return (uint64_t)b->vcap * (b->m->rgb ? 24 : 12) + (uint64_t)b->fcap * 8 + (uint64_t)b->ccap * 4 +
           (uint64_t)b->pcap * 4 + (uint64_t)b->lccap * 4;
}

/* An array growing from `was` bytes to `bytes`: it alone, and all the
 * arrays together with it, within the memory (each alone could fit
 * while the mesh does not). */
static int over_memory_grow(MeshBuild *b, const char *what, uint64_t bytes, uint64_t was)
{
    uint64_t avail = budget(b->e), all = arrays_bytes(b) - was + bytes;
    if (!avail || all <= avail)
        return 0;
    if (bytes > avail)
        return over_memory_say(b, what, bytes, avail);
    return over_memory_say(b, "mesh's arrays", all, avail);
}

/* Grow *arr (elements of `elem` bytes, `*cap` of them) to hold `need`,
 * asking for huge pages when it moved (a mesh's arrays are big). */
static int grow(void **arr, size_t *cap, size_t need, size_t elem)
{
    size_t before = *cap;
    if (grow_size(arr, cap, need, elem))
        return -1;
    if (*cap != before)
        bigmem_advise(*arr, *cap * elem, 0);
    return 0;
}

int mb_start(MeshBuild *b, Mesh *m, MeshErr *e, const char *name)
{
    memset(b, 0, sizeof *b);
    memset(m, 0, sizeof *m);
    b->m = m;
    b->e = e;
    /* The default object is named after the file, without folder or
     * extension. */
    const char *base = strrchr(name, '/');
    base = base ? base + 1 : name;
    const char *dot = strrchr(base, '.');
    size_t bn = dot && dot > base ? (size_t)(dot - base) : strlen(base);
    if (bn > MESH_NAME_MAX - 1)
        bn = MESH_NAME_MAX - 1;
    memcpy(b->basename, base, bn);
    b->basename[bn] = '\0';

    m->path = strdup(name);
    if (!m->path || grow((void **)&m->objs, &b->ocap, 1, sizeof(MeshObject)))
        return me_oom(e);
    m->nobjs = 1;
    memset(&m->objs[0], 0, sizeof m->objs[0]);
    memcpy(m->objs[0].name, b->basename, sizeof b->basename);
    return 0;
}

/* The capacity grow_size() would give an array of `cap` for `need`. */
static size_t next_cap(size_t cap, size_t need)
{
    size_t nc = cap ? cap : 256;
    while (nc < need && nc < SIZE_MAX / 4)
        nc *= 2;
    return nc;
}

/* Per-vertex texture coordinates for cap vertices (new ones 0, 0). */
static int grow_uv(MeshBuild *b, size_t cap)
{
    Mesh *m = b->m;
    if (cap <= b->uvcap)
        return 0;
    float *q = realloc(m->uv, cap * 2 * sizeof(float));
    if (!q)
        return me_oom(b->e);
    memset(q + 2 * b->uvcap, 0, (cap - b->uvcap) * 2 * sizeof(float));
    m->uv = q;
    b->uvcap = cap;
    return 0;
}

/* The per-corner texture coordinate indices as long as corner[]. */
static int grow_corner_uv(MeshBuild *b)
{
    Mesh *m = b->m;
    if (!m->corner_uv)
        return 0;
    uint32_t *q = realloc(m->corner_uv, (b->ccap ? b->ccap : 1) * sizeof *q);
    if (!q)
        return me_oom(b->e);
    m->corner_uv = q;
    return 0;
}

int mb_grow_verts(MeshBuild *b)
{
    Mesh *m = b->m;
    if (m->nverts >= UINT32_MAX - 1)
        return me_fail(b->e, "too many vertices");
    /* vertices alone are a point cloud: each a point */
    if (m->nfaces == 0 && m->npoints == 0 && m->nlines == 0 && over_polys(b, (uint64_t)m->nverts + 1))
        return -1;
    if (over_memory_grow(b, "vertices", (uint64_t)next_cap(b->vcap, (size_t)m->nverts + 1) * (m->rgb ? 24 : 12),
                         (uint64_t)b->vcap * (m->rgb ? 24 : 12)))
        return -1;
    size_t cap = b->vcap;
    if (grow((void **)&m->pos, &cap, (size_t)m->nverts + 1, 3 * sizeof(float)))
        return me_oom(b->e);
    if (m->rgb) {
        float *q = realloc(m->rgb, cap * 3 * sizeof(float));
        if (!q)
            return me_oom(b->e);
        m->rgb = q;
    }
    if (b->uv_per_vertex && grow_uv(b, cap))
        return -1;
    b->vcap = cap;
    return 0;
}

int mb_grow_faces(MeshBuild *b)
{
    Mesh *m = b->m;
    if (m->nfaces >= UINT32_MAX - 1)
        return me_fail(b->e, "too many faces");
    if (over_polys(b, (uint64_t)m->nfaces + m->npoints + 1) ||
        over_memory_grow(b, "faces", (uint64_t)next_cap(b->fcap, (size_t)m->nfaces + 1) * 8, (uint64_t)b->fcap * 8))
        return -1;
    size_t cap = next_cap(b->fcap, (size_t)m->nfaces + 1);
    if (m->face_mat) {
        int32_t *fm = realloc(m->face_mat, cap * sizeof(int32_t));
        if (!fm)
            return me_oom(b->e);
        m->face_mat = fm;
        bigmem_advise(fm, cap * sizeof(int32_t), 0);
    }
    uint32_t *q = realloc(m->face_start, (cap + 1) * sizeof(uint32_t));
    if (!q)
        return me_oom(b->e);
    m->face_start = q;
    b->fcap = cap;
    return 0;
}

int32_t *mb_face_mats(MeshBuild *b)
{
    Mesh *m = b->m;
    if (m->face_mat)
        return m->face_mat;
    size_t cap = b->fcap ? b->fcap : 1;
    if (!(m->face_mat = malloc(cap * sizeof(int32_t)))) {
        me_oom(b->e);
        return NULL;
    }
    for (size_t f = 0; f < cap; f++)
        m->face_mat[f] = -1;
    return m->face_mat;
}

int mb_room_corners(MeshBuild *b, size_t n)
{
    if (b->ncorner + n >= UINT32_MAX - 1)
        return me_fail(b->e, "too many face corners");
    if (b->ncorner + n > b->ccap &&
        over_memory_grow(b, "face corners", (uint64_t)next_cap(b->ccap, b->ncorner + n) * 4, (uint64_t)b->ccap * 4))
        return -1;
    if (grow((void **)&b->m->corner, &b->ccap, b->ncorner + n, sizeof(uint32_t)))
        return me_oom(b->e);
    return grow_corner_uv(b);
}

int mb_grow_corners(MeshBuild *b)
{
    return mb_room_corners(b, 1);
}

int mb_grow_points(MeshBuild *b)
{
    Mesh *m = b->m;
    if (m->npoints >= UINT32_MAX - 1)
        return me_fail(b->e, "too many points");
    if (over_polys(b, (uint64_t)m->nfaces + m->npoints + 1) ||
        over_memory_grow(b, "points", (uint64_t)next_cap(b->pcap, (size_t)m->npoints + 1) * 4, (uint64_t)b->pcap * 4))
        return -1;
    if (grow((void **)&m->point, &b->pcap, (size_t)m->npoints + 1, sizeof(uint32_t)))
        return me_oom(b->e);
    return 0;
}

int mb_grow_lines(MeshBuild *b)
{
    Mesh *m = b->m;
    if (m->nlines >= UINT32_MAX - 2)
        return me_fail(b->e, "too many lines");
    size_t cap = b->lcap;
    /* line_start holds one more: the end of the last line */
    if (grow((void **)&m->line_start, &cap, (size_t)m->nlines + 2, sizeof(uint32_t)))
        return me_oom(b->e);
    b->lcap = cap - 1;
    return 0;
}

int mb_grow_line_corners(MeshBuild *b)
{
    if (b->nlcorner >= UINT32_MAX - 1)
        return me_fail(b->e, "too many line corners");
    if (over_memory_grow(b, "line corners", (uint64_t)next_cap(b->lccap, b->nlcorner + 1) * 4, (uint64_t)b->lccap * 4))
        return -1;
    if (grow((void **)&b->m->line_corner, &b->lccap, b->nlcorner + 1, sizeof(uint32_t)))
        return me_oom(b->e);
    return 0;
}

int mb_reserve_ex(MeshBuild *b, size_t verts, size_t faces, size_t corners, int exact)
{
    Mesh *m = b->m;
    size_t nv = (size_t)m->nverts + verts, nf = (size_t)m->nfaces + faces, nc = b->ncorner + corners;
    if (nv >= UINT32_MAX || nf >= UINT32_MAX || nc >= UINT32_MAX)
        return me_fail(b->e, "too many vertices or faces (%zu, %zu)", nv, nf);
    /* a guess (exact 0) is address space, pages made resident only as
     * they are written: judged as the arrays fill (mb_grow_*), or a file
     * that fits would be refused for what its size allowed */
    if (exact && over_memory(b, "mesh's arrays", (uint64_t)nv * (m->rgb ? 24 : 12) + (uint64_t)nf * 8 + (uint64_t)nc * 4))
        return -1;
    /* Exact sizes: a count read from a header is what the file holds. */
    if (nv > b->vcap) {
        float *p = realloc(m->pos, nv * 3 * sizeof(float));
        if (!p)
            return me_oom(b->e);
        m->pos = p;
        bigmem_advise(p, nv * 3 * sizeof(float), exact);
        b->vexact = exact;
        if (m->rgb) {
            float *q = realloc(m->rgb, nv * 3 * sizeof(float));
            if (!q)
                return me_oom(b->e);
            m->rgb = q;
        }
        if (b->uv_per_vertex && grow_uv(b, nv))
            return -1;
        b->vcap = nv;
    }
    if (nf > b->fcap || !m->face_start) {
        if (m->face_mat) {
            int32_t *fm = realloc(m->face_mat, (nf ? nf : 1) * sizeof(int32_t));
            if (!fm)
                return me_oom(b->e);
            m->face_mat = fm;
            bigmem_advise(fm, nf * sizeof(int32_t), exact);
        }
        uint32_t *fs = realloc(m->face_start, (nf + 1) * sizeof(uint32_t));
        if (!fs)
            return me_oom(b->e);
        m->face_start = fs;
        bigmem_advise(fs, (nf + 1) * sizeof(uint32_t), exact);
        b->fcap = nf;
    }
    if (nc > b->ccap) {
        uint32_t *c = realloc(m->corner, nc * sizeof(uint32_t));
        if (!c)
            return me_oom(b->e);
        m->corner = c;
        bigmem_advise(c, nc * sizeof(uint32_t), exact);
        b->ccap = nc;
        if (grow_corner_uv(b))
            return -1;
    }
    return 0;
}

int mb_reserve(MeshBuild *b, size_t verts, size_t faces, size_t corners)
{
    return mb_reserve_ex(b, verts, faces, corners, 1);
}

int mb_want_rgb(MeshBuild *b)
{
    Mesh *m = b->m;
    if (m->rgb)
        return 0;
    m->rgb = malloc((b->vcap ? b->vcap : 1) * 3 * sizeof(float));
    if (!m->rgb)
        return me_oom(b->e);
    /* a point cloud's colours are as big as its positions: fault them in
     * at once too when the count is exact */
    bigmem_advise(m->rgb, b->vcap * 3 * sizeof(float), b->vexact);
    for (size_t i = 0; i < 3 * (size_t)m->nverts; i++)
        m->rgb[i] = 1.0f;
    return 0;
}

int mb_object(MeshBuild *b, const char *name, size_t len)
{
    return mb_object_at(b, name, len, b->m->nfaces, b->m->npoints, b->m->nlines);
}

int mb_object_at(MeshBuild *b, const char *name, size_t len, uint32_t nf, uint32_t np, uint32_t nl)
{
    Mesh *m = b->m;
    MeshObject *cur = &m->objs[m->nobjs - 1];
    if (cur->face_first != nf || cur->point_first != np || cur->line_first != nl) {
        if (m->nobjs == b->ocap &&
            grow((void **)&m->objs, &b->ocap, (size_t)m->nobjs + 1, sizeof(MeshObject)))
            return me_oom(b->e);
        cur = &m->objs[m->nobjs++];
    }
    /* An object that got nothing is renamed rather than kept. */
    memset(cur, 0, sizeof *cur);
    cur->face_first = nf;
    cur->point_first = np;
    cur->line_first = nl;
    if (len > MESH_NAME_MAX - 1)
        len = MESH_NAME_MAX - 1;
    if (len) {
        memcpy(cur->name, name, len);
        cur->name[len] = '\0';
    } else {
        memcpy(cur->name, b->basename, sizeof cur->name);
    }
    return 0;
}

int32_t mb_material(MeshBuild *b, const char *name, float r, float g, float bl, float alpha)
{
    Mesh *m = b->m;
    if (m->nmats >= INT32_MAX - 1) {
        me_fail(b->e, "too many materials");
        return -1;
    }
    if (m->nmats == b->mcap) {
        uint32_t nc = b->mcap ? b->mcap * 2 : 8;
        Material *nm = realloc(m->mats, nc * sizeof *nm);
        if (!nm) {
            me_oom(b->e);
            return -1;
        }
        m->mats = nm;
        b->mcap = nc;
    }
    Material *mt = &m->mats[m->nmats];
    memset(mt, 0, sizeof *mt);
    mb_material_no_texture(mt);
    snprintf(mt->name, sizeof mt->name, "%s", name);
    mt->kd[0] = r;
    mt->kd[1] = g;
    mt->kd[2] = bl;
    mt->alpha = alpha;
    return (int32_t)m->nmats++;
}

static uint32_t colour_hash(uint32_t k)
{
    k ^= k >> 16;
    k *= 0x7feb352du;
    k ^= k >> 15;
    k *= 0x846ca68bu;
    return k ^ (k >> 16);
}

int32_t mb_colour(MeshBuild *b, uint8_t r, uint8_t g, uint8_t bl, uint8_t a)
{
    ColourIndex *ci = &b->colours;
    uint32_t key = (uint32_t)r << 24 | (uint32_t)g << 16 | (uint32_t)bl << 8 | a;
    if ((ci->used + 1) * 2 > ci->cap) {
        uint32_t nc = ci->cap ? ci->cap * 2 : 64;
        uint64_t *ns = calloc(nc, sizeof *ns);
        if (!ns) {
            me_oom(b->e);
            return -1;
        }
        for (uint32_t i = 0; i < ci->cap; i++) {
            if (!ci->slot[i])
                continue;
            uint32_t j = colour_hash((uint32_t)(ci->slot[i] >> 32)) & (nc - 1);
            while (ns[j])
                j = (j + 1) & (nc - 1);
            ns[j] = ci->slot[i];
        }
        free(ci->slot);
        ci->slot = ns;
        ci->cap = nc;
    }
    uint32_t mask = ci->cap - 1, i = colour_hash(key) & mask;
    for (; ci->slot[i]; i = (i + 1) & mask)
        if ((uint32_t)(ci->slot[i] >> 32) == key)
            return (int32_t)(uint32_t)ci->slot[i] - 1;
    char name[16];
    snprintf(name, sizeof name, "#%02x%02x%02x", r, g, bl);
    int32_t mi = mb_material(b, name, r / 255.0f, g / 255.0f, bl / 255.0f, a / 255.0f);
    if (mi < 0)
        return -1;
    ci->slot[i] = (uint64_t)key << 32 | (uint32_t)(mi + 1);
    ci->used++;
    return mi;
}

/* Vertices alone (a PLY or OFF without faces, an OBJ of `v` lines): a
 * point cloud. No index array: point i is vertex i. */
static void make_cloud(MeshBuild *b)
{
    Mesh *m = b->m;
    free(m->point);
    m->point = NULL;
    b->pcap = 0;
    m->npoints = m->nverts;
    m->nobjs = 1;
    m->objs[0].face_first = m->objs[0].line_first = m->objs[0].point_first = 0;
}

/* Nothing to show: when statements were skipped, the first is why. */
static int nothing_to_show(MeshBuild *b)
{
    MeshErr *e = b->e;
    if (e->skipped) {
        char first[sizeof e->first];
        memcpy(first, e->first, sizeof first);
        return me_fail_raw(e, "%s (%u statement%s skipped, nothing left to show)", first, e->skipped,
                           e->skipped == 1 ? "" : "s");
    }
    /* say what the bytes held: nothing at all, or nothing drawable */
    if (b->m->info.bytes == 0)
        return me_fail(e, "no faces (empty file)");
    if (b->m->nverts == 0)
        return me_fail(e, "no faces and no vertices in its %llu bytes", (unsigned long long)b->m->info.bytes);
    return me_fail(e, "no faces (%u vertices, none used)", b->m->nverts);
}

/* Each object's counts from where the next one starts; only the last
 * can be empty (see mb_object), and an empty last one goes. */
static void close_objects(Mesh *m)
{
    for (uint32_t i = 0; i < m->nobjs; i++) {
        MeshObject *o = &m->objs[i];
        int last = i + 1 == m->nobjs;
        o->face_count = (last ? m->nfaces : m->objs[i + 1].face_first) - o->face_first;
        o->point_count = (last ? m->npoints : m->objs[i + 1].point_first) - o->point_first;
        o->line_count = (last ? m->nlines : m->objs[i + 1].line_first) - o->line_first;
    }
    if (m->nobjs > 1) {
        const MeshObject *o = &m->objs[m->nobjs - 1];
        if (o->face_count == 0 && o->point_count == 0 && o->line_count == 0)
            m->nobjs--;
    }
}

static inline void range_add(uint32_t v, uint32_t *lo, uint32_t *hi)
{
    *lo = v < *lo ? v : *lo;
    *hi = v > *hi ? v : *hi;
}

/* The vertex index range object o's faces, points and lines use. */
static void object_range(const Mesh *m, MeshObject *o)
{
    uint32_t lo = UINT32_MAX, hi = 0;
    uint32_t c0 = m->face_start[o->face_first];
    uint32_t c1 = m->face_start[o->face_first + o->face_count];
    for (uint32_t c = c0; c < c1; c++)
        range_add(m->corner[c], &lo, &hi);
    if (o->point_count && !m->point) {
        /* a cloud: its points are a run of vertices */
        range_add(o->point_first, &lo, &hi);
        range_add(o->point_first + o->point_count - 1, &lo, &hi);
    }
    for (uint32_t k = o->point_first; k < o->point_first + o->point_count && m->point; k++)
        range_add(m->point[k], &lo, &hi);
    if (o->line_count) {
        uint32_t l0 = m->line_start[o->line_first], l1 = m->line_start[o->line_first + o->line_count];
        for (uint32_t c = l0; c < l1; c++)
            range_add(m->line_corner[c], &lo, &hi);
    }
    /* Every index a loader stored is a vertex: the scene, the front end
     * and the shading index pos[] and rgb[] with them unchecked. The
     * loaders check each index (OBJ's forward ones at the end); this is
     * where the last of them has been dropped. */
    ZV_ASSERT(lo > hi || hi < m->nverts);
    if (lo > hi)        /* an empty first object */
        lo = hi = 0;
    o->vert_min = lo;
    o->vert_max = hi;
}

/* Give back the growth slack; a failed shrink keeps the old block. */
static void give_back_slack(MeshBuild *b)
{
    Mesh *m = b->m;
    void *q;
    size_t nv = m->nverts ? m->nverts : 1, nf = m->nfaces ? m->nfaces : 1;
    if (m->pos && (q = realloc(m->pos, nv * 3 * sizeof(float))))
        m->pos = q;
    if (m->rgb && (q = realloc(m->rgb, nv * 3 * sizeof(float))))
        m->rgb = q;
    if (m->corner && (q = realloc(m->corner, (b->ncorner ? b->ncorner : 1) * sizeof(uint32_t))))
        m->corner = q;
    if ((q = realloc(m->face_start, ((size_t)m->nfaces + 1) * sizeof(uint32_t))))
        m->face_start = q;
    if (m->face_mat && (q = realloc(m->face_mat, nf * sizeof(int32_t))))
        m->face_mat = q;
    if (m->point && (q = realloc(m->point, (m->npoints ? m->npoints : 1) * sizeof(uint32_t))))
        m->point = q;
    if (m->line_start && (q = realloc(m->line_start, ((size_t)m->nlines + 1) * sizeof(uint32_t))))
        m->line_start = q;
    if (m->line_corner && (q = realloc(m->line_corner, (b->nlcorner ? b->nlcorner : 1) * sizeof(uint32_t))))
        m->line_corner = q;
    if (m->corner_uv && (q = realloc(m->corner_uv, (b->ncorner ? b->ncorner : 1) * sizeof(uint32_t))))
        m->corner_uv = q;
    if (m->uv && (q = realloc(m->uv, (m->nuv ? m->nuv : 1) * 2 * sizeof(float))))
        m->uv = q;
}

/* Texture coordinates checked: per vertex, one entry each; per corner,
 * an index past the entries (OBJ's forward vt references, known only
 * now) means none. Without a textured material they are dropped: no
 * face would use them. */
static void finish_uv(MeshBuild *b)
{
    Mesh *m = b->m;
    if (b->uv_per_vertex)
        m->nuv = m->nverts;
    if (m->corner_uv)
        for (size_t c = 0; c < b->ncorner; c++)
            if (m->corner_uv[c] >= m->nuv)
                m->corner_uv[c] = MESH_NO_UV;
    int textured = 0;
    for (uint32_t i = 0; i < m->nmats; i++)
        textured |= m->mats[i].tex >= 0;
    if (!textured || (!m->corner_uv && !b->uv_per_vertex)) {
        free(m->uv);
        free(m->corner_uv);
        m->uv = NULL;
        m->corner_uv = NULL;
        m->nuv = 0;
    }
}

int mb_finish(MeshBuild *b, int cloud_ok)
{
    Mesh *m = b->m;
    MeshErr *e = b->e;
    free(b->colours.slot);
    b->colours.slot = NULL;
    b->colours.cap = b->colours.used = 0;
    if (cloud_ok && m->nfaces == 0 && m->npoints == 0 && m->nlines == 0 && m->nverts)
        make_cloud(b);
    if (over_polys(b, (uint64_t)m->nfaces + m->npoints))
        return -1;
    if (m->nfaces == 0 && m->npoints == 0 && m->nlines == 0)
        return nothing_to_show(b);
    if (!m->face_start && !(m->face_start = malloc(sizeof(uint32_t))))
        return me_oom(e);
    /* the sentinel closes the last face, which has 3 corners or more */
    ZV_ASSERT(m->nfaces == 0 || (size_t)m->face_start[m->nfaces - 1] + 3 <= b->ncorner);
    m->face_start[m->nfaces] = (uint32_t)b->ncorner;
    if (m->nlines)
        m->line_start[m->nlines] = (uint32_t)b->nlcorner;
    close_objects(m);
    for (uint32_t i = 0; i < m->nobjs; i++)
        object_range(m, &m->objs[i]);
    finish_uv(b);
    give_back_slack(b);
    /* materials that all came to nothing (unknown names): no array */
    uint32_t f = 0;
    while (m->face_mat && f < m->nfaces && m->face_mat[f] == -1)
        f++;
    if (m->face_mat && f == m->nfaces) {
        free(m->face_mat);
        m->face_mat = NULL;
    }
    return 0;
}

void mb_abort(MeshBuild *b)
{
    free(b->colours.slot);
    memset(&b->colours, 0, sizeof b->colours);
    mesh_free(b->m);
}

void mesh_free(Mesh *m)
{
    if (!m)
        return;
    free(m->path);
    free(m->pos);
    free(m->rgb);
    free(m->face_start);
    free(m->corner);
    free(m->face_mat);
    free(m->mats);
    free(m->objs);
    free(m->point);
    free(m->line_start);
    free(m->line_corner);
    mesh_free_textures(m);
    memset(m, 0, sizeof *m);
}

/* --points of a mesh of several objects: each object's points are the
 * vertices its faces, points and lines use (a vertex two objects share
 * goes to the first), so that objects stay objects (--move 2:...).
 * Vertices nothing uses go to the last. Returns the point array (object
 * by object, every vertex once), or NULL out of memory. */
static uint32_t *points_by_object(Mesh *m)
{
    uint32_t nv = m->nverts;
    uint32_t *pt = malloc((size_t)(nv ? nv : 1) * sizeof *pt);
    uint8_t *seen = calloc((size_t)nv / 8 + 1, 1);
    if (!pt || !seen) {
        free(pt);
        free(seen);
        return NULL;
    }
    uint32_t k = 0;
#define TAKE(v)                                                              \
    do {                                                                     \
        uint32_t v_ = (v);                                                   \
        if (v_ < nv && !(seen[v_ >> 3] >> (v_ & 7) & 1)) {                   \
            seen[v_ >> 3] |= (uint8_t)(1u << (v_ & 7));                      \
            pt[k++] = v_;                                                    \
        }                                                                    \
    } while (0)
    for (uint32_t i = 0; i < m->nobjs; i++) {
        MeshObject *o = &m->objs[i];
        uint32_t first = k;
        for (uint32_t f = o->face_first; f < o->face_first + o->face_count; f++)
            for (uint32_t c = m->face_start[f]; c < m->face_start[f + 1]; c++)
                TAKE(m->corner[c]);
        for (uint32_t p = o->point_first; p < o->point_first + o->point_count; p++)
            TAKE(m->point ? m->point[p] : p);
        for (uint32_t l = o->line_first; l < o->line_first + o->line_count; l++)
            for (uint32_t c = m->line_start[l]; c < m->line_start[l + 1]; c++)
                TAKE(m->line_corner[c]);
        if (i + 1 == m->nobjs)
            for (uint32_t v = 0; v < nv; v++)
                TAKE(v);
#undef TAKE
        o->point_first = first;
        o->point_count = k - first;
    }
    free(seen);
    return pt;
}

void mesh_as_points(Mesh *m)
{
    /* the vertices stay; every vertex is a point, of the object that
     * used it (points are not textured) */
    uint32_t *pt = m->nobjs > 1 ? points_by_object(m) : NULL;
    free(m->corner_uv);
    free(m->uv);
    m->corner_uv = NULL;
    m->uv = NULL;
    m->nuv = 0;
    free(m->face_start);
    free(m->corner);
    free(m->face_mat);
    free(m->point);
    free(m->line_start);
    free(m->line_corner);
    m->face_start = m->corner = m->point = m->line_start = m->line_corner = NULL;
    m->face_mat = NULL;
    m->nfaces = m->nlines = 0;
    m->info.triangles = 0;
    m->npoints = m->nverts;
    /* a mesh is never without its face_start sentinel */
    m->face_start = calloc(1, sizeof *m->face_start);
    if (pt) {
        m->point = pt;
        for (uint32_t i = 0; i < m->nobjs; i++) {
            MeshObject *o = &m->objs[i];
            o->face_first = o->face_count = o->line_first = o->line_count = 0;
            uint32_t lo = UINT32_MAX, hi = 0;
            for (uint32_t p = o->point_first; p < o->point_first + o->point_count; p++) {
                lo = pt[p] < lo ? pt[p] : lo;
                hi = pt[p] > hi ? pt[p] : hi;
            }
            o->vert_min = o->point_count ? lo : 0;
            o->vert_max = o->point_count ? hi : 0;
        }
        /* an object left without points (all its vertices shared with an
         * earlier one) goes, as mb_finish drops empty objects */
        uint32_t n = 0;
        for (uint32_t i = 0; i < m->nobjs; i++)
            if (m->objs[i].point_count)
                m->objs[n++] = m->objs[i];
        m->nobjs = n;
        return;
    }
    if (m->nobjs > 1) {
        /* out of memory for the table: the whole mesh, one object named
         * after the file as its default object is */
        const char *base = m->path ? strrchr(m->path, '/') : NULL;
        base = base ? base + 1 : m->path ? m->path : "points";
        const char *dot = strrchr(base, '.');
        size_t n = dot && dot > base ? (size_t)(dot - base) : strlen(base);
        if (n > MESH_NAME_MAX - 1)
            n = MESH_NAME_MAX - 1;
        memcpy(m->objs[0].name, base, n);
        m->objs[0].name[n] = '\0';
    }
    m->nobjs = m->nobjs ? 1 : 0;
    if (m->nobjs) {
        MeshObject *o = &m->objs[0];
        o->face_first = o->face_count = o->line_first = o->line_count = 0;
        o->point_first = 0;
        o->point_count = m->nverts;
        o->vert_min = 0;
        o->vert_max = m->nverts ? m->nverts - 1 : 0;
    }
}

void mesh_flip_winding(Mesh *m)
{
    if (!m->face_start || !m->corner)
        return;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t *a = m->corner + m->face_start[f], *z = m->corner + m->face_start[f + 1] - 1;
        for (; a < z; a++, z--) {
            uint32_t t = *a;
            *a = *z;
            *z = t;
        }
        if (m->corner_uv) {
            a = m->corner_uv + m->face_start[f];
            z = m->corner_uv + m->face_start[f + 1] - 1;
            for (; a < z; a++, z--) {
                uint32_t t = *a;
                *a = *z;
                *z = t;
            }
        }
    }
}

/* ==== Merging identical vertices ==== */

int vm_init(VertMerge *vm, size_t expect)
{
    size_t cap = 1024;
    while (cap < 2 * expect && cap < ((size_t)1 << 31))
        cap *= 2;
    vm->slot = calloc(cap, sizeof *vm->slot);
    bigmem_advise(vm->slot, cap * sizeof *vm->slot, 1);
    vm->mask = (uint32_t)(cap - 1);
    vm->used = 0;
    return vm->slot ? 0 : -1;
}

void vm_free(VertMerge *vm)
{
    free(vm->slot);
    memset(vm, 0, sizeof *vm);
}

int vm_grow(VertMerge *vm, const float *pos)
{
    size_t cap = (size_t)vm->mask + 1;
    if (cap >= ((size_t)1 << 31))
        return -1;
    size_t nc = cap * 2;
    uint64_t *ns = calloc(nc, sizeof *ns);
    if (!ns)
        return -1;
    for (size_t i = 0; i < cap; i++) {
        uint64_t s = vm->slot[i];
        if (!s)
            continue;
        uint32_t b[3];
        memcpy(b, pos + 3 * (size_t)((uint32_t)s - 1), sizeof b);
        size_t j = (uint32_t)(vm_hash(b[0], b[1], b[2]) >> 32) & (nc - 1);
        while (ns[j])
            j = (j + 1) & (nc - 1);
        ns[j] = s;
    }
    free(vm->slot);
    vm->slot = ns;
    vm->mask = (uint32_t)(nc - 1);
    return 0;
}
