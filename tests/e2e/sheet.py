#!/usr/bin/env python3
"""sheet.py: the tiles of a contact sheet (zview --gallery -o FILE.ppm).

usage: sheet.py FILE.ppm N PW PH
Lays out N tiles of PW x PH pixel pictures as the man page says (up to 8
across, as many as the square root of N rounded up), with the margins of
src/gallery/sheet.c (8 pixels about a picture, a title line and two text
lines of 10 pixels); checks the image's size against that layout, then
prints, for each tile in order, the pixels of its picture that differ
from the background (the sheet's top-left pixel). Exit 1 on a size that
does not match."""
import math
import sys


def read_ppm(path):
    d = open(path, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:
        while d[pos:pos + 1].isspace():
            pos += 1
        if d[pos:pos + 1] == b"#":
            pos = d.index(b"\n", pos) + 1
            continue
        end = pos
        while not d[end:end + 1].isspace():
            end += 1
        fields.append(d[pos:end])
        pos = end
    pos += 1
    if fields[0] != b"P6" or fields[3] != b"255":
        sys.exit("%s: not a binary 8-bit PPM" % path)
    return int(fields[1]), int(fields[2]), d[pos:]


def main(path, n, pw, ph):
    w, h, px = read_ppm(path)
    cols = min(8, max(1, math.ceil(math.sqrt(n))))
    rows = (n + cols - 1) // cols
    margin, line = 8, 10
    tw, th, top = pw + 2 * margin, ph + 2 * line + 2 * margin, line + margin
    want = (cols * tw, top + max(rows, 1) * th)
    if (w, h) != want:
        sys.exit("%s: %dx%d, the layout of %d tiles is %dx%d" % (path, w, h, n, want[0], want[1]))
    bg = px[0:3]
    for i in range(n):
        x0 = (i % cols) * tw + margin
        y0 = top + (i // cols) * th + margin
        count = 0
        for y in range(y0, y0 + ph):
            row = px[3 * (y * w + x0):3 * (y * w + x0 + pw)]
            count += sum(1 for k in range(0, len(row), 3) if row[k:k + 3] != bg)
        print(i, count)


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]))
