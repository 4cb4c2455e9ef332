#ifndef ZV_MESHPREFIX_H
#define ZV_MESHPREFIX_H
/* meshprefix: what a load has parsed so far, for a picture while it
 * loads (the viewer's first file). The loader appends the vertices and
 * faces it has settled, in file order, to a shared mapping made before
 * the load starts (a memfd, so that a sandboxed child maps and writes
 * what its parent reads); the reader takes a copy of the
 * prefix as a Mesh built as a load builds one, checked as the sandbox's
 * wire checks what a child sends (the writer is not trusted).
 *
 * The prefix of a file that lists its vertices before its faces is,
 * face for face, the file cut after its last published face: the mesh
 * a load of that cut file makes (tests/test_meshprefix.c). Before the
 * first face it is the vertices as points, as a load of the cut file
 * shows a file of vertices alone. Only OBJ publishes; materials, vertex
 * colours and texture coordinates are not in it (the faces take the
 * default colour until the load is done). */

#include <stdint.h>

#include "mesh.h"

typedef struct MeshPrefix MeshPrefix;

/* The most faces published (a hold's aside): a picture of more shows no
 * more in a terminal, and the copy costs 16 bytes a face. */
#define MESH_PREFIX_FACES_MAX 4000000u

/* Room for the prefix of a file of `bytes` bytes (address space for the
 * densest OBJ such a file can be; pages are only made as they are
 * written). NULL when it cannot be had (no picture while loading). */
MeshPrefix *mesh_prefix_new(uint64_t bytes);
void        mesh_prefix_free(MeshPrefix *p);

/* The mapping is a memfd, for a writer in a process not forked from
 * this one (the sandbox's fork server): its descriptor and the size
 * given to mesh_prefix_new; there, mesh_prefix_attach(fd, bytes) is the
 * writer's view of it (NULL when it cannot be mapped). */
int         mesh_prefix_fd(const MeshPrefix *p, uint64_t *bytes_out);
MeshPrefix *mesh_prefix_attach(int fd, uint64_t bytes);

/* For tests (the viewer's ZV_TEST_HOLD): the writer publishes at most
 * `faces` faces, and once it has, waits until the file `path` exists
 * before it goes on. */
void        mesh_prefix_hold(MeshPrefix *p, uint64_t faces, const char *path);

/* The writer (the loader, between statements): append what m holds
 * past what was published; ncorner: the corners its faces use. */
void        mesh_prefix_publish(MeshPrefix *p, const Mesh *m, size_t ncorner);

/* The reader will take no more: the writer stops copying (but for a
 * hold's faces, which it still publishes). */
void        mesh_prefix_stop(MeshPrefix *p);

/* For tests: where the published arrays start (the vertices' floats
 * first) and how far the mapping goes past it. */
const void *mesh_prefix_data(const MeshPrefix *p, size_t *len);

/* Vertices and faces published so far (atomic reads). */
void        mesh_prefix_counts(const MeshPrefix *p, uint64_t *verts, uint64_t *faces);

/* The reader: a copy of the prefix as a mesh named `path` (as a load
 * of it would name it). Faces naming a vertex not (yet) published are
 * left out, as a load of the cut file skips them. 0 with *m filled, 1
 * when there is nothing to show yet, -1 out of memory. */
int         mesh_prefix_take(const MeshPrefix *p, const char *path, Mesh *m);

#endif
