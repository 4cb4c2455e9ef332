#ifndef ZV_APP_H
#define ZV_APP_H
/* app: what the two front doors (oneshot/ and viewer/) share: the
 * options, loading the files they name into a scene, and the pipeline
 * that ties the stages together (scene -> screen polygons -> hidden
 * surfaces -> shading -> cells). The one-shot outputs, the benchmark and
 * the viewer all render through pipeline_render(). */

#include "backdrop.h"
#include "hsr.h"
#include "printq.h"
#include "present.h"
#include "sandbox.h"
#include "scene.h"
#include "screen.h"
#include "section.h"
#include "shade.h"

#define ZV_VERSION "0.1.0"
#define MAX_FILES 64
#define MAX_PLACE 64
#define TEXT_SAMPLES 4          /* default samples per pixel of text pictures (viewer, --print) */

/* --move, --turn, --scale: one object's placement. */
typedef enum { PLACE_MOVE, PLACE_TURN, PLACE_SCALE } PlaceKind;
typedef struct {
    PlaceKind kind;
    int       obj;              /* 0-based object index */
    float     v[3];             /* x y z, yaw pitch roll (degrees), or the scale in v[0] */
} Placement;

/* Points marked on the model (the viewer's measuring mode, --marks):
 * points of the scene's objects (a vertex, an edge's midpoint or a
 * face's centre), drawn over the picture with the lines between them
 * (measuremarks.c), and the cursor that picks them. */
#define MEASURE_MARKS 3
enum { MEASURE_VERTEX, MEASURE_EDGE, MEASURE_FACE };
typedef struct {
    int      obj;                       /* the scene object it is on */
    int      kind;                      /* MEASURE_VERTEX, MEASURE_EDGE or MEASURE_FACE */
    uint32_t a, b;                      /* 0-based: vertex a of the object's mesh; the midpoint
                                           of the edge from its vertex a to b (a < b); the centre
                                           (corners' mean) of the object's own face a */
} MeasurePick;
typedef struct {
    int      n;                         /* marks, 0 to 3 */
    MeasurePick mark[MEASURE_MARKS];
    int      cursor;                    /* the cursor shown (the measuring mode) */
    MeasurePick cur;
    int      wide;                      /* the cursor snaps to edge midpoints and face centres
                                           too, not to vertices only (the viewer's S in M) */
} MeasureMarks;

typedef struct {
    const char *files[MAX_FILES];
    int         nfiles;
    int         help, version, print, info, bench, bench_tty, json;
    const char *out;            /* -o FILE.png|FILE.ppm, "-" = standard output */
    int         image_format;   /* --image-format: IMG_PNG, IMG_PPM, or IMG_AUTO (by name) */
    const char *format;         /* --format: the model format, NULL = detect */
    int         formats;        /* --formats: list them */
    int         up;             /* --up: UpAxis, -1 = as each file's format says (MeshInfo.up) */
    int         flip;           /* --flip: reverse every face's winding */
    const char *dump_ids;
    const char *dump_screen;
    int         w, h;           /* --size (0 = not given) */
    int         mode;           /* DisplayMode, -1 = from the locale */
    int         pixels;         /* PixelProto: --mode sixel|kitty|iterm|cells|auto, -1 = not given */
    int         max_rate;       /* --max-rate KB/s: the viewer's still images fit it (0 = the default) */
    int         colour;          /* ColourDepth, -1 = from the environment */
    int         shade;          /* ShadeMode */
    const char *algo;           /* name, "all", or a comma list (bench) */
    const char *view;           /* --view name, "auto", or NULL */
    int         layout;         /* LayoutKind of several files */
    float       yaw, pitch, roll;   /* degrees, added to the view's turn */
    int         turned;         /* --yaw, --pitch or --roll given */
    float       zoom;
    float       pan[2];         /* --pan, fractions of the scene radius */
    float       fit_from[3];    /* --fit-from yaw pitch roll, degrees */
    int         has_fit_from;
    Placement   place[MAX_PLACE];
    int         nplace;
    uint64_t    max_polys;      /* refuse bigger scenes; 0: what memory holds */
    double      tessellation;   /* --tessellation: CAD deflection over the diagonal; 0: the default */
    uint64_t    max_memory;     /* --max-memory: bytes a load may take (0: the default bound, sandbox.h) */
    int         no_sandbox;     /* --no-sandbox: load in this process (sandbox.h) */
    SandboxServer sandbox;      /* where sandboxed loads are forked (main starts it); pid 0: from here */
    int         persp;          /* 1 = --persp given */
    float       fov;
    int         cull;
    int         views, threads, grid, fps;
    int         samples;        /* --samples, 0 = the default of the output */
    float       crease;         /* --crease, degrees */
    float       light[2];       /* --light yaw, pitch in degrees */
    float       ambient;        /* --ambient */
    int         edges;          /* --edges */
    int         order;          /* PolyOrder */
    /* points, lines and lenient loading */
    int         point_size;     /* --point-size, pixels */
    int         line_width;     /* --line-width, pixels */
    int         wireframe;      /* --wireframe */
    int         points;         /* --points: every vertex a point, faces dropped */
    int         strict;         /* --strict: refuse a file with a statement it cannot read */
    int         print_view;     /* --print-view: the view's command line on stdout when the viewer quits */
    int         turntable;      /* --turntable N: N frames turning 360/N degrees each (0 = off) */
    int         sketch;         /* --sketch: the viewer starts drawing polygons on an empty canvas */
    /* the background (backdrop.h) */
    const char *bg;             /* --bg COLOR as written, NULL = default (the terminal's; images: picked) */
    uint8_t     bg_rgb[3];      /* --bg's colour */
    float       contrast;       /* --contrast: least OKLab L from the background, 0 = colours as given */
    int         no_textures;    /* --no-textures: faces in their base colours (t in the viewer) */
    /* not options: how the front door wants textures loaded */
    int         tex_defer;      /* the viewer: images longer than this a side decode after the first picture */
    int         tex_skip;       /* one picture without textures: no image is opened */
    int         check;          /* --check: is each model right (a report, exit status 3 on problems) */
    int         problems;       /* --problems: what the check finds, drawn on the model */
    int         parts;          /* --parts: each connected part its own colour */
    int         watch;          /* --watch: the files read again when they change */
    int         max_locations;  /* --max-locations: --check --json locates so many problems of each kind */
    SectionPlane section[SECTION_MAX];  /* --section: the planes the model is cut by */
    int         nsections;
    int         problem;        /* --problem K: the picture framed on the K-th problem (1 the first), 0 none */
    int         gallery;        /* --gallery: the files, or the folders' models, as tiles (gallery.h) */
    int         all;            /* --all: a folder's every file, not only its models */
    int         recursive;      /* -r: --check enters a folder's subfolders too */
    int         jsonl;          /* --jsonl: --check streams a JSON object a file, a line each */
    int         summary;        /* --summary: the files are --jsonl output, summed up */
    /* --repair (oneshot/repairrun.c) */
    unsigned    repair;         /* --repair[=STEPS]: the REPAIR_* steps (repair.h), 0 = not asked */
    double      weld;           /* --weld EPS: file units, 0 = positions bit for bit */
    uint32_t    max_hole;       /* --max-hole N: edges, 0 = no limit */
    /* --diff A B (diff.h) */
    int         diff;           /* how B differs from A: the picture, or a report */
    double      tolerance;      /* --tolerance: distances up to it are the same; < 0: the default */
    int         show;           /* --show: what the picture shows (DiffShow: both a b heat) */
    int         quiet;          /* --quiet: no report, the exit status says */
    int         textconv;       /* --textconv: --check as git's textconv driver wants it */
    int         preview;        /* --preview WxH: a file manager's preview (w, h: its cells) */
    /* will it print, and its measures (printq.h) */
    double      bed[3];         /* --bed W x D x H, in the report's unit; 0: not given */
    const char *unit;           /* --unit mm|in|m: the files' unit (the figures then in mm); NULL: as stated */
    int         overhang;       /* --overhang[=DEG]: overhanging faces coloured, their area in --check */
    float       overhang_deg;   /* its angle from the vertical, degrees (45) */
    int         thickness;      /* --thickness: the faces coloured by wall thickness */
    double      min_thickness;  /* --min-thickness T: --check reports what is thinner; 0: not given */
    PrintqPoint measure[3];     /* --measure A B [C]: points or vertices */
    int         nmeasure;       /* points given (0: no --measure) */
    MeasureMarks marks;         /* --marks: the points marked on the model */
} Options;

/* The viewer decodes images longer than this a side on a thread of its
 * own, after the first picture (a 4096 x 4096 JPEG takes about 0.2 s). */
#define TEX_DEFER_SIDE 2048

#define POINT_SIZE_MAX 16       /* pixels: at 4 x 4 samples a pixel, PRIM_SIZE_MAX samples */

enum { IMG_AUTO, IMG_PNG, IMG_PPM };

/* ==== The option table (options.c) ====
 * Each option is written once, in cli_options[]: getopt's table, the
 * --help text and the parsing come from it, and tests/test_options.c
 * checks the man page, the completion files, the README and the view
 * command against it. */
typedef enum {
    OPTSEC_GENERAL, OPTSEC_INPUT, OPTSEC_OUTPUT, OPTSEC_VIEW, OPTSEC_BENCH, OPTSEC_COUNT
} OptSection;

enum {
    OPT_ALIAS   = 1 << 0,       /* another spelling (--colour): not listed in --help or the man page */
    OPT_VIEWCMD = 1 << 1,       /* the view command (C, --print-view) writes it when it is not the default */
    OPT_OPTIONAL = 1 << 2,      /* its value is optional, given as --name=VALUE only (--repair=STEPS) */
};

/* One option's value as the setter sees it: the value, the option as
 * the user wrote it (--size or -s) and where a message goes. */
typedef struct {
    const char *val;
    const char *name;
    char       *err;
    size_t      errlen;
} OptCall;

typedef struct {
    const char *name;           /* the long name, without the dashes */
    char        letter;         /* the short option, 0 = none */
    const char *arg;            /* the value's name in --help (WxH, N); NULL: the values, or no value */
    const char *values;         /* the words the value can be, space-separated, NULL = any */
    OptSection  section;        /* the man page's subsection, --help's heading */
    const char *help;           /* --help's text, lines split by '\n'; NULL for an alias */
    /* takes the value into Options: 0, or -1 with the message in c->err;
     * NULL: a flag (no value) that sets the int at `flag` to 1 */
    int       (*set)(Options *o, const OptCall *c);
    size_t      flag;           /* offsetof(Options, field) of a flag */
    unsigned    traits;         /* OPT_ALIAS, OPT_VIEWCMD */
} OptSpec;

#define CLI_OPTIONS_MAX 96      /* bounds getopt's table, built on the stack */
extern const OptSpec cli_options[];
extern const int     cli_noptions;
extern const char *const cli_section_names[OPTSEC_COUNT];
/* The option of that long name, NULL when there is none. */
const OptSpec *cli_option(const char *name);
/* Whether the option takes a value: one that does names it or its words
 * (OPT_OPTIONAL: may take one). */
static inline int opt_has_value(const OptSpec *s) { return s->arg || s->values; }

/* Parse argv. Returns 0, or -1 with a message in err (a usage error). */
void cli_defaults(Options *o);
int  cli_parse(int argc, char **argv, Options *o, char *err, size_t errlen);
void cli_usage(FILE *f);
/* The integer conversions in a frame-file pattern (printf's %d, %03d,
 * %i, %u, %x, %o with flags, width, precision; %% is a percent sign),
 * or -1 when it has any other conversion. --turntable needs exactly 1. */
int  frame_pattern_check(const char *pat);

/* ==== The first view (firstview.c, standin.c) ====
 * Candidate views rendered small and scored by what they see (the rule
 * is in firstview.c's opening comment). */
#define FV_VIEWS 12                 /* candidate views */
#define FV_STANDIN_POLYS 100000     /* polygons, points and segments from which a stand-in is rendered */

typedef struct {
    float      yaw, pitch;          /* degrees: the view chosen */
    float      seen, back;          /* of its picture: the shares of faces seen from the front, from behind */
    float      score[FV_VIEWS];     /* every candidate's score */
    int        chosen;              /* its candidate */
    int        inside_out;          /* every face was seen from behind: the sides were swapped */
    SceneFront front;               /* where the model's front was taken to face */
    int        rendered;            /* candidates rendered (0: no memory; the geometry alone chose) */
    int        standin;             /* a stand-in was rendered (the scene is huge) */
    uint32_t   polys;               /* polygons rendered a view */
    uint32_t   prims;               /* points and segments rendered a view */
    double     ms;                  /* the time it took */
} FirstView;

/* Choose the first view of the scene's loaded objects (threads: for the
 * renders, 0 = one per core). The scene's camera is left as it was.
 * Always gives a view (without memory to render, scene_pick_view's). */
int   app_first_view(Scene *s, int threads, FirstView *out);
/* Candidate i's yaw (returned) and pitch (degrees). */
float app_view_candidate(int i, float *pitch_out);
/* A stand-in for a scene of FV_STANDIN_POLYS polygons, points and
 * segments or more (vertex clustering, standin.c), built into *out; -1
 * when the scene is small enough to render itself, or out of memory. */
int   app_standin(const Scene *s, Scene *out);

/* Load every file (or the demo scene when none) into a scene. Returns 0,
 * or -1 with "file:line: message" in err. app_load_scene_ex also gives
 * the automatic first view's choice (fv NULL: not wanted). */
int  app_load_scene(const Options *o, Scene *s, char *err, size_t errlen);
/* How the options say loads are sandboxed (--no-sandbox, --max-memory),
 * and the warning, once a run, of a system that cannot sandbox them. */
/* The loader's options from the command line, written once for every
 * path that loads (the command line's files, --check, the viewer's
 * first load, O and --watch): the caller adds only what is its own
 * (quiet, progress, cancel). And what applies to a mesh once loaded
 * (--flip, --points), the same on every path. */
MeshLoadOpts app_load_opts(const Options *o);
void         app_after_load(const Options *o, Mesh *m);
SandboxOpts app_sandbox_opts(const Options *o);
void app_sandbox_warn(const Options *o);
int  app_load_scene_ex(const Options *o, Scene *s, FirstView *fv, char *err, size_t errlen);
/* The second half of app_load_scene_ex: nfiles meshes (malloc'd array,
 * --flip and --points applied; taken over, freed on failure) into the
 * scene, placed and viewed as the options say. The viewer builds its
 * pictures while loading with it, so that they are what --print makes
 * of the same meshes. */
int  app_scene_from_meshes(const Options *o, Mesh *meshes, int nfiles, Scene *s, FirstView *fv, char *err,
                           size_t errlen);
/* The same scene while other threads read the meshes (scene_build_kept):
 * their faces stay until scene_release_faces, and on failure (-1, or 1
 * when the model is one scene_build scales down: not built) the meshes
 * and their array stay the caller's. */
int  app_scene_beside(const Options *o, Mesh *meshes, int nfiles, Scene *s, FirstView *fv, char *err,
                      size_t errlen);
/* Refuse (-1, the reason in err) a scene that, with its --grid copies,
 * would have more than --max-polys polygons, or, without --max-polys,
 * whose copies and one frame would need more memory than is available;
 * the message gives the count, an estimate of the memory and the limit
 * or the memory available. Called before the copies are made. */
int  app_check_size(const Options *o, const Scene *s, char *err, size_t errlen);
/* Path of the bundled demo scene (next to the binary or installed). */
const char *app_demo_path(void);

/* The problem in focus (focus.c): one of a check's items, on a scene
 * object, drawn over the picture by pipeline_render. */
typedef struct {
    const CheckItems *items;    /* NULL: none */
    uint32_t    item;
    int         obj;            /* the scene object it is on */
} ProblemFocus;

/* The colours of --overhang and --thickness over the scene's faces
 * (printtint.c), and what they were made for. */
typedef struct {
    FaceTint     ft;
    const Scene *key;
    uint32_t     key_gen;
    int          key_up, key_overhang, key_thickness;
    float        key_deg;
    double       key_limit;
    /* what the status bar and the report say of them */
    double       overhang_area; /* file units squared, over the loaded faces */
    double       thick_scale;   /* the ramp's blue end, file units (0: nothing measured) */
    double       thick_min;     /* the thinnest, file units */
} PrintTint;

/* Make p->tint for the scene and the pipeline's --overhang and
 * --thickness when either changed: 1 when the frame shades with it, 0
 * when neither is asked, -1 with the reason in err. */
struct Pipeline;
int  app_print_tint(struct Pipeline *p, char *err, size_t errlen);
void print_tint_free(PrintTint *t);
/* The ramp's scale in words for the status bar ("thickness red 0 to
 * blue 4 mm"), or "" when there is none. */
void print_tint_status(const struct Pipeline *p, char *buf, size_t len);

/* measuremarks.c: the measuring mode's marks on the picture. Draw the
 * marks, the lines between them and the cursor over p's last frame. */
struct Pipeline;
void app_measure_draw(struct Pipeline *p);
/* The cursor moved from where it is (none: the picture's middle) to
 * the nearest point visible in the last frame in the direction dx, dy
 * (screen, y down; 0, 0: the nearest to where it is): 0, or -1 when
 * there is none that way (the cursor stays). The points are vertices,
 * and with marks.wide edge midpoints and face centres too. */
int  app_measure_step(struct Pipeline *p, int dx, int dy);
/* The cursor moved to the visible point nearest the last frame's
 * sample (x, y) (a click; wide: edge midpoints and face centres too,
 * whatever marks.wide says): 0, or -1 when none is visible (the cursor
 * stays). */
int  app_measure_pick(struct Pipeline *p, double x, double y, int wide);
/* What the marks measure, in words: the cursor's point ("wide snap: "
 * first when it takes edge midpoints and face centres) and position
 * (not when brief), the distance and dx dy dz of two marks, the angle of
 * three; in file units (each object's file's coordinates). */
void app_measure_words(const Scene *s, const MeasureMarks *m, int brief, char *buf, size_t len);
/* One point as --marks writes it: "v12", "2:e3-4" (an edge's
 * midpoint), "f7" (a face's centre). */
void app_measure_pick_word(const MeasurePick *k, char *buf, size_t len);
/* One point of --marks' words at *s (vN, eA-B, fN, each optionally
 * after I: for object I): 0 with *out and *s past it, or -1. */
int  app_measure_pick_parse(const char **s, MeasurePick *out);
void app_measure_option(const MeasureMarks *m, char *buf, size_t len);

typedef struct Pipeline {
    Scene       *scene;
    const HsrAlgo *algo;
    HsrRunner    run;
    int          threads;
    ScreenPolys  sp;
    PolyOrder    order;         /* --order: polygons to the algorithm in this order */
    ReorderScratch reorder;
    FrameBufs    fb;
    Image        img;
    ShadeCache   shade_cache;
    CellGrid     cells;
    Viewport     vp;
    ShadeMode    shade;
    float        crease;        /* smooth shading's crease angle, degrees */
    int          highlight;     /* object shown highlighted, -1 none */
    int          edges;         /* outlines (--edges) */
    int          samples;       /* per pixel: 1, 4, 9 or 16 (rendered at sqrt x the size, averaged) */
    Image        img_ss;        /* the supersampled picture before averaging */
    HsrStats     st;
    double       project_ms, hsr_ms, shade_ms, cells_ms;
    /* points and lines (prims.c) */
    int          point_size;    /* pixels a side (times the samples' side in samples) */
    int          line_width;    /* pixels */
    int          wireframe;     /* every face edge as a line (the scene's wire is built on first use) */
    int          no_textures;   /* textured faces in their one colour */
    /* what --check found, on the model (Scene.marks, when a check set them) */
    int          problems;      /* problem edges drawn, faces seen from inside or crossing coloured */
    int          parts;         /* each part its own colour */
    MarkColours  markcol;       /* the faces' colours for those */
    /* will it print, on the model (printtint.c): faces coloured by a
     * question asked of the scene's meshes, made again when the scene
     * or the question changes */
    int          overhang;      /* --overhang: the faces past overhang_deg red */
    float        overhang_deg;
    int          thickness;     /* --thickness: the faces on the thickness ramp */
    double       thick_limit;   /* --min-thickness, file units (0: none): the ramp's middle */
    PrintTint    tint;
    MeasureMarks marks;         /* the points measured, drawn over the picture */
    ProblemFocus focus;         /* a problem drawn over the picture (items NULL: none) */
    /* the section planes (--section; the viewer's / ' \\ keys) */
    SectionPlane planes[SECTION_MAX];
    int          nplanes;
    int          cut_off;       /* the planes are kept but do not cut */
    SectionCut   cut;
    Scene        shade_view;    /* the scene with those colours, as shading reads it */
    PrimWork    *prims;
    /* the background and the contrast rule (backdrop.h), applied to img
     * once a backdrop is set */
    Backdrop     bd;
    int          has_bd;        /* bd is set: pipeline_render applies the rule */
    float        contrast;      /* the least OKLab L from it, 0 = colours as given */
    Contrast     rule;
} Pipeline;

int  pipeline_init(Pipeline *p, Scene *s, const HsrAlgo *algo, int threads);
int  pipeline_set_algo(Pipeline *p, const HsrAlgo *algo);
/* The scene is about to change in place (objects added or removed):
 * stop what reads it in the background (hzb-octree's tree builder) and
 * drop what was built from it (the trees, smooth normals, colours), so
 * that nothing stale or half-read outlives the change. Call before
 * touching the scene. Returns 0, or -1 out of memory (no runner then:
 * pipeline_set_algo again). */
int  pipeline_scene_changing(Pipeline *p);
/* The picture settings of the options: shading, crease, outlines, polygon
 * order, and samples when given (each output has its own default). */
void pipeline_apply_options(Pipeline *p, const Options *o);
void pipeline_free(Pipeline *p);
/* Project + hidden surfaces (+ shading when shade_too) for a w x h
 * picture: at (k w) x (k h) pixels when samples = k^2 > 1, the shaded
 * image then averaged down to w x h in img (fb holds the full-size
 * buffers: the exact render at the higher resolution). */
int  pipeline_render(Pipeline *p, int w, int h, float pixel_aspect, int cull, int shade_too);
/* The picture is seen on b: from now on pipeline_render keeps what it
 * draws p->contrast away from it (and the -o image is painted with it). */
void pipeline_set_backdrop(Pipeline *p, const Backdrop *b);
/* The backdrop of a text picture (the viewer, --print): --bg's colour,
 * painted; else the terminal's own, not painted, its colour as asked
 * (asked: the answer to the colour query, NULL when none came), else
 * from COLORFGBG, else taken for black. */
Backdrop pipeline_text_backdrop(const Options *o, const uint8_t *asked);
/* The side k of the k x k samples a pixel gets for a sample count. */
int  pipeline_samples_side(int samples);
/* Memory of one w x h frame at `samples` samples per pixel (dropped to
 * 1 as pipeline_render drops it) with `cells` text cells (0 for an
 * image): the buffers, the shaded and averaged images, the cells. */
uint64_t pipeline_frame_bytes(int w, int h, int samples, uint64_t cells);
/* Refuse (-1, the reason in err, starting with `what`) a frame larger
 * than SCREEN_MAX pixels on a side or whose memory is more than the
 * process can still take; called before anything is loaded. */
int  pipeline_check_frame(int w, int h, int samples, uint64_t cells, const char *what, char *err,
                          size_t errlen);
/* Why the last frame covers no pixel, as one line with the key or
 * option that fixes it ("the model is edge-on: try --view iso or turn
 * with the arrow keys"); NULL when something was drawn. */
const char *frame_empty_reason(const Pipeline *p);

/* focus.c: one problem in focus (the viewer's . and , keys, --problem
 * K). app_focus_object: the scene object item i of `it` is on (the
 * items of a check of the scene's files, file i its meshes[i]), -1 when
 * the scene has none such. app_focus_frame: the camera framed on it for
 * a w x h picture of pixel_aspect: the turn kept, moved and zoomed so
 * that it is in the middle at about a third of the picture; turned (to
 * the nearest of 26 directions where it shows) only when faces hide it
 * from there, as small renders on `threads` threads say. *turned_out
 * (may be NULL) says whether it turned. 0, or -1 out of memory.
 * app_focus_draw: the focus over the picture pipeline_render just made
 * (pipeline_render calls it). */
int  app_focus_object(const Scene *s, const CheckItems *it, uint32_t i);
int  app_focus_frame(Scene *s, const CheckItems *it, uint32_t i, int obj, int w, int h, float pixel_aspect,
                     int threads, int *turned_out);
void app_focus_draw(Pipeline *p);

/* report.c: what one rendered frame did, as --info --algo prints it and
 * the viewer's info panel (i) shows it: lines of a label ("polygons:")
 * and its text. out_ms is the time the frame took to reach the
 * terminal (cells and output), < 0 when there is none (--info). */
#define REPORT_LINES 8
#define REPORT_TEXT  256
typedef struct {
    const char *label;
    char        text[REPORT_TEXT];
} ReportLine;
int  frame_report(const Pipeline *p, double out_ms, ReportLine *lines, int max);

/* problems.c: the check of a scene's files (--problems, --parts, the
 * viewer's ! key): each file's MeshCheck (with the lists an overlay
 * draws) and their figures together. */
typedef struct {
    MeshCheck  *files;
    int         nfiles;
    CheckCounts all;            /* the files' figures summed */
    CheckItems  items;          /* the problems located, one by one (file i of the items is files[i]) */
} SceneCheck;
/* The most problems of one kind of one object the picture's check
 * locates (the viewer's . and , keys step through them). */
#define APP_CHECK_LOCATIONS 10000
/* Check meshes m[0..n) (scene_check_meshes' copies of the files; on any
 * thread; cancel as CheckOpts.cancel). 0, or -1 with the message. */
int  app_check_meshes(const Mesh *m, int n, int threads, const int *cancel, SceneCheck *out, char *err,
                      size_t errlen);
/* The same on the scene's files, then what it found set as the scene's
 * marks (on the calling thread: --print and -o); the problems one by
 * one and the figures into *keep when it is not NULL (the caller frees
 * it with scene_check_free). */
int  app_check_scene(Scene *s, int threads, SceneCheck *keep, char *err, size_t errlen);
void scene_check_free(SceneCheck *sc);
/* The verdict in a word or two for the status bar: "watertight", "3
 * holes · 12 flipped" (sep between the problems). Returns the number of
 * problems. */
int  check_verdict_short(const CheckCounts *c, const char *sep, char *buf, size_t len);
/* The same with at most max problems named and the rest counted ("6
 * holes · +3"; max 0: "4 problems"), so that a narrow status bar gives
 * way by whole items, never mid-word. */
int  check_verdict_items(const CheckCounts *c, const char *sep, int max, char *buf, size_t len);
/* Item i of `it` in words for the status bar: "hole 2 of 6 · 34 edges
 * · 1.2 mm", "crossing 3 of 161 · faces 920 and 3202" (sep between the
 * parts; of N: all of its kind in `all`, the figures the items come
 * from; lengths times scale, in unit when there is one); brief: "hole
 * 2/6". */
void check_item_words(const CheckItems *it, uint32_t i, const CheckCounts *all, const char *unit, double scale,
                      const char *sep, int brief, char *buf, size_t len);
/* The counts as lines of the info panel (labels as report.c's). */
int  check_report(const SceneCheck *sc, ReportLine *lines, int max);

/* The settings outside the scene that change the picture. */
typedef struct {
    int         mode;           /* DisplayMode, -1 = not part of the view (images) */
    ShadeMode   shade;
    float       crease;
    int         cull;
    int         samples;        /* 0 = the default */
    const char *algo;           /* NULL = the default */
    int         edges;          /* outlines (--edges) */
    int         wireframe;      /* --wireframe */
    int         point_size;     /* pixels, 0 or 1 = the default */
    int         line_width;     /* pixels, 0 or 1 = the default */
    int         no_textures;    /* textures hidden (--no-textures, t) */
    int         problems;       /* --problems (!) */
    int         parts;          /* --parts */
    int         overhang;       /* --overhang */
    float       overhang_deg;
    int         thickness;      /* --thickness */
    const MeasureMarks *marks;  /* the points measured (NULL: none) */
    const SectionPlane *planes; /* the section planes that cut the picture (none when the
                                   viewer's cut is off) */
    int         nplanes;
} ViewSettings;

/* viewcmd.c: the command line that reproduces the view (the files of o,
 * the scene's camera and placements, the settings v) into buf. Returns
 * 0, or -1 when buf is too small. */
int  view_command(char *buf, size_t len, const Options *o, const Scene *s, const ViewSettings *v);

int  default_threads(void);

/* folder.c: the command line's files, each folder replaced by the model
 * files in it (by name, or every regular file with all), sorted by name
 * folder by folder, its subfolders entered when recursive. Each folder
 * is entered once, however many links lead to it, at most
 * FOLDER_MAX_DEPTH deep. 0, or -1 with "DIR: reason" in err (a folder
 * named that cannot be read, no memory). */
#define FOLDER_MAX_DEPTH 64
typedef struct {
    char   **path;              /* owned */
    int      n, cap;
    int      folders;           /* folders named on the command line */
    uint64_t skipped;           /* entries that are no model file, or no regular file */
    uint64_t loops;             /* folders reached again (links), not entered again */
} FolderList;
int  folder_list(FolderList *l, const char *const *args, int nargs, int recursive, int all, char *err,
                 size_t errlen);
void folder_list_free(FolderList *l);

#endif
