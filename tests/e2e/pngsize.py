#!/usr/bin/env python3
"""pngsize.py FILE: decode a PNG far enough to trust it (signature, chunk
lengths and CRCs, IHDR, the IDAT stream inflated to exactly the rows the
header promises) and print "W H". Exit 1 with a reason otherwise."""
import struct
import sys
import zlib

CHANNELS = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}


def main(path):
    d = open(path, "rb").read()
    if d[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("%s: not a PNG signature" % path)
    pos, idat, ihdr, end = 8, b"", None, False
    while pos + 12 <= len(d):
        n, kind = struct.unpack(">I4s", d[pos:pos + 8])
        body = d[pos + 8:pos + 8 + n]
        crc, = struct.unpack(">I", d[pos + 8 + n:pos + 12 + n])
        if zlib.crc32(kind + body) & 0xffffffff != crc:
            sys.exit("%s: bad CRC in %s" % (path, kind))
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            end = True
        pos += 12 + n
    if not ihdr or not end:
        sys.exit("%s: no IHDR or IEND" % path)
    w, h, depth, colour = ihdr[:4]
    raw = zlib.decompress(idat)
    want = h * (1 + w * CHANNELS[colour] * depth // 8)
    if len(raw) != want:
        sys.exit("%s: %d bytes of pixels, the header says %d" % (path, len(raw), want))
    print(w, h)


main(sys.argv[1])
