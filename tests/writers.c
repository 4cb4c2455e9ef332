/* writers.c: see writers.h. Written for the tests, not for speed. */
#define _DEFAULT_SOURCE

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "writers.h"

static uint32_t fcount(const Mesh *m, uint32_t f) { return m->face_start[f + 1] - m->face_start[f]; }
static const float *vpos(const Mesh *m, uint32_t v) { return m->pos + 3 * (size_t)v; }

/* open_memstream sets the buffer and its length at fclose. */
static char *finish(FILE *f, char **buf, size_t *len)
{
    (void)len;
    if (fclose(f) != 0) {
        free(*buf);
        return NULL;
    }
    return *buf;
}

char *w_obj(const Mesh *m, size_t *len)
{
    char *buf;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    fprintf(f, "# written by the zview tests\n");
    for (uint32_t v = 0; v < m->nverts; v++)
        fprintf(f, "v %.9g %.9g %.9g\n", vpos(m, v)[0], vpos(m, v)[1], vpos(m, v)[2]);
    for (uint32_t fi = 0; fi < m->nfaces; fi++) {
        fputc('f', f);
        for (uint32_t k = m->face_start[fi]; k < m->face_start[fi + 1]; k++)
            fprintf(f, " %u", m->corner[k] + 1);
        fputc('\n', f);
    }
    return finish(f, &buf, len);
}

static void put_u32le(FILE *f, uint32_t v)
{
    unsigned char b[4] = { (unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
                           (unsigned char)(v >> 24) };
    fwrite(b, 1, 4, f);
}

static void put_f32le(FILE *f, float x)
{
    uint32_t u;
    memcpy(&u, &x, 4);
    put_u32le(f, u);
}

static void put_u32be(FILE *f, uint32_t v)
{
    unsigned char b[4] = { (unsigned char)(v >> 24), (unsigned char)(v >> 16), (unsigned char)(v >> 8),
                           (unsigned char)v };
    fwrite(b, 1, 4, f);
}

static void put_f32be(FILE *f, float x)
{
    uint32_t u;
    memcpy(&u, &x, 4);
    put_u32be(f, u);
}

char *w_stl_binary(const Mesh *m, size_t *len)
{
    char *buf;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    /* starts with "solid", as many real binary files do */
    char head[80];
    memset(head, ' ', sizeof head);
    memcpy(head, "solid written by the zview tests", 32);
    fwrite(head, 1, 80, f);
    put_u32le(f, m->nfaces);
    for (uint32_t fi = 0; fi < m->nfaces; fi++) {
        if (fcount(m, fi) != 3) {
            finish(f, &buf, len);
            free(buf);
            return NULL;
        }
        for (int k = 0; k < 3; k++)
            put_f32le(f, 0.0f);
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++)
                put_f32le(f, vpos(m, m->corner[m->face_start[fi] + c])[k]);
        fputc(0, f);
        fputc(0, f);
    }
    return finish(f, &buf, len);
}

char *w_stl_ascii(const Mesh *m, size_t *len)
{
    char *buf;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    fprintf(f, "solid test\n");
    for (uint32_t fi = 0; fi < m->nfaces; fi++) {
        if (fcount(m, fi) != 3) {
            finish(f, &buf, len);
            free(buf);
            return NULL;
        }
        fprintf(f, "  facet normal 0 0 1\n    outer loop\n");
        for (int c = 0; c < 3; c++) {
            const float *p = vpos(m, m->corner[m->face_start[fi] + c]);
            fprintf(f, "      vertex %.9g %.9g %.9g\n", p[0], p[1], p[2]);
        }
        fprintf(f, "    endloop\n  endfacet\n");
    }
    fprintf(f, "endsolid test\n");
    return finish(f, &buf, len);
}

char *w_ply_binary(const Mesh *m, int big_endian, size_t *len)
{
    char *buf;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    fprintf(f, "ply\nformat %s 1.0\ncomment zview tests\nelement vertex %u\n"
               "property float x\nproperty float y\nproperty float z\nelement face %u\n"
               "property list uchar int vertex_indices\nend_header\n",
            big_endian ? "binary_big_endian" : "binary_little_endian", m->nverts, m->nfaces);
    for (uint32_t v = 0; v < m->nverts; v++)
        for (int k = 0; k < 3; k++)
            (big_endian ? put_f32be : put_f32le)(f, vpos(m, v)[k]);
    for (uint32_t fi = 0; fi < m->nfaces; fi++) {
        fputc((int)fcount(m, fi), f);
        for (uint32_t k = m->face_start[fi]; k < m->face_start[fi + 1]; k++)
            (big_endian ? put_u32be : put_u32le)(f, m->corner[k]);
    }
    return finish(f, &buf, len);
}

char *w_ply_ascii(const Mesh *m, size_t *len)
{
    char *buf;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex %u\nproperty float x\nproperty float y\n"
               "property float z\nelement face %u\nproperty list uchar int vertex_indices\n"
               "end_header\n", m->nverts, m->nfaces);
    for (uint32_t v = 0; v < m->nverts; v++)
        fprintf(f, "%.9g %.9g %.9g\n", vpos(m, v)[0], vpos(m, v)[1], vpos(m, v)[2]);
    for (uint32_t fi = 0; fi < m->nfaces; fi++) {
        fprintf(f, "%u", fcount(m, fi));
        for (uint32_t k = m->face_start[fi]; k < m->face_start[fi + 1]; k++)
            fprintf(f, " %u", m->corner[k]);
        fputc('\n', f);
    }
    return finish(f, &buf, len);
}

char *w_off(const Mesh *m, size_t *len)
{
    char *buf;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    fprintf(f, "OFF\n# zview tests\n%u %u 0\n", m->nverts, m->nfaces);
    for (uint32_t v = 0; v < m->nverts; v++)
        fprintf(f, "%.9g %.9g %.9g\n", vpos(m, v)[0], vpos(m, v)[1], vpos(m, v)[2]);
    for (uint32_t fi = 0; fi < m->nfaces; fi++) {
        fprintf(f, "%u", fcount(m, fi));
        for (uint32_t k = m->face_start[fi]; k < m->face_start[fi + 1]; k++)
            fprintf(f, " %u", m->corner[k]);
        fputc('\n', f);
    }
    return finish(f, &buf, len);
}

/* glTF 2.0 binary: a JSON chunk (one mesh, one node, one scene; two
 * accessors: POSITION floats with their bounds, and uint32 indices) and
 * a BIN chunk. Chunks are padded to 4 bytes (JSON with blanks). */
char *w_glb(const Mesh *m, size_t *len)
{
    for (uint32_t fi = 0; fi < m->nfaces; fi++)
        if (fcount(m, fi) != 3)
            return NULL;
    float lo[3] = { 3e38f, 3e38f, 3e38f }, hi[3] = { -3e38f, -3e38f, -3e38f };
    for (uint32_t v = 0; v < m->nverts; v++)
        for (int k = 0; k < 3; k++) {
            float c = vpos(m, v)[k];
            lo[k] = c < lo[k] ? c : lo[k];
            hi[k] = c > hi[k] ? c : hi[k];
        }
    size_t pos_bytes = (size_t)m->nverts * 12, idx_bytes = (size_t)m->nfaces * 12;
    char json[2048];
    int jn = snprintf(json, sizeof json,
        "{\"asset\":{\"version\":\"2.0\",\"generator\":\"zview tests\"},"
        "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"model\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4}]}],"
        "\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu,\"target\":34962},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34963}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%u,\"type\":\"VEC3\","
        "\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]},"
        "{\"bufferView\":1,\"componentType\":5125,\"count\":%u,\"type\":\"SCALAR\"}]}",
        pos_bytes + idx_bytes, pos_bytes, pos_bytes, idx_bytes, m->nverts, lo[0], lo[1], lo[2],
        hi[0], hi[1], hi[2], 3 * m->nfaces);
    while (jn % 4)
        json[jn++] = ' ';
    size_t bin = pos_bytes + idx_bytes;   /* a multiple of 4 */
    char *buf;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    fwrite("glTF", 1, 4, f);
    put_u32le(f, 2);
    put_u32le(f, (uint32_t)(12 + 8 + jn + 8 + bin));
    put_u32le(f, (uint32_t)jn);
    fwrite("JSON", 1, 4, f);
    fwrite(json, 1, (size_t)jn, f);
    put_u32le(f, (uint32_t)bin);
    fwrite("BIN\0", 1, 4, f);
    for (uint32_t v = 0; v < m->nverts; v++)
        for (int k = 0; k < 3; k++)
            put_f32le(f, vpos(m, v)[k]);
    for (uint32_t c = 0; c < 3 * m->nfaces; c++)
        put_u32le(f, m->corner[c]);
    return finish(f, &buf, len);
}

int w_save(const char *path, const char *buf, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    size_t n = fwrite(buf, 1, len, f);
    return fclose(f) == 0 && n == len ? 0 : -1;
}
