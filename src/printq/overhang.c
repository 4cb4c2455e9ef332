/* overhang.c: the faces that overhang, and their area. A face leans
 * out past deg from the vertical when its outward unit normal n has
 * -n.up > sin(deg): the rule of Blender's 3D-Print Toolbox (the angle
 * between the normal and straight down under 90 - deg), which slicers
 * share. A face whose every corner sits at the model's lowest height
 * lies on the bed and needs no support. The normal and area are
 * Newell's, in double from the float corners. */

#define _DEFAULT_SOURCE         /* M_PI */

#include <math.h>
#include <string.h>

#include "printq.h"

/* The up axis as a model-space unit vector. */
static void up_vector(int up, double u[3])
{
    static const double v[UP_COUNT][3] = {
        [UP_Y] = { 0, 1, 0 },  [UP_Z] = { 0, 0, 1 },  [UP_X] = { 1, 0, 0 },
        [UP_NEG_Y] = { 0, -1, 0 }, [UP_NEG_Z] = { 0, 0, -1 }, [UP_NEG_X] = { -1, 0, 0 },
    };
    memcpy(u, v[up >= 0 && up < UP_COUNT ? up : UP_Y], sizeof v[0]);
}

void printq_newell(const Mesh *m, uint32_t f, double out[3])
{
    out[0] = out[1] = out[2] = 0;
    uint32_t c0 = m->face_start[f], n = m->face_start[f + 1] - c0;
    for (uint32_t k = 0; k < n; k++) {
        const float *a = &m->pos[3 * (size_t)m->corner[c0 + k]];
        const float *b = &m->pos[3 * (size_t)m->corner[c0 + (k + 1) % n]];
        out[0] += ((double)a[1] - b[1]) * ((double)a[2] + b[2]);
        out[1] += ((double)a[2] - b[2]) * ((double)a[0] + b[0]);
        out[2] += ((double)a[0] - b[0]) * ((double)a[1] + b[1]);
    }
}

double printq_overhang(const Mesh *m, int up, double deg, uint8_t *flag_out)
{
    double u[3];
    up_vector(up, u);
    /* the lowest height of any face's corner: the bed */
    double low = INFINITY;
    for (uint32_t c = 0; m->nfaces && c < m->face_start[m->nfaces]; c++) {
        const float *p = &m->pos[3 * (size_t)m->corner[c]];
        double h = u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
        low = h < low ? h : low;
    }
    double s = sin(deg * M_PI / 180), area = 0;
    for (uint32_t f = 0; f < m->nfaces; f++) {
        double nv[3];
        printq_newell(m, f, nv);
        double len = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
        double down = len > 0 ? -(nv[0] * u[0] + nv[1] * u[1] + nv[2] * u[2]) / len : 0;
        int over = down > s;
        if (over) {
            int on_bed = 1;
            for (uint32_t c = m->face_start[f]; on_bed && c < m->face_start[f + 1]; c++) {
                const float *p = &m->pos[3 * (size_t)m->corner[c]];
                on_bed = u[0] * p[0] + u[1] * p[1] + u[2] * p[2] == low;
            }
            over = !on_bed;
        }
        if (over)
            area += len / 2;
        if (flag_out)
            flag_out[f] = (uint8_t)over;
    }
    return area;
}
