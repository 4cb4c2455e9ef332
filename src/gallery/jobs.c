/* jobs.c: the gallery's tiles made on worker threads. Each worker takes
 * the next pending tile: first those the screen shows (gallery_jobs_want,
 * in the screen's order), then the rest in list order, so that the
 * first screen fills first and the status line's counts complete in
 * the background. A worker makes its tile in a copy of its own, outside
 * the lock (the load runs in a sandboxed child), and puts the result in
 * place under the lock: the UI thread reads tiles under it. Stopping
 * cancels the loads under way (MeshLoadOpts.cancel ends the child). */

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "gallery.h"
#include "thread.h"

#define JOBS_MAX 16

struct GalleryJobs {
    pthread_mutex_t mu;
    pthread_cond_t  work;       /* a tile was asked for, or stop */
    pthread_cond_t  done;       /* a tile was made */
    GalleryList    *l;
    GalleryLook     look;
    pthread_t       th[JOBS_MAX];
    int             nth;
    int             stop;       /* under mu; also read by the loads (atomically) */
    int            *want;       /* tiles asked for first, -1 taken */
    int             nwant;
    int             next;       /* the rest: the first that may be pending */
    int             made;       /* tiles made (the unreadable ones of the listing too) */
    int             stored;     /* tiles written back, pictured or checked */
};

/* The scheduling alone (the policy the tests replay step by step). */
int gallery_pick(GalleryList *l, const int *want, int nwant, int *next, int *what)
{
    GalleryTile *t = l->tile;
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < nwant; k++) {
            int i = want[k];
            if (i < 0 || i >= l->n || t[i].state != (pass ? GS_PICTURED : GS_PENDING))
                continue;
            t[i].state = pass ? GS_CHECKING : GS_WORKING;
            *what = pass ? TILE_CHECK : TILE_PICTURE;
            return i;
        }
    for (; *next < l->n; ++*next)
        if (t[*next].state == GS_PENDING || t[*next].state == GS_PICTURED) {
            *what = t[*next].state == GS_PENDING ? TILE_BOTH : TILE_CHECK;
            t[*next].state = t[*next].state == GS_PENDING ? GS_WORKING : GS_CHECKING;
            return (*next)++;
        }
    return -1;
}

static void *worker(void *arg)
{
    GalleryJobs *j = arg;
    pthread_mutex_lock(&j->mu);
    while (!j->stop) {
        int what, i = gallery_pick(j->l, j->want, j->nwant, &j->next, &what);
        if (i < 0) {
            pthread_cond_wait(&j->work, &j->mu);
            continue;
        }
        int back = j->l->tile[i].state == GS_CHECKING ? GS_PICTURED : GS_PENDING;
        GalleryTile t = j->l->tile[i];      /* the path stays put: the list does not grow */
        memset(&t.pic, 0, sizeof t.pic);
        pthread_mutex_unlock(&j->mu);
        int rc = gallery_tile_make(&t, &j->look, what);
        pthread_mutex_lock(&j->mu);
        GalleryTile *dst = &j->l->tile[i];
        if (j->stop && t.state == GS_UNREADABLE && strstr(t.verdict, "cancelled")) {
            dst->state = back;              /* stopped, not unreadable */
            image_free(&t.pic);
            continue;
        }
        if (rc && t.state >= GS_SOUND && t.state != GS_UNREADABLE) {
            size_t len = strlen(t.verdict);
            snprintf(t.verdict + len, sizeof t.verdict - len, " (no picture)");
        }
        if (what == TILE_CHECK)
            t.pic = dst->pic;               /* the picture made before stays */
        else
            image_free(&dst->pic);
        *dst = t;
        j->made += t.state >= GS_SOUND;
        j->stored++;
        pthread_cond_broadcast(&j->done);
    }
    pthread_mutex_unlock(&j->mu);
    return NULL;
}

GalleryJobs *gallery_jobs_start(GalleryList *l, const GalleryLook *look, int nthreads, const int *want, int nwant)
{
    GalleryJobs *j = calloc(1, sizeof *j);
    if (!j)
        return NULL;
    pthread_mutex_init(&j->mu, NULL);
    pthread_cond_init(&j->work, NULL);
    pthread_cond_init(&j->done, NULL);
    j->l = l;
    j->look = *look;
    j->look.cancel = &j->stop;
    for (int i = 0; i < l->n; i++)
        j->made += l->tile[i].state == GS_UNREADABLE;
    if (nthreads <= 0) {
        long c = sysconf(_SC_NPROCESSORS_ONLN);
        nthreads = c > 0 ? (int)c : 1;
    }
    nthreads = nthreads > JOBS_MAX ? JOBS_MAX : nthreads;
    if (nwant > 0)
        gallery_jobs_want(j, want, 0, nwant);   /* before any worker picks */
    for (int k = 0; k < nthreads; k++)
        if (thread_start(&j->th[j->nth], worker, j) == 0)
            j->nth++;
    if (!j->nth) {
        gallery_jobs_stop(j);
        return NULL;
    }
    return j;
}

void gallery_jobs_want(GalleryJobs *j, const int *order, int first, int n)
{
    pthread_mutex_lock(&j->mu);
    int *w = realloc(j->want, (size_t)(n > 0 ? n : 1) * sizeof *w);
    if (w) {
        j->want = w;
        j->nwant = n > 0 ? n : 0;
        for (int k = 0; k < j->nwant; k++)
            w[k] = order[first + k];
    }
    pthread_cond_broadcast(&j->work);
    pthread_mutex_unlock(&j->mu);
}

void gallery_jobs_lock(GalleryJobs *j)
{
    pthread_mutex_lock(&j->mu);
}

void gallery_jobs_unlock(GalleryJobs *j)
{
    pthread_mutex_unlock(&j->mu);
}

int gallery_jobs_stored(GalleryJobs *j)
{
    pthread_mutex_lock(&j->mu);
    int n = j->stored;
    pthread_mutex_unlock(&j->mu);
    return n;
}

void gallery_jobs_wait(GalleryJobs *j)
{
    pthread_mutex_lock(&j->mu);
    while (j->made < j->l->n)
        pthread_cond_wait(&j->done, &j->mu);
    pthread_mutex_unlock(&j->mu);
}

void gallery_jobs_stop(GalleryJobs *j)
{
    if (!j)
        return;
    pthread_mutex_lock(&j->mu);
    __atomic_store_n(&j->stop, 1, __ATOMIC_RELAXED);
    pthread_cond_broadcast(&j->work);
    pthread_mutex_unlock(&j->mu);
    for (int k = 0; k < j->nth; k++)
        pthread_join(j->th[k], NULL);
    pthread_cond_destroy(&j->work);
    pthread_cond_destroy(&j->done);
    pthread_mutex_destroy(&j->mu);
    free(j->want);
    free(j);
}
