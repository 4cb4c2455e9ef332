/* firstview.c: the automatic first view, chosen by what each candidate
 * view sees.
 *
 * A model's first view should show its outside from the front. Twelve
 * candidate views are rendered small (FV_W x FV_H pixels, the exact
 * z-buffer, no culling): eight three-quarter views from above (yaws 30,
 * 60, 120, 150 either side, pitch 25), which show a solid's depth best,
 * and the four level views straight at its sides (yaws 0, 90, 180, -90),
 * which look squarely into an open box. In each picture every pixel's
 * face is seen either from its front (its normal towards the viewer) or
 * from behind: the inside of an open shell seen from outside, through
 * the shell (the Cornell box's green wall, hiding both blocks), or faces
 * wound the wrong way. A view scores
 *
 *     (front pixels - back pixels) x the world area of a pixel
 *       / the largest area any candidate draws
 *       x front_factor (1.3 straight at a sure front, 0.7 behind it)
 *       x 0.75 for a level view,
 *
 * and the best wins (the first of equals, in the order above). The
 * first term is how much of the model's outside the view shows, in world
 * units (each picture is fitted to its own view, so pixels alone would
 * favour a compact outline): a long model is seen from its side, an open
 * box through its opening (no back faces there). The front factor (scene/view.c: the format's forward axis, else the side
 * more of the faces face) decides between a solid's front and back,
 * whose outlines are mirror images; the level views' handicap keeps the
 * three-quarter views for solids, a level view winning only where it
 * sees clearly more (an open box from its open side). A model whose
 * every face is seen from behind in every view is wound inside out:
 * front and back swap. Points and lines have no side and count as seen
 * from the front.
 *
 * Huge scenes are scored on a stand-in (FV_STANDIN_POLYS polygons,
 * points and segments or more, standin.c): their vertices merged on a grid of 64 cells a side
 * (vertex clustering), which keeps the shape and the way its faces face
 * at these few pixels, at a fraction of the cost (the dragon: 12 ms, 65
 * ms rendered whole, the same choice). */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "clock.h"

#define FV_W 64
#define FV_H 48
#define FV_LEVEL_HANDICAP 0.75f

typedef struct {
    float yaw, pitch;
    int   level;
} Candidate;

static const Candidate candidates[FV_VIEWS] = {
    { -30, 25, 0 },  { 30, 25, 0 },  { -60, 25, 0 }, { 60, 25, 0 },  { -120, 25, 0 }, { 120, 25, 0 },
    { -150, 25, 0 }, { 150, 25, 0 }, { 0, 0, 1 },    { 180, 0, 1 },  { 90, 0, 1 },    { -90, 0, 1 },
};

/* ==== One candidate ==== */

/* The pixels of the last picture seen from the front and from behind. */
static void count_sides(const Scene *s, const FrameBufs *fb, const Mat4 *om, Vec3 d, uint32_t *front,
                        uint32_t *back)
{
    uint32_t f = 0, b = 0;
    size_t n = (size_t)fb->w * fb->h;
    for (size_t k = 0; k < n; k++) {
        int32_t id = fb->ids[k];
        if (id < 0)
            continue;
        if ((uint32_t)id >= s->nfaces) {
            f++;                /* a point or a line: no side */
            continue;
        }
        float nf[3];
        scene_face_normal(s, (uint32_t)id, nf);
        Vec3 wn = m4_dir(&om[scene_face_obj(s, (uint32_t)id)], v3(nf[0], nf[1], nf[2]));
        if (v3_dot(wn, d) > 0)
            f++;
        else
            b++;
    }
    *front = f;
    *back = b;
}

/* Render candidate c of s (camera fitted to it) and count its sides;
 * *px_area: the world area a pixel covers in that picture. */
static int look(Pipeline *p, const Mat4 *om, const Candidate *c, uint32_t *front, uint32_t *back,
                double *px_area)
{
    Scene *s = p->scene;
    Camera *cam = &s->cam;
    cam->yaw = deg2rad(c->yaw);
    cam->pitch = deg2rad(c->pitch);
    cam->roll = 0;
    cam->persp = 0;
    cam->zoom = 1;
    cam->pan = v3(0, 0, 0);
    scene_fit(s);
    if (pipeline_render(p, FV_W, FV_H, 1.0f, 0, 0))
        return -1;
    count_sides(s, &p->fb, om, view_dir(c->yaw, c->pitch), front, back);
    *px_area = 1.0 / ((double)p->sp.focal_x * p->sp.focal_y);
    return 0;
}

/* ==== Scoring ==== */

/* What one candidate saw: pixels of faces from the front and from
 * behind, and the world area of a pixel (each picture is fitted to its
 * view, so areas, not pixels, compare between views). */
typedef struct {
    uint32_t front, back;
    double   px_area;
} Look;

static void choose(const SceneFront *front, const Look lk[FV_VIEWS], FirstView *out)
{
    uint64_t sf = 0, sb = 0;
    double most = 0;
    for (int c = 0; c < FV_VIEWS; c++) {
        sf += lk[c].front;
        sb += lk[c].back;
        most = fmax(most, (lk[c].front + lk[c].back) * lk[c].px_area);
    }
    int inside_out = sf == 0 && sb > 0;
    const double npx = (double)FV_W * FV_H;
    int best = 0;
    double bests = -INFINITY;
    for (int c = 0; c < FV_VIEWS; c++) {
        uint32_t seen = inside_out ? lk[c].back : lk[c].front, behind = inside_out ? lk[c].front : lk[c].back;
        /* the outside seen, as a share of the most any view draws */
        double sc = most > 0 ? ((double)seen - behind) * lk[c].px_area / most : 0;
        sc *= front_factor(front, candidates[c].yaw, candidates[c].pitch);
        if (candidates[c].level)
            sc *= FV_LEVEL_HANDICAP;
        out->score[c] = (float)sc;
        if (sc > bests) {
            bests = sc;
            best = c;
            out->seen = (float)(seen / npx);
            out->back = (float)(behind / npx);
        }
    }
    out->yaw = candidates[best].yaw;
    out->pitch = candidates[best].pitch;
    out->chosen = best;
    out->inside_out = inside_out;
}

/* ==== The first view ==== */

int app_first_view(Scene *s, int threads, FirstView *out)
{
    double t0 = now_ms();
    memset(out, 0, sizeof *out);
    scene_front(s, &out->front);
    Scene standin;
    Scene *r = s;
    if (app_standin(s, &standin) == 0)
        r = &standin;
    Camera saved = s->cam;
    Pipeline p;
    Mat4 *om = malloc((size_t)(r->nobjs > 0 ? r->nobjs : 1) * sizeof *om);
    int rc = om ? pipeline_init(&p, r, hsr_find("zbuffer"), threads) : -1;
    if (rc == 0) {
        for (int i = 0; i < r->nobjs; i++)
            om[i] = object_matrix(&r->objs[i]);
        Look lk[FV_VIEWS];
        for (int c = 0; c < FV_VIEWS && rc == 0; c++)
            rc = look(&p, om, &candidates[c], &lk[c].front, &lk[c].back, &lk[c].px_area);
        if (rc == 0)
            choose(&out->front, lk, out);
        pipeline_free(&p);
    }
    free(om);
    out->polys = r->npolys;
    out->prims = r->npoints + r->nsegs;
    out->standin = r != s;
    if (r != s)
        scene_free(&standin);
    s->cam = saved;
    if (rc) {
        /* no memory to render: the geometry alone */
        scene_pick_view(s, &out->yaw, &out->pitch);
        out->rendered = 0;
    } else
        out->rendered = FV_VIEWS;
    out->ms = now_ms() - t0;
    return 0;
}

float app_view_candidate(int i, float *pitch_out)
{
    *pitch_out = candidates[i].pitch;
    return candidates[i].yaw;
}
