/* load.c: command-line files (or the demo scene) -> one scene. */

#define _DEFAULT_SOURCE

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"

#ifndef ZV_DATADIR
#define ZV_DATADIR "/usr/local/share/zview"
#endif

const char *app_demo_path(void)
{
    static char path[PATH_MAX + 32];
    /* next to the binary (the source tree), then the installed copy, then cwd */
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = 0;
            snprintf(path, sizeof path, "%s/assets/demo.obj", exe);
            if (access(path, R_OK) == 0)
                return path;
            snprintf(path, sizeof path, "%s/../share/zview/demo.obj", exe);
            if (access(path, R_OK) == 0)
                return path;
        }
    }
    snprintf(path, sizeof path, "%s/demo.obj", ZV_DATADIR);
    if (access(path, R_OK) == 0)
        return path;
    return "assets/demo.obj";
}

int app_load_scene(const Options *o, Scene *s, char *err, size_t errlen)
{
    const char *demo[1];
    const char *const *files = o->files;
    int nfiles = o->nfiles;
    if (nfiles == 0) {
        demo[0] = app_demo_path();
        files = demo;
        nfiles = 1;
    }
    Mesh *meshes = calloc((size_t)nfiles, sizeof *meshes);
    if (!meshes) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (int i = 0; i < nfiles; i++) {
        if (mesh_load(&meshes[i], files[i], err, errlen)) {
            for (int k = 0; k < i; k++)
                mesh_free(&meshes[k]);
            free(meshes);
            return -1;
        }
    }
    if (scene_build(s, meshes, nfiles, err, errlen)) {
        for (int k = 0; k < nfiles; k++)
            mesh_free(&meshes[k]);
        free(meshes);
        return -1;
    }
    if (o->grid > 1 && scene_make_grid(s, o->grid, err, errlen)) {
        scene_free(s);
        return -1;
    }
    /* scene_build left everything reset: set the view, then fit once */
    s->cam.persp = o->persp;
    s->cam.fov_deg = o->fov;
    s->cam.yaw = deg2rad(o->yaw);
    s->cam.pitch = deg2rad(o->pitch);
    s->cam.roll = deg2rad(o->roll);
    scene_fit(s);   /* as seen from the requested turn */
    s->cam.zoom = o->zoom;
    return 0;
}
