/* action: the viewer's key table. Each row of it is a line of the ? help
 * and the keys it names, each bound to a tiny action that changes the
 * view and returns what to redo (viewer_app.h). Turns, moves and scaling
 * apply to the selected object, or to the whole scene (the camera) when
 * none is selected. */

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tty.h"
#include "viewer_app.h"

#define STEP_DEG   5.0f     /* arrows, hjkl, u/o */
#define COARSE_DEG 15.0f    /* IJKL */
#define DRAG_DEG   3.0f     /* per cell of a left drag */
#define MOVE_FRAC  0.05f    /* of the scene radius (or fit radius) per key */
#define SCALE_STEP 1.15f
#define LIGHT_STEP 15.0f    /* degrees per [ ] { } */

/* ==== Helpers ==== */

static Object *selected(App *a)
{
    return a->sel >= 0 && a->sel < a->s->nobjs ? &a->s->objs[a->sel] : NULL;
}

/* Turn by degrees: yaw about the vertical (positive brings the front to
 * the right), pitch about the horizontal (positive tips the front down),
 * roll about the view axis (positive is anticlockwise). */
static Reaction turn(App *a, float dyaw, float dpitch, float droll)
{
    Object *o = selected(a);
    float *y = o ? &o->yaw : &a->s->cam.yaw;
    float *p = o ? &o->pitch : &a->s->cam.pitch;
    float *r = o ? &o->roll : &a->s->cam.roll;
    *y = remainderf(*y + deg2rad(dyaw), 2 * ZV_PI);
    *p = remainderf(*p + deg2rad(dpitch), 2 * ZV_PI);
    *r = remainderf(*r + deg2rad(droll), 2 * ZV_PI);
    return RE_RENDER;
}

/* Move by fractions of the scene's size along the screen's right and up. */
static Reaction move(App *a, float right, float up)
{
    Camera *c = &a->s->cam;
    float zoom = c->zoom > 0 ? c->zoom : 1;
    Object *o = selected(a);
    if (!o) {
        c->pan.x += right / zoom;
        c->pan.y += up / zoom;
        return RE_RENDER;
    }
    /* The screen's axes in world space: the camera turn is a rotation,
     * so its inverse is its transpose. */
    Mat4 t = m4_rotate_ypr(c->yaw, c->pitch, c->roll);
    float k = c->radius / zoom;
    for (int i = 0; i < 3; i++) {
        float d = (t.m[0][i] * right + t.m[1][i] * up) * k;
        if (i == 0) o->offset.x += d;
        else if (i == 1) o->offset.y += d;
        else o->offset.z += d;
    }
    return RE_RENDER;
}

static Reaction scale(App *a, float f)
{
    Object *o = selected(a);
    float *v = o ? &o->scale : &a->s->cam.zoom;
    float n = *v * f;
    if (n < 1e-3f || n > 1e3f)
        return RE_NONE;
    *v = n;
    return RE_RENDER;
}

/* ==== Actions ==== */

static Reaction act_yaw_left(App *a)    { return turn(a, -STEP_DEG, 0, 0); }
static Reaction act_yaw_right(App *a)   { return turn(a, STEP_DEG, 0, 0); }
static Reaction act_pitch_up(App *a)    { return turn(a, 0, -STEP_DEG, 0); }
static Reaction act_pitch_down(App *a)  { return turn(a, 0, STEP_DEG, 0); }
static Reaction act_roll_left(App *a)   { return turn(a, 0, 0, STEP_DEG); }
static Reaction act_roll_right(App *a)  { return turn(a, 0, 0, -STEP_DEG); }
static Reaction act_big_left(App *a)    { return turn(a, -COARSE_DEG, 0, 0); }
static Reaction act_big_right(App *a)   { return turn(a, COARSE_DEG, 0, 0); }
static Reaction act_big_up(App *a)      { return turn(a, 0, -COARSE_DEG, 0); }
static Reaction act_big_down(App *a)    { return turn(a, 0, COARSE_DEG, 0); }
static Reaction act_move_left(App *a)   { return move(a, -MOVE_FRAC, 0); }
static Reaction act_move_right(App *a)  { return move(a, MOVE_FRAC, 0); }
static Reaction act_move_up(App *a)     { return move(a, 0, MOVE_FRAC); }
static Reaction act_move_down(App *a)   { return move(a, 0, -MOVE_FRAC); }
static Reaction act_bigger(App *a)      { return scale(a, SCALE_STEP); }
static Reaction act_smaller(App *a)     { return scale(a, 1 / SCALE_STEP); }

static Reaction act_fit(App *a)
{
    scene_fit(a->s);
    return RE_RENDER;
}

/* Back to the view the model opened with, objects where they opened. */
static Reaction act_reset(App *a)
{
    scene_reset(a->s);
    if (a->opening.zoom > 0)        /* set when the viewer started */
        scene_view_like(a->s, &a->opening);
    return RE_RENDER;
}

static Reaction act_next_object(App *a)
{
    if (a->s->nobjs == 0)
        return RE_NONE;
    a->sel = (a->sel + 1) % a->s->nobjs;
    return RE_DRAW;
}

static Reaction act_prev_object(App *a)
{
    if (a->s->nobjs == 0)
        return RE_NONE;
    a->sel = a->sel <= 0 ? a->s->nobjs - 1 : a->sel - 1;
    return RE_DRAW;
}

static Reaction act_whole_scene(App *a)
{
    a->sel = -1;
    return RE_DRAW;
}

static Reaction set_algo(App *a, int k)
{
    k = (k + hsr_nalgos) % hsr_nalgos;
    if (pipeline_set_algo(&a->p, hsr_algos[k])) {
        /* keep the old one running */
        pipeline_set_algo(&a->p, hsr_algos[a->algo]);
        snprintf(a->note, sizeof a->note, "out of memory for %s", hsr_algos[k]->name);
        return RE_DRAW;
    }
    a->algo = k;
    return RE_RENDER;
}

static Reaction act_next_algo(App *a) { return set_algo(a, a->algo + 1); }
static Reaction act_prev_algo(App *a) { return set_algo(a, a->algo - 1); }

static Reaction act_mode(App *a)
{
    if (!a->utf8) {
        snprintf(a->note, sizeof a->note, "half and braille need a UTF-8 locale");
        return RE_DRAW;
    }
    /* where the terminal draws pixels: stills in pixels (cells, half
     * blocks, while the model moves), then each text mode alone */
    PixelProto px = term_pixels();
    if (a->pixels && px != PIX_CELLS) {
        a->pixels = 0;
    } else if (px != PIX_CELLS && a->mode == MODE_COUNT - 1) {
        a->pixels = 1;
        a->mode = MODE_HALF;
    } else {
        a->pixels = 0;          /* a text mode chosen: pixels named late do not take over */
        a->mode = (DisplayMode)((a->mode + 1) % MODE_COUNT);
    }
    /* every key that changes a setting says so: at 80 columns the
     * bar's own field for it is one of the first to go */
    if (a->pixels)
        snprintf(a->note, sizeof a->note, "mode: %s when still, %s while moving", pixel_proto_names[px],
                 mode_names[a->mode]);
    else
        snprintf(a->note, sizeof a->note, "mode: %s", mode_names[a->mode]);
    return RE_RENDER;
}

static Reaction act_shade(App *a)
{
    a->p.shade = (ShadeMode)((a->p.shade + 1) % SHADE_COUNT);
    snprintf(a->note, sizeof a->note, "shading: %s", shade_names[a->p.shade]);
    return RE_RENDER;
}

/* A named view (1-7) or the automatic one (8): the camera turned there
 * and fitted, as --view NAME starts; objects keep their placements. */
static Reaction look_from(App *a, float yaw, float pitch, const char *name)
{
    Camera *c = &a->s->cam;
    c->yaw = remainderf(deg2rad(yaw), 2 * ZV_PI);
    c->pitch = remainderf(deg2rad(pitch), 2 * ZV_PI);
    c->roll = 0;
    scene_fit(a->s);
    snprintf(a->note, sizeof a->note, "view %s", name);
    return RE_RENDER;
}

static Reaction set_view(App *a, int i)
{
    float y, p;
    const char *name = view_name(i);
    if (!name || view_from_name(name, &y, &p))
        return RE_NONE;
    return look_from(a, y, p, name);
}

static Reaction act_view1(App *a) { return set_view(a, 0); }
static Reaction act_view2(App *a) { return set_view(a, 1); }
static Reaction act_view3(App *a) { return set_view(a, 2); }
static Reaction act_view4(App *a) { return set_view(a, 3); }
static Reaction act_view5(App *a) { return set_view(a, 4); }
static Reaction act_view6(App *a) { return set_view(a, 5); }
static Reaction act_view7(App *a) { return set_view(a, 6); }

static Reaction act_view_auto(App *a)
{
    FirstView pick;
    app_first_view(a->s, a->opt->threads, &pick);
    return look_from(a, pick.yaw, pick.pitch, "auto");
}

/* Turn the light (it stays fixed to the view): yaw wraps, pitch stops
 * straight above or below. */
static Reaction move_light(App *a, float dyaw, float dpitch)
{
    Light *l = &a->s->light;
    float yaw = remainderf(l->yaw + dyaw, 360.0f);
    float pitch = l->pitch + dpitch;
    pitch = pitch > 90 ? 90 : pitch < -90 ? -90 : pitch;
    light_set(l, yaw, pitch, l->ambient);
    snprintf(a->note, sizeof a->note, "light %g,%g", l->yaw, l->pitch);
    return RE_RENDER;
}

static Reaction act_light_left(App *a)  { return move_light(a, -LIGHT_STEP, 0); }
static Reaction act_light_right(App *a) { return move_light(a, LIGHT_STEP, 0); }
static Reaction act_light_up(App *a)    { return move_light(a, 0, LIGHT_STEP); }
static Reaction act_light_down(App *a)  { return move_light(a, 0, -LIGHT_STEP); }

static Reaction act_edges(App *a)
{
    a->p.edges = !a->p.edges;
    snprintf(a->note, sizeof a->note, "edges %s", a->p.edges ? "on" : "off");
    return RE_RENDER;
}

static Reaction act_textures(App *a)
{
    a->p.no_textures = !a->p.no_textures;
    snprintf(a->note, sizeof a->note, "textures %s", a->p.no_textures ? "off" : "on");
    return RE_RENDER;
}

/* 1, 4, 9, 16 samples a pixel, round */
static Reaction act_samples(App *a)
{
    int k = pipeline_samples_side(a->p.samples) % 4 + 1;
    a->p.samples = k * k;
    snprintf(a->note, sizeof a->note, "samples %d", a->p.samples);
    return RE_RENDER;
}

static Reaction act_command(App *a)
{
    a->cmd = 1;
    return RE_DRAW;
}

static Reaction act_snapshot(App *a)
{
    return viewer_snapshot(a);
}

static Reaction act_persp(App *a)
{
    a->s->cam.persp = !a->s->cam.persp;
    if (a->s->cam.fov_deg <= 1)
        a->s->cam.fov_deg = 50;
    snprintf(a->note, sizeof a->note, "%s", a->s->cam.persp ? "perspective" : "orthographic");
    return RE_RENDER;
}

static Reaction act_cull(App *a)
{
    a->cull = !a->cull;
    snprintf(a->note, sizeof a->note, "back faces %s", a->cull ? "culled" : "drawn");
    return RE_RENDER;
}

/* The model's up axis, cycled y, z, x, -y, -z, -x (for every object),
 * then fitted again: most scans and CAD files are z-up. */
static Reaction act_up(App *a)
{
    int up = ((a->s->nobjs ? a->s->objs[0].up : 0) + 1) % UP_COUNT;
    scene_set_up(a->s, up);
    snprintf(a->note, sizeof a->note, "up: %s", up_axis_name(up));
    return RE_RENDER;
}

/* Points and lines: the squares' size and the lines' width in pixels,
 * and the wireframe (every face edge as a line). */
static Reaction prim_step(App *a, int *v, int d, const char *what)
{
    int n = *v + d;
    if (n < 1 || n > POINT_SIZE_MAX)
        return RE_NONE;
    *v = n;
    snprintf(a->note, sizeof a->note, "%s %d", what, n);
    return RE_RENDER;
}

static Reaction act_point_bigger(App *a)  { return prim_step(a, &a->p.point_size, 1, "point size"); }
static Reaction act_point_smaller(App *a) { return prim_step(a, &a->p.point_size, -1, "point size"); }
static Reaction act_line_wider(App *a)    { return prim_step(a, &a->p.line_width, 1, "line width"); }
static Reaction act_line_thinner(App *a)  { return prim_step(a, &a->p.line_width, -1, "line width"); }

static Reaction act_wireframe(App *a)
{
    a->p.wireframe = !a->p.wireframe;
    snprintf(a->note, sizeof a->note, "wireframe %s", a->p.wireframe ? "on" : "off");
    return RE_RENDER;
}

/* What the check finds, on the model (checkjob.c runs it when wanted). */
static Reaction act_problems(App *a)
{
    a->p.problems = !a->p.problems;
    if (!a->p.problems)
        viewer_focus_clear(a);
    snprintf(a->note, sizeof a->note, "problems %s", a->p.problems ? "shown" : "hidden");
    return RE_RENDER;
}

/* The section planes (cutkeys.c). */
static Reaction act_cut(App *a) { return viewer_cut_toggle(a); }
static Reaction act_cut_back(App *a) { return viewer_cut_slide(a, -1); }
static Reaction act_cut_on(App *a) { return viewer_cut_slide(a, 1); }
static Reaction act_cut_turn(App *a) { return viewer_cut_turn(a); }
static Reaction act_cut_next(App *a) { return viewer_cut_next(a); }

/* The next and previous problem in focus (checkjob.c). */
static Reaction act_next_problem(App *a) { return viewer_problem_step(a, 1); }
static Reaction act_prev_problem(App *a) { return viewer_problem_step(a, -1); }

static Reaction act_measure(App *a) { return viewer_measure_toggle(a); }

static Reaction act_parts(App *a)
{
    a->p.parts = !a->p.parts;
    snprintf(a->note, sizeof a->note, "parts in colours %s", a->p.parts ? "on" : "off");
    return RE_RENDER;
}

/* --diff: both models, A alone, B alone, the heat map, and round again. */
static Reaction act_diff_show(App *a)
{
    static const char *const says[DIFF_SHOW_COUNT] = { "both models", "A alone (red: far from B)",
                                                       "B alone (green: far from A)", "heat map of the distance" };
    if (!a->diff) {
        snprintf(a->note, sizeof a->note, "V shows a diff's models in turn (zview --diff A B)");
        return RE_DRAW;
    }
    int show = (a->diff->show + 1) % DIFF_SHOW_COUNT;
    if (diff_show(a->diff, &a->p, show))
        return RE_RENDER;       /* out of memory: the frame says so */
    a->live.show = show;        /* the view's command line (C) shows it */
    snprintf(a->note, sizeof a->note, "%s", says[show]);
    return RE_RENDER;
}

static Reaction act_sketch(App *a)
{
    return sketch_mode_enter(a);
}

/* The scene edited live (live.c): open, remove, empty. Emptying asks
 * first: it cannot be undone but by opening the files again. */
/* --diff's scene is its two files: nothing joins or leaves it. */
static int diff_fixed(App *a)
{
    if (a->diff)
        snprintf(a->note, sizeof a->note, "--diff: O, X and E are off");
    return a->diff != NULL;
}

static Reaction act_open(App *a)   { return diff_fixed(a) ? RE_DRAW : viewer_open_prompt(a); }
static Reaction act_remove(App *a) { return diff_fixed(a) ? RE_DRAW : viewer_remove_selected(a); }

static Reaction act_clear(App *a)
{
    if (diff_fixed(a))
        return RE_DRAW;
    if (a->s->nobjs == 0)
        return RE_NONE;     /* empty already (a file still loading comes in all the same) */
    a->confirm = 1;
    snprintf(a->note, sizeof a->note, "empty the scene (%d object%s)? y/n", a->s->nobjs,
             a->s->nobjs == 1 ? "" : "s");
    return RE_DRAW;
}

/* The info panel: the numbers of each frame (report.c), as --info prints them. */
static Reaction act_info(App *a)
{
    a->info = !a->info;
    return RE_DRAW;
}

static Reaction act_spin(App *a)
{
    a->spin = !a->spin;
    snprintf(a->note, sizeof a->note, "turntable %s", a->spin ? "on" : "off");
    return RE_DRAW;
}

static Reaction act_help(App *a)
{
    a->help = 1;
    a->help_top = 0;
    return RE_DRAW;
}

static Reaction act_redraw(App *a)
{
    (void)a;
    return RE_CLEAR | RE_DRAW;
}

static Reaction act_quit(App *a)
{
    (void)a;
    return RE_QUIT;
}

/* Esc quits, unless a file is loading: then it cancels that first (a
 * load stuck on a FIFO nobody writes to, or one that is too slow). */
static Reaction act_escape(App *a)
{
    return a->job ? viewer_cancel_load(a) : RE_QUIT;
}

/* ==== Entry points ==== */

const KeyBind *key_find(const KeyRow *rows, int n, int key)
{
    /* a few dozen rows, searched once a key press */
    for (int r = 0; r < n; r++)
        for (const KeyBind *b = rows[r].bind; b < rows[r].bind + KEY_ROW_BINDS && b->key; b++)
            if (b->key == key)
                return b;
    return NULL;
}

const char *key_name(int key, char *buf, size_t len)
{
    static const struct { int key; const char *name; } names[] = {
        { TK_LEFT, "Left" }, { TK_RIGHT, "Right" }, { TK_UP, "Up" }, { TK_DOWN, "Down" },
        { TK_SLEFT, "Shift-Left" }, { TK_SRIGHT, "Shift-Right" }, { TK_SUP, "Shift-Up" }, { TK_SDOWN, "Shift-Down" },
        { TK_BTAB, "Shift-Tab" }, { TK_DEL, "Delete" }, { TK_HOME, "Home" }, { TK_END, "End" },
        { TK_INS, "Insert" }, { TK_PGUP, "Page Up" }, { TK_PGDN, "Page Down" }, { TK_TAB, "Tab" },
        { TK_ENTER, "Enter" }, { TK_BACKSPACE, "Backspace" }, { TK_CTRL_L, "Ctrl-L" }, { TK_ESC, "Esc" },
        { ' ', "Space" },
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (names[i].key == key)
            return names[i].name;
    snprintf(buf, len, "%c", key > ' ' && key < 127 ? key : '?');
    return buf;
}

/* A key while the help is shown: it scrolls the help when the help does
 * not fit (Up/Down a row, Page Up/Down a page, Home/End to either end),
 * else it closes the help and does nothing more (a `q` that closes the
 * help does not also quit). */
static Reaction help_key(App *a, int key)
{
    int page = a->help_page > 1 ? a->help_page - 1 : 1;     /* a row of the last page stays */
    int by = key == TK_UP || key == 'k' ? -1 : key == TK_DOWN || key == 'j' ? 1
           : key == TK_PGUP ? -page : key == TK_PGDN ? page
           : key == TK_HOME ? -a->help_hidden : key == TK_END ? a->help_hidden : 0;
    if (a->help_hidden > 0 && by) {
        a->help_top += by;
        if (a->help_top < 0)
            a->help_top = 0;
        if (a->help_top > a->help_hidden)
            a->help_top = a->help_hidden;
        return RE_DRAW;
    }
    a->help = 0;
    return RE_DRAW;
}

Reaction viewer_key(App *a, int key)
{
    a->note[0] = 0;
    switch (viewer_mode(a)) {
    case VM_PROMPT:
        return viewer_prompt_key(a, key);
    case VM_CONFIRM:
        /* the key that answers does nothing else */
        a->confirm = 0;
        if (key == 'y' || key == 'Y')
            return viewer_clear_scene(a);
        snprintf(a->note, sizeof a->note, "the scene stays");
        return RE_DRAW;
    case VM_HELP:
        return help_key(a, key);
    case VM_COMMAND:
        a->cmd = 0;         /* like the help: the key that closes it does nothing else */
        return RE_DRAW;
    case VM_SKETCH: {
        /* sketch mode's own keys, then the few of the viewer's it shares */
        const KeyBind *b = key_find(sketch_keys, sketch_keys_n, key);
        Reaction r = b && b->act ? b->act(a) : RE_NONE;
        if (r != RE_NONE)
            return r | RE_DRAW;
        if (!b || b->act)
            return RE_NONE;
        break;
    }
    case VM_VIEW:
        if (a->measuring) {     /* the measuring mode's keys first (measureui.c) */
            Reaction r = viewer_measure_key(a, key);
            if (r != RE_NONE)
                return r | RE_DRAW;
        }
        break;
    }
    const KeyBind *b = key_find(viewer_keys, viewer_keys_n, key);
    if (!b)
        return RE_NONE;
    return b->act(a) | RE_DRAW;
}

Reaction viewer_drag(App *a, int button, int dx, int dy)
{
    if (button == 1)
        return turn(a, DRAG_DEG * dx, DRAG_DEG * dy, 0);
    /* a cell is about 1/40 of a typical window: move about that much */
    return move(a, 0.05f * dx, -0.1f * dy);
}

Reaction viewer_wheel(App *a, int dy)
{
    return scale(a, dy < 0 ? SCALE_STEP : 1 / SCALE_STEP);
}

void viewer_spin(App *a, float radians)
{
    Object *o = selected(a);
    float *y = o ? &o->yaw : &a->s->cam.yaw;
    *y = remainderf(*y + radians, 2 * ZV_PI);
}

/* ==== The help overlay ==== */

#define HELP_GAP 3          /* spaces between columns */
#define HELP_MAX_COLUMNS 3

/* Row r of the layout: ncols entries side by side (column-major), or in
 * the stacked form (ncols 0) the keys on even rows, the meaning below. */
static void help_row(const KeyRow *help, int n, char *out, int r, int nrows, int ncols, int kw, int ew)
{
    if (ncols == 0) {
        const KeyRow *e = &help[r / 2];
        snprintf(out, HELP_LINE_MAX, r % 2 ? "  %s" : "%s", r % 2 ? e->what : e->keys);
        return;
    }
    int len = 0;
    out[0] = 0;
    for (int c = 0; c < ncols; c++) {
        int k = c * nrows + r;
        if (k >= n)
            break;
        len += snprintf(out + len, (size_t)(HELP_LINE_MAX - len), "%*s%-*s  %-*s", c ? HELP_GAP : 0, "",
                        kw, help[k].keys, ew - kw - 2, help[k].what);
        if (len >= HELP_LINE_MAX)
            break;
    }
    while (len > 0 && out[len - 1] == ' ')
        out[--len] = 0;
}

int viewer_help_layout(App *a, int cols, int rows, const char **lines)
{
    /* sketch mode has keys of its own */
    const KeyRow *help = a->sk.on ? sketch_keys : viewer_keys;
    const int nhelp = a->sk.on ? sketch_keys_n : viewer_keys_n;
    int kw = 0, dw = 0;
    for (int k = 0; k < nhelp; k++) {
        int n = (int)strlen(help[k].keys), m = (int)strlen(help[k].what);
        kw = n > kw ? n : kw;
        dw = m > dw ? m : dw;
    }
    int ew = kw + 2 + dw;
    int inner = cols - 4;               /* the box's frame and margins */
    int avail = rows - 1 - 2 - 1;       /* less the status bar, the frame, the title */
    if (avail > HELP_LINES_MAX - 1)
        avail = HELP_LINES_MAX - 1;
    /* as few columns as show everything, else as many as fit across */
    int ncols = 0, nrows = 2 * nhelp;
    for (int c = 1; c <= HELP_MAX_COLUMNS && c * ew + (c - 1) * HELP_GAP <= inner; c++) {
        ncols = c;
        nrows = (nhelp + c - 1) / c;
        if (nrows <= avail)
            break;
    }
    int shown = nrows < avail ? nrows : avail > 0 ? avail : 0;
    a->help_hidden = nrows - shown;
    a->help_page = shown;
    if (a->help_top > a->help_hidden)
        a->help_top = a->help_hidden;
    if (a->help_top < 0)
        a->help_top = 0;
    const char *title = a->sk.on ? "zview sketch keys (any key closes this)" : "zview keys (any key closes this)";
    char more[HELP_LINE_MAX];
    if (a->help_hidden) {
        snprintf(more, sizeof more, "zview keys %d-%d of %d: Up/Down scroll, other keys close",
                 a->help_top + 1, a->help_top + shown, nrows);
        title = (int)strlen(more) <= inner ? more : inner >= 18 ? "Up/Down: more keys" : "Up/Down: more";
    }
    snprintf(a->help_text[0], HELP_LINE_MAX, "%s", title);
    lines[0] = a->help_text[0];
    for (int i = 0; i < shown; i++) {
        help_row(help, nhelp, a->help_text[1 + i], a->help_top + i, nrows, ncols, kw, ew);
        lines[1 + i] = a->help_text[1 + i];
    }
    return 1 + shown;
}

/* The key table, which is also the ? help, a row a line. */
const KeyRow viewer_keys[] = {
    { "arrows h j k l", "turn (yaw, pitch)",
      { { TK_LEFT, act_yaw_left }, { 'h', act_yaw_left }, { TK_RIGHT, act_yaw_right }, { 'l', act_yaw_right },
        { TK_UP, act_pitch_up }, { 'k', act_pitch_up }, { TK_DOWN, act_pitch_down }, { 'j', act_pitch_down } } },
    { "u o", "roll", { { 'u', act_roll_left }, { 'o', act_roll_right } } },
    { "I J K L", "turn 15 degrees",
      { { 'J', act_big_left }, { 'L', act_big_right }, { 'I', act_big_up }, { 'K', act_big_down } } },
    { "Shift-arrows", "turn 15 degrees",
      { { TK_SLEFT, act_big_left }, { TK_SRIGHT, act_big_right }, { TK_SUP, act_big_up }, { TK_SDOWN, act_big_down } } },
    { "w a s d", "move",
      { { 'a', act_move_left }, { 'd', act_move_right }, { 'w', act_move_up }, { 's', act_move_down } } },
    { "+ = z - _ c wheel", "scale",
      { { '+', act_bigger }, { '=', act_bigger }, { 'z', act_bigger },
        { '-', act_smaller }, { '_', act_smaller }, { 'c', act_smaller } } },
    { "f", "fit to view", { { 'f', act_fit } } },
    { "r x", "back to the opening view", { { 'r', act_reset }, { 'x', act_reset } } },
    { "Tab n", "next object", { { TK_TAB, act_next_object }, { 'n', act_next_object } } },
    { "shift-Tab", "previous object", { { TK_BTAB, act_prev_object } } },
    { "N 0", "whole scene", { { 'N', act_whole_scene }, { '0', act_whole_scene } } },
    { "g G", "next / previous algorithm", { { 'g', act_next_algo }, { 'G', act_prev_algo } } },
    { "1 2 3 4", "view front back left right",
      { { '1', act_view1 }, { '2', act_view2 }, { '3', act_view3 }, { '4', act_view4 } } },
    { "5 6 7", "view top bottom iso", { { '5', act_view5 }, { '6', act_view6 }, { '7', act_view7 } } },
    { "8", "automatic view", { { '8', act_view_auto } } },
    { "m", "display mode", { { 'm', act_mode } } },
    { "v", "shading", { { 'v', act_shade } } },
    { "e", "outlines (edges)", { { 'e', act_edges } } },
    { "t", "textures on / off", { { 't', act_textures } } },
    { "S", "samples 1 4 9 16", { { 'S', act_samples } } },
    { "[ ] { }", "light left right up down",
      { { '[', act_light_left }, { ']', act_light_right }, { '{', act_light_up }, { '}', act_light_down } } },
    { "p", "ortho / perspective", { { 'p', act_persp } } },
    { "b", "back-face culling", { { 'b', act_cull } } },
    { "U", "up axis (y z x -y -z -x)", { { 'U', act_up } } },
    { "< >", "point size", { { '<', act_point_smaller }, { '>', act_point_bigger } } },
    { "( )", "line width", { { '(', act_line_thinner }, { ')', act_line_wider } } },
    { "W ! @", "wireframe, problems, parts",
      { { 'W', act_wireframe }, { '!', act_problems }, { '@', act_parts } } },
    { ". ,", "next / previous problem", { { '.', act_next_problem }, { ',', act_prev_problem } } },
    { "/ ; ' \\ |", "cut: on, slide, turn, next",
      { { '/', act_cut }, { ';', act_cut_back }, { '\'', act_cut_on }, { '\\', act_cut_turn }, { '|', act_cut_next } } },
    { "V", "diff: A, B, heat map, both", { { 'V', act_diff_show } } },
    { "M", "measure: arrows click Enter", { { 'M', act_measure } } },
    { "S (in M)", "snap to edge mids, centres", { { 0, NULL } } },
    { "space", "auto-rotate", { { ' ', act_spin } } },
    { "O", "open a file (Tab completes)", { { 'O', act_open } } },
    { "X Delete", "remove the selected object", { { 'X', act_remove }, { TK_DEL, act_remove } } },
    { "E", "empty the scene (asks y/n)", { { 'E', act_clear } } },
    { "i", "info panel: times, counts", { { 'i', act_info } } },
    { "C", "command line of the view", { { 'C', act_command } } },
    { "P", "snapshot: PNG and text", { { 'P', act_snapshot } } },
    { "D", "sketch: draw polygons", { { 'D', act_sketch } } },
    { "?", "this help", { { '?', act_help } } },
    { "Ctrl-L", "redraw", { { TK_CTRL_L, act_redraw } } },
    { "q Esc", "quit (Esc: stop a load)", { { 'q', act_quit }, { TK_ESC, act_escape } } },
    { "left drag", "turn (in M: the cursor)", { { 0, NULL } } },
    { "right drag", "move", { { 0, NULL } } },
};
const int viewer_keys_n = (int)(sizeof viewer_keys / sizeof viewer_keys[0]);
