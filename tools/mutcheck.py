#!/usr/bin/env python3
"""mutcheck.py LIST SRC [NAME...]: every mutant of LIST (tests/mutants.txt's
format, described at its top) still applies to the tree at SRC: it names
a file there, has a why:, its from: text occurs exactly once in that file,
and its change changes something. Used by tools/mutate.sh, before a run
and for --check (make test); one process for the whole list, where the
shell's loop started five awk processes a mutant (10 s of make test's CPU).

The snippets are read as mutate.sh's awk applies them: the first from:
(to:) line's leading blanks dropped, each next line's one leading space,
the lines joined by newlines. ZV_MUTANT (a mutant applied in SRC) and the
mutants of the file ZV_MUTANT_FILE names are not checked: their text is
gone from SRC by design. Prints one line per problem; exit status 2 when
there is one, else 0."""

import os
import sys


def parse(path):
    """The mutants in file order: name -> {key: [values]}, and the names."""
    mutants, order, cur = {}, [], None
    with open(path, encoding="utf-8", errors="surrogateescape") as f:
        for line in f.read().split("\n"):
            if line.startswith("name:"):
                words = line.split()
                cur = words[1] if len(words) > 1 else ""
                if cur not in mutants:
                    mutants[cur] = {}
                    order.append(cur)
                continue
            if cur is None:
                continue
            for key in ("file", "from", "to", "why"):
                if line.startswith(key + ":"):
                    mutants[cur].setdefault(key, []).append(line[len(key) + 1:])
                    break
    return mutants, order


def snippet(lines):
    """from: or to: lines as one text (mutate.sh's joining)."""
    if not lines:
        return ""
    first = lines[0].lstrip(" \t")
    rest = [l[1:] if l.startswith(" ") else l for l in lines[1:]]
    return "\n".join([first] + rest)


def where(src, text):
    """The files under src/ and include/ holding text."""
    found = []
    for top in ("src", "include"):
        for dirpath, _, files in os.walk(os.path.join(src, top)):
            for name in files:
                p = os.path.join(dirpath, name)
                try:
                    with open(p, encoding="utf-8", errors="surrogateescape") as f:
                        if text in f.read():
                            found.append(os.path.relpath(p, src))
                except OSError:
                    pass
    return sorted(found)


def main(argv):
    if len(argv) < 3:
        print("usage: mutcheck.py LIST SRC [NAME...]", file=sys.stderr)
        return 2
    listpath, src, names = argv[1], argv[2], argv[3:]
    mutants, order = parse(listpath)
    skip_name = os.environ.get("ZV_MUTANT", "")
    skip_file = os.environ.get("ZV_MUTANT_FILE", "")
    bad = 0
    for m in names or order:
        if m == skip_name:
            continue
        mu = mutants.get(m)
        f = " ".join(v.lstrip(" \t") for v in mu.get("file", [])) if mu else ""
        if skip_file and f == skip_file:
            continue
        if mu is None:
            print(f"mutate: {m}: no such mutant in {listpath}", file=sys.stderr)
            bad = 1
            continue
        path = os.path.join(src, f)
        if not f or not os.path.isfile(path):
            print(f"mutate: {m}: no file '{f}'", file=sys.stderr)
            bad = 1
            continue
        if not " ".join(v.lstrip(" \t") for v in mu.get("why", [])):
            print(f"mutate: {m}: no why: (what a user would see if it went in)", file=sys.stderr)
            bad = 1
            continue
        frm = snippet(mu.get("from", []))
        to = snippet(mu.get("to", []))
        with open(path, encoding="utf-8", errors="surrogateescape") as fh:
            text = fh.read()
        n = text.count(frm) if frm else 0
        if n != 1:
            first = frm.split("\n")[0]
            files = " ".join(where(src, first)) if first else ""
            print(f"mutate: {m}: its text occurs {n} times in {f}, not once "
                  f"(its first line is in: {files or 'no file'})", file=sys.stderr)
            bad = 1
        elif frm == to:
            print(f"mutate: {m}: changes nothing", file=sys.stderr)
            bad = 1
    return 2 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
