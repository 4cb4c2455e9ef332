/* repair.c: repair_mesh, the steps in order (include/repair.h).
 *
 * Not built yet: this first version refuses every mesh, so that the
 * command line can be built on the interface while the steps are
 * written. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "repair.h"

int repair_mesh(Mesh *m, const RepairOpts *opt, RepairReport *rep, char *err, size_t errlen)
{
    (void)opt;
    memset(rep, 0, sizeof *rep);
    snprintf(err, errlen, "%s: repair is not built yet", m->path ? m->path : "(input)");
    return -1;
}

void repair_report_free(RepairReport *rep)
{
    free(rep->holes);
    rep->holes = NULL;
    rep->nholes = 0;
}
