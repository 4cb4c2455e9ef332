/* statusbar.c: the viewer's status bar, one line of fields that give
 * way by rank as the window narrows (the man page's KEYS section gives
 * the same order). */

#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "safetext.h"
#include "tty.h"
#include "viewer_app.h"

/* The colour depth as the status bar names it. */
static const char *depth_label(ColourDepth d)
{
    switch (d) {
    case COLOUR_TRUE: return "24bit";
    case COLOUR_256:  return "256";
    case COLOUR_16:   return "16";
    case COLOUR_8:    return "8";
    default:         return "mono";
    }
}

/* The status bar's fields, in the order shown. When the bar is wider
 * than the window, fields go by rank, lowest first: 1 frame time and
 * fps, 2 picture size, 3 display mode, shading and colours, 4 view flags
 * (persp, cull, spin), 5 selection. Rank 0 stays: the file, the
 * polygons (points and lines too when there are some), the algorithm and
 * its time, the section cut (cutkeys.c), work going on in the background (a file loading, the octree
 * building), and "? help"; in a window still
 * too narrow they take their brief forms ("drawn/faces", "?"), then the
 * file name is cut to a dozen columns, then the note is cut at its end or
 * goes (rank 6: it answers a key, so it outlasts everything else but the
 * name's last columns; without one, why the frame is empty), and last of
 * all the file name is cut further. The man page gives the same order. */
#define BAR_FIELDS 13
#define BAR_NOTE   6
enum { CUT = 8, CHECK = 9, BUSY = 10, NOTE = 11, HELP = 12 };     /* the last fields' places */

typedef struct {
    char text[96];
    char brief[32];     /* a rank 0 field's short form ("" = none) */
    int  rank;          /* -1: dropped */
    int  glued;         /* joined to the field before by a space, not " | " */
} BarField;

static void bar_field(BarField *f, int rank, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void bar_field(BarField *f, int rank, const char *fmt, ...)
{
    char raw[sizeof f->text];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    /* a file's name, an object's, a warning: made safe here (safetext.h),
     * so that the widths below are of what vt_text draws */
    safetext(f->text, sizeof f->text, raw);
    f->brief[0] = 0;
    f->rank = rank;
    f->glued = 0;
}

/* Join the fields still in (not dropped, not empty). Returns the length. */
static int bar_join(const BarField *f, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = 0;
    for (int i = 0; i < BAR_FIELDS; i++) {
        if (f[i].rank < 0 || !f[i].text[0])
            continue;
        int k = snprintf(buf + o, len - o, "%s%s", !o ? " " : f[i].glued ? " " : " | ", f[i].text);
        if (k < 0 || (size_t)k >= len - o)
            break;
        o += (size_t)k;
    }
    return (int)o;
}

/* Cut the file name (field 0) until the bar fits, keeping at least
 * `keep_min` bytes and marking the cut with '~'. */
static void shorten_name(BarField *f, char *buf, size_t len, int width, int keep_min)
{
    int over = bar_join(f, buf, len) - width;
    int name_len = (int)strlen(f[0].text);
    if (over <= 0 || name_len <= keep_min + 1)
        return;
    int keep = name_len - over - 1 > keep_min ? name_len - over - 1 : keep_min;
    while (keep > 3 && (f[0].text[keep] & 0xc0) == 0x80)
        keep--;         /* not inside a UTF-8 character */
    f[0].text[keep] = '~';      /* ASCII: the locale may not be UTF-8 */
    f[0].text[keep + 1] = 0;
}

void viewer_status_text(const App *a, char *buf, size_t len, double frame_ms, int fps_cap, int width)
{
    if (a->sk.on) {
        sketch_mode_status(a, buf, len, width);
        return;
    }
    const Scene *s = a->s;
    BarField f[BAR_FIELDS];
    bar_field(&f[0], 0, "%s", a->name);
    bar_field(&f[1], 5, "%s", "");
    if (a->sel >= 0)
        bar_field(&f[1], 5, "[%s %d/%d]", s->objs[a->sel].name, a->sel + 1, s->nobjs);
    else if (s->nobjs > 1)
        bar_field(&f[1], 5, "[all %d]", s->nobjs);
    f[1].glued = 1;
    /* points and lines beside the faces when the scene has them */
    char prims[48] = "";
    if (s->npoints)
        snprintf(prims, sizeof prims, " points %u", s->npoints);
    if (s->nlines)
        snprintf(prims + strlen(prims), sizeof prims - strlen(prims), " lines %u", s->nlines);
    bar_field(&f[2], 0, "faces %u%s drawn %u", s->nfaces, prims, a->p.sp.npolys);
    /* a cloud (or a load's first picture, its vertices) is its points */
    if (s->nfaces == 0 && s->npoints)
        snprintf(f[2].brief, sizeof f[2].brief, "points %u", s->npoints);
    else
        snprintf(f[2].brief, sizeof f[2].brief, "%u/%u", a->p.sp.npolys, s->nfaces);
    bar_field(&f[3], 0, "%s %.2fms", a->p.algo->name, a->p.hsr_ms);
    bar_field(&f[4], 1, "frame %.1fms %.0ffps", frame_ms, frame_ms > 0 ? 1000.0 / frame_ms : 0);
    /* while a still image shows, the image's own colours and size (the
     * cells under it, which move with the model, are the text's) */
    int image = term_image_shown() && term_pixels() != PIX_CELLS;
    bar_field(&f[5], 3, "%s %s %s", a->pixels && term_pixels() != PIX_CELLS ? pixel_proto_names[term_pixels()]
                                                                          : mode_names[a->mode],
              shade_names[a->p.shade],
              !image ? depth_label(term_colour()) : term_pixels() == PIX_SIXEL ? "256" : "24bit");
    char spin[24] = "";
    if (a->spin)
        snprintf(spin, sizeof spin, "spin@%d", fps_cap);
    bar_field(&f[6], 4, "%s%s%s%s%s", s->cam.persp ? "persp" : "",
              s->cam.persp && (a->cull || a->spin) ? " " : "", a->cull ? "cull" : "",
              a->cull && a->spin ? " " : "", spin);
    bar_field(&f[7], 2, "%dx%dpx", a->p.img.w, a->p.img.h);
    /* the section plane in use and its area (--section, /) */
    viewer_cut_status(a, f[CUT].text, sizeof f[CUT].text, f[CUT].brief, sizeof f[CUT].brief);
    f[CUT].rank = 0;
    f[CUT].glued = 0;
    /* a note answers a key; without one, why the frame is empty */
    bar_field(&f[NOTE], BAR_NOTE, "%s", a->note[0] ? a->note : a->empty_why && !a->first ? a->empty_why : "");
    bar_field(&f[HELP], 0, "? help");
    snprintf(f[HELP].brief, sizeof f[HELP].brief, "?");
    /* work going on in the background, so that nothing looks frozen */
    char busy[96] = "";
    if (a->first)
        firstload_status(a->first, busy, sizeof busy);
    else if (a->job)
        loadjob_status(a->job, busy, sizeof busy);
    else if (a->tex)
        texjob_status(a->tex, busy, sizeof busy);
    else if (a->p.st.building)
        snprintf(busy, sizeof busy, "building octree...");
    bar_field(&f[BUSY], 0, "%s", busy);
    /* the check's verdict in a word or two (--problems, --parts, !) */
    char verdict[96];
    viewer_check_status(a, INT_MAX, verdict, sizeof verdict);
    bar_field(&f[CHECK], 0, "%s", verdict);
    for (int rank = 1; rank < BAR_NOTE && bar_join(f, buf, len) > width; rank++)
        for (int i = 0; i < BAR_FIELDS; i++)
            if (f[i].rank == rank)
                f[i].rank = -1;
    if (bar_join(f, buf, len) > width)
        for (int i = 0; i < BAR_FIELDS; i++)
            if (f[i].brief[0])
                memcpy(f[i].text, f[i].brief, sizeof f[i].brief);
    /* the verdict gives way by whole problems ("6 holes · +3"), before
     * the file name is cut */
    for (int items = 8; items >= 1 && bar_join(f, buf, len) > width; items--) {
        viewer_check_status(a, items, verdict, sizeof verdict);
        snprintf(f[CHECK].text, sizeof f[CHECK].text, "%s", verdict);
    }
    /* a note outranks the rest while it shows: the file name gives way
     * first (to a dozen columns), then the note is cut at its end, and
     * goes when little would be left; the name last of all */
    shorten_name(f, buf, len, width, 12);
    int over = bar_join(f, buf, len) - width, note_len = (int)strlen(f[NOTE].text);
    if (over > 0 && note_len - over - 1 >= 12) {
        int keep = note_len - over - 1;
        while (keep > 0 && (f[NOTE].text[keep] & 0xc0) == 0x80)
            keep--;
        f[NOTE].text[keep] = '~';
        f[NOTE].text[keep + 1] = 0;
    } else if (over > 0) {
        f[NOTE].rank = -1;
    }
    shorten_name(f, buf, len, width, 3);
    /* still too wide: the verdict as a count, then gone, so that "?"
     * (help) always shows and nothing is cut mid-word by the edge */
    if (bar_join(f, buf, len) > width) {
        viewer_check_status(a, 0, verdict, sizeof verdict);
        snprintf(f[CHECK].text, sizeof f[CHECK].text, "%s", verdict);
    }
    if (bar_join(f, buf, len) > width)
        f[CHECK].rank = -1;
    bar_join(f, buf, len);
}

/* ==== Overlays: the open prompt, its candidates, the info panel ==== */
