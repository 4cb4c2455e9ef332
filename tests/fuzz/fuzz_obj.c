/* fuzz_obj.c: the loader harness. OBJ text (and the MTL file it names)
 * through mesh_parse, scene_build, a small render in every display mode
 * and the text output, the way `zview --print` goes; then every algorithm
 * against the z-buffer on the loaded scene (abort on a difference); and
 * the text parsed in pieces on two threads against the serial parse
 * (objpar.c; abort on a difference).
 *
 * Input: OBJ text, optionally followed by a line "@@mtl" and the text of
 * the file in.mtl, which `mtllib in.mtl` in the OBJ part loads. mtllib is
 * resolved against the OBJ's folder and opens real files, so the OBJ is
 * named as if it sat in a per-process temporary folder, the MTL part is
 * written there, and inputs whose mtllib names reach out of that folder
 * (a '/' in the name: /dev/stdin, ../..) are skipped. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "fuzz.h"
#include "testlib.h"

#define SEPARATOR "@@mtl\n"

/* The per-process folder (libFuzzer runs the harness in one process per
 * job, many inputs each): made on first use, removed at exit. */
typedef struct {
    char  dir[256], obj[300], mtl[300];
    FILE *null;
} Workdir;

static Workdir work;

static void work_remove(void)
{
    unlink(work.mtl);
    rmdir(work.dir);
    if (work.null)
        fclose(work.null);
}

static int work_init(void)
{
    if (work.dir[0])
        return 0;
    const char *tmp = getenv("TMPDIR");
    snprintf(work.dir, sizeof work.dir, "%s/zview-fuzz-obj-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(work.dir) || !(work.null = fopen("/dev/null", "w"))) {
        perror("fuzz_obj: temporary folder");
        abort();
    }
    snprintf(work.obj, sizeof work.obj, "%s/in.obj", work.dir);
    snprintf(work.mtl, sizeof work.mtl, "%s/in.mtl", work.dir);
    atexit(work_remove);
    return 0;
}

/* Where the MTL part starts (just past the separator line), or NULL. */
static const char *find_separator(const char *p, size_t n, size_t *obj_len)
{
    size_t k = sizeof SEPARATOR - 1;
    for (size_t i = 0; i + k <= n; i++)
        if ((i == 0 || p[i - 1] == '\n') && memcmp(p + i, SEPARATOR, k) == 0) {
            *obj_len = i;
            return p + i + k;
        }
    *obj_len = n;
    return NULL;
}

/* Does a '/' follow "mtllib" within its logical line (backslash-newline
 * continues a line, as the loader joins them)? */
static int mtllib_leaves_folder(const char *p, size_t n)
{
    for (size_t i = 0; i + 6 <= n; i++) {
        if (memcmp(p + i, "mtllib", 6) != 0)
            continue;
        for (size_t j = i + 6; j < n; j++) {
            if (p[j] == '/')
                return 1;
            if (p[j] == '\n') {
                size_t b = j;
                if (b > 0 && p[b - 1] == '\r')
                    b--;
                if (!(b > 0 && p[b - 1] == '\\'))
                    break;
            }
        }
    }
    return 0;
}

static int write_file(const char *path, const char *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    size_t w = fwrite(p, 1, n, f);
    return fclose(f) == 0 && w == n ? 0 : -1;
}

/* Loaded scenes hold what the differential harness's encoding cannot
 * give (faces of hundreds of corners, any mix of objects): every
 * algorithm must agree with the z-buffer on them too. */
static void agree_or_abort(Scene *s, int persp)
{
    static TlAgree bufs;    /* kept: see fuzz_diff.c */
    /* turned, a little panned; in perspective the eye is inside */
    TlView v = { .yaw = 0.4f, .pitch = -0.3f, .roll = 0.1f, .fit_yaw = 0.4f, .fit_pitch = -0.3f,
                 .fit_roll = 0.1f, .zoom = persp ? 3.0f : 1.2f, .pan_x = 0.05f, .pan_y = -0.05f,
                 .persp = persp, .fov_deg = 60 };
    Viewport vp = { 48, 40, 2.0f, 0 };
    char msg[512];
    tl_set_view(s, &v);
    if (tl_agree(&bufs, s, &vp, 1, msg, sizeof msg) > 0) {
        fprintf(stderr, "fuzz_obj: %s: %s\n", persp ? "perspective" : "orthographic", msg);
        abort();
    }
}

/* The frame in each display mode and colour depth, some with culling,
 * perspective or another shading, as text to /dev/null. */
static void render_all(Scene *s)
{
    static const struct {
        DisplayMode mode;
        ColourDepth  colour;
        ShadeMode   shade;
        int         cull, persp;
    } runs[] = {
        { MODE_HALF, COLOUR_256, SHADE_LAMBERT, 0, 0 },
        { MODE_ASCII, COLOUR_16, SHADE_DEPTH, 1, 0 },
        { MODE_BRAILLE, COLOUR_TRUE, SHADE_ID, 0, 1 },
        { MODE_HALF, COLOUR_NONE, SHADE_LAMBERT, 1, 1 },
    };
    Pipeline p;
    if (pipeline_init(&p, s, hsr_find("zbuffer"), 1))
        return;
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        int pw, ph;
        s->cam.persp = runs[k].persp;
        s->cam.fov_deg = 60;
        scene_reset(s);
        if (runs[k].persp)
            s->cam.zoom = 3;    /* the eye inside the scene: the near plane clips */
        p.shade = runs[k].shade;
        mode_cell_pixels(runs[k].mode, &pw, &ph);
        if (pipeline_render(&p, 40 * pw, 20 * ph, mode_pixel_aspect(runs[k].mode), runs[k].cull, 1) ||
            cells_from_image(&p.img, runs[k].mode, runs[k].colour, &p.cells))
            break;
        print_cells(work.null, &p.cells, runs[k].colour);
    }
    pipeline_free(&p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    work_init();
    const char *text = (const char *)data;
    size_t obj_len;
    const char *mtl = find_separator(text, size, &obj_len);
    if (mtllib_leaves_folder(text, obj_len))
        return 0;
    /* each input sees only its own MTL part, never the last one's */
    if (mtl ? write_file(work.mtl, mtl, size - (size_t)(mtl - text)) : (unlink(work.mtl), 0))
        return 0;
    /* parsed in pieces (small ones, so that the fuzzer's short inputs
     * are cut too) on two threads: the serial parse, byte for byte */
    for (int strict = 0; strict <= 1; strict++) {
        const char *d = tl_obj_pieces_differ(work.obj, text, obj_len, 2, 1 + size % 61, strict);
        if (d) {
            fprintf(stderr, "fuzz_obj: %s\n", d);
            abort();
        }
    }
    Mesh *m = calloc(1, sizeof *m);
    char err[512];
    if (!m)
        return 0;
    if (mesh_parse(m, work.obj, text, obj_len, err, sizeof err)) {
        free(m);
        return 0;
    }
    Scene s;
    if (scene_build(&s, m, 1, err, sizeof err)) {
        mesh_free(m);
        free(m);
        return 0;
    }
    render_all(&s);
    agree_or_abort(&s, 0);
    agree_or_abort(&s, 1);
    scene_free(&s);
    return 0;
}
