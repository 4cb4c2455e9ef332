/* testlib.c: see testlib.h. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "testlib.h"

/* Build a one-mesh scene from m (loaded or not: rc says). */
static int scene_from_mesh(Scene *s, Mesh *m, int rc, char *err, size_t errlen)
{
    if (rc) {
        fprintf(stderr, "%s\n", err);
        free(m);
        return -1;
    }
    if (scene_build(s, m, 1, err, errlen)) {
        fprintf(stderr, "%s\n", err);
        mesh_free(m);
        free(m);
        return -1;
    }
    return 0;
}

int tl_scene_from_text(Scene *s, const char *name, const char *obj_text)
{
    char err[512];
    Mesh *m = calloc(1, sizeof *m);
    int rc = mesh_parse(m, name, obj_text, strlen(obj_text), err, sizeof err);
    return scene_from_mesh(s, m, rc, err, sizeof err);
}

int tl_scene_from_file(Scene *s, const char *path)
{
    char err[512];
    Mesh *m = calloc(1, sizeof *m);
    int rc = mesh_load(m, path, err, sizeof err);
    return scene_from_mesh(s, m, rc, err, sizeof err);
}

static uint32_t hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

static float unit(uint32_t seed, uint32_t k)
{
    return (hash32(seed * 7919u + k * 104729u + 1u) & 0xffffff) / (float)0x1000000;
}

void tl_random_view(Scene *s, uint32_t seed, int persp)
{
    s->cam.persp = persp;
    s->cam.fov_deg = 30 + 70 * unit(seed, 1);
    scene_reset(s);
    s->cam.yaw = 6.2831853f * unit(seed, 2);
    s->cam.pitch = 3.1415926f * (unit(seed, 3) - 0.5f);
    s->cam.roll = 6.2831853f * unit(seed, 4);
    s->cam.zoom = 0.7f + 1.8f * unit(seed, 5);
    if (persp && seed % 3 == 2)
        s->cam.zoom = 3.5f;   /* the eye inside the scene: the near plane cuts */
    s->cam.pan = v3(0.4f * (unit(seed, 6) - 0.5f), 0.4f * (unit(seed, 7) - 0.5f), 0);
}

int tl_render(Scene *s, const HsrAlgo *algo, int threads, int w, int h, int cull,
              ScreenPolys *sp, FrameBufs *fb, HsrStats *st)
{
    Viewport vp = { w, h, 1.0f, cull };
    if (screen_project(sp, s, &vp))
        return -1;
    HsrRunner r;
    if (hsr_runner_init(&r, algo, threads))
        return -1;
    HsrInput in = { sp, s, &vp };
    int rc = hsr_run(&r, &in, fb, st);
    hsr_runner_free(&r);
    return rc;
}

long tl_diff(const FrameBufs *ref, const FrameBufs *fb, int *first_x, int *first_y)
{
    long n = 0;
    *first_x = *first_y = -1;
    for (int j = 0; j < ref->h; j++)
        for (int i = 0; i < ref->w; i++) {
            size_t k = (size_t)j * ref->w + i;
            if (ref->ids[k] != fb->ids[k] ||
                memcmp(&ref->depth[k], &fb->depth[k], sizeof(float)) != 0) {
                if (!n) {
                    *first_x = i;
                    *first_y = j;
                }
                n++;
            }
        }
    return n;
}

const char *tl_shared_model(const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "../shared/models/%s", name);
    return access(path, R_OK) == 0 ? path : NULL;
}
