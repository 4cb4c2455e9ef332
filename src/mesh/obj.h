#ifndef ZV_MESH_OBJ_H
#define ZV_MESH_OBJ_H
/* obj: what the OBJ loader's three parts share, the parser's state.
 * obj.c reads the file line by line and the statements that carry
 * numbers (v, vt, vn) or nothing drawn; objface.c the statements that
 * list vertices (f, p, l), and after the last line drops what used a
 * vertex that could not be read; objmtl.c materials: usemtl names,
 * mtllib files (each read once), names resolved at the end. Not part
 * of the public API. */

#include <stddef.h>
#include <stdint.h>

#include "mesh_internal.h"

static inline int is_digit(char c) { return mesh_is_digit(c); }
static inline int is_space(char c) { return mesh_is_blank(c); }

/* ==== Name sets (objmtl.c) ==== */

/* Open-addressing index over an array of names, so that usemtl and the
 * final material lookup stay linear however many materials a file has.
 * Slots hold index + 1; 0 is empty. */
typedef struct {
    uint32_t *slot;
    uint32_t  cap;   /* power of two, or 0 */
    uint32_t  used;
} NameIndex;

/* The names mtllib lines gave (resolved against the OBJ's folder), so
 * that a name repeated on every line is looked at once, and the files
 * read (device and inode), so that two names of one file read it once. */
typedef struct {
    char    **names;
    uint32_t  nnames, namecap;
    uint32_t *slot;              /* name index + 1, open addressing; 0 = empty */
    uint32_t  slotcap;
    uint64_t *files;             /* dev, ino pairs */
    uint32_t  nfiles, filecap;
} LibSet;

/* ==== Parser state ==== */

typedef struct {
    char     name[MESH_NAME_MAX];
    uint64_t line;               /* first usemtl naming it */
} UseName;

/* A statement with an index past the vertices read so far; for a `p`
 * statement, the points it added (all dropped when it is skipped). */
typedef struct {
    uint64_t line, max;
    uint32_t point_first, point_count;
} FwdRef;

typedef struct {
    Mesh       *m;
    MeshBuild   b;
    MeshErr    *e;
    const char *path;            /* on disk, for mtllib; NULL: open nothing */
    uint64_t    line;            /* current (first physical) line, 1-based */

    int32_t     cur_use;         /* index into uses, -1 before any usemtl */
    UseName    *uses;
    uint32_t    nuse, usecap;
    NameIndex   use_index;
    int         mtl_loaded;      /* some mtllib opened: unknown names warn */
    LibSet      libs;
    /* Material libraries that could not be read: the first few warn by
     * name, the rest are counted into one warning at the end (a file can
     * name 50,000 missing ones). Opening them is bounded too. */
    uint32_t    lib_tries;       /* libraries looked for */
    uint32_t    lib_failed;      /* ... that could not be read */
    uint64_t    lib_bytes;       /* bytes of libraries read */

    /* Positive indices may point past the vertices read so far; they
     * are checked once the whole file is read, against the largest.
     * Leniently, each statement that had one is kept in fwd[] (its
     * line and largest index), so that the bad ones can be skipped. */
    uint64_t    fwd_max;
    uint64_t    fwd_line;
    FwdRef     *fwd;
    uint32_t    nfwd, fwdcap;
    int         stmt_failed;     /* the statement being read could not be */
    int         stmt_vertex;     /* ... and it is a `v` */
    int         saw_elements;    /* some f, l or p statement, read or not */
    uint32_t    undrawn;         /* free-form statements (undrawn_kw) */
    const char *first_undrawn;
    /* Vertices whose statement could not be read keep their number (so
     * later indices still mean what the file meant): a stand-in is
     * added, and whatever uses it is dropped at the end. */
    uint32_t   *bad_vert;
    uint32_t    nbad, badcap;

    char       *scratch;         /* joined `\` continuation lines */
    size_t      scap;

    /* A piece of the file parsed apart (objpar.c): indices that count
     * back (-1) resolve within the piece and are marked OBJ_LOCAL, the
     * merge adding the vertices before it, or, reaching back past its
     * start, are marked OBJ_EXTERN with how far past (the merge takes
     * them from the vertices before it); faces before the piece's first
     * usemtl take OBJ_INHERIT; whatever the piece cannot judge alone (an
     * mtllib, any statement that fails) fails it, and the file is read
     * on from there by the serial parser. fwd_max: the largest positive
     * index past the piece's own vertices; ext_max: the farthest back
     * past its start. */
    int         piece;
    int         renamed0;        /* an `o` named the piece's first object */
    uint32_t    ext_max;
} Parser;

/* A piece's index resolved within the piece (at most 2^29 vertices fit
 * in the 4 GB a file may have, at 8 bytes a vertex at least, so the top
 * bits are free). */
#define OBJ_LOCAL 0x80000000u
/* A piece's index counting back past its start, by OBJ_FAR_MASK (at
 * most OBJ_FAR_MAX) before its first vertex. */
#define OBJ_EXTERN 0xC0000000u
#define OBJ_FAR_MASK 0x3FFFFFFFu
#define OBJ_FAR_MAX (1u << 29)
/* A texture coordinate index a piece cannot resolve (never a valid one:
 * nor local, since no file has 2^31 entries, nor MESH_NO_UV). */
#define OBJ_UNKNOWN 0xFFFFFFFEu
/* A piece's faces before its first usemtl: the material current where
 * the piece starts. */
#define OBJ_INHERIT (-2)

/* ==== The lines (obj.c) ==== */

/* A parser for the mesh c builds (mb_start'ed), serial or a piece. */
int  obj_parser_init(Parser *ps, MeshCtx *c, int piece);
void obj_parser_free(Parser *ps);
/* One logical line; a statement that cannot be read is skipped (undone
 * and counted) unless the load is strict. Returns -1 to stop. */
int  obj_statement(Parser *ps, const char *ls, const char *e);
/* Read the lines lr gives to its end (file_end: the text's, for the
 * message): 0, 1 when a NUL ended the text (the rest is not read), -1
 * to stop. */
int  obj_lines(Parser *ps, LineReader *lr, const char *file_end);
/* After the last line: what only the whole file settles, then the
 * finish. 0 or -1. */
int  obj_finish(Parser *ps);

/* ==== Parsing on every core (objpar.c) ==== */

/* Parse text[from, len) (the start of the file is `text`) with ps, in
 * pieces on several threads when it is big enough and the load allows
 * (MeshErr.threads), else serially: the mesh, its ids, objects,
 * materials, warnings and messages are those of the serial parse.
 * Returns obj_lines' result. */
int  obj_parse_parallel(Parser *ps, MeshCtx *c, const char *text, size_t from, size_t len);

/* ==== Messages (obj.c) ==== */

/* The statement being read cannot be: "path:line: msg". Returns -1. */
int obj_fail(Parser *ps, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static inline int obj_oom(Parser *ps) { return me_oom(ps->e); }

/* The rest of a statement, trimmed: [*p, *e). */
static inline void obj_trim(const char **p, const char **e)
{
    while (*p < *e && is_space(**p))
        (*p)++;
    while (*e > *p && is_space((*e)[-1]))
        (*e)--;
}

/* ==== Faces, points and lines (objface.c) ==== */

/* f, p and l: [p, e) is the statement after its keyword, ls its line's
 * start (for messages). 0, or -1 (obj_fail's message, or out of memory). */
int obj_face(Parser *ps, const char *ls, const char *p, const char *e);
int obj_points(Parser *ps, const char *ls, const char *p, const char *e);
int obj_polyline(Parser *ps, const char *ls, const char *p, const char *e);
/* After the last line: what could not be resolved until the end (see
 * objface.c). 0 or -1. */
int obj_drop_unreadable(Parser *ps);

/* ==== Materials (objmtl.c) ==== */

/* usemtl NAME: the faces after it take that name's material. */
int obj_use_material(Parser *ps, const char *p, const char *e);
/* The index of usemtl name `name` (first named at `line`), added when
 * new; -1 out of memory. */
int32_t obj_use_index(Parser *ps, const char *name, uint64_t line);
/* mtllib NAME...: each library read (once) into the mesh's materials. */
int obj_mtllib(Parser *ps, const char *p, const char *e);
/* After the last line: usemtl names to material indices. 0 or -1. */
int obj_resolve_materials(Parser *ps);
/* The warning that counts the libraries not named in one. */
void obj_libs_warn(Parser *ps);
void obj_materials_free(Parser *ps);

#endif
