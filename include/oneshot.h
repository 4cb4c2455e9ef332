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
/* --preview WxH FILE: the picture in the cells above the last row, the
 * check's verdict in it; a file not read says why in one line there.
 * Returns 0, or 1 when the file was not read or a write failed. */
int  oneshot_preview(const Options *o);
/* --diff A B without the viewer: the picture when --print or -o asks,
 * then the report (--json: JSON; --quiet: none). Returns 0 the same
 * within the tolerance, 3 they differ, 1 an output not written. */
int  oneshot_diff(const Options *o, DiffSet *ds);
/* The figures of one object or file: the text report's block (unit as
 * MeshCheck.unit, ind before each line), and the JSON members (each
 * after ",\n" and ind). Every row of counts.c's table is in them. */
void check_text_counts(Out *out, const CheckCounts *c, const CheckLocations *loc, const char *unit, const char *ind);
void check_json_counts(Out *out, const CheckCounts *c, const char *ind);
/* checkwhere.c: where the problems are. The text report's lines of the
 * locations whose count is on text line `line` (CheckLine.line), and the
 * JSON member "locations" (after ",\n" and ind). */
void check_text_locations(Out *out, const CheckLocations *l, const CheckCounts *c, int line, const char *unit,
                          const char *ind);
void check_json_locations(Out *out, const CheckLocations *l, const CheckCounts *c, const char *ind);
/* printreport.c: will it print, in --check's report. The figures of one
 * file, worked out while its mesh is at hand (after the check): the
 * unit (stated, given with --unit, or what the size suggests), the fit
 * on --bed, the overhanging area (--overhang), the walls' thickness
 * (--thickness, --min-thickness). */
typedef struct {
    char         unit_given[4];     /* --unit's word ("" none): the figures are in mm */
    const char  *unit_guess;        /* printq_unit_guess, when the format states none and --unit is not given */
    int          has_bed;
    double       bed[3];
    PrintqOrders orders;
    int          fits[PRINTQ_ORDERS];
    int          fit;               /* the first order that fits, -1 none */
    int          has_overhang;
    double       overhang_deg, overhang_area;
    int          has_thickness;
    PrintqThickness thick;          /* its face array freed once summed */
    double       thin_limit, thin_area;
} PrintFigures;
int  print_figures_run(const Options *o, const Mesh *m, const CheckCounts *c, PrintFigures *pf, char *err,
                       size_t errlen);
void print_figures_text(Out *out, const PrintFigures *pf, const char *unit, const char *ind);
void print_figures_json(Out *out, const PrintFigures *pf, const char *ind);
/* --measure A B [C] FILE: the figures, text or --json. */
int  oneshot_measure(const Options *o);
/* A JSON string: quotes, backslashes and controls escaped, a byte that
 * is not UTF-8 (an object name in Latin-1) as U+FFFD (safetext.h). */
void oneshot_json_str(Out *out, const char *s);
/* --repair IN -o OUT: IN loaded, checked, repaired (repair.h), written
 * (save.h), OUT read back and checked; what each step did and the two
 * checks side by side (--json: JSON), on standard output (standard
 * error when OUT is -). Returns 0 when OUT is sound, 3 when problems
 * remain, 1 when IN could not be read or OUT not written, 2 when OUT
 * would be IN. */
int  oneshot_repair(const Options *o);
/* Refuse (-1, the reason in err) a --print, -o or dump frame that has
 * more than SCREEN_MAX pixels on a side or more memory than is left,
 * before anything is loaded. */
int  oneshot_check_output(const Options *o, char *err, size_t errlen);

#endif
