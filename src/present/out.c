/* out: checked output. Every write and flush goes through these, and the
 * first failure's errno is kept: with stdio buffering a full disk or a
 * closed descriptor often shows only at a later flush, and by then errno
 * may have changed. After a failure nothing more is written (the output
 * is lost already), so a long run can stop at the next check. */

#include <errno.h>
#include <stdarg.h>
#include <string.h>
#include "present.h"
#include "safetext.h"

void out_init(Out *o, FILE *f, const char *name)
{
    o->f = f;
    o->name = name;
    o->err = 0;
}

static int out_fail(Out *o, int e)
{
    if (!o->err)
        o->err = e ? e : EIO;
    return -1;
}

int out_printf(Out *o, const char *fmt, ...)
{
    if (o->err)
        return -1;
    va_list ap;
    va_start(ap, fmt);
    errno = 0;
    int n = vfprintf(o->f, fmt, ap);
    int e = errno;
    va_end(ap);
    return n < 0 ? out_fail(o, e) : 0;
}

int out_line(Out *o, const char *fmt, ...)
{
    char msg[SAFETEXT_LINE], line[4 * SAFETEXT_LINE + 2];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    safetext(line, sizeof line - 1, msg);
    size_t n = strlen(line);
    line[n++] = '\n';
    return out_write(o, line, n);
}

int out_write(Out *o, const void *p, size_t n)
{
    if (o->err)
        return -1;
    errno = 0;
    if (n && fwrite(p, 1, n, o->f) != n)
        return out_fail(o, errno);
    return 0;
}

int out_flush(Out *o)
{
    if (o->err)
        return -1;
    errno = 0;
    /* ferror: a failure of a write made around these functions */
    if (fflush(o->f) != 0 || ferror(o->f))
        return out_fail(o, errno);
    return 0;
}

int out_close(Out *o)
{
    out_flush(o);
    errno = 0;
    if (fclose(o->f) != 0)
        out_fail(o, errno);
    o->f = NULL;
    return o->err ? -1 : 0;
}

const char *out_error(const Out *o)
{
    return strerror(o->err ? o->err : EIO);
}
