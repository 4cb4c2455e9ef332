# xshot.sh: a real terminal under Xvfb, looked at through screenshots
# (sourced after lib.sh by test_xterm, long_mlterm, long_mux, long_kitty).
# What a person sees is counted, not read: the distinct colours of the
# screenshot's top rows (cells have a terminal's few colours; a picture
# in pixels many shades), or the columns where colours change along a
# row (cells change only at their edges).
#
#   x_start WxH          a display of its own: $d its number, $xvfb the
#                        server's pid (the script's trap kills it)
#   shot                 the whole display into $T/shot.ppm
#   colours ROWS         the distinct colours of its top ROWS rows
#   changes ROWS         the columns at which the colour changes along
#                        every second of its top ROWS rows
#   until_colours CMP N ROWS
#                        screenshots until `colours ROWS` CMP N holds
#                        (test's operators: -gt, -lt, ...), up to 10 s;
#                        $n the last count

x_start() {
    # the server picks a free number and says which
    Xvfb -displayfd 3 -screen 0 "$1"x24 -nolisten tcp 3>"$T/display" >/dev/null 2>&1 &
    xvfb=$!
    i=0
    while [ ! -s "$T/display" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    d=$(cat "$T/display")
    [ -n "$d" ] || { notok "Xvfb starts" "no display number in 10 s"; exit 1; }
}

shot() { DISPLAY=:$d import -window root "$T/shot.ppm"; }

# the screenshot's pixels: import writes 8 or 16 bits a sample
x_pixels() {
    python3 - "$T/shot.ppm" "$1" "$2" <<'PY'
import sys
data = open(sys.argv[1], 'rb').read()
parts, pos = [], 0
while len(parts) < 4:
    while data[pos:pos + 1].isspace(): pos += 1
    start = pos
    while not data[pos:pos + 1].isspace(): pos += 1
    parts.append(data[start:pos])
w, h = int(parts[1]), int(parts[2])
b = 6 if int(parts[3]) > 255 else 3
px = data[pos + 1:]
rows = min(int(sys.argv[3]), h)
if sys.argv[2] == 'colours':
    print(len({px[i:i + b] for i in range(0, w * rows * b, b)}))
else:
    cols = set()
    for y in range(0, rows, 2):
        row = px[y * w * b:(y + 1) * w * b]
        for x in range(1, w):
            if row[x * b:x * b + b] != row[x * b - b:x * b]:
                cols.add(x)
    print(len(cols))
PY
}
colours() { x_pixels colours "$1"; }
changes() { x_pixels changes "$1"; }

until_colours() {
    i=0
    while [ $i -lt 40 ]; do
        shot
        n=$(colours "$3" 2>/dev/null)
        n=${n:-0}
        [ "$n" "$1" "$2" ] && return 0
        sleep 0.25
        i=$((i + 1))
    done
    return 1
}
