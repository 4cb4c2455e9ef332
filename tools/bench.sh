#!/bin/sh
# make bench: the targets of issue 21, one row each with its goal, then
# (unless SKIP_FULL=1) the full table on the bundled assets and, when
# present, ../shared/models: 240x120 and 1920x1080, two threads, the
# deep scene. Frame rows are medians over VIEWS views of zview --bench
# after a first frame; cpu_ms is the process's CPU time per frame, which
# a shared machine's other jobs do not inflate as they do the wall
# clock. Single-thread rows run pinned to one core (PIN below). The 5.2M
# and 31M models are written by tools/subdiv (the dragon subdivided once,
# then again) into a temporary folder, deleted at the end; SKIP_31M=1
# leaves the 31M model out (1.4 GB of disk, about a minute to write).
# The memory row renders MEM_FRAMES frames (10,000) through
# tools/memframes.c; the load rows come from tools/bench-load.sh.
set -u
ZV=${ZVIEW:-./zview}
SUBDIV=${SUBDIV:-build/subdiv}
MEMFRAMES=${MEMFRAMES:-build/memframes}
MEM_FRAMES=${MEM_FRAMES:-10000}
S=../shared/models
VIEWS=${VIEWS:-8}
HERE=$(dirname "$0")
TMP=$(mktemp -d "${TMPDIR:-/tmp}/zview-bench-XXXXXX")
trap 'rm -rf "$TMP"' EXIT
trap 'exit 1' HUP INT PIPE TERM
models="assets/torus.obj assets/knot.obj assets/demo.obj"
big=""
if [ -d "$S" ]; then
    for m in stanford-bunny.obj armadillo.obj nefertiti.obj buddha-100k.obj scene-overlap.obj dragon.obj; do
        [ -f "$S/$m" ] && big="$big $S/$m"
    done
fi
sh "$HERE/stamp.sh" "make bench (tools/bench.sh), VIEWS=$VIEWS views"

# Single-thread runs are pinned to one core (BENCH_CPU, default 0), as
# the figures of one thread should be; PIN= turns that off.
PIN=${PIN-taskset -c ${BENCH_CPU:-0}}
command -v taskset >/dev/null 2>&1 || PIN=
pinned() {
    case " $* " in
    *" --threads 1 "*) $PIN "$@" ;;
    *) "$@" ;;
    esac
}

# One row of --bench --json as "frame_ms cpu_ms proj_ms hsr_ms shade_ms first_ms ready_ms".
row() {
    pinned "$ZV" --bench --json --views "$VIEWS" "$@" | awk '
        { for (i = 1; i <= NF; i++) { k = $i; gsub(/[":,{}]/, "", k); v = $(i + 1); gsub(/[",}]/, "", v); f[k] = v } }
        END { printf "%s %s %s %s %s %s %s\n", f["frame_median_ms"], f["cpu_median_ms"], f["project_median_ms"],
              f["median_ms"], f["shade_median_ms"], f["first_frame_ms"], f["ready_ms"] }'
}

# target NAME GOAL ARGS...: a frame row of the targets table.
target() {
    name=$1 goal=$2
    shift 2
    # shellcheck disable=SC2046
    set -- $(row "$@")
    printf "%-46s %9s %9s %8s %8s %8s   %s\n" "$name" "${1:--}" "${2:--}" "${3:--}" "${4:--}" "${5:--}" "$goal"
    LAST_FIRST=${6:--} LAST_READY=${7:--}
}

# other NAME VALUE GOAL: a row measured otherwise (in the frame_ms column).
other() {
    printf "%-46s %9s %9s %8s %8s %8s   %s\n" "$1" "$2" "" "" "" "" "$3"
}

D=$S/dragon.obj
if [ -f "$D" ]; then
    # the big models, once for every row that needs them
    m5=$TMP/dragon-5m.obj m31=$TMP/dragon-31m.obj
    if [ ! -x "$SUBDIV" ] || ! "$SUBDIV" "$D" "$m5" >/dev/null 2>&1; then
        rm -f "$m5"
    fi
    if [ "${SKIP_31M:-0}" != 1 ] && [ -s "$m5" ]; then
        "$SUBDIV" "$m5" "$m31" >/dev/null 2>&1 || rm -f "$m31"
    fi

    echo
    echo "## issue 21 targets (frames: projection + hidden surfaces + shading, zbuffer; medians of $VIEWS views, ms)"
    printf "%-46s %9s %9s %8s %8s %8s   %s\n" "case" "frame_ms" "cpu_ms" "proj" "hsr" "shade" "target"
    target "dragon 160x96, 1 sample, 1 thread" "<= 2.5" --threads 1 --size 160x96 --samples 1 --algo zbuffer "$D"
    # issue 32: the viewer at 160x48 cells (160x96 pixels, 4 samples)
    # while the cut slides: each view's plane is another (bench.c), so
    # every frame cuts the dragon again; 20 frames a second is 50 ms
    target "dragon 160x96, 4 samples, cut sliding, 1 thread" "<= 50" --threads 1 --size 160x96 --samples 4 --algo zbuffer --section z=0 "$D"
    for m in "$m5:5.2M" "$m31:31M"; do
        f=${m%:*} n=${m##*:}
        goal="<= 10"
        [ "$n" = 31M ] && goal="<= 60"
        if [ -s "$f" ]; then
            target "$n triangles 160x96, 4 samples, 2 threads" "$goal" --threads 2 --size 160x96 --samples 4 --algo zbuffer "$f"
        elif [ "$n" = 31M ] && [ "${SKIP_31M:-0}" = 1 ]; then
            other "$n triangles 160x96, 4 samples, 2 threads" "(SKIP_31M)" "$goal"
        else
            other "$n triangles 160x96, 4 samples, 2 threads" "(no model)" "$goal: $SUBDIV could not write it"
        fi
    done
    [ -f "$S/stanford-bunny.obj" ] &&
        target "bunny 1920x1080, 1 thread" "<= 5" --threads 1 --size 1920x1080 --samples 1 --algo zbuffer "$S/stanford-bunny.obj"
    target "dragon 1920x1080, 1 thread" "<= 35" --threads 1 --size 1920x1080 --samples 1 --algo zbuffer "$D"
    # two threads against one (tools/bench-threads.sh, same columns)
    ZVIEW="$ZV" VIEWS=$VIEWS MODEL="$D" PIN="$PIN" sh "$HERE/bench-threads.sh"

    # the first picture against wc -l and the bytes a triangle keeps
    # resident: tools/bench-load.sh's table, on the same big models
    BIG_DIR=$TMP ZVIEW="$ZV" SUBDIV="$SUBDIV" sh "$HERE/bench-load.sh" >"$TMP/load.txt" 2>&1
    for n in dragon-5m dragon-31m; do
        awk -v n="$n" '$1 == n && $2 == "after" && $3 == 2 {
            printf "%-46s %9s %9s %8s %8s %8s   %s\n", n ": first picture / wc -l, 2 threads", $6 "x", "", "", "", "", "<= 8x (" $5 " s against " $4 " s)"
            printf "%-46s %9s %9s %8s %8s %8s   %s\n", n ": bytes per triangle resident", $9, "", "", "", "", "<= 32 (max RSS " $8 " MB)" }' "$TMP/load.txt"
    done

    # memory over frames: the viewer's default algorithm and the one
    # with structures of its own, two threads, the view turning
    if [ -x "$MEMFRAMES" ]; then
        for a in zbuffer hzb-octree; do
            "$MEMFRAMES" --views "$MEM_FRAMES" --size 160x96 --samples 1 --threads 2 --algo "$a" "$D" | awk -v a="$a" -v n="$MEM_FRAMES" 'NR == 2 {
                printf "%-46s %9s %9s %8s %8s %8s   %s\n", "RSS KB grown, frames 100-" n ", " a, $9, "", "", "", "",
                    "0 (RSS " $6 " -> " $7 " MB; heap " $10 " -> " $11 " MB, " $12 " B grown after frame 1000)" }'
        done
    else
        other "memory over $MEM_FRAMES frames" "(no tool)" "0: $MEMFRAMES is not built (make bench builds it)"
    fi

    # --diff of the dragon and of the 5.2M model against edited copies
    # (tools/bench-diff.sh, same columns)
    BIG_DIR=$TMP HEADER=0 RUNS=${DIFF_RUNS:-3} ZVIEW="$ZV" SUBDIV="$SUBDIV" PERTURB="${PERTURB:-build/perturb}" \
        sh "$HERE/bench-diff.sh"

    # zview --repair of the dragon (one thread, pinned) and of the 5.2M
    # model (two), writing included, and their peaks against loading
    # alone (tools/bench-repair-cli.sh, same columns)
    BIG_DIR=$TMP HEADER=0 RUNS=${REPAIR_RUNS:-3} ZVIEW="$ZV" SUBDIV="$SUBDIV" CHECKBENCH="${CHECKBENCH:-build/checkbench}" \
        sh "$HERE/bench-repair-cli.sh"

    # ==== HOOK (preview21): the preview's time to its first partial picture ====
    # tools/bench-preview.sh, when present, prints its own rows of this
    # table (same columns) for the models in BIG_DIR.
    if [ -f "$HERE/bench-preview.sh" ]; then
        BIG_DIR=$TMP ZVIEW="$ZV" SUBDIV="$SUBDIV" sh "$HERE/bench-preview.sh"
    else
        other "preview: time to the first partial picture" "(absent)" "tools/bench-preview.sh not written yet"
    fi

    echo
    echo "## switching to hzb-octree on the dragon (160x96, 4 samples as in the viewer): the first frame, and when its trees are in use"
    for t in 2 1; do
        target "hzb-octree, $t thread(s)" "no freeze" --threads "$t" --size 160x96 --samples 4 --algo hzb-octree "$D" >/dev/null
        printf "%-46s first frame %8.1f ms, trees ready after %8.1f ms\n" "hzb-octree, $t thread(s)" "$LAST_FIRST" "$LAST_READY"
    done

    echo
    echo "## the load rows above in full (tools/bench-load.sh)"
    grep -v '^# commit' "$TMP/load.txt"
fi
echo
echo "# load $(cut -d' ' -f1-3 /proc/loadavg) after the targets"
[ "${SKIP_FULL:-0}" = 1 ] && exit 0

for size in 240x120 1920x1080; do
    echo
    echo "## $size, 1 thread"
    # shellcheck disable=SC2086
    $PIN "$ZV" --bench --algo all --threads 1 --views "$VIEWS" --size "$size" $models $big
done
if [ -f "$D" ]; then
    echo
    echo "## threads: dragon 1920x1080, 1 and 2 threads"
    $PIN "$ZV" --bench --algo all --threads 1 --views "$VIEWS" --size 1920x1080 "$D"
    "$ZV" --bench --algo all --threads 2 --views "$VIEWS" --size 1920x1080 "$D" | tail -n +2
fi
grid_model=assets/torus.obj
[ -f "$S/bunny-5k.obj" ] && grid_model=$S/bunny-5k.obj
echo
echo "## deep scene: 5 x 5 x 5 copies of $(basename "$grid_model"), 1 thread"
$PIN "$ZV" --bench --grid 5 --algo all --threads 1 --views "$VIEWS" --size 1920x1080 "$grid_model"
echo
echo "# load $(cut -d' ' -f1-3 /proc/loadavg) at the end"
