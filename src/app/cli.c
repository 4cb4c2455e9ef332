/* cli.c: argv -> Options. Reports errors, never exits. */

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

void cli_usage(FILE *f)
{
    fputs(
"usage: zview [OPTIONS] [FILE.obj ...]\n"
"A fast, exact 3D model viewer for the terminal. With no file, opens the\n"
"bundled demo scene. Several files make one scene of several objects.\n"
"\n"
"Output (default: the interactive viewer; --print when stdout is no terminal):\n"
"  --print               write one frame to stdout as text, no curses\n"
"  -o FILE.png|FILE.ppm  write the image to a file\n"
"  --size WxH            pixels for -o (default 640x480); cells for --print\n"
"  --mode half|ascii|braille      text mode (default: half on UTF-8)\n"
"  --color truecolor|256|16|none  colours (default: from COLORTERM/TERM/NO_COLOR)\n"
"  --shade lambert|depth|id       shading (default lambert)\n"
"  --info                print file statistics (with --algo: render statistics)\n"
"  --dump-ids FILE       face-id buffer: W*H little-endian int32, -1 = background\n"
"  --dump-screen FILE    screen-space polygons as OBJ text\n"
"\n"
"View:\n"
"  --algo NAME           zbuffer, scanline, span, hzb, hzb-octree (default zbuffer)\n"
"  --yaw DEG --pitch DEG --roll DEG   turn the scene\n"
"  --zoom F              scale (1 = fit to 90% of the view)\n"
"  --persp FOV | --ortho perspective with a vertical field of view, or orthographic\n"
"  --cull                back-face culling (off by default)\n"
"  --grid N              N x N x N copies of the scene (a deep scene)\n"
"\n"
"Benchmark:\n"
"  --bench [--views N] [--threads N] [--json] [--algo all|a,b,...]\n"
"  --bench-tty           bytes written per frame for a scripted rotation\n"
"  --threads N           threads for the hidden-surface step (default: all cores)\n"
"  --fps N               auto-rotate frame cap in the viewer (default 30)\n"
"\n"
"  --help, --version\n"
"Exit status: 0 ok, 1 runtime error, 2 usage error.\n", f);
}

static int parse_float(const char *s, float *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno || !isfinite((float)v) || fabs(v) > 1e9)
        return -1;
    *out = (float)v;
    return 0;
}

static int parse_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi)
        return -1;
    *out = (int)v;
    return 0;
}

static int parse_size(const char *s, int *w, int *h)
{
    char *end;
    const char *x = strpbrk(s, "xX");
    if (!isdigit((unsigned char)s[0]) || !x || !isdigit((unsigned char)x[1]))
        return -1;
    long a = strtol(s, &end, 10);
    if (end == s || (*end != 'x' && *end != 'X'))
        return -1;
    const char *t = end + 1;
    long b = strtol(t, &end, 10);
    if (end == t || *end || a < 1 || b < 1 || a > SCREEN_MAX || b > SCREEN_MAX)
        return -1;
    *w = (int)a;
    *h = (int)b;
    return 0;
}

int cli_parse(int argc, char **argv, Options *o, char *err, size_t errlen)
{
    memset(o, 0, sizeof *o);
    o->mode = -1;
    o->color = -1;
    o->shade = SHADE_LAMBERT;
    o->algo = NULL;
    o->zoom = 1;
    o->fov = 50;
    o->views = 8;
    o->threads = 0;
    o->fps = 30;
    o->grid = 1;
    int only_files = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = NULL;
#define NEED_VAL()                                                              \
    do {                                                                        \
        if (i + 1 >= argc) {                                                    \
            snprintf(err, errlen, "option '%s' needs a value", a);              \
            return -1;                                                          \
        }                                                                       \
        val = argv[++i];                                                        \
    } while (0)
#define BAD_VAL(what)                                                           \
    do {                                                                        \
        snprintf(err, errlen, "bad value '%s' for %s (%s)", val, a, what);      \
        return -1;                                                              \
    } while (0)
        if (only_files || a[0] != '-' || a[1] == 0) {
            if (o->nfiles >= MAX_FILES) {
                snprintf(err, errlen, "too many files (at most %d)", MAX_FILES);
                return -1;
            }
            o->files[o->nfiles++] = a;
        } else if (!strcmp(a, "--")) {
            only_files = 1;
        } else if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            o->help = 1;
        } else if (!strcmp(a, "-V") || !strcmp(a, "--version")) {
            o->version = 1;
        } else if (!strcmp(a, "--print")) {
            o->print = 1;
        } else if (!strcmp(a, "--info")) {
            o->info = 1;
        } else if (!strcmp(a, "--bench")) {
            o->bench = 1;
        } else if (!strcmp(a, "--bench-tty")) {
            o->bench_tty = 1;
        } else if (!strcmp(a, "--json")) {
            o->json = 1;
        } else if (!strcmp(a, "--cull")) {
            o->cull = 1;
        } else if (!strcmp(a, "--ortho")) {
            o->persp = 0;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            NEED_VAL();
            size_t n = strlen(val);
            if (n < 5 || (strcmp(val + n - 4, ".png") && strcmp(val + n - 4, ".ppm")))
                BAD_VAL("the file must end in .png or .ppm");
            o->out = val;
        } else if (!strcmp(a, "--dump-ids")) {
            NEED_VAL();
            o->dump_ids = val;
        } else if (!strcmp(a, "--dump-screen")) {
            NEED_VAL();
            o->dump_screen = val;
        } else if (!strcmp(a, "--size")) {
            NEED_VAL();
            if (parse_size(val, &o->w, &o->h))
                BAD_VAL("expected WxH, e.g. 640x480");
        } else if (!strcmp(a, "--mode")) {
            NEED_VAL();
            if ((o->mode = mode_from_name(val)) < 0)
                BAD_VAL("half, ascii or braille");
        } else if (!strcmp(a, "--color") || !strcmp(a, "--colour")) {
            NEED_VAL();
            if ((o->color = color_from_name(val)) < 0)
                BAD_VAL("truecolor, 256, 16 or none");
        } else if (!strcmp(a, "--shade")) {
            NEED_VAL();
            if ((o->shade = shade_from_name(val)) < 0)
                BAD_VAL("lambert, depth or id");
        } else if (!strcmp(a, "--algo")) {
            NEED_VAL();
            o->algo = val;
        } else if (!strcmp(a, "--yaw") || !strcmp(a, "--pitch") || !strcmp(a, "--roll") ||
                   !strcmp(a, "--zoom")) {
            NEED_VAL();
            float v;
            if (parse_float(val, &v))
                BAD_VAL("a number");
            if (a[2] == 'y') o->yaw = v;
            else if (a[2] == 'p') o->pitch = v;
            else if (a[2] == 'r') o->roll = v;
            else {
                if (v <= 0)
                    BAD_VAL("a positive number");
                o->zoom = v;
            }
        } else if (!strcmp(a, "--persp")) {
            NEED_VAL();
            if (parse_float(val, &o->fov) || o->fov <= 1 || o->fov >= 179)
                BAD_VAL("a field of view in degrees, 1 < FOV < 179");
            o->persp = 1;
        } else if (!strcmp(a, "--views")) {
            NEED_VAL();
            if (parse_int(val, 1, 100000, &o->views))
                BAD_VAL("a count >= 1");
        } else if (!strcmp(a, "--threads")) {
            NEED_VAL();
            if (parse_int(val, 1, 64, &o->threads))
                BAD_VAL("1 to 64");
        } else if (!strcmp(a, "--grid")) {
            NEED_VAL();
            if (parse_int(val, 1, 40, &o->grid))
                BAD_VAL("1 to 40");
        } else if (!strcmp(a, "--fps")) {
            NEED_VAL();
            if (parse_int(val, 1, 1000, &o->fps))
                BAD_VAL("1 to 1000");
        } else {
            snprintf(err, errlen, "unknown option '%s' (see --help)", a);
            return -1;
        }
#undef NEED_VAL
#undef BAD_VAL
    }
    if (o->algo && !o->bench && !hsr_find(o->algo)) {
        snprintf(err, errlen, "unknown algorithm '%s' (zbuffer, scanline, span, hzb, hzb-octree)", o->algo);
        return -1;
    }
    return 0;
}
