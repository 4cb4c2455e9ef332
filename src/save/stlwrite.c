/* stlwrite.c: binary STL: an 80-byte header, the triangle count, then
 * 50 bytes a triangle (a normal, three corners, an attribute word), all
 * little-endian. STL holds triangles and nothing else: a polygon is
 * written as the triangles that cover what zview draws of it (the fan
 * from its first corner, a concave one cut by ear clipping:
 * triangles.c), a face of fewer than 3 corners is left out, and points,
 * lines, objects, colours and texture coordinates are counted as
 * dropped.
 *
 * The header does not start with "solid" (readers that go by it would
 * take the file for ASCII) and holds no "COLOR=" (Materialise's part
 * colour); the attribute word is 0, which no convention reads as a
 * colour. The normal is the corners' cross product made unit length (0
 * for a degenerate triangle): readers ignore it, but some check it. */

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "save_internal.h"

static unsigned char *put_f32(unsigned char *p, float x)
{
    uint32_t u;
    memcpy(&u, &x, 4);
    p[0] = (unsigned char)u;
    p[1] = (unsigned char)(u >> 8);
    p[2] = (unsigned char)(u >> 16);
    p[3] = (unsigned char)(u >> 24);
    return p + 4;
}

static void unit_normal(const float *a, const float *b, const float *c, float n[3])
{
    double u[3] = { (double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2] };
    double v[3] = { (double)c[0] - a[0], (double)c[1] - a[1], (double)c[2] - a[2] };
    double w[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
    double len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int k = 0; k < 3; k++)
        n[k] = len > 0 && isfinite(len) ? (float)(w[k] / len) : 0.0f;
}

/* The triangles the faces make: n - 2 a face of n >= 3 corners. */
static uint64_t triangle_count(const Mesh *m)
{
    uint64_t t = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t n = m->face_start[f + 1] - m->face_start[f];
        t += n >= 3 ? n - 2 : 0;
    }
    return t;
}

static void count_dropped(const Mesh *m, SaveReport *rep)
{
    uint32_t objs = 0;
    for (uint32_t i = 0; i < m->nobjs; i++)
        objs += m->objs[i].face_count > 0;
    rep->objects_merged = objs > 1 ? objs - 1 : 0;
    rep->points_dropped = m->npoints;
    rep->lines_dropped = m->nlines;
    rep->materials_dropped = m->nmats;
    rep->colours_dropped = m->rgb != NULL;
    rep->uvs_dropped = m->uv != NULL;
}

void save_stl(const Mesh *m, SaveOut *o, SaveReport *rep)
{
    count_dropped(m, rep);
    uint64_t tris = triangle_count(m);
    unsigned char head[84];
    memset(head, ' ', 80);
    static const char says[] = "binary STL written by zview";
    memcpy(head, says, sizeof says - 1);
    /* the count is 32 bits; a mesh's corners are counted in 32 bits too,
     * so its triangles fit */
    uint32_t t32 = (uint32_t)tris;
    for (int k = 0; k < 4; k++)
        head[80 + k] = (unsigned char)(t32 >> (8 * k));
    so_put(o, head, sizeof head);
    SaveScratch scratch = { 0 };
    uint32_t tri_small[3 * 62], *tri = tri_small, tri_cap = 64;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t c0 = m->face_start[f], n = m->face_start[f + 1] - c0;
        if (n < 3) {
            rep->faces_dropped++;
            continue;
        }
        rep->polygons_split += n > 3;
        if (n > tri_cap) {
            uint32_t *grown = malloc(3 * (size_t)(n - 2) * sizeof *grown);
            if (!grown) {
                o->err = ENOMEM;
                break;
            }
            if (tri != tri_small)
                free(tri);
            tri = grown;
            tri_cap = n;
        }
        uint32_t ntri = (uint32_t)save_face_triangles(m, f, tri, &scratch);
        for (uint32_t k = 0; k < ntri; k++) {
            const float *a = m->pos + 3 * (size_t)m->corner[c0 + tri[3 * k]];
            const float *b = m->pos + 3 * (size_t)m->corner[c0 + tri[3 * k + 1]];
            const float *c = m->pos + 3 * (size_t)m->corner[c0 + tri[3 * k + 2]];
            float nrm[3];
            unit_normal(a, b, c, nrm);
            unsigned char *p = (unsigned char *)so_room(o, 50), *q = p;
            for (int i = 0; i < 3; i++)
                q = put_f32(q, nrm[i]);
            for (int i = 0; i < 3; i++)
                q = put_f32(q, a[i]);
            for (int i = 0; i < 3; i++)
                q = put_f32(q, b[i]);
            for (int i = 0; i < 3; i++)
                q = put_f32(q, c[i]);
            q[0] = q[1] = 0;
            so_commit(o, 50);
        }
    }
    if (tri != tri_small)
        free(tri);
    save_scratch_free(&scratch);
    rep->faces = t32;
    rep->vertices = 0;
}
