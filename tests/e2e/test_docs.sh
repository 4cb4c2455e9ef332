#!/bin/sh
# The documents against the program, so that they cannot drift again:
# - a text capture (a ```text block of README.md, CONTRIBUTING.md or
#   doc/*.md whose first line is "$ zview ARGS") equals what zview ARGS
#   prints, line for line (trailing blanks aside); captures use --print,
#   --size and --color none, so that they are the same on every machine,
#   or are --check or --repair reports (text alone; status 3 allowed;
#   --repair writes its copy in a temporary folder);
# - the example commands of the ```sh blocks whose model files are in
#   assets/ run with status 0 (standard output is no terminal, so a
#   viewer example prints one frame);
# - the layout map (doc/design.md) names every file under src/ and
#   include/, and no file that is not there.
. "$(dirname "$0")/lib.sh"
Z=${ZVIEW:-$ROOT/zview}
DOCS="README.md CONTRIBUTING.md doc/design.md doc/benchmarks.md"

# ==== Text captures ====

# Split each capture of a document into $T/cap-N.cmd (the arguments)
# and $T/cap-N.want (the lines after the command), N from $2.
split_captures() {
    awk -v dir="$T" -v n="$2" '
        /^```text$/ { intext = 1; first = 1; next }
        /^```/ && intext { if (cap) close(want); intext = 0; cap = 0; next }
        intext && first {
            first = 0
            if (substr($0, 1, 8) == "$ zview ") {
                cap = 1; n++
                want = dir "/cap-" n ".want"
                print substr($0, 9) > (dir "/cap-" n ".cmd")
                close(dir "/cap-" n ".cmd")
                printf "" > want
            }
            next
        }
        cap { print > want }
        END { print n > (dir "/ncap") }' "$1"
}

# where examples run (and --repair writes): the bundled models beside them
mkdir "$T/run"
ln -s "$ROOT/assets" "$T/run/assets"
ln -s "$ROOT/tests" "$T/run/tests"

ncap=0
for doc in $DOCS; do
    [ -f "$doc" ] || continue
    first=$ncap
    split_captures "$doc" "$ncap"
    ncap=$(cat "$T/ncap")
    k=$first
    while [ "$k" -lt "$ncap" ]; do
        k=$((k + 1))
        args=$(cat "$T/cap-$k.cmd")
        name="$doc: zview $args"
        fixed=0
        case " $args " in *" --print "*) fixed=$((fixed + 1)) ;; esac
        case " $args " in *" --size "*) fixed=$((fixed + 1)) ;; esac
        case " $args " in *" --color none "*) fixed=$((fixed + 1)) ;; esac
        # --check's report is text alone, the same everywhere; its status
        # 3 (a problem found) is what the capture shows; so is --repair's,
        # which writes its copy in a folder of its own
        check=0 here=$ROOT
        case " $args " in *" --check "*) check=1 fixed=3 ;; esac
        case " $args " in *" --repair "* | *" --repair="*) check=1 fixed=3 here=$T/run ;; esac
        if [ "$fixed" -ne 3 ]; then
            notok "$name" "a capture needs --print, --size and --color none (or --check), to be the same everywhere"
            continue
        fi
        set -f
        # shellcheck disable=SC2086
        (cd "$here" && "$Z" $args >"$T/got" 2>"$T/err" </dev/null)
        rc=$?
        set +f
        sed 's/[[:space:]]*$//' "$T/got" >"$T/got.s"
        sed 's/[[:space:]]*$//' "$T/cap-$k.want" >"$T/want.s"
        if [ "$rc" -ne 0 ] && { [ "$check" -eq 0 ] || [ "$rc" -ne 3 ]; }; then
            notok "$name" "status $rc: $(head -c 200 "$T/err")"
        elif cmp -s "$T/got.s" "$T/want.s"; then
            ok "$name"
        else
            notok "$name" "the capture differs from the output (- doc, + zview): $(diff "$T/want.s" "$T/got.s" | head -n 6 | tr '\n' '|')"
        fi
    done
done
if [ "$ncap" -ge 3 ]; then ok "the documents hold $ncap text captures"; else notok "the documents hold $ncap text captures, not 3 or more"; fi

# ==== Example commands ====

# Every line of a ```sh block that runs zview, its comment dropped.
awk_examples() {
    awk '/^```sh$/ { insh = 1; next } /^```/ { insh = 0; next }
         insh && ($1 == "zview" || $1 == "./zview") { sub(/[ \t][ \t]+#.*$/, ""); print }' "$@"
}

nex=0
# shellcheck disable=SC2086
awk_examples $(for d in $DOCS; do [ -f "$d" ] && echo "$d"; done) >"$T/examples"
while IFS= read -r line; do
    case "$line" in
    *'|'* | *'$'* | *'<'* | *'>'* | *';'* | *'&'* | *'['* | *'('*) continue ;;   # pipes and shell: illustrations
    *--sketch* | *--print-view* | *--bench*) continue ;;                        # a terminal, or minutes
    esac
    set -f
    # shellcheck disable=SC2086
    set -- $line
    set +f
    shift
    missing=
    for w in "$@"; do
        case "$w" in
        *.obj | *.stl | *.ply | *.off | *.xyz | *.glb) [ -e "$ROOT/$w" ] || missing=$w ;;
        esac
    done
    [ -n "$missing" ] && continue          # a model of the reader's own
    nex=$((nex + 1))
    (cd "$T/run" && timeout 120 "$Z" "$@" >"$T/out" 2>"$T/err" </dev/null)
    rc=$?
    if [ "$rc" -eq 0 ]; then ok "example: $line"; else notok "example: $line" "status $rc: $(head -c 200 "$T/err")"; fi
done <"$T/examples"
if [ "$nex" -ge 4 ]; then ok "$nex example commands ran"; else notok "only $nex example commands ran, not 4 or more"; fi

# ==== The layout map ====

# The map is the first ```text block after the comment that names this test.
awk '/<!-- tests\/e2e\/test_docs.sh/ { seen = 1 }
     seen && /^```text$/ { inmap = 1; next }
     inmap && /^```/ { exit }
     inmap {
         dir = substr($0, 1, 15); sub(/ +$/, "", dir)
         if (dir != "") cur = dir
         n = split(substr($0, 16), w, " ")
         for (i = 1; i <= n && w[i] ~ /^[A-Za-z0-9_]+\.[ch]$/; i++) print cur w[i]
     }' doc/design.md | sort >"$T/map"
find src include -name '*.[ch]' | sort >"$T/tree"
if [ ! -s "$T/map" ]; then
    notok "doc/design.md has a layout map" "no \`\`\`text block after the line naming tests/e2e/test_docs.sh"
else
    missing=$(comm -13 "$T/map" "$T/tree" | tr '\n' ' ')
    extra=$(comm -23 "$T/map" "$T/tree" | tr '\n' ' ')
    if [ -z "$missing" ]; then ok "the layout map names every file under src/ and include/"; else notok "the layout map names every file under src/ and include/" "missing: $missing"; fi
    if [ -z "$extra" ]; then ok "the layout map names only files that exist"; else notok "the layout map names only files that exist" "not in the tree: $extra"; fi
fi

# ==== make help names every target ====
make -s help >"$T/help" 2>&1
missing=
for t in $(sed -n 's/^\.PHONY: *//p' Makefile); do
    case $t in all | help) continue ;; esac
    grep -Eq "make $t( |,|$)|, $t( |,|$)" "$T/help" || missing="$missing $t"
done
if [ -z "$missing" ]; then ok "make help names every target of .PHONY"; else notok "make help names every target of .PHONY" "missing:$missing"; fi

# ==== Curses in the one file the docs name ====
# doc/design.md names it ("in `src/...`, the only file that includes
# it"); no other file under src/ or include/ includes curses or terminfo
# (<curses.h>, <ncurses.h>, <term.h>, their ncursesw/ forms) or calls
# their functions: the screen is written by vt.c, the keys read by
# keys.c, and curses only sets the modes and reads the description.
named=$(tr '\n' ' ' <doc/design.md | grep -o '`src/[A-Za-z0-9_/]*\.c`, the only file that includes it' | sed 's/^`\([^`]*\)`.*/\1/')
{
    grep -rlE '^[[:space:]]*#[[:space:]]*include[[:space:]]*<(ncursesw?/)?(n?curses|term)\.h>' src include
    grep -rlE '(^|[^A-Za-z0-9_])(initscr|newterm|set_term|delscreen|endwin|doupdate|refresh|resizeterm|newpad|newwin|delwin|keypad|curs_set|cbreak|noecho|nonl|intrflush|setupterm|set_curterm|del_curterm|tigetstr|tigetflag|tigetnum|tputs|putp|tparm|tiparm)[[:space:]]*\(' src include
} | sort -u >"$T/curses"
if [ -z "$named" ]; then
    notok "doc/design.md names the one file that includes curses" "no \"\`src/...\`, the only file that includes it\""
elif [ "$(cat "$T/curses")" = "$named" ]; then
    ok "curses only in $named, as doc/design.md says"
else
    notok "curses only in $named, as doc/design.md says" "curses or terminfo in: $(tr '\n' ' ' <"$T/curses")"
fi

# ==== one name per file: a file name alone finds its file ====
dups=$(find src include -name '*.[ch]' -printf '%f\n' | sort | uniq -d | tr '\n' ' ')
if [ -z "$dups" ]; then ok "no two files under src/ and include/ share a name"; else notok "no two files under src/ and include/ share a name" "$dups"; fi

# ==== one prefix per room: app_ is app/'s ====
stray=$(grep -ln '^[A-Za-z][A-Za-z0-9_ *]*[ *]app_[a-z0-9_]*(' $(find src -name '*.c' ! -path 'src/app/*') 2>/dev/null | tr '\n' ' ')
if [ -z "$stray" ]; then ok "only src/app/ defines app_ functions"; else notok "only src/app/ defines app_ functions" "$stray"; fi

# ==== the README stays a newcomer's page (issue 29: at most 400 lines) ====
n=$(wc -l <README.md)
if [ "$n" -le 400 ]; then ok "README.md is $n lines (at most 400)"; else notok "README.md is $n lines (at most 400)" "the detail goes in doc/design.md"; fi
