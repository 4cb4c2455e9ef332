#!/bin/sh
# The sandbox's cost (issue 22): the dragon loaded sandboxed and with
# --no-sandbox, alternately, pinned to one core, RUNS times each; the
# medians of the load as --info reports it (wall time from the load's
# start to a Mesh in hand: for the sandbox that is the fork, the child's
# load, the filter and the copy back) and of the whole command; then the
# CPU time of RUNS commands of each (perf's task-clock of the whole
# tree, the sandboxed child's included; without perf, user + system of
# zview and its waited children, which misses the child), which a busy
# machine disturbs far less than wall time.
# MODEL=... another model; RUNS=N (default 21).
set -u
Z=${ZVIEW:-./zview}
MODEL=${MODEL:-../shared/models/dragon.obj}
RUNS=${RUNS:-21}
CPU=${CPU:-1}
[ -r "$MODEL" ] || { echo "bench-sandbox: $MODEL not found" >&2; exit 1; }
sh "$(dirname "$0")/stamp.sh" "make bench-sandbox" 2>/dev/null
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
cat "$MODEL" >/dev/null     # in the page cache for both
i=0
while [ $i -lt "$RUNS" ]; do
    for mode in on off; do
        flag=; [ $mode = off ] && flag=--no-sandbox
        s=$(date +%s%N)
        taskset -c "$CPU" "$Z" --info $flag "$MODEL" 2>/dev/null | sed -n 's/^load: *\([0-9.]*\) ms.*/\1/p' >>"$T/load-$mode"
        e=$(date +%s%N)
        echo "$(( (e - s) / 1000 ))" >>"$T/run-$mode"
    done
    i=$((i + 1))
done
med() { sort -n "$1" | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
lon=$(med "$T/load-on"); loff=$(med "$T/load-off")
ron=$(med "$T/run-on"); roff=$(med "$T/run-off")
echo "model: $MODEL, $RUNS runs each, pinned to CPU $CPU, medians"
awk -v a="$lon" -v b="$loff" 'BEGIN { printf "load (--info):  sandboxed %.1f ms, --no-sandbox %.1f ms: %+.1f%%\n", a, b, 100 * (a - b) / b }'
awk -v a="$ron" -v b="$roff" 'BEGIN { printf "whole command:  sandboxed %.1f ms, --no-sandbox %.1f ms: %+.1f%%\n", a / 1000, b / 1000, 100 * (a - b) / b }'
# CPU of the whole process tree: perf stat's task-clock counts every
# descendant, the fork server's children too, which /usr/bin/time
# misses (the server is not waited for when zview exits)
cpu() {
    if perf stat -e task-clock true >/dev/null 2>&1; then
        perf stat -x, -e task-clock -o "$T/cpu" taskset -c "$CPU" sh -c \
            "i=0; while [ \$i -lt $RUNS ]; do '$Z' --info $1 '$MODEL' >/dev/null 2>&1; i=\$((i + 1)); done"
        sed -n 's/^\([0-9.]*\),.*task-clock.*/\1/p' "$T/cpu" | awk -v n="$RUNS" '{ printf "%.1f", $1 / n }'
        return
    fi
    /usr/bin/time -f "%U %S" -o "$T/cpu" taskset -c "$CPU" sh -c \
        "i=0; while [ \$i -lt $RUNS ]; do '$Z' --info $1 '$MODEL' >/dev/null 2>&1; i=\$((i + 1)); done"
    awk -v n="$RUNS" '{ printf "%.1f", ($1 + $2) * 1000 / n }' "$T/cpu"
}
con=$(cpu ""); coff=$(cpu --no-sandbox)
awk -v a="$con" -v b="$coff" 'BEGIN { printf "CPU a command:  sandboxed %.1f ms, --no-sandbox %.1f ms: %+.1f%%\n", a, b, 100 * (a - b) / b }'
