/* test_gallery.c: the gallery's grid (layout, moves, scrolling), its
 * orders and filter against brute force, the listing of a folder (links
 * that loop, links to folders, files not models, the cap), one tile
 * made from a file (verdict and picture), and the font. */

#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gallery.h"

/* ==== Layout ==== */

Test(gallery, the_grid_fits_as_many_whole_tiles_as_the_screen_holds)
{
    for (int cols = 1; cols <= 200; cols += 7)
        for (int rows = 1; rows <= 60; rows += 3) {
            GalleryGrid g;
            gallery_grid(&g, cols, rows, 20, 9);
            cr_assert(g.pic_cols >= 1 && g.pic_rows >= 1);
            cr_assert_eq(g.tile_cols, g.pic_cols + GALLERY_GAP);
            cr_assert_eq(g.tile_rows, g.pic_rows + 2, "a name's line and a verdict's under the picture");
            cr_assert(g.cols >= 1 && g.rows >= 1);
            /* as many as fit, no more (at least one however small) */
            if (g.cols > 1 || cols >= g.tile_cols)
                cr_assert(g.cols * g.tile_cols <= cols && (g.cols + 1) * g.tile_cols > cols, "%d cols: %d across",
                          cols, g.cols);
            if (g.rows > 1 || rows >= g.tile_rows)
                cr_assert(g.rows * g.tile_rows <= rows && (g.rows + 1) * g.tile_rows > rows, "%d rows: %d down",
                          rows, g.rows);
        }
    GalleryGrid g;
    gallery_grid(&g, 100, 29, 20, 9);
    cr_assert(g.cols == 4 && g.rows == 2 && g.pic_cols == 20 && g.pic_rows == 9, "100x29: %dx%d", g.cols, g.rows);
    gallery_grid(&g, 12, 6, 20, 9);
    cr_assert(g.pic_cols == 10 && g.pic_rows == 4 && g.cols == 1 && g.rows == 1, "a small screen shrinks the picture");
}

/* The move by rows and columns, worked out independently: the cell of
 * the selection, moved, and kept when it leaves the tiles. */
static int move_ref(int cols, int n, int sel, int dx, int dy)
{
    if (dx) {
        int to = sel + dx;
        return to < 0 ? 0 : to >= n ? n - 1 : to;
    }
    int r = sel / cols, c = sel % cols, last_row = (n - 1) / cols;
    int nr = r + dy;
    if (nr < 0)
        return sel;
    if (nr > last_row)
        return sel;
    int to = nr * cols + c;
    return to < n ? to : n - 1;     /* below, on a shorter last row: its last tile */
}

Test(gallery, the_arrows_move_as_the_rows_and_columns_say)
{
    for (int cols = 1; cols <= 5; cols++)
        for (int n = 1; n <= 13; n++)
            for (int sel = 0; sel < n; sel++) {
                GalleryGrid g = { .cols = cols, .rows = 2 };
                static const int d[4][2] = { { -1, 0 }, { 1, 0 }, { 0, -1 }, { 0, 1 } };
                for (int k = 0; k < 4; k++) {
                    int got = gallery_move(&g, n, sel, d[k][0], d[k][1]);
                    int want = move_ref(cols, n, sel, d[k][0], d[k][1]);
                    cr_assert_eq(got, want, "%d across, %d tiles, from %d by %d,%d: %d, not %d", cols, n, sel,
                                 d[k][0], d[k][1], got, want);
                }
            }
}

Test(gallery, the_screen_scrolls_as_little_as_keeps_the_selection_on_it)
{
    GalleryGrid g = { .cols = 4, .rows = 3 };
    for (int top = 0; top < 10; top++)
        for (int sel = 0; sel < 60; sel++) {
            int t = gallery_top_row(&g, sel, top);
            int row = sel / 4;
            cr_assert(row >= t && row < t + g.rows, "selection %d off the screen from row %d", sel, t);
            if (row >= top && row < top + g.rows)
                cr_assert_eq(t, top, "scrolled though the selection showed");
            else
                cr_assert(t == row || t == row - g.rows + 1, "scrolled further than needed");
        }
}

/* ==== Orders and the filter ==== */

static GalleryTile tiles[8];

static void make_tiles(void)
{
    static char paths[8][32];
    static const char *names[8] = { "Bunny.obj", "apple.stl", "cube.obj", "zeta.ply", "bunny.obj", "d.off", "e.obj",
                                     "f.obj" };
    static const uint64_t sizes[8] = { 500, 20, 20, 7000, 500, 1, 300, 0 };
    static const uint32_t faces[8] = { 10, 40, 12, 3, 10, 0, 7, 99 };
    static const int states[8] = { GS_SOUND, GS_PROBLEM, GS_SOUND, GS_UNREADABLE, GS_PROBLEM, GS_PENDING,
                                   GS_PROBLEM, GS_PICTURED };
    static const uint32_t problems[8] = { 0, 1, 0, 0, 3, 0, 2, 0 };
    memset(tiles, 0, sizeof tiles);
    for (int i = 0; i < 8; i++) {
        snprintf(paths[i], sizeof paths[i], "dir%d/%s", i % 2, names[i]);
        tiles[i] = (GalleryTile){ .path = paths[i], .name = names[i], .size = sizes[i], .faces = faces[i],
                                  .state = states[i], .problems = problems[i] };
    }
}

/* a comes before b in order `by`, or ties (brute force of the rule) */
static int before_or_tie(const GalleryTile *a, const GalleryTile *b, GallerySort by)
{
    switch (by) {
    case GSORT_SIZE:
        if (a->size != b->size)
            return a->size > b->size;
        break;
    case GSORT_FACES:
        if (a->faces != b->faces)
            return a->faces > b->faces;
        break;
    case GSORT_VERDICT:
        if (gallery_verdict_rank(a) != gallery_verdict_rank(b))
            return gallery_verdict_rank(a) < gallery_verdict_rank(b);
        if (a->problems != b->problems)
            return a->problems > b->problems;
        break;
    default:
        break;
    }
    int c = strcmp(a->name, b->name);
    return c ? c < 0 : strcmp(a->path, b->path) <= 0;
}

Test(gallery, each_sort_orders_every_pair_and_is_the_same_from_any_start)
{
    make_tiles();
    for (int by = 0; by < GSORT_COUNT; by++) {
        int first[8];
        for (int start = 0; start < 8; start++) {
            int order[8];
            for (int i = 0; i < 8; i++)
                order[i] = (i * 3 + start) % 8;     /* another permutation each time */
            gallery_sort(order, 8, tiles, (GallerySort)by);
            int seen[8] = { 0 };
            for (int i = 0; i < 8; i++)
                seen[order[i]]++;
            for (int i = 0; i < 8; i++)
                cr_assert_eq(seen[i], 1, "the sort lost or doubled tile %d", i);
            for (int i = 0; i + 1 < 8; i++)
                for (int k = i + 1; k < 8; k++)
                    cr_assert(before_or_tie(&tiles[order[i]], &tiles[order[k]], (GallerySort)by),
                              "sort %s: %s before %s", gallery_sort_names[by], tiles[order[i]].name,
                              tiles[order[k]].name);
            if (start == 0)
                memcpy(first, order, sizeof first);
            else
                cr_assert(!memcmp(first, order, sizeof first), "sort %s depends on the start", gallery_sort_names[by]);
        }
    }
    /* known values: the verdict order puts the unreadable file first, then
     * the problems by how many kinds, the sound ones, the ones not done */
    int order[8] = { 0, 1, 2, 3, 4, 5, 6, 7 };
    gallery_sort(order, 8, tiles, GSORT_VERDICT);
    cr_assert_str_eq(tiles[order[0]].name, "zeta.ply");
    cr_assert_str_eq(tiles[order[1]].name, "bunny.obj");
    cr_assert_str_eq(tiles[order[2]].name, "e.obj");
    cr_assert_str_eq(tiles[order[3]].name, "apple.stl");
    cr_assert_str_eq(tiles[order[4]].name, "Bunny.obj");
}

/* The grid's order as galleryui.c's loop keeps it: sorted once at the
 * start, then again after a tick of the workers when gallery_order_due
 * says. Six tiles are pictured (their faces known) and later checked
 * (their verdict known), some ticks storing none, one or two. After
 * every tick, in every sort, each pair of tiles shown is in the order
 * the rule says (before_or_tie, the brute force), and a tick that stored
 * nothing sorts nothing. */
Test(gallery, the_order_follows_each_tile_pictured_or_checked_and_idle_ticks_sort_nothing)
{
    static const char *names[6] = { "a.obj", "b.obj", "c.obj", "d.obj", "e.obj", "f.obj" };
    static char paths[6][16];
    for (int i = 0; i < 6; i++)
        snprintf(paths[i], sizeof paths[i], "dir/%s", names[i]);
    static const uint64_t sizes[6] = { 30, 10, 60, 20, 50, 40 };
    static const uint32_t faces[6] = { 5, 900, 12, 40, 3, 77 };
    static const uint32_t problems[6] = { 0, 2, 0, 1, 0, 3 };
    /* the tiles stored at each tick, -1 ends: a tile's first time its
     * picture, its second its check */
    static const int ticks[][3] = { { -1 }, { 1, -1 }, { -1 },    { 4, 2, -1 }, { 1, -1 }, { -1 }, { 5, -1 },
                                    { 0, 3, -1 }, { 4, -1 }, { 2, 5, -1 }, { 0, -1 }, { 3, -1 }, { -1 } };
    int nticks = (int)(sizeof ticks / sizeof ticks[0]);
    for (int by = 0; by < GSORT_COUNT; by++) {
        GalleryTile t[6];
        int order[6], times[6] = { 0 };
        for (int i = 0; i < 6; i++) {
            t[i] = (GalleryTile){ .path = paths[i], .name = names[i], .size = sizes[i], .state = GS_PENDING };
            order[i] = 5 - i;
        }
        gallery_sort(order, 6, t, (GallerySort)by);
        int stored = 0, seen = -1, last = -1, sorts = 0, news = 0;
        for (int k = 0; k < nticks; k++) {
            for (int j = 0; ticks[k][j] >= 0; j++) {
                int i = ticks[k][j];
                if (times[i]++ == 0) {
                    t[i].state = GS_PICTURED;
                    t[i].faces = faces[i];
                } else {
                    t[i].state = problems[i] ? GS_PROBLEM : GS_SOUND;
                    t[i].problems = problems[i];
                }
                stored++;
            }
            int fresh = stored != last;     /* the first tick too: the loop's first look */
            news += fresh;
            last = stored;
            if (gallery_order_due(&seen, stored, (GallerySort)by)) {
                cr_assert(fresh, "sort %s, tick %d: nothing stored, sorted again", gallery_sort_names[by], k);
                gallery_sort(order, 6, t, (GallerySort)by);
                sorts++;
            }
            for (int i = 0; i + 1 < 6; i++)
                for (int m = i + 1; m < 6; m++)
                    cr_assert(before_or_tie(&t[order[i]], &t[order[m]], (GallerySort)by),
                              "sort %s, tick %d: %s shown before %s", gallery_sort_names[by], k, t[order[i]].name,
                              t[order[m]].name);
        }
        cr_assert_eq(stored, 12, "each tile pictured and checked");
        /* by name nothing a tile's making knows moves it */
        cr_assert_eq(sorts, by == GSORT_NAME ? 0 : news, "sort %s: %d sorts, %d ticks with news", gallery_sort_names[by],
                     sorts, news);
    }
}

Test(gallery, the_filter_keeps_the_names_containing_it_in_their_order)
{
    make_tiles();
    static const char *needles[] = { "", "bunny", "BUN", "obj", ".o", "q", "unny.o" };
    for (size_t k = 0; k < sizeof needles / sizeof needles[0]; k++) {
        int order[8] = { 7, 6, 5, 4, 3, 2, 1, 0 };
        int n = gallery_filter(order, 8, tiles, needles[k]);
        int want[8], nw = 0;
        for (int i = 7; i >= 0; i--) {
            /* brute force: lower both, then strstr */
            char hay[32], nd[32];
            size_t j;
            for (j = 0; tiles[i].name[j]; j++)
                hay[j] = (char)(tiles[i].name[j] >= 'A' && tiles[i].name[j] <= 'Z' ? tiles[i].name[j] + 32
                                                                                    : tiles[i].name[j]);
            hay[j] = 0;
            for (j = 0; needles[k][j]; j++)
                nd[j] = (char)(needles[k][j] >= 'A' && needles[k][j] <= 'Z' ? needles[k][j] + 32 : needles[k][j]);
            nd[j] = 0;
            if (strstr(hay, nd))
                want[nw++] = i;
        }
        cr_assert_eq(n, nw, "'%s': %d kept, not %d", needles[k], n, nw);
        for (int i = 0; i < n; i++)
            cr_assert_eq(order[i], want[i], "'%s': the order changed", needles[k]);
    }
}

/* ==== Listing ==== */

static void touch(const char *dir, const char *name, const char *text)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    cr_assert(f);
    fputs(text, f);
    fclose(f);
}

static const GalleryTile *named(const GalleryList *l, const char *name)
{
    for (int i = 0; i < l->n; i++)
        if (!strcmp(l->tile[i].name, name))
            return &l->tile[i];
    return NULL;
}

Test(gallery, a_folder_lists_its_models_and_the_links_that_loop_never_a_subfolder)
{
    char dir[] = "/tmp/zv-gallery-XXXXXX", p[600], q[600];
    cr_assert(mkdtemp(dir));
    touch(dir, "b.obj", "v 0 0 0\n");
    touch(dir, "a.STL", "solid x\nendsolid x\n");
    touch(dir, "notes.txt", "hello\n");
    snprintf(p, sizeof p, "%s/sub.obj", dir);
    cr_assert_eq(mkdir(p, 0700), 0);
    touch(p, "inside.obj", "v 0 0 0\n");
    snprintf(p, sizeof p, "%s/loop.obj", dir);
    cr_assert_eq(symlink("loop.obj", p), 0);
    snprintf(p, sizeof p, "%s/up.obj", dir);
    cr_assert_eq(symlink(".", p), 0);           /* a link to a folder, named like a model */
    snprintf(p, sizeof p, "%s/gone.ply", dir);
    cr_assert_eq(symlink("nothing-here.ply", p), 0);
    GalleryList l;
    char err[256];
    const char *args[1] = { dir };
    cr_assert_eq(gallery_scan(&l, args, 1, 0, err, sizeof err), 0, "%s", err);
    cr_assert_eq(l.n, 4, "b.obj, a.STL, loop.obj, gone.ply: %d", l.n);
    cr_assert_eq(l.skipped, 1, "notes.txt skipped");
    cr_assert_str_eq(l.tile[0].name, "a.STL", "sorted by name");
    cr_assert(named(&l, "b.obj") && named(&l, "b.obj")->state == GS_PENDING && named(&l, "b.obj")->size == 8);
    const GalleryTile *t = named(&l, "loop.obj");
    cr_assert(t && t->state == GS_UNREADABLE && strstr(t->verdict, "unreadable: a link that loops"), "%s",
              t ? t->verdict : "missing");
    t = named(&l, "gone.ply");
    cr_assert(t && t->state == GS_UNREADABLE && strstr(t->verdict, "a link to nothing"));
    cr_assert(!named(&l, "up.obj") && !named(&l, "sub.obj") && !named(&l, "inside.obj"), "a folder was entered");
    gallery_list_free(&l);
    cr_assert_eq(gallery_scan(&l, args, 1, 1, err, sizeof err), 0);
    cr_assert(l.n == 5 && named(&l, "notes.txt") && l.skipped == 0, "--all lists notes.txt too");
    gallery_list_free(&l);
    const char *none[1] = { "/nonexistent-zv-dir/x.obj" };
    cr_assert_eq(gallery_scan(&l, none, 1, 0, err, sizeof err), 0, "a file named is a tile, read or not");
    cr_assert(l.n == 1 && l.tile[0].state == GS_UNREADABLE);
    gallery_list_free(&l);
    snprintf(q, sizeof q, "rm -rf '%s'", dir);
    cr_assert_eq(system(q), 0);
}

/* A folder named with slashes at its end ("dir/", as a shell completes
 * it): its files' paths, which the viewer opened from the gallery shows
 * and an unreadable tile's verdict names, join it with one slash. */
Test(gallery, a_folder_named_with_trailing_slashes_joins_its_files_with_one)
{
    char dir[] = "/tmp/zv-gallery-XXXXXX", p[600], q[600];
    cr_assert(mkdtemp(dir));
    touch(dir, "b.obj", "v 0 0 0\n");
    snprintf(q, sizeof q, "%s/b.obj", dir);
    for (int slashes = 0; slashes <= 3; slashes++) {
        snprintf(p, sizeof p, "%s%.*s", dir, slashes, "///");
        GalleryList l;
        char err[256];
        const char *args[1] = { p };
        cr_assert_eq(gallery_scan(&l, args, 1, 0, err, sizeof err), 0, "%s", err);
        cr_assert_eq(l.n, 1);
        cr_assert_str_eq(l.tile[0].path, q, "%s: %s", p, l.tile[0].path);
        gallery_list_free(&l);
    }
    snprintf(q, sizeof q, "rm -rf '%s'", dir);
    cr_assert_eq(system(q), 0);
}

Test(gallery, a_folder_of_more_than_the_cap_lists_the_cap_and_counts_the_rest, .timeout = 60)
{
    char dir[] = "/tmp/zv-gallery-XXXXXX", p[600];
    cr_assert(mkdtemp(dir));
    int total = GALLERY_MAX_FILES + 25;
    for (int i = 0; i < total; i++) {
        snprintf(p, sizeof p, "%s/m%05d.stl", dir, i);
        FILE *f = fopen(p, "w");
        cr_assert(f);
        fclose(f);
    }
    GalleryList l;
    char err[256];
    const char *args[1] = { dir };
    cr_assert_eq(gallery_scan(&l, args, 1, 0, err, sizeof err), 0, "%s", err);
    cr_assert_eq(l.n, GALLERY_MAX_FILES);
    cr_assert_eq(l.over, 25);
    gallery_list_free(&l);
    snprintf(p, sizeof p, "rm -rf '%s'", dir);
    cr_assert_eq(system(p), 0);
}

/* ==== One tile ==== */

static const char cube_obj[] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                               "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n";

static void tile_of(const char *dir, const char *name, const char *text, int what, GalleryTile *t)
{
    static char path[600];
    touch(dir, name, text);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    static Options o;
    cli_defaults(&o);
    o.no_sandbox = 1;           /* in this process: the unit tests start no fork server */
    GalleryLook look = { .o = &o, .w = 40, .h = 30, .aspect = 1.0f, .samples = 1 };
    look.bd = (Backdrop){ { 0, 0, 0 }, 1, BD_GIVEN };
    memset(t, 0, sizeof *t);
    t->path = path;
    t->name = name;
    cr_assert_eq(gallery_tile_make(t, &look, what), 0);
}

Test(gallery, a_tile_says_the_checks_verdict_and_has_a_picture)
{
    char dir[] = "/tmp/zv-gallery-XXXXXX", q[600];
    cr_assert(mkdtemp(dir));
    GalleryTile t;
    /* an open box: one hole, whatever else the check says */
    tile_of(dir, "open.obj", cube_obj, TILE_BOTH, &t);
    cr_assert_eq(t.state, GS_PROBLEM, "%s", t.verdict);
    cr_assert_str_eq(t.verdict, "1 hole");
    cr_assert_eq(t.faces, 5);
    cr_assert(t.pic.w == 40 && t.pic.h == 30);
    int lit = 0;
    for (int i = 0; i < 40 * 30; i++)
        lit += t.pic.lit[i];
    cr_assert(lit > 40 && lit < 40 * 30, "the picture shows the model (%d pixels)", lit);
    image_free(&t.pic);
    /* closed: sound */
    char closed[sizeof cube_obj + 32];
    snprintf(closed, sizeof closed, "%sf 1 5 8 4\n", cube_obj);
    tile_of(dir, "closed.obj", closed, TILE_BOTH, &t);
    cr_assert_eq(t.state, GS_SOUND);
    cr_assert_str_eq(t.verdict, "sound");
    image_free(&t.pic);
    /* the picture alone: the check to come, said so */
    tile_of(dir, "first.obj", closed, TILE_PICTURE, &t);
    cr_assert(t.state == GS_PICTURED && t.pic.w == 40 && !strcmp(t.verdict, "checking"));
    image_free(&t.pic);
    /* the check alone: no picture */
    tile_of(dir, "second.obj", cube_obj, TILE_CHECK, &t);
    cr_assert(t.state == GS_PROBLEM && t.pic.w == 0);
    /* not a model: unreadable, with the loader's reason without the path */
    tile_of(dir, "bad.obj", "garbage here\n", TILE_BOTH, &t);
    cr_assert_eq(t.state, GS_UNREADABLE);
    cr_assert(!strncmp(t.verdict, "unreadable: ", 12) && !strstr(t.verdict, dir), "%s", t.verdict);
    cr_assert_eq(t.pic.w, 0);
    snprintf(q, sizeof q, "rm -rf '%s'", dir);
    cr_assert_eq(system(q), 0);
}

/* The workers' choice replayed step by step: six tiles, the last two
 * asked for (the screen's, in its order). One worker finishing each
 * tile before it picks again: both asked for are pictured, then both
 * checked, and only then the rest, in list order, each in one go. */
Test(gallery, the_tiles_asked_for_are_pictured_then_checked_before_the_rest)
{
    GalleryTile tiles[6] = { 0 };
    GalleryList l = { .tile = tiles, .n = 6, .cap = 6 };
    int want[2] = { 5, 4 }, next = 0, what;
    const int order[][2] = { { 5, TILE_PICTURE }, { 4, TILE_PICTURE }, { 5, TILE_CHECK }, { 4, TILE_CHECK },
                             { 0, TILE_BOTH },    { 1, TILE_BOTH },    { 2, TILE_BOTH },  { 3, TILE_BOTH } };
    for (size_t k = 0; k < sizeof order / sizeof order[0]; k++) {
        int i = gallery_pick(&l, want, 2, &next, &what);
        cr_assert(i == order[k][0] && what == order[k][1], "step %zu: tile %d, what %d", k, i, what);
        cr_assert_eq(tiles[i].state, what == TILE_CHECK ? GS_CHECKING : GS_WORKING);
        tiles[i].state = what == TILE_PICTURE ? GS_PICTURED : GS_SOUND;     /* made */
    }
    cr_assert_eq(gallery_pick(&l, want, 2, &next, &what), -1, "nothing left");
}

/* A tile's name in UTF-8 is one cell a character, each cell the code
 * point (the Unicode charts' numbers): two, three and four bytes. */
Test(gallery, a_name_in_utf8_is_its_code_points_a_cell_each)
{
    GalleryGrid grid;
    gallery_grid(&grid, 40, 12, 20, 9);
    GalleryTile tile = { .name = "\xc3\xa9\xe2\x82\xac\xf0\x9d\x84\x9ez.obj", .state = GS_UNREADABLE,
                         .verdict = "x" };
    const uint32_t want[] = { 0xe9, 0x20ac, 0x1d11e, 'z', '.', 'o', 'b', 'j' };
    Cell cells[40 * 12];
    CellGrid g = { .cols = 40, .rows = 12, .cells = cells, .cap = 40 * 12 };
    int order[1] = { 0 };
    Backdrop bd = { 0 };
    cr_assert_eq(gallery_compose(&g, &grid, &tile, order, 1, 0, -1, MODE_ASCII, COLOUR_NONE, &bd), 0);
    const Cell *row = &cells[(size_t)grid.pic_rows * g.cols + GALLERY_GAP / 2];
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++)
        cr_assert_eq(row[k].ch, want[k], "cell %zu: U+%04X, not U+%04X", k, (unsigned)row[k].ch, (unsigned)want[k]);
    cr_assert_eq(row[sizeof want / sizeof want[0]].ch, ' ');
}

/* The same with the list's first tiles on the screen (the gallery as it
 * opens): tile 0 asked for is a tile like any other, pictured with the
 * screen's before any is checked. */
Test(gallery, the_first_tile_asked_for_is_pictured_with_the_screens)
{
    GalleryTile tiles[4] = { 0 };
    GalleryList l = { .tile = tiles, .n = 4, .cap = 4 };
    int want[2] = { 1, 0 }, next = 0, what;
    const int order[][2] = { { 1, TILE_PICTURE }, { 0, TILE_PICTURE }, { 1, TILE_CHECK },
                             { 0, TILE_CHECK },   { 2, TILE_BOTH },    { 3, TILE_BOTH } };
    for (size_t k = 0; k < sizeof order / sizeof order[0]; k++) {
        int i = gallery_pick(&l, want, 2, &next, &what);
        cr_assert(i == order[k][0] && what == order[k][1], "step %zu: tile %d, what %d", k, i, what);
        tiles[i].state = what == TILE_PICTURE ? GS_PICTURED : GS_SOUND;
    }
    cr_assert_eq(gallery_pick(&l, want, 2, &next, &what), -1, "nothing left");
}

/* Two workers: while the tiles asked for are being made, the second
 * takes the rest rather than wait; a tile of the rest pictured before
 * (it was on the screen once) is only checked; a tile no longer asked
 * for is not taken twice. */
Test(gallery, a_second_worker_takes_the_rest_while_the_screens_tiles_are_made)
{
    GalleryTile tiles[4] = { 0 };
    GalleryList l = { .tile = tiles, .n = 4, .cap = 4 };
    tiles[1].state = GS_PICTURED;
    int want[3] = { 3, 9, -1 }, next = 0, what;   /* out of the list and taken: skipped */
    cr_assert_eq(gallery_pick(&l, want, 3, &next, &what), 3);
    cr_assert_eq(what, TILE_PICTURE);
    cr_assert_eq(gallery_pick(&l, want, 3, &next, &what), 0, "the second worker: the rest's first");
    cr_assert_eq(what, TILE_BOTH);
    cr_assert_eq(gallery_pick(&l, want, 3, &next, &what), 1);
    cr_assert_eq(what, TILE_CHECK, "pictured before: the check only");
    cr_assert_eq(gallery_pick(&l, want, 3, &next, &what), 2);
    cr_assert_eq(gallery_pick(&l, want, 3, &next, &what), -1, "tile 3 is being made: not twice");
    tiles[3].state = GS_PICTURED;
    cr_assert_eq(gallery_pick(&l, want, 3, &next, &what), 3);
    cr_assert_eq(what, TILE_CHECK);
}

/* The same on a real worker: one thread, six tiles of one file, the
 * last two asked for. Whenever a tile of the rest has been taken, the
 * two asked for are checked already; in the end every tile is made. */
Test(gallery, one_worker_makes_every_tile_the_screens_first, .timeout = 60)
{
    char dir[] = "/tmp/zv-gallery-XXXXXX", q[600];
    cr_assert(mkdtemp(dir));
    GalleryList l = { 0 };
    l.tile = calloc(6, sizeof *l.tile);
    cr_assert(l.tile);
    static char paths[6][640];
    for (int i = 0; i < 6; i++) {
        char name[16];
        snprintf(name, sizeof name, "m%d.obj", i);
        touch(dir, name, cube_obj);
        snprintf(paths[i], sizeof paths[i], "%s/%s", dir, name);
        l.tile[i].path = strdup(paths[i]);
        l.tile[i].name = strrchr(l.tile[i].path, '/') + 1;
    }
    l.n = l.cap = 6;
    Options o;
    cli_defaults(&o);
    o.no_sandbox = 1;
    GalleryLook look = { .o = &o, .w = 16, .h = 12, .aspect = 1.0f, .samples = 1 };
    int want[2] = { 5, 4 };
    GalleryJobs *j = gallery_jobs_start(&l, &look, 1, want, 2);
    cr_assert(j);
    int saw_rest = 0;
    while (!saw_rest) {
        gallery_jobs_lock(j);
        int rest = 0, checked = 0;
        for (int i = 0; i < 4; i++)
            rest += l.tile[i].state != GS_PENDING;
        for (int i = 4; i < 6; i++)
            checked += l.tile[i].state >= GS_SOUND;
        if (rest) {
            saw_rest = 1;
            cr_assert_eq(checked, 2, "a tile not asked for was taken before those asked for were checked");
        }
        gallery_jobs_unlock(j);
        usleep(200);
    }
    gallery_jobs_wait(j);
    /* each time a tile is written back the grid's order may change */
    cr_assert_eq(gallery_jobs_stored(j), 8, "the two asked for stored twice (pictured, then checked), the other "
                                            "four once (made whole): %d", gallery_jobs_stored(j));
    gallery_jobs_stop(j);
    for (int i = 0; i < 6; i++)
        cr_assert(l.tile[i].state == GS_PROBLEM && !strcmp(l.tile[i].verdict, "1 hole") && l.tile[i].pic.w == 16,
                  "tile %d: %s", i, l.tile[i].verdict);
    gallery_list_free(&l);
    snprintf(q, sizeof q, "rm -rf '%s'", dir);
    cr_assert_eq(system(q), 0);
}

Test(gallery, unreadable_drops_the_path_and_line_the_tile_names_already)
{
    char buf[128];
    gallery_unreadable("/a/b.obj", "/a/b.obj:3: unknown statement 'x'", buf, sizeof buf);
    cr_assert_str_eq(buf, "unreadable: unknown statement 'x'");
    gallery_unreadable("/a/b.obj", "/a/b.obj: not a model", buf, sizeof buf);
    cr_assert_str_eq(buf, "unreadable: not a model");
    gallery_unreadable("/a/b.obj", "out of memory", buf, sizeof buf);
    cr_assert_str_eq(buf, "unreadable: out of memory");
}

/* ==== The font ==== */

Test(gallery, every_printable_glyph_has_ink_but_the_space_and_differs_from_the_others)
{
    uint64_t bits[95];
    for (int c = 32; c < 127; c++) {
        uint64_t b = 0;
        for (int y = 0; y < GALLERY_GLYPH_H; y++)
            for (int x = 0; x < GALLERY_GLYPH_W; x++)
                b = b << 1 | (uint64_t)gallery_glyph_ink((unsigned char)c, x, y);
        bits[c - 32] = b;
        cr_assert(c == ' ' ? b == 0 : b != 0, "glyph '%c'", c);
        for (int k = 32; k < c; k++)
            cr_assert(bits[k - 32] != b, "'%c' and '%c' are drawn alike", k, c);
    }
    cr_assert(gallery_glyph_ink(0x80, 0, 0) && gallery_glyph_ink(0x80, 4, 6) && !gallery_glyph_ink(0x80, 2, 3),
              "a byte outside ASCII is a hollow box");
    cr_assert(!gallery_glyph_ink('A', -1, 0) && !gallery_glyph_ink('A', 5, 0) && !gallery_glyph_ink('A', 0, 7));
}
