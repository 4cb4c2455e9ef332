#ifndef ZV_SAFEFILE_H
#define ZV_SAFEFILE_H
/* safefile: files written whole or not at all. The bytes go to a
 * temporary name beside the target and are renamed over it only when
 * every write and the close succeeded; on failure (a full disk, a quota)
 * the temporary file is removed and the old file, if any, is untouched.
 * Targets that are not regular files (/dev/stdout, a FIFO, a terminal)
 * are written directly: renaming over them would replace the device. */

#include <limits.h>
#include <stdio.h>

typedef struct {
    char path[PATH_MAX];        /* the target (a symlink's target, resolved) */
    char tmp[PATH_MAX + 32];    /* what is written; "" when writing path directly */
} SafeFile;

/* Open for writing ("w" or "wb"). NULL with errno set on failure. */
FILE *safefile_open(SafeFile *sf, const char *path, const char *mode);

/* Close f; when `failed` is 0 and the close succeeds, the file takes its
 * name. Otherwise what was written is removed and -1 returned, errno the
 * close's failure (or left as the caller's when failed). */
int safefile_close(SafeFile *sf, FILE *f, int failed);

#endif
