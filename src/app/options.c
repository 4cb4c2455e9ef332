/* options.c: the option table. Every option of zview is written once,
 * here: its long and short names, the name of its value, the words the
 * value can be, its line in --help, the section of the man page it sits
 * in, whether the view command writes it back, and what it does to
 * Options. cli.c builds getopt's table and the usage text from this one;
 * tests/test_options.c fails when the man page, a completion file, the
 * README or the view command disagrees with it. A new option is one row
 * here (and a setter when it takes a value), then the man page and the
 * two completion files, which the test names when they lag. */

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "pixels.h"
#include "repair.h"

/* ==== Reading values ==== */

/* The message every bad value gets: the value, the option as written,
 * and what it should have been. Returns -1 for the setter to pass on. */
static int bad(const OptCall *c, const char *what)
{
    snprintf(c->err, c->errlen, "bad value '%s' for %s (%s)", c->val, c->name, what);
    return -1;
}

/* The whole of s as a finite number. */
static int parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

static int parse_float(const char *s, float *out)
{
    double v;
    if (parse_double(s, &v) || fabs(v) > 1e9)
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

/* An integer in [lo, hi] into *dst. */
static int set_int(int *dst, const OptCall *c, long lo, long hi, const char *what)
{
    long n;
    if (parse_int(c->val, lo, hi, &n))
        return bad(c, what);
    *dst = (int)n;
    return 0;
}

/* A number in [lo, hi] into *dst. */
static int set_float(float *dst, const OptCall *c, float lo, float hi, const char *what)
{
    if (parse_float(c->val, dst) || !(*dst >= lo && *dst <= hi))
        return bad(c, what);
    return 0;
}

/* The words an option takes, from the table that defines them: name i,
 * or NULL past the last. */
typedef const char *(*NameAt)(int i);

/* "a, b, c or d": every word of a table, for a refusal. */
static void name_list(NameAt name_at, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = 0;
    for (int i = 0; name_at(i) && o < len; i++)
        o += (size_t)snprintf(buf + o, len - o, "%s%s", i == 0 ? "" : name_at(i + 1) ? ", " : " or ", name_at(i));
}

/* A name that from_name knows (it returns -1 for the others) into *dst;
 * else the refusal lists the table's words. */
static int set_name(int *dst, const OptCall *c, int (*from_name)(const char *), NameAt name_at)
{
    if ((*dst = from_name(c->val)) < 0) {
        char words[256];
        name_list(name_at, words, sizeof words);
        return bad(c, words);
    }
    return 0;
}

static const char *up_word(int i) { return i < UP_COUNT ? up_axis_name(i) : NULL; }
static const char *colour_word(int i) { return i <= COLOUR_TRUE ? colour_name((ColourDepth)(COLOUR_TRUE - i)) : NULL; }
static const char *shade_word(int i) { return i < SHADE_COUNT ? shade_names[i] : NULL; }
static const char *order_word(int i) { return i < ORDER_COUNT ? order_names[i] : NULL; }
static const char *layout_word(int i) { return i < LAYOUT_COUNT ? layout_names[i] : NULL; }
/* --mode: the text modes, then the pixel protocols (cells and auto too) */
static const char *mode_word(int i)
{
    return i < MODE_COUNT ? mode_names[i] : i < MODE_COUNT + PIX_COUNT ? pixel_proto_names[i - MODE_COUNT] : NULL;
}
/* --view: the named views, then auto */
static const char *view_word(int i)
{
    return view_name(i) ? view_name(i) : i > 0 && view_name(i - 1) ? "auto" : NULL;
}

/* ==== Setters: one per option that takes a value ==== */

static int set_output(Options *o, const OptCall *c)
{
    /* the name is checked after the loop: --image-format may follow */
    if (!*c->val)
        return bad(c, "a file name, or - for standard output");
    o->out = c->val;
    return 0;
}

static int set_image_format(Options *o, const OptCall *c)
{
    if (!strcmp(c->val, "png"))
        o->image_format = IMG_PNG;
    else if (!strcmp(c->val, "ppm"))
        o->image_format = IMG_PPM;
    else
        return bad(c, "png or ppm");
    return 0;
}

static int set_format(Options *o, const OptCall *c)
{
    if (!mesh_format_valid(c->val)) {
        char list[160];
        mesh_formats_short(list, sizeof list);
        snprintf(c->err, c->errlen, "bad value '%s' for %s (a model format: %s; see --formats)", c->val,
                 c->name, list);
        return -1;
    }
    o->format = c->val;
    return 0;
}

static int set_size(Options *o, const OptCall *c)
{
    switch (parse_size(c->val, &o->w, &o->h)) {
    case -1:
        return bad(c, "expected WxH, e.g. 640x480");
    case -2:
        snprintf(c->err, c->errlen, "--size %s: 1 to %d per side", c->val, SCREEN_MAX);
        return -1;
    }
    return 0;
}

/* --preview WxH: a file manager's pane of W x H cells. */
static int set_preview(Options *o, const OptCall *c)
{
    o->preview = 1;
    return set_size(o, c);
}

static int set_view(Options *o, const OptCall *c)
{
    float y, p;
    if (strcmp(c->val, "auto") && view_from_name(c->val, &y, &p)) {
        char words[256];
        name_list(view_word, words, sizeof words);
        return bad(c, words);
    }
    o->view = c->val;
    return 0;
}

/* --yaw, --pitch, --roll: given alone they replace the automatic view. */
static int set_turn_angle(float *dst, Options *o, const OptCall *c)
{
    if (parse_float(c->val, dst))
        return bad(c, "degrees, at most 1e9 in size");
    o->turned = 1;
    return 0;
}

static int set_pan(Options *o, const OptCall *c)
{
    if (parse_floats(c->val, o->pan, 2) || fabsf(o->pan[0]) > 1e4f || fabsf(o->pan[1]) > 1e4f)
        return bad(c, "X,Y, each at most 10000 in size");
    return 0;
}

static int set_fit_from(Options *o, const OptCall *c)
{
    if (parse_floats(c->val, o->fit_from, 3))
        return bad(c, "YAW,PITCH,ROLL in degrees");
    o->has_fit_from = 1;
    return 0;
}

/* --move, --turn, --scale: each adds a placement, in the order given. */
static int add_place(Options *o, const OptCall *c, PlaceKind kind)
{
    if (o->nplace >= MAX_PLACE) {
        snprintf(c->err, c->errlen, "too many --move, --turn and --scale (at most %d)", MAX_PLACE);
        return -1;
    }
    Placement *pl = &o->place[o->nplace];
    pl->kind = kind;
    if (kind == PLACE_MOVE && parse_place(c->val, 3, pl))
        return bad(c, "I:X,Y,Z with I the object's number from 1 to 65535 and X, Y, Z from -1e9 to 1e9");
    if (kind == PLACE_TURN && parse_place(c->val, 3, pl))
        return bad(c, "I:YAW,PITCH,ROLL with I the object's number from 1 to 65535 and the angles from -1e9 to 1e9 degrees");
    if (kind == PLACE_SCALE && (parse_place(c->val, 1, pl) || !(pl->v[0] >= 1e-3f && pl->v[0] <= 1e3f)))
        return bad(c, "I:F with I the object's number from 1 to 65535 and F from 0.001 to 1000");
    o->nplace++;
    return 0;
}

static int set_persp(Options *o, const OptCall *c)
{
    if (parse_float(c->val, &o->fov) || o->fov <= 1 || o->fov >= 179)
        return bad(c, "a field of view in degrees, more than 1 and less than 179");
    o->persp = 1;
    return 0;
}

static int set_samples(Options *o, const OptCall *c)
{
    long n;
    if (parse_int(c->val, 1, 16, &n) || (n != 1 && n != 4 && n != 9 && n != 16))
        return bad(c, "1, 4, 9 or 16");
    o->samples = (int)n;
    return 0;
}

static int set_max_polys(Options *o, const OptCall *c)
{
    long n;
    if (parse_int(c->val, 1, 2000000000L, &n))
        return bad(c, "1 to 2000000000");
    o->max_polys = (uint64_t)n;
    return 0;
}

/* "512M", "2G", "1.5G", or bytes: the memory a load may take. */
static int set_max_memory(Options *o, const OptCall *c)
{
    char *end;
    double v = strtod(c->val, &end);
    double unit = *end == 'k' || *end == 'K' ? 1e3 : *end == 'M' ? 1048576.0 : *end == 'G' ? 1073741824.0
                : *end == 'T' ? 1099511627776.0 : 1;
    if (unit != 1)
        end++;
    if (end == c->val || *end || !(v * unit >= 16 * 1048576.0) || v * unit > 1e18)
        return bad(c, "a size of at least 16M (512M, 2G, or bytes)");
    o->max_memory = (uint64_t)(v * unit);
    return 0;
}

static int set_light(Options *o, const OptCall *c)
{
    if (parse_floats(c->val, o->light, 2))
        return bad(c, "YAW,PITCH in degrees");
    return 0;
}

static int set_ortho(Options *o, const OptCall *c)
{
    (void)c;
    o->persp = 0;
    return 0;
}

static int set_algo(Options *o, const OptCall *c)
{
    o->algo = c->val;
    return 0;
}

static int set_dump_ids(Options *o, const OptCall *c)
{
    o->dump_ids = c->val;
    return 0;
}

static int set_dump_screen(Options *o, const OptCall *c)
{
    o->dump_screen = c->val;
    return 0;
}

static int set_up(Options *o, const OptCall *c)
{
    return set_name(&o->up, c, up_axis_from_name, up_word);
}

static int pixel_proto_from_name(const char *name)
{
    for (int i = 0; i < PIX_COUNT; i++)
        if (!strcmp(name, pixel_proto_names[i]))
            return i;
    return -1;
}

/* --mode: a text mode (half, ascii, braille), or the terminal's pixels
 * (sixel, kitty, iterm), cells (text only) or auto (ask the terminal) */
static int set_mode(Options *o, const OptCall *c)
{
    if (mode_from_name(c->val) < 0 && pixel_proto_from_name(c->val) >= 0) {
        o->pixels = pixel_proto_from_name(c->val);
        return 0;
    }
    return set_name(&o->mode, c, mode_from_name, mode_word);
}

static int set_colour(Options *o, const OptCall *c)
{
    return set_name(&o->colour, c, colour_from_name, colour_word);
}

static int set_shade(Options *o, const OptCall *c)
{
    return set_name(&o->shade, c, shade_from_name, shade_word);
}

static int set_order(Options *o, const OptCall *c)
{
    return set_name(&o->order, c, order_from_name, order_word);
}

static int set_layout(Options *o, const OptCall *c)
{
    return set_name(&o->layout, c, layout_from_name, layout_word);
}

static int set_yaw(Options *o, const OptCall *c)
{
    return set_turn_angle(&o->yaw, o, c);
}

static int set_pitch(Options *o, const OptCall *c)
{
    return set_turn_angle(&o->pitch, o, c);
}

static int set_roll(Options *o, const OptCall *c)
{
    return set_turn_angle(&o->roll, o, c);
}

static int set_zoom(Options *o, const OptCall *c)
{
    return set_float(&o->zoom, c, 1e-3f, 1e3f, "from 0.001 to 1000");
}

static int set_crease(Options *o, const OptCall *c)
{
    return set_float(&o->crease, c, 0, 180, "degrees from 0 to 180");
}

static int set_ambient(Options *o, const OptCall *c)
{
    return set_float(&o->ambient, c, 0, 1, "from 0 to 1");
}

static int set_move(Options *o, const OptCall *c)
{
    return add_place(o, c, PLACE_MOVE);
}

static int set_turn(Options *o, const OptCall *c)
{
    return add_place(o, c, PLACE_TURN);
}

static int set_scale(Options *o, const OptCall *c)
{
    return add_place(o, c, PLACE_SCALE);
}

static int set_views(Options *o, const OptCall *c)
{
    return set_int(&o->views, c, 1, 100000, "1 to 100000");
}

static int set_threads(Options *o, const OptCall *c)
{
    return set_int(&o->threads, c, 1, 64, "1 to 64");
}

static int set_grid(Options *o, const OptCall *c)
{
    return set_int(&o->grid, c, 1, 100, "1 to 100");
}

static int set_turntable(Options *o, const OptCall *c)
{
    return set_int(&o->turntable, c, 1, 3600, "1 to 3600 frames");
}

static int set_max_locations(Options *o, const OptCall *c)
{
    return set_int(&o->max_locations, c, 0, 10000000, "0 to 10000000");
}

static int set_problem(Options *o, const OptCall *c)
{
    return set_int(&o->problem, c, 1, INT_MAX, "a problem's number, 1 the first");
}

static int set_section(Options *o, const OptCall *c)
{
    char why[160];
    if (o->nsections >= SECTION_MAX) {
        snprintf(c->err, c->errlen, "%s: at most %d planes", c->name, SECTION_MAX);
        return -1;
    }
    if (section_parse(c->val, &o->section[o->nsections], why, sizeof why)) {
        snprintf(c->err, c->errlen, "%s '%.40s': %s", c->name, c->val, why);
        return -1;
    }
    o->nsections++;
    return 0;
}

static int set_fps(Options *o, const OptCall *c)
{
    return set_int(&o->fps, c, 1, 1000, "1 to 1000");
}

static int set_max_rate(Options *o, const OptCall *c)
{
    return set_int(&o->max_rate, c, 1, 10000000, "KB a second, 1 to 10000000");
}

static int set_point_size(Options *o, const OptCall *c)
{
    return set_int(&o->point_size, c, 1, POINT_SIZE_MAX, "pixels, 1 to 16");
}

static int set_line_width(Options *o, const OptCall *c)
{
    return set_int(&o->line_width, c, 1, POINT_SIZE_MAX, "pixels, 1 to 16");
}

static int set_bg(Options *o, const OptCall *c)
{
    if (!strcmp(c->val, "default")) {
        o->bg = NULL;
        return 0;
    }
    if (backdrop_parse(c->val, o->bg_rgb)) {
        snprintf(c->err, c->errlen, "bad value '%s' for %s (default, #rrggbb, #rgb or a name: %s)", c->val, c->name,
                 backdrop_names);
        return -1;
    }
    o->bg = c->val;
    return 0;
}

static int set_contrast(Options *o, const OptCall *c)
{
    return set_float(&o->contrast, c, 0, CONTRAST_MAX, "an OKLab lightness from 0 (off) to 0.4");
}

/* --repair[=STEPS]: the steps named (a comma list), or all of them. */
static int set_repair(Options *o, const OptCall *c)
{
    static const struct {
        const char *name;
        unsigned    bit;
    } steps[] = {
        { "weld", REPAIR_WELD },   { "clean", REPAIR_CLEAN },       { "winding", REPAIR_WINDING },
        { "holes", REPAIR_HOLES }, { "manifold", REPAIR_MANIFOLD }, { "all", REPAIR_DEFAULT },
    };
    static const char words[] = "a comma list of weld, clean, winding, holes, manifold, or all";
    if (!c->val) {
        o->repair = REPAIR_DEFAULT;
        return 0;
    }
    unsigned got = 0;
    for (const char *p = c->val;;) {
        size_t n = strcspn(p, ",");
        size_t i = 0;
        while (i < sizeof steps / sizeof steps[0] && (strlen(steps[i].name) != n || strncmp(steps[i].name, p, n)))
            i++;
        if (i == sizeof steps / sizeof steps[0])
            return bad(c, words);
        got |= steps[i].bit;
        if (!p[n])
            break;
        p += n + 1;
    }
    o->repair = got;
    return 0;
}

static int set_weld(Options *o, const OptCall *c)
{
    double v;
    if (parse_double(c->val, &v) || !(v > 0 && v <= 1e9))
        return bad(c, "a distance in file units, more than 0 and at most 1e9");
    o->weld = v;
    return 0;
}

static int set_max_hole(Options *o, const OptCall *c)
{
    long n;
    if (parse_int(c->val, 1, 2000000000L, &n))
        return bad(c, "edges, 1 to 2000000000");
    o->max_hole = (uint32_t)n;
    return 0;
}

static int set_tolerance(Options *o, const OptCall *c)
{
    double v;
    if (parse_double(c->val, &v) || v < 0)
        return bad(c, "a distance in the files' units, 0 or more");
    o->tolerance = v;
    return 0;
}

/* --show's words, in DiffShow's order (diff.h) */
static int set_show(Options *o, const OptCall *c)
{
    static const char *const words[] = { "both", "a", "b", "heat" };
    for (int i = 0; i < (int)(sizeof words / sizeof *words); i++)
        if (!strcmp(c->val, words[i])) {
            o->show = i;
            return 0;
        }
    return bad(c, "both, a, b or heat");
}

/* ==== Will it print, and its measures (printq.h) ==== */

static int set_bed(Options *o, const OptCall *c)
{
    char *end;
    const char *p = c->val;
    for (int k = 0; k < 3; k++) {
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || errno || !(v > 0 && v <= 1e9) || (k < 2 ? *end != 'x' && *end != 'X' : *end != 0))
            return bad(c, "WxDxH: the bed's width, depth and height, more than 0 (e.g. 220x220x250)");
        o->bed[k] = v;
        p = end + 1;
    }
    return 0;
}

static int set_unit(Options *o, const OptCall *c)
{
    if (printq_unit_mm(c->val) == 0)
        return bad(c, "mm, in or m");
    o->unit = c->val;
    return 0;
}

/* --overhang[=DEG]: 45 when given without a value. */
static int set_overhang(Options *o, const OptCall *c)
{
    o->overhang = 1;
    o->overhang_deg = 45;
    if (c->val && (parse_float(c->val, &o->overhang_deg) || !(o->overhang_deg > 0 && o->overhang_deg < 90)))
        return bad(c, "degrees from the vertical, more than 0 and less than 90");
    return 0;
}

static int set_min_thickness(Options *o, const OptCall *c)
{
    double v;
    if (parse_double(c->val, &v) || !(v > 0 && v <= 1e9))
        return bad(c, "a thickness in the report's unit, more than 0");
    o->min_thickness = v;
    return 0;
}

/* --measure A: the first point; the next ones follow as words (cli.c). */
static int set_measure(Options *o, const OptCall *c)
{
    if (o->nmeasure || printq_point_parse(c->val, &o->measure[0]))
        return bad(c, "a point X,Y,Z or a vertex vN, then one or two more: --measure A B [C]");
    o->nmeasure = 1;
    return 0;
}

/* --marks A,B,C: vertices vN, edge midpoints eA-B and face centres fN
 * of the first object, or after I: of object I. */
static int set_marks(Options *o, const OptCall *c)
{
    static const char what[] =
        "up to three points, comma apart: vertices vN, edge midpoints eA-B, face centres fN, or I:vN of object I";
    MeasureMarks *m = &o->marks;
    m->n = 0;
    for (const char *p = c->val; *p;) {
        if (m->n == MEASURE_MARKS || app_measure_pick_parse(&p, &m->mark[m->n]) || (*p && *p != ','))
            return bad(c, what);
        m->n++;
        p += *p == ',';
    }
    return m->n ? 0 : bad(c, what);
}

/* ==== The table ==== */

const char *const cli_section_names[OPTSEC_COUNT] = {
    [OPTSEC_GENERAL] = "General",
    [OPTSEC_INPUT] = "Input",
    [OPTSEC_OUTPUT] = "Output",
    [OPTSEC_VIEW] = "View",
    [OPTSEC_BENCH] = "Benchmark and performance",
};

/* A flag: no value, sets the int field F of Options to 1. */
#define FLAG(F) .flag = offsetof(Options, F)

/* In man page order within each section. Help lines are at most 56
 * columns, so that --help fits 80 (test_options checks). */
const OptSpec cli_options[] = {
    /* ---- General ---- */
    { "help", 'h', NULL, NULL, OPTSEC_GENERAL, "print this summary of the options and exit", NULL, FLAG(help), 0 },
    { "version", 'V', NULL, NULL, OPTSEC_GENERAL, "print the version and exit", NULL, FLAG(version), 0 },
    { "formats", 0, NULL, NULL, OPTSEC_GENERAL, "list the formats this build reads and exit", NULL, FLAG(formats), 0 },
    /* ---- Input ---- */
    { "format", 0, "NAME", NULL, OPTSEC_INPUT,
      "read FILE as NAME (obj, stl, ply, off, xyz, or an\nassimp format; see --formats)", set_format, 0, OPT_VIEWCMD },
    { "up", 0, NULL, "y z x -y -z -x", OPTSEC_INPUT,
      "the model's up axis (default: as the file's\nformat says: z for STL, 3MF, Blender, ...; else y)", set_up, 0, OPT_VIEWCMD },
    { "flip", 0, NULL, NULL, OPTSEC_INPUT, "reverse every face's winding (inside out)", NULL, FLAG(flip), OPT_VIEWCMD },
    { "strict", 0, NULL, NULL, OPTSEC_INPUT,
      "refuse a file with a statement zview cannot read\n(default: skip those, show the rest, warn once)",
      NULL, FLAG(strict), 0 },
    { "no-sandbox", 0, NULL, NULL, OPTSEC_INPUT,
      "load in zview's own process, not in a sandboxed child\n(README: Security)", NULL, FLAG(no_sandbox), 0 },
    { "max-memory", 0, "SIZE", NULL, OPTSEC_INPUT,
      "memory a load may take (512M, 2G; default: 4 times\nthe input, 48 through assimp, at least 512M)", set_max_memory, 0, 0 },
    { "points", 0, NULL, NULL, OPTSEC_INPUT, "every vertex as a point, the faces left out", NULL, FLAG(points),
      OPT_VIEWCMD },
    /* ---- Output ---- */
    { "print", 'p', NULL, NULL, OPTSEC_OUTPUT, "write one frame to stdout as text, no curses", NULL, FLAG(print), 0 },
    { "output", 'o', "FILE", NULL, OPTSEC_OUTPUT,
      "write the image to FILE.png or FILE.ppm (- is\nstdout, PNG), or the text --print gives to FILE.txt",
      set_output, 0, 0 },
    { "image-format", 0, NULL, "png ppm", OPTSEC_OUTPUT, "the image format for -o (default: by the name)",
      set_image_format, 0, 0 },
    { "turntable", 0, "N", NULL, OPTSEC_OUTPUT,
      "N frames turning 360/N degrees each about the\nvertical, to -o PATTERN (one integer conversion:\n"
      "out-%03d.png; frames from 0) or with --print",
      set_turntable, 0, 0 },
    { "print-view", 0, NULL, NULL, OPTSEC_OUTPUT, "the viewer prints the command line of its last\nview on quitting",
      NULL, FLAG(print_view), 0 },
    { "sketch", 0, NULL, NULL, OPTSEC_OUTPUT,
      "the viewer starts on an empty canvas: draw polygons\nand watch the algorithms hide them (D in the viewer)",
      NULL, FLAG(sketch), 0 },
    { "size", 's', "WxH", NULL, OPTSEC_OUTPUT, "pixels for -o (default 640x480); cells for --print\nand the viewer",
      set_size, 0, 0 },
    { "mode", 0, NULL, "half ascii braille sixel kitty iterm cells auto", OPTSEC_OUTPUT,
      "text mode (default: half on UTF-8, else ascii), or\nthe terminal's pixels: sixel, kitty, iterm, auto\n(what the terminal answers), cells (text only)",
      set_mode, 0, OPT_VIEWCMD },
    { "color", 0, NULL, "truecolor 256 16 8 none", OPTSEC_OUTPUT,
      "colours (default: from COLORTERM, TERM, NO_COLOR)", set_colour, 0, 0 },
    { "colour", 0, NULL, "truecolor 256 16 8 none", OPTSEC_OUTPUT, NULL, set_colour, 0, OPT_ALIAS },
    { "bg", 0, "COLOR", "default black white grey", OPTSEC_OUTPUT,
      "the background: default (the terminal's own; for\n-o black, or white behind a dark model), a name\n"
      "or #rrggbb (painted)",
      set_bg, 0, OPT_VIEWCMD },
    { "contrast", 0, "L", NULL, OPTSEC_OUTPUT,
      "keep drawn pixels L (OKLab lightness) from the\nbackground (default 0.2; 0: colours as given)",
      set_contrast, 0, OPT_VIEWCMD },
    { "edges", 0, NULL, NULL, OPTSEC_OUTPUT, "outline silhouettes, creases and depth steps", NULL, FLAG(edges),
      OPT_VIEWCMD },
    { "point-size", 0, "N", NULL, OPTSEC_OUTPUT, "points as N x N pixel squares (1 to 16, default 1)",
      set_point_size, 0, OPT_VIEWCMD },
    { "line-width", 0, "N", NULL, OPTSEC_OUTPUT, "lines N pixels wide (1 to 16, default 1)", set_line_width, 0,
      OPT_VIEWCMD },
    { "wireframe", 0, NULL, NULL, OPTSEC_OUTPUT, "every edge of the faces as a line, hidden where\nfaces hide it",
      NULL, FLAG(wireframe), OPT_VIEWCMD },
    { "no-textures", 0, NULL, NULL, OPTSEC_OUTPUT,
      "faces in their base colours, textures not drawn\n(t in the viewer)", NULL, FLAG(no_textures), OPT_VIEWCMD },
    { "crease", 0, "DEG", NULL, OPTSEC_OUTPUT,
      "smooth shading and --edges: a sharper edge is a\ncrease (default 60)", set_crease, 0, OPT_VIEWCMD },
    { "light", 0, "YAW,PITCH", NULL, OPTSEC_OUTPUT, "the light's direction in degrees from the view\n(default -34,37)",
      set_light, 0, OPT_VIEWCMD },
    { "ambient", 0, "F", NULL, OPTSEC_OUTPUT, "ambient light, 0 to 1 (default 0.22)", set_ambient, 0, OPT_VIEWCMD },
    { "samples", 0, "N", "1 4 9 16", OPTSEC_OUTPUT,
      "samples per pixel, 1, 4, 9 or 16, averaged (default\n4 for text and the viewer, 1 for -o)", set_samples, 0,
      OPT_VIEWCMD },
    { "shade", 0, NULL, "lambert smooth depth id", OPTSEC_OUTPUT, "shading (default lambert: flat per face)",
      set_shade, 0, OPT_VIEWCMD },
    { "info", 0, NULL, NULL, OPTSEC_OUTPUT, "print file statistics (with --algo: render ones)", NULL, FLAG(info),
      0 },
    { "check", 0, NULL, NULL, OPTSEC_OUTPUT,
      "is each model right: holes, flipped, non-manifold\nand crossing faces, parts, size, volume (exit 3\n"
      "on problems); with --print or -o the picture too",
      NULL, FLAG(check), 0 },
    { "repair", 0, "STEPS", NULL, OPTSEC_OUTPUT,
      "write a repaired copy of FILE to -o OUT (.stl, .obj,\n.ply): STEPS a comma list of weld, clean,\n"
      "winding, holes, manifold (default all); says what\nit did, and the check before and after (exit 3\n"
      "when problems remain)",
      set_repair, 0, OPT_OPTIONAL },
    { "weld", 0, "EPS", NULL, OPTSEC_OUTPUT, "--repair: weld vertices up to EPS apart (file\nunits; default: at one position only)",
      set_weld, 0, 0 },
    { "max-hole", 0, "N", NULL, OPTSEC_OUTPUT, "--repair: leave holes of more than N edges open", set_max_hole, 0,
      0 },
    { "problems", 0, NULL, NULL, OPTSEC_OUTPUT,
      "draw what the check finds on the model: holes and\nnon-manifold edges as lines, faces seen from\n"
      "inside and crossing faces coloured (! in the viewer)",
      NULL, FLAG(problems), OPT_VIEWCMD },
    { "max-locations", 0, "N", NULL, OPTSEC_OUTPUT,
      "with --check --json: where the first N problems of\neach kind are (default 100; the counts are whole)",
      set_max_locations, 0, 0 },
    { "problem", 0, "K", NULL, OPTSEC_OUTPUT,
      "the picture framed on the K-th problem the check\nfinds, drawn over the model (. and , in the viewer)",
      set_problem, 0, 0 },
    { "section", 0, "PLANE", NULL, OPTSEC_OUTPUT,
      "cut the model open: AXIS=V (x, y or z at V, file\nunits; -x=V keeps what lies above V) or\n"
      "X,Y,Z:NX,NY,NZ (a point and a normal); what lies\nbeyond every plane given goes, the cut is capped;\n"
      "with --check each plane's area, perimeter and\nloops (/ in the viewer)",
      set_section, 0, OPT_VIEWCMD },
    { "parts", 0, NULL, NULL, OPTSEC_OUTPUT, "each connected part of the model its own colour\n(@ in the viewer)",
      NULL, FLAG(parts), OPT_VIEWCMD },
    { "diff", 0, NULL, NULL, OPTSEC_OUTPUT,
      "how B differs from A (zview --diff A B): both in\none frame, coloured by the distance to the other\n"
      "(V in the viewer), or a report; exit 3 when they\ndiffer beyond the tolerance",
      NULL, FLAG(diff), OPT_VIEWCMD },
    { "tolerance", 0, "D", NULL, OPTSEC_OUTPUT,
      "with --diff: distances up to D are the same\n(default 0.1% of the bounding box's diagonal)", set_tolerance,
      0, OPT_VIEWCMD },
    { "show", 0, NULL, "both a b heat", OPTSEC_OUTPUT,
      "with --diff: both models, A or B alone, or a heat\nmap of the distance (default both)", set_show, 0,
      OPT_VIEWCMD },
    { "quiet", 0, NULL, NULL, OPTSEC_OUTPUT, "with --diff: no report, the exit status alone", NULL, FLAG(quiet), 0 },
    { "bed", 0, "WxDxH", NULL, OPTSEC_OUTPUT,
      "with --check (which it turns on): does the model\nfit a bed of W x D x H, and in which of the six\n"
      "orders of its axes",
      set_bed, 0, 0 },
    { "unit", 0, NULL, "mm in m", OPTSEC_OUTPUT,
      "the files' length unit, when the format states\nnone (or another): the figures then in mm",
      set_unit, 0, 0 },
    { "overhang", 0, "DEG", NULL, OPTSEC_OUTPUT,
      "colour the faces leaning out past DEG from the\nvertical (default 45; --up is up); --check gives\n"
      "their area",
      set_overhang, 0, OPT_OPTIONAL | OPT_VIEWCMD },
    { "thickness", 0, NULL, NULL, OPTSEC_OUTPUT,
      "colour the faces by wall thickness (a ray inward\nfrom each face), red thin to blue thick",
      NULL, FLAG(thickness), OPT_VIEWCMD },
    { "min-thickness", 0, "T", NULL, OPTSEC_OUTPUT,
      "with --check (which it turns on): the area of the\nwalls thinner than T, and the thinnest point",
      set_min_thickness, 0, 0 },
    { "measure", 0, "A B [C]", NULL, OPTSEC_OUTPUT,
      "print the distance and dx, dy, dz from A to B (and\nthe angle ABC): points X,Y,Z or vertices vN",
      set_measure, 0, 0 },
    { "marks", 0, "A,B,C", NULL, OPTSEC_OUTPUT,
      "mark up to three points (vertices vN, edge\nmidpoints eA-B, face centres fN; I:vN of object I)\non the picture, joined (the viewer's M keeps them)",
      set_marks, 0, OPT_VIEWCMD },
    { "preview", 0, "WxH", NULL, OPTSEC_OUTPUT,
      "as a file manager's previewer (lf, fzf, ranger,\nyazi): FILE in W x H cells, the last row the\n"
      "check's verdict; a file not read says why there",
      set_preview, 0, 0 },
    { "textconv", 0, NULL, NULL, OPTSEC_OUTPUT,
      "with --check: the report as git's textconv wants\nit (the file unnamed, exit status 0 once read)", NULL,
      FLAG(textconv), 0 },
    { "watch", 0, NULL, NULL, OPTSEC_INPUT,
      "the viewer reads the files again when they change\n(an exporter's rename too), keeping the view", NULL,
      FLAG(watch), 0 },
    { "dump-ids", 0, "FILE", NULL, OPTSEC_OUTPUT, "face-id buffer: W*H little-endian int32, -1 = none",
      set_dump_ids, 0, 0 },
    { "dump-screen", 0, "FILE", NULL, OPTSEC_OUTPUT, "screen-space polygons as OBJ text", set_dump_screen, 0, 0 },
    /* ---- View ---- */
    { "algo", 'a', "NAME", "zbuffer scanline span hzb hzb-octree all", OPTSEC_VIEW,
      "zbuffer (default), scanline, span, hzb, hzb-octree;\nwith --bench also all, or a list a,b", set_algo, 0,
      OPT_VIEWCMD },
    { "view", 0, "NAME", "auto front back left right top bottom iso", OPTSEC_VIEW,
      "front, back, left, right, top, bottom, iso, or auto\n(the default: the three-quarter view that sees most)",
      set_view, 0, 0 },
    { "yaw", 0, "DEG", NULL, OPTSEC_VIEW, "turn the scene about the vertical (on top of --view)", set_yaw, 0,
      OPT_VIEWCMD },
    { "pitch", 0, "DEG", NULL, OPTSEC_VIEW, "turn the scene about the horizontal", set_pitch, 0, OPT_VIEWCMD },
    { "roll", 0, "DEG", NULL, OPTSEC_VIEW, "turn the scene about the view direction", set_roll, 0, OPT_VIEWCMD },
    { "zoom", 0, "F", NULL, OPTSEC_VIEW, "scale (1 = fit to 90% of the view; 0.001 to 1000)", set_zoom, 0,
      OPT_VIEWCMD },
    { "pan", 0, "X,Y", NULL, OPTSEC_VIEW, "move the view right and up (fractions of the\nscene's radius)", set_pan,
      0, OPT_VIEWCMD },
    { "fit-from", 0, "YAW,PITCH,ROLL", NULL, OPTSEC_VIEW, "the turn the view was fitted at (default: the turn)",
      set_fit_from, 0, OPT_VIEWCMD },
    { "move", 0, "I:X,Y,Z", NULL, OPTSEC_VIEW, "move object I (1 = the first) in world units", set_move, 0,
      OPT_VIEWCMD },
    { "turn", 0, "I:YAW,PITCH,ROLL", NULL, OPTSEC_VIEW, "turn object I about its centre (degrees)", set_turn, 0,
      OPT_VIEWCMD },
    { "scale", 0, "I:F", NULL, OPTSEC_VIEW, "scale object I about its centre", set_scale, 0, OPT_VIEWCMD },
    { "persp", 0, "FOV", NULL, OPTSEC_VIEW, "perspective, FOV degrees of vertical field of view", set_persp, 0,
      OPT_VIEWCMD },
    { "ortho", 0, NULL, NULL, OPTSEC_VIEW, "orthographic (the default)", set_ortho, 0, 0 },
    { "cull", 0, NULL, NULL, OPTSEC_VIEW, "back-face culling (off by default)", NULL, FLAG(cull), OPT_VIEWCMD },
    { "layout", 0, NULL, "row grid none", OPTSEC_VIEW,
      "several files side by side at a common size (row,\nthe default; grid), or where their coordinates put\n"
      "them (none)",
      set_layout, 0, OPT_VIEWCMD },
    { "grid", 0, "N", NULL, OPTSEC_VIEW, "N x N x N copies of the scene (a deep scene)", set_grid, 0,
      OPT_VIEWCMD },
    { "order", 0, NULL, "file front-to-back back-to-front shuffle", OPTSEC_VIEW,
      "the order polygons reach the algorithm (same picture)", set_order, 0, 0 },
    { "max-polys", 0, "N", NULL, OPTSEC_VIEW, "refuse scenes of more polygons (default: what fits)", set_max_polys, 0,
      0 },
    /* ---- Benchmark and performance ---- */
    { "bench", 0, NULL, NULL, OPTSEC_BENCH, "time the algorithms (all, or --algo) on views of\neach file", NULL,
      FLAG(bench), 0 },
    { "bench-tty", 0, NULL, NULL, OPTSEC_BENCH, "bytes written per frame for a scripted rotation", NULL,
      FLAG(bench_tty), 0 },
    { "views", 0, "N", NULL, OPTSEC_BENCH, "with --bench: views per model (default 8)", set_views, 0, 0 },
    { "json", 0, NULL, NULL, OPTSEC_BENCH, "with --bench, --check, --diff or --repair: JSON, not\ntext",
      NULL, FLAG(json), 0 },
    { "threads", 'j', "N", NULL, OPTSEC_BENCH, "threads for every stage (default: all cores)", set_threads, 0, 0 },
    { "fps", 0, "N", NULL, OPTSEC_BENCH, "auto-rotate frame cap in the viewer (default 30)", set_fps, 0, 0 },
    { "max-rate", 0, "KB", NULL, OPTSEC_BENCH,
      "the link's speed in KB/s for the viewer's still\nimages in pixels (default 1000): one goes only\nwhen it takes at most 0.5 s", set_max_rate, 0, 0 },
};

const int cli_noptions = (int)(sizeof cli_options / sizeof cli_options[0]);

_Static_assert(sizeof cli_options / sizeof cli_options[0] <= CLI_OPTIONS_MAX,
               "CLI_OPTIONS_MAX bounds getopt's table in cli_parse");

const OptSpec *cli_option(const char *name)
{
    for (int i = 0; i < cli_noptions; i++)
        if (!strcmp(cli_options[i].name, name))
            return &cli_options[i];
    return NULL;
}
