/* memframes.c: does memory stay flat while the view turns? (issue 21;
 * make bench-memory runs it through tools/bench-memory.sh.) Loads the
 * models as zview does, then for each algorithm renders --views frames
 * (10,000 unless told) through pipeline_render, shading included, the
 * view turning half a degree a frame with a nod, as a user holding an
 * arrow key would. It prints, after frame 100 and after the last, the
 * process's resident memory (/proc/self/statm) and the bytes malloc has
 * handed out and not had back (mallinfo2: heap and mmap'd blocks), the
 * most resident at any hundredth frame between, and the growth per
 * frame. Frame 100 is the baseline: every buffer has grown to the
 * frame's size by then and the trees built in the background are
 * ready. Buffers sized by the view (a row's crossings, the polygons on
 * screen) may still grow until every view has been seen once: the turn
 * and the nod repeat every 720 frames, so the heap's growth from frame
 * TURN_FRAME (1,000) to the last (heap_B) is what no view explains: a
 * leak, or a cache without a bound.
 *
 *   memframes [zview options: --size, --samples, --threads, --algo
 *              (all, or a comma list), --views, --cull] MODEL... */

#define _DEFAULT_SOURCE         /* mallopt, mallinfo2 */

#include <malloc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"

#define BASE_FRAME 100
#define TURN_FRAME 1000         /* past a whole turn and nod (720 frames) */

/* Resident bytes, from /proc/self/statm (its second field, in pages). */
static long long resident_bytes(void)
{
    long long size = 0, res = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%lld %lld", &size, &res) != 2)
            res = 0;
        fclose(f);
    }
    return res * sysconf(_SC_PAGESIZE);
}

/* Bytes malloc has handed out: in use on the heap, and mmap'd blocks. */
static long long malloc_bytes(void)
{
    struct mallinfo2 mi = mallinfo2();
    return (long long)(mi.uordblks + mi.hblkhd);
}

/* Frame k's view: half a degree further round, nodding 10 degrees up
 * and down every 720 frames. */
static void turn(Scene *s, const Camera *start, int k)
{
    s->cam.yaw = start->yaw + deg2rad(0.5f * (float)k);
    s->cam.pitch = start->pitch + deg2rad(10.0f * sinf(6.2831853f * (float)k / 720));
}

typedef struct {
    long long rss0, rss1, rss_max, heap0, heap_turn, heap1;
} Mem;

/* N frames of s with algo; 0, or -1 when out of memory. */
static int run(Scene *s, const Options *o, const HsrAlgo *algo, int frames, Mem *m)
{
    Pipeline p;
    Camera start = s->cam;
    if (pipeline_init(&p, s, algo, o->threads))
        return -1;
    pipeline_apply_options(&p, o);
    int rc = 0;
    for (int k = 1; k <= frames && !rc; k++) {
        turn(s, &start, k);
        rc = pipeline_render(&p, o->w, o->h, 1.0f, o->cull, 1);
        if (k == BASE_FRAME || (frames < BASE_FRAME && k == frames)) {
            m->rss0 = m->rss_max = resident_bytes();
            m->heap0 = m->heap_turn = malloc_bytes();
        }
        if (k == TURN_FRAME)
            m->heap_turn = malloc_bytes();
        if (k >= BASE_FRAME && k % 100 == 0) {
            long long r = resident_bytes();
            m->rss_max = r > m->rss_max ? r : m->rss_max;
        }
    }
    m->rss1 = resident_bytes();
    m->heap1 = malloc_bytes();
    m->rss_max = m->rss1 > m->rss_max ? m->rss1 : m->rss_max;
    pipeline_free(&p);
    s->cam = start;
    return rc;
}

int main(int argc, char **argv)
{
    /* as zview's main does: big buffers come from mmap and go back */
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    Options o;
    char err[512];
    /* parsed as --bench's options are (it takes "all" and lists) */
    char **args = calloc((size_t)argc + 2, sizeof *args);
    if (!args)
        return 1;
    args[0] = argv[0];
    args[1] = "--bench";
    memcpy(args + 2, argv + 1, (size_t)(argc - 1) * sizeof *args);
    if (cli_parse(argc + 1, args, &o, err, sizeof err) || o.nfiles == 0) {
        fprintf(stderr, "memframes: %s\nusage: memframes [--size WxH] [--samples N] [--threads N] [--algo A,B]"
                        " [--views N] MODEL...\n", o.nfiles ? err : "no model");
        return 2;
    }
    int frames = o.views > 8 ? o.views : 10000;     /* 8: --bench's default, not asked for */
    o.w = o.w > 0 ? o.w : 160;
    o.h = o.h > 0 ? o.h : 96;
    o.samples = o.samples > 0 ? o.samples : TEXT_SAMPLES;
    o.threads = o.threads > 0 ? o.threads : 1;
    /* the algorithms: all of them, or the comma list --algo names */
    const HsrAlgo *algos[16];
    int nalgos = 0;
    char list[256];
    snprintf(list, sizeof list, "%s", o.algo && strcmp(o.algo, "all") ? o.algo : "");
    for (char *t = strtok(list, ","); t && nalgos < 16; t = strtok(NULL, ","))
        if (!(algos[nalgos++] = hsr_find(t))) {
            fprintf(stderr, "memframes: unknown algorithm '%s'\n", t);
            return 2;
        }
    if (nalgos == 0)
        for (int a = 0; a < hsr_nalgos && a < 16; a++)
            algos[nalgos++] = hsr_algos[a];
    printf("%-20s %-11s %-14s %2s %7s %9s %9s %9s %9s %10s %9s %9s\n", "model", "algo", "size", "th", "frames",
           "rss100_MB", "rssN_MB", "rssmax_MB", "grow_KB", "heap100_MB", "heapN_MB", "heap_B");
    int rc = 0;
    for (int f = 0; f < o.nfiles && !rc; f++) {
        Options one = o;
        one.nfiles = 1;
        one.files[0] = o.files[f];
        Scene s;
        if (app_load_scene(&one, &s, err, sizeof err)) {
            fprintf(stderr, "memframes: %s\n", err);
            return 1;
        }
        const char *base = strrchr(o.files[f], '/');
        base = base ? base + 1 : o.files[f];
        for (int a = 0; a < nalgos && !rc; a++) {
            const HsrAlgo *algo = algos[a];
            Mem m;
            if (run(&s, &one, algo, frames, &m)) {
                fprintf(stderr, "memframes: out of memory\n");
                rc = 1;
                break;
            }
            char size[32];
            snprintf(size, sizeof size, "%dx%dx%d", o.w, o.h, o.samples);
            printf("%-20s %-11s %-14s %2d %7d %9.1f %9.1f %9.1f %9lld %10.1f %9.1f %9.0f\n", base, algo->name, size,
                   o.threads, frames, m.rss0 / 1048576.0, m.rss1 / 1048576.0, m.rss_max / 1048576.0,
                   (m.rss1 - m.rss0) / 1024, m.heap0 / 1048576.0, m.heap1 / 1048576.0,
                   (double)(m.heap1 - m.heap_turn));
            fflush(stdout);
        }
        scene_free(&s);
    }
    free(args);
    return rc;
}
