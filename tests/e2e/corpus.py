"""corpus.py ZVIEW DIR [asan]: zview --info on every file under DIR, two at a
time, and what a refusal looks like (issue 28). Prints one line a
count ("files N", "refused N", "refusals of more than one line N",
"refusals not naming the file N", "control bytes N", "outside the
folder N"), then "bad: PATH: STDERR" for each file that breaks a rule:
a refusal (status 1) is exactly one line, "zview: PATH: ...", with no
control byte; no output at all has one; and no reference is refused as
"outside the model's folder" (those in it are read since issue 28; the
ones still refused leave the folder by '..'). asan: a checking build
passes a library's own lines on (a sanitizer's report): zview's line is
the last."""
import concurrent.futures, os, subprocess, sys

zview, top = sys.argv[1], sys.argv[2]
asan = len(sys.argv) > 3 and sys.argv[3] == "asan"
files = sorted(os.path.join(d, f) for d, _, fs in os.walk(top) for f in fs)


def run(path):
    try:
        p = subprocess.run([zview, "--info", path], stdin=subprocess.DEVNULL, capture_output=True, timeout=120)
        return path, p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        return path, -1, b"", b"timed out\n"


def raw(b):
    t = b.decode("utf-8", "replace")
    return any((ord(c) < 0x20 and c != "\n") or 0x7f <= ord(c) <= 0x9f for c in t)


count = dict.fromkeys(["files", "refused", "refusals of more than one line", "refusals not naming the file",
                       "control bytes", "outside the folder", "leaving the folder by '..'"], 0)
bad = []
with concurrent.futures.ThreadPoolExecutor(2) as pool:
    for path, st, out, err in pool.map(run, files):
        count["files"] += 1
        lines = err.decode("utf-8", "replace").splitlines()
        if asan and st == 1:
            lines = [l for l in lines if l.startswith("zview: ")]
        why = []
        if st == 1:
            count["refused"] += 1
            if len(lines) != 1:
                count["refusals of more than one line"] += 1
                why.append("%d lines" % len(lines))
            elif not lines[0].startswith("zview: " + path + ":") and not lines[0].startswith("zview: " + path + " "):
                count["refusals not naming the file"] += 1
                why.append("does not name the file")
        elif st not in (0, 3):
            why.append("status %d" % st)
        if raw(out) or raw(err):
            count["control bytes"] += 1
            why.append("control bytes")
        if any("'..' leads out of the model's folder" in l for l in lines):
            count["leaving the folder by '..'"] += 1
        if any("outside the model's folder" in l for l in lines):
            count["outside the folder"] += 1
            why.append("a reference refused as outside its folder")
        if why:
            bad.append("bad: %s: %s: %s" % (path, ", ".join(why), " | ".join(lines)[:300]))
for k, v in count.items():
    print("%s %d" % (k, v))
for b in bad:
    print(b)
