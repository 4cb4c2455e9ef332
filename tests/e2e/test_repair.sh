#!/bin/sh
# zview --repair IN -o OUT, the command line: usage errors (status 2),
# the input never written (the same file by any name), writes that fail
# (a full device, a full disk: status 1, one line naming the file,
# nothing left behind), the formats by name and the pipe, positions bit
# for bit, --json read by python3. What the repairs do to broken parts
# is test_repair_parts.sh's.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
C="python3 tests/e2e/meshcount.py"

# ==== The command line ====
expect_status "--repair without -o is a usage error" 2 "$Z" --repair assets/cube.obj
expect_err "... saying the input is never written" "--repair needs -o OUT"
expect_status "--repair of two files is a usage error" 2 "$Z" --repair assets/cube.obj assets/knot.obj -o "$T/x.stl"
expect_status "-o of another kind of file is a usage error" 2 "$Z" --repair assets/cube.obj -o "$T/x.png"
expect_err "... naming the kinds it writes" "ends in .stl, .obj or .ply"
expect_status "-o - without --format is a usage error" 2 "$Z" --repair assets/cube.obj -o -
expect_status "--format of a format zview does not write is a usage error" 2 "$Z" --repair assets/cube.obj --format off -o -
expect_status "--format against -o's name is a usage error" 2 "$Z" --repair assets/cube.obj --format ply -o "$T/x.stl"
expect_status "an unknown step is a usage error" 2 "$Z" --repair=weld,glue assets/cube.obj -o "$T/x.stl"
expect_err "... naming the steps" "weld, clean, winding, holes, manifold"
expect_status "--weld without --repair is a usage error" 2 "$Z" --weld 0.1 assets/cube.obj
expect_status "--weld 0 is a usage error" 2 "$Z" --repair --weld 0 assets/cube.obj -o "$T/x.stl"
expect_status "--max-hole without --repair is a usage error" 2 "$Z" --max-hole 10 assets/cube.obj
expect_status "--repair with --check is a usage error" 2 "$Z" --repair --check assets/cube.obj -o "$T/x.stl"
expect_status "--repair with --print is a usage error" 2 "$Z" --repair -p assets/cube.obj -o "$T/x.stl"
[ ! -e "$T/x.stl" ] && ok "no usage error wrote a file" || notok "no usage error wrote a file"

# ==== The input is never written ====
cp assets/cube.obj "$T/in.obj"
cksum <"$T/in.obj" >"$T/in.sum"
ln -s in.obj "$T/sym.obj"
ln "$T/in.obj" "$T/hard.obj"
mkdir "$T/sub"
expect_status "-o IN is refused" 2 "$Z" --repair "$T/in.obj" -o "$T/in.obj"
expect_err "... saying a copy is written, never the input" "never the input"
expect_status "-o a symlink to IN is refused" 2 "$Z" --repair "$T/in.obj" -o "$T/sym.obj"
expect_status "-o a hard link of IN is refused" 2 "$Z" --repair "$T/in.obj" -o "$T/hard.obj"
expect_status "-o IN spelt through another folder is refused" 2 "$Z" --repair "$T/in.obj" -o "$T/sub/../in.obj"
# a model named x.mtl (told an OBJ by its content): the copy x.obj's MTL would be it
cp assets/cube.obj "$T/two.mtl"
expect_status "an OBJ whose MTL would be IN is refused" 2 "$Z" --repair "$T/two.mtl" -o "$T/two.obj"
[ ! -e "$T/two.obj" ] && ok "... and nothing is written" || notok "... and nothing is written"
if cksum <"$T/in.obj" | cmp -s - "$T/in.sum"; then ok "the input is as it was"; else notok "the input is as it was"; fi

# ==== Writes that fail ====
NOSPC=$(python3 -c 'import os, errno; print(os.strerror(errno.ENOSPC))' 2>/dev/null || echo "No space left on device")
if [ -w /dev/full ]; then
    ln -s /dev/full "$T/full.stl"
    expect_status "-o a full device exits 1" 1 "$Z" --repair assets/knot.obj -o "$T/full.stl"
    expect_err "... one line naming it" "$T/full.stl: $NOSPC"
    n=$(wc -l <"$T/err")
    [ "$n" -eq 1 ] && ok "... one line only" || notok "... one line only" "$n lines"
    # on two threads the file is written beside the check of the result
    expect_status "-o a full device on two threads exits 1" 1 "$Z" --repair -j 2 assets/knot.obj -o "$T/full.stl"
    expect_err "... one line naming it" "$T/full.stl: $NOSPC"
    expect_status "-o - to a full device exits 1" 1 sh -c "\"$Z\" --repair assets/knot.obj -o - --format ply >/dev/full"
    expect_err "... naming standard output" "standard output: $NOSPC"
else
    skip "a full device" "no /dev/full"
fi
# a file size limit stands for a full disk: the write fails part way
mkdir "$T/disk"
printf 'old\n' >"$T/disk/old.stl"
expect_status "a full disk exits 1" 1 sh -c "ulimit -f 16; trap '' XFSZ; exec \"$Z\" --repair assets/knot.obj -o \"$T/disk/old.stl\""
expect_err "... naming the file" "$T/disk/old.stl: "
expect_status "... with materials too" 1 sh -c "ulimit -f 16; trap '' XFSZ; exec \"$Z\" --repair assets/demo.obj -o \"$T/disk/new.obj\""
if [ "$(ls "$T/disk")" = old.stl ] && [ "$(cat "$T/disk/old.stl")" = old ]; then ok "... leaving the old file as it was and nothing else"
else notok "... leaving the old file as it was and nothing else" "$(ls "$T/disk" | tr '\n' ' ')"; fi

# ==== Formats, the pipe, the report ====
for ext in stl obj ply; do
    expect_status "a sound cube to .$ext exits 0" 0 "$Z" --repair assets/cube.obj -o "$T/cube.$ext"
    expect_out "... the report's last line says so" "verdict: sound"
    w=$($C "$T/cube.$ext" 2>&1)
    case $w in *'"watertight": true'*'"volume": 1.0'* | *'"volume": 1.0'*'"watertight": true'*) ok "... counted watertight, volume 1" ;;
        *) notok "... counted watertight, volume 1" "$w" ;; esac
done
head -c 5 "$T/cube.stl" | grep -q solid && notok "the STL is binary, not starting with solid" || ok "the STL is binary, not starting with solid"
expect_status "standard input to standard output" 0 sh -c "cat assets/cube.obj | \"$Z\" --repair - -o - --format stl >\"$T/piped.stl\""
if cmp -s "$T/piped.stl" "$T/cube.stl"; then ok "... the bytes -o cube.stl wrote"; else notok "... the bytes -o cube.stl wrote"; fi
expect_err "... the report on standard error" "standard output (stl)"
expect_status "a cube's faces kept as quads in the OBJ" 0 grep -c '^f [0-9]* [0-9]* [0-9]* [0-9]*$' "$T/cube.obj"
# positions bit for bit: every v of the input, as float, is in the output in order
if python3 - "$T/cube.obj" assets/cube.obj assets/knot.obj "$Z" "$T" <<'EOF'
import struct, subprocess, sys
out, cube, knot, z, t = sys.argv[1:]
def vs(p):
    return [struct.pack("<3f", *[float(x) for x in l.split()[1:4]]) for l in open(p) if l.startswith("v ")]
assert vs(out) == vs(cube), "cube"
subprocess.run([z, "--repair", knot, "-o", t + "/knot.obj"], stdout=subprocess.DEVNULL, check=False)
assert vs(t + "/knot.obj") == vs(knot), "knot"
EOF
then ok "positions read back as the input's floats, bit for bit (cube, knot)"; else notok "positions read back as the input's floats, bit for bit (cube, knot)"; fi

# one thread or two (the file written beside the check of the result):
# the same bytes and the same report but its times
for j in 1 2; do
    mkdir "$T/j$j"
    "$Z" --repair -j $j --json assets/scene.obj -o "$T/j$j/s.obj" 2>/dev/null | sed 's/"ms": {[^}]*}//; s#/j[12]/#/jN/#g' >"$T/j$j.json"
done
if cmp -s "$T/j1/s.obj" "$T/j2/s.obj" && cmp -s "$T/j1/s.mtl" "$T/j2/s.mtl" && cmp -s "$T/j1.json" "$T/j2.json" &&
    [ -s "$T/j2/s.obj" ]; then
    ok "-j 1 and -j 2 write the same bytes and report the same"
else
    notok "-j 1 and -j 2 write the same bytes and report the same" "$(diff "$T/j1.json" "$T/j2.json" | head -5)"
fi

# --json: the documented members, and ok as the exit status says
"$Z" --repair --json assets/scene.obj -o "$T/scene.obj" >"$T/scene.json" 2>"$T/err"
rc=$?
if python3 - "$T/scene.json" "$rc" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
for k in ("ok", "input", "input_format", "steps", "weld", "max_hole", "repair", "written", "before", "after"):
    assert k in d, k
assert d["ok"] == (sys.argv[2] == "0"), (d["ok"], sys.argv[2])
assert d["steps"] == ["weld", "clean", "manifold", "winding", "holes"], d["steps"]
assert d["written"]["format"] == "obj" and d["written"]["mtl"].endswith("scene.mtl"), d["written"]
for side in ("before", "after"):
    for k in ("faces", "holes", "boundary_edges", "watertight", "self_intersections", "problems"):
        assert k in d[side], (side, k)
assert d["before"]["holes"] == 2, d["before"]["holes"]
EOF
then ok "--json parses, with its members (status $rc)"; else notok "--json parses, with its members" "$(head -c 300 "$T/scene.json")"; fi

