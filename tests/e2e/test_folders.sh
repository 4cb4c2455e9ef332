#!/bin/sh
# A folder checked whole (issue 34): --check DIR checks the model files
# in it (-r: in its subfolders too, each entered once however many links
# lead to it; a FIFO never opened), with one summary line on standard
# error and the exit status of the worst; --jsonl streams a JSON object a
# file, in the files' order, with --json's members; --summary sums such
# lines up. The references are python's: the JSON parsed and counted
# apart from zview.
. "$(dirname "$0")/lib.sh"
need_python "the folder checks" || exit 0
Z=$ZVIEW
D=$T/models
mkdir -p "$D/sub/deeper"
cp assets/cube.obj assets/knot.obj assets/concave.obj "$D/"
cp assets/cube.obj "$D/sub/c2.obj"
cp assets/cube.obj "$D/sub/deeper/c3.obj"
printf 'solid\n' >"$D/sub/broken.stl"
echo notes >"$D/readme.txt"
ln -s .. "$D/sub/up"                      # a link back up: a loop
ln -s .. "$D/sub/deeper/again"            # a second way into sub
mkfifo "$D/sub/pipe.stl"                  # named like a model, never opened

# one level
timeout 60 "$Z" --check "$D" >"$T/out" 2>"$T/err"
st=$?
if [ $st -eq 3 ]; then ok "--check DIR: status 3 (problems, every file read)"; else notok "--check DIR: status 3" "status $st: $(cat "$T/err")"; fi
if grep -qx 'zview: checked 3 files in 1 folder: 2 sound, 1 with problems, 0 not read' "$T/err"; then ok "... the three models of the folder, summed up on one line"
else notok "... the three models of the folder, summed up on one line" "$(cat "$T/err")"; fi

# the tree, as JSON lines
timeout 60 "$Z" --check -r --jsonl "$D" >"$T/lines" 2>"$T/err"
st=$?
if [ $st -eq 1 ]; then ok "-r --jsonl: status 1 (the broken file)"; else notok "-r --jsonl: status 1 (the broken file)" "status $st"; fi
if grep -q 'checked 6 files in 1 folder: 4 sound, 1 with problems, 1 not read; 2 folders reached again by a link, not entered again' "$T/err"
then ok "... six models, the loop and the second way in counted, the FIFO passed over"
else notok "... six models, the loop and the second way in counted, the FIFO passed over" "$(tail -2 "$T/err")"; fi
python3 - "$T/lines" "$D" >"$T/py" 2>&1 <<'EOF'
import json, sys
lines = open(sys.argv[1]).read().split("\n")
assert lines[-1] == "", "ends with a newline"
objs = [json.loads(l) for l in lines[:-1]]
# the pretty layout folded, none of its indent left: "{" first, and no
# two spaces in a row (the test's paths have none)
assert all(l.startswith("{") and "  " not in l for l in lines[:-1]), lines[:-1]
paths = [o["path"] for o in objs]
d = sys.argv[2]
want = [d + "/" + p for p in ["concave.obj", "cube.obj", "knot.obj", "sub/broken.stl", "sub/c2.obj", "sub/deeper/c3.obj"]]
assert paths == want, paths
bad = [o for o in objs if not o["ok"]]
assert [o["path"] for o in bad] == [d + "/concave.obj", d + "/sub/broken.stl"], bad
assert "error" in bad[1] and "objects" not in bad[1]
assert objs[1]["objects"][0]["faces"] == 6 and objs[1]["faces"] == 6
print("ok", len(objs))
EOF
if grep -qx 'ok 6' "$T/py"; then ok "... one JSON object a line, in the files' order, the broken one with its error"
else notok "... one JSON object a line, in the files' order, the broken one with its error" "$(cat "$T/py")"; fi
# the members --json gives the same file
"$Z" --check --json "$D/knot.obj" >"$T/one.json" 2>/dev/null
python3 - "$T/lines" "$T/one.json" >"$T/py" 2>&1 <<'EOF'
import json, sys
line = [json.loads(l) for l in open(sys.argv[1]) if '"knot.obj"' in l or l.find("/knot.obj") >= 0][0]
whole = json.load(open(sys.argv[2]))
f = dict(whole["files"][0])
objs = [dict(o) for o in whole["objects"]]
for o in objs:
    del o["file"]
got = dict(line)
got_objs = got.pop("objects")
for o in got_objs:
    o.pop("file", None)
f["path"] = got["path"]
assert got == f, (set(got.items()) ^ set((k, json.dumps(v)) for k, v in f.items()))
assert got_objs == objs
print("same")
EOF
if grep -qx same "$T/py"; then ok "... a line holds --json's members of its file and objects"; else notok "... a line holds --json's members of its file and objects" "$(tail -3 "$T/py")"; fi
"$Z" -j 1 --check -r --jsonl "$D" >"$T/lines1" 2>/dev/null
if cmp -s "$T/lines" "$T/lines1"; then ok "... the same bytes on one thread"; else notok "... the same bytes on one thread"; fi

# the summary of several runs
head -n 3 "$T/lines" >"$T/a.jsonl"
tail -n +4 "$T/lines" >"$T/b.jsonl"
expect_status "--summary of the run split in two" 1 "$Z" --summary "$T/a.jsonl" "$T/b.jsonl"
python3 - "$T/lines" >"$T/want" <<'EOF'
import json, sys
objs = [json.loads(l) for l in open(sys.argv[1])]
print("files       %d, from 2 JSONL files" % len(objs))
print("sound       %d" % sum(1 for o in objs if o["ok"]))
print("problems    %d" % sum(1 for o in objs if not o["ok"] and "error" not in o))
print("not read    %d" % sum(1 for o in objs if "error" in o))
EOF
if head -n 4 "$T/out" | cmp -s - "$T/want"; then ok "... counts what python counts"; else notok "... counts what python counts" "$(head -4 "$T/out")"; fi
if grep -q '^by problem  1 file with holes$' "$T/out" && grep -q "^worst       $D/sub/broken.stl: not read: " "$T/out" &&
    grep -q "^            $D/concave.obj: 5 holes" "$T/out"; then ok "... the kinds of problem and the worst files, the unread first"
else notok "... the kinds of problem and the worst files, the unread first" "$(cat "$T/out")"; fi
printf '{"path": "x.obj", "ok": true}\nnot json\n{"ok": true}\n' >"$T/bad.jsonl"
expect_status "--summary of lines that are no check's" 1 "$Z" --summary "$T/bad.jsonl"
expect_err "... naming the file and line" "bad.jsonl:2: not a file's check of --check --jsonl"
expect_err "... each" "bad.jsonl:3: not a file's check"
expect_out "... and counting the one that is" "files       1, from 1 JSONL file"

# what does not go together
expect_status "-r without --check" 2 "$Z" -r "$D"
expect_status "--jsonl with --json" 2 "$Z" --check --jsonl --json "$D"
expect_status "--check DIR with -o" 2 "$Z" --check -o "$T/x.png" "$D"
expect_err "... says the gallery draws a folder" "--gallery DIR -o sheet.png"
# a mode that reads its file its own way takes no folder: not the gallery
expect_status "--info DIR is no gallery" 1 "$Z" --info "$D"
expect_err "... it says the file is a folder" "$D: is a directory"
expect_status "a folder that cannot be read" 1 "$Z" --check "$T/none"
