#!/usr/bin/env python3
"""meshcount.py: a model's soundness counted without zview, to hold
--repair's output to a reference of its own (not --check).

    meshcount.py FILE...     one JSON object a line per FILE

Reads binary STL, OBJ (v and f; v/vt/vn corners, negative indices) and
binary little-endian or ascii PLY (the vertex x y z, the face list).
Vertices at one position are one point (exact coordinates, -0 = +0), as
slicers take them. Each face is its polygon: its edges are its
consecutive corners. Counted:

  faces        the faces read
  degenerate   faces whose corners all lie on one line, exactly (rational
               arithmetic on the floats)
  boundary     edges one face uses
  nonmanifold  edges three or more faces use
  misoriented  edges of two faces that run the same way in both (a
               winding that disagrees)
  pinched      vertices where separate fans of faces meet (two cubes
               touching at a corner)
  parts        faces joined by shared edges
  volume       the enclosed volume by the divergence theorem: the sum of
               a . (b x c) / 6 over each face's fan of triangles (each
               part's alone too: inside_out_parts have none above 0)
  watertight   no boundary, non-manifold or misoriented edge, no pinched
               vertex, no degenerate face, every part's volume positive
               (outward)
"""
import json
import struct
import sys
from fractions import Fraction


def read_stl(data):
    n = struct.unpack_from("<I", data, 80)[0]
    if len(data) != 84 + 50 * n:
        raise ValueError("not a binary STL (%d bytes for %d triangles)" % (len(data), n))
    verts, faces = [], []
    for i in range(n):
        f = struct.unpack_from("<12f", data, 84 + 50 * i)
        base = len(verts)
        verts += [f[3:6], f[6:9], f[9:12]]
        faces.append([base, base + 1, base + 2])
    return verts, faces


def read_obj(data):
    verts, faces = [], []
    for line in data.decode("utf-8", "replace").splitlines():
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            verts.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "f":
            face = []
            for c in w[1:]:
                i = int(c.split("/")[0])
                face.append(i - 1 if i > 0 else len(verts) + i)
            faces.append(face)
    return verts, faces


PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h", "ushort": "H",
             "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I", "float": "f", "float32": "f",
             "double": "d", "float64": "d"}


def read_ply(data):
    end = data.index(b"end_header") + len(b"end_header")
    end = data.index(b"\n", end) + 1
    head = data[:end].decode("ascii").splitlines()
    fmt, elems = None, []
    for line in head:
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elems.append((w[1], int(w[2]), []))
        elif w[0] == "property":
            elems[-1][2].append(w[1:])
    verts, faces = [], []
    if fmt == "ascii":
        words = data[end:].split()
        k = 0
        for name, count, props in elems:
            for _ in range(count):
                rec = {}
                for p in props:
                    if p[0] == "list":
                        m = int(words[k])
                        rec[p[3]] = [int(x) for x in words[k + 1:k + 1 + m]]
                        k += 1 + m
                    else:
                        rec[p[1]] = float(words[k])
                        k += 1
                take(name, rec, verts, faces)
        return verts, faces
    if fmt != "binary_little_endian":
        raise ValueError("PLY format %s not read here" % fmt)
    at = end
    for name, count, props in elems:
        for _ in range(count):
            rec = {}
            for p in props:
                if p[0] == "list":
                    ct, it = PLY_TYPES[p[1]], PLY_TYPES[p[2]]
                    m = struct.unpack_from("<" + ct, data, at)[0]
                    at += struct.calcsize(ct)
                    rec[p[3]] = list(struct.unpack_from("<%d%s" % (m, it), data, at))
                    at += m * struct.calcsize(it)
                else:
                    t = PLY_TYPES[p[0]]
                    rec[p[1]] = struct.unpack_from("<" + t, data, at)[0]
                    at += struct.calcsize(t)
            take(name, rec, verts, faces)
    return verts, faces


def take(name, rec, verts, faces):
    if name == "vertex":
        verts.append((float(rec["x"]), float(rec["y"]), float(rec["z"])))
    elif name == "face":
        faces.append(rec.get("vertex_indices", rec.get("vertex_index")))


def collinear(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    scale = (abs(u[0]) + abs(u[1]) + abs(u[2])) * (abs(v[0]) + abs(v[1]) + abs(v[2]))
    if max(abs(x) for x in w) > 1e-9 * scale:
        return False        # clearly not: the exact test only for the close calls
    a, b, c = [[Fraction(x) for x in p] for p in (a, b, c)]
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    return u[1] * v[2] - u[2] * v[1] == 0 and u[2] * v[0] - u[0] * v[2] == 0 and u[0] * v[1] - u[1] * v[0] == 0


def find(parent, x):
    while parent[x] != x:
        parent[x] = parent[parent[x]]
        x = parent[x]
    return x


def pinched(c_faces, edge_faces, npoints):
    """Vertices where separate fans of faces meet: around each vertex,
    its faces joined when they share an edge at it."""
    around = {}
    for f, c in enumerate(c_faces):
        for v in set(c):
            around.setdefault(v, []).append(f)
    parent = {}
    for (a, b), fs in edge_faces.items():
        for v in (a, b):
            for f in fs:
                parent.setdefault((v, f), (v, f))
            for f in fs[1:]:
                ra, rb = find(parent, (v, fs[0])), find(parent, (v, f))
                parent[ra] = rb
    n = 0
    for v, fs in around.items():
        roots = set(find(parent, (v, f)) if (v, f) in parent else (v, f) for f in fs)
        n += len(roots) > 1
    return n


def count(path):
    data = open(path, "rb").read()
    ext = path.lower().rsplit(".", 1)[-1]
    verts, faces = {"stl": read_stl, "obj": read_obj, "ply": read_ply}[ext](data)
    point = {}
    pid = [point.setdefault(tuple(0.0 + x for x in v), len(point)) for v in verts]   # 0.0 + -0.0 is 0.0
    pos = list(point.keys())
    uses, edge_faces, kept = {}, {}, []
    degenerate = 0
    for face in faces:
        c = [pid[i] for i in face]
        if all(collinear(pos[c[0]], pos[c[1]], pos[c[k]]) for k in range(2, len(c))):
            degenerate += 1
            continue
        f = len(kept)
        kept.append(c)
        for k in range(len(c)):
            a, b = c[k], c[(k + 1) % len(c)]
            key = (min(a, b), max(a, b))
            d = uses.setdefault(key, [0, 0])
            d[0 if a < b else 1] += 1
            edge_faces.setdefault(key, []).append(f)
    # parts: faces joined by shared edges; each part's volume
    parent = list(range(len(kept)))
    for fs in edge_faces.values():
        for f in fs[1:]:
            parent[find(parent, f)] = find(parent, fs[0])
    vol = {}
    for f, c in enumerate(kept):
        p0, r = pos[c[0]], find(parent, f)
        for k in range(1, len(c) - 1):
            p1, p2 = pos[c[k]], pos[c[k + 1]]
            vol[r] = vol.get(r, 0.0) + (p0[0] * (p1[1] * p2[2] - p1[2] * p2[1]) + p0[1] * (p1[2] * p2[0] - p1[0] * p2[2]) +
                                        p0[2] * (p1[0] * p2[1] - p1[1] * p2[0])) / 6.0
    boundary = sum(1 for d in uses.values() if d[0] + d[1] == 1)
    nonmanifold = sum(1 for d in uses.values() if d[0] + d[1] >= 3)
    misoriented = sum(1 for d in uses.values() if d[0] + d[1] == 2 and d[0] != 1)
    pinch = pinched(kept, edge_faces, len(pos))
    inside_out = sum(1 for v in vol.values() if v <= 0)
    return {"file": path, "faces": len(faces), "points": len(pos), "degenerate": degenerate, "edges": len(uses),
            "boundary": boundary, "nonmanifold": nonmanifold, "pinched": pinch, "misoriented": misoriented,
            "parts": len(vol), "inside_out_parts": inside_out, "volume": sum(vol.values()),
            "watertight": bool(faces) and boundary == 0 and nonmanifold == 0 and pinch == 0 and misoriented == 0
            and degenerate == 0 and inside_out == 0}


if __name__ == "__main__":
    for p in sys.argv[1:]:
        print(json.dumps(count(p)))
