#!/bin/sh
# Points, lines and lenient loading on the command line: clouds in XYZ,
# PLY and OBJ, glTF POINTS and LINES through assimp, --points,
# --point-size, --wireframe, --info's counts, the empty frame's reason.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
P="--print --size 40x14 --mode ascii --color none"

printf '0 0 0\n1 0 0\n0 1 0\n1 1 1\n' >"$T/c.xyz"
expect_status "an XYZ cloud prints" 0 "$Z" $P "$T/c.xyz"
cp "$T/out" "$T/small"
if [ "$(tr -d ' \n' <"$T/small" | wc -c)" -ge 4 ]; then ok "... its four points show"; else notok "... its four points show" "$(cat "$T/small")"; fi
expect_status "--info counts the points" 0 "$Z" --info "$T/c.xyz"
expect_out "... as every vertex" "points:     4 (every vertex)"
# shellcheck disable=SC2086
"$Z" $P --point-size 3 "$T/c.xyz" >"$T/big" 2>"$T/err"
if [ "$(tr -d ' \n' <"$T/big" | wc -c)" -gt "$(tr -d ' \n' <"$T/small" | wc -c)" ]; then ok "--point-size 3 draws bigger points"; else
    notok "--point-size 3 draws bigger points" "$(cat "$T/big")"; fi
expect_status "--point-size 17 is a usage error" 2 "$Z" $P --point-size 17 "$T/c.xyz"

printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nl 1 2 3 4 1\np 1 3\n' >"$T/l.obj"
expect_status "OBJ polylines and points print" 0 "$Z" $P "$T/l.obj"
expect_status "--info counts lines and segments" 0 "$Z" --info "$T/l.obj"
expect_out "... per file" "lines:      1 (4 segments)"
expect_out "... and for the scene" "2 points, 1 lines (4 segments)"

expect_status "--points on a mesh" 0 "$Z" --info --points assets/cube.obj
expect_out "... makes its vertices points" "points:     8 (every vertex)"
# shellcheck disable=SC2086
"$Z" $P assets/cube.obj >"$T/faces" 2>/dev/null
# shellcheck disable=SC2086
"$Z" $P --wireframe assets/cube.obj >"$T/wire" 2>"$T/err"
if [ -s "$T/wire" ] && ! cmp -s "$T/faces" "$T/wire"; then ok "--wireframe changes the picture"; else notok "--wireframe changes the picture" "$(cat "$T/err")"; fi
for a in scanline span hzb hzb-octree; do
    # shellcheck disable=SC2086
    "$Z" $P --wireframe --algo $a assets/cube.obj >"$T/wire2" 2>/dev/null
    if cmp -s "$T/wire" "$T/wire2"; then ok "--wireframe --algo $a: the z-buffer's picture"; else notok "--wireframe --algo $a: the z-buffer's picture"; fi
done

"$Z" --formats >"$T/formats" 2>&1
if grep -q '^gltf ' "$T/formats"; then
    expect_status "glTF POINTS, LINES and LINE_STRIP load" 0 "$Z" --info tests/data/prims/lines-points.gltf
    expect_out "... as points" "points:     5"
    expect_out "... and segments" "lines:      6 (6 segments)"
    expect_status "... and print" 0 "$Z" $P tests/data/prims/lines-points.gltf
else
    skip "glTF POINTS, LINES and LINE_STRIP load" "no assimp in this build"
fi

# an empty picture says why
printf 'v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n' >"$T/sq.obj"
expect_status "a square seen edge-on prints" 0 "$Z" $P --yaw 90 "$T/sq.obj"
expect_err "... and says why nothing is drawn" "zview: nothing drawn: the model is edge-on: try --view iso or turn with the arrow keys"
expect_status "a square culled from behind" 0 "$Z" $P --yaw 180 --cull "$T/sq.obj"
expect_err "... says why" "every face was culled as a back face"
expect_status "a square panned away" 0 "$Z" --size 64x48 -o "$T/x.png" --pan 40,0 "$T/sq.obj"
expect_err "... says why in -o too" "everything is outside the picture"
