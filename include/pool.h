#ifndef ZV_POOL_H
#define ZV_POOL_H
/* pool: a few persistent helper threads for fork-join work. The front end
 * (project.c) and the band runner (hsr.c) each keep one, so a frame
 * starts no thread: pool_run() wakes the helpers, runs part 0 on the
 * caller, and returns when every part is done. */

typedef void (*PoolFn)(void *arg, int part);
typedef struct Pool Pool;

/* Start up to `helpers` threads (fewer when the system refuses more).
 * NULL when out of memory; a pool with no helper is fine: pool_run()
 * then runs every part on the caller. */
Pool *pool_create(int helpers);
int   pool_helpers(const Pool *p);          /* helper threads running */
/* fn(arg, 0) on the caller and fn(arg, i), 0 < i < nparts, on helpers;
 * parts beyond the helpers run on the caller after its own. */
void  pool_run(Pool *p, int nparts, PoolFn fn, void *arg);
void  pool_free(Pool *p);

#endif
