/* assimp.c: the long tail of formats (glTF 2.0 and GLB, FBX, 3DS,
 * COLLADA, 3MF, X3D, Blender, ...) through the assimp C API, behind the
 * same loader interface as the native ones. Built only with ZV_ASSIMP
 * (make ASSIMP=0 leaves this file out); all assimp code is here.
 *
 * The scene's node tree is walked with the nodes' transforms applied,
 * each node that holds meshes becoming an object named after it; faces
 * keep their polygon form (no triangulation), in the order assimp gives
 * them. A material's base colour (glTF's baseColorFactor, else the
 * diffuse colour) becomes the faces' material; a mesh with vertex
 * colours gets them, multiplied by that base colour as glTF says, and
 * no material (a material would hide them). Points (glTF POINTS) and
 * segments (LINES, LINE_STRIP, LINE_LOOP: assimp gives each segment as
 * a face of two indices) are kept as the mesh's points and lines.
 *
 * The library is opened (dlopen) the first time a format of its is
 * asked for, not linked: linking it costs every run 5 MB of resident
 * memory (it and the C++ runtime), and zview then runs, native formats
 * and all, where assimp is not installed. */
#define _DEFAULT_SOURCE

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/version.h>

#include "mesh.h"
#include "mesh_internal.h"

#ifndef ZV_ASSIMP_SONAME
#define ZV_ASSIMP_SONAME "libassimp.so.5"
#endif

/* The functions used, typed by the library's own declarations. */
#define AI_FUNCS(X)                                                                    \
    X(aiImportFile) X(aiImportFileFromMemory) X(aiReleaseImport) X(aiGetErrorString)   \
    X(aiIsExtensionSupported) X(aiGetImportFormatCount) X(aiGetImportFormatDescription) \
    X(aiGetVersionMajor) X(aiGetVersionMinor) X(aiGetVersionPatch) X(aiGetMaterialColor) \
    X(aiGetMaterialFloatArray) X(aiGetMaterialString) X(aiIdentityMatrix4)

typedef struct {
#define AI_FIELD(f) __typeof__(f) *f;
    AI_FUNCS(AI_FIELD)
#undef AI_FIELD
} AiApi;

/* Set once (pthread_once), read-only after: the one piece of state here,
 * the library's handle, not any loader's. */
static AiApi ai_table;
static int ai_loaded;
static pthread_once_t ai_once = PTHREAD_ONCE_INIT;

static void ai_open(void)
{
    void *h = dlopen(ZV_ASSIMP_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!h)
        h = dlopen("libassimp.so", RTLD_NOW | RTLD_LOCAL);
    if (!h)
        return;
#define AI_SYM(f)                                                   \
    if (!(*(void **)&ai_table.f = dlsym(h, #f))) {                  \
        dlclose(h);                                                 \
        return;                                                     \
    }
    AI_FUNCS(AI_SYM)
#undef AI_SYM
    ai_loaded = 1;
}

/* The library, or NULL when it cannot be opened. */
static const AiApi *ai(void)
{
    pthread_once(&ai_once, ai_open);
    return ai_loaded ? &ai_table : NULL;
}

/* Validation guards the walk below against malformed files. Joining
 * identical vertices undoes the per-corner copies many formats store
 * (3DS, FBX, STL); glTF is indexed already, and the join would cost
 * seconds on a big glTF mesh for nothing. */
static unsigned ai_flags(const char *hint)
{
    int indexed = hint && (!strcmp(hint, "glb") || !strcmp(hint, "gltf"));
    return aiProcess_ValidateDataStructure | (indexed ? 0 : aiProcess_JoinIdenticalVertices);
}

typedef struct {
    MeshCtx              *c;
    MeshBuild             b;
    const struct aiScene *sc;
    int32_t              *matmap;   /* assimp material -> ours, -2 = not made yet */
    unsigned              depth;
} Walk;

static float clamp01(float v) { return v < 0 ? 0 : v > 1 ? 1 : v; }

/* The base colour of an assimp material. */
static struct aiColor4D base_colour(const struct aiMaterial *mat)
{
    struct aiColor4D c = { 1, 1, 1, 1 };
    if (ai()->aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &c) != aiReturn_SUCCESS &&
        ai()->aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) != aiReturn_SUCCESS) {
        c.r = c.g = c.b = 0.8f;   /* what MTL gives a material without Kd */
        c.a = 1;
    }
    float op;
    unsigned int one = 1;
    if (ai()->aiGetMaterialFloatArray(mat, AI_MATKEY_OPACITY, &op, &one) == aiReturn_SUCCESS && op < c.a)
        c.a = op;
    return c;
}

static int32_t material(Walk *w, unsigned i)
{
    if (i >= w->sc->mNumMaterials)
        return -1;
    if (w->matmap[i] != -2)
        return w->matmap[i];
    const struct aiMaterial *mat = w->sc->mMaterials[i];
    struct aiString name;
    int named = ai()->aiGetMaterialString(mat, AI_MATKEY_NAME, &name) == aiReturn_SUCCESS && name.length;
    struct aiColor4D c = base_colour(mat);
    /* What assimp adds to a file without materials (named so, or glTF's
     * unnamed white default): zview's default colour, as every other
     * format gets. */
    if ((named && strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0) ||
        (!named && c.r == 1 && c.g == 1 && c.b == 1 && c.a == 1))
        return w->matmap[i] = -1;
    if (!named)
        snprintf(name.data, sizeof name.data, "material %u", i);
    int32_t k = mb_material(&w->b, name.data, clamp01(c.r), clamp01(c.g), clamp01(c.b), clamp01(c.a));
    if (k >= 0)
        w->matmap[i] = k;
    return k < 0 ? -3 : k;
}

/* One mesh instance: its vertices through the node's transform, then
 * its faces. */
static int add_mesh(Walk *w, const struct aiMesh *am, const struct aiMatrix4x4 *t, int identity)
{
    Mesh *m = w->b.m;
    MeshErr *e = &w->c->err;
    if ((uint64_t)m->nverts + am->mNumVertices >= UINT32_MAX)
        return me_fail(e, "too many vertices");
    uint32_t base = m->nverts;
    const struct aiColor4D *vc = am->mColors[0];
    struct aiColor4D bc = { 1, 1, 1, 1 };
    if (am->mMaterialIndex < w->sc->mNumMaterials)
        bc = base_colour(w->sc->mMaterials[am->mMaterialIndex]);
    if (vc && mb_want_rgb(&w->b))
        return -1;
    for (unsigned v = 0; v < am->mNumVertices; v++) {
        struct aiVector3D p = am->mVertices[v];
        float x = p.x, y = p.y, z = p.z;
        if (!identity) {
            /* in double, rounded once to float */
            double dx = (double)t->a1 * p.x + (double)t->a2 * p.y + (double)t->a3 * p.z + t->a4;
            double dy = (double)t->b1 * p.x + (double)t->b2 * p.y + (double)t->b3 * p.z + t->b4;
            double dz = (double)t->c1 * p.x + (double)t->c2 * p.y + (double)t->c3 * p.z + t->c4;
            x = (float)dx;
            y = (float)dy;
            z = (float)dz;
        }
        if (!(x - x == 0 && y - y == 0 && z - z == 0))
            return me_fail(e, "NaN or infinite coordinate (mesh '%s', vertex %u)", am->mName.data, v + 1);
        if (mb_vertex(&w->b, x, y, z))
            return -1;
        if (vc) {
            float *d = m->rgb + 3 * (size_t)(m->nverts - 1);
            d[0] = clamp01(vc[v].r * bc.r);
            d[1] = clamp01(vc[v].g * bc.g);
            d[2] = clamp01(vc[v].b * bc.b);
        }
    }
    int32_t mat = -1;
    if (!vc && (mat = material(w, am->mMaterialIndex)) == -3)
        return -1;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *af = &am->mFaces[f];
        if (af->mNumIndices < 3) {
            /* glTF POINTS come as faces of one index, LINES, LINE_STRIP
             * and LINE_LOOP as faces of two (a segment each) */
            for (unsigned k = 0; k < af->mNumIndices; k++)
                if (af->mIndices[k] >= am->mNumVertices)
                    return me_fail(e, "vertex index %u out of range (mesh '%s', %u vertices)", af->mIndices[k],
                                   am->mName.data, am->mNumVertices);
            if (af->mNumIndices == 1 && mb_point(&w->b, base + af->mIndices[0]))
                return -1;
            if (af->mNumIndices == 2) {
                size_t first = w->b.nlcorner;
                if (mb_line_corner(&w->b, base + af->mIndices[0]) ||
                    mb_line_corner(&w->b, base + af->mIndices[1]) || mb_line_end(&w->b, first))
                    return -1;
            }
            continue;
        }
        size_t first = w->b.ncorner;
        if (mb_room_corners(&w->b, af->mNumIndices))
            return -1;
        for (unsigned k = 0; k < af->mNumIndices; k++) {
            unsigned idx = af->mIndices[k];
            if (idx >= am->mNumVertices)
                return me_fail(e, "vertex index %u out of range (mesh '%s', %u vertices)", idx,
                               am->mName.data, am->mNumVertices);
            m->corner[w->b.ncorner++] = base + idx;
        }
        if (mb_face_end(&w->b, first, mat))
            return -1;
    }
    return 0;
}

static int is_identity(const struct aiMatrix4x4 *t)
{
    return t->a1 == 1 && t->a2 == 0 && t->a3 == 0 && t->a4 == 0 && t->b1 == 0 && t->b2 == 1 &&
           t->b3 == 0 && t->b4 == 0 && t->c1 == 0 && t->c2 == 0 && t->c3 == 1 && t->c4 == 0;
}

static struct aiMatrix4x4 mul(const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b)
{
    struct aiMatrix4x4 r;
    const float *x = &a->a1, *y = &b->a1;
    float *o = &r.a1;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            o[4 * i + j] = x[4 * i] * y[j] + x[4 * i + 1] * y[4 + j] + x[4 * i + 2] * y[8 + j] +
                           x[4 * i + 3] * y[12 + j];
    return r;
}

static int walk(Walk *w, const struct aiNode *n, const struct aiMatrix4x4 *parent)
{
    if (++w->depth > 1000)
        return me_fail(&w->c->err, "node tree deeper than 1000");
    struct aiMatrix4x4 t = mul(parent, &n->mTransformation);
    if (n->mNumMeshes) {
        if (mb_object(&w->b, n->mName.data, strlen(n->mName.data)))
            return -1;
        int id = is_identity(&t);
        for (unsigned i = 0; i < n->mNumMeshes; i++) {
            unsigned k = n->mMeshes[i];
            if (k >= w->sc->mNumMeshes)
                return me_fail(&w->c->err, "node '%s' names mesh %u of %u", n->mName.data, k,
                               w->sc->mNumMeshes);
            if (add_mesh(w, w->sc->mMeshes[k], &t, id))
                return -1;
        }
    }
    for (unsigned i = 0; i < n->mNumChildren; i++)
        if (walk(w, n->mChildren[i], &t))
            return -1;
    w->depth--;
    return 0;
}

/* assimp's message, first line only. */
static int import_failed(MeshCtx *c)
{
    const char *s = ai()->aiGetErrorString();
    if (!s || !*s)
        s = "assimp could not read it";
    size_t n = strcspn(s, "\n");
    return me_fail(&c->err, "%.*s", (int)(n < 300 ? n : 300), s);
}

static int from_scene(MeshCtx *c, const struct aiScene *sc)
{
    Walk w = { .c = c, .sc = sc };
    Mesh *m = c->m;
    if (mb_start(&w.b, m, &c->err, c->err.name))
        return -1;
    snprintf(m->info.format, sizeof m->info.format, "%.20s (assimp)", c->hint && *c->hint ? c->hint : "?");
    /* the unit the format states: glTF is in metres; 3MF and AMF are in
     * millimetres unless the file names another unit, which the import
     * does not pass on (so the default is what is named) */
    if (c->hint && (!strcmp(c->hint, "gltf") || !strcmp(c->hint, "glb")))
        snprintf(m->info.unit, sizeof m->info.unit, "m");
    else if (c->hint && (!strcmp(c->hint, "3mf") || !strcmp(c->hint, "amf")))
        snprintf(m->info.unit, sizeof m->info.unit, "mm");
    int r = -1;
    w.matmap = malloc((sc->mNumMaterials ? sc->mNumMaterials : 1) * sizeof *w.matmap);
    if (!w.matmap) {
        me_oom(&c->err);
        goto out;
    }
    for (unsigned i = 0; i < sc->mNumMaterials; i++)
        w.matmap[i] = -2;
    struct aiMatrix4x4 id;
    ai()->aiIdentityMatrix4(&id);
    if (!sc->mRootNode) {
        me_fail(&c->err, "no scene in the file");
        goto out;
    }
    if (walk(&w, sc->mRootNode, &id))
        goto out;
    r = mb_finish(&w.b, 1);
out:
    free(w.matmap);
    if (r)
        mb_abort(&w.b);
    return r;
}

static int no_library(MeshCtx *c)
{
    return me_fail(&c->err, "the assimp library (%s) cannot be opened", ZV_ASSIMP_SONAME);
}

static int ai_parse_path(MeshCtx *c, const char *path)
{
    if (!ai())
        return no_library(c);
    const struct aiScene *sc = ai()->aiImportFile(path, ai_flags(c->hint));
    if (!sc)
        return import_failed(c);
    int r = from_scene(c, sc);
    ai()->aiReleaseImport(sc);
    return r;
}

static int ai_parse(MeshCtx *c, const char *data, size_t len)
{
    if (!ai())
        return no_library(c);
    if (len > UINT_MAX)
        return me_fail(&c->err, "too large for assimp from memory");
    /* the hint is an extension, or "assimp" when forced without one */
    const char *hint = c->hint && strcmp(c->hint, "assimp") ? c->hint : "";
    const struct aiScene *sc = ai()->aiImportFileFromMemory(data, (unsigned)len, ai_flags(hint), hint);
    if (!sc)
        return import_failed(c);
    int r = from_scene(c, sc);
    if (r == 0)
        c->m->info.bytes = len;
    ai()->aiReleaseImport(sc);
    return r;
}

static int has_word(const char *h, size_t n, const char *w)
{
    size_t wl = strlen(w);
    for (size_t i = 0; i + wl <= n; i++)
        if (memcmp(h + i, w, wl) == 0)
            return 1;
    return 0;
}

/* Formats with a magic or a telling header; the rest go by extension. */
static int ai_probe(const char *h, size_t n, uint64_t size)
{
    (void)size;
    if (n >= 8 && memcmp(h, "glTF", 4) == 0 && rd_u32le(h + 4) == 2)
        return PROBE_SURE;
    if (n >= 18 && memcmp(h, "Kaydara FBX Binary", 18) == 0)
        return PROBE_SURE;
    size_t i = 0;
    while (i < n && mesh_is_ws(h[i]))
        i++;
    if (i < n && h[i] == '{' && has_word(h, n, "\"asset\"") && has_word(h, n, "\"version\""))
        return PROBE_SURE;   /* glTF JSON */
    if (i < n && h[i] == '<' && (has_word(h, n, "<COLLADA") || has_word(h, n, "<X3D")))
        return PROBE_SURE;
    return PROBE_NO;
}

int mesh_assimp_available(void)
{
    return ai() != NULL;
}

int mesh_assimp_has_ext(const char *ext)
{
    if (!ai() || !ext || !*ext || strlen(ext) > 30 || strchr(ext, '.') || strchr(ext, '*'))
        return 0;
    char dot[34];
    snprintf(dot, sizeof dot, ".%s", ext);
    return ai()->aiIsExtensionSupported(dot) == AI_TRUE;
}

/* Every importer's extensions, with the importer's name. */
void mesh_assimp_list(void (*fn)(const char *ext, const char *what, void *ctx), void *ctx)
{
    if (!ai())
        return;
    size_t nf = ai()->aiGetImportFormatCount();
    for (size_t i = 0; i < nf; i++) {
        const struct aiImporterDesc *d = ai()->aiGetImportFormatDescription(i);
        if (!d || !d->mFileExtensions)
            continue;
        const char *p = d->mFileExtensions;
        for (;;) {
            while (*p == ' ')
                p++;
            size_t wl = strcspn(p, " ");
            if (!wl)
                break;
            char ext[32];
            snprintf(ext, sizeof ext, "%.*s", (int)(wl < 31 ? wl : 31), p);
            fn(ext, d->mName ? d->mName : "", ctx);
            p += wl;
        }
    }
}

const char *mesh_assimp_version(char *buf, size_t n)
{
    if (!ai())
        snprintf(buf, n, "not found");
    else
        snprintf(buf, n, "%u.%u.%u", ai()->aiGetVersionMajor(), ai()->aiGetVersionMinor(),
                 ai()->aiGetVersionPatch());
    return buf;
}

const MeshLoader mesh_loader_assimp = {
    .name = "assimp",
    .exts = "",
    .what = "the formats assimp reads",
    .probe = ai_probe,
    .parse = ai_parse,
    .parse_path = ai_parse_path,
};
