#!/bin/sh
# make bench-speed: the targets of issue 35, one row each with its goal,
# as a table for doc/benchmarks.md, then the tables the rows came from.
# The rows reuse the benchmarks that already measure them:
#   - the dragon, 5.2M and 31M models' --print against wc -l of the
#     cached file: tools/bench-load.sh (its two-thread rows);
#   - the sandbox's cost on the dragon's load: tools/bench-sandbox.sh
#     (--info's load, sandboxed against --no-sandbox, medians);
#   - the bunny's 1920x1080 textured frame against untextured:
#     tools/bench-textures.sh (TABLE_ONLY=1, CALLGRIND=0);
#   - --check of the 5.2M model on two threads, beyond loading, and its
#     peak against loading alone: tools/bench-check.sh (checkbench);
#   - two threads against one: tools/bench-threads.sh (as make bench).
# Measured here: the z-buffer's 1920x1080 frame against llvmpipe's on
# the same triangles (tools/glref.c; zview --bench --view front and glref
# draw the same views; one thread each, pinned to one core, compared on
# CPU time a frame, which other jobs on the machine stretch far less than
# the wall; then both on two threads, wall), and zview -o of the dragon,
# the whole process, against f3d --output under Xvfb (one Xvfb for every
# run, its start not counted against f3d).
# The 5.2M and 31M models are written by tools/subdiv into a temporary
# folder (deleted at the end); SKIP_31M=1 leaves the 31M model out (its
# row says so). ZVIEW, CHECKBENCH, SUBDIV may name another commit's
# builds (the "before" column); RUNS (default 3) runs a timed command,
# VIEWS (default 8) views a frame's median, SANDBOX_RUNS (default 11).
set -u
ZV=${ZVIEW:-./zview}
SUBDIV=${SUBDIV:-build/subdiv}
CHECKBENCH=${CHECKBENCH:-build/checkbench}
UVMODEL=${UVMODEL:-build/uvmodel}
GLREF=${GLREF:-build/glref}
RUNS=${RUNS:-3}
VIEWS=${VIEWS:-8}
S=../shared/models
HERE=$(dirname "$0")
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-speed-XXXXXX")
XPID=
cleanup() {
    [ -n "$XPID" ] && kill "$XPID" 2>/dev/null
    rm -rf "$TMP"
}
trap cleanup EXIT
trap 'exit 1' HUP INT PIPE TERM
sh "$HERE/stamp.sh" "make bench-speed (tools/bench-speed.sh), zview $ZV, RUNS=$RUNS VIEWS=$VIEWS"
# the commit of the zview measured, when it was built in a git tree
# other than this one (another commit's build, for a "before" column)
zc=$(git -C "$(dirname "$ZV")" rev-parse --short HEAD 2>/dev/null)
[ -n "$zc" ] && echo "# zview measured: $ZV, built at commit $zc"

D=$S/dragon.obj B=$S/stanford-bunny.obj
if [ ! -f "$D" ] || [ ! -f "$B" ]; then
    echo "bench-speed: $D and $B are needed (../shared/models)"
    exit 0
fi
: >"$TMP/rows"
# row NAME MEASURED GOAL DETAIL: a row of the table
row() { printf "| %s | %s | %s | %s |\n" "$1" "$2" "$3" "$4" >>"$TMP/rows"; }
median() { sort -n | awk '{ a[NR] = $1 } END { print NR ? a[int((NR + 1) / 2)] : "-" }'; }
# json KEY: KEY's value in zview --bench --json on stdin
json() { awk -v k="\"$1\":" '{ for (i = 1; i <= NF; i++) if ($i == k) { v = $(i + 1); gsub(/[",}]/, "", v); print v } }'; }

# the big models, once for every row that needs them
m5=$TMP/dragon-5m.obj m31=$TMP/dragon-31m.obj
"$SUBDIV" "$D" "$m5" >/dev/null 2>&1 || rm -f "$m5"
if [ "${SKIP_31M:-0}" != 1 ] && [ -s "$m5" ]; then
    "$SUBDIV" "$m5" "$m31" >/dev/null 2>&1 || rm -f "$m31"
fi

# 1-3: --print against wc -l (bench-load.sh, two threads)
BIG_DIR=$TMP RUNS=$RUNS ZVIEW="$ZV" SUBDIV="$SUBDIV" sh "$HERE/bench-load.sh" >"$TMP/load.txt" 2>&1
load_row() {
    name=$1 model=$2 goal=$3
    line=$(awk -v n="$model" '$1 == n && $2 == "after" && $3 == 2' "$TMP/load.txt")
    if [ -n "$line" ]; then
        # shellcheck disable=SC2086
        set -- $line
        row "$name" "$6x" "$goal" "$5 s against $4 s, 2 threads, wall medians of $RUNS"
    elif [ "$model" = dragon-31m ] && [ "${SKIP_31M:-0}" = 1 ]; then
        row "$name" "skipped" "$goal" "SKIP_31M=1"
    else
        row "$name" "-" "$goal" "not measured: no $model (subdiv) or no row from bench-load.sh"
    fi
}
load_row "dragon (33 MB OBJ), whole --print against wc -l" dragon "<= 12x"
load_row "5.2M triangles (214 MB OBJ), first picture against wc -l" dragon-5m "<= 10x"
load_row "31.4M triangles (1.37 GB OBJ), whole model against wc -l" dragon-31m "<= 12x"

# 4: the sandbox's cost (bench-sandbox.sh)
RUNS=${SANDBOX_RUNS:-11} ZVIEW="$ZV" MODEL="$D" sh "$HERE/bench-sandbox.sh" >"$TMP/sandbox.txt" 2>&1
sb=$(awk '/^load \(--info\):/ { print $NF }' "$TMP/sandbox.txt")
sbd=$(sed -n 's/^load (--info): *//p' "$TMP/sandbox.txt" | sed 's/: [-+0-9.]*%$//')
sbc=$(sed -n 's/^CPU a command: *//p' "$TMP/sandbox.txt")
row "the sandbox's cost on the dragon's load" "${sb:--}" "<= +3%" "${sbd:-no figure} (medians of ${SANDBOX_RUNS:-11}, pinned); CPU a command: ${sbc:--}"

# 5: textured against untextured (bench-textures.sh)
TABLE_ONLY=1 CALLGRIND=0 VIEWS=$VIEWS ZVIEW="$ZV" UVMODEL="$UVMODEL" sh "$HERE/bench-textures.sh" >"$TMP/tex.txt" 2>&1
tx=$(awk -F'|' '$2 ~ /bunny 1920x1080/ { print $7 }' "$TMP/tex.txt" | sed 's/^ *//; s/ *$//')
txd=$(awk -F'|' '$2 ~ /bunny 1920x1080/ { gsub(/ /, "", $3); gsub(/ /, "", $5); print $3 " ms against " $5 " ms" }' "$TMP/tex.txt")
row "bunny 1920x1080 textured frame against untextured" "$(echo "${tx:--}" | awk -F', ' 'NF == 2 { print $2 " (" $1 ")"; next } { print }')" \
    "<= +2 ms" "${txd:-no figure}, 1 thread pinned, medians of $VIEWS views"

# 6: --check of the 5.2M model on two threads (bench-check.sh's checkbench
# rows; it finds the model where it keeps it, under TMPDIR)
if [ -s "$m5" ]; then
    mkdir -p "$TMP/zview-bench"
    ln "$m5" "$TMP/zview-bench/dragon-5m.obj" 2>/dev/null || cp "$m5" "$TMP/zview-bench/dragon-5m.obj"
    TMPDIR=$TMP RUNS=$RUNS ZVIEW="$ZV" CHECKBENCH="$CHECKBENCH" SUBDIV="$SUBDIV" sh "$HERE/bench-check.sh" >"$TMP/check.txt" 2>&1
    rm -f "$TMP/zview-bench/dragon-5m.obj"
    alone=$(awk '/dragon-5m.obj/ && /loading alone/ { for (i = 1; i < NF; i++) if ($i == "peak") print $(i + 1) }' "$TMP/check.txt" | head -1)
    line=$(awk '/dragon-5m.obj/ && /threads 2/ && !/no crossings/' "$TMP/check.txt" | head -1)
    wall=$(echo "$line" | awk '{ for (i = 1; i < NF; i++) if ($i == "check") print $(i + 1) }')
    cpu=$(echo "$line" | awk '{ for (i = 1; i < NF; i++) if ($i == "cpu") print $(i + 1) }')
    peak=$(echo "$line" | awk '{ for (i = 1; i < NF; i++) if ($i == "peak") print $(i + 1) }')
    whole=$(awk '$1 == "dragon-5m.obj" && $3 == "--threads" && $4 == 2 { print $5 }' "$TMP/check.txt")
    if [ -n "$wall" ] && [ -n "$peak" ] && [ -n "$alone" ]; then
        row "--check of 5.2M triangles, two threads" \
            "$(awk -v w="$wall" -v p="$peak" -v a="$alone" 'BEGIN { printf "%.2f s, %.2fx memory", w / 1000, p / a }')" \
            "<= 2 s, <= 1.5x" "beyond loading, wall median of $RUNS (checkbench; CPU ${cpu:--} ms); peak $peak MB against $alone MB loading alone; the whole zview --check --threads 2: ${whole:--} s"
    else
        row "--check of 5.2M triangles, two threads" "-" "<= 2 s, <= 1.5x" "not measured: no row from bench-check.sh"
    fi
else
    row "--check of 5.2M triangles, two threads" "-" "<= 2 s, <= 1.5x" "not measured: $SUBDIV could not write the model"
fi

# 7: the z-buffer against llvmpipe on the same triangles and views
if [ -x "$GLREF" ] && LIBGL_ALWAYS_SOFTWARE=1 "$GLREF" --views 1 --size 16x16 "$S/tetrahedron.obj" >"$TMP/gl-probe" 2>&1; then
    : >"$TMP/gl.txt"
    for m in "$B" "$D"; do
        n=$(basename "$m" .obj)
        set -- --bench --json --views "$VIEWS" --algo zbuffer --view front --size 1920x1080 "$m"
        $PIN "$ZV" "$@" --threads 1 >"$TMP/z1"
        "$ZV" "$@" --threads 2 >"$TMP/z2"
        LIBGL_ALWAYS_SOFTWARE=1 LP_NUM_THREADS=1 $PIN "$GLREF" --views "$VIEWS" "$m" >"$TMP/g1"
        LIBGL_ALWAYS_SOFTWARE=1 LP_NUM_THREADS=2 "$GLREF" --views "$VIEWS" "$m" >"$TMP/g2"
        zc=$(json cpu_median_ms <"$TMP/z1") zf=$(json frame_median_ms <"$TMP/z1") z2=$(json frame_median_ms <"$TMP/z2")
        gc=$(awk '{ for (i = 1; i < NF; i++) if ($i == "cpu_ms") print $(i + 1) }' "$TMP/g1")
        gf=$(awk '{ for (i = 1; i < NF; i++) if ($i == "frame_ms") print $(i + 1) }' "$TMP/g1")
        g2=$(awk '{ for (i = 1; i < NF; i++) if ($i == "frame_ms") print $(i + 1) }' "$TMP/g2")
        { echo "zview 1 thread: $(tr -d '\n' <"$TMP/z1")"; echo "zview 2 threads: $(tr -d '\n' <"$TMP/z2")"
          echo "glref 1 thread: $(cat "$TMP/g1")"; echo "glref 2 threads: $(cat "$TMP/g2")"; } >>"$TMP/gl.txt"
        row "1080p z-buffer frame against llvmpipe, $n" \
            "$(awk -v a="$zc" -v b="$gc" 'BEGIN { printf "%.3f", (b > 0 ? a / b : 0) }')" "<= 0.18" \
            "CPU a frame, 1 thread pinned: $zc ms against $gc ms (wall $zf against $gf); 2 threads, wall: $z2 against $g2 ms ($(awk -v a="$z2" -v b="$g2" 'BEGIN { printf "%.3f", (b > 0 ? a / b : 0) }'))"
    done
    renderer=$(sed -n 's/^renderer "\([^"]*\)".*/\1/p' "$TMP/g1")
else
    row "1080p z-buffer frame against llvmpipe" "-" "<= 0.18" "not measured: $GLREF: $(head -1 "$TMP/gl-probe" 2>/dev/null)"
    renderer=
fi

# 8: two threads against one (bench-threads.sh)
MD=1 VIEWS=$VIEWS ZVIEW="$ZV" MODEL="$D" PIN="$PIN" sh "$HERE/bench-threads.sh" >>"$TMP/rows"

# 9: zview -o of the dragon against f3d --output under Xvfb
if command -v f3d >/dev/null 2>&1 && command -v Xvfb >/dev/null 2>&1; then
    Xvfb -displayfd 9 -screen 0 1280x1024x24 -nolisten tcp 9>"$TMP/display" >/dev/null 2>&1 &
    XPID=$!
    i=0
    while [ ! -s "$TMP/display" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    disp=$(cat "$TMP/display")
    # one NAME CMD...: RUNS runs, "wall cpu" a line (s; CPU of the waited tree)
    one() {
        name=$1
        shift
        for i in $(seq "$RUNS"); do
            t0=$(date +%s%N)
            /usr/bin/time -f "%U %S" -o "$TMP/t" "$@" >/dev/null 2>&1 || echo "failed: $*" >>"$TMP/f3d.err"
            t1=$(date +%s%N)
            awk -v w="$(( (t1 - t0) / 1000000 ))" '{ printf "%.3f %.2f\n", w / 1000, $1 + $2 }' "$TMP/t"
        done >"$TMP/$name.runs"
    }
    if [ -n "$disp" ]; then
        one zview "$ZV" -o "$TMP/z.png" --size 800x600 "$D"
        one f3d env DISPLAY=":$disp" f3d --output "$TMP/f.png" --resolution 800,600 "$D"
        zw=$(cut -d' ' -f1 "$TMP/zview.runs" | median) fw=$(cut -d' ' -f1 "$TMP/f3d.runs" | median)
        zc=$(cut -d' ' -f2 "$TMP/zview.runs" | median) fc=$(cut -d' ' -f2 "$TMP/f3d.runs" | median)
        if [ -s "$TMP/f3d.err" ]; then
            row "-o out.png of the dragon against f3d --output" "-" ">= 10x faster" "not measured: $(head -1 "$TMP/f3d.err")"
        else
            row "-o out.png of the dragon against f3d --output" \
                "$(awk -v a="$zw" -v b="$fw" 'BEGIN { printf "%.1fx faster", (a > 0 ? b / a : 0) }')" ">= 10x faster" \
                "800x600, wall medians of $RUNS: $zw s against $fw s (f3d under Xvfb started once); CPU $zc s against $fc s"
        fi
    else
        row "-o out.png of the dragon against f3d --output" "-" ">= 10x faster" "not measured: Xvfb did not start"
    fi
    kill "$XPID" 2>/dev/null
    wait "$XPID" 2>/dev/null
    XPID=
else
    row "-o out.png of the dragon against f3d --output" "-" ">= 10x faster" "not measured: f3d or Xvfb is not installed (tools/deps.sh)"
fi

echo
echo "## issue 35 targets ($ZV; load $(cut -d' ' -f1-3 /proc/loadavg) at the end)"
echo
echo "| target | measured | goal | how |"
echo "|---|---:|---|---|"
cat "$TMP/rows"
[ -n "$renderer" ] && echo && echo "llvmpipe: $renderer; its frame: clear, draw, glReadPixels of the colour, glFinish"
for f in load sandbox tex check gl; do
    [ -s "$TMP/$f.txt" ] || continue
    echo
    echo "## from $f"
    grep -v '^# commit' "$TMP/$f.txt"
done
