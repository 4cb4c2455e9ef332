/* report.c: the numbers of one rendered frame, in words. --info --algo
 * prints them and the viewer's info panel shows them: one function, so
 * the two always agree. */

#include <stdio.h>

#include "app.h"

int frame_report(const Pipeline *p, double out_ms, ReportLine *lines, int max)
{
    int n = 0;
    const HsrStats *st = &p->st;
    const FrameBufs *fb = &p->fb;
    uint64_t covered = 0;
    for (size_t i = 0; i < (size_t)fb->w * fb->h; i++)
        covered += fb->ids[i] >= 0;
#define LINE(lab, ...)                                                     \
    do {                                                                   \
        if (n < max) {                                                     \
            lines[n].label = lab;                                          \
            snprintf(lines[n].text, sizeof lines[n].text, __VA_ARGS__);    \
            n++;                                                           \
        }                                                                  \
    } while (0)
    LINE("render:", "%s, %dx%d pixels, %d thread%s", p->algo->name, fb->w, fb->h, p->threads,
         p->threads > 1 ? "s" : "");
    LINE("polygons:", "%u in, %u back faces culled, %u cover no sample, %u to the algorithm", p->sp.in_polys,
         p->sp.culled_back, p->sp.culled_empty, p->sp.npolys);
    if (p->sp.points_in || p->sp.edges_in)
        LINE("points:", "%u on screen, %u squares after keeping the nearest per sample box; "
                        "%u segments and edges, %u quads, %u as samples in %u squares",
             p->sp.points_in, p->sp.points_drawn, p->sp.edges_in, p->sp.edges_drawn, p->sp.edges_sampled,
             p->sp.edge_squares);
    LINE("pyramid:", "%llu polygons culled, %llu octree nodes visited, %llu culled",
         (unsigned long long)st->polys_culled, (unsigned long long)st->nodes_visited,
         (unsigned long long)st->nodes_culled);
    LINE("pixels:", "%llu written, %llu covered, overdraw %.2f", (unsigned long long)st->pixels_written,
         (unsigned long long)covered, covered ? (double)st->pixels_written / covered : 0.0);
    if (out_ms >= 0)
        LINE("time:", "transform %.2f ms (points and lines %.2f), build %.2f ms, scan %.2f ms, shade %.2f ms, "
                      "output %.2f ms",
             p->project_ms, p->sp.prim_ms, st->build_ms, st->scan_ms, p->shade_ms, out_ms);
    else
        LINE("time:", "transform %.2f ms (points and lines %.2f), build %.2f ms, scan %.2f ms, shade %.2f ms",
             p->project_ms, p->sp.prim_ms, st->build_ms, st->scan_ms, p->shade_ms);
    if (p->has_bd) {
        char bd[96];
        backdrop_describe(&p->bd, bd, sizeof bd);
        if (p->contrast > 0)
            LINE("background:", "%s, drawn pixels kept %.2g from its lightness", bd, (double)p->contrast);
        else
            LINE("background:", "%s, colours as given", bd);
    }
    TextureCount tc;
    scene_texture_count(p->scene, &tc);
    if (tc.count)
        LINE("textures:", "%u, %.1f MB of texels%s%s%s%s", tc.count, tc.bytes / 1e6,
             tc.failed ? ", " : "", tc.failed ? "some could not be read" : "", tc.pending ? ", decoding" : "",
             p->no_textures ? "; hidden (t shows them)" : "");
    const char *why = frame_empty_reason(p);
    if (why)
        LINE("empty:", "%s", why);
#undef LINE
    return n;
}
