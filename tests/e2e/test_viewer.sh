#!/bin/sh
# The interactive viewer under tmux: a shell runs in a detached pane of a
# fixed size, zview is typed into it, keys are sent, and the pane's text
# is polled (capture-pane) until a condition holds or a bounded timeout
# passes. Each session has its own server socket, killed on exit even
# when a check fails.
. "$(dirname "$0")/lib.sh"
. "$(dirname "$0")/tmux.sh"

# ==== start-up, status bar, --print equality ====
start 100 30 assets/torus.obj
if wait_for 'faces [0-9]+ drawn'; then ok "status bar shows"; else notok "status bar shows" "$(cat "$T/screen")"; fi
bar=$(status 30)
nf=$(grep -c '^f ' assets/torus.obj)
check "polygon count is the face count ($nf)" 'echo "$bar" | grep -q "faces $nf "' "$bar"
# drawn: the polygons that reached the algorithm, as --info counts them
# for the same picture (100 x 29 cells of half blocks: 100 x 58 pixels,
# 4 samples each)
nd=$("$Z" --info --algo zbuffer --samples 4 --size 100x58 assets/torus.obj | sed -n 's/^polygons:.* \([0-9][0-9]*\) to the algorithm$/\1/p')
check "drawn is what --info counts for the same picture ($nd, fewer than $nf)" \
    '[ -n "$nd" ] && [ "$nd" -lt "$nf" ] && echo "$bar" | grep -q "drawn $nd "' "$bar"
check "algorithm named" 'echo "$bar" | grep -q "| zbuffer "' "$bar"
check "picture size in pixels" 'echo "$bar" | grep -q "100x58px"' "$bar"
picture 29 >"$T/p0"
check "picture is not empty" '[ "$(tr -d " \n" <"$T/p0" | wc -c)" -gt 500 ]' "$(head -c 300 "$T/p0")"
# colours included: the viewer uses --print's quantizer, dithered alike
if need_python "screen equals --print cell for cell, colours included (256)"; then
    print_looks --color 256 --size 100x29 assets/torus.obj >"$T/print"
    wait_looks 29 "$T/print"
    check "screen equals --print cell for cell, colours included (256)" 'cmp -s "$T/looks" "$T/print"' "$(diff "$T/looks" "$T/print" | head -5)"
fi

# ==== keys ====
tm send-keys -t zv Right
if wait_change "$T/p0" 29; then ok "a rotation key changes the picture"; else notok "a rotation key changes the picture"; fi
wait_stable
picture 29 >"$T/p1"
tm send-keys -t zv g
if wait_for '\| scanline '; then ok "g switches to the next algorithm"; else notok "g switches to the next algorithm" "$(status 30)"; fi
picture 29 >"$T/p2"
check "another algorithm draws the same picture" 'cmp -s "$T/p1" "$T/p2"' "$(diff "$T/p1" "$T/p2" | head -5)"
for algo in span hzb hzb-octree; do
    tm send-keys -t zv g
    if wait_for "\\| $algo "; then
        picture 29 >"$T/pa"
        check "$algo draws the same picture" 'cmp -s "$T/p1" "$T/pa"' "$(diff "$T/p1" "$T/pa" | head -5)"
    else
        notok "$algo draws the same picture" "not selected: $(status 30)"
    fi
done
check "half mode draws half blocks" 'grep -q "▀" "$T/p1"'
tm send-keys -t zv m
if wait_for '(\| |mode: )ascii '; then ok "m switches to ascii"; else notok "m switches to ascii" "$(status 30)"; fi
picture 29 >"$T/p3"
check "ascii mode uses other characters" '! grep -q "[▀▄]" "$T/p3" && grep -q "[.:=+*#%@-]" "$T/p3"' "$(head -c 300 "$T/p3")"
tm send-keys -t zv m
if wait_for '(\| |mode: )braille '; then
    picture 29 >"$T/p4"
    check "braille mode draws braille dots" 'grep -q "⣿" "$T/p4" && ! grep -q "[▀▄]" "$T/p4"' "$(head -c 300 "$T/p4")"
else
    notok "m switches to braille" "$(status 30)"
fi
tm send-keys -t zv '?'
if wait_for 'zview keys'; then ok "? shows the help"; else notok "? shows the help"; fi
# the overlay may still be drawing when its title shows: wait for its line
if wait_for 'q Esc +quit'; then ok "help lists the quit key"; else notok "help lists the quit key" "$(head -c 400 "$T/screen")"; fi
tm send-keys -t zv '?'
if wait_gone 'zview keys'; then ok "? again closes the help"; else notok "? again closes the help"; fi

# ==== mouse (SGR reports, as xterm and tmux send them) and auto-rotate ====
tm send-keys -t zv m
wait_for '\| half ' >/dev/null
wait_stable
picture 29 >"$T/m0"
tm send-keys -t zv -l "$(printf '\033[<0;50;15M\033[<32;56;15M\033[<32;62;17M\033[<0;62;17m')"
if wait_change "$T/m0" 29; then ok "a left drag turns the model"; else notok "a left drag turns the model"; fi
wait_stable
picture 29 >"$T/m1"
tm send-keys -t zv -l "$(printf '\033[<65;50;15M\033[<65;50;15M')"
if wait_change "$T/m1" 29; then ok "the wheel scales the model"; else notok "the wheel scales the model"; fi
wait_stable
picture 29 >"$T/m2"
tm send-keys -t zv ' '
if wait_for ' spin@30'; then ok "space starts the turntable"; else notok "space starts the turntable" "$(status 30)"; fi
if wait_change "$T/m2" 29; then
    picture 29 >"$T/m3"
    if wait_change "$T/m3" 29; then ok "the turntable keeps turning without keys"; else notok "the turntable keeps turning without keys"; fi
else
    notok "the turntable keeps turning without keys" "no change"
fi
tm send-keys -t zv ' '
if wait_gone ' spin@' && wait_stable; then ok "space stops the turntable"; else notok "space stops the turntable" "$(status 30)"; fi

# ==== quit with q: prompt back, normal screen, cursor visible ====
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "q quits with status 0"; else notok "q quits with status 0" "$(cat "$T/screen")"; fi
if prompt_back; then ok "the shell prompt is back after q"; else notok "the shell prompt is back after q" "$(cat "$T/screen")"; fi
check "no alternate screen after q" '[ "$(tm display -p -t zv "#{alternate_on}")" = 0 ]'
check "cursor visible after q" '[ "$(tm display -p -t zv "#{cursor_flag}")" = 1 ]'

# ==== objects ====
# ascii: the shading shows in the characters, so a move shows in the text
start 120 30 --mode ascii --yaw 30 --pitch 25 assets/scene.obj
wait_for 'faces [0-9]+ drawn' >/dev/null
check "a scene of several objects shows them all" 'grep -q "\[all 6\]" "$T/screen"' "$(status 30)"
tm send-keys -t zv n
if wait_for '\[cone 1/6\]'; then ok "n selects the first object"; else notok "n selects the first object" "$(status 30)"; fi
tm send-keys -t zv Tab
if wait_for '\[floor 2/6\]'; then ok "Tab selects the next object"; else notok "Tab selects the next object" "$(status 30)"; fi
picture 29 >"$T/s0"
tm send-keys -t zv d d d
if wait_change "$T/s0" 29; then ok "moving the selected object changes the picture"; else notok "moving the selected object changes the picture"; fi
tm send-keys -t zv N
if wait_for '\[all 6\]'; then ok "N selects the whole scene"; else notok "N selects the whole scene" "$(status 30)"; fi

# ==== resize ====
start 100 30 assets/torus.obj
wait_for 'faces [0-9]+ drawn' >/dev/null
picture 29 >"$T/r0"
tm resize-window -t zv -x 70 -y 22
# the new picture is exactly what --print draws at the new size
if need_python "the picture follows a resize (equals --print at the new size)"; then
    print_looks --color 256 --size 70x21 assets/torus.obj >"$T/print"
    wait_looks 21 "$T/print"
    check "the picture follows a resize (equals --print at the new size)" 'cmp -s "$T/looks" "$T/print"' "$(diff "$T/looks" "$T/print" | head -5)"
fi
wait_for 'faces 12288' >/dev/null
check "the status bar moves to the new last line" 'status 22 | grep -q "faces 12288"' "$(status 22)"
tm resize-window -t zv -x 10 -y 3
if wait_for 'too small'; then ok "a tiny window shows a short message"; else notok "a tiny window shows a short message" "$(cat "$T/screen")"; fi
tm resize-window -t zv -x 100 -y 30
if wait_for '100x58px'; then ok "the picture comes back after growing"; else notok "the picture comes back after growing"; fi

# ==== SIGTERM and SIGINT: the terminal is restored ====
i=0
while [ ! -s "$T/pid" ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
kill -TERM "$(cat "$T/pid")"
if wait_for 'zv-exit=143'; then ok "SIGTERM ends zview"; else notok "SIGTERM ends zview" "$(cat "$T/screen")"; fi
check "no alternate screen after SIGTERM" '[ "$(tm display -p -t zv "#{alternate_on}")" = 0 ]'
check "cursor visible after SIGTERM" '[ "$(tm display -p -t zv "#{cursor_flag}")" = 1 ]'
check "mouse reporting off after SIGTERM" '[ "$(tm display -p -t zv "#{mouse_any_flag}#{mouse_standard_flag}#{mouse_button_flag}#{mouse_sgr_flag}")" = 0000 ]'
check "keypad mode off after SIGTERM" '[ "$(tm display -p -t zv "#{keypad_flag}#{keypad_cursor_flag}")" = 00 ]'
if prompt_back; then ok "the shell prompt is back after SIGTERM"; else notok "the shell prompt is back after SIGTERM" "$(cat "$T/screen")"; fi

start 80 24 assets/cube.obj
wait_for 'faces 6 drawn' >/dev/null
i=0
while [ ! -s "$T/pid" ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
kill -HUP "$(cat "$T/pid")"
if wait_for 'zv-exit=129'; then ok "SIGHUP (a dropped ssh link) ends zview"; else notok "SIGHUP (a dropped ssh link) ends zview" "$(cat "$T/screen")"; fi
check "no alternate screen after SIGHUP" '[ "$(tm display -p -t zv "#{alternate_on}")" = 0 ]'
check "cursor visible after SIGHUP" '[ "$(tm display -p -t zv "#{cursor_flag}")" = 1 ]'

# a crash (a bug) must not leave the terminal in curses modes either
start 80 24 assets/cube.obj
wait_for 'faces 6 drawn' >/dev/null
i=0
while [ ! -s "$T/pid" ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
kill -SEGV "$(cat "$T/pid")"
if wait_for 'zv-exit=139'; then ok "SIGSEGV ends zview"; else notok "SIGSEGV ends zview" "$(cat "$T/screen")"; fi
check "no alternate screen after a crash" '[ "$(tm display -p -t zv "#{alternate_on}")" = 0 ]'
check "cursor visible after a crash" '[ "$(tm display -p -t zv "#{cursor_flag}")" = 1 ]'

start 80 24 assets/cube.obj
if wait_for 'faces 6 drawn'; then ok "the cube shows 6 faces"; else notok "the cube shows 6 faces" "$(cat "$T/screen")"; fi
i=0
while [ ! -s "$T/pid" ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
pid=$(cat "$T/pid")
tm send-keys -t zv C-c
# the interactive shell drops the rest of a command line stopped by
# Ctrl-C, so watch the process instead of its exit status
i=0
while kill -0 "$pid" 2>/dev/null && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
if ! kill -0 "$pid" 2>/dev/null; then ok "Ctrl-C ends zview"; else notok "Ctrl-C ends zview" "$(cat "$T/screen")"; fi
if prompt_back; then ok "the shell prompt is back after Ctrl-C"; else notok "the shell prompt is back after Ctrl-C" "$(cat "$T/screen")"; fi
check "no alternate screen after Ctrl-C" '[ "$(tm display -p -t zv "#{alternate_on}")" = 0 ]'
check "cursor visible after Ctrl-C" '[ "$(tm display -p -t zv "#{cursor_flag}")" = 1 ]'

# ==== Ctrl-Z and fg: every mode the viewer set comes back ====
# the modes as tmux sees them: alternate screen, cursor hidden, mouse
# drags reported (1002, not just clicks: 1000) in the SGR form, keypad
modes() { tm display -p -t zv 'alt=#{alternate_on} cursor=#{cursor_flag} click=#{mouse_standard_flag} drag=#{mouse_button_flag} sgr=#{mouse_sgr_flag} keypad=#{keypad_cursor_flag}'; }
start 80 24 assets/cube.obj
wait_for 'faces 6 drawn' >/dev/null
before=$(modes)
check "the viewer's modes: drags reported" '[ "$before" = "alt=1 cursor=0 click=0 drag=1 sgr=1 keypad=1" ]' "$before"
tm send-keys -t zv C-z
wait_gone 'faces 6 drawn' >/dev/null
stopped=$(modes)
check "Ctrl-Z leaves every mode" '[ "$stopped" = "alt=0 cursor=1 click=0 drag=0 sgr=0 keypad=0" ]' "$stopped"
tm send-keys -t zv fg Enter
if wait_for 'faces 6 drawn'; then ok "fg draws the viewer again"; else notok "fg draws the viewer again" "$(cat "$T/screen")"; fi
after=$(modes)
check "after fg the modes are the viewer's again (drags, not clicks only)" '[ "$after" = "$before" ]' "before: $before, after: $after"
picture 23 >"$T/z0"
tm send-keys -t zv -l "$(printf '\033[<0;30;10M\033[<32;40;10M\033[<0;40;10m')"
if wait_change "$T/z0" 23; then ok "after fg a drag turns the model"; else notok "after fg a drag turns the model"; fi
pid=$(cat "$T/pid")
tm send-keys -t zv q
# the shell went on with its command line when the job stopped: watch
# the process, and the shell's prompt
i=0
while kill -0 "$pid" 2>/dev/null && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
if ! kill -0 "$pid" 2>/dev/null && prompt_back; then ok "q quits after fg"; else notok "q quits after fg" "$(tail -3 "$T/screen")"; fi
check "no mouse reporting left after q" '[ "$(modes)" = "alt=0 cursor=1 click=0 drag=0 sgr=0 keypad=0" ]' "$(modes)"

# ==== what terminals send besides keys: never read as Esc (which quits) ====
start 80 24 --mode ascii assets/cube.obj
wait_for 'faces 6 drawn' >/dev/null
# focus in and out, a bracketed paste holding a q, an unasked-for
# any-motion mouse report, a mode report, F5, and every form of End,
# Home, Insert, Page Up/Down (Delete has a meaning: it removes)
tm send-keys -t zv -H 1b 5b 49 1b 5b 4f
tm send-keys -t zv -l "$(printf '\033[200~q\033[201~\033[<35;10;10M\033[?1002;1$y\033[15~')"
tm send-keys -t zv -H 1b 5b 46 1b 4f 46 1b 5b 34 7e 1b 5b 38 7e 1b 5b 31 3b 35 46
tm send-keys -t zv -H 1b 5b 48 1b 4f 48 1b 5b 31 7e 1b 5b 37 7e 1b 5b 32 7e 1b 5b 35 7e 1b 5b 36 7e 1b 5b 36 3b 32 7e
sleep 0.3
tm send-keys -t zv f
if wait_for 'faces 6 drawn' && ! grep -q 'zv-exit' "$T/screen"; then ok "focus events, a paste, reports and the editing keys do not quit"; else
    notok "focus events, a paste, reports and the editing keys do not quit" "$(tail -3 "$T/screen")"; fi
# the open prompt: Home and End as tmux and screen send them move the cursor
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l abc
tm send-keys -t zv -H 1b 5b 31 7e
tm send-keys -t zv x
tm send-keys -t zv -H 1b 5b 34 7e
tm send-keys -t zv y
tm send-keys -t zv -H 1b 5b 48
tm send-keys -t zv 1
tm send-keys -t zv -H 1b 4f 46
tm send-keys -t zv 2
if wait_for '^ open: 1xabcy2$'; then ok "Home and End in every form move the prompt's cursor"; else notok "Home and End in every form move the prompt's cursor" "$(status 24)"; fi
tm send-keys -t zv -H 1b 5b 49
tm send-keys -t zv -l "$(printf '\033[200~zz\033[201~')"
sleep 0.2
if wait_for '^ open: 1xabcy2$'; then ok "a focus event or a paste does not cancel the prompt"; else notok "a focus event or a paste does not cancel the prompt" "$(status 24)"; fi
tm send-keys -t zv Escape
if wait_gone '^ open:' && wait_for 'faces 6 drawn'; then ok "Esc still cancels the prompt"; else notok "Esc still cancels the prompt" "$(status 24)"; fi
tm send-keys -t zv Escape
if wait_for 'zv-exit=0'; then ok "a lone Esc still quits"; else notok "a lone Esc still quits" "$(tail -3 "$T/screen")"; fi

# ==== a slow link: q quits at once, however much of a frame waits ====
# a 200 x 60 window in 24-bit colour, its other side read at 2 kB/s and
# 200 B/s (a frame of the torus is some 100 kB: 50 s and 500 s of link)
if need_python "q quits within 5 s on a slow link, the terminal reset"; then
    for rate in 2000 200; do
        res=$(TERM=xterm-256color python3 tests/e2e/slowpty.py $rate 1 5 200 60 -- "$Z" --color 24bit assets/torus.obj)
        check "q quits within 5 s on a link read at $rate B/s, the terminal reset" \
            'echo "$res" | grep -q "^quit after .*reset seen"' "$res"
    done
fi

# ==== not a terminal / unknown terminal: behave like --print ====
"$Z" assets/cube.obj --size 40x12 --color none >"$T/pipe" 2>"$T/err" </dev/null
st=$?
check "stdout not a terminal prints one frame" '[ $st -eq 0 ] && [ "$(wc -l <"$T/pipe")" -eq 12 ] && ! grep -q "$(printf "\033")" "$T/pipe"' "status $st"
session xterm-256color 80 24
# an unknown TERM: a warning, and the viewer on a description we have
tm send-keys -t zv "TERM=nonsense $Z assets/cube.obj 2>$T/warn; echo zv-exit=\$?" Enter
if wait_for 'faces 6 drawn'; then ok "TERM=nonsense: the viewer runs"; else notok "TERM=nonsense: the viewer runs" "$(cat "$T/screen")"; fi
check "TERM=nonsense: the picture is drawn" 'grep -q "[▀▄]" "$T/screen"' "$(cat "$T/screen")"
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "TERM=nonsense: q quits with status 0"; else notok "TERM=nonsense: q quits with status 0" "$(cat "$T/screen")"; fi
check "TERM=nonsense: stderr warns and names the fallback" 'grep -qx "zview: unknown terminal type .nonsense.: using xterm-256color" "$T/warn"' "$(cat "$T/warn")"
# xterm-direct without its entry (ncurses-term not installed) falls back too, in 24-bit colour;
# where ncurses-term is installed (mlterm depends on it: tools/deps.sh), a
# -direct name no package has stands for it
direct=xterm-direct
infocmp $direct >/dev/null 2>&1 && direct=zvtest-direct
tm send-keys -t zv "clear; TERM=$direct $Z assets/cube.obj 2>$T/warn; echo zv-exit=\$?" Enter
if wait_for 'faces 6 drawn'; then ok "TERM=$direct without its entry: the viewer runs"; else
    notok "TERM=$direct without its entry: the viewer runs" "$(cat "$T/screen")"; fi
check "TERM=$direct without its entry: 24-bit colours" 'tm capture-pane -p -e -t zv | grep -q "38;2;"' "$(tm capture-pane -p -e -t zv | head -c 300 | od -c | head)"
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null
check "TERM=$direct without its entry: stderr warns" 'grep -q "unknown terminal type .$direct.: using" "$T/warn"' "$(cat "$T/warn")"

# ==== standard input not a terminal: keys come from the terminal ====
# cpu_ticks PID: user + system time so far, in clock ticks
cpu_ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }
session xterm-256color 80 24
rm -f "$T/pid"
tm send-keys -t zv "echo | TERM=xterm-256color sh -c 'echo \$\$ >$T/pid; exec $Z assets/cube.obj'; echo zv-exit=\$?" Enter
if wait_for 'faces 6 drawn'; then ok "stdin at its end: the viewer shows the model"; else notok "stdin at its end: the viewer shows the model" "$(cat "$T/screen")"; fi
check "stdin at its end: the picture is drawn" 'grep -q "▀" "$T/screen"' "$(cat "$T/screen")"
i=0
while [ ! -s "$T/pid" ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
pid=$(cat "$T/pid")
# a CPU-use check, not a timing test: idle, the process must not run
t0=$(cpu_ticks "$pid")
sleep 2
t1=$(cpu_ticks "$pid")
check "stdin at its end: no CPU while idle (< 5 ticks in 2 s)" '[ $((t1 - t0)) -lt 5 ]' "ticks $t0 -> $t1"
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "stdin at its end: q (read from the terminal) quits"; else notok "stdin at its end: q (read from the terminal) quits" "$(cat "$T/screen")"; fi
check "no alternate screen after q with stdin at its end" '[ "$(tm display -p -t zv "#{alternate_on}")" = 0 ]'

start 80 24 assets/cube.obj '</dev/null'
if wait_for 'faces 6 drawn'; then ok "stdin from /dev/null: the viewer shows the model"; else notok "stdin from /dev/null: the viewer shows the model" "$(cat "$T/screen")"; fi
picture 23 >"$T/d0"
tm send-keys -t zv Right
if wait_change "$T/d0" 23; then ok "stdin from /dev/null: Right (read from the terminal) turns the picture"; else
    notok "stdin from /dev/null: Right (read from the terminal) turns the picture" "$(cat "$T/screen")"; fi
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "stdin from /dev/null: q quits"; else notok "stdin from /dev/null: q quits" "$(cat "$T/screen")"; fi

# no terminal to read keys from (setsid: no controlling terminal): one frame and a note
session xterm-256color 80 24
tm send-keys -t zv "echo | TERM=xterm-256color setsid -w $Z --color none assets/cube.obj 2>$T/note; echo zv-exit=\$?" Enter
if wait_for 'zv-exit=0'; then ok "no terminal for keys: one frame, status 0"; else notok "no terminal for keys: one frame, status 0" "$(cat "$T/screen")"; fi
check "no terminal for keys: the note says so" 'grep -q "^zview: no terminal to read keys from" "$T/note"' "$(cat "$T/note")"
check "no terminal for keys: the frame has the cube" 'grep -q "▀" "$T/screen"' "$(cat "$T/screen")"

# ==== the help overlay ====
start 100 30 assets/cube.obj
wait_for 'faces 6 drawn' >/dev/null
check "drag reporting is on while the viewer runs" '[ "$(tm display -p -t zv "#{mouse_button_flag}")" = 1 ]'
tm send-keys -t zv '?'
wait_for 'zview keys' >/dev/null
tm send-keys -t zv q
if wait_gone 'zview keys'; then ok "q closes the help"; else notok "q closes the help" "$(cat "$T/screen")"; fi
# the q that closed the help must not also have quit: the viewer still takes keys
tm send-keys -t zv m
if wait_for '\| ascii ' && ! grep -q 'zv-exit' "$T/screen"; then ok "the key that closes the help does nothing else"; else
    notok "the key that closes the help does nothing else" "$(cat "$T/screen")"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

# a small window: the box fits, and scrolling reaches every key
start 40 12 assets/torus.obj
wait_for 'zbuffer' >/dev/null
tm send-keys -t zv '?'
if wait_for 'more'; then ok "the help in a small window says there is more"; else notok "the help in a small window says there is more" "$(cat "$T/screen")"; fi
check "the help box fits the small window (both frame lines show)" '[ "$(grep -c "^ *+---*+ *$" "$T/screen")" -eq 2 ] || [ "$(grep -c "+---*+" "$T/screen")" -eq 2 ]' "$(cat "$T/screen")"
# j (a row) ten at a time, at most 150: a key, a pause and a look each
# took 7 s; a j past the end is one the help takes and ignores
i=0
while [ $i -lt 150 ] && ! grep -q 'right drag' "$T/screen"; do
    tm send-keys -t zv j j j j j j j j j j
    sleep 0.05
    cap
    i=$((i + 10))
done
check "scrolling the help reaches its last key" 'grep -q "right drag" "$T/screen"' "$(cat "$T/screen")"
check "scrolling did not leave the help" 'grep -q "more" "$T/screen"' "$(cat "$T/screen")"
tm send-keys -t zv Escape
if wait_gone 'right drag' && ! grep -q 'zv-exit' "$T/screen"; then ok "Esc closes the help without quitting"; else
    notok "Esc closes the help without quitting" "$(cat "$T/screen")"; fi

# ==== the status bar keeps what matters at 80 columns ====
start 80 24 assets/scene.obj
wait_for 'faces [0-9]+ drawn' >/dev/null
bar=$(status 24)
nd=$("$Z" --info --algo zbuffer --samples 4 --size 80x46 assets/scene.obj | sed -n 's/^polygons:.* \([0-9][0-9]*\) to the algorithm$/\1/p')
for want in 'scene\.obj' '\[all 6\]' "faces 3049 drawn ${nd:-none} " 'zbuffer [0-9.]+ms' '\? help$'; do
    check "80 columns: the status bar keeps $want" 'echo "$bar" | grep -Eq "$want"' "$bar"
done
check "80 columns: the frame time went first" '! echo "$bar" | grep -q "fps"' "$bar"
tm resize-window -t zv -x 110 -y 24
wait_for '110x46px' >/dev/null
bar=$(status 24)
check "110 columns: picture size and mode are back, the frame time is not" 'echo "$bar" | grep -q "half lambert 256 | 110x46px | ? help" && ! echo "$bar" | grep -q fps' "$bar"
tm resize-window -t zv -x 140 -y 24
wait_for 'fps' >/dev/null
bar=$(status 24)
check "140 columns: every field" 'echo "$bar" | grep -Eq "frame [0-9.]+ms [0-9]+fps \| half lambert 256 \| 140x46px \| \? help"' "$bar"

# ==== nothing left on the shell after quitting from a grown or shrunk window ====
for size in "110 34" "60 14"; do
    start 80 24 assets/torus.obj
    wait_for 'faces [0-9]+ drawn' >/dev/null
    set -- $size
    tm resize-window -t zv -x "$1" -y "$2"
    # the status bar on the new last line: the viewer has drawn at the new
    # size (at 60 columns it counts drawn/faces, without the word)
    i=0
    while [ $i -lt 200 ]; do
        cap
        status "$2" | grep -q '^ torus\.obj | ' && break
        sleep 0.05
        i=$((i + 1))
    done
    tm send-keys -t zv q
    wait_for 'zv-exit=0' >/dev/null
    check "quit after resizing to $1x$2 leaves no picture on the shell" '! grep -q "[▀▄]" "$T/screen"' "$(cat "$T/screen")"
done

# ==== --size fixes the viewer's picture ====
start 100 30 --size 40x10 --color none assets/torus.obj
wait_for '40x20px' >/dev/null
"$Z" --print --color none --size 40x10 assets/torus.obj | sed 's/[[:space:]]*$//' >"$T/print"
picture 10 >"$T/p10"
check "--size 40x10: the picture is the --print picture of that size" 'cmp -s "$T/p10" "$T/print"' "$(diff "$T/p10" "$T/print" | head -5)"
check "--size 40x10: nothing drawn below it" '[ -z "$(sed -n 11,29p "$T/screen" | tr -d " \n")" ]' "$(sed -n 11,29p "$T/screen")"
check "--size 40x10: the status bar on the last line" 'status 30 | grep -q "40x20px"' "$(status 30)"
# a window smaller than --size: the picture shrinks to the window
"$Z" --print --color none --size 30x7 assets/torus.obj | sed 's/[[:space:]]*$//' >"$T/print"
tm resize-window -t zv -x 30 -y 8
i=0
while [ $i -lt 200 ]; do
    cap
    picture 7 | cmp -s - "$T/print" && break
    sleep 0.05
    i=$((i + 1))
done
picture 7 >"$T/p7"
check "--size bigger than the window: the window's size" 'cmp -s "$T/p7" "$T/print"' "$(diff "$T/p7" "$T/print" | head -5)"

# ==== colours: 24-bit when asked, --print's palette numbers otherwise ====
# run_in COLS ROWS ENV...: zview with extra environment (TERM included)
# typed into a fresh pane; its arguments follow in $ARGS
run_in() {
    cols=$1; rows=$2; shift 2
    session xterm-256color "$cols" "$rows"
    rm -f "$T/pid"
    tm send-keys -t zv "$* sh -c 'echo \$\$ >$T/pid; exec $Z $ARGS'; echo zv-exit=\$?" Enter
}
ARGS="assets/knot.obj"
run_in 100 30 TERM=xterm-256color COLORTERM=truecolor
wait_for 'faces [0-9]+ drawn' >/dev/null
check "COLORTERM=truecolor on xterm-256color: 24-bit escapes" 'tm capture-pane -p -e -t zv | grep -q "38;2;[0-9]*;[0-9]*;[0-9]*m"' "$(tm capture-pane -p -e -t zv | head -c 300 | od -c | head -5)"
check "the status bar says 24bit" 'status 30 | grep -q "half lambert 24bit"' "$(status 30)"
if need_python "24-bit: the screen equals --print --color truecolor"; then
    print_looks --color truecolor --size 100x29 assets/knot.obj >"$T/print"
    wait_looks 29 "$T/print"
    check "24-bit: the screen equals --print --color truecolor" 'cmp -s "$T/looks" "$T/print"' "$(diff "$T/looks" "$T/print" | head -5)"
fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

ARGS="--color truecolor assets/knot.obj"
run_in 100 30 TERM=xterm-256color COLORTERM=
wait_for 'faces [0-9]+ drawn' >/dev/null
check "--color truecolor without COLORTERM: 24-bit escapes" 'tm capture-pane -p -e -t zv | grep -q "38;2;"'
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

# TERM=xterm describes 8 colours: a grey cube stays grey (black and white dithered)
ARGS="assets/cube.obj"
run_in 100 30 TERM=xterm
wait_for 'faces 6 drawn' >/dev/null
check "TERM=xterm: the status bar says 8" 'status 30 | grep -q "half lambert 8 "' "$(status 30)"
if need_python "8 colours: black and white only, the screen equal to --print --color 8"; then
    tm capture-pane -p -e -N -t zv | head -n 29 | python3 tests/e2e/looks.py --colours >"$T/colours"
    check "8 colours: a grey model is drawn in black and white only" '[ "$(cat "$T/colours")" = "0 7 B" ]' "colours: $(cat "$T/colours")"
    print_looks --color 8 --size 100x29 assets/cube.obj >"$T/print"
    wait_looks 29 "$T/print"
    check "8 colours: the screen equals --print --color 8" 'cmp -s "$T/looks" "$T/print"' "$(diff "$T/looks" "$T/print" | head -5)"
fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

ARGS="--color 16 assets/knot.obj"
run_in 100 30 TERM=xterm-256color
wait_for 'faces [0-9]+ drawn' >/dev/null
check "--color 16: the status bar says 16" 'status 30 | grep -q "half lambert 16 "' "$(status 30)"
if need_python "16 colours: the screen equals --print --color 16"; then
    print_looks --color 16 --size 100x29 assets/knot.obj >"$T/print"
    wait_looks 29 "$T/print"
    check "16 colours: the screen equals --print --color 16" 'cmp -s "$T/looks" "$T/print"' "$(diff "$T/looks" "$T/print" | head -5)"
fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

ARGS="--color none assets/cube.obj"
run_in 100 30 TERM=xterm-256color
wait_for 'faces 6 drawn' >/dev/null
check "--color none: the status bar says mono" 'status 30 | grep -q "half lambert mono "' "$(status 30)"
check "--color none: no colour escapes" '! tm capture-pane -p -e -t zv | head -n 29 | grep -q "\[[0-9;]*[34][0-9]"'
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

# ==== keys: views, light, outlines, samples, shading ====
# key_equals NAME KEY NOTE PRINT-ARGS: the key's note shows, and the
# picture is then what --print draws with PRINT-ARGS
key_equals() {
    tm send-keys -t zv "$2"
    if ! wait_for "$3"; then
        notok "$1" "no note '$3': $(status 30)"
        return
    fi
    need_python "$1" || return
    # shellcheck disable=SC2086
    print_looks --color 256 --size 100x29 $4 >"$T/print"
    wait_looks 29 "$T/print"
    check "$1" 'cmp -s "$T/looks" "$T/print"' "$(diff "$T/looks" "$T/print" | head -3)"
}
start 100 30 assets/knot.obj
wait_for 'faces [0-9]+ drawn' >/dev/null
key_equals "1 is the front view" 1 "view front" "--view front assets/knot.obj"
key_equals "4 is the right view" 4 "view right" "--view right assets/knot.obj"
key_equals "7 is the iso view" 7 "view iso" "--view iso assets/knot.obj"
key_equals "8 is the automatic view" 8 "view auto" "assets/knot.obj"
key_equals "] turns the light right" ']' "light -19,37" "--light -19,37 assets/knot.obj"
key_equals "{ raises the light" '{' "light -19,52" "--light -19,52 assets/knot.obj"
key_equals "e draws outlines" e "edges on" "--edges --light -19,52 assets/knot.obj"
key_equals "S takes 9 samples" S "samples 9" "--samples 9 --edges --light -19,52 assets/knot.obj"
tm send-keys -t zv e
wait_for "edges off" >/dev/null
tm send-keys -t zv v
if wait_for "half smooth 256"; then ok "v goes on to smooth shading"; else notok "v goes on to smooth shading" "$(status 30)"; fi

# ==== the view's command line: shown on C, printed by --print-view ====
# the command shown gives the picture back
tm send-keys -t zv 3
wait_for 'view left' >/dev/null
tm send-keys -t zv J
wait_gone 'view left' >/dev/null
wait_stable
if command -v python3 >/dev/null 2>&1; then looks 29 >"$T/before"; fi
tm send-keys -t zv C
if wait_for 'command line of this view'; then ok "C shows the command line"; else notok "C shows the command line" "$(cat "$T/screen")"; fi
# the box's lines, frame stripped, continuation lines joined
sed -n 's/^ *| \(.*\) *| *$/\1/p' "$T/screen" | sed 's/[[:space:]]*$//' | sed -n '/^zview /,$p' |
    sed -e ':a' -e '/ \\$/{N; s/ \\\n/ /; ba' -e '}' >"$T/cmd"
check "the command is one line starting with zview" '[ "$(wc -l <"$T/cmd")" -eq 1 ] && grep -q "^zview assets/knot.obj --yaw " "$T/cmd"' "$(cat "$T/cmd")"
check "the command has the view's settings" 'grep -q -- "--shade smooth" "$T/cmd" && grep -q -- "--samples 9" "$T/cmd" && grep -q -- "--light -19,52" "$T/cmd"' "$(cat "$T/cmd")"
if need_python "the command shown gives the same picture"; then
    sh -c "$(sed "s|^zview|\"$Z\" --print --size 100x29 --color 256|" "$T/cmd")" | python3 tests/e2e/looks.py >"$T/again"
    check "the command shown gives the same picture" 'cmp -s "$T/before" "$T/again"' "$(diff "$T/before" "$T/again" | head -3)"
fi
tm send-keys -t zv q
if wait_gone 'command line of this view' && ! grep -q 'zv-exit' "$T/screen"; then ok "a key closes the command line and does nothing else"; else
    notok "a key closes the command line and does nothing else" "$(cat "$T/screen")"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null

# --print-view: standard output is kept for the command line, the viewer draws on the terminal
session xterm-256color 100 30
tm send-keys -t zv "TERM=xterm-256color $Z --print-view assets/torus.obj >$T/pv; echo zv-exit=\$?" Enter
if wait_for 'faces [0-9]+ drawn'; then ok "--print-view with standard output in a file: the viewer shows"; else
    notok "--print-view with standard output in a file: the viewer shows" "$(cat "$T/screen")"; fi
tm send-keys -t zv 2 '['
wait_for 'light -49,37' >/dev/null
wait_stable
if command -v python3 >/dev/null 2>&1; then looks 29 >"$T/before"; fi
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null
check "--print-view prints one command line" '[ "$(wc -l <"$T/pv")" -eq 1 ] && grep -q "^zview assets/torus.obj --yaw 180 --pitch 0 .*--light -49,37" "$T/pv"' "$(cat "$T/pv")"
if need_python "--print-view's command gives the last picture back"; then
    sh -c "$(sed "s|^zview|\"$Z\" --print --size 100x29 --color 256|" "$T/pv")" | python3 tests/e2e/looks.py >"$T/again"
    check "--print-view's command gives the last picture back" 'cmp -s "$T/before" "$T/again"' "$(diff "$T/before" "$T/again" | head -3)"
fi

# ==== snapshots ====
mkdir -p "$T/snap" "$T/models"
cp assets/cube.obj "$T/models/cube.obj"
session xterm-256color 100 30
tm send-keys -t zv "cd $T/snap && TERM=xterm-256color $Z $T/models/cube.obj; echo zv-exit=\$?" Enter
wait_for 'faces 6 drawn' >/dev/null
tm send-keys -t zv P
if wait_for 'wrote zview-cube-001.png 800x464'; then ok "P: the status bar says what was written"; else notok "P: the status bar says what was written" "$(status 30)"; fi
check "P: the PNG and the text exist" '[ -s "$T/snap/zview-cube-001.png" ] && [ -s "$T/snap/zview-cube-001.txt" ]' "$(ls "$T/snap")"
if need_python "P: the PNG decodes, 8x16 pixels a cell"; then
    check "P: the PNG decodes, 8x16 pixels a cell" '[ "$(python3 tests/e2e/pngsize.py "$T/snap/zview-cube-001.png")" = "800 464" ]' "$(python3 tests/e2e/pngsize.py "$T/snap/zview-cube-001.png" 2>&1)"
fi
"$Z" --print --size 100x29 --color 256 "$T/models/cube.obj" >"$T/print"
check "P: the text is the bytes --print gives" 'cmp -s "$T/snap/zview-cube-001.txt" "$T/print"'
: >"$T/snap/zview-cube-003.txt"
tm send-keys -t zv P
wait_for 'wrote zview-cube-002' >/dev/null
tm send-keys -t zv P
if wait_for 'wrote zview-cube-004'; then ok "P: a number with either file taken is skipped"; else notok "P: a number with either file taken is skipped" "$(status 30)"; fi
check "P: nothing is overwritten" '[ ! -s "$T/snap/zview-cube-003.txt" ] && [ ! -e "$T/snap/zview-cube-003.png" ]' "$(ls -l "$T/snap")"
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null
# a folder where no file can be made (/proc, even for root): next to the model
tm send-keys -t zv "clear; cd /proc && TERM=xterm-256color $Z $T/models/cube.obj; echo zv-exit=\$?" Enter
wait_for 'faces 6 drawn' >/dev/null
tm send-keys -t zv P
if wait_for "wrote zview-cube-001.png 800x464, .txt in"; then ok "P in an unwritable folder: next to the model"; else notok "P in an unwritable folder: next to the model" "$(status 30)"; fi
check "P in an unwritable folder: both files next to the model" '[ -s "$T/models/zview-cube-001.png" ] && [ -s "$T/models/zview-cube-001.txt" ]' "$(ls "$T/models")"
tm send-keys -t zv q
wait_for 'zv-exit=0' >/dev/null
