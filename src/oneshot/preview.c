/* preview.c: --preview WxH FILE, zview as a file manager's previewer
 * (lf, fzf --preview, ranger, yazi): called once per file the cursor
 * rests on, with the cells the preview pane has. The model is loaded
 * once, drawn as --print draws it in the pane less its last row, and
 * checked; the last row is the check's verdict, cut by whole items to
 * the pane's width. Everything goes to standard output, which is all a
 * file manager shows: a file that is no model (or no readable one) gives
 * one line saying why, and exit status 1, quickly. No terminal is asked
 * anything: standard output is the file manager's pipe. */

#include <stdio.h>
#include <string.h>

#include "oneshot.h"
#include "safetext.h"

/* Columns of UTF-8 text s (each character one column: the verdict's are). */
static int columns(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += ((unsigned char)*s & 0xc0) != 0x80;
    return n;
}

/* The verdict of what the check found, as many of its items named as
 * fit in w columns (then "+N"), and the faces counted when they fit. */
static void verdict_line(const SceneCheck *sc, int w, char *buf, size_t len)
{
    char v[256];
    int max = 8;
    check_verdict_items(&sc->all, ", ", max, v, sizeof v);
    while (max > 0 && columns(v) > w)
        check_verdict_items(&sc->all, ", ", --max, v, sizeof v);
    snprintf(buf, len, "%s, %llu faces", v, (unsigned long long)sc->all.faces);
    if (columns(buf) > w)
        snprintf(buf, len, "%s", v);
}

/* Text in at most `lines` lines of w columns, broken between words
 * where it can be (a file manager cuts or wraps longer lines itself, each
 * its own way); what does not fit is left out. */
static void say(const char *what, int w, int lines)
{
    char safe[1024];
    safetext(safe, sizeof safe, what);
    const char *p = safe;
    for (int l = 0; l < lines && *p; l++) {
        /* the longest run of whole characters in w columns, back to its
         * last space when the text goes on past it */
        size_t end = 0, brk = 0;
        int cols = 0;
        while (p[end] && cols < w) {
            end++;
            while (((unsigned char)p[end] & 0xc0) == 0x80)
                end++;
            cols++;
            if (p[end] == ' ')
                brk = end;
        }
        if (p[end] && brk)
            end = brk;
        printf("%.*s\n", (int)end, p);
        p += end;
        while (*p == ' ')
            p++;
    }
}

int oneshot_preview(const Options *o)
{
    char err[512];
    int w = o->w, rows = o->h;
    Scene s;
    if (app_load_scene(o, &s, err, sizeof err)) {
        say(err, w, rows);
        return 1;
    }
    /* the picture in the rows above the verdict (a pane of one row: the
     * verdict alone) */
    int rc = 0;
    if (rows > 1) {
        Options pic = *o;
        pic.print = 1;
        pic.h = rows - 1;
        rc = oneshot_run(&pic, &s);
        fflush(stdout);
    }
    SceneCheck sc = { 0 };
    if (!rc) {
        char line[600];
        if (app_check_scene(&s, o->threads, &sc, err, sizeof err))
            snprintf(line, sizeof line, "check: %s", err);
        else
            verdict_line(&sc, w, line, sizeof line);
        say(line, w, 1);
    }
    scene_check_free(&sc);
    scene_free(&s);
    return rc;
}
