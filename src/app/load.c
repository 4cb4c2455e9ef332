/* load.c: command-line files (or the demo scene) -> one scene. */

#define _DEFAULT_SOURCE

#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "safetext.h"
#include "sandbox.h"

#ifndef ZV_DATADIR
#define ZV_DATADIR "/usr/local/share/zview"
#endif

/* The places the demo scene is looked for, in order: next to the
 * binary (the source tree), the installed copy beside it, the install
 * prefix's, then the working folder's assets/. Returns how many. */
static int demo_places(char places[4][PATH_MAX + 32])
{
    int n = 0;
    char exe[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash = len > 0 ? (exe[len] = 0, strrchr(exe, '/')) : NULL;
    if (slash) {
        *slash = 0;
        snprintf(places[n++], PATH_MAX + 32, "%s/assets/demo.obj", exe);
        snprintf(places[n++], PATH_MAX + 32, "%s/../share/zview/demo.obj", exe);
    }
    snprintf(places[n++], PATH_MAX + 32, "%s/demo.obj", ZV_DATADIR);
    snprintf(places[n++], PATH_MAX + 32, "assets/demo.obj");
    return n;
}

const char *app_demo_path(void)
{
    static char path[PATH_MAX + 32];
    char places[4][PATH_MAX + 32];
    int n = demo_places(places);
    for (int i = 0; i < n; i++)
        if (access(places[i], R_OK) == 0 || i == n - 1) {
            memcpy(path, places[i], sizeof path);
            break;
        }
    return path;
}

/* When no place holds the demo scene, every place in the message (a
 * binary copied away from the source names them all). 0 when found. */
static int demo_missing(char *err, size_t errlen)
{
    char places[4][PATH_MAX + 32];
    int n = demo_places(places);
    for (int i = 0; i < n; i++)
        if (access(places[i], R_OK) == 0)
            return 0;
    size_t o = (size_t)snprintf(err, errlen, "no model given, and no demo scene in ");
    for (int i = 0; i < n && o < errlen; i++)
        o += (size_t)snprintf(err + o, errlen - o, "%s%s", i == 0 ? "" : i == n - 1 ? " or " : ", ", places[i]);
    if (o < errlen)
        snprintf(err + o, errlen - o, " (zview MODEL opens a model)");
    return -1;
}

MeshLoadOpts app_load_opts(const Options *o)
{
    MeshLoadOpts lo = { .format = o->format, .strict = o->strict, .max_polys = o->max_polys, .threads = o->threads,
                        .max_bytes = o->max_memory, .tex_defer_side = o->tex_defer, .no_textures = o->tex_skip,
                        .tessellation = o->tessellation };
    return lo;
}

void app_after_load(const Options *o, Mesh *m)
{
    if (o->flip)
        mesh_flip_winding(m);
    if (o->points)
        mesh_as_points(m);
    /* --unit: the file's lengths taken as that unit, in millimetres from
     * here on (said in the report: never done without --unit) */
    double k = o->unit ? printq_unit_mm(o->unit) : 1;
    if (k != 1)
        for (size_t i = 0; i < 3 * (size_t)m->nverts; i++)
            m->pos[i] = (float)(m->pos[i] * k);
    if (o->unit)
        snprintf(m->info.unit, sizeof m->info.unit, "mm");
}

SandboxOpts app_sandbox_opts(const Options *o)
{
    SandboxOpts so = { .off = o->no_sandbox, .max_memory = o->max_memory, .server = o->sandbox };
    return so;
}

void app_sandbox_warn(const Options *o)
{
    if (!o->no_sandbox && !sandbox_available())
        safetext_line(stderr, "zview: warning: this system has no seccomp filters: models load in zview's own process, "
                "unsandboxed (--no-sandbox says so and silences this)");
}

int app_load_scene(const Options *o, Scene *s, char *err, size_t errlen)
{
    return app_load_scene_ex(o, s, NULL, err, errlen);
}

/* Every file of the command line into meshes (nfiles of them), each in
 * the sandbox: one of several that cannot be read (gone, unreadable, not
 * a model) is named in a warning and the rest are kept; --strict, or
 * every file failing, refuses. Returns how many were read, or -1 with
 * the reason in err (meshes freed). */
static int read_files(const Options *o, const char *const *files, int nfiles, Mesh *meshes, char *err,
                      size_t errlen)
{
    int from_stdin = 0;
    app_sandbox_warn(o);
    MeshLoadOpts lo = app_load_opts(o);
    SandboxOpts so = app_sandbox_opts(o);
    int nread = 0, nfailed = 0;
    char left_out[256] = "";
    for (int i = 0; i < nfiles; i++) {
        from_stdin |= strcmp(files[i], "-") == 0;
        if (sandbox_load(&meshes[nread], files[i], &lo, &so, err, errlen)) {
            nfailed++;
            if (nfiles > 1 && !o->strict && nfailed < nfiles) {
                safetext_line(stderr, "zview: warning: %s (left out; the other files are shown)", err);
                if (!left_out[0])
                    snprintf(left_out, sizeof left_out, "%s (left out)", err);
                continue;
            }
            for (int k = 0; k < nread; k++)
                mesh_free(&meshes[k]);
            return -1;
        }
        app_after_load(o, &meshes[nread]);
        nread++;
    }
    err[0] = '\0';
    /* the viewer's status bar shows the first file's first warning (the
     * screen covers stderr): a file left out is the one to know about */
    if (left_out[0] && !meshes[0].info.skipped && !meshes[0].info.tex_failed) {
        meshes[0].info.warnings++;
        memcpy(meshes[0].info.first_warning, left_out, sizeof left_out);
    }
    /* The model came through standard input (`curl ... | zview -`): the
     * viewer reads its keys from there, so give it the terminal back. */
    if (from_stdin && !isatty(STDIN_FILENO)) {
        int fd = open("/dev/tty", O_RDONLY | O_CLOEXEC);
        if (fd >= 0) {
            dup2(fd, STDIN_FILENO);
            close(fd);
            clearerr(stdin);
        }
    }
    return nread;
}

/* --move, --turn and --scale on the objects, then what a reset (r in the
 * viewer) goes back to. Returns 0, or -1 for an object that does not
 * exist. */
static int place_objects(const Options *o, Scene *s, char *err, size_t errlen)
{
    for (int k = 0; k < o->nplace; k++) {
        const Placement *pl = &o->place[k];
        if (pl->obj >= (int)s->nbase_objs) {
            snprintf(err, errlen, "object %d does not exist (the scene has %u)", pl->obj + 1, s->nbase_objs);
            return -1;
        }
        Object *ob = &s->objs[pl->obj];
        if (pl->kind == PLACE_MOVE)
            ob->offset = v3_add(ob->home, v3(pl->v[0], pl->v[1], pl->v[2]));
        else if (pl->kind == PLACE_TURN) {
            ob->yaw = deg2rad(pl->v[0]);
            ob->pitch = deg2rad(pl->v[1]);
            ob->roll = deg2rad(pl->v[2]);
        } else
            ob->scale = ob->home_scale * pl->v[0];
    }
    for (int k = 0; k < s->nobjs; k++) {
        Object *ob = &s->objs[k];
        ob->open_move = v3_sub(ob->offset, ob->home);
        ob->open_yaw = ob->yaw;
        ob->open_pitch = ob->pitch;
        ob->open_roll = ob->roll;
        ob->open_scale = ob->home_scale != 0 ? ob->scale / ob->home_scale : 1;
    }
    return 0;
}

/* The camera: fitted once as seen from the requested (or the
 * --fit-from) turn, then turned, zoomed and panned: any state of the
 * viewer is reachable from here. */
static void set_camera(const Options *o, Scene *s, float yaw, float pitch)
{
    light_set(&s->light, o->light[0], o->light[1], o->ambient);
    s->cam.persp = o->persp;
    s->cam.fov_deg = o->fov;
    const float *fit = o->has_fit_from ? o->fit_from : (const float[3]){ yaw, pitch, o->roll };
    s->cam.yaw = deg2rad(fit[0]);
    s->cam.pitch = deg2rad(fit[1]);
    s->cam.roll = deg2rad(fit[2]);
    scene_fit(s);
    s->cam.yaw = deg2rad(yaw);
    s->cam.pitch = deg2rad(pitch);
    s->cam.roll = deg2rad(o->roll);
    s->cam.zoom = o->zoom;
    s->cam.pan = v3(o->pan[0], o->pan[1], 0);
}

int app_load_scene_ex(const Options *o, Scene *s, FirstView *fv, char *err, size_t errlen)
{
    const char *demo[1];
    const char *const *files = o->files;
    int nfiles = o->nfiles;
    if (nfiles == 0) {
        if (demo_missing(err, errlen))
            return -1;
        demo[0] = app_demo_path();
        files = demo;
        nfiles = 1;
    }
    Mesh *meshes = calloc((size_t)nfiles, sizeof *meshes);
    if (!meshes) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    nfiles = read_files(o, files, nfiles, meshes, err, errlen);
    if (nfiles < 0) {
        free(meshes);
        return -1;
    }
    return app_scene_from_meshes(o, meshes, nfiles, s, fv, err, errlen);
}

/* keep: scene_build_kept's (app_scene_beside): on failure the meshes
 * stay the caller's. */
static int scene_from_meshes(const Options *o, Mesh *meshes, int nfiles, Scene *s, FirstView *fv, int keep,
                             char *err, size_t errlen)
{
    int rc = keep ? scene_build_kept(s, meshes, nfiles, err, errlen) : scene_build(s, meshes, nfiles, err, errlen);
    if (rc) {
        if (keep)
            return rc;
        for (int k = 0; k < nfiles; k++)
            mesh_free(&meshes[k]);
        free(meshes);
        return -1;
    }
    if (o->up >= 0)
        scene_set_up(s, o->up);    /* else each object stands as its file says */
    /* the view: a named one, the picked one (asked for, or when no turn
     * is given at all), or just the turn given. Several files are laid
     * out across the picked view, whatever view is asked for, so that a
     * view's command line (viewcmd.c) finds them where they were. */
    FirstView pick;
    app_first_view(s, o->threads, &pick);
    if (fv)
        *fv = pick;
    float py = pick.yaw, pp = pick.pitch, vy = 0, vp = 0;
    if (o->view && strcmp(o->view, "auto"))
        view_from_name(o->view, &vy, &vp);
    else if (o->view || !o->turned) {
        vy = py;
        vp = pp;
    }
    scene_layout(s, (LayoutKind)o->layout, deg2rad(py));
    if (app_check_size(o, s, err, errlen) || (o->grid > 1 && scene_make_grid(s, o->grid, err, errlen)) ||
        place_objects(o, s, err, errlen)) {
        if (keep) {
            s->meshes = NULL;       /* still the caller's */
            s->nmeshes = 0;
        }
        scene_free(s);
        return -1;
    }
    set_camera(o, s, vy + o->yaw, vp + o->pitch);
    return 0;
}

int app_scene_from_meshes(const Options *o, Mesh *meshes, int nfiles, Scene *s, FirstView *fv, char *err,
                          size_t errlen)
{
    return scene_from_meshes(o, meshes, nfiles, s, fv, 0, err, errlen);
}

int app_scene_beside(const Options *o, Mesh *meshes, int nfiles, Scene *s, FirstView *fv, char *err,
                     size_t errlen)
{
    return scene_from_meshes(o, meshes, nfiles, s, fv, 1, err, errlen);
}
