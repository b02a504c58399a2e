#!/bin/bash
# Deferred local lights, tiled against clustered, on the GPU: light counts 1..16384 at 1080p and 4K,
# on the gallery (needs ../shared/assets) and on scenes/depth-discontinuity.json (near pillars
# against a far wall: the case per-tile depth bounds handle worst). From the repository root:
#   bench/lighting_clustered.sh BUNDLE OUTDIR    (BUNDLE: run, lib/)
# Writes OUTDIR/clustered_<scene>.json (lightpass bench) and OUTDIR/lighting_clustered.md (the table).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$R/device.txt" 2>/dev/null
$B/run --version
for s in gallery depth-discontinuity; do
  $B/run bench --scene scenes/$s.json --frames 100 --warmup 10 --floors --max-seconds 3 --min-frames 3 \
    --vary '--local-lights tiled,clustered' --vary '--light-count 1,16,256,1024,4096,16384' \
    --vary '--size 1920x1080,3840x2160' --timings-json "$R/clustered_$s.json" -q > "$R/clustered_$s.log" 2>&1 \
    || echo "bench $s failed (see $R/clustered_$s.log)"
done
python3 bench/summarize_clustered.py "$R"/clustered_gallery.json "$R"/clustered_depth-discontinuity.json \
  | tee "$R/lighting_clustered.md"
