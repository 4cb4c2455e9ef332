#ifndef ZV_ONESHOT_H
#define ZV_ONESHOT_H
/* oneshot: the front door without a terminal: --print, -o, the dumps,
 * --turntable, --info, --check and --bench. Each returns the exit
 * status. */

#include "app.h"
#include "diff.h"

/* --info: what was loaded, how the first view was chosen (fv, from
 * app_load_scene_ex), and (with --algo) what a render did. */
int  oneshot_info(const Options *o, Scene *s, const FirstView *fv);
/* --bench: the benchmark table (each model loaded on its own; s unused). */
int  oneshot_bench(const Options *o, Scene *s);
/* --print, -o FILE, --dump-ids, --dump-screen, --turntable. */
int  oneshot_run(const Options *o, Scene *s);
/* --check: each file loaded and checked on its own, the picture first
 * when --print or -o asks for one, then the report (--json: JSON).
 * Returns 0 sound, 3 problems found, 1 a file not read. */
int  oneshot_check(const Options *o);
/* --diff A B without the viewer: the picture when --print or -o asks,
 * then the report (--json: JSON; --quiet: none). Returns 0 the same
 * within the tolerance, 3 they differ, 1 an output not written. */
int  oneshot_diff(const Options *o, DiffSet *ds);
/* The figures of one object or file: the text report's block (unit as
 * MeshCheck.unit, ind before each line), and the JSON members (each
 * after ",\n" and ind). Every row of counts.c's table is in them. */
void check_text_counts(Out *out, const CheckCounts *c, const char *unit, const char *ind);
void check_json_counts(Out *out, const CheckCounts *c, const char *ind);
/* Refuse (-1, the reason in err) a --print, -o or dump frame that has
 * more than SCREEN_MAX pixels on a side or more memory than is left,
 * before anything is loaded. */
int  oneshot_check_output(const Options *o, char *err, size_t errlen);

#endif
