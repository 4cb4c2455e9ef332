/* scenebig.c: the differential fuzzer's large meshes (scenecode.h: the
 * part after the points and lines). A few bytes give tens of thousands
 * of triangles, as real models have and the hand-written objects never
 * reach: deep octrees, full pyramids, front-end work split between
 * threads and long SIMD loops with their tails. The shapes are smooth
 * enough that most triangles cover a sample or two at the fuzzer's
 * image sizes, rather than all collapsing into one pixel. */

#include <math.h>

#include "scenecode.h"
#include "testlib.h"

typedef struct {
    Mesh    *m;
    double   c[3], size;        /* the centre and the half extent */
    uint32_t v0, faces_left;
    uint32_t st;                /* xorshift state */
} Big;

static uint32_t rnd(Big *b)
{
    b->st ^= b->st << 13;
    b->st ^= b->st >> 17;
    b->st ^= b->st << 5;
    return b->st;
}

/* A number in [-1, 1). */
static double unit_rnd(Big *b)
{
    return (double)(rnd(b) >> 8) / (1 << 23) - 1;
}

/* The vertex c + size * (x, y, z); not finite (a huge size): c itself. */
static int vert(Big *b, double x, double y, double z)
{
    double d[3] = { x, y, z };
    float p[3];
    for (int i = 0; i < 3; i++) {
        p[i] = (float)(b->c[i] + b->size * d[i]);
        if (!isfinite(p[i]))
            p[i] = (float)b->c[i];
    }
    return tl_mesh_vertex(b->m, p[0], p[1], p[2]);
}

/* The triangle of the mesh's vertices v0 + (i, j, k), within the budget
 * (a face past it is left out, not an error). */
static int tri(Big *b, uint32_t i, uint32_t j, uint32_t k)
{
    if (b->faces_left == 0)
        return 0;
    b->faces_left--;
    uint32_t c[3] = { b->v0 + i, b->v0 + j, b->v0 + k };
    return tl_mesh_face(b->m, c, 3);
}

/* A quad of the grid of rows `row` vertices long as two triangles, split
 * along either diagonal at random. */
static int quad(Big *b, uint32_t row, int i, int j)
{
    uint32_t a = (uint32_t)j * row + (uint32_t)i, q[4] = { a, a + 1, a + row + 1, a + row };
    if (rnd(b) & 1)
        return tri(b, q[0], q[1], q[2]) || tri(b, q[0], q[2], q[3]);
    return tri(b, q[0], q[1], q[3]) || tri(b, q[1], q[2], q[3]);
}

/* Smooth hills over [-1, 1]^2: four waves of random direction and
 * phase, of height amp in all. */
typedef struct {
    double kx[4], ky[4], ph[4], amp;
} Hills;

static void hills_init(Big *b, Hills *h, double amp)
{
    for (int k = 0; k < 4; k++) {
        h->kx[k] = 6 * unit_rnd(b);
        h->ky[k] = 6 * unit_rnd(b);
        h->ph[k] = 3.2 * unit_rnd(b);
    }
    h->amp = amp / 4;
}

static double hills_at(const Hills *h, double x, double y)
{
    double z = 0;
    for (int k = 0; k < 4; k++)
        z += cos(h->kx[k] * x + h->ky[k] * y + h->ph[k]);
    return h->amp * z;
}

/* A grid of g x g quads over [-1, 1]^2 at height z0 plus hills. */
static int sheet(Big *b, int g, double z0, double amp)
{
    Hills h;
    hills_init(b, &h, amp);
    b->v0 = b->m->nverts;
    for (int j = 0; j <= g; j++)
        for (int i = 0; i <= g; i++) {
            double x = 2.0 * i / g - 1, y = 2.0 * j / g - 1;
            if (vert(b, x, y, z0 + hills_at(&h, x, y)))
                return -1;
        }
    for (int j = 0; j < g; j++)
        for (int i = 0; i < g; i++)
            if (quad(b, (uint32_t)g + 1, i, j))
                return -1;
    return 0;
}

/* A closed sphere of segs x rings quads (triangles at the poles),
 * bumpy when asked: its radius varies by up to a fifth. */
static int sphere(Big *b, int segs, int rings, int bumpy)
{
    Hills h;
    hills_init(b, &h, bumpy ? 0.2 : 0);
    b->v0 = b->m->nverts;
    if (vert(b, 0, 0, 1) || vert(b, 0, 0, -1))
        return -1;
    for (int j = 1; j <= rings; j++)
        for (int i = 0; i < segs; i++) {
            double th = 3.141592653589793 * j / (rings + 1), ph = 6.283185307179586 * i / segs;
            double r = 1 + hills_at(&h, th, ph);
            if (vert(b, r * sin(th) * cos(ph), r * sin(th) * sin(ph), r * cos(th)))
                return -1;
        }
    uint32_t last = 2 + (uint32_t)((rings - 1) * segs);
    for (int i = 0; i < segs; i++) {
        uint32_t i0 = (uint32_t)i, i1 = (uint32_t)((i + 1) % segs);
        if (tri(b, 0, 2 + i0, 2 + i1) || tri(b, 1, last + i1, last + i0))
            return -1;
        for (int j = 0; j + 1 < rings; j++) {
            uint32_t a = 2 + (uint32_t)(j * segs), c = a + (uint32_t)segs;
            if (tri(b, a + i0, c + i0, c + i1) || tri(b, a + i0, c + i1, a + i1))
                return -1;
        }
    }
    return 0;
}

/* Small triangles strewn through the cube: they cross one another. */
static int soup(Big *b, int count, double len)
{
    b->v0 = b->m->nverts;
    for (int t = 0; t < count; t++) {
        double c[3] = { unit_rnd(b), unit_rnd(b), unit_rnd(b) };
        for (int k = 0; k < 3; k++)
            if (vert(b, c[0] + len * unit_rnd(b), c[1] + len * unit_rnd(b), c[2] + len * unit_rnd(b)))
                return -1;
        if (tri(b, 3 * (uint32_t)t, 3 * (uint32_t)t + 1, 3 * (uint32_t)t + 2))
            return -1;
    }
    return 0;
}

int sc_big_mesh(Mesh *m, unsigned kind, unsigned n, unsigned seed, const double centre[3], double size,
                uint32_t max_faces)
{
    Big b = { .m = m, .c = { centre[0], centre[1], centre[2] }, .size = size, .faces_left = max_faces,
              .st = seed * 2654435761u + 11 };
    switch (kind % 4) {
    case 0:     /* a terrain: up to 144 x 144 quads, 41,472 triangles */
        return sheet(&b, 24 + (int)(n % 16) * 8, 0, (n >> 4) / 16.0);
    case 1: {   /* a sphere: up to 226 x 113, 51,076 triangles */
        int segs = 16 + (int)(n % 16) * 14;
        return sphere(&b, segs, segs / 2, n >> 4 & 1);
    }
    case 2:     /* a soup: up to 8,192 triangles, each 1/2 .. 1/256 of the cube across.
                 * Not more: span keeps a row's crossings sorted by insertion,
                 * which is quadratic when most edges cross from row to row,
                 * and 15,000 such triangles took a minute under the fuzzer */
        return soup(&b, 512 * (1 + (int)(n % 16)), ldexp(1, -1 - (int)(n >> 5)));
    default:    /* layers one behind another: up to 16 sheets of 2,592 triangles */
        for (int k = 0, layers = 1 + (int)(n % 16); k < layers; k++)
            if (sheet(&b, 36, layers > 1 ? 2.0 * k / (layers - 1) - 1 : 0, (n >> 4) / 32.0))
                return -1;
        return 0;
    }
}
