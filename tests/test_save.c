/* test_save.c: the writers (src/save/). Numbers: every float printed
 * reads back bit for bit, through strtof and the loaders' own parser,
 * in as few digits as printf's %.Ng needs (the shortest N found by
 * trying each). Models: each asset read by every native reader (OBJ as
 * it is, and as tests/writers.c writes it: OBJ, binary STL, PLY, OFF),
 * written by each writer (STL, OBJ, PLY) and read back: the same
 * positions bit for bit, the same polygons (STL: each face's fan), the
 * same objects and materials where the format carries them, and from
 * seeded views the same face-id buffer, which every algorithm gives
 * (tl_agree). Failures: /dev/full, a file size limit (a full disk):
 * one message naming the file, nothing left behind, an old file as it
 * was. A PLY polygon of 255, 256 or 300 corners reads back whole (its
 * count a byte, then a word). The shared models go through the same in
 * the "models" suite. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "mesh.h"
#include "save.h"
#include "testlib.h"
#include "writers.h"
#include "../src/mesh/reader.h"

static char E[512];
static char D[64];

static void setup(void)
{
    snprintf(D, sizeof D, "/tmp/zview-save-XXXXXX");
    cr_assert_not_null(mkdtemp(D));
}

static void teardown(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", D);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", D);
}

TestSuite(save, .init = setup, .fini = teardown);

static const char *tmp(const char *name)
{
    static char p[4][256];
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "%s/%.100s", D, name);
    return p[k];
}

/* ==== Numbers ==== */

static uint32_t rng(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(*s >> 32);
}

static float float_of(uint32_t u)
{
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static uint32_t bits_of(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

/* The significant digits of a decimal ("-0.000120" has 2; "100" 1). */
static int sig_digits(const char *s)
{
    char d[64];
    int n = 0;
    for (; *s && *s != 'e'; s++)
        if (*s >= '0' && *s <= '9')
            d[n++] = *s;
    int a = 0;
    while (a < n && d[a] == '0')
        a++;
    while (n > a && d[n - 1] == '0')
        n--;
    return n - a;
}

/* x through save_float: back bit for bit by strtof and by the loaders'
 * parser; returns its significant digits. */
static int round_trip(float x)
{
    char buf[SAVE_FLOAT_MAX + 1];
    int n = save_float(buf, x);
    cr_assert(n > 0 && n <= SAVE_FLOAT_MAX, "%a: %d characters", (double)x, n);
    buf[n] = 0;
    cr_assert_eq(bits_of(strtof(buf, NULL)), bits_of(x), "%a printed %s reads back as %a", (double)x, buf,
                 (double)strtof(buf, NULL));
    const char *p = buf;
    float y;
    cr_assert_eq(mesh_parse_float(&p, buf + n, &y), MESH_NUM_OK, "%s", buf);
    cr_assert_eq(bits_of(y), bits_of(x), "%a printed %s: the loaders read %a", (double)x, buf, (double)y);
    return sig_digits(buf);
}

/* The fewest digits printf's %.Ng needs for x to read back. */
static int shortest(float x)
{
    char buf[64];
    for (int p = 1; p < 9; p++) {
        snprintf(buf, sizeof buf, "%.*g", p, (double)x);
        if (bits_of(strtof(buf, NULL)) == bits_of(x))
            return p;
    }
    return 9;
}

Test(save, floats_read_back_bit_for_bit_in_the_fewest_digits)
{
    static const float special[] = { 0.0f, -0.0f, 1.0f, -1.0f, 0.1f, 0.2f, 0.3f, 1e-5f, 1.5e-5f, 123456789.0f,
                                     1e9f, 1e10f, 3.0e38f, FLT_MAX, -FLT_MAX, FLT_MIN, 1e-45f, -1e-45f,
                                     1.17549421e-38f, 16777216.0f, 16777215.0f, 0.5f, 9.5f, 99.5f, 0.0001f,
                                     0.00001f, 7.0e-10f, 1.0e-6f, 8388608.5f,
                                     /* 8.06588e+08 lies halfway to the next float: its last bit is 0, so
                                      * a reader takes it to this one; 33554450 lies halfway below
                                      * 33554452, whose last bit is 1: it needs all 8 digits */
                                     806588032.0f, 33554452.0f, 33554448.0f };
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++)
        cr_assert_eq(round_trip(special[i]), special[i] == 0 ? 0 : shortest(special[i]), "%a",
                     (double)special[i]);
    /* every power of two, and its neighbours (the gap below is half the one above) */
    for (int e = -149; e <= 127; e++) {
        float x = ldexpf(1.0f, e);
        round_trip(x);
        round_trip(nextafterf(x, 0));
        round_trip(nextafterf(x, INFINITY));
    }
    uint64_t s = 1;
    int longer = 0;
    for (int i = 0; i < 300000; i++) {
        uint32_t u = rng(&s);
        float x = float_of(u);
        if (!isfinite(x))
            continue;
        int got = round_trip(x), want = shortest(x);
        cr_assert_leq(got, want + 1, "%a: %d digits, %%.%dg reads back", (double)x, got, want);
        longer += got > want;
    }
    /* typical coordinates: few digits, as a scanner or an exporter writes them */
    for (int i = 0; i < 200000; i++) {
        char buf[32];
        snprintf(buf, sizeof buf, "%.*f", (int)(rng(&s) % 7), (rng(&s) % 2000000) / 1000.0 - 1000);
        float x = strtof(buf, NULL);
        int got = round_trip(x), want = shortest(x);
        cr_assert_leq(got, want + 1, "%a: %d digits, %%.%dg reads back", (double)x, got, want);
        longer += got > want;
    }
    /* a digit more only where the decimal lies too near a midpoint to tell in double */
    cr_expect_leq(longer, 5, "%d of 500000 floats took a digit more than the shortest", longer);
}

Test(save, integers_in_decimal)
{
    uint32_t v[] = { 0, 1, 9, 10, 99, 100, 4294967295u, 1000000000u, 123456789u };
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
        char buf[16], want[16];
        int n = save_u32(buf, v[i]);
        buf[n] = 0;
        snprintf(want, sizeof want, "%u", v[i]);
        cr_assert_str_eq(buf, want);
    }
}

/* ==== Formats by name ==== */

Test(save, formats_by_name_and_extension)
{
    cr_assert_eq(save_format_from_name("stl"), SAVE_STL);
    cr_assert_eq(save_format_from_name("OBJ"), SAVE_OBJ);
    cr_assert_eq(save_format_from_name("ply"), SAVE_PLY);
    cr_assert_eq(save_format_from_name("off"), -1);
    cr_assert_eq(save_format_of_path("a/b.c/x.Stl"), SAVE_STL);
    cr_assert_eq(save_format_of_path("x.obj"), SAVE_OBJ);
    cr_assert_eq(save_format_of_path("x.ply"), SAVE_PLY);
    cr_assert_eq(save_format_of_path("x.stl.gz"), -1);
    cr_assert_eq(save_format_of_path("a.stl/x"), -1);
    cr_assert_eq(save_format_of_path("-"), -1);
}

/* ==== Models read, written, read back ==== */

#define VIEW_W 96
#define VIEW_H 72
#define NVIEWS 3

/* The face-id buffers of path from NVIEWS seeded views (its geometry
 * alone: every file stood y-up), each checked to be every algorithm's
 * (tl_agree). */
static void views_of(const char *path, int32_t *ids)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, path), 0, "%s", path);
    scene_set_up(&s, UP_Y);
    TlAgree a = { 0 };
    for (int v = 0; v < NVIEWS; v++) {
        tl_random_view(&s, (uint32_t)v, v & 1);
        Viewport vp = { VIEW_W, VIEW_H, 1.0f, v == 2 };
        char msg[512];
        cr_assert_eq(tl_agree(&a, &s, &vp, 2, msg, sizeof msg), 0, "%s view %d: %s", path, v, msg);
        memcpy(ids + (size_t)v * VIEW_W * VIEW_H, a.ref.ids, (size_t)VIEW_W * VIEW_H * sizeof *ids);
    }
    tl_agree_free(&a);
    scene_free(&s);
}

static int same_floats(const float *a, const float *b, size_t n)
{
    return (!a && !b) || (a && b && !memcmp(a, b, n * sizeof *a));
}

/* What OBJ and PLY keep: every vertex and polygon as it was. */
static void same_polygons(const Mesh *a, const Mesh *b, const char *what)
{
    cr_assert_eq(b->nverts, a->nverts, "%s: vertices", what);
    cr_assert(same_floats(a->pos, b->pos, 3 * (size_t)a->nverts), "%s: the positions differ", what);
    cr_assert_eq(b->nfaces, a->nfaces, "%s: faces", what);
    cr_assert(!memcmp(a->face_start, b->face_start, ((size_t)a->nfaces + 1) * sizeof *a->face_start),
              "%s: the polygons' sizes differ", what);
    cr_assert(!memcmp(a->corner, b->corner, (size_t)a->face_start[a->nfaces] * sizeof *a->corner),
              "%s: the corners differ", what);
}

/* Is face f within 1e-5 of its size of the plane of its Newell normal
 * through its first corner? (Tighter than the scene's 1e-4, so that no
 * face the scene splits counts.) */
static int flat_face(const Mesh *m, uint32_t f, const double nrm[3], double len)
{
    uint32_t c0 = m->face_start[f], n = m->face_start[f + 1] - c0;
    if (len == 0)
        return 0;
    const float *o = m->pos + 3 * (size_t)m->corner[c0];
    double size = 0, off = 0;
    for (uint32_t k = 0; k < n; k++) {
        const float *p = m->pos + 3 * (size_t)m->corner[c0 + k];
        double d[3] = { (double)p[0] - o[0], (double)p[1] - o[1], (double)p[2] - o[2] };
        size = fmax(size, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        off = fmax(off, fabs(d[0] * nrm[0] + d[1] * nrm[1] + d[2] * nrm[2]) / len);
    }
    return off <= 1e-5 * size;
}

/* What STL keeps: face f of a (n corners) as n - 2 triangles, in
 * order, each on corners of the face (positions bit for bit) and wound
 * as it is: their vector areas add up to the face's (Newell's normal),
 * and for a planar face none is turned backwards (their areas add up to
 * its area: no triangle covers what is not the face's). tri_face gets
 * each triangle's face. */
static void same_triangles(const Mesh *a, const Mesh *b, const char *what, uint32_t *tri_face)
{
    uint32_t t = 0;
    for (uint32_t f = 0; f < a->nfaces; f++) {
        uint32_t c0 = a->face_start[f], n = a->face_start[f + 1] - c0;
        double sum[3] = { 0, 0, 0 }, area = 0, newell[3] = { 0, 0, 0 };
        for (uint32_t k = 0; k < n; k++) {
            const float *p = a->pos + 3 * (size_t)a->corner[c0 + k], *q = a->pos + 3 * (size_t)a->corner[c0 + (k + 1) % n];
            newell[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
            newell[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
            newell[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
        }
        for (uint32_t k = 0; k + 2 < n; k++, t++) {
            cr_assert_lt(t, b->nfaces, "%s: too few triangles", what);
            cr_assert_eq(b->face_start[t + 1] - b->face_start[t], 3, "%s: face %u is no triangle", what, t);
            const float *c[3];
            for (int i = 0; i < 3; i++) {
                c[i] = b->pos + 3 * (size_t)b->corner[b->face_start[t] + i];
                int on = 0;
                for (uint32_t j = 0; j < n && !on; j++)
                    on = same_floats(c[i], a->pos + 3 * (size_t)a->corner[c0 + j], 3);
                cr_assert(on, "%s: triangle %u corner %d is no corner of face %u", what, t, i, f);
            }
            double u[3], v[3], w[3];
            for (int i = 0; i < 3; i++) {
                u[i] = (double)c[1][i] - c[0][i];
                v[i] = (double)c[2][i] - c[0][i];
            }
            w[0] = u[1] * v[2] - u[2] * v[1];
            w[1] = u[2] * v[0] - u[0] * v[2];
            w[2] = u[0] * v[1] - u[1] * v[0];
            for (int i = 0; i < 3; i++)
                sum[i] += w[i];
            area += sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
            tri_face[t] = f;
        }
        double len = sqrt(newell[0] * newell[0] + newell[1] * newell[1] + newell[2] * newell[2]);
        for (int i = 0; i < 3; i++)
            cr_assert_leq(fabs(sum[i] - newell[i]), 1e-9 * (area + len) + 1e-30, "%s: face %u's triangles wind another way",
                          what, f);
        if (flat_face(a, f, newell, len))
            cr_assert_leq(area, len * (1 + 1e-9) + 1e-30, "%s: face %u is planar, yet a triangle of it is turned "
                          "backwards (covers what the face does not)", what, f);
    }
    cr_assert_eq(t, b->nfaces, "%s: %u triangles for %u", what, b->nfaces, t);
}

static void same_objects(const Mesh *a, const Mesh *b, const char *what)
{
    uint32_t na = 0, nb = 0;
    for (uint32_t i = 0; i < a->nobjs; i++) {
        const MeshObject *x = &a->objs[i];
        if (!x->face_count && !x->point_count && !x->line_count)
            continue;
        while (nb < b->nobjs && !b->objs[nb].face_count && !b->objs[nb].point_count && !b->objs[nb].line_count)
            nb++;
        cr_assert_lt(nb, b->nobjs, "%s: object %u \"%s\" is gone", what, i, x->name);
        const MeshObject *y = &b->objs[nb++];
        na++;
        cr_assert_str_eq(y->name, x->name, "%s: object %u", what, i);
        cr_assert(y->face_first == x->face_first && y->face_count == x->face_count, "%s: object %s's faces", what,
                  x->name);
        cr_assert(y->point_count == x->point_count && y->line_count == x->line_count, "%s: object %s's points and lines",
                  what, x->name);
    }
    cr_assert_gt(na, 0, "%s: no object", what);
}

/* OBJ's materials: each face's, with its colour, opacity and texture. */
static void same_materials(const Mesh *a, const Mesh *b, const char *what)
{
    for (uint32_t f = 0; f < a->nfaces; f++) {
        int32_t ma = mesh_face_mat(a, f), mb = mesh_face_mat(b, f);
        cr_assert_eq(ma < 0, mb < 0, "%s: face %u: material %d, read back %d", what, f, ma, mb);
        if (ma < 0)
            continue;
        const Material *x = &a->mats[ma], *y = &b->mats[mb];
        cr_assert(same_floats(x->kd, y->kd, 3) && x->alpha == y->alpha, "%s: material %s", what, x->name);
        cr_assert_eq(x->tex < 0, y->tex < 0, "%s: material %s's texture", what, x->name);
        if (x->tex >= 0)
            cr_assert_str_eq(strrchr(b->tex[y->tex].name, '/') ? strrchr(b->tex[y->tex].name, '/') + 1 : b->tex[y->tex].name,
                             strrchr(a->tex[x->tex].name, '/') ? strrchr(a->tex[x->tex].name, '/') + 1 : a->tex[x->tex].name,
                             "%s: material %s's texture", what, x->name);
    }
}

/* Do faces f and g lie in one plane (within 1e-6 of their size)? */
static int coplanar(const Mesh *m, uint32_t f, uint32_t g)
{
    double n[3] = { 0, 0, 0 };
    uint32_t c0 = m->face_start[f], nf = m->face_start[f + 1] - c0;
    for (uint32_t k = 0; k < nf; k++) {
        const float *p = m->pos + 3 * (size_t)m->corner[c0 + k], *q = m->pos + 3 * (size_t)m->corner[c0 + (k + 1) % nf];
        n[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
        n[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
        n[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
    }
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), size = 0, off = 0;
    if (len == 0)
        return 0;
    const float *o = m->pos + 3 * (size_t)m->corner[c0];
    for (int pass = 0; pass < 2; pass++) {
        uint32_t h = pass ? g : f, a = m->face_start[h], b = m->face_start[h + 1];
        for (uint32_t k = a; k < b; k++) {
            const float *p = m->pos + 3 * (size_t)m->corner[k];
            double d[3] = { (double)p[0] - o[0], (double)p[1] - o[1], (double)p[2] - o[2] };
            size = fmax(size, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
            off = fmax(off, fabs(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / len);
        }
    }
    return off <= 1e-6 * size;
}

/* The same face at every pixel of the views; tri_face: b's faces are a's
 * cut into triangles (STL), and b's face t is a's face tri_face[t]. A
 * polygon drawn whole has one depth plane and its triangles each their
 * own, which differ in the last bits: where two faces of a overlap in
 * one plane (a rug on a floor) that decides which shows, so there a
 * coplanar face may stand for the other (at most 1% of the pixels).
 * nfaces >= 0: the format dropped the points and lines (ids from nfaces
 * on), and where one was seen nothing is known. */
static void ids_equal(const Mesh *a, const int32_t *want, const int32_t *got, const uint32_t *tri_face,
                      int64_t nfaces, const char *what)
{
    size_t npx = (size_t)NVIEWS * VIEW_W * VIEW_H, fights = 0;
    for (size_t i = 0; i < npx; i++) {
        if (nfaces >= 0 && want[i] >= nfaces)
            continue;
        int32_t g = got[i] >= 0 && tri_face ? (int32_t)tri_face[got[i]] : got[i];
        if (g == want[i])
            continue;
        if (tri_face && g >= 0 && want[i] >= 0 && want[i] < (int32_t)a->nfaces && coplanar(a, (uint32_t)want[i], (uint32_t)g)) {
            fights++;
            continue;
        }
        cr_assert_fail("%s: view %zu pixel (%zu, %zu): face %d, read back %d", what, i / (VIEW_W * VIEW_H),
                       i % VIEW_W, i / VIEW_W % VIEW_H, want[i], g);
    }
    cr_assert_leq(fights, npx / 100, "%s: %zu pixels show another face of the same plane", what, fights);
}

/* Is every vertex colour a byte's k/255 (as a reader divides it)? */
static int bytes_only(const Mesh *m)
{
    for (size_t i = 0; i < 3 * (size_t)m->nverts; i++)
        if ((float)((int)(m->rgb[i] * 255 + 0.5f) / 255.0) != m->rgb[i])
            return 0;
    return 1;
}

/* in (a model a reader reads) through every writer and back. */
static void through_writers(const char *in, const char *name)
{
    Mesh a;
    cr_assert_eq(mesh_load(&a, in, E, sizeof E), 0, "%s", E);
    size_t npx = (size_t)NVIEWS * VIEW_W * VIEW_H;
    int32_t *want = malloc(npx * sizeof *want), *got = malloc(npx * sizeof *got);
    uint32_t *tri_face = malloc(((size_t)a.face_start[a.nfaces] + 1) * sizeof *tri_face);
    cr_assert(want && got && tri_face);
    views_of(in, want);
    static const char *const ext[SAVE_COUNT] = { "stl", "obj", "ply" };
    for (int fmt = 0; fmt < SAVE_COUNT; fmt++) {
        char out[300], what[400];
        snprintf(out, sizeof out, "%s/out-%s.%s", D, name, ext[fmt]);
        snprintf(what, sizeof what, "%s -> %s", in, ext[fmt]);
        SaveReport rep;
        cr_assert_eq(save_mesh(&a, out, (SaveFormat)fmt, &rep, E, sizeof E), 0, "%s: %s", what, E);
        struct stat st;
        cr_assert_eq(stat(out, &st), 0);
        cr_assert_eq((uint64_t)st.st_size, rep.bytes, "%s: the report's bytes", what);
        Mesh b;
        cr_assert_eq(mesh_load(&b, out, E, sizeof E), 0, "%s: %s", what, E);
        views_of(out, got);
        if (fmt == SAVE_STL) {
            same_triangles(&a, &b, what, tri_face);
            ids_equal(&a, want, got, tri_face, a.nfaces, what);
        } else {
            same_polygons(&a, &b, what);
            ids_equal(&a, want, got, NULL, rep.points_dropped || rep.lines_dropped ? (int64_t)a.nfaces : -1, what);
            cr_assert(same_floats(a.rgb, b.rgb, 3 * (size_t)a.nverts), "%s: vertex colours", what);
        }
        if (fmt == SAVE_PLY && a.face_mat && rep.materials_dropped == 0) {
            for (uint32_t f = 0; f < a.nfaces; f++)
                for (int k = 0; k < 3; k++)     /* as a byte: the nearest k/255 */
                    cr_assert_eq((int)(a.mats[a.face_mat[f]].kd[k] * 255 + 0.5f),
                                 (int)(b.mats[mesh_face_mat(&b, f)].kd[k] * 255 + 0.5f), "%s: face %u's colour", what, f);
        }
        if (fmt == SAVE_PLY)
            cr_assert_eq(rep.ply_float_colours, a.rgb && !bytes_only(&a), "%s: colours as floats", what);
        if (fmt == SAVE_OBJ) {
            same_objects(&a, &b, what);
            same_materials(&a, &b, what);
            cr_assert_eq(b.npoints, a.npoints, "%s: points", what);
            cr_assert_eq(b.nlines, a.nlines, "%s: lines", what);
            cr_assert_eq(rep.materials_dropped, 0);
        }
        mesh_free(&b);
        unlink(out);
        if (rep.mtl_path[0])
            unlink(rep.mtl_path);
    }
    free(want);
    free(got);
    free(tri_face);
    mesh_free(&a);
}

/* src as every native reader reads it: as it is, and as OBJ, binary
 * STL (triangles only), PLY and OFF written by tests/writers.c. */
static void every_reader(const char *src, const char *name)
{
    through_writers(src, name);
    Mesh m;
    cr_assert_eq(mesh_load(&m, src, E, sizeof E), 0, "%s", E);
    int triangles = 1;
    for (uint32_t f = 0; f < m.nfaces; f++)
        triangles &= m.face_start[f + 1] - m.face_start[f] == 3;
    struct {
        const char *ext;
        char *(*write)(const Mesh *, size_t *);
    } in[] = { { "obj", w_obj }, { "stl", w_stl_binary }, { "off", w_off }, { "ply", w_ply_ascii } };
    for (size_t i = 0; i < sizeof in / sizeof in[0]; i++) {
        if (!strcmp(in[i].ext, "stl") && !triangles)
            continue;           /* an STL of polygons is written fanned: the STL writer's own test above */
        size_t n;
        char *buf = in[i].write(&m, &n);
        cr_assert_not_null(buf);
        char path[300], nm[200];
        snprintf(nm, sizeof nm, "%.100s-%s", name, in[i].ext);
        snprintf(path, sizeof path, "%s/in-%s.%s", D, name, in[i].ext);
        cr_assert_eq(w_save(path, buf, n), 0);
        free(buf);
        through_writers(path, nm);
        unlink(path);
    }
    mesh_free(&m);
}

Test(save, every_asset_through_every_reader_and_writer, .timeout = 600)
{
    DIR *d = opendir("assets");
    cr_assert_not_null(d);
    int files = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t n = strlen(e->d_name);
        if (n < 5 || strcmp(e->d_name + n - 4, ".obj"))
            continue;
        char path[300], name[200];
        snprintf(path, sizeof path, "assets/%s", e->d_name);
        snprintf(name, sizeof name, "%.*s", (int)(n - 4), e->d_name);
        every_reader(path, name);
        files++;
    }
    closedir(d);
    cr_assert_geq(files, 8);
}

/* What no asset has: vertex colours (floats, and bytes), texture
 * coordinates, a texture with -o, -s and -clamp, a face of no material
 * between others, names a reader could take for something else (a
 * material named like a comment, an object with a space), a duplicate
 * material name, points and polylines, face colours (PLY). */
Test(save, colours_materials_textures_points_lines_objects)
{
    static const char obj[] =
        "mtllib rich.mtl\n"
        "v 0 0 0 0.1 0.2 0.3\nv 1 0 0 1 0 0\nv 1 1 0 0.5 0.25 0.125\nv 0 1 0 0.333 0.666 0.999\n"
        "v 0 0 1 0 0 0\nv 1 0 1 1 1 1\nv 1 1 1 0.7 0.7 0.7\nv 0 1 1 0.01 0.02 0.03\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.1 0.3\n"
        "o first\nusemtl red\nf 1/1 2/2 3/3 4/4\nusemtl\nf 8 7 6 5\n"
        "o second object\nusemtl tex\nf 1/1 4/2 8/3 5/4\nusemtl #ff0000\nf 2 6 7 3\np 1 2 3\nl 1 2 3 4\n"
        "o\nusemtl red\nf 1 5 6 2\nf 4 3 7 8\n";
    static const char mtl[] =
        "newmtl red\nKd 1 0 0\nd 0.5\n"
        "newmtl tex\nKd 0.2 0.4 0.6\nmap_Kd -s 2 3 -o 0.25 0.5 -clamp on tex.tga\n"
        "newmtl #ff0000\nKd 0.9 0.1 0.1\n";
    size_t n;
    char *tga = w_tga_rle(4, 4, 1, &n);
    cr_assert_not_null(tga);
    cr_assert_eq(w_save(tmp("tex.tga"), tga, n), 0);
    free(tga);
    cr_assert_eq(w_save(tmp("rich.obj"), obj, sizeof obj - 1), 0);
    cr_assert_eq(w_save(tmp("rich.mtl"), mtl, sizeof mtl - 1), 0);
    Mesh m;
    cr_assert_eq(mesh_load(&m, tmp("rich.obj"), E, sizeof E), 0, "%s", E);
    cr_assert_not_null(m.rgb);
    cr_assert_eq(m.nmats, 3);
    cr_assert_eq(m.ntex, 1);
    cr_assert_eq(m.tex[0].state, MTEX_OK, "the texture decodes");
    cr_assert_eq(m.npoints, 3);
    cr_assert_eq(m.nlines, 1);
    mesh_free(&m);
    through_writers(tmp("rich.obj"), "rich");

    /* texture coordinates and the texture's options come back (v as near as float allows) */
    SaveReport rep;
    cr_assert_eq(mesh_load(&m, tmp("rich.obj"), E, sizeof E), 0, "%s", E);
    cr_assert_eq(save_mesh(&m, tmp("again.obj"), SAVE_OBJ, &rep, E, sizeof E), 0, "%s", E);
    cr_assert_str_eq(rep.mtl_path, tmp("again.mtl"));
    Mesh b;
    cr_assert_eq(mesh_load(&b, tmp("again.obj"), E, sizeof E), 0, "%s", E);
    cr_assert_eq(b.nuv, m.nuv);
    for (uint32_t i = 0; i < 2 * m.nuv; i++)
        cr_assert_leq(fabsf(b.uv[i] - m.uv[i]), 6e-8f, "uv %u: %a, read back %a", i, (double)m.uv[i], (double)b.uv[i]);
    cr_assert(!memcmp(b.corner_uv, m.corner_uv, m.face_start[m.nfaces] * sizeof *m.corner_uv));
    const Material *x = &m.mats[1], *y = &b.mats[1];
    cr_assert_str_eq(y->name, "tex");
    cr_assert(x->tex_scale[0] == y->tex_scale[0] && x->tex_scale[1] == y->tex_scale[1]);
    cr_assert(fabsf(x->tex_off[0] - y->tex_off[0]) < 1e-7f && fabsf(x->tex_off[1] - y->tex_off[1]) < 1e-7f);
    cr_assert_eq(b.tex[y->tex].img.wrap_u, TEX_CLAMP);
    cr_assert_eq(b.tex[y->tex].state, MTEX_OK, "the texture is found beside the model");
    mesh_free(&b);

    /* what STL and PLY cannot carry is counted */
    cr_assert_eq(save_mesh(&m, tmp("again.stl"), SAVE_STL, &rep, E, sizeof E), 0, "%s", E);
    cr_assert_eq(rep.faces, 12);
    cr_assert_eq(rep.polygons_split, 6);
    cr_assert_eq(rep.points_dropped, 3);
    cr_assert_eq(rep.lines_dropped, 1);
    cr_assert_eq(rep.objects_merged, 2);
    cr_assert_eq(rep.materials_dropped, 3);
    cr_assert(rep.colours_dropped && rep.uvs_dropped);
    cr_assert_eq(save_mesh(&m, tmp("again.ply"), SAVE_PLY, &rep, E, sizeof E), 0, "%s", E);
    cr_assert_eq(rep.faces, 6);
    cr_assert_eq(rep.materials_dropped, 3, "a face has no material: no face colours");
    cr_assert(rep.ply_float_colours);
    mesh_free(&m);

    /* a PLY of byte colours, on vertices and faces */
    static const char ply[] =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\n"
        "property list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
        "end_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 10 20 30\n3 0 1 2 200 100 50\n"
        "3 0 2 3 1 2 3\n";
    cr_assert_eq(w_save(tmp("bytes.ply"), ply, sizeof ply - 1), 0);
    through_writers(tmp("bytes.ply"), "bytes");
    cr_assert_eq(mesh_load(&m, tmp("bytes.ply"), E, sizeof E), 0, "%s", E);
    cr_assert_eq(save_mesh(&m, tmp("bytes-out.ply"), SAVE_PLY, &rep, E, sizeof E), 0, "%s", E);
    cr_assert(!rep.ply_float_colours && rep.materials_dropped == 0, "byte colours stay bytes, faces keep theirs");
    mesh_free(&m);
}

/* ==== Failures ==== */

static int files_in(const char *dir)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        n += e->d_name[0] != '.';
    closedir(d);
    return n;
}

Test(save, a_full_device_is_one_message_naming_it)
{
    Mesh m;
    cr_assert_eq(mesh_load(&m, "assets/knot.obj", E, sizeof E), 0, "%s", E);
    for (int fmt = 0; fmt < SAVE_COUNT; fmt++) {
        cr_assert_eq(save_mesh(&m, "/dev/full", (SaveFormat)fmt, NULL, E, sizeof E), -1, "%d", fmt);
        char want[128];
        snprintf(want, sizeof want, "/dev/full: %s", strerror(ENOSPC));
        cr_assert_str_eq(E, want);
    }
    mesh_free(&m);
}

/* A file size limit stands for a full disk: the write fails part way. */
Test(save, a_full_disk_leaves_nothing_and_the_old_file_as_it_was)
{
    Mesh m;
    cr_assert_eq(mesh_load(&m, "assets/demo.obj", E, sizeof E), 0, "%s", E);
    cr_assert_gt(m.nmats, 0, "demo.obj has materials: an MTL would be written");
    cr_assert_eq(w_save(tmp("old.stl"), "old\n", 4), 0);
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit was, lim;
    cr_assert_eq(getrlimit(RLIMIT_FSIZE, &was), 0);
    lim = was;
    lim.rlim_cur = 64 * 1024;
    cr_assert_eq(setrlimit(RLIMIT_FSIZE, &lim), 0);
    static const char *const names[SAVE_COUNT] = { "old.stl", "new.obj", "new.ply" };
    for (int fmt = 0; fmt < SAVE_COUNT; fmt++) {
        const char *path = tmp(names[fmt]);
        int rc = save_mesh(&m, path, (SaveFormat)fmt, NULL, E, sizeof E);
        char want[512];
        snprintf(want, sizeof want, "%s: %s", path, strerror(EFBIG));
        cr_expect_eq(rc, -1, "%s", path);
        cr_expect_str_eq(E, want);
    }
    setrlimit(RLIMIT_FSIZE, &was);
    cr_assert_eq(files_in(D), 1, "only old.stl is left (no temporary file, no new.mtl)");
    FILE *f = fopen(tmp("old.stl"), "rb");
    char buf[16] = "";
    cr_assert(f && fread(buf, 1, sizeof buf, f) == 4 && !memcmp(buf, "old\n", 4), "old.stl as it was");
    fclose(f);
    mesh_free(&m);
}

/* ==== The shared models (suite "models": make test-models) ==== */

static void shared_folder(int dragon)
{
    const char *dir = "../shared/models";
    DIR *d = opendir(dir);
    if (!d)
        cr_skip_test("../shared/models not found");
    int files = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t n = strlen(e->d_name);
        if (n < 5 || strcmp(e->d_name + n - 4, ".obj") || (strcmp(e->d_name, "dragon.obj") == 0) != dragon)
            continue;
        char path[600], name[200];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        snprintf(name, sizeof name, "%.*s", (int)(n - 4), e->d_name);
        every_reader(path, name);
        files++;
    }
    closedir(d);
    cr_assert_gt(files, 0, "no models in %s", dir);
}

Test(models, shared_models_through_every_reader_and_writer, .init = setup, .fini = teardown, .timeout = 3000)
{
    shared_folder(0);
}

Test(models, dragon_through_every_reader_and_writer, .init = setup, .fini = teardown, .timeout = 3000)
{
    if (!getenv("ZV_MODELS"))
        cr_skip_test("set ZV_MODELS=1 with ../shared/models present (make test-models)");
    shared_folder(1);
}

/* Materials of one name (assimp gives such), of none, and two of the
 * longest name a reader keeps (63 bytes): each written under a name of
 * its own that reads back whole (the suffix of the second long one fits
 * within the 63), so that every face finds its own. */
Test(save, material_names_made_unique_and_whole)
{
    Mesh m;
    cr_assert_eq(tl_mesh_init(&m, tmp("names.obj")), 0);
    for (int i = 0; i < 7; i++)
        cr_assert_eq(tl_mesh_vertex(&m, (float)i, (float)(i % 2), 0), 0);
    for (uint32_t f = 0; f < 5; f++)
        cr_assert_eq(tl_mesh_face(&m, (uint32_t[]){ f, f + 1, f + 2 }, 3), 0);
    cr_assert_eq(tl_mesh_finish(&m), 0);
    char longest[MESH_NAME_MAX];
    memset(longest, 'x', MESH_NAME_MAX - 1);
    longest[MESH_NAME_MAX - 1] = 0;
    const char *const names[5] = { "wood", "wood", "", longest, longest };
    m.nmats = 5;
    m.mats = calloc(5, sizeof *m.mats);
    m.face_mat = malloc(5 * sizeof *m.face_mat);
    cr_assert(m.mats && m.face_mat);
    for (int i = 0; i < 5; i++) {
        snprintf(m.mats[i].name, sizeof m.mats[i].name, "%s", names[i]);
        m.mats[i].kd[0] = (float)i / 8;
        m.mats[i].alpha = 1;
        m.mats[i].tex = -1;
        m.face_mat[i] = 4 - i;
    }
    SaveReport rep;
    cr_assert_eq(save_mesh(&m, tmp("names.obj"), SAVE_OBJ, &rep, E, sizeof E), 0, "%s", E);
    Mesh b;
    cr_assert_eq(mesh_load(&b, tmp("names.obj"), E, sizeof E), 0, "%s", E);
    cr_assert_eq(b.nmats, 5, "every material a name of its own (%u read back)", b.nmats);
    for (uint32_t f = 0; f < 5; f++)
        cr_assert_eq(b.mats[b.face_mat[f]].kd[0], m.mats[m.face_mat[f]].kd[0], "face %u's material", f);
    mesh_free(&b);
    mesh_free(&m);
}

/* A PLY face's corner count is a byte up to 255 corners and a 32-bit
 * word past it: a regular polygon of 255, 256 or 300 corners (the
 * byte's last count and the first two past it), beside a triangle,
 * reads back as it was, every corner of every face. */
Test(save, ply_polygons_of_255_256_and_300_corners_read_back)
{
    static const uint32_t sizes[3] = { 255, 256, 300 };
    for (int k = 0; k < 3; k++) {
        Mesh m;
        cr_assert_eq(tl_mesh_init(&m, tmp("ngon.ply")), 0);
        uint32_t n = sizes[k], c[300];
        for (uint32_t i = 0; i < n; i++) {
            double a = 2 * M_PI * i / n;
            cr_assert_eq(tl_mesh_vertex(&m, (float)cos(a), (float)sin(a), (float)k), 0);
            c[i] = i;
        }
        cr_assert_eq(tl_mesh_face(&m, c, n), 0);
        cr_assert_eq(tl_mesh_face(&m, (uint32_t[]){ 0, 1, 2 }, 3), 0);
        cr_assert_eq(tl_mesh_finish(&m), 0);
        SaveReport rep;
        cr_assert_eq(save_mesh(&m, tmp("ngon.ply"), SAVE_PLY, &rep, E, sizeof E), 0, "%s", E);
        Mesh b;
        cr_assert_eq(mesh_load(&b, tmp("ngon.ply"), E, sizeof E), 0, "%u corners: %s", n, E);
        char what[32];
        snprintf(what, sizeof what, "a %u-gon", n);
        same_polygons(&m, &b, what);
        mesh_free(&b);
        mesh_free(&m);
    }
}

/* A binary STL's facet normal is its triangle's unit normal, by the
 * right-hand rule (the corners counter-clockwise seen from outside):
 * each worked out by hand here, none through the origin. */
Test(save, stl_facet_normals_are_the_triangles_unit_normals)
{
    Mesh m;
    cr_assert_eq(tl_mesh_init(&m, "n.obj"), 0);
    static const float v[9][3] = { { 0, 0, 5 }, { 2, 0, 5 }, { 0, 2, 5 },      /* z = 5, normal +z */
                                   { 1, 0, 2 }, { 1, 1, 2 }, { 1, 0, 3 },      /* x = 1, normal +x */
                                   { 0, 0, 7 }, { 0, 0, 10 }, { 3, 4, 7 } };   /* (-0.8, 0.6, 0) */
    static const float want[3][3] = { { 0, 0, 1 }, { 1, 0, 0 }, { -0.8f, 0.6f, 0 } };
    for (int i = 0; i < 9; i++)
        cr_assert_eq(tl_mesh_vertex(&m, v[i][0], v[i][1], v[i][2]), 0);
    for (uint32_t t = 0; t < 3; t++) {
        uint32_t c[3] = { 3 * t, 3 * t + 1, 3 * t + 2 };
        cr_assert_eq(tl_mesh_face(&m, c, 3), 0);
    }
    cr_assert_eq(tl_mesh_finish(&m), 0);
    SaveReport rep;
    cr_assert_eq(save_mesh(&m, tmp("n.stl"), SAVE_STL, &rep, E, sizeof E), 0, "%s", E);
    mesh_free(&m);
    unsigned char b[84 + 3 * 50];
    FILE *f = fopen(tmp("n.stl"), "rb");
    cr_assert(f);
    cr_assert_eq(fread(b, 1, sizeof b, f), sizeof b);
    cr_assert_eq(fgetc(f), EOF);
    fclose(f);
    cr_assert_eq(b[80] | b[81] << 8 | b[82] << 16 | (uint32_t)b[83] << 24, 3u);
    for (int t = 0; t < 3; t++)
        for (int k = 0; k < 3; k++) {
            float n;
            memcpy(&n, b + 84 + 50 * t + 4 * k, 4);     /* little-endian, as this machine */
            cr_assert_float_eq(n, want[t][k], 1e-6, "triangle %d's normal[%d]: %g, not %g", t, k, n, want[t][k]);
        }
}

/* A texture's name longer than any path (a file may name anything) is
 * written cut to PATH_MAX - 1 bytes, the longest path the system opens:
 * map_Kd's line holds no more. */
Test(save, a_texture_name_longer_than_a_path_is_cut_to_the_longest_path)
{
    static const char obj[] = "mtllib long.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl t\nf 1/1 2/1 3/1\n";
    static const char mtl[] = "newmtl t\nmap_Kd x.png\n";
    cr_assert_eq(w_save(tmp("long.obj"), obj, sizeof obj - 1), 0);
    cr_assert_eq(w_save(tmp("long.mtl"), mtl, sizeof mtl - 1), 0);
    Mesh m;
    MeshLoadOpts lo = { .quiet = 1 };     /* x.png is not there: its name is what counts */
    cr_assert_eq(mesh_load_ex(&m, tmp("long.obj"), &lo, E, sizeof E), 0, "%s", E);
    cr_assert_eq(m.ntex, 1);
    for (size_t len = PATH_MAX - 2; len <= PATH_MAX + 1; len++) {
        free(m.tex[0].name);
        m.tex[0].name = malloc(len + 1);
        cr_assert(m.tex[0].name);
        memset(m.tex[0].name, 'a', len);
        m.tex[0].name[len] = 0;
        SaveReport rep;
        cr_assert_eq(save_mesh(&m, tmp("out.obj"), SAVE_OBJ, &rep, E, sizeof E), 0, "%s", E);
        FILE *f = fopen(tmp("out.mtl"), "r");
        cr_assert(f);
        static char line[2 * PATH_MAX];
        size_t got = 0;
        while (fgets(line, sizeof line, f))
            if (!strncmp(line, "map_Kd ", 7)) {
                got = strcspn(line + 7, "\n");
                cr_assert_eq(strspn(line + 7, "a"), got);
            }
        fclose(f);
        size_t want = len < PATH_MAX ? len : PATH_MAX - 1;
        cr_assert_eq(got, want, "a name of %zu bytes written as %zu, not %zu", len, got, want);
    }
    mesh_free(&m);
}
