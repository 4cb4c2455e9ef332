#!/bin/sh
# Real pixels (pixels.h): --print in each protocol (the stream's framing;
# tests/test_pixels.c decodes the pixels), auto without a terminal, and
# the viewer under tmux, which passes no images: inside it the viewer
# asks nothing and draws cells; with TMUX unset the questions go to
# tmux, which answers the device attributes without a 4, so cells
# again, and no byte of a question or an answer shows.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

"$Z" --print --mode sixel --size 20x5 assets/torus.obj >"$T/sixel"
hex() { od -An -tx1 | tr -d ' \n'; }
check "--print --mode sixel: one DCS string, then a newline" \
    '[ "$(head -c 2 "$T/sixel" | hex)" = 1b50 ] && [ "$(tail -c 3 "$T/sixel" | hex)" = 1b5c0a ]' \
    "$(head -c 2 "$T/sixel" | hex) ... $(tail -c 3 "$T/sixel" | hex)"
check "--print --mode sixel --size 20x5: 200x100 pixels (10x20 a cell without a terminal)" 'grep -q "\"1;1;200;100" "$T/sixel"'
"$Z" --print --mode kitty --size 20x5 assets/torus.obj >"$T/kitty"
check "--print --mode kitty: APC strings of PNG data" 'head -c 40 "$T/kitty" | grep -q "_Ga=T,f=100"'
"$Z" --print --mode iterm --size 20x5 assets/torus.obj >"$T/iterm"
check "--print --mode iterm: an OSC 1337 File string" 'head -c 40 "$T/iterm" | grep -q "1337;File=inline=1"'
"$Z" --print --mode auto --size 20x5 assets/torus.obj >"$T/auto"
check "--print --mode auto into a pipe: cells, no question, no image" \
    'grep -q "▀" "$T/auto" && ! grep -q "_G\|1337\|P0;1;0q" "$T/auto"'
expect_status "--mode nope is a usage error" 2 "$Z" --mode nope --print assets/torus.obj
expect_err "... naming the pixel modes" "cells, sixel, kitty, iterm or auto"

# the viewer's status bar while a still image shows names the image's
# colours and size, not the cells' under it (140x30 cells of the default
# 10x20 pixels: an image of 1400x580 over 29 rows)
if need_python "the status bar names the image's colours and size"; then
    for m in sixel:256 kitty:24bit iterm:24bit; do
        mode=${m%%:*} want=${m#*:}
        TERM=xterm-256color python3 tests/e2e/pixbar.py 140 30 -- "$Z" --mode "$mode" --color 16 assets/torus.obj >"$T/bar" 2>&1
        check "$mode: the cells' bar says their 16 colours and 140x58px" \
            'grep -q "^cells: .* $mode lambert 16 | 140x58px |" "$T/bar"' "$(cat "$T/bar")"
        check "... the image's says $want and 1400x580px" \
            'grep -q "^image: .* $mode lambert $want | 1400x580px | ? help" "$T/bar"' "$(cat "$T/bar")"
    done
fi

command -v tmux >/dev/null 2>&1 || { skip "the viewer under tmux" "no tmux"; exit 0; }
. "$(dirname "$0")/tmux.sh"
for how in inside unset; do
    session xterm-256color 100 30
    if [ $how = unset ]; then
        tm send-keys -t zv "env -u TMUX TERM=xterm-256color $Z --color truecolor assets/torus.obj; echo zv-exit=\$?" Enter
    else
        tm send-keys -t zv "TERM=xterm-256color $Z --color truecolor assets/torus.obj; echo zv-exit=\$?" Enter
    fi
    if ! wait_for 'faces [0-9]+ drawn'; then notok "viewer ($how tmux) starts" "$(cat "$T/screen")"; continue; fi
    check "viewer, TMUX $how: half blocks, not pixels" 'grep -q " half " "$T/screen" && grep -q "▀" "$T/screen"' \
        "$(tail -1 "$T/screen")"
    check "viewer, TMUX $how: no question or answer on the screen" '! grep -Eq "Gi=31|AAAA|\?1;2c|\^\[" "$T/screen"'
    tm send-keys -t zv m
    wait_for 'mode: ascii' >/dev/null
    check "viewer, TMUX $how: m goes from half to ascii (no pixels to cycle into)" 'grep -q "mode: ascii" "$T/screen"' \
        "$(tail -1 "$T/screen")"
    tm send-keys -t zv q
    wait_for 'zv-exit=[0-9]' >/dev/null
    check "viewer, TMUX $how: quits with status 0" 'grep -q "zv-exit=0" "$T/screen"' "$(tail -2 "$T/screen")"
done
cleanup
