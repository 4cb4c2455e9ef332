#!/bin/sh
# mutate.sh [--check] [LIST]: mutation testing (make mutate). Each
# mutant of LIST (default tests/mutants.txt; the format is described at
# its top) is applied alone to a copy of the tree, never to this one, and
# `make test` runs in the copy; a mutant the tests do not notice
# survives, and is a test we lack. Prints what killed each mutant and the kill rate; exits 1
# when one survives, 2 when a mutant is stale (its text not found exactly
# once) or does not build, or when the unmutated copy fails its tests.
# --check only checks that every mutant still applies (make test does),
# but the one ZV_MUTANT names: the run sets it to the mutant it applied.
#
#   MUTANTS="a b"        run only these (names from the list)
#   MUTATE_TIMEOUT=900   seconds a mutant's make test may take (then killed:
#                        a mutant that hangs the suite is noticed)
#   MUTATE_REV=HEAD      copy a commit instead of the working files
#   MUTATE_LOGS=DIR      where each mutant's make test output is kept
#                        (default build/mutate)
#   MUTATE_CMD='make unit'  another command than make test, run in the copy
#                        (a quick look while writing a test; the kill rate
#                        counts only with make test)
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here" || exit 2
check=0
[ "${1:-}" = --check ] && { check=1; shift; }
list=${1:-tests/mutants.txt}
[ -r "$list" ] || { echo "mutate: cannot read $list" >&2; exit 2; }
: "${MUTANTS:=}"
: "${MUTATE_TIMEOUT:=900}"
: "${MUTATE_REV:=}"
: "${MUTATE_LOGS:=build/mutate}"
: "${MUTATE_CMD:=make test}"

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

# the first line of a mutant's snippet, to say where it went
first_from() {
    awk -v n="$1" '/^name:/ { cur = $2; next }
        cur == n && index($0, "from:") == 1 { v = substr($0, 6); sub(/^[ \t]+/, "", v); print v; exit }' "$list"
}

# killer LOG: the first test a log names as failed (a unit test, an
# end-to-end check, a fuzz harness), else make's last word
killer() {
    for re in '^\[FAIL\] ' '^not ok ' '^fuzz_[a-z]*: |^replay: ' '^make.*\*\*\*'; do
        line=$(grep -E -- "$re" "$1" | head -n 1)
        [ -n "$line" ] && { echo "$line" | cut -c1-120; return; }
    done
}

# The run, read whole before it starts: a shell reads a script as it
# goes, and this one runs for most of an hour while the tree is edited.
main() {
    all=$(awk '/^name:/ { print $2 }' "$list")
    dups=$(echo "$all" | sort | uniq -d)
    [ -z "$dups" ] || { echo "mutate: names used twice in $list: $dups" >&2; exit 2; }
    names=${MUTANTS:-$all}
    unset MUTANTS           # not for the make test of a copy

    # ==== every mutant checked before the long run ====
    work=$(mktemp -d "${TMPDIR:-/tmp}/zview-mutate.XXXXXX") || exit 2
    trap 'rm -rf "$work"' EXIT
    trap 'exit 130' INT TERM HUP
    tmpf=$work/mutated
    src=$here
    if [ -n "$MUTATE_REV" ]; then
        src=$work/rev
        mkdir -p "$src"
        git archive "$MUTATE_REV" | tar -C "$src" -xf - || exit 2
    fi
    bad=0
    for m in $names; do
        f=$(field "$m" file)
        # the copy a mutant's make test runs in holds that mutant: its
        # text is gone from there by design
        [ "$m" = "${ZV_MUTANT:-}" ] && continue
        if ! echo "$all" | grep -qx -- "$m"; then
            echo "mutate: $m: no such mutant in $list" >&2
            bad=1
        elif [ -z "$f" ] || [ ! -f "$src/$f" ]; then
            echo "mutate: $m: no file '$f'" >&2
            bad=1
        elif [ -z "$(field "$m" why)" ]; then
            echo "mutate: $m: no why: (what a user would see if it went in)" >&2
            bad=1
        elif ! n=$(mutate "$m" "$src/$f" 2>&1 >"$tmpf"); then
            where=$(cd "$src" && grep -rlF -- "$(first_from "$m")" src include 2>/dev/null | tr '\n' ' ')
            echo "mutate: $m: its text occurs ${n:-0} times in $f, not once (its first line is in: ${where:-no file})" >&2
            bad=1
        elif cmp -s "$tmpf" "$src/$f"; then
            echo "mutate: $m: changes nothing" >&2
            bad=1
        fi
    done
    [ $bad = 0 ] || exit 2
    if [ $check = 1 ]; then
        echo "mutate: all $(echo "$names" | wc -w) mutants apply${ZV_MUTANT:+ (but $ZV_MUTANT, applied here)}"
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

    echo "mutate: the unmutated copy first ($MUTATE_CMD in $copy)"
    t0=$(date +%s)
    if ! (cd "$copy" && sh -c "$MUTATE_CMD") >"$MUTATE_LOGS/baseline.log" 2>&1; then
        echo "mutate: $MUTATE_CMD fails without any mutant: see $MUTATE_LOGS/baseline.log" >&2
        exit 2
    fi
    echo "mutate: baseline green in $(($(date +%s) - t0)) s"

    # ==== one mutant at a time ====
    killed=0
    total=0
    survivors=
    broken=
    for m in $names; do
        f=$(field "$m" file)
        log=$MUTATE_LOGS/$m.log
        cp "$copy/$f" "$work/orig"
        mutate "$m" "$work/orig" >"$copy/$f"
        t0=$(date +%s)
        # built first, so that a mutant that does not compile is told apart
        if ! make -C "$copy" -j2 all build/zview-tests >"$log" 2>&1; then
            echo "BROKEN   $m: does not build (see $log)"
            broken="$broken $m"
            cp "$work/orig" "$copy/$f"
            continue
        fi
        (cd "$copy" && ZV_MUTANT=$m exec timeout "$MUTATE_TIMEOUT" sh -c "$MUTATE_CMD") >>"$log" 2>&1
        rc=$?
        # the original back (a newer time stamp: the next build recompiles it)
        cp "$work/orig" "$copy/$f"
        total=$((total + 1))
        secs=$(($(date +%s) - t0))
        if [ $rc -eq 0 ]; then
            echo "SURVIVED $m ($secs s): $(field "$m" why)"
            survivors="$survivors $m"
        else
            killed=$((killed + 1))
            if [ $rc -eq 124 ]; then
                by="the suite ran past $MUTATE_TIMEOUT s"
            else
                by=$(killer "$log")
            fi
            echo "killed   $m ($secs s) by ${by:-make test failing (see $log)}"
        fi
    done

    pct=0
    [ $total -gt 0 ] && pct=$((100 * killed / total))
    echo "mutate: $killed of $total mutants killed ($pct%)"
    [ -z "$survivors" ] || echo "mutate: survived:$survivors (each is a test we lack; logs in $MUTATE_LOGS)"
    [ -z "$broken" ] || { echo "mutate: do not build:$broken" >&2; exit 2; }
    [ -z "$survivors" ]
}

main "$@"; exit $?
