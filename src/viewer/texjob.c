/* texjob.c: big textures decoded on a thread of their own, after the
 * first picture. The viewer loads with MeshLoadOpts.tex_defer_side set:
 * an image longer than that a side (a 16k x 16k PNG takes seconds) is
 * left pending, its faces in their base colours, and this job decodes
 * the pending images one after the other while the viewer draws and
 * takes keys, each in a sandboxed child of its own under its own memory
 * bound (sandbox_texture_decode): the bytes are a stranger's, as the
 * model's are, and an image that claims 65000 x 65000 pixels must cost
 * the viewer nothing. The UI thread puts each finished one in place
 * between frames (texjob_poll) and draws again.
 *
 * The job owns its work: the sources (a path, or the image's bytes) move
 * from the meshes into it when it starts, and the textures it makes stay
 * its own until the UI thread installs them. The thread reads nothing of
 * the scene, which the viewer may edit meanwhile (O, X, E): a texture
 * whose mesh went is dropped at install. A job the viewer no longer
 * wants (it quits) is abandoned: the thread frees the job when it ends. */

#define _DEFAULT_SOURCE

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "thread.h"
#include "viewer_app.h"

typedef struct {
    MeshTexture *target;        /* where it goes (compared, never read by the thread) */
    MeshTexture  src;           /* name, path or bytes, wrap modes: the thread's copy */
    Texture      img;
    int          halved, rc;
    int          done;          /* under mu */
    int          installed;     /* UI thread only */
    char         err[256];
} TexWork;

struct TexJob {
    pthread_mutex_t mu;
    pthread_t    th;
    TexWork     *work;
    int          n;
    int          finished;      /* under mu: the thread has ended its loop */
    int          abandoned;     /* under mu: the thread frees the job */
    int          cancelled;     /* under mu */
    int          stop;          /* the same, atomic: ends the child decoding */
    SandboxOpts  so;
};

static void job_free(TexJob *j)
{
    for (int i = 0; i < j->n; i++) {
        texture_free(&j->work[i].img);
        free(j->work[i].src.name);
        free(j->work[i].src.path);
        free(j->work[i].src.data);
    }
    free(j->work);
    pthread_mutex_destroy(&j->mu);
    free(j);
}

static void *job_main(void *arg)
{
    TexJob *j = arg;
    for (int i = 0; i < j->n; i++) {
        pthread_mutex_lock(&j->mu);
        int stop = j->cancelled;
        pthread_mutex_unlock(&j->mu);
        if (stop)
            break;
        TexWork *w = &j->work[i];
        w->rc = sandbox_texture_decode(&w->src, &j->so, &j->stop, &w->img, &w->halved, w->err, sizeof w->err);
        pthread_mutex_lock(&j->mu);
        w->done = 1;
        pthread_mutex_unlock(&j->mu);
    }
    pthread_mutex_lock(&j->mu);
    j->finished = 1;
    int mine = j->abandoned;
    pthread_mutex_unlock(&j->mu);
    if (mine)
        job_free(j);
    return NULL;
}

TexJob *texjob_start(Scene *s, const Options *o)
{
    int n = 0;
    for (int i = 0; i < s->nmeshes; i++)
        for (uint32_t k = 0; k < s->meshes[i].ntex; k++)
            n += s->meshes[i].tex[k].state == MTEX_PENDING;
    if (!n)
        return NULL;
    TexJob *j = calloc(1, sizeof *j);
    TexWork *w = j ? calloc((size_t)n, sizeof *w) : NULL;
    if (!w) {
        free(j);
        return NULL;            /* they stay pending: the faces keep their base colours */
    }
    j->work = w;
    j->so = app_sandbox_opts(o);
    for (int i = 0; i < s->nmeshes; i++)
        for (uint32_t k = 0; k < s->meshes[i].ntex; k++) {
            MeshTexture *t = &s->meshes[i].tex[k];
            if (t->state != MTEX_PENDING)
                continue;
            TexWork *x = &w[j->n++];
            x->target = t;
            x->src = *t;
            x->src.name = strdup(t->name);
            /* the source moves into the job */
            t->path = NULL;
            t->data = NULL;
            t->len = 0;
        }
    pthread_mutex_init(&j->mu, NULL);
    if (thread_start(&j->th, job_main, j)) {
        /* no thread: put the sources back, still pending */
        for (int i = 0; i < j->n; i++) {
            j->work[i].target->path = j->work[i].src.path;
            j->work[i].target->data = j->work[i].src.data;
            j->work[i].target->len = j->work[i].src.len;
            j->work[i].src.path = NULL;
            j->work[i].src.data = NULL;
        }
        job_free(j);
        return NULL;
    }
    return j;
}

/* Is t still a pending texture of one of s's meshes? */
static int still_there(const Scene *s, const MeshTexture *t, const char *name)
{
    for (int i = 0; i < s->nmeshes; i++) {
        const Mesh *m = &s->meshes[i];
        if (m->ntex && t >= m->tex && t < m->tex + m->ntex)
            return t->state == MTEX_PENDING && (!name || strcmp(t->name, name) == 0);
    }
    return 0;
}

int texjob_poll(TexJob **jp, Scene *s, char *note, size_t notelen)
{
    TexJob *j = *jp;
    if (!j)
        return 0;
    int put = 0;
    pthread_mutex_lock(&j->mu);
    int finished = j->finished;
    pthread_mutex_unlock(&j->mu);
    for (int i = 0; i < j->n; i++) {
        TexWork *w = &j->work[i];
        pthread_mutex_lock(&j->mu);
        int done = w->done;
        pthread_mutex_unlock(&j->mu);
        if (!done || w->installed)
            continue;
        w->installed = 1;
        if (!still_there(s, w->target, w->src.name))
            continue;           /* its mesh left the scene */
        mesh_texture_install(w->target, w->rc, &w->img, w->halved);
        if (w->rc)
            snprintf(note, notelen, "texture %s: %s; its faces show their base colour",
                     w->src.name ? w->src.name : "?", w->err);
        put = 1;
    }
    if (finished) {
        pthread_join(j->th, NULL);
        job_free(j);
        *jp = NULL;
    }
    return put;
}

void texjob_status(TexJob *j, char *buf, size_t len)
{
    int done = 0;
    pthread_mutex_lock(&j->mu);
    for (int i = 0; i < j->n; i++)
        done += j->work[i].done;
    pthread_mutex_unlock(&j->mu);
    snprintf(buf, len, "decoding textures %d/%d", done, j->n);
}

void texjob_abandon(TexJob *j)
{
    if (!j)
        return;
    pthread_mutex_lock(&j->mu);
    j->cancelled = 1;
    __atomic_store_n(&j->stop, 1, __ATOMIC_RELAXED);
    int ended = j->finished;
    j->abandoned = !ended;
    pthread_mutex_unlock(&j->mu);
    if (ended) {
        pthread_join(j->th, NULL);
        job_free(j);
    } else {
        pthread_detach(j->th);
    }
}
