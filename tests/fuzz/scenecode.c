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

/* One object's vertices and faces into m. */
static int decode_object(Rd *r, Mesh *m, int oflags, uint32_t *faces_left)
{
    double base[3];
    for (int i = 0; i < 3; i++)
        base[i] = rd_coord(r, oflags & SO_RAW);
    double unit = ldexp(1, (int)(rd_u8(r) % 64) - 40);
    uint32_t v0 = m->nverts, nv = 3 + rd_u8(r) % 30;
    for (uint32_t k = 0; k < nv; k++) {
        float p[3];
        for (int i = 0; i < 3; i++) {
            int d = oflags & SO_WIDE ? rd_i16(r) : (int8_t)rd_u8(r);
            p[i] = (float)(base[i] + d * unit);
            if (!isfinite(p[i]))    /* files cannot give an infinite vertex either */
                p[i] = (float)base[i];
        }
        if (tl_mesh_vertex(m, p[0], p[1], p[2]))
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
    return 0;
}

/* Placements, read in object order; applied after the scene is built. */
typedef struct {
    int   placed;
    float yaw, pitch, roll, scale;
    Vec3  move;
} Place;

int sc_decode(const uint8_t *data, size_t size, Scene *s, Viewport *vp, int *threads)
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
    Mesh *meshes = calloc((size_t)nmeshes, sizeof *meshes);
    Place place[SC_MAX_OBJS];
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
    /* drop the empty meshes, keep the order */
    int kept = 0;
    for (int mi = 0; mi < nmeshes; mi++)
        if (meshes[mi].nfaces)
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
