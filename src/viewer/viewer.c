/* viewer.c: the interactive viewer. kilo's loop: draw what changed, wait
 * for input, read every pending event before the next frame (held-down
 * keys coalesce, the view never lags), repeat. Frames are rendered only
 * when something changed, or on the auto-rotate clock (--fps). Its
 * set-up and render are benchtty.c's too. */

#define _DEFAULT_SOURCE         /* lstat on glibc */

#include <errno.h>
#include <langinfo.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "safetext.h"
#include "tty.h"
#include "viewer_app.h"

#define MIN_COLS 16
#define MIN_ROWS 4
#define SPIN_DEG_PER_S 40.0f
#define INFO_BOX 104        /* the info panel's box is at most this wide */
#define INFO_BESIDE_MIN (INFO_BOX + 60)     /* ... and sits beside a picture this much wider */
#define BUSY_TICK_MS 100    /* a background load's progress, and a frame to see whether
                               hzb-octree's trees are ready, this often */

/* ==== Set-up ==== */

static int locale_utf8(void)
{
    const char *cs = nl_langinfo(CODESET);
    return cs && (!strcmp(cs, "UTF-8") || !strcmp(cs, "utf-8") || !strcmp(cs, "UTF8"));
}

int viewer_app_init(App *a, const Options *o, Scene *s, int loading)
{
    memset(a, 0, sizeof *a);
    sketch_init(&a->sk.k);
    a->opt = o;
    a->s = s;
    a->opening = s->cam;        /* what r goes back to */
    a->sel = -1;
    a->cull = o->cull;
    a->utf8 = locale_utf8();
    a->mode = o->mode >= 0 ? (DisplayMode)o->mode : mode_from_locale();
    /* pixels when still: asked for, or (no --mode) where the terminal
     * has them; --mode half and its kind mean cells */
    a->pixels = o->pixels > PIX_CELLS || (o->pixels < 0 && o->mode < 0);
    const HsrAlgo *algo = hsr_find(o->algo ? o->algo : "zbuffer");
    if (!algo)
        algo = hsr_algos[0];
    for (int i = 0; i < hsr_nalgos; i++)
        if (hsr_algos[i] == algo)
            a->algo = i;
    if (viewer_live_init(a, o))
        goto fail;
    viewer_update_name(a);
    /* a lenient load's warnings went to stderr, which the screen is
     * about to cover: the first file's that had any shows in the bar */
    for (int i = 0; i < s->nmeshes; i++)
        if (s->meshes[i].info.warnings) {
            viewer_warning_note(a, &s->meshes[i].info, s->meshes[i].path ? s->meshes[i].path : "?");
            break;
        }
    if (pipeline_init(&a->p, s, algo, o->threads))
        goto fail;
    a->p.samples = TEXT_SAMPLES;
    pipeline_apply_options(&a->p, o);
    /* images the load left for later (tex_defer): on their own thread */
    a->tex = texjob_start(s, a->opt);
    a->pic_cols = o->w;     /* --size fixes the picture (0: the window's size) */
    a->pic_rows = o->h;
    a->reload = -1;
    a->focus = -1;
    a->focus_want = o->problem > 0 ? o->problem - 1 : -1;
    char err[160];
    a->first_cam = s->cam;
    if (loading && !(a->first = firstload_start(o, err, sizeof err)))
        goto fail;              /* (out of memory, or of threads: the caller says so) */
    if (o->watch && !(a->watch = watch_start(err, sizeof err)))
        viewer_note(a, "%s", err);
    return 0;
fail:
    viewer_app_free(a);         /* what was made so far; the rest is zero */
    return -1;
}

void viewer_app_free(App *a)
{
    pipeline_free(&a->p);       /* its runner first: it may read the sketch's scene */
    meshcheck_items_free(&a->items);
    sketch_mode_free(a);
    viewer_live_free(a);
}

/* ==== One frame ==== */

/* Render the picture for cols x rows cells: the same call --print makes,
 * so the same view gives the same cells. */
int viewer_render(App *a, int cols, int rows)
{
    int pw, ph;
    mode_cell_pixels(a->mode, &pw, &ph);
    if (a->sk.on && sketch_mode_frame(a, cols * pw, rows * ph, mode_pixel_aspect(a->mode)))
        return -1;
    a->p.highlight = a->s->nobjs > 1 ? a->sel : -1;      /* the selection shows in the picture */
    if (pipeline_render(&a->p, cols * pw, rows * ph, mode_pixel_aspect(a->mode), a->cull, 1))
        return -1;
    /* as --print says on stderr, the bar says why nothing shows (sketch
     * mode's bar has its own words for an empty canvas) */
    a->empty_why = a->sk.on ? NULL
                 : a->s->nobjs == 0 ? "empty scene: O opens a file" : frame_empty_reason(&a->p);
    double t0 = now_ms();
    int rc = cells_from_image_on(&a->p.img, a->mode, term_colour(), &a->p.bd, &a->p.cells);
    a->p.cells_ms = now_ms() - t0;
    if (rc)
        return -1;
    if (a->sk.on)
        sketch_mode_marks(a, &a->p.cells);
    return 0;
}

/* ==== The view's command line ==== */

ViewSettings viewer_view_settings(const App *a)
{
    ViewSettings v = {
        .mode = a->mode,
        .shade = a->p.shade,
        .crease = a->p.crease,
        .cull = a->cull,
        .samples = a->p.samples,
        .algo = a->p.algo->name,
        .edges = a->p.edges,
        .wireframe = a->p.wireframe,
        .point_size = a->p.point_size,
        .line_width = a->p.line_width,
        .no_textures = a->p.no_textures,
        .problems = a->p.problems,
        .parts = a->p.parts,
        .overhang = a->p.overhang,
        .overhang_deg = a->p.overhang_deg,
        .thickness = a->p.thickness,
        .marks = &a->p.marks,
        .planes = a->p.planes,
        .nplanes = a->p.cut_off ? 0 : a->p.nplanes,
    };
    return v;
}

int viewer_view_command(const App *a, char *buf, size_t len)
{
    ViewSettings v = viewer_view_settings(a);
    if (a->sk.on) {
        /* the drawing as written: the file opens with this very view */
        const char *file = sketch_mode_file(a);
        if (!file)
            return -1;
        Options o;
        cli_defaults(&o);
        o.files[0] = file;
        o.nfiles = 1;
        return view_command(buf, len, &o, a->s, &v);
    }
    return view_command(buf, len, a->opt, a->s, &v);
}

int viewer_command_layout(const App *a, int cols, char *buf, size_t len, const char **lines, int max)
{
    char cmd[CMD_MAX];
    if (max < 2 || viewer_view_command(a, cmd, sizeof cmd)) {
        snprintf(buf, len, a->sk.on && !sketch_mode_file(a) ? "write the sketch first (w): the command line opens the file"
                                                             : "the command line is too long to show");
        lines[0] = buf;
        return 1;
    }
    int w = cols - 4 > 16 ? cols - 4 : 16;     /* the box's frame and margins */
    size_t o = 0;
    int n = 0;
    int k = snprintf(buf, len, "command line of this view (any key closes)");
    lines[n++] = buf;
    o = (size_t)k + 1;
    /* whole words while they fit, " \\" where the command goes on (a
     * word longer than a line is cut: rare, a long path) */
    const char *p = cmd;
    while (*p && n < max && o + (size_t)w + 3 < len) {
        int room = w - 2, take = (int)strlen(p);
        if (take > w) {
            take = room;
            for (int i = room; i > 0; i--)
                if (p[i] == ' ') {
                    take = i;
                    break;
                }
        }
        int more = p[take] != 0;
        k = snprintf(buf + o, len - o, "%.*s%s", take, p, more ? " \\" : "");
        lines[n++] = buf + o;
        o += (size_t)k + 1;
        p += take;
        while (*p == ' ')
            p++;
    }
    return n;
}


const char *viewer_prompt_scroll(const char *bar, int cols, int *cursor)
{
    int at = *cursor;
    const char *show = bar;
    while (at > cols - 2 && *show) {
        char piece[SAFETEXT_PIECE];
        size_t took = safetext_next(show, piece, SAFETEXT_TEXT);
        at -= vt_text_cols(show, took);                      /* drop a character from the left */
        show += took;
    }
    *cursor = at;
    return show;
}

/* The prompt in the status line: its label and line, scrolled so that
 * the cursor shows, the cursor out of reverse video. A name completed
 * from the folder may hold controls: they show as vt_text shows them
 * (\x1b), and the columns are counted the same way. */
static void draw_prompt(const Prompt *pr, int row, int cols)
{
    char bar[PROMPT_MAX + 64];
    snprintf(bar, sizeof bar, " %s%s", pr->label, pr->buf);
    size_t head = 1 + strlen(pr->label);
    int at = vt_text_cols(bar, head + (size_t)pr->cur);      /* the cursor's column */
    const char *show = viewer_prompt_scroll(bar, cols, &at);
    term_draw_bar(row, show);
    term_bar_cursor(row, at);
}

/* A second Tab's candidates in columns in a box above the status line. */
static void draw_candidates(App *a, int cols, int rows)
{
    const Prompt *pr = &a->prompt;
    const char *names[256];
    int n = 0, wide = 0;
    char copy[PROMPT_LIST];
    snprintf(copy, sizeof copy, "%s", pr->list);
    for (char *s = copy, *e; s && *s && n < 256; s = e) {
        e = strchr(s, '\n');
        if (e)
            *e++ = 0;
        names[n++] = s;
        int l = (int)strlen(s);
        wide = l > wide ? l : wide;
    }
    if (n == 0)
        return;
    int inner = cols - 4 > 8 ? cols - 4 : 8, colw = wide + 2;
    int per = inner / colw > 0 ? inner / colw : 1;
    int nrows = (n + per - 1) / per, maxrows = rows / 2 - 3 > 1 ? rows / 2 - 3 : 1;
    if (nrows > maxrows)
        nrows = maxrows;
    const char *lines[HELP_LINES_MAX];
    int nl = 0;
    snprintf(a->help_text[0], HELP_LINE_MAX, "%d match%s%s", pr->nlist, pr->nlist == 1 ? "" : "es",
             nrows * per < pr->nlist ? " (the first shown)" : "");
    lines[nl++] = a->help_text[0];
    for (int r = 0; r < nrows && nl < HELP_LINES_MAX; r++, nl++) {
        char *t = a->help_text[nl];
        int len = 0;
        t[0] = 0;
        for (int c = 0; c < per; c++) {
            int k = r * per + c;        /* row-major: names read across, as ls -x */
            if (k >= n)
                break;
            len += snprintf(t + len, (size_t)(HELP_LINE_MAX - len), "%-*s", c + 1 < per ? colw : 0, names[k]);
            if (len >= HELP_LINE_MAX)
                break;
        }
        lines[nl] = t;
    }
    term_draw_box_at(lines, nl, 0, -1);
}

/* The info panel: the frame's numbers (report.c, as --info prints them)
 * in a box at the top right (over the picture, or beside it in a window
 * of INFO_BESIDE_MIN columns), each line wrapped after a comma to fit. */
static void draw_info(App *a, int cols, int rows, double out_ms)
{
    ReportLine rl[REPORT_LINES + 8];
    int n = frame_report(&a->p, out_ms, rl, REPORT_LINES);
    n += viewer_check_report(a, rl + n, 5);
    /* the colours, and what decided them (the terminal may draw more than
     * its environment says: COLORTERM does not cross ssh) */
    rl[n].label = "colours:";
    snprintf(rl[n].text, REPORT_TEXT, "%s (%s)", colour_name(term_colour()),
             a->opt->colour >= 0 ? "--color" : term_colour_answered() ? "the terminal answered"
             : term_colour() < colour_from_env() ? "TERM's description" : colour_env_reason());
    n++;
    /* the start's questions: at once, one wait (a silent terminal costs
     * TERM_ASK_MS once) */
    double waited;
    int said = term_answered(&waited);
    if (said >= 0) {
        rl[n].label = "asked:";
        snprintf(rl[n].text, REPORT_TEXT, said ? "once at start: answered in %.0f ms"
                                               : "once at start: no answer in %.0f ms (a late one still counts)",
                 waited);
        n++;
    }
    if (term_pixels() == PIX_CELLS && term_mux_hint(0)) {
        rl[n].label = "pixels:";
        snprintf(rl[n].text, REPORT_TEXT, "cells (%s)", term_mux_hint(0));
        n++;
    } else if (term_pixels() != PIX_CELLS) {
        rl[n].label = "pixels:";
        if (a->pix_bytes)
            snprintf(rl[n].text, REPORT_TEXT, "%s when still, last image %zu KB%s", pixel_proto_names[term_pixels()],
                     a->pix_bytes / 1000, a->pix_shrink > 1 ? " (fewer pixels, scaled)" : "");
        else
            snprintf(rl[n].text, REPORT_TEXT, "%s when still%s", pixel_proto_names[term_pixels()],
                     a->pixels ? "" : " (off: m)");
        n++;
    }
    int inner = cols - 4 < INFO_BOX - 4 ? cols - 4 : INFO_BOX - 4;    /* the box's frame and margins */
    if (inner < 20)
        return;
    const char *lines[HELP_LINES_MAX];
    int nl = 0, maxl = rows - 3 < HELP_LINES_MAX ? rows - 3 : HELP_LINES_MAX;
    snprintf(a->help_text[nl], HELP_LINE_MAX, "frame info (i closes)");
    lines[nl] = a->help_text[nl];
    nl++;
    for (int i = 0; i < n && nl < maxl; i++) {
        const char *t = rl[i].text;
        int first = 1;
        while (*t && nl < maxl) {
            /* as much as fits, broken after a comma when it must be */
            int room = inner - 12, len = (int)strlen(t), take = len;
            if (len > room) {
                take = room;
                for (int k = room; k > 0; k--)
                    if (t[k - 1] == ',') {
                        take = k;
                        break;
                    }
            }
            snprintf(a->help_text[nl], HELP_LINE_MAX, "%-12s%.*s", first ? rl[i].label : "", take, t);
            lines[nl] = a->help_text[nl];
            nl++;
            t += take;
            while (*t == ' ')
                t++;
            first = 0;
        }
    }
    term_draw_box_at(lines, nl, -1, 0);
}

typedef struct {
    int    cols, rows;      /* window size last drawn (0 = none yet) */
    int    small;           /* last draw was the too-small message */
    int    help;            /* last draw showed the help */
    int    pic_cols;        /* the picture's width last drawn */
    int    pic_rows;        /* ... and height */
    double out_ms;          /* last curses output time */
    double frame_ms;        /* last rendered frame, render + output */
    double pix_due;         /* when the model has been still long enough for pixels (0: not due) */
} DrawState;

/* Cells while the model moves, the terminal's pixels once it has been
 * still this long: a full-resolution image costs tens of kilobytes to
 * hundreds, too much for every frame of a turn over SSH. */
#define PIX_STILL_MS 180

/* Why the loop ended (and what draw() can fail with). */
enum { RUN_QUIT = 0, RUN_NO_MEMORY = -1, RUN_INPUT_ENDED = 1, RUN_OUTPUT_FAILED = 2 };

/* What the mode on top draws over the picture: the prompt's candidates,
 * or a box (help, the command line). */
static void draw_overlay(App *a, ViewerMode m, int cols, int rows)
{
    const char *lines[HELP_LINES_MAX];
    char buf[2 * CMD_MAX];
    switch (m) {
    case VM_PROMPT:
        if (a->prompt.list[0])
            draw_candidates(a, cols, rows);
        break;
    case VM_HELP:
        term_draw_box(lines, viewer_help_layout(a, cols, rows, lines));
        break;
    case VM_COMMAND:
        term_draw_box(lines, viewer_command_layout(a, cols, buf, sizeof buf, lines,
                                                rows - 3 < HELP_LINES_MAX ? rows - 3 : HELP_LINES_MAX));
        break;
    default:
        break;
    }
}

/* Draw the screen; render first when asked or when the size changed.
 * Returns 0, RUN_NO_MEMORY, or RUN_OUTPUT_FAILED (errno says why). */
static int draw(App *a, DrawState *d, Reaction what, int fps_cap)
{
    int cols, rows;
    term_size(&cols, &rows);
    int full = (what & RE_CLEAR) != 0;
    if (cols < MIN_COLS || rows < MIN_ROWS) {
        term_message("too small");
        d->small = 1;
        return term_update(full) ? RUN_OUTPUT_FAILED : 0;
    }
    if (d->small || cols != d->cols || rows != d->rows) {
        term_erase();
        what |= RE_RENDER;
        d->small = 0;
        d->cols = cols;
        d->rows = rows;
    }
    ViewerMode m = viewer_mode(a);
    int over = viewer_mode_boxed(m) || m == VM_PROMPT || a->info;     /* drawn past the picture */
    /* a new picture, or anything over it: the cells again */
    if ((what & RE_RENDER) == RE_RENDER || over || a->sk.on)
        term_hide_image();
    if (d->help && !over)
        term_erase();       /* the box may reach past a --size picture */
    d->help = over;
    /* --size: that many cells, or fewer when the window is smaller */
    int pc = a->pic_cols > 0 && a->pic_cols < cols ? a->pic_cols : cols;
    int pr = a->pic_rows > 0 && a->pic_rows < rows - 1 ? a->pic_rows : rows - 1;
    /* a wide window keeps the info panel beside the picture, not over it */
    if (a->info && !viewer_mode_boxed(m) && cols >= INFO_BESIDE_MIN && pc > cols - INFO_BOX)
        pc = cols - INFO_BOX;
    if (pc != d->pic_cols) {
        if (d->pic_cols)
            term_erase();
        what |= RE_RENDER;
        d->pic_cols = pc;
    }
    double t0 = now_ms();
    if ((what & RE_RENDER) == RE_RENDER && viewer_render(a, pc, pr))
        return RUN_NO_MEMORY;
    term_draw_cells(&a->p.cells, 0);
    double t1 = now_ms();
    if ((what & RE_RENDER) == RE_RENDER)
        d->frame_ms = (t1 - t0) + d->out_ms;
    char bar[512];
    if (m == VM_PROMPT) {
        draw_prompt(&a->prompt, rows - 1, cols);
    } else {
        viewer_status_text(a, bar, sizeof bar, d->frame_ms, fps_cap, cols);
        term_draw_bar(rows - 1, bar);
    }
    if (a->info && !viewer_mode_boxed(m))
        draw_info(a, cols, rows, a->p.cells_ms + d->out_ms);
    draw_overlay(a, m, cols, rows);
    if (term_update(full))
        return RUN_OUTPUT_FAILED;
    if ((what & RE_RENDER) == RE_RENDER) {
        d->out_ms = now_ms() - t1;
        d->pic_rows = pr;
        d->pix_due = term_pixels() != PIX_CELLS && a->pixels ? now_ms() + PIX_STILL_MS : 0;
    }
    return 0;
}

/* The still picture in the terminal's pixels, over the cells: the same
 * view at the cells' size in pixels, on the background, painted. Not
 * over a box, the info panel, sketch mode or a turning model. Within the
 * link's budget (--max-rate for PIXELS_BUDGET_S): kitty and iTerm2
 * images are rendered at a half, then a quarter of the pixels and
 * scaled by the terminal to the same cells; a sixel image over it is
 * not sent (the cells stay, and the note says why). */
static int draw_pixels(App *a, DrawState *d, int fps_cap)
{
    if (viewer_mode(a) != VM_VIEW || a->info || a->spin || a->sk.on || !d->pic_cols || !d->pic_rows ||
        term_image_shown())
        return 0;
    int cw = PIXELS_CELL_W, ch = PIXELS_CELL_H;
    term_cell_pixels(&cw, &ch);
    PixelProto px = term_pixels();
    double budget = (a->opt->max_rate > 0 ? a->opt->max_rate : PIXELS_RATE_DEFAULT) * 1000.0 * PIXELS_BUDGET_S;
    a->p.highlight = a->s->nobjs > 1 ? a->sel : -1;
    ByteBuf b = { 0 };
    for (int shrink = 1; shrink <= 4; shrink *= 2) {
        int w = d->pic_cols * cw / shrink, h = d->pic_rows * ch / shrink;
        if (w < 1 || h < 1 || pipeline_render(&a->p, w, h, 1.0f, a->cull, 1)) {
            bytebuf_free(&b);
            return RUN_NO_MEMORY;
        }
        if (a->p.has_bd)
            backdrop_paint(&a->p.img, &a->p.bd);
        b.len = 0;
        if (pixels_encode(px, &a->p.img, 1, d->pic_cols, d->pic_rows, &b)) {
            bytebuf_free(&b);
            return RUN_NO_MEMORY;
        }
        a->pix_bytes = b.len;
        a->pix_shrink = shrink;
        if ((double)b.len <= budget)
            break;
        if (px == PIX_SIXEL || shrink == 4) {
            snprintf(a->note, sizeof a->note, "%s still image %zu KB: over --max-rate's budget, cells kept",
                     pixel_proto_names[px], b.len / 1000);
            bytebuf_free(&b);
            return 0;
        }
    }
    int rc = term_show_image(&b) ? RUN_OUTPUT_FAILED : 0;
    bytebuf_free(&b);
    /* the status bar again: it now names the image's colours and size */
    if (!rc) {
        int cols, rows;
        term_size(&cols, &rows);
        char bar[512];
        viewer_status_text(a, bar, sizeof bar, d->frame_ms, fps_cap, cols);
        term_draw_bar(rows - 1, bar);
        rc = term_update(0) ? RUN_OUTPUT_FAILED : 0;
    }
    return rc;
}

static Reaction dispatch(App *a, const TermEvent *ev)
{
    switch (ev->type) {
    case TE_KEY:    return viewer_key(a, ev->key);
    case TE_RESIZE: return RE_RENDER;
    /* the pointer turns and moves the model under any box, but not under
     * sketch mode, whose canvas stays put; a click draws only when sketch
     * mode is on top */
    case TE_DRAG:
        /* the measuring mode's left drag moves its cursor, not the model */
        if (viewer_mode(a) == VM_VIEW && a->measuring && ev->button == 1)
            return viewer_measure_mouse(a, ev->x, ev->y, ev->mods, 1);
        return a->sk.on ? RE_NONE : viewer_drag(a, ev->button, ev->dx, ev->dy);
    case TE_WHEEL:  return a->sk.on ? RE_NONE : viewer_wheel(a, ev->dy);
    case TE_CLICK:
        if (viewer_mode(a) == VM_VIEW && a->measuring && ev->button == 1)
            return viewer_measure_mouse(a, ev->x, ev->y, ev->mods, 0);
        return viewer_mode(a) == VM_SKETCH ? sketch_mode_click(a, ev->button, ev->x, ev->y) : RE_NONE;
    case TE_READY:  return RE_NONE;     /* the loop sends what waits */
    }
    return RE_NONE;
}

/* ==== The loop ==== */

static int run(App *a, int fps)
{
    DrawState d = { 0 };
    Reaction todo = RE_RENDER;
    double period = 1000.0 / (fps > 0 ? fps : 30);
    double next = 0, last_spin = 0, tick = 0;
    for (;;) {
        /* a frame goes only when the last one is through: on a slow
         * link frames are dropped (the newest state drawn when the line
         * is free), never queued */
        if (todo & RE_DRAW && term_ready()) {
            int rc = draw(a, &d, todo, fps);
            if (rc)
                return rc;
            todo = RE_NONE;
        }
        if (!todo && d.pix_due > 0 && now_ms() >= d.pix_due && term_ready()) {
            d.pix_due = 0;
            int rc = draw_pixels(a, &d, fps);
            if (rc)
                return rc;
        }
        int timeout = -1;
        if (a->spin) {
            double now = now_ms();
            timeout = next > now ? (int)(next - now + 0.999) : 0;
        }
        if (todo & RE_DRAW) {
            int pace = term_pace_ms();
            if (timeout < 0 || pace < timeout)
                timeout = pace;
        }
        /* through tmux: asked now and then whether the pane moved or
         * shows again (another window was current) */
        int pane = a->pixels && !a->spin && !todo ? term_pane_poll_ms() : -1;
        if (pane >= 0 && (timeout < 0 || pane < timeout))
            timeout = pane;
        if (d.pix_due > 0) {
            double now = now_ms();
            int t = d.pix_due > now ? (int)(d.pix_due - now + 0.999) : 0;
            if (timeout < 0 || t < timeout)
                timeout = t;
        }
        /* work in the background: wake up to show how it goes */
        int busy = a->job != NULL || a->first != NULL || a->tex != NULL || a->p.st.building || a->chk != NULL ||
                   a->watch != NULL;
        if (busy) {
            double now = now_ms();
            int t = tick > now ? (int)(tick - now + 0.999) : 0;
            if (timeout < 0 || t < timeout)
                timeout = t;
        }
        TermEvent ev;
        int got = term_read(&ev, timeout);
        if (got > 0) {
            int was_spinning = a->spin;
            /* take everything already typed before drawing again */
            do
                todo |= dispatch(a, &ev);
            while (!(todo & RE_QUIT) && (got = term_read(&ev, 0)) > 0);
            if (todo & RE_QUIT)
                return RUN_QUIT;
            if (a->spin && !was_spinning)
                next = last_spin = now_ms();
        }
        if (got < 0)
            return RUN_INPUT_ENDED;     /* no key will come: waiting would spin */
        if (a->pixels && !a->spin && !todo && term_pane_moved()) {
            term_hide_image();
            todo |= RE_RENDER;          /* the cells again, then the image where the pane is now */
        }
        if (!a->first)
            todo |= viewer_check_poll(a);  /* a key asked for the check, or it is done */
        if (busy && now_ms() >= tick) {
            /* a finished load joins the scene here, on this thread */
            todo |= viewer_load_poll(a) | viewer_watch_poll(a) | viewer_first_poll(a);
            if (todo & RE_QUIT)
                return RUN_QUIT;    /* the first file failed to load */
            if (a->chk)
                todo |= RE_DRAW;    /* the check's time in the status line */
            /* a big texture decoded: in place between frames, then drawn */
            if (a->tex && !a->sk.on && texjob_poll(&a->tex, a->s, a->note, sizeof a->note))
                todo |= RE_RENDER;
            else if (a->tex)
                todo |= RE_DRAW;    /* its progress in the status line */
            if (a->p.st.building)
                todo |= RE_RENDER;
            tick = now_ms() + BUSY_TICK_MS;
        }
        if (a->spin) {
            double now = now_ms();
            if (now >= next) {
                /* by elapsed time: the turn keeps its speed when frames are slow */
                viewer_spin(a, deg2rad(SPIN_DEG_PER_S) * (float)((now - last_spin) / 1000.0));
                last_spin = now;
                next = next + period > now ? next + period : now + period;
                todo |= RE_RENDER;
            }
        }
    }
}

/* Where keys come from: standard input when it is a terminal, else the
 * controlling terminal (`echo | zview m.obj`, `zview m.obj < /dev/null`),
 * whose end of file would otherwise read as a key that never comes.
 * NULL when there is none; *name says which for messages. */
static FILE *open_keys(FILE **opened, const char **name)
{
    *opened = NULL;
    *name = "standard input";
    if (isatty(STDIN_FILENO))
        return stdin;
    *name = "/dev/tty";
    *opened = fopen("/dev/tty", "re");
    return *opened;
}

/* No viewer after all: one frame as --print gives, or, when the view's
 * command line was wanted on standard output, an error rather than a
 * frame in its place. */
static int no_viewer(const Options *o, Scene *s, int loading, DiffSet *diff)
{
    if (diff)
        return oneshot_diff(o, diff);
    if (loading && firstload_now(o, s))
        return 1;
    if (o->sketch) {
        safetext_line(stderr, "zview: --sketch: no terminal to draw on");
        return 1;
    }
    if (o->print_view) {
        safetext_line(stderr, "zview: --print-view: no terminal to show the viewer on");
        return 1;
    }
    return oneshot_run(o, s);
}

/* The view's command line on standard output (--print-view); 0, or -1
 * with the error said. */
static int print_line(const char *line)
{
    Out out;
    out_init(&out, stdout, "standard output");
    out_printf(&out, "%s\n", line);
    if (out_flush(&out)) {
        safetext_line(stderr, "zview: standard output: %s", out_error(&out));
        return -1;
    }
    return 0;
}

static int viewer_main(const Options *o, Scene *s, int loading, DiffSet *diff);

int viewer_run(const Options *o, Scene *s)
{
    return viewer_main(o, s, 0, NULL);
}

int viewer_run_loading(const Options *o, Scene *s)
{
    return viewer_main(o, s, 1, NULL);
}

int viewer_run_diff(const Options *o, DiffSet *ds)
{
    int rc = viewer_main(o, &ds->scene, 0, ds);
    return rc ? rc : diff_differ(&ds->d) ? 3 : 0;
}

static int viewer_main(const Options *o, Scene *s, int loading, DiffSet *diff)
{
    const char *t = getenv("TERM");
    if (!t || !*t || !strcmp(t, "dumb")) {
        /* a terminal that cannot move its cursor (an editor's shell, a
         * CI log): say so, and what shows a picture there */
        safetext_line(stderr, "zview: TERM=%s cannot show the viewer (it needs a terminal that moves its "
                        "cursor: set TERM, e.g. TERM=xterm-256color)%s",
                t ? t : "", o->print_view || o->sketch ? "" : "; one frame instead, as --print gives");
        return no_viewer(o, s, loading, diff);
    }
    /* what is made below is unmade in one place, at the end */
    App a;
    int made = 0, fallback = 0, rc = 1;
    FILE *tty = NULL, *screen_tty = NULL;
    const char *keys_name;
    FILE *keys = open_keys(&tty, &keys_name);
    if (!keys) {
        safetext_line(stderr, "zview: no terminal to read keys from (standard input is not one, "
                        "/dev/tty: %s)%s", strerror(errno), o->print_view ? "" : ": one frame instead");
        fallback = 1;
        goto done;
    }
    /* the screen: standard output, or the terminal when --print-view
     * keeps standard output for the command line */
    FILE *screen = stdout;
    if (!isatty(STDOUT_FILENO) && !(screen = screen_tty = fopen("/dev/tty", "we"))) {
        fallback = 1;
        goto done;
    }
    if (viewer_app_init(&a, o, s, loading)) {
        safetext_line(stderr, "zview: out of memory");
        goto done;
    }
    made = 1;
    a.diff = diff;
    /* an unknown TERM (or xterm-direct without its entry): a description
     * we have does better than one frame */
    const char *use = term_resolve(t);
    if (use && strcmp(use, t))
        safetext_line(stderr, "zview: unknown terminal type '%s': using %s", t, use);
    TermConfig cfg = {
        .out = screen,
        .in = keys,
        .termname = use,
        .colour = o->colour >= 0 ? (ColourDepth)o->colour : colour_from_env(),
        .colour_env = o->colour < 0,
        .mouse = 1,
        .signals = 1,
        .ask_bg = !o->bg,       /* --bg given: nothing to ask */
        .pixels = !a.pixels ? PIX_CELLS : o->pixels > PIX_CELLS ? o->pixels : PIX_AUTO,
    };
    char err[256];
    if (!use || term_open(&cfg, err, sizeof err)) {
        safetext_line(stderr, "zview: %s%s",
                use ? err : "no terminal description installed (not even xterm, vt100 or ansi)",
                o->print_view ? "" : ": one frame instead");
        fallback = 1;
        goto done;
    }
    /* a.pixels stays what was asked: a terminal on a slow link names its
     * pixels after the start's wait (term_read then says TE_RESIZE) */
    /* cells because of tmux or screen: said once, with what to do */
    const char *mux = term_mux_hint(1);
    if (mux && !a.note[0])
        snprintf(a.note, sizeof a.note, "%s", mux);
    /* the picture is kept visible on the terminal's background */
    uint8_t asked[3];
    Backdrop bd = pipeline_text_backdrop(o, term_background(asked, NULL) ? asked : NULL);
    pipeline_set_backdrop(&a.p, &bd);
    if (o->sketch) {
        a.sk.only = o->nfiles == 0;     /* no model to go back to */
        sketch_mode_enter(&a);
    }
    int run_rc = run(&a, o->fps);
    int out_errno = errno;
    term_restore();
    /* --print-view: the command line of the view as it was left */
    char cmd[CMD_MAX];
    int cmd_ok = o->print_view && run_rc == RUN_QUIT && viewer_view_command(&a, cmd, sizeof cmd) == 0;
    int unsaved = a.sk.on && !sketch_mode_file(&a);
    if (a.load_err[0])
        safetext_line(stderr, "zview: %s", a.load_err);
    else if (run_rc == RUN_NO_MEMORY)
        safetext_line(stderr, "zview: out of memory");
    else if (run_rc == RUN_INPUT_ENDED)
        safetext_line(stderr, "zview: %s: the input ended (no more keys)", keys_name);
    else if (run_rc == RUN_OUTPUT_FAILED)
        safetext_line(stderr, "zview: the terminal: %s", strerror(out_errno));
    else if (o->print_view && !cmd_ok && unsaved)
        safetext_line(stderr, "zview: --print-view: the sketch on screen was not written (w): no file shows it");
    else if (o->print_view && !cmd_ok)
        safetext_line(stderr, "zview: the view's command line is too long to print");
    else if (cmd_ok && print_line(cmd))
        ;
    else
        rc = 0;
done:
    if (made)
        viewer_app_free(&a);
    if (tty)
        fclose(tty);
    if (screen_tty)
        fclose(screen_tty);
    return fallback ? no_viewer(o, s, loading, diff) : rc;
}
