/* step.c: the CAD exchange formats, STEP (ISO 10303-21), IGES and
 * OpenCASCADE's BREP, read by OpenCASCADE through its shim
 * (src/mesh/occt/occtshim.cpp, libzview-occt.so), which this file opens
 * at run time as assimp.c opens assimp: zview builds, and runs its other
 * formats, where OCCT is missing, and says so in one line for these.
 *
 * The shim is looked for where ZV_OCCT_SHIM names it (only there, when
 * set), beside the running binary, and in the install's library folder
 * (ZV_OCCT_LIBDIR, the Makefile's $(PREFIX)/lib/zview). It hands back
 * triangles tessellated at a deflection relative to the model's size
 * (--tessellation; ZV_OCCT_DEFLECTION of the bounding box's diagonal by
 * default), grouped by the assembly's parts, with the parts' names, the
 * colours the file gives and its length unit. Each B-rep face has its
 * own vertices there; equal positions (exact bits) are merged here, as
 * STL's are, so that faces meeting along an edge share it and a closed
 * solid is watertight for --check.
 *
 * Files only: OCCT reads a path (a stream from standard input is refused
 * as such by the reading layer). */
#define _DEFAULT_SOURCE

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mesh.h"
#include "mesh_internal.h"
#include "occt/occtshim.h"

#ifndef ZV_OCCT_LIBDIR
#define ZV_OCCT_LIBDIR "/usr/local/lib/zview"
#endif
#define SHIM_NAME "libzview-occt.so"

typedef struct {
    ZvOcctVersionFn version;
    ZvOcctReadFn    read;
    ZvOcctFreeFn    free;
    char            why[200];   /* why it could not be opened */
} OcctApi;

/* Set once (pthread_once), read-only after: the shim's handle, as
 * assimp.c keeps the library's. */
static OcctApi occt_table;
static int occt_loaded;
static pthread_once_t occt_once = PTHREAD_ONCE_INIT;

static void *open_shim(const char *path, char *why, size_t n)
{
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *e = dlerror();
        snprintf(why, n, "%.190s", e ? e : path);
    }
    return h;
}

/* The folder of the running binary, with a '/' after it ("" unknown). */
static void exe_dir(char *buf, size_t n)
{
    ssize_t k = readlink("/proc/self/exe", buf, n - 1);
    buf[k > 0 ? k : 0] = '\0';
    char *slash = strrchr(buf, '/');
    if (slash)
        slash[1] = '\0';
    else
        buf[0] = '\0';
}

static void occt_open(void)
{
    char path[PATH_MAX + 32], dir[PATH_MAX];
    const char *forced = getenv("ZV_OCCT_SHIM");
    void *h;
    if (forced && *forced) {
        h = open_shim(forced, occt_table.why, sizeof occt_table.why);
    } else {
        exe_dir(dir, sizeof dir);
        snprintf(path, sizeof path, "%s" SHIM_NAME, dir);
        h = dir[0] ? open_shim(path, occt_table.why, sizeof occt_table.why) : NULL;
        if (!h)
            h = open_shim(ZV_OCCT_LIBDIR "/" SHIM_NAME, occt_table.why, sizeof occt_table.why);
        if (!h)
            snprintf(occt_table.why, sizeof occt_table.why, "no %s beside zview or in " ZV_OCCT_LIBDIR
                     " (zview built without OCCT's headers, or not installed with it)", SHIM_NAME);
    }
    if (!h)
        return;
    ZvOcctAbiFn abi = (ZvOcctAbiFn)dlsym(h, "zv_occt_abi");
    ZvOcctInitFn init = (ZvOcctInitFn)dlsym(h, "zv_occt_init");
    occt_table.version = (ZvOcctVersionFn)dlsym(h, "zv_occt_version");
    occt_table.read = (ZvOcctReadFn)dlsym(h, "zv_occt_read");
    occt_table.free = (ZvOcctFreeFn)dlsym(h, "zv_occt_free");
    if (!abi || !init || !occt_table.version || !occt_table.read || !occt_table.free || abi() != ZV_OCCT_ABI) {
        snprintf(occt_table.why, sizeof occt_table.why, "%s is not the shim this zview was built with", SHIM_NAME);
        dlclose(h);
        return;
    }
    if (init() != 0) {
        snprintf(occt_table.why, sizeof occt_table.why, "OpenCASCADE could not be started");
        dlclose(h);
        return;
    }
    occt_loaded = 1;
}

/* The shim, or NULL when it cannot be opened. */
static const OcctApi *occt(void)
{
    pthread_once(&occt_once, occt_open);
    return occt_loaded ? &occt_table : NULL;
}

int mesh_occt_available(void)
{
    return occt() != NULL;
}

const char *mesh_occt_version(char *buf, size_t n)
{
    snprintf(buf, n, "%s", occt() ? occt()->version() : "OCCT not found");
    return buf;
}

/* ==== From the shim's triangles to a Mesh ==== */

static int to_mesh(MeshCtx *c, const ZvOcctMesh *o, const char *format)
{
    MeshBuild b;
    VertMerge vm = { 0 };
    int32_t *mat = NULL;
    uint32_t *remap = NULL;
    int r = -1;
    if (mb_start(&b, c->m, &c->err, c->err.name))
        return -1;
    snprintf(c->m->info.format, sizeof c->m->info.format, "%s (OCCT)", format);
    snprintf(c->m->info.unit, sizeof c->m->info.unit, "%s", o->unit);
    mat = malloc((o->ncolours ? o->ncolours : 1) * sizeof *mat);
    remap = malloc((o->nverts ? o->nverts : 1) * sizeof *remap);
    if (!mat || !remap || vm_init(&vm, o->nverts)) {
        me_oom(&c->err);
        goto out;
    }
    if (mb_afford(&b, o->ntris, mb_estimate(o->nverts, 0, o->ntris, 3 * (uint64_t)o->ntris, 0),
                  "the tessellation's triangles") ||
        mb_reserve_ex(&b, o->nverts, o->ntris, 3 * (size_t)o->ntris, 0))
        goto out;
    for (uint32_t k = 0; k < o->ncolours; k++) {
        const float *q = o->colour + 4 * (size_t)k;
        uint8_t v[4];
        for (int i = 0; i < 4; i++)
            v[i] = (uint8_t)(q[i] <= 0 ? 0 : q[i] >= 1 ? 255 : q[i] * 255 + 0.5f);
        if ((mat[k] = mb_colour(&b, v[0], v[1], v[2], v[3])) < 0)
            goto out;
    }
    for (uint32_t v = 0; v < o->nverts; v++) {
        uint32_t bits[3];
        memcpy(bits, o->pos + 3 * (size_t)v, sizeof bits);
        if (bits_nonfinite(bits[0]) || bits_nonfinite(bits[1]) || bits_nonfinite(bits[2])) {
            me_fail(&c->err, "a NaN or infinite coordinate in OCCT's tessellation");
            goto out;
        }
        if (vm_add(&vm, &b, bits, vm_hash(bits[0], bits[1], bits[2]), &remap[v]))
            goto out;
    }
    uint32_t obj = UINT32_MAX;
    for (uint32_t t = 0; t < o->ntris; t++) {
        if (o->tri_obj[t] != obj) {
            obj = o->tri_obj[t];
            const char *name = obj < o->nobjs && o->obj_name[obj] ? o->obj_name[obj] : "";
            if (mb_object(&b, name, strlen(name)))
                goto out;
        }
        size_t first = b.ncorner;
        for (int i = 0; i < 3; i++) {
            uint32_t v = o->tri[3 * (size_t)t + i];
            if (v >= o->nverts) {
                me_fail(&c->err, "OCCT's triangle %u names vertex %u of %u", t + 1, v + 1, o->nverts);
                goto out;
            }
            if (mb_corner(&b, remap[v]))
                goto out;
        }
        int32_t col = o->tri_colour[t];
        if (mb_face_end(&b, first, col >= 0 && (uint32_t)col < o->ncolours ? mat[col] : -1))
            goto out;
    }
    r = mb_finish(&b, 0);
out:
    if (r)
        mb_abort(&b);
    vm_free(&vm);
    free(mat);
    free(remap);
    return r;
}

static int read_kind(MeshCtx *c, const char *path, int kind, const char *format)
{
    static const char *const upper[] = { "STEP", "IGES", "BREP" };
    const OcctApi *api = occt();
    if (!api)
        return me_fail(&c->err, "%s needs OpenCASCADE: %s", upper[kind], occt_table.why);
    ZvOcctMesh o;
    char why[512] = "";
    if (api->read(path, kind, c->tessellation, &o, why, sizeof why))
        return me_fail(&c->err, "%s", why[0] ? why : "OCCT could not read it");
    int r = to_mesh(c, &o, format);
    api->free(&o);
    if (r == 0) {
        /* none of the three says; CAD programs build z-up */
        c->m->info.up = UP_Z;
        c->m->info.front = -1;
        snprintf(c->m->info.up_why, sizeof c->m->info.up_why, "%s: the CAD convention, z up", format);
    }
    return r;
}

static int step_path(MeshCtx *c, const char *path) { return read_kind(c, path, ZV_OCCT_STEP, "step"); }
static int iges_path(MeshCtx *c, const char *path) { return read_kind(c, path, ZV_OCCT_IGES, "iges"); }
static int brep_path(MeshCtx *c, const char *path) { return read_kind(c, path, ZV_OCCT_BREP, "brep"); }

/* ==== Telling them by content ==== */

static int step_probe(const char *h, size_t n, uint64_t size)
{
    (void)size;
    size_t i = mesh_bom_len(h, n);
    while (i < n && mesh_is_ws(h[i]))
        i++;
    return n - i >= 13 && memcmp(h + i, "ISO-10303-21;", 13) == 0 ? PROBE_SURE : PROBE_NO;
}

/* IGES: 80-column records, the first a Start record ('S' in column 73,
 * its sequence number 1 in 74 to 80). */
static int iges_probe(const char *h, size_t n, uint64_t size)
{
    (void)size;
    if (n < 81 || h[72] != 'S')
        return PROBE_NO;
    for (int i = 73; i < 79; i++)
        if (h[i] != ' ' && h[i] != '0')
            return PROBE_NO;
    return h[79] == '1' && (h[80] == '\n' || h[80] == '\r') ? PROBE_SURE : PROBE_NO;
}

static int brep_probe(const char *h, size_t n, uint64_t size)
{
    (void)size;
    static const char a[] = "DBRep_DrawableShape", b[] = "CASCADE Topology V";
    size_t i = 0;
    while (i < n && mesh_is_ws(h[i]))
        i++;
    if (n - i >= sizeof a - 1 && memcmp(h + i, a, sizeof a - 1) == 0)
        return PROBE_SURE;
    return n - i >= sizeof b - 1 && memcmp(h + i, b, sizeof b - 1) == 0 ? PROBE_SURE : PROBE_NO;
}

const MeshLoader mesh_loader_step = {
    .name = "step",
    .exts = "step stp p21",
    .what = "STEP (ISO 10303-21) through OpenCASCADE: parts, names, colours, unit",
    .probe = step_probe,
    .parse_path = step_path,
    .text = 1,
    .library = 1,
};

const MeshLoader mesh_loader_iges = {
    .name = "iges",
    .exts = "iges igs",
    .what = "IGES through OpenCASCADE: names, colours, unit",
    .probe = iges_probe,
    .parse_path = iges_path,
    .text = 1,
    .library = 1,
};

const MeshLoader mesh_loader_brep = {
    .name = "brep",
    .exts = "brep brp",
    .what = "OpenCASCADE BREP through OpenCASCADE: one shape",
    .probe = brep_probe,
    .parse_path = brep_path,
    .text = 1,
    .library = 1,
};
