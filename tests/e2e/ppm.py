#!/usr/bin/env python3
"""ppm.py: what a -o PPM image shows, for the background tests.

usage: ppm.py FILE at X Y     the pixel at (X, Y): "R G B"
       ppm.py FILE drawn      the pixels that differ from the corner (0, 0),
                              taken for the background: "N DISTINCT MIN_L MAX_L R,G,B"
                              (their count, distinct colours, least and most
                              OKLab lightness, the most common colour)
       ppm.py TEXT-FILE sgr   the 24-bit colours of a text frame's SGR
                              escapes: "N MIN_L MAX_L" over the foregrounds
                              and backgrounds that are not the given --bg
Lightness is OKLab's L (Ottosson 2020), as zview measures it.
"""
import re
import sys
from collections import Counter


def lin(c):
    c /= 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def lightness(rgb):
    r, g, b = (lin(x) for x in rgb)
    l = 0.4122214708 * r + 0.5363325363 * g + 0.0514459929 * b
    m = 0.2119034982 * r + 0.6806995451 * g + 0.1073969566 * b
    s = 0.0883024619 * r + 0.2817188376 * g + 0.6299787005 * b
    l, m, s = (v ** (1 / 3) for v in (l, m, s))
    return 0.2104542553 * l + 0.7936177850 * m - 0.0040720468 * s


def read_ppm(path):
    d = open(path, "rb").read()
    magic, size, top, px = d.split(b"\n", 3)
    if magic != b"P6" or top != b"255":
        sys.exit("%s: not a P6 PPM" % path)
    w, h = map(int, size.split())
    return w, h, px


def main(argv):
    if argv[2] == "sgr":
        text = open(argv[1], encoding="utf-8").read()
        skip = tuple(int(x) for x in argv[3].split(",")) if len(argv) > 3 else None
        cols = [tuple(map(int, m)) for m in re.findall(r"[34]8;2;(\d+);(\d+);(\d+)", text)]
        cols = [c for c in cols if c != skip]
        ls = [lightness(c) for c in set(cols)]
        print(len(cols), "%.4f" % min(ls) if ls else "-", "%.4f" % max(ls) if ls else "-")
        return
    w, h, px = read_ppm(argv[1])
    pixel = lambda x, y: tuple(px[3 * (y * w + x):3 * (y * w + x) + 3])
    if argv[2] == "at":
        print("%d %d %d" % pixel(int(argv[3]), int(argv[4])))
        return
    bg = pixel(0, 0)
    drawn = Counter(pixel(x, y) for y in range(h) for x in range(w) if pixel(x, y) != bg)
    if not drawn:
        print("0 0 - - -")
        return
    ls = [lightness(c) for c in drawn]
    top = drawn.most_common(1)[0][0]
    print(sum(drawn.values()), len(drawn), "%.4f" % min(ls), "%.4f" % max(ls), "%d,%d,%d" % top)


main(sys.argv)
