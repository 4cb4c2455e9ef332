/* jpeg.c: JPEG images through libjpeg-turbo, reduced by up to 8 by
 * libjpeg itself (scale_denom) and the rest by shrink.c as the rows come.
 *
 * What a JPEG may cost is bounded before it is decoded. A baseline
 * file is read a band of rows at a time, but a progressive one (or one
 * whose colours come in separate scans) is held whole as DCT
 * coefficients, 2 bytes each, at the full size whatever the scale: a
 * 874-byte file declaring 65500 x 65500 asked for 8.6 GB. That array is
 * counted against the budget (texture_check_budget) and libjpeg's own
 * max_memory_to_use is set to what is left, a second fence. And every
 * scan of a progressive file is a pass over the whole image: a 1 MB
 * file of 25,000 copies of one small scan took minutes, so the work of
 * the scans is counted as each starts (a progress monitor) and stopped
 * past JPEG_WORK: a block costs 1 in a first scan, and in a refinement
 * 1 more for every 16 coefficients it refines (libjpeg looks at each
 * one: a refinement of 63 cost 95 ns a block against about 25). A real
 * encoder's 10 scans of a 16k x 16k 4:2:0 image cost about 75 million;
 * so does a baseline file of 75 million blocks (one scan), and a
 * baseline file past JPEG_WORK is refused before it is read. At most
 * JPEG_MAX_SCANS scans whatever their size (each has its cost to set up).
 *
 * CMYK and YCCK files (print workflows) come out as CMYK from libjpeg
 * and are turned into RGB here: with Adobe's APP14 marker the bytes are
 * inverted (255 = no ink), as Photoshop writes them; without it 0 is no
 * ink. */

#include <limits.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
/* jpeglib.h needs FILE and size_t declared first */
#include <jpeglib.h>

#include "texture_internal.h"

/* The work a file may ask for, in blocks of first scans (above):
 * about 4 s on a loaded machine. */
#define JPEG_WORK      ((uint64_t)150 * 1000 * 1000)
#define JPEG_MAX_SCANS 1000

typedef struct {
    struct jpeg_error_mgr      mgr;     /* first: libjpeg's pointer is to it */
    struct jpeg_progress_mgr   prog;
    jmp_buf                    jmp;
    int                        scan;        /* the last scan counted */
    uint64_t                   work;        /* of the scans so far */
    char                       msg[JMSG_LENGTH_MAX + 64];
} JpegErr;

static void jpeg_on_error(j_common_ptr c)
{
    JpegErr *e = (JpegErr *)c->err;
    c->err->format_message(c, e->msg);
    longjmp(e->jmp, 1);
}

/* Warnings (a truncated file, bad data the decoder gets past) are not
 * written to stderr: the image shows what could be read. */
static void jpeg_quiet(j_common_ptr c, int level)
{
    (void)c;
    (void)level;
}

/* The work of the scan that has just begun (its header read). */
static uint64_t scan_work(const struct jpeg_decompress_struct *c)
{
    uint64_t blocks = 0;
    for (int i = 0; i < c->comps_in_scan; i++)
        blocks += (uint64_t)c->cur_comp_info[i]->width_in_blocks * c->cur_comp_info[i]->height_in_blocks;
    return c->Ah ? blocks * (1 + (uint64_t)(c->Se - c->Ss + 1) / 16) : blocks;
}

/* Called before each band of a scan is taken in: a file past the work
 * it may cost stops before the scan that would pass it. */
static void jpeg_on_progress(j_common_ptr cc)
{
    j_decompress_ptr c = (j_decompress_ptr)cc;
    JpegErr *e = (JpegErr *)cc->err;
    if (c->input_scan_number == e->scan)
        return;
    e->scan = c->input_scan_number;
    e->work += scan_work(c);
    if (e->work > JPEG_WORK || e->scan > JPEG_MAX_SCANS) {
        if (e->scan > JPEG_MAX_SCANS)
            snprintf(e->msg, sizeof e->msg, "a %ux%u progressive JPEG of more than %d scans", (unsigned)c->image_width,
                     (unsigned)c->image_height, JPEG_MAX_SCANS);
        else
            snprintf(e->msg, sizeof e->msg,
                     "a %ux%u progressive JPEG whose first %d scans are more work than a texture may take "
                     "(%.0f million block passes)",
                     (unsigned)c->image_width, (unsigned)c->image_height, e->scan, (double)JPEG_WORK / 1e6);
        longjmp(e->jmp, 1);
    }
}

static void jpeg_setup(struct jpeg_decompress_struct *c, JpegErr *e)
{
    c->err = jpeg_std_error(&e->mgr);
    e->mgr.error_exit = jpeg_on_error;
    e->mgr.emit_message = jpeg_quiet;
    e->msg[0] = 0;
    e->scan = 0;
    e->work = 0;
}

int texture_jpeg_peek(const void *data, size_t len, int *w_out, int *h_out)
{
    struct jpeg_decompress_struct c;
    JpegErr e;
    jpeg_setup(&c, &e);
    if (setjmp(e.jmp)) {
        jpeg_destroy_decompress(&c);
        return -1;
    }
    jpeg_create_decompress(&c);
    jpeg_mem_src(&c, data, (unsigned long)len);
    jpeg_read_header(&c, TRUE);
    *w_out = (int)c.image_width;
    *h_out = (int)c.image_height;
    jpeg_destroy_decompress(&c);
    return 0;
}

/* ==== what a decode costs ==== */

static uint64_t round_up(uint64_t n, unsigned k) { return (n + k - 1) / k * k; }

/* The blocks of every component (libjpeg's whole-image coefficient
 * array holds them padded to whole MCUs: jdcoefct.c). */
static uint64_t jpeg_blocks(const struct jpeg_decompress_struct *c)
{
    uint64_t n = 0;
    for (int i = 0; i < c->num_components; i++) {
        const jpeg_component_info *ci = &c->comp_info[i];
        n += round_up(ci->width_in_blocks, (unsigned)ci->h_samp_factor) *
             round_up(ci->height_in_blocks, (unsigned)ci->v_samp_factor);
    }
    return n;
}

/* Whether libjpeg keeps the whole image's coefficients: a progressive
 * file, or one whose first scan has not every component (jdinput.c's
 * has_multiple_scans). */
static int jpeg_multiscan(const struct jpeg_decompress_struct *c)
{
    return c->progressive_mode || c->comps_in_scan < c->num_components;
}

/* ==== CMYK ==== */

static inline uint8_t mul255(unsigned a, unsigned b) { return (uint8_t)((a * b + 127) / 255); }

/* n pixels of C M Y K in place to R G B A (inverted: Adobe's bytes) */
static void cmyk_to_rgba(uint8_t *p, size_t n, int inverted)
{
    for (size_t i = 0; i < n; i++, p += 4) {
        unsigned c = p[0], m = p[1], y = p[2], k = p[3];
        if (!inverted) {
            c = 255 - c;
            m = 255 - m;
            y = 255 - y;
            k = 255 - k;
        }
        /* now 255 - ink: light passes through both the colour and the black */
        p[0] = mul255(c, k);
        p[1] = mul255(m, k);
        p[2] = mul255(y, k);
        p[3] = 255;
    }
}

/* ==== the decode ==== */

int texture_decode_jpeg(Texture *t, const void *data, size_t len, const char *name, uint64_t max_bytes, int halve,
                        char *err, size_t errlen)
{
    struct jpeg_decompress_struct c;
    JpegErr e;
    TexShrink s;
    volatile int started = 0;
    memset(t, 0, sizeof *t);
    jpeg_setup(&c, &e);
    /* t and s are written after setjmp only through their pointers:
     * what they hold when libjpeg gives up is freed below */
    if (setjmp(e.jmp)) {
        if (started)
            texture_shrink_abort(&s);
        jpeg_destroy_decompress(&c);
        memset(t, 0, sizeof *t);
        snprintf(err, errlen, "%s: %s", name, e.msg[0] ? e.msg : "not a JPEG image zview can read");
        return -1;
    }
    jpeg_create_decompress(&c);
    jpeg_mem_src(&c, data, (unsigned long)len);
    jpeg_read_header(&c, TRUE);
    int j = halve < 3 ? halve : 3;          /* libjpeg reduces by 8 at most */
    c.scale_num = 1;
    c.scale_denom = 1u << j;
    jpeg_calc_output_dimensions(&c);
    int ow = (int)c.output_width, oh = (int)c.output_height, kw, kh;
    if (ow < 1 || oh < 1 || ow > TEX_MAX_SIDE || oh > TEX_MAX_SIDE) {
        snprintf(err, errlen, "%s: a %dx%d image (1 to %d per side)", name, ow, oh, TEX_MAX_SIDE);
        jpeg_destroy_decompress(&c);
        return -1;
    }
    texture_kept_size(ow, oh, halve - j, &kw, &kh);
    uint64_t blocks = jpeg_blocks(&c);
    int multi = jpeg_multiscan(&c);
    /* the coefficients (64 of 2 bytes a block), libjpeg's bands of rows
     * at the output size (generous), and the rows shrink.c halves */
    uint64_t working = (multi ? blocks * 128 : 0) + (uint64_t)ow * (uint64_t)c.num_components * 64 +
                       texture_shrink_bytes(ow, oh, halve - j);
    if (texture_check_budget(name, c.progressive_mode ? "progressive JPEG" : "JPEG", (int)c.image_width,
                             (int)c.image_height, kw, kh, working, max_bytes, err, errlen)) {
        jpeg_destroy_decompress(&c);
        return -1;
    }
    uint64_t fence = texture_budget(kw, kh, max_bytes) - (texture_bytes_for(kw, kh) + texture_lin_bytes_for(kw, kh));
    c.mem->max_memory_to_use = fence > LONG_MAX ? LONG_MAX : (long)fence;
    if (multi) {
        e.prog.progress_monitor = jpeg_on_progress;
        c.progress = &e.prog;
    } else if (blocks > JPEG_WORK) {
        snprintf(err, errlen, "%s: a %ux%u JPEG of %.0f million blocks, more work than a texture may take (%.0f million)",
                 name, (unsigned)c.image_width, (unsigned)c.image_height, (double)blocks / 1e6, (double)JPEG_WORK / 1e6);
        jpeg_destroy_decompress(&c);
        return -1;
    }
    int cmyk = c.jpeg_color_space == JCS_CMYK || c.jpeg_color_space == JCS_YCCK;
    /* libjpeg-turbo: grey and RGB to RGBA; CMYK (and YCCK, which it
     * turns into CMYK) is converted below */
    c.out_color_space = cmyk ? JCS_CMYK : JCS_EXT_RGBA;
    jpeg_start_decompress(&c);
    if (texture_shrink_begin(&s, t, ow, oh, halve - j)) {
        jpeg_destroy_decompress(&c);
        snprintf(err, errlen, "%s: out of memory", name);
        return -1;
    }
    started = 1;
    while (c.output_scanline < c.output_height) {
        JSAMPROW row = texture_shrink_row(&s);
        jpeg_read_scanlines(&c, &row, 1);
        if (cmyk)
            cmyk_to_rgba(row, (size_t)ow, c.saw_Adobe_marker);
        texture_shrink_push(&s);
    }
    jpeg_finish_decompress(&c);
    jpeg_destroy_decompress(&c);
    texture_shrink_finish(&s);
    return 0;
}
