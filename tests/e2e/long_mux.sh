#!/bin/sh
# Pixels through tmux (issue 33): xterm -ti vt340 (which draws sixel)
# under Xvfb runs tmux 3.3 with allow-passthrough on, the viewer in it.
# The still model shows in sixel pixels (many colours in a screenshot,
# where --color 16 keeps cells to a few), is gone while another tmux
# window is current and back when the viewer's is, and is gone after q.
# With allow-passthrough off: cells, and the status bar and the info
# panel say how to turn it on. In GNU screen: cells, and the info panel
# says why.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }
for tool in Xvfb xterm import tmux screen; do
    command -v $tool >/dev/null 2>&1 || { skip "pixels through tmux" "no $tool (tools/deps.sh installs xvfb, xterm, imagemagick, tmux, screen)"; exit 0; }
done
need_python "pixels through tmux" || exit 0

. "$(dirname "$0")/xshot.sh"
x_start 700x500
xt=
sock=zv-mux-$$
TM="tmux -L $sock"
trap '$TM kill-server 2>/dev/null; [ -n "$xt" ] && kill $xt 2>/dev/null; kill $xvfb 2>/dev/null; rm -rf "$T"' EXIT INT TERM HUP

# the pane's picture: the top 280 rows, above the viewer's status bar
ROWS=280
# screen_has TEXT: the viewer's pane shows TEXT (up to 10 s)
screen_has() {
    i=0
    while [ $i -lt 50 ]; do
        $TM capture-pane -p -t zv:0 2>/dev/null | grep -qF -- "$1" && return 0
        sleep 0.2
        i=$((i + 1))
    done
    return 1
}
VIEW="$Z --color 16 assets/demo.obj; echo \$? >$T/rc; sleep 60"

# passthrough on: tmux's one session in a fresh xterm -ti vt340, 80x24
printf 'set -g allow-passthrough on\nset -g status off\n' >"$T/tmux.conf"
DISPLAY=:$d xterm -ti vt340 -geometry 80x24 -e $TM -f "$T/tmux.conf" new-session -s zv "$VIEW" >"$T/xterm.log" 2>&1 &
xt=$!
until_colours -gt 30 $ROWS
check "tmux with allow-passthrough on in xterm -ti vt340: the still model in sixel pixels ($n colours)" \
    '[ "$n" -gt 30 ]' "$n colours; $($TM capture-pane -p -t zv:0 2>&1 | tail -1)"
$TM new-window -t zv:1 "sleep 60"
until_colours -le 3 $ROWS
check "... another tmux window current: the image is gone ($n colours)" '[ "$n" -le 3 ]' "$n colours"
sleep 1     # tmux is asked every 500 ms (MUX_POLL_MS): a quicker return goes unseen
$TM select-window -t zv:0
until_colours -gt 30 $ROWS
check "... the viewer's window current again: the image is back ($n colours)" '[ "$n" -gt 30 ]' "$n colours"
$TM send-keys -t zv:0 q
i=0
while [ ! -s "$T/rc" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
until_colours -le 3 $ROWS
check "... q: the viewer ends (status $(cat "$T/rc" 2>/dev/null)) and leaves no image ($n colours)" \
    '[ "$(cat "$T/rc" 2>/dev/null)" = 0 ] && [ "$n" -le 3 ]' "$n colours"

# passthrough off: cells, and how to turn it on
$TM set -g allow-passthrough off
rm -f "$T/rc"
$TM respawn-pane -k -t zv:0 "$VIEW"
screen_has "zbuffer"
sleep 1
until_colours -ge 3 $ROWS
check "tmux with allow-passthrough off: cells ($n colours)" '[ "$n" -ge 3 ] && [ "$n" -le 18 ]' "$n colours"
check "... the status bar says how to turn it on" 'screen_has "set -g allow-passthrough on"' \
    "$($TM capture-pane -p -t zv:0 | tail -1)"
$TM send-keys -t zv:0 i
check "... and so does the info panel" 'screen_has "tmux passes no images: set -g"' \
    "$($TM capture-pane -p -t zv:0 | grep -F 'pixels:')"

# GNU screen (inside tmux, which only shows it): cells, and why
mkdir -m 700 "$T/screen"
$TM respawn-pane -k -t zv:0 "SCREENDIR=$T/screen screen -c /dev/null $Z --color 16 assets/demo.obj"
screen_has "zbuffer"
check "GNU screen: the status bar says cells" 'screen_has "screen: cells, no images"' \
    "$($TM capture-pane -p -t zv:0 | tail -1)"
$TM send-keys -t zv:0 i
check "... and the info panel why" 'screen_has "GNU screen passes no images"' \
    "$($TM capture-pane -p -t zv:0 | grep -F 'pixels:')"
$TM send-keys -t zv:0 q
