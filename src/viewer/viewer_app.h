#ifndef ZV_VIEWER_APP_H
#define ZV_VIEWER_APP_H
/* viewer_app (private to src/viewer): the interactive viewer's state, and
 * the key table in action.c that changes it. Each action is tiny and
 * returns what the loop in viewer.c has to redo. (The guard is not
 * include/viewer.h's, so that a file can include both.) */

#include <pthread.h>

#include "oneshot.h"
#include "viewer.h"
#include "sketch.h"
#include "prompt.h"

typedef enum {
    RE_NONE   = 0,
    RE_DRAW   = 1,          /* draw the screen again from the current cells */
    RE_RENDER = 2 | 1,      /* render a new frame, then draw */
    RE_CLEAR  = 4,          /* repaint the whole terminal (Ctrl-L) */
    RE_QUIT   = 8,
} Reaction;

/* The help overlay's lines: a title, then rows of one or more columns. */
#define HELP_LINES_MAX 48
#define HELP_LINE_MAX  160
#define CMD_MAX        4096     /* a view's command line */

/* Sketch mode (sketchui.c): polygons drawn on a canvas, which becomes
 * the scene each time it changes. */
typedef struct {
    int     on;             /* drawing: the sketch's keys, the canvas shown */
    int     only;           /* started with --sketch and no model: leaving quits */
    Sketch  k;
    Scene   scene;          /* the drawing as a scene (built while on) */
    int     built;          /* scene holds a built scene */
    int     dirty;          /* the drawing changed since scene was built */
    Scene  *model;          /* the viewer's scene, given back on leaving */
    int     cx, cy;         /* the keyboard cursor's cell in the picture */
    int     cursor;         /* the cursor is shown (the arrows moved it last, not the mouse) */
    int     w, h;           /* the picture in pixels at the last frame */
    char    saved[32];      /* the file written last ("" none) */
    int     saved_clean;    /* ... and the drawing is still what it holds */
} SketchMode;
/* loadjob.c: one file loaded on a thread of its own (the O key). */
typedef struct LoadJob LoadJob;
/* Start loading path as the options say (format, strict, flip, points);
 * NULL with a message when no thread can be had. */
LoadJob *loadjob_start(const char *path, const Options *o, char *err, size_t errlen);
/* The same for a file read again (--watch): only a regular file, looked
 * at without opening it; a FIFO, a device, a folder or nothing there is
 * NULL with the reason ("not a regular file (a FIFO)"), and the loader
 * opens it without waiting and refuses anything else in its place by
 * then. */
LoadJob *loadjob_reload(const char *path, const Options *o, char *err, size_t errlen);
int      loadjob_done(LoadJob *j);          /* the thread has finished */
/* Join the thread; 0 with the file's scene part in *part_out (the
 * caller owns it), or -1 with the loader's message. Frees the job. */
int      loadjob_finish(LoadJob *j, Scene *part_out, char *err, size_t errlen);
/* Esc, or the viewer quits mid-load: the thread finishes alone (at once
 * when it waits for a FIFO's writer, else after the step it is in) and
 * frees the job. */
void     loadjob_abandon(LoadJob *j);
const char *loadjob_path(const LoadJob *j);
/* "loading dragon.obj 42%", or a spinner, the seconds and the size when
 * the format reports no progress; "building dragon.obj" after parsing. */
void     loadjob_status(LoadJob *j, char *buf, size_t len);

/* firstload.c: the command line's big file loaded on threads while the
 * viewer runs, with pictures of what is parsed so far. */
typedef struct FirstLoad FirstLoad;
FirstLoad *firstload_start(const Options *o, char *err, size_t errlen);
/* q mid-load: the threads end alone (the sandbox's child is killed). */
void     firstload_abandon(FirstLoad *f);
/* "loading dragon.obj 42%" */
void     firstload_status(FirstLoad *f, char *buf, size_t len);
/* No viewer after all (no terminal description): the file loaded into
 * s (its empty scene freed) before the one-shot output. 0, or -1 with
 * the loader's message on stderr. */
int      firstload_now(const Options *o, Scene *s);

/* texjob.c: the pending (big) textures of a scene decoded on a thread
 * of their own, each in a sandboxed child as o says (sandbox.h). NULL
 * when there are none (or no thread). */
typedef struct TexJob TexJob;
TexJob  *texjob_start(Scene *s, const Options *o);
/* Put the finished ones in place (on the UI thread, between frames);
 * returns 1 when one was (draw again). A texture that could not be read
 * says so in note. When every one is done the job is freed (*jp NULL). */
int      texjob_poll(TexJob **jp, Scene *s, char *note, size_t notelen);
/* "decoding textures 1/2" */
void     texjob_status(TexJob *j, char *buf, size_t len);
/* Stop wanting it: the thread ends alone. */
void     texjob_abandon(TexJob *j);

/* checkjob.c: the check behind --problems, --parts and !, on a thread
 * of its own (the job owns copies of the files). */
typedef struct CheckJob CheckJob;
void     checkjob_abandon(CheckJob *j);     /* cancelled; the thread ends alone */

/* watch.c: --watch, the files' folders watched through inotify. */
typedef struct Watch Watch;
Watch   *watch_start(char *err, size_t errlen);
void     watch_free(Watch *w);
/* Watch these files (again: the files changed). */
void     watch_files(Watch *w, const char *const *paths, int n);
/* The index of a file changed and settled, -1 none. */
int      watch_due(Watch *w, double now);
/* File i again later (a load was under way). */
void     watch_again(Watch *w, int i, double now);

typedef struct App {
    const Options *opt;     /* the command line: files and layout, for view commands
                               (points at live below: O, X and E change its files) */
    Options     live;
    char       *paths[MAX_FILES]; /* live's files, owned (NULL: not yet copied) */
    Scene      *s;
    Camera      opening;    /* the view the model opened with (the automatic one or the
                               command line's): r goes back to it */
    Pipeline    p;
    int         algo;       /* index into hsr_algos */
    DisplayMode mode;
    int         utf8;       /* half and braille need a UTF-8 locale */
    int         cull;
    int         sel;        /* selected object, -1 = the whole scene */
    int         spin;       /* auto-rotate (turntable) */
    int         pixels;     /* a still picture in the terminal's pixels, where it has them (m turns it off) */
    size_t      pix_bytes;  /* the last image's bytes */
    int         pix_shrink; /* ... rendered at 1/pix_shrink of the cells' pixels a side, to fit the link */
    int         help;       /* help overlay shown */
    int         help_top;   /* first help row shown (scrolled) */
    int         help_hidden; /* help rows that did not fit the window (0: all shown) */
    int         help_page;  /* help rows shown: what Page Up/Down scroll by */
    int         cmd;        /* the view's command line shown (any key closes it) */
    int         pic_cols, pic_rows; /* --size: the picture's cells (0 = the window's) */
    char        name[96];   /* file name(s) for the status line */
    char        note[160];  /* a one-off note for the status line */
    int         cut_plane;  /* the section plane the ; ' \\ keys move (cutkeys.c) */
    /* live editing of the scene (live.c) */
    int         prompting;  /* the open prompt is in the status line */
    Prompt      prompt;
    LoadJob    *job;        /* a file loading in the background, or NULL */
    FirstLoad  *first;      /* the command line's file loading (firstload.c), or NULL */
    Camera      first_cam;  /* the camera of the last scene it gave: the user has not moved it */
    char        load_err[512];  /* it failed: the viewer ends with this message */
    TexJob     *tex;        /* big textures decoding in the background, or NULL */
    int         info;       /* the info panel is shown */
    int         confirm;    /* E asked "empty the scene? y/n": the next key answers */
    const char *empty_why;  /* why the last frame covers no pixel, NULL when it covers some */
    /* what the check found (checkjob.c), and --watch (watch.c) */
    CheckJob   *chk;        /* a check running, or NULL */
    int         check_started;  /* a check was started for check_gen */
    uint32_t    check_gen;  /* the scene generation checked (its marks are set when it went well) */
    CheckCounts check;      /* its figures */
    char        check_err[160];     /* why it failed, "" none */
    CheckItems  items;      /* its problems one by one (the . and , keys) */
    int         focus;      /* the item in focus, -1 none */
    int         focus_step; /* . or , pressed before the check was done: +1, -1; 0 none */
    int         focus_want; /* --problem K: item K - 1 once the check is done; -1 none */
    Watch      *watch;      /* --watch, or NULL */
    int         watch_set;  /* the files are watched as of watch_gen */
    uint32_t    watch_gen;
    int         reload;     /* the load job reads file reload again (--watch), -1 none */
    DiffSet    *diff;       /* --diff: the two models' diff, whose scene this is; NULL none */
    char        help_text[HELP_LINES_MAX][HELP_LINE_MAX];
    SketchMode  sk;
    int         measuring;  /* the measuring mode (M): arrows move the cursor (measureui.c) */
} App;

/* The viewer's modes, from the one on top. The first that is on takes
 * every key (and a click), and decides what is drawn over the picture:
 * the open prompt (its line and candidates), the y/n question of E, the
 * help box, the view's command line box, sketch mode (its marks and its
 * own keys, some of the viewer's shared), or the plain viewer. The info
 * panel is not a mode: it stays beside or under whatever is on top,
 * hidden only by a box. viewer_key, draw and dispatch all ask this one
 * function, so the order is written once. */
typedef enum { VM_PROMPT, VM_CONFIRM, VM_HELP, VM_COMMAND, VM_SKETCH, VM_VIEW } ViewerMode;

static inline ViewerMode viewer_mode(const App *a)
{
    return a->prompting ? VM_PROMPT
         : a->confirm   ? VM_CONFIRM
         : a->help      ? VM_HELP
         : a->cmd       ? VM_COMMAND
         : a->sk.on     ? VM_SKETCH
                        : VM_VIEW;
}

/* A box (help, command line) covers the picture and the info panel. */
static inline int viewer_mode_boxed(ViewerMode m)
{
    return m == VM_HELP || m == VM_COMMAND;
}

/* The effect of a key (term.h codes), a drag of dx, dy cells with button
 * 1 (left: turn) or 3 (right: move), or a wheel step (dy < 0: up). */
Reaction viewer_key(App *a, int key);
Reaction viewer_drag(App *a, int button, int dx, int dy);
Reaction viewer_wheel(App *a, int dy);
/* Turn the scene (or the selected object) about the vertical axis. */
void     viewer_spin(App *a, float radians);

/* The settings of the picture on screen, for view_command(). */
ViewSettings viewer_view_settings(const App *a);
/* The command line giving the view on screen back, into buf. Returns 0,
 * or -1 when it does not fit. */
int      viewer_view_command(const App *a, char *buf, size_t len);
/* The view's command line wrapped to cols columns for the screen: a
 * title, then lines that end in " \\" where the command goes on (pasted
 * into a shell, it stays one command). Fills lines[] (at most max) with
 * pointers into buf and returns how many. */
int      viewer_command_layout(const App *a, int cols, char *buf, size_t len, const char **lines, int max);
/* Snapshot (snapshot.c): the picture as a PNG and as the --print text,
 * under the next free zview-<model>-NNN name in the current directory
 * (or the model's when that cannot be written); the note says what was
 * written. Returns what to redo. */
Reaction viewer_snapshot(App *a);
/* measureui.c: the measuring mode. M turns it on and off; while on, a
 * key it takes (arrows, Enter, Backspace, S, Esc) is its own (RE_NONE:
 * not one of them). */
Reaction viewer_measure_toggle(App *a);
Reaction viewer_measure_key(App *a, int key);
/* A left click (drag 0) or drag (1) on cell x, y of the window with
 * mods (TE_CTRL ...) held: the cursor to the nearest visible point
 * there; a click on the cursor's own point marks it. */
Reaction viewer_measure_mouse(App *a, int x, int y, int mods, int drag);

/* ==== Sketch mode (sketchui.c) ==== */

/* Enter sketch mode: the canvas becomes the scene (the drawing kept from
 * the last time). Returns what to redo. */
Reaction sketch_mode_enter(App *a);
/* A press of button 1 or 3 on cell x, y, in sketch mode (its keys: sketch_keys). */
Reaction sketch_mode_click(App *a, int button, int x, int y);
/* Before a frame of w x h pixels: the scene rebuilt when the drawing
 * changed, the camera pinned to the canvas. Returns 0, or -1 with the
 * reason in a->note. */
int      sketch_mode_frame(App *a, int w, int h, float aspect);
/* After it: the open polygon's corners and the cursor marked on the cells. */
void     sketch_mode_marks(const App *a, CellGrid *g);
/* The status bar in sketch mode, at most width columns. */
void     sketch_mode_status(const App *a, char *buf, size_t len, int width);
/* The file the view's command line names: the saved drawing, NULL when
 * the drawing is not saved as it is. */
const char *sketch_mode_file(const App *a);
void     sketch_mode_free(App *a);

/* ==== Key tables: the viewer's (action.c) and sketch mode's (sketchui.c) ====
 * A row is one line of the ? help (the keys as it names them, what they
 * do) and the keys it stands for, each with its action: the help is
 * drawn from the rows, so no key is bound and left out of it.
 * tests/test_options.c checks that each row's label names its keys and
 * that the man page lists every key. */
typedef Reaction (*KeyAction)(App *a);
typedef struct {
    int       key;          /* a character or a TK_* code */
    KeyAction act;          /* NULL in sketch mode's table: the viewer's action for the key */
} KeyBind;
#define KEY_ROW_BINDS 8
typedef struct {
    const char *keys;       /* as the help names them: "arrows h j k l" */
    const char *what;       /* "turn (yaw, pitch)" */
    KeyBind     bind[KEY_ROW_BINDS];    /* ended by key 0; none for the mouse's rows */
} KeyRow;
extern const KeyRow viewer_keys[];
extern const int    viewer_keys_n;
extern const KeyRow sketch_keys[];
extern const int    sketch_keys_n;
/* The binding of key in rows[0..n), NULL when there is none. */
const KeyBind *key_find(const KeyRow *rows, int n, int key);
/* The key's name as the help and the man page write it: "Left",
 * "Shift-Tab", "Ctrl-L", "Space", or the character ("q"). */
const char *key_name(int key, char *buf, size_t len);
/* live.c: the scene edited while the viewer runs. */
Reaction viewer_open_prompt(App *a);           /* O: ask for a file */
Reaction viewer_prompt_key(App *a, int key);   /* a key while the prompt is up */
Reaction viewer_load_poll(App *a);             /* a background load finished? join its part */
Reaction viewer_first_poll(App *a);            /* a new picture of the first file, or the whole */
Reaction viewer_cancel_load(App *a);           /* Esc while loading: drop the load, note it */
Reaction viewer_remove_selected(App *a);       /* X, Delete */
Reaction viewer_clear_scene(App *a);           /* E */
/* checkjob.c: start the check when it is wanted and the scene changed,
 * set its marks when it is done; the verdict for the status bar (""
 * when not wanted), the counts for the info panel. */
Reaction viewer_check_poll(App *a);
void     viewer_check_status(const App *a, int max_items, char *buf, size_t len);
/* . and ,: the next (step 1) or previous (-1) problem in focus, the
 * camera framed on it; --problems turned on first when it is off, and
 * the step taken when the check is done. viewer_focus_clear: none in
 * focus (the items stay). */
Reaction viewer_problem_step(App *a, int step);

/* cutkeys.c: the section planes in the viewer. / cuts and uncuts (with
 * no plane yet: z through the middle of the model), ; and ' slide the
 * plane by a fiftieth of the model's size along its normal, \ turns it
 * to the next axis (x, y, z) through the middle, | picks the next plane
 * of several. viewer_cut_status: the plane's position and the
 * section's area, for the status bar ("" when there is no cut). */
Reaction viewer_cut_toggle(App *a);
Reaction viewer_cut_slide(App *a, int dir);
Reaction viewer_cut_turn(App *a);
Reaction viewer_cut_next(App *a);
void     viewer_cut_status(const App *a, char *buf, size_t len, char *brief, size_t brief_len);
void     viewer_focus_clear(App *a);
int      viewer_check_report(const App *a, ReportLine *lines, int max);
/* watch.c: a watched file changed: read it again (a load job). */
Reaction viewer_watch_poll(App *a);
/* The files of the command line copied so that they can change; the
 * status line's name from them. */
int      viewer_live_init(App *a, const Options *o);
void     viewer_live_free(App *a);
void     viewer_update_name(App *a);
/* A loaded file's warnings (statements skipped, else the first) as the
 * status line's note. */
void     viewer_warning_note(App *a, const MeshInfo *info, const char *path);
/* Set the status line's note (cut to its size). */
void     viewer_note(App *a, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The help overlay laid out for a window of cols x rows (the status bar
 * included): a title and as many rows of keys as fit, in as few columns
 * as fit (keys over their meaning when even one column is too wide);
 * a->help_top is clamped and a->help_hidden set. Fills lines[] (pointers
 * into a->help_text) and returns how many. */
int      viewer_help_layout(App *a, int cols, int rows, const char **lines);

/* The status bar's text for a window width columns wide (statusbar.c):
 * frame_ms the last frame's time, fps_cap the auto-rotate cap. */
void viewer_status_text(const App *a, char *buf, size_t len, double frame_ms, int fps_cap, int width);
/* The prompt's line bar in cols columns, the cursor at column *cursor
 * of it: the characters dropped from the left until the cursor is at
 * most at column cols - 2 (the last column kept free), as few as that
 * takes. Returns where the line shown starts; *cursor becomes the
 * cursor's column on the screen. */
const char *viewer_prompt_scroll(const char *bar, int cols, int *cursor);

/* viewer.c: the App set up for a scene (a load of the first file under
 * way when loading), and everything it made freed (also what a failed
 * set-up made); the picture for cols x rows cells, as --print makes it. */
int  viewer_app_init(App *a, const Options *o, Scene *s, int loading);
void viewer_app_free(App *a);
int  viewer_render(App *a, int cols, int rows);

#endif
