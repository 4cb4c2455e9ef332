/* guard.c: the repair must not leave the check worse.
 *
 * The check of the input (the "before", on a helper thread beside the
 * check of the result when the repair may use two threads or more: it
 * reads the input, which the repair only copies) and the check of the
 * repaired mesh are compared object by object, figure by figure: a
 * problem the check reports that is new or counts more is worse. The
 * input is checked only when the repair did something that could make
 * a figure worse (repair.c says what cannot). An object that came out
 * worse is repaired again less boldly (repair.c runs every object
 * again, each at its level):
 *
 *   1  fins of an odd number of faces left whole (no face cut loose)
 *   2  no splits and no fills
 *   3  no winding either (weld and clean alone)
 *   4  the object as it was
 *
 * Weld and clean cannot make a figure worse (the check sets degenerate
 * faces aside, and twins.c drops no duplicate that would open an edge),
 * and level 4 changes nothing, so the ladder ends. The levels each
 * object ended at are in the report (RepairReport.held_back). */

#include <string.h>

#include "meshcheck.h"
#include "repair_internal.h"
#include "thread.h"

static void *before_main(void *arg)
{
    Before *b = arg;
    b->rc = meshcheck_run(&b->mc, b->m, &b->co, b->err, sizeof b->err);
    return NULL;
}

int rp_before_start(Before *b, const Mesh *m, const RepairOpts *opt, int now)
{
    memset(b, 0, sizeof *b);
    b->m = m;
    b->co = (CheckOpts){ .threads = now ? opt->threads : 1, .intersections = opt->intersections,
                         .cancel = opt->cancel };
    if (!now && opt->threads > 1 && thread_start(&b->th, before_main, b) == 0) {
        b->threaded = 1;
        return 0;
    }
    before_main(b);
    return b->rc;
}

int rp_before_wait(Before *b)
{
    if (b->threaded) {
        pthread_join(b->th, NULL);
        b->threaded = 0;
    }
    return b->rc;
}

void rp_before_free(Before *b)
{
    rp_before_wait(b);
    if (b->rc == 0)
        meshcheck_free(&b->mc);
    b->rc = -1;
}

/* Is row r of after worse than of before? */
static int row_worse(const CheckRow *r, const CheckCounts *before, const CheckCounts *after)
{
    if (r->bad == CHECK_FINE)
        return 0;
    int was = meshcheck_bad(r, before), is = meshcheck_bad(r, after);
    if (is && !was)
        return 1;
    return r->bad == CHECK_BAD_SET && meshcheck_value(r, after) > meshcheck_value(r, before);
}

uint32_t rp_worse(const MeshCheck *before, const MeshCheck *after, uint8_t *level)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < before->nobjs && i < after->nobjs; i++) {
        int worse = 0;
        for (int k = 0; k < check_nrows && !worse; k++)
            worse = row_worse(&check_rows[k], &before->objs[i].c, &after->objs[i].c);
        if (worse && level[i] < RP_LEVEL_UNTOUCHED) {
            level[i]++;
            n++;
        }
    }
    return n;
}
