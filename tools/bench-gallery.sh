#!/bin/sh
# make bench-gallery: zview DIR's first screen (issue 34). A folder of
# COUNT (100) copies of the shared bunny (stanford-bunny.obj, 69k
# triangles, 2.4 MB; MODEL=path another file) is written to a temporary
# folder (deleted at the end); the grid runs in a 100 x 30 tmux pane
# (4 tiles across, 3 rows showing: 12 tiles), the pane is polled
# (capture-pane, one after another) and each row is the wall-clock
# median of RUNS runs from the command typed:
#   first screen    every tile on the screen has its picture (none
#                   shows "..." or "loading")
#   first verdicts  ... and its verdict (none says "checking")
#   all checked     the status line says COUNT/COUNT loaded
# and the same folder's contact sheet (--gallery -o) for comparison.
# Latencies include tmux's own and the shell's start (a few ms): upper
# bounds, on a quiet machine. FIRST_ONLY=1: the first screen's rows only.
set -u
ZV=$(cd "$(dirname "${ZVIEW:-./zview}")" && pwd)/$(basename "${ZVIEW:-./zview}")
RUNS=${RUNS:-3}
COUNT=${COUNT:-100}
command -v tmux >/dev/null 2>&1 || { echo "bench-gallery: no tmux"; exit 0; }
M=${MODEL:-../shared/models/stanford-bunny.obj}
[ -f "$M" ] || M=/work/shared/models/stanford-bunny.obj
[ -f "$M" ] || { echo "bench-gallery: no model ($M)"; exit 0; }
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-gallery-XXXXXX")
SOCK=zv-bench-gallery-$$
tm() { tmux -L "$SOCK" -f /dev/null "$@"; }
trap 'tm kill-server >/dev/null 2>&1; rm -rf "$TMP"' EXIT INT TERM
exec 2>/dev/null
sh "$(dirname "$0")/stamp.sh" "make bench-gallery (tools/bench-gallery.sh), RUNS=$RUNS COUNT=$COUNT"
mkdir "$TMP/d"
i=1
while [ $i -le "$COUNT" ]; do
    cp "$M" "$TMP/d/model$(printf %04d $i).obj"
    i=$((i + 1))
done
cat "$TMP"/d/* >/dev/null     # from the page cache, as the runs read them

ms() { echo $(( ($(date +%s%N) - T0) / 1000000 )); }
screen() { tm capture-pane -p -t zv; }
median() { sort -n | awk '{ a[NR] = $1 } END { print NR ? a[int((NR + 1) / 2)] : "-" }'; }
until_ok() {
    t_end=$(( $(date +%s) + 300 ))
    while ! eval "$1" 2>/dev/null; do
        tm has-session -t zv 2>/dev/null || return 1
        [ "$(date +%s)" -gt $t_end ] && return 1
    done
    return 0
}
# the grid is up (the status line) and no tile waits for its picture
pictured() { s=$(screen); echo "$s" | grep -q "loaded ·" && ! echo "$s" | grep -Eq '\.\.\.|loading'; }
verdicts() { s=$(screen); pictured && ! echo "$s" | grep -q "checking"; }
all() { screen | grep -q " $COUNT/$COUNT loaded"; }

: >"$TMP/first"; : >"$TMP/verdicts"; : >"$TMP/all"; : >"$TMP/sheet"
r=0
while [ $r -lt "$RUNS" ]; do
    tm kill-server >/dev/null 2>&1
    tm new-session -d -s zv -x 100 -y 30 -e TERM=xterm-256color sh
    tm send-keys -t zv "clear; echo ready" Enter
    until_ok 'screen | grep -q "^ready"'
    T0=$(date +%s%N)
    tm send-keys -t zv "exec $ZV $TMP/d" Enter
    until_ok pictured && ms >>"$TMP/first"
    until_ok verdicts && ms >>"$TMP/verdicts"
    if [ "${FIRST_ONLY:-0}" != 1 ]; then
        until_ok all && ms >>"$TMP/all"
        tm send-keys -t zv q
        T0=$(date +%s%N)
        "$ZV" --gallery "$TMP/d" -o "$TMP/sheet.png" >/dev/null && ms >>"$TMP/sheet"
    fi
    r=$((r + 1))
done
printf '%-34s %8s ms   (target 1000 ms)\n' "first screen (12 tiles) pictured" "$(median <"$TMP/first")"
printf '%-34s %8s ms\n' "first screen's verdicts" "$(median <"$TMP/verdicts")"
[ "${FIRST_ONLY:-0}" = 1 ] && exit 0
printf '%-34s %8s ms\n' "all $COUNT checked" "$(median <"$TMP/all")"
printf '%-34s %8s ms\n' "contact sheet of $COUNT (-o)" "$(median <"$TMP/sheet")"
