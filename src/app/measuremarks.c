/* measuremarks.c: the measuring mode's marks on the picture (the
 * viewer's M key, --marks). A mark is a point of a scene object: a
 * vertex, an edge's midpoint or a face's centre. The cursor moves from
 * point to point, taking the nearest one in the direction of the arrow
 * (or to a clicked sample) among those the last frame shows (a point
 * whose depth is not behind the depth buffer's at its sample, and not
 * on the removed side of the section planes), so that it never lands on
 * a hidden one. Marks are points of the mesh, not of the screen, so
 * they stay on the model while it turns, and the figures are in file
 * units from the mesh's own positions (printq/measure.c). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

/* ==== Faces, as the scene keeps them ==== */

/* The scene keeps a face as one polygon, or as a fan of triangles (c0,
 * ck, ck+1) when it is not flat (scene.h): its polygons [p, q). */
typedef struct {
    uint32_t p, q;
} FaceRun;

static uint32_t face_ncorners(const Scene *s, FaceRun r)
{
    return r.q - r.p == 1 ? scene_poly_c0(s, r.p + 1) - scene_poly_c0(s, r.p) : r.q - r.p + 2;
}

/* Corner i of the face's outline: a fan's is c0, each triangle's
 * second corner, and the last one's third. */
static uint32_t face_corner(const Scene *s, FaceRun r, uint32_t i)
{
    const uint32_t *pc = s->poly_corner;
    if (r.q - r.p == 1 || i == 0)
        return pc[scene_poly_c0(s, r.p) + i];
    if (i <= r.q - r.p)
        return pc[scene_poly_c0(s, r.p + i - 1) + 1];
    return pc[scene_poly_c0(s, r.q - 1) + 2];
}

/* Face f of object ob (its own numbering, from 0) in the scene's
 * polygons: 0, or -1 when it has none. The polygons of an object follow
 * its faces' order. */
static int face_run(const Scene *s, const Object *ob, uint32_t f, FaceRun *out)
{
    uint32_t lo = ob->poly_first, hi = ob->poly_first + ob->poly_count;
    if (f >= ob->face_count)
        return -1;
    if (!s->poly_lface) {
        *out = (FaceRun){ lo + f, lo + f + 1 };
        return lo + f < hi ? 0 : -1;
    }
    while (lo < hi) {       /* the first polygon of a face not before f */
        uint32_t mid = lo + (hi - lo) / 2;
        if (s->poly_lface[mid] < f)
            lo = mid + 1;
        else
            hi = mid;
    }
    uint32_t q = lo, end = ob->poly_first + ob->poly_count;
    while (q < end && s->poly_lface[q] == f)
        q++;
    *out = (FaceRun){ lo, q };
    return q > lo ? 0 : -1;
}

/* ==== Points ==== */

/* Is the point there? Marks outlive edits of the scene (O, X) and come
 * from the command line (--marks): every use asks. */
static int exists(const Scene *s, const MeasurePick *k)
{
    if (k->obj < 0 || k->obj >= s->nobjs || !s->objs[k->obj].mesh)
        return 0;
    const Object *ob = &s->objs[k->obj];
    FaceRun r;
    switch (k->kind) {
    case MEASURE_VERTEX: return k->a < ob->mesh->nverts;
    case MEASURE_EDGE:   return k->a < ob->mesh->nverts && k->b < ob->mesh->nverts;
    case MEASURE_FACE:   return face_run(s, ob, k->a, &r) == 0;
    }
    return 0;
}

/* The mean of n vertices of mesh m (mesh units: file units times
 * 2^-pos_exp), in double; the vertices from a list, or a face's run. */
static void mean_of(const Mesh *m, const uint32_t *v, uint32_t n, double out[3])
{
    for (int j = 0; j < 3; j++)
        out[j] = 0;
    for (uint32_t i = 0; i < n; i++)
        for (int j = 0; j < 3; j++)
            out[j] += m->pos[3 * (size_t)v[i] + j];
    for (int j = 0; j < 3; j++)
        out[j] /= n;
}

static void face_centre(const Scene *s, const Mesh *m, FaceRun r, double out[3])
{
    uint32_t n = face_ncorners(s, r);
    for (int j = 0; j < 3; j++)
        out[j] = 0;
    for (uint32_t i = 0; i < n; i++) {
        const float *q = &m->pos[3 * (size_t)face_corner(s, r, i)];
        for (int j = 0; j < 3; j++)
            out[j] += q[j];
    }
    for (int j = 0; j < 3; j++)
        out[j] /= n;
}

/* The point in its mesh's units, in double: a vertex, an edge's
 * midpoint, a face's centre (the mean of its corners). It exists. */
static void pick_pos(const Scene *s, const MeasurePick *k, double out[3])
{
    const Object *ob = &s->objs[k->obj];
    FaceRun r;
    uint32_t v[2] = { k->a, k->b };
    if (k->kind == MEASURE_FACE && face_run(s, ob, k->a, &r) == 0)
        face_centre(s, ob->mesh, r, out);
    else
        mean_of(ob->mesh, v, k->kind == MEASURE_EDGE ? 2 : 1, out);
}

/* A point of object o (mesh units) in samples of the last frame (x, y,
 * depth) through mv, the object's model-view matrix: 0, or -1 behind
 * the eye. */
static int project(const Pipeline *p, const Mat4 *mv, const double q[3], double out[3])
{
    Vec3 w = m4_point(mv, v3((float)q[0], (float)q[1], (float)q[2]));
    return screen_view_point(&p->sp, w.x, w.y, w.z, out);
}

static Mat4 model_view(const Scene *s, int o)
{
    return m4_mul(camera_view(&s->cam), object_matrix(&s->objs[o]));
}

/* A mark's point in samples of the last frame: 0, or -1 behind the eye
 * or not there. */
static int on_screen(const Pipeline *p, const MeasurePick *k, double out[3])
{
    const Scene *s = p->scene;
    if (!exists(s, k))
        return -1;
    double q[3];
    pick_pos(s, k, q);
    Mat4 mv = model_view(s, k->obj);
    return project(p, &mv, q, out);
}

/* Does the last frame show the point (on the screen, not behind what
 * the depth buffer holds at its sample, within a margin for the faces
 * that meet at it)? */
static int shown(const Pipeline *p, const double sp[3])
{
    const FrameBufs *fb = &p->fb;
    if (!(sp[0] >= 0 && sp[1] >= 0 && sp[0] < fb->w && sp[1] < fb->h))
        return 0;
    float d = fb->depth[(size_t)sp[1] * (size_t)fb->w + (size_t)sp[0]];
    return !(d < INFINITY) || sp[2] <= d + 5e-3;
}

/* ==== The hunt for the nearest point ==== */

/* The search: from c on the screen, the way dx, dy (0, 0: the nearest
 * to c), the best so far. */
typedef struct {
    const Pipeline *p;
    Mat4     mv;                /* the object's model-view matrix */
    const SectionCut *cut;      /* the last frame's cut (NULL: none) */
    double   c[2];
    int      dx, dy;
    double   best;
    MeasurePick pick;
} Hunt;

/* Cut away: on the removed side of every plane of the last frame's
 * cut, where the cap hides it but the depth buffer cannot say so (it is
 * in front of the cap). */
static int cut_away(const SectionCut *cut, const double q[3])
{
    if (!cut || !cut->nplanes)
        return 0;
    float f[3] = { (float)q[0], (float)q[1], (float)q[2] };
    for (int i = 0; i < cut->nplanes; i++)
        if (section_side(&cut->plane[i], f) <= 0)
            return 0;
    return 1;
}

static void consider(Hunt *h, const MeasurePick *k, const double q[3])
{
    double sp[3];
    if (project(h->p, &h->mv, q, sp) || !shown(h->p, sp) || cut_away(h->cut, q))
        return;
    double ex = sp[0] - h->c[0], ey = sp[1] - h->c[1], score;
    if (h->dx || h->dy) {
        double along = ex * h->dx + ey * h->dy, across = fabs(ex * h->dy - ey * h->dx);
        if (along < 1)
            return;         /* not that way (or the cursor's own point) */
        score = along + 3 * across;
    } else {
        score = ex * ex + ey * ey;
    }
    if (score < h->best) {
        h->best = score;
        h->pick = *k;
    }
}

/* Object o's faces' centres and their edges' midpoints (an edge
 * between two faces is looked at twice: the same point, no harm). */
static void consider_faces(Hunt *h, int o)
{
    const Scene *s = h->p->scene;
    const Object *ob = &s->objs[o];
    uint32_t end = ob->poly_first + ob->poly_count;
    for (uint32_t p = ob->poly_first; p < end;) {
        FaceRun r = { p, p + 1 };
        while (s->poly_lface && r.q < end && s->poly_lface[r.q] == s->poly_lface[p])
            r.q++;
        MeasurePick k = { .obj = o, .kind = MEASURE_FACE, .a = scene_poly_lface(s, ob, p) };
        double q[3];
        face_centre(s, ob->mesh, r, q);
        consider(h, &k, q);
        uint32_t n = face_ncorners(s, r);
        for (uint32_t i = 0; i < n; i++) {
            uint32_t a = face_corner(s, r, i), b = face_corner(s, r, (i + 1) % n);
            uint32_t v[2] = { a < b ? a : b, a < b ? b : a };
            k = (MeasurePick){ .obj = o, .kind = MEASURE_EDGE, .a = v[0], .b = v[1] };
            mean_of(ob->mesh, v, 2, q);
            consider(h, &k, q);
        }
        p = r.q;
    }
}

/* The cursor to the best point seen from c the way dx, dy. */
static int hunt(Pipeline *p, const double c[2], int dx, int dy, int wide)
{
    const Scene *s = p->scene;
    Hunt h = { .p = p, .cut = p->sp.cut, .c = { c[0], c[1] }, .dx = dx, .dy = dy, .best = INFINITY,
               .pick = { .obj = -1 } };
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    for (int o = 0; o < nb; o++) {
        const Object *ob = &s->objs[o];
        if (!ob->mesh || (!ob->face_count && !ob->point_count))
            continue;
        h.mv = model_view(s, o);
        for (uint32_t v = ob->vert_min; v <= ob->vert_max && v < ob->mesh->nverts; v++) {
            MeasurePick k = { .obj = o, .kind = MEASURE_VERTEX, .a = v };
            double q[3];
            mean_of(ob->mesh, &v, 1, q);
            consider(&h, &k, q);
        }
        if (wide)
            consider_faces(&h, o);
    }
    if (h.pick.obj < 0)
        return -1;
    p->marks.cursor = 1;
    p->marks.cur = h.pick;
    return 0;
}

int app_measure_step(Pipeline *p, int dx, int dy)
{
    MeasureMarks *m = &p->marks;
    if (!p->fb.depth || !p->fb.w)
        return -1;
    double c[3] = { p->fb.w / 2.0, p->fb.h / 2.0, 0 };
    int from = m->cursor && on_screen(p, &m->cur, c) == 0;
    if (!from)
        dx = dy = 0;        /* no cursor yet: the point nearest the middle */
    return hunt(p, c, dx, dy, m->wide);
}

int app_measure_pick(Pipeline *p, double x, double y, int wide)
{
    if (!p->fb.depth || !p->fb.w)
        return -1;
    double c[2] = { x, y };
    return hunt(p, c, 0, 0, wide);
}

/* ==== In words ==== */

/* A point's position in its file's units (the scene's positions may
 * be scaled by a power of two: scene.h pos_exp). */
static PrintqPoint point_of(const Scene *s, const MeasurePick *k)
{
    PrintqPoint pt = { .vertex = k->kind == MEASURE_VERTEX ? k->a + 1 : 0 };
    double q[3];
    pick_pos(s, k, q);
    for (int j = 0; j < 3; j++)
        pt.p[j] = ldexp(q[j], s->pos_exp);
    return pt;
}

void app_measure_pick_word(const MeasurePick *k, char *buf, size_t len)
{
    char obj[16] = "";
    if (k->obj)
        snprintf(obj, sizeof obj, "%d:", k->obj + 1);
    if (k->kind == MEASURE_EDGE)
        snprintf(buf, len, "%se%u-%u", obj, k->a + 1, k->b + 1);
    else
        snprintf(buf, len, "%s%c%u", obj, k->kind == MEASURE_FACE ? 'f' : 'v', k->a + 1);
}

/* A 1-based index at *s (no sign, no leading zero): 0 with it 0-based. */
static int index_at(const char **s, uint32_t *out)
{
    const char *p = *s;
    if (*p < '1' || *p > '9')
        return -1;
    unsigned long long v = 0;
    for (; *p >= '0' && *p <= '9'; p++)
        if ((v = v * 10 + (unsigned)(*p - '0')) > UINT32_MAX)
            return -1;
    *out = (uint32_t)(v - 1);
    *s = p;
    return 0;
}

int app_measure_pick_parse(const char **s, MeasurePick *out)
{
    const char *p = *s;
    MeasurePick k = { 0 };
    if (*p >= '1' && *p <= '9') {
        uint32_t o;
        if (index_at(&p, &o) || *p != ':' || o >= 65535)
            return -1;
        k.obj = (int)o;
        p++;
    }
    k.kind = *p == 'e' ? MEASURE_EDGE : *p == 'f' ? MEASURE_FACE : MEASURE_VERTEX;
    if (*p != 'v' && *p != 'e' && *p != 'f')
        return -1;
    p++;
    if (index_at(&p, &k.a))
        return -1;
    if (k.kind == MEASURE_EDGE && (*p++ != '-' || index_at(&p, &k.b) || k.b == k.a))
        return -1;
    *out = k;
    *s = p;
    return 0;
}

void app_measure_words(const Scene *s, const MeasureMarks *m, int brief, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = 0;
    if (m->cursor && exists(s, &m->cur)) {
        char w[48];
        app_measure_pick_word(&m->cur, w, sizeof w);
        o += (size_t)snprintf(buf, len, "%s%s", m->wide ? "wide snap: " : "", w);
        if (!brief && o < len) {
            PrintqPoint c = point_of(s, &m->cur);
            o += (size_t)snprintf(buf + o, len - o, " %.4g %.4g %.4g", c.p[0], c.p[1], c.p[2]);
        }
    }
    int there = 1;
    for (int i = 0; i < m->n; i++)
        there &= exists(s, &m->mark[i]);
    if (o >= len)
        return;
    if (!there) {
        snprintf(buf + o, len - o, "%sa mark is on no point of the scene", o ? ", " : "");
        return;
    }
    if (m->n >= 2) {
        PrintqPoint pt[MEASURE_MARKS];
        for (int i = 0; i < m->n; i++)
            pt[i] = point_of(s, &m->mark[i]);
        PrintqMeasure r;
        printq_measure(pt, m->n, &r);
        o += (size_t)snprintf(buf + o, len - o, "%sAB %.6g (dx %.4g dy %.4g dz %.4g)", o ? ", " : "", r.dist, r.d[0],
                              r.d[1], r.d[2]);
        if (m->n == 3 && o < len)
            snprintf(buf + o, len - o, ", BC %.6g, angle ABC %.4g", r.dist2, r.angle);
    } else if (m->n == 1) {
        snprintf(buf + o, len - o, "%sA marked", o ? ", " : "");
    }
}

void app_measure_option(const MeasureMarks *m, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = 0;
    for (int i = 0; i < m->n && o < len; i++) {
        char w[48];
        app_measure_pick_word(&m->mark[i], w, sizeof w);
        o += (size_t)snprintf(buf + o, len - o, "%s%s", i ? "," : "", w);
    }
}

void app_measure_draw(Pipeline *p)
{
    const MeasureMarks *m = &p->marks;
    if (!p->img.w || (!m->n && !m->cursor))
        return;
    static const uint8_t line_rgb[3] = { 0, 230, 230 }, cur_rgb[3] = { 255, 255, 255 };
    double k = p->sp.w > 0 ? (double)p->sp.w / p->img.w : 1;
    int small = p->img.w < p->img.h ? p->img.w : p->img.h;
    int width = small >= 480 ? 3 : small >= 240 ? 2 : 1;
    double r = fmax(3, small / 40.0);
    double prev[3] = { 0, 0, 0 };
    for (int i = 0; i < m->n; i++) {
        double q[3];
        int ok = on_screen(p, &m->mark[i], q) == 0;
        if (ok && i > 0)
            image_line(&p->img, prev[0] / k, prev[1] / k, q[0] / k, q[1] / k, line_rgb, width);
        if (ok)
            image_ring(&p->img, q[0] / k, q[1] / k, r, line_rgb, width);
        if (ok)
            memcpy(prev, q, sizeof prev);
        else
            break;
    }
    double c[3];
    if (m->cursor && on_screen(p, &m->cur, c) == 0) {
        image_ring(&p->img, c[0] / k, c[1] / k, r * 1.6, cur_rgb, width);
        image_line(&p->img, c[0] / k - 2 * r, c[1] / k, c[0] / k + 2 * r, c[1] / k, cur_rgb, 1);
        image_line(&p->img, c[0] / k, c[1] / k - 2 * r, c[0] / k, c[1] / k + 2 * r, cur_rgb, 1);
    }
}
