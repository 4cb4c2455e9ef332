/* Pixels for terminals that draw them: each protocol's stream is read
 * back by a decoder written here (sixel's bands and registers, kitty's
 * chunks, iTerm2's string; base64 by its RFC's vectors) and compared
 * with the image it came from, which for a rendered view is the -o PNG
 * of the same view read back through libpng. */

#define _GNU_SOURCE
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "pixels.h"
#include "present.h"
#include "scene.h"
#include "testlib.h"
#include "texture.h"
#include "tty.h"

/* ==== base64 ==== */

Test(pixels, base64_matches_the_rfc_vectors)
{
    static const char *in[] = { "", "f", "fo", "foo", "foob", "fooba", "foobar" };
    static const char *want[] = { "", "Zg==", "Zm8=", "Zm9v", "Zm9vYg==", "Zm9vYmE=", "Zm9vYmFy" };
    for (int i = 0; i < 7; i++) {
        ByteBuf b = { 0 };
        base64_put(&b, (const uint8_t *)in[i], strlen(in[i]));
        cr_expect_eq(b.len, strlen(want[i]), "'%s'", in[i]);
        cr_expect(b.len == 0 || !memcmp(b.b, want[i], b.len), "'%s': %.*s", in[i], (int)b.len, (const char *)b.b);
        bytebuf_free(&b);
    }
}

static int b64_value(int c)
{
    return c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26 : c >= '0' && c <= '9' ? c - '0' + 52
         : c == '+' ? 62 : c == '/' ? 63 : -1;
}

/* Decode base64 (the test's own decoder); returns the length, -1 bad. */
static long b64_decode(const char *s, size_t n, uint8_t *out)
{
    long len = 0;
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '=')
            break;
        int v = b64_value((unsigned char)s[i]);
        if (v < 0)
            return -1;
        acc = acc << 6 | (uint32_t)v;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out[len++] = (uint8_t)(acc >> bits);
        }
    }
    return len;
}

/* ==== Test images ==== */

static Image gradient(int w, int h)
{
    Image im = { .w = w, .h = h, .rgb = malloc(3 * (size_t)w * h), .cap = (size_t)w * h };   /* as image_resize sets it */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint8_t *p = im.rgb + 3 * ((size_t)y * w + x);
            p[0] = (uint8_t)(x * 255 / (w - 1));
            p[1] = (uint8_t)(y * 255 / (h - 1));
            p[2] = (uint8_t)((x * 7 + y * 13) & 255);
        }
    return im;
}

/* PNG bytes -> the image (through libpng, as the texture loader reads
 * them); its level 0 as RGB. */
static Image png_read_back(const uint8_t *png, size_t len)
{
    Texture t;
    char err[256];
    cr_assert_eq(texture_decode(&t, png, len, "stream", 0, err, sizeof err), 0, "%s", err);
    Image im = { .w = t.w, .h = t.h, .rgb = malloc(3 * (size_t)t.w * t.h), .cap = (size_t)t.w * t.h };
    for (size_t i = 0; i < (size_t)t.w * t.h; i++)
        memcpy(im.rgb + 3 * i, t.rgba + 4 * i, 3);
    texture_free(&t);
    return im;
}

static void expect_same(const Image *a, const Image *b, const char *what)
{
    cr_assert_eq(a->w, b->w, "%s: width", what);
    cr_assert_eq(a->h, b->h, "%s: height", what);
    cr_expect(!memcmp(a->rgb, b->rgb, 3 * (size_t)a->w * a->h), "%s: the pixels differ", what);
}

/* ==== kitty ==== */

/* The kitty stream's chunks joined and decoded: checks each chunk's
 * framing, the keys of the first, the m= flags and the chunk size. */
static Image kitty_read_back(const ByteBuf *s, uint32_t id)
{
    const char *p = (const char *)s->b, *end = p + s->len;
    char *b64 = malloc(s->len);
    size_t n = 0;
    int chunks = 0, more = 1;
    while (p < end && more) {
        cr_assert(end - p > 3 && !memcmp(p, "\033_G", 3), "chunk %d does not start with ESC _ G", chunks);
        const char *semi = memchr(p, ';', (size_t)(end - p));
        cr_assert_not_null(semi);
        char keys[128];
        snprintf(keys, sizeof keys, "%.*s", (int)(semi - p - 3), p + 3);
        if (chunks == 0) {
            cr_expect_not_null(strstr(keys, "a=T"), "%s", keys);
            cr_expect_not_null(strstr(keys, "f=100"), "%s", keys);
            char want[32];
            snprintf(want, sizeof want, "i=%u", id);
            cr_expect_eq(strstr(keys, "i=") != NULL, id != 0, "%s", keys);
            if (id) {
                cr_expect_not_null(strstr(keys, want), "%s", keys);
                cr_expect(id != 7 || strstr(keys, "c=30,r=10"), "scaled to its cells: %s", keys);
            }
        }
        const char *stop = strstr(semi, "\033\\");
        cr_assert_not_null(stop);
        cr_expect_leq(stop - semi - 1, 4096, "a chunk of %ld bytes", (long)(stop - semi - 1));
        more = strstr(keys, "m=1") != NULL;
        memcpy(b64 + n, semi + 1, (size_t)(stop - semi - 1));
        n += (size_t)(stop - semi - 1);
        p = stop + 2;
        chunks++;
    }
    cr_expect_eq(p, end, "bytes after the last chunk (m=0)");
    uint8_t *png = malloc(n);
    long len = b64_decode(b64, n, png);
    cr_assert_gt(len, 0);
    Image im = png_read_back(png, (size_t)len);
    free(png);
    free(b64);
    return im;
}

Test(pixels, kitty_stream_reads_back_as_the_image)
{
    for (int k = 0; k < 2; k++) {
        Image im = gradient(k ? 301 : 9, k ? 177 : 5);   /* one chunk, and many */
        ByteBuf s = { 0 };
        cr_assert_eq(pixels_encode(PIX_KITTY, &im, k ? 7 : 0, k ? 30 : 0, k ? 10 : 0, &s), 0);
        Image back = kitty_read_back(&s, k ? 7 : 0);
        expect_same(&im, &back, "kitty");
        free(back.rgb);
        free(im.rgb);
        bytebuf_free(&s);
    }
}

/* ==== iTerm2 ==== */

static Image iterm_read_back(const ByteBuf *s)
{
    const char *p = (const char *)s->b;
    cr_assert(s->len > 20 && !memcmp(p, "\033]1337;File=", 12), "not an OSC 1337 File string");
    cr_assert_eq(p[s->len - 1], '\a', "not ended by BEL");
    const char *colon = memchr(p, ':', s->len);
    cr_assert_not_null(colon);
    char args[256];
    snprintf(args, sizeof args, "%.*s", (int)(colon - p), p);
    cr_expect_not_null(strstr(args, "inline=1"), "%s", args);
    const char *sz = strstr(args, "size=");
    cr_assert_not_null(sz);
    size_t n = (size_t)(p + s->len - 1 - (colon + 1));
    uint8_t *png = malloc(n);
    long len = b64_decode(colon + 1, n, png);
    cr_expect_eq(len, atol(sz + 5), "size= says %ld, the data has %ld bytes", atol(sz + 5), len);
    Image im = png_read_back(png, (size_t)len);
    free(png);
    return im;
}

Test(pixels, iterm_stream_reads_back_as_the_image)
{
    Image im = gradient(64, 40);
    ByteBuf s = { 0 };
    cr_assert_eq(pixels_encode(PIX_ITERM, &im, 0, 0, 0, &s), 0);
    Image back = iterm_read_back(&s);
    expect_same(&im, &back, "iterm");
    free(back.rgb);
    free(im.rgb);
    bytebuf_free(&s);
}

/* ==== sixel ==== */

/* A sixel decoder: the DCS string's raster attributes size the image,
 * '#n;2;r;g;b' defines register n in percent, '#n' selects it, '?'..'~'
 * set up to six pixels downward, '!k' repeats, '$' returns to the
 * band's start, '-' goes to the next band. Pixels never set stay
 * (255, 0, 255) so that a gap shows. */
static Image sixel_read_back(const ByteBuf *s)
{
    const char *p = (const char *)s->b, *end = p + s->len;
    cr_assert(s->len > 4 && p[0] == '\033' && p[1] == 'P', "not a DCS string");
    p = memchr(p, 'q', s->len);
    cr_assert_not_null(p);
    p++;
    int w = 0, h = 0;
    cr_assert_eq(sscanf(p, "\"1;1;%d;%d", &w, &h), 2, "no raster attributes");
    Image im = { .w = w, .h = h, .rgb = malloc(3 * (size_t)w * h), .cap = (size_t)w * h };   /* as image_resize sets it */
    for (size_t i = 0; i < (size_t)w * h; i++)
        memcpy(im.rgb + 3 * i, (uint8_t[3]){ 255, 0, 255 }, 3);
    uint8_t reg[256][3] = { { 0 } };
    int cur = 0, x = 0, y = 0;
    p++;
    while (p < end && *p != '"' && !(*p >= '?' && *p <= '~') && *p != '#')
        p++;
    while (p < end) {
        char c = *p;
        if (c == '\033')
            break;
        if (c == '#') {
            int n = 0, m = 0, r = 0, g = 0, b = 0, used = 0;
            if (sscanf(p + 1, "%d;%d;%d;%d;%d%n", &n, &m, &r, &g, &b, &used) == 5 && m == 2) {
                reg[n & 255][0] = (uint8_t)((r * 255 + 50) / 100);
                reg[n & 255][1] = (uint8_t)((g * 255 + 50) / 100);
                reg[n & 255][2] = (uint8_t)((b * 255 + 50) / 100);
                p += 1 + used;
            } else {
                cr_assert_eq(sscanf(p + 1, "%d%n", &n, &used), 1);
                cur = n & 255;
                p += 1 + used;
            }
            continue;
        }
        int rep = 1;
        if (c == '!') {
            int used = 0;
            cr_assert_eq(sscanf(p + 1, "%d%n", &rep, &used), 1);
            p += 1 + used;
            c = *p;
        }
        if (c == '$') {
            x = 0;
        } else if (c == '-') {
            x = 0;
            y += 6;
        } else if (c >= '?' && c <= '~') {
            int bits = c - '?';
            for (int r = 0; r < rep; r++, x++)
                for (int k = 0; k < 6; k++)
                    if (bits >> k & 1) {
                        cr_assert(x < w && y + k < h, "a pixel outside the raster at %d,%d", x, y + k);
                        memcpy(im.rgb + 3 * ((size_t)(y + k) * w + x), reg[cur], 3);
                    }
        } else {
            cr_assert_fail("unexpected byte %d in the sixel data", c);
        }
        p++;
    }
    cr_expect(p + 2 <= end && p[0] == '\033' && p[1] == '\\', "not ended by ST");
    return im;
}

Test(pixels, sixel_stream_reads_back_as_the_quantized_image)
{
    for (int k = 0; k < 2; k++) {
        Image im = gradient(k ? 97 : 13, k ? 53 : 6);       /* a last band of 5 rows, and one whole band */
        ByteBuf s = { 0 };
        cr_assert_eq(pixels_encode(PIX_SIXEL, &im, 0, 0, 0, &s), 0);
        Image back = sixel_read_back(&s);
        cr_assert_eq(back.w, im.w);
        cr_assert_eq(back.h, im.h);
        /* every pixel is the 256-colour text's choice for it (the same
         * quantizer), as far as percent registers carry it */
        Quantizer q;
        cr_assert_eq(quant_init(&q, COLOUR_256), 0);
        long err = 0;
        for (int y = 0; y < im.h; y++)
            for (int x = 0; x < im.w; x++) {
                size_t i = 3 * ((size_t)y * im.w + x);
                uint8_t want[3];
                palette_256_rgb(quant_pick(&q, im.rgb + i, x, y), want);
                for (int c = 0; c < 3; c++) {
                    int d = back.rgb[i + c] - want[c];
                    cr_expect(d >= -2 && d <= 2, "pixel %d,%d channel %d: %d, the palette says %d", x, y, c,
                              back.rgb[i + c], want[c]);
                    err += abs(back.rgb[i + c] - im.rgb[i + c]);
                }
            }
        quant_free(&q);
        /* and near the picture itself: dithering between neighbours of a
         * cube of 6 levels a channel is off by less than a level's half */
        double mean = (double)err / (3.0 * im.w * im.h);
        cr_expect_lt(mean, 26, "mean error %.1f per channel", mean);
        free(back.rgb);
        free(im.rgb);
        bytebuf_free(&s);
    }
}

/* ==== A rendered view: the -o PNG and each protocol agree ==== */

Test(pixels, a_view_in_each_protocol_is_the_o_image)
{
    Scene s;
    cr_assert_eq(tl_scene_from_file(&s, "assets/torus.obj"), 0);
    Pipeline p;
    cr_assert_eq(pipeline_init(&p, &s, hsr_find("zbuffer"), 1), 0);
    cr_assert_eq(pipeline_render(&p, 160, 90, 1.0f, 0, 1), 0);
    char path[] = "/tmp/zview-pixels-XXXXXX.png", err[256];
    int fd = mkstemps(path, 4);
    cr_assert_geq(fd, 0);
    close(fd);
    cr_assert_eq(write_png(path, &p.img, err, sizeof err), 0, "%s", err);
    FILE *f = fopen(path, "rb");
    uint8_t *file = malloc(1 << 20);
    size_t flen = fread(file, 1, 1 << 20, f);
    fclose(f);
    unlink(path);
    Image o = png_read_back(file, flen);
    free(file);
    for (PixelProto proto = PIX_SIXEL; proto <= PIX_ITERM; proto++) {
        ByteBuf b = { 0 };
        cr_assert_eq(pixels_encode(proto, &p.img, 3, 0, 0, &b), 0);
        Image back = proto == PIX_KITTY ? kitty_read_back(&b, 3) : proto == PIX_ITERM ? iterm_read_back(&b)
                                                                                   : sixel_read_back(&b);
        if (proto != PIX_SIXEL) {
            expect_same(&o, &back, pixel_proto_names[proto]);
        } else {
            /* sixel: 256 colours; the same size, and black where -o is */
            cr_assert_eq(back.w, o.w);
            cr_assert_eq(back.h, o.h);
            int off = 0;
            for (size_t i = 0; i < (size_t)o.w * o.h; i++)
                off += !memcmp(o.rgb + 3 * i, "\0\0\0", 3) != !memcmp(back.rgb + 3 * i, "\0\0\0", 3);
            cr_expect_eq(off, 0, "%d pixels black in one and not the other", off);
        }
        free(back.rgb);
        bytebuf_free(&b);
    }
    free(o.rgb);
    pipeline_free(&p);
    scene_free(&s);
}

/* ==== Asking the terminal ==== */

static PixelScan scan_split(const char *answer, size_t at)
{
    PixelScan s;
    pixels_scan_init(&s, 0);
    size_t n = strlen(answer);
    pixels_scan(&s, (const unsigned char *)answer, at < n ? at : n);
    if (at < n)
        pixels_scan(&s, (const unsigned char *)answer + at, n - at);
    return s;
}

Test(pixels, the_answers_say_which_protocol_at_any_split)
{
    const char *vt340 = "\033[?63;1;2;4;6;9;15;22c";
    const char *vt220 = "\033[?62;1;2;6;9;15;22;29c";
    const char *kitty = "\033_Gi=31;OK\033\\\033[?62;c";
    const char *refused = "\033_Gi=31;ENOTSUPPORTED:x\033\\\033[?62;4c";
    const char *keys = "q\033[A\033[?1;2c";
    const char *iterm = "\033P>|iTerm2 3.5.0\033\\\033[?62;4c";
    const char *xterm = "\033P>|XTerm(379)\033\\\033[?63;1;2;4;6;9;15;22c";
    for (size_t at = 0; at <= strlen(kitty); at++) {
        PixelScan a = scan_split(vt340, at), b = scan_split(vt220, at), c = scan_split(kitty, at),
                  d = scan_split(refused, at), e = scan_split(keys, at), f = scan_split(iterm, at),
                  g = scan_split(xterm, at);
        cr_expect(a.got_da && a.sixel && !a.kitty, "vt340 split at %zu", at);
        cr_expect(b.got_da && !b.sixel && !b.kitty, "vt220 split at %zu", at);
        cr_expect(c.got_da && !c.sixel && c.kitty, "kitty split at %zu", at);
        cr_expect(d.got_da && d.sixel && !d.kitty, "an error answer is no kitty (split at %zu)", at);
        cr_expect(e.got_da && !e.sixel && !e.kitty, "keys before the answer (split at %zu)", at);
        cr_expect(f.got_da && f.iterm && !f.kitty, "iTerm2 by its name (split at %zu)", at);
        cr_expect(g.got_da && g.sixel && !g.iterm && !g.kitty, "xterm's name and a VT340's attributes (split at %zu)", at);
    }
}

Test(pixels, multiplexers_and_dumb_terminals_get_cells_without_a_question)
{
    const char *names[] = { "TMUX", "STY", "TERM" };
    char *saved[3];
    for (int i = 0; i < 3; i++)
        saved[i] = getenv(names[i]) ? strdup(getenv(names[i])) : NULL;
    unsetenv("TMUX");
    unsetenv("STY");
    setenv("TERM", "xterm-256color", 1);
    cr_expect_eq(pixels_from_env(), PIX_AUTO);
    setenv("TMUX", "/tmp/tmux-0/default,1,0", 1);
    cr_expect_eq(pixels_from_env(), PIX_CELLS, "inside tmux");
    unsetenv("TMUX");
    setenv("TERM", "screen-256color", 1);
    cr_expect_eq(pixels_from_env(), PIX_CELLS, "inside screen");
    setenv("TERM", "dumb", 1);
    cr_expect_eq(pixels_from_env(), PIX_CELLS, "TERM=dumb");
    for (int i = 0; i < 3; i++) {
        if (saved[i])
            setenv(names[i], saved[i], 1);
        else
            unsetenv(names[i]);
        free(saved[i]);
    }
}

/* pixels_detect over pipes standing for a terminal: one whose answers
 * are waiting, one that never answers (the wait ends, cells), and the
 * keys that came with the answers passed on. */
typedef struct {
    char   got[64];
    size_t n;
} Sink;

static void sink_keep(void *ctx, const unsigned char *b, size_t n)
{
    Sink *s = ctx;
    for (size_t i = 0; i < n && s->n + 1 < sizeof s->got; i++)
        s->got[s->n++] = (char)b[i];
}

static PixelProto detect_with(const char *answer, Sink *sink, char *question, size_t qlen)
{
    int out[2], in[2];
    cr_assert_eq(pipe(out), 0);
    cr_assert_eq(pipe(in), 0);
    if (answer)
        cr_assert_eq(write(in[1], answer, strlen(answer)), (ssize_t)strlen(answer));
    PixelScan scan;
    pixels_scan_init(&scan, 0);
    PixelProto p = pixels_detect(out[1], in[0], 60, sink_keep, sink, &scan);
    cr_expect_eq(pixels_scanned(&scan), p, "the scan says what detect returned");
    close(out[1]);
    out[1] = -1;
    ssize_t n = read(out[0], question, qlen - 1);       /* the end, at once, when nothing was asked */
    question[n > 0 ? n : 0] = 0;
    close(out[0]);
    close(in[0]);
    close(in[1]);
    return p;
}

Test(pixels, detect_asks_and_reads_the_answers)
{
    char *tmux = getenv("TMUX") ? strdup(getenv("TMUX")) : NULL, *sty = getenv("STY") ? strdup(getenv("STY")) : NULL;
    char *term = getenv("TERM") ? strdup(getenv("TERM")) : NULL;
    unsetenv("TMUX");
    unsetenv("STY");
    setenv("TERM", "xterm", 1);
    char q[256];
    Sink s = { .n = 0 };
    cr_expect_eq(detect_with("\033[?63;1;2;4;6c", &s, q, sizeof q), PIX_SIXEL, "a VT340's answer");
    cr_expect_not_null(strstr(q, "\033[c"), "the attributes asked");
    cr_expect_not_null(strstr(q, "a=q"), "the kitty query asked");
    s.n = 0;
    cr_expect_eq(detect_with("\033_Gi=31;OK\033\\\033[?62;22c", &s, q, sizeof q), PIX_KITTY, "kitty's answer");
    s.n = 0;
    cr_expect_eq(detect_with("\033P>|iTerm2 3.5.0\033\\\033[?62;4c", &s, q, sizeof q), PIX_ITERM,
                 "iTerm2 (which also takes sixel): its own images");
    s.n = 0;
    cr_expect_eq(detect_with("j\033[?62;22c", &s, q, sizeof q), PIX_CELLS, "a VT220's answer");
    cr_expect(s.n >= 1 && s.got[0] == 'j', "the key typed before the answer is passed on");
    s.n = 0;
    cr_expect_eq(detect_with(NULL, &s, q, sizeof q), PIX_CELLS, "no answer: cells after the wait");
    setenv("TMUX", "/tmp/x,1,0", 1);
    cr_expect_eq(detect_with("\033[?63;4c", &s, q, sizeof q), PIX_CELLS, "tmux: cells");
    cr_expect_eq(q[0], 0, "and nothing asked inside tmux");
    if (tmux)
        setenv("TMUX", tmux, 1);
    else
        unsetenv("TMUX");
    if (sty)
        setenv("STY", sty, 1);
    if (term)
        setenv("TERM", term, 1);
    else
        unsetenv("TERM");
    free(tmux);
    free(sty);
    free(term);
}
