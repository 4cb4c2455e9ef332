# Shared helpers for the e2e tests: check NAME CONDITION-COMMAND...
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
cd "$ROOT" || exit 1
# python3, as the scripts call it (hundreds of times, some in polling
# loops): the interpreter itself, not a launcher that picks one at every
# call (pyenv's shim took 0.5 s a call here), found once (run.sh finds
# it for every script: ZV_PYTHON), and started with -S: the scripts use
# the standard library alone, and site's .pth files took 70 ms of each
# start here. By the same name, first in PATH, so that the tmux panes
# and python's own children get it too.
if [ -z "${ZV_PYTHON:-}" ] && command -v python3 >/dev/null 2>&1; then
    ZV_PYTHON=$(python3 -c 'import sys; print(sys.executable)' 2>/dev/null)
fi
if [ -x "${ZV_PYTHON:-}" ] && mkdir "$T/bin" &&
    printf '#!/bin/sh\nexec "%s" -S "$@"\n' "$ZV_PYTHON" >"$T/bin/python3" && chmod +x "$T/bin/python3"; then
    PATH=$T/bin:$PATH
    export PATH ZV_PYTHON
fi
# the terminal's background as some terminals export it would change
# what --print draws (backdrop.h): the tests say it where they need one
unset COLORFGBG

ok() { echo "ok - $1"; }
notok() { echo "not ok - $1"; shift; [ $# -gt 0 ] && echo "#   $*"; }
# skip NAME REASON: a check that could not run here (TAP's directive):
# run.sh counts it apart, and fails on it unless skips are allowed
skip() { echo "ok - $1 # skip $2"; }
# need_python NAME: true when python3 is here, else NAME is a skip
need_python() {
    command -v python3 >/dev/null 2>&1 && return 0
    skip "$1" "no python3"
    return 1
}

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
