#!/bin/sh
# make bench-folder: zview --check --jsonl over a folder of COUNT
# (10,000) small models (issue 34: within 60 s), sandboxed and with
# --no-sandbox, alternately, RUNS (3) times each; the medians of the wall
# time and of the CPU time of the whole process tree (the fork server and
# its children included: perf stat's task-clock, which counts every
# descendant; without perf, /usr/bin/time, which misses the children of
# the server and says so). The models are copies of one closed cube OBJ
# written to a temporary folder (deleted at the end). The sandbox's cost
# a file is the difference over COUNT.
set -u
Z=$(cd "$(dirname "${ZVIEW:-./zview}")" && pwd)/$(basename "${ZVIEW:-./zview}")
COUNT=${COUNT:-10000}
RUNS=${RUNS:-3}
T=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-folder-XXXXXX")
trap 'rm -rf "$T"' EXIT INT TERM
sh "$(dirname "$0")/stamp.sh" "make bench-folder (tools/bench-folder.sh), COUNT=$COUNT RUNS=$RUNS" 2>/dev/null
mkdir "$T/d"
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n' >"$T/cube.obj"
printf 'f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n' >>"$T/cube.obj"
i=1
while [ $i -le "$COUNT" ]; do
    cp "$T/cube.obj" "$T/d/c$i.obj"
    i=$((i + 1))
done
perf stat -e task-clock true >/dev/null 2>&1 && PERF=1 || PERF=0
[ $PERF = 1 ] || echo "bench-folder: no perf: CPU from /usr/bin/time, without the sandbox's children"
one() {     # one run: "wall_ms cpu_ms"
    s=$(date +%s%N)
    if [ $PERF = 1 ]; then
        perf stat -x, -e task-clock -o "$T/cpu" -- "$Z" --check --jsonl $1 "$T/d" >"$T/out" 2>/dev/null
        cpu=$(sed -n 's/^\([0-9.]*\),.*task-clock.*/\1/p' "$T/cpu")
    else
        /usr/bin/time -f "%U %S" -o "$T/cpu" "$Z" --check --jsonl $1 "$T/d" >"$T/out" 2>/dev/null
        cpu=$(awk '{ print ($1 + $2) * 1000 }' "$T/cpu")
    fi
    e=$(date +%s%N)
    n=$(wc -l <"$T/out")
    [ "$n" -eq "$COUNT" ] || echo "bench-folder: $n lines of $COUNT" >&2
    echo "$(( (e - s) / 1000000 )) ${cpu%.*}"
}
i=0
while [ $i -lt "$RUNS" ]; do
    one "" >>"$T/on"
    one --no-sandbox >>"$T/off"
    i=$((i + 1))
done
med() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
won=$(cut -d' ' -f1 "$T/on" | med); con=$(cut -d' ' -f2 "$T/on" | med)
woff=$(cut -d' ' -f1 "$T/off" | med); coff=$(cut -d' ' -f2 "$T/off" | med)
echo "$COUNT cubes, --check --jsonl, medians of $RUNS, load $(cut -d' ' -f1-3 /proc/loadavg)"
awk -v w="$won" -v c="$con" -v n="$COUNT" 'BEGIN { printf "sandboxed:     %.1f s wall, %.1f s CPU (%.2f ms a file)\n", w / 1000, c / 1000, c / n }'
awk -v w="$woff" -v c="$coff" -v n="$COUNT" 'BEGIN { printf "--no-sandbox:  %.1f s wall, %.1f s CPU (%.2f ms a file)\n", w / 1000, c / 1000, c / n }'
