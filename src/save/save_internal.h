#ifndef ZV_SAVE_INTERNAL_H
#define ZV_SAVE_INTERNAL_H
/* save_internal: what the front door (save.c) and the format writers
 * share: a buffered, checked output. The writers put bytes; the first
 * failure is kept with its errno and everything after it is dropped, so
 * that a writer runs to its end and the front door reports once. */

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "save.h"

#define SAVE_BUF (256 * 1024)

typedef struct {
    FILE    *f;
    char    *buf;               /* SAVE_BUF bytes */
    size_t   n;                 /* bytes waiting in buf */
    int      err;               /* errno of the first failure, 0 none */
    uint64_t bytes;             /* bytes put so far */
} SaveOut;

/* Write what is buffered; 0, or -1 (err set). */
int  so_flush(SaveOut *o);

static inline void so_put(SaveOut *o, const void *p, size_t n)
{
    o->bytes += n;
    if (n > SAVE_BUF - o->n && so_flush(o))
        return;
    if (n > SAVE_BUF) {         /* bigger than the buffer: straight through */
        errno = 0;
        if (!o->err && fwrite(p, 1, n, o->f) != n)
            o->err = errno ? errno : EIO;
        return;
    }
    memcpy(o->buf + o->n, p, n);
    o->n += n;
}

static inline void so_str(SaveOut *o, const char *s)
{
    so_put(o, s, strlen(s));
}

/* Room for at least n bytes at the buffer's end, to fill in place and
 * then commit with so_commit (n at most 4096). After a failure the
 * buffer is reused and its bytes dropped: the output is lost already. */
static inline char *so_room(SaveOut *o, size_t n)
{
    if (n > SAVE_BUF - o->n && so_flush(o))
        o->n = 0;
    return o->buf + o->n;
}

static inline void so_commit(SaveOut *o, size_t n)
{
    o->n += n;
    o->bytes += n;
}

/* A name from a file as one word of a text statement: controls (a
 * newline would end the statement) and a trailing backslash (which
 * would continue it) become '_', and the blanks around it go, as the
 * OBJ and MTL readers drop them. Writes NUL-terminated into dst (n >=
 * 1); returns dst. */
char *save_name_clean(char *dst, size_t n, const char *src);

/* The triangles of face f for a format of triangles (triangles.c): its
 * n - 2 triangles as corner offsets 0..n-1 within the face, 3 each, into
 * tri (3 (n - 2) entries); returns n - 2 (0 for fewer than 3 corners).
 * The scratch is the caller's, grown as needed (save_scratch_free). */
typedef struct {
    double  *mem;
    uint32_t cap;
} SaveScratch;
int  save_face_triangles(const Mesh *m, uint32_t f, uint32_t *tri, SaveScratch *s);
void save_scratch_free(SaveScratch *s);

/* The writers: the body of the model (and for OBJ, of its MTL) on o.
 * mtl_name: the library the OBJ names (NULL: none, the materials go). */
void save_stl(const Mesh *m, SaveOut *o, SaveReport *rep);
void save_ply(const Mesh *m, SaveOut *o, SaveReport *rep);
/* The OBJ needs its materials' names unique and clean: names holds
 * m->nmats of them, SAVE_NAME bytes each (save_obj_names fills it). */
#define SAVE_NAME MESH_NAME_MAX + 12
int  save_obj_names(const Mesh *m, char (*names)[SAVE_NAME]);
void save_obj(const Mesh *m, SaveOut *o, const char *mtl_name, char (*names)[SAVE_NAME], SaveReport *rep);
void save_mtl(const Mesh *m, SaveOut *o, char (*names)[SAVE_NAME]);

#endif
