#!/usr/bin/env bash
# The viewer as a user drives it: starts on the default scene under Xvfb (Mesa), key '2' switches to
# the normals view and F12's screenshot shows the normal encoding, '+'/'-' there say exposure is not
# shown in it, 'p' says the scene has no camera path, 'r' resets the camera, Space pauses and plays the
# scene clock and ']' / '[' double and halve its speed, 'm' and 't' step through the
# material-input and term views, 'c' compares the final view with the path tracer (and says why not in
# another view), 'x' toggles scissor, '7' adds the
# toon pass and '8' the bloom pass (alone: toon is moot) to the compiled graph, '0' takes them out again, unticking the
# panel's "sky" checkbox removes that pass from the compiled graph, Esc quits.
#   viewer_under_xvfb.sh LIGHTPASS SCENE OUTDIR
set -uo pipefail
lp=$1 scene=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
. "$(dirname "$0")/xvfb_lib.sh"
start_xvfb 640x720x24 "$out"  # tall enough for the passes table down to "sky"
"$lp" view "$scene" --size 600x680 --spp 4 --screenshot-dir "$out" --hide-panel --panel-rows-out "$out/rows.txt" \
  >"$out/viewer.log" 2>&1 &
viewer=$!
wait_for() {  # wait_for PATTERN FILE (an extended regular expression)
  for i in $(seq 300); do grep -qE -- "$1" "$2" 2>/dev/null && return 0; kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
  echo "timed out waiting for '$1' in $2"; cat "$out/viewer.log"; exit 1
}
wait_for "viewer ready" "$out/viewer.log"
xdotool mousemove 100 75  # focus follows the pointer without a window manager
xdotool key 2
wait_for "view normals" "$out/viewer.log"
xdotool key F12
wait_for "screenshot" "$out/viewer.log"
# Every key answers: exposure in a G-buffer view says it shows raw values; 'p' on a scene without a
# camera path says so; 'r' says it reset the camera.
xdotool key equal
wait_for "^exposure \+0\.5 EV \(not in this view" "$out/viewer.log"
xdotool key minus
wait_for "^exposure \+0\.0 EV \(not in this view" "$out/viewer.log"
xdotool key p
wait_for "^no camera path" "$out/viewer.log"
xdotool key r
wait_for "^camera reset" "$out/viewer.log"
# Space pauses and plays the scene clock; ']' and '[' double and halve its speed.
xdotool key space
wait_for "^clock paused at [0-9.]+ s \(speed x1\.00\)" "$out/viewer.log"
xdotool key bracketright
wait_for "^clock speed x2\.00 \(paused: Space plays\)" "$out/viewer.log"
xdotool key bracketleft
wait_for "^clock speed x1\.00 \(paused" "$out/viewer.log"
xdotool key space
wait_for "^clock playing at" "$out/viewer.log"
# 'm' steps through the material inputs, 't' through the lit frame's terms.
xdotool key m
wait_for "view base-color" "$out/viewer.log"
xdotool key m
wait_for "view metallic" "$out/viewer.log"
xdotool key t
wait_for "view term-diffuse" "$out/viewer.log"
xdotool key t
wait_for "view term-specular" "$out/viewer.log"
xdotool key t
wait_for "view clearcoat" "$out/viewer.log"
# 'k' the clearcoat term directly (KHR_materials_clearcoat's layer): a second "view clearcoat" line.
xdotool key k
for i in $(seq 300); do [ "$(grep -c 'view clearcoat' "$out/viewer.log")" -ge 2 ] && break; sleep 0.1; done
[ "$(grep -c 'view clearcoat' "$out/viewer.log")" -ge 2 ] || { echo "'k' printed no view clearcoat"; cat "$out/viewer.log"; exit 1; }
# 'c' compares with the path tracer only in the final view; there it prints the error against it.
xdotool key c
wait_for "^compare with the path tracer: only in the final view" "$out/viewer.log"
xdotool key x
wait_for "scissor off \(used by the scissor method; now tiled" "$out/viewer.log"  # the default method says it ignores it
# "graph:" lines list the passes that ran, printed whenever that list changes.
last_graph() { grep '^graph:' "$out/viewer.log" | tail -1; }
xdotool key 7
wait_for "toon on" "$out/viewer.log"
wait_for "^graph:.* toon" "$out/viewer.log"
xdotool key 8
wait_for "bloom only on" "$out/viewer.log"
wait_for "^graph:.* bloom" "$out/viewer.log"
xdotool key 0
wait_for "view final" "$out/viewer.log"
xdotool key c
wait_for "^compare with the path tracer on" "$out/viewer.log"
wait_for "^compare: path tracer 4 samples a pixel \(noise [0-9.]+%\); raster against it: mean \|relative error\| [0-9.]+%, RMSE [0-9.e-]+$" "$out/viewer.log"
xdotool key c
wait_for "^compare with the path tracer off$" "$out/viewer.log"
xdotool key equal
wait_for "^exposure \+0\.5 EV$" "$out/viewer.log"  # the final image shows it: no reason given
xdotool key minus
for i in $(seq 100); do last_graph | grep -qE ' (bloom|toon)' || break; sleep 0.1; done
last_graph | grep -qE ' (bloom|toon)' && { echo "'0' left bloom or toon on: $(last_graph)"; exit 1; }
last_graph | grep -q ' sky' || { echo "sky missing before the checkbox test: $(last_graph)"; exit 1; }
# Tab shows the panel; --panel-rows-out says where it drew the "sky" checkbox in the passes table.
xdotool key Tab
for i in $(seq 100); do grep -qP '^pass\tsky\t[1-9]' "$out/rows.txt" 2>/dev/null && break; sleep 0.1; done
read -r sx sy <<<"$(grep -P '^pass\tsky\t' "$out/rows.txt" | cut -f3 | tr ',' ' ')"
[ -n "${sy:-}" ] || { echo "no sky row in $out/rows.txt"; cat "$out/rows.txt"; exit 1; }
xdotool mousemove "${sx%.*}" "${sy%.*}" click 1
for i in $(seq 100); do last_graph | grep -q ' sky' || break; sleep 0.1; done
last_graph | grep -q ' sky' && { echo "unticking sky left it in the graph: $(last_graph)"; exit 1; }
xdotool mousemove 400 300
xdotool key Escape
for i in $(seq 100); do kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
kill -0 $viewer 2>/dev/null && { echo "viewer did not quit on Escape"; exit 1; }
wait $viewer; code=$?
[ $code -eq 0 ] || { echo "viewer exit code $code"; cat "$out/viewer.log"; exit 1; }
# The back wall faces the camera: its eye-space normal is +Z, encoded (0.5, 0.5, 1.0).
px=$(python3 "$(dirname "$0")/png_pixel.py" "$out/lightpass-0.png" 0.5 0.25)  # upper middle: the back wall
echo "normals view pixel $px"
read -r r g b <<<"$px"
[ $((r > 128 ? r - 128 : 128 - r)) -le 2 ] && [ $((g > 128 ? g - 128 : 128 - g)) -le 2 ] && [ "$b" -ge 253 ] ||
  { echo "back wall normal encodes as ($px)"; exit 1; }
echo "viewer test passed"
