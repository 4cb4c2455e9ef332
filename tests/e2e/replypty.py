#!/usr/bin/env python3
"""replypty.py PROFILE -- COMMAND...: a terminal that answers.

COMMAND (the viewer) runs on an 80x24 pty whose other side plays the
terminal PROFILE: it answers the questions the viewer asks (the
background colour, OSC 11; the device attributes, CSI c; kitty's
graphics query, APC G; the terminal's name, CSI > q; the status
request after each frame, CSI 5 n) as that terminal does, and sends
the answers and keys down one line, in order, as a link does:

  kitty      OSC 11 with ST, kitty's APC OK, its name, DA1 "?62;c"
  xterm      OSC 11 with BEL, its name, DA1 with sixel (4); no APC
  foot       OSC 11 with ST, its name, DA1 "?62;4;22c"
  tmux       TMUX set (the viewer asks no pixels), tmux's own DA1 and
             colour, then kitty's answer wrapped in tmux's passthrough
             (DCS tmux; with every ESC doubled), unasked
  late       kitty's answers 400 ms late (after the viewer's wait), then
             an APC, a PM and an SOS nobody asked for
  slow       kitty's answers byte by byte, 30 ms apart, the leading ESC
             alone 30 to 300 ms before the rest (a slow ssh link)
  slowxterm  xterm's answers, the same way
  xterm8     xterm's answers in their 8-bit forms (CSI 0x9b, OSC 0x9d,
             ST 0x9c), in a Latin-1 locale
  silent     no answer to anything (not even the status requests); the
             key i typed 20 ms after the questions, during the viewer's
             wait: the first picture within 150 ms of the questions, and
             the i read as the key (the info panel shows)

Checks, printed as "ok - ..." / "not ok - ...": the viewer is still
running once every answer is in (the answers read as Esc quit it); the
still model is drawn in the pixels the answers name, however late;
a key that turns the model draws again; q quits with status 0 and the
terminal put back (the alternate screen left). Exit status 0 when every
check passed.
"""
import os
import pty
import re
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

ESC = b'\x1b'
ST = ESC + b'\\'

# the questions, as the viewer sends them
Q_BG = ESC + b']11;?' + ST
Q_DA = ESC + b'[c'
Q_KITTY = ESC + b'_Gi=31,'
Q_NAME = ESC + b'[>0q'
Q_STATUS = ESC + b'[5n'
Q_SGR = ESC + b'P$qm' + ST      # DECRQSS for the SGR, after a 24-bit colour was set
Q_SGR_SET = ESC + b'[38;2;1;2;3m'

KITTY = {
    Q_BG: ESC + b']11;rgb:0000/0000/0000' + ST,
    Q_DA: ESC + b'[?62;c',
    Q_KITTY: ESC + b'_Gi=31;OK' + ST,
    Q_NAME: ESC + b'P>|kitty(0.26.5)' + ST,
}
XTERM = {
    Q_BG: ESC + b']11;rgb:ffff/ffff/ffff\x07',
    Q_DA: ESC + b'[?63;1;2;4;6;9;15;16;17;18;21;22;28c',
    Q_NAME: ESC + b'P>|XTerm(379)' + ST,
}
FOOT = {
    Q_BG: ESC + b']11;rgb:1e1e/1e1e/2e2e' + ST,
    Q_DA: ESC + b'[?62;4;22c',
    Q_NAME: ESC + b'P>|foot(1.13.1)' + ST,
}
TMUX = {
    Q_BG: ESC + b']11;rgb:0000/0000/0000' + ST,
    Q_DA: ESC + b'[?1;2c',
}
XTERM8 = {
    Q_BG: b'\x9d11;rgb:ffff/ffff/ffff\x9c',
    Q_DA: b'\x9b?63;1;2;4;6;22c',
    Q_NAME: b'\x90>|XTerm(379)\x9c',
}

# xterm over ssh: TERM=xterm (8 colours), no COLORTERM; it says the
# 24-bit colour it was given back as set (xterm's direct colour)
XTERM_SGR = dict(XTERM)
XTERM_SGR[Q_SGR] = ESC + b'P1$r0;38:2::1:2:3m' + ST

PROFILES = {
    # name: answers, extra answers nobody asked for, delay (s), slow, env
    'kitty': (KITTY, [], 0, False, {}),
    'xterm': (XTERM, [], 0, False, {}),
    'foot': (FOOT, [], 0, False, {}),
    'tmux': (TMUX, [ESC + b'Ptmux;' + ESC + ESC + b'_Gi=31;OK' + ESC + ESC + b'\\' + ST], 0, False,
             {'TMUX': '/tmp/tmux-0/default,1,0', 'TERM': 'tmux-256color'}),
    'late': (KITTY, [ESC + b'_Gi=31;OK' + ST, ESC + b'^a private message' + ST, ESC + b'Xa string\x07'], 0.4,
             False, {}),
    'slow': (KITTY, [], 0, True, {}),
    'slowxterm': (XTERM, [], 0, True, {}),
    'xterm8': (XTERM8, [], 0, False, {'LC_ALL': 'C', 'LANG': 'C'}),
    'xtermssh': (XTERM_SGR, [], 0, False, {'TERM': 'xterm', 'COLORTERM': ''}),
    'xterm16': (XTERM, [], 0, False, {'TERM': 'xterm', 'COLORTERM': ''}),
    'silent': ({}, [], 0, False, {}),
}
SILENT = {'silent'}
FIRST_PICTURE_MS = 150      # from a silent terminal's questions: the one wait (TERM_ASK_MS, 100) and a frame

# the colours each profile's frames are drawn in: 24-bit where COLORTERM
# says so or the terminal answered the SGR report, else TERM's (xterm: 8)
COLOURS = {'xtermssh': 'truecolor', 'xterm16': '8'}

# the pixels each profile's answers name, and how each image begins
PIXELS = {'kitty': 'kitty', 'xterm': 'sixel', 'foot': 'sixel', 'tmux': 'cells', 'late': 'kitty',
          'slow': 'kitty', 'slowxterm': 'sixel', 'xterm8': 'sixel', 'xtermssh': 'sixel', 'xterm16': 'sixel',
          'silent': 'cells'}
IMAGE_HEADS = {'kitty': ESC + b'_Ga=T', 'sixel': ESC + b'P0;1;0q'}

ESC_GAPS = [0.03, 0.12, 0.3]    # the leading ESC alone before the rest, in turn
BYTE_GAP = 0.03


class Link:
    """One line to the viewer: what is queued goes in order, at its time."""

    def __init__(self, fd, slow):
        self.fd = fd
        self.slow = slow
        self.queue = []         # (time, bytes)
        self.free_at = 0.0      # when the line is free for the next message
        self.splits = 0

    def send(self, data, delay=0.0):
        t = max(time.monotonic() + delay, self.free_at)
        if not self.slow:
            self.queue.append((t, data))
            self.free_at = t
            return
        for i in range(len(data)):
            t += 0 if i == 0 else ESC_GAPS[self.splits % len(ESC_GAPS)] if i == 1 else BYTE_GAP
            self.queue.append((t, data[i:i + 1]))
        self.splits += 1
        self.free_at = t + BYTE_GAP

    def pump(self):
        now = time.monotonic()
        while self.queue and self.queue[0][0] <= now:
            os.write(self.fd, self.queue.pop(0)[1])

    def busy(self):
        return bool(self.queue)

    def next_at(self):
        return self.queue[0][0] if self.queue else None


class Viewer:
    def __init__(self, profile, cmd):
        self.answers, self.extra, self.delay, slow, env = PROFILES[profile]
        child_env = dict(os.environ)
        child_env['TERM'] = 'xterm-256color'
        child_env['COLORTERM'] = 'truecolor'
        child_env.setdefault('LC_ALL', 'C.UTF-8')
        child_env.pop('TMUX', None)
        child_env.pop('STY', None)
        child_env.update(env)
        self.pid, self.fd = pty.fork()
        if self.pid == 0:
            try:
                os.execvpe(cmd[0], cmd, child_env)
            finally:
                os._exit(127)
        # 80x24 cells of 8x16 pixels
        fcntl.ioctl(self.fd, termios.TIOCSWINSZ, struct.pack('HHHH', 24, 80, 640, 384))
        self.link = Link(self.fd, slow)
        self.out = b''          # everything the viewer wrote
        self.scanned = 0        # questions answered up to here
        self.status = None      # the exit status, once it has exited
        self.asked = {}
        self.silent = profile in SILENT
        self.t_start = time.monotonic()
        self.t_asked = None     # when the first question was read
        self.t_picture = None   # when the first picture's status bar was read

    def answer(self):
        """Answer the questions written since the last look, in order."""
        qs = list(self.answers.keys()) + [Q_STATUS]
        while True:
            best = None
            for q in qs:
                i = self.out.find(q, self.scanned)
                if i >= 0 and (best is None or i < best[0]):
                    best = (i, q)
            if best is None:
                # keep a question's start that may be cut at the end
                self.scanned = max(self.scanned, len(self.out) - 16)
                return
            i, q = best
            self.scanned = i + len(q)
            self.asked[q] = self.asked.get(q, 0) + 1
            reply = ESC + b'[0n' if q == Q_STATUS and not self.silent else self.answers.get(q)
            if reply:
                self.link.send(reply, self.delay if q != Q_STATUS else 0)

    def step(self, timeout):
        """Read, answer, send what is due, note an exit."""
        waits = [timeout]
        t = self.link.next_at()
        if t is not None:
            waits.append(max(0.0, t - time.monotonic()))
        r, _, _ = select.select([self.fd], [], [], min(waits))
        if r:
            try:
                d = os.read(self.fd, 65536)
            except OSError:
                d = b''
            self.out += d
            if self.t_asked is None and Q_DA in self.out:
                self.t_asked = time.monotonic()
            if self.t_picture is None and b'zbuffer' in self.out:
                self.t_picture = time.monotonic()
            self.answer()
        self.link.pump()
        if self.status is None:
            p, st = os.waitpid(self.pid, os.WNOHANG)
            if p:
                self.status = st

    def run_for(self, seconds, until=None):
        end = time.monotonic() + seconds
        while time.monotonic() < end and self.status is None:
            self.step(0.01)
            if until and until():
                return True
        return bool(until and until())

    def quiet_for(self, seconds, limit):
        """Run until the viewer wrote nothing for `seconds` (at most limit s)."""
        end = time.monotonic() + limit
        while time.monotonic() < end and self.status is None:
            n = len(self.out)
            self.run_for(seconds)
            if len(self.out) == n and not self.link.busy():
                return True
        return False

    def kill(self):
        if self.status is None:
            os.kill(self.pid, signal.SIGKILL)
            os.waitpid(self.pid, 0)


def main():
    profile = sys.argv[1]
    cmd = sys.argv[3:]
    results = []

    def check(name, cond, why=''):
        results.append(cond)
        print(('ok - ' if cond else 'not ok - ') + profile + ': ' + name)
        if not cond and why:
            print('#   ' + why)

    v = Viewer(profile, cmd)
    try:
        t0 = time.monotonic()
        if v.silent:
            # a key typed during the wait for answers that never come
            v.run_for(5, until=lambda: v.t_asked is not None)
            v.run_for(0.02)
            v.link.send(b'i')
            v.run_for(5, until=lambda: v.t_picture is not None)
            # the clock of a loaded machine is no test (the viewer's own
            # measure below is): said, not checked
            ms = (v.t_picture - v.t_asked) * 1000 if v.t_picture else -1
            print('# %s: the first picture %.0f ms after the questions, %.0f ms after the start (the model\'s '
                  'load before them)' % (profile, ms, (v.t_picture or v.t_asked) * 1000 - v.t_start * 1000))
            check('a first picture', v.t_picture is not None)
            v.run_for(5, until=lambda: b'frame info' in v.out)
            check('the key typed during the wait is read: i shows the info panel', b'frame info' in v.out)
            v.run_for(5, until=lambda: re.search(rb'no answer in (\d+) ms', v.out))
            m = re.search(rb'no answer in (\d+) ms', v.out)
            waited = int(m.group(1)) if m else -1
            check('the panel: asked once, no answer, %d ms waited (at most %d)' % (waited, FIRST_PICTURE_MS),
                  0 <= waited <= FIRST_PICTURE_MS)
            v.link.send(b'i')
            v.run_for(0.3)
        # the questions, their answers, the first frames
        v.run_for(8, until=lambda: (Q_DA in v.asked or v.silent) and not v.link.busy() and
                  time.monotonic() - t0 > 1.0)
        for extra in v.extra:
            v.link.send(extra, 0.1)
        v.run_for(8, until=lambda: not v.link.busy())
        v.quiet_for(1.0, 10)
        asked = ', '.join('%r x%d' % (q, n) for q, n in v.asked.items())
        check('still running once every answer is in (%.1f s)' % (time.monotonic() - t0), v.status is None,
              'exited with status %r; asked: %s' % (v.status, asked))
        if v.status is not None:
            return 1
        # the still model in the pixels the terminal said it draws, late
        # answers too (a slow link's come after the viewer's wait, and the
        # cells it drew first give way to them); tmux passes no images
        want = PIXELS[profile]
        got = [name for name, head in IMAGE_HEADS.items() if head in v.out]
        check('the still model drawn in %s (images seen: %s)' % (want, ', '.join(got) or 'none'),
              got == ([want] if want != 'cells' else []))
        # the cells' colours: 24-bit SGR (38;2 / 48;2) or none of it
        # (in SGR sequences alone: a sixel palette reads "#38;2;..."; and
        # not the question's own colour, 38;2;1;2;3)
        sgr = re.findall(rb'\x1b\[([0-9;:]*)m', v.out.replace(Q_SGR_SET, b''))
        direct = any(re.search(rb'(^|;)[34]8;2;', s) for s in sgr)
        palette = any(re.search(rb'(^|;)[34]8;5;', s) for s in sgr)
        want = COLOURS.get(profile, 'truecolor')
        check('the cells drawn in %s colours (24-bit SGR %s, 256 %s)' % (want, direct, palette),
              direct if want == 'truecolor' else not direct and not palette)
        # a key that turns the model: the viewer, quiet until now, draws
        # again (cells, or the image a still model is shown in)
        before = len(v.out)
        v.link.send(b'l')
        drew = v.run_for(6, until=lambda: len(v.out) - before > 300)
        check('a key turns the model (%d bytes drawn)' % (len(v.out) - before), drew and v.status is None,
              'status %r' % v.status)
        v.quiet_for(0.5, 8)
        # q quits, the terminal put back
        before = len(v.out)
        v.link.send(b'q')
        v.run_for(10, until=lambda: v.status is not None)
        while True:     # what it wrote last
            r, _, _ = select.select([v.fd], [], [], 0.2)
            if not r:
                break
            try:
                d = os.read(v.fd, 65536)
            except OSError:
                break
            if not d:
                break
            v.out += d
        code = os.waitstatus_to_exitcode(v.status) if v.status is not None else None
        check('q quits with status 0', code == 0, 'status %r' % code)
        check('the terminal is put back', b'\x1b[?1049l' in v.out[before:],
              'last bytes %r' % v.out[-200:])
    finally:
        v.kill()
    return 0 if all(results) else 1


sys.exit(main())
