/* fuzz_diff.c: the differential harness. The input decodes to a scene
 * (faces, points and lines), a view and a viewport (scenecode.h); every
 * algorithm renders it on one or two threads and must give the
 * z-buffer's face-id and depth buffers byte for byte. A difference
 * aborts, so libFuzzer keeps the input. */

#include <stdio.h>
#include <stdlib.h>

#include "fuzz.h"
#include "scenecode.h"
#include "testlib.h"

/* The render buffers live as long as the process: libFuzzer calls this
 * thousands of times a second, and fresh large buffers each time (mapped,
 * faulted in, unmapped) cost more than the rendering. Reachable at exit,
 * so no leak. */
static TlAgree bufs;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    Scene s;
    Viewport vp;
    int threads;
    if (sc_decode_style(data, size, &s, &vp, &threads, &bufs.style))
        return 0;
    char msg[512];
    long n = tl_agree(&bufs, &s, &vp, threads, msg, sizeof msg);
    if (n > 0) {
        fprintf(stderr, "fuzz_diff: %s\n", msg);
        abort();
    }
    scene_free(&s);
    return 0;
}
