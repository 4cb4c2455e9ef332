/* sysmem.c: the memory a process may still take (see sysmem.h). */

#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "sysmem.h"

/* MemAvailable from /proc/meminfo in bytes, UINT64_MAX when unreadable
 * (not Linux, /proc not mounted). */
static uint64_t meminfo_available(void)
{
    FILE *f = fopen("/proc/meminfo", "re");
    if (!f)
        return UINT64_MAX;
    char line[256];
    uint64_t kb = UINT64_MAX;
    while (fgets(line, sizeof line, f)) {
        unsigned long long v;
        if (sscanf(line, "MemAvailable: %llu kB", &v) == 1) {
            kb = v;
            break;
        }
    }
    fclose(f);
    return kb == UINT64_MAX ? UINT64_MAX : kb * 1024;
}

static uint64_t min_u64(uint64_t a, uint64_t b) { return a < b ? a : b; }

uint64_t sysmem_available(void)
{
    const char *env = getenv("ZV_MEM_AVAILABLE");
    if (env && *env) {
        char *end;
        unsigned long long v = strtoull(env, &end, 10);
        if (!*end)
            return v;
    }
    uint64_t avail = meminfo_available();
    /* an address-space or data limit (ulimit -v, a container's setting)
     * ends allocation before the machine's memory does; what is already
     * mapped counts against it, so this is an upper bound */
    static const int limits[] = { RLIMIT_AS, RLIMIT_DATA };
    for (size_t i = 0; i < sizeof limits / sizeof limits[0]; i++) {
        struct rlimit rl;
        if (getrlimit(limits[i], &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
            avail = min_u64(avail, (uint64_t)rl.rlim_cur);
    }
    return avail;
}

void sysmem_format(uint64_t bytes, char *buf, size_t len)
{
    double b = (double)bytes;
    if (b >= 1e9)
        snprintf(buf, len, "%.1f GB", b / 1e9);
    else if (b >= 1e6)
        snprintf(buf, len, "%.0f MB", b / 1e6);
    else
        snprintf(buf, len, "%.0f KB", b / 1e3);
}
