#!/bin/sh
# The loading sandbox (issue 22): a stand-in assimp library whose import
# writes a file, runs a shell, opens a socket, allocates without bound or
# spins (tests/standin, built by make and found through LD_LIBRARY_PATH)
# does none of it and is one line of error; assimp's hostile cases end
# with an error and bounded memory; references out of the model's folder
# are refused with warnings and never opened (strace watches); the viewer
# survives all of it through O, and Esc ends a load that spins.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
LIB=${ZV_STANDIN_LIB:-$ROOT/build/standin}
S=$T/standin
mkdir -p "$S"
# An AddressSanitizer build (make asan): the child's sanitizer reports
# what it catches (an allocation past the limit, in operator new too) on
# stderr before zview's line, and ends the child itself; malloc may
# return NULL there as it does in the release build.
ASAN=$(ldd "$Z" 2>/dev/null | grep -c libasan)
# LeakSanitizer cannot run under strace, which watches what is opened
# here (the other tests check for leaks).
[ "$ASAN" -gt 0 ] && export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}allocator_may_return_null=1:detect_leaks=0"
# one_line FILE: zview's error is the only line of stderr (under ASan: the last)
one_line() {
    if [ "$ASAN" -gt 0 ]; then tail -1 "$T/err" | grep -q "^zview: $1: "; else
        [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "^zview: $1: " "$T/err"; fi
}
echo 'Kaydara FBX stand-in' >"$S/x.fbx"

# run_standin WHAT ARGS...: zview --info with the stand-in doing WHAT
run_standin() {
    what=$1; shift
    rm -f "$S/created" "$S/exec-ran" "$S/socket-opened"
    LD_LIBRARY_PATH=$LIB ZV_STANDIN=$what ZV_STANDIN_DIR=$S timeout 30 "$Z" --info "$@" >"$T/out" 2>"$T/err" </dev/null
    st=$?
}

if [ ! -d "$LIB" ]; then
    skip "the stand-in assimp library" "not built ($LIB): make builds it"
else
    for case in "create created" "exec exec-ran" "socket socket-opened"; do
        what=${case% *}; marker=${case#* }
        # without the sandbox the attempt is real: the test can fail
        run_standin "$what" --no-sandbox "$S/x.fbx"
        if [ -e "$S/$marker" ]; then ok "unsandboxed, the stand-in's $what happens ($marker)"; else
            notok "unsandboxed, the stand-in's $what happens ($marker)" "status $st: $(cat "$T/err")"; fi
        run_standin "$what" "$S/x.fbx"
        if [ $st -eq 1 ] && [ ! -e "$S/$marker" ] && [ "$(wc -l <"$T/err")" -eq 1 ] &&
            grep -q "^zview: $S/x.fbx: the loader tried something the sandbox forbids" "$T/err"; then
            ok "sandboxed, $what does not happen: one line naming the file, status 1"
        else notok "sandboxed, $what does not happen: one line naming the file, status 1" "status $st, $(ls "$S"): $(cat "$T/err")"; fi
    done
    rm -f "$S/created" "$S/exec-ran" "$S/socket-opened"
    LD_LIBRARY_PATH=$LIB ZV_STANDIN=create,exec ZV_STANDIN_DIR=$S timeout 30 "$Z" --info --format fbx - <"$S/x.fbx" >"$T/out" 2>"$T/err"
    st=$?
    if [ $st -eq 1 ] && [ ! -e "$S/created" ] && [ ! -e "$S/exec-ran" ] && grep -q "^zview: stdin: the loader tried" "$T/err"; then
        ok "the same from standard input"; else notok "the same from standard input" "status $st: $(cat "$T/err")"; fi
    run_standin alloc --max-memory 256M "$S/x.fbx"
    if [ $st -eq 1 ] && grep -q "^zview: $S/x.fbx: stand-in: no more memory after [0-9]* MB" "$T/err"; then
        n=$(sed -n 's/.*after \([0-9]*\) MB.*/\1/p' "$T/err")
        check_n=$([ "$n" -le 256 ] && echo yes)
        if [ "$check_n" = yes ]; then ok "allocation without bound stops at --max-memory 256M ($n MB)"; else
            notok "allocation without bound stops at --max-memory 256M" "$n MB"; fi
    else notok "allocation without bound stops at --max-memory 256M" "status $st: $(cat "$T/err")"; fi
fi

# ==== assimp's hostile cases: an error naming the file, memory bounded ====
if need_python "assimp's hostile cases"; then
    H=$T/hostile
    mkdir -p "$H"
    python3 tests/e2e/hostile_assimp.py "$H"
    for f in dag.gltf chain.gltf deep.dae count.dae chunk.glb; do
        timeout 60 "$Z" --max-memory 1G --info "$H/$f" >"$T/out" 2>"$T/err" </dev/null
        st=$?
        if [ $st -eq 1 ] && one_line "$H/$f"; then
            ok "$f: status 1, one line naming it ($(tail -1 "$T/err" | cut -c1-90 | sed "s|$H/||"))"
        else notok "$f: status 1, one line naming it" "status $st: $(head -c 300 "$T/err")"; fi
    done
    timeout 60 "$Z" --max-memory 1G --info "$H/dag.gltf" >"$T/out" 2>"$T/err" </dev/null
    if [ "$ASAN" -gt 0 ]; then
        expect_err "the node DAG runs out of its 1G (ASan ends it)" "dag.gltf: the loader failed in the sandbox"
    else
        expect_err "the node DAG runs out of its 1G, and says so" "out of memory reading it"
    fi
    timeout 60 "$Z" --max-memory 1G --info "$H/chain.gltf" >"$T/out" 2>"$T/err" </dev/null
    expect_err "the deep chain's crash is the child's" "the loader crashed (Segmentation fault) in the sandbox"
fi

# ==== references out of the model's folder: refused, never opened ====
R=$T/refs
mkdir -p "$R/m" "$R/out"
printf 'newmtl a\nKd 1 0 0\n' >"$R/out/secret.mtl"
printf 'SECRET' >"$R/out/secret.bin"
ln -s ../out/secret.mtl "$R/m/link.mtl"
ln -s ../out/secret.bin "$R/m/link.bin"
ln -s /dev/zero "$R/m/zero.mtl"
mkfifo "$R/m/fifo.mtl" "$R/m/fifo.bin"
tri='v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'
n=0
for ref in ../out/secret.mtl "$R/out/secret.mtl" link.mtl /dev/zero zero.mtl fifo.mtl; do
    n=$((n + 1))
    printf "mtllib $ref\n$tri" >"$R/m/r$n.obj"
    if command -v strace >/dev/null 2>&1; then
        timeout 20 strace -f -qq -o "$T/trace" -e trace=open,openat,openat2 "$Z" --info "$R/m/r$n.obj" >"$T/out" 2>"$T/err" </dev/null
        st=$?
        opened=$(grep -E 'secret|/dev/zero|zero.mtl|fifo' "$T/trace" | grep -v ' = -1 ' | grep -v 'O_PATH' | head -3)
    else
        timeout 20 "$Z" --info "$R/m/r$n.obj" >"$T/out" 2>"$T/err" </dev/null
        st=$?
        opened="strace is missing (tools/deps.sh installs it)"
    fi
    if [ $st -eq 0 ] && grep -qF "cannot open material library '$ref' (refused: " "$T/err" && [ -z "$opened" ]; then
        ok "mtllib $ref: refused with a warning naming it, nothing opened ($(sed 's/.*(refused: \(.*\))/\1/' "$T/err"))"
    else notok "mtllib $ref: refused with a warning naming it, nothing opened" "status $st, opened: $opened; $(cat "$T/err")"; fi
done
# a texture out of the folder, through a library inside it
printf 'newmtl a\nKd 1 1 1\nmap_Kd ../out/secret.bin\n' >"$R/m/t.mtl"
printf "mtllib t.mtl\nusemtl a\nvt 0 0\nvt 1 0\nvt 0 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\n" >"$R/m/t.obj"
expect_status "a texture named by ../ loads the model" 0 "$Z" --info "$R/m/t.obj"
expect_err "... and refuses the texture, by name" "texture $R/m/../out/secret.bin: refused: '..' leads out of the model's folder"
# a model on standard input names nothing, not even beside the working folder
(cd "$R/out" && printf "mtllib secret.mtl\n$tri" | "$Z" --info - >"$T/out" 2>"$T/err")
expect_err "a model on standard input may name no file" "cannot open material library 'secret.mtl' (refused: a model on standard input may name no other file)"

# glTF buffers: by .., absolute, a link out, /dev/zero, a FIFO
if "$Z" --formats 2>/dev/null | grep -q '^gltf'; then
    n=0
    for uri in ../out/secret.bin "$R/out/secret.bin" link.bin /dev/zero fifo.bin; do
        n=$((n + 1))
        printf '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"buffers":[{"byteLength":36,"uri":"%s"}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}]}' "$uri" >"$R/m/b$n.gltf"
        if command -v strace >/dev/null 2>&1; then
            timeout 20 strace -f -qq -o "$T/trace" -e trace=open,openat,openat2 "$Z" --info "$R/m/b$n.gltf" >"$T/out" 2>"$T/err" </dev/null
            st=$?
            opened=$(grep -E 'secret|/dev/zero|fifo' "$T/trace" | grep -v ' = -1 ' | grep -v 'O_PATH' | head -3)
        else
            timeout 20 "$Z" --info "$R/m/b$n.gltf" >"$T/out" 2>"$T/err" </dev/null
            st=$?
            opened="strace is missing (tools/deps.sh installs it)"
        fi
        if [ $st -eq 1 ] && grep -q "is not read (refused: " "$T/err" && [ -z "$opened" ] && ! grep -q bounds "$T/out"; then
            ok "glTF buffer $uri: refused with a warning, nothing opened, status 1"
        else notok "glTF buffer $uri: refused with a warning, nothing opened, status 1" "status $st, opened: $opened; $(cat "$T/err")"; fi
    done
fi

# a uri naming the model's own folder, absolute (directly and through a
# link to the folder): read, in the sandbox too (issue 28: it was refused
# as outside the folder)
if "$Z" --formats 2>/dev/null | grep -q '^gltf'; then
    python3 -c 'import struct, sys; open(sys.argv[1], "wb").write(struct.pack("<9f", 0,0,0, 1,0,0, 0,1,0))' "$R/m/tri.bin"
    ln -s m "$R/mlink"
    for uri in "$R/m/tri.bin" "$R/mlink/tri.bin"; do
        printf '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"buffers":[{"byteLength":36,"uri":"%s"}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}]}' "$uri" >"$R/m/own.gltf"
        for sb in "" --no-sandbox; do
            timeout 20 "$Z" --info $sb "$R/m/own.gltf" >"$T/out" 2>"$T/err" </dev/null
            st=$?
            if [ $st -eq 0 ] && grep -q '^faces: *1$' "$T/out" && [ ! -s "$T/err" ]; then
                ok "glTF buffer ${uri#"$R"/} (absolute, in the folder) ${sb:-sandboxed}: read, no warning"
            else notok "glTF buffer ${uri#"$R"/} (absolute, in the folder) ${sb:-sandboxed}: read, no warning" "status $st: $(cat "$T/err")"; fi
        done
    done
fi

# ==== the result's way back: the child's memory, else the memfd ====
if command -v strace >/dev/null 2>&1; then
    # --info without its timing line
    info() { "$@" 2>&1 | grep -v '^load:\|scored in'; }
    info "$Z" --info --no-sandbox assets/demo.obj >"$T/want"
    info strace -f -qq -o "$T/trace" -e trace=process_vm_readv "$Z" --info assets/demo.obj >"$T/out"
    if grep -aq 'process_vm_readv(.*) = [1-9]' "$T/trace" && cmp -s "$T/want" "$T/out"; then
        ok "the mesh is copied out of the child's memory, and is the mesh loaded in-process"
    else notok "the mesh is copied out of the child's memory, and is the mesh loaded in-process" "$(diff "$T/want" "$T/out" | head -5)"; fi
    # where reading another process is not allowed (ptrace rules), the memfd
    info strace -f -qq -o /dev/null -e trace=process_vm_readv -e inject=process_vm_readv:error=EPERM \
        "$Z" --info assets/demo.obj >"$T/out"
    if cmp -s "$T/want" "$T/out"; then ok "process_vm_readv refused: the same mesh through the memfd"; else
        notok "process_vm_readv refused: the same mesh through the memfd" "$(diff "$T/want" "$T/out" | head -5)"; fi
else
    skip "the result's way back" "no strace (tools/deps.sh installs it)"
fi

# ==== the viewer: O survives each, Esc ends a load that spins ====
[ -d "$LIB" ] || exit 0
. "$(dirname "$0")/tmux.sh"
for f in create-exec-socket.fbx alloc.fbx spin.fbx; do echo 'Kaydara FBX stand-in' >"$S/$f"; done
rm -f "$S/created" "$S/exec-ran" "$S/socket-opened"
session xterm-256color 100 30
tm send-keys -t zv "LD_LIBRARY_PATH=$LIB ZV_STANDIN_DIR=$S TERM=xterm-256color sh -c 'echo \$\$ >$T/pid; exec $Z --max-memory 256M --mode ascii assets/cube.obj'; echo zv-exit=\$?" Enter
wait_for 'cube.obj \| (6/6|faces 6 drawn)' >/dev/null
# open_file PATH: O, the path, Enter
open_file() {
    tm send-keys -t zv O
    wait_for '^ open:' >/dev/null
    tm send-keys -t zv -l "$1"
    tm send-keys -t zv Enter
}
open_file "$S/create-exec-socket.fbx"
if wait_for 'create-exec-socket.fbx: the loader tried' && wait_for 'cube.obj \| (6/6|faces 6 drawn)' &&
    [ ! -e "$S/created" ] && [ ! -e "$S/exec-ran" ] && [ ! -e "$S/socket-opened" ]; then
    ok "O: the stand-in's attacks stop the load, nothing happens, the scene stays"
else notok "O: the stand-in's attacks stop the load, nothing happens, the scene stays" "$(ls "$S"); $(tail -2 "$T/screen")"; fi
open_file "$S/alloc.fbx"
if wait_for 'alloc.fbx: stand-in: no more memory after' && wait_for 'cube.obj \| (6/6|faces 6 drawn)'; then
    ok "O: allocation without bound ends at --max-memory, the scene stays"
else notok "O: allocation without bound ends at --max-memory, the scene stays" "$(tail -2 "$T/screen")"; fi
open_file "$S/spin.fbx"
wait_for 'loading spin.fbx' >/dev/null
zpid=$(cat "$T/pid")
kids=$(ps -o pid= --ppid "$zpid" | wc -l)
tm send-keys -t zv Escape
left=1
i=0
# a bounded wait (10 s on a busy machine), not a timing: the child goes
# within a poll of the cancel (50 ms) once the key is read
while [ $i -lt 50 ]; do
    left=$(ps -o pid= --ppid "$zpid" | wc -l)
    [ "$left" -eq 0 ] && break
    sleep 0.2
    i=$((i + 1))
done
cap
if [ "$kids" -eq 1 ] && [ "$left" -eq 0 ] && wait_for 'cancelled loading spin.fbx' && wait_for 'cube.obj \| (6/6|faces 6 drawn)'; then
    ok "Esc ends a load that spins: its child is gone, the scene stays"
else notok "Esc ends a load that spins: its child is gone, the scene stays" "children $kids then $left; $(tail -2 "$T/screen")"; fi
tm send-keys -t zv q
if wait_for 'zv-exit=0'; then ok "the viewer quits normally after all of it"; else notok "the viewer quits normally after all of it" "$(tail -3 "$T/screen")"; fi

# assimp's hostile cases through O, with the real library
if [ -n "${H:-}" ] && [ -e "$H/chain.gltf" ]; then
    session xterm-256color 100 30
    tm send-keys -t zv "TERM=xterm-256color $Z --max-memory 1G --mode ascii assets/cube.obj; echo zv-exit=\$?" Enter
    wait_for 'cube.obj \| (6/6|faces 6 drawn)' >/dev/null
    for f in dag.gltf chain.gltf deep.dae count.dae chunk.glb; do
        open_file "$H/$f"
        if wait_for "$f: " && wait_for 'cube.obj \| (6/6|faces 6 drawn)'; then ok "O $f: a message naming it, the scene stays"; else
            notok "O $f: a message naming it, the scene stays" "$(tail -2 "$T/screen")"; fi
    done
    tm send-keys -t zv q
    if wait_for 'zv-exit=0'; then ok "... and the viewer quits normally"; else notok "... and the viewer quits normally" "$(tail -3 "$T/screen")"; fi
fi
