/* markcolour.c: what --check found, in colour (Scene.marks, shade.h).
 *
 * The warning colours are fully saturated, unlike the muted colours
 * objects get (layout.c) and the greys of a model without any, so that a
 * marked face never passes for an object's; the contrast rule
 * (contrast.c) keeps them a lightness away from the terminal's
 * background, as every drawn pixel. A part's colour comes from a table
 * of twelve hues of middle lightness (OKLab L 0.6 to 0.8: clear of
 * black and of white), neighbours far apart in hue; beyond twelve parts
 * the table repeats a step lighter or darker, so that parts 1 and 13
 * still differ. */

#include <stdlib.h>
#include <string.h>

#include "shade.h"

static const uint8_t edge_rgb[2][3] = {
    { 255, 48, 48 },        /* MARK_BOUNDARY: the holes' edges, red */
    { 235, 40, 235 },       /* MARK_NONMANIFOLD: magenta */
};
static const uint8_t flipped_rgb[3] = { 30, 60, 255 };     /* seen from inside: blue */
static const uint8_t crossing_rgb[3] = { 255, 220, 0 };    /* crossing another face: yellow */

static const uint8_t part_rgb[12][3] = {
    { 230, 120, 60 },  { 70, 170, 230 }, { 150, 200, 60 },  { 200, 110, 210 },
    { 240, 190, 50 },  { 60, 190, 160 }, { 230, 100, 130 }, { 120, 140, 240 },
    { 190, 160, 90 },  { 100, 200, 100 }, { 210, 140, 170 }, { 80, 180, 200 },
};

void shade_mark_edge_colour(int kind, uint8_t rgb_out[3])
{
    memcpy(rgb_out, edge_rgb[kind == MARK_NONMANIFOLD], 3);
}

void shade_mark_face_colour(int bits, uint8_t rgb_out[3])
{
    memcpy(rgb_out, bits & MARK_CROSSING ? crossing_rgb : flipped_rgb, 3);
}

void shade_problem_colour(int kind, uint8_t rgb_out[3])
{
    static const uint8_t orange[3] = { 255, 140, 0 };
    const uint8_t *c = kind == CHECK_LOC_HOLES ? edge_rgb[0]
                     : kind == CHECK_LOC_NM_EDGES || kind == CHECK_LOC_NM_VERTICES ? edge_rgb[1]
                     : kind == CHECK_LOC_FLIPPED ? flipped_rgb
                     : kind == CHECK_LOC_CROSSING ? crossing_rgb : orange;
    memcpy(rgb_out, c, 3);
}

void shade_part_colour(uint32_t part, uint8_t rgb_out[3])
{
    const uint8_t *c = part_rgb[part % 12];
    /* each round of the table a step lighter, then darker: 1, 0.8, 1.15, ... */
    static const float step[4] = { 1.0f, 0.8f, 1.15f, 0.9f };
    float k = step[part / 12 % 4];
    for (int a = 0; a < 3; a++) {
        float v = c[a] * k;
        rgb_out[a] = (uint8_t)(v > 255 ? 255 : v + 0.5f);
    }
}

void mark_colours_free(MarkColours *mc)
{
    free(mc->rgb);
    free(mc->surf);
    memset(mc, 0, sizeof *mc);
}

/* Room for n faces. -1 out of memory. */
static int grow(MarkColours *mc, uint32_t n, int surf)
{
    if (n > mc->cap || (surf && !mc->surf)) {
        uint8_t *rgb = realloc(mc->rgb, 3 * (size_t)n + 1);
        if (!rgb)
            return -1;
        mc->rgb = rgb;
        free(mc->surf);
        mc->surf = NULL;
        mc->cap = n;
    }
    if (surf && !mc->surf && !(mc->surf = malloc((size_t)(mc->cap ? mc->cap : 1) * sizeof *mc->surf)))
        return -1;
    return 0;
}

int shade_mark_colours(MarkColours *mc, const Scene *s, int mode, const FaceTint *tint)
{
    const SceneMarks *mk = &s->marks;
    int problems = mode & 1, parts = mode & 2;
    int tinted = tint && tint->rgba && tint->nfaces;
    int marked = mk->set && mk->nfaces && (parts || mk->nflagged);
    if (!marked && !tinted)
        return 0;
    uint32_t tgen = tinted ? tint->gen : 0;
    if (mc->key == s && mc->key_gen == s->gen && mc->key_marks == mk->gen && mc->key_mode == mode &&
        mc->key_nfaces == s->nfaces && mc->key_tint == tgen)
        return 1;
    uint32_t n = s->nfaces;
    /* parts: every face plain, in its part's colour; problems alone: the
     * marked faces plain, the others as they were */
    int keep_surf = !(parts && marked) && s->face_surf;
    mc->key = NULL;
    if (grow(mc, n, keep_surf))
        return -1;
    if (!keep_surf) {
        free(mc->surf);
        mc->surf = NULL;
    } else {
        memcpy(mc->surf, s->face_surf, (size_t)n * sizeof *mc->surf);
    }
    if (s->face_rgb)
        memcpy(mc->rgb, s->face_rgb, 3 * (size_t)n);
    else
        for (uint32_t g = 0; g < n; g++)
            memcpy(&mc->rgb[3 * (size_t)g], scene_default_rgb, 3);     /* the compact form's one colour */
    /* grid copies repeat the loaded faces in order */
    for (uint32_t g = 0; g < n; g++) {
        uint8_t *rgb = &mc->rgb[3 * (size_t)g];
        if (marked && parts)
            shade_part_colour(mk->face_part[g % mk->nfaces], rgb);
        const uint8_t *t = tinted ? &tint->rgba[4 * (size_t)(g % tint->nfaces)] : NULL;
        if (t && t[3]) {
            memcpy(rgb, t, 3);
            if (mc->surf)
                mc->surf[g] = SURF_PLAIN;
        }
        if (marked && problems && mk->face[g % mk->nfaces]) {
            shade_mark_face_colour(mk->face[g % mk->nfaces], rgb);
            if (mc->surf)
                mc->surf[g] = SURF_PLAIN;
        }
    }
    mc->key = s;
    mc->key_gen = s->gen;
    mc->key_marks = mk->gen;
    mc->key_mode = mode;
    mc->key_nfaces = n;
    mc->key_tint = tgen;
    return 1;
}

void shade_thickness_colour(double t, uint8_t rgb_out[3])
{
    /* red, yellow, green, blue at 0, 1/3, 2/3, 1: saturated, as the
     * warnings are, so that no object's muted colour passes for one */
    static const uint8_t stop[4][3] = { { 235, 40, 30 }, { 240, 220, 40 }, { 40, 190, 70 }, { 40, 90, 235 } };
    double x = !(t > 0) ? 0 : t >= 1 ? 3 : 3 * t;
    int i = x >= 3 ? 2 : (int)x;
    double f = x - i;
    for (int a = 0; a < 3; a++)
        rgb_out[a] = (uint8_t)(stop[i][a] + (stop[i + 1][a] - stop[i][a]) * f + 0.5);
}

void shade_overhang_colour(uint8_t rgb_out[3])
{
    static const uint8_t red[3] = { 225, 30, 60 };
    memcpy(rgb_out, red, 3);
}
