#!/bin/sh
# Sketch mode under tmux (zview --sketch, D): polygons drawn with mouse
# reports (SGR, as xterm and tmux send them) and with the keys; the
# nearer one shows where they overlap, Tab flips that, a tilted one
# pierces the other the same way under every algorithm, w writes an OBJ
# that `zview --print` shows exactly as the sketch did; undo and clear.
# Colours are read from the pane (capture-pane -e) in 24-bit, where a
# flat face is one colour, not a dither of two.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW

# every check reads the pane's colours through looks.py
need_python "every check of sketch mode" || exit 0
. "$(dirname "$0")/tmux.sh"

# sketch_session: a fresh 100 x 30 pane whose shell works in $T/sk (where
# w writes)
sketch_session() {
    root=$ROOT
    ROOT=$T/sk
    session xterm-256color 100 30
    ROOT=$root
}
# run ARGS...: zview ARGS (24-bit colour) in a sketch_session
run() {
    sketch_session
    tm send-keys -t zv "TERM=xterm-256color $Z --color truecolor $*; echo zv-exit=\$?" Enter
}
# the status bar: the pane's last line
status() { sed -n 30p "$T/screen"; }
# looks: the picture's 29 rows, what each cell looks like (looks.py)
looks() { tm capture-pane -p -e -N -t zv | head -n 29 | python3 tests/e2e/looks.py; }
# wait_stable: poll until two looks 0.1 s apart agree (a frame can be
# caught half written); leaves them in $T/looks
wait_stable() {
    looks >"$T/looks"
    i=0
    while [ $i -lt 100 ]; do
        sleep 0.1
        looks >"$T/looks2"
        cmp -s "$T/looks" "$T/looks2" && return 0
        mv "$T/looks2" "$T/looks"
        i=$((i + 1))
    done
    return 1
}
# at COL ROW: the look of picture cell (COL, ROW), 1-based, in $T/looks
at() { awk -v r="$2" -v c="$1" 'NR == r { print $c }' "$T/looks"; }
# click BUTTON COL ROW: press and release (SGR: 0 left, 2 right; 1-based cells)
click() { tm send-keys -t zv -l "$(printf '\033[<%d;%d;%dM\033[<%d;%d;%dm' "$1" "$2" "$3" "$1" "$2" "$3")"; }
# corner COL ROW N: a left click, then the status bar names corner N
corner() {
    click 0 "$1" "$2"
    wait_for "corner $3 at" >/dev/null || notok "corner $3 by a click at $1,$2" "$(status)"
}
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

mkdir -p "$T/sk"

# ==== by mouse: two crossing squares ====
# --print-view: the command line of the last view on standard output
sketch_session
tm send-keys -t zv "TERM=xterm-256color $Z --color truecolor --sketch --print-view >$T/pv; echo zv-exit=\$?" Enter
if wait_for '^ sketch \| 0 polygons \| 0 open'; then ok "--sketch opens an empty canvas"; else
    notok "--sketch opens an empty canvas" "$(cat "$T/screen")"; fi
# A: a wide bar, cells 25..75 x 12..18; B: 35..65 x 5..26 across it;
# they overlap in 35..65 x 12..18
corner 25 12 1
corner 75 12 2
corner 75 18 3
corner 25 18 4
click 2 40 10
if wait_for 'polygon 1 closed'; then ok "a right click closes the polygon"; else notok "a right click closes the polygon" "$(status)"; fi
corner 35 5 1
corner 65 5 2
corner 65 26 3
wait_stable
check "the open polygon's corners show" '[ "$(at 65 26)" = "$(at 35 5)" ] && at 65 26 | grep -q "^o:"' "$(at 65 26) $(at 35 5)"
corner 35 26 4
click 2 60 20
if wait_for '^ sketch \| 2 polygons \| 0 open'; then ok "two polygons drawn by mouse"; else notok "two polygons drawn by mouse" "$(status)"; fi
wait_stable
a=$(at 28 15) b=$(at 50 22) both=$(at 50 15)
check "each polygon has its own colour" '[ -n "$a" ] && [ "$a" != "B/B" ] && [ -n "$b" ] && [ "$b" != "B/B" ] && [ "$a" != "$b" ]' "A $a, B $b"
check "where they overlap the nearer (the last drawn) shows" '[ "$both" = "$b" ] && [ "$(at 38 15)" = "$b" ] && [ "$(at 62 15)" = "$b" ]' "overlap $both, A $a, B $b"
check "outside both the canvas is empty" '[ "$(at 28 24)" = "B/B" ] || [ -z "$(at 28 24)" ]' "$(at 28 24)"
cp "$T/looks" "$T/drawn"

# ==== flip ====
tm send-keys -t zv Tab
wait_for '\| flipped \|' >/dev/null
wait_stable
check "Tab flips the order: the first drawn shows in the overlap" '[ "$(at 50 16)" = "$a" ] && [ "$(at 65 24)" = "$b" ]' "overlap $(at 50 16), A $a, B $b"
tm send-keys -t zv Tab
wait_for '^ sketch \| 2 polygons \| 0 open \| #2 selected \| zbuffer' >/dev/null
wait_stable
check "Tab again gives the drawing back" 'cmp -s "$T/looks" "$T/drawn"' "$(diff "$T/drawn" "$T/looks" | head -3)"

# ==== tilt: B leans through A (about the vertical: its right side comes
# forward, its left side goes back behind A) ====
tm send-keys -t zv t t t
if wait_for 'polygon 2 tilted 45,0'; then ok "t tilts the selected polygon"; else notok "t tilts the selected polygon" "$(status)"; fi
wait_stable
left=$(at 38 15) right=$(at 62 15)
check "tilted, B pierces A: A in front at the overlap's left, B at its right" \
    '[ "$left" = "$a" ] && [ "$right" != "$a" ] && [ "$right" != "B/B" ] && [ "$right" != "$b" ]' "left $left, right $right, A $a, B $b"
cp "$T/looks" "$T/tilted"
for algo in scanline span hzb hzb-octree; do
    tm send-keys -t zv g
    if wait_for "\\| $algo [0-9.]+ms"; then
        wait_stable
        check "$algo draws the same piercing polygons" 'cmp -s "$T/looks" "$T/tilted"' "$(diff "$T/tilted" "$T/looks" | head -3)"
    else
        notok "$algo draws the same piercing polygons" "not selected: $(status)"
    fi
done
tm send-keys -t zv g
wait_for '\| zbuffer [0-9.]+ms' >/dev/null

# ==== write, the command line, and the file reopened ====
tm send-keys -t zv C
if wait_for 'write the sketch first'; then ok "C before w: the command line needs the file"; else notok "C before w: the command line needs the file" "$(cat "$T/screen")"; fi
tm send-keys -t zv x
tm send-keys -t zv w
if wait_for 'wrote sketch-001.obj'; then ok "w writes sketch-001.obj"; else notok "w writes sketch-001.obj" "$(status)"; fi
check "... an OBJ of two objects" '[ "$(grep -c "^o " "$T/sk/sketch-001.obj")" = 2 ] && [ "$(grep -c "^f " "$T/sk/sketch-001.obj")" = 2 ]' "$(head -5 "$T/sk/sketch-001.obj")"
tm send-keys -t zv w
if wait_for 'wrote sketch-002.obj'; then ok "w again takes the next number"; else notok "w again takes the next number" "$(status)"; fi
check "... the first file is kept" 'cmp -s "$T/sk/sketch-001.obj" "$T/sk/sketch-002.obj"'
wait_stable
# the canvas's corner marks (white on black) are the sketch's, not the
# drawing's: --print has the background there
check "the canvas's corners are marked" '[ "$(grep -o "[,.]:255:255:255:0:0:0:" "$T/looks" | wc -l)" -eq 2 ]' "$(head -1 "$T/looks" | head -c 300)"
# (and a row of background alone is an empty line, as looks.py gives it)
sed -e 's/[^ ]:255:255:255:0:0:0:/B\/B/g' -e 's/^B\/B\( B\/B\)*$//' "$T/looks" |
    awk '{ l[NR] = $0 } $0 != "" { last = NR } END { for (i = 1; i <= last; i++) print l[i] }' >"$T/saved"
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "q quits the sketch"; else notok "q quits the sketch" "$(cat "$T/screen")"; fi
check "--print-view names the written file" 'grep -q "^zview sketch-002.obj --yaw 0 --pitch 0 .*--zoom .*--pan " "$T/pv"' "$(cat "$T/pv")"
(cd "$T/sk" && sh -c "$(sed "s|^zview|\"$Z\" --print --size 100x29 --color truecolor|" "$T/pv")") | python3 tests/e2e/looks.py >"$T/print"
check "zview --print of the written OBJ gives the sketch's picture, cell for cell" 'cmp -s "$T/print" "$T/saved"' \
    "$(diff "$T/saved" "$T/print" | head -5 | cut -c1-200; diff "$T/saved" "$T/print" | sed -n "/^>/p" | head -2 | cut -c1-300)"
(cd "$T/sk" && "$Z" --print --size 100x29 --color truecolor --view front sketch-001.obj) | python3 tests/e2e/looks.py >"$T/front"
check "... and the plain front view of it the same colours" \
    'grep -q "$(echo "$a" | cut -d/ -f1)" "$T/front" && grep -q "$(echo "$right" | cut -d/ -f1)" "$T/front"' "$(head -c 300 "$T/front")"

# ==== by keys: arrows, space, Enter ====
run --sketch
wait_for '^ sketch \| 0 polygons' >/dev/null
# the cursor starts in the middle of the picture (cell 51, 15)
tm send-keys -t zv Left
if wait_for '^ {49}\+'; then ok "an arrow shows the cursor"; else notok "an arrow shows the cursor" "$(sed -n 15p "$T/screen")"; fi
# key COUNT KEY: KEY sent COUNT times
keys() { k=0; set_keys=""; while [ $k -lt "$1" ]; do set_keys="$set_keys $2"; k=$((k + 1)); done; tm send-keys -t zv $set_keys; }
# A: 30..50 x 5..17 (from 50,15), B: 40..65 x 10..25
keys 20 Left; keys 10 Up; tm send-keys -t zv Space
wait_for 'corner 1 at' >/dev/null
keys 20 Right; tm send-keys -t zv Space
wait_for 'corner 2 at' >/dev/null
keys 12 Down; tm send-keys -t zv Space
wait_for 'corner 3 at' >/dev/null
keys 20 Left; tm send-keys -t zv Space
wait_for 'corner 4 at' >/dev/null
tm send-keys -t zv Enter
if wait_for 'polygon 1 closed'; then ok "Enter closes the polygon"; else notok "Enter closes the polygon" "$(status)"; fi
keys 10 Right; keys 7 Up; tm send-keys -t zv Space
wait_for 'corner 1 at' >/dev/null
keys 25 Right; tm send-keys -t zv Space
wait_for 'corner 2 at' >/dev/null
keys 15 Down; tm send-keys -t zv Space
wait_for 'corner 3 at' >/dev/null
keys 25 Left; tm send-keys -t zv Space
wait_for 'corner 4 at' >/dev/null
tm send-keys -t zv Enter
if wait_for '^ sketch \| 2 polygons \| 0 open'; then ok "two polygons drawn by keys"; else notok "two polygons drawn by keys" "$(status)"; fi
wait_stable
ka=$(at 35 8) kb=$(at 60 22) kboth=$(at 45 14)
check "by keys: two colours, the nearer in the overlap" \
    '[ "$ka" != "B/B" ] && [ "$kb" != "B/B" ] && [ "$ka" != "$kb" ] && [ "$kboth" = "$kb" ]' "A $ka, B $kb, overlap $kboth"
check "... the same colours as drawn by mouse" '[ "$ka" = "$a" ] && [ "$kb" = "$b" ]' "keys $ka $kb, mouse $a $b"

# ==== undo and clear ====
tm send-keys -t zv u
if wait_for 'polygon 2 taken back'; then ok "u takes back the last polygon"; else notok "u takes back the last polygon" "$(status)"; fi
wait_for '^ sketch \| 1 polygon \| 0 open' >/dev/null
wait_stable
check "... it leaves the picture, A shows in the overlap" '[ "$(at 45 14)" = "$ka" ] && [ "$(at 60 22)" != "$kb" ]' "overlap $(at 45 14)"
tm send-keys -t zv Space
wait_for '^ sketch \| 1 polygon \| 1 open' >/dev/null
tm send-keys -t zv BSpace
if wait_for 'corner taken back' && wait_for '^ sketch \| 1 polygon \| 0 open'; then ok "Backspace takes back a corner"; else notok "Backspace takes back a corner" "$(status)"; fi
tm send-keys -t zv '?'
if wait_for 'zview sketch keys' && wait_for 'Tab +flip the depth order'; then ok "? lists the sketch keys"; else notok "? lists the sketch keys" "$(cat "$T/screen")"; fi
tm send-keys -t zv x
tm send-keys -t zv c
if wait_for '^ sketch \| 0 polygons \| 0 open'; then ok "c clears all"; else notok "c clears all" "$(status)"; fi
wait_stable
check "... the canvas is empty but for the cursor" '[ "$(grep -o "[0-9]*:[0-9]*:[0-9]*/" "$T/looks" | wc -l)" = 0 ]' "$(grep -m1 "/" "$T/looks" | head -c 200)"
tm send-keys -t zv Escape
if wait_for 'zv-exit=0'; then ok "Esc leaves --sketch (no model to go back to)"; else notok "Esc leaves --sketch" "$(cat "$T/screen")"; fi

# ==== D: from a model into the sketch and back ====
run "$ROOT/assets/cube.obj"
wait_for 'faces 6 drawn' >/dev/null
tm send-keys -t zv D
if wait_for '^ sketch \| 0 polygons'; then ok "D opens the sketch from the viewer"; else notok "D opens the sketch from the viewer" "$(status)"; fi
tm send-keys -t zv D
if wait_for 'faces 6 drawn'; then ok "D again gives the model back"; else notok "D again gives the model back" "$(status)"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

# ==== the command line ====
TERM=dumb "$Z" --sketch >"$T/out" 2>"$T/err" </dev/null
rc=$?
check "--sketch with no terminal: status 1" '[ $rc -eq 1 ]' "status $rc"
expect_err "... and says why" "--sketch: no terminal to draw on"
expect_status "--sketch with --print is a usage error" 2 "$Z" --sketch --print
expect_err "... naming the clash" "--sketch draws in the viewer: it does not go with --print"
