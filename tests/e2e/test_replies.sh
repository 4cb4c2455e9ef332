#!/bin/sh
# The viewer on a pty that plays a terminal answering its questions
# (tests/e2e/replypty.py, issue 28): kitty, xterm, foot, tmux, answers
# that come late, a slow link that splits every answer byte by byte with
# its ESC alone up to 300 ms before the rest, 8-bit answers. An answer
# read as keys quit the viewer (kitty's APC, a split OSC 11 or DA); now
# it runs on, turns on a key and quits on q with the terminal put back.
# The profiles run side by side: they mostly wait.
. "$(dirname "$0")/lib.sh"
need_python "the viewer answered by terminals" || exit 0
Z=$ZVIEW
here=$(dirname "$0")
profiles="kitty xterm foot tmux late slow slowxterm xterm8 xtermssh xterm16 silent"
for p in $profiles; do
    python3 "$here/replypty.py" "$p" -- "$Z" assets/knot.obj >"$T/$p.out" 2>&1 &
done
wait
for p in $profiles; do
    cat "$T/$p.out"
    grep -q '^ok - ' "$T/$p.out" || notok "$p: the harness ran" "$(head -c 300 "$T/$p.out")"
done
