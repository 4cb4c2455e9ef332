"""hugejpeg.py OUT [SIDE]: a progressive JPEG of a few dozen bytes whose
frame header claims SIDE x SIDE pixels (default 65000): one grey
component, one DC scan of all-zero differences, then the end."""
import struct, sys
out = sys.argv[1]
side = int(sys.argv[2]) if len(sys.argv) > 2 else 65000
def seg(marker, body):
    return b'\xff' + bytes([marker]) + struct.pack('>H', len(body) + 2) + body
dqt = seg(0xDB, b'\x00' + bytes([1] * 64))
sof2 = seg(0xC2, struct.pack('>BHHB', 8, side, side, 1) + bytes([1, 0x11, 0]))
# DC table 0: one code, length 1, for category 0 (a zero difference)
dht = seg(0xC4, b'\x00' + bytes([1] + [0] * 15) + b'\x00')
sos = seg(0xDA, bytes([1, 1, 0x00, 0, 0, 0x00]))
data = b'\x00' * 16         # sixteen bytes of '0' codes: 128 blocks, the rest missing
open(out, 'wb').write(b'\xff\xd8' + dqt + sof2 + dht + sos + data + b'\xff\xd9')
