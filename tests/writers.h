#ifndef ZV_TEST_WRITERS_H
#define ZV_TEST_WRITERS_H
/* writers: a loaded Mesh written back as every format zview reads
 * natively (and as glTF binary for assimp), so that the tests can load
 * one model in each and compare. Floats are written exactly (binary, or
 * %.9g, which round-trips a float). Each returns a malloc'd buffer and
 * its length, or NULL. */

#include <stddef.h>
#include <stdint.h>
#include "mesh.h"

char *w_obj(const Mesh *m, size_t *len);
char *w_stl_binary(const Mesh *m, size_t *len);   /* triangles only */
char *w_stl_ascii(const Mesh *m, size_t *len);    /* triangles only */
char *w_ply_binary(const Mesh *m, int big_endian, size_t *len);
char *w_ply_ascii(const Mesh *m, size_t *len);
char *w_off(const Mesh *m, size_t *len);
char *w_glb(const Mesh *m, size_t *len);          /* triangles only */

/* ==== images, hostile ones among them ====
 * Each returns a malloc'd buffer and its length, or NULL. */

/* A JPEG written by libjpeg from w x h pixels of `comps` bytes each
 * (1 grey, 3 RGB, 4 CMYK as bytes of ink: 0 none, 255 full). colour: the
 * JPEG's colour space, "grey", "ycc" (from RGB), "rgb", "cmyk" or
 * "ycck" (from CMYK); adobe: write Adobe's APP14 marker (libjpeg
 * writes it for CMYK and YCCK, and writes CMYK inverted, 255 = no ink,
 * as Adobe does; without the marker the bytes are stored as given);
 * progressive: jpeg_simple_progression's scans. */
char *w_jpeg(const uint8_t *px, int w, int h, int comps, const char *colour, int adobe, int progressive,
             size_t *len);
/* The JPEG's frame header (SOF) says w x h instead (the data stays the
 * small image's: a decoder reads past its end as zeros). 0, or -1 when
 * there is no SOF. */
int  w_jpeg_set_size(char *jpg, size_t len, int w, int h);
/* The JPEG with its last scan (and the tables written just before it)
 * repeated n more times before the end: a progressive file whose
 * every copy makes the decoder pass over the whole image again. */
char *w_jpeg_repeat_last_scan(const char *jpg, size_t len, int n, size_t *len_out);
/* A PNG whose header says w x h (8-bit RGB) and whose one IDAT holds a
 * zlib stream of a single zero byte: 57 bytes that claim any size. */
char *w_png_claiming(int w, int h, size_t *len);
/* A run-length encoded grey TGA of w x h (top row first when top) whose
 * packets of 128 repeated pixels cover the image: 2 bytes a packet. */
char *w_tga_rle(int w, int h, int top, size_t *len);

/* Write buf to path; 0 on success. */
int  w_save(const char *path, const char *buf, size_t len);

#endif
