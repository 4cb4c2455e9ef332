#!/bin/sh
# Hostile sizes and shapes (issue 16): what used to crash, overflow or take
# quadratic time now draws or is refused in one line naming the limit.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW

# a scene of lines (or one point) and no faces, copied by --grid
printf 'v 0 0 0\nv 1 1 0\nl 1 2\n' >"$T/line.obj"
expect_status "--grid 2 on a scene of lines and no faces draws" 0 "$Z" -p --grid 2 --size 20x6 "$T/line.obj"
printf 'v 0 0 0\n' >"$T/point.obj"
expect_status "--grid 2 on one point draws" 0 "$Z" -p --grid 2 --points --size 20x6 "$T/point.obj"

# finite coordinates far past 1e20: fitted like any other model
for e in 1e20 1e30 3e38; do
    printf 'v 0 0 0\nv %s 0 0\nv 0 %s 0\nf 1 2 3\n' "$e" "$e" >"$T/big.obj"
    expect_status "a triangle $e across is drawn" 0 "$Z" -p --size 20x6 --yaw 30 --pitch 20 "$T/big.obj"
    if grep -q '▀\|▄\|█' "$T/out" && ! grep -q "nothing drawn" "$T/err"; then ok "... and covers pixels"
    else notok "... and covers pixels" "$(head -c 200 "$T/err")"; fi
done
expect_status "--info gives its bounds in the file's units" 0 "$Z" --info "$T/big.obj"
expect_out "... 3e38, not the scaled-down value" "bounds:     0 0 0 .. 3e+38 3e+38 0"

# one face of 120,000 corners (a triangle listed 40,000 times): the
# crossings of a row are many; hung before (12.7 s at 80x24, half a
# second a row), so a generous bound is no timing test (60 s: each takes
# 0.5 s of CPU at 320x180, most of it sorting the crossings of its rows,
# 1.6 s with the C library's qsort; quadratic, the 180 rows took a minute
# and a half)
awk 'BEGIN { print "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0"; printf "f"; for (i = 0; i < 40000; i++) printf " 1 2 4"; print "" }' >"$T/many.obj"
for a in zbuffer scanline span hzb hzb-octree; do
    expect_status "a 120,000-corner face with $a" 0 timeout 60 "$Z" -o "$T/many.png" --size 320x180 -a "$a" "$T/many.obj"
done

# sizes: the limit is named, and a frame that cannot fit is refused before
# anything is loaded
expect_status "--size 16385x100 is a usage error" 2 "$Z" -p --size 16385x100 assets/cube.obj
expect_err "... naming the limit" "--size 16385x100: 1 to 16384 per side"
expect_status "-p with 32768 pixel rows is refused" 1 "$Z" -p --mode half --size 100x16384 assets/cube.obj
expect_err "... naming the limit" "--size 100x16384 in half mode: a picture of 100x32768 pixels (at most 16384 per side)"
expect_status "a frame bigger than the memory left is refused" 1 env ZV_MEM_AVAILABLE=100000000 "$Z" -o "$T/x.png" --size 4096x4096 assets/cube.obj
expect_err "... with the estimate and what is available" "--size 4096x4096: a picture of 4096x4096 pixels needs about 201 MB; 100 MB available"
if [ ! -e "$T/x.png" ]; then ok "... and nothing written"; else notok "... and nothing written"; fi
expect_status "... and so is a text frame, before loading (a missing file is not reached)" 1 env ZV_MEM_AVAILABLE=100000000 "$Z" -p --mode half --size 2000x2000 "$T/no-such.obj"
expect_err "... with the estimate" "in half mode: a picture of 2000x4000 pixels needs about"

# a full disk (played by a 100 KB file-size limit, SIGXFSZ ignored so that
# writes fail with EFBIG): every output fails naming the file, the old
# file stays as it was, and no partial or temporary file is left
full() { (ulimit -f 100; trap '' XFSZ; exec "$@"); }
mkdir "$T/full"
for out in x.png x.ppm x.txt; do
    echo old >"$T/full/$out"
    expect_status "-o $out on a full disk fails" 1 full "$Z" -o "$T/full/$out" --size 1024x1024 assets/knot.obj
    expect_err "... naming the file" "$T/full/$out: File too large"
    if [ "$(cat "$T/full/$out")" = old ]; then ok "... the old $out untouched"; else notok "... the old $out untouched"; fi
done
expect_status "--dump-ids on a full disk fails" 1 full "$Z" --dump-ids "$T/full/ids.bin" --size 1024x1024 assets/knot.obj
expect_status "--dump-screen on a full disk fails" 1 full "$Z" --dump-screen "$T/full/s.obj" --size 1024x1024 assets/knot.obj
expect_status "--turntable on a full disk fails" 1 full "$Z" --turntable 3 -o "$T/full/t-%d.ppm" --size 1024x1024 assets/knot.obj
left=$(ls "$T/full" | tr '\n' ' ')
if [ "$left" = "x.png x.ppm x.txt " ]; then ok "... no partial or temporary file left"; else notok "... no partial or temporary file left" "$left"; fi
# the same outputs with room: written whole, a symlink keeps pointing at its file
ln -s x.ppm "$T/full/link.ppm"
expect_status "-o through a symlink" 0 "$Z" -o "$T/full/link.ppm" --size 64x64 assets/knot.obj
if [ -L "$T/full/link.ppm" ] && head -c 2 "$T/full/x.ppm" | grep -q P6; then ok "... writes the file it names, the link stays"
else notok "... writes the file it names, the link stays"; fi
expect_status "-o /dev/null (not a regular file) is written as it is" 0 "$Z" -o /dev/null --image-format ppm --size 64x64 assets/knot.obj
if [ -c /dev/null ]; then ok "... /dev/null is still a device"; else notok "... /dev/null is still a device"; fi

# messages about limits name the file; points count toward --max-polys
awk 'BEGIN { for (i = 0; i < 70000; i++) printf "o o%d\nv 0 0 %d\nv 1 0 %d\nv 0 1 %d\nf -3 -2 -1\n", i, i, i, i }' >"$T/objs.obj"
expect_status "70,000 objects are refused" 1 "$Z" -p "$T/objs.obj"
expect_err "... naming the file and the limit" "$T/objs.obj: too many objects for one scene (70000; at most 65535)"
awk 'BEGIN { for (i = 0; i < 10; i++) printf "%d 0 0\n", i }' >"$T/ten.xyz"
expect_status "a cloud of 10 points passes --max-polys 10" 0 "$Z" -p --size 20x6 --max-polys 10 "$T/ten.xyz"
expect_status "... and not --max-polys 9: points count" 1 "$Z" -p --size 20x6 --max-polys 9 "$T/ten.xyz"
expect_err "... naming the file" "$T/ten.xyz: more than the limit of 9 polygons"

# Issue 21: no fixed polygon count. A big OBJ that cannot fit is refused
# before it is parsed, from its size and lines of its start and end, with
# the estimate and the memory there is; one that fits is not refused.
awk 'BEGIN { n = 420; for (i = 0; i < n; i++) for (j = 0; j < n; j++) printf "v %.6f %.6f %.6f\n", i / n, j / n, (i * j) % 7 / 70.0
    for (i = 0; i < n - 1; i++) for (j = 0; j < n - 1; j++) { a = i * n + j + 1; printf "f %d %d %d\nf %d %d %d\n", a, a + 1, a + n, a + 1, a + n + 1, a + n } }' >"$T/grid.obj"
expect_status "a 13 MB OBJ on a machine of 8 MB is refused" 1 env ZV_MEM_AVAILABLE=8000000 "$Z" --info "$T/grid.obj"
expect_err "... before parsing, with the estimate and the memory" "grid.obj: 13 MB of OBJ need at least about 12 MB for the mesh (judged from lines of its start and end); 8 MB available"
expect_status "... and loads whole with 40 MB" 0 env ZV_MEM_AVAILABLE=40000000 "$Z" --info "$T/grid.obj"
expect_out "... every triangle of it" "triangles:  351122"
expect_status "--max-polys is still a cap" 1 "$Z" --info --max-polys 351121 "$T/grid.obj"
expect_err "... named in the refusal" "more than the limit of 351,121 polygons"
