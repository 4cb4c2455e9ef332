# Shared helpers for the e2e tests: check NAME CONDITION-COMMAND...
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT" || exit 1

ok() { echo "ok - $1"; }
notok() { echo "not ok - $1"; shift; [ $# -gt 0 ] && echo "#   $*"; }

# expect_status NAME WANT CMD...: run CMD, compare its exit status
expect_status() {
    name=$1; want=$2; shift 2
    "$@" >"$T/out" 2>"$T/err" </dev/null
    got=$?
    if [ "$got" -eq "$want" ]; then ok "$name"; else notok "$name" "status $got, wanted $want; stderr: $(head -c 300 "$T/err")"; fi
}

# expect_err NAME TEXT: the last command's stderr contains TEXT
expect_err() {
    if grep -qF -- "$2" "$T/err"; then ok "$1"; else notok "$1" "stderr lacks '$2': $(head -c 300 "$T/err")"; fi
}
expect_out() {
    if grep -qF -- "$2" "$T/out"; then ok "$1"; else notok "$1" "stdout lacks '$2': $(head -c 300 "$T/out")"; fi
}
