#!/bin/sh
# The scene edited while the viewer runs (O opens, X and Delete remove,
# E empties), the info panel (i) against --info, and what the status
# line says on its own: points and lines, why a frame is empty, a
# lenient load's warnings. Every wait polls for a condition (tmux.sh).
. "$(dirname "$0")/lib.sh"
. "$(dirname "$0")/tmux.sh"

torus=$(grep -c '^f ' assets/torus.obj)
knot=$(grep -c '^f ' assets/knot.obj)

# ==== open: the prompt, Tab completion, loading, the face count ====
start 100 30 --view front assets/torus.obj
wait_for "faces $torus drawn" >/dev/null || notok "the viewer starts" "$(cat "$T/screen")"
tm send-keys -t zv O
if wait_for '^ open:$'; then ok "O opens a prompt in the status line"; else notok "O opens a prompt in the status line" "$(status 30)"; fi
tm send-keys -t zv -l 'assets/kn'
tm send-keys -t zv Tab
if wait_for '^ open: assets/knot\.obj$'; then ok "Tab completes the path"; else notok "Tab completes the path" "$(status 30)"; fi
tm send-keys -t zv Enter
both=$((torus + knot))
if wait_for "faces $both drawn"; then ok "Enter loads it: the face count grows to $both"; else notok "Enter loads it: the face count grows to $both" "$(status 30)"; fi
check "the status line names both files" 'status 30 | grep -q "torus.obj +1"' "$(status 30)"
# laid out as --layout says: the same picture as both files on the command line
if need_python "the picture is the one both files on the command line give"; then
    print_looks --color 256 --size 100x29 --view front assets/torus.obj assets/knot.obj >"$T/print"
    if wait_looks 29 "$T/print"; then ok "the picture is the one both files on the command line give"; else
        notok "the picture is the one both files on the command line give" "$(diff "$T/looks" "$T/print" | head -5)"; fi
fi

# the view's command line names the files the scene now holds
tm send-keys -t zv C
if wait_for 'zview assets/torus.obj assets/knot.obj '; then ok "C names both files"; else notok "C names both files" "$(cat "$T/screen")"; fi
tm send-keys -t zv C
wait_gone 'command line of this view' >/dev/null

# a second Tab lists the candidates; Esc leaves the scene alone
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l 'assets/c'
tm send-keys -t zv Tab
wait_for '^ open: assets/c' >/dev/null
tm send-keys -t zv Tab
if wait_for 'concave\.obj +cube\.obj'; then ok "a second Tab lists the candidates"; else notok "a second Tab lists the candidates" "$(cat "$T/screen")"; fi
tm send-keys -t zv Escape
if wait_gone 'concave\.obj +cube\.obj' && wait_for "faces $both drawn"; then ok "Esc cancels the prompt"; else
    notok "Esc cancels the prompt" "$(status 30)"; fi

# errors: the loader's message, nothing changed
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l 'assets/nope.obj'
tm send-keys -t zv Enter
if wait_for 'nope\.obj: cannot open'; then ok "a missing file: the loader's message"; else notok "a missing file: the loader's message" "$(status 30)"; fi
check "... and the scene is unchanged" 'status 30 | grep -Eq "faces $both drawn|/$both "' "$(status 30)"
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l 'README.md'
tm send-keys -t zv Enter
if wait_for 'not a model zview can read'; then ok "a file of no model format: the loader's message"; else notok "a file of no model format: the loader's message" "$(status 30)"; fi

# ==== remove, empty, open again ====
tm send-keys -t zv Tab
wait_for '\[torus' >/dev/null
tm send-keys -t zv X
if wait_for "faces $knot drawn" && wait_for 'removed torus'; then ok "X removes the selected object"; else notok "X removes the selected object" "$(status 30)"; fi
check "the status line names the file left" 'status 30 | grep -q "^ knot.obj |"' "$(status 30)"
tm send-keys -t zv E
if wait_for 'empty the scene \(1 object\)\? y/n'; then ok "E asks first"; else notok "E asks first" "$(status 30)"; fi
tm send-keys -t zv n
if wait_for 'the scene stays'; then ok "... n keeps the scene"; else notok "... n keeps the scene" "$(status 30)"; fi
tm send-keys -t zv E
wait_for 'y/n' >/dev/null
tm send-keys -t zv y
if wait_for 'empty scene: O opens a file'; then ok "y empties it: the status line says so"; else notok "y empties it: the status line says so" "$(status 30)"; fi
check "... no face left" 'status 30 | grep -q "faces 0 drawn 0"' "$(status 30)"
# every algorithm, the info panel and the keys that touch objects on an empty scene
for algo in scanline span hzb hzb-octree zbuffer; do
    tm send-keys -t zv g
    if wait_for "\\| $algo .*empty scene"; then ok "an empty scene under $algo"; else notok "an empty scene under $algo" "$(status 30)"; fi
done
tm send-keys -t zv i Tab n X W e v v p b
if wait_for 'frame info' && wait_for 'the scene has nothing to draw'; then ok "the info panel on an empty scene"; else
    notok "the info panel on an empty scene" "$(cat "$T/screen")"; fi
tm send-keys -t zv i
wait_gone 'frame info' >/dev/null
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l 'assets/cube.obj'
tm send-keys -t zv Enter
if wait_for 'faces 6 drawn' && wait_for 'opened cube.obj'; then ok "O after E: a scene again"; else notok "O after E: a scene again" "$(status 30)"; fi
# the Delete key
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l 'assets/knot.obj'
tm send-keys -t zv Enter
wait_for "faces $((knot + 6)) drawn" >/dev/null
tm send-keys -t zv Tab
wait_for '\[cube' >/dev/null
tm send-keys -t zv DC
if wait_for "faces $knot drawn" && wait_for 'removed cube'; then ok "Delete removes the selected object"; else notok "Delete removes the selected object" "$(status 30)"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null || notok "q quits after the edits" "$(tail -3 "$T/screen")"

# ==== loads that wait: a FIFO (Esc cancels), devices refused ====
start 100 30 assets/cube.obj
wait_for 'faces 6 drawn' >/dev/null
mkfifo "$T/pipe.obj"
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l "$T/pipe.obj"
tm send-keys -t zv Enter
if wait_for 'waiting for a writer to pipe\.obj'; then ok "O on a FIFO waits for its writer (the status line says so)"; else
    notok "O on a FIFO waits for its writer (the status line says so)" "$(status 30)"; fi
tm send-keys -t zv Escape
if wait_for 'cancelled loading pipe\.obj' && wait_gone 'waiting for a writer'; then ok "Esc cancels the load"; else
    notok "Esc cancels the load" "$(status 30)"; fi
check "... and does not quit" '! grep -q "zv-exit" "$T/screen"' "$(tail -3 "$T/screen")"
# nothing holds the FIFO open any more: a writer's open waits for a reader
timeout 1 sh -c 'exec 3>"$1"' sh "$T/pipe.obj"
check "the cancelled load let go of the FIFO" '[ $? -eq 124 ]'
tm send-keys -t zv O
if wait_for '^ open:$'; then ok "O again after the cancel (no \"still loading\")"; else notok "O again after the cancel (no \"still loading\")" "$(status 30)"; fi
tm send-keys -t zv -l "$T/pipe.obj"
tm send-keys -t zv Enter
wait_for 'waiting for a writer to pipe\.obj' >/dev/null
timeout 10 sh -c 'cat assets/knot.obj >"$1"' sh "$T/pipe.obj"
if wait_for "faces $((knot + 6)) drawn" && wait_for "opened pipe\\.obj: $knot faces"; then ok "a FIFO's writer comes: its model joins the scene"; else
    notok "a FIFO's writer comes: its model joins the scene" "$(status 30)"; fi
for dev in /dev/urandom /dev/zero; do
    tm send-keys -t zv O
    wait_for '^ open:$' >/dev/null
    tm send-keys -t zv -l "$dev"
    tm send-keys -t zv Enter
    name=${dev#/dev/}
    if wait_for "$name: not a file \\(a character device\\)"; then ok "O $dev is refused at once"; else notok "O $dev is refused at once" "$(status 30)"; fi
done
tm send-keys -t zv Escape
if wait_for 'zv-exit=0'; then ok "Esc quits when nothing loads"; else notok "Esc quits when nothing loads" "$(tail -3 "$T/screen")"; fi

# ==== hzb-octree across edits: trees of the scene before are never used ====
start 100 30 --view front --algo hzb-octree assets/torus.obj
wait_for "faces $torus drawn" >/dev/null
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l 'assets/knot.obj'
tm send-keys -t zv Enter
wait_for "faces $both drawn" >/dev/null
if need_python "hzb-octree after O and X draws the z-buffer's picture"; then
    print_looks --color 256 --size 100x29 --view front --algo zbuffer assets/torus.obj assets/knot.obj >"$T/print"
    if wait_looks 29 "$T/print"; then ok "hzb-octree after O draws the z-buffer's picture"; else
        notok "hzb-octree after O draws the z-buffer's picture" "$(diff "$T/looks" "$T/print" | head -5)"; fi
    tm send-keys -t zv Tab X
    wait_for "faces $knot drawn" >/dev/null
    print_looks --color 256 --size 100x29 --view front --algo zbuffer assets/knot.obj >"$T/print"
    if wait_looks 29 "$T/print"; then ok "hzb-octree after X draws the z-buffer's picture"; else
        notok "hzb-octree after X draws the z-buffer's picture" "$(diff "$T/looks" "$T/print" | head -5)"; fi
fi
tm send-keys -t zv q

# ==== the info panel: the numbers --info --algo prints for the same view ====
# 120 x 40 cells in half blocks: 120 x 78 pixels; one sample a pixel and
# one thread, so that every count is the same as --info's
start 120 40 --mode half --samples 1 --threads 1 assets/torus.obj
wait_for "faces $torus drawn" >/dev/null
tm send-keys -t zv i
wait_for 'frame info' >/dev/null
for algo in zbuffer scanline span hzb hzb-octree; do
    if ! wait_for "\\| $algo " || ! wait_for "render: +$algo,"; then
        notok "the info panel under $algo" "$(head -12 "$T/screen")"
        tm send-keys -t zv g
        continue
    fi
    "$Z" --info --algo "$algo" --size 120x78 --samples 1 --threads 1 assets/torus.obj >"$T/info" 2>/dev/null
    same=1
    for what in render polygons pyramid pixels; do
        want=$(grep "^$what:" "$T/info" | sed "s/^$what: *//")
        got=$(grep "| $what:" "$T/screen" | sed "s/.*| $what: *//; s/ *|\$//")
        if [ "$want" != "$got" ]; then
            same=0
            notok "info panel under $algo: $what" "panel '$got', --info '$want'"
        fi
    done
    [ $same = 1 ] && ok "the info panel under $algo: the counts --info --algo $algo prints"
    check "... times of every stage, output included" 'grep -q "time: *transform [0-9.]* ms" "$T/screen" && grep -q "output [0-9.]* ms" "$T/screen"' "$(head -12 "$T/screen")"
    tm send-keys -t zv g
done
tm send-keys -t zv i
if wait_gone 'frame info'; then ok "i again closes the panel"; else notok "i again closes the panel"; fi
tm send-keys -t zv q

# ==== the status line on its own ====
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nl 1 3\np 2 4\nf 1 2 9\n' >"$T/mixed.obj"
start 200 30 "$T/mixed.obj"
if wait_for 'faces 1 points 2 lines 1 drawn'; then ok "points and lines counted beside the faces"; else notok "points and lines counted beside the faces" "$(status 30)"; fi
if wait_for 'mixed.obj: 1 statement skipped \(first:'; then ok "a lenient load's warning shows at start"; else notok "a lenient load's warning shows at start" "$(status 30)"; fi
tm send-keys -t zv q
# O under --strict refuses what the command line refuses
start 200 30 --strict assets/cube.obj
wait_for 'faces 6 drawn' >/dev/null
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l "$T/mixed.obj"
tm send-keys -t zv Enter
if wait_for 'mixed\.obj:8: vertex index 9 out of range'; then ok "O under --strict: the file is refused, file and line named"; else
    notok "O under --strict: the file is refused, file and line named" "$(status 30)"; fi
check "... and the scene is unchanged" 'status 30 | grep -q "faces 6 drawn"' "$(status 30)"
tm send-keys -t zv q
start 80 24 --pan 40,0 assets/cube.obj
if wait_for 'everything is outside the picture'; then ok "an empty frame says why"; else notok "an empty frame says why" "$(status 24)"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null
