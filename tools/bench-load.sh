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
# model (1.4 GB of disk and about a minute to write). BIG_DIR=folder
# takes dragon-5m.obj and dragon-31m.obj from there when they are in it
# (make bench writes them once for all its rows), instead of writing them.
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
if [ -n "${BIG_DIR:-}" ] && [ -s "$BIG_DIR/dragon-5m.obj" ]; then
    models="$models $BIG_DIR/dragon-5m.obj"
    [ "${SKIP_31M:-0}" != 1 ] && [ -s "$BIG_DIR/dragon-31m.obj" ] && models="$models $BIG_DIR/dragon-31m.obj"
elif [ -x "$SUBDIV" ]; then
    "$SUBDIV" "$D" "$TMP/dragon-5m.obj" >/dev/null && models="$models $TMP/dragon-5m.obj"
    if [ "${SKIP_31M:-0}" != 1 ] && "$SUBDIV" "$TMP/dragon-5m.obj" "$TMP/dragon-31m.obj" >/dev/null; then
        models="$models $TMP/dragon-31m.obj"
    fi
fi

# median of the numbers on stdin
median() { sort -n | awk '{ a[NR] = $1 } END { print NR ? a[int((NR + 1) / 2)] : "-" }'; }

# secs CMD...: "wall cpu max_rss_kb" of RUNS runs: the median wall and
# CPU (user + system) seconds, the largest resident set
secs() {
    for i in $(seq "$RUNS"); do
        t0=$(date +%s%N)
        /usr/bin/time -f "%U %S %M" -o "$TMP/t" "$@" >/dev/null 2>&1
        t1=$(date +%s%N)
        echo "$(( (t1 - t0) / 1000000 )) $(cat "$TMP/t")"
    done | awk '{ printf "%.3f %s %s %s\n", $1 / 1000, $2, $3, $4 }' >"$TMP/runs"
    printf "%s %s %s\n" "$(awk '{ print $1 }' "$TMP/runs" | median)" \
        "$(awk '{ print $2 + $3 }' "$TMP/runs" | median)" "$(awk '{ print $4 }' "$TMP/runs" | sort -n | tail -1)"
}

echo
echo "## first picture (--print --size 80x24) against wc -l of the same cached file; medians of $RUNS, seconds"
echo "## (wall: the clock, which other jobs on the machine stretch; cpu: user + system of all threads)"
printf "%-14s %-8s %7s %7s %8s %7s %7s %9s %7s\n" "model" "build" "threads" "wc_s" "print_s" "x_wc" "cpu_s" "rss_MB" "B/tri"
for m in $models; do
    name=$(basename "$m" .obj)
    cat "$m" >/dev/null
    tris=$("$ZV" --info "$m" | awk '/^triangles:/ { print $2 }')
    wc=$(secs wc -l "$m" | cut -d' ' -f1)
    for b in after ${BEFORE:+before}; do
        set -- "$ZV"
        # the older builds refuse more than 20M polygons unless told
        [ "$b" = before ] && set -- "$BEFORE" --max-polys 2000000000
        for t in 1 2; do
            set -- $(secs "$@" --print --size 80x24 --threads "$t" "$m") "$@"
            awk -v n="$name" -v b="$b" -v t="$t" -v w="$wc" -v p="$1" -v cpu="$2" -v kb="$3" -v tri="$tris" 'BEGIN {
                printf "%-14s %-8s %7s %7.3f %8.3f %7.1f %7.2f %9.0f %7.1f\n", n, b, t, w, p, (w > 0 ? p / w : 0), cpu, kb / 1024, kb * 1024 / tri }'
            shift 3
        done
    done
done
