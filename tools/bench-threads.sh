#!/bin/sh
# Two threads against one (issues 21 and 35): the dragon's z-buffer frame
# at 1920x1080 (1 sample) and at 160x96 (4 samples, the viewer's 160x48
# cells), medians of VIEWS views of zview --bench; the one-thread run
# pinned to a core (BENCH_CPU, default 0; PIN= turns that off), the
# two-thread run free. One row each, in make bench's columns (bench.sh
# and bench-speed.sh call this); MD=1 prints them as table rows of
# bench-speed.sh instead. MODEL=... another model.
set -u
ZV=${ZVIEW:-./zview}
VIEWS=${VIEWS:-8}
D=${MODEL:-../shared/models/dragon.obj}
GOAL=${GOAL:->= 1.85x}
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
[ -f "$D" ] || { echo "bench-threads: $D not found"; exit 0; }
frame() {
    "$@" | awk '{ for (i = 1; i <= NF; i++) if ($i == "\"frame_median_ms\":") { v = $(i + 1); gsub(/[",}]/, "", v); print v } }'
}
for args in "--size 1920x1080 --samples 1" "--size 160x96 --samples 4"; do
    # shellcheck disable=SC2086
    one=$(frame $PIN "$ZV" --bench --json --views "$VIEWS" --threads 1 --algo zbuffer $args "$D")
    # shellcheck disable=SC2086
    two=$(frame "$ZV" --bench --json --views "$VIEWS" --threads 2 --algo zbuffer $args "$D")
    # shellcheck disable=SC2086
    set -- $args
    awk -v md="${MD:-0}" -v n="$(basename "$D" .obj) $2 x$4: 2 threads against 1" -v o="$one" -v t="$two" -v g="$GOAL" 'BEGIN {
        r = sprintf("%.2fx", (t > 0 ? o / t : 0))
        if (md) printf "| %s | %s | %s | %s ms against %s ms, frame medians |\n", n, r, g, o, t
        else printf "%-46s %9s %9s %8s %8s %8s   %s (%s ms against %s ms)\n", n, r, "", "", "", "", g, o, t }'
done
