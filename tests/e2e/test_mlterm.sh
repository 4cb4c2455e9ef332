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

Xvfb -displayfd 3 -screen 0 1000x700x24 -nolisten tcp 3>"$T/display" >/dev/null 2>&1 &
xvfb=$!
ml=
trap '[ -n "$ml" ] && kill $ml 2>/dev/null; kill $xvfb 2>/dev/null; rm -rf "$T"' EXIT INT TERM HUP
i=0
while [ ! -s "$T/display" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
d=$(cat "$T/display")
[ -n "$d" ] || { notok "Xvfb starts" "no display number in 10 s"; exit 1; }

shot() { DISPLAY=:$d import -window root "$T/shot.ppm"; }
# colours: the distinct colours of the screenshot's top 300 rows (the
# picture, above the status bar of a 24-row mlterm)
colours() {
    python3 - "$T/shot.ppm" <<'PY'
import sys
data = open(sys.argv[1], 'rb').read()
parts, pos = [], 0
while len(parts) < 4:
    while data[pos:pos + 1].isspace(): pos += 1
    start = pos
    while not data[pos:pos + 1].isspace(): pos += 1
    parts.append(data[start:pos])
w, h = int(parts[1]), int(parts[2])
b = 6 if int(parts[3]) > 255 else 3
px = data[pos + 1:]
print(len({px[i:i + b] for i in range(0, w * min(300, h) * b, b)}))
PY
}
# until CMP N: screenshots until `colours CMP N` holds (up to 10 s); n the last count
until_colours() {
    i=0
    while [ $i -lt 40 ]; do
        shot
        n=$(colours 2>/dev/null)
        n=${n:-0}
        [ "$n" "$1" "$2" ] && return 0
        sleep 0.25
        i=$((i + 1))
    done
    return 1
}
# run ARGS: the viewer with ARGS in a fresh mlterm, 80x24; its pid in $T/pid
run() {
    [ -n "$ml" ] && kill $ml 2>/dev/null
    rm -f "$T/pid"
    DISPLAY=:$d mlterm -g 80x24 --sb=false --aa=false -e sh -c "echo \$\$ >$T/pid; exec $Z $*" >>"$T/mlterm.log" 2>&1 &
    ml=$!
}

run --color 16 --mode half assets/demo.obj
until_colours -ge 3
sleep 1
shot
cells=$(colours)
check "mlterm, --mode half --color 16: cells ($cells colours)" '[ "$cells" -ge 3 ] && [ "$cells" -le 20 ]' \
    "$cells colours; $(tail -2 "$T/mlterm.log")"
run --color 16 assets/demo.obj
until_colours -gt 40
check "mlterm: asked, it draws sixel: the still model in pixels ($n colours, cells $cells)" '[ "$n" -gt 40 ]' \
    "$n colours; $(tail -2 "$T/mlterm.log")"
kill -TERM "$(cat "$T/pid")" 2>/dev/null
until_colours -le 3
check "mlterm: the viewer ended by SIGTERM leaves no image ($n colours)" '[ "$n" -le 3 ]' "$n colours"
