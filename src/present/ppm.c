/* ppm: save an Image as binary PPM (P6), the format with no library:
 * a text header, then w * h RGB triples from the top row. */

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include "present.h"

int write_ppm(const char *path, const Image *im, char *err, size_t errlen)
{
    if (im->w <= 0 || im->h <= 0) {
        snprintf(err, errlen, "%s: empty image", path);
        return -1;
    }
    FILE *f = fopen(path, "wb");
    if (!f) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    size_t n = 3 * (size_t)im->w * (size_t)im->h;
    int ok = fprintf(f, "P6\n%d %d\n255\n", im->w, im->h) > 0 &&
             fwrite(im->rgb, 1, n, f) == n && fflush(f) == 0;
    int saved = errno;
    if (fclose(f) != 0 && ok) {
        ok = 0;
        saved = errno;
    }
    if (!ok) {
        snprintf(err, errlen, "%s: %s", path, strerror(saved ? saved : EIO));
        return -1;
    }
    return 0;
}
