/* wireframe.c: the wireframe (--wireframe, the viewer's W): every edge of
 * every object's faces once, as a pair of vertex indices, drawn as a
 * line hidden where the faces hide it. Edges are found per object
 * through a hash table of vertex pairs, so an edge two faces share is
 * drawn once; the diagonals that split a non-planar face into a fan are
 * not edges of the face and are left out. Grid copies draw their
 * source's edges. */

#include <stdio.h>
#include <stdlib.h>

#include "scene.h"
#include "scene_internal.h"

/* The edges found so far and the table that tells a new one. */
typedef struct {
    uint32_t *wire;    /* 2 a edge: its vertex indices */
    uint32_t  n;       /* edges in wire */
    uint64_t *key;     /* an edge's two vertices, the smaller first */
    uint32_t *stamp;   /* the object a slot was filled for + 1; another: empty */
    uint32_t  mask;    /* slots - 1, a power of two minus one */
} EdgeSet;

/* A hash of an edge's two vertex indices (the smaller first). */
static inline uint32_t edge_hash(uint32_t a, uint32_t b)
{
    uint64_t h = ((uint64_t)a << 32 | b) * 0x9E3779B97F4A7C15ull;
    return (uint32_t)(h >> 32);
}

/* Add edge (a, b) to the table unless there (slots hold an edge's two
 * vertices and the stamp of the object they were added for: another
 * stamp is an empty slot, so the table is not cleared between objects). */
static int edge_add(uint64_t *key, uint32_t *stamp, uint32_t mask, uint32_t st, uint32_t a, uint32_t b)
{
    if (a == b)
        return 0;       /* a degenerate edge draws nothing */
    if (a > b) {
        uint32_t t = a;
        a = b;
        b = t;
    }
    uint64_t k = (uint64_t)a << 32 | b;
    for (uint32_t i = edge_hash(a, b) & mask;; i = (i + 1) & mask) {
        if (stamp[i] != st) {
            stamp[i] = st;
            key[i] = k;
            return 1;
        }
        if (key[i] == k)
            return 0;
    }
}

/* Edge (a, b) of the object stamped st, kept when it is new. */
static inline void edge_put(EdgeSet *es, uint32_t st, uint32_t a, uint32_t b)
{
    if (edge_add(es->key, es->stamp, es->mask, st, a, b)) {
        es->wire[2 * es->n] = a;
        es->wire[2 * es->n + 1] = b;
        es->n++;
    }
}

/* The outline of one face, polygons [p, q) of the scene: one when it is
 * kept whole, else a fan (c0, ck, ck+1) whose diagonals are no edges of
 * the face: its outline is c0, each fan triangle's second corner, and
 * the last one's third. */
static void face_edges(const Scene *s, EdgeSet *es, uint32_t st, uint32_t p, uint32_t q)
{
    const uint32_t *pc = s->poly_corner;
    uint32_t prev, first;
    if (q - p == 1) {
        uint32_t c0 = scene_poly_c0(s, p), c1 = scene_poly_c0(s, p + 1);
        first = prev = pc[c0];
        for (uint32_t c = c0 + 1; c < c1; c++) {
            edge_put(es, st, prev, pc[c]);
            prev = pc[c];
        }
    } else {
        first = prev = pc[scene_poly_c0(s, p)];
        for (uint32_t t = p; t < q; t++) {
            uint32_t c0 = scene_poly_c0(s, t);
            uint32_t next[2] = { pc[c0 + 1], pc[c0 + 2] };
            for (int j = 0; j < (t + 1 == q ? 2 : 1); j++) {
                edge_put(es, st, prev, next[j]);
                prev = next[j];
            }
        }
    }
    edge_put(es, st, prev, first);
}

/* Object k's edges: each face's (its run of polygons of one face). */
static void object_edges(Scene *s, EdgeSet *es, int k)
{
    Object *o = &s->objs[k];
    o->wire_first = es->n;
    uint32_t p = o->poly_first, pe = o->poly_first + o->poly_count;
    while (p < pe) {
        uint32_t q = p + 1;
        while (s->poly_lface && q < pe && s->poly_lface[q] == s->poly_lface[p])
            q++;
        face_edges(s, es, (uint32_t)k + 1, p, q);
        p = q;
    }
    o->wire_count = es->n - o->wire_first;
}

/* The edge list (an edge per polygon corner at most) and a table big
 * enough for the largest object at most half full. -1 with the message. */
static int edges_alloc(const Scene *s, int nb, EdgeSet *es, char *err, size_t errlen)
{
    uint64_t corners = scene_ncorners(s), most = 0;
    for (int k = 0; k < nb; k++) {
        const Object *o = &s->objs[k];
        uint64_t c = scene_poly_c0(s, o->poly_first + o->poly_count) - scene_poly_c0(s, o->poly_first);
        most = c > most ? c : most;
    }
    uint64_t cap = 64;
    while (cap < 2 * most)
        cap *= 2;
    if (corners > INT32_MAX || cap > ((uint64_t)1 << 31)) {
        snprintf(err, errlen, "--wireframe: too many edges (%llu corners)", (unsigned long long)corners);
        return -1;
    }
    es->wire = malloc((corners ? corners : 1) * 2 * sizeof *es->wire);
    es->key = malloc(cap * sizeof *es->key);
    es->stamp = calloc(cap, sizeof *es->stamp);
    es->mask = (uint32_t)(cap - 1);
    if (!es->wire || !es->key || !es->stamp) {
        free(es->wire);
        free(es->key);
        free(es->stamp);
        snprintf(err, errlen, "--wireframe: out of memory");
        return -1;
    }
    return 0;
}

int scene_wire_build(Scene *s, char *err, size_t errlen)
{
    if (s->wire_built)
        return 0;
    int nb = s->nbase_objs ? (int)s->nbase_objs : s->nobjs;
    EdgeSet es = { 0 };
    if (edges_alloc(s, nb, &es, err, errlen))
        return -1;
    for (int k = 0; k < nb; k++)
        object_edges(s, &es, k);
    free(es.key);
    free(es.stamp);
    uint32_t n = es.n;
    uint32_t *w = realloc(es.wire, (n ? n : 1) * 2 * sizeof *w);
    s->wire = w ? w : es.wire;
    s->nwire_edges = n;
    /* grid copies draw their source's edges */
    for (int k = nb; k < s->nobjs; k++) {
        s->objs[k].wire_first = s->objs[k % nb].wire_first;
        s->objs[k].wire_count = s->objs[k % nb].wire_count;
    }
    if (scene_number_prims(s)) {
        for (int k = 0; k < s->nobjs; k++)
            s->objs[k].wire_count = 0;
        scene_number_prims(s);
        free(s->wire);
        s->wire = NULL;
        s->nwire_edges = 0;
        snprintf(err, errlen, "--wireframe: more than %d faces and edges", INT32_MAX);
        return -1;
    }
    s->wire_built = 1;
    return 0;
}
