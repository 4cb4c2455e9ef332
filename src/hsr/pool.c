/* pool.c: persistent helper threads for fork-join work (pool.h).
 * Creating and joining threads every frame costs tens of microseconds
 * each and more on a loaded machine; a helper waiting on a condition
 * variable costs nothing and wakes in a few. */

#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdlib.h>

#include "pool.h"

#define POOL_MAX 64

typedef struct {
    Pool *pool;
    int   idx;              /* its part number: 1 .. helpers */
} Helper;

struct Pool {
    pthread_mutex_t mu;
    pthread_cond_t  go, done;
    unsigned        gen;        /* bumped for each pool_run */
    int             pending;    /* helpers' parts not finished yet */
    int             quit;
    PoolFn          fn;
    void           *arg;
    int             nparts;     /* of the current run */
    int             nth;        /* helpers running */
    pthread_t       th[POOL_MAX];
    Helper          helper[POOL_MAX];
};

static void *helper_main(void *a)
{
    Helper *h = a;
    Pool *p = h->pool;
    unsigned seen = 0;
    pthread_mutex_lock(&p->mu);
    for (;;) {
        while (p->gen == seen && !p->quit)
            pthread_cond_wait(&p->go, &p->mu);
        if (p->quit)
            break;
        seen = p->gen;
        if (h->idx >= p->nparts)
            continue;           /* no part for it this time */
        PoolFn fn = p->fn;
        void *arg = p->arg;
        pthread_mutex_unlock(&p->mu);
        fn(arg, h->idx);
        pthread_mutex_lock(&p->mu);
        if (--p->pending == 0)
            pthread_cond_signal(&p->done);
    }
    pthread_mutex_unlock(&p->mu);
    return NULL;
}

Pool *pool_create(int helpers)
{
    Pool *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    if (helpers > POOL_MAX - 1)
        helpers = POOL_MAX - 1;
    pthread_mutex_init(&p->mu, NULL);
    pthread_cond_init(&p->go, NULL);
    pthread_cond_init(&p->done, NULL);
    for (int i = 0; i < helpers; i++) {
        p->helper[i].pool = p;
        p->helper[i].idx = i + 1;
        if (pthread_create(&p->th[i], NULL, helper_main, &p->helper[i]) != 0)
            break;
        p->nth = i + 1;
    }
    return p;
}

int pool_helpers(const Pool *p)
{
    return p ? p->nth : 0;
}

void pool_run(Pool *p, int nparts, PoolFn fn, void *arg)
{
    int on_helpers = 0;
    if (p && nparts > 1) {
        on_helpers = nparts - 1 < p->nth ? nparts - 1 : p->nth;
        pthread_mutex_lock(&p->mu);
        p->fn = fn;
        p->arg = arg;
        p->nparts = on_helpers + 1;
        p->pending = on_helpers;
        p->gen++;
        pthread_cond_broadcast(&p->go);
        pthread_mutex_unlock(&p->mu);
    }
    fn(arg, 0);
    for (int i = on_helpers + 1; i < nparts; i++)
        fn(arg, i);             /* more parts than helpers: the caller does them */
    if (on_helpers) {
        pthread_mutex_lock(&p->mu);
        while (p->pending > 0)
            pthread_cond_wait(&p->done, &p->mu);
        pthread_mutex_unlock(&p->mu);
    }
}

void pool_free(Pool *p)
{
    if (!p)
        return;
    pthread_mutex_lock(&p->mu);
    p->quit = 1;
    pthread_cond_broadcast(&p->go);
    pthread_mutex_unlock(&p->mu);
    for (int i = 0; i < p->nth; i++)
        pthread_join(p->th[i], NULL);
    pthread_mutex_destroy(&p->mu);
    pthread_cond_destroy(&p->go);
    pthread_cond_destroy(&p->done);
    free(p);
}
