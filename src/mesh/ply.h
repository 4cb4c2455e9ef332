#ifndef ZV_MESH_PLY_H
#define ZV_MESH_PLY_H
/* ply: what the PLY loader's three parts share. ply.c reads the header
 * (elements, their typed properties, the counts checked against the
 * size) and is the loader; plybin.c reads binary bodies, plyascii.c
 * ascii ones, each element by element into the MeshBuild. Not part of
 * the public API. */

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "mesh_internal.h"

typedef enum { T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64, T_NONE } PlyType;

/* Bytes of a value of each type, and the value an integer colour
 * channel of that type means as full intensity (1 for the floats). */
extern const unsigned ply_type_size[];
extern const double   ply_type_max[];

enum { R_NONE, R_X, R_Y, R_Z, R_RED, R_GREEN, R_BLUE, R_ALPHA, R_INDICES };
enum { EL_OTHER, EL_VERTEX, EL_FACE };
enum { FMT_ASCII, FMT_LE, FMT_BE };

typedef struct {
    PlyType  type;        /* scalar type, or the list's item type */
    PlyType  count_type;  /* a list's count type; T_NONE: a scalar */
    int      role;
    unsigned offset;      /* in a record of fixed size (binary, no lists) */
} PlyProp;

typedef struct {
    char     name[32];
    uint64_t count;
    int      kind;
    PlyProp *props;
    uint32_t nprops, cap;
    int      has_list;
    uint64_t fixed;       /* record size without lists */
    uint64_t min_size;    /* the least bytes a record can take (binary) */
    uint64_t min_tokens;  /* the least numbers a record holds (ascii) */
} PlyElem;

typedef struct {
    MeshCtx   *c;
    MeshErr   *e;
    MeshBuild *b;
    int        fmt;
    PlyElem   *el;
    uint32_t   nel, elcap;
    const char *data, *body, *end;
    uint64_t   body_line;  /* ascii: the line the body starts on */
    uint64_t   nverts;     /* the vertex element's count */
    int        ended;      /* the file ended inside the faces (kept so far) */
} Ply;

/* ==== Shared by the bodies (ply.c) ==== */

/* The material of a face's colour (channels 0..1). 0 or -1. */
int ply_face_colour(Ply *ply, const float c3[3], int32_t *mat);
/* The faces read so far are kept when the file ends inside one (not
 * strict): the rest of the file is one skipped statement. Returns 0 to
 * go on (with ply->ended set), -1 to fail. */
int ply_ended_early(Ply *ply);

/* A colour channel of type t as 0..1: integers scaled by their type's
 * maximum, floats as they are; clamped. */
static inline float ply_colour_of(double v, PlyType t)
{
    float f = (float)(t >= T_F32 ? v : v / ply_type_max[t]);
    return f < 0 ? 0 : f > 1 ? 1 : f;
}

/* A coordinate as float; -1 when not finite (or past a float's range). */
static inline int ply_to_coord(double v, float *out)
{
    if (!(fabs(v) <= 3.4028234663852886e38))
        return -1;
    *out = (float)v;
    return 0;
}

/* Does any property of el carry a colour channel? */
static inline int ply_coloured(const PlyElem *el)
{
    int coloured = 0;
    for (uint32_t k = 0; k < el->nprops; k++)
        coloured |= el->props[k].role >= R_RED && el->props[k].role <= R_BLUE;
    return coloured;
}

/* ==== The bodies ==== */

/* Every element of a binary body (the header read and its counts
 * checked, the arrays reserved); data is the file's start, for the byte
 * offsets of messages. 0 or -1. */
int ply_read_binary(Ply *ply, const char *data);
/* The same for an ascii body. */
int ply_read_ascii(Ply *ply);

#endif
