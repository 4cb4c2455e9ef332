#ifndef ZV_SANDBOX_INTERNAL_H
#define ZV_SANDBOX_INTERNAL_H
/* The sandbox's files among themselves. A child's work is a Req: plain
 * bytes and descriptors, so that it crosses to the fork server as one
 * message (server.c) as easily as it is handed to a child forked here;
 * the child runs it (child.c). The parent (sandbox.c) waits, counts the
 * files the child names into its memory bound (budget.c) and reads the
 * result back (wire.c). */

#include <linux/filter.h>
#include <stdint.h>
#include <sys/resource.h>
#include <sys/types.h>

#include "sandbox.h"

enum { REQ_LOAD, REQ_TEXTURE };

/* A request's descriptors (-1: none). The child keeps RESULT, ALIVE and
 * GO; it maps PROGRESS, PREFIX and DATA and closes them; STDIN, STDERR
 * and CWD stand in for its own (from the server: the requester's);
 * STATUS is the server's waiter's, never the child's. */
enum { RQ_RESULT, RQ_ALIVE, RQ_GO, RQ_PROGRESS, RQ_PREFIX, RQ_DATA, RQ_STDIN, RQ_STDERR, RQ_CWD, RQ_STATUS,
       RQ_NFD };

/* What the child writes on ALIVE: 'r' its result is ready; 'f', a kind
 * byte (1: an image), a 16-bit length and a path: a file it opened, to
 * be counted (the parent answers 'k' on GO). On GO: 'k', and 'w' (write
 * the arrays into the memfd); EOF ends it. */
#define REF_PATH_MAX 4000

typedef struct {
    uint32_t kind;              /* REQ_* */
    char     path[4096];        /* the model ("-": standard input), or a texture's name */
    char     format[32];        /* --format ("" detects) */
    int32_t  has_format;
    int32_t  strict, quiet, tex_defer_side, no_textures, threads;
    int32_t  wrap_u, wrap_v;    /* a texture's */
    uint64_t max_polys, max_bytes, piece_bytes;
    double   tessellation;      /* MeshLoadOpts's */
    uint64_t budget;            /* bytes the child may add (its soft limits) */
    uint64_t ceiling;           /* what the parent may raise them to (hard limits) */
    uint32_t cpu;               /* seconds */
    int32_t  on_ref;            /* tell the parent of each file named (budget.c) */
    uint64_t data_len;          /* DATA's bytes */
    uint64_t prefix_bytes;      /* PREFIX's layout (mesh_prefix_attach) */
    int      fd[RQ_NFD];
} Req;

/* A seccomp program (filter.c), its instructions malloc'd. */
typedef struct {
    struct sock_filter *ins;
    size_t              len;
} SandboxFilter;

/* The filter (filter.c), compiled once: make, with markers for the
 * child's numbers (0, or -1: the child then compiles its own); apply,
 * in the child, with its numbers in place (f NULL or empty: compiled
 * there, sandbox_filter_install): 0, or -1. compile: libseccomp's
 * program for these very numbers; patch: a copy of a made program with
 * them in place (the tests compare the two). */
int  sandbox_filter_make(SandboxFilter *f);
int  sandbox_filter_apply(const SandboxFilter *f, int memfd, int pipefd);
int  sandbox_filter_compile(SandboxFilter *out, uint32_t memfd, uint32_t pipefd, uint32_t self);
int  sandbox_filter_patch(const SandboxFilter *f, SandboxFilter *out, uint32_t memfd, uint32_t pipefd,
                          uint32_t self);
void sandbox_filter_free(SandboxFilter *f);

/* The child: never returns. filter: the program made once (NULL: the
 * child compiles its own). */
void sandbox_child_main(Req *r, const SandboxFilter *filter) __attribute__((noreturn));

/* A started child: its pid, and from the server a pidfd to signal it
 * by (-1: by pid) and the socket the server's waiter reports its end on
 * (-1: it is this process's own child: wait4). */
typedef struct {
    pid_t pid;
    int   pidfd;
    int   status;
} Child;

/* The fork server (server.c): start r's child there (0), or -1 when the
 * server is gone. The requester's standard input, error and working
 * folder go with it. */
int  sandbox_server_spawn(const SandboxServer *s, Req *r, Child *c);
/* The waiter's report of c's end: 0 with *status and *ru, or -1. */
int  sandbox_server_reap(Child *c, int *status, struct rusage *ru);

/* Landlock (landlock.c): confine this process's reads to the model's
 * folder (model NULL or "-": nothing by path) with the rights of ABI
 * abi; 0 (also when abi < 1: nothing done), or -1. The words for --info. */
int  sandbox_landlock_restrict(const char *model, int abi);
void sandbox_landlock_say(int abi, char *buf, size_t len);

/* Budgets (budget.c): what an input of so many bytes may take (native:
 * read by zview's own loaders), what an image of so many bytes may, the
 * budget of an allowance (at least SANDBOX_FLOOR), the hard ceiling
 * (the machine's memory), and the room a loader's threads take beyond
 * the input. */
uint64_t sandbox_input_allowance(uint64_t bytes, int native);
uint64_t sandbox_image_allowance(uint64_t bytes);
uint64_t sandbox_budget_of(uint64_t allowance);
uint64_t sandbox_ceiling(void);
void     sandbox_thread_room(int threads, uint64_t *as, uint64_t *data);

#endif
