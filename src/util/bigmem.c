/* bigmem: first touches of a big fresh array cost a page fault each (in a
 * VM several microseconds: more than parsing or computing what fills the
 * page). So the aligned inside of a big array asks for huge pages (512
 * times fewer faults where the kernel has them, as with transparent huge
 * pages in "madvise" mode) and, when its size is final, is faulted in by
 * one call instead of one trap a page. Both are advice. */
#define _DEFAULT_SOURCE

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>

#include "bigmem.h"

void bigmem_advise(void *p, size_t bytes, int populate)
{
    const uintptr_t huge = (uintptr_t)2 << 20, page = 4096;
    if (!p || bytes < huge)
        return;
    uintptr_t a = ((uintptr_t)p + huge - 1) & ~(huge - 1), e = ((uintptr_t)p + bytes) & ~(huge - 1);
#ifdef MADV_HUGEPAGE
    if (e > a)
        madvise((void *)a, e - a, MADV_HUGEPAGE);
#endif
#ifdef MADV_POPULATE_WRITE
    uintptr_t pa = ((uintptr_t)p + page - 1) & ~(page - 1), pe = ((uintptr_t)p + bytes) & ~(page - 1);
    if (populate && pe > pa)
        madvise((void *)pa, pe - pa, MADV_POPULATE_WRITE);
#else
    (void)populate;
    (void)page;
#endif
}

void *bigmem_alloc(size_t bytes)
{
    void *p = malloc(bytes ? bytes : 1);
    bigmem_advise(p, bytes, 1);
    return p;
}

void *bigmem_zalloc(size_t bytes)
{
    void *p = mmap(NULL, bytes ? bytes : 1, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    return p == MAP_FAILED ? NULL : p;
}

void bigmem_zfree(void *p, size_t bytes)
{
    if (p)
        munmap(p, bytes ? bytes : 1);
}
