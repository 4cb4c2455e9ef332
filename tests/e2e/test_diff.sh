#!/bin/sh
# zview --diff A B (issue 31): the exit status (0 the same, 3 they
# differ, 1 a file not read, 2 usage), --quiet, the text report and
# --json (read by python: the figures of a cube against the cube with a
# second added, an STL against the OBJ it came from), -o's picture read
# pixel by pixel (B's added cube green, nothing red; A alone shows no
# green; the heat map's ramp), --print and --turntable; git's difftool
# (-x 'zview --diff') and a textconv driver (zview --check --textconv)
# in a real repository; and the viewer under tmux: the headline in the
# status bar, V cycling A, B and the heat map, the picture the --print
# of the same view, O refused. The report the same bytes on 1, 2 and 3
# threads.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

# the unit cube (quads, outward), optionally moved by $1 along x
cube() {
    printf 'v %s 0 0\nv %s 0 0\nv %s 1 0\nv %s 1 0\nv %s 0 1\nv %s 0 1\nv %s 1 1\nv %s 1 1\n' \
        "$1" "$(($1 + 1))" "$(($1 + 1))" "$1" "$1" "$(($1 + 1))" "$(($1 + 1))" "$1"
}
faces() {
    o=$1
    printf 'f %d %d %d %d\nf %d %d %d %d\nf %d %d %d %d\nf %d %d %d %d\nf %d %d %d %d\nf %d %d %d %d\n' \
        $((o + 1)) $((o + 4)) $((o + 3)) $((o + 2)) $((o + 5)) $((o + 6)) $((o + 7)) $((o + 8)) \
        $((o + 1)) $((o + 2)) $((o + 6)) $((o + 5)) $((o + 2)) $((o + 3)) $((o + 7)) $((o + 6)) \
        $((o + 3)) $((o + 4)) $((o + 8)) $((o + 7)) $((o + 4)) $((o + 1)) $((o + 5)) $((o + 8))
}
{ cube 0; faces 0; } >"$T/cube.obj"
{ cube 0; cube 3; faces 0; faces 8; } >"$T/two.obj"
sed 's/^v 1 1 1$/v 1.1 1.1 1.1/' "$T/cube.obj" >"$T/moved.obj"
grep -v '^f 4 1 5 8$' "$T/cube.obj" >"$T/open.obj"

# ==== exit status ====
expect_status "a model against itself: status 0" 0 "$Z" --diff "$T/cube.obj" "$T/cube.obj"
expect_out "... and the report says the same" "verdict: the same (max 0)"
expect_status "a vertex moved: status 3" 3 "$Z" --diff "$T/cube.obj" "$T/moved.obj"
expect_out "... max 0.173 (0.1 along each axis), one region" "max 0.173 · 1 region changed"
expect_status "within --tolerance 0.2 the two are the same: status 0" 0 "$Z" --diff --tolerance 0.2 "$T/cube.obj" \
    "$T/moved.obj"
expect_out "... and the report names the tolerance given" "tolerance     0.2 (--tolerance)"
expect_status "a file that cannot be read: status 1" 1 "$Z" --diff "$T/cube.obj" "$T/nothing.obj"
expect_err "... named in one line" "nothing.obj"
expect_status "one file: usage, status 2" 2 "$Z" --diff "$T/cube.obj"
expect_err "... the message says two files" "--diff compares two files"
expect_status "--tolerance without --diff: status 2" 2 "$Z" --tolerance 1 "$T/cube.obj"
expect_status "a negative --tolerance: status 2" 2 "$Z" --diff --tolerance -1 "$T/cube.obj" "$T/cube.obj"
expect_status "--diff --check: status 2" 2 "$Z" --diff --check "$T/cube.obj" "$T/cube.obj"
printf 'v 0 0 0\nv 1 0 0\n' >"$T/points.obj"
expect_status "a model without faces: status 1" 1 "$Z" --diff "$T/cube.obj" "$T/points.obj"
expect_err "... it says why" "no faces (--diff compares surfaces)"
# B loads beside A on two threads, quietly: its warnings (and its error)
# are still said, after A's, as when the two load in turn
{ echo "mtllib a-none.mtl"; cat "$T/cube.obj"; } >"$T/warn-a.obj"
{ echo "mtllib b-none.mtl"; cat "$T/moved.obj"; } >"$T/warn-b.obj"
for j in 1 2; do
    "$Z" --threads $j --diff --quiet "$T/warn-a.obj" "$T/warn-b.obj" 2>"$T/werr$j"
    check "-j $j: A's missing MTL warned, then B's" \
        'sed -n 1p "$T/werr$j" | grep -q a-none.mtl && sed -n 2p "$T/werr$j" | grep -q b-none.mtl && [ "$(wc -l <"$T/werr$j")" -eq 2 ]' \
        "stderr: $(cat "$T/werr$j")"
done
check "... the same bytes on 1 and 2 threads" 'cmp -s "$T/werr1" "$T/werr2"' "$(cat "$T/werr2")"
expect_status "-j 2: B that cannot be read, after A's warning: status 1" 1 "$Z" --threads 2 --diff "$T/warn-a.obj" \
    "$T/nothing.obj"
expect_err "... the warning and the error both said" "a-none.mtl"
out=$("$Z" --diff --quiet "$T/cube.obj" "$T/moved.obj" || echo changed)
check "--quiet prints nothing: zview --diff --quiet a b || echo changed" '[ "$out" = changed ]' "got '$out'"
out=$("$Z" --diff --quiet "$T/cube.obj" "$T/cube.obj" || echo changed)
check "... and nothing for the same" '[ -z "$out" ]' "got '$out'"

# ==== the report as JSON ====
if need_python "--json: the figures of a cube added"; then
    "$Z" --diff --json "$T/cube.obj" "$T/two.obj" >"$T/j.json"
    st=$?
    check "--json: status 3 for a cube added" '[ $st -eq 3 ]' "status $st"
    if python3 - "$T/j.json" >"$T/py" 2>&1 <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["same"] is False, d["same"]
assert abs(d["added_area"] - 6) < 1e-9, d["added_area"]
assert d["removed_area"] == 0, d["removed_area"]
assert d["regions_count"] == 1 and len(d["regions"]) == 1
r = d["regions"][0]
assert abs(r["added_area"] - 6) < 1e-9 and r["faces_b"] == 6 and r["box_min"][0] == 3 and r["box_max"][0] == 4, r
assert d["hausdorff"] == 3 and d["b"]["distance_max"] == 3 and d["a"]["distance_max"] == 0
assert d["a"]["faces"] == 6 and d["b"]["faces"] == 12 and d["b"]["vertices"] == 16
assert d["area_change"] == 6 and d["volume_change"] == 1
assert d["a"]["watertight"] is True and d["b"]["watertight"] is True and d["a"]["crossings_tested"] is False
assert d["b"]["samples"]["vertices"] == 16 and d["b"]["samples"]["faces"] > 60000
assert d["tolerance_given"] is False and abs(d["tolerance"] - 1e-3 * 18 ** 0.5) < 1e-9
EOF
    then ok "--json: added area 6, one region from x 3 to 4, max 3, the check of each side"; else
        notok "--json: added area 6, one region from x 3 to 4, max 3, the check of each side" "$(cat "$T/py")"; fi
    "$Z" --diff --json "$T/cube.obj" "$T/open.obj" >"$T/j.json"
    if python3 -c "
import json, sys
d = json.load(open('$T/j.json'))
assert d['a']['watertight'] and not d['b']['watertight'] and d['b']['holes'] == 1, d['b']
assert d['a']['ok'] and not d['b']['ok'] and d['b']['problems'] == ['1 hole (4 boundary edges)'], d['b']['problems']
" 2>"$T/py"; then ok "--json: a face taken away: B not watertight, 1 hole"; else
        notok "--json: a face taken away: B not watertight, 1 hole" "$(cat "$T/py")"; fi
    "$Z" --diff "$T/cube.obj" "$T/open.obj" >"$T/out"
    expect_out "... and the report's headline says so" "verdict: no longer watertight (1 hole) · max 0.5"
    # an STL of the same cube (its quads as two triangles each) is the same
    python3 - "$T/cube.obj" "$T/cube.stl" <<'EOF'
import sys
v, out = [], ["solid cube"]
for line in open(sys.argv[1]):
    w = line.split()
    if w and w[0] == "v":
        v.append(w[1:4])
    elif w and w[0] == "f":
        c = [v[int(i) - 1] for i in w[1:]]
        for k in range(1, len(c) - 1):
            out += ["facet normal 0 0 0", "outer loop"] + ["vertex " + " ".join(p) for p in (c[0], c[k], c[k + 1])] + ["endloop", "endfacet"]
open(sys.argv[2], "w").write("\n".join(out + ["endsolid cube", ""]))
EOF
    expect_status "an STL against the OBJ it came from: the same, status 0" 0 "$Z" --diff --tolerance 0 "$T/cube.stl" \
        "$T/cube.obj"
    expect_out "... max 0" "verdict: the same (max 0)"
fi

# ==== the same on any threads ====
# a wavy sheet of 150 x 150 quads against a copy with every vertex moved
# and a raised patch: several chunks of samples on each side, shared
# between the threads beside the checks; the report and the JSON the
# same bytes on 1, 2 and 3 threads
sheet() {
    awk -v bump="$1" 'BEGIN {
        n = 150; s = 12345
        for (j = 0; j <= n; j++) for (i = 0; i <= n; i++) {
            x = i / n; y = j / n; z = 0.05 * sin(9 * x) * cos(7 * y)
            if (bump) { s = (s * 1103515245 + 12345) % 2147483648; z += (s / 2147483648 - 0.5) * 2e-3
                        if (i > 50 && i < 75 && j > 50 && j < 75) z += 0.01 }
            printf "v %.7g %.7g %.7g\n", x, y, z
        }
        for (j = 0; j < n; j++) for (i = 0; i < n; i++) {
            v = j * (n + 1) + i + 1
            printf "f %d %d %d %d\n", v, v + 1, v + n + 2, v + n + 1
        }
    }'
}
sheet 0 >"$T/sheet.obj"
sheet 1 >"$T/sheet2.obj"
for j in 1 2 3; do
    "$Z" --diff -j $j "$T/sheet.obj" "$T/sheet2.obj" >"$T/sheet-$j.txt"
    "$Z" --diff --json -j $j "$T/sheet.obj" "$T/sheet2.obj" >"$T/sheet-$j.json"
done
check "-j 1, 2 and 3: the same report, byte for byte" \
    'cmp -s "$T/sheet-1.txt" "$T/sheet-2.txt" && cmp -s "$T/sheet-1.txt" "$T/sheet-3.txt"' \
    "$(diff "$T/sheet-1.txt" "$T/sheet-2.txt" | head -5)"
check "... and the same JSON" 'cmp -s "$T/sheet-1.json" "$T/sheet-2.json" && cmp -s "$T/sheet-1.json" "$T/sheet-3.json"' \
    "$(diff "$T/sheet-1.json" "$T/sheet-2.json" | head -5)"
check "... which finds the raised patch: one region or more" 'grep -q "regions  *[1-9]" "$T/sheet-1.txt"' \
    "$(cat "$T/sheet-1.txt")"

# ==== the picture ====
if need_python "-o: the diff's colours, pixel by pixel"; then
    # count pixels of the added green (40, 190, 75) and the removed red
    # (225, 45, 45) lit by any light: a hue test on the PPM
    cat >"$T/hues.py" <<'EOF'
import sys
d = open(sys.argv[1], "rb").read()
head = d.split(None, 4)
px = head[4]
green = red = grey = 0
for i in range(0, len(px) - 2, 3):
    r, g, b = px[i], px[i + 1], px[i + 2]
    if g > r + 40 and g > b + 40:
        green += 1
    elif r > g + 40 and r > b + 40:
        red += 1
    elif max(r, g, b) - min(r, g, b) < 16 and r > 40:
        grey += 1
print(green, red, grey)
EOF
    hues() { python3 "$T/hues.py" "$1" >"$T/hues" && read -r green red grey <"$T/hues"; }
    "$Z" --diff -o "$T/d.ppm" --size 160x120 --contrast 0 --bg black "$T/cube.obj" "$T/two.obj" >/dev/null
    hues "$T/d.ppm"
    check "-o: the added cube is green ($green pixels), the unchanged one grey ($grey), nothing red ($red)" \
        '[ "$green" -gt 500 ] && [ "$red" -eq 0 ] && [ "$grey" -gt 500 ]' "$green $red $grey"
    "$Z" --diff -o "$T/d.ppm" --size 160x120 --contrast 0 --bg black --show a "$T/cube.obj" "$T/two.obj" >/dev/null
    hues "$T/d.ppm"
    check "--show a: A alone, no green ($green)" '[ "$green" -eq 0 ] && [ "$grey" -gt 500 ]' "$green $red $grey"
    "$Z" --diff -o "$T/d.ppm" --size 160x120 --contrast 0 --bg black "$T/two.obj" "$T/cube.obj" >/dev/null
    hues "$T/d.ppm"
    check "the other way round: the cube taken away is red ($red pixels)" '[ "$red" -gt 500 ] && [ "$green" -eq 0 ]' \
        "$green $red $grey"
    "$Z" --diff -o "$T/h.ppm" --size 160x120 --contrast 0 --bg black --show heat "$T/cube.obj" "$T/two.obj" >/dev/null
    n=$(python3 -c "
d = open('$T/h.ppm', 'rb').read().split(None, 4)[4]
print(sum(1 for i in range(0, len(d) - 2, 3) if d[i + 2] > d[i] + 30))")
    check "--show heat: the unchanged cube in the ramp's blue ($n pixels)" '[ "$n" -gt 300 ]' "$n"
fi
"$Z" --diff --print --size 40x12 --color 256 "$T/cube.obj" "$T/two.obj" >"$T/both" 2>&1
"$Z" --diff --print --size 40x12 --color 256 --show a "$T/cube.obj" "$T/two.obj" >"$T/a" 2>&1
st=$?
check "--print: the picture, then the report" 'grep -q "▀\|▄\|█" "$T/both" && grep -q "^verdict: max 3" "$T/both"' \
    "$(head -c 300 "$T/both")"
check "--show a draws another picture (no second cube), status 3" '[ $st -eq 3 ] && ! cmp -s "$T/both" "$T/a"' \
    "status $st"
rm -f "$T"/t-*.png
"$Z" --diff --quiet --turntable 3 -o "$T/t-%d.png" --size 64x48 "$T/cube.obj" "$T/moved.obj"
check "--turntable: three frames" '[ -s "$T/t-0.png" ] && [ -s "$T/t-1.png" ] && [ -s "$T/t-2.png" ] && ! cmp -s "$T/t-0.png" "$T/t-1.png"' \
    "$(ls "$T")"

# ==== git: difftool and a textconv driver, in a real repository ====
if command -v git >/dev/null 2>&1; then
    G=$T/repo
    mkdir "$G"
    (
        cd "$G" && git init -q && git config user.email t@example.com && git config user.name t &&
            git config diff.zview.textconv "$Z --check --textconv" &&
            echo '*.obj diff=zview' >.gitattributes && cp "$T/cube.obj" part.obj &&
            git add .gitattributes part.obj && git commit -qm cube && cp "$T/open.obj" part.obj
    )
    (cd "$G" && git --no-pager diff part.obj) >"$T/gd" 2>&1
    check "git diff with the textconv driver shows the check's lines that changed" \
        'grep -q "^-  edges  *0 boundary in 0 holes" "$T/gd" && grep -q "^+  edges  *4 boundary in 1 hole" "$T/gd" && grep -q "^+verdict: model: 1 hole" "$T/gd"' \
        "$(cat "$T/gd")"
    check "... naming no temporary file" '! grep -q "tmp\|part.obj (obj)" "$T/gd"' "$(grep tmp "$T/gd")"
    (cd "$G" && git difftool -y -x "$Z --diff" part.obj) >"$T/gt" 2>&1
    check "git difftool -x 'zview --diff' prints the diff (no terminal)" \
        'grep -q "^verdict: no longer watertight (1 hole)" "$T/gt" && grep -q "^A  .*part.obj (obj)" "$T/gt"' "$(cat "$T/gt")"
    (cd "$G" && git difftool -y --trust-exit-code -x "$Z --diff --quiet" part.obj) >/dev/null 2>&1
    st=$?
    check "... and with --trust-exit-code its status says they differ" '[ $st -ne 0 ]' "status $st"
else
    skip "git difftool and textconv" "no git"
fi

. "$(dirname "$0")/tmux.sh"

# ==== the viewer ====
start 100 30 --diff --view iso "$T/cube.obj" "$T/two.obj"
if wait_for 'max 3 · 1 region changed'; then ok "the viewer: the headline in the status bar"; else
    notok "the viewer: the headline in the status bar" "$(status 30)"; fi
if need_python "the viewer draws what --print draws for the diff"; then
    wait_stable
    looks 29 >"$T/viewer"
    print_looks --diff --view iso --size 100x29 --color 256 "$T/cube.obj" "$T/two.obj" >"$T/printed.all"
    head -n 29 "$T/printed.all" | sed -e :a -e '/^\n*$/{$d;N;ba' -e '}' >"$T/printed"
    check "the viewer draws what --print draws for the diff, colours included" 'cmp -s "$T/viewer" "$T/printed"' \
        "$(diff "$T/viewer" "$T/printed" | head -5)"
fi
cap
picture 29 >"$T/before"
tm send-keys -t zv V
if wait_for 'A alone'; then ok "V: A alone"; else notok "V: A alone" "$(status 30)"; fi
if wait_change "$T/before" 29; then ok "... the picture changes"; else notok "... the picture changes" "the same"; fi
tm send-keys -t zv V
if wait_for 'B alone'; then ok "V again: B alone"; else notok "V again: B alone" "$(status 30)"; fi
tm send-keys -t zv V
if wait_for 'heat: blue 0 to yellow 3'; then ok "V again: the heat map and its scale"; else
    notok "V again: the heat map and its scale" "$(status 30)"; fi
tm send-keys -t zv V
if wait_for 'both models'; then ok "V again: both"; else notok "V again: both" "$(status 30)"; fi
tm send-keys -t zv O
if wait_for 'O, X and E are off'; then ok "O in a diff: refused with a note"; else
    notok "O in a diff: refused with a note" "$(status 30)"; fi
tm send-keys -t zv q
if wait_for 'zv-exit=3'; then ok "quitting a diff that differs: status 3"; else
    notok "quitting a diff that differs: status 3" "$(tail -3 "$T/screen")"; fi
