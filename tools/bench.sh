#!/bin/sh
# make bench: first the targets of issue 10 (whole frames: projection,
# hidden surfaces and shading), then the full table on the bundled assets
# and, when present, ../shared/models, at 240x120 and 1920x1080, the
# two-thread speed-up and the deep scene. Medians over VIEWS views after a
# first frame (first_ms: choosing the algorithm, its structures included);
# cpu_ms is the process's CPU time per frame, which a shared machine's
# other jobs do not inflate as they do the wall clock. Compare rows of one
# run only. Single-thread rows run pinned to one core (see PIN below).
# SKIP_FULL=1 stops after the targets.
set -u
ZV=${ZVIEW:-./zview}
SUBDIV=${SUBDIV:-build/subdiv}
S=../shared/models
VIEWS=${VIEWS:-8}
TMP=${TMPDIR:-/tmp}/zview-bench
models="assets/torus.obj assets/knot.obj assets/demo.obj"
big=""
if [ -d "$S" ]; then
    for m in stanford-bunny.obj armadillo.obj nefertiti.obj buddha-100k.obj scene-overlap.obj dragon.obj; do
        [ -f "$S/$m" ] && big="$big $S/$m"
    done
fi
sh "$(dirname "$0")/stamp.sh" "make bench (tools/bench.sh), VIEWS=$VIEWS views"

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

# target NAME GOAL ARGS...: a line of the targets table.
target() {
    name=$1 goal=$2
    shift 2
    set -- $(row "$@")
    printf "%-44s %9s %9s %8s %8s %8s   %s\n" "$name" "$1" "$2" "$3" "$4" "$5" "$goal"
    LAST_FRAME=$1 LAST_FIRST=$6 LAST_READY=$7
}

if [ -f "$S/dragon.obj" ]; then
    D=$S/dragon.obj
    echo
    echo "## issue 10 targets (whole frame = projection + hidden surfaces + shading; medians, ms)"
    printf "%-44s %9s %9s %8s %8s %8s   %s\n" "case" "frame_ms" "cpu_ms" "proj" "hsr" "shade" "target"
    target "dragon 160x96, 1 sample, 1 thread" "<= 4" --threads 1 --size 160x96 --samples 1 --algo zbuffer "$D"
    target "dragon 160x96, 4 samples (320x192), 1 thread" "(report)" --threads 1 --size 160x96 --samples 4 --algo zbuffer "$D"
    big5m=$TMP/dragon-5m.obj
    if [ ! -s "$big5m" ] && [ -x "$SUBDIV" ]; then
        mkdir -p "$TMP" && "$SUBDIV" "$D" "$big5m" >/dev/null 2>&1 || rm -f "$big5m"
    fi
    if [ -s "$big5m" ]; then
        target "5.2M triangles 160x96, 2 threads" "<= 12" --threads 2 --size 160x96 --samples 1 --algo zbuffer "$big5m"
    else
        echo "5.2M triangles: $SUBDIV could not write $big5m"
    fi
    [ -f "$S/stanford-bunny.obj" ] &&
        target "bunny 1920x1080, zbuffer, 1 thread" "<= 7" --threads 1 --size 1920x1080 --algo zbuffer "$S/stanford-bunny.obj"
    target "dragon 1920x1080, zbuffer, 1 thread" "<= 50" --threads 1 --size 1920x1080 --algo zbuffer "$D"
    echo
    echo "## switching to hzb-octree on the dragon (160x96, 4 samples as in the viewer): the first frame, and when its trees are in use"
    for t in 2 1; do
        target "hzb-octree, $t thread(s)" "no freeze" --threads "$t" --size 160x96 --samples 4 --algo hzb-octree "$D" >/dev/null
        printf "%-44s first frame %8.1f ms, trees ready after %8.1f ms\n" "hzb-octree, $t thread(s)" "$LAST_FIRST" "$LAST_READY"
    done
    echo
    echo "## two threads against one (frame medians, ms; a speed-up needs two free cores)"
    for args in "--size 160x96 --samples 1" "--size 160x96 --samples 4" "--size 1920x1080 --samples 1"; do
        # shellcheck disable=SC2086
        one=$(row --threads 1 --algo zbuffer $args "$D" | cut -d' ' -f1)
        # shellcheck disable=SC2086
        two=$(row --threads 2 --algo zbuffer $args "$D" | cut -d' ' -f1)
        awk -v a="$args" -v o="$one" -v t="$two" 'BEGIN { printf "dragon %-36s 1 thread %8.2f  2 threads %8.2f  %.2fx (target >= 1.7x)\n", a, o, t, o / t }'
    done
fi
[ "${SKIP_FULL:-0}" = 1 ] && exit 0

for size in 240x120 1920x1080; do
    echo
    echo "## $size, 1 thread"
    # shellcheck disable=SC2086
    $PIN "$ZV" --bench --algo all --threads 1 --views "$VIEWS" --size "$size" $models $big
done
if [ -f "$S/dragon.obj" ]; then
    echo
    echo "## threads: dragon 1920x1080, 1 and 2 threads"
    $PIN "$ZV" --bench --algo all --threads 1 --views "$VIEWS" --size 1920x1080 "$S/dragon.obj"
    "$ZV" --bench --algo all --threads 2 --views "$VIEWS" --size 1920x1080 "$S/dragon.obj" | tail -n +2
fi
grid_model=assets/torus.obj
[ -f "$S/bunny-5k.obj" ] && grid_model=$S/bunny-5k.obj
echo
echo "## deep scene: 5 x 5 x 5 copies of $(basename "$grid_model"), 1 thread"
$PIN "$ZV" --bench --grid 5 --algo all --threads 1 --views "$VIEWS" --size 1920x1080 "$grid_model"
echo
echo "# load $(cut -d' ' -f1-3 /proc/loadavg) at the end"
