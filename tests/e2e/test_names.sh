#!/bin/sh
# Names and words from files reach the terminal only made safe (issue
# 28): a file named with OSC 52 (write the clipboard) and CSI 2J (clear
# the screen), a glTF whose buffer uri holds them (assimp echoes it in
# its error), an OBJ whose object and material library are named with
# them, and a stand-in library that prints them on stderr itself. No
# control byte but the newline, no DEL and no C1 character reaches
# standard output or standard error of --info, --check, -o or a failing
# load, and --check --json gives the names back exactly.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
need_python "names with escapes" || exit 0
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

# clean NAME FILE...: no byte below 0x20 but \n, no DEL, no C1 (raw or
# as UTF-8) in the files
clean() {
    name=$1; shift
    bad=$(python3 -c '
import sys
for f in sys.argv[1:]:
    b = open(f, "rb").read()
    t = b.decode("utf-8", "replace")
    bad = [c for c in t if (ord(c) < 0x20 and c != "\n") or 0x7f <= ord(c) <= 0x9f]
    if bad:
        print(f.rsplit("/", 1)[-1], repr(bad[:5]), repr(b[:120]))
' "$@")
    if [ -z "$bad" ]; then ok "$name"; else notok "$name" "$bad"; fi
}
# has NAME FILE TEXT: FILE holds TEXT (a fixed string)
has() {
    if grep -qF -- "$3" "$2"; then ok "$1"; else notok "$1" "lacks '$3': $(head -c 300 "$2")"; fi
}
# run ARGS...: zview with its outputs in $T/out and $T/err, the status in $st
run() {
    timeout 60 "$Z" "$@" >"$T/out" 2>"$T/err" </dev/null
    st=$?
}

ESC=$(printf '\033')
BEL=$(printf '\007')
EVIL="evil${ESC}]52;c;aGk=${BEL}${ESC}[2J"
SHOWN='evil\x1b]52;c;aGk=\x07\x1b[2J'
D=$T/d
mkdir -p "$D"
M="$D/$EVIL.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >"$M"

# ==== a file's name ====
run --info "$M"
check "--info on a file named with OSC 52 and CSI 2J: status 0" '[ $st -eq 0 ]' "status $st: $(cat "$T/err")"
clean "... nothing raw on stdout or stderr" "$T/out" "$T/err"
has "... the name shown by its bytes" "$T/out" "file:       $D/$SHOWN.obj"
run --check "$M"
check "--check on it: sound, status 0" '[ $st -eq 0 ]' "status $st: $(cat "$T/err")"
clean "... nothing raw" "$T/out" "$T/err"
has "... the verdict names it safely" "$T/out" "$D/$SHOWN.obj (obj)"
run --check --json "$M"
clean "--check --json: nothing raw" "$T/out" "$T/err"
r=$(python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); print("yes" if d["files"][0]["path"] == sys.argv[2] else repr(d["files"][0]["path"]))' "$T/out" "$M" 2>&1)
check "... the JSON parses and gives the name back exactly" '[ "$r" = yes ]' "$r"
has "... as \\u001b" "$T/out" 'evil\u001b]52;c;aGk=\u0007\u001b[2J.obj'
run -o "$T/x.png" --size 40x30 "$M"
check "-o draws it: status 0, a PNG" '[ $st -eq 0 ] && [ -s "$T/x.png" ]' "status $st: $(cat "$T/err")"
clean "... nothing raw" "$T/out" "$T/err"
run -o "$D/$EVIL.png" --size 40x30 "$M"
check "-o to a file named so: status 0" '[ $st -eq 0 ] && [ -s "$D/$EVIL.png" ]' "status $st: $(cat "$T/err")"
run -o "$T/none/$EVIL.png" --size 40x30 "$M"
check "-o into a missing folder: status 1" '[ $st -eq 1 ]' "status $st"
clean "... the error shows the name safely" "$T/out" "$T/err"
has "... naming it" "$T/err" "none/$SHOWN.png"
run --info "$D/gone$EVIL.obj"
check "a missing file named so: status 1" '[ $st -eq 1 ]' "status $st"
clean "... the error shows the name safely" "$T/out" "$T/err"
# a failing load, alone and beside a good file
printf 'ply\nformat bogus 1.0\nend_header\n' >"$D/$EVIL.ply"
run --check "$D/$EVIL.ply"
check "a file named so that cannot be read: status 1" '[ $st -eq 1 ]' "status $st"
clean "... nothing raw in the report or the error" "$T/out" "$T/err"
has "... one line naming it safely" "$T/err" "zview: $D/$SHOWN.ply:2: unknown format 'bogus'"
check "... one line" '[ "$(wc -l <"$T/err")" -eq 1 ]' "$(cat "$T/err")"
run --info "$M" "$D/$EVIL.ply"
clean "the warning that leaves it out of a scene: nothing raw" "$T/out" "$T/err"
has "... naming it safely" "$T/err" "zview: warning: $D/$SHOWN.ply:2: "
# other characters that must not reach a terminal: a C1 CSI in UTF-8,
# a bidirectional override, bytes that are not UTF-8
C1=$(printf 'c1\302\233x\342\200\256y\377')
cp "$M" "$D/$C1.obj"
run --info "$D/$C1.obj"
clean "a name with a C1 CSI, a right-to-left override and a stray byte: nothing raw" "$T/out" "$T/err"
has "... each shown by its bytes" "$T/out" 'c1\xc2\x9bx\xe2\x80\xaey\xff.obj'
run --check --json "$D/$C1.obj"
r=$(python3 -c 'import json, sys; p = json.load(open(sys.argv[1]))["files"][0]["path"]; print(p.rsplit("/", 1)[1])' "$T/out" 2>&1)
want=$(printf 'c1\302\233x\342\200\256y\357\277\275.obj')
check "... in JSON as escapes, the stray byte U+FFFD" '[ "$r" = "$want" ]' "$r"
check "... nothing raw in the JSON" '! grep -q "$(printf '\302\233')" "$T/out"'

# ==== names inside a file: an object, a material library ====
# (an OBJ line with a C0 control is binary data, skipped: the names hold
# what a text line may, C1 and a right-to-left override in UTF-8)
ODD=$(printf 'part\302\233\342\200\256')
printf 'mtllib lib%s.mtl\no %s\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no other\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n' \
    "$ODD" "$ODD" >"$D/inside.obj"
run --info "$D/inside.obj"
check "an OBJ naming a library and an object with C1 and RLO: status 0" '[ $st -eq 0 ]' "status $st: $(cat "$T/err")"
clean "... its warning shows the library's name safely" "$T/out" "$T/err"
has "... by its bytes" "$T/err" 'libpart\xc2\x9b\xe2\x80\xae.mtl'
run --check "$D/inside.obj"
clean "--check: the object's name shown safely" "$T/out" "$T/err"
has "... by its bytes" "$T/out" 'object 1 "part\xc2\x9b\xe2\x80\xae"'
run --check --json "$D/inside.obj"
clean "--check --json: nothing raw" "$T/out" "$T/err"
r=$(python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); print("yes" if d["objects"][0]["name"] == sys.argv[2] else repr(d["objects"][0]["name"]))' "$T/out" "$ODD" 2>&1)
check "... given back exactly" '[ "$r" = yes ]' "$r"

# ==== a glTF's uri, echoed in assimp's error ====
if ! "$Z" --formats 2>/dev/null | grep -q '^gltf'; then
    skip "a glTF uri with escapes" "no assimp in this build"
else
    python3 -c '
import json, sys
d = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
     "buffers": [{"byteLength": 36, "uri": "x" + sys.argv[2] + "y.bin"}],
     "bufferViews": [{"buffer": 0, "byteLength": 36}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}]}
open(sys.argv[1], "w").write(json.dumps(d))' "$D/uri.gltf" "$EVIL"
    for args in "--info" "--check" "--check --json" "-o $T/g.png"; do
        # shellcheck disable=SC2086
        run $args "$D/uri.gltf"
        check "glTF uri with escapes, $args: status 1" '[ $st -eq 1 ]' "status $st: $(cat "$T/err")"
        clean "... nothing raw on stdout or stderr" "$T/out" "$T/err"
        check "... one line on stderr" '[ "$(wc -l <"$T/err")" -eq 1 ]' "$(cat "$T/err")"
    done
    has "... assimp's words quote the uri by its bytes" "$T/err" "x${SHOWN}y.bin"
    run --check --json "$D/uri.gltf"
    r=$(python3 -c 'import json, sys; e = json.load(open(sys.argv[1]))["files"][0]["error"]; print("yes" if ("x" + sys.argv[2] + "y.bin") in e else repr(e))' "$T/out" "$EVIL" 2>&1)
    check "... and --check --json gives assimp's words back exactly" '[ "$r" = yes ]' "$r"
    # an object named with escapes (a glTF node's name), its buffer inline
    python3 -c '
import base64, json, struct, sys
buf = struct.pack("<9f", 0,0,0, 1,0,0, 0,1,0)
node = {"mesh": 0, "name": "part" + sys.argv[2]}
d = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}], "nodes": [node, {"mesh": 0, "translation": [0, 0, 2]}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
     "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
     "bufferViews": [{"buffer": 0, "byteLength": 36}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}]}
open(sys.argv[1], "w").write(json.dumps(d))' "$D/node.gltf" "$EVIL"
    run --check "$D/node.gltf"
    clean "a glTF node named with OSC 52 and CSI 2J, --check: nothing raw" "$T/out" "$T/err"
    has "... the object's name by its bytes" "$T/out" "\"part$SHOWN\""
    run --check --json "$D/node.gltf"
    clean "... --check --json: nothing raw" "$T/out" "$T/err"
    r=$(python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); n = [o["name"] for o in d["objects"]]; print("yes" if "part" + sys.argv[2] in n else repr(n))' "$T/out" "$EVIL" 2>&1)
    check "... and gives the name back exactly" '[ "$r" = yes ]' "$r"
fi

# ==== a library that prints on stderr itself ====
LIB=${ZV_STANDIN_LIB:-$ROOT/build/standin}
if [ ! -d "$LIB" ]; then
    skip "a library's own words on stderr" "the stand-in library is not built ($LIB): make builds it"
else
    echo 'Kaydara FBX stand-in' >"$D/chatter.fbx"
    LD_LIBRARY_PATH=$LIB ZV_STANDIN=chatter timeout 30 "$Z" --info "$D/chatter.fbx" >"$T/out" 2>"$T/err" </dev/null
    st=$?
    check "a stand-in library that prints escapes on stderr: status 1" '[ $st -eq 1 ]' "status $st"
    clean "... none reaches stderr" "$T/out" "$T/err"
    if ldd "$Z" 2>/dev/null | grep -q libasan; then
        ok "... its own lines are left out (the checking build shows them)"
    else
        check "... its own lines are left out" '! grep -q "library chatter\|xxxxxxxxxx" "$T/err"' "$(cat "$T/err")"
    fi
    has "... a line of zview's it forged is shown safely" "$T/err" 'zview: a forged line \x1b[2J\xc2\x9b'
    check "... the error is the last line: its message of several lines joined" \
        '[ "$(tail -1 "$T/err")" = "zview: $D/chatter.fbx: stand-in: line one line two \x1b]52;c;aGk=\x07 end" ]' \
        "$(tail -1 "$T/err")"
fi
