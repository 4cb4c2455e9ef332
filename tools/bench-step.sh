#!/bin/sh
# A STEP part's first picture (issue 34): zview -o x.png against f3d's
# --output (under xvfb-run, as it needs a display) on the same ~1 MB file
# (tools/occtgen.cpp --bench: a plate of N x N holes, each in a ring;
# N = 11 is 0.99 MB), alternately, pinned to one core, RUNS times each:
# the medians of the whole command's wall time and of its CPU time (user
# + system, children included), and f3d --no-render (the load alone).
# The sandboxed zview's CPU leaves out its loading child (the fork
# server's child, not the command's): zview --no-sandbox gives the whole.
# Both read through OpenCASCADE 7.6; zview at --tessellation's default
# (0.1% of the diagonal), f3d at its own. RUNS=N (default 5), N=holes a side.
set -u
Z=${ZVIEW:-./zview}
G=${OCCTGEN:-build/occtgen}
RUNS=${RUNS:-5}
N=${N:-11}
CPU=${CPU:-1}
command -v f3d >/dev/null && command -v xvfb-run >/dev/null ||
    { echo "bench-step: needs f3d and xvfb-run (tools/deps.sh installs f3d)" >&2; exit 1; }
[ -x "$G" ] || { echo "bench-step: $G not built (OpenCASCADE's headers missing?)" >&2; exit 1; }
sh "$(dirname "$0")/stamp.sh" "make bench-step" 2>/dev/null
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
"$G" --bench "$T" "$N" || exit 1
F=$T/plate.step
# one: NAME CMD...: its wall (ms) and CPU (ms) appended to T/NAME.*
one() {
    name=$1
    shift
    /usr/bin/time -f "%e %U %S" -o "$T/t" taskset -c "$CPU" "$@" >/dev/null 2>&1 ||
        { echo "bench-step: $name failed: $*" >&2; exit 1; }
    awk '{ print $1 * 1000 }' "$T/t" >>"$T/$name.wall"
    awk '{ print ($2 + $3) * 1000 }' "$T/t" >>"$T/$name.cpu"
}
i=0
while [ $i -lt "$RUNS" ]; do
    one zview "$Z" -o "$T/z.png" -s 800x600 "$F"
    one zview-nosb "$Z" --no-sandbox -o "$T/z.png" -s 800x600 "$F"
    one f3d xvfb-run -a f3d --output "$T/f.png" --resolution 800,600 "$F"
    one f3d-load f3d --no-render "$F"
    i=$((i + 1))
done
med() { sort -n "$1" | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
tris=$("$Z" --info "$F" | sed -n 's/^triangles: *//p')
echo "file: a plate of $N x $N holes, $(wc -c <"$F") bytes; zview tessellates it to $tris triangles"
echo "$RUNS runs each, pinned to CPU $CPU, medians (wall, CPU of the command and its children)"
for k in zview zview-nosb f3d f3d-load; do
    printf '%-42s %8.0f ms wall %8.0f ms CPU%s\n' "$(case $k in zview) echo "zview -o x.png -s 800x600" ;;
        zview-nosb) echo "zview --no-sandbox -o x.png -s 800x600" ;;
        f3d) echo "xvfb-run f3d --output x.png" ;; *) echo "f3d --no-render (the load alone)" ;; esac)" \
        "$(med "$T/$k.wall")" "$(med "$T/$k.cpu")" "$([ $k = zview ] && echo ' (not the child)')"
done
awk -v a="$(med "$T/zview.wall")" -v b="$(med "$T/f3d.wall")" -v c="$(med "$T/zview-nosb.cpu")" -v d="$(med "$T/f3d.cpu")" \
    'BEGIN { printf "zview / f3d: %.2f of the wall time (sandboxed), %.2f of the CPU time (--no-sandbox)\n", a / b, c / d }'
