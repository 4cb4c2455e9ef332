/* objpar.c: an OBJ parsed on every core. The file is cut into pieces at
 * line starts; the first piece is read by the serial parser itself (it
 * may name material libraries, which are read in order), the others
 * each by a parser of its own into a mesh of its own (obj.h: a piece),
 * and they are merged into the serial parser's mesh in file order, as
 * each is done, so that the arrays of a few pieces at most exist twice.
 * What a piece cannot settle alone (a library, any statement that
 * cannot be read, a `\` line, a NUL, an index past its end or back past
 * the first vertex) fails it, and the serial parser reads on from its
 * start, with the state the merges left, which is the state a serial
 * parse has there:
 * the mesh, ids, objects, materials, warnings and messages are the
 * serial parse's in every case (tests/test_objpar.c compares them). */
#define _GNU_SOURCE     /* memrchr */

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "grow.h"
#include "meshprefix.h"
#include "obj.h"
#include "pool.h"

/* Pieces of this many bytes (the last ones a little more): big enough
 * that the merge is a small part of the work, small enough that both
 * cores have several to take. */
#define PIECE_BYTES ((uint64_t)8 << 20)
#define MAX_PIECES 4096
/* A cut is looked for this far past where a piece would end. */
#define CUT_LOOK ((size_t)64 << 10)
/* A piece of a mapped file is read in blocks of this size (pread: the
 * mapping's window is the serial parser's alone). */
#define READ_BLOCK ((size_t)4 << 20)

enum { PC_TODO = 0, PC_DONE, PC_FAILED };

typedef struct {
    size_t   from, to;      /* its bytes of the file */
    int      state;         /* PC_*, under the run's lock */
    uint64_t lines;
    MeshCtx  c;             /* its own mesh and messages (quiet) */
    Mesh     m;
    Parser   ps;
    int      started;       /* ps is set up (to be freed) */
} Piece;

typedef struct {
    Parser         *ps;     /* the serial parser: the first piece, the merges, the rest */
    MeshCtx        *c;
    const char     *text;
    size_t          len;
    Piece          *pc;
    int             n;
    pthread_mutex_t mu;
    int             merged; /* pieces merged so far */
    int             stop;   /* the first piece not to be merged (n: none); atomic */
    int             failed; /* the first piece known to have failed (n: none); atomic:
                             * the pieces after it are read again serially whatever
                             * they hold, so none is parsed alone any more */
    int             fatal;  /* the load fails (the serial parser's message) */
    int             first_rc;
    uint64_t        lines;  /* lines of the pieces merged */
} Run;

/* ==== Cutting ==== */

/* Is the line start at i a place to cut: after a line end, the line
 * before not continued by a `\`? p holds bytes [base, ...). */
static int cut_ok(const char *p, size_t base, size_t i)
{
    if (i < base + 1 || p[i - 1 - base] != '\n')
        return 0;
    size_t j = i - 1;
    if (j > base && p[j - 1 - base] == '\r')
        j--;
    return !(j > base && p[j - 1 - base] == '\\');
}

/* The first place to cut in [at, at + CUT_LOOK), or 0. */
static size_t find_cut(const Run *r, size_t at)
{
    size_t lo = at >= 3 ? at - 3 : 0, hi = at + CUT_LOOK < r->len ? at + CUT_LOOK : r->len;
    const char *p = r->text + lo;
    char *buf = NULL;
    MeshFile *f = r->c->file;
    if (f && f->map) {
        buf = malloc(hi - lo);
        if (!buf || pread(f->fd, buf, hi - lo, (off_t)lo) != (ssize_t)(hi - lo)) {
            free(buf);
            return 0;
        }
        p = buf;
    }
    size_t cut = 0;
    for (size_t i = at; i < hi && !cut; i++)
        if (cut_ok(p, lo, i))
            cut = i;
    free(buf);
    return cut;
}

/* The pieces of [from, len): *n of them (1: parse serially). */
static Piece *cut_pieces(Run *r, size_t from, uint64_t piece, int *n)
{
    uint64_t span = r->len - from;
    if (span / piece > MAX_PIECES)
        piece = span / MAX_PIECES;
    int most = (int)(span / piece) + 1;
    Piece *pc = calloc((size_t)most, sizeof *pc);
    if (!pc)
        return NULL;
    int k = 0;
    pc[0].from = from;
    for (uint64_t at = from + piece; at + piece / 2 < r->len && k + 1 < most; at += piece) {
        size_t cut = find_cut(r, (size_t)at);
        if (!cut || cut <= pc[k].from || cut >= r->len)
            continue;
        pc[k].to = cut;
        pc[++k].from = cut;
    }
    pc[k].to = r->len;
    *n = k + 1;
    return pc;
}

/* ==== A piece ==== */

/* The lines lr gives, each a statement of its own: 0, or -1 when the
 * piece cannot be settled alone. */
static int piece_read(Parser *ps, LineReader *lr)
{
    const char *ls, *le;
    while (lr_next(lr, &ls, &le)) {
        ps->line = lr->line;
        if (le > ls && (le[-1] == '\\' || le[-1] == '\0'))
            return -1;
        if (obj_statement(ps, ls, le) || ps->e->skipped || ps->e->warned)
            return -1;
    }
    return 0;
}

/* A piece of a mapped file, read in blocks of whole lines. */
static int piece_read_file(Piece *p, MeshFile *f)
{
    size_t cap = READ_BLOCK, have = 0, at = p->from;
    char *buf = malloc(cap);
    int rc = buf ? 0 : -1;
    while (!rc && (at < p->to || have)) {
        if (f->cancel && __atomic_load_n(f->cancel, __ATOMIC_RELAXED)) {
            rc = -1;        /* the serial parser stops as cancelled */
            break;
        }
        size_t want = cap - have < p->to - at ? cap - have : p->to - at;
        ssize_t got = want ? pread(f->fd, buf + have, want, (off_t)at) : 0;
        if (got < 0 || (size_t)got != want) {
            rc = -1;        /* changed under us: the serial parser says so */
            break;
        }
        at += want;
        have += want;
        size_t use = have;
        if (at < p->to) {
            const char *nl = memrchr(buf, '\n', have);
            if (!nl) {      /* a line longer than the block */
                char *nb = realloc(buf, cap * 2);
                rc = nb ? 0 : -1;
                buf = nb ? nb : buf;
                cap *= 2;
                continue;
            }
            use = (size_t)(nl + 1 - buf);
        }
        LineReader lr;
        lr_init(&lr, buf, use, NULL);
        lr.line = p->lines;
        rc = piece_read(&p->ps, &lr);
        p->lines = lr.line;
        memmove(buf, buf + use, have - use);
        have -= use;
    }
    free(buf);
    return rc;
}

static int piece_parse(Run *r, Piece *p)
{
    const MeshErr *e = &r->c->err;
    p->c = (MeshCtx){ .m = &p->m,
                      .err = { .name = e->name, .strict = e->strict, .quiet = 1, .max_polys = e->max_polys,
                               .max_bytes = e->max_bytes } };
    if (obj_parser_init(&p->ps, &p->c, 1))
        return -1;
    p->started = 1;
    size_t guess = (p->to - p->from) / 24;
    if (mb_reserve_ex(&p->ps.b, guess, guess, 3 * guess, 0))
        return -1;
    MeshFile *f = r->c->file;
    if (f && f->map)
        return piece_read_file(p, f);
    LineReader lr;
    lr_init(&lr, r->text + p->from, p->to - p->from, NULL);
    int rc = piece_read(&p->ps, &lr);
    p->lines = lr.line;
    return rc;
}

static void piece_free(Piece *p)
{
    if (!p->started)
        return;
    obj_parser_free(&p->ps);
    mb_abort(&p->ps.b);
    p->started = 0;
}

/* ==== Merging ==== */

/* A piece's vertex index, with `base` vertices before the piece (the
 * merge checked that OBJ_EXTERN ones reach no farther back). */
static inline uint32_t fix(uint32_t v, uint32_t base)
{
    if (!(v & OBJ_LOCAL))
        return v;
    if ((v & OBJ_EXTERN) == OBJ_EXTERN)
        return base - (v & OBJ_FAR_MASK);
    return (v & ~OBJ_LOCAL) + base;
}

/* The same for a texture coordinate entry: one reaching back past the
 * entries there are is none, as in the serial parse. */
static inline uint32_t fix_uv(uint32_t t, uint32_t base)
{
    if (t == MESH_NO_UV)
        return t;
    if ((t & OBJ_EXTERN) == OBJ_EXTERN)
        return (t & OBJ_FAR_MASK) <= base ? base - (t & OBJ_FAR_MASK) : MESH_NO_UV;
    return fix(t, base);
}

/* Room for the piece in the serial parser's arrays (growing by half
 * again, not exactly). Nothing else changes, so a failure (a bound)
 * leaves the state a serial parse has at the piece's start. */
static int merge_room(Parser *ps, const Piece *p)
{
    MeshBuild *b = &ps->b;
    const Mesh *m = ps->m, *pm = &p->m;
    const Parser *pp = &p->ps;
    /* an index past the piece's end: a serial parse keeps such
     * statements apart (obj_drop_unreadable); it reads on from here */
    if (pp->fwd_max > (uint64_t)m->nverts + pm->nverts)
        return -1;
    /* an index back past the first vertex: the serial parse says so */
    if (pp->ext_max > m->nverts)
        return -1;
    /* a polygon bound met inside: where the serial parse meets it */
    uint64_t polys = (uint64_t)m->nfaces + m->npoints + pm->nfaces + pm->npoints;
    if (ps->e->max_polys && polys > ps->e->max_polys)
        return -1;
    size_t v = m->nverts + (size_t)pm->nverts > b->vcap ? pm->nverts + (size_t)m->nverts / 2 : 0;
    size_t f = m->nfaces + (size_t)pm->nfaces > b->fcap ? pm->nfaces + (size_t)m->nfaces / 2 : 0;
    size_t c = b->ncorner + pp->b.ncorner > b->ccap ? pp->b.ncorner + b->ncorner / 2 : 0;
    return mb_reserve_ex(b, v, f, c, 0);
}

/* Vertices, colours and texture coordinates. 0 or -1 (out of memory). */
static int merge_vertices(Parser *ps, const Piece *p)
{
    MeshBuild *b = &ps->b;
    Mesh *m = ps->m;
    const Mesh *pm = &p->m;
    if (pm->rgb && !m->rgb && mb_want_rgb(b))
        return -1;
    /* (memcpy may not be given NULL, even for nothing) */
    if (pm->nverts)
        memcpy(m->pos + 3 * (size_t)m->nverts, pm->pos, 3 * sizeof(float) * pm->nverts);
    if (m->rgb) {
        float *d = m->rgb + 3 * (size_t)m->nverts;
        if (pm->rgb && pm->nverts)
            memcpy(d, pm->rgb, 3 * sizeof(float) * pm->nverts);
        else if (!pm->rgb)
            for (size_t i = 0; i < 3 * (size_t)pm->nverts; i++)
                d[i] = 1.0f;
    }
    m->nverts += pm->nverts;
    if (pm->nuv) {
        if (grow_size((void **)&m->uv, &b->uvcap, (size_t)m->nuv + pm->nuv, 2 * sizeof(float)))
            return -1;
        memcpy(m->uv + 2 * (size_t)m->nuv, pm->uv, 2 * sizeof(float) * pm->nuv);
    }
    return 0;
}

/* Faces: corners (and their texture coordinates), starts, materials. */
static int merge_faces(Parser *ps, const Piece *p, const int32_t *usemap, uint32_t vbase, uint32_t uvbase)
{
    MeshBuild *b = &ps->b;
    Mesh *m = ps->m;
    const Mesh *pm = &p->m;
    size_t cbase = b->ncorner, nc = p->ps.b.ncorner;
    for (size_t i = 0; i < nc; i++)
        m->corner[cbase + i] = fix(pm->corner[i], vbase);
    /* the array is made at the first corner that has an entry: one
     * reaching back too far has none */
    int some = 0;
    for (size_t i = 0; pm->corner_uv && !m->corner_uv && i < nc && !some; i++)
        some = fix_uv(pm->corner_uv[i], uvbase) != MESH_NO_UV;
    if (some) {
        m->corner_uv = malloc((b->ccap ? b->ccap : 1) * sizeof *m->corner_uv);
        if (!m->corner_uv)
            return -1;
        for (size_t i = 0; i < cbase; i++)
            m->corner_uv[i] = MESH_NO_UV;
    }
    for (size_t i = 0; m->corner_uv && i < nc; i++) {
        uint32_t t = pm->corner_uv ? pm->corner_uv[i] : MESH_NO_UV;
        m->corner_uv[cbase + i] = fix_uv(t, uvbase);
    }
    b->ncorner += nc;
    for (uint32_t i = 0; i < pm->nfaces; i++) {
        int32_t u = mesh_face_mat(pm, i);
        int32_t mat = u == OBJ_INHERIT ? ps->cur_use : u >= 0 ? usemap[u] : -1;
        m->face_start[m->nfaces + i] = pm->face_start[i] + (uint32_t)cbase;
        if (mat != -1 && !m->face_mat && !mb_face_mats(b))
            return -1;
        if (m->face_mat)
            m->face_mat[m->nfaces + i] = mat;
    }
    m->nfaces += pm->nfaces;
    m->info.triangles += pm->info.triangles;
    return 0;
}

/* Points, polylines and objects (few: through the builder). */
static int merge_rest(Parser *ps, const Piece *p, uint32_t vbase, uint32_t fbase)
{
    MeshBuild *b = &ps->b;
    Mesh *m = ps->m;
    const Mesh *pm = &p->m;
    uint32_t pbase = m->npoints, lbase = m->nlines;
    for (uint32_t i = 0; i < pm->npoints; i++)
        if (mb_point(b, fix(pm->point[i], vbase)))
            return -1;
    for (uint32_t l = 0; l < pm->nlines; l++) {
        size_t first = b->nlcorner, c1 = l + 1 < pm->nlines ? pm->line_start[l + 1] : p->ps.b.nlcorner;
        for (size_t c = pm->line_start[l]; c < c1; c++)
            if (mb_line_corner(b, fix(pm->line_corner[c], vbase)))
                return -1;
        if (mb_line_end(b, first))
            return -1;
    }
    /* the piece's first object goes on with the current one, unless an
     * `o` before its first element named it */
    for (uint32_t i = p->ps.renamed0 ? 0 : 1; i < pm->nobjs; i++) {
        const MeshObject *o = &pm->objs[i];
        if (mb_object_at(b, o->name, strlen(o->name), fbase + o->face_first, pbase + o->point_first,
                         lbase + o->line_first))
            return -1;
    }
    return 0;
}

/* The counters and names of info and the parser. */
static void merge_counts(Parser *ps, const Piece *p)
{
    MeshInfo *in = &ps->m->info;
    const MeshInfo *pi = &p->m.info;
    const Parser *pp = &p->ps;
    in->texcoords += pi->texcoords;
    in->normals += pi->normals;
    in->groups += pi->groups;
    if (!in->unknown && pi->unknown)
        memcpy(in->first_unknown, pi->first_unknown, sizeof in->first_unknown);
    in->unknown += pi->unknown;
    if (!ps->undrawn && pp->undrawn)
        ps->first_undrawn = pp->first_undrawn;
    ps->undrawn += pp->undrawn;
    ps->saw_elements |= pp->saw_elements;
}

/* Merge piece p: 0, 1 when it cannot be (the serial parser reads on
 * from its start), -1 out of memory (the load fails). */
static int merge_piece(Run *r, Piece *p)
{
    Parser *ps = r->ps;
    const Parser *pp = &p->ps;
    if (merge_room(ps, p)) {
        MeshErr *e = ps->e;
        if (e->buf && e->len)
            e->buf[0] = '\0';       /* not the load's message: the serial parse may pass */
        return 1;
    }
    int32_t *usemap = malloc((pp->nuse ? pp->nuse : 1) * sizeof *usemap);
    if (!usemap)
        return me_oom(ps->e);
    for (uint32_t i = 0; i < pp->nuse; i++)
        if ((usemap[i] = obj_use_index(ps, pp->uses[i].name, pp->uses[i].line + r->lines)) < 0) {
            free(usemap);
            return me_oom(ps->e);
        }
    uint32_t vbase = ps->m->nverts, uvbase = ps->m->nuv, fbase = ps->m->nfaces;
    /* (the faces take the material current before the piece) */
    int rc = merge_vertices(ps, p) || merge_faces(ps, p, usemap, vbase, uvbase) ? me_oom(ps->e)
                                                                                : merge_rest(ps, p, vbase, fbase);
    ps->m->nuv += p->m.nuv;
    if (pp->cur_use != OBJ_INHERIT)
        ps->cur_use = pp->cur_use >= 0 ? usemap[pp->cur_use] : -1;
    free(usemap);
    if (rc)
        return -1;
    merge_counts(ps, p);
    r->lines += p->lines;
    return 0;
}

/* Merge what is done, in order (whoever finishes a piece does). */
static void merge_ready(Run *r)
{
    pthread_mutex_lock(&r->mu);
    while (r->merged < r->n && r->merged < r->stop && r->pc[r->merged].state != PC_TODO) {
        Piece *p = &r->pc[r->merged];
        int rc = p->state == PC_DONE ? (r->merged ? merge_piece(r, p) : 0) : 1;
        piece_free(p);
        if (rc) {
            __atomic_store_n(&r->stop, r->merged, __ATOMIC_RELAXED);
            r->fatal |= rc < 0;
            break;
        }
        MeshFile *f = r->c->file;
        if (f && f->progress)
            __atomic_store_n(f->progress, (uint64_t)p->to, __ATOMIC_RELAXED);
        r->merged++;
        /* the file so far, in order, for a picture while loading */
        if (r->c->err.prefix)
            mesh_prefix_publish(r->c->err.prefix, r->ps->m, r->ps->b.ncorner);
    }
    pthread_mutex_unlock(&r->mu);
}

static void piece_task(void *arg, int k, int worker)
{
    (void)worker;
    Run *r = arg;
    Piece *p = &r->pc[k];
    int state = PC_FAILED;
    if (k < __atomic_load_n(&r->stop, __ATOMIC_RELAXED) && k < __atomic_load_n(&r->failed, __ATOMIC_RELAXED)) {
        if (k == 0) {
            /* the serial parser itself, in place */
            LineReader lr;
            lr_init(&lr, r->text + p->from, p->to - p->from, r->c->file);
            r->first_rc = obj_lines(r->ps, &lr, r->text + r->len);
            r->lines = lr.line;
            r->fatal = r->first_rc < 0;
            state = r->first_rc == 0 ? PC_DONE : PC_FAILED;
        } else {
            state = piece_parse(r, p) == 0 ? PC_DONE : PC_FAILED;
        }
    }
    pthread_mutex_lock(&r->mu);
    p->state = state;
    if (state == PC_FAILED && k < r->failed)
        __atomic_store_n(&r->failed, k, __ATOMIC_RELAXED);
    pthread_mutex_unlock(&r->mu);
    merge_ready(r);
}

/* ==== The parse ==== */

static int threads_for(const MeshErr *e)
{
    long n = e->threads > 0 ? e->threads : sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 64 ? 64 : (int)n;
}

int obj_parse_parallel(Parser *ps, MeshCtx *c, const char *text, size_t from, size_t len)
{
    Run r = { .ps = ps, .c = c, .text = text, .len = len };
    uint64_t piece = c->err.piece_bytes ? c->err.piece_bytes : PIECE_BYTES;
    int threads = threads_for(&c->err);
    r.n = 1;
    if (threads > 1 && len - from >= 2 * piece)
        r.pc = cut_pieces(&r, from, piece, &r.n);
    if (r.n <= 1) {
        free(r.pc);
        LineReader lr;
        lr_init(&lr, text + from, len - from, c->file);
        return obj_lines(ps, &lr, text + len);
    }
    r.stop = r.n;
    r.failed = r.n;
    pthread_mutex_init(&r.mu, NULL);
    Pool *pool = pool_create(threads - 1);
    pool_run(pool, r.n, piece_task, &r);
    pool_free(pool);
    pthread_mutex_destroy(&r.mu);
    int rc = r.fatal ? -1 : r.first_rc;
    size_t resume = r.stop < r.n ? r.pc[r.stop].from : len;
    for (int k = 0; k < r.n; k++)
        piece_free(&r.pc[k]);
    free(r.pc);
    if (rc || resume >= len)
        return rc;
    /* a piece that could not be settled alone: read on from its start */
    LineReader lr;
    lr_init(&lr, text + resume, len - resume, c->file);
    lr.line = r.lines;
    return obj_lines(ps, &lr, text + len);
}
