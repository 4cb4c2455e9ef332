/* edit.c: objects added to and removed from a built scene (the viewer's
 * O, X and E keys).
 *
 * A scene's per-object data lives in flat arrays indexed by global face
 * id and scene polygon (scene.c), with objects referring to ranges and
 * to their mesh by pointer. Both edits are one operation: compose a new
 * scene from the objects kept of the old one followed by the objects of
 * a new part, copying each object's ranges to where they now fall and
 * moving the meshes still used into a new array. Everything is made
 * before anything is freed, so a failure leaves both inputs as they
 * were. The result is what scene_build would have made of the remaining
 * files: ids in load order, objects without colours of their own
 * coloured by their index (as a fresh load colours them). */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "invariant.h"
#include "scene.h"
#include "scene_internal.h"

int scene_object_file(const Scene *s, int i)
{
    if (i < 0 || i >= s->nobjs || !s->objs[i].mesh || !s->meshes)
        return -1;
    ptrdiff_t f = s->objs[i].mesh - s->meshes;
    return f >= 0 && f < s->nmeshes ? (int)f : -1;
}

/* One source of objects: a scene and which of its loaded objects to take
 * (keep NULL: all). */
typedef struct {
    Scene         *s;
    const uint8_t *keep;
} Source;

static int taken(const Source *src, int i)
{
    return !src->keep || src->keep[i];
}

/* What the composed scene holds. */
typedef struct {
    uint64_t nobjs, nfaces, npolys, ncorners, nsegs, nmeshes;
    uint64_t nsurf;                  /* every source's surfaces, all kept */
    int      surf, uv;               /* some source has face_surf, poly_uv */
} ComposeCounts;

/* Count what the sources give, numbering the meshes still used in
 * mesh_used (-1: not used). -1 with a message when the result passes a
 * scene's limits. */
static int compose_count(const Source *src, int nsrc, int *mesh_used[], ComposeCounts *n, char *err,
                         size_t errlen)
{
    for (int k = 0; k < nsrc; k++) {
        const Scene *s = src[k].s;
        int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
        n->nsurf += s->nsurf;
        n->surf |= s->face_surf != NULL;
        n->uv |= s->poly_uv != NULL;
        for (int i = 0; i < s->nmeshes; i++)
            mesh_used[k][i] = -1;
        for (int i = 0; i < nb; i++) {
            if (!taken(&src[k], i))
                continue;
            const Object *o = &s->objs[i];
            n->nobjs++;
            n->nfaces += o->face_count;
            n->npolys += o->poly_count;
            n->ncorners += scene_poly_c0(s, o->poly_first + o->poly_count) - scene_poly_c0(s, o->poly_first);
            n->nsegs += o->seg_count;
            int f = scene_object_file(s, i);
            if (f >= 0 && mesh_used[k][f] < 0)
                mesh_used[k][f] = (int)n->nmeshes++;
        }
    }
    if (n->nobjs > 65535 || n->nfaces > INT32_MAX || n->nsegs > INT32_MAX || n->nsurf > SCENE_SURF_MAX ||
        n->npolys > UINT32_MAX / 2 || n->ncorners > UINT32_MAX / 2) {
        const Scene *last = src[nsrc - 1].s;    /* what is being added */
        scene_too_large(last->meshes, last->nmeshes, n->nobjs, n->nfaces, err, errlen);
        return -1;
    }
    return 0;
}

/* out's arrays for n. -1 out of memory (out left empty). */
static int compose_alloc(Scene *out, const ComposeCounts *n)
{
    uint64_t nfaces = n->nfaces, npolys = n->npolys;
    out->meshes = malloc((n->nmeshes ? n->nmeshes : 1) * sizeof *out->meshes);
    out->objs = calloc(n->nobjs ? n->nobjs : 1, sizeof *out->objs);
    out->face_normal = malloc((nfaces ? nfaces : 1) * 3 * sizeof(float));
    out->face_rgb = malloc((nfaces ? nfaces : 1) * 3);
    out->face_own = malloc(nfaces ? nfaces : 1);
    out->face_obj = malloc((nfaces ? nfaces : 1) * sizeof(uint16_t));
    out->poly_start = malloc((npolys + 1) * sizeof(uint32_t));
    out->poly_corner = malloc((n->ncorners ? n->ncorners : 1) * sizeof(uint32_t));
    out->poly_lface = malloc((npolys ? npolys : 1) * sizeof(uint32_t));
    out->seg_corner = malloc((n->nsegs ? n->nsegs : 1) * sizeof(uint32_t));
    if (n->surf)
        out->face_surf = malloc((nfaces ? nfaces : 1) * sizeof *out->face_surf);
    if (n->nsurf)
        out->surf = malloc(n->nsurf * sizeof *out->surf);
    if (n->uv)
        out->poly_uv = malloc((n->ncorners ? n->ncorners : 1) * 2 * sizeof(float));
    if (!out->meshes || !out->objs || !out->face_normal || !out->face_rgb || !out->face_own || !out->face_obj ||
        !out->poly_start || !out->poly_corner || !out->poly_lface || !out->seg_corner ||
        (n->surf && !out->face_surf) || (n->nsurf && !out->surf) || (n->uv && !out->poly_uv)) {
        free(out->meshes);
        out->meshes = NULL;
        scene_free(out);
        return -1;
    }
    return 0;
}

/* Where the composed scene's lists have been written to. */
typedef struct {
    uint32_t oi, fi, pi, ci, si;   /* objects, faces, polygons, corners, segments */
    uint32_t surf0;                /* where the current source's surfaces start in out */
} ComposePos;

/* The faces' surfaces (textured ones moved to where s's surfaces now
 * start) and the polygon corners' texture coordinates of faces [f0,
 * f0 + nf) and corners [c0, c0 + nc) of s, to out at `at`. */
static void copy_surfaces(Scene *out, const Scene *s, uint32_t f0, uint32_t nf, uint32_t c0, uint32_t nc,
                          const ComposePos *at)
{
    if (out->face_surf)
        for (uint32_t q = 0; q < nf; q++) {
            uint16_t k = s->face_surf ? s->face_surf[f0 + q] : SURF_PLAIN;
            out->face_surf[at->fi + q] = (uint16_t)(k >= SURF_TEX0 ? k + at->surf0 : k);
        }
    if (!out->poly_uv)
        return;
    if (s->poly_uv)
        memcpy(&out->poly_uv[2 * (size_t)at->ci], &s->poly_uv[2 * (size_t)c0], 2 * (size_t)nc * sizeof(float));
    else
        memset(&out->poly_uv[2 * (size_t)at->ci], 0, 2 * (size_t)nc * sizeof(float));
}

/* Copy object i of s (whose mesh is now out's mesh `mesh`, or none) to
 * the end of out: the object, its faces' data, its polygons (offsets
 * moved to where its corners now start) and its segments. */
static void copy_object(Scene *out, const Scene *s, int i, Mesh *mesh, ComposePos *at)
{
    const Object *from = &s->objs[i];
    Object *o = &out->objs[at->oi];
    *o = *from;
    o->mesh = mesh;
    o->face_base = (int32_t)at->fi;
    o->poly_first = at->pi;
    o->seg_first = at->si;
    o->wire_first = o->wire_count = 0;
    o->mark_first = o->mark_count = 0;      /* what a check found is dropped with the ids it named */
    uint32_t fi = at->fi, pi = at->pi, ci = at->ci;
    uint32_t f0 = (uint32_t)from->face_base, nf = from->face_count;
    /* a compact source (scene.h) is written out in full */
    for (uint32_t q = 0; q < nf; q++)
        scene_face_normal(s, f0 + q, &out->face_normal[3 * ((size_t)fi + q)]);
    if (s->face_rgb) {
        memcpy(&out->face_rgb[3 * (size_t)fi], &s->face_rgb[3 * (size_t)f0], 3 * (size_t)nf);
        if (s->face_own)
            memcpy(&out->face_own[fi], &s->face_own[f0], nf);
        else
            memset(&out->face_own[fi], 1, nf);
    } else {
        memset(&out->face_own[fi], 0, nf);      /* coloured below */
    }
    for (uint32_t q = 0; q < nf; q++)
        out->face_obj[fi + q] = (uint16_t)at->oi;
    uint32_t c0 = scene_poly_c0(s, from->poly_first);
    for (uint32_t q = 0; q < from->poly_count; q++) {
        uint32_t p = from->poly_first + q;
        out->poly_start[pi + q] = ci + (scene_poly_c0(s, p) - c0);
        out->poly_lface[pi + q] = scene_poly_lface(s, from, p);
    }
    uint32_t nc = scene_poly_c0(s, from->poly_first + from->poly_count) - c0;
    memcpy(&out->poly_corner[ci], &s->poly_corner[c0], (size_t)nc * sizeof(uint32_t));
    copy_surfaces(out, s, f0, nf, c0, nc, at);
    memcpy(&out->seg_corner[at->si], &s->seg_corner[from->seg_first], (size_t)from->seg_count * sizeof(uint32_t));
    at->fi += nf;
    at->pi += from->poly_count;
    at->ci += nc;
    at->si += from->seg_count;
    at->oi++;
}

/* The source whose objects are the whole result, taken as they are
 * (all its loaded objects, no grid copies, its files in order), or -1.
 * Moving it keeps a compact scene compact (scene.h): the viewer's first
 * file arrives as a part added to an empty scene. */
static int sole_source(const Source *src, int nsrc, int *mesh_used[])
{
    int sole = -1;
    for (int k = 0; k < nsrc; k++) {
        const Scene *s = src[k].s;
        int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs, any = 0, all = 1;
        for (int i = 0; i < nb; i++) {
            any |= taken(&src[k], i);
            all &= taken(&src[k], i);
        }
        if (!any)
            continue;
        if (sole >= 0 || !all || s->nobjs != nb || !s->nmeshes)
            return -1;
        for (int i = 0; i < s->nmeshes; i++)
            if (mesh_used[k][i] != i)
                return -1;
        sole = k;
    }
    return sole;
}

/* out is source k's scene, moved (its wireframe and marks dropped, as a
 * composed scene has none); the source is left empty. */
static void compose_move(Scene *out, const Source *src, int k)
{
    Scene *s = src[k].s;
    *out = *s;
    memset(s, 0, sizeof *s);
    scene_marks_release(&out->marks);
    memset(&out->marks, 0, sizeof out->marks);
    free(out->wire);
    out->wire = NULL;
    out->nwire_edges = out->nwire = 0;
    out->wire_built = 0;
    for (int i = 0; i < out->nobjs; i++) {
        Object *o = &out->objs[i];
        o->wire_first = o->wire_count = o->mark_first = o->mark_count = 0;
    }
    scene_number_prims(out);    /* fewer ids than before: fits */
}

/* Compose *out from the sources in order (see the top of the file).
 * Returns 0, or -1 with a message; the sources are untouched either way
 * (meshes are copied by value: the caller releases what moved), but for
 * one that is the whole result, which is moved into *out. */
static int compose(Scene *out, const Source *src, int nsrc, int *mesh_used[], char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    ComposeCounts n = { 0 };
    if (compose_count(src, nsrc, mesh_used, &n, err, errlen))
        return -1;
    int sole = sole_source(src, nsrc, mesh_used);
    if (sole >= 0) {
        Camera cam = src[0].s->cam;
        Light light = src[0].s->light;
        uint32_t gen = src[0].s->gen + 1;
        compose_move(out, src, sole);
        out->cam = cam;
        out->light = light;
        out->gen = gen;
        return 0;
    }
    if (compose_alloc(out, &n)) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (int k = 0; k < nsrc; k++)
        for (int i = 0; i < src[k].s->nmeshes; i++)
            if (mesh_used[k][i] >= 0)
                out->meshes[mesh_used[k][i]] = src[k].s->meshes[i];
    out->nmeshes = (int)n.nmeshes;
    /* invariant: at counts the objects, faces, polygons, corners and
     * segments copied so far */
    ComposePos at = { 0, 0, 0, 0, 0, 0 };
    for (int k = 0; k < nsrc; k++) {
        const Scene *s = src[k].s;
        int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
        at.surf0 = out->nsurf;
        if (s->nsurf) {
            /* the meshes (and their textures) move by value: the
             * surfaces' texture pointers stay good */
            memcpy(&out->surf[out->nsurf], s->surf, s->nsurf * sizeof *s->surf);
            out->nsurf += s->nsurf;
        }
        for (int i = 0; i < nb; i++) {
            if (!taken(&src[k], i))
                continue;
            int f = scene_object_file(s, i);
            copy_object(out, s, i, f >= 0 ? &out->meshes[mesh_used[k][f]] : NULL, &at);
        }
    }
    /* what was copied is what compose_count counted, which sized out */
    ZV_ASSERT(at.oi == n.nobjs && at.fi == n.nfaces && at.pi == n.npolys && at.ci == n.ncorners &&
              at.si == n.nsegs);
    out->poly_start[at.pi] = at.ci;
    out->npolys = at.pi;
    out->nobjs = (int)at.oi;
    out->nbase_objs = at.oi;
    out->nfaces = at.fi;
    /* colours by index, as a load of these files colours them */
    for (uint32_t g = 0; g < at.fi; g++)
        if (!out->face_own[g]) {
            if (at.oi > 1)
                object_colour(out->face_obj[g], &out->face_rgb[3 * (size_t)g]);
            else
                memcpy(&out->face_rgb[3 * (size_t)g], scene_default_rgb, 3);
        }
    if (scene_number_prims(out)) {
        free(out->meshes);
        out->meshes = NULL;
        out->nmeshes = 0;
        scene_free(out);
        snprintf(err, errlen, "scene too large (more than %d faces, points and segments)", INT32_MAX);
        return -1;
    }
    out->cam = src[0].s->cam;
    out->light = src[0].s->light;
    out->gen = src[0].s->gen + 1;
    return 0;
}

/* Free what the old scene held but its meshes that moved (used[i] >= 0). */
static void release(Scene *s, const int *used)
{
    for (int i = 0; i < s->nmeshes; i++)
        if (used[i] < 0)
            mesh_free(&s->meshes[i]);
    s->nmeshes = 0;
    scene_free(s);
}

/* Run compose over one or two sources, then replace *s by the result. */
static int edit(Scene *s, const uint8_t *keep, Scene *part, char *err, size_t errlen)
{
    int *used0 = malloc((size_t)(s->nmeshes ? s->nmeshes : 1) * sizeof(int));
    int *used1 = malloc((size_t)(part && part->nmeshes ? part->nmeshes : 1) * sizeof(int));
    int rc = -1;
    if (!used0 || !used1) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    Source src[2] = { { s, keep }, { part, NULL } };
    int *used[2] = { used0, used1 };
    Scene n;
    if (compose(&n, src, part ? 2 : 1, used, err, errlen))
        goto out;
    release(s, used0);
    if (part) {
        release(part, used1);
        memset(part, 0, sizeof *part);
    }
    *s = n;
    rc = 0;
out:
    free(used0);
    free(used1);
    return rc;
}

int scene_add(Scene *s, Scene *part, char *err, size_t errlen)
{
    return edit(s, NULL, part, err, errlen);
}

int scene_remove(Scene *s, int i, char *err, size_t errlen)
{
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    if (i < 0 || i >= nb) {
        snprintf(err, errlen, "no object %d", i + 1);
        return -1;
    }
    uint8_t *keep = malloc((size_t)nb);
    if (!keep) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    memset(keep, 1, (size_t)nb);
    keep[i] = 0;
    int rc = edit(s, keep, NULL, err, errlen);
    free(keep);
    return rc;
}

void scene_clear(Scene *s)
{
    Camera cam = s->cam;
    Light light = s->light;
    uint32_t gen = s->gen;
    scene_free(s);
    /* what scene_build makes of no file: a polygon list of none */
    s->poly_start = calloc(1, sizeof *s->poly_start);
    s->cam = cam;
    s->light = light;
    s->gen = gen + 1;
}

int scene_replace_file(Scene *s, int f, Scene *part, char *err, size_t errlen)
{
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    if (f < 0 || f >= s->nmeshes) {
        snprintf(err, errlen, "no file %d", f + 1);
        return -1;
    }
    /* the files before f, the new one, the files after: in that order,
     * the scene keeps its order of files (and so its layout) */
    uint8_t *keep = malloc(2 * (size_t)(nb ? nb : 1));
    int *used = malloc((size_t)(2 * s->nmeshes + (part->nmeshes ? part->nmeshes : 1)) * sizeof(int));
    if (!keep || !used) {
        free(keep);
        free(used);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (int i = 0; i < nb; i++) {
        int fi = scene_object_file(s, i);
        keep[i] = fi >= 0 && fi < f;
        keep[nb + i] = fi > f;
    }
    Source src[3] = { { s, keep }, { part, NULL }, { s, keep + nb } };
    int *u[3] = { used, used + 2 * s->nmeshes, used + s->nmeshes };
    Scene n;
    int rc = compose(&n, src, 3, u, err, errlen);
    if (rc == 0) {
        /* a mesh of s moved when either of its two sources took it */
        for (int i = 0; i < s->nmeshes; i++)
            u[0][i] = u[0][i] >= 0 ? u[0][i] : u[2][i];
        release(s, u[0]);
        release(part, u[1]);
        memset(part, 0, sizeof *part);
        *s = n;
    }
    free(keep);
    free(used);
    return rc;
}
