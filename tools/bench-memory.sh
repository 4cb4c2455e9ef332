#!/bin/sh
# make bench-memory: memory while the view turns (issue 21: "memory per
# frame stays flat while turning, no growth over 10,000 frames"). For
# each algorithm, FRAMES frames (10,000) of the dragon (the bundled knot
# when ../shared/models is absent) at 160x96 with 4 samples, as the
# viewer draws a small terminal, on one thread and on two: resident
# memory (rss) and malloc'd bytes (heap) after frame 100 and after the
# last, the most resident between, the growth in KB and in bytes of heap
# per frame (tools/memframes.c). Flat is a growth of 0 (a page or two of
# rss is the allocator, not a leak: the heap column says which). Memory
# is not time: the figures do not depend on the machine's load. ALGO=
# a comma list narrows it; SIZE=WxH, SAMPLES=N change the frame.
set -u
MEMFRAMES=${MEMFRAMES:-build/memframes}
FRAMES=${FRAMES:-10000}
SIZE=${SIZE:-160x96}
SAMPLES=${SAMPLES:-1}
ALGO=${ALGO:-all}
M=../shared/models/dragon.obj
[ -f "$M" ] || M=assets/knot.obj
sh "$(dirname "$0")/stamp.sh" "make bench-memory (tools/bench-memory.sh), FRAMES=$FRAMES"
echo
echo "## $(basename "$M"), $FRAMES frames turning half a degree each, $SIZE x $SAMPLES samples, shaded"
for t in 1 2; do
    "$MEMFRAMES" --views "$FRAMES" --size "$SIZE" --samples "$SAMPLES" --threads "$t" --algo "$ALGO" "$M" |
        if [ "$t" = 1 ]; then cat; else tail -n +2; fi
done
