/* smooth: per-pixel interpolated normals (--shade smooth).
 *
 * Once per scene (and crease angle), every polygon corner gets a normal:
 * the area-weighted sum of the normals of the faces around its vertex
 * that turn from its own face by at most the crease angle, so curved
 * surfaces shade smoothly while real edges (a cube's) stay sharp. The
 * faces' areas and unit normals come from the scene (Newell's method).
 *
 * Per pixel, the hidden-surface step has left a face id and a depth.
 * The pixel centre and its depth are taken back through the projection
 * to view space, then through the inverse of the object's placement to
 * object space, where the point lies on (or a rounding away from) one of
 * the face's triangles (a fan over its corners); its barycentric weights
 * there blend the corner normals, which are then lit two-sided like the
 * flat shading. Nothing here decides visibility: the exact face-id
 * buffer does, so every algorithm still gives the same picture.
 *
 * Normals interpolated per pixel: B. T. Phong, "Illumination for
 * Computer Generated Pictures", CACM 18(6), 1975 (the diffuse term only).
 * Face normals by Newell's method, as given in I. Sutherland, R. Sproull
 * and R. Schumacker, "A Characterization of Ten Hidden-Surface
 * Algorithms", Computing Surveys 6(1), 1974.
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "invariant.h"
#include "shade.h"

void smooth_free(SmoothData *sd)
{
    free(sd->cnorm);
    free(sd->face_poly);
    memset(sd, 0, sizeof *sd);
}

/* Newell normal (not normalised: its length is twice the area) of
 * scene polygon k with the vertex positions of mesh pos. */
static Vec3 poly_newell(const Scene *s, const float *pos, uint32_t k)
{
    Vec3 n = v3(0, 0, 0);
    uint32_t c0 = scene_poly_c0(s, k), c1 = scene_poly_c0(s, k + 1);
    for (uint32_t c = c0; c < c1; c++) {
        const float *p = &pos[3 * (size_t)s->poly_corner[c]];
        const float *q = &pos[3 * (size_t)s->poly_corner[c + 1 < c1 ? c + 1 : c0]];
        n.x += (p[1] - q[1]) * (p[2] + q[2]);
        n.y += (p[2] - q[2]) * (p[0] + q[0]);
        n.z += (p[0] - q[0]) * (p[1] + q[1]);
    }
    return n;
}

/* The corner normals of one loaded object: a vertex -> polygons table
 * over its vertex range, then per corner the sum over that vertex's
 * polygons within the crease angle of its own. */
static int object_normals(SmoothData *sd, const Scene *s, const Object *o, float cos_crease)
{
    const float *pos = o->mesh->pos;
    uint32_t nv = o->vert_max - o->vert_min + 1, p0 = o->poly_first, np = o->poly_count;
    uint32_t c0 = scene_poly_c0(s, p0), nc = scene_poly_c0(s, p0 + np) - c0;
    uint32_t *start = calloc((size_t)nv + 1, sizeof *start);
    uint32_t *list = malloc((size_t)(nc ? nc : 1) * sizeof *list);
    Vec3 *pn = malloc((size_t)(np ? np : 1) * sizeof *pn);     /* area-weighted */
    if (!start || !list || !pn) {
        free(start);
        free(list);
        free(pn);
        return -1;
    }
    for (uint32_t k = 0; k < np; k++)
        pn[k] = poly_newell(s, pos, p0 + k);
    for (uint32_t c = c0; c < c0 + nc; c++)
        start[s->poly_corner[c] - o->vert_min + 1]++;
    for (uint32_t v = 0; v < nv; v++)
        start[v + 1] += start[v];
    for (uint32_t k = 0; k < np; k++)
        for (uint32_t c = scene_poly_c0(s, p0 + k); c < scene_poly_c0(s, p0 + k + 1); c++)
            list[start[s->poly_corner[c] - o->vert_min]++] = k;
    /* start[v] now ends v's run: shift back */
    for (uint32_t v = nv; v > 0; v--)
        start[v] = start[v - 1];
    start[0] = 0;
    for (uint32_t k = 0; k < np; k++) {
        Vec3 own = v3_norm(pn[k]);
        for (uint32_t c = scene_poly_c0(s, p0 + k); c < scene_poly_c0(s, p0 + k + 1); c++) {
            uint32_t v = s->poly_corner[c] - o->vert_min;
            Vec3 sum = v3(0, 0, 0);
            for (uint32_t i = start[v]; i < start[v + 1]; i++) {
                Vec3 other = pn[list[i]];
                if (v3_dot(own, v3_norm(other)) >= cos_crease)
                    sum = v3_add(sum, other);
            }
            sum = v3_len(sum) > 0 ? v3_norm(sum) : own;
            float *out = &sd->cnorm[3 * (size_t)c];
            out[0] = sum.x;
            out[1] = sum.y;
            out[2] = sum.z;
        }
    }
    free(start);
    free(list);
    free(pn);
    return 0;
}

void shade_face_polys(const Scene *s, uint32_t *face_poly)
{
    /* face -> its run of polygons (first, count) in its loaded object */
    memset(face_poly, 0, ((size_t)s->nfaces + 1) * 2 * sizeof(uint32_t));   /* loaded faces only */
    uint32_t nb = s->nbase_objs ? s->nbase_objs : (uint32_t)s->nobjs;
    for (uint32_t oi = 0; oi < nb && (int)oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        if (!o->poly_count || !o->mesh)
            continue;
        for (uint32_t k = o->poly_first; k < o->poly_first + o->poly_count; k++) {
            uint32_t f = (uint32_t)o->face_base + scene_poly_lface(s, o, k);
            if (f >= s->nfaces)
                continue;
            uint32_t *fp = &face_poly[2 * (size_t)f];
            if (!fp[1])
                fp[0] = k;
            if (fp[0] + fp[1] == k)     /* a face's polygons are consecutive */
                fp[1]++;
        }
    }
}

int smooth_prepare(SmoothData *sd, const Scene *s, float crease_deg)
{
    if (sd->key == s && sd->key_gen == s->gen && sd->key_npolys == s->npolys && sd->crease == crease_deg &&
        sd->cnorm)
        return 0;
    smooth_free(sd);
    uint32_t ncorners = scene_ncorners(s);
    sd->cnorm = malloc((size_t)(ncorners ? ncorners : 1) * 3 * sizeof(float));
    sd->face_poly = malloc(((size_t)s->nfaces + 1) * 2 * sizeof(uint32_t));
    if (!sd->cnorm || !sd->face_poly) {
        smooth_free(sd);
        return -1;
    }
    shade_face_polys(s, sd->face_poly);
    float cos_crease = cosf(deg2rad(crease_deg < 0 ? 0 : crease_deg > 180 ? 180 : crease_deg));
    uint32_t nb = s->nbase_objs ? s->nbase_objs : (uint32_t)s->nobjs;
    for (uint32_t oi = 0; oi < nb && (int)oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        if (!o->poly_count || !o->mesh)
            continue;
        if (object_normals(sd, s, o, cos_crease)) {
            smooth_free(sd);
            return -1;
        }
    }
    sd->key = s;
    sd->key_gen = s->gen;
    sd->key_npolys = s->npolys;
    sd->crease = crease_deg;
    return 0;
}

/* The inverse of a placement m (a rotation, a uniform scale and a move:
 * the inverse's linear part is the transpose over the squared scale). */
static Mat4 placement_inverse(const Mat4 *m)
{
    Mat4 r = m4_identity();
    float s2 = m->m[0][0] * m->m[0][0] + m->m[1][0] * m->m[1][0] + m->m[2][0] * m->m[2][0];
    float k = s2 > 0 ? 1.0f / s2 : 0;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            r.m[i][j] = m->m[j][i] * k;
        r.m[i][3] = -(r.m[i][0] * m->m[0][3] + r.m[i][1] * m->m[1][3] + r.m[i][2] * m->m[2][3]);
    }
    return r;
}

/* Per object instance this frame: view -> object space (inv), and the
 * normal matrix object -> view (the placement's linear part). */
typedef struct {
    Mat4 inv, fwd;
} InstMat;

static void inst_mat(const Scene *s, const Mat4 *view, int obj, InstMat *im)
{
    im->fwd = m4_mul(*view, object_matrix(&s->objs[obj]));
    im->inv = placement_inverse(&im->fwd);
}

/* Barycentric weights of p in triangle (a, b, c), in the plane's best 2D
 * projection; returns the smallest weight (negative: outside). */
static float barycentric(const float *a, const float *b, const float *c, const float p[3], float w[3])
{
    float e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    float n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
    int ax = fabsf(n[0]) > fabsf(n[1]) ? (fabsf(n[0]) > fabsf(n[2]) ? 0 : 2) : (fabsf(n[1]) > fabsf(n[2]) ? 1 : 2);
    int u = (ax + 1) % 3, v = (ax + 2) % 3;
    float det = n[ax];
    if (det == 0) {
        w[0] = 1;
        w[1] = w[2] = 0;
        return -INFINITY;
    }
    float pu = p[u] - a[u], pv = p[v] - a[v];
    w[1] = (pu * e2[v] - pv * e2[u]) / det;
    w[2] = (e1[u] * pv - e1[v] * pu) / det;
    w[0] = 1 - w[1] - w[2];
    float m = w[0] < w[1] ? w[0] : w[1];
    return m < w[2] ? m : w[2];
}

/* The interpolated object-space normal of face f at object point p. */
static Vec3 face_normal_at(const SmoothData *sd, const Scene *s, const Object *o, uint32_t f, const float p[3])
{
    const uint32_t *fp = &sd->face_poly[2 * (size_t)f];
    const float *pos = o->mesh->pos;
    float best = -INFINITY, bw[3] = { 1, 0, 0 };
    uint32_t bc[3] = { 0, 0, 0 };
    for (uint32_t k = fp[0]; k < fp[0] + fp[1]; k++) {
        uint32_t c0 = scene_poly_c0(s, k), c1 = scene_poly_c0(s, k + 1);
        for (uint32_t c = c0 + 1; c + 1 < c1; c++) {
            float w[3];
            const float *a = &pos[3 * (size_t)s->poly_corner[c0]], *b = &pos[3 * (size_t)s->poly_corner[c]],
                        *d = &pos[3 * (size_t)s->poly_corner[c + 1]];
            float m = barycentric(a, b, d, p, w);
            if (m > best) {
                best = m;
                memcpy(bw, w, sizeof w);
                bc[0] = c0;
                bc[1] = c;
                bc[2] = c + 1;
            }
        }
    }
    if (best == -INFINITY) {
        float n[3];
        scene_face_normal(s, f, n);
        return v3(n[0], n[1], n[2]);
    }
    /* a point a rounding outside: clamp to the triangle */
    float sum = 0;
    for (int i = 0; i < 3; i++) {
        bw[i] = bw[i] < 0 ? 0 : bw[i];
        sum += bw[i];
    }
    Vec3 n = v3(0, 0, 0);
    for (int i = 0; i < 3; i++) {
        const float *cn = &sd->cnorm[3 * (size_t)bc[i]];
        n = v3_add(n, v3_scale(v3(cn[0], cn[1], cn[2]), bw[i] / sum));
    }
    return n;
}

int shade_smooth(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, SmoothData *sd,
                 const uint8_t *face_rgb_default, SurfFrame *sf, Image *out)
{
    Mat4 view = camera_view(&s->cam);
    double cx = fb->w * 0.5, cy = fb->h * 0.5;
    int cached = -1;
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    InstMat im;
    memset(&im, 0, sizeof im);     /* set before use (cached starts at -1) */
    float amb = s->light.ambient;
    for (int y = 0; y < fb->h; y++)
        for (int x = 0; x < fb->w; x++) {
            size_t i = (size_t)y * fb->w + x;
            uint8_t *px = out->rgb + 3 * i;
            int32_t id = fb->ids[i];
            if (id < 0 || (uint32_t)id >= s->nfaces) {
                px[0] = px[1] = px[2] = 0;
                out->lit[i] = 0;
                continue;
            }
            /* the sample back in view space */
            double d = fb->depth[i], vx, vy, vz;
            if (!sp->persp) {
                vz = (sp->depth_bias - d) / sp->depth_scale;
                vx = (x + 0.5 - cx) / sp->focal_x;
                vy = (cy - (y + 0.5)) / sp->focal_y;
            } else {
                /* depth = f/(f-n) (1 - n/ze) */
                double f = sp->far_z, n = sp->near_z;
                double ze = n / (1 - d * (f - n) / f);
                vz = sp->eye_z - ze;
                vx = (x + 0.5 - cx) * ze / sp->focal_x;
                vy = (cy - (y + 0.5)) * ze / sp->focal_y;
            }
            /* the instance that drew it (grid copies have faces of their
             * own) and the loaded object whose polygons it shares */
            int inst = s->face_obj ? s->face_obj[id] : 0;
            int base = inst % nb;
            uint32_t bface = (uint32_t)(s->objs[base].face_base + (id - s->objs[inst].face_base));
            if (inst != cached) {
                /* the face is its instance's, and the instance a copy of
                 * a loaded object: bface indexes that object's faces */
                ZV_ASSERT(inst >= 0 && inst < s->nobjs && base < s->nobjs &&
                          (uint32_t)(id - s->objs[inst].face_base) < s->objs[inst].face_count);
                inst_mat(s, &view, inst, &im);
                cached = inst;
            }
            Vec3 q = m4_point(&im.inv, v3((float)vx, (float)vy, (float)vz));
            float p[3] = { q.x, q.y, q.z };
            Vec3 n = face_normal_at(sd, s, &s->objs[base], bface, p);
            Vec3 v = v3_norm(m4_dir(&im.fwd, n));
            float k = amb + (1.0f - amb) * fabsf(v3_dot(v, s->light.dir));
            float lin[3];
            if (sf && texel_colour(sf, id, x, y, lin)) {
                /* a texture or corner colours: in linear light */
                float kl = texel_light(k);
                for (int a = 0; a < 3; a++)
                    px[a] = srgb_enc(sf->sc->enc, lin[a] * kl);
                out->lit[i] = 1;
                continue;
            }
            const uint8_t *c = s->face_rgb ? s->face_rgb + 3 * (size_t)id : face_rgb_default;
            for (int a = 0; a < 3; a++) {
                float val = (float)c[a] * k + 0.5f;
                px[a] = val >= 255 ? 255 : (uint8_t)val;
            }
            out->lit[i] = 1;
        }
    return 0;
}
