/* objwrite.c: Wavefront OBJ text and its MTL material library.
 *
 * The OBJ: every vertex in order (`v x y z`, with `r g b` after when the
 * mesh has vertex colours), the texture coordinates (`vt`), then object
 * by object (`o NAME`) its faces (`f`, polygons as they are, `v/vt`
 * where a corner has a texture coordinate), points (`p`) and polylines
 * (`l`), with `usemtl` where the material changes (a bare `usemtl` back
 * to no material). Indices are 1-based and absolute, so the vertex,
 * face, point and line ids read back as they were. Numbers are the
 * shortest decimals that read back bit for bit (savenum.c); a texture
 * coordinate's v is stored down the image and written up it (1 - v),
 * which float arithmetic cannot always undo exactly: the nearest that
 * reads back is written.
 *
 * The MTL: per material `newmtl`, `Kd`, `d`, and `map_Kd` with `-o`,
 * `-s` and `-clamp on` as the reader takes them. A texture's name is
 * kept as the model named it: relative to the model's folder, so that
 * an OBJ written beside the one it was read from finds its images.
 * Names are made one statement each (save_name_clean) and unique (a
 * second "wood" is "wood_2"): usemtl finds materials by name. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "save_internal.h"

/* ==== Names ==== */

char *save_name_clean(char *dst, size_t n, const char *src)
{
    while (*src == ' ' || *src == '\t')
        src++;
    size_t k = 0;
    for (; *src && k + 1 < n; src++)
        dst[k++] = (unsigned char)*src < 0x20 || *src == 0x7f ? '_' : *src;
    while (k > 0 && (dst[k - 1] == ' ' || dst[k - 1] == '\t'))
        k--;
    if (k > 0 && dst[k - 1] == '\\')
        dst[k - 1] = '_';
    dst[k] = 0;
    return dst;
}

static int by_name(const void *a, const void *b, void *names)
{
    const char (*nm)[SAVE_NAME] = names;
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    int c = strcmp(nm[i], nm[j]);
    return c ? c : (i > j) - (i < j);
}

/* Material indices sorted by name, the lower index first among equals
 * (qsort has no context argument in C11: a merge sort of our own). */
static void sort_by_name(uint32_t *idx, uint32_t *tmp, uint32_t n, char (*names)[SAVE_NAME])
{
    if (n < 2)
        return;
    uint32_t h = n / 2;
    sort_by_name(idx, tmp, h, names);
    sort_by_name(idx + h, tmp, n - h, names);
    uint32_t i = 0, j = h, k = 0;
    while (i < h && j < n)
        tmp[k++] = by_name(&idx[i], &idx[j], names) <= 0 ? idx[i++] : idx[j++];
    while (i < h)
        tmp[k++] = idx[i++];
    while (j < n)
        tmp[k++] = idx[j++];
    memcpy(idx, tmp, n * sizeof *idx);
}

int save_obj_names(const Mesh *m, char (*names)[SAVE_NAME])
{
    for (uint32_t i = 0; i < m->nmats; i++) {
        save_name_clean(names[i], MESH_NAME_MAX, m->mats[i].name);
        if (!names[i][0])
            snprintf(names[i], SAVE_NAME, "material");
    }
    uint32_t *idx = malloc(2 * (size_t)m->nmats * sizeof *idx + 1);
    if (!idx)
        return -1;
    for (uint32_t i = 0; i < m->nmats; i++)
        idx[i] = i;
    sort_by_name(idx, idx + m->nmats, m->nmats, names);
    /* a run of equal names: the first keeps it, the others get _2, _3,
     * ... (a suffix that makes it equal another name is taken too) */
    for (uint32_t a = 0; a < m->nmats;) {
        uint32_t b = a + 1;
        while (b < m->nmats && !strcmp(names[idx[a]], names[idx[b]]))
            b++;
        for (uint32_t k = a + 1; k < b; k++) {
            char base[MESH_NAME_MAX];
            snprintf(base, sizeof base, "%s", names[idx[k]]);
            for (uint32_t s = k - a + 1;; s++) {
                /* within the MESH_NAME_MAX - 1 bytes a reader keeps of a name */
                char suffix[16];
                int sl = snprintf(suffix, sizeof suffix, "_%u", s);
                snprintf(names[idx[k]], SAVE_NAME, "%.*s%s", MESH_NAME_MAX - 1 - sl, base, suffix);
                int taken = 0;
                for (uint32_t j = 0; j < m->nmats && !taken; j++)
                    taken = j != idx[k] && !strcmp(names[j], names[idx[k]]);
                if (!taken)
                    break;
            }
        }
        a = b;
    }
    free(idx);
    return 0;
}

/* ==== The OBJ ==== */

/* "KEY a b c" of floats, then end ("\n", or "" to go on). */
static void put_floats_end(SaveOut *o, const char *key, const float *x, int n, const char *end)
{
    char *p = so_room(o, 8 + (size_t)n * (SAVE_FLOAT_MAX + 1)), *q = p;
    size_t kl = strlen(key);
    memcpy(q, key, kl);
    q += kl;
    for (int i = 0; i < n; i++) {
        *q++ = ' ';
        q += save_float(q, x[i]);
    }
    if (*end)
        *q++ = *end;
    so_commit(o, (size_t)(q - p));
}

static void put_floats(SaveOut *o, const char *key, const float *x, int n)
{
    put_floats_end(o, key, x, n, "\n");
}

/* The file's v for a stored v (down the image): t with 1 - t == v in
 * float, or the nearest. */
static float v_up(float v)
{
    float t = 1.0f - v, best = t;
    for (int k = 0; k < 4; k++) {
        if (1.0f - t == v)
            return t;
        if (fabsf((1.0f - t) - v) < fabsf((1.0f - best) - v))
            best = t;
        t = nextafterf(t, 1.0f - t > v ? INFINITY : -INFINITY);
    }
    return best;
}

static void put_vertices(const Mesh *m, SaveOut *o)
{
    for (uint32_t v = 0; v < m->nverts; v++) {
        float x[6];
        memcpy(x, m->pos + 3 * (size_t)v, 3 * sizeof *x);
        if (m->rgb)
            memcpy(x + 3, m->rgb + 3 * (size_t)v, 3 * sizeof *x);
        put_floats(o, "v", x, m->rgb ? 6 : 3);
    }
    for (uint32_t t = 0; m->uv && t < m->nuv; t++) {
        float uv[2] = { m->uv[2 * (size_t)t], v_up(m->uv[2 * (size_t)t + 1]) };
        put_floats(o, "vt", uv, 2);
    }
}

/* "KEY i j k ...\n": corners [c0, c1) of idx (1-based on output), each
 * with its texture coordinate (uv: per corner; per_vertex: the vertex's
 * own; neither: none). Long statements go out in runs. */
static void put_indices(SaveOut *o, const char *key, const uint32_t *idx, uint32_t c0, uint32_t c1,
                        const uint32_t *uv, int per_vertex)
{
    so_str(o, key);
    for (uint32_t c = c0; c < c1;) {
        uint32_t run = c1 - c < 128 ? c1 - c : 128;
        char *p = so_room(o, run * 24), *q = p;
        for (uint32_t k = c; k < c + run; k++) {
            *q++ = ' ';
            q += save_u32(q, idx[k] + 1);
            uint32_t t = uv ? uv[k] : per_vertex ? idx[k] : MESH_NO_UV;
            if (t != MESH_NO_UV) {
                *q++ = '/';
                q += save_u32(q, t + 1);
            }
        }
        so_commit(o, (size_t)(q - p));
        c += run;
    }
    so_str(o, "\n");
}

static void put_object(const Mesh *m, SaveOut *o, const MeshObject *ob, int mats, int32_t *cur,
                       char (*names)[SAVE_NAME])
{
    char name[MESH_NAME_MAX], line[SAVE_NAME + 16];
    snprintf(line, sizeof line, "o %s\n", save_name_clean(name, sizeof name, ob->name));
    so_str(o, line);
    int per_vertex = m->uv && !m->corner_uv && m->nuv == m->nverts;
    for (uint32_t f = ob->face_first; f < ob->face_first + ob->face_count; f++) {
        int32_t mat = mats ? mesh_face_mat(m, f) : -1;
        if (mat != *cur) {
            if (mat >= 0 && (uint32_t)mat < m->nmats)
                snprintf(line, sizeof line, "usemtl %s\n", names[mat]);
            else
                snprintf(line, sizeof line, "usemtl\n");
            so_str(o, line);
            *cur = mat;
        }
        put_indices(o, "f", m->corner, m->face_start[f], m->face_start[f + 1], m->uv ? m->corner_uv : NULL,
                    per_vertex);
    }
    /* points: a line of up to 16 (the mesh's own array, or point i is vertex i) */
    for (uint32_t k = ob->point_first; k < ob->point_first + ob->point_count;) {
        uint32_t run = ob->point_first + ob->point_count - k < 16 ? ob->point_first + ob->point_count - k : 16;
        uint32_t ids[16];
        for (uint32_t i = 0; i < run; i++)
            ids[i] = m->point ? m->point[k + i] : k + i;
        put_indices(o, "p", ids, 0, run, NULL, 0);
        k += run;
    }
    for (uint32_t l = ob->line_first; l < ob->line_first + ob->line_count; l++)
        put_indices(o, "l", m->line_corner, m->line_start[l], m->line_start[l + 1], NULL, 0);
}

/* A cloud (every vertex a point, nothing else) is its vertices alone:
 * the OBJ reader makes such a file a cloud again. */
static int is_cloud(const Mesh *m)
{
    return !m->nfaces && !m->nlines && !m->point && m->npoints == m->nverts;
}

void save_obj(const Mesh *m, SaveOut *o, const char *mtl_name, char (*names)[SAVE_NAME], SaveReport *rep)
{
    so_str(o, "# written by zview\n");
    int mats = mtl_name && m->nmats > 0;
    if (mats) {
        char clean[4096], line[4200];
        snprintf(line, sizeof line, "mtllib %s\n", save_name_clean(clean, sizeof clean, mtl_name));
        so_str(o, line);
    }
    rep->materials_dropped = mats ? 0 : m->nmats;
    put_vertices(m, o);
    int32_t cur = -1;
    for (uint32_t i = 0; i < m->nobjs && !is_cloud(m); i++) {
        const MeshObject *ob = &m->objs[i];
        if (ob->face_count + ob->point_count + ob->line_count)
            put_object(m, o, ob, mats, &cur, names);
    }
    rep->vertices = m->nverts;
    rep->faces = m->nfaces;
}

/* ==== The MTL ==== */

/* The texture's name for an MTL beside the model: relative to the
 * model's folder when it is under it (the reader joined them). */
static const char *texture_name(const Mesh *m, const char *name)
{
    const char *slash = m->path ? strrchr(m->path, '/') : NULL;
    size_t dl = slash ? (size_t)(slash - m->path) + 1 : 0;
    if (dl && !strncmp(name, m->path, dl) && name[dl])
        return name + dl;
    return name;
}

void save_mtl(const Mesh *m, SaveOut *o, char (*names)[SAVE_NAME])
{
    so_str(o, "# written by zview\n");
    for (uint32_t i = 0; i < m->nmats; i++) {
        const Material *mt = &m->mats[i];
        char line[SAVE_NAME + 16];
        snprintf(line, sizeof line, "\nnewmtl %s\n", names[i]);
        so_str(o, line);
        put_floats(o, "Kd", mt->kd, 3);
        put_floats(o, "d", &mt->alpha, 1);
        if (mt->tex < 0 || (uint32_t)mt->tex >= m->ntex || !m->tex[mt->tex].name)
            continue;
        const MeshTexture *t = &m->tex[mt->tex];
        so_str(o, "map_Kd");
        /* the reader's v' = v s + (1 - s - o) undone: the file's o is 1 - s - off */
        float off[2] = { mt->tex_off[0], 1.0f - mt->tex_scale[1] - mt->tex_off[1] };
        if (off[0] != 0 || off[1] != 0)
            put_floats_end(o, " -o", off, 2, "");
        if (mt->tex_scale[0] != 1 || mt->tex_scale[1] != 1)
            put_floats_end(o, " -s", mt->tex_scale, 2, "");
        if (t->img.wrap_u == TEX_CLAMP)
            so_str(o, " -clamp on");
        char clean[4096];
        so_str(o, " ");
        so_str(o, save_name_clean(clean, sizeof clean, texture_name(m, t->name)));
        so_str(o, "\n");
    }
}
