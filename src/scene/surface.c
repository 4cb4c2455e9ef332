/* surface.c: what a face's colour comes from when it varies across the
 * face. A face whose material has a base-colour texture, and whose
 * corners all have texture coordinates, is textured: it refers to a
 * surface (the material's texture, base colour and coordinate
 * transform), and its polygon corners carry their coordinates. A face
 * without a material whose corners have different vertex colours has
 * them interpolated. Every other face keeps one colour. Shading reads
 * this (src/shade/texel.c); nothing here depends on the view. */

#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "scene_internal.h"

/* The base colour as shading multiplies the texture by it: the byte the
 * untextured face would show, decoded, so that a white texture looks
 * as the material alone does. */
static float factor_of(float kd)
{
    float c = kd <= 0 ? 0 : kd >= 1 ? 255 : kd * 255.0f + 0.5f;
    return srgb_to_linear((uint8_t)c);
}

int surf_build_start(SurfBuild *sb, Scene *s, const Mesh *meshes, int nmeshes, uint64_t nfaces)
{
    memset(sb, 0, sizeof *sb);
    int want = 0;
    for (int i = 0; i < nmeshes; i++) {
        const Mesh *m = &meshes[i];
        want |= m->rgb != NULL || (m->uv != NULL && m->ntex > 0);
        if (m->nmats > sb->cap)
            sb->cap = m->nmats;
    }
    if (!want)
        return 0;
    s->face_surf = calloc(nfaces ? nfaces : 1, sizeof *s->face_surf);
    sb->matsurf = malloc((sb->cap ? sb->cap : 1) * sizeof *sb->matsurf);
    if (!s->face_surf || !sb->matsurf)
        return -1;
    sb->on = 1;
    return 0;
}

void surf_build_mesh(SurfBuild *sb, const Mesh *m)
{
    sb->mesh = m;
    if (sb->on)
        for (uint32_t i = 0; i < m->nmats; i++)
            sb->matsurf[i] = -1;
}

/* The surface of material mat of the current mesh, made on first use;
 * -1 when the scene has as many as it can hold. */
static int32_t surface_of(SurfBuild *sb, Scene *s, int32_t mat)
{
    if (sb->matsurf[mat] >= 0)
        return sb->matsurf[mat];
    if (s->nsurf >= SCENE_SURF_MAX)
        return -1;
    if (s->nsurf == sb->surfcap) {
        uint32_t nc = sb->surfcap ? 2 * sb->surfcap : 8;
        SceneSurf *n = realloc(s->surf, nc * sizeof *n);
        if (!n)
            return -1;
        s->surf = n;
        sb->surfcap = nc;
    }
    const Mesh *m = sb->mesh;
    const Material *mt = &m->mats[mat];
    SceneSurf *su = &s->surf[s->nsurf];
    su->tex = &m->tex[mt->tex];
    for (int a = 0; a < 3; a++)
        su->factor[a] = factor_of(mt->kd[a]);
    su->off[0] = mt->tex_off[0];
    su->off[1] = mt->tex_off[1];
    su->scale[0] = mt->tex_scale[0];
    su->scale[1] = mt->tex_scale[1];
    return sb->matsurf[mat] = (int32_t)s->nsurf++;
}

void surf_mean_rgb(const SceneSurf *su, uint8_t rgb_out[3])
{
    const Texture *t = &su->tex->img;
    const uint8_t *top = t->rgba + 4 * t->off[t->levels - 1];   /* 1 x 1: the mean */
    for (int a = 0; a < 3; a++)
        rgb_out[a] = linear_to_srgb(srgb_to_linear(top[a]) * su->factor[a]);
}

/* Does every corner of face f have a texture coordinate? */
static int corners_have_uv(const Mesh *m, uint32_t f)
{
    if (!m->uv)
        return 0;
    if (!m->corner_uv)
        return 1;
    for (uint32_t k = m->face_start[f]; k < m->face_start[f + 1]; k++)
        if (m->corner_uv[k] == MESH_NO_UV)
            return 0;
    return 1;
}

/* Do face f's corners differ in colour? */
static int corners_differ(const Mesh *m, uint32_t f)
{
    const float *c0 = &m->rgb[3 * (size_t)m->corner[m->face_start[f]]];
    for (uint32_t k = m->face_start[f] + 1; k < m->face_start[f + 1]; k++)
        if (memcmp(c0, &m->rgb[3 * (size_t)m->corner[k]], 3 * sizeof(float)) != 0)
            return 1;
    return 0;
}

int surf_of_face(SurfBuild *sb, Scene *s, uint32_t f, uint32_t gface, uint8_t rgb_inout[3])
{
    if (!sb->on)
        return SURF_PLAIN;
    const Mesh *m = sb->mesh;
    int32_t mat = m->face_mat ? m->face_mat[f] : -1;
    int kind = SURF_PLAIN;
    if (mat >= 0 && (uint32_t)mat < m->nmats) {
        int32_t t = m->mats[mat].tex;
        if (t >= 0 && (uint32_t)t < m->ntex && m->tex[t].state != MTEX_FAILED && corners_have_uv(m, f)) {
            int32_t k = surface_of(sb, s, mat);
            if (k >= 0) {
                kind = SURF_TEX0 + k;
                if (m->tex[t].state == MTEX_OK)
                    surf_mean_rgb(&s->surf[k], rgb_inout);
            }
        }
    } else if (m->rgb && corners_differ(m, f)) {
        kind = SURF_VCOLOUR;
    }
    s->face_surf[gface] = (uint16_t)kind;
    return kind;
}

void surf_build_end(SurfBuild *sb, Scene *s)
{
    free(sb->matsurf);
    sb->matsurf = NULL;
    if (!s->face_surf)
        return;
    int any = 0;
    for (uint32_t f = 0; f < s->nfaces && !any; f++)
        any = s->face_surf[f] != SURF_PLAIN;
    if (!any) {
        free(s->face_surf);
        s->face_surf = NULL;
    }
}

int surf_want_uv(const Scene *s)
{
    return s->nsurf > 0;
}

void scene_texture_count(const Scene *s, TextureCount *out)
{
    memset(out, 0, sizeof *out);
    for (int i = 0; i < s->nmeshes; i++) {
        const Mesh *m = &s->meshes[i];
        out->count += m->ntex;
        out->bytes += mesh_texture_bytes(m);
        for (uint32_t k = 0; k < m->ntex; k++) {
            out->failed += m->tex[k].state == MTEX_FAILED;
            out->pending += m->tex[k].state == MTEX_PENDING;
        }
    }
}

void surf_corner_uv(const Mesh *m, uint32_t k, float *out)
{
    uint32_t i = !m->uv ? MESH_NO_UV : m->corner_uv ? m->corner_uv[k] : m->corner[k];
    if (i == MESH_NO_UV || i >= m->nuv) {
        out[0] = out[1] = 0;
        return;
    }
    out[0] = m->uv[2 * (size_t)i];
    out[1] = m->uv[2 * (size_t)i + 1];
}
