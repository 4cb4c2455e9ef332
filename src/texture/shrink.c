/* shrink.c: an image halved while it is decoded (texture_internal.h).
 * Level j + 1's row y is texture_halve of level j's rows 2y and 2y + 1,
 * made as soon as row 2y + 1 arrives; an odd last row is left out and a
 * level one row high is halved with itself, as texture_build_levels
 * does over the whole image, so the kept level has the very bytes of
 * the whole chain's level `halve`. */

#include <stdlib.h>
#include <string.h>

#include "texture_internal.h"

uint64_t texture_shrink_bytes(int w, int h, int halve)
{
    (void)h;
    uint64_t n = 0;
    for (int j = 0; j < halve; j++, w = w > 1 ? w / 2 : 1)
        n += 2 * (uint64_t)w * 4;
    return n;
}

int texture_shrink_begin(TexShrink *s, Texture *t, int w, int h, int halve)
{
    memset(s, 0, sizeof *s);
    s->t = t;
    s->halve = halve;
    s->lw[0] = w;
    s->lh[0] = h;
    for (int j = 0; j < halve; j++) {
        s->lw[j + 1] = s->lw[j] > 1 ? s->lw[j] / 2 : 1;
        s->lh[j + 1] = s->lh[j] > 1 ? s->lh[j] / 2 : 1;
    }
    if (!texture_alloc_levels(t, s->lw[halve], s->lh[halve]))
        return -1;
    for (int j = 0; j < halve; j++) {
        s->pair[j] = malloc(2 * (size_t)s->lw[j] * 4);
        if (!s->pair[j]) {
            texture_shrink_abort(s);
            return -1;
        }
    }
    texture_encoder_init(&s->enc);
    return 0;
}

/* Where level j's next row goes. */
static uint8_t *slot(TexShrink *s, int j)
{
    if (j == s->halve)
        return s->t->rgba + (size_t)s->got[j] * (size_t)s->lw[j] * 4;
    return s->pair[j] + (size_t)(s->got[j] & 1) * (size_t)s->lw[j] * 4;
}

uint8_t *texture_shrink_row(TexShrink *s) { return slot(s, 0); }

void texture_shrink_push(TexShrink *s)
{
    /* invariant: level j's rows [0, got[j]) are written (and halved on) */
    for (int j = 0; j <= s->halve; j++) {
        if (s->got[j] >= s->lh[j])
            return;             /* past the last row */
        int r = s->got[j]++;
        if (j == s->halve)
            return;
        int one = s->lh[j] == 1;
        if (!one && (!(r & 1)))
            return;             /* the pair's first row: wait for the second (an odd last stays out) */
        texture_halve(&s->enc, s->pair[j], s->lw[j], one ? 1 : 2, slot(s, j + 1), s->lw[j + 1], 1);
    }
}

/* Whether some level holds the first row of a pair (not an odd last
 * row, which is left out). */
static int half_pair(const TexShrink *s)
{
    for (int j = 0; j < s->halve; j++)
        if ((s->got[j] & 1) && s->got[j] < s->lh[j] && s->lh[j] > 1)
            return 1;
    return 0;
}

void texture_shrink_black(TexShrink *s, int n)
{
    int k = s->halve, step = 1 << k;
    while (n > 0 && s->got[0] < s->lh[0]) {
        /* no level waits for the second row of a pair, and the next
         * `step` rows make one kept row, every level having them:
         * that row is the halving of black rows alone, black */
        int whole = !half_pair(s) && n >= step && s->lh[k] > 1;
        for (int j = 0; whole && j <= k; j++)
            whole = s->got[j] + (step >> j) <= s->lh[j];
        if (whole) {
            memset(slot(s, k), 0, (size_t)s->lw[k] * 4);
            for (int j = 0; j <= k; j++)
                s->got[j] += step >> j;
            n -= step;
        } else {
            memset(texture_shrink_row(s), 0, (size_t)s->lw[0] * 4);
            texture_shrink_push(s);
            n--;
        }
    }
}

void texture_shrink_finish(TexShrink *s)
{
    texture_shrink_black(s, s->lh[0] - s->got[0]);
    for (int j = 0; j < s->halve; j++) {
        free(s->pair[j]);
        s->pair[j] = NULL;
    }
    texture_build_levels(s->t);
}

void texture_shrink_abort(TexShrink *s)
{
    for (int j = 0; j < s->halve; j++) {
        free(s->pair[j]);
        s->pair[j] = NULL;
    }
    texture_free(s->t);
}
