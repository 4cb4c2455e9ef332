#!/usr/bin/env python3
"""threads.py TRACE: the threads a run started, from `strace -f -e
trace=clone,clone3` output, by the process that started them.

Prints two numbers: the threads started in the first process (zview
itself: its render helpers, the viewer's loader and check threads) and
the threads started in every other process (the loading children: the
parse's helpers). A line is "TID syscall(...) = NEW"; a call whose flags
hold CLONE_THREAD makes NEW a thread of the caller's process, any other
a process of its own.
"""
import re
import sys

tgid = {}
first = None
own = others = 0
for line in open(sys.argv[1], errors='replace'):
    m = re.match(r'^(\d+)\s+(clone3?|fork|vfork)\((.*)\)\s+=\s+(\d+)\s*$', line)
    if not m:
        continue
    tid, new = int(m.group(1)), int(m.group(4))
    if first is None:
        first = tid
    group = tgid.get(tid, tid)
    if 'CLONE_THREAD' in m.group(3):
        tgid[new] = group
        if group == first:
            own += 1
        else:
            others += 1
    else:
        tgid[new] = new
print(own, others)
