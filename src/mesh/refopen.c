/* refopen.c: files a model names (material libraries, textures, glTF
 * buffers and images through assimp), opened only beneath the model's
 * folder. A model from a stranger must not make zview read
 * ../../secret.bin or /etc/passwd as geometry, nor wait for ever on a
 * FIFO, nor read /dev/zero until memory runs out: absolute paths
 * outside the folder, `..` that leaves it, symbolic links that lead out
 * of it, and anything but a regular file are refused before they are
 * opened, with a reason for the caller's warning. A model on standard
 * input (or in memory) has no folder and may name nothing.
 *
 * What a name means, as the loaders hand it over:
 *   - the folder and a name ("m/tex.png"): the name, in the folder;
 *   - the folder, a slash and a name that starts with one ("m//x"), as
 *     assimp joins them: the kernel reads m/x, which is tried first; when
 *     that is not there, the name may be an absolute path that assimp
 *     joined to the folder (a glTF uri naming its own folder), read next;
 *   - "//name": Blender's way to say the blend file's folder;
 *   - a relative name without the folder (assimp's LWS and Ogre
 *     importers): in the folder;
 *   - an absolute name: allowed when its real path (links resolved) lies
 *     in the real path of the folder, component by component (/a/bc is
 *     not in /a/b); it is then opened as the name relative to the folder.
 *
 * openat2(RESOLVE_BENEATH) walks a relative name in the kernel, which
 * refuses every way out, symbolic links included. Where it is missing (old
 * kernels, and the loading sandbox, whose filter cannot see openat2's
 * flags and so says ENOSYS) both the folder and the name are resolved
 * with realpath and the result must lie in the folder; the file is then
 * opened without following a last link, and must be the file checked. */

#define _GNU_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <linux/openat2.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "mesh_internal.h"

#define RO_FLAGS (O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK)

/* The system's reason in why, errno kept (ENOENT tells a name that is
 * not there from one refused). */
static int sys_fail(char *why, size_t whylen)
{
    int e = errno;
    snprintf(why, whylen, "%s", strerror(e));
    errno = e;
    return -1;
}

static int refuse(char *why, size_t whylen, const char *what)
{
    snprintf(why, whylen, "refused: %s", what);
    errno = EACCES;
    return -1;
}

static int not_regular(const struct stat *st, char *why, size_t whylen)
{
    const char *k = S_ISFIFO(st->st_mode) ? "a FIFO" : S_ISCHR(st->st_mode) ? "a character device"
                  : S_ISBLK(st->st_mode) ? "a block device" : S_ISDIR(st->st_mode) ? "a folder"
                  : S_ISSOCK(st->st_mode) ? "a socket" : "not a regular file";
    return refuse(why, whylen, k);
}

/* Does the relative name rel climb above where it starts (`..` more
 * often than folders)? */
static int climbs(const char *rel)
{
    int depth = 0;
    for (const char *p = rel; *p;) {
        size_t n = strcspn(p, "/");
        if (n == 2 && p[0] == '.' && p[1] == '.') {
            if (--depth < 0)
                return 1;
        } else if (n && !(n == 1 && p[0] == '.')) {
            depth++;
        }
        p += n + (p[n] == '/');
    }
    return 0;
}

/* Beneath dirfd by the kernel: an fd, -1 (why set), or -2 when openat2
 * is not there. The file is looked at (O_PATH) before it is opened:
 * opening a device or a FIFO can have effects. */
static int open_beneath(int dirfd, const char *rel, char *why, size_t whylen)
{
    struct open_how how = { .flags = O_PATH | O_CLOEXEC,
                            .resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS };
    int pfd = (int)syscall(SYS_openat2, dirfd, rel, &how, sizeof how);
    if (pfd < 0 && (errno == ENOSYS || errno == EPERM))
        return -2;
    if (pfd < 0 && errno == EXDEV)
        return refuse(why, whylen, "it leads out of the model's folder");
    if (pfd < 0)
        return sys_fail(why, whylen);
    struct stat st;
    int fd = -1;
    if (fstat(pfd, &st) != 0)
        snprintf(why, whylen, "%s", strerror(errno));
    else if (!S_ISREG(st.st_mode))
        not_regular(&st, why, whylen);
    else {
        how.flags = RO_FLAGS;
        fd = (int)syscall(SYS_openat2, dirfd, rel, &how, sizeof how);
        if (fd < 0)
            snprintf(why, whylen, "%s", strerror(errno));
    }
    close(pfd);
    return fd;
}

/* Is the real path p in the real folder root, component by component
 * (/a/bc is not in /a/b)? The name in it, or NULL. */
static const char *real_beneath(const char *root, const char *p)
{
    size_t rl = strlen(root);
    if (rl == 1 && root[0] == '/')
        return p[0] == '/' ? p + 1 : NULL;
    return strncmp(p, root, rl) == 0 && p[rl] == '/' ? p + rl + 1 : NULL;
}

/* Beneath root by realpath: an fd, or -1 with why. */
static int open_resolved(const char *root, const char *rel, char *why, size_t whylen)
{
    char full[2 * PATH_MAX + 2], rroot[PATH_MAX], rfull[PATH_MAX];
    snprintf(full, sizeof full, "%s/%s", root, rel);
    if (!realpath(root, rroot) || !realpath(full, rfull))
        return sys_fail(why, whylen);
    if (!real_beneath(rroot, rfull))
        return refuse(why, whylen, "a symbolic link leads out of the model's folder");
    struct stat st, st2;
    if (stat(rfull, &st) != 0)
        return sys_fail(why, whylen);
    if (!S_ISREG(st.st_mode))
        return not_regular(&st, why, whylen);
    int fd = open(rfull, RO_FLAGS | O_NOFOLLOW);
    if (fd < 0)
        return sys_fail(why, whylen);
    if (fstat(fd, &st2) != 0 || st2.st_dev != st.st_dev || st2.st_ino != st.st_ino || !S_ISREG(st2.st_mode)) {
        close(fd);
        return refuse(why, whylen, "the file changed while it was opened");
    }
    return fd;
}

/* The relative name rel beneath the folder root: by the kernel, else by
 * realpath. An fd, or -1 with why (errno ENOENT: not there). */
static int open_rel(const char *root, const char *rel, char *why, size_t whylen)
{
    if (!*rel || climbs(rel))
        return refuse(why, whylen, "'..' leads out of the model's folder");
    int dirfd = open(root, O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (dirfd < 0)
        return sys_fail(why, whylen);
    int fd = open_beneath(dirfd, rel, why, whylen);
    int e = errno;
    close(dirfd);
    errno = e;
    if (fd == -2)
        fd = open_resolved(root, rel, why, whylen);
    return fd;
}

/* An absolute name: opened when its real path lies in the folder's.
 * joined: it came after the folder ("m//x"), where m/x was not there:
 * not being there either, it is not there (assimp looking for optional
 * files), not refused. */
static int open_absolute(const char *root, const char *abs, int joined, char *why, size_t whylen)
{
    char rroot[PATH_MAX], rabs[PATH_MAX];
    if (!realpath(root, rroot))
        return sys_fail(why, whylen);
    if (!realpath(abs, rabs)) {
        if (joined)
            return sys_fail(why, whylen);
        return refuse(why, whylen, "an absolute path outside the model's folder");
    }
    const char *rel = real_beneath(rroot, rabs);
    if (!rel)
        return refuse(why, whylen, "an absolute path outside the model's folder");
    return open_rel(rroot, rel, why, whylen);
}

/* full relative to the folder root by name, or NULL when it does not
 * start with the folder. */
static const char *beneath(const char *root, const char *full)
{
    size_t rl = strlen(root);
    if (!strcmp(root, "."))
        return full[0] == '/' ? NULL : full;
    if (!strcmp(root, "/"))
        return full[0] == '/' ? full + 1 : NULL;
    if (!strncmp(full, root, rl) && full[rl] == '/')
        return full + rl + 1;
    return NULL;
}

int mesh_ref_open(const char *model, const char *full, char *why, size_t whylen)
{
    if (!model || !strcmp(model, "-"))
        return refuse(why, whylen, "a model on standard input may name no other file");
    char root[PATH_MAX];
    const char *slash = strrchr(model, '/');
    if (!slash)
        snprintf(root, sizeof root, ".");
    else if (slash == model)
        snprintf(root, sizeof root, "/");
    else
        snprintf(root, sizeof root, "%.*s", (int)(slash - model), model);
    const char *rel = beneath(root, full);
    if (rel && rel[0] == '/') {
        /* "m//x": m/x as the kernel reads it, else the absolute /x that
         * assimp joined to the folder */
        int fd = open_rel(root, rel + strspn(rel, "/"), why, whylen);
        if (fd >= 0 || errno != ENOENT)
            return fd;
        return open_absolute(root, rel, 1, why, whylen);
    }
    if (rel)
        return open_rel(root, rel, why, whylen);
    if (full[0] == '/' && full[1] == '/' && full[2] != '/')
        return open_rel(root, full + 2, why, whylen);      /* Blender's "//name" */
    if (full[0] != '/')
        return open_rel(root, full, why, whylen);          /* a name without the folder */
    return open_absolute(root, full, 0, why, whylen);
}

int me_ref_open(MeshErr *e, const char *model, const char *full, int image, char *why, size_t whylen)
{
    int fd = mesh_ref_open(model, full, why, whylen);
    if (fd >= 0 && e->on_ref)
        e->on_ref(e->on_ref_arg, full, image);
    return fd;
}
