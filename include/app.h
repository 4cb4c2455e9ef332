#ifndef ZV_APP_H
#define ZV_APP_H
/* app: the command line, and the pipeline that ties the stages together
 * (scene -> screen polygons -> hidden surfaces -> shading -> cells). The
 * one-shot outputs, the benchmark and the viewer all render through
 * pipeline_render(). */

#include "hsr.h"
#include "present.h"
#include "scene.h"
#include "screen.h"
#include "shade.h"

#define ZV_VERSION "0.1.0"
#define MAX_FILES 64
#define MAX_PLACE 64

/* --move, --turn, --scale: one object's placement. */
typedef enum { PLACE_MOVE, PLACE_TURN, PLACE_SCALE } PlaceKind;
typedef struct {
    PlaceKind kind;
    int       obj;              /* 0-based object index */
    float     v[3];             /* x y z, yaw pitch roll (degrees), or the scale in v[0] */
} Placement;

typedef struct {
    const char *files[MAX_FILES];
    int         nfiles;
    int         help, version, print, info, bench, bench_tty, json;
    const char *out;            /* -o FILE.png|FILE.ppm, "-" = standard output */
    int         image_format;   /* --image-format: IMG_PNG, IMG_PPM, or IMG_AUTO (by name) */
    const char *format;         /* --format: the model format, NULL = detect */
    int         formats;        /* --formats: list them */
    int         up;             /* --up: UpAxis */
    int         flip;           /* --flip: reverse every face's winding */
    const char *dump_ids;
    const char *dump_screen;
    int         w, h;           /* --size (0 = not given) */
    int         mode;           /* DisplayMode, -1 = from the locale */
    int         color;          /* ColorDepth, -1 = from the environment */
    int         shade;          /* ShadeMode */
    const char *algo;           /* name, "all", or a comma list (bench) */
    float       yaw, pitch, roll;   /* degrees */
    float       zoom;
    float       pan[2];         /* --pan, fractions of the scene radius */
    float       fit_from[3];    /* --fit-from yaw pitch roll, degrees */
    int         has_fit_from;
    Placement   place[MAX_PLACE];
    int         nplace;
    uint64_t    max_polys;      /* refuse bigger scenes */
    int         persp;          /* 1 = --persp given */
    float       fov;
    int         cull;
    int         views, threads, grid, fps;
} Options;

enum { IMG_AUTO, IMG_PNG, IMG_PPM };

/* Parse argv. Returns 0, or -1 with a message in err (a usage error). */
void cli_defaults(Options *o);
int  cli_parse(int argc, char **argv, Options *o, char *err, size_t errlen);
void cli_usage(FILE *f);

/* Load every file (or the demo scene when none) into a scene. Returns 0,
 * or -1 with "file:line: message" in err. */
int  app_load_scene(const Options *o, Scene *s, char *err, size_t errlen);
/* Path of the bundled demo scene (next to the binary or installed). */
const char *app_demo_path(void);

typedef struct {
    Scene       *scene;
    const HsrAlgo *algo;
    HsrRunner    run;
    int          threads;
    ScreenPolys  sp;
    FrameBufs    fb;
    Image        img;
    ShadeCache   shade_cache;
    CellGrid     cells;
    Viewport     vp;
    ShadeMode    shade;
    HsrStats     st;
    double       project_ms, hsr_ms, shade_ms, cells_ms;
} Pipeline;

int  pipeline_init(Pipeline *p, Scene *s, const HsrAlgo *algo, int threads);
int  pipeline_set_algo(Pipeline *p, const HsrAlgo *algo);
void pipeline_free(Pipeline *p);
/* Project + hidden surfaces (+ shading when shade_too). */
int  pipeline_render(Pipeline *p, int w, int h, float pixel_aspect, int cull, int shade_too);

/* The modes main() dispatches to; each returns the exit status. */
int  app_info(const Options *o, Scene *s);
int  app_bench(const Options *o, Scene *s);
int  app_oneshot(const Options *o, Scene *s);
int  app_viewer(const Options *o, Scene *s);   /* falls back to app_oneshot */
int  app_bench_tty(const Options *o);          /* bytes per frame of a scripted rotation */

int  default_threads(void);

#endif
