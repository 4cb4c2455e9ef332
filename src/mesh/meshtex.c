/* meshtex.c: what a model brings for its textures. Texture coordinates
 * (per face corner, as OBJ's vt gives them, or per vertex, as PLY and
 * assimp do) and the images its materials name, each read once per name
 * and wrap mode: decoded while loading, or, when big and the load defers
 * such, kept pending with their source for a thread of the viewer's (a
 * 16k x 16k image takes seconds to decode; the first picture does not
 * wait for it). An image that cannot be read is one warning that names
 * it, and its faces keep their base colour. */
#define _DEFAULT_SOURCE

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "grow.h"
#include "mesh_internal.h"

/* ==== Texture coordinates ==== */

int mb_uv(MeshBuild *b, float u, float v)
{
    Mesh *m = b->m;
    if (m->nuv >= UINT32_MAX - 1)
        return me_fail(b->e, "too many texture coordinates");
    if (m->nuv == b->uvcap && grow_size((void **)&m->uv, &b->uvcap, (size_t)m->nuv + 1, 2 * sizeof(float)))
        return me_oom(b->e);
    m->uv[2 * (size_t)m->nuv] = u;
    m->uv[2 * (size_t)m->nuv + 1] = v;
    m->nuv++;
    return 0;
}

int mb_corner_uv(MeshBuild *b, uint32_t uvi)
{
    Mesh *m = b->m;
    if (!m->corner_uv) {
        if (uvi == MESH_NO_UV)
            return 0;
        /* as long as corner[]: mb_room_corners grows both from here on */
        m->corner_uv = malloc((b->ccap ? b->ccap : 1) * sizeof *m->corner_uv);
        if (!m->corner_uv)
            return me_oom(b->e);
        for (size_t c = 0; c < b->ncorner; c++)
            m->corner_uv[c] = MESH_NO_UV;
    }
    ZV_ASSERT(b->ncorner > 0);
    m->corner_uv[b->ncorner - 1] = uvi;
    return 0;
}

int mb_want_vertex_uv(MeshBuild *b)
{
    Mesh *m = b->m;
    if (m->uv)
        return 0;
    m->uv = calloc((b->vcap ? b->vcap : 1) * 2, sizeof(float));
    if (!m->uv)
        return me_oom(b->e);
    b->uv_per_vertex = 1;
    b->uvcap = b->vcap;
    return 0;
}

/* ==== Textures ==== */

void mb_material_no_texture(Material *mt)
{
    mt->tex = -1;
    mt->tex_off[0] = mt->tex_off[1] = 0;
    mt->tex_scale[0] = mt->tex_scale[1] = 1;
}

/* A file's bytes, for an image: regular files only (a FIFO would block
 * for ever), no bigger than the texels of the largest image allowed
 * (compressed images are far smaller). 0, or -1 with the reason. */
static int read_image_file(MeshErr *e, const char *path, void **data_out, size_t *len_out, char *why,
                           size_t whylen)
{
    struct stat st;
    *data_out = NULL;
    *len_out = 0;
    /* beneath the model's folder, a regular file (mesh_ref_open); no
     * model (e NULL), no file */
    int fd = e ? me_ref_open(e, e->model, path, 1, why, whylen) : mesh_ref_open(NULL, path, why, whylen);
    if (fd < 0)
        return -1;
    if (fstat(fd, &st) != 0) {
        snprintf(why, whylen, "%s", strerror(errno));
        close(fd);
        return -1;
    }
    if ((uint64_t)st.st_size > texture_bytes_for(TEX_MAX_SIDE, TEX_MAX_SIDE)) {
        snprintf(why, whylen, "too large for an image");
        close(fd);
        return -1;
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        snprintf(why, whylen, "%s", strerror(errno));
        close(fd);
        return -1;
    }
    size_t n = (size_t)st.st_size;
    void *buf = malloc(n ? n : 1);
    size_t got = buf ? fread(buf, 1, n, f) : 0;
    int bad = !buf ? 2 : got != n || ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        snprintf(why, whylen, "%s", bad == 2 ? "out of memory" : "read error");
        return -1;
    }
    *data_out = buf;
    *len_out = n;
    return 0;
}

/* The texture already listed under this name and wrap mode, -1 none. */
static int32_t find_texture(const Mesh *m, const char *name, TexWrap wu, TexWrap wv)
{
    for (uint32_t i = 0; i < m->ntex; i++)
        if (strcmp(m->tex[i].name, name) == 0 && m->tex[i].img.wrap_u == wu && m->tex[i].img.wrap_v == wv)
            return (int32_t)i;
    return -1;
}

/* A new entry named name (state failed until told otherwise). */
static MeshTexture *new_texture(MeshBuild *b, const char *name, TexWrap wu, TexWrap wv)
{
    Mesh *m = b->m;
    if (m->ntex >= INT32_MAX - 1)
        return NULL;
    if (m->ntex == b->tcap) {
        uint32_t nc = b->tcap ? 2 * b->tcap : 4;
        MeshTexture *nt = realloc(m->tex, nc * sizeof *nt);
        if (!nt)
            return NULL;
        m->tex = nt;
        b->tcap = nc;
    }
    MeshTexture *t = &m->tex[m->ntex];
    memset(t, 0, sizeof *t);
    t->name = strdup(name);
    if (!t->name)
        return NULL;
    t->state = MTEX_FAILED;
    t->img.wrap_u = wu;
    t->img.wrap_v = wv;
    m->ntex++;
    return t;
}

/* The warning for a texture that cannot be read, counted in the info. */
static void texture_failed(MeshBuild *b, const char *name, const char *why)
{
    MeshInfo *info = &b->m->info;
    char msg[256];
    snprintf(msg, sizeof msg, "texture %s: %s; its faces show their base colour", name, why);
    if (info->tex_failed++ == 0)
        snprintf(info->first_tex_failed, sizeof info->first_tex_failed, "%s", msg);
    me_warn(b->e, NULL, 0, "%s", msg);
}

int mesh_texture_decode(const MeshTexture *t, uint64_t max_bytes, Texture *out, int *halved_out, char *err,
                        size_t errlen)
{
    void *data = t->data;
    size_t len = t->len;
    char why[160];
    memset(out, 0, sizeof *out);
    /* a pending texture's path has no model to be confined to (and may
     * have come from a sandboxed child): none is opened */
    if (!data && t->path && read_image_file(NULL, t->path, &data, &len, why, sizeof why)) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    char e2[256];
    int rc = texture_decode_fit(out, data, len, t->name, max_bytes, TEX_FIT_SIDE, halved_out, e2, sizeof e2);
    if (rc) {
        /* the decoder's message starts with the name given */
        size_t n = strlen(t->name);
        snprintf(err, errlen, "%s", strncmp(e2, t->name, n) == 0 && e2[n] == ':' ? e2 + n + 2 : e2);
    }
    if (data != t->data)
        free(data);
    out->wrap_u = t->img.wrap_u;
    out->wrap_v = t->img.wrap_v;
    return rc;
}

void mesh_texture_install(MeshTexture *t, int rc, Texture *img, int halved)
{
    free(t->path);
    free(t->data);
    t->path = NULL;
    t->data = NULL;
    t->len = 0;
    if (rc) {
        texture_free(img);
        t->state = MTEX_FAILED;
        return;
    }
    TexWrap wu = t->img.wrap_u, wv = t->img.wrap_v;
    texture_free(&t->img);
    t->img = *img;
    t->img.wrap_u = wu;
    t->img.wrap_v = wv;
    t->halved = halved;
    t->state = MTEX_OK;
    memset(img, 0, sizeof *img);
}

/* Decode now, or keep the bytes when the image is big and the load
 * defers such. data is taken over (freed or kept). */
static void decode_or_defer(MeshBuild *b, MeshTexture *t, void *data, size_t len)
{
    MeshErr *e = b->e;
    texture_peek(data, len, &t->src_w, &t->src_h);
    if (e->tex_defer_side > 0 && (t->src_w > e->tex_defer_side || t->src_h > e->tex_defer_side)) {
        t->data = data;
        t->len = len;
        t->state = MTEX_PENDING;
        return;
    }
    t->data = data;
    t->len = len;
    Texture img;
    char why[256];
    int halved = 0;
    int rc = mesh_texture_decode(t, e->max_bytes, &img, &halved, why, sizeof why);
    t->data = NULL;
    free(data);
    t->len = 0;
    mesh_texture_install(t, rc, &img, halved);
    if (rc)
        texture_failed(b, t->name, why);
}

/* The texture of this name and wrap modes (its index, *t_new NULL), or a
 * new one for the caller to fill (*t_new). -1 when textures are off, or
 * out of memory (*oom set). */
static int32_t texture_slot(MeshBuild *b, const char *name, TexWrap wrap_u, TexWrap wrap_v, int *oom,
                            MeshTexture **t_new)
{
    *oom = 0;
    *t_new = NULL;
    if (b->e->no_textures)
        return -1;
    int32_t i = find_texture(b->m, name, wrap_u, wrap_v);
    if (i >= 0)
        return i;
    MeshTexture *t = new_texture(b, name, wrap_u, wrap_v);
    if (!t) {
        *oom = 1;
        me_oom(b->e);
        return -1;
    }
    *t_new = t;
    return (int32_t)(t - b->m->tex);
}

/* A reference whose last name is "." or ".." (or nothing: "dir/")
 * names a folder, whatever is there: said so rather than whatever
 * opening it would say ("map_Kd ." was "a symbolic link leads out"). */
static int names_a_folder(const char *path)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    return !*base || !strcmp(base, ".") || !strcmp(base, "..");
}

int32_t mb_texture(MeshBuild *b, const char *name, const char *path, const void *data, size_t len,
                   TexWrap wrap_u, TexWrap wrap_v, int *oom)
{
    MeshTexture *t;
    int32_t i = texture_slot(b, name, wrap_u, wrap_v, oom, &t);
    if (!t)
        return i;      /* there already, textures off, or out of memory */
    if (path && names_a_folder(path)) {
        texture_failed(b, name, "a folder, not an image");
        return i;
    }

    void *bytes = NULL;
    char why[160];
    if (path) {
        if (read_image_file(b->e, path, &bytes, &len, why, sizeof why)) {
            texture_failed(b, name, why);
            return i;
        }
    } else {
        bytes = malloc(len ? len : 1);
        if (!bytes) {
            texture_failed(b, name, "out of memory");
            return i;
        }
        memcpy(bytes, data, len);
    }
    decode_or_defer(b, t, bytes, len);
    return i;
}

int32_t mb_texture_rgba(MeshBuild *b, const char *name, const uint8_t *rgba, int w, int h, TexWrap wrap_u,
                        TexWrap wrap_v, int *oom)
{
    MeshTexture *t;
    int32_t i = texture_slot(b, name, wrap_u, wrap_v, oom, &t);
    if (!t)
        return i;      /* there already, textures off, or out of memory */
    t->src_w = w;
    t->src_h = h;
    Texture img;
    char why[256];
    if (texture_from_rgba(&img, rgba, w, h, name, b->e->max_bytes, why, sizeof why)) {
        texture_failed(b, name, why);
        return i;
    }
    mesh_texture_install(t, 0, &img, 0);
    return i;
}

int32_t mb_texture_missing(MeshBuild *b, const char *name, const char *why, TexWrap wrap_u, TexWrap wrap_v,
                           int *oom)
{
    MeshTexture *t;
    int32_t i = texture_slot(b, name, wrap_u, wrap_v, oom, &t);
    if (!t)
        return i;      /* there already, textures off, or out of memory */
    texture_failed(b, name, why);
    return i;
}

/* ==== Reading them back ==== */

const Texture *mesh_material_texture(const Mesh *m, int32_t mat)
{
    if (mat < 0 || (uint32_t)mat >= m->nmats)
        return NULL;
    int32_t t = m->mats[mat].tex;
    if (t < 0 || (uint32_t)t >= m->ntex || m->tex[t].state != MTEX_OK)
        return NULL;
    return &m->tex[t].img;
}

uint64_t mesh_texture_bytes(const Mesh *m)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < m->ntex; i++)
        if (m->tex[i].state == MTEX_OK)
            n += texture_bytes(&m->tex[i].img);
    return n;
}

void mesh_free_textures(Mesh *m)
{
    for (uint32_t i = 0; i < m->ntex; i++) {
        texture_free(&m->tex[i].img);
        free(m->tex[i].name);
        free(m->tex[i].path);
        free(m->tex[i].data);
    }
    free(m->tex);
    free(m->uv);
    free(m->corner_uv);
    m->tex = NULL;
    m->ntex = 0;
    m->uv = NULL;
    m->nuv = 0;
    m->corner_uv = NULL;
}
