#!/bin/sh
# make bench-order: how the hierarchical z-buffer depends on the order the
# polygons reach it (--order; the picture is the same under every order).
# For the simple (hzb: the pyramid) and the complete (hzb-octree: pyramid
# and object-space octree) mode, on the dragon and on the deep scene
# (5 x 5 x 5 copies of a bunny), prints a markdown table: the share of
# the polygons given to the algorithm that the pyramid culls, and the
# median time of the hidden-surface step (ms, one thread). Compare rows
# of one run only.
set -u
ZV=${ZVIEW:-./zview}
S=../shared/models
VIEWS=${VIEWS:-8}
SIZE=${SIZE:-1920x1080}

sh "$(dirname "$0")/stamp.sh" "make bench-order (tools/bench-order.sh), VIEWS=$VIEWS views at $SIZE"

# "culled_pct hsr_median_ms" of one --bench --json run
cell() {
    "$ZV" --bench --json --views "$VIEWS" --threads 1 --size "$SIZE" "$@" | awk '
        { for (i = 1; i <= NF; i++) { k = $i; gsub(/[":,{}]/, "", k); v = $(i + 1); gsub(/[",}]/, "", v); f[k] = v } }
        END { printf "%s %s\n", f["culled_pct"], f["median_ms"] }'
}

scene() {
    name=$1
    shift
    for order in file front-to-back back-to-front shuffle; do
        set -- "$@"
        a=$(cell --algo hzb --order "$order" "$@")
        b=$(cell --algo hzb-octree --order "$order" "$@")
        # shellcheck disable=SC2086
        printf "| %s | %s | %s%% | %s | %s%% | %s |\n" "$name" "$order" ${a% *} ${a#* } ${b% *} ${b#* }
    done
}

echo "# $SIZE, $VIEWS views, 1 thread; load $(cut -d' ' -f1-3 /proc/loadavg) at the start"
echo
echo "| scene | --order | hzb culled | hzb ms | hzb-octree culled | hzb-octree ms |"
echo "|---|---|---|---|---|---|"
dragon=$S/dragon.obj
[ -f "$dragon" ] || dragon=assets/knot.obj
grid_model=$S/bunny-5k.obj
[ -f "$grid_model" ] || grid_model=assets/torus.obj
scene "$(basename "$dragon" .obj)" "$dragon"
scene "deep: $(basename "$grid_model" .obj) x125" --grid 5 "$grid_model"
