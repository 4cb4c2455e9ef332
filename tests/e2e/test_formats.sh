#!/bin/sh
# Model formats on the command line: every format opens in --print and
# -o and prints the OBJ's picture, standard input (-), --format,
# --formats, the one-line refusal, -o - and --image-format, --up, --flip.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
D=tests/data/formats
P="--print --size 40x14 --mode ascii --color none"

# shellcheck disable=SC2086
"$Z" $P $D/house.obj >"$T/ref.txt" 2>"$T/err" </dev/null
if [ -s "$T/ref.txt" ]; then ok "the OBJ prints"; else notok "the OBJ prints" "$(cat "$T/err")"; fi
"$Z" --size 64x48 -o "$T/ref.png" $D/house.obj </dev/null
# an STL stands z-up (the 3D-printing convention): its picture is the
# OBJ's with --up z
# shellcheck disable=SC2086
"$Z" $P --up z $D/house.obj >"$T/refz.txt" 2>"$T/err" </dev/null
"$Z" --size 64x48 -o "$T/refz.png" --up z $D/house.obj </dev/null
# ref NAME: the reference picture for file NAME (.txt or .png)
ref() { case "$1" in *.stl) echo "$T/refz.$2" ;; *) echo "$T/ref.$2" ;; esac; }

has_assimp=0
"$Z" --formats >"$T/formats" 2>&1
grep -q '^glb ' "$T/formats" && has_assimp=1

for f in house.stl house-ascii.stl house-le.ply house-be.ply house-ascii.ply house.off house.glb; do
    if [ "$f" = house.glb ] && [ $has_assimp = 0 ]; then
        expect_status "$f is refused without assimp" 1 "$Z" --print $D/$f
        expect_err "$f: the refusal names glTF" "glTF binary"
        skip "$f loads like the other formats" "no assimp in this build"
        continue
    fi
    # shellcheck disable=SC2086
    "$Z" $P $D/$f >"$T/out.txt" 2>"$T/err" </dev/null
    st=$?
    if [ $st -eq 0 ] && cmp -s "$(ref $f txt)" "$T/out.txt"; then ok "$f prints the OBJ's picture"; else
        notok "$f prints the OBJ's picture" "status $st; $(head -c 200 "$T/err")"; fi
    expect_status "$f -o png" 0 "$Z" --size 64x48 -o "$T/out.png" $D/$f
    if cmp -s "$(ref $f png)" "$T/out.png"; then ok "$f -o gives the OBJ's image"; else notok "$f -o gives the OBJ's image"; fi
done

# colours: the VisCAM roof and the COFF apex change the picture
for f in house-viscam.stl house.coff; do
    "$Z" --print --size 40x14 --mode half --color 256 $D/$f >"$T/c.txt" 2>"$T/err" </dev/null
    "$Z" --print --size 40x14 --mode half --color 256 $D/house.obj >"$T/g.txt" 2>/dev/null </dev/null
    if [ -s "$T/c.txt" ] && ! cmp -s "$T/c.txt" "$T/g.txt"; then ok "$f is drawn in its colours"; else
        notok "$f is drawn in its colours" "$(head -c 200 "$T/err")"; fi
done

# standard input
for f in house.stl house-le.ply house-ascii.stl house.off house.obj; do
    # shellcheck disable=SC2086
    cat $D/$f | "$Z" $P - >"$T/out.txt" 2>"$T/err"
    if cmp -s "$(ref $f txt)" "$T/out.txt"; then ok "cat $f | zview --print -"; else
        notok "cat $f | zview --print -" "$(head -c 200 "$T/err")"; fi
done
# shellcheck disable=SC2086
"$Z" $P - <$D/house-be.ply >"$T/out.txt" 2>"$T/err"
if cmp -s "$T/ref.txt" "$T/out.txt"; then ok "zview - < file"; else notok "zview - < file" "$(cat "$T/err")"; fi
sed 1d $D/house.off >"$T/bare"   # no OFF keyword: only --format can tell
# shellcheck disable=SC2086
cat "$T/bare" | "$Z" $P - >"$T/out.txt" 2>"$T/err"
st=$?
if [ $st -eq 1 ] && grep -q "stdin: not a model zview can read" "$T/err"; then ok "a keyword-less OFF on stdin is refused"; else
    notok "a keyword-less OFF on stdin is refused" "status $st: $(cat "$T/err")"; fi
# shellcheck disable=SC2086
cat "$T/bare" | "$Z" $P --format off - >"$T/out.txt" 2>"$T/err"
if cmp -s "$T/ref.txt" "$T/out.txt"; then ok "--format off - reads it"; else notok "--format off - reads it" "$(cat "$T/err")"; fi
expect_status "- twice is a usage error" 2 "$Z" --print - -

# --formats
expect_status "--formats" 0 "$Z" --formats
for n in obj stl ply off; do expect_out "--formats lists $n" "$n "; done
if [ $has_assimp = 1 ]; then
    for n in glb gltf fbx dae 3ds 3mf x3d; do expect_out "--formats lists $n (assimp)" "$n "; done
else
    skip "--formats lists the assimp formats" "no assimp in this build"
fi
# --info counts the texture coordinates and normals an assimp model
# carries, as the file's own accessors say (read here with python's json)
box=/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf
if [ $has_assimp = 1 ] && [ -r "$box" ] && need_python "--info counts a glTF's texcoords and normals"; then
    counts=$(python3 -c 'import json,sys; g=json.load(open(sys.argv[1])); p=g["meshes"][0]["primitives"][0]["attributes"]; a=g["accessors"]; print("texcoords:  %d   normals: %d" % (a[p["TEXCOORD_0"]]["count"], a[p["NORMAL"]]["count"]))' "$box")
    expect_status "--info on a textured glTF" 0 "$Z" --info "$box"
    expect_out "... counts its texcoords and normals ($counts)" "${counts:-none read}"
elif [ $has_assimp = 1 ]; then
    skip "--info counts a glTF's texcoords and normals" "no assimp-testmodels"
fi
expect_status "an unknown --format is a usage error" 2 "$Z" --format gzip --print $D/house.obj
expect_err "the usage error lists the formats" "obj stl ply off"

# files no loader accepts: one line, status 1
# (gzip is decompressed: test_files.sh; bzip2 is not)
printf 'BZh91AY&SY\001\002' >"$T/x.bz2"
expect_status "a bzip2 file is refused" 1 "$Z" --print "$T/x.bz2"
expect_err "the refusal says what it is" "x.bz2: not a model zview can read (bzip2 data; formats: obj stl ply off"
if [ "$(wc -l <"$T/err")" -eq 1 ]; then ok "the refusal is one line"; else notok "the refusal is one line" "$(cat "$T/err")"; fi
# Binary STL has no magic: noise reads as a file cut short inside its
# triangles, whose 80 whole ones load when none holds a NaN or an
# infinity (about 6% of random files). Either way, no crash: a picture
# (status 0) or a one-line refusal naming the file (status 1).
head -c 4096 /dev/urandom >"$T/noise.stl"
"$Z" --print --size 40x12 "$T/noise.stl" >/dev/null 2>"$T/err" </dev/null
st=$?
if [ "$st" -eq 0 ] || { [ "$st" -eq 1 ] && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "noise.stl" "$T/err"; }; then
    ok "noise named .stl: a picture or a one-line refusal naming it"
else
    notok "noise named .stl: a picture or a one-line refusal naming it" "status $st: $(cat "$T/err")"
fi
head -c 4096 /dev/urandom >"$T/noise.ply"
expect_status "noise named .ply fails cleanly" 1 "$Z" --print "$T/noise.ply"
expect_err "noise named .ply is refused as binary data" "binary data"

# -o - and --image-format
"$Z" --size 64x48 -o - $D/house.stl >"$T/stdout.png" 2>"$T/err" </dev/null
if cmp -s "$T/refz.png" "$T/stdout.png"; then ok "-o - writes the PNG to stdout"; else notok "-o - writes the PNG to stdout" "$(cat "$T/err")"; fi
"$Z" --size 64x48 --image-format ppm -o - $D/house.stl >"$T/stdout.ppm" 2>"$T/err" </dev/null
if [ "$(head -c 2 "$T/stdout.ppm")" = P6 ] && [ "$(wc -c <"$T/stdout.ppm")" -eq $((13 + 64 * 48 * 3)) ]; then
    ok "--image-format ppm -o - writes PPM"; else notok "--image-format ppm -o - writes PPM"; fi
expect_status "--image-format with any name" 0 "$Z" --size 64x48 --image-format png -o "$T/image.bin" $D/house.stl
if cmp -s "$T/refz.png" "$T/image.bin"; then ok "--image-format png writes PNG"; else notok "--image-format png writes PNG"; fi
expect_status "-o without .png/.ppm or --image-format is a usage error" 2 "$Z" -o "$T/x.jpg" $D/house.obj
expect_status "-o - with --print is a usage error" 2 "$Z" --print -o - $D/house.obj
expect_status "a bad --image-format is a usage error" 2 "$Z" --image-format gif -o - $D/house.obj

# --up and --flip
# shellcheck disable=SC2086
"$Z" $P --up y $D/house.stl >"$T/y.txt" 2>/dev/null
# shellcheck disable=SC2086
"$Z" $P --up z --view front $D/house.stl >"$T/z.txt" 2>/dev/null
# shellcheck disable=SC2086
"$Z" $P --view front $D/house.stl >"$T/stl.txt" 2>/dev/null
if cmp -s "$T/ref.txt" "$T/y.txt"; then ok "--up y overrides the STL's z"; else notok "--up y overrides the STL's z"; fi
if ! cmp -s "$T/y.txt" "$T/z.txt"; then ok "--up z turns the model"; else notok "--up z turns the model"; fi
if cmp -s "$T/stl.txt" "$T/z.txt"; then ok "an STL stands z-up without --up"; else notok "an STL stands z-up without --up"; fi
# with z up, seen from the front, the roof's apex is the top of the
# picture: its first drawn row is narrow
first=$(grep -m1 '[^ ]' "$T/z.txt" | tr -d ' ' | wc -c)
last=$(grep '[^ ]' "$T/z.txt" | tail -n 1 | tr -d ' ' | wc -c)
if [ "$first" -lt "$last" ]; then ok "--up z puts the roof on top"; else notok "--up z puts the roof on top" "$(cat "$T/z.txt")"; fi
expect_status "a bad --up is a usage error" 2 "$Z" --up w $D/house.obj
# shellcheck disable=SC2086
"$Z" $P --cull $D/house.obj >"$T/cull.txt" 2>/dev/null
# shellcheck disable=SC2086
"$Z" $P --cull --flip $D/house.obj >"$T/flip.txt" 2>/dev/null
if ! cmp -s "$T/cull.txt" "$T/flip.txt"; then ok "--flip turns the faces inside out"; else notok "--flip turns the faces inside out"; fi

# --info names the format, and the up axis and why
"$Z" --info $D/house.stl >"$T/out" 2>"$T/err"
expect_out "--info names the format" "format:     stl binary"
expect_out "--info counts the merged corners" "vertices:   9 (merged from 42 corners)"
expect_out "--info says why the STL is z-up" "up:         z (STL: the 3D-printing convention)"
"$Z" --info --up y $D/house.stl >"$T/out" 2>"$T/err"
expect_out "--info says when --up set the axis" "up:         y (--up)"
"$Z" --info $D/house.obj >"$T/out" 2>"$T/err"
expect_out "--info: an OBJ says nothing" "up:         y (obj: the format does not say)"
