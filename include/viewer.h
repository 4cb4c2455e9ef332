#ifndef ZV_VIEWER_H
#define ZV_VIEWER_H
/* viewer: the interactive front door: the model on the terminal, turned,
 * moved and scaled by keys and the mouse; files opened and removed while
 * it runs; sketch mode. Its insides are in src/viewer/viewer_app.h. */

#include "app.h"
#include "diff.h"

/* The viewer on the terminal; without one, the one-shot output
 * (oneshot_run). Returns the exit status. */
int  viewer_run(const Options *o, Scene *s);
/* Is the one file of the command line big enough, and the viewer sure
 * to run, to load it while the viewer shows what is parsed so far? */
int  viewer_loads_first(const Options *o);
/* The viewer on the empty scene s, loading the command line's file into
 * it (firstload.c). */
int  viewer_run_loading(const Options *o, Scene *s);
/* --diff A B on the terminal: the diff's scene, V cycling what it
 * shows, the headline in the status bar. The exit status as
 * oneshot_diff's (without a terminal, that is what runs). */
int  viewer_run_diff(const Options *o, DiffSet *ds);
/* --bench-tty: the bytes per frame of a scripted rotation. */
int  viewer_bench_tty(const Options *o);

#endif
