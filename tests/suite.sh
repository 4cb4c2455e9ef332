#!/bin/sh
# suite.sh TESTBIN FILTER BUILD: make test's three parts, at once. The
# end-to-end scripts (tests/e2e/run.sh) spend most of their time waiting
# (tmux panes polled, X started, sleeps): beside them, at a lower
# priority (nice), the unit tests (tests/unit.sh TESTBIN --jobs 2
# --filter FILTER) and then the fuzz replays (tests/fuzz/replay.sh BUILD) fill
# the cores, and yield them whenever a script wants one. Run one after
# the other, the parts took 3 min 40 s here (before issue 30's suites);
# see the Makefile's help for what they take now.
#
# Each part's output is kept and printed whole when it has ended, the
# unit tests' and the replays' first; the run fails when any part did.
# The environment (ZVIEW, ZV_STANDIN_LIB, E2E_JOBS, CI, ZV_ALLOW_SKIPS)
# goes to the parts as it is.
set -u
here=$(cd "$(dirname "$0")" && pwd)
bin=$1
filter=$2
build=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT TERM HUP

echo "make test: the unit tests and the fuzz replays (nice) beside the end-to-end scripts; each part's output when it ends"
(
    nice -n 10 sh "$here/unit.sh" "$bin" --jobs 2 --filter "$filter"
    unit=$?
    nice -n 10 sh "$here/fuzz/replay.sh" "$build"
    rc=$?
    [ $unit -eq 0 ] && [ $rc -eq 0 ]
) >"$work/unit" 2>&1 &
side=$!
sh "$here/e2e/run.sh" >"$work/e2e" 2>&1 &
e2e=$!

wait $side
side_rc=$?
cat "$work/unit"
[ $side_rc -eq 0 ] || echo "make test: the unit tests or the fuzz replays failed"
wait $e2e
e2e_rc=$?
cat "$work/e2e"
[ $e2e_rc -eq 0 ] || echo "make test: the end-to-end tests failed"
[ $side_rc -eq 0 ] && [ $e2e_rc -eq 0 ]
