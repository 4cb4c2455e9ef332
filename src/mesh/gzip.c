/* gzip.c: gzip-compressed input (x.stl.gz, a .blend saved compressed,
 * `gzip -c | zview -`). mf_open finds the magic in a file's first bytes
 * and from then on the file is read as a stream whose bytes come out of
 * zlib: the loaders, the format probes and a stream's bounds (memory,
 * MESH_MAX_BYTES, a format's own size) see only decompressed bytes, and
 * are the same as for an uncompressed stream.
 *
 * A file may hold several members (`cat a.gz b.gz`, pigz, bgzip): they
 * are read one after the other, as zcat does, an empty one included.
 * After the last, zero bytes (a tape's padding) are ignored, and other
 * bytes are ignored with a warning (mf_gz_trailing; --strict refuses
 * them), as zcat says "trailing garbage ignored"; a member cut short, or
 * the start of one, is an error. */
#define _DEFAULT_SOURCE

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "reader.h"

/* Compressed bytes are read this many at a time. */
#define GZ_IN ((size_t)1 << 16)
/* Zero bytes after the last member passed over quietly (zcat ignores a
 * tape's padding, 10 KB a block). */
#define GZ_PAD_MAX ((uint64_t)1 << 16)

typedef struct MfGzip {
    z_stream z;
    uint64_t in_total;     /* compressed bytes handed to zlib, for messages */
    int      ended;        /* the last member ended */
    uint64_t trailing;     /* 1 + the compressed byte where bytes that are no member start; 0: none */
    unsigned char in[GZ_IN];
} MfGzip;

int mf_is_gzip(const char *h, size_t n)
{
    return n >= 3 && (unsigned char)h[0] == 0x1f && (unsigned char)h[1] == 0x8b && h[2] == 8;
}

int mf_gz_start(MeshFile *f, const char *seed, size_t nseed, char *msg, size_t msglen)
{
    MfGzip *g = calloc(1, sizeof *g);
    if (!g) {
        snprintf(msg, msglen, "out of memory");
        return -1;
    }
    /* 15 + 16: a gzip header and trailer, not a raw zlib stream */
    if (inflateInit2(&g->z, 15 + 16) != Z_OK) {
        free(g);
        snprintf(msg, msglen, "out of memory (zlib)");
        return -1;
    }
    if (nseed > GZ_IN)
        nseed = GZ_IN;
    memcpy(g->in, seed, nseed);
    g->z.next_in = g->in;
    g->z.avail_in = (uInt)nseed;
    g->in_total = nseed;
    f->gz = g;
    return 0;
}

/* At least want compressed bytes waiting (fewer at the end of the
 * file): 0, or -1 with msg. What waits moves to the buffer's start. */
static int fill(MeshFile *f, MfGzip *g, size_t want, char *msg, size_t msglen)
{
    if (g->z.avail_in >= want)
        return 0;
    memmove(g->in, g->z.next_in, g->z.avail_in);
    g->z.next_in = g->in;
    while (g->z.avail_in < want) {
        ssize_t r = read(f->fd, g->in + g->z.avail_in, GZ_IN - g->z.avail_in);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            snprintf(msg, msglen, "cannot read: %s", strerror(errno));
            return -1;
        }
        if (r == 0)
            return 0;
        g->z.avail_in += (uInt)r;
        g->in_total += (uint64_t)r;
    }
    return 0;
}

/* A member ended: 1 when another starts (zlib reset to read it), 0 at
 * the end of the data (zero padding skipped; other bytes noted in
 * g->trailing), -1 with msg (the start of a member cut short). */
static int next_member(MeshFile *f, MfGzip *g, char *msg, size_t msglen)
{
    /* zeros: a tape's padding, a block at most; more (a stream of them)
     * is left unread, as trailing bytes */
    uint64_t zeros = 0, at = g->in_total - g->z.avail_in;
    for (;;) {
        if (fill(f, g, 1, msg, msglen))
            return -1;
        if (g->z.avail_in == 0)
            return 0;
        if (*g->z.next_in != 0 || zeros == GZ_PAD_MAX)
            break;
        g->z.next_in++;
        g->z.avail_in--;
        zeros++;
    }
    if (!zeros && *g->z.next_in == 0x1f) {
        if (fill(f, g, 2, msg, msglen))
            return -1;
        if (g->z.avail_in < 2) {
            /* the file ends inside a member's magic: as zcat, an error */
            snprintf(msg, msglen, "gzip data cut short (after %llu compressed bytes)",
                     (unsigned long long)g->in_total);
            return -1;
        }
        if (g->z.next_in[1] == 0x8b) {
            /* another member: zlib reads its header (a damaged one is
             * an error there) */
            if (inflateReset(&g->z) != Z_OK) {
                snprintf(msg, msglen, "out of memory (zlib)");
                return -1;
            }
            return 1;
        }
    }
    g->trailing = at + 1;
    return 0;
}

uint64_t mf_gz_trailing(const MeshFile *f)
{
    return f->gz ? f->gz->trailing : 0;
}

/* Up to n decompressed bytes into buf: the count, 0 at the end of the
 * data, -1 with msg (damaged or cut short, and where). */
long mf_gz_read(MeshFile *f, char *buf, size_t n, char *msg, size_t msglen)
{
    MfGzip *g = f->gz;
    if (g->ended || n == 0)
        return 0;
    if (n > ((size_t)1 << 30))
        n = (size_t)1 << 30;
    g->z.next_out = (unsigned char *)buf;
    g->z.avail_out = (uInt)n;
    while (g->z.avail_out == n) {
        if (g->z.avail_in == 0) {
            ssize_t r = read(f->fd, g->in, GZ_IN);
            if (r < 0 && errno == EINTR)
                continue;
            if (r < 0) {
                snprintf(msg, msglen, "cannot read: %s", strerror(errno));
                return -1;
            }
            if (r == 0) {
                snprintf(msg, msglen, "gzip data cut short (after %llu compressed bytes)",
                         (unsigned long long)g->in_total);
                return -1;
            }
            g->z.next_in = g->in;
            g->z.avail_in = (uInt)r;
            g->in_total += (uint64_t)r;
        }
        int zr = inflate(&g->z, Z_NO_FLUSH);
        if (zr == Z_STREAM_END) {
            int more = next_member(f, g, msg, msglen);
            if (more < 0)
                return -1;
            if (!more) {
                g->ended = 1;
                break;
            }
            continue;
        }
        if (zr == Z_MEM_ERROR) {
            snprintf(msg, msglen, "out of memory (zlib)");
            return -1;
        }
        if (zr != Z_OK && zr != Z_BUF_ERROR) {
            snprintf(msg, msglen, "damaged gzip data near compressed byte %llu (%s)",
                     (unsigned long long)(g->in_total - g->z.avail_in),
                     g->z.msg ? g->z.msg : "inflate failed");
            return -1;
        }
    }
    return (long)(n - g->z.avail_out);
}

void mf_gz_end(MeshFile *f)
{
    if (!f->gz)
        return;
    inflateEnd(&f->gz->z);
    free(f->gz);
    f->gz = NULL;
}
