#!/usr/bin/env bash
# The viewer's panel as a new user meets it at 1280x720 (Xvfb, Mesa): a sidebar at most 380 px wide by
# default, docked at the left, with the image rendered beside it (never under it: check_viewport.py
# reads the window back with the panel and with Tab) and the whole window for the image without it; its pass rows keep their names, order and places when a pass is
# switched off, and a second click at the same spot switches the same pass on again (the rows, read
# from --panel-rows-out, come back identical); every candidate pass has its row from the start, so
# '8' (bloom) inserts none; its layout goes to $LIGHTPASS_CONFIG_DIR/imgui.ini,
# never the working directory, and the next run opens where that file says.
#   viewer_panel_under_xvfb.sh LIGHTPASS SCENE OUTDIR
set -uo pipefail
lp=$1 scene=$2 out=$3
rm -rf "$out" && mkdir -p "$out/cwd"
. "$(dirname "$0")/xvfb_lib.sh"
start_xvfb 1280x720x24 "$out"
rows="$out/rows.txt"
log=
start_viewer() {  # start_viewer LOG: from a working directory of its own, to see that nothing lands there
  log=$1
  rm -f "$rows"
  # --aa off: a quarter of the default SSAA's work per frame on llvmpipe (the panel is what is tested)
  (cd "$out/cwd" && exec "$lp" view "$scene" --size 1280x720 --aa off --panel-rows-out "$rows" --screenshot-dir "$out" \
     --screenshot-ui) >"$log" 2>&1 &
  viewer=$!
}
wait_for() {  # wait_for PATTERN FILE (an extended regular expression)
  for i in $(seq 600); do grep -qE -- "$1" "$2" 2>/dev/null && return 0; kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
  echo "timed out waiting for '$1' in $2"; cat "$log"; [ -f "$rows" ] && cat "$rows"; exit 1
}
quit_viewer() {
  xdotool key Escape
  for i in $(seq 100); do kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
  kill -0 $viewer 2>/dev/null && { echo "viewer did not quit on Escape"; exit 1; }
  wait $viewer; code=$?
  [ $code -eq 0 ] || { echo "viewer exit code $code"; cat "$log"; exit 1; }
}
# The rows without their state column: "pass NAME X,Y" (the checkbox centre in window pixels).
places() { grep '^pass' "$1" | cut -f1-3; }
tab=$'\t'

start_viewer "$out/viewer-1.log"
wait_for "viewer ready" "$log"
wait_for "^pass${tab}sky${tab}.*${tab}runs" "$rows"
[ -d "$out/config" ] || { echo "the config folder $out/config was not created"; exit 1; }
read -r px py pw ph <<<"$(grep '^panel' "$rows" | sed -E 's/^panel\t([0-9.]+),([0-9.]+)\t([0-9.]+)x([0-9.]+)$/\1 \2 \3 \4/')"
echo "panel at $px,$py, ${pw}x$ph"
python3 -c "import sys; sys.exit(0 if 0 < $pw <= 380 and $px == 0 and $py == 0 and $ph == 720 else 1)" ||
  { echo "the default panel is ${pw}x$ph at $px,$py: not a sidebar at most 380 px wide, docked left, full height"; exit 1; }
# The image beside it: the viewport starts at the panel's right edge and takes the rest of the window.
read -r vx vw vh <<<"$(grep '^viewport' "$rows" | sed -E 's/^viewport\t([0-9]+),0\t([0-9]+)x([0-9]+)$/\1 \2 \3/')"
echo "viewport from x = $vx, ${vw}x$vh"
python3 -c "import sys; sys.exit(0 if abs($vx - $pw) <= 1 and $vx + $vw == 1280 and $vh == 720 else 1)" ||
  { echo "the viewport ($vx, ${vw}x$vh) is not the window right of the ${pw}-px panel"; exit 1; }
cp "$rows" "$out/rows-before.txt"
read -r sx sy <<<"$(grep "^pass${tab}sky${tab}" "$rows" | cut -f3 | tr ',' ' ')"
sx=${sx%.*} sy=${sy%.*}
echo "sky's checkbox at $sx,$sy"
xdotool mousemove "$sx" "$sy" click 1
wait_for "^pass${tab}sky${tab}.*${tab}off" "$rows"
cp "$rows" "$out/rows-off.txt"
[ "$(places "$out/rows-before.txt")" = "$(places "$out/rows-off.txt")" ] ||
  { echo "switching sky off moved or removed rows:"; diff "$out/rows-before.txt" "$out/rows-off.txt"; exit 1; }
grep '^graph:' "$log" | tail -1 | grep -q ' sky' && { echo "sky is off in the panel but still ran"; exit 1; }
xdotool key F12  # the window with the panel, sky off: for a person to look at
wait_for "screenshot .*window with panel" "$log"
# The same spot again: the same pass, on again, and every row as it was.
xdotool mousemove "$sx" "$sy" click 1
wait_for "^pass${tab}sky${tab}.*${tab}runs" "$rows"
cp "$rows" "$out/rows-after.txt"
[ "$(places "$out/rows-before.txt")" = "$(places "$out/rows-after.txt")" ] ||
  { echo "switching sky on again moved rows:"; diff "$out/rows-before.txt" "$out/rows-after.txt"; exit 1; }
diff "$out/rows-before.txt" "$out/rows-after.txt" >/dev/null ||
  { echo "the rows differ after switching sky off and on:"; diff "$out/rows-before.txt" "$out/rows-after.txt"; exit 1; }
# '8' (the bloom buffer alone, bloom switched on): bloom's row was there from the start, greyed; it
# now runs, and no row is inserted or moved. '8' again: back as it was.
grep -qE "^pass${tab}bloom${tab}.*${tab}(skipped|not in this frame)" "$rows" ||
  { echo "no greyed bloom row before '8':"; cat "$rows"; exit 1; }
xdotool mousemove 900 400 key 8
wait_for "^pass${tab}bloom${tab}.*${tab}runs" "$rows"
cp "$rows" "$out/rows-bloom.txt"
[ "$(places "$out/rows-before.txt")" = "$(places "$out/rows-bloom.txt")" ] ||
  { echo "'8' moved, added or removed rows:"; diff "$out/rows-before.txt" "$out/rows-bloom.txt"; exit 1; }
xdotool key 8
wait_for "^pass${tab}bloom${tab}.*${tab}(skipped|not in this frame)" "$rows"
[ "$(places "$out/rows-before.txt")" = "$(places "$rows")" ] || { echo "'8' twice moved rows"; exit 1; }
# The window read back with the panel, then with Tab (panel hidden, the whole window for the image).
xdotool key F12
wait_for "screenshot .*lightpass-1.png .*window with panel" "$log"
xdotool key Tab
wait_for "^viewport${tab}0,0${tab}1280x720$" "$rows"
grep -q "^panel${tab}hidden" "$rows" || { echo "Tab did not hide the panel"; cat "$rows"; exit 1; }
xdotool key F12
wait_for "screenshot .*lightpass-2.png" "$log"
python3 "$(dirname "$0")/check_viewport.py" "$out/lightpass-1.png" "$vx" "$out/lightpass-2.png" || exit 1
xdotool key Tab
wait_for "^viewport${tab}${vx},0${tab}${vw}x720$" "$rows"
quit_viewer
ini="$out/config/imgui.ini"
[ -f "$ini" ] || { echo "no $ini after the run"; ls -la "$out/config"; exit 1; }
grep -q 'lightpass panel\]' "$ini" || { echo "$ini has no panel window:"; cat "$ini"; exit 1; }
[ -z "$(ls -A "$out/cwd")" ] || { echo "the viewer wrote into its working directory: $(ls -A "$out/cwd")"; exit 1; }

# The next run opens the panel as wide as the ini file says (as if the user had dragged its edge),
# still docked at the left, full height, with the image beside it.
sed -i -E 's/^Pos=.*/Pos=40,30/; s/^Size=.*/Size=300,500/' "$ini"
start_viewer "$out/viewer-2.log"
wait_for "viewer ready" "$log"
wait_for "^panel${tab}0,0${tab}300x720$" "$rows"
wait_for "^viewport${tab}300,0${tab}980x720$" "$rows"
quit_viewer
echo "viewer panel test passed"
