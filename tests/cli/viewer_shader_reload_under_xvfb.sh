#!/usr/bin/env bash
# Shader hot reload in the running viewer (Xvfb, Mesa), on a copy of shaders/: a syntax error saved
# into common/tonemap.glsl is reported as shaders/common/tonemap.glsl:3 while the viewer keeps
# rendering the last good programs; fixing it and making tonemap.comp write magenta reloads, and the
# next screenshot is magenta.
#   viewer_shader_reload_under_xvfb.sh LIGHTPASS SCENE SHADERS OUTDIR
set -uo pipefail
lp=$1 scene=$2 shaders=$3 out=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out" && mkdir -p "$out"
cp -r "$shaders" "$out/shaders"
. "$(dirname "$0")/xvfb_lib.sh"
start_xvfb 640x480x24 "$out"
LIGHTPASS_SHADER_DIR="$out/shaders" "$lp" view "$scene" --size 200x150 --screenshot-dir "$out" --hide-panel \
  >"$out/viewer.log" 2>&1 &
viewer=$!
wait_for() {  # wait_for REGEX
  for i in $(seq 300); do grep -qE -- "$1" "$out/viewer.log" 2>/dev/null && return 0; kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
  echo "timed out waiting for '$1'"; cat "$out/viewer.log"; exit 1
}
wait_for "viewer ready"
xdotool mousemove 100 75

common="$out/shaders/common/tonemap.glsl"
cp "$common" "$out/tonemap.glsl.good"
sed -i '3i this is not glsl;' "$common"
wait_for "shader error: .*shaders/common/tonemap.glsl:3:"
xdotool key F12  # still rendering: the screenshot comes and shows the lit scene
wait_for "screenshot .*lightpass-0.png"
read -r r g b < <(python3 "$here/png_pixel.py" "$out/lightpass-0.png" 0.5 0.25)
echo "after the broken edit: back wall ($r, $g, $b)"
[ $((r + g + b)) -gt 30 ] && ! { [ "$r" -eq 255 ] && [ "$g" -eq 0 ] && [ "$b" -eq 255 ]; } || { echo "not the lit scene"; exit 1; }

cp "$out/tonemap.glsl.good" "$common"
python3 - "$out/shaders/tonemap.comp" <<'PY'
import sys
src = open(sys.argv[1]).read()
i = src.index("imageStore(uLdr, p,")
open(sys.argv[1], "w").write(src[:i] + "imageStore(uLdr, p, vec4(1.0, 0.0, 1.0, 1.0));\n}\n")
PY
wait_for "shaders reloaded: .*tonemap.comp"
sleep 0.5
xdotool key F12
wait_for "screenshot .*lightpass-1.png"
read -r r g b < <(python3 "$here/png_pixel.py" "$out/lightpass-1.png" 0.5 0.25)
echo "after the good edit: ($r, $g, $b)"
[ "$r" -eq 255 ] && [ "$g" -eq 0 ] && [ "$b" -eq 255 ] || { echo "the edited tonemap.comp did not take effect"; exit 1; }
xdotool key Escape
for i in $(seq 100); do kill -0 $viewer 2>/dev/null || break; sleep 0.1; done
wait $viewer; code=$?
[ $code -eq 0 ] || { echo "viewer exit code $code"; cat "$out/viewer.log"; exit 1; }
echo "viewer shader reload test passed"
