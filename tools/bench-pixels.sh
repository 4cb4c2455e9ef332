#!/bin/sh
# make bench-pixels: the bytes one picture costs on the wire in each of
# the terminal's pixel protocols (issue 23), against the half-block text
# of the same view, at 100x30 cells (10x20-pixel cells: 1000x600 pixels)
# and 200x60; and how long a link of --max-rate-like speeds takes to
# carry each (the viewer sends cells while the model moves and one
# image once it is still).
set -u
ZV=${ZVIEW:-./zview}
S=../shared/models
sh "$(dirname "$0")/stamp.sh" "make bench-pixels (tools/bench-pixels.sh)"
echo
echo "| model | cells | half-block text (truecolor) | sixel | kitty | iterm | sixel at 1 MB/s |"
echo "|---|---|---:|---:|---:|---:|---:|"
for m in assets/torus.obj "$S/stanford-bunny.obj" "$S/dragon.obj"; do
    [ -f "$m" ] || continue
    for size in 100x30 200x60; do
        t=$("$ZV" --print --color truecolor --size "$size" "$m" | wc -c)
        sx=$("$ZV" --print --mode sixel --size "$size" "$m" | wc -c)
        k=$("$ZV" --print --mode kitty --size "$size" "$m" | wc -c)
        i=$("$ZV" --print --mode iterm --size "$size" "$m" | wc -c)
        awk -v m="$(basename "$m")" -v s="$size" -v t="$t" -v sx="$sx" -v k="$k" -v i="$i" 'BEGIN {
            printf "| %s | %s | %d | %d | %d | %d | %.0f ms |\n", m, s, t, sx, k, i, sx / 1e6 * 1000 }'
    done
done
