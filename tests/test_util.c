/* test_util.c: the rooms every stage uses: helper threads, the memory
 * probe, files written whole, text safe to print. */

#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <errno.h>
#include <limits.h>
#include <criterion/redirect.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "invariant.h"
#include "pool.h"
#include "safefile.h"
#include "safetext.h"
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

/* A name as long as the array that keeps it, or longer, is refused as
 * too long before anything is copied (no name of PATH_MAX bytes or more
 * can be opened: the limit counts the NUL); one byte shorter goes on to
 * the file system, which says what it says of a missing folder. The
 * SafeFile sits between two guards that must keep their bytes. */
Test(util, a_safe_file_refuses_a_name_too_long_for_it)
{
    static char name[PATH_MAX + 2];
    struct {
        char before[64];
        SafeFile sf;
        char after[64];
    } g;
    for (int extra = -1; extra <= 1; extra++) {
        size_t len = sizeof g.sf.path + extra;
        memset(name, 'a', len);
        name[0] = '/';
        memcpy(name + 1, "zv-no-such-dir/", 15);
        name[len] = 0;
        memset(&g, 0x5a, sizeof g);
        errno = 0;
        FILE *f = safefile_open(&g.sf, name, "w");
        cr_assert_null(f, "a name of %zu bytes opened", len);
        if (extra >= 0)
            cr_expect_eq(errno, ENAMETOOLONG, "%zu bytes: errno %d", len, errno);
        else
            cr_expect_eq(errno, ENOENT, "%zu bytes: errno %d", len, errno);
        for (size_t i = 0; i < sizeof g.before; i++)
            cr_assert(g.before[i] == 0x5a && g.after[i] == 0x5a, "%zu bytes: a guard's byte %zu written", len, i);
        if (extra >= 0)
            cr_expect(g.sf.tmp[0] == 0 && (unsigned char)g.sf.tmp[1] == 0x5a,
                      "%zu bytes: a temporary name was made of it", len);
    }
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

Test(util, a_safe_file_over_a_symlink_replaces_the_file_it_names)
{
    /* the link keeps pointing where it did; the file it names is the new
     * one (a plain file in the link's place would leave the target old) */
    char dir[] = "/tmp/zv-safe-XXXXXX", target[64], link[64];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(target, sizeof target, "%s/real.txt", dir);
    snprintf(link, sizeof link, "%s/link.txt", dir);
    FILE *f = fopen(target, "w");
    fputs("old", f);
    fclose(f);
    cr_assert_eq(symlink("real.txt", link), 0);
    SafeFile sf;
    f = safefile_open(&sf, link, "w");
    cr_assert_not_null(f);
    fputs("new", f);
    cr_expect_eq(safefile_close(&sf, f, 0), 0);
    struct stat st;
    cr_expect(lstat(link, &st) == 0 && S_ISLNK(st.st_mode), "the link is still a link");
    cr_expect_str_eq(slurp(target), "new");
    unlink(link);
    unlink(target);
    rmdir(dir);
}

/* ==== The helper pool ==== */

typedef struct {
    int  ntasks, helpers;
    int *runs;          /* ntasks + 1 counts: the last catches a task past the end */
    int  bad;           /* a task or worker number out of range */
} PoolTally;

static void tally_task(void *arg, int task, int worker)
{
    PoolTally *c = arg;
    if (task < 0 || task > c->ntasks || worker < 0 || worker > c->helpers)
        __atomic_store_n(&c->bad, 1, __ATOMIC_RELAXED);
    else
        __atomic_add_fetch(&c->runs[task], 1, __ATOMIC_RELAXED);
}

Test(util, a_pool_runs_every_task_once_and_no_other)
{
    /* pool.h's contract: fn for every task in [0, ntasks), once, on
     * worker 0 (the caller) .. helpers; run after run on the same pool,
     * and without one */
    Pool *pools[2] = { pool_create(3), NULL };
    cr_assert_not_null(pools[0]);
    cr_expect(pool_helpers(pools[0]) >= 1 && pool_helpers(pools[0]) <= 3);
    for (int q = 0; q < 2; q++)
        for (int ntasks = 0; ntasks <= 40; ntasks++)
            for (int round = 0; round < 3; round++) {
                int runs[41] = { 0 };
                PoolTally c = { ntasks, pool_helpers(pools[q]), runs, 0 };
                pool_run(pools[q], ntasks, tally_task, &c);
                cr_assert_eq(c.bad, 0, "a task or worker out of range (%d tasks)", ntasks);
                for (int t = 0; t < ntasks; t++)
                    cr_assert_eq(runs[t], 1, "task %d of %d ran %d times", t, ntasks, runs[t]);
                cr_assert_eq(runs[ntasks], 0, "a task past the last ran (%d tasks)", ntasks);
            }
    pool_free(pools[0]);
}

/* Asked for more helpers than it holds, a pool starts 63 (the caller
 * makes 64 workers, the most a projection uses: SCREEN_MAX_THREADS) and
 * runs every task once on them. */
Test(util, a_pool_asked_for_a_thousand_helpers_starts_at_most_63)
{
    Pool *p = pool_create(1000);
    cr_assert_not_null(p);
    int n = pool_helpers(p);
    cr_assert(n >= 1 && n <= 63, "%d helpers", n);
    int runs[201] = { 0 };
    PoolTally c = { 200, n, runs, 0 };
    pool_run(p, 200, tally_task, &c);
    cr_assert_eq(c.bad, 0, "a task or worker out of range");
    for (int t = 0; t < 200; t++)
        cr_assert_eq(runs[t], 1, "task %d ran %d times", t, runs[t]);
    pool_free(p);
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

/* ==== Text safe to print (issue 28) ==== */

static const char *safe(const char *s)
{
    static char buf[512];
    return safetext(buf, sizeof buf, s);
}

static const char *json(const char *s)
{
    static char buf[512];
    size_t o = 0;
    while (*s) {
        char piece[SAFETEXT_PIECE];
        s += safetext_next(s, piece, SAFETEXT_JSON);
        o += (size_t)snprintf(buf + o, sizeof buf - o, "%s", piece);
    }
    buf[o] = 0;
    return buf;
}

Test(util, safe_text_shows_controls_and_broken_utf8_by_their_bytes)
{
    struct { const char *in, *want; } cases[] = {
        { "plain/name-1.obj", "plain/name-1.obj" },
        { "mod\xc3\xa8le \xe6\x97\xa5 \xf0\x9f\x99\x82", "mod\xc3\xa8le \xe6\x97\xa5 \xf0\x9f\x99\x82" },
        { "a\x1b]52;c;aGk=\x07\x1b[2Jb", "a\\x1b]52;c;aGk=\\x07\\x1b[2Jb" },      /* OSC 52, CSI 2J */
        { "tab\there\nnewline\r", "tab\\x09here\\x0anewline\\x0d" },
        { "del\x7f", "del\\x7f" },
        { "c1 \xc2\x9b" "2J", "c1 \\xc2\\x9b2J" },            /* U+009B, a CSI in UTF-8 */
        { "raw \x9b" "2J", "raw \\x9b2J" },                   /* the C1 byte alone: no UTF-8 */
        { "rlo \xe2\x80\xae" "gpj.exe", "rlo \\xe2\\x80\\xaegpj.exe" },    /* a bidirectional override */
        { "ls \xe2\x80\xa8", "ls \\xe2\\x80\\xa8" },          /* the line separator */
        { "over \xc0\xaf", "over \\xc0\\xaf" },               /* an overlong '/' */
        { "sur \xed\xa0\x80", "sur \\xed\\xa0\\x80" },        /* a surrogate */
        { "big \xf4\x90\x80\x80", "big \\xf4\\x90\\x80\\x80" },   /* past U+10FFFF */
        { "cut \xe6\x97", "cut \\xe6\\x97" },                 /* a character cut short */
        { "cont \x80x", "cont \\x80x" },
        { "back\\slash", "back\\slash" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        cr_expect_str_eq(safe(cases[i].in), cases[i].want, "case %zu", i);
}

Test(util, safe_text_in_json_escapes_what_text_shows_by_bytes)
{
    cr_expect_str_eq(json("a\x1b[2J\x07"), "a\\u001b[2J\\u0007");
    cr_expect_str_eq(json("q\"b\\"), "q\\\"b\\\\");
    cr_expect_str_eq(json("\x7f\xc2\x9b\xe2\x80\xae"), "\\u007f\\u009b\\u202e");
    cr_expect_str_eq(json("x\xff\xc0\xafy"), "x\\ufffd\\ufffd\\ufffdy", "a byte that is not UTF-8 is U+FFFD");
    cr_expect_str_eq(json("mod\xc3\xa8le \xf0\x9f\x99\x82"), "mod\xc3\xa8le \xf0\x9f\x99\x82");
}

Test(util, safe_text_is_cut_at_a_whole_character)
{
    char buf[8];
    cr_expect_str_eq(safetext(buf, sizeof buf, "ab\x1b"), "ab\\x1b");
    cr_expect_str_eq(safetext(buf, sizeof buf, "abcd\x1b"), "abcd", "the escape does not fit: left out whole");
    cr_expect_str_eq(safetext(buf, sizeof buf, "abcde\xc3\xa9"), "abcde\xc3\xa9");
    cr_expect_str_eq(safetext(buf, sizeof buf, "abcdef\xc3\xa9"), "abcdef");
    cr_expect_str_eq(safetext(buf, 1, "abc"), "");
}

/* Every string of up to two bytes, and random ones of up to eight: the
 * text has no control byte, no DEL, no C1 character and is valid UTF-8;
 * a string of printable ASCII is itself. */
Test(util, safe_text_of_any_bytes_is_printable_utf8)
{
    unsigned seed = 28;
    for (long k = 0; k < 65536 + 256 + 200000; k++) {
        unsigned char in[9] = { 0 };
        if (k < 256) {
            in[0] = (unsigned char)k;
        } else if (k < 65536 + 256) {
            in[0] = (unsigned char)((k - 256) >> 8);
            in[1] = (unsigned char)(k - 256);
        } else {
            int n = 1 + (int)(rand_r(&seed) % 8);
            for (int i = 0; i < n; i++)
                in[i] = (unsigned char)rand_r(&seed);
        }
        const unsigned char *out = (const unsigned char *)safe((const char *)in);
        int ascii = 1;
        for (const unsigned char *p = in; *p; p++)
            ascii &= *p >= 0x20 && *p < 0x7f;
        if (ascii)
            cr_assert_str_eq((const char *)out, (const char *)in);
        for (const unsigned char *p = out; *p;) {
            cr_assert(*p >= 0x20 && *p != 0x7f, "byte %02x in the text of string %ld", *p, k);
            if (*p < 0x80) {
                p++;
                continue;
            }
            /* a well-formed sequence, by the table of RFC 3629 */
            int n = *p >= 0xf0 ? 4 : *p >= 0xe0 ? 3 : 2;
            cr_assert(*p >= 0xc2 && *p <= 0xf4, "lead byte %02x of string %ld", *p, k);
            for (int i = 1; i < n; i++)
                cr_assert((p[i] & 0xc0) == 0x80, "string %ld", k);
            cr_assert(!(*p == 0xc2 && p[1] < 0xa0), "a C1 character in the text of string %ld", k);
            cr_assert(!(*p == 0xe0 && p[1] < 0xa0) && !(*p == 0xed && p[1] >= 0xa0) &&
                      !(*p == 0xf0 && p[1] < 0x90) && !(*p == 0xf4 && p[1] >= 0x90), "string %ld", k);
            p += n;
        }
    }
}

Test(util, a_safe_line_is_one_line_in_one_piece)
{
    char path[] = "/tmp/zv-safeline-XXXXXX";
    int fd = mkstemp(path);
    cr_assert(fd >= 0);
    FILE *f = fdopen(fd, "w+");
    safetext_line(f, "zview: %s: %s", "e\x1b[2Jvil.obj", "two\nlines");
    rewind(f);
    char got[200] = "";
    size_t n = fread(got, 1, sizeof got - 1, f);
    got[n] = 0;
    cr_expect_str_eq(got, "zview: e\\x1b[2Jvil.obj: two\\x0alines\n");
    fclose(f);
    unlink(path);
}
