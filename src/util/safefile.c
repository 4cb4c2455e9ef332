/* safefile.c: write to a temporary name, rename when complete (see
 * safefile.h). */

#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "safefile.h"

/* The file the name stands for: a symlink is followed, so that the link
 * keeps pointing where it did and the file it names is replaced. */
static int resolve(SafeFile *sf, const char *path)
{
    struct stat st;
    if (strlen(path) >= sizeof sf->path) {
        errno = ENAMETOOLONG;
        return -1;
    }
    strcpy(sf->path, path);
    if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) {
        char *real = realpath(path, NULL);
        if (real && strlen(real) < sizeof sf->path)
            strcpy(sf->path, real);
        free(real);
    }
    return 0;
}

FILE *safefile_open(SafeFile *sf, const char *path, const char *mode)
{
    sf->tmp[0] = 0;
    if (resolve(sf, path))
        return NULL;
    struct stat st;
    if (stat(sf->path, &st) == 0 && !S_ISREG(st.st_mode))
        return fopen(sf->path, mode);          /* a device or FIFO: as it is */
    /* O_EXCL with a name of our own (the pid and a counter): created with
     * 0666 less the umask, as fopen would, which mkstemp's 0600 is not */
    for (int n = 0; n < 100; n++) {
        snprintf(sf->tmp, sizeof sf->tmp, "%s.zv%ld-%d.tmp", sf->path, (long)getpid(), n);
        int fd = open(sf->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            FILE *f = fdopen(fd, mode);
            if (!f) {
                int e = errno;
                close(fd);
                unlink(sf->tmp);
                errno = e;
            }
            return f;
        }
        if (errno != EEXIST)
            break;
    }
    /* no temporary file beside it (a folder we may not write in, though
     * the file itself is writable): write the file directly */
    sf->tmp[0] = 0;
    return fopen(sf->path, mode);
}

int safefile_close(SafeFile *sf, FILE *f, int failed)
{
    int e = errno;
    if (fclose(f) != 0 && !failed) {
        failed = 1;
        e = errno ? errno : EIO;
    }
    if (!failed && (!sf->tmp[0] || rename(sf->tmp, sf->path) == 0))
        return 0;
    if (!failed)
        e = errno;
    if (sf->tmp[0])
        unlink(sf->tmp);
    else {
        struct stat st;
        if (stat(sf->path, &st) == 0 && S_ISREG(st.st_mode))
            unlink(sf->path);       /* half a file is worse than none */
    }
    errno = e;
    return -1;
}
