/* bed.c: does the model fit a printer's bed, and in which of the six
 * orders of its axes (the axis swaps: as it stands, turned a quarter
 * about the vertical, or on one of its sides). Only the box is asked:
 * a part that fits in no order of its axes might still fit turned by
 * some other angle (a long rod across the bed's diagonal); the report
 * says "axis orders", not "every way". */

#include <stdio.h>

#include "printq.h"

/* The model's axis (0 x, 1 y, 2 z) an UpAxis names. */
static int up_axis_index(int up)
{
    switch (up) {
    case UP_X: case UP_NEG_X: return 0;
    case UP_Z: case UP_NEG_Z: return 2;
    default: return 1;
    }
}

void printq_bed_orders(int up, PrintqOrders *out)
{
    int u = up_axis_index(up);
    int a = u == 0 ? 1 : 0, b = u == 2 ? 1 : 2;    /* the level axes, in x, y, z order */
    const int ord[PRINTQ_ORDERS][3] = {
        { a, b, u }, { b, a, u },                   /* standing; turned about the vertical */
        { a, u, b }, { u, a, b },                   /* on a side: b up */
        { b, u, a }, { u, b, a },                   /* on a side: a up */
    };
    for (int k = 0; k < PRINTQ_ORDERS; k++)
        for (int i = 0; i < 3; i++)
            out->axis[k][i] = ord[k][i];
}

int printq_bed_fit(const double size[3], const double bed[3], const PrintqOrders *orders,
                   int fits_out[PRINTQ_ORDERS])
{
    int first = -1;
    for (int k = 0; k < PRINTQ_ORDERS; k++) {
        int fits = 1;
        for (int i = 0; i < 3; i++)
            fits &= size[orders->axis[k][i]] <= bed[i];
        fits_out[k] = fits;
        if (fits && first < 0)
            first = k;
    }
    return first;
}

void printq_order_words(const int axis[3], char *buf, size_t len)
{
    static const char xyz[3] = { 'x', 'y', 'z' };
    snprintf(buf, len, "%c %c %c", xyz[axis[0]], xyz[axis[1]], xyz[axis[2]]);
}
