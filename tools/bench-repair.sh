#!/bin/sh
# make bench-repair: what repair_mesh costs beyond loading (issue 30's
# targets): the dragon (871k triangles) on one thread pinned to a core
# and on two, and the 5.2M-triangle model (tools/subdiv, as make bench
# makes it) on two; each repair's median over RUNS runs in separate
# processes, its phases (weld, clean, the objects' splits, winding and
# holes, the vertices' order, the check of what is left; the check of
# the input runs beside them on the second thread, or first on one),
# and the peak resident memory against loading alone
# (tools/repairbench.c; RUSAGE maxrss of the same process). Writing the
# repaired file is the command line's (zview --repair IN -o OUT): when
# this zview has --repair, its whole run under /usr/bin/time follows.
# Compare rows of one run.
set -u
ZV=${ZVIEW:-./zview}
RB=${REPAIRBENCH:-build/repairbench}
SUBDIV=${SUBDIV:-build/subdiv}
RUNS=${RUNS:-5}
S=../shared/models
TMP=${TMPDIR:-/tmp}/zview-bench
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
sh "$(dirname "$0")/stamp.sh" "make bench-repair (tools/bench-repair.sh), RUNS=$RUNS"
D=$S/dragon.obj
[ -f "$D" ] || { echo "bench-repair: $D not found (../shared/models)"; exit 0; }
mkdir -p "$TMP"
big5m=$TMP/dragon-5m.obj
if [ ! -s "$big5m" ] && [ -x "$SUBDIV" ]; then
    "$SUBDIV" "$D" "$big5m" >/dev/null 2>&1 || rm -f "$big5m"
fi

# median PIN ARGS...: RUNS runs of repairbench, the line of the median repair
median() {
    pin=$1
    shift
    i=0
    : >"$TMP/runs"
    while [ "$i" -lt "$RUNS" ]; do
        $pin "$RB" "$@" >>"$TMP/runs" || return 1
        i=$((i + 1))
    done
    # the repair's wall ms is the field after "repair"
    awk '{ for (i = 1; i < NF; i++) if ($i == "repair") print $(i + 1), NR }' "$TMP/runs" | sort -n |
        awk -v n="$RUNS" 'NR == int(n / 2) + 1 { print $2 }' >"$TMP/pick"
    sed -n "$(cat "$TMP/pick")p" "$TMP/runs" | sed 's/  \[.*//'
}

echo
echo "## repair_mesh beyond loading (repairbench: medians of $RUNS processes; ms)"
$PIN "$RB" --load-only "$D"
median "$PIN" -j 1 "$D"                 # target: <= 1500 ms with the writing
median "" -j 2 "$D"
if [ -s "$big5m" ]; then
    "$RB" --load-only "$big5m"
    median "" -j 2 "$big5m"             # target: <= 10000 ms on two threads
else
    echo "5.2M triangles: $SUBDIV could not write $big5m"
fi
echo
echo "## what the dragon's repair did"
"$RB" -j 2 "$D" | sed 's/.*  \[/[/'
if "$ZV" --help 2>&1 | grep -q -- '--repair' && [ -x /usr/bin/time ]; then
    echo
    echo "## the whole zview --repair IN -o OUT (wall s, peak MB; /usr/bin/time) against zview --info (loading alone)"
    for m in "$D" ${big5m:+"$big5m"}; do
        [ -s "$m" ] || continue
        for args in "--info" "--repair -o $TMP/repaired.obj --threads 1" "--repair -o $TMP/repaired.obj --threads 2"; do
            # shellcheck disable=SC2086
            /usr/bin/time -f "%e %M" -o "$TMP/time" "$ZV" $args "$m" >/dev/null 2>&1
            printf "%-28s %-40s %6s s %8.1f MB\n" "$(basename "$m")" "$args" "$(tail -n 1 "$TMP/time" | cut -d' ' -f1)" \
                "$(tail -n 1 "$TMP/time" | awk '{ print $2 / 1024 }')"
        done
    done
    rm -f "$TMP/repaired.obj"
fi
