#ifndef ZV_GALLERY_H
#define ZV_GALLERY_H
/* gallery: a folder of models at a glance, the room src/gallery/. The
 * models of a folder (zview DIR) or of several files (--gallery) as a
 * grid of tiles, each a small picture, the file's name and the check's
 * verdict in a word or two ("sound", "3 holes", "unreadable: ...").
 * scan.c lists the files (bounded: GALLERY_MAX_FILES, no directory
 * followed); tile.c makes one tile (the file loaded in the sandbox as
 * any load, checked, rendered small, then freed: a tile keeps its
 * picture, never the mesh); jobs.c makes them on worker threads, the
 * ones asked for first; grid.c lays them out, sorts and filters them
 * (no I/O, unit tested); sheet.c writes the contact sheet (-o PNG) and
 * the text grid (--print); galleryui.c is the grid on the terminal,
 * Enter opening a model in the viewer. */

#include <pthread.h>
#include <stdint.h>

#include "app.h"

#define GALLERY_MAX_FILES 10000     /* files listed a run; past it they are counted, not read */
#define GALLERY_VERDICT   96        /* bytes of a tile's verdict */

typedef enum {
    GS_PENDING,                 /* not made yet */
    GS_WORKING,                 /* a worker is making it */
    GS_PICTURED,                /* its picture made, its check to come (a tile the screen shows) */
    GS_CHECKING,                /* ... a worker is checking it */
    GS_SOUND,                   /* read, and the check found nothing wrong */
    GS_PROBLEM,                 /* read, and the check found problems */
    GS_UNREADABLE,              /* not read: the verdict says why */
} GalleryState;

typedef enum { GSORT_NAME, GSORT_SIZE, GSORT_FACES, GSORT_VERDICT, GSORT_COUNT } GallerySort;
extern const char *const gallery_sort_names[GSORT_COUNT];

typedef struct {
    char       *path;           /* as listed (owned) */
    const char *name;           /* its last component, inside path */
    uint64_t    size;           /* bytes (0: unknown, e.g. a symlink loop) */
    uint32_t    faces;          /* once read */
    uint32_t    problems;       /* kinds of problem the check found */
    int         state;          /* GalleryState */
    char        verdict[GALLERY_VERDICT];
    Image       pic;            /* the tile's picture once made (w 0: none) */
    float       yaw;            /* the picture's turn, radians from the chosen view (the spin) */
} GalleryTile;

typedef struct {
    GalleryTile *tile;
    int          n, cap;
    int          skipped;       /* entries that are no model file (shown with --all) */
    int          over;          /* entries past GALLERY_MAX_FILES, not listed */
} GalleryList;

/* ==== Listing (scan.c) ==== */

/* Does the name end in an extension a reader of this build knows
 * (a native one, assimp's, either under .gz)? */
int  gallery_is_model_name(const char *name);
/* The tiles of args: a folder gives its entries (not its subfolders,
 * nor links to folders; a link that loops, or any entry that cannot be
 * looked at, is a tile that says so), a file itself. Entries that are
 * not model files (by their name) are skipped unless all. At most
 * GALLERY_MAX_FILES; sorted by name. 0, or -1 with "DIR: reason" in err
 * (a folder that cannot be opened, no memory). */
int  gallery_scan(GalleryList *l, const char *const *args, int nargs, int all, char *err, size_t errlen);
void gallery_list_free(GalleryList *l);

/* ==== One tile (tile.c) ==== */

/* How tiles are pictured: the picture's pixels and pixel aspect, its
 * samples, the backdrop it is seen on and the options of the command
 * line (format, --max-memory, --flip, the sandbox). */
typedef struct {
    const Options *o;
    int         w, h;           /* pixels */
    float       aspect;         /* pixel height / width */
    int         samples;
    Backdrop    bd;
    const int  *cancel;         /* set (atomically) by another thread: loads under way end */
} GalleryLook;

/* Make tile t (its path read) as look says, on the calling thread:
 * loaded in the sandbox, then as `what` says pictured, checked (one
 * thread), or both, and the mesh freed. Fills faces, then pic (state
 * GS_PICTURED when the check is still to come), or problems, verdict
 * and state. A picture alone is what the screen waits for: a check
 * (about twice the load's time) comes after, its file loaded again.
 * An unreadable file is a tile too (GS_UNREADABLE); -1 only when there
 * is no memory for the picture. */
enum { TILE_PICTURE = 1, TILE_CHECK = 2, TILE_BOTH = 3 };
int  gallery_tile_make(GalleryTile *t, const GalleryLook *look, int what);
/* The check's verdict in a word or two: "sound", "no faces", the first
 * problem in the status bar's words ("3 holes", "12 flipped"), "+N"
 * after it when there are more kinds. */
void gallery_verdict(const CheckCounts *c, char *buf, size_t len);
/* "unreadable: reason" from a loader's message ("path: reason"). */
void gallery_unreadable(const char *path, const char *err, char *buf, size_t len);

/* A scene of one file for the spin of the selected tile (galleryui.c):
 * 0, or -1 (the file is unreadable now, or cancel was set: the load's
 * child is ended at once). */
int  gallery_tile_scene(const char *path, const Options *o, const int *cancel, Scene *out);
/* Render scene s turned by yaw radians into t->pic as look says. */
int  gallery_tile_render(Scene *s, const GalleryLook *look, float yaw, Image *pic);

/* ==== Making them on threads (jobs.c) ==== */

typedef struct GalleryJobs GalleryJobs;
/* Workers (nthreads, 0: one per core) making the list's pending tiles:
 * the ones asked for first (want[0..nwant), list indices, as
 * gallery_jobs_want after), then the rest in order. The list is shared:
 * read tiles under gallery_jobs_lock. */
GalleryJobs *gallery_jobs_start(GalleryList *l, const GalleryLook *look, int nthreads, const int *want, int nwant);
/* The tiles order[first..first+n) first (the screen's), in that order. */
void gallery_jobs_want(GalleryJobs *j, const int *order, int first, int n);
void gallery_jobs_lock(GalleryJobs *j);
void gallery_jobs_unlock(GalleryJobs *j);
/* Tiles written back so far, pictured or checked: each may have moved
 * in an order (its faces known, then its verdict). A snapshot, under
 * the lock or not. */
int  gallery_jobs_stored(GalleryJobs *j);
/* Wait until every tile is made. */
void gallery_jobs_wait(GalleryJobs *j);
/* Stop the workers (after the tile each is making) and free the jobs. */
void gallery_jobs_stop(GalleryJobs *j);
/* The workers' choice, under the lock: the next tile to work on, marked
 * GS_WORKING or GS_CHECKING, with what to make in *what; -1 none. The
 * tiles in want[0..nwant) are pictured first, in that order, then
 * checked; then the rest from *next on (which it moves), each in one go
 * (a tile pictured before is only checked). */
int  gallery_pick(GalleryList *l, const int *want, int nwant, int *next, int *what);

/* ==== The grid (grid.c): layout, order, filter ==== */

/* Tiles in character cells: the picture pic_cols x pic_rows, then the
 * name's and the verdict's lines, GALLERY_GAP columns between tiles. */
#define GALLERY_GAP 2
typedef struct {
    int pic_cols, pic_rows;     /* the picture of a tile, cells */
    int tile_cols, tile_rows;   /* a tile with its gap and text lines */
    int cols;                   /* tiles across */
    int rows;                   /* whole tiles down the screen (at least 1) */
} GalleryGrid;

/* The grid for a screen of cols x rows cells (the status line not
 * counted) and tile pictures of about pic_cols x pic_rows. */
void gallery_grid(GalleryGrid *g, int cols, int rows, int pic_cols, int pic_rows);
/* The selection after a move of dx tiles across and dy down among n
 * tiles (clamped: never off the ends; up from the first row stays). */
int  gallery_move(const GalleryGrid *g, int n, int sel, int dx, int dy);
/* The first tile row shown so that row `sel` is on screen, from the
 * current top (scrolling as little as possible). */
int  gallery_top_row(const GalleryGrid *g, int sel, int top_row);
/* Order the indices order[0..n) of tiles t by `by` (ties by name, then
 * by path: a total order, the same each time). */
void gallery_sort(int *order, int n, const GalleryTile *t, GallerySort by);
/* Keep in order[0..n) the tiles whose name contains needle (ASCII case
 * ignored; "" keeps all), in the same order; returns how many. */
int  gallery_filter(int *order, int n, const GalleryTile *t, const char *needle);
/* Is the order to be made again, now that `now` tiles are stored
 * (gallery_jobs_stored) and *seen were at the last look? Only when a
 * tile was stored since, and the order is not by name (which no tile's
 * making changes): sorting on every tick of the grid would cost as much
 * with nothing new. *seen becomes now. */
int  gallery_order_due(int *seen, int now, GallerySort by);
/* The rank of a tile in the verdict sort: unreadable, problems (more
 * kinds first), sound, then not yet made. */
int  gallery_verdict_rank(const GalleryTile *t);

/* ==== Sheets (sheet.c, font.c) ==== */

#define GALLERY_GLYPH_W 5
#define GALLERY_GLYPH_H 7
/* Is pixel x, y of character c's glyph ink? */
int  gallery_glyph_ink(unsigned char c, int x, int y);
/* s in the 5 x 7 font with its top left at x0, y0, at most maxw pixels
 * wide (whole characters), clipped to the image. */
void gallery_draw_text(Image *im, int x0, int y0, const char *s, int maxw, const uint8_t rgb[3]);

/* zview --gallery ... -o sheet.png, --print: every tile made, then the
 * contact sheet or the text grid. Returns the exit status (0; 1 when
 * nothing could be listed or written). */
int  gallery_oneshot(const Options *o);
/* The text grid of tiles order[0..n) from tile row top_row into g
 * (g->cols x g->rows cells, already sized): pictures in mode and depth
 * on bd, names and verdicts under them, the selected one (sel, an
 * index into order; -1 none) marked. */
int  gallery_compose(CellGrid *g, const GalleryGrid *grid, const GalleryTile *t, const int *order, int n,
                     int top_row, int sel, DisplayMode mode, ColourDepth depth, const Backdrop *bd);

/* ==== The grid on the terminal (galleryui.c) ==== */

/* zview DIR: the grid; Enter opens a model in the viewer. Without a
 * terminal, the text grid (--print). Returns the exit status. */
int  gallery_run(const Options *o);

#endif
