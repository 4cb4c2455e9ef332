#!/bin/sh
# make bench-printq (issue 32): what --thickness costs on the dragon
# (871k triangles): zview --print --size 8x4 with and without it (the
# load and the first view are the same in both; the difference is the
# BVH built over the faces and one ray cast inward from each), on two
# threads and on one pinned to a core; and --check with and without
# --thickness --overhang. Each row the median of RUNS runs: wall
# seconds, and the process's CPU seconds (user and system), which a
# shared machine's other jobs do not inflate as they do the wall clock.
# The target (issue 32): --thickness within 3 s on two threads.
set -u
ZV=${ZVIEW:-./zview}
RUNS=${RUNS:-3}
D=${MODEL:-../shared/models/dragon.obj}
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-printq-XXXXXX")
trap 'rm -rf "$TMP"' EXIT
trap 'exit 1' HUP INT PIPE TERM
sh "$(dirname "$0")/stamp.sh" "make bench-printq (tools/bench-printq.sh), RUNS=$RUNS"
if [ ! -f "$D" ] || [ ! -x /usr/bin/time ]; then
    echo "bench-printq: needs $D and /usr/bin/time"
    exit 0
fi

# run PIN ARGS...: RUNS runs of zview ARGS; the median's "wall cpu"
run() {
    pin=$1
    shift
    i=0
    : >"$TMP/runs"
    while [ "$i" -lt "$RUNS" ]; do
        # shellcheck disable=SC2086
        /usr/bin/time -f "%e %U %S" -o "$TMP/t" $pin "$ZV" "$@" >/dev/null 2>"$TMP/err"
        tail -n 1 "$TMP/t" | awk '{ printf "%.2f %.2f\n", $1, $2 + $3 }' >>"$TMP/runs"
        i=$((i + 1))
    done
    sort -n -k 2 "$TMP/runs" | awk -v n="$RUNS" 'NR == int((n + 1) / 2)'
}

echo
printf "%-52s %8s %8s\n" "dragon.obj (871k triangles)" "wall s" "CPU s"
for j in 2 1; do
    pin=
    [ "$j" = 1 ] && pin=$PIN
    plain=$(run "$pin" -j "$j" --print --size 8x4 --color none "$D")
    thick=$(run "$pin" -j "$j" --print --size 8x4 --color none --thickness "$D")
    printf "%-52s %8s %8s\n" "--print 8x4, $j thread(s)" $plain
    printf "%-52s %8s %8s\n" "--print 8x4 --thickness, $j thread(s)" $thick
    echo "$plain $thick" | awk -v j="$j" '{ printf "%-52s %8.2f %8.2f\n", "  --thickness alone (the difference), " j " thread(s)", $3 - $1, $4 - $2 }'
done
plain=$(run "" -j 2 --check "$D")
both=$(run "" -j 2 --check --thickness --overhang "$D")
printf "%-52s %8s %8s\n" "--check, 2 threads" $plain
printf "%-52s %8s %8s\n" "--check --thickness --overhang, 2 threads" $both
