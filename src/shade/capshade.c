/* capshade.c: the caps of a section (section.h) in their own colour,
 * lit by the scene's light as a flat face of the cap plane's normal,
 * with their outline drawn darker: a cap sample next to a sample that
 * is not the same cap. From the id buffer alone, after the faces are
 * shaded, so every algorithm's picture is the same. */

#include <math.h>

#include "section.h"
#include "shade.h"

/* The caps' base colour: a warm red no default face colour is near. */
static const float cap_rgb[3] = { 224, 72, 56 };
#define CAP_OUTLINE 0.45f       /* the outline's share of the cap's colour */

/* How bright the cap of plane i of object o is under the light. */
static float cap_light(const Scene *s, const SectionCut *c, int o, int i)
{
    Mat4 mv = m4_mul(camera_view(&s->cam), object_matrix(&s->objs[o]));
    const double *n = c->plane[i].n;
    double v[3];
    for (int r = 0; r < 3; r++)
        v[r] = mv.m[r][0] * n[0] + mv.m[r][1] * n[1] + mv.m[r][2] * n[2];
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const Light *l = &s->light;
    double d = len > 0 ? (v[0] * l->dir.x + v[1] * l->dir.y + v[2] * l->dir.z) / len : 0;
    return l->ambient + (1 - l->ambient) * (float)fabs(d);
}

void shade_caps(const Scene *s, const SectionCut *c, const FrameBufs *fb, Image *out)
{
    if (!c || c->nplanes <= 0)
        return;
    int64_t id0 = section_cap_id0(s), n = (int64_t)s->nobjs * c->nplanes;
    int32_t last = -1;
    float bright = 1;
    for (int y = 0; y < fb->h; y++)
        for (int x = 0; x < fb->w; x++) {
            size_t i = (size_t)y * fb->w + x;
            int32_t id = fb->ids[i];
            if (id < id0 || id - id0 >= n)
                continue;
            if (id != last) {
                int64_t k = id - id0;
                bright = cap_light(s, c, (int)(k / c->nplanes), (int)(k % c->nplanes));
                last = id;
            }
            /* the outline: a neighbour (or the picture's edge) that is not this cap */
            int edge = x == 0 || y == 0 || x + 1 == fb->w || y + 1 == fb->h || fb->ids[i - 1] != id ||
                       fb->ids[i + 1] != id || fb->ids[i - (size_t)fb->w] != id || fb->ids[i + (size_t)fb->w] != id;
            float f = edge ? bright * CAP_OUTLINE : bright;
            for (int a = 0; a < 3; a++) {
                float v = cap_rgb[a] * f;
                out->rgb[3 * i + a] = (uint8_t)(v > 255 ? 255 : v + 0.5f);
            }
            out->lit[i] = 1;
        }
}
