#!/bin/sh
# make mutate's list (tests/mutants.txt) stays true to the code: every
# mutant names a file, text found there exactly once, a change and a
# reason; code that moves takes its mutant along. (The mutation run
# itself is make mutate: too long for make test.)
. "$(dirname "$0")/lib.sh"
# (MUTANTS= : every mutant, whatever the caller chose)
if MUTANTS= sh tools/mutate.sh --check tests/mutants.txt >"$T/out" 2>&1; then ok "every mutant of tests/mutants.txt still applies"; else
    notok "every mutant of tests/mutants.txt still applies" "$(cat "$T/out")"; fi
n=$(grep -c '^name:' tests/mutants.txt)
if [ "$n" -ge 18 ]; then ok "the list holds at least the 18 mutants of issue 17 ($n)"; else notok "the list holds at least 18 mutants" "$n"; fi
# a stale mutant is refused, naming where its text went
printf 'name: stale\nfile: src/present/quant.c\nfrom: no such text anywhere\nto: x\nwhy: a test\n' >"$T/list"
MUTANTS= sh tools/mutate.sh --check "$T/list" >"$T/out" 2>&1
rc=$?
if [ $rc -eq 2 ] && grep -q 'stale: its text occurs 0 times in src/present/quant.c' "$T/out"; then ok "a stale mutant is refused (status 2)"; else
    notok "a stale mutant is refused (status 2)" "status $rc: $(cat "$T/out")"; fi
