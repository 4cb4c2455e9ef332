/* viewcmd.c: the command line that reproduces a view.
 *
 * What the viewer's keys change is all in the scene (the camera's turn,
 * the turn it was fitted from, zoom and pan, each object's placement)
 * and in a few settings (display mode, shading, light, algorithm,
 * culling, samples, projection). Every one of them has an option, so a
 * view someone found can be written down, pasted into a shell, put into
 * a script with --print or -o, or sent to a colleague. Only what differs
 * from the defaults is written; numbers keep enough digits to give the
 * same picture. */

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "safetext.h"

typedef struct {
    char  *buf;
    size_t len, at;
    int    full;        /* ran out of room */
} CmdBuf;

static void put(CmdBuf *o, const char *fmt, ...)
{
    if (o->full)
        return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(o->buf + o->at, o->len - o->at, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= o->len - o->at)
        o->full = 1;
    else
        o->at += (size_t)n;
}

/* A word for a POSIX shell: as is when it is plain, else in single
 * quotes (a quote inside becomes '\''). A word with a character that
 * is not safe to print (safetext.h: ESC, a newline, bytes that are not
 * UTF-8) is written $'...' with those bytes as \xNN: the command is
 * printed and pasted, and the terminal must not act on the name. */
static void put_word(CmdBuf *o, const char *w)
{
    int plain = *w != 0, printable = 1;
    for (const char *c = w; *c;) {
        size_t n;
        printable &= safetext_plain(c, &n);
        if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./,:=+@%", *c))
            plain = 0;
        c += n;
    }
    if (plain) {
        put(o, " %s", w);
        return;
    }
    if (printable) {
        put(o, " '");
        for (const char *c = w; *c; c++)
            put(o, *c == '\'' ? "'\\''" : "%c", *c);
        put(o, "'");
        return;
    }
    put(o, " $'");
    for (const char *c = w; *c;) {
        size_t n;
        if (!safetext_plain(c, &n))
            for (size_t i = 0; i < n; i++)
                put(o, "\\x%02x", (unsigned char)c[i]);
        else if (*c == '\'' || *c == '\\')
            put(o, "\\%c", *c);
        else
            put(o, "%.*s", (int)n, c);
        c += n;
    }
    put(o, "'");
}

static void put_file(CmdBuf *o, const char *path)
{
    char buf[4096 + 3];
    if (path[0] == '-' && path[1] && snprintf(buf, sizeof buf, "./%s", path) < (int)sizeof buf)
        path = buf;
    put_word(o, path);
}

/* Degrees that the command line turns back into exactly these radians
 * (deg2rad of the printed value), so the view comes back to the bit. */
static float deg(float rad)
{
    if (rad == 0)
        return 0;
    float d = rad * (180.0f / ZV_PI);
    float up = d, down = d;
    for (int k = 0; k < 16; k++) {
        if (deg2rad(up) == rad)
            return up;
        if (deg2rad(down) == rad)
            return down;
        up = nextafterf(up, INFINITY);
        down = nextafterf(down, -INFINITY);
    }
    return d;
}

/* ==== the shortest number that gives the value back ====
 * The options read a number as a double and keep it as a float. A float
 * needs up to 9 significant digits to come back, but most values are
 * reached by far fewer ("-25", not "-25.0000019"): the first precision
 * whose text passes the check (what the option does with the number gives
 * back the value) is printed. */

typedef struct {
    char s[32];
} Num;

typedef int (*NumCheck)(float parsed, const float *ctx);

static int same(float x, const float *c) { return x == c[0]; }
static int same_angle(float x, const float *c) { return deg2rad(x) == c[0]; }
static int same_scaled(float x, const float *c) { return c[0] * x == c[1]; }    /* home_scale * F */
static int same_moved(float x, const float *c) { return c[0] + x == c[1]; }     /* home + X */

/* The shortest text, plain ("30", "0.125") or in exponent form ("1e-07")
 * when that is shorter, that passes the check. v: a value that passes it
 * at 9 significant digits (a float comes back). */
static Num shortest(float v, NumCheck ok, const float *ctx)
{
    Num best, n;
    snprintf(best.s, sizeof best.s, "%.9g", (double)v);
    for (int form = 0; form < 2; form++)
        for (int p = form; p <= 9; p++) {
            if (form == 0 && fabsf(v) >= 1e9f)
                break;
            snprintf(n.s, sizeof n.s, form == 0 ? "%.*f" : "%.*g", p, (double)v);
            if (strlen(n.s) < strlen(best.s) && ok((float)strtod(n.s, NULL), ctx))
                best = n;
        }
    return best;
}

static Num num(float v) { return shortest(v, same, (const float[1]){ v }); }
static Num angle(float rad) { return shortest(deg(rad), same_angle, (const float[1]){ rad }); }
static Num scaled(float home, float v) { return shortest(v / home, same_scaled, (const float[2]){ home, v }); }
static Num moved(float home, float v) { return shortest(v - home, same_moved, (const float[2]){ home, v }); }

int view_command(char *buf, size_t len, const Options *opt, const Scene *s, const ViewSettings *v)
{
    CmdBuf o = { buf, len, 0, 0 };
    const Camera *c = &s->cam;
    put(&o, "zview");
    /* the files first, so that options can be appended to the line
     * ($cmd -o out.png); a name that starts with '-' is written ./-x,
     * which no option parser takes for an option ("-" alone stays:
     * standard input) */
    for (int i = 0; i < opt->nfiles; i++)
        put_file(&o, opt->files[i]);
    /* the turn, and where it was fitted from when that differs */
    put(&o, " --yaw %s --pitch %s", angle(c->yaw).s, angle(c->pitch).s);
    if (deg(c->roll) != 0)
        put(&o, " --roll %s", angle(c->roll).s);
    if (c->fit_yaw != c->yaw || c->fit_pitch != c->pitch || c->fit_roll != c->roll)
        put(&o, " --fit-from %s,%s,%s", angle(c->fit_yaw).s, angle(c->fit_pitch).s, angle(c->fit_roll).s);
    if (c->zoom != 1)
        put(&o, " --zoom %s", num(c->zoom).s);
    if (c->pan.x != 0 || c->pan.y != 0)
        put(&o, " --pan %s,%s", num(c->pan.x).s, num(c->pan.y).s);
    if (c->persp)
        put(&o, " --persp %s", num(c->fov_deg).s);
    /* objects away from their home placement */
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++) {
        const Object *ob = &s->objs[i];
        Vec3 h = ob->home, at = ob->offset;
        if (at.x != h.x || at.y != h.y || at.z != h.z)
            put(&o, " --move %u:%s,%s,%s", i + 1, moved(h.x, at.x).s, moved(h.y, at.y).s, moved(h.z, at.z).s);
        if (ob->yaw != 0 || ob->pitch != 0 || ob->roll != 0)
            put(&o, " --turn %u:%s,%s,%s", i + 1, angle(ob->yaw).s, angle(ob->pitch).s, angle(ob->roll).s);
        if (ob->scale != ob->home_scale)
            put(&o, " --scale %u:%s", i + 1, scaled(ob->home_scale, ob->scale).s);
    }
    /* the settings that change the picture */
    if (v->cull)
        put(&o, " --cull");
    if (v->mode >= 0)
        put(&o, " --mode %s", mode_names[v->mode]);
    if (v->shade != SHADE_LAMBERT)
        put(&o, " --shade %s", shade_names[v->shade]);
    if ((v->shade == SHADE_SMOOTH || v->edges) && v->crease != SHADE_CREASE_DEFAULT)
        put(&o, " --crease %s", num(v->crease).s);
    if (v->edges)
        put(&o, " --edges");
    if (v->wireframe)
        put(&o, " --wireframe");
    if (v->no_textures)
        put(&o, " --no-textures");
    if (v->problems)
        put(&o, " --problems");
    if (v->parts)
        put(&o, " --parts");
    if (v->overhang && v->overhang_deg == 45)
        put(&o, " --overhang");
    else if (v->overhang)
        put(&o, " --overhang=%s", num(v->overhang_deg).s);
    if (v->thickness)
        put(&o, " --thickness");
    /* the cut: a plane whose words start with '-' (-x=2) is joined to
     * its option, which no parser then takes for an option of its own */
    for (int i = 0; i < v->nplanes; i++) {
        char t[SECTION_TEXT];
        section_text(&v->planes[i], t, sizeof t);
        put(&o, " --section%c%s", t[0] == '-' ? '=' : ' ', t);
    }
    if (v->marks && v->marks->n) {
        char marks[128];
        app_measure_option(v->marks, marks, sizeof marks);
        put(&o, " --marks %s", marks);
    }
    if (v->point_size > 1)
        put(&o, " --point-size %d", v->point_size);
    if (v->line_width > 1)
        put(&o, " --line-width %d", v->line_width);
    if (opt->points)
        put(&o, " --points");
    if (s->light.yaw != LIGHT_YAW || s->light.pitch != LIGHT_PITCH)
        put(&o, " --light %s,%s", num(s->light.yaw).s, num(s->light.pitch).s);
    if (s->light.ambient != LIGHT_AMBIENT)
        put(&o, " --ambient %s", num(s->light.ambient).s);
    if (opt->bg) {
        put(&o, " --bg");
        put_word(&o, opt->bg);      /* #rrggbb: quoted, # starts a comment in a shell */
    }
    if (opt->contrast != CONTRAST_DEFAULT)
        put(&o, " --contrast %s", num(opt->contrast).s);
    if (v->samples > 0 && v->samples != TEXT_SAMPLES)
        put(&o, " --samples %d", v->samples);
    if (v->algo && strcmp(v->algo, "zbuffer"))
        put(&o, " --algo %s", v->algo);
    /* the files' own up axes come back by themselves; one set for all
     * (--up, U) is written */
    int up = scene_up_forced(s);
    if (up >= 0)
        put(&o, " --up %s", up_axis_name(up));
    if (opt->flip)
        put(&o, " --flip");
    if (opt->format)
        put(&o, " --format %s", opt->format);
    if (opt->nfiles > 1 && opt->layout != LAYOUT_ROW)
        put(&o, " --layout %s", layout_names[opt->layout]);
    if (opt->grid > 1)
        put(&o, " --grid %d", opt->grid);
    if (opt->diff)
        put(&o, " --diff");
    if (opt->diff && opt->tolerance >= 0)
        put(&o, " --tolerance %.17g", opt->tolerance);
    if (opt->diff && opt->show > 0 && opt->show < 4)
        put(&o, " --show %s", (const char *const[]){ "both", "a", "b", "heat" }[opt->show]);
    return o.full ? -1 : 0;
}
