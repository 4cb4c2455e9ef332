/* gzip.c: gzip-compressed input (x.stl.gz, a .blend saved compressed,
 * `gzip -c | zview -`). mf_open finds the magic in a file's first bytes
 * and from then on the file is read as a stream whose bytes come out of
 * zlib: the loaders, the format probes and a stream's bounds (memory,
 * MESH_MAX_BYTES, a format's own size) see only decompressed bytes, and
 * are the same as for an uncompressed stream. */
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

typedef struct MfGzip {
    z_stream z;
    uint64_t in_total;     /* compressed bytes handed to zlib, for messages */
    int      ended;        /* the last member ended */
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
            /* what follows the first member (more members, padding) is
             * not read: gzip -c writes one */
            g->ended = 1;
            break;
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
