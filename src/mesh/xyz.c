/* xyz.c: the plain text of scanners and point-cloud tools (.xyz, .pts,
 * .xyzrgb): one point a line, its numbers separated by blanks, commas or
 * semicolons:
 *
 *   x y z                 a point
 *   x y z i               with an intensity (not used)
 *   x y z r g b           with a colour
 *   x y z i r g b         the .pts layout
 *   x y z a b c ...       other widths: x y z, the rest not used
 *
 * Lines starting with '#' or "//" are comments; a first line that is a
 * single integer (the point count of .pts) or holds no number at all (a
 * header of column names) is skipped. Three columns after x y z are a
 * colour unless one of them is negative anywhere in the file: then they
 * are normals (MeshLab writes x y z nx ny nz), and the points get no
 * colour. Colours are 0..1 floats, or 0..255 when any value exceeds 1.
 * Every vertex is a point; no per-point array is made. A line that is
 * not a point is a skipped statement (--strict refuses the file). */
#define _DEFAULT_SOURCE

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "mesh_internal.h"

#define XYZ_MAX_COLS 16     /* numbers looked at on a line; more are skipped unread */

static inline int is_sep(char c) { return mesh_is_blank(c) || c == ',' || c == ';'; }

/* The numbers of line [p, e) into v (up to XYZ_MAX_COLS; *n counts them
 * all). Returns 0, or a MESH_NUM_* code with *bad at the offending token. */
static int line_numbers(const char *p, const char *e, float *v, int *n, const char **bad)
{
    int k = 0;
    for (;;) {
        while (p < e && is_sep(*p))
            p++;
        if (p >= e)
            break;
        const char *t = p;
        while (p < e && !is_sep(*p))
            p++;
        if (k < XYZ_MAX_COLS) {
            const char *q = t;
            int r = mesh_parse_float(&q, p, &v[k]);
            if (r) {
                *bad = t;
                *n = k;
                return r;
            }
        }
        k++;
    }
    *n = k;
    return MESH_NUM_OK;
}

/* Does [p, e) hold no token that starts like a number? (a header line) */
static int no_numbers(const char *p, const char *e)
{
    for (; p < e; p++)
        if (mesh_is_digit(*p) || ((*p == '-' || *p == '+' || *p == '.') && p + 1 < e && mesh_is_digit(p[1])))
            return 0;
    return 1;
}

static int is_comment(const char *p, const char *e)
{
    while (p < e && mesh_is_blank(*p))
        p++;
    return p >= e || *p == '#' || (e - p >= 2 && p[0] == '/' && p[1] == '/');
}

static int xyz_parse(MeshCtx *c, const char *data, size_t len)
{
    MeshBuild b;
    MeshErr *e = &c->err;
    if (mb_start(&b, c->m, e, e->name))
        return -1;
    Mesh *m = c->m;
    m->info.bytes = len;
    snprintf(m->info.format, sizeof m->info.format, "xyz");
    /* the densest plausible file: "0 0 0\n", a point per 6 bytes; a
     * guess, so its pages are not faulted in ahead (past 256 MB the
     * arrays grow instead) */
    if (len >= ((size_t)1 << 20)) {
        size_t guess = (len < ((size_t)256 << 20) ? len : ((size_t)256 << 20)) / 16;
        if (mb_reserve_ex(&b, guess, 0, 0, 0))
            goto fail;
    }
    const char *p = data, *end = data + len;
    if (len >= 3 && memcmp(p, "\xEF\xBB\xBF", 3) == 0)
        p += 3;
    LineReader lr;
    lr_init(&lr, p, (size_t)(end - p), c->file);
    const char *ls, *le;
    int first = 1, colours = 0;
    float cmin = INFINITY, cmax = -INFINITY;
    while (lr_next(&lr, &ls, &le)) {
        if (is_comment(ls, le))
            continue;
        float v[XYZ_MAX_COLS];
        int n;
        const char *bad = NULL;
        int r = line_numbers(ls, le, v, &n, &bad);
        int head = first;
        first = 0;
        if (head && ((r == MESH_NUM_OK && n == 1 && v[0] == floorf(v[0]) && v[0] >= 0) ||
                     (r != MESH_NUM_OK && !mesh_has_binary(ls, le) && no_numbers(ls, le))))
            continue;   /* a point count, or column names */
        if (r != MESH_NUM_OK || n < 3) {
            if (mesh_has_binary(ls, le))
                me_fail_line(e, lr.line, "binary or unreadable data");
            else if (r == MESH_NUM_NONFINITE)
                me_fail_line(e, lr.line, "NaN or infinite number '%.*s'", mesh_tok_len(bad, le), bad);
            else if (r == MESH_NUM_RANGE)
                me_fail_line(e, lr.line, "number out of range '%.*s'", mesh_tok_len(bad, le), bad);
            else if (r != MESH_NUM_OK)
                me_fail_line(e, lr.line, "malformed number '%.*s'", mesh_tok_len(bad, le), bad);
            else
                me_fail_line(e, lr.line, "a point needs x y z, got %d number%s", n, n == 1 ? "" : "s");
            if (me_skip(e, lr.line))
                goto fail;
            if (le > ls && le[-1] == '\0') {
                /* no text goes on past a NUL: the rest is not read */
                me_warn(e, NULL, lr.line, "binary data: the rest of the file (%llu bytes) is not read",
                        (unsigned long long)(end - le));
                break;
            }
            continue;
        }
        if (mb_vertex(&b, v[0], v[1], v[2]))
            goto fail;
        int at = n == 6 ? 3 : n == 7 ? 4 : -1;
        if (at < 0) {
            if (m->rgb) {   /* no colour here: NaN marks it until the end */
                float *d = m->rgb + 3 * (size_t)(m->nverts - 1);
                d[0] = d[1] = d[2] = NAN;
            }
            continue;
        }
        if (!m->rgb) {
            if (mb_want_rgb(&b))
                goto fail;
            for (size_t i = 0; i + 1 < m->nverts; i++)
                m->rgb[3 * i] = m->rgb[3 * i + 1] = m->rgb[3 * i + 2] = NAN;
        }
        float *d = m->rgb + 3 * (size_t)(m->nverts - 1);
        for (int k = 0; k < 3; k++) {
            d[k] = v[at + k];
            cmin = d[k] < cmin ? d[k] : cmin;
            cmax = d[k] > cmax ? d[k] : cmax;
        }
        colours = 1;
    }
    if (colours && cmin < 0) {
        /* normals, not colours */
        free(m->rgb);
        m->rgb = NULL;
    } else if (colours) {
        float k = cmax > 1 ? 1.0f / 255.0f : 1.0f;
        for (size_t i = 0; i < 3 * (size_t)m->nverts; i++) {
            float x = m->rgb[i];
            m->rgb[i] = x != x ? 1.0f : x * k > 1 ? 1.0f : x * k;
        }
    }
    if (mb_finish(&b, 1))
        goto fail;
    return 0;
fail:
    mb_abort(&b);
    return -1;
}

/* Plausible when every whole line of the head that is not a comment
 * holds the same number (three or more) of numbers, after a lone count
 * or a line of column names:
 * a scanner writes one layout a line. (An OFF file without its keyword
 * starts with three counts too, but its face lines differ from its
 * vertex lines.) Never sure: plain numbers prove nothing, so the
 * extension or --format decides first. */
static int xyz_probe(const char *head, size_t n, uint64_t size)
{
    if (!n || mesh_has_binary(head, head + n))
        return PROBE_NO;
    LineReader lr;
    lr_init(&lr, head, n, NULL);
    const char *ls, *le;
    int seen = 0, cols = 0;
    while (lr_next(&lr, &ls, &le)) {
        if (le == head + n && size > n)
            break;          /* a line cut by the head's end proves nothing */
        if (is_comment(ls, le))
            continue;
        float v[XYZ_MAX_COLS];
        int k;
        const char *bad;
        int first = seen == 0 && cols == 0;
        if (line_numbers(ls, le, v, &k, &bad) != MESH_NUM_OK) {
            if (first && no_numbers(ls, le)) {
                cols = -1;  /* column names, once */
                continue;
            }
            return PROBE_NO;
        }
        if (first && k == 1) {
            cols = -1;      /* the point count of .pts, once */
            continue;
        }
        if (k < 3 || (seen && k != cols))
            return PROBE_NO;
        cols = k;
        seen++;
    }
    return seen ? PROBE_MAYBE : PROBE_NO;
}

const MeshLoader mesh_loader_xyz = {
    .name = "xyz",
    .exts = "xyz pts xyzrgb",
    .what = "XYZ point clouds: x y z [r g b] a line (.xyz, .pts, .xyzrgb)",
    .probe = xyz_probe,
    .parse = xyz_parse,
    .text = 1,
};
