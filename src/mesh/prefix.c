/* prefix.c: a load's prefix in a shared mapping (meshprefix.h). The
 * mapping holds three arrays sized for the densest OBJ the file can be
 * (a vertex or a face per 8 bytes, a corner per 2), and a header whose
 * counts say how much of each is written. The writer copies each new
 * run once, then stores the counts (faces last, with release order);
 * the reader loads them (faces first, acquire) and so never sees a face
 * whose corners or vertices are not written yet. Published runs never
 * change: a face's start is where the face before it ends, the same
 * number whichever publication wrote it. */

#define _GNU_SOURCE            /* memfd_create, its seals */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "meshprefix.h"
#include "mesh_internal.h"

#define HOLD_POLL_NS 20000000L      /* a held writer looks for its file this often */

typedef struct {
    uint64_t nverts, nfaces, ncorner;   /* published (atomic) */
    int      full;                      /* the arrays could not take more: publishing stopped */
    int      stop;                      /* the reader wants no more (atomic) but what a hold shows */
    uint64_t hold_faces;                /* 0: none */
    char     hold_path[512];
} Shared;

struct MeshPrefix {
    Shared   *sh;       /* the mapping's start */
    size_t    maplen;
    int       fd;       /* the memfd mapped (-1: a view attached in another process) */
    uint64_t  bytes;    /* the file's size the layout is for */
    uint64_t  vcap, fcap, ccap;         /* kept here, out of the writer's reach */
    float    *pos;
    uint32_t *fstart;   /* fcap + 1 */
    uint32_t *corner;
    int       released;         /* the reader's side: stopped, its pages given back */
};

static uint64_t cap32(uint64_t n)
{
    return n < UINT32_MAX ? n : UINT32_MAX;
}

/* The layout for a file of `bytes` bytes over the mapping at m. */
static void lay_out(MeshPrefix *p, uint64_t bytes)
{
    p->bytes = bytes;
    p->vcap = cap32(bytes / 8 + 1);
    p->fcap = cap32(bytes / 8 + 1);
    p->ccap = cap32(bytes / 2 + 1);
    size_t head = (sizeof(Shared) + 63) & ~(size_t)63;
    p->maplen = head + p->vcap * 12 + (p->fcap + 1) * 4 + p->ccap * 4;
}

static int map_at(MeshPrefix *p, int fd)
{
    void *m = mmap(NULL, p->maplen, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_NORESERVE, fd, 0);
    if (m == MAP_FAILED)
        return -1;
    size_t head = (sizeof(Shared) + 63) & ~(size_t)63;
    p->sh = m;
    p->pos = (float *)((char *)m + head);
    p->fstart = (uint32_t *)(p->pos + 3 * p->vcap);
    p->corner = p->fstart + p->fcap + 1;
    return 0;
}

MeshPrefix *mesh_prefix_new(uint64_t bytes)
{
    MeshPrefix *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    lay_out(p, bytes);
    /* a memfd, not an anonymous mapping: a child forked elsewhere (the
     * sandbox's fork server) maps it too. Its size is sealed: the writer,
     * not trusted, cannot shrink it under the reader (SIGBUS). Pages are
     * only made as they are written. */
    p->fd = memfd_create("zview-prefix", MFD_CLOEXEC | MFD_ALLOW_SEALING);
    if (p->fd < 0 || ftruncate(p->fd, (off_t)p->maplen) != 0 ||
        fcntl(p->fd, F_ADD_SEALS, F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_SEAL) != 0 || map_at(p, p->fd) != 0) {
        if (p->fd >= 0)
            close(p->fd);
        free(p);
        return NULL;
    }
    return p;
}

int mesh_prefix_fd(const MeshPrefix *p, uint64_t *bytes_out)
{
    *bytes_out = p->bytes;
    return p->fd;
}

MeshPrefix *mesh_prefix_attach(int fd, uint64_t bytes)
{
    MeshPrefix *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    lay_out(p, bytes);
    struct stat st;
    /* the layout must fit in what was made for it */
    if (fstat(fd, &st) != 0 || (uint64_t)st.st_size < p->maplen || map_at(p, fd) != 0) {
        free(p);
        return NULL;
    }
    p->fd = -1;
    return p;
}

void mesh_prefix_free(MeshPrefix *p)
{
    if (!p)
        return;
    munmap(p->sh, p->maplen);
    if (p->fd >= 0)
        close(p->fd);
    free(p);
}

void mesh_prefix_hold(MeshPrefix *p, uint64_t faces, const char *path)
{
    p->sh->hold_faces = faces;
    snprintf(p->sh->hold_path, sizeof p->sh->hold_path, "%s", path);
}

void mesh_prefix_stop(MeshPrefix *p)
{
    __atomic_store_n(&p->sh->stop, 1, __ATOMIC_RELAXED);
    if (p->sh->hold_faces || p->released)
        return;         /* a hold's faces are still to be read */
    /* The reader takes no more: the copy is given back now, not when the
     * load ends (on the 31M model it held up to 700 MB just when the
     * whole mesh arrives, the viewer's most resident moment). MADV_REMOVE
     * frees shared pages for the writer too; a copy it is still making
     * lands in fresh pages no one reads, and it publishes no more. */
    uintptr_t page = 4096, a = ((uintptr_t)p->pos + page - 1) & ~(page - 1);
    uintptr_t e = ((uintptr_t)p->sh + p->maplen) & ~(page - 1);
    if (e > a)
        madvise((void *)a, e - a, MADV_REMOVE);
    p->released = 1;
}

const void *mesh_prefix_data(const MeshPrefix *p, size_t *len)
{
    *len = p->maplen - (size_t)((const char *)p->pos - (const char *)p->sh);
    return p->pos;
}

void mesh_prefix_counts(const MeshPrefix *p, uint64_t *verts, uint64_t *faces)
{
    *faces = __atomic_load_n(&p->sh->nfaces, __ATOMIC_ACQUIRE);
    *verts = __atomic_load_n(&p->sh->nverts, __ATOMIC_ACQUIRE);
}

/* ==== The writer ==== */

static void hold(const Shared *sh)
{
    struct timespec ts = { 0, HOLD_POLL_NS };
    while (access(sh->hold_path, F_OK) != 0)
        nanosleep(&ts, NULL);
}

void mesh_prefix_publish(MeshPrefix *p, const Mesh *m, size_t ncorner)
{
    Shared *sh = p->sh;
    if (sh->full)
        return;
    uint64_t pv = sh->nverts, pf = sh->nfaces, pc = sh->ncorner;
    uint64_t nv = m->nverts, nf = m->nfaces, nc = ncorner;
    int held = sh->hold_faces && nf >= sh->hold_faces;
    if (held && pf >= sh->hold_faces)
        return;                 /* held already, and let go: the rest comes whole */
    if (!held && __atomic_load_n(&sh->stop, __ATOMIC_RELAXED))
        return;
    if (held) {
        nf = sh->hold_faces;
        nc = nf < m->nfaces ? (m->face_start ? m->face_start[nf] : 3 * nf) : ncorner;
    }
    /* a picture while loading shows at most MESH_PREFIX_FACES_MAX faces:
     * past them the copy (16 bytes a face, shared, so counted in the
     * loader's memory too) would only add to the load's most resident
     * moment, for no more than a terminal shows */
    int capped = !held && nf > MESH_PREFIX_FACES_MAX;
    if (capped) {
        nf = MESH_PREFIX_FACES_MAX;
        nc = m->face_start ? m->face_start[nf] : 3 * nf;
    }
    if (nv > p->vcap || nf > p->fcap || nc > p->ccap || nv < pv || nf < pf || nc < pc) {
        sh->full = 1;
        return;
    }
    /* (memcpy may not be given NULL, even for nothing) */
    if (nv > pv)
        memcpy(p->pos + 3 * pv, m->pos + 3 * pv, (nv - pv) * 3 * sizeof(float));
    for (uint64_t f = pf; f < nf; f++)
        p->fstart[f] = m->face_start ? m->face_start[f] : (uint32_t)(3 * f);
    p->fstart[nf] = (uint32_t)nc;
    if (nc > pc)
        memcpy(p->corner + pc, m->corner + pc, (nc - pc) * sizeof(uint32_t));
    __atomic_store_n(&sh->nverts, nv, __ATOMIC_RELEASE);
    __atomic_store_n(&sh->ncorner, nc, __ATOMIC_RELEASE);
    __atomic_store_n(&sh->nfaces, nf, __ATOMIC_RELEASE);
    if (capped)
        sh->full = 1;           /* the rest comes whole */
    if (held)
        hold(sh);
}

/* ==== The reader ==== */

/* The faces [0, nf) over nv vertices and nc corners, each checked. */
static int take_faces(const MeshPrefix *p, MeshBuild *b, uint64_t nf, uint64_t nv, uint64_t nc)
{
    for (uint64_t f = 0; f < nf; f++) {
        uint64_t c0 = p->fstart[f], c1 = p->fstart[f + 1];     /* each read once */
        if (c1 < c0 + 3 || c1 > nc)
            break;              /* not what a loader writes: the rest is not trusted */
        size_t first = b->ncorner;
        int ok = 1;
        for (uint64_t c = c0; c < c1 && ok; c++) {
            uint32_t v = p->corner[c];
            ok = v < nv;        /* a vertex further on: the cut file skips the face */
            if (ok && mb_corner(b, v))
                return -1;
        }
        if (!ok)
            b->ncorner = first;
        else if (mb_face_end(b, first, -1))
            return -1;
    }
    return 0;
}

int mesh_prefix_take(const MeshPrefix *p, const char *path, Mesh *m)
{
    memset(m, 0, sizeof *m);
    if (p->released)
        return 1;       /* given back at the stop */
    uint64_t nf = __atomic_load_n(&p->sh->nfaces, __ATOMIC_ACQUIRE);
    uint64_t nc = __atomic_load_n(&p->sh->ncorner, __ATOMIC_ACQUIRE);
    uint64_t nv = __atomic_load_n(&p->sh->nverts, __ATOMIC_ACQUIRE);
    nf = nf < p->fcap ? nf : p->fcap;
    nc = nc < p->ccap ? nc : p->ccap;
    nv = nv < p->vcap ? nv : p->vcap;
    if (nv == 0)
        return 1;
    char msg[256];
    MeshErr e = { .name = path, .buf = msg, .len = sizeof msg, .quiet = 1 };
    MeshBuild b;
    if (mb_start(&b, m, &e, path))
        return -1;
    if (mb_reserve_ex(&b, nv, nf, nc, 0))
        goto fail;
    for (uint64_t v = 0; v < nv; v++) {
        float x = p->pos[3 * v], y = p->pos[3 * v + 1], z = p->pos[3 * v + 2];
        /* a loader stores finite numbers only */
        if (mb_vertex(&b, isfinite(x) ? x : 0, isfinite(y) ? y : 0, isfinite(z) ? z : 0))
            goto fail;
    }
    if (take_faces(p, &b, nf, nv, nc))
        goto fail;
    snprintf(m->info.format, sizeof m->info.format, "obj");
    if (mb_finish(&b, nf == 0)) {
        mb_abort(&b);
        return 1;               /* nothing to show (every face left out) */
    }
    return 0;
fail:
    mb_abort(&b);
    return -1;
}
