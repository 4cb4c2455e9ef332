#ifndef ZV_SYSMEM_H
#define ZV_SYSMEM_H
/* sysmem: how much memory this process may still take, for refusing work
 * that cannot fit before allocating it (a huge --size, a file whose
 * header promises billions of elements) with an estimate instead of
 * growing until the kernel or malloc gives up. */

#include <stddef.h>
#include <stdint.h>

/* Bytes the process can still allocate: the kernel's MemAvailable (free
 * memory plus reclaimable cache), lowered by RLIMIT_AS and RLIMIT_DATA
 * when they are set and by what a cgroup v2 memory limit leaves.
 * ZV_MEM_AVAILABLE (bytes) overrides it, so that tests can play a small
 * machine. UINT64_MAX when nothing is known. */
uint64_t sysmem_available(void);

/* "4.3 GB", "180 MB", "12 KB": a byte count for messages. */
void sysmem_format(uint64_t bytes, char *buf, size_t len);

#endif
