/* test_sketchui.c: sketch mode's keys and clicks without a terminal: a
 * click's corner lands in the clicked cell, the drawing becomes the
 * scene, flip, tilt, undo, clear, the file w writes and the command line
 * that opens it, and D in and out. */

#define _DEFAULT_SOURCE     /* mkdtemp */

#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../src/viewer/viewer_app.h"
#include "tty.h"

static Options opt;
static Scene model;
static App app;

enum { COLS = 60, ROWS = 20 };      /* the picture in half-block cells: 60 x 40 pixels */

static void setup(void)
{
    char err[256];
    cli_defaults(&opt);
    cr_assert_eq(scene_build(&model, NULL, 0, err, sizeof err), 0, "%s", err);
    light_set(&model.light, LIGHT_YAW, LIGHT_PITCH, LIGHT_AMBIENT);
    memset(&app, 0, sizeof app);
    sketch_init(&app.sk.k);
    app.opt = &opt;
    app.s = &model;
    app.sel = -1;
    app.mode = MODE_HALF;
    app.utf8 = 1;
    cr_assert_eq(pipeline_init(&app.p, &model, hsr_find("zbuffer"), 1), 0);
    app.p.samples = 1;
}

static void teardown(void)
{
    pipeline_free(&app.p);
    sketch_mode_free(&app);
    scene_free(&model);
}

TestSuite(sketchui, .init = setup, .fini = teardown);

/* A frame as the viewer makes one: the sketch's scene and camera, then
 * the render; the face id seen at the middle of cell (x, y). */
static void frame(void)
{
    int pw, ph;
    mode_cell_pixels(app.mode, &pw, &ph);
    cr_assert_eq(sketch_mode_frame(&app, COLS * pw, ROWS * ph, mode_pixel_aspect(app.mode)), 0, "%s", app.note);
    cr_assert_eq(pipeline_render(&app.p, COLS * pw, ROWS * ph, mode_pixel_aspect(app.mode), 0, 1), 0);
}

static int32_t seen(int x, int y)
{
    int pw, ph;
    mode_cell_pixels(app.mode, &pw, &ph);
    return app.p.fb.ids[(y * ph + ph / 2) * app.p.fb.w + x * pw];
}

/* A rectangle of clicked cells, closed by a right click. */
static void rect(int x0, int y0, int x1, int y1)
{
    const int c[4][2] = { { x0, y0 }, { x1, y0 }, { x1, y1 }, { x0, y1 } };
    for (int i = 0; i < 4; i++)
        cr_assert_eq(sketch_mode_click(&app, 1, c[i][0], c[i][1]), RE_RENDER, "%s", app.note);
    cr_assert_eq(sketch_mode_click(&app, 3, x0, y0), RE_RENDER, "%s", app.note);
    frame();
}

static void start(void)
{
    cr_assert_eq(viewer_key(&app, 'D'), RE_RENDER | RE_DRAW);
    cr_assert(app.sk.on);
    frame();
    cr_assert_eq(app.s, &app.sk.scene, "the drawing is the scene");
    cr_assert_eq(app.s->nfaces, 0u);
}

Test(sketchui, clicked_polygons_cover_the_clicked_cells)
{
    start();
    rect(14, 3, 35, 12);
    cr_expect_eq(app.s->nfaces, 1u);
    /* the corners are the cells' middles: the cells next to the sides
     * inside are covered, the ones outside are not */
    cr_expect_eq(seen(15, 4), 0);
    cr_expect_eq(seen(34, 11), 0);
    cr_expect_eq(seen(13, 4), -1, "left of it");
    cr_expect_eq(seen(36, 11), -1, "right of it");
    cr_expect_eq(seen(20, 13), -1, "below it");
    rect(25, 8, 46, 17);
    cr_expect_eq(seen(30, 10), 1, "the last drawn is nearer");
    cr_expect_eq(seen(20, 5), 0);
    cr_expect_eq(seen(42, 15), 1);
    char bar[256];
    sketch_mode_status(&app, bar, sizeof bar, 200);
    cr_expect(strstr(bar, " sketch | 2 polygons | 0 open | #2 selected | zbuffer") == bar, "%s", bar);
}

Test(sketchui, a_click_beside_the_canvas_lands_on_its_edge)
{
    start();
    /* the canvas is 95% of the 40-pixel height wide: cells 11..48 */
    cr_assert_eq(sketch_mode_click(&app, 1, 0, 0), RE_RENDER);
    cr_expect_float_eq(app.sk.k.pts[0].x, -1, 1e-6);
    cr_expect_float_eq(app.sk.k.pts[0].y, 1, 1e-6);
    cr_expect_eq(sketch_mode_click(&app, 1, COLS, 0), RE_NONE, "past the picture: ignored");
    cr_expect_eq(sketch_open_points(&app.sk.k), 1u);
}

Test(sketchui, keys_flip_tilt_undo_clear)
{
    start();
    rect(14, 3, 35, 12);
    rect(25, 8, 46, 17);
    viewer_key(&app, TK_TAB);
    frame();
    cr_expect_eq(seen(30, 10), 0, "flipped: the first drawn in front");
    viewer_key(&app, TK_TAB);
    /* tilted 45 degrees about the vertical, the second pierces the first */
    for (int i = 0; i < 3; i++)
        viewer_key(&app, 't');
    frame();
    cr_expect_float_eq(app.sk.k.tilt[2], 45, 1e-6);
    cr_expect_eq(seen(26, 10), 0, "its left side behind");
    cr_expect_eq(seen(34, 10), 1, "its right side in front");
    viewer_key(&app, 'n');
    cr_expect_eq(app.sk.k.sel, 0, "n selects the next (wrapping)");
    viewer_key(&app, 'u');
    frame();
    cr_expect_eq(app.s->nfaces, 1u, "u takes the last polygon back");
    cr_expect_eq(seen(42, 15), -1);
    viewer_key(&app, ' ');
    cr_expect_eq(sketch_open_points(&app.sk.k), 1u, "space adds a corner at the cursor");
    viewer_key(&app, TK_BACKSPACE);
    cr_expect_eq(sketch_open_points(&app.sk.k), 0u, "Backspace takes it back");
    viewer_key(&app, 'c');
    frame();
    cr_expect_eq(app.s->nfaces, 0u, "c clears all");
}

Test(sketchui, arrows_move_the_cursor_and_marks_show_it)
{
    start();
    int cx = app.sk.cx, cy = app.sk.cy;
    cr_expect_eq(cx, COLS / 2);
    cr_expect_eq(cy, ROWS / 2);
    viewer_key(&app, TK_LEFT);
    viewer_key(&app, TK_UP);
    cr_expect_eq(app.sk.cx, cx - 1);
    cr_expect_eq(app.sk.cy, cy - 1);
    cr_expect(app.sk.cursor);
    for (int i = 0; i < 200; i++)
        viewer_key(&app, TK_RIGHT);
    cr_expect_eq(app.sk.cx, COLS - 1, "the cursor stays in the picture");
    for (int i = 0; i < 20; i++)
        viewer_key(&app, TK_LEFT);
    viewer_key(&app, ' ');
    frame();
    cr_assert_eq(cells_from_image(&app.p.img, app.mode, COLOUR_TRUE, &app.p.cells), 0);
    sketch_mode_marks(&app, &app.p.cells);
    const Cell *row = &app.p.cells.cells[(cy - 1) * COLS];
    cr_expect_eq(row[39].ch, '+', "the cursor over its corner");
    viewer_key(&app, TK_LEFT);
    viewer_key(&app, TK_LEFT);
    cr_assert_eq(cells_from_image(&app.p.img, app.mode, COLOUR_TRUE, &app.p.cells), 0);
    sketch_mode_marks(&app, &app.p.cells);
    cr_expect_eq(row[39].ch, 'o', "the open corner");
    cr_expect_eq(row[38].ch, '.', "the side on to the cursor");
    cr_expect_eq(row[37].ch, '+');
}

Test(sketchui, w_writes_the_next_free_file_and_the_command_opens_it)
{
    char dir[] = "/tmp/zv-sketch-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    cr_assert_eq(chdir(dir), 0);
    start();
    char cmd[CMD_MAX];
    cr_expect_eq(viewer_key(&app, 'w'), RE_DRAW);
    cr_expect(strstr(app.note, "nothing to write") != NULL, "%s", app.note);
    rect(14, 3, 35, 12);
    cr_expect_eq(viewer_view_command(&app, cmd, sizeof cmd), -1, "not written yet");
    FILE *f = fopen("sketch-001.obj", "w");
    cr_assert_not_null(f);
    fclose(f);
    viewer_key(&app, 'w');
    cr_expect_str_eq(app.note, "wrote sketch-002.obj", "the first number taken: the next");
    cr_assert_eq(viewer_view_command(&app, cmd, sizeof cmd), 0);
    cr_expect(strstr(cmd, "zview sketch-002.obj --yaw 0 --pitch 0 --zoom ") == cmd, "%s", cmd);
    /* the file reads back as the scene on screen */
    Mesh *m = calloc(1, sizeof *m);
    char err[256];
    cr_assert_eq(mesh_load(m, "sketch-002.obj", err, sizeof err), 0, "%s", err);
    cr_expect_eq(m->nfaces, 1u);
    mesh_free(m);
    free(m);
    rect(25, 8, 46, 17);
    cr_expect_eq(viewer_view_command(&app, cmd, sizeof cmd), -1, "changed since: the file no longer shows it");
    unlink("sketch-001.obj");
    unlink("sketch-002.obj");
    cr_expect_eq(rmdir(dir), 0);
}

Test(sketchui, D_goes_back_to_the_model_and_help_lists_the_keys)
{
    start();
    rect(14, 3, 35, 12);
    const char *lines[HELP_LINES_MAX];
    viewer_key(&app, '?');
    int n = viewer_help_layout(&app, 120, 40, lines);
    int found = 0;
    for (int i = 0; i < n; i++)
        found |= strstr(lines[i], "flip the depth order") != NULL;
    cr_expect(found, "the sketch's keys in its help");
    viewer_key(&app, 'x');     /* closes the help */
    cr_expect_eq(viewer_key(&app, 'D'), RE_RENDER | RE_DRAW);
    cr_expect(!app.sk.on);
    cr_expect_eq(app.s, &model);
    cr_expect_eq(app.p.scene, &model);
    viewer_key(&app, 'D');
    frame();
    cr_expect_eq(app.s->nfaces, 1u, "the drawing is kept");
    app.sk.only = 1;
    cr_expect(viewer_key(&app, TK_ESC) & RE_QUIT, "started with --sketch: Esc quits");
}

/* The canvas's corners: each a corner mark, a side's first cell and the
 * first cell down (or up) the side, the rest of the picture unmarked but
 * for the cursor in the middle. The canvas is 38 pixels square (95% of
 * the 40-pixel height), centred: its sides at x = 11 and 49 and at
 * y = 1 and 39, in cells 11 and 49 and rows 0 and 19; the rows are drawn
 * here by hand. */
Test(sketchui, the_canvas_corners)
{
    start();
    frame();
    cr_assert_eq(cells_from_image(&app.p.img, app.mode, COLOUR_TRUE, &app.p.cells), 0);
    for (int i = 0; i < COLS * ROWS; i++)
        app.p.cells.cells[i].ch = ' ';
    sketch_mode_marks(&app, &app.p.cells);
    char want[ROWS][COLS + 1];
    for (int y = 0; y < ROWS; y++)
        snprintf(want[y], sizeof want[y], "%*s", COLS, "");
    memcpy(want[0] + 11, ",-", 2);
    memcpy(want[0] + 48, "-.", 2);
    want[1][11] = want[1][49] = '|';
    want[18][11] = want[18][49] = '|';
    memcpy(want[19] + 11, "`-", 2);
    memcpy(want[19] + 48, "-'", 2);
    want[ROWS / 2][COLS / 2] = '+';
    for (int y = 0; y < ROWS; y++) {
        char got[COLS + 1];
        for (int x = 0; x < COLS; x++)
            got[x] = (char)app.p.cells.cells[y * COLS + x].ch;
        got[COLS] = 0;
        cr_expect_str_eq(got, want[y], "row %d: [%s]", y, got);
    }
}
