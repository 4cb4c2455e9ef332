#!/bin/sh
# The line each benchmark prints first, so that a table copied into
# doc/benchmarks.md says where it came from: the commit (with "+changes"
# when the tree differs from it), the machine (cores, CPU, memory), its
# load, and the command.
# Usage: sh tools/stamp.sh "make bench VIEWS=8"
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
git diff --quiet HEAD -- src include 2>/dev/null || commit="$commit+changes"
cpu=$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ *//')
mem=$(awk '/^MemTotal:/ { printf "%.1f GB memory", $2 / 1048576 }' /proc/meminfo 2>/dev/null)
echo "# commit $commit; machine: $(nproc) cores, ${cpu:-unknown CPU}, ${mem:-unknown memory}, load $(cut -d' ' -f1-3 /proc/loadavg); $(date -u +%Y-%m-%d); command: $1"
