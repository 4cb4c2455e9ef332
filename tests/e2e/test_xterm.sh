#!/bin/sh
# A real terminal that draws sixel: xterm -ti vt340 under Xvfb, looked
# at through a screenshot of the X display. --print --mode auto asks it,
# gets sixel and draws the torus in pixels (many shades of grey); plain
# xterm (a VT420 without graphics) gets cells in its 16 colours. Then
# the viewer in xterm -ti vt340: the same shades once the model is
# still, and after q the screen holds no image; in plain xterm with
# TERM=xterm and no COLORTERM (ssh), 24-bit cells once xterm says it
# draws them.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }
for tool in Xvfb xterm import; do
    command -v $tool >/dev/null 2>&1 || { skip "sixel in xterm" "no $tool (tools/deps.sh installs xvfb, xterm, imagemagick)"; exit 0; }
done
need_python "sixel in xterm" || exit 0

# a display of its own: the server picks a free number and says which
Xvfb -displayfd 3 -screen 0 700x500x24 -nolisten tcp 3>"$T/display" >/dev/null 2>&1 &
xvfb=$!
trap 'pkill -f "xterm.*zv-xterm-$$" 2>/dev/null; kill $xvfb 2>/dev/null; rm -rf "$T"' EXIT INT TERM HUP
i=0
while [ ! -s "$T/display" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
d=$(cat "$T/display")
[ -n "$d" ] || { notok "Xvfb starts" "no display number in 10 s"; exit 1; }

shot() { DISPLAY=:$d import -window root "$T/shot.ppm"; }
# colours ROWS: the distinct colours of the screenshot's top ROWS rows.
# Cells in plain xterm have its 16 colours at most (the demo scene uses
# about 7); sixel has the 256-colour palette (the demo scene about 20-30
# in this window)
colours() {
    python3 - "$T/shot.ppm" "$1" <<'PY'
import sys
data = open(sys.argv[1], 'rb').read()
parts, pos = [], 0
while len(parts) < 4:
    while data[pos:pos + 1].isspace(): pos += 1
    start = pos
    while not data[pos:pos + 1].isspace(): pos += 1
    parts.append(data[start:pos])
w, h = int(parts[1]), int(parts[2])
px = data[pos + 1:]
rows = min(int(sys.argv[2]), h)
print(len({px[i:i + 3] for i in range(0, w * rows * 3, 3)}))
PY
}
# run TI CMD: CMD in a fresh xterm (-ti TI, or its default), 80x24
run() {
    ti=$1; shift
    pkill -f "xterm.*zv-xterm-$$" 2>/dev/null && sleep 0.5     # the last one gone first
    rm -f "$T/rc"
    DISPLAY=:$d xterm $ti -title zv-xterm-$$ -geometry 80x24 -e sh -c "$*" >>"$T/xterm.log" 2>&1 &
}
wait_rc() { i=0; while [ ! -s "$T/rc" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done; }

# shades ROWS MIN: screenshots until colours ROWS is more than MIN (or
# 10 s); n is the last count
shades() {
    i=0
    while [ $i -lt 40 ]; do
        shot
        n=$(colours "$1" 2>/dev/null)
        n=${n:-0}
        [ "$n" -gt "$2" ] && return 0
        sleep 0.25
        i=$((i + 1))
    done
    return 1
}

# demo.obj: six objects in six colours, shaded
run "-ti vt340" "$Z --print --mode auto --size 80x22 assets/demo.obj; echo \$? >$T/rc; sleep 30"
wait_rc
shades 290 14
check "xterm -ti vt340: --print --mode auto draws sixel (the demo scene in $n colours)" '[ "$n" -gt 14 ]' "$n colours"
pkill -f "xterm.*zv-xterm-$$"
run "" "$Z --print --mode auto --size 80x22 assets/demo.obj; echo \$? >$T/rc; sleep 30"
wait_rc
shades 290 2
check "plain xterm: --print --mode auto draws cells (the demo scene in $n colours)" '[ "$n" -ge 3 ] && [ "$n" -le 12 ]' "$n colours"
pkill -f "xterm.*zv-xterm-$$"

run "-ti vt340" "$Z assets/demo.obj; echo \$? >$T/rc; sleep 30"
shades 290 14 || { run "-ti vt340" "$Z assets/demo.obj; echo \$? >$T/rc; sleep 30"; shades 290 14; }
check "the viewer in xterm -ti vt340: a still model in pixels ($n colours)" '[ "$n" -gt 14 ]' "$n colours"
pkill -f "xterm.*zv-xterm-$$"
# a link of 1 KB/s: the sixel image (tens of KB) is over the budget,
# the cells stay
# (in 16 colours, that cells and pixels be told apart by their count)
run "-ti vt340" "$Z --max-rate 1 --color 16 assets/demo.obj; echo \$? >$T/rc; sleep 30"
shades 290 2
sleep 2
shot
n=$(colours 290)
check "the viewer in xterm -ti vt340 with --max-rate 1: cells kept ($n colours)" '[ "$n" -ge 3 ] && [ "$n" -le 12 ]' "$n colours"
# over ssh: TERM=xterm (8 colours in its description) and no COLORTERM;
# asked, xterm says it draws 24 bits (issue 33), and the cells show them
run "" "env -u COLORTERM TERM=xterm $Z assets/demo.obj; echo \$? >$T/rc; sleep 30"
shades 290 14
many=$n
check "the viewer in plain xterm, TERM=xterm, no COLORTERM: cells in 24-bit colour ($n colours)" '[ "$n" -gt 14 ]' "$n colours"
run "" "env -u COLORTERM TERM=xterm $Z --color 8 assets/demo.obj; echo \$? >$T/rc; sleep 30"
shades 290 2
sleep 2
shot
n=$(colours 290)
check "... --color 8 still wins: cells in 8 colours ($n colours, $many without it)" '[ "$n" -ge 3 ] && [ "$n" -le 12 ]' "$n colours"
pkill -f "xterm.*zv-xterm-$$"
