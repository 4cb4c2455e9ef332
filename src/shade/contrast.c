/* contrast.c: the contrast rule (backdrop.h). A drawn pixel whose
 * lightness comes within `min` of the background's is moved away from
 * it, on the final picture, after shading: whatever made the colour
 * (a material, a vertex colour, a texture, the depth ramp, the
 * selection's tint) is treated alike, and the hidden-surface step and
 * the shading before it do not change.
 *
 * Why per pixel and by a curve: a pixel does not know whether it is dark
 * because its material is or because it faces away from the light, so
 * the rule cannot darken one and spare the other; it squeezes the
 * lightnesses near the background's into the band just outside the
 * minimum, continuously and in order, so that shading keeps its
 * gradient (no step appears where a face crosses a threshold) and a
 * pixel farther out than min + CONTRAST_KNEE keeps its bytes.
 *
 * OKLab: B. Ottosson, "A perceptual color space for image processing"
 * (2020): L = A l' + B m' - C s', where l', m', s' are the cube roots of
 * three cone responses, each a positive mix of linear R, G and B. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "backdrop.h"
#include "texture.h"

#define OK_A 0.2104542553f
#define OK_B 0.7936177850f
#define OK_C 0.0040720468f

#define MARGIN 1e-4f            /* the fast test errs towards the exact one */
#define NUDGES 8                /* last-bit steps after rounding, at most */
#define HALVINGS 20             /* bisection steps towards white: L within 1e-6 */

/* ==== Lightness of linear light ==== */

typedef struct {
    float l, m, s;              /* the cone responses, before their cube roots */
} Cones;

static inline Cones cones(const float c[3])
{
    return (Cones){ 0.4122214708f * c[0] + 0.5363325363f * c[1] + 0.0514459929f * c[2],
                    0.2119034982f * c[0] + 0.6806995451f * c[1] + 0.1073969566f * c[2],
                    0.0883024619f * c[0] + 0.2817188376f * c[1] + 0.6299787005f * c[2] };
}

float contrast_lightness(const float c[3])
{
    Cones k = cones(c);
    return OK_A * cbrtf(k.l) + OK_B * cbrtf(k.m) - OK_C * cbrtf(k.s);
}

static inline void linear(const uint8_t rgb[3], float out[3])
{
    for (int a = 0; a < 3; a++)
        out[a] = srgb_to_linear(rgb[a]);
}

/* The fast test. With l' and m' both at least t (and s' at most 1) L is
 * at least (A + B) t - C; with both at most t (and s' at least 0), at
 * most (A + B) t. So l and m both at or above the first cube below give
 * L >= hi, both at or below the second give L <= lo, with no cube root. */
static float cube_giving_at_least(float hi)
{
    float t = (hi + OK_C + MARGIN) / (OK_A + OK_B);
    return t * t * t;
}

static float cube_giving_at_most(float lo)
{
    float t = (lo - MARGIN) / (OK_A + OK_B);
    return t > 0 ? t * t * t : -1;
}

/* ==== The rule ==== */

/* The fast test (above) of one colour: its l and m both at or past the
 * band's far threshold on the side given. */
static inline int past_band(const Contrast *c, const uint8_t p[3], int up)
{
    float lin[3];
    linear(p, lin);
    float l = 0.4122214708f * lin[0] + 0.5363325363f * lin[1] + 0.0514459929f * lin[2];
    float m = 0.2119034982f * lin[0] + 0.6806995451f * lin[1] + 0.1073969566f * lin[2];
    return up ? l >= c->keep_hi3 && m >= c->keep_hi3 : l <= c->keep_lo3 && m <= c->keep_lo3;
}

/* The cubes of CONTRAST_CELL^3 colours that keep their bytes whole: l
 * and m grow with every channel, so a cube is past the band above when
 * its darkest corner is, below when its lightest corner is. Per pixel,
 * one bit then stands for the fast test. */
static void mark_kept_cells(Contrast *c)
{
    const int k = CONTRAST_CELL, side = 256 / CONTRAST_CELL;
    memset(c->kept, 0, CONTRAST_CELLS / 8);
    for (int r = 0; r < side; r++)
        for (int g = 0; g < side; g++)
            for (int b = 0; b < side; b++) {
                uint8_t dark[3] = { (uint8_t)(r * k), (uint8_t)(g * k), (uint8_t)(b * k) };
                uint8_t light[3] = { (uint8_t)(r * k + k - 1), (uint8_t)(g * k + k - 1), (uint8_t)(b * k + k - 1) };
                uint32_t cell = (uint32_t)((r * side + g) * side + b);
                if ((c->up && past_band(c, dark, 1)) || (c->down && past_band(c, light, 0)))
                    c->kept[cell >> 3] |= (uint8_t)(1u << (cell & 7));
            }
}

int contrast_prepare(Contrast *c, const Backdrop *b, float min)
{
    float bg = backdrop_lightness(b->rgb);
    if (c->slot && c->bg_l == bg && c->min == min)
        return 0;
    if (!c->slot) {
        c->slot = calloc(CONTRAST_SLOTS, sizeof *c->slot);
        c->value = malloc(CONTRAST_SLOTS * sizeof *c->value);
        c->kept = malloc(CONTRAST_CELLS / 8);
        if (!c->slot || !c->value || !c->kept) {
            contrast_free(c);
            return -1;
        }
    } else {
        memset(c->slot, 0, CONTRAST_SLOTS * sizeof *c->slot);     /* made for another rule */
    }
    c->bg_l = bg;
    c->min = min;
    c->floor_up = bg + min;
    c->ceil_down = bg - min;
    c->up = min > 0 && c->floor_up <= 1 - CONTRAST_ROOM;
    c->down = min > 0 && c->ceil_down >= CONTRAST_ROOM;
    /* kept as they are: at or above hi, at or below lo */
    c->hi = c->up ? fminf(c->floor_up + CONTRAST_KNEE, 1.0f) : 2.0f;
    c->lo = c->down ? fmaxf(c->ceil_down - CONTRAST_KNEE, 0.0f) : -1.0f;
    c->keep_hi3 = c->up ? cube_giving_at_least(c->hi) : INFINITY;
    c->keep_lo3 = c->down ? cube_giving_at_most(c->lo) : -1.0f;
    mark_kept_cells(c);
    return 0;
}

void contrast_free(Contrast *c)
{
    free(c->slot);
    free(c->value);
    free(c->kept);
    memset(c, 0, sizeof *c);
}

/* Which way a pixel of lightness L goes: lighter (1) or darker (0). */
static inline int goes_up(const Contrast *c, float L)
{
    return c->up && (L >= c->bg_l || !c->down);
}

/* The lightness a pixel of lightness L is given. */
static float target(const Contrast *c, float L)
{
    if (!c->up && !c->down)
        return L;
    if (goes_up(c, L)) {
        if (L >= c->hi)
            return L;
        /* [base, hi] onto [floor_up, hi]: base is the background, or
         * black when every pixel goes lighter */
        float base = c->down ? c->bg_l : 0.0f;
        return c->floor_up + (L - base) * (c->hi - c->floor_up) / (c->hi - base);
    }
    if (L <= c->lo)
        return L;
    float top = c->up ? c->bg_l : 1.0f;
    return c->ceil_down - (top - L) * (c->ceil_down - c->lo) / (top - c->lo);
}

/* lin, of lightness L, brought to lightness want: scaled in linear light
 * (OKLab L scales with the cube root of the scale, hue and saturation
 * stay) while that stays in gamut; else the brightest colour of its hue
 * mixed with white until want is reached (black becomes grey). */
static void reach(const float lin[3], float L, float want, float out[3])
{
    float mx = fmaxf(lin[0], fmaxf(lin[1], lin[2]));
    if (L > 1e-6f) {
        float r = want / L, s = r * r * r;
        if (mx * s <= 1.0f) {
            for (int a = 0; a < 3; a++)
                out[a] = lin[a] * s;
            return;
        }
    }
    float base[3], lo = 0, hi = 1;
    for (int a = 0; a < 3; a++)
        base[a] = mx > 0 ? lin[a] / mx : 0.0f;
    for (int k = 0; k < HALVINGS; k++) {
        float t = 0.5f * (lo + hi), mix[3];
        for (int a = 0; a < 3; a++)
            mix[a] = base[a] + t * (1.0f - base[a]);
        if (contrast_lightness(mix) < want)
            lo = t;
        else
            hi = t;
    }
    for (int a = 0; a < 3; a++)
        out[a] = base[a] + hi * (1.0f - base[a]);
}

/* The rounding to bytes may land a hair inside the minimum: step every
 * channel one value outwards until it holds. */
static void nudge(const Contrast *c, int up, uint8_t out[3])
{
    for (int k = 0; k < NUDGES; k++) {
        float l = backdrop_lightness(out);
        if (up ? l >= c->floor_up : l <= c->ceil_down)
            return;
        for (int a = 0; a < 3; a++)
            out[a] = (uint8_t)(up ? (out[a] < 255 ? out[a] + 1 : 255) : (out[a] > 0 ? out[a] - 1 : 0));
    }
}

void contrast_colour(Contrast *c, const uint8_t rgb[3], uint8_t out[3])
{
    float lin[3], moved[3];
    linear(rgb, lin);
    float L = contrast_lightness(lin), want = target(c, L);
    if (want == L) {
        memcpy(out, rgb, 3);
        return;
    }
    reach(lin, L, want, moved);
    for (int a = 0; a < 3; a++)
        out[a] = linear_to_srgb(moved[a]);
    nudge(c, goes_up(c, L), out);
}

/* Whether the fast test proves a colour is kept as it is: its cube's
 * bit. */
static inline int surely_kept(const Contrast *c, const uint8_t p[3])
{
    const int shift = CONTRAST_CELL_BITS, bits = 8 - CONTRAST_CELL_BITS;
    uint32_t cell = (uint32_t)(p[0] >> shift) << (2 * bits) | (uint32_t)(p[1] >> shift) << bits | (uint32_t)(p[2] >> shift);
    return c->kept[cell >> 3] >> (cell & 7) & 1;
}

/* The colour key (24-bit rgb) of a pixel. */
static inline uint32_t key_of(const uint8_t *p)
{
    return (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
}

/* What key becomes: kept, remembered, or worked out and remembered. */
static uint32_t moved_key(Contrast *c, const uint8_t *p, uint32_t key)
{
    if (surely_kept(c, p))
        return key;
    uint32_t h = (key * 2654435761u) >> 20;     /* Fibonacci hashing to 12 bits */
    if (c->slot[h] == (key | 1u << 24))
        return c->value[h];
    uint8_t out[3];
    contrast_colour(c, p, out);
    c->slot[h] = key | 1u << 24;
    c->value[h] = key_of(out);
    return c->value[h];
}

int contrast_apply(Contrast *c, const Backdrop *b, float min, Image *im)
{
    if (min <= 0)
        return 0;               /* colours as given */
    if (contrast_prepare(c, b, min))
        return -1;
    if (!c->up && !c->down)
        return 0;
    size_t n = (size_t)im->w * (size_t)im->h;
    uint32_t last_in = 0xffffffffu, last_out = 0;
    for (size_t i0 = 0; i0 < n; i0 += 8) {
        size_t i1 = n - i0 < 8 ? n : i0 + 8;
        uint64_t any = 0;
        if (i1 - i0 == 8)
            memcpy(&any, im->lit + i0, 8);  /* eight of the background at once (most of a big picture) */
        if (i1 - i0 == 8 && !any)
            continue;
        for (size_t i = i0; i < i1; i++) {
            if (!im->lit[i])
                continue;
            uint8_t *p = im->rgb + 3 * i;
            uint32_t key = key_of(p);
            if (key != last_in) {   /* neighbours mostly share a colour (a face's) */
                last_in = key;
                last_out = moved_key(c, p, key);
            }
            if (last_out == key)
                continue;
            p[0] = (uint8_t)(last_out >> 16);
            p[1] = (uint8_t)(last_out >> 8);
            p[2] = (uint8_t)last_out;
        }
    }
    return 0;
}

/* ==== The backdrop an image gets ==== */

Backdrop backdrop_pick(const Image *im, float min)
{
    size_t n = (size_t)im->w * (size_t)im->h, near_black = 0, near_white = 0;
    float not_black3 = cube_giving_at_least(min), not_white3 = cube_giving_at_most(1 - min);
    uint32_t last = 0xffffffffu;
    int black = 0, white = 0;
    for (size_t i = 0; i < n; i++) {
        if (!im->lit[i])
            continue;
        const uint8_t *p = im->rgb + 3 * i;
        uint32_t key = key_of(p);
        if (key != last) {
            last = key;
            float lin[3];
            linear(p, lin);
            Cones k = cones(lin);
            int far_black = k.l >= not_black3 && k.m >= not_black3;
            int far_white = k.l <= not_white3 && k.m <= not_white3;
            float L = far_black && far_white ? 0.5f : contrast_lightness(lin);
            black = !far_black && L < min;
            white = !far_white && L > 1 - min;
        }
        near_black += (size_t)black;
        near_white += (size_t)white;
    }
    Backdrop b = { { 0, 0, 0 }, 1, BD_PICKED };
    if (near_black > near_white)
        b.rgb[0] = b.rgb[1] = b.rgb[2] = 255;
    return b;
}
