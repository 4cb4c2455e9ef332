#!/bin/sh
# Rewrite the text captures of the documents from the program: each
# ```text block whose first line is "$ zview ARGS" gets the output of
# zview ARGS (trailing blanks dropped) in place of its old lines.
# tests/e2e/test_docs.sh fails until this is run after a change to what
# --print draws. Usage: sh tools/captures.sh [FILE.md ...]
set -eu
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
Z=${ZVIEW:-$ROOT/zview}
unset COLORFGBG     # the captures are of a dark terminal's picture, wherever they are made
[ $# -gt 0 ] || set -- README.md CONTRIBUTING.md doc/design.md doc/benchmarks.md
for doc in "$@"; do
    [ -f "$doc" ] || continue
    awk -v zv="$Z" '
        /^```text$/ {
            print
            if ((getline line) <= 0) exit
            print line
            if (substr(line, 1, 8) != "$ zview ")
                next
            cmd = zv " " substr(line, 9) " </dev/null"
            while ((cmd | getline out) > 0) {
                sub(/[ \t]+$/, "", out)
                print out
            }
            close(cmd)
            while ((getline line) > 0 && line !~ /^```/)
                ;
            print line
            next
        }
        { print }' "$doc" >"$doc.new"
    if cmp -s "$doc" "$doc.new"; then rm "$doc.new"; else mv "$doc.new" "$doc" && echo "captures: rewrote $doc"; fi
done
