#!/usr/bin/env python3
"""mkseeds_mesh.py: writes fuzz-mesh's seeds (tests/fuzz/seeds/mesh): a
selector byte (fuzz_mesh.c: format, lenient, --points, wireframe, size)
then a small valid file of each native format, ascii and binary, with
faces, points, lines and colours where the format has them. The output
is committed; this is how it was made: python3 tests/fuzz/mkseeds_mesh.py"""
import gzip
import os
import struct
import sys

OBJ, STL, PLY, OFF, XYZ, DETECT = 0, 1, 2, 3, 4, 5
LENIENT, POINTS, WIRE = 8, 16, 32

out = sys.argv[1] if len(sys.argv) > 1 else "tests/fuzz/seeds/mesh"
os.makedirs(out, exist_ok=True)


def save(name, sel, data):
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(out, name), "wb") as f:
        f.write(bytes([sel]) + data)


cube_v = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
cube_f = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
tris = [t for q in cube_f for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]

obj = "".join("v %g %g %g\n" % v for v in cube_v)
obj += "o box\n" + "".join("f %d %d %d %d\n" % tuple(i + 1 for i in f) for f in cube_f)
obj += "o marks\np 1 2 -1\nl 1 2 4 3 1\nl 5/1 8/2\nvt 0 0\nvn 0 0 1\ns off\ng part\nusemtl none\n"
save("obj-cube-points-lines", OBJ | WIRE, obj)
save("obj-detected-lenient", DETECT | LENIENT | 64, obj + "f 1 2\nbogus 1\nf 1 2 99\nv 1 x 2\nf 1 2 9\n")
save("obj-cloud", OBJ | 128, "".join("v %d %d %d 0.%d 0.5 1\n" % (i % 3, i // 3 % 3, i // 9, i) for i in range(27)))

stl = "solid cube\n"
for t in tris:
    stl += " facet normal 0 0 0\n  outer loop\n"
    for i in t:
        stl += "   vertex %g %g %g\n" % cube_v[i]
    stl += "  endloop\n endfacet\n"
stl += "endsolid cube\n"
save("stl-ascii-cube", STL, stl)
b = b"binary stl".ljust(80, b" ") + struct.pack("<I", len(tris))
for k, t in enumerate(tris):
    b += struct.pack("<3f", 0, 0, 0)
    for i in t:
        b += struct.pack("<3f", *cube_v[i])
    b += struct.pack("<H", 0x8000 | (k * 997 & 0x7fff))
save("stl-binary-cube-colours", STL | WIRE, b)
save("stl-binary-detected", DETECT, b)


def ply_header(fmt, nv, nf, colours=True, faces=True):
    h = "ply\nformat %s 1.0\ncomment seed\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % (fmt, nv)
    if colours:
        h += "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    if faces:
        h += "element face %d\nproperty list uchar int vertex_indices\nproperty uchar red\n" % nf
    return h + "end_header\n"


body = "".join("%g %g %g %d %d %d\n" % (v + (30 * i, 255 - 30 * i, 128)) for i, v in enumerate(cube_v))
body += "".join("4 %d %d %d %d %d\n" % (f + (50 * k,)) for k, f in enumerate(cube_f))
save("ply-ascii-cube", PLY | WIRE, ply_header("ascii", 8, 6) + body)
for name, fmt, e in (("le", "binary_little_endian", "<"), ("be", "binary_big_endian", ">")):
    b = ply_header(fmt, 8, 6).encode()
    for i, v in enumerate(cube_v):
        b += struct.pack(e + "3f3B", *v, 30 * i, 255 - 30 * i, 128)
    for k, f in enumerate(cube_f):
        b += struct.pack(e + "B4iB", 4, *f, 50 * k)
    save("ply-binary-%s-cube" % name, PLY | (LENIENT if e == ">" else 0), b)
cloud = ply_header("binary_little_endian", 64, 0, faces=False).encode()
for i in range(64):
    cloud += struct.pack("<3f3B", i % 4, i // 4 % 4, i // 16, 4 * i, 255 - 4 * i, 100)
save("ply-binary-cloud", PLY | 64, cloud)
save("ply-ascii-cloud-detected", DETECT | 128, ply_header("ascii", 4, 0, faces=False) +
     "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n0 0 1 9 9 9\n")

off = "OFF\n# a cube\n8 6 12\n" + "".join("%g %g %g\n" % v for v in cube_v)
off += "".join("4 %d %d %d %d\n" % f for f in cube_f)
save("off-cube", OFF | WIRE, off)
coff = "COFF\n8 6 0\n" + "".join("%g %g %g %d %d %d 255\n" % (v + (30 * i, 100, 200)) for i, v in enumerate(cube_v))
coff += "".join("4 %d %d %d %d 255 0 0\n" % f for f in cube_f)
save("off-colours-detected", DETECT | LENIENT, coff)
save("off-cloud", OFF, "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n")

save("xyz-colours", XYZ | 64, "# x y z r g b\n" + "".join("%g %g %g %d %d %d\n" % (v + (200, 30 * i, 10)) for i, v in enumerate(cube_v)))
save("pts-intensity", XYZ | LENIENT, "8\n" + "".join("%g %g %g -%d %d %d %d\n" % (v + (i * 100, 10 * i, 20, 30)) for i, v in enumerate(cube_v)))
save("xyz-normals-commas", XYZ | 128, "".join("%g,%g,%g,0,%d,1\n" % (v + (-1 if i % 2 else 1,)) for i, v in enumerate(cube_v)))
save("xyz-detected", DETECT, "X Y Z\n" + "".join("%g %g %g\n" % v for v in cube_v))

# gzip streams (decompressed as they are read, reader.c/gzip.c): detected
# and forced formats, binary and text, and a stream cut inside its data
def gz(data):
    return gzip.compress(data.encode() if isinstance(data, str) else data, mtime=0)


save("gz-obj-detected", DETECT | 128, gz(obj))
save("gz-stl-binary-forced", STL | LENIENT | 128, gz(open(os.path.join(out, "stl-binary-cube-colours"), "rb").read()[1:]))
save("gz-ply-ascii-detected", DETECT | 128, gz(ply_header("ascii", 8, 6) + body))
save("gz-off-cut", DETECT | LENIENT | 128, gz(off)[:40])
save("gz-twice", DETECT | 128, gz(gz(off)))
