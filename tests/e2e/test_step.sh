#!/bin/sh
# STEP, IGES and BREP through OpenCASCADE (issue 34), on files written
# by OpenCASCADE itself (tools/occtgen.cpp, $ZV_OCCTGEN): the 10 x 20 x 30
# box in the three formats is watertight with volume 6000 (to 1e-6);
# the cylinder's volume is within the tessellation's bound (between
# pi (r - d)^2 h and pi r^2 h, d the deflection: 0.1% of the diagonal,
# or what --tessellation says); the assembly's two parts keep their names
# and colours (--info); the inch file's unit reaches --info and --check;
# malformed STEP (cut short, garbage entities) is refused in one line
# naming the file, status 1; and a zview without the shim says so in
# one line. Without OCCT (no generator, no shim) every check is a skip.
. "$(dirname "$0")/lib.sh"
Z=$ZVIEW
check() { if eval "$2"; then ok "$1"; else notok "$1" "$3"; fi; }

G=${ZV_OCCTGEN:-}
if [ -z "$G" ] || [ ! -x "$G" ] || ! "$Z" --formats 2>/dev/null | grep -q '^step .*(OCCT [0-9]'; then
    for c in box iges brep cylinder tessellation assembly inch malformed missing picture; do
        skip "STEP, IGES, BREP: $c" "no OpenCASCADE (sh tools/deps.sh installs it; the Makefile builds the shim and build/occtgen)"
    done
    exit 0
fi
D=$T/cad
mkdir -p "$D"
expect_status "occtgen writes the test files through OpenCASCADE" 0 "$G" "$D"

# member FILE NAME: the first number (or word) a JSON report gives NAME
member() { sed -n "s/^ *\"$2\": \"*\([^\",]*\)\"*,*$/\1/p" "$1" | head -n 1; }
# within A B TOL: |A - B| <= TOL
within() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && d <= t) }'; }

# ==== The box in three formats ====
for f in box.step box.igs box.brep; do
    expect_status "$f: --check --json exits 0 (sound)" 0 "$Z" --check --json "$D/$f"
    cp "$T/out" "$T/$f.json"
    v=$(member "$T/$f.json" volume)
    check "$f: the volume is 6000 to 1e-6 (got $v)" 'within "$v" 6000 0.000001' "$(head -c 300 "$T/$f.json")"
    check "$f: watertight" '[ "$(member "$T/$f.json" watertight)" = true ]'
    check "$f: 12 triangles, 8 vertices after merging the faces' own" \
        '[ "$(member "$T/$f.json" faces)" = 12 ] && [ "$(member "$T/$f.json" vertices)" = 8 ]'
done
check "box.step and box.igs state millimetres; box.brep no unit" \
    '[ "$(member "$T/box.step.json" unit)" = mm ] && [ "$(member "$T/box.igs.json" unit)" = mm ] &&
     grep -q "\"unit\": null" "$T/box.brep.json"'
expect_status "box.step --info" 0 "$Z" --info "$D/box.step"
expect_out "--info names the reader" "format:     step (OCCT)"
expect_out "the six faces' own corners merged: 8 vertices, not 24" "vertices:   8"
expect_out "--info: the load ran in the sandbox" "sandbox:    seccomp"
expect_out "--info: STEP stands z-up" "up:         z (step: the CAD convention, z up)"

# ==== The cylinder: r 5, h 20; diagonal sqrt(10^2 + 10^2 + 20^2) ====
cyl_bound() {   # NAME REL [OPTS]: the volume within the bound at deflection REL x diagonal
    cname=$1 rel=$2
    shift 2
    expect_status "cylinder ($cname): --check exits 0" 0 "$Z" --check --json "$@" "$D/cylinder.step"
    v=$(member "$T/out" volume)
    lo=$(awk -v r="$rel" 'BEGIN { d = r * sqrt(600); pi = atan2(0, -1); printf "%.6f", pi * (5 - d) ^ 2 * 20 }')
    hi=$(awk 'BEGIN { pi = atan2(0, -1); printf "%.6f", pi * 25 * 20 }')
    check "cylinder ($cname): volume $v between pi (r - d)^2 h = $lo and pi r^2 h = $hi" \
        'awk -v v="$v" -v lo="$lo" -v hi="$hi" "BEGIN { exit !(v != \"\" && v >= lo && v <= hi) }"'
    check "cylinder ($cname): watertight" '[ "$(member "$T/out" watertight)" = true ]'
    faces=$(member "$T/out" faces)
}
cyl_bound "default, 0.001" 0.001
fine=$faces
cyl_bound "--tessellation 0.02" 0.02 --tessellation 0.02
check "--tessellation 0.02 makes fewer triangles than the default ($faces < $fine)" '[ "$faces" -lt "$fine" ]'
expect_status "--tessellation 0 is refused" 2 "$Z" --tessellation 0 --check "$D/cylinder.step"
expect_err "it says what it takes" "0.000001 to 0.5"

# ==== The assembly: two parts, named and coloured ====
expect_status "assembly.step --info" 0 "$Z" --info "$D/assembly.step"
expect_out "two objects" "objects:    2"
expect_out "the bracket, red" "bracket: 12 faces, colour #ff0000"
check "the shaft is blue" 'grep -q "shaft: [0-9]* faces, colour #0000ff" "$T/out"' "$(grep shaft "$T/out")"
expect_status "assembly.step --check --json" 0 "$Z" --check --json "$D/assembly.step"
check "the assembly's objects by name in --check" \
    'grep -q "\"name\": \"bracket\"" "$T/out" && grep -q "\"name\": \"shaft\"" "$T/out"'
# the bracket 40 x 10 x 5 = 2000 exactly; its object's volume
check "the bracket's volume is 2000" \
    'sed -n "/\"name\": \"bracket\"/,/volume/p" "$T/out" | grep -q "\"volume\": 2000,"'

# ==== Inches ====
expect_status "inch.step --info" 0 "$Z" --info "$D/inch.step"
expect_out "--info names the file's unit" "unit:       in (inches, as the file states)"
expect_out "the coordinates stay in inches (1 x 2 x 3)" "bounds:     0 0 0 .. 1 2 3"
expect_status "inch.step --check --json" 0 "$Z" --check --json "$D/inch.step"
check "--check's unit is in, the volume 6 (cubic inches)" \
    '[ "$(member "$T/out" unit)" = in ] && within "$(member "$T/out" volume)" 6 0.000001' "$(head -c 300 "$T/out")"

# ==== Malformed STEP ====
head -c 3000 "$D/box.step" >"$T/cut.step"
sed 's/^#2[0-9] = .*/#20 = GARBAGE_ENTITY((#1,,#2)) junk;/' "$D/box.step" >"$T/garbage.step"
printf 'ISO-10303-21;\nHEADER;\nFILE_NAME(\n' >"$T/stub.step"
for f in cut.step garbage.step stub.step; do
    expect_status "$f is refused, status 1" 1 "$Z" -o "$T/x.png" "$T/$f"
    check "$f: one line naming the file" '[ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "^zview: $T/$f: " "$T/err"' \
        "$(cat "$T/err")"
done

# ==== Standard input: OCCT reads files by name ====
check "a STEP on standard input: status 1, one line saying why" \
    '! "$Z" -o "$T/x.png" - <"$D/box.step" 2>"$T/err" && [ "$(wc -l <"$T/err")" -eq 1 ] &&
     grep -q "stdin: step is read from a named file only, not standard input$" "$T/err"' "$(cat "$T/err")"

# ==== Without the shim ====
expect_status "the shim hidden (ZV_OCCT_SHIM): status 1" 1 env ZV_OCCT_SHIM="$T/none.so" "$Z" -o "$T/x.png" "$D/box.step"
check "one line: STEP needs OpenCASCADE" '[ "$(wc -l <"$T/err")" -eq 1 ] && grep -q "box.step: STEP needs OpenCASCADE" "$T/err"' \
    "$(cat "$T/err")"
mkdir -p "$T/alone"
cp "$Z" "$T/alone/zview"
expect_status "a zview with no shim beside it: status 1" 1 env -u ZV_OCCT_SHIM "$T/alone/zview" -o "$T/x.png" "$D/box.igs"
expect_err "it names what it looked for" "IGES needs OpenCASCADE: no libzview-occt.so beside zview"
expect_status "and reads the other formats" 0 "$T/alone/zview" -o "$T/x.png" assets/demo.obj

# ==== A picture ====
rm -f "$T/x.png"
expect_status "assembly.step -o x.png" 0 "$Z" -o "$T/x.png" -s 120x90 "$D/assembly.step"
check "the picture was written" '[ -s "$T/x.png" ]'
