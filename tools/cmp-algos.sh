#!/bin/sh
# cmp-algos.sh MODEL [zview options...]: dump the face-id buffer with every
# algorithm and compare each with the z-buffer's, byte for byte.
set -u
ZV=${ZVIEW:-./zview}
model=$1; shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$ZV" "$model" "$@" --algo zbuffer --dump-ids "$tmp/ref" -o "$tmp/ref.ppm" || exit 1
bad=0
for a in scanline span hzb hzb-octree; do
    "$ZV" "$model" "$@" --algo "$a" --dump-ids "$tmp/$a" -o "$tmp/$a.ppm" || exit 1
    if cmp -s "$tmp/ref" "$tmp/$a"; then echo "$a: identical"; else
        n=$(cmp -l "$tmp/ref" "$tmp/$a" | awk '{print int(($1-1)/4)}' | uniq | wc -l)
        echo "$a: DIFFERS in $n pixels"; bad=1; fi
done
exit $bad
