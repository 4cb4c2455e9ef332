#!/bin/sh
# Run every tests/e2e/test_*.sh; each prints "ok - name" / "not ok - name"
# lines. Ends with "N passed, N failed" and a non-zero status on failure.
set -u
here=$(cd "$(dirname "$0")" && pwd)
: "${ZVIEW:=$here/../../zview}"
export ZVIEW
pass=0
fail=0
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for t in "$here"/test_*.sh; do
    sh "$t" >"$out" 2>&1
    rc=$?
    cat "$out"
    p=$(grep -c '^ok ' "$out")
    f=$(grep -c '^not ok ' "$out")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "not ok - $(basename "$t") exited with status $rc"
        f=1
    fi
    pass=$((pass + p))
    fail=$((fail + f))
done
echo "e2e: $pass passed, $fail failed"
[ "$fail" -eq 0 ] && [ "$pass" -gt 0 ]
