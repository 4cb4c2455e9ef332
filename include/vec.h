#ifndef ZV_VEC_H
#define ZV_VEC_H
/* vec: plain 3-vectors and 4x4 matrices, all inline. Matrices are row
 * major and act on column vectors: p' = M p. */

#include <math.h>

typedef struct { float x, y, z; } Vec3;
typedef struct { float m[4][4]; } Mat4;

static inline Vec3 v3(float x, float y, float z) { Vec3 r = { x, y, z }; return r; }
static inline Vec3 v3_add(Vec3 a, Vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline Vec3 v3_sub(Vec3 a, Vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline Vec3 v3_scale(Vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline float v3_dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline Vec3 v3_cross(Vec3 a, Vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline float v3_len(Vec3 a) { return sqrtf(v3_dot(a, a)); }
static inline Vec3 v3_norm(Vec3 a)
{
    float l = v3_len(a);
    return l > 0 ? v3_scale(a, 1.0f / l) : a;
}

static inline Mat4 m4_identity(void)
{
    Mat4 r = { { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } } };
    return r;
}

static inline Mat4 m4_mul(Mat4 a, Mat4 b)
{
    Mat4 r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] +
                        a.m[i][2] * b.m[2][j] + a.m[i][3] * b.m[3][j];
    return r;
}

static inline Mat4 m4_translate(Vec3 t)
{
    Mat4 r = m4_identity();
    r.m[0][3] = t.x; r.m[1][3] = t.y; r.m[2][3] = t.z;
    return r;
}

static inline Mat4 m4_scale(float s)
{
    Mat4 r = m4_identity();
    r.m[0][0] = r.m[1][1] = r.m[2][2] = s;
    return r;
}

/* Rotation about +y by yaw, then +x by pitch, then +z by roll (radians):
 * R = Rz(roll) * Rx(pitch) * Ry(yaw). */
static inline Mat4 m4_rotate_ypr(float yaw, float pitch, float roll)
{
    float cy = cosf(yaw), sy = sinf(yaw);
    float cp = cosf(pitch), sp = sinf(pitch);
    float cr = cosf(roll), sr = sinf(roll);
    Mat4 ry = { { { cy, 0, sy, 0 }, { 0, 1, 0, 0 }, { -sy, 0, cy, 0 }, { 0, 0, 0, 1 } } };
    Mat4 rx = { { { 1, 0, 0, 0 }, { 0, cp, -sp, 0 }, { 0, sp, cp, 0 }, { 0, 0, 0, 1 } } };
    Mat4 rz = { { { cr, -sr, 0, 0 }, { sr, cr, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } } };
    return m4_mul(rz, m4_mul(rx, ry));
}

static inline Vec3 m4_point(const Mat4 *a, Vec3 p)
{
    return v3(a->m[0][0] * p.x + a->m[0][1] * p.y + a->m[0][2] * p.z + a->m[0][3],
              a->m[1][0] * p.x + a->m[1][1] * p.y + a->m[1][2] * p.z + a->m[1][3],
              a->m[2][0] * p.x + a->m[2][1] * p.y + a->m[2][2] * p.z + a->m[2][3]);
}

/* The linear part only (directions, normals under rotation+uniform scale). */
static inline Vec3 m4_dir(const Mat4 *a, Vec3 p)
{
    return v3(a->m[0][0] * p.x + a->m[0][1] * p.y + a->m[0][2] * p.z,
              a->m[1][0] * p.x + a->m[1][1] * p.y + a->m[1][2] * p.z,
              a->m[2][0] * p.x + a->m[2][1] * p.y + a->m[2][2] * p.z);
}

#define ZV_PI 3.14159265358979323846f
static inline float deg2rad(float d) { return d * (ZV_PI / 180.0f); }

#endif
