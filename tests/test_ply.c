/* test_ply.c: the PLY loader: ascii and both binary byte orders, any
 * property order and type, colours, skipped elements, point clouds, and
 * every bad input (counts past the end or overflowing, wrong types,
 * out-of-range indices, NaN, truncation). Parsed with mesh_parse_buffer
 * from exactly sized heap copies. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "testlib.h"

static Mesh M;
static char E[512];

static void teardown(void) { mesh_free(&M); }
TestSuite(ply, .fini = teardown);

static int parse_n(const void *s, size_t n)
{
    char *buf = malloc(n ? n : 1);
    cr_assert_not_null(buf);
    memcpy(buf, s, n);
    mesh_free(&M);   /* a parse zeroes the mesh: free the last one */
    int r = mesh_parse_buffer(&M, "t.ply", NULL, buf, n, E, sizeof E);
    free(buf);
    return r;
}

static int parse(const char *s) { return parse_n(s, strlen(s)); }

static void expect_err(const char *s, size_t n, const char *want)
{
    cr_assert_eq(parse_n(s, n), -1, "expected an error");
    cr_assert_not_null(strstr(E, want), "error '%s' lacks '%s'", E, want);
    cr_assert_null(M.pos);
    cr_assert_eq(M.nfaces, 0);
}
#define EXPECT_ERR(lit, want) expect_err(lit, sizeof lit - 1, want)

static void expect_corners(uint32_t f, const uint32_t *want, uint32_t n)
{
    cr_assert_eq(M.face_start[f + 1] - M.face_start[f], n, "face %u corner count", f);
    for (uint32_t i = 0; i < n; i++)
        cr_assert_eq(M.corner[M.face_start[f] + i], want[i], "face %u corner %u", f, i);
}

/* ==== ascii ==== */

static const char square_ascii[] =
    "ply\n"
    "format ascii 1.0\n"
    "comment a unit square as two faces: a triangle and a quad would do, "
    "but this has both\n"
    "element vertex 5\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 2\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n"
    "3 0 1 4\n"
    "4 0 1 2 3\n";

Test(ply, ascii_basic)
{
    cr_assert_eq(parse(square_ascii), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "ply ascii");
    cr_assert_eq(M.nverts, 5);
    cr_assert_eq(M.nfaces, 2);
    cr_assert_eq(M.info.triangles, 3);
    expect_corners(0, (uint32_t[]){ 0, 1, 4 }, 3);
    expect_corners(1, (uint32_t[]){ 0, 1, 2, 3 }, 4);
    cr_assert_eq(M.pos[12], 0.5f);
    cr_assert_eq(M.pos[14], 1.0f);
    cr_assert_null(M.rgb);
    cr_assert_eq(mesh_face_mat(&M, 1), -1);
    cr_assert_str_eq(M.objs[0].name, "t");
}

Test(ply, any_property_order_extra_properties_and_colours)
{
    cr_assert_eq(parse("ply\nformat ascii 1.0\nelement vertex 3\n"
                       "property uchar red\nproperty double z\nproperty float nx\n"
                       "property uchar green\nproperty float y\nproperty list uchar float junk\n"
                       "property float x\nproperty uchar blue\n"
                       "element face 1\nproperty float quality\nproperty list ushort uint vertex_index\n"
                       "end_header\n"
                       "255 3 0.5 0 2 2 9 9 1 0\n"
                       "0 6 0.5 255 5 0 4 51\n"
                       "0 9 0.5 0 8 1 7 7 255\n"
                       "0.25 3 2 1 0\n"), 0, "%s", E);
    cr_assert_eq(M.pos[0], 1.0f);
    cr_assert_eq(M.pos[1], 2.0f);
    cr_assert_eq(M.pos[2], 3.0f);
    cr_assert_eq(M.pos[3], 4.0f);
    cr_assert_eq(M.pos[8], 9.0f);
    cr_assert_not_null(M.rgb);
    cr_assert_eq(M.rgb[0], 1.0f);
    cr_assert_eq(M.rgb[1], 0.0f);
    cr_assert_eq(M.rgb[4], 1.0f);
    cr_assert_float_eq(M.rgb[5], 0.2f, 1e-6);
    expect_corners(0, (uint32_t[]){ 2, 1, 0 }, 3);
}

Test(ply, float_colours_and_face_colours)
{
    cr_assert_eq(parse("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
                       "element face 2\nproperty list uchar int vertex_indices\nproperty uchar red\n"
                       "property uchar green\nproperty uchar blue\nend_header\n"
                       "0 0 0 0.5 1 2\n1 0 0 0 0 0\n0 1 0 1 1 1\n"
                       "3 0 1 2 255 0 0\n3 0 2 1 255 0 0\n"), 0, "%s", E);
    cr_assert_eq(M.rgb[0], 0.5f);
    cr_assert_eq(M.rgb[2], 1.0f, "floats are clamped to 0..1");
    cr_assert_eq(M.nmats, 1, "equal face colours share a material");
    cr_assert_eq(mesh_face_mat(&M, 0), 0);
    cr_assert_eq(mesh_face_mat(&M, 1), 0);
    cr_assert_eq(M.mats[0].kd[0], 1.0f);
    cr_assert_eq(M.mats[0].kd[1], 0.0f);
}

Test(ply, other_elements_skipped_in_any_order)
{
    cr_assert_eq(parse("ply\r\nformat ascii 1.0\r\nelement material 2\r\nproperty list int int ids\r\n"
                       "property float shine\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\n"
                       "element vertex 3\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
                       "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n"
                       "2 7 8 0.5\r\n0 1\r\n"
                       "3 0 1 2\r\n"
                       "0 0 0\r\n1 0 0\r\n0 1 0\r\n"
                       "0 1\r\n"), 0, "%s", E);
    cr_assert_eq(M.nverts, 3);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_eq(M.pos[3], 1.0f);
    expect_corners(0, (uint32_t[]){ 0, 1, 2 }, 3);
}

Test(ply, point_cloud_loads_its_vertices, .init = cr_redirect_stderr)
{
    cr_assert_eq(parse("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                       "property float z\nend_header\n1 2 3\n4 5 6\n"), 0, "%s", E);
    cr_assert_eq(M.nverts, 2);
    cr_assert_eq(M.nfaces, 0);
    /* every vertex a point, without a per-point array */
    cr_assert_eq(M.npoints, 2);
    cr_assert_null(M.point);
    cr_assert_eq(M.nobjs, 1);
    cr_assert_eq(M.objs[0].face_count, 0);
    cr_assert_eq(M.objs[0].point_count, 2);
    cr_assert_eq(M.objs[0].vert_min, 0);
    cr_assert_eq(M.objs[0].vert_max, 1);
    cr_assert_not_null(M.face_start);
    fflush(stderr);
    cr_assert_stderr_eq_str("");
}

Test(ply, old_mac_line_ends)
{
    cr_assert_eq(parse("ply\rformat ascii 1.0\relement vertex 3\rproperty float x\rproperty float y\r"
                       "property float z\relement face 1\rproperty list uchar int vertex_indices\r"
                       "end_header\r0 0 0\r1 0 0\r0 1 0\r3 0 1 2\r"), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
}

Test(ply, ascii_errors)
{
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
               "t.ply:11: NaN or infinite number 'nan'");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
               "t.ply:13: vertex index 3 out of range (3 vertices)");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
               "t.ply:13: vertex index -1 out of range");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n",
               "t.ply:13: malformed integer '1.5'");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
               "t.ply:13: face has 2 vertices (at least 3)");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
               "file ends inside element 'face'");
    /* counts checked against the size before anything is allocated */
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
               "property float z\nend_header\n0 0 0\n",
               "t.ply: element 'vertex' of 4000000000 records needs more than the 6 bytes after the header");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 99999999999999999999\nproperty list uchar int vertex_indices\nend_header\n",
               "t.ply:7: bad element count '99999999999999999999'");
}

/* ==== the header ==== */

Test(ply, header_errors)
{
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "the header has no end_header");
    EXPECT_ERR("ply\nformat ascii 2.0 x\nelement vertex 1\nproperty flaot x\nend_header\n", "t.ply:4: unknown type 'flaot'");
    EXPECT_ERR("ply\nformat binary_middle_endian 1.0\nend_header\n", "t.ply:2: unknown format");
    EXPECT_ERR("ply\nelement vertex 1\nproperty float x\nend_header\n", "no format line");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
               "the vertex element lacks x, y or z");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 1 2\n",
               "no vertex element");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list float int vertex_indices\nend_header\n", "t.ply:8: bad list count type 'float'");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar float vertex_indices\nend_header\n",
               "t.ply:8: vertex indices of type float (not an integer type)");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float x\n", "t.ply:5: property 'x' given twice");
    EXPECT_ERR("ply\nformat ascii 1.0\nproperty float x\n", "t.ply:3: property before any element");
    EXPECT_ERR("ply\nformat ascii 1.0\nfrobnicate\nend_header\n", "t.ply:3: unknown header line 'frobnicate'");
    EXPECT_ERR("ply\nformat ascii 1.0\nelement vertex 3\x01\n", "binary or unreadable data in the header");
}

/* ==== binary ==== */

typedef struct {
    unsigned char *b;
    size_t n, cap;
    int be;
} Buf;

static void put(Buf *b, const void *p, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2 + 256;
        b->b = realloc(b->b, b->cap);
    }
    memcpy(b->b + b->n, p, n);
    b->n += n;
}

static void put_s(Buf *b, const char *s) { put(b, s, strlen(s)); }

/* n bytes of v in the buffer's byte order */
static void put_int(Buf *b, uint64_t v, int n)
{
    unsigned char q[8];
    for (int i = 0; i < n; i++)
        q[b->be ? n - 1 - i : i] = (unsigned char)(v >> (8 * i));
    put(b, q, (size_t)n);
}

static void put_f(Buf *b, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put_int(b, u, 4);
}

static void put_d(Buf *b, double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    put_int(b, u, 8);
}

static const float V[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0.25f } };

/* float x y z, faces (uchar count, int indices): a triangle and a quad */
static Buf plain(int be)
{
    Buf b = { .be = be };
    put_s(&b, be ? "ply\nformat binary_big_endian 1.0\n" : "ply\nformat binary_little_endian 1.0\n");
    put_s(&b, "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 2\nproperty list uchar int vertex_indices\nend_header\n");
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            put_f(&b, V[i][k]);
    put_int(&b, 3, 1);
    put_int(&b, 0, 4);
    put_int(&b, 1, 4);
    put_int(&b, 3, 4);
    put_int(&b, 4, 1);
    for (int k = 0; k < 4; k++)
        put_int(&b, (uint64_t)k, 4);
    return b;
}

static void expect_plain(void)
{
    cr_assert_eq(M.nverts, 4);
    cr_assert_eq(M.nfaces, 2);
    cr_assert_eq(memcmp(M.pos, V, sizeof V), 0);
    expect_corners(0, (uint32_t[]){ 0, 1, 3 }, 3);
    expect_corners(1, (uint32_t[]){ 0, 1, 2, 3 }, 4);
}

Test(ply, binary_both_byte_orders)
{
    for (int be = 0; be < 2; be++) {
        Buf b = plain(be);
        cr_assert_eq(parse_n(b.b, b.n), 0, "%s", E);
        cr_assert_str_eq(M.info.format, be ? "ply binary big endian" : "ply binary little endian");
        expect_plain();
        mesh_free(&M);
        free(b.b);
    }
}

Test(ply, binary_every_type)
{
    /* double coordinates after an int8 and a ushort, ushort colours,
     * a uint count with int16 indices, and a trailing skipped list */
    for (int be = 0; be < 2; be++) {
        Buf b = { .be = be };
        put_s(&b, be ? "ply\nformat binary_big_endian 1.0\n" : "ply\nformat binary_little_endian 1.0\n");
        put_s(&b, "element vertex 4\nproperty char flag\nproperty ushort red\nproperty double x\n"
                  "property double y\nproperty double z\nproperty list uint8 int32 tags\n"
                  "element face 2\nproperty list uint int16 vertex_indices\nproperty list uchar double w\n"
                  "end_header\n");
        for (int i = 0; i < 4; i++) {
            put_int(&b, (uint64_t)-1, 1);
            put_int(&b, 65535, 2);
            for (int k = 0; k < 3; k++)
                put_d(&b, V[i][k]);
            put_int(&b, 1, 1);
            put_int(&b, 77, 4);
        }
        put_int(&b, 3, 4);
        put_int(&b, 0, 2);
        put_int(&b, 1, 2);
        put_int(&b, 3, 2);
        put_int(&b, 1, 1);
        put_d(&b, 0.5);
        put_int(&b, 4, 4);
        for (int k = 0; k < 4; k++)
            put_int(&b, (uint64_t)k, 2);
        put_int(&b, 0, 1);
        cr_assert_eq(parse_n(b.b, b.n), 0, "%s", E);
        expect_plain();
        cr_assert_not_null(M.rgb);
        cr_assert_eq(M.rgb[0], 1.0f);
        cr_assert_eq(M.rgb[1], 1.0f, "absent green is white");
        mesh_free(&M);
        free(b.b);
    }
}

Test(ply, binary_and_ascii_agree)
{
    cr_assert_eq(parse("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                       "0 0 0\n1 0 0\n1 1 0\n0 1 0.25\n3 0 1 3\n4 0 1 2 3\n"), 0, "%s", E);
    expect_plain();
}

Test(ply, binary_errors)
{
    /* truncated inside the faces */
    Buf b = plain(0);
    cr_assert_eq(parse_n(b.b, b.n - 3), -1);
    cr_assert_not_null(strstr(E, "face 2 of 4 vertices goes past the end of the file"), "%s", E);
    /* every prefix fails cleanly, never reads past the end */
    for (size_t n = 0; n < b.n; n++) {
        cr_assert_eq(parse_n(b.b, n), -1, "prefix %zu", n);
        cr_assert_null(M.pos);
    }
    free(b.b);

    /* a NaN coordinate: its byte offset */
    b = plain(1);
    size_t hdr = b.n - 4 * 12 - 13 - 17;
    float nan = __builtin_nanf("");
    uint32_t u;
    memcpy(&u, &nan, 4);
    unsigned char q[4] = { (unsigned char)(u >> 24), (unsigned char)(u >> 16), (unsigned char)(u >> 8),
                           (unsigned char)u };
    memcpy(b.b + hdr + 12 + 4, q, 4);
    cr_assert_eq(parse_n(b.b, b.n), -1);
    char want[80];
    snprintf(want, sizeof want, "t.ply: byte %zu: NaN or infinite coordinate (vertex 2)", hdr + 12);
    cr_assert_str_eq(E, want);
    free(b.b);

    /* an index past the vertices, and a negative one */
    b = plain(0);
    b.b[b.n - 1] = 9;   /* last index, high byte of a little-endian int: 0x09000003 */
    cr_assert_eq(parse_n(b.b, b.n), -1);
    cr_assert_not_null(strstr(E, "vertex index 150994947 out of range (4 vertices; face 2)"), "%s", E);
    b.b[b.n - 1] = 0xff;
    cr_assert_eq(parse_n(b.b, b.n), -1);
    cr_assert_not_null(strstr(E, "vertex index -16777213 out of range"), "%s", E);
    free(b.b);

    /* a face of 2 corners */
    b = plain(0);
    b.b[b.n - 17] = 2;
    cr_assert_eq(parse_n(b.b, b.n), -1);
    cr_assert_not_null(strstr(E, "face 2 has 2 vertices (at least 3)"), "%s", E);
    free(b.b);
}

Test(ply, binary_counts_checked_before_allocation)
{
    /* 2^32 - 2 faces of at least 13 bytes claimed in a file of a few */
    Buf b = { 0 };
    put_s(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 4294967294\nproperty list uchar int vertex_indices\nend_header\n");
    for (int i = 0; i < 9; i++)
        put_f(&b, 0);
    cr_assert_eq(parse_n(b.b, b.n), -1);
    cr_assert_str_eq(E, "t.ply: element 'face' of 4294967294 records needs more than the 36 bytes after the header");
    free(b.b);
    /* counts that overflow a 64-bit product */
    b = (Buf){ 0 };
    put_s(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement junk 9223372036854775807\nproperty double a\nproperty double b\n"
              "end_header\n");
    for (int i = 0; i < 9; i++)
        put_f(&b, 0);
    cr_assert_eq(parse_n(b.b, b.n), -1);
    cr_assert_not_null(strstr(E, "element 'junk' of 9223372036854775807 records needs more"), "%s", E);
    free(b.b);
}

Test(ply, random_mutations_load_or_are_refused_by_name, .init = cr_redirect_stderr)
{
    /* three bytes of a good binary file changed at random, 2000 times in
     * each byte order: each result either loads a mesh that keeps every
     * loader promise (never more than the header's 4 vertices and 2
     * faces), or is refused with a message naming the file and nothing
     * left behind */
    uint32_t seed = 7;
    int loaded = 0, refused = 0;
    for (int be = 0; be < 2; be++) {
        Buf b = plain(be);
        for (int t = 0; t < 2000; t++) {
            unsigned char *c = malloc(b.n);
            memcpy(c, b.b, b.n);
            for (int k = 0; k < 3; k++) {
                seed = seed * 1664525u + 1013904223u;
                c[(seed >> 8) % b.n] = (unsigned char)(seed >> 24);
            }
            int r = parse_n(c, b.n);
            const char *broken = tl_load_broken(r, &M, E, "t.ply");
            cr_assert_null(broken, "mutation %d (%s endian): '%s' does not hold (status %d, '%s')", t,
                           be ? "big" : "little", broken, r, E);
            if (r == 0 && strncmp(M.info.format, "ply binary", 10) == 0)
                cr_assert(M.nverts <= 4 && M.nfaces <= 2, "mutation %d: %u vertices, %u faces", t, M.nverts,
                          M.nfaces);
            loaded += r == 0;
            refused += r != 0;
            mesh_free(&M);
            free(c);
        }
        free(b.b);
    }
    /* both outcomes happen (58 and 3942 with this seed) */
    cr_assert_gt(loaded, 20, "%d loaded", loaded);
    cr_assert_gt(refused, 1000, "%d refused", refused);
}
