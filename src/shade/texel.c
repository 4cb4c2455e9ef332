/* texel.c: colours that vary across a face, per sample: a base-colour
 * texture times its material's base colour, or the face's corner
 * colours interpolated. The hidden-surface step is not involved: it has
 * left a face id per sample, and shading finds where in that face the
 * sample lies.
 *
 * Where: for a triangle of the face with view-space corners Q0, Q1, Q2
 * and the ray through the sample, from the eye E along d (perspective),
 * or from the sample's point on the view plane straight back (ortho),
 * the barycentric weight of corner i is m_i / (m0 + m1 + m2) with
 * m_i = d . ((Q_i+1 - E) x (Q_i+2 - E)), the signed volumes the ray
 * spans with the opposite edge. Each m_i is affine in the sample's
 * screen position, so a face is set up once (three planes a triangle)
 * and each sample costs three plane evaluations and a division: the
 * weights are exact for the triangle in 3D, which is what makes them
 * perspective-correct (straight texture lines stay straight) with no
 * seam between a quad's two triangles. The same planes give the
 * derivatives of the texture coordinates across the screen, and with
 * them the sample's footprint on the texture, which picks the mipmap
 * level: a fine texture far away averages instead of aliasing.
 *
 * Colour maths is in linear light: texels and corner colours are
 * decoded from sRGB, filtered, interpolated and multiplied (texture x
 * base colour x light), and encoded once at the end. The light is the
 * one untextured faces get, as a factor on linear light (texel_light),
 * so that a white texture looks as a white material does.
 *
 * Perspective-correct interpolation as homogeneous (rational linear)
 * interpolation: J. Blinn, "Hyperbolic Interpolation", IEEE Computer
 * Graphics and Applications 12(4), 1992. Mipmaps and the footprint's
 * level: L. Williams, "Pyramidal Parametrics", SIGGRAPH 1983.
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bigmem.h"
#include "invariant.h"
#include "shade.h"
#include "simd.h"

/* ==== Set-up of a face ==== */

#define SURF_TRI 2      /* fan triangles a slot holds: a triangle, a quad */

typedef struct {
    float a[3], b[3], c[3];     /* m_i(X, Y) = a_i X + b_i Y + c_i, X Y in pixels */
    float sa, sb;               /* d(sum m_i)/dX, /dY */
    float at[3][3];             /* per corner: u, v (transformed), or linear r, g, b */
    float au, bu, av, bv;       /* sum a_i u_i, sum b_i u_i, the same for v */
} TriSetup;

struct SurfSetup {
    int32_t  id;                /* face, -1 = empty */
    uint32_t frame;
    int      kind;              /* SURF_VCOLOUR, SURF_TEX0 + k, or SURF_PLAIN (nothing varies) */
    int      ntri;              /* triangles set up; 0 = more than SURF_TRI (set up per sample) */
    const Texture *tex;
    float    fac[3];            /* base colour times the texture, linear */
    float    tw, th;            /* level 0's size: texture units to texels */
    float    klin;              /* the face's flat light, as a factor on linear light */
    float    lod;               /* orthographic, one triangle: the footprint's level, one for the face */
    int      flat1;             /* orthographic, one triangle, 16-bit texels: tl holds the levels */
    TexLod   tl;
    TriSetup tri[SURF_TRI];
};

void texel_cache_free(SurfCache *sc)
{
    free(sc->face_poly);
    free(sc->slot);
    free(sc->enc);
    memset(sc, 0, sizeof *sc);
}

float texel_light(float k)
{
    /* k scales an untextured face's sRGB bytes; on linear light the same
     * picture is the decoded k (sRGB is close to a power law, and
     * (c k)^g = c^g k^g), taken between the table's bytes */
    const float *t = srgb_table();
    float x = k <= 0 ? 0 : k >= 1 ? 255 : k * 255.0f;
    int i = (int)x;
    if (i >= 255)
        return 1;
    float f = x - (float)i;
    return t[i] + (t[i + 1] - t[i]) * f;
}

/* A 0..1 sRGB value (a vertex colour) in linear light. */
static inline float lin_of(float c)
{
    float b = c <= 0 ? 0 : c >= 1 ? 255 : c * 255.0f + 0.5f;
    return srgb_table()[(int)b];
}

/* The loaded object instance inst copies: a division only for grid
 * copies (a division is dozens of cycles, and a face met takes several). */
static inline int base_of(const SurfFrame *f, int inst)
{
    return inst < f->nb ? inst : inst % f->nb;
}

/* Triangle (Q0, Q1, Q2, view space) as three planes over the screen. */
static void tri_planes(const SurfFrame *f, const Vec3 q[3], TriSetup *t)
{
    /* by the reciprocals of the focal lengths, not 12 divisions a
     * triangle (the weights are rounded to float: the same but for a
     * last bit in a few million) */
    const ScreenPolys *sp = f->sp;
    double cx = sp->w * 0.5, cy = sp->h * 0.5, ifx = 1.0 / sp->focal_x, ify = 1.0 / sp->focal_y;
    static const int next[3][2] = { { 1, 2 }, { 2, 0 }, { 0, 1 } };
    for (int i = 0; i < 3; i++) {
        const Vec3 *p = &q[next[i][0]], *r = &q[next[i][1]];
        double A, B, C;
        if (sp->persp) {
            /* m_i = d . (P - E) x (R - E), d = ((X - cx)/fx, (cy - Y)/fy, -1) */
            double ez = sp->eye_z;
            double px = p->x, py = p->y, pz = p->z - ez, rx = r->x, ry = r->y, rz = r->z - ez;
            double nx = py * rz - pz * ry, ny = pz * rx - px * rz, nz = px * ry - py * rx;
            A = nx * ifx;
            B = -ny * ify;
            C = -nx * cx * ifx + ny * cy * ify - nz;
        } else {
            /* the ray from (vx, vy) along -z: m_i = -((P - O) x (R - O)).z */
            double px = p->x, py = p->y, rx = r->x, ry = r->y;
            A = -(py - ry) * ifx;
            B = (rx - px) * ify;
            C = -(px * ry - py * rx) + (py - ry) * cx * ifx - (rx - px) * cy * ify;
        }
        t->a[i] = (float)A;
        t->b[i] = (float)B;
        t->c[i] = (float)C;
    }
    t->sa = t->a[0] + t->a[1] + t->a[2];
    t->sb = t->b[0] + t->b[1] + t->b[2];
}

/* The weights of sample (X, Y) in t; returns the smallest (negative:
 * outside), -INFINITY for a triangle seen edge-on. */
static inline float tri_weights(const TriSetup *t, float X, float Y, float w[3], float *inv_out)
{
    float m0 = t->a[0] * X + t->b[0] * Y + t->c[0];
    float m1 = t->a[1] * X + t->b[1] * Y + t->c[1];
    float m2 = t->a[2] * X + t->b[2] * Y + t->c[2];
    float l = m0 + m1 + m2;
    if (!(l != 0) || !isfinite(l))
        return -INFINITY;
    float inv = 1.0f / l;
    w[0] = m0 * inv;
    w[1] = m1 * inv;
    w[2] = m2 * inv;
    *inv_out = inv;
    float m = w[0] < w[1] ? w[0] : w[1];
    return m < w[2] ? m : w[2];
}

/* The instance's placement in view (object -> view), cached for the run
 * of faces of one instance. */
typedef struct {
    int  inst;
    Mat4 fwd;
} InstCache;

/* One fan triangle (corners c0, c1, c2 of the scene's polygon lists) of
 * face `id` into t, attributes as the kind wants. */
static void tri_setup(const SurfFrame *f, const Object *base, const SurfSetup *st, const Mat4 *fwd,
                      const uint32_t c[3], TriSetup *t)
{
    const Scene *s = f->s;
    const Mesh *m = base->mesh;
    Vec3 q[3];
    for (int i = 0; i < 3; i++) {
        const float *p = &m->pos[3 * (size_t)s->poly_corner[c[i]]];
        q[i] = m4_point(fwd, v3(p[0], p[1], p[2]));
    }
    tri_planes(f, q, t);
    if (st->kind == SURF_VCOLOUR) {
        for (int i = 0; i < 3; i++)
            for (int a = 0; a < 3; a++)
                t->at[i][a] = lin_of(m->rgb[3 * (size_t)s->poly_corner[c[i]] + a]);
        return;
    }
    const SceneSurf *su = &s->surf[st->kind - SURF_TEX0];
    for (int i = 0; i < 3; i++) {
        const float *uv = &s->poly_uv[2 * (size_t)c[i]];
        t->at[i][0] = uv[0] * su->scale[0] + su->off[0];
        t->at[i][1] = uv[1] * su->scale[1] + su->off[1];
        t->at[i][2] = 0;
    }
    t->au = t->a[0] * t->at[0][0] + t->a[1] * t->at[1][0] + t->a[2] * t->at[2][0];
    t->bu = t->b[0] * t->at[0][0] + t->b[1] * t->at[1][0] + t->b[2] * t->at[2][0];
    t->av = t->a[0] * t->at[0][1] + t->a[1] * t->at[1][1] + t->a[2] * t->at[2][1];
    t->bv = t->b[0] * t->at[0][1] + t->b[1] * t->at[1][1] + t->b[2] * t->at[2][1];
}

/* The face's fan triangles as corner triples into tris (the first max
 * of them); returns how many there are. */
static int face_tris(const Scene *s, const uint32_t *fp, uint32_t tris[][3], int max)
{
    int n = 0;
    for (uint32_t k = fp[0]; k < fp[0] + fp[1]; k++) {
        uint32_t c0 = scene_poly_c0(s, k), c1 = scene_poly_c0(s, k + 1);
        for (uint32_t c = c0 + 1; c + 1 < c1; c++, n++)
            if (n < max) {
                tris[n][0] = c0;
                tris[n][1] = c;
                tris[n][2] = c + 1;
            }
    }
    return n;
}

/* log2 of x > 0 from its bits, to within 0.09: the level's fraction
 * only blends two neighbouring levels. */
static inline float fast_log2(float x)
{
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    float e = (float)((int)(u >> 23) - 127);
    u = (u & 0x7fffffu) | 0x3f800000u;
    float m;
    memcpy(&m, &u, sizeof m);
    return e + (m - 1.0f);
}

/* Orthographic, the level of a triangle's footprint is one for all of
 * it: the coordinates' derivatives are constant (sum m_i is). */
static float tri_lod(const SurfSetup *st, const TriSetup *b)
{
    float l = b->c[0] + b->c[1] + b->c[2], inv = l != 0 ? 1.0f / l : 0;
    float ux = b->au * inv * st->tw, vx = b->av * inv * st->th;
    float uy = b->bu * inv * st->tw, vy = b->bv * inv * st->th;
    float fx = ux * ux + vx * vx, fy = uy * uy + vy * vy, f2 = fx > fy ? fx : fy;
    return f2 > 1 && isfinite(f2) ? 0.5f * fast_log2(f2) : 0;
}

/* ==== Per frame ==== */

/* The kind of colour face id shows this frame. */
static int face_kind(const SurfFrame *f, int32_t id, const Texture **tex_out)
{
    const Scene *s = f->s;
    int k = s->face_surf[id];
    *tex_out = NULL;
    if (k < SURF_TEX0)
        return k;
    const SceneSurf *su = &s->surf[k - SURF_TEX0];
    if (f->no_tex || su->tex->state != MTEX_OK || !s->poly_uv)
        return SURF_PLAIN;
    *tex_out = &su->tex->img;
    return k;
}

/* The flat light of face id (as lambert shading computes it). */
static float face_klin(const SurfFrame *f, int32_t id, const Mat4 *fwd)
{
    float n[3];
    scene_face_normal(f->s, (uint32_t)id, n);
    Vec3 v = v3_norm(m4_dir(fwd, v3(n[0], n[1], n[2])));
    float amb = f->s->light.ambient;
    return texel_light(amb + (1.0f - amb) * fabsf(v3_dot(v, f->s->light.dir)));
}

/* Face id set up in st for this frame; NULL when its colour does not
 * vary. */
static const SurfSetup *face_setup_in(SurfFrame *f, InstCache *ic, int32_t id, SurfSetup *st)
{
    SurfCache *sc = f->sc;
    const Scene *s = f->s;
    st->id = id;
    st->frame = sc->frame;
    st->kind = face_kind(f, id, &st->tex);
    if (st->kind == SURF_PLAIN)
        return NULL;
    int inst = s->face_obj ? s->face_obj[id] : 0, base = base_of(f, inst);
    if (inst != ic->inst) {
        ic->fwd = m4_mul(f->view, object_matrix(&s->objs[inst]));
        ic->inst = inst;
    }
    uint32_t bface = (uint32_t)(s->objs[base].face_base + (id - s->objs[inst].face_base));
    st->klin = face_klin(f, id, &ic->fwd);
    if (st->tex) {
        const SceneSurf *su = &s->surf[st->kind - SURF_TEX0];
        memcpy(st->fac, su->factor, sizeof st->fac);
        st->tw = (float)st->tex->w;
        st->th = (float)st->tex->h;
    }
    uint32_t tris[SURF_TRI][3];
    int n = face_tris(s, &sc->face_poly[2 * (size_t)bface], tris, SURF_TRI);
    st->ntri = n <= SURF_TRI ? n : 0;
    for (int i = 0; i < st->ntri; i++)
        tri_setup(f, &s->objs[base], st, &ic->fwd, tris[i], &st->tri[i]);
    if (n == 0)
        st->kind = SURF_PLAIN;      /* no polygon: nothing to interpolate over */
    st->lod = 0;
    st->flat1 = 0;
    if (st->ntri == 1 && st->tex && !f->sp->persp) {
        st->lod = tri_lod(st, &st->tri[0]);
        if (st->tex->lin) {
            texture_lod(st->tex, st->lod, &st->tl);
            st->flat1 = 1;
        }
    }
    return st->kind == SURF_PLAIN ? NULL : st;
}

/* The slot of face id, set up for this frame; NULL when its colour
 * does not vary. */
static const SurfSetup *face_setup(SurfFrame *f, InstCache *ic, int32_t id)
{
    SurfCache *sc = f->sc;
    SurfSetup *st = &sc->slot[(uint32_t)id & (SURF_SLOTS - 1)];
    if (st->id == id && st->frame == sc->frame)
        return st->kind == SURF_PLAIN ? NULL : st;
    return face_setup_in(f, ic, id, st);
}

/* The colour at (X, Y) from the best triangle of t[0..n). */
static void eval_tris(const SurfSetup *st, const TriSetup *t, int n, float X, float Y, int simd, float out[3])
{
    float w[3] = { 1, 0, 0 }, inv = 0, best = -INFINITY;
    int bi = 0;
    for (int i = 0; i < n; i++) {
        float wi[3], ii = 0;
        float m = tri_weights(&t[i], X, Y, wi, &ii);
        if (m > best) {
            best = m;
            bi = i;
            memcpy(w, wi, sizeof w);
            inv = ii;
        }
    }
    const TriSetup *b = &t[bi];
    float v0 = w[0] * b->at[0][0] + w[1] * b->at[1][0] + w[2] * b->at[2][0];
    float v1 = w[0] * b->at[0][1] + w[1] * b->at[1][1] + w[2] * b->at[2][1];
    if (best < 0) {
        /* a sample a rounding outside (the polygon is snapped to 1/256
         * pixel): the nearest point of the triangle, so that a texture
         * atlas's neighbouring island never shows at an edge */
        float sum = 0;
        for (int i = 0; i < 3; i++) {
            w[i] = w[i] > 0 ? w[i] : 0;
            sum += w[i];
        }
        if (!(sum > 0)) {
            w[0] = 1;
            w[1] = w[2] = 0;
            sum = 1;
        }
        for (int i = 0; i < 3; i++)
            w[i] /= sum;
        v0 = w[0] * b->at[0][0] + w[1] * b->at[1][0] + w[2] * b->at[2][0];
        v1 = w[0] * b->at[0][1] + w[1] * b->at[1][1] + w[2] * b->at[2][1];
    }
    if (!st->tex) {
        out[0] = v0;
        out[1] = v1;
        out[2] = w[0] * b->at[0][2] + w[1] * b->at[1][2] + w[2] * b->at[2][2];
        return;
    }
    /* the footprint: texture units a sample step moves, in texels */
    float lod = 0;
    if (best > -INFINITY) {
        float ux = (b->au - v0 * b->sa) * inv * st->tw, vx = (b->av - v1 * b->sa) * inv * st->th;
        float uy = (b->bu - v0 * b->sb) * inv * st->tw, vy = (b->bv - v1 * b->sb) * inv * st->th;
        float fx = ux * ux + vx * vx, fy = uy * uy + vy * vy, f2 = fx > fy ? fx : fy;
        lod = f2 > 1 && isfinite(f2) ? 0.5f * fast_log2(f2) : 0;
    }
    texture_sample_lin(st->tex, v0, v1, lod, simd, out);
    out[0] *= st->fac[0];
    out[1] *= st->fac[1];
    out[2] *= st->fac[2];
}

/* eval_face's first case with the face's levels looked up once (the
 * same bits): 0 when the sample is not inside the triangle. */
static inline int flat1_colour(const SurfSetup *st, float X, float Y, int simd, float out[3])
{
    const TriSetup *t = &st->tri[0];
    float m0 = t->a[0] * X + t->b[0] * Y + t->c[0];
    float m1 = t->a[1] * X + t->b[1] * Y + t->c[1];
    float m2 = t->a[2] * X + t->b[2] * Y + t->c[2];
    float l = m0 + m1 + m2;
    if (!(m0 * l >= 0 && m1 * l >= 0 && m2 * l >= 0 && l != 0))
        return 0;
    float inv = 1.0f / l;
    float u = (m0 * t->at[0][0] + m1 * t->at[1][0] + m2 * t->at[2][0]) * inv;
    float v = (m0 * t->at[0][1] + m1 * t->at[1][1] + m2 * t->at[2][1]) * inv;
    texture_lookup(&st->tl, u, v, simd, out);
    out[0] *= st->fac[0];
    out[1] *= st->fac[1];
    out[2] *= st->fac[2];
    return 1;
}

/* The colour of face id at (X, Y) (its slot st): from the slot's
 * triangles, or, for a face of more, each set up here. */
static void eval_face(SurfFrame *f, InstCache *ic, const SurfSetup *st, int32_t id, float X, float Y,
                      float out[3])
{
    if (st->ntri == 1 && st->tex && !f->sp->persp) {
        /* nearly every sample: inside its one triangle, seen flat on */
        const TriSetup *t = &st->tri[0];
        float m0 = t->a[0] * X + t->b[0] * Y + t->c[0];
        float m1 = t->a[1] * X + t->b[1] * Y + t->c[1];
        float m2 = t->a[2] * X + t->b[2] * Y + t->c[2];
        float l = m0 + m1 + m2;
        if (m0 * l >= 0 && m1 * l >= 0 && m2 * l >= 0 && l != 0) {
            float inv = 1.0f / l;
            float u = (m0 * t->at[0][0] + m1 * t->at[1][0] + m2 * t->at[2][0]) * inv;
            float v = (m0 * t->at[0][1] + m1 * t->at[1][1] + m2 * t->at[2][1]) * inv;
            texture_sample_lin(st->tex, u, v, st->lod, f->simd, out);
            out[0] *= st->fac[0];
            out[1] *= st->fac[1];
            out[2] *= st->fac[2];
            return;
        }
    }
    if (st->ntri) {
        eval_tris(st, st->tri, st->ntri, X, Y, f->simd, out);
        return;
    }
    /* a polygon of many corners: its triangles one at a time, the one
     * holding the sample (the largest smallest weight) kept */
    const Scene *s = f->s;
    int inst = s->face_obj ? s->face_obj[id] : 0, base = base_of(f, inst);
    uint32_t bface = (uint32_t)(s->objs[base].face_base + (id - s->objs[inst].face_base));
    const uint32_t *fp = &f->sc->face_poly[2 * (size_t)bface];
    TriSetup best, t;
    float bm = -INFINITY;
    int any = 0;
    for (uint32_t k = fp[0]; k < fp[0] + fp[1]; k++) {
        uint32_t c0 = scene_poly_c0(s, k), c1 = scene_poly_c0(s, k + 1);
        for (uint32_t c = c0 + 1; c + 1 < c1; c++) {
            const uint32_t tri[3] = { c0, c, c + 1 };
            tri_setup(f, &s->objs[base], st, &ic->fwd, tri, &t);
            float w[3], inv = 0;
            float m = tri_weights(&t, X, Y, w, &inv);
            if (!any || m > bm) {
                best = t;
                bm = m;
                any = 1;
            }
        }
    }
    eval_tris(st, &best, 1, X, Y, f->simd, out);
}

int texel_frame_begin(SurfFrame *f, const Scene *s, const ScreenPolys *sp, const ShadeSettings *set,
                     SurfCache *sc)
{
    if (!s->face_surf || !sp || !s->nfaces)
        return 1;
    if (!(sc->key == s && sc->key_gen == s->gen && sc->key_npolys == s->npolys && sc->face_poly)) {
        free(sc->face_poly);
        sc->face_poly = malloc(((size_t)s->nfaces + 1) * 2 * sizeof(uint32_t));
        if (!sc->face_poly)
            return -1;
        bigmem_advise(sc->face_poly, ((size_t)s->nfaces + 1) * 2 * sizeof(uint32_t), 1);
        shade_face_polys(s, sc->face_poly);
        sc->key = s;
        sc->key_gen = s->gen;
        sc->key_npolys = s->npolys;
    }
    if (!sc->slot) {
        sc->slot = malloc(SURF_SLOTS * sizeof *sc->slot);
        if (!sc->slot)
            return -1;
        for (int i = 0; i < SURF_SLOTS; i++)
            sc->slot[i].id = -1;
    }
    if (!sc->enc) {
        sc->enc = malloc(sizeof *sc->enc);
        if (!sc->enc)
            return -1;
        srgb_enc_init(sc->enc);
    }
    if (++sc->frame == 0) {         /* a stamp no slot has */
        for (int i = 0; i < SURF_SLOTS; i++)
            sc->slot[i].id = -1;
        sc->frame = 1;
    }
    f->s = s;
    f->sp = sp;
    f->sc = sc;
    f->no_tex = set->no_textures;
    f->simd = simd_use(set->simd);
    f->nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    f->view = camera_view(&s->cam);
    return 0;
}

int texel_colour(SurfFrame *f, int32_t id, int x, int y, float out[3])
{
    if (id < 0 || (uint32_t)id >= f->s->nfaces || f->s->face_surf[id] == SURF_PLAIN)
        return 0;
    InstCache ic = { -1, m4_identity() };
    const SurfSetup *st = face_setup(f, &ic, id);
    if (!st)
        return 0;
    if (!st->ntri && ic.inst < 0)
        ic.fwd = m4_mul(f->view, object_matrix(&f->s->objs[f->s->face_obj ? f->s->face_obj[id] : 0]));
    eval_face(f, &ic, st, id, (float)x + 0.5f, (float)y + 0.5f, out);
    return 1;
}

/* The sample's bytes: colour c under light k, srgb_enc's (the SSE2
 * lanes clamp and index as it does: the same bytes). */
static inline void encode_px(const SrgbEnc *enc, const float c[3], float k, int simd, uint8_t *px)
{
#ifdef ZV_SSE2
    if (simd >= SIMD_SSE2) {
        __m128 v = _mm_mul_ps(_mm_setr_ps(c[0], c[1], c[2], 0), _mm_set1_ps(k));
        /* maxps gives its second operand for NaN: 0, as srgb_enc */
        v = _mm_min_ps(_mm_max_ps(v, _mm_setzero_ps()), _mm_set1_ps(1.0f));
        __m128i i = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, _mm_set1_ps((float)SRGB_ENC_SIZE)), _mm_set1_ps(0.5f)));
        int32_t ix[4];
        _mm_storeu_si128((__m128i *)(void *)ix, i);
        px[0] = enc->b[ix[0]];
        px[1] = enc->b[ix[1]];
        px[2] = enc->b[ix[2]];
        return;
    }
#endif
    (void)simd;
    for (int a = 0; a < 3; a++)
        px[a] = srgb_enc(enc, c[a] * k);
}

/* ==== The samples of a face seen flat on, together (SSE2 and AVX2) ==== */

#ifdef ZV_SSE2
/* Samples gathered before they are looked up: a face has a dozen on
 * average at 1920x1080, a row of it a few, so the vector work goes
 * over the face's samples, not along rows. */
#define ROW_RUN 64
/* Fewer samples than this are shaded one at a time: a group's set-up
 * (8 lanes of weights and offsets for two levels) costs more than it
 * saves for a face of one sample (the dragon at 160x96, 4 samples a
 * pixel; callgrind: 2 fewer instructions in all than 4 or 8). */
#define ROW_MIN 2

/* flat1_colour's test and coordinates for samples (x[i] + 0.5,
 * y[i] + 0.5), i < n, a lane a sample (the same operations, so the same
 * bits): in[i] is nonzero where the sample is inside the triangle.
 * Writes whole vectors: the arrays hold ROW_RUN + 8, x and y are read
 * past n. */
static void flat1_uv_sse2(const TriSetup *t, const int32_t *x, const int32_t *y, int n, float *u, float *v,
                          int32_t *in)
{
    __m128 a0 = _mm_set1_ps(t->a[0]), a1 = _mm_set1_ps(t->a[1]), a2 = _mm_set1_ps(t->a[2]);
    __m128 b0 = _mm_set1_ps(t->b[0]), b1 = _mm_set1_ps(t->b[1]), b2 = _mm_set1_ps(t->b[2]);
    __m128 c0 = _mm_set1_ps(t->c[0]), c1 = _mm_set1_ps(t->c[1]), c2 = _mm_set1_ps(t->c[2]);
    __m128 u0 = _mm_set1_ps(t->at[0][0]), u1 = _mm_set1_ps(t->at[1][0]), u2 = _mm_set1_ps(t->at[2][0]);
    __m128 v0 = _mm_set1_ps(t->at[0][1]), v1 = _mm_set1_ps(t->at[1][1]), v2 = _mm_set1_ps(t->at[2][1]);
    __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), half = _mm_set1_ps(0.5f);
    for (int i = 0; i < n; i += 4) {
        __m128 X = _mm_add_ps(_mm_cvtepi32_ps(_mm_loadu_si128((const __m128i *)(const void *)(x + i))), half);
        __m128 Y = _mm_add_ps(_mm_cvtepi32_ps(_mm_loadu_si128((const __m128i *)(const void *)(y + i))), half);
        __m128 m0 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(a0, X), _mm_mul_ps(b0, Y)), c0);
        __m128 m1 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(a1, X), _mm_mul_ps(b1, Y)), c1);
        __m128 m2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(a2, X), _mm_mul_ps(b2, Y)), c2);
        __m128 l = _mm_add_ps(_mm_add_ps(m0, m1), m2);
        __m128 ok = _mm_and_ps(_mm_cmpge_ps(_mm_mul_ps(m0, l), zero), _mm_cmpge_ps(_mm_mul_ps(m1, l), zero));
        ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(_mm_mul_ps(m2, l), zero), _mm_cmpneq_ps(l, zero)));
        __m128 inv = _mm_div_ps(one, l);
        __m128 uu = _mm_add_ps(_mm_add_ps(_mm_mul_ps(m0, u0), _mm_mul_ps(m1, u1)), _mm_mul_ps(m2, u2));
        __m128 vv = _mm_add_ps(_mm_add_ps(_mm_mul_ps(m0, v0), _mm_mul_ps(m1, v1)), _mm_mul_ps(m2, v2));
        _mm_storeu_ps(u + i, _mm_mul_ps(uu, inv));
        _mm_storeu_ps(v + i, _mm_mul_ps(vv, inv));
        _mm_storeu_si128((__m128i *)(void *)(in + i), _mm_castps_si128(ok));
    }
}

#ifdef ZV_AVX2
/* flat1_uv_sse2 eight lanes at a time. */
static ZV_AVX2_FN void flat1_uv_avx2(const TriSetup *t, const int32_t *x, const int32_t *y, int n, float *u,
                                     float *v, int32_t *in)
{
    __m256 a0 = _mm256_set1_ps(t->a[0]), a1 = _mm256_set1_ps(t->a[1]), a2 = _mm256_set1_ps(t->a[2]);
    __m256 b0 = _mm256_set1_ps(t->b[0]), b1 = _mm256_set1_ps(t->b[1]), b2 = _mm256_set1_ps(t->b[2]);
    __m256 c0 = _mm256_set1_ps(t->c[0]), c1 = _mm256_set1_ps(t->c[1]), c2 = _mm256_set1_ps(t->c[2]);
    __m256 u0 = _mm256_set1_ps(t->at[0][0]), u1 = _mm256_set1_ps(t->at[1][0]), u2 = _mm256_set1_ps(t->at[2][0]);
    __m256 v0 = _mm256_set1_ps(t->at[0][1]), v1 = _mm256_set1_ps(t->at[1][1]), v2 = _mm256_set1_ps(t->at[2][1]);
    __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
    for (int i = 0; i < n; i += 8) {
        __m256 X = _mm256_add_ps(_mm256_cvtepi32_ps(_mm256_loadu_si256((const __m256i *)(const void *)(x + i))), half);
        __m256 Y = _mm256_add_ps(_mm256_cvtepi32_ps(_mm256_loadu_si256((const __m256i *)(const void *)(y + i))), half);
        __m256 m0 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a0, X), _mm256_mul_ps(b0, Y)), c0);
        __m256 m1 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a1, X), _mm256_mul_ps(b1, Y)), c1);
        __m256 m2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a2, X), _mm256_mul_ps(b2, Y)), c2);
        __m256 l = _mm256_add_ps(_mm256_add_ps(m0, m1), m2);
        __m256 ok = _mm256_and_ps(_mm256_cmp_ps(_mm256_mul_ps(m0, l), zero, _CMP_GE_OQ),
                                  _mm256_cmp_ps(_mm256_mul_ps(m1, l), zero, _CMP_GE_OQ));
        ok = _mm256_and_ps(ok, _mm256_and_ps(_mm256_cmp_ps(_mm256_mul_ps(m2, l), zero, _CMP_GE_OQ),
                                             _mm256_cmp_ps(l, zero, _CMP_NEQ_UQ)));
        __m256 inv = _mm256_div_ps(one, l);
        __m256 uu = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(m0, u0), _mm256_mul_ps(m1, u1)), _mm256_mul_ps(m2, u2));
        __m256 vv = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(m0, v0), _mm256_mul_ps(m1, v1)), _mm256_mul_ps(m2, v2));
        _mm256_storeu_ps(u + i, _mm256_mul_ps(uu, inv));
        _mm256_storeu_ps(v + i, _mm256_mul_ps(vv, inv));
        _mm256_storeu_si256((__m256i *)(void *)(in + i), _mm256_castps_si256(ok));
    }
}
#endif

/* The sample's bytes from a lookup's colour (4 floats, the fourth
 * ignored): times the face's factor, then encode_px's SSE2 lanes. */
static inline void encode_fac(const SrgbEnc *enc, const SurfSetup *st, const float *c, uint8_t *px)
{
    __m128 v = _mm_mul_ps(_mm_mul_ps(_mm_loadu_ps(c), _mm_setr_ps(st->fac[0], st->fac[1], st->fac[2], 0)),
                          _mm_set1_ps(st->klin));
    v = _mm_min_ps(_mm_max_ps(v, _mm_setzero_ps()), _mm_set1_ps(1.0f));
    __m128i i = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, _mm_set1_ps((float)SRGB_ENC_SIZE)), _mm_set1_ps(0.5f)));
    int32_t ix[4];
    _mm_storeu_si128((__m128i *)(void *)ix, i);
    px[0] = enc->b[ix[0]];
    px[1] = enc->b[ix[1]];
    px[2] = enc->b[ix[2]];
}

/* Samples (x[i], y[i]), i < n, of face st seen flat on: those inside
 * its triangle looked up together (texture_lookup_row), the rest as
 * eval_face has them; the bytes of the sample-by-sample pass. */
static void flat1_batch(SurfFrame *f, InstCache *ic, const SurfSetup *st, int32_t id, int32_t *x, int32_t *y, int n,
                        int w, Image *out)
{
    const SrgbEnc *enc = f->sc->enc;
    float u[ROW_RUN + TEX_ROW_PAD], v[ROW_RUN + TEX_ROW_PAD], col[4 * ROW_RUN];
    int32_t in[ROW_RUN + 8];
    for (int i = n; i < n + 8; i++)
        x[i] = y[i] = 0;            /* the vectors' lanes past n */
#ifdef ZV_AVX2
    if (f->simd >= SIMD_AVX2)
        flat1_uv_avx2(&st->tri[0], x, y, n, u, v, in);
    else
#endif
        flat1_uv_sse2(&st->tri[0], x, y, n, u, v, in);
    int k = 0;
    for (int i = 0; i < n; i++) {
        if (in[i]) {
            u[k] = u[i];
            v[k] = v[i];
            x[k] = x[i];
            y[k++] = y[i];
            continue;
        }
        float c[3];
        eval_face(f, ic, st, id, (float)x[i] + 0.5f, (float)y[i] + 0.5f, c);
        encode_px(enc, c, st->klin, f->simd, out->rgb + 3 * ((size_t)y[i] * w + x[i]));
    }
    for (int i = k; i < k + TEX_ROW_PAD; i++) {
        u[i] = u[0];
        v[i] = v[0];
    }
    texture_lookup_row(&st->tl, u, v, k, f->simd, col);
    for (int j = 0; j < k; j++)
        encode_fac(enc, st, col + 4 * j, out->rgb + 3 * ((size_t)y[j] * w + x[j]));
}

/* shade_box's samples of a face seen flat on (st->flat1) from row y0
 * on, at SSE2 or AVX2: gathered, then flat1_batch. */
static void shade_flat1(SurfFrame *f, InstCache *ic, const FrameBufs *fb, const SurfSetup *st, int32_t id, int x0,
                        int x1, int y0, int y1, Image *out)
{
    int32_t x[ROW_RUN + 8], y[ROW_RUN + 8];
    int n = 0;
    for (int yy = y0; yy < y1; yy++) {
        const int32_t *ids = fb->ids + (size_t)yy * fb->w;
        for (int xx = x0; xx < x1; xx++) {
            if (ids[xx] != id)
                continue;
            if (n == ROW_RUN) {
                flat1_batch(f, ic, st, id, x, y, n, fb->w, out);
                n = 0;
            }
            x[n] = xx;
            y[n++] = yy;
        }
    }
    if (n >= ROW_MIN) {
        flat1_batch(f, ic, st, id, x, y, n, fb->w, out);
        return;
    }
    for (int i = 0; i < n; i++) {
        float c[3], X = (float)x[i] + 0.5f, Y = (float)y[i] + 0.5f;
        if (!flat1_colour(st, X, Y, f->simd, c))
            eval_face(f, ic, st, id, X, Y, c);
        encode_px(f->sc->enc, c, st->klin, f->simd, out->rgb + 3 * ((size_t)y[i] * fb->w + x[i]));
    }
}
#endif

/* The samples of face id within polygon box [x0, x1) x [y0, y1), each
 * its own colour under the face's light. The face is set up at its
 * first sample: a polygon whose face lost every sample costs a scan of
 * its box and nothing more. */
static void shade_box(SurfFrame *f, InstCache *ic, const FrameBufs *fb, int32_t id, int x0, int x1, int y0, int y1,
                      Image *out)
{
    const Scene *s = f->s;
    const SrgbEnc *enc = f->sc->enc;
    const SurfSetup *st = NULL;
    /* set up here, not in the slot table: the pass meets each face once
     * (in its polygon's box), and the table's slots, scattered over
     * 512 x ~350 bytes, were a cache miss or several a face */
    SurfSetup local;
    for (int y = y0; y < y1; y++) {
        const int32_t *ids = fb->ids + (size_t)y * fb->w;
        for (int x = x0; x < x1; x++) {
            if (ids[x] != id)
                continue;
            if (!st) {
                st = face_setup_in(f, ic, id, &local);
                if (!st)
                    return;
                int inst = s->face_obj ? s->face_obj[id] : 0;
                if (!st->ntri && ic->inst != inst) {
                    ic->inst = inst;
                    ic->fwd = m4_mul(f->view, object_matrix(&s->objs[inst]));
                }
            }
#ifdef ZV_SSE2
            if (st->flat1 && f->simd >= SIMD_SSE2) {
                shade_flat1(f, ic, fb, st, id, x0, x1, y, y1, out);
                return;
            }
#endif
            float c[3];
            if (!st->flat1 || !flat1_colour(st, (float)x + 0.5f, (float)y + 0.5f, f->simd, c))
                eval_face(f, ic, st, id, (float)x + 0.5f, (float)y + 0.5f, c);
            encode_px(enc, c, st->klin, f->simd, out->rgb + 3 * ((size_t)y * fb->w + x));
        }
    }
}

/* Setting a face up reads a chain of arrays, each index from the one
 * before: its polygon run (face_poly), the run's first corner
 * (poly_start), the corners' vertices (poly_corner) and texture
 * coordinates, the vertices' positions. The faces drawn are a sparse
 * subset of the mesh's, so each link is a cache miss of its own. The
 * pass fetches them ahead in stages, SURF_STEP polygons apart, each
 * stage reading only what the one before fetched. */
#define SURF_STEP 8

/* The scene polygon run of face id (its loaded object's face). */
static inline const uint32_t *face_run(const SurfFrame *f, int32_t id)
{
    const Scene *s = f->s;
    int inst = s->face_obj ? s->face_obj[id] : 0, base = base_of(f, inst);
    uint32_t bface = (uint32_t)(s->objs[base].face_base + (id - s->objs[inst].face_base));
    return &f->sc->face_poly[2 * (size_t)bface];
}

/* Stage k (4: furthest) of the fetch of face id: k = 4 only fetches,
 * every other stage reads what the stage before fetched. Inlined by
 * force: as a function of its own, GCC 12 (its mod-ref analysis) finds
 * that it changes nothing and drops the calls, and with them every
 * fetch (none was issued until this was seen). */
static inline __attribute__((always_inline)) void prefetch_stage(const SurfFrame *f, int32_t id, int k)
{
    const Scene *s = f->s;
    if (id < 0 || (uint32_t)id >= s->nfaces)
        return;
    if (k == 4) {
        __builtin_prefetch(&s->face_surf[id]);
        if (s->face_obj)
            __builtin_prefetch(&s->face_obj[id]);
        if (s->face_normal)
            __builtin_prefetch(&s->face_normal[3 * (size_t)id]);
        return;
    }
    if (s->face_surf[id] == SURF_PLAIN)
        return;
    const uint32_t *fp = face_run(f, id);
    if (k == 3) {
        __builtin_prefetch(fp);
        return;
    }
    if (!fp[1])
        return;
    if (k == 2) {
        if (s->poly_start)
            __builtin_prefetch(&s->poly_start[fp[0]]);
        return;
    }
    uint32_t c0 = scene_poly_c0(s, fp[0]);
    if (k == 1) {
        __builtin_prefetch(&s->poly_corner[c0]);
        if (s->poly_uv)
            __builtin_prefetch(&s->poly_uv[2 * (size_t)c0]);
        return;
    }
    const float *pos = s->objs[base_of(f, s->face_obj ? s->face_obj[id] : 0)].mesh->pos;
    for (uint32_t c = c0; c < c0 + 3; c++)
        __builtin_prefetch(&pos[3 * (size_t)s->poly_corner[c]]);
}

/* Whether polygon p's box holds a sample of its face. */
static inline int poly_shows(const FrameBufs *fb, const ScreenPoly *p)
{
    int x1 = p->x1 < fb->w ? p->x1 : fb->w, y1 = p->y1 < fb->h ? p->y1 : fb->h;
    for (int y = p->y0; y < y1; y++) {
        const int32_t *ids = fb->ids + (size_t)y * fb->w;
        for (int x = p->x0; x < x1; x++)
            if (ids[x] == p->face)
                return 1;
    }
    return 0;
}

/* Polygons with a sample waiting to be shaded: a ring of SURF_RING
 * (a power of two, more than the 5 stages' SURF_STEP apart). */
#define SURF_RING 64

void shade_surfaces_flat(SurfFrame *f, const FrameBufs *fb, Image *out)
{
    /* Polygon by polygon, over each one's box of samples, rather than
     * sample by sample: the polygons come in face order, so each face's
     * data (its corners, their positions and texture coordinates) is
     * read in order, where the samples would visit the faces scattered,
     * a cache miss or several each (the dragon in a small picture: a
     * third of the shading time). Even where faces are big (the bunny
     * at 1920x1080) this beats a pass sample by sample with the set-ups
     * looked up again (measured: 33 against 38 ms of CPU a frame).
     *
     * Only the polygons that kept a sample are fetched ahead and set
     * up: a huge mesh in a small picture has most of its polygons' boxes
     * empty (the dragon at 160x96 x 4: 18k of 43k show), and fetching
     * those too would put the fetches of the ones that count too close
     * to their use. The id buffer (read first) is small and hot. */
    const Scene *s = f->s;
    const ScreenPolys *sp = f->sp;
    InstCache ic = { -1, m4_identity() };
    uint32_t ring[SURF_RING], head = 0, tail = 0, i = 0;
    /* points and lines (after the faces) have ids past the faces' */
    for (;;) {
        while (tail - head <= 5 * SURF_STEP && i < sp->npolys) {
            const ScreenPoly *p = &sp->polys[i++];
            if (p->face < 0 || (uint32_t)p->face >= s->nfaces || !poly_shows(fb, p))
                continue;
            ring[tail % SURF_RING] = (uint32_t)(p - sp->polys);
            for (int k = 0; k < 5; k++)
                if (tail >= (uint32_t)k * SURF_STEP)
                    prefetch_stage(f, sp->polys[ring[(tail - (uint32_t)k * SURF_STEP) % SURF_RING]].face, 4 - k);
            tail++;
        }
        if (head == tail)
            break;
        /* the ring holds what is fetched ahead (5 stages SURF_STEP
         * apart, plus one) and no more: a lap past it would shade a
         * polygon fetched for another */
        ZV_ASSERT(tail - head <= SURF_RING);
        const ScreenPoly *p = &sp->polys[ring[head++ % SURF_RING]];
        int32_t id = p->face;
        /* boxes start in the image (screen/ clips them): shade_box reads
         * ids from (x0, y0) on, unclamped */
        ZV_ASSERT(p->x0 >= 0 && p->y0 >= 0);
        if (s->face_surf[id] == SURF_PLAIN)
            continue;
        shade_box(f, &ic, fb, id, p->x0, p->x1 < fb->w ? p->x1 : fb->w, p->y0, p->y1 < fb->h ? p->y1 : fb->h, out);
    }
}
