/* checkbench.c: what --check costs beyond loading, for make bench-check
 * (tools/bench-check.sh). Loads a model as zview does, then runs the
 * check on it and prints one line: the load's wall time, the check's
 * wall time and its phases, and the process's peak resident memory.
 *
 *   checkbench [-j THREADS] [--no-cross] [-l N] [--load-only] MODEL
 *
 * -l N locates the first N problems of each kind, as --check
 * does (3 for the text report, --max-locations for --json: 100).
 * --load-only stops after the load: its peak memory is "loading alone",
 * what the check's peak is compared with. */

#define _DEFAULT_SOURCE         /* mallopt */

#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "clock.h"
#include "meshcheck.h"

static long peak_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

int main(int argc, char **argv)
{
    CheckOpts opt = { .threads = 1, .intersections = 1 };
    int load_only = 0;
    const char *path = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-j") && i + 1 < argc)
            opt.threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--no-cross"))
            opt.intersections = 0;
        else if (!strcmp(argv[i], "-l") && i + 1 < argc)
            opt.locations = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--load-only"))
            load_only = 1;
        else
            path = argv[i];
    }
    if (!path) {
        fprintf(stderr, "usage: checkbench [-j THREADS] [--no-cross] [-l N] [--load-only] MODEL\n");
        return 2;
    }
    /* as zview's main does: big arrays go back to the system when freed */
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    Mesh m;
    char err[512];
    double t0 = now_ms();
    if (mesh_load(&m, path, err, sizeof err)) {
        fprintf(stderr, "checkbench: %s\n", err);
        return 1;
    }
    double load_ms = now_ms() - t0;
    /* as --check does (oneshot/checkreport.c): what the check does not read
     * goes before it starts */
    free(m.face_mat);
    m.face_mat = NULL;
    free(m.rgb);
    m.rgb = NULL;
    if (load_only) {
        printf("%-28s faces %9u  load %7.1f ms  peak %7.1f MB (loading alone)\n", path, m.nfaces, load_ms,
               peak_kb() / 1024.0);
        mesh_free(&m);
        return 0;
    }
    MeshCheck mc;
    t0 = now_ms();
    double c0 = process_cpu_ms();
    if (meshcheck_run(&mc, &m, &opt, err, sizeof err)) {
        fprintf(stderr, "checkbench: %s\n", err);
        return 1;
    }
    double ms = now_ms() - t0, cpu = process_cpu_ms() - c0;
    char verdict[256];
    meshcheck_verdict(&mc.file, verdict, sizeof verdict);
    printf("%-28s faces %9u  load %7.1f ms  check %7.1f ms, cpu %7.1f ms (weld %.0f, edges %.0f, shape %.0f, dups %.0f, "
           "cross %.0f)  threads %d%s%s  peak %7.1f MB  [%s]\n",
           path, m.nfaces, load_ms, ms, cpu, mc.ms[CHECK_T_WELD], mc.ms[CHECK_T_EDGES], mc.ms[CHECK_T_SHAPE],
           mc.ms[CHECK_T_DUPS], mc.ms[CHECK_T_CROSS], opt.threads, opt.intersections ? "" : ", no crossings",
           opt.locations ? ", located" : "", peak_kb() / 1024.0, verdict);
    meshcheck_free(&mc);
    mesh_free(&m);
    return 0;
}
