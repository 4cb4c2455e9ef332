/* palette: the xterm palette's colours, and RGB -> 256- and 16-colour
 * indices by nearest squared RGB distance (quant.c chooses perceptually
 * and dithers; these plain nearest maps stay for comparison). The 256 map searches only 16..255 (cube and greys):
 * the first 16 are themable, so their real colour is unknown. */

#include "present.h"

/* xterm's default first 16 colours. */
static const uint8_t ansi16[16][3] = {
    {   0,   0,   0 }, { 205,   0,   0 }, {   0, 205,   0 }, { 205, 205,   0 },
    {   0,   0, 238 }, { 205,   0, 205 }, {   0, 205, 205 }, { 229, 229, 229 },
    { 127, 127, 127 }, { 255,   0,   0 }, {   0, 255,   0 }, { 255, 255,   0 },
    {  92,  92, 255 }, { 255,   0, 255 }, {   0, 255, 255 }, { 255, 255, 255 },
};

static const uint8_t cube_level[6] = { 0, 95, 135, 175, 215, 255 };

/* Nearest cube level of one channel; the boundaries are the midpoints. */
static inline int cube_index(int v)
{
    return v < 48 ? 0 : v < 115 ? 1 : v < 155 ? 2 : v < 195 ? 3 : v < 235 ? 4 : 5;
}

static inline int sq(int v) { return v * v; }

int palette_256(const uint8_t rgb[3])
{
    int r = rgb[0], g = rgb[1], b = rgb[2];
    /* The distance is a sum over channels, so the nearest cube colour is
     * the nearest level per channel. */
    int ri = cube_index(r), gi = cube_index(g), bi = cube_index(b);
    int dc = sq(r - cube_level[ri]) + sq(g - cube_level[gi]) + sq(b - cube_level[bi]);
    /* Distance to grey (v,v,v) is 3 (v - mean)^2 + const: the nearest grey
     * step is the one nearest the mean, round((sum/3 - 8) / 10). */
    int sum = r + g + b;
    int k = sum < 24 ? 0 : (sum - 24 + 15) / 30;
    if (k > 23)
        k = 23;
    int gv = 8 + 10 * k;
    int dg = sq(r - gv) + sq(g - gv) + sq(b - gv);
    if (dg < dc)
        return 232 + k;
    return 16 + 36 * ri + 6 * gi + bi;
}

int palette_16(const uint8_t rgb[3])
{
    int best = 0, bestd = 1 << 30;
    for (int i = 0; i < 16; i++) {
        int d = sq(rgb[0] - ansi16[i][0]) + sq(rgb[1] - ansi16[i][1]) + sq(rgb[2] - ansi16[i][2]);
        if (d < bestd) {
            bestd = d;
            best = i;
        }
    }
    return best;
}

void palette_rgb(ColourDepth depth, int idx, uint8_t rgb_out[3])
{
    /* 8 and 16 colours are the first entries of the same table */
    if (depth != COLOUR_256 && idx >= 16)
        idx = 15;
    palette_256_rgb(idx, rgb_out);
}

void palette_256_rgb(int idx, uint8_t rgb_out[3])
{
    if (idx < 0)
        idx = 0;
    if (idx > 255)
        idx = 255;
    if (idx < 16) {
        rgb_out[0] = ansi16[idx][0];
        rgb_out[1] = ansi16[idx][1];
        rgb_out[2] = ansi16[idx][2];
    } else if (idx < 232) {
        int c = idx - 16;
        rgb_out[0] = cube_level[c / 36];
        rgb_out[1] = cube_level[(c / 6) % 6];
        rgb_out[2] = cube_level[c % 6];
    } else {
        uint8_t v = (uint8_t)(8 + 10 * (idx - 232));
        rgb_out[0] = rgb_out[1] = rgb_out[2] = v;
    }
}
