/* live.c: the scene edited while the viewer runs: O opens a file into
 * it (loaded on a thread of its own, loadjob.c), X removes the selected
 * object, E empties it. After each, the files are laid out again as
 * --layout says (every file from its own coordinates, as a load of the
 * same files together lays them out; objects keep what the user's keys
 * did to them relative to that) and the camera is fitted again at its
 * turn. The command line of the view (C, --print-view) names the files
 * the scene now holds.
 *
 * Before the scene changes, pipeline_scene_changing() stops and drops
 * what was built from it (hzb-octree's trees and their builder thread,
 * smooth normals): the scene keeps its address, so nothing keyed by the
 * pointer alone may survive (Scene.gen covers the rest). */

#define _DEFAULT_SOURCE         /* strdup */

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "viewer_app.h"

void viewer_note(App *a, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(a->note, sizeof a->note, fmt, ap);    /* cut to fit: the bar cuts it further */
    va_end(ap);
}

/* ==== The files ==== */

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s && s[1] ? s + 1 : path;
}

int viewer_live_init(App *a, const Options *o)
{
    a->live = *o;
    a->opt = &a->live;
    for (int i = 0; i < o->nfiles; i++) {
        a->paths[i] = strdup(o->files[i]);
        if (!a->paths[i])
            return -1;
        a->live.files[i] = a->paths[i];
    }
    return 0;
}

void viewer_live_free(App *a)
{
    for (int i = 0; i < MAX_FILES; i++) {
        free(a->paths[i]);
        a->paths[i] = NULL;
    }
    if (a->job) {
        loadjob_abandon(a->job);
        a->job = NULL;
    }
    firstload_abandon(a->first);
    a->first = NULL;
    texjob_abandon(a->tex);
    a->tex = NULL;
    checkjob_abandon(a->chk);
    a->chk = NULL;
    watch_free(a->watch);
    a->watch = NULL;
}

void viewer_update_name(App *a)
{
    const Options *o = a->opt;
    if (a->s->nobjs == 0)
        snprintf(a->name, sizeof a->name, "empty");
    else if (o->nfiles == 0)
        snprintf(a->name, sizeof a->name, "demo");
    else if (o->nfiles == 1)
        snprintf(a->name, sizeof a->name, "%s", base_name(o->files[0]));
    else
        snprintf(a->name, sizeof a->name, "%s +%d", base_name(o->files[0]), o->nfiles - 1);
}

static int add_path(App *a, const char *path)
{
    if (a->live.nfiles >= MAX_FILES)
        return -1;
    char *c = strdup(path);
    if (!c)
        return -1;
    a->paths[a->live.nfiles] = c;
    a->live.files[a->live.nfiles++] = c;
    return 0;
}

static void drop_path(App *a, int f)
{
    if (f < 0 || f >= a->live.nfiles)
        return;
    free(a->paths[f]);
    for (int i = f; i + 1 < a->live.nfiles; i++) {
        a->paths[i] = a->paths[i + 1];
        a->live.files[i] = a->live.files[i + 1];
    }
    a->live.nfiles--;
    a->paths[a->live.nfiles] = NULL;
    a->live.files[a->live.nfiles] = NULL;
}

/* The demo scene (no file given) is a file like any other once the
 * scene is edited: the view's command line must name it. */
static int name_the_demo(App *a)
{
    if (a->live.nfiles == 0 && a->s->nmeshes == 1)
        return add_path(a, a->s->meshes[0].path ? a->s->meshes[0].path : app_demo_path());
    return 0;
}

/* Tell the pipeline the scene is about to change. Its runner is made
 * anew; without memory for one, the note says so (the scene is then left
 * alone, and the next frame tries the runner again). */
static int changing(App *a)
{
    if (pipeline_scene_changing(&a->p) == 0)
        return 0;
    viewer_note(a, "out of memory");
    return -1;
}

void viewer_warning_note(App *a, const MeshInfo *info, const char *path)
{
    /* a texture that failed first: the picture looks wrong without a word */
    if (info->tex_failed)
        viewer_note(a, "%s: %u texture%s could not be read (first: %s)", base_name(path), info->tex_failed,
                 info->tex_failed == 1 ? "" : "s", info->first_tex_failed);
    else if (info->skipped)
        viewer_note(a, "%s: %u statement%s skipped (first: %s)", base_name(path), info->skipped,
                 info->skipped == 1 ? "" : "s", info->first_skipped);
    else if (info->warnings)
        viewer_note(a, "warning: %s", info->first_warning);
}

/* ==== Layout ==== */

/* Lay the files out again from their own coordinates, keep each
 * object's placement relative to its home, make the --grid copies
 * again, and fit at the camera's turn. */
static int relayout(App *a, char *err, size_t errlen)
{
    Scene *s = a->s;
    int nb = (int)s->nbase_objs;
    Vec3 *moved = malloc((size_t)(nb ? nb : 1) * sizeof *moved);
    float *scaled = malloc((size_t)(nb ? nb : 1) * sizeof *scaled);
    if (!moved || !scaled) {
        free(moved);
        free(scaled);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (int i = 0; i < nb; i++) {
        Object *o = &s->objs[i];
        moved[i] = v3_sub(o->offset, o->home);
        scaled[i] = o->home_scale != 0 ? o->scale / o->home_scale : 1;
        o->home = o->offset = v3(0, 0, 0);
        o->home_scale = o->scale = 1;
    }
    FirstView pick;
    app_first_view(s, a->opt->threads, &pick);
    scene_layout(s, (LayoutKind)a->opt->layout, deg2rad(pick.yaw));
    for (int i = 0; i < nb; i++) {
        Object *o = &s->objs[i];
        o->offset = v3_add(o->home, moved[i]);
        o->scale = o->home_scale * scaled[i];
    }
    free(moved);
    free(scaled);
    if (a->opt->grid > 1 && nb > 0 && scene_make_grid(s, a->opt->grid, err, errlen))
        return -1;
    scene_fit(s);
    return 0;
}

/* ==== Open ==== */

/* The command line's file is still loading (firstload.c): the scene is
 * a picture of its part, replaced as the load goes on, so it is not
 * edited (1, with the note). */
static int first_loading(App *a)
{
    if (!a->first)
        return 0;
    viewer_note(a, "still loading %s (q quits)", a->name);
    return 1;
}

Reaction viewer_open_prompt(App *a)
{
    if (a->job) {
        viewer_note(a, "still loading %s (Esc cancels)", base_name(loadjob_path(a->job)));
        return RE_DRAW;
    }
    if (first_loading(a))
        return RE_DRAW;
    a->prompting = 1;
    prompt_start(&a->prompt, "open: ");
    return RE_DRAW;
}

Reaction viewer_prompt_key(App *a, int key)
{
    PromptResult r = prompt_key(&a->prompt, key);
    if (r == PR_EDIT)
        return RE_DRAW;
    a->prompting = 0;
    if (r == PR_CANCEL || a->prompt.len == 0)
        return RE_DRAW;
    char path[PROMPT_MAX + 256], err[256];
    if (path_expand_home(a->prompt.buf, path, sizeof path)) {
        viewer_note(a, "path too long");
        return RE_DRAW;
    }
    if (a->live.nfiles >= MAX_FILES) {
        viewer_note(a, "the scene holds %d files already", MAX_FILES);
        return RE_DRAW;
    }
    a->job = loadjob_start(path, a->opt, err, sizeof err);
    if (!a->job)
        viewer_note(a, "%s: %s", base_name(path), err);
    return RE_DRAW;
}

Reaction viewer_cancel_load(App *a)
{
    if (!a->job)
        return RE_NONE;
    viewer_note(a, "cancelled loading %s", base_name(loadjob_path(a->job)));
    a->reload = -1;
    loadjob_abandon(a->job);    /* the thread ends alone; the scene is as it was */
    a->job = NULL;
    return RE_DRAW;
}

/* Polygons of the loaded objects, grid copies counted. */
static uint64_t scene_polys(const Scene *s, uint64_t copies)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++)
        n += s->objs[i].poly_count;
    return n * copies;
}

/* Join a loaded file's part to the scene. */
static Reaction add_part(App *a, Scene *part, const char *path)
{
    Scene *s = a->s;
    char err[256];
    const Options *o = a->opt;
    uint64_t copies = o->grid > 1 ? (uint64_t)o->grid * o->grid * o->grid : 1;
    uint64_t total = scene_polys(s, copies) + scene_polys(part, copies);
    if (o->max_polys && total > o->max_polys) {
        viewer_note(a, "%s: the scene would have %llu polygons (limit %llu; --max-polys raises it)",
                 base_name(path), (unsigned long long)total, (unsigned long long)o->max_polys);
        return RE_DRAW;
    }
    /* what to show of the file once the part is gone into the scene */
    MeshInfo info = part->nmeshes ? part->meshes[0].info : (MeshInfo){ 0 };
    uint32_t faces = part->nfaces, points = part->npoints, segs = part->nsegs;
    /* an up axis set for every object (--up, U) holds for the new file
     * too; else it stands as its format says */
    int up = scene_up_forced(s);
    if (up < 0)
        up = o->up;
    int first = (int)s->nbase_objs;
    if (name_the_demo(a) || add_path(a, path)) {
        viewer_note(a, "out of memory");
        return RE_DRAW;
    }
    if (changing(a) || scene_add(s, part, err, sizeof err)) {
        drop_path(a, a->live.nfiles - 1);
        if (!a->note[0])
            viewer_note(a, "%s: %s", base_name(path), err);
        return RE_RENDER;
    }
    for (int i = first; i < s->nobjs; i++)
        if (up >= 0)
            s->objs[i].up = up;
    if (relayout(a, err, sizeof err))
        viewer_note(a, "%s", err);
    else if (info.warnings)
        viewer_warning_note(a, &info, path);
    else if (points || segs)
        viewer_note(a, "opened %s: %u faces, %u points, %u segments", base_name(path), faces,
                 points, segs);
    else
        viewer_note(a, "opened %s: %u faces", base_name(path), faces);
    viewer_update_name(a);
    return RE_RENDER;
}

/* --watch: file f read again (part) takes the old one's place among the
 * files; its objects keep the old ones' placements when there are as
 * many, else the files are laid out again; the camera stays. */
static Reaction reload_file(App *a, Scene *part, int f, const char *path)
{
    Scene *s = a->s;
    char err[256];
    int nb = (int)s->nbase_objs, first = -1, count = 0;
    for (int i = 0; i < nb; i++)
        if (scene_object_file(s, i) == f) {
            first = first < 0 ? i : first;
            count++;
        }
    Object *was = malloc((size_t)(count ? count : 1) * sizeof *was);
    if (!was) {
        viewer_note(a, "out of memory");
        return RE_DRAW;
    }
    if (count)
        memcpy(was, &s->objs[first], (size_t)count * sizeof *was);
    Camera cam = s->cam;
    int same = (int)part->nbase_objs == count, up = scene_up_forced(s);
    uint32_t faces = part->nfaces;
    if (changing(a) || scene_replace_file(s, f, part, err, sizeof err)) {
        if (!a->note[0])
            viewer_note(a, "%s: %s", base_name(path), err);
        free(was);
        return RE_RENDER;
    }
    if (same) {
        for (int k = 0; k < count; k++) {
            Object *o = &s->objs[first + k];
            o->yaw = was[k].yaw, o->pitch = was[k].pitch, o->roll = was[k].roll;
            o->offset = was[k].offset, o->home = was[k].home;
            o->scale = was[k].scale, o->home_scale = was[k].home_scale;
            o->open_move = was[k].open_move, o->open_scale = was[k].open_scale;
            o->open_yaw = was[k].open_yaw, o->open_pitch = was[k].open_pitch, o->open_roll = was[k].open_roll;
            o->up = was[k].up;
        }
        if (a->opt->grid > 1 && s->nobjs > 0 && scene_make_grid(s, a->opt->grid, err, sizeof err))
            viewer_note(a, "%s", err);
    } else {
        for (int i = 0; i < s->nobjs; i++)
            if (up >= 0 && scene_object_file(s, i) == f)
                s->objs[i].up = up;
        if (relayout(a, err, sizeof err))
            viewer_note(a, "%s", err);
    }
    free(was);
    s->cam = cam;           /* the view stays as it was */
    if (!same || a->sel >= (int)s->nbase_objs)
        a->sel = -1;
    viewer_note(a, "read %s again: %u faces", base_name(path), faces);
    return RE_RENDER;
}

Reaction viewer_load_poll(App *a)
{
    if (!a->job)
        return RE_NONE;
    if (!loadjob_done(a->job))
        return RE_DRAW;         /* the progress in the status line moves on */
    if (a->sk.on)
        return RE_NONE;         /* the scene on screen is the sketch's: the file joins the model's when D leaves */
    char path[4096], err[512];
    snprintf(path, sizeof path, "%s", loadjob_path(a->job));
    Scene part;
    int rc = loadjob_finish(a->job, &part, err, sizeof err);
    a->job = NULL;
    int reload = a->reload;
    a->reload = -1;
    if (rc && reload >= 0) {
        /* --watch: a file written halfway, or broken: what was read last stays */
        size_t n = strlen(path);
        const char *why = strncmp(err, path, n) == 0 && err[n] == ':' ? err + n : NULL;
        viewer_note(a, "kept the last good model: %s%s", why ? base_name(path) : "", why ? why : err);
        return RE_DRAW;
    }
    if (reload >= 0) {
        Reaction r = reload_file(a, &part, reload, path);
        scene_free(&part);
        if (!a->tex)
            a->tex = texjob_start(a->s, a->opt);
        return r;
    }
    if (rc) {
        /* the loader's message names the file by the path it was given,
         * which a narrow bar would cut before the reason: the short name
         * instead (the scene is unchanged) */
        size_t n = strlen(path);
        const char *why = strncmp(err, path, n) == 0 && err[n] == ':' ? err + n : NULL;
        if (why)
            viewer_note(a, "%s%s", base_name(path), why);
        else
            viewer_note(a, "%s", err);
        return RE_DRAW;
    }
    Reaction r = add_part(a, &part, path);
    scene_free(&part);          /* empty when it went into the scene */
    if (!a->tex)
        a->tex = texjob_start(a->s, a->opt);
    return r;
}

/* ==== Remove and clear ==== */

Reaction viewer_remove_selected(App *a)
{
    if (first_loading(a))
        return RE_DRAW;
    Scene *s = a->s;
    int nb = (int)s->nbase_objs;
    if (nb == 0) {
        viewer_note(a, "nothing to remove");
        return RE_DRAW;
    }
    if (a->sel < 0 && nb > 1) {
        viewer_note(a, "select an object first (Tab), or E empties the scene");
        return RE_DRAW;
    }
    int i = a->sel < 0 ? 0 : a->sel % nb;   /* a --grid copy: its loaded object, copies and all */
    char name[MESH_NAME_MAX], err[256];
    snprintf(name, sizeof name, "%s", s->objs[i].name);
    if (name_the_demo(a)) {
        viewer_note(a, "out of memory");
        return RE_DRAW;
    }
    int f = scene_object_file(s, i), files = s->nmeshes;
    if (changing(a) || scene_remove(s, i, err, sizeof err)) {
        if (!a->note[0])
            viewer_note(a, "%s", err);
        return RE_RENDER;
    }
    if (s->nmeshes < files)
        drop_path(a, f);        /* its file's last object */
    if (s->nobjs > 0 && relayout(a, err, sizeof err))
        viewer_note(a, "%s", err);
    else
        viewer_note(a, "removed %s", name);
    nb = (int)s->nbase_objs;
    a->sel = nb > 1 ? (i < nb ? i : nb - 1) : -1;
    viewer_update_name(a);
    return RE_RENDER;
}

Reaction viewer_clear_scene(App *a)
{
    if (first_loading(a) || changing(a))
        return RE_DRAW;
    scene_clear(a->s);
    while (a->live.nfiles > 0)
        drop_path(a, a->live.nfiles - 1);
    a->sel = -1;
    viewer_update_name(a);
    return RE_RENDER;
}
