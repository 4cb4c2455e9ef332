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
 * no material (a material would hide them), unless the material has a
 * base-colour texture (glTF baseColorTexture, else the diffuse one) and
 * the mesh texture coordinates: then the texture. Its image is a file
 * beside the model, or one the file holds (GLB, data: URIs, embedded
 * images: assimp lists them in mTextures, named "*N", compressed or as
 * texels). Points (glTF POINTS) and
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

#include "assimpio.h"
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
    X(aiGetMaterialFloatArray) X(aiGetMaterialString) X(aiIdentityMatrix4) X(aiGetMaterialTexture) X(aiImportFileEx)

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
    int                   uv;       /* per-vertex texture coordinates kept */
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

/* ==== Textures ==== */

static TexWrap wrap_of(enum aiTextureMapMode m)
{
    return m == aiTextureMapMode_Clamp || m == aiTextureMapMode_Decal ? TEX_CLAMP
           : m == aiTextureMapMode_Mirror                              ? TEX_MIRROR
                                                                       : TEX_REPEAT;
}

/* The embedded image a texture path names: "*N", or (assimp 5) the
 * file name an embedded image was stored under. */
static const struct aiTexture *embedded(const struct aiScene *sc, const char *path)
{
    if (path[0] == '*') {
        char *end;
        unsigned long n = strtoul(path + 1, &end, 10);
        return *end == 0 && n < sc->mNumTextures ? sc->mTextures[n] : NULL;
    }
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    for (unsigned i = 0; i < sc->mNumTextures; i++) {
        const char *f = sc->mTextures[i]->mFilename.data, *fb = strrchr(f, '/');
        fb = fb ? fb + 1 : f;
        if (*fb && strcmp(fb, base) == 0)
            return sc->mTextures[i];
    }
    return NULL;
}

/* An embedded image: compressed bytes (mHeight 0), or texels in
 * assimp's B G R A order. */
static int32_t embedded_texture(Walk *w, const struct aiTexture *t, const char *name, TexWrap wu, TexWrap wv,
                                int *oom)
{
    size_t bl = sizeof MESH_BROKEN_IMAGE - 1;
    if (t->mHeight == 0 && t->mWidth == bl && !memcmp(t->pcData, MESH_BROKEN_IMAGE, bl))
        return mb_texture_missing(&w->b, name, "its data: URI is not base64", wu, wv, oom);
    if (t->mHeight == 0)
        return mb_texture(&w->b, name, NULL, t->pcData, t->mWidth, wu, wv, oom);
    if (t->mWidth > TEX_MAX_SIDE || t->mHeight > TEX_MAX_SIDE)
        return mb_texture_missing(&w->b, name, "an image of more than 16384 texels a side", wu, wv, oom);
    size_t n = (size_t)t->mWidth * t->mHeight;
    uint8_t *rgba = malloc(n * 4);
    if (!rgba) {
        *oom = 1;
        me_oom(&w->c->err);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        rgba[4 * i] = t->pcData[i].r;
        rgba[4 * i + 1] = t->pcData[i].g;
        rgba[4 * i + 2] = t->pcData[i].b;
        rgba[4 * i + 3] = t->pcData[i].a;
    }
    int32_t k = mb_texture_rgba(&w->b, name, rgba, (int)t->mWidth, (int)t->mHeight, wu, wv, oom);
    free(rgba);
    return k;
}

/* A path as a model writes it, as a file: '\\' as '/' (Windows),
 * %XX decoded (glTF URIs), relative to the model's folder. NULL out of
 * memory. */
static char *texture_file(const char *model, const char *p)
{
    const char *slash = model ? strrchr(model, '/') : NULL;
    size_t dl = (*p != '/' && slash) ? (size_t)(slash - model) + 1 : 0, n = strlen(p);
    char *out = malloc(dl + n + 1);
    if (!out)
        return NULL;
    memcpy(out, model, dl);
    size_t o = dl;
    for (size_t i = 0; i < n; i++) {
        unsigned hex;
        if (p[i] == '%' && i + 2 < n && sscanf(p + i + 1, "%2x", &hex) == 1 && hex) {
            out[o++] = (char)hex;
            i += 2;
        } else {
            out[o++] = p[i] == '\\' ? '/' : p[i];
        }
    }
    out[o] = 0;
    return out;
}

/* The base-colour texture of assimp material mat into mt (mt->tex -1
 * when it has none or none can be had). -1 out of memory. */
static int material_texture(Walk *w, const struct aiMaterial *mat, Material *mt)
{
    struct aiString path;
    enum aiTextureMapMode mode[3] = { aiTextureMapMode_Wrap, aiTextureMapMode_Wrap, aiTextureMapMode_Wrap };
    enum aiTextureType type = aiTextureType_BASE_COLOR;
    if (ai()->aiGetMaterialTexture(mat, type, 0, &path, NULL, NULL, NULL, NULL, mode, NULL) != aiReturn_SUCCESS) {
        type = aiTextureType_DIFFUSE;
        mode[0] = mode[1] = aiTextureMapMode_Wrap;
        if (ai()->aiGetMaterialTexture(mat, type, 0, &path, NULL, NULL, NULL, NULL, mode, NULL) != aiReturn_SUCCESS)
            return 0;
    }
    TexWrap wu = wrap_of(mode[0]), wv = wrap_of(mode[1]);
    int oom = 0;
    if (!path.length) {
        /* a texture whose image is nothing (glTF's "data:" with no data) */
        struct aiString mn;
        const char *model = w->c->err.name, *base = strrchr(model, '/');
        int named = ai()->aiGetMaterialString(mat, AI_MATKEY_NAME, &mn) == aiReturn_SUCCESS && mn.length;
        char name[300];
        snprintf(name, sizeof name, "%.150s %s%.100s%s", base ? base + 1 : model, named ? "material '" : "a material",
                 named ? mn.data : "", named ? "'" : "");
        mt->tex = mb_texture_missing(&w->b, name, "its image is empty (a data: URI without data?)", wu, wv, &oom);
        return oom ? -1 : 0;
    }
    const struct aiTexture *emb = embedded(w->sc, path.data);
    if (emb) {
        char name[300];
        const char *model = w->c->err.name, *base = strrchr(model, '/');
        snprintf(name, sizeof name, "%.150s %.100s", base ? base + 1 : model, path.data);
        mt->tex = embedded_texture(w, emb, name, wu, wv, &oom);
    } else if (strncmp(path.data, "data:", 5) == 0 || !w->c->path) {
        /* a data: URI assimp did not decode, or a model read from memory:
         * nothing to open */
        char name[80];
        snprintf(name, sizeof name, "%.60s%s", path.data, path.length > 60 ? "..." : "");
        mt->tex = mb_texture_missing(&w->b, name, w->c->path ? "not an image zview can read" : "no file to read it from",
                                     wu, wv, &oom);
    } else {
        char *file = texture_file(w->c->path, path.data);
        if (!file)
            return me_oom(&w->c->err);
        mt->tex = mb_texture(&w->b, file, file, NULL, 0, wu, wv, &oom);
        free(file);
    }
    if (oom)
        return -1;
    /* KHR_texture_transform and the like; assimp's v runs up, ours down */
    float tr[5];
    unsigned int n = 5;
    if (ai()->aiGetMaterialFloatArray(mat, _AI_MATKEY_UVTRANSFORM_BASE, type, 0, tr, &n) == aiReturn_SUCCESS &&
        n >= 4) {
        mt->tex_scale[0] = tr[2];
        mt->tex_scale[1] = tr[3];
        mt->tex_off[0] = tr[0];
        mt->tex_off[1] = 1.0f - tr[3] - tr[1];
    } else {
        mt->tex_off[1] = 0;     /* the flip is done on the coordinates themselves */
    }
    return 0;
}

/* ==== Materials ==== */

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
    if (k < 0 || material_texture(w, mat, &w->b.m->mats[k]))
        return -3;
    return w->matmap[i] = k;
}

/* Does assimp material i have a base-colour texture? */
static int textured(const Walk *w, unsigned i)
{
    struct aiString path;
    if (i >= w->sc->mNumMaterials)
        return 0;
    const struct aiMaterial *mat = w->sc->mMaterials[i];
    return !w->c->err.no_textures &&
           (ai()->aiGetMaterialTexture(mat, aiTextureType_BASE_COLOR, 0, &path, NULL, NULL, NULL, NULL, NULL,
                                       NULL) == aiReturn_SUCCESS ||
            ai()->aiGetMaterialTexture(mat, aiTextureType_DIFFUSE, 0, &path, NULL, NULL, NULL, NULL, NULL, NULL) ==
                aiReturn_SUCCESS);
}

static uint32_t sat_add(uint32_t a, uint32_t b)
{
    return a > UINT32_MAX - b ? UINT32_MAX : a + b;
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
    const struct aiVector3D *tc = am->mTextureCoords[0];
    struct aiColor4D bc = { 1, 1, 1, 1 };
    if (am->mMaterialIndex < w->sc->mNumMaterials)
        bc = base_colour(w->sc->mMaterials[am->mMaterialIndex]);
    /* a texture wins over vertex colours */
    if (!tc || !textured(w, am->mMaterialIndex))
        tc = NULL;
    else
        vc = NULL;
    if (vc && mb_want_rgb(&w->b))
        return -1;
    if (tc && mb_want_vertex_uv(&w->b))
        return -1;
    /* what the file carries, for --info (OBJ counts its vt and vn lines) */
    if (am->mTextureCoords[0])
        m->info.texcoords = sat_add(m->info.texcoords, am->mNumVertices);
    if (am->mNormals)
        m->info.normals = sat_add(m->info.normals, am->mNumVertices);
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
        if (w->b.uv_per_vertex) {
            /* assimp's v runs up the image, ours down */
            float *d = m->uv + 2 * (size_t)(m->nverts - 1);
            d[0] = tc ? tc[v].x : 0;
            d[1] = tc ? 1.0f - tc[v].y : 0;
        }
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

/* ==== How the model stands ====
 * Where a format fixes its axes, the model's up axis (and its front, for
 * the first view) come from the format; assimp hands coordinates over as
 * the file has them, but for COLLADA, whose <up_axis> it applies to the
 * root node itself (so the model arrives y-up, and is not turned again
 * here), and FBX, whose axes it leaves in the scene's metadata. The
 * importer is named by the scene's metadata, whatever the extension. */

typedef struct {
    const char *importer;       /* start of assimp's importer name */
    int         up, front;      /* UpAxis values; front -1: none */
    const char *why;
} AiStance;

static const AiStance ai_stances[] = {
    { "glTF", UP_Y, UP_Z, "glTF: y-up by its specification, the front towards +z" },
    { "3mf", UP_Z, -1, "3MF: z-up by its specification" },
    { "Additive manufacturing", UP_Z, -1, "AMF: z-up by its specification" },
    { "Blender", UP_Z, UP_NEG_Y, "Blender: z-up, the front towards -y" },
    { "Stereolithography", UP_Z, -1, "STL: the 3D-printing convention" },
    { "TrueSpace", UP_Z, -1, "trueSpace: z-up" },
    { "Quick3D", UP_Z, -1, "Quick3D: z-up, as its files are written" },
    { "Valve SMD", UP_Z, -1, "SMD: z-up, as in Valve's engines" },
};

/* A metadata entry of the scene by key, NULL if none. */
static const struct aiMetadataEntry *ai_meta(const struct aiScene *sc, const char *key)
{
    const struct aiMetadata *md = sc->mMetaData;
    if (!md || !md->mKeys || !md->mValues)
        return NULL;
    for (unsigned i = 0; i < md->mNumProperties; i++)
        if (strcmp(md->mKeys[i].data, key) == 0 && md->mValues[i].mData)
            return &md->mValues[i];
    return NULL;
}

static int ai_meta_int(const struct aiScene *sc, const char *key, int *out)
{
    const struct aiMetadataEntry *e = ai_meta(sc, key);
    if (!e || e->mType != AI_INT32)
        return 0;
    memcpy(out, e->mData, sizeof *out);
    return 1;
}

/* FBX's axis (0 x, 1 y, 2 z) and sign as an UpAxis, -1 if invalid. */
static int fbx_axis(int axis, int sign)
{
    static const int pos[3] = { UP_X, UP_Y, UP_Z }, neg[3] = { UP_NEG_X, UP_NEG_Y, UP_NEG_Z };
    if (axis < 0 || axis > 2 || (sign != 1 && sign != -1))
        return -1;
    return sign > 0 ? pos[axis] : neg[axis];
}

static void fbx_stance(MeshInfo *in, const struct aiScene *sc)
{
    static const char *const names[UP_COUNT] = { "+y", "+z", "+x", "-y", "-z", "-x" };
    int axis, sign = 1, up = -1, front = -1;
    if (ai_meta_int(sc, "UpAxis", &axis) && ai_meta_int(sc, "UpAxisSign", &sign))
        up = fbx_axis(axis, sign);
    if (ai_meta_int(sc, "FrontAxis", &axis) && ai_meta_int(sc, "FrontAxisSign", &sign))
        front = fbx_axis(axis, sign);
    if (up < 0) {
        snprintf(in->up_why, sizeof in->up_why, "FBX: no UpAxis in the file");
        return;
    }
    in->up = up;
    in->front = front == up || front == (up + 3) % UP_COUNT ? -1 : front;
    snprintf(in->up_why, sizeof in->up_why, "FBX: UpAxis %s%s%s", names[up], in->front >= 0 ? ", FrontAxis " : "",
             in->front >= 0 ? names[in->front] : "");
}

/* COLLADA's <up_axis> (X_UP, Y_UP, Z_UP) from the head of the document,
 * where its <asset> is; "" when it is not there (Y_UP is the default). */
static void collada_up_axis(const char *h, size_t n, char out[8])
{
    static const char tag[] = "<up_axis>";
    out[0] = 0;
    for (size_t i = 0; i + sizeof tag - 1 + 4 <= n; i++) {
        if (memcmp(h + i, tag, sizeof tag - 1))
            continue;
        const char *v = h + i + sizeof tag - 1;
        size_t k = 0;
        while (v + k < h + n && k < 7 && (v[k] == '_' || (v[k] >= 'A' && v[k] <= 'Z')))
            k++;
        memcpy(out, v, k);
        out[k] = 0;
        return;
    }
}

#define COLLADA_HEAD 65536

/* data: the file in memory, or NULL to read the head of c->path. */
static void collada_stance(MeshCtx *c, const char *data, size_t len)
{
    MeshInfo *in = &c->m->info;
    char axis[8] = "";
    if (data)
        collada_up_axis(data, len < COLLADA_HEAD ? len : COLLADA_HEAD, axis);
    else if (c->path) {
        char *buf = malloc(COLLADA_HEAD);
        FILE *f = buf ? fopen(c->path, "rb") : NULL;
        if (f) {
            collada_up_axis(buf, fread(buf, 1, COLLADA_HEAD, f), axis);
            fclose(f);
        }
        free(buf);
    }
    in->up = UP_Y;
    in->front = -1;
    if (axis[0] && strcmp(axis, "Y_UP"))
        snprintf(in->up_why, sizeof in->up_why, "COLLADA: up_axis %s, turned upright by assimp", axis);
    else if (axis[0])
        snprintf(in->up_why, sizeof in->up_why, "COLLADA: up_axis %s", axis);
    else
        snprintf(in->up_why, sizeof in->up_why, "COLLADA: no up_axis, so Y_UP");
}

static void ai_stance(MeshCtx *c, const struct aiScene *sc, const char *data, size_t len)
{
    const struct aiMetadataEntry *e = ai_meta(sc, "SourceAsset_Format");
    const char *imp = e && e->mType == AI_AISTRING ? ((const struct aiString *)e->mData)->data : "";
    MeshInfo *in = &c->m->info;
    if (strncmp(imp, "Autodesk FBX", 12) == 0)
        return fbx_stance(in, sc);
    if (strncmp(imp, "Collada", 7) == 0)
        return collada_stance(c, data, len);
    for (size_t i = 0; i < sizeof ai_stances / sizeof ai_stances[0]; i++)
        if (strncmp(imp, ai_stances[i].importer, strlen(ai_stances[i].importer)) == 0) {
            in->up = ai_stances[i].up;
            in->front = ai_stances[i].front;
            snprintf(in->up_why, sizeof in->up_why, "%s", ai_stances[i].why);
            return;
        }
    /* the rest: as every format that does not say (format.c) */
}

/* assimp's message as one line: its lines joined (a run of newlines and
 * blanks is one space), cut at AI_MSG_MAX bytes with "...". What it
 * quotes from the file is made safe where it is printed (safetext.h). */
#define AI_MSG_MAX 300
static int import_failed(MeshCtx *c)
{
    const char *s = ai()->aiGetErrorString();
    if (!s || !*s)
        s = "assimp could not read it";
    char msg[AI_MSG_MAX + 4];
    size_t o = 0;
    const char *p = s;
    for (; *p && o < AI_MSG_MAX; p++) {
        if (strchr(" \t\r\n", *p)) {
            p += strspn(p, " \t\r\n") - 1;
            if (o && p[1])
                msg[o++] = ' ';
        } else {
            msg[o++] = *p;
        }
    }
    if (*p) {
        memcpy(msg + o, "...", 3);
        o += 3;
    }
    msg[o] = '\0';
    if (strstr(msg, "bad_alloc"))   /* the sandbox's bound (which it names) or the machine's */
        return me_fail(&c->err, "out of memory reading it (assimp: %.100s)", msg);
    return me_fail(&c->err, "%s", msg);
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
    /* meshes no node names (assimp's AC3D importer makes a mesh of
     * points for an object without surfaces and leaves it out of the
     * node): shown as they are, when the nodes gave nothing */
    if (!m->nfaces && !m->npoints && !m->nlines)
        for (unsigned k = 0; k < sc->mNumMeshes; k++)
            if (sc->mMeshes[k] && add_mesh(&w, sc->mMeshes[k], &id, 1))
                goto out;
    r = mb_finish(&w.b, 1);
out:
    free(w.matmap);
    if (r)
        mb_abort(&w.b);
    return r;
}

/* A file told by content has no extension to name its format: the
 * importer's name, when it gives one. */
static void ai_name_format(MeshCtx *c, const struct aiScene *sc)
{
    if (c->hint && *c->hint && strcmp(c->hint, "assimp"))
        return;
    const struct aiMetadataEntry *e = ai_meta(sc, "SourceAsset_Format");
    const char *imp = e && e->mType == AI_AISTRING ? ((const struct aiString *)e->mData)->data : "";
    size_t n = strlen(imp);
    if (n > 9 && strcmp(imp + n - 9, " Importer") == 0)
        n -= 9;   /* "AC3D Importer": the format is AC3D */
    if (n > 20)
        n = 20;
    snprintf(c->m->info.format, sizeof c->m->info.format, "%.*s (assimp)", (int)(n ? n : 15),
             n ? imp : "told by content");
}

/* A file's bytes (a glTF's JSON, read again to be mended). */
static char *read_whole(const char *path, size_t *len_out)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    long n = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    if (n >= 0 && fseek(f, 0, SEEK_SET) == 0 && (buf = malloc((size_t)n + 1)) &&
        fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    *len_out = (size_t)n;
    return buf;
}

/* assimp refused a glTF for an image whose data: URI is not base64
 * (its message says so): the import again with each such image replaced
 * (datauri.c), so the model draws and each is one warning
 * (embedded_texture). The model at path, or in memory (data, len). NULL
 * when that is not the case or the model fails still (and then
 * assimp's message is the second import's). */
static const struct aiScene *import_mended(MeshCtx *c, unsigned flags, const char *path, const char *data,
                                           size_t len)
{
    const char *why = ai()->aiGetErrorString();
    if (!why || !strstr(why, "base64") || !c->hint || strcmp(c->hint, "gltf"))
        return NULL;
    char *own = data ? NULL : read_whole(path, &len);
    if (!data && !own)
        return NULL;
    size_t ml;
    int n;
    char *mended = mesh_gltf_mend_images(data ? data : own, len, &ml, &n);
    free(own);
    if (!mended)
        return NULL;
    AiIo io;
    ai_io_init(&io, &c->err, path, path ? NULL : mended, ml, "gltf");
    io.model_data = mended;         /* served under the model's own path */
    io.model_len = ml;
    const struct aiScene *sc = ai()->aiImportFileEx(path ? path : io.name, flags, &io.fio);
    free(mended);                   /* assimp has read it into its own */
    return sc;
}

static int no_library(MeshCtx *c)
{
    return me_fail(&c->err, "the assimp library (%s) cannot be opened", ZV_ASSIMP_SONAME);
}

static int ai_parse_path(MeshCtx *c, const char *path)
{
    if (!ai())
        return no_library(c);
    /* what the model names is opened beneath its folder only (assimpio.c) */
    AiIo io;
    ai_io_init(&io, &c->err, path, NULL, 0, NULL);
    const struct aiScene *sc = ai()->aiImportFileEx(path, ai_flags(c->hint), &io.fio);
    if (!sc)
        sc = import_mended(c, ai_flags(c->hint), path, NULL, 0);
    if (!sc)
        return import_failed(c);
    int r = from_scene(c, sc);
    if (r == 0) {
        ai_stance(c, sc, NULL, 0);
        ai_name_format(c, sc);
    }
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

/* The extension of the format ai_probe knows these bytes by ("" for
 * none). */
static const char *content_hint(const char *h, size_t n)
{
    if (n > MESH_HEAD)
        n = MESH_HEAD;
    if (n >= 4 && memcmp(h, "glTF", 4) == 0)
        return "glb";
    if (n >= 18 && memcmp(h, "Kaydara FBX Binary", 18) == 0)
        return "fbx";
    if (n >= 7 && memcmp(h, "BLENDER", 7) == 0)
        return "blend";
    size_t i = 0;
    while (i < n && mesh_is_ws(h[i]))
        i++;
    if (i < n && h[i] == '{' && has_word(h, n, "\"asset\""))
        return "gltf";
    if (i < n && h[i] == '<' && has_word(h, n, "<COLLADA"))
        return "dae";
    if (i < n && h[i] == '<' && has_word(h, n, "<X3D"))
        return "x3d";
    if (n >= 18 && memcmp(h, "; FBX", 5) == 0)
        return "fbx";
    return "";
}

static int ai_parse(MeshCtx *c, const char *data, size_t len)
{
    if (!ai())
        return no_library(c);
    if (len > UINT_MAX)
        return me_fail(&c->err, "too large for assimp from memory");
    /* the hint is an extension, or "assimp" when forced without one;
     * without one (standard input) the content names the format, as
     * assimp from memory goes by the hint */
    const char *hint = c->hint && strcmp(c->hint, "assimp") ? c->hint : "";
    if (!*hint) {
        hint = content_hint(data, len);
        if (*hint)
            c->hint = hint;   /* and the format's unit and name follow it */
    }
    /* from memory through a file system of its own, which serves the
     * bytes and nothing else: assimp's own memory import would open the
     * files a model names from the current folder */
    AiIo io;
    ai_io_init(&io, &c->err, NULL, data, len, hint);
    const struct aiScene *sc = ai()->aiImportFileEx(io.name, ai_flags(hint), &io.fio);
    if (!sc)
        sc = import_mended(c, ai_flags(hint), NULL, data, len);
    if (!sc)
        return import_failed(c);
    int r = from_scene(c, sc);
    if (r == 0) {
        c->m->info.bytes = len;
        ai_stance(c, sc, data, len);
        ai_name_format(c, sc);
    }
    ai()->aiReleaseImport(sc);
    return r;
}


/* Formats with a magic or a telling header; the rest go by extension. */
static int ai_probe(const char *h, size_t n, uint64_t size)
{
    (void)size;
    if (n >= 8 && memcmp(h, "glTF", 4) == 0 && rd_u32le(h + 4) == 2)
        return PROBE_SURE;
    if (n >= 18 && memcmp(h, "Kaydara FBX Binary", 18) == 0)
        return PROBE_SURE;
    if (n >= 7 && memcmp(h, "BLENDER", 7) == 0)
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
