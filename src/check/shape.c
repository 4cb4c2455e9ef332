/* shape.c: the winding, the parts and the measures of one object.
 *
 * Winding: two faces on a manifold edge agree when they run it in
 * opposite directions. A union-find with parity over the manifold edges
 * (each face's parity relative to its root: flip or keep) gives each
 * face of a patch (faces joined by manifold edges) a parity so that all
 * agree; a patch where a face would need both is non-orientable (a
 * Moebius strip), and no flip helps. Elsewhere the
 * fewest flips are the smaller of the patch's two parity classes (on a
 * tie, the class whose flip leaves the volume positive). Non-manifold
 * edges bound the patches: a fin's three faces have no winding to agree
 * on. The parts are the patches joined across non-manifold edges, both
 * numbered in face order; a degenerate face (out of the pairing, a
 * patch alone) is in no part.
 *
 * Area, volume and centre of mass, in face order: each face is a fan of
 * triangles from its first corner. The volume is the sum of the signed
 * volumes of the tetrahedra each triangle makes with a reference point
 * (the divergence theorem), taken about the bounding box's centre so
 * that a model far from the origin loses no digits, with the flips made
 * first: a closed mesh whose sum is negative is inside out. The centre
 * of mass is the tetrahedra's centroids weighted by their signed
 * volumes (uniform density). Degenerate faces (flagged by topo.c) have
 * zero area: every corner on one line, decided exactly (exact.c), so
 * that a thin but real sliver is not one. */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_internal.h"
#include "exact.h"

/* ==== One face ==== */

int check_face_degenerate(const ObjCheck *o, uint32_t f)
{
    uint32_t s = oc_start(o, f), e = oc_start(o, f + 1);
    if (e - s < 3)
        return 1;
    uint32_t p = oc_pt(o, s), q = CHECK_NONE, qc = 0;
    for (uint32_t c = s + 1; c < e; c++) {
        uint32_t r = oc_pt(o, c);
        if (r == p || r == q)
            continue;
        if (q == CHECK_NONE) {
            q = r;
            qc = c;
            continue;
        }
        if (!exact_collinear_quick(oc_vpos(o, oc_vert(o, s)), oc_vpos(o, oc_vert(o, qc)), oc_vpos(o, oc_vert(o, c))))
            return 0;
    }
    return 1;
}

typedef struct {
    double area, vol, mom[3];   /* vol and mom about o->ref, as wound in the file */
} FaceMeasure;

/* Area, signed volume and first moment of face f's fan. */
static void face_measure(const ObjCheck *o, uint32_t f, FaceMeasure *fm)
{
    uint32_t s = oc_start(o, f), e = oc_start(o, f + 1);
    memset(fm, 0, sizeof *fm);
    double a[3], b[3], c[3];
    const float *pa = oc_vpos(o, oc_vert(o, s));
    for (int k = 0; k < 3; k++)
        a[k] = pa[k] - o->ref[k];
    for (uint32_t i = s + 1; i + 1 < e; i++) {
        const float *pb = oc_vpos(o, oc_vert(o, i)), *pc = oc_vpos(o, oc_vert(o, i + 1));
        for (int k = 0; k < 3; k++) {
            b[k] = pb[k] - o->ref[k];
            c[k] = pc[k] - o->ref[k];
        }
        double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
        double wx = c[0] - a[0], wy = c[1] - a[1], wz = c[2] - a[2];
        double nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
        fm->area += 0.5 * sqrt(nx * nx + ny * ny + nz * nz);
        /* the tetrahedron (ref, a, b, c): volume a . (b x c) / 6, centroid (a + b + c) / 4 */
        double v = (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                    a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
        fm->vol += v;
        for (int k = 0; k < 3; k++)
            fm->mom[k] += v * (a[k] + b[k] + c[k]) / 4.0;
    }
}

/* ==== The winding and the parts ==== */

/* A union-find over faces that also keeps, for each face, its parity
 * relative to its parent (bit 0 of bits[]): the parity of a face to its
 * root is the sum along the path. A root's bit 1 says its patch has a
 * conflict (a face that would need both parities). The union-find array
 * is o->part. */
typedef struct {
    uint32_t *up;
    uint8_t  *bits;
} ParityFind;

static uint32_t pfind(ParityFind *u, uint32_t f, int *parity)
{
    uint32_t r = f;
    int p = 0;
    while (u->up[r] != r) {
        /* parents point to earlier faces (punion links under the
         * smaller root): the walk ends, and patches_find labels each
         * root before the faces that name it */
        ZV_ASSERT(u->up[r] < r);
        p ^= u->bits[r] & 1;
        r = u->up[r];
    }
    /* every face on the path straight to the root, with its parity there */
    for (uint32_t x = f, q = (uint32_t)p; x != r && u->up[x] != r;) {
        uint32_t next = u->up[x], px = u->bits[x] & 1u;
        u->up[x] = r;
        u->bits[x] = (uint8_t)((u->bits[x] & 2u) | q);
        q ^= px;
        x = next;
    }
    *parity = p;
    return r;
}

/* Faces f and g must have parities that differ by rel. */
static void punion(ParityFind *u, uint32_t f, uint32_t g, int rel)
{
    int pf, pg;
    uint32_t rf = pfind(u, f, &pf), rg = pfind(u, g, &pg);
    if (rf == rg) {
        if ((pf ^ pg) != rel)
            u->bits[rf] |= 2;
        return;
    }
    /* the smaller root stays one: patches are then numbered in face order */
    uint32_t lo = rf < rg ? rf : rg, hi = rf < rg ? rg : rf;
    u->up[hi] = lo;
    u->bits[lo] |= u->bits[hi] & 2;
    u->bits[hi] = (uint8_t)((u->bits[hi] & 2) | (pf ^ pg ^ rel));
}

typedef struct {
    uint32_t  npatches;
    uint32_t *count;            /* 2 per patch: its faces of parity 0 and 1 */
    uint8_t  *conflict;         /* per patch */
    uint8_t  *flip;             /* per patch: the parity whose faces flip */
} Patches;

/* Faces joined by manifold edges, with the parities that make them
 * agree; then o->part holds each face's patch and bits[] its parity. */
static int patches_find(ObjCheck *o, ParityFind *u, Patches *pt)
{
    for (uint32_t f = 0; f < o->nf; f++)
        u->up[f] = f;
    for (uint32_t c = 0; c < o->nc; c++) {
        uint32_t m = o->mate[c];
        /* the same direction (both leave one point) disagrees: then
         * exactly one of the two must flip */
        if (m < MATE_FIRST_SPECIAL && c < m)
            punion(u, oc_face(o, c), oc_face(o, m), oc_pt(o, c) == oc_pt(o, m));
    }
    uint32_t n = 0;
    for (uint32_t f = 0; f < o->nf; f++) {
        int p;
        n += pfind(u, f, &p) == f;
    }
    pt->npatches = n;
    pt->count = check_big((2 * (size_t)n + 1) * sizeof *pt->count, 1);
    pt->conflict = check_big((size_t)n + 1, 1);
    pt->flip = check_big((size_t)n + 1, 1);
    if (!pt->count || !pt->conflict || !pt->flip)
        return -1;
    /* every face now names its root, the root its smallest face: label
     * the roots in face order, each before the faces that name it */
    n = 0;
    for (uint32_t f = 0; f < o->nf; f++) {
        if (u->up[f] == f) {
            pt->conflict[n] = (u->bits[f] & 2) != 0;
            u->up[f] = n++;
        } else {
            ZV_ASSERT(u->up[f] < f);        /* its root, labelled already */
            u->up[f] = u->up[u->up[f]];
        }
        /* a patch label indexes count[], conflict[] and flip[] */
        ZV_ASSERT(u->up[f] < pt->npatches);
        pt->count[2 * u->up[f] + (u->bits[f] & 1)]++;
    }
    return 0;
}

/* Which class of each patch flips: the smaller; on a tie, the one whose
 * flip leaves the volume positive. */
static int patches_settle(ObjCheck *o, const ParityFind *u, Patches *pt)
{
    double *vol = NULL;
    for (uint32_t p = 0; p < pt->npatches; p++) {
        pt->flip[p] = pt->count[2 * p + 1] < pt->count[2 * p] ? 1 : 0;
        if (pt->count[2 * p] == pt->count[2 * p + 1] && !vol &&
            !(vol = calloc(2 * (size_t)pt->npatches, sizeof *vol)))
            return -1;
    }
    if (vol) {
        for (uint32_t f = 0; f < o->nf; f++) {
            uint32_t p = u->up[f];
            if (pt->count[2 * p] == pt->count[2 * p + 1]) {
                FaceMeasure fm;
                face_measure(o, f, &fm);
                vol[2 * p + (u->bits[f] & 1)] += fm.vol;
            }
        }
        for (uint32_t p = 0; p < pt->npatches; p++)
            if (pt->count[2 * p] == pt->count[2 * p + 1])
                pt->flip[p] = vol[2 * p] - vol[2 * p + 1] >= 0 ? 1 : 0;
        free(vol);
    }
    for (uint32_t p = 0; p < pt->npatches; p++) {
        if (pt->conflict[p])
            o->c->nonorientable++;
        else
            o->c->inconsistent_faces += pt->count[2 * p + pt->flip[p]];
    }
    for (uint32_t f = 0; f < o->nf; f++) {
        uint32_t p = u->up[f];
        if (pt->conflict[p])
            o->flags[f] |= CHECK_NONORIENT;
        else if ((u->bits[f] & 1) == pt->flip[p])
            o->flags[f] |= CHECK_FLIPPED;
    }
    return 0;
}

/* Patches joined across non-manifold edges are one part: o->part goes
 * from patch numbers to part numbers (both in order of first face, so
 * the smaller root of check_union labels each part first). */
static int join_patches(ObjCheck *o, uint32_t npatches)
{
    uint32_t *uf = check_identity(npatches);
    if (!uf)
        return -1;
    for (size_t g = 0; g + 1 < o->nm_ngroup; g++) {
        uint32_t first = o->part[oc_face(o, o->nm_half[o->nm_group[g]])];
        for (uint32_t k = o->nm_group[g] + 1; k < o->nm_group[g + 1]; k++)
            check_union(uf, first, o->part[oc_face(o, o->nm_half[k])]);
    }
    /* every entry straight to its root first: the relabelling below
     * overwrites roots with labels, which a later find must not walk */
    for (uint32_t p = 0; p < npatches; p++)
        uf[p] = check_find(uf, p);
    /* a degenerate face's patch is itself alone, joined to nothing */
    for (uint32_t f = 0; f < o->nf; f++)
        if (o->flags[f] & CHECK_DEGENERATE)
            uf[o->part[f]] = CHECK_NONE;
    uint32_t parts = 0;
    for (uint32_t p = 0; p < npatches; p++)
        if (uf[p] != CHECK_NONE)
            uf[p] = uf[p] == p ? parts++ : uf[uf[p]];
    for (uint32_t f = 0; f < o->nf; f++) {
        o->part[f] = uf[o->part[f]];
        /* face_part: a part below the count (--parts colours by it), or
         * none for a degenerate face alone */
        ZV_ASSERT(o->flags[f] & CHECK_DEGENERATE ? o->part[f] == CHECK_NONE : o->part[f] < parts);
    }
    o->c->components = parts;
    free(uf);
    return 0;
}

static int winding(ObjCheck *o)
{
    ParityFind u = { o->part, check_big((size_t)o->nf + 1, 1) };
    Patches pt = { 0 };
    int r = -1;
    if (u.bits && patches_find(o, &u, &pt) == 0 && patches_settle(o, &u, &pt) == 0)
        r = join_patches(o, pt.npatches);
    free(u.bits);
    free(pt.count);
    free(pt.conflict);
    free(pt.flip);
    return r;
}

/* ==== The measures ==== */

void check_measures(ObjCheck *o)
{
    CheckCounts *c = o->c;
    double vol = 0, mom[3] = { 0, 0, 0 };
    for (uint32_t f = 0; f < o->nf; f++) {
        FaceMeasure fm;
        face_measure(o, f, &fm);
        /* the crossing test may be setting CHECK_INTERSECTS beside this
         * (check.c): the flags are read as it writes them, atomically */
        uint8_t fl = __atomic_load_n(&o->flags[f], __ATOMIC_RELAXED);
        if (!(fl & CHECK_DEGENERATE))
            c->area += fm.area;
        double s = fl & CHECK_FLIPPED ? -1 : 1;
        vol += s * fm.vol;
        for (int k = 0; k < 3; k++)
            mom[k] += s * fm.mom[k];
    }
    /* faces of no area alone (a triangle collapsed to two points, whose
     * edge a-b twice looked like a closed surface) close nothing */
    c->closed = o->nf > c->degenerate_faces && c->boundary_edges == 0;
    c->watertight = c->closed && c->nonmanifold_edges == 0;
    c->has_volume = c->closed && c->nonorientable == 0;
    if (c->has_volume) {
        c->inside_out = vol < 0;
        c->volume = fabs(vol);
        for (int k = 0; k < 3; k++)
            c->centre[k] = o->ref[k] + (vol != 0 ? mom[k] / vol : 0);
    }
}

int check_shape(ObjCheck *o)
{
    return winding(o);
}
