/* repairbench.c: what repair_mesh costs beyond loading, for make
 * bench-repair (tools/bench-repair.sh). Loads a model as zview does,
 * repairs it and prints one line: the load's wall time, the repair's
 * wall and CPU time and its phases, the process's peak resident memory,
 * and the report's figures (what each step did, what is left).
 *
 *   repairbench [-j THREADS] [--steps MASK] [--eps D] [--max-hole N]
 *               [--cross] [--load-only] [--obj OUT] MODEL
 *
 * --load-only stops after the load: its peak memory is "loading alone".
 * --obj writes the repaired mesh as plain OBJ (positions as %.9g, which
 * reads back to the same floats; faces only): for looking at, not the
 * command line's writer. */

#define _DEFAULT_SOURCE         /* mallopt */

#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "clock.h"
#include "repair.h"

static long peak_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

static int write_obj(const Mesh *m, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    for (uint32_t v = 0; v < m->nverts; v++)
        fprintf(f, "v %.9g %.9g %.9g\n", m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]);
    for (uint32_t i = 0; i < m->nobjs; i++) {
        const MeshObject *o = &m->objs[i];
        fprintf(f, "o %s\n", o->name);
        for (uint32_t k = o->face_first; k < o->face_first + o->face_count; k++) {
            fputc('f', f);
            for (uint32_t c = m->face_start[k]; c < m->face_start[k + 1]; c++)
                fprintf(f, " %u", m->corner[c] + 1);
            fputc('\n', f);
        }
    }
    return fclose(f) ? -1 : 0;
}

int main(int argc, char **argv)
{
    RepairOpts opt = { .steps = REPAIR_DEFAULT, .threads = 1 };
    int load_only = 0;
    const char *path = NULL, *out = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-j") && i + 1 < argc)
            opt.threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--steps") && i + 1 < argc)
            opt.steps = (unsigned)strtoul(argv[++i], NULL, 0);
        else if (!strcmp(argv[i], "--eps") && i + 1 < argc)
            opt.weld_eps = atof(argv[++i]);
        else if (!strcmp(argv[i], "--max-hole") && i + 1 < argc)
            opt.max_hole = (uint32_t)strtoul(argv[++i], NULL, 0);
        else if (!strcmp(argv[i], "--cross"))
            opt.intersections = 1;
        else if (!strcmp(argv[i], "--load-only"))
            load_only = 1;
        else if (!strcmp(argv[i], "--obj") && i + 1 < argc)
            out = argv[++i];
        else
            path = argv[i];
    }
    if (!path) {
        fprintf(stderr, "usage: repairbench [-j N] [--steps MASK] [--eps D] [--max-hole N] [--cross] [--load-only] "
                        "[--obj OUT] MODEL\n");
        return 2;
    }
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    Mesh m;
    char err[512];
    double t0 = now_ms();
    if (mesh_load(&m, path, err, sizeof err)) {
        fprintf(stderr, "repairbench: %s\n", err);
        return 1;
    }
    double load_ms = now_ms() - t0;
    if (load_only) {
        printf("%-28s faces %9u  load %7.1f ms  peak %7.1f MB (loading alone)\n", path, m.nfaces, load_ms,
               peak_kb() / 1024.0);
        mesh_free(&m);
        return 0;
    }
    RepairReport rep;
    double c0 = process_cpu_ms();
    if (repair_mesh(&m, &opt, &rep, err, sizeof err)) {
        fprintf(stderr, "repairbench: %s\n", err);
        return 1;
    }
    double cpu = process_cpu_ms() - c0;
    printf("%-28s faces %9u  load %7.1f ms  repair %7.1f ms, cpu %7.1f ms (weld %.0f, clean %.0f, objects %.0f, "
           "order %.0f, check %.0f)  threads %d  peak %7.1f MB  [",
           path, rep.faces_before, load_ms, rep.ms, cpu, rep.ms_phase[REPAIR_T_WELD], rep.ms_phase[REPAIR_T_CLEAN],
           rep.ms_phase[REPAIR_T_OBJECTS], rep.ms_phase[REPAIR_T_ORDER], rep.ms_phase[REPAIR_T_CHECK], opt.threads,
           peak_kb() / 1024.0);
    int first = 1;
    for (int i = 0; i < repair_nrows; i++) {
        char words[160];
        repair_say(&repair_rows[i], &rep, words, sizeof words);
        if (words[0]) {
            printf("%s%s", first ? "" : ", ", words);
            first = 0;
        }
    }
    printf("]\n");
    for (uint32_t i = 0; i < rep.nholes && i < 10; i++)
        printf("  open: object %u, %u edges at vertex %u: %s\n", rep.holes[i].object, rep.holes[i].edges,
               rep.holes[i].vertex + 1, repair_open_why(rep.holes[i].why));
    repair_report_free(&rep);
    int rc = out && write_obj(&m, out) ? 1 : 0;
    if (rc)
        fprintf(stderr, "repairbench: cannot write %s\n", out);
    mesh_free(&m);
    return rc;
}
