#!/bin/sh
# zview as a file manager's previewer (issue 34): --preview WxH draws the
# model in W x (H-1) cells exactly as --print does, and the check's
# verdict on the last row, every row within W columns; a file it cannot
# read says why on standard output (all a file manager shows) in at most
# H rows, status 1; no terminal is opened. Then the recipes of
# doc/previewers.md, run in real lf and fzf (Debian packages, tools/deps.sh)
# under tmux: the pane shows the verdict.
. "$(dirname "$0")/lib.sh"
. "$(dirname "$0")/tmux.sh"

# widest FILE: the widest line's columns, colours left out
widest() { sed 's/\x1b\[[0-9;]*m//g' "$1" | LC_ALL=C.UTF-8 wc -L; }

expect_status "--preview 60x20 on the knot" 0 "$Z" --preview 60x20 assets/knot.obj
if [ "$(wc -l <"$T/out")" -eq 20 ]; then ok "... 20 rows"; else notok "... 20 rows" "$(wc -l <"$T/out")"; fi
head -n 19 "$T/out" >"$T/pic"
"$Z" -p -s 60x19 assets/knot.obj >"$T/print"
if cmp -s "$T/pic" "$T/print"; then ok "... the first 19 the picture --print -s 60x19 gives"; else notok "... the first 19 the picture --print -s 60x19 gives"; fi
faces=$("$Z" --check assets/knot.obj | awk '$1 == "faces" { print $2; exit }' | tr -d ,)
last=$(tail -n 1 "$T/out")
if [ -n "$faces" ] && [ "$last" = "watertight, $faces faces" ]; then ok "... the last the verdict and --check's faces ($last)"
else notok "... the last the verdict and --check's faces" "'$last', --check: $faces"; fi
if [ "$(widest "$T/out")" -le 60 ]; then ok "... every row within 60 columns"; else notok "... every row within 60 columns" "$(widest "$T/out")"; fi

# a model with problems, the row narrow: whole items only
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf 1 2 3\nf 1 2 4\nf 5 6 7\nf 5 7 6\n' >"$T/bad.obj"
"$Z" --check "$T/bad.obj" >"$T/check"
"$Z" --preview 60x8 "$T/bad.obj" >"$T/wide"
"$Z" --preview 12x8 "$T/bad.obj" >"$T/narrow"
wide=$(tail -n 1 "$T/wide")
narrow=$(tail -n 1 "$T/narrow")
# the items --check names (its problems line), each in the verdict
items=$(sed -n 's/^  problems *//p' "$T/check" | sed 's/ ([^)]*)//g; s/ face\(s\)\{0,1\}//g')
if [ -n "$items" ] && [ "$wide" = "$items, 4 faces" ]; then ok "a model with problems: the verdict names --check's ($wide)"
else notok "a model with problems: the verdict names --check's" "'$wide', --check: '$items'"; fi
n=$(echo "$items" | awk -F', ' '{ print NF }')
first=${items%%,*}
if [ "$narrow" = "$first, +$((n - 1))" ] && [ "$(printf %s "$narrow" | LC_ALL=C.UTF-8 wc -m)" -le 12 ]; then
    ok "... in 12 columns the first named, the rest counted ($narrow)"
else notok "... in 12 columns the first named, the rest counted" "'$narrow' of '$wide'"; fi

# what is not a model: why, on standard output, in the pane
# (a name longer than the pane: broken mid-word, at the pane's edge)
long=$T/notes-about-the-part-written-by-hand.txt
echo "not a model" >"$long"
expect_status "a text file is refused" 1 "$Z" --preview 30x4 "$long"
if tr -d '\n' <"$T/out" | grep -qF "$long" && [ ! -s "$T/err" ] && [ "$(wc -l <"$T/out")" -le 4 ] && [ "$(widest "$T/out")" -le 30 ]; then
    ok "... why on standard output, in 4 rows of 30 columns"
else notok "... why on standard output, in 4 rows of 30 columns" "$(cat "$T/out" "$T/err")"; fi
expect_status "two files are a usage error" 2 "$Z" --preview 30x4 assets/cube.obj assets/knot.obj
expect_status "--preview with --check is a usage error" 2 "$Z" --preview 30x4 --check assets/cube.obj
if command -v strace >/dev/null 2>&1; then
    strace -f -qq -e trace=open,openat -o "$T/trace" "$Z" --preview 30x8 assets/cube.obj >/dev/null 2>&1
    if grep -q '/dev/tty\|/dev/pts' "$T/trace"; then notok "no terminal is opened" "$(grep 'tty\|pts' "$T/trace" | head -3)"
    else ok "no terminal is opened"; fi
else skip "no terminal is opened" "no strace (tools/deps.sh)"; fi

# ==== the recipes, in the real programs ====
mkdir -p "$T/models" "$T/cfg/lf"
cp assets/knot.obj "$T/models/"
if command -v fzf >/dev/null 2>&1; then
    session xterm-256color 100 30
    tm send-keys -t zv "echo $T/models/knot.obj | fzf --preview '$Z --preview \${FZF_PREVIEW_COLUMNS}x\${FZF_PREVIEW_LINES} {}'" Enter
    if wait_for 'watertight, [0-9]+ faces'; then ok "fzf --preview (doc/previewers.md): the verdict in its pane"
    else notok "fzf --preview (doc/previewers.md): the verdict in its pane" "$(tail -5 "$T/screen")"; fi
    tm send-keys -t zv Escape
else skip "fzf --preview" "no fzf (tools/deps.sh)"; fi
if command -v lf >/dev/null 2>&1; then
    # the script of doc/previewers.md, zview named by its path
    sed -n '/^#!\/bin\/sh$/,/^esac$/p' doc/previewers.md | sed "s|exec zview |exec $Z |" >"$T/cfg/lf/preview"
    chmod +x "$T/cfg/lf/preview"
    echo "set previewer $T/cfg/lf/preview" >"$T/cfg/lf/lfrc"
    session xterm-256color 120 30
    tm send-keys -t zv "XDG_CONFIG_HOME=$T/cfg lf $T/models" Enter
    if wait_for 'watertight, [0-9]+ faces'; then ok "lf's previewer (doc/previewers.md): the verdict in its pane"
    else notok "lf's previewer (doc/previewers.md): the verdict in its pane" "$(tail -5 "$T/screen")"; fi
    tm send-keys -t zv q
else skip "lf's previewer" "no lf (tools/deps.sh)"; fi
