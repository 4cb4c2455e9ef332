/* marks.c: what --check found, on the model (--problems, --parts, the
 * viewer's ! key). Two halves:
 *
 * The check reads a Mesh with its faces, which scene_build dropped once
 * the polygon lists held them: scene_check_meshes makes each file's
 * faces again from the scene's polygons (a face kept whole is its
 * polygon; a split one is the fan (c0, ck, ck+1), whose outline is c0,
 * each triangle's second corner and the last one's third), with copies
 * of the positions, points and lines, so that the check owns everything
 * it reads and may run on another thread while the viewer edits the
 * scene. A mesh face keeps its index: object face_first + its polygons'
 * poly_lface.
 *
 * scene_marks_set turns the checks into what the picture draws: the
 * boundary and non-manifold edges as lines (prims.c draws them like the
 * wireframe's, ids after its), and per face whether it is seen from
 * inside (the fewest faces whose flip makes the winding agree, or, in a
 * closed object that is inside out, all the others) or crosses another,
 * and its part. */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "scene_internal.h"

/* ==== The files as meshes again ==== */

static void *dup_array(const void *p, size_t bytes, int *oom)
{
    if (!p)
        return NULL;
    void *q = malloc(bytes ? bytes : 1);
    if (!q)
        *oom = 1;
    else
        memcpy(q, p, bytes);
    return q;
}

/* Object o's faces' corners: counts into cnt[mesh face] (pass 0), or the
 * corners at start[mesh face] (pass 1). */
static void object_faces(const Scene *s, const Object *o, int pass, uint32_t *cnt, const uint32_t *start,
                         uint32_t *corner)
{
    const uint32_t *pc = s->poly_corner;
    uint32_t p = o->poly_first, pe = o->poly_first + o->poly_count;
    while (p < pe) {
        uint32_t q = p + 1;
        while (s->poly_lface && q < pe && s->poly_lface[q] == s->poly_lface[p])
            q++;
        uint32_t f = o->face_first + scene_poly_lface(s, o, p);
        uint32_t c0 = scene_poly_c0(s, p);
        uint32_t n = q - p == 1 ? scene_poly_c0(s, p + 1) - c0 : (q - p) + 2;
        if (pass == 0) {
            cnt[f] = n;
        } else if (q - p == 1) {
            memcpy(&corner[start[f]], &pc[c0], n * sizeof *corner);
        } else {
            uint32_t k = start[f];
            corner[k++] = pc[c0];
            for (uint32_t t = p; t < q; t++)
                corner[k++] = pc[scene_poly_c0(s, t) + 1];
            corner[k] = pc[scene_poly_c0(s, q - 1) + 2];
        }
        p = q;
    }
}

/* File mi of s as a mesh of its own. -1 out of memory (*m freed). */
static int mesh_again(const Scene *s, int mi, Mesh *m)
{
    const Mesh *src = &s->meshes[mi];
    int oom = 0;
    memset(m, 0, sizeof *m);
    m->info = src->info;
    m->nverts = src->nverts;
    m->nfaces = src->nfaces;
    m->nobjs = src->nobjs;
    m->npoints = src->npoints;
    m->nlines = src->nlines;
    m->path = src->path ? dup_array(src->path, strlen(src->path) + 1, &oom) : NULL;
    m->pos = dup_array(src->pos, 3 * (size_t)src->nverts * sizeof(float), &oom);
    m->objs = dup_array(src->objs, src->nobjs * sizeof *src->objs, &oom);
    m->point = dup_array(src->point, src->npoints * sizeof(uint32_t), &oom);
    if (src->line_start) {
        m->line_start = dup_array(src->line_start, (src->nlines + 1) * sizeof(uint32_t), &oom);
        m->line_corner = dup_array(src->line_corner, src->line_start[src->nlines] * sizeof(uint32_t), &oom);
    }
    m->face_start = calloc((size_t)src->nfaces + 1, sizeof(uint32_t));
    if (oom || !m->face_start) {
        mesh_free(m);
        return -1;
    }
    /* the counts, then the offsets (a face no object holds: none) */
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    for (int i = 0; i < nb; i++)
        if (s->objs[i].mesh == src)
            object_faces(s, &s->objs[i], 0, m->face_start, NULL, NULL);
    uint64_t total = 0;
    for (uint32_t f = 0; f <= src->nfaces; f++) {
        uint32_t c = f < src->nfaces ? m->face_start[f] : 0;
        m->face_start[f] = (uint32_t)total;
        total += c;
    }
    m->corner = malloc((total ? total : 1) * sizeof(uint32_t));
    if (!m->corner || total > UINT32_MAX) {
        mesh_free(m);
        return -1;
    }
    for (int i = 0; i < nb; i++)
        if (s->objs[i].mesh == src)
            object_faces(s, &s->objs[i], 1, NULL, m->face_start, m->corner);
    return 0;
}

int scene_check_meshes(const Scene *s, Mesh **out, int *n, char *err, size_t errlen)
{
    *out = NULL;
    *n = 0;
    Mesh *m = calloc(s->nmeshes ? (size_t)s->nmeshes : 1, sizeof *m);
    if (!m) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (int i = 0; i < s->nmeshes; i++)
        if (mesh_again(s, i, &m[i])) {
            scene_check_meshes_free(m, i);
            snprintf(err, errlen, "out of memory");
            return -1;
        }
    *out = m;
    *n = s->nmeshes;
    return 0;
}

void scene_check_meshes_free(Mesh *m, int n)
{
    for (int i = 0; m && i < n; i++)
        mesh_free(&m[i]);
    free(m);
}

/* ==== The marks ==== */

void scene_marks_release(SceneMarks *mk)
{
    free(mk->edge);
    free(mk->edge_kind);
    free(mk->face);
    free(mk->face_part);
    uint32_t gen = mk->gen;
    memset(mk, 0, sizeof *mk);
    mk->gen = gen + 1;
}

void scene_marks_clear(Scene *s)
{
    int had = s->marks.nedges > 0;
    scene_marks_release(&s->marks);
    for (int i = 0; s->objs && i < s->nobjs; i++)
        s->objs[i].mark_first = s->objs[i].mark_count = 0;
    if (had)
        scene_number_prims(s);      /* fewer ids: always fits */
}

/* Object i's problem edges from its check into the marks. */
static void object_marks(Scene *s, int i, const CheckObject *co)
{
    SceneMarks *mk = &s->marks;
    Object *o = &s->objs[i];
    o->mark_first = mk->nedges;
    for (uint32_t k = 0; k < co->c.boundary_edges; k++, mk->nedges++) {
        memcpy(&mk->edge[2 * (size_t)mk->nedges], &co->boundary[2 * (size_t)k], 2 * sizeof(uint32_t));
        mk->edge_kind[mk->nedges] = MARK_BOUNDARY;
    }
    for (uint32_t k = 0; k < co->c.nonmanifold_edges; k++, mk->nedges++) {
        memcpy(&mk->edge[2 * (size_t)mk->nedges], &co->nm_edges[2 * (size_t)k], 2 * sizeof(uint32_t));
        mk->edge_kind[mk->nedges] = MARK_NONMANIFOLD;
    }
    o->mark_count = mk->nedges - o->mark_first;
}

/* Object i's faces: seen from inside, crossing, their parts (after
 * *part0 parts of the objects before). */
static void object_faces_marks(Scene *s, int i, const MeshCheck *mc, uint32_t mobj, uint32_t *part0)
{
    SceneMarks *mk = &s->marks;
    const Object *o = &s->objs[i];
    const CheckObject *co = &mc->objs[mobj];
    int inside_out = co->c.inside_out;
    for (uint32_t f = 0; f < o->face_count; f++) {
        uint32_t g = (uint32_t)o->face_base + f, mf = o->face_first + f;
        uint8_t fl = mc->face_flags ? mc->face_flags[mf] : 0, bits = 0;
        /* the winding made to agree points in: the faces not flipped to
         * agree are the ones seen from inside */
        if (!(fl & (CHECK_DEGENERATE | CHECK_NONORIENT)) && (inside_out ? !(fl & CHECK_FLIPPED) : fl & CHECK_FLIPPED))
            bits |= MARK_FLIPPED;
        if (fl & CHECK_INTERSECTS)
            bits |= MARK_CROSSING;
        mk->face[g] = bits;
        mk->nflagged += bits != 0;
        mk->face_part[g] = *part0 + (mc->face_part ? mc->face_part[mf] : 0);
    }
    *part0 += co->c.components;
}

int scene_marks_set(Scene *s, const MeshCheck *checks, int n, char *err, size_t errlen)
{
    scene_marks_clear(s);
    SceneMarks *mk = &s->marks;
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    uint64_t nedges = 0;
    for (int i = 0; i < n && i < s->nmeshes; i++)
        nedges += (uint64_t)checks[i].file.boundary_edges + checks[i].file.nonmanifold_edges;
    uint32_t nf = 0;
    for (int i = 0; i < nb; i++)
        nf += s->objs[i].face_count;
    mk->edge = malloc((nedges ? nedges : 1) * 2 * sizeof *mk->edge);
    mk->edge_kind = malloc(nedges ? nedges : 1);
    mk->face = calloc(nf ? nf : 1, 1);
    mk->face_part = calloc(nf ? nf : 1, sizeof *mk->face_part);
    if (!mk->edge || !mk->edge_kind || !mk->face || !mk->face_part || nedges > INT32_MAX) {
        scene_marks_clear(s);
        snprintf(err, errlen, "out of memory marking the problems");
        return -1;
    }
    mk->nfaces = nf;
    uint32_t part0 = 0;
    for (int i = 0; i < nb; i++) {
        int f = scene_object_file(s, i);
        const Object *o = &s->objs[i];
        if (f < 0 || f >= n)
            continue;
        /* the mesh object this one is: the one of its first face */
        const MeshCheck *mc = &checks[f];
        uint32_t mobj = 0;
        while (mobj < mc->nobjs && !(mc->objs[mobj].face_first == o->face_first &&
                                     mc->objs[mobj].face_count == o->face_count))
            mobj++;
        if (mobj == mc->nobjs)
            continue;
        object_marks(s, i, &mc->objs[mobj]);
        object_faces_marks(s, i, mc, mobj, &part0);
    }
    mk->nparts = part0;
    /* grid copies draw their source's edges */
    for (int k = nb; k < s->nobjs; k++) {
        s->objs[k].mark_first = s->objs[k % nb].mark_first;
        s->objs[k].mark_count = s->objs[k % nb].mark_count;
    }
    if (scene_number_prims(s)) {
        scene_marks_clear(s);
        snprintf(err, errlen, "too many faces and edges to mark the problems");
        return -1;
    }
    mk->set = 1;
    return 0;
}
