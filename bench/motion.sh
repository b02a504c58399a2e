#!/bin/bash
# Motion vectors and motion blur on a moving camera (scenes/cornell-flythrough.json's camera path,
# frames at 60 fps from t = 1 s) at 1080p and 4K: the G-buffer without and with the velocity target,
# and motion blur at 4, 8, 16 and 32 samples, each pass with its floor. From the repository root:
#   bench/motion.sh BUNDLE OUTDIR    (BUNDLE: run, gl_tests, lib/)
# Writes OUTDIR/motion.json (lightpass bench) and OUTDIR/motion.md (bench/summarize_motion.py).
set -u
B=$(cd "$1" && pwd); R=$2; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $R/device.txt
LD_LIBRARY_PATH=$B/lib $B/gl_tests --gtest_brief=1 --gtest_filter='Motion*' > $R/gl_tests_motion.txt 2>&1
tail -3 $R/gl_tests_motion.txt
# '--exposure 0' is the variant without motion blur: nothing reads motion, so the G-buffer writes no
# velocity. Every --motion-blur variant makes it write gbuffer.velocity.
$B/run bench --scene scenes/cornell-flythrough.json --time 1 --fps 60 --frames 200 --warmup 20 --floors \
  --vary '--size 1920x1080,3840x2160' \
  --vary '--exposure 0|--motion-blur --motion-blur-samples 4|--motion-blur --motion-blur-samples 8|--motion-blur --motion-blur-samples 16|--motion-blur --motion-blur-samples 32' \
  --timings-json $R/motion.json -q > /dev/null 2> $R/bench_progress.txt || { echo "bench failed"; tail -3 $R/bench_progress.txt; }
python3 bench/summarize_motion.py $R/motion.json | tee $R/motion.md
