#!/bin/sh
# Run every tests/e2e/test_*.sh; each prints "ok - name" / "not ok - name"
# lines, and "ok - name # skip reason" for a check it could not run here
# (lib.sh's skip). Ends with "N passed, N failed, N skipped", the skips
# named; fails on a failure, and on a skip unless skips are allowed
# (tests/skips.sh).
set -u
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../skips.sh"
: "${ZVIEW:=$here/../../zview}"
export ZVIEW
pass=0
fail=0
skipped=0
out=$(mktemp)
skips=$(mktemp)
trap 'rm -f "$out" "$skips"' EXIT
for t in "$here"/test_*.sh; do
    sh "$t" >"$out" 2>&1
    rc=$?
    cat "$out"
    s=$(grep -ci '^ok .*# skip' "$out")
    p=$(($(grep -c '^ok ' "$out") - s))
    f=$(grep -c '^not ok ' "$out")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "not ok - $(basename "$t") exited with status $rc"
        f=1
    fi
    grep -i '^ok .*# skip' "$out" | sed "s|^ok - |  skipped: $(basename "$t"): |" >>"$skips"
    pass=$((pass + p))
    fail=$((fail + f))
    skipped=$((skipped + s))
done
echo "e2e: $pass passed, $fail failed, $skipped skipped"
cat "$skips"
verdict=0
skips_verdict e2e "$skipped" || verdict=1
[ "$fail" -eq 0 ] && [ "$pass" -gt 0 ] && [ $verdict -eq 0 ]
