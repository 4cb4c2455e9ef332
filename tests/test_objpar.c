/* test_objpar.c: OBJ parsed in pieces on several threads (issue 21) is
 * the serial parse, byte for byte: the mesh (every array, object,
 * material and info field), the result and the message, strict or not,
 * for every piece size from a byte up, on the bundled assets, the fuzz
 * seeds and regression inputs, generated files that put every kind of
 * statement across the cuts, files read from disk (the pieces read by
 * pread) and, in the "models" suite, the shared models. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mesh.h"
#include "testlib.h"

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    *len = (size_t)n;
    return buf;
}

/* Serial against pieces of each size, on 2 and 3 threads, strict and
 * not; counts the comparisons made. */
static int check_text(const char *name, const char *text, size_t len, const uint64_t *pieces, int npieces)
{
    int n = 0;
    for (int k = 0; k < npieces; k++)
        for (int threads = 2; threads <= 3; threads++)
            for (int strict = 0; strict <= 1; strict++) {
                const char *d = tl_obj_pieces_differ(name, text, len, threads, pieces[k], strict);
                cr_expect_null(d, "%s", d);
                n++;
            }
    return n;
}

static int check_file(const char *path, const uint64_t *pieces, int npieces)
{
    size_t len = 0;
    char *text = slurp(path, &len);
    cr_assert_not_null(text, "%s", path);
    int n = check_text(path, text, len, pieces, npieces);
    free(text);
    return n;
}

/* Every regular file of a folder. */
static int check_folder(const char *dir, const uint64_t *pieces, int npieces)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d, "%s", dir);
    struct dirent *e;
    int n = 0;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        n += check_file(path, pieces, npieces);
    }
    closedir(d);
    return n;
}

static const uint64_t Small[] = { 1, 3, 16, 61, 256, 4096 };
#define NSMALL ((int)(sizeof Small / sizeof Small[0]))

Test(objpar, assets)
{
    const char *files[] = { "assets/demo.obj", "assets/knot.obj", "assets/torus.obj", "assets/cube.obj",
                            "assets/concave.obj", "assets/cyclic.obj", "assets/star-pierce.obj" };
    /* the big ones in fewer pieces: thousands of pieces cost time, and
     * the small files and generated ones below cut everywhere */
    const uint64_t big[] = { 997, 4096, 65536 };
    int n = 0;
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++)
        if (access(files[i], R_OK) == 0)
            n += check_file(files[i], i < 3 ? big : Small, i < 3 ? 3 : NSMALL);
    cr_expect_gt(n, 0, "no asset was compared");
}

Test(objpar, fuzz_inputs)
{
    const uint64_t pieces[] = { 1, 7, 40 };
    int n = check_folder("tests/fuzz/seeds/obj", pieces, 3);
    n += check_folder("tests/fuzz/regress/obj", pieces, 3);
    cr_expect_gt(n, 0);
}

/* Every kind of statement, each where a cut can fall before, inside or
 * after it: indices counting back across the cuts, materials switched
 * and named again, objects started before and after their faces,
 * texture coordinates both ways, colours from the middle on, points and
 * polylines, groups, comments, free-form and unknown statements, bad
 * statements, indices past the end, `\` lines, CRLF and lone CR. */
static const char *const Tricky[] = {
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
    "o first\nusemtl red\nf 1/1/1 2/2/1 3/3/1\nf -1 -2 -3\n"
    "g grp\nusemtl blue\nf 2 4 3\n# comment\n\no second\no renamed\nf -4/-3 -3/-2 -2/-1\n"
    "usemtl red\nf 1 2 4\nusemtl\nf 1 3 4\n"
    "v 2 2 2 0.5 0.25 1\nf 5 1 2\np 1 2 -1\nl 1 2 3 -2\ns 1\ncurv 0 1 2\nf 1 2 5\n",
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\nv 1 1 1\nf 1 2 4\nbogus 1 2\nf 1 2\nv x y z\nf 4 5 6\n"
    "v 2 0 0\nv 0 2 0\nf 6 7 1\nf 1 2 \\\n 3\nvt 0.5 0.5\nf 1/1 2/1 3/-1\n",
    "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\no a\r\nf 3 2 1\rv 1 1 0\rf 1 2 4\r\n"
    "mtllib none.mtl\nusemtl x\nf 1 2 3\nv 0 0 1 2\nf -1 -2 -3\n",
    "o lead\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"
    "o empty\no pts\np 1 2 3 4\no lines\nl 1 2\nl 3 4 1\no back\nf -4 -3 -2\nf 4 3 2\n",
};

Test(objpar, statements_across_every_cut)
{
    int n = 0;
    for (size_t i = 0; i < sizeof Tricky / sizeof Tricky[0]; i++) {
        /* repeated so that the later pieces hold the same kinds again */
        size_t one = strlen(Tricky[i]), len = 12 * one;
        char *text = malloc(len);
        for (int r = 0; r < 12; r++)
            memcpy(text + (size_t)r * one, Tricky[i], one);
        for (uint64_t piece = 1; piece <= 700; piece += piece < 24 ? 1 : 23)
            n += check_text("tricky.obj", text, len, &piece, 1);
        free(text);
    }
    cr_expect_gt(n, 400);
}

/* A NUL ends the text: before, inside and after the pieces. */
Test(objpar, nul_anywhere)
{
    static const char base[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 1 1 0\nf 2 4 3\nf -1 -2 -3\n";
    size_t len = sizeof base - 1;
    for (size_t at = 0; at < len; at += 5) {
        char text[sizeof base];
        memcpy(text, base, len);
        text[at] = '\0';
        const uint64_t pieces[] = { 2, 9 };
        check_text("nul.obj", text, len, pieces, 2);
    }
}

/* From disk: the pieces are read with pread, the first through the
 * mapping's window. */
Test(objpar, from_a_file)
{
    char path[] = "/tmp/zv-objpar-XXXXXX";
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    FILE *f = fdopen(fd, "w");
    for (int i = 0; i < 3000; i++)
        fprintf(f, "v %d %d %d\n", i % 17, i % 13, i % 11);
    for (int i = 0; i < 5000; i++) {
        if (i % 700 == 0)
            fprintf(f, "o part%d\nusemtl m%d\n", i, i % 3);
        fprintf(f, i % 3 ? "f %d %d %d\n" : "f -%d -%d -%d\n", 1 + i % 2990, 2 + i % 2990, 3 + i % 2990);
    }
    fclose(f);
    Mesh a, b;
    char ea[256], eb[256];
    MeshLoadOpts oa = { .strict = 0, .quiet = 1, .threads = 1 }, ob = oa;
    ob.threads = 2;
    for (uint64_t piece = 100; piece < 20000; piece = piece * 3 + 1) {
        ob.piece_bytes = piece;
        cr_assert_eq(mesh_load_ex(&a, path, &oa, ea, sizeof ea), 0, "%s", ea);
        cr_assert_eq(mesh_load_ex(&b, path, &ob, eb, sizeof eb), 0, "%s", eb);
        const char *d = tl_mesh_differs(&a, &b);
        cr_expect_null(d, "pieces of %llu: %s differs", (unsigned long long)piece, d);
        cr_expect_eq(a.nfaces, 5000);
        mesh_free(&a);
        mesh_free(&b);
    }
    unlink(path);
}

/* A line longer than a piece's read block (4 MB): the block grows. */
Test(objpar, a_line_longer_than_the_block)
{
    char path[] = "/tmp/zv-objpar-XXXXXX";
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fprintf(f, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n");
    for (int k = 0; k < 3; k++) {
        fprintf(f, "f");
        for (int i = 0; i < 900000; i++)
            fprintf(f, " 1 2 4");
        fprintf(f, "\nf -1 -2 -3\n");
        /* short lines, where the cuts fall (none inside a long line) */
        for (int i = 0; i < 150000; i++)
            fprintf(f, "f 1 2 3\n");
    }
    fclose(f);
    Mesh a, b;
    char ea[256], eb[256];
    MeshLoadOpts oa = { .strict = 1, .quiet = 1, .threads = 1 }, ob = oa;
    ob.threads = 2;
    ob.piece_bytes = 1 << 20;
    cr_assert_eq(mesh_load_ex(&a, path, &oa, ea, sizeof ea), 0, "%s", ea);
    cr_assert_eq(mesh_load_ex(&b, path, &ob, eb, sizeof eb), 0, "%s", eb);
    const char *d = tl_mesh_differs(&a, &b);
    cr_expect_null(d, "%s differs", d);
    cr_expect_eq(a.nfaces, 3 * 150002);
    mesh_free(&a);
    mesh_free(&b);
    unlink(path);
}

static void write_text(const char *path, const char *text, size_t n)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(text, 1, n, f), n);
    fclose(f);
}

/* Indices counting back past a piece's start, vertices and texture
 * coordinates, with a textured material (so that the texture
 * coordinates are kept and compared), and one reaching back exactly one
 * past the first vertex (the serial parse skips it). */
Test(objpar, indices_back_past_a_piece)
{
    char dir[] = "/tmp/zv-objpar-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char obj[64], mtl[64], tga[64];
    snprintf(obj, sizeof obj, "%s/t.obj", dir);
    snprintf(mtl, sizeof mtl, "%s/t.mtl", dir);
    snprintf(tga, sizeof tga, "%s/t.tga", dir);
    /* a 2x2 true-colour TGA */
    const unsigned char img[18 + 12] = { 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0, 24, 0,
                                         255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255 };
    write_text(tga, (const char *)img, sizeof img);
    write_text(mtl, "newmtl m\nmap_Kd t.tga\n", 22);
    FILE *f = fopen(obj, "w");
    fprintf(f, "mtllib t.mtl\nusemtl m\n");
    for (int i = 0; i < 400; i++) {
        fprintf(f, "v %d 0 0\nv 0 %d 0\nv 0 0 %d\nvt 0.%d 0.5\nvt 0.5 0.%d\n", i, i + 1, i + 2, i % 10, i % 7);
        /* a cut between a face and the vertices it counts back to */
        fprintf(f, "f -3/-2 -2/-1 -1/-2\nf -6/-4 -5/-3 -4/-%d\n", i % 2 ? 9 : 1);
    }
    fprintf(f, "f -1 -2 -1201\nf -1 -2 -1200\n");
    fclose(f);
    Mesh a, b;
    char ea[256], eb[256];
    for (int strict = 0; strict <= 1; strict++)
        for (uint64_t piece = 16; piece < 3000; piece = piece * 2 + 3) {
            MeshLoadOpts oa = { .strict = strict, .quiet = 1, .threads = 1 }, ob = oa;
            ob.threads = 2;
            ob.piece_bytes = piece;
            int ra = mesh_load_ex(&a, obj, &oa, ea, sizeof ea), rb = mesh_load_ex(&b, obj, &ob, eb, sizeof eb);
            cr_expect_eq(ra, rb);
            cr_expect_str_eq(ea, eb);
            if (ra == 0 && rb == 0) {
                const char *d = tl_mesh_differs(&a, &b);
                cr_expect_null(d, "pieces of %llu: %s differs", (unsigned long long)piece, d);
                cr_expect_not_null(a.corner_uv, "the texture coordinates are kept");
            }
            mesh_free(&a);
            mesh_free(&b);
        }
    /* entries counted back where there are none: no corner has one, and
     * no per-corner array is made */
    f = fopen(obj, "w");
    fprintf(f, "mtllib t.mtl\nusemtl m\n");
    for (int i = 0; i < 300; i++)
        fprintf(f, "v %d 0 0\nv 0 %d 0\nv 0 0 1\nf -3/-1 -2/-2 -1/-3\n", i, i + 1);
    fclose(f);
    for (uint64_t piece = 16; piece < 2000; piece = piece * 2 + 3) {
        MeshLoadOpts oa = { .quiet = 1, .threads = 1 }, ob = oa;
        ob.threads = 2;
        ob.piece_bytes = piece;
        cr_assert_eq(mesh_load_ex(&a, obj, &oa, ea, sizeof ea), 0, "%s", ea);
        cr_assert_eq(mesh_load_ex(&b, obj, &ob, eb, sizeof eb), 0, "%s", eb);
        const char *d = tl_mesh_differs(&a, &b);
        cr_expect_null(d, "no entries, pieces of %llu: %s differs", (unsigned long long)piece, d);
        mesh_free(&a);
        mesh_free(&b);
    }
    unlink(obj);
    unlink(mtl);
    unlink(tga);
    rmdir(dir);
}

/* The comparison itself sees a difference (a test that cannot fail
 * proves nothing). */
Test(objpar, a_difference_is_seen)
{
    Mesh a, b;
    char e[256];
    cr_assert_eq(mesh_parse(&a, "a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 32, e, sizeof e), 0, "%s", e);
    cr_assert_eq(mesh_parse(&b, "a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 3 2\n", 32, e, sizeof e), 0, "%s", e);
    cr_expect_str_eq(tl_mesh_differs(&a, &b), "corner");
    cr_expect_null(tl_mesh_differs(&a, &a));
    mesh_free(&a);
    mesh_free(&b);
}

Test(models, objpar_shared)
{
    const char *names[] = { "dragon.obj", "cornell_box.obj", "negative-indices.obj", "spot.obj",
                            "bunny-5k-relative.obj", "scene-overlap.obj", "sword-quads.obj" };
    const uint64_t pieces[] = { 4096, 1 << 20 };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        const char *p = tl_shared_model(names[i]);
        if (p)
            check_file(p, pieces, 2);
    }
}
