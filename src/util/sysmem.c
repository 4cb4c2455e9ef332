/* sysmem.c: the memory a process may still take (see sysmem.h). */

#define _DEFAULT_SOURCE

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/sysinfo.h>

#include "sysmem.h"

/* MemAvailable from /proc/meminfo in bytes; else sysinfo's free and
 * buffer memory (kernels before 3.14, /proc not mounted); UINT64_MAX
 * when neither tells. */
static uint64_t meminfo_available(void)
{
    FILE *f = fopen("/proc/meminfo", "re");
    uint64_t kb = UINT64_MAX;
    if (f) {
        char line[256];
        while (fgets(line, sizeof line, f)) {
            unsigned long long v;
            if (sscanf(line, "MemAvailable: %llu kB", &v) == 1) {
                kb = v;
                break;
            }
        }
        fclose(f);
    }
    if (kb != UINT64_MAX)
        return kb * 1024;
    struct sysinfo si;
    if (sysinfo(&si) == 0 && si.freeram)
        return ((uint64_t)si.freeram + si.bufferram) * si.mem_unit;
    return UINT64_MAX;
}

/* One number from a small file (a cgroup's); -1 when absent or "max". */
static int read_number(const char *path, uint64_t *out)
{
    FILE *f = fopen(path, "re");
    if (!f)
        return -1;
    unsigned long long v;
    int ok = fscanf(f, "%llu", &v) == 1;
    fclose(f);
    if (!ok)
        return -1;
    *out = v;
    return 0;
}

/* What a cgroup v2 memory limit leaves (a container's limit can be far
 * below the machine's memory); UINT64_MAX when there is none. */
static uint64_t cgroup_left(void)
{
    uint64_t lim, cur;
    if (read_number("/sys/fs/cgroup/memory.max", &lim) || read_number("/sys/fs/cgroup/memory.current", &cur))
        return UINT64_MAX;
    return lim > cur ? lim - cur : 0;
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
    uint64_t avail = min_u64(meminfo_available(), cgroup_left());
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
