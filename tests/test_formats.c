/* test_formats.c: choosing the loader (content first, extension second,
 * --format), the one-line refusal, standard input, the hostile inputs
 * of issue 7 (a self-naming mtllib, FIFOs, a 2 GB sparse file, a 2^63
 * index, CR-only lines), and the same model in every format giving
 * byte-identical face-id buffers (the bunny; the dragon in the "models"
 * suite), and through assimp a GLB giving the same coverage. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "mesh.h"
#include "app.h"
#include "testlib.h"
#include "writers.h"

static Mesh M;
static char E[512];
static char dir[64];

static void setup(void)
{
    snprintf(dir, sizeof dir, "/tmp/zview-formats-XXXXXX");
    cr_assert_not_null(mkdtemp(dir));
}

static void teardown(void)
{
    mesh_free(&M);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", dir);
}

TestSuite(formats, .init = setup, .fini = teardown);

static const char *tmp(const char *name)
{
    static char p[4][256];
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
    return p[k];
}

static void save(const char *path, const void *data, size_t n)
{
    cr_assert_eq(w_save(path, data, n), 0, "cannot write %s", path);
}

/* Time limits of the hostile-input tests: the sanitizers' builds are
 * several times slower (and poison the shadow of big reservations). */
#if defined(__SANITIZE_ADDRESS__)
#define SLOW 10
#else
#define SLOW 1
#endif

/* The process's CPU time (its threads' and the kernel's for it), not
 * the wall's: a shared machine's load does not lengthen it. */
static double ms_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* The bytes this process has read through read() and its kind
 * (/proc/self/io's rchar: from the page cache and pipes too); -1 when
 * the kernel does not say. */
static long long bytes_read(void)
{
    FILE *f = fopen("/proc/self/io", "r");
    long long n = -1;
    if (f) {
        char line[128];
        while (fgets(line, sizeof line, f))
            if (sscanf(line, "rchar: %lld", &n) == 1)
                break;
        fclose(f);
    }
    return n;
}

static const char tri_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
static const char tri_off[] = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
static const char tri_ply[] = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
static const char tri_stl[] = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                              "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";

/* ==== Choosing the loader ==== */

Test(formats, content_beats_the_extension)
{
    const struct {
        const char *name, *data, *format;
    } t[] = {
        { "a.obj", tri_off, "off" },  { "a.stl", tri_ply, "ply ascii" }, { "a.ply", tri_stl, "stl ascii" },
        { "a.off", tri_obj, "obj" },  { "noext", tri_off, "off" },       { "a.txt", tri_obj, "obj" },
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        save(tmp(t[i].name), t[i].data, strlen(t[i].data));
        cr_assert_eq(mesh_load(&M, tmp(t[i].name), E, sizeof E), 0, "%s: %s", t[i].name, E);
        cr_assert_str_eq(M.info.format, t[i].format, "%s", t[i].name);
        cr_assert_eq(M.nfaces, 1);
        mesh_free(&M);
    }
}

Test(formats, the_extension_when_content_cannot_tell)
{
    /* an OFF without its (optional) keyword reads as OFF by name only */
    static const char bare[] = "3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    save(tmp("bare.off"), bare, sizeof bare - 1);
    cr_assert_eq(mesh_load(&M, tmp("bare.off"), E, sizeof E), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "off");
    mesh_free(&M);
    save(tmp("bare.dat"), bare, sizeof bare - 1);
    cr_assert_eq(mesh_load(&M, tmp("bare.dat"), E, sizeof E), -1);
    cr_assert_not_null(strstr(E, "not a model zview can read (text; formats: obj stl ply off"), "%s", E);
    /* --format forces it */
    cr_assert_eq(mesh_load_as(&M, tmp("bare.dat"), "off", E, sizeof E), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
}

Test(formats, forcing_a_format_names_its_errors)
{
    save(tmp("t.obj"), tri_obj, strlen(tri_obj));
    cr_assert_eq(mesh_load_as(&M, tmp("t.obj"), "ply", E, sizeof E), -1);
    cr_assert_not_null(strstr(E, "t.obj:1: not a PLY file"), "%s", E);
    cr_assert_eq(mesh_load_as(&M, tmp("t.obj"), "nope", E, sizeof E), -1);
    cr_assert_not_null(strstr(E, "unknown format 'nope'"), "%s", E);
    cr_assert(mesh_format_valid("obj") && mesh_format_valid("STL") && !mesh_format_valid("gz"));
}

Test(formats, not_a_model_in_one_line)
{
    const struct {
        const char *name;
        const char *data;
        size_t n;
        const char *what;
    } t[] = {
        { "x.bz2", "BZh91AY&SY", 10, "bzip2 data" },
        { "x.png", "\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16, "PNG image" },
        { "x.obj", "\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16, "PNG image" },
        { "x.zip", "PK\x03\x04\x14\0\0\0", 8, "zip archive" },
        { "x.bin", "\0\0\0\0\x01\x02\x03", 7, "binary data" },
        { "x.obj", "\0\0\0\0\x01\x02\x03", 7, "binary data" },
        { "x.txt", "hello world\n", 12, "text" },
        { "x", "", 0, "empty file" },
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        save(tmp(t[i].name), t[i].data, t[i].n);
        cr_assert_eq(mesh_load(&M, tmp(t[i].name), E, sizeof E), -1, "%s", t[i].name);
        char want[160];
        snprintf(want, sizeof want, "%s: not a model zview can read (%s; formats: obj stl ply off",
                 tmp(t[i].name), t[i].what);
        cr_assert_eq(strncmp(E, want, strlen(want)), 0, "'%s' is not '%s...'", E, want);
        cr_assert_null(strchr(E, '\n'));
    }
    /* an empty .obj is still the OBJ loader's to refuse */
    save(tmp("e.obj"), "", 0);
    cr_assert_eq(mesh_load(&M, tmp("e.obj"), E, sizeof E), -1);
    cr_assert_not_null(strstr(E, "e.obj: no faces (empty file)"), "%s", E);
}

/* ==== Standard input ==== */

/* Load "-" with `data` written into standard input by a child. */
static int load_stdin(const void *data, size_t n, const char *format)
{
    int p[2];
    cr_assert_eq(pipe(p), 0);
    pid_t pid = fork();
    cr_assert_geq(pid, 0);
    if (pid == 0) {
        close(p[0]);
        signal(SIGPIPE, SIG_DFL);
        const char *c = data;
        while (n) {
            ssize_t w = write(p[1], c, n);
            if (w <= 0)
                _exit(0);
            c += w;
            n -= (size_t)w;
        }
        _exit(0);
    }
    close(p[1]);
    int saved = dup(0);
    dup2(p[0], 0);
    close(p[0]);
    int r = mesh_load_as(&M, "-", format, E, sizeof E);
    dup2(saved, 0);
    close(saved);
    kill(pid, SIGKILL);
    waitpid(pid, NULL, 0);
    return r;
}

Test(formats, standard_input_every_native_format)
{
    const char *texts[] = { tri_obj, tri_off, tri_ply, tri_stl };
    for (int i = 0; i < 4; i++) {
        cr_assert_eq(load_stdin(texts[i], strlen(texts[i]), NULL), 0, "%s", E);
        cr_assert_eq(M.nfaces, 1);
        cr_assert_str_eq(M.path, "stdin");
        mesh_free(&M);
    }
    /* binary STL: told by its size, which a stream shows only at its end */
    cr_assert_eq(mesh_parse_buffer(&M, "t.obj", NULL, tri_obj, strlen(tri_obj), E, sizeof E), 0);
    size_t ns, np;
    char *stl = w_stl_binary(&M, &ns);
    char *ply = w_ply_binary(&M, 0, &np);
    mesh_free(&M);
    cr_assert_eq(load_stdin(stl, ns, NULL), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "stl binary");
    mesh_free(&M);
    cr_assert_eq(load_stdin(ply, np, NULL), 0, "%s", E);
    cr_assert_str_eq(M.info.format, "ply binary little endian");
    mesh_free(&M);
    /* and --format where content cannot tell */
    static const char bare[] = "3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    cr_assert_eq(load_stdin(bare, sizeof bare - 1, NULL), -1);
    cr_assert_eq(load_stdin(bare, sizeof bare - 1, "off"), 0, "%s", E);
    free(stl);
    free(ply);
}

Test(formats, standard_input_of_zeros_stops_early)
{
    /* 64 MB of zeros: refused after the first bytes, not read whole */
    size_t n = (size_t)64 << 20;
    char *z = calloc(1, n);
    double t0 = ms_now();
    long long read0 = bytes_read();
    cr_assert_eq(load_stdin(z, n, NULL), -1);
    cr_assert_lt(ms_now() - t0, 3000 * SLOW);
    long long got = bytes_read() - read0;
    cr_assert(read0 >= 0 && got < (8 << 20), "%lld bytes of standard input read", got);
    cr_assert_not_null(strstr(E, "stdin: not a model zview can read (binary data"), "%s", E);
    free(z);
}

/* ==== Hostile inputs (issue 7) ==== */

Test(formats, mtllib_naming_itself_on_every_line, .init = cr_redirect_stderr)
{
    /* 20,000 lines naming the OBJ itself (and by another name): each
     * file is read once, so this is linear (it took 21 s) */
    const char *path = tmp("self.obj");
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f, "newmtl red\nKd 1 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    for (int i = 0; i < 20000; i++)
        fprintf(f, i % 2 ? "mtllib self.obj\n" : "mtllib ./self.obj\n");
    fclose(f);
    double t0 = ms_now();
    /* as the command line loads it: newmtl and Kd are no OBJ
     * statements, skipped (strict would refuse the file) */
    MeshLoadOpts lenient = { .strict = 0 };
    cr_assert_eq(mesh_load_ex(&M, path, &lenient, E, sizeof E), 0, "%s", E);
    cr_assert_lt(ms_now() - t0, 2000 * SLOW, "took %.0f ms", ms_now() - t0);
    cr_assert_eq(M.info.skipped, 2);
    cr_assert_eq(M.nmats, 1, "the library was read once");
    cr_assert_eq(mesh_face_mat(&M, 0), 0);
    cr_assert_eq(M.mats[0].kd[0], 1.0f);
}

/* Were the FIFO opened, this would wait for ever: alarm() ends the
 * test's process then (not Criterion's .timeout, which leaks a little
 * under LeakSanitizer when two tests with time limits run at once). */
Test(formats, mtllib_naming_a_fifo_does_not_block, .init = cr_redirect_stderr)
{
    alarm(60);
    char fifo[300], obj[300];
    snprintf(fifo, sizeof fifo, "%s", tmp("pipe.mtl"));
    snprintf(obj, sizeof obj, "%s", tmp("f.obj"));
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    static const char s[] = "mtllib pipe.mtl\nmtllib /dev/stdin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    save(obj, s, sizeof s - 1);
    /* standard input a pipe too, which /dev/stdin would wait on */
    int p[2];
    cr_assert_eq(pipe(p), 0);
    int saved = dup(0);
    dup2(p[0], 0);
    int r = mesh_load(&M, obj, E, sizeof E);
    dup2(saved, 0);
    close(saved);
    close(p[0]);
    close(p[1]);
    cr_assert_eq(r, 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    fflush(stderr);
    char want[1024];
    snprintf(want, sizeof want,
             "zview: warning: %s:1: cannot open material library 'pipe.mtl' (refused: a FIFO)\n"
             "zview: warning: %s:2: cannot open material library '/dev/stdin' (refused: an absolute path outside "
             "the model's folder)\n",
             obj, obj);
    cr_assert_stderr_eq_str(want);
}

static long max_rss_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

Test(formats, sparse_2gb_file_refused_without_paging_it_in)
{
    /* A 2 GB hole: refused from its first bytes, under whatever name. */
    const char *names[] = { "big.obj", "big.stl", "big.ply", "big.off", "big" };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        const char *path = tmp(names[i]);
        int fd = open(path, O_CREAT | O_WRONLY | O_TRUNC, 0600);
        cr_assert_geq(fd, 0);
        cr_assert_eq(ftruncate(fd, (off_t)2 << 30), 0);
        close(fd);
        long rss0 = max_rss_kb();
        double t0 = ms_now();
        cr_assert_eq(mesh_load(&M, path, E, sizeof E), -1, "%s", names[i]);
        double ms = ms_now() - t0;
        cr_assert_lt(ms, 1000 * SLOW, "%s: %.0f ms", names[i], ms);
        cr_assert_lt(max_rss_kb() - rss0, 64 * 1024, "%s: %ld KB more resident", names[i],
                     max_rss_kb() - rss0);
        /* a binary STL has no magic: by its name it gets the STL's word */
        const char *want = i == 1 ? "the header's count, 0 triangles, makes 84 bytes" : "binary data";
        cr_assert_not_null(strstr(E, want), "%s: %s", names[i], E);
        unlink(path);
    }
}

Test(formats, obj_with_a_valid_start_then_zeros_reads_a_window_only)
{
    /* a real first line, then 1 GB of zeros: the error comes from the
     * first window, not after paging in the whole file */
    const char *path = tmp("late.obj");
    int fd = open(path, O_CREAT | O_WRONLY | O_TRUNC, 0600);
    cr_assert_geq(fd, 0);
    for (int i = 0; i < 1024; i++)
        cr_assert_eq(write(fd, "v 0 0 0\n", 8), 8);
    cr_assert_eq(ftruncate(fd, (off_t)1 << 30), 0);
    close(fd);
    long rss0 = max_rss_kb();
    double t0 = ms_now();
    cr_assert_eq(mesh_load(&M, path, E, sizeof E), -1);
    double ms = ms_now() - t0;
    cr_assert_lt(ms, 1000 * SLOW, "%.0f ms of CPU", ms);
    cr_assert_lt(max_rss_kb() - rss0, 64 * 1024, "%ld KB more resident", max_rss_kb() - rss0);
    cr_assert_str_eq(E + strlen(path), ":1025: binary or unreadable data");
    unlink(path);
}

Test(formats, huge_index_printed_whole)
{
    static const char s[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9223372036854775808\n";
    cr_assert_eq(mesh_parse(&M, "t.obj", s, sizeof s - 1, E, sizeof E), -1);
    cr_assert_str_eq(E, "t.obj:4: vertex index 9223372036854775808 out of range (3 vertices)");
    static const char s2[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -123456789012345678901234567890\n";
    cr_assert_eq(mesh_parse(&M, "t.obj", s2, sizeof s2 - 1, E, sizeof E), -1);
    cr_assert_str_eq(E, "t.obj:4: vertex index -123456789012345678901234567890 out of range "
                        "(3 vertices so far)");
}

Test(formats, cr_only_line_ends)
{
    static const char s[] = "# old Mac\rv 0 0 0\rv 1 0 0\rv 0 1 0\ro tri\rf 1 2 3\rf 1 2 4\r";
    cr_assert_eq(mesh_parse(&M, "t.obj", s, sizeof s - 1, E, sizeof E), -1);
    cr_assert_str_eq(E, "t.obj:7: vertex index 4 out of range (3 vertices)", "lines are counted");
    cr_assert_eq(mesh_parse(&M, "t.obj", s, sizeof s - 9, E, sizeof E), 0, "%s", E);
    cr_assert_eq(M.nfaces, 1);
    cr_assert_str_eq(M.objs[0].name, "tri");
}

/* ==== The same model in every format ==== */

typedef struct {
    const char *name;
    char *(*write)(const Mesh *, size_t *);
    int be;
} Writer;

static char *ply_le(const Mesh *m, size_t *n) { return w_ply_binary(m, 0, n); }
static char *ply_be(const Mesh *m, size_t *n) { return w_ply_binary(m, 1, n); }

static const Writer writers[] = {
    { "m.obj", w_obj, 0 },         { "m.stl", w_stl_binary, 0 }, { "m-ascii.stl", w_stl_ascii, 0 },
    { "m-le.ply", ply_le, 0 },     { "m-be.ply", ply_be, 0 },    { "m-ascii.ply", w_ply_ascii, 0 },
    { "m.off", w_off, 0 },
};

static void render_ids(Scene *s, int w, int h, uint32_t seed, int persp, FrameBufs *fb)
{
    tl_random_view(s, seed, persp);
    ScreenPolys sp = { 0 };
    HsrStats st;
    cr_assert_eq(tl_render(s, &hsr_zbuffer, 1, w, h, 0, &sp, fb, &st), 0);
    screen_free(&sp);
}

/* Load `src`, write it in every format, load each, and compare the
 * face-id buffers of several views with the original's. */
static void same_everywhere(const char *src, int nviews, int w, int h)
{
    Mesh m;
    cr_assert_eq(mesh_load(&m, src, E, sizeof E), 0, "%s", E);
    Scene ref;
    cr_assert_eq(tl_scene_from_file(&ref, src), 0);
    size_t npx = (size_t)w * h;
    FrameBufs *want = calloc((size_t)nviews, sizeof *want);
    for (int v = 0; v < nviews; v++)
        render_ids(&ref, w, h, (uint32_t)v, v & 1, &want[v]);
    scene_free(&ref);
    for (size_t i = 0; i < sizeof writers / sizeof writers[0]; i++) {
        size_t n;
        char *buf = writers[i].write(&m, &n);
        cr_assert_not_null(buf, "%s", writers[i].name);
        const char *path = tmp(writers[i].name);
        save(path, buf, n);
        free(buf);
        Scene s;
        cr_assert_eq(tl_scene_from_file(&s, path), 0, "%s", writers[i].name);
        cr_assert_eq(s.nfaces, m.nfaces);
        /* the geometry alone: an STL stands z-up (test_formats' stance tests) */
        scene_set_up(&s, UP_Y);
        for (int v = 0; v < nviews; v++) {
            FrameBufs fb = { 0 };
            render_ids(&s, w, h, (uint32_t)v, v & 1, &fb);
            cr_assert_eq(memcmp(fb.ids, want[v].ids, npx * sizeof *fb.ids), 0,
                         "%s: view %d: the face-id buffer differs from the OBJ's", writers[i].name, v);
            fbuf_free(&fb);
        }
        scene_free(&s);
        unlink(path);
    }
#ifdef ZV_ASSIMP
    /* through assimp: the same coverage (assimp may order faces its way) */
    size_t n;
    char *glb = w_glb(&m, &n);
    cr_assert_not_null(glb);
    save(tmp("m.glb"), glb, n);
    free(glb);
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, tmp("m.glb")), 0);
    cr_assert_eq(s.nfaces, m.nfaces);
    for (int v = 0; v < nviews; v++) {
        FrameBufs fb = { 0 };
        render_ids(&s, w, h, (uint32_t)v, v & 1, &fb);
        size_t diff = 0;
        for (size_t k = 0; k < npx; k++)
            diff += (fb.ids[k] >= 0) != (want[v].ids[k] >= 0);
        cr_assert_eq(diff, 0, "glb view %d: %zu pixels covered differently", v, diff);
        fbuf_free(&fb);
    }
    scene_free(&s);
#endif
    for (int v = 0; v < nviews; v++)
        fbuf_free(&want[v]);
    free(want);
    mesh_free(&m);
}

/* same_everywhere reads a GLB too when the build has assimp; say so when
 * it has not, so that the glTF checks are counted as skipped */
Test(formats, glb_through_assimp)
{
#ifndef ZV_ASSIMP
    cr_skip_test("built without assimp: the GLB checks of same_ids_in_every_format are left out");
#else
    cr_assert(mesh_format_valid("glb"), "built with assimp, yet glb is not a format");
#endif
}

Test(formats, same_ids_in_every_format_knot)
{
    same_everywhere("assets/knot.obj", 4, 160, 120);
}

/* Suite "models": the shared models, with make test-models. */
Test(models, same_ids_in_every_format_bunny)
{
    const char *p = tl_shared_model("stanford-bunny.obj");
    if (!p)
        cr_skip_test("../shared/models/stanford-bunny.obj not found");
    setup();
    same_everywhere(p, 4, 320, 240);
    teardown();
}

/* The dragon, with `make test-models`. */
Test(models, same_ids_in_every_format_dragon, .timeout = 3000)
{
    const char *p = getenv("ZV_MODELS") ? tl_shared_model("dragon.obj") : NULL;
    if (!p)
        cr_skip_test("set ZV_MODELS=1 with ../shared/models present (make test-models)");
    setup();
    same_everywhere(p, 2, 640, 480);
    teardown();
}

/* ==== How a model stands (issue 18) ==== */

/* A box 1 wide (x), 2 deep (y) and 3 tall (z), in triangles (what STL
 * holds) wound CCW from outside. */
static const char tall_z_box[] =
    "v 0 0 0\nv 1 0 0\nv 1 2 0\nv 0 2 0\nv 0 0 3\nv 1 0 3\nv 1 2 3\nv 0 2 3\n"
    "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";

/* The world's half extents as the plain front view sees them (x right,
 * y up, z towards the viewer): scene_build fits at no turn. */
static Vec3 stood(const Scene *s)
{
    return s->cam.fit_half;
}

Test(formats, stl_stands_z_up)
{
    Mesh m;
    cr_assert_eq(mesh_parse(&m, "box.obj", tall_z_box, sizeof tall_z_box - 1, E, sizeof E), 0, "%s", E);
    cr_expect_eq(m.info.up, UP_Y, "OBJ says nothing: y");
    cr_expect_eq(m.info.front, -1, "and has no front");
    cr_expect_str_eq(m.info.up_why, "obj: the format does not say");
    char *(*const writers_stl[2])(const Mesh *, size_t *) = { w_stl_binary, w_stl_ascii };
    for (int k = 0; k < 2; k++) {
        size_t n;
        char *buf = writers_stl[k](&m, &n);
        cr_assert_not_null(buf);
        const char *path = tmp(k ? "box-ascii.stl" : "box.stl");
        save(path, buf, n);
        free(buf);
        Scene sc;
        cr_assert_eq(tl_scene_from_file(&sc, path), 0);
        const MeshInfo *in = &sc.meshes[0].info;
        cr_expect_eq(in->up, UP_Z, "%s", path);
        cr_expect_eq(in->front, -1);
        cr_expect_str_eq(in->up_why, "STL: the 3D-printing convention");
        cr_expect_eq(sc.objs[0].up, UP_Z, "the object stands as its file says");
        Vec3 h = stood(&sc);
        cr_expect_float_eq(h.y, 1.5f, 1e-5, "%s: 3 tall, standing: half height %g", path, h.y);
        cr_expect_float_eq(h.z, 1.0f, 1e-5, "2 deep: half depth %g", h.z);
        scene_free(&sc);
    }
    mesh_free(&m);
}

#ifdef ZV_ASSIMP
Test(formats, gltf_is_y_up_and_faces_z)
{
    Mesh m;
    cr_assert_eq(mesh_parse(&m, "box.obj", tall_z_box, sizeof tall_z_box - 1, E, sizeof E), 0, "%s", E);
    size_t n;
    char *glb = w_glb(&m, &n);
    cr_assert_not_null(glb);
    save(tmp("box.glb"), glb, n);
    free(glb);
    mesh_free(&m);
    Scene sc;
    cr_assert_eq(tl_scene_from_file(&sc, tmp("box.glb")), 0);
    const MeshInfo *in = &sc.meshes[0].info;
    cr_expect_eq(in->up, UP_Y);
    cr_expect_eq(in->front, UP_Z, "glTF's front faces +z");
    cr_expect_str_eq(in->up_why, "glTF: y-up by its specification, the front towards +z");
    cr_expect_float_eq(stood(&sc).z, 1.5f, 1e-5, "not turned: the 3 along z stays along z");
    scene_free(&sc);
}

/* A COLLADA document of one triangle reaching 3 along its up axis. */
static char *collada_doc(const char *up_axis)
{
    static char doc[2048];
    snprintf(doc, sizeof doc,
             "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
             "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
             "<asset><unit name=\"meter\" meter=\"1\"/>%s%s%s</asset>\n"
             "<library_geometries><geometry id=\"g\" name=\"g\"><mesh>\n"
             "<source id=\"p\"><float_array id=\"pa\" count=\"9\">0 0 0 1 0 0 0 0 3</float_array>\n"
             "<technique_common><accessor source=\"#pa\" count=\"3\" stride=\"3\">\n"
             "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
             "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
             "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
             "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>0 1 2</p>"
             "</triangles>\n</mesh></geometry></library_geometries>\n"
             "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\" name=\"n\">"
             "<instance_geometry url=\"#g\"/></node></visual_scene></library_visual_scenes>\n"
             "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n",
             up_axis ? "<up_axis>" : "", up_axis ? up_axis : "", up_axis ? "</up_axis>" : "");
    return doc;
}

static float max_coord(const Mesh *m, int axis)
{
    float v = -INFINITY;
    for (uint32_t i = 0; i < m->nverts; i++)
        v = fmaxf(v, m->pos[3 * i + axis]);
    return v;
}

/* assimp turns a Z_UP document upright itself (on the root node): the
 * model arrives y-up and is not turned a second time. */
Test(formats, collada_up_axis_is_applied_once)
{
    const char *doc = collada_doc("Z_UP");
    save(tmp("z.dae"), doc, strlen(doc));
    Scene sc;
    cr_assert_eq(tl_scene_from_file(&sc, tmp("z.dae")), 0);
    const Mesh *m = &sc.meshes[0];
    cr_expect_float_eq(max_coord(m, 1), 3.0f, 1e-6, "assimp turned z to y: top %g", max_coord(m, 1));
    cr_expect_eq(m->info.up, UP_Y, "so it stands y-up");
    cr_expect_eq(sc.objs[0].up, UP_Y, "not turned again");
    cr_expect_str_eq(m->info.up_why, "COLLADA: up_axis Z_UP, turned upright by assimp");
    scene_free(&sc);
    /* from memory too (standard input), and the other spellings */
    Mesh mm;
    cr_assert_eq(mesh_parse_buffer(&mm, NULL, "dae", doc, strlen(doc), E, sizeof E), 0, "%s", E);
    cr_expect_str_eq(mm.info.up_why, "COLLADA: up_axis Z_UP, turned upright by assimp");
    mesh_free(&mm);
    doc = collada_doc("Y_UP");
    cr_assert_eq(mesh_parse_buffer(&mm, NULL, "dae", doc, strlen(doc), E, sizeof E), 0, "%s", E);
    cr_expect_str_eq(mm.info.up_why, "COLLADA: up_axis Y_UP");
    cr_expect_float_eq(max_coord(&mm, 2), 3.0f, 1e-6, "Y_UP: left as it is");
    mesh_free(&mm);
    doc = collada_doc(NULL);
    cr_assert_eq(mesh_parse_buffer(&mm, NULL, "dae", doc, strlen(doc), E, sizeof E), 0, "%s", E);
    cr_expect_str_eq(mm.info.up_why, "COLLADA: no up_axis, so Y_UP");
    mesh_free(&mm);
}

/* Files of Debian's assimp-testmodels (tools/deps.sh installs it). */
#define AI_MODELS "/usr/share/assimp/models/"

typedef struct {
    const char *file;
    int         up, front;
    const char *why;
} Stance;

Test(formats, stance_of_the_test_models)
{
    static const Stance want[] = {
        { "FBX/embedded_ascii/box.FBX", UP_Z, UP_NEG_Y, "FBX: UpAxis +z, FrontAxis -y" },
        { "FBX/spider.fbx", UP_Y, UP_Z, "FBX: UpAxis +y, FrontAxis +z" },
        { "3MF/box.3mf", UP_Z, -1, "3MF: z-up by its specification" },
        { "AMF/test1.amf", UP_Z, -1, "AMF: z-up by its specification" },
        { "BLEND/HUMAN.blend", UP_Z, UP_NEG_Y, "Blender: z-up, the front towards -y" },
        { "Q3D/E-AT-AT.q3o", UP_Z, -1, "Quick3D: z-up, as its files are written" },
        { "COB/dwarf.cob", UP_Z, -1, "trueSpace: z-up" },
        { "SMD/holy_grailref.smd", UP_Z, -1, "SMD: z-up, as in Valve's engines" },
        { "Collada/lights.dae", UP_Y, -1, "COLLADA: up_axis Z_UP, turned upright by assimp" },
        { "3DS/fels.3ds", UP_Y, -1, "3ds (assimp): the format does not say" },
    };
    if (access(AI_MODELS, R_OK) != 0)
        cr_skip_test("no " AI_MODELS ": install assimp-testmodels (sh tools/deps.sh)");
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        char path[256];
        snprintf(path, sizeof path, AI_MODELS "%s", want[i].file);
        Mesh m;
        cr_assert_eq(mesh_load(&m, path, E, sizeof E), 0, "%s", E);
        cr_expect_eq(m.info.up, want[i].up, "%s: up %d", want[i].file, m.info.up);
        cr_expect_eq(m.info.front, want[i].front, "%s: front %d", want[i].file, m.info.front);
        cr_expect_str_eq(m.info.up_why, want[i].why, "%s", want[i].file);
        mesh_free(&m);
    }
}
#endif

/* ==== The command line's new options ==== */

static int cli(Options *o, char *err, int n, const char **args)
{
    char *argv[16];
    argv[0] = "zview";
    for (int i = 0; i < n; i++)
        argv[i + 1] = (char *)args[i];
    argv[n + 1] = NULL;
    return cli_parse(n + 1, argv, o, err, 256);
}
#define CLI(o, err, ...)                                                        \
    cli(o, err, (int)(sizeof((const char *[]){ __VA_ARGS__ }) / sizeof(char *)), \
        (const char *[]){ __VA_ARGS__ })

Test(formats, cli_options)
{
    Options o;
    char err[256];
    cr_assert_eq(CLI(&o, err, "--format=stl", "--up", "-z", "--flip", "-"), 0, "%s", err);
    cr_assert_str_eq(o.format, "stl");
    cr_assert_eq(o.up, UP_NEG_Z);
    cr_assert(o.flip);
    cr_assert_str_eq(o.files[0], "-");
    cr_assert_eq(CLI(&o, err, "m.obj"), 0);
    cr_assert_eq(o.up, -1, "by default each file stands as its format says");
    cr_assert_null(o.format);
    cr_assert_eq(CLI(&o, err, "--formats"), 0);
    cr_assert(o.formats);
    cr_assert_eq(CLI(&o, err, "-o", "-", "m.obj"), 0, "%s", err);
    cr_assert_str_eq(o.out, "-");
    cr_assert_eq(CLI(&o, err, "--image-format=ppm", "-oimage", "m.obj"), 0, "%s", err);
    cr_assert_eq(o.image_format, IMG_PPM);

    cr_assert_eq(CLI(&o, err, "--format", "zip", "m.obj"), -1);
    cr_assert_not_null(strstr(err, "bad value 'zip' for --format"), "%s", err);
    cr_assert_eq(CLI(&o, err, "--up", "w"), -1);
    cr_assert_eq(CLI(&o, err, "-", "-"), -1);
    cr_assert_not_null(strstr(err, "standard input) given twice"), "%s", err);
    cr_assert_eq(CLI(&o, err, "-o", "image", "m.obj"), -1);
    cr_assert_eq(CLI(&o, err, "-p", "-o", "-", "m.obj"), -1);
    cr_assert_eq(CLI(&o, err, "--image-format", "gif"), -1);
}

/* Not a test: with ZV_FORMATS_OUT=DIR (tools/bench-formats.sh), write
 * ZV_FORMATS_MODEL (default the dragon) into DIR in every format, for
 * the README's load figures. Suite "tools": neither make test nor make
 * test-models runs it. */
Test(tools, write_formats, .timeout = 3000)
{
    const char *out = getenv("ZV_FORMATS_OUT");
    const char *src = getenv("ZV_FORMATS_MODEL");
    if (!src)
        src = tl_shared_model("dragon.obj");
    if (!out || !src)
        cr_skip_test("set ZV_FORMATS_OUT=DIR (tools/bench-formats.sh)");
    Mesh m;
    cr_assert_eq(mesh_load(&m, src, E, sizeof E), 0, "%s", E);
    const struct {
        const char *name;
        char *(*write)(const Mesh *, size_t *);
    } t[] = {
        { "model.obj", w_obj },         { "model.stl", w_stl_binary }, { "model-ascii.stl", w_stl_ascii },
        { "model-le.ply", ply_le },     { "model-be.ply", ply_be },    { "model-ascii.ply", w_ply_ascii },
        { "model.off", w_off },         { "model.glb", w_glb },
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        size_t n;
        char *buf = t[i].write(&m, &n);
        cr_assert_not_null(buf, "%s", t[i].name);
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", out, t[i].name);
        save(path, buf, n);
        free(buf);
    }
    mesh_free(&m);
}
