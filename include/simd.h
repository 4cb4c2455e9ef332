#ifndef ZV_SIMD_H
#define ZV_SIMD_H
/* simd: the one SIMD switch. Which vector paths are compiled in, the
 * attribute that compiles an AVX2 function in a baseline build, and the
 * level a frame runs at.
 *
 * Every SIMD path of zview performs the scalar reference's IEEE
 * operations in the scalar order (the build has -ffp-contract=off: no
 * fused multiply-add), so every level gives the same bits and the level
 * is only a matter of speed. The level is chosen per frame:
 *  - compiled in: ZV_SSE2 where the compiler targets SSE2 (every
 *    x86-64), ZV_AVX2 where GCC or Clang can compile AVX2 functions for
 *    x86 with a target attribute (the build itself stays baseline);
 *    -DZV_NO_SIMD leaves both out (make nosimd), so the scalar paths
 *    are the only ones;
 *  - run: the best level compiled in that this CPU has, unless the
 *    environment variable ZV_SIMD=scalar|sse2|avx2 asks for a lower one;
 *  - a stage's setting (ScreenPolys.simd, HsrInput.simd,
 *    ShadeSettings.simd) is a SimdLevel: SIMD_AUTO for the level in use,
 *    else at most that level (the tests compare the levels).
 * Nothing is cached: the level is read where a frame starts and passed
 * down. */

#include <stdio.h>

#if defined(__SSE2__) && !defined(ZV_NO_SIMD)
#define ZV_SSE2 1
#include <emmintrin.h>
#endif

#if defined(ZV_SSE2) && (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define ZV_AVX2 1
#include <immintrin.h>
/* An AVX2 function: compiled for AVX2 whatever the build's target, and
 * called only when the level in use is SIMD_AVX2. */
#define ZV_AVX2_FN __attribute__((target("avx2")))
#endif

typedef enum {
    SIMD_AUTO = 0,      /* a setting: the level in use (ZV_SIMD, else the best) */
    SIMD_SCALAR,        /* plain C, the reference */
    SIMD_SSE2,          /* four lanes: the x86-64 baseline */
    SIMD_AVX2,          /* eight lanes, chosen at run time */
    SIMD_LEVELS
} SimdLevel;

/* "auto", "scalar", "sse2", "avx2" (ZV_SIMD's values and --info's). */
const char *simd_name(int level);

/* The best level compiled in that this CPU runs. */
SimdLevel simd_best(void);

/* The level in use: the one ZV_SIMD names when this CPU and build run
 * it, else the best below it; the best when ZV_SIMD is unset, empty or
 * unknown. Reads the environment each time. */
SimdLevel simd_level(void);

/* A stage's setting as the level to run: SIMD_AUTO becomes
 * simd_level(), anything else at most simd_best(). */
SimdLevel simd_use(int want);

/* When ZV_SIMD names an unknown level or one this CPU or build cannot
 * run, one line on f naming ZV_SIMD and the level used instead; returns
 * 1 then, else 0 (nothing written). main calls it once at start. */
int simd_warn(FILE *f);

#endif
