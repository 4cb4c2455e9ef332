/* thread.c: helper threads with signals blocked (thread.h). */

#include <signal.h>

#include "thread.h"

int thread_start(pthread_t *th, void *(*fn)(void *), void *arg)
{
    /* the new thread inherits the creator's mask: block all around the
     * create, then give the creator its own back */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    int rc = pthread_create(th, NULL, fn, arg);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    return rc;
}
