#!/bin/sh
# Will it print, and its measures (issue 32): --bed's known answers (a
# 10 cube on a 5 bed fits no order of its axes; a 10 x 20 x 5 part fits
# a 21 x 11 x 6 bed turned a quarter), the unit a size suggests and
# --unit's scaling, --overhang's area (a 3-4-5 tilted plate: 100 past
# 45 degrees, 150 past 30) in text and JSON and its colour in -o,
# --thickness and --min-thickness on a hollow box with walls 2 thick,
# --measure between known vertices (text, JSON, refusals), and the
# viewer's status bar with --thickness.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

# box FILE X0 Y0 Z0 X1 Y1 Z1 [in] [BASE]: an axis-aligned box facing
# out (in: a cavity, facing in), its vertices numbered from BASE + 1
box() {
    f=$1 a=$2 b=$3 c=$4 d=$5 e=$6 g=$7 dir=${8:-out} n=${9:-0}
    printf 'v %s %s %s\nv %s %s %s\nv %s %s %s\nv %s %s %s\n' $a $b $c $d $b $c $d $e $c $a $e $c >>"$f"
    printf 'v %s %s %s\nv %s %s %s\nv %s %s %s\nv %s %s %s\n' $a $b $g $d $b $g $d $e $g $a $e $g >>"$f"
    for q in "1 4 3 2" "5 6 7 8" "1 2 6 5" "2 3 7 6" "3 4 8 7" "4 1 5 8"; do
        set -- $q
        if [ "$dir" = in ]; then echo "f $(($4 + n)) $(($3 + n)) $(($2 + n)) $(($1 + n))"; else
            echo "f $(($1 + n)) $(($2 + n)) $(($3 + n)) $(($4 + n))"; fi >>"$f"
    done
}
box "$T/cube.obj" 0 0 0 10 10 10
box "$T/part.obj" 0 0 0 10 20 5
box "$T/hollow.obj" 0 0 0 20 20 20
box "$T/hollow.obj" 2 2 2 18 18 18 in 8
box "$T/inch.obj" 0 0 0 1.5 0.75 0.25
# the plate on a 3-4-5 slope (z up): its underside faces (3, 0, -4) / 5
{ printf 'v 0 0 0\nv 8 0 6\nv 5 0 10\nv -3 0 4\nv 0 10 0\nv 8 10 6\nv 5 10 10\nv -3 10 4\n'
  printf 'f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n'; } >"$T/plate.obj"

# ==== --bed ====
expect_status "--bed turns --check on: a sound cube exits 0" 0 "$Z" "$T/cube.obj" --bed 5x5x5
expect_out "a 10 cube on a 5 bed fits no order" "bed           5 x 5 x 5: does not fit in any order of its axes"
expect_status "the part on a 21x11x6 bed" 0 "$Z" --check --up z "$T/part.obj" --bed 21x11x6
expect_out "it fits turned a quarter, y along W" "fits turned a quarter about the vertical (y x z along the bed's W D H)"
expect_status "the part on a 21x21x6 bed" 0 "$Z" --check --up z "$T/part.obj" --bed 21x21x6
expect_out "as it stands, and one other order" "fits as it stands (x y z along the bed's W D H); 1 other order too"
if need_python "--bed in JSON: fits and the six orders"; then
    "$Z" --check --json --up z "$T/part.obj" --bed 21x11x6 >"$T/j" 2>"$T/err"
    got=$(python3 -c "
import json; f = json.load(open('$T/j'))['files'][0]['bed']
print(f['fits'], f['size'], [o['axes'] for o in f['orders'] if o['fits']], len(f['orders']))")
    check "--bed in JSON: fits and the six orders" '[ "$got" = "True [21, 11, 6] ['"'"'y x z'"'"'] 6" ]' "got $got"
fi
expect_status "--bed with --diff is refused" 2 "$Z" --diff "$T/cube.obj" "$T/part.obj" --bed 5x5x5
expect_err "... saying it goes with --check" "--bed goes with --check, not --diff"
expect_status "--bed 10x10 is refused" 2 "$Z" "$T/cube.obj" --bed 10x10
expect_err "... naming what it wants" "bad value '10x10' for --bed (WxDxH"

# ==== units ====
expect_status "a part of 1.5 x 0.75 x 0.25" 0 "$Z" --check "$T/inch.obj"
expect_out "the size suggests inches" "none stated; the size suggests inches (--unit in takes them so)"
expect_out "... and nothing is rescaled" "size          1.5 x 0.75 x 0.25 (file units; the format states none)"
expect_status "--unit in" 0 "$Z" --check "$T/inch.obj" --unit in
expect_out "the figures in mm" "size          38.1 x 19.05 x 6.35 mm"
expect_out "... and it says so" "unit          inches (--unit in), the figures in mm"
expect_status "a 10 cube suggests nothing" 0 "$Z" --check "$T/cube.obj"
check "... no unit line" '! grep -q "^  unit" "$T/out"' "$(grep unit "$T/out")"
if need_python "--unit in JSON: unit mm, unit_given in"; then
    "$Z" --check --json "$T/inch.obj" --unit in >"$T/j" 2>"$T/err"
    got=$(python3 -c "
import json; f = json.load(open('$T/j'))['files'][0]
print(f['unit'], f['unit_given'], f['unit_guess'], [round(x, 4) for x in f['size']])")
    check "--unit in JSON: unit mm, unit_given in" '[ "$got" = "mm in None [38.1, 19.05, 6.35]" ]' "got $got"
fi
expect_status "--unit ft is refused" 2 "$Z" --check "$T/cube.obj" --unit ft

# ==== --overhang ====
expect_status "--check --overhang on the tilted plate" 0 "$Z" --check --up z --overhang "$T/plate.obj"
expect_out "its underside: 100 past 45 degrees" "overhang      100 of faces past 45 degrees from the vertical"
expect_status "--overhang=30" 0 "$Z" --check --up z --overhang=30 "$T/plate.obj"
expect_out "the low end too: 150 past 30" "overhang      150 of faces past 30 degrees from the vertical"
expect_status "--overhang=90 is refused" 2 "$Z" --check --overhang=90 "$T/plate.obj"
if need_python "--overhang in -o: the underside red, none without it"; then
    for w in "" --overhang; do
        "$Z" -o "$T/p$w.ppm" --size 120x90 --contrast 0 --up z --view bottom $w "$T/plate.obj" 2>"$T/err"
    done
    n=$(python3 -c "
def red(p):
    d = open(p, 'rb').read(); h = d.split(b'\n', 3); px = h[3]
    return sum(1 for i in range(0, len(px), 3) if px[i] > 2 * px[i + 1] + 20 and px[i] > 60)
print(red('$T/p.ppm'), red('$T/p--overhang.ppm'))")
    check "--overhang in -o: the underside red, none without it" '[ "${n% *}" -eq 0 ] && [ "${n#* }" -gt 1000 ]' "red pixels: $n"
fi

# ==== thickness ====
expect_status "--min-thickness on the hollow box" 0 "$Z" "$T/hollow.obj" --min-thickness 2.5
expect_out "the thinnest wall is 2" "thickness     thinnest 2 at "
expect_out "... every face measured, median 2" "median 2; 12 of 12 faces measured"
expect_out "... all its area is thinner than 2.5" "thin walls    3936 thinner than 2.5"
expect_status "--min-thickness 1.5" 0 "$Z" "$T/hollow.obj" --min-thickness 1.5
expect_out "... none of it thinner than 1.5" "thin walls    0 thinner than 1.5"
if need_python "--thickness in JSON"; then
    "$Z" --check --json --thickness "$T/hollow.obj" >"$T/j" 2>"$T/err"
    got=$(python3 -c "
import json; t = json.load(open('$T/j'))['files'][0]['thickness']
print(t['min'], t['median'], t['measured'], t['faces'])")
    check "--thickness in JSON" '[ "$got" = "2 2 12 12" ]' "got $got"
fi
"$Z" --print --size 40x12 --color none "$T/hollow.obj" >"$T/a" 2>&1
"$Z" --print --size 40x12 --color 256 --thickness "$T/hollow.obj" >"$T/b" 2>&1
"$Z" --print --size 40x12 --color 256 "$T/hollow.obj" >"$T/c" 2>&1
check "--thickness colours --print" '! cmp -s "$T/b" "$T/c"' "the same picture"

# ==== --measure ====
expect_status "--measure v1 v7 on the cube" 0 "$Z" "$T/cube.obj" --measure v1 v7
expect_out "the distance, exact" "distance AB    17.3205081"
expect_out "dx dy dz" "dx dy dz       10 10 10"
expect_status "--measure three points" 0 "$Z" "$T/cube.obj" --measure v2 v1 v4
expect_out "the angle at the corner" "angle ABC      90 degrees"
expect_status "--measure numbers and a vertex" 0 "$Z" "$T/cube.obj" --measure 0,0,0 v3
expect_out "... the vertex named" "(v3)"
expect_out "... the diagonal of a side" "distance AB    14.1421356"
if need_python "--measure --json"; then
    "$Z" --json "$T/cube.obj" --measure v1 v2 v3 >"$T/j" 2>"$T/err"
    got=$(python3 -c "
import json; m = json.load(open('$T/j'))
print(m['distance'], m['delta'], m['angle'], m['points'][0]['vertex'], m['unit'])")
    check "--measure --json" '[ "$got" = "10 [10, 0, 0] 90 1 None" ]' "got $got"
fi
expect_status "--measure --unit in: mm" 0 "$Z" "$T/cube.obj" --unit in --measure v1 v2
expect_out "... 10 in is 254 mm" "distance AB    254 mm"
expect_status "--measure with one point is refused" 2 "$Z" "$T/cube.obj" --measure v1
expect_err "... saying it needs two" "--measure needs two or three points"
expect_status "a vertex past the model's" 2 "$Z" "$T/cube.obj" --measure v1 v9
expect_err "... is named" "v9: the model has 8 vertices"
expect_status "--measure with --check is refused" 2 "$Z" --check "$T/cube.obj" --measure v1 v2

# ==== --marks ====
expect_status "--marks past the model's vertices draws no mark" 0 "$Z" -o "$T/m.png" --size 80x60 --marks v1,v99 "$T/cube.obj"
expect_status "--marks v0 is refused" 2 "$Z" -o "$T/m.png" --marks v0 "$T/cube.obj"
expect_err "... saying what it takes" "up to three points, comma apart: vertices vN, edge midpoints eA-B, face centres fN"
expect_status "--marks takes edge midpoints and face centres" 0 "$Z" -o "$T/m.png" --size 80x60 --marks e1-2,f3,1:v4 "$T/cube.obj"
expect_status "--marks e1-1 (no edge) is refused" 2 "$Z" -o "$T/m.png" --marks e1-1 "$T/cube.obj"

# ==== the viewer ====
. "$(dirname "$0")/tmux.sh"
start 120 30 "$T/hollow.obj" --thickness --overhang
if wait_for 'thickness red 0 to blue 4'; then ok "the status bar gives the thickness's scale"; else
    notok "the status bar gives the thickness's scale" "$(tail -2 "$T/screen")"; fi
if wait_for 'overhang past 45: 256'; then ok "... and the overhanging area"; else
    notok "... and the overhanging area" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null || notok "the viewer quits" "$(tail -3 "$T/screen")"

# the measuring mode: M, the cursor on a vertex, two marks, the
# distance along a cube's edge or diagonal, C writing them as --marks
start 120 30 "$T/cube.obj"
wait_for 'faces 6 drawn' >/dev/null || notok "the viewer starts" "$(tail -2 "$T/screen")"
tm send-keys -t zv M
if wait_for 'v[1-8] (0|10) (0|10) (0|10)'; then ok "M: the cursor on a vertex, its coordinates"; else
    notok "M: the cursor on a vertex, its coordinates" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv Enter Right Enter
if wait_for 'AB (10|14\.1421|17\.3205) \(dx'; then ok "two marks: the distance along an edge or a diagonal"; else
    notok "two marks: the distance along an edge or a diagonal" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv Down Enter
if wait_for 'angle ABC (45|54\.74|90|35\.26|60)'; then ok "three marks: the angle"; else
    notok "three marks: the angle" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv h
if wait_for 'angle ABC'; then ok "the marks stay while it turns"; else notok "the marks stay while it turns" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv C
if wait_for '--marks v[1-8],v[1-8],v[1-8]'; then ok "C writes the marks"; else notok "C writes the marks" "$(cat "$T/screen")"; fi
tm send-keys -t zv x M
if wait_for 'measuring off'; then ok "M leaves"; else notok "M leaves" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null || notok "the viewer quits" "$(tail -3 "$T/screen")"

# the measuring mode by mouse (SGR reports, cells from 1): a click puts
# the cursor on the nearest visible vertex, a click on the cursor's own
# point marks it; Ctrl (or Shift) with a click, or S, snaps to edge
# midpoints and face centres too; a left drag moves the cursor, not the
# model (C still writes the opening turn)
mouse() { tm send-keys -t zv -l "$(printf '\033[<%d;%d;%dM\033[<%d;%d;%dm' "$1" "$2" "$3" "$1" "$2" "$3")"; }
start 120 30 "$T/cube.obj"
wait_for 'faces 6 drawn' >/dev/null || notok "the viewer starts" "$(tail -2 "$T/screen")"
tm send-keys -t zv M
wait_for '\| v[1-8] ' >/dev/null || notok "M: the cursor" "$(tail -2 "$T/screen")"
mouse 0 40 26
if wait_for '\| v[1-8] (0|10) (0|10) (0|10) \|'; then ok "a click: the cursor on a vertex"; else
    notok "a click: the cursor on a vertex" "$(tail -2 "$T/screen")"; fi
mouse 0 40 26
if wait_for 'v[1-8] (0|10) (0|10) (0|10), A marked'; then ok "a click on the cursor's vertex marks it"; else
    notok "a click on the cursor's vertex marks it" "$(tail -2 "$T/screen")"; fi
mouse 0 100 20
mouse 0 100 20
if wait_for 'AB (10|14\.1421|17\.3205) \(dx'; then ok "two clicks elsewhere: the second mark, the distance"; else
    notok "two clicks elsewhere: the second mark, the distance" "$(tail -2 "$T/screen")"; fi
mouse 16 60 8
if wait_for '\| (f[1-6] |e[1-8]-[1-8] )[0-9. ]+, AB'; then ok "Ctrl with a click: a face centre or an edge midpoint"; else
    notok "Ctrl with a click: a face centre or an edge midpoint" "$(tail -2 "$T/screen")"; fi
mouse 4 60 8
if wait_for 'angle ABC'; then ok "Shift with a click on it: the third mark"; else
    notok "Shift with a click on it: the third mark" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv S
if wait_for 'wide snap: '; then ok "S: the wide snap, in the status bar"; else notok "S: the wide snap, in the status bar" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv -l "$(printf '\033[<0;62;14M\033[<32;50;6M\033[<32;40;6M\033[<0;40;6m')"
if wait_for 'wide snap: (f[1-6]|e[1-8]-[1-8]|v[1-8]) .*angle ABC'; then ok "a drag moves the cursor and keeps the marks"; else
    notok "a drag moves the cursor and keeps the marks" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv C
if wait_for '--yaw -30 --pitch 25 .*--marks v[1-8],v[1-8],(f[1-6]|e[1-8]-[1-8])'; then
    ok "C: the marks with the face or edge, the model not turned by the drag"; else
    notok "C: the marks with the face or edge, the model not turned by the drag" "$(cat "$T/screen")"; fi
tm send-keys -t zv x q
wait_for 'zv-exit=0' >/dev/null || notok "the viewer quits" "$(tail -3 "$T/screen")"
