/* measuremarks.c: the measuring mode's marks on the picture (the
 * viewer's M key, --marks). A mark is a vertex of a scene object; the
 * cursor moves from vertex to vertex, taking the nearest one in the
 * direction of the arrow among those the last frame shows (a vertex
 * whose depth is not behind the depth buffer's at its sample), so that
 * it never lands on a hidden one. Marks are vertices, not screen
 * points, so they stay on the model while it turns, and the figures
 * are in file units from the mesh's own positions (printq/measure.c). */

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "app.h"

/* Is vertex v of object o there? Marks outlive edits of the scene
 * (O, X) and come from the command line (--marks): every use asks. */
static int exists(const Scene *s, int o, uint32_t v)
{
    return o >= 0 && o < s->nobjs && s->objs[o].mesh && v < s->objs[o].mesh->nverts;
}

/* Vertex v of object o in samples of the last frame (x, y, depth):
 * 0, or -1 behind the eye or not there. */
static int on_screen(const Pipeline *p, int o, uint32_t v, double out[3])
{
    const Scene *s = p->scene;
    if (!exists(s, o, v))
        return -1;
    const Object *ob = &s->objs[o];
    const float *q = &ob->mesh->pos[3 * (size_t)v];
    Mat4 mv = m4_mul(camera_view(&s->cam), object_matrix(ob));
    Vec3 w = m4_point(&mv, v3(q[0], q[1], q[2]));
    return screen_view_point(&p->sp, w.x, w.y, w.z, out);
}

/* Does the last frame show the point (on the screen, not behind what
 * the depth buffer holds at its sample, within a margin for the faces
 * that meet at it)? */
static int shown(const Pipeline *p, const double sp[3])
{
    const FrameBufs *fb = &p->fb;
    if (!(sp[0] >= 0 && sp[1] >= 0 && sp[0] < fb->w && sp[1] < fb->h))
        return 0;
    float d = fb->depth[(size_t)sp[1] * (size_t)fb->w + (size_t)sp[0]];
    return !(d < INFINITY) || sp[2] <= d + 5e-3;
}

int app_measure_step(Pipeline *p, int dx, int dy)
{
    MeasureMarks *m = &p->marks;
    const Scene *s = p->scene;
    if (!p->fb.depth || !p->fb.w)
        return -1;
    double c[3] = { p->fb.w / 2.0, p->fb.h / 2.0, 0 };
    int from = m->cursor && on_screen(p, m->cur_obj, m->cur_v, c) == 0;
    if (!from)
        dx = dy = 0;        /* no cursor yet: the vertex nearest the middle */
    double best = INFINITY;
    int bo = -1;
    uint32_t bv = 0;
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    for (int o = 0; o < nb; o++) {
        const Object *ob = &s->objs[o];
        if (!ob->face_count && !ob->point_count)
            continue;
        for (uint32_t v = ob->vert_min; v <= ob->vert_max && v < ob->mesh->nverts; v++) {
            double q[3];
            if (on_screen(p, o, v, q) || !shown(p, q))
                continue;
            double ex = q[0] - c[0], ey = q[1] - c[1], score;
            if (dx || dy) {
                double along = ex * dx + ey * dy, across = fabs(ex * dy - ey * dx);
                if (along < 1)
                    continue;       /* not that way (or the cursor's own vertex) */
                score = along + 3 * across;
            } else {
                score = ex * ex + ey * ey;
            }
            if (score < best) {
                best = score;
                bo = o;
                bv = v;
            }
        }
    }
    if (bo < 0)
        return -1;
    m->cursor = 1;
    m->cur_obj = bo;
    m->cur_v = bv;
    return 0;
}

/* A vertex's position in its file's units (the scene's positions may
 * be scaled by a power of two: scene.h pos_exp). */
static PrintqPoint point_of(const Scene *s, int o, uint32_t v)
{
    PrintqPoint pt = { .vertex = v + 1 };
    const float *q = &s->objs[o].mesh->pos[3 * (size_t)v];
    for (int k = 0; k < 3; k++)
        pt.p[k] = ldexp(q[k], s->pos_exp);
    return pt;
}

void app_measure_words(const Scene *s, const MeasureMarks *m, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = 0;
    if (m->cursor && exists(s, m->cur_obj, m->cur_v)) {
        PrintqPoint c = point_of(s, m->cur_obj, m->cur_v);
        o += (size_t)snprintf(buf, len, "v%u %.4g %.4g %.4g", c.vertex, c.p[0], c.p[1], c.p[2]);
    }
    int there = 1;
    for (int i = 0; i < m->n; i++)
        there &= exists(s, m->obj[i], m->v[i]);
    if (!there) {
        snprintf(buf + o, len - o, "%sa mark is on no vertex of the scene", o ? ", " : "");
        return;
    }
    if (m->n >= 2 && o < len) {
        PrintqPoint pt[MEASURE_MARKS];
        for (int i = 0; i < m->n; i++)
            pt[i] = point_of(s, m->obj[i], m->v[i]);
        PrintqMeasure r;
        printq_measure(pt, m->n, &r);
        o += (size_t)snprintf(buf + o, len - o, "%sAB %.6g (dx %.4g dy %.4g dz %.4g)", o ? ", " : "", r.dist, r.d[0],
                              r.d[1], r.d[2]);
        if (m->n == 3 && o < len)
            snprintf(buf + o, len - o, ", BC %.6g, angle ABC %.4g", r.dist2, r.angle);
    } else if (m->n == 1 && o < len) {
        snprintf(buf + o, len - o, "%sA marked", o ? ", " : "");
    }
}

void app_measure_option(const MeasureMarks *m, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = 0;
    for (int i = 0; i < m->n && o < len; i++) {
        if (m->obj[i])
            o += (size_t)snprintf(buf + o, len - o, "%s%d:v%u", i ? "," : "", m->obj[i] + 1, m->v[i] + 1);
        else
            o += (size_t)snprintf(buf + o, len - o, "%sv%u", i ? "," : "", m->v[i] + 1);
    }
}

void app_measure_draw(Pipeline *p)
{
    const MeasureMarks *m = &p->marks;
    if (!p->img.w || (!m->n && !m->cursor))
        return;
    static const uint8_t line_rgb[3] = { 0, 230, 230 }, cur_rgb[3] = { 255, 255, 255 };
    double k = p->sp.w > 0 ? (double)p->sp.w / p->img.w : 1;
    int small = p->img.w < p->img.h ? p->img.w : p->img.h;
    int width = small >= 480 ? 3 : small >= 240 ? 2 : 1;
    double r = fmax(3, small / 40.0);
    double prev[3] = { 0, 0, 0 };
    for (int i = 0; i < m->n; i++) {
        double q[3];
        int ok = on_screen(p, m->obj[i], m->v[i], q) == 0;
        if (ok && i > 0)
            image_line(&p->img, prev[0] / k, prev[1] / k, q[0] / k, q[1] / k, line_rgb, width);
        if (ok)
            image_ring(&p->img, q[0] / k, q[1] / k, r, line_rgb, width);
        if (ok)
            memcpy(prev, q, sizeof prev);
        else
            break;
    }
    double c[3];
    if (m->cursor && on_screen(p, m->cur_obj, m->cur_v, c) == 0) {
        image_ring(&p->img, c[0] / k, c[1] / k, r * 1.6, cur_rgb, width);
        image_line(&p->img, c[0] / k - 2 * r, c[1] / k, c[0] / k + 2 * r, c[1] / k, cur_rgb, 1);
        image_line(&p->img, c[0] / k, c[1] / k - 2 * r, c[0] / k, c[1] / k + 2 * r, cur_rgb, 1);
    }
}
