#!/usr/bin/env python3
"""looks.py: ANSI text (a --print frame, or a tmux capture-pane -e) ->
one line per row of what each cell looks like, so that two ways of
drawing the same picture compare equal.

A terminal may draw a cell in several ways that look alike: an upper half
block of a on b is a lower half block of b on a, a space on c is a full
block of c, and the colour behind a space's foreground is never seen.
Cells of that family become "top/bottom" colours; any other cell keeps
its glyph and both colours. Palette colours are numbers however they were
written (31, 91, 38;5;1), 24-bit ones r:g:b; the default foreground and
background are "F" and "B" (different colours). Blank cells at the end of
a row are dropped (tmux trims them).

usage: looks.py [--colours] < text      --colours: list the colours used
"""
import re
import sys

BLOCKS = {" ", "\u2588", "\u2580", "\u2584"}


def colour(params, i, bg):
    """The colour at params[i] (38/48 forms included) and the next index."""
    p = params[i]
    if p in (38, 48):
        if len(params) > i + 2 and params[i + 1] == 5:
            return str(params[i + 2]), i + 3
        if len(params) > i + 4 and params[i + 1] == 2:
            return "%d:%d:%d" % tuple(params[i + 2:i + 5]), i + 5
        return ("B" if bg else "F"), len(params)
    if 30 <= p <= 37 or 40 <= p <= 47:
        return str(p % 10), i + 1
    if 90 <= p <= 97 or 100 <= p <= 107:
        return str(p % 10 + 8), i + 1
    return ("B" if bg else "F"), i + 1


def rows(text):
    fg, bg, rev = "F", "B", False
    out = []
    for line in text.split("\n"):
        cells = []
        for tok in re.findall(r"\x1b\[[0-9;]*[A-Za-z]|\x1b.|.", line):
            if tok.startswith("\x1b"):
                if not tok.endswith("m"):
                    continue
                params = [int(x) if x else 0 for x in tok[2:-1].split(";")] or [0]
                i = 0
                while i < len(params):
                    p = params[i]
                    if p == 0:
                        fg, bg, rev = "F", "B", False
                        i += 1
                    elif p == 7:
                        rev, i = True, i + 1
                    elif p == 27:
                        rev, i = False, i + 1
                    elif p in (39,) or 30 <= p <= 38 or 90 <= p <= 97:
                        fg, i = colour(params, i, False) if p != 39 else ("F", i + 1)
                    elif p in (49,) or 40 <= p <= 48 or 100 <= p <= 107:
                        bg, i = colour(params, i, True) if p != 49 else ("B", i + 1)
                    else:
                        i += 1
                continue
            cells.append(look(tok, fg, bg, rev))
        while cells and cells[-1] == ("blk", "B", "B"):
            cells.pop()
        out.append(cells)
    while out and not out[-1]:
        out.pop()
    return out


def look(ch, fg, bg, rev):
    """("blk", top, bottom) for the block family, else ("txt", glyph, fg, bg, rev)."""
    if ch in BLOCKS and not rev:
        top, bottom = {
            " ": (bg, bg),
            "\u2588": (fg, fg),
            "\u2580": (fg, bg),
            "\u2584": (bg, fg),
        }[ch]
        return ("blk", top, bottom)
    return ("txt", ch, fg, bg, "rev" if rev else "")


def show(c):
    return "%s/%s" % c[1:] if c[0] == "blk" else "%s:%s:%s:%s" % c[1:]


def main():
    text = sys.stdin.buffer.read().decode("utf-8", "replace")
    rs = rows(text)
    if "--colours" in sys.argv:
        used = set()
        for r in rs:
            for c in r:
                used.update(c[1:3] if c[0] == "blk" else c[2:4])
        print(" ".join(sorted(used)))
        return
    for r in rs:
        print(" ".join(show(c) for c in r))


main()
