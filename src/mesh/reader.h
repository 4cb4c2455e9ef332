#ifndef ZV_MESH_READER_H
#define ZV_MESH_READER_H
/* reader: what every loader shares and nothing format-specific.
 *
 *   input    a file mapped once (a stream read once), its first bytes
 *            read before any of the rest is paged in, the rest paged in
 *            and dropped again in a window that follows the parser;
 *   errors   "path:line: msg" (text), "path: byte N: msg" (binary),
 *            "path: msg";
 *   text     line ends (LF, CRLF or old-Mac CR), decimal numbers;
 *   binary   unaligned little- and big-endian loads.
 *
 * Nothing here keeps file-static mutable state: all of it lives in
 * structs the caller owns, so loaders can run on several threads and a
 * fuzz harness can call them on a memory buffer. Not part of the public
 * API. */

#include "sysmem.h"
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "simd.h"

/* ==== Errors ==== */

typedef struct {
    const char *name;      /* the input as messages name it */
    char       *buf;       /* the message goes here */
    size_t      len;
    /* Statements a loader could not read (a face without vertices, an
     * index out of range, an unknown keyword): with strict, the load
     * fails with the first one's message; otherwise they are skipped and
     * counted here, and the rest of the file is shown. */
    int         strict;
    uint32_t    skipped;
    uint64_t    first_at;  /* line (text) or byte (binary) of the first, for ordering */
    char        first[256];/* its message, "path:line: msg" */
    char        msg[256];  /* the last message, whatever buf's size */
    /* Warnings: on stderr unless quiet; counted, the first kept. */
    int         quiet;
    uint32_t    warned;
    char        warning[256];
    /* The load's bounds (MeshLoadOpts): a count or an array past them is
     * refused with a message, like any bad input. 0: none / ask the
     * machine (sysmem_available). */
    uint64_t    max_polys;
    uint64_t    max_bytes;
    /* Textures (MeshLoadOpts): defer those with a longer side, or open
     * none at all. */
    int         tex_defer_side;
    int         no_textures;
    /* The model's file: what it names is opened beneath its folder only
     * (mesh_ref_open). NULL for standard input and memory: nothing. */
    const char *model;
    /* Threads a text loader may parse on (0: every core; 1: serially),
     * and the size of its pieces (0: its own; tests make them small). */
    int         threads;
    uint64_t    piece_bytes;
    /* NULL, or where the prefix parsed so far is published (meshprefix.h) */
    struct MeshPrefix *prefix;
    /* MeshLoadOpts.on_ref: told of each file mesh_ref_open lets through */
    void      (*on_ref)(void *arg, const char *path, int image);
    void       *on_ref_arg;
} MeshErr;

/* Each writes the message and returns -1, so `return me_fail(...)`. */
int me_fail(MeshErr *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int me_fail_line(MeshErr *e, uint64_t line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
int me_fail_at(MeshErr *e, uint64_t byte, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
int me_oom(MeshErr *e);
/* The whole message as given (it names the input itself). */
int me_fail_raw(MeshErr *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The statement whose message was just written (at line or byte `at`,
 * 0 = after the end) is skipped: returns 0 and counts it, keeping the
 * message when it is the earliest so far; under strict returns -1 and
 * leaves the message as the load's error. */
int me_skip(MeshErr *e, uint64_t at);
/* A warning: "name:line: msg" (line 0: "name: msg"; name NULL: e's),
 * counted and the first kept in e, and on stderr prefixed "zview:
 * warning: " unless e->quiet. */
void me_warn(MeshErr *e, const char *name, uint64_t line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* ==== Input ==== */

/* Larger inputs are refused: 32-bit corner offsets, and a stream that
 * never ends (/dev/zero) stops here instead of eating all memory. */
#define MESH_MAX_BYTES ((size_t)1 << 32)
/* What format detection looks at before the rest of a file is read. */
#define MESH_HEAD 4096

enum {
    MF_REGULAR_ONLY = 1,   /* refuse FIFOs, devices (material libraries) */
};

/* A file's bytes, mapped (regular files) or read into the heap (pipes,
 * devices, standard input). The data is NOT NUL-terminated.
 *
 * A mapped file is never read where the file itself backs the mapping:
 * a file truncated under a mapping raises SIGBUS on the next touch of a
 * page past its new end, and that would kill the process (the viewer
 * loads on a thread). So the window a parser reads is first copied into
 * the mapping's private pages (MADV_POPULATE_WRITE, or pread), a step
 * that fails with an error instead of a signal; a file found shorter
 * gets zeros for the rest, the parser ends on them, and the load fails
 * "changed while reading" (mf_changed, which also compares the size and
 * modification time at the end). */
typedef struct MeshFile {
    const char *data;      /* after mf_load: the whole input */
    size_t      len;
    const char *head;      /* after mf_open: the first nhead bytes */
    size_t      nhead;
    uint64_t    size;      /* a regular file's size; a stream's bytes read so far */
    int         regular;
    int         fd;        /* -1 once closed; a mapped file keeps it for mf_changed */
    uint64_t    dev, ino;  /* identity, to load a file once */
    int64_t     mtime_ns;  /* modification time at mf_open */
    int         changed;   /* the file was found shorter than at mf_open */
    int        *mute;      /* NULL, or set to 1 then: what the parser says of the
                              zeros it then reads is not to be shown (MeshErr.quiet) */
    char        headbuf[MESH_HEAD];
    void       *map;       /* mmap base, or NULL */
    char       *heap;      /* stream bytes, or NULL */
    size_t      cap;
    /* the paging window (mapped files): [released, populated) is what
     * was copied in and not yet dropped (populated: whole pages, at most
     * len); mf_progress moves it at `mark` */
    size_t      populated, released, mark;
    uint64_t   *progress;  /* NULL, or bytes parsed so far (atomic stores, see MeshProgress) */
    /* for tests: called each time the window has moved, with the byte
     * the parser reported (a test truncates the file there) */
    void      (*on_window)(void *arg, uint64_t pos);
    void       *on_window_arg;
    const int  *cancel;    /* NULL, or nonzero (read atomically) when the load is
                              no longer wanted: the rest reads as zeros */
    int         cancelled; /* cancel was seen */
    struct MfGzip *gz;     /* gzip data: the stream's bytes come out of zlib (gzip.c) */
} MeshFile;

/* Open `path` ("-" = standard input) and read its first bytes into head
 * (a regular file: pread, nothing mapped yet; a stream: the start of the
 * heap copy). On failure returns -1 with a message without the path
 * ("cannot open: ...", "is a directory", "not a regular file (a FIFO)").
 * An empty file succeeds with nhead 0. */
int  mf_open(MeshFile *f, const char *path, int flags, char *msg, size_t msglen);
/* The same on a descriptor already open (taken over: closed on failure
 * and by mf_close): a file mesh_ref_open let through. */
int  mf_open_fd(MeshFile *f, int fd, int flags, char *msg, size_t msglen);

/* mesh_ref_open (mesh.h) is how a loader opens what a model names. */
/* mesh_ref_open for a load: e->on_ref is told of the file once it is
 * open (image: a texture). */
int  me_ref_open(MeshErr *e, const char *model, const char *full, int image, char *why, size_t whylen);

/* gzip (gzip.c): do these bytes start gzip data? Start decompressing
 * f (its fd read on from where it stands; seed: the compressed bytes
 * already read from it), read decompressed bytes of every member in turn
 * (0 at the end, -1 with msg), and free the state (mf_close does). */
int  mf_is_gzip(const char *h, size_t n);
int  mf_gz_start(MeshFile *f, const char *seed, size_t nseed, char *msg, size_t msglen);
long mf_gz_read(MeshFile *f, char *buf, size_t n, char *msg, size_t msglen);
void mf_gz_end(MeshFile *f);
/* After the data was read to its end: 1 + the compressed byte where
 * bytes that are no gzip member follow the last (ignored, as zcat does,
 * with a warning), or 0. */
uint64_t mf_gz_trailing(const MeshFile *f);

/* How much of a stream to read (mapped files are always whole). */
typedef struct {
    int      stop_at_nul;  /* text: a NUL already makes it invalid */
    uint64_t max;          /* stop after this many bytes (0 = MESH_MAX_BYTES) */
    uint64_t mem;          /* what memory allows a stream to hold (0 = no limit but max) */
} MfLimits;

/* Make the whole input available in data/len: map a regular file (the
 * first window copied in), or read the rest of a stream. -1 with msg on
 * failure ("file too large", "cannot read: ..."). */
int  mf_load(MeshFile *f, const MfLimits *lim, char *msg, size_t msglen);
void mf_close(MeshFile *f);
/* After a parse: did the mapped file change while it was read (found
 * shorter, or its size or modification time differ from mf_open's)? */
int  mf_changed(MeshFile *f);

/* The paging window: a loader reports how far it has read, every few
 * MB; what lies ahead is copied in, and what lies well behind is dropped
 * from this process (the page cache keeps it), so a big file costs a
 * window of memory, not its size. A loader must not look back more than
 * MF_KEEP_BEHIND bytes from the last position it reported, nor read
 * more than MF_AHEAD - MF_STEP bytes past it: a longer read (a record or
 * a line longer than that) asks with mf_need first. */
#define MF_AHEAD       ((size_t)4 << 20)
#define MF_KEEP_BEHIND ((size_t)1 << 20)
#define MF_STEP        ((size_t)2 << 20)
/* Keep [keep - MF_KEEP_BEHIND, upto + MF_AHEAD) in. */
void mf_window(MeshFile *f, size_t keep, size_t upto);
static inline void mf_progress(MeshFile *f, const char *p)
{
    if (f && f->map && (size_t)(p - f->data) >= f->mark)
        mf_window(f, (size_t)(p - f->data), (size_t)(p - f->data));
}
/* Before reading [keep, upto): make it safe to read, without dropping
 * anything from keep on (a long line or record). */
static inline void mf_need(MeshFile *f, const void *keep, const void *upto)
{
    if (f && f->map && (size_t)((const char *)upto - f->data) > f->populated)
        mf_window(f, (size_t)((const char *)keep - f->data), (size_t)((const char *)upto - f->data));
}
/* Where reading must stop until mf_need is asked (the end for memory). */
static inline const char *mf_limit(const MeshFile *f, const char *end)
{
    return f && f->map && f->data + f->populated < end ? f->data + f->populated : end;
}

/* A count with thousands separators: "180,000,000". */
void mesh_count_str(uint64_t n, char *buf, size_t len);

/* ==== Text ==== */

enum {
    MESH_NUM_OK = 0,
    MESH_NUM_BAD,        /* not a number, or junk glued to it */
    MESH_NUM_NONFINITE,  /* "nan", "inf", "infinity" (any case, signed) */
    MESH_NUM_RANGE       /* finite text whose value overflows the type */
};

static inline int mesh_is_digit(char c) { return (unsigned char)(c - '0') < 10; }
/* Blanks within a line. */
static inline int mesh_is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
/* Any white space, line ends included (token-based formats). */
static inline int mesh_is_ws(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

/* Parse one decimal float at *pp (sign, digits, '.', e/E exponent). The
 * number must be followed by the end or white space. On success
 * advances *pp past it. Never reads at or past `end`. */
int  mesh_parse_float(const char **pp, const char *end, float *out);

/* Parse an optionally signed decimal integer into *out, followed by the
 * end or white space. MESH_NUM_RANGE past +-(2^63 - 1). */
int  mesh_parse_int(const char **pp, const char *end, int64_t *out);

/* True if [p, end) holds a control byte other than tab, CR and LF, which
 * no text model line can carry. */
int  mesh_has_binary(const char *p, const char *end);

/* Case-insensitive: does [p, end) start with the lower-case word w,
 * followed by the end or white space? */
int  mesh_word_is(const char *p, const char *end, const char *w);

/* The token at p (up to white space), at most 40 bytes, for messages. */
int  mesh_tok_len(const char *p, const char *end);

/* The UTF-8 byte-order mark some editors put first: 3, or 0. */
static inline size_t mesh_bom_len(const char *p, size_t n)
{
    return n >= 3 && memcmp(p, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
}

/* Lines end at LF, CRLF or a lone CR, in any mix (files pass through
 * editors and tools of both worlds). Lines are numbered from 1. A NUL,
 * which no text line holds, ends a line too, the line holding it and
 * the run of NULs after it: a file of zeros past a valid start is not
 * searched to its end for a line end, and is one bad line, not one a
 * byte. Reading a mapped file, the reader keeps the window (MeshFile)
 * on the line it returns, however long. */
typedef struct {
    const char *p, *end;
    uint64_t    line;      /* number of the line last returned */
    MeshFile   *file;      /* the paging window; NULL for memory */
} LineReader;

void lr_init(LineReader *lr, const char *data, size_t len, MeshFile *file);

/* The first '\n', '\r' or NUL in [p, end), or end: sixteen bytes at a
 * time with SSE2 (every x86-64 has it), else eight (a line of an OBJ is
 * some 30 bytes; this is the loaders' inner loop). Never reads at or
 * past end. Chosen when compiled (ZV_SSE2), not by the frame's level:
 * loading has no frame, and make nosimd tests the eight-byte loop. */
static inline const char *lr_stop(const char *p, const char *end)
{
#ifdef ZV_SSE2
    const __m128i lf = _mm_set1_epi8('\n'), cr = _mm_set1_epi8('\r'), nul = _mm_setzero_si128();
    while (end - p >= 16) {
        __m128i v = _mm_loadu_si128((const __m128i *)(const void *)p);
        __m128i hit = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(v, lf), _mm_cmpeq_epi8(v, cr)),
                                   _mm_cmpeq_epi8(v, nul));
        unsigned mask = (unsigned)_mm_movemask_epi8(hit);
        if (mask)
            return p + __builtin_ctz(mask);
        p += 16;
    }
#endif
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    const uint64_t ones = 0x0101010101010101ull, highs = 0x8080808080808080ull;
    while (end - p >= 8) {
        uint64_t w;
        memcpy(&w, p, 8);
        uint64_t lf8 = w ^ (ones * '\n'), cr8 = w ^ (ones * '\r');
        /* a byte is flagged when it is zero; below the first flag the
         * test is exact, so the lowest flag is the first stop */
        uint64_t z = ((w - ones) & ~w) | ((lf8 - ones) & ~lf8) | ((cr8 - ones) & ~cr8);
        z &= highs;
        if (z)
            return p + (__builtin_ctzll(z) >> 3);
        p += 8;
    }
#endif
    while (p < end && *p != '\n' && *p != '\r' && *p != '\0')
        p++;
    return p;
}

/* The stop of a line that reaches the window's end (lr_next's slow
 * path): the window is moved on, keeping the line, until a stop. */
const char *lr_long_line(LineReader *lr, const char *ls, const char *from);

/* The next line [*ls, *le) without its line end. Returns 0 at the end
 * of the input. */
static inline __attribute__((always_inline)) int lr_next(LineReader *lr, const char **ls, const char **le)
{
    const char *p = lr->p, *end = lr->end;
    if (p >= end)
        return 0;
    lr->line++;
    mf_progress(lr->file, p);
    const char *lim = mf_limit(lr->file, end);
    const char *q = lr_stop(p, lim);
    /* the byte after a CR decides CRLF: it must be in too */
    if (lim < end && q + 1 >= lim)
        q = lr_long_line(lr, p, q);
    *ls = p;
    *le = q;
    if (q >= end)
        lr->p = end;
    else if (*q == '\n')
        lr->p = q + 1;
    else if (*q == '\r')
        lr->p = q + 1 < end && q[1] == '\n' ? q + 2 : q + 1;
    else {
        /* a NUL: it and the NULs after it (those in the window) are this line's */
        lim = mf_limit(lr->file, end);
        while (q < lim && *q == '\0')
            q++;
        *le = lr->p = q;
    }
    return 1;
}

/* ==== Binary ==== */

static inline uint16_t rd_u16le(const void *p)
{
    const unsigned char *b = p;
    return (uint16_t)(b[0] | b[1] << 8);
}
static inline uint32_t rd_u32le(const void *p)
{
    uint32_t v;
    memcpy(&v, p, 4);
#if __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    v = __builtin_bswap32(v);
#endif
    return v;
}
static inline uint32_t rd_u32be(const void *p)
{
    uint32_t v;
    memcpy(&v, p, 4);
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    v = __builtin_bswap32(v);
#endif
    return v;
}
static inline float rd_f32le(const void *p)
{
    uint32_t u = rd_u32le(p);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

#endif
