#ifndef ZV_PRINTQ_H
#define ZV_PRINTQ_H
/* printq: will it print, and what are its measures. The questions a
 * 3D-printing check asks of a loaded Mesh in its file's coordinates:
 * does it fit a bed (and in which of the six axis orders), which unit
 * its size suggests, which faces overhang (and their area), how thick
 * its walls are (a ray cast inward from each face, through the BVH of
 * geom/), and the distances and angles between points or vertices.
 * Knows nothing of scenes, pictures or reports: numbers in, numbers out.
 * The up axis is an UpAxis (mesh.h): the model's axis that points up. */

#include <stddef.h>
#include <stdint.h>

#include "mesh.h"

/* ==== The bed (bed.c) ==== */

/* The six orders of the model's axes along the bed's width, depth and
 * height: order k lays model axis printq_orders[k][i] along bed axis i.
 * Order 0 is the model as it stands (its two level axes in x, y, z
 * order along W and D, its up axis along H); order 1 the same turned a
 * quarter about the vertical (the level axes swapped); orders 2 to 5 on
 * a side. printq_bed_orders fills them for an up axis. */
#define PRINTQ_ORDERS 6
typedef struct {
    int axis[PRINTQ_ORDERS][3];         /* 0 x, 1 y, 2 z of the model */
} PrintqOrders;
void printq_bed_orders(int up, PrintqOrders *out);

/* Does a box of size[3] (the model's x, y, z extents) fit within
 * bed[3] (W, D, H) in each order: fits_out[k] 1 or 0 (touching fits).
 * Returns the first order that fits, -1 none. */
int printq_bed_fit(const double size[3], const double bed[3], const PrintqOrders *orders,
                   int fits_out[PRINTQ_ORDERS]);

/* "x, y, z" as the orders lay them: "y x z" for order {1, 0, 2}. */
void printq_order_words(const int axis[3], char *buf, size_t len);

/* ==== Units (units.c) ==== */

/* The unit a size suggests when the format states none: "in" when its
 * longest side is 0.5 to 20 and every side is within 0.2% (or 0.001)
 * of a sixteenth, one of them not a whole number; "m" when its longest
 * side is 0.001 to 0.5 (in millimetres it would be under half a
 * millimetre); else NULL. Never used to rescale anything. */
const char *printq_unit_guess(const double size[3]);

/* --unit's words: millimetres in one unit ("mm" 1, "in" 25.4, "m"
 * 1000); 0 for any other word. And the unit's name in words. */
double      printq_unit_mm(const char *unit);
const char *printq_unit_words(const char *unit);

/* ==== Overhangs (overhang.c) ==== */

/* Faces that overhang: their outward normal points down (against the
 * up axis) more steeply than deg degrees from the horizontal, so that
 * the face leans out past deg from the vertical (Blender's 3D-Print
 * Toolbox's rule: the angle between the normal and straight down under
 * 90 - deg). A face lying on the bed (every corner at the model's
 * lowest height) rests on it and is not an overhang; nor is a face of
 * no area. flag_out (NULL: not wanted) gets 1 per overhanging face;
 * returns their area in file units squared (double, Newell's area). */
double printq_overhang(const Mesh *m, int up, double deg, uint8_t *flag_out);

/* Face f's Newell vector: twice its area times its unit normal, in
 * double from the float corners. */
void printq_newell(const Mesh *m, uint32_t f, double out[3]);

/* ==== Wall thickness (thickness.c) ==== */

/* The thickness at each face: one ray from its centroid along its
 * reversed normal (inward, on an outward-facing surface) to the first
 * other face it meets, through a BVH of the triangles (the single-ray
 * "ray-based" thickness; Shapira, Shamir and Cohen-Or 2008 take the
 * median of a cone of rays, the shape diameter function). A face whose
 * ray meets nothing (an open model, a face seen from inside) has none
 * (a negative value). Threads share the rays. */
typedef struct {
    float   *face;          /* per face: the thickness, file units; < 0: none */
    uint32_t nfaces;
    uint32_t measured;      /* faces with a thickness */
    double   min;           /* the least thickness (0 when none measured) */
    uint32_t min_face;      /* its face */
    double   min_at[3];     /* its ray's start: the face's centroid */
    double   median;        /* of the faces measured, by face */
} PrintqThickness;

int  printq_thickness(const Mesh *m, int threads, PrintqThickness *out, char *err, size_t errlen);
void printq_thickness_free(PrintqThickness *t);
/* The area of the faces measured thinner than limit, file units squared. */
double printq_thin_area(const Mesh *m, const PrintqThickness *t, double limit);

/* ==== Measuring (measure.c) ==== */

/* A point of --measure: X,Y,Z, or vN (the N-th vertex as loaded, 1 the
 * first). */
typedef struct {
    double   p[3];
    uint32_t vertex;        /* 1-based when given as vN; 0: given as numbers */
} PrintqPoint;

/* "X,Y,Z" or "vN" into pt (the vertex's position filled later): 0, or
 * -1 not a point. */
int printq_point_parse(const char *s, PrintqPoint *pt);
/* The vertices of the points given as vN from m: 0, or -1 with the
 * reason in err (a vertex past the mesh's). */
int printq_points_resolve(const Mesh *m, PrintqPoint *pts, int n, char *err, size_t errlen);

/* Two points: distance and difference (b - a). Three: also the angle at
 * the middle point b between a and c, degrees (0 when a or c is b). */
typedef struct {
    double d[3];            /* b - a */
    double dist;            /* |b - a| */
    double dist2;           /* |c - b| (three points) */
    double angle;           /* degrees, three points */
} PrintqMeasure;
void printq_measure(const PrintqPoint *pts, int n, PrintqMeasure *out);

#endif
