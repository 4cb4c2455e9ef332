#!/bin/sh
# A real kitty (Debian's, 0.26) under Xvfb with software OpenGL, looked at
# through a screenshot of the X display (issue 28). kitty answers the
# viewer's graphics query as its protocol says (ESC _ G i=31;OK ESC \);
# the key parser read that as Esc, and the viewer quit at once, status 0,
# having drawn nothing. Now: the model shows in kitty's pixels, the viewer
# is still running seconds later, and q (typed through kitty's remote
# control) quits it with status 0. --mode half in the same kitty gives the
# measure's other side: cells.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }
for tool in Xvfb kitty import; do
    command -v $tool >/dev/null 2>&1 || { skip "zview in kitty" "no $tool (tools/deps.sh installs xvfb, kitty, imagemagick)"; exit 0; }
done
need_python "zview in kitty" || exit 0

. "$(dirname "$0")/xshot.sh"
x_start 800x600
kpid=
stop_kitty() {
    [ -n "$kpid" ] && kill "$kpid" 2>/dev/null && wait "$kpid" 2>/dev/null
    kpid=
}
trap 'stop_kitty; kill $xvfb 2>/dev/null; rm -rf "$T"' EXIT INT TERM HUP PIPE

# run ARGS: the viewer with ARGS in a fresh kitty filling the display; its
# pid in $T/pid, its exit status in $T/rc when it ends. The viewer starts
# once kitty answers its remote control (up to 60 s): its question about
# pixels waits 100 ms for the answer (TERM_ASK_MS), which a kitty
# still starting on a loaded machine missed.
run() {
    stop_kitty
    rm -f "$T/rc" "$T/pid" "$T/sock" "$T/go"
    mkdir -p "$T/cache" "$T/conf"
    DISPLAY=:$d LIBGL_ALWAYS_SOFTWARE=1 XDG_CACHE_HOME="$T/cache" KITTY_CONFIG_DIRECTORY="$T/conf" \
        kitty --config NONE -o allow_remote_control=yes --listen-on "unix:$T/sock" \
        -o initial_window_width=800 -o initial_window_height=600 -o remember_window_size=no \
        sh -c "echo \$\$ >$T/pid; while [ ! -e $T/go ]; do sleep 0.05; done; $Z $*; echo \$? >$T/rc; sleep 60" >>"$T/kitty.log" 2>&1 &
    kpid=$!
    i=0
    while [ $i -lt 120 ]; do
        [ -s "$T/pid" ] && kitty @ --to "unix:$T/sock" ls >/dev/null 2>&1 && break
        sleep 0.5
        i=$((i + 1))
    done
    : >"$T/go"
}
# the picture: the top 540 rows, above the status line. Cells change
# colour only at their edges (one column in 8 or so: at most 100 in 800
# pixels); a picture in pixels changes almost anywhere along the model.
ROWS=540
# settle MIN: screenshots until changes is above MIN, for up to 60 s (a
# loaded machine draws late); n the last
settle() {
    end=$(($(date +%s) + 60))
    while :; do
        shot
        n=$(changes $ROWS 2>/dev/null)
        n=${n:-0}
        [ "$n" -gt "$1" ] && return 0
        [ "$(date +%s)" -lt $end ] || return 1
        sleep 0.5
    done
}
alive() { [ ! -s "$T/rc" ] && [ -s "$T/pid" ] && kill -0 "$(cat "$T/pid")" 2>/dev/null; }
quit_viewer() {
    kitty @ --to "unix:$T/sock" send-text q >>"$T/kitty.log" 2>&1
    i=0
    while [ ! -s "$T/rc" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    rc=$(cat "$T/rc" 2>/dev/null)
}

# cells first: the measure's baseline (ZV_KITTY_SHOT=x.png keeps the
# screenshots, x-cells.png and x.png)
run --mode half assets/knot.obj
settle 20
sleep 1
shot
cells=$(changes $ROWS)
[ -n "$ZV_KITTY_SHOT" ] && convert "$T/shot.ppm" "${ZV_KITTY_SHOT%.png}-cells.png"
check "kitty, --mode half: the knot in cells (colour changes at $cells columns)" \
    '[ "$cells" -gt 20 ] && [ "$cells" -le 110 ]' "$cells columns; $(tail -3 "$T/kitty.log")"
quit_viewer
check "kitty, --mode half: q quits (status $rc)" '[ "$rc" = 0 ]' "status '$rc'"

# the default: kitty is asked, answers, and the still model is drawn in
# its pixels
run assets/knot.obj
settle 300
check "kitty: the knot in pixels (colour changes at $n columns, cells $cells)" '[ "$n" -gt 300 ]' \
    "$n columns; viewer status '$(cat "$T/rc" 2>/dev/null)'; $(tail -3 "$T/kitty.log")"
cp "$T/shot.ppm" "$T/pixels.ppm"
sleep 2
check "kitty: the viewer is still running 2 s after its picture" 'alive' \
    "exited with status '$(cat "$T/rc" 2>/dev/null)'"
[ -n "$ZV_KITTY_SHOT" ] && convert "$T/pixels.ppm" "$ZV_KITTY_SHOT"
was=0
alive && was=1
quit_viewer
check "kitty: q quits the running viewer (status $rc)" '[ $was = 1 ] && [ "$rc" = 0 ]' "running before q: $was, status '$rc'"
stop_kitty
