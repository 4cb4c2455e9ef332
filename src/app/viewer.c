/* viewer.c: the interactive terminal viewer (placeholder until the
 * curses front end lands: behaves like --print). */

#include "app.h"

int app_viewer(const Options *o, Scene *s)
{
    return app_oneshot(o, s);
}

int app_bench_tty(const Options *o)
{
    (void)o;
    return 1;
}
