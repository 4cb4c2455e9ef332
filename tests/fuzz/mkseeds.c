/* mkseeds.c: writes the differential fuzzer's seed scenes in the format of
 * scenecode.h (make fuzz-seeds; the output is committed under
 * tests/fuzz/seeds/diff). Each seed is a case the agreement tests know to
 * be hard: shared edges, piercing and cyclic faces, concave and
 * non-planar outlines, the near plane, tiny objects far from the origin,
 * huge coordinates, grid copies, pans, zooms, pixel aspects. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenecode.h"

typedef struct {
    uint8_t b[8192];
    size_t  n;
} Out;

static void w8(Out *o, unsigned v)
{
    if (o->n < sizeof o->b)
        o->b[o->n++] = (uint8_t)v;
}

static void w16(Out *o, int v)
{
    w8(o, (unsigned)v & 0xff);
    w8(o, ((unsigned)v >> 8) & 0xff);
}

static void wangle(Out *o, double deg)
{
    long v = lround(deg * 32768 / 180);
    w16(o, (int)(v > 32767 ? 32767 : v < -32768 ? -32768 : v));
}

/* The nearest coord code (i16 m, u8 e) to x. */
static void wcoord(Out *o, double x)
{
    int e = 0;
    while (e < 63 && fabs(x) > ldexp(1, e - 24) * (32767.0 / 32768))
        e++;
    w16(o, (int)lround(x / ldexp(1, e - 24) * 32768));
    w8(o, (unsigned)e);
}

static void wraw(Out *o, float f)
{
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    w16(o, (int)(bits & 0xffff));
    w16(o, (int)(bits >> 16));
}

typedef struct {
    int    w, h, flags;         /* flags: SC_*, aspect code in bits 5-7 */
    double custom_aspect;
    double fov, yaw, pitch, roll, fit[3], zoom;
    int    pan_scale;
    double pan_x, pan_y;        /* -1 .. 1 of sc_pan_scales[pan_scale] */
} Head;

static void whead(Out *o, const Head *h)
{
    w8(o, (unsigned)h->w - 1);
    w8(o, (unsigned)h->h - 1);
    w8(o, (unsigned)h->flags);
    if ((h->flags >> 5) == 7)
        w8(o, (unsigned)lround((h->custom_aspect - 0.25) * 32));
    w8(o, (unsigned)lround((h->fov - 2) * 255 / 176));
    wangle(o, h->yaw);
    wangle(o, h->pitch);
    wangle(o, h->roll);
    if (h->flags & SC_REFIT)
        for (int i = 0; i < 3; i++)
            wangle(o, h->fit[i]);
    w16(o, (int)lround((log10(h->zoom) + 3) / 6 * 65535));
    w8(o, (unsigned)h->pan_scale);
    w16(o, (int)lround(h->pan_x * 32767));
    w16(o, (int)lround(h->pan_y * 32767));
}

typedef struct {
    int           flags;        /* SO_* */
    double        base[3];
    int           unit;         /* vertex step 2^(unit - 40) */
    int           nv;
    const int   (*v)[3];        /* deltas in steps */
    int           nf;
    const uint8_t *faces;       /* per face: corner count, then indices */
    double        turn[3], move[3], scale;   /* SO_PLACED */
    int           gen[3];       /* SO_GEN: kind, n, seed */
} Obj;

static void wobj(Out *o, const Obj *b)
{
    w8(o, (unsigned)b->flags);
    for (int i = 0; i < 3; i++) {
        if (b->flags & SO_RAW)
            wraw(o, (float)b->base[i]);
        else
            wcoord(o, b->base[i]);
    }
    w8(o, (unsigned)b->unit);
    if (b->flags & SO_GEN) {
        w8(o, (unsigned)b->gen[0]);
        w8(o, (unsigned)b->gen[1]);
        w16(o, b->gen[2]);
    }
    w8(o, (unsigned)b->nv - 3);
    for (int k = 0; k < b->nv; k++)
        for (int i = 0; i < 3; i++) {
            if (b->flags & SO_WIDE)
                w16(o, b->v[k][i]);
            else
                w8(o, (unsigned)b->v[k][i] & 0xff);
        }
    w8(o, (unsigned)b->nf - 1);
    const uint8_t *f = b->faces;
    for (int k = 0; k < b->nf; k++) {
        int n = *f++;
        /* 5 + code % 12 corners: 224 % 12 is 8, hence the turn */
        w8(o, n == 3 ? 0 : n == 4 ? 160 : 224 + (unsigned)(n - 5 + 4) % 12);
        for (int c = 0; c < n; c++)
            w8(o, *f++);
    }
    if (b->flags & SO_PLACED) {
        for (int i = 0; i < 3; i++)
            wangle(o, b->turn[i]);
        for (int i = 0; i < 3; i++) {
            if (b->flags & SO_RAW)
                wraw(o, (float)b->move[i]);
            else
                wcoord(o, b->move[i]);
        }
        w8(o, (unsigned)lround((log10(b->scale) + 3) / 6 * 255));
    }
}

/* A mesh of points and lines (scenecode.h, after the meshes). */
typedef struct {
    int            flags;       /* PF_* */
    double         base[3];
    int            unit;
    int            copy;        /* PF_COPY: the mesh whose vertices it takes */
    int            nv;
    const int    (*v)[3];
    int            cloud[2];    /* PF_CLOUD: n, seed */
    int            np;
    const uint8_t *pts;
    int            nl;
    const uint8_t *lines;       /* per line: corner count, then indices */
    double         turn[3], move[3], scale;
} PObj;

/* The style byte: point size and line width in samples, wireframe,
 * every point drawn. */
static void wstyle(Out *o, int size, int width, int wire, int all)
{
    w8(o, (unsigned)(size - 1) | (unsigned)(width - 1) << 3 | (unsigned)wire << 6 | (unsigned)all << 7);
}

static void wpobj(Out *o, const PObj *b)
{
    w8(o, (unsigned)b->flags);
    for (int i = 0; i < 3; i++)
        wcoord(o, b->base[i]);
    w8(o, (unsigned)b->unit);
    if (b->flags & PF_COPY) {
        w8(o, (unsigned)b->copy);
    } else {
        w8(o, (unsigned)b->nv - 1);
        for (int k = 0; k < b->nv; k++)
            for (int i = 0; i < 3; i++)
                w8(o, (unsigned)b->v[k][i] & 0xff);
    }
    if (b->flags & PF_CLOUD) {
        w8(o, (unsigned)b->cloud[0]);
        w16(o, b->cloud[1]);
    } else {
        w8(o, (unsigned)b->np);
        for (int k = 0; k < b->np; k++)
            w8(o, b->pts[k]);
    }
    w8(o, (unsigned)b->nl);
    const uint8_t *l = b->lines;
    for (int k = 0; k < b->nl; k++) {
        int n = *l++;
        w8(o, (unsigned)n - 2);
        for (int c = 0; c < n; c++)
            w8(o, *l++);
    }
    if (b->flags & PF_PLACED) {
        for (int i = 0; i < 3; i++)
            wangle(o, b->turn[i]);
        for (int i = 0; i < 3; i++)
            wcoord(o, b->move[i]);
        w8(o, (unsigned)lround((log10(b->scale) + 3) / 6 * 255));
    }
}

/* The part after the points and lines (scenecode.h): the polygons'
 * order, the hidden-surface SIMD level (0 every level), the shuffle's
 * seed; then a large mesh (kind, n, seed, its centre, its half extent
 * 2^(size - 32)) when kind >= 0. Written after the style byte and the
 * points' and lines' meshes. */
static void wrun(Out *o, int order, int hsr_simd, int seed, int kind, int n, int bseed, const double c[3], int size)
{
    w8(o, (unsigned)order | (unsigned)hsr_simd << 2);
    w16(o, seed);
    w8(o, kind >= 0);
    if (kind < 0)
        return;
    w8(o, (unsigned)kind);
    w8(o, (unsigned)n);
    w16(o, bseed);
    for (int i = 0; i < 3; i++)
        wcoord(o, c[i]);
    w8(o, (unsigned)size);
}

/* Section planes after the run part (scenecode.h): n planes, each
 * kind, the point across the first mesh's box, a slanted one's normal. */
static void wplanes(Out *o, int n, const uint8_t (*pl)[7])
{
    w8(o, (unsigned)n);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 7; k++)
            w8(o, pl[i][k]);
}

static int save(const char *dir, const char *name, const Out *o)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(o->b, 1, o->n, f) != o->n || fclose(f) != 0) {
        perror(path);
        return -1;
    }
    return 0;
}

/* ==== shapes ==== */

static const int cube_v[8][3] = { { -64, -64, -64 }, { 64, -64, -64 }, { -64, 64, -64 }, { 64, 64, -64 },
                                  { -64, -64, 64 },  { 64, -64, 64 },  { -64, 64, 64 },  { 64, 64, 64 } };
static const uint8_t cube_f[] = { 4, 0, 2, 3, 1, 4, 4, 5, 7, 6, 4, 0, 1, 5, 4,
                                  4, 2, 6, 7, 3, 4, 0, 4, 6, 2, 4, 1, 3, 7, 5 };

static const int pierce_v[9][3] = { { -100, -100, 0 }, { 100, -100, 0 }, { 0, 100, 0 },
                                    { -100, 0, -100 }, { 100, 0, 100 },  { 20, 10, 100 },
                                    { -100, 50, 100 }, { 100, -50, -100 }, { 0, -100, 70 } };
static const uint8_t pierce_f[] = { 3, 0, 1, 2, 3, 3, 4, 5, 3, 6, 7, 8 };

/* a 16-point star, every other point pulled in and lifted: concave and
 * not planar (split into triangles) */
static int star_v[16][3];
static const uint8_t star_f[] = { 16, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15 };

static void make_star(void)
{
    for (int k = 0; k < 16; k++) {
        double a = 6.283185307179586 * k / 16, r = k % 2 ? 40 : 120;
        star_v[k][0] = (int)lround(r * cos(a));
        star_v[k][1] = (int)lround(r * sin(a));
        star_v[k][2] = k % 2 ? 20 : 0;
    }
}

/* a long open box the perspective eye can sit inside */
static const int corridor_v[8][3] = { { -20, -20, -120 }, { 20, -20, -120 }, { 20, -20, 120 }, { -20, -20, 120 },
                                      { -20, 20, -120 },  { 20, 20, -120 },  { 20, 20, 120 },  { -20, 20, 120 } };
static const uint8_t corridor_f[] = { 4, 0, 1, 2, 3, 4, 7, 6, 5, 4, 4, 0, 3, 7, 4, 4, 1, 5, 6, 2 };

/* three bars in cyclic overlap */
static const int cyclic_v[12][3] = { { -100, -10, 0 }, { 100, -10, 20 }, { 100, 10, 20 }, { -100, 10, 0 },
                                     { -10, -100, 20 }, { 10, -100, 20 }, { 10, 100, 0 }, { -10, 100, 0 },
                                     { -80, -80, 10 }, { -60, -80, 10 }, { 80, 80, 10 }, { 60, 80, 10 } };
static const uint8_t cyclic_f[] = { 4, 0, 1, 2, 3, 4, 4, 5, 6, 7, 4, 8, 9, 10, 11 };

/* two triangles between earlier objects' vertices (SO_SHARE) */
static const int bridge_v[3][3] = { { 0, 0, 0 }, { 10, 0, 0 }, { 0, 10, 0 } };
static const uint8_t bridge_f[] = { 3, 0, 9, 17, 3, 1, 12, 20 };

#define OBJ(fl, bx, by, bz, u, verts, faces, nfaces) \
    { fl, { bx, by, bz }, u, (int)(sizeof verts / sizeof verts[0]), verts, nfaces, faces, { 0, 0, 0 }, { 0, 0, 0 }, 1, { 0, 0, 0 } }

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "tests/fuzz/seeds/diff";
    make_star();
    int rc = 0;
    Out o;
    /* unit 34: steps of 2^-6, so +-64 steps is +-1 */
    Obj cube = OBJ(0, 0, 0, 0, 34, cube_v, cube_f, 6);
    Obj pierce = OBJ(0, 0, 0, 0, 34, pierce_v, pierce_f, 3);
    Obj star = OBJ(0, 0, 0, 0, 34, star_v, star_f, 1);
    Obj corridor = OBJ(0, 0, 0, 0, 34, corridor_v, corridor_f, 4);
    Obj cyclic = OBJ(0, 0, 0, 0, 34, cyclic_v, cyclic_f, 3);

    /* 1: the cube, orthographic, straight on: edges on sample rows */
    Head h = { 80, 48, 0, 0, 50, 0, 0, 0, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    rc |= save(dir, "cube-ortho", &o);

    /* 2: the cube turned, perspective, terminal cells, two threads */
    h = (Head){ 120, 60, SC_PERSP | SC_THREADS2 | 1 << 5, 0, 50, 30, 20, 10, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    rc |= save(dir, "cube-persp-aspect2", &o);

    /* 3: piercing triangles, cyclic bars and a star in one mesh */
    h = (Head){ 160, 100, SC_THREADS2, 0, 50, 10, -15, 5, { 0 }, 1.3, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 2);
    wobj(&o, &pierce); wobj(&o, &cyclic); wobj(&o, &star);
    rc |= save(dir, "pierce-cyclic-star", &o);

    /* 4: small objects about 1e5 from the origin, turned and scaled,
     * perspective, panned, two threads (the case of commit 5d8e448) */
    Obj far1 = OBJ(SO_PLACED, 1e5, -3e4, 7e4, 26, cube_v, cube_f, 6);
    far1.turn[0] = 30; far1.turn[1] = 40; far1.scale = 1.5;
    far1.move[0] = 0.002;
    Obj far2 = OBJ(SO_PLACED, 1e5 + 0.004, -3e4, 7e4 + 0.003, 26, pierce_v, pierce_f, 3);
    far2.turn[2] = 70; far2.scale = 0.7;
    Obj far3 = OBJ(0, 1e5 - 0.003, -3e4 + 0.002, 7e4, 27, star_v, star_f, 1);
    h = (Head){ 200, 120, SC_PERSP | SC_THREADS2, 0, 60, 25, -35, 0, { 0 }, 2.5, 0, 0.2, -0.3 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 2);
    wobj(&o, &far1); wobj(&o, &far2); wobj(&o, &far3);
    rc |= save(dir, "far-tiny-persp", &o);

    /* 5: the same orthographic, terminal cells, fitted at another turn */
    h = (Head){ 100, 50, SC_REFIT | 1 << 5, 0, 50, 80, 10, -20, { 10, 50, 0 }, 4, 0, -0.5, 0.5 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 2);
    wobj(&o, &far1); wobj(&o, &far2); wobj(&o, &far3);
    rc |= save(dir, "far-tiny-ortho-refit", &o);

    /* 6: the eye inside a corridor: the near plane clips */
    h = (Head){ 128, 96, SC_PERSP, 0, 90, 0, 0, 0, { 0 }, 6, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 1);
    wobj(&o, &corridor); wobj(&o, &pierce);
    rc |= save(dir, "corridor-near-plane", &o);

    /* 7: two meshes; the second mesh's last object joins its own earlier
     * objects' vertices (overlapping vertex ranges); culling on */
    Obj bridge = OBJ(SO_SHARE, 0, 0, 0, 34, bridge_v, bridge_f, 2);
    Obj cube2 = cube;
    cube2.base[0] = 2.5;
    h = (Head){ 140, 70, SC_CULL | SC_THREADS2 | 2 << 5, 0, 50, -30, 25, 0, { 0 }, 0.9, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 1);
    w8(&o, 0); wobj(&o, &cube);
    w8(&o, 2); wobj(&o, &pierce); wobj(&o, &cube2); wobj(&o, &bridge);
    rc |= save(dir, "two-meshes-shared-cull", &o);

    /* 8: a 2 x 2 x 2 grid of copies seen in perspective */
    h = (Head){ 160, 120, SC_PERSP | SC_GRID | SC_THREADS2, 0, 40, 35, 30, 0, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 1);
    wobj(&o, &cube); wobj(&o, &star);
    rc |= save(dir, "grid-persp", &o);

    /* 9: huge coordinates: three vertex clusters far out (raw floats)
     * joined by triangles of a fourth object, and a cube 1e11 across;
     * once about 1e18 from the origin, once near the top of the float
     * range (where the scene's radius overflows) */
    static const uint8_t huge_f[] = { 3, 0, 3, 6, 3, 1, 5, 7, 4, 0, 4, 8, 2 };
    for (int k = 0; k < 2; k++) {
        double big = k ? 3e38 : 1e18;
        Obj hx = OBJ(SO_RAW, big / 3, 0, 0, 0, bridge_v, bridge_f, 1);
        Obj hy = OBJ(SO_RAW, 0, big, 0, 0, bridge_v, bridge_f, 1);
        Obj hz = OBJ(SO_RAW, 0, 0, -big / 5, 0, bridge_v, bridge_f, 1);
        Obj hj = OBJ(SO_SHARE, 0, 0, 0, 0, bridge_v, huge_f, 3);
        Obj hc = OBJ(SO_WIDE, 0, 0, 0, 63, cube_v, cube_f, 6);
        h = (Head){ 64, 64, SC_THREADS2, 0, 50, 20, 20, 20, { 0 }, 1, 0, 0, 0 };
        o.n = 0; whead(&o, &h); w8(&o, 1); w8(&o, 3);
        wobj(&o, &hx); wobj(&o, &hy); wobj(&o, &hz); wobj(&o, &hj);
        w8(&o, 0); wobj(&o, &hc);
        rc |= save(dir, k ? "huge-coordinates-float-max" : "huge-coordinates", &o);
    }

    /* 10: zoomed far in and panned across, a custom pixel aspect */
    h = (Head){ 256, 256, SC_THREADS2 | 7 << 5, 1.7, 50, 15, 5, 0, { 0 }, 300, 0, 0.02, -0.01 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 2);
    wobj(&o, &pierce); wobj(&o, &cyclic); wobj(&o, &star);
    rc |= save(dir, "zoom-pan-aspect", &o);

    /* 11: zoomed far out into a few pixels; a one-pixel image */
    h = (Head){ 7, 5, SC_PERSP, 0, 170, 45, 45, 0, { 0 }, 0.08, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 1);
    wobj(&o, &cube); wobj(&o, &cyclic);
    rc |= save(dir, "tiny-image", &o);
    h = (Head){ 1, 1, 0, 0, 50, 0, 0, 0, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &pierce);
    rc |= save(dir, "one-pixel", &o);

    /* 12: generated objects of many faces: a closed sphere (culled, and
     * deep enough for octree nodes), a rough height field (quads that are
     * not planar), a cloud of small triangles; perspective, two threads */
    Obj sphere = OBJ(SO_GEN, 0, 0, 0, 34, bridge_v, bridge_f, 1);
    sphere.gen[0] = 2; sphere.gen[1] = 21 + 22 * 9; sphere.gen[2] = 1;
    Obj field = OBJ(SO_GEN | SO_PLACED, 0, 0, -1.5, 34, bridge_v, bridge_f, 1);
    field.gen[0] = 0; field.gen[1] = 14 + 16 * 3; field.gen[2] = 7;
    field.turn[1] = -60; field.scale = 2;
    Obj cloud = OBJ(SO_GEN, 0.5, 0.5, 1, 33, bridge_v, bridge_f, 1);
    cloud.gen[0] = 1; cloud.gen[1] = 250; cloud.gen[2] = 3;
    h = (Head){ 180, 120, SC_PERSP | SC_THREADS2, 0, 60, 20, 25, 0, { 0 }, 1.2, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 2);
    wobj(&o, &sphere); wobj(&o, &field); wobj(&o, &cloud);
    rc |= save(dir, "generated-persp", &o);
    h.flags = SC_CULL | 1 << 5;
    h.zoom = 3;
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 2);
    wobj(&o, &sphere); wobj(&o, &field); wobj(&o, &cloud);
    rc |= save(dir, "generated-ortho-cull-aspect2", &o);

    /* 13: spheres one behind another in a grid, far from the origin:
     * whole objects hidden (the octree's object and node culling) */
    Obj fs = OBJ(SO_GEN, 1e5, 2e5, -1e5, 30, bridge_v, bridge_f, 1);
    fs.gen[0] = 2; fs.gen[1] = 15 + 22 * 5; fs.gen[2] = 9;
    h = (Head){ 200, 150, SC_PERSP | SC_GRID | SC_THREADS2, 0, 45, 5, 5, 0, { 0 }, 1.5, 0, 0.05, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0);
    wobj(&o, &fs);
    rc |= save(dir, "generated-far-grid", &o);

    /* 14: points on the cube's corners and lines along its edges (the
     * same float vertices: ties with the faces' depths), the wireframe
     * over it, squares of 2 samples; perspective, two threads */
    static const uint8_t corner_pts[] = { 0, 1, 2, 3, 4, 5, 6, 7 };
    static const uint8_t cube_lines[] = { 5, 0, 1, 3, 2, 0, 2, 4, 7, 3, 6, 5, 1 };
    PObj on_cube = { PF_COPY, { 0, 0, 0 }, 34, 0, 0, NULL, { 0, 0 }, 8, corner_pts, 3, cube_lines,
                     { 0 }, { 0 }, 1 };
    h = (Head){ 120, 90, SC_PERSP | SC_THREADS2, 0, 50, 30, 20, 10, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    wstyle(&o, 2, 1, 1, 0); w8(&o, 1 | 1 << 4); wpobj(&o, &on_cube);     /* squares on pixels of 2 samples */
    rc |= save(dir, "points-lines-wire-on-cube", &o);

    /* 15: a dense cloud (4096 points on a coarse grid: many share a
     * position or a sample box) beside a star, orthographic, squares of
     * 3 samples, lines 2 wide; then every point drawn, in perspective */
    PObj cloud_p = { PF_CLOUD | PF_PLACED, { 0.5, 0, 0 }, 33, 0, 3, bridge_v, { 255, 11 }, 0, NULL, 2, cube_lines,
                     { 10, 20, 0 }, { 0 }, 0.8 };
    h = (Head){ 64, 40, SC_THREADS2, 0, 50, 25, 15, 0, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &star);
    wstyle(&o, 3, 2, 0, 0); w8(&o, 1); wpobj(&o, &cloud_p);
    rc |= save(dir, "cloud-dense-ortho", &o);
    h.flags = SC_PERSP | 1 << 5;
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &star);
    wstyle(&o, 1, 1, 1, 1); w8(&o, 1); wpobj(&o, &cloud_p);
    rc |= save(dir, "cloud-all-points-persp", &o);

    /* 16: the eye inside the corridor, lines running past it (the near
     * plane cuts them) and the corridor's wireframe, 3 samples wide */
    static const int past_v[4][3] = { { 0, 0, -120 }, { 0, 0, 120 }, { 10, -10, -100 }, { -10, 10, 110 } };
    static const uint8_t past_l[] = { 2, 0, 1, 3, 2, 3, 0 };
    PObj past = { 0, { 0, 0, 0 }, 34, 0, 4, past_v, { 0, 0 }, 4, corner_pts, 2, past_l, { 0 }, { 0 }, 1 };
    h = (Head){ 128, 96, SC_PERSP | SC_THREADS2, 0, 90, 0, 0, 0, { 0 }, 6, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &corridor);
    wstyle(&o, 4, 3, 1, 0); w8(&o, 1); wpobj(&o, &past);
    rc |= save(dir, "lines-near-plane-wire", &o);

    /* 17: large meshes (tens of thousands of triangles) under each
     * --order, with the cube or the star beside them; the hidden
     * surfaces at every SIMD level unless a level is named */
    static const double origin[3] = { 0, 0, 0 }, aside[3] = { 0.5, -0.3, 0.2 };
    /* a 144 x 144 terrain of hills seen from above in perspective, front to back */
    h = (Head){ 256, 160, SC_PERSP | SC_THREADS2, 0, 60, 20, -50, 0, { 0 }, 2.5, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_FRONT, 0, 0, 0, 15 + 16 * 8, 5, origin, 32);
    rc |= save(dir, "big-terrain-front", &o);
    /* a bumpy sphere of 51,076 triangles, culled, back to front, terminal cells */
    h = (Head){ 160, 80, SC_PERSP | SC_CULL | SC_THREADS2 | 1 << 5, 0, 50, 30, 20, 0, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_BACK, 0, 0, 1, 15 + 16, 9, aside, 32);
    rc |= save(dir, "big-sphere-cull-back", &o);
    /* 32,768 small crossing triangles shuffled, the hidden surfaces at AVX2 */
    h = (Head){ 256, 256, SC_THREADS2, 0, 50, 35, 25, 10, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &pierce);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_SHUFFLE, 3, 1234, 2, 31 + 32 * 3, 77, origin, 32);
    rc |= save(dir, "big-soup-shuffle-avx2", &o);
    /* 16 wavy layers one behind another, orthographic, one thread, the file's order */
    h = (Head){ 180, 100, 0, 0, 50, 10, 80, 0, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_FILE, 0, 0, 3, 15 + 16 * 4, 3, aside, 33);
    rc |= save(dir, "big-layers-file", &o);
    /* the same layers seen edge on in perspective, shuffled, the wireframe over them */
    h = (Head){ 120, 120, SC_PERSP, 0, 70, 5, 5, 0, { 0 }, 2, 0, 0.1, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    wstyle(&o, 1, 1, 1, 0); w8(&o, 0); wrun(&o, ORDER_SHUFFLE, 0, 7, 3, 7 + 16 * 8, 4, aside, 33);
    rc |= save(dir, "big-layers-edge-wire-shuffle", &o);
    /* a grid of 2 x 2 x 2 spheres (6,000 triangles each), front to back, SSE2 */
    h = (Head){ 200, 150, SC_PERSP | SC_GRID | SC_THREADS2, 0, 45, 5, 5, 0, { 0 }, 1.5, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_FRONT, 2, 0, 1, 7, 1, origin, 32);
    rc |= save(dir, "big-grid-spheres-front-sse2", &o);
    /* the small generated scene of 12 under each reordering, no large mesh */
    static const char *const gen_names[3] = { "generated-front", "generated-back", "generated-shuffle" };
    for (int ord = ORDER_FRONT; ord <= ORDER_SHUFFLE; ord++) {
        h = (Head){ 180, 120, SC_PERSP | SC_THREADS2, 0, 60, 20, 25, 0, { 0 }, 1.2, 0, 0, 0 };
        o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 2);
        wobj(&o, &sphere); wobj(&o, &field); wobj(&o, &cloud);
        wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ord, 0, 99, -1, 0, 0, origin, 0);
        rc |= save(dir, gen_names[ord - ORDER_FRONT], &o);
    }
    /* 18: section planes: the cube's corner cut away by three axis
     * planes through its middle; the star and the piercing triangles by
     * a slanted plane, perspective, culled; the bumpy sphere cut by two,
     * shuffled on two threads; the generated scene by a plane seen from
     * its removed side */
    static const uint8_t corner3[3][7] = { { 0, 128, 128, 128 }, { 2, 128, 128, 128 }, { 4, 128, 128, 128 } };
    static const uint8_t slant[1][7] = { { 1, 120, 140, 100, 5, (uint8_t)-3, 7 } };
    static const uint8_t two[2][7] = { { 8 | 2, 0, 100, 0 }, { 1, 150, 128, 128, 1, 1, 0 } };
    h = (Head){ 160, 120, 0, 0, 50, 35, 25, 0, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_FILE, 0, 0, -1, 0, 0, origin, 0); wplanes(&o, 3, corner3);
    rc |= save(dir, "section-cube-corner", &o);
    h = (Head){ 200, 150, SC_PERSP | SC_CULL | SC_THREADS2, 0, 60, 40, 30, 10, { 0 }, 1.3, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 1); wobj(&o, &star); wobj(&o, &pierce);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_FRONT, 0, 0, -1, 0, 0, origin, 0); wplanes(&o, 1, slant);
    rc |= save(dir, "section-star-pierce-slanted", &o);
    h = (Head){ 160, 80, SC_PERSP | SC_THREADS2 | 1 << 5, 0, 50, 30, 20, 0, { 0 }, 1, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 0); wobj(&o, &cube);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_SHUFFLE, 0, 5, 1, 15 + 16, 9, aside, 32); wplanes(&o, 2, two);
    rc |= save(dir, "section-sphere-two-shuffle", &o);
    h = (Head){ 180, 120, SC_PERSP | SC_THREADS2, 0, 60, 200, 25, 0, { 0 }, 1.2, 0, 0, 0 };
    o.n = 0; whead(&o, &h); w8(&o, 0); w8(&o, 2);
    wobj(&o, &sphere); wobj(&o, &field); wobj(&o, &cloud);
    wstyle(&o, 1, 1, 0, 0); w8(&o, 0); wrun(&o, ORDER_BACK, 0, 99, -1, 0, 0, origin, 0); wplanes(&o, 1, slant);
    rc |= save(dir, "section-generated-back", &o);
    return rc ? 1 : 0;
}
