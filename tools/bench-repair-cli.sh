#!/bin/sh
# make bench-repair-cli: what zview --repair costs (issue 30's targets):
# the dragon (871k triangles) repaired and written as OBJ and as STL on
# the default threads (goal: 1.5 s, writing included), the 5.2M-triangle
# model (tools/subdiv, as make bench makes it) on two threads (goal:
# 10 s), and the peak resident memory of each against loading alone
# (checkbench --load-only: mesh_load and nothing else; goal: within 3x).
# Each row is the median wall time of RUNS processes under
# /usr/bin/time, with their CPU time (user + system: a crowded
# machine's wall clock counts waiting) and --json's phases (load, check
# before, repair, write, check after; then the repair's own: weld,
# clean, objects, order, and its check of what it made; ms).
set -u
ZV=${ZVIEW:-./zview}
CB=${CHECKBENCH:-build/checkbench}
SUBDIV=${SUBDIV:-build/subdiv}
RUNS=${RUNS:-3}
S=../shared/models
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-repair-cli-XXXXXX")
trap 'rm -rf "$TMP"' EXIT
trap 'exit 1' HUP INT PIPE TERM
sh "$(dirname "$0")/stamp.sh" "make bench-repair-cli (tools/bench-repair-cli.sh), RUNS=$RUNS"
D=$S/dragon.obj
[ -f "$D" ] || { echo "bench-repair-cli: $D not found (../shared/models)"; exit 0; }
[ -x /usr/bin/time ] || { echo "bench-repair-cli: no /usr/bin/time"; exit 0; }
big5m=$TMP/dragon-5m.obj
[ -x "$SUBDIV" ] && "$SUBDIV" "$D" "$big5m" >/dev/null 2>&1 || rm -f "$big5m"

# loading alone: the peak of a process that only loads (MB)
load_mb() {
    "$CB" --load-only "$1" | awk '{ for (i = 1; i < NF; i++) if ($i == "peak") { v = $(i + 1); sub(/MB/, "", v); print v } }'
}

# row LABEL GOAL_S LOAD_MB ARGS...: RUNS runs of zview ARGS --json; the
# median by wall time, with its CPU, peak and phases
row() {
    label=$1 goal=$2 base=$3
    shift 3
    i=0
    : >"$TMP/runs"
    while [ "$i" -lt "$RUNS" ]; do
        /usr/bin/time -f "%e %U %S %M" -o "$TMP/time" "$ZV" "$@" --json >"$TMP/json" 2>"$TMP/err"
        rc=$?
        [ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] || { echo "$label: status $rc: $(head -c 300 "$TMP/err")"; return; }
        ms=$(sed -n 's/.*"ms": { \(.*\) }.*/\1/p' "$TMP/json" | tr -d '"' | sed 's/check_after/after/; s/repair_//g')
        echo "$(tail -n 1 "$TMP/time") $ms" >>"$TMP/runs"
        i=$((i + 1))
    done
    sort -n "$TMP/runs" | awk -v n="$RUNS" 'NR == int(n / 2) + 1' >"$TMP/med"
    read -r wall user sys kb rest <"$TMP/med"
    printf "| %s | %s | %.2f | %.0f | %.2fx | %s | %s |\n" "$label" "$wall" "$(echo "$user $sys" | awk '{ print $1 + $2 }')" \
        "$(echo "$kb" | awk '{ print $1 / 1024 }')" "$(echo "$kb $base" | awk '{ print $1 / 1024 / $2 }')" "$rest" "$goal"
}

echo
echo "| case | wall s | CPU s | peak MB | of loading alone | phases (ms) | goal |"
echo "|---|---:|---:|---:|---:|---|---|"
base=$(load_mb "$D")
echo "| dragon, loading alone (checkbench, its load-only mode) | | | $base | 1.00x | | |"
row "dragon --repair -o .obj" "<= 1.5 s, <= 3x" "$base" --repair "$D" -o "$TMP/dragon.obj"
row "dragon --repair -o .stl" "<= 1.5 s, <= 3x" "$base" --repair "$D" -o "$TMP/dragon.stl"
if [ -s "$big5m" ]; then
    base=$(load_mb "$big5m")
    echo "| 5.2M triangles, loading alone | | | $base | 1.00x | | |"
    row "5.2M triangles --repair -j 2 -o .obj" "<= 10 s, <= 3x" "$base" --repair -j 2 "$big5m" -o "$TMP/5m.obj"
else
    echo "5.2M triangles: $SUBDIV could not write $big5m"
fi
