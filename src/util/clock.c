/* clock.c: clock_gettime in milliseconds (clock.h). */

#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "clock.h"

static double clock_ms(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

double now_ms(void) { return clock_ms(CLOCK_MONOTONIC); }
double thread_cpu_ms(void) { return clock_ms(CLOCK_THREAD_CPUTIME_ID); }
double process_cpu_ms(void) { return clock_ms(CLOCK_PROCESS_CPUTIME_ID); }
