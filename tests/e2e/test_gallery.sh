#!/bin/sh
# The gallery (issue 34): a temporary folder of the bundled models, a
# file that is no model named like one, a link that loops, a link to a
# folder above, and files that are not models. Its contact sheet (the
# size of the layout, each readable tile's picture drawn, the broken
# ones empty), the text grid (names, verdicts, what --all adds), and
# the grid on the terminal under tmux: tiles and verdicts appear, the
# arrows move, Enter opens the model in the viewer and q comes back to
# the same place, / filters, s sorts.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

G=$T/models
mkdir -p "$G/sub"
cp assets/*.obj assets/*.mtl "$G/"
cp assets/README.md "$G/notes.md"
printf 'this is not a model\n' >"$G/broken.obj"
ln -s loop.obj "$G/loop.obj"
ln -s .. "$G/sub/up"
ln -s sub "$G/sub.obj"              # a link to a folder, named like a model: not entered
nmodels=$(ls assets/*.obj | wc -l)
nt=$((nmodels + 2))                 # and broken.obj, loop.obj (not $nt: tmux.sh counts its sessions in it)
names=$(cd "$G" && LC_ALL=C ls -d *.obj | while read -r f; do [ -d "$f" ] || echo "$f"; done)

# ==== the contact sheet ====
expect_status "--gallery DIR -o sheet.png writes the sheet" 0 "$Z" --gallery "$G" -o "$T/sheet.png"
if need_python "the sheet is a whole PNG of the layout's size"; then
    expect_status "--gallery DIR -o sheet.ppm writes the sheet" 0 "$Z" --gallery "$G" -o "$T/sheet.ppm"
    python3 tests/e2e/sheet.py "$T/sheet.ppm" "$nt" 160 120 >"$T/tiles" 2>"$T/sheet.err"
    check "the sheet has the layout's size ($nt tiles)" '[ -s "$T/tiles" ]' "$(cat "$T/sheet.err")"
    size=$(python3 tests/e2e/pngsize.py "$T/sheet.png")
    psize=$(head -c 20 "$T/sheet.ppm" | sed -n 2p)
    check "the PNG and the PPM sheets are the same size ($size)" '[ "$size" = "$psize" ]' "png $size, ppm $psize"
    i=0
    bad=""
    for f in $ntames; do
        px=$(sed -n "$((i + 1))p" "$T/tiles" | cut -d' ' -f2)
        case $f in
        broken.obj | loop.obj) [ "$px" -eq 0 ] || bad="$bad $f:$px(want 0)" ;;
        *) [ "$px" -gt 500 ] || bad="$bad $f:$px" ;;
        esac
        i=$((i + 1))
    done
    check "each readable tile's picture differs from the background, the unreadable ones are empty" '[ -z "$bad" ]' "$bad"
fi
"$Z" --gallery "$G" -o "$T/sheet2.png" --size 64x48 >/dev/null 2>&1
if need_python "--size sets the sheet's pictures"; then
    s2=$(python3 tests/e2e/pngsize.py "$T/sheet2.png")
    cols=$(python3 -c "import math; print(min(8, math.ceil(math.sqrt($nt))))")
    rows=$(( (nt + cols - 1) / cols ))
    check "--size 64x48 sets the sheet's pictures ($s2)" '[ "$s2" = "$((cols * 80)) $((18 + rows * 84))" ]' "$s2"
fi

# ==== the text grid ====
expect_status "--gallery DIR --print" 0 "$Z" --gallery "$G" --print --size 100x20 --color none
tr -s ' ' <"$T/out" >"$T/grid"
check "every model is named in the grid" 'for f in $ntames; do grep -q " $f" "$T/grid" || exit 1; done' "$(cat "$T/grid" | head -40)"
check "files that are not models are left out" '! grep -q "notes.md\|demo.mtl\|sub.obj" "$T/grid"'
check "the counts: $nt models, 3 sound, 2 unreadable" 'grep -q "^$nt models: 3 sound, [0-9]* with problems, 2 unreadable" "$T/grid"' "$(tail -1 "$T/grid")"
# the verdicts under the names: the line after a row of names
verdict_of() {
    # the verdict sits under the name, in the tile's 20 columns
    line=$(grep -n " $1 " "$T/out" | head -1 | cut -d: -f1)
    [ -n "$line" ] || line=$(grep -n " $1\$" "$T/out" | head -1 | cut -d: -f1)
    col=$(sed -n "${line}p" "$T/out" | awk -v f="$1" '{ print index($0, " " f) }')
    sed -n "$((line + 1))p" "$T/out" | cut -c"$((col + 1))-$((col + 21))" | sed 's/ *$//'
}
check "cube.obj is sound" '[ "$(verdict_of cube.obj)" = sound ]' "$(verdict_of cube.obj)"
check "the broken file is unreadable" 'verdict_of broken.obj | grep -q "^unreadable: "' "$(verdict_of broken.obj)"
check "the link that loops says so" 'verdict_of loop.obj | grep -q "^unreadable: a link"' "$(verdict_of loop.obj)"
check "concave.obj has its holes" 'verdict_of concave.obj | grep -q "^[0-9]* holes\?"' "$(verdict_of concave.obj)"
"$Z" --gallery --all "$G" --print --size 100x20 --color none >"$T/all" 2>&1
check "--all lists the other files too" 'grep -q "notes.md" "$T/all" && grep -q "demo.mtl" "$T/all"' "$(tail -3 "$T/all")"
expect_status "zview DIR without a terminal prints the grid" 0 "$Z" "$G" --size 100x20 --color none
check "... the same grid" 'grep -q "^$nt models:" "$T/out"'
expect_status "--gallery without files is refused" 2 "$Z" --gallery
expect_err "... saying what it needs" "--gallery needs a folder"
expect_status "--gallery -o FILE.txt is refused" 2 "$Z" --gallery "$G" -o "$T/x.txt"
expect_status "a file that is not there is a tile" 0 "$Z" --gallery "$T/nothing-here.obj" --print --size 40x12 --color none
expect_out "... that says so" "unreadable: No such"

# a tile's loader warnings would land on the grid curses draws: none
# goes to stderr (the grid on the terminal is the same tiles' code)
mkdir -p "$T/mtlgone"
printf 'mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/mtlgone/a.obj"
"$Z" --gallery "$T/mtlgone" --print --size 40x12 --color none >"$T/out" 2>"$T/err"
check "a tile's loader warning (its MTL missing) stays off the screen" '[ ! -s "$T/err" ] && grep -q "a.obj" "$T/out"' \
    "$(head -c 300 "$T/err")"

# ==== the grid on the terminal ====
. "$(dirname "$0")/tmux.sh"
start 100 30 "$G"
if wait_for "$nt/$nt loaded"; then ok "the grid loads every tile"; else notok "the grid loads every tile" "$(status 30)"; fi
cap
check "tiles show names and verdicts" 'grep -q "> broken.obj" "$T/screen" && grep -q "unreadable: " "$T/screen" && grep -q "cube.obj" "$T/screen"' "$(cat "$T/screen")"
check "the status line counts sound and problem files" 'status 30 | grep -q "3 sound · $((nt - 3)) problems"' "$(status 30)"
picture 20 >"$T/g0"
check "tiles have pictures" '[ "$(tr -d " \n" <"$T/g0" | wc -c)" -gt 300 ]'
tm send-keys -t zv Right Right
if wait_for "> cube.obj"; then ok "the arrows move the selection"; else notok "the arrows move the selection" "$(cat "$T/screen")"; fi
# the selected tile turns once the screen is pictured
picture 9 >"$T/t0"
if wait_change "$T/t0" 9; then ok "the selected tile turns"; else notok "the selected tile turns"; fi
tm send-keys -t zv Enter
if wait_for "cube.obj \| faces 6 "; then ok "Enter opens the model in the viewer"; else notok "Enter opens the model in the viewer" "$(status 30)"; fi
tm send-keys -t zv q
if wait_for "> cube.obj" && wait_for "loaded ·"; then ok "q comes back to the grid at the same place"; else notok "q comes back to the grid at the same place" "$(cat "$T/screen")"; fi
tm send-keys -t zv Left Enter
if wait_for "concave.obj .*\| faces "; then ok "Enter opens another"; else notok "Enter opens another" "$(status 30)"; fi
tm send-keys -t zv Escape
if wait_for "> concave.obj" && wait_for "loaded ·"; then ok "Esc comes back to the grid too"; else notok "Esc comes back to the grid too" "$(cat "$T/screen")"; fi
tm send-keys -t zv End
if wait_for "> torus.obj"; then ok "End scrolls to the last tile"; else notok "End scrolls to the last tile" "$(cat "$T/screen")"; fi
check "... the first row scrolled off" '! grep -q "broken.obj" "$T/screen"' "$(cat "$T/screen")"
tm send-keys -t zv Home
wait_for "> broken.obj"
tm send-keys -t zv / t o r
if wait_for "/tor_"; then ok "/ opens the filter"; else notok "/ opens the filter" "$(status 30)"; fi
cap
check "the filter shows only the names that match" 'grep -q "> torus.obj" "$T/screen" && ! grep -q "cube.obj\|knot.obj" "$T/screen"' "$(cat "$T/screen")"
tm send-keys -t zv Escape
if wait_gone "/tor" && wait_for "knot.obj"; then ok "Esc clears the filter"; else notok "Esc clears the filter" "$(cat "$T/screen")"; fi
tm send-keys -t zv s
if wait_for "sort size"; then ok "s sorts by size"; else notok "s sorts by size" "$(status 30)"; fi
tm send-keys -t zv s s
if wait_for "sort verdict"; then ok "s cycles to the verdict"; else notok "s cycles to the verdict" "$(status 30)"; fi
tm send-keys -t zv Home
wait_for "> broken.obj|> loop.obj"
check "sorted by verdict, an unreadable file comes first" 'grep -Eq "^ > (broken|loop).obj +(broken|loop).obj" "$T/screen"' "$(sed -n 10p "$T/screen")"
tm send-keys -t zv q
if wait_for "zv-exit=0"; then ok "q quits the grid (status 0)"; else notok "q quits the grid (status 0)" "$(tail -3 "$T/screen")"; fi
