/* shade: face ids + depths in, an RGB image out.
 *
 * Lambert and id colours depend only on the face, so they are computed
 * once per visible face per frame and kept in a ShadeCache keyed by a
 * frame stamp; the per-pixel loop is then a lookup and a 3-byte copy.
 * Depth colours depend on the pixel and are computed per pixel. At the
 * frame's SIMD level AVX2 (ShadeSettings.simd, simd.h) faces are
 * coloured and pixels copied eight at a time, with the scalar loops'
 * bytes.
 *
 * Diffuse light is Lambert's cosine law (J. H. Lambert, Photometria,
 * 1760) plus an ambient share.
 */

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "bigmem.h"
#include "invariant.h"
#include "shade.h"
#include "simd.h"
#include "facecol.h"

/* ==== Names ==== */

const char *const shade_names[SHADE_COUNT] = { "lambert", "smooth", "depth", "id" };

int shade_from_name(const char *name)
{
    if (!name)
        return -1;
    for (int i = 0; i < SHADE_COUNT; i++)
        if (strcmp(name, shade_names[i]) == 0)
            return i;
    return -1;
}

/* ==== Cache ==== */

void shade_cache_free(ShadeCache *c)
{
    bigmem_zfree(c->stamp, (size_t)c->cap * sizeof *c->stamp);
    free(c->rgb);
    free(c->slot);
    free(c->nrm);
    smooth_free(&c->smooth);
    edges_free(&c->edges);
    texel_cache_free(&c->surf);
    memset(c, 0, sizeof *c);
}

/* Room for n faces, every one stale (stamp 0, which no frame uses).
 * The stamps come zeroed from the kernel (bigmem_zalloc), not realloc'd
 * and cleared: only the pages of faces a frame shows become resident (a
 * 5M-face model in a terminal-sized picture leaves nearly all of its
 * 20 MB of stamps untouched; issue 21). */
static int cache_grow(ShadeCache *c, uint32_t n)
{
    if (n <= c->cap && c->stamp && c->rgb)
        return 0;
    uint32_t cap = n ? n : 1;
    bigmem_zfree(c->stamp, (size_t)c->cap * sizeof *c->stamp);
    free(c->rgb);
    c->stamp = bigmem_zalloc((size_t)cap * sizeof *c->stamp);
    c->rgb = malloc((size_t)cap * 3 + 1);     /* + 1: the pixel loop loads 4 bytes a face */
    c->cap = c->stamp ? cap : 0;               /* the size bigmem_zfree is given */
    return c->stamp && c->rgb ? 0 : -1;
}

/* Start a frame: a fresh stamp makes every cached colour stale at once. */
static void cache_next_frame(ShadeCache *c)
{
    if (++c->frame == 0) {
        if (c->stamp)
            memset(c->stamp, 0, (size_t)c->cap * sizeof *c->stamp);
        c->frame = 1;
    }
}

/* ==== Colours ==== */

static inline uint8_t clamp_u8(float v)
{
    v += 0.5f;
    return v <= 0.0f ? 0 : v >= 255.0f ? 255 : (uint8_t)v;
}

/* 32-bit finaliser (from the murmur3 family): every input bit moves
 * every output bit, so neighbouring ids get unrelated values. */
static inline uint32_t mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

void shade_id_colour(int32_t id, uint8_t rgb_out[3])
{
    /* Hue steps by the golden ratio so consecutive ids land far apart
     * on the wheel; saturation and value vary with a second hash so ids
     * whose hues nearly meet still differ. Value stays >= 0.65 so no
     * face is close to the black background. */
    uint32_t u = (uint32_t)id;
    float hue = (float)((u * 2654435769u) >> 8) * (6.0f / 16777216.0f);
    uint32_t hsh = mix32(u);
    float sat = 0.55f + 0.45f * (float)(hsh & 0xff) / 255.0f;
    float val = 0.65f + 0.35f * (float)((hsh >> 8) & 0xff) / 255.0f;
    int sector = (int)hue;
    if (sector > 5)
        sector = 5;
    float f = hue - (float)sector;
    float p = val * (1.0f - sat);
    float q = val * (1.0f - sat * f);
    float t = val * (1.0f - sat * (1.0f - f));
    float r, g, b;
    switch (sector) {
    case 0: r = val; g = t; b = p; break;
    case 1: r = q; g = val; b = p; break;
    case 2: r = p; g = val; b = t; break;
    case 3: r = p; g = q; b = val; break;
    case 4: r = t; g = p; b = val; break;
    default: r = val; g = p; b = q; break;
    }
    rgb_out[0] = clamp_u8(r * 255.0f);
    rgb_out[1] = clamp_u8(g * 255.0f);
    rgb_out[2] = clamp_u8(b * 255.0f);
}

void shade_normal_mat(const Scene *s, const Mat4 *view, int obj, NormalMat *out)
{
    Mat4 om = object_matrix(&s->objs[obj]);
    Mat4 m = m4_mul(*view, om);
    out->obj = obj;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out->m[i][j] = m.m[i][j];
}

/* Lambert colour of one face, two-sided (|n.l|) so faces seen from the
 * back are lit like their fronts. nrm: the faces' normals when at hand
 * (NULL: computed, scene.h). */
void shade_lambert_face(const Scene *s, const float *nrm, const NormalMat *nm, uint32_t face, uint8_t out[3])
{
    float own[3];
    const float *n = nrm ? nrm + 3 * (size_t)face : own;
    if (!nrm)
        scene_face_normal(s, face, own);
    Vec3 v = v3(nm->m[0][0] * n[0] + nm->m[0][1] * n[1] + nm->m[0][2] * n[2],
                nm->m[1][0] * n[0] + nm->m[1][1] * n[1] + nm->m[1][2] * n[2],
                nm->m[2][0] * n[0] + nm->m[2][1] * n[1] + nm->m[2][2] * n[2]);
    v = v3_norm(v);
    float amb = s->light.ambient;
    float k = amb + (1.0f - amb) * fabsf(v3_dot(v, s->light.dir));
    const uint8_t *base = scene_face_rgb(s, face);
    out[0] = clamp_u8((float)base[0] * k);
    out[1] = clamp_u8((float)base[1] * k);
    out[2] = clamp_u8((float)base[2] * k);
}

/* ==== Frame ==== */

static void shade_depth(const FrameBufs *fb, uint32_t nfaces, Image *out)
{
    /* nfaces here: every id drawn, points and lines included */
    size_t n = (size_t)fb->w * (size_t)fb->h;
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (fb->ids[i] < 0 || (uint32_t)fb->ids[i] >= nfaces)
            continue;
        float d = fb->depth[i];
        if (!isfinite(d))
            continue;
        if (d < lo) lo = d;
        if (d > hi) hi = d;
    }
    /* One depth (or none) in the frame: everything drawn is "nearest". */
    float scale = hi > lo ? 255.0f / (hi - lo) : 0.0f;
    for (size_t i = 0; i < n; i++) {
        uint8_t *px = out->rgb + 3 * i;
        if (fb->ids[i] < 0 || (uint32_t)fb->ids[i] >= nfaces) {
            px[0] = px[1] = px[2] = 0;
            out->lit[i] = 0;
            continue;
        }
        float d = fb->depth[i];
        uint8_t v = !isfinite(d) ? 0 : scale == 0.0f ? 255 : clamp_u8(255.0f - (d - lo) * scale);
        px[0] = px[1] = px[2] = v;
        out->lit[i] = 1;
    }
}

static int id_object(const Scene *s, int32_t id);

/* Tint the pixels of object obj towards a warm yellow: the selection
 * shows in any shading and at any colour depth. */
static void highlight_object(const Scene *s, const FrameBufs *fb, int obj, Image *out)
{
    static const float tint[3] = { 255, 205, 60 }, share = 0.45f;
    size_t n = (size_t)fb->w * (size_t)fb->h;
    for (size_t i = 0; i < n; i++) {
        int32_t id = fb->ids[i];
        if (id < 0 || id_object(s, id) != obj)
            continue;
        uint8_t *px = out->rgb + 3 * i;
        for (int a = 0; a < 3; a++)
            px[a] = clamp_u8((1 - share) * (float)px[a] + share * tint[a]);
    }
}

static int shade_mode(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, const ShadeSettings *set,
                      ShadeCache *cache, Image *out);

static inline uint8_t unit_u8(float c)
{
    return (uint8_t)(c <= 0 ? 0 : c >= 1 ? 255 : c * 255.0f + 0.5f);
}

/* The colour of point or segment k of object o before the depth cue;
 * returns 1 when it has vertex colours of its own (no cue then). */
static int prim_base(const Scene *s, int obj, PrimKind kind, uint32_t k, uint8_t out[3])
{
    const Object *o = &s->objs[obj];
    const Mesh *m = o->mesh;
    if (m->rgb) {
        uint32_t v[2];
        if (kind == PRIM_POINT)
            v[0] = v[1] = object_point_vert(o, k);
        else
            scene_edge_verts(s, o, kind, k, v);
        for (int a = 0; a < 3; a++)
            out[a] = unit_u8(0.5f * (m->rgb[3 * (size_t)v[0] + a] + m->rgb[3 * (size_t)v[1] + a]));
        return 1;
    }
    if (s->nbase_objs > 1) {
        object_colour(obj % (int)s->nbase_objs, out);
    } else {
        out[0] = 204;
        out[1] = 204;
        out[2] = 196;
    }
    return 0;
}

static inline int is_prim(const Scene *s, int32_t id)
{
    return id >= 0 && (uint32_t)id >= s->nfaces && (uint32_t)id - s->nfaces < s->nprims;
}

/* Colour the pixels of points, segments and wireframe edges (lambert
 * and smooth; depth and id shading did them with the faces), and dim
 * the faces under a wireframe. */
static void shade_prims(const Scene *s, const FrameBufs *fb, const ShadeSettings *set, Image *out)
{
    size_t n = (size_t)fb->w * (size_t)fb->h;
    int lit_mode = set->mode == SHADE_LAMBERT || set->mode == SHADE_SMOOTH;
    if (set->wire && lit_mode)
        for (size_t i = 0; i < n; i++)
            if (fb->ids[i] >= 0 && (uint32_t)fb->ids[i] < s->nfaces)
                for (int a = 0; a < 3; a++)
                    out->rgb[3 * i + a] = (uint8_t)(out->rgb[3 * i + a] * WIRE_FACE_SHADE + 0.5f);
    if (!s->nprims || !lit_mode)
        return;
    /* the depth range of the frame's points and lines, for the cue */
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++)
        if (is_prim(s, fb->ids[i]) && isfinite(fb->depth[i])) {
            lo = fb->depth[i] < lo ? fb->depth[i] : lo;
            hi = fb->depth[i] > hi ? fb->depth[i] : hi;
        }
    float scale = hi > lo ? (1.0f - PRIM_FAR_SHADE) / (hi - lo) : 0;
    int32_t last = -1;
    uint8_t base[3] = { 0, 0, 0 };
    int own = 0;
    PrimKind kind = PRIM_NONE;
    for (size_t i = 0; i < n; i++) {
        int32_t id = fb->ids[i];
        if (!is_prim(s, id))
            continue;
        if (id != last) {       /* neighbouring pixels mostly share an id */
            int obj;
            uint32_t k;
            kind = scene_prim_of(s, id, &obj, &k);
            /* an id past the faces names a point, segment or edge of an
             * object (is_prim said it is in range): the mark colours and
             * prim_base index that object's arrays by it */
            ZV_ASSERT(kind != PRIM_NONE && kind != PRIM_FACE && obj >= 0 && obj < s->nobjs);
            if (kind == PRIM_WIRE) {
                base[0] = base[1] = base[2] = 235;
                own = 1;
            } else if (kind == PRIM_MARK) {
                shade_mark_edge_colour(s->marks.edge_kind[s->objs[obj].mark_first + k], base);
                own = 1;
            } else {
                own = prim_base(s, obj, kind, k, base);
            }
            last = id;
        }
        uint8_t *px = out->rgb + 3 * i;
        float cue = own || !isfinite(fb->depth[i]) ? 1.0f : 1.0f - (fb->depth[i] - lo) * scale;
        for (int a = 0; a < 3; a++)
            px[a] = clamp_u8((float)base[a] * cue);
        out->lit[i] = 1;
    }
}

/* The object of a drawn id (faces, points, lines), -1 for none. */
static int id_object(const Scene *s, int32_t id)
{
    int obj;
    uint32_t k;
    if (id >= 0 && (uint32_t)id < s->nfaces)
        return s->face_obj ? s->face_obj[id] : 0;
    return is_prim(s, id) && scene_prim_of(s, id, &obj, &k) != PRIM_NONE ? obj : -1;
}


/* ==== Lambert and id colours, per face, per pixel ==== */

/* Face id's colour, made current. */
static inline const uint8_t *face_colour(FaceColours *fc, int32_t id)
{
    uint8_t *c = fc->crgb + 3 * (size_t)id;
    if (fc->stamp[id] != fc->frame) {
        face_make(fc, id, c);
        fc->stamp[id] = fc->frame;
    }
    return c;
}

#ifdef ZV_AVX2
/* The normal matrix of object obj, from its direct-mapped slot (for the
 * eight-face loop: the scalar code finds it face by face). */
static inline const NormalMat *object_nmat(FaceColours *fc, int obj)
{
    NormalMat *nm = &fc->nmat[obj & (NMAT_SLOTS - 1)];
    if (nm->obj != obj)
        shade_normal_mat(fc->s, &fc->view, obj, nm);
    return nm;
}
#endif

/* The face normals of a big frame: the scene's, or for the compact form
 * (scene.h) computed once a scene and kept: computing them every frame
 * cost more than the colours (8 of 12 ms for the dragon at 1920x1080,
 * 100 ms for the 5.2M dragon). NULL out of memory. */
static const float *dense_normals(ShadeCache *c, const Scene *s, int simd)
{
    if (s->face_normal)
        return s->face_normal;
    if (c->nrm && c->nrm_key == s && c->nrm_gen == s->gen && c->nrm_n == s->nfaces && c->nrm_corner == s->poly_corner)
        return c->nrm;
    free(c->nrm);
    c->nrm_key = NULL;
    if (!(c->nrm = malloc(((size_t)s->nfaces + 1) * 3 * sizeof(float))))
        return NULL;
    for (int o = 0; o < s->nobjs; o++) {
        const Object *ob = &s->objs[o];
        scene_face_normals(s, (uint32_t)ob->face_base, ob->face_count, c->nrm + 3 * (size_t)ob->face_base, simd);
    }
    c->nrm_key = s;
    c->nrm_corner = s->poly_corner;
    c->nrm_gen = s->gen;
    c->nrm_n = s->nfaces;
    return c->nrm;
}

#ifdef ZV_AVX2
/* shade_lambert_face() of faces [f0, f1) of one object (normal matrix nm),
 * eight at a time: the same float operations in the same order (the
 * matrix rows, the length by sqrt, 1 / length, the scale, |n.l|, the
 * ambient mix, base * k + 0.5 clamped and truncated), so the same bytes;
 * the faces' stamps made current. A whole object's faces in a row read
 * their normals (nrm: face f0's on) and base colours in order, with no
 * gathers. */
ZV_AVX2_FN static void colour_faces_avx2(FaceColours *fc, const NormalMat *nm, uint32_t f0, uint32_t f1,
                                         const float *nrm)
{
    const Scene *s = fc->s;
    __m256 m[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            m[r][c] = _mm256_set1_ps(nm->m[r][c]);
    const float amb = s->light.ambient;
    const __m256 lx = _mm256_set1_ps(s->light.dir.x), ly = _mm256_set1_ps(s->light.dir.y),
                 lz = _mm256_set1_ps(s->light.dir.z);
    const __m256 vamb = _mm256_set1_ps(amb), voma = _mm256_set1_ps(1.0f - amb);
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f),
                 top = _mm256_set1_ps(255.0f);
    const __m256i vframe = _mm256_set1_epi32((int32_t)fc->frame);
    /* bytes 3 l + c of 24 (16 in lo, 8 in hi) to lane l of channel c */
    const __m128i pick_lo[3] = {
        _mm_setr_epi8(0, 3, 6, 9, 12, 15, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
        _mm_setr_epi8(1, 4, 7, 10, 13, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1),
        _mm_setr_epi8(2, 5, 8, 11, 14, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1) };
    const __m128i pick_hi[3] = {
        _mm_setr_epi8(-1, -1, -1, -1, -1, -1, 2, 5, -1, -1, -1, -1, -1, -1, -1, -1),
        _mm_setr_epi8(-1, -1, -1, -1, -1, 0, 3, 6, -1, -1, -1, -1, -1, -1, -1, -1),
        _mm_setr_epi8(-1, -1, -1, -1, -1, 1, 4, 7, -1, -1, -1, -1, -1, -1, -1, -1) };
    uint32_t f = f0;
    for (; f + 8 <= f1; f += 8) {
        /* faces 0-3 in the low lanes, 4-7 in the high ones, deinterleaved
         * in-lane (as project.c's vertex loop does) */
        const float *p = nrm + 3 * (size_t)(f - f0);
        __m256 va = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p)), _mm_loadu_ps(p + 12), 1);
        __m256 vb = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4)), _mm_loadu_ps(p + 16), 1);
        __m256 vc = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 8)), _mm_loadu_ps(p + 20), 1);
        __m256 t = _mm256_shuffle_ps(vb, vc, _MM_SHUFFLE(2, 1, 3, 2));
        __m256 u = _mm256_shuffle_ps(va, vb, _MM_SHUFFLE(1, 0, 2, 1));
        __m256 nx = _mm256_shuffle_ps(va, t, _MM_SHUFFLE(2, 0, 3, 0));
        __m256 ny = _mm256_shuffle_ps(u, t, _MM_SHUFFLE(3, 1, 2, 0));
        __m256 nz = _mm256_shuffle_ps(u, vc, _MM_SHUFFLE(3, 0, 3, 1));
        __m256 v[3];
        for (int r = 0; r < 3; r++)
            v[r] = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(m[r][0], nx), _mm256_mul_ps(m[r][1], ny)),
                                 _mm256_mul_ps(m[r][2], nz));
        /* v3_norm(): scaled by 1 / length where the length is > 0 */
        __m256 len = _mm256_sqrt_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(v[0], v[0]), _mm256_mul_ps(v[1], v[1])),
                                                  _mm256_mul_ps(v[2], v[2])));
        __m256 pos = _mm256_cmp_ps(len, zero, _CMP_GT_OQ), inv = _mm256_div_ps(one, len);
        for (int r = 0; r < 3; r++)
            v[r] = _mm256_blendv_ps(v[r], _mm256_mul_ps(v[r], inv), pos);
        __m256 d = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(v[0], lx), _mm256_mul_ps(v[1], ly)), _mm256_mul_ps(v[2], lz));
        __m256 k = _mm256_add_ps(vamb, _mm256_mul_ps(voma, _mm256_andnot_ps(_mm256_set1_ps(-0.0f), d)));
        __m256i ch[3];
        __m128i lo = _mm_setzero_si128(), hi = _mm_setzero_si128();
        if (s->face_rgb) {
            lo = _mm_loadu_si128((const __m128i *)(s->face_rgb + 3 * (size_t)f));
            hi = _mm_loadl_epi64((const __m128i *)(s->face_rgb + 3 * (size_t)f + 16));
        }
        for (int c = 0; c < 3; c++) {
            __m256 base = _mm256_set1_ps((float)scene_default_rgb[c]);
            if (s->face_rgb)
                base = _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(
                    _mm_or_si128(_mm_shuffle_epi8(lo, pick_lo[c]), _mm_shuffle_epi8(hi, pick_hi[c]))));
            /* clamp_u8(): v + 0.5, <= 0 gives 0 (max returns its second
             * operand, 0, for NaN, as the scalar's conversion of NaN ends
             * in 0), >= 255 gives 255, else truncated */
            __m256 x = _mm256_add_ps(_mm256_mul_ps(base, k), half);
            ch[c] = _mm256_cvttps_epi32(_mm256_min_ps(_mm256_max_ps(x, zero), top));
        }
        /* three bytes a face, packed: the low bytes of r, g, b lanes */
        int32_t r8[8], g8[8], b8[8];
        _mm256_storeu_si256((__m256i *)r8, ch[0]);
        _mm256_storeu_si256((__m256i *)g8, ch[1]);
        _mm256_storeu_si256((__m256i *)b8, ch[2]);
        uint8_t *out = fc->crgb + 3 * (size_t)f;
        for (int l = 0; l < 8; l++) {
            out[3 * l] = (uint8_t)r8[l];
            out[3 * l + 1] = (uint8_t)g8[l];
            out[3 * l + 2] = (uint8_t)b8[l];
        }
        _mm256_storeu_si256((__m256i *)(fc->stamp + f), vframe);
    }
    for (; f < f1; f++) {
        shade_lambert_face(s, fc->nrm, nm, f, fc->crgb + 3 * (size_t)f);
        fc->stamp[f] = fc->frame;
    }
}


/* Every face of every object with polygons in the frame, object by
 * object, eight at a time: cheaper than face by face over the polygons
 * when most faces have one on screen (a dense mesh at a large size).
 * Returns -1 out of memory. */
ZV_AVX2_FN static void colour_objects_avx2(FaceColours *fc)
{
    const Scene *s = fc->s;
    const float *nrm = fc->nrm;
    for (int o = 0; o < s->nobjs; o++) {
        const Object *ob = &s->objs[o];
        if (!ob->poly_count || !ob->face_count)
            continue;
        uint32_t f0 = (uint32_t)ob->face_base, f1 = f0 + ob->face_count;
        colour_faces_avx2(fc, object_nmat(fc, o), f0, f1, nrm + 3 * (size_t)f0);
    }
}

/* The faces and pixels split over a pool's threads: each task a range
 * of face ids (its own copy of the colours' state: the normal matrices'
 * slots are a cache it fills) or of pixels (reading colours all made
 * current before, so nothing shared is written but its own bytes). A
 * face's colour and a pixel's bytes do not depend on the split. */
typedef struct {
    const FaceColours *fc;
    const int32_t     *ids;
    uint8_t           *rgb, *lit;
    size_t             n;           /* faces or pixels */
    int                ntasks;
} ShadeSplit;

/* Range t of n among ntasks, in multiples of 8. */
static void split_range(size_t n, int t, int ntasks, size_t *a, size_t *b)
{
    *a = n * (size_t)t / (size_t)ntasks / 8 * 8;
    *b = t + 1 == ntasks ? n : n * (size_t)(t + 1) / (size_t)ntasks / 8 * 8;
}

ZV_AVX2_FN static void colour_faces_task(void *arg, int t, int worker)
{
    (void)worker;
    const ShadeSplit *sp = arg;
    FaceColours fc = *sp->fc;
    size_t lo, hi;
    split_range(sp->n, t, sp->ntasks, &lo, &hi);
    const Scene *s = fc.s;
    for (int o = 0; o < s->nobjs; o++) {
        const Object *ob = &s->objs[o];
        size_t f0 = (uint32_t)ob->face_base, f1 = f0 + ob->face_count;
        f0 = f0 > lo ? f0 : lo;
        f1 = f1 < hi ? f1 : hi;
        if (ob->poly_count && f0 < f1)
            colour_faces_avx2(&fc, object_nmat(&fc, o), (uint32_t)f0, (uint32_t)f1, fc.nrm + 3 * f0);
    }
}

ZV_AVX2_FN static size_t shade_pixels_avx2(FaceColours *fc, const int32_t *ids, size_t n, uint8_t *rgb,
                                           uint8_t *lit);

ZV_AVX2_FN static void shade_pixels_task(void *arg, int t, int worker)
{
    (void)worker;
    const ShadeSplit *sp = arg;
    FaceColours *fc = (FaceColours *)sp->fc;    /* current: only read */
    size_t a, b;
    split_range(sp->n, t, sp->ntasks, &a, &b);
    /* the eight-pixel loop stops short of its range's end: no store
     * reaches the next range */
    size_t i = a + shade_pixels_avx2(fc, sp->ids + a, b - a, sp->rgb + 3 * a, sp->lit + a);
    shade_pixels_range(fc, sp->ids, i, b, sp->rgb, sp->lit);
}

#endif

/* Distance (in polygons) the colour pre-pass fetches ahead. */
#define FETCH_AHEAD 16

#ifdef ZV_AVX2
/* Tasks for work of n items: a few per thread (a helper may be late to
 * get a core), none under 64k items; one without helpers. */
static int split_tasks(Pool *pool, size_t n)
{
    if (pool_helpers(pool) == 0)
        return 1;
    int t = 4 * (pool_helpers(pool) + 1);
    size_t most = n / 65536;
    return most < (size_t)t ? (most ? (int)most : 1) : t;
}
#endif

/* Every drawn polygon's face colour, before the pixels: the polygons come
 * in face order, so the per-face arrays are read in order (and fetched
 * ahead), where the pixels would visit them scattered, one cache miss
 * each. Only faces of sp's polygons can be in the picture, so the pixel
 * loop then finds every colour current. */
static void colour_polys_in(FaceColours *fc, const ScreenPolys *sp, uint32_t lo, uint32_t hi)
{
    const Scene *s = fc->s;
    int32_t last = -1;
    for (uint32_t i = 0; i < sp->npolys; i++) {
        if (i + FETCH_AHEAD < sp->npolys) {
            uint32_t f = (uint32_t)sp->polys[i + FETCH_AHEAD].face;
            if (f >= lo && f < hi) {
                __builtin_prefetch(&fc->stamp[f]);
                if (s->face_normal)
                    __builtin_prefetch(&s->face_normal[3 * (size_t)f]);
                if (s->face_rgb)
                    __builtin_prefetch(&s->face_rgb[3 * (size_t)f]);
                __builtin_prefetch(&fc->crgb[3 * (size_t)f], 1);
            }
        }
        int32_t f = sp->polys[i].face;
        if (f == last || f < 0 || (uint32_t)f < lo || (uint32_t)f >= hi)
            continue;
        last = f;
        face_colour(fc, f);
    }
}

static void colour_polys(FaceColours *fc, const ScreenPolys *sp)
{
    colour_polys_in(fc, sp, 0, fc->s->nfaces);
}

/* colour_polys() over a pool: each task every polygon but only the
 * faces of its range of ids, so no face is two tasks' (the polygons of
 * one face need not be next to each other). */
typedef struct {
    const FaceColours *fc;
    const ScreenPolys *sp;
    int                ntasks;
} PolySplit;

static void colour_polys_task(void *arg, int t, int worker)
{
    (void)worker;
    const PolySplit *ps = arg;
    FaceColours fc = *ps->fc;
    uint64_t n = fc.s->nfaces;
    colour_polys_in(&fc, ps->sp, (uint32_t)(n * (uint32_t)t / (uint32_t)ps->ntasks),
                    (uint32_t)(n * (uint32_t)(t + 1) / (uint32_t)ps->ntasks));
}

/* Pixels [i0, i1) one at a time. */
void shade_pixels_range(FaceColours *fc, const int32_t *ids, size_t i0, size_t i1, uint8_t *rgb, uint8_t *lit)
{
    uint32_t nfaces = fc->s->nfaces;
    for (size_t i = i0; i < i1; i++) {
        int32_t id = ids[i];
        uint8_t *px = rgb + 3 * i;
        if (id < 0 || (uint32_t)id >= nfaces) {
            if (fc->mode == SHADE_ID && is_prim(fc->s, id)) {
                shade_id_colour(id, px);    /* points and lines: their id's colour too */
                lit[i] = 1;
                continue;
            }
            px[0] = px[1] = px[2] = 0;
            lit[i] = 0;
            continue;
        }
        const uint8_t *c = face_colour(fc, id);
        px[0] = c[0];
        px[1] = c[1];
        px[2] = c[2];
        lit[i] = 1;
    }
}

#ifdef ZV_AVX2
/* Eight pixels a step: eight of the background stored black at once;
 * unless every colour is known current, their stamps gathered and
 * checked at once (a face seen for the first time this frame sends the
 * eight through shade_pixels, which makes its colour); their colours gathered as 4-byte
 * words at 3 id (the cache's spare byte keeps the last in bounds), packed
 * to 24 bytes, and the lit bytes from the same mask. Stops short of the
 * end (the second 16-byte store ends 4 bytes past the eighth pixel, in
 * the tenth); returns where the caller's plain loop takes over. */
ZV_AVX2_FN static size_t shade_pixels_avx2(FaceColours *fc, const int32_t *ids, size_t n, uint8_t *rgb, uint8_t *lit)
{
    const __m256i bias = _mm256_set1_epi32(INT32_MIN);
    const __m256i nf = _mm256_xor_si256(_mm256_set1_epi32((int32_t)fc->s->nfaces), bias);
    const __m256i vframe = _mm256_set1_epi32((int32_t)fc->frame), low24 = _mm256_set1_epi32(0xffffff);
    const __m256i pack = _mm256_setr_epi8(0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1,
                                          0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1);
    const __m256i one8 = _mm256_set1_epi8(1);
    size_t i = 0;
    for (; i + 10 <= n; i += 8) {
        __m256i id = _mm256_loadu_si256((const __m256i *)(ids + i));
        /* 0 <= id < nfaces, as unsigned */
        __m256i valid = _mm256_cmpgt_epi32(nf, _mm256_xor_si256(id, bias));
        uint8_t *px = rgb + 3 * i;
        if (_mm256_testz_si256(valid, valid)) {
            /* background (most of a big picture): black, unlit */
            _mm_storeu_si128((__m128i *)px, _mm_setzero_si128());
            _mm_storeu_si128((__m128i *)(px + 12), _mm_setzero_si128());
            _mm_storel_epi64((__m128i *)(lit + i), _mm_setzero_si128());
            continue;
        }
        if (!fc->current) {
            __m256i st = _mm256_mask_i32gather_epi32(vframe, (const int *)fc->stamp, id, valid, 4);
            if (!_mm256_testc_si256(_mm256_cmpeq_epi32(st, vframe), _mm256_set1_epi32(-1))) {
                shade_pixels_range(fc, ids, i, i + 8, rgb, lit);
                continue;
            }
        }
        __m256i id3 = _mm256_add_epi32(_mm256_add_epi32(id, id), id);
        __m256i col = _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), (const int *)fc->crgb, id3, valid, 1);
        col = _mm256_shuffle_epi8(_mm256_and_si256(col, low24), pack);
        _mm_storeu_si128((__m128i *)px, _mm256_castsi256_si128(col));
        _mm_storeu_si128((__m128i *)(px + 12), _mm256_extracti128_si256(col, 1));
        /* the mask's lanes as bytes: two packs, the high half's four next to the low's */
        __m256i b = _mm256_packs_epi16(_mm256_packs_epi32(valid, valid), _mm256_setzero_si256());
        b = _mm256_permutevar8x32_epi32(b, _mm256_setr_epi32(0, 4, 0, 4, 0, 4, 0, 4));
        _mm_storel_epi64((__m128i *)(lit + i), _mm_and_si128(_mm256_castsi256_si128(b), _mm256_castsi256_si128(one8)));
    }
    return i;
}
#endif

int shade_frame(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, const ShadeSettings *set,
                ShadeCache *cache, Image *out)
{
    if (image_resize(out, fb->w, fb->h) != 0)
        return -1;
    if (shade_mode(s, sp, fb, set, cache, out))
        return -1;
    shade_prims(s, fb, set, out);
    if (set->highlight >= 0 && set->highlight < s->nobjs)
        highlight_object(s, fb, set->highlight, out);
    /* a big frame's outlines compare many pairs of faces: their normals
     * computed once (dense_normals), not twice a pair (issue 21) */
    cache->edges.nrm = s->face_normal;
    if (set->edges && sp && !s->face_normal && (uint64_t)sp->npolys * 8 >= s->nfaces &&
        !(cache->edges.nrm = dense_normals(cache, s, set->simd)))
        return -1;
    if (set->edges && sp && shade_edges(s, sp, fb, set->crease, &cache->edges, out))
        return -1;
    return 0;
}

static int shade_mode(const Scene *s, const ScreenPolys *sp, const FrameBufs *fb, const ShadeSettings *set,
                      ShadeCache *cache, Image *out)
{
    uint32_t nfaces = s->nfaces;
    ShadeMode mode = set->mode;
    if (mode == SHADE_DEPTH) {
        shade_depth(fb, nfaces + s->nprims, out);
        return 0;
    }
    SurfFrame sf;
    int varying = 0;
    if (mode == SHADE_LAMBERT || mode == SHADE_SMOOTH) {
        int r = texel_frame_begin(&sf, s, sp, set, &cache->surf);
        if (r < 0)
            return -1;
        varying = r == 0;
    }
    if (mode == SHADE_SMOOTH) {
        if (smooth_prepare(&cache->smooth, s, set->crease))
            return -1;
        return shade_smooth(s, sp, fb, &cache->smooth, scene_default_rgb, varying ? &sf : NULL, out);
    }
    size_t n = (size_t)fb->w * (size_t)fb->h, i = 0;
    int avx2 = simd_use(set->simd) >= SIMD_AVX2;
    /* a frame whose polygons are an eighth of the faces or more holds
     * about as much per face as the per-face arrays and normals (80
     * bytes a polygon): they are kept (issue 21); every face is coloured
     * eight at a time when the polygons are a quarter of the faces and
     * no more than the pixels (below) */
    int big = sp && (uint64_t)sp->npolys * 8 >= nfaces;
    int dense = avx2 && mode == SHADE_LAMBERT && sp && sp->npolys <= n && (uint64_t)sp->npolys * 4 >= nfaces;
    int slots = !big && shade_slots_pay(nfaces, n);
    if (!slots && cache_grow(cache, nfaces) != 0)
        return -1;
    /* the colour tables hold every face an id may name: face_colour
     * reads stamp[id] and rgb[3 id] for any id below nfaces */
    ZV_ASSERT(slots || (cache->cap >= nfaces && cache->stamp && cache->rgb));
    cache_next_frame(cache);

    FaceColours fc = { s, mode, cache->frame, cache->stamp, cache->rgb, 0, camera_view(&s->cam), { { 0 } }, NULL };
    for (int k = 0; k < NMAT_SLOTS; k++)
        fc.nmat[k].obj = -1;
    fc.nrm = s->face_normal;
    if (big && mode == SHADE_LAMBERT && !(fc.nrm = dense_normals(cache, s, set->simd)))
        return -1;
    if (slots) {
        if (shade_pixels_slots(&fc, cache, fb->ids, n, out->rgb, out->lit))
            return -1;
        if (varying)
            shade_surfaces_flat(&sf, fb, out);
        return 0;
    }
    /* Colour the faces before the pixels, so that the pixel loop finds
     * every colour current and checks no stamp: the polygons' faces when
     * they are no more than the pixels (measured: the bunny at 1920x1080
     * shades in half the time this way). A huge mesh in a small picture
     * (polygons under a sixteenth of the faces, or more than the pixels)
     * skips the cache: each pixel straight from its face (the dragon at
     * 160x96: 0.65 -> 0.17 ms). */
#ifndef ZV_AVX2
    (void)dense;            /* no eight-lane loops in this build */
#endif
    if (sp && sp->npolys <= n && !(mode == SHADE_LAMBERT && (uint64_t)sp->npolys * 16 < nfaces)) {
        /* a frame's polygons are a subset of the faces' (split faces
         * repeat a face): when they are a quarter of them or more, every
         * face of the objects in view, in order, eight at a time, costs
         * less than theirs one by one (measured: the dragon at 1920x1080
         * with --cull, a third of its faces drawn, shades in 6 ms instead
         * of 9) */
#ifdef ZV_AVX2
        if (dense) {
            ShadeSplit sf = { &fc, NULL, NULL, NULL, nfaces, split_tasks(set->pool, nfaces) };
            if (sf.ntasks > 1)
                pool_run(set->pool, sf.ntasks, colour_faces_task, &sf);
            else
                colour_objects_avx2(&fc);
        } else
#endif
        {
            /* each task reads every polygon: worth it from a few
             * thousand up, with one task a thread */
            PolySplit ps = { &fc, sp, pool_helpers(set->pool) + 1 };
            if (ps.ntasks > 1 && sp->npolys >= 16384)
                pool_run(set->pool, ps.ntasks, colour_polys_task, &ps);
            else
                colour_polys(&fc, sp);
        }
        fc.current = 1;
    } else if (sp && mode == SHADE_LAMBERT) {
        shade_pixels_direct(&fc, fb->ids, n, out->rgb, out->lit);
        i = n;
    }
#ifdef ZV_AVX2
    /* the eight-pixel loop leaves ids past the faces black: not for id
     * colours of points and lines */
    if (i < n && avx2 && !(mode == SHADE_ID && s->nprims)) {
        ShadeSplit sx = { &fc, fb->ids, out->rgb, out->lit, n, fc.current ? split_tasks(set->pool, n) : 1 };
        if (sx.ntasks > 1) {
            pool_run(set->pool, sx.ntasks, shade_pixels_task, &sx);
            i = n;
        } else {
            i = shade_pixels_avx2(&fc, fb->ids, n, out->rgb, out->lit);
        }
    }
#endif
    shade_pixels_range(&fc, fb->ids, i, n, out->rgb, out->lit);
    /* textured and vertex-coloured faces: their samples again, each its
     * own colour under the face's light */
    if (varying)
        shade_surfaces_flat(&sf, fb, out);
    return 0;
}
