#!/bin/sh
# -j 1 starts no thread to parse (issue 29): every path that loads (the
# one-shot output, --check, the viewer's first load, O and --watch) builds
# its loader's options in one place (app_load_opts), so none parses a big
# OBJ on every core when told one. The threads are counted from strace's
# clone calls (threads.py): in zview's own process and in the loading
# children, apart. -j 2 on the same file is the control: it does start
# them, so the checks can fail.
. "$(dirname "$0")/lib.sh"
. "$(dirname "$0")/tmux.sh"
for tool in strace python3; do
    command -v "$tool" >/dev/null 2>&1 || { skip "-j 1 starts no thread" "no $tool"; exit 0; }
done

# an OBJ of 24 MB, past the parse's two pieces of 8 MB (objpar.c), so that more
# than one thread would be used
awk 'BEGIN { n = 640; for (i = 0; i < n; i++) for (j = 0; j < n; j++) printf "v %.6f %.6f %.6f\n", i / n, j / n, (i * j) % 7 / 70.0;
             for (i = 0; i < n - 1; i++) for (j = 0; j < n - 1; j++) { a = i * n + j + 1; printf "f %d %d %d %d\n", a, a + 1, a + n + 1, a + n } }' >"$T/big.obj"
trace() { strace -f -qq -e trace=clone,clone3,fork,vfork -o "$T/st" "$@" >/dev/null 2>&1 </dev/null; }
counts() { python3 tests/e2e/threads.py "$T/st"; }

trace "$Z" -j 1 -o "$T/b.png" --size 64x48 "$T/big.obj"
c=$(counts)
check "-o with -j 1: no thread in zview or its loader ($c)" '[ "$c" = "0 0" ]' "$c"
trace "$Z" -j 2 -o "$T/b.png" --size 64x48 "$T/big.obj"
c=$(counts)
check "... with -j 2 the loader parses on two ($c)" '[ "${c#* }" -ge 1 ]' "$c"

trace "$Z" -j 1 --check "$T/big.obj"
c=$(counts)
check "--check with -j 1: no thread ($c; before issue 29, one a core)" '[ "$c" = "0 0" ]' "$c"
trace "$Z" -j 2 --check "$T/big.obj"
c=$(counts)
check "... with -j 2 it does ($c)" '[ "${c#* }" -ge 1 ]' "$c"

# the viewer: its own threads (loading in the background, checking) are
# its way of working; the loading children's are the parse's
faces=$(grep -c '^f ' "$T/big.obj")
cube=$(grep -c '^f ' assets/cube.obj)
viewer() {
    session xterm-256color 100 30
    tm send-keys -t zv "TERM=xterm-256color strace -f -qq -e trace=clone,clone3,fork,vfork -o $T/st $Z $*; echo zv-exit=\$?" Enter
}
quit() { tm send-keys -t zv q; WAIT_POLLS=600 wait_for 'zv-exit=' >/dev/null; }

for j in 1 2; do
    viewer -j $j "$T/big.obj"
    WAIT_POLLS=1200 wait_for "faces $faces " >/dev/null
    quit
    c=$(counts)
    if [ $j = 1 ]; then
        check "the viewer's first load with -j 1: no thread in the loader (${c#* })" '[ "${c#* }" = 0 ]' "$c"
    else
        check "... with -j 2 it does (${c#* })" '[ "${c#* }" -ge 1 ]' "$c"
    fi
done

viewer -j 1 assets/cube.obj
wait_for "faces $cube drawn" >/dev/null
tm send-keys -t zv O
wait_for '^ open:$' >/dev/null
tm send-keys -t zv -l "$T/big.obj"
tm send-keys -t zv Enter
WAIT_POLLS=1200 wait_for "faces $((faces + cube)) " >/dev/null
status_o=$(tail -1 "$T/screen")
quit
c=$(counts)
check "O with -j 1: the file opened ($status_o)" 'echo "$status_o" | grep -q "faces $((faces + cube)) "' "$status_o"
check "... and no thread in the loader (${c#* }; before issue 29, one a core)" '[ "${c#* }" = 0 ]' "$c"

cp assets/cube.obj "$T/w.obj"
viewer -j 1 --watch "$T/w.obj"
wait_for "faces $cube drawn" >/dev/null
cp "$T/big.obj" "$T/w.new"
mv "$T/w.new" "$T/w.obj"
WAIT_POLLS=1200 wait_for "faces $faces " >/dev/null
status_w=$(tail -1 "$T/screen")
quit
c=$(counts)
check "--watch with -j 1: the new file read ($status_w)" 'echo "$status_w" | grep -q "faces $faces "' "$status_w"
check "... and no thread in the loader (${c#* }; before issue 29, one a core)" '[ "${c#* }" = 0 ]' "$c"
