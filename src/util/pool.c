/* pool.c: persistent helper threads for fork-join work (pool.h).
 * Creating and joining threads every frame costs tens of microseconds
 * each and more on a loaded machine; a helper waiting on a condition
 * variable costs nothing and wakes in a few.
 *
 * Tasks are claimed one at a time from a shared counter, by the caller
 * as well as the helpers: when a woken helper does not get a core at
 * once, the caller takes its tasks rather than wait for it. A helper
 * joins a run under the lock (running++) and reads the run's function
 * then; a new run starts only when no helper is still in the last one,
 * so no helper can take a task of one run with another's function. */

#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdlib.h>

#include "thread.h"
#include "pool.h"

#define POOL_MAX 64

typedef struct {
    Pool *pool;
    int   idx;              /* its worker number: 1 .. helpers */
} Helper;

struct Pool {
    pthread_mutex_t mu;
    pthread_cond_t  go, done;
    unsigned        gen;        /* bumped for each pool_run */
    int             running;    /* helpers inside a run */
    int             quit;
    PoolFn          fn;
    void           *arg;
    int             ntasks;
    int             next;       /* next task to claim (atomic) */
    int             nth;        /* helpers running */
    pthread_t       th[POOL_MAX];
    Helper          helper[POOL_MAX];
};

/* Claim and run tasks until none is left. */
static void take_tasks(Pool *p, PoolFn fn, void *arg, int ntasks, int worker)
{
    for (;;) {
        int t = __atomic_fetch_add(&p->next, 1, __ATOMIC_ACQ_REL);
        if (t >= ntasks)
            return;
        fn(arg, t, worker);
    }
}

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
        p->running++;
        PoolFn fn = p->fn;
        void *arg = p->arg;
        int ntasks = p->ntasks;
        pthread_mutex_unlock(&p->mu);
        take_tasks(p, fn, arg, ntasks, h->idx);
        pthread_mutex_lock(&p->mu);
        if (--p->running == 0)
            pthread_cond_broadcast(&p->done);
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
        if (thread_start(&p->th[i], helper_main, &p->helper[i]) != 0)
            break;
        p->nth = i + 1;
    }
    return p;
}

int pool_helpers(const Pool *p)
{
    return p ? p->nth : 0;
}

void pool_run(Pool *p, int ntasks, PoolFn fn, void *arg)
{
    if (!p || p->nth == 0 || ntasks < 2) {
        for (int t = 0; t < ntasks; t++)
            fn(arg, t, 0);
        return;
    }
    pthread_mutex_lock(&p->mu);
    while (p->running > 0)      /* a late helper still leaving the last run */
        pthread_cond_wait(&p->done, &p->mu);
    p->fn = fn;
    p->arg = arg;
    p->ntasks = ntasks;
    __atomic_store_n(&p->next, 0, __ATOMIC_RELEASE);
    p->gen++;
    pthread_cond_broadcast(&p->go);
    pthread_mutex_unlock(&p->mu);
    take_tasks(p, fn, arg, ntasks, 0);
    pthread_mutex_lock(&p->mu);
    while (p->running > 0)      /* helpers finishing the tasks they took */
        pthread_cond_wait(&p->done, &p->mu);
    pthread_mutex_unlock(&p->mu);
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
