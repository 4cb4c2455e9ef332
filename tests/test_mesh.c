/* test_mesh.c: the OBJ/MTL loader. Most cases parse in-memory text with
 * mesh_parse (path "t.obj"); files under tests/data/mesh cover what
 * needs a real file system; the shared models, when present, are
 * checked against the counts in their README. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mesh.h"
#include "../src/mesh/mesh_internal.h"

#define MODELS "../shared/models"

static Mesh M;
static char E[512];

/* Parse `s` from an exactly sized heap copy, so that a read past the
 * end shows up under AddressSanitizer. */
static int parse_as(const char *path, const char *s, size_t n)
{
    char *buf = malloc(n ? n : 1);
    cr_assert_not_null(buf);
    memcpy(buf, s, n);
    int r = mesh_parse(&M, path, buf, n, E, sizeof E);
    free(buf);
    return r;
}

static int parse(const char *s) { return parse_as("t.obj", s, strlen(s)); }

static void teardown(void) { mesh_free(&M); }

TestSuite(mesh, .fini = teardown);

static void expect_ok(const char *s)
{
    int r = parse(s);
    cr_assert_eq(r, 0, "parse failed: %s", E);
}

/* The error names "t.obj:<line>: " and contains `phrase`; the mesh is
 * left empty. */
static void expect_err(const char *s, int line, const char *phrase)
{
    char prefix[64];
    cr_assert_eq(parse(s), -1, "expected an error for:\n%s", s);
    snprintf(prefix, sizeof prefix, "t.obj:%d: ", line);
    cr_assert_eq(strncmp(E, prefix, strlen(prefix)), 0, "error '%s' does not start with '%s'",
                 E, prefix);
    cr_assert_not_null(strstr(E, phrase), "error '%s' lacks '%s'", E, phrase);
    cr_assert_eq(M.nverts, 0);
    cr_assert_eq(M.nfaces, 0);
    cr_assert_null(M.pos);
    cr_assert_null(M.objs);
    cr_assert_null(M.path);
}

static void expect_corners(uint32_t face, const uint32_t *want, uint32_t n)
{
    cr_assert_lt(face, M.nfaces);
    cr_assert_eq(M.face_start[face + 1] - M.face_start[face], n, "face %u corner count", face);
    for (uint32_t i = 0; i < n; i++)
        cr_assert_eq(M.corner[M.face_start[face] + i], want[i], "face %u corner %u: %u != %u",
                     face, i, M.corner[M.face_start[face] + i], want[i]);
}

/* ==== Basic statements ==== */

Test(mesh, triangle)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    cr_assert_eq(M.nverts, 3);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_eq(M.face_start[0], 0);
    cr_assert_eq(M.face_start[1], 3);
    expect_corners(0, (uint32_t[]){0, 1, 2}, 3);
    cr_assert_float_eq(M.pos[3], 1.0f, 0.0f);
    cr_assert_float_eq(M.pos[7], 1.0f, 0.0f);
    cr_assert_null(M.rgb);
    cr_assert_eq(mesh_face_mat(&M, 0), -1);
    cr_assert_eq(M.nmats, 0);
    cr_assert_eq(M.nobjs, 1);
    cr_assert_str_eq(M.objs[0].name, "t");
    cr_assert_str_eq(M.path, "t.obj");
    cr_assert_eq(M.info.triangles, 1);
    cr_assert_eq(M.info.bytes, strlen("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    cr_assert_geq(M.info.load_ms, 0.0);
}

Test(mesh, coordinates_exact)
{
    expect_ok("v -1.5 2.25e2 +3E-1\nv .5 5. -0.000123456789\nv 123456789012345678901234 1e-38 -7\n"
              "f 1 2 3\n");
    cr_assert_eq(M.pos[0], -1.5f);
    cr_assert_eq(M.pos[1], 225.0f);
    cr_assert_eq(M.pos[2], 0.3f);
    cr_assert_eq(M.pos[3], 0.5f);
    cr_assert_eq(M.pos[4], 5.0f);
    cr_assert_eq(M.pos[5], -0.000123456789f);
    cr_assert_eq(M.pos[6], 123456789012345678901234.0f);
    cr_assert_eq(M.pos[7], 1e-38f);
    cr_assert_eq(M.pos[8], -7.0f);
}

Test(mesh, vertex_w)
{
    expect_ok("v 2 4 6 2\nv 1 2 3 0\nv 1 1 1 1\nf 1 2 3\n");
    cr_assert_eq(M.pos[0], 1.0f);
    cr_assert_eq(M.pos[1], 2.0f);
    cr_assert_eq(M.pos[2], 3.0f);
    /* w = 0 is left alone rather than dividing by zero */
    cr_assert_eq(M.pos[3], 1.0f);
    cr_assert_eq(M.pos[5], 3.0f);
    cr_assert_null(M.rgb);
}

Test(mesh, vertex_colours_mixed)
{
    expect_ok("v 0 0 0\nv 1 0 0 0.5 0.25 0\nv 0 1 0\nf 1 2 3\n");
    cr_assert_not_null(M.rgb);
    float want[9] = {1, 1, 1, 0.5f, 0.25f, 0, 1, 1, 1};
    for (int i = 0; i < 9; i++)
        cr_assert_eq(M.rgb[i], want[i], "rgb[%d] = %g", i, M.rgb[i]);
    cr_assert_eq(M.pos[3], 1.0f);
    cr_assert_eq(M.pos[4], 0.0f);
}

Test(mesh, vertex_colours_grow)
{
    /* Colours first seen after the arrays have grown several times. */
    char *s = malloc(64 * 2000 + 64);
    size_t n = 0;
    for (int i = 0; i < 2000; i++)
        n += (size_t)sprintf(s + n, i == 1500 ? "v %d 0 0 0 1 0\n" : "v %d 0 0\n", i);
    n += (size_t)sprintf(s + n, "f 1 2 2000\n");
    cr_assert_eq(parse_as("t.obj", s, n), 0, "%s", E);
    free(s);
    cr_assert_eq(M.nverts, 2000);
    cr_assert_eq(M.pos[3 * 1999], 1999.0f);
    cr_assert_eq(M.rgb[3 * 1500 + 0], 0.0f);
    cr_assert_eq(M.rgb[3 * 1500 + 1], 1.0f);
    cr_assert_eq(M.rgb[3 * 1499 + 0], 1.0f);
    cr_assert_eq(M.rgb[3 * 1999 + 2], 1.0f);
}

Test(mesh, texcoords_and_normals_counted)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1 0\nvn 0 0 1\nf 1 2 3\n");
    cr_assert_eq(M.info.texcoords, 3);
    cr_assert_eq(M.info.normals, 1);
    cr_assert_eq(M.nverts, 3);
}

Test(mesh, face_forms)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
              "f 1 2 3\nf 1/1 2/1 3/1\nf 1//1 3//1 4//1\nf 4/1/1 3/1/1 2/1/1 1/1/1\n");
    cr_assert_eq(M.nfaces, 4);
    expect_corners(0, (uint32_t[]){0, 1, 2}, 3);
    expect_corners(1, (uint32_t[]){0, 1, 2}, 3);
    expect_corners(2, (uint32_t[]){0, 2, 3}, 3);
    expect_corners(3, (uint32_t[]){3, 2, 1, 0}, 4);
    cr_assert_eq(M.face_start[4], 13);
    cr_assert_eq(M.info.triangles, 5);
}

Test(mesh, negative_indices_relative_to_point_in_file)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
              "v 5 5 5\nf -1/-1 -2//-1 -4/1/-1\nf 1 -1 -2\n");
    cr_assert_eq(M.nverts, 4);
    expect_corners(0, (uint32_t[]){0, 1, 2}, 3);
    expect_corners(1, (uint32_t[]){3, 2, 0}, 3);
    expect_corners(2, (uint32_t[]){0, 3, 2}, 3);
}

Test(mesh, polygon_any_size)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nv 0 0 1\nv 0 0 2\n"
              "f 1 2 3 4 5 6 7\nf 1 2 3\n");
    cr_assert_eq(M.nfaces, 2);
    expect_corners(0, (uint32_t[]){0, 1, 2, 3, 4, 5, 6}, 7);
    cr_assert_eq(M.info.triangles, 6);
}

Test(mesh, forward_reference_allowed)
{
    /* A positive index may name a vertex defined later in the file. */
    expect_ok("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n");
    expect_corners(0, (uint32_t[]){0, 1, 2}, 3);
}

/* ==== Objects, groups, materials ==== */

Test(mesh, default_object_named_after_file)
{
    cr_assert_eq(parse_as("some/dir/My Model.v2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3",
                          strlen("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3")), 0, "%s", E);
    cr_assert_eq(M.nobjs, 1);
    cr_assert_str_eq(M.objs[0].name, "My Model.v2");
    cr_assert_eq(M.objs[0].face_first, 0);
    cr_assert_eq(M.objs[0].face_count, 1);
}

Test(mesh, objects_split_faces)
{
    expect_ok("o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n"
              "o empty\n"
              "o second one \nv 2 2 2\nv 3 2 2\nv 2 3 2\nf 5 6 7\n"
              "o trailing_empty\n");
    cr_assert_eq(M.nobjs, 2);
    cr_assert_str_eq(M.objs[0].name, "first");
    cr_assert_eq(M.objs[0].face_first, 0);
    cr_assert_eq(M.objs[0].face_count, 2);
    cr_assert_eq(M.objs[0].vert_min, 0);
    cr_assert_eq(M.objs[0].vert_max, 3);
    cr_assert_str_eq(M.objs[1].name, "second one");
    cr_assert_eq(M.objs[1].face_first, 2);
    cr_assert_eq(M.objs[1].face_count, 1);
    cr_assert_eq(M.objs[1].vert_min, 4);
    cr_assert_eq(M.objs[1].vert_max, 6);
}

Test(mesh, faces_before_first_o_keep_default_object)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no named\nf 3 2 1\nf 1 3 2\n");
    cr_assert_eq(M.nobjs, 2);
    cr_assert_str_eq(M.objs[0].name, "t");
    cr_assert_eq(M.objs[0].face_count, 1);
    cr_assert_str_eq(M.objs[1].name, "named");
    cr_assert_eq(M.objs[1].face_first, 1);
    cr_assert_eq(M.objs[1].face_count, 2);
}

Test(mesh, long_object_name_truncated)
{
    char s[400];
    char name[200];
    memset(name, 'n', sizeof name - 1);
    name[sizeof name - 1] = '\0';
    snprintf(s, sizeof s, "o %s\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", name);
    expect_ok(s);
    cr_assert_eq(strlen(M.objs[0].name), MESH_NAME_MAX - 1);
}

Test(mesh, groups_counted_smoothing_ignored)
{
    expect_ok("g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\ns 1\ng b c\nf 1 2 3\ns off\ng\n");
    cr_assert_eq(M.info.groups, 3);
    cr_assert_eq(M.info.unknown, 0);
    cr_assert_eq(M.nobjs, 1);
}

Test(mesh, usemtl_without_library_is_default)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl red\nf 1 2 3\nusemtl\nf 3 2 1\n");
    cr_assert_eq(M.nmats, 0);
    cr_assert_eq(mesh_face_mat(&M, 0), -1);
    cr_assert_eq(mesh_face_mat(&M, 1), -1);
    cr_assert_eq(mesh_face_mat(&M, 2), -1);
}

Test(mesh, mtllib_relative_to_obj_folder, .init = cr_redirect_stderr)
{
    const char *path = "tests/data/mesh/materials.obj";
    cr_assert_eq(mesh_load(&M, path, E, sizeof E), 0, "%s", E);
    cr_assert_eq(M.nmats, 5);
    cr_assert_str_eq(M.mats[0].name, "red");
    cr_assert_eq(M.mats[0].kd[0], 1.0f);
    cr_assert_eq(M.mats[0].kd[1], 0.0f);
    cr_assert_eq(M.mats[0].alpha, 0.5f);
    cr_assert_str_eq(M.mats[1].name, "green");
    cr_assert_eq(M.mats[1].kd[1], 1.0f);
    cr_assert_eq(M.mats[1].alpha, 0.75f);            /* 1 - Tr */
    cr_assert_str_eq(M.mats[2].name, "nokd");
    for (int i = 0; i < 3; i++)
        cr_assert_eq(M.mats[2].kd[i], 0.8f);
    cr_assert_eq(M.mats[2].alpha, 1.0f);
    cr_assert_str_eq(M.mats[3].name, "both");
    cr_assert_eq(M.mats[3].kd[2], 0.6f);
    cr_assert_eq(M.mats[3].alpha, 0.3f);             /* d wins over Tr */
    cr_assert_str_eq(M.mats[4].name, "blue");        /* from extra/more.mtl */
    cr_assert_eq(M.mats[4].kd[2], 1.0f);
    int32_t want[6] = {0, 4, 2, -1, 1, 3};
    cr_assert_eq(M.nfaces, 6);
    for (int i = 0; i < 6; i++)
        cr_assert_eq(mesh_face_mat(&M, i), want[i], "face_mat[%d] = %d", i, mesh_face_mat(&M, i));
    cr_assert_eq(M.info.triangles, 7);
    fflush(stderr);
    cr_assert_stderr_eq_str(
        "zview: warning: tests/data/mesh/materials.obj:14: unknown material 'nosuch'\n");
}

Test(mesh, missing_mtl_is_a_warning, .init = cr_redirect_stderr)
{
    const char *path = "tests/data/mesh/missing_mtl.obj";
    cr_assert_eq(mesh_load(&M, path, E, sizeof E), 0, "%s", E);
    cr_assert_eq(M.nmats, 0);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_eq(mesh_face_mat(&M, 0), -1);
    cr_assert_str_eq(M.objs[0].name, "missing_mtl");
    fflush(stderr);
    cr_assert_stderr_eq_str("zview: warning: tests/data/mesh/missing_mtl.obj:2: "
                            "cannot open material library 'nothere.mtl' "
                            "(cannot open: No such file or directory)\n");
}

Test(mesh, mtllib_from_parse_uses_path_folder, .init = cr_redirect_stderr)
{
    const char *s = "mtllib colors.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl green\nf 1 2 3\n";
    cr_assert_eq(parse_as("tests/data/mesh/inline.obj", s, strlen(s)), 0, "%s", E);
    cr_assert_eq(M.nmats, 4);
    cr_assert_eq(mesh_face_mat(&M, 0), 1);
    fflush(stderr);
    cr_assert_stderr_eq_str("");
}

/* ==== Lexical details ==== */

Test(mesh, comments_blank_lines_and_tabs)
{
    expect_ok("# header\n\n   \n\tv\t0 0 0 # trailing\nv 1\t0 0\n  v 0 1 0\n#f 9 9 9\n"
              "f\t1  2\t\t3 # tri\n");
    cr_assert_eq(M.nverts, 3);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_eq(M.pos[3], 1.0f);
}

Test(mesh, crlf_line_ends)
{
    expect_ok("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\no crlf\r\nf 1 2 3\r\n");
    cr_assert_eq(M.nfaces, 1);
    cr_assert_str_eq(M.objs[0].name, "crlf");
    expect_corners(0, (uint32_t[]){0, 1, 2}, 3);
}

Test(mesh, missing_final_newline)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3");
    cr_assert_eq(M.nfaces, 1);
    expect_corners(0, (uint32_t[]){0, 1, 2}, 3);
}

Test(mesh, utf8_bom_skipped)
{
    expect_ok("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    cr_assert_eq(M.nverts, 3);
}

Test(mesh, line_continuation)
{
    expect_ok("v 0 0 0\nv 1 \\\n 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 \\\r\n3 \\\n4\nf 1 2 3\n");
    cr_assert_eq(M.nverts, 4);
    cr_assert_eq(M.nfaces, 2);
    expect_corners(0, (uint32_t[]){0, 1, 2, 3}, 4);
    cr_assert_eq(M.pos[3], 1.0f);
    cr_assert_eq(M.pos[4], 0.0f);
}

Test(mesh, continuation_keeps_line_numbers)
{
    /* The joined statement reports its first line; later lines count on. */
    expect_err("v 0 0 0\nv 1 \\\n0 0\nv 0 1 0\nf 1 2 \\\n9\n", 5, "index 9");
    expect_err("v 0 0 0\nv 1 \\\n0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n", 6, "fewer");
}

Test(mesh, unknown_statements_counted, .init = cr_redirect_stderr)
{
    /* free-form statements of the format (vp, cstype) are counted and
     * named in one warning, not errors, even when strict */
    expect_ok("v 0 0 0\nvp 0.5\nv 1 0 0\nv 0 1 0\ncstype bezier\nl 1 2\nf 1 2 3\nvp 1\np 1\n");
    cr_assert_eq(M.info.unknown, 3);
    cr_assert_eq(M.info.skipped, 0);
    /* points and polylines are kept beside the faces */
    cr_assert_eq(M.nlines, 1);
    cr_assert_eq(M.npoints, 1);
    cr_assert_str_eq(M.info.first_unknown, "vp");
    fflush(stderr);
    cr_assert_stderr_eq_str("zview: warning: t.obj: 3 free-form statements (curves, surfaces) not drawn, first 'vp'\n");
}

Test(mesh, first_unknown_truncated, .init = cr_redirect_stderr)
{
    /* a keyword the format does not have: strict refuses it, the
     * lenient load skips it and counts it */
    const char *s = "averyveryverylongkeywordthatgoesonandon 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    cr_assert_eq(parse(s), -1);
    cr_assert_eq(strncmp(E, "t.obj:1: unknown statement 'averyvery", 37), 0, "%s", E);
    MeshLoadOpts lenient = { .strict = 0 };
    cr_assert_eq(mesh_parse_buffer_ex(&M, "t.obj", &lenient, s, strlen(s), E, sizeof E), 0, "%s", E);
    cr_assert_eq(M.info.unknown, 1);
    cr_assert_eq(M.info.skipped, 1);
    cr_assert_eq(strlen(M.info.first_unknown), sizeof M.info.first_unknown - 1);
    cr_assert_eq(strncmp(M.info.first_unknown, "averyveryvery", 13), 0);
}

/* ==== Errors ==== */

Test(mesh, error_missing_file)
{
    const char *path = "tests/data/mesh/does-not-exist.obj";
    cr_assert_eq(mesh_load(&M, path, E, sizeof E), -1);
    cr_assert_str_eq(E, "tests/data/mesh/does-not-exist.obj: cannot open: No such file or directory");
    cr_assert_null(M.pos);
    cr_assert_null(M.path);
}

Test(mesh, error_directory)
{
    cr_assert_eq(mesh_load(&M, "tests/data/mesh", E, sizeof E), -1);
    cr_assert_str_eq(E, "tests/data/mesh: is a directory");
}

Test(mesh, error_empty_file)
{
    cr_assert_eq(mesh_load(&M, "tests/data/mesh/empty.obj", E, sizeof E), -1);
    cr_assert_eq(strncmp(E, "tests/data/mesh/empty.obj: no faces", 35), 0, "%s", E);
}

Test(mesh, error_no_faces)
{
    /* vertices alone are a point cloud now (see test_prims.c) */
    cr_assert_eq(parse("# only vertices\nv 0 0 0\nv 1 0 0\n"), 0, "%s", E);
    cr_assert_eq(M.npoints, 2);
    mesh_free(&M);
    cr_assert_eq(parse(""), -1);
    cr_assert_eq(strncmp(E, "t.obj: no faces", 15), 0, "%s", E);
    cr_assert_eq(parse("o a\no b\n"), -1);
    cr_assert_str_eq(E, "t.obj: no faces and no vertices in its 8 bytes", "not called empty");
    cr_assert_eq(parse("# a comment\n\n"), -1);
    cr_assert_str_eq(E, "t.obj: no faces and no vertices in its 13 bytes");
}

Test(mesh, error_index_zero)
{
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "index 0");
    cr_assert_not_null(strstr(E, "3 vertices"), "%s", E);
}

Test(mesh, error_index_out_of_range)
{
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n", 5, "vertex index 4 out of range");
    cr_assert_not_null(strstr(E, "(3 vertices)"), "%s", E);
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", 4, "out of range");
}

Test(mesh, error_negative_index_out_of_range)
{
    /* Relative to the vertices so far: -4 is too far back on line 4 even
     * though a fourth vertex follows. */
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\nv 1 1 1\n", 4,
               "vertex index -4 out of range");
    cr_assert_not_null(strstr(E, "3 vertices"), "%s", E);
}

Test(mesh, error_face_too_small)
{
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4, "fewer than 3");
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf\n", 4, "fewer than 3");
}

Test(mesh, error_nan_and_inf)
{
    expect_err("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", 2, "NaN or infinite");
    expect_err("v 0 0 -INF\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 1, "NaN or infinite");
    expect_err("v 0 0 0\nv 1 0 0\nv 0 infinity 0\nf 1 2 3\n", 3, "NaN or infinite");
    expect_err("v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", 2, "out of range");
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 NaN 1\nf 1 2 3\n", 4, "NaN or infinite");
}

Test(mesh, error_malformed_numbers)
{
    expect_err("v 0 0 0\nv 1.2.3 0 0\nv 0 1 0\nf 1 2 3\n", 2, "malformed number '1.2.3'");
    expect_err("v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n", 3, "malformed number 'x'");
    expect_err("v 1e 0 0\n", 1, "malformed number");
    expect_err("v - 0 0\n", 1, "malformed number");
    expect_err("v 0 0 .\n", 1, "malformed number");
    expect_err("v 0 0 0,5\n", 1, "malformed number");
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 zero\nf 1 2 3\n", 4, "malformed number");
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3a\n", 4, "malformed face corner '3a'");
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/x\n", 4, "malformed face corner");
    expect_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 /3\n", 4, "malformed face corner");
}

Test(mesh, error_vertex_arity)
{
    expect_err("v 0 0\n", 1, "vertex needs x y z");
    expect_err("v 0 0 0 1 1\n", 1, "5 numbers");
    expect_err("v 0 0 0 1 1 1 1 1\n", 1, "too many numbers");
}

Test(mesh, error_binary_data)
{
    static const char nul[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\0003\n";
    cr_assert_eq(parse_as("t.obj", nul, sizeof nul - 1), -1);
    cr_assert_str_eq(E, "t.obj:4: binary or unreadable data");
    static const char png[] = "\x89PNG\r\n\x1a\n\0\0\0\rIHDR";
    cr_assert_eq(parse_as("t.obj", png, sizeof png - 1), -1);
    cr_assert_str_eq(E, "t.obj:1: binary or unreadable data");
    expect_err("v 0 0 0\n# bell \a here\n", 2, "binary or unreadable data");
    expect_err("v 0 0 0\no na\001me\n", 2, "binary or unreadable data");
    expect_err("v 0 0 0\n}{ 1 2\n", 2, "binary or unreadable data");
    expect_err("v 0 0\0010\n", 1, "binary or unreadable data");
}

/* ==== The number parser ==== */

static uint32_t rng_state = 12345;
static uint32_t rng(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return rng_state >> 8;
}

static int64_t float_ord(float f)
{
    int32_t i;
    memcpy(&i, &f, sizeof i);
    return i < 0 ? -(int64_t)(i & 0x7fffffff) : i;
}

Test(mesh, float_parser_within_one_ulp_of_strtof)
{
    char buf[64];
    for (int k = 0; k < 200000; k++) {
        int n = 0;
        if (rng() & 1)
            buf[n++] = '-';
        int digits = 1 + (int)(rng() % 24), dot = (int)(rng() % (unsigned)(digits + 1));
        for (int i = 0; i < digits; i++) {
            if (i == dot && i > 0)
                buf[n++] = '.';
            buf[n++] = (char)('0' + rng() % 10);
        }
        if (rng() % 3 == 0)
            n += sprintf(buf + n, "e%d", (int)(rng() % 80) - 45);
        buf[n] = '\0';
        float want = strtof(buf, NULL);
        if (isinf(want) || (want != 0 && fabsf(want) < 1.1754944e-38f))
            continue;       /* overflow and subnormals: checked elsewhere */
        const char *p = buf;
        float got;
        cr_assert_eq(mesh_parse_float(&p, buf + n, &got), MESH_NUM_OK, "'%s'", buf);
        cr_assert_eq(p, buf + n);
        int64_t d = float_ord(got) - float_ord(want);
        cr_assert(d >= -1 && d <= 1, "'%s': got %.9g want %.9g", buf, got, want);
    }
}

Test(mesh, float_parser_stops_at_end_pointer)
{
    const char *s = "12.5e3";
    for (size_t n = 1; n <= 6; n++) {
        const char *p = s;
        float f = -1;
        int r = mesh_parse_float(&p, s + n, &f);
        char tmp[8] = {0};
        memcpy(tmp, s, n);
        float want = strtof(tmp, NULL);
        if (n == 5) {               /* "12.5e" lacks exponent digits */
            cr_assert_eq(r, MESH_NUM_BAD);
            continue;
        }
        cr_assert_eq(r, MESH_NUM_OK, "n=%zu", n);
        cr_assert_eq(f, want, "n=%zu", n);
        cr_assert_eq(p, s + n);
    }
}

/* ==== Robustness ==== */

static const char sample[] =
    "# sample\r\nmtllib none.mtl\no a\nv 0 0 0\nv 1.5 -2e1 3\nv 0 1 0 0.5 0.5 0.5\n"
    "vt 0 1\nvn 0 0 1\nusemtl m\nf 1/1/1 2/1/1 3/1/1\ng x\nf -3 -2 \\\n-1\no b\nv 1 1 1 2\n"
    "f 1//1 4//1 2//1\ns 1\nf 4 3 2 1";

Test(mesh, every_prefix_parses_without_overrun, .init = cr_redirect_stderr)
{
    for (size_t n = 0; n <= sizeof sample - 1; n++) {
        int r = parse_as("t.obj", sample, n);
        if (r == 0) {
            /* vertices alone are a point cloud */
            cr_assert(M.nfaces > 0 || M.npoints > 0 || M.nlines > 0);
            mesh_free(&M);
        } else {
            cr_assert_eq(strncmp(E, "t.obj", 5), 0, "n=%zu: %s", n, E);
        }
    }
}

Test(mesh, random_mutations_never_crash, .init = cr_redirect_stderr)
{
    char buf[sizeof sample];
    for (int k = 0; k < 5000; k++) {
        memcpy(buf, sample, sizeof sample - 1);
        int edits = 1 + (int)(rng() % 4);
        for (int i = 0; i < edits; i++)
            buf[rng() % (sizeof sample - 1)] = (char)(rng() & 0xff);
        size_t n = sizeof sample - 1 - rng() % 8;
        int r = parse_as("t.obj", buf, n);
        if (r == 0) {
            cr_assert(M.nfaces > 0 || M.npoints > 0 || M.nlines > 0);
            cr_assert_eq(M.face_start[0], 0);
            for (uint32_t f = 0; f < M.nfaces; f++)
                cr_assert_geq(M.face_start[f + 1], M.face_start[f] + 3);
            for (uint32_t c = 0; c < M.face_start[M.nfaces]; c++)
                cr_assert_lt(M.corner[c], M.nverts);
            mesh_free(&M);
        } else {
            cr_assert_eq(strncmp(E, "t.obj", 5), 0, "%s", E);
            cr_assert_null(M.pos);
        }
    }
}

Test(mesh, free_is_idempotent)
{
    expect_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    mesh_free(&M);
    mesh_free(&M);
    cr_assert_null(M.pos);
    cr_assert_eq(M.nfaces, 0);
}

/* ==== Shared models (suite "models": make test-models, which CI runs
 * when ../shared/models is there) ==== */

static void need_models(const char *file)
{
    char p[256];
    snprintf(p, sizeof p, MODELS "/%s", file);
    if (access(p, R_OK) != 0)
        cr_skip_test("%s not found", p);
}

static void load_model(const char *file)
{
    char p[256];
    need_models(file);
    snprintf(p, sizeof p, MODELS "/%s", file);
    cr_assert_eq(mesh_load(&M, p, E, sizeof E), 0, "%s", E);
}

Test(models, mesh_cube, .fini = teardown)
{
    load_model("cube.obj");
    cr_assert_eq(M.nverts, 8);
    cr_assert_eq(M.nfaces, 6);
    cr_assert_eq(M.info.triangles, 12);
    cr_assert_eq(M.nobjs, 1);
    cr_assert_str_eq(M.objs[0].name, "cube");
    cr_assert_eq(M.objs[0].vert_min, 0);
    cr_assert_eq(M.objs[0].vert_max, 7);
    expect_corners(0, (uint32_t[]){4, 5, 6, 7}, 4);
    expect_corners(5, (uint32_t[]){0, 1, 5, 4}, 4);
    cr_assert_eq(M.pos[0], -0.5f);
}

Test(models, mesh_negative_indices, .fini = teardown)
{
    load_model("negative-indices.obj");
    cr_assert_eq(M.nverts, 24);
    cr_assert_eq(M.nfaces, 6);
    cr_assert_eq(M.info.triangles, 12);
    cr_assert_eq(M.info.texcoords, 4);
    cr_assert_eq(M.info.normals, 3);
    cr_assert_str_eq(M.objs[0].name, "cube_relative");
    for (uint32_t f = 0; f < 6; f++)
        expect_corners(f, (uint32_t[]){4 * f, 4 * f + 1, 4 * f + 2, 4 * f + 3}, 4);
}

Test(models, mesh_cornell_box, .fini = teardown)
{
    load_model("cornell_box.obj");
    cr_assert_eq(M.nverts, 76);
    cr_assert_eq(M.nfaces, 18);
    cr_assert_eq(M.info.triangles, 36);
    cr_assert_eq(M.nmats, 5);
    /* 9 `o` statements; front_wall has its face commented out. */
    static const char *names[] = {"floor", "light", "ceiling", "back_wall", "green_wall",
                                  "red_wall", "short_block", "tall_block"};
    cr_assert_eq(M.nobjs, 8);
    for (int i = 0; i < 8; i++)
        cr_assert_str_eq(M.objs[i].name, names[i]);
    cr_assert_eq(M.objs[0].face_count, 3);
    cr_assert_eq(M.objs[1].face_first, 3);
    cr_assert_eq(M.objs[1].vert_min, 12);
    cr_assert_eq(M.objs[1].vert_max, 15);
    cr_assert_eq(M.objs[6].face_count, 5);
    cr_assert_eq(M.objs[7].face_count, 5);
    cr_assert_eq(M.objs[7].face_first, 13);
    cr_assert_str_eq(M.mats[mesh_face_mat(&M, 3)].name, "light");
    cr_assert_str_eq(M.mats[mesh_face_mat(&M, M.objs[4].face_first)].name, "green");
    const Material *red = &M.mats[mesh_face_mat(&M, M.objs[5].face_first)];
    cr_assert_str_eq(red->name, "red");
    cr_assert_eq(red->kd[0], 1.0f);
    cr_assert_eq(red->kd[1], 0.0f);
    cr_assert_eq(red->alpha, 1.0f);
    for (uint32_t f = 0; f < M.nfaces; f++)
        cr_assert_geq(mesh_face_mat(&M, f), 0);
}

static int cmp_key(const void *x, const void *y)
{
    const float *a = x, *b = y;
    for (int i = 0; i < 9; i++)
        if (a[i] != b[i])
            return a[i] < b[i] ? -1 : 1;
    return 0;
}

/* Each triangle as its 9 corner coordinates, sorted, so that two
 * meshes can be compared whatever their vertex and face order. */
static float *face_keys(const Mesh *m)
{
    float *k = malloc((size_t)m->nfaces * 9 * sizeof(float));
    cr_assert_not_null(k);
    for (uint32_t f = 0; f < m->nfaces; f++) {
        cr_assert_eq(m->face_start[f + 1] - m->face_start[f], 3);
        for (int c = 0; c < 3; c++)
            memcpy(k + 9 * f + 3 * c, m->pos + 3 * m->corner[m->face_start[f] + c],
                   3 * sizeof(float));
    }
    qsort(k, m->nfaces, 9 * sizeof(float), cmp_key);
    return k;
}

Test(models, mesh_bunny_relative_matches_absolute, .fini = teardown)
{
    Mesh a;
    load_model("bunny-5k-relative.obj");
    need_models("bunny-5k.obj");
    cr_assert_eq(mesh_load(&a, MODELS "/bunny-5k.obj", E, sizeof E), 0, "%s", E);
    cr_assert_eq(M.nverts, 2503);
    cr_assert_eq(a.nverts, 2503);
    cr_assert_eq(M.nfaces, 4968);
    cr_assert_eq(a.nfaces, 4968);
    cr_assert_eq(M.info.triangles, 4968);
    /* Vertex and face order differ between the files; the set of faces,
     * each as its corner positions in order, must not. */
    float *ka = face_keys(&a), *km = face_keys(&M);
    cr_assert_eq(memcmp(ka, km, (size_t)a.nfaces * 9 * sizeof(float)), 0);
    free(ka);
    free(km);
    mesh_free(&a);
}

Test(models, mesh_dragon_counts, .fini = teardown)
{
    load_model("dragon.obj");
    cr_assert_eq(M.nverts, 437645);
    cr_assert_eq(M.nfaces, 871414);
    cr_assert_eq(M.info.triangles, 871414);
    cr_assert_eq(M.info.bytes, 33397721);
}
