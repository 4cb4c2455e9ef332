#!/usr/bin/env python3
"""pixbar.py COLS ROWS -- COMMAND...: the status bar before and after a
still image.

COMMAND (the viewer, with a --mode that draws pixels) runs on a pty of
COLS x ROWS; after 3 s a q is typed. The bytes it wrote are split at the
first image (a sixel DCS, a kitty APC or an iTerm2 OSC 1337), and the
last row is followed through each part as a terminal would (cursor
moves to it, text written there; other sequences skipped). Prints two
lines: "cells: BAR" (the bar as it stood when the image went out) and
"image: BAR" (as it stood when the viewer quit); exit status 1 when no
image was drawn.
"""
import os
import pty
import re
import select
import struct
import sys
import time

import fcntl
import termios

SEQ = re.compile(rb'\x1b(\[[0-?]*[ -/]*[@-~]|[PX^_\]].*?(\x1b\\|\x07)|[()][0-9A-Za-z]|[=>78])', re.S)


def last_row(data, cols, rows, row):
    """Follow the text written on the last row through data."""
    x = y = 0
    pos = 0
    while pos < len(data):
        m = SEQ.match(data, pos) if data[pos] == 0x1b else None
        if m:
            s = m.group(0)
            cup = re.fullmatch(rb'\x1b\[(\d*);?(\d*)H', s)
            if cup:
                y = int(cup.group(1) or 1) - 1
                x = int(cup.group(2) or 1) - 1
            elif re.fullmatch(rb'\x1b\[(\d*)D', s):
                x = max(0, x - int(s[2:-1] or 1))
            pos = m.end()
            continue
        if data[pos] == 0x1b:
            pos += 1
            continue
        if data[pos] == 0x0a:
            y += 1
            pos += 1
            continue
        if data[pos] == 0x0d:
            x = 0
            pos += 1
            continue
        n = 1
        if data[pos] >= 0xc0:
            n = 2 if data[pos] < 0xe0 else 3 if data[pos] < 0xf0 else 4
        if y == rows - 1 and 0 <= x < cols:
            row[x] = data[pos:pos + n].decode('utf-8', 'replace')
        x += 1
        pos += n
    return row


def main():
    cols, rows = int(sys.argv[1]), int(sys.argv[2])
    cmd = sys.argv[4:]
    pid, fd = pty.fork()
    if pid == 0:
        try:
            os.execvp(cmd[0], cmd)
        finally:
            os._exit(127)
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack('HHHH', rows, cols, 0, 0))
    out = b''
    t0 = time.monotonic()
    q = False
    while time.monotonic() - t0 < 15:
        r, _, _ = select.select([fd], [], [], 0.1)
        if r:
            try:
                d = os.read(fd, 65536)
            except OSError:
                break
            if not d:
                break
            out += d
        if not q and time.monotonic() - t0 > 3:
            os.write(fd, b'q')
            q = True
    os.waitpid(pid, 0)
    # the image, and where the viewer left the screen (the alternate one)
    m = re.search(rb'\x1bP[0-9;]*q|\x1b_G|\x1b\]1337;', out)
    end = out.rfind(b'\x1b[?1049l')
    if not m:
        print('no image')
        return 1
    row = last_row(out[:m.start()], cols, rows, [' '] * cols)
    print('cells: ' + ''.join(row).strip())
    row = last_row(out[m.start():end if end > m.start() else len(out)], cols, rows, row)
    print('image: ' + ''.join(row).strip())
    return 0


sys.exit(main())
