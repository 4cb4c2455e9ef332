/* fuzz_tex.c: the image decoders textures go through: PNG (libpng) and
 * JPEG (libjpeg-turbo) through our error handling, and TGA, parsed here
 * (tga.c). The first byte picks the call:
 *
 *   bit 0      texture_decode_fit with a side of at most 64 (JPEG's
 *              reduced scale, PNG's dropped levels), else texture_decode
 *   bits 1-2   the memory bound: 16 MB, 1 MB, 64 KB, 1 KB (a hundred
 *              bytes of run-length TGA make a picture of millions of
 *              texels, which is right, and takes 20 s under the
 *              sanitizers: the fuzzer's time goes to smaller ones)
 *
 * and the rest is the image. A success must hold a consistent pyramid
 * (levels halving down to 1x1, offsets in order, the bytes counted) and
 * sample without reading outside it at any coordinate and level; a
 * failure must name the input and leave the texture empty. texture_peek
 * must agree with the decode on the size where both succeed. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "simd.h"
#include "texture.h"

#define CHECK(cond)                                                                 \
    do {                                                                            \
        if (!(cond)) {                                                              \
            fprintf(stderr, "fuzz_tex: %s:%d: %s\n", __FILE__, __LINE__, #cond);    \
            abort();                                                                \
        }                                                                           \
    } while (0)

static void check_pyramid(const Texture *t)
{
    CHECK(t->w > 0 && t->h > 0 && t->rgba);
    CHECK(t->levels >= 1 && t->levels <= TEX_MAX_LEVELS);
    CHECK(t->lw[0] == t->w && t->lh[0] == t->h && t->off[0] == 0);
    size_t end = 0;
    for (int k = 0; k < t->levels; k++) {
        CHECK(t->lw[k] >= 1 && t->lh[k] >= 1);
        if (k) {
            CHECK(t->lw[k] == (t->lw[k - 1] > 1 ? t->lw[k - 1] / 2 : 1));
            CHECK(t->lh[k] == (t->lh[k - 1] > 1 ? t->lh[k - 1] / 2 : 1));
        }
        CHECK(t->off[k] == end);
        end += (size_t)t->lw[k] * t->lh[k];
    }
    CHECK(t->lw[t->levels - 1] == 1 && t->lh[t->levels - 1] == 1);
    CHECK(texture_bytes_for(t->w, t->h) == 4 * end);
    CHECK(texture_bytes(t) >= 4 * end);     /* and the 16-bit linear copy, when there is one */
    /* the last texel of the last level is readable (ASan says if not) */
    volatile uint8_t last = t->rgba[4 * end - 1];
    (void)last;
}

static void sample_all_over(const Texture *t, const uint8_t *data, size_t size)
{
    static const float where[] = { 0, 0.5f, 1, -1, 2.75f, -3.25f, 1e7f, -1e7f, 0.999999f, 1e-9f };
    int nw = (int)(sizeof where / sizeof where[0]);
    for (int i = 0; i < nw; i++)
        for (int j = 0; j < nw; j++) {
            float lod = (float)((i * 7 + j) % 20) - 2.5f + (size ? data[(i + j) % size] / 64.0f : 0);
            float c[3];
            texture_sample(t, where[i], where[j], lod, c);
            for (int k = 0; k < 3; k++)
                CHECK(c[k] >= 0 && c[k] <= 1.0001f);
        }
    float c[3];
    texture_sample(t, NAN, INFINITY, NAN, c);
    texture_sample(t, 0.5f, 0.5f, INFINITY, c);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    static const uint64_t bounds[] = { 16 << 20, 1 << 20, 64 << 10, 1 << 10 };
    int fit = data[0] & 1;
    uint64_t bound = bounds[(data[0] >> 1) & 3];
    const uint8_t *img = data + 1;
    size_t len = size - 1;
    Texture t;
    memset(&t, 0xab, sizeof t);
    char err[512] = "";
    int halved = -1;
    int rc = fit ? texture_decode_fit(&t, img, len, "fuzz.img", bound, 64, &halved, err, sizeof err)
                 : texture_decode(&t, img, len, "fuzz.img", bound, err, sizeof err);
    if (rc) {
        CHECK(rc == -1);
        CHECK(strstr(err, "fuzz.img") != NULL);
        CHECK(t.rgba == NULL);
        return 0;
    }
    check_pyramid(&t);
    if (bound)
        CHECK(texture_bytes(&t) <= bound);
    if (fit) {
        CHECK(t.w <= 64 && t.h <= 64);
        CHECK(halved >= 0);
    }
    int pw, ph;
    if (!fit && texture_peek(img, len, &pw, &ph) == 0)
        CHECK(pw == t.w && ph == t.h);
    sample_all_over(&t, data, size);
    /* the shading pass's lookup from the 16-bit copy, at every SIMD level */
    for (int simd = 0; simd <= (int)simd_level(); simd++) {
        float c[3];
        texture_sample_lin(&t, NAN, INFINITY, 3.5f, simd, c);
        texture_sample_lin(&t, 1e7f, -0.25f, NAN, simd, c);
        texture_sample_lin(&t, 0.3f, 0.7f, INFINITY, simd, c);
        for (int k = 0; k < 3; k++)
            CHECK(c[k] >= 0 && c[k] <= 1.0001f);
    }
    for (TexWrap m = TEX_REPEAT; m <= TEX_MIRROR; m++) {
        t.wrap_u = m;
        t.wrap_v = (TexWrap)((m + 1) % 3);
        sample_all_over(&t, data, size);
    }
    texture_free(&t);
    return 0;
}
