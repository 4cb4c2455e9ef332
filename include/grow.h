#ifndef ZV_GROW_H
#define ZV_GROW_H
/* grow: the one way plain arrays grow. Capacity rises geometrically
 * until it holds `need` elements and never shrinks, so per-frame buffers
 * stop allocating once they have seen the biggest frame. */

#include <stdint.h>
#include <stdlib.h>

/* *p holds *cap elements of `elem` bytes; make room for need. Returns 0,
 * or -1 on out of memory (then *p and *cap are unchanged). */
static inline int grow_array(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return 0;
    uint32_t n = *cap ? *cap : 64;
    while (n < need)
        n = n > UINT32_MAX / 3 * 2 ? need : n + n / 2;
    void *q = realloc(*p, (size_t)n * elem);
    if (!q)
        return -1;
    *p = q;
    *cap = n;
    return 0;
}

/* The same for size_t capacities (a loader's arrays, which may pass 4 G
 * bytes): doubling from 256, and -1 when the size would overflow.
 * Allocates even for need 0 when *p is NULL, so that an empty array is
 * still an array. */
static inline int grow_size(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap && *p)
        return 0;
    size_t n = *cap ? *cap : 256;
    while (n < need) {
        if (n > SIZE_MAX / 2 / elem)
            return -1;
        n *= 2;
    }
    void *q = realloc(*p, n * elem);
    if (!q)
        return -1;
    *p = q;
    *cap = n;
    return 0;
}

#endif
