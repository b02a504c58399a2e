# Sourced by the viewer tests. start_xvfb SCREEN DIR: checks for Xvfb, xdotool and python3, starts
# Xvfb on a free display (-displayfd: other tests may run Xvfb at the same time) with its log in DIR,
# waits until it answers, exports DISPLAY, and points the panel's imgui.ini at DIR/config (never the
# user's own ~/.config). On exit it stops Xvfb and the test's $viewer, which the caller sets.
start_xvfb() {
  local screen=$1 dir=$2 i
  for cmd in Xvfb xdotool python3; do command -v $cmd >/dev/null || { echo "missing $cmd"; exit 1; }; done
  Xvfb -displayfd 3 -screen 0 "$screen" -nolisten tcp 3>"$dir/display" >"$dir/xvfb.log" 2>&1 &
  xvfb=$!
  viewer=
  trap 'kill $viewer $xvfb 2>/dev/null; wait 2>/dev/null' EXIT
  for i in $(seq 50); do [ -s "$dir/display" ] && break; sleep 0.1; done
  export DISPLAY=:$(cat "$dir/display")
  for i in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.1; done
  export LIGHTPASS_CONFIG_DIR="$dir/config"
}
