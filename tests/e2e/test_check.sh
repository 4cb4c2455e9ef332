#!/bin/sh
# zview --check: the report, its exit statuses (0 sound, 3 problems, 1 a
# file not read, 2 usage), the verdict line, --json read by python3's
# json with the documented names and types, several files, a missing
# one among them, and --print --check (the picture, then the report).
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW

# ==== Models with known answers ====
cube() {    # cube FILE [FACES...]: the unit cube with the faces named (default all six)
    faces=${2:-"1 2 3 4 5 6"}
    {
        printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n'
        for f in $faces; do
            case $f in
                1) echo 'f 1 4 3 2' ;;
                2) echo 'f 5 6 7 8' ;;
                3) echo 'f 1 2 6 5' ;;
                4) echo 'f 3 4 8 7' ;;
                5) echo 'f 1 5 8 4' ;;
                6) echo 'f 2 3 7 6' ;;
                6r) echo 'f 6 7 3 2' ;;
            esac
        done
    } >"$1"
}
cube "$T/cube.obj"
cube "$T/open.obj" "1 3 4 5 6"
cube "$T/flip.obj" "1 2 3 4 5 6r"
# two cubes crossing, the second offset by half
{ cat "$T/cube.obj"; printf 'v .5 .5 .5\nv 1.5 .5 .5\nv 1.5 1.5 .5\nv .5 1.5 .5\nv .5 .5 1.5\nv 1.5 .5 1.5\nv 1.5 1.5 1.5\nv .5 1.5 1.5\n'
  printf 'f 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 11 12 16 15\nf 9 13 16 12\nf 10 11 15 14\n'; } >"$T/cross.obj"

# ==== Exit statuses and the verdict ====
expect_status "a sound cube exits 0" 0 "$Z" --check "$T/cube.obj"
last=$(tail -n 1 "$T/out")
if [ "$last" = "verdict: sound" ]; then ok "its last line: verdict: sound"; else notok "its last line: verdict: sound" "got '$last'"; fi
expect_out "the report says watertight" "0 boundary in 0 holes, 0 non-manifold (watertight)"
expect_out "the report gives the volume and centre of mass" "volume        1, centre of mass 0.5 0.5 0.5"
expect_out "the report gives the area" "area          6"
expect_out "the report gives the size in file units" "size          1 x 1 x 1 (file units; the format states none)"
if [ ! -s "$T/err" ]; then ok "a sound check writes nothing to stderr"; else notok "a sound check writes nothing to stderr" "$(head -c 200 "$T/err")"; fi

expect_status "the cube missing a face exits 3" 3 "$Z" --check "$T/open.obj"
last=$(tail -n 1 "$T/out")
want="verdict: $T/open.obj: 1 hole (4 boundary edges)"
if [ "$last" = "$want" ]; then ok "its verdict names the hole"; else notok "its verdict names the hole" "got '$last'"; fi
expect_out "an open mesh has no volume" "volume        none: not closed"

expect_status "a flipped face exits 3" 3 "$Z" --check "$T/flip.obj"
expect_out "... and is counted" "1 flipped face"
expect_status "--flip turns a sound cube inside out" 3 "$Z" --check --flip "$T/cube.obj"
expect_out "... which the verdict says" "inside out"
expect_status "crossing cubes exit 3" 3 "$Z" --check "$T/cross.obj"
expect_out "... with the 6 pairs of faces that cross" "6 intersecting face pairs"

expect_status "a missing file exits 1" 1 "$Z" --check "$T/none.obj"
expect_err "... naming it on stderr" "$T/none.obj"
expect_status "a missing file among sound ones exits 1" 1 "$Z" --check "$T/cube.obj" "$T/none.obj" "$T/cube.obj"
expect_out "... the others still reported" "$T/cube.obj (obj)"
expect_out "... the missing one said not read" "$T/none.obj: not read"
last=$(tail -n 1 "$T/out")
if [ "$last" = "verdict: $T/none.obj: not read" ]; then ok "... and in the verdict"; else notok "... and in the verdict" "got '$last'"; fi
expect_status "a missing file wins over problems: 1" 1 "$Z" --check "$T/open.obj" "$T/none.obj"
printf 'this is not a mesh\n' >"$T/junk.stl"
expect_status "an unreadable file exits 1" 1 "$Z" --check "$T/junk.stl"

expect_status "--check without files is a usage error" 2 "$Z" --check
expect_err "... that says what is missing" "--check"
expect_status "--check with a bad option is a usage error" 2 "$Z" --check --frobnicate "$T/cube.obj"
expect_status "--json without --check or --bench is a usage error (not a picture where JSON was asked)" 2 "$Z" --json -p "$T/cube.obj"
expect_err "... that says what it goes with" "--json goes with --check, --diff, --bench or --repair"

expect_status "several files: one verdict line" 3 "$Z" --check "$T/cube.obj" "$T/open.obj" "$T/flip.obj"
n=$(grep -c '^verdict' "$T/out")
if [ "$n" -eq 1 ]; then ok "... exactly one"; else notok "... exactly one" "$n"; fi
last=$(tail -n 1 "$T/out")
want="verdict: $T/open.obj: 1 hole (4 boundary edges); $T/flip.obj: 1 flipped face"
if [ "$last" = "$want" ]; then ok "... naming each file with problems"; else notok "... naming each file with problems" "got '$last'"; fi

# an object per block when a file has several
{ echo 'o first'; cat "$T/cube.obj"; echo 'o second'; printf 'v 3 0 0\nv 4 0 0\nv 3 1 0\nf 9 10 11\n'; } >"$T/two.obj"
expect_status "two objects, one open: 3" 3 "$Z" --check "$T/two.obj"
expect_out "each object has a block" 'object 2 "second"'
expect_out "... and the file its total" "all 2 objects"

expect_status "a write error on stdout exits 1" 1 sh -c "\"$Z\" --check \"$T/cube.obj\" >/dev/full"

# ==== --print --check: the picture, then the report ====
expect_status "--print --check exits as --check" 3 "$Z" --print --check -s 40x12 "$T/open.obj"
pic=$(grep -n "$(printf '\033')" "$T/out" | tail -n 1 | cut -d: -f1)
rep=$(grep -n "^$T/open.obj (obj)" "$T/out" | cut -d: -f1)
if [ -n "$pic" ] && [ -n "$rep" ] && [ "$pic" -lt "$rep" ]; then ok "... the picture first, the report after"
else notok "... the picture first, the report after" "last picture line ${pic:-none}, report at ${rep:-none}"; fi

# ==== --json ====
if need_python "--check --json parses"; then
    expect_status "--json exits as the text report" 3 "$Z" --check --json "$T/cube.obj" "$T/open.obj" "$T/cross.obj"
    cp "$T/out" "$T/three.json"
    expect_status "--json with a missing file exits 1" 1 "$Z" --check --json "$T/cube.obj" "$T/none.obj"
    cp "$T/out" "$T/missing.json"
    expect_status "--json of a sound cube exits 0" 0 "$Z" --check --json "$T/cube.obj"
    cp "$T/out" "$T/sound.json"
    # names, types and values as the man page documents them
    cat >"$T/schema.py" <<'EOF'
import json, sys
T = sys.argv[1]
INT = ["faces", "vertices", "components", "boundary_edges", "holes", "nonmanifold_edges",
       "nonmanifold_vertices", "inconsistent_faces", "degenerate_faces", "duplicate_faces",
       "unused_vertices", "self_intersections", "pair_tests", "pair_budget"]
BOOL = ["ok", "inside_out", "watertight", "non_orientable", "intersections_stopped"]
def fail(msg):
    print(msg)
    sys.exit(1)
def num(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)
def counts(o, where):
    for k in INT:
        if not isinstance(o.get(k), int) or isinstance(o[k], bool) or o[k] < 0:
            fail("%s: %s is %r" % (where, k, o.get(k)))
    for k in BOOL:
        if not isinstance(o.get(k), bool):
            fail("%s: %s is %r" % (where, k, o.get(k)))
    if not num(o.get("area")):
        fail("%s: area %r" % (where, o.get("area")))
    for k in ("size", "min"):
        if not (isinstance(o.get(k), list) and len(o[k]) == 3 and all(num(x) for x in o[k])):
            fail("%s: %s %r" % (where, k, o.get(k)))
    closed = o["boundary_edges"] == 0 and not o["non_orientable"]
    if closed:
        if not num(o.get("volume")) or o["volume"] < 0:
            fail("%s: volume %r" % (where, o.get("volume")))
        if not (isinstance(o.get("center_of_mass"), list) and len(o["center_of_mass"]) == 3):
            fail("%s: center_of_mass %r" % (where, o.get("center_of_mass")))
    elif o.get("volume", 0) is not None or o.get("center_of_mass", 0) is not None:
        fail("%s: not closed, volume %r centre %r" % (where, o.get("volume"), o.get("center_of_mass")))
    if not (isinstance(o.get("problems"), list) and all(isinstance(p, str) for p in o["problems"])):
        fail("%s: problems %r" % (where, o.get("problems")))
    if o["ok"] != (len(o["problems"]) == 0):
        fail("%s: ok %r with problems %r" % (where, o["ok"], o["problems"]))

three = json.load(open(T + "/three.json"))
if three["ok"] is not False:
    fail("three files with problems: ok %r" % three["ok"])
objs = three["objects"]
if [o["file"] for o in objs] != [T + "/cube.obj", T + "/open.obj", T + "/cross.obj"]:
    fail("objects %r" % [o["file"] for o in objs])
for o in objs:
    counts(o, o["file"])
    if not isinstance(o["name"], str):
        fail("name %r" % o["name"])
for f in three["files"]:
    counts(f, f["path"])
cube, open_, cross = objs
want = {"faces": 6, "vertices": 8, "components": 1, "boundary_edges": 0, "holes": 0, "watertight": True,
        "inside_out": False, "self_intersections": 0, "ok": True, "volume": 1, "area": 6,
        "center_of_mass": [0.5, 0.5, 0.5], "size": [1, 1, 1], "intersections_stopped": False,
        "pair_budget": 64 * 12 + 2 ** 20}
for k, v in want.items():
    if cube[k] != v:
        fail("cube: %s %r, wanted %r" % (k, cube[k], v))
if (open_["boundary_edges"], open_["holes"], open_["volume"], open_["watertight"], open_["ok"]) != (4, 1, None, False, False):
    fail("open cube: %r" % open_)
if open_["problems"] != ["1 hole (4 boundary edges)"]:
    fail("open cube problems %r" % open_["problems"])
if cross["self_intersections"] != 6 or cross["components"] != 2 or cross["ok"]:
    fail("crossing cubes: %r" % cross)

missing = json.load(open(T + "/missing.json"))
if missing["ok"] is not False or len(missing["files"]) != 2 or len(missing["objects"]) != 1:
    fail("missing: %r" % missing)
bad = missing["files"][1]
if bad["ok"] is not False or T + "/none.obj" not in bad["error"]:
    fail("missing file entry %r" % bad)

sound = json.load(open(T + "/sound.json"))
if sound["ok"] is not True or sound["files"][0]["unit"] is not None or sound["files"][0]["format"] != "obj":
    fail("sound: %r" % sound["files"][0])
print("ok")
EOF
    r=$(python3 "$T/schema.py" "$T" 2>&1)
    if [ "$r" = ok ]; then ok "--check --json: the documented names, types and values"; else notok "--check --json: the documented names, types and values" "$r"; fi

    # an object name that is not UTF-8, with a quote and a backslash
    { printf 'o we"ird\\\377name\n'; cat "$T/cube.obj"; } >"$T/name.obj"
    "$Z" --check --json "$T/name.obj" >"$T/name.json" 2>/dev/null
    r=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["objects"][0]["name"])' "$T/name.json" 2>&1)
    want=$(printf 'we"ird\\\357\277\275name')
    if [ "$r" = "$want" ]; then ok "--json escapes names and replaces bytes that are not UTF-8"; else notok "--json escapes names and replaces bytes that are not UTF-8" "$r"; fi
fi

# ==== Degenerate faces: counted, and out of the topology ====
{ cat "$T/cube.obj"; printf 'f 1 1 2\nf 3 3 3\n'; } >"$T/degen.obj"
expect_status "a cube with degenerate faces on its edge and corner exits 3" 3 "$Z" --check "$T/degen.obj"
expect_out "... which are counted" "faces         8, 2 degenerate, 0 duplicate"
expect_out "... and make no part" "parts         1"
expect_out "... no non-manifold edge, the cube still watertight" "0 boundary in 0 holes, 0 non-manifold (watertight)"
expect_out "... no non-manifold vertex" "vertices      8, 0 non-manifold, 0 unused"
printf 'v 0 0 0\nv 1 0 0\nf 1 2 1\n' >"$T/collapsed.obj"
expect_status "a triangle collapsed to two points exits 3" 3 "$Z" --check "$T/collapsed.obj"
if grep -q "watertight" "$T/out"; then notok "... and is not watertight" "$(cat "$T/out")"; else ok "... and is not watertight"; fi
expect_out "... nor closed" "volume        none: not closed"

# ==== Hostile inputs: the crossing test is bounded (issue 28) ====
# tests/e2e/hostile_check.py writes them (binary STL); each stops at its
# budget of pair tests (64 a triangle + 2^20, and what two threads may
# have under way) and says so. Not timed: the work is counted.
if need_python "--check of hostile inputs"; then
    for c in "fan 10000" "coincident 16000" "edge 100000" "stacked 20000"; do
        set -- $c
        f="$T/$1-$2.stl"
        python3 tests/e2e/hostile_check.py "$1" "$2" "$f"
        expect_status "$1 $2: exits 3" 3 "$Z" --check -j2 "$f"
        case $1 in
            coincident) expect_out "... $(($2 - 1)) duplicates, left out of the crossing test" "crossing      0 pairs of faces" ;;
            stacked) expect_out "... a lower bound, and where it stopped" "crossing      at least " ;;
            *) expect_out "... none found, and where it stopped" "crossing      at least 0 pairs of faces (stopped after" ;;
        esac
        "$Z" --check --json -j2 "$f" >"$T/h.json" 2>/dev/null
        cat >"$T/h.py" <<'EOF'
import json, sys
o = json.load(open(sys.argv[1]))["objects"][0]
kind, n = sys.argv[2], int(sys.argv[3])
tris = 1 if kind == "coincident" else n
budget = 64 * tris + 2 ** 20
if o["pair_budget"] != budget:
    print("budget %d, wanted %d" % (o["pair_budget"], budget)); sys.exit()
stopped = kind != "coincident"
if o["intersections_stopped"] is not stopped:
    print("stopped %r" % o["intersections_stopped"]); sys.exit()
if stopped and not budget <= o["pair_tests"] <= budget + 2 * 8192:
    print("pair tests %d, budget %d" % (o["pair_tests"], budget)); sys.exit()
if stopped and not any(p.startswith("at least %d intersecting face pair" % o["self_intersections"]) for p in o["problems"]):
    print("problems %r" % o["problems"]); sys.exit()
if kind == "coincident" and (o["duplicate_faces"] != n - 1 or o["pair_tests"] != 0):
    print("coincident: %r" % o); sys.exit()
print("ok")
EOF
        r=$(python3 "$T/h.py" "$T/h.json" "$1" "$2" 2>&1)
        if [ "$r" = ok ]; then ok "... --json: within the budget, stopped and said so"; else notok "... --json: within the budget, stopped and said so" "$r"; fi
    done
fi

# ==== Other formats: the loaders' meshes, the same answers ====
printf 'OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 0 4 7 3\n4 1 2 6 5\n' >"$T/cube.off"
expect_status "an OFF cube is sound" 0 "$Z" --check "$T/cube.off"
expect_out "... in OFF" "$T/cube.off (off)"

# ==== The unit a format states (through assimp: 3MF millimetres, glTF metres) ====
"$Z" --formats >"$T/formats" 2>/dev/null
A=/usr/share/assimp/models
if ! grep -q '^3mf ' "$T/formats"; then
    skip "3MF states millimetres" "no assimp in this build"
elif [ ! -r "$A/3MF/box.3mf" ]; then
    skip "3MF states millimetres" "no assimp-testmodels (tools/deps.sh)"
else
    expect_status "a 3MF box is sound" 0 "$Z" --check "$A/3MF/box.3mf"
    expect_out "... its size in millimetres" "size          10 x 20 x 30 mm"
    expect_out "... its volume in cubic millimetres" "volume        6000 mm^3, centre of mass 5 10 15"
    expect_status "a glTF box" 0 "$Z" --check --json "$A/glTF2/BoxTextured-glTF/BoxTextured.gltf"
    expect_out "... states metres" '"unit": "m"'
fi
