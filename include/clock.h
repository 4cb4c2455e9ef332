#ifndef ZV_CLOCK_H
#define ZV_CLOCK_H
/* clock: the one place time is read, in milliseconds as doubles. */

/* Wall time since an arbitrary start (CLOCK_MONOTONIC): durations. */
double now_ms(void);
/* CPU time of the calling thread: what a load cost, whatever else shares
 * the machine (a shared machine's wall time also counts waiting). */
double thread_cpu_ms(void);
/* CPU time of the whole process, every thread: the benchmark's. */
double process_cpu_ms(void);

#endif
