#!/bin/sh
# The README's table of --repair against admesh: the broken parts of
# tests/e2e/brokenstl.py, each repaired by `zview --repair` and by
# `admesh` (every fix it has: its default), and each result counted by
# tests/e2e/meshcount.py, not by either tool: watertight (no boundary,
# non-manifold or misoriented edge, no pinched vertex, no degenerate
# face, every part's volume positive), the volume by the divergence
# theorem, and the faces of the part a tool deleted. Prints a Markdown
# table after the stamp line.
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
order = ["open-box", "flipped", "inside-out", "twisted", "fin", "hole-200", "moebius", "wavy-hole", "part-inside-out",
         "edge-touching", "corner-touching"]
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
def cell(path, faces_in):
    if not os.path.exists(path):
        return "no output"
    c = count(path)
    gone = faces_in - c["faces"]
    if c["watertight"]:
        return "watertight, volume %.4g" % c["volume"] + (", %d face%s deleted" % (gone, "s" if gone > 1 else "") if gone > 0 else "")
    left = []
    for k, one, many in (("boundary", "boundary edge", "boundary edges"),
                         ("nonmanifold", "non-manifold edge", "non-manifold edges"),
                         ("pinched", "pinched vertex", "pinched vertices"),
                         ("misoriented", "misoriented edge", "misoriented edges"),
                         ("inside_out_parts", "part inside out", "parts inside out"),
                         ("degenerate", "degenerate face", "degenerate faces")):
        if c[k]:
            left.append("%d %s" % (c[k], one if c[k] == 1 else many))
    return "not: " + ", ".join(left)
print("| broken part | admesh | zview --repair |")
print("|---|---|---|")
names = [os.path.basename(f)[:-4] for f in glob.glob(d + "/*.stl") if not f.endswith(".out.stl")]
for name in sorted(names, key=lambda n: (order.index(n) if n in order else len(order), n)):
    n = count(d + "/" + name + ".stl")["faces"]
    print("| %s (`%s`) | %s | %s |" % (what.get(name, name), name, cell(d + "/" + name + ".admesh.out.stl", n),
                                    cell(d + "/" + name + ".zview.out.stl", n)))
EOF
