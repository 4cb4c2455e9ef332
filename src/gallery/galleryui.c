/* galleryui.c: zview DIR on the terminal. The grid of tiles is drawn
 * from the list as the workers (jobs.c) fill it: the tiles on the
 * screen are asked for first, each time the screen moves, and the rest
 * follow in the background, so the status line's counts complete. The
 * UI thread only reads tiles (under the jobs' lock), composes the
 * screen (gallery_compose) and takes keys: the arrows move the
 * selection, Enter leaves the grid for the viewer on that model (q or
 * Esc there comes back to the same place), / types a filter on the
 * names, s cycles the order, q or Esc quits. The selected tile turns
 * slowly: its file is loaded again on a thread of its own (one scene,
 * the selected one's, at most) and rendered at the tile's size a few
 * times a second; its still picture comes back when the selection
 * moves on. */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "gallery.h"
#include "safetext.h"
#include "thread.h"
#include "tty.h"
#include "viewer.h"

#define UI_PIC_COLS  20         /* a tile's picture, cells */
#define UI_PIC_ROWS  9
#define UI_TICK_MS   100        /* the spin's frames, and looks at the workers */
#define SPIN_WAIT_MS 400        /* the selection rests this long before its tile turns */
#define SPIN_STEP    0.08f      /* radians a frame: a turn in about 8 s */

/* The selected tile's scene, loaded on a thread of its own. */
typedef struct {
    pthread_t   th;
    int         running;        /* th started, not joined */
    int         stop;           /* set (atomically): the load is no longer wanted */
    int         done;           /* under the jobs' lock: the thread has finished */
    int         ok;
    int         tile;           /* the list index it is for */
    char       *path;
    const Options *o;
    Scene       s;
    float       yaw;
    Image       still;          /* the tile's own picture, put back after */
    int         have_still;
    GalleryJobs *jobs;
} Spin;

typedef struct {
    const Options *o;
    GalleryList  l;
    GalleryJobs *jobs;
    GalleryLook  look;
    GalleryGrid  grid;
    int          cols, rows;    /* the window */
    int         *order;         /* the tiles shown, sorted and filtered */
    int          n;
    int          sel, top;      /* selection (into order), first tile row shown */
    GallerySort  sort;
    char         filter[128];
    int          typing;        /* / is open: keys go into the filter */
    char         note[160];
    DisplayMode  mode;
    ColourDepth  depth;
    CellGrid     screen;
    Spin         spin;
    double       sel_since;     /* when the selection last moved */
} Ui;

/* ==== The spin ==== */

static void *spin_load(void *arg)
{
    Spin *sp = arg;
    int ok = gallery_tile_scene(sp->path, sp->o, &sp->stop, &sp->s) == 0;
    gallery_jobs_lock(sp->jobs);
    sp->ok = ok;
    sp->done = 1;
    gallery_jobs_unlock(sp->jobs);
    return NULL;
}

/* Stop the spin: the thread joined, the scene freed, the tile's still
 * picture back. */
static void spin_stop(Ui *u)
{
    Spin *sp = &u->spin;
    /* a big model still loading: its child is ended, not waited for */
    __atomic_store_n(&sp->stop, 1, __ATOMIC_RELAXED);
    if (sp->running)
        pthread_join(sp->th, NULL);
    if (sp->running && sp->ok)
        scene_free(&sp->s);
    if (sp->have_still) {
        gallery_jobs_lock(u->jobs);
        GalleryTile *t = &u->l.tile[sp->tile];
        image_free(&t->pic);
        t->pic = sp->still;
        gallery_jobs_unlock(u->jobs);
    }
    free(sp->path);
    memset(sp, 0, sizeof *sp);
}

/* The selected tile starts to turn (its scene loading), once every
 * picture on the screen is made: its load and frames would otherwise
 * take a core from the first screen. */
static void spin_start(Ui *u)
{
    if (!u->n || u->spin.running)
        return;
    int i = u->order[u->sel];
    int first = u->top * u->grid.cols, last = first + (u->grid.rows + 1) * u->grid.cols;
    gallery_jobs_lock(u->jobs);
    int ready = u->l.tile[i].state >= GS_PICTURED && u->l.tile[i].state != GS_UNREADABLE;
    ready = ready && u->l.tile[i].pic.w;
    for (int k = first; k < last && k < u->n && ready; k++)
        ready = u->l.tile[u->order[k]].state != GS_PENDING && u->l.tile[u->order[k]].state != GS_WORKING;
    gallery_jobs_unlock(u->jobs);
    Spin *sp = &u->spin;
    if (!ready || !(sp->path = strdup(u->l.tile[i].path)))
        return;
    sp->tile = i;
    sp->o = u->o;
    sp->jobs = u->jobs;
    if (thread_start(&sp->th, spin_load, sp) == 0)
        sp->running = 1;
    else {
        free(sp->path);
        sp->path = NULL;
    }
}

/* One step of the turn into the tile's picture: 1 when drawn anew. */
static int spin_step(Ui *u)
{
    Spin *sp = &u->spin;
    gallery_jobs_lock(u->jobs);
    int ready = sp->running && sp->done && sp->ok;
    gallery_jobs_unlock(u->jobs);
    if (!ready)
        return 0;
    sp->yaw += SPIN_STEP;
    Image pic = { 0 };
    if (gallery_tile_render(&sp->s, &u->look, sp->yaw, &pic)) {
        image_free(&pic);
        return 0;
    }
    gallery_jobs_lock(u->jobs);
    GalleryTile *t = &u->l.tile[sp->tile];
    if (!sp->have_still) {
        sp->still = t->pic;         /* kept to put back */
        sp->have_still = 1;
    } else
        image_free(&t->pic);
    t->pic = pic;
    gallery_jobs_unlock(u->jobs);
    return 1;
}

/* ==== The order and the screen ==== */

/* Sort and filter anew, the selection kept on the same tile when it is
 * still shown. */
static void reorder(Ui *u)
{
    int keep = u->n ? u->order[u->sel] : -1;
    for (int i = 0; i < u->l.n; i++)
        u->order[i] = i;
    if (u->jobs)
        gallery_jobs_lock(u->jobs);
    gallery_sort(u->order, u->l.n, u->l.tile, u->sort);
    if (u->jobs)
        gallery_jobs_unlock(u->jobs);
    u->n = gallery_filter(u->order, u->l.n, u->l.tile, u->filter);
    u->sel = 0;
    for (int k = 0; k < u->n; k++)
        if (u->order[k] == keep)
            u->sel = k;
    u->top = gallery_top_row(&u->grid, u->sel, u->top);
}

/* The window's size into the grid; the screen's tiles asked for first. */
static int layout(Ui *u)
{
    term_size(&u->cols, &u->rows);
    gallery_grid(&u->grid, u->cols, u->rows - 1, UI_PIC_COLS, UI_PIC_ROWS);
    u->screen.cols = u->cols;
    u->screen.rows = u->rows - 1 > 0 ? u->rows - 1 : 1;
    size_t need = (size_t)u->screen.cols * u->screen.rows;
    if (need > u->screen.cap) {
        Cell *c = realloc(u->screen.cells, need * sizeof *c);
        if (!c)
            return -1;
        u->screen.cells = c;
        u->screen.cap = need;
    }
    u->top = gallery_top_row(&u->grid, u->sel, u->top);
    return 0;
}

static void want_screen(Ui *u)
{
    int first = u->top * u->grid.cols, n = (u->grid.rows + 1) * u->grid.cols;   /* a part row shows too */
    if (first + n > u->n)
        n = u->n - first;
    gallery_jobs_want(u->jobs, u->order, first, n > 0 ? n : 0);
}

static void status(Ui *u, char *buf, size_t len)
{
    int made = 0, sound = 0, bad = 0;
    gallery_jobs_lock(u->jobs);
    for (int i = 0; i < u->l.n; i++) {
        int s = u->l.tile[i].state;
        made += s >= GS_SOUND;
        sound += s == GS_SOUND;
        bad += s == GS_PROBLEM || s == GS_UNREADABLE;
    }
    char verdict[GALLERY_VERDICT] = "";
    if (u->n)
        snprintf(verdict, sizeof verdict, "%s", u->l.tile[u->order[u->sel]].verdict);
    gallery_jobs_unlock(u->jobs);
    char filter[160] = "";
    if (u->typing || u->filter[0])
        snprintf(filter, sizeof filter, " · /%s%s", u->filter, u->typing ? "_" : "");
    char raw[1024];
    snprintf(raw, sizeof raw, " %d/%d loaded · %d sound · %d problem%s · sort %s%s · %s%s", made, u->l.n, sound, bad,
             bad == 1 ? "" : "s", gallery_sort_names[u->sort], filter, u->note[0] ? u->note : u->n ? verdict : "",
             u->n ? "" : "nothing matches");
    safetext(buf, len, raw);
}

static int draw(Ui *u)
{
    gallery_jobs_lock(u->jobs);
    int rc = gallery_compose(&u->screen, &u->grid, u->l.tile, u->order, u->n, u->top, u->sel, u->mode, u->depth,
                             &u->look.bd);
    gallery_jobs_unlock(u->jobs);
    if (rc)
        return -1;
    char bar[2048];
    status(u, bar, sizeof bar);
    term_draw_cells(&u->screen, 0);
    term_draw_bar(u->rows - 1, bar);
    return term_update(0);
}

/* ==== Opening one ==== */

/* The selected model in the viewer, the grid's terminal left meanwhile
 * and opened again after. 0, or -1 when the terminal cannot be had back. */
static int open_model(Ui *u, const TermConfig *cfg)
{
    if (!u->n)
        return 0;
    spin_stop(u);
    const GalleryTile *t = &u->l.tile[u->order[u->sel]];
    Options vo = *u->o;
    vo.gallery = 0;
    vo.files[0] = t->path;
    vo.nfiles = 1;
    term_restore();
    char err[512];
    Scene s;
    if (app_load_scene(&vo, &s, err, sizeof err) == 0) {
        viewer_run(&vo, &s);
        scene_free(&s);
        u->note[0] = '\0';
    } else
        snprintf(u->note, sizeof u->note, "%.150s", err);
    if (term_open(cfg, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return -1;
    }
    term_update(1);
    return 0;
}

/* ==== Keys ==== */

/* A key while / is open. */
static void filter_key(Ui *u, int key)
{
    size_t len = strlen(u->filter);
    if (key == TK_ENTER)
        u->typing = 0;
    else if (key == TK_ESC) {
        u->typing = 0;
        u->filter[0] = '\0';
    } else if (key == TK_BACKSPACE && len)
        u->filter[len - 1] = '\0';
    else if (key >= 32 && key < 127 && len + 1 < sizeof u->filter) {
        u->filter[len] = (char)key;
        u->filter[len + 1] = '\0';
    }
    reorder(u);
}

/* A key on the grid: 1 quit, -1 the terminal is lost, else 0. */
static int grid_key(Ui *u, int key, const TermConfig *cfg)
{
    int sel = u->sel, page = u->grid.rows * u->grid.cols;
    switch (key) {
    case 'q':
    case TK_ESC:
        return 1;
    case TK_LEFT:
    case 'h':
        sel = gallery_move(&u->grid, u->n, sel, -1, 0);
        break;
    case TK_RIGHT:
    case 'l':
        sel = gallery_move(&u->grid, u->n, sel, 1, 0);
        break;
    case TK_UP:
    case 'k':
        sel = gallery_move(&u->grid, u->n, sel, 0, -1);
        break;
    case TK_DOWN:
    case 'j':
        sel = gallery_move(&u->grid, u->n, sel, 0, 1);
        break;
    case TK_PGDN:
        sel = sel + page < u->n ? sel + page : u->n - 1;
        break;
    case TK_PGUP:
        sel = sel - page > 0 ? sel - page : 0;
        break;
    case TK_HOME:
        sel = 0;
        break;
    case TK_END:
        sel = u->n - 1;
        break;
    case TK_ENTER:
        return open_model(u, cfg);
    case '/':
        u->typing = 1;
        break;
    case 's':
        u->sort = (GallerySort)((u->sort + 1) % GSORT_COUNT);
        reorder(u);
        break;
    case TK_CTRL_L:
        term_update(1);
        break;
    default:
        break;
    }
    if (sel < 0)
        sel = 0;
    if (sel != u->sel) {
        spin_stop(u);
        u->sel = sel;
        u->sel_since = now_ms();
    }
    u->top = gallery_top_row(&u->grid, u->sel, u->top);
    return 0;
}

/* ==== The loop ==== */

static int loop(Ui *u, const TermConfig *cfg)
{
    int stored = -1;
    for (;;) {
        want_screen(u);
        if (draw(u))
            return 1;
        TermEvent ev;
        int got = term_read(&ev, UI_TICK_MS);
        if (got < 0)
            return 1;
        if (got > 0 && ev.type == TE_RESIZE && layout(u))
            return 1;
        if (got > 0 && ev.type == TE_KEY) {
            if (u->typing)
                filter_key(u, ev.key);
            else {
                int rc = grid_key(u, ev.key, cfg);
                if (rc)
                    return rc < 0 ? 1 : 0;
            }
        }
        if (gallery_order_due(&stored, gallery_jobs_stored(u->jobs), u->sort))
            reorder(u);         /* a tile pictured or checked may move in the order */
        if (!u->spin.running && u->n && now_ms() - u->sel_since >= SPIN_WAIT_MS)
            spin_start(u);
        spin_step(u);
    }
}

int gallery_run(const Options *o)
{
    char err[512];
    Ui u = { .o = o };
    if (gallery_scan(&u.l, o->files, o->nfiles, o->all, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    const char *t = getenv("TERM");
    const char *use = t && *t && strcmp(t, "dumb") ? term_resolve(t) : NULL;
    FILE *keys = isatty(STDIN_FILENO) ? stdin : NULL;
    if (!use || !keys) {
        gallery_list_free(&u.l);
        return gallery_oneshot(o);     /* no terminal to draw on: the text grid */
    }
    app_sandbox_warn(o);
    TermConfig cfg = { .out = stdout, .in = keys, .termname = use,
                       .colour = o->colour >= 0 ? (ColourDepth)o->colour : colour_from_env(),
                       .colour_env = o->colour < 0, .signals = 1, .ask_bg = !o->bg, .pixels = PIX_CELLS };
    if (term_open(&cfg, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        gallery_list_free(&u.l);
        return 1;
    }
    uint8_t asked[3];
    u.mode = o->mode >= 0 ? (DisplayMode)o->mode : mode_from_locale();
    u.depth = term_colour();
    int pw, ph;
    mode_cell_pixels(u.mode, &pw, &ph);
    u.order = malloc((size_t)(u.l.n > 0 ? u.l.n : 1) * sizeof *u.order);
    int rc = 1;
    if (!u.order || layout(&u)) {
        term_restore();
        safetext_line(stderr, "zview: out of memory");
        goto out;
    }
    u.look = (GalleryLook){ .o = o, .w = u.grid.pic_cols * pw, .h = u.grid.pic_rows * ph,
                            .aspect = mode_pixel_aspect(u.mode), .samples = TEXT_SAMPLES,
                            .bd = pipeline_text_backdrop(o, term_background(asked, NULL) ? asked : NULL) };
    /* the first screen asked for before any worker starts */
    reorder(&u);
    int screen = (u.grid.rows + 1) * u.grid.cols;
    if (!(u.jobs = gallery_jobs_start(&u.l, &u.look, o->threads, u.order, screen < u.n ? screen : u.n))) {
        term_restore();
        safetext_line(stderr, "zview: no thread to make the tiles with");
        goto out;
    }
    u.sel_since = now_ms();
    rc = loop(&u, &cfg);
    spin_stop(&u);
    term_restore();
out:
    gallery_jobs_stop(u.jobs);
    gallery_list_free(&u.l);
    free(u.order);
    free(u.screen.cells);
    return rc;
}
