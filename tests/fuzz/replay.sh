#!/bin/sh
# replay.sh BUILD: every input that ever failed, and the seeds, through
# the normal build's replay harnesses (BUILD/replay-*, replay.c): make
# replay, and make test beside its other parts (tests/suite.sh).
# pending/ is not replayed. fuzz-mesh's, fuzz-check's and fuzz-repair's loaders warn
# about what they skip: that goes to /dev/null. Each harness runs,
# whatever the one before it did; the status fails when one failed.
b=$1
rc=0
run() {
    echo "$*"
    "$@" || rc=1
}
run "$b/replay-obj" tests/fuzz/seeds/obj tests/fuzz/regress/obj
run "$b/replay-diff" tests/fuzz/seeds/diff tests/fuzz/regress/diff
run "$b/replay-mesh" tests/fuzz/seeds/mesh tests/fuzz/regress/mesh 2>/dev/null
run "$b/replay-check" tests/fuzz/seeds/check tests/fuzz/regress/check 2>/dev/null
run "$b/replay-tex" tests/fuzz/seeds/tex tests/fuzz/regress/tex
run "$b/replay-repair" tests/fuzz/seeds/repair tests/fuzz/regress/repair 2>/dev/null
run "$b/replay-dist" tests/fuzz/seeds/dist tests/fuzz/regress/dist
exit $rc
