/* testlib.c: see testlib.h. */
#define _DEFAULT_SOURCE   /* strdup */

#include <malloc.h>       /* malloc_usable_size */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "testlib.h"

/* Build a one-mesh scene from m (loaded or not: rc says). */
static int scene_from_mesh(Scene *s, Mesh *m, int rc, char *err, size_t errlen)
{
    if (rc) {
        fprintf(stderr, "%s\n", err);
        free(m);
        return -1;
    }
    if (scene_build(s, m, 1, err, errlen)) {
        fprintf(stderr, "%s\n", err);
        mesh_free(m);
        free(m);
        return -1;
    }
    return 0;
}

int tl_scene_from_text(Scene *s, const char *name, const char *obj_text)
{
    char err[512];
    Mesh *m = calloc(1, sizeof *m);
    int rc = mesh_parse(m, name, obj_text, strlen(obj_text), err, sizeof err);
    return scene_from_mesh(s, m, rc, err, sizeof err);
}

int tl_scene_from_file(Scene *s, const char *path)
{
    char err[512];
    Mesh *m = calloc(1, sizeof *m);
    int rc = mesh_load(m, path, err, sizeof err);
    return scene_from_mesh(s, m, rc, err, sizeof err);
}

static uint32_t hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

static float unit(uint32_t seed, uint32_t k)
{
    return (hash32(seed * 7919u + k * 104729u + 1u) & 0xffffff) / (float)0x1000000;
}

void tl_random_view(Scene *s, uint32_t seed, int persp)
{
    s->cam.persp = persp;
    s->cam.fov_deg = 30 + 70 * unit(seed, 1);
    scene_reset(s);
    s->cam.yaw = 6.2831853f * unit(seed, 2);
    s->cam.pitch = 3.1415926f * (unit(seed, 3) - 0.5f);
    s->cam.roll = 6.2831853f * unit(seed, 4);
    s->cam.zoom = 0.7f + 1.8f * unit(seed, 5);
    if (persp && seed % 3 == 2)
        s->cam.zoom = 3.5f;   /* the eye inside the scene: the near plane cuts */
    s->cam.pan = v3(0.4f * (unit(seed, 6) - 0.5f), 0.4f * (unit(seed, 7) - 0.5f), 0);
}

int tl_project(ScreenPolys *sp, Scene *s, const Viewport *vp, const PrimStyle *style, PrimWork **work)
{
    PrimStyle st = { 1, 1, 0, 0, 0, 0 };
    if (style)
        st = *style;
    st.point_size = st.point_size > 0 ? st.point_size : 1;
    st.line_width = st.line_width > 0 ? st.line_width : 1;
    char err[160];
    if (screen_project(sp, s, vp) || (st.wire && scene_wire_build(s, err, sizeof err)))
        return -1;
    return screen_prims(sp, s, &st, work);
}

int tl_render(Scene *s, const HsrAlgo *algo, int threads, int w, int h, int cull,
              ScreenPolys *sp, FrameBufs *fb, HsrStats *st)
{
    Viewport vp = { w, h, 1.0f, cull };
    PrimWork *work = NULL;
    int prc = tl_project(sp, s, &vp, NULL, &work);
    prims_free(&work);
    if (prc)
        return -1;
    HsrRunner r;
    if (hsr_runner_init(&r, algo, threads))
        return -1;
    HsrInput in = { .sp = sp, .scene = s, .vp = &vp };
    int rc = hsr_run(&r, &in, fb, st);
    hsr_runner_free(&r);
    return rc;
}

long tl_diff(const FrameBufs *ref, const FrameBufs *fb, int *first_x, int *first_y)
{
    long n = 0;
    *first_x = *first_y = -1;
    /* equal buffers, the usual case, told by two memcmp (the loop below
     * took a tenth of the agreement matrix's time) */
    size_t all = (size_t)ref->w * ref->h;
    if (all == 0 || (memcmp(ref->ids, fb->ids, all * sizeof *ref->ids) == 0 &&
                     memcmp(ref->depth, fb->depth, all * sizeof *ref->depth) == 0))
        return 0;
    for (int j = 0; j < ref->h; j++)
        for (int i = 0; i < ref->w; i++) {
            size_t k = (size_t)j * ref->w + i;
            if (ref->ids[k] != fb->ids[k] ||
                memcmp(&ref->depth[k], &fb->depth[k], sizeof(float)) != 0) {
                if (!n) {
                    *first_x = i;
                    *first_y = j;
                }
                n++;
            }
        }
    return n;
}

/* ==== scenes built without OBJ text ==== */

/* p with room for n elements of `size` bytes (NULL when out of memory,
 * p then unchanged). Grown to a power of two only when full, the room
 * read back with malloc_usable_size: a test adds 600,000 vertices one at
 * a time, and a realloc per call is quadratic under ASan (its realloc
 * always copies), which kept make asan from finishing. */
static void *grown(void *p, size_t n, size_t size)
{
    size_t want = (n ? n : 1) * size;
    if (p && malloc_usable_size(p) >= want)
        return p;
    size_t cap = 64;
    while (cap < want)
        cap *= 2;
    return realloc(p, cap);
}

int tl_mesh_init(Mesh *m, const char *path)
{
    memset(m, 0, sizeof *m);
    m->path = strdup(path);
    m->objs = calloc(1, sizeof *m->objs);
    m->face_start = calloc(1, sizeof *m->face_start);
    if (!m->path || !m->objs || !m->face_start)
        return -1;
    m->nobjs = 1;
    snprintf(m->objs[0].name, sizeof m->objs[0].name, "%s", path);
    return 0;
}

int tl_mesh_object(Mesh *m, const char *name)
{
    MeshObject *cur = &m->objs[m->nobjs - 1];
    if (cur->face_first != m->nfaces || cur->point_first != m->npoints || cur->line_first != m->nlines) {
        MeshObject *objs = grown(m->objs, m->nobjs + 1, sizeof *objs);
        if (!objs)
            return -1;
        m->objs = objs;
        cur = &m->objs[m->nobjs++];
    }
    memset(cur, 0, sizeof *cur);
    cur->face_first = m->nfaces;
    cur->point_first = m->npoints;
    cur->line_first = m->nlines;
    snprintf(cur->name, sizeof cur->name, "%s", name);
    return 0;
}

int tl_mesh_vertex(Mesh *m, float x, float y, float z)
{
    float *pos = grown(m->pos, 3 * ((size_t)m->nverts + 1), sizeof *pos);
    if (!pos)
        return -1;
    m->pos = pos;
    float *p = &m->pos[3 * (size_t)m->nverts++];
    p[0] = x;
    p[1] = y;
    p[2] = z;
    return 0;
}

int tl_mesh_face(Mesh *m, const uint32_t *corner, uint32_t n)
{
    uint32_t c0 = m->face_start[m->nfaces];
    uint32_t *cs = grown(m->corner, (size_t)c0 + n, sizeof *cs);
    if (cs)
        m->corner = cs;
    uint32_t *fs = grown(m->face_start, (size_t)m->nfaces + 2, sizeof *fs);
    if (fs)
        m->face_start = fs;
    int32_t *fm = grown(m->face_mat, (size_t)m->nfaces + 1, sizeof *fm);
    if (fm)
        m->face_mat = fm;
    if (!cs || !fs || !fm)
        return -1;
    memcpy(&m->corner[c0], corner, n * sizeof *corner);
    m->face_mat[m->nfaces++] = -1;
    m->face_start[m->nfaces] = c0 + n;
    m->info.triangles += n - 2;
    return 0;
}

const uint32_t tl_cube_faces[6][4] = {
    { 0, 3, 2, 1 },     /* z = 0, seen from -z */
    { 4, 5, 6, 7 },     /* z = s */
    { 0, 1, 5, 4 },     /* y = 0 */
    { 2, 3, 7, 6 },     /* y = s */
    { 0, 4, 7, 3 },     /* x = 0 */
    { 1, 2, 6, 5 },     /* x = s */
};

int tl_mesh_cube_verts(Mesh *m, float x, float y, float z, float s, uint32_t *first)
{
    static const float c[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
                                   { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
    *first = m->nverts;
    for (int i = 0; i < 8; i++)
        if (tl_mesh_vertex(m, x + s * c[i][0], y + s * c[i][1], z + s * c[i][2]))
            return -1;
    return 0;
}

int tl_mesh_cube(Mesh *m, float x, float y, float z, float s, int skip, unsigned flip, int tris)
{
    uint32_t v;
    if (tl_mesh_cube_verts(m, x, y, z, s, &v))
        return -1;
    for (int f = 0; f < 6; f++) {
        if (f == skip)
            continue;
        uint32_t q[4];
        for (int k = 0; k < 4; k++)
            q[k] = v + tl_cube_faces[f][flip >> f & 1 ? 3 - k : k];
        if (tris ? tl_mesh_face(m, q, 3) || tl_mesh_face(m, (uint32_t[]){ q[0], q[2], q[3] }, 3) : tl_mesh_face(m, q, 4))
            return -1;
    }
    return 0;
}

int tl_mesh_point(Mesh *m, uint32_t v)
{
    uint32_t *pt = grown(m->point, (size_t)m->npoints + 1, sizeof *pt);
    if (!pt)
        return -1;
    m->point = pt;
    m->point[m->npoints++] = v;
    return 0;
}

int tl_mesh_line(Mesh *m, const uint32_t *corner, uint32_t n)
{
    uint32_t *ls = grown(m->line_start, (size_t)m->nlines + 2, sizeof *ls);
    if (ls)
        m->line_start = ls;
    if (!ls)
        return -1;
    if (m->nlines == 0)
        m->line_start[0] = 0;
    uint32_t c0 = m->line_start[m->nlines];
    uint32_t *lc = grown(m->line_corner, (size_t)c0 + n, sizeof *lc);
    if (!lc)
        return -1;
    m->line_corner = lc;
    memcpy(&m->line_corner[c0], corner, n * sizeof *corner);
    m->line_start[++m->nlines] = c0 + n;
    return 0;
}

static void range_add(MeshObject *o, uint32_t v)
{
    o->vert_min = v < o->vert_min ? v : o->vert_min;
    o->vert_max = v > o->vert_max ? v : o->vert_max;
}

int tl_mesh_finish(Mesh *m)
{
    if (m->nfaces == 0 && m->npoints == 0 && m->nlines == 0 && m->nverts) {
        /* a cloud, as the loaders make it */
        free(m->point);
        m->point = NULL;
        m->npoints = m->nverts;
        m->nobjs = 1;
        memset(&m->objs[0].face_first, 0, sizeof *m->objs - offsetof(MeshObject, face_first));
    }
    if (m->nfaces == 0 && m->npoints == 0 && m->nlines == 0)
        return -1;
    MeshObject *last = &m->objs[m->nobjs - 1];
    if (m->nobjs > 1 && last->face_first == m->nfaces && last->point_first == m->npoints &&
        last->line_first == m->nlines)
        m->nobjs--;
    for (uint32_t i = 0; i < m->nobjs; i++) {
        MeshObject *o = &m->objs[i];
        int end = i + 1 == m->nobjs;
        uint32_t next = end ? m->nfaces : m->objs[i + 1].face_first;
        o->face_count = next - o->face_first;
        o->point_count = (end ? m->npoints : m->objs[i + 1].point_first) - o->point_first;
        o->line_count = (end ? m->nlines : m->objs[i + 1].line_first) - o->line_first;
        o->vert_min = UINT32_MAX;
        o->vert_max = 0;
        for (uint32_t c = m->face_start[o->face_first]; c < m->face_start[next]; c++)
            range_add(o, m->corner[c]);
        for (uint32_t k = o->point_first; k < o->point_first + o->point_count; k++)
            range_add(o, m->point ? m->point[k] : k);
        for (uint32_t l = o->line_first; l < o->line_first + o->line_count; l++)
            for (uint32_t c = m->line_start[l]; c < m->line_start[l + 1]; c++)
                range_add(o, m->line_corner[c]);
        if (o->vert_min > o->vert_max)
            o->vert_min = o->vert_max = 0;
    }
    return 0;
}

void tl_set_view(Scene *s, const TlView *v)
{
    s->cam.persp = v->persp;
    s->cam.fov_deg = v->fov_deg;
    s->cam.yaw = v->fit_yaw;
    s->cam.pitch = v->fit_pitch;
    s->cam.roll = v->fit_roll;
    scene_fit(s);
    s->cam.yaw = v->yaw;
    s->cam.pitch = v->pitch;
    s->cam.roll = v->roll;
    s->cam.zoom = v->zoom;
    s->cam.pan = v3(v->pan_x, v->pan_y, 0);
}

int tl_render_poisoned(const HsrAlgo *algo, int threads, const HsrInput *in, FrameBufs *fb)
{
    HsrRunner r;
    HsrStats st;
    if (fbuf_resize(fb, in->sp->w, in->sp->h))
        return -1;
    size_t n = (size_t)fb->w * fb->h;
    for (size_t i = 0; i < n; i++) {
        fb->ids[i] = INT32_MIN;
        fb->depth[i] = NAN;
    }
    if (hsr_runner_init(&r, algo, threads))
        return -1;
    int rc = hsr_run(&r, in, fb, &st);
    hsr_runner_free(&r);
    return rc;
}

long tl_agree(TlAgree *a, Scene *s, const Viewport *vp, int threads, char *msg, size_t msglen)
{
    HsrInput in = { .sp = &a->sp, .scene = s, .vp = vp };
    snprintf(msg, msglen, "out of memory");
    if (tl_project(&a->sp, s, vp, &a->style, &a->prims) || tl_render_poisoned(&hsr_zbuffer, 1, &in, &a->ref))
        return -1;
    msg[0] = '\0';
    for (int k = 0; k < hsr_nalgos; k++) {
        if (hsr_algos[k] == &hsr_zbuffer && threads == 1)
            continue;   /* the reference itself */
        if (tl_render_poisoned(hsr_algos[k], threads, &in, &a->fb)) {
            snprintf(msg, msglen, "out of memory");
            return -1;
        }
        int fx, fy;
        long n = tl_diff(&a->ref, &a->fb, &fx, &fy);
        if (n) {
            size_t i = (size_t)fy * vp->w + fx;
            snprintf(msg, msglen,
                     "%dx%d aspect %g cull %d, %u polygons: %s on %d thread%s differs from zbuffer "
                     "in %ld pixels; first (%d,%d): id %d depth %.9g, zbuffer id %d depth %.9g",
                     vp->w, vp->h, (double)vp->pixel_aspect, vp->cull, a->sp.npolys,
                     hsr_algos[k]->name, threads, threads == 1 ? "" : "s", n, fx, fy, a->fb.ids[i],
                     (double)a->fb.depth[i], a->ref.ids[i], (double)a->ref.depth[i]);
            return n;
        }
    }
    return 0;
}

void tl_agree_free(TlAgree *a)
{
    prims_free(&a->prims);
    screen_free(&a->sp);
    fbuf_free(&a->ref);
    fbuf_free(&a->fb);
}

const char *tl_shared_model(const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "../shared/models/%s", name);
    return access(path, R_OK) == 0 ? path : NULL;
}

/* ==== the same mesh ==== */

#define SAME(what, cond)        \
    do {                        \
        if (!(cond))            \
            return what;        \
    } while (0)

static int same_bytes(const void *a, const void *b, size_t n)
{
    return n == 0 || (a && b && memcmp(a, b, n) == 0);
}

const char *tl_mesh_differs(const Mesh *a, const Mesh *b)
{
    SAME("path", (!a->path && !b->path) || (a->path && b->path && strcmp(a->path, b->path) == 0));
    SAME("nverts", a->nverts == b->nverts);
    SAME("pos", same_bytes(a->pos, b->pos, 3 * sizeof(float) * a->nverts));
    SAME("rgb", !a->rgb == !b->rgb && (!a->rgb || same_bytes(a->rgb, b->rgb, 3 * sizeof(float) * a->nverts)));
    SAME("nfaces", a->nfaces == b->nfaces);
    SAME("face_start", !a->face_start == !b->face_start &&
                           (!a->face_start || same_bytes(a->face_start, b->face_start, 4 * ((size_t)a->nfaces + 1))));
    size_t nc = a->face_start ? a->face_start[a->nfaces] : 0;
    SAME("corner", same_bytes(a->corner, b->corner, 4 * nc));
    SAME("face_mat", !a->face_mat == !b->face_mat && (!a->face_mat || same_bytes(a->face_mat, b->face_mat, 4 * (size_t)a->nfaces)));
    SAME("nmats", a->nmats == b->nmats);
    SAME("mats", same_bytes(a->mats, b->mats, sizeof(Material) * a->nmats));
    SAME("nobjs", a->nobjs == b->nobjs);
    SAME("objs", same_bytes(a->objs, b->objs, sizeof(MeshObject) * a->nobjs));
    SAME("npoints", a->npoints == b->npoints);
    SAME("point", !a->point == !b->point && (!a->point || same_bytes(a->point, b->point, 4 * (size_t)a->npoints)));
    SAME("nlines", a->nlines == b->nlines);
    SAME("line_start", !a->nlines || same_bytes(a->line_start, b->line_start, 4 * ((size_t)a->nlines + 1)));
    size_t nl = a->nlines ? a->line_start[a->nlines] : 0;
    SAME("line_corner", same_bytes(a->line_corner, b->line_corner, 4 * nl));
    SAME("nuv", a->nuv == b->nuv);
    SAME("uv", !a->uv == !b->uv && (!a->uv || same_bytes(a->uv, b->uv, 2 * sizeof(float) * a->nuv)));
    SAME("corner_uv", !a->corner_uv == !b->corner_uv && (!a->corner_uv || same_bytes(a->corner_uv, b->corner_uv, 4 * nc)));
    SAME("ntex", a->ntex == b->ntex);
    for (uint32_t i = 0; i < a->ntex; i++)
        SAME("tex", a->tex[i].state == b->tex[i].state && strcmp(a->tex[i].name, b->tex[i].name) == 0);
    MeshInfo ia = a->info, ib = b->info;
    ia.load_ms = ib.load_ms = ia.load_cpu_ms = ib.load_cpu_ms = 0;
    SAME("info", memcmp(&ia, &ib, sizeof ia) == 0);
    return NULL;
}

const char *tl_obj_pieces_differ(const char *name, const char *text, size_t len, int threads, uint64_t piece,
                                 int strict)
{
    static char why[700];
    Mesh a, b;
    char ea[256], eb[256];
    MeshLoadOpts oa = { .format = "obj", .strict = strict, .quiet = 1, .threads = 1 };
    MeshLoadOpts ob = oa;
    ob.threads = threads;
    ob.piece_bytes = piece;
    int ra = mesh_parse_buffer_ex(&a, name, &oa, text, len, ea, sizeof ea);
    int rb = mesh_parse_buffer_ex(&b, name, &ob, text, len, eb, sizeof eb);
    const char *d = ra != rb ? "result" : strcmp(ea, eb) ? "message" : ra ? NULL : tl_mesh_differs(&a, &b);
    if (d)
        snprintf(why, sizeof why, "%s: %d threads, pieces of %llu, strict %d: %s differs (serial %d '%s', "
                 "pieces %d '%s')", name ? name : "(input)", threads, (unsigned long long)piece, strict, d, ra,
                 ea, rb, eb);
    mesh_free(&a);
    mesh_free(&b);
    return d ? why : NULL;
}

/* ==== what every loader promises ==== */

#define PROMISE(cond)           \
    do {                        \
        if (!(cond))            \
            return #cond;       \
    } while (0)

const char *tl_mesh_broken(const Mesh *m)
{
    PROMISE(m->nobjs >= 1 && m->objs);
    PROMISE(m->nfaces || m->npoints || m->nlines);
    PROMISE(m->face_start && m->face_start[0] == 0);
    for (uint32_t f = 0; f < m->nfaces; f++)
        PROMISE(m->face_start[f + 1] >= m->face_start[f] + 3);
    for (uint32_t c = 0; c < (m->nfaces ? m->face_start[m->nfaces] : 0); c++)
        PROMISE(m->corner[c] < m->nverts);
    for (uint32_t f = 0; f < m->nfaces; f++)
        PROMISE(mesh_face_mat(m, f) < 0 || (uint32_t)mesh_face_mat(m, f) < m->nmats);
    PROMISE(m->point || m->npoints <= m->nverts);
    for (uint32_t k = 0; m->point && k < m->npoints; k++)
        PROMISE(m->point[k] < m->nverts);
    if (m->nlines) {
        PROMISE(m->line_start[0] == 0);
        for (uint32_t l = 0; l < m->nlines; l++)
            PROMISE(m->line_start[l + 1] >= m->line_start[l] + 2);
        for (uint32_t c = 0; c < m->line_start[m->nlines]; c++)
            PROMISE(m->line_corner[c] < m->nverts);
    }
    uint32_t f = 0, p = 0, l = 0;
    for (uint32_t i = 0; i < m->nobjs; i++) {
        const MeshObject *o = &m->objs[i];
        /* objects own consecutive runs of each */
        PROMISE(o->face_first == f && o->point_first == p && o->line_first == l);
        f += o->face_count;
        p += o->point_count;
        l += o->line_count;
        PROMISE(o->vert_min <= o->vert_max && (o->vert_max < m->nverts || m->nverts == 0));
        for (uint32_t q = o->face_first; q < o->face_first + o->face_count; q++)
            for (uint32_t c = m->face_start[q]; c < m->face_start[q + 1]; c++)
                PROMISE(m->corner[c] >= o->vert_min && m->corner[c] <= o->vert_max);
        for (uint32_t k = o->point_first; k < o->point_first + o->point_count; k++) {
            uint32_t v = m->point ? m->point[k] : k;
            PROMISE(v >= o->vert_min && v <= o->vert_max);
        }
        for (uint32_t q = o->line_first; q < o->line_first + o->line_count; q++)
            for (uint32_t c = m->line_start[q]; c < m->line_start[q + 1]; c++)
                PROMISE(m->line_corner[c] >= o->vert_min && m->line_corner[c] <= o->vert_max);
    }
    PROMISE(f == m->nfaces && p == m->npoints && l == m->nlines);
    for (size_t i = 0; i < 3 * (size_t)m->nverts; i++)
        PROMISE(m->pos[i] - m->pos[i] == 0);      /* finite */
    return NULL;
}

const char *tl_load_broken(int rc, const Mesh *m, const char *err, const char *name)
{
    if (rc == 0)
        return tl_mesh_broken(m);
    PROMISE(rc == -1);
    PROMISE(strncmp(err, name, strlen(name)) == 0);   /* the message names the input */
    PROMISE(strlen(err) > strlen(name) + 2);          /* and says something */
    PROMISE(m->pos == NULL && m->nverts == 0 && m->nfaces == 0);  /* nothing left behind */
    return NULL;
}

/* Whether face f's colour is its own (scene.h: no face_rgb, none is;
 * no face_own, all are). */
static int face_own_of(const Scene *s, uint32_t f)
{
    return s->face_rgb ? (s->face_own ? s->face_own[f] : 1) : 0;
}

/* The object whose polygon range holds polygon k (loaded objects). */
static const Object *poly_object(const Scene *s, uint32_t k)
{
    for (int i = 0; i < s->nobjs; i++)
        if (k >= s->objs[i].poly_first && k - s->objs[i].poly_first < s->objs[i].poly_count)
            return &s->objs[i];
    return NULL;
}

int tl_scene_faces_differ(const Scene *a, const Scene *b, char *msg, size_t n)
{
    if (a->npolys != b->npolys || a->nfaces != b->nfaces || scene_ncorners(a) != scene_ncorners(b)) {
        snprintf(msg, n, "counts: %u vs %u polygons, %u vs %u faces, %u vs %u corners", a->npolys, b->npolys,
                 a->nfaces, b->nfaces, scene_ncorners(a), scene_ncorners(b));
        return 1;
    }
    for (uint32_t k = 0; k < a->npolys; k++) {
        uint32_t ca = scene_poly_c0(a, k), cb = scene_poly_c0(b, k);
        const Object *oa = poly_object(a, k), *ob = poly_object(b, k);
        if (ca != cb || scene_poly_c0(a, k + 1) != scene_poly_c0(b, k + 1) ||
            memcmp(&a->poly_corner[ca], &b->poly_corner[cb], (scene_poly_c0(a, k + 1) - ca) * sizeof(uint32_t)) ||
            !oa || !ob || scene_poly_lface(a, oa, k) != scene_poly_lface(b, ob, k)) {
            snprintf(msg, n, "polygon %u: corners from %u vs %u, or its face", k, ca, cb);
            return 1;
        }
    }
    for (uint32_t f = 0; f < a->nfaces; f++) {
        float na[3], nb[3];
        scene_face_normal(a, f, na);
        scene_face_normal(b, f, nb);
        if (memcmp(na, nb, sizeof na) || scene_face_obj(a, f) != scene_face_obj(b, f) ||
            memcmp(scene_face_rgb(a, f), scene_face_rgb(b, f), 3) || face_own_of(a, f) != face_own_of(b, f)) {
            snprintf(msg, n, "face %u: normal %g %g %g vs %g %g %g, object %d vs %d, colour or own colour", f,
                     na[0], na[1], na[2], nb[0], nb[1], nb[2], scene_face_obj(a, f), scene_face_obj(b, f));
            return 1;
        }
    }
    return 0;
}
