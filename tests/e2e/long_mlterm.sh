#!/bin/sh
# A second real terminal that draws sixel (issue 33): mlterm (Debian's)
# under Xvfb, looked at through screenshots. The viewer asks it, gets
# sixel, and the still model shows in pixels: many colours where --color
# 16 keeps cells to a few, their glyphs drawn without anti-aliasing (--mode half, the same model, is the measure's
# other side). Ended by SIGTERM (mlterm takes no keys from outside), the
# viewer puts the screen back and leaves no image.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }
for tool in Xvfb mlterm import; do
    command -v $tool >/dev/null 2>&1 || { skip "sixel in mlterm" "no $tool (tools/deps.sh installs xvfb, mlterm, imagemagick)"; exit 0; }
done
need_python "sixel in mlterm" || exit 0

. "$(dirname "$0")/xshot.sh"
x_start 1000x700
ml=
trap '[ -n "$ml" ] && kill $ml 2>/dev/null; kill $xvfb 2>/dev/null; rm -rf "$T"' EXIT INT TERM HUP

# the picture: the top 300 rows, above the status bar of a 24-row mlterm
ROWS=300
# run ARGS: the viewer with ARGS in a fresh mlterm, 80x24; its pid in $T/pid
run() {
    [ -n "$ml" ] && kill $ml 2>/dev/null
    rm -f "$T/pid"
    DISPLAY=:$d mlterm -g 80x24 --sb=false --aa=false -e sh -c "echo \$\$ >$T/pid; exec $Z $*" >>"$T/mlterm.log" 2>&1 &
    ml=$!
}

run --color 16 --mode half assets/demo.obj
until_colours -ge 3 $ROWS
sleep 1
shot
cells=$(colours $ROWS)
check "mlterm, --mode half --color 16: cells ($cells colours)" '[ "$cells" -ge 3 ] && [ "$cells" -le 20 ]' \
    "$cells colours; $(tail -2 "$T/mlterm.log")"
run --color 16 assets/demo.obj
until_colours -gt 40 $ROWS
check "mlterm: asked, it draws sixel: the still model in pixels ($n colours, cells $cells)" '[ "$n" -gt 40 ]' \
    "$n colours; $(tail -2 "$T/mlterm.log")"
kill -TERM "$(cat "$T/pid")" 2>/dev/null
until_colours -le 3 $ROWS
check "mlterm: the viewer ended by SIGTERM leaves no image ($n colours)" '[ "$n" -le 3 ]' "$n colours"
