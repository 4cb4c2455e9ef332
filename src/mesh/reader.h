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

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

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
 * devices, standard input). The data is NOT NUL-terminated. */
typedef struct MeshFile {
    const char *data;      /* after mf_load: the whole input */
    size_t      len;
    const char *head;      /* after mf_open: the first nhead bytes */
    size_t      nhead;
    uint64_t    size;      /* a regular file's size; a stream's bytes read so far */
    int         regular;
    int         fd;        /* -1 once loaded or closed */
    uint64_t    dev, ino;  /* identity, to load a file once */
    char        headbuf[MESH_HEAD];
    void       *map;       /* mmap base, or NULL */
    char       *heap;      /* stream bytes, or NULL */
    size_t      cap;
    /* the paging window (mapped files): [released, populated) is what
     * was asked in and not yet dropped; mf_progress moves it at `mark` */
    size_t      populated, released, mark;
    uint64_t   *progress;  /* NULL, or bytes parsed so far (atomic stores, see MeshProgress) */
} MeshFile;

/* Open `path` ("-" = standard input) and read its first bytes into head
 * (a regular file: pread, nothing mapped yet; a stream: the start of the
 * heap copy). On failure returns -1 with a message without the path
 * ("cannot open: ...", "is a directory", "not a regular file (a FIFO)").
 * An empty file succeeds with nhead 0. */
int  mf_open(MeshFile *f, const char *path, int flags, char *msg, size_t msglen);

/* How much of a stream to read (mapped files are always whole). */
typedef struct {
    int      stop_at_nul;  /* text: a NUL already makes it invalid */
    uint64_t max;          /* stop after this many bytes (0 = MESH_MAX_BYTES) */
} MfLimits;

/* Make the whole input available in data/len: map a regular file (the
 * first window paged in), or read the rest of a stream. -1 with msg on
 * failure ("file too large", "cannot read: ..."). */
int  mf_load(MeshFile *f, const MfLimits *lim, char *msg, size_t msglen);
void mf_close(MeshFile *f);

/* The paging window: a loader reports how far it has read, every few
 * MB; what lies ahead is paged in, and what lies well behind is dropped
 * from this process (the page cache keeps it), so a big file costs a
 * window of memory, not its size. A loader must not look back more than
 * MF_KEEP_BEHIND bytes from the last position it reported. */
#define MF_AHEAD       ((size_t)8 << 20)
#define MF_KEEP_BEHIND ((size_t)1 << 20)
#define MF_STEP        ((size_t)2 << 20)
void mf_window(MeshFile *f, size_t pos);
static inline void mf_progress(MeshFile *f, const char *p)
{
    if (f && f->map && (size_t)(p - f->data) >= f->mark)
        mf_window(f, (size_t)(p - f->data));
}

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

/* Lines: LF and CRLF, and old-Mac CR-only files (decided by the first
 * line end in the file: a CR not followed by LF). In CR files a CRLF
 * also ends one line. Lines are numbered from 1. */
typedef struct {
    const char *p, *end;
    uint64_t    line;      /* number of the line last returned */
    char        eol;       /* '\n' or '\r' */
} LineReader;

void lr_init(LineReader *lr, const char *data, size_t len);
/* Where the line at p ends, when it is longer than a first look: it
 * ends at its line end, or just after a NUL (no text line holds one, and
 * a file of zeros past a valid start must not be read to its end to find
 * a line end it does not have). */
const char *lr_long_line(const char *p, const char *end, char eol);

#define LR_LOOK 4096

/* The next line [*ls, *le) without its line end (a trailing CR of CRLF
 * is stripped). Returns 0 at the end of the input. */
static inline int lr_next(LineReader *lr, const char **ls, const char **le)
{
    const char *p = lr->p, *end = lr->end;
    if (p >= end)
        return 0;
    lr->line++;
    size_t look = (size_t)(end - p) < LR_LOOK ? (size_t)(end - p) : LR_LOOK;
    const char *nl = memchr(p, lr->eol, look);
    if (!nl && look < (size_t)(end - p))
        nl = lr_long_line(p, end, lr->eol);
    const char *e = nl ? nl : end;
    *ls = p;
    lr->p = nl ? nl + 1 : end;
    if (lr->eol == '\n') {
        if (e > p && e[-1] == '\r')
            e--;
    } else if (lr->p < end && *lr->p == '\n') {
        lr->p++;
    }
    *le = e;
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
