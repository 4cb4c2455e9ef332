/* normals.c: face normals, stored or computed. Newell's normal in
 * double for any polygon, unit in float; for the compact form of a file
 * of triangles (scene.h), which stores none, the same arithmetic run
 * per face when the picture needs it (eight lanes of four doubles with
 * AVX2: the same operations in the same order, so the same bits). */

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "scene.h"
#include "scene_internal.h"
#include "simd.h"

/* Newell's normal of the polygon of corners c[0 .. n) (vertex indices
 * into pos): robust for any simple or concave polygon. Not unit. A
 * triangle takes one cross product. In double: the stored normals and
 * the compact form's computed ones (scene_face_normal) come from here,
 * so they are the same bits. */
static void corners_newell(const float *pos, const uint32_t *c, uint32_t n, double out[3])
{
    if (n == 3) {
        const float *p = &pos[3 * (size_t)c[0]], *q = &pos[3 * (size_t)c[1]], *r = &pos[3 * (size_t)c[2]];
        double ux = (double)q[0] - p[0], uy = (double)q[1] - p[1], uz = (double)q[2] - p[2];
        double vx = (double)r[0] - p[0], vy = (double)r[1] - p[1], vz = (double)r[2] - p[2];
        out[0] = uy * vz - uz * vy;
        out[1] = uz * vx - ux * vz;
        out[2] = ux * vy - uy * vx;
        return;
    }
    out[0] = out[1] = out[2] = 0;
    for (uint32_t k = 0; k < n; k++) {
        const float *p = &pos[3 * (size_t)c[k]], *q = &pos[3 * (size_t)c[k + 1 < n ? k + 1 : 0]];
        out[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
        out[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
        out[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
    }
}

void scene_face_newell(const Mesh *m, uint32_t f, double n[3])
{
    uint32_t a = m->face_start[f], b = m->face_start[f + 1];
    corners_newell(m->pos, &m->corner[a], b - a, n);
}

/* The unit normal of Newell vector n (+z when it has no length). */
void scene_unit_normal(const double n[3], float out[3])
{
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; i++)
        out[i] = len > 0 ? (float)(n[i] / len) : (i == 2);
}

void scene_face_normal(const Scene *s, uint32_t id, float n[3])
{
    if (s->face_normal) {
        memcpy(n, &s->face_normal[3 * (size_t)id], 3 * sizeof(float));
        return;
    }
    /* no face_normal: one polygon a face, polygon poly_first + lface */
    const Object *o = &s->objs[scene_face_obj(s, id)];
    uint32_t k = o->poly_first + (id - (uint32_t)o->face_base);
    uint32_t c0 = scene_poly_c0(s, k), c1 = scene_poly_c0(s, k + 1);
    double v[3];
    corners_newell(o->mesh->pos, s->poly_corner + c0, c1 - c0, v);
    scene_unit_normal(v, n);
}

#ifdef ZV_AVX2
/* The unit normals of four triangles (corners c[0 .. 12)) at once: the
 * double operations of corners_newell and scene_unit_normal in their order, each
 * lane rounding as a scalar double does (no fused multiply-add), so the
 * same bits. */
ZV_AVX2_FN static void tri_normals4(const float *pos, const uint32_t *c, float *out)
{
    double v[9][4];     /* p, q, r: x y z, a lane each */
    for (int l = 0; l < 4; l++)
        for (int k = 0; k < 3; k++) {
            const float *p = &pos[3 * (size_t)c[3 * l + k]];
            for (int a = 0; a < 3; a++)
                v[3 * k + a][l] = p[a];
        }
    __m256d u[3], w[3];
    for (int a = 0; a < 3; a++) {
        __m256d p = _mm256_loadu_pd(v[a]);
        u[a] = _mm256_sub_pd(_mm256_loadu_pd(v[3 + a]), p);
        w[a] = _mm256_sub_pd(_mm256_loadu_pd(v[6 + a]), p);
    }
    __m256d n[3] = { _mm256_sub_pd(_mm256_mul_pd(u[1], w[2]), _mm256_mul_pd(u[2], w[1])),
                     _mm256_sub_pd(_mm256_mul_pd(u[2], w[0]), _mm256_mul_pd(u[0], w[2])),
                     _mm256_sub_pd(_mm256_mul_pd(u[0], w[1]), _mm256_mul_pd(u[1], w[0])) };
    __m256d len = _mm256_sqrt_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(n[0], n[0]), _mm256_mul_pd(n[1], n[1])),
                                               _mm256_mul_pd(n[2], n[2])));
    __m256d some = _mm256_cmp_pd(len, _mm256_setzero_pd(), _CMP_GT_OQ);
    float f[3][4];
    for (int a = 0; a < 3; a++) {
        __m256d none = _mm256_set1_pd(a == 2 ? 1.0 : 0.0);     /* scene_unit_normal's +z */
        _mm_storeu_ps(f[a], _mm256_cvtpd_ps(_mm256_blendv_pd(none, _mm256_div_pd(n[a], len), some)));
    }
    for (int l = 0; l < 4; l++)
        for (int a = 0; a < 3; a++)
            out[3 * l + a] = f[a][l];
}
#endif

void scene_face_normals(const Scene *s, uint32_t f0, uint32_t n, float *out, int simd)
{
    if (s->face_normal || !n) {
        if (n)
            memcpy(out, &s->face_normal[3 * (size_t)f0], 3 * (size_t)n * sizeof(float));
        return;
    }
    const Object *o = &s->objs[scene_face_obj(s, f0)];
    const float *pos = o->mesh->pos;
    uint32_t k = o->poly_first + (f0 - (uint32_t)o->face_base), i = 0;
#ifdef ZV_AVX2
    if (simd_use(simd) >= SIMD_AVX2 && !s->poly_start)     /* triangles: corners 3k on */
        for (; i + 4 <= n; i += 4, k += 4)
            tri_normals4(pos, s->poly_corner + 3 * (size_t)k, &out[3 * (size_t)i]);
#else
    (void)simd;
#endif
    uint32_t c1 = scene_poly_c0(s, k);
    for (; i < n; i++, k++) {
        uint32_t c0 = c1;
        c1 = scene_poly_c0(s, k + 1);
        double v[3];
        corners_newell(pos, s->poly_corner + c0, c1 - c0, v);
        scene_unit_normal(v, &out[3 * (size_t)i]);
    }
}
