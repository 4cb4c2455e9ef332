#!/bin/sh
# Run every tests/e2e/test_*.sh (make test; E2E_PREFIX=long_ runs the
# long_*.sh of make test-long instead); each prints "ok - name" / "not ok - name"
# lines, and "ok - name # skip reason" for a check it could not run here
# (lib.sh's skip). Ends with "N passed, N failed, N skipped", the skips
# named; fails on a failure, and on a skip unless skips are allowed
# (tests/skips.sh).
#
# The scripts run E2E_JOBS at a time (default twice the cores: most of
# a script's time is waiting, on tmux panes polled, X and terminals
# starting, a child's memory limit: a quiet run of every script one
# after the other took 318 s, 124 s of it CPU): each has its own
# temporary folder, tmux socket and X display, so they do not meet. The
# longest start first (their times from the last run are kept in
# $E2E_TIMES), so that the queues end together; each script's output is printed whole, in name
# order, once all have ended, then the names of those that failed.
#
# For tools/mutate.sh, which only needs to know whether some check fails:
#   E2E_FIRST="test_a test_b"  start these first, in this order
#   E2E_FAIL_FAST=1            start no script once one has failed (those
#                              running end; the run fails, naming the
#                              scripts that never ran; times are not
#                              kept), and the shortest first
#   E2E_EXCLUDE="test_a"       do not run these (mutate.sh, for a script
#                              that fails without any mutant on a loaded
#                              machine); the summary names them
set -u
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../skips.sh"
: "${ZVIEW:=$here/../../zview}"
: "${E2E_JOBS:=$((2 * $(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)))}"
: "${E2E_TIMES:=$here/../../build/e2e-times}"
: "${E2E_FIRST:=}"
: "${E2E_EXCLUDE:=}"
: "${E2E_FAIL_FAST:=}"
: "${E2E_PREFIX:=test_}"
export ZVIEW
# the python3 interpreter, found once for every script (lib.sh)
if [ -z "${ZV_PYTHON:-}" ] && command -v python3 >/dev/null 2>&1; then
    ZV_PYTHON=$(python3 -c 'import sys; print(sys.executable)' 2>/dev/null)
    export ZV_PYTHON
fi
pass=0
fail=0
skipped=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# one script: its output, exit status and seconds into $work
one() {
    name=$(basename "$1" .sh)
    start=$(date +%s)
    # the script in a shell of its own, whose "times" gives the CPU its
    # children spent (not the tmux servers': they leave it)
    sh -c 'sh "$1" >"$2" 2>&1; echo $? >"$3"; times >"$4"' sh "$1" "$2/$name.out" "$2/$name.rc" "$2/$name.cpu"
    echo $(($(date +%s) - start)) >"$2/$name.sec"
    # xargs starts nothing more after a command's status 255
    if [ -n "$E2E_FAIL_FAST" ] && { [ "$(cat "$2/$name.rc")" -ne 0 ] || grep -q '^not ok ' "$2/$name.out"; }; then
        exit 255
    fi
}
if [ "${1:-}" = --one ]; then
    one "$2" "$3"
    exit 0
fi

# longest first by the last run's times (a new script counts as long),
# so that the queues end together; shortest first when the run stops at
# a failure, which it then meets sooner
order=-rn
[ -z "$E2E_FAIL_FAST" ] || order=-n
for t in "$here/$E2E_PREFIX"*.sh; do
    n=$(basename "$t" .sh)
    s=$(awk -v n="$n" '$1 == n { print $2 }' "$E2E_TIMES" 2>/dev/null)
    echo "${s:-999} $t"
done | sort $order | cut -d' ' -f2- >"$work/order"
if [ -n "$E2E_FIRST" ]; then
    for n in $E2E_FIRST; do
        [ -f "$here/$n.sh" ] && echo "$here/$n.sh"
    done >"$work/first"
    grep -vxF -f "$work/first" "$work/order" >>"$work/first"
    mv "$work/first" "$work/order"
fi
for n in $E2E_EXCLUDE; do
    grep -vxF "$here/$n.sh" "$work/order" >"$work/rest"
    mv "$work/rest" "$work/order"
done
if [ -n "$E2E_FAIL_FAST" ]; then
    # (xargs says that it stopped: the summary says it better)
    xargs -P "$E2E_JOBS" -I{} sh "$here/run.sh" --one {} "$work" <"$work/order" 2>/dev/null
else
    xargs -P "$E2E_JOBS" -I{} sh "$here/run.sh" --one {} "$work" <"$work/order"
fi

: >"$work/times"
failed=
notrun=
for t in "$here/$E2E_PREFIX"*.sh; do
    n=$(basename "$t" .sh)
    out="$work/$n.out"
    case " $E2E_EXCLUDE " in *" $n "*) continue ;; esac
    if [ -n "$E2E_FAIL_FAST" ] && [ ! -f "$work/$n.rc" ]; then
        notrun="$notrun $n"
        continue
    fi
    cat "$out"
    rc=$(cat "$work/$n.rc" 2>/dev/null || echo 1)
    # seconds, then the CPU seconds (user + system) of its processes
    cpu=$(sed -n 2p "$work/$n.cpu" 2>/dev/null | tr 'ms' '  ' | awk '{ printf "%.1f", $1 * 60 + $2 + $3 * 60 + $4 }')
    echo "$n $(cat "$work/$n.sec" 2>/dev/null || echo 999) ${cpu:-?}" >>"$work/times"
    s=$(grep -ci '^ok .*# skip' "$out")
    p=$(($(grep -c '^ok ' "$out") - s))
    f=$(grep -c '^not ok ' "$out")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "not ok - $n.sh exited with status $rc"
        f=1
    fi
    [ "$f" -eq 0 ] || failed="$failed $n"
    grep -i '^ok .*# skip' "$out" | sed "s|^ok - |  skipped: $n.sh: |" >>"$work/skips"
    pass=$((pass + p))
    fail=$((fail + f))
    skipped=$((skipped + s))
done
[ -n "$notrun$E2E_EXCLUDE" ] || cp "$work/times" "$E2E_TIMES" 2>/dev/null || true
echo "e2e: $pass passed, $fail failed, $skipped skipped"
[ -z "$failed" ] || echo "e2e: failed:$failed"
[ -z "$notrun" ] || echo "e2e: not run after the first failure:$notrun"
[ -z "$E2E_EXCLUDE" ] || echo "e2e: left out (E2E_EXCLUDE): $E2E_EXCLUDE"
[ -f "$work/skips" ] && cat "$work/skips"
verdict=0
skips_verdict e2e "$skipped" || verdict=1
[ "$fail" -eq 0 ] && [ "$pass" -gt 0 ] && [ $verdict -eq 0 ]
