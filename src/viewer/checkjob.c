/* checkjob.c: the check behind --problems, --parts and the ! key, on a
 * thread of its own: the dragon's takes about a second, which the viewer
 * spends drawing and taking keys.
 *
 * The job owns its work: the files as meshes (scene_check_meshes copies
 * them on the UI thread) and what the check makes; the thread reads
 * nothing of the scene, which the viewer may edit meanwhile (O, X, E, a
 * file read again by --watch). The UI thread sets the result as the
 * scene's marks only if the scene is still the one it was made from
 * (Scene.gen); otherwise it is dropped and the check runs again. A job
 * the viewer no longer wants is cancelled (meshcheck_run stops at its
 * next step) and abandoned: the thread frees the job when it ends. */

#define _DEFAULT_SOURCE

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "thread.h"
#include "viewer_app.h"

struct CheckJob {
    pthread_mutex_t mu;
    pthread_t   th;
    int         done, abandoned;    /* under mu */
    int         cancel;             /* stored atomically: meshcheck_run stops */
    Mesh       *m;
    int         n, threads;
    uint32_t    gen;                /* the scene's generation it was made from */
    double      t0;
    int         rc;
    char        err[256];
    SceneCheck  res;
};

static void job_free(CheckJob *j)
{
    scene_check_meshes_free(j->m, j->n);
    scene_check_free(&j->res);
    pthread_mutex_destroy(&j->mu);
    free(j);
}

static void *job_main(void *arg)
{
    CheckJob *j = arg;
    j->rc = app_check_meshes(j->m, j->n, j->threads, &j->cancel, &j->res, j->err, sizeof j->err);
    pthread_mutex_lock(&j->mu);
    j->done = 1;
    int gone = j->abandoned;
    pthread_mutex_unlock(&j->mu);
    if (gone)
        job_free(j);
    return NULL;
}

static CheckJob *job_start(const Scene *s, int threads, char *err, size_t errlen)
{
    CheckJob *j = calloc(1, sizeof *j);
    if (!j) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    if (scene_check_meshes(s, &j->m, &j->n, err, errlen)) {
        free(j);
        return NULL;
    }
    j->threads = threads;
    j->gen = s->gen;
    j->t0 = now_ms();
    pthread_mutex_init(&j->mu, NULL);
    if (thread_start(&j->th, job_main, j)) {
        snprintf(err, errlen, "cannot start a thread to check the model");
        job_free(j);
        return NULL;
    }
    return j;
}

static int job_done(CheckJob *j)
{
    pthread_mutex_lock(&j->mu);
    int d = j->done;
    pthread_mutex_unlock(&j->mu);
    return d;
}

void checkjob_abandon(CheckJob *j)
{
    if (!j)
        return;
    pthread_t th = j->th;
    __atomic_store_n(&j->cancel, 1, __ATOMIC_RELAXED);
    pthread_mutex_lock(&j->mu);
    int done = j->done;
    j->abandoned = !done;
    pthread_mutex_unlock(&j->mu);
    if (done) {
        pthread_join(th, NULL);
        job_free(j);
    } else {
        pthread_detach(th);
    }
}

/* ==== The viewer's side ==== */

static int wanted(const App *a)
{
    return (a->p.problems || a->p.parts) && !a->sk.on;
}

/* ==== The problem in focus ==== */

void viewer_focus_clear(App *a)
{
    a->focus = -1;
    a->p.focus.items = NULL;
}

/* Item i in focus, the camera framed on it for the picture as last
 * drawn. */
static Reaction focus_go(App *a, uint32_t i)
{
    int obj = app_focus_object(a->s, &a->items, i), turned = 0;
    if (obj < 0)
        return RE_NONE;
    int w = a->p.vp.w > 0 ? a->p.vp.w : 80, h = a->p.vp.h > 0 ? a->p.vp.h : 48;
    float aspect = a->p.vp.pixel_aspect > 0 ? a->p.vp.pixel_aspect : 1;
    if (app_focus_frame(a->s, &a->items, i, obj, w, h, aspect, a->opt->threads, &turned)) {
        viewer_note(a, "out of memory framing the problem");
        return RE_DRAW;
    }
    a->focus = (int)i;
    a->p.focus = (ProblemFocus){ &a->items, i, obj };
    if (turned)
        viewer_note(a, "turned: hidden from the view before");
    return RE_RENDER;
}

/* A step asked before the check was done, or --problem K's. */
static Reaction focus_pending(App *a)
{
    Reaction r = RE_NONE;
    if (a->focus_want >= 0 || a->focus_step)
        a->note[0] = 0;         /* "checking: ..." said what is done now */
    if (a->focus_want >= 0 && (uint32_t)a->focus_want < a->items.n)
        r = focus_go(a, (uint32_t)a->focus_want);
    else if (a->focus_want >= 0)
        viewer_note(a, "--problem %d: the check found %u", a->focus_want + 1, a->items.n);
    else if (a->focus_step && a->items.n)
        r = focus_go(a, a->focus_step > 0 ? 0 : a->items.n - 1);
    else if (a->focus_step)
        viewer_note(a, "no problem to go to");
    a->focus_want = -1;
    a->focus_step = 0;
    return r;
}

Reaction viewer_problem_step(App *a, int step)
{
    if (a->sk.on)
        return RE_NONE;
    Reaction r = RE_NONE;
    if (!a->p.problems) {
        a->p.problems = 1;
        r = RE_RENDER;
    }
    /* the check of this scene not done yet: the step waits for it */
    if (a->chk || !a->s->marks.set || a->check_gen != a->s->gen) {
        a->focus_step = step;
        viewer_note(a, "checking: the problem comes when it is done");
        return r | RE_DRAW;
    }
    if (!a->items.n) {
        viewer_note(a, "no problem to go to");
        return r | RE_DRAW;
    }
    int n = (int)a->items.n;
    int i = a->focus < 0 ? (step > 0 ? 0 : n - 1) : ((a->focus + step) % n + n) % n;
    return r | focus_go(a, (uint32_t)i);
}

Reaction viewer_check_poll(App *a)
{
    Scene *s = a->s;
    if (!wanted(a))
        return RE_NONE;
    if (a->chk && job_done(a->chk)) {
        CheckJob *j = a->chk;
        a->chk = NULL;
        pthread_join(j->th, NULL);
        Reaction r = RE_NONE;       /* the scene changed meanwhile: checked again below */
        if (j->gen == s->gen) {
            r = RE_DRAW;
            if (j->rc)
                snprintf(a->check_err, sizeof a->check_err, "%.150s", j->err);
            else if (scene_marks_set(s, j->res.files, j->res.nfiles, a->check_err, sizeof a->check_err) == 0) {
                a->check = j->res.all;
                /* the problems one by one are the viewer's now */
                viewer_focus_clear(a);
                meshcheck_items_free(&a->items);
                a->items = j->res.items;
                memset(&j->res.items, 0, sizeof j->res.items);
                r = RE_RENDER | focus_pending(a);
            }
        }
        job_free(j);
        if (r != RE_NONE)
            return r;
    }
    if (a->chk && a->chk->gen != s->gen) {
        checkjob_abandon(a->chk);   /* for a scene that is gone */
        a->chk = NULL;
    }
    /* a scene edited since (its marks went with the edit): check it again */
    if (!a->chk && s->nobjs > 0 && (!a->check_started || a->check_gen != s->gen)) {
        a->check_started = 1;
        a->check_gen = s->gen;
        a->check_err[0] = 0;
        /* what was found is of a scene that is gone */
        viewer_focus_clear(a);
        meshcheck_items_free(&a->items);
        a->chk = job_start(s, a->opt->threads, a->check_err, sizeof a->check_err);
        return RE_DRAW;
    }
    return RE_NONE;
}

static void check_status(const App *a, int max_items, char *buf, size_t len);

/* --overhang's and --thickness's figures first (printtint.c), then the
 * check's */
void viewer_check_status(const App *a, int max_items, char *buf, size_t len)
{
    /* the measuring mode's figures outrank the rest (brief: the
     * cursor's coordinates give way) */
    if (a->measuring || a->p.marks.n) {
        app_measure_words(a->s, &a->p.marks, max_items == 0, buf, len);
        if (buf[0])
            return;
    }
    print_tint_status(&a->p, buf, len);
    size_t o = strlen(buf);
    if (o && max_items == 0)
        return;
    if (!o) {
        check_status(a, max_items, buf, len);
    } else if (o + 4 < len) {
        check_status(a, max_items, buf + o + 2, len - o - 2);
        if (buf[o + 2])
            memcpy(buf + o, ", ", 2);
        else
            buf[o] = 0;
    }
}

static void check_status(const App *a, int max_items, char *buf, size_t len)
{
    buf[0] = 0;
    if (a->diff && a->diff->gen == a->s->gen) {     /* --diff: its headline, while the scene is its own */
        diff_status(a->diff, max_items == 0, a->utf8 ? " \xc2\xb7 " : ", ", buf, len);
        return;
    }
    if (!wanted(a) || a->s->nobjs == 0)
        return;
    if (a->chk) {
        double t = (now_ms() - a->chk->t0) / 1000.0;
        snprintf(buf, len, "checking %.1fs", t);
    } else if (a->check_err[0]) {
        snprintf(buf, len, "check: %s", a->check_err);
    } else if (a->s->marks.set && a->focus >= 0 && (uint32_t)a->focus < a->items.n) {
        const CheckItem *e = &a->items.item[a->focus];
        const char *unit = e->file >= 0 && e->file < a->s->nmeshes ? a->s->meshes[e->file].info.unit : "";
        check_item_words(&a->items, (uint32_t)a->focus, &a->check, unit, ldexp(1, a->s->pos_exp),
                         a->utf8 ? " \xc2\xb7 " : ", ", max_items <= 0, buf, len);
    } else if (a->s->marks.set) {
        check_verdict_items(&a->check, a->utf8 ? " \xc2\xb7 " : ", ", max_items, buf, len);
    }
}

int viewer_check_report(const App *a, ReportLine *lines, int max)
{
    if (a->diff && a->diff->gen == a->s->gen)
        return diff_report_lines(a->diff, lines, max);
    if (!wanted(a) || a->chk || a->check_err[0] || !a->s->marks.set)
        return 0;
    SceneCheck sc = { .all = a->check };
    return check_report(&sc, lines, max);
}
