/* project_sse2.c: the front end's vertex loop (pass 1, project.c) four
 * vertices at a time in SSE2, the x86-64 baseline: the floats of
 * m4_point(), then proj_point(), in_guard() and snap() in doubles, two
 * lanes at a time, in vert_one()'s order (no fused multiply-add: the
 * build has -ffp-contract=off), so every vertex gets vert_one()'s bits. */

#include "project.h"

#ifdef ZV_SSE2
/* x, y, z of four vertices from 12 consecutive floats. */
static inline void load4_xyz(const float *p, __m128 *x, __m128 *y, __m128 *z)
{
    __m128 a = _mm_loadu_ps(p), b = _mm_loadu_ps(p + 4), c = _mm_loadu_ps(p + 8);
    __m128 t = _mm_shuffle_ps(b, c, _MM_SHUFFLE(2, 1, 3, 2));      /* x2 y2 x3 y3 */
    __m128 u = _mm_shuffle_ps(a, b, _MM_SHUFFLE(1, 0, 2, 1));      /* y0 z0 y1 z1 */
    *x = _mm_shuffle_ps(a, t, _MM_SHUFFLE(2, 0, 3, 0));
    *y = _mm_shuffle_ps(u, t, _MM_SHUFFLE(3, 1, 2, 0));
    *z = _mm_shuffle_ps(u, c, _MM_SHUFFLE(3, 0, 3, 1));
}

/* m4_point's row r on four points: ((m0 x + m1 y) + m2 z) + m3 in float. */
static inline __m128 row4(const Mat4 *m, int r, __m128 x, __m128 y, __m128 z)
{
    __m128 s = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(m->m[r][0]), x), _mm_mul_ps(_mm_set1_ps(m->m[r][1]), y));
    s = _mm_add_ps(s, _mm_mul_ps(_mm_set1_ps(m->m[r][2]), z));
    return _mm_add_ps(s, _mm_set1_ps(m->m[r][3]));
}

/* snap() on two pairs of doubles: four int32. max/min return their
 * second operand for a NaN, which is snap()'s clamp of NaN to the low
 * end; the truncation is corrected down where it rounded up. */
static inline __m128i snap4(__m128d lo, __m128d hi)
{
    const __m128d k = _mm_set1_pd((double)SUBPIX), half = _mm_set1_pd(0.5);
    const __m128d tmin = _mm_set1_pd(-1073741824.0), tmax = _mm_set1_pd(1073741824.0);
    __m128d tl = _mm_add_pd(_mm_mul_pd(lo, k), half), th = _mm_add_pd(_mm_mul_pd(hi, k), half);
    tl = _mm_min_pd(_mm_max_pd(tl, tmin), tmax);
    th = _mm_min_pd(_mm_max_pd(th, tmin), tmax);
    __m128i il = _mm_cvttpd_epi32(tl), ih = _mm_cvttpd_epi32(th);
    __m128d dl = _mm_cmplt_pd(tl, _mm_cvtepi32_pd(il)), dh = _mm_cmplt_pd(th, _mm_cvtepi32_pd(ih));
    __m128i down = _mm_castps_si128(_mm_shuffle_ps(_mm_castpd_ps(dl), _mm_castpd_ps(dh), _MM_SHUFFLE(2, 0, 2, 0)));
    return _mm_add_epi32(_mm_unpacklo_epi64(il, ih), down);     /* adding -1 steps down */
}

/* Two 64-bit masks each of lo and hi as four 32-bit ones. */
static inline __m128i mask4(__m128d lo, __m128d hi)
{
    return _mm_castps_si128(_mm_shuffle_ps(_mm_castpd_ps(lo), _mm_castpd_ps(hi), _MM_SHUFFLE(2, 0, 2, 0)));
}

static inline __m128d guard2(const Proj *pj, __m128d sx, __m128d sy)
{
    __m128d in = _mm_and_pd(_mm_cmpge_pd(sx, _mm_set1_pd(pj->gx0)), _mm_cmple_pd(sx, _mm_set1_pd(pj->gx1)));
    return _mm_and_pd(in, _mm_and_pd(_mm_cmpge_pd(sy, _mm_set1_pd(pj->gy0)), _mm_cmple_pd(sy, _mm_set1_pd(pj->gy1))));
}

/* proj_point() and in_guard() on two view-space points (floats widened). */
static inline void proj2(const Proj *pj, __m128d x, __m128d y, __m128d z, __m128d *sx, __m128d *sy,
                         __m128d *sz, __m128d *ok)
{
    if (!pj->persp) {
        *sx = _mm_add_pd(_mm_set1_pd(pj->cx), _mm_mul_pd(_mm_set1_pd(pj->fx), x));
        *sy = _mm_sub_pd(_mm_set1_pd(pj->cy), _mm_mul_pd(_mm_set1_pd(pj->fy), y));
        *sz = _mm_sub_pd(_mm_set1_pd(pj->dbias), _mm_mul_pd(_mm_set1_pd(pj->dscale), z));
        *ok = guard2(pj, *sx, *sy);
    } else {
        __m128d ze = _mm_sub_pd(_mm_set1_pd(pj->eye), z);
        *sx = _mm_add_pd(_mm_set1_pd(pj->cx), _mm_div_pd(_mm_mul_pd(_mm_set1_pd(pj->fx), x), ze));
        *sy = _mm_sub_pd(_mm_set1_pd(pj->cy), _mm_div_pd(_mm_mul_pd(_mm_set1_pd(pj->fy), y), ze));
        *sz = _mm_mul_pd(_mm_set1_pd(pj->dk), _mm_sub_pd(_mm_set1_pd(1.0), _mm_div_pd(_mm_set1_pd(pj->n), ze)));
        *ok = _mm_and_pd(_mm_cmpge_pd(ze, _mm_set1_pd(pj->n)), guard2(pj, *sx, *sy));
    }
}

/* project.h */
void project_verts_sse2(const VertJob *j, uint32_t a, uint32_t b)
{
    const Mat4 *m = &j->mv;
    const __m128i out = _mm_set1_epi32(VERT_OUT);
    uint32_t i = a;
    for (; i + 4 < b; i += 4) {
        __m128 x, y, z;
        load4_xyz(j->pos + 3 * (size_t)i, &x, &y, &z);
        __m128 qx = row4(m, 0, x, y, z), qy = row4(m, 1, x, y, z), qz = row4(m, 2, x, y, z);
        __m128d sx[2], sy[2], sz[2], ok[2];
        proj2(j->pj, _mm_cvtps_pd(qx), _mm_cvtps_pd(qy), _mm_cvtps_pd(qz), &sx[0], &sy[0], &sz[0], &ok[0]);
        proj2(j->pj, _mm_cvtps_pd(_mm_movehl_ps(qx, qx)), _mm_cvtps_pd(_mm_movehl_ps(qy, qy)),
              _mm_cvtps_pd(_mm_movehl_ps(qz, qz)), &sx[1], &sy[1], &sz[1], &ok[1]);
        __m128i okm = mask4(ok[0], ok[1]);
        __m128i ix = snap4(sx[0], sx[1]), iy = snap4(sy[0], sy[1]);
        ix = _mm_or_si128(_mm_and_si128(okm, ix), _mm_andnot_si128(okm, out));
        iy = _mm_or_si128(_mm_and_si128(okm, iy), _mm_andnot_si128(okm, out));
        store4(j, i, ix, iy, _mm_movelh_ps(_mm_cvtpd_ps(sz[0]), _mm_cvtpd_ps(sz[1])), okm);
    }
    for (; i < b; i++)
        vert_one(j, i);
}
#endif
