#!/usr/bin/env python3
"""brokenstl.py: broken parts as binary STL, each with one kind of fault
--repair (and admesh) should fix, for test_repair.sh and
tools/repair-table.sh.

    brokenstl.py DIR        writes DIR/NAME.stl for every NAME below

  open-box     a cube missing one face: a planar hole of 4 edges
  flipped      a cube with one triangle wound backwards
  inside-out   a cube with every triangle wound backwards
  twisted      a cube whose top corners are raised and lowered in turn
               (a twisted quad) and whose top is missing: a hole whose
               4 edges are not in one plane
  fin          a cube with a triangle standing on one of its edges: an
               edge of three faces
  hole-200     a 200-sided prism missing its top: a hole of 200 edges
  moebius      a Moebius strip: one side, one edge, no inside
  part-inside-out  two cubes apart, the second wound backwards: the
               file's volume is positive, one part's negative
  edge-touching    two cubes sharing one edge: an edge of four faces
  corner-touching  two cubes sharing one corner: a pinched vertex
  wavy-hole    a 48-sided prism whose top rim waves up and down, its top
               missing: a hole of 48 edges far from any plane
"""
import math
import os
import struct
import sys

CUBE = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
# outward (counter-clockwise seen from outside) quads: bottom, top, front, back, left, right
QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (0, 4, 7, 3), (1, 2, 6, 5)]


def tris_of(quads, pts):
    out = []
    for a, b, c, d in quads:
        out.append((pts[a], pts[b], pts[c]))
        out.append((pts[a], pts[c], pts[d]))
    return out


def flip(t):
    return (t[0], t[2], t[1])


def normal(t):
    """The unit normal of the winding, as an exporter writes it."""
    u = [t[1][i] - t[0][i] for i in range(3)]
    v = [t[2][i] - t[0][i] for i in range(3)]
    w = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    n = math.sqrt(sum(x * x for x in w))
    return tuple(x / n for x in w) if n else (0.0, 0.0, 0.0)


def write(path, tris):
    with open(path, "wb") as f:
        f.write(b"broken part for zview's repair tests".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", *normal(t)))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def prism(n, top):
    ring0 = [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n), 0.0) for i in range(n)]
    ring1 = [(x, y, 1.0) for x, y, _ in ring0]
    tris = []
    for i in range(n):
        j = (i + 1) % n
        tris.append((ring0[i], ring0[j], ring1[j]))
        tris.append((ring0[i], ring1[j], ring1[i]))
        tris.append(((0.0, 0.0, 0.0), ring0[j], ring0[i]))       # the bottom, facing down
        if top:
            tris.append(((0.0, 0.0, 1.0), ring1[i], ring1[j]))
    return tris


def moebius(n):
    tris = []
    def at(i, s):
        t = 2 * math.pi * i / n
        r = 1 + 0.3 * s * math.cos(t / 2)
        return (r * math.cos(t), r * math.sin(t), 0.3 * s * math.sin(t / 2))
    for i in range(n):
        a, b, c, d = at(i, -1), at(i, 1), at(i + 1, 1), at(i + 1, -1)
        if i == n - 1:          # the ends meet turned over
            c, d = at(0, -1), at(0, 1)
        tris.append((a, d, c))
        tris.append((a, c, b))
    return tris


def moved(tris, d):
    return [tuple((p[0] + d[0], p[1] + d[1], p[2] + d[2]) for p in t) for t in tris]


def wavy(n):
    ring0 = [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n), 0.0) for i in range(n)]
    ring1 = [(x, y, 1.0 + 0.4 * math.sin(6 * math.pi * i / n)) for i, (x, y, _) in enumerate(ring0)]
    tris = []
    for i in range(n):
        j = (i + 1) % n
        tris += [(ring0[i], ring0[j], ring1[j]), (ring0[i], ring1[j], ring1[i]), ((0.0, 0.0, 0.0), ring0[j], ring0[i])]
    return tris


def cases():
    cube = tris_of(QUADS, CUBE)
    twisted_pts = [p if p[2] == 0 else (p[0], p[1], 1 + (0.25 if (p[0] + p[1]) % 2 == 0 else -0.25)) for p in CUBE]
    return {
        "open-box": tris_of(QUADS[:1] + QUADS[2:], CUBE),
        "flipped": cube[:5] + [flip(cube[5])] + cube[6:],
        "inside-out": [flip(t) for t in cube],
        "twisted": tris_of(QUADS[:1] + QUADS[2:], twisted_pts),
        "fin": cube + [((0, 0, 0), (1, 0, 0), (0.5, -1, 0.5))],
        "hole-200": prism(200, False),
        "moebius": moebius(48),
        "part-inside-out": cube + [flip(t) for t in moved(cube, (3, 0, 0))],
        "edge-touching": cube + moved(cube, (1, 1, 0)),
        "corner-touching": cube + moved(cube, (1, 1, 1)),
        "wavy-hole": wavy(48),
    }


if __name__ == "__main__":
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, tris in cases().items():
        write(os.path.join(out, name + ".stl"), [tuple(tuple(float(x) for x in p) for p in t) for t in tris])
