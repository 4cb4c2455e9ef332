/* tile.c: one tile of the gallery. The file is loaded as every load is
 * (in the sandbox's child, the options' format, --max-memory, --flip),
 * without textures (a tile is too small to show them, and their images
 * are the biggest part of a textured model's memory); checked on one
 * thread (the workers are the parallelism); made a scene of its own,
 * whose first view is chosen as the viewer's is; rendered once at the
 * tile's size; then everything but the picture is freed, so that a
 * folder of ten thousand models holds ten thousand small pictures and
 * at most one mesh per worker. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gallery.h"
#include "meshcheck.h"

void gallery_verdict(const CheckCounts *c, char *buf, size_t len)
{
    if (!c->faces) {
        snprintf(buf, len, "no faces");
        return;
    }
    char item[CHECK_PROBLEMS_MAX][CHECK_PROBLEM_LEN];
    int k = meshcheck_problems_as(c, CHECK_SAY_SHORT, item, CHECK_PROBLEMS_MAX);
    if (k == 0)
        snprintf(buf, len, "sound");
    else if (k == 1)
        snprintf(buf, len, "%s", item[0]);
    else
        snprintf(buf, len, "%s +%d", item[0], k - 1);
}

void gallery_unreadable(const char *path, const char *err, char *buf, size_t len)
{
    /* the loader's message names the file: the tile names it already */
    size_t n = strlen(path);
    const char *why = err;
    if (!strncmp(err, path, n) && err[n] == ':') {
        why = err + n + 1;
        while ((*why >= '0' && *why <= '9') || *why == ':' || *why == ' ')
            why++;      /* "path:3: " or "path: " */
    }
    snprintf(buf, len, "unreadable: %s", why);
}

/* The command line's options as they apply to one tile: its own scene,
 * one thread, no --grid copies or placements of the command line's. */
static void tile_options(const Options *o, Options *out)
{
    *out = *o;
    out->threads = 1;
    out->grid = 0;
    out->nplace = 0;
    out->nfiles = 0;
}

/* Load path into *m (one malloc'd mesh): 0, or -1 with the reason. */
static int load(const char *path, const Options *o, const int *cancel, Mesh **m, char *err, size_t errlen)
{
    MeshLoadOpts lo = app_load_opts(o);
    lo.cancel = cancel;
    lo.no_textures = 1;
    lo.threads = 1;
    lo.quiet = 1;       /* a tile's loader warnings would land on the grid curses draws (a missing MTL:
                           the tile shows the model in its colours, and the verdict says the rest) */
    SandboxOpts so = app_sandbox_opts(o);
    *m = calloc(1, sizeof **m);
    if (!*m) {
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    if (sandbox_load(*m, path, &lo, &so, err, errlen)) {
        free(*m);
        *m = NULL;
        return -1;
    }
    app_after_load(o, *m);
    return 0;
}

int gallery_tile_scene(const char *path, const Options *o, const int *cancel, Scene *out)
{
    char err[512];
    Options to;
    tile_options(o, &to);
    Mesh *m;
    if (load(path, &to, cancel, &m, err, sizeof err))
        return -1;
    return app_scene_from_meshes(&to, m, 1, out, NULL, err, sizeof err);
}

int gallery_tile_render(Scene *s, const GalleryLook *look, float yaw, Image *pic)
{
    Pipeline p;
    if (pipeline_init(&p, s, hsr_find("zbuffer"), 1))
        return -1;
    pipeline_apply_options(&p, look->o);
    p.samples = look->samples;
    pipeline_set_backdrop(&p, &look->bd);
    float yaw0 = s->cam.yaw;
    s->cam.yaw += yaw;
    int rc = pipeline_render(&p, look->w, look->h, look->aspect, look->o->cull, 1);
    s->cam.yaw = yaw0;
    if (!rc && look->bd.paint)
        backdrop_paint(&p.img, &look->bd);
    if (!rc && !(rc = image_resize(pic, p.img.w, p.img.h))) {
        memcpy(pic->rgb, p.img.rgb, 3 * (size_t)p.img.w * p.img.h);
        memcpy(pic->lit, p.img.lit, (size_t)p.img.w * p.img.h);
    }
    pipeline_free(&p);
    return rc ? -1 : 0;
}

int gallery_tile_make(GalleryTile *t, const GalleryLook *look, int what)
{
    char err[512];
    Options to;
    tile_options(look->o, &to);
    Mesh *m;
    if (load(t->path, &to, look->cancel, &m, err, sizeof err)) {
        t->state = GS_UNREADABLE;
        gallery_unreadable(t->path, err, t->verdict, sizeof t->verdict);
        return 0;
    }
    t->faces = m->nfaces;
    if (what & TILE_CHECK) {
        /* the check first: the scene takes the mesh over */
        MeshCheck mc;
        CheckOpts co = { .threads = 1, .intersections = 1 };
        if (meshcheck_run(&mc, m, &co, err, sizeof err)) {
            mesh_free(m);
            free(m);
            t->state = GS_UNREADABLE;
            gallery_unreadable(t->path, err, t->verdict, sizeof t->verdict);
            return 0;
        }
        gallery_verdict(&mc.file, t->verdict, sizeof t->verdict);
        t->problems = (uint32_t)meshcheck_problems(&mc.file, NULL, 0);
        t->state = meshcheck_sound(&mc.file) ? GS_SOUND : GS_PROBLEM;
        meshcheck_free(&mc);
    } else {
        t->state = GS_PICTURED;
        snprintf(t->verdict, sizeof t->verdict, "checking");
    }
    if (!(what & TILE_PICTURE)) {
        mesh_free(m);
        free(m);
        return 0;
    }
    Scene s;
    if (app_scene_from_meshes(&to, m, 1, &s, NULL, err, sizeof err))
        return 0;       /* too big to picture (--max-polys, memory): the verdict stands */
    int rc = gallery_tile_render(&s, look, t->yaw, &t->pic);
    scene_free(&s);
    return rc;
}
