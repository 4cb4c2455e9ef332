#ifndef ZV_SCENE_INTERNAL_H
#define ZV_SCENE_INTERNAL_H
/* scene internals shared by scene.c and edit.c. Not part of the public
 * API. */

#include "scene.h"

/* normals.c: Newell's normal of face f of m, in double, not unit; and
 * a normal made unit in float (+z for a degenerate one). Stored and
 * computed normals both come from these, so they are the same bits. */
void scene_face_newell(const Mesh *m, uint32_t f, double n[3]);
void scene_unit_normal(const double n[3], float out[3]);

/* Number the points, segments and wireframe edges after the faces: every
 * object's points, then every object's segments, then every object's
 * edges. -1 when the ids would pass INT32_MAX. */
int scene_number_prims(Scene *s);

/* marks.c: free what the marks hold (the objects' ranges left as they are). */
void scene_marks_release(SceneMarks *mk);

/* "scene too large" messages: the files, then what passes which limit. */
void scene_too_large(const Mesh *meshes, int n, uint64_t nobjs, uint64_t nfaces, char *err, size_t errlen);

/* ==== surface.c: faces whose colour varies across them ==== */

typedef struct {
    int         on;          /* some mesh has texture coordinates and textures, or vertex colours */
    const Mesh *mesh;        /* the mesh whose faces come now */
    int32_t    *matsurf;     /* its materials' surfaces, -1 = not made yet */
    uint32_t    cap;         /* materials matsurf holds */
    uint32_t    surfcap;     /* surfaces Scene.surf holds */
} SurfBuild;

/* Before the faces: face_surf allocated when any mesh can need it. -1
 * out of memory. */
int  surf_build_start(SurfBuild *sb, Scene *s, const Mesh *meshes, int nmeshes, uint64_t nfaces);
/* The faces of mesh m come next. */
void surf_build_mesh(SurfBuild *sb, const Mesh *m);
/* Face f of the current mesh (global face gface): its SURF_* kind in
 * face_surf; a textured face's rgb becomes its texture's mean times its
 * base colour. */
int  surf_of_face(SurfBuild *sb, Scene *s, uint32_t f, uint32_t gface, uint8_t rgb_inout[3]);
/* After the faces: face_surf dropped when every face is plain. */
void surf_build_end(SurfBuild *sb, Scene *s);
/* Do polygon corners need texture coordinates (a face is textured)? */
int  surf_want_uv(const Scene *s);
/* The texture coordinate of mesh corner k (0, 0 when it has none). */
void surf_corner_uv(const Mesh *m, uint32_t k, float *out);
/* A texture's mean (its last mipmap level) times the base colour. */
void surf_mean_rgb(const SceneSurf *su, uint8_t rgb_out[3]);

#endif
