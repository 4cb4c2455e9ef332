/* reader.c: input, errors and number parsing for every loader (see
 * reader.h). Numbers go through a hand-written parser because strtod
 * per coordinate would dominate the load time of a large mesh. */
#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "reader.h"
#include "safetext.h"

/* ==== Errors ==== */

/* The message after its prefix ("name: ", "name:12: ", ...), written
 * into e->msg (kept for me_skip) and copied into the caller's buffer. */
static int vtail(MeshErr *e, int k, const char *fmt, va_list ap)
{
    if (k >= 0 && (size_t)k < sizeof e->msg)
        vsnprintf(e->msg + k, sizeof e->msg - (size_t)k, fmt, ap);
    if (e->buf && e->len)
        snprintf(e->buf, e->len, "%s", e->msg);
    return -1;
}

int me_fail(MeshErr *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vtail(e, snprintf(e->msg, sizeof e->msg, "%s: ", e->name), fmt, ap);
    va_end(ap);
    return -1;
}

int me_fail_line(MeshErr *e, uint64_t line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vtail(e, snprintf(e->msg, sizeof e->msg, "%s:%llu: ", e->name, (unsigned long long)line), fmt, ap);
    va_end(ap);
    return -1;
}

int me_fail_at(MeshErr *e, uint64_t byte, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vtail(e, snprintf(e->msg, sizeof e->msg, "%s: byte %llu: ", e->name, (unsigned long long)byte), fmt, ap);
    va_end(ap);
    return -1;
}

int me_fail_raw(MeshErr *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vtail(e, 0, fmt, ap);
    va_end(ap);
    return -1;
}

int me_oom(MeshErr *e)
{
    return me_fail(e, "out of memory");
}

int me_skip(MeshErr *e, uint64_t at)
{
    if (e->strict)
        return -1;
    if (at == 0)
        at = UINT64_MAX;
    if (e->skipped == 0 || at < e->first_at) {
        memcpy(e->first, e->msg, sizeof e->first);
        e->first[sizeof e->first - 1] = '\0';
        e->first_at = at;
    }
    if (e->skipped < UINT32_MAX)
        e->skipped++;
    if (e->buf && e->len)
        e->buf[0] = '\0';
    return 0;
}

void me_warn(MeshErr *e, const char *name, uint64_t line, const char *fmt, ...)
{
    char msg[512], full[800];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (!name)
        name = e->name;
    if (line)
        snprintf(full, sizeof full, "%s:%llu: %s", name, (unsigned long long)line, msg);
    else
        snprintf(full, sizeof full, "%s: %s", name, msg);
    if (!e->warned++) {
        size_t n = strlen(full) < sizeof e->warning - 1 ? strlen(full) : sizeof e->warning - 1;
        memcpy(e->warning, full, n);
        e->warning[n] = '\0';
    }
    if (!e->quiet)
        safetext_line(stderr, "zview: warning: %s", full);
}

/* ==== Input ==== */

static const char *kind_of(mode_t m)
{
    return S_ISFIFO(m) ? "a FIFO" : S_ISCHR(m) ? "a character device"
         : S_ISBLK(m) ? "a block device" : S_ISSOCK(m) ? "a socket" : "not a file";
}

/* Read into the heap copy until it holds `want` bytes or the stream
 * ends. Returns 0, or -1 with msg. */
static int read_more(MeshFile *f, size_t want, int stop_at_nul, char *msg, size_t msglen)
{
    while (f->len < want) {
        if (f->len == f->cap) {
            size_t nc = f->cap ? f->cap * 2 : (size_t)1 << 16;
            char *nb = realloc(f->heap, nc);
            if (!nb) {
                snprintf(msg, msglen, "out of memory");
                return -1;
            }
            f->heap = nb;
            f->cap = nc;
        }
        size_t room = f->cap - f->len;
        if (room > want - f->len)
            room = want - f->len;
        if (f->cancel && __atomic_load_n(f->cancel, __ATOMIC_RELAXED)) {
            f->cancelled = 1;
            snprintf(msg, msglen, "cancelled");
            return -1;
        }
        ssize_t r = f->gz ? mf_gz_read(f, f->heap + f->len, room, msg, msglen)
                          : read(f->fd, f->heap + f->len, room);
        if (r < 0 && f->gz)
            return -1;
        if (r < 0) {
            if (errno == EINTR)
                continue;
            snprintf(msg, msglen, "cannot read: %s", strerror(errno));
            return -1;
        }
        if (r == 0)
            break;
        /* A NUL already makes a text file invalid: stop there, so that an
         * endless binary stream ends in an error, not exhausted memory. */
        const char *nul = stop_at_nul ? memchr(f->heap + f->len, '\0', (size_t)r) : NULL;
        f->len += (size_t)r;
        if (nul) {
            f->len = (size_t)(nul - f->heap) + 1;
            break;
        }
    }
    f->data = f->heap ? f->heap : "";
    f->size = f->len;
    return 0;
}

int mf_open(MeshFile *f, const char *path, int flags, char *msg, size_t msglen)
{
    memset(f, 0, sizeof *f);
    f->fd = -1;
    f->data = f->head = "";
    int fd;
    if (strcmp(path, "-") == 0) {
        fd = dup(STDIN_FILENO);   /* closing ours leaves standard input alone */
    } else {
        /* O_NONBLOCK: opening a FIFO for reading would wait for a writer;
         * with it the type check below refuses it at once */
        fd = open(path, O_RDONLY | O_CLOEXEC | (flags & MF_REGULAR_ONLY ? O_NONBLOCK : 0));
    }
    if (fd < 0) {
        snprintf(msg, msglen, "cannot open: %s", strerror(errno));
        return -1;
    }
    return mf_open_fd(f, fd, flags, msg, msglen);
}

int mf_open_fd(MeshFile *f, int fd, int flags, char *msg, size_t msglen)
{
    memset(f, 0, sizeof *f);
    f->data = f->head = "";
    f->fd = fd;
    struct stat st;
    if (fstat(fd, &st) < 0) {
        snprintf(msg, msglen, "cannot open: %s", strerror(errno));
        mf_close(f);
        return -1;
    }
    f->dev = (uint64_t)st.st_dev;
    f->ino = (uint64_t)st.st_ino;
    f->mtime_ns = (int64_t)st.st_mtim.tv_sec * 1000000000 + st.st_mtim.tv_nsec;
    if (S_ISDIR(st.st_mode)) {
        snprintf(msg, msglen, "is a directory");
        mf_close(f);
        return -1;
    }
    if (!S_ISREG(st.st_mode) && (flags & MF_REGULAR_ONLY)) {
        snprintf(msg, msglen, "not a regular file (%s)", kind_of(st.st_mode));
        mf_close(f);
        return -1;
    }
    /* Standard input redirected from a file part-way through it (a
     * script read some of it first) is read from where it stands, as a
     * stream: a mapping would start at the file's beginning. */
    if (S_ISREG(st.st_mode) && lseek(fd, 0, SEEK_CUR) == 0) {
        f->regular = 1;
        f->size = (uint64_t)st.st_size;
        size_t want = f->size < MESH_HEAD ? (size_t)f->size : MESH_HEAD;
        size_t got = 0;
        while (got < want) {
            ssize_t r = pread(fd, f->headbuf + got, want - got, (off_t)got);
            if (r < 0 && errno == EINTR)
                continue;
            if (r < 0) {
                snprintf(msg, msglen, "cannot read: %s", strerror(errno));
                mf_close(f);
                return -1;
            }
            if (r == 0)
                break;
            got += (size_t)r;
        }
        f->head = f->headbuf;
        f->nhead = got;
        if (!mf_is_gzip(f->head, f->nhead))
            return 0;
        /* compressed: read as a stream of the decompressed bytes, from
         * the start (pread left the offset there) */
        f->regular = 0;
        f->size = 0;
        if (mf_gz_start(f, "", 0, msg, msglen) || read_more(f, MESH_HEAD, 0, msg, msglen)) {
            mf_close(f);
            return -1;
        }
        f->head = f->data;
        f->nhead = f->len;
        return 0;
    }
    /* A stream: its first bytes start the heap copy (nothing can be read
     * twice). A NUL in the head is kept: binary formats need it. */
    if (read_more(f, MESH_HEAD, 0, msg, msglen)) {
        mf_close(f);
        return -1;
    }
    if (mf_is_gzip(f->data, f->len)) {
        /* what was read is compressed: it seeds zlib, and the copy
         * starts again with the bytes that come out */
        size_t n = f->len;
        f->len = 0;
        if (mf_gz_start(f, f->heap, n, msg, msglen) || read_more(f, MESH_HEAD, 0, msg, msglen)) {
            mf_close(f);
            return -1;
        }
    }
    f->head = f->data;
    f->nhead = f->len;
    return 0;
}

/* Huge pages, the unit the window is copied in by. */
#define MF_HUGE ((size_t)2 << 20)

/* Map a regular file for mf_window: read-only, at an address aligned to
 * MF_HUGE, so that the window's copies (anonymous memory laid over the
 * mapping) can be huge pages: a 4 KB page each costs a fault, which in
 * a VM costs more than copying the page. */
static int map_file(MeshFile *f)
{
    size_t len = (size_t)f->size;
    char *area = mmap(NULL, len + MF_HUGE, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (area == MAP_FAILED)
        return -1;
    char *at = (char *)(((uintptr_t)area + MF_HUGE - 1) & ~(uintptr_t)(MF_HUGE - 1));
    void *map = mmap(at, len, PROT_READ, MAP_PRIVATE | MAP_FIXED, f->fd, 0);
    if (map == MAP_FAILED) {
        munmap(area, len + MF_HUGE);
        return -1;
    }
    /* give back the reserve around it */
    size_t page = (size_t)sysconf(_SC_PAGESIZE), tail = (len + page - 1) & ~(page - 1);
    if (at > area)
        munmap(area, (size_t)(at - area));
    if (area + len + MF_HUGE > at + tail)
        munmap(at + tail, (size_t)(area + len + MF_HUGE - (at + tail)));
    f->map = map;
    f->data = map;
    f->len = len;
    mf_window(f, 0, 0);
    return 0;
}

int mf_load(MeshFile *f, const MfLimits *lim, char *msg, size_t msglen)
{
    uint64_t max = lim && lim->max ? lim->max : MESH_MAX_BYTES;
    if (max > MESH_MAX_BYTES)
        max = MESH_MAX_BYTES;
    if (f->regular && f->fd >= 0 && !f->map) {
        if (f->size > MESH_MAX_BYTES) {
            snprintf(msg, msglen, "file too large (%llu bytes; at most %llu)",
                     (unsigned long long)f->size, (unsigned long long)MESH_MAX_BYTES);
            return -1;
        }
        if (f->size == 0) {
            close(f->fd);
            f->fd = -1;
            return 0;
        }
        /* No MAP_POPULATE: the window pages the file in as the parser
         * goes, so a file rejected early is never read whole. */
        if (map_file(f) == 0)
            return 0;
        /* Some file systems cannot map: read it like a stream. */
        f->regular = 0;
    }
    if (f->fd < 0 || f->map)
        return 0;
    /* a stream holds its bytes in memory: no more than memory has */
    uint64_t mem = lim ? lim->mem : 0;
    uint64_t cap = mem && mem < max ? mem : max;
    int nul = 0;
    if (lim && lim->stop_at_nul && memchr(f->data, '\0', f->len)) {
        f->len = (size_t)((const char *)memchr(f->data, '\0', f->len) - f->data) + 1;
        nul = 1;
    } else if (f->len < cap) {
        if (read_more(f, (size_t)cap, lim && lim->stop_at_nul, msg, msglen))
            return -1;
        nul = lim && lim->stop_at_nul && f->len && f->data[f->len - 1] == '\0';
    }
    /* full: an error when the stream goes on past a limit of ours (a
     * format's own bound, lim->max, lets the loader see the byte more) */
    char c;
    if (!nul && f->len >= cap && (cap < max || max == MESH_MAX_BYTES) &&
        (f->gz ? mf_gz_read(f, &c, 1, msg, msglen) : read(f->fd, &c, 1)) == 1) {
        char have[32];
        sysmem_format(cap, have, sizeof have);
        if (cap < max)
            snprintf(msg, msglen, "input too large for the memory available (more than %s)", have);
        else
            snprintf(msg, msglen, "input too large (more than %llu bytes)", (unsigned long long)MESH_MAX_BYTES);
        return -1;
    }
    close(f->fd);
    f->fd = -1;
    f->head = f->data;
    return 0;
}

/* The file ended before `from` could be copied in: what is left of the
 * mapping becomes zeros of the process's own (a parser reads those and
 * ends; the load then fails as changed), never the file's missing pages. */
static void lost_file(MeshFile *f, size_t from)
{
    size_t page = (size_t)sysconf(_SC_PAGESIZE);
    size_t start = from & ~(page - 1);
    size_t stop = (f->len + page - 1) & ~(page - 1);
    f->changed = 1;
    if (f->mute)
        *f->mute = 1;
    if (stop > start)
        mmap((char *)f->map + start, stop - start, PROT_READ | PROT_WRITE,
             MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED | MAP_NORESERVE, -1, 0);
    f->populated = f->len;
}

/* Copy [start, stop) of the file into memory of the process's own,
 * laid over the mapping there (huge pages where the kernel has them).
 * A file that ends early fails (-1; the rest of the range is zeros)
 * where touching the file's pages would have raised SIGBUS. */
static int copy_in(MeshFile *f, size_t start, size_t stop)
{
    char *base = (char *)f->map;
    if (mmap(base + start, stop - start, PROT_READ | PROT_WRITE,
             MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED | MAP_NORESERVE, -1, 0) == MAP_FAILED)
        return -1;
#ifdef MADV_HUGEPAGE
    madvise(base + start, stop - start, MADV_HUGEPAGE);
#endif
    size_t want = (stop < f->len ? stop : f->len) - start;
    for (size_t at = 0; at < want;) {
        ssize_t r = pread(f->fd, base + start + at, want - at, (off_t)(start + at));
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return -1;
        at += (size_t)r;
    }
    return 0;
}

void mf_window(MeshFile *f, size_t keep, size_t upto)
{
    if (!f->map)
        return;
    size_t page = (size_t)sysconf(_SC_PAGESIZE);
    size_t want = f->len - upto < MF_AHEAD ? f->len : upto + MF_AHEAD;
    if (f->cancel && !f->changed && __atomic_load_n(f->cancel, __ATOMIC_RELAXED)) {
        /* as if the file ended here: the parser reads zeros and stops */
        f->cancelled = 1;
        lost_file(f, f->populated);
    }
    if (want > f->populated && !f->changed) {
        /* in huge pages: the window's start and end stay aligned */
        size_t start = f->populated;
        size_t stop = (want + MF_HUGE - 1) & ~(MF_HUGE - 1);
        if (stop > ((f->len + page - 1) & ~(page - 1)))
            stop = (f->len + page - 1) & ~(page - 1);
        if (copy_in(f, start, stop))
            lost_file(f, start);
        else
            f->populated = stop < f->len ? stop : f->len;
    }
    if (keep > MF_KEEP_BEHIND) {
        size_t rel = (keep - MF_KEEP_BEHIND) & ~(page - 1);
        if (rel > f->released && !f->changed) {
            /* the copies go; the pages would come back from the file if
             * ever touched again, which no parser does */
            madvise((char *)f->map + f->released, rel - f->released, MADV_DONTNEED);
            f->released = rel;
        }
    }
    f->mark = keep + MF_STEP;
    if (f->progress)
        __atomic_store_n(f->progress, (uint64_t)keep, __ATOMIC_RELAXED);
    if (f->on_window)
        f->on_window(f->on_window_arg, keep);
}

int mf_changed(MeshFile *f)
{
    struct stat st;
    if (!f->map || f->fd < 0)
        return f->changed;
    if (fstat(f->fd, &st) == 0 &&
        ((uint64_t)st.st_size != f->size ||
         (int64_t)st.st_mtim.tv_sec * 1000000000 + st.st_mtim.tv_nsec != f->mtime_ns))
        f->changed = 1;
    return f->changed;
}

void mf_close(MeshFile *f)
{
    if (f->map)
        munmap(f->map, f->len);
    mf_gz_end(f);
    free(f->heap);
    if (f->fd >= 0)
        close(f->fd);
    memset(f, 0, sizeof *f);
    f->fd = -1;
    f->data = f->head = "";
}


void mesh_count_str(uint64_t v, char *buf, size_t len)
{
    char d[32];
    int nd = snprintf(d, sizeof d, "%llu", (unsigned long long)v);
    size_t k = 0;
    for (int i = 0; i < nd && k + 1 < len; i++) {
        if (i && (nd - i) % 3 == 0 && k + 2 < len)
            buf[k++] = ',';
        buf[k++] = d[i];
    }
    buf[k] = '\0';
}

/* ==== Numbers ==== */

static const double pow10_tab[23] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

int mesh_word_is(const char *p, const char *end, const char *w)
{
    for (; *w; w++, p++)
        if (p >= end || (*p | 0x20) != *w)
            return 0;
    return p == end || mesh_is_ws(*p);
}

int mesh_parse_float(const char **pp, const char *end, float *out)
{
    const char *p = *pp;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) {
        neg = *p == '-';
        p++;
    }
    /* Up to 19 significant digits fit a uint64 exactly; later digits
     * only move the decimal exponent. Leading zeros are not significant
     * and do not use up the budget. */
    uint64_t mant = 0;
    int nd = 0, exp10 = 0, any = 0;
    while (p < end && *p == '0') {
        p++;
        any = 1;
    }
    while (p < end && mesh_is_digit(*p)) {
        if (nd < 19) {
            mant = mant * 10 + (uint64_t)(*p - '0');
            nd++;
        } else {
            exp10++;
        }
        p++;
        any = 1;
    }
    if (p < end && *p == '.') {
        p++;
        if (nd == 0) {
            while (p < end && *p == '0') {
                p++;
                exp10--;
                any = 1;
            }
        }
        while (p < end && mesh_is_digit(*p)) {
            if (nd < 19) {
                mant = mant * 10 + (uint64_t)(*p - '0');
                nd++;
                exp10--;
            }
            p++;
            any = 1;
        }
    }
    if (!any) {
        /* Recognised only so that they can be refused by name. */
        if (mesh_word_is(p, end, "nan") || mesh_word_is(p, end, "infinity") ||
            mesh_word_is(p, end, "inf"))
            return MESH_NUM_NONFINITE;
        return MESH_NUM_BAD;
    }
    if (p < end && (*p | 0x20) == 'e') {
        p++;
        int eneg = 0;
        if (p < end && (*p == '-' || *p == '+')) {
            eneg = *p == '-';
            p++;
        }
        if (p >= end || !mesh_is_digit(*p))
            return MESH_NUM_BAD;
        int ev = 0;
        while (p < end && mesh_is_digit(*p)) {
            if (ev < 100000)          /* far past any float; no overflow */
                ev = ev * 10 + (*p - '0');
            p++;
        }
        exp10 += eneg ? -ev : ev;
    }
    if (p < end && !mesh_is_ws(*p))
        return MESH_NUM_BAD;

    double v = (double)mant;
    if (mant == 0 || exp10 < -400) {
        v = 0.0;
    } else if (exp10 > 400) {
        return MESH_NUM_RANGE;
    } else if (exp10 >= 0) {
        /* Exact when exp10 <= 22 and mant < 2^53; otherwise a few
         * roundings in double, still far below a float's ulp. */
        while (exp10 > 22) {
            v *= 1e22;
            exp10 -= 22;
        }
        v *= pow10_tab[exp10];
    } else {
        while (exp10 < -22) {
            v /= 1e22;
            exp10 += 22;
        }
        v /= pow10_tab[-exp10];
    }
    /* Converting a double beyond FLT_MAX is undefined in C, so the
     * rounding boundary (FLT_MAX + half an ulp) is tested in double. */
    float f;
    if (v >= 3.4028235677973366e38)
        return MESH_NUM_RANGE;
    f = v > 3.4028234663852886e38 ? 3.4028234663852886e38f : (float)v;
    *out = neg ? -f : f;
    *pp = p;
    return MESH_NUM_OK;
}

int mesh_parse_int(const char **pp, const char *end, int64_t *out)
{
    const char *p = *pp;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) {
        neg = *p == '-';
        p++;
    }
    const char *d0 = p;
    uint64_t v = 0;
    int over = 0;
    while (p < end && mesh_is_digit(*p)) {
        unsigned d = (unsigned)(*p - '0');
        if (v > (UINT64_C(0x7fffffffffffffff) - d) / 10)
            over = 1;
        else
            v = v * 10 + d;
        p++;
    }
    if (p == d0 || (p < end && !mesh_is_ws(*p)))
        return MESH_NUM_BAD;
    if (over)
        return MESH_NUM_RANGE;
    *out = neg ? -(int64_t)v : (int64_t)v;
    *pp = p;
    return MESH_NUM_OK;
}

int mesh_has_binary(const char *p, const char *end)
{
    for (; p < end; p++) {
        unsigned char c = (unsigned char)*p;
        if ((c < 0x20 && c != '\t' && c != '\r' && c != '\n') || c == 0x7f)
            return 1;
    }
    return 0;
}

int mesh_tok_len(const char *p, const char *end)
{
    const char *q = p;
    while (q < end && !mesh_is_ws(*q) && q - p < 40)
        q++;
    return (int)(q - p);
}

/* ==== Lines ==== */

const char *lr_long_line(LineReader *lr, const char *ls, const char *from)
{
    const char *end = lr->end;
    for (;;) {
        const char *lim = mf_limit(lr->file, end);
        const char *q = lr_stop(from, lim);
        /* done when all is in, or at a stop whose next byte is in or
         * does not matter (only a CR looks at the next) */
        if (lim >= end || q + 1 < lim || (q < lim && *q != '\r'))
            return q;
        /* the window ends first: move it on, keeping the line */
        size_t more = (size_t)(end - lim) < 2 * MF_STEP ? (size_t)(end - lim) : 2 * MF_STEP;
        mf_need(lr->file, ls, lim + more);
        if (mf_limit(lr->file, end) <= lim)
            return q;       /* cannot happen: the window always moves */
        from = q;           /* a CR on the last byte is looked at again */
    }
}

void lr_init(LineReader *lr, const char *data, size_t len, MeshFile *file)
{
    lr->p = data;
    lr->end = data + len;
    lr->line = 0;
    lr->file = file;
}
