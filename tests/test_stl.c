/* test_stl.c: the STL loader, binary and ASCII: telling them apart,
 * merging equal vertices, both face-colour conventions, and every bad
 * input (truncated, lying counts, NaN, broken ASCII structure). Files
 * are built in memory and parsed with mesh_parse_buffer from exactly
 * sized heap copies (a read past the end shows under ASan). */
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
TestSuite(stl, .fini = teardown);

static int parse_fmt(const char *path, const char *fmt, const void *s, size_t n)
{
    char *buf = malloc(n ? n : 1);
    cr_assert_not_null(buf);
    memcpy(buf, s, n);
    mesh_free(&M);   /* a parse zeroes the mesh: free the last one */
    int r = mesh_parse_buffer(&M, path, fmt, buf, n, E, sizeof E);
    free(buf);
    return r;
}

static int parse(const void *s, size_t n) { return parse_fmt("t.stl", NULL, s, n); }

/* ==== Building binary files ==== */

typedef struct {
    unsigned char *b;
    size_t n, cap;
} Buf;

static void put(Buf *b, const void *p, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2 + 64;
        b->b = realloc(b->b, b->cap);
        cr_assert_not_null(b->b);
    }
    memcpy(b->b + b->n, p, n);
    b->n += n;
}

static void put_u32(Buf *b, uint32_t v)
{
    unsigned char q[4] = { (unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
                           (unsigned char)(v >> 24) };
    put(b, q, 4);
}

static void put_f(Buf *b, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put_u32(b, u);
}

static void header_n(Buf *b, const char *text, size_t len, uint32_t n)
{
    char h[80];
    memset(h, 0, sizeof h);
    memcpy(h, text, len < 80 ? len : 80);
    put(b, h, 80);
    put_u32(b, n);
}

static void header(Buf *b, const char *text, uint32_t n)
{
    char h[80];
    memset(h, 0, sizeof h);
    memcpy(h, text, strlen(text) < 80 ? strlen(text) : 80);
    put(b, h, 80);
    put_u32(b, n);
}

static void tri(Buf *b, const float v[9], uint16_t attr)
{
    for (int k = 0; k < 3; k++)
        put_f(b, 0.0f);
    for (int k = 0; k < 9; k++)
        put_f(b, v[k]);
    unsigned char a[2] = { (unsigned char)attr, (unsigned char)(attr >> 8) };
    put(b, a, 2);
}

static const float T0[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
static const float T1[9] = { 1, 0, 0, 1, 1, 0, 0, 1, 0 };

/* Two triangles sharing an edge. */
static Buf square(const char *head, uint16_t a0, uint16_t a1)
{
    Buf b = { 0 };
    header(&b, head, 2);
    tri(&b, T0, a0);
    tri(&b, T1, a1);
    return b;
}

static void expect_corners(uint32_t f, uint32_t a, uint32_t b, uint32_t c)
{
    cr_assert_eq(M.face_start[f + 1] - M.face_start[f], 3);
    const uint32_t *k = M.corner + M.face_start[f];
    cr_assert(k[0] == a && k[1] == b && k[2] == c, "face %u: %u %u %u, wanted %u %u %u", f, k[0],
              k[1], k[2], a, b, c);
}

/* ==== Binary ==== */

Test(stl, binary_merges_equal_vertices)
{
    Buf b = square("made by a test", 0, 0);
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "stl binary");
    cr_assert_eq(M.nfaces, 2);
    cr_assert_eq(M.info.triangles, 2);
    cr_assert_eq(M.nverts, 4, "shared corners are merged");
    cr_assert_eq(M.info.corners_read, 6);
    expect_corners(0, 0, 1, 2);
    expect_corners(1, 1, 3, 2);
    cr_assert_eq(M.pos[9], 1.0f);
    cr_assert_eq(M.pos[10], 1.0f);
    cr_assert_eq(mesh_face_mat(&M, 0), -1);
    cr_assert_eq(M.nmats, 0);
    cr_assert_null(M.rgb);
    cr_assert_eq(M.nobjs, 1);
    cr_assert_str_eq(M.objs[0].name, "t");
    cr_assert_eq(M.objs[0].vert_max, 3);
    free(b.b);
}

Test(stl, binary_that_starts_with_solid)
{
    /* The size, 84 + 50 n, says binary whatever the header says. */
    Buf b = square("solid cube exported by a CAD program", 0, 0);
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "stl binary");
    cr_assert_eq(M.nfaces, 2);
    free(b.b);
}

Test(stl, merge_is_by_exact_bits)
{
    Buf b = { 0 };
    header(&b, "", 2);
    const float a[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    const float z[9] = { -0.0f, 0, 0, 1, 0, 0, 0, 1, 0 };   /* -0 is another pattern */
    tri(&b, a, 0);
    tri(&b, z, 0);
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    cr_assert_eq(M.nverts, 4);
    expect_corners(1, 3, 1, 2);
    free(b.b);
}

Test(stl, many_triangles_grow_the_merge_table)
{
    /* a triangle soup bigger than the first guess: nothing shared */
    enum { N = 5000 };
    Buf b = { 0 };
    header(&b, "", N);
    for (int i = 0; i < N; i++) {
        float v[9] = { (float)i, 0, 0, (float)i, 1, 0, (float)i, 0, 1 };
        tri(&b, v, 0);
    }
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    cr_assert_eq(M.nverts, 3 * N);
    cr_assert_eq(M.pos[3 * (3 * N - 1)], (float)(N - 1));
    expect_corners(N - 1, 3 * N - 3, 3 * N - 2, 3 * N - 1);
    free(b.b);
}

Test(stl, viscam_face_colours)
{
    /* bit 15 = valid; red in bits 10-14, green 5-9, blue 0-4 */
    Buf b = square("", 0x8000 | 31 << 10, 0);
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    cr_assert_eq(M.nmats, 1);
    cr_assert_eq(mesh_face_mat(&M, 0), 0);
    cr_assert_eq(mesh_face_mat(&M, 1), -1, "bit 15 clear: no colour");
    cr_assert_eq(M.mats[0].kd[0], 1.0f);
    cr_assert_eq(M.mats[0].kd[1], 0.0f);
    cr_assert_eq(M.mats[0].kd[2], 0.0f);
    cr_assert_str_eq(M.mats[0].name, "#ff0000");
    free(b.b);
}

Test(stl, viscam_equal_colours_share_a_material)
{
    Buf b = square("", 0x8000 | 16 << 5, 0x8000 | 16 << 5);
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    cr_assert_eq(M.nmats, 1);
    cr_assert_eq(mesh_face_mat(&M, 0), mesh_face_mat(&M, 1));
    cr_assert_float_eq(M.mats[0].kd[1], 132 / 255.0f, 1e-6);   /* 16 of 31 -> 132 */
    free(b.b);
}

Test(stl, materialise_part_and_face_colours)
{
    /* "COLOR=" R G B A: the part colour; bit 15 set = use it, clear =
     * the face's own colour with red in the LOW bits */
    static const char head[] = "COLOR=\x00\x00\xff\xff rest of header";
    Buf b = { 0 };
    header_n(&b, head, sizeof head - 1, 2);
    tri(&b, T0, 0x8000);
    tri(&b, T1, 31);
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    cr_assert_eq(M.nmats, 2);
    const Material *part = &M.mats[mesh_face_mat(&M, 0)], *own = &M.mats[mesh_face_mat(&M, 1)];
    cr_assert_eq(part->kd[2], 1.0f);
    cr_assert_eq(part->kd[0], 0.0f);
    cr_assert_eq(own->kd[0], 1.0f);
    cr_assert_eq(own->kd[2], 0.0f);
    free(b.b);
}

Test(stl, error_truncated)
{
    Buf b = square("", 0, 0);
    cr_assert_eq(parse(b.b, b.n - 10), -1);
    cr_assert_str_eq(E, "t.stl: byte 134: file ends inside triangle 2 of 2 (2 triangles need "
                        "184 bytes, the file has 174)");
    cr_assert_null(M.pos);
    cr_assert_eq(M.nfaces, 0);
    free(b.b);
}

Test(stl, error_count_past_the_end_allocates_nothing)
{
    /* 4 billion triangles claimed in a 184-byte file */
    Buf b = square("", 0, 0);
    b.b[80] = b.b[81] = b.b[82] = b.b[83] = 0xff;
    cr_assert_eq(parse_fmt("t.stl", "stl", b.b, b.n), -1);
    cr_assert_not_null(strstr(E, "4294967295 triangles need 214748364834 bytes"), "%s", E);
    free(b.b);
}

Test(stl, error_nan_and_inf)
{
    Buf b = square("", 0, 0);
    float nan = __builtin_nanf("");
    memcpy(b.b + 84 + 50 + 12 + 4 * 4, &nan, 4);   /* second triangle, corner 2 y */
    cr_assert_eq(parse(b.b, b.n), -1);
    cr_assert_str_eq(E, "t.stl: byte 162: NaN or infinite coordinate (triangle 2)");
    float inf = __builtin_inff();
    memcpy(b.b + 84 + 50 + 12 + 4 * 4, &inf, 4);
    cr_assert_eq(parse(b.b, b.n), -1);
    cr_assert_not_null(strstr(E, "NaN or infinite"), "%s", E);
    free(b.b);
}

Test(stl, nan_normals_are_ignored)
{
    Buf b = square("", 0, 0);
    float nan = __builtin_nanf("");
    memcpy(b.b + 84, &nan, 4);
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    free(b.b);
}

Test(stl, error_zero_triangles)
{
    Buf b = { 0 };
    header(&b, "", 0);
    cr_assert_eq(parse(b.b, b.n), -1);
    cr_assert_str_eq(E, "t.stl: no faces (a binary STL of 0 triangles)");
    free(b.b);
}

Test(stl, error_too_short)
{
    cr_assert_eq(parse_fmt("t.stl", "stl", "\x01\x02\x03", 3), -1);
    cr_assert_not_null(strstr(E, "too short for a binary STL"), "%s", E);
}

Test(stl, trailing_bytes_warn, .init = cr_redirect_stderr)
{
    Buf b = square("", 0, 0);
    put(&b, "\0\0\0", 3);
    cr_assert_eq(parse_fmt("t.stl", "stl", b.b, b.n), 0, "%s", E);
    cr_assert_eq(M.nfaces, 2);
    fflush(stderr);
    cr_assert_stderr_eq_str("zview: warning: t.stl: 3 bytes after the last of 2 triangles ignored\n");
    free(b.b);
}

Test(stl, a_count_short_by_a_whole_triangle_is_refused, .init = cr_redirect_stderr)
{
    /* 84 + 50 n bytes hold n triangles: a header that says 1 over 2
     * triangles' bytes is wrong, not trailing junk; 49 bytes more than
     * the count still are junk (a warning, the triangle kept) */
    Buf b = square("", 0, 0);
    b.b[80] = 1;
    cr_assert_eq(parse_fmt("t.stl", "stl", b.b, b.n), -1, "loaded %u faces", M.nfaces);
    cr_assert_str_eq(E, "t.stl: the header's count, 1 triangles, makes 134 bytes; the file has 184");
    cr_assert_null(M.pos);
    cr_assert_eq(parse_fmt("t.stl", "stl", b.b, b.n - 1), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    fflush(stderr);
    cr_assert_stderr_eq_str("zview: warning: t.stl: 49 bytes after the last of 1 triangles ignored\n");
    free(b.b);
}

Test(stl, every_prefix_fails_cleanly)
{
    Buf b = square("", 0x8000 | 7, 0);
    for (size_t n = 0; n < b.n; n++) {
        cr_assert_eq(parse_fmt("t.stl", "stl", b.b, n), -1, "prefix %zu", n);
        cr_assert_null(M.pos);
    }
    free(b.b);
}

/* ==== ASCII ==== */

static const char ascii2[] =
    "solid part\n"
    "  facet normal 0 0 1\n"
    "    outer loop\n"
    "      vertex 0 0 0\n"
    "      vertex 1 0 0\n"
    "      vertex 0 1 0\n"
    "    endloop\n"
    "  endfacet\n"
    "  facet normal 0 0 1\n"
    "    outer loop\n"
    "      vertex 1 0 0\n"
    "      vertex 1 1 0\n"
    "      vertex 0 1 0\n"
    "    endloop\n"
    "  endfacet\n"
    "endsolid part\n";

static int parse_text(const char *s) { return parse(s, strlen(s)); }

static void expect_err(const char *s, const char *want)
{
    cr_assert_eq(parse_text(s), -1, "expected an error for:\n%s", s);
    cr_assert_not_null(strstr(E, want), "error '%s' lacks '%s'", E, want);
    cr_assert_null(M.pos);
}

Test(stl, ascii_basic)
{
    cr_assert_eq(parse_text(ascii2), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "stl ascii");
    cr_assert_eq(M.nverts, 4);
    cr_assert_eq(M.nfaces, 2);
    cr_assert_eq(M.info.corners_read, 6);
    expect_corners(0, 0, 1, 2);
    expect_corners(1, 1, 3, 2);
    cr_assert_eq(M.nobjs, 1);
    cr_assert_str_eq(M.objs[0].name, "part");
}

Test(stl, ascii_and_binary_agree)
{
    cr_assert_eq(parse_text(ascii2), 0, "%s", E);
    Mesh a = M;
    memset(&M, 0, sizeof M);
    Buf b = square("", 0, 0);
    cr_assert_eq(parse(b.b, b.n), 0, "%s", E);
    cr_assert_eq(a.nverts, M.nverts);
    cr_assert_eq(memcmp(a.pos, M.pos, 12 * a.nverts), 0);
    cr_assert_eq(memcmp(a.corner, M.corner, 4 * 6), 0);
    mesh_free(&a);
    free(b.b);
}

Test(stl, ascii_case_blanks_and_line_ends)
{
    /* upper case, tabs, CRLF, no final endsolid, exponents */
    cr_assert_eq(parse_text("SOLID x\r\nFACET NORMAL 0 0 1\r\nOUTER LOOP\r\n\tVERTEX 0 0 0\r\n"
                            "VERTEX 1e0 0 0\r\nVERTEX 0 1.0E+00 0\r\nENDLOOP\r\nENDFACET\r\n"), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_eq(M.pos[3], 1.0f);
    cr_assert_eq(M.pos[7], 1.0f);
    /* old-Mac CR-only line ends */
    cr_assert_eq(parse_text("solid x\rfacet normal 0 0 1\router loop\rvertex 0 0 0\rvertex 1 0 0\r"
                            "vertex 0 1 0\rendloop\rendfacet\rendsolid\r"), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
}

Test(stl, ascii_solids_are_objects)
{
    cr_assert_eq(parse_text("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                            "vertex 0 1 0\nendloop\nendfacet\nendsolid a\nsolid\nfacet normal 0 0 1\n"
                            "outer loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
                            "endsolid\n"), 0, "%s", E);
    cr_assert_eq(M.nobjs, 2);
    cr_assert_str_eq(M.objs[0].name, "a");
    cr_assert_str_eq(M.objs[1].name, "t", "an unnamed solid: the file's name");
    cr_assert_eq(M.objs[1].face_first, 1);
    cr_assert_eq(M.nverts, 4);
}

Test(stl, ascii_polygon_loops)
{
    cr_assert_eq(parse_text("solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                            "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n"), 0, "%s", E);
    cr_assert_eq(M.face_start[1], 4);
    cr_assert_eq(M.info.triangles, 2);
}

Test(stl, ascii_errors)
{
    expect_err("solid\nvertex 0 0 0\n", "t.stl:2: vertex outside a facet");
    expect_err("solid\nfacet normal 0 0 1\nouter loop\nvertex 0 nan 0\n", "t.stl:4: NaN or infinite number 'nan'");
    expect_err("solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 1e39\n", "t.stl:4: number out of range");
    expect_err("solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0,5 0\n", "t.stl:4: malformed number '0,5'");
    expect_err("solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n", "t.stl:4: vertex needs x y z, got 2 numbers");
    expect_err("solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0 0\n", "t.stl:4: vertex has more than x y z");
    expect_err("solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n",
               "t.stl:2: facet has fewer than 3 vertices (2)");
    expect_err("solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n",
               "t.stl:2: file ends inside this facet");
    expect_err("solid\nfacet normal 0 0 1\nfacet normal 0 0 1\n", "t.stl:3: facet inside a facet");
    expect_err("solid\nfacets 1\n", "t.stl:2: unknown statement 'facets'");
    expect_err("solid x\nendsolid x\n", "t.stl: no faces");
    expect_err("solid x\nfacet normal 0 0 1\x01\n", "binary or unreadable");
}

Test(stl, ascii_every_prefix_loads_or_is_refused_by_name)
{
    /* each prefix either loads a mesh that keeps every loader promise
     * (at most the file's two triangles), or is refused with a message
     * naming the file and nothing left behind */
    size_t n = strlen(ascii2);
    int loaded = 0, refused = 0;
    for (size_t k = 0; k <= n; k++) {
        int r = parse_fmt("t.stl", "stl", ascii2, k);
        const char *broken = tl_load_broken(r, &M, E, "t.stl");
        cr_assert_null(broken, "the first %zu bytes: '%s' does not hold (status %d, '%s')", k, broken, r, E);
        if (r == 0)
            cr_assert_leq(M.nfaces, 2);
        if (k == n)
            cr_assert(r == 0 && M.nfaces == 2, "the whole file: %s", E);
        loaded += r == 0;
        refused += r != 0;
        mesh_free(&M);
    }
    cr_assert_gt(refused, 0);
    cr_assert_gt(loaded, 0);
}

/* ==== Detection ==== */

Test(stl, detected_by_content_whatever_the_name)
{
    Buf b = square("", 0, 0);
    cr_assert_eq(parse_fmt("model.dat", NULL, b.b, b.n), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "stl binary");
    cr_assert_eq(parse_fmt("model.obj", NULL, ascii2, strlen(ascii2)), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "stl ascii");
    free(b.b);
}
