/* writers.c: see writers.h. Written for the tests, not for speed. */
#define _DEFAULT_SOURCE

#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <jpeglib.h>
#include <zlib.h>

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

/* ==== images ==== */

typedef struct {
    struct jpeg_error_mgr mgr;
    jmp_buf               jmp;
} WjErr;

static void wj_fail(j_common_ptr c) { longjmp(((WjErr *)c->err)->jmp, 1); }

char *w_jpeg(const uint8_t *px, int w, int h, int comps, const char *colour, int adobe, int progressive,
             size_t *len)
{
    struct jpeg_compress_struct c;
    WjErr e;
    unsigned char *buf = NULL;
    unsigned long n = 0;
    c.err = jpeg_std_error(&e.mgr);
    e.mgr.error_exit = wj_fail;
    if (setjmp(e.jmp)) {
        jpeg_destroy_compress(&c);
        free(buf);
        return NULL;
    }
    jpeg_create_compress(&c);
    jpeg_mem_dest(&c, &buf, &n);
    c.image_width = (JDIMENSION)w;
    c.image_height = (JDIMENSION)h;
    c.input_components = comps;
    c.in_color_space = comps == 1 ? JCS_GRAYSCALE : comps == 4 ? JCS_CMYK : JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 100, TRUE);
    J_COLOR_SPACE cs = strcmp(colour, "grey") == 0   ? JCS_GRAYSCALE
                     : strcmp(colour, "rgb") == 0    ? JCS_RGB
                     : strcmp(colour, "cmyk") == 0   ? JCS_CMYK
                     : strcmp(colour, "ycck") == 0   ? JCS_YCCK
                                                     : JCS_YCbCr;
    jpeg_set_colorspace(&c, cs);
    c.write_Adobe_marker = adobe ? TRUE : FALSE;
    /* full-size chroma: pure colours come back within rounding */
    for (int i = 0; i < c.num_components; i++)
        c.comp_info[i].h_samp_factor = c.comp_info[i].v_samp_factor = 1;
    if (progressive)
        jpeg_simple_progression(&c);
    jpeg_start_compress(&c, TRUE);
    /* libjpeg stores CMYK as it is given; Adobe's files hold it inverted */
    size_t row = (size_t)w * comps;
    uint8_t *tmp = malloc(row);
    while (tmp && c.next_scanline < c.image_height) {
        const uint8_t *src = px + (size_t)c.next_scanline * row;
        for (size_t i = 0; i < row; i++)
            tmp[i] = comps == 4 && adobe ? (uint8_t)(255 - src[i]) : src[i];
        JSAMPROW r = tmp;
        jpeg_write_scanlines(&c, &r, 1);
    }
    free(tmp);
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    *len = n;
    return (char *)buf;
}

int w_jpeg_set_size(char *jpg, size_t len, int w, int h)
{
    uint8_t *b = (uint8_t *)jpg;
    for (size_t i = 2; i + 9 < len;) {
        if (b[i] != 0xFF)
            return -1;
        int m = b[i + 1];
        size_t seg = (size_t)b[i + 2] << 8 | b[i + 3];
        if (m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC) {
            b[i + 5] = (uint8_t)(h >> 8);
            b[i + 6] = (uint8_t)h;
            b[i + 7] = (uint8_t)(w >> 8);
            b[i + 8] = (uint8_t)w;
            return 0;
        }
        i += 2 + seg;
    }
    return -1;
}

/* The end of the entropy-coded data that starts at i: the next marker
 * that is neither a stuffed 0xFF00 nor a restart. */
static size_t scan_end(const uint8_t *b, size_t len, size_t i)
{
    while (i + 1 < len && !(b[i] == 0xFF && b[i + 1] != 0 && !(b[i + 1] >= 0xD0 && b[i + 1] <= 0xD7)))
        i++;
    return i;
}

char *w_jpeg_repeat_last_scan(const char *jpg, size_t len, int n, size_t *len_out)
{
    const uint8_t *b = (const uint8_t *)jpg;
    size_t i = 2, piece = 0, sos_end = 0, first_table = 0;
    int tables = 0;
    /* the last run of DHT/DQT segments and the SOS + data after it */
    while (i + 4 <= len && b[i] == 0xFF && b[i + 1] != 0xD9) {
        int m = b[i + 1];
        size_t seg = (size_t)b[i + 2] << 8 | b[i + 3];
        if (m == 0xC4 || m == 0xDB) {
            if (!tables)
                first_table = i;
            tables = 1;
            i += 2 + seg;
        } else if (m == 0xDA) {
            piece = tables ? first_table : i;
            tables = 0;
            sos_end = scan_end(b, len, i + 2 + seg);
            i = sos_end;
        } else {
            tables = 0;
            i += 2 + seg;
        }
    }
    if (!sos_end || i + 2 > len)
        return NULL;
    size_t one = sos_end - piece, total = len + (size_t)n * one;
    char *out = malloc(total);
    if (!out)
        return NULL;
    memcpy(out, jpg, sos_end);
    for (int k = 0; k < n; k++)
        memcpy(out + sos_end + (size_t)k * one, jpg + piece, one);
    memcpy(out + sos_end + (size_t)n * one, jpg + sos_end, len - sos_end);
    *len_out = total;
    return out;
}

static void put_chunk(FILE *f, const char *type, const uint8_t *data, uint32_t n)
{
    put_u32be(f, n);
    uint8_t head[4];
    memcpy(head, type, 4);
    fwrite(head, 1, 4, f);
    if (n)
        fwrite(data, 1, n, f);
    uLong crc = crc32(crc32(0, head, 4), data, n);
    put_u32be(f, (uint32_t)crc);
}

char *w_png_claiming(int w, int h, size_t *len)
{
    char *buf;
    FILE *f = open_memstream(&buf, len);
    if (!f)
        return NULL;
    fwrite("\x89PNG\r\n\x1a\n", 1, 8, f);
    uint8_t ihdr[13] = { (uint8_t)(w >> 24), (uint8_t)(w >> 16), (uint8_t)(w >> 8), (uint8_t)w,
                         (uint8_t)(h >> 24), (uint8_t)(h >> 16), (uint8_t)(h >> 8), (uint8_t)h,
                         8, 2, 0, 0, 0 };
    put_chunk(f, "IHDR", ihdr, 13);
    uint8_t zero = 0, z[16];
    uLongf zn = sizeof z;
    compress(z, &zn, &zero, 1);
    put_chunk(f, "IDAT", z, (uint32_t)zn);
    put_chunk(f, "IEND", NULL, 0);
    return finish(f, &buf, len);
}

char *w_tga_rle(int w, int h, int top, size_t *len)
{
    size_t px = (size_t)w * h, packets = (px + 127) / 128;
    uint8_t *b = malloc(18 + 2 * packets);
    if (!b)
        return NULL;
    memset(b, 0, 18);
    b[2] = 11;                                  /* grey, run-length encoded */
    b[12] = (uint8_t)w;
    b[13] = (uint8_t)(w >> 8);
    b[14] = (uint8_t)h;
    b[15] = (uint8_t)(h >> 8);
    b[16] = 8;
    b[17] = top ? 0x20 : 0;
    for (size_t k = 0; k < packets; k++) {
        size_t run = px - 128 * k < 128 ? px - 128 * k : 128;
        b[18 + 2 * k] = (uint8_t)(0x80 | (run - 1));
        b[18 + 2 * k + 1] = (uint8_t)(k * 37);
    }
    *len = 18 + 2 * packets;
    return (char *)b;
}
