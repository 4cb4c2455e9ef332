#!/bin/sh
# The command line: exit statuses, error messages naming file and line,
# one-shot outputs and their formats.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW

expect_status "help exits 0" 0 "$Z" --help
expect_out "help lists --algo" "--algo"
expect_status "version exits 0" 0 "$Z" --version
expect_out "version names zview" "zview"
expect_status "unknown option is a usage error" 2 "$Z" --frobnicate
expect_err "unknown option is named" "--frobnicate"
expect_status "bad --size is a usage error" 2 "$Z" --size 12 assets/cube.obj
expect_status "unknown algorithm is a usage error" 2 "$Z" --algo painter assets/cube.obj

expect_status "missing file fails" 1 "$Z" --print no/such/file.obj
expect_err "missing file is named" "no/such/file.obj"
# a folder alone is the gallery (issue 34); beside a model it is no model
expect_status "a folder alone is the gallery" 0 "$Z" --print --size 80x12 --color none assets
expect_out "... of its models" "models: "
expect_status "a folder beside a model is left out" 0 "$Z" --print assets/cube.obj assets
expect_err "... named as a folder" "assets: is a directory"
# A bad statement: --strict refuses the file with file:line; by default
# it is skipped, and a file with nothing else left still fails, naming it
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n' >"$T/zero.obj"
expect_status "index 0 fails with --strict" 1 "$Z" --strict --print "$T/zero.obj"
expect_err "index 0 names file and line" "zero.obj:4:"
expect_status "index 0 in the only face fails anyway" 1 "$Z" --print "$T/zero.obj"
expect_err "... naming file, line and why nothing is left" "zero.obj:4: vertex index 0 is invalid (indices start at 1; 3 vertices) (1 statement skipped, nothing left to show)"
printf 'v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n' >"$T/nan.obj"
expect_status "NaN fails with --strict" 1 "$Z" --strict --print "$T/nan.obj"
expect_err "NaN names file and line" "nan.obj:3:"
expect_status "NaN in the only face's vertex fails anyway" 1 "$Z" --print "$T/nan.obj"
expect_err "... naming the vertex's line" "nan.obj:3: NaN or infinite number 'nan'"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf\nfoo bar\nf 2 4 3\nf 1 2 40\n' >"$T/few.obj"
expect_status "a few broken statements: the rest is shown" 0 "$Z" --print --size 20x8 "$T/few.obj"
expect_err "... with a warning that counts them and names the first" \
    "zview: warning: $T/few.obj: 3 statements skipped (first: $T/few.obj:6: face has fewer than 3 vertices (0))"
expect_status "--strict refuses it" 1 "$Z" --strict --print --size 20x8 "$T/few.obj"
expect_err "... with the first one's file and line" "few.obj:6: face has fewer than 3 vertices (0)"
expect_status "--info counts what was skipped" 0 "$Z" --info "$T/few.obj"
expect_out "... in a line of its own" "skipped:    3 statements (first: $T/few.obj:6:"
: >"$T/empty.obj"
expect_status "an empty file fails" 1 "$Z" --print "$T/empty.obj"
head -c 3000 /dev/urandom >"$T/garbage.obj"
"$Z" --print "$T/garbage.obj" >/dev/null 2>&1 </dev/null
st=$?
if [ "$st" -eq 1 ]; then ok "binary garbage fails cleanly"; else notok "binary garbage fails cleanly" "status $st"; fi

# one-shot image outputs
expect_status "-o png" 0 "$Z" assets/cube.obj --size 64x48 -o "$T/c.png"
if [ "$(head -c 8 "$T/c.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; then ok "png signature"; else notok "png signature"; fi
expect_status "-o ppm" 0 "$Z" assets/cube.obj --size 64x48 -o "$T/c.ppm"
if [ "$(head -c 13 "$T/c.ppm")" = "$(printf 'P6\n64 48\n255')" ] && [ "$(wc -c <"$T/c.ppm")" -eq $((13 + 64 * 48 * 3)) ]; then
    ok "ppm header and size"; else notok "ppm header and size" "$(head -c 20 "$T/c.ppm" | od -c | head -2)"; fi
expect_status "-o with another extension is a usage error" 2 "$Z" assets/cube.obj -o "$T/c.jpg"

# face ids and screen polygons
expect_status "--dump-ids" 0 "$Z" assets/cube.obj --size 40x30 --dump-ids "$T/ids" -o "$T/x.ppm"
if [ "$(wc -c <"$T/ids")" -eq $((40 * 30 * 4)) ]; then ok "dump-ids is W*H int32"; else notok "dump-ids is W*H int32" "$(wc -c <"$T/ids")"; fi
# corner pixel is background (-1 = ff ff ff ff)
if [ "$(head -c 4 "$T/ids" | od -An -tx1 | tr -d ' \n')" = "ffffffff" ]; then ok "background id is -1"; else notok "background id is -1"; fi
# each named view looks at one face of the cube: the centre pixel is the
# face whose 4 corners all lie on that side (front: z = +0.5, left:
# x = -0.5, top: y = +0.5, ...), its id counted from 0 in the file
for v in front:3:+ back:3:- left:1:- right:1:+ top:2:+ bottom:2:-; do
    name=${v%%:*}; axis=$(echo "$v" | cut -d: -f2); sign=${v##*:}
    want=$(awk -v a="$axis" -v s="$sign" '
        /^v / { n++; c[n] = $(a + 1) + 0 }
        /^f / { f++; all = 1
                for (i = 2; i <= NF; i++) { k = $i + 0; if (s == "+" ? c[k] <= 0 : c[k] >= 0) all = 0 }
                if (all) print f - 1 }' assets/cube.obj)
    "$Z" assets/cube.obj --size 40x30 --view "$name" --dump-ids "$T/ids" -o "$T/x.ppm" 2>"$T/err"
    centre=$(od -An -t d4 -j $(((15 * 40 + 20) * 4)) -N 4 "$T/ids" | tr -d ' ')
    if [ -n "$want" ] && [ "$centre" = "$want" ]; then ok "--view $name: the centre pixel is face $want"; else
        notok "--view $name: the centre pixel is face ${want:-?}" "id $centre"; fi
done
expect_status "--dump-screen" 0 "$Z" assets/cube.obj --size 40x30 --yaw 30 --pitch 20 --dump-screen "$T/s.obj" -o "$T/x.ppm"
if [ "$(head -n 1 "$T/s.obj")" = "# zview screen 40 30" ]; then ok "dump-screen header"; else notok "dump-screen header" "$(head -n 1 "$T/s.obj")"; fi
nf=$(grep -c '^f .* # [0-5]$' "$T/s.obj")
if [ "$nf" -eq 6 ]; then ok "dump-screen has the 6 faces with ids"; else notok "dump-screen has the 6 faces with ids" "$nf"; fi
"$Z" "$T/s.obj" --info >"$T/out" 2>"$T/err"
expect_out "the dump is valid OBJ" "faces:      6"

# --info
expect_status "--info" 0 "$Z" --info assets/cube.obj
expect_out "info vertices" "vertices:   8"
expect_out "info faces" "faces:      6"
expect_out "info triangles" "triangles:  12"
expect_out "info speed" "MB/s"
expect_status "--info --algo" 0 "$Z" --info --algo zbuffer --size 64x48 assets/cube.obj
expect_out "info render stats" "overdraw"
# the bytes of a still image in each protocol (issue 33): what --print
# writes for the same 640x480 pixels (64x24 cells of 10x20 without a
# terminal), within 5% (--print's picture keeps the text's background)
"$Z" --info --algo zbuffer --size 640x480 assets/knot.obj >"$T/info" 2>&1
for proto in sixel kitty iterm; do
    said=$(sed -n "s/^image: .*$proto \([0-9]*\) bytes.*/\1/p" "$T/info")
    wrote=$("$Z" --print --mode $proto --size 64x24 assets/knot.obj </dev/null 2>/dev/null | wc -c)
    if [ -n "$said" ] && [ "$wrote" -gt 1000 ] && [ $((said * 100)) -ge $((wrote * 95)) ] &&
        [ $((said * 100)) -le $((wrote * 105)) ]; then
        ok "--info --algo: a still $proto image's bytes ($said) as --print writes them ($wrote)"
    else
        notok "--info --algo: a still $proto image's bytes ($said) as --print writes them ($wrote)" "$(tail -2 "$T/info")"
    fi
done
# --info draws no picture: a --size too big for a printed one (16384
# rows of half blocks are 32768 pixels) is no error there
expect_status "--info takes a --size no printed picture could" 0 "$Z" --info --size 16384x16384 assets/cube.obj
expect_out "... and gives the counts" "faces:      6"

# ZV_SIMD (include/simd.h): --info names the level in use; a level that
# cannot run is said once, naming the variable and the level used; every
# level draws the same picture, with every algorithm
expect_status "ZV_SIMD=scalar" 0 env ZV_SIMD=scalar "$Z" --info assets/cube.obj
expect_out "... --info names the level" "simd:       scalar"
if [ -s "$T/err" ]; then notok "... and nothing is said" "$(head -c 300 "$T/err")"; else ok "... and nothing is said"; fi
expect_status "an unknown ZV_SIMD still runs" 0 env ZV_SIMD=avx9 "$Z" --info assets/cube.obj
expect_err "... with a warning naming it" "ZV_SIMD=avx9"
used=$(sed -n 's/^simd: *//p' "$T/out")
expect_err "... and the level --info names" "using $used"
if [ "$(wc -l <"$T/err")" -eq 1 ]; then ok "... once"; else notok "... once" "$(cat "$T/err")"; fi
same=1
for algo in zbuffer scanline span hzb hzb-octree; do
    for level in scalar sse2 avx2; do
        ZV_SIMD=$level "$Z" --algo $algo --size 96x64 --samples 4 --yaw 30 --pitch 20 -o "$T/$level.ppm" assets/demo.obj 2>"$T/err" ||
            same=0
        cmp -s "$T/scalar.ppm" "$T/$level.ppm" || { same=0; notok "ZV_SIMD=$level, $algo: the scalar picture"; }
    done
done
[ $same = 1 ] && ok "every ZV_SIMD level draws the scalar picture, with every algorithm"

# --print: the committed frames, and stdout that is not a terminal
for f in tests/expected/*.txt; do
    args=$(head -n 1 "$f" | sed 's/^# args: //')
    # shellcheck disable=SC2086
    "$Z" $args >"$T/frame" 2>"$T/err" </dev/null
    if tail -n +2 "$f" | cmp -s - "$T/frame"; then ok "print frame $(basename "$f")"; else
        notok "print frame $(basename "$f")" "output differs from $f"; fi
done
"$Z" assets/cube.obj --size 30x10 --mode ascii --color none >"$T/a" </dev/null
"$Z" assets/cube.obj --size 30x10 --mode ascii --color none --print >"$T/b" </dev/null
if cmp -s "$T/a" "$T/b" && [ "$(wc -l <"$T/a")" -eq 10 ]; then ok "no terminal behaves like --print"; else notok "no terminal behaves like --print"; fi
# every algorithm prints the same frame
for a in scanline span hzb hzb-octree; do
    "$Z" assets/scene.obj --size 60x20 --mode half --color 256 --algo "$a" --yaw 20 --pitch 15 >"$T/alg" </dev/null
    "$Z" assets/scene.obj --size 60x20 --mode half --color 256 --algo zbuffer --yaw 20 --pitch 15 >"$T/ref" </dev/null
    if cmp -s "$T/alg" "$T/ref"; then ok "print with $a equals zbuffer"; else notok "print with $a equals zbuffer"; fi
done
NO_COLOR=1 TERM=xterm-256color "$Z" assets/cube.obj --size 20x8 --mode half >"$T/nc" </dev/null
if grep -q "$(printf '\033')" "$T/nc"; then notok "NO_COLOR gives no escapes"; else ok "NO_COLOR gives no escapes"; fi

# the benchmark: a table, and JSON with the documented keys
expect_status "--bench" 0 "$Z" --bench --views 2 --size 64x48 --algo zbuffer,span assets/cube.obj
expect_out "bench table names the algorithm" "span"
t0=$(date +%s%N)
"$Z" --bench --json --views 2 --size 64x48 --algo all --grid 2 assets/cube.obj >"$T/b.json" 2>"$T/err"
wall_ms=$(( ($(date +%s%N) - t0) / 1000000 ))
n=$(grep -c '"algo": ' "$T/b.json")
if [ "$n" -eq 5 ]; then ok "bench --json has one object per algorithm"; else notok "bench --json has one object per algorithm" "$n"; fi
for key in model polygons algo width height threads views median_ms min_ms frame_median_ms culled_pct overdraw; do
    if [ "$(grep -c "\"$key\": " "$T/b.json")" -eq 5 ]; then ok "bench --json has $key"; else notok "bench --json has $key"; fi
done
if grep -q '"polygons": 48,' "$T/b.json"; then ok "grid polygons count every copy"; else notok "grid polygons count every copy" "$(head -c 300 "$T/b.json")"; fi
if head -c 1 "$T/b.json" | grep -q '\[' && tail -n 1 "$T/b.json" | grep -q '^\]$'; then ok "bench --json is one array"; else notok "bench --json is one array"; fi
# JSON that a strict parser reads, each object naming the model and its copies
m=$(python3 -c 'import json, sys; print(" ".join(sorted(set(o["model"] for o in json.load(open(sys.argv[1]))))))' "$T/b.json" 2>&1)
if [ "$m" = "cube.obj x2^3" ]; then ok "bench --json parses, its model the file's name and the grid"
else notok "bench --json parses, its model the file's name and the grid" "$m"; fi
# each algorithm's first frame and its time to ready are spans of this
# run: from 0 to the whole run's time as the shell measured it, first <= ready
bad=$(tr ',' '\n' <"$T/b.json" | awk -v wall="$wall_ms" '
    /"first_frame_ms": / { f = $2 + 0; if (f < 0 || f > wall) print "first_frame_ms " f }
    /"ready_ms": / { r = $2 + 0; if (r < f || r > wall) print "ready_ms " r " (first " f ")" }')
if [ -z "$bad" ]; then ok "bench first_frame_ms and ready_ms lie within the run"; else notok "bench first_frame_ms and ready_ms lie within the run" "$bad; the run took $wall_ms ms"; fi

# the view state from the command line (what the viewer's keys change)
"$Z" --print --size=40x12 --mode ascii --color none assets/cube.obj >"$T/nopan.txt"
"$Z" --print --size=40x12 --mode ascii --color none --pan=0.5,0 assets/cube.obj >"$T/pan.txt"
lead() { sed -n 6p "$1" | sed 's/[^ ].*//' | wc -c; }
if [ "$(lead "$T/pan.txt")" -gt "$(lead "$T/nopan.txt")" ]; then ok "--pan moves the picture right"; else
    notok "--pan moves the picture right" "$(cat "$T/pan.txt")"; fi
expect_status "--move of a missing object fails" 1 "$Z" --print --move 2:1,0,0 assets/cube.obj
expect_err "the missing object is named" "object 2"

# supersampling
expect_status "--samples 3 is a usage error" 2 "$Z" --print --samples 3 assets/cube.obj
expect_err "the allowed counts are named" "1, 4, 9 or 16"
"$Z" --print --size 40x12 --color none --mode ascii assets/knot.obj >"$T/s-default"
"$Z" --print --size 40x12 --color none --mode ascii --samples 4 assets/knot.obj >"$T/s4"
"$Z" --print --size 40x12 --color none --mode ascii --samples 1 assets/knot.obj >"$T/s1"
if cmp -s "$T/s-default" "$T/s4" && ! cmp -s "$T/s4" "$T/s1"; then ok "--print takes 4 samples by default"; else
    notok "--print takes 4 samples by default"; fi

# views
expect_status "an unknown --view is a usage error" 2 "$Z" --print --view sideways assets/cube.obj
expect_err "the views are named" "front, back, left"
"$Z" --print --size 30x10 --color none --view front assets/knot.obj >"$T/vf"
"$Z" --print --size 30x10 --color none --yaw 0 --pitch 0 assets/knot.obj >"$T/v0"
"$Z" --print --size 30x10 --color none assets/knot.obj >"$T/vauto"
if cmp -s "$T/vf" "$T/v0" && ! cmp -s "$T/vf" "$T/vauto"; then ok "--view front is the plain view; the default picks another"; else
    notok "--view front is the plain view; the default picks another"; fi
# runaway scenes are refused before they are built: --grid 40 of the torus
# is 64,000 copies (hundreds of millions of polygons)
# (issue 21: no fixed count; the limit is the memory, ZV_MEM_AVAILABLE
# plays a machine of 1 GB)
expect_status "--grid 40 is refused" 1 env ZV_MEM_AVAILABLE=1000000000 "$Z" --print --grid 40 assets/torus.obj
expect_err "the refusal gives the polygon count" "would have 786,432,000 polygons"
expect_err "the refusal gives the memory estimate" "GB for itself and one frame"
expect_err "the refusal gives the memory available" "more than it has; 1.0 GB available)"
expect_err "the refusal names the file" "assets/torus.obj: the scene would have"
expect_status "a grid that fits is not refused: no fixed count" 0 env ZV_MEM_AVAILABLE=1000000000 \
    "$Z" --print --size 20x6 --grid 4 assets/torus.obj
expect_status "--max-polys is an explicit cap" 1 "$Z" --print --size 20x6 --max-polys 1000 assets/torus.obj
expect_err "the cap's refusal gives the limit" "more than the limit of 1,000 polygons"
# the limit is the exact polygon count, grid copies counted
np=$("$Z" --info assets/torus.obj | sed -n 's/.* faces, \([0-9]*\) polygons.*/\1/p')
expect_status "--max-polys lets a moderate grid through" 0 "$Z" --print --size 20x6 --grid 3 --max-polys $((np * 27)) assets/torus.obj
expect_status "one polygon less is refused" 1 "$Z" --print --size 20x6 --grid 3 --max-polys $((np * 27 - 1)) assets/torus.obj
expect_err "the refusal names the count with the copies" "$(printf "%d" $((np * 27)) | sed ':a;s/\B[0-9]\{3\}\>/,&/;ta') polygons"
# (on the machine of 1 GB too: a compact scene's copies cost so much less
# that on a big machine the refusal is no longer certain, issue 21)
expect_status "the benchmark refuses it too" 1 env ZV_MEM_AVAILABLE=1000000000 "$Z" --bench --views 1 --grid 40 assets/torus.obj
expect_err "the benchmark names the memory" "GB available)"

# every write is checked: a full device (/dev/full) or a closed standard
# output (>&-) is an error naming the file, status 1, never a quiet success
# write_fails NAME WHERE MESSAGE CMD...: WHERE is "full" (stdout on
# /dev/full), "closed" (stdout closed) or "file" (CMD writes a file itself)
write_fails() {
    name=$1; where=$2; msg=$3; shift 3
    # the C locale: strerror's messages in English
    case $where in
    full) LC_ALL=C "$@" >/dev/full 2>"$T/err" </dev/null ;;
    closed) LC_ALL=C "$@" >&- 2>"$T/err" </dev/null ;;
    *) LC_ALL=C "$@" >"$T/out" 2>"$T/err" </dev/null ;;
    esac
    st=$?
    if [ "$st" -eq 1 ] && grep -qxF "zview: $msg" "$T/err"; then ok "$name"; else
        notok "$name" "status $st, stderr: $(head -c 300 "$T/err")"; fi
}
if [ -w /dev/full ]; then
    NOSPC="No space left on device"
    FULL="standard output: $NOSPC"
    CLOSED="standard output: Bad file descriptor"
    ln -s /dev/full "$T/full.png"
    ln -s /dev/full "$T/full.ppm"
    write_fails "--print to a full device" full "$FULL" "$Z" --print --size 20x6 assets/cube.obj
    write_fails "--print to a closed stdout" closed "$CLOSED" "$Z" --print --size 20x6 assets/cube.obj
    write_fails "--info to a full device" full "$FULL" "$Z" --info assets/cube.obj
    write_fails "--info to a closed stdout" closed "$CLOSED" "$Z" --info assets/cube.obj
    write_fails "--info --algo to a full device" full "$FULL" "$Z" --info --algo span --size 32x24 assets/cube.obj
    write_fails "--bench to a full device" full "$FULL" "$Z" --bench --views 1 --size 32x24 assets/cube.obj
    write_fails "--bench to a closed stdout" closed "$CLOSED" "$Z" --bench --views 1 --size 32x24 assets/cube.obj
    write_fails "--bench --json to a full device" full "$FULL" "$Z" --bench --json --views 1 --size 32x24 assets/cube.obj
    write_fails "--bench --json to a closed stdout" closed "$CLOSED" "$Z" --bench --json --views 1 --size 32x24 assets/cube.obj
    write_fails "--bench-tty to a full device" full "$FULL" "$Z" --bench-tty --size 20x6 assets/cube.obj
    write_fails "--bench-tty to a closed stdout" closed "$CLOSED" "$Z" --bench-tty --size 20x6 assets/cube.obj
    write_fails "--help to a full device" full "$FULL" "$Z" --help
    write_fails "--version to a closed stdout" closed "$CLOSED" "$Z" --version
    write_fails "-o png to a full device" file "$T/full.png: $NOSPC" "$Z" --size 64x48 -o "$T/full.png" assets/cube.obj
    write_fails "-o ppm to a full device" file "$T/full.ppm: $NOSPC" "$Z" --size 4x3 -o "$T/full.ppm" assets/cube.obj
    write_fails "--dump-ids to a full device" file "/dev/full: $NOSPC" "$Z" --size 4x3 --dump-ids /dev/full -o "$T/x.ppm" assets/cube.obj
    write_fails "--dump-screen to a full device" file "/dev/full: $NOSPC" "$Z" --size 4x3 --dump-screen /dev/full -o "$T/x.ppm" assets/cube.obj
    write_fails "--dump-ids to a folder that does not exist" file "$T/no/ids: No such file or directory" "$Z" --size 4x3 --dump-ids "$T/no/ids" -o "$T/x.ppm" assets/cube.obj
    # a closed stdout must not be taken by the next file opened
    "$Z" --size 4x3 -o "$T/c.ppm" assets/cube.obj >&- 2>"$T/err"
    if [ "$(head -c 2 "$T/c.ppm")" = P6 ] && [ "$(wc -c <"$T/c.ppm")" -eq $((11 + 36)) ]; then ok "-o with stdout closed writes only the file"; else
        notok "-o with stdout closed writes only the file" "$(head -c 40 "$T/c.ppm" | od -c | head -3)"; fi
else
    skip "writes to a full device fail with the reason" "no /dev/full"
fi

# --turntable N: N frames a 360/N-degree turn apart, the number in the name
expect_status "--turntable 4 -o pattern.png" 0 "$Z" --turntable 4 -o "$T/tt-%03d.png" --size 64x48 assets/knot.obj
if [ -s "$T/tt-000.png" ] && [ -s "$T/tt-003.png" ] && [ ! -e "$T/tt-004.png" ]; then ok "--turntable 4 writes frames 000 to 003"; else
    notok "--turntable 4 writes frames 000 to 003" "$(ls "$T")"; fi
if need_python "--turntable frames decode at the size asked"; then
    bad=0
    for k in 0 1 2 3; do
        [ "$(python3 tests/e2e/pngsize.py "$T/tt-00$k.png")" = "64 48" ] || bad=1
    done
    if [ $bad -eq 0 ]; then ok "--turntable frames decode at the size asked"; else notok "--turntable frames decode at the size asked"; fi
fi
if ! cmp -s "$T/tt-000.png" "$T/tt-001.png" && ! cmp -s "$T/tt-001.png" "$T/tt-002.png"; then ok "--turntable frames differ"; else
    notok "--turntable frames differ"; fi
# text frames: frame k is the view turned 360k/N degrees, fitted as frame 0
expect_status "--turntable 4 -o pattern.txt" 0 "$Z" --turntable 4 -o "$T/tt-%d.txt" --size 40x12 --color 256 --view front assets/knot.obj
"$Z" --print --size 40x12 --color 256 --view front assets/knot.obj >"$T/f0"
"$Z" --print --size 40x12 --color 256 --view front --yaw 90 --fit-from 0,0,0 assets/knot.obj >"$T/f1"
if cmp -s "$T/tt-0.txt" "$T/f0" && cmp -s "$T/tt-1.txt" "$T/f1" && ! cmp -s "$T/tt-1.txt" "$T/tt-2.txt"; then
    ok "--turntable text frames are the turned views --print gives"; else notok "--turntable text frames are the turned views --print gives"; fi
"$Z" --turntable 3 --print --size 20x6 --color none assets/cube.obj >"$T/ttp"
if [ "$(wc -l <"$T/ttp")" -eq 18 ]; then ok "--turntable --print writes the frames to stdout"; else notok "--turntable --print writes the frames to stdout" "$(wc -l <"$T/ttp") lines"; fi
expect_status "--turntable: a pattern without a number is a usage error" 2 "$Z" --turntable 3 -o "$T/t.png" assets/cube.obj
expect_err "the pattern's problem is named" "needs exactly one integer conversion"
expect_status "--turntable: two numbers are a usage error" 2 "$Z" --turntable 3 -o "$T/t-%d-%d.png" assets/cube.obj
expect_status "--turntable: %s is a usage error" 2 "$Z" --turntable 3 -o "$T/t-%s.png" assets/cube.obj
expect_status "--turntable: %% and one number are fine" 0 "$Z" --turntable 2 -o "$T/t-%%-%02d.ppm" --size 8x6 assets/cube.obj
if [ -s "$T/t-%-01.ppm" ]; then ok "%% is a percent sign in the name"; else notok "%% is a percent sign in the name" "$(ls "$T")"; fi
expect_status "--turntable without an output is a usage error" 2 "$Z" --turntable 3 assets/cube.obj
expect_status "--turntable 0 is a usage error" 2 "$Z" --turntable 0 -o "$T/t-%d.png" assets/cube.obj
if [ -w /dev/full ]; then
    ln -s /dev/full "$T/full-1.png"
    "$Z" --turntable 3 -o "$T/full-%d.png" --size 16x12 assets/cube.obj >/dev/null 2>"$T/err" </dev/null
    st=$?
    if [ $st -eq 1 ] && grep -qx "zview: $T/full-1.png: No space left on device" "$T/err" && [ ! -e "$T/full-2.png" ]; then
        ok "--turntable stops at the first frame that cannot be written"; else
        notok "--turntable stops at the first frame that cannot be written" "status $st: $(cat "$T/err")"; fi
fi
# -o FILE.txt: the text --print gives
expect_status "-o FILE.txt" 0 "$Z" -o "$T/one.txt" --size 30x8 --color 256 assets/torus.obj
"$Z" --print --size 30x8 --color 256 assets/torus.obj >"$T/one-print"
if cmp -s "$T/one.txt" "$T/one-print"; then ok "-o FILE.txt writes what --print does"; else notok "-o FILE.txt writes what --print does"; fi
# --print-view with no terminal at all: an error, not a frame in the command's place
echo | TERM=xterm-256color setsid -w "$Z" --print-view assets/cube.obj >"$T/out" 2>"$T/err"
st=$?
if [ $st -eq 1 ] && [ ! -s "$T/out" ] && grep -q "print-view" "$T/err"; then ok "--print-view without a terminal fails cleanly"; else
    notok "--print-view without a terminal fails cleanly" "status $st: $(cat "$T/err")"; fi
# a binary copied away from the source tree, run where no assets/ is:
# the demo scene's refusal names every place it looked
mkdir -p "$T/away/bin" "$T/away/cwd"
cp "$Z" "$T/away/bin/zview"
if [ -r /usr/local/share/zview/demo.obj ]; then
    expect_status "a copied binary finds the installed demo scene" 0 sh -c "cd '$T/away/cwd' && '$T/away/bin/zview' -p --size 20x6"
else
    expect_status "a copied binary with no demo scene anywhere fails" 1 sh -c "cd '$T/away/cwd' && '$T/away/bin/zview' -p --size 20x6"
    for place in "$T/away/bin/assets/demo.obj" "$T/away/bin/../share/zview/demo.obj" "/usr/local/share/zview/demo.obj" " or assets/demo.obj"; do
        expect_err "... naming $place" "$place"
    done
    check_lines=$(wc -l <"$T/err")
    if [ "$check_lines" -eq 1 ]; then ok "... in one line"; else notok "... in one line" "$(cat "$T/err")"; fi
fi
# options that cannot both be honoured are refused, not one silently dropped
for combo in "--info -o $T/i.png" "--info --dump-ids $T/i.bin" "--info --print" "--bench -o $T/b.png" \
             "--turntable 2 -o $T/t%d.png --dump-ids $T/t.bin" "--info --bench" "--check --dump-ids $T/c.bin"; do
    expect_status "$combo is refused" 2 "$Z" $combo assets/cube.obj
    first=${combo%% *}
    expect_err "... naming $first" "$first"
done
for f in i.png i.bin b.png t0.png t.bin c.bin; do
    if [ ! -e "$T/$f" ]; then ok "... and $f not written"; else notok "... and $f not written"; fi
done
