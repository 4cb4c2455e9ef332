#!/bin/sh
# The background (backdrop.h): --bg and --contrast on the command line;
# their effect on -o images (pixels read back from PPM) and --print
# frames (the colours of the escapes); then the viewer and --print
# asking the terminal under tmux, which answers the colour query when
# the pane's style gives it a background and not otherwise: the colour
# taken (the info panel says so), the picture kept visible on it, and no
# byte of an answer on the screen or left for the shell.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW

# ==== the options ====
expect_status "--bg nope is a usage error" 2 "$Z" --bg nope --print --size 20x8 assets/cube.obj
expect_err "--bg nope: the message names the value and the colours" "bad value 'nope' for --bg (default, #rrggbb"
expect_status "--bg '#12345' is a usage error" 2 "$Z" --bg '#12345' --print --size 20x8 assets/cube.obj
expect_status "--contrast 0.5 is a usage error (at most 0.4)" 2 "$Z" --contrast 0.5 --print --size 20x8 assets/cube.obj
expect_status "--contrast -1 is a usage error" 2 "$Z" --contrast -1 --print --size 20x8 assets/cube.obj
for v in default black white grey '#fff' '#336699'; do
    expect_status "--bg $v" 0 "$Z" --bg "$v" --print --size 20x8 assets/cube.obj
done

need_python "every check of the background's pixels" || exit 0

# A cube in one material: navy (lit, 0 0 64: OKLab L 0.17), near black
# (5 5 5: L 0.12). --ambient 1 lights every face fully, so every drawn
# pixel is the material's colour.
material() {
    printf 'newmtl m\nKd %s\n' "$2" >"$T/$1.mtl"
    { echo "mtllib $1.mtl"; echo "usemtl m"; grep -v '^#' assets/cube.obj; } >"$T/$1.obj"
}
material navy "0 0 0.25"
material nearblack "0.02 0.02 0.02"
px() { python3 tests/e2e/ppm.py "$@"; }
ge() { python3 -c "import sys; sys.exit(0 if float('$1') >= float('$2') else 1)"; }
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }
# drawn FILE: the drawn pixels of an image: npx, distinct, minl, maxl, top
# (not n: tmux.sh counts its servers in n)
drawn() { set -- $(px "$1" drawn); npx=$1 distinct=$2 minl=$3 maxl=$4 top=$5; stats="$*"; }
# sgr FILE [R,G,B]: the colours of a text frame but that one: npx, minl, maxl
sgr() { set -- $(px "$1" sgr $2); npx=$1 minl=$2 maxl=$3; stats="$*"; }

# ==== -o ====
for m in navy nearblack; do
    "$Z" -o "$T/off.ppm" --size 64x48 --bg black --contrast 0 --ambient 1 "$T/$m.obj"
    drawn "$T/off.ppm"
    asis=$top
    check "-o $m, --contrast 0: one colour, exactly the material's, under the minimum ($stats)" \
        '[ "$npx" -gt 300 ] && [ "$distinct" = 1 ] && ! ge "$minl" 0.2' "$stats"
    "$Z" -o "$T/on.ppm" --size 64x48 --bg black --ambient 1 "$T/$m.obj"
    drawn "$T/on.ppm"
    check "-o $m on --bg black: lifted to the minimum, one colour still ($stats)" \
        '[ "$distinct" = 1 ] && [ "$top" != "$asis" ] && ge "$minl" 0.2' "$stats"
    check "-o $m on --bg black: the background is black" '[ "$(px "$T/on.ppm" at 0 0)" = "0 0 0" ]'
    "$Z" -o "$T/lit.ppm" --size 64x48 --bg black "$T/$m.obj"
    drawn "$T/lit.ppm"
    check "-o $m on black, lit and in shade: every drawn pixel at least 0.2 from black ($stats)" 'ge "$minl" 0.1999' "$stats"
    "$Z" -o "$T/auto.ppm" --size 64x48 --ambient 1 "$T/$m.obj"
    drawn "$T/auto.ppm"
    check "-o $m without --bg: a white background, the material's colour kept ($stats)" \
        '[ "$(px "$T/auto.ppm" at 0 0)" = "255 255 255" ] && [ "$top" = "$asis" ]' "$stats"
done
"$Z" -o "$T/t.ppm" --size 80x60 assets/torus.obj
drawn "$T/t.ppm"
check "-o of a light grey model without --bg: black behind it, its light faces kept ($stats)" \
    '[ "$(px "$T/t.ppm" at 0 0)" = "0 0 0" ] && ge "$maxl" 0.82' "$stats"
"$Z" -o "$T/t.ppm" --size 80x60 --bg white assets/torus.obj
drawn "$T/t.ppm"
check "-o on --bg white: white behind, nothing drawn lighter than 0.8 ($stats)" \
    '[ "$(px "$T/t.ppm" at 0 0)" = "255 255 255" ] && ! ge "$maxl" 0.8001' "$stats"
"$Z" -o "$T/t.ppm" --size 80x60 --bg '#336699' assets/torus.obj
check "-o on --bg '#336699': that colour behind" '[ "$(px "$T/t.ppm" at 0 0)" = "51 102 153" ]' "$(px "$T/t.ppm" at 0 0)"
"$Z" --turntable 3 -o "$T/tt-%d.ppm" --size 64x48 --ambient 1 "$T/navy.obj"
check "--turntable: every frame keeps the first frame's background" \
    '[ "$(px "$T/tt-0.ppm" at 0 0)" = "255 255 255" ] && [ "$(px "$T/tt-2.ppm" at 0 0)" = "255 255 255" ]'

# ==== --print ====
"$Z" --print --color truecolor --size 40x16 --bg white assets/torus.obj >"$T/w.txt" </dev/null
sgr "$T/w.txt" 255,255,255
check "--print --bg white: the model's colours no lighter than 0.8 ($stats)" '[ "$npx" -gt 50 ] && ! ge "$maxl" 0.8001' "$stats"
check "--print --bg white: the background painted in every row" \
    '[ "$(grep -c "48;2;255;255;255m" "$T/w.txt")" -eq 16 ]' "$(grep -c "48;2;255;255;255m" "$T/w.txt")"
"$Z" --print --color truecolor --size 40x16 assets/torus.obj >"$T/d.txt" </dev/null
check "--print without --bg: nothing painted (the terminal's own background)" '! grep -q "48;2;0;0;0m" "$T/d.txt"'
"$Z" --print --color truecolor --size 40x16 "$T/navy.obj" >"$T/n.txt" </dev/null
sgr "$T/n.txt"
check "--print of navy, no terminal to ask: kept 0.2 from black ($stats)" '[ "$npx" -gt 20 ] && ge "$minl" 0.1999' "$stats"
COLORFGBG='0;15' "$Z" --print --color truecolor --size 40x16 assets/torus.obj >"$T/e.txt" </dev/null
sgr "$T/e.txt"
check "--print with COLORFGBG=0;15 (a white background): no colour lighter than 0.8 ($stats)" '! ge "$maxl" 0.8001' "$stats"
"$Z" --print --color none --mode ascii --size 40x16 --bg white assets/torus.obj >"$T/aw.txt" </dev/null
"$Z" --print --color none --mode ascii --size 40x16 --bg black assets/torus.obj >"$T/ab.txt" </dev/null
check "--color none --bg white: no escapes, and the ramp turned (dark faces dense)" \
    '! grep -q "$(printf "\033")" "$T/aw.txt" && ! cmp -s "$T/aw.txt" "$T/ab.txt"'

# ==== the terminal asked, under tmux ====
. "$(dirname "$0")/tmux.sh"

# start_on STYLE COLS ROWS ARGS...: start, in a pane whose background
# the window style sets (tmux then answers the colour query with it);
# STYLE "": tmux's default, which does not answer it
start_on() {
    style=$1; shift
    cols=$1; rows=$2; shift 2
    session xterm-256color "$cols" "$rows"
    [ -n "$style" ] && tm set-option -g window-style "$style" >/dev/null
    rm -f "$T/pid"
    tm send-keys -t zv "TERM=xterm-256color sh -c 'echo \$\$ >$T/pid; exec $Z $*'; echo zv-exit=\$?" Enter
}
colours() { tm capture-pane -p -e -t zv >"$T/cap"; sgr "$T/cap"; }
no_answer_shown() { ! grep -Eq 'rgb:|11;|\?1;2c|\^\[' "$T/screen"; }

for bg in none white; do
    if [ $bg = white ]; then start_on 'bg=#ffffff' 100 30 --color truecolor assets/torus.obj
    else start_on '' 100 30 --color truecolor assets/torus.obj; fi
    if ! wait_for 'faces [0-9]+ drawn'; then notok "viewer on a $bg pane starts" "$(cat "$T/screen")"; continue; fi
    wait_stable
    check "viewer on a $bg pane: no byte of an answer on the screen" no_answer_shown "$(head -5 "$T/screen")"
    colours
    if [ $bg = white ]; then
        check "viewer on a white pane: nothing drawn lighter than 0.8 ($stats)" '[ "$npx" -gt 50 ] && ! ge "$maxl" 0.8001' "$stats"
        tm send-keys -t zv i
        wait_for 'background:' >/dev/null
        check "viewer on a white pane: the info panel names the terminal's answer" \
            'grep -q "#ffffff (the terminal.s, asked)" "$T/screen"' "$(grep -A1 background: "$T/screen")"
    else
        check "viewer on a pane that does not answer: the light faces kept ($stats)" 'ge "$maxl" 0.82' "$stats"
        tm send-keys -t zv i
        wait_for 'background:' >/dev/null
        check "viewer on a pane that does not answer: taken for black" \
            'grep -q "#000000 (assumed" "$T/screen"' "$(grep -A1 background: "$T/screen")"
    fi
    tm send-keys -t zv q
    wait_for '^zv-exit=0' >/dev/null || notok "viewer on a $bg pane quits" "$(tail -3 "$T/screen")"
    prompt_back || notok "the shell after the viewer on a $bg pane" "$(tail -3 "$T/screen")"
    check "the shell after the viewer on a $bg pane reads what is typed, nothing before it" \
        'grep -q "^back-in-42$" "$T/screen" && no_answer_shown' "$(tail -4 "$T/screen")"

    # --print on the pane's terminal: asked too, through /dev/tty
    session xterm-256color 60 20
    [ $bg = white ] && tm set-option -g window-style 'bg=#ffffff' >/dev/null
    tm send-keys -t zv "TERM=xterm-256color $Z --print --color truecolor --size 40x12 assets/torus.obj; echo pr-exit=\$?" Enter
    wait_for '^pr-exit=0' >/dev/null || notok "--print on a $bg pane ends" "$(tail -3 "$T/screen")"
    colours
    if [ $bg = white ]; then
        check "--print on a white pane: nothing lighter than 0.8 ($stats)" '[ "$npx" -gt 30 ] && ! ge "$maxl" 0.8001' "$stats"
    else
        check "--print on a pane that does not answer: the light faces kept ($stats)" 'ge "$maxl" 0.82' "$stats"
    fi
    prompt_back || notok "the shell after --print on a $bg pane" "$(tail -3 "$T/screen")"
    check "--print on a $bg pane: no answer on the screen or typed into the shell" \
        'no_answer_shown && grep -q "^back-in-42$" "$T/screen"' "$(tail -4 "$T/screen")"
done

# TERM=dumb says the terminal knows no escapes: not even asked (the pane
# would answer white)
session xterm-256color 60 20
tm set-option -g window-style 'bg=#ffffff' >/dev/null
tm send-keys -t zv "TERM=dumb $Z --print --color truecolor --size 40x12 assets/torus.obj; echo pr-exit=\$?" Enter
wait_for '^pr-exit=0' >/dev/null || notok "--print on TERM=dumb ends" "$(tail -3 "$T/screen")"
colours
check "--print on TERM=dumb: the terminal not asked, the light faces kept ($stats)" 'ge "$maxl" 0.82' "$stats"
