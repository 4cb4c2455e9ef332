#ifndef ZV_SANDBOX_H
#define ZV_SANDBOX_H
/* sandbox: mesh_load in a child process that can do nothing but read and
 * fail. A model file is input from strangers, and its parsers (assimp's
 * above all) have a long record of memory-safety bugs; whatever a
 * malformed file makes a parser do happens in a child that
 *   - has a seccomp-bpf filter: it may read files, map memory, make
 *     threads and write to standard error; creating or writing files,
 *     exec, sockets, ptrace, signals to other processes and the rest are
 *     refused (the attacks kill the child, the rest fail with EPERM);
 *   - has limits: address space (the memory it may add: --max-memory, by
 *     default what the machine has available), CPU time, no core file;
 *   - hands the Mesh back: a header in a memfd says where its arrays
 *     are, and the parent copies them straight out of the child's memory
 *     (process_vm_readv: one copy), or, where it may not, out of the
 *     memfd the child then fills; the error text and warnings come in
 *     MeshInfo as in a load in-process.
 * A child that crashes, breaks the filter or passes a limit becomes one
 * line naming the file ("x.fbx: the loader crashed (Segmentation fault)
 * in the sandbox"). Knows nothing of scenes or terminals. */

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "mesh.h"

/* CPU time a load may take. A 30 M-triangle file loads in well under a
 * minute on a slow machine; a file that keeps a parser busy longer is
 * taken for hostile (assimp's node DAGs grow without end). */
#define SANDBOX_CPU_SECONDS 120

typedef struct {
    int      off;           /* --no-sandbox: load in this process */
    uint64_t max_memory;    /* bytes the load may add to the address space; 0: what is available */
    unsigned cpu_seconds;   /* 0: SANDBOX_CPU_SECONDS */
} SandboxOpts;

/* Can this system sandbox a load (a kernel with seccomp filters)? When
 * it cannot, sandbox_load loads in-process (the caller warns once). */
int sandbox_available(void);

/* mesh_load_ex in a child (in-process when so->off or no seccomp). Same
 * contract: 0, or -1 with "path: message" in err and *m empty. A set
 * lo->cancel ends the child at once ("path: cancelled"); lo->progress
 * is copied from the child's while it runs. so may be NULL (defaults). */
int sandbox_load(Mesh *m, const char *path, const MeshLoadOpts *lo, const SandboxOpts *so, char *err,
                 size_t errlen);

/* mesh_parse_buffer_ex in a child: the bytes are already here (a FIFO
 * read by the viewer), path names them and gives the folder for what
 * they reference. */
int sandbox_parse_buffer(Mesh *m, const char *path, const MeshLoadOpts *lo, const SandboxOpts *so,
                         const void *data, size_t len, char *err, size_t errlen);

/* ---- Used by the sandbox's own files and its tests ---- */

/* The result of a load in a memfd: a header (rc, err, the Mesh's
 * scalars, where each array is) and, unless in_child, every array after
 * it. in_child: the arrays stay in the child's memory, which the parent
 * reads with process_vm_readv while the child waits. wire_read rebuilds
 * *m (arrays malloc'd, as mesh_free expects) from fd's len bytes, or from
 * the memory of pid when the header says so (pid 0: never), checking
 * every offset, length and index (the child is not trusted): 0 (*rc the
 * load's result, err its message), or -1 with a message. */
int sandbox_wire_write(int fd, const Mesh *m, int rc, const char *err, int in_child);
int sandbox_wire_read(int fd, size_t len, pid_t pid, Mesh *m, int *rc, char *err, size_t errlen);

/* Install the child's filter (memfd: the result's; pipefd: the one it
 * may write to besides standard error): 0, or -1 when seccomp cannot be
 * had. */
int sandbox_filter_install(int memfd, int pipefd);

/* The child's standard error (childerr.c): a pipe the parent reads while
 * it waits, passing on zview's lines made safe (safetext.h) and dropping
 * a library's own. open: the parent's end in ce, the child's in
 * *child_end (0, or -1 when no pipe can be had: the child then writes
 * straight to standard error); read: what is there now, without
 * waiting; close: the rest, then the pipe closed. */
typedef struct {
    int    fd;          /* the parent's end, non-blocking; -1: none */
    size_t n;           /* bytes of the line so far */
    int    over;        /* the line was longer than line: the rest is dropped */
    char   line[1024];
} ChildErr;
int  childerr_open(ChildErr *ce, int *child_end);
void childerr_read(ChildErr *ce);
void childerr_close(ChildErr *ce);

#endif
