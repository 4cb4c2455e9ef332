"""locations.py MODEL.obj REPORT.json [MAX]: hold every location of
zview --check --json to the problem it names, computed here from the OBJ
text alone (test_locations.sh). Positions are taken as zview keeps them,
32-bit floats, and points at one position are one point. Prints one
line per object, "ok NAME KIND=N ...", or the first location that does
not hold, and exits 1.

  holes               each step of the loop (the last back to the first)
                      is an edge that exactly one face uses; its points
                      are distinct; edges and perimeter as it says
  nonmanifold_edges   three or more faces use the edge: exactly those listed
  nonmanifold_vertices a point whose faces make two fans or more
  inconsistent_faces  with every listed face turned round, no edge of two
                      faces is run twice the same way
  degenerate_faces    the corners on one line
  duplicate_faces     an earlier face has the same points
  self_intersections  the point on both faces (their fan triangles),
                      within a millionth of the model's size
And each kind lists min(count, MAX) items, count being the object's
member of that name."""

import json
import math
import struct
import sys


def f32(x):
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def key(p):
    # -0 and +0 are one position
    return tuple(0.0 if c == 0 else c for c in p)


def read_obj(path):
    verts, faces, objects = [], [], []  # objects: (name, first face)
    for line in open(path, encoding="utf-8", errors="replace"):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            verts.append(key(f32(c) for c in w[1:4]))
        elif w[0] == "f":
            idx = []
            for t in w[1:]:
                i = int(t.split("/")[0])
                idx.append(i - 1 if i > 0 else len(verts) + i)
            faces.append([verts[i] for i in idx])
        elif w[0] == "o":
            objects.append((w[1] if len(w) > 1 else "", len(faces)))
    return faces, objects


def collinear(f):
    a = f[0]
    for i in range(1, len(f)):
        for j in range(i + 1, len(f)):
            u = [f[i][k] - a[k] for k in range(3)]
            v = [f[j][k] - a[k] for k in range(3)]
            c = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            if any(x != 0 for x in c):
                return False
    return True


def steps(f):
    n = len(f)
    return [(f[k], f[(k + 1) % n]) for k in range(n) if f[k] != f[(k + 1) % n]]


class Obj:
    def __init__(self, faces, first, end):
        self.first, self.end = first, end
        self.faces = faces
        self.uses = {}  # unordered edge -> [(face, a, b)]
        for i in range(first, end):
            if collinear(faces[i]):
                continue
            for a, b in steps(faces[i]):
                self.uses.setdefault(frozenset((a, b)), []).append((i, a, b))


def fail(msg):
    print("not ok:", msg)
    sys.exit(1)


def check_holes(o, items):
    for n, h in enumerate(items):
        loop = [key(f32(c) for c in p) for p in h["loop"]]
        if len(loop) < 3 or len(set(loop)) != len(loop):
            fail("hole %d: %d points, %d distinct" % (n, len(loop), len(set(loop))))
        length = 0
        for k in range(len(loop)):
            a, b = loop[k], loop[(k + 1) % len(loop)]
            uses = len(o.uses.get(frozenset((a, b)), []))
            if uses != 1:
                fail("hole %d step %d: %s-%s used by %d faces, not one" % (n, k, a, b, uses))
            length += math.dist(a, b)
        if h["edges"] != len(loop) or abs(h["perimeter"] - length) > 1e-6 * (length + 1):
            fail("hole %d: %s edges, perimeter %s; the loop has %d, %s" % (n, h["edges"], h["perimeter"], len(loop), length))


def check_nm_edges(o, items):
    for n, e in enumerate(items):
        a, b = (key(f32(c) for c in p) for p in e["ends"])
        on = sorted(set(f for f, _, _ in o.uses.get(frozenset((a, b)), [])))
        if len(o.uses.get(frozenset((a, b)), [])) < 3 or on != e["faces"]:
            fail("non-manifold edge %d: faces %s listed, %s use it" % (n, e["faces"], on))


def fans_at(o, x):
    at = [i for i in range(o.first, o.end) if not collinear(o.faces[i]) and x in o.faces[i]]
    parent = {i: i for i in at}

    def find(i):
        while parent[i] != i:
            i = parent[i]
        return i

    # faces joined across the edges they share at x
    for edge, uses in o.uses.items():
        if x in edge:
            fs = [f for f, _, _ in uses]
            for f in fs[1:]:
                parent[find(f)] = find(fs[0])
    return len(set(find(i) for i in at))


def check_nm_vertices(o, items):
    for n, v in enumerate(items):
        x = key(f32(c) for c in v["point"])
        if fans_at(o, x) < 2:
            fail("non-manifold vertex %d at %s: %d fans" % (n, x, fans_at(o, x)))


def check_flips(o, items, count):
    if len(items) < count:
        return
    flip = set(items)
    for edge, uses in o.uses.items():
        if len(uses) != 2:
            continue
        (f, a, b), (g, c, d) = uses
        same = (a, b) == (c, d)
        if (f in flip) != (g in flip):
            same = not same
        if same:
            fail("faces %d and %d run %s-%s the same way once the listed faces are flipped" % (f, g, a, b))


def check_faces(o, degenerate, duplicate):
    for f in degenerate:
        if not collinear(o.faces[f]):
            fail("face %d is listed as degenerate" % f)
    for f in duplicate:
        pts = sorted(o.faces[f])
        if not any(sorted(o.faces[g]) == pts for g in range(o.first, f)):
            fail("face %d is listed as a duplicate of none" % f)


def tri_dist(p, a, b, c):
    # closest point of triangle abc to p, by barycentrics, else the edges
    ab = [b[k] - a[k] for k in range(3)]
    ac = [c[k] - a[k] for k in range(3)]
    ap = [p[k] - a[k] for k in range(3)]
    dot = lambda u, v: sum(u[k] * v[k] for k in range(3))
    d00, d01, d11, d20, d21 = dot(ab, ab), dot(ab, ac), dot(ac, ac), dot(ap, ab), dot(ap, ac)
    den = d00 * d11 - d01 * d01
    if den > 0:
        v, w = (d11 * d20 - d01 * d21) / den, (d00 * d21 - d01 * d20) / den
        if v >= 0 and w >= 0 and v + w <= 1:
            return math.dist(p, [a[k] + v * ab[k] + w * ac[k] for k in range(3)])
    best = math.inf
    for s, e in ((a, b), (b, c), (c, a)):
        d = [e[k] - s[k] for k in range(3)]
        dd = dot(d, d)
        t = 0 if dd == 0 else min(1, max(0, dot([p[k] - s[k] for k in range(3)], d) / dd))
        best = min(best, math.dist(p, [s[k] + t * d[k] for k in range(3)]))
    return best


def face_dist(f, p):
    return min(tri_dist(p, f[0], f[k], f[k + 1]) for k in range(1, len(f) - 1))


def check_crossings(o, items, size):
    for n, x in enumerate(items):
        a, b = x["faces"]
        if not (o.first <= a < b < o.end):
            fail("crossing %d: faces %d %d" % (n, a, b))
        da, db = face_dist(o.faces[a], x["point"]), face_dist(o.faces[b], x["point"])
        if max(da, db) > 1e-6 * size:
            fail("crossing %d (faces %d, %d): the point %s is %g and %g from them" % (n, a, b, x["point"], da, db))


def main():
    faces, objects = read_obj(sys.argv[1])
    report = json.load(open(sys.argv[2]))
    most = int(sys.argv[3]) if len(sys.argv) > 3 else 100
    # objects with faces, as zview names them; no o: the file as one
    bounds = [(n, s, objects[k + 1][1] if k + 1 < len(objects) else len(faces)) for k, (n, s) in enumerate(objects)]
    if not objects or objects[0][1] > 0:
        bounds.insert(0, (None, 0, objects[0][1] if objects else len(faces)))
    bounds = [b for b in bounds if b[2] > b[1]]
    if len(bounds) != len(report["objects"]):
        fail("%d objects with faces, the report has %d" % (len(bounds), len(report["objects"])))
    size = max(r["size"] and max(r["size"]) or 0 for r in report["objects"])
    for (name, first, end), r in zip(bounds, report["objects"]):
        o = Obj(faces, first, end)
        loc = r["locations"]
        said = []
        for kind, v in loc.items():
            if v["count"] != r[kind]:
                fail("%s: count %s, the member says %s" % (kind, v["count"], r[kind]))
            if len(v["items"]) != min(v["count"], most):
                fail("%s: %d items of %d, at most %d" % (kind, len(v["items"]), v["count"], most))
            said.append("%s=%d" % (kind, len(v["items"])))
        check_holes(o, loc["holes"]["items"])
        check_nm_edges(o, loc["nonmanifold_edges"]["items"])
        check_nm_vertices(o, loc["nonmanifold_vertices"]["items"])
        check_flips(o, loc["inconsistent_faces"]["items"], loc["inconsistent_faces"]["count"])
        check_faces(o, loc["degenerate_faces"]["items"], loc["duplicate_faces"]["items"])
        check_crossings(o, loc["self_intersections"]["items"], size)
        print("ok", r["name"], " ".join(said))


main()
