/* genassets: writes zview's bundled models into a folder (`make assets`
 * runs `build/genassets assets`).
 *
 * Every model is built in memory first, then checked (indices in range,
 * no repeated corner, no zero-area or bent face, closed solids
 * watertight and wound counter-clockwise seen from outside, flat shapes
 * facing the way they claim, tubes that do not run into themselves) and
 * only then written. A failed check writes nothing and exits 1, so a bad
 * edit here cannot slip a broken model into assets/.
 *
 * The output is a pure function of this file: no clock, no randomness,
 * numbers printed with %.6g, so running it twice gives the same bytes
 * and `git diff assets/` shows only real changes. */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* ==== Vector math ==== */

typedef struct { double x, y, z; } V3;

static V3 v3(double x, double y, double z) { V3 r = { x, y, z }; return r; }
static V3 v_add(V3 a, V3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static V3 v_sub(V3 a, V3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static V3 v_scale(V3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
static double v_dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static double v_len(V3 a) { return sqrt(v_dot(a, a)); }
static V3 v_cross(V3 a, V3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static V3 v_norm(V3 a)
{
    double l = v_len(a);
    return l > 0 ? v_scale(a, 1.0 / l) : a;
}

/* A rigid motion p' = R p + t. Built from single-axis turns so each
 * placement below reads as "turn this much, then move there". */
typedef struct { double r[3][3]; V3 t; } Xform;

static Xform xf_identity(void)
{
    Xform x = { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } }, { 0, 0, 0 } };
    return x;
}

/* Turn by `deg` about axis 0 (x), 1 (y) or 2 (z), right-handed. */
static Xform xf_turn(int axis, double deg)
{
    Xform x = xf_identity();
    double c = cos(deg * PI / 180.0), s = sin(deg * PI / 180.0);
    int i = (axis + 1) % 3, j = (axis + 2) % 3;
    x.r[i][i] = c; x.r[i][j] = -s;
    x.r[j][i] = s; x.r[j][j] = c;
    return x;
}

static Xform xf_move(V3 t) { Xform x = xf_identity(); x.t = t; return x; }

static V3 xf_apply(const Xform *x, V3 p)
{
    return v3(x->r[0][0] * p.x + x->r[0][1] * p.y + x->r[0][2] * p.z + x->t.x,
              x->r[1][0] * p.x + x->r[1][1] * p.y + x->r[1][2] * p.z + x->t.y,
              x->r[2][0] * p.x + x->r[2][1] * p.y + x->r[2][2] * p.z + x->t.z);
}

/* `first`, then `second`. */
static Xform xf_then(Xform first, Xform second)
{
    Xform o;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            o.r[i][j] = second.r[i][0] * first.r[0][j] + second.r[i][1] * first.r[1][j] +
                        second.r[i][2] * first.r[2][j];
    o.t = xf_apply(&second, first.t);
    return o;
}

/* ==== The in-memory model ==== */

#define MAX_OBJS 16
#define MAX_MATS 16
#define NAME_MAX_LEN 32

typedef struct {
    char name[NAME_MAX_LEN];
    V3   kd;                    /* diffuse colour, 0..1 */
} Mat;

typedef struct {
    char     name[NAME_MAX_LEN];
    uint32_t vfirst, ffirst;    /* 0-based; each range ends where the next object's starts */
    int      closed;            /* must be a watertight solid wound CCW from outside */
    V3       facing;            /* every face normal points this way; 0,0,0 = no claim */
} Obj;

typedef struct {
    const char    *file;        /* "cube.obj" */
    const char    *mtlfile;     /* "scene.mtl", or NULL for no materials */
    V3            *pos, *rgb;
    unsigned char *has_rgb;     /* 1 = written as `v x y z r g b` */
    uint32_t       nv, capv;
    uint32_t      *corner;      /* 0-based vertex index per face corner */
    uint32_t       nc, capc;
    uint32_t      *fstart;      /* nf + 1 offsets into corner[] */
    int           *fmat;        /* material per face, -1 = none */
    uint32_t       nf, capf;
    Obj            objs[MAX_OBJS];
    int            nobj;
    Mat            mats[MAX_MATS];
    int            nmat;
    int            cur_mat;     /* what new faces get */
} Model;

/* Sizes of what was written, for the summary and the README table. */
typedef struct {
    uint32_t verts, faces, tris;
    long     bytes;
} Stats;

static void *xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n);
    if (!q) {
        fprintf(stderr, "genassets: out of memory\n");
        exit(1);   /* a build tool, not library code: nothing to restore */
    }
    return q;
}

static void model_init(Model *m, const char *file, const char *mtlfile)
{
    memset(m, 0, sizeof *m);
    m->file = file;
    m->mtlfile = mtlfile;
    m->cur_mat = -1;
    m->fstart = xrealloc(NULL, sizeof *m->fstart);
    m->fstart[0] = 0;
}

static void model_free(Model *m)
{
    free(m->pos); free(m->rgb); free(m->has_rgb);
    free(m->corner); free(m->fstart); free(m->fmat);
    memset(m, 0, sizeof *m);
}

static int model_mat(Model *m, const char *name, double r, double g, double b)
{
    if (m->nmat == MAX_MATS) {
        fprintf(stderr, "genassets: %s: too many materials\n", m->file);
        exit(1);
    }
    Mat *t = &m->mats[m->nmat];
    snprintf(t->name, sizeof t->name, "%s", name);
    t->kd = v3(r, g, b);
    return m->nmat++;
}

static void model_use(Model *m, int mat) { m->cur_mat = mat; }

/* Start a new `o` object; following vertices and faces belong to it. */
static void model_obj(Model *m, const char *name, int closed, V3 facing)
{
    if (m->nobj == MAX_OBJS) {
        fprintf(stderr, "genassets: %s: too many objects\n", m->file);
        exit(1);
    }
    Obj *o = &m->objs[m->nobj++];
    snprintf(o->name, sizeof o->name, "%s", name);
    o->vfirst = m->nv;
    o->ffirst = m->nf;
    o->closed = closed;
    o->facing = facing;
}

static uint32_t model_vc(Model *m, V3 p, const V3 *rgb)
{
    if (m->nv == m->capv) {
        m->capv = m->capv ? 2 * m->capv : 256;
        m->pos = xrealloc(m->pos, m->capv * sizeof *m->pos);
        m->rgb = xrealloc(m->rgb, m->capv * sizeof *m->rgb);
        m->has_rgb = xrealloc(m->has_rgb, m->capv);
    }
    m->pos[m->nv] = p;
    m->rgb[m->nv] = rgb ? *rgb : v3(0, 0, 0);
    m->has_rgb[m->nv] = rgb != NULL;
    return m->nv++;
}

static uint32_t model_v(Model *m, V3 p) { return model_vc(m, p, NULL); }

static void model_face(Model *m, int n, const uint32_t *idx)
{
    while (m->nc + (uint32_t)n > m->capc) {
        m->capc = m->capc ? 2 * m->capc : 1024;
        m->corner = xrealloc(m->corner, m->capc * sizeof *m->corner);
    }
    if (m->nf == m->capf) {
        m->capf = m->capf ? 2 * m->capf : 256;
        m->fstart = xrealloc(m->fstart, (m->capf + 1) * sizeof *m->fstart);
        m->fmat = xrealloc(m->fmat, m->capf * sizeof *m->fmat);
    }
    memcpy(m->corner + m->nc, idx, (size_t)n * sizeof *idx);
    m->nc += (uint32_t)n;
    m->fmat[m->nf] = m->cur_mat;
    m->fstart[++m->nf] = m->nc;
}

static void model_tri(Model *m, uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t f[3] = { a, b, c };
    model_face(m, 3, f);
}

static void model_quad(Model *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    uint32_t f[4] = { a, b, c, d };
    model_face(m, 4, f);
}

/* Move every vertex made since `vfrom` (shapes are built at the origin
 * and placed afterwards). */
static void model_place(Model *m, uint32_t vfrom, Xform x)
{
    for (uint32_t i = vfrom; i < m->nv; i++)
        m->pos[i] = xf_apply(&x, m->pos[i]);
}

static uint32_t obj_vend(const Model *m, int k)
{
    return k + 1 < m->nobj ? m->objs[k + 1].vfirst : m->nv;
}

static uint32_t obj_fend(const Model *m, int k)
{
    return k + 1 < m->nobj ? m->objs[k + 1].ffirst : m->nf;
}

/* ==== Shapes (each appends to the current object) ==== */

/* Axis-aligned box; the corner numbering is bit 0 = x, 1 = y, 2 = z. */
static void shape_box(Model *m, V3 lo, V3 hi)
{
    uint32_t c[8];
    for (int i = 0; i < 8; i++)
        c[i] = model_v(m, v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z));
    model_quad(m, c[0], c[4], c[6], c[2]);   /* -x */
    model_quad(m, c[1], c[3], c[7], c[5]);   /* +x */
    model_quad(m, c[0], c[1], c[5], c[4]);   /* -y */
    model_quad(m, c[2], c[6], c[7], c[3]);   /* +y */
    model_quad(m, c[0], c[2], c[3], c[1]);   /* -z */
    model_quad(m, c[4], c[5], c[7], c[6]);   /* +z */
}

typedef V3 (*SurfaceFn)(double u, double v, const void *ctx);

/* A surface closed in both directions (torus topology): nu x nv
 * vertices, each grid cell split into two triangles along the same
 * diagonal. `fn` takes u, v in [0, 1); d/du x d/dv must point outward. */
static void shape_wrapped_grid(Model *m, int nu, int nv, SurfaceFn fn, const void *ctx)
{
    uint32_t base = m->nv;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++)
            model_v(m, fn((double)i / nu, (double)j / nv, ctx));
    for (int i = 0; i < nu; i++) {
        int i1 = (i + 1) % nu;
        for (int j = 0; j < nv; j++) {
            int j1 = (j + 1) % nv;
            uint32_t a = base + (uint32_t)(i * nv + j), b = base + (uint32_t)(i1 * nv + j);
            uint32_t c = base + (uint32_t)(i1 * nv + j1), d = base + (uint32_t)(i * nv + j1);
            model_tri(m, a, b, c);
            model_tri(m, a, c, d);
        }
    }
}

/* UV sphere around the y axis: one vertex per pole (no zero-area pole
 * slivers), `stacks - 1` rings of `slices` vertices. */
static void shape_sphere(Model *m, V3 c, double r, int slices, int stacks)
{
    uint32_t top = model_v(m, v_add(c, v3(0, r, 0)));
    uint32_t ring0 = m->nv;
    for (int k = 1; k < stacks; k++) {
        double th = PI * k / stacks;
        for (int j = 0; j < slices; j++) {
            double ph = 2 * PI * j / slices;
            model_v(m, v_add(c, v3(r * sin(th) * cos(ph), r * cos(th), -r * sin(th) * sin(ph))));
        }
    }
    uint32_t bottom = model_v(m, v_add(c, v3(0, -r, 0)));
    for (int j = 0; j < slices; j++) {
        uint32_t j1 = (uint32_t)((j + 1) % slices);
        model_tri(m, top, ring0 + (uint32_t)j, ring0 + j1);
        for (int k = 0; k + 1 < stacks - 1; k++) {
            uint32_t a = ring0 + (uint32_t)(k * slices + j), b = ring0 + (uint32_t)(k * slices) + j1;
            uint32_t d = a + (uint32_t)slices, e = b + (uint32_t)slices;
            model_tri(m, a, d, e);
            model_tri(m, a, e, b);
        }
        uint32_t last = ring0 + (uint32_t)((stacks - 2) * slices);
        model_tri(m, last + (uint32_t)j, bottom, last + j1);
    }
}

/* Hue h in [0, 1) to a saturated colour (for vertex colours). */
static V3 hue_rgb(double h)
{
    double k[3] = { 0, 2.0 / 3.0, 1.0 / 3.0 };
    double c[3];
    for (int i = 0; i < 3; i++) {
        double t = fabs(fmod(h + k[i], 1.0) * 6.0 - 3.0) - 1.0;
        c[i] = t < 0 ? 0 : t > 1 ? 1 : t;
    }
    return v3(c[0], c[1], c[2]);
}

/* Cone standing on the y = 0 plane, apex at y = h; the base is a single
 * n-gon face. With `rainbow`, every vertex carries a colour (hue around
 * the rim, white apex) instead of relying on a material. */
static void shape_cone(Model *m, double r, double h, int n, int rainbow)
{
    V3 white = v3(1, 1, 1);
    uint32_t apex = model_vc(m, v3(0, h, 0), rainbow ? &white : NULL);
    uint32_t rim = m->nv;
    for (int j = 0; j < n; j++) {
        double ph = 2 * PI * j / n;
        V3 col = hue_rgb((double)j / n);
        model_vc(m, v3(r * cos(ph), 0, -r * sin(ph)), rainbow ? &col : NULL);
    }
    uint32_t *base = xrealloc(NULL, (size_t)n * sizeof *base);
    for (int j = 0; j < n; j++) {
        model_tri(m, rim + (uint32_t)j, rim + (uint32_t)((j + 1) % n), apex);
        base[j] = rim + (uint32_t)(n - 1 - j);   /* seen from below: reversed */
    }
    model_face(m, n, base);
    free(base);
}

/* A flat polygon from n (x, y) pairs in the plane z = z0. */
static void shape_polygon(Model *m, int n, const double *xy, double dx, double dy, double z0)
{
    uint32_t idx[32];
    for (int i = 0; i < n && i < 32; i++)
        idx[i] = model_v(m, v3(xy[2 * i] + dx, xy[2 * i + 1] + dy, z0));
    model_face(m, n, idx);
}

/* ---- Torus: ring radius R in the xy plane (axis z), tube radius r ---- */

typedef struct { double big, small; } TorusParams;

static V3 torus_at(double u, double v, const void *ctx)
{
    const TorusParams *t = ctx;
    double a = 2 * PI * u, b = 2 * PI * v;
    double rho = t->big + t->small * cos(b);
    return v3(rho * cos(a), rho * sin(a), t->small * sin(b));
}

static void shape_torus(Model *m, double big, double small, int nu, int nv)
{
    TorusParams t = { big, small };
    shape_wrapped_grid(m, nu, nv, torus_at, &t);
}

/* ---- Torus knot tube ----
 * The core curve runs p times round the z axis and q times round the
 * ring (R, a); the tube's frame comes from the direction away from the
 * ring's centre circle, which is never along the tangent while p*R != 0,
 * so the frame closes on itself without any twist correction. */

typedef struct { int p, q; double big, a, tube; } KnotParams;

static V3 knot_curve(const KnotParams *k, double t, V3 *tangent_out, V3 *away_out)
{
    double pt = k->p * t, qt = k->q * t;
    double rho = k->big + k->a * cos(qt), drho = -k->a * k->q * sin(qt);
    *tangent_out = v_norm(v3(drho * cos(pt) - rho * k->p * sin(pt),
                             drho * sin(pt) + rho * k->p * cos(pt),
                             k->a * k->q * cos(qt)));
    *away_out = v3(cos(qt) * cos(pt), cos(qt) * sin(pt), sin(qt));
    return v3(rho * cos(pt), rho * sin(pt), k->a * sin(qt));
}

static V3 knot_at(double u, double v, const void *ctx)
{
    const KnotParams *k = ctx;
    V3 tan, away;
    V3 c = knot_curve(k, 2 * PI * u, &tan, &away);
    V3 n = v_norm(v_sub(away, v_scale(tan, v_dot(away, tan))));
    V3 b = v_cross(tan, n);
    /* -v: d/du x d/dv then points out of the tube. */
    double th = -2 * PI * v;
    return v_add(c, v_scale(v_add(v_scale(n, cos(th)), v_scale(b, sin(th))), k->tube));
}

/* The tube must not pass through itself: any two core points further
 * apart along the curve than half a tube circumference must be more
 * than a tube diameter apart in space, and the core must not bend
 * tighter than the tube radius. Returns 0 when that holds. */
static int knot_check(const char *file, const KnotParams *k)
{
    enum { N = 1200 };
    static V3 pt[N];
    static double arc[N + 1];
    V3 tan, away;
    for (int i = 0; i < N; i++)
        pt[i] = knot_curve(k, 2 * PI * i / N, &tan, &away);
    arc[0] = 0;
    for (int i = 0; i < N; i++)
        arc[i + 1] = arc[i] + v_len(v_sub(pt[(i + 1) % N], pt[i]));
    double total = arc[N], gap = 1e30, bend = 1e30;
    for (int i = 0; i < N; i++) {
        for (int j = i + 1; j < N; j++) {
            double s = arc[j] - arc[i];
            if (s > total - s)
                s = total - s;
            if (s > PI * k->tube) {
                double d = v_len(v_sub(pt[i], pt[j]));
                if (d < gap)
                    gap = d;
            }
        }
        /* radius of the circle through three neighbours */
        V3 a = pt[(i + N - 1) % N], b = pt[i], c = pt[(i + 1) % N];
        double ab = v_len(v_sub(a, b)), bc = v_len(v_sub(b, c)), ca = v_len(v_sub(c, a));
        double area2 = v_len(v_cross(v_sub(b, a), v_sub(c, a)));
        if (area2 > 0 && ab * bc * ca / (2 * area2) < bend)
            bend = ab * bc * ca / (2 * area2);
    }
    if (gap <= 2.2 * k->tube || bend <= 1.5 * k->tube) {
        fprintf(stderr, "genassets: %s: knot tube %.3g too thick (strand gap %.3g, tightest bend %.3g)\n",
                file, k->tube, gap, bend);
        return -1;
    }
    return 0;
}

static void shape_knot(Model *m, const KnotParams *k, int along, int around)
{
    shape_wrapped_grid(m, along, around, knot_at, k);
}

/* ==== Checks ==== */

static V3 face_normal(const Model *m, uint32_t f)   /* Newell: |n| = 2 * area */
{
    V3 n = v3(0, 0, 0);
    uint32_t s = m->fstart[f], e = m->fstart[f + 1];
    for (uint32_t i = s; i < e; i++) {
        V3 a = m->pos[m->corner[i]], b = m->pos[m->corner[i + 1 < e ? i + 1 : s]];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    return n;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Watertight and consistently wound: every directed edge once, and its
 * reverse present; then the signed volume says the winding is outward. */
static int check_closed(const Model *m, int k)
{
    const Obj *o = &m->objs[k];
    uint32_t fs = o->ffirst, fe = obj_fend(m, k);
    size_t n = m->fstart[fe] - m->fstart[fs], at = 0;
    uint64_t *edge = xrealloc(NULL, (n ? n : 1) * sizeof *edge);
    double vol = 0;
    for (uint32_t f = fs; f < fe; f++) {
        uint32_t s = m->fstart[f], e = m->fstart[f + 1];
        for (uint32_t i = s; i < e; i++) {
            uint32_t a = m->corner[i], b = m->corner[i + 1 < e ? i + 1 : s];
            edge[at++] = (uint64_t)a << 32 | b;
        }
        for (uint32_t i = s + 1; i + 1 < e; i++)
            vol += v_dot(m->pos[m->corner[s]],
                         v_cross(m->pos[m->corner[i]], m->pos[m->corner[i + 1]])) / 6.0;
    }
    qsort(edge, n, sizeof *edge, cmp_u64);
    const char *bad = NULL;
    for (size_t i = 0; i < n && !bad; i++) {
        uint64_t rev = edge[i] << 32 | edge[i] >> 32;
        if (i + 1 < n && edge[i] == edge[i + 1])
            bad = "an edge is used twice the same way (winding flips)";
        else if (!bsearch(&rev, edge, n, sizeof *edge, cmp_u64))
            bad = "an edge has no partner (surface is open)";
    }
    free(edge);
    if (!bad && vol <= 0)
        bad = "wound inside out (negative volume)";
    if (bad) {
        fprintf(stderr, "genassets: %s: object %s: %s\n", m->file, o->name, bad);
        return -1;
    }
    return 0;
}

static int model_check(const Model *m)
{
    int bad = 0, had_mat = 0;
    for (int k = 0; k < m->nobj; k++) {
        const Obj *o = &m->objs[k];
        uint32_t vs = o->vfirst, ve = obj_vend(m, k);
        for (uint32_t f = o->ffirst; f < obj_fend(m, k); f++) {
            uint32_t s = m->fstart[f], e = m->fstart[f + 1];
            const char *why = NULL;
            if (e - s < 3)
                why = "fewer than 3 corners";
            for (uint32_t i = s; i < e && !why; i++) {
                if (m->corner[i] < vs || m->corner[i] >= ve)
                    why = "uses a vertex of another object";
                for (uint32_t j = s; j < i && !why; j++)
                    if (m->corner[i] == m->corner[j])
                        why = "repeats a corner";
            }
            if (m->fmat[f] >= 0)
                had_mat = 1;
            else if (had_mat)
                why = "has no material after one was set (OBJ cannot unset usemtl)";
            V3 n = v3(0, 0, 0);
            if (!why) {
                n = face_normal(m, f);
                if (v_len(n) < 1e-9)
                    why = "has zero area";
            }
            for (uint32_t i = s; i < e && !why; i++)   /* flat: no corner off the plane */
                if (fabs(v_dot(v_norm(n), v_sub(m->pos[m->corner[i]], m->pos[m->corner[s]]))) > 1e-9)
                    why = "is not planar";
            if (!why && v_len(o->facing) > 0 && v_dot(n, o->facing) <= 0)
                why = "faces the wrong way";
            if (why) {
                fprintf(stderr, "genassets: %s: object %s: face %u %s\n",
                        m->file, o->name, (unsigned)(f + 1), why);
                bad = 1;
                break;
            }
        }
        if (o->closed && check_closed(m, k))
            bad = 1;
    }
    return bad ? -1 : 0;
}

/* ==== Writing ==== */

/* %.6g, without "-0" or 1e-17 noise from sin/cos near zero. */
static void put_num(FILE *fp, double x)
{
    if (fabs(x) < 5e-7)
        x = 0;
    fprintf(fp, " %.6g", x);
}

static FILE *open_out(const char *dir, const char *file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    FILE *fp = fopen(path, "wb");
    if (!fp)
        perror(path);
    return fp;
}

static int close_out(FILE *fp, const char *dir, const char *file, long *bytes_out)
{
    long n = ftell(fp);
    int err = ferror(fp);
    if (fclose(fp) != 0 || err) {
        fprintf(stderr, "genassets: %s/%s: write failed\n", dir, file);
        return -1;
    }
    if (bytes_out)
        *bytes_out = n;
    return 0;
}

static int write_mtl(const Model *m, const char *dir)
{
    FILE *fp = open_out(dir, m->mtlfile);
    if (!fp)
        return -1;
    fprintf(fp, "# %s: materials for %s\n", m->mtlfile, m->file);
    fprintf(fp, "# made by tools/genassets.c (make assets); edit that, not this file\n");
    for (int i = 0; i < m->nmat; i++) {
        fprintf(fp, "\nnewmtl %s\nKa 0 0 0\nKd", m->mats[i].name);
        put_num(fp, m->mats[i].kd.x);
        put_num(fp, m->mats[i].kd.y);
        put_num(fp, m->mats[i].kd.z);
        fprintf(fp, "\nKs 0 0 0\nd 1\nillum 1\n");
    }
    return close_out(fp, dir, m->mtlfile, NULL);
}

/* `about` is the header: one line per string, NULL-terminated. */
static int model_write(const Model *m, const char *dir, const char *const *about, Stats *st)
{
    if (model_check(m))
        return -1;
    memset(st, 0, sizeof *st);
    st->verts = m->nv;
    st->faces = m->nf;
    for (uint32_t f = 0; f < m->nf; f++)
        st->tris += m->fstart[f + 1] - m->fstart[f] - 2;
    if (m->mtlfile && write_mtl(m, dir))
        return -1;

    FILE *fp = open_out(dir, m->file);
    if (!fp)
        return -1;
    fprintf(fp, "# %s: %s\n", m->file, about[0]);
    for (int i = 1; about[i]; i++)
        fprintf(fp, "# %s\n", about[i]);
    fprintf(fp, "# %u vertices, %u faces, %u triangles, %d object%s\n", (unsigned)st->verts,
            (unsigned)st->faces, (unsigned)st->tris, m->nobj, m->nobj == 1 ? "" : "s");
    fprintf(fp, "# made by tools/genassets.c (make assets); edit that, not this file\n");
    if (m->mtlfile)
        fprintf(fp, "mtllib %s\n", m->mtlfile);
    int cur = -1;
    for (int k = 0; k < m->nobj; k++) {
        const Obj *o = &m->objs[k];
        fprintf(fp, "\no %s\n", o->name);
        for (uint32_t v = o->vfirst; v < obj_vend(m, k); v++) {
            fputc('v', fp);
            put_num(fp, m->pos[v].x);
            put_num(fp, m->pos[v].y);
            put_num(fp, m->pos[v].z);
            if (m->has_rgb[v]) {
                put_num(fp, m->rgb[v].x);
                put_num(fp, m->rgb[v].y);
                put_num(fp, m->rgb[v].z);
            }
            fputc('\n', fp);
        }
        for (uint32_t f = o->ffirst; f < obj_fend(m, k); f++) {
            if (m->fmat[f] >= 0 && m->fmat[f] != cur) {
                cur = m->fmat[f];
                fprintf(fp, "usemtl %s\n", m->mats[cur].name);
            }
            fputc('f', fp);
            for (uint32_t i = m->fstart[f]; i < m->fstart[f + 1]; i++)
                fprintf(fp, " %u", (unsigned)(m->corner[i] + 1));
            fputc('\n', fp);
        }
    }
    return close_out(fp, dir, m->file, &st->bytes);
}

/* ==== The models ==== */

static const V3 NO_FACING = { 0, 0, 0 };

static int make_cube(const char *dir, Stats *st)
{
    static const char *const about[] = {
        "the unit cube, [-0.5, 0.5] on every axis, as 6 quads",
        "wound counter-clockwise seen from outside, so every normal points out",
        NULL };
    Model m;
    model_init(&m, "cube.obj", NULL);
    model_obj(&m, "cube", 1, NO_FACING);
    shape_box(&m, v3(-0.5, -0.5, -0.5), v3(0.5, 0.5, 0.5));
    int rc = model_write(&m, dir, about, st);
    model_free(&m);
    return rc;
}

static int make_concave(const char *dir, Stats *st)
{
    static const char *const about[] = {
        "concave polygons, each ONE face, flat in the z = 0 plane, facing +z",
        "L (6 corners), U (8), comb with three teeth (12), arrow (7), chevron (6).",
        "A fan from the first corner covers area outside each of them, so",
        "drawing them right needs a real polygon fill or an ear-clipping split.",
        NULL };
    static const double ell[] = { 2, 0, 2, 0.6, 0.6, 0.6, 0.6, 2, 0, 2, 0, 0 };
    static const double you[] = { 0, 0, 2, 0, 2, 2, 1.5, 2, 1.5, 0.5, 0.5, 0.5, 0.5, 2, 0, 2 };
    static const double comb[] = { 0, 0, 2.5, 0, 2.5, 2, 2, 2, 2, 0.5, 1.5, 0.5,
                                   1.5, 2, 1, 2, 1, 0.5, 0.5, 0.5, 0.5, 2, 0, 2 };
    static const double arrow[] = { 0, 0.6, 1.2, 0.6, 1.2, 0, 2.2, 1, 1.2, 2, 1.2, 1.4, 0, 1.4 };
    static const double chevron[] = { 0, 2, 1, 1, 0, 0, 0.8, 0, 1.8, 1, 0.8, 2 };
    V3 up = v3(0, 0, 1);
    Model m;
    model_init(&m, "concave.obj", NULL);
    model_obj(&m, "L", 0, up);
    shape_polygon(&m, 6, ell, -4.2, 0.3, 0);
    model_obj(&m, "U", 0, up);
    shape_polygon(&m, 8, you, -1.5, 0.3, 0);
    model_obj(&m, "comb", 0, up);
    shape_polygon(&m, 12, comb, 1.3, 0.3, 0);
    model_obj(&m, "arrow", 0, up);
    shape_polygon(&m, 7, arrow, -3.0, -2.6, 0);
    model_obj(&m, "chevron", 0, up);
    shape_polygon(&m, 6, chevron, 0.4, -2.6, 0);
    int rc = model_write(&m, dir, about, st);
    model_free(&m);
    return rc;
}

static int make_star_pierce(const char *dir, Stats *st)
{
    static const char *const about[] = {
        "a five-point star as ONE 10-corner concave face (z = 0, facing +z),",
        "a thin triangle stabbing through the middle of the star, and, to the",
        "right, two triangles tilted +-27 degrees that pass through each other",
        "(each has an edge poking through the other). No depth order per face",
        "exists here: the renderer has to resolve depth per pixel or split faces.",
        NULL };
    Model m;
    model_init(&m, "star-pierce.obj", NULL);
    model_obj(&m, "star", 0, v3(0, 0, 1));
    double star[20];
    for (int i = 0; i < 10; i++) {
        double ang = PI / 2 + PI * i / 5, r = i % 2 ? 0.4 : 1.0;
        star[2 * i] = r * cos(ang);
        star[2 * i + 1] = r * sin(ang);
    }
    shape_polygon(&m, 10, star, 0, 0, 0);

    /* Crosses z = 0 along y = 0.071, |x| < 0.23: inside the star's core
     * pentagon (half-width 0.31 there). */
    model_obj(&m, "stake", 0, NO_FACING);
    model_tri(&m, model_v(&m, v3(-0.4, -0.1, -0.6)), model_v(&m, v3(0.4, -0.1, -0.6)),
              model_v(&m, v3(0, 0.3, 0.8)));

    /* Planes z = y/2 and z = -y/2 meet on y = z = 0, where the first
     * spans x 2.5..3.5 and the second 2.8..3.8. */
    model_obj(&m, "blade_a", 0, NO_FACING);
    model_tri(&m, model_v(&m, v3(2, -1, -0.5)), model_v(&m, v3(4, -1, -0.5)),
              model_v(&m, v3(3, 1, 0.5)));
    model_obj(&m, "blade_b", 0, NO_FACING);
    model_tri(&m, model_v(&m, v3(4.3, 1, -0.5)), model_v(&m, v3(2.3, 1, -0.5)),
              model_v(&m, v3(3.3, -1, 0.5)));
    int rc = model_write(&m, dir, about, st);
    model_free(&m);
    return rc;
}

static int make_cyclic(const char *dir, Stats *st)
{
    static const char *const about[] = {
        "four long thin bars framing a square, each tilted along its length",
        "so that, seen from +z, bottom is over right, right over top, top over",
        "left and left over bottom: a cycle, so no back-to-front order of whole",
        "faces exists (the painter's algorithm must fail, per-pixel depth works).",
        "The bars never touch: at each overlap they are >= 0.55 apart in z.",
        NULL };
    static const char *names[4] = { "bar_bottom", "bar_right", "bar_top", "bar_left" };
    static const double kd[4][3] = { { 0.9, 0.2, 0.15 }, { 0.2, 0.75, 0.25 },
                                     { 0.2, 0.4, 0.95 }, { 0.95, 0.8, 0.15 } };
    static const char *mats[4] = { "red", "green", "blue", "yellow" };
    Model m;
    model_init(&m, "cyclic.obj", "cyclic.mtl");
    for (int i = 0; i < 4; i++) {
        model_mat(&m, mats[i], kd[i][0], kd[i][1], kd[i][2]);
    }
    for (int i = 0; i < 4; i++) {
        /* The bottom bar, z rising with x, turned i quarter turns about z:
         * where it meets the next bar it is high, the previous one low. */
        model_use(&m, i);
        model_obj(&m, names[i], 0, v3(0, 0, 1));
        uint32_t v0 = m.nv;
        model_quad(&m, model_v(&m, v3(-2, -2, -0.5)), model_v(&m, v3(2, -2, 0.5)),
                   model_v(&m, v3(2, -1.4, 0.5)), model_v(&m, v3(-2, -1.4, -0.5)));
        model_place(&m, v0, xf_turn(2, 90.0 * i));
    }
    int rc = model_write(&m, dir, about, st);
    model_free(&m);
    return rc;
}

static int make_torus(const char *dir, Stats *st)
{
    static const char *const about[] = {
        "a torus, ring radius 1, tube radius 0.4, 96 x 64 cells as triangles,",
        "turned 60 degrees about x so the +z view sees into the hole and the",
        "tube hides part of itself. Closed, wound CCW seen from outside.",
        NULL };
    Model m;
    model_init(&m, "torus.obj", NULL);
    model_obj(&m, "torus", 1, NO_FACING);
    shape_torus(&m, 1.0, 0.4, 96, 64);
    model_place(&m, 0, xf_turn(0, -60));
    int rc = model_write(&m, dir, about, st);
    model_free(&m);
    return rc;
}

static int make_knot(const char *dir, Stats *st)
{
    static const char *const about[] = {
        "a (3,7) torus knot tube: the core winds 3 times round the z axis and",
        "7 times round a ring of radius 1 (offset 0.45); tube radius 0.12,",
        "640 x 24 cells as triangles. Seen from +z it crosses itself 14 times:",
        "many thin, deep overlaps. Closed, wound CCW seen from outside.",
        NULL };
    KnotParams k = { 3, 7, 1.0, 0.45, 0.12 };
    if (knot_check("knot.obj", &k))
        return -1;
    Model m;
    model_init(&m, "knot.obj", NULL);
    model_obj(&m, "knot_3_7", 1, NO_FACING);
    shape_knot(&m, &k, 640, 24);
    int rc = model_write(&m, dir, about, st);
    model_free(&m);
    return rc;
}

static int make_scene(const char *dir, Stats *st)
{
    static const char *const about[] = {
        "a small room for depth tests; camera on +z looking to -z, +y up.",
        "Floor (y = -1) and back wall (z = -3) quads, a sphere (1984 triangles),",
        "a turned cube in front of the sphere, a cone behind the cube and a",
        "torus lying on the floor in front of the sphere's right side. The cone",
        "has per-vertex colours (`v x y z r g b`) and no material; it comes",
        "first because OBJ has no way to unset a material. Solids float 0.01",
        "above the floor so no two faces are coplanar.",
        NULL };
    Model m;
    model_init(&m, "scene.obj", "scene.mtl");
    int floor_mat = model_mat(&m, "floor", 0.6, 0.6, 0.55);
    int wall = model_mat(&m, "wall", 0.55, 0.65, 0.85);
    int red = model_mat(&m, "red", 0.85, 0.15, 0.1);
    int green = model_mat(&m, "green", 0.2, 0.7, 0.3);
    int gold = model_mat(&m, "gold", 0.95, 0.7, 0.2);
    uint32_t v0;

    model_obj(&m, "cone", 1, NO_FACING);
    v0 = m.nv;
    shape_cone(&m, 0.7, 1.8, 32, 1);
    model_place(&m, v0, xf_move(v3(-1.9, -0.99, -1.7)));

    model_use(&m, floor_mat);
    model_obj(&m, "floor", 0, v3(0, 1, 0));
    model_quad(&m, model_v(&m, v3(-3, -1, 2)), model_v(&m, v3(3, -1, 2)),
               model_v(&m, v3(3, -1, -3)), model_v(&m, v3(-3, -1, -3)));

    model_use(&m, wall);
    model_obj(&m, "wall", 0, v3(0, 0, 1));
    model_quad(&m, model_v(&m, v3(-3, -1, -3)), model_v(&m, v3(3, -1, -3)),
               model_v(&m, v3(3, 2.5, -3)), model_v(&m, v3(-3, 2.5, -3)));

    model_use(&m, red);
    model_obj(&m, "sphere", 1, NO_FACING);
    shape_sphere(&m, v3(0.5, -0.04, -1.6), 0.95, 32, 32);

    model_use(&m, green);
    model_obj(&m, "cube", 1, NO_FACING);
    v0 = m.nv;
    shape_box(&m, v3(-0.5, -0.5, -0.5), v3(0.5, 0.5, 0.5));
    model_place(&m, v0, xf_then(xf_turn(1, 35), xf_move(v3(-0.7, -0.49, -0.2))));

    model_use(&m, gold);
    model_obj(&m, "torus", 1, NO_FACING);
    v0 = m.nv;
    shape_torus(&m, 0.45, 0.15, 32, 16);
    model_place(&m, v0, xf_then(xf_turn(0, -90), xf_move(v3(1.7, -0.84, 0.3))));

    int rc = model_write(&m, dir, about, st);
    model_free(&m);
    return rc;
}

static int make_demo(const char *dir, Stats *st)
{
    static const char *const about[] = {
        "zview's demo scene (what `zview` shows with no file): an orange",
        "trefoil knot standing over an 8 x 5 checker floor, with a red cone,",
        "a blue sphere, a green cube and a violet torus in front. The whole",
        "scene is pitched 34 degrees toward +z so the default view from +z",
        "looks down onto the floor.",
        NULL };
    Model m;
    model_init(&m, "demo.obj", "demo.mtl");
    int light = model_mat(&m, "tile_light", 0.85, 0.85, 0.8);
    int dark = model_mat(&m, "tile_dark", 0.22, 0.26, 0.36);
    int orange = model_mat(&m, "knot_orange", 1.0, 0.5, 0.08);
    int blue = model_mat(&m, "sphere_blue", 0.2, 0.45, 1.0);
    int green = model_mat(&m, "cube_green", 0.25, 0.8, 0.3);
    int red = model_mat(&m, "cone_red", 0.9, 0.15, 0.15);
    int violet = model_mat(&m, "torus_violet", 0.7, 0.3, 0.9);
    uint32_t v0;

    /* Floor: a shared (COLS+1) x (ROWS+1) vertex grid, light tiles first,
     * then dark. Wide and shallow, like the terminal, so the scene's
     * bounding sphere (what a fit-to-view sees) stays tight. */
    enum { COLS = 8, ROWS = 5 };
    const double tile = 0.6, hx = COLS * tile / 2, hz = ROWS * tile / 2;
    model_obj(&m, "floor", 0, v3(0, 1, 0));
    uint32_t g0 = m.nv;
    for (int r = 0; r <= ROWS; r++)
        for (int c = 0; c <= COLS; c++)
            model_v(&m, v3(-hx + c * tile, 0, hz - r * tile));
    for (int pass = 0; pass < 2; pass++) {
        model_use(&m, pass ? dark : light);
        for (int r = 0; r < ROWS; r++)
            for (int c = 0; c < COLS; c++) {
                if ((r + c) % 2 != pass)
                    continue;
                uint32_t a = g0 + (uint32_t)(r * (COLS + 1) + c);
                model_quad(&m, a, a + 1, a + COLS + 2, a + COLS + 1);
            }
    }

    KnotParams k = { 2, 3, 0.85, 0.42, 0.2 };
    if (knot_check(m.file, &k)) {
        model_free(&m);
        return -1;
    }
    model_use(&m, orange);
    model_obj(&m, "trefoil", 1, NO_FACING);
    v0 = m.nv;
    shape_knot(&m, &k, 320, 24);
    model_place(&m, v0, xf_then(xf_turn(2, 90), xf_move(v3(0, 1.6, -0.7))));

    /* The small solids stand in a row in front, two each side. */
    model_use(&m, red);
    model_obj(&m, "cone", 1, NO_FACING);
    v0 = m.nv;
    shape_cone(&m, 0.36, 1.0, 32, 0);
    model_place(&m, v0, xf_move(v3(-1.85, 0.01, 0.75)));

    model_use(&m, blue);
    model_obj(&m, "sphere", 1, NO_FACING);
    shape_sphere(&m, v3(-0.85, 0.41, 0.9), 0.4, 32, 16);

    model_use(&m, green);
    model_obj(&m, "cube", 1, NO_FACING);
    v0 = m.nv;
    shape_box(&m, v3(-0.32, 0, -0.32), v3(0.32, 0.64, 0.32));
    model_place(&m, v0, xf_then(xf_turn(1, 30), xf_move(v3(0.85, 0.01, 0.9))));

    model_use(&m, violet);
    model_obj(&m, "torus", 1, NO_FACING);
    v0 = m.nv;
    shape_torus(&m, 0.34, 0.12, 40, 16);
    model_place(&m, v0, xf_then(xf_turn(0, -90), xf_move(v3(1.85, 0.13, 0.75))));

    model_place(&m, 0, xf_turn(0, 34));   /* pitch the whole scene toward the camera */

    int rc = model_write(&m, dir, about, st);
    model_free(&m);
    return rc;
}

/* ==== README ==== */

typedef struct {
    const char *file;
    int (*make)(const char *dir, Stats *st);
    const char *tests;          /* the README's "what it tests" column */
    Stats st;
} Asset;

static Asset assets[] = {
    { "cube.obj", make_cube, "the smallest closed solid: quads, culling, fit-to-view", { 0, 0, 0, 0 } },
    { "concave.obj", make_concave, "concave single-face polygons (L, U, comb, arrow, chevron): "
      "a fan from corner 1 would cover the notches", { 0, 0, 0, 0 } },
    { "star-pierce.obj", make_star_pierce, "a 10-corner star face; triangles that pass through "
      "each other and through the star (per-pixel depth, no face order)", { 0, 0, 0, 0 } },
    { "cyclic.obj", make_cyclic, "four bars overlapping in a cycle (no painter's order); "
      "`o` + `usemtl` per bar, cyclic.mtl", { 0, 0, 0, 0 } },
    { "torus.obj", make_torus, "a closed curved mesh that hides part of itself; "
      "mid-size load and render timing", { 0, 0, 0, 0 } },
    { "knot.obj", make_knot, "(3,7) torus knot: many thin overlapping tubes, 14 crossings; "
      "the heaviest bundled model", { 0, 0, 0, 0 } },
    { "scene.obj", make_scene, "objects in front of each other and of a wall, materials "
      "(scene.mtl), one object with `v x y z r g b` colours", { 0, 0, 0, 0 } },
    { "demo.obj", make_demo, "the default demo scene (`zview` with no file); "
      "knot over a checker floor, demo.mtl", { 0, 0, 0, 0 } },
};

static int write_readme(const char *dir)
{
    FILE *fp = open_out(dir, "README.md");
    if (!fp)
        return -1;
    fprintf(fp, "# Bundled models\n\n"
            "zview's own small test models. All of them are made by tools/genassets.c "
            "(`make assets`), which also writes this file; edit the generator, not the "
            "outputs. Output is deterministic: the same source gives the same bytes.\n\n"
            "Every model is checked by the generator before it is written: indices in "
            "range, no repeated corner, no zero-area or non-planar face, closed solids "
            "watertight and wound counter-clockwise seen from outside, flat shapes facing "
            "the side they claim. Counting: faces are OBJ `f` lines; triangles are "
            "sum(corners - 2).\n\n"
            "| File | Vertices | Faces | Triangles | Size | What it tests |\n"
            "|---|---:|---:|---:|---:|---|\n");
    long total = 0;
    for (size_t i = 0; i < sizeof assets / sizeof assets[0]; i++) {
        const Asset *a = &assets[i];
        fprintf(fp, "| %s | %u | %u | %u | %.1f KB | %s |\n", a->file, (unsigned)a->st.verts,
                (unsigned)a->st.faces, (unsigned)a->st.tris, a->st.bytes / 1024.0, a->tests);
        total += a->st.bytes;
    }
    fprintf(fp, "\nMaterial libraries: cyclic.mtl, scene.mtl, demo.mtl (`Kd` colours). "
            "OBJ total %.1f KB. Made by tools/genassets.c (make assets).\n\n"
            "Check them with `python3 /work/shared/models/check_obj.py assets/*.obj`.\n",
            total / 1024.0);
    return close_out(fp, dir, "README.md", NULL);
}

int main(int argc, char **argv)
{
    if (argc > 2 || (argc == 2 && argv[1][0] == '-')) {
        fprintf(stderr, "usage: genassets [DIR]   (writes zview's models into DIR, default assets)\n");
        return 2;
    }
    const char *dir = argc == 2 ? argv[1] : "assets";
    for (size_t i = 0; i < sizeof assets / sizeof assets[0]; i++) {
        Asset *a = &assets[i];
        if (a->make(dir, &a->st))
            return 1;
        printf("%s/%-16s %6u vertices %6u faces %6u triangles %8ld bytes\n", dir, a->file,
               (unsigned)a->st.verts, (unsigned)a->st.faces, (unsigned)a->st.tris, a->st.bytes);
    }
    if (write_readme(dir))
        return 1;
    return 0;
}
