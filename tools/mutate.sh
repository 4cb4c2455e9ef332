#!/bin/sh
# mutate.sh [--check] [LIST]: mutation testing (make mutate). Each
# mutant of LIST (default tests/mutants.txt; the format is described at
# its top) is applied alone to a copy of the tree, never to this one, and
# make test's checks run in the copy; a mutant the tests do not notice
# survives, and is a test we lack. Prints what killed each mutant and the
# kill rate; exits 1 when one survives, 2 when a mutant is stale (its
# text not found exactly once) or does not build, or when the unmutated
# copy fails its tests.
# --check only checks that every mutant still applies (make test does),
# but the one ZV_MUTANT names and those of the file ZV_MUTANT_FILE names:
# the run sets them to the mutant it applied and its file.
#
# A mutant costs what it takes to notice it, not a whole make test: the
# verdict is make test's (a survivor passed every check make test runs),
# in an order that finds a failure soon.
#   1. The build. When every object it rebuilt is the same code as the
#      unmutated one (debug information aside), no test can tell the
#      mutant apart: it is reported SAME (equivalent), and nothing runs.
#   2. The unit suites that killed this room's mutants earlier in the run
#      and those named after the mutated file or its room, then the rest
#      of make test's unit suites, each stopping at its first failure
#      (Criterion's --fail-fast).
#   3. make replay (the fuzz corpora).
#   4. The end-to-end scripts (make e2e), those that killed this room's
#      mutants earlier and the one named after the room first, stopping
#      once one fails (tests/e2e/run.sh: E2E_FIRST, E2E_FAIL_FAST).
# A stage that fails is run again (a unit test alone, the e2e scripts
# that failed first) and the mutant is killed only when it fails again:
# several runs share this machine, and a check that waits on a clock can
# fail once under load; a kill that does not repeat is no kill. An e2e
# script that fails twice in the unmutated copy is left out of the run,
# and the run says so: its survivors were not held to that script.
#
#   MUTANTS="a b"        run only these (names from the list)
#   MUTATE_TIMEOUT=1800  seconds a stage may take (then killed: a mutant
#                        that hangs the suite is noticed; a whole e2e
#                        run takes 10 to 15 minutes on a loaded machine)
#   MUTATE_REV=HEAD      copy a commit instead of the working files
#   MUTATE_LOGS=DIR      where each mutant's output is kept
#                        (default build/mutate)
#   MUTATE_BASELINE=unit  the unmutated copy is built and its unit tests
#                        run, not its e2e scripts: for a commit whose make
#                        test is known green, when the e2e stage (10 to 40
#                        minutes on a loaded machine) would take the time
#                        of the run (no flaky e2e script is then left out)
#   MUTATE_UNIT_ONLY=1   stop after the unit stage: a first pass over many
#                        mutants, whose survivors (reported "SURVIVED ...
#                        (unit tests only)") are then run again whole;
#                        a survivor of an e2e stage costs 10 to 40 minutes
#                        on a loaded machine, a unit kill under a minute
#   MUTATE_CMD='make unit'  one command instead of the stages, run whole
#                        in the copy (MUTATE_CMD='make test' is the plain
#                        run; another is a quick look while writing a
#                        test: the kill rate counts only with make test's)
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here" || exit 2
check=0
[ "${1:-}" = --check ] && { check=1; shift; }
list=${1:-tests/mutants.txt}
[ -r "$list" ] || { echo "mutate: cannot read $list" >&2; exit 2; }
: "${MUTANTS:=}"
: "${MUTATE_TIMEOUT:=1800}"
: "${MUTATE_REV:=}"
: "${MUTATE_LOGS:=build/mutate}"
: "${MUTATE_CMD:=}"
: "${MUTATE_BASELINE:=test}"
: "${MUTATE_UNIT_ONLY:=}"

# field NAME KEY: a mutant's value for KEY (file, why), one line
field() {
    awk -v n="$1" -v k="$2" '
        /^name:/ { cur = $2; next }
        cur == n && index($0, k ":") == 1 {
            v = substr($0, length(k) + 2)
            sub(/^[ \t]+/, "", v)
            out = out (out == "" ? "" : " ") v
        }
        END { print out }' "$list"
}

# mutate NAME FILE: FILE with the mutant's change, on stdout. Status 3
# when the text does not occur exactly once (its count on stderr).
mutate() {
    awk -v n="$1" '
        FNR == NR {
            if ($0 ~ /^name:/) { cur = $2; next }
            if (cur != n) next
            if (index($0, "from:") == 1) {
                v = substr($0, 6)
                if (nf++ == 0) { sub(/^[ \t]+/, "", v); from = v } else { sub(/^ /, "", v); from = from "\n" v }
            } else if (index($0, "to:") == 1) {
                v = substr($0, 4)
                if (nt++ == 0) { sub(/^[ \t]+/, "", v); to = v } else { sub(/^ /, "", v); to = to "\n" v }
            }
            next
        }
        { text = text $0 "\n" }
        END {
            if (from == "") { print 0 > "/dev/stderr"; exit 3 }
            count = 0
            rest = text
            while ((i = index(rest, from)) > 0) {
                count++
                rest = substr(rest, i + length(from))
            }
            if (count != 1) { print count > "/dev/stderr"; exit 3 }
            i = index(text, from)
            printf "%s%s%s", substr(text, 1, i - 1), to, substr(text, i + length(from))
        }' "$list" "$2"
}

# killer LOG: the first test a log names as failed (a unit test, an
# end-to-end check, a fuzz harness), else make's last word
killer() {
    for re in '^\[FAIL\] ' '^not ok ' '^fuzz_[a-z]*: |^replay: ' '^make.*\*\*\*'; do
        line=$(grep -E -- "$re" "$1" | head -n 1)
        [ -n "$line" ] && { echo "$line" | cut -c1-120; return; }
    done
}

# makevar NAME: the value of a variable of the copy's Makefile
makevar() {
    printf "print-%%:\n\t@printf '%%s\\\\n' '\$(\$*)'\n" | make -s --no-print-directory -C "$copy" -f Makefile -f - "print-$1"
}

# same_code: every object the last build remade is, debug information
# aside, the code of the unmutated tree (a new object is not)
same_code() {
    changed=$(cd "$copy" && find build -name '*.o' -newer "$work/stamp")
    [ -n "$changed" ] || return 1
    for o in $changed; do
        [ -f "$work/code/$o" ] || return 1
        objcopy --strip-debug "$copy/$o" "$work/o" && cmp -s "$work/o" "$work/code/$o" || return 1
    done
    return 0
}

# first_of ROOM KIND NAMES [ANY]: the suites or scripts of KIND (unit,
# e2e) that killed ROOM's mutants so far, most kills first, then NAMES
# (the ones named after the file and the room), then with ANY those that
# killed most in any room, each once
first_of() {
    { kills_of "$1" "$2" | head -n 4
      for x in $3; do echo "$x"; done
      [ -z "${4:-}" ] || kills_of '*' "$2" | head -n 3; } | awk 'NF && !seen[$0]++'
}
kills_of() {
    awk -v r="$1" -v k="$2" '(r == "*" || $1 == r) && $2 == k { n[$3]++ } END { for (s in n) print n[s], s }' "$work/kills" |
        sort -k1,1rn -k2 | cut -d' ' -f2
}

# unit_stage FILTER LOG: the unit suites FILTER selects, stopping at the
# first failure; a failure is run again alone, then the stage again, and
# counts when it repeats. Sets by. Status 0 passed, 1 failed.
unit_stage() {
    (cd "$copy" && ZVIEW="$copy/${bin_zview}" exec timeout "$MUTATE_TIMEOUT" sh tests/unit.sh "$bin_tests" --jobs 2 --fail-fast --filter "$1") >"$work/stage" 2>&1
    rc=$?
    cat "$work/stage" >>"$2"
    [ $rc -eq 0 ] && return 0
    [ $rc -eq 124 ] && { by="unit tests running past $MUTATE_TIMEOUT s ($1)"; return 1; }
    t=$(grep -m1 '^\[FAIL\] [A-Za-z0-9_]*::[A-Za-z0-9_]*' "$work/stage" | sed 's/^\[FAIL\] \([A-Za-z0-9_]*\)::\([A-Za-z0-9_]*\).*/\1 \2/')
    if [ -n "$t" ]; then
        set -- "$1" "$2" ${t}
        echo "mutate: again, alone: $3::$4" >>"$2"
        if ! (cd "$copy" && ZVIEW="$copy/${bin_zview}" exec timeout "$MUTATE_TIMEOUT" sh tests/unit.sh "$bin_tests" --filter "$3/$4") >>"$2" 2>&1; then
            by="unit $3::$4"
            echo "$room unit $3" >>"$work/kills"
            return 1
        fi
    fi
    echo "mutate: the failure did not repeat: the stage again" >>"$2"
    (cd "$copy" && ZVIEW="$copy/${bin_zview}" exec timeout "$MUTATE_TIMEOUT" sh tests/unit.sh "$bin_tests" --jobs 2 --fail-fast --filter "$1") >"$work/stage" 2>&1 && { cat "$work/stage" >>"$2"; return 0; }
    cat "$work/stage" >>"$2"
    by="unit $(grep -m1 '^\[FAIL\] ' "$work/stage" | cut -c8-80) (on the second run)"
    return 1
}

# e2e_stage FIRST LOG: make e2e, the scripts FIRST first, stopping at a
# failure; then again with the scripts that failed first, and a failure
# counts when it repeats. Sets by. Status 0 passed, 1 failed.
e2e_stage() {
    for try in 1 2; do
        (cd "$copy" && E2E_FIRST="$1" E2E_FAIL_FAST=1 E2E_EXCLUDE="$exclude" exec timeout "$MUTATE_TIMEOUT" make --no-print-directory e2e) >"$work/stage" 2>&1
        rc=$?
        cat "$work/stage" >>"$2"
        [ $rc -eq 0 ] && return 0
        [ $rc -eq 124 ] && { by="e2e scripts running past $MUTATE_TIMEOUT s"; return 1; }
        failed=$(sed -n 's/^e2e: failed://p' "$work/stage")
        [ $try = 1 ] && echo "mutate: again, these first:$failed" >>"$2"
        set -- "$failed $1" "$2"
    done
    n=$(echo $failed | cut -d' ' -f1)
    by="e2e ${n:-(make e2e)}.sh: $(grep -m1 '^not ok ' "$work/stage" | cut -c1-90)"
    [ -n "$n" ] && echo "$room e2e $n" >>"$work/kills"
    return 1
}

# staged NAME FILE LOG: make test's checks in the copy, in the order that
# kills soonest (see the top). Status 0 when every check passed, 1 when
# one failed (by says which), 2 when the rest of the build failed.
staged() {
    room=$(echo "$2" | awk -F/ '$1 == "src" { print $2; next } { print $1 }')
    stem=$(basename "$2" | sed 's/\.[ch]$//')
    named=
    for x in $stem $room; do
        echo "$suites" | grep -qx -- "$x" && named="$named $x"
    done
    first=$(first_of "$room" unit "$named" | tr '\n' '|' | sed 's/|$//; s/|/\/*|/g; s/$/\/*/')
    inner=$(echo "$base" | sed -n 's/^!(\(.*\))$/\1/p')
    if [ -n "$named$(grep "^$room unit " "$work/kills")" ] && [ -n "$inner" ]; then
        unit_stage "@($first)" "$3" || return 1
        unit_stage "!($inner|$first)" "$3" || return 1
    else
        unit_stage "$base" "$3" || return 1
    fi
    [ -z "$MUTATE_UNIT_ONLY" ] || return 0
    make -C "$copy" -j2 $bins_rest >>"$3" 2>&1 || return 2
    echo "mutate: make replay" >>"$3"
    if ! make -C "$copy" --no-print-directory replay >>"$3" 2>&1; then
        by="make replay: $(grep -E -m1 '^fuzz_[a-z]*: |^replay: ' "$3" | cut -c1-90)"
        return 1
    fi
    scripts=
    for x in $room $stem; do
        [ -f "$copy/tests/e2e/test_$x.sh" ] && scripts="$scripts test_$x"
    done
    e2e_stage "$(first_of "$room" e2e "$scripts" any | tr '\n' ' ')" "$3" || return 1
    return 0
}

# The run, read whole before it starts: a shell reads a script as it
# goes, and this one runs for most of an hour while the tree is edited.
main() {
    all=$(awk '/^name:/ { print $2 }' "$list")
    dups=$(echo "$all" | sort | uniq -d)
    [ -z "$dups" ] || { echo "mutate: names used twice in $list: $dups" >&2; exit 2; }
    names=${MUTANTS:-$all}
    unset MUTANTS           # not for the make test of a copy
    start=$(date +%s)

    # ==== every mutant checked before the long run ====
    work=$(mktemp -d "${TMPDIR:-/tmp}/zview-mutate.XXXXXX") || exit 2
    trap 'rm -rf "$work"' EXIT
    trap 'exit 130' INT TERM HUP
    src=$here
    if [ -n "$MUTATE_REV" ]; then
        src=$work/rev
        mkdir -p "$src"
        git archive "$MUTATE_REV" | tar -C "$src" -xf - || exit 2
    fi
    # every one at once (tools/mutcheck.py: the file, the why, the text
    # found once, a change), but ZV_MUTANT and ZV_MUTANT_FILE's
    # shellcheck disable=SC2086
    python3 "$here/tools/mutcheck.py" "$list" "$src" $names || exit 2
    if [ $check = 1 ]; then
        echo "mutate: all $(echo "$names" | wc -w) mutants apply${ZV_MUTANT:+ (but those of $ZV_MUTANT_FILE, where $ZV_MUTANT is applied)}"
        exit 0
    fi

    # ==== the copy ====
    copy=$work/tree
    mkdir -p "$copy" "$MUTATE_LOGS"
    if [ "$src" = "$here" ]; then
        # the working files, committed or not (what a make test here would test)
        git ls-files -z --cached --others --exclude-standard |
            tar --null --ignore-failed-read -T - -cf - 2>/dev/null | tar -C "$copy" -xf - || exit 2
    else
        (cd "$src" && tar -cf - .) | tar -C "$copy" -xf - || exit 2
    fi

    # make test's own parts, for the stages
    base=$(makevar UNIT_FILTER)
    bin_zview=$(makevar BIN)
    bin_tests=$(makevar TESTBIN)
    # what the unit tests need, and every object (compiled, to compare);
    # the rest is linked only for a mutant the unit tests let through
    bins="$bin_zview $bin_tests $(makevar REPLAY_OBJS)"
    bins_rest="$(makevar REPLAYS) $(makevar STANDIN)"
    : >"$work/kills"
    suites=
    exclude=
    by=

    t0=$(date +%s)
    if [ -n "$MUTATE_CMD" ]; then
        echo "mutate: the unmutated copy first ($MUTATE_CMD in $copy)"
        (cd "$copy" && sh -c "$MUTATE_CMD") >"$MUTATE_LOGS/baseline.log" 2>&1
    elif [ "$MUTATE_BASELINE" = unit ]; then
        echo "mutate: the unmutated copy first (its unit tests; MUTATE_BASELINE=unit: its e2e scripts are taken as green)"
        make -C "$copy" -j2 $bins $bins_rest >"$MUTATE_LOGS/baseline.log" 2>&1 &&
            room=none unit_stage "$base" "$MUTATE_LOGS/baseline.log"
    else
        echo "mutate: the unmutated copy first (make test's checks, in stages, in $copy)"
        make -C "$copy" -j2 $bins $bins_rest >"$MUTATE_LOGS/baseline.log" 2>&1 && {
            staged "" src/none "$MUTATE_LOGS/baseline.log" || {
                # an e2e script that fails twice without any mutant: the
                # machine is too loaded for its clock (long_kitty's 200 ms
                # for the terminal's answer). It is left out, and said.
                case $by in "e2e "*) ;; *) false ;; esac &&
                    exclude=$(echo $failed) && [ -n "$exclude" ] &&
                    echo "mutate: $exclude failed twice without any mutant: left out of every run below (a survivor was not held to it)" &&
                    e2e_stage "" "$MUTATE_LOGS/baseline.log"
            }
        }
    fi || {
        echo "mutate: the unmutated copy fails its tests: see $MUTATE_LOGS/baseline.log" >&2
        exit 2
    }
    echo "mutate: baseline green in $(($(date +%s) - t0)) s"
    : >"$work/kills"
    # the code of every object, to tell a mutant that changes no code
    suites=$(cd "$copy" && "$bin_tests" --list 2>/dev/null | sed -n 's/^\([A-Za-z0-9_]*\): [0-9]* tests*$/\1/p')
    (cd "$copy" && find build -name '*.o') | while read -r o; do
        mkdir -p "$work/code/$(dirname "$o")"
        objcopy --strip-debug "$copy/$o" "$work/code/$o"
    done

    # ==== one mutant at a time ====
    killed=0
    total=0
    same=0
    survivors=
    broken=
    for m in $names; do
        f=$(field "$m" file)
        log=$MUTATE_LOGS/$m.log
        cp "$copy/$f" "$work/orig"
        mutate "$m" "$work/orig" >"$copy/$f"
        t0=$(date +%s)
        touch "$work/stamp"
        # built first, so that a mutant that does not compile is told apart
        if ! make -C "$copy" -j2 $bins >"$log" 2>&1; then
            echo "BROKEN   $m: does not build (see $log)"
            broken="$broken $m"
            cp "$work/orig" "$copy/$f"
            continue
        fi
        total=$((total + 1))
        if [ -z "$MUTATE_CMD" ] && same_code; then
            cp "$work/orig" "$copy/$f"
            echo "SAME     $m: compiles to the code of the original (an equivalent mutant; no test can kill it)"
            same=$((same + 1))
            survivors="$survivors $m"
            continue
        fi
        by=
        if [ -n "$MUTATE_CMD" ]; then
            (cd "$copy" && ZV_MUTANT=$m ZV_MUTANT_FILE=$f exec timeout "$MUTATE_TIMEOUT" sh -c "$MUTATE_CMD") >>"$log" 2>&1
            rc=$?
            if [ $rc -eq 124 ]; then
                by="the suite ran past $MUTATE_TIMEOUT s"
            elif [ $rc -ne 0 ]; then
                by=$(killer "$log")
            fi
        else
            ZV_MUTANT=$m ZV_MUTANT_FILE=$f staged "$m" "$f" "$log"
            rc=$?
        fi
        if [ $rc -eq 2 ]; then
            cp "$work/orig" "$copy/$f"
            total=$((total - 1))
            echo "BROKEN   $m: does not build (see $log)"
            broken="$broken $m"
            continue
        fi
        # the original back (a newer time stamp: the next build recompiles it)
        cp "$work/orig" "$copy/$f"
        secs=$(($(date +%s) - t0))
        if [ $rc -eq 0 ]; then
            echo "SURVIVED $m ($secs s)${MUTATE_UNIT_ONLY:+ (unit tests only)}: $(field "$m" why)"
            survivors="$survivors $m"
        else
            killed=$((killed + 1))
            echo "killed   $m ($secs s) by ${by:-make test failing (see $log)}"
        fi
    done

    pct=0
    [ $total -gt 0 ] && pct=$((100 * killed / total))
    echo "mutate: $killed of $total mutants killed ($pct%), $same the same code as the original; $(( ($(date +%s) - start) / 60 )) minutes"
    [ -z "$exclude" ] || echo "mutate: left out of every run: $exclude (failed twice without any mutant)"
    [ -z "$survivors" ] || echo "mutate: survived:$survivors (each is a test we lack, or an equivalent mutant; logs in $MUTATE_LOGS)"
    [ -z "$broken" ] || { echo "mutate: do not build:$broken" >&2; exit 2; }
    [ -z "$survivors" ]
}

main "$@"; exit $?
