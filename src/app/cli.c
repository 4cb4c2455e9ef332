/* cli.c: argv -> Options, GNU style (getopt_long): --size=80x24 or
 * --size 80x24, -oout.png or -o out.png, clusters of short flags, `--`
 * ends the options. Reports errors, never exits. */

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

void cli_usage(FILE *f)
{
    fputs(
"usage: zview [OPTIONS] [FILE ...]\n"
"A fast, exact 3D model viewer for the terminal. With no file, opens the\n"
"bundled demo scene. Several files make one scene of several objects.\n"
"FILE is a model in any format zview reads (--formats), told by its\n"
"content; - reads one from standard input.\n"
"\n"
"Input:\n"
"  --format NAME         read FILE as NAME (obj, stl, ply, off, or an assimp format)\n"
"  --formats             list the formats this build reads\n"
"  --up x|y|z|-x|-y|-z   the model's up axis (default y; scans and CAD are often z)\n"
"  --flip                reverse every face's winding (inside out)\n"
"  --strict              refuse a file with a statement zview cannot read (default:\n"
"                        skip such statements, show the rest, warn with their count)\n"
"  --points              draw every vertex as a point instead of the faces\n"
"\n"
"Output (default: the interactive viewer; --print when stdout is no terminal):\n"
"  -p, --print           write one frame to stdout as text, no curses\n"
"  -o, --output FILE     write the image to FILE.png or FILE.ppm (- = stdout, PNG), or\n"
"                        the text --print gives to FILE.txt\n"
"  --image-format png|ppm  the image format for -o (default: by the name; - is PNG)\n"
"  -s, --size WxH        pixels for -o (default 640x480); cells for --print\n"
"  --mode half|ascii|braille      text mode (default: half on UTF-8)\n"
"  --color truecolor|256|16|8|none colours (default: from COLORTERM/TERM/NO_COLOR)\n"
"  --shade lambert|smooth|depth|id  shading (default lambert: flat per face)\n"
"  --edges               outline silhouettes, creases and depth steps\n"
"  --crease DEG          smooth shading and --edges: a sharper edge is a crease (default 60)\n"
"  --point-size N        points as N x N pixel squares (1 to 16, default 1; < > in the viewer)\n"
"  --line-width N        lines N pixels wide (1 to 16, default 1; ( ) in the viewer)\n"
"  --wireframe           every edge of the faces as a line, hidden where faces hide it (W)\n"
"  --light YAW,PITCH     light direction in degrees from the viewer (default -34,37)\n"
"  --ambient F           ambient light, 0 to 1 (default 0.22)\n"
"  --samples N           samples per pixel, 1, 4, 9 or 16, averaged (default 4 for\n"
"                        text and the viewer, 1 for -o)\n"
"  --turntable N         N frames turning 360/N degrees each about the vertical, to\n"
"                        -o PATTERN (one integer conversion: out-%03d.png, .ppm, .txt;\n"
"                        frames numbered from 0) or with --print to stdout\n"
"  --print-view          the viewer prints the command line of its last view on quitting\n"
"  --sketch              the viewer starts on an empty canvas: draw polygons with the\n"
"                        mouse or the keys and watch the algorithms hide them (D in the\n"
"                        viewer; a FILE given too is shown on leaving the canvas)\n"
"  --info                print file statistics (with --algo: render statistics)\n"
"  --dump-ids FILE       face-id buffer: W*H little-endian int32, -1 = background\n"
"  --dump-screen FILE    screen-space polygons as OBJ text\n"
"\n"
"View:\n"
"  -a, --algo NAME       zbuffer, scanline, span, hzb, hzb-octree (default zbuffer)\n"
"  --view NAME           front, back, left, right, top, bottom, iso, or auto (the\n"
"                        default: the three-quarter view that sees most of the model)\n"
"  --yaw DEG --pitch DEG --roll DEG   turn the scene (on top of --view's turn)\n"
"  --zoom F              scale (1 = fit to 90% of the view)\n"
"  --pan X,Y             move the view (fractions of the scene's radius, right and up)\n"
"  --fit-from YAW,PITCH,ROLL  the turn the view was fitted at (default: the turn)\n"
"  --move I:X,Y,Z        move object I (1 = the first) in world units\n"
"  --turn I:YAW,PITCH,ROLL   turn object I about its centre (degrees)\n"
"  --scale I:F           scale object I about its centre\n"
"  --persp FOV | --ortho perspective with a vertical field of view, or orthographic\n"
"  --cull                back-face culling (off by default)\n"
"  --grid N              N x N x N copies of the scene (a deep scene)\n"
"  --order file|front-to-back|back-to-front|shuffle\n"
"                        the order polygons reach the algorithm (same picture)\n"
"  --layout row|grid|none  several files side by side at a common size (row, the\n"
"                        default; grid), or where their coordinates put them (none)\n"
"  --max-polys N         refuse scenes of more polygons (default 20000000)\n"
"\n"
"Benchmark:\n"
"  --bench [--views N] [--threads N] [--json] [--algo all|a,b,...]\n"
"  --bench-tty           bytes written per frame for a scripted rotation\n"
"  -j, --threads N       threads for every stage (default: all cores)\n"
"  --fps N               auto-rotate frame cap in the viewer (default 30)\n"
"\n"
"  -h, --help, -V, --version\n"
"Exit status: 0 ok, 1 runtime error, 2 usage error.\n", f);
}

int frame_pattern_check(const char *pat)
{
    int n = 0;
    for (const char *p = pat; *p; p++) {
        if (*p != '%')
            continue;
        p++;
        if (*p == '%')
            continue;
        /* flags, width, precision: then the conversion, an integer one */
        while (*p && strchr("-+ #0", *p))
            p++;
        while (*p >= '0' && *p <= '9')
            p++;
        if (*p == '.') {
            p++;
            while (*p >= '0' && *p <= '9')
                p++;
        }
        if (!*p || !strchr("diuxXo", *p))
            return -1;
        n++;
    }
    return n;
}

static int parse_float(const char *s, float *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno || !isfinite(v) || fabs(v) > 1e9)
        return -1;
    *out = (float)v;
    return 0;
}

static int parse_int(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

/* "a,b,c": exactly n finite numbers of at most 1e9 in size. */
static int parse_floats(const char *s, float *out, int n)
{
    char buf[256];
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    char *p = buf;
    for (int k = 0; k < n; k++) {
        char *comma = strchr(p, ',');
        if ((comma != NULL) != (k + 1 < n))
            return -1;
        if (comma)
            *comma = 0;
        if (parse_float(p, &out[k]))
            return -1;
        p = comma + 1;
    }
    return 0;
}

/* "WxH": -1 when it is not two numbers, -2 when one is 0 or more than
 * SCREEN_MAX. */
static int parse_size(const char *s, int *w, int *h)
{
    char *end;
    const char *x = strpbrk(s, "xX");
    if (s[0] < '0' || s[0] > '9' || !x || x[1] < '0' || x[1] > '9')
        return -1;
    errno = 0;
    long a = strtol(s, &end, 10);
    if (end != x)
        return -1;
    long b = strtol(x + 1, &end, 10);
    if (*end)
        return -1;
    if (errno || a < 1 || b < 1 || a > SCREEN_MAX || b > SCREEN_MAX)
        return -2;
    *w = (int)a;
    *h = (int)b;
    return 0;
}

/* "I:v1,v2,..." for --move, --turn, --scale. */
static int parse_place(const char *s, int n, Placement *pl)
{
    char *end;
    errno = 0;
    long i = strtol(s, &end, 10);
    if (end == s || *end != ':' || errno || i < 1 || i > 65535)
        return -1;
    pl->obj = (int)i - 1;
    return parse_floats(end + 1, pl->v, n);
}

enum {
    OPT_INFO = 256, OPT_BENCH, OPT_BENCH_TTY, OPT_JSON, OPT_CULL, OPT_ORTHO, OPT_PERSP,
    OPT_DUMP_IDS, OPT_DUMP_SCREEN, OPT_MODE, OPT_COLOR, OPT_SHADE, OPT_YAW, OPT_PITCH,
    OPT_ROLL, OPT_ZOOM, OPT_PAN, OPT_FIT_FROM, OPT_MOVE, OPT_TURN, OPT_SCALE, OPT_VIEWS,
    OPT_GRID, OPT_FPS, OPT_MAX_POLYS, OPT_SAMPLES, OPT_CREASE, OPT_LIGHT, OPT_AMBIENT, OPT_VIEW,
    OPT_LAYOUT, OPT_EDGES, OPT_ORDER, OPT_FORMAT, OPT_FORMATS, OPT_UP, OPT_FLIP, OPT_IMAGE_FORMAT,
    /* points, lines, lenient loading */
    OPT_POINT_SIZE, OPT_LINE_WIDTH, OPT_WIREFRAME, OPT_POINTS, OPT_STRICT,
    OPT_PRINT_VIEW, OPT_TURNTABLE, OPT_SKETCH,
};

static const struct option long_opts[] = {
    { "help", no_argument, NULL, 'h' },
    { "version", no_argument, NULL, 'V' },
    { "print", no_argument, NULL, 'p' },
    { "output", required_argument, NULL, 'o' },
    { "size", required_argument, NULL, 's' },
    { "algo", required_argument, NULL, 'a' },
    { "threads", required_argument, NULL, 'j' },
    { "info", no_argument, NULL, OPT_INFO },
    { "bench", no_argument, NULL, OPT_BENCH },
    { "bench-tty", no_argument, NULL, OPT_BENCH_TTY },
    { "json", no_argument, NULL, OPT_JSON },
    { "cull", no_argument, NULL, OPT_CULL },
    { "ortho", no_argument, NULL, OPT_ORTHO },
    { "persp", required_argument, NULL, OPT_PERSP },
    { "dump-ids", required_argument, NULL, OPT_DUMP_IDS },
    { "dump-screen", required_argument, NULL, OPT_DUMP_SCREEN },
    { "mode", required_argument, NULL, OPT_MODE },
    { "color", required_argument, NULL, OPT_COLOR },
    { "colour", required_argument, NULL, OPT_COLOR },
    { "shade", required_argument, NULL, OPT_SHADE },
    { "view", required_argument, NULL, OPT_VIEW },
    { "layout", required_argument, NULL, OPT_LAYOUT },
    { "edges", no_argument, NULL, OPT_EDGES },
    { "order", required_argument, NULL, OPT_ORDER },
    { "print-view", no_argument, NULL, OPT_PRINT_VIEW },
    { "turntable", required_argument, NULL, OPT_TURNTABLE },
    { "sketch", no_argument, NULL, OPT_SKETCH },
    { "yaw", required_argument, NULL, OPT_YAW },
    { "pitch", required_argument, NULL, OPT_PITCH },
    { "roll", required_argument, NULL, OPT_ROLL },
    { "zoom", required_argument, NULL, OPT_ZOOM },
    { "pan", required_argument, NULL, OPT_PAN },
    { "fit-from", required_argument, NULL, OPT_FIT_FROM },
    { "move", required_argument, NULL, OPT_MOVE },
    { "turn", required_argument, NULL, OPT_TURN },
    { "scale", required_argument, NULL, OPT_SCALE },
    { "views", required_argument, NULL, OPT_VIEWS },
    { "grid", required_argument, NULL, OPT_GRID },
    { "fps", required_argument, NULL, OPT_FPS },
    { "max-polys", required_argument, NULL, OPT_MAX_POLYS },
    { "samples", required_argument, NULL, OPT_SAMPLES },
    { "crease", required_argument, NULL, OPT_CREASE },
    { "light", required_argument, NULL, OPT_LIGHT },
    { "ambient", required_argument, NULL, OPT_AMBIENT },
    { "format", required_argument, NULL, OPT_FORMAT },
    { "formats", no_argument, NULL, OPT_FORMATS },
    { "up", required_argument, NULL, OPT_UP },
    { "flip", no_argument, NULL, OPT_FLIP },
    { "image-format", required_argument, NULL, OPT_IMAGE_FORMAT },
    /* points, lines, lenient loading */
    { "point-size", required_argument, NULL, OPT_POINT_SIZE },
    { "line-width", required_argument, NULL, OPT_LINE_WIDTH },
    { "wireframe", no_argument, NULL, OPT_WIREFRAME },
    { "points", no_argument, NULL, OPT_POINTS },
    { "strict", no_argument, NULL, OPT_STRICT },
    { NULL, 0, NULL, 0 },
};

/* The option as the user wrote it, for messages. */
static void opt_name(int c, int long_index, char *buf, size_t n)
{
    if (long_index >= 0)
        snprintf(buf, n, "--%s", long_opts[long_index].name);
    else
        snprintf(buf, n, "-%c", c);
}

void cli_defaults(Options *o)
{
    memset(o, 0, sizeof *o);
    o->mode = -1;
    o->color = -1;
    o->shade = SHADE_LAMBERT;
    o->zoom = 1;
    o->fov = 50;
    o->views = 8;
    o->fps = 30;
    o->grid = 1;
    o->max_polys = 20000000;
    o->crease = SHADE_CREASE_DEFAULT;
    o->light[0] = LIGHT_YAW;
    o->light[1] = LIGHT_PITCH;
    o->ambient = LIGHT_AMBIENT;
    o->point_size = 1;
    o->line_width = 1;
}

int cli_parse(int argc, char **argv, Options *o, char *err, size_t errlen)
{
    cli_defaults(o);
    /* getopt keeps its place in globals: start afresh on every call; a
     * leading ':' in the short options and opterr = 0 let us word the
     * errors ourselves */
    optind = 0;
    opterr = 0;
    for (;;) {
        int li = -1;
        int c = getopt_long(argc, argv, ":hVpo:s:a:j:", long_opts, &li);
        if (c == -1)
            break;
        char name[64];
        const char *val = optarg;
        long n;
        if (c == '?' || c == ':') {
            /* optind has moved past the faulty word */
            const char *word = optind > 0 && optind <= argc ? argv[optind - 1] : "?";
            if (c == ':')
                snprintf(err, errlen, "option '%s' needs a value", word);
            else if (optopt && word[0] == '-' && word[1] != '-')
                snprintf(err, errlen, "unknown option '-%c' (see --help)", optopt);
            else
                snprintf(err, errlen, "unknown option '%s' (see --help)", word);
            return -1;
        }
        opt_name(c, li, name, sizeof name);
#define BAD_VAL(what)                                                           \
    do {                                                                        \
        snprintf(err, errlen, "bad value '%s' for %s (%s)", val, name, what);   \
        return -1;                                                              \
    } while (0)
        switch (c) {
        case 'h': o->help = 1; break;
        case 'V': o->version = 1; break;
        case 'p': o->print = 1; break;
        case OPT_INFO: o->info = 1; break;
        case OPT_BENCH: o->bench = 1; break;
        case OPT_BENCH_TTY: o->bench_tty = 1; break;
        case OPT_JSON: o->json = 1; break;
        case OPT_CULL: o->cull = 1; break;
        case OPT_EDGES: o->edges = 1; break;
        case OPT_PRINT_VIEW: o->print_view = 1; break;
        case OPT_SKETCH: o->sketch = 1; break;
        case OPT_ORTHO: o->persp = 0; break;
        case 'o':
            /* the name is checked after the loop: --image-format may follow */
            if (!*val)
                BAD_VAL("a file name, or - for standard output");
            o->out = val;
            break;
        case OPT_IMAGE_FORMAT:
            if (!strcmp(val, "png"))
                o->image_format = IMG_PNG;
            else if (!strcmp(val, "ppm"))
                o->image_format = IMG_PPM;
            else
                BAD_VAL("png or ppm");
            break;
        case OPT_FORMAT:
            if (!mesh_format_valid(val)) {
                char list[160];
                mesh_formats_short(list, sizeof list);
                snprintf(err, errlen, "bad value '%s' for %s (a model format: %s; see --formats)",
                         val, name, list);
                return -1;
            }
            o->format = val;
            break;
        case OPT_FORMATS: o->formats = 1; break;
        case OPT_UP:
            if ((o->up = up_axis_from_name(val)) < 0)
                BAD_VAL("x, y, z, -x, -y or -z");
            break;
        case OPT_FLIP: o->flip = 1; break;
        case OPT_DUMP_IDS: o->dump_ids = val; break;
        case OPT_DUMP_SCREEN: o->dump_screen = val; break;
        case 's':
            switch (parse_size(val, &o->w, &o->h)) {
            case -1: BAD_VAL("expected WxH, e.g. 640x480");
            case -2:
                snprintf(err, errlen, "--size %s: 1 to %d per side", val, SCREEN_MAX);
                return -1;
            }
            break;
        case OPT_MODE:
            if ((o->mode = mode_from_name(val)) < 0)
                BAD_VAL("half, ascii or braille");
            break;
        case OPT_COLOR:
            if ((o->color = color_from_name(val)) < 0)
                BAD_VAL("truecolor, 256, 16, 8 or none");
            break;
        case OPT_SHADE:
            if ((o->shade = shade_from_name(val)) < 0)
                BAD_VAL("lambert, smooth, depth or id");
            break;
        case 'a': o->algo = val; break;
        case OPT_VIEW: {
            float y, p;
            if (strcmp(val, "auto") && view_from_name(val, &y, &p))
                BAD_VAL("front, back, left, right, top, bottom, iso or auto");
            o->view = val;
            break;
        }
        case OPT_ORDER:
            if ((o->order = order_from_name(val)) < 0)
                BAD_VAL("file, front-to-back, back-to-front or shuffle");
            break;
        case OPT_LAYOUT:
            if ((o->layout = layout_from_name(val)) < 0)
                BAD_VAL("row, grid or none");
            break;
        case OPT_YAW:
            if (parse_float(val, &o->yaw))
                BAD_VAL("degrees, at most 1e9 in size");
            o->turned = 1;
            break;
        case OPT_PITCH:
            if (parse_float(val, &o->pitch))
                BAD_VAL("degrees, at most 1e9 in size");
            o->turned = 1;
            break;
        case OPT_ROLL:
            if (parse_float(val, &o->roll))
                BAD_VAL("degrees, at most 1e9 in size");
            o->turned = 1;
            break;
        case OPT_ZOOM:
            if (parse_float(val, &o->zoom) || !(o->zoom >= 1e-3f && o->zoom <= 1e3f))
                BAD_VAL("from 0.001 to 1000");
            break;
        case OPT_PAN:
            if (parse_floats(val, o->pan, 2) || fabsf(o->pan[0]) > 1e4f || fabsf(o->pan[1]) > 1e4f)
                BAD_VAL("X,Y, each at most 10000 in size");
            break;
        case OPT_FIT_FROM:
            if (parse_floats(val, o->fit_from, 3))
                BAD_VAL("YAW,PITCH,ROLL in degrees");
            o->has_fit_from = 1;
            break;
        case OPT_MOVE:
        case OPT_TURN:
        case OPT_SCALE: {
            if (o->nplace >= MAX_PLACE) {
                snprintf(err, errlen, "too many --move, --turn and --scale (at most %d)", MAX_PLACE);
                return -1;
            }
            Placement *pl = &o->place[o->nplace];
            pl->kind = c == OPT_MOVE ? PLACE_MOVE : c == OPT_TURN ? PLACE_TURN : PLACE_SCALE;
            if (c == OPT_MOVE && parse_place(val, 3, pl))
                BAD_VAL("I:X,Y,Z with I the object's number from 1");
            if (c == OPT_TURN && parse_place(val, 3, pl))
                BAD_VAL("I:YAW,PITCH,ROLL with I the object's number from 1");
            if (c == OPT_SCALE && (parse_place(val, 1, pl) || !(pl->v[0] >= 1e-3f && pl->v[0] <= 1e3f)))
                BAD_VAL("I:F with I the object's number from 1 and F from 0.001 to 1000");
            o->nplace++;
            break;
        }
        case OPT_PERSP:
            if (parse_float(val, &o->fov) || o->fov <= 1 || o->fov >= 179)
                BAD_VAL("a field of view in degrees, 1 < FOV < 179");
            o->persp = 1;
            break;
        case OPT_VIEWS:
            if (parse_int(val, 1, 100000, &n))
                BAD_VAL("1 to 100000");
            o->views = (int)n;
            break;
        case 'j':
            if (parse_int(val, 1, 64, &n))
                BAD_VAL("1 to 64");
            o->threads = (int)n;
            break;
        case OPT_GRID:
            if (parse_int(val, 1, 100, &n))
                BAD_VAL("1 to 100");
            o->grid = (int)n;
            break;
        case OPT_TURNTABLE:
            if (parse_int(val, 1, 3600, &n))
                BAD_VAL("1 to 3600 frames");
            o->turntable = (int)n;
            break;
        case OPT_FPS:
            if (parse_int(val, 1, 1000, &n))
                BAD_VAL("1 to 1000");
            o->fps = (int)n;
            break;
        case OPT_CREASE:
            if (parse_float(val, &o->crease) || o->crease < 0 || o->crease > 180)
                BAD_VAL("degrees from 0 to 180");
            break;
        case OPT_LIGHT:
            if (parse_floats(val, o->light, 2))
                BAD_VAL("YAW,PITCH in degrees");
            break;
        case OPT_AMBIENT:
            if (parse_float(val, &o->ambient) || o->ambient < 0 || o->ambient > 1)
                BAD_VAL("from 0 to 1");
            break;
        case OPT_SAMPLES:
            if (parse_int(val, 1, 16, &n) || (n != 1 && n != 4 && n != 9 && n != 16))
                BAD_VAL("1, 4, 9 or 16");
            o->samples = (int)n;
            break;
        case OPT_MAX_POLYS:
            if (parse_int(val, 1, 2000000000L, &n))
                BAD_VAL("1 to 2000000000");
            o->max_polys = (uint64_t)n;
            break;
        /* points, lines, lenient loading */
        case OPT_POINT_SIZE:
            if (parse_int(val, 1, POINT_SIZE_MAX, &n))
                BAD_VAL("pixels, 1 to 16");
            o->point_size = (int)n;
            break;
        case OPT_LINE_WIDTH:
            if (parse_int(val, 1, POINT_SIZE_MAX, &n))
                BAD_VAL("pixels, 1 to 16");
            o->line_width = (int)n;
            break;
        case OPT_WIREFRAME: o->wireframe = 1; break;
        case OPT_POINTS: o->points = 1; break;
        case OPT_STRICT: o->strict = 1; break;
        default:
            snprintf(err, errlen, "unknown option (see --help)");
            return -1;
        }
#undef BAD_VAL
    }
    int stdin_files = 0;
    for (int i = optind; i < argc; i++) {
        if (o->nfiles >= MAX_FILES) {
            snprintf(err, errlen, "too many files (at most %d)", MAX_FILES);
            return -1;
        }
        if (strcmp(argv[i], "-") == 0 && stdin_files++) {
            snprintf(err, errlen, "- (standard input) given twice");
            return -1;
        }
        o->files[o->nfiles++] = argv[i];
    }
    if (o->out) {
        size_t len = strlen(o->out);
        int ext = len >= 5 && (!strcmp(o->out + len - 4, ".png") || !strcmp(o->out + len - 4, ".ppm") ||
                               !strcmp(o->out + len - 4, ".txt"));
        if (!ext && !o->image_format && strcmp(o->out, "-")) {
            snprintf(err, errlen, "bad value '%s' for -o (the file must end in .png, .ppm or .txt, "
                                  "or give --image-format)", o->out);
            return -1;
        }
        if (!strcmp(o->out, "-") && o->print) {
            snprintf(err, errlen, "-o - and --print both write to standard output: choose one");
            return -1;
        }
    }
    if (o->turntable && !o->out && !o->print) {
        snprintf(err, errlen, "--turntable needs -o PATTERN (e.g. out-%%03d.png) or --print");
        return -1;
    }
    if (o->turntable && o->out && frame_pattern_check(o->out) != 1) {
        snprintf(err, errlen, "--turntable: the file name '%s' needs exactly one integer conversion "
                 "for the frame number (e.g. out-%%03d.png; %%%% for a %%)", o->out);
        return -1;
    }
    if (o->sketch && (o->print || o->out || o->info || o->bench || o->bench_tty || o->turntable || o->dump_ids ||
                      o->dump_screen)) {
        snprintf(err, errlen, "--sketch draws in the viewer: it does not go with %s",
                 o->print ? "--print" : o->out ? "-o" : o->info ? "--info" : o->bench ? "--bench"
                 : o->bench_tty ? "--bench-tty" : o->turntable ? "--turntable" : o->dump_ids ? "--dump-ids"
                 : "--dump-screen");
        return -1;
    }
    if (o->algo && !o->bench && !hsr_find(o->algo)) {
        snprintf(err, errlen, "unknown algorithm '%s' (zbuffer, scanline, span, hzb, hzb-octree)", o->algo);
        return -1;
    }
    return 0;
}
