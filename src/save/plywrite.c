/* plywrite.c: PLY, binary little-endian: a text header declaring a
 * vertex element (x y z as float, then red green blue when the mesh has
 * vertex colours) and a face element (a list of int vertex indices,
 * then red green blue when every face has a material), then the records.
 *
 * Colours are bytes (uchar, 0..255: what most tools read) when every
 * one is exactly k/255 as a PLY reader divides it, which is what a
 * byte colour loaded from any file is; else floats (0..1), so that they
 * come back bit for bit. A face's colour is its material's Kd as a byte;
 * a mesh where some face has none keeps no face colour (the file would
 * have to invent one), and its materials are counted as dropped. A mesh
 * of vertices alone is written without a face element: a point cloud,
 * as PLY readers take it. Objects are written as one; lines and (beside
 * faces) points are dropped. */

#include <string.h>

#include "save_internal.h"

static unsigned char *put_u32(unsigned char *p, uint32_t u)
{
    p[0] = (unsigned char)u;
    p[1] = (unsigned char)(u >> 8);
    p[2] = (unsigned char)(u >> 16);
    p[3] = (unsigned char)(u >> 24);
    return p + 4;
}

static unsigned char *put_f32(unsigned char *p, float x)
{
    uint32_t u;
    memcpy(&u, &x, 4);
    return put_u32(p, u);
}

/* c as a byte, when a reader's k/255 gives c back exactly; -1 otherwise. */
static int byte_of(float c)
{
    if (!(c >= 0 && c <= 1))
        return -1;
    int q = (int)(c * 255.0f + 0.5f);
    return (float)(q / 255.0) == c ? q : -1;
}

static uint8_t byte_near(float c)
{
    return c <= 0 ? 0 : c >= 1 ? 255 : (uint8_t)(c * 255.0f + 0.5f);
}

/* Every vertex colour a byte's? */
static int colours_are_bytes(const Mesh *m)
{
    for (size_t i = 0; i < 3 * (size_t)m->nverts; i++)
        if (byte_of(m->rgb[i]) < 0)
            return 0;
    return 1;
}

/* Does every face have a material (so that each can carry its colour)? */
static int every_face_coloured(const Mesh *m)
{
    if (!m->face_mat || !m->nfaces)
        return 0;
    for (uint32_t f = 0; f < m->nfaces; f++)
        if (m->face_mat[f] < 0 || (uint32_t)m->face_mat[f] >= m->nmats)
            return 0;
    return 1;
}

static void header(const Mesh *m, SaveOut *o, int bytes, int face_rgb, uint32_t max_corners)
{
    char line[128];
    so_str(o, "ply\nformat binary_little_endian 1.0\ncomment written by zview\n");
    snprintf(line, sizeof line, "element vertex %u\n", m->nverts);
    so_str(o, line);
    so_str(o, "property float x\nproperty float y\nproperty float z\n");
    if (m->rgb)
        so_str(o, bytes ? "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                        : "property float red\nproperty float green\nproperty float blue\n");
    if (m->nfaces) {
        snprintf(line, sizeof line, "element face %u\n", m->nfaces);
        so_str(o, line);
        /* a byte's count is what most readers expect; bigger polygons need more */
        so_str(o, max_corners <= 255 ? "property list uchar int vertex_indices\n"
                                     : "property list uint int vertex_indices\n");
        if (face_rgb)
            so_str(o, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    }
    so_str(o, "end_header\n");
}

void save_ply(const Mesh *m, SaveOut *o, SaveReport *rep)
{
    int bytes = m->rgb && colours_are_bytes(m), face_rgb = every_face_coloured(m);
    uint32_t max_corners = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t n = m->face_start[f + 1] - m->face_start[f];
        max_corners = n > max_corners ? n : max_corners;
    }
    uint32_t objs = 0;
    for (uint32_t i = 0; i < m->nobjs; i++)
        objs += m->objs[i].face_count + m->objs[i].point_count + m->objs[i].line_count > 0;
    rep->objects_merged = objs > 1 ? objs - 1 : 0;
    rep->lines_dropped = m->nlines;
    rep->points_dropped = m->nfaces ? m->npoints : 0;   /* a cloud is its vertices */
    rep->materials_dropped = face_rgb ? 0 : m->nmats;
    rep->uvs_dropped = m->uv != NULL;
    rep->ply_float_colours = m->rgb && !bytes;
    header(m, o, bytes, face_rgb, max_corners);

    size_t rec = 12 + (m->rgb ? (bytes ? 3 : 12) : 0);
    for (uint32_t v = 0; v < m->nverts; v++) {
        unsigned char *p = (unsigned char *)so_room(o, rec), *q = p;
        const float *x = m->pos + 3 * (size_t)v;
        q = put_f32(put_f32(put_f32(q, x[0]), x[1]), x[2]);
        if (m->rgb) {
            const float *c = m->rgb + 3 * (size_t)v;
            for (int k = 0; k < 3; k++) {
                if (bytes)
                    *q++ = (unsigned char)byte_of(c[k]);
                else
                    q = put_f32(q, c[k]);
            }
        }
        so_commit(o, rec);
    }
    for (uint32_t f = 0; f < m->nfaces; f++) {
        uint32_t c0 = m->face_start[f], n = m->face_start[f + 1] - c0;
        unsigned char head[4];
        if (max_corners <= 255) {
            head[0] = (unsigned char)n;
            so_put(o, head, 1);
        } else {
            put_u32(head, n);
            so_put(o, head, 4);
        }
        for (uint32_t k = 0; k < n;) {
            uint32_t run = n - k < 512 ? n - k : 512;
            unsigned char *p = (unsigned char *)so_room(o, 4 * run), *q = p;
            for (uint32_t i = 0; i < run; i++)
                q = put_u32(q, m->corner[c0 + k + i]);
            so_commit(o, 4 * run);
            k += run;
        }
        if (face_rgb) {
            const float *kd = m->mats[m->face_mat[f]].kd;
            unsigned char rgb[3] = { byte_near(kd[0]), byte_near(kd[1]), byte_near(kd[2]) };
            so_put(o, rgb, 3);
        }
    }
    rep->vertices = m->nverts;
    rep->faces = m->nfaces;
}
