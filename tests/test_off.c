/* test_off.c: the OFF loader and its variants (COFF, NOFF, 4OFF, nOFF,
 * no keyword at all): extra columns skipped, colours read, comments,
 * and every bad input. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "testlib.h"

static Mesh M;
static char E[512];

static void teardown(void) { mesh_free(&M); }
TestSuite(off, .fini = teardown);

static int parse_as(const char *path, const char *s)
{
    size_t n = strlen(s);
    char *buf = malloc(n ? n : 1);
    cr_assert_not_null(buf);
    memcpy(buf, s, n);
    mesh_free(&M);   /* a parse zeroes the mesh: free the last one */
    int r = mesh_parse_buffer(&M, path, NULL, buf, n, E, sizeof E);
    free(buf);
    return r;
}

static int parse(const char *s) { return parse_as("t.off", s); }

static void expect_err(const char *s, const char *want)
{
    cr_assert_eq(parse(s), -1, "expected an error for:\n%s", s);
    cr_assert_not_null(strstr(E, want), "error '%s' lacks '%s'", E, want);
    cr_assert_null(M.pos);
}

static void expect_corners(uint32_t f, const uint32_t *want, uint32_t n)
{
    cr_assert_eq(M.face_start[f + 1] - M.face_start[f], n, "face %u corner count", f);
    for (uint32_t i = 0; i < n; i++)
        cr_assert_eq(M.corner[M.face_start[f] + i], want[i], "face %u corner %u", f, i);
}

Test(off, basic)
{
    cr_assert_eq(parse("OFF\n# a comment\n4 2 5\n0 0 0\n1 0 0\n1 1 0 # trailing\n0 1 0\n\n"
                       "3 0 1 3\n4 0 1 2 3\n"), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "off");
    cr_assert_eq(M.nverts, 4);
    cr_assert_eq(M.nfaces, 2);
    cr_assert_eq(M.info.triangles, 3);
    expect_corners(0, (uint32_t[]){ 0, 1, 3 }, 3);
    expect_corners(1, (uint32_t[]){ 0, 1, 2, 3 }, 4);
    cr_assert_eq(M.pos[6], 1.0f);
    cr_assert_null(M.rgb);
    cr_assert_eq(mesh_face_mat(&M, 0), -1);
}

Test(off, counts_on_the_keyword_line_and_no_keyword)
{
    cr_assert_eq(parse("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    /* the keyword is optional: a .off file starting with the counts */
    cr_assert_eq(parse("3 1\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n"), 0, "%s", E);
    expect_corners(0, (uint32_t[]){ 2, 1, 0 }, 3);
}

Test(off, noff_and_st_columns_skipped)
{
    cr_assert_eq(parse("STNOFF\n3 1 0\n0 0 0 0 0 1 0.5 0.5\n1 0 0 0 0 1 1 0\n0 1 0 0 0 1 0 1\n"
                       "3 0 1 2\n"), 0, "%s", E);
    cr_assert_eq(M.pos[3], 1.0f);
    cr_assert_eq(M.pos[7], 1.0f);
    cr_assert_str_eq(M.info.format, "off (STNOFF)");
}

Test(off, coff_vertex_colours_ints_and_floats)
{
    cr_assert_eq(parse("COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0\n0 1 0 0.0 0.5 1.0 1.0\n"
                       "3 0 1 2\n"), 0, "%s", E);
    cr_assert_not_null(M.rgb);
    cr_assert_eq(M.rgb[0], 1.0f);
    cr_assert_eq(M.rgb[1], 0.0f);
    cr_assert_eq(M.rgb[4], 1.0f, "integers are 0..255");
    cr_assert_eq(M.rgb[7], 0.5f, "floats are 0..1");
    cr_assert_eq(M.rgb[8], 1.0f);
}

Test(off, cnoff_colour_after_the_normal)
{
    cr_assert_eq(parse("CNOFF\n3 1 0\n0 0 0 0 0 1 255 0 0 255\n1 0 0 0 0 1 0 255 0 255\n"
                       "0 1 0 0 0 1 0 0 255 255\n3 0 1 2\n"), 0, "%s", E);
    cr_assert_eq(M.rgb[0], 1.0f);
    cr_assert_eq(M.rgb[2], 0.0f);
    cr_assert_eq(M.rgb[8], 1.0f);
}

Test(off, face_colours)
{
    cr_assert_eq(parse("OFF\n4 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 255 0 0\n3 0 2 3 1.0 0.0 0.0 0.5\n"
                       "3 0 1 3 7\n"), 0, "%s", E);
    cr_assert_eq(M.nmats, 1, "equal colours share a material");
    cr_assert_eq(mesh_face_mat(&M, 0), 0);
    cr_assert_eq(mesh_face_mat(&M, 1), 0);
    cr_assert_eq(mesh_face_mat(&M, 2), -1, "a colour-map index is skipped");
    cr_assert_eq(M.mats[0].kd[0], 1.0f);
}

Test(off, four_d_divides_by_w)
{
    cr_assert_eq(parse("4OFF\n3 1 0\n0 0 0 1\n2 0 0 2\n0 3 0 3\n3 0 1 2\n"), 0, "%s", E);
    cr_assert_eq(M.pos[3], 1.0f);
    cr_assert_eq(M.pos[7], 1.0f);
}

Test(off, line_ends)
{
    cr_assert_eq(parse("OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n"), 0, "%s", E);
    cr_assert_eq(parse("OFF\r3 1 0\r0 0 0\r1 0 0\r0 1 0\r3 0 1 2\r"), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
}

Test(off, errors)
{
    expect_err("OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "t.off:4: NaN or infinite number 'nan'");
    expect_err("OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", "t.off:4: vertex needs x y z, got 2 numbers");
    expect_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "t.off:6: vertex index 3 out of range (3 vertices)");
    expect_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "t.off:6: vertex index -1 out of range");
    expect_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "t.off:6: face has 2 vertices (at least 3)");
    expect_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "t.off:6: face of 4 vertices lists 3");
    expect_err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2x\n", "t.off:6: face: malformed number '2x'");
    expect_err("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "file ends early (3 vertices and 2 faces stated");
    expect_err("OFF\nthree 1 0\n", "t.off:2: bad count 'three'");
    expect_err("OFF\n3\n", "t.off:2: expected the counts");
    expect_err("OFF BINARY\n3 1 0\n", "binary OFF is not read");
    expect_err("nOFF\n4\n3 1 0\n", "only 3-dimensional nOFF files are read");
    expect_err("", "no faces (empty file)");
    expect_err("# a comment\n\n", "no faces (only comments and blank lines)");
    expect_err("OFF\n0 0 0\n", "no faces and no vertices in its 10 bytes");
    /* counts checked against the size before anything is allocated */
    expect_err("OFF\n4000000000 1 0\n0 0 0\n", "4000000000 vertices and 1 faces cannot fit in the 6 bytes left");
    expect_err("OFF\n99999999999999999999 1 0\n", "bad count '99999999999999999999'");
}

Test(off, every_prefix_loads_or_is_refused_by_name)
{
    /* each prefix of a good file either loads a mesh that keeps every
     * loader promise, or is refused with a message naming the file and
     * nothing left behind; the whole file loads what it says */
    const char *s = "COFF\n# c\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 1 1 1 1\n1 1 0 0 0 0 0\n0 1 0 9 9 9 9\n"
                    "3 0 1 3 1 0 0\n4 0 1 2 3\n";
    size_t n = strlen(s);
    int loaded = 0, refused = 0;
    for (size_t k = 0; k <= n; k++) {
        char *buf = malloc(k ? k : 1);
        memcpy(buf, s, k);
        int r = mesh_parse_buffer(&M, "t.off", "off", buf, k, E, sizeof E);
        const char *broken = tl_load_broken(r, &M, E, "t.off");
        cr_assert_null(broken, "the first %zu bytes: '%s' does not hold (status %d, '%s')", k, broken, r, E);
        if (k == n) {
            cr_assert_eq(r, 0, "%s", E);
            cr_assert_eq(M.nverts, 4);
            cr_assert_eq(M.nfaces, 2);
        }
        loaded += r == 0;
        refused += r != 0;
        mesh_free(&M);
        free(buf);
    }
    cr_assert_gt(refused, 0);
    cr_assert_gt(loaded, 0);
}
