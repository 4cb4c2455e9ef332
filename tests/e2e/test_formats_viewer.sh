#!/bin/sh
# The viewer with models from other formats, under tmux: a model piped
# into `zview -` (the viewer then reads its keys from the terminal), and
# the U key cycling the up axis (the picture equals --print --up).
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
D=tests/data/formats

. "$(dirname "$0")/tmux.sh"
session xterm-256color 120 20

# the picture once two captures 0.1 s apart agree
settle() {
    cap
    cp "$T/screen" "$T/prev"
    i=0
    while [ $i -lt 100 ]; do
        sleep 0.1
        cap
        cmp -s "$T/screen" "$T/prev" && break
        cp "$T/screen" "$T/prev"
        i=$((i + 1))
    done
    head -n 19 "$T/screen" >"$1"
}

# a binary STL through a pipe; keys still work
tm send-keys -t zv "cat $D/house.stl | TERM=xterm-256color $Z --mode ascii --color none --view front -; echo zv-exit=\$?" Enter
if wait_for 'faces 14 drawn'; then ok "cat house.stl | zview - opens the viewer"; else
    notok "cat house.stl | zview - opens the viewer" "$(cat "$T/screen")"; fi
settle "$T/y"
"$Z" --print --mode ascii --color none --size 120x19 --view front $D/house.stl | sed 's/[[:space:]]*$//' >"$T/print-y"
if cmp -s "$T/y" "$T/print-y"; then ok "the piped model's picture equals --print"; else
    notok "the piped model's picture equals --print" "$(diff "$T/y" "$T/print-y" | head -5)"; fi

# an STL stands z-up: U goes on to x
tm send-keys -t zv U
if wait_for 'up: x'; then ok "U cycles the STL's up axis from z to x (and says so)"; else
    notok "U cycles the STL's up axis from z to x (and says so)" "$(tail -n 1 "$T/screen")"; fi
settle "$T/x"
"$Z" --print --mode ascii --color none --size 120x19 --up x --view front $D/house.stl | sed 's/[[:space:]]*$//' >"$T/print-x"
if cmp -s "$T/x" "$T/print-x"; then ok "after U the picture equals --print --up x"; else
    notok "after U the picture equals --print --up x" "$(diff "$T/x" "$T/print-x" | head -5)"; fi
if ! cmp -s "$T/x" "$T/y"; then ok "U turned the model"; else notok "U turned the model"; fi

tm send-keys -t zv '?'
if wait_for 'up axis'; then ok "the help lists the up-axis key"; else notok "the help lists the up-axis key"; fi
tm send-keys -t zv q q
if wait_for '^zv-exit=0$'; then ok "the piped viewer quits with status 0"; else notok "the piped viewer quits with status 0" "$(tail -n 3 "$T/screen")"; fi
