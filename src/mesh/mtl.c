/* mtl.c: Wavefront MTL text (obj.c reads the file). Only what a
 * flat-shaded viewer uses is kept: the name, Kd (base colour) and
 * opacity (d, or 1 - Tr). Every other statement is skipped. A bad line
 * is not fatal, since the model still shows without it: it is skipped
 * with one warning per file. */
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

int mesh_mtl_parse(MeshErr *err, const char *name, MeshFile *file, const char *data, size_t len,
                   Material **mats, uint32_t *nmats, uint32_t *cap)
{
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
