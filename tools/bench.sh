#!/bin/sh
# make bench: the benchmark table on the bundled assets and, when present,
# on ../shared/models, at 240x120 (a big terminal) and 1920x1080, single
# thread; then the two-thread speed-up and the deep-scene (grid) case.
# Medians of 8 views after a warm-up frame; compare rows of one run only.
set -u
ZV=${ZVIEW:-./zview}
S=../shared/models
VIEWS=${VIEWS:-8}
models="assets/torus.obj assets/knot.obj assets/demo.obj"
big=""
if [ -d "$S" ]; then
    for m in stanford-bunny.obj armadillo.obj nefertiti.obj buddha-100k.obj scene-overlap.obj dragon.obj; do
        [ -f "$S/$m" ] && big="$big $S/$m"
    done
fi
echo "# machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
for size in 240x120 1920x1080; do
    echo
    echo "## $size, 1 thread"
    # shellcheck disable=SC2086
    "$ZV" --bench --algo all --threads 1 --views "$VIEWS" --size "$size" $models $big
done
if [ -f "$S/dragon.obj" ]; then
    echo
    echo "## threads: dragon 1920x1080, 1 and 2 threads"
    "$ZV" --bench --algo all --threads 1 --views "$VIEWS" --size 1920x1080 "$S/dragon.obj"
    "$ZV" --bench --algo all --threads 2 --views "$VIEWS" --size 1920x1080 "$S/dragon.obj" | tail -n +2
fi
grid_model=assets/torus.obj
[ -f "$S/bunny-5k.obj" ] && grid_model=$S/bunny-5k.obj
echo
echo "## deep scene: 5 x 5 x 5 copies of $(basename "$grid_model"), 1 thread"
"$ZV" --bench --grid 5 --algo all --threads 1 --views "$VIEWS" --size 1920x1080 "$grid_model"
