#!/bin/sh
# Load speed and peak memory of every format, for the README's table:
# the model (default ../shared/models/dragon.obj) is written in every
# format by the test helpers (tests/writers.c), then each file is loaded
# RUNS times with `zview --info`, pinned to one core; the medians of the
# load time (--info's figure: open, read and parse) and of the peak RSS
# (/usr/bin/time, the whole run: load, scene build, no render) are
# printed as a Markdown table, with the best run beside the median, and
# the median of the load's CPU time (what the load cost, whatever else
# the shared machine ran meanwhile).
# Usage: sh tools/bench-formats.sh [MODEL.obj] (make bench-formats)
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
MODEL=${1:-$ROOT/../shared/models/dragon.obj}
RUNS=${RUNS:-7}
Z=${ZVIEW:-$ROOT/zview}
T=${ZV_FORMATS_OUT:-$(mktemp -d)}
mkdir -p "$T"
cd "$ROOT"
ZV_FORMATS_OUT=$T ZV_FORMATS_MODEL=$MODEL build/zview-tests --filter 'tools/write_formats' >/dev/null 2>&1
ln -sf "$MODEL" "$T/original.obj"
median() { sort -n | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }
best() { sort -n | head -n 1; }
sh "$ROOT/tools/stamp.sh" "make bench-formats (tools/bench-formats.sh $MODEL), RUNS=$RUNS runs"
printf '| format | file MB | load ms, median (best) | MB/s, median (best) | load CPU ms, median (MB/s) | peak RSS MB, median |\n'
printf '|---|---:|---:|---:|---:|---:|\n'
for f in original.obj model.obj model.stl model-ascii.stl model-le.ply model-be.ply model-ascii.ply model.off model.glb; do
    [ -f "$T/$f" ] || continue
    : >"$T/ms"
    : >"$T/cpu"
    : >"$T/rss"
    i=0
    while [ $i -lt "$RUNS" ]; do
        /usr/bin/time -f '%M' -o "$T/time" taskset -c 0 "$Z" --info "$T/$f" >"$T/info" 2>/dev/null
        sed -n 's/^load: *\([0-9.]*\) ms.*/\1/p' "$T/info" >>"$T/ms"
        sed -n 's/^load:.*(cpu \([0-9.]*\) ms.*/\1/p' "$T/info" >>"$T/cpu"
        cat "$T/time" >>"$T/rss"
        i=$((i + 1))
    done
    fmt=$(sed -n 's/^format: *//p' "$T/info")
    [ "$f" = original.obj ] && fmt="obj (the original file)"
    [ "$f" = model.obj ] && fmt="obj (written with %.9g)"
    mb=$(awk -v b="$(wc -c <"$T/$f")" 'BEGIN { printf "%.1f", b / 1e6 }')
    ms=$(median <"$T/ms")
    msb=$(best <"$T/ms")
    cpu=$(median <"$T/cpu")
    rss=$(median <"$T/rss")
    awk -v fmt="$fmt" -v mb="$mb" -v ms="$ms" -v msb="$msb" -v cpu="$cpu" -v rss="$rss" 'BEGIN {
        printf "| %s | %s | %.0f (%.0f) | %.0f (%.0f) | %.0f (%.0f) | %.0f |\n", fmt, mb, ms, msb,
            mb / ms * 1e3, mb / msb * 1e3, cpu, mb / cpu * 1e3, rss / 1024 }'
done
[ -n "${ZV_FORMATS_OUT:-}" ] || rm -rf "$T"
