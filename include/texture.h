#ifndef ZV_TEXTURE_H
#define ZV_TEXTURE_H
/* texture: a model's base-colour images. Decoded (PNG through libpng,
 * JPEG through libjpeg-turbo, TGA here), mipmapped in linear light, and sampled
 * with a filter as wide as a sample's footprint, so that a 4096 x 4096
 * texture on a terminal-sized picture neither aliases nor shimmers as
 * the model turns. Knows nothing of meshes, screens or terminals.
 *
 * Texture coordinates: u across the image from its left edge, v down
 * from its first (top) row, 1 = the image's far side; what lies outside
 * [0, 1] is wrapped by the texture's wrap mode. (OBJ's v runs up: its
 * loader turns it over.) Colours are sRGB bytes in memory and linear
 * light when sampled. */

#include <stddef.h>
#include <stdint.h>

#define TEX_MAX_SIDE   16384        /* larger images are refused */
#define TEX_MAX_LEVELS 15           /* 1 + log2(TEX_MAX_SIDE) */

typedef enum { TEX_REPEAT = 0, TEX_CLAMP, TEX_MIRROR } TexWrap;

typedef struct {
    int      w, h;                  /* level 0 */
    int      levels;                /* level k is max(1, w >> k) x max(1, h >> k) */
    int      lw[TEX_MAX_LEVELS], lh[TEX_MAX_LEVELS];
    size_t   off[TEX_MAX_LEVELS];   /* level k's first texel */
    uint8_t *rgba;                  /* every level, 4 bytes a texel, sRGB (alpha kept, unused) */
    uint16_t *lin;                  /* every level again, for sampling: 3 x 16 bits a texel, linear
                                       light x 65535 (NULL when memory ran out: rgba is sampled) */
    TexWrap  wrap_u, wrap_v;
} Texture;

/* Decode a PNG, JPEG or TGA image held in memory (told by its first
 * bytes) and build its mipmaps. name is what messages call it. Returns 0,
 * or -1 with "name: reason" in err and *t empty. max_bytes: refuse an
 * image whose decode (the decoder's own memory, the texels and mipmaps)
 * would take more (0: the default budget, texture_decode_fit). */
int  texture_decode(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes,
                    char *err, size_t errlen);
/* Texels already decoded (rgba: w x h, 4 bytes a texel, sRGB), copied
 * and mipmapped; the same checks and result. */
int  texture_from_rgba(Texture *t, const uint8_t *rgba, int w, int h, const char *name, uint64_t max_bytes,
                       char *err, size_t errlen);
/* The same from a file. */
int  texture_load_file(Texture *t, const char *path, uint64_t max_bytes, char *err, size_t errlen);

/* The size of a PNG or JPEG image from its header alone (nothing is
 * decoded): 0, or -1 when the bytes are not one. */
int  texture_peek(const void *data, size_t len, int *w_out, int *h_out);
/* texture_decode, but an image with a side longer than max_side (> 0)
 * is halved until it fits: JPEG decoded at a reduced scale (libjpeg's
 * scale_denom, which skips most of the work), and the rest halved as
 * the rows are decoded (the bytes of the whole image's mipmap level).
 * *halved_out: how many times (may be NULL). A picture has no use for
 * more texels than it has samples, and a 16k x 16k image's texels would
 * take 1.4 GB. With max_bytes 0 the bound is proportional to the
 * texture kept: 16 times its level 0's texels (at least 64 MB). */
int  texture_decode_fit(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes,
                        int max_side, int *halved_out, char *err, size_t errlen);
void texture_free(Texture *t);
/* The 16-bit linear texels (t->lin) for levels that came whole from
 * elsewhere (the loading sandbox passes the sRGB levels only); left NULL
 * when out of memory, and sampling then reads the sRGB levels. */
void texture_make_lin(Texture *t);
/* Bytes the texels of every level take (rgba and lin). */
size_t texture_bytes(const Texture *t);
/* Bytes a w x h image's texels and mipmaps take (4/3 of level 0). */
uint64_t texture_bytes_for(int w, int h);

/* The colour at (u, v) in linear light, out[0..2]. lod: log2 of how many
 * level-0 texels the sample's footprint spans along its longer side; at
 * or below 0 the image is magnified (bilinear on level 0), above it the
 * two nearest levels are blended (trilinear). */
void texture_sample(const Texture *t, float u, float v, float lod, float out[3]);
/* The same from the 16-bit linear texels (t->lin), the shading pass's
 * lookup: a texel is 3 loads fewer table look-ups and one load, and
 * the coordinates are wrapped once for both levels. Within 8e-6 of
 * texture_sample (a texel's rounding to 16 bits; 16 times finer than
 * the step between the darkest sRGB bytes). simd: a SimdLevel to run
 * at (SIMD_SCALAR: plain C); every level gives the same bits. */
void texture_sample_lin(const Texture *t, float u, float v, float lod, int simd, float out[3]);
/* texture_sample_lin in two steps, for samples that share a level (a
 * face seen orthographically has one footprint): the levels and their
 * weights once (t->lin must be there), then each lookup; the same bits. */
typedef struct {
    const uint16_t *px[2];          /* the levels' first texels */
    int      w[2], h[2];
    float    wt[2];                 /* the levels' weights */
    int      n;                     /* levels blended: 1 or 2 */
    TexWrap  wrap_u, wrap_v;
    float    size[4];               /* w[0], h[0], w[1], h[1] as floats (the lanes of the SIMD path) */
    int32_t  last[4];               /* the same less one */
    int32_t  repeat[4];             /* -1 on the lanes whose wrap is TEX_REPEAT (else clamp) */
    int      vec;                   /* no mirror: the SIMD path can wrap */
} TexLod;
void texture_lod(const Texture *t, float lod, TexLod *l);
void texture_lookup(const TexLod *l, float u, float v, int simd, float out[3]);
/* texture_lookup of n samples (u[i], v[i]) into out[4 i .. 4 i + 2]
 * (out[4 i + 3] is scratch), several at a time: the same bits, sample
 * by sample, at every level. u and v are read in whole groups of
 * TEX_ROW_PAD: the caller fills them to n rounded up (with a sample's
 * coordinates: lanes past n are computed and dropped). */
#define TEX_ROW_PAD 8
void texture_lookup_row(const TexLod *l, const float *u, const float *v, int n, int simd, float *out);

/* sRGB transfer (IEC 61966-2-1): a byte to linear light, and back. */
float   srgb_to_linear(uint8_t v);
uint8_t linear_to_srgb(float v);
/* The decoding table itself (256 entries), for loops that inline it. */
const float *srgb_table(void);

/* Encoding by table, for per-sample loops (linear_to_srgb's power costs
 * more than a whole texture lookup): SRGB_ENC_SIZE steps over [0, 1],
 * a value takes the byte of the nearest step, within one of linear_to_srgb's. The
 * caller owns the table (made once by srgb_enc_init). */
#define SRGB_ENC_SIZE 4096
typedef struct {
    uint8_t b[SRGB_ENC_SIZE + 1];
} SrgbEnc;
void srgb_enc_init(SrgbEnc *e);
static inline uint8_t srgb_enc(const SrgbEnc *e, float v)
{
    /* NaN and negatives to 0, past 1 to 255 */
    float x = v > 0 ? (v < 1 ? v : 1) : 0;
    return e->b[(int)(x * (float)SRGB_ENC_SIZE + 0.5f)];
}

#endif
