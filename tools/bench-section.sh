#!/bin/sh
# tools/bench-section.sh: what a section cut costs a frame (issue 32).
# The dragon at the viewer's 160x48 cells (160x96 pixels, 4 samples,
# as make bench's row), medians of VIEWS views of zview --bench, pinned
# to one core: whole, cut by a plane that slides every view (bench.c:
# the cut made again each frame, as the viewer's ; and ' keys make it),
# then by two sliding planes. The goal is 20 frames a second: 50 ms.
set -u
ZV=${ZVIEW:-./zview}
S=../shared/models
D=$S/dragon.obj
VIEWS=${VIEWS:-8}
[ -f "$D" ] || { echo "bench-section: $D is not there" >&2; exit 1; }
sh "$(dirname "$0")/stamp.sh" "tools/bench-section.sh, VIEWS=$VIEWS views"
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
row() {
    name=$1
    shift
    $PIN "$ZV" --bench --json --views "$VIEWS" --threads 1 --size 160x96 --samples 4 --algo zbuffer "$@" "$D" | awk -v n="$name" '
        { for (i = 1; i <= NF; i++) { k = $i; gsub(/[":,{}]/, "", k); v = $(i + 1); gsub(/[",}]/, "", v); f[k] = v } }
        END { printf "%-40s %9s %9s %8s %8s %8s\n", n, f["frame_median_ms"], f["cpu_median_ms"], f["project_median_ms"],
              f["median_ms"], f["shade_median_ms"] }'
}
printf "%-40s %9s %9s %8s %8s %8s\n" "dragon 160x96, 4 samples, 1 thread" "frame_ms" "cpu_ms" "proj" "hsr" "shade"
row "whole"
row "cut sliding, z" --section z=0
row "cut sliding, two planes" --section z=0 --section 0,0,0:1,1,0
