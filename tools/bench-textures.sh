#!/bin/sh
# make bench-textures: the texture targets of issue 18. tools/uvmodel
# writes textured copies of the dragon and the bunny (a texture
# coordinate per vertex, a 2048 x 2048 PNG repeated 4 times across);
# each is timed textured and with --no-textures (the same file and
# geometry, faces in one colour each), medians over VIEWS views on one
# core. Then the texels' memory as --info reports it, and a 16k x 16k
# image: how long one picture takes with it (JPEG, decoded at a quarter
# of its size; PNG, halved as its rows are decoded), against the viewer, which
# draws its first picture before decoding such an image. TABLE_ONLY=1
# stops after the textured-against-untextured table.
set -u
ZV=${ZVIEW:-./zview}
UVMODEL=${UVMODEL:-build/uvmodel}
S=../shared/models
VIEWS=${VIEWS:-8}
TMP=${TMPDIR:-/tmp}/zview-bench-textures
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
mkdir -p "$TMP"
sh "$(dirname "$0")/stamp.sh" "make bench-textures (tools/bench-textures.sh), VIEWS=$VIEWS views"

# frame and shade medians (ms) of --bench --json
row() {
    $PIN "$ZV" --bench --json --views "$VIEWS" --threads 1 --algo zbuffer "$@" | awk '
        { for (i = 1; i <= NF; i++) { k = $i; gsub(/[":,{}]/, "", k); v = $(i + 1); gsub(/[",}]/, "", v); f[k] = v } }
        END { printf "%s %s\n", f["frame_median_ms"], f["shade_median_ms"] }'
}

# case NAME TARGET FILE ARGS...: textured against not
case_row() {
    name=$1 goal=$2 file=$3
    shift 3
    set -- $(row "$@" "$file") $(row "$@" --no-textures "$file")
    awk -v n="$name" -v g="$goal" -v tf="$1" -v ts="$2" -v uf="$3" -v us="$4" 'BEGIN {
        printf "| %s | %.2f | %.2f | %.2f | %.2f | %.2fx, %+.2f ms | %s |\n", n, tf, ts, uf, us, tf / uf, tf - uf, g }'
}

for m in dragon stanford-bunny; do
    [ -f "$S/$m.obj" ] || { echo "$S/$m.obj: not there"; exit 1; }
    [ -s "$TMP/$m-uv.obj" ] || "$UVMODEL" "$S/$m.obj" "$TMP/$m-uv.obj" "$TMP/$m-uv.png" 2048 || exit 1
done
echo
echo "| case (zbuffer, 1 thread, pinned; ms, medians of $VIEWS views) | frame | shade | frame untextured | shade untextured | textured / untextured | target |"
echo "|---|---:|---:|---:|---:|---:|---|"
case_row "dragon 160x96, 4 samples" "<= 1.25x" "$TMP/dragon-uv.obj" --size 160x96 --samples 4
case_row "bunny 1920x1080, 1 sample" "<= +2 ms (issue 35)" "$TMP/stanford-bunny-uv.obj" --size 1920x1080 --samples 1
# TABLE_ONLY=1: the two rows above and nothing more (bench-speed.sh)
[ "${TABLE_ONLY:-0}" = 1 ] && exit 0
# Instructions (callgrind, no timing noise: the machine's cores are
# shared) in shade_frame, textured and not, over a --views 2 run:
# CALLGRIND=0 leaves them out. --no-sandbox: under valgrind the loading
# child cannot install its filter, the load fails and nothing is counted.
icount() {
    valgrind --tool=callgrind --callgrind-out-file="$TMP/cg.out" --toggle-collect=shade_frame \
        "$ZV" --no-sandbox --bench --views 2 --threads 1 --algo zbuffer "$@" >/dev/null 2>&1 &&
        callgrind_annotate "$TMP/cg.out" 2>/dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); printf "%.1fM", $1 / 1e6 }'
}
if [ "${CALLGRIND:-1}" != 0 ] && command -v valgrind >/dev/null 2>&1; then
    echo
    echo "| case: instructions in shade_frame (callgrind, --views 2) | textured | untextured |"
    echo "|---|---:|---:|"
    echo "| dragon 160x96, 4 samples | $(icount --size 160x96 --samples 4 "$TMP/dragon-uv.obj") | $(icount --size 160x96 --samples 4 --no-textures "$TMP/dragon-uv.obj") |"
    echo "| bunny 1920x1080, 1 sample | $(icount --size 1920x1080 --samples 1 "$TMP/stanford-bunny-uv.obj") | $(icount --size 1920x1080 --samples 1 --no-textures "$TMP/stanford-bunny-uv.obj") |"
fi
echo
echo "Texture memory (zview --info):"
"$ZV" --info "$TMP/dragon-uv.obj" | grep -A1 '^textures:'

echo
echo "A 16k x 16k image on the torus: one picture (--print 80x24, wall s), and --info's account of it"
[ -s "$TMP/torus16k.obj" ] || "$UVMODEL" assets/torus.obj "$TMP/torus16k.obj" "$TMP/big16k.jpg" 16384 || exit 1
[ -s "$TMP/torus16kpng.obj" ] || { "$UVMODEL" assets/torus.obj "$TMP/torus16kpng.obj" "$TMP/big16k.png" 16384 &&
    sed 's/big16k.jpg/big16k.png/' "$TMP/torus16k.mtl" > "$TMP/torus16kpng.mtl"; } || exit 1
for f in torus16k torus16kpng; do
    t0=$(date +%s.%N)
    "$ZV" --print --size 80x24 --color none "$TMP/$f.obj" >/dev/null || exit 1
    t1=$(date +%s.%N)
    "$ZV" --info "$TMP/$f.obj" | grep -A1 '^textures:' | tail -1 | sed 's/^ */    /'
    awk -v a="$t0" -v b="$t1" -v f="$f" 'BEGIN { printf "    %s: one picture in %.2f s\n", f, b - a }'
done
echo "The viewer (images longer than 2048 a side decode on a thread of their own): first picture"
tmux kill-session -t zvbt 2>/dev/null
for f in torus16k torus16kpng; do
    t0=$(date +%s.%N)
    tmux new-session -d -s zvbt -x 100 -y 30 "$ZV $TMP/$f.obj" || { echo "no tmux"; break; }
    until tmux capture-pane -p -t zvbt 2>/dev/null | grep -q 'faces'; do sleep 0.02; done
    t1=$(date +%s.%N)
    until ! tmux capture-pane -p -t zvbt | grep -q 'decoding textures'; do sleep 0.05; done
    t2=$(date +%s.%N)
    tmux kill-session -t zvbt
    awk -v a="$t0" -v b="$t1" -v c="$t2" -v f="$f" \
        'BEGIN { printf "    %s: first picture after %.2f s, textured after %.2f s\n", f, b - a, c - a }'
done
