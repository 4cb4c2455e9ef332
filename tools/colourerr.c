/* colourerr: how far a 256-, 16- or 8-colour picture is from the
 * truecolor one, before (plain nearest palette colour in RGB) and after
 * (quant.c: nearest in OKLab, ordered dithering).
 *
 *   build/colourerr [-s WxH] [-o DIR] model.obj ...
 *
 * For each model, a three-quarter view is shaded at WxH pixels (default
 * 160x96, a terminal's worth of half blocks). Two errors are printed, in
 * OKLab distance x 100 (about 1 = a just noticeable difference):
 *   pixel: the mean over lit pixels of the distance pixel by pixel;
 *   seen:  the mean over 4x4 blocks of the distance between the blocks'
 *          average colours (averaged in linear light, as the eye does
 *          from a viewing distance), i.e. what dithering aims at.
 * With -o, the pictures are written as PNG files into DIR to look at. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

static float lin(uint8_t v)
{
    float c = v / 255.0f;
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static uint8_t unlin(float c)
{
    float v = c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1 / 2.4f) - 0.055f;
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return (uint8_t)lrintf(v * 255);
}

static float oklab_dist(const uint8_t a[3], const uint8_t b[3])
{
    float la[3], lb[3];
    quant_rgb_to_oklab(a, la);
    quant_rgb_to_oklab(b, lb);
    return sqrtf((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1]) +
                 (la[2] - lb[2]) * (la[2] - lb[2]));
}

/* The plain nearest colour of the first n palette entries, in RGB. */
static int nearest_rgb(const uint8_t rgb[3], int first, int last)
{
    int best = first, bd = 1 << 30;
    for (int i = first; i <= last; i++) {
        uint8_t p[3];
        palette_256_rgb(i, p);
        int d = (rgb[0] - p[0]) * (rgb[0] - p[0]) + (rgb[1] - p[1]) * (rgb[1] - p[1]) +
                (rgb[2] - p[2]) * (rgb[2] - p[2]);
        if (d < bd) {
            bd = d;
            best = i;
        }
    }
    return best;
}

static void errors(const Image *t, const uint8_t *q, double *pixel, double *seen)
{
    double sp = 0, ss = 0;
    long np = 0, ns = 0;
    for (int by = 0; by + 4 <= t->h; by += 4)
        for (int bx = 0; bx + 4 <= t->w; bx += 4) {
            float at[3] = { 0 }, aq[3] = { 0 };
            int lit = 0;
            for (int y = by; y < by + 4; y++)
                for (int x = bx; x < bx + 4; x++) {
                    size_t i = (size_t)y * t->w + x;
                    if (!t->lit[i])
                        continue;
                    lit++;
                    sp += oklab_dist(t->rgb + 3 * i, q + 3 * i);
                    np++;
                    for (int a = 0; a < 3; a++) {
                        at[a] += lin(t->rgb[3 * i + a]);
                        aq[a] += lin(q[3 * i + a]);
                    }
                }
            if (lit < 16)
                continue;       /* edges mix in the background */
            uint8_t mt[3], mq[3];
            for (int a = 0; a < 3; a++) {
                mt[a] = unlin(at[a] / 16);
                mq[a] = unlin(aq[a] / 16);
            }
            ss += oklab_dist(mt, mq);
            ns++;
        }
    *pixel = np ? 100 * sp / np : 0;
    *seen = ns ? 100 * ss / ns : 0;
}

int main(int argc, char **argv)
{
    int w = 160, h = 96;
    const char *dir = NULL;
    int a = 1;
    for (; a < argc && argv[a][0] == '-'; a += 2) {
        if (a + 1 >= argc)
            return 2;
        if (!strcmp(argv[a], "-s") && sscanf(argv[a + 1], "%dx%d", &w, &h) == 2)
            continue;
        if (!strcmp(argv[a], "-o")) {
            dir = argv[a + 1];
            continue;
        }
        fprintf(stderr, "usage: colourerr [-s WxH] [-o DIR] model ...\n");
        return 2;
    }
    printf("%-22s %6s  %-14s %-14s\n", "model", "colours", "before pixel/seen", "after pixel/seen");
    for (; a < argc; a++) {
        Options o;
        cli_defaults(&o);
        o.files[0] = argv[a];
        o.nfiles = 1;
        o.yaw = 35;
        o.pitch = 25;
        Scene s;
        char err[512];
        if (app_load_scene(&o, &s, err, sizeof err)) {
            fprintf(stderr, "colourerr: %s\n", err);
            return 1;
        }
        Pipeline p;
        if (pipeline_init(&p, &s, hsr_find("zbuffer"), 1) || pipeline_render(&p, w, h, 1.0f, 0, 1)) {
            fprintf(stderr, "colourerr: out of memory\n");
            return 1;
        }
        const Image *t = &p.img;
        uint8_t *before = malloc((size_t)w * h * 3), *after = malloc((size_t)w * h * 3);
        const char *base = strrchr(argv[a], '/') ? strrchr(argv[a], '/') + 1 : argv[a];
        for (ColourDepth d = COLOUR_256; d >= COLOUR_8; d--) {
            Quantizer q;
            if (!before || !after || quant_init(&q, d))
                return 1;
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++) {
                    size_t i = (size_t)y * w + x;
                    const uint8_t *c = t->rgb + 3 * i;
                    int old = d == COLOUR_256 ? palette_256(c) : nearest_rgb(c, 0, d == COLOUR_16 ? 15 : 7);
                    palette_256_rgb(old, before + 3 * i);
                    palette_256_rgb(quant_pick(&q, c, x, y), after + 3 * i);
                }
            quant_free(&q);
            double bp, bs, ap, as;
            errors(t, before, &bp, &bs);
            errors(t, after, &ap, &as);
            printf("%-22s %6s  %6.2f / %-6.2f %6.2f / %-6.2f\n", base, colour_name(d), bp, bs, ap, as);
            if (dir) {
                char path[1024];
                Image im = *t;
                im.rgb = before;
                snprintf(path, sizeof path, "%s/%s-%s-before.png", dir, base, colour_name(d));
                write_png(path, &im, err, sizeof err);
                im.rgb = after;
                snprintf(path, sizeof path, "%s/%s-%s-after.png", dir, base, colour_name(d));
                write_png(path, &im, err, sizeof err);
            }
        }
        if (dir) {
            char path[1024];
            snprintf(path, sizeof path, "%s/%s-truecolor.png", dir, base);
            write_png(path, t, err, sizeof err);
        }
        free(before);
        free(after);
        pipeline_free(&p);
        scene_free(&s);
    }
    return 0;
}
