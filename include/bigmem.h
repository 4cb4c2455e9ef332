#ifndef ZV_BIGMEM_H
#define ZV_BIGMEM_H
/* bigmem: advice for big arrays that are written front to back once
 * (a loaded mesh, a built scene). Nothing depends on it. */

#include <stddef.h>

/* Ask for huge pages for the aligned inside of [p, p + bytes), and with
 * populate, fault it all in with one call (its size is final). */
void bigmem_advise(void *p, size_t bytes, int populate);

/* malloc(bytes), and for a big block huge pages faulted in at once
 * (bigmem_advise with populate): an array about to be written whole
 * costs a few faults instead of one every 4 KB. free() frees it. */
void *bigmem_alloc(size_t bytes);

/* An array of zero bytes whose pages become resident only when written
 * (straight from the kernel: calloc of a block the heap reuses would
 * write every byte), for a table indexed by face of which a frame
 * touches few entries. NULL out of memory; bigmem_zfree with the same
 * size (p NULL: nothing). */
void *bigmem_zalloc(size_t bytes);
void  bigmem_zfree(void *p, size_t bytes);

#endif
