/* test_hostile.c: the loaders against hostile input (issue 16): a file
 * that changes while it is read, material libraries of zeros or too big,
 * streams of garbage, counts that the file allows and memory does not,
 * byte-order marks and mixed line ends, warnings that would flood, and
 * polygons of many corners parsed in linear time. Big inputs are sparse
 * files in a temporary folder, made on the fly. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "mesh.h"
#include "../src/mesh/reader.h"

static char Dir[64];
static Mesh M;
static char E[512];

static void setup(void)
{
    snprintf(Dir, sizeof Dir, "/tmp/zv-hostile-XXXXXX");
    cr_assert_not_null(mkdtemp(Dir));
    signal(SIGPIPE, SIG_IGN);   /* a stream zview stops reading */
}

static void teardown(void)
{
    mesh_free(&M);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", Dir);
    cr_expect_eq(system(cmd), 0);
}

TestSuite(hostile, .init = setup, .fini = teardown);

/* Dir/name, into buf. */
static const char *at(const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/%s", Dir, name);
    return buf;
}

static void write_file(const char *path, const void *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "%s", path);
    cr_assert_eq(fwrite(p, 1, n, f), n);
    cr_assert_eq(fclose(f), 0);
}

/* A file of `head` then zeros up to `size` bytes, holes on disk. */
static void sparse_file(const char *path, const void *head, size_t n, uint64_t size)
{
    write_file(path, head, n);
    cr_assert_eq(truncate(path, (off_t)size), 0);
}

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec / 1e9;
}

static int load(const char *path, const MeshLoadOpts *o)
{
    mesh_free(&M);
    return mesh_load_ex(&M, path, o, E, sizeof E);
}

/* An OBJ of `tris` triangles, some 40 bytes a line. */
static void big_obj(const char *path, int tris)
{
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    for (int i = 0; i < tris + 2; i++)
        fprintf(f, "v %d.000001 %d.000002 0.000003\n", i, i & 1);
    for (int i = 1; i <= tris; i++)
        fprintf(f, "f %d %d %d\n", i, i + 1, i + 2);
    cr_assert_eq(fclose(f), 0);
}

/* ==== A file that changes while it is read ==== */

typedef struct {
    const char *path;
    uint64_t    when, calls;
    off_t       to;
} Cut;

static void cut_file(void *arg, uint64_t pos)
{
    Cut *c = arg;
    c->calls++;
    if (pos >= c->when && c->to >= 0) {
        cr_assert_eq(truncate(c->path, c->to), 0);
        c->to = -1;
    }
}

Test(hostile, a_file_truncated_while_read_fails_changed_and_nothing_else, .init = cr_redirect_stderr)
{
    char path[128];
    at("big.obj", path, sizeof path);
    big_obj(path, 600000);          /* some 30 MB */
    Cut cut = { path, (uint64_t)4 << 20, 0, (off_t)1 << 20 };
    MeshLoadOpts o = { .strict = 0, .on_window = cut_file, .on_window_arg = &cut };
    /* without the copy into memory of its own this died of SIGBUS */
    cr_assert_eq(load(path, &o), -1);
    char want[192];
    snprintf(want, sizeof want, "%s: changed while reading", path);
    cr_expect_str_eq(E, want);
    cr_expect_gt(cut.calls, 2, "the window moved %llu times", (unsigned long long)cut.calls);
    cr_expect_null(M.pos);
    fflush(stderr);
    cr_expect_stderr_eq_str("", "nothing else is said");
}

/* The viewer's Esc: another thread sets MeshLoadOpts.cancel. Set here
 * when the window passes 4 MB of a 30 MB file: the load stops within a
 * window's length and fails "cancelled", not "changed", reading no more. */
typedef struct {
    int      flag;
    uint64_t last;
} Stop;

static void stop_at_4mb(void *arg, uint64_t pos)
{
    Stop *st = arg;
    st->last = pos;
    if (pos >= (uint64_t)4 << 20)
        __atomic_store_n(&st->flag, 1, __ATOMIC_RELAXED);
}

Test(hostile, a_cancelled_load_stops_reading, .init = cr_redirect_stderr)
{
    char path[128];
    at("big.obj", path, sizeof path);
    big_obj(path, 600000);
    struct stat st;
    cr_assert_eq(stat(path, &st), 0);
    Stop stop = { 0, 0 };
    MeshProgress prog = { 0, 0 };
    MeshLoadOpts o = { .on_window = stop_at_4mb, .on_window_arg = &stop, .cancel = &stop.flag,
                       .progress = &prog };
    cr_assert_eq(load(path, &o), -1);
    char want[192];
    snprintf(want, sizeof want, "%s: cancelled", path);
    cr_expect_str_eq(E, want);
    cr_expect_null(M.pos);
    cr_expect_lt(stop.last, (uint64_t)st.st_size / 2, "read on to %llu of %lld bytes",
                 (unsigned long long)stop.last, (long long)st.st_size);
    fflush(stderr);
    cr_expect_stderr_eq_str("", "nothing else is said");
}

Test(hostile, each_format_survives_a_truncation)
{
    /* binary STL, binary PLY and XYZ go through other loops than OBJ's */
    char path[128];
    at("big.stl", path, sizeof path);
    uint32_t n = 500000;
    char hdr[84] = { 0 };
    memcpy(hdr + 80, &n, 4);
    sparse_file(path, hdr, sizeof hdr, 84 + 50 * (uint64_t)n);
    Cut cut = { path, (uint64_t)2 << 20, 0, 4096 };
    MeshLoadOpts o = { .strict = 1, .on_window = cut_file, .on_window_arg = &cut };
    cr_expect_eq(load(path, &o), -1);
    cr_expect(strstr(E, "changed while reading"), "%s", E);

    at("big.ply", path, sizeof path);
    const char *ph = "ply\nformat binary_little_endian 1.0\nelement vertex 2000000\n"
                     "property float x\nproperty float y\nproperty float z\nend_header\n";
    sparse_file(path, ph, strlen(ph), strlen(ph) + 24000000);
    cut = (Cut){ path, (uint64_t)3 << 20, 0, 100000 };
    cr_expect_eq(load(path, &o), -1);
    cr_expect(strstr(E, "changed while reading"), "%s", E);
}

Test(hostile, the_reader_turns_a_lost_page_into_zeros)
{
    char path[128], msg[256];
    at("r.bin", path, sizeof path);
    char *buf = malloc((size_t)24 << 20);
    cr_assert_not_null(buf);
    memset(buf, 'x', (size_t)24 << 20);
    write_file(path, buf, (size_t)24 << 20);
    free(buf);
    MeshFile f;
    cr_assert_eq(mf_open(&f, path, 0, msg, sizeof msg), 0, "%s", msg);
    cr_assert_eq(mf_load(&f, NULL, msg, sizeof msg), 0, "%s", msg);
    cr_assert_eq(truncate(path, 1 << 20), 0);
    /* read it all as a parser would (reporting every 64 KB) */
    size_t xs = 0;
    for (size_t i = 0; i < f.len; i++) {
        if ((i & 0xffff) == 0)
            mf_progress(&f, f.data + i);
        xs += f.data[i] == 'x';
    }
    cr_expect(mf_changed(&f));
    cr_expect_geq(xs, (size_t)1 << 20, "what was read before is the file's");
    cr_expect_lt(xs, (size_t)24 << 20, "what the file lost reads as zeros");
    mf_close(&f);
}

Test(hostile, a_file_rewritten_while_read_is_changed_too)
{
    char path[128];
    at("t.obj", path, sizeof path);
    big_obj(path, 300000);
    struct stat st;
    cr_assert_eq(stat(path, &st), 0);
    MeshFile f;
    char msg[256];
    cr_assert_eq(mf_open(&f, path, 0, msg, sizeof msg), 0);
    cr_assert_eq(mf_load(&f, NULL, msg, sizeof msg), 0);
    cr_expect_not(mf_changed(&f));
    /* the same size, new contents: the time tells */
    struct timespec t[2] = { { 0, UTIME_OMIT }, { st.st_mtim.tv_sec + 5, 0 } };
    cr_assert_eq(utimensat(AT_FDCWD, path, t, 0), 0);
    cr_expect(mf_changed(&f));
    mf_close(&f);
}

/* A file whose change shows only at the end (its time, not its size): the
 * load fails "changed while reading" and nothing else, not even the
 * summary of a statement the parser skipped in what it read. */
static void touch_at_end(void *arg, uint64_t pos)
{
    const char *path = arg;
    (void)pos;
    struct stat st;
    cr_assert_eq(stat(path, &st), 0);
    struct timespec t[2] = { { 0, UTIME_OMIT }, { st.st_mtim.tv_sec + 5, 0 } };
    cr_assert_eq(utimensat(AT_FDCWD, path, t, 0), 0);
}

Test(hostile, a_change_seen_at_the_end_says_only_that, .init = cr_redirect_stderr)
{
    char path[128];
    at("late.obj", path, sizeof path);
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n", f);
    cr_assert_eq(fclose(f), 0);
    MeshLoadOpts o = { .on_window = touch_at_end, .on_window_arg = path };
    cr_assert_eq(load(path, &o), -1);
    char want[192];
    snprintf(want, sizeof want, "%s: changed while reading", path);
    cr_expect_str_eq(E, want);
    fflush(stderr);
    cr_expect_stderr_eq_str("", "the skipped face is not reported");
}

/* ==== Material libraries ==== */

static const char mtl_obj[] = "mtllib z.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";

Test(hostile, a_sparse_material_library_is_refused_by_its_first_bytes)
{
    char obj[128], mtl[128];
    write_file(at("m.obj", obj, sizeof obj), mtl_obj, sizeof mtl_obj - 1);
    sparse_file(at("z.mtl", mtl, sizeof mtl), "", 0, (uint64_t)64 << 20);
    MeshLoadOpts o = { .strict = 0, .quiet = 1 };
    double t0 = cpu_s();
    cr_assert_eq(load(obj, &o), 0, "%s", E);
    /* 17 s before: every NUL a line of its own */
    cr_expect_lt(cpu_s() - t0, 0.5);
    cr_expect_eq(M.nmats, 0);
    cr_expect(strstr(M.info.first_warning, "z.mtl") && strstr(M.info.first_warning, "binary"), "%s",
              M.info.first_warning);
}

Test(hostile, a_material_library_stops_at_binary_data)
{
    char obj[128], mtl[128];
    write_file(at("m.obj", obj, sizeof obj), mtl_obj, sizeof mtl_obj - 1);
    /* a valid start past the first look (4 KB), then 32 MB of zeros */
    char head[8192];
    size_t hn = (size_t)snprintf(head, sizeof head, "newmtl a\nKd 1 0 0\n");
    while (hn < 6000)
        hn += (size_t)snprintf(head + hn, sizeof head - hn, "# a comment line\n");
    sparse_file(at("z.mtl", mtl, sizeof mtl), head, hn, (uint64_t)32 << 20);
    MeshLoadOpts o = { .strict = 0, .quiet = 1 };
    double t0 = cpu_s();
    cr_assert_eq(load(obj, &o), 0, "%s", E);
    cr_expect_lt(cpu_s() - t0, 0.5);
    cr_assert_eq(M.nmats, 1, "the material before the zeros is read");
    cr_expect_float_eq(M.mats[0].kd[0], 1.0f, 1e-6);
    cr_expect(strstr(M.info.first_warning, "z.mtl:") && strstr(M.info.first_warning, ": binary data"), "%s",
              M.info.first_warning);
}

Test(hostile, a_huge_material_library_is_not_read)
{
    char obj[128], mtl[128];
    write_file(at("m.obj", obj, sizeof obj), mtl_obj, sizeof mtl_obj - 1);
    static const char head[] = "newmtl a\nKd 1 0 0\n";
    sparse_file(at("z.mtl", mtl, sizeof mtl), head, sizeof head - 1, (uint64_t)4 << 30);
    MeshLoadOpts o = { .strict = 0, .quiet = 1 };
    double t0 = cpu_s();
    cr_assert_eq(load(obj, &o), 0, "%s", E);
    cr_expect_lt(cpu_s() - t0, 0.5);
    cr_expect_eq(M.nmats, 0);
    cr_expect(strstr(M.info.first_warning, "material library 'z.mtl' too large"), "%s", M.info.first_warning);
}

Test(hostile, missing_material_libraries_warn_a_few_times_then_count)
{
    char obj[128];
    FILE *f = fopen(at("m.obj", obj, sizeof obj), "w");
    cr_assert_not_null(f);
    for (int i = 0; i < 5000; i++)
        fprintf(f, "mtllib missing%d.mtl\n", i);
    fprintf(f, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    cr_assert_eq(fclose(f), 0);
    MeshLoadOpts o = { .strict = 0, .quiet = 1 };
    cr_assert_eq(load(obj, &o), 0, "%s", E);
    /* three by name and one count, not 5000 */
    cr_expect_eq(M.info.warnings, 4);
    cr_expect(strstr(M.info.first_warning, "missing0.mtl"), "%s", M.info.first_warning);
}

/* ==== Streams ==== */

typedef struct {
    int         fd;
    const char *head;
    size_t      nhead;
    uint64_t    total;      /* bytes to write in all; the rest after head is `fill` */
    int         fill;       /* a byte, or -1: pseudo-random */
    uint64_t    written;
} Feed;

static void *feed_main(void *arg)
{
    Feed *fd = arg;
    char buf[65536];
    uint64_t x = 88172645463325252ull;
    if (fd->nhead && write(fd->fd, fd->head, fd->nhead) == (ssize_t)fd->nhead)
        fd->written = fd->nhead;
    while (fd->written < fd->total) {
        for (size_t i = 0; i < sizeof buf; i++) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            buf[i] = fd->fill >= 0 ? (char)fd->fill : (char)x;
        }
        size_t n = fd->total - fd->written < sizeof buf ? (size_t)(fd->total - fd->written) : sizeof buf;
        ssize_t w = write(fd->fd, buf, n);
        if (w <= 0)
            break;          /* zview stopped reading */
        fd->written += (uint64_t)w;
    }
    close(fd->fd);
    return NULL;
}

/* Load what a thread writes into a pipe; how many bytes it got out. */
static uint64_t load_stream(Feed *feed, const MeshLoadOpts *o, int *rc)
{
    int p[2];
    cr_assert_eq(pipe(p), 0);
    feed->fd = p[1];
    pthread_t th;
    cr_assert_eq(pthread_create(&th, NULL, feed_main, feed), 0);
    char path[32];
    snprintf(path, sizeof path, "/dev/fd/%d", p[0]);
    *rc = load(path, o);
    close(p[0]);
    pthread_join(th, NULL);
    return feed->written;
}

Test(hostile, random_bytes_on_a_stream_are_refused_from_their_head)
{
    Feed feed = { .total = (uint64_t)1 << 30, .fill = -1 };
    MeshLoadOpts o = { .strict = 1 };
    int rc;
    uint64_t got = load_stream(&feed, &o, &rc);
    cr_expect_eq(rc, -1);
    cr_expect(strstr(E, "binary data"), "%s", E);
    /* before: read to 4 GiB */
    cr_expect_lt(got, (uint64_t)1 << 20, "%llu bytes taken", (unsigned long long)got);
}

Test(hostile, zeros_as_a_binary_stl_stop_at_the_count)
{
    Feed feed = { .total = (uint64_t)1 << 30, .fill = 0 };
    MeshLoadOpts o = { .format = "stl", .strict = 1 };
    int rc;
    uint64_t got = load_stream(&feed, &o, &rc);
    cr_expect_eq(rc, -1);
    cr_expect_lt(got, (uint64_t)1 << 20, "%llu bytes taken", (unsigned long long)got);
}

Test(hostile, a_ply_header_bounds_the_stream_after_it, .init = cr_redirect_stderr)
{
    static const char head[] = "ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
                               "property float x\nproperty float y\nproperty float z\n"
                               "element face 1000\nproperty list uchar int vertex_indices\nend_header\n";
    Feed feed = { .head = head, .nhead = sizeof head - 1, .total = (uint64_t)1 << 30, .fill = 0 };
    MeshLoadOpts o = { .strict = 0 };
    int rc;
    uint64_t got = load_stream(&feed, &o, &rc);
    (void)rc;
    /* 1000 records of 12 bytes, 1000 lists of at most 255 indices */
    cr_expect_lt(got, (uint64_t)8 << 20, "%llu bytes taken", (unsigned long long)got);
}

Test(hostile, a_stream_holds_no_more_than_memory_allows)
{
    /* text that never ends, with 64 MB to load it in */
    static const char head[] = "v 0 0 0\n";
    Feed feed = { .head = head, .nhead = sizeof head - 1, .total = (uint64_t)1 << 30, .fill = ' ' };
    MeshLoadOpts o = { .strict = 1, .max_bytes = (uint64_t)64 << 20 };
    int rc;
    uint64_t got = load_stream(&feed, &o, &rc);
    cr_expect_eq(rc, -1);
    cr_expect(strstr(E, "too large for the memory available"), "%s", E);
    cr_expect_lt(got, (uint64_t)40 << 20, "%llu bytes taken", (unsigned long long)got);
}

/* ==== Counts the file allows and memory does not ==== */

Test(hostile, a_sparse_binary_stl_is_refused_before_allocating)
{
    char path[128];
    at("big.stl", path, sizeof path);
    uint32_t n = (uint32_t)(((uint64_t)1 << 32) / 50 - 2);   /* 4.3 GB */
    char hdr[84] = { 0 };
    memcpy(hdr + 80, &n, 4);
    sparse_file(path, hdr, sizeof hdr, 84 + 50 * (uint64_t)n);
    MeshLoadOpts o = { .strict = 1, .max_polys = 20000000 };
    double t0 = cpu_s();
    cr_assert_eq(load(path, &o), -1);
    cr_expect_lt(cpu_s() - t0, 0.5, "3.6 GB were loaded before the refusal");
    char want[256];
    snprintf(want, sizeof want, "%s: 85,899,343 triangles, more than the limit of 20,000,000 polygons "
             "(--max-polys raises it)", path);
    cr_expect_str_eq(E, want);
    /* no polygon limit: memory refuses it, with the estimate */
    o.max_polys = 0;
    o.max_bytes = (uint64_t)2 << 30;
    cr_assert_eq(load(path, &o), -1);
    cr_expect(strstr(E, "big.stl: 85,899,343 triangles need about ") && strstr(E, "GB; 2.1 GB available"),
              "%s", E);
}

Test(hostile, sparse_plys_of_points_or_empty_faces_are_refused_by_their_header)
{
    char path[128];
    at("p.ply", path, sizeof path);
    const char *ph = "ply\nformat binary_little_endian 1.0\nelement vertex 350000000\n"
                     "property float x\nproperty float y\nproperty float z\nend_header\n";
    sparse_file(path, ph, strlen(ph), strlen(ph) + 350000000ull * 12);
    MeshLoadOpts o = { .strict = 0, .max_polys = 20000000 };
    cr_assert_eq(load(path, &o), -1);
    cr_expect(strstr(E, "p.ply: 350,000,000 points, more than the limit of 20,000,000"), "%s", E);

    at("f.ply", path, sizeof path);
    const char *fh = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                     "property float y\nproperty float z\nelement face 323000000\n"
                     "property list uchar int vertex_indices\nend_header\n";
    sparse_file(path, fh, strlen(fh), strlen(fh) + 36 + 323000000ull * 13);
    o.max_polys = 0;
    o.max_bytes = (uint64_t)1 << 30;
    double t0 = cpu_s();
    cr_assert_eq(load(path, &o), -1);
    cr_expect_lt(cpu_s() - t0, 0.5, "6.3 GB were allocated and filled before");
    cr_expect(strstr(E, "f.ply: 3 vertices and 323,000,000 faces need about "), "%s", E);
}

Test(hostile, growing_formats_stop_at_the_polygon_limit)
{
    /* points count: a cloud of 3000 is over a limit of 2000 */
    char xyz[40000];
    size_t n = 0;
    for (int i = 0; i < 3000; i++)
        n += (size_t)snprintf(xyz + n, sizeof xyz - n, "%d 0 0\n", i);
    MeshLoadOpts o = { .format = "xyz", .strict = 1, .max_polys = 2000 };
    mesh_free(&M);
    cr_expect_eq(mesh_parse_buffer_ex(&M, "c.xyz", &o, xyz, n, E, sizeof E), -1);
    cr_expect(strstr(E, "c.xyz: more than the limit of 2,000 polygons"), "%s", E);
    o.max_polys = 3000;
    cr_expect_eq(mesh_parse_buffer_ex(&M, "c.xyz", &o, xyz, n, E, sizeof E), 0, "%s", E);
    cr_expect_eq(M.npoints, 3000);
}

Test(hostile, growing_arrays_stop_at_the_memory_available)
{
    char path[128];
    at("g.obj", path, sizeof path);
    big_obj(path, 120000);      /* under 8 MB: not judged before parsing (below) */
    MeshLoadOpts o = { .strict = 1, .max_bytes = (uint64_t)2 << 20 };
    cr_assert_eq(load(path, &o), -1);
    cr_expect(strstr(E, "g.obj: the ") && strstr(E, "available"), "%s", E);
}

/* Issue 21: a big OBJ that cannot fit is refused before it is parsed,
 * from its size and lines of its start and end; the estimate leans low,
 * so the memory the whole mesh takes lets it through. */
Test(hostile, a_big_obj_is_judged_before_parsing)
{
    char path[128];
    at("g.obj", path, sizeof path);
    big_obj(path, 400000);
    MeshLoadOpts o = { .strict = 1, .max_bytes = (uint64_t)2 << 20 };
    cr_assert_eq(load(path, &o), -1);
    cr_expect(strstr(E, "g.obj: 22 MB of OBJ need at least about ") &&
                  strstr(E, "for the mesh (judged from lines of its start and end); 2 MB available"),
              "%s", E);
    /* what the finished mesh and its scene take (mb_estimate's terms) */
    o.max_bytes = (uint64_t)400002 * 12 + (uint64_t)400000 * (8 + 19 + 12);
    cr_expect_eq(load(path, &o), 0, "%s", E);
    cr_expect_eq(M.nfaces, 400000, "%u faces", M.nfaces);
}

/* ==== Byte-order marks and line ends ==== */

static int parse(const char *name, const char *text)
{
    mesh_free(&M);
    size_t n = strlen(text);
    char *copy = malloc(n ? n : 1);    /* exact size: ASan sees a read past it */
    memcpy(copy, text, n);
    int r = mesh_parse_buffer(&M, name, NULL, copy, n, E, sizeof E);
    free(copy);
    return r;
}

Test(hostile, every_format_takes_a_byte_order_mark)
{
    cr_expect_eq(parse("t.stl", "\xEF\xBB\xBFsolid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n"), 0, "%s", E);
    cr_expect_str_eq(M.info.format, "stl ascii");
    cr_expect_eq(M.nfaces, 1);
    cr_expect_eq(parse("t.ply", "\xEF\xBB\xBFply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                "property float y\nproperty float z\nelement face 1\n"
                                "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                                "3 0 1 2\n"), 0, "%s", E);
    cr_expect_eq(M.nfaces, 1);
    cr_expect_eq(parse("t.off", "\xEF\xBB\xBFOFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), 0, "%s", E);
    cr_expect_eq(M.nfaces, 1);
    /* detected without the name's help too */
    cr_expect_eq(parse("t", "\xEF\xBB\xBFOFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), 0, "%s", E);
    cr_expect_eq(parse("t", "\xEF\xBB\xBFply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                            "property float y\nproperty float z\nend_header\n0 0 0\n"), 0, "%s", E);
}

Test(hostile, a_first_line_ending_in_cr_then_lf_lines)
{
    cr_assert_eq(parse("c.obj", "# cube\rv 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 1 1\nv 1 0 0\nv 1 0 1\n"
                                "v 1 1 0\nv 1 1 1\nf 1 2 4 3\nf 5 6 8 7\n"), 0, "%s", E);
    cr_expect_eq(M.nverts, 8, "1 of 8 before");
    cr_expect_eq(M.nfaces, 2);
    cr_expect_eq(M.info.skipped, 0);
}

Test(hostile, any_mix_of_line_ends_in_every_text_format)
{
    cr_assert_eq(parse("m.obj", "v 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2 3\r"), 0, "%s", E);
    cr_expect_eq(M.nverts, 3);
    cr_expect_eq(M.nfaces, 1);
    cr_assert_eq(parse("m.off", "OFF\r3 1 0\r\n0 0 0\n1 0 0\r0 1 0\r\n3 0 1 2"), 0, "%s", E);
    cr_expect_eq(M.nfaces, 1);
    cr_assert_eq(parse("m.stl", "solid t\rfacet normal 0 0 1\r\nouter loop\nvertex 0 0 0\rvertex 1 0 0\r\n"
                                "vertex 0 1 0\nendloop\rendfacet\r\nendsolid t\r"), 0, "%s", E);
    cr_expect_eq(M.nfaces, 1);
    cr_assert_eq(parse("m.xyz", "0 0 0\r1 0 0\r\n0 1 0\n"), 0, "%s", E);
    cr_expect_eq(M.npoints, 3);
    cr_assert_eq(parse("m.ply", "ply\rformat ascii 1.0\r\nelement vertex 3\nproperty float x\r"
                                "property float y\nproperty float z\r\nend_header\r0 0 0\n1 0 0\r\n0 1 0\r"),
                 0, "%s", E);
    cr_expect_eq(M.npoints, 3);
    /* errors count the lines as they end */
    cr_expect_eq(parse("e.obj", "v 0 0 0\rv 1 0 0\r\nv 0 1 0\nbad 1\r"), -1);
    cr_expect(strstr(E, "e.obj:4:"), "%s", E);
}

Test(hostile, a_binary_ply_after_a_cr_only_header_may_start_with_lf)
{
    /* the header's lines end in CR: the body's first byte, 0x0A, is data */
    static const char h[] = "ply\rformat binary_little_endian 1.0\relement vertex 1\rproperty uchar n\r"
                            "property float x\rproperty float y\rproperty float z\rend_header\r";
    char buf[sizeof h - 1 + 13];
    memcpy(buf, h, sizeof h - 1);
    float v[3] = { 1, 2, 3 };
    buf[sizeof h - 1] = '\n';
    memcpy(buf + sizeof h, v, sizeof v);
    mesh_free(&M);
    cr_assert_eq(mesh_parse_buffer(&M, "b.ply", NULL, buf, sizeof buf, E, sizeof E), 0, "%s", E);
    cr_expect_float_eq(M.pos[2], 3.0f, 1e-6);
}

/* ==== Big polygons parse in linear time ==== */

/* CPU seconds to parse an OBJ of one face of n corners. */
static double face_time(int n)
{
    size_t cap = 32 + (size_t)n * 12, len = 0;
    char *t = malloc(cap);
    cr_assert_not_null(t);
    len += (size_t)snprintf(t, cap, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for (int i = 0; i < n; i++)
        len += (size_t)snprintf(t + len, cap - len, " %d", 1 + i % 3);
    t[len++] = '\n';
    mesh_free(&M);
    double t0 = cpu_s();
    int r = mesh_parse_buffer(&M, "f.obj", NULL, t, len, E, sizeof E);
    double dt = cpu_s() - t0;
    free(t);
    cr_assert_eq(r, 0, "%s", E);
    cr_assert_eq(M.face_start[1], (uint32_t)n);
    return dt;
}

Test(hostile, one_face_of_millions_of_corners_parses_in_linear_time)
{
    double a = face_time(500000), b = face_time(4000000);
    /* 8 times the corners: linear is 8 times the time, quadratic 64 */
    cr_expect_lt(b, 20 * a + 0.05, "%.3f s for 500k corners, %.3f s for 4M", a, b);
    cr_expect_lt(b, 2.0);
}

Test(hostile, ply_and_off_faces_of_many_corners_parse_quickly)
{
    int n = 1000000;
    size_t hl;
    char hdr[256];
    hl = (size_t)snprintf(hdr, sizeof hdr, "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                          "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                          "property list int int vertex_indices\nend_header\n");
    size_t len = hl + 36 + 4 + 4 * (size_t)n;
    char *b = calloc(1, len);
    cr_assert_not_null(b);
    memcpy(b, hdr, hl);
    float v[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    memcpy(b + hl, v, 36);
    memcpy(b + hl + 36, &n, 4);
    for (int i = 0; i < n; i++) {
        int k = i % 3;
        memcpy(b + hl + 40 + 4 * (size_t)i, &k, 4);
    }
    mesh_free(&M);
    double t0 = cpu_s();
    cr_assert_eq(mesh_parse_buffer(&M, "p.ply", NULL, b, len, E, sizeof E), 0, "%s", E);
    cr_expect_lt(cpu_s() - t0, 1.0);
    cr_expect_eq(M.face_start[1], (uint32_t)n);
    free(b);

    n = 100000;
    char *o = malloc(64 + 8 * (size_t)n);
    cr_assert_not_null(o);
    len = (size_t)sprintf(o, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n%d", n);
    for (int i = 0; i < n; i++)
        len += (size_t)sprintf(o + len, " %d", i % 3);
    o[len++] = '\n';
    mesh_free(&M);
    t0 = cpu_s();
    cr_assert_eq(mesh_parse_buffer(&M, "p.off", NULL, o, len, E, sizeof E), 0, "%s", E);
    cr_expect_lt(cpu_s() - t0, 1.0);
    cr_expect_eq(M.face_start[1], (uint32_t)n);
    free(o);
}
