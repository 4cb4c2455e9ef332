#!/bin/sh
# make bench-repair-cli: what zview --repair costs (issue 30's targets):
# the dragon (871k triangles) repaired and written as OBJ and as STL on
# one thread (goal: 1.5 s, writing included), the 5.2M-triangle
# model (tools/subdiv, as make bench makes it) on two threads (goal:
# 10 s), and the peak resident memory of each against loading alone
# (checkbench --load-only: mesh_load and nothing else; goal: within 3x).
# Each row is the median wall time of RUNS processes under
# /usr/bin/time, with their CPU time (user + system: a crowded
# machine's wall clock counts waiting) and --json's phases (load, the
# check of the input, the repair less its checks, write, the check of
# what OUT holds; then the repair's own: weld, clean, objects, order,
# and its check of what it made, which is the check after unless OUT
# was read back; ms). The
# dragon's rows are on one thread pinned to a core (PIN), the 5.2M
# model's on two. HEADER=0 (make bench) prints the same figures as rows
# of make bench's table instead, without the stamp; BIG_DIR: where the
# 5.2M model is (or is made).
set -u
ZV=${ZVIEW:-./zview}
CB=${CHECKBENCH:-build/checkbench}
SUBDIV=${SUBDIV:-build/subdiv}
RUNS=${RUNS:-3}
S=../shared/models
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
HEADER=${HEADER:-1}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-repair-cli-XXXXXX")
trap 'rm -rf "$TMP"' EXIT
trap 'exit 1' HUP INT PIPE TERM
[ "$HEADER" = 1 ] && sh "$(dirname "$0")/stamp.sh" "make bench-repair-cli (tools/bench-repair-cli.sh), RUNS=$RUNS"
D=$S/dragon.obj
[ -f "$D" ] || { echo "bench-repair-cli: $D not found (../shared/models)"; exit 0; }
[ -x /usr/bin/time ] || { echo "bench-repair-cli: no /usr/bin/time"; exit 0; }
big5m=${BIG_DIR:-$TMP}/dragon-5m.obj
if [ ! -s "$big5m" ]; then
    [ -x "$SUBDIV" ] && "$SUBDIV" "$D" "$big5m" >/dev/null 2>&1 || rm -f "$big5m"
fi

# loading alone: the peak of a process that only loads (MB)
load_mb() {
    "$CB" --load-only "$1" | awk '{ for (i = 1; i < NF; i++) if ($i == "peak") { v = $(i + 1); sub(/MB/, "", v); print v } }'
}

# row LABEL GOAL_S LOAD_MB PIN ARGS...: RUNS runs of zview ARGS --json
# (under PIN, "" for none); the median by wall time, with its CPU, peak
# and phases
row() {
    label=$1 goal=$2 base=$3 pin=$4
    shift 4
    i=0
    : >"$TMP/runs"
    while [ "$i" -lt "$RUNS" ]; do
        # shellcheck disable=SC2086
        /usr/bin/time -f "%e %U %S %M" -o "$TMP/time" $pin "$ZV" "$@" --json >"$TMP/json" 2>"$TMP/err"
        rc=$?
        [ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] || { echo "$label: status $rc: $(head -c 300 "$TMP/err")"; return; }
        ms=$(sed -n 's/.*"ms": { \(.*\) }.*/\1/p' "$TMP/json" | tr -d '"' | sed 's/check_after/after/; s/repair_check/its check/; s/repair_//g')
        echo "$(tail -n 1 "$TMP/time") $ms" >>"$TMP/runs"
        i=$((i + 1))
    done
    sort -n "$TMP/runs" | awk -v n="$RUNS" 'NR == int(n / 2) + 1' >"$TMP/med"
    read -r wall user sys kb rest <"$TMP/med"
    cpu=$(echo "$user $sys" | awk '{ printf "%.2f", $1 + $2 }')
    mb=$(echo "$kb" | awk '{ printf "%.0f", $1 / 1024 }')
    ratio=$(echo "$kb $base" | awk '{ printf "%.2fx", $1 / 1024 / $2 }')
    if [ "$HEADER" = 1 ]; then
        printf "| %s | %s | %s | %s | %s | %s | %s |\n" "$label" "$wall" "$cpu" "$mb" "$ratio" "$rest" "$goal"
    else        # make bench's columns: wall s, CPU s, the goal
        printf "%-46s %9s %9s %8s %8s %8s   %s\n" "repair: $label" "$wall" "$cpu" "" "" "" \
            "$goal (wall s; peak $mb MB, $ratio loading alone)"
    fi
}

# a table's line (HEADER=1 only)
say() {
    [ "$HEADER" = 1 ] && echo "$@"
}

say
say "| case | wall s | CPU s | peak MB | of loading alone | phases (ms) | goal |"
say "|---|---:|---:|---:|---:|---|---|"
base=$(load_mb "$D")
say "| dragon, loading alone (checkbench, its load-only mode) | | | $base | 1.00x | | |"
row "dragon -j 1 -o .obj" "<= 1.5 s, <= 3x" "$base" "$PIN" --repair -j 1 "$D" -o "$TMP/dragon.obj"
row "dragon -j 1 -o .stl" "<= 1.5 s, <= 3x" "$base" "$PIN" --repair -j 1 "$D" -o "$TMP/dragon.stl"
if [ -s "$big5m" ]; then
    base=$(load_mb "$big5m")
    say "| 5.2M triangles, loading alone | | | $base | 1.00x | | |"
    row "5.2M triangles -j 2 -o .obj" "<= 10 s, <= 3x" "$base" "" --repair -j 2 "$big5m" -o "$TMP/5m.obj"
else
    echo "5.2M triangles: $SUBDIV could not write $big5m"
fi
