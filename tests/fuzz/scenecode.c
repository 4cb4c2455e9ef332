/* scenecode.c: see scenecode.h. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenecode.h"
#include "testlib.h"

const float sc_aspects[7] = { 1, 2, 0.5f, 1.5f, 3, 0.75f, 2.25f };
const float sc_pan_scales[4] = { 0.1f, 1, 10, 1000 };

/* A cursor over the input: reads past the end give 0. */
typedef struct {
    const uint8_t *p, *e;
} Rd;

static unsigned rd_u8(Rd *r)
{
    return r->p < r->e ? *r->p++ : 0;
}

static unsigned rd_u16(Rd *r)
{
    unsigned lo = rd_u8(r);
    return lo | rd_u8(r) << 8;
}

static int rd_i16(Rd *r)
{
    return (int16_t)(uint16_t)rd_u16(r);
}

static float rd_angle(Rd *r)
{
    return deg2rad((float)rd_i16(r) * (180.0f / 32768.0f));
}

static double rd_coord(Rd *r, int raw)
{
    if (raw) {
        uint32_t bits = rd_u16(r);
        bits |= (uint32_t)rd_u16(r) << 16;
        float f;
        memcpy(&f, &bits, sizeof f);
        return isfinite(f) ? f : 0;
    }
    int m = rd_i16(r);
    return m / 32768.0 * ldexp(1, (int)(rd_u8(r) % 64) - 24);
}

/* The vertex base + d * unit, as a float. */
static int add_vertex(Mesh *m, const double base[3], double unit, const int d[3])
{
    float p[3];
    for (int i = 0; i < 3; i++) {
        p[i] = (float)(base[i] + d[i] * unit);
        if (!isfinite(p[i]))    /* files cannot give an infinite vertex either */
            p[i] = (float)base[i];
    }
    return tl_mesh_vertex(m, p[0], p[1], p[2]);
}

/* A face of corners v0 + idx[], within the budget. */
static int add_face(Mesh *m, uint32_t v0, const uint32_t *idx, uint32_t n, uint32_t *faces_left)
{
    uint32_t c[4];
    if (*faces_left == 0)
        return 0;
    (*faces_left)--;
    for (uint32_t k = 0; k < n; k++)
        c[k] = v0 + idx[k];
    return tl_mesh_face(m, c, n);
}

static uint32_t xorshift(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

/* SO_GEN: many faces from a few bytes (see scenecode.h). */
static int generate_object(Rd *r, Mesh *m, const double base[3], double unit, uint32_t *faces_left)
{
    unsigned kind = rd_u8(r) % 3, n = rd_u8(r), seed = rd_u16(r);
    uint32_t st = seed * 2654435761u + kind + 1, v0 = m->nverts;
    if (kind == 0) {
        int g = 2 + (int)(n % 15), amp = (int)(n >> 4) * 8;
        for (int j = 0; j <= g; j++)
            for (int i = 0; i <= g; i++) {
                int d[3] = { i * 254 / g - 127, j * 254 / g - 127,
                             amp ? (int)(xorshift(&st) % (2u * amp + 1)) - amp : 0 };
                if (add_vertex(m, base, unit, d))
                    return -1;
            }
        for (int j = 0; j < g; j++)
            for (int i = 0; i < g; i++) {
                uint32_t a = (uint32_t)(j * (g + 1) + i), q[4] = { a, a + 1, a + g + 2, a + g + 1 };
                int rc;
                if (xorshift(&st) % 4 == 0) {
                    uint32_t t[3] = { q[0], q[2], q[3] };
                    rc = add_face(m, v0, q, 3, faces_left) || add_face(m, v0, t, 3, faces_left);
                } else {
                    rc = add_face(m, v0, q, 4, faces_left);
                }
                if (rc)
                    return -1;
            }
    } else if (kind == 1) {
        int size = 1 << (seed % 8);
        for (unsigned t = 0; t < 8 + n; t++) {
            int c[3], d[3];
            for (int i = 0; i < 3; i++)
                c[i] = (int)(xorshift(&st) % 255) - 127;
            uint32_t idx[3];
            for (int k = 0; k < 3; k++) {
                for (int i = 0; i < 3; i++)
                    d[i] = c[i] + (int)(xorshift(&st) % (2u * size + 1)) - size;
                idx[k] = m->nverts - v0;
                if (add_vertex(m, base, unit, d))
                    return -1;
            }
            if (add_face(m, v0, idx, 3, faces_left))
                return -1;
        }
    } else {
        int segs = 3 + (int)(n % 22), rings = 2 + (int)(n / 22 % 10);
        int pole[2][3] = { { 0, 0, 127 }, { 0, 0, -127 } };
        if (add_vertex(m, base, unit, pole[0]) || add_vertex(m, base, unit, pole[1]))
            return -1;
        for (int j = 1; j <= rings; j++)
            for (int i = 0; i < segs; i++) {
                double th = 3.141592653589793 * j / (rings + 1), ph = 6.283185307179586 * i / segs;
                int d[3] = { (int)lround(127 * sin(th) * cos(ph)), (int)lround(127 * sin(th) * sin(ph)),
                             (int)lround(127 * cos(th)) };
                if (add_vertex(m, base, unit, d))
                    return -1;
            }
        for (int i = 0; i < segs; i++) {
            uint32_t i1 = (uint32_t)((i + 1) % segs), i0 = (uint32_t)i;
            uint32_t top[3] = { 0, 2 + i0, 2 + i1 };
            uint32_t last = 2 + (uint32_t)((rings - 1) * segs);
            uint32_t bottom[3] = { 1, last + i1, last + i0 };
            if (add_face(m, v0, top, 3, faces_left) || add_face(m, v0, bottom, 3, faces_left))
                return -1;
            for (int j = 0; j + 1 < rings; j++) {
                uint32_t a = 2 + (uint32_t)(j * segs), b = a + (uint32_t)segs;
                uint32_t q[4] = { a + i0, b + i0, b + i1, a + i1 };
                if (add_face(m, v0, q, 4, faces_left))
                    return -1;
            }
        }
    }
    return 0;
}

/* One object's vertices and faces into m. */
static int decode_object(Rd *r, Mesh *m, int oflags, uint32_t *faces_left)
{
    double base[3];
    for (int i = 0; i < 3; i++)
        base[i] = rd_coord(r, oflags & SO_RAW);
    double unit = ldexp(1, (int)(rd_u8(r) % 64) - 40);
    if ((oflags & SO_GEN) && generate_object(r, m, base, unit, faces_left))
        return -1;
    uint32_t v0 = m->nverts, nv = 3 + rd_u8(r) % 30;
    for (uint32_t k = 0; k < nv; k++) {
        int d[3];
        for (int i = 0; i < 3; i++)
            d[i] = oflags & SO_WIDE ? rd_i16(r) : (int8_t)rd_u8(r);
        if (add_vertex(m, base, unit, d))
            return -1;
    }
    uint32_t nf = 1 + rd_u8(r) % 16;
    for (uint32_t f = 0; f < nf && *faces_left > 0; f++, (*faces_left)--) {
        unsigned code = rd_u8(r);
        uint32_t nc = code < 160 ? 3 : code < 224 ? 4 : 5 + code % 12, corner[16];
        for (uint32_t k = 0; k < nc; k++) {
            unsigned v = rd_u8(r);
            corner[k] = oflags & SO_SHARE ? v % m->nverts : v0 + v % nv;
        }
        if (tl_mesh_face(m, corner, nc))
            return -1;
    }
    if ((oflags & SO_BIG) && *faces_left > 0) {
        uint32_t n = 25 + rd_u16(r) % 4000, st = rd_u16(r) * 2654435761u + 3;
        uint32_t *c = malloc(n * sizeof *c);
        if (!c)
            return -1;
        for (uint32_t k = 0; k < n; k++)
            c[k] = v0 + xorshift(&st) % nv;
        int rc = tl_mesh_face(m, c, n);
        free(c);
        (*faces_left)--;
        if (rc)
            return -1;
    }
    return 0;
}

/* Placements, read in object order; applied after the scene is built. */
typedef struct {
    int   placed;
    float yaw, pitch, roll, scale;
    Vec3  move;
} Place;

/* A mesh of points and lines (see scenecode.h), after the others. */
static int decode_prim_mesh(Rd *r, Mesh *m, const Mesh *earlier, int nearlier, int pflags)
{
    double base[3];
    for (int i = 0; i < 3; i++)
        base[i] = rd_coord(r, pflags & PF_RAW);
    double unit = ldexp(1, (int)(rd_u8(r) % 64) - 40);
    if ((pflags & PF_COPY) && nearlier > 0) {
        const Mesh *src = &earlier[rd_u8(r) % (unsigned)nearlier];
        for (uint32_t v = 0; v < src->nverts && v < 4096; v++)
            if (tl_mesh_vertex(m, src->pos[3 * v], src->pos[3 * v + 1], src->pos[3 * v + 2]))
                return -1;
    } else {
        uint32_t nv = 1 + rd_u8(r) % 30;
        for (uint32_t k = 0; k < nv; k++) {
            int d[3];
            for (int i = 0; i < 3; i++)
                d[i] = pflags & PF_WIDE ? rd_i16(r) : (int8_t)rd_u8(r);
            if (add_vertex(m, base, unit, d))
                return -1;
        }
    }
    if (pflags & PF_CLOUD) {
        unsigned n = rd_u8(r), seed = rd_u16(r);
        uint32_t st = seed * 2654435761u + 7;
        for (unsigned k = 0; k < 16 * (n + 1); k++) {
            /* a coarse grid: many points share a position or a box */
            int d[3];
            for (int i = 0; i < 3; i++)
                d[i] = ((int)(xorshift(&st) % 33) - 16) * 8;
            if (add_vertex(m, base, unit, d))
                return -1;
        }
    } else {
        unsigned np = rd_u8(r) % 64;
        for (unsigned k = 0; k < np; k++)
            if (tl_mesh_point(m, rd_u8(r) % m->nverts))
                return -1;
    }
    unsigned nl = rd_u8(r) % 8;
    for (unsigned l = 0; l < nl; l++) {
        uint32_t nc = 2 + rd_u8(r) % 6, c[8];
        for (uint32_t k = 0; k < nc; k++)
            c[k] = rd_u8(r) % m->nverts;
        if (tl_mesh_line(m, c, nc))
            return -1;
    }
    return 0;
}

int sc_decode(const uint8_t *data, size_t size, Scene *s, Viewport *vp, int *threads)
{
    PrimStyle st;
    return sc_decode_style(data, size, s, vp, threads, &st);
}

int sc_decode_style(const uint8_t *data, size_t size, Scene *s, Viewport *vp, int *threads, PrimStyle *style)
{
    ScRun run;
    return sc_decode_run(data, size, s, vp, threads, style, &run);
}

/* The large mesh (scenecode.h) into m, of at most SC_MAX_BIG_FACES /
 * part faces; 1 when the input asks for none. */
static int decode_big(Rd *r, Mesh *m, int part)
{
    if (rd_u8(r) == 0)
        return 1;
    unsigned kind = rd_u8(r), n = rd_u8(r), seed = rd_u16(r);
    double c[3];
    for (int i = 0; i < 3; i++)
        c[i] = rd_coord(r, 0);
    double size = ldexp(1, (int)(rd_u8(r) % 64) - 32);
    if (tl_mesh_init(m, "big") || tl_mesh_object(m, "big") ||
        sc_big_mesh(m, kind, n, seed, c, size, SC_MAX_BIG_FACES / (uint32_t)part))
        return -1;
    return 0;
}

/* The section planes' bytes, placed across the first mesh's box. */
static void decode_planes(const Scene *s, uint8_t pl[][7], ScRun *run)
{
    const Mesh *m = &s->meshes[0];
    double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
    for (uint32_t v = 0; v < m->nverts; v++)
        for (int k = 0; k < 3; k++) {
            double c = m->pos[3 * (size_t)v + k];
            lo[k] = v == 0 || c < lo[k] ? c : lo[k];
            hi[k] = v == 0 || c > hi[k] ? c : hi[k];
        }
    for (int i = 0; i < run->nplanes; i++) {
        const uint8_t *b = pl[i];
        double q[3];
        for (int k = 0; k < 3; k++)     /* in the mesh's units: file units past 2^pos_exp */
            q[k] = ldexp(lo[k] + (hi[k] - lo[k]) * b[1 + k] / 255.0, s->pos_exp);
        if (!(b[0] & 1)) {
            int axis = (b[0] >> 1) % 3;
            run->plane[i] = section_axis_plane(axis, b[0] >> 3 & 1, q[axis]);
            continue;
        }
        SectionPlane p = { { q[0], q[1], q[2] }, { (int8_t)b[4], (int8_t)b[5], (int8_t)b[6] }, -1 };
        if (p.n[0] == 0 && p.n[1] == 0 && p.n[2] == 0)
            p.n[2] = 1;
        run->plane[i] = p;
    }
}

int sc_decode_run(const uint8_t *data, size_t size, Scene *s, Viewport *vp, int *threads, PrimStyle *style,
                  ScRun *run)
{
    Rd r = { data, data + size };
    memset(s, 0, sizeof *s);
    vp->w = 1 + (int)rd_u8(&r);
    vp->h = 1 + (int)rd_u8(&r);
    unsigned flags = rd_u8(&r);
    unsigned ac = flags >> 5;
    vp->pixel_aspect = ac < 7 ? sc_aspects[ac] : 0.25f + (float)rd_u8(&r) / 32;
    vp->cull = (flags & SC_CULL) != 0;
    *threads = flags & SC_THREADS2 ? 2 : 1;
    TlView v;
    v.persp = (flags & SC_PERSP) != 0;
    v.fov_deg = 2 + (float)rd_u8(&r) * 176.0f / 255.0f;
    v.yaw = rd_angle(&r);
    v.pitch = rd_angle(&r);
    v.roll = rd_angle(&r);
    if (flags & SC_REFIT) {
        v.fit_yaw = rd_angle(&r);
        v.fit_pitch = rd_angle(&r);
        v.fit_roll = rd_angle(&r);
    } else {
        v.fit_yaw = v.yaw;
        v.fit_pitch = v.pitch;
        v.fit_roll = v.roll;
    }
    v.zoom = (float)pow(10, -3 + 6 * rd_u16(&r) / 65535.0);
    float pan = sc_pan_scales[rd_u8(&r) & 3];
    v.pan_x = (float)rd_i16(&r) / 32768.0f * pan;
    v.pan_y = (float)rd_i16(&r) / 32768.0f * pan;

    int nmeshes = 1 + (int)(rd_u8(&r) % SC_MAX_MESHES);
    Mesh *meshes = calloc((size_t)nmeshes + SC_MAX_PRIM_MESHES + 1, sizeof *meshes);
    Place place[SC_MAX_OBJS + SC_MAX_PRIM_MESHES + 1];
    int nplace = 0;
    uint32_t faces_left = SC_MAX_FACES;
    if (!meshes)
        return -1;
    int built = 0;
    for (int mi = 0; mi < nmeshes; mi++) {
        Mesh *m = &meshes[mi];
        char name[16];
        snprintf(name, sizeof name, "mesh%d", mi);
        if (tl_mesh_init(m, name))
            goto fail;
        int nobj = 1 + (int)(rd_u8(&r) % SC_MAX_MESH_OBJS);
        for (int k = 0; k < nobj && nplace < SC_MAX_OBJS; k++) {
            snprintf(name, sizeof name, "o%d", k);
            int oflags = (int)rd_u8(&r);
            if (tl_mesh_object(m, name) || decode_object(&r, m, oflags, &faces_left))
                goto fail;
            Place *pl = &place[nplace++];
            pl->placed = oflags & SO_PLACED;
            if (pl->placed) {
                pl->yaw = rd_angle(&r);
                pl->pitch = rd_angle(&r);
                pl->roll = rd_angle(&r);
                double mx = rd_coord(&r, oflags & SO_RAW), my = rd_coord(&r, oflags & SO_RAW),
                       mz = rd_coord(&r, oflags & SO_RAW);
                pl->move = v3((float)mx, (float)my, (float)mz);
                pl->scale = (float)pow(10, -3 + 6 * rd_u8(&r) / 255.0);
            }
        }
        /* every object got at least one face unless the face budget ran
         * out; a mesh without faces is left out, as a file that fails to
         * load would be */
        if (tl_mesh_finish(m)) {
            mesh_free(m);
            memset(m, 0, sizeof *m);
        }
    }
    /* points and lines: their style, then meshes of their own */
    unsigned sb = rd_u8(&r);
    style->point_size = 1 + (int)(sb & 7);
    style->line_width = 1 + (int)(sb >> 3 & 7);
    style->wire = sb >> 6 & 1;
    style->all_prims = sb >> 7 & 1;
    unsigned pb = rd_u8(&r);
    int nprim = (int)(pb % (SC_MAX_PRIM_MESHES + 1));
    style->pixel = 1 + (int)(pb >> 4 & 3) % 3;
    for (int k = 0; k < nprim; k++) {
        Mesh *m = &meshes[nmeshes++];     /* counted first: fail frees it */
        char name[24];
        snprintf(name, sizeof name, "prims%d", k);
        int pflags = (int)rd_u8(&r);
        if (tl_mesh_init(m, name) || decode_prim_mesh(&r, m, meshes, nmeshes - 1, pflags))
            goto fail;
        Place *pl = &place[nplace++];
        pl->placed = pflags & PF_PLACED;
        if (pl->placed) {
            pl->yaw = rd_angle(&r);
            pl->pitch = rd_angle(&r);
            pl->roll = rd_angle(&r);
            double mx = rd_coord(&r, pflags & PF_RAW), my = rd_coord(&r, pflags & PF_RAW),
                   mz = rd_coord(&r, pflags & PF_RAW);
            pl->move = v3((float)mx, (float)my, (float)mz);
            pl->scale = (float)pow(10, -3 + 6 * rd_u8(&r) / 255.0);
        }
        if (tl_mesh_finish(m)) {
            mesh_free(m);
            memset(m, 0, sizeof *m);
            pl->placed = 0;
        }
    }
    /* how the frame is run, then the large mesh */
    unsigned rb = rd_u8(&r);
    run->order = (int)(rb & 3);
    run->hsr_simd = (int)(rb >> 2 & 3);
    run->seed = rd_u16(&r);
    Mesh *big = &meshes[nmeshes++];
    int rc = decode_big(&r, big, (flags & SC_GRID ? 10 : 1) * (style->wire ? 10 : 1));
    if (rc < 0)
        goto fail;
    place[nplace++].placed = 0;
    uint8_t pl[SECTION_MAX][7];
    run->nplanes = (int)(rd_u8(&r) % 5);
    for (int i = 0; i < run->nplanes; i++)
        for (int k = 0; k < 7; k++)
            pl[i][k] = rd_u8(&r);
    if (rc > 0 || tl_mesh_finish(big)) {
        mesh_free(big);
        memset(big, 0, sizeof *big);
    }
    /* drop the empty meshes, keep the order (and the placements' order:
     * they go to the objects that remain) */
    int kept = 0;
    for (int mi = 0; mi < nmeshes; mi++)
        if (meshes[mi].nfaces || meshes[mi].npoints || meshes[mi].nlines)
            meshes[kept++] = meshes[mi];
    char err[256];
    if (kept == 0 || scene_build(s, meshes, kept, err, sizeof err))
        goto fail;
    built = 1;
    if ((flags & SC_GRID) && scene_make_grid(s, 2, err, sizeof err))
        goto fail;
    /* placements go to the loaded objects in order (as --move/--turn/
     * --scale number them); grid copies keep their home offsets */
    for (int i = 0; i < nplace && i < (int)s->nbase_objs; i++) {
        if (!place[i].placed)
            continue;
        Object *o = &s->objs[i];
        o->yaw = place[i].yaw;
        o->pitch = place[i].pitch;
        o->roll = place[i].roll;
        o->offset = v3_add(o->home, place[i].move);
        o->scale = place[i].scale;
    }
    tl_set_view(s, &v);
    decode_planes(s, pl, run);
    return 0;

fail:
    if (built) {
        scene_free(s);
    } else {
        for (int mi = 0; mi < nmeshes; mi++)
            mesh_free(&meshes[mi]);
        free(meshes);
        memset(s, 0, sizeof *s);
    }
    return -1;
}
