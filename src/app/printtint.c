/* printtint.c: will it print, on the model (--overhang, --thickness,
 * and the viewer's keys for them): the faces coloured by a question
 * asked of the scene's files. Each file is made a mesh again as the
 * check's picture makes it (scene_check_meshes: the faces keep their
 * indices), asked (printq/: the overhanging faces, the thickness at
 * each face), and the answers laid over the loaded faces as a FaceTint
 * that shading reads through the mark colours (shade/markcolour.c), so
 * that the picture is every algorithm's and every output's. Made again
 * only when the scene or the question changes. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

void print_tint_free(PrintTint *t)
{
    free(t->ft.rgba);
    uint32_t gen = t->ft.gen;
    memset(t, 0, sizeof *t);
    t->ft.gen = gen + 1;
}

/* The up axis of the first loaded object of mesh mi (its file's). */
static int mesh_up(const Scene *s, int mi)
{
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    for (int i = 0; i < nb; i++)
        if (s->objs[i].mesh == &s->meshes[mi])
            return s->objs[i].up;
    return UP_Y;
}

/* The answers of mesh mi over its loaded faces. */
static void lay(const Pipeline *p, int mi, const uint8_t *over, const float *thick, double scale, uint8_t *rgba)
{
    const Scene *s = p->scene;
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    for (int i = 0; i < nb; i++) {
        const Object *o = &s->objs[i];
        if (o->mesh != &s->meshes[mi])
            continue;
        for (uint32_t f = 0; f < o->face_count; f++) {
            uint8_t *c = &rgba[4 * ((size_t)o->face_base + f)];
            uint32_t mf = o->face_first + f;
            if (thick && thick[mf] >= 0) {
                shade_thickness_colour(scale > 0 ? thick[mf] / scale : 0, c);
                c[3] = 1;
            }
            if (over && over[mf]) {
                shade_overhang_colour(c);
                c[3] = 1;
            }
        }
    }
}

/* Loaded faces: the grid copies repeat them. */
static uint32_t loaded_faces(const Scene *s)
{
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    uint32_t n = 0;
    for (int i = 0; i < nb; i++) {
        uint32_t e = (uint32_t)s->objs[i].face_base + s->objs[i].face_count;
        n = e > n ? e : n;
    }
    return n;
}

static int make(Pipeline *p, char *err, size_t errlen)
{
    PrintTint *t = &p->tint;
    const Scene *s = p->scene;
    Mesh *m;
    int n, rc = -1;
    if (scene_check_meshes(s, &m, &n, err, errlen))
        return -1;
    uint32_t nload = loaded_faces(s);
    PrintqThickness *th = calloc(n > 0 ? (size_t)n : 1, sizeof *th);
    t->ft.rgba = calloc(4 * (size_t)nload + 4, 1);
    if (!th || !t->ft.rgba) {
        snprintf(err, errlen, "out of memory");
        goto out;
    }
    t->ft.nfaces = nload;
    double unit = ldexp(1, s->pos_exp);     /* the scene's positions back to the file's */
    double scale = 0;
    for (int i = 0; p->thickness && i < n; i++) {
        if (printq_thickness(&m[i], p->threads, &th[i], err, errlen))
            goto out;
        double sc = 2 * th[i].median;
        scale = sc > scale ? sc : scale;
        if (th[i].measured && (t->thick_min == 0 || th[i].min * unit < t->thick_min))
            t->thick_min = th[i].min * unit;
    }
    if (p->thick_limit > 0)
        scale = 2 * p->thick_limit / unit;
    t->thick_scale = scale * unit;
    for (int i = 0; i < n; i++) {
        uint8_t *over = NULL;
        if (p->overhang) {
            over = malloc(m[i].nfaces ? m[i].nfaces : 1);
            if (!over) {
                snprintf(err, errlen, "out of memory");
                goto out;
            }
            t->overhang_area += printq_overhang(&m[i], mesh_up(s, i), p->overhang_deg, over) * unit * unit;
        }
        lay(p, i, over, p->thickness ? th[i].face : NULL, scale, t->ft.rgba);
        free(over);
    }
    rc = 0;
out:
    for (int i = 0; th && i < n; i++)
        printq_thickness_free(&th[i]);
    free(th);
    scene_check_meshes_free(m, n);
    return rc;
}

int app_print_tint(Pipeline *p, char *err, size_t errlen)
{
    PrintTint *t = &p->tint;
    const Scene *s = p->scene;
    if (!p->overhang && !p->thickness) {
        if (t->ft.rgba)
            print_tint_free(t);
        return 0;
    }
    int up = s->nobjs ? s->objs[0].up : UP_Y;
    if (t->key == s && t->key_gen == s->gen && t->key_up == up && t->key_overhang == p->overhang &&
        t->key_deg == p->overhang_deg && t->key_thickness == p->thickness && t->key_limit == p->thick_limit)
        return t->ft.rgba ? 1 : 0;
    print_tint_free(t);
    if (s->nobjs && make(p, err, errlen)) {
        print_tint_free(t);
        return -1;
    }
    t->key = s;
    t->key_gen = s->gen;
    t->key_up = up;
    t->key_overhang = p->overhang;
    t->key_deg = p->overhang_deg;
    t->key_thickness = p->thickness;
    t->key_limit = p->thick_limit;
    return t->ft.rgba ? 1 : 0;
}

void print_tint_status(const Pipeline *p, char *buf, size_t len)
{
    const PrintTint *t = &p->tint;
    const Scene *s = p->scene;
    const char *unit = s->nmeshes ? s->meshes[0].info.unit : "";
    size_t o = 0;
    buf[0] = 0;
    if (p->thickness && t->ft.rgba && o < len)
        o += (size_t)snprintf(buf + o, len - o, t->thick_scale > 0 ? "thickness red 0 to blue %.3g%s%s" : "thickness: none measured",
                              t->thick_scale, unit[0] ? " " : "", unit);
    if (p->overhang && t->ft.rgba && o < len)
        snprintf(buf + o, len - o, "%soverhang past %g: %.4g%s%s%s", o ? ", " : "", p->overhang_deg, t->overhang_area,
                 unit[0] ? " " : "", unit, unit[0] ? "^2" : "");
}
