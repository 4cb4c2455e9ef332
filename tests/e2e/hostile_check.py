#!/usr/bin/env python3
"""hostile_check.py: the inputs that kept --check busy for hours (issue
28), as binary STL, so that no large file is committed.

    hostile_check.py KIND N OUT.stl

KIND:
  fan        N triangles around one vertex, in one plane (a disk cut in
             N slices): every pair shares the centre, no pair crosses
  coincident the same triangle N times (N - 1 duplicates)
  edge       N triangles on one edge, each in its own half-plane (a fin
             of N blades): every pair shares the edge, none crosses
  stacked    N triangles in one plane, each moved a little along it:
             every pair overlaps (N (N - 1) / 2 crossing pairs)
  tilted     the same in the plane x + y + z = 1, coordinates of every
             magnitude: each coplanar test takes the exact arithmetic
"""
import math
import struct
import sys


def fan(n):
    pts = [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n), 0.0) for i in range(n)]
    return [((0.0, 0.0, 0.0), pts[i], pts[(i + 1) % n]) for i in range(n)]


def coincident(n):
    return [((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))] * n


def edge(n):
    a, b = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)
    out = []
    for i in range(n):
        t = 2 * math.pi * i / n
        out.append((a, b, (0.5, math.cos(t), math.sin(t))))
    return out


def stacked(n):
    out = []
    for i in range(n):
        d = i * 1e-5
        out.append(((d, d, 0.0), (1.0 + d, d, 0.0), (d, 1.0 + d, 0.0)))
    return out


def tilted(n):
    # in the plane x + y + z = 1 exactly: corners whose coordinates are
    # small dyadic numbers beside 1 (exact in floats), moved along it
    out = []
    for i in range(n):
        d = (i + 1) * 2.0 ** -20
        out.append(((d, 0.0, 1.0 - d), (1.0, d, -d), (0.0, 1.0 - d, d)))
    return out


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("fan", "coincident", "edge", "stacked", "tilted"):
        sys.exit(__doc__)
    tris = globals()[sys.argv[1]](int(sys.argv[2]))
    with open(sys.argv[3], "wb") as f:
        f.write(b"zview issue 28: " + sys.argv[1].encode() + b" " + sys.argv[2].encode())
        f.write(b" " * (80 - f.tell()))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0, 0, 0))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


main()
