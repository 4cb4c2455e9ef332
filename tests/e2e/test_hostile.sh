#!/bin/sh
# Hostile input on the command line (issue 16): streams of garbage and
# zeros decided from their head, counts refused before loading, a sparse
# material library, floods of warnings, byte-order marks and a file cut
# while it loads. Big inputs are sparse files made here; every command
# runs under a timeout (the cases took seconds to minutes before).
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW

# expect_quick NAME WANT CMD...: the status within 10 s
expect_quick() {
    name=$1; want=$2; shift 2
    timeout 10 "$@" >"$T/out" 2>"$T/err" </dev/null
    got=$?
    if [ "$got" -eq "$want" ]; then ok "$name"; else notok "$name" "status $got, wanted $want; stderr: $(head -c 300 "$T/err")"; fi
}

# streams: 4 GiB were read before zview decided
head -c 50000000 /dev/urandom >"$T/rnd" 2>/dev/null
timeout 10 sh -c "cat '$T/rnd' | '$Z' -p --size 40x20 -" >"$T/out" 2>"$T/err"
st=$?
if [ $st -eq 1 ]; then ok "random bytes on a pipe are refused at once"; else notok "random bytes on a pipe are refused at once" "status $st $(head -c 200 "$T/err")"; fi
# binary data, or (a head without a NaN, 1 in 40) a count past the limit
expect_err "the refusal names stdin" "zview: stdin: "
expect_quick "--format stl /dev/zero ends at once" 1 "$Z" --info --format stl /dev/zero
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\nproperty float y\nproperty float z\nelement face 100\nproperty list uchar int vertex_indices\nend_header\n' >"$T/ply.h"
timeout 10 sh -c "cat '$T/ply.h' /dev/zero | '$Z' --info -" >"$T/out" 2>"$T/err"
st=$?
if [ $st -le 1 ]; then ok "a PLY header on zeros is read only as far as it says"; else notok "a PLY header on zeros is read only as far as it says" "status $st"; fi

# counts the file allows and the limit does not
printf '%080d' 0 | tr 0 '\000' >"$T/big.stl"
printf '\120\270\036\005' >>"$T/big.stl"         # 85,899,344 triangles
truncate -s $((84 + 50 * 85899344)) "$T/big.stl"
expect_quick "a sparse 4.3 GB STL is refused by its count" 1 "$Z" --info --max-polys 20000000 "$T/big.stl"
expect_err "the refusal names the file, the count and the limit" "big.stl: 85,899,344 triangles, more than the limit of 20,000,000 polygons (--max-polys raises it)"
expect_quick "... and without --max-polys, by the memory it needs (a 2 GB machine)" 1 env ZV_MEM_AVAILABLE=2000000000 "$Z" --info "$T/big.stl"
expect_err "... named with the estimate and the memory" "big.stl: 85,899,344 triangles need about 4.6 GB; 2.0 GB available"

# a material library of zeros (17 s before), and 50,000 missing ones
printf 'mtllib z.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n' >"$T/m.obj"
truncate -s 64M "$T/z.mtl"
expect_quick "a sparse material library does not hold the model up" 0 "$Z" --info "$T/m.obj"
expect_err "its warning names it" "material library 'z.mtl' is binary data"
awk 'BEGIN { for (i = 0; i < 50000; i++) printf "mtllib m%d.mtl\n", i; print "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3" }' >"$T/libs.obj"
expect_quick "50,000 missing material libraries" 0 "$Z" --info "$T/libs.obj"
n=$(wc -l <"$T/err")
if [ "$n" -eq 4 ]; then ok "warn three times and count the rest"; else notok "warn three times and count the rest" "$n lines"; fi
expect_err "the count" "49,997 more material libraries could not be read"

# byte-order marks
printf '\357\273\277solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' >"$T/bom.stl"
expect_quick "an ASCII STL with a BOM" 0 "$Z" --info "$T/bom.stl"
expect_out "... reads as ASCII" "stl ascii"

# a file cut while it loads: "changed while reading" and nothing else, or
# (when the load won the race) the model
awk 'BEGIN { for (i = 0; i < 1500000; i++) printf "v %d.000001 %d.000002 0.5\n", i, i % 7;
             for (i = 1; i < 1500000; i++) printf "f %d %d %d\n", i, i + 1, i + 2 }' >"$T/cut.obj"
( "$Z" --info "$T/cut.obj" >"$T/out" 2>"$T/err"; echo $? >"$T/st" ) &
sleep 0.1
truncate -s 1M "$T/cut.obj"
wait
st=$(cat "$T/st")
if [ "$st" -eq 0 ] || { [ "$st" -eq 1 ] && [ "$(cat "$T/err")" = "zview: $T/cut.obj: changed while reading" ]; }; then
    ok "a file cut while it loads (status $st)"
else
    notok "a file cut while it loads" "status $st: $(head -c 300 "$T/err")"
fi
