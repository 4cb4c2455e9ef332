/* firstload.c: the command line's big file loaded while the viewer
 * already runs, with a picture of what is parsed so far (issue 21). The
 * viewer starts on an empty scene at once; a loader thread runs the
 * load (in the sandbox, as every load) and builds the scene as
 * app_load_scene does; a preview thread meanwhile takes what the loader
 * has published (meshprefix.h: the vertices as points, then the faces
 * so far) and builds a scene of it with the same function
 * (app_scene_from_meshes), so that a picture while loading is what
 * --print makes of a file cut there. The UI thread only swaps finished
 * scenes in, between frames: keys are answered all along.
 *
 * Previews are rebuilt when the prefix has doubled, or has stopped
 * growing, never sooner than three times the last build's time after
 * it (building takes at most a quarter of a core from the parse), and
 * only when the picture comes within the first third of the wait for
 * the whole model (after that the loader stops copying for pictures). The vertices are shown
 * as points up to 2M of them, then the faces as they come. The camera
 * is fitted to each new scene until the user turns or moves it; from
 * then on it stays.
 *
 * The job is shared by three threads; whichever lets go of it last
 * frees it, so that q mid-load neither waits for the loader nor for a
 * preview being built. */

#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "clock.h"
#include "meshprefix.h"
#include "safetext.h"
#include "thread.h"
#include "viewer_app.h"

/* Files smaller than this load before the viewer starts, as they always
 * did (a fraction of a second): a picture while loading is for the big. */
#define FIRST_LOAD_MIN_BYTES ((uint64_t)32 << 20)
#define PREVIEW_MIN_MS 100      /* previews at most this often ... */
#define PREVIEW_IDLE_MS 50      /* ... the prefix looked at this often */
/* Points are not refined past this many: a terminal's picture of more
 * looks the same, and building them takes time from the parse. */
#define PREVIEW_POINTS_MAX 2000000
#define PREVIEW_SLACK 3         /* a picture comes within the first 1/PREVIEW_SLACK of the wait */

struct FirstLoad {
    pthread_mutex_t mu;
    pthread_cond_t  cv;         /* wakes the preview thread: done or cancelled */
    pthread_t       loader, previewer;
    int             refs;       /* under mu: the UI and the threads still holding the job */
    int             cancelled;  /* under mu */
    int             done;       /* under mu: the loader has finished (rc, err, final) */
    int             stop;       /* atomic, MeshLoadOpts.cancel */
    Options         o;
    char            path[4096];
    MeshLoadOpts    lo;
    SandboxOpts     so;
    MeshProgress    prog;
    MeshPrefix     *prefix;     /* NULL: no picture while loading */
    double          t0;
    /* the results, under mu */
    int             rc;
    char            err[512];
    Scene           final;
    Scene           preview;
    int             have_preview;
};

static void release(FirstLoad *f)
{
    pthread_mutex_lock(&f->mu);
    int last = --f->refs == 0;
    pthread_mutex_unlock(&f->mu);
    if (!last)
        return;
    if (f->have_preview)
        scene_free(&f->preview);
    if (f->done && f->rc == 0)
        scene_free(&f->final);
    mesh_prefix_free(f->prefix);
    pthread_cond_destroy(&f->cv);
    pthread_mutex_destroy(&f->mu);
    free(f);
}

static int is_cancelled(FirstLoad *f)
{
    pthread_mutex_lock(&f->mu);
    int c = f->cancelled;
    pthread_mutex_unlock(&f->mu);
    return c;
}

/* One mesh into a scene as the command line places and views it. */
static int build(FirstLoad *f, Mesh *m, Scene *s, char *err, size_t errlen)
{
    app_after_load(&f->o, m);
    return app_scene_from_meshes(&f->o, m, 1, s, NULL, err, errlen);
}

static void *loader_main(void *arg)
{
    FirstLoad *f = arg;
    Mesh *m = calloc(1, sizeof *m);
    Scene s = { 0 };
    char err[512] = "out of memory";
    int rc = -1;
    if (m && sandbox_load(m, f->path, &f->lo, &f->so, err, sizeof err) == 0) {
        if (is_cancelled(f)) {
            mesh_free(m);       /* nobody wants it: no scene built */
            free(m);
        } else {
            rc = build(f, m, &s, err, sizeof err);     /* takes m, freed when it fails */
        }
        m = NULL;
    }
    free(m);
    pthread_mutex_lock(&f->mu);
    f->done = 1;
    f->rc = rc;
    if (rc == 0)
        f->final = s;
    snprintf(f->err, sizeof f->err, "%s", err);
    pthread_cond_broadcast(&f->cv);
    pthread_mutex_unlock(&f->mu);
    release(f);
    return NULL;
}

/* Sleep until `until` (now_ms) unless the load ends: 1 to go on. */
static int nap(FirstLoad *f, double until)
{
    pthread_mutex_lock(&f->mu);
    while (!f->done && !f->cancelled) {
        double left = until - now_ms();
        if (left <= 0)
            break;
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        long ns = ts.tv_nsec + (long)(left * 1e6);
        ts.tv_sec += ns / 1000000000L;
        ts.tv_nsec = ns % 1000000000L;
        pthread_cond_timedwait(&f->cv, &f->mu, &ts);
    }
    int go = !f->done && !f->cancelled;
    pthread_mutex_unlock(&f->mu);
    return go;
}

/* Worth a new picture: the first, twice the last (so that all the
 * pictures together cost about what the last does), or no longer
 * growing (a slow stretch, or the end of what will come before the
 * whole: the picture then shows all of it). */
static int worth(uint64_t n, uint64_t built, uint64_t seen)
{
    return n != built && (built == 0 || n - built >= built || n == seen);
}

/* Would a picture of n vertices and faces, at took_per ms each (the
 * last build's pace), come well before the whole model: within the
 * first 1/PREVIEW_SLACK of the wait for it? The wait is the parse's
 * rest at its pace so far, and the whole model's build, its size
 * judged from the bytes (at the same pace: a small build's fixed costs
 * make both estimates high alike). A picture that would not only slows
 * the whole down: the builds share the cores. */
static int in_time(FirstLoad *f, double took_per, uint64_t n)
{
    uint64_t done = __atomic_load_n(&f->prog.done, __ATOMIC_RELAXED);
    uint64_t total = __atomic_load_n(&f->prog.total, __ATOMIC_RELAXED);
    if (took_per <= 0 || done == 0 || total <= done)
        return total == 0 || done < total;
    double spent = now_ms() - f->t0, grow = (double)total / (double)done;
    double wait = spent * (grow - 1) + took_per * (double)n * grow;
    return took_per * (double)n * PREVIEW_SLACK < wait;
}

static void preview_once(FirstLoad *f)
{
    Mesh *m = calloc(1, sizeof *m);
    if (!m)
        return;
    if (mesh_prefix_take(f->prefix, f->path, m) != 0) {
        free(m);
        return;
    }
    Scene s;
    char err[256];
    if (build(f, m, &s, err, sizeof err))
        return;                 /* (freed) a picture fewer */
    pthread_mutex_lock(&f->mu);
    if (f->have_preview)
        scene_free(&f->preview);    /* the UI did not take the last one: this is newer */
    f->preview = s;
    f->have_preview = 1;
    pthread_mutex_unlock(&f->mu);
}

static void *previewer_main(void *arg)
{
    FirstLoad *f = arg;
    uint64_t built = 0, seen = 0;   /* vertices while there are no faces, then vertices + faces */
    double took_per = 0;            /* the last build's milliseconds per vertex and face */
    int faces = 0;
    double next = now_ms();
    while (nap(f, next)) {
        uint64_t nv, nf;
        mesh_prefix_counts(f->prefix, &nv, &nf);
        if (nf && !faces)
            faces = 1, built = seen = 0;    /* the first faces: points no more */
        /* a picture costs for its vertices and its faces alike: it is
         * the sum that doubles (a file's vertices come first, so that
         * faces doubling from the first few would mean a dozen pictures
         * of every vertex) */
        uint64_t n = faces ? nv + nf : nv;
        if (!worth(n, built, seen) || (!faces && built && n > PREVIEW_POINTS_MAX)) {
            seen = n;
            next = now_ms() + PREVIEW_IDLE_MS;
            continue;
        }
        /* a build costs for its vertices and its faces alike */
        if (!in_time(f, took_per, nv + nf)) {
            /* with faces there, a later picture would be later still:
             * the loader need not copy more for pictures to come */
            if (faces)
                mesh_prefix_stop(f->prefix);
            next = now_ms() + PREVIEW_IDLE_MS;
            continue;
        }
        double t0 = now_ms();
        preview_once(f);
        built = seen = n;
        double took = now_ms() - t0;
        took_per = took / (double)(nv + nf);
        /* a picture of faces whose double would come too late, or of
         * as many faces as the loader publishes, is the last: the loader's copy is given back now, not when the load
         * ends (on the 31M model the copy held 566 MB in the loader at
         * its most resident moment) */
        if (faces && (nf >= MESH_PREFIX_FACES_MAX || !in_time(f, took_per, 2 * (nv + nf))))
            mesh_prefix_stop(f->prefix);
        next = now_ms() + (3 * took > PREVIEW_MIN_MS ? 3 * took : PREVIEW_MIN_MS);
    }
    release(f);
    return NULL;
}

/* ==== The UI's side ==== */

int viewer_loads_first(const Options *o)
{
    struct stat st;
    const char *t = getenv("TERM");
    return o->nfiles == 1 && !o->sketch && !o->print_view && strcmp(o->files[0], "-") &&
           isatty(STDIN_FILENO) && isatty(STDOUT_FILENO) && t && *t && strcmp(t, "dumb") &&
           stat(o->files[0], &st) == 0 && S_ISREG(st.st_mode) && (uint64_t)st.st_size >= FIRST_LOAD_MIN_BYTES;
}

/* ZV_TEST_HOLD=FACES:PATH (tests): the loader stops after publishing
 * FACES faces until PATH exists, so that a test sees a picture of a
 * known prefix for as long as it wants. PATH must be in the model's
 * folder: the sandboxed child looks for it, and Landlock lets it see
 * nothing else. */
static void test_hold(MeshPrefix *p)
{
    const char *h = getenv("ZV_TEST_HOLD");
    char *end;
    unsigned long long faces = h ? strtoull(h, &end, 10) : 0;
    if (p && faces && *end == ':' && end[1])
        mesh_prefix_hold(p, faces, end + 1);
}

FirstLoad *firstload_start(const Options *o, char *err, size_t errlen)
{
    FirstLoad *f = calloc(1, sizeof *f);
    if (!f || snprintf(f->path, sizeof f->path, "%s", o->files[0]) >= (int)sizeof f->path) {
        snprintf(err, errlen, f ? "path too long" : "out of memory");
        free(f);
        return NULL;
    }
    app_sandbox_warn(o);        /* before the screen covers standard error */
    f->o = *o;
    f->lo = app_load_opts(o);
    f->lo.quiet = 1;            /* curses owns the terminal: warnings go to the status bar */
    f->lo.progress = &f->prog;
    f->lo.cancel = &f->stop;
    f->so = app_sandbox_opts(o);
    struct stat st;
    if (stat(f->path, &st) == 0)
        f->prefix = mesh_prefix_new((uint64_t)st.st_size);
    test_hold(f->prefix);
    f->lo.prefix = f->prefix;
    f->t0 = now_ms();
    pthread_mutex_init(&f->mu, NULL);
    pthread_cond_init(&f->cv, NULL);
    f->refs = 2 + (f->prefix != NULL);
    if (thread_start(&f->loader, loader_main, f)) {
        snprintf(err, errlen, "cannot start a thread to load it");
        mesh_prefix_free(f->prefix);
        pthread_cond_destroy(&f->cv);
        pthread_mutex_destroy(&f->mu);
        free(f);
        return NULL;
    }
    pthread_detach(f->loader);
    if (f->prefix && thread_start(&f->previewer, previewer_main, f) == 0)
        pthread_detach(f->previewer);
    else if (f->prefix)
        release(f);             /* no previews: the load goes on */
    return f;
}

void firstload_abandon(FirstLoad *f)
{
    if (!f)
        return;
    pthread_mutex_lock(&f->mu);
    f->cancelled = 1;
    __atomic_store_n(&f->stop, 1, __ATOMIC_RELAXED);
    pthread_cond_broadcast(&f->cv);
    pthread_mutex_unlock(&f->mu);
    release(f);
}

/* A new scene in place of the viewer's: the camera fitted to it unless
 * the user has turned or moved the last one. */
static Reaction install(App *a, Scene *s)
{
    if (pipeline_scene_changing(&a->p)) {
        scene_free(s);
        viewer_note(a, "out of memory");
        return RE_DRAW;
    }
    Camera cam = a->s->cam;
    int moved = memcmp(&cam, &a->first_cam, sizeof cam) != 0;
    scene_free(a->s);
    *a->s = *s;
    if (moved)
        a->s->cam = cam;
    else
        a->opening = a->s->cam;     /* r goes back to the fitted view */
    a->first_cam = a->s->cam;
    a->sel = -1;
    viewer_update_name(a);
    return RE_RENDER;
}

Reaction viewer_first_poll(App *a)
{
    FirstLoad *f = a->first;
    /* sketch mode holds its own scene in a->s: the pictures wait */
    if (!f || a->sk.on)
        return RE_NONE;
    Scene s;
    int have = 0, done;
    pthread_mutex_lock(&f->mu);
    done = f->done;
    if (done && f->rc == 0) {
        s = f->final;
        f->rc = 1;              /* taken */
        have = 1;
    } else if (!done && f->have_preview) {
        s = f->preview;
        f->have_preview = 0;
        have = 1;
    }
    if (done && f->rc < 0)
        snprintf(a->load_err, sizeof a->load_err, "%s", f->err);
    pthread_mutex_unlock(&f->mu);
    if (done && !have) {
        firstload_abandon(f);
        a->first = NULL;
        return RE_QUIT;         /* the load failed: the viewer says why as it ends */
    }
    Reaction r = have ? install(a, &s) : RE_DRAW;   /* (the bar's progress) */
    if (done) {
        firstload_abandon(f);
        a->first = NULL;
        for (int i = 0; i < a->s->nmeshes; i++)
            if (a->s->meshes[i].info.warnings) {
                viewer_warning_note(a, &a->s->meshes[i].info, a->s->meshes[i].path ? a->s->meshes[i].path : "?");
                break;
            }
        a->tex = texjob_start(a->s, a->opt);
    }
    return r;
}

void firstload_status(FirstLoad *f, char *buf, size_t len)
{
    const char *slash = strrchr(f->path, '/');
    const char *name = slash && slash[1] ? slash + 1 : f->path;
    uint64_t done = __atomic_load_n(&f->prog.done, __ATOMIC_RELAXED);
    uint64_t total = __atomic_load_n(&f->prog.total, __ATOMIC_RELAXED);
    double s = (now_ms() - f->t0) / 1000.0;
    if (total > 0)
        snprintf(buf, len, "loading %s %d%%", name, (int)(100.0 * (double)done / (double)total));
    else
        snprintf(buf, len, "loading %s %.1fs", name, s);
}

int firstload_now(const Options *o, Scene *s)
{
    char err[512];
    scene_free(s);
    if (app_load_scene(o, s, err, sizeof err) == 0)
        return 0;
    memset(s, 0, sizeof *s);    /* (the caller frees it again) */
    safetext_line(stderr, "zview: %s", err);
    return -1;
}
