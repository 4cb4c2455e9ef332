#!/usr/bin/env python3
"""slowpty.py RATE WAIT LIMIT COLS ROWS -- COMMAND...: a slow link.

COMMAND runs on a pty of COLS x ROWS whose other side reads at most
RATE bytes a second (a slow ssh link); after WAIT seconds a q is typed.
Prints "quit after S s" with the seconds from the q until COMMAND exits,
and whether the last bytes it wrote leave the alternate screen
("reset seen" / "no reset"); "no exit within LIMIT s" if it does not
exit, and kills it. Exit status 0 when it exited within LIMIT.
"""
import os
import pty
import select
import signal
import struct
import sys
import time

try:
    import fcntl
    import termios
except ImportError:
    sys.exit(2)


def main():
    rate, wait, limit = float(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
    cols, rows = int(sys.argv[4]), int(sys.argv[5])
    cmd = sys.argv[7:]
    pid, fd = pty.fork()
    if pid == 0:
        try:
            os.execvp(cmd[0], cmd)
        finally:
            os._exit(127)
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack('HHHH', rows, cols, 0, 0))
    t0 = time.monotonic()
    q_at = None
    got = 0
    tail = b''
    while True:
        now = time.monotonic()
        if q_at is None and now - t0 >= wait:
            os.write(fd, b'q')
            q_at = now
        # read only as much as the rate allows so far
        allow = int(rate * (now - t0)) - got
        r, _, _ = select.select([fd], [], [], 0.02)
        if r and allow > 0:
            try:
                d = os.read(fd, allow)
            except OSError:
                d = b''
            got += len(d)
            tail = (tail + d)[-4096:]
        p, _ = os.waitpid(pid, os.WNOHANG)
        if p:
            took = time.monotonic() - q_at if q_at else -1
            # what is left on the line after the exit, read at full speed
            while True:
                r, _, _ = select.select([fd], [], [], 0.2)
                if not r:
                    break
                try:
                    d = os.read(fd, 65536)
                except OSError:
                    break
                if not d:
                    break
                tail = (tail + d)[-4096:]
            print("quit after %.2f s (%d bytes read before), %s" %
                  (took, got, "reset seen" if b'\x1b[?1049l' in tail else "no reset"))
            return 0
        if q_at is not None and now - q_at > limit:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            print("no exit within %.0f s of q (%d bytes read)" % (limit, got))
            return 1
        time.sleep(0.02)


sys.exit(main())
