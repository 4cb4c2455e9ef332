#ifndef ZV_POOL_H
#define ZV_POOL_H
/* pool: a few persistent helper threads for fork-join work. The front end
 * (project.c) and the band runner (hsr.c) each keep one, so a frame
 * starts no thread: pool_run() wakes the helpers and the caller and they
 * take the tasks one at a time until none is left. A helper that is slow
 * to get a core (a loaded machine) finds its tasks done by the caller
 * instead of holding it up. */

/* Task `task` of a run, on worker `worker`: 0 is the caller, 1 .. helpers
 * the helpers; a worker runs one task at a time. */
typedef void (*PoolFn)(void *arg, int task, int worker);
typedef struct Pool Pool;

/* Start up to `helpers` threads, at most 63 (a run's workers are the
 * caller and the helpers: 64, SCREEN_MAX_THREADS), fewer when the system
 * refuses more.
 * NULL when out of memory; a pool with no helper is fine: pool_run()
 * then runs every task on the caller. */
Pool *pool_create(int helpers);
int   pool_helpers(const Pool *p);          /* helper threads running */
/* Run fn(arg, task, worker) for every task in [0, ntasks), in any order,
 * on the caller and the helpers; returns when all are done. p may be
 * NULL (the caller alone). */
void  pool_run(Pool *p, int ntasks, PoolFn fn, void *arg);
void  pool_free(Pool *p);

#endif
