#!/bin/sh
# What the check finds, on the model: --problems and --parts in --print
# and -o (nothing changes on a sound model; the hole of an open cube is
# drawn), --check --print (the picture, then the report), and in the
# viewer the ! key with the verdict in the status bar and the counts in
# the info panel; --watch reading a file renamed over the old one, a
# broken write leaving the last good model with the reason, and a FIFO
# or a device in the model's place passed over.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

# the unit cube, closed, outward; the same without its x = 0 side
cube() {
    printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n'
    printf 'f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n'
    [ "$1" = open ] || printf 'f 4 1 5 8\n'
}
cube >"$T/cube.obj"
cube open >"$T/open.obj"

# ==== one-shot ====
for o in "--print --size 60x20 --color 256" "-o $T/x.ppm --size 120x90"; do
    out=${o%% *}
    $Z $o --view left --yaw 20 --pitch 20 "$T/cube.obj" >"$T/plain" 2>&1
    [ "$out" = -o ] && cp "$T/x.ppm" "$T/plain"
    $Z $o --view left --yaw 20 --pitch 20 --problems "$T/cube.obj" >"$T/marked" 2>&1
    [ "$out" = -o ] && cp "$T/x.ppm" "$T/marked"
    check "$out --problems: a closed cube is drawn as without it" 'cmp -s "$T/plain" "$T/marked"' "the pictures differ"
    $Z $o --view left --yaw 20 --pitch 20 "$T/open.obj" >"$T/plain" 2>&1
    [ "$out" = -o ] && cp "$T/x.ppm" "$T/plain"
    $Z $o --view left --yaw 20 --pitch 20 --problems "$T/open.obj" >"$T/marked" 2>&1
    [ "$out" = -o ] && cp "$T/x.ppm" "$T/marked"
    check "$out --problems: the open cube's hole is drawn" '! cmp -s "$T/plain" "$T/marked"' "the pictures are the same"
done
# the hole's edges in red: pixels of (255, 48, 48) lit as lines are (unlit)
if need_python "-o --problems draws the boundary in its red"; then
    $Z -o "$T/x.ppm" --size 120x90 --contrast 0 --view left --yaw 20 --pitch 20 --problems "$T/open.obj"
    n=$(python3 -c "
d = open('$T/x.ppm', 'rb').read()
head = d.split(None, 4)            # P6 W H 255 pixels
px = head[4]
print(sum(1 for i in range(0, len(px) - 2, 3) if px[i:i + 3] == bytes((255, 48, 48))))")
    check "-o --problems draws the boundary in its red ($n pixels)" '[ "$n" -gt 20 ]' "$n red pixels"
fi
$Z --print --size 40x12 --color none --check --problems "$T/open.obj" >"$T/out" 2>"$T/err"
st=$?
check "--check --print --problems: exit status 3 for the hole" '[ $st -eq 3 ]' "status $st"
check "... the picture comes first, then the report" \
    'head -n 12 "$T/out" | grep -q "[▀▄█]" && sed -n 13p "$T/out" | grep -q "open.obj (obj)"' "$(head -c 400 "$T/out")"
$Z --print --size 40x12 --color 256 --parts "$T/cube.obj" assets/torus.obj >"$T/parts" 2>&1
$Z --print --size 40x12 --color 256 "$T/cube.obj" assets/torus.obj >"$T/plain" 2>&1
check "--parts colours the parts" '! cmp -s "$T/parts" "$T/plain"' "the same picture"

. "$(dirname "$0")/tmux.sh"

# ==== the viewer: ! and the verdict ====
start 100 30 --view left --yaw 20 --pitch 20 "$T/open.obj"
wait_for "faces 5 drawn" >/dev/null || notok "the viewer starts" "$(cat "$T/screen")"
check "no verdict before the key" '! status 30 | grep -q "hole"' "$(status 30)"
cap
picture 29 >"$T/before"
tm send-keys -t zv '!'
if wait_for '1 hole'; then ok "! checks the model: the status bar says 1 hole"; else notok "! checks the model: the status bar says 1 hole" "$(status 30)"; fi
if wait_change "$T/before" 29; then ok "... and the hole is drawn"; else notok "... and the hole is drawn" "the picture did not change"; fi
tm send-keys -t zv i
if wait_for 'edges: +4 boundary in 1 hole'; then ok "the info panel lists the counts"; else notok "the info panel lists the counts" "$(cat "$T/screen")"; fi
tm send-keys -t zv i
tm send-keys -t zv '!'
if wait_gone '1 hole'; then ok "! again: the verdict goes"; else notok "! again: the verdict goes" "$(status 30)"; fi
tm send-keys -t zv q
# the shell's prompt once zview has gone (keys typed before that are zview's)
wait_for 'zv-exit=[0-9]' >/dev/null && prompt_back >/dev/null || notok "the viewer quits" "$(tail -3 "$T/screen")"

# ==== a long verdict in a narrow window gives way by whole problems ====
# an open cube (a hole), a triangle listed both ways (non-manifold,
# flipped) and once more (a duplicate), a face with a repeated corner:
# more problems than 50 columns hold
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nv 3 0 0\nv 4 0 0\nv 3 1 0\n' >"$T/many-problems.obj"
printf 'f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 4 8 7 3\nf 9 10 11\nf 9 11 10\nf 9 10 11\nf 1 1 2\n' >>"$T/many-problems.obj"
start 50 20 --problems "$T/many-problems.obj"
wait_for 'hole' >/dev/null
bar=$(status 20)
check "50 columns: the verdict names what fits and counts the rest" 'echo "$bar" | grep -Eq "[0-9]+ (hole|holes|non-manifold)( · [0-9]+ [a-z -]+)* · \+[0-9]+ \| \?( help)?$"' "$bar"
check "... the help key stays at the end" 'echo "$bar" | grep -Eq "\| \?( help)?$"' "$bar"
tm resize-window -t zv -x 34 -y 20
i=0
while [ $i -lt 100 ]; do cap; status 20 | grep -q 'hole' || break; sleep 0.05; i=$((i + 1)); done
bar=$(status 20)
check "34 columns: the verdict is a count or gone, never cut mid-word; ? stays" 'echo "$bar" | grep -Eq "(\| [0-9]+ problems )?\| \?( help)?$" && ! echo "$bar" | grep -q "hole"' "$bar"
tm send-keys -t zv q
wait_for 'zv-exit=[0-9]' >/dev/null

# ==== --watch ====
cp "$T/open.obj" "$T/w.obj"
start 100 30 --watch --problems --view left --yaw 20 --pitch 20 "$T/w.obj"
if wait_for '1 hole'; then ok "--problems: the verdict from the start"; else notok "--problems: the verdict from the start" "$(status 30)"; fi
# an exporter's way: a new file renamed over the old one
cube >"$T/w.new"
mv "$T/w.new" "$T/w.obj"
if wait_for 'faces 6 drawn' && wait_for 'watertight'; then ok "--watch reads a file renamed over the old one, and checks it again"; else
    notok "--watch reads a file renamed over the old one, and checks it again" "$(status 30)"; fi
# a broken write: the last good model stays, and the bar says why
printf 'v 0 0 0\nv 1 0 0\nf 1 2 9\n' >"$T/w.obj"
if wait_for 'kept the last good model: w.obj:3: vertex index 9'; then ok "a broken file: the bar says why"; else notok "a broken file: the bar says why" "$(status 30)"; fi
check "... and the last good model stays" 'status 30 | grep -Eq "faces 6 drawn| 6/6 "' "$(status 30)"
# written in place again, whole
cube open >"$T/w.obj"
if wait_for 'faces 5 drawn' && wait_for '1 hole'; then ok "--watch reads a file written in place"; else
    notok "--watch reads a file written in place" "$(status 30)"; fi
# issue 28: a FIFO in the model's place waited for a writer for ever, and
# the changes after it waited behind it until Esc. Now it is passed over
# with a note, never opened; keys still work, and the next file is read.
rm -f "$T/w.obj"
mkfifo "$T/w.obj"
if wait_for 'w\.obj: not a regular file \(a FIFO\); still watching'; then ok "--watch: a FIFO in the model's place is passed over with a note"; else
    notok "--watch: a FIFO in the model's place is passed over with a note" "$(status 30)"; fi
tm send-keys -t zv g
if wait_for '\| scanline '; then ok "... and the viewer takes keys"; else notok "... and the viewer takes keys" "$(status 30)"; fi
cube >"$T/w.new"
mv "$T/w.new" "$T/w.obj"
if wait_for 'faces 6 drawn' && wait_for 'watertight'; then ok "... and the file renamed over it is read"; else
    notok "... and the file renamed over it is read" "$(status 30)"; fi
# a link to a device: looked at, never opened (a device can do things on open)
ln -s /dev/zero "$T/w.new"
mv "$T/w.new" "$T/w.obj"
if wait_for 'w\.obj: not a regular file \(a character device\)'; then ok "--watch: a link to /dev/zero is passed over with a note"; else
    notok "--watch: a link to /dev/zero is passed over with a note" "$(status 30)"; fi
check "... and the last model stays" 'status 30 | grep -Eq "faces 6 drawn| 6/6 "' "$(status 30)"
cube open >"$T/w.new"
mv "$T/w.new" "$T/w.obj"
if wait_for 'faces 5 drawn'; then ok "... and the file after it is read"; else notok "... and the file after it is read" "$(status 30)"; fi
tm send-keys -t zv q
# the shell's prompt once zview has gone (keys typed before that are zview's)
wait_for 'zv-exit=[0-9]' >/dev/null && prompt_back >/dev/null || notok "the viewer quits" "$(tail -3 "$T/screen")"

# the view stays: a turned camera, the same file written again
cp assets/torus.obj "$T/t.obj"
start 100 30 --watch --view front "$T/t.obj" assets/cube.obj
wait_for "faces [0-9]+ drawn" >/dev/null || notok "the viewer starts" "$(cat "$T/screen")"
tm send-keys -t zv h h K w
wait_stable
picture 29 >"$T/turned"
cp assets/torus.obj "$T/t.new"
mv "$T/t.new" "$T/t.obj"
if wait_for 'read t\.obj again'; then ok "--watch says it read the file again"; else notok "--watch says it read the file again" "$(status 30)"; fi
wait_stable
check "... and the camera and the layout stay as they were" 'picture 29 | cmp -s - "$T/turned"' "the picture moved"
tm send-keys -t zv q
# the shell's prompt once zview has gone (keys typed before that are zview's)
wait_for 'zv-exit=[0-9]' >/dev/null && prompt_back >/dev/null || notok "the viewer quits" "$(tail -3 "$T/screen")"
