/* fuzz_mesh.c: every native loader. The first byte picks the format and
 * the load's options, the rest is the file:
 *
 *   bits 0-2   format: obj stl ply off xyz, 5-7 = told by the content
 *   bit 3      lenient (skip what cannot be read) instead of strict
 *   bit 4      --points: every vertex a point
 *   bit 5      the wireframe
 *   bit 6      point size and line width - 1 (samples)
 *   bit 7      read as a stream (a pipe a thread writes into), the way
 *              `zview -` reads: decided from its head, within bounds;
 *              gzip data is decompressed on the way (seeds gz-*)
 *
 * The bytes go through mesh_parse_buffer (no path: no other file is
 * opened), or through mesh_load_ex on a pipe; the mesh's invariants are checked (every index in range,
 * objects' runs within the arrays, vertex ranges holding what they use:
 * abort otherwise), then scene_build, a small render through the
 * pipeline in two shadings, and every algorithm against the z-buffer on
 * it. A loader's message must name the input. */

#define _DEFAULT_SOURCE

#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "fuzz.h"
#include "testlib.h"

static const char *const formats[] = { "obj", "stl", "ply", "off", "xyz" };

#define CHECK(cond)                                                                 \
    do {                                                                            \
        if (!(cond)) {                                                              \
            fprintf(stderr, "fuzz_mesh: %s:%d: %s\n", __FILE__, __LINE__, #cond);   \
            abort();                                                                \
        }                                                                           \
    } while (0)

typedef struct {
    int            fd;
    const uint8_t *p;
    size_t         n;
} Feed;

static void *feed_main(void *arg)
{
    Feed *f = arg;
    while (f->n) {
        ssize_t w = write(f->fd, f->p, f->n);
        if (w <= 0)
            break;          /* the loader stopped reading */
        f->p += w;
        f->n -= (size_t)w;
    }
    close(f->fd);
    return NULL;
}

/* Load [p, p + n) from a pipe a thread fills; 0 or -1 as mesh_load_ex,
 * whose messages then name "/dev/fd/N". */
static int load_stream(Mesh *m, const MeshLoadOpts *opt, const uint8_t *p, size_t n, char *err,
                       size_t errlen, char *name, size_t namelen)
{
    int fds[2];
    if (pipe(fds))
        return -2;
    signal(SIGPIPE, SIG_IGN);
    Feed f = { fds[1], p, n };
    pthread_t th;
    if (pthread_create(&th, NULL, feed_main, &f)) {
        close(fds[0]);
        close(fds[1]);
        return -2;
    }
    snprintf(name, namelen, "/dev/fd/%d", fds[0]);
    int r = mesh_load_ex(m, name, opt, err, errlen);
    close(fds[0]);
    pthread_join(th, NULL);
    return r;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static TlAgree bufs;    /* kept: see fuzz_diff.c */
    if (size < 1)
        return 0;
    unsigned sel = data[0];
    /* quiet: a stream's loader would warn on stderr (the buffer's too) */
    MeshLoadOpts opt = { .format = (sel & 7) < 5 ? formats[sel & 7] : NULL, .strict = !(sel & 8),
                         .quiet = 1, .max_polys = 1000000 };
    Mesh *m = calloc(1, sizeof *m);
    char err[512], name[32] = "(input)";
    if (!m)
        return 0;
    int r = sel & 128 ? load_stream(m, &opt, data + 1, size - 1, err, sizeof err, name, sizeof name)
                      : mesh_parse_buffer_ex(m, NULL, &opt, data + 1, size - 1, err, sizeof err);
    if (r == -2) {
        free(m);
        return 0;           /* no pipe or thread: nothing tested */
    }
    if (r) {
        CHECK(strncmp(err, name, strlen(name)) == 0);
        CHECK(m->pos == NULL && m->nverts == 0);
        free(m);
        return 0;
    }
    const char *broken = tl_mesh_broken(m);
    if (broken) {
        fprintf(stderr, "fuzz_mesh: the mesh breaks '%s'\n", broken);
        abort();
    }
    if (sel & 16)
        mesh_as_points(m);
    Scene s;
    if (scene_build(&s, m, 1, err, sizeof err)) {
        mesh_free(m);
        free(m);
        return 0;
    }
    int samples = 1 + (int)(sel >> 6 & 1);
    Pipeline p;
    if (pipeline_init(&p, &s, hsr_find("zbuffer"), 1) == 0) {
        p.point_size = samples;
        p.line_width = samples;
        p.wireframe = (sel & 32) != 0;
        p.shade = SHADE_LAMBERT;
        if (pipeline_render(&p, 32, 20, 2.0f, 0, 1) == 0) {
            frame_empty_reason(&p);
            p.shade = SHADE_DEPTH;
            s.cam.persp = 1;
            s.cam.zoom = 3;     /* the eye inside: the near plane cuts */
            pipeline_render(&p, 32, 20, 2.0f, 1, 1);
            frame_empty_reason(&p);
        }
        pipeline_free(&p);
    }
    scene_reset(&s);
    bufs.style = (PrimStyle){ .point_size = samples, .line_width = samples, .wire = (sel & 32) != 0, .pixel = samples };
    Viewport vp = { 40, 28, 1.0f, 0 };
    char msg[512];
    TlView v = { 0.4f, -0.3f, 0.1f, 0.4f, -0.3f, 0.1f, 1.2f, 0.05f, -0.05f, 0, 60 };
    tl_set_view(&s, &v);
    if (tl_agree(&bufs, &s, &vp, 1, msg, sizeof msg) > 0) {
        fprintf(stderr, "fuzz_mesh: %s\n", msg);
        abort();
    }
    scene_free(&s);
    return 0;
}
