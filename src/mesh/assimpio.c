/* assimpio.c: assimp's file system, confined. assimp opens what a model
 * names (glTF buffers and images, an OBJ's MTL, COLLADA's images, ...)
 * through an IO system; by default it opens any path at all. Here every
 * open goes through mesh_ref_open, beneath the model's folder, and each
 * refusal is a warning naming the reference. A model in memory (standard
 * input, a FIFO's bytes) is served under one name, and every other file
 * it names is refused: it has no folder. A model file whose bytes are
 * given (a glTF mended: datauri.c) is served from them under its own
 * path, the rest beneath its folder. Writing is never granted. */
#define _DEFAULT_SOURCE

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "assimpio.h"

typedef struct {
    FILE       *f;              /* a file, or NULL for the buffer */
    const char *data;
    size_t      len, pos;
} IoFile;

static size_t io_read(struct aiFile *af, char *buf, size_t size, size_t count)
{
    IoFile *h = (IoFile *)af->UserData;
    if (h->f)
        return fread(buf, size, count, h->f);
    if (!size)
        return 0;
    size_t n = (h->len - h->pos) / size < count ? (h->len - h->pos) / size : count;
    memcpy(buf, h->data + h->pos, n * size);
    h->pos += n * size;
    return n;
}

static size_t io_write(struct aiFile *af, const char *buf, size_t size, size_t count)
{
    (void)af, (void)buf, (void)size, (void)count;
    return 0;                   /* a model is read, never written */
}

static size_t io_tell(struct aiFile *af)
{
    IoFile *h = (IoFile *)af->UserData;
    long p = h->f ? ftell(h->f) : (long)h->pos;
    return p < 0 ? 0 : (size_t)p;
}

static size_t io_size(struct aiFile *af)
{
    IoFile *h = (IoFile *)af->UserData;
    if (!h->f)
        return h->len;
    long at = ftell(h->f);
    fseek(h->f, 0, SEEK_END);
    long n = ftell(h->f);
    fseek(h->f, at, SEEK_SET);
    return n < 0 ? 0 : (size_t)n;
}

static enum aiReturn io_seek(struct aiFile *af, size_t off, enum aiOrigin from)
{
    IoFile *h = (IoFile *)af->UserData;
    if (h->f) {
        int wh = from == aiOrigin_SET ? SEEK_SET : from == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
        return fseek(h->f, (long)off, wh) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
    }
    size_t base = from == aiOrigin_SET ? 0 : from == aiOrigin_CUR ? h->pos : h->len;
    if (off > h->len - base)
        return aiReturn_FAILURE;
    h->pos = base + off;
    return aiReturn_SUCCESS;
}

static void io_flush(struct aiFile *af)
{
    (void)af;
}

static struct aiFile *io_new(AiIo *io, FILE *f)
{
    struct aiFile *af = calloc(1, sizeof *af);
    IoFile *h = calloc(1, sizeof *h);
    if (!af || !h) {
        free(af);
        free(h);
        if (f)
            fclose(f);
        return NULL;
    }
    h->f = f;
    h->data = io->data;
    h->len = io->len;
    *af = (struct aiFile){ .ReadProc = io_read, .WriteProc = io_write, .TellProc = io_tell,
                           .FileSizeProc = io_size, .SeekProc = io_seek, .FlushProc = io_flush,
                           .UserData = (aiUserData)h };
    return af;
}

static struct aiFile *io_open(struct aiFileIO *fio, const char *name, const char *mode)
{
    AiIo *io = (AiIo *)fio->UserData;
    if (!name || !mode || strpbrk(mode, "wa+"))
        return NULL;
    if (io->model_data && io->model && !strcmp(name, io->model)) {
        /* the model file's own bytes, mended (datauri.c) */
        struct aiFile *af = io_new(io, NULL);
        if (af) {
            ((IoFile *)af->UserData)->data = io->model_data;
            ((IoFile *)af->UserData)->len = io->model_len;
        }
        return af;
    }
    if (io->data && !strcmp(name, io->name))
        return io_new(io, NULL);
    char why[200];
    int fd = me_ref_open(io->err, io->data ? NULL : io->model, name, 0, why, sizeof why);
    if (fd < 0) {
        /* a name that is not there is assimp looking for optional files;
         * a refusal is the model reaching out, and the user hears of it */
        if (!strncmp(why, "refused", 7) && io->warned++ < AI_IO_WARN)
            me_warn(io->err, NULL, 0, "'%s' is not read (%s)", name, why);
        return NULL;
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return NULL;
    }
    return io_new(io, f);
}

static void io_close(struct aiFileIO *fio, struct aiFile *af)
{
    (void)fio;
    if (!af)
        return;
    IoFile *h = (IoFile *)af->UserData;
    if (h->f)
        fclose(h->f);
    free(h);
    free(af);
}

void ai_io_init(AiIo *io, MeshErr *err, const char *model, const char *data, size_t len, const char *hint)
{
    memset(io, 0, sizeof *io);
    io->err = err;
    io->model = model;
    io->data = data;
    io->len = len;
    /* the buffer's name: its extension is how assimp picks an importer */
    snprintf(io->name, sizeof io->name, "zview-memory%s%.20s", hint && *hint ? "." : "", hint ? hint : "");
    io->fio = (struct aiFileIO){ .OpenProc = io_open, .CloseProc = io_close, .UserData = (aiUserData)io };
}
