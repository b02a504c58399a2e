#!/bin/bash
# Deferred against forward+ (--render-path) on the GPU: the gallery (needs ../shared/assets) and the
# Cornell box at 1080p and 4K with 1, 32, 256 and 1024 local lights (--light-count). Three variants:
# deferred with tiled and with clustered local lights, and forward+ (which always reads the clustered
# lists). From the repository root:
#   bench/render_path.sh BUNDLE OUTDIR    (BUNDLE: run, lib/)
# Writes OUTDIR/render_path_<scene>.json (lightpass bench) and OUTDIR/render_path.md (the table).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$R/device.txt" 2>/dev/null
$B/run --version
for s in gallery cornell; do
  $B/run bench --scene scenes/$s.json --frames 100 --warmup 10 --floors --max-seconds 3 --min-frames 3 \
    --vary '--render-path deferred --local-lights tiled|--render-path deferred --local-lights clustered|--render-path forward+' \
    --vary '--light-count 1,32,256,1024' --vary '--size 1920x1080,3840x2160' \
    --timings-json "$R/render_path_$s.json" -q > "$R/render_path_$s.log" 2>&1 \
    || echo "bench $s failed (see $R/render_path_$s.log)"
done
python3 bench/summarize_render_path.py "$R"/render_path_gallery.json "$R"/render_path_cornell.json \
  | tee "$R/render_path.md"
