#!/bin/sh
# The point-cloud figures (make bench-points; README: Points and lines):
# a synthetic scan of POINTS points (default 10 million) sampled from the
# dragon's surface by area, coloured by normal, as a binary PLY: its load
# (--info's wall and CPU times, 5 runs; peak memory), then frames at the
# viewer's size for 160x48 cells in half blocks (160x94 pixels, 2x2
# samples each: 320x188 samples) for every algorithm, on two threads and
# one, and with bigger points. The machine is shared: read the CPU times.
Z=${ZVIEW:-./zview}
MK=${MKCLOUD:-build/mkcloud}
N=${POINTS:-10000000}
MODEL=${MODEL:-../shared/models/dragon.obj}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
[ -r "$MODEL" ] || { echo "bench-points: $MODEL not found" >&2; exit 1; }
sh "$(dirname "$0")/../tools/stamp.sh" "make bench-points (tests/bench_points.sh), POINTS=$N"
"$MK" "$MODEL" "$T/scan.ply" "$N" || exit 1
echo "== $(ls -l "$T/scan.ply" | awk '{ printf "%.1f MB", $5 / 1e6 }'), $N points"
echo "== load (--info), 5 runs"
for i in 1 2 3 4 5; do "$Z" --info "$T/scan.ply" | grep '^load:'; done
if [ -x /usr/bin/time ]; then
    /usr/bin/time -f "peak RSS of --info: %M KB" "$Z" --info "$T/scan.ply" >/dev/null
    /usr/bin/time -f "peak RSS of a 160x94 --print frame: %M KB" "$Z" --print --size 160x47 "$T/scan.ply" >/dev/null
fi
echo "== frames: 160x94 pixels, 4 samples (the viewer at 160x48 cells), 16 views"
"$Z" --bench --views 16 --size 160x94 --samples 4 --algo all "$T/scan.ply"
"$Z" --bench --views 16 --size 160x94 --samples 4 --algo zbuffer,hzb-octree --threads 1 "$T/scan.ply"
echo "== point size 3"
"$Z" --bench --views 16 --size 160x94 --samples 4 --point-size 3 --algo zbuffer "$T/scan.ply"
echo "== what a frame does (--info --algo zbuffer)"
"$Z" --info --algo zbuffer --size 320x188 "$T/scan.ply" | sed -n '/^render:/,$p'
