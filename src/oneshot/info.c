/* info.c: --info: what was loaded, and (with --algo) what a render did. */

#include <float.h>
#include <math.h>
#include <stdio.h>

#include "oneshot.h"
#include "pixels.h"
#include "printq.h"
#include "safetext.h"
#include "simd.h"

/* The objects of a model of several (an assembly's parts, OBJ's o and
 * g): each one's name, faces and the colour of its first face when that
 * colour is its own (a material, a CAD part's colour), the first
 * INFO_OBJECTS of them. */
#define INFO_OBJECTS 16
static void print_objects(Out *out, const Scene *s, const Mesh *m)
{
    if (m->nobjs < 2)
        return;
    uint32_t shown = 0;
    for (int k = 0; k < s->nobjs; k++) {
        const Object *ob = &s->objs[k];
        if (ob->mesh != m)
            continue;
        if (shown++ == INFO_OBJECTS)
            break;
        uint32_t f = (uint32_t)ob->face_base;
        int own = ob->face_count && s->face_rgb && f < s->nfaces && (!s->face_own || s->face_own[f]);
        if (own) {
            const uint8_t *c = s->face_rgb + 3 * (size_t)f;
            out_line(out, "            %s: %u faces, colour #%02x%02x%02x", ob->name, ob->face_count, c[0], c[1],
                     c[2]);
        } else {
            out_line(out, "            %s: %u faces", ob->name, ob->face_count);
        }
    }
    if (m->nobjs > INFO_OBJECTS)
        out_line(out, "            ... and %u more", m->nobjs - INFO_OBJECTS);
}

/* pos_exp: the scene scaled the positions by 2^-pos_exp (scene.h); the
 * bounds are given in the file's units. */
static void print_mesh(Out *out, const Scene *s, const Mesh *m, int pos_exp)
{
    float lo[3] = { FLT_MAX, FLT_MAX, FLT_MAX }, hi[3] = { -FLT_MAX, -FLT_MAX, -FLT_MAX };
    for (uint32_t v = 0; v < m->nverts; v++)
        for (int k = 0; k < 3; k++) {
            float c = m->pos[3 * v + k];
            if (c < lo[k]) lo[k] = c;
            if (c > hi[k]) hi[k] = c;
        }
    if (!m->nverts)
        lo[0] = lo[1] = lo[2] = hi[0] = hi[1] = hi[2] = 0;
    double mb = m->info.bytes / 1e6;
    out_line(out, "file:       %s", m->path ? m->path : "?");
    out_line(out, "format:     %s", m->info.format[0] ? m->info.format : "?");
    if (m->info.corners_read)
        out_line(out, "vertices:   %u (merged from %llu corners)", m->nverts,
               (unsigned long long)m->info.corners_read);
    else
        out_line(out, "vertices:   %u", m->nverts);
    out_line(out, "faces:      %u", m->nfaces);
    out_line(out, "triangles:  %u", m->info.triangles);
    out_line(out, "objects:    %u", m->nobjs);
    print_objects(out, s, m);
    double u = ldexp(1, pos_exp);
    out_line(out, "bounds:     %g %g %g .. %g %g %g", lo[0] * u, lo[1] * u, lo[2] * u, hi[0] * u, hi[1] * u,
               hi[2] * u);
    if (m->info.unit[0])
        out_line(out, "unit:       %s (%s, as the file states)", m->info.unit, printq_unit_words(m->info.unit));
    out_line(out, "materials:  %u", m->nmats);
    out_line(out, "texcoords:  %u   normals: %u   vertex colours: %s", m->info.texcoords,
           m->info.normals, m->rgb ? "yes" : "no");
    if (m->ntex) {
        out_line(out, "textures:   %u, %.1f MB of texels", m->ntex, mesh_texture_bytes(m) / 1e6);
        for (uint32_t k = 0; k < m->ntex; k++) {
            const MeshTexture *t = &m->tex[k];
            if (t->state == MTEX_FAILED)
                out_line(out, "            %s: could not be read", t->name);
            else if (t->state == MTEX_PENDING)
                out_line(out, "            %s: %dx%d, not decoded yet", t->name, t->src_w, t->src_h);
            else if (t->halved)
                out_line(out, "            %s: %dx%d, kept at %dx%d, %.1f MB", t->name, t->src_w, t->src_h,
                           t->img.w, t->img.h, texture_bytes(&t->img) / 1e6);
            else
                out_line(out, "            %s: %dx%d, %.1f MB", t->name, t->img.w, t->img.h,
                           texture_bytes(&t->img) / 1e6);
        }
    }
    if (m->npoints || m->nlines) {
        uint32_t segs = m->nlines ? m->line_start[m->nlines] - m->nlines : 0;
        out_line(out, "points:     %u%s", m->npoints, m->npoints && !m->point ? " (every vertex)" : "");
        out_line(out, "lines:      %u (%u segments)", m->nlines, segs);
    }
    if (m->info.skipped)
        out_line(out, "skipped:    %u statements (first: %s)", m->info.skipped, m->info.first_skipped);
    if (m->info.unknown)
        out_line(out, "unknown:    %u statements skipped (first: '%s')", m->info.unknown,
               m->info.first_unknown);
    else
        out_line(out, "unknown:    0");
    out_line(out, "load:       %.1f ms, %.1f MB, %.0f MB/s (cpu %.1f ms, %.0f MB/s)", m->info.load_ms, mb,
           m->info.load_ms > 0 ? mb / (m->info.load_ms / 1e3) : 0.0, m->info.load_cpu_ms,
           m->info.load_cpu_ms > 0 ? mb / (m->info.load_cpu_ms / 1e3) : 0.0);
}

/* Which axis of mesh i's model points up, and why: as its format says,
 * or as --up set it. */
static void print_up(Out *out, const Options *o, const Scene *s, int i)
{
    const Mesh *m = &s->meshes[i];
    int up = m->info.up;
    for (int k = 0; k < s->nobjs; k++)
        if (s->objs[k].mesh == m) {
            up = s->objs[k].up;
            break;
        }
    if (o->up >= 0)
        out_line(out, "up:         %s (--up)", up_axis_name(up));
    else
        out_line(out, "up:         %s (%s)", up_axis_name(up),
                   m->info.up_why[0] ? m->info.up_why : "the default");
}

/* The report so far went out, or a message says why not. */
static int report_ok(Out *out)
{
    if (out_flush(out) == 0)
        return 1;
    safetext_line(stderr, "zview: %s: %s", out->name, out_error(out));
    return 0;
}

/* The front as a direction: an axis when it is one ("-z"), else the
 * yaw that looks straight at it. */
static void front_text(const SceneFront *f, char *buf, size_t len)
{
    static const struct { float x, z; const char *name; } axes[] = {
        { 0, 1, "+z" }, { 0, -1, "-z" }, { 1, 0, "+x" }, { -1, 0, "-x" },
    };
    for (size_t i = 0; i < sizeof axes / sizeof axes[0]; i++)
        if (fabsf(f->dir.x - axes[i].x) < 0.035f && fabsf(f->dir.z - axes[i].z) < 0.035f) {  /* 2 degrees */
            snprintf(buf, len, "%s", axes[i].name);
            return;
        }
    snprintf(buf, len, "yaw %.0f", atan2f(-f->dir.x, f->dir.z) * (180 / ZV_PI));
}

/* How the automatic first view was chosen (firstview.c). */
static void print_first_view(Out *out, const FirstView *fv)
{
    if (!fv->rendered) {
        out_printf(out, "auto view:  yaw %g, pitch %g (from the geometry alone: no memory to render)\n",
                   fv->yaw, fv->pitch);
        return;
    }
    char what[64];
    if (fv->prims)
        snprintf(what, sizeof what, "%u polygons, %u points and segments", fv->polys, fv->prims);
    else
        snprintf(what, sizeof what, "%u polygons", fv->polys);
    out_printf(out, "auto view:  yaw %g, pitch %g: %d views of %s%s scored in %.1f ms\n", fv->yaw, fv->pitch,
               fv->rendered, what, fv->standin ? " (a stand-in)" : "", fv->ms);
    out_printf(out, "            its picture: %.0f%% faces seen from the front, %.0f%% from behind%s\n",
               100 * fv->seen, 100 * fv->back, fv->inside_out ? " (the model is inside out: swapped)" : "");
    char dir[32];
    front_text(&fv->front, dir, sizeof dir);
    if (fv->front.from == FRONT_FORMAT)
        out_printf(out, "front:      %s (the format's forward axis)\n", dir);
    else if (fv->front.from == FRONT_FACES)
        out_printf(out, "front:      %s (more of the faces face it: lean %.3f, weight %.2f)\n", dir,
                   fv->front.lean, fv->front.weight);
    else
        out_printf(out, "front:      %s (nothing says: the plain front view's side)\n", dir);
}

/* What the picture just rendered costs as one still image in each
 * terminal protocol, on its background as the viewer sends it: the
 * bytes a pixel frame puts on the link (an SSH session's budget). */
static void print_image_bytes(Out *out, Pipeline *p)
{
    if (p->has_bd)
        backdrop_paint(&p->img, &p->bd);
    char text[160];
    int len = 0;
    for (int proto = PIX_SIXEL; proto <= PIX_ITERM && len < (int)sizeof text; proto++) {
        ByteBuf b = { 0 };
        int bad = pixels_encode((PixelProto)proto, &p->img, 0, 0, 0, &b) || b.err;
        len += snprintf(text + len, sizeof text - (size_t)len, "%s%s %s", len ? ", " : "",
                        pixel_proto_names[proto], bad ? "?" : "");
        if (!bad && len < (int)sizeof text)
            len += snprintf(text + len, sizeof text - (size_t)len, "%zu bytes", b.len);
        bytebuf_free(&b);
    }
    out_line(out, "%-12s%s (a still image of this picture)", "image:", text);
}

int oneshot_info(const Options *o, Scene *s, const FirstView *fv)
{
    Out outs, *out = &outs;
    out_init(out, stdout, "standard output");
    for (int i = 0; i < s->nmeshes; i++) {
        if (i)
            out_printf(out, "\n");
        print_mesh(out, s, &s->meshes[i], s->pos_exp);
        char sb[160];
        sandbox_describe(&s->meshes[i].info, o->no_sandbox, sb, sizeof sb);
        out_printf(out, "sandbox:    %s\n", sb);
        print_up(out, o, s, i);
    }
    uint64_t npolys = 0;   /* grid copies share their source's polygon lists */
    for (int k = 0; k < s->nobjs; k++)
        npolys += s->objs[k].poly_count;
    out_printf(out, "\nscene:      %d objects, %u faces, %llu polygons after splitting non-planar faces\n",
           s->nobjs, s->nfaces, (unsigned long long)npolys);
    if (s->npoints || s->nlines)
        out_printf(out, "            %u points, %u lines (%u segments)\n", s->npoints, s->nlines, s->nsegs);
    if (fv)
        print_first_view(out, fv);
    TextureCount tc;
    scene_texture_count(s, &tc);
    if (tc.count)
        out_printf(out, "            %u texture%s, %.1f MB of texels%s\n", tc.count, tc.count == 1 ? "" : "s",
                   tc.bytes / 1e6, tc.failed ? " (some could not be read)" : "");
    out_printf(out, "simd:       %s\n", simd_name(simd_level()));
    if (!report_ok(out))
        return 1;
    if (!o->algo)
        return 0;
    const HsrAlgo *algo = hsr_find(o->algo);
    Pipeline p;
    if (pipeline_init(&p, s, algo, o->threads)) {
        safetext_line(stderr, "zview: out of memory");
        return 1;
    }
    pipeline_apply_options(&p, o);
    int w = o->w > 0 ? o->w : 640, h = o->h > 0 ? o->h : 480;
    if (pipeline_render(&p, w, h, 1.0f, o->cull, 1)) {
        safetext_line(stderr, "zview: out of memory");
        pipeline_free(&p);
        return 1;
    }
    ReportLine lines[REPORT_LINES];
    int n = frame_report(&p, -1, lines, REPORT_LINES);
    out_printf(out, "\n");
    for (int i = 0; i < n; i++)
        out_line(out, "%-12s%s", lines[i].label, lines[i].text);
    print_image_bytes(out, &p);
    pipeline_free(&p);
    return report_ok(out) ? 0 : 1;
}
