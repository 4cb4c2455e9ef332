/* ppm: save an Image as binary PPM (P6), the format with no library:
 * a text header, then w * h RGB triples from the top row. */

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include "present.h"
#include "safefile.h"

int write_ppm(const char *path, const Image *im, char *err, size_t errlen)
{
    if (im->w <= 0 || im->h <= 0) {
        snprintf(err, errlen, "%s: empty image", path);
        return -1;
    }
    SafeFile sf;
    FILE *f = safefile_open(&sf, path, "wb");
    if (!f) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    size_t n = 3 * (size_t)im->w * (size_t)im->h;
    Out out;
    out_init(&out, f, path);
    out_printf(&out, "P6\n%d %d\n255\n", im->w, im->h);
    out_write(&out, im->rgb, n);
    out_flush(&out);
    errno = out.err;
    if (safefile_close(&sf, f, out.err != 0)) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno ? errno : EIO));
        return -1;
    }
    return 0;
}
