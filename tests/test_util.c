/* test_util.c: the rooms every stage uses: helper threads, the memory
 * probe, files written whole. */

#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "safefile.h"
#include "sysmem.h"
#include "thread.h"

static void *read_mask(void *arg)
{
    pthread_sigmask(SIG_SETMASK, NULL, (sigset_t *)arg);
    return NULL;
}

Test(util, a_helper_thread_has_every_signal_blocked_and_the_caller_keeps_its_mask)
{
    sigset_t before, after, inside;
    sigemptyset(&before);
    pthread_sigmask(SIG_SETMASK, &before, NULL);
    pthread_t th;
    cr_assert_eq(thread_start(&th, read_mask, &inside), 0);
    pthread_join(th, NULL);
    static const int sigs[] = { SIGINT, SIGTSTP, SIGWINCH, SIGCONT, SIGTERM, SIGHUP };
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
        cr_expect(sigismember(&inside, sigs[i]), "signal %d reaches the helper", sigs[i]);
    pthread_sigmask(SIG_SETMASK, NULL, &after);
    cr_expect(!sigismember(&after, SIGWINCH) && !sigismember(&after, SIGINT), "the caller's mask changed");
}

Test(util, memory_sizes_read_as_people_write_them)
{
    char b[32];
    sysmem_format(4300000000ull, b, sizeof b);
    cr_expect_str_eq(b, "4.3 GB");
    sysmem_format(180000000, b, sizeof b);
    cr_expect_str_eq(b, "180 MB");
    sysmem_format(12345, b, sizeof b);
    cr_expect_str_eq(b, "12 KB");
}

Test(util, the_memory_probe_takes_the_test_override_and_otherwise_reads_the_machine)
{
    setenv("ZV_MEM_AVAILABLE", "123456789", 1);
    cr_expect_eq(sysmem_available(), 123456789ull);
    unsetenv("ZV_MEM_AVAILABLE");
    uint64_t m = sysmem_available();
    /* every machine this runs on has more than 16 MB and less than 64 TB */
    cr_expect(m > (16ull << 20) && m < (64ull << 40), "available: %llu", (unsigned long long)m);
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "r");
    static char buf[256];
    if (!f)
        return NULL;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = 0;
    fclose(f);
    return buf;
}

Test(util, a_safe_file_replaces_the_old_one_only_when_complete)
{
    char dir[] = "/tmp/zv-safe-XXXXXX", path[64], tmpname[PATH_MAX + 32];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/out.txt", dir);
    FILE *f = fopen(path, "w");
    fputs("old", f);
    fclose(f);
    /* a failed write: the old file stays, the temporary one goes */
    SafeFile sf;
    f = safefile_open(&sf, path, "w");
    cr_assert_not_null(f);
    cr_assert_neq(sf.tmp[0], 0, "written beside the target, not over it");
    strcpy(tmpname, sf.tmp);
    fputs("half", f);
    cr_expect_eq(safefile_close(&sf, f, 1), -1);
    cr_expect_str_eq(slurp(path), "old");
    cr_expect_neq(access(tmpname, F_OK), 0, "the temporary file is left behind");
    /* a good one takes the name */
    f = safefile_open(&sf, path, "w");
    fputs("new", f);
    cr_expect_eq(safefile_close(&sf, f, 0), 0);
    cr_expect_str_eq(slurp(path), "new");
    struct stat st;
    cr_expect_eq(stat(path, &st), 0);
    mode_t um = umask(0);
    umask(um);
    cr_expect_eq(st.st_mode & 0777, 0666 & ~um, "mode %o, as fopen would make it", st.st_mode & 0777);
    unlink(path);
    rmdir(dir);
}

Test(util, a_safe_file_writes_a_device_as_it_is)
{
    SafeFile sf;
    FILE *f = safefile_open(&sf, "/dev/null", "w");
    cr_assert_not_null(f);
    cr_expect_eq(sf.tmp[0], 0, "no temporary file beside /dev/null");
    fputs("x", f);
    cr_expect_eq(safefile_close(&sf, f, 0), 0);
    struct stat st;
    cr_expect(stat("/dev/null", &st) == 0 && S_ISCHR(st.st_mode));
}

/* ZV_ASSERT is on exactly in the checked builds (make asan, the
 * fuzzers): there it evaluates its condition once; elsewhere not at all. */
Test(util, invariants_are_evaluated_only_in_checked_builds)
{
    int evaluated = 0;
    ZV_ASSERT(++evaluated == 1);
    cr_assert_eq(evaluated, ZV_CHECKS_ON, "ZV_ASSERT evaluated its condition %d times", evaluated);
}

#ifdef ZV_CHECKS
/* and a broken one stops the program (abort, which a crash handler sees) */
Test(util, a_broken_invariant_aborts, .signal = SIGABRT, .init = cr_redirect_stderr)
{
    volatile int zero = 0;
    ZV_ASSERT(zero == 1);
}
#endif
