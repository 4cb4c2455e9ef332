/* test_texture.c: decoding, mipmaps and filtered sampling of textures,
 * against the sRGB formula, images written by libpng and libjpeg
 * directly, and hand-made patterns whose averages are known. */
#define _DEFAULT_SOURCE

#include <criterion/criterion.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <jpeglib.h>
#include <zlib.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "simd.h"
#include "texture.h"
#include "writers.h"

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
    cr_expect_str_eq(err, "big.png: a 256x256 PNG needs about 878 KB to decode; 100 KB allowed");
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

Test(texture, lookups_of_a_row_of_samples_give_each_samples_bits_at_every_level)
{
    /* texture_lookup_row against texture_lookup sample by sample: runs
     * of every length to 40 (whole groups and padded ones), both wraps
     * the vector paths take and mirror, one level and two, a level of
     * 1 x 1, and groups holding a coordinate too big or NaN */
    Texture t;
    make_grey(&t, 37, 23, noise);
    cr_assert_not_null(t.lin);
    const TexWrap modes[3] = { TEX_REPEAT, TEX_CLAMP, TEX_MIRROR };
    const float lods[5] = { -1.0f, 0.0f, 1.37f, 3.5f, 9.0f };
    uint32_t r = 777;
    float u[40 + TEX_ROW_PAD], v[40 + TEX_ROW_PAD], got[4 * 40], want[3];
    long compared = 0;
    for (int m = 0; m < 9; m++) {
        t.wrap_u = modes[m % 3];
        t.wrap_v = modes[m / 3];
        for (int li = 0; li < 5; li++) {
            TexLod l;
            texture_lod(&t, lods[li], &l);
            for (int n = 0; n <= 40; n++) {
                for (int i = 0; i < n + TEX_ROW_PAD; i++) {
                    r = r * 1664525u + 1013904223u;
                    u[i] = (float)((int)(r >> 8) % 40000 - 20000) / 4096.0f;
                    r = r * 1664525u + 1013904223u;
                    v[i] = (float)((int)(r >> 8) % 40000 - 20000) / 4096.0f;
                }
                if (n % 7 == 3)
                    u[n / 2] = n % 2 ? 3e30f : NAN;
                if (n % 11 == 5)
                    v[n - 1] = -2e6f;
                for (int lv = SIMD_SCALAR; lv < SIMD_LEVELS; lv++) {
                    texture_lookup_row(&l, u, v, n, lv, got);
                    for (int i = 0; i < n; i++, compared++) {
                        texture_lookup(&l, u[i], v[i], SIMD_SCALAR, want);
                        cr_assert(!memcmp(got + 4 * i, want, sizeof want),
                                  "level %d, wrap %d, lod %g, sample %d of %d at (%g, %g): %.9g %.9g %.9g, one at a time "
                                  "%.9g %.9g %.9g",
                                  lv, m, (double)lods[li], i, n, (double)u[i], (double)v[i], (double)got[4 * i],
                                  (double)got[4 * i + 1], (double)got[4 * i + 2], (double)want[0], (double)want[1],
                                  (double)want[2]);
                    }
                }
            }
        }
    }
    cr_assert_gt(compared, 100000);
    texture_free(&t);
}

/* ==== hostile images (issue 28) ==== */

/* The decode of `data` run in a child: its peak resident memory (KB),
 * and its message (or "" when it decoded) in msg. */
static long child_decode(const void *data, size_t len, const char *name, uint64_t max_bytes, int max_side,
                         char *msg, size_t msglen)
{
    int p[2];
    cr_assert_eq(pipe(p), 0);
    pid_t pid = fork();
    cr_assert_geq(pid, 0);
    if (pid == 0) {
        close(p[0]);
        Texture t;
        char err[512] = "";
        alarm(60);          /* a hang guard only: the bound tested is memory */
        if (texture_decode_fit(&t, data, len, name, max_bytes, max_side, NULL, err, sizeof err) == 0)
            err[0] = 0;
        ssize_t w = write(p[1], err, strlen(err) + 1);
        _exit(w > 0 ? 0 : 1);
    }
    close(p[1]);
    size_t got = 0;
    ssize_t r;
    while (got + 1 < msglen && (r = read(p[0], msg + got, msglen - 1 - got)) > 0)
        got += (size_t)r;
    msg[got] = 0;
    close(p[0]);
    int status;
    struct rusage ru;
    cr_assert_eq(wait4(pid, &status, 0, &ru), pid);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the child ended with status %d", status);
    return ru.ru_maxrss;
}

/* What a decode in a child of this process costs at rest (the test
 * binary itself), to measure the decode's own memory against. */
static long child_rest(void)
{
    static const uint8_t px[4] = { 1, 2, 3, 255 };
    size_t n;
    unsigned char *png = png_bytes(px, 1, 1, &n);
    char msg[64];
    long kb = child_decode(png, n, "rest.png", 0, 4096, msg, sizeof msg);
    free(png);
    return kb;
}

Test(texture, a_tiny_progressive_jpeg_declaring_65500_squared_is_refused_before_its_coefficients)
{
    /* 16 x 16 grey, progressive, its frame header saying 65500 x 65500:
     * libjpeg would hold 8.6 GB of coefficients (it took 9.25 GB and 64 s) */
    uint8_t px[16 * 16];
    for (int i = 0; i < 256; i++)
        px[i] = (uint8_t)(i * 37);
    size_t n;
    char *jpg = w_jpeg(px, 16, 16, 1, "grey", 0, 1, &n);
    cr_assert_not_null(jpg);
    cr_assert_eq(w_jpeg_set_size(jpg, n, 65500, 65500), 0);
    cr_expect_lt(n, 1000, "%zu bytes", n);
    char msg[512];
    long rest = child_rest(), kb = child_decode(jpg, n, "huge.jpg", 0, 4096, msg, sizeof msg);
    /* 8188 blocks a side, 128 bytes each, and the kept 4094 x 4094 texture */
    cr_expect(strncmp(msg, "huge.jpg: a 65500x65500 progressive JPEG needs about 8.8 GB to decode; ", 71) == 0, "%s", msg);
    cr_expect(strstr(msg, "the budget for a texture kept at 4094x4094 is ") || strstr(msg, "available"), "%s", msg);
    cr_expect_null(strchr(msg, '\n'));
    cr_expect_lt(kb - rest, 16 << 10, "the refusal took %ld KB more than a decode of nothing", kb - rest);
    /* and under a bound of the caller's, the bound is named */
    child_decode(jpg, n, "huge.jpg", 64 << 20, 4096, msg, sizeof msg);
    cr_expect_str_eq(msg, "huge.jpg: a 65500x65500 progressive JPEG needs about 8.8 GB to decode; 67 MB allowed");
    free(jpg);
}

Test(texture, a_jpeg_of_thousands_of_scans_stops_at_the_work_a_texture_may_take)
{
    /* 256 x 256 grey, progressive, its last scan (a refinement of all
     * 63 coefficients) repeated 20,000 times: each copy a pass over
     * every block */
    uint8_t *px = calloc(256 * 256, 1);
    size_t n, m;
    char *jpg = w_jpeg(px, 256, 256, 1, "grey", 0, 1, &n);
    cr_assert_not_null(jpg);
    Texture t;
    char err[512];
    cr_assert_eq(texture_decode(&t, jpg, n, "ok.jpg", 0, err, sizeof err), 0, "%s", err);
    texture_free(&t);
    char *many = w_jpeg_repeat_last_scan(jpg, n, 20000, &m);
    cr_assert_not_null(many);
    cr_expect_lt(m, 1 << 20, "%zu bytes", m);
    cr_assert_eq(texture_decode(&t, many, m, "scans.jpg", 0, err, sizeof err), -1);
    /* 1,024 blocks a scan at a cost of 4 (1 + 63 / 16): the count of
     * scans stops it first */
    cr_expect_str_eq(err, "scans.jpg: a 256x256 progressive JPEG of more than 1000 scans");
    cr_expect_null(t.rgba);
    free(many);
    /* a bigger image passes the work first: 4096 x 4096 is 262,144
     * blocks; its own 6 scans cost 12 a block (the two refinements of
     * 63 coefficients 4 each), each copy 4: 141 copies pass 150 million */
    free(jpg);
    px = realloc(px, 4096 * 4096);
    memset(px, 0, 4096 * 4096);
    jpg = w_jpeg(px, 4096, 4096, 1, "grey", 0, 1, &n);
    many = w_jpeg_repeat_last_scan(jpg, n, 1000, &m);
    cr_assert_eq(texture_decode(&t, many, m, "big.jpg", 0, err, sizeof err), -1);
    cr_expect_str_eq(err, "big.jpg: a 4096x4096 progressive JPEG whose first 147 scans are more work than a texture "
                          "may take (150 million block passes)");
    free(many);
    free(jpg);
    free(px);
}

Test(texture, a_png_and_a_tga_claiming_a_huge_size_cost_what_their_kept_texture_does)
{
    char msg[512];
    size_t n;
    long rest = child_rest();
    /* 57 bytes saying 100000 x 100000, and 16384 x 16384 */
    char *png = w_png_claiming(100000, 100000, &n);
    child_decode(png, n, "wide.png", 0, 4096, msg, sizeof msg);
    cr_expect_str_eq(msg, "wide.png: a 100000x100000 image (1 to 16384 per side)");
    free(png);
    png = w_png_claiming(16384, 16384, &n);
    long kb = child_decode(png, n, "tall.png", 0, 4096, msg, sizeof msg);
    cr_expect_str_eq(msg, "tall.png: Not enough image data");
    cr_expect_lt(kb - rest, 16 << 10, "%ld KB", kb - rest);
    child_decode(png, n, "tall.png", 64 << 20, 4096, msg, sizeof msg);
    cr_expect_str_eq(msg, "tall.png: a 16384x16384 PNG needs about 224 MB to decode; 67 MB allowed");
    free(png);
    /* a TGA header of 16384 x 16384 and 4 bytes of run-length data: the
     * image decodes (black where the file ends), kept at 4096 x 4096:
     * its 224 MB, not the 1.4 GB of the whole image's chain */
    char *tga = w_tga_rle(16384, 16384, 0, &n);
    kb = child_decode(tga, 18 + 4, "cut.tga", 0, 4096, msg, sizeof msg);
    cr_expect_str_eq(msg, "");
    cr_expect_lt(kb - rest, 300 << 10, "%ld KB", kb - rest);
    child_decode(tga, 18 + 4, "cut.tga", 64 << 20, 4096, msg, sizeof msg);
    cr_expect_str_eq(msg, "cut.tga: a 16384x16384 TGA needs about 224 MB to decode; 67 MB allowed");
    free(tga);
}

/* A chunk of a PNG: length, type, data, CRC. */
static size_t png_chunk(uint8_t *o, const char *type, const uint8_t *d, uint32_t n)
{
    o[0] = (uint8_t)(n >> 24);
    o[1] = (uint8_t)(n >> 16);
    o[2] = (uint8_t)(n >> 8);
    o[3] = (uint8_t)n;
    memcpy(o + 4, type, 4);
    if (n)
        memcpy(o + 8, d, n);
    uint32_t crc = (uint32_t)crc32(crc32(0, o + 4, 4), d, n);
    for (int i = 0; i < 4; i++)
        o[8 + n + i] = (uint8_t)(crc >> (24 - 8 * i));
    return 12 + n;
}

Test(texture, a_png_of_text_chunks_that_inflate_to_a_gigabyte_is_not_read_for_them)
{
    /* a 4 x 4 image after 250 zTXt chunks of 4 KB, each 4 MB of zeros
     * inflated: libpng's reader took 40 s over them (the size was
     * peeked through it); the chunks are skipped unread now */
    static uint8_t zeros[4 << 20];
    uLongf zn = compressBound(sizeof zeros);
    uint8_t *z = malloc(zn + 8);
    memcpy(z, "k\0\0", 3);
    cr_assert_eq(compress2(z + 3, &zn, zeros, sizeof zeros, 9), Z_OK);
    size_t cap = 8 + 25 + 250 * (12 + 3 + zn) + 200, n = 8;
    uint8_t *png = malloc(cap);
    memcpy(png, "\x89PNG\r\n\x1a\n", 8);
    const uint8_t ihdr[13] = { 0, 0, 0, 4, 0, 0, 0, 4, 8, 2, 0, 0, 0 };
    n += png_chunk(png + n, "IHDR", ihdr, 13);
    for (int i = 0; i < 250; i++)
        n += png_chunk(png + n, "zTXt", z, (uint32_t)(3 + zn));
    uint8_t raw[4 * 13] = { 0 }, idat[128];
    uLongf in = sizeof idat;
    cr_assert_eq(compress(idat, &in, raw, sizeof raw), Z_OK);
    n += png_chunk(png + n, "IDAT", idat, (uint32_t)in);
    n += png_chunk(png + n, "IEND", NULL, 0);
    cr_expect_lt(n, 1100000, "%zu bytes", n);
    int w, h;
    cr_expect_eq(texture_peek(png, n, &w, &h), 0);
    cr_expect(w == 4 && h == 4);
    /* in a child: its CPU time (the guard is generous; the bomb took 40 s) */
    pid_t pid = fork();
    cr_assert_geq(pid, 0);
    if (pid == 0) {
        Texture t;
        char err[256];
        alarm(120);
        _exit(texture_decode_fit(&t, png, n, "text.png", 0, 4096, NULL, err, sizeof err) == 0 ? 0 : 1);
    }
    int status;
    struct rusage ru;
    cr_assert_eq(wait4(pid, &status, 0, &ru), pid);
    cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 0, "status %d", status);
    double cpu = (double)ru.ru_utime.tv_sec + (double)ru.ru_utime.tv_usec / 1e6;
    cr_expect_lt(cpu, 5.0, "%.1f s of CPU", cpu);
    free(png);
    free(z);
}

/* ==== CMYK and YCCK JPEGs ==== */

Test(texture, cmyk_and_ycck_jpegs_come_out_as_rgb)
{
    /* 16 x 16 blocks of inks (C M Y K, 255 = full) and the light they leave */
    static const uint8_t ink[6][4] = { { 255, 0, 0, 0 }, { 0, 255, 0, 0 }, { 0, 0, 255, 0 },
                                       { 0, 0, 0, 255 }, { 0, 0, 0, 0 }, { 0, 255, 255, 0 } };
    static const uint8_t rgb[6][3] = { { 0, 255, 255 }, { 255, 0, 255 }, { 255, 255, 0 },
                                       { 0, 0, 0 }, { 255, 255, 255 }, { 255, 0, 0 } };
    enum { W = 96, H = 16 };
    uint8_t px[W * H * 4];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            memcpy(px + 4 * (y * W + x), ink[x / 16], 4);
    static const struct {
        const char *colour;
        int adobe;
    } kinds[] = { { "cmyk", 1 }, { "cmyk", 0 }, { "ycck", 1 } };
    for (int k = 0; k < 3; k++) {
        size_t n;
        char *jpg = w_jpeg(px, W, H, 4, kinds[k].colour, kinds[k].adobe, k == 2, &n);
        cr_assert_not_null(jpg);
        Texture t;
        char err[256];
        cr_assert_eq(texture_decode(&t, jpg, n, "ink.jpg", 0, err, sizeof err), 0, "%s %s: %s", kinds[k].colour,
                     kinds[k].adobe ? "Adobe" : "plain", err);
        for (int b = 0; b < 6; b++) {
            const uint8_t *p = t.rgba + 4 * (8 * W + 16 * b + 8);
            for (int c = 0; c < 3; c++)
                cr_expect(abs(p[c] - rgb[b][c]) <= 3, "%s (%s) block %d channel %d: %d, want %d", kinds[k].colour,
                          kinds[k].adobe ? "Adobe" : "plain", b, c, p[c], rgb[b][c]);
            cr_expect_eq(p[3], 255);
        }
        texture_free(&t);
        free(jpg);
    }
}

/* ==== rows halved as they arrive ==== */

/* A PNG by libpng's own writer: any colour type, depth, interlace and gamma. */
static unsigned char *png_ll(int w, int h, int type, int depth, int interlace, double gamma, int trns, size_t *len)
{
    png_structp p = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(p);
    FILE *f;
    char *buf = NULL;
    f = open_memstream(&buf, len);
    png_init_io(p, f);
    png_set_IHDR(p, info, (png_uint_32)w, (png_uint_32)h, depth, type, interlace, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (type == PNG_COLOR_TYPE_PALETTE) {
        png_color pal[16];
        png_byte alpha[16];
        for (int i = 0; i < 16; i++) {
            pal[i].red = (png_byte)(i * 17);
            pal[i].green = (png_byte)(255 - i * 13);
            pal[i].blue = (png_byte)(i * i);
            alpha[i] = (png_byte)(255 - i * 9);
        }
        png_set_PLTE(p, info, pal, 16);
        if (trns)
            png_set_tRNS(p, info, alpha, 16, NULL);
    } else if (trns && !(type & PNG_COLOR_MASK_ALPHA)) {
        png_color_16 c = { 0, 7, 7, 7, 7 };
        png_set_tRNS(p, info, NULL, 0, &c);
    }
    if (gamma > 0)
        png_set_gAMA(p, info, gamma);
    png_write_info(p, info);
    int ch = png_get_channels(p, info);
    size_t rowbytes = png_get_rowbytes(p, info);
    uint8_t *row = malloc(rowbytes);
    int passes = png_set_interlace_handling(p);
    for (int pass = 0; pass < passes; pass++)
        for (int y = 0; y < h; y++) {
            /* samples of the row's bytes, any depth: a pattern of x, y and the channel */
            for (size_t i = 0; i < rowbytes; i++)
                row[i] = (uint8_t)((i * 29 + (size_t)y * 113 + (i * (size_t)y) / 7) ^ (size_t)ch);
            if (type == PNG_COLOR_TYPE_PALETTE)
                for (size_t i = 0; i < rowbytes; i++)
                    row[i] &= depth == 8 ? 15 : 0xff;
            png_write_row(p, row);
        }
    png_write_end(p, info);
    png_destroy_write_struct(&p, &info);
    fclose(f);
    free(row);
    return (unsigned char *)buf;
}

Test(texture, png_rows_give_the_bytes_of_libpngs_simplified_reader)
{
    /* the simplified API (png_image_finish_read, RGBA) is the reference:
     * zview read with it before reading a row at a time. Of the same
     * pixels written without interlacing: libpng 1.6.39's simplified
     * reader gets 16-bit interlaced images wrong (the sRGB bytes of the
     * first pixel 210 240 90 for linear 29 14935 29841, where the same
     * image not interlaced gives 0 130 178, as the formula does) */
    static const struct {
        int type, depth, interlace, trns;
        double gamma;
    } kinds[] = {
        { PNG_COLOR_TYPE_RGB, 8, 0, 0, 0 },          { PNG_COLOR_TYPE_RGB_ALPHA, 8, 0, 0, 0 },
        { PNG_COLOR_TYPE_GRAY, 8, 0, 0, 0 },         { PNG_COLOR_TYPE_GRAY_ALPHA, 8, 0, 0, 0 },
        { PNG_COLOR_TYPE_GRAY, 1, 0, 0, 0 },         { PNG_COLOR_TYPE_GRAY, 4, 1, 1, 0 },
        { PNG_COLOR_TYPE_PALETTE, 8, 0, 1, 0 },      { PNG_COLOR_TYPE_PALETTE, 4, 1, 0, 0 },
        { PNG_COLOR_TYPE_RGB, 16, 0, 0, 0 },         { PNG_COLOR_TYPE_RGB_ALPHA, 16, 0, 0, 0 },
        { PNG_COLOR_TYPE_RGB, 16, 0, 0, 1 / 2.2 },   { PNG_COLOR_TYPE_RGB, 8, 0, 1, 1 / 1.8 },
        { PNG_COLOR_TYPE_RGB_ALPHA, 8, 1, 0, 1 / 2.2 }, { PNG_COLOR_TYPE_GRAY_ALPHA, 16, 0, 0, 0 },
        { PNG_COLOR_TYPE_RGB, 16, 1, 0, 0 }, { PNG_COLOR_TYPE_GRAY_ALPHA, 16, 1, 0, 0 },
    };
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        int w = 37, h = 23;
        size_t n;
        unsigned char *png = png_ll(w, h, kinds[k].type, kinds[k].depth, kinds[k].interlace, kinds[k].gamma,
                                    kinds[k].trns, &n);
        size_t rn;
        unsigned char *ref = png_ll(w, h, kinds[k].type, kinds[k].depth, 0, kinds[k].gamma, kinds[k].trns, &rn);
        png_image img;
        memset(&img, 0, sizeof img);
        img.version = PNG_IMAGE_VERSION;
        cr_assert(png_image_begin_read_from_memory(&img, ref, rn), "kind %zu: %s", k, img.message);
        img.format = PNG_FORMAT_RGBA;
        uint8_t *want = malloc(PNG_IMAGE_SIZE(img));
        cr_assert(png_image_finish_read(&img, NULL, want, 0, NULL), "kind %zu: %s", k, img.message);
        Texture t;
        char err[256];
        cr_assert_eq(texture_decode(&t, png, n, "kind.png", 0, err, sizeof err), 0, "kind %zu: %s", k, err);
        cr_assert_eq(t.w, w);
        cr_assert_eq(t.h, h);
        for (int i = 0; i < w * h * 4; i++)
            cr_assert_eq(t.rgba[i], want[i], "kind %zu (type %d, %d bits%s): byte %d: %d, libpng %d", k,
                         kinds[k].type, kinds[k].depth, kinds[k].interlace ? ", interlaced" : "", i, t.rgba[i],
                         want[i]);
        texture_free(&t);
        free(want);
        free(png);
        free(ref);
    }
}

/* The levels of `a` from level k on are those of `b`. */
static void expect_same_levels(const Texture *a, int k, const Texture *b, const char *what)
{
    cr_assert_eq(a->levels - k, b->levels, "%s: %d levels less %d, %d", what, a->levels, k, b->levels);
    for (int i = 0; i < b->levels; i++) {
        cr_assert_eq(a->lw[k + i], b->lw[i], "%s level %d", what, i);
        cr_assert_eq(a->lh[k + i], b->lh[i], "%s level %d", what, i);
        cr_assert(!memcmp(a->rgba + 4 * a->off[k + i], b->rgba + 4 * b->off[i], 4 * (size_t)b->lw[i] * b->lh[i]),
                  "%s: level %d differs from the whole chain's", what, i);
    }
}

static char *tga_bytes(const uint8_t *rgba, int w, int h, int top, int rle, size_t *len)
{
    /* 32-bit BGRA; run-length packets of up to 128 equal pixels, across rows */
    size_t npx = (size_t)w * h, o = 18;
    uint8_t *b = malloc(18 + npx * 5);
    memset(b, 0, 18);
    b[2] = rle ? 10 : 2;
    b[12] = (uint8_t)w;
    b[13] = (uint8_t)(w >> 8);
    b[14] = (uint8_t)h;
    b[15] = (uint8_t)(h >> 8);
    b[16] = 32;
    b[17] = top ? 0x20 : 0;
    for (size_t i = 0; i < npx;) {
        size_t y = i / (size_t)w, x = i % (size_t)w, fy = top ? y : (size_t)h - 1 - y;
        const uint8_t *p = rgba + 4 * (fy * (size_t)w + x);
        size_t run = 1;
        if (rle) {
            while (run < 128 && i + run < npx) {
                size_t j = i + run, qy = j / (size_t)w, qfy = top ? qy : (size_t)h - 1 - qy;
                if (memcmp(rgba + 4 * (qfy * (size_t)w + j % (size_t)w), p, 4))
                    break;
                run++;
            }
            b[o++] = (uint8_t)(0x80 | (run - 1));
        }
        b[o++] = p[2];
        b[o++] = p[1];
        b[o++] = p[0];
        b[o++] = p[3];
        i += run;
    }
    *len = o;
    return (char *)b;
}

Test(texture, an_image_halved_as_it_is_read_has_the_bytes_of_the_whole_chain)
{
    /* odd sizes (the last odd row and column), a side of 1, each kind */
    static const int sizes[][2] = { { 75, 43 }, { 64, 64 }, { 130, 3 }, { 1, 90 }, { 33, 1 } };
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        int w = sizes[s][0], h = sizes[s][1];
        uint8_t *px = malloc((size_t)w * h * 4);
        for (int i = 0; i < w * h; i++) {
            /* runs of equal pixels for the TGA's packets, noise elsewhere */
            int q = i % 7 < 3 ? i / 7 : i;
            px[4 * i] = (uint8_t)(q * 53);
            px[4 * i + 1] = (uint8_t)(q * 91 + 7);
            px[4 * i + 2] = (uint8_t)(q * q);
            px[4 * i + 3] = (uint8_t)(255 - q % 64);
        }
        char what[64];
        for (int kind = 0; kind < 7; kind++) {
            size_t n;
            char *img = kind == 0 ? (char *)png_bytes(px, w, h, &n)
                                  : tga_bytes(px, w, h, kind & 1, kind >= 3, &n);
            /* 5, 6: RLE TGAs cut at 40%: the rows past the end are black */
            if (kind >= 5)
                n = 18 + (n - 18) * 2 / 5;
            for (int side = 1; side <= 64; side *= 4) {
                Texture whole, fit;
                char err[256];
                int halved = -1;
                snprintf(what, sizeof what, "%dx%d %s to %d", w, h,
                         (const char *[]){ "PNG", "TGA top", "TGA bottom", "RLE TGA top", "RLE TGA bottom",
                                           "cut RLE TGA top", "cut RLE TGA bottom" }[kind], side);
                cr_assert_eq(texture_decode(&whole, img, n, "a", 0, err, sizeof err), 0, "%s: %s", what, err);
                if (kind < 5)
                    cr_assert(!memcmp(whole.rgba, px, (size_t)w * h * 4), "%s: level 0 is not the image", what);
                cr_assert_eq(texture_decode_fit(&fit, img, n, "a", 0, side, &halved, err, sizeof err), 0, "%s: %s",
                             what, err);
                cr_expect(fit.w <= side && fit.h <= side, "%s: %dx%d", what, fit.w, fit.h);
                expect_same_levels(&whole, halved, &fit, what);
                texture_free(&whole);
                texture_free(&fit);
            }
            free(img);
        }
        free(px);
    }
}

Test(texture, a_4_megapixel_png_kept_at_128_is_never_whole_in_memory)
{
    /* 2048 x 2048: its chain would be 22 MB and the 16-bit copy 34 */
    enum { S = 2048 };
    uint8_t *px = malloc((size_t)S * S * 4);
    for (size_t i = 0; i < (size_t)S * S * 4; i++)
        px[i] = (uint8_t)(i * 2654435761u >> 24);
    size_t n;
    unsigned char *png = png_bytes(px, S, S, &n);
    free(px);
    char msg[256];
    long rest = child_rest(), kb = child_decode(png, n, "big.png", 0, 128, msg, sizeof msg);
    cr_expect_str_eq(msg, "");
    /* the file's bytes are the parent's (read, not copied); 32 KB of
     * rows a level and 0.2 MB of kept texels */
    cr_expect_lt(kb - rest, 8 << 10, "%ld KB more than a decode of nothing", kb - rest);
    free(png);
}

Test(texture, an_interlaced_png_counts_its_whole_image_and_a_plain_one_its_rows)
{
    /* 1024 x 1024 kept at 64: read a row at a time it needs 0.1 MB; an
     * interlaced one is whole before its rows are known (4 MB) */
    size_t n, ni;
    unsigned char *plain = png_ll(1024, 1024, PNG_COLOR_TYPE_GRAY, 8, 0, 0, 0, &n);
    unsigned char *inter = png_ll(1024, 1024, PNG_COLOR_TYPE_GRAY, 8, 1, 0, 0, &ni);
    Texture t;
    char err[256];
    cr_expect_eq(texture_decode_fit(&t, plain, n, "plain.png", 1 << 20, 64, NULL, err, sizeof err), 0, "%s", err);
    texture_free(&t);
    cr_expect_eq(texture_decode_fit(&t, inter, ni, "inter.png", 1 << 20, 64, NULL, err, sizeof err), -1);
    cr_expect_str_eq(err, "inter.png: a 1024x1024 interlaced PNG needs about 4 MB to decode; 1 MB allowed");
    cr_expect_eq(texture_decode_fit(&t, inter, ni, "inter.png", 8 << 20, 64, NULL, err, sizeof err), 0, "%s", err);
    texture_free(&t);
    free(plain);
    free(inter);
}

Test(texture, every_average_of_two_bytes_encodes_as_linear_to_srgb_does)
{
    /* level 1 of a 512 x 512 image whose columns 2x, 2x + 1 hold bytes
     * x and y: all 65,536 pairs (the encoder's buckets start each search
     * near its answer; this is every answer a pair can have) */
    enum { S = 512 };
    uint8_t *px = malloc((size_t)S * S * 4);
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            uint8_t v = (uint8_t)(x & 1 ? y / 2 : x / 2);
            uint8_t *p = px + 4 * ((size_t)y * S + x);
            p[0] = p[1] = p[2] = v;
            p[3] = 255;
        }
    Texture t;
    char err[128];
    cr_assert_eq(texture_from_rgba(&t, px, S, S, "pairs", 0, err, sizeof err), 0, "%s", err);
    for (int b = 0; b < 256; b++)
        for (int a = 0; a < 256; a++) {
            int got = t.rgba[4 * (t.off[1] + (size_t)b * 256 + a)];
            float m = 0.25f * (srgb_to_linear((uint8_t)a) + srgb_to_linear((uint8_t)b) + srgb_to_linear((uint8_t)a) +
                               srgb_to_linear((uint8_t)b));
            cr_assert_eq(got, linear_to_srgb(m), "bytes %d and %d", a, b);
        }
    texture_free(&t);
    free(px);
}
