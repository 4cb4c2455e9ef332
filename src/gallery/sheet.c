/* sheet.c: the gallery without a terminal. --gallery ... -o sheet.png
 * writes a contact sheet: a title line with the counts, then the tiles
 * in rows, each its picture on the sheet's background with the file's
 * name and the verdict under it in the 5 x 7 font (font.c); --print
 * writes the same grid as text (gallery_compose, which the viewer's
 * grid draws too). Every tile is made first, on the workers (jobs.c). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "gallery.h"
#include "safetext.h"

#define SHEET_PIC_W  160        /* a tile's picture, pixels, unless --size says */
#define SHEET_PIC_H  120
#define SHEET_MARGIN 8
#define SHEET_LINE   (GALLERY_GLYPH_H + 3)
#define SHEET_COLS_MAX 8
#define TEXT_PIC_COLS 20        /* a text tile's picture, cells */
#define TEXT_PIC_ROWS 9

static const uint8_t sheet_bg[3] = { 32, 32, 36 };
static const uint8_t ink_name[3] = { 230, 230, 230 };
static const uint8_t ink_sound[3] = { 110, 210, 110 };
static const uint8_t ink_problem[3] = { 240, 190, 60 };
static const uint8_t ink_unread[3] = { 240, 90, 80 };

static const uint8_t *verdict_ink(const GalleryTile *t)
{
    return t->state == GS_SOUND ? ink_sound : t->state == GS_PROBLEM ? ink_problem : ink_unread;
}

/* The counts of the title and the summary line. */
static void counts(const GalleryList *l, char *buf, size_t len)
{
    int sound = 0, bad = 0, unread = 0;
    for (int i = 0; i < l->n; i++) {
        sound += l->tile[i].state == GS_SOUND;
        bad += l->tile[i].state == GS_PROBLEM;
        unread += l->tile[i].state == GS_UNREADABLE;
    }
    int k = snprintf(buf, len, "%d model%s: %d sound, %d with problems, %d unreadable", l->n, l->n == 1 ? "" : "s",
                     sound, bad, unread);
    if (l->over && k > 0 && (size_t)k < len)
        snprintf(buf + k, len - (size_t)k, " (%d more not listed)", l->over);
}

/* Every tile of l made as look says. 0, or -1 (no thread). */
static int make_all(GalleryList *l, const GalleryLook *look, int threads)
{
    for (int i = 0; i < l->n; i++)
        if (l->tile[i].state != GS_UNREADABLE) {
            l->tile[i].state = GS_PENDING;
            image_free(&l->tile[i].pic);
        }
    GalleryJobs *j = gallery_jobs_start(l, look, threads, NULL, 0);
    if (!j)
        return -1;
    gallery_jobs_wait(j);
    gallery_jobs_stop(j);
    return 0;
}

/* ==== The contact sheet ==== */

static void fill(Image *im, const uint8_t rgb[3])
{
    for (size_t i = 0; i < (size_t)im->w * im->h; i++) {
        memcpy(im->rgb + 3 * i, rgb, 3);
        im->lit[i] = 0;
    }
}

/* Tile t's picture with its top left at x0, y0 of the sheet. */
static void blit(Image *sheet, const Image *pic, int x0, int y0)
{
    for (int y = 0; y < pic->h && y0 + y < sheet->h; y++)
        for (int x = 0; x < pic->w && x0 + x < sheet->w; x++) {
            size_t s = (size_t)y * pic->w + x, d = (size_t)(y0 + y) * sheet->w + (x0 + x);
            memcpy(sheet->rgb + 3 * d, pic->rgb + 3 * s, 3);
            sheet->lit[d] = pic->lit[s];
        }
}

static int write_sheet(const Options *o, GalleryList *l)
{
    char err[512];
    int pw = o->w > 0 ? o->w : SHEET_PIC_W, ph = o->h > 0 ? o->h : SHEET_PIC_H;
    GalleryLook look = { .o = o, .w = pw, .h = ph, .aspect = 1.0f, .samples = o->samples > 0 ? o->samples : 4 };
    look.bd = (Backdrop){ { sheet_bg[0], sheet_bg[1], sheet_bg[2] }, 1, BD_GIVEN };
    if (o->bg)
        look.bd = pipeline_text_backdrop(o, NULL);
    if (make_all(l, &look, o->threads)) {
        safetext_line(stderr, "zview: no thread to make the tiles with");
        return 1;
    }
    int cols = (int)ceil(sqrt((double)(l->n > 0 ? l->n : 1)));
    cols = cols > SHEET_COLS_MAX ? SHEET_COLS_MAX : cols;
    int rows = (l->n + cols - 1) / cols;
    int tw = pw + 2 * SHEET_MARGIN, th = ph + 2 * SHEET_LINE + 2 * SHEET_MARGIN;
    int top = SHEET_LINE + SHEET_MARGIN;
    char what[64];
    snprintf(what, sizeof what, "the contact sheet (%d x %d tiles)", cols, rows);
    Image sheet = { 0 };
    if (pipeline_check_frame(cols * tw, top + rows * th, 1, 0, what, err, sizeof err) ||
        image_resize(&sheet, cols * tw, top + (rows > 0 ? rows : 1) * th)) {
        safetext_line(stderr, "zview: %s", err[0] ? err : "out of memory");
        return 1;
    }
    fill(&sheet, look.bd.rgb);
    char line[256], safe[4 * sizeof line];
    counts(l, line, sizeof line);
    gallery_draw_text(&sheet, SHEET_MARGIN, SHEET_MARGIN / 2, line, sheet.w - 2 * SHEET_MARGIN, ink_name);
    for (int i = 0; i < l->n; i++) {
        const GalleryTile *t = &l->tile[i];
        int x0 = (i % cols) * tw + SHEET_MARGIN, y0 = top + (i / cols) * th + SHEET_MARGIN;
        if (t->pic.w)
            blit(&sheet, &t->pic, x0, y0);
        gallery_draw_text(&sheet, x0, y0 + ph + 3, safetext(safe, sizeof safe, t->name), pw, ink_name);
        gallery_draw_text(&sheet, x0, y0 + ph + 3 + SHEET_LINE, safetext(safe, sizeof safe, t->verdict), pw,
                          verdict_ink(t));
    }
    size_t n = strlen(o->out);
    int ppm = o->image_format ? o->image_format == IMG_PPM : n >= 4 && !strcmp(o->out + n - 4, ".ppm");
    int rc = ppm ? write_ppm(o->out, &sheet, err, sizeof err) : write_png(o->out, &sheet, err, sizeof err);
    image_free(&sheet);
    if (rc) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    return 0;
}

/* ==== The text grid ==== */

/* UTF-8 text into the cells of row y from x, at most w of them, one
 * code point a cell; fg NULL: the terminal's colours, else with fg
 * (reverse: on fg, in the background's colour). */
static void put_text(CellGrid *g, int x, int y, int w, const char *s, const uint8_t *fg, int reverse)
{
    if (y < 0 || y >= g->rows)
        return;
    const unsigned char *p = (const unsigned char *)s;
    for (int k = 0; k < w && *p && x + k < g->cols; k++) {
        uint32_t c = *p++;
        int more = c >= 0xf0 ? 3 : c >= 0xe0 ? 2 : c >= 0xc0 ? 1 : 0;
        c &= more == 3 ? 0x07 : more == 2 ? 0x0f : more == 1 ? 0x1f : 0x7f;
        for (; more && (*p & 0xc0) == 0x80; more--)
            c = c << 6 | (*p++ & 0x3f);
        Cell *cell = &g->cells[(size_t)y * g->cols + x + k];
        cell->ch = c >= 32 ? c : '?';
        cell->flags = 0;
        if (fg && reverse) {
            memcpy(cell->bg, fg, 3);
            memset(cell->fg, 0, 3);
            cell->flags = CELL_FG | CELL_BG;
        } else if (fg) {
            memcpy(cell->fg, fg, 3);
            cell->flags = CELL_FG;
        }
    }
}

int gallery_compose(CellGrid *g, const GalleryGrid *grid, const GalleryTile *t, const int *order, int n,
                    int top_row, int sel, DisplayMode mode, ColourDepth depth, const Backdrop *bd)
{
    for (size_t i = 0; i < (size_t)g->cols * g->rows; i++)
        g->cells[i] = (Cell){ .ch = ' ' };
    CellGrid pic = { 0 };
    char safe[4 * GALLERY_VERDICT + 4 * 256], name[260];
    int rc = 0;
    for (int k = top_row * grid->cols; k < n && !rc; k++) {
        int row = k / grid->cols - top_row, col = k % grid->cols;
        int x0 = col * grid->tile_cols + GALLERY_GAP / 2, y0 = row * grid->tile_rows;
        if (y0 >= g->rows)
            break;
        const GalleryTile *tile = &t[order[k]];
        if (tile->pic.w && !(rc = cells_from_image_on(&tile->pic, mode, depth, bd, &pic)))
            for (int y = 0; y < pic.rows && y0 + y < g->rows; y++)
                for (int x = 0; x < pic.cols && x0 + x < g->cols; x++)
                    g->cells[(size_t)(y0 + y) * g->cols + x0 + x] = pic.cells[(size_t)y * pic.cols + x];
        if (!tile->pic.w) {
            const char *what = tile->state == GS_PENDING || tile->state == GS_WORKING ? "..." : "(no picture)";
            int len = (int)strlen(what);
            put_text(g, x0 + (grid->pic_cols - len) / 2, y0 + grid->pic_rows / 2, grid->pic_cols, what, NULL, 0);
        }
        snprintf(name, sizeof name, "%s%s", k == sel ? "> " : "", tile->name);
        static const uint8_t white[3] = { 230, 230, 230 };
        put_text(g, x0, y0 + grid->pic_rows, grid->pic_cols, safetext(safe, sizeof safe, name),
                 k == sel ? white : NULL, k == sel);
        const char *v = tile->state == GS_PENDING || tile->state == GS_WORKING ? "loading" : tile->verdict;
        put_text(g, x0, y0 + grid->pic_rows + 1, grid->pic_cols, safetext(safe, sizeof safe, v),
                 tile->state >= GS_SOUND ? verdict_ink(tile) : NULL, 0);
    }
    cells_free(&pic);
    return rc ? -1 : 0;
}

/* The columns of --print: --size's, else the terminal's, else 80. */
static int text_cols(const Options *o)
{
    struct winsize ws;
    if (o->w > 0)
        return o->w;
    if (isatty(STDOUT_FILENO) && ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0)
        return ws.ws_col;
    return 80;
}

static int print_grid(const Options *o, GalleryList *l)
{
    DisplayMode mode = o->mode >= 0 ? (DisplayMode)o->mode : mode_from_locale();
    ColourDepth depth = o->colour >= 0 ? (ColourDepth)o->colour : colour_from_env();
    int pw, ph;
    mode_cell_pixels(mode, &pw, &ph);
    GalleryGrid grid;
    gallery_grid(&grid, text_cols(o), TEXT_PIC_ROWS + 2, TEXT_PIC_COLS, TEXT_PIC_ROWS);
    GalleryLook look = { .o = o, .w = grid.pic_cols * pw, .h = grid.pic_rows * ph,
                         .aspect = mode_pixel_aspect(mode), .samples = o->samples > 0 ? o->samples : TEXT_SAMPLES,
                         .bd = pipeline_text_backdrop(o, NULL) };
    if (make_all(l, &look, o->threads)) {
        safetext_line(stderr, "zview: no thread to make the tiles with");
        return 1;
    }
    int *order = malloc((size_t)(l->n > 0 ? l->n : 1) * sizeof *order);
    CellGrid g = { 0 };
    int rows = (l->n + grid.cols - 1) / grid.cols;
    g.cols = grid.cols * grid.tile_cols;
    g.rows = rows * grid.tile_rows;
    g.cells = calloc((size_t)g.cols * (g.rows > 0 ? g.rows : 1), sizeof *g.cells);
    g.cap = (size_t)g.cols * g.rows;
    int rc = !order || !g.cells;
    for (int i = 0; !rc && i < l->n; i++)
        order[i] = i;
    if (!rc)
        rc = gallery_compose(&g, &grid, l->tile, order, l->n, 0, -1, mode, depth, &look.bd) != 0;
    if (rc)
        safetext_line(stderr, "zview: out of memory");
    char line[256];
    counts(l, line, sizeof line);
    if (!rc && (print_cells(stdout, &g, depth) || printf("%s\n", line) < 0)) {
        safetext_line(stderr, "zview: standard output: write failed");
        rc = 1;
    }
    free(order);
    free(g.cells);
    return rc;
}

int gallery_oneshot(const Options *o)
{
    char err[512];
    GalleryList l;
    if (gallery_scan(&l, o->files, o->nfiles, o->all, err, sizeof err)) {
        safetext_line(stderr, "zview: %s", err);
        return 1;
    }
    app_sandbox_warn(o);
    int rc = 0;
    if (o->out)
        rc = write_sheet(o, &l);
    if (!rc && (o->print || !o->out))
        rc = print_grid(o, &l);
    gallery_list_free(&l);
    return rc;
}
