/* grid.c: the gallery's arithmetic, without I/O: how many tiles fit
 * across and down, where a move of the selection lands, which row the
 * screen starts at, the orders of `s` and the filter of `/`. */

#include <stdlib.h>
#include <string.h>

#include "gallery.h"

const char *const gallery_sort_names[GSORT_COUNT] = { "name", "size", "faces", "verdict" };

void gallery_grid(GalleryGrid *g, int cols, int rows, int pic_cols, int pic_rows)
{
    /* the picture shrinks to fit one tile on a narrow or short screen */
    g->pic_cols = pic_cols < cols - GALLERY_GAP ? pic_cols : cols - GALLERY_GAP;
    g->pic_rows = pic_rows < rows - 2 ? pic_rows : rows - 2;
    if (g->pic_cols < 1)
        g->pic_cols = 1;
    if (g->pic_rows < 1)
        g->pic_rows = 1;
    g->tile_cols = g->pic_cols + GALLERY_GAP;
    g->tile_rows = g->pic_rows + 2;     /* the name's line, the verdict's */
    g->cols = cols / g->tile_cols;
    g->rows = rows / g->tile_rows;
    if (g->cols < 1)
        g->cols = 1;
    if (g->rows < 1)
        g->rows = 1;
}

int gallery_move(const GalleryGrid *g, int n, int sel, int dx, int dy)
{
    if (n <= 0)
        return 0;
    int to = sel + dx + dy * g->cols;
    if (dy && (to < 0 || to >= n)) {
        /* off the top or the bottom: the row does not change, except down
         * to the last tile when a shorter last row has none below */
        if (dy > 0 && sel / g->cols < (n - 1) / g->cols)
            return n - 1;
        return sel;
    }
    return to < 0 ? 0 : to >= n ? n - 1 : to;
}

int gallery_top_row(const GalleryGrid *g, int sel, int top_row)
{
    int row = sel / g->cols;
    if (row < top_row)
        return row;
    if (row >= top_row + g->rows)
        return row - g->rows + 1;
    return top_row < 0 ? 0 : top_row;
}

int gallery_verdict_rank(const GalleryTile *t)
{
    switch (t->state) {
    case GS_UNREADABLE:
        return 0;
    case GS_PROBLEM:
        return 1;
    case GS_SOUND:
        return 2;
    default:
        return 3;
    }
}

/* qsort has no context argument: the tiles and the key travel in the
 * array itself, each element a tile index with a pointer to the tiles. */
typedef struct {
    int                idx;
    GallerySort        by;
    const GalleryTile *t;
} SortItem;

static int cmp_u64(uint64_t a, uint64_t b)
{
    return a < b ? -1 : a > b;
}

static int item_cmp(const void *pa, const void *pb)
{
    const SortItem *a = pa, *b = pb;
    const GalleryTile *x = &a->t[a->idx], *y = &b->t[b->idx];
    int c = 0;
    switch (a->by) {
    case GSORT_SIZE:
        c = -cmp_u64(x->size, y->size);             /* the biggest first */
        break;
    case GSORT_FACES:
        c = -cmp_u64(x->faces, y->faces);
        break;
    case GSORT_VERDICT:
        c = gallery_verdict_rank(x) - gallery_verdict_rank(y);
        if (!c)
            c = -cmp_u64(x->problems, y->problems);  /* more kinds of problem first */
        break;
    default:
        break;
    }
    if (!c)
        c = strcmp(x->name, y->name);
    if (!c)
        c = strcmp(x->path, y->path);
    return c ? c : (a->idx > b->idx) - (a->idx < b->idx);
}

void gallery_sort(int *order, int n, const GalleryTile *t, GallerySort by)
{
    SortItem *it = n > 0 ? malloc((size_t)n * sizeof *it) : NULL;
    if (!it)
        return;                 /* out of memory: the order stays as it was */
    for (int i = 0; i < n; i++)
        it[i] = (SortItem){ order[i], by, t };
    qsort(it, (size_t)n, sizeof *it, item_cmp);
    for (int i = 0; i < n; i++)
        order[i] = it[i].idx;
    free(it);
}

/* Does hay contain needle, ASCII letters in either case? */
static int contains(const char *hay, const char *needle)
{
    size_t m = strlen(needle);
    for (const char *h = hay; *h; h++) {
        size_t k = 0;
        while (k < m && h[k]) {
            int a = (unsigned char)h[k], b = (unsigned char)needle[k];
            if (a >= 'A' && a <= 'Z')
                a += 32;
            if (b >= 'A' && b <= 'Z')
                b += 32;
            if (a != b)
                break;
            k++;
        }
        if (k == m)
            return 1;
    }
    return m == 0;
}

int gallery_order_due(int *seen, int now, GallerySort by)
{
    int due = now != *seen && by != GSORT_NAME;
    *seen = now;
    return due;
}

int gallery_filter(int *order, int n, const GalleryTile *t, const char *needle)
{
    int k = 0;
    for (int i = 0; i < n; i++)
        if (contains(t[order[i]].name, needle))
            order[k++] = order[i];
    return k;
}
