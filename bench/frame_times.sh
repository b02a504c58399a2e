#!/usr/bin/env bash
# Per-pass GPU times of a scene at 1920x1080 and 3840x2160 (median of N frames after warm-up),
# written as JSON per size and summarised into a Markdown table.
#   bench/frame_times.sh [LIGHTPASS] [SCENE] [FRAMES] [OUTDIR]
set -euo pipefail
lp=${1:-build/app/lightpass}
scene=${2:-scenes/cornell.json}
frames=${3:-300}
out=${4:-bench/results/frame/$(date +%F)_frame-times}
mkdir -p "$out"
name=$(basename "$scene" .json)
for size in 1920x1080 3840x2160; do
  "$lp" render --scene "$scene" --size "$size" --frames "$frames" --warmup 30 \
        --out "$out/${name}_${size}.png" --timings-json "$out/${name}_${size}.json"
done
python3 "$(dirname "$0")/summarize_timings.py" "$out"/"${name}"_*.json > "$out/${name}_frame_times.md"
cat "$out/${name}_frame_times.md"
