#!/bin/sh
# make bench-load: loading big OBJ files (issue 21). For the dragon and
# the dragon subdivided once (5.2M triangles) and twice (31M; tools/subdiv
# writes both into a temporary folder, deleted at the end unless KEEP=1):
# the whole first picture of `--print` (load, scene, one frame) against
# `wc -l` of the same file, read from the page cache, wall-clock medians
# of RUNS runs; and the most memory resident (max RSS, /usr/bin/time) per
# triangle. With BEFORE=path/to/zview (a build of an older commit) each
# case runs with it too, in the same run, so that rows compare. The
# timed rows are wall clock and so depend on the machine being quiet; the
# ratio to `wc -l` is taken within one run. SKIP_31M=1 leaves out the 31M
# model (1.4 GB of disk and about a minute to write).
set -u
ZV=${ZVIEW:-./zview}
BEFORE=${BEFORE:-}
SUBDIV=${SUBDIV:-build/subdiv}
S=../shared/models
RUNS=${RUNS:-3}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-load-XXXXXX")
[ "${KEEP:-0}" = 1 ] || trap 'rm -rf "$TMP"' EXIT INT TERM
sh "$(dirname "$0")/stamp.sh" "make bench-load (tools/bench-load.sh), RUNS=$RUNS"

D=$S/dragon.obj
if [ ! -f "$D" ]; then
    echo "bench-load: $D is missing"
    exit 0
fi
models="$D"
if [ -x "$SUBDIV" ]; then
    "$SUBDIV" "$D" "$TMP/dragon-5m.obj" >/dev/null && models="$models $TMP/dragon-5m.obj"
    if [ "${SKIP_31M:-0}" != 1 ] && "$SUBDIV" "$TMP/dragon-5m.obj" "$TMP/dragon-31m.obj" >/dev/null; then
        models="$models $TMP/dragon-31m.obj"
    fi
fi

# median of the numbers on stdin
median() { sort -n | awk '{ a[NR] = $1 } END { print NR ? a[int((NR + 1) / 2)] : "-" }'; }

# secs CMD...: the median wall time of RUNS runs, seconds
secs() {
    for i in $(seq "$RUNS"); do
        /usr/bin/time -f "%e" -o "$TMP/t" "$@" >/dev/null 2>&1
        cat "$TMP/t"
    done | median
}

# rss CMD...: max resident set of one run, KB
rss() {
    /usr/bin/time -f "%M" -o "$TMP/t" "$@" >/dev/null 2>&1
    cat "$TMP/t"
}

echo
echo "## first picture (--print --size 80x24) against wc -l of the same cached file; medians of $RUNS, seconds"
printf "%-14s %-10s %8s %8s %8s %8s %10s %8s\n" "model" "build" "threads" "wc_s" "print_s" "x_wc" "rss_MB" "B/tri"
for m in $models; do
    name=$(basename "$m" .obj)
    cat "$m" >/dev/null
    tris=$("$ZV" --info "$m" | awk '/^triangles:/ { print $2 }')
    wc=$(secs wc -l "$m")
    for b in after ${BEFORE:+before}; do
        set -- "$ZV"
        # the older builds refuse more than 20M polygons unless told
        [ "$b" = before ] && set -- "$BEFORE" --max-polys 2000000000
        for t in 1 2; do
            p=$(secs "$@" --print --size 80x24 --threads "$t" "$m")
            kb=$(rss "$@" --print --size 80x24 --threads "$t" "$m")
            awk -v n="$name" -v b="$b" -v t="$t" -v w="$wc" -v p="$p" -v kb="$kb" -v tri="$tris" 'BEGIN {
                printf "%-14s %-10s %8s %8.2f %8.2f %8.1f %10.0f %8.1f\n", n, b, t, w, p, w > 0 ? p / w : 0, kb / 1024, kb * 1024 / tri }'
        done
    done
done
