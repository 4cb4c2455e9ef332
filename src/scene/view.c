/* view.c: named views, where a model's front is, and a first view from
 * the geometry alone.
 *
 * The first view zview shows is chosen in app/firstview.c by rendering
 * candidate views and counting what each one sees; this file gives it
 * the part that needs no rendering: which way the model's front faces.
 *
 * The front: the format's forward axis where it has one (glTF faces +z,
 * an FBX file its FrontAxis, Blender -y: MeshInfo.front), turned as the
 * object stands. Where the format says nothing (OBJ, PLY, STL, ...) the
 * faces are counted instead: a model is made in finer detail where it is
 * looked at (a face, hands, a decorated side), so more of its faces point
 * that way. The sum of the faces' unit normals, unweighted by area, is 0
 * for a closed surface made of equal faces and leans towards its detailed
 * side; its horizontal part, divided by the number of faces, is how much
 * (Stanford's Lucy: 0.016 towards her front; a cube 0). A lean of
 * FRONT_FULL or more counts fully, less in proportion, and it is added
 * to a pull of FRONT_PLAIN towards +z: the plain front view's side,
 * which OpenGL's convention, glTF's and the OBJ exports of Blender and
 * Maya make the front of most models made by hand. A clear lean
 * outweighs it (Lucy is seen from her front, at -z); a faint one, or
 * none, leaves the front at +z.
 *
 * scene_pick_view scores eight three-quarter views from above (yaws 30,
 * 60, 120 and 150 degrees either side, pitch 25) by the surface facing
 * each, the sum over polygons of their area-weighted normal's component
 * towards the viewer (for a closed model its projected area: a long model
 * from its side), times the front preference. It sees no occlusion; the
 * app uses it when it cannot render (out of memory). */

#include <math.h>
#include <string.h>

#include "scene.h"

#define SAMPLE_POLYS 200000
#define NCAND 8
#define FRONT_FULL 0.02f        /* lean of the faces (see the top) that counts fully */
#define FRONT_PLAIN 0.3f        /* the weight of +z, the plain front view's side, where the format says nothing */
#define FRONT_PULL 0.3f         /* a view straight at a sure front scores 1.3 times, from behind 0.7 */

typedef struct {
    const char *name;
    float yaw, pitch;
} NamedView;

/* yaw turns the front to the right, pitch tips it down (scene.h) */
static const NamedView named[] = {
    { "front", 0, 0 },     { "back", 180, 0 },  { "left", 90, 0 },   { "right", -90, 0 },
    { "top", 0, 90 },      { "bottom", 0, -90 }, { "iso", -45, 35.264f },
};

int view_from_name(const char *name, float *yaw_out, float *pitch_out)
{
    for (size_t i = 0; i < sizeof named / sizeof named[0]; i++)
        if (strcmp(name, named[i].name) == 0) {
            *yaw_out = named[i].yaw;
            *pitch_out = named[i].pitch;
            return 0;
        }
    return -1;
}

const char *view_name(int i)
{
    return i >= 0 && i < (int)(sizeof named / sizeof named[0]) ? named[i].name : NULL;
}

Vec3 view_dir(float yaw_deg, float pitch_deg)
{
    float y = deg2rad(yaw_deg), p = deg2rad(pitch_deg);
    return v3(-sinf(y) * cosf(p), sinf(p), cosf(y) * cosf(p));
}

/* ==== The front ==== */

/* The unit vector of a model axis (UpAxis). */
static Vec3 axis_vec(int a)
{
    static const float v[UP_COUNT][3] = {
        [UP_Y] = { 0, 1, 0 },  [UP_Z] = { 0, 0, 1 },  [UP_X] = { 1, 0, 0 },
        [UP_NEG_Y] = { 0, -1, 0 }, [UP_NEG_Z] = { 0, 0, -1 }, [UP_NEG_X] = { -1, 0, 0 },
    };
    return v3(v[a][0], v[a][1], v[a][2]);
}

/* The objects' formats' forward axes in the world, each weighted by its
 * polygons, and whether any object has one. */
static int format_front(const Scene *s, Vec3 *sum)
{
    int any = 0;
    *sum = v3(0, 0, 0);
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        if (!o->mesh || o->mesh->info.front < 0 || o->mesh->info.front >= UP_COUNT)
            continue;
        Mat4 om = object_matrix(o);
        Vec3 d = v3_norm(m4_dir(&om, axis_vec(o->mesh->info.front)));
        *sum = v3_add(*sum, v3_scale(d, (float)o->poly_count));
        any = 1;
    }
    return any;
}

/* The sum of the faces' unit normals in the world (see the top), and the
 * faces counted; huge scenes are sampled. */
static Vec3 face_lean(const Scene *s, double *faces_out)
{
    uint64_t total = 0;
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++)
        total += s->objs[i].face_count;
    uint32_t stride = total > SAMPLE_POLYS ? (uint32_t)(total / SAMPLE_POLYS) + 1 : 1;
    Vec3 sum = v3(0, 0, 0);
    double n = 0;
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        double x = 0, y = 0, z = 0;
        for (uint32_t f = 0; f < o->face_count; f += stride) {
            float nf[3];
            scene_face_normal(s, (uint32_t)o->face_base + f, nf);
            x += nf[0];
            y += nf[1];
            z += nf[2];
            n++;
        }
        Mat4 om = object_matrix(o);
        float sc = o->scale != 0 ? 1.0f / o->scale : 1;
        sum = v3_add(sum, v3_scale(m4_dir(&om, v3((float)x, (float)y, (float)z)), sc));
    }
    *faces_out = n;
    return sum;
}

void scene_front(const Scene *s, SceneFront *out)
{
    Vec3 f;
    memset(out, 0, sizeof *out);
    if (format_front(s, &f) && (f.x != 0 || f.z != 0)) {
        out->dir = v3_norm(v3(f.x, 0, f.z));
        out->weight = 1;
        out->from = FRONT_FORMAT;
        out->lean = 1;
        return;
    }
    double n;
    Vec3 lean = face_lean(s, &n);
    float h = sqrtf(lean.x * lean.x + lean.z * lean.z);
    out->lean = n > 0 ? (float)(h / n) : 0;
    /* the faces' lean, as sure as it is large, and +z, a little */
    float w = out->lean >= FRONT_FULL ? 1 : out->lean / FRONT_FULL;
    Vec3 sum = v3(0, 0, FRONT_PLAIN);
    if (h > 0)
        sum = v3_add(sum, v3(w * lean.x / h, 0, w * lean.z / h));
    float len = v3_len(sum);
    out->dir = len > 0 ? v3_scale(sum, 1 / len) : v3(0, 0, 1);
    out->weight = len < 1 ? len : 1;
    out->from = w > FRONT_PLAIN / 4 ? FRONT_FACES : FRONT_NONE;
}

float front_factor(const SceneFront *f, float yaw_deg, float pitch_deg)
{
    Vec3 d = view_dir(yaw_deg, pitch_deg);
    float h = sqrtf(d.x * d.x + d.z * d.z);
    float c = h > 0 ? (d.x * f->dir.x + d.z * f->dir.z) / h : 0;
    return 1 + FRONT_PULL * f->weight * c;
}

/* ==== From the geometry alone ==== */

void scene_pick_view(const Scene *s, float *yaw_out, float *pitch_out)
{
    static const float yaws[NCAND] = { -30, 30, -60, 60, -120, 120, -150, 150 };
    const float pitch = 25;
    Vec3 d[NCAND];
    double score[NCAND] = { 0 };
    for (int c = 0; c < NCAND; c++)
        d[c] = view_dir(yaws[c], pitch);
    uint32_t total = 0;
    for (uint32_t oi = 0; oi < s->nbase_objs && (int)oi < s->nobjs; oi++)
        total += s->objs[oi].poly_count;
    uint32_t stride = total > SAMPLE_POLYS ? total / SAMPLE_POLYS + 1 : 1;
    for (uint32_t oi = 0; oi < s->nbase_objs && (int)oi < s->nobjs; oi++) {
        const Object *o = &s->objs[oi];
        if (!o->mesh)
            continue;
        const float *pos = o->mesh->pos;
        /* the views are of the world: the object's up axis turns its normals */
        Mat4 om = object_matrix(o);
        for (uint32_t k = o->poly_first; k < o->poly_first + o->poly_count; k += stride) {
            /* Newell's vector: the normal times twice the area */
            float n[3] = { 0, 0, 0 };
            uint32_t c0 = scene_poly_c0(s, k), c1 = scene_poly_c0(s, k + 1);
            for (uint32_t c = c0; c < c1; c++) {
                const float *p = &pos[3 * (size_t)s->poly_corner[c]];
                const float *q = &pos[3 * (size_t)s->poly_corner[c + 1 < c1 ? c + 1 : c0]];
                n[0] += (p[1] - q[1]) * (p[2] + q[2]);
                n[1] += (p[2] - q[2]) * (p[0] + q[0]);
                n[2] += (p[0] - q[0]) * (p[1] + q[1]);
            }
            Vec3 wn = m4_dir(&om, v3(n[0], n[1], n[2]));
            for (int c = 0; c < NCAND; c++) {
                float f = wn.x * d[c].x + wn.y * d[c].y + wn.z * d[c].z;
                if (f > 0)
                    score[c] += f;
            }
        }
    }
    SceneFront front;
    scene_front(s, &front);
    int best = 0;
    double bests = -1;
    for (int c = 0; c < NCAND; c++) {
        double sc = score[c] * front_factor(&front, yaws[c], pitch);
        if (sc > bests * (1 + 1e-9)) {
            bests = sc;
            best = c;
        }
    }
    *yaw_out = yaws[best];
    *pitch_out = pitch;
}
