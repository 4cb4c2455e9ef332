#ifndef ZV_HSR_OCTREE_H
#define ZV_HSR_OCTREE_H
/* Internal to hsr/: the object-space octrees of hzb-octree. octree.c
 * walks them; octree_build.c builds them, once per scene, on the
 * caller's thread or on a builder thread of their own, and hands each
 * frame the trees of its scene (OctShared.use). */

#include <pthread.h>
#include <stdint.h>

#include "scene.h"

#define MAX_DEPTH   20      /* a node is never deeper than this */
#define NO_TREE     UINT32_MAX

typedef struct {
    uint32_t first, count;  /* its polygons (whole subtree): order[first .. first + count) */
    uint32_t child;         /* first child, children contiguous and after it; 0 = leaf */
    uint32_t nchild;
} OctNode;

/* The trees of every loaded object of one scene, built once. */
typedef struct {
    const Scene *key;
    uint32_t   key_gen;
    uint32_t   key_npolys;
    int        key_nobjs;
    const uint32_t *key_corner;
    OctNode   *nodes;
    uint32_t   nnodes, cap_nodes;
    uint32_t  *order;       /* polygon index within its object, per node run */
    uint32_t  *leaf;        /* per polygon (tree's base + index within object): its leaf */
    uint32_t  *roots;       /* per loaded object: its first node, NO_TREE if none */
    uint32_t  *node_end;    /* per loaded object: one past its last node */
    uint32_t  *base;        /* per loaded object: its polygons' start in order[] and leaf[] */
    int        nroots;
    int        lface_sorted;    /* each object's polygons are in face order */
    const int *cancel;      /* while building: stop when this becomes nonzero */
    int        simd;        /* the SimdLevel it is built at (the same tree at every level) */
} OctTree;

/* Shared by the bands of one runner: the current trees and the builder. */
typedef struct {
    pthread_mutex_t mu;
    int        background;  /* build on a thread of its own (more than one thread) */
    OctTree   *cur;         /* the trees frames use, NULL before the first */
    OctTree   *next;        /* being built by the builder thread */
    int        building;    /* the builder thread runs (or has ended, not yet joined) */
    int        done;        /* ... and has ended: join it, take next */
    int        failed;      /* the last build ran out of memory: do not retry for that scene */
    const Scene *failed_key;
    uint32_t   failed_gen;
    int        cancel;      /* tell the builder to stop (read atomically) */
    const Scene *build_key; /* the scene the builder builds for */
    uint32_t   build_gen;   /* ... at this generation. The scene must not change while
                               it builds (pipeline_scene_changing stops it first) */
    pthread_t  th;
    /* for this frame, set by frame_begin before the bands start */
    const OctTree *use;     /* the trees of this frame's scene, or NULL */
} OctShared;

void octree_shared_init(OctShared *sh, int background);
/* Stops and joins the builder, frees the trees. */
void octree_shared_free(OctShared *sh);
/* Before a frame's bands start (one thread): take finished trees, start
 * (or, on one thread, do) the build this frame's scene needs, at the
 * frame's SIMD level (resolved: simd_use), and set sh->use. */
void octree_shared_frame_begin(OctShared *sh, const Scene *sc, int simd);

#endif
