#!/bin/sh
# Where each problem is (issue 30): --check --json's locations held to
# the problems they name by locations.py's own computation from the OBJ
# text (hand-made models: a cube less a face, a cube with a face
# flipped, two cubes sharing an edge or a corner, a duplicate and a
# degenerate face, crossing faces, several objects; the assets; the
# teapot of ../shared/models when it is there), the JSON valid, the
# counts whole past --max-locations, the text report's lines under the
# counts; --problem K -o framing the K-th problem in the middle of the
# picture, and its refusals; and in the viewer . and , naming each
# problem in the status bar as the camera moves to it.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

# cube X Y Z OPEN FLIP: a unit cube's 8 vertices and its faces (OPEN: the
# face left out, 0 none; FLIP: the face written backwards, 0 none), its
# vertex numbers counted from the vertices already written ($nv)
nv=0
cube() {
    x=$1; y=$2; z=$3
    for c in "0 0 0" "1 0 0" "1 1 0" "0 1 0" "0 0 1" "1 0 1" "1 1 1" "0 1 1"; do
        set -- $c
        echo "v $(($1 + x)) $(($2 + y)) $(($3 + z))"
    done
    k=0
    for f in "1 4 3 2" "5 6 7 8" "1 2 6 5" "2 3 7 6" "3 4 8 7" "4 1 5 8"; do
        k=$((k + 1))
        [ "$k" = "$open" ] && continue
        set -- $f
        if [ "$k" = "$flip" ]; then
            echo "f $(($4 + nv)) $(($3 + nv)) $(($2 + nv)) $(($1 + nv))"
        else
            echo "f $(($1 + nv)) $(($2 + nv)) $(($3 + nv)) $(($4 + nv))"
        fi
    done
    nv=$((nv + 8))
}
mk() { nv=0; open=0; flip=0; }

mk; open=2; cube 0 0 0 >"$T/open.obj"
mk; flip=5; cube 0 0 0 >"$T/flip.obj"
mk; { cube 0 0 0; cube 1 1 0; } >"$T/edge.obj"
mk; { cube 0 0 0; cube 1 1 1; } >"$T/corner.obj"
mk; { cube 0 0 0; echo "v 0 0 0"; echo "v 2 0 0"; echo "v 5 0 0"; echo "f 9 10 11"; echo "f 2 3 7 6"; } >"$T/dupdeg.obj"
printf 'v 0 0 0\nv 4 0 0\nv 0 4 0\nv 1 1 -1\nv 1.25 1 -1\nv 1.125 1 1\nf 1 2 3\nf 4 5 6\n' >"$T/cross.obj"
printf 'v 10 0 0\nv 12 0 0\nv 12 2 0\nv 10 2 0\nv 11 -1 -1\nv 11 3 -1\nv 11 3 1\nv 11 -1 1\nf 7 8 9 10\nf 11 12 13 14\n' >>"$T/cross.obj"
# several objects: face numbers run on across them
mk; { echo "o first"; open=2; cube 0 0 0; echo "o second"; open=0; flip=3; cube 3 0 0; } >"$T/objects.obj"

# ==== the JSON, held to the OBJ ====
if need_python "--check --json: every location holds"; then
    for m in open flip edge corner dupdeg cross objects; do
        "$Z" --check --json "$T/$m.obj" >"$T/$m.json" 2>"$T/err"
        st=$?
        out=$(python3 tests/e2e/locations.py "$T/$m.obj" "$T/$m.json" 2>&1)
        check "--check --json $m.obj: status 3, valid JSON, every location holds" \
            '[ $st -eq 3 ] && echo "$out" | grep -q "^ok " && ! echo "$out" | grep -q "not ok"' "status $st: $out"
    done
    check "... the cube less a face: its one loop of 4" \
        'python3 -c "import json,sys; h=json.load(open(sys.argv[1]))[\"objects\"][0][\"locations\"][\"holes\"]; sys.exit(h[\"count\"] != 1 or h[\"items\"][0][\"edges\"] != 4)" "$T/open.json"' \
        "$(grep -A3 '"holes": {' "$T/open.json")"
    check "... the flipped face by its index" \
        'python3 -c "import json,sys; d=json.load(open(sys.argv[1])); sys.exit(d[\"objects\"][0][\"locations\"][\"inconsistent_faces\"][\"items\"] != [4])" "$T/flip.json"' \
        "$(grep -A2 inconsistent_faces "$T/flip.json" | tail -3)"
    check "... face numbers run on across objects" \
        'python3 -c "import json,sys; d=json.load(open(sys.argv[1])); sys.exit(d[\"objects\"][1][\"locations\"][\"inconsistent_faces\"][\"items\"] != [7])" "$T/objects.json"' \
        "$(grep -A2 inconsistent_faces "$T/objects.json")"
    for m in assets/*.obj; do
        "$Z" --check --json --max-locations 1000 "$m" >"$T/a.json" 2>/dev/null
        out=$(python3 tests/e2e/locations.py "$m" "$T/a.json" 1000 2>&1)
        check "--check --json $m: every location holds" '! echo "$out" | grep -q "not ok" && echo "$out" | grep -q "^ok "' "$out"
    done
    # the shared teapot: 6 holes, a non-manifold vertex, 161 crossing pairs
    tp=../shared/models/teapot.obj
    if [ -f "$tp" ]; then
        "$Z" --check --json --max-locations 1000 "$tp" >"$T/tp.json" 2>/dev/null
        out=$(python3 tests/e2e/locations.py "$tp" "$T/tp.json" 1000 2>&1)
        check "the teapot: 6 loops, 1 vertex, 161 crossing points, each holding" \
            'echo "$out" | grep -q "^ok teapot holes=6 .*nonmanifold_vertices=1 .*self_intersections=161$"' "$out"
    fi
    # --max-locations: the lists cut, the counts whole
    printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 9 0 0\nv 10 0 0\nv 9 1 0\nf 1 2 3\nf 4 5 6\nf 7 8 9\n' >"$T/three.obj"
    "$Z" --check --json --max-locations 2 "$T/three.obj" >"$T/three.json"
    out=$(python3 tests/e2e/locations.py "$T/three.obj" "$T/three.json" 2 2>&1)
    check "--max-locations 2: two of the three holes listed, the count 3" \
        'echo "$out" | grep -q "^ok .*holes=2" && grep -q "\"holes\": {\"count\": 3" "$T/three.json"' "$out"
    "$Z" --check --json --max-locations 0 "$T/three.obj" >"$T/three.json"
    check "--max-locations 0: none listed" 'grep -q "\"holes\": {\"count\": 3, \"items\": \[\]}" "$T/three.json"' \
        "$(grep holes "$T/three.json")"
    # a name that is not text stays a JSON string
    printf 'o "a\033]0;x\007\\b\n' >"$T/name.obj"
    sed -n '2,$p' "$T/open.obj" >>"$T/name.obj"
    "$Z" --check --json "$T/name.obj" >"$T/name.json" 2>/dev/null
    check "--check --json with locations stays valid JSON for a name with controls" \
        'python3 -m json.tool "$T/name.json" >/dev/null' "$(head -c 300 "$T/name.json")"
fi
expect_status "--max-locations -1 is a usage error" 2 "$Z" --check --json --max-locations -1 "$T/open.obj"

# ==== the text report ====
"$Z" --check "$T/objects.obj" >"$T/out" 2>&1
check "the text report lists the hole under its count" \
    'grep -A1 "^    edges  *4 boundary in 1 hole" "$T/out" | grep -Eq "^ *hole 1: 4 edges, perimeter 4, through \([01] [01] 1\) \([01] [01] 1\) \([01] [01] 1\) \.\.\.$"' "$(cat "$T/out")"
check "... and the flipped face by its index" 'grep -q "^ *flipped faces: 7$" "$T/out"' "$(cat "$T/out")"
"$Z" --check "$T/cross.obj" >"$T/out" 2>&1
check "... a crossing pair by its faces and a point" \
    'grep -A1 "^  crossing  *2 pairs of faces" "$T/out" | grep -Eq "crossing 1: faces 0 and 1, through \(1\.[0-9]+ 1 0\)"' "$(cat "$T/out")"
"$Z" --check "$T/three.obj" >"$T/out" 2>&1
check "... the first three of a kind" 'grep -q "^ *hole 3:" "$T/out" && ! grep -q "more" "$T/out"' "$(cat "$T/out")"
printf 'v 20 0 0\nv 21 0 0\nv 20 1 0\nf 10 11 12\n' >>"$T/three.obj"
"$Z" --check "$T/three.obj" >"$T/out" 2>&1
check "... then how many more" '! grep -q "^ *hole 4:" "$T/out" && grep -q "^ *(and 1 more hole)$" "$T/out"' "$(cat "$T/out")"
if need_python "--check --json lists more than the text report's three"; then
    "$Z" --check --json "$T/three.obj" >"$T/four.json"
    out=$(python3 tests/e2e/locations.py "$T/three.obj" "$T/four.json" 2>&1)
    check "--check --json lists more than the text report's three: all 4 holes" 'echo "$out" | grep -q "^ok .*holes=4"' "$out"
fi

# ==== --problem K ====
# the open cube beside a closed one: unframed, the hole is off the middle
mk; { open=2; cube 0 0 0; open=0; cube 4 0 0; } >"$T/pair.obj"
view="--size 200x150 --contrast 0 --view iso"
"$Z" -o "$T/plain.ppm" $view --problems "$T/pair.obj"
"$Z" -o "$T/framed.ppm" $view --problem 1 "$T/pair.obj"
st=$?
check "--problem 1 -o writes the picture (status 0)" '[ $st -eq 0 ] && [ -s "$T/framed.ppm" ]' "status $st"
check "... framed otherwise than without it" '! cmp -s "$T/plain.ppm" "$T/framed.ppm"' "the same picture"
if need_python "--problem 1 -o centres the hole"; then
    # the mean place of the hole's red, as a share of the width and height
    red() {
        python3 -c "
import sys
d = open(sys.argv[1], 'rb').read().split(None, 4)
w, h, px = int(d[1]), int(d[2]), d[4]
pts = [(i // 3 % w, i // 3 // w) for i in range(0, len(px) - 2, 3) if px[i:i + 3] == bytes((255, 48, 48))]
print('%d %.3f %.3f' % (len(pts), sum(p[0] for p in pts) / len(pts) / w, sum(p[1] for p in pts) / len(pts) / h) if pts else '0 0 0')" "$1"
    }
    set -- $(red "$T/plain.ppm")
    n=$1 x=$2 y=$3
    check "... unframed, the hole is off the middle ($x, $y)" \
        '[ "$n" -gt 0 ] && python3 -c "import sys; sys.exit(abs($x - 0.5) < 0.1 and abs($y - 0.5) < 0.1)"' "$n $x $y"
    set -- $(red "$T/framed.ppm")
    n=$1 x=$2 y=$3
    check "... framed, it is in the middle ($x, $y)" \
        '[ "$n" -gt 0 ] && python3 -c "import sys; sys.exit(not (abs($x - 0.5) < 0.06 and abs($y - 0.5) < 0.06))"' "$n $x $y"
fi
mk; { cube 0 0 0; cube 4 0 0; } >"$T/sound.obj"
"$Z" --print --size 60x20 --color none --view iso --problem 1 "$T/objects.obj" >"$T/p1" 2>"$T/err"
"$Z" --print --size 60x20 --color none --view iso --problem 2 "$T/objects.obj" >"$T/p2" 2>"$T/err"
st=$?
check "--problem 2 --print: the second problem, framed otherwise than the first" '[ $st -eq 0 ] && ! cmp -s "$T/p1" "$T/p2"' "status $st: $(cat "$T/err")"
expect_status "--problem past the last: status 1" 1 "$Z" -o "$T/x.png" --problem 5 "$T/pair.obj"
expect_err "... saying how many there are" "--problem 5: the check found 1 problem"
expect_status "--problem on a sound model: status 1" 1 "$Z" -o "$T/x.png" --problem 1 "$T/sound.obj"
expect_err "... saying so" "found no problem"
expect_status "--problem 0: a usage error" 2 "$Z" -o "$T/x.png" --problem 0 "$T/pair.obj"
expect_status "--problem with --turntable: a usage error" 2 "$Z" -o "$T/x%d.png" --turntable 4 --problem 1 "$T/pair.obj"

# ==== the viewer: . and , ====
. "$(dirname "$0")/tmux.sh"
start 100 30 --view iso "$T/objects.obj"
wait_for "faces 11 drawn" >/dev/null || notok "the viewer starts" "$(cat "$T/screen")"
wait_stable
picture 29 >"$T/before"
tm send-keys -t zv '.'
if wait_for 'hole 1 of 1 · 4 edges · 4'; then ok ". names the first problem: hole 1 of 1 · 4 edges · 4"; else
    notok ". names the first problem: hole 1 of 1 · 4 edges · 4" "$(status 30)"; fi
if wait_change "$T/before" 29; then ok "... and the camera moves to it"; else notok "... and the camera moves to it" "the picture did not change"; fi
wait_stable
picture 29 >"$T/hole"
tm send-keys -t zv '.'
if wait_for 'flipped face 1 of 1 · face 7'; then ok ". again: the next, flipped face 1 of 1 · face 7"; else
    notok ". again: the next, flipped face 1 of 1 · face 7" "$(status 30)"; fi
if wait_change "$T/hole" 29; then ok "... the camera moves again"; else notok "... the camera moves again" "the picture did not change"; fi
wait_stable
picture 29 >"$T/flipped"
tm send-keys -t zv ','
if wait_for 'hole 1 of 1'; then ok ", goes back"; else notok ", goes back" "$(status 30)"; fi
if wait_change "$T/flipped" 29; then ok "... the camera with it"; else notok "... the camera with it" "the picture did not change"; fi
tm send-keys -t zv '?'
wait_for 'zview keys' >/dev/null
# on the first page, or past it when the help scrolls (End: the last)
if ! WAIT_POLLS=20 wait_for '\. ,  +next / previous problem' && grep -q 'Up/Down' "$T/screen"; then
    tm send-keys -t zv End
fi
if wait_for '\. ,  +next / previous problem'; then ok "? lists . and ,"; else notok "? lists . and ," "$(cat "$T/screen")"; fi
tm send-keys -t zv Escape
wait_gone 'zview keys' >/dev/null
tm send-keys -t zv q
wait_for 'zv-exit=[0-9]' >/dev/null && prompt_back >/dev/null || notok "the viewer quits" "$(tail -3 "$T/screen")"
