/* test_texture.c: decoding, mipmaps and filtered sampling of textures,
 * against the sRGB formula, images written by libpng and libjpeg
 * directly, and hand-made patterns whose averages are known. */

#include <criterion/criterion.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <jpeglib.h>

#include "simd.h"
#include "texture.h"

/* The IEC 61966-2-1 decoding, in double, written out here. */
static double iec_linear(int byte)
{
    double c = byte / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

Test(texture, srgb_bytes_decode_by_the_standard_formula)
{
    for (int b = 0; b < 256; b++)
        cr_expect(fabs(srgb_to_linear((uint8_t)b) - iec_linear(b)) < 1e-6, "byte %d: %.9g, formula %.9g", b,
                  (double)srgb_to_linear((uint8_t)b), iec_linear(b));
    /* the round trip is the identity on bytes */
    for (int b = 0; b < 256; b++)
        cr_expect_eq(linear_to_srgb(srgb_to_linear((uint8_t)b)), b, "byte %d", b);
    /* known values: mid-grey light is sRGB 188, not 128 */
    cr_expect_eq(linear_to_srgb(0.5f), 188);
    cr_expect_eq(linear_to_srgb(0), 0);
    cr_expect_eq(linear_to_srgb(1), 255);
    cr_expect_eq(linear_to_srgb(-1), 0);
    cr_expect_eq(linear_to_srgb(NAN), 0);
}

/* ==== images made by the libraries themselves ==== */

static unsigned char *png_bytes(const uint8_t *rgba, int w, int h, size_t *len)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)w;
    img.height = (png_uint_32)h;
    img.format = PNG_FORMAT_RGBA;
    png_alloc_size_t n = 0;
    cr_assert(png_image_write_to_memory(&img, NULL, &n, 0, rgba, 0, NULL));
    unsigned char *buf = malloc(n);
    cr_assert(png_image_write_to_memory(&img, buf, &n, 0, rgba, 0, NULL));
    *len = n;
    return buf;
}

static unsigned char *jpeg_bytes(const uint8_t *rgb, int w, int h, size_t *len)
{
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr e;
    c.err = jpeg_std_error(&e);
    jpeg_create_compress(&c);
    unsigned char *buf = NULL;
    unsigned long n = 0;
    jpeg_mem_dest(&c, &buf, &n);
    c.image_width = (JDIMENSION)w;
    c.image_height = (JDIMENSION)h;
    c.input_components = 3;
    c.in_color_space = JCS_RGB;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 100, TRUE);
    jpeg_start_compress(&c, TRUE);
    while (c.next_scanline < c.image_height) {
        JSAMPROW row = (JSAMPROW)(rgb + (size_t)c.next_scanline * w * 3);
        jpeg_write_scanlines(&c, &row, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    *len = n;
    return buf;
}

Test(texture, a_png_decodes_texel_for_texel)
{
    uint8_t px[5 * 3 * 4];
    for (int i = 0; i < 15; i++) {
        px[4 * i] = (uint8_t)(17 * i);
        px[4 * i + 1] = (uint8_t)(255 - 13 * i);
        px[4 * i + 2] = (uint8_t)(i * i);
        px[4 * i + 3] = 255;
    }
    size_t n;
    unsigned char *png = png_bytes(px, 5, 3, &n);
    Texture t;
    char err[256];
    cr_assert_eq(texture_decode(&t, png, n, "five.png", 0, err, sizeof err), 0, "%s", err);
    cr_expect_eq(t.w, 5);
    cr_expect_eq(t.h, 3);
    cr_expect_eq(t.levels, 3, "5x3, 2x1, 1x1");
    cr_expect_eq(memcmp(t.rgba, px, sizeof px), 0);
    /* the sRGB bytes, and the 16-bit linear copy sampling reads (6 bytes a texel, 8 of padding) */
    cr_expect_eq(texture_bytes(&t), (5 * 3 + 2 * 1 + 1) * (4 + 6) + 8);
    texture_free(&t);
    free(png);
}

Test(texture, a_jpeg_decodes_close_to_what_was_written)
{
    /* flat colour blocks of 16 x 16 (whole JPEG blocks, so little ringing) */
    enum { W = 32, H = 16 };
    static const uint8_t col[2][3] = { { 200, 40, 30 }, { 20, 90, 220 } };
    uint8_t rgb[W * H * 3];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            memcpy(rgb + 3 * (y * W + x), col[x / 16], 3);
    size_t n;
    unsigned char *jpg = jpeg_bytes(rgb, W, H, &n);
    Texture t;
    char err[256];
    cr_assert_eq(texture_decode(&t, jpg, n, "two.jpg", 0, err, sizeof err), 0, "%s", err);
    cr_assert_eq(t.w, W);
    cr_assert_eq(t.h, H);
    for (int side = 0; side < 2; side++) {
        const uint8_t *p = t.rgba + 4 * (8 * W + 4 + 16 * side);
        for (int c = 0; c < 3; c++)
            cr_expect(abs(p[c] - col[side][c]) <= 6, "block %d channel %d: %d, written %d", side, c, p[c],
                      col[side][c]);
    }
    texture_free(&t);
    free(jpg);
}

Test(texture, what_is_not_an_image_is_refused_by_name)
{
    Texture t;
    char err[256];
    cr_expect_eq(texture_decode(&t, "GIF89a....", 10, "x.gif", 0, err, sizeof err), -1);
    cr_expect_str_eq(err, "x.gif: not a PNG, JPEG or TGA image");
    cr_expect_null(t.rgba);
    /* a PNG cut short, and a JPEG cut short */
    uint8_t px[64 * 64 * 4];
    for (size_t i = 0; i < sizeof px; i++)
        px[i] = (uint8_t)(i * 7919 >> 3);
    size_t n;
    unsigned char *png = png_bytes(px, 64, 64, &n);
    cr_expect_eq(texture_decode(&t, png, n / 2, "cut.png", 0, err, sizeof err), -1);
    cr_expect(strncmp(err, "cut.png: ", 9) == 0, "%s", err);
    cr_expect_null(t.rgba);
    free(png);
    cr_expect_eq(texture_load_file(&t, "/no/such/tex.png", 0, err, sizeof err), -1);
    cr_expect_str_eq(err, "/no/such/tex.png: No such file or directory");
}

Test(texture, an_image_too_big_for_the_memory_allowed_is_refused_before_decoding)
{
    uint8_t px[256 * 256 * 4] = { 0 };
    size_t n;
    unsigned char *png = png_bytes(px, 256, 256, &n);
    Texture t;
    char err[256];
    cr_expect_eq(texture_decode(&t, png, n, "big.png", 100000, err, sizeof err), -1);
    cr_expect_str_eq(err, "big.png: a 256x256 image needs about 874 KB; 100 KB available");
    cr_expect_eq(texture_bytes_for(256, 256), 349524, "4/3 of the texels, 4 bytes each, down to 1x1");
    free(png);
}

/* ==== mipmaps and sampling ==== */

/* A w x h texture of level 0 texels from f(x, y) (grey), mipmapped. */
static void make_grey(Texture *t, int w, int h, uint8_t (*f)(int, int))
{
    uint8_t *px = malloc((size_t)w * h * 4);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint8_t g = f(x, y);
            uint8_t *p = px + 4 * ((size_t)y * w + x);
            p[0] = p[1] = p[2] = g;
            p[3] = 255;
        }
    size_t n;
    unsigned char *png = png_bytes(px, w, h, &n);
    char err[256];
    cr_assert_eq(texture_decode(t, png, n, "grey.png", 0, err, sizeof err), 0, "%s", err);
    free(png);
    free(px);
}

static uint8_t checker1(int x, int y) { return (x + y) & 1 ? 255 : 0; }
static uint8_t ramp(int x, int y) { (void)y; return (uint8_t)(x * 64); }

Test(texture, mipmaps_average_in_linear_light)
{
    Texture t;
    make_grey(&t, 64, 64, checker1);
    cr_assert_eq(t.levels, 7);
    /* every texel of level 1 and up is half black, half white: linear
     * 0.5, sRGB 188 (averaging bytes would give 128) */
    for (int k = 1; k < t.levels; k++) {
        const uint8_t *p = t.rgba + 4 * t.off[k];
        cr_expect_eq(p[0], 188, "level %d: %d", k, p[0]);
        cr_expect_eq(p[4 * (t.lw[k] * t.lh[k] - 1)], 188, "level %d's last texel", k);
    }
    texture_free(&t);
}

Test(texture, a_fine_checker_far_away_averages_instead_of_aliasing)
{
    Texture t;
    make_grey(&t, 64, 64, checker1);
    /* a footprint of 8 texels (lod 3): wherever the sample falls the
     * result is the average, 0.5; with no filter it would be 0 or 1 */
    for (int i = 0; i < 50; i++) {
        float u = 0.0137f * i, v = 0.0291f * i, c[3];
        texture_sample(&t, u, v, 3.0f, c);
        cr_expect(fabsf(c[0] - 0.5f) < 0.01f, "at (%g, %g): %g", (double)u, (double)v, (double)c[0]);
        texture_sample(&t, u, v, 2.5f, c);
        cr_expect(fabsf(c[0] - 0.5f) < 0.01f, "lod 2.5 at (%g, %g): %g", (double)u, (double)v, (double)c[0]);
    }
    /* magnified, at a texel's centre: that texel exactly */
    float c[3];
    texture_sample(&t, 3.5f / 64, 0.5f / 64, 0, c);
    cr_expect_eq(c[0], 1.0f);
    texture_sample(&t, 2.5f / 64, 0.5f / 64, -2, c);
    cr_expect_eq(c[0], 0.0f);
    texture_free(&t);
}

Test(texture, bilinear_between_texel_centres_and_the_wrap_modes)
{
    Texture t;
    make_grey(&t, 4, 1, ramp);     /* bytes 0 64 128 192 */
    float c[3], lin[4];
    for (int i = 0; i < 4; i++)
        lin[i] = (float)iec_linear(64 * i);
    /* halfway between the centres of texels 1 and 2 */
    texture_sample(&t, 2.0f / 4, 0.5f, 0, c);
    cr_expect(fabsf(c[0] - 0.5f * (lin[1] + lin[2])) < 1e-6f, "%g", (double)c[0]);
    /* repeat: u + 1 is u; halfway between the last and the first texel */
    texture_sample(&t, 1.25f + 0.125f, 0.5f, 0, c);
    float want[3];
    texture_sample(&t, 0.375f, 0.5f, 0, want);
    cr_expect(fabsf(c[0] - want[0]) < 1e-6f);
    texture_sample(&t, 0.0f, 0.5f, 0, c);
    cr_expect(fabsf(c[0] - 0.5f * (lin[3] + lin[0])) < 1e-6f, "repeat at the seam: %g", (double)c[0]);
    /* clamp: past the edge is the edge texel */
    t.wrap_u = TEX_CLAMP;
    texture_sample(&t, 1.7f, 0.5f, 0, c);
    cr_expect(fabsf(c[0] - lin[3]) < 1e-6f);
    texture_sample(&t, -3.0f, 0.5f, 0, c);
    cr_expect(fabsf(c[0] - lin[0]) < 1e-6f);
    /* mirror: 1 + x reads 1 - x */
    t.wrap_u = TEX_MIRROR;
    texture_sample(&t, 1.0f + 0.375f, 0.5f, 0, c);
    texture_sample(&t, 1.0f - 0.375f, 0.5f, 0, want);
    cr_expect(fabsf(c[0] - want[0]) < 1e-6f, "%g vs %g", (double)c[0], (double)want[0]);
    /* huge and NaN coordinates stay in the image */
    texture_sample(&t, 3e30f, NAN, 0, c);
    cr_expect(c[0] >= 0 && c[0] <= 1);
    texture_free(&t);
}

Test(texture, mipmap_bytes_are_the_encoding_of_the_average_exactly)
{
    /* level 1 of a 2 x 1 image of bytes a and b is linear_to_srgb of the
     * mean of their linear values (the table mip.c encodes with must give
     * the power's very bytes), and within one of the formula's */
    for (int a = 0; a < 256; a += 5)
        for (int b = 0; b < 256; b += 3) {
            uint8_t px[8] = { (uint8_t)a, (uint8_t)a, (uint8_t)a, 255, (uint8_t)b, (uint8_t)b, (uint8_t)b, 255 };
            Texture t;
            char err[128];
            cr_assert_eq(texture_from_rgba(&t, px, 2, 1, "pair", 0, err, sizeof err), 0, "%s", err);
            float la = srgb_to_linear((uint8_t)a), lb = srgb_to_linear((uint8_t)b);
            int got = t.rgba[4 * t.off[1]];
            cr_expect_eq(got, linear_to_srgb(0.25f * (la + lb + la + lb)), "bytes %d and %d", a, b);
            double m = 0.5 * (iec_linear(a) + iec_linear(b));
            double c = m <= 0.0031308 ? m * 12.92 : 1.055 * pow(m, 1 / 2.4) - 0.055;
            cr_expect(abs(got - (int)floor(c * 255 + 0.5)) <= 1, "bytes %d and %d: %d", a, b, got);
            texture_free(&t);
        }
}

/* ==== the shading pass's lookup from 16-bit linear texels ==== */

static uint8_t noise(int x, int y) { return (uint8_t)((x * 73 + y * 151 + ((x * y) ^ 0x5a)) & 255); }

Test(texture, the_16_bit_lookup_is_the_reference_to_8e_6_and_every_simd_level_gives_its_bits)
{
    /* odd sizes (levels 37x23 .. 1x1), coordinates far out, on edges,
     * huge and NaN, every level and wrap mode */
    Texture t;
    make_grey(&t, 37, 23, noise);
    cr_assert_not_null(t.lin);
    const TexWrap modes[3] = { TEX_REPEAT, TEX_CLAMP, TEX_MIRROR };
    uint32_t r = 12345;
    for (int m = 0; m < 9; m++) {
        t.wrap_u = modes[m % 3];
        t.wrap_v = modes[m / 3];
        for (int i = 0; i < 4000; i++) {
            float c[3];
            r = r * 1664525u + 1013904223u;
            float u = (float)((int)(r >> 8) % 40000 - 20000) / 4096.0f;
            r = r * 1664525u + 1013904223u;
            float v = (float)((int)(r >> 8) % 40000 - 20000) / 4096.0f;
            float lod = (float)(i % 80) / 10.0f - 1.0f;
            if (i % 97 == 0)
                u = i % 2 ? 3e30f : NAN;
            if (i % 89 == 0)
                v = (float)(i % 23) / 23.0f;
            float want[3], got[SIMD_LEVELS][3];
            texture_sample(&t, u, v, lod, want);
            for (int lv = SIMD_SCALAR; lv < SIMD_LEVELS; lv++)
                texture_sample_lin(&t, u, v, lod, lv, got[lv]);
            for (int k = 0; k < 3; k++) {
                cr_assert(fabsf(got[SIMD_SCALAR][k] - want[k]) < 8e-6f, "wrap %d at (%g, %g) lod %g: %.9g, reference %.9g",
                          m, (double)u, (double)v, (double)lod, (double)got[SIMD_SCALAR][k], (double)want[k]);
                for (int lv = SIMD_SSE2; lv < SIMD_LEVELS; lv++)
                    cr_assert(!memcmp(&got[lv][k], &got[SIMD_SCALAR][k], sizeof(float)), "level %d, wrap %d at (%g, %g)",
                              lv, m, (double)u, (double)v);
            }
            /* the two-step form gives the same bits */
            TexLod l;
            texture_lod(&t, lod, &l);
            texture_lookup(&l, u, v, SIMD_SSE2, c);
            cr_assert(!memcmp(c, got[SIMD_SSE2], sizeof c));
        }
    }
    texture_free(&t);
}
