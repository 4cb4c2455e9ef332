#!/bin/sh
# unit.sh TESTBIN [CRITERION-ARGS...]: the Criterion tests, then the ones
# that skipped themselves (cr_skip_test) counted and named from a TAP
# report; skips fail the run as tests/skips.sh says. Criterion reports a
# test its --filter left out as skipped too, as "test was skipped": those
# are not counted (every cr_skip_test in tests/ gives its reason).
set -u
here=$(cd "$(dirname "$0")" && pwd)
. "$here/skips.sh"
bin=$1
shift
tap=$(mktemp)
trap 'rm -f "$tap"' EXIT
"$bin" --tap="$tap" "$@"
rc=$?
skipped=$(grep -i '^ok .*# SKIP' "$tap" | grep -v '# SKIP test was skipped$')
n=0
[ -n "$skipped" ] && n=$(echo "$skipped" | wc -l)
echo "unit: $n skipped"
[ "$n" -eq 0 ] || echo "$skipped" | sed 's/^ok - /  skipped: /'
skips_verdict unit "$n" || [ $rc -ne 0 ] || rc=1
exit $rc
