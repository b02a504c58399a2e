#!/bin/bash
# Anti-aliasing: what each --aa method costs in GPU ms and how far its image is from 4x4 SSAA.
# From the repository root:
#   bench/aa.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, cuda_tests, lib/)
# `lightpass sweep --knob aa` (off, fxaa, taa, ssaa2, ssaa3 against ssaa4, the reference) per scene
# and size, plus --ssaa-scale and --taa-history-weight on the gallery at 1080p:
#   still:  the Cornell box and the gallery at 1920x1080, the gallery at 3840x2160;
#   moving: the gallery at 1080p with --fps 60 --globes: its orbiting lights' globes move (TAA's
#           history must follow them through the motion vectors; the camera stays still), and
#           scenes/cornell-flythrough.json at 1080p with --time 1 --fps 60: the camera moves every frame.
# Then bench/summarize_aa.py: aa.md (frame ms, the AA pass's ms, HDR RMSE, FLIP on the PNGs where
# flip-evaluator is installed) and aa_pareto.png (error against frame ms, Pareto front marked).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
$B/run --version
sweep() {  # NAME ARGS...
  local name=$1; shift
  $B/run sweep "$@" --out-dir $R/$name -q > $R/$name.log 2>&1 || echo "sweep $name failed (see $R/$name.log)"
}
sweep cornell_1080p --scene scenes/cornell.json --knob aa --size 1920x1080 --frames 50 --warmup 10
sweep gallery_1080p --scene scenes/gallery.json --knob aa --knob ssaa-scale --knob taa-history-weight \
  --size 1920x1080 --frames 50 --warmup 10
sweep gallery_1080p_moving --scene scenes/gallery.json --knob aa --size 1920x1080 --frames 30 --warmup 10 \
  --fps 60 --globes
sweep cornell_flythrough_1080p --scene scenes/cornell-flythrough.json --knob aa --size 1920x1080 --frames 30 \
  --warmup 10 --time 1 --fps 60
# 4K: ssaa4 renders 15360x8640 (about 10 GB of targets on the gallery scene); fewer frames.
sweep gallery_4k --scene scenes/gallery.json --knob aa --size 3840x2160 --frames 20 --warmup 5
python3 bench/summarize_aa.py $R $R/cornell_1080p $R/gallery_1080p $R/gallery_1080p_moving $R/cornell_flythrough_1080p $R/gallery_4k
