#!/bin/sh
# Files a person meets (issue 20): told by content and name together,
# gzip-compressed and piped input, partial files, several files of which
# one is missing. Corpus files from Debian's assimp-testmodels where it
# has them (tools/deps.sh), generated files otherwise.
. "$(dirname "$0")/lib.sh"
. "$(dirname "$0")/tmux.sh"
A=/usr/share/assimp/models
have_corpus() {
    [ -d "$A" ] && "$Z" --formats | grep -q assimp && return 0
    skip "$1" "no assimp or no $A (tools/deps.sh)"
    return 1
}
# info FIELD: the value of a --info field in $T/out
info() { sed -n "s/^$1: *//p" "$T/out" | head -1; }

# ---- gzip: transparent, on files and standard input, errors name the file
gzip -c assets/cube.obj >"$T/model.obj.gz"
expect_status "model.obj.gz loads" 0 "$Z" --info "$T/model.obj.gz"
check "... as the OBJ it holds, 6 faces" '[ "$(info format)" = obj ] && [ "$(info faces)" = 6 ]' "$(cat "$T/out")"
"$Z" -o "$T/plain.png" --size 40x30 assets/cube.obj && "$Z" -o "$T/gz.png" --size 40x30 "$T/model.obj.gz"
check "... and draws the same picture as the plain file" 'cmp -s "$T/plain.png" "$T/gz.png"'
gzip -c assets/cube.obj | "$Z" --info - >"$T/out" 2>"$T/err"
check "gzip on standard input loads" '[ "$(info faces)" = 6 ]' "$(cat "$T/err")"
head -c 40 "$T/model.obj.gz" >"$T/cut.obj.gz"
expect_status "a gzip file cut short: status 1" 1 "$Z" --info "$T/cut.obj.gz"
expect_err "... one line naming the file" "$T/cut.obj.gz: gzip data cut short"
printf '\037\213\010\000\000\000\000\000\000\003garbage-not-deflate' >"$T/bad.stl.gz"
expect_status "damaged gzip data: status 1" 1 "$Z" --info "$T/bad.stl.gz"
expect_err "... one line naming the file and the byte" "$T/bad.stl.gz: damaged gzip data near compressed byte"
# several members (issue 28: all but the first were lost): read one after
# the other as zcat does; made by python3's gzip module
if need_python "gzip files of several members"; then
    python3 - "$T" <<'EOF'
import gzip, sys
d = sys.argv[1]
obj = open("assets/cube.obj", "rb").read()
cut = obj.index(b"\nv ", len(obj) // 3) + 4          # inside a line
w = lambda name, b: open(d + "/" + name, "wb").write(b)
w("two.obj.gz", gzip.compress(obj[:cut]) + gzip.compress(obj[cut:]))
w("empty-first.obj.gz", gzip.compress(b"") + gzip.compress(obj))
w("garbage.obj.gz", gzip.compress(obj) + b"not gzip")
w("zeros.obj.gz", gzip.compress(obj) + bytes(4096))
second = gzip.compress(obj[cut:])
w("cut-second.obj.gz", gzip.compress(obj[:cut]) + second[:len(second) // 2])
w("cut-magic.obj.gz", gzip.compress(obj) + b"\x1f")
EOF
    expect_status "two members, the OBJ split inside a line: loads" 0 "$Z" --info "$T/two.obj.gz"
    check "... the whole cube, 6 faces" '[ "$(info faces)" = 6 ]' "$(cat "$T/out" "$T/err")"
    "$Z" -o "$T/two.png" --size 40x30 "$T/two.obj.gz"
    check "... the same picture as the plain file" 'cmp -s "$T/plain.png" "$T/two.png"'
    expect_status "an empty first member: loads" 0 "$Z" --info "$T/empty-first.obj.gz"
    check "... the cube of the second, 6 faces" '[ "$(info faces)" = 6 ] && [ ! -s "$T/err" ]' "$(cat "$T/out" "$T/err")"
    expect_status "bytes after the last member: loads" 0 "$Z" --info "$T/garbage.obj.gz"
    check "... 6 faces" '[ "$(info faces)" = 6 ]' "$(cat "$T/out")"
    expect_err "... with a warning as zcat's, naming the file" "zview: warning: $T/garbage.obj.gz: trailing garbage after the gzip data ignored (from compressed byte"
    expect_status "... --strict refuses it" 1 "$Z" --info --strict "$T/garbage.obj.gz"
    expect_err "... saying why" "$T/garbage.obj.gz: bytes that are not gzip data after the last member"
    expect_status "zero padding after the last member: loads" 0 "$Z" --info "$T/zeros.obj.gz"
    check "... quietly, as zcat" '[ "$(info faces)" = 6 ] && [ ! -s "$T/err" ]' "$(cat "$T/err")"
    expect_status "a second member cut short: status 1" 1 "$Z" --info "$T/cut-second.obj.gz"
    check "... one line naming the file" '[ "$(wc -l <"$T/err")" -eq 1 ]' "$(cat "$T/err")"
    expect_err "... saying so" "zview: $T/cut-second.obj.gz: gzip data cut short"
    expect_status "a file ending in a member's first byte: status 1" 1 "$Z" --info "$T/cut-magic.obj.gz"
    expect_err "... cut short" "zview: $T/cut-magic.obj.gz: gzip data cut short"
    cat "$T/two.obj.gz" | "$Z" --info - >"$T/out" 2>"$T/err"
    check "two members on standard input: 6 faces" '[ "$(info faces)" = 6 ]' "$(cat "$T/err")"
    # a stream of zeros after a member ends at once, with the warning
    (cat "$T/zeros.obj.gz"; head -c 20000000 /dev/zero) | timeout 10 "$Z" --info - >"$T/out" 2>"$T/err"
    check "zeros without end after a member: 6 faces, a warning" '[ "$(info faces)" = 6 ] && grep -q "trailing garbage" "$T/err"' "$(cat "$T/err")"
fi
# a gzip bomb is held to the same bound as any stream: the memory a load
# may take (ZV_MEM_AVAILABLE stands in for a small machine)
head -c 50000000 /dev/zero | tr '\0' 'v' | gzip -c >"$T/bomb.obj.gz"
ZV_MEM_AVAILABLE=16000000 "$Z" --info "$T/bomb.obj.gz" >/dev/null 2>"$T/err"
st=$?
check "a gzip bomb past the memory bound is refused" '[ $st -eq 1 ]' "status $st"
expect_err "... saying so, naming the file" "$T/bomb.obj.gz: input too large for the memory available"
if have_corpus "gzip-compressed .blend"; then
    expect_status "a compressed .blend (BlenderDefault_250_Compressed) loads" 0 "$Z" --info "$A/BLEND/BlenderDefault_250_Compressed.blend"
    check "... through assimp as blend" '[ "$(info format)" = "blend (assimp)" ]' "$(info format)"
    gzip -c "$A/PLY/cube.ply" >"$T/scan.ply.gz"
    expect_status "scan.ply.gz loads" 0 "$Z" --info "$T/scan.ply.gz"
fi

# ---- content and name together; assimp asked for what it tells by content
if have_corpus "nff and extensionless files"; then
    expect_status ".nff (whose first word is v) goes to assimp" 0 "$Z" --info "$A/NFF/NFF/cylinder.nff"
    check "... named nff, not read as OBJ" '[ "$(info format)" = "nff (assimp)" ]' "$(info format) $(cat "$T/err")"
    for f in 3DS/testFormatDetection X/TestFormatDetection AC/TestFormatDetection; do
        expect_status "extensionless $f: assimp tells it by content" 0 "$Z" --info "$A/$f"
        check "... and names the format" 'info format | grep -q "(assimp)"' "$(info format)"
    done
fi
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/tri"
expect_status "extensionless OBJ text is still OBJ" 0 "$Z" --info "$T/tri"
check "... format obj" '[ "$(info format)" = obj ]' "$(info format)"
cp "$T/tri" "$T/tri.stl"
expect_status "OBJ text named .stl: the STL reader cannot read it, OBJ does" 0 "$Z" --info "$T/tri.stl"
echo "hello there" >"$T/notes"
expect_status "text nothing reads: refused" 1 "$Z" --info "$T/notes"
expect_err "... in zview's own words" "$T/notes: not a model zview can read (text;"

# ---- standard input with a format assimp reads: imported from memory
if have_corpus "assimp formats on standard input"; then
    "$Z" --info - <"$A/FBX/box.fbx" >"$T/out" 2>"$T/err"
    check "zview - < box.fbx: read from memory, told by content" '[ "$(info format)" = "fbx (assimp)" ] && [ "$(info vertices)" = 24 ]' "$(cat "$T/err")"
    G=$A/glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb
    cat "$G" | "$Z" --format glb --info - >"$T/out" 2>"$T/err"
    check "cat x.glb | zview --format glb -" '[ "$(info format)" = "glb (assimp)" ] && [ "$(info vertices)" = 24 ]' "$(cat "$T/err")"
    cat "$G" | "$Z" --info - >"$T/out" 2>"$T/err"
    check "cat x.glb | zview - (the content names it)" '[ "$(info format)" = "glb (assimp)" ]' "$(cat "$T/err")"
    "$Z" -p --size 30x10 --color none - <"$A/FBX/box.fbx" >"$T/p" 2>"$T/err"
    check "zview -p - < box.fbx draws" 'grep -q "[▀▄█]" "$T/p"' "$(cat "$T/err")"
    gzip -c "$A/BLEND/box.blend" | "$Z" --info - >"$T/out" 2>"$T/err"
    check "a gzip-compressed .blend on standard input" '[ "$(info format)" = "blend (assimp)" ]' "$(cat "$T/err")"
fi

# ---- partial and odd files: shown with a warning, refused by --strict
if have_corpus "PLY with a writer's own header line"; then
    "$Z" --info "$A/PLY/Wuson.ply" >"$T/out" 2>"$T/err"
    check "Wuson.ply (a 'Created by Blender' header line) loads" '[ "$(info format)" = "ply ascii" ] && [ "$(info faces)" -gt 0 ]' "$(cat "$T/err")"
    expect_err "... warning of the line skipped" "Wuson.ply:3: unknown header line 'Created'"
    expect_status "... --strict refuses it" 1 "$Z" --strict --info "$A/PLY/Wuson.ply"
    expect_err "... naming the line" "Wuson.ply:3: unknown header line 'Created'"
fi
python3 - "$T" <<'PY'
import struct, sys
d = b'\0' * 80 + struct.pack('<I', 3)
for t in (((0,0,0),(1,0,0),(0,1,0)), ((0,0,0),(0,1,0),(0,0,1)), ((0,0,0),(1,0,0),(0,0,1))):
    d += struct.pack('<3f', 0, 0, 1) + b''.join(struct.pack('<3f', *v) for v in t) + b'\0\0'
open(sys.argv[1] + '/cut.stl', 'wb').write(d[:84 + 2 * 50 + 20])
PY
python3 - "$T" <<'PY'
import struct, sys
d = b'\0' * 80 + struct.pack('<I', 2)
for t in (((0,0,0),(1,0,0),(0,1,0)), ((0,0,0),(0,1,0),(0,0,1))):
    d += struct.pack('<3f', 0, 0, 1) + b''.join(struct.pack('<3f', *v) for v in t) + b'\0\0'
open(sys.argv[1] + '/part.stl', 'wb').write(d)
PY
gzip -c "$T/part.stl" >"$T/part.stl.gz"
"$Z" --info "$T/part.stl.gz" >"$T/out" 2>"$T/err"
check "part.stl.gz (a binary STL, told by its size once decompressed)" '[ "$(info format)" = "stl binary" ] && [ "$(info faces)" = 2 ]' "$(cat "$T/err")"
"$Z" --info "$T/cut.stl" >"$T/out" 2>"$T/err"
check "a binary STL cut inside triangle 3 of 3 shows the 2 whole ones" '[ "$(info faces)" = 2 ]' "$(cat "$T/err")"
expect_err "... with a warning saying where it ends" "byte 184: file ends inside triangle 3 of 3"
expect_status "... --strict refuses it" 1 "$Z" --strict --info "$T/cut.stl"

# ---- points only through assimp: a cloud, as the native loaders show one
if have_corpus "AC/nosurfaces.ac"; then
    "$Z" --info "$A/AC/nosurfaces.ac" >"$T/out" 2>"$T/err"
    check "nosurfaces.ac (7 vertices, no surface) is a cloud of 7 points" '[ "$(info points)" = 7 ]' "$(cat "$T/err")"
    "$Z" -p --size 30x10 --color none "$A/AC/nosurfaces.ac" >"$T/p" 2>"$T/err"
    check "... and draws them" '[ "$(grep -o "[▀▄█]" "$T/p" | wc -l)" -ge 5 ]' "$(cat "$T/p")"
fi

# ---- one file of several missing: the rest shown, the missing one named
"$Z" --info assets/cube.obj "$T/gone.obj" assets/knot.obj >"$T/out" 2>"$T/err"
st=$?
check "cube, a missing file, knot: status 0" '[ $st -eq 0 ]' "status $st: $(cat "$T/err")"
check "... the two others make the scene" 'grep -q "^scene: *2 objects" "$T/out"' "$(grep scene "$T/out")"
expect_err "... a warning names the missing one" "warning: $T/gone.obj: cannot open: No such file or directory (left out"
expect_status "--strict refuses the run" 1 "$Z" --strict --info assets/cube.obj "$T/gone.obj"
expect_err "... naming the file" "$T/gone.obj: cannot open"
expect_status "every file missing: status 1" 1 "$Z" --info "$T/gone.obj" "$T/gone2.obj"
start 100 30 assets/cube.obj "$T/gone.obj"
if wait_for "gone.obj: cannot open"; then ok "the viewer's status bar names the file left out"; else notok "the viewer's status bar names the file left out" "$(tail -2 "$T/screen")"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

# ---- an unreadable vertex is never drawn
printf 'v 1 abc 2\n' >"$T/onebad.obj"
expect_status "a file whose only vertex is unreadable: nothing to show, status 1" 1 "$Z" --info "$T/onebad.obj"
expect_err "... naming the line" "onebad.obj:1: malformed number 'abc' (1 statement skipped, nothing left to show)"
"$Z" -p --size 20x10 --color none "$T/onebad.obj" >"$T/p" 2>/dev/null
check "... and draws no point at the origin" '! grep -q "[▀▄█]" "$T/p"' "$(cat "$T/p")"
printf 'v 5 5 5\nv 1 abc 2\nv 6 6 6\n' >"$T/cloud.obj"
"$Z" --info "$T/cloud.obj" >"$T/out" 2>"$T/err"
check "a cloud of 3 vertices, one unreadable: 2 points" '[ "$(info points)" = "2 (every vertex)" ] && [ "$(info vertices)" = 2 ]' "$(info points)"
printf 'v 0 0 0\nv 1 x 0\nv 1 0 0\nv 0 1 0\nf 1 3 4\nf 1 2 3\n' >"$T/tri.obj"
"$Z" --points --info "$T/tri.obj" >"$T/out" 2>"$T/err"
check "--points draws the 3 readable vertices, not the unreadable one" '[ "$(info points)" = "3 (every vertex)" ]' "$(info points)"

# ---- --points keeps the objects: --move 2:... moves the second
expect_status "--points --move 2:1,0,0 on a scene of 6 objects" 0 "$Z" --points --move 2:1,0,0 --info assets/scene.obj
check "... the objects stay" 'grep -q "^scene: *6 objects, 0 faces" "$T/out"' "$(grep scene "$T/out") $(cat "$T/err")"
"$Z" --points -p --size 40x12 --color none --fit-from 30,25,0 --yaw 30 --pitch 25 assets/scene.obj >"$T/p1"
"$Z" --points --move 2:1,0,0 -p --size 40x12 --color none --fit-from 30,25,0 --yaw 30 --pitch 25 assets/scene.obj >"$T/p2" 2>"$T/err"
check "... and the move changes the picture" '! cmp -s "$T/p1" "$T/p2"' "$(cat "$T/err")"

# ---- --scale acts within the fitted view; empty frames say why
"$Z" -p --size 30x10 --color none assets/cube.obj >"$T/p1"
"$Z" -p --size 30x10 --color none --scale 1:0.5 assets/cube.obj >"$T/p2"
n1=$(grep -o "[▀▄█]" "$T/p1" | wc -l); n2=$(grep -o "[▀▄█]" "$T/p2" | wc -l)
check "--scale 1:0.5 on a single object: it shrinks in the picture, as documented" '[ "$n2" -lt "$n1" ] && [ "$n2" -gt 0 ]' "$n1 -> $n2"
grep -q "as loaded and laid out" doc/zview.1
check "... and the man page says the fit is of the objects as loaded" '[ $? -eq 0 ]'
"$Z" -o "$T/x.png" --size 30x10 --scale 1:1000 --move 1:2000,0,0 assets/cube.obj 2>"$T/err"
expect_err "a scene scaled and moved out of view: outside the picture" "everything is outside the picture (--pan, --move, --scale or --zoom)"
"$Z" -o "$T/x.png" --size 30x10 --scale 1:0.001 assets/cube.obj 2>"$T/err"
expect_err "scaled too small: says it was scaled down" "the model, scaled down (--scale), covers no sample"
printf 'v 0 0 0\nv 1 1 1\nv 2 2 2\nv 0 1 0\nf 1 2 3\nf 4 4 4\n' >"$T/zero.obj"
"$Z" -o "$T/x.png" --size 30x10 "$T/zero.obj" 2>"$T/err"
expect_err "a model whose faces all have zero area says so" "nothing drawn: every face has zero area"
