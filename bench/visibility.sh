#!/bin/bash
# The G-buffer stage, classic raster against the visibility buffer (gbuffer_visibility + gbuffer_resolve),
# on the gallery (needs ../shared/assets) and the Cornell box at 1080p and 4K, in the default layout
# (unpacked normals, stored positions) and the smallest exact-enough one (oct32, positions from depth).
# One `lightpass bench` per scene (floors measured on the same GPU), then the sweep of --knob gbuffer-mode
# (its error against classic, ~0, and its ms). From the repository root:
#   bench/visibility.sh BUNDLE OUTDIR    (BUNDLE: run, lib/)
# Writes OUTDIR/visibility_<scene>.json, OUTDIR/sweep/ and OUTDIR/visibility.md (the table).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p "$R"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$R/device.txt" 2>/dev/null
$B/run --version
for s in gallery cornell; do
  $B/run bench --scene scenes/$s.json --frames 100 --warmup 10 --floors --max-seconds 4 --min-frames 10 \
    --vary '--gbuffer-mode classic,visibility' \
    --vary '--gbuffer unpacked --gbuffer-position stored|--gbuffer oct32 --gbuffer-position depth' \
    --vary '--size 1920x1080,3840x2160' --timings-json "$R/visibility_$s.json" -q > "$R/visibility_$s.log" 2>&1 \
    || echo "bench $s failed (see $R/visibility_$s.log)"
done
$B/run sweep --scene scenes/gallery.json --size 3840x2160 --frames 100 --knob gbuffer-mode --out-dir "$R/sweep" \
  > "$R/sweep.log" 2>&1 || echo "sweep failed (see $R/sweep.log)"
python3 bench/summarize_visibility.py "$R"/visibility_gallery.json "$R"/visibility_cornell.json \
  --sweep "$R/sweep/sweep.csv" | tee "$R/visibility.md"
