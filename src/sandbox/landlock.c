/* landlock.c: a loading child reads beneath its model's folder only,
 * where the kernel has Landlock (Linux 5.13 and later, when enabled).
 * The seccomp filter (filter.c) lets the child open any file read-only:
 * what it may read is refopen.c's rule, zview's own code, which a
 * parser taken over by a hostile file could skip. Landlock is the
 * kernel's: every right the running kernel knows is handled (denied),
 * and reading files and listing folders is granted beneath the model's
 * folder and on the model's file itself (a link to elsewhere), nothing
 * more; no write, create, remove, truncate or device ioctl anywhere; no
 * TCP (ABI 4) and no signals or abstract sockets out of the child (ABI
 * 6). A model on standard input or bytes in memory (a texture) grant
 * nothing at all. Best effort: an older ABI handles fewer rights, a
 * kernel without Landlock (ENOSYS, or EOPNOTSUPP when disabled at boot)
 * none, and --info says which.
 *
 * Raw system calls: glibc has no wrappers, and the installed header
 * predates the newer rights, which are defined here from the kernel's
 * documentation (Documentation/userspace-api/landlock.rst). */

#define _GNU_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <linux/landlock.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "sandbox_internal.h"

/* rights newer than the installed header: ABI 3, 5, 4 and 6 */
#define FS_TRUNCATE     (1ULL << 14)
#define FS_IOCTL_DEV    (1ULL << 15)
#define NET_BIND_TCP    (1ULL << 0)
#define NET_CONNECT_TCP (1ULL << 1)
#define SCOPE_ABSTRACT_UNIX_SOCKET (1ULL << 0)
#define SCOPE_SIGNAL    (1ULL << 1)

/* struct landlock_ruleset_attr as of ABI 6; older kernels are given the
 * prefix they know (its size says which) */
typedef struct {
    uint64_t handled_access_fs;
    uint64_t handled_access_net;
    uint64_t scoped;
} RulesetAttr;

#define FS_READ (LANDLOCK_ACCESS_FS_READ_FILE | LANDLOCK_ACCESS_FS_READ_DIR)

int sandbox_landlock_abi(void)
{
    const char *fake = getenv("ZV_LANDLOCK_ABI");
    if (fake && *fake)
        return atoi(fake);
    long v = syscall(SYS_landlock_create_ruleset, NULL, 0, LANDLOCK_CREATE_RULESET_VERSION);
    return v > 0 ? (int)v : -errno;
}

/* Every filesystem right ABI abi knows. */
static uint64_t fs_rights(int abi)
{
    uint64_t fs = (LANDLOCK_ACCESS_FS_MAKE_SYM << 1) - 1;  /* ABI 1: bits 0 to 12 */
    if (abi >= 2)
        fs |= LANDLOCK_ACCESS_FS_REFER;
    if (abi >= 3)
        fs |= FS_TRUNCATE;
    if (abi >= 5)
        fs |= FS_IOCTL_DEV;
    return fs;
}

/* Grant read (fs: the rights) beneath path, a folder or a file. */
static int allow(int ruleset, const char *path, uint64_t fs)
{
    int fd = open(path, O_PATH | O_CLOEXEC);
    if (fd < 0)
        return errno == ENOENT ? 0 : -1;    /* nothing there: the load says so */
    struct landlock_path_beneath_attr pb = { .allowed_access = fs, .parent_fd = fd };
    int r = (int)syscall(SYS_landlock_add_rule, ruleset, LANDLOCK_RULE_PATH_BENEATH, &pb, 0);
    close(fd);
    return r;
}

int sandbox_landlock_restrict(const char *model, int abi)
{
    if (abi < 1)
        return 0;
    RulesetAttr ra = { .handled_access_fs = fs_rights(abi) };
    size_t size = sizeof ra.handled_access_fs;
    if (abi >= 4) {
        ra.handled_access_net = NET_BIND_TCP | NET_CONNECT_TCP;
        size = offsetof(RulesetAttr, scoped);
    }
    if (abi >= 6) {
        ra.scoped = SCOPE_ABSTRACT_UNIX_SOCKET | SCOPE_SIGNAL;
        size = sizeof ra;
    }
    int rs = (int)syscall(SYS_landlock_create_ruleset, &ra, size, 0);
    if (rs < 0)
        return -1;
    int r = 0;
    if (model && strcmp(model, "-")) {
        /* the folder as the model names it (what refopen.c confines to),
         * and the file itself: a link to a file elsewhere is what was
         * asked for */
        char dir[4096];
        const char *slash = strrchr(model, '/');
        if (!slash)
            strcpy(dir, ".");
        else if (slash == model)
            strcpy(dir, "/");
        else
            snprintf(dir, sizeof dir, "%.*s", (int)(slash - model), model);
        r |= allow(rs, dir, FS_READ);
        r |= allow(rs, model, LANDLOCK_ACCESS_FS_READ_FILE);
    }
    /* restricting oneself needs no new privileges (or CAP_SYS_ADMIN);
     * the seccomp filter sets it too */
    if (r == 0 && prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) == 0)
        r = (int)syscall(SYS_landlock_restrict_self, rs, 0);
    else
        r = -1;
    close(rs);
    return r;
}

void sandbox_landlock_say(int abi, char *buf, size_t len)
{
    if (abi > 0)
        snprintf(buf, len, "landlock (ABI %d)", abi);
    else if (abi == -EOPNOTSUPP)
        snprintf(buf, len, "no landlock (disabled at boot)");
    else if (abi == -ENOSYS || abi == 0)
        snprintf(buf, len, "no landlock (not in this kernel)");
    else
        snprintf(buf, len, "no landlock (%s)", strerror(-abi));
}
