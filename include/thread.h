#ifndef ZV_THREAD_H
#define ZV_THREAD_H
/* thread: starting a helper thread the way every stage should. */

#include <pthread.h>

/* pthread_create with every signal blocked in the new thread: a signal
 * for the process (Ctrl-Z, a window resize, Ctrl-C) then goes to the main
 * thread, whose handlers may touch the terminal, never to a worker in
 * the middle of a frame. Returns pthread_create's result. */
int thread_start(pthread_t *th, void *(*fn)(void *), void *arg);

#endif
