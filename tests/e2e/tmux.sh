# Shared by the tmux tests of the viewer (sourced after lib.sh): a shell
# runs in a detached pane of a fixed size, zview is typed into it, keys
# are sent, and the pane's text is polled (capture-pane) until a
# condition holds or a bounded timeout passes. Each session has its own
# server socket, killed on exit even when a check fails.
Z=$ZVIEW

if ! command -v tmux >/dev/null 2>&1; then
    skip "every check of the viewer under tmux" "no tmux"
    exit 0
fi

export LC_ALL=C.UTF-8 LANG=C.UTF-8
# One server socket per started session: a new server never races the
# old one's shutdown. The trap kills every one of them.
n=0
SOCK=zv-$$-0
tm() { tmux -L "$SOCK" -f /dev/null "$@"; }
cleanup() {
    k=0
    while [ $k -le $n ]; do
        tmux -L "zv-$$-$k" -f /dev/null kill-server >/dev/null 2>&1
        # tmux leaves its socket file behind
        rm -f "${TMUX_TMPDIR:-/tmp}/tmux-$(id -u)/zv-$$-$k"
        k=$((k + 1))
    done
    rm -rf "$T"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

# session TERM COLS ROWS: a fresh server with a shell in a COLS x ROWS pane
session() {
    tm kill-server >/dev/null 2>&1
    n=$((n + 1))
    SOCK=zv-$$-$n
    tm new-session -d -s zv -x "$2" -y "$3" -c "$ROOT" \
        -e TERM="$1" -e LANG=C.UTF-8 -e LC_ALL=C.UTF-8 -e NO_COLOR= -e COLORTERM= -e COLORFGBG= sh
    tm set-option -t zv remain-on-exit on >/dev/null
}

# start COLS ROWS ARGS...: zview ARGS typed into a fresh pane (tmux sets
# the pane's TERM itself, so the command sets it again). zview writes its
# pid to $T/pid; after it exits the shell prints zv-exit=STATUS.
start() {
    cols=$1; rows=$2; shift 2
    session xterm-256color "$cols" "$rows"
    rm -f "$T/pid"
    tm send-keys -t zv "TERM=xterm-256color sh -c 'echo \$\$ >$T/pid; exec $Z $*'; echo zv-exit=\$?" Enter
}

# prompt_back: the shell reads commands again after zview left
prompt_back() {
    tm send-keys -t zv "echo back-in-\$((40 + 2))" Enter
    wait_for '^back-in-42$'
}

# cap: the pane's text, trailing blanks dropped (by tmux itself: -N
# would keep them; a sed after it cost a third of a poll's processes)
cap() { tm capture-pane -p -t zv >"$T/screen"; }
# pause: the pause between two polls of a wait, counted in $i in steps
# of 0.05 s: 0.05 s for the first second, then 0.2 s. Most waits end at
# the first or second poll; the long ones (a big file loading) wait
# seconds, and polling them every 0.05 s cost a process or three each
# time for nothing. A wait's bound stays WAIT_POLLS steps of 0.05 s.
pause() {
    if [ "$i" -lt 20 ]; then
        sleep 0.05
        i=$((i + 1))
    else
        sleep 0.2
        i=$((i + 4))
    fi
}
# wait_for EXTENDED-REGEX: poll the pane (up to about 10 s: WAIT_POLLS
# steps of 0.05 s, pause) until it matches
wait_for() {
    i=0
    while [ $i -lt "${WAIT_POLLS:-200}" ]; do
        cap
        grep -Eq -- "$1" "$T/screen" && return 0
        pause
    done
    return 1
}
# picture ROWS: the first ROWS lines of the last capture (above the status bar)
picture() { head -n "$1" "$T/screen"; }
status() { sed -n "$1p" "$T/screen"; }
# wait_change FILE ROWS: poll until the picture differs from FILE
wait_change() {
    i=0
    while [ $i -lt "${WAIT_POLLS:-200}" ]; do
        cap
        picture "$2" | cmp -s - "$1" || return 0
        pause
    done
    return 1
}
# wait_stable: poll until two captures 0.1 s apart agree (a frame can be
# caught half written)
wait_stable() {
    cap
    cp "$T/screen" "$T/prev"
    i=0
    while [ $i -lt 100 ]; do
        sleep 0.1
        cap
        cmp -s "$T/screen" "$T/prev" && return 0
        cp "$T/screen" "$T/prev"
        i=$((i + 1))
    done
    return 1
}
# wait_gone EXTENDED-REGEX: poll until the pane no longer matches
wait_gone() {
    i=0
    while [ $i -lt "${WAIT_POLLS:-200}" ]; do
        cap
        grep -Eq -- "$1" "$T/screen" || return 0
        pause
    done
    return 1
}
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }
# looks ROWS: what the first ROWS rows of the pane look like, colours
# included (looks.py: a half block of a on b is one of b on a); the
# checks that use it start with need_python (lib.sh)
looks() { tm capture-pane -p -e -N -t zv | head -n "$1" | python3 tests/e2e/looks.py; }
# print_looks ARGS...: the same for a --print frame
print_looks() { "$Z" --print "$@" | python3 tests/e2e/looks.py; }
# wait_looks ROWS FILE: poll until the pane's looks equal FILE (in
# $T/looks, the last looks read); looks.py reads a capture only when it
# differs from the last one read (each python costs ten captures)
wait_looks() {
    i=0
    : >"$T/looks.cap"
    while [ $i -lt "${WAIT_POLLS:-200}" ]; do
        tm capture-pane -p -e -N -t zv | head -n "$1" >"$T/looks.new"
        if ! cmp -s "$T/looks.new" "$T/looks.cap"; then
            mv "$T/looks.new" "$T/looks.cap"
            python3 tests/e2e/looks.py <"$T/looks.cap" >"$T/looks"
            cmp -s "$T/looks" "$2" && return 0
        fi
        pause
    done
    return 1
}
