#!/usr/bin/env bash
# The viewer as a user drives it: starts on the default scene under Xvfb (Mesa), key '2' switches to
# the normals view and F12's screenshot shows the normal encoding, 'x' toggles scissor, Esc quits.
#   viewer_under_xvfb.sh LIGHTPASS SCENE OUTDIR
set -uo pipefail
lp=$1 scene=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
for cmd in Xvfb xdotool python3; do command -v $cmd >/dev/null || { echo "missing $cmd"; exit 1; }; done
display=:$((90 + RANDOM % 100))
Xvfb "$display" -screen 0 640x480x24 -nolisten tcp >"$out/xvfb.log" 2>&1 &
xvfb=$!
trap 'kill $viewer $xvfb 2>/dev/null; wait 2>/dev/null' EXIT
export DISPLAY=$display
for i in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.1; done
"$lp" view "$scene" --size 200x150 --screenshot-dir "$out" --hide-panel >"$out/viewer.log" 2>&1 &
viewer=$!
wait_for() {  # wait_for PATTERN FILE
  for i in $(seq 300); do grep -q -- "$1" "$2" 2>/dev/null && return 0; kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
  echo "timed out waiting for '$1' in $2"; cat "$out/viewer.log"; exit 1
}
wait_for "viewer ready" "$out/viewer.log"
xdotool mousemove 100 75  # focus follows the pointer without a window manager
xdotool key 2
wait_for "view normals" "$out/viewer.log"
xdotool key F12
wait_for "screenshot" "$out/viewer.log"
xdotool key x
wait_for "scissor off" "$out/viewer.log"
xdotool key Escape
for i in $(seq 100); do kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
kill -0 $viewer 2>/dev/null && { echo "viewer did not quit on Escape"; exit 1; }
wait $viewer; code=$?
[ $code -eq 0 ] || { echo "viewer exit code $code"; cat "$out/viewer.log"; exit 1; }
# The back wall faces the camera: its eye-space normal is +Z, encoded (0.5, 0.5, 1.0).
python3 - "$out/lightpass-0.png" <<'PY'
import sys, zlib, struct
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, chunks = 8, {}
idat = b""
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR": w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
    if kind == b"IDAT": idat += body
    pos += 12 + n
raw = zlib.decompress(idat)
bpp = 4 if ctype == 6 else 3
stride = w * bpp
rows, prev = [], bytearray(stride)
for y in range(h):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b, c = prev[i], prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line); prev = line
x, y = w // 2, h // 4  # upper middle: the back wall, above the spheres
px = rows[y][x * bpp:x * bpp + 3]
print("normals view pixel", tuple(px))
assert abs(px[0] - 128) <= 2 and abs(px[1] - 128) <= 2 and px[2] >= 253, f"back wall normal encodes as {tuple(px)}"
PY
echo "viewer test passed"
