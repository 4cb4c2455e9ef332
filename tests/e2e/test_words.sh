#!/bin/sh
# What a newcomer meets at the command line and in the viewer (issue 20):
# the words zview says, view commands that take more options, frames that
# play back, snapshots with names that say what they are.
. "$(dirname "$0")/lib.sh"
. "$(dirname "$0")/tmux.sh"

# -o - on a full device says why
"$Z" -o - --size 8x8 assets/cube.obj >/dev/full 2>"$T/err"
st=$?
check "-o - on a full device fails" '[ $st -eq 1 ]' "status $st"
expect_err "... and says why" "-o -: cannot write to standard output: No space left on device"

# --turntable --print: every frame starts at the top left (the first on a
# cleared screen), so cat plays them in place
"$Z" --turntable 3 --print --size 12x5 --color none assets/cube.obj >"$T/frames"
n=$(grep -o "$(printf '\033')\[H" "$T/frames" | wc -l)
check "--turntable --print: each of 3 frames homes the cursor" '[ "$n" -eq 3 ]' "$n"
check "... the first clears the screen first" '[ "$(head -c 7 "$T/frames" | od -An -c | tr -d " ")" = "033[H033[2J" ]' "$(head -c 7 "$T/frames" | od -An -c)"

# the view command: the files first, so that an option appended works
start 100 30 --print-view assets/knot.obj
wait_for 'faces [0-9]+ drawn' >/dev/null
tm send-keys -t zv l q
wait_for 'zv-exit=0' >/dev/null
cap
cmd=$(grep '^zview ' "$T/screen" | head -1)
check "--print-view starts with the file" 'echo "$cmd" | grep -q "^zview assets/knot.obj --yaw "' "$cmd"
sh -c "$(echo "$cmd" | sed "s|^zview|\"$Z\"|") -o $T/appended.png --size 64x48" 2>"$T/err"
check "... and an option appended to it is taken as an option" '[ -s "$T/appended.png" ] && [ ! -s "$T/err" ]' "$(cat "$T/err")"

# snapshots: a model from standard input is named stdin; an empty scene
# has nothing to save
mkdir -p "$T/snap"
session xterm-256color 100 30
tm send-keys -t zv "cd $T/snap && TERM=xterm-256color $Z - < $ROOT/assets/cube.obj; echo zv-exit=\$?" Enter
wait_for 'faces 6 drawn' >/dev/null
tm send-keys -t zv P
if wait_for 'wrote zview-stdin-001.png'; then ok "P of a model from standard input: zview-stdin-001"; else notok "P of a model from standard input: zview-stdin-001" "$(status 30)"; fi
tm send-keys -t zv E
wait_for 'y/n' >/dev/null
tm send-keys -t zv y
sleep 0.3
tm send-keys -t zv P
if wait_for 'the scene is empty, nothing to save'; then ok "P on an emptied scene says there is nothing to save"; else notok "P on an emptied scene says there is nothing to save" "$(status 30)"; fi
check "... and writes nothing" '[ ! -e "$T/snap/zview-stdin-002.png" ]' "$(ls "$T/snap")"
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

# TERM=dumb or no TERM at all: say the viewer cannot run there and what to
# do, then the one frame --print gives (on the terminal itself: a frame
# to a file or pipe never tries the viewer)
for term in dumb ""; do
    session xterm-256color 100 30
    tm send-keys -t zv "clear; TERM='$term' $Z --size 30x8 assets/cube.obj 2>$T/dumb.err; echo zv-exit=\$?" Enter
    wait_for 'zv-exit=[0-9]' >/dev/null
    check "TERM='$term': one frame on the terminal, status 0" 'grep -q "zv-exit=0" "$T/screen" && grep -q "▀" "$T/screen"' "$(tail -3 "$T/screen")"
    check "... and stderr says why there is no viewer and what to set" 'grep -q "TERM=$term cannot show the viewer .*TERM=xterm-256color" "$T/dumb.err"' "$(cat "$T/dumb.err")"
done

# at 80 columns: every key that changes a setting says so, and a note
# outranks a long file name while it shows
long="$T/a-model-with-a-rather-long-file-name-as-exporters-write-them.obj"
cp assets/cube.obj "$long"
start 80 24 "$long"
# (the long name leaves room for the counts as drawn/faces only)
wait_for '\| (faces 6 |6/6 )' >/dev/null
tm send-keys -t zv v
if wait_for 'shading: smooth'; then ok "80 columns: v says the shading"; else notok "80 columns: v says the shading" "$(status 24)"; fi
check "... and the file name gave way to it, marked" 'status 24 | grep -q "^ a-model-with[-a-z]*~ | "' "$(status 24)"
tm send-keys -t zv m
if wait_for 'mode: ascii'; then ok "80 columns: m says the mode"; else notok "80 columns: m says the mode" "$(status 24)"; fi
tm send-keys -t zv b
if wait_for 'back faces culled'; then ok "80 columns: b says culling"; else notok "80 columns: b says culling" "$(status 24)"; fi
# a file that cannot be opened: its short name and the reason, not the
# cut-off start of a long path
printf 'v 0 0 0\nf 1 2 3\n' >"$T/broken-model.obj"
tm send-keys -t zv O "$T/broken-model.obj" Enter
if wait_for 'broken-model.obj:2: '; then ok "a failed O names the file by its short name, the reason after"; else notok "a failed O names the file by its short name, the reason after" "$(status 24)"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

# sketch mode at start: the canvas's corners, the cursor in the middle and
# a one-line hint; at 80 columns w's note outranks the counts
mkdir -p "$T/sk80"
session xterm-256color 80 24
tm send-keys -t zv "cd $T/sk80 && TERM=xterm-256color $Z --sketch; echo zv-exit=\$?" Enter
if wait_for 'arrows move \+, space: corner, Enter: close'; then ok "--sketch starts with a hint in the status bar"; else notok "--sketch starts with a hint in the status bar" "$(status 24)"; fi
check "... the canvas's top corners marked" 'head -1 "$T/screen" | grep -q "^ *,-  *-\.$"' "$(head -2 "$T/screen")"
check "... and its bottom ones" 'sed -n 23p "$T/screen" | grep -q "^ *\`-  *-'"'"'$"' "$(sed -n 22,23p "$T/screen")"
check "... the cursor shown in the middle before any key" '[ "$(grep -c "^ *+$" "$T/screen")" = 1 ] && grep -n "^ *+$" "$T/screen" | grep -q "^1[0-2]:"' "$(grep -n "+" "$T/screen")"
tm send-keys -t zv Left Space Up Up Up Space S-Right Space Enter
wait_for '1 polygon' >/dev/null
tm send-keys -t zv t
wait_for 'tilted' >/dev/null
tm send-keys -t zv w
if wait_for 'wrote sketch-001.obj'; then ok "80 columns: w's note shows"; else notok "80 columns: w's note shows" "$(status 24)"; fi
check "... in full, before the help key" 'status 24 | grep -q "wrote sketch-001.obj | ? help$"' "$(status 24)"
check "... and the file is there" '[ -s "$T/sk80/sketch-001.obj" ]'
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null
