#!/bin/sh
# A picture while a big file loads (issue 21): the viewer starts at
# once, shows what is parsed so far with "loading N%" in the status bar,
# answers keys, and ends with the whole model; the picture of the part
# parsed is what --print draws of a file holding just those faces; q
# mid-load quits at once with the terminal given back; a load that
# fails after the viewer started ends it with the loader's one line.
# ZV_TEST_HOLD=FACES:FILE holds the loader after FACES faces until FILE
# exists, so that the checks see a known part for as long as they need
# (no timing: every wait polls for a condition, tmux.sh).
. "$(dirname "$0")/lib.sh"
. "$(dirname "$0")/tmux.sh"
# each load here parses a 59 MB file: under the sanitizers, on a loaded
# machine, that passed the 10 s the waits give by default
WAIT_POLLS=1200
# The loads here are sandboxed in every build, the AddressSanitizer one
# too: their children come from the fork server, forked before any
# thread (src/sandbox/server.c). When the loading thread forked them
# itself, GCC 12's libasan, which takes no lock around fork, hung about
# one run in three on an allocator lock the drawing and preview threads
# held at the fork.

# A 900 x 900 height field, its vertices first (59 MB: past the 32 MB
# from which the viewer loads while it shows), then its triangles.
N=900
mkdir -p "$T/snap"
awk -v n=$N 'BEGIN {
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++)
            printf "v %.5f %.5f %.5f\n", i / n - 0.5, 0.15 * sin(i * 0.05) * cos(j * 0.07), j / n - 0.5
    for (j = 0; j < n - 1; j++)
        for (i = 0; i < n - 1; i++) {
            a = j * n + i + 1
            printf "f %d %d %d\nf %d %d %d\n", a, a + n, a + 1, a + 1, a + n, a + n + 1
        }
}' >"$T/grid.obj"
all=$(( 2 * (N - 1) * (N - 1) ))
hold=300000

# ==== held after $hold faces: the part, exactly ====
session xterm-256color 100 30
tm send-keys -t zv "cd $T/snap && TERM=xterm-256color ZV_TEST_HOLD=$hold:$T/go $Z $T/grid.obj; echo zv-exit=\$?" Enter
if wait_for "faces $hold drawn"; then ok "the first $hold faces show while the file loads"; else
    notok "the first $hold faces show while the file loads" "$(status 30)"; fi
check "the status bar says loading N%" 'status 30 | grep -Eq "loading grid\.obj [0-9]+%"' "$(status 30)"
tm send-keys -t zv '?'
if wait_for 'zview keys'; then ok "? shows the help while loading"; else notok "? shows the help while loading" "$(status 30)"; fi
tm send-keys -t zv '?'
wait_gone 'zview keys' >/dev/null
tm send-keys -t zv O
if wait_for 'still loading grid\.obj'; then ok "O waits for the load (the scene is a picture of its part)"; else
    notok "O waits for the load (the scene is a picture of its part)" "$(status 30)"; fi
tm send-keys -t zv P
if wait_for 'wrote zview-grid-001'; then ok "P writes the picture while loading"; else notok "P writes the picture while loading" "$(status 30)"; fi
# the file cut after its $hold-th face, printed at the same size
head -n $((N * N + hold)) "$T/grid.obj" >"$T/cut.obj"
"$Z" --print --size 100x29 --color 256 "$T/cut.obj" >"$T/print"
check "the picture while loading is --print's of the file cut there" 'cmp -s "$T/snap/zview-grid-001.txt" "$T/print"' \
    "$(cmp "$T/snap/zview-grid-001.txt" "$T/print" 2>&1)"
: >"$T/go"
# (the bar may shorten the count to drawn/faces beside the note P left)
if wait_for "(faces $all drawn|/$all )"; then ok "then the whole model: faces $all"; else notok "then the whole model: faces $all" "$(status 30)"; fi
check "no longer loading" '! status 30 | grep -q loading' "$(status 30)"
tm send-keys -t zv P
wait_for 'wrote zview-grid-002' >/dev/null
"$Z" --print --size 100x29 --color 256 "$T/grid.obj" >"$T/print"
check "the whole model's picture is --print's of the file" 'cmp -s "$T/snap/zview-grid-002.txt" "$T/print"' \
    "$(cmp "$T/snap/zview-grid-002.txt" "$T/print" 2>&1)"
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "q quits after the load"; else notok "q quits after the load" "$(status 30)"; fi
rm -f "$T/go"

# ==== turned while loading: the camera stays where the user put it ====
session xterm-256color 100 30
tm send-keys -t zv "cd $T/snap && TERM=xterm-256color ZV_TEST_HOLD=$hold:$T/go $Z $T/grid.obj; echo zv-exit=\$?" Enter
wait_for "faces $hold drawn" >/dev/null
wait_stable
picture 29 >"$T/before"
tm send-keys -t zv h
wait_change "$T/before" 29 || notok "h turns the picture while loading"
: >"$T/go"
wait_for "(faces $all drawn|/$all )" >/dev/null
tm send-keys -t zv P
wait_for 'wrote zview-grid-003' >/dev/null
check "turned while loading, the whole model keeps the turn" '! cmp -s "$T/snap/zview-grid-003.txt" "$T/print"'
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null
rm -f "$T/go"

# ==== q while loading ====
session xterm-256color 100 30
tm send-keys -t zv "TERM=xterm-256color ZV_TEST_HOLD=$hold:$T/go sh -c 'echo \$\$ >$T/pid; exec $Z $T/grid.obj'; echo zv-exit=\$?" Enter
wait_for "faces $hold drawn" >/dev/null
check "the load is held (loading)" 'status 30 | grep -q "loading grid.obj"' "$(status 30)"
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "q while loading quits"; else notok "q while loading quits" "$(status 30)"; fi
pid=$(cat "$T/pid" 2>/dev/null)
check "no zview process is left" '[ -n "$pid" ] && ! kill -0 "$pid" 2>/dev/null && ! pgrep -f "$T/grid.obj" >/dev/null' \
    "$(pgrep -af "$T/grid.obj")"
prompt_back
tm send-keys -t zv "stty -a | tr ' ;' '\n\n' | grep -Ex -- '-?(icanon|echo)' | tr '\n' ' '; echo" Enter
if wait_for '^icanon echo$'; then ok "the terminal is given back (echo, line editing)"; else
    notok "the terminal is given back (echo, line editing)" "$(tail -3 "$T/screen")"; fi

# the same with the load in zview's own process (--no-sandbox): the
# loading thread is held, and the viewer does not wait for it
session xterm-256color 100 30
tm send-keys -t zv "TERM=xterm-256color ZV_TEST_HOLD=$hold:$T/go $Z --no-sandbox $T/grid.obj; echo zv-exit=\$?" Enter
wait_for "faces $hold drawn" >/dev/null
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "--no-sandbox: q while loading quits"; else notok "--no-sandbox: q while loading quits" "$(status 30)"; fi

# ==== a load that fails after the viewer started ====
cp "$T/grid.obj" "$T/bad.obj"
echo "f 1 2 $((N * N + 5))" >>"$T/bad.obj"
session xterm-256color 100 30
tm send-keys -t zv "TERM=xterm-256color $Z --strict $T/bad.obj; echo zv-exit=\$?" Enter
if wait_for 'zv-exit=1'; then ok "a load that fails ends the viewer (status 1)"; else notok "a load that fails ends the viewer (status 1)" "$(tail -3 "$T/screen")"; fi
check "... with the loader's line naming the file" 'grep -q "^zview: .*bad\.obj:" "$T/screen"' "$(tail -4 "$T/screen")"
