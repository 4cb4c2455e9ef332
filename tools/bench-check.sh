#!/bin/sh
# make bench-check: what zview --check costs beyond loading (issue 19's
# targets): the dragon (871k triangles) on one thread pinned to a core,
# without and with the crossing tests, and the 5.2M-triangle model
# (tools/subdiv, as make bench makes it) on two threads; each check's
# median over RUNS runs in separate processes, its phases, and the peak
# resident memory against loading alone (tools/checkbench.c; RUSAGE
# maxrss of the same process). Then the whole `zview --check` under
# /usr/bin/time for the wall clock a user sees. Compare rows of one run.
set -u
ZV=${ZVIEW:-./zview}
CB=${CHECKBENCH:-build/checkbench}
SUBDIV=${SUBDIV:-build/subdiv}
RUNS=${RUNS:-5}
S=../shared/models
TMP=${TMPDIR:-/tmp}/zview-bench
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
sh "$(dirname "$0")/stamp.sh" "make bench-check (tools/bench-check.sh), RUNS=$RUNS"
D=$S/dragon.obj
[ -f "$D" ] || { echo "bench-check: $D not found (../shared/models)"; exit 0; }
big5m=$TMP/dragon-5m.obj
if [ ! -s "$big5m" ] && [ -x "$SUBDIV" ]; then
    mkdir -p "$TMP" && "$SUBDIV" "$D" "$big5m" >/dev/null 2>&1 || rm -f "$big5m"
fi

# median PIN ARGS...: RUNS runs of checkbench, the line of the median check
median() {
    pin=$1
    shift
    i=0
    : >"$TMP/runs"
    while [ "$i" -lt "$RUNS" ]; do
        $pin "$CB" "$@" >>"$TMP/runs" || return 1
        i=$((i + 1))
    done
    # the check's wall ms is the field after "check"
    awk '{ for (i = 1; i < NF; i++) if ($i == "check") print $(i + 1), NR }' "$TMP/runs" | sort -n |
        awk -v n="$RUNS" 'NR == int(n / 2) + 1 { print $2 }' >"$TMP/pick"
    sed -n "$(cat "$TMP/pick")p" "$TMP/runs"
}

mkdir -p "$TMP"
echo
echo "## --check beyond loading (checkbench: medians of $RUNS processes; ms)"
$PIN "$CB" --load-only "$D"
median "$PIN" -j 1 --no-cross "$D"      # target: <= 300 ms beyond loading
median "$PIN" -j 1 "$D"                 # target: <= 1000 ms
median "$PIN" -j 1 -l 100 "$D"          # issue 30: located as --check --json does; as fast as without
if [ -s "$big5m" ]; then
    "$CB" --load-only "$big5m"
    median "" -j 2 "$big5m"             # target: <= 3000 ms
    median "" -j 2 --no-cross "$big5m"
else
    echo "5.2M triangles: $SUBDIV could not write $big5m"
fi
echo
echo "## the whole zview --check (wall s, peak MB; /usr/bin/time) against zview --info (loading alone)"
if [ -x /usr/bin/time ]; then
    for m in "$D" ${big5m:+"$big5m"}; do
        [ -s "$m" ] || continue
        for args in "--info" "--check --threads 1" "--check --threads 2"; do
            # shellcheck disable=SC2086
            /usr/bin/time -f "%e %M" -o "$TMP/time" "$ZV" $args "$m" >/dev/null 2>&1
            # the last line: time writes the exit status first when it is not 0
            printf "%-28s %-22s %6s s %8.1f MB\n" "$(basename "$m")" "$args" "$(tail -n 1 "$TMP/time" | cut -d' ' -f1)" \
                "$(tail -n 1 "$TMP/time" | awk '{ print $2 / 1024 }')"
        done
    done
else
    echo "no /usr/bin/time"
fi
