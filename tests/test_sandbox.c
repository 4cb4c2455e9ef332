/* test_sandbox.c: the loading sandbox (issues 22, 28). A load in the
 * child gives the very arrays a load in-process gives (the wire loses
 * and invents nothing, textures included), whether the child is forked
 * here or by the fork server, from any number of threads at once; a
 * texture decoded in a child is the one decoded here, and a hostile one
 * stops at its bound; a result the child could have forged is refused
 * by the parent's checks; cancel ends the child; references beneath the
 * model's folder are the only ones opened; the default bound is what
 * budget.c says, and --info's words for it. */

#define _GNU_SOURCE

#include <criterion/criterion.h>
#include <errno.h>
#include <fcntl.h>
#include <png.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "../src/mesh/mesh_internal.h"
#include "../src/sandbox/sandbox_internal.h"
#include "sandbox.h"

#define SAME(a, b, n) ((!(a) && !(b)) || ((a) && (b) && memcmp((a), (b), (n)) == 0))

static void assert_same(const Mesh *a, const Mesh *b)
{
    cr_assert_eq(a->nverts, b->nverts);
    cr_assert_eq(a->nfaces, b->nfaces);
    cr_assert_eq(a->nmats, b->nmats);
    cr_assert_eq(a->nobjs, b->nobjs);
    cr_assert_eq(a->ntex, b->ntex);
    cr_assert_eq(a->nuv, b->nuv);
    cr_assert_str_eq(a->path, b->path);
    cr_assert(SAME(a->pos, b->pos, (size_t)a->nverts * 12));
    cr_assert(SAME(a->rgb, b->rgb, (size_t)a->nverts * 12));
    cr_assert(SAME(a->face_start, b->face_start, ((size_t)a->nfaces + 1) * 4));
    size_t nc = a->face_start ? a->face_start[a->nfaces] : 0;
    cr_assert(SAME(a->corner, b->corner, nc * 4));
    cr_assert(SAME(a->corner_uv, b->corner_uv, nc * 4));
    cr_assert(SAME(a->face_mat, b->face_mat, (size_t)a->nfaces * 4));
    cr_assert(SAME(a->mats, b->mats, (size_t)a->nmats * sizeof(Material)));
    cr_assert(SAME(a->objs, b->objs, (size_t)a->nobjs * sizeof(MeshObject)));
    cr_assert(SAME(a->uv, b->uv, (size_t)a->nuv * 8));
    for (uint32_t i = 0; i < a->ntex; i++) {
        cr_assert_str_eq(a->tex[i].name, b->tex[i].name);
        cr_assert_eq(a->tex[i].state, b->tex[i].state);
        cr_assert_eq(texture_bytes(&a->tex[i].img), texture_bytes(&b->tex[i].img));
        /* the sRGB levels crossed the wire; the 16-bit linear copy was
         * made again on this side and must be the same bytes */
        const Texture *ta = &a->tex[i].img, *tb = &b->tex[i].img;
        size_t srgb = ta->rgba ? (size_t)texture_bytes_for(ta->w, ta->h) : 0;
        cr_assert(SAME(ta->rgba, tb->rgba, srgb));
        cr_assert_eq(ta->lin != NULL, tb->lin != NULL);
        cr_assert(SAME(ta->lin, tb->lin, texture_bytes(ta) - srgb));
    }
    cr_assert_eq(a->info.warnings, b->info.warnings);
    cr_assert_str_eq(a->info.format, b->info.format);
}

static void load_both(const char *path)
{
    Mesh in, out;
    char e1[512], e2[512];
    MeshLoadOpts lo = { .quiet = 1 };
    SandboxOpts off = { .off = 1 }, on = { 0 };
    cr_assert_eq(sandbox_load(&in, path, &lo, &off, e1, sizeof e1), 0, "%s", e1);
    cr_assert_eq(sandbox_load(&out, path, &lo, &on, e2, sizeof e2), 0, "%s", e2);
    assert_same(&in, &out);
    mesh_free(&in);
    mesh_free(&out);
}

Test(sandbox, a_sandboxed_load_gives_the_same_mesh)
{
    cr_assert(sandbox_available());
    load_both("assets/demo.obj");       /* materials, objects */
    load_both("assets/torus.obj");
}

/* read(2) for this whole test binary, the sandbox's parent included: as
 * the system's, but one byte a call while ZV_TEST_READ_ONE is set. A
 * pipe may hand a reader any part of what was written: the parent must
 * put a child's message together whole however it comes (an honest
 * child writes each in one piece, which a pipe never splits; one whose
 * loader was taken over writes as it likes). */
ssize_t read(int fd, void *buf, size_t n)
{
    if (n > 1 && getenv("ZV_TEST_READ_ONE"))
        n = 1;
    return syscall(SYS_read, fd, buf, n);
}

Test(sandbox, a_childs_messages_read_a_byte_at_a_time_give_the_same_mesh)
{
    cr_assert_eq(setenv("ZV_TEST_READ_ONE", "1", 1), 0);
    load_both("assets/demo.obj");       /* names demo.mtl: a message of its path */
    load_both("assets/scene.obj");
    cr_assert_eq(unsetenv("ZV_TEST_READ_ONE"), 0);
}

/* write(2) for this whole test binary, the sandbox's child included
 * (it is a fork of it): as the system's, but while ZV_TEST_FORGE_REF is
 * set a child's message naming a file ('f', its kind, a 16-bit length,
 * the path) is sent with the length that variable gives and that many
 * bytes of path: what a child whose loader was taken over could send. */
ssize_t write(int fd, const void *buf, size_t n)
{
    const char *forge = getenv("ZV_TEST_FORGE_REF");
    const unsigned char *b = buf;
    if (forge && n >= 4 && b[0] == 'f' && n == 4 + ((size_t)b[2] | (size_t)b[3] << 8)) {
        size_t len = strtoul(forge, NULL, 10);
        unsigned char msg[4 + 4096];
        cr_assert(len <= 4096);
        msg[0] = 'f';
        msg[1] = b[1];
        msg[2] = (unsigned char)(len & 255);
        msg[3] = (unsigned char)(len >> 8);
        memset(msg + 4, 'a', len);
        return syscall(SYS_write, fd, msg, 4 + len) == (ssize_t)(4 + len) ? (ssize_t)n : -1;
    }
    return syscall(SYS_write, fd, buf, n);
}

/* A child that names a file of no bytes, or of more than REF_PATH_MAX
 * (more than it may send, and than the parent's buffer holds), broke the
 * protocol: it is stopped, and the load fails saying so. The longest
 * path it may send is taken. */
Test(sandbox, a_child_naming_a_path_too_long_or_empty_is_stopped)
{
    const struct { const char *len; int ok; } cases[] = { { "0", 0 }, { "4001", 0 }, { "4000", 1 }, { "7", 1 } };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cr_assert_eq(setenv("ZV_TEST_FORGE_REF", cases[i].len, 1), 0);
        Mesh m;
        char err[512] = "";
        MeshLoadOpts lo = { .quiet = 1 };
        SandboxOpts on = { 0 };
        int rc = sandbox_load(&m, "assets/demo.obj", &lo, &on, err, sizeof err);
        if (cases[i].ok) {
            cr_assert_eq(rc, 0, "a path of %s bytes: %s", cases[i].len, err);
            mesh_free(&m);
        } else {
            cr_assert_eq(rc, -1, "a path of %s bytes was taken", cases[i].len);
            cr_assert(strstr(err, "broke the sandbox's protocol"), "%s", err);
        }
    }
    cr_assert_eq(unsetenv("ZV_TEST_FORGE_REF"), 0);
}

Test(sandbox, textures_cross_the_wire)
{
    const char *p = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    cr_assert_eq(access(p, R_OK), 0, "assimp-testmodels is missing (tools/deps.sh)");
    Mesh m;
    char err[512];
    MeshLoadOpts lo = { .quiet = 1 };
    cr_assert_eq(sandbox_load(&m, p, &lo, NULL, err, sizeof err), 0, "%s", err);
    cr_assert_eq(m.ntex, 1);
    cr_assert_eq(m.tex[0].state, MTEX_OK);
    mesh_free(&m);
    load_both(p);
}

Test(sandbox, errors_read_as_in_process)
{
    Mesh a, b;
    char e1[512], e2[512];
    SandboxOpts off = { .off = 1 };
    cr_assert_eq(sandbox_load(&a, "/nonexistent/x.obj", NULL, &off, e1, sizeof e1), -1);
    cr_assert_eq(sandbox_load(&b, "/nonexistent/x.obj", NULL, NULL, e2, sizeof e2), -1);
    cr_assert_str_eq(e1, e2);
    cr_assert_eq(b.nverts, 0);
    cr_assert_null(b.pos);
}

Test(sandbox, a_set_cancel_ends_the_child)
{
    Mesh m;
    char err[512];
    int stop = 1;
    MeshLoadOpts lo = { .cancel = &stop };
    cr_assert_eq(sandbox_load(&m, "assets/torus.obj", &lo, NULL, err, sizeof err), -1);
    cr_assert_str_eq(err, "assets/torus.obj: cancelled");
}

Test(sandbox, a_buffer_loads_in_the_child)
{
    static const char obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    Mesh m;
    char err[512];
    cr_assert_eq(sandbox_parse_buffer(&m, "t.obj", NULL, NULL, obj, sizeof obj - 1, err, sizeof err), 0, "%s", err);
    cr_assert_eq(m.nverts, 3);
    cr_assert_eq(m.nfaces, 1);
    cr_assert_eq(m.corner[2], 2);
    mesh_free(&m);
}

/* ==== A forged result ==== */

/* The wire of the demo model in a memfd, mapped writable: *len bytes. */
static char *wire_of(const char *path, size_t *len, Mesh *m, int *fd_out)
{
    char err[512];
    cr_assert_eq(mesh_load(m, path, err, sizeof err), 0, "%s", err);
    int fd = memfd_create("t", 0);
    cr_assert(fd >= 0);
    cr_assert_eq(sandbox_wire_write(fd, m, 0, "", 0), 0);
    struct stat st;
    cr_assert_eq(fstat(fd, &st), 0);
    *len = (size_t)st.st_size;
    char *map = mmap(NULL, *len, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    cr_assert(map != MAP_FAILED);
    *fd_out = fd;
    return map;
}

/* The map is the memfd's, shared: what the test writes there is what
 * the reader reads through fd. */
static int read_back(int fd, size_t len, char *err, size_t errlen)
{
    Mesh m;
    int rc = 0;
    int r = sandbox_wire_read(fd, len, 0, &m, &rc, err, errlen);
    if (r == 0)
        mesh_free(&m);
    return r;
}

/* Offset of the bytes of `needle` (n bytes) in the map, after the header. */
static size_t find(const char *map, size_t len, const void *needle, size_t n)
{
    for (size_t i = 64; i + n <= len; i += 4)
        if (!memcmp(map + i, needle, n))
            return i;
    cr_assert_fail("not found");
    return 0;
}

Test(sandbox, a_forged_result_is_refused)
{
    Mesh m;
    size_t len;
    char err[256];
    int fd;
    char *map = wire_of("assets/demo.obj", &len, &m, &fd);
    cr_assert_eq(read_back(fd, len, err, sizeof err), 0, "%s", err);
    /* a corner index past the vertices */
    size_t at = find(map, len, m.corner, 16);
    uint32_t keep;
    memcpy(&keep, map + at, 4);
    uint32_t bad = m.nverts + 5;
    memcpy(map + at, &bad, 4);
    cr_assert_eq(read_back(fd, len, err, sizeof err), -1);
    cr_assert(strstr(err, "malformed mesh (faces)"), "%s", err);
    memcpy(map + at, &keep, 4);
    /* cut short: a span past the end */
    cr_assert_eq(read_back(fd, len - 64, err, sizeof err), -1);
    cr_assert(strstr(err, "malformed mesh"), "%s", err);
    /* no magic: the child died half-way */
    char m0 = map[0];
    map[0] ^= 1;
    cr_assert_eq(read_back(fd, len, err, sizeof err), -1);
    cr_assert(strstr(err, "no result"), "%s", err);
    map[0] = m0;
    /* a face_start that runs backwards */
    at = find(map, len, m.face_start, 12);
    uint32_t huge = 0xfffffff0u;
    memcpy(map + at + 4, &huge, 4);
    cr_assert_eq(read_back(fd, len, err, sizeof err), -1);
    munmap(map, len);
    close(fd);
    mesh_free(&m);
}

/* A texture whose first level's size is not its image's is refused:
 * the parent would read its texels past the bytes sent. The levels'
 * widths are w, w / 2, ... 1 (texture.h); the first made one less. */
Test(sandbox, a_forged_texture_level_is_refused)
{
    const char *p = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    cr_assert_eq(access(p, R_OK), 0, "assimp-testmodels is missing (tools/deps.sh)");
    Mesh m;
    size_t len;
    char err[256];
    int fd;
    char *map = wire_of(p, &len, &m, &fd);
    cr_assert_eq(m.ntex, 1);
    const Texture *t = &m.tex[0].img;
    cr_assert(t->rgba && t->levels > 1 && t->w > 1, "the texture decoded, with its levels");
    cr_assert_eq(read_back(fd, len, err, sizeof err), 0, "%s", err);
    size_t at = find(map, len, t->lw, (size_t)t->levels * sizeof *t->lw);
    int lw0 = t->w - 1;
    memcpy(map + at, &lw0, sizeof lw0);
    cr_assert_eq(read_back(fd, len, err, sizeof err), -1, "a first level %d texels wide for an image of %d", lw0,
                 t->w);
    cr_assert(strstr(err, "malformed mesh (textures)"), "%s", err);
    munmap(map, len);
    close(fd);
    mesh_free(&m);
}

/* ==== References beneath the model's folder ==== */

Test(sandbox, references_stay_beneath_the_folder)
{
    char dir[] = "/tmp/zv-ref-XXXXXX", p[600], why[200];
    cr_assert(mkdtemp(dir));
    snprintf(p, sizeof p, "mkdir -p %s/m/sub %s/out && echo x >%s/m/sub/ok.png && echo s >%s/out/s.bin && "
             "ln -s ../out/s.bin %s/m/out.bin && ln -s sub/ok.png %s/m/in.png && mkfifo %s/m/f",
             dir, dir, dir, dir, dir, dir, dir);
    cr_assert_eq(system(p), 0);
    char model[300], full[400];
    snprintf(model, sizeof model, "%s/m/x.obj", dir);
    struct { const char *ref; int ok; const char *why; } cases[] = {
        { "sub/ok.png", 1, NULL },
        { "sub/../sub/ok.png", 1, NULL },
        { "in.png", 1, NULL },                          /* a link that stays inside */
        { "../out/s.bin", 0, "'..' leads out" },
        { "sub/../../out/s.bin", 0, "'..' leads out" },
        { "out.bin", 0, "leads out of the model's folder" },
        { "f", 0, "a FIFO" },
        { "/dev/zero", 0, "an absolute path" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (cases[i].ref[0] == '/')
            snprintf(full, sizeof full, "%s", cases[i].ref);
        else
            snprintf(full, sizeof full, "%s/m/%s", dir, cases[i].ref);
        int fd = mesh_ref_open(model, full, why, sizeof why);
        if (cases[i].ok) {
            cr_assert(fd >= 0, "%s: %s", cases[i].ref, why);
            close(fd);
        } else {
            cr_assert_eq(fd, -1, "%s was opened", cases[i].ref);
            cr_assert(strstr(why, "refused: ") && strstr(why, cases[i].why), "%s: %s", cases[i].ref, why);
        }
    }
    snprintf(full, sizeof full, "%s/m/sub/ok.png", dir);
    cr_assert_eq(mesh_ref_open("-", full, why, sizeof why), -1);
    cr_assert_eq(mesh_ref_open(NULL, full, why, sizeof why), -1);
    snprintf(p, sizeof p, "rm -rf %s", dir);
    cr_assert_eq(system(p), 0);
}

/* Issue 28: names that are in the folder however they are written (an
 * absolute path to it, through a link to it, assimp's "m//name" and
 * "m//<absolute>", Blender's "//name", a name without the folder) open;
 * what leaves it (a sibling whose name starts alike, a link out, '..'
 * after "//") stays refused; a name that is not there is not a refusal
 * (assimp looking for optional files). */
Test(sandbox, references_in_the_folder_open_however_they_are_written)
{
    char dir[] = "/tmp/zv-ref-XXXXXX", p[700], why[200];
    cr_assert(mkdtemp(dir));
    snprintf(p, sizeof p, "mkdir -p %s/m/sub %s/mm %s/out && echo x >%s/m/sub/ok.png && echo s >%s/mm/s.bin && "
             "echo s >%s/out/s.bin && ln -s ../out/s.bin %s/m/out.bin && ln -s m %s/link",
             dir, dir, dir, dir, dir, dir, dir, dir);
    cr_assert_eq(system(p), 0);
    char model[300], full[900];
    snprintf(model, sizeof model, "%s/m/x.gltf", dir);
    struct { const char *fmt; int ok; const char *why; } cases[] = {
        { "%1$s/m/sub/ok.png", 1, NULL },               /* absolute, in the folder */
        { "%1$s/link/sub/ok.png", 1, NULL },            /* absolute, through a link to the folder */
        { "%1$s/m//sub/ok.png", 1, NULL },              /* assimp's "folder//name" */
        { "%1$s/m/%1$s/m/sub/ok.png", 1, NULL },        /* a uri naming its own folder, joined */
        { "%1$s/m/%1$s/m/sub/../../m/sub/ok.png", 1, NULL },
        { "%1$s/m/%1$s/link/sub/ok.png", 1, NULL },
        { "//sub/ok.png", 1, NULL },                    /* Blender: the blend file's folder */
        { "sub/ok.png", 1, NULL },                      /* a name without the folder */
        { "%1$s/m//nothere.bin", 0, "No such file" },
        { "%1$s/m/%1$s/m/nothere.bin", 0, "No such file" },
        { "%1$s/mm/s.bin", 0, "refused: an absolute path outside" },    /* /a/mm is not in /a/m */
        { "%1$s/m/%1$s/mm/s.bin", 0, "refused: an absolute path outside" },
        { "%1$s/m/%1$s/out/s.bin", 0, "refused: an absolute path outside" },
        { "%1$s/m/out.bin", 0, "leads out of the model's folder" },     /* a link out, absolute */
        { "%1$s/m/%1$s/m/out.bin", 0, "refused: an absolute path outside" },
        { "//../out/s.bin", 0, "'..' leads out" },
        { "%1$s/m//../out/s.bin", 0, "'..' leads out" },
        { "%1$s/out/nothere.bin", 0, "refused: an absolute path outside" },
        { "/etc/passwd", 0, "refused: an absolute path outside" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(full, sizeof full, cases[i].fmt, dir);
        int fd = mesh_ref_open(model, full, why, sizeof why);
        if (cases[i].ok) {
            cr_expect(fd >= 0, "%s: %s", full, why);
            if (fd >= 0)
                close(fd);
        } else {
            cr_expect_eq(fd, -1, "%s was opened", full);
            cr_expect(strstr(why, cases[i].why), "%s: %s", full, why);
        }
    }
    /* a model named relative to the working folder, a uri absolute */
    char cwd[600];
    cr_assert(getcwd(cwd, sizeof cwd));
    cr_assert_eq(chdir(dir), 0);
    snprintf(full, sizeof full, "m//%s/m/sub/ok.png", dir);
    int fd = mesh_ref_open("m/x.gltf", full, why, sizeof why);
    cr_expect(fd >= 0, "%s: %s", full, why);
    if (fd >= 0)
        close(fd);
    snprintf(full, sizeof full, "%s/m/sub/ok.png", dir);
    fd = mesh_ref_open("m/x.gltf", full, why, sizeof why);
    cr_expect(fd >= 0, "%s: %s", full, why);
    if (fd >= 0)
        close(fd);
    cr_assert_eq(chdir(cwd), 0);
    snprintf(p, sizeof p, "rm -rf %s", dir);
    cr_assert_eq(system(p), 0);
}

/* ==== The filter compiled once (issue 34) ==== */

/* The program the server makes once, with a child's numbers put in, is
 * instruction for instruction the one libseccomp compiles for those
 * numbers: the same rules, whatever the descriptors and the pid. (When
 * a number equals another constant of the rules, pid 2 and standard
 * error's 2, libseccomp shares the two comparisons' identical blocks:
 * 236 instructions, where the made program keeps 240 that say the same:
 * the markers are apart, and a child whose numbers coincide so (a pid
 * namespace's small pids) gets the unshared blocks, as strict.) */
Test(sandbox, the_filter_made_once_is_the_one_compiled_for_each_child)
{
    SandboxFilter made;
    cr_assert_eq(sandbox_filter_make(&made), 0);
    cr_assert_gt(made.len, 50);
    const uint32_t nums[][3] = { { 3, 4, 5 }, { 9, 7, 31337 }, { 250, 12, 4194303 }, { 1023, 1022, 65536 } };
    for (size_t t = 0; t < sizeof nums / sizeof nums[0]; t++) {
        SandboxFilter ref, got;
        cr_assert_eq(sandbox_filter_compile(&ref, nums[t][0], nums[t][1], nums[t][2]), 0);
        cr_assert_eq(sandbox_filter_patch(&made, &got, nums[t][0], nums[t][1], nums[t][2]), 0);
        cr_assert_eq(got.len, ref.len, "case %zu: %zu instructions, libseccomp's %zu", t, got.len, ref.len);
        cr_assert(memcmp(got.ins, ref.ins, ref.len * sizeof *ref.ins) == 0, "case %zu differs", t);
        /* and the markers were there to replace: the made program is not
         * the child's as it stands */
        cr_assert(memcmp(made.ins, ref.ins, ref.len * sizeof *ref.ins) != 0);
        sandbox_filter_free(&ref);
        sandbox_filter_free(&got);
    }
    sandbox_filter_free(&made);
    cr_assert_null(made.ins);
}

/* ==== The fork server (issue 28) ==== */

typedef struct {
    const SandboxOpts *so;
    const Mesh        *want;
    int                ok;
    char               err[512];
} Loader;

static void *load_five(void *arg)
{
    Loader *l = arg;
    MeshLoadOpts lo = { .quiet = 1 };
    for (int i = 0; i < 5; i++) {
        Mesh m;
        if (sandbox_load(&m, "assets/demo.obj", &lo, l->so, l->err, sizeof l->err) != 0)
            return NULL;
        int same = m.nfaces == l->want->nfaces && m.nverts == l->want->nverts &&
                   !memcmp(m.pos, l->want->pos, (size_t)m.nverts * 12) &&
                   !memcmp(m.corner, l->want->corner, (size_t)m.face_start[m.nfaces] * 4);
        mesh_free(&m);
        if (!same) {
            snprintf(l->err, sizeof l->err, "load %d: another mesh", i);
            return NULL;
        }
    }
    l->ok = 1;
    return NULL;
}

Test(sandbox, the_fork_server_serves_every_thread)
{
    SandboxOpts so = { 0 };
    cr_assert_eq(sandbox_server_start(&so.server), 0);
    cr_assert_gt(so.server.pid, 0);
    Mesh in, out;
    char err[512];
    MeshLoadOpts lo = { .quiet = 1 };
    SandboxOpts off = { .off = 1 };
    cr_assert_eq(sandbox_load(&in, "assets/demo.obj", &lo, &off, err, sizeof err), 0, "%s", err);
    cr_assert_eq(sandbox_load(&out, "assets/demo.obj", &lo, &so, err, sizeof err), 0, "%s", err);
    assert_same(&in, &out);
    cr_assert_eq(out.info.sandboxed, 1);
    mesh_free(&out);
    /* four threads at once, five loads each, through the one server */
    pthread_t th[4];
    Loader l[4];
    for (int i = 0; i < 4; i++) {
        l[i] = (Loader){ .so = &so, .want = &in };
        cr_assert_eq(pthread_create(&th[i], NULL, load_five, &l[i]), 0);
    }
    for (int i = 0; i < 4; i++) {
        pthread_join(th[i], NULL);
        cr_expect(l[i].ok, "thread %d: %s", i, l[i].err);
    }
    /* a server gone (a copy of its handle kept): the child is forked here */
    SandboxOpts stale = so;
    sandbox_server_stop(&so.server);
    cr_assert_eq(so.server.pid, 0);
    cr_assert_eq(sandbox_load(&out, "assets/demo.obj", &lo, &stale, err, sizeof err), 0, "%s", err);
    assert_same(&in, &out);
    mesh_free(&out);
    mesh_free(&in);
}

Test(sandbox, a_cancel_ends_a_child_of_the_server)
{
    SandboxOpts so = { 0 };
    cr_assert_eq(sandbox_server_start(&so.server), 0);
    Mesh m;
    char err[512];
    int stop = 1;
    MeshLoadOpts lo = { .cancel = &stop };
    cr_assert_eq(sandbox_load(&m, "assets/torus.obj", &lo, &so, err, sizeof err), -1);
    cr_assert_str_eq(err, "assets/torus.obj: cancelled");
    sandbox_server_stop(&so.server);
}

/* ==== Textures decoded in a child (issue 28) ==== */

static unsigned char *png_of(int w, int h, size_t *len)
{
    uint8_t *rgba = malloc((size_t)w * h * 4);
    for (int i = 0; i < w * h; i++) {
        rgba[4 * i] = (uint8_t)(i * 7);
        rgba[4 * i + 1] = (uint8_t)(i / w * 5);
        rgba[4 * i + 2] = (uint8_t)(i % w * 3);
        rgba[4 * i + 3] = 255;
    }
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)w;
    img.height = (png_uint_32)h;
    img.format = PNG_FORMAT_RGBA;
    png_alloc_size_t n = 0;
    cr_assert(png_image_write_to_memory(&img, NULL, &n, 0, rgba, 0, NULL));
    unsigned char *buf = malloc(n);
    cr_assert(png_image_write_to_memory(&img, buf, &n, 0, rgba, 0, NULL));
    free(rgba);
    *len = n;
    return buf;
}

Test(sandbox, a_texture_decoded_in_the_child_is_the_one_decoded_here)
{
    size_t len;
    unsigned char *png = png_of(64, 48, &len);
    MeshTexture t = { .name = "t.png", .data = png, .len = len };
    t.img.wrap_u = TEX_CLAMP;
    t.img.wrap_v = TEX_MIRROR;
    Texture a, b;
    int ha = -1, hb = -1;
    char e1[256], e2[256];
    SandboxOpts off = { .off = 1 }, on = { 0 };
    cr_assert_eq(sandbox_texture_decode(&t, &off, NULL, &a, &ha, e1, sizeof e1), 0, "%s", e1);
    cr_assert_eq(sandbox_texture_decode(&t, &on, NULL, &b, &hb, e2, sizeof e2), 0, "%s", e2);
    cr_assert_eq(a.w, b.w);
    cr_assert_eq(a.h, b.h);
    cr_assert_eq(a.levels, b.levels);
    cr_assert_eq(ha, hb);
    cr_assert_eq(b.wrap_u, TEX_CLAMP);
    cr_assert_eq(b.wrap_v, TEX_MIRROR);
    cr_assert_eq(texture_bytes(&a), texture_bytes(&b));
    cr_assert(!memcmp(a.rgba, b.rgba, texture_bytes_for(a.w, a.h)));
    cr_assert(a.lin && b.lin && !memcmp(a.lin, b.lin, texture_bytes(&a) - texture_bytes_for(a.w, a.h)));
    texture_free(&a);
    texture_free(&b);
    /* bytes that are no image: the decoder's reason, without the name */
    t.len = 40;
    cr_assert_eq(sandbox_texture_decode(&t, &on, NULL, &b, &hb, e2, sizeof e2), -1);
    cr_assert_eq(sandbox_texture_decode(&t, &off, NULL, &a, &ha, e1, sizeof e1), -1);
    cr_assert_str_eq(e1, e2);
    cr_assert_null(b.rgba);
    free(png);
}

/* tests/e2e/hugejpeg.py's JPEG: progressive, one grey component, a
 * header claiming side x side pixels, one DC scan of zero differences
 * (sixteen bytes of it), then the end: 134 bytes. */
static size_t hostile_jpeg(unsigned char *b, int side)
{
    static const unsigned char dht[] = { 0xFF, 0xC4, 0, 20, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
    static const unsigned char sos[] = { 0xFF, 0xDA, 0, 8, 1, 1, 0, 0, 0, 0 };
    size_t n = 0;
    b[n++] = 0xFF, b[n++] = 0xD8;
    b[n++] = 0xFF, b[n++] = 0xDB, b[n++] = 0, b[n++] = 67, b[n++] = 0;
    for (int i = 0; i < 64; i++)
        b[n++] = 1;
    unsigned char sof[] = { 0xFF, 0xC2, 0, 11, 8, (unsigned char)(side >> 8), (unsigned char)side,
                            (unsigned char)(side >> 8), (unsigned char)side, 1, 1, 0x11, 0 };
    memcpy(b + n, sof, sizeof sof);
    n += sizeof sof;
    memcpy(b + n, dht, sizeof dht);
    n += sizeof dht;
    memcpy(b + n, sos, sizeof sos);
    n += sizeof sos;
    memset(b + n, 0, 16);
    n += 16;
    b[n++] = 0xFF, b[n++] = 0xD9;
    return n;
}

Test(sandbox, a_hostile_jpeg_stops_at_its_bound_in_the_child)
{
    unsigned char jpg[256];
    size_t len = hostile_jpeg(jpg, 24000);
    cr_assert_eq(len, 134);
    int w = 0, h = 0;
    cr_assert_eq(texture_peek(jpg, len, &w, &h), 0, "a JPEG libjpeg reads");
    cr_assert_eq(w, 24000);
    MeshTexture t = { .name = "mid.jpg", .data = jpg, .len = len };
    Texture out;
    int halved;
    char err[512];
    /* its coefficients alone would take 1.1 GB (the viewer's own 1.17 GB
     * peak before issue 28): the decoder counts them before it starts
     * (texture/jpeg.c) and refuses in the child, by default against the
     * texture's own budget, with --max-memory against that; the child's
     * bound (512 MB by default) stands behind it */
    SandboxOpts def = { 0 }, small = { .max_memory = (uint64_t)64 << 20 };
    cr_assert_eq(sandbox_texture_decode(&t, &def, NULL, &out, &halved, err, sizeof err), -1);
    cr_expect(strstr(err, "24000x24000 progressive JPEG needs about"), "%s", err);
    cr_assert_null(out.rgba);
    cr_assert_eq(sandbox_texture_decode(&t, &small, NULL, &out, &halved, err, sizeof err), -1);
    cr_expect(strstr(err, "needs about") && strstr(err, "67 MB allowed"), "%s", err);
    /* a cancel ends the child */
    int stop = 1;
    cr_assert_eq(sandbox_texture_decode(&t, &def, &stop, &out, &halved, err, sizeof err), -1);
    cr_assert_str_eq(err, "cancelled");
}

/* ==== The default bound, and --info's words (issue 28) ==== */

Test(sandbox, the_default_bound)
{
    const uint64_t MB = (uint64_t)1 << 20;
    cr_assert_eq(sandbox_budget_of(0), 512 * MB);
    cr_assert_eq(sandbox_budget_of(600 * MB), 600 * MB);
    cr_assert_eq(sandbox_input_allowance(1000, 1), 4000);
    cr_assert_eq(sandbox_input_allowance(1000, 0), 48000);
    cr_assert_eq(sandbox_input_allowance(UINT64_MAX / 2, 0), UINT64_MAX, "saturates");
    /* an image: as many pixels as its bytes can hold, 8 bytes each, and 64 MB */
    cr_assert_eq(sandbox_image_allowance(100), 100 * 8256 * 8 + 64 * MB);
    cr_assert_eq(sandbox_image_allowance(40000), (uint64_t)16384 * 16384 * 8 + 64 * MB);
    cr_assert_eq(sandbox_image_allowance(UINT64_MAX), (uint64_t)16384 * 16384 * 8 + 64 * MB);
    uint64_t as, data;
    sandbox_thread_room(1, &as, &data);
    cr_assert_eq(as + data, 0);
    sandbox_thread_room(3, &as, &data);
    cr_assert_eq(as, 2 * 80 * MB);
    cr_assert_eq(data, 2 * 8 * MB);
}

Test(sandbox, what_info_says_protected_a_load)
{
    MeshInfo in = { .sandboxed = 1, .landlock = 7, .mem_bound = (uint64_t)512 << 20 };
    char b[160];
    sandbox_describe(&in, 0, b, sizeof b);
    cr_assert_str_eq(b, "seccomp, landlock (ABI 7), memory 512 MB");
    in.landlock = -ENOSYS;
    in.mem_bound = (uint64_t)5 << 30;
    sandbox_describe(&in, 0, b, sizeof b);
    cr_assert_str_eq(b, "seccomp, no landlock (not in this kernel), memory 5.0 GB");
    in.landlock = -EOPNOTSUPP;
    sandbox_describe(&in, 0, b, sizeof b);
    cr_assert_str_eq(b, "seccomp, no landlock (disabled at boot), memory 5.0 GB");
    in.sandboxed = 0;
    sandbox_describe(&in, 1, b, sizeof b);
    cr_assert_str_eq(b, "none (--no-sandbox)");
    sandbox_describe(&in, 0, b, sizeof b);
    cr_assert_str_eq(b, "none (this system has no seccomp filters)");
}
