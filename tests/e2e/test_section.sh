#!/bin/sh
# Section planes (issue 32): --section's words and refusals; --check
# --json's and the text report's figures of each plane (the unit cube at
# z = 0.5: area 1, perimeter 4, one loop; a box less a face: its open
# chain and where it ends); -o and --print cut and capped (the cap's colour where the top
# was); and in the viewer / cutting, ; and ' sliding the plane with the
# status bar following it, \ turning it, ? listing the keys.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

cube() {    # the cube [0, 1]^3, without face $1 (0: closed)
    printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n'
    k=0
    for f in "1 4 3 2" "5 6 7 8" "1 2 6 5" "2 3 7 6" "3 4 8 7" "4 1 5 8"; do
        k=$((k + 1))
        [ "$k" = "$1" ] || echo "f $f"
    done
}
cube 0 >"$T/cube.obj"
cube 4 >"$T/open.obj"

# ==== the words ====
"$Z" --section w=1 --print "$T/cube.obj" >/dev/null 2>"$T/err"; st=$?
check "--section w=1 is refused (status 2) with what it should be" \
    '[ $st -eq 2 ] && grep -q "AXIS=VALUE" "$T/err"' "status $st: $(cat "$T/err")"
"$Z" --section 0,0,0:0,0,0 --print "$T/cube.obj" >/dev/null 2>"$T/err"; st=$?
check "--section with a zero normal is refused" '[ $st -eq 2 ] && grep -q "normal" "$T/err"' "status $st: $(cat "$T/err")"
"$Z" --section z=0 --section z=1 --section x=0 --section y=0 --section y=1 --print "$T/cube.obj" >/dev/null 2>"$T/err"; st=$?
check "a fifth --section is refused" '[ $st -eq 2 ] && grep -q "at most 4" "$T/err"' "status $st: $(cat "$T/err")"

# ==== --check --json ====
"$Z" --check --json --section z=0.5 --section 0.5,0.5,0.5:1,0,0 "$T/cube.obj" >"$T/cube.json" 2>"$T/err"; st=$?
check "--check --json --section: the unit cube at z=0.5 has area 1, perimeter 4, one loop" \
    '[ $st -eq 0 ] && grep -q "{ \"plane\": \"z=0.5\", \"area\": 1, \"perimeter\": 4, \"loops\": 1, \"open_chains\": 0, \"open_ends\": \[\] }" "$T/cube.json"' \
    "status $st: $(grep -A3 sections "$T/cube.json")"
check "... and at x=0.5 by a point and a normal, the same" \
    'grep -q "\"plane\": \"0.5,0.5,0.5:1,0,0\", \"area\": 1, \"perimeter\": 4, \"loops\": 1" "$T/cube.json"' \
    "$(grep -A3 sections "$T/cube.json")"
if need_python "--check --json --section: valid JSON"; then
    check "... valid JSON" 'python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$T/cube.json"' "$(cat "$T/cube.json")"
fi
"$Z" --check --json --section z=0.5 "$T/open.obj" >"$T/open.json" 2>"$T/err"; st=$?
check "a box less its x=1 face: no loop, one open chain from (1,1,0.5) to (1,0,0.5), perimeter 3" \
    '[ $st -eq 3 ] && grep -q "\"area\": 0, \"perimeter\": 3, \"loops\": 0, \"open_chains\": 1, \"open_ends\": \[\[\[1, 1, 0.5\], \[1, 0, 0.5\]\]\]" "$T/open.json"' \
    "status $st: $(grep -A3 sections "$T/open.json")"
# the text report says the same, a line a plane
"$Z" --check --section z=0.5 "$T/cube.obj" >"$T/cube.txt" 2>"$T/err"; st=$?
check "--check --section (text): the unit cube at z=0.5, area 1, perimeter 4, one loop" \
    '[ $st -eq 0 ] && grep -qx "  section       z=0.5: area 1, perimeter 4, 1 closed loop, 0 open chains" "$T/cube.txt"' \
    "status $st: $(cat "$T/cube.txt" "$T/err")"
"$Z" --check --section z=0.5 --section 0.5,0.5,0.5:1,0,0 "$T/open.obj" >"$T/open.txt" 2>"$T/err"; st=$?
check "... the open box: no loop, one open chain and its ends; the second plane on its own line" \
    '[ $st -eq 3 ] && grep -qx "  section       z=0.5: area 0, perimeter 3, 0 closed loops, 1 open chain (from 1 1 0.5 to 1 0 0.5)" "$T/open.txt" &&
     grep -q "^  section       0.5,0.5,0.5:1,0,0: area " "$T/open.txt"' "status $st: $(cat "$T/open.txt" "$T/err")"
"$Z" --check "$T/cube.obj" >"$T/plain.txt"
check "... and without --section no section line" '! grep -q "section" "$T/plain.txt"' "$(cat "$T/plain.txt")"
"$Z" --check --json "$T/cube.obj" >"$T/plain.json"
check "without --section no sections member" '! grep -q "\"sections\"" "$T/plain.json"' ""

# ==== pictures ====
"$Z" --print --size 40x20 --color 256 --view top "$T/cube.obj" >"$T/whole.txt"
"$Z" --print --size 40x20 --color 256 --view top --section z=0.5 "$T/cube.obj" >"$T/cut.txt"; st=$?
check "--print --section: status 0, another picture" '[ $st -eq 0 ] && ! cmp -s "$T/whole.txt" "$T/cut.txt"' "status $st"
"$Z" -o "$T/a.ppm" --size 64x64 --view top "$T/cube.obj" --section y=0.5 --section x=0.5; st=$?
check "-o with two planes: status 0" '[ $st -eq 0 ] && [ -s "$T/a.ppm" ]' "status $st"
if need_python "-o --section: the cap's colour where the top was cut away"; then
    out=$(python3 - "$T/a.ppm" <<'PY'
import sys
d = open(sys.argv[1], 'rb').read()
parts = d.split(b'\n', 3)
w, h = map(int, parts[1].split())
px = parts[3]
def at(x, y):
    i = 3 * (y * w + x)
    return px[i], px[i + 1], px[i + 2]
# from the top (down y): x to the right; the half x > 0.5 cut down to y = 0.5
left, right = at(w // 4, h // 2), at(3 * w // 4, h // 2)
redder = lambda c: c[0] > c[1] + 60 and c[0] > c[2] + 60
print("ok" if redder(right) and not redder(left) else "no", left, right)
PY
)
    check "... the cap (red) where the top was cut away, the top (grey) where it was not" \
        'echo "$out" | grep -q "^ok"' "$out"
fi

# ==== the viewer ====
. "$(dirname "$0")/tmux.sh"
start 100 30 --view iso "$T/cube.obj"
wait_for "faces 6 drawn" >/dev/null || notok "the viewer starts" "$(cat "$T/screen")"
tm send-keys -t zv '/'
if wait_for 'cut z=0.5 area 1'; then ok "/ cuts at z through the middle: the status bar says cut z=0.5 area 1"; else
    notok "/ cuts at z through the middle" "$(status 30)"; fi
tm send-keys -t zv "'"
if wait_for 'cut z=0.52 area 1'; then ok "' slides the plane by a fiftieth: z=0.52"; else
    notok "' slides the plane" "$(status 30)"; fi
tm send-keys -t zv '\;'
tm send-keys -t zv '\;'
if wait_for 'cut z=0.48 area 1'; then ok "; slides it back"; else notok "; slides it back" "$(status 30)"; fi
tm send-keys -t zv '\'
if wait_for 'cut x=0.5 area 1'; then ok "\\ turns it to x through the middle"; else notok "\\ turns it" "$(status 30)"; fi
# C: the view's command line cuts as the viewer does, and gives the
# same picture back
wait_stable
if need_python "C gives the cut picture back"; then looks 29 >"$T/before"; fi
tm send-keys -t zv C
wait_for 'command line of this view' >/dev/null || notok "C shows the command line" "$(cat "$T/screen")"
sed -n 's/^ *| \(.*\) *| *$/\1/p' "$T/screen" | sed 's/[[:space:]]*$//' | sed -n '/^zview /,$p' |
    sed -e ':a' -e '/ \\$/{N; s/ \\\n/ /; ba' -e '}' >"$T/cmd"
check "C writes the plane: --section x=0.5" 'grep -q -- " --section x=0.5" "$T/cmd"' "$(cat "$T/cmd")"
if need_python "C gives the cut picture back"; then
    sh -c "$(sed "s|^zview|\"$Z\" --print --size 100x29 --color 256|" "$T/cmd")" | python3 tests/e2e/looks.py >"$T/again"
    check "the command C wrote gives the cut picture back" 'cmp -s "$T/before" "$T/again"' "$(diff "$T/before" "$T/again" | head -3)"
    "$Z" --print --size 100x29 --color 256 --view iso "$T/cube.obj" | python3 tests/e2e/looks.py >"$T/whole"
    check "... which is not the whole cube's" '! cmp -s "$T/whole" "$T/again"' ""
fi
tm send-keys -t zv Escape
wait_gone 'command line of this view' >/dev/null
tm send-keys -t zv '/'
if wait_for 'cut off'; then ok "/ again: the model whole"; else notok "/ again" "$(status 30)"; fi
tm send-keys -t zv '?'
wait_for 'zview keys' >/dev/null
# on the first page, or past it when the help scrolls (End: the last)
if ! WAIT_POLLS=20 wait_for "/ ; ' .* +cut: on, slide" && grep -q 'Up/Down' "$T/screen"; then
    tm send-keys -t zv End
fi
if wait_for "/ ; ' .* +cut: on, slide, turn, next"; then ok "? lists / ; ' \\ |"; else notok "? lists the cut's keys" "$(cat "$T/screen")"; fi
tm send-keys -t zv Escape
wait_gone 'zview keys' >/dev/null
tm send-keys -t zv q
wait_for 'zv-exit=[0-9]' >/dev/null && prompt_back >/dev/null || notok "the viewer quits" "$(tail -3 "$T/screen")"
