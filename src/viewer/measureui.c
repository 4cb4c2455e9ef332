/* measureui.c: the measuring mode (M). The arrows move a cursor from
 * point to point of what the picture shows (app_measure_step: the
 * nearest visible one that way), and so does the mouse: a left click
 * (or a drag with it held) puts the cursor on the visible point nearest
 * the cell (app_measure_pick), and a click on the cursor's own point
 * marks it, as Enter does (up to three marks: a fourth starts again).
 * The points are vertices; S widens the snap to edge midpoints and face
 * centres too, and so does Ctrl or Shift held with a click, where the
 * terminal reports it. Backspace takes the last mark back, Esc or M
 * leaves. The marks are points of the mesh, so they stay on the model
 * while it turns (h j k l, the right drag and the wheel still work); the
 * status bar gives the snap, the cursor's coordinates and what the
 * marks measure (app_measure_words), and C writes them as --marks. */

#include <stdio.h>

#include "tty.h"
#include "viewer_app.h"

Reaction viewer_measure_toggle(App *a)
{
    MeasureMarks *m = &a->p.marks;
    a->measuring = !a->measuring;
    if (!a->measuring) {
        m->cursor = 0;
        m->n = 0;
        snprintf(a->note, sizeof a->note, "measuring off");
        return RE_RENDER;
    }
    if (app_measure_step(&a->p, 0, 0))
        snprintf(a->note, sizeof a->note, "measuring: no vertex in sight");
    else
        snprintf(a->note, sizeof a->note,
                 "measuring: arrows or click move, Enter or a click on the cursor marks, S snap, Bksp, M leaves");
    return RE_RENDER;
}

static Reaction mark(App *a)
{
    MeasureMarks *m = &a->p.marks;
    if (!m->cursor)
        return RE_DRAW;
    if (m->n == MEASURE_MARKS)
        m->n = 0;
    m->mark[m->n++] = m->cur;
    return RE_RENDER;
}

Reaction viewer_measure_key(App *a, int key)
{
    MeasureMarks *m = &a->p.marks;
    int dx = key == TK_LEFT ? -1 : key == TK_RIGHT ? 1 : 0, dy = key == TK_UP ? -1 : key == TK_DOWN ? 1 : 0;
    if (dx || dy) {
        if (app_measure_step(&a->p, dx, dy))
            snprintf(a->note, sizeof a->note, "no point in sight that way");
        return RE_RENDER;
    }
    switch (key) {
    case TK_ENTER:
        return mark(a);
    case TK_BACKSPACE:
        if (m->n)
            m->n--;
        return RE_RENDER;
    case 'S':
        m->wide = !m->wide;
        snprintf(a->note, sizeof a->note, "snap to %s",
                 m->wide ? "vertices, edge midpoints and face centres" : "vertices");
        return RE_RENDER;
    case TK_ESC:
        return viewer_measure_toggle(a);
    }
    return RE_NONE;
}

Reaction viewer_measure_mouse(App *a, int x, int y, int mods, int drag)
{
    const CellGrid *g = &a->p.cells;
    const FrameBufs *fb = &a->p.fb;
    if (x < 0 || y < 0 || x >= g->cols || y >= g->rows || !fb->w)
        return RE_NONE;     /* the status bar, or beside a --size picture */
    /* the cell's middle in samples of the last frame (cells or, after a
     * still image, the terminal's pixels: the same picture either way) */
    double sx = (x + 0.5) * fb->w / g->cols, sy = (y + 0.5) * fb->h / g->rows;
    MeasureMarks *m = &a->p.marks;
    MeasurePick was = m->cur;
    int had = m->cursor;
    if (app_measure_pick(&a->p, sx, sy, m->wide || (mods & (TE_CTRL | TE_SHIFT)))) {
        snprintf(a->note, sizeof a->note, "no point in sight");
        return RE_DRAW;
    }
    a->note[0] = 0;
    if (!drag && had && was.obj == m->cur.obj && was.kind == m->cur.kind && was.a == m->cur.a &&
        (was.kind != MEASURE_EDGE || was.b == m->cur.b))
        return mark(a);
    return RE_RENDER;
}
