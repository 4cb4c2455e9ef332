#!/bin/sh
# Every file of Debian's assimp test models (assimp-testmodels, installed
# by tools/deps.sh) through zview --info (issue 28; corpus.py walks it,
# two at a time; about 600 loads, so make test-long runs it, not make
# test): a refusal is one line naming the file, assimp's words
# and a library's own output included; nothing raw reaches the terminal;
# no reference inside a model's folder is refused as outside it.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
A=/usr/share/assimp/models
if [ ! -d "$A" ] || ! "$Z" --formats 2>/dev/null | grep -q assimp; then
    skip "the assimp corpus" "no assimp or no $A (tools/deps.sh)"
    exit 0
fi
need_python "the assimp corpus" || exit 0
# a checking build (make asan) passes a library's own lines on
asan=$(ldd "$Z" 2>/dev/null | grep -q libasan && echo asan)
python3 tests/e2e/corpus.py "$Z" "$A" $asan >"$T/out" 2>"$T/err"
n() { sed -n "s/^$1 //p" "$T/out"; }
# bad WORDS: the first files that break the rule WORDS names
bad() { grep '^bad: ' "$T/out" | grep -E "$1" | head -5; }
files=$(n files)
if [ "${files:-0}" -gt 500 ]; then ok "the corpus walked: $files files, $(n refused) refused"; else
    notok "the corpus walked" "$(cat "$T/out" "$T/err" | head -c 500)"; fi
if [ "$(n 'refusals of more than one line')" = 0 ] && [ "$(n 'refusals not naming the file')" = 0 ]; then
    ok "every refusal is one line naming the file"
else notok "every refusal is one line naming the file" "$(bad 'lines|does not name')"; fi
if [ "$(n 'control bytes')" = 0 ]; then ok "... and no output holds a control byte"; else
    notok "... and no output holds a control byte" "$(bad 'control bytes')"; fi
if [ "$(n 'outside the folder')" = 0 ]; then
    ok "no reference is refused as outside its model's folder ($(n "leaving the folder by '..'") files name one by '..', refused)"
else notok "no reference is refused as outside its model's folder" "$(bad 'outside its folder')"; fi
if [ -z "$(bad .)" ]; then ok "no file breaks a rule"; else notok "no file breaks a rule" "$(bad .)"; fi
