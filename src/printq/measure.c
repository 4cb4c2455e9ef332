/* measure.c: distances and angles between points given as numbers or
 * as vertices (--measure, the viewer's measuring mode). In double from
 * the float positions: a distance between two vertices is as exact as
 * the floats they are. */

#define _DEFAULT_SOURCE         /* M_PI */

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "printq.h"

int printq_point_parse(const char *s, PrintqPoint *pt)
{
    memset(pt, 0, sizeof *pt);
    char *end;
    errno = 0;
    if (s[0] == 'v' && s[1] >= '1' && s[1] <= '9') {
        unsigned long long v = strtoull(s + 1, &end, 10);
        if (*end || errno || v > UINT32_MAX)
            return -1;
        pt->vertex = (uint32_t)v;
        return 0;
    }
    const char *p = s;
    for (int k = 0; k < 3; k++) {
        double v = strtod(p, &end);
        if (end == p || errno || !isfinite(v) || fabs(v) > 1e30 || *end != (k < 2 ? ',' : '\0'))
            return -1;
        pt->p[k] = v;
        p = end + 1;
    }
    return 0;
}

int printq_points_resolve(const Mesh *m, PrintqPoint *pts, int n, char *err, size_t errlen)
{
    for (int i = 0; i < n; i++) {
        if (!pts[i].vertex)
            continue;
        if (pts[i].vertex > m->nverts) {
            snprintf(err, errlen, "v%u: the model has %u vertices", pts[i].vertex, m->nverts);
            return -1;
        }
        const float *p = &m->pos[3 * (size_t)(pts[i].vertex - 1)];
        for (int k = 0; k < 3; k++)
            pts[i].p[k] = p[k];
    }
    return 0;
}

void printq_measure(const PrintqPoint *pts, int n, PrintqMeasure *out)
{
    memset(out, 0, sizeof *out);
    double e[3];
    for (int k = 0; k < 3; k++)
        out->d[k] = pts[1].p[k] - pts[0].p[k];
    out->dist = sqrt(out->d[0] * out->d[0] + out->d[1] * out->d[1] + out->d[2] * out->d[2]);
    if (n < 3)
        return;
    for (int k = 0; k < 3; k++)
        e[k] = pts[2].p[k] - pts[1].p[k];
    out->dist2 = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    if (out->dist == 0 || out->dist2 == 0)
        return;
    /* the angle at b between b->a and b->c: atan2 of |cross| and dot,
     * well-conditioned near 0 and 180 degrees (acos is not) */
    double a[3] = { -out->d[0], -out->d[1], -out->d[2] };
    double cx = a[1] * e[2] - a[2] * e[1], cy = a[2] * e[0] - a[0] * e[2], cz = a[0] * e[1] - a[1] * e[0];
    double dot = a[0] * e[0] + a[1] * e[1] + a[2] * e[2];
    out->angle = atan2(sqrt(cx * cx + cy * cy + cz * cz), dot) * 180 / M_PI;
}
