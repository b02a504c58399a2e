#!/bin/bash
# Anti-aliasing: what each --aa method costs in GPU ms and how far its image is from 4x4 SSAA.
# From the repository root:
#   bench/aa.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, cuda_tests, lib/)
# One `lightpass sweep --knob aa` per scene and size (off, fxaa, ssaa2, ssaa3 against ssaa4, the
# reference; 1080p and 4K), then bench/summarize_aa.py: aa.md (frame ms, the AA pass's ms, HDR RMSE,
# FLIP on the PNGs where flip-evaluator is installed) and aa_pareto.png (error against frame ms).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
$B/run --version
for s in cornell gallery; do
  $B/run sweep --scene scenes/$s.json --knob aa --knob ssaa-scale --size 1920x1080 --frames 50 --warmup 10 \
    --out-dir $R/${s}_1080p -q > $R/${s}_1080p.log 2>&1 || echo "sweep $s 1080p failed (see $R/${s}_1080p.log)"
done
# 4K: ssaa4 renders 15360x8640 (about 10 GB of targets on the gallery scene); fewer frames.
$B/run sweep --scene scenes/gallery.json --knob aa --size 3840x2160 --frames 20 --warmup 5 \
  --out-dir $R/gallery_4k -q > $R/gallery_4k.log 2>&1 || echo "sweep gallery 4K failed (see $R/gallery_4k.log)"
python3 bench/summarize_aa.py $R $R/cornell_1080p $R/gallery_1080p $R/gallery_4k
