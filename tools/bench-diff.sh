#!/bin/sh
# make bench-diff, and make bench's rows of it (issue 31): zview --diff
# of the dragon against an edited copy (tools/perturb: a bump of 1% of
# the diagonal, every vertex moved by up to 0.01% of it, so no vertex is
# shared and every one is queried), the report and the first picture
# (--diff -o FILE.png --size 640x480, the report on standard output),
# one thread pinned to a core and two; the 5.2M-triangle model
# (tools/subdiv) against its edited copy on two threads; and the peak
# memory of the 5.2M diff against zview --info of both files (loading
# both), beside a yardstick measured in the same run (--check's passes on
# the dragon, whose CPU time quiet is documented). Each row is the
# median of RUNS runs (wall seconds, and CPU
# seconds of the process, user and system, which a shared machine's
# other jobs do not inflate as they do the wall clock). BIG_DIR: where
# make bench wrote the big models (else they are written here, into a
# temporary folder). HEADER=0 leaves out the stamp and the heading.
set -u
ZV=${ZVIEW:-./zview}
SUBDIV=${SUBDIV:-build/subdiv}
PERTURB=${PERTURB:-build/perturb}
RUNS=${RUNS:-5}
S=../shared/models
D=$S/dragon.obj
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-diff-XXXXXX")
trap 'rm -rf "$TMP"' EXIT
trap 'exit 1' HUP INT PIPE TERM
[ "${HEADER:-1}" = 1 ] && sh "$(dirname "$0")/stamp.sh" "make bench-diff (tools/bench-diff.sh), RUNS=$RUNS"
if [ ! -f "$D" ] || [ ! -x /usr/bin/time ] || [ ! -x "$PERTURB" ]; then
    echo "bench-diff: needs $D, /usr/bin/time and $PERTURB"
    exit 0
fi
BIG=${BIG_DIR:-$TMP}
m5=$BIG/dragon-5m.obj
[ -s "$m5" ] || "$SUBDIV" "$D" "$m5" >/dev/null 2>&1 || rm -f "$m5"
"$PERTURB" "$D" "$TMP/dragon-edited.obj"
[ -s "$m5" ] && "$PERTURB" "$m5" "$TMP/dragon-5m-edited.obj"

# run PIN ARGS...: RUNS runs of zview ARGS; the median's "wall cpu maxrss_MB"
run() {
    pin=$1
    shift
    i=0
    : >"$TMP/runs"
    while [ "$i" -lt "$RUNS" ]; do
        # shellcheck disable=SC2086
        /usr/bin/time -f "%e %U %S %M" -o "$TMP/t" $pin "$ZV" "$@" >/dev/null 2>"$TMP/err"
        tail -n 1 "$TMP/t" | awk '{ printf "%.2f %.2f %.0f\n", $1, $2 + $3, $4 / 1024 }' >>"$TMP/runs"
        i=$((i + 1))
    done
    sort -n -k 2 "$TMP/runs" | awk -v n="$RUNS" 'NR == int((n + 1) / 2)'
}

row() {
    printf "%-46s %9s %9s %8s %8s %8s   %s\n" "$1" "$2" "$3" "" "" "" "$4"
}

if [ "${HEADER:-1}" = 1 ]; then
    echo
    echo "## --diff (issue 31): medians of $RUNS runs; wall s, CPU s (user + system)"
    printf "%-46s %9s %9s %8s %8s %8s   %s\n" "case" "wall_s" "cpu_s" "" "" "" "target"
fi
# a yardstick measured in the same run: --check's passes on the dragon,
# one thread, no crossing test (doc/benchmarks.md: The check, 217 ms of
# CPU on a quiet machine): how much slower this machine runs just now
if [ -x "${CHECKBENCH:-build/checkbench}" ]; then
    $PIN "${CHECKBENCH:-build/checkbench}" -j 1 --no-cross "$D" |
        awk '{ for (i = 1; i < NF; i++) if ($i == "cpu") c = $(i + 1) }
             END { printf "%-46s %9s %9.2f %8s %8s %8s   %s\n", "yardstick: --check dragon, no crossing test", "", c / 1000, "", "", "", "0.22 s of CPU quiet" }'
fi
out="-o $TMP/diff.png --size 640x480"
# shellcheck disable=SC2086
set -- $(run "$PIN" --threads 1 --diff $out "$D" "$TMP/dragon-edited.obj")
row "dragon --diff: report + picture, 1 thread" "$1" "$2" "<= 2 s"
# shellcheck disable=SC2086
set -- $(run "" --threads 2 --diff $out "$D" "$TMP/dragon-edited.obj")
row "dragon --diff: report + picture, 2 threads" "$1" "$2" "<= 1.2 s"
if [ -s "$m5" ]; then
    # shellcheck disable=SC2086
    set -- $(run "" --threads 2 --diff $out "$m5" "$TMP/dragon-5m-edited.obj")
    w=$1 c=$2 mem=$3
    row "5.2M --diff: report + picture, 2 threads" "$w" "$c" "<= 15 s"
    set -- $(run "" --threads 2 --info "$m5" "$TMP/dragon-5m-edited.obj")
    row "5.2M --diff: peak MB against loading both" "$mem" "$3" \
        "<= 3x: $(awk -v d="$mem" -v l="$3" 'BEGIN { printf "%.2fx", (l > 0 ? d / l : 0) }') (--diff, --info A B)"
else
    row "5.2M --diff" "(no model)" "" "$SUBDIV could not write it"
fi
