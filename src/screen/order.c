/* order.c: the order the screen polygons reach the hidden-surface
 * algorithm (--order), without changing a face id or the picture.
 *
 * Every algorithm decides each sample by (depth, face id), so its result
 * does not depend on the order it draws in; its speed can. The
 * hierarchical z-buffer culls a polygon only once nearer ones are in the
 * pyramid: front to back is its best case, back to front its worst, and
 * the file's own order (or a shuffle) somewhere between. Reordering the
 * front end's output makes that measurable. The polygons and their
 * corners are copied in the new order into a second set of arrays that
 * is then swapped in (no allocation once grown), and the map from scene
 * polygons follows them. */

#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "screen.h"

const char *const order_names[ORDER_COUNT] = { "file", "front-to-back", "back-to-front", "shuffle" };

int order_from_name(const char *name)
{
    for (int i = 0; i < ORDER_COUNT; i++)
        if (strcmp(name, order_names[i]) == 0)
            return i;
    return -1;
}

void reorder_free(ReorderScratch *rs)
{
    free(rs->verts);
    free(rs->polys);
    free(rs->key);
    free(rs->newpos);
    memset(rs, 0, sizeof *rs);
}

/* A sort key that orders floats as numbers (NaN last), as unsigned. */
static inline uint32_t float_key(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u & 0x80000000u ? ~u : u | 0x80000000u;
}

static int cmp_key(const void *a, const void *b)
{
    const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

int screen_reorder(ScreenPolys *sp, PolyOrder order, uint32_t seed, ReorderScratch *rs)
{
    sp->face_sorted = order == ORDER_FILE;
    uint32_t n = sp->npolys;
    if (order == ORDER_FILE || n < 2)
        return 0;
    if (grow_array((void **)&rs->key, &rs->cap_key, n, sizeof *rs->key) ||
        grow_array((void **)&rs->newpos, &rs->cap_newpos, n, sizeof *rs->newpos) ||
        grow_array((void **)&rs->verts, &rs->cap_verts, sp->cap_verts, sizeof *rs->verts) ||
        grow_array((void **)&rs->polys, &rs->cap_polys, sp->cap_polys, sizeof *rs->polys))
        return -1;
    /* key: the order in the high half, the old index in the low half */
    uint32_t r = seed * 2654435761u + 1;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t k;
        if (order == ORDER_SHUFFLE) {
            r ^= r << 13;
            r ^= r >> 17;
            r ^= r << 5;
            k = r;
        } else {
            k = float_key(sp->polys[i].zmin);
            if (order == ORDER_BACK)
                k = ~k;
        }
        rs->key[i] = (uint64_t)k << 32 | i;
    }
    qsort(rs->key, n, sizeof *rs->key, cmp_key);
    uint32_t nv = 0;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t i = (uint32_t)rs->key[k];
        ScreenPoly p = sp->polys[i];
        uint32_t c = screen_poly_nverts(sp, i);
        memcpy(&rs->verts[nv], &sp->verts[p.first], c * sizeof *rs->verts);
        p.first = nv;
        nv += c;
        rs->polys[k] = p;
        rs->newpos[i] = (int32_t)k;
    }
    rs->polys[n].first = nv;        /* the sentinel */
    /* swap the arrays in; the old ones become the scratch */
    ScreenVert *tv = sp->verts;
    ScreenPoly *tp = sp->polys;
    uint32_t cv = sp->cap_verts, cp = sp->cap_polys;
    sp->verts = rs->verts;
    sp->polys = rs->polys;
    sp->cap_verts = rs->cap_verts;
    sp->cap_polys = rs->cap_polys;
    rs->verts = tv;
    rs->polys = tp;
    rs->cap_verts = cv;
    rs->cap_polys = cp;
    for (uint32_t k = 0; k < sp->nmap; k++)
        if (sp->map[k] >= 0)
            sp->map[k] = rs->newpos[sp->map[k]];
    return 0;
}
