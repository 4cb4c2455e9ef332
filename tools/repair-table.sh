#!/bin/sh
# The README's table of --repair against admesh: the broken parts of
# tests/e2e/brokenstl.py, each repaired by `zview --repair` and by
# `admesh` (every fix it has: its default), and each result counted by
# tests/e2e/meshcount.py, not by either tool: watertight (no boundary,
# non-manifold or misoriented edge, no pinched vertex, no degenerate
# face, every part's volume positive), and the volume by the divergence
# theorem. Prints a Markdown table after the stamp line.
#   sh tools/repair-table.sh
set -u
ZV=${ZVIEW:-./zview}
command -v admesh >/dev/null 2>&1 || { echo "repair-table: no admesh (sh tools/deps.sh installs it)"; exit 1; }
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-repair-table-XXXXXX")
trap 'rm -rf "$TMP"' EXIT
sh "$(dirname "$0")/stamp.sh" "sh tools/repair-table.sh ($(admesh --version 2>&1 | head -n 1))"
python3 tests/e2e/brokenstl.py "$TMP"
for f in "$TMP"/*.stl; do
    name=$(basename "$f" .stl)
    "$ZV" --repair "$f" -o "$TMP/$name.zview.out.stl" >/dev/null 2>&1
    admesh -b "$TMP/$name.admesh.out.stl" "$f" >/dev/null 2>&1
done
python3 - "$TMP" <<'EOF'
import glob, os, sys
sys.path.insert(0, "tests/e2e")
from meshcount import count
d = sys.argv[1]
what = {
    "open-box": "a cube missing a face",
    "flipped": "a cube, one triangle flipped",
    "inside-out": "a cube inside out",
    "twisted": "a hole whose 4 edges are in no plane",
    "fin": "a fin on a cube's edge",
    "hole-200": "a hole of 200 edges",
    "moebius": "a Moebius strip",
    "part-inside-out": "two cubes, one inside out",
    "edge-touching": "two cubes on one edge",
    "corner-touching": "two cubes on one corner",
    "wavy-hole": "a hole of 48 edges far from a plane",
}
def cell(path):
    if not os.path.exists(path):
        return "no output"
    c = count(path)
    if c["watertight"]:
        return "watertight, volume %.4g" % c["volume"]
    left = []
    for k, w in (("boundary", "boundary edges"), ("nonmanifold", "non-manifold edges"), ("pinched", "pinched vertices"),
                 ("misoriented", "misoriented edges"), ("inside_out_parts", "parts inside out"), ("degenerate", "degenerate")):
        if c[k]:
            left.append("%d %s" % (c[k], w))
    return "not: " + ", ".join(left)
print("| broken part | admesh | zview --repair |")
print("|---|---|---|")
for f in sorted(glob.glob(d + "/*.stl")):
    name = os.path.basename(f)[:-4]
    if name.endswith(".out"):
        continue
    print("| %s (`%s`) | %s | %s |" % (what.get(name, name), name, cell(d + "/" + name + ".admesh.out.stl"),
                                    cell(d + "/" + name + ".zview.out.stl")))
EOF
