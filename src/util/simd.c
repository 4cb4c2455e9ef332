/* simd.c: which SIMD level runs (simd.h). No state of its own: the CPU
 * is asked through the compiler's cpu builtins (which keep their own
 * answer), the environment is read on each call. */

#include <stdlib.h>
#include <string.h>

#include "safetext.h"
#include "simd.h"

static const char *const level_names[SIMD_LEVELS] = { "auto", "scalar", "sse2", "avx2" };

const char *simd_name(int level)
{
    return level >= 0 && level < SIMD_LEVELS ? level_names[level] : "?";
}

SimdLevel simd_best(void)
{
#ifdef ZV_AVX2
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2"))
        return SIMD_AVX2;
#endif
#ifdef ZV_SSE2
    return SIMD_SSE2;
#else
    return SIMD_SCALAR;
#endif
}

/* The level ZV_SIMD names: SIMD_AUTO when it is unset or empty (an
 * empty value is how a shell unsets a variable for one command), -1
 * when it names none. "auto" is not a value: only the three levels. */
static int env_level(const char **value_out)
{
    const char *v = getenv("ZV_SIMD");
    *value_out = v;
    if (!v || !*v)
        return SIMD_AUTO;
    for (int l = SIMD_SCALAR; l < SIMD_LEVELS; l++)
        if (strcmp(v, level_names[l]) == 0)
            return l;
    return -1;
}

SimdLevel simd_use(int want)
{
    const char *v;
    if (want == SIMD_AUTO)
        want = env_level(&v);
    SimdLevel best = simd_best();
    if (want <= SIMD_AUTO || want > (int)best)
        return best;
    return (SimdLevel)want;
}

SimdLevel simd_level(void)
{
    return simd_use(SIMD_AUTO);
}

int simd_warn(FILE *f)
{
    const char *v;
    int want = env_level(&v);
    SimdLevel best = simd_best();
    if (want < 0) {
        safetext_line(f, "zview: ZV_SIMD=%s is not a level (scalar, sse2, avx2): using %s", v, simd_name(best));
        return 1;
    }
    if (want > (int)best) {
        safetext_line(f, "zview: ZV_SIMD=%s: this CPU or build cannot run it: using %s", v, simd_name(best));
        return 1;
    }
    return 0;
}
