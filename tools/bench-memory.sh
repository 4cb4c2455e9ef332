#!/bin/sh
# make bench-memory: memory while the view turns (issue 21: "memory per
# frame stays flat while turning, no growth over 10,000 frames"). For
# each algorithm, FRAMES frames (10,000) of the dragon (the bundled knot
# when ../shared/models is absent) at 160x96 with 1 sample (SAMPLES=4 for
# the viewer's; the buffers are then 4 times larger, the question the
# same, the run twice as long), on one thread and on two: resident
# memory (rss) and malloc'd bytes (heap) after frame 100 and after the
# last, the most resident between, the rss growth in KB, and heap_B, the
# bytes the heap grew from frame 1,000 (past a whole turn: every view
# seen once) to the last (tools/memframes.c). Flat is 0 in both. Memory
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
