#!/bin/sh
# zview --repair on broken parts (tests/e2e/brokenstl.py: a cube missing
# a face, a flipped face, inside out, a twisted-quad hole, a fin, a hole
# of 200 edges, a Moebius strip, an inside-out part beside a sound one,
# two cubes on one edge or one corner, a wavy hole), repaired by zview
# and by admesh, every result counted by tests/e2e/meshcount.py (edge
# uses, pinched vertices, each part's volume by the divergence theorem:
# not by --check): wherever admesh makes a part watertight zview does
# too (the fin among them: both delete its stray triangle), and zview
# does where admesh does not (the inside-out part, the cubes
# on an edge or a corner); the exit status and --json's "ok" agree with
# the count; the .obj and .ply of a repair count as its .stl.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
need_python "broken parts repaired" || exit 0

# ==== Broken parts: zview against admesh, counted apart ====
python3 tests/e2e/brokenstl.py "$T/b"
have_admesh=1
command -v admesh >/dev/null 2>&1 || { have_admesh=0; skip "zview against admesh" "no admesh (tools/deps.sh installs it)"; }
# every repair first (python3 starts slowly: one run of it judges them all)
for f in "$T"/b/*.stl; do
    name=$(basename "$f" .stl)
    "$Z" --repair --json "$f" -o "$T/b/$name-z.stl" >"$T/b/$name.json" 2>"$T/b/$name.err"
    echo $? >"$T/b/$name.rc"
    for ext in obj ply; do
        "$Z" --repair "$f" -o "$T/b/$name-z.$ext" >/dev/null 2>&1
    done
    [ "$have_admesh" -eq 1 ] && admesh -b "$T/b/$name-a.stl" "$f" >/dev/null 2>&1
done
# beyond admesh: these (tools/repair-table.sh shows the table)
python3 - "$T/b" "$have_admesh" "part-inside-out edge-touching corner-touching" <<'EOF'
import glob, json, os, sys
sys.path.insert(0, "tests/e2e")
from meshcount import count
d, have_admesh, beyond = sys.argv[1], sys.argv[2] == "1", sys.argv[3].split()
def say(good, name, why=""):
    print("ok - " + name if good else "not ok - " + name + ("\n#   " + why if why else ""))
for f in sorted(glob.glob(d + "/*.stl")):
    name = os.path.basename(f)[:-4]
    if name.endswith("-z") or name.endswith("-a"):
        continue
    z = count(d + "/" + name + "-z.stl")
    rc = int(open(d + "/" + name + ".rc").read())
    try:
        ok_json = json.load(open(d + "/" + name + ".json"))["ok"]
    except (ValueError, KeyError) as e:
        ok_json = "unreadable (%s)" % e
    agree = (z["watertight"] and rc == 0 and ok_json is True) or (not z["watertight"] and rc == 3 and ok_json is False)
    say(agree, "%s: the status (%d) and --json's ok agree with the count" % (name, rc),
        "watertight %s, json ok %s: %s %s" % (z["watertight"], ok_json, z, open(d + "/" + name + ".err").read()[:200]))
    for ext in ("obj", "ply"):
        w = count(d + "/" + name + "-z." + ext)["watertight"]
        say(w == z["watertight"], "%s: the .%s as watertight as the .stl" % (name, ext), "%s against %s" % (w, z["watertight"]))
    if name in beyond:
        say(z["watertight"], "%s: zview makes it watertight" % name, str(z))
    if name == "fin":
        # the stray triangle dropped, the cube as it was: volume 1, one
        # face fewer than the input
        i = count(f)
        say(z["watertight"] and abs(z["volume"] - 1) < 1e-6 and z["faces"] == i["faces"] - 1,
            "fin: zview drops the stray triangle alone, the cube watertight, volume 1", str(z))
    if have_admesh:
        a = count(d + "/" + name + "-a.stl")["watertight"]
        say(not a or z["watertight"], "%s: watertight by zview wherever by admesh (admesh %d, zview %d)" %
            (name, a, z["watertight"]), str(z))
EOF
expect_status "the fin's stray triangle dropped: 0" 0 "$Z" --repair "$T/b/fin.stl" -o "$T/b/f.stl"
expect_out "... the report says so" "1 stray fin face dropped"
expect_status "a Moebius strip stays a problem (3)" 3 "$Z" --repair "$T/b/moebius.stl" -o "$T/b/m.stl"
expect_out "... said non-orientable" "non-orientable"
expect_status "the twisted hole filled: 0" 0 "$Z" --repair "$T/b/twisted.stl" -o "$T/b/t.stl"
expect_out "... the report counts it filled" "1 hole filled"
expect_status "--max-hole 100 leaves the 200-edge hole open: 3" 3 "$Z" --repair --max-hole 100 "$T/b/hole-200.stl" -o "$T/b/h.stl"
expect_out "... and says why" "more edges than the limit"
expect_status "--repair=winding alone leaves the hole: 3" 3 "$Z" --repair=winding "$T/b/open-box.stl" -o "$T/b/o.stl"
expect_out "... the other steps not asked" "not asked  weld, clean, manifold, holes"
expect_status "--weld says the distance it used" 0 "$Z" --repair --weld 0.001 "$T/b/flipped.stl" -o "$T/b/w.stl"
expect_out "... in the report" "--weld 0.001"
