#ifndef ZV_BIGMEM_H
#define ZV_BIGMEM_H
/* bigmem: advice for big arrays that are written front to back once
 * (a loaded mesh, a built scene). Nothing depends on it. */

#include <stddef.h>

/* Ask for huge pages for the aligned inside of [p, p + bytes), and with
 * populate, fault it all in with one call (its size is final). */
void bigmem_advise(void *p, size_t bytes, int populate);

#endif
