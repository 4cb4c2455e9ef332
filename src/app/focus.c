/* focus.c: one problem in focus, for the viewer's . and , keys and
 * --problem K: the camera framed on it, and the problem drawn over the
 * picture in its warning colour.
 *
 * Framing keeps the camera's turn and its fit (where the view looks
 * from) and moves only the pan and the zoom: the box of the problem's
 * points, as the camera sees it, goes to the middle of the picture at
 * FOCUS_SHARE of its width or height, whichever is tighter (a point, or
 * a problem smaller than FOCUS_MIN_SHARE of the fitted scene, counts as
 * that big: a little of the model round it shows). Only when the
 * problem is hidden from there does the camera turn: small renders
 * (FOCUS_TEST_W pixels wide, the z-buffer) from the 26 directions of a
 * cube's faces, edges and corners, nearest to the current direction
 * first, and the first from which at least half of the problem's
 * points show wins (else the one that shows most; none shows, as inside
 * a closed cavity: the direction stays). A point shows when it is not
 * behind what the render drew within a pixel of it, or when there is
 * background there (a hole's rim against the inside seen through it); a
 * face is tested by its middle and its corners drawn a quarter of the
 * way in, and a hole or a face seen nearly edge on (FOCUS_EDGE_ON) does
 * not show.
 *
 * Drawing is on the finished picture (shade/overlay.c), after the
 * contrast rule, so the colour is the warning colour itself: each line
 * of the item (a hole's loop, a face's outline, an edge) and a ring
 * about its point when it has one, through the frame's own projection. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"

#define FOCUS_SHARE      0.35   /* of the picture's width or height the problem's box fills */
#define FOCUS_MIN_SHARE  0.03   /* of the fitted scene's half size: the least extent framed */
#define FOCUS_TEST_W     96     /* pixels across the visibility test's renders */
#define FOCUS_ANCHORS    64     /* points of a problem tested at most */
#define FOCUS_SHOWS      0.5    /* the share of them that must show */
#define FOCUS_EDGE_ON    0.25   /* a hole or face seen closer to edge on than this cosine does not */

/* ==== Which object ==== */

int app_focus_object(const Scene *s, const CheckItems *it, uint32_t i)
{
    if (!it || i >= it->n)
        return -1;
    const CheckItem *e = &it->item[i];
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    for (int k = 0; k < nb; k++)
        if (scene_object_file(s, k) == e->file && s->objs[k].face_first == e->face_first)
            return k;
    return -1;
}

/* ==== The problem's points ==== */

typedef struct {
    Vec3     p[FOCUS_ANCHORS];  /* world */
    int      n;
    Vec3     normal;            /* unit, world: a hole's or a face's; zero for the rest */
} Anchors;

/* The unit normal of line l of the item (Newell's), in world space. */
static Vec3 line_normal(const CheckItems *it, uint32_t l, const Mat4 *om)
{
    uint32_t b0 = it->line_start[l], b1 = it->line_start[l + 1];
    double n[3] = { 0, 0, 0 };
    for (uint32_t k = b0; k < b1; k++) {
        const float *p = it->pt + 3 * (size_t)k, *q = it->pt + 3 * (size_t)(k + 1 < b1 ? k + 1 : b0);
        n[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
        n[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
        n[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
    }
    Vec3 w = m4_dir(om, v3((float)n[0], (float)n[1], (float)n[2]));
    float len = sqrtf(v3_dot(w, w));
    return len > 0 && isfinite(len) ? v3_scale(w, 1 / len) : v3(0, 0, 0);
}

/* The points tested: a hole's loop and an edge as they are (a rim
 * against the inside seen through it shows); a face by its middle and
 * its corners drawn a quarter of the way in (its corners may lie on the
 * outline of what hides it); the ring's point. */
static void anchors_of(const Scene *s, const CheckItems *it, uint32_t i, int obj, Anchors *a)
{
    const CheckItem *e = &it->item[i];
    Mat4 om = object_matrix(&s->objs[obj]);
    uint32_t p0 = it->line_start[e->line0], p1 = it->line_start[e->line0 + e->nlines];
    uint32_t n = p1 - p0 + e->nlines, room = e->has_ring ? FOCUS_ANCHORS - 1 : FOCUS_ANCHORS;
    uint32_t step = n > room ? (n + room - 1) / room : 1, seen = 0;
    a->n = 0;
    for (uint32_t l = e->line0; l < e->line0 + e->nlines; l++) {
        uint32_t b0 = it->line_start[l], b1 = it->line_start[l + 1];
        int face = it->line_closed[l] && e->kind != CHECK_LOC_HOLES && b1 - b0 > 2;
        double mid[3] = { 0, 0, 0 };
        for (uint32_t k = b0; k < b1; k++)
            for (int c = 0; c < 3; c++)
                mid[c] += it->pt[3 * (size_t)k + c] / (double)(b1 - b0);
        if (face && a->n < (int)room)
            a->p[a->n++] = m4_point(&om, v3((float)mid[0], (float)mid[1], (float)mid[2]));
        for (uint32_t k = b0; k < b1 && a->n < (int)room; k++, seen++) {
            if (seen % step)
                continue;
            double q[3];
            for (int c = 0; c < 3; c++)
                q[c] = face ? 0.75 * it->pt[3 * (size_t)k + c] + 0.25 * mid[c] : it->pt[3 * (size_t)k + c];
            a->p[a->n++] = m4_point(&om, v3((float)q[0], (float)q[1], (float)q[2]));
        }
    }
    if (e->has_ring)
        a->p[a->n++] = m4_point(&om, v3(e->ring[0], e->ring[1], e->ring[2]));
    /* a hole or a face seen edge on does not show, whatever its points
     * do (a degenerate face has no side to see) */
    int sided = e->kind == CHECK_LOC_HOLES || e->kind == CHECK_LOC_FLIPPED || e->kind == CHECK_LOC_DUPLICATE;
    a->normal = sided && e->nlines ? line_normal(it, e->line0, &om) : v3(0, 0, 0);
}

/* ==== Framing from the current turn ==== */

static void frame_here(Scene *s, const Anchors *a, int w, int h, float aspect)
{
    Camera *c = &s->cam;
    Mat4 turn = m4_rotate_ypr(c->yaw, c->pitch, c->roll);
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int k = 0; k < a->n; k++) {
        Vec3 q = m4_dir(&turn, v3_sub(a->p[k], c->centre));
        double v[3] = { q.x, q.y, q.z };
        for (int j = 0; j < 3; j++) {
            lo[j] = fmin(lo[j], v[j]);
            hi[j] = fmax(hi[j], v[j]);
        }
    }
    if (!(lo[0] <= hi[0]))
        return;
    double r = c->radius > 0 ? c->radius : 1;
    double hx = c->fit_half.x > 0 ? c->fit_half.x : r, hy = c->fit_half.y > 0 ? c->fit_half.y : r;
    double hz = c->fit_half.z > 0 ? c->fit_half.z : r;
    double least = FOCUS_MIN_SHARE * fmax(hx, hy);
    double ex = fmax(0.5 * (hi[0] - lo[0]), least), ey = fmax(0.5 * (hi[1] - lo[1]), least);
    double mid[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
    double half_w = 0.5 * w, half_h = 0.5 * h * (aspect > 0 ? aspect : 1);
    c->pan = v3((float)(-mid[0] / r), (float)(-mid[1] / r), 0);
    double zoom;
    if (!c->persp) {
        /* project.c: pixels per unit = zoom 0.9 min(half_w / hx, half_h / hy) */
        double unit = 0.9 * fmin(half_w / hx, half_h / hy);
        zoom = FOCUS_SHARE * fmin(half_w / ex, half_h / ey) / unit;
    } else {
        /* project.c: the eye at (hz + max(hx f / half_w, hy f / half_h) / 0.9) / zoom */
        double fov = (c->fov_deg > 1 && c->fov_deg < 179 ? c->fov_deg : 50) * 3.14159265358979323846 / 180;
        double f = fmin(half_w, half_h) / tan(fov / 2);
        double eye1 = hz + fmax(hx * f / half_w, hy * f / half_h) / 0.9;
        double d = fmax(f * ex / (FOCUS_SHARE * half_w), f * ey / (FOCUS_SHARE * half_h));
        double eye = fmax(mid[2] + d, hi[2] + 0.05 * r);
        zoom = eye > 0 ? eye1 / eye : 1000;
    }
    c->zoom = (float)fmin(1000, fmax(0.05, zoom));
}

/* ==== Does it show? ==== */

/* The share of the anchors that show in a render of the scene as its
 * camera stands (tp: a pipeline of its own on the scene). -1 out of
 * memory. */
static double shows(Pipeline *tp, const Anchors *a, int w, int h, float aspect)
{
    const Camera *c = &tp->scene->cam;
    Mat4 turn = m4_rotate_ypr(c->yaw, c->pitch, c->roll);
    if (fabsf(v3_dot(a->normal, v3(turn.m[2][0], turn.m[2][1], turn.m[2][2]))) < FOCUS_EDGE_ON &&
        v3_dot(a->normal, a->normal) > 0)
        return 0;
    int tw = FOCUS_TEST_W;
    double ratio = (double)h * (aspect > 0 ? aspect : 1) / (w > 0 ? w : 1);
    int th = (int)lround(tw * ratio);
    th = th < 16 ? 16 : th > 4 * FOCUS_TEST_W ? 4 * FOCUS_TEST_W : th;
    if (pipeline_render(tp, tw, th, 1.0f, 0, 0))
        return -1;
    const FrameBufs *fb = &tp->fb;
    Mat4 view = camera_view(&tp->scene->cam);
    int seen = 0;
    for (int k = 0; k < a->n; k++) {
        Vec3 q = m4_point(&view, a->p[k]);
        double sp[3];
        if (screen_view_point(&tp->sp, q.x, q.y, q.z, sp))
            continue;
        int x = (int)floor(sp[0]), y = (int)floor(sp[1]);
        if (x < 0 || y < 0 || x >= fb->w || y >= fb->h)
            continue;
        int open = 0;
        float far = -INFINITY;
        for (int j = y - 1; j <= y + 1; j++)
            for (int i = x - 1; i <= x + 1; i++) {
                if (i < 0 || j < 0 || i >= fb->w || j >= fb->h)
                    continue;
                size_t at = (size_t)j * (size_t)fb->w + (size_t)i;
                open |= fb->ids[at] < 0;
                far = fb->depth[at] > far ? fb->depth[at] : far;
            }
        seen += open || sp[2] <= (double)far + 1e-4;
    }
    return a->n ? (double)seen / a->n : 0;
}

/* ==== Framing ==== */

/* The yaw and pitch (radians) that look along -d: the viewer towards d
 * from the model (view_dir's inverse). */
static void turn_towards(Vec3 d, float *yaw, float *pitch)
{
    double n = sqrt((double)d.x * d.x + (double)d.y * d.y + (double)d.z * d.z);
    *pitch = (float)asin(fmax(-1, fmin(1, d.y / n)));
    *yaw = (float)atan2(-d.x, d.z);
}

typedef struct {
    Vec3   d;
    double near;        /* cosine to the current direction */
} Way;

static int by_nearness(const void *x, const void *y)
{
    double a = ((const Way *)x)->near, b = ((const Way *)y)->near;
    return a > b ? -1 : a < b;
}

int app_focus_frame(Scene *s, const CheckItems *it, uint32_t i, int obj, int w, int h, float pixel_aspect,
                    int threads, int *turned_out)
{
    if (turned_out)
        *turned_out = 0;
    if (!it || i >= it->n || obj < 0 || obj >= s->nobjs)
        return 0;
    Anchors a;
    anchors_of(s, it, i, obj, &a);
    frame_here(s, &a, w, h, pixel_aspect);
    Pipeline tp;
    if (pipeline_init(&tp, s, hsr_algos[0], threads))
        return -1;
    double here = shows(&tp, &a, w, h, pixel_aspect);
    if (here < 0 || here >= FOCUS_SHOWS) {
        pipeline_free(&tp);
        return here < 0 ? -1 : 0;
    }
    /* hidden from here: the 26 ways round, nearest first */
    Camera start = s->cam;
    Mat4 turn = m4_rotate_ypr(start.yaw, start.pitch, start.roll);
    Vec3 now = v3(turn.m[2][0], turn.m[2][1], turn.m[2][2]);
    Way way[26];
    int n = 0;
    for (int x = -1; x <= 1; x++)
        for (int y = -1; y <= 1; y++)
            for (int z = -1; z <= 1; z++)
                if (x || y || z) {
                    Vec3 d = v3_scale(v3((float)x, (float)y, (float)z), 1.0f / sqrtf((float)(x * x + y * y + z * z)));
                    way[n++] = (Way){ d, v3_dot(d, now) };
                }
    qsort(way, 26, sizeof *way, by_nearness);
    int best = -1;
    double best_share = here;
    for (int k = 0; k < 26 && best_share < FOCUS_SHOWS; k++) {
        turn_towards(way[k].d, &s->cam.yaw, &s->cam.pitch);
        s->cam.roll = 0;
        scene_fit(s);
        frame_here(s, &a, w, h, pixel_aspect);
        double sh = shows(&tp, &a, w, h, pixel_aspect);
        if (sh < 0) {
            pipeline_free(&tp);
            s->cam = start;
            return -1;
        }
        if (sh > best_share) {
            best_share = sh;
            best = k;
        }
    }
    pipeline_free(&tp);
    s->cam = start;
    if (best < 0)
        return 0;               /* shows from nowhere better: the turn stays */
    turn_towards(way[best].d, &s->cam.yaw, &s->cam.pitch);
    s->cam.roll = 0;
    scene_fit(s);
    frame_here(s, &a, w, h, pixel_aspect);
    if (turned_out)
        *turned_out = 1;
    return 0;
}

/* ==== Drawing ==== */

void app_focus_draw(Pipeline *p)
{
    const ProblemFocus *f = &p->focus;
    const Scene *s = p->scene;
    if (!f->items || f->item >= f->items->n || f->obj < 0 || f->obj >= s->nobjs || !p->img.w)
        return;
    const CheckItems *it = f->items;
    const CheckItem *e = &it->item[f->item];
    uint8_t rgb[3];
    shade_problem_colour(e->kind, rgb);
    Mat4 mv = m4_mul(camera_view(&s->cam), object_matrix(&s->objs[f->obj]));
    /* the projection is of the samples; the picture has k x k a pixel */
    double k = p->sp.w > 0 ? (double)p->sp.w / p->img.w : 1;
    int small = p->img.w < p->img.h ? p->img.w : p->img.h;
    int width = small >= 480 ? 3 : small >= 240 ? 2 : 1;
    for (uint32_t l = e->line0; l < e->line0 + e->nlines; l++) {
        uint32_t a = it->line_start[l], b = it->line_start[l + 1];
        double prev[3] = { 0, 0, 0 }, first[3] = { 0, 0, 0 };
        int have_prev = 0, have_first = 0;
        for (uint32_t q = a; q <= b; q++) {
            int closing = q == b;
            if (closing && !(it->line_closed[l] && b - a > 2))
                break;
            const float *v = it->pt + 3 * (size_t)(closing ? a : q);
            Vec3 w = m4_point(&mv, v3(v[0], v[1], v[2]));
            double sp[3];
            int ok = screen_view_point(&p->sp, w.x, w.y, w.z, sp) == 0;
            if (ok && have_prev)
                image_line(&p->img, prev[0] / k, prev[1] / k, sp[0] / k, sp[1] / k, rgb, width);
            if (ok && !have_first && !closing) {
                memcpy(first, sp, sizeof first);
                have_first = 1;
            }
            if (ok)
                memcpy(prev, sp, sizeof prev);
            have_prev = ok;
        }
        /* a line of one point (a degenerate face on one spot) */
        if (b - a == 1 && have_first)
            image_ring(&p->img, first[0] / k, first[1] / k, width, rgb, width);
    }
    if (e->has_ring) {
        Vec3 w = m4_point(&mv, v3(e->ring[0], e->ring[1], e->ring[2]));
        double sp[3];
        if (screen_view_point(&p->sp, w.x, w.y, w.z, sp) == 0)
            image_ring(&p->img, sp[0] / k, sp[1] / k, fmax(3, small / 16.0), rgb, width);
    }
}
