/* pipeline.c: one frame through the stages, timed stage by stage. */

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "app.h"
#include "simd.h"
#include "sysmem.h"

/* The hidden-surface algorithms' own tables per polygon (bucket keys,
 * sort order, records): a few words each, rounded up. */
#define ALGO_BYTES_PER_POLY 16
/* Pixels assumed when --size is not given: the benchmark's default,
 * the biggest of the defaults. */
#define DEFAULT_PIXELS (1920u * 1080u)
/* Bytes per pixel: face ids and depths, RGB and the lit mask. */
#define BYTES_PER_PIXEL (4 + 4 + 3 + 1)

/* 398131200 -> "398,131,200". */
static void with_commas(uint64_t v, char *buf, size_t len)
{
    char tmp[32];
    int n = snprintf(tmp, sizeof tmp, "%llu", (unsigned long long)v);
    size_t o = 0;
    for (int i = 0; i < n && o + 2 < len; i++) {
        if (i && (n - i) % 3 == 0)
            buf[o++] = ',';
        buf[o++] = tmp[i];
    }
    buf[o] = 0;
}

/* An estimate of the memory of the scene (--grid copies included) and of
 * one frame of polys polygons with `corners` corners; *scene_out gets
 * the scene's part. */
static uint64_t scene_frame_bytes(const Scene *s, uint64_t copies, uint64_t polys, uint64_t corners,
                                  uint64_t pixels, uint64_t *scene_out)
{
    uint64_t verts = 0;
    for (int i = 0; i < s->nmeshes; i++)
        verts += s->meshes[i].nverts;
    /* what the scene holds: the compact form (scene.h) leaves out the
     * arrays it derives */
    uint64_t face_bytes = (s->face_normal ? 3 * sizeof(float) : 0) + (s->face_rgb ? 3 + 1 : 0) +
                          (s->face_obj || copies > 1 ? sizeof(uint16_t) : 0);
    uint64_t scene = verts * 3 * sizeof(float) +
                     (uint64_t)s->npolys * ((s->poly_start ? 1 : 0) + (s->poly_lface ? 1 : 0)) * sizeof(uint32_t) +
                     (uint64_t)scene_ncorners(s) * sizeof(uint32_t) +          /* corners */
                     (uint64_t)s->nfaces * copies * face_bytes +
                     (uint64_t)s->nobjs * copies * sizeof(Object);
    uint64_t frame = polys * (sizeof(ScreenPoly) + sizeof(int32_t) + ALGO_BYTES_PER_POLY) +
                     corners * sizeof(ScreenVert) * 65 / 64 +
                     (uint64_t)s->nfaces * copies * 7 +                         /* shade cache */
                     pixels * BYTES_PER_PIXEL;
    if (scene_out)
        *scene_out = scene;
    return scene + frame;
}

static void bytes_text(double bytes, char *buf, size_t len)
{
    if (bytes >= 1e9)
        snprintf(buf, len, "%.1f GB", bytes / 1e9);
    else
        snprintf(buf, len, "%.0f MB", bytes / 1e6);
}

int app_check_size(const Options *o, const Scene *s, char *err, size_t errlen)
{
    uint64_t copies = o->grid > 1 ? (uint64_t)o->grid * o->grid * o->grid : 1;
    /* grid copies project their source's polygons again; points and
     * segments are drawn as polygons too (a square, a quad) */
    uint64_t polys = 0, corners = 0, prims = 0;
    for (int k = 0; k < s->nobjs; k++) {
        const Object *ob = &s->objs[k];
        polys += ob->poly_count;
        corners += scene_poly_c0(s, ob->poly_first + ob->poly_count) - scene_poly_c0(s, ob->poly_first);
        prims += (uint64_t)ob->point_count + ob->seg_count;
    }
    polys = (polys + prims) * copies;
    corners = (corners + 4 * prims) * copies;
    /* the pixels' buffers are judged by oneshot_check_output: against the
     * memory, only the polygons' part counts here */
    uint64_t pixels = !o->max_polys ? 0 : o->w > 0 ? (uint64_t)o->w * o->h : DEFAULT_PIXELS;
    uint64_t have = 0, avail = 0, scene = 0, need = 0;
    uint64_t bytes = scene_frame_bytes(s, copies, polys, corners, pixels, &scene);
    /* No fixed count: without --max-polys the limit is what memory holds.
     * The scene of one copy is built already (it is in no longer
     * available memory), so what must still fit is the rest: the copies'
     * tables and one frame. */
    if (o->max_polys) {
        if (polys <= o->max_polys)
            return 0;
    } else {
        /* the frame's part counts every polygon projected and kept: culling
         * and clipping leave a fraction of them (the 5.2M dragon at 80x24:
         * 541 MB estimated, 72 MB measured), and a model that fits must
         * not be refused, so a quarter of it is what must fit */
        scene_frame_bytes(s, 1, 0, 0, 0, &have);
        avail = sysmem_available();
        need = scene + (bytes - scene) / 4;
        if (need <= have || need - have <= avail)
            return 0;
    }
    char np[32], lim[32], mem[32], av[112];
    with_commas(polys, np, sizeof np);
    bytes_text((double)bytes, mem, sizeof mem);
    if (o->max_polys) {
        with_commas(o->max_polys, lim, sizeof lim);
        snprintf(av, sizeof av, "limit %s; --max-polys raises it", lim);
    } else {
        char more[32];
        bytes_text((double)(need - have), more, sizeof more);
        bytes_text((double)avail, lim, sizeof lim);
        snprintf(av, sizeof av, "%s more than it has; %s available", more, lim);
    }
    char files[320];
    scene_files_text(s->meshes, s->nmeshes, files, sizeof files);
    snprintf(err, errlen,
             "%s: the scene would have %s polygons, points and segments and need about %s for itself "
             "and one frame (%s)",
             files, np, mem, av);
    return -1;
}

/* Bytes a text cell costs beyond its pixels: the cell and its share of
 * the printed text (measured: about 14). */
#define BYTES_PER_CELL (sizeof(Cell) + 6)

uint64_t pipeline_frame_bytes(int w, int h, int samples, uint64_t cells)
{
    int k = pipeline_samples_side(samples);
    if ((long)w * k > SCREEN_MAX || (long)h * k > SCREEN_MAX)
        k = 1;                  /* as pipeline_render drops it */
    uint64_t px = (uint64_t)w * h, ss = px * k * k;
    /* the buffers and shaded image at the sampled size, the averaged
     * image (RGBA) when supersampled, and the cells */
    return ss * BYTES_PER_PIXEL + (k > 1 ? px * 4 : 0) + cells * BYTES_PER_CELL;
}

int pipeline_check_frame(int w, int h, int samples, uint64_t cells, const char *what, char *err,
                         size_t errlen)
{
    if (w > SCREEN_MAX || h > SCREEN_MAX) {
        snprintf(err, errlen, "%s: a picture of %dx%d pixels (at most %d per side)", what, w, h, SCREEN_MAX);
        return -1;
    }
    uint64_t need = pipeline_frame_bytes(w, h, samples, cells), avail = sysmem_available();
    if (need <= avail)
        return 0;
    char n[32], a[32];
    sysmem_format(need, n, sizeof n);
    sysmem_format(avail, a, sizeof a);
    snprintf(err, errlen, "%s: a picture of %dx%d pixels needs about %s; %s available", what, w, h, n, a);
    return -1;
}

int default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 64 ? 64 : (int)n;
}

int pipeline_init(Pipeline *p, Scene *s, const HsrAlgo *algo, int threads)
{
    memset(p, 0, sizeof *p);
    p->scene = s;
    p->threads = threads > 0 ? threads : default_threads();
    p->sp.threads = p->threads;     /* --threads 1: no helper thread anywhere */
    p->shade = SHADE_LAMBERT;
    p->samples = 1;
    p->crease = SHADE_CREASE_DEFAULT;
    p->highlight = -1;
    p->point_size = 1;
    p->line_width = 1;
    p->contrast = CONTRAST_DEFAULT;
    return pipeline_set_algo(p, algo);
}

void pipeline_apply_options(Pipeline *p, const Options *o)
{
    p->shade = (ShadeMode)o->shade;
    p->crease = o->crease;
    p->edges = o->edges;
    p->order = (PolyOrder)o->order;
    if (o->samples > 0)
        p->samples = o->samples;
    p->point_size = o->point_size > 0 ? o->point_size : 1;
    p->line_width = o->line_width > 0 ? o->line_width : 1;
    p->wireframe = o->wireframe;
    p->contrast = o->contrast;
    p->no_textures = o->no_textures;
    p->problems = o->problems;
    p->parts = o->parts;
    p->overhang = o->overhang;
    p->overhang_deg = o->overhang_deg;
    p->thickness = o->thickness;
    p->thick_limit = o->min_thickness;
    p->marks = o->marks;
    memcpy(p->planes, o->section, sizeof p->planes);
    p->nplanes = o->nsections;
}

void pipeline_set_backdrop(Pipeline *p, const Backdrop *b)
{
    p->bd = *b;
    p->has_bd = 1;
}

Backdrop pipeline_text_backdrop(const Options *o, const uint8_t *asked)
{
    Backdrop b = { { 0, 0, 0 }, 0, BD_ASSUMED };
    if (o->bg) {
        memcpy(b.rgb, o->bg_rgb, 3);
        b.paint = 1;
        b.source = BD_GIVEN;
    } else if (asked) {
        memcpy(b.rgb, asked, 3);
        b.source = BD_ASKED;
    } else if (bg_from_env(b.rgb) == 0) {
        b.source = BD_ENV;
    }
    return b;
}

int pipeline_set_algo(Pipeline *p, const HsrAlgo *algo)
{
    if (p->algo)
        hsr_runner_free(&p->run);
    p->algo = algo;
    return hsr_runner_init(&p->run, algo, p->threads);
}

int pipeline_scene_changing(Pipeline *p)
{
    /* a fresh runner: the old one's shared state (trees, builder thread)
     * is joined and freed with it */
    shade_cache_free(&p->shade_cache);
    p->cut.key = NULL;          /* the cut is made again */
    return pipeline_set_algo(p, p->algo);
}

void pipeline_free(Pipeline *p)
{
    if (p->algo)
        hsr_runner_free(&p->run);
    screen_free(&p->sp);
    reorder_free(&p->reorder);
    fbuf_free(&p->fb);
    image_free(&p->img);
    image_free(&p->img_ss);
    shade_cache_free(&p->shade_cache);
    cells_free(&p->cells);
    prims_free(&p->prims);
    contrast_free(&p->rule);
    mark_colours_free(&p->markcol);
    print_tint_free(&p->tint);
    section_cut_free(&p->cut);
    memset(p, 0, sizeof *p);
}

int pipeline_samples_side(int samples)
{
    int k = 1;
    while ((k + 1) * (k + 1) <= samples)
        k++;
    return k;
}

/* The scene as shading reads it: itself, or, when what a check found
 * colours faces (--problems, --parts), a view of it whose faces' colours
 * and surfaces are those (the geometry and ids are the scene's own
 * arrays). NULL out of memory. */
static const Scene *shade_scene(Pipeline *p)
{
    int mode = (p->problems ? 1 : 0) | (p->parts ? 2 : 0);
    char err[160];
    int tinted = app_print_tint(p, err, sizeof err);
    if (tinted < 0)
        return NULL;
    const FaceTint *ft = tinted ? &p->tint.ft : NULL;
    int r = mode || ft ? shade_mark_colours(&p->markcol, p->scene, mode, ft) : 0;
    if (r <= 0)
        return r < 0 ? NULL : p->scene;
    p->shade_view = *p->scene;
    p->shade_view.face_rgb = p->markcol.rgb;
    p->shade_view.face_surf = p->markcol.surf;
    return &p->shade_view;
}

int pipeline_render(Pipeline *p, int w, int h, float pixel_aspect, int cull, int shade_too)
{
    if (!p->run.algo && hsr_runner_init(&p->run, p->algo, p->threads))
        return -1;      /* pipeline_scene_changing found no memory for it */
    int k = pipeline_samples_side(p->samples);
    if ((long)w * k > SCREEN_MAX || (long)h * k > SCREEN_MAX)
        k = 1;          /* a huge image needs no supersampling */
    p->vp.w = w * k;
    p->vp.h = h * k;
    p->vp.pixel_aspect = pixel_aspect;
    p->vp.cull = cull;
    /* one SIMD level for the whole frame (ZV_SIMD read here), passed to
     * every stage */
    int simd = simd_level();
    p->sp.simd = simd;
    double t0 = now_ms();
    p->sp.no_map = !p->algo->uses_map;
    char err[160];
    /* the wireframe's ids before the caps', which follow every line's */
    if (p->wireframe && !p->scene->wire_built && scene_wire_build(p->scene, err, sizeof err))
        return -1;
    p->sp.cut = NULL;
    if (p->nplanes && !p->cut_off) {
        if (section_cut_update(&p->cut, p->scene, p->planes, p->nplanes, err, sizeof err))
            return -1;
        p->sp.cut = &p->cut;
    }
    if (screen_project(&p->sp, p->scene, &p->vp))
        return -1;
    if (p->order != ORDER_FILE && screen_reorder(&p->sp, p->order, 1, &p->reorder))
        return -1;
    /* points and lines after the faces (and after --order's reordering,
     * which they need not take part in) */
    int ps = p->point_size > 0 ? p->point_size : 1, lw = p->line_width > 0 ? p->line_width : 1;
    PrimStyle style = { ps * k, lw * k, p->wireframe, 0, k, p->problems && p->scene->marks.set };
    if (screen_prims(&p->sp, p->scene, &style, &p->prims))
        return -1;
    double t1 = now_ms();
    HsrInput in = { .sp = &p->sp, .scene = p->scene, .vp = &p->vp, .simd = simd };
    if (hsr_run(&p->run, &in, &p->fb, &p->st))
        return -1;
    double t2 = now_ms();
    p->project_ms = t1 - t0;
    p->hsr_ms = t2 - t1;
    p->shade_ms = 0;
    if (shade_too) {
        ShadeSettings set = { p->shade, p->crease, p->highlight, p->edges, p->wireframe, simd, p->no_textures,
                              p->run.pool };
        const Scene *ss = shade_scene(p);
        if (!ss)
            return -1;
        Image *to = k == 1 ? &p->img : &p->img_ss;
        if (shade_frame(ss, &p->sp, &p->fb, &set, &p->shade_cache, to))
            return -1;
        shade_caps(p->scene, p->sp.cut, &p->fb, to);
        if (k > 1 && image_downsample(&p->img_ss, k, &p->img))
            return -1;
        /* on the final pixels, so that what is shown keeps the minimum */
        if (p->has_bd && contrast_apply(&p->rule, &p->bd, p->contrast, &p->img))
            return -1;
        /* the problem in focus over it all, in its own colour */
        app_focus_draw(p);
        app_measure_draw(p);
        p->shade_ms = now_ms() - t2;
    }
    return 0;
}

/* ==== why a frame is empty ==== */

/* The screen box of every object's box (its 8 corners, through the
 * projection the frame used); which of them are in front of the eye. */
typedef struct {
    double x0, x1, y0, y1;      /* screen pixels of the corners in front */
    int    in_front, behind;    /* corners of each kind */
    int    objects;             /* objects with something to draw */
} SceneExtent;

static void scene_extent(const Pipeline *p, SceneExtent *e)
{
    const Scene *s = p->scene;
    const ScreenPolys *sp = &p->sp;
    memset(e, 0, sizeof *e);
    e->x0 = e->y0 = INFINITY;
    e->x1 = e->y1 = -INFINITY;
    Mat4 view = camera_view(&s->cam);
    for (int i = 0; i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        if (!o->poly_count && !o->point_count && !o->seg_count)
            continue;
        e->objects++;
        Mat4 mv = m4_mul(view, object_matrix(o));
        for (int k = 0; k < 8; k++) {
            Vec3 c = v3(o->centre.x + (k & 1 ? o->half.x : -o->half.x), o->centre.y + (k & 2 ? o->half.y : -o->half.y),
                        o->centre.z + (k & 4 ? o->half.z : -o->half.z));
            Vec3 q = m4_point(&mv, c);
            double x, y;
            if (sp->persp) {
                double ze = (double)sp->eye_z - q.z;
                if (!(ze >= sp->near_z)) {
                    e->behind++;
                    continue;
                }
                x = sp->w * 0.5 + sp->focal_x * q.x / ze;
                y = sp->h * 0.5 - sp->focal_y * q.y / ze;
            } else {
                x = sp->w * 0.5 + (double)sp->focal_x * q.x;
                y = sp->h * 0.5 - (double)sp->focal_y * q.y;
            }
            e->in_front++;
            e->x0 = fmin(e->x0, x);
            e->x1 = fmax(e->x1, x);
            e->y0 = fmin(e->y0, y);
            e->y1 = fmax(e->y1, y);
        }
    }
}

/* Does any polygon of the scene have an area (a nonzero Newell normal,
 * in the mesh's coordinates)? Asked only of an empty frame. */
static int any_face_area(const Scene *s)
{
    for (int i = 0; i < s->nobjs; i++) {
        const Object *o = &s->objs[i];
        const float *pos = o->mesh->pos;
        for (uint32_t q = o->poly_first; q < o->poly_first + o->poly_count; q++) {
            double n[3] = { 0, 0, 0 };
            uint32_t c0 = scene_poly_c0(s, q), c1 = scene_poly_c0(s, q + 1);
            for (uint32_t c = c0; c < c1; c++) {
                const float *a = &pos[3 * (size_t)s->poly_corner[c]];
                const float *b = &pos[3 * (size_t)s->poly_corner[c + 1 < c1 ? c + 1 : c0]];
                n[0] += ((double)a[1] - b[1]) * ((double)a[2] + b[2]);
                n[1] += ((double)a[2] - b[2]) * ((double)a[0] + b[0]);
                n[2] += ((double)a[0] - b[0]) * ((double)a[1] + b[1]);
            }
            if (n[0] != 0 || n[1] != 0 || n[2] != 0)
                return 1;
        }
    }
    return 0;
}

/* Were objects scaled down from how they were laid out (--scale)? */
static int scaled_down(const Scene *s)
{
    for (int i = 0; i < s->nobjs; i++)
        if (s->objs[i].scale < s->objs[i].home_scale)
            return 1;
    return 0;
}

const char *frame_empty_reason(const Pipeline *p)
{
    const FrameBufs *fb = &p->fb;
    size_t n = (size_t)fb->w * fb->h;
    for (size_t i = 0; i < n; i++)
        if (fb->ids[i] >= 0)
            return NULL;
    const Scene *s = p->scene;
    if (!s || (s->nfaces == 0 && s->nprims == 0))
        return "the scene has nothing to draw";
    SceneExtent e;
    scene_extent(p, &e);
    const ScreenPolys *sp = &p->sp;
    if (e.objects && !e.in_front)
        return "everything is behind the eye (--persp with a --zoom that moves the eye past the model): "
               "try --zoom 1, or fit with f, reset with r";
    if (e.objects && (e.x1 <= 0 || e.x0 >= sp->w || e.y1 <= 0 || e.y0 >= sp->h))
        return "everything is outside the picture (--pan, --move, --scale or --zoom): try --pan 0,0, or fit "
               "with f, reset with r";
    if (s->nprims == 0 && !any_face_area(s))
        return "every face has zero area (its corners lie on a line or a point): nothing to fill";
    /* a flat model turned edge-on: its box's outline has no width or no
     * height (less than a sample across); not from a sample's size */
    if (e.objects && (e.x1 - e.x0 < 1 || e.y1 - e.y0 < 1) && (e.x1 - e.x0 >= 1 || e.y1 - e.y0 >= 1) &&
        s->nprims == 0)
        return "the model is edge-on: try --view iso or turn with the arrow keys";
    if (sp->cull && sp->culled_back > 0 && sp->culled_back + sp->culled_empty >= sp->in_polys)
        return "every face was culled as a back face (--cull): try without --cull (b in the viewer), "
               "or --flip if the faces point inwards";
    if (scaled_down(s))
        return "the model, scaled down (--scale), covers no sample at this size: try a larger --scale, "
               "a bigger --size or --zoom (+ in the viewer)";
    return "the model covers no sample at this size: try a bigger --size or --zoom (+ in the viewer)";
}
