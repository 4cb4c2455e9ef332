#!/bin/sh
# make bench-preview: the picture while a big OBJ loads (issue 21). The
# viewer runs in a tmux pane on the dragon subdivided twice (31M
# triangles, written by tools/subdiv into a temporary folder, deleted at
# the end unless KEEP=1; MODEL=path uses that file instead); the pane is
# polled (capture-pane) and each row is the wall-clock median of RUNS
# runs:
#   first picture   start to the first partial picture (the vertices
#                   parsed so far as points: "loading" and a count > 0)
#   first faces     start to the first picture of faces while loading
#   whole model     start to the whole model drawn (no longer loading)
#   ? while loading key to the help box shown, and ? again to it gone
#   h while loading key to a turned picture
#   q while loading key to the shell's prompt
# and, for comparison, the whole model with --print-view (which loads
# before the viewer starts, as every load did before issue 21).
# Latencies include tmux's own (send-keys, a capture: a few ms), so
# they are upper bounds. The rows are wall clock and depend on the
# machine being quiet. Called by make bench (tools/bench.sh) with
# BIG_DIR, the folder where it wrote dragon-31m.obj: that model, and
# rows in bench.sh's table (name, figure, the target) instead.
set -u
ZV=$(cd "$(dirname "${ZVIEW:-./zview}")" && pwd)/$(basename "${ZVIEW:-./zview}")
SUBDIV=${SUBDIV:-build/subdiv}
RUNS=${RUNS:-3}
KEYS=${KEYS:-5}
command -v tmux >/dev/null 2>&1 || { echo "bench-preview: no tmux"; exit 0; }
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-preview-XXXXXX")
SOCK=zv-bench-preview-$$
tm() { tmux -L "$SOCK" -f /dev/null "$@"; }
[ "${KEEP:-0}" = 1 ] || trap 'tm kill-server >/dev/null 2>&1; rm -rf "$TMP"' EXIT INT TERM
exec 2>/dev/null    # tmux's words on a server gone (after q) are not results
M=${MODEL:-}
[ -n "${BIG_DIR:-}" ] && [ -z "$M" ] && M=$BIG_DIR/dragon-31m.obj
[ -n "${BIG_DIR:-}" ] && [ ! -f "$M" ] && { echo "bench-preview: $M is missing"; exit 0; }
[ -n "${BIG_DIR:-}" ] || sh "$(dirname "$0")/stamp.sh" "make bench-preview (tools/bench-preview.sh), RUNS=$RUNS"

if [ -z "$M" ]; then
    D=../shared/models/dragon.obj
    [ -f "$D" ] || D=/work/shared/models/dragon.obj
    if [ ! -f "$D" ] || [ ! -x "$SUBDIV" ]; then
        echo "bench-preview: the dragon or $SUBDIV is missing"
        exit 0
    fi
    "$SUBDIV" "$D" "$TMP/d5m.obj" >/dev/null && "$SUBDIV" "$TMP/d5m.obj" "$TMP/dragon-31m.obj" >/dev/null || exit 1
    rm -f "$TMP/d5m.obj"
    M=$TMP/dragon-31m.obj
fi
cat "$M" >/dev/null     # from the page cache, as the runs read it

ms() { echo $(( ($(date +%s%N) - T0) / 1000000 )); }
bar() { tm capture-pane -p -t zv | sed -n '30p'; }
screen() { tm capture-pane -p -t zv; }
median() { sort -n | awk '{ a[NR] = $1 } END { print NR ? a[int((NR + 1) / 2)] : "-" }'; }

# until CMD: poll (capture after capture) until CMD succeeds; fails
# after 120 s, or at once when the pane is gone
until_ok() {
    t_end=$(( $(date +%s) + 120 ))
    while ! eval "$1" 2>/dev/null; do
        tm has-session -t zv 2>/dev/null || return 1
        [ "$(date +%s)" -gt $t_end ] && return 1
    done
    return 0
}

start() {
    tm kill-server >/dev/null 2>&1
    tm new-session -d -s zv -x 100 -y 30 -e TERM=xterm-256color sh
    tm send-keys -t zv "clear; echo ready" Enter
    until_ok 'screen | grep -q "^ready"'
    T0=$(date +%s%N)
    tm send-keys -t zv "exec $ZV $* $M" Enter
}

loading() { bar | grep -q loading; }
shows() { bar | grep -Eq "loading" && bar | grep -Eq "(faces [1-9]|points [1-9])"; }
faces_loading() { b=$(bar); echo "$b" | grep -q loading && echo "$b" | grep -Eq "faces [1-9]"; }
whole() { b=$(bar); ! echo "$b" | grep -q loading && echo "$b" | grep -Eq "faces [1-9]"; }

: >"$TMP/first"; : >"$TMP/faces"; : >"$TMP/whole"; : >"$TMP/old"
: >"$TMP/help"; : >"$TMP/unhelp"; : >"$TMP/turn"; : >"$TMP/quit"
r=0
while [ $r -lt "$RUNS" ]; do
    r=$((r + 1))
    start
    until_ok shows && ms >>"$TMP/first"
    k=0
    while [ $k -lt "$KEYS" ] && loading; do
        k=$((k + 1))
        T0=$(date +%s%N); tm send-keys -t zv '?'
        until_ok 'screen | grep -q "zview keys"' && ms >>"$TMP/help"
        T0=$(date +%s%N); tm send-keys -t zv '?'
        until_ok '! screen | grep -q "zview keys"' && ms >>"$TMP/unhelp"
        screen | head -n 29 >"$TMP/pic"
        T0=$(date +%s%N); tm send-keys -t zv h
        until_ok '! screen | head -n 29 | cmp -s - "$TMP/pic"' && ms >>"$TMP/turn"
    done
    tm kill-server >/dev/null 2>&1
    # undisturbed: the faces, then the whole
    start
    until_ok faces_loading && ms >>"$TMP/faces"
    until_ok whole && ms >>"$TMP/whole"
    # q mid-load
    start
    until_ok shows
    T0=$(date +%s%N); tm send-keys -t zv q
    until_ok '! tm has-session -t zv 2>/dev/null || ! tm list-panes -t zv -F "#{pane_current_command}" 2>/dev/null | grep -q zview' && ms >>"$TMP/quit"
    tm kill-server >/dev/null 2>&1
    # before issue 21: loaded before the viewer starts
    start --print-view
    until_ok whole && ms >>"$TMP/old"
    tm kill-server >/dev/null 2>&1
done

worst=$(cat "$TMP/help" "$TMP/unhelp" "$TMP/turn" | sort -n | tail -1)
if [ -n "${BIG_DIR:-}" ]; then
    # bench.sh's table: name, figure, four empty columns, the target
    row() { printf "%-46s %9s %9s %8s %8s %8s   %s\n" "$1" "$2" "" "" "" "" "$3"; }
    b=$(basename "$M" .obj)
    row "$b: viewer, first partial picture ms" "$(median <"$TMP/first")" "<= 500 ms (points; faces at $(median <"$TMP/faces") ms)"
    row "$b: viewer, key while loading, worst ms" "${worst:--}" "<= 50 ms (medians: ? $(median <"$TMP/help"), h $(median <"$TMP/turn"), q $(median <"$TMP/quit"))"
    row "$b: viewer, whole model ms" "$(median <"$TMP/whole")" "(loaded before the viewer: $(median <"$TMP/old") ms)"
    exit 0
fi
n=$(grep -c '^f ' "$M" 2>/dev/null || echo "?")
echo "model: $(basename "$M"), $(du -m "$M" | cut -f1) MB, $n faces; 100x30 pane; medians of $RUNS runs (ms)"
printf '%-34s %8s\n' "first picture (points)" "$(median <"$TMP/first")"
printf '%-34s %8s\n' "first faces while loading" "$(median <"$TMP/faces")"
printf '%-34s %8s\n' "whole model" "$(median <"$TMP/whole")"
printf '%-34s %8s\n' "whole model, loaded before the UI" "$(median <"$TMP/old")"
printf '%-34s %8s  (%s keys)\n' "? to help shown, while loading" "$(median <"$TMP/help")" "$(wc -l <"$TMP/help")"
printf '%-34s %8s\n' "? to help gone, while loading" "$(median <"$TMP/unhelp")"
printf '%-34s %8s\n' "h to a turned picture, loading" "$(median <"$TMP/turn")"
printf '%-34s %8s\n' "q to the viewer gone, loading" "$(median <"$TMP/quit")"
printf '%-34s %8s\n' "worst key (help, turn)" "${worst:--}"
