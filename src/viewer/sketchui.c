/* sketchui.c: sketch mode of the viewer (zview --sketch, D). Polygons are
 * drawn on the canvas with the mouse (a left click adds a corner, a
 * right click closes) or the keys (arrows move a cursor, space adds,
 * Enter closes); the drawing (sketch.c) becomes the scene each time it
 * changes, rendered by the algorithm in use, so a person watches every
 * algorithm hide the polygons, flip their order and resolve them piercing
 * one another. The keys have their own table; a few of the viewer's
 * (algorithm, display mode, shading, help, quit) work here too. */

#define _DEFAULT_SOURCE         /* fdopen */

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tty.h"
#include "viewer_app.h"

#define TILT_STEP 15.0f         /* degrees per t T y Y */
#define SAVE_MAX  999           /* sketch-001.obj .. sketch-999.obj */

/* ==== Helpers ==== */

/* The drawing changed: the scene is built again before the next frame,
 * and the file written last no longer holds it. */
static Reaction changed(App *a)
{
    a->sk.dirty = 1;
    a->sk.saved_clean = 0;
    return RE_RENDER;
}

/* The picture's size in cells at the last frame. */
static void pic_cells(const App *a, int *cols_out, int *rows_out)
{
    int pw, ph;
    mode_cell_pixels(a->mode, &pw, &ph);
    *cols_out = a->sk.w / pw;
    *rows_out = a->sk.h / ph;
}

/* The canvas point at the centre of picture cell (x, y), pulled onto the
 * canvas: a click beside the square puts the corner on its edge. */
static SketchPt cell_canvas(const App *a, int x, int y)
{
    int pw, ph;
    mode_cell_pixels(a->mode, &pw, &ph);
    SketchPt c = sketch_canvas_at(a->sk.w, a->sk.h, mode_pixel_aspect(a->mode), ((float)x + 0.5f) * (float)pw,
                                  ((float)y + 0.5f) * (float)ph);
    c.x = fmaxf(-1, fminf(1, c.x));
    c.y = fmaxf(-1, fminf(1, c.y));
    return c;
}

/* The picture cell holding canvas point c (may be outside the picture). */
static void canvas_cell(const App *a, SketchPt c, int *x_out, int *y_out)
{
    int pw, ph;
    float px, py;
    mode_cell_pixels(a->mode, &pw, &ph);
    sketch_pixel_at(a->sk.w, a->sk.h, mode_pixel_aspect(a->mode), c, &px, &py);
    *x_out = (int)floorf(px / (float)pw);
    *y_out = (int)floorf(py / (float)ph);
}

static Reaction add_corner(App *a, int x, int y)
{
    if (a->sk.w <= 0)
        return RE_NONE;     /* no frame yet: nowhere to map the cell to */
    SketchPt c = cell_canvas(a, x, y);
    if (sketch_add_point(&a->sk.k, c.x, c.y)) {
        snprintf(a->note, sizeof a->note, "out of memory");
        return RE_DRAW;
    }
    snprintf(a->note, sizeof a->note, "corner %u at %.2f,%.2f", sketch_open_points(&a->sk.k), (double)c.x,
             (double)c.y);
    return RE_RENDER;       /* the open corners are marks on a fresh frame, not the scene */
}

static Reaction close_polygon(App *a)
{
    uint32_t open = sketch_open_points(&a->sk.k);
    if (sketch_close(&a->sk.k)) {
        snprintf(a->note, sizeof a->note, open < 3 ? "a polygon needs 3 corners (%u so far)" : "out of memory",
                 open);
        return RE_DRAW;
    }
    snprintf(a->note, sizeof a->note, "polygon %u closed", a->sk.k.npolys);
    return changed(a);
}

/* ==== Actions ==== */

typedef Reaction (*SketchAction)(App *a);

static Reaction move_cursor(App *a, int dx, int dy)
{
    int cols, rows;
    pic_cells(a, &cols, &rows);
    SketchMode *m = &a->sk;
    m->cursor = 1;
    m->cx = m->cx + dx < 0 ? 0 : m->cx + dx >= cols ? cols - 1 : m->cx + dx;
    m->cy = m->cy + dy < 0 ? 0 : m->cy + dy >= rows ? rows - 1 : m->cy + dy;
    return RE_RENDER;       /* marks go on fresh cells (the old cursor with the old frame) */
}

static Reaction sk_left(App *a)  { return move_cursor(a, -1, 0); }
static Reaction sk_right(App *a) { return move_cursor(a, 1, 0); }
static Reaction sk_up(App *a)    { return move_cursor(a, 0, -1); }
static Reaction sk_down(App *a)  { return move_cursor(a, 0, 1); }
/* Shift with an arrow: five cells, to cross a wide canvas in few presses */
static Reaction sk_far_left(App *a)  { return move_cursor(a, -5, 0); }
static Reaction sk_far_right(App *a) { return move_cursor(a, 5, 0); }
static Reaction sk_far_up(App *a)    { return move_cursor(a, 0, -5); }
static Reaction sk_far_down(App *a)  { return move_cursor(a, 0, 5); }

static Reaction sk_add(App *a)
{
    a->sk.cursor = 1;
    return add_corner(a, a->sk.cx, a->sk.cy);
}

static Reaction sk_close(App *a) { return close_polygon(a); }

static Reaction sk_flip(App *a)
{
    sketch_flip(&a->sk.k);
    snprintf(a->note, sizeof a->note, "%s drawn in front", a->sk.k.flipped ? "first" : "last");
    return changed(a);
}

static Reaction tilt(App *a, float about_vertical, float about_horizontal)
{
    Sketch *k = &a->sk.k;
    if (sketch_tilt(k, about_vertical, about_horizontal)) {
        snprintf(a->note, sizeof a->note, "no polygon to tilt: close one first");
        return RE_DRAW;
    }
    snprintf(a->note, sizeof a->note, "polygon %d tilted %g,%g", k->sel + 1, (double)k->tilt[2 * k->sel],
             (double)k->tilt[2 * k->sel + 1]);
    return changed(a);
}

static Reaction sk_tilt_right(App *a) { return tilt(a, TILT_STEP, 0); }
static Reaction sk_tilt_left(App *a)  { return tilt(a, -TILT_STEP, 0); }
static Reaction sk_tilt_up(App *a)    { return tilt(a, 0, TILT_STEP); }
static Reaction sk_tilt_down(App *a)  { return tilt(a, 0, -TILT_STEP); }

static Reaction sk_next(App *a)
{
    sketch_select_next(&a->sk.k);
    if (a->sk.k.sel >= 0)
        snprintf(a->note, sizeof a->note, "polygon %d selected", a->sk.k.sel + 1);
    return RE_DRAW;
}

static Reaction sk_undo(App *a)
{
    uint32_t open = sketch_open_points(&a->sk.k);
    if (sketch_undo(&a->sk.k)) {
        snprintf(a->note, sizeof a->note, "nothing to undo");
        return RE_DRAW;
    }
    if (open > 0) {
        snprintf(a->note, sizeof a->note, "corner taken back");
        return RE_RENDER;
    }
    snprintf(a->note, sizeof a->note, "polygon %u taken back", a->sk.k.npolys + 1);
    return changed(a);
}

static Reaction sk_clear(App *a)
{
    sketch_clear(&a->sk.k);
    snprintf(a->note, sizeof a->note, "cleared");
    return changed(a);
}

/* w: the drawing as sketch-NNN.obj in the current directory, the first
 * number not taken (O_EXCL: nothing is overwritten, even by a race). */
static Reaction sk_write(App *a)
{
    SketchMode *m = &a->sk;
    if (m->k.npolys == 0) {
        snprintf(a->note, sizeof a->note, "nothing to write: close a polygon first");
        return RE_DRAW;
    }
    char name[sizeof m->saved];
    int fd = -1;
    for (int n = 1; n <= SAVE_MAX && fd < 0; n++) {
        snprintf(name, sizeof name, "sketch-%03d.obj", n);
        fd = open(name, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST)
            break;
    }
    if (fd < 0) {
        snprintf(a->note, sizeof a->note, "%s: %s", name, errno == EEXIST ? "every number is taken" : strerror(errno));
        return RE_DRAW;
    }
    FILE *f = fdopen(fd, "w");
    if (!f) {
        int e = errno;
        close(fd);
        unlink(name);
        snprintf(a->note, sizeof a->note, "%s: %s", name, strerror(e));
        return RE_DRAW;
    }
    errno = 0;
    int rc = sketch_to_obj(&m->k, f);
    int e = errno;
    if (fclose(f) != 0 && !e)
        e = errno;
    if (rc || e) {
        unlink(name);       /* half a drawing is worse than none */
        snprintf(a->note, sizeof a->note, "%s: %s", name, strerror(e ? e : EIO));
        return RE_DRAW;
    }
    snprintf(m->saved, sizeof m->saved, "%s", name);
    m->saved_clean = 1;
    snprintf(a->note, sizeof a->note, "wrote %s", name);
    return RE_DRAW;
}

/* Give the model its place back (or quit when there is none). */
static Reaction sk_leave(App *a)
{
    SketchMode *m = &a->sk;
    if (m->only)
        return RE_QUIT;
    m->on = 0;
    m->cursor = 0;
    a->s = m->model;
    a->p.scene = a->s;
    /* the runner's trees and the shading caches know the scene by its
     * address: start them afresh (the runner joins its builder first) */
    shade_cache_free(&a->p.shade_cache);
    if (pipeline_set_algo(&a->p, a->p.algo))
        snprintf(a->note, sizeof a->note, "out of memory");
    if (m->built)
        scene_free(&m->scene);
    m->built = 0;
    return RE_RENDER;
}

static Reaction sk_toggle(App *a)
{
    if (a->sk.only) {
        snprintf(a->note, sizeof a->note, "no model to go back to (q quits)");
        return RE_DRAW;
    }
    return sk_leave(a);
}

/* ==== Entry points ==== */

Reaction sketch_mode_enter(App *a)
{
    SketchMode *m = &a->sk;
    if (m->on)
        return RE_NONE;
    m->on = 1;
    m->model = a->s;
    m->dirty = 1;
    m->cx = m->cy = -1;     /* the picture's middle, once its size is known */
    m->cursor = 1;          /* shown from the start: where space adds a corner */
    a->sel = -1;
    a->spin = 0;
    /* a first-time user sees a blank canvas: say how to start */
    snprintf(a->note, sizeof a->note, "arrows move +, space: corner, Enter: close");
    return RE_RENDER;
}

int sketch_mode_frame(App *a, int w, int h, float aspect)
{
    SketchMode *m = &a->sk;
    if (m->dirty || !m->built) {
        Scene s;
        char err[256];
        if (sketch_scene(&m->k, &s, err, sizeof err)) {
            snprintf(a->note, sizeof a->note, "%.70s", err);
            return -1;
        }
        s.light = m->model->light;
        /* a new scene, perhaps at the old one's address: the runner's
         * trees and the caches start afresh, the runner joined before
         * the old scene goes */
        shade_cache_free(&a->p.shade_cache);
        if (pipeline_set_algo(&a->p, a->p.algo)) {
            scene_free(&s);
            snprintf(a->note, sizeof a->note, "out of memory");
            return -1;
        }
        if (m->built)
            scene_free(&m->scene);
        m->scene = s;
        m->built = 1;
        m->dirty = 0;
        a->s = &m->scene;
        a->p.scene = a->s;
    }
    int pw, ph;
    mode_cell_pixels(a->mode, &pw, &ph);
    if (m->cx < 0 || m->w != w || m->h != h) {
        m->cx = w / pw / 2;
        m->cy = h / ph / 2;
    }
    m->w = w;
    m->h = h;
    sketch_camera(&m->scene, w, h, aspect);
    return 0;
}

static void mark(CellGrid *g, int x, int y, uint32_t ch)
{
    if (x < 0 || y < 0 || x >= g->cols || y >= g->rows)
        return;
    Cell *c = &g->cells[y * g->cols + x];
    c->ch = ch;
    memset(c->fg, 255, 3);          /* white on black shows on any colour */
    memset(c->bg, 0, 3);
    c->flags = CELL_FG | CELL_BG;
}

static void canvas_corners(const App *a, CellGrid *g);

void sketch_mode_marks(const App *a, CellGrid *g)
{
    canvas_corners(a, g);
    const Sketch *k = &a->sk.k;
    uint32_t open = sketch_open_points(k), first = k->npts - open;
    /* the open polygon's sides as dots, from each corner to the next
     * (the last one to the cursor when it is shown), then the corners */
    for (uint32_t i = first; i + 1 < k->npts || (a->sk.cursor && i < k->npts); i++) {
        int x0, y0, x1, y1;
        canvas_cell(a, k->pts[i], &x0, &y0);
        if (i + 1 < k->npts) {
            canvas_cell(a, k->pts[i + 1], &x1, &y1);
        } else {
            x1 = a->sk.cx;
            y1 = a->sk.cy;
        }
        int n = abs(x1 - x0) > abs(y1 - y0) ? abs(x1 - x0) : abs(y1 - y0);
        for (int s = 1; s < n; s++)
            mark(g, x0 + (int)lroundf((float)(x1 - x0) * (float)s / (float)n),
                 y0 + (int)lroundf((float)(y1 - y0) * (float)s / (float)n), '.');
    }
    for (uint32_t i = first; i < k->npts; i++) {
        int x, y;
        canvas_cell(a, k->pts[i], &x, &y);
        mark(g, x, y, 'o');
    }
    if (a->sk.cursor)
        mark(g, a->sk.cx, a->sk.cy, '+');
}

/* The canvas's corners, so that a person sees where a drawing can go
 * (a click beside it lands on its edge). ASCII: the locale may not be
 * UTF-8. Drawn under the drawing's marks. */
static void canvas_corners(const App *a, CellGrid *g)
{
    int x0, y0, x1, y1;
    canvas_cell(a, (SketchPt){ -1, -1 }, &x0, &y0);
    canvas_cell(a, (SketchPt){ 1, 1 }, &x1, &y1);
    int l = x0 < x1 ? x0 : x1, r = x0 < x1 ? x1 : x0, t = y0 < y1 ? y0 : y1, b = y0 < y1 ? y1 : y0;
    /* the cells of the corners themselves, kept inside the picture */
    l = l < 0 ? 0 : l;
    t = t < 0 ? 0 : t;
    r = r >= g->cols ? g->cols - 1 : r;
    b = b >= g->rows ? g->rows - 1 : b;
    if (r - l < 2 || b - t < 2)
        return;
    for (int k = 0; k < 2; k++) {
        int y = k ? b : t;
        mark(g, l, y, k ? '`' : ',');
        mark(g, l + 1, y, '-');
        mark(g, r - 1, y, '-');
        mark(g, r, y, k ? '\'' : '.');
    }
    mark(g, l, t + 1, '|');
    mark(g, r, t + 1, '|');
    mark(g, l, b - 1, '|');
    mark(g, r, b - 1, '|');
}

Reaction sketch_mode_click(App *a, int button, int x, int y)
{
    int cols, rows;
    pic_cells(a, &cols, &rows);
    if (x < 0 || y < 0 || x >= cols || y >= rows)
        return RE_NONE;     /* the status bar, or beside a --size picture */
    a->note[0] = 0;
    a->sk.cx = x;
    a->sk.cy = y;
    int had_cursor = a->sk.cursor;
    a->sk.cursor = 0;       /* the pointer is the cursor now */
    Reaction r = button == 1 ? add_corner(a, x, y) : close_polygon(a);
    return had_cursor ? r | RE_RENDER : r;     /* the mark goes with a fresh frame */
}

const char *sketch_mode_file(const App *a)
{
    return a->sk.saved[0] && a->sk.saved_clean ? a->sk.saved : NULL;
}

void sketch_mode_status(const App *a, char *buf, size_t len, int width)
{
    const SketchMode *m = &a->sk;
    char sel[24] = "", hints[96], counts[96], algo[48], note[sizeof a->note + 4] = "";
    if (m->k.sel >= 0)
        snprintf(sel, sizeof sel, " | #%d selected", m->k.sel + 1);
    snprintf(hints, sizeof hints, " | Tab flip t y tilt n next u undo c clear w write %s", m->only ? "q quit" : "D back");
    snprintf(counts, sizeof counts, " | %u polygon%s | %u open%s%s", m->k.npolys, m->k.npolys == 1 ? "" : "s",
             sketch_open_points(&m->k), sel, m->k.flipped ? " | flipped" : "");
    snprintf(algo, sizeof algo, " | %s %.2fms", a->p.algo->name, a->p.hsr_ms);
    if (a->note[0])
        snprintf(note, sizeof note, " | %s", a->note);
    /* the parts in the order they go when the window is narrow: the key
     * hints first, then the algorithm, then the counts; a note answers
     * the key just pressed (w's file name) and outranks them all, as in
     * the viewer's bar; the help key stays (the whole cut at the end in
     * a window narrower still) */
    for (int keep = 3; keep >= 0; keep--) {
        int n = snprintf(buf, len, " sketch%s%s%s%s | ? help", keep >= 1 ? counts : "", keep >= 2 ? algo : "", note,
                         keep >= 3 ? hints : "");
        if (n >= 0 && n <= width)
            return;
    }
    if (width >= 0 && (size_t)width < len)
        buf[width] = 0;
}

void sketch_mode_free(App *a)
{
    sketch_free(&a->sk.k);
    if (a->sk.built)
        scene_free(&a->sk.scene);
    a->sk.built = 0;
}

/* The key table of sketch mode, which is also its help. A key bound to
 * NULL keeps the viewer's meaning (action.c passes it on). */
const KeyRow sketch_keys[] = {
    { "left click", "add a corner there", { { 0, NULL } } },
    { "arrows", "move the cursor",
      { { TK_LEFT, sk_left }, { TK_RIGHT, sk_right }, { TK_UP, sk_up }, { TK_DOWN, sk_down } } },
    { "Shift-arrows", "move the cursor 5 cells",
      { { TK_SLEFT, sk_far_left }, { TK_SRIGHT, sk_far_right }, { TK_SUP, sk_far_up }, { TK_SDOWN, sk_far_down } } },
    { "space", "add a corner at the cursor", { { ' ', sk_add } } },
    { "right click Enter", "close the polygon", { { TK_ENTER, sk_close } } },
    { "Tab", "flip the depth order", { { TK_TAB, sk_flip } } },
    { "t T", "tilt about the vertical", { { 't', sk_tilt_right }, { 'T', sk_tilt_left } } },
    { "y Y", "tilt about the horizontal", { { 'y', sk_tilt_up }, { 'Y', sk_tilt_down } } },
    { "n", "select the next polygon", { { 'n', sk_next } } },
    { "u Backspace", "undo a corner or polygon", { { 'u', sk_undo }, { TK_BACKSPACE, sk_undo } } },
    { "c", "clear all", { { 'c', sk_clear } } },
    { "w", "write sketch-NNN.obj", { { 'w', sk_write } } },
    { "g G", "next / previous algorithm", { { 'g', NULL }, { 'G', NULL } } },
    { "m v", "display mode, shading", { { 'm', NULL }, { 'v', NULL } } },
    { "e S", "outlines, samples", { { 'e', NULL }, { 'S', NULL } } },
    { "C", "command line (after w)", { { 'C', NULL } } },
    { "D Esc", "back to the model (Esc: quit if none)", { { 'D', sk_toggle }, { TK_ESC, sk_leave } } },
    { "?", "this help", { { '?', NULL } } },
    { "Ctrl-L", "redraw", { { TK_CTRL_L, NULL } } },
    { "q", "quit", { { 'q', NULL } } },
};
const int sketch_keys_n = (int)(sizeof sketch_keys / sizeof sketch_keys[0]);
