#ifndef ZV_TEXTURE_INTERNAL_H
#define ZV_TEXTURE_INTERNAL_H
/* Internal to src/texture/. */

#include "texture.h"

/* Level 0 is in t->rgba (with room for all levels): fill in every
 * level's size and offset and compute levels 1.. from it (mip.c). */
void texture_build_levels(Texture *t);
/* linear_to_srgb by table (mip.c), and one level from the one before:
 * dst (dw x dh) from src (sw x sh), each texel the average in linear
 * light of its 2 x 2 block (a side of 1 averaged with itself). */
#define TEX_ENC_BUCKETS 4096
typedef struct {
    float   th[255];                        /* th[b]: the least linear value encoded as b + 1 or more */
    uint8_t start[TEX_ENC_BUCKETS + 1];     /* the byte of k / TEX_ENC_BUCKETS */
} TexEncoder;
void texture_encoder_init(TexEncoder *e);
void texture_halve(const TexEncoder *e, const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh);

/* ==== shrink.c: an image halved as its rows arrive ====
 * A decoder hands its rows top to bottom; each pair of rows is halved
 * at once into the next level's pair, and so on `halve` times, so that
 * only the kept level is ever whole: a 16k x 16k image kept at 4096 x
 * 4096 takes its 224 MB of texels and 2 rows a level, not the 1.4 GB of
 * its own chain. The bytes are those of level `halve` of the whole
 * image's chain (the same texture_halve, in the same order). */
typedef struct {
    Texture *t;                     /* the result; its level 0 is level `halve` */
    int      halve;
    int      lw[TEX_MAX_LEVELS + 1], lh[TEX_MAX_LEVELS + 1];   /* level j's size, j <= halve */
    int      got[TEX_MAX_LEVELS + 1];                          /* rows level j has had */
    uint8_t *pair[TEX_MAX_LEVELS];  /* two rows of each level j < halve (one block) */
    TexEncoder enc;
} TexShrink;
/* Working bytes beyond the kept texture's own (texture_bytes_for). */
uint64_t texture_shrink_bytes(int w, int h, int halve);
/* t takes the kept level, with room for its chain. 0, or -1 out of
 * memory (nothing held). */
int      texture_shrink_begin(TexShrink *s, Texture *t, int w, int h, int halve);
/* Where the next source row goes (w x 4 bytes, RGBA), and that it has
 * been written. Rows past the last are ignored. */
uint8_t *texture_shrink_row(TexShrink *s);
void     texture_shrink_push(TexShrink *s);
/* n black rows (0, 0, 0, 0: what a file cut short does not hold),
 * not halved one by one where a whole kept row is black: a TGA that
 * claims 16384 x 16384 in 20 bytes costs its kept texels only. */
void     texture_shrink_black(TexShrink *s, int n);
/* Rows never given are black; the kept level's chain is built. The
 * rows' memory is given back. */
void     texture_shrink_finish(TexShrink *s);
/* A decode that failed: everything given back, t empty. */
void     texture_shrink_abort(TexShrink *s);

/* ==== budget (decode.c) ====
 * A texture is kept at most TEX_FIT_SIDE-ish a side (the caller's
 * max_side), so what it may cost to decode is counted against that: by
 * default TEX_BUDGET_FACTOR times the kept level 0's texels (never less
 * than TEX_BUDGET_FLOOR), or the caller's max_bytes when it gives one;
 * never more than the machine has. */
#define TEX_BUDGET_FACTOR 16
#define TEX_BUDGET_FLOOR  ((uint64_t)64 << 20)
uint64_t texture_budget(int kw, int kh, uint64_t max_bytes);
/* Refuse a decode that would pass the budget: "name: a WxH what needs
 * about X to decode; the budget is Y (...)". working: the decoder's own
 * bytes; the kept texture (kw x kh, both copies) is added. 0 or -1. */
int texture_check_budget(const char *name, const char *what, int w, int h, int kw, int kh, uint64_t working,
                         uint64_t max_bytes, char *err, size_t errlen);
/* The kept level of a w x h image halved `halve` times. */
void texture_kept_size(int w, int h, int halve, int *kw, int *kh);

/* ==== the decoders: each halves `halve` times as it goes ==== */
int texture_decode_png(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes, int halve,
                       char *err, size_t errlen);
/* libjpeg does up to 3 of the halvings itself (its scale_denom, which
 * skips most of the work). */
int texture_decode_jpeg(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes, int halve,
                        char *err, size_t errlen);
/* The JPEG's size from its header: 0, or -1. */
int texture_jpeg_peek(const void *data, size_t len, int *w_out, int *h_out);
/* t->lin from t->rgba's levels (mip.c), once the levels are final; left
 * NULL when out of memory. */
void texture_build_lin(Texture *t);
/* Bytes t->lin takes for a w x h level 0 (its padding included). */
uint64_t texture_lin_bytes_for(int w, int h);

/* Refuse a w x h image before decoding it: too big a side, or more
 * memory than the caller allows or the machine has ("name: a 20000x20
 * image (1 to 16384 per side)"). 0 or -1. */
int  texture_check_size(int w, int h, const char *name, uint64_t max_bytes, char *err, size_t errlen);
/* Level 0's texels for a w x h image, with room for every level (t
 * zeroed first). NULL out of memory. */
uint8_t *texture_alloc_levels(Texture *t, int w, int h);

/* tga.c: Truevision TGA, true colour or grey, plain or run-length
 * encoded (what COLLADA and 3DS models often carry). The probe: 0 with
 * the size when the header is one, else -1. */
int  texture_tga_probe(const uint8_t *b, size_t len, int *w_out, int *h_out);
int  texture_decode_tga(Texture *t, const uint8_t *b, size_t len, const char *name, uint64_t max_bytes, int halve,
                        char *err, size_t errlen);

#endif
