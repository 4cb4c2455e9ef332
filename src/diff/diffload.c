/* diffload.c: --diff A B from the command line to a DiffSet: each file
 * loaded through the one load path (sandboxed, app_load_opts), checked
 * and measured (diff.c) and,
 * for a picture, put with the other in one scene: each in its own
 * coordinates (no layout: a model and its edited copy overlap where
 * they agree), fitted once to the union, standing as A's format says. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diff.h"
#include "thread.h"

const char *const diff_show_names[DIFF_SHOW_COUNT] = { "both", "a", "b", "heat" };

int diff_show_from_name(const char *name)
{
    for (int i = 0; i < DIFF_SHOW_COUNT; i++)
        if (!strcmp(name, diff_show_names[i]))
            return i;
    return -1;
}

/* One file; 1 with the message when it cannot be read or has no faces.
 * quiet: its warnings kept off stderr (still counted in its info). */
static int load_one(const Options *o, const char *path, int quiet, Mesh *m, char *err, size_t errlen)
{
    MeshLoadOpts lo = app_load_opts(o);
    lo.no_textures = 1;         /* the picture's colours are the distances */
    lo.quiet = quiet;
    SandboxOpts so = app_sandbox_opts(o);
    if (sandbox_load(m, path, &lo, &so, err, errlen))
        return 1;
    app_after_load(o, m);
    if (!m->nfaces) {
        snprintf(err, errlen, "%s: no faces (--diff compares surfaces)", path);
        mesh_free(m);
        return 1;
    }
    return 0;
}

/* B's load on a thread of its own, beside A's. */
typedef struct {
    const Options *o;
    Mesh          *m;
    int            rc;
    char           err[1024];
} LoadB;

static void *load_b_main(void *arg)
{
    LoadB *l = arg;
    l->rc = load_one(l->o, l->o->files[1], 1, l->m, l->err, sizeof l->err);
    return NULL;
}

/* Both files into m[0], m[1]: 0, or 1 with the first failure's message.
 * On several threads B loads beside A (each load's parse has a serial
 * part, and the sandbox's round trip), quietly; what the command says
 * is the same bytes as loading in turn: B loads again in turn, aloud,
 * when its quiet load warned or failed (its warnings then follow A's,
 * and its error, as before), and A's failure discards B. Standard input
 * is read in turn (it cannot be read twice). */
static int load_both(const Options *o, Mesh *m, char *err, size_t errlen)
{
    int threads = o->threads > 0 ? o->threads : default_threads();
    LoadB lb = { .o = o, .m = &m[1], .rc = -1 };
    pthread_t th;
    int beside = threads > 1 && strcmp(o->files[0], "-") && strcmp(o->files[1], "-") &&
                 thread_start(&th, load_b_main, &lb) == 0;
    int rc = load_one(o, o->files[0], 0, &m[0], err, errlen);
    if (beside) {
        pthread_join(th, NULL);
        if (lb.rc == 0 && (rc || m[1].info.warnings)) {
            mesh_free(&m[1]);
            lb.rc = -1;
        }
    }
    if (rc)
        return 1;
    if (lb.rc == 0)
        return 0;
    if (load_one(o, o->files[1], 0, &m[1], err, errlen)) {
        mesh_free(&m[0]);
        return 1;
    }
    return 0;
}

void diff_set_free(DiffSet *ds)
{
    diff_free(&ds->d);
    if (ds->has_scene)
        scene_free(&ds->scene);
    free(ds->obj_counts);
    memset(ds, 0, sizeof *ds);
}

/* The options the scene of both is made with: no layout (a model and
 * its edited copy overlap where they agree), standing as A says. */
static Options scene_opts(const Options *o, const Mesh *meshes)
{
    Options so = *o;
    so.layout = LAYOUT_NONE;
    so.up = o->up >= 0 ? o->up : meshes[0].info.up >= 0 && meshes[0].info.up < UP_COUNT ? meshes[0].info.up : UP_Y;
    return so;
}

/* The scene made, each object's counts kept for diff_show. */
static int scene_made(DiffSet *ds, const Options *o, char *err, size_t errlen)
{
    ds->has_scene = 1;
    Scene *s = &ds->scene;
    ds->obj_counts = malloc((size_t)(s->nobjs ? s->nobjs : 1) * 3 * sizeof *ds->obj_counts);
    if (!ds->obj_counts) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    ds->nobjs_a = 0;
    for (int i = 0; i < s->nobjs; i++) {
        const Object *ob = &s->objs[i];
        ds->nobjs_a += ob->mesh == &s->meshes[0];
        ds->obj_counts[3 * i] = ob->poly_count;
        ds->obj_counts[3 * i + 1] = ob->point_count;
        ds->obj_counts[3 * i + 2] = ob->seg_count;
    }
    return diff_show(ds, NULL, o->show);
}

/* The scene of both, after the diff (it takes the meshes). */
static int make_scene(DiffSet *ds, const Options *o, Mesh *meshes, char *err, size_t errlen)
{
    Options so = scene_opts(o, meshes);
    if (app_scene_from_meshes(&so, meshes, 2, &ds->scene, NULL, err, errlen))
        return -1;
    return scene_made(ds, o, err, errlen);
}

/* The scene made beside the diff (DiffOpts.beside, on several threads):
 * the picture's part that needs no distance, on one of the diff's
 * threads while the others measure, instead of after them. The meshes
 * are only read meanwhile; their faces go once the diff is done. */
typedef struct {
    const Options *o;
    Mesh          *m;
    Scene         *scene;       /* the DiffSet's */
    int            ran, rc;
    char           err[1024];
} Beside;

static void scene_beside(void *arg)
{
    Beside *b = arg;
    Options so = scene_opts(b->o, b->m);
    b->rc = app_scene_beside(&so, b->m, 2, b->scene, NULL, b->err, sizeof b->err);
    b->ran = 1;
}

int diff_load(DiffSet *ds, const Options *o, int scene, char *err, size_t errlen)
{
    memset(ds, 0, sizeof *ds);
    ds->path[0] = o->files[0];
    ds->path[1] = o->files[1];
    app_sandbox_warn(o);
    Mesh *m = calloc(2, sizeof *m);
    if (!m) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    if (load_both(o, m, err, errlen)) {
        free(m);
        return 1;
    }
    for (int i = 0; i < 2; i++) {
        snprintf(ds->format[i], sizeof ds->format[i], "%s", m[i].info.format);
        snprintf(ds->unit[i], sizeof ds->unit[i], "%s", m[i].info.unit);
        ds->nverts[i] = m[i].nverts;
        ds->nfaces[i] = m[i].nfaces;
    }
    Beside *b = scene ? calloc(1, sizeof *b) : NULL;
    if (b) {
        b->o = o;
        b->m = m;
        b->scene = &ds->scene;
    }
    DiffOpts dop = { o->threads, o->tolerance, NULL, 0, 1, b ? scene_beside : NULL, b };
    int rc = diff_compute(&ds->d, &m[0], &m[1], &dop, err, errlen);
    if (b && b->ran && b->rc == 0) {
        /* the scene holds the meshes now; the errors come in the order
         * they would after the diff: its own, then the scene's */
        free(b);
        if (rc) {
            scene_free(&ds->scene);
            return -1;
        }
        scene_release_faces(&ds->scene);
        return scene_made(ds, o, err, errlen) ? -1 : 0;
    }
    if (b && b->ran && b->rc < 0 && !rc) {
        snprintf(err, errlen, "%s", b->err);
        rc = -1;
    } else if (!rc && scene) {
        free(b);
        return make_scene(ds, o, m, err, errlen) ? -1 : 0;      /* the scene took the meshes */
    }
    free(b);
    mesh_free(&m[0]);
    mesh_free(&m[1]);
    free(m);
    return rc ? -1 : 0;
}
