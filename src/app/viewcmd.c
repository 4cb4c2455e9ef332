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
#include <string.h>

#include "app.h"

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
 * quotes (a quote inside becomes '\''). */
static void put_word(CmdBuf *o, const char *w)
{
    int plain = *w != 0;
    for (const char *c = w; *c; c++)
        if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./,:=+@%", *c))
            plain = 0;
    if (plain) {
        put(o, " %s", w);
        return;
    }
    put(o, " '");
    for (const char *c = w; *c; c++)
        put(o, *c == '\'' ? "'\\''" : "%c", *c);
    put(o, "'");
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

int view_command(char *buf, size_t len, const Options *opt, const Scene *s, const ViewSettings *v)
{
    CmdBuf o = { buf, len, 0, 0 };
    const Camera *c = &s->cam;
    put(&o, "zview");
    /* the turn, and where it was fitted from when that differs */
    put(&o, " --yaw %.9g --pitch %.9g", deg(c->yaw), deg(c->pitch));
    if (deg(c->roll) != 0)
        put(&o, " --roll %.9g", deg(c->roll));
    if (c->fit_yaw != c->yaw || c->fit_pitch != c->pitch || c->fit_roll != c->roll)
        put(&o, " --fit-from %.9g,%.9g,%.9g", deg(c->fit_yaw), deg(c->fit_pitch), deg(c->fit_roll));
    if (c->zoom != 1)
        put(&o, " --zoom %.9g", c->zoom);
    if (c->pan.x != 0 || c->pan.y != 0)
        put(&o, " --pan %.9g,%.9g", c->pan.x, c->pan.y);
    if (c->persp)
        put(&o, " --persp %.9g", c->fov_deg);
    /* objects away from their home placement */
    for (uint32_t i = 0; i < s->nbase_objs && (int)i < s->nobjs; i++) {
        const Object *ob = &s->objs[i];
        Vec3 d = v3_sub(ob->offset, ob->home);
        if (d.x != 0 || d.y != 0 || d.z != 0)
            put(&o, " --move %u:%.9g,%.9g,%.9g", i + 1, d.x, d.y, d.z);
        if (ob->yaw != 0 || ob->pitch != 0 || ob->roll != 0)
            put(&o, " --turn %u:%.9g,%.9g,%.9g", i + 1, deg(ob->yaw), deg(ob->pitch), deg(ob->roll));
        if (ob->scale != ob->home_scale)
            put(&o, " --scale %u:%.9g", i + 1, ob->scale / ob->home_scale);
    }
    /* the settings that change the picture */
    if (v->cull)
        put(&o, " --cull");
    if (v->mode >= 0)
        put(&o, " --mode %s", mode_names[v->mode]);
    if (v->shade != SHADE_LAMBERT)
        put(&o, " --shade %s", shade_names[v->shade]);
    if ((v->shade == SHADE_SMOOTH || v->edges) && v->crease != SHADE_CREASE_DEFAULT)
        put(&o, " --crease %.9g", v->crease);
    if (v->edges)
        put(&o, " --edges");
    if (v->wireframe)
        put(&o, " --wireframe");
    if (v->point_size > 1)
        put(&o, " --point-size %d", v->point_size);
    if (v->line_width > 1)
        put(&o, " --line-width %d", v->line_width);
    if (opt->points)
        put(&o, " --points");
    if (s->light.yaw != LIGHT_YAW || s->light.pitch != LIGHT_PITCH)
        put(&o, " --light %.9g,%.9g", s->light.yaw, s->light.pitch);
    if (s->light.ambient != LIGHT_AMBIENT)
        put(&o, " --ambient %.9g", s->light.ambient);
    if (v->samples > 0 && v->samples != TEXT_SAMPLES)
        put(&o, " --samples %d", v->samples);
    if (v->algo && strcmp(v->algo, "zbuffer"))
        put(&o, " --algo %s", v->algo);
    if (s->nobjs > 0 && s->objs[0].up != UP_Y)
        put(&o, " --up %s", up_axis_name(s->objs[0].up));
    if (opt->flip)
        put(&o, " --flip");
    if (opt->format)
        put(&o, " --format %s", opt->format);
    if (opt->nfiles > 1 && opt->layout != LAYOUT_ROW)
        put(&o, " --layout %s", layout_names[opt->layout]);
    if (opt->grid > 1)
        put(&o, " --grid %d", opt->grid);
    if (opt->nfiles > 0)
        put(&o, " --");
    for (int i = 0; i < opt->nfiles; i++)
        put_word(&o, opt->files[i]);
    return o.full ? -1 : 0;
}
