#ifndef ZV_INVARIANT_H
#define ZV_INVARIANT_H
/* invariant: ZV_ASSERT(cond), the invariants one stage promises another at
 * an internal boundary (mesh indices, screen polygon boxes, band rows,
 * edge walks). On in the builds that hunt bugs: make asan and the
 * fuzzers define ZV_CHECKS, and a broken invariant then stops the
 * program where it broke (stderr names the condition, then abort(),
 * which the terminal's crash handler sees like any crash) instead of
 * turning up later as a wrong pixel or a stray write. Off in release:
 * the condition is not evaluated and costs nothing, but it is still
 * compiled, so an assert cannot rot into code that no longer builds.
 * Independent of NDEBUG and <assert.h>.
 *
 * Each assert says in a comment why its invariant matters; asserts sit
 * where checking is cheap next to the work around them (per edge, per
 * span, per band), never per sample. */

/* Print "zview: file:line: func: invariant broken: cond", then abort(). */
void zv_check_failed(const char *cond, const char *file, int line, const char *func)
    __attribute__((noreturn, cold));

#ifdef ZV_CHECKS
#define ZV_CHECKS_ON 1
#define ZV_ASSERT(cond) \
    (__builtin_expect(!!(cond), 1) ? (void)0 : zv_check_failed(#cond, __FILE__, __LINE__, __func__))
#else
#define ZV_CHECKS_ON 0
#define ZV_ASSERT(cond) ((void)sizeof((cond) ? 1 : 0))
#endif

/* A helper only asserts call: compiled in every build, called in none
 * but the checked ones (no "unused" warning in release). */
#define ZV_CHECK_FN __attribute__((unused))

#endif
