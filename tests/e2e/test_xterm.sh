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

. "$(dirname "$0")/xshot.sh"
x_start 700x500
trap 'pkill -f "xterm.*zv-xterm-$$" 2>/dev/null; kill $xvfb 2>/dev/null; rm -rf "$T"' EXIT INT TERM HUP

# Counted in the top 290 rows, above the status bar: cells in plain
# xterm have its 16 colours and its default foreground and background at
# most (the demo scene uses about 10); sixel has the 256-colour palette
# (the demo scene about 50-80 in this window), 24-bit cells about 200.

# run TI CMD: CMD in a fresh xterm (-ti TI, or its default), 80x24
run() {
    ti=$1; shift
    pkill -f "xterm.*zv-xterm-$$" 2>/dev/null && sleep 0.5     # the last one gone first
    rm -f "$T/rc"
    DISPLAY=:$d xterm $ti -title zv-xterm-$$ -geometry 80x24 -e sh -c "$*" >>"$T/xterm.log" 2>&1 &
}
wait_rc() { i=0; while [ ! -s "$T/rc" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done; }

shades() { until_colours -gt "$2" "$1"; }

# demo.obj: six objects in six colours, shaded
run "-ti vt340" "$Z --print --mode auto --size 80x22 assets/demo.obj; echo \$? >$T/rc; sleep 30"
wait_rc
shades 290 30
check "xterm -ti vt340: --print --mode auto draws sixel (the demo scene in $n colours)" '[ "$n" -gt 30 ]' "$n colours"
pkill -f "xterm.*zv-xterm-$$"
run "" "$Z --print --mode auto --size 80x22 assets/demo.obj; echo \$? >$T/rc; sleep 30"
wait_rc
shades 290 2
check "plain xterm: --print --mode auto draws cells (the demo scene in $n colours)" '[ "$n" -ge 3 ] && [ "$n" -le 18 ]' "$n colours"
pkill -f "xterm.*zv-xterm-$$"

# (in 16 colours, so that cells, at most 18, do not pass for pixels)
run "-ti vt340" "$Z --color 16 assets/demo.obj; echo \$? >$T/rc; sleep 30"
shades 290 30 || { run "-ti vt340" "$Z --color 16 assets/demo.obj; echo \$? >$T/rc; sleep 30"; shades 290 30; }
check "the viewer in xterm -ti vt340, --color 16: a still model in pixels ($n colours)" '[ "$n" -gt 30 ]' "$n colours"
pkill -f "xterm.*zv-xterm-$$"
# a link of 1 KB/s: the sixel image (tens of KB) is over the budget,
# the cells stay
run "-ti vt340" "$Z --max-rate 1 --color 16 assets/demo.obj; echo \$? >$T/rc; sleep 30"
shades 290 2
sleep 2
shot
n=$(colours 290)
check "the viewer in xterm -ti vt340 with --max-rate 1: cells kept ($n colours)" '[ "$n" -ge 3 ] && [ "$n" -le 18 ]' "$n colours"
# over ssh: TERM=xterm (8 colours in its description) and no COLORTERM;
# asked, xterm says it draws 24 bits (issue 33), and the cells show them
run "" "env -u COLORTERM TERM=xterm $Z assets/demo.obj; echo \$? >$T/rc; sleep 30"
shades 290 30
many=$n
check "the viewer in plain xterm, TERM=xterm, no COLORTERM: cells in 24-bit colour ($n colours)" '[ "$n" -gt 30 ]' "$n colours"
run "" "env -u COLORTERM TERM=xterm $Z --color 8 assets/demo.obj; echo \$? >$T/rc; sleep 30"
shades 290 2
sleep 2
shot
n=$(colours 290)
check "... --color 8 still wins: cells in 8 colours ($n colours, $many without it)" '[ "$n" -ge 3 ] && [ "$n" -le 18 ]' "$n colours"
pkill -f "xterm.*zv-xterm-$$"
