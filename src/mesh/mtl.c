/* mtl.c: Wavefront MTL text (obj.c reads the file). Only what zview
 * draws is kept: the name, Kd (base colour), opacity (d, or 1 - Tr) and
 * the base-colour texture map_Kd with its -o (offset), -s (scale) and
 * -clamp options. Every other statement is skipped. A bad line is not
 * fatal, since the model still shows without it: it is skipped with one
 * warning per file. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "mesh_internal.h"

static int mtl_space(char c) { return c == ' ' || c == '\t' || c == '\r'; }

static float clamp01(float v) { return v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v; }

/* Reads up to `max` numbers of the rest of a line; returns how many, or
 * -1 if one is malformed or junk follows them. */
static int mtl_numbers(const char *p, const char *e, float *out, int max)
{
    int n = 0;
    for (;;) {
        while (p < e && mtl_space(*p))
            p++;
        if (p >= e || *p == '#')
            return n;
        if (n == max || mesh_parse_float(&p, e, &out[n]) != MESH_NUM_OK)
            return -1;
        n++;
    }
}

static int word_is(const char *k, size_t n, const char *w)
{
    return strlen(w) == n && memcmp(k, w, n) == 0;
}

/* ==== map_Kd ==== */

/* The options of a texture statement and how many values each takes
 * (numbers: up to that many; 'w': one word). */
static const struct {
    const char *name;
    int         nums;
} map_opts[] = {
    { "-o", 3 }, { "-s", 3 }, { "-t", 3 }, { "-mm", 2 }, { "-bm", 1 }, { "-boost", 1 }, { "-texres", 1 },
    { "-clamp", 0 }, { "-blendu", 0 }, { "-blendv", 0 }, { "-cc", 0 }, { "-imfchan", 0 }, { "-type", 0 },
};

/* Up to max numbers at *pp (as many as parse), into out. */
static int map_numbers(const char **pp, const char *e, float *out, int max)
{
    int n = 0;
    const char *p = *pp;
    while (n < max) {
        while (p < e && mtl_space(*p))
            p++;
        const char *q = p;
        if (p >= e || mesh_parse_float(&q, e, &out[n]) != MESH_NUM_OK || (q < e && !mtl_space(*q)))
            break;
        p = q;
        n++;
    }
    *pp = p;
    return n;
}

/* map_Kd [options] file: the options read into mt, the file (the rest
 * of the line: names may hold spaces) resolved against the library's
 * folder and read. 0, 1 for a line that names no file, -1 out of
 * memory. */
static int map_kd(MeshBuild *b, const char *lib, Material *mt, const char *p, const char *e)
{
    float off[3] = { 0, 0, 0 }, scale[3] = { 1, 1, 1 }, junk[3];
    TexWrap wrap = TEX_REPEAT;
    for (;;) {
        while (p < e && mtl_space(*p))
            p++;
        if (p >= e || *p != '-')
            break;
        const char *k = p;
        while (p < e && !mtl_space(*p))
            p++;
        size_t kn = (size_t)(p - k);
        size_t i = 0, n = sizeof map_opts / sizeof map_opts[0];
        while (i < n && !word_is(k, kn, map_opts[i].name))
            i++;
        if (i == n)
            return 1;               /* an option we do not know: cannot tell its values from the name */
        if (map_opts[i].nums == 0) {
            while (p < e && mtl_space(*p))
                p++;
            const char *w = p;
            while (p < e && !mtl_space(*p))
                p++;
            if (word_is(k, kn, "-clamp"))
                wrap = word_is(w, (size_t)(p - w), "on") ? TEX_CLAMP : TEX_REPEAT;
            continue;
        }
        float *dst = word_is(k, kn, "-o") ? off : word_is(k, kn, "-s") ? scale : junk;
        int got = map_numbers(&p, e, dst, map_opts[i].nums);
        if (got == 0)
            return 1;
        if (dst == scale && got == 1)
            scale[1] = scale[0];    /* "-s 2": both ways, as exporters mean it */
    }
    while (e > p && mtl_space(e[-1]))
        e--;
    if (p >= e)
        return 1;
    /* a folder and the name, '\' as '/' (files exported on Windows) */
    const char *slash = strrchr(lib, '/');
    size_t dl = (*p != '/' && slash) ? (size_t)(slash - lib) + 1 : 0, n = (size_t)(e - p);
    char *path = malloc(dl + n + 1);
    if (!path)
        return me_oom(b->e);
    memcpy(path, lib, dl);
    for (size_t i = 0; i < n; i++)
        path[dl + i] = p[i] == '\\' ? '/' : p[i];
    path[dl + n] = '\0';
    int oom;
    mt->tex = mb_texture(b, path, path, NULL, 0, wrap, wrap, &oom);
    free(path);
    if (oom)
        return -1;
    /* MTL's v runs up and ours down: v' = v s + o in its terms is
     * v s + (1 - s - o) in ours */
    mt->tex_scale[0] = scale[0];
    mt->tex_scale[1] = scale[1];
    mt->tex_off[0] = off[0];
    mt->tex_off[1] = 1.0f - scale[1] - off[1];
    return 0;
}

/* ==== The library ==== */

int mesh_mtl_parse(MeshBuild *b, const char *name, MeshFile *file, const char *data, size_t len)
{
    MeshErr *err = b->e;
    Material **mats = &b->m->mats;
    uint32_t *nmats = &b->m->nmats, *cap = &b->mcap;
    Material *cur = NULL;
    int have_d = 0, warned = 0;
    LineReader lr;
    size_t bom = mesh_bom_len(data, len);
    lr_init(&lr, data + bom, len - bom, file);
    const char *q, *e;
    while (lr_next(&lr, &q, &e)) {
        while (q < e && mtl_space(*q))
            q++;
        if (q >= e || *q == '#')
            continue;
        const char *k = q;
        while (q < e && !mtl_space(*q))
            q++;
        size_t kn = (size_t)(q - k);
        int bad = mesh_has_binary(k, e);
        float v[3];

        if (bad) {
            /* no text goes on past binary data: the rest is not read */
            me_warn(err, name, lr.line, "binary data: the rest of the material library is not read");
            break;
        } else if (word_is(k, kn, "newmtl")) {
            if (*nmats == *cap) {
                uint32_t nc = *cap ? *cap * 2 : 8;
                Material *nm = realloc(*mats, nc * sizeof *nm);
                if (!nm)
                    return -1;
                *mats = nm;
                *cap = nc;
            }
            cur = &(*mats)[(*nmats)++];
            memset(cur, 0, sizeof *cur);
            mb_material_no_texture(cur);
            while (q < e && mtl_space(*q))
                q++;
            const char *ne = e;
            while (ne > q && mtl_space(ne[-1]))
                ne--;
            size_t n = (size_t)(ne - q);
            if (n > MESH_NAME_MAX - 1)
                n = MESH_NAME_MAX - 1;
            memcpy(cur->name, q, n);
            cur->name[n] = '\0';
            /* The common default of exporters for a material without Kd. */
            cur->kd[0] = cur->kd[1] = cur->kd[2] = 0.8f;
            cur->alpha = 1.0f;
            have_d = 0;
        } else if (!cur) {
            /* statements before the first newmtl belong to nothing */
        } else if (word_is(k, kn, "Kd")) {
            const char *r = q;
            while (r < e && mtl_space(*r))
                r++;
            /* "Kd spectral file" and "Kd xyz x y z" are not RGB; skip. */
            if (r < e && (*r == 's' || *r == 'x')) {
                /* ignored */
            } else {
                int n = mtl_numbers(q, e, v, 3);
                if (n == 1 || n == 3) {
                    for (int i = 0; i < 3; i++)
                        cur->kd[i] = clamp01(v[n == 1 ? 0 : i]);
                } else {
                    bad = 1;
                }
            }
        } else if (word_is(k, kn, "d")) {
            while (q < e && mtl_space(*q))
                q++;
            if (e - q >= 5 && memcmp(q, "-halo", 5) == 0)
                q += 5;
            if (mtl_numbers(q, e, v, 1) == 1) {
                cur->alpha = clamp01(v[0]);
                have_d = 1;
            } else {
                bad = 1;
            }
        } else if (word_is(k, kn, "map_Kd")) {
            int r = map_kd(b, name, cur, q, e);
            if (r < 0)
                return -1;
            bad = r;
        } else if (word_is(k, kn, "Tr")) {
            /* d wins when a material has both, whatever their order. */
            if (mtl_numbers(q, e, v, 1) == 1) {
                if (!have_d)
                    cur->alpha = clamp01(1.0f - v[0]);
            } else {
                bad = 1;
            }
        }
        if (bad && !warned) {
            me_warn(err, name, lr.line, "bad material statement, skipped");
            warned = 1;
        }
    }
    return 0;
}
