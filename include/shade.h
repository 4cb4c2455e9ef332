#ifndef ZV_SHADE_H
#define ZV_SHADE_H
/* shade: face ids + depths + the scene's normals, colours and light in,
 * an RGB image out. Knows nothing of terminals or file formats. */

#include "pool.h"
#include <stddef.h>
#include <stdint.h>
#include "hsr.h"
#include "image.h"
#include "scene.h"
#include "screen.h"
#include "texture.h"

typedef enum { SHADE_LAMBERT = 0, SHADE_SMOOTH, SHADE_DEPTH, SHADE_ID, SHADE_COUNT } ShadeMode;

extern const char *const shade_names[SHADE_COUNT];
int shade_from_name(const char *name);          /* -1 if unknown */

/* Smooth shading's per-scene data (smooth.c), built on first use. */
typedef struct {
    const Scene *key;       /* built for this scene at this generation (Scene.gen: */
    uint32_t  key_gen;      /* the viewer edits its scene in place) */
    uint32_t  key_npolys;
    float     crease;       /* degrees it was built for */
    float    *cnorm;        /* 3 per scene polygon corner: object-space unit normal */
    uint32_t *face_poly;    /* 2 per face: first scene polygon, count */
} SmoothData;

/* Outlines' per-frame data (edges.c). */
typedef struct {
    int32_t  *face_sp;      /* per face: its screen polygon this frame, -1 none */
    uint32_t  cap;
    const float *nrm;       /* the faces' normals when at hand (set by shade_frame), else
                               NULL: computed pair by pair (scene.h) */
} EdgeData;

/* Textured and vertex-coloured faces' data (surface.c): per scene, each
 * face's polygons; per frame, the set-up of the faces met, in a small
 * table of SURF_SLOTS slots by face id (neighbouring samples mostly
 * show the same faces), and the sRGB encoding table. */
#define SURF_SLOTS 512
typedef struct SurfSetup SurfSetup;
typedef struct {
    const Scene *key;       /* face_poly built for this scene at this generation */
    uint32_t  key_gen, key_npolys;
    uint32_t *face_poly;    /* 2 per face: first scene polygon, count */
    SurfSetup *slot;        /* SURF_SLOTS */
    uint32_t  frame;        /* stamps the slots of this frame */
    SrgbEnc  *enc;
} SurfCache;

/* A face's colour in the table a frame uses instead of the per-face
 * arrays when they would outweigh it (a huge mesh in a small picture). */
typedef struct {
    int32_t id;         /* -1: empty */
    uint8_t rgb[4];
} ShadeSlot;

/* Per-face colour cache, reused across frames (grows to the face count). */
typedef struct {
    uint32_t *stamp;    /* frame stamp per face: colour below is current */
    uint8_t  *rgb;      /* 3 per face */
    uint32_t  cap, frame;
    ShadeSlot *slot;    /* slots (a power of two), keyed by a hash of the id */
    uint32_t  nslot;
    /* The compact form's face normals (scene.h), made by the first frame
     * big enough, for the scene nrm_key at generation nrm_gen with nrm_n
     * faces and its corners at nrm_corner (a scene built again in the
     * same place has new arrays) */
    float    *nrm;
    const Scene *nrm_key;
    const uint32_t *nrm_corner;
    uint32_t  nrm_gen, nrm_n;
    SmoothData smooth;
    EdgeData   edges;
    SurfCache  surf;
} ShadeCache;

#define SHADE_CREASE_DEFAULT 60.0f  /* degrees: sharper edges stay sharp under smooth */

void shade_cache_free(ShadeCache *c);

/* Colour every pixel: lambert (ambient + two-sided Lambert from
 * scene->light on the face's base colour), smooth (the same with normals
 * interpolated per pixel from the corners, edges sharper than crease
 * degrees kept), depth (near white, far black, over the frame's depth
 * range) or id (a distinct colour per face id). sp gives the projection
 * the frame was rendered with. The highlighted object's pixels are
 * tinted warm. Background pixels get rgb 0 and lit 0. */
typedef struct {
    ShadeMode mode;
    float     crease;       /* smooth: degrees */
    int       highlight;    /* object drawn highlighted (the viewer's selection), -1 none */
    int       edges;        /* draw outlines: silhouettes, creases, depth steps */
    int       wire;         /* the wireframe is drawn: faces dimmed under its edges */
    int       simd;         /* a SimdLevel (simd.h): SIMD_AUTO (0) = the level in use */
    int       no_textures;  /* textured faces show their one colour (--no-textures, the t key) */
    Pool     *pool;         /* helpers for the per-face and per-pixel loops (NULL: the caller alone);
                               the picture is the same with any number */
} ShadeSettings;

int  shade_frame(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, const ShadeSettings *set,
                 ShadeCache *cache, Image *out);

/* capshade.c: the caps of a section cut (ids from section_cap_id0) in
 * their own colour under the light, outlined; c NULL or no planes:
 * nothing. After shade_frame, on the same buffers. */
struct SectionCut;
void shade_caps(const Scene *s, const struct SectionCut *c, const FrameBufs *fb, Image *out);

/* edges.c: outlines over a shaded image (creases sharper than crease). */
int  shade_edges(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, float crease_deg, EdgeData *ed,
                 Image *out);
void edges_free(EdgeData *ed);

/* surface.c: colours that vary across a face (Scene.face_surf), per
 * sample, perspective-correct, in linear light. A frame's view of them: */
typedef struct {
    const Scene       *s;
    const ScreenPolys *sp;
    SurfCache         *sc;
    int                no_tex;
    int                nb;          /* loaded objects (grid copies share their polygons) */
    int                simd;        /* the SimdLevel texture lookups run at */
    Mat4               view;
} SurfFrame;

/* Start a frame: 0 with f ready, 1 when the scene has no such face (f
 * unused), -1 out of memory. */
int  texel_frame_begin(SurfFrame *f, const Scene *s, const ScreenPolys *sp, const ShadeSettings *set,
                      SurfCache *sc);
/* The colour of face id at sample (x, y) before light, linear, into
 * out; 0 when the face's colour does not vary (its face_rgb is right). */
int  texel_colour(SurfFrame *f, int32_t id, int x, int y, float out[3]);
/* Light k (the fraction Lambert gives an untextured face's bytes) as a
 * factor on linear light: a white texture lit by k shows as a white
 * material does. */
float texel_light(float k);
/* Lambert shading's pass: every sample of such a face, lit as its face
 * is (the face's light stays one, the colour varies). */
void shade_surfaces_flat(SurfFrame *f, const FrameBufs *fb, Image *out);
void texel_cache_free(SurfCache *sc);

/* smooth.c */
int  smooth_prepare(SmoothData *sd, const Scene *s, float crease_deg);
void smooth_free(SmoothData *sd);
/* sf: the frame's varying colours, NULL when there are none */
int  shade_smooth(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, SmoothData *sd,
                  const uint8_t *face_rgb_default, SurfFrame *sf, Image *out);
/* Each face's run of scene polygons (2 per face: first, count; face_poly
 * holds 2 (nfaces + 1)); grid copies' faces are left 0, 0. */
void shade_face_polys(const Scene *s, uint32_t *face_poly);

/* prims.c's points, segments and wireframe edges are not lit: a point
 * or segment takes its vertices' colours (PLY, XYZ, OBJ `v x y z r g
 * b`), else its object's colour dimmed with depth (near full, the
 * farthest of the frame's points and lines at 40%), so a scan without
 * colours still shows its shape; wireframe edges are near white over
 * faces dimmed to 40%. Depth and id shading treat them as faces do. */
#define PRIM_FAR_SHADE  0.4f
#define WIRE_FACE_SHADE 0.4f

/* marks.c: what --check found, in colour (Scene.marks). Problem edges
 * are drawn unlit in their kind's colour (MARK_BOUNDARY, MARK_NONMANIFOLD);
 * with --problems a face seen from inside takes MARK_FLIPPED's colour
 * and one that crosses another MARK_CROSSING's (crossing first), lit as
 * any face; with --parts every face takes its part's colour. */
void shade_mark_edge_colour(int kind, uint8_t rgb_out[3]);
void shade_mark_face_colour(int bits, uint8_t rgb_out[3]);
void shade_part_colour(uint32_t part, uint8_t rgb_out[3]);
/* The colour a problem in focus is drawn in over the picture (a
 * CheckLocKind): a hole red and a non-manifold edge or vertex magenta
 * as their edges, a flipped face blue and a crossing pair yellow as
 * their faces, a degenerate or duplicate face orange. */
void shade_problem_colour(int kind, uint8_t rgb_out[3]);
/* The faces' colours and surfaces a frame shades with instead of the
 * scene's, made again only when the scene, its marks or the mode
 * change. */
typedef struct {
    uint8_t     *rgb;           /* 3 per face (and one byte more: 4-byte loads) */
    uint16_t    *surf;          /* per face, NULL: every face plain */
    uint32_t     cap;           /* faces the arrays hold */
    const Scene *key;
    uint32_t     key_gen, key_marks, key_nfaces, key_tint;
    int          key_mode;
} MarkColours;
/* Colours laid over the loaded faces by a question asked of the model
 * (--overhang, --thickness; app/printtint.c): per loaded face r, g, b
 * and 1 when it is coloured (0: its own colour). Grid copies repeat
 * them. gen changes whenever they do. */
typedef struct {
    uint8_t  *rgba;
    uint32_t  nfaces;
    uint32_t  gen;
} FaceTint;
/* Make them for mode (1 problems, 2 parts, 3 both) and the tint (NULL
 * or none: no tint; over the parts' colours, under the problems'): 1
 * when the frame should shade with them, 0 when the scene's own
 * colours are right (no marks and no tint, or --problems with no face
 * marked), -1 out of memory. */
int  shade_mark_colours(MarkColours *mc, const Scene *s, int mode, const FaceTint *tint);
/* The ramp of --thickness: t 0 red, 1/3 yellow, 2/3 green, 1 and past
 * it blue; and the colour of an overhanging face. */
void shade_thickness_colour(double t, uint8_t rgb_out[3]);
void shade_overhang_colour(uint8_t rgb_out[3]);
void mark_colours_free(MarkColours *mc);

/* Distinct colour for a face id (also used by tests). */
void shade_id_colour(int32_t id, uint8_t rgb_out[3]);

#endif
