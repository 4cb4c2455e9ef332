/* octree_build.c: the octrees of hzb-octree (octree.c), one per loaded
 * object of a scene, built once and shared by the bands of a runner.
 *
 * A node splits its polygons by centroid into the octants about the
 * middle of their centroids' box (a stable counting sort, so every run
 * stays in polygon order), until a leaf holds at most LEAF_POLYS or the
 * tree is MAX_DEPTH deep; a node's polygons are one contiguous run of a
 * flat index array, and every polygon knows its leaf. For a big scene
 * with more than one thread the trees are built on a thread of their
 * own, which a frame for another scene, or the runner's end, cancels.
 *
 * Octree subdivision as in D. Meagher, "Geometric Modeling Using Octree
 * Encoding", CGIP 19(2), 1982.
 */

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "octree.h"
#include "simd.h"
#include "thread.h"

#define LEAF_POLYS  128     /* a node with more polygons is split */
/* Scenes of fewer polygons (loaded objects) build their trees right away,
 * in a few milliseconds, even with threads to spare. */
#define BACKGROUND_MIN 65536

/* ==== building ==== */

static int new_nodes(OctTree *s, uint32_t n, uint32_t *first_out)
{
    if (s->nnodes + n > s->cap_nodes) {
        uint32_t cap = s->cap_nodes ? s->cap_nodes : 256;
        while (cap < s->nnodes + n)
            cap *= 2;
        OctNode *q = realloc(s->nodes, (size_t)cap * sizeof *q);
        if (!q)
            return -1;
        s->nodes = q;
        s->cap_nodes = cap;
    }
    *first_out = s->nnodes;
    memset(&s->nodes[s->nnodes], 0, n * sizeof *s->nodes);
    s->nnodes += n;
    return 0;
}

static int cancelled(const OctTree *s)
{
    return s->cancel && __atomic_load_n(s->cancel, __ATOMIC_RELAXED);
}

/* Build scratch: the centroids travel with the polygons they belong to,
 * so each pass over a node reads them in order. */
typedef struct {
    float    *cen;          /* 3 per polygon, in order[] order */
    float    *cen2;         /* scratch of the same size */
    uint32_t *ord2;         /* scratch for order[] */
    uint8_t  *oct;          /* each polygon's octant in its node */
    int       simd;         /* the SimdLevel of the octant loop */
} BuildWork;

/* The octant of each of count centroids about mid (bit a set: above mid
 * on axis a), the octants' counts (cnt, zeroed by the caller) and the
 * boxes of their centroids (clo, chi; +inf/-inf for an empty octant).
 * Minima and maxima are taken as
 * min(box, c) = box < c ? box : c and max likewise, the operand order
 * of the SSE2 instructions, so both loops give the same bits (a -0
 * against a +0 included). */
static void split_scalar(const float *cen, uint8_t *oct, uint32_t count, const float mid[3], uint32_t cnt[8],
                         float clo[8][3], float chi[8][3])
{
    for (int o = 0; o < 8; o++)
        for (int a = 0; a < 3; a++) {
            clo[o][a] = INFINITY;
            chi[o][a] = -INFINITY;
        }
    for (uint32_t i = 0; i < count; i++) {
        const float *c = cen + 3 * (size_t)i;
        int o = (c[0] > mid[0]) | (c[1] > mid[1]) << 1 | (c[2] > mid[2]) << 2;
        oct[i] = (uint8_t)o;
        cnt[o]++;
        for (int a = 0; a < 3; a++) {
            clo[o][a] = clo[o][a] < c[a] ? clo[o][a] : c[a];
            chi[o][a] = chi[o][a] > c[a] ? chi[o][a] : c[a];
        }
    }
}

#ifdef ZV_SSE2
/* split_scalar four floats a load (the scratch has one to spare at its
 * end): the octant from one compare, the child's box by min and max. */
static void split_sse2(const float *cen, uint8_t *oct, uint32_t count, const float mid[3], uint32_t cnt[8],
                       float clo[8][3], float chi[8][3])
{
    __m128 vlo[8], vhi[8];
    const __m128 vmid = _mm_setr_ps(mid[0], mid[1], mid[2], 0);
    for (int o = 0; o < 8; o++) {
        vlo[o] = _mm_set1_ps(INFINITY);
        vhi[o] = _mm_set1_ps(-INFINITY);
    }
    for (uint32_t i = 0; i < count; i++) {
        __m128 c = _mm_loadu_ps(cen + 3 * (size_t)i);
        int o = _mm_movemask_ps(_mm_cmpgt_ps(c, vmid)) & 7;
        oct[i] = (uint8_t)o;
        cnt[o]++;
        vlo[o] = _mm_min_ps(vlo[o], c);
        vhi[o] = _mm_max_ps(vhi[o], c);
    }
    for (int o = 0; o < 8; o++) {
        float l[4], h[4];
        _mm_storeu_ps(l, vlo[o]);
        _mm_storeu_ps(h, vhi[o]);
        memcpy(clo[o], l, sizeof clo[o]);
        memcpy(chi[o], h, sizeof chi[o]);
    }
}
#endif

/* Fill node ni over order[first .. first + count) (polygon indices local
 * to the object, ascending; w->cen[first ..] their centroids, within the
 * box lo..hi) and split it when large: about the middle of the box, by a
 * stable counting sort that also finds each child's box. Stable, so every
 * node's run stays ascending: a leaf reads the screen polygons in order. */
static int build_node(OctTree *s, BuildWork *w, uint32_t ni, uint32_t first, uint32_t count, const float lo[3],
                      const float hi[3], int depth)
{
    OctNode *n = &s->nodes[ni];
    n->first = first;
    n->count = count;
    n->child = 0;
    n->nchild = 0;
    if (count <= LEAF_POLYS || depth >= MAX_DEPTH)
        return 0;
    if (cancelled(s))
        return -1;
    float mid[3];
    for (int a = 0; a < 3; a++)
        mid[a] = 0.5f * (lo[a] + hi[a]);
    uint32_t cnt[8] = { 0 };
    float clo[8][3], chi[8][3];
    const float *cen = w->cen + 3 * (size_t)first;
    uint8_t *oct = w->oct + first;
#ifdef ZV_SSE2
    if (w->simd >= SIMD_SSE2)
        split_sse2(cen, oct, count, mid, cnt, clo, chi);
    else
#endif
        split_scalar(cen, oct, count, mid, cnt, clo, chi);
    int used = 0;
    for (int o = 0; o < 8; o++)
        used += cnt[o] > 0;
    if (used < 2)           /* all centroids on one side: nothing to split */
        return 0;
    uint32_t start[8], acc = 0;
    for (int o = 0; o < 8; o++) {
        start[o] = acc;
        acc += cnt[o];
    }
    uint32_t *ord = s->order + first, *ord2 = w->ord2 + first;
    float *cen2 = w->cen2 + 3 * (size_t)first;
    for (uint32_t i = 0; i < count; i++) {
        uint32_t at = start[oct[i]]++;
        ord2[at] = ord[i];
        memcpy(cen2 + 3 * (size_t)at, cen + 3 * (size_t)i, 3 * sizeof(float));
    }
    memcpy(ord, ord2, count * sizeof *ord);
    memcpy(w->cen + 3 * (size_t)first, cen2, 3 * (size_t)count * sizeof(float));
    uint32_t kids;
    if (new_nodes(s, (uint32_t)used, &kids))
        return -1;
    s->nodes[ni].child = kids;
    s->nodes[ni].nchild = (uint32_t)used;
    uint32_t at = first, k = 0;
    for (int o = 0; o < 8; o++) {
        if (!cnt[o])
            continue;
        if (build_node(s, w, kids + k, at, cnt[o], clo[o], chi[o], depth + 1))
            return -1;
        at += cnt[o];
        k++;
    }
    return 0;
}

static void tree_free(OctTree *s)
{
    if (!s)
        return;
    free(s->nodes);
    free(s->order);
    free(s->leaf);
    free(s->roots);
    free(s->node_end);
    free(s->base);
    free(s);
}

static int tree_is_for(const OctTree *t, const Scene *sc)
{
    return t && t->key == sc && t->key_gen == sc->gen && t->key_npolys == sc->npolys && t->key_nobjs == sc->nobjs &&
           t->key_corner == sc->poly_corner;
}

/* Build the trees of every loaded object of the scene into s (zeroed but
 * for cancel). Returns 0, or -1 (out of memory, or cancelled). */
static int tree_build(OctTree *s, const Scene *sc)
{
    s->key = sc;
    s->key_gen = sc->gen;
    s->key_npolys = sc->npolys;
    s->key_nobjs = sc->nobjs;
    s->key_corner = sc->poly_corner;
    int nb = (int)sc->nbase_objs;
    if (nb <= 0 || nb > sc->nobjs)
        nb = sc->nobjs;
    uint64_t total = 0;
    for (int k = 0; k < nb; k++)
        total += sc->objs[k].poly_count;
    size_t nbs = (size_t)(nb > 0 ? nb : 1), tot = (size_t)(total > 0 ? total : 1);
    s->roots = malloc(nbs * sizeof *s->roots);
    s->node_end = malloc(nbs * sizeof *s->node_end);
    s->base = malloc(nbs * sizeof *s->base);
    s->order = malloc(tot * sizeof *s->order);
    s->leaf = malloc(tot * sizeof *s->leaf);
    BuildWork w;
    /* indexed like order[]: every loaded object's polygons */
    w.cen = malloc((tot * 3 + 1) * sizeof(float));     /* + 1: 4-float loads */
    w.cen2 = malloc((tot * 3 + 1) * sizeof(float));
    w.ord2 = malloc(tot * sizeof(uint32_t));
    w.oct = malloc(tot);
    w.simd = s->simd;
    int rc = -1;
    if (!s->roots || !s->node_end || !s->base || !s->order || !s->leaf || !w.cen || !w.cen2 || !w.ord2 || !w.oct)
        goto out;
    s->nroots = nb;
    /* the flat walk finds an object's screen polygons by face id */
    s->lface_sorted = 1;
    for (int k = 0; k < nb; k++) {
        const Object *o = &sc->objs[k];
        for (uint32_t i = 1; sc->poly_lface && i < o->poly_count; i++)
            if (sc->poly_lface[o->poly_first + i] < sc->poly_lface[o->poly_first + i - 1])
                s->lface_sorted = 0;
    }
    uint32_t at = 0;
    for (int k = 0; k < nb; k++) {
        const Object *o = &sc->objs[k];
        s->roots[k] = NO_TREE;
        s->base[k] = at;
        if (!o->poly_count || !o->mesh)
            continue;
        const float *pos = o->mesh->pos;
        float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
        for (uint32_t i = 0; i < o->poly_count; i++) {
            uint32_t pk = o->poly_first + i;
            /* summed in locals: a store to w.cen could alias pos */
            float c[3] = { 0, 0, 0 };
            uint32_t c0 = scene_poly_c0(sc, pk), c1 = scene_poly_c0(sc, pk + 1);
            for (uint32_t q = c0; q < c1; q++) {
                const float *v = &pos[3 * (size_t)sc->poly_corner[q]];
                c[0] += v[0];
                c[1] += v[1];
                c[2] += v[2];
            }
            float inv = c1 > c0 ? 1.0f / (float)(c1 - c0) : 0;
            for (int a = 0; a < 3; a++) {
                c[a] *= inv;
                lo[a] = c[a] < lo[a] ? c[a] : lo[a];
                hi[a] = c[a] > hi[a] ? c[a] : hi[a];
            }
            memcpy(&w.cen[3 * ((size_t)at + i)], c, sizeof c);
            s->order[at + i] = i;
        }
        uint32_t root;
        if (cancelled(s) || new_nodes(s, 1, &root) || build_node(s, &w, root, at, o->poly_count, lo, hi, 0))
            goto out;
        s->roots[k] = root;
        s->node_end[k] = s->nnodes;
        /* each polygon's leaf, for gathering the bounds in polygon order */
        for (uint32_t n = root; n < s->nnodes; n++)
            if (!s->nodes[n].nchild)
                for (uint32_t i = 0; i < s->nodes[n].count; i++)
                    s->leaf[at + s->order[s->nodes[n].first + i] ] = n;
        at += o->poly_count;
    }
    rc = 0;
out:
    free(w.cen);
    free(w.cen2);
    free(w.ord2);
    free(w.oct);
    return rc;
}

/* ==== the shared trees: built once, in the background or not ==== */

static void *builder_main(void *arg)
{
    OctShared *sh = arg;
    /* next and its scene stay as they are until this thread is joined */
    int rc = tree_build(sh->next, sh->build_key);
    pthread_mutex_lock(&sh->mu);
    if (rc) {
        sh->failed = !__atomic_load_n(&sh->cancel, __ATOMIC_RELAXED);
        sh->failed_key = sh->build_key;
        sh->failed_gen = sh->build_gen;
        tree_free(sh->next);
        sh->next = NULL;
    }
    sh->done = 1;
    pthread_mutex_unlock(&sh->mu);
    return NULL;
}

/* Wait for the builder (told to stop first when cancel), and take what
 * it built. Called with sh->mu not held, from one thread. */
static void builder_join(OctShared *sh, int cancel)
{
    if (!sh->building)
        return;
    if (cancel)
        __atomic_store_n(&sh->cancel, 1, __ATOMIC_RELAXED);
    pthread_join(sh->th, NULL);
    sh->building = sh->done = 0;
    __atomic_store_n(&sh->cancel, 0, __ATOMIC_RELAXED);
    if (sh->next) {
        tree_free(sh->cur);
        sh->cur = sh->next;
        sh->next = NULL;
    }
}

static OctTree *tree_new(OctShared *sh, const Scene *sc, int simd)
{
    OctTree *t = calloc(1, sizeof *t);
    if (t) {
        t->key = sc;
        t->cancel = &sh->cancel;
        t->simd = simd;
    }
    return t;
}

/* octree.h */
void octree_shared_frame_begin(OctShared *sh, const Scene *sc, int simd)
{
    sh->use = NULL;
    if (!sc || sc->nobjs == 0)
        return;
    pthread_mutex_lock(&sh->mu);
    int done = sh->done;
    pthread_mutex_unlock(&sh->mu);
    if (sh->building && (done || sh->build_key != sc || sh->build_gen != sc->gen))
        builder_join(sh, !done);     /* finished, or building for a scene gone by */
    if (tree_is_for(sh->cur, sc)) {
        sh->use = sh->cur;
        return;
    }
    if (sh->building || (sh->failed && sh->failed_key == sc && sh->failed_gen == sc->gen))
        return;
    sh->failed = 0;
    OctTree *t = tree_new(sh, sc, simd);
    if (!t)
        return;
    uint64_t polys = 0;
    for (int k = 0; k < (int)sc->nbase_objs && k < sc->nobjs; k++)
        polys += sc->objs[k].poly_count;
    if (sh->background && polys >= BACKGROUND_MIN) {
        sh->next = t;
        sh->build_key = sc;
        sh->build_gen = sc->gen;
        sh->done = 0;
        if (thread_start(&sh->th, builder_main, sh) == 0) {
            sh->building = 1;
            return;
        }
        sh->next = NULL;        /* no thread to be had: build it here */
    }
    if (tree_build(t, sc)) {
        tree_free(t);
        sh->failed = 1;
        sh->failed_key = sc;
        sh->failed_gen = sc->gen;
        return;
    }
    tree_free(sh->cur);
    sh->cur = t;
    sh->use = t;
}

void octree_shared_init(OctShared *sh, int background)
{
    memset(sh, 0, sizeof *sh);
    pthread_mutex_init(&sh->mu, NULL);
    sh->background = background;
}

void octree_shared_free(OctShared *sh)
{
    builder_join(sh, 1);
    tree_free(sh->cur);
    tree_free(sh->next);
    pthread_mutex_destroy(&sh->mu);
}
