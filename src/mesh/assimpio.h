#ifndef ZV_ASSIMPIO_H
#define ZV_ASSIMPIO_H
/* assimpio: the file system assimp is given (assimpio.c): files beneath
 * the model's folder only, or one buffer in memory and nothing else. */

#include <assimp/cfileio.h>
#include <assimp/types.h>

#include "mesh_internal.h"

/* Refusals warned about by name, at most (then they are only refused). */
#define AI_IO_WARN 4

typedef struct {
    struct aiFileIO fio;        /* what aiImportFileEx is given */
    MeshErr        *err;        /* where refusals are warned about */
    const char     *model;      /* the model's file (its folder bounds the rest) */
    const char     *data;       /* a model in memory, or NULL */
    size_t          len;
    char            name[40];   /* the buffer's name for assimp */
    const char     *model_data; /* served for the model's own path when set (a mended glTF) */
    size_t          model_len;
    unsigned        warned;
} AiIo;

/* Set io up for the model at `model` (data NULL) or in memory (data,
 * len; hint its extension, "" none): then aiImportFileEx(model or
 * io->name, flags, &io->fio). */
void ai_io_init(AiIo *io, MeshErr *err, const char *model, const char *data, size_t len, const char *hint);

#endif
