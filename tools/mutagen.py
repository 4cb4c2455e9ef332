#!/usr/bin/env python3
"""mutagen.py [--per-room N] [--seed S] [ROOM...]: mechanical mutants.

The hand-written mutants of tests/mutants.txt say what a user would see;
these are the blind ones that find what nobody thought of. For each room
under src/ (or the rooms named), N lines are drawn at random (seeded, so
a run can be repeated) among those that hold a mutation site, and one
site of each is changed:

  relational   <  <=  >  >=  ==  !=   each to its neighbour (< to <=, == to !=, ...)
  logical      &&  ||                 swapped
  arithmetic   a + b  a - b  a * b    + and - swapped, * to +
  constant     an integer literal k   k + 1 (0 to 1, 1 to 2, ...)

Lines that only describe (comments, preprocessor lines, messages in
printf-style calls, asserts) are left out: a changed message is not a
changed behaviour. A line whose text is not unique in its file is left
out too (tools/mutate.sh applies a mutant by finding its text once).

The mutants are printed in the format of tests/mutants.txt, named
auto-ROOM-K, for tools/mutate.sh:

  tools/mutagen.py --per-room 10 > build/mutants-auto.txt
  sh tools/mutate.sh build/mutants-auto.txt

(`make mutate-rooms` does both, and prints the kill rate per room.)
"""
import argparse
import os
import random
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# an operator with what it becomes; longer ones first so that '<=' is not
# read as '<'
RELATIONAL = [('<=', '<'), ('>=', '>'), ('==', '!='), ('!=', '=='), ('<', '<='), ('>', '>=')]
SKIP_LINE = re.compile(r'^\s*(#|//|/\*|\*|\}|\{|$)|ZV_ASSERT|assert\(|printf|fprintf|snprintf|'
                       r'me_fail|bad\(|viewer_note|perror|fputs|out_printf|return me_|"[^"]*"\s*[,)]')
INT = re.compile(r'(?<![\w.])(\d+)(?![\w.])')


def code_part(line):
    """The line without a trailing comment and with strings blanked, so
    that sites inside them are not found."""
    line = re.sub(r'"(\\.|[^"\\])*"', lambda m: '"' + ' ' * (len(m.group(0)) - 2) + '"', line)
    line = re.sub(r"'(\\.|[^'\\])*'", lambda m: "'" + ' ' * (len(m.group(0)) - 2) + "'", line)
    i = line.find('/*')
    if i >= 0:
        line = line[:i] + ' ' * (len(line) - i)
    i = line.find('//')
    if i >= 0:
        line = line[:i] + ' ' * (len(line) - i)
    return line


def sites(line):
    """Every (start, end, replacement, kind) a line offers."""
    code = code_part(line)
    out = []
    # relational: not part of <<, >>, ->, <<=, >>=, or a #include <...>
    i = 0
    while i < len(code):
        for op, to in RELATIONAL:
            if code.startswith(op, i):
                prev = code[i - 1] if i > 0 else ' '
                nxt = code[i + len(op)] if i + len(op) < len(code) else ' '
                if prev in '<>-=!' or nxt in '<>=' and len(op) == 1 or (op in ('<', '>') and nxt == op):
                    break
                if op == '>' and prev == '-':
                    break
                # a declaration's template-like use or a cast is not C here;
                # only spaced comparisons, the house style
                if prev == ' ' and nxt == ' ':
                    out.append((i, i + len(op), to, 'relational'))
                i += len(op) - 1
                break
        i += 1
    for m in re.finditer(r' (&&|\|\|) ', code):
        out.append((m.start(1), m.end(1), '||' if m.group(1) == '&&' else '&&', 'logical'))
    for m in re.finditer(r'(?<=[\w)\]]) ([+\-*]) (?=[\w(])', code):
        op = m.group(1)
        out.append((m.start(1), m.end(1), {'+': '-', '-': '+', '*': '+'}[op], 'arithmetic'))
    # constants, but not an allocation's count (calloc(1, n) and calloc(2,
    # n) differ in nothing a test can see)
    if not re.search(r'\b(calloc|malloc|realloc|grow_array)\(', code):
        for m in INT.finditer(code):
            out.append((m.start(1), m.end(1), str(int(m.group(1)) + 1), 'constant'))
    return out


def candidates(path):
    with open(path, encoding='utf-8', errors='replace') as f:
        text = f.read()
    lines = text.split('\n')
    in_comment = False
    for n, line in enumerate(lines, 1):
        s = line.strip()
        if in_comment:
            if '*/' in s:
                in_comment = False
            continue
        if s.startswith('/*') and '*/' not in s:
            in_comment = True
            continue
        if SKIP_LINE.search(line) or len(s) < 8:
            continue
        if text.count(s) != 1:
            continue
        found = sites(line)
        if found:
            yield n, line, found


def read_list(path):
    """name -> ((file, from, to), why) of a list in the format of tests/mutants.txt."""
    out, cur = {}, None
    with open(path, encoding='utf-8', errors='replace') as f:
        for line in f:
            line = line.rstrip('\n')
            if line.startswith('name:'):
                cur = line.split()[1]
                out[cur] = ['', [], [], []]
            elif cur and line.startswith('file:'):
                out[cur][0] = line[5:].strip()
            elif cur and line.startswith('from:'):
                out[cur][1].append(line[5:].strip())
            elif cur and line.startswith('to:'):
                out[cur][2].append(line[3:].strip())
            elif cur and line.startswith('why:'):
                out[cur][3].append(line[4:].strip())
    return {n: ((v[0], '\n'.join(v[1]), '\n'.join(v[2])), ' '.join(v[3])) for n, v in out.items()}


def summary(log, mutants=None, equivalents=None):
    """Per room: the mutants run, killed, survived and equivalent, and the
    kill rate of the others (killed / (run - equivalent)). Equivalent: the
    compiler made the same code of it (SAME in the log), or the list
    EQUIVALENTS explains why no behaviour can change (a mutant is matched
    by its file, text and replacement, not its name, which is only the
    draw's)."""
    explained = {}
    if mutants and equivalents:
        eq = dict(read_list(equivalents).values())
        explained = {n: eq[v] for n, (v, _) in read_list(mutants).items() if v in eq}
    rooms = {}
    with open(log, encoding='utf-8', errors='replace') as f:
        for line in f:
            m = re.match(r'^(killed|SURVIVED|SAME) +auto-([a-z]+)-(\d+)', line)
            if not m:
                continue
            name = 'auto-%s-%s' % (m.group(2), m.group(3))
            r = rooms.setdefault(m.group(2), {'run': 0, 'killed': 0, 'same': [], 'explained': [], 'survived': []})
            r['run'] += 1
            if m.group(1) == 'killed':
                r['killed'] += 1
            elif m.group(1) == 'SAME':
                r['same'].append(name)
            elif name in explained:
                r['explained'].append(name)
            else:
                r['survived'].append(name)
    print('room      run killed survived equivalent  rate')
    worst = 100.0
    tot = {'run': 0, 'killed': 0, 'surv': 0, 'eq': 0}
    for room in sorted(rooms):
        r = rooms[room]
        eq = len(r['same']) + len(r['explained'])
        live = r['run'] - eq
        pct = 100.0 * r['killed'] / live if live else 100.0
        worst = min(worst, pct)
        print('%-8s %4d %6d %8d %10d %5.0f%%%s' % (room, r['run'], r['killed'], len(r['survived']), eq, pct,
              ('  survived: ' + ' '.join(r['survived'])) if r['survived'] else ''))
        tot['run'] += r['run']
        tot['killed'] += r['killed']
        tot['surv'] += len(r['survived'])
        tot['eq'] += eq
    live = tot['run'] - tot['eq']
    print('%-8s %4d %6d %8d %10d %5.0f%%  (the weakest room %.0f%%)' % (
        'all', tot['run'], tot['killed'], tot['surv'], tot['eq'], 100.0 * tot['killed'] / max(live, 1), worst))
    for room in sorted(rooms):
        for n in rooms[room]['same']:
            print('equivalent %s: the same code' % n)
        for n in rooms[room]['explained']:
            print('equivalent %s: %s' % (n, explained[n]))
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--per-room', type=int, default=10)
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--summary', metavar='LOG', help="the kill rate per room from tools/mutate.sh's output")
    ap.add_argument('--list', metavar='MUTANTS', help='with --summary: the list the run applied')
    ap.add_argument('--equivalent', metavar='LIST', help='with --summary: the mutants explained as equivalent')
    ap.add_argument('rooms', nargs='*')
    a = ap.parse_args()
    if a.summary:
        return summary(a.summary, a.list, a.equivalent)
    src = os.path.join(ROOT, 'src')
    rooms = a.rooms or sorted(d for d in os.listdir(src) if os.path.isdir(os.path.join(src, d)))
    rng = random.Random(a.seed)
    print('# mechanical mutants (tools/mutagen.py --per-room %d --seed %d): not hand-written;' %
          (a.per_room, a.seed))
    print('# each changes one operator or constant on a line drawn at random.\n')
    for room in rooms:
        pool = []
        d = os.path.join(src, room)
        for name in sorted(os.listdir(d)):
            if name.endswith('.c') or name.endswith('.h'):
                rel = 'src/%s/%s' % (room, name)
                pool += [(rel, n, line, found) for n, line, found in candidates(os.path.join(ROOT, rel))]
        rng.shuffle(pool)
        for k, (rel, n, line, found) in enumerate(pool[:a.per_room], 1):
            start, end, to, kind = rng.choice(found)
            mutated = line[:start] + to + line[end:]
            print('name: auto-%s-%d' % (room, k))
            print('file: %s' % rel)
            print('from: %s' % line.strip())
            print('to:   %s' % mutated.strip())
            print('why:  mechanical (%s, line %d): %s -> %s' % (kind, n, line[start:end], to))
            print()
    return 0


sys.exit(main())
