/* measureui.c: the measuring mode (M). The arrows move a cursor from
 * vertex to vertex of what the picture shows (app_measure_step: the
 * nearest visible one that way), Enter marks the vertex under it (up
 * to three: a fourth starts again), Backspace takes the last mark back,
 * Esc or M leaves. The marks are vertices, so they stay on the model
 * while it turns (h j k l and the mouse still turn it); the status bar
 * gives the cursor's coordinates and what the marks measure
 * (app_measure_words), and C writes them as --marks. */

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
        snprintf(a->note, sizeof a->note, "measuring: arrows move, Enter marks, Backspace unmarks, M leaves");
    return RE_RENDER;
}

Reaction viewer_measure_key(App *a, int key)
{
    MeasureMarks *m = &a->p.marks;
    int dx = key == TK_LEFT ? -1 : key == TK_RIGHT ? 1 : 0, dy = key == TK_UP ? -1 : key == TK_DOWN ? 1 : 0;
    if (dx || dy) {
        if (app_measure_step(&a->p, dx, dy))
            snprintf(a->note, sizeof a->note, "no vertex in sight that way");
        return RE_RENDER;
    }
    switch (key) {
    case TK_ENTER:
        if (!m->cursor)
            return RE_DRAW;
        if (m->n == MEASURE_MARKS)
            m->n = 0;
        m->obj[m->n] = m->cur_obj;
        m->v[m->n++] = m->cur_v;
        return RE_RENDER;
    case TK_BACKSPACE:
        if (m->n)
            m->n--;
        return RE_RENDER;
    case TK_ESC:
        return viewer_measure_toggle(a);
    }
    return RE_NONE;
}
